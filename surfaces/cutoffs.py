r"""Cut-offs of measured PSDs: self-affine fit, roll-off, instrument reliability limit.

Conventions (``docs/conventions.md``): :math:`q_L = 2\pi/L` (longest wavelength measured), :math:`q_0` the roll-off
(PSD flat below), :math:`q_r` the reliability limit of the instrument, :math:`q_1` the short-distance
cut-off of the physics; :math:`q_1 > q_r` means the tail is extrapolated (see :meth:`surfaces.PSD.extrapolate`).

The fits take any PSD object (:class:`surfaces.PSD`, :class:`surfaces.SelfAffine`, :class:`surfaces.PSD1D`); the
fits of a bare table and their results (:class:`SelfAffineFit`, :class:`RolloffFit`, importable from here) are
in :mod:`surfaces.psdfit`, the log-log line fits in :mod:`surfaces.powerlaw`.
"""

from __future__ import annotations

import math

import numpy as np

from frictioncite import doi

from ._util import positive
from .errors import InputError
from .powerlaw import broken_power_law_fit
from .psd import PSD, SelfAffine
from .psdfit import RolloffFit, SelfAffineFit, fit_table_rolloff, fit_table_self_affine, with_estimated_rolloff
from .spectra import PSD1D

__all__ = ["SelfAffineFit", "RolloffFit", "fit_self_affine", "fit_rolloff", "reliability_limit",
           "with_estimated_rolloff", "broken_power_law_fit"]

_PERSSON_2005 = "10.1088/0953-8984/17/1/R01"
_JACOBS_2017 = "10.1088/2051-672X/aa51f8"
_SANNER_2022 = "10.1016/j.apsadv.2021.100190"


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
    q, C, kind = _table(psd)
    if kind == "1d" and q_max is None and psd.q_r is not None:
        q_max = psd.q_r
    return fit_table_self_affine(q, C, kind, q_min, q_max, where=_name(psd))


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

    Raises
    ------
    InputError
        Fewer than five points in the band, fewer than three above the fitted break (one or two are fitted exactly
        by any slope, so they give no exponent), or a fitted H outside (0, 1].
    """
    q, C, kind = _table(psd)
    if kind == "1d" and q_max is None and psd.q_r is not None:
        q_max = psd.q_r
    return fit_table_rolloff(q, C, kind, q_min, q_max, where=_name(psd))


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


# ---------------------------------------------------------------------- helpers


def _table(psd):
    """(q, C, kind) of a PSD-like object."""
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
