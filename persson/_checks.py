"""Argument checks shared by the engine's modules: each raises an InputError naming the argument."""

from __future__ import annotations

import math

from .errors import InputError

__all__ = ["number", "positive"]


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
