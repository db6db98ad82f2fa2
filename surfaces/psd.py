"""Isotropic 2D power spectral densities in Persson's convention.

Two objects share one small interface used by the friction engine:

* :class:`SelfAffine` -- the analytic self-affine PSD :math:`C(q) = C_0 q^{-2(1+H)}` between the roll-off
  ``q0`` and the short-distance cut-off ``q1``, optionally flat from ``qL`` to ``q0``;
* :class:`PSD` -- a tabulated PSD ``(q, C)``, interpolated linearly in log-log.

Both expose ``C(q)``, ``hrms()``, ``rms_slope()``, ``moment(n)``, ``with_cutoff(...)`` and the support
``q_range = (q_start, q_end)`` over which the physics integrals run. ``C`` is zero outside the support.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .errors import InputError

__all__ = ["SelfAffine", "PSD"]


@doi("10.1088/0953-8984/17/1/R01")
@dataclass(frozen=True, init=False)
class SelfAffine:
    r"""Self-affine isotropic PSD with roll-off.

    .. math::
        C(q) = \begin{cases} C_0 q_0^{-2(1+H)} & q_L \le q < q_0 \\
                             C_0 q^{-2(1+H)} & q_0 \le q \le q_1 \\
                             0 & \text{otherwise} \end{cases}

    (Persson et al., J. Phys.: Condens. Matter 17, R1 (2005), Eq. 10).

    Parameters
    ----------
    hurst : float
        Hurst exponent H, 0 < H < 1.
    q0 : float
        Roll-off wavevector, rad/m.
    q1 : float
        Short-distance cut-off, rad/m (> q0).
    hrms : float, optional
        Root-mean-square height over the whole support, m. Give exactly one of ``hrms`` and ``C0``.
    C0 : float, optional
        Prefactor of the power law, m^4 (rad/m)^(2(1+H)).
    qL : float, optional
        Smallest wavevector (2 pi / L). ``None`` (default) means no roll-off plateau: C = 0 below q0.
    """

    hurst: float
    q0: float
    q1: float
    C0: float
    qL: float | None

    def __init__(self, hurst: float, q0: float, q1: float, hrms: float | None = None, C0: float | None = None,
                 qL: float | None = None):
        H = _finite_float(hurst, "hurst")
        if not 0.0 < H < 1.0:
            raise InputError(f"hurst: expected 0 < H < 1, got {H}")
        q0 = _positive(q0, "q0")
        q1 = _positive(q1, "q1")
        if not q1 > q0:
            raise InputError(f"q1: expected q1 > q0 = {q0:g} rad/m, got {q1:g}")
        if qL is not None:
            qL = _positive(qL, "qL")
            if qL > q0:
                raise InputError(f"qL: expected qL <= q0 = {q0:g} rad/m, got {qL:g}")
        if (hrms is None) == (C0 is None):
            raise InputError("SelfAffine: give exactly one of hrms= (m) and C0= (m^4 (rad/m)^(2+2H))")
        if C0 is None:
            h = _positive(hrms, "hrms")
            C0 = h**2 / (2.0 * math.pi * _moment_selfaffine(1.0, H, q0, q1, qL, 1))
        else:
            C0 = _positive(C0, "C0")
        for name, value in (("hurst", H), ("q0", q0), ("q1", q1), ("C0", float(C0)), ("qL", qL)):
            object.__setattr__(self, name, value)

    @property
    def q_range(self) -> tuple[float, float]:
        """Support (q_start, q_end) of C in rad/m: (qL or q0, q1)."""
        return (self.qL if self.qL is not None else self.q0, self.q1)

    def C(self, q):
        """PSD C(q) in m^4 at wavevector(s) ``q`` (rad/m); zero outside the support."""
        q = np.asarray(q, dtype=float)
        H = self.hurst
        lo = self.q_range[0]
        out = np.where(q < self.q0, self.C0 * self.q0 ** (-2 * (1 + H)), self.C0 * np.abs(q) ** (-2 * (1 + H)))
        return np.where((q >= lo * (1 - 1e-12)) & (q <= self.q1 * (1 + 1e-12)), out, 0.0)

    def moment(self, n: int) -> float:
        r"""Spectral moment :math:`2\pi \int q^n C(q)\, dq` over the support (exact)."""
        return 2.0 * math.pi * _moment_selfaffine(self.C0, self.hurst, self.q0, self.q1, self.qL, n)

    def hrms(self) -> float:
        r"""RMS height, m: :math:`h_{rms}^2 = 2\pi\int q C(q) dq`."""
        return math.sqrt(self.moment(1))

    def rms_slope(self) -> float:
        r"""RMS slope: :math:`\xi^2 = 2\pi\int q^3 C(q) dq`."""
        return math.sqrt(self.moment(3))

    def with_cutoff(self, q0: float | None = None, q1: float | None = None) -> "SelfAffine":
        """Same power law (same C0) with other cut-offs."""
        return SelfAffine(self.hurst, self.q0 if q0 is None else q0, self.q1 if q1 is None else q1,
                          C0=self.C0, qL=self.qL if (q0 is None or self.qL is None or self.qL <= q0) else None)

    def tabulate(self, n_per_decade: int = 64) -> "PSD":
        """Tabulated copy on a log grid over the support (the power-law part exactly interpolated)."""
        lo, hi = self.q_range
        n = max(2, int(math.ceil(n_per_decade * math.log10(hi / lo))) + 1)
        q = np.geomspace(lo, hi, n)
        if self.qL is not None and self.qL < self.q0:
            q = np.union1d(q, [self.q0])
        return PSD(q, self.C(q))


@dataclass(frozen=True, eq=False)
class PSD:
    r"""Tabulated isotropic 2D PSD, interpolated linearly in log-log, zero outside ``[q[0], q[-1]]``.

    Parameters
    ----------
    q : array_like
        Strictly increasing wavevectors, rad/m.
    C : array_like
        PSD values, m^4, strictly positive (Persson convention, 2D isotropic).
    q_r : float, optional
        Reliability limit of the instrument, rad/m; past it the tail is extrapolated.
    extrapolated : bool
        True when part of the table beyond ``q_r`` is an extrapolation, not a measurement.
    """

    q: np.ndarray
    C_values: np.ndarray
    q_r: float | None = None
    extrapolated: bool = False
    source: str = ""

    def __init__(self, q, C, q_r: float | None = None, extrapolated: bool = False, source: str = ""):
        q = np.array(q, dtype=float, copy=True).ravel()
        C = np.array(C, dtype=float, copy=True).ravel()
        where = f" ({source})" if source else ""
        if q.size < 2 or q.size != C.size:
            raise InputError(f"PSD{where}: q and C must have the same length >= 2, got {q.size} and {C.size}")
        bad = ~np.isfinite(q) | ~np.isfinite(C)
        if bad.any():
            raise InputError(f"PSD{where}: non-finite value in q or C at row {int(np.argmax(bad))}")
        if (q <= 0).any():
            raise InputError(f"PSD{where}: column q must be > 0 rad/m (row {int(np.argmax(q <= 0))})")
        if (np.diff(q) <= 0).any():
            raise InputError(f"PSD{where}: column q must be strictly increasing (row {int(np.argmax(np.diff(q) <= 0)) + 1})")
        if (C <= 0).any():
            raise InputError(f"PSD{where}: column C must be > 0 m^4 (row {int(np.argmax(C <= 0))})")
        q.setflags(write=False)
        C.setflags(write=False)
        object.__setattr__(self, "q", q)
        object.__setattr__(self, "C_values", C)
        object.__setattr__(self, "q_r", None if q_r is None else _positive(q_r, "q_r"))
        object.__setattr__(self, "extrapolated", bool(extrapolated))
        object.__setattr__(self, "source", str(source))

    @property
    def q0(self) -> float:
        """First wavevector of the table, rad/m."""
        return float(self.q[0])

    @property
    def q1(self) -> float:
        """Last wavevector of the table, rad/m."""
        return float(self.q[-1])

    @property
    def q_range(self) -> tuple[float, float]:
        """Support (q_start, q_end), rad/m."""
        return (self.q0, self.q1)

    def C(self, q):
        """PSD at ``q`` (rad/m), log-log interpolation, zero outside the table."""
        q = np.asarray(q, dtype=float)
        lq = np.log(np.clip(q, self.q[0], self.q[-1]))
        out = np.exp(np.interp(lq, np.log(self.q), np.log(self.C_values)))
        inside = (q >= self.q[0] * (1 - 1e-12)) & (q <= self.q[-1] * (1 + 1e-12))
        return np.where(inside, out, 0.0)

    def moment(self, n: int) -> float:
        r"""Spectral moment :math:`2\pi\int q^n C(q) dq`, exact for the log-log interpolant."""
        return 2.0 * math.pi * float(np.sum(_powerlaw_segments_integral(self.q, self.C_values, n)))

    def hrms(self) -> float:
        """RMS height, m."""
        return math.sqrt(self.moment(1))

    def rms_slope(self) -> float:
        """RMS slope (dimensionless)."""
        return math.sqrt(self.moment(3))

    def with_cutoff(self, q0: float | None = None, q1: float | None = None) -> "PSD":
        """The table restricted to ``[q0, q1]`` (end points interpolated). Extending past the table is not
        done here; see the surfaces cut-off tools for tail extrapolation."""
        lo = self.q0 if q0 is None else _positive(q0, "q0")
        hi = self.q1 if q1 is None else _positive(q1, "q1")
        if not hi > lo:
            raise InputError(f"with_cutoff: expected q1 > q0, got q0={lo:g}, q1={hi:g}")
        if lo < self.q0 * (1 - 1e-9) or hi > self.q1 * (1 + 1e-9):
            raise InputError(f"with_cutoff: [{lo:g}, {hi:g}] rad/m lies outside the table [{self.q0:g}, {self.q1:g}]; "
                             "extrapolate the tail explicitly")
        inner = self.q[(self.q > lo) & (self.q < hi)]
        q = np.concatenate([[lo], inner, [hi]])
        return PSD(q, self.C(q), q_r=self.q_r, extrapolated=self.extrapolated, source=self.source)


def _powerlaw_segments_integral(q: np.ndarray, C: np.ndarray, n: int) -> np.ndarray:
    r"""Exact :math:`\int_{q_i}^{q_{i+1}} q^n C(q) dq` for C a power law on each segment (log-log linear)."""
    qa, qb, Ca, Cb = q[:-1], q[1:], C[:-1], C[1:]
    r = np.log(qb / qa)
    s = np.log(Cb / Ca) / r
    p = n + s + 1.0
    fa = Ca * qa ** (n + 1)
    with np.errstate(over="ignore", invalid="ignore"):
        general = fa * np.expm1(p * r) / p
    return np.where(np.abs(p * r) < 1e-10, fa * r, general)


def _moment_selfaffine(C0: float, H: float, q0: float, q1: float, qL: float | None, n: int) -> float:
    r"""Exact :math:`\int q^n C(q) dq` of the self-affine PSD with plateau."""
    a = n + 1 - 2 * (1 + H)
    tail = C0 * ((q1**a - q0**a) / a if abs(a) > 1e-12 else math.log(q1 / q0))
    plateau = 0.0
    if qL is not None and qL < q0:
        plateau = C0 * q0 ** (-2 * (1 + H)) * (q0 ** (n + 1) - qL ** (n + 1)) / (n + 1)
    return tail + plateau


def _finite_float(value, name: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected a number, got {value!r}") from None
    if not math.isfinite(x):
        raise InputError(f"{name}: expected a finite number, got {x}")
    return x


def _positive(value, name: str) -> float:
    x = _finite_float(value, name)
    if x <= 0:
        raise InputError(f"{name}: expected a positive number, got {x:g}")
    return x
