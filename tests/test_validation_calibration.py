"""validation: a calibration error of the rig named where it fits as well as the effects a diagnosis adds.

mu is the ratio of two measured forces: a gain error of a load cell scales every measured mu, a zero offset of the
friction force adds Delta F_x / F_z (as 1/p). A loss modulus a few per cent higher (strain softening with a loss
factor above 1) raises the hysteresis friction almost uniformly, as a gain does, so a diagnosis of data from a
badly calibrated rig can name strain softening. The check fits both errors on top of every subset of the answer
(closed-form weighted least squares, checked here against numpy's) and names one that fits as well.

60 sliding rows: 3 temperatures x 10 speeds x 2 pressures, known noise ``mu_std`` = 0.005.
"""

import dataclasses
import math
import warnings

import numpy as np
import pytest

import materials
import persson
import surfaces
import validation
from validation.calibration import GAIN_RANGE, OFFSET_LIMIT, check_calibration
from validation.report import render_report

SURFACE = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=3e-4)
TREAD = materials.example_tread()
SIGMA = 0.005
PRESSURES = (2e5, 4e5)


def _rows():
    v = np.geomspace(1e-3, 1.0, 10)
    speed = np.tile(v, 6)
    temperature = np.tile(np.repeat([10.0, 25.0, 40.0], 10), 2)
    pressure = np.repeat(PRESSURES, 30)
    return validation.Measurements.from_arrays(slip=1.0, speed=speed, temperature=temperature, pressure=pressure,
                                               mu=0.5, mu_std=SIGMA)


def _with_noise(rows, mu, seed):
    mu = mu + np.random.default_rng(seed).normal(0.0, SIGMA, rows.n)
    return rows.with_mu(mu, mu_std=np.full(rows.n, SIGMA))


@pytest.fixture(scope="module")
def baseline():
    base = persson.Model(SURFACE, TREAD)
    rows = _rows()
    return base, rows, validation.predict(base, rows).mu


@pytest.fixture(scope="module")
def gain_error(baseline):
    """Data from a rig whose mu reads 6 % high; strain softening is the only candidate."""
    base, rows, f = baseline
    m = _with_noise(rows, 1.06 * f, 11)
    return validation.improve(base, m, candidates=["strain_softening"])


def test_a_gain_error_absorbed_by_strain_softening_is_named_as_its_rival(gain_error):
    imp = gain_error
    assert imp.added == ("strain_softening",), imp.table_text()
    cal = imp.selection.calibration
    (first, *_) = cal.rivals
    assert first.kind == "gain" and first.effects == () and first.on == "(baseline)"
    # the baseline is exact here (no fitted parameter), so the gain is unbiased: within 4 standard errors of 1.06
    assert abs(first.value - 1.06) < 4 * first.std and 0 < first.std < 0.01
    assert first.at_noise and first.delta_bic < validation.select.EQUAL and first.gain_over_set > 10
    # named in the verdict, its text, the JSON and the report
    assert "strain_softening" in imp.final.calibration and "calibration" in imp.final.headline
    assert "check the rig's calibration" in imp.table_text()
    data = imp.as_dict()
    assert data["calibration"]["rivals"] and data["calibration"]["fits"][0]["kind"] == "gain"
    assert data["verdict_detail"]["calibration"] == imp.final.calibration
    html = render_report([imp])
    assert "Calibration of the rig" in html


def test_the_single_effect_diagnosis_names_the_rival_too(baseline, gain_error):
    base, rows, f = baseline
    dx = validation.diagnose(base, gain_error.measurements, candidates=["strain_softening"])
    assert dx.verdict.effect == "strain_softening"
    assert dx.calibration.rivals and dx.calibration.rivals[0].kind == "gain"
    assert dx.verdict.calibration and dx.explanation.startswith(dx.verdict.headline)
    assert dx.as_dict()["calibration"]["answer"] == "strain_softening"


def test_the_gain_and_the_offset_are_the_weighted_least_squares_fits(baseline, gain_error):
    base, rows, f = baseline
    ctx = gain_error.steps[0].diagnosis.context
    y, w = ctx.settings.y, ctx.settings.w
    n, k = y.size, 0
    bic0 = validation.candidates.bic(float(np.sum((w * (y - f)) ** 2)), n, k, True)
    check = check_calibration([("(baseline)", (), f, k, bic0)], ("(baseline)", (), bic0), ctx)
    by_kind = {c.kind: c for c in check.fits}
    p = rows.pressure
    p_ref = math.sqrt(PRESSURES[0] * PRESSURES[1])
    for kind, basis, target in (("gain", f, y), ("offset", p_ref / p, y - f)):
        A = (w * basis)[:, None]
        (value,), (rss,), _, _ = np.linalg.lstsq(A, w * target, rcond=None)
        c = by_kind[kind]
        assert c.value == pytest.approx(value, rel=1e-10)
        assert c.bic == pytest.approx(rss + (k + 1) * math.log(n), rel=1e-10)
        assert c.delta_bic == pytest.approx(c.bic - bic0, abs=1e-9)
        # variance unit 1 with mu_std, scaled by the Birge ratio where the fit misses the noise
        birge = max(1.0, rss / (n - k - 1))
        assert c.std == pytest.approx(math.sqrt(birge / float(A[:, 0] @ A[:, 0])), rel=1e-10)
    assert by_kind["offset"].p_ref == pytest.approx(p_ref, rel=1e-12)
    # lowest BIC first
    assert [c.bic for c in check.fits] == sorted(c.bic for c in check.fits)


def test_an_offset_of_the_friction_force_falls_with_pressure_and_is_found(baseline, gain_error):
    base, rows, f = baseline
    p_ref = math.sqrt(PRESSURES[0] * PRESSURES[1])
    m = _with_noise(rows, f + 0.03 * p_ref / rows.pressure, 12)
    ctx = gain_error.steps[0].diagnosis.context
    ctx = dataclasses.replace(ctx, settings=dataclasses.replace(ctx.settings, y=m.mu), measurements=m)
    bic0 = validation.candidates.bic(float(np.sum(((m.mu - f) / SIGMA) ** 2)), m.n, 0, True)
    check = check_calibration([("(baseline)", (), f, 0, bic0)], ("(baseline)", (), bic0), ctx)
    (first, *_) = check.rivals
    assert first.kind == "offset" and abs(first.value - 0.03) < 4 * first.std and first.at_noise
    assert "zero offset of the friction force" in check.text() and "Check the rig's calibration" in check.text()


def test_errors_beyond_a_plausible_calibration_or_that_earn_nothing_are_no_rivals(baseline, gain_error):
    base, rows, f = baseline
    ctx0 = gain_error.steps[0].diagnosis.context
    for mu, why in ((1.5 * f, "a gain of 1.5 is a faulty rig"), (f + 0.2, "an offset of 0.2 too"),
                    (f, "no error: the gain earns nothing")):
        m = _with_noise(rows, mu, 13)
        ctx = dataclasses.replace(ctx0, settings=dataclasses.replace(ctx0.settings, y=m.mu), measurements=m)
        bic0 = validation.candidates.bic(float(np.sum(((m.mu - f) / SIGMA) ** 2)), m.n, 0, True)
        check = check_calibration([("(baseline)", (), f, 0, bic0)], ("(baseline)", (), bic0), ctx)
        assert not check.rivals, why
        assert check.text() == ""
    assert GAIN_RANGE[0] < 1 < GAIN_RANGE[1] and OFFSET_LIMIT > 0
    # the bands are the set search's: equally supported within EQUAL, an extra parameter earning more than STAY
    assert (validation.calibration.BAND, validation.calibration.EARN) == (validation.select.EQUAL,
                                                                          validation.select.STAY)


def test_an_effect_unlike_a_calibration_error_has_no_rival(baseline):
    """An adhesive peak over the speeds is nothing like a gain or an offset: the answer stands alone."""
    base, rows, f = baseline
    truth = base.with_effect(persson.effects.Adhesion(tau_f0=2e5, c=0.5, v_ref=0.03))
    m = _with_noise(rows, validation.predict(truth, rows).mu, 14)
    imp = validation.improve(base, m, candidates=["adhesion"])
    assert imp.added == ("adhesion",), imp.table_text()
    cal = imp.selection.calibration
    assert not cal.rivals and imp.final.calibration == ""
    assert all(c.delta_bic > validation.select.EQUAL for c in cal.fits)
    assert "calibration" not in imp.final.headline


def test_without_a_noise_estimate_a_rival_is_never_said_to_be_at_the_noise(baseline, gain_error):
    """Six rows, no mu_std, no replicates: the BIC still compares the fits, but nothing is at the noise level."""
    base, rows, f = baseline
    six = rows.subset(np.arange(0, 60, 10))
    m = validation.Measurements.from_arrays(slip=1.0, speed=six.speed, temperature=six.temperature,
                                            pressure=six.pressure, mu=1.2 * f[::10])
    dx = validation.diagnose(base, m, candidates=["strain_softening"])
    assert dx.verdict.verdict == "undetermined"
    assert all(not c.at_noise for c in dx.calibration.fits)
    assert "at the noise level" not in dx.calibration.text()


def test_a_temperature_offset_of_the_recorded_rows_is_found_and_named():
    """Rows measured with the rubber 2 K warmer than recorded (the truth on a converged grid, not the
    diagnosis's): the offset is found within 4 standard errors and named, and the gain and the zero offset are
    not what fits."""
    base = persson.Model(SURFACE, TREAD)
    truth = persson.Model(SURFACE, TREAD, grid=persson.GridSettings(q_per_decade=64, omega_per_decade=120,
                                                                    temperature_step=0.1))
    rows = _rows()
    warm = validation.Measurements.from_arrays(slip=1.0, speed=rows.speed, temperature=rows.temperature + 2.0,
                                               pressure=rows.pressure, mu=0.5)
    m = _with_noise(rows, validation.predict(truth, warm).mu, 15)
    dx = validation.diagnose(base, m, candidates=["strain_softening"])
    (t,) = [c for c in dx.calibration.fits if c.kind == "temperature" and c.on == "(baseline)"]
    assert abs(t.value - 2.0) < 4 * t.std and 0 < t.std < 0.2
    assert t.rival and t.at_noise and dx.calibration.rivals[0] is t
    assert "2.0 K warmer than recorded" in dx.verdict.calibration
    assert "temperature measurement" in dx.verdict.calibration
    # the loop checks it once, on its final answer
    imp = validation.improve(base, m, candidates=["strain_softening"])
    assert [(c.kind, c.on) for c in imp.selection.calibration.fits].count(("temperature", "(baseline)")) == 1
    assert [c.kind for c in imp.steps[0].diagnosis.calibration.fits].count("temperature") == 0


@pytest.mark.parametrize("temperatures, speeds, pressure, sigma", [
    ((-30.0, -20.0, -10.0), (0.1, 3.0), 5e4, SIGMA),      # glassy: cold, fast, light
    ((60.0, 80.0, 100.0), (1e-5, 1e-2), 8e5, 0.001),      # soft: hot, slow, heavy (mu 0.00-0.06)
], ids=["cold-fast-light", "hot-slow-heavy"])
@pytest.mark.parametrize("kind, error", [("temperature", 6.0), ("speed", 0.8)])
def test_the_errors_of_the_conditions_are_found_at_the_corners(temperatures, speeds, pressure, sigma, kind, error):
    """A 6 K offset or speeds 20 % below the recorded ones, where the WLF shift is steep (cold) and where the
    friction is nearly gone (hot, slow): the two chord steps still land within 4 standard errors (data from a
    converged grid)."""
    base = persson.Model(SURFACE, TREAD)
    truth = persson.Model(SURFACE, TREAD, grid=persson.GridSettings(q_per_decade=64, omega_per_decade=120,
                                                                    temperature_step=0.1))
    v = np.geomspace(*speeds, 10)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, 3), temperature=np.repeat(temperatures, 10),
                                               pressure=pressure, mu=0.5, mu_std=sigma)
    warm = validation.Measurements.from_arrays(
        slip=1.0, speed=rows.speed * (error if kind == "speed" else 1.0),
        temperature=rows.temperature + (error if kind == "temperature" else 0.0), pressure=pressure, mu=0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mu = np.clip(validation.predict(truth, warm).mu + np.random.default_rng(1).normal(0.0, sigma, rows.n), 0, None)
        dx = validation.diagnose(base, rows.with_mu(mu, mu_std=np.full(rows.n, sigma)), candidates=["strain_softening"])
    (t,) = [c for c in dx.calibration.fits if c.kind == kind and c.on == "(baseline)"]
    assert abs(t.value - error) < 4 * t.std and t.rival and t.at_noise


def test_a_speed_error_of_the_rig_is_found_and_named():
    """Rows whose true speeds are 20 % above the recorded ones (a wheel's rolling radius or an encoder off; the
    truth on a converged grid): the speed factor is found within 4 standard errors, rivals strain softening at the
    noise level and fits best. Through the WLF shift a temperature offset of about -0.9 K moves the rows almost as a
    speed factor does (the shift per K changes little between 10 and 40 C), so it is named beside it."""
    base = persson.Model(SURFACE, TREAD)
    truth = persson.Model(SURFACE, TREAD, grid=persson.GridSettings(q_per_decade=64, omega_per_decade=120,
                                                                    temperature_step=0.1))
    rows = _rows()
    fast = dataclasses.replace(rows, speed=1.2 * rows.speed)
    m = _with_noise(rows, validation.predict(truth, fast).mu, 16)
    dx = validation.diagnose(base, m, candidates=["strain_softening"])
    (v,) = [c for c in dx.calibration.fits if c.kind == "speed" and c.on == "(baseline)"]
    (t,) = [c for c in dx.calibration.fits if c.kind == "temperature" and c.on == "(baseline)"]
    assert abs(v.value - 1.2) < 4 * v.std and 0 < v.std < 0.05
    assert v.rival and v.at_noise and dx.calibration.rivals[0] is v
    assert v.bic < t.bic and t.rival and t.value < 0
    assert "also (baseline) with the rubber" in dx.verdict.calibration
    assert "speeds" in dx.verdict.calibration and "higher than recorded" in dx.verdict.calibration
    assert "speed measurement" in dx.verdict.calibration
    assert dx.as_dict()["calibration"]["fits"][0]["kind"] == "speed"


def test_the_errors_of_the_conditions_are_fitted_on_the_sets_one_effect_short_of_the_answer(baseline):
    """Against an answer of two effects, the temperature and speed errors are fitted on the baseline and on each
    set that lacks one of the two (there they may replace it), not on sets that lack both or are not subsets. The
    sets here are stand-ins (the baseline model under other labels), enough to follow which are used."""
    base, rows, f = baseline
    m = _with_noise(rows, validation.predict(base, dataclasses.replace(rows, speed=0.85 * rows.speed)).mu, 17)
    dx = validation.diagnose(base, m, candidates=["strain_softening"])
    ctx = dx.context
    y, w = ctx.settings.y, ctx.settings.w
    b = validation.candidates.bic(float(np.sum((w * (y - f)) ** 2)), rows.n, 0, True)
    sets = [("(baseline)", (), f, 0, b), ("adhesion", ("adhesion",), f, 0, b), ("wet", ("wet",), f, 0, b)]
    conditions = [(label, effects, base, None, 0, b) for label, effects, *_ in sets]
    check = check_calibration(sets, ("adhesion + microtexture", ("adhesion", "microtexture"), b - 50.0), ctx,
                              conditions=conditions)
    on = sorted((c.kind, c.on) for c in check.fits if c.kind in ("temperature", "speed"))
    assert on == [("speed", "adhesion"), ("temperature", "adhesion")]
    check = check_calibration(sets, ("adhesion + microtexture", ("adhesion", "microtexture"), b - 50.0), ctx,
                              baseline=(base, None, 0, b), conditions=conditions)
    (v,) = [c for c in check.fits if c.kind == "speed" and c.on == "adhesion"]
    # the baseline is exact here, so the chord steps land on the factor the rows were made with
    assert abs(v.value - 0.85) < 4 * v.std and v.effects == ("adhesion",)
    assert sorted(c.on for c in check.fits if c.kind == "speed") == ["(baseline)", "adhesion"]


def test_a_gain_of_one_device_among_two_is_found_by_a_gain_per_device(baseline):
    """Rows from two rigs, the warmest temperature measured on rig B only, whose mu reads 10 % high: to a model
    the excess looks like friction that rises with temperature. One gain for all rows cannot fit it; a gain per
    device (block-diagonal least squares, checked against numpy's) does, at the noise level, and is named."""
    base, rows, f = baseline
    device = np.where(rows.temperature > 30.0, "rig B", "rig A")
    m = _with_noise(rows, np.where(device == "rig B", 1.10, 1.0) * f, 18)
    m = dataclasses.replace(m, device=tuple(device))
    dx = validation.diagnose(base, m, candidates=["strain_softening"])
    (g,) = [c for c in dx.calibration.fits if c.kind == "device_gains" and c.on == "(baseline)"]
    (one,) = [c for c in dx.calibration.fits if c.kind == "gain" and c.on == "(baseline)"]
    gains = {d: (v, sd) for d, v, sd in g.per_device}
    for rig, true in (("rig A", 1.0), ("rig B", 1.10)):
        assert abs(gains[rig][0] - true) < 4 * gains[rig][1]
    assert g.value == gains["rig B"][0] and g.std == gains["rig B"][1]
    assert g.rival and g.at_noise and dx.calibration.rivals[0] is g and g.bic < one.bic - 10
    assert "device rig B reading" in dx.verdict.calibration and "each device's calibration" in dx.verdict.calibration
    # the same numbers from numpy: one column per device (f on its rows, 0 elsewhere), weights 1 / mu_std
    X = np.column_stack([np.where(device == d, f, 0.0) for d in ("rig A", "rig B")]) / SIGMA
    coef, res, *_ = np.linalg.lstsq(X, m.mu / SIGMA, rcond=None)
    cov = np.linalg.inv(X.T @ X)
    assert np.allclose([gains["rig A"][0], gains["rig B"][0]], coef, rtol=1e-10)
    assert np.allclose([gains["rig A"][1], gains["rig B"][1]], np.sqrt(np.diag(cov)) * max(1.0, math.sqrt(
        res[0] / (rows.n - 2))), rtol=1e-8)
    assert g.bic == pytest.approx(validation.candidates.bic(float(res[0]), rows.n, 2, True))
    data = dx.as_dict()["calibration"]["fits"][0]
    assert data["kind"] == "device_gains" and [d["device"] for d in data["per_device"]] == ["rig A", "rig B"]


def test_rows_of_one_device_get_no_gain_per_device(baseline):
    base, rows, f = baseline
    dx = validation.diagnose(base, _with_noise(rows, 1.05 * f, 19), candidates=["strain_softening"])
    assert not [c for c in dx.calibration.fits if c.kind == "device_gains" and c.on == "(baseline)"]


def _slip_rows(sigma=SIGMA):
    """Two slip sweeps (10 and 30 C, 3 m/s, 0.3 MPa) of 12 slips from 0.005 to 0.9, and 10 sliding speeds at each
    temperature."""
    slip = np.geomspace(0.005, 0.9, 12)
    v = np.geomspace(1e-3, 1.0, 10)
    n_s, n_v = slip.size, v.size
    return validation.Measurements.from_arrays(
        slip=np.concatenate([slip, slip, np.ones(2 * n_v)]),
        speed=np.concatenate([np.full(2 * n_s, 3.0), v, v]),
        temperature=np.concatenate([np.full(n_s, 10.0), np.full(n_s, 30.0), np.full(n_v, 10.0), np.full(n_v, 30.0)]),
        pressure=3e5, mu=0.5, mu_std=sigma,
        series=["s10"] * n_s + ["s30"] * n_s + ["v10"] * n_v + ["v30"] * n_v,
        contact=persson.slip.Contact(length=0.02, width=0.01, stiffness=3e9))


def test_a_slip_offset_of_the_rig_is_found_and_named():
    """Slip sweeps whose true slip ratios are 0.01 above the recorded ones (a wheel's effective rolling radius off;
    the truth on a converged grid): at small slip mu rises steeply, so the baseline misses the noise; the offset is
    found within 4 standard errors (the secant steps follow the curvature of mu(s)) and named at the noise level."""
    base = persson.Model(SURFACE, TREAD)
    truth = persson.Model(SURFACE, TREAD, grid=persson.GridSettings(q_per_decade=64, omega_per_decade=120))
    rows = _slip_rows()
    shifted = dataclasses.replace(rows, slip=np.where(rows.slip < 1, rows.slip + 0.01, 1.0))
    m = _with_noise(rows, validation.predict(truth, shifted).mu, 20)
    dx = validation.diagnose(base, m, candidates=["strain_softening"])
    fits = [c for c in dx.calibration.fits if c.kind == "slip"]
    assert fits and (best := min(fits, key=lambda c: c.bic)) is dx.calibration.rivals[0]
    assert abs(best.value - 0.01) < 4 * best.std and 0 < best.std < 0.003 and best.at_noise
    assert "slip ratios" in dx.verdict.calibration and "slip measurement" in dx.verdict.calibration


def test_on_top_of_the_answer_a_calibration_error_must_reach_the_noise():
    """The same slip offset with a misfit no error of the rig makes (a wave in log speed on the sliding rows): the
    offset fitted on top of what the diagnosis names still earns its parameter, but leaves a residual above the
    noise, so it is not named as what the answer leaves."""
    base = persson.Model(SURFACE, TREAD)
    truth = persson.Model(SURFACE, TREAD, grid=persson.GridSettings(q_per_decade=64, omega_per_decade=120))
    rows = _slip_rows()
    shifted = dataclasses.replace(rows, slip=np.where(rows.slip < 1, rows.slip + 0.01, 1.0))
    wave = np.where(rows.slip < 1, 0.0, 0.03 * np.sin(2.0 * np.log10(rows.speed)))
    m = _with_noise(rows, validation.predict(truth, shifted).mu + wave, 21)
    dx = validation.diagnose(base, m, candidates=["strain_softening"])
    on_answer = [c for c in dx.calibration.fits if set(c.effects) == set(dx.calibration.answer_effects)]
    assert any(c.gain_over_set > 10 for c in on_answer)
    assert not any(c.rival for c in on_answer) and all(not c.at_noise for c in on_answer)


def test_an_error_partly_taken_up_by_a_fitted_parameter_is_found_by_the_joint_step():
    """A zero offset of the friction force (+0.04 at p_ref, as 1/p) with the adhesion's shear stress fitted: the
    refit baseline's tau_f0 takes up part of the offset, and the offset alone on top of it comes out at 0.01, 400
    BIC units worse than the answer. Refitted together with tau_f0 (one Gauss-Newton step, checked by a
    prediction) it is found within 4 standard errors, at the noise level, and named (truth on a converged grid)."""
    from persson import effects as fx

    truth = persson.Model(SURFACE, TREAD, effects=[fx.Adhesion(tau_f0=1.0e6, c=0.1, v_ref=1e-2)],
                          grid=persson.GridSettings(q_per_decade=64, omega_per_decade=120))
    base = persson.Model(SURFACE, TREAD, effects=[fx.Adhesion(tau_f0=1.5e6, c=0.1, v_ref=1e-2)])
    rows = _rows()
    p_ref = float(np.exp(np.mean(np.log(rows.pressure))))
    m = _with_noise(rows, validation.predict(truth, rows).mu + 0.04 * p_ref / rows.pressure, 22)
    dx = validation.diagnose(base, m, candidates=["strain_softening"], fit=("adhesion.tau_f0",))
    (off,) = [c for c in dx.calibration.fits if c.kind == "offset" and c.on == "(baseline)"]
    assert off.joint and off.rival and off.at_noise and dx.calibration.rivals[0] is off
    assert abs(off.value - 0.04) < 4 * off.std < 0.01
    assert dx.as_dict()["calibration"]["fits"][0]["joint"] is True
    # the same check without the joint step (the baseline's parameters held): far off, and no rival
    b = dx.baseline
    alone = check_calibration([("(baseline)", (), b.predicted, b.n_params, b.bic)],
                              (dx.calibration.answer, dx.calibration.answer_effects, dx.calibration.answer_bic),
                              dx.context)
    (held,) = [c for c in alone.fits if c.kind == "offset"]
    assert not held.joint and not held.rival and abs(held.value - 0.04) > 10 * held.std


def test_a_temperature_offset_is_refitted_with_the_fitted_shear_stress():
    """Rows 3 K warmer than recorded with the adhesion's shear stress fitted: the temperature offset and tau_f0
    stepped together (the offset's own secant steps first) land within 4 standard errors of 3 K, at the noise
    level (truth on a converged grid). With tau_f0 held at its refit value the offset comes out at 1.9 +- 0.19 K,
    above the noise, and nothing is named."""
    from persson import effects as fx

    truth = persson.Model(SURFACE, TREAD, effects=[fx.Adhesion(tau_f0=1.0e6, c=0.1, v_ref=1e-2)],
                          grid=persson.GridSettings(q_per_decade=64, omega_per_decade=120, temperature_step=0.1))
    base = persson.Model(SURFACE, TREAD, effects=[fx.Adhesion(tau_f0=1.5e6, c=0.1, v_ref=1e-2)])
    rows = _rows()
    warm = dataclasses.replace(rows, temperature=rows.temperature + 3.0)
    m = _with_noise(rows, validation.predict(truth, warm).mu, 24)
    dx = validation.diagnose(base, m, candidates=["strain_softening"], fit=("adhesion.tau_f0",))
    (t,) = [c for c in dx.calibration.fits if c.kind == "temperature" and c.on == "(baseline)"]
    assert t.joint and t.rival and t.at_noise and abs(t.value - 3.0) < 4 * t.std < 0.5


@pytest.mark.parametrize("temperatures, speed, pressure, sigma", [
    ((-30.0, -20.0), 20.0, 5e4, SIGMA),       # glassy: cold, fast, light (mu 0.03-0.59)
    ((60.0, 80.0), 0.1, 8e5, 0.001),          # soft: hot, slow, heavy (mu 0.01-0.13)
], ids=["cold-fast-light", "hot-slow-heavy"])
def test_the_slip_offset_is_found_at_the_corners(temperatures, speed, pressure, sigma):
    """Slip sweeps 0.01 above the recorded slip where the modulus is glassy and where it is soft: the secant steps
    land within 4 standard errors of 0.01, at the noise level (truth on a converged grid)."""
    base = persson.Model(SURFACE, TREAD)
    truth = persson.Model(SURFACE, TREAD, grid=persson.GridSettings(q_per_decade=64, omega_per_decade=120))
    slip = np.geomspace(0.005, 0.9, 12)
    rows = validation.Measurements.from_arrays(
        slip=np.concatenate([slip, slip]), speed=speed, temperature=np.repeat(temperatures, 12), pressure=pressure,
        mu=0.5, mu_std=sigma, series=["a"] * 12 + ["b"] * 12,
        contact=persson.slip.Contact(length=0.02, width=0.01, stiffness=3e9))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mu = validation.predict(truth, dataclasses.replace(rows, slip=rows.slip + 0.01)).mu
        mu = np.clip(mu + np.random.default_rng(3).normal(0.0, sigma, rows.n), 0, None)
        dx = validation.diagnose(base, rows.with_mu(mu, mu_std=np.full(rows.n, sigma)), candidates=["strain_softening"])
    (s,) = [c for c in dx.calibration.fits if c.kind == "slip" and c.on == "(baseline)"]
    assert abs(s.value - 0.01) < 4 * s.std and s.rival and s.at_noise


@pytest.mark.parametrize("temperatures, speeds, pressure, sigma, offset", [
    ((-30.0, -20.0, -10.0), (0.1, 3.0), 5e4, SIGMA, 0.02),     # glassy: cold, fast, light
    ((60.0, 80.0, 100.0), (1e-5, 1e-2), 8e5, 0.001, 0.005),    # soft: hot, slow, heavy
], ids=["cold-fast-light", "hot-slow-heavy"])
def test_the_joint_step_finds_a_zero_offset_at_the_corners(temperatures, speeds, pressure, sigma, offset):
    """A zero offset (as 1/p over two pressures) with the adhesion's shear stress fitted, where the modulus is
    glassy and where it is soft: refitted together with tau_f0, the offset on the baseline lands within 4 standard
    errors of the truth, at the noise level (truth on a converged grid)."""
    from persson import effects as fx

    truth = persson.Model(SURFACE, TREAD, effects=[fx.Adhesion(tau_f0=1.0e6, c=0.1, v_ref=1e-2)],
                          grid=persson.GridSettings(q_per_decade=64, omega_per_decade=120))
    base = persson.Model(SURFACE, TREAD, effects=[fx.Adhesion(tau_f0=1.5e6, c=0.1, v_ref=1e-2)])
    v = np.geomspace(*speeds, 10)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, 6),
                                               temperature=np.tile(np.repeat(temperatures, 10), 2),
                                               pressure=np.repeat([pressure, 2 * pressure], 30), mu=0.5, mu_std=sigma)
    p_ref = float(np.exp(np.mean(np.log(rows.pressure))))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mu = (validation.predict(truth, rows).mu + offset * p_ref / rows.pressure
              + np.random.default_rng(4).normal(0.0, sigma, rows.n))
        dx = validation.diagnose(base, rows.with_mu(mu, mu_std=np.full(rows.n, sigma)), candidates=["strain_softening"],
                                 fit=("adhesion.tau_f0",))
    (off,) = [c for c in dx.calibration.fits if c.kind == "offset" and c.on == "(baseline)"]
    assert off.joint and off.rival and off.at_noise and abs(off.value - offset) < 4 * off.std
