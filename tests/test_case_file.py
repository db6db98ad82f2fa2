"""case.toml: the material from DMA isotherms, with and without the compound's WLF constants."""

import numpy as np
import pytest

import materials
from persson.case import read_case


@pytest.fixture()
def dma_dir(tmp_path):
    tread = materials.example_tread()
    f = np.geomspace(0.1, 100, 8)
    rows = ["T_C,f_Hz,E_storage_Pa,E_loss_Pa"]
    for T in (-20.0, -10.0, 0.0, 10.0, 20.0, 40.0):
        E = tread.E(2 * np.pi * f, T)
        rows += [f"{T},{ff!r},{e.real!r},{e.imag!r}" for ff, e in zip(f, E)]
    (tmp_path / "dma.csv").write_text("\n".join(rows) + "\n")
    return tmp_path


def test_dma_with_wlf_uses_the_given_shift(dma_dir):
    (dma_dir / "case.toml").write_text('[surface]\nexample = "road"\n[material]\ndma = "dma.csv"\n'
                                       'wlf = { C1 = 8.86, C2 = 101.6, T_ref_C = 20.0 }\n')
    m = read_case(dma_dir / "case.toml").model.material
    assert (m.wlf.C1, m.wlf.C2, m.wlf.T_ref) == (8.86, 101.6, 20.0)
    w = np.array([1e2, 1e4])
    truth = materials.example_tread().E(w, 30.0)
    np.testing.assert_allclose(m.E(w, 30.0), truth, rtol=0.02)


def test_dma_without_wlf_is_shifted_automatically(dma_dir):
    (dma_dir / "case.toml").write_text('[surface]\nexample = "road"\n[material]\ndma = "dma.csv"\nT_ref_C = 20.0\n')
    m = read_case(dma_dir / "case.toml").model.material
    assert m.wlf.C1 == pytest.approx(8.86, rel=0.1) and m.wlf.C2 == pytest.approx(101.6, rel=0.1)


def test_profiles_with_options(tmp_path):
    rng = np.random.default_rng(0)
    x = np.arange(8192) * 20e-6
    z = np.cumsum(rng.normal(size=x.size)) * 2e-6
    (tmp_path / "scan.csv").write_text("x_m,z_m\n" + "\n".join(f"{a!r},{b!r}" for a, b in zip(x, z)))
    (tmp_path / "case.toml").write_text('[surface]\nprofiles = ["scan.csv"]\nisotropic_options = { q_max = 3e4 }\n'
                                        '[material]\nexample = "tread"\n')
    s = read_case(tmp_path / "case.toml").model.surface
    assert s.q_range[1] <= 3e4 * (1 + 1e-9)
    (tmp_path / "case.toml").write_text('[surface]\nprofiles = ["scan.csv"]\nisotropic_options = { nonsense = 1 }\n'
                                        '[material]\nexample = "tread"\n')
    with pytest.raises(ValueError, match="isotropic_options"):
        read_case(tmp_path / "case.toml")
