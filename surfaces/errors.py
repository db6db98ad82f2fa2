"""Errors and warning categories of :mod:`surfaces`.

Every warning of the package has a category below, so that a script or a test can keep, silence or turn into
an error exactly the warnings it means. They all derive from :class:`UserWarning`, as the package's warnings
always have.
"""

from __future__ import annotations

__all__ = ["InputError", "SurfacesWarning", "DataWarning", "AccuracyWarning", "UnitWarning"]

import frictionerrors
from frictionerrors import UnitWarning  # the one category of unit slips, shared by every package


class InputError(frictionerrors.InputError):
    """Bad input to :mod:`surfaces`: the message names the file, column, row or argument and what was expected."""


class SurfacesWarning(UserWarning):
    """Base of the warnings of :mod:`surfaces`."""


class DataWarning(SurfacesWarning):
    """The measured data hold less than they seem: profiles without roughness, no valid MPD segment."""


class AccuracyWarning(SurfacesWarning, frictionerrors.AccuracyWarning):
    """A result to check before trusting it: a tail extrapolated with an assumed Hurst exponent."""
