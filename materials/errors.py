"""Errors raised by :mod:`materials`."""

import frictionerrors


class InputError(frictionerrors.InputError):
    """Bad input to :mod:`materials`: the message names the file, column, row or argument and what was expected."""
