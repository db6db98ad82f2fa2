"""Errors and warnings raised by :mod:`persson`."""


class InputError(ValueError):
    """Bad input to the engine: the message names the argument (or file, column, row) and what was expected."""


class ConvergenceWarning(RuntimeWarning):
    """A self-consistent iteration stopped before reaching its tolerance (the result says so too)."""


class AccuracyWarning(RuntimeWarning):
    """The estimated quadrature error of a result exceeds ``GridSettings.tolerance`` (the result says so too)."""


class PhysicsWarning(UserWarning):
    """A result lies where the theory or its inputs are doubtful (rms slope far above 1, mu above 3, a PSD cut by
    an effect, a surface without roughness); the result's ``notes`` say so too."""
