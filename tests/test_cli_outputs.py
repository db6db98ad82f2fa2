"""Output rules of every command: never overwrite an input, an existing file only with --force, check the folder
before computing, keep the previous output on an interruption and put the partial result beside it."""

import json
import os

import numpy as np
import pytest

import persson
from persson.commands.cli import main
from persson.io import Outputs, check_output, partial_path

CASE = """
name = "out-test"
[surface]
example = "road"
[material]
example = "tread"
[conditions]
speeds_m_s = [0.01, 1.0]
[measurements]
file = "m.csv"
"""
MEAS = "slip,speed_m_s,T_C,pressure_Pa,mu\n1,0.01,20,3e5,0.8\n1,1.0,20,3e5,1.1\n"


@pytest.fixture()
def case(tmp_path):
    (tmp_path / "case.toml").write_text(CASE)
    (tmp_path / "m.csv").write_text(MEAS)
    return tmp_path / "case.toml"


@pytest.fixture()
def no_engine(monkeypatch):
    """Fail the test if the engine is called (checks must come before any computation)."""
    def boom(*a, **k):
        raise AssertionError("computed before checking the outputs")

    monkeypatch.setattr(persson.Model, "friction", boom)


@pytest.mark.parametrize("target", ["case.toml", "m.csv"])
def test_output_that_is_an_input_is_refused(case, capsys, no_engine, target):
    before = (case.parent / target).read_text()
    assert main(["friction", str(case), "-o", str(case.parent / target)]) == 2
    err = capsys.readouterr().err
    assert "one of the inputs" in err and target in err
    assert (case.parent / target).read_text() == before


def test_output_that_is_an_input_through_another_path_is_refused(case, capsys, no_engine, monkeypatch):
    monkeypatch.chdir(case.parent)
    (case.parent / "sub").mkdir()
    assert main(["friction", "case.toml", "-o", "sub/../m.csv"]) == 2
    assert "one of the inputs" in capsys.readouterr().err


def test_existing_output_needs_force(case, capsys):
    out = case.parent / "out.csv"
    out.write_text("previous result\n")
    assert main(["friction", str(case), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "exists" in err and "pass --force" in err
    assert out.read_text() == "previous result\n"
    assert main(["friction", str(case), "-o", str(out), "--force"]) == 0
    assert out.read_text().startswith("# case")
    assert sorted(p.name for p in case.parent.iterdir()) == ["case.toml", "m.csv", "out.csv"]  # nothing left over


def test_unwritable_output_folder_fails_before_computing_naming_the_folder(case, capsys, no_engine, tmp_path):
    blocker = tmp_path / "afile"
    blocker.write_text("x")
    assert main(["friction", str(case), "-o", str(blocker / "out.csv")]) == 2
    err = capsys.readouterr().err
    assert str(blocker) in err and ".tmp" not in err
    locked = tmp_path / "locked"
    locked.mkdir()
    os.chmod(locked, 0o555)
    try:
        if os.access(locked, os.W_OK):
            pytest.skip("running with privileges that ignore folder permissions")
        assert main(["friction", str(case), "-o", str(locked / "out.csv")]) == 2
        err = capsys.readouterr().err
        assert f"{locked} is not writable" in err
    finally:
        os.chmod(locked, 0o755)


def test_friction_and_sweep_take_shipped_case_names(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["friction", "example", "--speeds", "0.01:1:3", "-q"]) == 0
    assert (tmp_path / "example_friction.csv").is_file()
    assert main(["sweep", "example", "--speeds", "1.0", "--param", "pressure=0.2e6,0.4e6", "-q"]) == 0
    assert (tmp_path / "example_sweep.csv").is_file()
    assert main(["friction", "exampel"]) == 2
    assert "did you mean 'example'" in capsys.readouterr().err


def _sweep(case, out, *extra):
    return main(["sweep", str(case), "--param", "pressure=0.1e6:0.6e6:6", "--speeds", "0.1", "-o", str(out),
                 "--no-progress", *extra])


def test_interrupted_sweep_keeps_the_previous_file_and_writes_the_partial_one_beside_it(case, capsys, monkeypatch):
    from persson.sweeps import core

    out = case.parent / "sweep.csv"
    out.write_text("previous good result\n")
    real = core._compute
    calls = {"n": 0}

    def interrupt_at_third(task):
        calls["n"] += 1
        if calls["n"] == 3:
            raise KeyboardInterrupt
        return real(task)

    monkeypatch.setattr(core, "_compute", interrupt_at_third)
    assert _sweep(case, out, "--force") == 130
    err = capsys.readouterr().err
    assert out.read_text() == "previous good result\n"
    partial = partial_path(out)
    assert partial.name == "sweep.partial.csv" and str(partial.resolve()) in err and "interrupted" in err
    table = persson.sweeps.read_table(partial)
    np.testing.assert_array_equal(table["pressure_Pa"], [0.1e6, 0.2e6])
    assert any(c.startswith("PARTIAL") for c in table.comments)
    assert not [p for p in case.parent.iterdir() if p.name.startswith(".")]  # no staging left


def test_sweep_failing_midway_keeps_the_previous_file(case, capsys, monkeypatch):
    from persson.sweeps import core

    out = case.parent / "sweep.csv"
    out.write_text("previous good result\n")
    real = core._compute
    calls = {"n": 0}

    def fail_at_second(task):
        calls["n"] += 1
        if calls["n"] == 2:
            raise persson.InputError("something went wrong in the middle")
        return real(task)

    monkeypatch.setattr(core, "_compute", fail_at_second)
    assert _sweep(case, out, "--force") == 2
    err = capsys.readouterr().err
    assert "something went wrong" in err and "partial result" in err
    assert out.read_text() == "previous good result\n"
    assert len(persson.sweeps.read_table(partial_path(out))) == 1


def test_command_line_flags_in_the_wrong_unit_are_refused(case, capsys, no_engine):
    assert main(["friction", str(case), "--pressure", "0.3", "-o", str(case.parent / "o.csv")]) == 2
    err = capsys.readouterr().err
    assert "--pressure" in err and "looks like MPa" in err
    assert main(["sweep", str(case), "--temperature", "293.15", "-o", str(case.parent / "o.csv")]) == 2
    err = capsys.readouterr().err
    assert "--temperature" in err and "looks like kelvin" in err
    assert main(["sweep", str(case), "--param", "pressure=0.1:0.5:3", "-o", str(case.parent / "o.csv")]) == 2
    err = capsys.readouterr().err
    assert "--param 'pressure=0.1:0.5:3'" in err and "looks like MPa" in err
    assert not (case.parent / "o.csv").exists()


def test_diagnose_json_to_stdout_is_clean(capsys):
    assert main(["diagnose", "hidden_adhesion", "--json", "-", "--candidates", "adhesion"]) == 0
    captured = capsys.readouterr()
    data = json.loads(captured.out)  # stdout holds the JSON and nothing else
    assert data["candidates"][0]["effect"] == "adhesion"
    assert "diagnosis took" in captured.err


def test_demo_never_overwrites_an_earlier_run(tmp_path, monkeypatch, capsys):
    """The default folder holds an earlier run: the demo writes to the next free name and says so."""
    import validation

    (tmp_path / "persson-demo").mkdir()
    (tmp_path / "persson-demo" / "report.html").write_text("earlier demo")
    monkeypatch.chdir(tmp_path)

    def stop(*a, **k):
        raise validation.InputError("stopped here by the test")

    monkeypatch.setattr(validation, "load_case", stop)
    assert main(["demo"]) == 2
    out = capsys.readouterr().out
    assert "writing to ./persson-demo-2" in out
    assert (tmp_path / "persson-demo" / "report.html").read_text() == "earlier demo"
    assert not (tmp_path / "persson-demo-2").exists()  # nothing was finished: no empty folder left behind


# ------------------------------------------------------------------------------------------------- Outputs
def test_outputs_are_moved_into_place_together(tmp_path):
    with Outputs("t") as outs:
        a = outs.file(tmp_path / "a.txt")
        b = outs.file(tmp_path / "sub" / "b.txt")
        a.write_text("A")
        b.write_text("B")
        assert not (tmp_path / "a.txt").exists()  # staged until the block ends
    assert (tmp_path / "a.txt").read_text() == "A" and (tmp_path / "sub" / "b.txt").read_text() == "B"
    assert outs.written == [tmp_path / "a.txt", tmp_path / "sub" / "b.txt"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "sub"]


def test_outputs_on_an_error_keep_the_old_files_and_leave_partial_ones(tmp_path, capsys):
    (tmp_path / "a.txt").write_text("old")
    with pytest.raises(RuntimeError):
        with Outputs("t", force=True) as outs:
            outs.file(tmp_path / "a.txt").write_text("new, half done")
            raise RuntimeError("stop")
    assert (tmp_path / "a.txt").read_text() == "old"
    assert (tmp_path / "a.partial.txt").read_text() == "new, half done"
    assert "a.partial.txt" in capsys.readouterr().err


def test_outputs_refuse_inputs_existing_files_and_folders(tmp_path):
    (tmp_path / "in.csv").write_text("x")
    with pytest.raises(persson.InputError, match="one of the inputs"):
        check_output(tmp_path / "in.csv", inputs=[tmp_path / "in.csv"], force=True)
    with pytest.raises(persson.InputError, match="exists"):
        check_output(tmp_path / "in.csv")
    with pytest.raises(persson.InputError, match="is a folder"):
        check_output(tmp_path)
    with pytest.raises(persson.InputError, match="given twice"):
        with Outputs("t") as outs:
            outs.file(tmp_path / "o.csv")
            outs.file(tmp_path / "o.csv")
    assert not (tmp_path / "o.csv").exists()


def test_an_output_folder_with_earlier_results_needs_force(tmp_path):
    (tmp_path / "x_mu.png").write_text("old plot")
    with pytest.raises(persson.InputError, match="x_mu.png exists"):
        Outputs("t").folder(tmp_path, patterns=("x_*.png",))
    with Outputs("t", force=True) as outs:
        staged = outs.folder(tmp_path, patterns=("x_*.png",))
        (staged / "x_mu.png").write_text("new plot")
    assert (tmp_path / "x_mu.png").read_text() == "new plot"
