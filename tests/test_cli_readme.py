"""The command line and the README's promises."""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from persson.commands.cli import main

ROOT = Path(__file__).resolve().parents[1]

CASE = """
name = "cli-test"
[surface]
example = "road"
[material]
example = "tread"
[model]
gamma = 0.5
effects = ["flash_temperature", "adhesion"]
[model.adhesion]
tau_f0 = 1.0e6
[conditions]
speed_range_m_s = [1e-4, 1.0, 5]
temperature_C = 25.0
pressure_Pa = 0.4e6
"""


def test_help_lists_the_commands(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["--help"])
    assert exc.value.code == 0
    out = capsys.readouterr().out
    for name in ("demo", "friction", "compare", "diagnose", "report", "sweep"):
        assert f"    {name} " in out


def test_the_program_runs_the_command_of_its_arguments_and_leaves_what_lives_to_the_process_exit(monkeypatch, capsys):
    """The ``persson`` console script and ``python -m persson`` run :func:`persson.commands.cli.program`: the
    command named in ``sys.argv``, its exit status returned; what lives when it ends is moved out of the garbage
    collector's sight, so that the interpreter's shutdown skips full collections over numba's, scipy's and the
    command's objects (0.3 s of a 3.7 s diagnosis)."""
    import gc

    from persson.case.loader import tomllib    # tomllib, or on Python 3.10 the tomli the package depends on
    from persson.commands import cli
    from persson.commands.cli import program

    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts["persson"] == "persson.commands.cli:program"
    assert "program()" in (ROOT / "persson" / "__main__.py").read_text()
    monkeypatch.setattr(sys, "argv", ["persson"])
    gc.unfreeze()
    before = gc.get_threshold()
    try:
        assert program() == 2                    # no command: the help, and status 2
        assert gc.get_freeze_count() > 1000
    finally:
        gc.unfreeze()                            # the rest of the test session collects as before
    assert "usage: persson" in capsys.readouterr().out
    # while the command runs, the oldest generation is collected rarely (its full walks cost a report 0.25-0.5 s);
    # the thresholds are given back afterwards
    seen = []
    monkeypatch.setattr(cli, "main", lambda: seen.append(gc.get_threshold()) or 0)
    try:
        assert program() == 0
    finally:
        gc.unfreeze()
    assert seen == [(before[0], before[1], max(before[2], 1000))] and gc.get_threshold() == before


#: Checks that need a fresh interpreter (what importing a package pulls in, ``python -m persson``).
FRESH_INTERPRETER = {
    "engine imports": [sys.executable, "-c",
                       "import sys, persson, persson.commands.cli, persson.commands.friction, persson.commands.sweep, "
                       "persson.case; print('validation' in sys.modules)"],
    "package imports": [sys.executable, "-c",
                        "import sys, persson, persson.commands.cli, persson.case, materials, surfaces; "
                        "print(sorted(m for m in ('scipy.optimize', 'scipy.interpolate', 'scipy.stats') "
                        "if m in sys.modules))"],
    "python -m persson": [sys.executable, "-m", "persson", "--help"],
    "lazy subpackages": [sys.executable, "-c",
                         "import sys, persson, validation, validation.commands.diagnose; "
                         "before = sorted(m for m in ('persson.tread', 'persson.sweeps') if m in sys.modules); "
                         "from persson import sweeps; "
                         "print(before, callable(persson.tread.simulate), callable(sweeps.grid), "
                         "'tread' in dir(persson))"],
}


@pytest.fixture(scope="module", autouse=True)
def fresh_interpreters():
    """The :data:`FRESH_INTERPRETER` processes, all started when this file's first test runs: each spends seconds
    importing the packages, which they do on another core while the tests run here."""
    procs = {name: subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for name, cmd in FRESH_INTERPRETER.items()}
    yield procs
    for p in procs.values():
        p.kill()
        p.communicate()


def stdout_of(procs, name):
    """What the fresh interpreter ``name`` printed, once it has exited without error."""
    out, err = procs[name].communicate()
    assert procs[name].returncode == 0, f"{FRESH_INTERPRETER[name]} failed:\n{err}"
    return out


def test_the_engine_does_not_import_the_validation_package(fresh_interpreters):
    """The validation commands come in through the ``persson.commands`` entry points, not an import."""
    assert stdout_of(fresh_interpreters, "engine imports").strip() == "False"


def test_importing_the_packages_leaves_the_slow_scipy_subpackages_unloaded(fresh_interpreters):
    """Start-up time of every command: scipy.optimize, scipy.interpolate and scipy.stats (0.2-0.4 s to import) are
    imported by the functions that fit or interpolate, when they run, not by importing the packages."""
    assert stdout_of(fresh_interpreters, "package imports").strip() == "[]"


def test_the_tread_tool_and_the_sweeps_are_imported_when_first_named(fresh_interpreters):
    """Start-up time of the friction and validation commands: ``import persson`` (and the validation package) leaves
    the tread-element tool and the sweeps unloaded; ``persson.tread`` and ``from persson import sweeps`` import
    them then."""
    assert stdout_of(fresh_interpreters, "lazy subpackages").strip() == "[] True True True"


def test_readme_command_table_shows_what_each_command_takes():
    """Every command is in the README table, written with the arguments its parser takes (CASE where it takes one)."""
    from persson.commands.cli import build_parser

    rows = dict(re.findall(r"^\| `persson (\w+)([^`]*)` \|", (ROOT / "README.md").read_text(), re.M))
    sub = next(a for a in build_parser()._actions if a.dest == "==SUPPRESS==" or a.__class__.__name__ ==
               "_SubParsersAction")
    assert set(rows) == set(sub.choices)
    for name, p in sub.choices.items():
        positional = [(a.metavar or a.dest).upper() for a in p._actions if not a.option_strings]
        shown = re.findall(r"\b[A-Z][A-Z_]+\b", rows[name].split("[")[0])
        assert shown == positional, (name, shown, positional)


def test_python_dash_m_runs_the_cli(fresh_interpreters):
    assert "friction" in stdout_of(fresh_interpreters, "python -m persson")


def test_friction_command_writes_csv_matching_the_api(tmp_path, capsys):
    case = tmp_path / "case.toml"
    case.write_text(CASE)
    out = tmp_path / "out.csv"
    assert main(["friction", str(case), "-o", str(out), "--plot"]) == 0
    printed = capsys.readouterr().out
    assert str(out.resolve()) in printed and out.with_suffix(".png").is_file()
    lines = [ln for ln in out.read_text().splitlines() if not ln.startswith("#")]
    data = np.genfromtxt(lines, delimiter=",", names=True)
    import materials
    import persson
    import surfaces

    model = persson.Model(surfaces.example_road(), materials.example_tread(), gamma=0.5,
                          effects=[persson.effects.FlashTemperature(), persson.effects.Adhesion(tau_f0=1e6)])
    r = model.friction(np.geomspace(1e-4, 1.0, 5), temperature=25.0, pressure=0.4e6)
    np.testing.assert_allclose(data["mu"], r.mu, rtol=1e-12)
    np.testing.assert_allclose(data["contact_area"], r.contact_area, rtol=1e-12)
    assert np.all(data["mu_adhesion"] > 0)


@pytest.mark.parametrize("text, word", [
    ("name='x'\n[material]\nexample='tread'\n", "surface"),
    ("[surface]\npsd='missing.csv'\n[material]\nexample='tread'\n", "missing.csv"),
    ("[surface]\nexample='road'\n[material]\nexample='tread'\n[model]\neffects=['nonsense']\n", "nonsense"),
    ("[surface\nexample='road'\n", "TOML"),
])
def test_bad_case_files_give_a_clear_error(tmp_path, capsys, text, word):
    case = tmp_path / "case.toml"
    case.write_text(text)
    assert main(["friction", str(case), "-o", str(tmp_path / "o.csv")]) == 2
    err = capsys.readouterr().err
    assert word in err and "case.toml" in err
    assert not (tmp_path / "o.csv").exists()


def test_readme_scripts_run(tmp_path, monkeypatch):
    text = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) >= 2
    monkeypatch.chdir(tmp_path)
    for block in blocks:
        exec(compile(block, "README.md", "exec"), {})
    assert (tmp_path / "report.html").stat().st_size > 10_000


def test_readme_quick_start_commands_are_what_ci_runs():
    text = (ROOT / "README.md").read_text()
    ci = (ROOT / ".ci" / "run").read_text()
    assert 'pip install -e . && persson demo' in text and 'pip install -e ".[test]" && pytest' in text
    assert "pip install -e . && (cd \"$workdir\" && persson demo)" in ci
    assert 'pip install -e ".[test]" && pytest' in ci
