"""A friction coefficient below 1e-3 on a road: a unit slip, or a compound that is nearly loss-free where the road
excites it (glassy, or on the rubbery plateau of an unfilled rubber)?

Persson's hysteresis friction in small contact tends to 4 sqrt(2)/pi^(3/2) gamma sin(delta) xi(q1) for a modulus of
constant phase delta (xi: the rms slope), so a tan delta of 0.002 gives well below 1e-3 on any road and is no unit
slip, while the same friction from a lossy compound means the slopes (the profile heights) are far too small.
"""

import math
import warnings

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.errors import PhysicsWarning, UnitWarning

# wavelengths 2 cm .. 0.1 mm: a road-scale texture
ROAD = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 0.02, q1=2 * math.pi / 1e-4, hrms=0.2e-3)


def friction(surface, material, **kwargs):
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        r = persson.Model(surface, material).friction(1.0, **kwargs)
    return r, rec


def small_contact_limit(tan_delta, xi, gamma=0.5):
    return 4 * math.sqrt(2) / math.pi ** 1.5 * gamma * math.sin(math.atan(tan_delta)) * xi


@pytest.mark.parametrize("E_storage, state", [(1e9, "glassy"), (3e6, "on its rubbery plateau")])
def test_a_nearly_loss_free_compound_is_physics_not_a_unit_slip(E_storage, state):
    tan_delta = 0.002
    r, rec = friction(ROAD, materials.ConstantModulus(E_storage=E_storage, E_loss=tan_delta * E_storage))
    xi = ROAD.rms_slope()
    assert float(r.mu) < 1e-3
    if state == "glassy":      # small contact: the closed form holds
        assert float(r.mu) == pytest.approx(small_contact_limit(tan_delta, xi), rel=0.05)
    assert not [w for w in rec if issubclass(w.category, UnitWarning)]
    [w] = [w for w in rec if issubclass(w.category, PhysicsWarning)]
    text = str(w.message)
    for words in ("nearly loss-free", state, "tan delta at most 0.002", f"rms slope ({xi:.3g})", "not a unit slip"):
        assert words in text
    assert [n.kind for n in r.notes if "loss-free" in n] == ["physics"]


def test_the_same_friction_from_a_lossy_compound_on_tiny_slopes_is_a_unit_slip():
    # heights a hundred times too small (3 um rms on a road): mu < 1e-3 with tan delta 0.5
    tiny = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 0.02, q1=2 * math.pi / 1e-4, hrms=3e-6)
    r, rec = friction(tiny, materials.ConstantModulus(E_storage=10e6, E_loss=5e6))
    assert float(r.mu) < 1e-3
    units = [str(w.message) for w in rec if issubclass(w.category, UnitWarning)]
    assert any("friction coefficient" in m and "check the units" in m for m in units)
    assert not any("loss-free" in str(w.message) for w in rec)


def test_a_low_friction_off_road_scales_says_nothing():
    # a fine sandpaper (wavelengths 0.5 mm .. 5 um) is not a road: no road-scale expectations apply
    paper = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-4, q1=2 * math.pi / 5e-6, hrms=5e-6)
    r, rec = friction(paper, materials.ConstantModulus(E_storage=1e9, E_loss=2e6))
    assert float(r.mu) < 1e-3
    assert not [w for w in rec if issubclass(w.category, (UnitWarning, PhysicsWarning))]


def test_the_glassy_corner_of_a_filled_tread_on_a_road():
    """The shipped tire tread at -30 C, 30 m/s on the shipped road: the Prony series of the compound has almost
    no loss so far above its glass transition in frequency (tan delta 0.015 at most), the engine's friction is
    1.5e-4, and the message says why instead of suspecting units."""
    model = persson.Model(surfaces.example_road(), materials.example_tire_tread(),
                          grid=persson.GridSettings(q_per_decade=8, n_phi=12, omega_per_decade=16))
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        r = model.friction(np.array([30.0]), temperature=-30.0)
    assert float(r.mu[0]) < 1e-3
    assert not [w for w in rec if issubclass(w.category, UnitWarning)]
    assert any("glassy" in str(w.message) and "Prony" in str(w.message) for w in rec
               if issubclass(w.category, PhysicsWarning))
