"""Default master curves: the temperature law chosen by how well it predicts the isotherms, the representation by
its misfit; the misfit defined and checked on real DMA data; progress, pickling and short reprs."""

import math
import pickle
import warnings
from pathlib import Path

import numpy as np
import pytest

import materials
from materials import InputError
from materials.dma import DMAData

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "dma"
PYVISCO = DATA / "pyvisco" / "freq_user_raw.csv"
PYVISCO_SHIFTS = DATA / "pyvisco" / "freq_user_master__shift_factors.csv"
R = 8.314462618


def _isotherms(log10_aT, Ts, f=np.logspace(-1, 2, 10), noise=0.0, seed=0):
    """Isotherms of the example compound's 20 C curve shifted by a given law (exact unless ``noise``)."""
    ref = materials.example_tread()
    T, F = np.repeat(Ts, f.size), np.tile(f, Ts.size)
    E = ref.E_reference(2 * np.pi * F * 10.0 ** log10_aT(T))
    rng = np.random.default_rng(seed)
    E1 = E.real * (1 + noise * rng.standard_normal(E.size))
    E2 = E.imag * (1 + noise * rng.standard_normal(E.size))
    return DMAData.from_arrays(T, F, E1, E2, source="synthetic isotherms")


def _misfit_by_hand(m, d):
    """The documented definition, written out: RMS of ln(E'_model/E'_data) and ln(E''_model/E''_data)."""
    total, n = 0.0, 0
    for i in range(len(d)):
        E = complex(m.E(2 * math.pi * d.f_Hz[i], d.T_C[i]))
        total += math.log(E.real / d.E_storage[i]) ** 2 + math.log(E.imag / d.E_loss[i]) ** 2
        n += 2
    return math.sqrt(total / n)


# ---------------------------------------------------------------------------------------------- synthetic laws

def test_wlf_data_get_the_wlf_law():
    wlf = materials.WLF(8.86, 101.6, 20.0)
    d = _isotherms(wlf.log10_aT, np.arange(-20.0, 61.0, 10.0))
    m = materials.master_curve(d, T_ref=20.0)
    assert m.shift.kind == "wlf"
    assert m.wlf.C1 == pytest.approx(8.86, rel=1e-3) and m.wlf.C2 == pytest.approx(101.6, rel=1e-3)
    assert m.misfit == pytest.approx(materials.isotherm_misfit(m, d), rel=1e-12)
    assert m.misfit == pytest.approx(_misfit_by_hand(m, d), rel=1e-9) and m.misfit < 1e-3
    assert [s.name for s in m.scores] == ["wlf", "arrhenius", "wlf+arrhenius", "tabulated"]


def test_arrhenius_below_tg_is_found_and_kept():
    # WLF above -10 C, Arrhenius (250 kJ/mol) below: the WLF law alone cannot describe the cold isotherms
    law = materials.WLFArrhenius.from_constants(8.86, 101.6, 20.0, 250e3, -10.0)
    d = _isotherms(law.log10_aT, np.array([-40.0, -30.0, -20.0, -5.0, 5.0, 15.0, 25.0, 35.0, 50.0]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")           # the coldest isotherms barely overlap (warned, tested elsewhere)
        m = materials.master_curve(d, T_ref=20.0)
        m2 = materials.master_curve(d, T_ref=20.0, shift_law="wlf+arrhenius")
    scores = {s.name: s for s in m.scores}
    assert scores["wlf+arrhenius"].misfit_loo < 0.3 * scores["wlf"].misfit_loo
    assert m.shift.kind in ("wlf+arrhenius", "tabulated") and m.misfit < 0.01
    if m.shift.kind == "wlf+arrhenius":
        assert m.shift.arrhenius.E_a == pytest.approx(250e3, rel=0.02)
    # asked for explicitly, the law is the one of the data
    assert -20.0 < m2.shift.arrhenius.T_g < -5.0 and m2.shift.arrhenius.E_a == pytest.approx(250e3, rel=0.02)
    np.testing.assert_allclose(m2.log10_aT([-30.0, 35.0]), law.log10_aT([-30.0, 35.0]), atol=0.02)


def test_noisy_shifts_prefer_a_smooth_law_over_following_the_noise():
    # exact WLF isotherms, then each isotherm's frequencies scaled by a random factor (0.15 decade scatter):
    # the cross-validated misfit sees that interpolating these shifts predicts worse than the WLF fit
    wlf = materials.WLF(8.86, 101.6, 20.0)
    Ts = np.arange(-15.0, 61.0, 5.0)
    rng = np.random.default_rng(7)
    jitter = dict(zip(Ts.tolist(), 0.15 * rng.standard_normal(Ts.size)))
    d = _isotherms(lambda T: wlf.log10_aT(T) + np.vectorize(jitter.get)(T), Ts)
    m = materials.master_curve(d, T_ref=20.0, shift_factors=dict(zip(Ts.tolist(), wlf.log10_aT(Ts).tolist()
                                                                     + np.array(list(jitter.values()))
                                                                     - jitter[20.0])))
    scores = {s.name: s for s in m.scores}
    assert scores["tabulated"].misfit < scores["wlf"].misfit            # in sample, following the noise wins
    assert m.shift.kind != "tabulated" or scores["tabulated"].misfit_loo <= scores["wlf"].misfit_loo


def test_options_are_validated():
    d = _isotherms(materials.WLF(8.86, 101.6, 20.0).log10_aT, np.arange(0.0, 41.0, 10.0))
    with pytest.raises(InputError, match="shift_law"):
        materials.master_curve(d, 20.0, shift_law="vogel")
    with pytest.raises(InputError, match="fit"):
        materials.master_curve(d, 20.0, fit="spline")
    with pytest.raises(InputError, match="Tg"):
        materials.master_curve(d, 20.0, shift_law="wlf", Tg=-10.0)
    with pytest.raises(InputError, match="conflicts"):
        materials.master_curve(d, 20.0, shift_law="wlf", shift_factors=materials.WLF(8.86, 101.6, 20.0))
    with pytest.raises(InputError, match="progress"):
        materials.master_curve(d, 20.0, progress="yes")
    with pytest.raises(InputError, match="wlf_range"):
        materials.master_curve(d, 20.0, wlf_range=(50.0, 10.0))


def test_progress_pickle_and_repr():
    d = _isotherms(materials.WLF(8.86, 101.6, 20.0).log10_aT, np.arange(-10.0, 51.0, 10.0))
    calls = []
    m = materials.master_curve(d, 20.0, progress=lambda message, fraction: calls.append((message, fraction)))
    assert len(calls) >= 4 and all(isinstance(msg, str) and msg for msg, _ in calls)
    fractions = [f for _, f in calls if f is not None]
    assert fractions == sorted(fractions) and fractions[0] == 0.0 and fractions[-1] == 1.0
    back = pickle.loads(pickle.dumps(m))
    w = np.logspace(-2, 8, 41)
    np.testing.assert_array_equal(back.E(w, 33.0), m.E(w, 33.0))
    assert back.misfit == m.misfit and back.shift.kind == m.shift.kind
    for obj in (m, d, m.shift, m.shift_factors, m.reduced, m.quality, m.scores[0], m.curve,
                materials.fit_prony([1.0, 10.0, 100.0], [1e6, 2e6, 3e6], [1e5, 3e5, 5e5]).prony,
                materials.example_tread(), m.wlf_fit, m.tabulated()):
        text = repr(obj)
        assert "array(" not in text and "\n" not in text and len(text) < 400, text


def test_sparse_data_two_isotherms_and_few_points():
    # the corner of sparse data: two isotherms of four points; no cross-validation is possible
    wlf = materials.WLF(8.86, 101.6, 20.0)
    d = _isotherms(wlf.log10_aT, np.array([10.0, 20.0]), f=np.logspace(-1, 2, 4))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = materials.master_curve(d, 20.0)
    E = m.E(np.logspace(-30, 30, 61), np.array([[-60.0], [20.0], [150.0]]))
    assert np.all(np.isfinite(E)) and np.all(E.real > 0) and np.all(E.imag >= 0)
    assert m.misfit < 0.02


def test_glassy_and_hot_corners_stay_physical():
    d = _isotherms(materials.WLF(8.86, 101.6, 20.0).log10_aT, np.arange(-30.0, 71.0, 10.0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")           # the -30 C isotherm barely overlaps its neighbour (warned)
        m = materials.master_curve(d, 20.0)
    w = np.logspace(-6, 12, 37)
    cold, hot = m.E(w, -45.0), m.E(w[w < 1e3], 120.0)
    # far below T_g the modulus is glassy (GPa) and E' never exceeds its largest measured value
    assert np.all(cold.real > 1e8) and cold.real.max() <= m.reduced.E_storage.max() * 1.01
    # far above, rubbery (MPa) and E' never below the smallest measured value
    assert np.all(hot.real < 2e7) and hot.real.min() >= m.reduced.E_storage.min() * 0.99
    assert np.all(np.isfinite(cold)) and np.all(np.isfinite(hot)) and np.all(hot.imag > 0)


# ---------------------------------------------------------------------------------------------- real data

@pytest.fixture(scope="module")
def pyvisco_default():
    if not PYVISCO.exists():
        pytest.skip(f"shared data not present: {PYVISCO}")
    d = materials.read_dma(PYVISCO)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")           # isotherms that do not superpose are warned elsewhere
        return d, materials.master_curve(d, T_ref=-5.0)


@pytest.mark.data
def test_pyvisco_default_meets_the_target(pyvisco_default):
    d, m = pyvisco_default
    # the target: <= 0.206 (pyvisco's own shifts with a causal Prony fit); the earlier default
    # (WLF run to its bounds) scored 2.57. Measured: 0.090 (tabulated shifts, interpolated reference curve).
    assert m.misfit <= 0.206
    assert m.misfit == pytest.approx(materials.isotherm_misfit(m, d), rel=1e-12)
    assert m.misfit == pytest.approx(_misfit_by_hand(m, d), rel=1e-9)
    # at least as good as every temperature law considered (same representation)
    assert m.misfit <= min(s.misfit for s in m.scores) * (1 + 1e-9)
    # measured (table representation): wlf 0.564, arrhenius 0.377, wlf+arrhenius 0.126, tabulated 0.090
    scores = {s.name: s for s in m.scores}
    assert scores["wlf"].misfit > 0.3 and scores["wlf+arrhenius"].misfit < 0.206
    assert float(m.log10_aT(-5.0)) == 0.0 and np.all(np.diff(m.shift_factors.log10_aT) <= 0.1)


@pytest.mark.data
def test_pyvisco_default_is_no_worse_than_pyvisco_shifts(pyvisco_default):
    d, m = pyvisco_default
    if not PYVISCO_SHIFTS.exists():
        pytest.skip(f"shared data not present: {PYVISCO_SHIFTS}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        theirs = materials.master_curve(d, T_ref=-5.0, shift_factors=materials.read_shift_factors(PYVISCO_SHIFTS),
                                        fit="prony")
    # pyvisco's shift factors (nominal temperatures, interpolated) with a causal Prony fit: 0.208 measured
    assert theirs.misfit == pytest.approx(0.206, abs=0.02)
    assert m.misfit < theirs.misfit


@pytest.mark.data
@pytest.mark.slow
def test_eplexor_default_is_the_best_option(eplexor_master):
    d, m = eplexor_master                         # the default master curve at T_ref = 50 C (tests/conftest.py)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")           # temperature drift within isotherms is warned (tested elsewhere)
        prony = materials.master_curve(d, T_ref=50.0, fit="prony")
    # measured: default 0.043 (table, tabulated); Prony with the tabulated law 0.073; the old default 0.288
    assert m.misfit <= min(s.misfit for s in m.scores) * (1 + 1e-9)
    assert m.misfit <= prony.misfit <= min(s.misfit for s in prony.scores) * (1 + 1e-9)
    assert m.misfit < 0.1 and m.quality.n_points == 1320
