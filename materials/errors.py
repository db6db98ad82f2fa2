"""Errors raised by :mod:`materials`."""


class InputError(ValueError):
    """Bad input to :mod:`materials`: the message names the file, column, row or argument and what was expected."""
