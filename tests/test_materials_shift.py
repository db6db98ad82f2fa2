"""Shift laws as objects: WLF, Arrhenius, WLF+Arrhenius, tabulated a_T (and its reader), usable by master curves."""

import math
import pickle
import warnings
from pathlib import Path

import numpy as np
import pytest

import materials
from materials import InputError
from materials.dma import DMAData

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "dma" / "pyvisco"
PYVISCO_SHIFTS = DATA / "freq_user_master__shift_factors.csv"
R = 8.314462618
C1, C2, T_REF = 8.86, 101.6, 20.0


def wlf():
    return materials.WLF(C1, C2, T_REF)


# ---------------------------------------------------------------------------------------------- parametric laws

def test_laws_against_their_closed_forms():
    # WLF at 0 C: -8.86 * (-20) / (101.6 - 20)
    assert wlf().log10_aT(0.0) == pytest.approx(8.86 * 20 / 81.6, rel=1e-14)
    # Arrhenius, E_a = 100 kJ/mol, a_T(20 C) = 1, at 0 C
    arr = materials.Arrhenius.from_reference(100e3, 20.0)
    expect = 100e3 / (R * math.log(10)) * (1 / 273.15 - 1 / 293.15)
    assert arr.log10_aT(0.0) == pytest.approx(expect, rel=1e-12) and arr.T_ref == 20.0
    assert isinstance(arr.log10_aT(0.0), float) and arr.log10_aT(np.zeros((2, 3))).shape == (2, 3)
    # every law: a_T(T_ref) = 1, and with_T_ref moves the reference exactly
    for law in (wlf(), arr, materials.WLFArrhenius.from_constants(C1, C2, T_REF, 250e3, -10.0)):
        assert float(law.log10_aT(law.T_ref)) == 0.0
        moved = law.with_T_ref(40.0)
        T = np.linspace(-30.0, 90.0, 13)
        np.testing.assert_allclose(moved.log10_aT(T), law.log10_aT(T) - law.log10_aT(40.0), atol=1e-12)
        assert float(moved.log10_aT(40.0)) == pytest.approx(0.0, abs=1e-14)


def test_wlf_arrhenius_is_continuous_at_tg_and_each_branch_is_its_law():
    Ea, Tg = 250e3, -10.0
    law = materials.WLFArrhenius.from_constants(C1, C2, T_REF, Ea, Tg)
    eps = 1e-9
    assert float(law.log10_aT(Tg - eps)) == pytest.approx(float(law.log10_aT(Tg + eps)), abs=1e-8)
    T_hi = np.array([-5.0, 20.0, 60.0])
    np.testing.assert_allclose(law.log10_aT(T_hi), wlf().log10_aT(T_hi), atol=1e-13)
    T_lo = np.array([-40.0, -20.0])
    anchor = wlf().log10_aT(Tg)
    expect = anchor + Ea / (R * math.log(10)) * (1 / (T_lo + 273.15) - 1 / (Tg + 273.15))
    np.testing.assert_allclose(law.log10_aT(T_lo), expect, rtol=1e-12)
    # a reference below T_g: a_T = 1 there, the shape unchanged
    cold = materials.WLFArrhenius.from_constants(C1, C2, -30.0, Ea, Tg)
    assert float(cold.log10_aT(-30.0)) == pytest.approx(0.0, abs=1e-12)
    with pytest.raises(InputError, match="singularity"):
        materials.WLFArrhenius.from_constants(C1, C2, T_REF, Ea, T_REF - C2 - 1.0)


def test_laws_from_case_file_mappings():
    from materials.shift import as_shift_law
    assert isinstance(as_shift_law({"C1": C1, "C2": C2, "T_ref_C": T_REF}), materials.WLF)
    both = as_shift_law({"C1": C1, "C2": C2, "T_ref_C": T_REF, "E_a": 2e5, "T_g": -10.0})
    assert isinstance(both, materials.WLFArrhenius) and both.arrhenius.T_g == -10.0
    assert isinstance(as_shift_law({"E_a": 2e5, "T_ref_C": 0.0}), materials.Arrhenius)
    with pytest.raises(InputError, match="T_g"):
        materials.WLFArrhenius.from_mapping({"C1": C1, "C2": C2, "T_ref_C": T_REF, "E_a": 2e5})
    with pytest.raises(InputError, match="shift"):
        as_shift_law({"A": 1.0})
    with pytest.raises(InputError, match="E_a"):
        materials.Arrhenius(E_a=-1.0, T_g=0.0, log10_aT_g=0.0)


# ---------------------------------------------------------------------------------------------- tabulated

def test_tabulated_wlf_gives_the_wlf_result():
    T = np.arange(-30.0, 101.0, 5.0)
    tab = materials.TabulatedShift(T, wlf().log10_aT(T))
    assert tab.T_ref == T_REF and tab.kind == "tabulated"
    np.testing.assert_allclose(tab.log10_aT(T), wlf().log10_aT(T), atol=1e-13)      # nodes
    mid = T[:-1] + 2.5
    # between nodes: within the error bound of linear interpolation, max|d2 y| / 8 (the table's own second
    # differences), which the monotone cubic does not exceed on this smooth law
    bound = np.max(np.abs(np.diff(wlf().log10_aT(T), 2))) / 8
    err = np.abs(tab.log10_aT(mid) - wlf().log10_aT(mid))
    assert err.max() < bound
    # outside the table: the WLF fit of the table, which recovers the law, continuous at the ends; with a warning
    back = tab.outside_fit.wlf.with_T_ref(T_REF)
    assert back.C1 == pytest.approx(C1, rel=1e-6) and back.C2 == pytest.approx(C2, rel=1e-6)
    with pytest.warns(UserWarning, match="outside the shift-factor table"):
        out = tab.log10_aT(np.array([-40.0, 120.0]))
    np.testing.assert_allclose(out, wlf().log10_aT(np.array([-40.0, 120.0])), atol=1e-6)
    # a Prony series takes any shift law: with the table it is the WLF material at the table's temperatures
    tread = materials.example_tread()
    p_tab = materials.Prony(tread.E_inf, tread.E_i, tread.tau_i, wlf=tab)
    w = np.logspace(-2, 6, 17)
    for temp in (-30.0, 0.0, 55.0, 100.0):
        np.testing.assert_allclose(p_tab.E(w, temp), tread.E(w, temp), rtol=1e-11)


def test_tabulated_law_in_master_curves_gives_the_wlf_result():
    # the same DMA isotherms with the WLF law and with a table of that law: the same material at the isotherms
    tread = materials.example_tread()
    Ts = np.arange(-20.0, 41.0, 10.0)
    f = np.logspace(-1, 2, 8)
    T, F = np.repeat(Ts, f.size), np.tile(f, Ts.size)
    E = tread.E(2 * np.pi * F, T)
    d = DMAData.from_arrays(T, F, E.real, E.imag)
    table = materials.TabulatedShift(Ts, wlf().log10_aT(Ts))
    a = materials.master_curve(d, T_REF, shift_factors=wlf(), fit="table")
    b = materials.master_curve(d, T_REF, shift_factors=table, fit="table")
    w = np.logspace(-1, 3, 9)
    for temp in Ts:
        # the shifts agree to 1e-13; the smoothing of the shifted data reacts to that (its penalty is chosen on a
        # grid) by a few 1e-6 at most
        np.testing.assert_allclose(b.E(w, temp), a.E(w, temp), rtol=1e-4)
    assert b.shift is table or b.shift.kind == "tabulated"
    # a master-curve table read with the tabulated law: the WLF result at the table's temperatures
    fm = np.logspace(-4, 10, 57)
    Em = tread.E(2 * np.pi * fm, T_REF)
    mapping = {"f_Hz": fm, "E_storage_Pa": Em.real, "E_loss_Pa": Em.imag}
    ma = materials.MasterCurve.from_table(mapping, wlf())
    mb = materials.MasterCurve.from_table(mapping, shift=table)
    for temp in Ts:
        np.testing.assert_allclose(mb.E(w, temp), ma.E(w, temp), rtol=1e-12)


def test_tabulated_reference_and_continuation():
    # no node at a_T = 1: the crossing of the interpolant is the reference
    tab = materials.TabulatedShift([0.0, 10.0, 30.0], [2.0, 1.0, -1.0])
    assert tab.T_ref == pytest.approx(20.0, abs=1e-9)
    moved = tab.with_T_ref(0.0)
    assert moved.T_ref == 0.0 and float(moved.log10_aT(30.0)) == pytest.approx(-3.0)
    with pytest.raises(InputError, match="never 1"):
        materials.TabulatedShift([0.0, 10.0], [2.0, 1.0])
    assert materials.TabulatedShift([0.0, 10.0], [2.0, 1.0], T_ref=10.0).T_ref == 10.0
    # a given continuation, anchored at the table's ends
    arr = materials.Arrhenius.from_reference(150e3, 0.0)
    cont = materials.TabulatedShift([0.0, 10.0, 30.0], [2.0, 1.0, -1.0], outside=arr)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        below = float(cont.log10_aT(-10.0))
        above = float(cont.log10_aT(50.0))
    assert below == pytest.approx(2.0 + arr.log10_aT(-10.0) - arr.log10_aT(0.0), abs=1e-12)
    assert above == pytest.approx(-1.0 + arr.log10_aT(50.0) - arr.log10_aT(30.0), abs=1e-12)
    with pytest.raises(InputError, match="twice"):
        materials.TabulatedShift([0.0, 0.0, 10.0], [1.0, 1.0, 0.0])
    with pytest.raises(InputError, match="absolute zero"):
        materials.TabulatedShift([-300.0, 0.0], [1.0, 0.0])
    again = pickle.loads(pickle.dumps(cont))
    assert float(again.log10_aT(20.0)) == float(cont.log10_aT(20.0))
    assert "array(" not in repr(cont) and len(repr(cont)) < 400


# ---------------------------------------------------------------------------------------------- reader

def _write(path, text, encoding="utf-8"):
    path.write_bytes(text.encode(encoding))
    return path


def test_read_shift_factors_kinds_and_units(tmp_path):
    T = np.arange(-20.0, 61.0, 10.0)
    la = wlf().log10_aT(T)
    # header-less, log10 a_T (values of both signs)
    p = _write(tmp_path / "a.csv", "".join(f"{float(t)!r},{float(v)!r}\n" for t, v in zip(T, la)))
    np.testing.assert_allclose(materials.read_shift_factors(p).log10_aT(T), la, atol=1e-13)
    # header-less a_T spanning many decades, with the 1 at T_ref: recognised as a_T
    p = _write(tmp_path / "b.txt", "".join(f"{t:g} {float(10 ** v)!r}\n" for t, v in zip(T, la)))
    np.testing.assert_allclose(materials.read_shift_factors(p).log10_aT(T), la, atol=1e-12)
    # named columns in kelvin, natural log, tab-separated with a units row and a Latin-1 degree sign
    p = _write(tmp_path / "c.tsv", "Temp\tln_aT\n[K]\t[-]\n"
               + "".join(f"{float(t + 273.15)!r}\t{float(v * math.log(10))!r}\n" for t, v in zip(T, la)), "latin-1")
    np.testing.assert_allclose(materials.read_shift_factors(p).log10_aT(T), la, atol=1e-12)
    p = _write(tmp_path / "d.csv", "T [\xb0C],a_T\n" + "".join(f"{t:g},{float(10 ** v)!r}\n" for t, v in zip(T, la)),
               "latin-1")
    np.testing.assert_allclose(materials.read_shift_factors(p).log10_aT(T), la, atol=1e-12)
    # the user names the columns of an ambiguous header-less table
    p = _write(tmp_path / "e.csv", "".join(f"{t:g},{float(20.0 - i)!r}\n" for i, t in enumerate(T)))
    with pytest.raises(InputError, match="cannot tell whether.*columns=\\('T_C', 'log10_aT'\\)"):
        materials.read_shift_factors(p)
    got = materials.read_shift_factors(p, columns=("T_C", "aT"), T_ref=-20.0)
    assert float(got.log10_aT(-10.0)) == pytest.approx(math.log10(19.0) - math.log10(20.0))


def test_read_shift_factors_refuses_unit_slips_and_bad_rows(tmp_path):
    p = _write(tmp_path / "k.csv", "T,log_aT\n253.15,2\n273.15,0\n293.15,-1.5\n")
    with pytest.raises(InputError, match="k.csv, column 'T'.*looks like kelvin"):
        materials.read_shift_factors(p)
    assert materials.read_shift_factors(p, units={"T": "K"}).T_ref == pytest.approx(0.0, abs=1e-12)
    p = _write(tmp_path / "neg.csv", "T_C,aT\n0,10\n20,1\n40,-0.1\n")
    with pytest.raises(InputError, match="line 4.*a_T must be > 0"):
        materials.read_shift_factors(p)
    p = _write(tmp_path / "dup.csv", "T_C,log10_aT\n0,1\n20,0\n20,0.1\n")
    with pytest.raises(InputError, match="line 4.*20 C appears twice"):
        materials.read_shift_factors(p)
    p = _write(tmp_path / "up.csv", "T_C,log10_aT\n0,1\n20,0\n40,0.5\n")
    with pytest.warns(UserWarning, match="increases with temperature between 20->40 C"):
        materials.read_shift_factors(p)
    p = _write(tmp_path / "z.csv", "T_C,log10_aT\n-300,1\n20,0\n")
    with pytest.raises(InputError, match="below absolute zero"):
        materials.read_shift_factors(p)


@pytest.mark.data
def test_read_pyvisco_shift_factor_file():
    if not PYVISCO_SHIFTS.exists():
        pytest.skip(f"shared data not present: {PYVISCO_SHIFTS}")
    tab = materials.read_shift_factors(PYVISCO_SHIFTS)
    # values typed from the file: T = 100 C -> -11.7, -50 C -> 12.75, a_T = 1 at -5 C
    assert tab.T_ref == -5.0 and tab.T_range == (-50.0, 100.0)
    assert float(tab.log10_aT(100.0)) == -11.7 and float(tab.log10_aT(-50.0)) == 12.75
    assert float(tab.log10_aT(55.0)) == -7.02
