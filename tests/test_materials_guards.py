"""Unit slips in DMA inputs are caught and named: MPa under Pa headers, Pa under MPa units, kelvin in a Celsius
column, temperatures below absolute zero; declared units are the way out."""

import numpy as np
import pytest

import materials
from materials import InputError
from materials.dma import DMAData


def _long(tmp_path, rows, header="T_C,f_Hz,E_storage_Pa,E_loss_Pa", name="dma.csv"):
    p = tmp_path / name
    p.write_text(header + "\n" + "\n".join(rows) + "\n")
    return p


def _rows(T=(0.0, 20.0), E1=3.5e6, E2=0.8e6):
    return [f"{t},{f},{E1 * (1 + f / 100)},{E2}" for t in T for f in (0.1, 1.0, 10.0)]


def test_mpa_values_under_pa_headers(tmp_path):
    p = _long(tmp_path, _rows(E1=3.5, E2=0.8))
    with pytest.raises(InputError) as err:
        materials.read_dma(p)
    msg = str(err.value)
    assert "dma.csv" in msg and "'E_storage_Pa'" in msg and "look like MPa" in msg and "units={'E': 'MPa'}" in msg
    d = materials.read_dma(p, units={"E": "MPa"})
    assert d.E_storage.min() == pytest.approx(3.5e6 * 1.001)


def test_pa_values_under_an_mpa_units_row(tmp_path):
    p = tmp_path / "pv.csv"
    p.write_text("f,E_stor,E_loss,T,Set\nHz,MPa,MPa,C,-\n"
                 + "".join(f"{f},{3.5e6},{0.8e6},{T},{i}\n" for i, T in enumerate((0.0, 20.0)) for f in (1, 10)))
    with pytest.raises(InputError, match=r"pv.csv, columns 'E_stor' and 'E_loss'.*above any polymer's range.*Pa"):
        materials.read_dma(p)
    assert materials.read_dma(p, units={"E": "Pa"}).E_storage.max() == 3.5e6


def test_temperatures_below_absolute_zero_and_in_kelvin(tmp_path):
    p = _long(tmp_path, _rows(T=(-400.0, 20.0)))
    with pytest.raises(InputError, match=r"dma.csv, column 'T_C', line 2: temperature -400 C is below absolute"):
        materials.read_dma(p)
    p = _long(tmp_path, _rows(T=(273.15, 293.15)))
    with pytest.raises(InputError, match=r"column 'T_C'.*looks like kelvin.*\(0\.\.20 C\)"):
        materials.read_dma(p)
    d = materials.read_dma(p, units={"T": "K"})
    np.testing.assert_allclose(d.T_isotherm, [0.0, 20.0], atol=1e-12)
    # a hot but genuine Celsius data set is kept when declared
    assert materials.read_dma(p, units={"T": "C"}).T_isotherm[0] == pytest.approx(273.15)


def test_arrays_are_guarded_too():
    T, f = [0.0, 0.0, 20.0, 20.0], [1.0, 10.0, 1.0, 10.0]
    with pytest.raises(InputError, match="look like MPa"):
        DMAData.from_arrays(T, f, [3.0, 4.0, 2.0, 3.0], [0.5, 0.6, 0.4, 0.5])
    with pytest.raises(InputError, match="below absolute zero"):
        DMAData.from_arrays([-300.0, -300.0, 20.0, 20.0], f, [3e6] * 4, [5e5] * 4)
    # a soft gel of 20 kPa is possible: the caller vouches for the unit
    gel = DMAData.from_arrays(T, f, [2e4, 2.5e4, 1.5e4, 2e4], [2e3] * 4, check_units=False)
    assert gel.E_storage.max() == 2.5e4


def test_master_curve_tables_and_sweeps_share_the_guards(tmp_path):
    p = tmp_path / "mc.csv"
    p.write_text("f_Hz,E_storage_Pa,E_loss_Pa\n1,3.0,0.9\n10,4.0,1.2\n100,6.0,1.8\n")
    with pytest.raises(InputError, match=r"mc.csv, column 'E_storage_Pa'.*\(unit Pa from the column name\).*MPa"):
        materials.read_master_curve(p, wlf={"C1": 8.86, "C2": 101.6, "T_ref_C": 20.0})
    m = materials.read_master_curve(p, wlf={"C1": 8.86, "C2": 101.6, "T_ref_C": 20.0}, units={"E": "MPa"})
    assert m.E(2 * np.pi).real == 3e6
