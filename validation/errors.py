"""Errors raised by :mod:`validation`."""


class InputError(ValueError):
    """Bad input to :mod:`validation`: the message names the file, row and column and what was expected."""
