"""Argument checks shared by the engine's modules: each raises an InputError naming the argument."""

from __future__ import annotations

import math

import numpy as np

from .errors import InputError

__all__ = ["number", "positive", "finite_array"]


def number(value, name: str) -> float:
    """``value`` as a finite float (booleans refused), or InputError naming ``name``."""
    if isinstance(value, bool):
        raise InputError(f"{name}: expected a number, got {value!r}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected a number, got {value!r}") from None
    if not math.isfinite(x):
        raise InputError(f"{name}: expected a finite number, got {x}")
    return x


def positive(value, name: str) -> float:
    """``value`` as a finite float > 0, or InputError naming ``name``."""
    x = number(value, name)
    if x <= 0:
        raise InputError(f"{name}: expected a value > 0, got {x:g}")
    return x


def finite_array(value, name: str) -> np.ndarray:
    """``value`` as a non-empty float array without NaN or inf (shape kept), or InputError naming ``name``."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected a number or an array of numbers, got {value!r}") from None
    if a.size == 0:
        raise InputError(f"{name}: expected at least one value")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name}: NaN or infinite value at index {int(np.argmax(~np.isfinite(a.ravel())))}")
    return a
