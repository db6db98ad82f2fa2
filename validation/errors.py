"""Errors and warnings raised by :mod:`validation` (``UnitWarning`` is the one category every package uses)."""

import frictionerrors
from frictionerrors import UnitWarning

__all__ = ["InputError", "UnitWarning", "ChannelWarning", "IdentificationWarning"]


class InputError(frictionerrors.InputError):
    """Bad input to :mod:`validation`: the message names the file, row and column and what was expected."""


class ChannelWarning(UserWarning):
    """Raw channels of a friction rig failed a check (a frozen channel, a force balance that does not close): the
    message names the tire, the channels and the rows, and the affected samples are left out of the reduction."""


class IdentificationWarning(UserWarning):
    """No Magic Formula passes through the (slip, mu) points of some road positions, or too few samples fell
    there: those positions carry no peak or locked mu, and the result says which."""
