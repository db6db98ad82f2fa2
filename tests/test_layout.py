"""The package layout: old module paths keep working after persson/ was organised into wings."""

import importlib
import pickle
import subprocess
import sys

import pytest

import persson
from persson._moved import MOVED


@pytest.mark.parametrize("old", sorted(MOVED))
def test_an_old_module_path_is_the_module_that_holds_the_code_now(old):
    assert importlib.import_module(old) is importlib.import_module(MOVED[old])


def test_names_of_the_old_modules_import_from_their_old_paths():
    from persson.effects.patch import PatchHeating, patch_friction
    from persson.model import Model
    from persson.tire import fit_magic_formula, piarc

    assert Model is persson.Model
    assert PatchHeating is persson.effects.PatchHeating
    assert patch_friction is persson.slip.patch_friction
    assert fit_magic_formula is persson.slip.fit_magic_formula and piarc is persson.slip.piarc


def test_a_pickle_that_names_an_old_module_path_loads():
    # protocol-0 pickle text written by hand with the module path a cached case of the flat layout carries
    blob = b"cpersson.grid\nGridSettings\np0\n."
    assert pickle.loads(blob) is persson.GridSettings
    blob = b"cpersson.effects.patch\nPatchHeating\np0\n."
    assert pickle.loads(blob) is persson.effects.PatchHeating


def test_old_paths_import_in_a_fresh_interpreter():
    # the alias finder must be in place whichever old path a script imports first
    code = "import persson.tire, persson.case_schema; from persson.solver import run_flash; print('ok')"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "ok"


@pytest.mark.parametrize("old", sorted(MOVED))
def test_an_alias_leaves_the_module_its_own_spec(old):
    # a module whose __spec__ named the alias would see __package__ != __spec__.parent on every relative import
    module = importlib.import_module(old)
    assert module.__spec__.name == MOVED[old]
    assert module.__spec__.parent == module.__package__
