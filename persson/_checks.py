"""Argument checks shared by the engine's modules: each raises an InputError naming the argument."""

from __future__ import annotations

import math
import warnings

import numpy as np

from .errors import InputError, UnitWarning

__all__ = ["number", "positive", "finite_array", "plausible_pressure", "plausible_temperature", "plausible_speed",
           "plausible_modulus", "unit_slip_notes", "UnitWarning", "PRESSURE_RANGE_PA", "KELVIN_LOOKING_C",
           "SPEED_OF_SOUND_M_S", "FAST_SPEED_M_S", "MODULUS_RANGE_PA"]


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


#: Speed of sound in air at 20 C, m/s: no tire, tester or rubber block slides faster; above it a speed is an error.
SPEED_OF_SOUND_M_S = 343.0
#: Above this sliding speed (360 km/h) a speed is warned about: it looks like km/h or mm/s typed as m/s.
FAST_SPEED_M_S = 100.0
#: Effective moduli E* = E/(1 - nu^2) of anything the contact mechanics is used for: soft gels (10 kPa) to glassy
#: polymers and metals (100 GPa); outside, E* is a unit slip (4 is 4 MPa typed as Pa).
MODULUS_RANGE_PA = (1.0e4, 1.0e12)
#: Surfaces whose wavelengths reach from 1 cm (macrotexture) down to 1 mm (microtexture) are roads (or road-like
#: textures): their rms roughness is 0.05-5 mm, never below a micrometre. A band of a road (a sweep's surface of its
#: own) is not a road: its wavelengths do not span both.
_ROAD_WAVELENGTHS_M = (0.01, 1.0e-3)
#: Below this (and above 0) a friction coefficient on a road-scale surface is taken for a unit slip.
_MIN_ROAD_MU = 1.0e-3
_ROAD_MIN_HRMS_M = 1.0e-6


def plausible_speed(value, name: str, *, stacklevel: int = 3) -> np.ndarray:
    """Check sliding speed(s) in m/s: above the speed of sound (343 m/s) an error, above 100 m/s a UnitWarning.

    The same rule holds in the API, the case file and on the command line: no rubber friction is measured or
    computed above the speed of sound, and speeds of 100-343 m/s are far beyond any tire or tester (they are what
    km/h or mm/s typed as m/s look like).

    Parameters
    ----------
    value : float or array_like
        Speed(s), m/s.
    name : str
        The argument, flag or case key, named in the message.

    Returns
    -------
    ndarray
        The speeds as floats (shape kept).
    """
    v = finite_array(value, name)
    flat = v.ravel()
    if np.any(flat > SPEED_OF_SOUND_M_S):
        bad = float(flat[np.argmax(flat > SPEED_OF_SOUND_M_S)])
        raise InputError(f"{name}: {bad:g} m/s is above the speed of sound ({SPEED_OF_SOUND_M_S:g} m/s); give "
                         f"sliding speeds in m/s ({bad:g} mm/s = {bad * 1e-3:g} m/s, {bad:g} km/h = "
                         f"{bad / 3.6:.4g} m/s)")
    if np.any(flat > FAST_SPEED_M_S):
        bad = float(flat[np.argmax(flat > FAST_SPEED_M_S)])
        _complain(f"{name}: {bad:g} m/s ({bad * 3.6:.4g} km/h) is faster than any tire or friction tester; it "
                  f"looks like km/h ({bad:g} km/h = {bad / 3.6:.4g} m/s) or mm/s typed as m/s", False, stacklevel)
    return v


def plausible_modulus(value, name: str, *, strict: bool = False, stacklevel: int = 3) -> float:
    """Check an effective modulus E* = E/(1 - nu^2) in Pa: > 0 always; outside 10 kPa-1 TPa an error (``strict``)
    or a UnitWarning (E* = 4 is 4 MPa typed as Pa and gives full contact).

    Parameters
    ----------
    value : float
        E*, Pa.
    name : str
        The argument, flag or case key, named in the message.
    strict : bool
        Raise InputError instead of warning on an implausible value.
    """
    E = number(value, name)
    if E <= 0:
        raise InputError(f"{name}: expected an effective modulus E* > 0 Pa, got {E:g}")
    lo, hi = MODULUS_RANGE_PA
    if E < lo:
        _complain(f"{name}: E* = {E:g} Pa is softer than any solid in rubber friction (10 kPa-1 TPa; a tread is "
                  f"1-100 MPa); it looks like MPa ({E:g} MPa = {E * 1e6:g} Pa) or kPa ({E * 1e3:g} Pa)",
                  strict, stacklevel)
    elif E > hi:
        _complain(f"{name}: E* = {E:g} Pa is stiffer than diamond (about 1e12 Pa); give the modulus in Pa",
                  strict, stacklevel)
    return E


def unit_slip_notes(surface, mu, contact_area, *, low_mu_explained: bool = False) -> list[str]:
    """Results that signal a unit slip on a road-scale surface (wavelengths from >= 1 cm to <= 1 mm), as messages.

    On a road the rms roughness is 0.05-5 mm, the real contact a few per cent of the nominal one and the friction
    of rubber 0.1-2. Full contact (A/A0 = 1), mu below 1e-3 or a roughness below 1 um there come from a profile in
    mm read as um, a modulus in MPa typed as Pa or a pressure typed in the wrong unit, not from physics. Each message
    names the value and the likely cause; the caller warns with :class:`UnitWarning` and adds them to the notes.

    Parameters
    ----------
    surface : object
        The PSD (``q_range``, and ``hrms()`` when it has one).
    mu, contact_area : float or ndarray
        Friction coefficient and A/A0 per speed (or pressure).
    low_mu_explained : bool
        The caller has found that the compound's own loss explains a friction below 1e-3 (a rubber that is
        nearly loss-free at the frequencies the surface excites, see :func:`low_road_friction`): no unit-slip
        message for it.
    """
    if not road_scale(surface):
        return []
    q_lo = float(surface.q_range[0])
    out = []
    hrms = getattr(surface, "hrms", None)
    h = float(hrms()) if callable(hrms) else None
    road = f"a road-scale surface (wavelengths up to {2.0 * math.pi / q_lo * 100:.3g} cm)"
    if h is not None and 0 < h < _ROAD_MIN_HRMS_M:
        out.append(f"{road} with an rms roughness of {h * 1e6:.3g} um: road textures are 0.05-5 mm rms; check the "
                   "height unit of the profiles (mm read as um?) or of the PSD (C in m^4)")
    area = np.atleast_1d(np.asarray(contact_area, dtype=float))
    if area.size and np.nanmax(area) >= 0.999:
        out.append(f"full contact (A/A0 = {np.nanmax(area):.4g}) on {road}: real contact on a road is a few per "
                   "cent; check the units of the modulus (MPa typed as Pa?), the pressure and the profile heights")
    m = np.atleast_1d(np.asarray(mu, dtype=float))
    m = m[m > 0]  # exactly 0 is a lossless material, not a unit slip
    if m.size and np.min(m) < _MIN_ROAD_MU and not low_mu_explained:
        out.append(f"friction coefficient {np.min(m):.3g} (< 1e-3) on {road}: rubber on a road gives 0.1-2; "
                   "check the units of the modulus, the pressure and the profile heights")
    return out


def road_scale(surface) -> bool:
    """The surface's wavelengths reach from 1 cm or more down to 1 mm or less (a road or road-like texture)."""
    try:
        q_lo, q_hi = (float(x) for x in surface.q_range)
    except (AttributeError, TypeError, ValueError, IndexError):
        return False
    longest, shortest = _ROAD_WAVELENGTHS_M
    return q_lo > 0 and 2.0 * math.pi / q_lo >= longest and 2.0 * math.pi / q_hi <= shortest


def low_road_friction(surface, mu) -> int | None:
    """Index of the lowest positive friction coefficient when it lies below 1e-3 on a road-scale surface (where
    :func:`unit_slip_notes` would take it for a unit slip), else None."""
    if not road_scale(surface):
        return None
    m = np.atleast_1d(np.asarray(mu, dtype=float))
    m = np.where(m > 0, m, np.inf)
    i = int(np.argmin(m))
    return i if m[i] < _MIN_ROAD_MU else None


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
