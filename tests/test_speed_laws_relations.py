"""Specification of the constants of the wet-road speed law from the road and the tyre (persson.slip.texture_laws)
and of the road and tyre columns of measurement files.

Independent references: synthetic surfaces drawn from known relations with known scatter, ordinary least squares
written out here (numpy.polyfit), and a Monte-Carlo draw of the regressions' constants and scatter against which the
linearised uncertainty of a predicted mu(V) is checked.
"""

import math

import numpy as np
import pytest

from persson import slip as ps
from persson.errors import InputError, PhysicsWarning
from validation import Measurements, read_measurements
from validation.errors import InputError as ValidationInputError

MPD = np.array([0.35, 0.5, 0.7, 1.0, 1.4, 1.9, 2.6, 3.2]) * 1e-3
BPN = np.array([42.0, 48.0, 55.0, 61.0, 67.0, 74.0, 80.0])


def test_speed_constant_from_macrotexture_per_device():
    rng = np.random.default_rng(11)
    truth = {"F1": (0.45, 1.60), "F13": (0.75, 1.35)}  # a, log10 b (b: Vs in m/s at MPD = 1 mm)
    mpd, vs, dev = [], [], []
    for d, (a, lb) in truth.items():
        mpd.append(MPD)
        vs.append(10 ** (lb + a * np.log10(MPD / 1e-3) + rng.normal(0, 0.03, MPD.size)))
        dev += [d] * MPD.size
    fits = ps.fit_vs_mpd_by_device(np.concatenate(mpd), np.concatenate(vs), dev)
    assert list(fits) == ["F1", "F13"]
    for d, (a, lb) in truth.items():
        f = fits[d]
        slope, icpt = np.polyfit(np.log10(MPD / 1e-3), np.log10(vs[list(truth).index(d)]), 1)
        assert f.params["a"] == pytest.approx(slope, rel=1e-10) and f.params["log10_b"] == pytest.approx(icpt)
        assert abs(f.params["a"] - a) < 4 * f.std["a"] and abs(f.params["log10_b"] - lb) < 4 * f.std["log10_b"]
        assert f.residual_std == pytest.approx(0.03, rel=0.6)
        assert f(1e-3) == pytest.approx(10 ** f.params["log10_b"])


def test_the_blank_tyre_slip_law_is_recovered_from_devices_of_several_slips():
    rng = np.random.default_rng(12)
    slip = np.array([0.14, 0.2, 0.3, 0.5, 0.86, 1.0])
    b_kmh = 10 ** (0.90 * np.log10(slip) + 2.07 + rng.normal(0, 0.02, slip.size))
    f = ps.fit_b_slip(slip, b_kmh / 3.6)
    assert abs(f.params["c"] - 0.90) < 4 * f.std["c"]
    assert abs(f.params["log10_b1"] - (2.07 - math.log10(3.6))) < 4 * f.std["log10_b1"]
    assert ps.BLANK_TIRE_SLIP_LAW(1.0) * 3.6 == pytest.approx(10**2.07)


def test_alpha_and_vs_against_water_over_tread_depth_saturate_at_one():
    rng = np.random.default_rng(13)
    r = np.array([0.1, 0.25, 0.4, 0.6, 0.8, 1.2, 2.0, 3.5, 5.0])
    alpha = 1.0 + 2.0 * np.minimum(r, 1.0) + rng.normal(0, 0.1, r.size)
    fa = ps.fit_water_ratio(r, alpha)
    assert abs(fa.params["y0"] - 1.0) < 4 * fa.std["y0"] and abs(fa.params["y_sat"] - 3.0) < 4 * fa.std["y_sat"]
    assert fa(10.0) == pytest.approx(fa.params["y_sat"]) and fa(0.0) == pytest.approx(fa.params["y0"])
    vs = 40.0 - 15.0 * np.minimum(r, 1.0) + rng.normal(0, 1.0, r.size)
    fv = ps.fit_water_ratio(r, vs, name="vs_water")
    assert fv.params["y0"] > fv.params["y_sat"]  # more water in the pattern: friction falls sooner
    assert ps.ALPHA_WATER_LAW(0.0) == 1.0 and ps.ALPHA_WATER_LAW(1.0) == 3.0 and ps.ALPHA_WATER_LAW(4.0) == 3.0
    with pytest.raises(InputError, match="below and above the saturation ratio"):
        ps.fit_water_ratio([1.5, 2.0, 3.0], [3.0, 3.1, 2.9])


@pytest.fixture(scope="module")
def relations():
    rng = np.random.default_rng(14)
    mu0 = 0.15 + 0.009 * BPN + rng.normal(0, 0.02, BPN.size)
    vs = 10 ** (1.45 + 0.55 * np.log10(MPD / 1e-3) + rng.normal(0, 0.04, MPD.size))
    r = np.array([0.1, 0.3, 0.5, 0.7, 0.9, 1.5, 3.0])
    return ps.WetRelations(mu0_bpn=ps.fit_mu0_bpn(BPN, mu0, device="F1"), vs_mpd=ps.fit_vs_mpd(MPD, vs, device="F1"),
                           alpha_water=ps.fit_water_ratio(r, 1 + 2 * np.minimum(r, 1) + rng.normal(0, 0.1, r.size)))


def test_predicted_curve_carries_the_uncertainty_of_the_regressions(relations):
    speed = np.array([2.0, 8.0, 15.0, 25.0])
    p = ps.predict_speed_curve(speed, relations, bpn=63.0, water_depth=1.0e-3, tread_depth=2.0e-3, mpd=1.2e-3,
                               mpd_std=0.05e-3)
    # the curve is the modified exponential with the constants the relations give
    mu0, vs, alpha = relations.mu0_bpn(63.0), relations.vs_mpd(1.2e-3), relations.alpha_water(0.5)
    assert p.mu0[0] == pytest.approx(mu0) and p.Vs[0] == pytest.approx(vs) and p.alpha[0] == pytest.approx(alpha)
    assert np.allclose(p.mu, mu0 * np.exp(-((speed / vs) ** alpha)), rtol=1e-12)
    # Monte Carlo: draw every regression's constants from its covariance, the surface's offsets from the scatter
    rng = np.random.default_rng(15)
    n = 20000
    draws = []
    for rel, x in ((relations.mu0_bpn, 63.0), (relations.vs_mpd, None), (relations.alpha_water, 0.5)):
        c = rng.multivariate_normal(rel.values, rel.covariance, n)
        off = rng.normal(0, rel.residual_std, n)
        if x is None:  # Vs at a drawn MPD
            m = rng.normal(1.2e-3, 0.05e-3, n)
            draws.append(10 ** (c[:, 0] * np.log10(m / 1e-3) + c[:, 1] + off))
        else:
            draws.append(np.einsum("ij,j->i", c, rel.design(x)) + off)
    mc = draws[0][:, None] * np.exp(-((speed[None, :] / draws[1][:, None]) ** draws[2][:, None]))
    assert np.allclose(p.std, mc.std(axis=0), rtol=0.12)  # linear propagation vs the full spread
    assert np.all(p.std_parameters < p.std) and np.all(p.std_parameters > 0)
    lo, hi = p.interval(2.0)
    assert np.all(lo < p.mu) and np.all(hi > p.mu)


def test_prediction_by_the_slip_route_and_its_refusals(relations):
    rel = ps.WetRelations(mu0_bpn=relations.mu0_bpn, mpd_exponent=(0.55, 0.05))
    p = ps.predict_speed_curve([5.0, 20.0], rel, bpn=60.0, water_depth=2e-3, tread_depth=0.0, mpd=0.8e-3, slip=0.86)
    assert p.Vs[0] == pytest.approx(ps.blank_tire_vs(0.8e-3, 0.86, 0.55)) and p.alpha[0] == 3.0  # blank tyre
    assert p.Vs[1] > 0  # the exponent's uncertainty reaches Vs
    with pytest.raises(InputError, match="millimetres"):  # a water depth of 2 read as metres
        ps.predict_speed_curve([5.0], rel, bpn=60.0, water_depth=2.0, tread_depth=0.0, mpd=0.8e-3, slip=0.86)
    with pytest.raises(InputError, match="BPN/100"):
        ps.predict_speed_curve([5.0], rel, bpn=0.6, water_depth=2e-3, tread_depth=0.0, mpd=0.8e-3, slip=0.86)
    with pytest.raises(InputError, match="vs_mpd"):
        ps.predict_speed_curve([5.0], rel, bpn=60.0, water_depth=2e-3, tread_depth=0.0, mpd=0.8e-3)
    with pytest.warns(PhysicsWarning, match="outside the fitted range"):
        far = ps.predict_speed_curve([5.0], relations, bpn=95.0, water_depth=1e-3, tread_depth=2e-3, mpd=1e-3)
    assert any("extrapolated" in n for n in far.notes)


def test_measurement_files_carry_water_tread_texture_bpn_and_device(tmp_path):
    head = "slip,speed_m_s,T_C,pressure_Pa,mu,water_depth_m,tread_depth_m,bpn,mpd_m,device\n"
    rows = ["1,5,20,2e5,0.62,0.001,0.002,63,0.0011,F1", "1,15,20,2e5,0.41,0.001,0.002,63,0.0011,F1"]
    path = tmp_path / "wet.csv"
    path.write_text(head + "\n".join(rows) + "\n")
    m = read_measurements(path)
    assert np.allclose(m.water_depth, 1e-3) and np.allclose(m.tread_depth, 2e-3) and np.allclose(m.bpn, 63)
    assert np.allclose(m.mpd, 1.1e-3) and m.device == ("F1", "F1")
    back = read_measurements(m.to_csv(tmp_path / "back.csv"))
    assert np.array_equal(back.water_depth, m.water_depth) and back.device == m.device
    assert m.subset([1]).device == ("F1",) and m.subset([1]).bpn.tolist() == [63.0]
    bad = head + rows[0] + "\n" + rows[1].replace("0.001,0.002", "2,0.002") + "\n"
    path.write_text(bad)
    with pytest.raises(ValidationInputError, match=r"line 3 .*'water_depth_m'.*millimetres"):
        read_measurements(path)
    path.write_text(head.replace(",device", "") + "1,5,20,2e5,0.62,0.001,0.002,0.63,0.0011\n")
    with pytest.raises(ValidationInputError, match="BPN/100"):
        read_measurements(path)
    path.write_text(head + rows[0] + "\n1,15,20,2e5,0.41,,0.002,63,0.0011,F1\n")
    with pytest.raises(ValidationInputError, match="every row"):
        read_measurements(path)
    plain = Measurements.from_arrays(slip=1.0, speed=[5.0, 10.0], temperature=20.0, pressure=2e5, mu=[0.6, 0.5])
    assert plain.water_depth is None and plain.device == () and "water_depth_m" not in plain.as_table()
    arr = Measurements.from_arrays(slip=1.0, speed=[5.0, 10.0], temperature=20.0, pressure=2e5, mu=[0.6, 0.5],
                                   water_depth=1e-3, device="F2")
    assert arr.water_depth.tolist() == [1e-3, 1e-3] and arr.device == ("F2", "F2")


def test_the_mpd_of_the_profiles_and_its_standard_error_feed_the_prediction(relations, monkeypatch):
    import surfaces

    per = (1.10e-3, 1.25e-3, 1.18e-3, 1.31e-3)
    fake = type("MPD", (), {"mpd": float(np.mean(per)), "per_profile": per, "profile_valid": (True,) * 4})()
    monkeypatch.setattr(surfaces, "mpd", lambda profiles: fake)  # surfaces.mpd itself is specified in its own tests
    kw = dict(bpn=63.0, water_depth=1e-3, tread_depth=2e-3)
    p = ps.predict_speed_curve([10.0], relations, profiles="scans.csv", **kw)
    q = ps.predict_speed_curve([10.0], relations, mpd=np.mean(per), mpd_std=np.std(per, ddof=1) / 2, **kw)
    assert p.mpd == q.mpd and p.mu == pytest.approx(q.mu) and p.std == pytest.approx(q.std)
    assert any("from 4 profiles" in n for n in p.notes)
    with pytest.raises(InputError, match="exactly one"):
        ps.predict_speed_curve([10.0], relations, profiles="scans.csv", mpd=1e-3, **kw)
