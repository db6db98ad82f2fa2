"""Strain-dependent modulus at every length scale (the Payne effect inside the Persson integrals).

Each scale q sees E' f(eps(q), T) and E'' g(eps(q), T) with the local strain eps(q) = kappa xi(q), xi(q) the rms
slope of the roughness up to q (StrainSoftening with measured StrainFactors).
"""

import math

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.effects import FlashTemperature, StrainSoftening
from persson.engine.reference import reference_friction

ROAD = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3)
TREAD = materials.example_tread()


def softening_sweep():
    """Synthetic strain sweeps: E' falls to 30 % and E'' to 60 % of their linear values around 10 % strain, a little
    less at 60 C than at 0 C (filled rubber, Payne effect)."""
    strain = np.geomspace(1e-4, 3.0, 40)
    T = np.array([0.0, 60.0])
    f = np.array([0.3 + 0.7 / (1.0 + (strain / 0.1) ** 1.2), 0.4 + 0.6 / (1.0 + (strain / 0.1) ** 1.2)])
    g = np.array([0.6 + 0.4 / (1.0 + (strain / 0.1)), 0.7 + 0.3 / (1.0 + (strain / 0.1))])
    return materials.StrainFactors(strain, T, f, g, source="synthetic")


def rms_slope_up_to(q):
    """xi(q) of the self-affine road in closed form: xi^2 = 2 pi C0 (q^(2-2H) - q0^(2-2H)) / (2 - 2H)."""
    H = ROAD.hurst
    return np.sqrt(2 * math.pi * ROAD.C0 * (q ** (2 - 2 * H) - ROAD.q0 ** (2 - 2 * H)) / (2 - 2 * H))


def test_constant_factors_at_every_scale_equal_the_constant_softening():
    """A flat strain sweep (the same factors at every strain) is the constant large-strain modulus of old."""
    v = np.array([1e-4, 1e-2, 1.0, 10.0])
    flat = StrainSoftening(factors=materials.StrainFactors.constant(0.3, 0.6))
    const = StrainSoftening(storage_factor=0.3, loss_factor=0.6)
    for extra in ((), (FlashTemperature(),)):
        a = persson.Model(ROAD, TREAD, effects=(flat,) + extra).friction(v, temperature=20.0, pressure=0.3e6)
        b = persson.Model(ROAD, TREAD, effects=(const,) + extra).friction(v, temperature=20.0, pressure=0.3e6)
        np.testing.assert_allclose(a.mu_hysteresis, b.mu_hysteresis, rtol=1e-8)
        np.testing.assert_allclose(a.contact_area, b.contact_area, rtol=1e-8)


@pytest.mark.parametrize("v, T", [(1e-2, 0.0), (1.0, 20.0), (30.0, 60.0)])
def test_per_scale_modulus_matches_an_independent_quadrature(v, T):
    sweep = softening_sweep()

    def factors(q):
        f, g = sweep.factors(0.5 * rms_slope_up_to(q), T)
        return float(f), float(g)

    ref = reference_friction(ROAD, TREAD, v, T, 0.3e6, modulus_factors=factors)
    r = persson.Model(ROAD, TREAD, effects=[StrainSoftening(factors=sweep)]).friction(v, temperature=T,
                                                                                     pressure=0.3e6)
    assert r.mu_hysteresis == pytest.approx(ref.mu[0], rel=1e-3)
    assert r.contact_area == pytest.approx(ref.contact_area[0], rel=1e-3)


def test_per_scale_softening_lies_between_the_linear_and_the_fully_softened_modulus():
    """The local strain grows from 0 at q0 to kappa xi(q1): the friction lies between the linear modulus and the
    modulus softened at the largest strain everywhere."""
    sweep = softening_sweep()
    eps_max = 0.5 * rms_slope_up_to(ROAD.q1)
    f_max, g_max = (float(x) for x in sweep.factors(eps_max, 20.0))
    v = np.array([1e-3, 1e-1, 3.0])
    lin = persson.Model(ROAD, TREAD).friction(v, temperature=20.0, pressure=0.3e6)
    per_scale = persson.Model(ROAD, TREAD, effects=[StrainSoftening(factors=sweep)]).friction(
        v, temperature=20.0, pressure=0.3e6)
    full = persson.Model(ROAD, TREAD, effects=[StrainSoftening(storage_factor=f_max, loss_factor=g_max)]).friction(
        v, temperature=20.0, pressure=0.3e6)
    # softer rubber: more contact area at every speed, ordered like the modulus
    assert np.all(lin.contact_area < per_scale.contact_area)
    assert np.all(per_scale.contact_area < full.contact_area)


def test_strain_per_slope_scales_the_local_strain():
    """Only kappa xi(q) enters: doubling kappa on a sweep whose strain axis is doubled changes nothing."""
    sweep = softening_sweep()
    stretched = materials.StrainFactors(2.0 * sweep.strain, sweep.T_C, sweep.storage_factor, sweep.loss_factor)
    v = np.array([1e-2, 1.0])
    a = persson.Model(ROAD, TREAD, effects=[StrainSoftening(factors=sweep, strain_per_slope=0.5)]).friction(
        v, pressure=0.3e6)
    b = persson.Model(ROAD, TREAD, effects=[StrainSoftening(factors=stretched, strain_per_slope=1.0)]).friction(
        v, pressure=0.3e6)
    np.testing.assert_allclose(a.mu_hysteresis, b.mu_hysteresis, rtol=1e-10)
    # and a larger kappa means larger strains, softer rubber, more contact
    c = persson.Model(ROAD, TREAD, effects=[StrainSoftening(factors=sweep, strain_per_slope=1.0)]).friction(
        v, pressure=0.3e6)
    assert np.all(c.contact_area > a.contact_area)


def test_flash_temperature_with_per_scale_modulus_converges():
    sweep = softening_sweep()
    model = persson.Model(ROAD, TREAD, effects=[StrainSoftening(factors=sweep), FlashTemperature()])
    r = model.friction(np.array([1e-3, 0.3, 10.0]), temperature=20.0, pressure=0.3e6)
    assert r.converged and np.all(r.error_estimate < 1e-3)
    assert np.all(np.isfinite(r.mu)) and np.all(r.max_flash_temperature >= 0)


def test_bad_factors_are_refused():
    with pytest.raises(persson.InputError, match="strain_softening.factors"):
        StrainSoftening(factors=[0.3, 0.6])
