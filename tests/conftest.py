"""Fixtures shared by several test files: expensive results computed once per test session."""

import warnings
from pathlib import Path

import pytest

import materials

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
