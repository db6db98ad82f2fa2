"""case.toml: the schema (typos, types, units), the material from DMA isotherms, the master-curve cache."""

from pathlib import Path

import numpy as np
import pytest

import materials
from persson import InputError
from persson.case import read_case


@pytest.fixture()
def dma_dir(tmp_path):
    tread = materials.example_tread()
    f = np.geomspace(0.1, 100, 8)
    rows = ["T_C,f_Hz,E_storage_Pa,E_loss_Pa"]
    for T in (-20.0, -10.0, 0.0, 10.0, 20.0, 40.0):
        E = tread.E(2 * np.pi * f, T)
        rows += [f"{T},{float(ff)!r},{float(e.real)!r},{float(e.imag)!r}" for ff, e in zip(f, E)]
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
    (tmp_path / "scan.csv").write_text("x_m,z_m\n" + "\n".join(f"{float(a)!r},{float(b)!r}" for a, b in zip(x, z)))
    (tmp_path / "case.toml").write_text('[surface]\nprofiles = ["scan.csv"]\nisotropic_options = { q_max = 3e4 }\n'
                                        '[material]\nexample = "tread"\n')
    s = read_case(tmp_path / "case.toml").model.surface
    assert s.q_range[1] <= 3e4 * (1 + 1e-9)
    (tmp_path / "case.toml").write_text('[surface]\nprofiles = ["scan.csv"]\nisotropic_options = { nonsense = 1 }\n'
                                        '[material]\nexample = "tread"\n')
    with pytest.raises(ValueError, match="isotropic_options"):
        read_case(tmp_path / "case.toml")


# ------------------------------------------------------------------------------------------------- schema
BASE = '[surface]\nexample = "road"\n[material]\nexample = "tread"\n'


def _case(tmp_path, text):
    (tmp_path / "case.toml").write_text(text)
    return tmp_path / "case.toml"


@pytest.mark.parametrize("text, words", [
    (BASE + '[model]\ngamma = "half"\n', ["[model] gamma", "expected a number", "'half'"]),
    (BASE + '[model]\neffects = ["adhesion"]\n[model.adhesion]\ntau_f0 = [1, 2]\n',
     ["[model.adhesion] tau_f0", "expected a number", "[1, 2]"]),
    (BASE + '[measurements]\nfile = 5\n', ["[measurements] file", "expected a file name", "got 5"]),
    (BASE + '[modle]\ngamma = 0.4\n', ["unknown section [modle]", "did you mean [model]"]),
    (BASE + '[model]\neffects = ["adhesion"]\n[model.adhesoin]\ntau_f0 = 1e6\n',
     ["unknown section [model.adhesoin]", "did you mean [model.adhesion]"]),
    (BASE + '[model]\ngama = 0.4\n', ["unknown key 'gama' in [model]", "did you mean 'gamma'"]),
    (BASE + 'nmae = "x"\n', ["unknown key 'nmae' in [material]"]),
    ('nmae = "x"\n' + BASE, ["unknown key 'nmae' in the top level", "did you mean 'name'"]),
    (BASE + '[model]\neffects = ["adhesoin"]\n', ["unknown effect 'adhesoin'", "did you mean 'adhesion'"]),
    (BASE + '[model]\neffects = ["adhesion"]\n[model.adhesion]\ntau_f = 1e6\n',
     ["[model.adhesion]", "unknown parameter of the adhesion effect 'tau_f'", "did you mean 'tau_f0'"]),
    (BASE + '[model.adhesion]\ntau_f0 = 1e6\n', ["[model.adhesion]", "not switched on", "effects"]),
    (BASE + '[model]\ngrid = { q_per_decad = 40 }\n', ["[model] grid", "'q_per_decad'", "'q_per_decade'"]),
    (BASE.replace('example = "tread"', 'example = "tread"\nthermal = { conductivty = 0.2 }'),
     ["[material] thermal", "'conductivty'", "did you mean 'conductivity'"]),
    (BASE.replace('example = "tread"', 'example = "tread"\npoisson = 0.7'), ["[material] poisson", "[0, 0.5]"]),
    (BASE.replace('example = "tread"', 'example = "tread"\nTg = "auto"'), ["Tg_C", "applies only with dma"]),
    (BASE + '[contact]\npressure_distribution = "parabolc"\n', ["pressure_distribution", "did you mean 'parabolic'"]),
    (BASE + '[conditions]\nspeeds_m_s = [1.0, -2.0]\n', ["[conditions] speeds_m_s[1]", "> 0"]),
    (BASE + '[conditions]\nspeeds_m_s = [1.0]\nspeed_range_m_s = [1e-3, 1, 5]\n', ["not both"]),
    (BASE + '[conditions]\nspeed_range_m_s = [1e-3, 1]\n', ["speed_range_m_s", "[min, max, n]"]),
    (BASE.replace('example = "road"', 'example = "road"\nread_options = { delimiter = ";" }'),
     ["read_options", "applies only with profiles"]),
    (BASE.replace('example = "road"', 'example = "road"\npsd = "x.csv"'), ["exactly one of psd, profiles, example"]),
])
def test_case_file_typos_and_wrong_types_name_the_key(tmp_path, text, words):
    with pytest.raises(InputError) as info:
        read_case(_case(tmp_path, text))
    msg = str(info.value)
    assert "case.toml" in msg
    for w in words:
        assert w in msg


@pytest.mark.parametrize("key, value, words", [
    ("pressure_Pa", "0.3", ["pressure_Pa", "looks like MPa", "300000 Pa"]),
    ("pressure_Pa", "300", ["pressure_Pa", "looks like kPa"]),
    ("pressure_Pa", "3e9", ["pressure_Pa", "above any contact pressure"]),
    ("temperature_C", "293.15", ["temperature_C", "looks like kelvin", "20 C"]),
    ("temperature_C", "-400", ["temperature_C", "below absolute zero"]),
])
def test_case_conditions_in_the_wrong_unit_are_refused(tmp_path, key, value, words):
    with pytest.raises(InputError) as info:
        read_case(_case(tmp_path, BASE + f"[conditions]\n{key} = {value}\n"))
    for w in words:
        assert w in str(info.value)


def test_effect_tables_are_honoured(tmp_path):
    spec = read_case(_case(tmp_path, BASE + '[model]\ngamma = 0.4\neffects = ["adhesion"]\n'
                                            '[model.adhesion]\ntau_f0 = 1.5e6\nc = 0.2\n'))
    assert spec.model.gamma == 0.4
    e = spec.model.effect("adhesion")
    assert (e.tau_f0, e.c) == (1.5e6, 0.2)


def test_inputs_are_listed(tmp_path):
    from persson.case import parse_case

    (tmp_path / "m.csv").write_text("slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.1,20,3e5,0.5\n")
    case = parse_case(_case(tmp_path, BASE + '[measurements]\nfile = "m.csv"\n'))
    assert [p.name for p in case.inputs] == ["case.toml", "m.csv"]


def test_shipped_case_names_resolve():
    from persson.case import resolve_case

    assert resolve_case("example").name == "case.toml" and resolve_case("example").parent.name == "example"
    with pytest.raises(InputError, match="did you mean 'example'"):
        resolve_case("exampel")


def test_docs_list_every_key_as_the_schema_declares_it():
    """docs/conventions.md carries the generated key reference; regenerate it with
    ``python -m persson.case.schema docs/conventions.md`` after changing the schema."""
    from pathlib import Path

    from persson.case.schema import BEGIN, END, KEYS, markdown

    text = (Path(__file__).resolve().parents[1] / "docs" / "conventions.md").read_text()
    section = BEGIN + text.split(BEGIN, 1)[1].split(END, 1)[0] + END
    assert section == markdown(), "docs/conventions.md is out of date: python -m persson.case.schema docs/conventions.md"
    for k in KEYS:
        assert f"| `{k.name}` |" in section


# ------------------------------------------------------------------------------------------------- material keys
def test_legacy_Tg_spelling_is_honoured_as_Tg_C(dma_dir, monkeypatch):
    seen = {}
    real = materials.master_curve

    def spy(dma, T_ref, **kw):
        seen.update(kw)
        return real(dma, T_ref, **kw)

    monkeypatch.setattr(materials, "master_curve", spy)
    monkeypatch.setenv("PERSSON_NO_CACHE", "1")
    (dma_dir / "case.toml").write_text('[surface]\nexample = "road"\n[material]\ndma = "dma.csv"\n'
                                       'wlf = { C1 = 8.86, C2 = 101.6, T_ref_C = 20.0 }\nTg = -40.0\n')
    read_case(dma_dir / "case.toml")
    assert seen["Tg"] == -40.0
    (dma_dir / "case.toml").write_text('[surface]\nexample = "road"\n[material]\ndma = "dma.csv"\n'
                                       'Tg = -40.0\nTg_C = -40.0\n')
    with pytest.raises(InputError, match="both Tg_C and its older spelling Tg"):
        read_case(dma_dir / "case.toml")


def test_dma_as_a_list_of_files_and_as_a_folder(dma_dir, monkeypatch):
    monkeypatch.setenv("PERSSON_NO_CACHE", "1")
    lines = (dma_dir / "dma.csv").read_text().splitlines()
    head, rows = lines[0], lines[1:]
    folder = dma_dir / "isotherms"
    folder.mkdir()
    for T in sorted({r.split(",")[0] for r in rows}):
        (folder / f"T{T}.csv").write_text("\n".join([head] + [r for r in rows if r.split(",")[0] == T]) + "\n")
    wlf = 'wlf = { C1 = 8.86, C2 = 101.6, T_ref_C = 20.0 }\n'
    w = np.array([1e2, 1e4])
    ref = None
    for dma in ('"isotherms"', str([f"isotherms/{p.name}" for p in sorted(folder.iterdir())]).replace("'", '"')):
        (dma_dir / "case.toml").write_text(f'[surface]\nexample = "road"\n[material]\ndma = {dma}\n{wlf}')
        spec = read_case(dma_dir / "case.toml")
        assert len([p for p in spec.inputs if p.parent == folder]) == 6
        E = spec.model.material.E(w, 30.0)
        ref = E if ref is None else ref
        np.testing.assert_allclose(E, ref, rtol=1e-4)  # same points; the fit may see them in another order
    np.testing.assert_allclose(ref, materials.example_tread().E(w, 30.0), rtol=0.02)


def test_missing_dma_folder_is_named(dma_dir):
    (dma_dir / "case.toml").write_text('[surface]\nexample = "road"\n[material]\ndma = "nowhere"\n')
    with pytest.raises(InputError, match=r"\[material\] dma: .*nowhere does not exist"):
        read_case(dma_dir / "case.toml")


def test_shift_factor_table_beside_a_master_curve(tmp_path):
    """A tabulated shift-factor file next to a master-curve table: E(w, T) = E(w aT(T), T_ref) with aT interpolated."""
    if not hasattr(materials, "read_shift_factors"):
        pytest.skip("materials.read_shift_factors not available yet")
    tread = materials.example_tread()
    f = np.geomspace(1e-3, 1e8, 120)
    E = tread.E(2 * np.pi * f, 20.0)
    (tmp_path / "mc.csv").write_text("f_Hz,E_storage_Pa,E_loss_Pa\n"
                                     + "\n".join(f"{float(a)!r},{float(e.real)!r},{float(e.imag)!r}" for a, e in zip(f, E)) + "\n")
    Ts = np.arange(-10.0, 61.0, 5.0)
    (tmp_path / "aT.csv").write_text("T_C,log10_aT\n" + "\n".join(f"{float(T)!r},{float(tread.log10_aT(T))!r}" for T in Ts))
    (tmp_path / "case.toml").write_text('[surface]\nexample = "road"\n[material]\nmaster_curve = "mc.csv"\n'
                                        'shift_factors = "aT.csv"\n')
    m = read_case(tmp_path / "case.toml").model.material
    w = np.array([1e1, 1e3])
    np.testing.assert_allclose(m.E(w, 40.0), tread.E(w, 40.0), rtol=0.03)


# ------------------------------------------------------------------------------------------------- cache
def test_master_curve_cache_hits_on_the_same_files_and_misses_when_they_change(dma_dir, tmp_path_factory,
                                                                                   monkeypatch):
    cache = tmp_path_factory.mktemp("cache")
    monkeypatch.setenv("PERSSON_CACHE_DIR", str(cache))
    monkeypatch.delenv("PERSSON_NO_CACHE", raising=False)
    calls = []
    real = materials.master_curve

    def counting(*a, **kw):
        calls.append(1)
        return real(*a, **kw)

    monkeypatch.setattr(materials, "master_curve", counting)
    (dma_dir / "case.toml").write_text('[surface]\nexample = "road"\n[material]\ndma = "dma.csv"\n'
                                       'wlf = { C1 = 8.86, C2 = 101.6, T_ref_C = 20.0 }\n')
    first = read_case(dma_dir / "case.toml")
    assert len(calls) == 1 and any("built and cached" in n for n in first.notes)
    second = read_case(dma_dir / "case.toml")
    assert len(calls) == 1, "the second read must not refit"
    assert any("loaded from the cache" in n for n in second.notes)
    w = np.geomspace(1, 1e6, 5)
    np.testing.assert_array_equal(second.model.material.E(w, 30.0), first.model.material.E(w, 30.0))
    assert not any(cache in p.parents for p in dma_dir.rglob("*")) and list(cache.rglob("*.pickle"))
    text = (dma_dir / "dma.csv").read_text().splitlines()
    text[3] = text[3].rsplit(",", 1)[0] + ",1234567.0"  # one loss modulus changed
    (dma_dir / "dma.csv").write_text("\n".join(text) + "\n")
    third = read_case(dma_dir / "case.toml")
    assert len(calls) == 2 and any("built and cached" in n for n in third.notes)
    monkeypatch.setenv("PERSSON_NO_CACHE", "1")
    read_case(dma_dir / "case.toml")
    assert len(calls) == 3


def test_cache_is_never_placed_among_the_inputs(dma_dir, monkeypatch):
    monkeypatch.setenv("PERSSON_CACHE_DIR", str(dma_dir / "cache"))
    (dma_dir / "case.toml").write_text('[surface]\nexample = "road"\n[material]\ndma = "dma.csv"\n'
                                       'wlf = { C1 = 8.86, C2 = 101.6, T_ref_C = 20.0 }\n')
    spec = read_case(dma_dir / "case.toml")
    assert any("not cached" in n for n in spec.notes) and not (dma_dir / "cache").exists()


# ------------------------------------------------------------------------------------------------- real DMA exports
DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "dma"


@pytest.mark.data
@pytest.mark.skipif(not DATA.is_dir(), reason=f"DMA data not found in {DATA} (shared data absent)")
def test_real_exports_go_into_a_case_file(tmp_path, monkeypatch):
    """An Eplexor export folder with Tg = "auto" (older spelling), and pyvisco data beside pyvisco's own shift
    factors, are read from case.toml; the master curve follows the measured isotherms."""
    monkeypatch.setenv("PERSSON_CACHE_DIR", str(tmp_path / "cache"))
    (tmp_path / "eplexor.toml").write_text(f'[surface]\nexample = "road"\n[material]\ndma = "{DATA / "eplexor"}"\n'
                                           'T_ref_C = 50.0\nTg = "auto"\n')
    spec = read_case(tmp_path / "eplexor.toml")
    assert len([p for p in spec.inputs if p.parent == DATA / "eplexor"]) == 23  # 22 isotherms + LICENSE
    dma = materials.read_dma(DATA / "eplexor")
    iso = int(np.argmin(np.abs(np.asarray(dma.T_isotherm) - 60.0)))
    sel = np.asarray(dma.isotherm) == iso
    T = float(dma.T_isotherm[iso])
    E = spec.model.material.E(2 * np.pi * dma.f_Hz[sel], T)
    assert sel.sum() > 5
    assert np.median(np.abs(np.log10(np.abs(E) / np.hypot(dma.E_storage[sel], dma.E_loss[sel])))) < 0.1
    if not hasattr(materials, "read_shift_factors"):
        return
    (tmp_path / "pyvisco.toml").write_text(
        f'[surface]\nexample = "road"\n[material]\ndma = "{DATA / "pyvisco" / "freq_user_raw.csv"}"\n'
        f'shift_factors = "{DATA / "pyvisco" / "freq_user_master__shift_factors.csv"}"\nT_ref_C = -5.0\n')
    m = read_case(tmp_path / "pyvisco.toml").model.material
    shifts = materials.read_shift_factors(DATA / "pyvisco" / "freq_user_master__shift_factors.csv")
    for T in (-20.0, 30.0):
        assert float(m.log10_aT(T)) == pytest.approx(float(shifts.log10_aT(T)), abs=1e-6)
