"""The tyre's footprint (step 1), tread patterns, and bad input to persson.tread (issue 27, items 1, 2 and 8)."""

import math
import warnings

import numpy as np
import pytest

import materials
import surfaces
from persson import tread
from persson.errors import InputError

TREAD = materials.example_tread()


def tire(**kw):
    args = dict(diameter=0.63, width=0.205, load=4000.0, inflation_pressure=2.2e5, tread_depth=8e-3)
    args.update(kw)
    return tread.Tire(**args)


@pytest.fixture(scope="module")
def rough():
    sa = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.15e-3, qL=2 * math.pi / 0.1)
    return surfaces.synthesize_profiles(sa, n_profiles=1, n=4000, length=0.4, seed=5)


def test_footprint_of_a_passenger_tyre_at_2_2_bar_and_4_kN():
    """MF-Swift footprint relations (Pacejka 2012, App. 3) with the reference tyre's coefficients: 205/60 R15,
    C_z = 209651 N/m at 2.2 bar, q = q_Fz2/q_Fz1 (the Fz = C_z rho (1 + q rho/R0) law)."""
    t = tire(diameter=0.627, width=0.205)
    fp = t.footprint
    R0 = 0.3135
    q = 15.4 / (209651.0 * R0 / 4000.0)
    rho = (-1 + math.sqrt(1 + 4 * q * 4000.0 / (209651.0 * R0))) * R0 / (2 * q)
    x = rho / R0
    assert fp.deflection == pytest.approx(rho, rel=1e-12)
    assert fp.length == pytest.approx(2 * R0 * (0.733 * x + 0.671 * math.sqrt(x)), rel=1e-12)
    assert fp.width == pytest.approx(2 * 0.205 * (-1.1878 * x + 1.059 * x ** (1 / 3)), rel=1e-12)
    assert fp.length == pytest.approx(0.1276, abs=5e-4) and fp.width == pytest.approx(0.1397, abs=5e-4)
    # a membrane would carry the load at the inflation pressure: the model's mean pressure is 2 % above it
    assert fp.mean_pressure == pytest.approx(2.2e5, rel=0.05)
    assert fp.area == pytest.approx(fp.membrane_area, rel=0.05)


def test_footprint_grows_with_load_and_shrinks_with_pressure():
    lengths = [tire(load=W).footprint.length for W in (2000.0, 4000.0, 6000.0)]
    assert lengths[0] < lengths[1] < lengths[2]
    hard, soft = tire(inflation_pressure=3.0e5).footprint, tire(inflation_pressure=1.6e5).footprint
    assert hard.area < soft.area
    assert soft.carcass_stiffness == pytest.approx(hard.carcass_stiffness)     # the carcass share does not change


def test_grooves_and_their_land():
    g = tread.Grooves(width=8e-3, pitch=30e-3)
    x = np.arange(30000) * 1e-6
    assert g.land(x, 0.0).mean() == pytest.approx(1 - 8 / 30, abs=1e-3)
    ribs = tread.Grooves(width=10e-3, pitch=40e-3, angle_deg=90.0)
    y = np.arange(16000) * 1e-5 - 0.08                                       # four whole pitches
    assert ribs.land(0.0, y).mean() == pytest.approx(0.75, abs=0.01) and ribs.pad_length() == math.inf
    assert not np.any(np.diff(ribs.land(x, 0.01)))                            # ribs do not vary along x


def test_footprint_image_read_with_otsu(tmp_path):
    from skimage import io

    img = np.full((120, 300), 230, dtype=np.uint8)                             # paper
    for start in range(0, 300, 30):                                          # ink blocks, 8-pixel grooves
        img[:, start:start + 22] = 30
    img = img + np.random.default_rng(0).integers(0, 20, img.shape).astype(np.uint8)
    path = tmp_path / "print.png"
    io.imsave(path, img, check_contrast=False)
    pattern = tread.read_footprint(path, pixel_size=1e-3)
    assert pattern.void_fraction == pytest.approx(8 / 30, abs=0.01)
    assert pattern.pad_length() == pytest.approx(22e-3, abs=1e-3)
    t = tire(grooves=pattern)
    assert t.void_fraction == pytest.approx(8 / 30, abs=0.01)


@pytest.mark.parametrize("kwargs, words", [
    (dict(grooves=dict(width=30e-3, pitch=30e-3)), "leaves no rubber"),
    (dict(load=40000.0), "beyond what the carcass can carry"),
    (dict(load=14000.0, inflation_pressure=1.0e5), "bottom out"),
    (dict(tread_depth=8.0), "expected metres"),
    (dict(inflation_pressure=2.2), "gauge pressure in Pa"),
    (dict(grooves="ribs"), "tire.grooves"),
])
def test_impossible_tyres_are_refused(kwargs, words):
    kw = dict(kwargs)
    with pytest.raises(InputError, match=words):
        if "grooves" in kw and isinstance(kw["grooves"], dict):
            kw["grooves"] = tread.Grooves(**kw["grooves"])
        tire(**kw)


def test_bad_runs_are_refused(rough):
    t = tire()
    short = surfaces.synthesize_profiles(surfaces.example_road(), n_profiles=1, n=2000, length=0.2, seed=1)
    with pytest.raises(InputError, match="too short for the .* footprint"):
        tread.simulate(t, short, TREAD, speed=16.7, slip=1.0, mu_loc=0.5)
    with pytest.raises(InputError, match="would skip road elements"):
        tread.simulate(t, rough, TREAD, speed=16.7, slip=1.0, mu_loc=0.5, dt=1e-4)
    with pytest.raises(InputError, match="slip"):
        tread.simulate(t, rough, TREAD, speed=16.7, slip=0.0, mu_loc=0.5)
    with pytest.raises(InputError, match="unknown option"):
        tread.simulate(t, rough, TREAD, speed=16.7, slip=1.0, mu_loc=0.5, elementsize=1e-3)
    with pytest.raises(InputError, match="finer than the profiles"):
        tread.simulate(t, rough, TREAD, speed=16.7, slip=1.0, mu_loc=0.5, road_element=5e-5)
    with pytest.raises(InputError, match="mu_loc"):
        tread.simulate(t, rough, TREAD, speed=16.7, slip=1.0, mu_loc=-0.1)


def test_water_deeper_than_the_tread_can_drain_is_allowed_and_noted(rough):
    t = tire(grooves=tread.Grooves(width=8e-3, pitch=30e-3))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = tread.simulate(t, rough, TREAD, speed=16.7, slip=1.0, mu_loc=0.5, element_size=5e-4,
                           water=tread.Water(thickness=5e-3))
    assert np.isfinite(r.mu) and r.lift > 0
    assert any("deeper than the road texture and the tread grooves can hold" in n for n in r.notes)
    with pytest.raises(InputError, match="water.thickness"):
        tread.Water(thickness=5.0)
