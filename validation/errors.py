"""Errors and warnings raised by :mod:`validation` (``UnitWarning`` is the one category every package uses)."""

import frictionerrors
from frictionerrors import UnitWarning

__all__ = ["InputError", "UnitWarning"]


class InputError(frictionerrors.InputError):
    """Bad input to :mod:`validation`: the message names the file, row and column and what was expected."""
