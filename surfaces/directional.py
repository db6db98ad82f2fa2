r"""Parallel line scans along and across a direction (the ridges of a brushed, tined or polished surface) read
into the two 1-D PSDs, their anisotropy, and the 2-D models they support.

On an anisotropic surface a line scan sees the 1-D PSD of its own direction. Scans across the ridges give
:math:`C_{1D}^\perp`, scans along them :math:`C_{1D}^\parallel`; the ratio of their rms slopes measures the
anisotropy. Two 2-D PSDs follow from them (Persson et al., J. Phys.: Condens. Matter 17, R1 (2005), for the two
limits of a 1-D scan): the unidirectional limit :math:`C_{1D}^\perp(q_\perp)\delta(q_\parallel)` when the scans
along the ridges are nearly flat, and a stretched isotropic surface (Carbone, Lorenz, Persson & Wohlers, Eur.
Phys. J. E 29, 275 (2009)) whose base is the isotropic surface of the scans across.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from frictioncite import doi

from ._util import positive
from .anisotropy import Stretched, Unidirectional, angle_in_degrees
from .errors import InputError
from .profiles import ProfileSet
from .spectra import PSD1D

__all__ = ["DirectionalPSDs", "directional_psds"]


@doi("10.1088/0953-8984/17/1/R01")
def directional_psds(across, along, *, angle_deg: float = 0.0, **psd_options) -> "DirectionalPSDs":
    r"""The 1-D PSDs of scans across and along the ridges, and their anisotropy.

    Parameters
    ----------
    across : surfaces.ProfileSet or surfaces.PSD1D
        Parallel scans across the ridges (along ``angle_deg + 90``), e.g. ``surfaces.read_profiles(...)``.
    along : surfaces.ProfileSet or surfaces.PSD1D
        Parallel scans along the ridges (along ``angle_deg``).
    angle_deg : float
        Direction of the ridges (of the scans ``along``), degrees from the x axis of the surface.
    **psd_options
        Passed to :meth:`surfaces.ProfileSet.psd` (``window``, ``detrend``, ``n_per_decade``...).

    Returns
    -------
    DirectionalPSDs
    """
    angle = float(angle_in_degrees(angle_deg, "angle_deg", stacklevel=3)) % 180.0
    return DirectionalPSDs(across=_psd1d(across, "across", psd_options), along=_psd1d(along, "along", psd_options),
                           angle_deg=angle)


@dataclass(frozen=True, eq=False)
class DirectionalPSDs:
    """The two 1-D PSDs of :func:`directional_psds`.

    Attributes
    ----------
    across, along : surfaces.PSD1D
        Two-sided 1-D PSDs of the scans across and along the ridges, m^3.
    angle_deg : float
        Direction of the ridges, degrees in [0, 180).
    """

    across: PSD1D
    along: PSD1D
    angle_deg: float

    def band(self) -> tuple[float, float]:
        """The wavevectors both PSDs cover (and trust: below both reliability limits), rad/m."""
        lo = max(self.across.q[0], self.along.q[0])
        hi = min(_top(self.across), _top(self.along))
        if not hi > lo:
            raise InputError(f"directional_psds: the scans across ({self.across.q[0]:.4g}-{_top(self.across):.4g} "
                             f"rad/m) and along ({self.along.q[0]:.4g}-{_top(self.along):.4g} rad/m) the ridges "
                             "share no band of wavevectors")
        return float(lo), float(hi)

    def slope_ratio(self, q_min: float | None = None, q_max: float | None = None) -> float:
        r"""Rms slope across over rms slope along the ridges, :math:`\sqrt{\int q^2 C^\perp_{1D} / \int q^2
        C^\parallel_{1D}}` over the common band (default :meth:`band`): 1 for an isotropic surface, the stretch
        factor of a stretched one, large for a polished one."""
        lo, hi = self.band()
        lo = lo if q_min is None else max(lo, positive(q_min, "q_min"))
        hi = hi if q_max is None else min(hi, positive(q_max, "q_max"))
        return math.sqrt(self.across.moment(2, lo, hi) / self.along.moment(2, lo, hi))

    def unidirectional(self) -> Unidirectional:
        """The unidirectional limit: the 1-D PSD across the ridges as :math:`C_{1D}(q_\\perp)\\delta(q_\\parallel)`
        (wavevectors along ``angle_deg + 90``)."""
        return Unidirectional(self.across, (self.angle_deg + 90.0) % 180.0)

    def stretched(self, ratio: float | None = None, **isotropic_options) -> Stretched:
        """A stretched surface: the isotropic surface of the scans across (:meth:`surfaces.PSD1D.to_isotropic`,
        options passed on) stretched along the ridges by ``ratio`` (default :meth:`slope_ratio`)."""
        ratio = self.slope_ratio() if ratio is None else positive(ratio, "ratio")
        if ratio < 1.0:
            raise InputError(f"ratio: the scans along the ridges are rougher than those across them (slope ratio "
                             f"{ratio:.3g} < 1): swap across and along, or give angle_deg + 90")
        return Stretched(self.across.to_isotropic(**isotropic_options), ratio, self.angle_deg)


def _psd1d(obj, name: str, options: dict) -> PSD1D:
    if isinstance(obj, PSD1D):
        return obj
    if isinstance(obj, ProfileSet):
        return obj.psd(**options)
    raise InputError(f"{name}: expected a surfaces.ProfileSet (e.g. surfaces.read_profiles(path)) or a "
                     f"surfaces.PSD1D, got {type(obj).__name__}")


def _top(p: PSD1D) -> float:
    return float(min(p.q[-1], p.q_r)) if p.q_r is not None else float(p.q[-1])
