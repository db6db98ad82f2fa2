"""Errors and warnings raised by :mod:`validation`."""


class InputError(ValueError):
    """Bad input to :mod:`validation`: the message names the file, row and column and what was expected."""


class UnitWarning(UserWarning):
    """A measurement column holds values that look like another unit (km/h, kPa, percent, kelvin)."""
