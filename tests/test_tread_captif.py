"""The tread-element tool on the real CAPTIF chip-seal scans (shared/data/road_profiles; skipped when absent).

The scans are 0.0375 mm laser profiles of a coarse chip seal (MPD about 3 mm); the tool uses them at the paper's
resolution (0.1 mm road elements, averaged). A chip seal drains a 1 mm water film entirely (no hydrodynamic lift),
and its sharp macrotexture gives it more macro-hysteresis than a fine road with the same local friction. About 1 %
of its contacts sit on flanks past the self-locking limit of Eq. 2 (chip faces, tan alpha > 1/mu_loc), and they
carry a third of the locked-wheel mu: a part set by the cap jam_min, which the result books and flags.
"""

import math
from pathlib import Path

import numpy as np
import pytest

import materials
import surfaces
from persson import tread
from persson.errors import AccuracyWarning

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "road_profiles"
FILES = sorted(DATA.glob("captif_aylesbury_station_*.dat")) if DATA.is_dir() else []

pytestmark = [
    pytest.mark.data,
    pytest.mark.skipif(len(FILES) != 3, reason=f"road profiles not found in {DATA} (shared data absent)"),
]

TREAD = materials.example_tread()


@pytest.fixture(scope="module")
def captif():
    return tread.as_road(surfaces.read_profiles(FILES), 1e-4).crop(0.5)


def test_captif_scans_become_three_rows_of_road_elements(captif):
    assert captif.n_rows == 3 and captif.dx == pytest.approx(1e-4)
    assert captif.length == pytest.approx(0.5, abs=1e-3)
    assert 2.0e-3 < captif.texture_depth() < 4.0e-3                     # ETD of a chip seal
    assert captif.rms_slope > 1.0                                         # sharp chips at 0.1 mm
    assert any("dropouts filled" in n for n in captif.notes)


@pytest.mark.filterwarnings("ignore:.*flanks too steep:persson.errors.PhysicsWarning")
@pytest.mark.filterwarnings("ignore:.*self-locking limit:persson.errors.AccuracyWarning")
def test_chip_seal_ranks_above_a_fine_road_and_drains_the_water(captif):
    t = tread.Tire(diameter=0.63, width=0.205, load=4000.0, inflation_pressure=2.2e5, tread_depth=8e-3,
                   grooves=tread.Grooves(width=8e-3, pitch=30e-3))
    sa = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.05e-3, qL=2 * math.pi / 0.1)
    fine = tread.as_road(surfaces.synthesize_profiles(sa, n_profiles=1, n=5000, length=0.5, seed=4))
    rank = tread.rank_surfaces({"captif": captif, "fine": fine}, t, TREAD, speed=16.7, slips=[0.1, 0.2, 1.0],
                               mu_loc=0.5, element_size=5e-4)
    assert list(rank.locked_rank) == [1, 2] and list(rank.peak_rank) == [1, 2]
    assert np.all(rank.peak_mu >= rank.locked_mu - 3 * rank.locked_std)
    wet = tread.wet_state(tread.Water(thickness=1e-3), t, captif, 25.0)
    assert wet.lift == 0.0                                                # the chips hold the whole film
    r = tread.simulate(t, captif, TREAD, speed=16.7, slip=1.0, mu_loc=0.5, element_size=5e-4)
    assert r.load_residual < 1e-9 and 0.05 < r.contact_fraction < 0.9


@pytest.mark.filterwarnings("ignore:.*flanks too steep:persson.errors.PhysicsWarning")
def test_chip_seal_friction_resting_on_self_locking_flanks_is_flagged(captif):
    t = tread.Tire(diameter=0.63, width=0.205, load=4000.0, inflation_pressure=2.2e5, tread_depth=8e-3)
    runs = []
    for jam_min in (0.1, 0.2):
        with pytest.warns(AccuracyWarning, match="self-locking limit"):
            runs.append(tread.simulate(t, captif, TREAD, speed=16.7, slip=1.0, mu_loc=0.5, element_size=5e-4,
                                       jam_min=jam_min))
    tight, loose = runs
    assert 0.2 * tight.mu < tight.jammed_share < tight.mu
    assert any("self-locking" in n for n in tight.notes)
    # doubling the cap roughly halves the capped part: mu moves with the cap, not with the road
    assert loose.mu < tight.mu - 0.4 * tight.jammed_share
    assert loose.jammed_share < tight.jammed_share
