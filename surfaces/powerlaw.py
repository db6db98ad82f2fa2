r"""Power laws in log-log: the straight-line and broken-line fits behind the self-affine and roll-off fits.

A self-affine surface has a power-law PSD (Persson et al. 2005; Jacobs, Junge & Pastewka 2017, Sec. 2): the
isotropic 2D PSD :math:`C(q) = C_0 q^{-2(1+H)}` and the line-scan PSD :math:`C_{1D}(q) = A q^{-(1+2H)}`, a
straight line in :math:`(\ln q, \ln C)` of slope :math:`-2(1+H)` or :math:`-(1+2H)`. A roll-off is a line with a
flat part. This module fits those lines to arrays; :mod:`surfaces.psdfit` and :mod:`surfaces.cutoffs` turn the
numbers into fits of PSD objects, and :func:`gamma_factor` links the two prefactors.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from ._util import band
from .errors import InputError

__all__ = ["gamma_factor", "PowerLawLine", "self_affine_line", "BrokenLine", "rolloff_line", "loglog_line",
           "broken_power_law_fit"]

_JACOBS_2017 = "10.1088/2051-672X/aa51f8"
_PERSSON_2005 = "10.1088/0953-8984/17/1/R01"


@doi(_PERSSON_2005, _JACOBS_2017)
def gamma_factor(hurst: float) -> float:
    r""":math:`\Gamma(1+H) / (\sqrt{\pi}\,\Gamma(H+1/2))`, the ratio :math:`q\,C(q)/C_{1D}(q)` of a pure power law.

    Examples
    --------
    >>> round(gamma_factor(0.5), 12)            # Gamma(3/2) / (sqrt(pi) Gamma(1)) = 1/2
    0.5
    """
    from scipy import special
    H = float(hurst)
    return float(np.exp(special.gammaln(1.0 + H) - special.gammaln(H + 0.5)) / math.sqrt(math.pi))


@dataclass(frozen=True)
class PowerLawLine:
    """A self-affine straight line fitted in log-log (see :func:`self_affine_line`).

    Attributes
    ----------
    hurst, hurst_stderr : float
        Hurst exponent and its standard error from the regression.
    prefactor : float
        :math:`e^{\\text{intercept}}`: :math:`C_0` of a 2D PSD, :math:`A` of a line-scan PSD.
    q_min, q_max : float
        First and last wavevector in the band, rad/m.
    n_points : int
        Points in the band.
    rms_log_residual : float
        Rms of the natural-log residuals.
    """

    hurst: float
    hurst_stderr: float
    prefactor: float
    q_min: float
    q_max: float
    n_points: int
    rms_log_residual: float


@doi(_PERSSON_2005, _JACOBS_2017)
def self_affine_line(q, C, kind: str, q_min: float | None, q_max: float | None, where: str) -> PowerLawLine:
    r"""Least-squares line through :math:`(\ln q, \ln C)` on ``[q_min, q_max]``, read as a Hurst exponent.

    Parameters
    ----------
    q, C : ndarray
        Wavevectors (rad/m, increasing) and PSD values.
    kind : {"isotropic", "1d"}
        Slope :math:`-2(1+H)` (2D PSD) or :math:`-(1+2H)` (line-scan PSD).
    q_min, q_max : float or None
        Band, rad/m (None: open end).
    where : str
        The PSD's name, for messages.

    Raises
    ------
    InputError
        Fewer than three points in the band, or a fitted H outside (0, 1] (the band is not self-affine).
    """
    m = band(q, q_min, q_max, "fit_self_affine")
    slope, intercept, (stderr, resid) = loglog_line(q[m], C[m], where=where, full=True)
    H = (-slope - 1.0) / 2.0 if kind == "1d" else -slope / 2.0 - 1.0
    if not (np.isfinite(H) and 0.0 < H <= 1.05):
        raise InputError(f"fit_self_affine ({where}): fitted H = {H:.3g} on [{q[m][0]:g}, {q[m][-1]:g}] rad/m "
                         "is outside (0, 1]: the band is not self-affine; choose another band")
    return PowerLawLine(hurst=float(H), hurst_stderr=float(stderr / 2.0), prefactor=math.exp(intercept),
                        q_min=float(q[m][0]), q_max=float(q[m][-1]), n_points=int(m.sum()),
                        rms_log_residual=float(resid))


@dataclass(frozen=True)
class BrokenLine:
    r"""A roll-off fitted in log-log (see :func:`rolloff_line`): flat at :math:`C_p` below :math:`q_0`, slope
    :math:`-s` above it, read as a Hurst exponent."""

    q0: float
    C_plateau: float
    slope: float
    hurst: float
    rms_log_residual: float


def rolloff_line(q, C, kind: str, q_min: float | None, q_max: float | None, where: str) -> BrokenLine:
    """The roll-off model (flat below :math:`q_0`, power law above) fitted in log-log on ``[q_min, q_max]``.

    Parameters are those of :func:`self_affine_line`.

    Raises
    ------
    InputError
        Fewer than five points in the band, fewer than three above the fitted break, or a fitted H outside (0, 1].
    """
    m = band(q, q_min, q_max, "fit_rolloff")
    if m.sum() < 5:
        raise InputError(f"fit_rolloff ({where}): need >= 5 points in the band, got {int(m.sum())}")
    x = np.log(q[m])
    a, s, b, resid = broken_power_law_fit(x, np.log(C[m]), flat="below")
    # with one or two points above the break, a break anywhere between them and the plateau fits exactly, each with
    # its own slope: the exponent is whatever the optimizer stopped at, not a property of the data
    n_above = int(np.sum(x > b))
    if n_above < 3:
        raise InputError(f"fit_rolloff ({where}): {n_above} point(s) of the band above the fitted roll-off "
                         f"q0 = {math.exp(b):.4g} rad/m; the power law above it needs >= 3 to give an exponent")
    H = (s - 1.0) / 2.0 if kind == "1d" else s / 2.0 - 1.0
    if not (np.isfinite(H) and 0.0 < H <= 1.05):
        raise InputError(f"fit_rolloff ({where}): fitted H = {H:.3g} is outside (0, 1]; the band has no "
                         "self-affine part above a plateau")
    return BrokenLine(q0=math.exp(b), C_plateau=math.exp(a), slope=s, hurst=float(H), rms_log_residual=float(resid))


def loglog_line(q, C, where: str, full: bool = False):
    """Least-squares line through (ln q, ln C): slope, intercept and the stderr of the slope, or with ``full``
    (stderr of the slope, rms residual)."""
    q = np.asarray(q, dtype=float)
    C = np.asarray(C, dtype=float)
    if q.size < 3:
        raise InputError(f"{where}: need >= 3 points for a power-law fit, got {q.size}")
    # ordinary least squares in closed form (what scipy.stats.linregress computes, without its 0.5 s import):
    # slope S_xy / S_xx, stderr of the slope sqrt(SS_res / (n - 2) / S_xx)
    x, y = np.log(q), np.log(C)
    dx, dy = x - x.mean(), y - y.mean()
    sxx = float(dx @ dx)
    if not sxx > 0.0:
        raise InputError(f"{where}: the wavevectors are all equal; a power law needs a range of q")
    slope = float(dx @ dy) / sxx
    intercept = float(y.mean() - slope * x.mean())
    r = y - (intercept + slope * x)
    stderr = math.sqrt(float(r @ r) / (x.size - 2) / sxx) if x.size > 2 else math.inf
    if full:
        return slope, intercept, (stderr, float(np.sqrt(np.mean(r**2))))
    return slope, intercept, stderr


def broken_power_law_fit(x: np.ndarray, y: np.ndarray, flat: str):
    """Least-squares fit of a line with a flat part: ``y = a - s*max(0, x-b)`` (flat below b) or
    ``y = a + s*min(0, x-b)`` (flat above b). Returns (a, s, b, rms residual); s > 0 means falling above
    the break for ``flat="below"`` and rising below it for ``flat="above"``."""
    from scipy import optimize
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)

    def design(b):
        ramp = -np.maximum(0.0, x - b) if flat == "below" else np.minimum(0.0, x - b)
        return np.column_stack([np.ones_like(x), ramp])

    def sse(b):
        A = design(b)
        coef, *_ = np.linalg.lstsq(A, y, rcond=None)
        r = y - A @ coef
        return float(r @ r)

    # Profile over the break: coarse scan, then bounded refinement around the best grid point.
    grid = np.linspace(x[0], x[-1], 200)
    costs = np.array([sse(b) for b in grid])
    i = int(np.argmin(costs))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    if hi > lo:
        res = optimize.minimize_scalar(sse, bounds=(lo, hi), method="bounded", options={"xatol": 1e-6})
        b = float(res.x) if res.fun <= costs[i] else float(grid[i])
    else:
        b = float(grid[i])
    coef, *_ = np.linalg.lstsq(design(b), y, rcond=None)
    return float(coef[0]), float(coef[1]), b, math.sqrt(sse(b) / x.size)
