"""One error hierarchy: every package's InputError is a frictionerrors.InputError (and a ValueError); one UnitWarning."""

import warnings

import pytest

import frictionerrors
import materials
import persson
import surfaces
import validation
from persson._checks import UnitWarning, plausible_pressure


@pytest.mark.parametrize("package", [persson, surfaces, materials, validation], ids=lambda m: m.__name__)
def test_every_package_input_error_is_caught_by_the_common_base(package):
    assert issubclass(package.InputError, frictionerrors.InputError)
    assert issubclass(package.InputError, ValueError)


def test_bad_input_from_any_package_is_caught_by_one_except_clause():
    caught = []
    for bad in (lambda: surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e2, hrms=1e-5),
                lambda: materials.ConstantModulus(E_storage=-1.0, E_loss=1.0),
                lambda: persson.GridSettings(q_per_decade=0)):
        try:
            bad()
        except frictionerrors.InputError as exc:
            caught.append(type(exc).__module__.split(".")[0])
    assert caught == ["surfaces", "materials", "persson"]


def test_one_unit_warning_class_for_every_package():
    assert UnitWarning is validation.UnitWarning is persson.errors.UnitWarning is frictionerrors.UnitWarning
    with warnings.catch_warnings():
        warnings.simplefilter("error", frictionerrors.UnitWarning)
        with pytest.raises(frictionerrors.UnitWarning, match="pressure"):
            plausible_pressure(0.3, "pressure")  # MPa typed as Pa


@pytest.mark.parametrize("package", [surfaces, materials], ids=lambda m: m.__name__)
def test_package_warning_categories_are_the_shared_ones(package):
    # a filter on the shared category catches the package's own warning of that kind
    for name in ("AccuracyWarning", "ConvergenceWarning", "PhysicsWarning"):
        cls = getattr(package, name, None)
        if cls is not None:
            assert issubclass(cls, getattr(frictionerrors, name)), f"{package.__name__}.{name}"
