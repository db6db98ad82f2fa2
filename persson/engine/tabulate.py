"""Modulus and temperature-shift tables the kernels interpolate.

The complex modulus is evaluated once per call on a log-uniform grid of angular frequency at the table
temperature T0 (a master curve's own T_ref, :func:`persson.engine.solver.table_temperature`), as ln E' and ln E'';
the grid's nodes are the multiples of its step and it reaches down to :data:`ANGULAR_LOW`, so that a value at a
frequency is the same in every call. A temperature T != T0 enters as a shift of log10 omega by
log10 a_T(T) - log10 a_T(T0) (time-temperature superposition, Williams, Landel & Ferry 1955), tabulated
on a uniform temperature grid, and an optional vertical shift ln b_T(T) (``log10_bT``) multiplies the moduli.
Materials without ``log10_aT`` are treated as temperature-independent.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass

import numpy as np

from materials.shift import EXTRAPOLATED_SHIFT

from ..errors import InputError
from .memo import per_object

__all__ = ["ModulusTable", "ShiftTable", "AngularTable", "modulus_table", "shift_table", "relative_shifts",
           "angular_table", "convolution_weights"]

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
        raise InputError(f"material: storage modulus must be > 0, got E'={E.real[i]:.3g} Pa at "
                         f"omega={10**lw[i]:.3g} rad/s")
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
    with warnings.catch_warnings():
        # the table spans temperatures the rubber may never reach; the result judges the ones it does reach
        # against the shift law's range (materials.extrapolated_shift_note), so a table's own notice is left out
        warnings.filterwarnings("ignore", message=EXTRAPOLATED_SHIFT)
        s = np.asarray(f(T), dtype=float) - float(np.asarray(f(T_table), dtype=float))
    s = np.broadcast_to(s, T.shape).astype(float)
    if not np.all(np.isfinite(s)):
        raise InputError(f"material: {name}(T) must be finite on [{T.min():g}, {T.max():g}] C")
    return s


# ==================================================================================================== angular
#: Decades of frequency the modulus table reaches below the lowest frequency looked up: the angular integrals
#: see E at omega cos(phi) < omega, with a weight that falls as 10^{-t} per decade t below (1e-5 at 5 decades,
#: where the modulus is continued by its value at the table's end).
ANGULAR_PAD_DECADES = 5.0
#: log10 omega (rad/s, at the table temperature) down to which every angular table reaches, whatever frequencies
#: a call looks up (lower where one looks up within ANGULAR_PAD_DECADES of it): the values at a frequency are then
#: the same in every call (see :func:`angular_table`).
ANGULAR_LOW = -20.0
#: The top of an angular table is rounded up to a multiple of 1/_TOP_STEPS decade (see :func:`angular_table`).
_TOP_STEPS = 2


@dataclass(frozen=True, eq=False)
class AngularTable:
    r"""The angular integrals of the modulus on a uniform grid of log10 omega (rad/s) at temperature ``T0``.

    ``ln_are``, ``ln_aim``, ``ln_l`` hold the natural logarithms of

    .. math::
        A_{re}(\omega) = \int_0^{2\pi} E'(\omega\cos\phi)^2 d\phi,\quad
        A_{im}(\omega) = \int_0^{2\pi} E''(\omega\cos\phi)^2 d\phi,\quad
        L(\omega) = \int_0^{2\pi} \cos\phi\, E''(\omega\cos\phi)\, d\phi

    (Im E odd in omega, so each is 4 times the integral over [0, pi/2]); ``lw_valid`` is the range of log10
    omega where they are accurate (the table reaches :data:`ANGULAR_PAD_DECADES` lower).
    """

    lw0: float
    dlw: float
    ln_are: np.ndarray
    ln_aim: np.ndarray
    ln_l: np.ndarray
    T0: float
    lw_valid: tuple

    @property
    def log10_omega(self) -> np.ndarray:
        """Grid of log10 omega, rad/s."""
        return self.lw0 + self.dlw * np.arange(self.ln_are.size)


def angular_table(material, T0: float, log10_omega_min: float, log10_omega_max: float,
                  per_decade: int) -> AngularTable:
    r"""Tabulate the angular integrals of ``material.E(omega, T0)`` for log10 omega in [min, max] (rad/s).

    With :math:`\cos\phi = 10^{-t}` each angular integral is a convolution in log frequency,
    :math:`\int_0^\infty K(t)\, F(\log_{10}\omega - t)\, dt` with
    :math:`K(t) = 4\ln 10\; 10^{-(1+p)t} / \sqrt{1 - 10^{-2t}}` (p = 0 for A, 1 for L), evaluated by
    :func:`persson.engine.kernels.angular_convolution` with the weights of :func:`convolution_weights` (exact for the
    cubic interpolant of F between the table nodes). Memoised per material object and arguments
    (:func:`persson.engine.memo.per_object`); a material with ``scaled_modulus`` (base, f, g), whose modulus is
    f E' + i g E'' of a base material (:class:`materials.StrainSoftened`), gets the base's table scaled.

    Raises
    ------
    InputError
        If the material returns non-finite values, E' <= 0 or E'' < 0 for omega > 0.
    """
    scaled = getattr(material, "scaled_modulus", None)
    if scaled is not None:
        # E = f E'_base + i g E''_base: A_re, A_im and L scale by f^2, g^2 and g (a fit of f and g builds one table)
        base, f, g = scaled
        t = angular_table(base, T0, log10_omega_min, log10_omega_max, per_decade)
        return AngularTable(lw0=t.lw0, dlw=t.dlw, ln_are=t.ln_are + 2.0 * math.log(f),
                            ln_aim=t.ln_aim + 2.0 * math.log(g), ln_l=t.ln_l + math.log(g), T0=t.T0,
                            lw_valid=t.lw_valid)
    # the bottom at ANGULAR_LOW, or lower where a call needs it: the integrals at a frequency see the modulus down
    # to the table's end (continued by its value there below it), so a bottom that followed each call's lowest
    # frequency made every value depend, by ~1e-8, on the other speeds and temperatures of the call
    lo = math.floor(min(log10_omega_min - ANGULAR_PAD_DECADES, ANGULAR_LOW) * per_decade) / per_decade
    # the top rounded up to a multiple of 1/_TOP_STEPS decade: a table reaches a little further than a call needs,
    # so that the calls of a fit, whose top frequency moves with its parameters (a flash temperature, a
    # microtexture's cut-off), share a few tables (values below the top do not depend on it: the angular integrals
    # reach down in frequency only)
    hi = math.ceil(log10_omega_max * _TOP_STEPS) / _TOP_STEPS + 3.0 / per_decade
    # a pure function of the material and the table's ends (nodes): fits evaluate one material hundreds of times
    key = ("angular", float(T0), lo, hi, int(per_decade))
    return per_object(material, key, lambda: _angular_table(material, float(T0), lo, hi, int(per_decade),
                                                            (lo + ANGULAR_PAD_DECADES, hi - 3.0 / per_decade)))


def _angular_table(material, T0: float, lo: float, hi: float, per_decade: int, valid: tuple) -> AngularTable:
    from . import kernels as _kernels

    table = modulus_table(material, T0, lo, hi, per_decade)
    Er = np.exp(table.ln_re)
    Ei = np.exp(table.ln_im)
    dlw = 1.0 / per_decade
    n = Er.size
    out = []
    for F, power in ((Er * Er, 0), (Ei * Ei, 0), (Ei, 1)):
        c = convolution_weights(per_decade, min(n, _max_weights(per_decade)), power)
        a = np.empty(n)
        _kernels.angular_convolution(np.ascontiguousarray(F), c, a)
        out.append(np.log(np.maximum(a, 1e-300)))
    return AngularTable(lw0=table.lw0, dlw=dlw, ln_are=out[0], ln_aim=out[1], ln_l=out[2], T0=T0, lw_valid=valid)


def _max_weights(per_decade: int) -> int:
    # K(t) < 1e-20 of its value near t = 0 past 20 decades: later weights are zero in double precision
    return int(20 * per_decade) + 3


@functools.lru_cache(maxsize=16)
def convolution_weights(per_decade: int, n: int, power: int) -> np.ndarray:
    r"""Weights c_d (d = -1 .. n+1, stored at ``c[d + 1]``; n cells) of :math:`\int_0^\infty K(t) F(\ell - t) dt =
    \sum_d c_d F(\ell - d\Delta)` for F interpolated by 4-point Lagrange polynomials on the uniform grid of step
    :math:`\Delta = 1/` ``per_decade``.

    Cell m covers :math:`t \in [m\Delta, (m+1)\Delta]`, where F is the cubic through the nodes
    :math:`\ell - (m+2)\Delta, ..., \ell - (m-1)\Delta`; each basis polynomial is integrated against K by 12-point
    Gauss-Legendre (in :math:`\sqrt{t}` on the first cell, where :math:`K \sim t^{-1/2}`). A cell's integrals do not
    depend on n: they are computed once for the most cells a table uses (:func:`_cell_weights`) and summed here
    over the first n. Pure function of its arguments, cached; read-only result.
    """
    dlw = 1.0 / per_decade
    cells = _cell_weights(per_decade, max(n, _max_weights(per_decade)), power)
    c = np.zeros(n + 3)
    for k, r in enumerate((-1, 0, 1, 2)):
        d = np.arange(n) + 1 - r  # the stencil node r of cell m is F_{j - (m + 1 - r)}
        np.add.at(c, d + 1, cells[k, :n])
    # K beyond the last cell, in closed form (y = 10^-t): 4 arcsin(Y) for p = 0, 4 (1 - sqrt(1 - Y^2)) for p = 1;
    # it multiplies values further down than any node, i.e. the clamped F_0
    Y = 10.0 ** (-n * dlw)
    c[-1] += 4.0 * math.asin(Y) if power == 0 else 4.0 * (1.0 - math.sqrt(1.0 - Y * Y))
    c.setflags(write=False)
    return c


@functools.lru_cache(maxsize=8)
def _cell_weights(per_decade: int, n: int, power: int) -> np.ndarray:
    """(4, n): the integral against K of each of the four Lagrange basis polynomials of cells 0 .. n-1 (see
    :func:`convolution_weights`); read-only."""
    dlw = 1.0 / per_decade
    xg, wg = np.polynomial.legendre.leggauss(12)
    xg = 0.5 * (xg + 1.0)
    wg = 0.5 * wg
    m = np.arange(n)[:, None]
    first = m == 0
    sig = np.where(first, xg * xg, xg)
    jac = np.where(first, 2.0 * xg, 1.0)
    t = (m + sig) * dlw
    K = 4.0 * math.log(10.0) * 10.0 ** (-(1 + power) * t) / np.sqrt(-np.expm1(-2.0 * math.log(10.0) * t))
    kw = K * jac * dlw * wg  # (n, 12)
    tau = 1.0 - sig  # position in the cell [node m+1 below, node m below] of the 4-point stencil
    basis = (-tau * (tau - 1) * (tau - 2) / 6, (tau + 1) * (tau - 1) * (tau - 2) / 2,
             -(tau + 1) * tau * (tau - 2) / 2, (tau + 1) * tau * (tau - 1) / 6)
    out = np.stack([(b * kw).sum(axis=1) for b in basis])
    out.setflags(write=False)
    return out
