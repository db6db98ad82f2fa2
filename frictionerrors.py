"""The error and warning classes shared by every package of the project.

Each package raises its own ``InputError`` (``surfaces.InputError``, ``materials.InputError``,
``persson.InputError``, ``validation.InputError``), and all of them subclass :class:`InputError` here, itself a
``ValueError``: a script catches bad input from any package with one ``except frictionerrors.InputError``. The
warning categories are defined once, here, so that ``warnings.simplefilter("error", UnitWarning)`` means the same
thing whichever package warns.
"""

from __future__ import annotations

__all__ = ["InputError", "UnitWarning", "PhysicsWarning", "ConvergenceWarning", "AccuracyWarning"]


class InputError(ValueError):
    """Bad input: the message names the file, column, row, key or argument and what was expected."""


class UnitWarning(UserWarning):
    """A value looks like another unit (MPa or kPa typed as Pa, kelvin typed as degrees Celsius, km/h as m/s)."""


class PhysicsWarning(UserWarning):
    """A result lies where the theory or its inputs are doubtful (rms slope far above 1, mu above 3, a PSD cut by
    an effect, a surface without roughness); the result's ``notes`` say so too."""


class ConvergenceWarning(RuntimeWarning):
    """A self-consistent iteration stopped before reaching its tolerance (the result says so too)."""


class AccuracyWarning(RuntimeWarning):
    """The estimated quadrature error of a result exceeds ``GridSettings.tolerance`` (the result says so too)."""
