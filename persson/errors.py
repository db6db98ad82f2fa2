"""Errors and warnings raised by :mod:`persson`."""


class InputError(ValueError):
    """Bad input to the engine: the message names the argument (or file, column, row) and what was expected."""


class ConvergenceWarning(RuntimeWarning):
    """A self-consistent iteration stopped before reaching its tolerance (the result says so too)."""
