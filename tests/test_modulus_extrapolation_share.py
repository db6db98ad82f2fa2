"""How much of the friction rests on a master curve's extrapolation.

A DMA master curve covers a finite band of reduced frequencies; at road speeds the small scales excite the rubber
far above it (q v a_T up to 1e9 rad/s and more), where the modulus is the curve's extrapolation. The result says
which share of mu_hysteresis comes from there: each scale's angular band omega = q v cos(phi), weighted by
cos(phi) as in Persson's loss integral, outside the measured band.
"""

import math
import warnings

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.errors import PhysicsWarning

ROAD = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 0.01, q1=1e6, hrms=0.2e-3)
TRUTH = materials.example_tread()


def master(f_lo_Hz, f_hi_Hz):
    """The example compound's 20 C curve measured from f_lo to f_hi (Hz), with its WLF law."""
    f = np.logspace(math.log10(f_lo_Hz), math.log10(f_hi_Hz), 25)
    E = TRUTH.E(2 * math.pi * f, 20.0)
    return materials.MasterCurve.from_table({"f_Hz": f, "E_storage_Pa": E.real, "E_loss_Pa": E.imag}, TRUTH.wlf)


def friction(material, speeds, T=20.0, effects=(), pressure=0.3e6):
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        r = persson.Model(ROAD, material, effects=list(effects), grid=persson.GridSettings(q_per_decade=12)).friction(
            np.asarray(speeds, dtype=float), temperature=T, pressure=pressure)
    return r, [w for w in rec if issubclass(w.category, PhysicsWarning)]


def brute_force_share(r, material, i):
    """The share by direct sampling of the angle at every node (10^5 angles, midpoint rule), independent of the
    closed form: the cos(phi)-weighted fraction of each scale's band outside the curve, averaged over the ends of
    each interval of the engine's cumulative friction."""
    lo, hi = material.frequency_range
    phi = (np.arange(100_000) + 0.5) * (math.pi / 2) / 100_000
    w = np.cos(phi) * (math.pi / 2) / 100_000
    a_T = 10.0 ** np.asarray(material.log10_aT(r.temperature_q[i]), dtype=float)
    frac = np.array([np.sum(w[(r.speed[i] * q * np.cos(phi) * a > hi) | (r.speed[i] * q * np.cos(phi) * a < lo)])
                     for q, a in zip(r.q, a_T)])
    cum = r.mu_cumulative[i]
    return float(np.sum(np.diff(cum) * 0.5 * (frac[1:] + frac[:-1])) / cum[-1])


@pytest.mark.parametrize("data_Hz, T, speeds, effects, pressure", [
    ((1e-1, 1e3), 20.0, [1e-3, 1e-1, 1.0], (), 0.3e6),                                   # the middle
    ((1e-3, 1e9), -20.0, [3.0, 30.0], (), 0.02e6),          # glassy: cold, fast, low pressure (above the data)
    ((1e-3, 1e11), -20.0, [3.0, 30.0], (), 0.02e6),
    ((3e-5, 1e3), 80.0, [1e-6, 1e-4], (), 0.3e6),                       # soft: hot and slow (below the data)
    ((1e-1, 1e3), 20.0, [0.3, 3.0], (persson.effects.FlashTemperature(),), 0.3e6),  # each scale at its flash T
])
def test_share_matches_a_direct_sampling_of_the_angular_band(data_Hz, T, speeds, effects, pressure):
    m = master(*data_Hz)
    r, _ = friction(m, speeds, T=T, effects=effects, pressure=pressure)
    share = r.modulus_extrapolated_share
    assert 0.0 < np.max(share) < 1.0          # partly extrapolated: the corner is not just all or nothing
    for i in range(len(speeds)):
        assert share[i] == pytest.approx(brute_force_share(r, m, i), abs=2e-4)


def test_a_narrow_curve_at_road_speed_warns_and_says_which_share():
    m = master(1e-1, 1e3)
    r, warned = friction(m, [1e-4, 1e-2, 1.0])
    share = r.modulus_extrapolated_share
    # at road speed the small scales leave the data at its top (slow, the large ones fall below its bottom)
    assert share[2] > 0.5 and share[2] > 5 * max(share[0], share[1])
    assert [n.kind for n in r.notes if "outside the measured master curve" in n] == ["extrapolated"]
    assert any("outside the measured master curve" in str(w.message) for w in warned)
    assert "modulus_extrapolated_share" in r.as_table()
    # warmer rubber shifts the same scales to lower reduced frequencies, back into the data
    hot, _ = friction(m, [1.0], T=60.0)
    assert hot.modulus_extrapolated_share[0] < share[2]


def test_a_curve_that_covers_every_excited_frequency_says_nothing():
    r, warned = friction(master(1e-8, 1e14), [1e-4, 1.0])
    assert np.all(r.modulus_extrapolated_share < 1e-4)
    assert not any("master curve" in n for n in r.notes) and not warned


def test_a_compound_without_a_measured_range_has_no_share():
    r, _ = friction(TRUTH, [1.0])
    assert r.modulus_extrapolated_share is None and "modulus_extrapolated_share" not in r.as_table()


def test_a_comparison_names_the_rows_that_rest_on_the_extrapolation():
    import validation

    m = master(1e-1, 1e3)
    speeds = np.array([1e-4, 1e-2, 1.0, 3.0])
    rows = validation.Measurements.from_arrays(slip=np.ones(4), speed=speeds, temperature=np.full(4, 20.0),
                                               pressure=np.full(4, 0.3e6), mu=np.full(4, 0.5))
    model = persson.Model(ROAD, m, grid=persson.GridSettings(q_per_decade=12))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)
        cmp = validation.compare(model, rows)
        direct = model.friction(speeds, temperature=20.0, pressure=0.3e6)
    np.testing.assert_allclose(cmp.rows_table()["modulus_extrapolated_share"], direct.modulus_extrapolated_share,
                               rtol=1e-12)
    assert list(cmp.rows_mostly_extrapolated()) == [2, 3]
    assert "2 of 4 rows rest for more than half" in cmp.summary()
    from validation.report import render_report

    html = render_report([cmp], title="t")
    assert "Compound data: 2 of 4 rows rest for more than half" in html
    assert cmp.as_dict()["rows_mostly_extrapolated"] == 2
    # a compound without a measured range: nothing to say, and no column
    plain = validation.compare(persson.Model(ROAD, TRUTH, grid=persson.GridSettings(q_per_decade=12)), rows)
    assert "modulus_extrapolated_share" not in plain.rows_table()
    assert plain.as_dict()["rows_mostly_extrapolated"] is None


def test_a_diagnosis_cautions_when_the_misfit_sits_where_the_modulus_is_extrapolated():
    """Rows made with the compound itself, modelled with its curve measured at 0.1-1000 Hz only: the fast rows rest
    on the extrapolation and carry the misfit, which no candidate effect is built to remove."""
    import validation

    speeds = np.geomspace(1e-4, 3.0, 8)
    T = np.repeat([20.0, 40.0], speeds.size)
    v = np.tile(speeds, 2)
    grid = persson.GridSettings(q_per_decade=12)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PhysicsWarning)
        truth = persson.Model(ROAD, TRUTH, grid=grid).friction(v, temperature=T, pressure=0.3e6).mu
        rows = validation.Measurements.from_arrays(slip=np.ones(v.size), speed=v, temperature=T,
                                                   pressure=np.full(v.size, 0.3e6), mu=truth,
                                                   mu_std=np.full(v.size, 0.01))
        dx = validation.diagnose(persson.Model(ROAD, master(1e-1, 1e3), grid=grid), rows, candidates=["adhesion"])
    share = dx.modulus_extrapolated_share
    k = int(np.sum(share > 0.5))
    assert k >= 2
    r2 = dx.baseline.residual ** 2
    assert np.sum(r2[share > 0.5]) / np.sum(r2) >= 0.5
    assert f"Compound data: {k} of {v.size} rows rest for more than half" in dx.explanation
    assert "rather than an effect of the list" in dx.explanation
    assert dx.as_dict()["baseline"]["rows_mostly_extrapolated"] == k


def test_rows_predicted_with_patch_heating_carry_the_share_at_their_sliding_point():
    """A wheel on the road with patch heating: each slip row's share is the engine's at the row's sliding point
    (s V, T0, sigma0) before the patch heats it, as for sliding rows; the heated patch lowers the rubber's reduced
    frequencies, so the share beyond the top of the data is at most that."""
    import validation
    from persson import effects as fx
    from persson.slip import Contact

    m = master(1e-1, 1e3)
    slips = np.array([0.02, 0.1, 0.3, 1.0, 0.05, 1.0])
    V = np.array([10.0, 10.0, 10.0, 10.0, 0.1, 0.1])
    rows = validation.Measurements.from_arrays(slip=slips, speed=V, temperature=np.full(6, 20.0),
                                               pressure=np.full(6, 0.3e6), mu=np.full(6, 0.5))
    grid = persson.GridSettings(q_per_decade=12)
    heating = fx.PatchHeating(points_per_decade=2, n_pressure=3, temperature_points_per_decade=2)
    model = persson.Model(ROAD, m, effects=[heating], grid=grid)
    contact = Contact(length=0.05, width=0.03, stiffness=2e8)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cmp = validation.compare(model, rows, contact)
        direct = persson.Model(ROAD, m, grid=grid).friction(slips * V, temperature=20.0, pressure=0.3e6)
    share = cmp.rows_table()["modulus_extrapolated_share"]
    np.testing.assert_allclose(share, direct.modulus_extrapolated_share, rtol=1e-12)
    assert share[3] > 0.5 > share[5]                      # 10 m/s sliding rests on the extrapolation, 0.1 m/s not
    assert 3 in cmp.rows_mostly_extrapolated()
    # a fit's predictions do not pay for it
    from validation.predict import Predictor

    assert Predictor(rows, contact).predict(model).modulus_extrapolated_share is None
