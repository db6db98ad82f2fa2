r"""Cut-offs of measured PSDs: self-affine fit, roll-off, instrument reliability limit.

Conventions (``docs/conventions.md``): :math:`q_L = 2\pi/L` (longest wavelength measured), :math:`q_0` the roll-off
(PSD flat below), :math:`q_r` the reliability limit of the instrument, :math:`q_1` the short-distance
cut-off of the physics; :math:`q_1 > q_r` means the tail is extrapolated (see :meth:`surfaces.PSD.extrapolate`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from ._util import band, positive
from .errors import InputError
from .psd import PSD, SelfAffine

__all__ = ["SelfAffineFit", "RolloffFit", "fit_self_affine", "fit_rolloff", "reliability_limit"]

_PERSSON_2005 = "10.1088/0953-8984/17/1/R01"
_JACOBS_2017 = "10.1088/2051-672X/aa51f8"
_SANNER_2022 = "10.1016/j.apsadv.2021.100190"


@dataclass(frozen=True)
class SelfAffineFit:
    r"""Result of :func:`fit_self_affine`: :math:`C(q) = C_0 q^{-2(1+H)}` on ``[q_min, q_max]``.

    Attributes
    ----------
    hurst : float
        Hurst exponent H.
    hurst_stderr : float
        Standard error of H from the regression.
    C0 : float
        Prefactor of the isotropic 2D PSD, m^4 (rad/m)^(2+2H). For a 1D fit it is converted with the Gamma
        factor of a power law, :math:`C_0 = \Gamma(1+H)/(\sqrt\pi\Gamma(H+1/2))\,A` with :math:`C_{1D} = A q^{-(1+2H)}`.
    q_min, q_max : float
        Band of the fit, rad/m.
    n_points : int
        Number of table points in the band.
    rms_log_residual : float
        Rms of the natural-log residuals (0 for a perfect power law).
    kind : str
        ``"isotropic"`` (fitted on a 2D PSD) or ``"1d"`` (fitted on a line-scan PSD).
    """

    hurst: float
    hurst_stderr: float
    C0: float
    q_min: float
    q_max: float
    n_points: int
    rms_log_residual: float
    kind: str

    def C(self, q):
        """The fitted isotropic power law at ``q`` (rad/m), m^4."""
        return self.C0 * np.asarray(q, dtype=float) ** (-2.0 * (1.0 + self.hurst))

    def model(self, q0: float | None = None, q1: float | None = None, qL: float | None = None) -> SelfAffine:
        """The fit as a :class:`surfaces.SelfAffine` (default cut-offs: the fitted band)."""
        return SelfAffine(min(self.hurst, 0.999999), self.q_min if q0 is None else q0,
                          self.q_max if q1 is None else q1, C0=self.C0, qL=qL)


@dataclass(frozen=True)
class RolloffFit:
    r"""Result of :func:`fit_rolloff`: flat below the roll-off, self-affine above.

    .. math:: C(q) = C_p \;(q < q_0), \qquad C(q) = C_p (q/q_0)^{-2(1+H)} \;(q \ge q_0)

    Attributes
    ----------
    q0 : float
        Roll-off wavevector, rad/m.
    C_plateau : float
        Plateau value :math:`C_p`, m^4 (m^3 for a 1D fit).
    hurst : float
        Hurst exponent of the power-law part.
    C0 : float
        Prefactor :math:`C_p q_0^{2(1+H)}` of the isotropic power law, m^4 (rad/m)^(2+2H).
    rms_log_residual : float
        Rms of the natural-log residuals.
    kind : str
        ``"isotropic"`` or ``"1d"``.
    """

    q0: float
    C_plateau: float
    hurst: float
    C0: float
    rms_log_residual: float
    kind: str

    def model(self, q1: float, qL: float | None = None) -> SelfAffine:
        """The fit as a :class:`surfaces.SelfAffine` with roll-off ``q0`` and cut-off ``q1``."""
        return SelfAffine(min(self.hurst, 0.999999), self.q0, q1, C0=self.C0, qL=qL)


@doi(_PERSSON_2005, _JACOBS_2017)
def fit_self_affine(psd, q_min: float | None = None, q_max: float | None = None) -> SelfAffineFit:
    r"""Fit a self-affine power law to a PSD on a band (least squares in log-log).

    On a 2D isotropic PSD the slope is :math:`-2(1+H)`; on a line-scan PSD (:class:`surfaces.PSD1D`)
    it is :math:`-(1+2H)` (Persson et al. 2005; Jacobs et al. 2017, Sec. 2).

    Parameters
    ----------
    psd : surfaces.PSD, surfaces.SelfAffine or surfaces.PSD1D
    q_min, q_max : float, optional
        Band, rad/m; default the whole table (for a PSD1D: up to its reliability limit ``q_r``).

    Returns
    -------
    SelfAffineFit
    """
    from .spectra import PSD1D, gamma_factor

    q, C, kind = _table(psd)
    if kind == "1d" and q_max is None and psd.q_r is not None:
        q_max = psd.q_r
    m = band(q, q_min, q_max, "fit_self_affine")
    slope, intercept, (stderr, resid) = _linear_loglog_fit(q[m], C[m], where=_name(psd), full=True)
    if kind == "1d":
        H = (-slope - 1.0) / 2.0
        H_err = stderr / 2.0
    else:
        H = -slope / 2.0 - 1.0
        H_err = stderr / 2.0
    if not (np.isfinite(H) and 0.0 < H <= 1.05):
        raise InputError(f"fit_self_affine ({_name(psd)}): fitted H = {H:.3g} on [{q[m][0]:g}, {q[m][-1]:g}] rad/m "
                         "is outside (0, 1]: the band is not self-affine; choose another band")
    A = math.exp(intercept)
    C0 = gamma_factor(min(H, 1.0)) * A if isinstance(psd, PSD1D) else A
    return SelfAffineFit(hurst=float(H), hurst_stderr=float(H_err), C0=float(C0), q_min=float(q[m][0]),
                         q_max=float(q[m][-1]), n_points=int(m.sum()), rms_log_residual=float(resid), kind=kind)


@doi(_PERSSON_2005)
def fit_rolloff(psd, q_min: float | None = None, q_max: float | None = None) -> RolloffFit:
    r"""Fit the roll-off model (flat below :math:`q_0`, power law above) to a PSD, in log-log.

    For each trial :math:`\ln q_0` the model is linear in :math:`(\ln C_p, \text{slope})` and solved by least
    squares; :math:`\ln q_0` is scanned on a fine grid and refined with :func:`scipy.optimize.minimize_scalar`.

    Parameters
    ----------
    psd : surfaces.PSD, surfaces.SelfAffine or surfaces.PSD1D
    q_min, q_max : float, optional
        Band of the fit, rad/m (default: the table; for a PSD1D up to ``q_r``).

    Returns
    -------
    RolloffFit
        For a PSD1D, ``hurst`` follows from the 1D slope :math:`-(1+2H)` and ``C0`` is converted to the
        isotropic prefactor with the Gamma factor; ``C_plateau`` stays the 1D plateau.
    """
    from .spectra import gamma_factor

    q, C, kind = _table(psd)
    if kind == "1d" and q_max is None and psd.q_r is not None:
        q_max = psd.q_r
    m = band(q, q_min, q_max, "fit_rolloff")
    if m.sum() < 5:
        raise InputError(f"fit_rolloff ({_name(psd)}): need >= 5 points in the band, got {int(m.sum())}")
    x, y = np.log(q[m]), np.log(C[m])
    a, s, b, resid = broken_power_law_fit(x, y, flat="below")
    H = (s - 1.0) / 2.0 if kind == "1d" else s / 2.0 - 1.0
    if not (np.isfinite(H) and 0.0 < H <= 1.05):
        raise InputError(f"fit_rolloff ({_name(psd)}): fitted H = {H:.3g} is outside (0, 1]; the band has no "
                         "self-affine part above a plateau")
    q0 = math.exp(b)
    Cp = math.exp(a)
    C0 = Cp * q0 ** s if kind != "1d" else gamma_factor(min(H, 1.0)) * Cp * q0 ** s
    return RolloffFit(q0=q0, C_plateau=Cp, hurst=float(H), C0=float(C0), rms_log_residual=float(resid), kind=kind)


@doi(_SANNER_2022)
def reliability_limit(*, dx: float | None = None, lateral_resolution: float | None = None,
                      tip_radius: float | None = None, profiles=None, safety_factor: float = 0.5) -> float:
    r"""Reliability limit :math:`q_r` (rad/m) of an instrument: the smallest of the applicable limits.

    * sampling: Nyquist, :math:`q_r = \pi/\Delta x`;
    * lateral resolution d (laser spot, pixel of the optics): :math:`q_r = \pi/d`;
    * stylus tip radius R: below a length scale :math:`\ell` the tip cannot follow the valleys once the
      most negative scale-dependent curvature of the measured profile,
      :math:`\kappa(\ell) = \min_x [h(x+\ell) - 2h(x) + h(x-\ell)]/\ell^2`, reaches :math:`-s/R`
      (Sanner et al., Scale-dependent roughness parameters for topography analysis, Appl. Surf. Sci. Adv. 7,
      100190 (2022); safety factor s = 1/2 from their simulations). Then :math:`q_r = 2\pi/\ell_c`.
      Needs ``profiles`` (a ProfileSet).

    Parameters
    ----------
    dx : float, optional
        Sample spacing, m.
    lateral_resolution : float, optional
        Lateral resolution of the instrument, m.
    tip_radius : float, optional
        Stylus tip radius, m (needs ``profiles``).
    profiles : surfaces.ProfileSet, optional
        Measured profiles for the tip criterion (dropouts filled, uniform spacing).
    safety_factor : float
        s in the curvature criterion.

    Returns
    -------
    float
        :math:`q_r` in rad/m (``inf`` when the tip never limits and nothing else is given).
    """
    limits = []
    if dx is not None:
        limits.append(math.pi / positive(dx, "dx"))
    if lateral_resolution is not None:
        limits.append(math.pi / positive(lateral_resolution, "lateral_resolution"))
    if tip_radius is not None:
        R = positive(tip_radius, "tip_radius")
        if profiles is None:
            raise InputError("tip_radius: the tip criterion needs the measured profiles (profiles=)")
        limits.append(_tip_limit(profiles, R, positive(safety_factor, "safety_factor")))
    if not limits:
        raise InputError("reliability_limit: give at least one of dx=, lateral_resolution=, tip_radius= (m)")
    return float(min(limits))


def with_estimated_rolloff(psd: PSD) -> PSD:
    """``psd`` with ``q_rolloff`` set from :func:`fit_rolloff` when the fit finds a plateau inside the table
    (the break lies past the first two points); unchanged otherwise. Used to label measured PSDs."""
    if psd.q_rolloff is not None or psd.q.size < 8:
        return psd
    try:
        fit = fit_rolloff(psd)
    except InputError:
        return psd
    if not psd.q[1] < fit.q0 < psd.q[-1] / 2:
        return psd
    return PSD(psd.q, psd.C_values, q_r=psd.q_r, extrapolated=psd.extrapolated, source=psd.source, qL=psd.qL,
               q_rolloff=fit.q0, hurst=psd.hurst)


# ---------------------------------------------------------------------- helpers (also used by texture.py)


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


def _linear_loglog_fit(q, C, where: str, full: bool = False):
    """Least-squares line through (ln q, ln C): slope, intercept (and stderr of slope, rms residual)."""
    q = np.asarray(q, dtype=float)
    C = np.asarray(C, dtype=float)
    if q.size < 3:
        raise InputError(f"{where}: need >= 3 points for a power-law fit, got {q.size}")
    from scipy import stats  # imported here: scipy.stats costs about 0.5 s at start-up

    res = stats.linregress(np.log(q), np.log(C))
    if full:
        r = np.log(C) - (res.intercept + res.slope * np.log(q))
        return res.slope, res.intercept, (res.stderr, float(np.sqrt(np.mean(r**2))))
    return res.slope, res.intercept, res.stderr


def _table(psd):
    """(q, C, kind) of a PSD-like object."""
    from .spectra import PSD1D

    if isinstance(psd, PSD1D):
        return psd.q, psd.C_values, "1d"
    if isinstance(psd, SelfAffine):
        t = psd.tabulate()
        return t.q, t.C_values, "isotropic"
    if isinstance(psd, PSD):
        return psd.q, psd.C_values, "isotropic"
    raise InputError(f"psd: expected a surfaces.PSD, SelfAffine or PSD1D, got {type(psd).__name__}")


def _name(psd) -> str:
    return getattr(psd, "source", "") or type(psd).__name__


def _tip_limit(profiles, R: float, s: float) -> float:
    """q_r = 2 pi / l_c, l_c the smallest stencil length at which min curvature >= -s/R for all profiles."""
    target = -s / R
    worst = 0.0  # the largest cut-off length over the profiles limits the set
    for p in profiles:
        z = p.z
        if np.isnan(z).any():
            raise InputError(f"{p.where}: fill dropouts before the tip-radius criterion (fill_dropouts())")
        dx = p.dx
        n_max = max(1, (z.size - 1) // 2)

        def min_curv(m: int) -> float:
            d2 = z[2 * m:] - 2.0 * z[m:-m] + z[:-2 * m]
            return float(d2.min()) / (m * dx) ** 2

        if min_curv(1) >= target:
            l_c = dx  # reliable down to the sampling
        else:
            lo, hi = 1, 2
            while hi <= n_max and min_curv(hi) < target:
                lo, hi = hi, 2 * hi
            if hi > n_max:
                raise InputError(f"{p.where}: the tip radius {R:g} m limits every scale of the profile")
            while hi - lo > 1:  # bisection on the integer stencil length
                mid = (lo + hi) // 2
                lo, hi = (mid, hi) if min_curv(mid) < target else (lo, mid)
            l_c = hi * dx
        worst = max(worst, l_c)
    return 2.0 * math.pi / worst

