"""How a fitted parameter is judged: identified or not (its 68 % interval against the range searched, in decades for
a parameter searched on a log scale), and when a value on a search bound makes a fit not credible (the data push it
out of the range) and when it does not (the data do not determine it at all)."""

import math

import numpy as np
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


def test_a_value_outside_its_plausible_range_stays_credible_when_its_interval_reaches_into_the_range():
    """As for a bound beyond the plausible range: a best value of 0.6 whose 68 % interval runs down to 0.45 has
    plausible values (c <= 0.5) within one unit of chi^2 of the best, so the data do not demand c = 0.6. The fit
    stays credible, the parameter identified, and the value carries a caveat; an interval that stops short of the
    range (0.55 - 0.65) keeps the issue."""
    e = _estimate(C, 0.6, 0.15, (0.45, 0.75), "quadratic", 0.3, None)
    assert e.issue == "" and e.identified and e.one_sided == ""
    assert e.caveat == "best value outside the plausible range 0 - 0.5; its 68 % interval reaches into it"
    assert f"[{e.caveat}]" in e.describe() and e.as_dict()["caveat"] == e.caveat
    e = _estimate(C, 0.6, 0.05, (0.55, 0.65), "quadratic", 0.3, None)
    assert e.issue == "outside the plausible range 0 - 0.5" and e.caveat == ""
    # a value without an interval yet (the bare estimate that decides which intervals to compute) keeps the issue
    e = _estimate(C, 0.6, math.nan, (math.nan, math.nan), "none", 0.3, None)
    assert e.issue == "outside the plausible range 0 - 0.5"


def test_caveats_and_issues_name_the_parameter_its_value_and_its_unit():
    """The phrases a verdict quotes: ``effect.parameter = value unit: why``, the unit left out when it is "1"; only
    the estimates with a caveat (or an issue) are named."""
    from dataclasses import replace

    from validation.refit import GlobalFit

    cav = _estimate(C, 0.6, 0.15, (0.45, 0.75), "quadratic", 0.3, None)
    bad = _estimate(C, 0.6, 0.05, (0.55, 0.65), "quadratic", 0.3, None)
    plain = replace(cav, unit="1")
    assert GlobalFit.caveats_of([cav, bad]) == (f"adhesion.c = 0.6 1/decade^2: {cav.caveat}",)
    assert GlobalFit.caveats_of([plain]) == (f"adhesion.c = 0.6: {cav.caveat}",)
    assert GlobalFit.issues_of([cav, bad]) == (f"adhesion.c = 0.6 1/decade^2: {bad.issue}",)


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
    from persson.effects import base
    from validation.refit import Z95, with_uncertainty

    monkeypatch.setattr(base, "_REGISTRY", dict(base._REGISTRY))
    fitter, fit0, se = _decay_fit(0.4)                      # sigma / sqrt(n) = 0.4 exp(-3)
    fit = with_uncertainty(fitter, fit0, s2=1.0, profile=True)
    (e,) = fit.estimates
    half = Z95 * se
    exact = (-math.log(math.exp(-3.0) + half), -math.log(math.exp(-3.0) - half))
    assert e.value == pytest.approx(3.0, abs=1e-4) and e.method == "quadratic"
    assert e.interval95 == pytest.approx(exact, abs=0.01)
    quadratic = (e.value - Z95 * e.std, e.value + Z95 * e.std)
    assert abs(quadratic[0] - exact[0]) > 0.1 and abs(quadratic[1] - exact[1]) > 0.5
    assert e.as_dict()["interval95"] == list(e.interval95)


def _decay_fit(sigma_over_root_n: float, seed: int = 5, hi: float = 8.0):
    """A fitter of mu = f0 + 0.5 + exp(-b) to rows whose mean excess is exactly exp(-3), with known noise such that
    sigma / sqrt(n) = ``sigma_over_root_n`` exp(-3): chi^2(b) = n (exp(-3) - exp(-b))^2 / sigma^2 about the optimum,
    so that the profile ends at delta chi^2 = z^2 are b = -ln(exp(-3) -+ z sigma / sqrt(n)); b is searched over
    0 - ``hi``. Returns (fitter, fit, sigma / sqrt(n))."""
    from dataclasses import dataclass

    import numpy as np

    import materials
    import persson
    import surfaces
    import validation
    from persson.effects import Effect, Parameter
    from validation.fitting import Fitter, ParameterSpace, free_parameters
    from validation.predict import Predictor
    from validation.refit import global_fit

    @dataclass(frozen=True)
    class Decay(Effect):
        name = "test_decay"
        parameters = (Parameter("b", min(3.0, hi / 2), (0.0, hi), "1", "decay exponent"),)
        b: float = min(3.0, hi / 2)

        def friction_term(self, state):  # 0.5 keeps the rows' friction positive at this noise
            return np.full_like(state.conditions.speed, 0.5 + math.exp(-self.b))

    v = np.geomspace(1e-3, 1.0, 8)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, 2), temperature=np.repeat([10.0, 30.0], 8),
                                               pressure=3e5, mu=0.5)
    plain = persson.Model(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e5, hrms=1e-4), materials.example_tread())
    f0 = validation.predict(plain, rows).mu
    n = rows.n
    sigma = sigma_over_root_n * math.exp(-3.0) * math.sqrt(n)
    noise = np.random.default_rng(seed).normal(0.0, sigma, n)
    y = f0 + 0.5 + math.exp(-3.0) + noise - noise.mean()
    m = rows.with_mu(y, mu_std=np.full(n, sigma))
    model = plain.with_effect(Decay())
    fitter = Fitter(Predictor(m, None), y, np.full(n, 1.0 / sigma), model,
                    ParameterSpace(free_parameters(Decay())), max_evals=400)
    return fitter, global_fit(fitter, fitter.space.u_of(model, None)), sigma / math.sqrt(n)


def test_the_95_percent_profile_has_evaluations_of_its_own_when_the_68_percent_ones_spent_the_budget(monkeypatch):
    """With a budget that the 68 % interval's checks use up, the 95 % interval is still the profile's (exact ends
    b = -ln(exp(-3) -+ 1.96 sigma / sqrt(n))), not the symmetric 1.96 standard errors it fell back on before, which
    miss the exact ends by 0.1 and 0.5 here. (The reserve is the default where no budget is given; an explicit
    budget is a cap unless the reserve is asked for.)"""
    from persson.effects import base
    from validation.refit import Z95, with_uncertainty

    monkeypatch.setattr(base, "_REGISTRY", dict(base._REGISTRY))
    fitter, fit, se = _decay_fit(0.4)
    out = with_uncertainty(fitter, fit, s2=1.0, profile=True, budget=2, reserve=True)
    (e,) = out.estimates
    exact = (-math.log(math.exp(-3.0) + Z95 * se), -math.log(math.exp(-3.0) - Z95 * se))
    assert e.interval95 == pytest.approx(exact, abs=0.01)
    assert not any("extrapolated" in n for n in out.notes)


def test_intervals_with_an_estimated_noise_use_students_t():
    """With the variance unit estimated on nu degrees of freedom the quadratic intervals are t_nu(0.8413) and
    t_nu(0.975) standard errors wide on each side (scipy.stats' quantiles, independently), the standard error itself
    unchanged; with a known variance, 1 and 1.96."""
    from scipy import stats

    from validation.refit import t_quantiles, with_uncertainty

    assert t_quantiles(math.inf) == pytest.approx((1.0, 1.959964), rel=1e-6)
    for nu in (3, 8, 20, 200):
        expect = (stats.t.ppf(stats.norm.cdf(1.0), nu), stats.t.ppf(0.975, nu))
        assert t_quantiles(nu) == pytest.approx(expect, rel=1e-9)
    fitter, fit, se = _decay_fit(0.02)          # nearly linear: both intervals quadratic
    known = with_uncertainty(fitter, fit, s2=1.0, profile=True)
    (k,) = known.estimates
    (e,) = with_uncertainty(fitter, fit, s2=1.0, profile=True, dof=8).estimates
    assert e.std == pytest.approx(k.std, rel=1e-12) and e.method == k.method == "quadratic"
    t68, t95 = stats.t.ppf(stats.norm.cdf(1.0), 8), stats.t.ppf(0.975, 8)
    assert e.interval[1] - e.value == pytest.approx(t68 * (k.interval[1] - k.value), rel=1e-3)
    assert e.interval95[1] - e.value == pytest.approx(t95 / 1.959964 * (k.interval95[1] - k.value), rel=1e-3)
    assert e.value - e.interval95[0] == pytest.approx(t95 / 1.959964 * (k.value - k.interval95[0]), rel=1e-3)


class _Parabola:
    """A stand-in fitter: chi^2(u) = 100 (u - 0.001)^2 in one parameter (its optimum on the lower bound, so that only
    the upper side is profiled), with a budget of model evaluations."""

    def __init__(self, evals: int):
        self.left = evals

    def chi2(self, v):
        from validation.fitting import BudgetExhausted

        if self.left <= 0:
            raise BudgetExhausted()
        self.left -= 1
        return 100.0 * (float(v[0]) - 0.001) ** 2


def test_a_profile_cut_short_by_the_budget_extrapolates_in_the_root_of_delta_chi2():
    """One evaluation at half the true distance (delta chi^2 = 0.96 of 3.84), then the budget is gone: the upper end
    is extrapolated linearly in sqrt(delta chi^2), exact for a parabola (0.001 + 1.96 / 10), and the memo says so;
    with no evaluation at all the budget error propagates (the caller falls back)."""
    import numpy as np

    from validation.fitting import BudgetExhausted
    from validation.refit import Z95, _profile

    u = np.array([0.001])
    memo: dict = {}
    lo, hi = _profile(_Parabola(1), u, 0, 0.0, 1.0, 0.05, 1, level=Z95 ** 2, memo=memo)
    assert lo == 0.0 and hi == pytest.approx(0.001 + Z95 / 10, rel=1e-9)
    assert memo[("extrapolated", 0)]
    with pytest.raises(BudgetExhausted):
        _profile(_Parabola(0), u, 0, 0.0, 1.0, 0.05, 1, level=Z95 ** 2)
    # with the budget it needs, the same profile brackets and refines to the exact end without extrapolating, and
    # a 68 % profile before it leaves points the 95 % one starts from
    memo = {}
    lo1, hi1 = _profile(_Parabola(40), u, 0, 0.0, 1.0, 0.1, 1, level=1.0, memo=memo)
    assert hi1 == pytest.approx(0.101, rel=1e-6)
    parabola = _Parabola(40)
    lo, hi = _profile(parabola, u, 0, 0.0, 1.0, 0.1, 1, level=Z95 ** 2, memo=memo)
    assert hi == pytest.approx(0.001 + Z95 / 10, rel=1e-6) and ("extrapolated", 0) not in memo
    assert 40 - parabola.left <= 2


def test_the_quadratic_check_follows_the_profile_along_a_ridge_of_correlated_parameters(monkeypatch):
    """mu = f0 + 0.5 + a b / 10 + exp(-a) x (x = log10 v): the rows fix the product a b sharply and exp(-a) only
    weakly. Along a with b fixed chi^2 is steep and quadratic (the product term), so a check along the axis passes;
    along the ridge (b refitted to keep a b) the profile is chi^2(a) = S_xx (exp(-a) - exp(-3))^2 / sigma^2 (the
    constant a b / 10 takes up the mean of the x term), far from quadratic at this noise. Its exact ends are
    a = -ln(exp(-3) -+ z sigma / sqrt(S_xx)); the check along the linearized profile sees the bend and profiles (the
    check along the axis took the 95 % interval for quadratic, 0.75 short of the exact upper end)."""
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
    class Ridge(Effect):
        name = "test_ridge"
        parameters = (Parameter("a", 3.0, (0.0, 8.0), "1", "decay exponent"),
                      Parameter("b", 2.0, (0.0, 20.0), "1", "factor of the product"))
        a: float = 3.0
        b: float = 2.0

        def friction_term(self, state):
            x = np.log10(state.conditions.speed)
            return 0.5 + self.a * self.b / 10.0 + math.exp(-self.a) * x

    v = np.geomspace(1e-3, 1.0, 8)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, 2), temperature=np.repeat([10.0, 30.0], 8),
                                               pressure=3e5, mu=0.5)
    plain = persson.Model(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e5, hrms=1e-4), materials.example_tread())
    f0 = validation.predict(plain, rows).mu
    x = np.log10(rows.speed)
    sxx = float(np.sum((x - x.mean()) ** 2))
    sigma = 0.4 * math.exp(-3.0) * math.sqrt(sxx)          # sigma / sqrt(S_xx) = 0.4 exp(-3)
    # noise orthogonal to the constant and to x: the optimum is exactly a = 3, b = 2
    basis = np.column_stack([np.ones_like(x), x])
    noise = np.random.default_rng(7).normal(0.0, sigma, x.size)
    noise -= basis @ np.linalg.lstsq(basis, noise, rcond=None)[0]
    y = f0 + 0.5 + 0.6 + math.exp(-3.0) * x + noise
    m = rows.with_mu(y, mu_std=np.full(x.size, sigma))
    model = plain.with_effect(Ridge())
    fitter = Fitter(Predictor(m, None), y, np.full(x.size, 1.0 / sigma), model,
                    ParameterSpace(free_parameters(Ridge())), max_evals=600)
    fit = with_uncertainty(fitter, global_fit(fitter, fitter.space.u_of(model, None)), s2=1.0, profile=True)
    e = next(e for e in fit.estimates if e.key.endswith(".a"))
    half = math.sqrt(1.0 / sxx) * sigma
    exact68 = (-math.log(math.exp(-3.0) + half), -math.log(math.exp(-3.0) - half))
    exact95 = (-math.log(math.exp(-3.0) + Z95 * half), -math.log(math.exp(-3.0) - Z95 * half))
    assert e.value == pytest.approx(3.0, abs=2e-3) and e.method.startswith("profile")
    assert e.std == pytest.approx(half * math.exp(3.0), rel=1e-3)
    assert e.interval == pytest.approx(exact68, abs=0.01)
    assert e.interval95 == pytest.approx(exact95, abs=0.01)
    quadratic95 = (e.value - Z95 * e.std, e.value + Z95 * e.std)
    assert abs(quadratic95[1] - exact95[1]) > 0.4


class _Trap:
    """A stand-in fitter whose profile (one parameter, optimum at u = 0.2) rises as (t / 0.5)^4 times the level out to
    t = 0.6 from the optimum and is 1000 times the level beyond, as where a refit started far along a curved ridge
    misses it."""

    def __init__(self, level: float):
        self.level = level

    def chi2(self, v):
        t = abs(float(v[0]) - 0.2)
        return self.level * ((t / 0.5) ** 4 if t < 0.6 else 1000.0)


@pytest.mark.parametrize("level", [1.0, 1.959964 ** 2])
def test_a_profile_with_a_large_standard_error_is_not_bracketed_by_a_missed_refit(level):
    """With a standard error of 0.98 in u the first step used to land on the trap, and five interpolations in
    sqrt(delta chi2) from the optimum to a point 1000 times the level ended near t = 0.13; stepping out from at most
    0.1 sqrt(level) and halving an upper bracket that far beyond the level finds the crossing at t = 0.5 (u = 0.7);
    the lower side runs into the bound u = 0 below the level."""
    import numpy as np

    from validation.refit import _profile

    lo, hi = _profile(_Trap(level), np.array([0.2]), 0, 0.0, 1.0, 0.98, 1, level=level)
    assert lo == 0.0 and hi == pytest.approx(0.7, abs=0.005)


def test_intervals_computed_when_first_read_equal_those_computed_at_once(monkeypatch):
    """``with_uncertainty(defer=True)`` spends the Jacobian's evaluations at once and the profiles' only when the
    estimates are read; the estimates, notes and covariance it then gives are those of ``defer=False`` (two fresh
    fitters of the same data), and ``on_evals`` is told what the profiles cost. The skewed 95 % profile of the decay
    (exact ends b = -ln(exp(-3) -+ 1.96 sigma / sqrt(n))) is the costly part that a search over sets of effects
    leaves out for the sets it never reports."""
    from persson.effects import base
    from validation.refit import Z95, with_uncertainty

    monkeypatch.setattr(base, "_REGISTRY", dict(base._REGISTRY))
    fitter, fit, se = _decay_fit(0.4)
    now = with_uncertainty(fitter, fit, s2=1.0, profile=True)
    spent_now = fitter.n_evals - fit.n_evals
    fitter2, fit2, _ = _decay_fit(0.4)
    told = []
    later = with_uncertainty(fitter2, fit2, s2=1.0, profile=True, defer=True, on_evals=told.append)
    jacobian_only = fitter2.n_evals - fit2.n_evals
    assert 0 < jacobian_only < spent_now
    (bare,) = later.estimates
    assert math.isnan(bare.std) and bare.value == pytest.approx(now.estimates[0].value, rel=1e-12)
    assert not later.pending.ready and told == []
    estimates, notes = later.pending()
    assert len(told) == 1                                 # the 68 % intervals; the 95 % ones wait to be read
    assert estimates == now.estimates and notes == now.notes
    assert len(told) == 2 and told[1] > 0
    assert later.covariance.estimates == now.estimates
    assert np.array_equal(later.covariance.matrix, now.covariance.matrix)
    assert sum(told) == fitter2.n_evals - fit2.n_evals - jacobian_only and jacobian_only + sum(told) == spent_now
    exact = (-math.log(math.exp(-3.0) + Z95 * se), -math.log(math.exp(-3.0) - Z95 * se))
    assert estimates[0].interval95 == pytest.approx(exact, abs=0.01)


def test_95_percent_intervals_computed_when_first_read_have_the_budget_they_had_at_once(monkeypatch):
    """``defer95=True`` (the diagnoses of a set search's steps, which report 68 % intervals only): the 68 % intervals
    at once, the 95 % profile when ``interval95`` is first read, equal to the one computed at once -- even when the
    fitter has been used in between and its budget moved: the 95 % profile gets the evaluations it had left."""
    from persson.effects import base
    from validation.refit import with_uncertainty

    monkeypatch.setattr(base, "_REGISTRY", dict(base._REGISTRY))
    fitter, fit, _ = _decay_fit(0.4)
    (now,) = with_uncertainty(fitter, fit, s2=1.0, profile=True).estimates
    fitter2, fit2, _ = _decay_fit(0.4)
    told = []
    (e,) = with_uncertainty(fitter2, fit2, s2=1.0, profile=True, defer95=True, on_evals=told.append).estimates
    assert (e.value, e.std, e.interval, e.method) == (now.value, now.std, now.interval, now.method)
    n0 = fitter2.n_evals
    fitter2.max_evals = fitter2.n_evals             # another user of the fitter spent its budget meanwhile
    assert e.interval95 == now.interval95 and e.note95 == now.note95 == ""
    assert told == [fitter2.n_evals - n0] and told[0] > 0


def test_the_credibility_of_a_deferred_fit_needs_only_the_intervals_of_its_doubtful_parameters(monkeypatch):
    """A decay searched over b in 0 - 2 while the data put b at 3: the fit ends on the upper search bound, where
    only b's 68 % interval tells "pushed out of the range" (bounded below the bound) from "not identified". The
    credibility estimates say what the full ones say, and cost no more; a parameter off its bounds and inside its
    plausible range needs none (the bare estimates have no issue)."""
    from persson.effects import base
    from validation.refit import with_uncertainty

    monkeypatch.setattr(base, "_REGISTRY", dict(base._REGISTRY))
    fitter, fit, _ = _decay_fit(0.4, hi=2.0)
    full = with_uncertainty(fitter, fit, s2=1.0, profile=True)
    (f,) = full.estimates
    assert f.value == pytest.approx(2.0) and f.issue.startswith("on the upper search bound 2")
    fitter2, fit2, _ = _decay_fit(0.4, hi=2.0)
    later = with_uncertainty(fitter2, fit2, s2=1.0, profile=True, defer=True)
    (bare,) = later.estimates
    assert bare.issue                                    # on the bound: the intervals must judge it
    n0 = fitter2.n_evals
    (c,) = later.credibility()
    assert c.issue == f.issue and c.interval == f.interval and math.isnan(c.interval95[0])
    assert fitter2.n_evals - n0 <= fitter.n_evals - fit.n_evals
    assert not later.pending.ready
    fitter3, fit3, _ = _decay_fit(0.4)
    (inside,) = with_uncertainty(fitter3, fit3, s2=1.0, profile=True, defer=True).estimates
    assert inside.issue == ""


def test_a_set_reads_its_intervals_only_when_they_are_needed():
    """A set of effects fitted in a search carries its intervals unevaluated: a set whose parameters all lie inside
    their plausible ranges and off their bounds is credible without them; a doubtful one is judged by its
    credibility estimates; the intervals themselves are computed once, on the first read of ``estimates``."""
    from validation.deferred import Deferred, is_ready
    from validation.refit import Estimate
    from validation.select import EffectSet

    calls = []

    def intervals():
        calls.append(1)
        return (Estimate(key="a.x", value=1.0, std=0.1, interval=(0.9, 1.1), method="quadratic"),)

    def fitted(clean, credibility=None):
        return EffectSet(effects=("a",), model=None, contact=None, predicted=np.zeros(3), rss=1.0, bic=0.0,
                         rmse=1.0, n_params=1, estimates=Deferred(intervals), lack=None, pattern=None,
                         fitted={"a.x": 1.0}, clean=clean, credibility=credibility)

    s = fitted(clean=True)
    assert s.plausible and s.parameters() == {"a.x": 1.0} and not is_ready(s, "estimates") and calls == []
    doubtful = Deferred(lambda: (Estimate(key="a.x", value=1.0, std=0.1, interval=(0.9, 1.1), method="profile",
                                          issue="on the upper search bound 1: the data push it out of the range "
                                                "searched"),))
    s = fitted(clean=False, credibility=doubtful)
    assert not s.plausible and calls == [] and doubtful.ready
    assert s.estimates[0].interval == (0.9, 1.1) and s.estimates is s.estimates and calls == [1]
    assert s.issues == ()          # once computed, the intervals themselves judge the set


def test_a_pickled_set_carries_its_intervals_computed():
    """Pickling (or copying) an object whose intervals are deferred computes them: a pickle cannot hold the
    computation, and the copy has the same values as the original once read."""
    import copy
    import pickle

    from validation.deferred import Deferred, is_ready
    from validation.refit import Estimate
    from validation.select import EffectSet

    calls = []

    def intervals():
        calls.append(1)
        return (Estimate(key="a.x", value=1.0, std=0.1, interval=(0.9, 1.1), method="quadratic"),)

    s = EffectSet(effects=("a",), model=None, contact=None, predicted=np.zeros(3), rss=1.0, bic=0.0, rmse=1.0,
                  n_params=1, estimates=Deferred(intervals), lack=None, pattern=None, clean=True)
    back = pickle.loads(pickle.dumps(s))
    assert calls == [1] and is_ready(back, "estimates") and back.estimates[0].interval == (0.9, 1.1)
    assert copy.deepcopy(s).estimates == s.estimates and calls == [1]


class _EdgeTrap:
    r"""A stand-in fitter of two parameters (a, b) whose profile in a is (t / 0.2)^2, t = a - 0.2, along the curved
    valley b = 0.5 - 3 t + 6 t^2 (always above 0.12): the Gauss-Newton Hessian at the optimum extrapolates b
    linearly, b = 0.5 - 3 t, which leaves the box beyond t = 1/6. On the edge b = 0 the effect vanishes, as an
    adhesion's with tau_f0 = 0, and a refit started there has no gradient and stays, far above the profile."""

    def __init__(self):
        self.n_evals = 0
        self.max_evals = 10**6
        self.second = 0             # refits that follow one started on the edge: the profile's second starts
        self.last_clipped = False

    @staticmethod
    def profile(a: float) -> float:
        return ((a - 0.2) / 0.2) ** 2

    @staticmethod
    def valley(a: float) -> float:
        t = a - 0.2
        return 0.5 - 3.0 * t + 6.0 * t * t

    def local(self, v, fixed=(), max_nfev=None):
        import numpy as np

        self.n_evals += 1
        a, b = float(v[0]), float(v[1])
        if self.last_clipped:
            self.second += 1
        self.last_clipped = b <= 0.0
        if b <= 0.0:
            return np.array([a, 0.0]), self.profile(a) + 1000.0 * self.valley(a) ** 2
        return np.array([a, self.valley(a)]), self.profile(a)


def test_a_profile_refit_whose_linearized_start_leaves_the_box_also_starts_from_the_last_point():
    """The 95 % end of the stand-in's profile is exactly t = 1.96 x 0.2 (a = 0.592). A refit started where the
    linearized valley crosses b = 0 (clipped onto the edge) stays on it and reads delta chi^2 more than 15 above the
    profile; the profile takes the lower of that refit and one from the last point below the level without the
    extrapolation, and finds the exact end (the refits from the edge alone put it at a = 0.38). The lower side runs
    into the bound a = 0 below the level. The second refit spends evaluations of its own: the fitter's budget left
    for the other profiles is what it was."""
    import numpy as np

    from validation.refit import Z95, _profile

    # Hessian with the valley's slope db/da = -3 at the optimum and the profile's curvature 1 / 0.2^2 (Schur)
    H = np.array([[25.0 + 9.0, 3.0], [3.0, 1.0]])
    trap = _EdgeTrap()
    lo, hi = _profile(trap, np.array([0.2, 0.5]), 0, 0.0, 1.0, 0.2, 2, H=H, level=Z95 ** 2)
    assert lo == 0.0 and hi == pytest.approx(0.2 + 0.2 * Z95, abs=2e-3)
    assert trap.second > 0 and trap.max_evals - trap.n_evals == 10**6 - (trap.n_evals - trap.second)
