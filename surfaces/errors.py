"""Errors raised by :mod:`surfaces`."""

import frictionerrors


class InputError(frictionerrors.InputError):
    """Bad input to :mod:`surfaces`: the message names the file, column, row or argument and what was expected."""
