"""What the tread-element tool must reproduce (the paper's Sections 4.1-4.2 and Fig. 9), on synthetic roads.

* the ABS peak between 10 and 20 % slip and the fall to the locked wheel; locked-wheel friction falling with speed
  (with the Persson engine's local friction, flash temperature on);
* wet below dry, more so at speed and on a road with little macrotexture (the pseudo-hydrodynamic bearing);
  adhesion taken out of mu_loc when wet;
* more captured microtexture, more friction;
* convergence of the steady mu in the time step and in the element size;
* the pseudo-bearing formula (Eq. 7) against the load of the slider from Reynolds' equation (the pressure in
  closed form, its integral by quadrature).
"""

import math

import numpy as np
import pytest
from scipy import integrate

import materials
import surfaces
from persson import effects, tread

TREAD = materials.example_tread()


def tire(**kw):
    args = dict(diameter=0.63, width=0.205, load=4000.0, inflation_pressure=2.2e5, tread_depth=8e-3)
    args.update(kw)
    return tread.Tire(**args)


def road(hrms, length=0.6, seed=1, dx=1e-4):
    sa = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=hrms, qL=2 * math.pi / 0.1)
    n = int(round(length / dx))
    return tread.as_road(surfaces.synthesize_profiles(sa, n_profiles=1, n=n, length=length, seed=seed))


@pytest.fixture(scope="module")
def dry_map():
    rd = road(0.15e-3)
    t = tire(grooves=tread.Grooves(width=8e-3, pitch=30e-3))
    slips = [0.05, 0.1, 0.15, 0.2, 0.5, 1.0]
    speeds = [8.3, 25.0]
    local = tread.local_friction(rd, TREAD, speeds=[0.05 * 8.3, 25.0], q1=1e7,
                                 effects=[effects.FlashTemperature()])
    return tread.slip_map(t, rd, TREAD, slips=slips, speeds=speeds, mu_loc=local, element_size=4e-4)


def test_abs_peak_between_10_and_20_percent_then_fall_to_locked(dry_map):
    m = dry_map
    fast = 1
    assert 0.1 <= m.peak_slip[fast] <= 0.2
    err = math.hypot(m.peak_std[fast], m.locked_std[fast])
    assert m.locked_mu[fast] < m.peak_mu[fast] - 3 * err
    # the rise: the brush's stick zone below the peak
    assert m.mu[fast, 0] < m.peak_mu[fast] - 3 * err


def test_locked_wheel_friction_falls_with_speed(dry_map):
    m = dry_map
    assert m.locked_mu[1] < m.locked_mu[0] - 3 * math.hypot(*m.locked_std)


@pytest.fixture(scope="module")
def wet_dry():
    """Locked wheel of a slick on a fine and a coarse road, dry and under 1 mm of water (constant mu_loc: the
    difference is the bearing alone)."""
    t = tire()
    out = {}
    for name, hrms in (("fine", 0.05e-3), ("coarse", 0.4e-3)):
        rd = road(hrms, length=0.45, seed=2)
        for V in (8.3, 25.0):
            dry = tread.simulate(t, rd, TREAD, speed=V, slip=1.0, mu_loc=0.5, element_size=4e-4)
            wet = tread.simulate(t, rd, TREAD, speed=V, slip=1.0, mu_loc=0.5, element_size=4e-4,
                                 water=tread.Water(thickness=1e-3))
            out[name, V] = (dry, wet)
    return out


def test_wet_below_dry_more_so_at_speed_and_with_little_macrotexture(wet_dry):
    penalty = {k: d.mu - w.mu for k, (d, w) in wet_dry.items()}
    assert all(p > 0 for p in penalty.values())
    assert penalty["fine", 25.0] > 2 * penalty["fine", 8.3]               # the lift grows with speed
    assert penalty["fine", 25.0] > 4 * penalty["coarse", 25.0]            # the texture drains the film
    d, w = wet_dry["fine", 25.0]
    assert w.lift > 0.01 * 4000.0 and w.mu == pytest.approx(d.mu * (1 - w.lift / 4000.0), rel=0.05)


def test_wet_local_friction_has_no_adhesion():
    rd = road(0.15e-3, length=0.3)
    dry = tread.local_friction(rd, TREAD, speeds=[0.01, 1.0])
    wet = tread.local_friction(rd, TREAD, speeds=[0.01, 1.0], wet=True)
    assert wet.wet and np.all(wet.mu < dry.mu)
    assert dry.extrapolated and any("extrapolated" in n for n in dry.notes)


def test_more_microtexture_more_friction():
    rd = road(0.15e-3, length=0.4)
    q0 = math.pi / rd.dx
    mus = []
    for hrms_micro in (2e-6, 8e-6):
        micro = surfaces.SelfAffine(hurst=0.8, q0=q0, q1=1e6, hrms=hrms_micro)
        r = tread.simulate(tire(), rd, TREAD, speed=16.7, slip=1.0, microtexture=micro, element_size=4e-4)
        mus.append(r.mu)
    assert mus[1] > mus[0] + 0.05


def test_steady_mu_converges_in_time_step_and_element_size():
    rd = road(0.15e-3, length=0.45, seed=3)
    t = tire()
    for slip in (0.15, 1.0):
        by_dt = [tread.simulate(t, rd, TREAD, speed=16.7, slip=slip, mu_loc=0.5, courant=c, element_size=4e-4).mu
                 for c in (1.0, 0.5, 0.25)]
        assert abs(by_dt[1] - by_dt[2]) <= abs(by_dt[0] - by_dt[2]) + 1e-12
        assert abs(by_dt[1] - by_dt[2]) < 3e-3 * by_dt[2]
    # the element size matters where elements adhere (the rolling part of the footprint): at slip 0.15
    by_size = [tread.simulate(t, rd, TREAD, speed=16.7, slip=0.15, mu_loc=0.5, element_size=es).mu
               for es in (4e-4, 2e-4, 1e-4)]
    assert abs(by_size[1] - by_size[2]) < 5e-3 * by_size[2]


def test_bearing_formula_is_the_slider_of_reynolds_equation():
    eta, U, L, width = 1.0e-3, 20.0, 0.1, 0.15
    for h_in, h_out in ((2e-3, 1e-3), (1e-3, 1e-4), (1.0015e-3, 1e-3)):
        def gap(x):
            return h_in + (h_out - h_in) * x / L

        m = (h_out - h_in) / L                                # dh/dx

        def int_pow(n, x):                                    # integral of h^-n from 0 to x, in closed form
            return (gap(x) ** (1 - n) - h_in ** (1 - n)) / ((1 - n) * m)

        h_star = int_pow(2, L) / int_pow(3, L)               # p(0) = p(L) = 0

        def pressure(x):
            return 6 * eta * U * (int_pow(2, x) - h_star * int_pow(3, x))

        load = width * integrate.quad(pressure, 0, L, epsabs=0, epsrel=1e-12, limit=200)[0]
        got = tread.bearing_lift(U, viscosity=eta, length=L, width=width, inlet=h_in, outlet=h_out)
        assert float(got) == pytest.approx(load, rel=1e-6)
    assert float(tread.bearing_lift(U, viscosity=eta, length=L, width=width, inlet=1e-3, outlet=1e-3)) == 0.0
