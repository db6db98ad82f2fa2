"""Slip curves at road speeds against published behaviour, and the pieces that make them: the tread stiffness from
the compound, the model with both kinds of frictional heating, the patch temperature feeding the flash.

The realistic case is :func:`persson.slip.example_road_case` (a passenger-car tire on a dry asphalt of rms slope
1.38, a filled tread compound, patch heating with the flash temperature, adhesion), on a coarser grid than the
documented one (the numbers agree within 0.002 in mu; ``benchmarks/slip_realism.py`` prints the fine ones). The
targets are published ones:

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

import materials
import persson
from persson import slip as ps

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

@pytest.mark.xfail(strict=True, reason="peak mu 0.33-0.36 at 0.4-3.4 % slip (fine grid, 0-40 C, 20-100 km/h): "
                   "the hysteresis and adhesion of the theory on a road of rms slope 1.38 stay near 0.3, and the "
                   "tread brush from the compound alone (initial slope 43-390) is 2-20 times stiffer than a tire")
def test_peak_between_0_9_and_1_3_at_8_to_20_percent_slip(curves):
    for pk, at, _ in curves.values():
        assert 0.9 <= pk <= 1.3 and 0.08 <= at <= 0.20


@pytest.mark.xfail(strict=True, reason="locked/peak 0.91 at 20 km/h and 20 C (0.83 at 100 km/h)")
def test_locked_wheel_between_0_65_and_0_9_of_the_peak_on_a_dry_road(curves):
    for pk, _, locked in curves.values():
        assert 0.65 <= locked / pk <= 0.90


def test_peak_and_locked_fall_with_speed(curves):
    slow, fast = curves[20.0, KMH20], curves[20.0, KMH100]
    assert fast[0] < slow[0] and fast[2] < slow[2]
    assert (slow[2] - fast[2]) / slow[2] > 0.05          # the locked wheel loses most: it slides fastest


def test_peak_falls_with_road_temperature_within_published_rates(curves):
    cold, warm, hot = (curves[T0, KMH20][0] for T0 in (0.0, 20.0, 40.0))
    assert hot < warm < cold
    rate = (hot - cold) / warm / 40.0                    # per K
    assert -0.006 <= rate < 0.0
