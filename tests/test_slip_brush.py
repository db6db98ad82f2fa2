"""Specification of the steady-state brush model (persson.slip), against independent closed forms.

Slip definition used throughout: braking slip s = (V - omega r)/V, sliding speed v_s = s V, bristle displacement
u(x) = x s/(1-s) from the leading edge (docs/slip.md). For s -> 0 the whole patch sticks and
mu = (1/(sigma0 l)) int_0^l k x s/(1-s) dx = k l s / (2 sigma0 (1-s)), so d mu/ds(0) = k l/(2 sigma0).

Closed forms for a constant local friction mu (theta = s/(1-s), a = k theta l/sigma0):
* uniform pressure: the stick zone ends at x_c/l = mu/a (when < 1): mu(s) = a/2 (a <= mu), mu (1 - mu/(2a)) (a > mu);
* parabolic 6 sigma0 (x/l)(1-x/l): x_c/l = lambda = max(0, 1 - theta/theta_sl), theta_sl = 6 mu sigma0/(k l),
  mu(s) = mu (1 - lambda^3) (Pacejka, Tire and Vehicle Dynamics, ch. 3);
* Sakai n-power p/sigma0 = (n+1)/n (1 - |2 xi - 1|^n): x_c from a xi = mu p(xi)/sigma0 (brentq here), and the
  load ahead of x_c in closed form G(xi) = (n+1)/n [xi - (1 + sign(w)|w|^(n+1)) / (2(n+1))], w = 2 xi - 1.
"""

import math

import numpy as np
import pytest
from scipy.integrate import trapezoid
from scipy.optimize import brentq

import materials
import persson
import surfaces
from persson import slip as ps
from persson.errors import InputError

L, W, K, SIGMA0 = 0.1, 0.15, 9.0e7, 0.3e6  # tire-like patch: initial slope k l/(2 sigma0) = 15
SLOPE = 15.0


def contact(dist="parabolic", n_points=401):
    return ps.Contact(length=L, width=W, stiffness=K, pressure_distribution=dist, n_points=n_points)


def const(mu):
    return lambda v: np.full_like(v, mu)


def parabolic_exact(s, mu):
    theta = s / (1 - s)
    theta_sl = 6 * mu * SIGMA0 / (K * L)
    lam = np.clip(1 - theta / theta_sl, 0, None)
    return mu * (1 - lam**3), lam


def uniform_exact(s, mu):
    a = K * (s / (1 - s)) * L / SIGMA0
    return np.where(a <= mu, a / 2, mu * (1 - mu / (2 * a)))


def sakai_exact(s, mu, n):
    a = K * (s / (1 - s)) * L / SIGMA0
    g = lambda xi: (n + 1) / n * (1 - abs(2 * xi - 1) ** n)  # noqa: E731

    def G(xi):
        w = 2 * xi - 1
        return (n + 1) / n * (xi - (1 + math.copysign(abs(w) ** (n + 1), w)) / (2 * (n + 1)))

    out = []
    for ai in np.atleast_1d(a):
        if ai >= mu * 2 * (n + 1):  # slope of mu p/sigma0 at the leading edge: no stick zone
            out.append(mu)
            continue
        xc = brentq(lambda x: mu * g(x) - ai * x, 1e-12, 1.0, xtol=1e-15, rtol=1e-15)
        out.append(0.5 * ai * xc**2 + mu * (1 - G(xc)))
    return np.array(out)


# ------------------------------------------------------------------------------------------------------------
def test_initial_slope_is_k_l_over_2_sigma0():
    c = contact()
    assert c.initial_slope(SIGMA0) == pytest.approx(K * L / (2 * SIGMA0)) == pytest.approx(SLOPE)
    for dist in ("uniform", "parabolic", {"sakai_n": 4}):
        h = np.array([1e-6, 2e-6])
        r = ps.mu_slip(const(0.8), h, 1.0, pressure=SIGMA0, contact=contact(dist))
        # secant slope near s = 0 and mu/s both -> k l/(2 sigma0) = 15
        assert (r.mu[1] - r.mu[0]) / 1e-6 == pytest.approx(SLOPE, rel=1e-4)
        assert r.mu[0] / 1e-6 == pytest.approx(SLOPE, rel=1e-4)
        assert r.stick_fraction[0] > 0.999


def test_saturates_at_constant_friction():
    mu0 = 0.8
    s = np.concatenate([np.geomspace(1e-4, 0.99, 300), [1.0]])
    for dist in ("parabolic", {"sakai_n": 4}, "uniform"):
        r = ps.mu_slip(const(mu0), s, 2.0, pressure=SIGMA0, contact=contact(dist))
        assert np.all(np.diff(r.mu) >= -1e-12), dist  # no peak with a constant friction
        assert r.mu[-1] == pytest.approx(mu0, abs=1e-14)  # s = 1: pure sliding
        assert np.max(r.mu) <= mu0 + 1e-12
    # parabolic: exactly mu from the full-sliding slip s_sl = theta_sl/(1+theta_sl) on
    c = contact()
    s_sl = c.full_sliding_slip(mu0, SIGMA0)
    theta_sl = 6 * mu0 * SIGMA0 / (K * L)
    assert s_sl == pytest.approx(theta_sl / (1 + theta_sl))
    r = ps.mu_slip(const(mu0), np.array([1.01, 1.5, 3.0]) * s_sl, 1.0, pressure=SIGMA0, contact=c)
    assert np.allclose(r.mu, mu0, atol=1e-13)
    assert np.all(r.stick_fraction == 0)


def test_parabolic_matches_closed_form_and_stick_zone():
    mu0 = 0.9
    s = np.geomspace(1e-4, 0.5, 200)
    r = ps.mu_slip(const(mu0), s, 1.0, pressure=SIGMA0, contact=contact())
    exact, lam = parabolic_exact(s, mu0)
    assert np.max(np.abs(r.mu - exact)) < 2e-5
    assert np.max(np.abs(r.stick_fraction - lam)) < 1e-4
    assert np.allclose(r.stick_length, r.stick_fraction * L)
    assert np.allclose(r.force, r.mu * SIGMA0 * L * W)
    assert r.load == pytest.approx(SIGMA0 * L * W)


def test_uniform_is_exact_at_any_resolution():
    mu0 = 0.7
    s = np.geomspace(1e-5, 0.999, 100)
    for n in (11, 401):
        r = ps.mu_slip(const(mu0), s, 1.0, pressure=SIGMA0, contact=contact("uniform", n))
        assert np.max(np.abs(r.mu - uniform_exact(s, mu0))) < 1e-12
        a = K * (s / (1 - s)) * L / SIGMA0
        assert np.allclose(r.stick_fraction, np.minimum(1.0, mu0 / a), atol=1e-12)


@pytest.mark.parametrize("dist, n", [("parabolic", 2.0), ({"sakai_n": 4}, 4.0), ({"sakai_n": 2.5}, 2.5)])
def test_converges_with_discretisation(dist, n):
    mu0 = 0.8
    s_sl = contact().full_sliding_slip(mu0, SIGMA0)  # parabolic value; Sakai's full sliding comes later
    s = np.linspace(0.02, 0.95, 40) * s_sl
    exact = sakai_exact(s, mu0, n)
    if n == 2.0:
        assert np.allclose(exact, parabolic_exact(s, mu0)[0], atol=1e-12)  # the two references agree
    errors = []
    for npts in (26, 51, 101, 201, 401, 801):
        r = ps.mu_slip(const(mu0), s, 1.0, pressure=SIGMA0, contact=contact(dist, npts))
        errors.append(np.max(np.abs(r.mu - exact)))
    errors = np.array(errors)
    assert np.all(np.diff(errors) < 0), errors
    order = np.log2(errors[:-1] / errors[1:])
    assert np.all(order > 1.6), order  # second order
    assert errors[4] < 2e-5  # default n_points = 401


def test_friction_falling_with_speed_gives_a_peak():
    # local friction falling with sliding speed (independent of the engine)
    mu_v = lambda v: 0.5 + 0.6 / (1 + v / 0.3)  # noqa: E731
    V = 10.0
    s = np.concatenate([np.geomspace(1e-3, 0.99, 400), [1.0]])
    r = ps.mu_slip(mu_v, s, V, pressure=SIGMA0, contact=contact())
    j = int(np.argmax(r.mu))
    assert 0 < j < s.size - 1
    assert r.mu[j] > r.mu[-1] + 0.1  # a clear peak above the locked-wheel value
    assert r.mu[-1] == pytest.approx(mu_v(V), abs=1e-14)
    assert 0.005 < s[j] < 0.2
    # the peak cannot exceed the largest local friction on the curve
    assert r.mu[j] <= np.max(mu_v(s * V)) + 1e-12
    pm, sp = r.peak()
    assert pm >= r.mu[j] - 1e-12 and abs(sp - s[j]) < 0.01


class CountingModel:
    """A friction model that records its calls: mu(v) = 0.6 + 0.1 log10(v)."""

    def __init__(self):
        self.calls = []

    def friction(self, speed, temperature, pressure):
        v = np.asarray(speed, dtype=float)
        self.calls.append((v.copy(), temperature, pressure))

        class R:
            mu = 0.6 + 0.1 * np.log10(v)
            converged = True
            notes = ()
            citations = ()

        return R()


def test_one_engine_evaluation_over_distinct_sliding_speeds():
    m = CountingModel()
    s = np.array([0.05, 0.1, 0.25, 0.5, 1.0])
    V = np.array([1.0, 2.0, 4.0])
    r = ps.mu_slip(m, s[:, None], V[None, :], temperature=35.0, pressure=SIGMA0, contact=contact())
    assert len(m.calls) == 1
    v_called, T, p = m.calls[0]
    assert T == 35.0 and p == SIGMA0
    assert np.all(np.diff(v_called) > 0)  # sorted and distinct
    assert v_called.size == np.unique(np.round(s[:, None] * V[None, :], 12)).size == 9  # of 15 pairs
    assert r.mu.shape == (5, 3) and r.stick_fraction.shape == (5, 3)
    assert np.allclose(r.sliding_speed, s[:, None] * V[None, :])
    # the same as element-by-element evaluation
    for i in range(5):
        for j in range(3):
            one = ps.mu_slip(CountingModel(), s[i], V[j], temperature=35.0, pressure=SIGMA0, contact=contact())
            assert isinstance(one.mu, float)
            assert one.mu == pytest.approx(r.mu[i, j], abs=1e-14)
    # equal sliding speeds (0.5 x 2 = 1 x 1) share one engine value
    r2 = ps.mu_slip(m, [0.5, 1.0], [2.0, 1.0], pressure=SIGMA0, contact=contact())
    assert m.calls[-1][0].size == 1
    assert r2.mu_local[0] == r2.mu_local[1]


def test_pure_sliding_is_the_engine_friction():
    model = persson.Model(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6),
                          materials.ConstantModulus(E_storage=5e6, E_loss=2e6))
    V = np.array([0.01, 0.1, 1.0, 10.0])
    ref = model.friction(V, temperature=20.0, pressure=SIGMA0).mu
    for dist in ("uniform", "parabolic", {"sakai_n": 4}, lambda xi: 6 * xi * (1 - xi)):
        r = ps.mu_slip(model, 1.0, V, temperature=20.0, pressure=SIGMA0, contact=contact(dist))
        assert np.allclose(r.mu, ref, rtol=1e-13)
        assert np.all(r.stick_fraction == 0)
        assert r.friction is not None and r.converged
        assert ps.PACEJKA_BOOK in r.citations and "10.1063/1.1388626" in r.citations


def test_custom_distribution_and_sakai_two_is_parabolic():
    s = np.geomspace(1e-3, 1, 50)
    a = ps.mu_slip(const(0.8), s, 1.0, pressure=SIGMA0, contact=contact("parabolic"))
    b = ps.mu_slip(const(0.8), s, 1.0, pressure=SIGMA0, contact=contact(lambda xi: 6 * xi * (1 - xi)))
    c = ps.mu_slip(const(0.8), s, 1.0, pressure=SIGMA0, contact=contact({"sakai_n": 2}))
    assert np.allclose(a.mu, b.mu, atol=1e-14) and np.allclose(a.mu, c.mu, atol=1e-14)
    cs = contact({"sakai_n": 4})
    x = np.linspace(0, L, 2001)
    p = cs.pressure(x, SIGMA0)
    assert trapezoid(p, x) == pytest.approx(SIGMA0 * L, rel=1e-6)  # integrates to the load / w
    assert p.max() == pytest.approx(SIGMA0 * 5 / 4, rel=1e-9)  # (n+1)/n at the centre
    assert ps.SAKAI_1981 in cs.citations
    assert ps.SAKAI_1981 in ps.mu_slip(const(0.8), 0.1, 1.0, pressure=SIGMA0, contact=cs).citations
    assert ps.SAKAI_1981 not in a.citations and ps.PACEJKA_BOOK in a.citations


@pytest.mark.parametrize("dist", ["uniform", "parabolic", {"sakai_n": 4}])
def test_a_contact_survives_pickling(dist):
    """A contact sent to another process (a process pool, a pickled result) keeps its pressure law exactly."""
    import pickle

    c = contact(dist)
    back = pickle.loads(pickle.dumps(c))
    x = np.linspace(0, L, 101)
    assert back.pressure_distribution == c.pressure_distribution
    assert np.array_equal(back.pressure(x, SIGMA0), c.pressure(x, SIGMA0)) and back.citations == c.citations


def test_two_coefficient_brush_and_map():
    n2 = 20.0
    s = np.geomspace(1e-4, 1, 20001)
    # equal coefficients: the plain brush with Sakai n = 4 (same initial slope)
    c4 = ps.Contact(L, W, K, {"sakai_n": 4})
    one = ps.two_coefficient_mu(s, mu_static=0.8, mu_dynamic=0.8, initial_slope=c4.initial_slope(SIGMA0))
    ref = ps.mu_slip(const(0.8), s, 1.0, pressure=SIGMA0, contact=c4)
    assert np.allclose(one.mu, ref.mu, atol=1e-14)
    assert np.allclose(one.mu[:3] / s[:3], c4.initial_slope(SIGMA0), rtol=1e-3)
    # mu_D < mu_s: a peak above mu_D, locked wheel at mu_D
    c = ps.two_coefficient_mu(s, mu_static=1.0, mu_dynamic=0.7, initial_slope=n2)
    assert c.mu[-1] == pytest.approx(0.7, abs=1e-14)
    assert np.max(c.mu) > 0.71 and np.argmax(c.mu) < s.size - 1
    # the map against a brute-force search on a dense slip grid
    n1 = np.array([0.5, 0.7, 0.85, 1.0])
    n2s = np.array([5.0, 10.0, 20.0, 40.0])
    bm = ps.two_coefficient_map(n1, n2s)
    assert bm.peak_ratio.shape == bm.slip_at_peak.shape == (4, 4)
    for i, a in enumerate(n1[:-1]):
        for j, b in enumerate(n2s):
            cur = ps.two_coefficient_mu(s, mu_static=1.0, mu_dynamic=a, initial_slope=b)
            k = int(np.argmax(cur.mu))
            assert bm.peak_ratio[i, j] == pytest.approx(cur.mu[k], abs=2e-6)
            assert bm.slip_at_peak[i, j] == pytest.approx(s[k], rel=2e-3)
    # scaling: mu/mu_s depends on n2*theta only, so the peak ratio depends on n1 alone and theta_peak * n2 is fixed
    theta_p = bm.slip_at_peak / (1 - bm.slip_at_peak)
    for i in range(3):
        assert np.ptp(bm.peak_ratio[i]) < 1e-6
        assert np.ptp(theta_p[i] * n2s) / np.mean(theta_p[i] * n2s) < 2e-3
    # n1 = 1: the single-coefficient curve saturates at mu_s at full sliding, theta_sl = 2(n+1)/(2 n2) = 5/n2
    theta_sl = 5.0 / n2s
    assert np.allclose(bm.peak_ratio[-1], 1.0, atol=1e-12)
    assert np.allclose(bm.slip_at_peak[-1], theta_sl / (1 + theta_sl), rtol=1e-2)
    # peak ratio rises with n1 and stays between n1 and 1
    assert np.all(np.diff(bm.peak_ratio[:, 0]) > 0)
    assert np.all(bm.peak_ratio[:, 0] >= n1) and np.all(bm.peak_ratio <= 1 + 1e-12)
    r, sp = bm.lookup(0.7, 20.0)
    assert r == pytest.approx(bm.peak_ratio[1, 2]) and sp == pytest.approx(bm.slip_at_peak[1, 2])


def test_drft_kinematics():
    k = ps.drft_kinematics(wheel_speed=0.9, disk_speed=1.0)
    assert k.slip == pytest.approx(0.1) and k.sliding_speed == pytest.approx(0.1) and k.speed == 1.0
    # angular: disk 5 rad/s at track radius 0.2 m -> V = 1 m/s; wheel r = 0.05 m at 18 rad/s -> 0.9 m/s
    ka = ps.drft_from_angular(18.0, 5.0, wheel_radius=0.05, track_radius=0.2)
    assert ka.speed == pytest.approx(1.0) and ka.slip == pytest.approx(0.1) and ka.sliding_speed == pytest.approx(0.1)
    back = ps.drft_speeds([0.0, 0.1, 1.0], 1.0, wheel_radius=0.05, track_radius=0.2)
    assert np.allclose(back.wheel_speed, [1.0, 0.9, 0.0])  # slip = 1: locked wheel, pure sliding
    assert np.allclose(back.omega_wheel, [20.0, 18.0, 0.0]) and np.allclose(back.omega_disk, 5.0)
    assert np.allclose(back.sliding_speed, [0.0, 0.1, 1.0])
    locked = ps.drft_kinematics(0.0, 2.5)
    assert locked.slip == 1.0 and locked.sliding_speed == 2.5
    driving = ps.drft_kinematics(1.1, 1.0)  # the wheel faster than the disk: driving (tests/test_slip_kinematics.py)
    assert driving.driving and driving.slip == pytest.approx(-0.1)
    with pytest.raises(InputError, match="wheel_speed"):
        ps.drft_kinematics(-0.1, 1.0)
    with pytest.raises(InputError, match="disk_speed"):
        ps.drft_kinematics(0.5, 0.0)
    with pytest.raises(InputError, match="slip"):
        ps.drft_speeds(1.2, 1.0)
    with pytest.raises(InputError, match="wheel_radius"):
        ps.drft_from_angular(1.0, 1.0, wheel_radius=0.0, track_radius=0.2)


@pytest.mark.parametrize("kwargs, match", [
    (dict(slip=0.0), "slip"), (dict(slip=-0.1), "slip"), (dict(slip=1.2), "slip"), (dict(slip=[0.1, np.nan]), "slip"),
    (dict(speed=0.0), "speed"), (dict(speed=[1.0, -2.0]), "speed"), (dict(pressure=0.0), "pressure"),
    (dict(contact="parabolic"), "contact"), (dict(slip=np.ones(3) * 0.5, speed=np.ones(4)), "broadcast"),
    (dict(model=lambda v: -0.1 * np.ones_like(v)), "model"), (dict(model=42), "model"),
])
def test_bad_input_to_mu_slip(kwargs, match):
    args = dict(model=const(0.8), slip=0.1, speed=1.0, pressure=SIGMA0, contact=contact())
    args.update(kwargs)
    model, s, V = args.pop("model"), args.pop("slip"), args.pop("speed")
    with pytest.raises(InputError, match=match):
        ps.mu_slip(model, s, V, **args)


@pytest.mark.parametrize("kwargs, match", [
    (dict(length=0.0), "length"), (dict(width=-1.0), "width"), (dict(stiffness=float("nan")), "stiffness"),
    (dict(pressure_distribution="triangular"), "pressure_distribution"),
    (dict(pressure_distribution={"sakai_n": 0}), "sakai_n"),
    (dict(pressure_distribution={"n": 4}), "pressure_distribution"),
    (dict(pressure_distribution=lambda xi: 12 * xi * (1 - xi)), "integrates"),  # twice the load
    (dict(pressure_distribution=lambda xi: np.ones_like(xi) * 0.5), "integrates"),
    (dict(pressure_distribution=lambda xi: 4 * xi - 1), "negative"),
    (dict(n_points=5), "n_points"),
])
def test_bad_contact(kwargs, match):
    args = dict(length=L, width=W, stiffness=K)
    args.update(kwargs)
    with pytest.raises(InputError, match=match):
        ps.Contact(**args)


def test_bad_input_two_coefficient():
    with pytest.raises(InputError, match="mu_static"):
        ps.two_coefficient_mu(0.1, mu_static=0.0, mu_dynamic=0.5, initial_slope=10)
    with pytest.raises(InputError, match="initial_slope"):
        ps.two_coefficient_mu(0.1, mu_static=1.0, mu_dynamic=0.5, initial_slope=-1)
    with pytest.raises(InputError, match="slip"):
        ps.two_coefficient_mu(1.5, mu_static=1.0, mu_dynamic=0.5, initial_slope=10)
    with pytest.raises(InputError, match="n1"):
        ps.two_coefficient_map([0.5, 0.4], [10, 20])
    with pytest.raises(InputError, match="pressure"):
        ps.brush_mu(contact(), 0.1, 0.8, pressure=-1)
