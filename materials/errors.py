"""Errors and warning categories of :mod:`materials`.

Every warning of the package has a category below, so that a script or a test can keep, silence or turn into
an error exactly the warnings it means (``warnings.filterwarnings(..., category=AccuracyWarning)``). They all
derive from :class:`UserWarning`, as the package's warnings always have.
"""

from __future__ import annotations

import warnings
from contextlib import contextmanager

__all__ = ["InputError", "MaterialsWarning", "DataWarning", "AccuracyWarning", "ConvergenceWarning",
           "PhysicsWarning", "ignoring"]

import frictionerrors


class InputError(frictionerrors.InputError):
    """Bad input to :mod:`materials`: the message names the file, column, row or argument and what was expected."""


class MaterialsWarning(UserWarning):
    """Base of the warnings of :mod:`materials`."""


class DataWarning(MaterialsWarning):
    """The data were changed on reading, or look suspect: rows dropped, merged or averaged, temperature drift
    within an isotherm, strain amplitudes left out of a master curve."""


class AccuracyWarning(MaterialsWarning, frictionerrors.AccuracyWarning):
    """A result to check before trusting it: extrapolated beyond the data, a fit that describes its data poorly,
    isotherms that do not superpose, an undetermined uncertainty."""


class ConvergenceWarning(MaterialsWarning, frictionerrors.ConvergenceWarning):
    """An iterative fit stopped before it converged (the result says so too)."""


class PhysicsWarning(MaterialsWarning, frictionerrors.PhysicsWarning):
    """The data contradict the physics: a shift factor that rises with temperature, a modulus that violates
    the Kramers-Kronig relations."""


@contextmanager
def ignoring(category: type[Warning], *messages: str):
    """Silence the warnings of ``category`` whose text matches one of ``messages``, and no others.

    Parameters
    ----------
    category : type
        Warning class (its subclasses included).
    *messages : str
        Regular expressions matched against the start of the warning text (``".*text"`` finds text anywhere).
    """
    with warnings.catch_warnings():
        for message in messages:
            warnings.filterwarnings("ignore", message=message, category=category)
        yield
