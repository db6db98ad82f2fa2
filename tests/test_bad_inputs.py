"""The catalogue of bad inputs: every one gives a clear error or a warning that names what was assumed.

Each case below is one a new user met on a real tread data set: a unit slip, a typo, a file in the wrong place,
a declared input that was silently ignored. The rule the tests hold the package to: no silently wrong result, no
crash (a raw TypeError or a numpy error), and every message names the key, file, line or argument at fault and
what was expected.
"""

import ast
import math
from pathlib import Path

import numpy as np
import pytest

import frictionerrors
import materials
import persson
import surfaces
import validation
from persson.commands.cli import main
from persson.effects import Adhesion, Effect, FlashTemperature, Parameter

ROOT = Path(__file__).resolve().parents[1]
ROAD = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e5, hrms=0.2e-3, qL=2 * math.pi / 0.1)
TREAD = materials.example_tread()
CASE = """name = "tread"
[surface]
psd = "surface_psd.csv"
{surface}
[material]
master_curve = "master_curve.csv"
wlf = {{ C1 = 8.86, C2 = 101.6, T_ref_C = 20.0 }}
{material}
[model]
effects = {effects}
grid = {{ q_per_decade = 8 }}
{model}
[conditions]
speeds_m_s = {speeds}
[measurements]
file = "measurements.csv"
"""
MEASUREMENTS = ("slip,speed_m_s,T_C,pressure_Pa,mu,series\n"
                "1,0.01,20,300000,0.5,sliding\n1,0.1,20,300000,0.6,sliding\n1,1.0,20,300000,0.7,sliding\n")


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """A case folder: a road PSD table (no roll-off declared), a master curve, three measured rows."""
    d = tmp_path_factory.mktemp("case")
    ROAD.tabulate(6).with_rolloff(None).to_csv(d / "surface_psd.csv")
    f = np.logspace(-8, 14, 45)
    E = TREAD.E(2 * np.pi * f, 20.0)
    persson.io.write_csv(d / "master_curve.csv", {"f_Hz": f, "E_storage_Pa": E.real, "E_loss_Pa": E.imag})
    (d / "measurements.csv").write_text(MEASUREMENTS)
    return d


def case(folder, name="case.toml", *, surface="", material="", effects="[]", model="", speeds="[0.01, 1.0]"):
    path = folder / name
    path.write_text(CASE.format(surface=surface, material=material, effects=effects, model=model, speeds=speeds))
    return path


def read_case(path):
    from persson.case.loader import read_case as read

    return read(path)


def says(message, *words):
    """The message names every one of ``words`` (the key, file, line or argument, and what was expected)."""
    text = str(message)
    missing = [w for w in words if w not in text]
    assert not missing, f"{missing} not in: {text}"


def cli(capsys, *argv):
    code = main([str(a) for a in argv])
    out = capsys.readouterr()
    return code, out.out, out.err


# ------------------------------------------------------------------------------------- silently wrong, before
def test_a_report_never_overwrites_an_input_of_the_case(folder, tmp_path):
    meas = validation.read_measurements(folder / "measurements.csv")
    model = persson.Model(ROAD, TREAD, grid=persson.GridSettings(q_per_decade=8))
    cmp = validation.compare(model, meas)
    before = (folder / "measurements.csv").read_text()
    with pytest.raises(frictionerrors.InputError) as err:
        validation.write_report([cmp], folder / "measurements.csv", overwrite=True)
    says(err.value, "measurements.csv", "input", "choose another file name")
    assert (folder / "measurements.csv").read_text() == before
    out = tmp_path / "report.html"
    out.write_text("an earlier report")
    with pytest.raises(frictionerrors.InputError) as err:
        validation.write_report([cmp], out)
    says(err.value, "report.html", "exists", "overwrite=True")
    validation.write_report(["a paragraph"], out, overwrite=True)  # (a comparison's figures take seconds)
    assert "a paragraph" in out.read_text()


def test_python_writers_refuse_an_existing_file_unless_asked(folder, tmp_path):
    path = tmp_path / "psd.csv"
    ROAD.to_csv(path, n_per_decade=4)
    master = materials.read_master_curve(folder / "master_curve.csv", wlf=materials.WLF(8.86, 101.6, 20.0))
    for write in (lambda: ROAD.to_csv(path, n_per_decade=4),
                  lambda: persson.io.write_csv(path, {"a": [1.0]}),
                  lambda: master.to_table(path)):
        with pytest.raises(frictionerrors.InputError) as err:
            write()
        says(err.value, "psd.csv", "exists", "overwrite=True")
    ROAD.to_csv(path, n_per_decade=4, overwrite=True)


@pytest.mark.parametrize("argv, words", [
    (["--pressures", "0.1,0.3", "--estar", "4e6"], ["--pressures", "0.1 Pa", "looks like MPa"]),
    (["--pressures", "1e5:1e6:3", "--estar", "4"], ["--estar", "E* = 4 Pa", "looks like MPa"]),
    (["--pressures", "1e6:1e4:0", "--estar", "4e6"], ["--pressures '1e6:1e4:0'", "n = 0", "n >= 1"]),
    (["--pressures", "0:1e6:5", "--estar", "4e6"], ["--pressures '0:1e6:5'", "values > 0 Pa", "log-spaced"]),
    (["--pressures", "1e5", "--estar", "4e6", "--temperature", "293.15"], ["--temperature", "looks like kelvin"]),
])
def test_contact_command_checks_units_like_friction(folder, capsys, argv, words):
    code, out, err = cli(capsys, "contact", folder / "surface_psd.csv", *argv, "-o", folder / "never.csv")
    assert code == 2 and not (folder / "never.csv").exists()
    says(err, *words)


def test_contact_api_warns_about_unit_slips():
    with pytest.warns(frictionerrors.UnitWarning) as rec:
        persson.contact(ROAD, 4e6, 0.3)
    says(rec[0].message, "pressure: 0.3 Pa", "looks like MPa")
    with pytest.warns(frictionerrors.UnitWarning) as rec:
        r = persson.contact(ROAD, 4.0, 3e5)
    says(rec[0].message, "material_or_Estar", "E* = 4 Pa", "looks like MPa")
    assert any("full contact" in n for n in r.notes)  # and the result says why it is wrong


def test_speeds_faster_than_sound_are_refused_everywhere(folder, capsys):
    model = persson.Model(ROAD, TREAD)
    with pytest.raises(frictionerrors.InputError) as err:
        model.friction(1e5)
    says(err.value, "speed: 100000 m/s", "speed of sound", "km/h")
    with pytest.warns(frictionerrors.UnitWarning, match=r"speed: 150 m/s .* looks like km/h"):
        persson.Model(ROAD, materials.ConstantModulus(5e6, 2e6),
                      grid=persson.GridSettings(q_per_decade=8)).friction(150.0)
    with pytest.raises(frictionerrors.InputError) as err:
        read_case(case(folder, "fast.toml", speeds="[1.0, 1e5]"))
    says(err.value, "fast.toml", "[conditions] speeds_m_s", "speed of sound")
    code, _, err = cli(capsys, "friction", case(folder), "--speeds", "1e5", "-o", folder / "never.csv")
    assert code == 2
    says(err, "--speeds", "speed of sound")


def test_a_profile_in_mm_under_a_um_header_is_warned_about(tmp_path):
    rng = np.random.default_rng(1)
    x = np.arange(4000) * 0.1                      # mm: a 0.4 m scan
    z_mm = np.cumsum(rng.normal(0, 0.02, x.size))  # heights of about 0.5 mm, written as um
    path = tmp_path / "scan.csv"
    path.write_text("x_mm,z_um\n" + "".join(f"{a:.4f},{b:.5f}\n" for a, b in zip(x, z_mm - z_mm.mean())))
    with pytest.warns(frictionerrors.UnitWarning) as rec:
        ps = surfaces.read_profiles(path)
    says(rec[0].message, "scan.csv", "column z_um", "rms height", "z_mm")
    psd = ps.psd().to_isotropic()
    with pytest.warns(frictionerrors.UnitWarning) as rec:
        r = persson.Model(psd, TREAD, grid=persson.GridSettings(q_per_decade=8)).friction(1.0)
    text = " ".join(str(w.message) for w in rec)
    says(text, "rms roughness", "um")
    assert any("um" in n for n in r.notes)


def test_defaults_standing_in_for_thermal_properties_are_listed(folder, capsys, tmp_path):
    path = case(folder, "flash.toml", effects='["flash_temperature"]')
    out = tmp_path / "flash.csv"
    code, _, err = cli(capsys, "friction", path, "-o", out, "-q")
    assert code == 0
    header = "".join(ln for ln in out.read_text().splitlines(True) if ln.startswith("#"))
    says(header, "no thermal table", "density = 1200 kg/m^3", "conductivity = 0.25")
    says(err, "note:", "no thermal table")
    # the PSD table declares no roll-off: the fitted one sets the hot spots, and the result says so
    says(header, "roll-off fitted to it", "q_m = 2 x")
    # the flash column is a rise above the background temperature, and the header says so
    says(header, "max_flash_temperature_K = flash temperature RISE", "not an absolute temperature")


def test_wet_with_adhesion_says_that_wet_removes_adhesion(folder):
    with pytest.warns(persson.PhysicsWarning) as rec:
        spec = read_case(case(folder, "wet.toml", effects='["adhesion", "wet"]'))
    says(rec[0].message, "wet.toml", "[model] effects", "wet removes adhesion", "mu_adhesion = 0")
    r = spec.model.friction(1.0)
    assert r.mu_adhesion == 0.0 and any("wet removes adhesion" in n for n in r.notes)


def test_contact_lengths_above_a_metre_are_refused(folder):
    path = case(folder, "long.toml", model="")
    path.write_text(path.read_text() + "[contact]\nlength_m = 20.0\nwidth_m = 0.01\nstiffness_Pa_per_m = 3e9\n")
    with pytest.raises(frictionerrors.InputError) as err:
        read_case(path)
    says(err.value, "long.toml", "[contact] length_m", "20 m", "0.02 m")
    with pytest.raises(frictionerrors.InputError) as err:
        persson.slip.Contact(length=20.0, width=0.01, stiffness=3e9)
    says(err.value, "contact.length", "20 m")


@pytest.mark.parametrize("line, words", [
    ("1,1.0,20,300000,0.7,sliding,extra\n", ["line 3", "7 fields", "6 columns"]),
    ("1,1.0,20,300000,0.7,sliding, 5 C\n", ["line 3", "must be quoted"]),
])
def test_csv_rows_with_more_fields_than_the_header_are_errors(tmp_path, line, words):
    path = tmp_path / "m.csv"
    path.write_text("slip,speed_m_s,T_C,pressure_Pa,mu,series\n1,0.1,20,300000,0.6,a\n" + line)
    with pytest.raises(frictionerrors.InputError) as err:
        validation.read_measurements(path)
    says(err.value, "m.csv", *words)
    psd = tmp_path / "psd.csv"
    psd.write_text("q,C\n100,1e-10\n1000,1e-13,7\n")
    with pytest.raises(frictionerrors.InputError) as err:
        surfaces.read_psd(psd)
    says(err.value, "psd.csv", "line 3", "3 fields")


@pytest.mark.parametrize("param, words", [
    ("grid.n_phi=12,24", ["'grid.n_phi'", "does not use it"]),
    ("material.quality.rms_rel=0.1,0.2", ["'material.quality.rms_rel'", "statistic of the material's fit"]),
    ("surface.hrm=1e-4", ["'surface.hrm'", "did you mean 'surface.hrms'"]),
])
def test_only_physical_parameters_are_sweepable(folder, capsys, param, words):
    code, _, err = cli(capsys, "sweep", case(folder), "--param", param, "--speeds", "1.0", "-o",
                       folder / "never.csv")
    assert code == 2
    says(err, *words)


def test_effect_parameters_are_checked_when_the_effect_is_built():
    with pytest.raises(frictionerrors.InputError) as err:
        Adhesion(tau_f0="2e6")
    says(err.value, "adhesion.tau_f0", "expected a number in Pa", "'2e6'")
    with pytest.raises(frictionerrors.InputError) as err:
        persson.effects.get("adhesion", tau=1e6)
    says(err.value, "adhesion", "'tau'", "did you mean 'tau_f0'")


# ------------------------------------------------------------------------------------------ unclear, before
def test_a_byte_order_mark_is_accepted_everywhere(folder, tmp_path):
    bom = "\ufeff"
    path = case(folder, "bom.toml")
    path.write_text(bom + path.read_text(), encoding="utf-8")
    for name in ("surface_psd.csv", "measurements.csv"):
        (tmp_path / name).write_text(bom + (folder / name).read_text(), encoding="utf-8")
    assert read_case(path).name == "tread"
    assert surfaces.read_psd(tmp_path / "surface_psd.csv").q.size > 5
    assert validation.read_measurements(tmp_path / "measurements.csv").n == 3
    (tmp_path / "p.csv").write_text(bom + "x_mm,z_mm\n" + "".join(f"{i * 0.1},{math.sin(i)}\n" for i in range(50)),
                                    encoding="utf-8")
    assert surfaces.read_profiles(tmp_path / "p.csv").profiles[0].z.size == 50
    (tmp_path / "dma.csv").write_text(bom + "T_C,f_Hz,E_storage_Pa,E_loss_Pa\n0,1,5e6,1e6\n0,10,6e6,2e6\n",
                                      encoding="utf-8")
    assert materials.read_dma(tmp_path / "dma.csv").f_Hz.size == 2


@pytest.mark.parametrize("speeds, words", [
    ("0:1:10", ["--speeds '0:1:10'", "values > 0 m/s", "log-spaced"]),
    ("1:1e-3:0", ["--speeds '1:1e-3:0'", "n >= 1"]),
    ("fast", ["--speeds 'fast'", "min:max:n"]),
])
def test_speeds_take_the_value_syntax_of_sweep_with_clear_errors(folder, capsys, speeds, words):
    code, _, err = cli(capsys, "friction", case(folder), "--speeds", speeds, "-o", folder / "never.csv")
    assert code == 2
    says(err, *words)


def test_speeds_as_a_list_and_as_a_range(folder, capsys, tmp_path):
    for speeds, n in (("0.01,1", 2), ("1e-3:1:4", 4)):
        out = tmp_path / f"f{n}.csv"
        code, _, _ = cli(capsys, "friction", case(folder), "--speeds", speeds, "-o", out, "-q")
        assert code == 0
        assert sum(1 for ln in out.read_text().splitlines() if ln and not ln.startswith("#")) == n + 1


def test_a_psd_table_given_as_the_case_says_what_a_case_is(folder, capsys):
    code, _, err = cli(capsys, "friction", folder / "surface_psd.csv", "-o", folder / "never.csv")
    assert code == 2
    says(err, "surface_psd.csv", "expected a case file (case.toml)", "[surface] psd")


def test_report_json_dash_prints_to_stdout(folder, capsys, monkeypatch, tmp_path):
    """The report command's plumbing (the loop itself is tested elsewhere): '--json -' writes the JSON to stdout
    and no file named '-'."""
    class Stub:
        name, n, notes = "tread", 3, ()
        spec = measurements = model = contact = None

        def __getattr__(self, _):
            return lambda *a, **k: "{\"verdict\": \"undetermined\"}"

    stub = Stub()
    stub.spec = type("S", (), {"notes": ()})()
    stub.measurements = type("M", (), {"n": 3})()
    monkeypatch.setattr(validation, "load_case", lambda *a, **k: stub)
    monkeypatch.setattr(validation, "compare", lambda *a, **k: stub)
    monkeypatch.setattr(validation, "diagnose", lambda *a, **k: stub)
    monkeypatch.setattr(validation, "write_report", lambda items, path, **k: Path(path).write_text("<html>"))
    monkeypatch.chdir(tmp_path)
    code, out, _ = cli(capsys, "report", case(folder), "--no-improve", "--json", "-", "-o", tmp_path / "r.html")
    assert code == 0
    assert out.strip() == "{\"verdict\": \"undetermined\"}"
    assert not (tmp_path / "-").exists()


def test_a_user_effect_named_like_a_built_in_one_is_refused():
    with pytest.raises(frictionerrors.InputError) as err:
        class MyAdhesion(Effect):
            name = "adhesion"
            parameters = (Parameter("k", 1.0, (0.0, 2.0), "1", "a factor"),)
            k: float = 1.0
    says(err.value, "MyAdhesion", "'adhesion'", "built-in effect", "another name")
    assert persson.effects.effect_class("adhesion") is Adhesion


def test_api_misuse_gives_input_errors_not_type_errors():
    s = ROAD
    for call, words in ((lambda: persson.Model(s, TREAD, effects=FlashTemperature()),
                         ["effects", "expected a list of effects"]),
                        (lambda: materials.ConstantModulus("5e6", 2e6), ["E_storage", "'5e6'"]),
                        (lambda: surfaces.read_psd(None), ["path", "PSD table"]),
                        (lambda: validation.read_measurements(None), ["path", "measurements"])):
        with pytest.raises(frictionerrors.InputError) as err:
            call()
        says(err.value, *words)


def test_strain_sweep_errors_suggest_strain_sweep_columns(tmp_path):
    path = tmp_path / "T20.txt"
    path.write_text("0.1\t8\t2\n1\t7\t2.2\n10\t4\t1.5\n")
    with pytest.raises(frictionerrors.InputError) as err:
        materials.read_strain_sweep(path)
    says(err.value, "T20.txt", "no header row", "strain_pct")


def test_a_modulus_labelled_pa_holding_mpa_is_caught(tmp_path):
    path = tmp_path / "T20.txt"
    path.write_text("0.1\t12.4\t2\n1\t11\t2.2\n10\t8\t1.5\n")
    with pytest.raises(frictionerrors.InputError) as err:
        materials.read_strain_sweep(path, columns=["strain_pct", "E_storage_Pa", "E_loss_Pa"])
    says(err.value, "T20.txt", "column 2", "from the columns option", "look like MPa", "units={'E': 'MPa'}")


def test_q_rolloff_is_a_surface_key(folder):
    spec = read_case(case(folder, "roll.toml", surface="q_rolloff = 1500.0"))
    assert spec.model.surface.q_rolloff == 1500.0
    with pytest.raises(frictionerrors.InputError) as err:
        read_case(case(folder, "roll_bad.toml", surface="q_rolloff = 5.0"))
    says(err.value, "roll_bad.toml", "[surface] q_rolloff", "outside the PSD's q range")


def test_a_psd_without_a_plateau_warns_that_no_rolloff_can_be_fitted():
    table = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6).tabulate(6)
    with pytest.warns(persson.PhysicsWarning, match="none can be fitted"):
        persson.Model(table.with_rolloff(None), TREAD, effects=[FlashTemperature()],
                      grid=persson.GridSettings(q_per_decade=8)).friction(1.0)


# ------------------------------------------------------------------------------------------------ categories
def test_every_warning_of_the_packages_has_a_project_category():
    generic = {"UserWarning", "RuntimeWarning", "Warning", "DeprecationWarning"}
    bad = []
    for package in ("persson", "surfaces", "materials", "validation"):
        for path in (ROOT / package).rglob("*.py"):
            text = path.read_text(encoding="utf-8")
            if "warnings.warn(" not in text:
                continue
            for node in ast.walk(ast.parse(text)):
                if isinstance(node, ast.Call) and getattr(node.func, "attr", None) == "warn" \
                        and getattr(node.func.value, "id", None) == "warnings":
                    cat = node.args[1] if len(node.args) > 1 else next(
                        (k.value for k in node.keywords if k.arg == "category"), None)
                    if cat is None or ast.unparse(cat) in generic:
                        bad.append(f"{path.relative_to(ROOT)}:{node.lineno}")
    assert not bad, f"warnings without a project category: {bad}"
