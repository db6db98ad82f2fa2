"""``persson tread CASE``: the [tire] section, CSV outputs, plots, and the output rules (no overwrite without
--force, never over an input)."""

import math

import numpy as np
import pytest

import surfaces
from persson.cli import main
from persson.errors import InputError

CASE = """\
name = "tread-test"
[surface]
profiles = ["road.csv"]
[material]
example = "tread"
[conditions]
temperature_C = 20.0
[tire]
diameter_m = 0.63
width_m = 0.205
load_N = 4000.0
inflation_pressure_Pa = 2.2e5
tread_depth_m = 8e-3
grooves = { width_m = 8e-3, pitch_m = 30e-3 }
water = { thickness_m = 1e-3 }
speeds_m_s = [10.0, 20.0]
slips = [0.1, 1.0]
mu_loc = 0.5
element_size_m = 5e-4
"""


def table(path):
    """The numbers of a CSV written by a command (comment lines and the header left out)."""
    lines = [x for x in path.read_text().splitlines() if x and not x.startswith("#")]
    return np.array([[float(v) for v in x.split(",")] for x in lines[1:]])


@pytest.fixture
def case(tmp_path):
    sa = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.15e-3, qL=2 * math.pi / 0.1)
    ps = surfaces.synthesize_profiles(sa, n_profiles=2, n=4000, length=0.4, seed=7)
    table = np.column_stack([ps[0].x * 1e3, ps[0].z * 1e3, ps[1].z * 1e3])
    np.savetxt(tmp_path / "road.csv", table, delimiter=",", header="x_mm,z1_mm,z2_mm", comments="")
    (tmp_path / "case.toml").write_text(CASE)
    return tmp_path


def test_tread_command_writes_the_map_and_the_summary(case, capsys):
    out = case / "map.csv"
    assert main(["tread", str(case / "case.toml"), "-o", str(out), "-q", "--plot"]) == 0
    head = out.read_text().splitlines()
    columns = next(line for line in head if not line.startswith("#")).split(",")
    assert columns == ["speed_m_s", "slip", "mu", "mu_std", "contact_fraction", "penetration_m", "lift_N"]
    rows = table(out)
    assert rows.shape == (4, 7) and np.all(rows[:, 6] > 0)              # wet: the bearing lifts at every point
    summary = (case / "map_summary.csv").read_text()
    assert "peak_mu" in summary and "locked_mu" in summary
    assert (case / "map.png").stat().st_size > 0 and (case / "map_bars.png").stat().st_size > 0
    assert "wrote" in capsys.readouterr().out
    # again without --force: refused, the file kept; with --force, rewritten; --dry has no lift
    before = out.read_text()
    assert main(["tread", str(case / "case.toml"), "-o", str(out), "-q"]) == 2
    assert out.read_text() == before
    assert main(["tread", str(case / "case.toml"), "-o", str(out), "-q", "--force", "--dry"]) == 0
    assert np.all(table(out)[:, 6] == 0)


def test_tread_command_refuses_bad_cases_and_inputs_as_outputs(case, capsys):
    assert main(["tread", str(case / "case.toml"), "-o", str(case / "road.csv"), "-q"]) == 2
    assert "road.csv" in capsys.readouterr().err
    bad = CASE.replace("pitch_m = 30e-3", "pitch_m = 5e-3")
    (case / "case.toml").write_text(bad)
    assert main(["tread", str(case / "case.toml"), "-q"]) == 2
    assert "no rubber" in capsys.readouterr().err
    (case / "case.toml").write_text(CASE.replace("tread_depth_m", "tread_depht_m"))
    assert main(["tread", str(case / "case.toml"), "-q"]) == 2
    assert "did you mean 'tread_depth_m'" in capsys.readouterr().err


def test_case_without_tire_section_is_refused(tmp_path):
    from persson.tread.case import read_tread_case

    (tmp_path / "case.toml").write_text('[surface]\nexample = "road"\n[material]\nexample = "tread"\n')
    with pytest.raises(InputError, match=r"no \[tire\] section"):
        read_tread_case(tmp_path / "case.toml")
