"""Errors raised by :mod:`surfaces`."""


class InputError(ValueError):
    """Bad input to :mod:`surfaces`: the message names the file, column, row or argument and what was expected."""
