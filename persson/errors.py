"""Errors and warnings raised by :mod:`persson` (the warning categories are shared by every package)."""

import frictionerrors
from frictionerrors import AccuracyWarning, ConvergenceWarning, PhysicsWarning, UnitWarning

__all__ = ["InputError", "ConvergenceWarning", "AccuracyWarning", "PhysicsWarning", "UnitWarning"]


class InputError(frictionerrors.InputError):
    """Bad input to the engine: the message names the argument (or file, column, row) and what was expected."""
