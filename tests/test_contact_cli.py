"""``persson contact``: the command writes what ``persson.contact`` computes, and keeps the output rules."""

import numpy as np
import pytest

import materials
import surfaces
from persson.commands.cli import main
from persson.contact import contact

CASE = """
name = "contact-test"
[surface]
example = "road"
[material]
example = "tread"
[model]
gamma = 0.5
[conditions]
temperature_C = 25.0
pressure_Pa = 0.4e6
"""


def _read(path):
    lines = [ln for ln in path.read_text().splitlines() if not ln.startswith("#")]
    return np.genfromtxt(lines, delimiter=",", names=True)


@pytest.fixture()
def psd_table(tmp_path):
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6, qL=2e2)
    return s.tabulate(64).to_csv(tmp_path / "surface_psd.csv"), s


def test_psd_table_with_estar_writes_the_api_numbers_and_a_plot(tmp_path, capsys, psd_table):
    path, _ = psd_table
    out = tmp_path / "contact.csv"
    assert main(["contact", str(path), "--estar", "4e6", "--pressures", "1e4:1e6:5", "-o", str(out), "--plot",
                 "--correction", "xu2024", "-q"]) == 0
    printed = capsys.readouterr().out
    assert str(out.resolve()) in printed and out.with_suffix(".png").is_file()
    data = _read(out)
    r = contact(surfaces.read_psd(path), 4e6, np.geomspace(1e4, 1e6, 5), correction="xu2024")
    np.testing.assert_allclose(data["contact_area"], r.contact_area, rtol=1e-12)
    np.testing.assert_allclose(data["mean_separation_m"], r.mean_separation, rtol=1e-12)
    np.testing.assert_allclose(data["elastic_energy_J_m2"], r.elastic_energy, rtol=1e-12)
    assert "correction=xu2024" in out.read_text()


def test_case_with_speed_uses_the_case_material(tmp_path):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    out = tmp_path / "c.csv"
    assert main(["contact", str(case), "--speed", "1.0", "--pressures", "0.3e6,0.8e6", "-o", str(out),
                 "--penetration", "kluppel", "-q"]) == 0
    data = _read(out)
    r = contact(surfaces.example_road(), materials.example_tread(), np.array([0.3e6, 0.8e6]), speed=1.0,
                temperature=25.0, gamma=0.5, penetration="kluppel")
    np.testing.assert_allclose(data["contact_area"], r.contact_area, rtol=1e-12)
    np.testing.assert_allclose(data["penetration_depth_m"], r.penetration_depths["kluppel"], rtol=1e-12)


def test_existing_output_needs_force_and_an_input_is_never_overwritten(tmp_path, capsys, psd_table):
    path, _ = psd_table
    out = tmp_path / "contact.csv"
    args = ["contact", str(path), "--estar", "4e6", "--pressures", "1e5", "-q"]
    assert main(args + ["-o", str(out)]) == 0
    before = out.read_text()
    assert main(args + ["-o", str(out), "--pressures", "2e5"]) == 2
    assert "--force" in capsys.readouterr().err and out.read_text() == before
    assert main(args + ["-o", str(out), "--pressures", "2e5", "--force"]) == 0
    assert out.read_text() != before
    table = path.read_text()
    assert main(args + ["-o", str(path), "--force"]) == 2
    assert "inputs" in capsys.readouterr().err and path.read_text() == table


@pytest.mark.parametrize("extra, word", [
    (["--pressures", "a:b:c"], "--pressures"),
    (["--pressures=0,1e5"], "--pressures"),
    ([], "--estar"),
])
def test_bad_flags_are_named(tmp_path, capsys, psd_table, extra, word):
    path, _ = psd_table
    args = ["contact", str(path), "-o", str(tmp_path / "x.csv"), "-q"]
    if not any(a.startswith("--pressures") for a in extra):
        args += ["--pressures", "1e5"]
    assert main(args + extra) == 2
    assert word in capsys.readouterr().err
    assert not (tmp_path / "x.csv").exists()


def test_case_needs_speed_or_estar(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    assert main(["contact", str(case), "--pressures", "1e5", "-o", str(tmp_path / "x.csv"), "-q"]) == 2
    assert "--speed" in capsys.readouterr().err
