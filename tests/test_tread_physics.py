"""The tread-element march against closed forms (persson.tread, issue 27, "How we know it is right").

* on a smooth road (alpha = 0) mu = mu_loc exactly, at any slip, speed, pattern, pressure shape (elements rigid in
  shear, the paper's equations; with shear compliance see the brush-model test below);
* a Kelvin element sliding at v over h = a sin(kx) without losing contact gives mu = C a^2 omega k / (2 F0)
  (omega = k v, F0 its mean force) with mu_loc = 0, at second order in the road element size; and 0 for C = 0;
* an element leaving contact relaxes as exp(-K t / C);
* the load balance (Eq. 4) holds to 1e-9 at every step;
* with elastic elements on a smooth road the march is the brush model: Pacejka's closed form
  mu (1 - lambda^3), lambda = 1 - theta / theta_sl, for the parabolic pressure.
"""

import inspect
import math

import numpy as np
import pytest

import materials
import surfaces
from persson import tread
from persson.tread import kernels

ELASTIC = materials.ConstantModulus(E_storage=5e6, E_loss=1e6)


def tire(**kw):
    args = dict(diameter=0.63, width=0.205, load=4000.0, inflation_pressure=2.2e5, tread_depth=8e-3)
    args.update(kw)
    return tread.Tire(**args)


def flat_road(length=0.4, dx=1e-4, rows=1):
    return tread.Road(np.zeros((rows, int(round(length / dx)) + 1)), dx)


@pytest.fixture(scope="module")
def rough():
    sa = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.15e-3, qL=2 * math.pi / 0.1)
    return tread.as_road(surfaces.synthesize_profiles(sa, n_profiles=2, n=3000, length=0.3, seed=3))


@pytest.mark.parametrize("slip, speed, kw", [
    (0.02, 1.0, dict(slip_stiffness=None)),                                          # slow, nearly rolling
    (1.0, 30.0, dict(slip_stiffness=None, grooves=tread.Grooves(width=8e-3, pitch=30e-3))),  # fast, locked
    (0.3, 16.7, dict(slip_stiffness=None, pressure_distribution={"sakai_n": 4},       # Sakai's law, ribs
                     grooves=tread.Grooves(width=10e-3, pitch=40e-3, angle_deg=90.0))),
])
def test_smooth_road_gives_mu_loc_exactly(slip, speed, kw):
    r = tread.simulate(tire(**kw), flat_road(rows=2), materials.example_tread(), speed=speed, slip=slip,
                       mu_loc=0.37, element_size=4e-4)
    # rigid elements (the paper's equations as written): every contacting element slides, mu = mu_loc
    assert abs(r.mu - 0.37) < 1e-12
    assert np.all(np.abs(r.mu_t[r.time > r.transient] - 0.37) < 1e-12)
    assert r.load_residual < 1e-9
    assert r.contact_fraction > 0.9


SIN_A, SIN_PERIODS, SIN_V = 50e-6, 32, 10.0
K_AREA, C_AREA = 1e9, 2e4          # Pa/m and Pa s/m per unit area: C/K = 20 us, omega C/K = 0.31


def sinusoid_run(per_element, damping):
    """Locked wheel (every element slides at V) on h = a sin(kx) whose period fits 32 times in the footprint;
    10 elements per period, ``per_element`` road elements per tread element."""
    t = tire(slip_stiffness=None, pressure_distribution="uniform")
    L = t.footprint.length
    lam = L / SIN_PERIODS
    es = lam / 10
    dx = es / per_element
    k = 2 * math.pi / lam
    x = np.arange(int(round(0.3 / dx)) + 1) * dx
    road = tread.Road(SIN_A * np.sin(k * x)[None, :], dx)
    r = tread.simulate(t, road, ELASTIC, speed=SIN_V, slip=1.0, mu_loc=0.0, stiffness=K_AREA, damping=damping,
                       element_size=es)
    C = damping * es * t.footprint.width
    F0 = t.load / (10 * SIN_PERIODS)
    return r, C * SIN_A ** 2 * (k * SIN_V) * k / (2 * F0)


def test_sinusoid_hysteresis_matches_closed_form_at_second_order():
    r1, mu1 = sinusoid_run(4, C_AREA)                                   # 40 road elements per period
    r2, mu2 = sinusoid_run(8, C_AREA)                                   # 80
    assert r1.contact_fraction == 1.0 and r2.contact_fraction == 1.0      # never loses contact
    e1, e2 = abs(r1.mu / mu1 - 1), abs(r2.mu / mu2 - 1)
    assert e2 < 3e-3
    assert 3.5 < e1 / e2 < 4.5                                            # second order
    assert r2.load_residual < 1e-9


def test_sinusoid_without_damping_has_no_friction():
    r, mu_cf = sinusoid_run(2, 0.0)
    assert mu_cf == 0.0
    assert abs(r.mu) < 1e-12 and np.max(np.abs(r.mu_t)) < 1e-12
    assert r.contact_fraction == 1.0


def test_element_leaving_contact_relaxes_exponentially():
    # a flat road with a 5 mm deep cliff: the leading element falls off it and relaxes freely
    dx, n = 1e-4, 4000
    z = np.zeros((1, n))
    z[0, 500:] = -5e-3
    n_elem, dt, V = 400, dx / 10.0, 10.0
    K, C = 2.0e4, 0.5                                   # C/K = 25 us: a few steps of 10 us
    _, _, _, residual, _, _, u, _, _ = kernels.march(
        z=z, tan_alpha=np.gradient(z, dx, axis=1), dx_road=dx, x_start=n_elem * dx + dx, n_steps=2000, dt=dt,
        v_slide=V, v_roll=0.0, n_elem=n_elem, dx_elem=dx, land=np.ones((1, n_elem + 2002), dtype=bool),
        shape=np.ones(11), offset_scale=0.0, stiffness=K, damping=C, shear_stiffness=np.inf, area=1e-5,
        load=100.0, load_total=100.0, p0=0.0, dp=1.0, mu_table=np.array([0.0]), jam_min=0.1, probe=0)
    fall = int(np.argmax(u[1:] < 0.9 * u[:-1])) + 1     # first step off the road
    assert u[fall - 1] > 0
    t = np.arange(30) * dt
    np.testing.assert_allclose(u[fall:fall + 30], u[fall - 1] * np.exp(-K * (t + dt) / C), rtol=1e-12)
    assert residual < 1e-9


def test_load_balance_holds_at_every_step(rough):
    t = tire(grooves=tread.Grooves(width=8e-3, pitch=30e-3, angle_deg=30.0))
    for slip, speed, water in ((0.05, 2.0, None), (1.0, 30.0, tread.Water(thickness=1.5e-3))):
        r = tread.simulate(t, rough, materials.example_tread(), speed=speed, slip=slip, mu_loc=0.6, water=water,
                           element_size=4e-4)
        assert r.load_residual < 1e-9
        assert 0 < r.contact_fraction < 1
        assert np.isfinite(r.mu) and r.mu_std > 0


def test_elastic_elements_on_a_smooth_road_are_the_brush_model():
    t = tire(pressure_distribution="parabolic")
    mu = 0.6
    theta_sl = 6 * mu / (2 * t.slip_stiffness)          # 6 mu sigma0 / (k l) with k = 2 sigma0 C / (F l)
    for s in (0.01, 0.03, 0.05, 0.2):
        theta = s / (1 - s)
        lam = max(0.0, 1 - theta / theta_sl)
        expected = mu * (1 - lam ** 3)
        r = tread.simulate(t, flat_road(length=0.45), ELASTIC, speed=16.7, slip=s, mu_loc=mu, damping=0.0,
                           element_size=1e-4)
        assert r.mu == pytest.approx(expected, rel=1e-3)


def test_kernel_parameters_are_all_documented():
    for fn in (kernels.march, kernels.march_points, kernels.block_mean):
        # cleandoc: Python 3.13 strips a docstring's indentation when it compiles it, earlier versions keep it
        doc = inspect.cleandoc(fn.__doc__)
        params = doc.split("Parameters\n----------\n", 1)[1].split("Returns\n", 1)[0]
        documented = set()
        for line in params.splitlines():
            if line and not line.startswith(" ") and " : " in line:
                documented.update(n.strip() for n in line.split(" : ")[0].split(","))
        names = list(inspect.signature(fn.py_func).parameters)
        assert documented == set(names), fn.__name__


def test_corners_glassy_cold_fast_and_soft_hot_slow(rough):
    """The compound near its glass transition (-30 C at 30 m/s: E' about a thousand times its rubbery value) barely
    yields to the road; hot and slow (80 C, 0.5 m/s sliding) it is soft and conforms. The march stays exact."""
    t = tire()
    cold = tread.simulate(t, rough, materials.example_tread(), speed=30.0, slip=1.0, temperature=-30.0,
                          mu_loc=0.5, element_size=4e-4)
    hot = tread.simulate(t, rough, materials.example_tread(), speed=5.0, slip=0.1, temperature=80.0,
                         mu_loc=0.5, element_size=4e-4)
    assert cold.stiffness > 100 * hot.stiffness
    assert cold.contact_fraction < 0.5 * hot.contact_fraction
    assert cold.penetration < hot.penetration
    for r in (cold, hot):
        assert r.load_residual < 1e-9 and np.isfinite(r.mu) and r.mu > 0


def test_flanks_past_the_self_locking_limit_carry_a_force_set_by_the_cap():
    """Eq. 2 on a flank with tan(alpha) >= 1/mu_loc has no finite tangential force (a self-locking wedge); the
    march caps the denominator at jam_min and books that force apart. Every element on the same slope t, rigid in
    shear, elastic: mu = (t + mu_loc)/(1 - mu_loc t) below the limit, (t + mu_loc)/jam_min past it, all booked."""
    dx, n_elem = 1e-4, 200
    n = 2000
    z = np.zeros((1, n))
    for t, jam_min in ((1.0, 0.1), (3.0, 0.1), (3.0, 0.2)):
        mu_t, _, _, residual, jammed, _, _, _, jam_t = kernels.march(
            z=z, tan_alpha=np.full((1, n), t), dx_road=dx, x_start=n_elem * dx + dx, n_steps=500, dt=dx / 10.0,
            v_slide=10.0, v_roll=0.0, n_elem=n_elem, dx_elem=dx, land=np.ones((1, n_elem + 502), dtype=bool),
            shape=np.ones(11), offset_scale=0.0, stiffness=2.0e4, damping=0.0, shear_stiffness=np.inf, area=1e-5,
            load=100.0, load_total=100.0, p0=0.0, dp=1.0, mu_table=np.array([0.5]), jam_min=jam_min, probe=-1)
        den = 1.0 - 0.5 * t
        if den >= jam_min:
            np.testing.assert_allclose(mu_t, (t + 0.5) / den, rtol=1e-12)
            assert jammed == 0.0 and np.all(jam_t == 0.0)
        else:
            np.testing.assert_allclose(mu_t, (t + 0.5) / jam_min, rtol=1e-12)
            np.testing.assert_allclose(jam_t, mu_t, rtol=1e-12)
            assert jammed == 1.0
        assert residual < 1e-9


def test_a_flat_face_rests_on_the_upper_envelope_of_the_road():
    """contact_surface against the closed form for h = a sin(kx): the face of length l touches the crest while one
    lies under it, else the higher of its two ends; its slope is the chord of that envelope across the face."""
    a, lam, dx = 50e-6, 2e-3, 1e-6
    x = np.arange(6001) * dx
    road = tread.Road((a * np.sin(2 * np.pi * x / lam))[None, :], dx)
    face = 0.4e-3
    z_e, tan_e = tread.contact_surface(road, face)

    def envelope(xs):
        lo, hi = xs - face / 2, xs + face / 2
        crest = np.floor((hi - lam / 4) / lam) * lam + lam / 4 >= lo
        return np.where(crest, a, a * np.maximum(np.sin(2 * np.pi * lo / lam), np.sin(2 * np.pi * hi / lam)))

    inner = slice(400, -400)
    np.testing.assert_allclose(z_e[0, inner], envelope(x[inner]), atol=a * (2 * np.pi * dx / lam) ** 2)
    chord = (envelope(x + face / 2) - envelope(x - face / 2)) / face
    np.testing.assert_allclose(tan_e[0, inner], chord[inner], atol=4 * a * (2 * np.pi / lam) * dx / face)
    # a slot narrower than the face is bridged: the element never sees it
    slot = np.zeros((1, 4001))
    slot[0, 2000:2003] = -1e-3
    z_s, tan_s = tread.contact_surface(tread.Road(slot, 1e-4), 5e-4)
    assert np.all(z_s == 0.0) and np.all(tan_s == 0.0)
    # without a face: the road itself
    z0, t0 = tread.contact_surface(road, None)
    assert z0 is road.z and np.array_equal(t0, road.slope)
