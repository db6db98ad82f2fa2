"""Argument checks shared by the engine's modules: each raises an InputError naming the argument."""

from __future__ import annotations

import math
import warnings

import numpy as np

from .errors import InputError, UnitWarning

__all__ = ["number", "positive", "finite_array", "plausible_pressure", "plausible_temperature", "UnitWarning",
           "PRESSURE_RANGE_PA", "KELVIN_LOOKING_C"]


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


# ---------------------------------------------------------------------------------------------------------
# Plausibility of operating conditions: the unit slips users actually make (MPa typed as Pa, kelvin typed as
# degrees Celsius). Impossible values are errors everywhere; implausible ones are errors where a person typed
# them (case files, command-line flags: ``strict=True``) and UnitWarnings in the API, where research scripts may
# probe extreme conditions on purpose.

#: Nominal pressures of rubber friction: a tread on a road carries 0.1-1 MPa, lab testers 10 kPa-10 MPa.
PRESSURE_RANGE_PA = (1.0e3, 1.0e8)
#: Background temperatures that look like kelvin (20 C = 293.15 K); no tread compound is tested this hot.
KELVIN_LOOKING_C = (200.0, 450.0)
ABSOLUTE_ZERO_C = -273.15


def plausible_pressure(value, name: str, *, strict: bool = False, stacklevel: int = 3) -> np.ndarray:
    """Check nominal pressure(s) in Pa: > 0 always; outside 1 kPa-100 MPa an error (``strict``) or a UnitWarning.

    Parameters
    ----------
    value : float or array_like
        Pressure(s), Pa.
    name : str
        The argument, flag or case key, named in the message.
    strict : bool
        Raise InputError instead of warning on an implausible value.

    Returns
    -------
    ndarray
        The pressures as floats (shape kept).
    """
    p = finite_array(value, name)
    if np.any(p <= 0):
        bad = float(p.ravel()[np.argmax(p.ravel() <= 0)])
        raise InputError(f"{name}: expected a nominal pressure > 0 Pa, got {bad:g}")
    lo, hi = PRESSURE_RANGE_PA
    out = (p < lo) | (p > hi)
    if np.any(out):
        bad = float(p.ravel()[np.argmax(out.ravel())])
        _complain(f"{name}: {bad:g} Pa is {_pressure_slip(bad)}", strict, stacklevel)
    return p


def plausible_temperature(value, name: str, *, strict: bool = False, stacklevel: int = 3) -> np.ndarray:
    """Check background temperature(s) in deg C: below -273.15 an error; 200-450 (kelvin-looking) an error
    (``strict``) or a UnitWarning.

    Parameters
    ----------
    value : float or array_like
        Temperature(s), deg C.
    name : str
        The argument, flag or case key, named in the message.
    strict : bool
        Raise InputError instead of warning on a kelvin-looking value.

    Returns
    -------
    ndarray
        The temperatures as floats (shape kept).
    """
    T = finite_array(value, name)
    flat = T.ravel()
    cold = flat < ABSOLUTE_ZERO_C
    if np.any(cold):
        bad = float(flat[np.argmax(cold)])
        raise InputError(f"{name}: {bad:g} C is below absolute zero (-273.15 C); give degrees Celsius")
    lo, hi = KELVIN_LOOKING_C
    kelvin = (flat >= lo) & (flat <= hi)
    if np.any(kelvin):
        bad = float(flat[np.argmax(kelvin)])
        _complain(f"{name}: {bad:g} C looks like kelvin ({bad:g} K = {bad + ABSOLUTE_ZERO_C:.4g} C); give degrees "
                  "Celsius", strict, stacklevel)
    return T


def _pressure_slip(p: float) -> str:
    if p < 1.0:
        return (f"far below any contact pressure of rubber friction (1 kPa-100 MPa); it looks like MPa: "
                f"{p:g} MPa = {p * 1e6:g} Pa")
    if p < PRESSURE_RANGE_PA[0]:
        return (f"below any contact pressure of rubber friction (1 kPa-100 MPa); it looks like kPa or bar: "
                f"{p:g} kPa = {p * 1e3:g} Pa, {p:g} bar = {p * 1e5:g} Pa")
    return ("above any contact pressure of rubber friction (1 kPa-100 MPa); it looks like a force or another "
            "unit: give the nominal pressure in Pa (0.3 MPa = 3e5 Pa)")


def _complain(message: str, strict: bool, stacklevel: int) -> None:
    if strict:
        raise InputError(message)
    warnings.warn(message, UnitWarning, stacklevel=stacklevel + 1)
