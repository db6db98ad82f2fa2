"""Time-temperature superposition, WLF and Arrhenius fits: recovery of known shift factors from synthetic data."""

import math

import numpy as np
import pytest

import materials
from materials import InputError
from materials.dma import DMAData

C1, C2, T_REF = 8.86, 101.6, 20.0


def truth_prony():
    """A rubber-like generalized Maxwell solid: log-normal spectrum (1.7 decades) centred at 10^-10.5 s at 20 C,
    3 MPa rubbery, 2 GPa glassy, 3 relaxation times per decade from 10^-16 to 10^2 s (no truncation effects in the
    measured window), WLF with the universal constants."""
    lt = np.arange(-16, 2.001, 1 / 3)
    w = np.exp(-0.5 * ((lt + 10.5) / 1.7) ** 2)
    return materials.Prony(3e6, (2e9 - 3e6) * w / w.sum(), 10 ** lt, wlf=materials.WLF(C1, C2, T_REF))


def synthetic_dma(seed=0, noise=0.02, Ts=np.arange(-35.0, 61.0, 5.0), f=np.logspace(-1, 2, 16), bT=None):
    """Isotherms 0.1-100 Hz (5 per decade), 2 % Gaussian noise on E' and E'' independently."""
    rng = np.random.default_rng(seed)
    p = truth_prony()
    T = np.repeat(Ts, f.size)
    F = np.tile(f, Ts.size)
    E = p.E(2 * np.pi * F, T)
    if bT is not None:
        E = E * bT(T)
    E1 = E.real * (1 + noise * rng.standard_normal(E.size))
    E2 = E.imag * (1 + noise * rng.standard_normal(E.size))
    return p, DMAData.from_arrays(T, F, E1, E2, source="synthetic")


@pytest.fixture(scope="module")
def recovered():
    p, d = synthetic_dma(seed=3)
    return p, d, materials.master_curve(d, T_ref=T_REF)


# ---------------------------------------------------------------------------------------------- Must show

def test_synthetic_shift_factors_within_0p1_decade(recovered):
    p, d, m = recovered
    sf = m.shift_factors
    true = p.log10_aT(sf.T_C)
    err = np.abs(sf.log10_aT - true)
    # measured: max error about 0.01-0.05 decades (over 8 noise seeds)
    assert err.max() < 0.1, err
    assert sf.T_ref == T_REF and sf.converged
    # the steps span 4 decades between the coldest isotherms: wide bounds are needed
    assert np.max(-np.diff(sf.log10_aT)) > 1.5


def test_synthetic_wlf_constants_within_10_percent(recovered):
    _, _, m = recovered
    fit = m.wlf_fit
    assert fit.C1 == pytest.approx(C1, rel=0.10)
    assert fit.C2 == pytest.approx(C2, rel=0.10)
    # measured: both within 1 %; the covariance is positive definite and its errors cover the truth
    assert np.all(np.linalg.eigvalsh(fit.covariance) > 0)
    assert abs(fit.C1 - C1) < 5 * fit.stderr[0] + 0.01 * C1
    assert m.wlf.T_ref == T_REF


def test_synthetic_master_curve_within_5_percent(recovered):
    p, _, m = recovered
    w = np.logspace(math.log10(m.reduced.omega.min()), math.log10(m.reduced.omega.max()), 400)
    Et, Em = p.E(w, T_REF), m.E(w, T_REF)
    assert np.max(np.abs(Em.real / Et.real - 1)) < 0.05
    assert np.max(np.abs(Em.imag / Et.imag - 1)) < 0.05
    # the causal fit reproduces the data to the noise level (2 %)
    assert 0.01 < m.quality.rms_rel_storage < 0.03 and 0.01 < m.quality.rms_rel_loss < 0.03
    # and at another temperature it is the WLF-shifted curve (same reduced-frequency window)
    w0 = w / 10 ** p.log10_aT(0.0)
    np.testing.assert_allclose(m.E(w0, 0.0), p.E(w0, 0.0), rtol=0.06)


# ---------------------------------------------------------------------------------------------- variants

def test_tan_delta_shifting_recovers_shifts():
    p, d = synthetic_dma(seed=1, Ts=np.arange(-30.0, 41.0, 5.0))
    sf = materials.shift_isotherms(d, T_REF, using="tan_delta")
    assert np.max(np.abs(sf.log10_aT - p.log10_aT(sf.T_C))) < 0.1


def test_vertical_shift_recovered():
    # b_T = (T + 273.15) / (T_ref + 273.15) (entropy elasticity, Ferry ch. 11): log b_T from -0.04 to +0.06;
    # 1 % noise (vertical and horizontal shifts are nearly degenerate where E' is flat)
    bT = lambda T: (np.asarray(T) + 273.15) / (T_REF + 273.15)
    p, d = synthetic_dma(seed=2, noise=0.01, Ts=np.arange(-25.0, 61.0, 5.0), bT=bT)
    sf = materials.shift_isotherms(d, T_REF, vertical=True)
    # measured: max error 0.003-0.012 in log10 b_T over 5 seeds
    assert np.max(np.abs(sf.log10_bT - np.log10(bT(sf.T_C)))) < 0.02
    assert np.max(np.abs(sf.log10_aT - p.log10_aT(sf.T_C))) < 0.1


def test_user_shift_factors_are_used():
    p, d = synthetic_dma(seed=4, Ts=np.arange(-20.0, 41.0, 10.0))
    table = {float(T): float(p.log10_aT(T)) for T in d.T_isotherm}
    m = materials.master_curve(d, T_REF, shift_factors=table)
    np.testing.assert_allclose(m.shift_factors.log10_aT, [table[T] for T in d.T_isotherm], atol=1e-9)
    assert m.shift_factors.method == "user"
    assert m.wlf.C1 == pytest.approx(C1, rel=1e-6) and m.wlf.C2 == pytest.approx(C2, rel=1e-6)
    # a WLF law is accepted too
    m2 = materials.master_curve(d, T_REF, shift_factors=materials.WLF(C1, C2, T_REF))
    assert m2.wlf == materials.WLF(C1, C2, T_REF)
    with pytest.raises(InputError, match="no value for the isotherm"):
        materials.master_curve(d, T_REF, shift_factors={100.0: 0.0, 110.0: -1.0})
    with pytest.raises(InputError, match="one per isotherm"):
        materials.master_curve(d, T_REF, shift_factors=[0.0, 1.0])


def test_wlf_fit_and_reference_change_exact():
    T = np.array([-10.0, 0.0, 10.0, 20.0, 40.0, 60.0])
    law = materials.WLF(C1, C2, T_REF)
    fit = materials.fit_wlf(T, law.log10_aT(T), T_REF)
    assert fit.C1 == pytest.approx(C1, rel=1e-6) and fit.C2 == pytest.approx(C2, rel=1e-6)
    assert fit.rms < 1e-8
    # the universal constants at T_ref = Tg + 50 become C1g = 17.44, C2g = 51.6 K at Tg (Ferry, ch. 11)
    at_tg = materials.wlf_change_reference(law, T_REF - 50.0)
    assert at_tg.C1 == pytest.approx(17.44, abs=0.01) and at_tg.C2 == pytest.approx(51.6)
    Tx = np.linspace(-25.0, 80.0, 9)
    np.testing.assert_allclose(at_tg.log10_aT(Tx), law.log10_aT(Tx) - law.log10_aT(T_REF - 50.0), atol=1e-12)
    with pytest.raises(InputError, match="singularity"):
        materials.wlf_change_reference(law, T_REF - 120.0)


def test_arrhenius_below_tg():
    Ea, Tg = 250e3, -10.0
    law = materials.WLF(C1, C2, T_REF)
    T_hi = np.arange(-10.0, 61.0, 10.0)
    T_lo = np.array([-40.0, -30.0, -20.0])
    y_lo = law.log10_aT(Tg) + Ea / (8.314462618 * math.log(10)) * (1 / (T_lo + 273.15) - 1 / (Tg + 273.15))
    T = np.concatenate([T_lo, T_hi])
    y = np.concatenate([y_lo, law.log10_aT(T_hi)])
    arr = materials.fit_arrhenius(T_lo, y_lo, Tg, float(law.log10_aT(Tg)))
    assert arr.E_a == pytest.approx(Ea, rel=1e-9)
    shift = materials.TemperatureShift(law, arr)
    np.testing.assert_allclose(shift.log10_aT(T), y, atol=1e-9)
    assert list(shift.law_at([-30.0, 0.0])) == ["Arrhenius", "WLF"]
    # a master curve with Tg set uses WLF above and Arrhenius below, and says so
    p = truth_prony()
    f = np.logspace(-1, 2, 10)
    TT, FF = np.repeat(T, f.size), np.tile(f, T.size)
    la = np.repeat(y, f.size)
    E = p.E_reference(2 * np.pi * FF * 10 ** la)
    d = DMAData.from_arrays(TT, FF, E.real, E.imag)
    m = materials.master_curve(d, T_REF, shift_factors=dict(zip(T.tolist(), y.tolist())), Tg=Tg)
    assert m.shift.arrhenius is not None and m.shift.arrhenius.E_a == pytest.approx(Ea, rel=1e-3)
    assert any("Arrhenius" in n for n in m.notes)
    assert float(m.log10_aT(-30.0)) == pytest.approx(y_lo[1], abs=1e-3)


def test_change_reference_temperature_of_master_curve(recovered):
    _, _, m = recovered
    m0 = m.with_T_ref(0.0)
    assert m0.T_ref == 0.0 and float(m0.log10_aT(0.0)) == 0.0
    w = np.logspace(-2, 6, 9)
    T = np.array([[-20.0], [10.0], [50.0]])
    np.testing.assert_allclose(m0.E(w, T), m.E(w, T), rtol=1e-9)
    assert m0.wlf.C2 == pytest.approx(m.wlf.C2 - 20.0)
    # a T_ref away from the isotherms goes through the WLF law, consistently
    p, d = synthetic_dma(seed=5, Ts=np.arange(-20.0, 41.0, 10.0))
    m5 = materials.master_curve(d, T_ref=23.0)
    assert float(m5.log10_aT(23.0)) == 0.0
    assert np.max(np.abs(m5.shift_factors.log10_aT - (p.log10_aT(m5.shift_factors.T_C) - p.log10_aT(23.0)))) < 0.1


def test_shift_options_validated():
    _, d = synthetic_dma(seed=6, Ts=np.array([0.0, 10.0]))
    with pytest.raises(InputError, match="using"):
        materials.shift_isotherms(d, using="E")
    with pytest.raises(InputError, match="max_step"):
        materials.shift_isotherms(d, max_step=-1)


def test_isotherms_without_overlap_are_warned_not_hidden():
    # 1-decade windows 50 K apart cannot overlap: the result is kept, with an explicit warning
    p, d = synthetic_dma(seed=0, Ts=np.array([-30.0, 20.0]), f=np.logspace(-1, 0, 5))
    with pytest.warns(UserWarning, match=r"T = -30.0 C do not overlap"):
        sf = materials.shift_isotherms(d, T_REF)
    assert np.all(np.isfinite(sf.log10_aT))
