"""validation: predictions, comparison tables and the diagnosis statistics against independent numbers.

The statistics are checked on effects whose refit has a closed form (a constant offset, a slope in log speed):
the bounded nonlinear refit must reproduce the linear least-squares solution, and RMSE, BIC, the F / chi2 test
and the score statistic must equal the textbook formulas computed here with numpy and scipy.
"""

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
    np.testing.assert_allclose(p[:3], model.friction([0.01, 0.1, 1.0], 20.0, 3e5).mu, rtol=1e-12)
    np.testing.assert_allclose(p[3:5], mu_slip(model, [0.02, 0.2], 1.0, temperature=20.0, pressure=3e5,
                                               contact=contact).mu, rtol=1e-12)
    # rows at another temperature share the engine call (and its modulus table) through time-temperature
    # superposition, so they agree with a separate call to the table's interpolation accuracy
    assert p[5] == pytest.approx(float(model.friction(0.1, 40.0, 2e5).mu), rel=1e-5)
    wet = model.with_effect(Wet())
    assert p[6] == pytest.approx(float(mu_slip(wet, 0.1, 0.5, temperature=20.0, pressure=3e5, contact=contact).mu),
                                 rel=1e-12)
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
    model = persson.Model(SURFACE, TREAD)
    m = _rows().with_mu(validation.predict(model, _rows()).mu + 0.001)
    dx = validation.diagnose(model, m, candidates=["wet"], probe=False)   # no wet rows
    assert dx.top.status == "no signature" and not dx.top.significant and dx.top.delta_bic == 0.0
    js = dx.to_json()
    assert '"wet"' in js


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
