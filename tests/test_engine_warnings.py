"""Results a user cannot trust say so: physics limits and numerical accuracy are warned and noted."""

import math
import warnings

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.effects import Microtexture

TREAD = materials.example_tread()


def test_rms_slope_far_above_one_is_warned():
    """A road PSD extrapolated far past its reliable range: rms slope >> 1, outside small-slope theory."""
    s = surfaces.SelfAffine(hurst=0.6, q0=1e3, q1=1e8, hrms=1e-3)
    assert s.rms_slope() > 3
    with pytest.warns(persson.PhysicsWarning, match="rms slope"):
        r = persson.Model(s, TREAD).friction(1.0, pressure=0.3e6)
    assert any("rms slope" in n for n in r.notes)


def test_friction_above_three_is_warned():
    s = surfaces.SelfAffine(hurst=0.6, q0=1e3, q1=1e8, hrms=1e-3)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        r = persson.Model(s, TREAD).friction(1.0, pressure=0.3e6)
    assert r.mu > 3  # the slope ~ 30 surface gives an absurd friction coefficient, which must be flagged
    assert any("friction coefficient" in str(x.message) for x in w)
    assert any("friction coefficient" in n for n in r.notes)


def test_an_effect_that_cuts_the_psd_says_so():
    s = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3)
    with pytest.warns(persson.PhysicsWarning, match="cut the PSD"):
        r = persson.Model(s, TREAD, effects=[Microtexture(q1=1e4)]).friction(1.0, pressure=0.3e6)
    assert any("microtexture" in n and "cut the PSD" in n for n in r.notes)


def test_a_surface_without_roughness_says_so():
    class Flat:
        q_range = (1e3, 1e6)

        def C(self, q):
            return np.zeros_like(np.asarray(q, dtype=float))

    with pytest.warns(persson.PhysicsWarning, match="no roughness"):
        r = persson.Model(Flat(), TREAD).friction(1.0, pressure=0.3e6)
    assert r.mu == 0.0 and r.contact_area == 1.0
    assert any("no roughness" in n for n in r.notes)


def test_ordinary_results_carry_no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        road = surfaces.example_road().with_cutoff(q1=1e6)  # rms slope 2.5
        r = persson.Model(road, TREAD).friction(np.geomspace(1e-6, 10, 8), pressure=0.3e6)
    assert r.notes == () or all("extrapolated" in n for n in r.notes)


def test_a_length_scale_band_cuts_the_psd_without_a_warning():
    """A band sweep restricts the PSD on purpose: that is its question, not a doubtful result."""
    from persson import sweeps

    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=0.2e-3)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        sweeps.bands(persson.Model(s, TREAD), "decades", n=3, speed=[0.01, 1.0])
    assert not [x for x in w if "cut the PSD" in str(x.message)]
