r"""Anisotropic surfaces: 2-D PSDs :math:`C(q_x, q_y)`, their principal directions, the unidirectional limit
and the stretched self-affine surface.

Persson's convention without the angular average (``docs/conventions.md``):

.. math:: C(\mathbf q) = \frac{1}{(2\pi)^2}\int d^2x\,\langle h(\mathbf x)h(0)\rangle e^{-i\mathbf q\cdot\mathbf x},
          \qquad h_{rms}^2 = \int d^2q\, C(\mathbf q),

written in polar form :math:`C(q, \phi)` with :math:`\mathbf q = q(\cos\phi, \sin\phi)` and :math:`\phi` measured
from the x axis; real heights give :math:`C(q, \phi + \pi) = C(q, \phi)`. Every object here is also an isotropic
PSD: ``C(q)`` returns the angular mean

.. math:: \bar C(q) = \frac{1}{2\pi}\int_0^{2\pi} C(q, \phi)\, d\phi ,

which has the same :math:`h_{rms}`, rms slope and contact area at rest as the anisotropic surface (Persson's
:math:`G(q)` of a surface pressed without sliding depends on :math:`\bar C` alone), so ``hrms()``, ``rms_slope()``
and ``q_range`` mean what they mean for :class:`surfaces.PSD`. The direction enters through
``angular_shape(q, phi)`` :math:`= C(q, \phi) / \bar C(q)` (mean 1 over the angles), which the friction engine
integrates against the modulus at :math:`q v \cos(\phi - \theta)` for a sliding direction :math:`\theta`.

Three kinds:

* :class:`Unidirectional` (:func:`unidirectional`): the polished or brushed limit, all wavevectors along one
  direction, :math:`C(\mathbf q) = C_{1D}(q_x)\,\delta(q_y)` rotated;
* :class:`Stretched` (:func:`stretched`): an isotropic surface stretched along one axis (the construction of
  Carbone, Lorenz, Persson & Wohlers, Eur. Phys. J. E 29, 275 (2009));
* :class:`surfaces.PSD2D` (:meth:`surfaces.HeightMap.psd2d`): the measured 2-D PSD of a height map.

Angles are in degrees from the x axis of the surface (``angle_deg``), as the sliding direction of the friction
engine (``direction_deg``).
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass

import numpy as np

import frictionerrors
from frictioncite import doi

from ._util import positive
from .errors import InputError
from .psd import PSD, Cutoffs, SelfAffine

__all__ = ["AnisotropicPSD", "Anisotropy", "Stretched", "Unidirectional", "stretched", "unidirectional",
           "angle_in_degrees"]

_CARBONE_2009 = "carbone:epje-29-275-2009"
_PERSSON_2005 = "10.1088/0953-8984/17/1/R01"
#: Gauss-Legendre points per panel of the angular and radial quadratures of this module, and the rule.
_GL_N = 8
_GL_X, _GL_W = np.polynomial.legendre.leggauss(_GL_N)


def stretched(psd, ratio: float, angle_deg: float = 0.0) -> "Stretched":
    r"""An anisotropic surface made from the isotropic ``psd`` by stretching it ``ratio`` times along
    ``angle_deg``: the ridges (the long correlation) run along ``angle_deg``.

    .. math:: h(\mathbf x) = h_{iso}\!\left(\frac{\mathbf x\cdot\mathbf u}{\zeta}, \mathbf x\cdot\mathbf n\right),
              \qquad C(q, \phi) = \zeta\, C_{iso}\!\left(q\sqrt{\zeta^2\cos^2(\phi-\alpha) +
              \sin^2(\phi-\alpha)}\right)

    with :math:`\zeta` = ``ratio``, :math:`\alpha` = ``angle_deg``, :math:`\mathbf u` the unit vector along
    :math:`\alpha` and :math:`\mathbf n` normal to it (Carbone, Lorenz, Persson & Wohlers, Eur. Phys. J. E 29, 275
    (2009)). ``ratio = 1`` is the isotropic surface itself. Without cut-offs the rms slope along the ridges is
    ``ratio`` times smaller than across them; inside the common cut-offs kept here (see Notes) the ratio of the
    slopes is somewhat smaller (2.7 for ``ratio = 3`` over three decades of a surface with H = 0.8).

    Parameters
    ----------
    psd : surfaces.SelfAffine or surfaces.PSD (or any isotropic PSD with ``C(q)`` and ``q_range``)
        The isotropic surface.
    ratio : float
        Stretch factor :math:`\zeta \ge 1` (for a ratio below 1 stretch the perpendicular axis: ``1/ratio`` and
        ``angle_deg + 90``).
    angle_deg : float
        Direction of the ridges (the stretched axis), degrees from the x axis.

    Returns
    -------
    Stretched

    Notes
    -----
    The support keeps the isotropic surface's :math:`q_0 \le |\mathbf q| \le q_1`: the cut-offs are those of the
    measurement and of the physics (system size, smallest scale in contact), the same in every direction. Inside
    it the stretched PSD reads the isotropic one at :math:`q s(\phi)` with :math:`1 \le s \le \zeta`, i.e. up to
    :math:`\zeta q_1`: a :class:`surfaces.SelfAffine` continues its power law there; a table is continued with
    the power law of its last interval (or its ``hurst``) and the result says ``extrapolated`` past
    :math:`q_1/\zeta`.

    Examples
    --------
    >>> import surfaces
    >>> base = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=10e-6)
    >>> s = surfaces.stretched(base, ratio=3.0, angle_deg=0.0)
    >>> a = s.anisotropy()
    >>> print(f"ridges along {a.ridge_angle_deg:.0f} deg, slope ratio {a.slope_ratio:.2f}")
    ridges along 0 deg, slope ratio 2.71
    """
    return Stretched(psd, ratio, angle_deg)


def unidirectional(psd1d, angle_deg: float = 0.0) -> "Unidirectional":
    r"""The unidirectional limit of a polished, brushed or tined surface: every wavevector along ``angle_deg``,

    .. math:: C(\mathbf q) = C_{1D}(q_\parallel)\,\delta(q_\perp), \qquad
              C(q, \phi) = \frac{C_{1D}(q)}{q}\,[\delta(\phi - \alpha) + \delta(\phi - \alpha - \pi)],

    with :math:`q_\parallel` along :math:`\alpha` = ``angle_deg`` (``angle_deg = 0``: :math:`C_{1D}(q_x)\delta(q_y)`,
    heights varying along x, ridges along y), in Persson's convention (:math:`h_{rms}^2 = \int C_{1D}\,dq`
    over both signs of q). The angular mean is :math:`\bar C(q) = C_{1D}(q)/(\pi q)`.

    Parameters
    ----------
    psd1d : surfaces.PSD1D (or any object with ``C(q)`` in m^3 and ``q_range``)
        Two-sided 1-D PSD of profiles scanned across the ridges (e.g. ``ProfileSet.psd()``).
    angle_deg : float
        Direction of the wavevectors, i.e. of the scans across the ridges, degrees from the x axis; the ridges
        run along ``angle_deg + 90``.

    Returns
    -------
    Unidirectional

    Examples
    --------
    >>> import numpy as np, surfaces
    >>> z = np.cumsum(np.random.default_rng(1).normal(size=(4, 1024)), axis=1) * 1e-6
    >>> s = surfaces.unidirectional(surfaces.profiles_from_array(z, dx=1e-5).psd(), angle_deg=90.0)
    >>> s.anisotropy().ridge_angle_deg, s.anisotropy().slope_ratio
    (0.0, inf)
    """
    return Unidirectional(psd1d, angle_deg)


def angle_in_degrees(value, name: str, *, strict: bool = False, stacklevel: int = 3) -> np.ndarray:
    r"""Check an angle (or array of angles) that should be in degrees; returns it as a float array.

    Angles typed in radians are caught: when every value is within :math:`|x| \le 2\pi` and at least one is not a
    whole number of degrees (1.5708 is 90 degrees typed as pi/2), that is an InputError with ``strict`` (case
    files, command line) and a :class:`frictionerrors.UnitWarning` otherwise (scripts may mean half a degree).

    Raises
    ------
    InputError
        A value that is not a finite number, or (``strict``) one that looks like radians.
    """
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected an angle in degrees (a number or an array of numbers), got {value!r}") \
            from None
    if a.size == 0:
        raise InputError(f"{name}: expected at least one angle in degrees")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name}: NaN or infinite angle at index {int(np.argmax(~np.isfinite(a.ravel())))}")
    flat = a.ravel()
    if np.all(np.abs(flat) <= 2.0 * math.pi + 1e-9) and np.any(np.abs(flat - np.round(flat)) > 1e-9):
        x = flat[np.argmax(np.abs(flat - np.round(flat)) > 1e-9)]
        msg = (f"{name}: {x:g} looks like an angle in radians ({math.degrees(x):.4g} degrees); the angle is in "
               f"degrees (the name says so): give {math.degrees(x):.4g}")
        if strict:
            raise InputError(msg)
        warnings.warn(msg, frictionerrors.UnitWarning, stacklevel=stacklevel)
    return a


# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Anisotropy:
    r"""Principal directions and anisotropy of a surface, from the slope tensor
    :math:`M = \int d^2q\, \mathbf q\mathbf q^T C(\mathbf q)` (:math:`\langle \partial_a h\, \partial_b h\rangle`).

    Attributes
    ----------
    steepest_angle_deg : float
        Direction of the largest rms slope (across the ridges), degrees in [0, 180).
    ridge_angle_deg : float
        Direction of the smallest rms slope (along the ridges), ``steepest_angle_deg + 90`` modulo 180.
    rms_slope_steepest, rms_slope_ridge : float
        Rms slopes along those two directions (their squares add up to the 2-D rms slope squared).
    slope_ratio : float
        ``rms_slope_steepest / rms_slope_ridge`` >= 1: 1 for an isotropic surface, infinite in the unidirectional
        limit; for a surface stretched without cut-offs the stretch ratio, which is also the ratio of its
        correlation lengths along and across the ridges.
    q_min, q_max : float
        Band of wavevectors the tensor was integrated over, rad/m.
    """

    steepest_angle_deg: float
    ridge_angle_deg: float
    rms_slope_steepest: float
    rms_slope_ridge: float
    slope_ratio: float
    q_min: float
    q_max: float

    @classmethod
    def from_tensor(cls, M: np.ndarray, q_min: float, q_max: float) -> "Anisotropy":
        """The principal directions and slopes of the symmetric 2 x 2 slope tensor ``M``."""
        vals, vecs = np.linalg.eigh(np.asarray(M, dtype=float))
        lo, hi = max(float(vals[0]), 0.0), max(float(vals[1]), 0.0)
        steep = math.degrees(math.atan2(vecs[1, 1], vecs[0, 1])) % 180.0
        if hi == 0.0:
            raise InputError("anisotropy: the surface has no slope in the band (C = 0)")
        ratio = math.inf if lo <= 1e-24 * hi else math.sqrt(hi / lo)
        steep = _tidy_angle(steep)
        return cls(steepest_angle_deg=steep, ridge_angle_deg=_tidy_angle((steep + 90.0) % 180.0),
                   rms_slope_steepest=math.sqrt(hi), rms_slope_ridge=math.sqrt(lo), slope_ratio=ratio,
                   q_min=float(q_min), q_max=float(q_max))


class AnisotropicPSD:
    """Base of the anisotropic 2-D PSDs: the isotropic interface of their angular mean plus the angular shape.

    A subclass provides ``q_range``, ``C(q)`` (the angular mean, m^4), ``C_polar(q, phi)`` (m^4, ``phi`` in
    radians from the x axis) and ``source``; :class:`Unidirectional` replaces ``C_polar`` (a distribution) by
    ``wave_angle_deg``.
    """

    #: Read by the friction engine: the direction of sliding matters for this surface.
    is_anisotropic = True
    q_r = None
    extrapolated = False
    qL = None
    q_rolloff = None
    hurst = None

    # ----------------------------------------------------------------------------------------------- 2-D
    def C2d(self, qx, qy) -> np.ndarray:
        r""":math:`C(q_x, q_y)`, m^4, at wavevectors (rad/m) broadcast together; zero outside the support."""
        qx, qy = np.broadcast_arrays(np.asarray(qx, dtype=float), np.asarray(qy, dtype=float))
        return self.C_polar(np.hypot(qx, qy), np.arctan2(qy, qx))

    def angular_shape(self, q, phi) -> np.ndarray:
        r"""The angular shape :math:`w(q, \phi) = C(q, \phi)/\bar C(q)` (mean 1 over the angles).

        Parameters
        ----------
        q : array_like, shape (n,)
            Wavevectors, rad/m; held at the ends of the support beyond them (so that an effect extending the
            angular mean past the support keeps the surface's own angular distribution there).
        phi : array_like, shape (n, ...)
            Angles, radians from the x axis, one row (of any shape) per wavevector.

        Returns
        -------
        ndarray
            The shape of ``phi``; 1 where :math:`\bar C = 0`.
        """
        q = np.atleast_1d(np.asarray(q, dtype=float))
        phi = np.asarray(phi, dtype=float)
        if phi.shape[:1] != q.shape:
            raise InputError(f"angular_shape: expected phi with one row per wavevector ({q.size}), got shape "
                             f"{phi.shape}")
        lo, hi = (float(x) for x in self.q_range)
        qc = np.clip(q, lo, hi)
        Cm = np.asarray(self.C(qc), dtype=float)
        qb = qc.reshape(qc.shape + (1,) * (phi.ndim - 1))
        Cb = Cm.reshape(qb.shape)
        Cp = self.C_polar(np.broadcast_to(qb, phi.shape), phi)
        return np.where(Cb > 0, Cp / np.where(Cb > 0, Cb, 1.0), 1.0)

    #: Angular width, radians, of the narrowest feature of the angular shape (the friction engine's first
    #: angular resolution); None: unknown.
    angular_width = None
    #: Whether the angular shape may have kinks (the friction engine then takes its angular interpolation as
    #: second order in its error estimate); True unless a subclass knows its shape is smooth.
    angular_kinks = True

    # ----------------------------------------------------------------------------------------------- moments
    def moment(self, n: int) -> float:
        r"""Spectral moment :math:`2\pi\int q^n \bar C(q)\,dq` over the support (Gauss-Legendre between the
        breakpoints; :math:`h_{rms}^2` for n = 1, the rms slope squared for n = 3)."""
        q, w = _radial_rule(self)
        return 2.0 * math.pi * float(np.sum(w * q**n * np.asarray(self.C(q), dtype=float)))

    def hrms(self) -> float:
        """RMS height, m."""
        return math.sqrt(self.moment(1))

    def rms_slope(self) -> float:
        r"""RMS slope :math:`\sqrt{\langle|\nabla h|^2\rangle}` (both directions together)."""
        return math.sqrt(self.moment(3))

    def breakpoints(self) -> np.ndarray:
        """Wavevectors (rad/m) where the angular mean may have a kink (none by default)."""
        return np.empty(0)

    @property
    def cutoffs(self) -> Cutoffs:
        """The cut-offs (qL, roll-off, reliability limit q_r, q1 = end of the support)."""
        return Cutoffs(qL=self.qL, q0=self.q_rolloff, q_r=self.q_r, q1=float(self.q_range[1]),
                       extrapolated=bool(self.extrapolated))

    # ----------------------------------------------------------------------------------------------- slopes
    def slope_tensor(self, q_min: float | None = None, q_max: float | None = None) -> np.ndarray:
        r"""The slope tensor :math:`M_{ab} = \int d^2q\, q_a q_b C(\mathbf q) = \langle\partial_a h\,\partial_b h\rangle`
        over :math:`q_{min} \le |\mathbf q| \le q_{max}` (default the support), a symmetric 2 x 2 array."""
        q, w = _radial_rule(self, q_min, q_max)
        # the trapezoid rule is spectrally accurate for the periodic shape once its step is well below the width
        n_phi = int(min(8192, max(360, math.ceil(8.0 * math.pi / (self.angular_width or 0.1)))))
        phi = (np.arange(n_phi) + 0.5) * (math.pi / n_phi)
        shape = self.angular_shape(q, np.broadcast_to(phi, (q.size, n_phi)))
        # int_0^{2 pi} dphi (n n^T) w = 2 (pi / n_phi) sum over [0, pi) (period pi, spectrally accurate)
        c, s = np.cos(phi), np.sin(phi)
        ang = (2.0 * math.pi / n_phi) * np.stack([shape @ (c * c), shape @ (c * s), shape @ (s * s)], axis=1)
        rad = w * q**3 * np.asarray(self.C(q), dtype=float)
        xx, xy, yy = rad @ ang
        return np.array([[xx, xy], [xy, yy]])

    def anisotropy(self, q_min: float | None = None, q_max: float | None = None) -> Anisotropy:
        """Principal directions, rms slopes along them and their ratio (:class:`Anisotropy`) over the band."""
        lo, hi = _band(self, q_min, q_max)
        return Anisotropy.from_tensor(self.slope_tensor(lo, hi), lo, hi)

    def with_cutoff(self, q0: float | None = None, q1: float | None = None) -> "AnisotropicPSD":
        """The surface on the band ``[q0, q1]`` of its support (the angular mean cut, the angular shape kept)."""
        return Reshaped(self.to_isotropic().with_cutoff(q0=q0, q1=q1), self)

    def extrapolate(self, q1: float, hurst: float | None = None, **options) -> "AnisotropicPSD":
        """The angular mean's self-affine tail continued to ``q1`` (:meth:`surfaces.PSD.extrapolate`, flagged as
        extrapolated), the angular shape held at its values at the end of the support."""
        return Reshaped(self.to_isotropic().extrapolate(q1, hurst=hurst, **options), self)

    def to_isotropic(self) -> PSD:
        """The angular mean as a :class:`surfaces.PSD` table (64 points per decade plus the breakpoints): the
        isotropic surface of the same rms height, rms slope and contact area at rest."""
        lo, hi = (float(x) for x in self.q_range)
        q = np.geomspace(lo, hi, max(2, int(math.ceil(64 * math.log10(hi / lo))) + 1))
        b = self.breakpoints()
        q = np.union1d(q, b[(b > lo) & (b < hi)])
        C = np.asarray(self.C(q), dtype=float)
        keep = C > 0
        return PSD(q[keep], C[keep], q_r=self.q_r, extrapolated=bool(self.extrapolated),
                   source=f"angular mean of {self.source}", qL=self.qL, q_rolloff=self.q_rolloff)


# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Reshaped(AnisotropicPSD):
    """An anisotropic surface whose angular mean is ``radial`` (an isotropic PSD) and whose angular shape is that
    of ``shape`` (held at the ends of its support beyond them): what cutting or extending an anisotropic PSD
    gives."""

    radial: object
    shape: object

    def __repr__(self) -> str:
        return f"Reshaped(radial={self.radial!r}, shape of {type(self.shape).__name__})"

    @property
    def q_range(self) -> tuple[float, float]:
        """Support (q_start, q_end), rad/m: that of ``radial``."""
        return tuple(float(x) for x in self.radial.q_range)

    @property
    def source(self) -> str:
        """Origin, for messages and reports: that of ``radial``, else that of ``shape``."""
        return getattr(self.radial, "source", "") or getattr(self.shape, "source", "")

    q_r = property(lambda self: getattr(self.radial, "q_r", None))
    extrapolated = property(lambda self: bool(getattr(self.radial, "extrapolated", False)))
    qL = property(lambda self: getattr(self.radial, "qL", None))
    q_rolloff = property(lambda self: getattr(self.radial, "q_rolloff", None))
    hurst = property(lambda self: getattr(self.radial, "hurst", None))
    angular_width = property(lambda self: getattr(self.shape, "angular_width", None))
    angular_kinks = property(lambda self: bool(getattr(self.shape, "angular_kinks", True)))

    def C(self, q) -> np.ndarray:
        """Angular mean at ``q`` (rad/m), m^4: the PSD of ``radial``."""
        return np.asarray(self.radial.C(q), dtype=float)

    def C_polar(self, q, phi) -> np.ndarray:
        """``C(q, phi)``, m^4: the angular mean of ``radial`` times the angular shape of ``shape`` (``phi`` in radians
        from the x axis; the shape held at the ends of its support beyond them)."""
        q, phi = np.broadcast_arrays(np.asarray(q, dtype=float), np.asarray(phi, dtype=float))
        lo, hi = (float(x) for x in self.shape.q_range)
        qc = np.clip(q, lo, hi)
        Cs = np.asarray(self.shape.C(qc), dtype=float)
        w = np.where(Cs > 0, self.shape.C_polar(qc, phi) / np.where(Cs > 0, Cs, 1.0), 1.0)
        return self.C(q) * w

    def angular_shape(self, q, phi) -> np.ndarray:
        """The angular shape of ``shape`` at ``q`` (rad/m) and ``phi`` (radians from the x axis)."""
        return self.shape.angular_shape(q, phi)

    def breakpoints(self) -> np.ndarray:
        """Wavevectors (rad/m) where the angular mean may have a kink: those of ``radial`` (none when it has none)."""
        f = getattr(self.radial, "breakpoints", None)
        return np.asarray(f() if callable(f) else (), dtype=float)


@doi(_CARBONE_2009, _PERSSON_2005)
@dataclass(frozen=True, eq=False)
class Stretched(AnisotropicPSD):
    r"""An isotropic PSD stretched ``ratio`` times along ``angle_deg`` (see :func:`stretched`).

    Attributes
    ----------
    base : isotropic PSD
        The surface before stretching.
    ratio : float
        Stretch factor, >= 1.
    angle_deg : float
        Direction of the ridges, degrees in [0, 180).
    """

    base: object
    ratio: float
    angle_deg: float = 0.0

    def __post_init__(self):
        base = self.base
        if getattr(base, "is_anisotropic", False):
            raise InputError("stretched: psd: expected an isotropic PSD (e.g. surfaces.SelfAffine), got an "
                             f"anisotropic one ({type(base).__name__})")
        if not (hasattr(base, "C") and hasattr(base, "q_range")):
            raise InputError(f"stretched: psd: expected an isotropic PSD with C(q) and q_range, got {base!r}")
        ratio = positive(self.ratio, "ratio")
        if ratio < 1.0:
            raise InputError(f"ratio: expected a stretch factor >= 1, got {ratio:g}; for ridges across "
                             f"{float(self.angle_deg):g} deg give ratio={1.0 / ratio:g} and "
                             f"angle_deg={(float(self.angle_deg) + 90.0) % 180.0:g}")
        angle = float(angle_in_degrees(self.angle_deg, "angle_deg", stacklevel=5))
        lo, hi = (float(x) for x in base.q_range)
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
            raise InputError(f"stretched: psd: expected 0 < q0 < q1, got q_range = ({lo:g}, {hi:g}) rad/m")
        object.__setattr__(self, "ratio", ratio)
        object.__setattr__(self, "angle_deg", angle % 180.0)
        object.__setattr__(self, "_ext", _extended(base))
        object.__setattr__(self, "_mean_memo", {})

    def __repr__(self) -> str:
        return (f"Stretched(ratio={self.ratio:g}, angle_deg={self.angle_deg:g}, base={self.base!r})")

    # --- the isotropic interface of the angular mean
    @property
    def q_range(self) -> tuple[float, float]:
        """Support (q_start, q_end), rad/m: the base surface's."""
        return tuple(float(x) for x in self.base.q_range)

    @property
    def source(self) -> str:
        """Origin, for messages and reports: the base's source (or type name), the stretch ratio and the ridge
        direction."""
        return f"{getattr(self.base, 'source', '') or type(self.base).__name__} stretched {self.ratio:g}x along " \
               f"{self.angle_deg:g} deg"

    @property
    def ridge_angle_deg(self) -> float:
        """Direction of the ridges, degrees."""
        return self.angle_deg

    @property
    def q_r(self):
        """Reliability limit, rad/m: the base's ``q_r`` (None when it has none); for a base other than
        :class:`SelfAffine` stretched by a ratio above 1, the end of its support divided by ``ratio`` (beyond it the
        power-law continuation of the base enters the PSD) when that is smaller or the base has no ``q_r``."""
        qr = getattr(self.base, "q_r", None)
        if self._ext.table_end is None or self.ratio == 1.0:
            return qr
        own = self._ext.table_end / self.ratio
        return own if qr is None else min(qr, own)

    @property
    def extrapolated(self) -> bool:
        """Whether part of the PSD is an extrapolation: the base's flag, or True for a base other than
        :class:`SelfAffine` stretched by a ratio above 1 (its power-law continuation past its support is used)."""
        return bool(getattr(self.base, "extrapolated", False)) or (self._ext.table_end is not None
                                                                   and self.ratio > 1.0)

    @property
    def qL(self):
        """The base's ``qL``, rad/m (None when it has none)."""
        return getattr(self.base, "qL", None)

    @property
    def q_rolloff(self):
        """Roll-off wavevector, rad/m: the base's ``q_rolloff``, else a :class:`SelfAffine` base's ``q0``, else None."""
        return getattr(self.base, "q_rolloff", None) or (self.base.q0 if isinstance(self.base, SelfAffine)
                                                         else None)

    @property
    def hurst(self):
        """The base's Hurst exponent (None when it has none)."""
        return getattr(self.base, "hurst", None)

    @property
    def angular_width(self) -> float:
        """The angular shape peaks across the ridges with a width of about 1/ratio radians."""
        return 1.0 / self.ratio

    @property
    def angular_kinks(self) -> bool:
        """Whether the angular shape has kinks: where q s(phi) crosses a kink of the base (a roll-off, the rows
        of a table) at some angles only."""
        return self.ratio > 1.0 and (len(self._ext.kinks) > 0 or self._ext.table_end is not None)

    def C(self, q) -> np.ndarray:
        r"""Angular mean :math:`\bar C(q) = \frac{2\zeta}{\pi}\int_0^{\pi/2} C_{iso}(q\sqrt{1 + (\zeta^2-1)\sin^2\beta})
        \,d\beta`, m^4 (zero outside the support), by Gauss-Legendre on panels graded towards the peak at
        :math:`\beta = 0` (across the ridges) and cut where the base PSD has a kink."""
        q = np.asarray(q, dtype=float)
        key = q.tobytes() + bytes(str(q.shape), "ascii")
        hit = self._mean_memo.get(key)
        if hit is not None:
            return hit.copy()
        out = self._mean(q.ravel()).reshape(q.shape)
        if len(self._mean_memo) > 64:
            self._mean_memo.clear()
        self._mean_memo[key] = out
        return out.copy()

    def C_polar(self, q, phi) -> np.ndarray:
        r""":math:`C(q, \phi) = \zeta\, C_{iso}(q s(\phi))`, :math:`s^2 = \zeta^2\cos^2(\phi-\alpha) +
        \sin^2(\phi-\alpha)`, m^4; zero outside the support."""
        q, phi = np.broadcast_arrays(np.asarray(q, dtype=float), np.asarray(phi, dtype=float))
        c = np.cos(phi - math.radians(self.angle_deg))
        s = np.sqrt(1.0 + (self.ratio**2 - 1.0) * c * c)
        lo, hi = self.q_range
        inside = (q >= lo * (1 - 1e-12)) & (q <= hi * (1 + 1e-12))
        return np.where(inside, self.ratio * self._ext(np.where(inside, q, lo) * s), 0.0)

    def breakpoints(self) -> np.ndarray:
        """The base's kinks and those kinks divided by ``ratio`` (where the angular mean starts to see them)."""
        b = np.asarray(self._ext.kinks, dtype=float)
        lo, hi = self.q_range
        out = np.union1d(b, b / self.ratio)
        return out[(out > lo) & (out < hi)]

    def with_cutoff(self, q0: float | None = None, q1: float | None = None) -> "Stretched":
        """The same stretch of the base cut to ``[q0, q1]``."""
        return Stretched(self.base.with_cutoff(q0=q0, q1=q1), self.ratio, self.angle_deg)

    def extrapolate(self, q1: float, hurst: float | None = None, **options) -> "Stretched":
        """The same stretch of the base extended to ``q1`` by its own ``extrapolate`` (a self-affine model
        continues its power law; a table its fitted tail, flagged as extrapolated)."""
        if not hasattr(self.base, "extrapolate"):
            return super().extrapolate(q1, hurst=hurst, **options)
        return Stretched(self.base.extrapolate(q1, hurst=hurst, **options), self.ratio, self.angle_deg)

    # --- helpers
    def _mean(self, q: np.ndarray) -> np.ndarray:
        out = np.zeros(q.size)
        lo, hi = self.q_range
        inside = (q >= lo * (1 - 1e-12)) & (q <= hi * (1 + 1e-12))
        if not inside.any():
            return out
        qi = np.clip(q[inside], lo, hi)
        z = self.ratio
        if z == 1.0:
            out[inside] = self._ext(qi)
            return out
        # panel edges in beta (0 = across the ridges): graded towards the peak of width ~1/z, plus the angles
        # where q s(beta) crosses a kink of the base
        geo = _graded_edges(z)
        kinks = np.asarray(self._ext.kinks, dtype=float)
        with np.errstate(invalid="ignore", divide="ignore"):
            x = (kinks[None, :] ** 2 / qi[:, None] ** 2 - 1.0) / (z * z - 1.0)
            kb = np.arcsin(np.sqrt(np.clip(x, 0.0, 1.0)))
        edges = np.sort(np.concatenate([np.zeros((qi.size, 1)), np.broadcast_to(geo, (qi.size, geo.size)), kb],
                                       axis=1), axis=1)
        a, b = edges[:, :-1], edges[:, 1:]
        g, w = _GL_X, _GL_W
        beta = 0.5 * (a + b)[..., None] + 0.5 * (b - a)[..., None] * g
        s = np.sqrt(1.0 + (z * z - 1.0) * np.sin(beta) ** 2)
        vals = self._ext(qi[:, None, None] * s)
        out[inside] = (2.0 * z / math.pi) * np.sum(0.5 * (b - a) * np.sum(vals * w, axis=-1), axis=-1)
        return out


# ---------------------------------------------------------------------------------------------------------
@doi(_PERSSON_2005)
@dataclass(frozen=True, eq=False)
class Unidirectional(AnisotropicPSD):
    """The unidirectional limit (see :func:`unidirectional`).

    Attributes
    ----------
    psd1d : 1-D PSD
        Two-sided line-scan PSD across the ridges, m^3.
    angle_deg : float
        Direction of the wavevectors (across the ridges), degrees in [0, 180).
    """

    psd1d: object
    angle_deg: float = 0.0

    def __post_init__(self):
        p = self.psd1d
        if isinstance(p, (SelfAffine, PSD)) or getattr(p, "is_anisotropic", False):
            raise InputError(f"unidirectional: psd1d: expected a 1-D line-scan PSD in m^3 (e.g. "
                             f"ProfileSet.psd()), got a 2-D PSD ({type(p).__name__}); for line scans across an "
                             "isotropic surface use surfaces.PSD1D.from_isotropic(psd)")
        if not (hasattr(p, "C") and hasattr(p, "q_range")):
            raise InputError(f"unidirectional: psd1d: expected a 1-D PSD with C(q) and q_range, got {p!r}")
        lo, hi = (float(x) for x in p.q_range)
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
            raise InputError(f"unidirectional: psd1d: expected 0 < q0 < q1, got q_range = ({lo:g}, {hi:g}) rad/m")
        angle = float(angle_in_degrees(self.angle_deg, "angle_deg", stacklevel=5))
        object.__setattr__(self, "angle_deg", angle % 180.0)

    def __repr__(self) -> str:
        return f"Unidirectional(angle_deg={self.angle_deg:g}, psd1d={self.psd1d!r})"

    @property
    def wave_angle_deg(self) -> float:
        """Direction of the wavevectors (across the ridges), degrees: the friction engine's delta direction."""
        return self.angle_deg

    @property
    def ridge_angle_deg(self) -> float:
        """Direction of the ridges, degrees."""
        return (self.angle_deg + 90.0) % 180.0

    @property
    def q_range(self) -> tuple[float, float]:
        """Support (q_start, q_end), rad/m: that of the 1-D PSD."""
        return tuple(float(x) for x in self.psd1d.q_range)

    @property
    def source(self) -> str:
        """Origin, for messages and reports: the 1-D PSD's source (or type name) and the wavevectors' direction."""
        src = getattr(self.psd1d, "source", "") or type(self.psd1d).__name__
        return f"{src} (unidirectional, wavevectors along {self.angle_deg:g} deg)"

    @property
    def q_r(self):
        """The 1-D PSD's reliability limit ``q_r``, rad/m (None when it has none)."""
        return getattr(self.psd1d, "q_r", None)

    @property
    def qL(self):
        """The 1-D PSD's ``qL``, rad/m (None when it has none)."""
        return getattr(self.psd1d, "qL", None)

    @property
    def hurst(self):
        """The 1-D PSD's Hurst exponent (None when it has none)."""
        return getattr(self.psd1d, "hurst", None)

    def C(self, q) -> np.ndarray:
        r"""Angular mean :math:`\bar C(q) = C_{1D}(q)/(\pi q)`, m^4 (zero outside the support)."""
        q = np.asarray(q, dtype=float)
        lo, hi = self.q_range
        inside = (q >= lo * (1 - 1e-12)) & (q <= hi * (1 + 1e-12))
        qs = np.where(inside, q, lo)
        return np.where(inside, np.asarray(self.psd1d.C(qs), dtype=float) / (math.pi * qs), 0.0)

    def C1D(self, q) -> np.ndarray:
        """The 1-D PSD across the ridges, m^3."""
        return np.asarray(self.psd1d.C(np.asarray(q, dtype=float)), dtype=float)

    def C_polar(self, q, phi):
        """Not defined in this limit (a delta along ``wave_angle_deg``): raises :class:`InputError`; use :meth:`C1D`."""
        raise InputError("a unidirectional PSD is a distribution in the angle (a delta along wave_angle_deg): it "
                         "has no pointwise C(q, phi); use C1D(q) and wave_angle_deg")

    def angular_shape(self, q, phi):
        """Not defined in this limit (a delta along ``wave_angle_deg``): raises :class:`InputError`."""
        raise InputError("a unidirectional PSD has no pointwise angular shape (a delta along wave_angle_deg)")

    def breakpoints(self) -> np.ndarray:
        """The wavevectors ``q`` of the 1-D PSD's table, rad/m (none when it has no ``q``)."""
        q = getattr(self.psd1d, "q", None)
        return np.empty(0) if q is None else np.asarray(q, dtype=float)

    def with_cutoff(self, q0: float | None = None, q1: float | None = None) -> "Unidirectional":
        """The same limit on the band ``[q0, q1]``."""
        return Unidirectional(_MeanAs1D(self.to_isotropic().with_cutoff(q0=q0, q1=q1)), self.angle_deg)

    def extrapolate(self, q1: float, hurst: float | None = None, **options) -> "Unidirectional":
        """The same limit with the self-affine tail of its angular mean continued to ``q1``."""
        return Unidirectional(_MeanAs1D(self.to_isotropic().extrapolate(q1, hurst=hurst, **options)),
                              self.angle_deg)

    def slope_tensor(self, q_min: float | None = None, q_max: float | None = None) -> np.ndarray:
        r"""All slope along the wavevectors: :math:`M = (\int q^2 C_{1D}\,dq)\,\mathbf n\mathbf n^T` (both signs of
        q), :math:`\mathbf n` along ``wave_angle_deg``."""
        q, w = _radial_rule(self, q_min, q_max)
        m2 = 2.0 * float(np.sum(w * q**2 * self.C1D(q)))
        n = np.array([math.cos(math.radians(self.angle_deg)), math.sin(math.radians(self.angle_deg))])
        return m2 * np.outer(n, n)


@dataclass(frozen=True, eq=False)
class _MeanAs1D:
    """The 1-D PSD C1D = pi q C(q) of a unidirectional surface whose angular mean is the isotropic PSD ``mean``."""

    mean: object

    @property
    def q_range(self):
        return self.mean.q_range

    @property
    def q(self):
        return getattr(self.mean, "q", None)

    def __getattr__(self, name):
        if name in ("q_r", "qL", "hurst", "source", "extrapolated"):
            return getattr(self.mean, name)
        raise AttributeError(name)

    def C(self, q):
        q = np.asarray(q, dtype=float)
        return math.pi * q * np.asarray(self.mean.C(q), dtype=float)


# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Extended:
    """An isotropic PSD as a function on (0, inf): itself inside its support, its power law continued past it."""

    psd: object
    kinks: tuple
    table_end: float | None  # last q of a table continued past its end (None: an analytic law)
    slope: float  # log-log slope of the continuation
    q_hi: float
    C_hi: float

    def __call__(self, k):
        k = np.asarray(k, dtype=float)
        p = self.psd
        if isinstance(p, SelfAffine):
            e = -2.0 * (1.0 + p.hurst)
            return p.C0 * np.maximum(k, p.q0) ** e
        inner = np.asarray(p.C(np.minimum(k, self.q_hi)), dtype=float)
        with np.errstate(divide="ignore", over="ignore"):
            outer = self.C_hi * (k / self.q_hi) ** self.slope
        return np.where(k <= self.q_hi, inner, outer)


def _extended(psd) -> _Extended:
    lo, hi = (float(x) for x in psd.q_range)
    if isinstance(psd, SelfAffine):
        kinks = (psd.q0,) if psd.qL is not None and psd.qL < psd.q0 else ()
        return _Extended(psd, kinks, None, -2.0 * (1.0 + psd.hurst), hi, float(psd.C(hi)))
    hurst = getattr(psd, "hurst", None)
    C_hi = float(np.asarray(psd.C(hi), dtype=float))
    if hurst is not None:
        slope = -2.0 * (1.0 + float(hurst))
    else:
        q_prev = float(psd.q[-2]) if isinstance(psd, PSD) else hi / 1.05
        C_prev = float(np.asarray(psd.C(q_prev), dtype=float))
        slope = math.log(C_hi / C_prev) / math.log(hi / q_prev) if C_prev > 0 and C_hi > 0 else -4.0
    f = getattr(psd, "breakpoints", None)
    kinks = np.asarray(f() if callable(f) else (f if f is not None else ()), dtype=float).ravel()
    return _Extended(psd, tuple(float(x) for x in kinks if lo <= x <= hi), hi, slope, hi, C_hi)


@functools.lru_cache(maxsize=32)
def _graded_edges(z: float) -> np.ndarray:
    """Panel edges in the angle from the across-ridge direction, doubling from 1/(8 z) to pi/2 (read-only)."""
    e = np.minimum(0.5 * math.pi, np.geomspace(0.125 / z, 0.5 * math.pi,
                                               max(4, math.ceil(math.log2(4.0 * math.pi * z)) + 1)))
    e.setflags(write=False)
    return e


def _band(psd, q_min, q_max) -> tuple[float, float]:
    lo, hi = (float(x) for x in psd.q_range)
    a = lo if q_min is None else max(lo, positive(q_min, "q_min"))
    b = hi if q_max is None else min(hi, positive(q_max, "q_max"))
    if not b > a:
        raise InputError(f"band: expected q_min < q_max inside the support [{lo:g}, {hi:g}] rad/m, got "
                         f"[{a:g}, {b:g}]")
    return a, b


def _radial_rule(psd, q_min=None, q_max=None, per_decade: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights in q over the band, on log-uniform panels cut at the breakpoints."""
    lo, hi = _band(psd, q_min, q_max)
    n = max(2, int(math.ceil(per_decade * math.log10(hi / lo))) + 1)
    b = np.asarray(psd.breakpoints(), dtype=float)
    x = np.unique(np.concatenate([np.linspace(math.log(lo), math.log(hi), n), np.log(b[(b > lo) & (b < hi)])]))
    g, w = _GL_X, _GL_W
    a, c = x[:-1, None], x[1:, None]
    t = 0.5 * (a + c) + 0.5 * (c - a) * g
    q = np.exp(t)
    return q.ravel(), (0.5 * (c - a) * w * q).ravel()


def _tidy_angle(a: float) -> float:
    """An angle in [0, 180) with round-off near whole degrees removed (179.9999999 -> 0)."""
    r = round(a)
    a = float(r) if abs(a - r) < 1e-7 else a
    return a % 180.0
