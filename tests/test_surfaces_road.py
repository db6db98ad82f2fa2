"""The real CAPTIF chip-seal road profiles (shared/data/road_profiles): load, PSD, MPD (issue 3, Must show 4).

The MPD is checked against the values of an independent ISO 13473-1 implementation, captif-slp (recorded below
with their provenance), within 0.5 %.
"""

import math
from pathlib import Path

import numpy as np
import pytest

import surfaces

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "road_profiles"
FILES = sorted(DATA.glob("captif_aylesbury_station_*.dat")) if DATA.is_dir() else []

pytestmark = [
    pytest.mark.data,
    pytest.mark.skipif(len(FILES) != 3, reason=f"road profiles not found in {DATA} (shared data absent)"),
]


@pytest.fixture(scope="module")
def road():
    return surfaces.read_profiles(FILES)


def test_raw_files_load_with_about_9_percent_dropouts():
    raw = [surfaces.read_profiles(f, trim_plates=False) for f in FILES]
    fractions = np.array([r[0].dropout_fraction for r in raw])
    assert np.all((fractions > 0.07) & (fractions < 0.12))
    assert fractions.mean() == pytest.approx(0.09, abs=0.015)
    for r in raw:
        p = r[0]
        assert p.is_uniform and p.dx == pytest.approx(0.0375e-3, rel=1e-3)
        assert p.x[-1] == pytest.approx(1.91, abs=0.02)         # about 1.91 m long
        assert np.nanmax(p.z) > 40e-3                             # the reference plates are in the raw scan
        assert r.meta["raw_dropout_fraction"] == pytest.approx(p.dropout_fraction)


def test_plates_are_trimmed(road):
    for p in road:
        assert 0.06 < p.x[0] < 0.075 and 1.86 < p.x[-1] < 1.88   # plates near 62 mm and 1870 mm
        assert np.nanmax(np.abs(p.z)) < 20e-3


def test_road_psd_and_isotropic_psd(road):
    p1 = road.psd()
    assert p1.n_profiles == 3
    assert p1.q_r == pytest.approx(math.pi / 0.0375e-3, rel=1e-3)
    assert p1.qL == pytest.approx(2 * math.pi / 1.81, rel=0.02)
    assert np.all(p1.C_values > 0) and np.all(np.isfinite(p1.spread))
    assert any("dropouts" in h for h in p1.history)
    # Parseval: the PSD carries the variance of the (detrended, windowed) profiles
    assert p1.hrms() == pytest.approx(surfaces.rq(road), rel=0.1)
    iso = p1.to_isotropic()
    assert isinstance(iso, surfaces.PSD) and np.all(iso.C_values > 0)
    assert iso.q_r == pytest.approx(p1.q_r) and not iso.extrapolated
    assert iso.hrms() == pytest.approx(surfaces.rq(road), rel=0.1)
    H = surfaces.fit_self_affine(iso, 2e3, 2e4).hurst
    assert 0.6 < H < 0.9
    assert surfaces.fit_self_affine(p1, 2e3, 2e4).hurst == pytest.approx(H, abs=0.1)
    ext = iso.with_cutoff(q1=2e4).extrapolate(1e7)
    assert ext.extrapolated and ext.q_r == pytest.approx(2e4) and ext.q_range[1] == pytest.approx(1e7)


def test_road_mpd(road):
    res = surfaces.mpd(road)
    assert res.is_valid and len(res.per_profile) == 3
    assert 2.5e-3 < res.mpd < 4.0e-3
    assert res.etd == pytest.approx(0.2e-3 + 0.8 * res.mpd)
    assert res.n_valid >= 0.5 * res.valid.size
    assert res.msd.size == res.segment_start.size == res.valid.size
    starts = res.segment_start[res.segment_profile == 0]
    np.testing.assert_allclose(starts, 0.1 * np.arange(starts.size), atol=1e-12)  # 100 mm segments


# MPD of each file by captif-slp 0.22 (an independent ISO 13473-1 implementation by the data's authors), computed
# with captif_slp.Reading.from_file(path, parallel=False, detect_plates=True, alpha=6).mpd()["mpd"] (mm), under
# numpy 1.26.4 / pandas 2.1.4. Kept as numbers: captif-slp pins pandas < 2.2 and would downgrade the numpy that
# users get if it were a test dependency.
CAPTIF_SLP_MPD_MM = {
    "captif_aylesbury_station_0.dat": 3.2777511155882353,
    "captif_aylesbury_station_1.dat": 3.03319923875,
    "captif_aylesbury_station_10.dat": 3.4201597089285714,
}


@pytest.mark.parametrize("index", [0, 1, 2])
def test_mpd_agrees_with_captif_slp(road, index):
    """Must show: MPD within 0.5 % of captif-slp (ISO 13473-1, plates detected, spike alpha 6)."""
    expected = CAPTIF_SLP_MPD_MM[FILES[index].name] * 1e-3
    ours = surfaces.mpd(road[index], spike_alpha=6.0).mpd
    assert ours == pytest.approx(expected, rel=0.005)
