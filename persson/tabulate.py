"""Modulus and temperature-shift tables the kernels interpolate.

The complex modulus is evaluated once per call on a log-uniform grid of angular frequency at the table
temperature T0, as ln E' and ln E''; a temperature T != T0 enters as a shift of log10 omega by
log10 a_T(T) - log10 a_T(T0) (time-temperature superposition, Williams, Landel & Ferry 1955), tabulated
on a uniform temperature grid, and an optional vertical shift ln b_T(T) (``log10_bT``) multiplies the moduli.
Materials without ``log10_aT`` are treated as temperature-independent.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError

__all__ = ["ModulusTable", "ShiftTable", "modulus_table", "shift_table", "relative_shifts"]

# Relative floor for ln E'' so that a purely elastic material (E'' = 0) stays finite in the log table.
_LOSS_FLOOR = 1e-30


@dataclass(frozen=True, eq=False)
class ModulusTable:
    """ln E' and ln E'' on a uniform grid of log10 omega (rad/s) at temperature ``T0`` (deg C)."""

    lw0: float
    dlw: float
    ln_re: np.ndarray
    ln_im: np.ndarray
    T0: float

    @property
    def log10_omega(self) -> np.ndarray:
        """Grid of log10 omega, rad/s."""
        return self.lw0 + self.dlw * np.arange(self.ln_re.size)


@dataclass(frozen=True, eq=False)
class ShiftTable:
    """log10 a_T(T) and ln b_T(T) relative to the table temperature, on a uniform grid from ``T_lo`` (deg C)."""

    T_lo: float
    dT: float
    shift: np.ndarray
    vshift: np.ndarray

    @property
    def T_hi(self) -> float:
        """Last temperature of the table, deg C."""
        return self.T_lo + self.dT * (self.shift.size - 1)


def modulus_table(material, T0: float, log10_omega_min: float, log10_omega_max: float,
                  per_decade: int) -> ModulusTable:
    """Tabulate ``material.E(omega, T0)`` for log10 omega in [min, max] (rad/s).

    Raises
    ------
    InputError
        If the material returns non-finite values, E' <= 0 or E'' < 0 for omega > 0.
    """
    lo = math.floor(log10_omega_min * per_decade) / per_decade
    hi = math.ceil(log10_omega_max * per_decade) / per_decade
    n = int(round((hi - lo) * per_decade)) + 1
    n = max(n, 2)
    lw = lo + np.arange(n) / per_decade
    E = np.asarray(material.E(10.0**lw, T0), dtype=complex)
    if E.shape != lw.shape:
        raise InputError(f"material: E(omega, T) returned shape {E.shape} for omega of shape {lw.shape}")
    if not np.all(np.isfinite(E)):
        i = int(np.argmax(~np.isfinite(E)))
        raise InputError(f"material: E(omega={10**lw[i]:.3g} rad/s, T={T0} C) is not finite")
    if np.any(E.real <= 0):
        i = int(np.argmax(E.real <= 0))
        raise InputError(f"material: storage modulus must be > 0, got E'={E.real[i]:.3g} Pa at omega={10**lw[i]:.3g} rad/s")
    if np.any(E.imag < 0):
        i = int(np.argmax(E.imag < 0))
        raise InputError(f"material: loss modulus must be >= 0 for omega > 0, got E''={E.imag[i]:.3g} Pa "
                         f"at omega={10**lw[i]:.3g} rad/s")
    floor = _LOSS_FLOOR * float(np.max(np.abs(E)))
    return ModulusTable(lw0=float(lo), dlw=1.0 / per_decade, ln_re=np.log(E.real),
                        ln_im=np.log(np.maximum(E.imag, floor)), T0=float(T0))


def shift_table(material, T_table: float, T_lo: float, T_hi: float, step: float) -> ShiftTable:
    """Tabulate log10 a_T(T) - log10 a_T(T_table) and ln b_T(T) - ln b_T(T_table) for T in [T_lo, T_hi] (deg C).

    Materials without ``log10_aT`` are temperature-independent (zero shifts); ``log10_bT`` (vertical shift)
    is optional.
    """
    n = max(2, int(math.ceil((T_hi - T_lo) / step)) + 1)
    T = T_lo + step * np.arange(n)
    s = _relative(material, "log10_aT", T, T_table)
    b = _relative(material, "log10_bT", T, T_table) * math.log(10.0)
    return ShiftTable(T_lo=float(T_lo), dT=float(step), shift=s, vshift=b)


def relative_shifts(material, T, T_table: float) -> tuple[np.ndarray, np.ndarray]:
    """(log10 a_T(T) - log10 a_T(T_table), ln b_T(T) - ln b_T(T_table)) at temperatures ``T``."""
    T = np.asarray(T, dtype=float)
    return (_relative(material, "log10_aT", T, T_table),
            _relative(material, "log10_bT", T, T_table) * math.log(10.0))


def _relative(material, name: str, T: np.ndarray, T_table: float) -> np.ndarray:
    f = getattr(material, name, None)
    if f is None:
        return np.zeros(T.shape)
    s = np.asarray(f(T), dtype=float) - float(np.asarray(f(T_table), dtype=float))
    s = np.broadcast_to(s, T.shape).astype(float)
    if not np.all(np.isfinite(s)):
        raise InputError(f"material: {name}(T) must be finite on [{T.min():g}, {T.max():g}] C")
    return s
