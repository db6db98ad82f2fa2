"""Modulus and temperature-shift tables the kernels interpolate.

The complex modulus is evaluated once per call on a log-uniform grid of angular frequency at the table
temperature T0, as ln E' and ln E''; a temperature T != T0 enters as a shift of log10 omega by
log10 a_T(T) - log10 a_T(T0) (time-temperature superposition, Williams, Landel & Ferry 1955), tabulated
on a uniform temperature grid. Materials without ``log10_aT`` are treated as temperature-independent.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError

__all__ = ["ModulusTable", "ShiftTable", "modulus_table", "shift_table"]

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
    """log10 a_T(T) - log10 a_T(T0) on a uniform temperature grid starting at ``T_lo`` (deg C)."""

    T_lo: float
    dT: float
    shift: np.ndarray

    def __call__(self, T):
        """Interpolated shift at temperature(s) T (clamped to the table)."""
        x = self.T_lo + self.dT * np.arange(self.shift.size)
        return np.interp(T, x, self.shift)


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


def shift_table(material, T0: float, T_max: float, step: float) -> ShiftTable:
    """Tabulate log10 a_T(T) - log10 a_T(T0) for T in [T0, T_max] (deg C)."""
    n = max(2, int(math.ceil((T_max - T0) / step)) + 1)
    T = T0 + step * np.arange(n)
    log_shift = getattr(material, "log10_aT", None)
    if log_shift is None:
        s = np.zeros(n)
    else:
        s = np.asarray(log_shift(T), dtype=float) - float(np.asarray(log_shift(T0), dtype=float))
        if s.shape != T.shape or not np.all(np.isfinite(s)):
            raise InputError(f"material: log10_aT(T) must be finite on [{T0:g}, {T_max:g}] C")
    return ShiftTable(T_lo=float(T0), dT=float(step), shift=s)
