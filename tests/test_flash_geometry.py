"""The macro-asperity geometry of the flash temperature is a property of the surface, not of the scan length."""

import math

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.effects import FlashTemperature

TREAD = materials.example_tread()
V = np.array([0.1, 1.0, 10.0])


C0 = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3).C0


def road(scan_length):
    """A road with a 5 mm roll-off, measured by a scan of the given length (the plateau starts at 2 pi / L)."""
    return surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, C0=C0, qL=2 * math.pi / scan_length)


def test_a_longer_scan_does_not_change_the_hot_spots():
    short = persson.Model(road(0.02), TREAD, effects=[FlashTemperature()]).friction(V, pressure=0.3e6)
    long = persson.Model(road(0.4), TREAD, effects=[FlashTemperature()]).friction(V, pressure=0.3e6)
    # the plateau below the roll-off adds a little long-wavelength roughness; the hot spots stay the same
    np.testing.assert_allclose(long.max_flash_temperature, short.max_flash_temperature, rtol=0.01)
    np.testing.assert_allclose(long.mu_hysteresis, short.mu_hysteresis, rtol=0.01)


def test_macro_asperity_diameter_follows_the_roll_off():
    """d = pi / q_m with q_m = 2 q_roll-off: the same as giving that diameter explicitly."""
    s = road(0.4)
    d = math.pi / (2.0 * s.q0)
    a = persson.Model(s, TREAD, effects=[FlashTemperature()]).friction(V, pressure=0.3e6)
    b = persson.Model(s, TREAD, effects=[FlashTemperature(contact_diameter=d)]).friction(V, pressure=0.3e6)
    np.testing.assert_allclose(a.mu, b.mu, rtol=1e-12)
    assert d == pytest.approx(1.25e-3)


def test_smaller_hot_spots_cool_faster_and_rub_harder_at_high_speed():
    s = road(0.1)
    big = persson.Model(s, TREAD, effects=[FlashTemperature(contact_diameter=5e-3)]).friction(10.0, pressure=0.3e6)
    small = persson.Model(s, TREAD, effects=[FlashTemperature(contact_diameter=0.2e-3)]).friction(10.0,
                                                                                                  pressure=0.3e6)
    assert small.max_flash_temperature < big.max_flash_temperature
    assert small.mu > big.mu


def test_a_table_without_roll_off_says_where_its_scale_comes_from():
    q = np.geomspace(2 * math.pi / 0.4, 1e6, 200)
    table = surfaces.PSD(q, road(0.4).C(q))
    r = persson.Model(table, TREAD, effects=[FlashTemperature()]).friction(1.0, pressure=0.3e6)
    assert any("no roll-off" in n for n in r.notes)
    declared = surfaces.PSD(q, road(0.4).C(q), q_rolloff=2 * math.pi / 5e-3)
    r2 = persson.Model(declared, TREAD, effects=[FlashTemperature()]).friction(1.0, pressure=0.3e6)
    assert not any("no roll-off" in n for n in r2.notes)
    ref = persson.Model(road(0.4), TREAD, effects=[FlashTemperature()]).friction(1.0, pressure=0.3e6)
    assert r2.mu == pytest.approx(ref.mu, rel=2e-3)


def test_adhesion_peak_speed_can_be_given_at_the_test_temperature():
    """v_ref at 60 C equals v_ref / a_T(60 C) at the reference temperature (20 C)."""
    from persson.effects import Adhesion

    aT = float(TREAD.wlf.aT(60.0))
    a = Adhesion(v_ref=1e-3, v_ref_temperature=60.0)
    b = Adhesion(v_ref=1e-3 * aT)
    v = np.geomspace(1e-6, 10, 7)
    for T in (0.0, 60.0):
        np.testing.assert_allclose(a.shear_stress(v, T, TREAD), b.shear_stress(v, T, TREAD), rtol=1e-12)
    # at its own temperature the peak sits at v_ref
    assert a.shear_stress(1e-3, 60.0, TREAD) == pytest.approx(a.tau_f0)
    with pytest.raises(persson.InputError, match="v_ref_temperature"):
        Adhesion(v_ref_temperature="hot")
