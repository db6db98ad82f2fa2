"""Strain factors f(strain, T), g(strain, T) from strain sweeps: recovered from synthetic sweeps, unity for flat ones,
clamped outside the data, vectorised and fast; the readers of strain-sweep exports and their unit guards."""

import pickle
import time

import numpy as np
import pytest

import materials
from materials import InputError

STRAINS = np.geomspace(1e-3, 0.5, 15)
TEMPS = np.array([0.0, 10.0, 30.0, 50.0])


def kraus(strain, T):
    """A Kraus-type Payne effect whose depth depends on temperature (synthetic, for the tests):
    f = f_inf + (1 - f_inf) / (1 + (e/e_c)^1.2), f_inf = 0.2 + 0.004 T; g rises to a peak near e_c and falls."""
    f_inf = 0.2 + 0.004 * T
    e_c = 0.02
    x = (strain / e_c) ** 1.2
    f = f_inf + (1 - f_inf) / (1 + x)
    g = f_inf + (1 - f_inf) / (1 + x) + 1.5 * x / (1 + x) ** 2
    return f, g


def sweeps(flat=False, freqs=(10.0,)):
    rows = []
    for T in TEMPS:
        E1_0, E2_0 = 8e6 * (1 - T / 100), 2e6 * (1 - T / 120)
        for fr in freqs:
            f, g = kraus(STRAINS, T)
            if flat:
                f, g = np.ones_like(f), np.ones_like(g)
            rows += [(T, fr, s, E1_0 * a, E2_0 * b) for s, a, b in zip(STRAINS, f, g)]
    T, fr, s, E1, E2 = map(np.array, zip(*rows))
    return materials.StrainSweep.from_arrays(T, s, E1, E2, f_Hz=fr)


# ---------------------------------------------------------------------------------------------- the factors

def test_known_strain_dependence_is_recovered():
    sf = materials.strain_factors(sweeps())
    np.testing.assert_array_equal(sf.T_C, TEMPS)
    np.testing.assert_allclose(sf.strain, STRAINS, rtol=1e-15)
    for T in TEMPS:
        f, g = kraus(STRAINS, T)
        f0, g0 = kraus(STRAINS[:1], T)
        F, G = sf.factors(STRAINS, T)
        np.testing.assert_allclose(F, f / f0, rtol=1e-12)
        np.testing.assert_allclose(G, g / g0, rtol=1e-12)
    # between temperatures: the linear blend of the neighbouring curves (20 C: half of 10 C and half of 30 C)
    F10, G10 = sf.factors(STRAINS, 10.0)
    F30, G30 = sf.factors(STRAINS, 30.0)
    F20, G20 = sf.factors(STRAINS, 20.0)
    np.testing.assert_allclose(F20, 0.5 * (F10 + F30), rtol=1e-14)
    np.testing.assert_allclose(G20, 0.5 * (G10 + G30), rtol=1e-14)
    # between strains: linear in ln(strain), within 1 % of the smooth law at mid-points of the 15-point sweep
    mid = np.sqrt(STRAINS[1:] * STRAINS[:-1])
    f, _ = kraus(mid, 30.0)
    np.testing.assert_allclose(sf.factors(mid, 30.0)[0], f / kraus(STRAINS[:1], 30.0)[0], rtol=1e-2)


def test_flat_sweep_gives_unit_factors_everywhere():
    sf = materials.strain_factors(sweeps(flat=True))
    e = np.concatenate([[0.0, 1e-6], STRAINS, [0.9, 5.0]])
    F, G = sf.factors(e[:, None], np.array([-40.0, 0.0, 25.0, 80.0]))
    assert F.shape == (e.size, 4) and np.all(F == 1.0) and np.all(G == 1.0)
    assert sf.is_constant


def test_outside_the_data_the_factors_are_clamped():
    sf = materials.strain_factors(sweeps())
    F_hi, G_hi = sf.factors(STRAINS[-1], 10.0)
    assert sf.factors(3.0, 10.0) == (F_hi, G_hi)                 # above the largest strain: held
    assert sf.factors(1e-6, 10.0) == (1.0, 1.0)                  # below the smallest: the linear regime
    assert sf.factors(0.0, 10.0) == (1.0, 1.0)
    np.testing.assert_array_equal(sf.factors(STRAINS, -30.0)[0], sf.factors(STRAINS, 0.0)[0])   # coldest curve
    np.testing.assert_array_equal(sf.factors(STRAINS, 90.0)[1], sf.factors(STRAINS, 50.0)[1])   # warmest curve


def test_several_frequencies_are_combined_and_references_respected():
    sf = materials.strain_factors(sweeps(freqs=(1.0, 10.0, 100.0)))
    f, g = kraus(STRAINS, 30.0)
    np.testing.assert_allclose(sf.factors(STRAINS, 30.0)[0], f / f[0], rtol=1e-12)
    assert "12 sweeps at 4 temperatures" in sf.source
    ref = materials.strain_factors(sweeps(), reference_strain=float(STRAINS[4]))
    f, g = kraus(STRAINS, 10.0)
    np.testing.assert_allclose(ref.factors(STRAINS[12], 10.0), (f[12] / f[4], g[12] / g[4]), rtol=1e-12)
    assert ref.factors(STRAINS[0], 10.0)[0] == pytest.approx(f[0] / f[4], rel=1e-12) and f[0] / f[4] > 1
    with pytest.raises(InputError, match="reference_strain"):
        materials.strain_factors(sweeps(), reference_strain=2.0)


def test_broadcasting_errors_and_speed():
    sf = materials.strain_factors(sweeps())
    strain = np.geomspace(1e-4, 1.0, 400)[:, None]
    T = np.linspace(-10.0, 70.0, 250)[None, :]
    F, G = sf.factors(strain, T)
    assert F.shape == G.shape == (400, 250)
    assert np.all((F > 0) & (F <= 1.0 + 1e-12)) and np.all(G > 0)
    # one evaluation on a (q, T) grid of 1e6 points: well under a second (0.35 s measured on a busy 2-core machine)
    big_e = np.geomspace(1e-4, 1.0, 1000)[:, None]
    big_T = np.linspace(0.0, 60.0, 1000)[None, :]
    t = time.perf_counter()
    sf.factors(big_e, big_T)
    assert time.perf_counter() - t < 1.5
    with pytest.raises(InputError, match="strain"):
        sf.factors(np.array([0.1, np.nan]), 20.0)
    with pytest.raises(InputError, match="strain"):
        sf.factors(-0.1, 20.0)
    with pytest.raises(InputError, match="give T"):
        sf.factors(0.1)
    with pytest.raises(InputError, match="broadcast"):
        sf.factors(np.ones(3), np.ones(4))


def test_constant_factors_pickle_and_repr():
    c = materials.StrainFactors.constant(0.22, 0.42)
    F, G = c.factors(np.geomspace(1e-4, 1, 7)[:, None], np.array([-20.0, 80.0]))
    assert np.all(F == 0.22) and np.all(G == 0.42) and c.is_constant and c.temperature_range is None
    assert c.factors(0.3) == (0.22, 0.42)
    with pytest.raises(InputError, match="positive"):
        materials.StrainFactors.constant(0.0, 0.4)
    old = materials.StrainSoftening(np.array([0.01, 0.1]), np.array([1.0, 0.5]), np.array([1.0, 0.8]))
    conv = materials.StrainFactors.from_softening(old)
    np.testing.assert_allclose(conv.factors(0.05), old.factors(0.05))
    sf = materials.strain_factors(sweeps())
    back = pickle.loads(pickle.dumps(sf))
    np.testing.assert_array_equal(back.factors(STRAINS, 20.0)[0], sf.factors(STRAINS, 20.0)[0])
    for obj in (c, sf, sweeps(), old):
        assert "array(" not in repr(obj) and len(repr(obj)) < 300


# ---------------------------------------------------------------------------------------------- readers

def _write(path, text, encoding="utf-8"):
    path.write_bytes(text.encode(encoding))
    return path


def test_read_strain_sweeps_from_exports(tmp_path):
    # one file per temperature (name carries it), strain in %, moduli in MPa, a units row, Latin-1
    for T in TEMPS:
        f, g = kraus(STRAINS, T)
        body = "".join(f"{100 * s:.6g}   {8 * (1 - T / 100) * a:.8g}   {2 * (1 - T / 120) * b:.8g}\n"
                       for s, a, b in zip(STRAINS, f, g))
        _write(tmp_path / f"sweep_T{T:g}.txt", "Strain E' E\"\n[%] [MPa] [MPa]\n" + body, "latin-1")
    sw = materials.read_strain_sweep(tmp_path)
    assert len(sw) == TEMPS.size * STRAINS.size and sw.strain.max() == pytest.approx(0.5, rel=1e-5)
    sf = materials.strain_factors(sw)
    np.testing.assert_array_equal(sf.T_C, TEMPS)
    f, g = kraus(STRAINS, 50.0)
    np.testing.assert_allclose(sf.factors(STRAINS, 50.0)[0], f / f[0], rtol=1e-6)
    # the project's long DMA table with a strain column reads the same way
    rows = ["T_C,f_Hz,E_storage_Pa,E_loss_Pa,strain"]
    for T in TEMPS:
        f, g = kraus(STRAINS, T)
        rows += [f"{T:g},10,{float(8e6 * a)!r},{float(2e6 * b)!r},{float(s)!r}" for s, a, b in zip(STRAINS, f, g)]
    p = _write(tmp_path / "long.csv", "\n".join(rows) + "\n")
    sf2 = materials.strain_factors(materials.read_strain_sweep(p))
    sf3 = materials.strain_factors(materials.read_dma(p))
    np.testing.assert_allclose(sf2.storage_factor, sf3.storage_factor, rtol=1e-15)


def test_header_less_sweep_with_declared_columns(tmp_path):
    f, g = kraus(STRAINS, 20.0)
    p = _write(tmp_path / "s.csv", "".join(f"{float(s)!r},{float(3e6 * a)!r},{float(1e6 * b)!r}\n" for s, a, b in zip(STRAINS, f, g)))
    with pytest.raises(InputError, match="no header row"):
        materials.read_strain_sweep(p, T=20.0)
    sw = materials.read_strain_sweep(p, columns=["strain", "E_storage_Pa", "E_loss_Pa"], T=20.0)
    assert np.all(sw.T_C == 20.0)
    with pytest.raises(InputError, match="no temperature column"):
        materials.read_strain_sweep(p, columns=["strain", "E_storage_Pa", "E_loss_Pa"])


def test_strain_sweep_unit_slips_are_refused(tmp_path):
    f, g = kraus(STRAINS, 20.0)
    p = _write(tmp_path / "pct.csv", "T_C,strain,E_storage_Pa,E_loss_Pa\n"
               + "".join(f"20,{float(100 * s)!r},{float(3e6 * a)!r},{float(1e6 * b)!r}\n" for s, a, b in zip(STRAINS, f, g)))
    with pytest.raises(InputError, match=r"pct.csv, column 'strain'.*look like percent"):
        materials.read_strain_sweep(p)
    sw = materials.read_strain_sweep(p, units={"strain": "%"})
    assert sw.strain.max() == pytest.approx(0.5)
    p = _write(tmp_path / "mpa.csv", "T_C,strain,E_storage_Pa,E_loss_Pa\n"
               + "".join(f"20,{float(s)!r},{float(3 * a)!r},{float(1 * b)!r}\n" for s, a, b in zip(STRAINS, f, g)))
    with pytest.raises(InputError, match=r"mpa.csv, column 'E_storage_Pa'.*MPa"):
        materials.read_strain_sweep(p)
    with pytest.raises(InputError, match="line 2, column 'strain'"):
        materials.StrainSweep.from_arrays([20.0, 20.0], [0.0, 0.1], [1e6, 1e6], [1e5, 1e5], line=[2, 3],
                                          source="x.csv")
    with pytest.raises(InputError, match="two strain amplitudes"):
        materials.strain_factors(materials.StrainSweep.from_arrays([20.0, 30.0], [0.1, 0.1], [1e6, 1e6], [1e5, 1e5]))
