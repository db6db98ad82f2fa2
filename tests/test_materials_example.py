"""materials.example_tread: a documented synthetic tread compound with the features the demo relies on."""

import numpy as np
import pytest

import materials


@pytest.fixture(scope="module")
def tread():
    return materials.example_tread()


def test_labelled_synthetic_and_thermal(tread):
    assert "synthetic" in tread.label
    th = tread.thermal
    assert isinstance(th, materials.Thermal)
    assert 1100 <= th.density <= 1200 and 1500 <= th.specific_heat <= 2000 and 0.2 <= th.conductivity <= 0.3


def test_plateaus_and_transition(tread):
    # rubbery plateau a few MPa (omega -> 0), glassy 1-3 GPa (omega -> inf)
    E0 = tread.E(0.0, 20.0)
    assert E0.imag == 0.0 and 1e6 <= E0.real <= 1e7
    Eg = tread.E(1e14, -40.0).real
    assert 1e9 <= Eg <= 3e9
    # Tg: the loss modulus at 1 Hz peaks between -40 and -20 C
    T = np.linspace(-70.0, 40.0, 1101)
    E = tread.E(2 * np.pi, T)
    assert -40.0 <= T[np.argmax(E.imag)] <= -20.0
    # transition several decades wide: E' rises 10 % -> 90 % of its log range over > 4 decades
    w = np.logspace(-4, 16, 2001)
    lE = np.log10(tread.E(w, 20.0).real)
    lo, hi = lE.min(), lE.max()
    x = np.log10(w)
    width = x[np.argmax(lE > lo + 0.9 * (hi - lo))] - x[np.argmax(lE > lo + 0.1 * (hi - lo))]
    assert width > 4.0


def test_vectorized_broadcast_odd_and_wlf(tread):
    w = np.array([-1e3, -1.0, 0.0, 1.0, 1e3])
    T = np.array([[-30.0], [20.0], [80.0]])
    E = tread.E(w, T)
    assert E.shape == (3, 5) and np.all(np.isfinite(E))
    np.testing.assert_allclose(E[:, ::-1].imag, -E.imag)       # Im E odd in omega
    np.testing.assert_allclose(E[:, ::-1].real, E.real)        # Re E even
    assert np.all(E[:, 2].imag == 0.0)
    # WLF with the universal constants at T_ref = 20 C: log10 aT(-30 C) = -8.86*(-50)/(101.6-50)
    assert tread.log10_aT(-30.0) == pytest.approx(8.86 * 50 / 51.6)
    # time-temperature superposition: E(w, T) = E(w aT, T_ref)
    np.testing.assert_allclose(tread.E(10.0, -10.0), tread.E(10.0 * 10 ** tread.log10_aT(-10.0), 20.0))


def test_extreme_inputs_finite(tread):
    E = tread.E(np.array([1e-300, 1e300, -1e300]), np.array([-81.0]))
    assert np.all(np.isfinite(E))
