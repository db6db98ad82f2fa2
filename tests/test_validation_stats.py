"""validation: predictions, comparison tables and the diagnosis statistics against independent numbers.

The statistics are checked on effects whose refit has a closed form (a constant offset, a slope in log speed):
the bounded nonlinear refit must reproduce the linear least-squares solution, and RMSE, BIC, the F / chi2 test
and the score statistic must equal the textbook formulas computed here with numpy and scipy.
"""

import math
from dataclasses import dataclass

import numpy as np
import pytest
from scipy import stats

import materials
import persson
import surfaces
import validation
from persson.effects import Effect, Parameter, Wet
from persson.slip import Contact, mu_slip

SURFACE = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e5, hrms=1e-4)
TREAD = materials.example_tread()


@pytest.fixture
def registry(monkeypatch):
    """Effects defined in a test register into a throw-away copy of the registry."""
    from persson.effects import base

    monkeypatch.setattr(base, "_REGISTRY", dict(base._REGISTRY))
    yield


def _offset_classes():
    @dataclass(frozen=True)
    class Offset(Effect):
        name = "test_offset"
        parameters = (Parameter("c", 0.05, (-0.5, 0.5), "1", "constant added to mu"),)
        c: float = 0.05

        def friction_term(self, state):
            return np.full_like(state.conditions.speed, self.c)

    @dataclass(frozen=True)
    class Slope(Effect):
        name = "test_slope"
        parameters = (Parameter("k", 0.01, (-0.2, 0.2), "1", "mu per decade of speed"),)
        k: float = 0.01

        def friction_term(self, state):
            return self.k * np.log10(state.conditions.speed)

    return Offset, Slope


def _rows(n_speed=8):
    v = np.geomspace(1e-3, 1.0, n_speed)
    T = np.repeat([10.0, 30.0], n_speed)
    return validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, 2), temperature=T, pressure=3e5,
                                               mu=np.full(2 * n_speed, 0.5))


# ---- predictions and comparison ----------------------------------------------------------------------------
def test_predictions_equal_direct_engine_and_brush_calls():
    model = persson.Model(SURFACE, TREAD, effects=[persson.effects.Adhesion(tau_f0=1e6)])
    contact = Contact(0.02, 0.01, 3e9)
    m = validation.Measurements.from_arrays(
        slip=[1, 1, 1, 0.02, 0.2, 1, 0.1], speed=[0.01, 0.1, 1.0, 1.0, 1.0, 0.1, 0.5],
        temperature=[20, 20, 20, 20, 20, 40, 20], pressure=[3e5, 3e5, 3e5, 3e5, 3e5, 2e5, 3e5],
        mu=0.5, wet=[0, 0, 0, 0, 0, 0, 1])
    p = validation.predict(model, m, contact).mu
    # the same engine and grid; the modulus table spans all the speeds of a call, so its convolution sums differ
    # by rounding (1e-12) from those of a call with fewer speeds
    np.testing.assert_allclose(p[:3], model.friction([0.01, 0.1, 1.0], 20.0, 3e5).mu, rtol=1e-10)
    np.testing.assert_allclose(p[3:5], mu_slip(model, [0.02, 0.2], 1.0, temperature=20.0, pressure=3e5,
                                               contact=contact).mu, rtol=1e-10)
    # rows at another temperature share the engine call (and its modulus table) through time-temperature
    # superposition, so they agree with a separate call to the table's interpolation accuracy
    assert p[5] == pytest.approx(float(model.friction(0.1, 40.0, 2e5).mu), rel=1e-5)
    wet = model.with_effect(Wet())
    assert p[6] == pytest.approx(float(mu_slip(wet, 0.1, 0.5, temperature=20.0, pressure=3e5, contact=contact).mu),
                                 rel=1e-10)
    # wet: no adhesion, so lower than the dry prediction at the same condition
    dry = float(mu_slip(model, 0.1, 0.5, temperature=20.0, pressure=3e5, contact=contact).mu)
    assert p[6] < dry


def test_comparison_numbers_and_tables():
    model = persson.Model(SURFACE, TREAD)
    m0 = _rows()
    f = validation.predict(model, m0).mu
    y = f + np.where(m0.speed > 0.05, 0.03, -0.01)   # systematic deviation at high speed
    m = m0.with_mu(y)
    cmp = validation.compare(model, m)
    r = y - f
    assert cmp.rmse == pytest.approx(np.sqrt(np.mean(r ** 2)), rel=1e-10)
    assert cmp.bias == pytest.approx(np.mean(r), rel=1e-10)
    np.testing.assert_allclose(cmp.residual, r, atol=1e-12)
    by_speed = {g.label: g for g in cmp.tables["sliding speed"]}
    vs = m.sliding_speed
    sel = (vs >= 0.1) & (vs < 1.0)
    g = by_speed["0.1-1 m/s"]
    assert g.n == int(sel.sum()) and g.bias == pytest.approx(np.mean(r[sel]), rel=1e-10)
    by_T = {g.label: g for g in cmp.tables["temperature"]}
    assert by_T["10 C"].measured == pytest.approx(np.mean(y[m.temperature == 10]), rel=1e-12)
    worst = cmp.worst_groups()
    assert worst and worst[0].bias == pytest.approx(0.03, abs=1e-9)


# ---- diagnosis statistics vs closed forms ------------------------------------------------------------------
def test_offset_refit_bic_F_test_and_score_match_closed_forms(registry):
    Offset, _ = _offset_classes()
    model = persson.Model(SURFACE, TREAD)
    m0 = _rows()
    f0 = validation.predict(model, m0).mu
    rng = np.random.default_rng(3)
    y = f0 + 0.04 + rng.normal(0, 0.005, f0.size)
    m = m0.with_mu(y)
    dx = validation.diagnose(model, m, candidates=[Offset()], probe=False)
    c = dx.candidate("test_offset")
    n = y.size
    r = y - f0
    rss0 = np.sum(r ** 2)
    rss1 = np.sum((r - r.mean()) ** 2)
    assert c.parameters["c"] == pytest.approx(r.mean(), rel=1e-4)
    assert c.rmse == pytest.approx(np.sqrt(rss1 / n), rel=1e-6)
    assert dx.baseline.bic == pytest.approx(n * np.log(rss0 / n), rel=1e-12)
    assert c.delta_bic == pytest.approx(n * np.log(rss1 / rss0) + np.log(n), rel=1e-6)
    F = (rss0 - rss1) / (rss1 / (n - 1))
    assert c.p_value == pytest.approx(stats.f.sf(F, 1, n - 1), rel=1e-4)
    assert c.score_z == pytest.approx(r.sum() / (np.sqrt(rss0 / n) * np.sqrt(n)), rel=1e-9)
    assert c.significant and c.test == "F"


def test_weighted_offset_with_mu_std_uses_chi2(registry):
    Offset, _ = _offset_classes()
    model = persson.Model(SURFACE, TREAD)
    m0 = _rows()
    f0 = validation.predict(model, m0).mu
    std = np.linspace(0.004, 0.012, f0.size)
    rng = np.random.default_rng(4)
    y = f0 + 0.02 + rng.normal(0, 1, f0.size) * std
    m = validation.Measurements.from_arrays(slip=m0.slip, speed=m0.speed, temperature=m0.temperature,
                                            pressure=m0.pressure, mu=y, mu_std=std)
    dx = validation.diagnose(model, m, candidates=["test_offset"], probe=False)
    c = dx.top
    w2 = 1 / std ** 2
    r = y - f0
    c_hat = np.sum(w2 * r) / np.sum(w2)
    chi0 = np.sum(w2 * r ** 2)
    chi1 = np.sum(w2 * (r - c_hat) ** 2)
    assert dx.sigma_known
    assert c.parameters["c"] == pytest.approx(c_hat, rel=1e-4)
    assert c.rss == pytest.approx(chi1, rel=1e-6)
    assert c.delta_bic == pytest.approx(chi1 - chi0 + np.log(y.size), rel=1e-6)
    assert c.p_value == pytest.approx(stats.chi2.sf(chi0 - chi1, 1), rel=1e-3)
    assert c.test == "chi2" and c.significant


def test_baseline_parameters_are_projected_out_and_refitted_jointly(registry):
    """Baseline: offset fitted ([model] fit). Candidate: slope in log v. The joint refit is linear regression on
    [1, log10 v]; the score test uses the signature with the constant projected out."""
    Offset, Slope = _offset_classes()
    model = persson.Model(SURFACE, TREAD, effects=[Offset(c=0.0)])
    m0 = _rows()
    f_given = validation.predict(model, m0).mu
    x = np.log10(m0.speed)
    rng = np.random.default_rng(5)
    y = f_given + 0.08 + 0.02 * x + rng.normal(0, 0.004, x.size)
    m = m0.with_mu(y)
    dx = validation.diagnose(model, m, candidates=[Slope()], fit=["test_offset.c"], probe=False)
    r = y - f_given
    n = y.size
    # baseline refit: offset = mean residual
    assert dx.baseline.fitted["test_offset.c"] == pytest.approx(r.mean(), rel=1e-6)
    rss0 = np.sum((r - r.mean()) ** 2)
    assert dx.baseline.rss == pytest.approx(rss0, rel=1e-6)
    A = np.column_stack([np.ones(n), x])
    coef, *_ = np.linalg.lstsq(A, r, rcond=None)
    rss1 = np.sum((r - A @ coef) ** 2)
    c = dx.top
    assert c.parameters["k"] == pytest.approx(coef[1], rel=1e-4)
    assert c.baseline_parameters["test_offset.c"] == pytest.approx(coef[0], rel=1e-4)
    assert c.delta_bic == pytest.approx(n * np.log(rss1 / rss0) + np.log(n), rel=1e-5)
    F = (rss0 - rss1) / (rss1 / (n - 2))
    assert c.p_value == pytest.approx(stats.f.sf(F, 1, n - 2), rel=1e-3)
    # score: signature k0 * x with the constant projected out, sigma from the fitted baseline (n - 1 dof)
    d = 0.01 * (x - x.mean())
    rc = r - r.mean()
    z = d @ rc / (np.sqrt(rss0 / (n - 1)) * np.linalg.norm(d))
    assert c.score_z == pytest.approx(z, rel=1e-4)
    assert c.significant


def test_candidate_that_changes_nothing_is_reported_without_signature(registry):
    @dataclass(frozen=True)
    class Fast(Effect):
        """A term that acts only above 10 m/s (the rows end at 1 m/s)."""

        name = "test_fast"
        parameters = (Parameter("a", 0.05, (0.0, 0.5), "1", "friction added above 10 m/s"),)
        a: float = 0.05

        def friction_term(self, state):
            return np.where(state.conditions.speed > 10.0, self.a, 0.0)

    model = persson.Model(SURFACE, TREAD)
    m = _rows().with_mu(validation.predict(model, _rows()).mu + 0.001)
    dx = validation.diagnose(model, m, candidates=[Fast(), "wet"], probe=False)
    fast = dx.candidate("test_fast")
    assert fast.status == "no signature" and not fast.significant and fast.delta_bic == 0.0
    # the wet effect cannot act on rows measured dry: not applicable (not failed, not a missing signature)
    wet = dx.candidate("wet")
    assert wet.status.startswith("not applicable") and "no wet rows" in wet.status and not wet.applicable
    assert [c.effect for c in dx.candidates] == ["test_fast", "wet"]
    assert "Not applicable to these rows: wet" in dx.explanation
    js = dx.to_json()
    assert '"wet"' in js and '"not applicable: no wet rows' in js


def test_failing_user_effect_is_reported_not_raised(registry):
    @dataclass(frozen=True)
    class Broken(Effect):
        name = "test_broken"
        parameters = (Parameter("a", 0.5, (0.0, 1.0), "1", "anything"),)
        a: float = 0.5

        def friction_term(self, state):
            raise RuntimeError("boom")

    model = persson.Model(SURFACE, TREAD)
    m = _rows().with_mu(validation.predict(model, _rows()).mu)
    dx = validation.diagnose(model, m, candidates=[Broken()], probe=False)
    assert dx.top.status.startswith("failed") and "boom" in dx.top.status and not dx.top.significant


def test_a_baseline_fit_that_runs_out_of_evaluations_still_gives_its_derivatives():
    """The budget bounds the search; the derivatives at the best point found are part of the result."""
    model = persson.Model(SURFACE, TREAD, effects=[persson.effects.Adhesion(tau_f0=0.5e6)])
    rows = _rows(n_speed=5)
    m = rows.with_mu(validation.predict(model.with_effect(persson.effects.Adhesion(tau_f0=1e6)), rows).mu)
    dx = validation.diagnose(model, m, fit=["adhesion.tau_f0"], candidates=["flash_temperature"], probe=False,
                             max_evals=3)
    assert dx.baseline.n_params == 1 and "adhesion.tau_f0" in dx.baseline.fitted
    assert any("budget" in n for n in dx.baseline.notes), dx.baseline.notes


def test_bad_arguments():
    model = persson.Model(SURFACE, TREAD)
    m = _rows()
    with pytest.raises(validation.InputError, match="candidates"):
        validation.diagnose(model, m, candidates=["no_such_effect"])
    with pytest.raises(validation.InputError, match="already in the model"):
        validation.diagnose(model.with_effect(persson.effects.Adhesion()), m, candidates=["adhesion"])
    with pytest.raises(validation.InputError, match="fit"):
        validation.diagnose(model, m, fit=["adhesion.tau_f0"])
    slip_rows = validation.Measurements.from_arrays(slip=0.1, speed=1.0, temperature=20, pressure=3e5, mu=0.5)
    with pytest.raises(validation.InputError, match="contact"):
        validation.compare(model, slip_rows)


# ---- global fits, uncertainties, plausibility (issue 12) -------------------------------------------------------
def _linear_rows(n_speed=10, temps=(10.0, 30.0)):
    v = np.geomspace(1e-3, 1.0, n_speed)
    return validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, len(temps)),
                                               temperature=np.repeat(temps, n_speed), pressure=3e5,
                                               mu=np.full(n_speed * len(temps), 0.5))


def _offset_class(bounds=(-0.5, 0.5), plausible=None, physical=()):
    @dataclass(frozen=True)
    class Offset(Effect):
        name = "test_offset"
        parameters = (Parameter("c", 0.01, bounds, "1", "constant added to mu", plausible=plausible,
                                physical_limits=physical),)
        c: float = 0.01

        def friction_term(self, state):
            return np.full_like(state.conditions.speed, self.c)

    return Offset


def test_standard_error_of_a_linear_refit_is_the_least_squares_one(registry):
    """Offset with known mu_std: the estimate is the weighted mean, its standard error 1/sqrt(sum w)."""
    Offset = _offset_class()
    model = persson.Model(SURFACE, TREAD)
    m0 = _linear_rows()
    f0 = validation.predict(model, m0).mu
    std = np.linspace(0.004, 0.012, f0.size)
    y = f0 + 0.03 + np.random.default_rng(21).normal(0, 1, f0.size) * std
    m = validation.Measurements.from_arrays(slip=m0.slip, speed=m0.speed, temperature=m0.temperature,
                                            pressure=m0.pressure, mu=y, mu_std=std)
    dx = validation.diagnose(model, m, candidates=[Offset()], probe=False)
    c = dx.top
    w = 1 / std ** 2
    (est,) = c.estimates
    assert est.value == pytest.approx(np.sum(w * (y - f0)) / np.sum(w), rel=1e-4)
    assert est.std == pytest.approx(1 / np.sqrt(np.sum(w)), rel=1e-3)
    assert est.method == "quadratic" and est.issue == "" and c.plausible
    assert dx.verdict.verdict == "explained" and dx.noise_estimate.source == "mu_std"
    d = c.as_dict()
    assert d["parameters_std"]["c"] == pytest.approx(est.std) and d["intervals"]["c"] == list(est.interval)


def test_intervals_of_a_fit_against_a_noise_estimated_from_replicates_use_students_t(registry):
    """Every condition measured twice and no mu_std: the noise is the replicates' pooled scatter on n/2 degrees of
    freedom, and the offset's intervals are its standard error s / sqrt(n) times Student's t quantiles with those
    degrees of freedom (scipy.stats, independently): wider than +- 1 and 1.96 standard errors by 3 % and 6 % here."""
    Offset = _offset_class()
    model = persson.Model(SURFACE, TREAD)
    m1 = _linear_rows()
    f1 = validation.predict(model, m1).mu
    n1 = f1.size
    rng = np.random.default_rng(31)
    y = np.concatenate([f1, f1]) + 0.03 + rng.normal(0, 0.005, 2 * n1)
    m = validation.Measurements.from_arrays(slip=np.tile(m1.slip, 2), speed=np.tile(m1.speed, 2),
                                            temperature=np.tile(m1.temperature, 2),
                                            pressure=np.tile(m1.pressure, 2), mu=y)
    dx = validation.diagnose(model, m, candidates=[Offset()], probe=False)
    noise = dx.noise_estimate
    assert noise.source == "replicates" and noise.dof == n1
    pure = np.sum((y[:n1] - y[n1:]) ** 2) / 2 / n1          # pooled variance of the pairs
    assert noise.sigma == pytest.approx(math.sqrt(pure), rel=1e-9)
    (est,) = dx.top.estimates
    se = math.sqrt(pure / (2 * n1))
    assert est.value == pytest.approx(np.mean(y - np.concatenate([f1, f1])), abs=1e-6)
    assert est.std == pytest.approx(se, rel=1e-3) and est.method == "quadratic"
    t68, t95 = stats.t.ppf(stats.norm.cdf(1.0), n1), stats.t.ppf(0.975, n1)
    assert est.interval == pytest.approx((est.value - t68 * se, est.value + t68 * se), rel=1e-4)
    assert est.interval95 == pytest.approx((est.value - t95 * se, est.value + t95 * se), rel=1e-4)


def test_parameter_on_a_search_bound_is_implausible_and_never_the_explanation(registry):
    """The data want an offset of 0.1; the search stops at 0.05. The fit is significant but not credible, the
    profile interval is open at the bound, and the verdict is 'unexplained'."""
    Offset = _offset_class(bounds=(-0.05, 0.05))
    model = persson.Model(SURFACE, TREAD)
    m0 = _linear_rows()
    f0 = validation.predict(model, m0).mu
    sigma = 0.005
    y = f0 + 0.1 + np.random.default_rng(22).normal(0, sigma, f0.size)
    m = validation.Measurements.from_arrays(slip=m0.slip, speed=m0.speed, temperature=m0.temperature,
                                            pressure=m0.pressure, mu=y, mu_std=np.full(f0.size, sigma))
    dx = validation.diagnose(model, m, candidates=[Offset()], probe=False)
    c = dx.top
    (est,) = c.estimates
    assert c.significant and not c.plausible and not c.credible
    assert est.bound == "search bound" and "upper search bound" in est.issue
    assert est.method.startswith("profile") and est.interval[1] == pytest.approx(0.05)
    # the profile's lower end, independently: chi2(c) - chi2(0.05) = t^2 s2 with chi2 = W (c - c_u)^2 + const about
    # the unconstrained optimum c_u; the model fails its lack-of-fit test, so the unit s2 is chi2_min / (n - 1)
    # (Birge), estimated with n - 1 degrees of freedom: t is Student's 84.13 % quantile with them
    W = f0.size / sigma ** 2
    c_u = float(np.mean(y - f0))
    s2 = float(np.sum(((y - f0 - 0.05) / sigma) ** 2)) / (f0.size - 1)
    assert not c.lack.consistent
    t68 = stats.t.ppf(stats.norm.cdf(1.0), f0.size - 1)
    lower = c_u - math.sqrt((0.05 - c_u) ** 2 + t68 ** 2 * s2 / W)
    assert est.interval[0] == pytest.approx(lower, abs=1e-4)
    assert dx.verdict.verdict == "unexplained" and dx.best is None
    assert "search bound" in dx.explanation and "Not credible" in dx.explanation


def test_value_outside_the_declared_plausible_range_demotes(registry):
    Offset = _offset_class(plausible=(0.0, 0.02))
    model = persson.Model(SURFACE, TREAD)
    m0 = _linear_rows()
    f0 = validation.predict(model, m0).mu
    y = f0 + 0.05 + np.random.default_rng(23).normal(0, 0.005, f0.size)
    dx = validation.diagnose(model, m0.with_mu(y), candidates=[Offset()], probe=False)
    assert dx.top.significant and not dx.top.plausible
    assert "outside the plausible range" in dx.top.issues[0]
    assert dx.verdict.verdict == "unexplained"


def test_a_physical_limit_is_a_legitimate_optimum(registry):
    Offset = _offset_class(bounds=(0.0, 0.5), physical=(0.0,))
    model = persson.Model(SURFACE, TREAD)
    m0 = _linear_rows()
    f0 = validation.predict(model, m0).mu
    y = f0 - 0.01 + np.random.default_rng(24).normal(0, 0.002, f0.size)
    dx = validation.diagnose(model, m0.with_mu(y), candidates=[Offset()], probe=False)
    (est,) = dx.top.estimates
    assert est.value == pytest.approx(0.0, abs=1e-6)
    assert est.bound == "physical limit" and est.issue == "" and dx.top.plausible


def test_the_global_fit_finds_the_optimum_a_local_fit_from_the_given_values_misses(registry):
    """A friction bump in log speed: started far from the data (x0 = 1.5, beyond the speeds), a local fit sees a
    flat objective; the Halton starts find the bump at x0 = -2.2."""

    @dataclass(frozen=True)
    class Bump(Effect):
        name = "test_bump"
        parameters = (Parameter("a", 0.05, (0.0, 0.3), "1", "height of the bump", physical_limits=(0.0,)),
                      Parameter("x0", 1.5, (-4.0, 2.0), "1", "log10 of the speed of the bump, m/s"))
        a: float = 0.05
        x0: float = 1.5

        def friction_term(self, state):
            return self.a * np.exp(-((np.log10(state.conditions.speed) - self.x0) / 0.3) ** 2)

    model = persson.Model(SURFACE, TREAD)
    m0 = _linear_rows(n_speed=13)
    f0 = validation.predict(model, m0).mu
    lv = np.log10(m0.speed)
    y = f0 + 0.08 * np.exp(-((lv + 2.2) / 0.3) ** 2) + np.random.default_rng(25).normal(0, 0.004, f0.size)
    dx = validation.diagnose(model, m0.with_mu(y), candidates=[Bump()], probe=False)
    c = dx.top
    assert c.parameters["x0"] == pytest.approx(-2.2, abs=0.05) and c.parameters["a"] == pytest.approx(0.08, rel=0.1)
    est = {e.name: e for e in c.estimates}
    assert abs(est["x0"].value + 2.2) <= 3 * est["x0"].std + 1e-3
    assert c.n_starts >= 2 and dx.verdict.verdict == "explained"


def test_placeholders_are_not_free_parameters():
    from validation.fitting import free_parameters

    assert [p.name for p in free_parameters(persson.effects.FlashTemperature())] == ["macro_scale_ratio"]
    with pytest.raises(validation.InputError, match="contact_diameter"):
        free_parameters(persson.effects.FlashTemperature(), names=["contact_diameter"])
    assert [p.name for p in free_parameters(persson.effects.Microtexture())] == ["q1"]
    (h,) = free_parameters(persson.effects.Microtexture(), names=["hurst"])
    assert (h.lo, h.hi) == (0.5, 1.0)       # the plausible range, which excludes the placeholder 0


def test_release_placeholders_starts_each_in_the_middle_of_its_plausible_range():
    from validation.fitting import release_placeholders

    eff, names, starts = release_placeholders(persson.effects.Microtexture(q1=3e5))
    assert starts == {"hurst": 0.75} and eff.hurst == 0.75 and eff.q1 == 3e5 and names == ["q1", "hurst"]
    assert release_placeholders(persson.effects.Microtexture(hurst=0.8)) is None      # no placeholder held
    assert release_placeholders(persson.effects.Adhesion()) is None                   # none declared


def test_a_placeholder_the_case_cannot_compute_is_fitted_over_its_plausible_range(registry):
    """A slope in log speed whose placeholder 0 ("from the data's own trend") cannot be computed on these rows:
    the candidate is fitted with the slope free over its plausible range, not reported as failed, and recovers
    the linear least-squares slope (closed form, computed here with numpy)."""

    @dataclass(frozen=True)
    class AutoSlope(Effect):
        name = "test_auto_slope"
        parameters = (Parameter("k", 0.0, (0.0, 0.2), "1", "mu per decade of speed", plausible=(0.001, 0.2),
                                sentinel=0.0, sentinel_doc="from the data's own trend"),)
        k: float = 0.0

        def friction_term(self, state):
            if self.k == 0.0:
                raise validation.InputError("test_auto_slope: no trend to read on these rows; give k= explicitly")
            return self.k * (np.log10(state.conditions.speed) + 3.0)

    model = persson.Model(SURFACE, TREAD)
    m0 = _linear_rows()
    f0 = validation.predict(model, m0).mu
    x = np.log10(m0.speed) + 3.0
    y = f0 + 0.03 * x + np.random.default_rng(26).normal(0.0, 0.002, f0.size)
    dx = validation.diagnose(model, m0.with_mu(y), candidates=[AutoSlope()], probe=False)
    c = dx.top
    assert c.status == "ok" and c.free == ("k",) and not c.placeholders
    assert any("test_auto_slope.k: its placeholder (from the data's own trend) cannot be computed" in n
               and "plausible range 0.001 - 0.2" in n for n in c.notes)
    k_lsq = float(np.sum(x * (y - f0)) / np.sum(x * x))   # least squares through the origin in x
    assert c.parameters["k"] == pytest.approx(k_lsq, rel=1e-4)
    assert dx.verdict.verdict == "explained" and dx.verdict.effect == "test_auto_slope"


def test_microtexture_on_a_psd_table_that_ends_at_its_roll_off_fits_the_tails_hurst_exponent():
    """The measured table stops just above the roll-off, so no self-affine tail is left to fit H on (the
    placeholder fails); the data, computed on the analytic self-affine surface that continues to q1 = 3e5 rad/m
    on a finer grid, still identify the tail: the candidate fits q1 and H, and the truth lies in their intervals."""
    H, q0, q_r = 0.8, 2.9e4, 3.2e4
    truth_surface = surfaces.SelfAffine(hurst=H, q0=q0, q1=3e5, hrms=2e-5, qL=q0 / 8)
    table = truth_surface.with_cutoff(q1=q_r).tabulate(n_per_decade=16)
    case_surface = surfaces.PSD(table.q, table.C_values, q_r=float(table.q[-1]), qL=table.qL,
                                q_rolloff=table.q_rolloff, source="measured to its roll-off")
    with pytest.raises(surfaces.InputError, match="need >= 3 points"):
        case_surface.extrapolate(3e5)
    speed, temperature = np.tile(np.geomspace(1e-5, 1.0, 6), 3), np.repeat([-10.0, 10.0, 30.0], 6)
    fine = persson.GridSettings(q_per_decade=48, omega_per_decade=80)
    mu = persson.Model(truth_surface, TREAD, grid=fine).friction(speed, temperature=temperature, pressure=3e5).mu
    y = np.clip(mu + np.random.default_rng(27).normal(0.0, 0.003, mu.size), 0.0, None)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=speed, temperature=temperature, pressure=3e5, mu=y,
                                               mu_std=np.full(mu.size, 0.003))
    dx = validation.diagnose(persson.Model(case_surface, TREAD), rows, candidates=["microtexture"], probe=False)
    c = dx.top
    assert c.status == "ok" and c.free == ("q1", "hurst") and c.significant
    est = {e.name: e for e in c.estimates}
    for name, true in (("q1", 3e5), ("hurst", H)):
        lo, hi = est[name].interval95
        assert lo <= true <= hi, (name, est[name])
    assert dx.verdict.verdict == "explained"
