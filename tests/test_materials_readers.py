"""materials readers: long CSV, pyvisco CSV, Eplexor exports; shear conversion; bad input named precisely."""

from pathlib import Path

import numpy as np
import pytest

import materials
from materials import InputError

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "dma"
PYVISCO = DATA / "pyvisco" / "freq_user_raw.csv"
EPLEXOR = DATA / "eplexor"


def _long_csv(tmp_path, rows, header="T_C,f_Hz,E_storage_Pa,E_loss_Pa", name="dma.csv"):
    p = tmp_path / name
    p.write_text("# a comment line\n" + header + "\n" + "\n".join(rows) + "\n", encoding="utf-8")
    return p


def _good_rows():
    return [f"{T},{f},{1e6 * (1 + T / 100 + f)},{2e5 * (1 + f)}" for T in (0.0, 20.0) for f in (0.1, 1.0, 10.0)]


# ---------------------------------------------------------------------------------------------- long CSV

def test_long_csv_reads_and_groups_isotherms(tmp_path):
    p = _long_csv(tmp_path, _good_rows())
    d = materials.read_dma(p)
    assert isinstance(d, materials.DMAData)
    assert len(d) == 6 and d.n_isotherms == 2
    np.testing.assert_allclose(d.T_isotherm, [0.0, 20.0])
    np.testing.assert_allclose(d.omega, 2 * np.pi * d.f_Hz)
    assert not d.shear_converted and d.strain is None
    # file line numbers are kept: the comment is line 1, the header line 2, the first data row line 3
    assert d.line.min() == 3


def test_long_csv_shear_is_converted_and_said(tmp_path):
    rows = [f"20,{f},1e6,1e5" for f in (0.1, 1.0)] + [f"30,{f},1e6,1e5" for f in (0.1, 1.0)]
    p = _long_csv(tmp_path, rows, header="T_C,f_Hz,G_storage_Pa,G_loss_Pa")
    d = materials.read_dma(p, poisson=0.5)
    # E = 2 (1 + nu) G = 3 G for an incompressible rubber
    np.testing.assert_allclose(d.E_storage, 3e6)
    np.testing.assert_allclose(d.E_loss, 3e5)
    assert d.shear_converted and d.poisson == 0.5
    assert any("shear" in n and "2(1+nu)G" in n for n in d.notes)
    d2 = materials.read_dma(p, poisson=0.4)
    np.testing.assert_allclose(d2.E_storage, 2.8e6)


def test_long_csv_strain_column(tmp_path):
    rows = [f"20,1,{1e6 / (1 + s / 0.1)},{1e5},{s}" for s in (0.01, 0.1, 0.3)]
    p = _long_csv(tmp_path, rows, header="T_C,f_Hz,E_storage_Pa,E_loss_Pa,strain")
    d = materials.read_dma(p)
    np.testing.assert_allclose(np.sort(d.strain), [0.01, 0.1, 0.3])


def test_write_long_csv_round_trip(tmp_path):
    d = materials.read_dma(_long_csv(tmp_path, _good_rows()))
    out = d.to_csv(tmp_path / "out" / "copy.csv")
    d2 = materials.read_dma(out)
    np.testing.assert_allclose(d2.E_storage, d.E_storage)
    assert not list((tmp_path / "out").glob(".*tmp"))        # no temporary file left behind


# ---------------------------------------------------------------------------------------------- bad input

@pytest.mark.parametrize("bad, column", [("-1e6", "E_storage"), ("0", "E_storage")])
def test_nonpositive_storage_modulus_names_line_and_column(tmp_path, bad, column):
    rows = _good_rows()
    rows[3] = f"20.0,0.1,{bad},2e5"
    p = _long_csv(tmp_path, rows)
    with pytest.raises(InputError) as e:
        materials.read_dma(p)
    msg = str(e.value)
    assert str(p) in msg and "line 6" in msg and column in msg


def test_negative_loss_modulus_raises(tmp_path):
    rows = _good_rows()
    rows[0] = "0.0,0.1,1e6,-5"
    with pytest.raises(InputError, match=r"line 3, column 'E_loss'"):
        materials.read_dma(_long_csv(tmp_path, rows))


def test_bad_rows_dropped_with_warning_when_asked(tmp_path):
    rows = _good_rows()
    rows[0] = "0.0,0.1,1e6,-5"
    with pytest.warns(UserWarning, match=r"dropped 1 bad rows \(line 3\)"):
        d = materials.read_dma(_long_csv(tmp_path, rows), drop_bad=True)
    assert len(d) == 5
    assert any("dropped" in n for n in d.notes)


@pytest.mark.parametrize("f", ["0", "-1"])
def test_nonpositive_frequency(tmp_path, f):
    rows = _good_rows()
    rows[1] = f"0.0,{f},1e6,1e5"
    with pytest.raises(InputError, match=r"line 4, column 'f_Hz': expected a positive frequency"):
        materials.read_dma(_long_csv(tmp_path, rows))


def test_non_numeric_and_missing_values(tmp_path):
    rows = _good_rows()
    rows[2] = "0.0,10,abc,1e5"
    with pytest.raises(InputError, match=r"line 5, column 'E_storage_Pa': expected a number, got 'abc'"):
        materials.read_dma(_long_csv(tmp_path, rows, name="a.csv"))
    rows = _good_rows()
    rows[2] = "0.0,10,,1e5"
    with pytest.raises(InputError, match=r"line 5, column 'E_storage'"):
        materials.read_dma(_long_csv(tmp_path, rows, name="b.csv"))


def test_duplicate_rows_warned_and_kept_once(tmp_path):
    rows = _good_rows()
    rows.append(rows[1])
    p = _long_csv(tmp_path, rows)
    with pytest.warns(UserWarning, match=r"identical duplicate rows dropped \(line 9\)"):
        d = materials.read_dma(p)
    assert len(d) == 6


def test_repeated_measurements_averaged_with_warning(tmp_path):
    rows = _good_rows() + ["0.0,1.0,4e6,2e5"]
    with pytest.warns(UserWarning, match="averaged"):
        d = materials.read_dma(_long_csv(tmp_path, rows))
    assert len(d) == 6
    i = np.flatnonzero((d.isotherm == 0) & (d.f_Hz == 1.0))[0]
    # geometric mean of 2e6 (first row) and 4e6
    assert d.E_storage[i] == pytest.approx(np.sqrt(2e6 * 4e6))


def test_missing_column_named(tmp_path):
    p = _long_csv(tmp_path, ["20,1,1e6", "30,1,1e6"], header="T_C,f_Hz,E_storage_Pa")
    with pytest.raises(InputError) as e:
        materials.read_dma(p)
    assert "E_loss_Pa" in str(e.value) and str(p) in str(e.value)
    p = _long_csv(tmp_path, ["20,1,1", "30,1,1"], header="T_C,freq,E_storage_Pa,E_loss_Pa", name="c.csv")
    with pytest.raises(InputError, match="f_Hz"):
        materials.read_dma(p)


def test_wrong_encoding(tmp_path):
    p = tmp_path / "utf16.csv"
    p.write_text("T_C,f_Hz,E_storage_Pa,E_loss_Pa\n20,1,1e6,1e5\n", encoding="utf-16")
    with pytest.raises(InputError, match="encoding") as e:
        materials.read_dma(p)
    assert str(p) in str(e.value)
    # Latin-1 bytes read with an explicit (wrong) encoding
    q = tmp_path / "latin.txt"
    q.write_bytes("T_C,f_Hz,E_storage_Pa,E_loss_Pa # \xb0C\n20,1,1e6,1e5\n".encode("latin-1"))
    with pytest.raises(InputError, match="utf-8"):
        materials.read_dma(q, encoding="utf-8")


def test_empty_and_missing_file(tmp_path):
    p = tmp_path / "empty.csv"
    p.write_text("# nothing\n")
    with pytest.raises(InputError, match="empty"):
        materials.read_dma(p)
    with pytest.raises(InputError, match="no such file"):
        materials.read_dma(tmp_path / "absent.csv")


def test_one_isotherm_is_read_but_cannot_make_a_master_curve(tmp_path):
    p = _long_csv(tmp_path, [f"20,{f},{1e6 * (1 + f)},1e5" for f in (0.1, 1, 10)])
    d = materials.read_dma(p)
    assert d.n_isotherms == 1
    with pytest.raises(InputError, match="one isotherm only") as e:
        materials.master_curve(d, 20.0)
    assert str(p) in str(e.value)


def test_temperature_drift_within_isotherm_warned(tmp_path):
    rows = [f"{20 + 0.9 * i},{f},1e6,1e5" for i, f in enumerate((0.1, 0.3, 1, 3))]
    with pytest.warns(UserWarning, match="drifts"):
        d = materials.read_dma(_long_csv(tmp_path, rows))
    assert d.n_isotherms == 1 and len(d) == 4


def test_unrecognised_format(tmp_path):
    p = tmp_path / "x.txt"
    p.write_text("hello world\n1 2\n")
    with pytest.raises(InputError, match="unrecognised DMA format"):
        materials.read_dma(p)


# ---------------------------------------------------------------------------------------------- pyvisco / Eplexor

def test_pyvisco_format_synthetic(tmp_path):
    p = tmp_path / "pv.csv"
    rows = [f"{f},{100 + i},{10 + i},{T},{s}" for s, T in enumerate((-10.1, 0.2)) for i, f in enumerate((0.1, 1, 10))]
    p.write_text("\ufefff,G_stor,G_loss,T,Set\nHz,MPa,MPa,C,-\n" + "\n".join(rows) + "\n", encoding="utf-8")
    d = materials.read_dma(p)
    assert d.n_isotherms == 2 and d.shear_converted
    np.testing.assert_allclose(d.E_storage[:3], 3e6 * np.array([100, 101, 102]))


def test_eplexor_synthetic_latin1_shear(tmp_path):
    header = "Index Ts f G' G\"\n[#] [\xb0C] [Hz] [MPa] [MPa]\n"
    body = "".join(f"{i} {25.0 + 0.1 * i:.3f} {f} {2.0 + i} {0.5}\n" for i, f in enumerate((0.1, 1.0, 10.0)))
    p = tmp_path / "T25.txt"
    p.write_bytes((header + body + "]1[SAMPLE_\n").encode("latin-1"))
    d = materials.read_dma(p)
    np.testing.assert_allclose(d.E_storage, 3e6 * np.array([2.0, 3.0, 4.0]))
    assert d.shear_converted
    assert any("Latin-1" in n for n in d.notes) and any("trailing" in n for n in d.notes)


@pytest.mark.data
def test_real_pyvisco_file():
    if not PYVISCO.exists():
        pytest.skip(f"shared data not present: {PYVISCO}")
    d = materials.read_dma(PYVISCO)
    assert d.n_isotherms == 21 and len(d) == 210
    assert d.T_isotherm[0] == pytest.approx(-49.94, abs=0.05) and d.T_isotherm[-1] == pytest.approx(100.0, abs=0.05)
    # MPa -> Pa: first row of the file is 8097.175545 MPa
    assert d.E_storage.max() > 1e9 and np.isclose(d.E_storage, 8097.175545e6).any()


@pytest.mark.data
def test_real_eplexor_folder():
    if not EPLEXOR.exists():
        pytest.skip(f"shared data not present: {EPLEXOR}")
    with pytest.warns(UserWarning, match="drifts"):
        d = materials.read_dma(EPLEXOR)
    assert d.n_isotherms == 22 and len(d) == 22 * 60
    # measured temperatures, not nominal ones: the 0 C file ran at about -3 C
    assert -4 < d.T_isotherm[0] < -1 and 103 < d.T_isotherm[-1] < 105
    assert any("Latin-1" in n for n in d.notes)
    # the Eplexor export is in MPa: 2.93911e+03 MPa in T0.txt line 3
    assert np.isclose(d.E_storage, 2.93911e9).any()
    with pytest.raises(InputError, match="utf-8"):
        materials.read_dma(EPLEXOR / "T20.txt", encoding="utf-8")
