"""Specification of the road-friction trailer article's brush (Lubricants 11(7), 277 (2023), Section 4).

* Kinematics: the article's bristle displacement dx = s x (its Eqs. 11, 19) beside Pacejka's theta x, theta = s/(1-s).
  Both are the same curve in theta, so mu_linear(s) = mu_pacejka(s / (1 + s)) exactly.
* The two-coefficient brush with Sakai's n = 4 pressure and dx = s x has the closed form of the article's Eqs. 20-24:
  x_c/l = f1/(30 mu_s) - 5 mu_s/(3 f1) + 2/3 with f1 = cbrt((-1350 y + 150 sqrt(3) sqrt(27 y^2 - 50 mu_s y
  + 25 mu_s^2) + 1250 mu_s) mu_s^2), y = abc s (Cardano's root of the stick condition; x_c = 0 once y >= 5 mu_s),
  the adhesion term abc s (x_c/l)^2 (Eq. 22 over the load) and the sliding term
  2 mu_D [P(l) - P(x_c)] / l^2, P(x) = -2x^5/l^3 + 5x^4/l^2 - 5x^3/l + 5x^2/2 (Eqs. 23-24 over the load).
* Pacejka's closed form for a constant friction and the parabolic pressure (Tire and Vehicle Dynamics, ch. 3):
  lambda = x_c/l = max(0, 1 - theta/theta_sl), adhesion 3 mu (1 - lambda) lambda^2, sliding mu (1 - 3 lambda^2
  + 2 lambda^3).
* Identification (the article's Figure 18): mu_D = the Magic Formula's locked mu, initial slope BCD, mu_s the least
  squares of the brush against the formula; checked against a brute-force scan with the node-based brush, its
  uncertainties against Monte Carlo over the formula's covariance.
* The peak ratio n3 = mu_peak/mu_s over the article's map 0.1 <= n1 <= 0.8, 1 <= n2 <= 6 (its Figure 20).
"""

import numpy as np
import pytest

from persson import slip as ps
from persson.errors import InputError
from persson.slip.brush_identify import _brush_exact, _sakai_table
from validation.rigs import RoadProfile

L, W, K, SIGMA0 = 0.1, 0.15, 9.0e7, 0.3e6  # tire-like patch: initial slope k l/(2 sigma0) = 15


def article_closed_form(s, mu_s, mu_d, abc):
    """Adhesion term, sliding term and x_c/l of the article's Eqs. 20-24 (l = 1), x_c clipped at the leading edge."""
    y = abc * s
    f1 = np.cbrt((-1350 * y + 150 * np.sqrt(3) * np.sqrt(27 * y * y - 50 * mu_s * y + 25 * mu_s**2)
                  + 1250 * mu_s) * mu_s**2)
    xc = np.clip(f1 / (30 * mu_s) - 5 * mu_s / (3 * f1) + 2 / 3, 0.0, 1.0)

    def P(x):
        return -2 * x**5 + 5 * x**4 - 5 * x**3 + 2.5 * x**2

    return abc * s * xc**2, 2 * mu_d * (P(1.0) - P(xc)), xc


@pytest.fixture(scope="module")
def seed_formula():
    """The seed's curve (peak 1.156 at 11 %, 0.679 at 93 %) as a Magic Formula with its covariance."""
    return ps.magic_formula_from_peak(0.11, 1.156, 0.93, 0.679, sigma=0.01, peak_slip_std=0.005)


@pytest.fixture(scope="module")
def seed_brush(seed_formula):
    """The brush identified from it (Pacejka's kinematics), with propagated uncertainties."""
    return ps.identify_two_coefficient(seed_formula)


# ---- kinematics -------------------------------------------------------------------------------------------------
def test_linear_kinematics_is_pacejka_at_the_slip_with_the_same_theta():
    s = np.linspace(0.002, 1.0, 60)
    lin = ps.two_coefficient_mu(s, mu_static=1.0, mu_dynamic=0.5, initial_slope=8.0, kinematics="linear")
    pac = ps.two_coefficient_mu(s / (1 + s), mu_static=1.0, mu_dynamic=0.5, initial_slope=8.0)
    assert np.allclose(lin.mu, pac.mu, rtol=0, atol=1e-14)
    c = ps.Contact(L, W, K, "parabolic")
    a = ps.brush_terms(c, s, 0.8, pressure=SIGMA0, kinematics="linear")
    b = ps.brush_terms(c, s / (1 + s), 0.8, pressure=SIGMA0)
    assert np.allclose(a.mu, b.mu, atol=1e-14) and np.allclose(a.stick_length, b.stick_length, atol=1e-15)
    # the default is unchanged; the same initial slope; the article is cited where its kinematics is used
    assert np.array_equal(ps.brush_mu(c, s / (1 + s), 0.8, pressure=SIGMA0)[0], b.mu)
    small = np.array([1e-5, 2e-5])
    for kin in ps.KINEMATICS:
        mu = ps.brush_mu(c, small, 0.8, pressure=SIGMA0, kinematics=kin)[0]
        assert np.allclose(mu / small, c.initial_slope(SIGMA0), rtol=1e-3)  # O(s) corrections: 1e-4 here
    assert ps.TRAILER_2023 in a.citations and ps.TRAILER_2023 not in b.citations
    with pytest.raises(InputError, match="kinematics"):
        ps.two_coefficient_mu(0.1, mu_static=1, mu_dynamic=0.5, initial_slope=8, kinematics="theta")


@pytest.mark.parametrize("abc", [3.0, 20.0])   # 3 < n + 1 = 5: a stick zone even at s = 1; 20: full sliding from 0.25
def test_two_coefficient_brush_with_dx_equal_s_x_is_the_articles_closed_form(abc):
    s = np.r_[1e-4, np.linspace(0.01, 1.0, 100)]
    for mu_d in (0.3, 0.5):                    # the article's Figure 19: mu_s = 1, mu_D = 0.3 and 0.5
        ad, sl, xc = article_closed_form(s, 1.0, mu_d, abc)
        err = []
        for n_points in (401, 1601):
            c = ps.two_coefficient_mu(s, mu_static=1.0, mu_dynamic=mu_d, initial_slope=abc, kinematics="linear",
                                      n_points=n_points, length=0.25)
            err.append(max(np.abs(c.mu_adhesion - ad).max(), np.abs(c.mu_sliding - sl).max()))
        assert np.abs(c.stick_fraction - xc).max() < 1e-5 and err[1] < 1e-6
        assert err[1] < err[0] / 10                # converges (second order in the node spacing)
        assert np.array_equal(c.mu, c.mu_adhesion + c.mu_sliding)
        assert np.allclose(c.stick_length, 0.25 * c.stick_fraction)
    # the identification's tabulated brush (exact stick length, linear interpolation in u) against the same forms
    got = _brush_exact(1.0, 0.5, abc, s, 4.0, _sakai_table(4.0))
    assert np.abs(got - np.sum(article_closed_form(s, 1.0, 0.5, abc)[:2], axis=0)).max() < 3e-8
    # corners: almost no slip sticks everywhere (mu = abc s, Eq. 13); the locked wheel slides only when abc >= 5 mu_s
    assert c.mu[0] == pytest.approx(abc * 1e-4, rel=1e-3)
    assert (c.stick_fraction[-1] > 0.1) == (abc < 5) and (c.mu[-1] == pytest.approx(0.5)) == (abc >= 5)


def test_adhesion_and_sliding_terms_against_pacejkas_closed_form():
    mu, s = 0.8, np.linspace(0.005, 1.0, 200)
    t = ps.brush_terms(ps.Contact(L, W, K, "parabolic"), s, mu, pressure=SIGMA0)
    theta = np.where(s < 1, s / (1 - np.where(s < 1, s, 0.0)), np.inf)
    lam = np.clip(1 - theta / (6 * mu * SIGMA0 / (K * L)), 0, None)
    assert np.allclose(t.mu_adhesion, 3 * mu * (1 - lam) * lam**2, rtol=0, atol=1e-5)
    assert np.allclose(t.mu_sliding, mu * (1 - 3 * lam**2 + 2 * lam**3), rtol=0, atol=1e-5)
    assert np.allclose(t.stick_length, lam * L, rtol=0, atol=5e-5 * L)
    assert t.mu_adhesion[-1] == 0 and t.mu_sliding[-1] == mu and np.array_equal(t.mu, t.mu_adhesion + t.mu_sliding)
    # uniform pressure: x_c/l = mu/a, adhesion mu^2/(2a), sliding mu (1 - mu/a) (a = k theta l/sigma0 > mu)
    u = ps.brush_terms(ps.Contact(L, W, K, "uniform"), 0.3, mu, pressure=SIGMA0)
    a = K * (0.3 / 0.7) * L / SIGMA0
    assert u.mu_adhesion == pytest.approx(mu**2 / (2 * a), rel=1e-12)
    assert u.mu_sliding == pytest.approx(mu * (1 - mu / a), rel=1e-12)


def test_figure_19_same_adhesion_term_different_sliding_term():
    s = np.linspace(0.005, 1.0, 200)
    low, high = (ps.two_coefficient_mu(s, mu_static=1.0, mu_dynamic=m, initial_slope=6.0) for m in (0.3, 0.5))
    assert np.array_equal(low.mu_adhesion, high.mu_adhesion)
    assert np.allclose(high.mu_sliding, low.mu_sliding * 0.5 / 0.3, rtol=1e-12, atol=1e-15)
    assert high.mu.max() - low.mu.max() > 0.05 and low.stick_length is None


# ---- identification from a Magic Formula (Figure 18) ----------------------------------------------------------
@pytest.mark.parametrize("kinematics", ps.KINEMATICS)
def test_identification_holds_mu_D_and_the_slope_and_finds_the_least_squares_mu_s(seed_formula, kinematics):
    mf = seed_formula.formula
    r = ps.identify_two_coefficient(mf, kinematics=kinematics)
    assert r.mu_dynamic == pytest.approx(mf(1.0), rel=1e-12) and r.initial_slope == pytest.approx(mf.initial_slope)
    assert r.n1 == pytest.approx(r.mu_dynamic / r.mu_static) and r.n2 == pytest.approx(r.initial_slope / r.mu_static)
    # a brute-force scan of mu_s with the node-based brush (an independent evaluation)
    s = np.arange(1, 101) / 100
    grid = r.mu_static * np.linspace(0.99, 1.01, 41)
    cost = [np.sum((ps.two_coefficient_mu(s, mu_static=g, mu_dynamic=r.mu_dynamic, initial_slope=r.initial_slope,
                                          kinematics=kinematics, n_points=1601).mu - mf(s)) ** 2) for g in grid]
    assert abs(grid[int(np.argmin(cost))] - r.mu_static) <= 0.5 * (grid[1] - grid[0])
    assert r.rms == pytest.approx(np.sqrt(min(cost) / s.size), rel=1e-3)
    near = r.curve(r.slip_at_peak * np.linspace(0.9, 1.1, 201), n_points=1601)
    assert np.max(near.mu) == pytest.approx(r.peak_mu, rel=1e-6) and not r.at_bound and r.notes == ()
    # the seed's sharp peak is beyond the brush with mu_D and the slope held (docs/slip.md quotes these numbers)
    expected = {"pacejka": (2.788, 0.109, 1.359), "linear": (2.685, 0.069, 1.315)}[kinematics]
    assert (r.mu_static, r.rms, r.peak_mu) == pytest.approx(expected, abs=1e-3)


def test_identification_uncertainties_agree_with_monte_carlo(seed_formula, seed_brush):
    r = seed_brush
    rng = np.random.default_rng(7)
    draws = rng.multivariate_normal(seed_formula.values, seed_formula.covariance, size=200, method="eigh")
    batch = ps.identify_two_coefficient([ps.MagicFormula(*p) for p in draws])
    for name in ("mu_static", "mu_dynamic", "initial_slope", "n1", "n2"):
        # the standard deviation of a 200-sample std is 5 %
        assert np.std(getattr(batch, name), ddof=1) == pytest.approx(getattr(r, name + "_std"), rel=0.15), name
    assert r.covariance.shape == (5, 5) and np.allclose(r.covariance, r.covariance.T)
    plain = ps.identify_two_coefficient(seed_formula.formula)
    assert plain.mu_static_std is None and plain.mu_static == pytest.approx(r.mu_static, rel=1e-12)


@pytest.fixture(scope="module")
def three_points():
    """Three (slip, mu) points with standard uncertainties 0.01 in mu and 0.002 in slip, and their brush."""
    s, m = np.array([0.05, 0.2, 1.0]), np.array([0.9, 1.1, 0.7])
    return s, m, ps.identify_two_coefficient(s, m, sigma=0.01, slip_std=0.002)


def test_three_points_with_their_uncertainties(seed_formula, seed_brush, three_points):
    from scipy.optimize import root

    s, m, r = three_points
    f = r.formula
    assert f(s) == pytest.approx(m, rel=1e-9)
    # the Jacobian of B, C, D in the points by central differences of an independent solve of the three equations
    J, h = np.zeros((3, 3)), 1e-6
    for i in range(3):
        for sign in (1, -1):
            mm = m.copy()
            mm[i] += sign * h
            sol = root(lambda q, mm=mm: ps.magic_formula(s, *q) - mm, [f.B, f.C, f.D], method="hybr", tol=1e-14)
            J[:, i] += sign * sol.x / (2 * h)
    slope = (f(s + 1e-7) - f(s - 1e-7)) / 2e-7
    cov = J @ np.diag(0.01**2 + (slope * 0.002) ** 2) @ J.T
    ref = ps.identify_two_coefficient(f, covariance=cov)
    assert r.mu_static == pytest.approx(ref.mu_static, rel=1e-9)
    assert np.allclose(r.covariance, ref.covariance, rtol=1e-4, atol=0)
    # more points are fitted; the uncertainties then come from the fit
    x = np.linspace(0.02, 1.0, 12)
    fit = ps.identify_two_coefficient(x, seed_formula.formula(x), sigma=0.01)
    assert fit.mu_static == pytest.approx(seed_brush.mu_static, rel=1e-4)
    assert fit.mu_static_std > 0


def test_linear_kinematics_note_and_bad_input():
    flat = ps.MagicFormula(B=2.0, C=1.5, D=1.0)  # slope 3: n2 < 5, a stick zone remains at the locked wheel
    r = ps.identify_two_coefficient(flat, kinematics="linear")
    assert r.n2 < 5 and abs(r.locked_mu - r.mu_dynamic) > 1e-3 and "stick zone" in r.notes[0]
    with pytest.raises(InputError, match="mix"):
        ps.identify_two_coefficient([flat, ps.SimpleMagicFormula(1.0, 1.5, 2.0)])
    with pytest.raises(InputError, match="covariance"):
        ps.identify_two_coefficient(flat, covariance=np.eye(2))
    with pytest.raises(InputError, match="slip_std"):
        ps.identify_two_coefficient(np.linspace(0.1, 1, 5), np.ones(5), slip_std=0.01)
    with pytest.raises(InputError, match="initial slope"):
        ps.identify_two_coefficient(ps.MagicFormula(B=2.0, C=1.5, D=-1.0))
    with pytest.raises(InputError, match="curve"):
        ps.identify_two_coefficient("seed")


def test_brush_per_road_position_from_a_road_profile(three_points):
    s3, m3, ref = three_points
    f = ref.formula
    s = np.array([s3, s3])
    m = np.array([m3, [np.nan] * 3])
    nan2 = np.array([1.0, np.nan])
    prof = RoadProfile(position=np.array([2.0, 6.0]), peak_mu=nan2, peak_mu_std=nan2, locked_mu=nan2,
                       locked_mu_std=nan2, peak_mu_std_common=nan2, locked_mu_std_common=nan2, slip_at_peak=nan2,
                       slip_at_peak_std=nan2, identified=np.array([True, False]), B=np.array([f.B, np.nan]),
                       C=np.array([f.C, np.nan]), D=np.array([f.D, np.nan]), slip=s, mu=m,
                       slip_std=np.full((2, 3), 0.002), mu_std=np.full((2, 3), 0.01), n_samples=np.full((2, 3), 9),
                       speed=np.array([12.0, 12.0]), step_m=4.0)
    b = prof.two_coefficient_brush()
    assert b.mu_static[0] == pytest.approx(ref.mu_static, rel=1e-9)
    assert b.mu_static_std[0] == pytest.approx(ref.mu_static_std, rel=1e-6)
    assert np.isnan(b.mu_static[1]) and "missing" in b.notes[0]


# ---- the peak ratio n3 over the article's map (Figure 20) -----------------------------------------------------
@pytest.fixture(scope="module")
def article_maps():
    n1, n2 = np.linspace(0.1, 0.8, 8), np.linspace(1.0, 6.0, 11)
    return {(kin, smax): ps.two_coefficient_map(n1, n2, kinematics=kin, slip_max=smax, n_slip=200, n_points=201)
            for kin, smax in (("pacejka", 1.0), ("linear", 1.0), ("linear", None))}


def test_peak_ratio_depends_on_n1_in_either_kinematics(article_maps):
    pac, lin, stat = (article_maps[k].sensitivity() for k in (("pacejka", 1.0), ("linear", 1.0), ("linear", None)))
    # Pacejka: theta covers [0, inf) on 0 < s <= 1, so n3 is a function of n1 alone
    assert pac.peak_ratio_share[1] < 1e-9 and pac.peak_ratio_driver == "n1"
    assert pac.peak_ratio_swing == pytest.approx((0.346, 0.0), abs=2e-3)
    # dx = s x: n2 enters only where the peak would lie beyond the locked wheel (n1 >= 0.5, small n2)
    assert lin.peak_ratio_share == pytest.approx((0.974, 0.008), abs=2e-3) and lin.peak_ratio_driver == "n1"
    assert lin.peak_ratio_swing == pytest.approx((0.325, 0.033), abs=2e-3)
    m = article_maps[("linear", 1.0)]
    at_lock = m.slip_at_peak == 1.0
    assert np.allclose(m.peak_ratio[at_lock], m.locked_ratio[at_lock], atol=1e-12)
    assert np.flatnonzero(at_lock.any(axis=1)).min() == 4 and np.ptp(m.peak_ratio[-1]) == pytest.approx(0.140, abs=2e-3)
    # the stationary maximum (the slip range not cut at s = 1) is Pacejka's n3 again
    assert stat.peak_ratio_share[1] < 1e-9
    assert np.allclose(article_maps[("linear", None)].peak_ratio, article_maps[("pacejka", 1.0)].peak_ratio, atol=1e-5)
    # the slip of the peak depends on both
    assert stat.slip_share == pytest.approx((0.39, 0.46), abs=0.01)
    for sens in (pac, lin):
        assert 0.4 < sens.slip_share[0] < 0.55 and 0.4 < sens.slip_share[1] < 0.55


def test_n2_dominates_only_with_a_stiffness_that_does_not_follow_n2(article_maps):
    """The article's Eqs. 22-24 with the tread stiffness of its Figure 17 (k = 8e6, w = 0.2 m, l = 0.25 m,
    F_Z = 2.5 kN: k w l^2/(2 F_Z) = 20) held while abc = n2 mu_s changes only the stick length and Eq. 24."""
    n1, n2 = article_maps[("linear", 1.0)].n1, article_maps[("linear", 1.0)].n2
    s = np.linspace(1e-4, 1.0, 4001)
    stiff = 8e6 * 0.2 * 0.25**2 / (2 * 2500.0)
    n3 = np.empty((n1.size, n2.size))
    for j, b in enumerate(n2):
        _, _, xc = article_closed_form(s, 1.0, 0.0, b)
        for i, a in enumerate(n1):
            mu = stiff * s * xc**2 + stiff / b * article_closed_form(s, 1.0, a, b)[1]
            n3[i, j] = mu.max()
    share = ps.BrushMap(n1=n1, n2=n2, peak_ratio=n3, slip_at_peak=n3, locked_ratio=n1, sakai_n=4.0).sensitivity()
    assert share.peak_ratio_share == pytest.approx((0.077, 0.908), abs=5e-3) and share.peak_ratio_driver == "n2"
    # ... and it is the consistent curve scaled by stiffness / (n2 mu_s): a peak far above mu_s
    assert np.allclose(n3, stiff / n2 * article_maps[("linear", 1.0)].peak_ratio, rtol=2e-3)
    assert n3.min() > 1.5 and n3.max() == pytest.approx(13.3, abs=0.05)
