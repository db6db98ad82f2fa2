"""Units of the columns found in DMA exports, and plausibility guards that catch unit slips.

The readers take the unit of each column from, in this order: the ``units=`` option (the user's word), a units
row or a bracketed unit in the header (``[MPa]``, ``(Hz)``), a unit suffix of the column name (``E_storage_Pa``,
``f_Hz``, ``T_C``, ``strain_pct``), and finally the project's default (Hz, Pa, deg C, absolute strain).

Whatever the source, the values are then checked against what a polymer can be (:func:`check_moduli`,
:func:`check_temperatures`, :func:`check_strains`). A unit given with ``units=`` is trusted for the range
checks that could only flag a unit slip; impossible values (below absolute zero) are refused whatever the unit.
"""

from __future__ import annotations

import math
import re

import numpy as np

from .errors import InputError

__all__ = ["ROLES", "MODULUS_RANGE_PA", "KELVIN_LOOKING_C", "unit_factor", "split_unit_suffix",
           "to_celsius", "check_moduli", "check_temperatures", "check_strains", "normalise_units"]

#: Column roles the readers know and the units each accepts.
ROLES = ("f", "E_storage", "E_loss", "T", "strain")

#: Young's (or shear) moduli of polymers lie in this range, Pa: soft gels near 1e4, rubbers 1e5 to 1e7, glassy
#: polymers a few GPa, and nothing above 1e11 (stiffer than any polymer crystal). A whole column below 1e5 Pa
#: (its largest storage modulus) is what MPa values read as Pa look like: 3.5 MPa typed as 3.5.
MODULUS_RANGE_PA = (1e5, 1e11)

#: Temperatures (deg C) that all lie in this band look like kelvin (200 K = -73 C, 450 K = 177 C): the same rule
#: as the measurement reader of :mod:`validation`.
KELVIN_LOOKING_C = (200.0, 450.0)

_ABS_ZERO_C = -273.15

_FREQUENCY = {"hz": 1.0, "khz": 1e3, "mhz": 1e6, "rad/s": 1.0 / (2.0 * math.pi),
              "rad/sec": 1.0 / (2.0 * math.pi), "rads": 1.0 / (2.0 * math.pi), "rad_s": 1.0 / (2.0 * math.pi)}
_MODULUS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9, "n/m2": 1.0, "n/m^2": 1.0, "n/mm2": 1e6,
            "n/mm^2": 1e6, "n/mm²": 1e6, "n/m²": 1.0}
_TEMPERATURE = {"c": "C", "degc": "C", "celsius": "C", "°c": "C", "ºc": "C", "k": "K", "kelvin": "K"}
_STRAIN = {"%": 0.01, "percent": 0.01, "pct": 0.01, "-": 1.0, "1": 1.0, "abs": 1.0, "absolute": 1.0,
           "mm/mm": 1.0, "m/m": 1.0, "": 1.0}

# a bare "1/s" is ambiguous for a frequency (Hz or rad/s): it is read as rad/s only for omega columns
_RAD_S = 1.0 / (2.0 * math.pi)


def unit_factor(role: str, unit: str, *, where: str, omega: bool = False):
    """Factor to the project's unit (Hz, Pa, absolute strain) or, for ``role="T"``, ``"C"`` / ``"K"``.

    Parameters
    ----------
    role : {"f", "E_storage", "E_loss", "T", "strain"}
    unit : str
        As written in the file or given by the user (brackets and case ignored).
    where : str
        File and column, for the message.
    omega : bool
        The column is an angular frequency (named ``omega``/``w``): a bare ``1/s`` means rad/s.

    Raises
    ------
    InputError
        An unknown unit, naming the column and the units accepted.

    Examples
    --------
    >>> unit_factor("E_storage", "MPa", where="dma.csv, column E'")
    1000000.0
    """
    u = _clean(unit)
    if role == "f":
        if u in ("", "-"):
            return _RAD_S if omega else 1.0
        if u == "1/s":
            return _RAD_S if omega else 1.0
        if u in _FREQUENCY:
            return _FREQUENCY[u]
        raise InputError(f"{where}: unknown frequency unit {unit!r} (expected Hz, kHz or rad/s)")
    if role in ("E_storage", "E_loss"):
        if u in _MODULUS:
            return _MODULUS[u]
        raise InputError(f"{where}: unknown modulus unit {unit!r} (expected Pa, kPa, MPa, GPa or N/mm2)")
    if role == "T":
        if u in _TEMPERATURE:
            return _TEMPERATURE[u]
        raise InputError(f"{where}: unknown temperature unit {unit!r} (expected C or K)")
    if role == "strain":
        if u in _STRAIN:
            return _STRAIN[u]
        raise InputError(f"{where}: unknown strain unit {unit!r} (expected % or - for an absolute strain)")
    raise InputError(f"units: unknown column role {role!r} (expected one of {', '.join(ROLES)})")


_SUFFIXES = (("_rad_s", "rad/s"), ("_rads", "rad/s"), ("_khz", "kHz"), ("_hz", "Hz"), ("_gpa", "GPa"),
             ("_mpa", "MPa"), ("_kpa", "kPa"), ("_pa", "Pa"), ("_pct", "%"), ("_percent", "%"), ("_%", "%"),
             ("_c", "C"), ("_k", "K"))


def split_unit_suffix(name: str) -> tuple[str, str | None]:
    """``"E_storage_MPa"`` -> (``"E_storage"``, ``"MPa"``); a name without a known unit suffix is returned whole."""
    low = name.strip().lower()
    for suffix, unit in _SUFFIXES:
        if low.endswith(suffix) and len(low) > len(suffix):
            return name.strip()[: -len(suffix)], unit
    return name.strip(), None


def normalise_units(units) -> dict[str, str]:
    """The ``units=`` option as {role: unit}: keys ``f``, ``E`` (both moduli), ``E_storage``, ``E_loss``, ``T``,
    ``strain`` (``G``, ``G_storage``, ``G_loss`` are accepted for shear data)."""
    if units is None:
        return {}
    if not hasattr(units, "items"):
        raise InputError(f"units: expected a mapping such as {{'f': 'Hz', 'E': 'MPa', 'T': 'C', 'strain': '%'}}, "
                         f"got {units!r}")
    out = {}
    for key, unit in units.items():
        k = str(key)
        if not isinstance(unit, str):
            raise InputError(f"units[{k!r}]: expected a unit name such as 'MPa', got {unit!r}")
        if k in ("E", "G", "modulus", "moduli"):
            out["E_storage"] = out["E_loss"] = unit
        elif k in ("E_storage", "G_storage", "E'", "G'"):
            out["E_storage"] = unit
        elif k in ("E_loss", "G_loss", "E''", "G''", 'E"', 'G"'):
            out["E_loss"] = unit
        elif k in ("f", "frequency", "omega"):
            out["f"] = unit
        elif k in ("T", "temperature"):
            out["T"] = unit
        elif k in ("strain", "strain_amplitude"):
            out["strain"] = unit
        else:
            raise InputError(f"units: unknown key {k!r} (expected f, E, E_storage, E_loss, T or strain)")
    return out


def to_celsius(T, unit_kind: str) -> np.ndarray:
    """Temperatures to deg C from ``"C"`` or ``"K"`` (as returned by :func:`unit_factor` for role ``"T"``)."""
    T = np.asarray(T, dtype=float)
    return T - 273.15 if unit_kind == "K" else T


def check_temperatures(T_C, *, where: str, lines=None, trusted: bool = False) -> None:
    """Refuse temperatures below absolute zero, and (unless the unit was given explicitly) columns in kelvin.

    Parameters
    ----------
    T_C : array_like
        Temperatures as read, deg C.
    where : str
        File and column, for the message.
    lines : array_like of int, optional
        File line of each value (the first offending line is named).
    trusted : bool
        The unit came from the ``units=`` option: the kelvin-looking check is skipped.

    Raises
    ------
    InputError
        A temperature below -273.15 C, or all temperatures within 200..450 "C".
    """
    T = np.asarray(T_C, dtype=float)
    finite = np.isfinite(T)
    below = finite & (T < _ABS_ZERO_C)
    if below.any():
        i = int(np.flatnonzero(below)[0])
        at = f", line {int(lines[i])}" if lines is not None and int(lines[i]) > 0 else ""
        raise InputError(f"{where}{at}: temperature {T[i]:g} C is below absolute zero (-273.15 C); expected "
                         "degrees Celsius")
    if trusted or not finite.any():
        return
    lo, hi = float(T[finite].min()), float(T[finite].max())
    if KELVIN_LOOKING_C[0] <= lo and hi <= KELVIN_LOOKING_C[1]:
        raise InputError(f"{where}: every temperature lies in {lo:g}..{hi:g}, which looks like kelvin "
                         f"({lo - 273.15:g}..{hi - 273.15:g} C); give degrees Celsius, or declare the unit "
                         "(units={'T': 'K'}, or units={'T': 'C'} if these really are deg C)")


def check_moduli(E_storage, E_loss=None, *, where: str, unit: str = "Pa", trusted: bool = False,
                 source_unit: str | None = None) -> None:
    """Refuse moduli outside any polymer's range (:data:`MODULUS_RANGE_PA`): the sign of a unit slip.

    Parameters
    ----------
    E_storage, E_loss : array_like
        Moduli already converted to Pa.
    where : str
        File and column(s), for the message.
    unit : str
        The unit the values were read in (named in the message).
    trusted : bool
        The unit came from the ``units=`` option: no range check (soft gels below 0.1 MPa are then accepted).
    source_unit : str, optional
        Where the unit came from (``"column name"``, ``"units row"``, ``"default"``), for the message.

    Raises
    ------
    InputError
        Naming the column, the range found, the likely unit and how to declare it.
    """
    if trusted:
        return
    E1 = np.asarray(E_storage, dtype=float)
    E1 = E1[np.isfinite(E1) & (E1 > 0)]
    if E1.size == 0:
        return
    lo, hi = MODULUS_RANGE_PA
    told = f" (unit {unit}" + (f" from the {source_unit}" if source_unit else "") + ")"
    if E1.max() < lo:
        scale = _likely_scale(E1.max())
        raise InputError(f"{where}: storage moduli {E1.min():.4g}..{E1.max():.4g} Pa{told} are below any "
                         f"polymer's range ({lo:.0e} to {hi:.0e} Pa); the values look like {scale}: declare the "
                         f"unit, e.g. units={{'E': '{scale}'}} (or units={{'E': 'Pa'}} if they really are Pa)")
    all_E = E1 if E_loss is None else np.concatenate([E1, np.asarray(E_loss, dtype=float).ravel()])
    all_E = all_E[np.isfinite(all_E)]
    if all_E.max() > hi:
        raise InputError(f"{where}: moduli up to {all_E.max():.4g} Pa{told} are above any polymer's range "
                         f"({lo:.0e} to {hi:.0e} Pa); the values look like Pa in a column read as {unit}: "
                         "declare the unit, e.g. units={'E': 'Pa'}")


def check_strains(strain, *, where: str, unit: str, trusted: bool = False) -> None:
    """Refuse strain amplitudes that look like percent in a column read as absolute strain.

    A DMA strain amplitude above 1 (100 %) is beyond any sweep; ``units={'strain': '-'}`` accepts it anyway.
    """
    s = np.asarray(strain, dtype=float)
    s = s[np.isfinite(s)]
    if trusted or s.size == 0 or unit not in ("-", "", "1", "abs", "absolute", "mm/mm", "m/m"):
        return
    if s.max() > 1.0:
        raise InputError(f"{where}: strain amplitudes up to {s.max():g} read as absolute strain ({100 * s.max():g} "
                         "%) are beyond any strain sweep; they look like percent: declare units={'strain': '%'} "
                         "(or units={'strain': '-'} if they really are absolute)")



# ==================================================================================================== helpers

def _clean(unit) -> str:
    u = str(unit).strip()
    u = re.sub(r"^[\[(]\s*|\s*[\])]$", "", u)
    return u.replace(" ", "").replace("\u00b0", "°").lower()


def _likely_scale(max_value_as_pa: float) -> str:
    # the unit that brings the stiffest point into 1e6..1e10 Pa
    for name, factor in (("MPa", 1e6), ("kPa", 1e3), ("GPa", 1e9)):
        if 1e5 <= max_value_as_pa * factor <= 1e11:
            return name
    return "MPa"
