"""Fixtures shared by several test files: expensive results computed once per test session, and effects defined
in test modules kept to their own module."""

import os
import warnings
from pathlib import Path

import pytest

import materials

if os.environ.get("PYTEST_XDIST_WORKER"):
    # one numba thread per test process: the processes already share the cores
    os.environ.setdefault("NUMBA_NUM_THREADS", "1")

DMA_DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "dma"


@pytest.fixture(scope="session")
def eplexor_master():
    """The real Eplexor export folder and its default master curve at T_ref = 50 C, ``(DMAData, MasterCurve)``.

    Several files check this fit (its quality, that the default is the best option); it takes a second or two.
    Skips when the shared data are absent.
    """
    folder = DMA_DATA / "eplexor"
    if not folder.exists():
        pytest.skip(f"shared data not present: {folder}")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")           # temperature drift within isotherms is warned (tested elsewhere)
        d = materials.read_dma(folder)
        return d, materials.master_curve(d, T_ref=50.0)


@pytest.fixture(autouse=True)
def _effects_of_other_test_modules_unregistered(request, monkeypatch):
    """Effects defined in a test module register themselves when pytest imports the module (as a user's would);
    every other test module then sees only the built-in effects and its own, so that default candidate lists do not
    depend on which test files were collected. Effects a test defines inside its body disappear after it."""
    from persson.effects import base

    own = request.module.__name__
    kept = {name: cls for name, cls in base._REGISTRY.items()
            if cls.__module__ == own or not _defined_in_tests(cls.__module__)}
    monkeypatch.setattr(base, "_REGISTRY", kept)


def _defined_in_tests(module: str) -> bool:
    return module.startswith(("tests.", "test_", "conftest"))

