"""Specification of the tire-level curve laws and fits (persson.slip): Magic Formula, friction-speed laws.

Reference numbers are independent of the fitting code: synthetic curves from known parameters, the Magic
Formula's peak from its closed form (C arctan(X) = pi/2, i.e. Bs - E(Bs - arctan Bs) = tan(pi/(2C))), and the
PIARC / Do-Marsac-Mosset identity at alpha = 1, beta = 0.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from persson import slip as tire
from persson.errors import InputError


def mf_peak_slip(B, C, E):
    X = math.tan(math.pi / (2 * C))
    return brentq(lambda s: B * s - E * (B * s - math.atan(B * s)) - X, 1e-9, 10.0, xtol=1e-15)


TRUE_BCDE = dict(B=14.0, C=1.65, D=0.95, E=-0.5)
TRUE_SIMPLE = dict(a=0.9, b=1.7, c=11.0, d=0.05)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_magic_formula_recovers_known_parameters_from_noisy_curve(seed):
    rng = np.random.default_rng(seed)
    s = np.linspace(0.0, 1.0, 61)
    noise = 0.005
    y = tire.magic_formula(s, **TRUE_BCDE) + rng.normal(0, noise, s.size)
    f = tire.fit_magic_formula(s, y, sigma=noise)
    for name, true in TRUE_BCDE.items():
        assert abs(f[name] - true) < 4 * f.std(name), (name, f[name], f.std(name))
        assert f[name] == pytest.approx(true, rel={"B": 0.05, "E": 0.3}.get(name, 0.01))
    # characteristics: peak D at the closed-form slip; locked wheel mu(1)
    s_p = mf_peak_slip(TRUE_BCDE["B"], TRUE_BCDE["C"], TRUE_BCDE["E"])
    assert abs(f.peak_mu - TRUE_BCDE["D"]) < 4 * f.peak_mu_std
    assert abs(f.slip_at_peak - s_p) < 4 * f.slip_at_peak_std
    locked = tire.magic_formula(1.0, **TRUE_BCDE)
    assert abs(f.locked_mu - locked) < 4 * f.locked_mu_std
    assert 0 < f.peak_mu_std < 0.01 and 0 < f.slip_at_peak_std < 0.01 and 0 < f.locked_mu_std < 0.01
    assert f.rms == pytest.approx(noise, rel=0.3)
    assert f.dof == s.size - 4
    assert tire.MAGIC_FORMULA in f.citations
    mf = f.formula
    assert isinstance(mf, tire.MagicFormula) and mf.peak_mu == pytest.approx(f.peak_mu)


@pytest.mark.parametrize("seed", [3, 4])
def test_simple_magic_formula_recovers_known_parameters(seed):
    rng = np.random.default_rng(seed)
    s = np.linspace(0.0, 1.0, 61)
    y = tire.magic_formula_simple(s, **TRUE_SIMPLE) + rng.normal(0, 0.005, s.size)
    f = tire.fit_magic_formula(s, y, form="simple")  # covariance scaled by the residuals
    for name, true in TRUE_SIMPLE.items():
        assert abs(f[name] - true) < 4 * f.std(name), (name, f[name], f.std(name))
    a, b, c, d = (TRUE_SIMPLE[k] for k in "abcd")
    s_p = math.tan(math.pi / (2 * b)) / c  # b atan(c s) = pi/2
    assert abs(f.peak_mu - (a + d)) < 4 * f.peak_mu_std
    assert abs(f.slip_at_peak - s_p) < 4 * f.slip_at_peak_std
    assert f.formula.initial_slope == pytest.approx(f["a"] * f["b"] * f["c"])


def test_reported_uncertainty_matches_scatter():
    """With absolute sigma, the reported standard uncertainty of D equals the scatter over noise realisations."""
    s = np.linspace(0.0, 1.0, 41)
    clean = tire.magic_formula(s, **TRUE_BCDE)
    D, stds = [], []
    for seed in range(40):
        y = clean + np.random.default_rng(100 + seed).normal(0, 0.01, s.size)
        f = tire.fit_magic_formula(s, y, sigma=0.01)
        D.append(f["D"])
        stds.append(f.std("D"))
    ratio = np.std(D, ddof=1) / np.mean(stds)
    assert 0.6 < ratio < 1.5, ratio


def test_fixed_parameters_and_bad_fits():
    s = np.linspace(0, 1, 30)
    y = tire.magic_formula(s, 10.0, 1.6, 0.9, 0.0)
    f = tire.fit_magic_formula(s, y, fixed={"E": 0.0})
    assert f["E"] == 0.0 and f.std("E") == 0.0 and f.fixed == ("E",)
    assert f["B"] == pytest.approx(10.0, rel=1e-6) and f["C"] == pytest.approx(1.6, rel=1e-6)
    with pytest.raises(InputError, match="slip"):
        tire.fit_magic_formula(s * 2, y)
    with pytest.raises(InputError, match="equal lengths"):
        tire.fit_magic_formula(s, y[:-1])
    with pytest.raises(InputError, match="form"):
        tire.fit_magic_formula(s, y, form="ABC")
    with pytest.raises(InputError, match="fixed"):
        tire.fit_magic_formula(s, y, fixed={"Q": 1.0})
    with pytest.raises(InputError, match="sigma"):
        tire.fit_magic_formula(s, y, sigma=-0.1)
    with pytest.raises(InputError, match="free parameters"):
        tire.fit_magic_formula(s[:4], y[:4])
    with pytest.raises(InputError, match="parameter"):
        f.std("Z")


def test_three_point_identification():
    true = tire.MagicFormula(B=12.0, C=1.7, D=0.95)
    pts = np.array([0.03, 0.12, 1.0])
    m = tire.magic_formula_from_points(pts, true(pts))
    assert (m.B, m.C, m.D) == pytest.approx((12.0, 1.7, 0.95), rel=1e-7)
    assert m.peak_mu == pytest.approx(0.95, rel=1e-9)
    assert m.slip_at_peak == pytest.approx(mf_peak_slip(12.0, 1.7, 0.0), rel=1e-6)
    assert m.locked_mu == pytest.approx(true(1.0), rel=1e-9)
    # with a given curvature factor E
    true_e = tire.MagicFormula(B=9.0, C=1.5, D=0.8, E=-0.4)
    pts = np.array([0.05, 0.2, 0.9])
    m = tire.magic_formula_from_points(pts, true_e(pts), E=-0.4)
    assert (m.B, m.C, m.D) == pytest.approx((9.0, 1.5, 0.8), rel=1e-7)
    with pytest.raises(InputError, match="three"):
        tire.magic_formula_from_points([0.1, 0.2], [0.5, 0.6])
    with pytest.raises(InputError, match="differ"):
        tire.magic_formula_from_points([0.1, 0.1, 1.0], [0.5, 0.5, 0.4])
    with pytest.raises(InputError, match="slip"):
        tire.magic_formula_from_points([0.0, 0.1, 1.0], [0.1, 0.5, 0.4])


# Pacejka's typical shapes (dry and wet tarmac, tire.PACEJKA_TYPICAL) and corners away from them: early and late
# peaks, C from 1.2 to 2.3, E from -2 to 1 (0.97 is the slowly falling dry curve where a single start stopped at
# B, C, D, E = 14.47, 1.316, 1.003, 0.042)
MF_CORNERS = [(10.0, 1.9, 1.0, 0.97), (12.0, 2.3, 0.82, 1.0), (25.0, 1.3, 1.1, 0.3), (6.0, 1.45, 0.7, -2.0),
              (40.0, 1.6, 1.2, 0.9), (18.0, 1.2, 1.0, -1.0)]


@pytest.mark.parametrize("B, C, D, E", MF_CORNERS)
def test_noise_free_magic_formula_is_recovered_exactly(B, C, D, E):
    s = np.linspace(0.0, 1.0, 26)
    f = tire.fit_magic_formula(s, tire.magic_formula(s, B, C, D, E))
    np.testing.assert_allclose(f.values, [B, C, D, E], rtol=1e-6)
    assert f.rms < 1e-9
    assert f.slip_at_peak == pytest.approx(mf_peak_slip(B, C, E), abs=1e-6)


def test_literature_shapes_are_pacejkas_typical_coefficients():
    assert tire.PACEJKA_TYPICAL["dry tarmac"] == (10.0, 1.9, 1.0, 0.97)
    assert tire.PACEJKA_TYPICAL["wet tarmac"] == (12.0, 2.3, 0.82, 1.0)


def test_peak_of_tabulated_curve():
    s = np.linspace(0, 1, 101)
    mu = tire.magic_formula(s, 14.0, 1.65, 0.95, -0.5)
    pm, sp = tire.peak(s, mu)
    assert pm == pytest.approx(0.95, abs=2e-4)
    assert sp == pytest.approx(mf_peak_slip(14.0, 1.65, -0.5), abs=2e-3)
    # several curves at once, slip along axis 0
    many = np.stack([mu, 0.5 * mu], axis=1)
    pm2, sp2 = tire.peak(s[:, None], many, axis=0)
    assert pm2 == pytest.approx([pm, 0.5 * pm]) and sp2 == pytest.approx([sp, sp])
    # maximum at the end: returned as it is
    assert tire.peak(s, s) == (1.0, 1.0)


def test_do_marsac_mosset_with_alpha_1_beta_0_is_piarc():
    V = np.linspace(0.5, 40.0, 50)
    assert np.array_equal(tire.do_marsac_mosset(V, 0.8, 20.0, 1.0, 0.0), tire.piarc(V, 0.8, 20.0))
    # the IFI form in km/h is the same law
    S = V * 3.6
    F60, Sp_kmh = 0.35, 90.0
    assert np.allclose(tire.piarc_ifi(S, F60, Sp_kmh), tire.piarc(V, F60 * math.exp(60 / Sp_kmh), Sp_kmh / 3.6))
    # and the fits agree: Do with alpha = 1, beta = 0 held fixed is the PIARC fit
    rng = np.random.default_rng(7)
    mu = tire.piarc(V, 0.8, 20.0) + rng.normal(0, 0.005, V.size)
    p = tire.fit_piarc(V, mu)
    d = tire.fit_do_marsac_mosset(V, mu, fixed={"alpha": 1.0, "beta": 0.0})
    assert d["mu0"] == pytest.approx(p["mu0"], rel=1e-7) and d["Vs"] == pytest.approx(p["Sp"], rel=1e-7)
    assert d.std("mu0") == pytest.approx(p.std("mu0"), rel=1e-4) and d.std("Vs") == pytest.approx(p.std("Sp"), rel=1e-4)
    assert abs(p["mu0"] - 0.8) < 4 * p.std("mu0") and abs(p["Sp"] - 20.0) < 4 * p.std("Sp")


def test_speed_laws_recover_known_parameters():
    rng = np.random.default_rng(11)
    V = np.linspace(0.5, 30.0, 40)
    mu = tire.do_marsac_mosset(V, 0.8, 15.0, 1.6, 0.004) + rng.normal(0, 0.003, V.size)
    d = tire.fit_do_marsac_mosset(V, mu, sigma=0.003)
    for name, true in dict(mu0=0.8, Vs=15.0, alpha=1.6, beta=0.004).items():
        assert abs(d[name] - true) < 4 * d.std(name), name
    Vr = np.geomspace(0.05, 30.0, 40)
    mu = tire.rado(Vr, 0.9, 3.0, 1.5) + rng.normal(0, 0.005, Vr.size)
    r = tire.fit_rado(Vr, mu)
    assert r["mu_locked"] == 0.0 and "mu_locked" in r.fixed
    for name, true in dict(mu_peak=0.9, Vc=3.0, C=1.5).items():
        assert abs(r[name] - true) < 4 * r.std(name), name
    mu = tire.rado(Vr, 0.9, 3.0, 1.5, 0.3) + rng.normal(0, 0.005, Vr.size)
    r4 = tire.fit_rado(Vr, mu, fit_mu_locked=True)
    for name, true in dict(mu_peak=0.9, Vc=3.0, C=1.5, mu_locked=0.3).items():
        assert abs(r4[name] - true) < 4 * r4.std(name), name
    assert r4(r4["Vc"]) == pytest.approx(r4["mu_peak"], rel=1e-12)  # the peak sits at Vc
    assert tire.RADO_1994 in r4.citations


def test_speed_law_bad_input():
    V = np.linspace(1, 10, 10)
    mu = tire.piarc(V, 0.8, 20.0)
    with pytest.raises(InputError, match="law"):
        tire.fit_speed_law("coulomb", V, mu)
    with pytest.raises(InputError, match="speed"):
        tire.fit_piarc(V - 5, mu)
    with pytest.raises(InputError, match="mu"):
        tire.fit_piarc(V, mu * np.nan)
    with pytest.raises(InputError, match="fixed"):
        tire.fit_do_marsac_mosset(V, mu, fixed={"gamma": 1.0})
    with pytest.raises(InputError, match="free parameters"):
        tire.fit_do_marsac_mosset(V[:4], mu[:4])
