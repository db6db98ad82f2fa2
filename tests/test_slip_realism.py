"""Slip curves at road speeds against published behaviour, and the pieces that make them: the tread stiffness from
the compound, the model with both kinds of frictional heating, the patch temperature feeding the flash.

The realistic case is :func:`persson.slip.example_road_case` (a passenger-car tire on a dry asphalt of rms slope
1.38, a filled tread compound on the carcass of a measured tire, patch heating with the flash temperature, adhesion),
on a coarser grid than the documented one (the numbers agree within 0.002 in mu; ``benchmarks/slip_realism.py``
prints the fine ones). The targets are published ones:

* peak mu 0.9-1.3 at 8-20 % slip and a locked wheel at 0.65-0.9 of the peak on a dry road: Pacejka's Magic
  Formula for a dry tarmac (peak 1.00 at 18 %, locked 0.91 of it) and Burckhardt's dry asphalt (1.17 at 17 %,
  0.65 of it);
* peak and locked mu falling from 20 to 100 km/h;
* the peak falling with the road temperature by no more than 0.6 % per K (UNECE Regulation 117 corrects its
  reference tyre's peak braking coefficient by about 0.2 % per K).

Where the model misses a target, the test says so (``xfail(strict=True)`` with the numbers): the target stays
written down and a change that meets it shows up.
"""

import math
import warnings

import numpy as np
import pytest
from scipy import integrate, optimize
from scipy.special import erf

import materials
import persson
from persson import slip as ps
from persson.slip import road

KMH20, KMH100 = 20 / 3.6, 100 / 3.6
SLIPS = np.concatenate([np.geomspace(0.002, 0.3, 16), [0.5, 1.0]])


@pytest.fixture(scope="module")
def case():
    grid = persson.GridSettings(q_per_decade=12, n_phi=16, omega_per_decade=20, tolerance=1e-2, temperature_step=1.0)
    heating = ps.PatchHeating(points_per_decade=2, n_pressure=4, temperature_points_per_decade=2)
    return ps.example_road_case(grid=grid, patch_heating=heating)


@pytest.fixture(scope="module")
def results(case):
    """{(T0, V): SlipResult}."""
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", persson.AccuracyWarning)      # the coarse grid of this test
        for T0, speeds in ((20.0, (KMH20, KMH100)), (0.0, (KMH20,)), (40.0, (KMH20,))):
            for V, r in zip(speeds, case.curves(SLIPS, speeds, T0, n_points=101, profiles=True)):
                out[T0, V] = r
    return out


@pytest.fixture(scope="module")
def curves(results):
    """{(T0, V): (peak mu, slip at peak, locked mu)}."""
    out = {}
    for key, r in results.items():
        pk, at = r.peak()
        out[key] = (float(pk), float(at), float(r.mu[-1]))
    return out


# ---------------------------------------------------------------------------------------------- the inputs

def test_the_compound_has_the_dma_of_a_filled_passenger_car_tread():
    m = materials.example_tire_tread()
    w = 2 * math.pi * 10.0
    T = np.arange(-40.0, 101.0, 1.0)
    E = m.E(w, T)
    tan = E.imag / E.real
    assert -15.0 <= T[np.argmax(tan)] <= -5.0 and 0.5 < tan.max() < 0.7           # glass transition at 10 Hz
    assert 0.35 < tan[T == 0.0][0] < 0.5 and 0.05 < tan[T == 60.0][0] < 0.15         # wet-grip and rolling indicators
    assert 8e6 < E.real[T == 20.0][0] < 15e6 and 4e6 < E.real[T == 60.0][0] < 7e6
    assert m.wlf.T_upper == 75.0                                                     # T_g + 100 K


def test_tread_stiffness_is_shear_and_bending_of_the_block():
    G = 2.0e6
    rubber = materials.ConstantModulus(E_storage=3 * G, E_loss=0.0)
    squat = ps.Tread(depth=8e-3, block_length=25e-3, land_ratio=0.7)
    k = squat.stiffness(rubber, speed=20.0, temperature=20.0, contact_length=0.12)
    assert k == pytest.approx(0.7 * G / 8e-3 / (1 + (8 / 25) ** 2 / 3), rel=1e-12)
    # a tall, slender block is a guided beam in bending: k -> E b^2 / h^3 (12 E I / h^3 per area b w)
    tall = ps.Tread(depth=0.3, block_length=0.01)
    k_beam = 3 * G * 0.01 ** 2 / 0.3 ** 3
    assert tall.stiffness(rubber, speed=20.0, temperature=20.0, contact_length=0.12) == pytest.approx(k_beam,
                                                                                                      rel=4e-3)
    # from the compound: stiffer at higher speed (loading frequency pi V / l) and in the cold
    tread, m = ps.Tread(depth=8e-3, block_length=25e-3), materials.example_tire_tread()
    k20, k100 = (tread.stiffness(m, speed=V, temperature=20.0, contact_length=0.12) for V in (KMH20, KMH100))
    assert k100 > k20 > tread.stiffness(m, speed=KMH20, temperature=40.0, contact_length=0.12)
    c = ps.Contact.from_tread(0.12, 0.15, tread, m, speed=KMH20, temperature=20.0)
    assert c.stiffness == k20
    with pytest.raises(persson.InputError, match="land_ratio"):
        ps.Tread(depth=8e-3, block_length=25e-3, land_ratio=1.5)


def test_the_carcass_is_a_spring_in_series_with_the_tread_that_gives_a_tire_its_slip_stiffness(case):
    m, tread = case.model.material, case.tread
    k_t = tread.stiffness(m, speed=KMH20, temperature=20.0, contact_length=0.12)
    c = ps.Contact.from_tread(0.12, 0.15, tread, m, speed=KMH20, temperature=20.0, carcass_stiffness=1e8)
    assert c.stiffness == pytest.approx(k_t * 1e8 / (k_t + 1e8), rel=1e-12)
    # the measured tire (Pacejka 2006, Table A3.1): K/Fz = (PKX1 + PKX2 dfz) exp(PKX3 dfz), dfz = (Fz - 4 kN)/4 kN
    assert road.tire_slip_stiffness() == 21.51
    dfz = (5400.0 - 4000.0) / 4000.0
    assert road.tire_slip_stiffness(5400.0) == pytest.approx((21.51 - 0.163 * dfz) * math.exp(0.245 * dfz), rel=1e-14)
    # the case's carcass returns the tire's slope where it was taken from (60 km/h, tread at 20 C) ...
    tire = case.contact(road.TIRE_205_60R15["LONGVL"], 20.0)
    assert tire.initial_slope(case.pressure) == pytest.approx(road.tire_slip_stiffness(5400.0), rel=1e-12)
    # ... and the slopes of tires (15-30 times the load) at 0-40 C and 20-100 km/h, where the tread alone gives 43-390
    slopes = [case.contact(V, T).initial_slope(case.pressure) for V in (KMH20, KMH100) for T in (0.0, 20.0, 40.0)]
    alone = [ps.Contact.from_tread(0.12, 0.15, tread, m, speed=V, temperature=T).initial_slope(case.pressure)
             for V in (KMH20, KMH100) for T in (0.0, 20.0, 40.0)]
    assert 15.0 < min(slopes) and max(slopes) < 30.0 and min(alone) > 40.0
    with pytest.raises(persson.InputError, match="carcass_stiffness"):
        ps.Contact.from_tread(0.12, 0.15, tread, m, speed=KMH20, carcass_stiffness=0.0)
    with pytest.raises(persson.InputError, match="slope"):              # a tire stiffer than its tread
        road.carcass_stiffness(500.0, tread, m, length=0.12, pressure=0.3e6, speed=KMH20, temperature=20.0)


def test_the_measured_tire_peaks_where_its_coefficients_put_it():
    """Pacejka's 205/60R15 at its nominal load: B = K/(C D) = 21.51/(1.685 x 1.21), E = 0.344; the maximum of
    D sin(C arctan(phi)) is where phi(B s) = Bs - E(Bs - arctan Bs) = tan(pi/(2C))."""
    B, C, D, E = road.tire_magic_formula()
    assert (B, C, D, E) == pytest.approx((21.51 / (1.685 * 1.21), 1.685, 1.21, 0.344), rel=1e-14)
    x = optimize.brentq(lambda x: x - E * (x - math.atan(x)) - math.tan(math.pi / (2 * C)), 0.1, 10.0, xtol=1e-14)
    s = np.linspace(0.0, 1.0, 200001)
    pk, at = ps.peak(s, ps.magic_formula(s, B, C, D, E))
    assert float(pk) == pytest.approx(1.21, abs=1e-9) and float(at) == pytest.approx(x / B, abs=1e-5)
    assert 0.14 < x / B < 0.15 and 0.65 < float(ps.magic_formula(1.0, B, C, D, E)) / 1.21 < 0.67
    with pytest.raises(persson.InputError, match="load"):
        road.tire_magic_formula(2e5)


def test_persson_hysteresis_in_small_contact_is_about_gamma_times_slope_times_sin_delta(case):
    """Why the case's friction is near 0.3: for a modulus of constant phase delta, Persson's mu reduces to one integral
    over the rms slope xi, mu = 4 E''* sigma0/(pi |E*|^2) int_0^x1 x erf(1/x) S(erf(1/x)) dx, x1 = |E*| xi(q1) /
    (sqrt 2 sigma0), which tends to 4 sqrt(2)/pi^(3/2) gamma sin(delta) xi(q1) in small contact: 0.35 for the
    compound's largest tan delta (0.56) on the case's road (rms slope 1.38) with gamma = 0.5."""
    xi1, sigma0, Ep, tan = case.model.surface.rms_slope(), 0.3e6, 10e6, 0.56
    Es, El = abs(complex(Ep, Ep * tan)) / 0.75, Ep * tan / 0.75
    x1 = Es * xi1 / (math.sqrt(2) * sigma0)
    for gamma in (0.5, 1.0):
        def f(x, gamma=gamma):
            P = erf(1 / x) if x > 0 else 1.0
            return x * P * (gamma + (1 - gamma) * P * P)
        exact = 4 * El * sigma0 / (math.pi * Es**2) * integrate.quad(f, 0.0, x1, limit=400, epsrel=1e-12)[0]
        r = persson.Model(case.model.surface, materials.ConstantModulus(E_storage=Ep, E_loss=Ep * tan),
                          gamma=gamma).friction(1.0, temperature=20.0, pressure=sigma0)
        assert float(r.mu) == pytest.approx(exact, rel=1e-6)
        limit = 4 * math.sqrt(2) / math.pi**1.5 * gamma * math.sin(math.atan(tan)) * xi1
        assert float(r.mu) == pytest.approx(limit, rel=0.02)


def test_the_road_model_adds_both_heatings_and_keeps_explicit_models(case):
    model = case.model
    assert set(model.effect_names) == {"adhesion", "patch_heating", "flash_temperature"}
    mine = ps.PatchHeating(counter_effusivity=2400.0)
    again = ps.with_road_heating(persson.Model(model.surface, model.material, effects=[mine]))
    assert again.effect("patch_heating") is mine and "flash_temperature" in again.effect_names
    # an explicit model is used as given: the same numbers, and a note at road speeds that the heating is off
    plain = persson.Model(model.surface, model.material, grid=model.grid)
    contact = ps.Contact(0.12, 0.15, 1e8, n_points=101)
    fast = ps.mu_slip(plain, SLIPS[:4], KMH100, contact=contact)
    slow = ps.mu_slip(plain, SLIPS[:4], 1.0, contact=contact)
    brush = ps.mu_slip(lambda v: plain.friction(v).mu, SLIPS[:4], KMH100, contact=contact)
    np.testing.assert_array_equal(fast.mu, brush.mu)
    assert any("road_model" in n for n in fast.notes) and not any("road_model" in n for n in slow.notes)


def test_the_patch_background_temperature_feeds_the_flash(case, results):
    # the locked wheel at 100 km/h: the local friction where the patch is hottest is the engine's, flash included,
    # at the background temperature the patch reached there and the local pressure
    r = results[20.0, KMH100]
    T = r.patch.temperature[-1]
    j = int(np.argmax(T[:-1]))
    T_j, p_j = float(T[j]), float(r.patch.pressure[j])
    assert T_j > 60.0
    direct = case.model.without("patch_heating").friction(KMH100, temperature=T_j, pressure=p_j)
    assert float(r.patch.mu_local[-1, j]) == pytest.approx(float(direct.mu), rel=5e-3)
    assert float(direct.max_flash_temperature) > 20.0          # the flash rides on the hot background


# ---------------------------------------------------------------------------------------------- the targets

@pytest.mark.xfail(strict=True, reason="peak mu 0.29-0.33 at 2.7-5.1 % slip (fine grid, 0-40 C, 20-100 km/h; at "
                   "0 C and 60-100 km/h the curve stays flat to the locked wheel, maximum at 82-90 %): the hysteresis "
                   "(0.24) and adhesion (0.08 at 2 MPa) of the theory on a road of rms slope 1.38 stay near 0.3, and "
                   "the brush of a tire (initial slope 18-29) puts the peak of so low a friction at 3-5 % slip")
def test_peak_between_0_9_and_1_3_at_8_to_20_percent_slip(curves):
    for pk, at, _ in curves.values():
        assert 0.9 <= pk <= 1.3 and 0.08 <= at <= 0.20


@pytest.mark.xfail(strict=True, reason="locked/peak 0.80-1.00 (fine grid): 0.93 at 20 km/h and 20 C, 0.97 at 0 C")
def test_locked_wheel_between_0_65_and_0_9_of_the_peak_on_a_dry_road(curves):
    for pk, _, locked in curves.values():
        assert 0.65 <= locked / pk <= 0.90


def test_peak_and_locked_fall_with_speed(curves):
    slow, fast = curves[20.0, KMH20], curves[20.0, KMH100]
    assert fast[0] < slow[0] and fast[2] < slow[2]
    assert (slow[2] - fast[2]) / slow[2] > 0.05          # the locked wheel loses most: it slides fastest


@pytest.mark.xfail(strict=True, reason="peak 0.308 / 0.330 / 0.329 at 0 / 20 / 40 C (20 km/h, fine grid): with a "
                   "tire's slip stiffness the peak lies at 0.15-0.3 m/s sliding speed, where this compound's friction "
                   "is larger at 20 C than at 0 C (with the tread alone the peak lay at 1-2 cm/s and fell 0.357 -> "
                   "0.329)")
def test_peak_falls_with_road_temperature_within_published_rates(curves):
    cold, warm, hot = (curves[T0, KMH20][0] for T0 in (0.0, 20.0, 40.0))
    assert hot < warm < cold
    rate = (hot - cold) / warm / 40.0                    # per K
    assert -0.006 <= rate < 0.0
