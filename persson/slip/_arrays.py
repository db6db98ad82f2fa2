"""Argument checks shared by the slip modules (slip ratios, speeds, friction values, broadcasting)."""

from __future__ import annotations

import numpy as np

from .._checks import finite_array
from ..errors import InputError


# =========================================================================================================
# validation helpers
# =========================================================================================================
def _slip_array(slip) -> np.ndarray:
    s = finite_array(slip, "slip")
    bad = (s <= 0) | (s > 1)
    if np.any(bad):
        j = int(np.argmax(bad.ravel()))
        raise InputError(f"slip: expected slip ratios in (0, 1] (1 = pure sliding), got {s.ravel()[j]:g} at index {j}")
    return s


def _speed_array(speed) -> np.ndarray:
    V = finite_array(speed, "speed")
    bad = V <= 0
    if np.any(bad):
        j = int(np.argmax(bad.ravel()))
        raise InputError(f"speed: expected speeds > 0 m/s, got {V.ravel()[j]:g} at index {j}")
    return V


def _mu_array(mu, name: str) -> np.ndarray:
    m = finite_array(mu, name)
    if np.any(m < 0):
        raise InputError(f"{name}: expected friction coefficients >= 0, got {np.min(m):g}")
    return m


def _increasing(values, name: str) -> np.ndarray:
    a = finite_array(values, name).ravel()
    if a.size < 2 or np.any(np.diff(a) <= 0):
        raise InputError(f"{name}: expected at least two strictly increasing values")
    return a


def _broadcast(names: str, *arrays):
    """np.broadcast_arrays, or InputError naming the arguments when their shapes do not broadcast."""
    try:
        return np.broadcast_arrays(*arrays)
    except ValueError:
        shapes = " and ".join(str(np.shape(a)) for a in arrays)
        raise InputError(f"{names}: shapes {shapes} do not broadcast") from None


def _sc(a):
    a = np.asarray(a, dtype=float)
    return float(a) if a.ndim == 0 else a
