"""Likely unit slips in the API: pressures in MPa typed as Pa, temperatures in kelvin, below absolute zero."""

import warnings

import pytest

import materials
import persson
import surfaces
from persson._checks import UnitWarning, plausible_pressure, plausible_temperature


@pytest.fixture(scope="module")
def model():
    return persson.Model(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=10e-6),
                         materials.ConstantModulus(5e6, 2e6))


@pytest.mark.parametrize("kwargs, words", [
    ({"pressure": 0.3}, ["pressure", "0.3 Pa", "looks like MPa", "300000 Pa"]),
    ({"pressure": 300.0}, ["pressure", "looks like kPa or bar"]),
    ({"pressure": 3e9}, ["pressure", "above any contact pressure"]),
    ({"temperature": 293.15}, ["temperature", "looks like kelvin", "20 C"]),
])
def test_friction_warns_about_a_likely_unit_slip(model, kwargs, words):
    with pytest.warns(UnitWarning) as rec:
        model.friction(1.0, **kwargs)
    text = str(rec[0].message)
    for w in words:
        assert w in text
    assert rec[0].filename == __file__  # points at the caller's line


def test_friction_refuses_temperatures_below_absolute_zero(model):
    with pytest.raises(persson.InputError, match="temperature: -300 C is below absolute zero"):
        model.friction(1.0, temperature=-300.0)
    with pytest.raises(persson.InputError, match="below absolute zero"):
        model.friction([1.0, 2.0], temperature=[20.0, -280.0])


def test_ordinary_conditions_raise_no_warning(model):
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnitWarning)
        model.friction([0.01, 1.0], temperature=[-30.0, 120.0], pressure=[2e4, 5e6])


def test_strict_checks_are_errors_naming_the_argument():
    with pytest.raises(persson.InputError, match=r"--pressure: 0.5 Pa .* looks like MPa"):
        plausible_pressure(0.5, "--pressure", strict=True)
    with pytest.raises(persson.InputError, match=r"T: 300 C looks like kelvin"):
        plausible_temperature(300.0, "T", strict=True)
    assert plausible_pressure(3e5, "p", strict=True) == 3e5
