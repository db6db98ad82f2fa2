"""How a fitted parameter is judged: identified or not (its 68 % interval against the range searched, in decades for
a parameter searched on a log scale), and when a value on a search bound makes a fit not credible (the data push it
out of the range) and when it does not (the data do not determine it at all)."""

import math

import pytest

from validation.fitting import FreeParameter
from validation.refit import Estimate, _estimate

V_REF = FreeParameter(effect="adhesion", name="v_ref", lo=1e-12, hi=1e6, log=True, unit="m/s",
                      plausible=(1e-6, 1e3))
C = FreeParameter(effect="adhesion", name="c", lo=0.0, hi=2.0, log=False, unit="1/decade^2", plausible=(0.0, 0.5))


def test_an_interval_on_a_log_scale_is_judged_in_decades():
    est = Estimate(key="adhesion.v_ref", value=1e6, std=math.inf, interval=(0.4, 1e6), method="profile",
                   search=(1e-12, 1e6), log_scale=True)
    assert est.identified                     # 0.4 m/s up: 6.4 of the 18 decades searched
    whole = Estimate(key="adhesion.v_ref", value=1e6, std=math.inf, interval=(1e-12, 1e6), method="profile",
                     search=(1e-12, 1e6), log_scale=True)
    assert not whole.identified
    # on a linear reading 0.4 would be "within 1e-6 of the range" of 1e6 and count as reaching its lower end
    linear = Estimate(key="x", value=1e6, std=math.inf, interval=(0.4, 1e6), method="profile", search=(1e-12, 1e6))
    assert not linear.identified


def test_a_value_on_a_search_bound_is_pushed_out_when_the_interval_is_bounded():
    e = _estimate(V_REF, 1e6, math.inf, (3e5, 1e6), "profile", 1.0, None)
    assert e.bound == "search bound" and e.identified
    assert e.issue == "on the upper search bound 1e+06: the data push it out of the range searched"


def test_a_value_on_a_search_bound_is_bounded_on_one_side_when_the_interval_reaches_plausible_values():
    """An adhesive peak somewhere above the measured speeds: the fit runs v_ref to the end of the range, but every
    value from 0.4 m/s up, the plausible ones to 1e3 m/s included, fits within one unit of chi2."""
    e = _estimate(V_REF, 1e6, math.inf, (0.4, 1e6), "profile", 1.0, None)
    assert e.bound == "search bound" and e.issue == "" and e.one_sided == "above 0.4" and not e.identified
    assert "bounded on one side only, the data allow any value above 0.4" in e.describe()
    e = _estimate(V_REF, 1e-12, math.inf, (1e-12, 3e-5), "profile", 0.0, None)
    assert e.one_sided == "below 3e-05" and e.issue == "" and not e.identified
    assert e.as_dict()["one_sided"] == "below 3e-05" and e.as_dict()["identified"] is False


def test_a_value_on_a_search_bound_is_not_identified_when_the_interval_spans_the_range():
    """A flat likelihood over the whole range: the bound is as good as any plausible value, so the fit stays
    credible and the parameter is reported as not identified (which keeps a verdict from ``explained``)."""
    e = _estimate(C, 2.0, math.inf, (0.0, 2.0), "profile", 1.0, None)
    assert e.bound == "search bound" and not e.identified and e.issue == ""
    assert "[not identified: the interval spans the range searched]" in e.describe()
    e = _estimate(V_REF, 1e6, math.inf, (1e-12, 1e6), "profile", 1.0, None)
    assert e.issue == "" and not e.identified


def test_a_value_outside_its_plausible_range_is_not_credible_unless_the_data_leave_it_open():
    e = _estimate(C, 0.9, 0.05, (0.85, 0.95), "quadratic", 0.45, None)
    assert e.bound == "" and e.issue == "outside the plausible range 0 - 0.5"
    e = _estimate(C, 0.9, math.inf, (0.0, 2.0), "profile", 0.45, None)
    assert e.issue == "" and not e.identified


@pytest.mark.parametrize("u", [0.0, 1.0])
def test_a_physical_limit_is_no_issue(u):
    tau = FreeParameter(effect="adhesion", name="tau_f0", lo=0.0, hi=50e6, log=False, unit="Pa",
                        physical_limits=(0.0,), plausible=(0.0, 10e6))
    e = _estimate(tau, 0.0, 1e5, (0.0, 1e5), "quadratic", 0.0, None)
    assert e.bound == "physical limit" and e.issue == ""


def test_a_bound_that_is_itself_plausible_is_pushed_against_whatever_the_interval():
    """Without a narrower plausible range the bound is a plausible value: reaching it, the fit wants more."""
    plain = FreeParameter(effect="test", name="k", lo=0.0, hi=2.0, log=False, unit="1")
    e = _estimate(plain, 2.0, math.inf, (1.0, 2.0), "profile", 1.0, None)
    assert e.issue.startswith("on the upper search bound 2") and e.one_sided == "" and e.identified
    e = _estimate(C, 2.0, math.inf, (0.3, 2.0), "profile", 1.0, None)      # plausible only up to 0.5
    assert e.issue == "" and e.one_sided == "above 0.3"


def test_the_95_percent_interval_follows_a_likelihood_that_is_not_quadratic_beyond_one_standard_error(monkeypatch):
    """mu = f0 + exp(-b) with known noise: chi^2(b) = n (m - exp(-b))^2 / sigma^2 about the optimum (m the mean
    excess), so the 95 % ends are exactly b = -ln(m -+ 1.96 sigma / sqrt(n)). With sigma / sqrt(n) = 0.4 m the
    likelihood is quadratic enough at one standard error (the 68 % interval stays quadratic) but not at two: the
    95 % interval is the profile's, asymmetric, where 1.96 standard errors would be 20-40 % off on either side."""
    from dataclasses import dataclass

    import numpy as np

    import materials
    import persson
    import surfaces
    import validation
    from persson.effects import Effect, Parameter, base
    from validation.fitting import Fitter, ParameterSpace, free_parameters
    from validation.predict import Predictor
    from validation.refit import Z95, global_fit, with_uncertainty

    monkeypatch.setattr(base, "_REGISTRY", dict(base._REGISTRY))

    @dataclass(frozen=True)
    class Decay(Effect):
        name = "test_decay"
        parameters = (Parameter("b", 3.0, (0.0, 8.0), "1", "decay exponent"),)
        b: float = 3.0

        def friction_term(self, state):  # 0.5 keeps the rows' friction positive at this noise
            return np.full_like(state.conditions.speed, 0.5 + math.exp(-self.b))

    v = np.geomspace(1e-3, 1.0, 8)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, 2), temperature=np.repeat([10.0, 30.0], 8),
                                               pressure=3e5, mu=0.5)
    plain = persson.Model(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e5, hrms=1e-4), materials.example_tread())
    f0 = validation.predict(plain, rows).mu
    n, sigma = rows.n, 0.08                                  # sigma / sqrt(n) = 0.02 = 0.4 exp(-3)
    noise = np.random.default_rng(5).normal(0.0, sigma, n)
    y = f0 + 0.5 + math.exp(-3.0) + noise - noise.mean()     # mean excess exactly exp(-3)
    m = rows.with_mu(y, mu_std=np.full(n, sigma))
    model = plain.with_effect(Decay())
    fitter = Fitter(Predictor(m, None), y, np.full(n, 1.0 / sigma), model,
                    ParameterSpace(free_parameters(Decay())), max_evals=400)
    fit = with_uncertainty(fitter, global_fit(fitter, fitter.space.u_of(model, None)), s2=1.0, profile=True)
    (e,) = fit.estimates
    half = Z95 * sigma / math.sqrt(n)
    exact = (-math.log(math.exp(-3.0) + half), -math.log(math.exp(-3.0) - half))
    assert e.value == pytest.approx(3.0, abs=1e-4) and e.method == "quadratic"
    assert e.interval95 == pytest.approx(exact, abs=0.01)
    quadratic = (e.value - Z95 * e.std, e.value + Z95 * e.std)
    assert abs(quadratic[0] - exact[0]) > 0.1 and abs(quadratic[1] - exact[1]) > 0.5
    assert e.as_dict()["interval95"] == list(e.interval95)
