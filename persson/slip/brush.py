r"""Friction against slip ratio: the steady-state brush model of a braked rubber wheel, and DRFT kinematics.

Geometry and conventions (docs/slip.md). A wheel rolls and is braked on a moving counter-surface (the
disk of a DRFT-style tester, or the road under a tire). ``V`` is the rolling reference speed (the surface speed
of the disk under the wheel, or the vehicle speed), ``omega r`` the circumferential speed of the wheel. Then

* braking slip ratio :math:`s = (V - \omega r)/V`, :math:`0 \le s \le 1` (``s = 1``: locked wheel, pure sliding);
* sliding speed :math:`v_s = s V = V - \omega r`;
* the contact patch has length :math:`l` (rolling direction), width :math:`w`; the coordinate :math:`x` runs
  from the leading edge (:math:`x = 0`) to the trailing edge (:math:`x = l`);
* normal pressure :math:`p(x)` with mean :math:`\sigma_0` (:math:`\int_0^l p\,dx = \sigma_0 l`):
  uniform, parabolic :math:`6\sigma_0 (x/l)(1 - x/l)`, or Sakai's n-power law (see :class:`Contact`);
* the tread (bristles) has a shear stiffness :math:`k` per unit area per unit displacement (Pa/m).

Brush model (Pacejka, *Tire and Vehicle Dynamics*, ch. 3, "theory of steady-state slip force generation",
the brush model for longitudinal slip). A bristle enters the contact undeformed at the leading edge. While it
adheres, its tip moves with the counter-surface and its base with the wheel, so its displacement grows as

.. math:: u(x) = \frac{v_s}{\omega r} x = \frac{s}{1-s}\, x \equiv \theta x,

(:math:`\theta = s/(1-s)` is Pacejka's "theoretical slip"). It adheres until its shear stress
:math:`k u(x)` first reaches the friction limit :math:`\mu(v_s) p(x)` at :math:`x = x_c`; behind :math:`x_c` it
slides with shear stress :math:`\mu(v_s) p(x)`. The friction coefficient of the wheel is

.. math:: \mu(s, V) = \frac{w\int_0^l \tau(x)\,dx}{\sigma_0 l w}
    = \frac{k\theta x_c^2}{2\sigma_0 l} + \frac{\mu(v_s)}{\sigma_0 l}\int_{x_c}^{l} p(x)\,dx ,

with :math:`\mu(v_s)` the local sliding friction at the sliding speed :math:`v_s = sV`, the background temperature
:math:`T_0` and the nominal pressure :math:`\sigma_0` (computed by a :class:`persson.Model` with its effects, or
given as a function). Limits: for :math:`s \to 0`, :math:`\mu \approx k l s/(2\sigma_0)` (initial slope
:math:`k l/(2\sigma_0)`); :math:`s = 1` gives pure sliding :math:`\mu(V)`. For a constant local friction and the
parabolic pressure the closed form is :math:`\mu(s) = \mu\,(1 - \lambda^3)`,
:math:`\lambda = \max(0, 1 - \theta/\theta_{sl})`,
:math:`\theta_{sl} = 6\mu\sigma_0/(k l)` (Pacejka's brush-model result; used by the tests as the reference).

Numerics: the patch is discretised on ``Contact.n_points`` nodes. The stick/slide boundary :math:`x_c` is the first
sign change of the stick margin :math:`\mu p(x) - k\theta x`, located by linear interpolation between nodes; the
stick part is integrated exactly, the slide part with the trapezoid rule on the pressure normalised so that the
discrete load is exact (``s = 1`` returns :math:`\mu(V)` to rounding). The error falls as ``n_points**-2``
(exact for the uniform pressure). Everything is vectorised over slips and speeds, and the friction model is
evaluated **once**, on the array of distinct sliding speeds.

Local pressure and temperature along the patch. When the model carries the
:class:`~persson.effects.PatchHeating` effect, the local friction is :math:`\mu(v_s, p(x), T(x))`: the engine's
sliding friction at the local pressure and at the background temperature of the rubber element as it travels
through the contact, heated by the frictional power :math:`\tau(x) v_s` behind the stick zone (one-dimensional
conduction into the tread and the counter-surface; see :mod:`persson.slip.heating`). The friction is then
tabulated once per call over (sliding speed, pressure, temperature) and interpolated; ``slip = 1`` is the
locked wheel, the patch average of the heated sliding friction (the limit of the curve). :func:`fit_slip` fits
contact and effect parameters of such a model to measured curves, with standard errors.

Two bristle kinematics (keyword ``kinematics``). ``"pacejka"`` (the default) is the displacement above,
:math:`u = \theta x` with :math:`\theta = s/(1-s)`: the bristle's root travels through the patch with the wheel's
surface at :math:`\omega r`, so it spends :math:`x/(\omega r)` in the patch before reaching :math:`x`.
``"linear"`` is the road-friction trailer article's Eq. 11/19, :math:`\Delta x = s\,x` (Study on the influence
of environmental conditions on road friction characteristics, Lubricants 11(7), 277 (2023), Section 4.1): the time
is taken as :math:`x/V`, the road's. Both agree to first order in s (:math:`\theta = s + s^2 + \dots`) and share the
initial slope; at large slip the linear kinematics displaces the bristles less, and at the locked wheel (s = 1)
it still leaves a stick zone whenever :math:`k l/\sigma_0 < \mu_s p'(0)/\sigma_0` (for Sakai's law:
:math:`C_0/\mu_s < n + 1`), where a locked wheel really slides everywhere. Every brush function returns the two
terms of the friction separately (the article's Figure 19): the **adhesion-region** term
:math:`k\theta x_c^2/(2\sigma_0 l)` and the **sliding-region** term :math:`(1/\sigma_0 l)\int_{x_c}^l\tau\,dx`.

Also here: the two-coefficient brush used to analyse trailer data (static limit :math:`\mu_s` in the stick zone,
dynamic :math:`\mu_D` in the slide zone, Sakai's n = 4 pressure) and its map over
:math:`n_1 = \mu_D/\mu_s` and :math:`n_2 = (\text{initial slope})/\mu_s`. Elsewhere in :mod:`persson.slip`:
:func:`~persson.slip.mu_slip` (:mod:`~persson.slip.curve`) drives this brush with the engine's friction,
:func:`~persson.slip.fit_brush` (:mod:`~persson.slip.brush_fit`) fits a Stribeck-type brush to a measured curve,
the DRFT kinematics are in :mod:`~persson.slip.kinematics`, the Magic Formula in :mod:`~persson.slip.magic`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .._checks import number, positive
from ..errors import InputError
from ._arrays import _broadcast, _increasing, _mu_array, _slip_array
from .contact import Contact
from .peaks import _parabola_vertex
from .references import PACEJKA_BOOK, SAKAI_1981, TRAILER_2023

__all__ = ["KINEMATICS", "brush_mu", "brush_terms", "BrushTerms", "BrushCurve", "two_coefficient_mu", "BrushMap",
           "MapSensitivity", "two_coefficient_map"]

#: Bristle kinematics of the brush functions: Pacejka's :math:`\theta = s/(1-s)` and the trailer article's
#: :math:`\Delta x = s x`.
KINEMATICS = ("pacejka", "linear")

_MAX_CELLS = 2_000_000  # rows x nodes per vectorised block of the brush integral


# =========================================================================================================
# Brush model for given local friction values
# =========================================================================================================
@dataclass(frozen=True, eq=False)
class BrushTerms:
    r"""mu(slip) of the brush model split into its adhesion-region and sliding-region terms.

    Attributes
    ----------
    slip : ndarray
        Slip ratios.
    mu : ndarray
        Friction coefficient, ``mu_adhesion + mu_sliding``.
    mu_adhesion : ndarray
        Adhesion-region (stick-zone) term :math:`k\theta x_c^2/(2\sigma_0 l)`.
    mu_sliding : ndarray
        Sliding-region term :math:`(1/\sigma_0 l)\int_{x_c}^l \mu(v_s) p(x)\,dx`.
    stick_fraction : ndarray
        :math:`x_c/l`.
    stick_length : ndarray
        :math:`x_c`, m.
    kinematics : str
        ``"pacejka"`` or ``"linear"``.
    citations : tuple of str
    """

    slip: np.ndarray
    mu: np.ndarray
    mu_adhesion: np.ndarray
    mu_sliding: np.ndarray
    stick_fraction: np.ndarray
    stick_length: np.ndarray
    kinematics: str = "pacejka"
    citations: tuple = (PACEJKA_BOOK,)


@doi(PACEJKA_BOOK, TRAILER_2023)
def brush_terms(contact: Contact, slip, mu_local, *, pressure: float, mu_static=None,
                kinematics: str = "pacejka") -> BrushTerms:
    r"""Brush-model friction for given local friction values, split into adhesion and sliding terms.

    .. math:: \mu = \underbrace{\frac{k\theta x_c^2}{2\sigma_0 l}}_{\text{adhesion}}
        + \underbrace{\frac{\mu(v_s)}{\sigma_0 l}\int_{x_c}^{l} p\,dx}_{\text{sliding}}

    (Pacejka, *Tire and Vehicle Dynamics*, ch. 3; the split is the trailer article's Figure 19, Lubricants 11,
    277 (2023)), with :math:`\theta = s/(1-s)` (``kinematics="pacejka"``) or :math:`\theta = s`
    (``"linear"``, the article's :math:`\Delta x = s x`).

    Parameters
    ----------
    contact : Contact
    slip : array_like
        Braking slip ratios in (0, 1].
    mu_local : array_like
        Local sliding friction :math:`\mu(v_s)` for each slip (broadcast against ``slip``), >= 0.
    pressure : float
        Mean pressure :math:`\sigma_0`, Pa.
    mu_static : array_like, optional
        Friction limit in the stick zone (default: ``mu_local``; give it for a two-coefficient brush).
    kinematics : {"pacejka", "linear"}
        Bristle displacement :math:`\theta x` with :math:`\theta = s/(1-s)`, or :math:`s x`.

    Returns
    -------
    BrushTerms
        Arrays of the broadcast shape of ``slip``, ``mu_local`` (and ``mu_static``).
    """
    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    kin = _kinematics(kinematics)
    s = _slip_array(slip)
    sigma0 = positive(pressure, "pressure")
    m = _mu_array(mu_local, "mu_local")
    mst = m if mu_static is None else _mu_array(mu_static, "mu_static")
    s, m, mst = _broadcast("slip, mu_local" if mu_static is None else "slip, mu_local, mu_static", s, m, mst)
    shape = s.shape
    a = _a_of(s.ravel(), contact, sigma0, kin)
    slide = m.ravel().astype(float)
    mu, xc, Gc = _brush(contact._xi, contact._g, contact._G, a, mst.ravel().astype(float), slide)
    adhesion, sliding = _split(a, xc, Gc, slide)
    cites = contact.citations + ((TRAILER_2023,) if kin == "linear" else ())
    return BrushTerms(slip=s, mu=mu.reshape(shape), mu_adhesion=adhesion.reshape(shape),
                      mu_sliding=sliding.reshape(shape), stick_fraction=xc.reshape(shape),
                      stick_length=contact.length * xc.reshape(shape), kinematics=kin, citations=cites)


@doi(PACEJKA_BOOK, TRAILER_2023)
def brush_mu(contact: Contact, slip, mu_local, *, pressure: float, mu_static=None, kinematics: str = "pacejka"):
    r"""Brush-model friction for given local friction values (no friction model involved).

    The total of :func:`brush_terms` (see there for the formula and the parameters).

    Returns
    -------
    (mu, stick_fraction) : ndarrays of the broadcast shape
        Friction coefficient and :math:`x_c/l`.
    """
    t = brush_terms(contact, slip, mu_local, pressure=pressure, mu_static=mu_static, kinematics=kinematics)
    return t.mu, t.stick_fraction


# =========================================================================================================
# Two-coefficient brush (trailer-data analysis)
# =========================================================================================================
@dataclass(frozen=True, eq=False)
class BrushCurve:
    """mu(slip) of the two-coefficient brush: ``slip``, ``mu`` and ``stick_fraction`` (x_c/l), same shape.

    ``mu_adhesion`` and ``mu_sliding`` are the adhesion-region and sliding-region terms (their sum is ``mu``),
    ``stick_length`` is x_c in metres when the contact length was given (else None); ``kinematics`` the bristle
    kinematics. Producers that do not split the curve leave the terms None.
    """

    slip: np.ndarray
    mu: np.ndarray
    stick_fraction: np.ndarray
    mu_static: float
    mu_dynamic: float
    initial_slope: float
    sakai_n: float
    citations: tuple = (PACEJKA_BOOK, SAKAI_1981)
    mu_adhesion: np.ndarray | None = None
    mu_sliding: np.ndarray | None = None
    stick_length: np.ndarray | None = None
    kinematics: str = "pacejka"


@doi(PACEJKA_BOOK, SAKAI_1981, TRAILER_2023)
def two_coefficient_mu(slip, *, mu_static: float, mu_dynamic: float, initial_slope: float,
                       sakai_n: float = 4.0, n_points: int = 401, kinematics: str = "pacejka",
                       length: float | None = None) -> BrushCurve:
    r"""Two-coefficient brush: stick up to the static limit :math:`\mu_s p`, slide with :math:`\mu_D p`.

    Same kinematics as :func:`mu_slip` (bristle displacement :math:`\theta x`, :math:`\theta = s/(1-s)`), or the
    trailer article's :math:`\Delta x = s x` (``kinematics="linear"``, Lubricants 11, 277 (2023), Eqs. 19-24);
    the bristles stick while :math:`k\theta x < \mu_s p(x)` and slide behind the first point where the static
    limit is reached, with shear :math:`\mu_D p(x)`; Sakai's n-power pressure (n = 4 by default). In terms of the
    initial slope :math:`C_0 = k l/(2\sigma_0)`:

    .. math:: \mu(s) = \underbrace{C_0\theta\xi_c^2}_{\text{adhesion}}
        + \underbrace{\mu_D\left[1 - \int_0^{\xi_c} \frac{p}{\sigma_0} d\xi\right]}_{\text{sliding}},\qquad
        2C_0\theta\,\xi_c = \mu_s\, p(\xi_c)/\sigma_0 .

    With :math:`\mu_D < \mu_s` the curve has a peak above :math:`\mu_D`; with Pacejka's kinematics it falls to
    :math:`\mu_D` at full sliding. With the linear kinematics the locked wheel keeps a stick zone while
    :math:`C_0/\mu_s < n + 1`, and :math:`\mu(1) \ne \mu_D` there (the stick zone carries less or more than
    :math:`\mu_D p`).

    Parameters
    ----------
    slip : array_like
        Slip ratios in (0, 1].
    mu_static, mu_dynamic : float
        :math:`\mu_s > 0` and :math:`\mu_D \ge 0`.
    initial_slope : float
        :math:`d\mu/ds` at s -> 0, i.e. :math:`k l/(2\sigma_0)` (> 0).
    sakai_n : float
        Exponent of Sakai's pressure law (> 0; 4 by default, 2 is parabolic).
    n_points : int
        Nodes along the patch.
    kinematics : {"pacejka", "linear"}
        :math:`\theta = s/(1-s)` (default) or :math:`\theta = s`.
    length : float, optional
        Contact length l, m: only to give ``stick_length`` in metres (the curve is dimensionless).

    Returns
    -------
    BrushCurve
        With the adhesion and sliding terms ``mu_adhesion``, ``mu_sliding``.
    """
    kin = _kinematics(kinematics)
    s = _slip_array(slip)
    ms = number(mu_static, "mu_static")
    md = number(mu_dynamic, "mu_dynamic")
    c0 = number(initial_slope, "initial_slope")
    if ms <= 0:
        raise InputError(f"mu_static: expected a value > 0, got {ms:g}")
    if md < 0:
        raise InputError(f"mu_dynamic: expected a value >= 0, got {md:g}")
    if c0 <= 0:
        raise InputError(f"initial_slope: expected a value > 0, got {c0:g}")
    ell = None if length is None else positive(length, "length")
    xi, g, G = _sakai_nodes(number(sakai_n, "sakai_n"), n_points)
    sf = s.ravel().astype(float)
    a = 2.0 * c0 * _theta(sf, kin)
    slide = np.full(sf.size, md)
    mu, xc, Gc = _brush(xi, g, G, a, np.full(sf.size, ms), slide)
    adhesion, sliding = _split(a, xc, Gc, slide)
    cites = (PACEJKA_BOOK, SAKAI_1981) + ((TRAILER_2023,) if kin == "linear" else ())
    return BrushCurve(slip=s, mu=mu.reshape(s.shape), stick_fraction=xc.reshape(s.shape), mu_static=ms,
                      mu_dynamic=md, initial_slope=c0, sakai_n=float(sakai_n), citations=cites,
                      mu_adhesion=adhesion.reshape(s.shape), mu_sliding=sliding.reshape(s.shape),
                      stick_length=None if ell is None else ell * xc.reshape(s.shape), kinematics=kin)


@dataclass(frozen=True, eq=False)
class BrushMap:
    r"""Peak of the two-coefficient brush over :math:`n_1 = \mu_D/\mu_s` and :math:`n_2 = C_0/\mu_s`.

    Attributes
    ----------
    n1 : ndarray (k,)
    n2 : ndarray (m,)
    peak_ratio : ndarray (k, m)
        :math:`n_3 = \mu_{peak}/\mu_s`.
    slip_at_peak : ndarray (k, m)
        Slip ratio of the peak (the first slip reaching the maximum when the curve has a plateau). With the
        linear kinematics and ``slip_max=None`` it can exceed 1 (a formal value beyond the locked wheel).
    locked_ratio : ndarray
        :math:`\mu(s=1)/\mu_s`: shape (k,), equal to ``n1``, with Pacejka's kinematics; shape (k, m) with the
        linear kinematics, where the locked wheel keeps a stick zone while :math:`n_2 < n + 1`.
    sakai_n : float
    kinematics : str
    slip_max : float or None
        The peak was searched on :math:`0 < s \le` ``slip_max`` (None: the curve's stationary maximum).
    """

    n1: np.ndarray
    n2: np.ndarray
    peak_ratio: np.ndarray
    slip_at_peak: np.ndarray
    locked_ratio: np.ndarray
    sakai_n: float
    citations: tuple = (PACEJKA_BOOK, SAKAI_1981)
    kinematics: str = "pacejka"
    slip_max: float | None = 1.0

    def lookup(self, n1: float, n2: float) -> tuple[float, float]:
        """(peak ratio, slip at peak) bilinearly interpolated at (n1, n2) (inside the map)."""
        from scipy.interpolate import RegularGridInterpolator

        pt = [[number(n1, "n1"), number(n2, "n2")]]
        if not (self.n1[0] <= pt[0][0] <= self.n1[-1] and self.n2[0] <= pt[0][1] <= self.n2[-1]):
            raise InputError(f"n1, n2: ({n1:g}, {n2:g}) lies outside the map "
                             f"[{self.n1[0]:g}, {self.n1[-1]:g}] x [{self.n2[0]:g}, {self.n2[-1]:g}]")
        r = RegularGridInterpolator((self.n1, self.n2), self.peak_ratio)(pt)[0]
        sp = RegularGridInterpolator((self.n1, self.n2), self.slip_at_peak)(pt)[0]
        return float(r), float(sp)

    def sensitivity(self) -> MapSensitivity:
        r"""How much the peak ratio and the slip at the peak depend on :math:`n_1` and on :math:`n_2`.

        Two measures over the map's grid, each for (n1, n2):

        * first-order variance shares :math:`S_i = \mathrm{Var}(E[y\,|\,n_i])/\mathrm{Var}(y)` with the grid
          points as equally likely (evenly spaced n1, n2 make them the first-order indices of I. M. Sobol, Math.
          Comput. Simul. 55, 271 (2001) for uniform ranges; :math:`S_1 + S_2 = 1` when y is additive, less when n1
          and n2 interact);
        * swings: the range of y as one parameter spans its grid with the other held, averaged over the other.
        """
        return MapSensitivity(peak_ratio_share=_shares(self.peak_ratio), slip_share=_shares(self.slip_at_peak),
                              peak_ratio_swing=_swings(self.peak_ratio), slip_swing=_swings(self.slip_at_peak),
                              n1_range=(float(self.n1[0]), float(self.n1[-1])),
                              n2_range=(float(self.n2[0]), float(self.n2[-1])), kinematics=self.kinematics,
                              slip_max=self.slip_max)


@dataclass(frozen=True)
class MapSensitivity:
    """Sensitivity of the two-coefficient brush's peak to n1 and n2 (:meth:`BrushMap.sensitivity`).

    Attributes
    ----------
    peak_ratio_share, slip_share : tuple of float
        First-order variance shares (of n1, of n2) of the peak ratio n3 and of the slip at the peak.
    peak_ratio_swing, slip_swing : tuple of float
        Mean range of n3 (of the slip at the peak) as n1 (as n2) spans the map, the other held.
    n1_range, n2_range : tuple of float
        The map's ranges.
    kinematics : str
    slip_max : float or None
    """

    peak_ratio_share: tuple
    slip_share: tuple
    peak_ratio_swing: tuple
    slip_swing: tuple
    n1_range: tuple
    n2_range: tuple
    kinematics: str
    slip_max: float | None

    @property
    def peak_ratio_driver(self) -> str:
        """``"n1"`` or ``"n2"``: the parameter with the larger variance share of the peak ratio."""
        return "n1" if self.peak_ratio_share[0] >= self.peak_ratio_share[1] else "n2"


@doi(PACEJKA_BOOK, SAKAI_1981, TRAILER_2023)
def two_coefficient_map(n1, n2, *, sakai_n: float = 4.0, n_slip: int = 400, n_points: int = 401,
                        kinematics: str = "pacejka", slip_max: float | None = 1.0) -> BrushMap:
    r"""Map of the peak :math:`\mu_{peak}/\mu_s` and the slip at the peak of the two-coefficient brush.

    With :math:`\mu_s = 1` the curve is :math:`n_2\theta\xi_c^2 + n_1[1 - G(\xi_c)]`, where the stick length
    :math:`\xi_c` (and the load fraction :math:`G(\xi_c)` ahead of it) depends on :math:`n_2\theta` only; the
    maximum over s is searched on ``n_slip`` log-spaced slips in [1e-4, ``slip_max``] and refined locally (41 slips;
    the slip of the peak then by a parabola through the three best).

    Because the curve depends on :math:`n_2\theta` only, with Pacejka's kinematics (:math:`\theta = s/(1-s)`
    covers :math:`[0, \infty)` on :math:`0 < s \le 1`) the peak ratio depends on :math:`n_1` (and n) alone and
    :math:`\theta_{peak} \propto 1/n_2`. With the trailer article's linear kinematics (:math:`\theta = s`,
    Lubricants 11, 277 (2023), Eq. 19, whose Figure 20 maps :math:`n_3 = \mu_{max}/\mu_s` over
    :math:`0.1 \le n_1 \le 0.8`, :math:`1 \le n_2 \le 6`) the slip range ends at :math:`n_2\theta = n_2`: where
    the stationary maximum lies beyond s = 1, the peak on :math:`s \le 1` is :math:`\mu(1)` and depends on
    :math:`n_2`. :meth:`BrushMap.sensitivity` measures both dependences.

    Parameters
    ----------
    n1 : array_like
        :math:`\mu_D/\mu_s`, increasing, > 0 (<= 1 for a peak).
    n2 : array_like
        Initial slope / :math:`\mu_s`, increasing, > 0.
    sakai_n : float
        Exponent of Sakai's pressure law (default 4).
    n_slip : int
        Slips of the coarse search (>= 20).
    n_points : int
        Nodes along the patch.
    kinematics : {"pacejka", "linear"}
        :math:`\theta = s/(1-s)` (default) or :math:`\theta = s`.
    slip_max : float or None
        Upper end of the slip range searched, in (0, 1] (default 1, the locked wheel: the peak of a measured
        curve). None searches for the curve's stationary maximum: with the linear kinematics up to the slip
        :math:`(n + 1)/n_2` at which the stick zone vanishes (beyond 1 when :math:`n_2 < n + 1`).
    """
    kin = _kinematics(kinematics)
    n1 = _increasing(n1, "n1")
    n2 = _increasing(n2, "n2")
    if np.any(n1 <= 0):
        raise InputError("n1: expected mu_D / mu_s > 0")
    if np.any(n2 <= 0):
        raise InputError("n2: expected initial slope / mu_s > 0")
    if isinstance(n_slip, bool) or not isinstance(n_slip, (int, np.integer)) or n_slip < 20:
        raise InputError(f"n_slip: expected an integer >= 20, got {n_slip!r}")
    n_exp = number(sakai_n, "sakai_n")
    if slip_max is None:
        s_hi = max(1.0, (n_exp + 1.0) / float(n2[0])) if kin == "linear" else 1.0
    else:
        s_hi = number(slip_max, "slip_max")
        if not 1e-3 < s_hi <= 1.0:
            raise InputError(f"slip_max: expected a slip ratio in (0.001, 1] or None, got {s_hi:g}")
    xi, g, G = _sakai_nodes(n_exp, n_points)
    s = np.geomspace(1e-4, s_hi, int(n_slip))

    def ratio(n1v, n2v, sv):
        """mu/mu_s for broadcastable n1, n2, s arrays (all same final shape)."""
        n1v, n2v, sv = np.broadcast_arrays(n1v, n2v, sv)
        sf = sv.ravel()
        a = 2.0 * n2v.ravel() * _theta(sf, kin)
        ones = np.ones(sf.size)
        stick, xc, Gc = _brush(xi, g, G, a, ones, np.zeros(sf.size))  # stick part only (mu_slide = 0)
        out = stick + n1v.ravel() * (1.0 - Gc)
        return out.reshape(sv.shape)

    # coarse: the stick part depends on (n2, s) only
    coarse = ratio(n1[:, None, None], n2[None, :, None], s[None, None, :])  # (k, m, S)
    j = np.argmax(coarse, axis=-1)
    lo = s[np.clip(j - 1, 0, s.size - 1)]
    hi = s[np.clip(j + 1, 0, s.size - 1)]
    t = np.linspace(0.0, 1.0, 41)
    sf = lo[..., None] * (hi / lo)[..., None] ** t  # (k, m, 41), log-spaced in the bracket
    fine = ratio(n1[:, None, None], n2[None, :, None], sf)
    jf = np.argmax(fine, axis=-1)
    best = np.take_along_axis(fine, jf[..., None], -1)[..., 0]
    sbest = np.take_along_axis(sf, jf[..., None], -1)[..., 0]
    # parabola through the three fine points around the maximum (in ln s)
    jm = np.clip(jf, 1, t.size - 2)
    x = np.log(np.stack([np.take_along_axis(sf, (jm + d)[..., None], -1)[..., 0] for d in (-1, 0, 1)]))
    y = np.stack([np.take_along_axis(fine, (jm + d)[..., None], -1)[..., 0] for d in (-1, 0, 1)])
    xv, yv, ok = _parabola_vertex(x, y)
    ok &= (jf >= 1) & (jf <= t.size - 2)
    peak_ratio = best  # the curve is flat at its maximum: the fine-grid value is exact to ~(ds)^2
    slip_at_peak = np.minimum(np.where(ok, np.exp(xv), sbest), s_hi)
    if kin == "linear":
        locked = ratio(n1[:, None], n2[None, :], np.ones((1, 1)))
        cites = (PACEJKA_BOOK, SAKAI_1981, TRAILER_2023)
    else:
        locked = n1.copy()
        cites = (PACEJKA_BOOK, SAKAI_1981)
    return BrushMap(n1=n1, n2=n2, peak_ratio=peak_ratio, slip_at_peak=slip_at_peak, locked_ratio=locked,
                    sakai_n=float(sakai_n), citations=cites, kinematics=kin, slip_max=slip_max if slip_max is None
                    else s_hi)


# =========================================================================================================
# Helpers: kinematics, the brush integral (vectorised), the split
# =========================================================================================================
def _kinematics(kinematics) -> str:
    key = kinematics.strip().lower() if isinstance(kinematics, str) else None
    if key not in KINEMATICS:
        raise InputError(f"kinematics: expected \"pacejka\" (theta = s/(1-s)) or \"linear\" (the trailer "
                         f"article's dx = s x), got {kinematics!r}")
    return key


def _theta(s: np.ndarray, kinematics: str) -> np.ndarray:
    """Bristle displacement per unit distance from the leading edge: s/(1-s) (inf at s = 1), or s."""
    if kinematics == "linear":
        return np.asarray(s, dtype=float).copy()
    with np.errstate(divide="ignore"):
        return np.where(s < 1.0, s / np.where(s < 1.0, 1.0 - s, 1.0), np.inf)


def _a_of(s: np.ndarray, contact: Contact, sigma0: float, kinematics: str = "pacejka") -> np.ndarray:
    """a = k theta l / sigma0 (theta of the kinematics; inf at s = 1 for Pacejka's)."""
    return contact.stiffness * contact.length / sigma0 * _theta(s, kinematics)


def _split(a, xc, Gc, mu_slide):
    """Adhesion term a xi_c^2 / 2 and sliding term mu_slide (1 - G(xi_c)) of the brush integral's output."""
    adhesion = np.where(np.isfinite(a), 0.5 * np.where(np.isfinite(a), a, 0.0) * xc**2, 0.0)
    return adhesion, mu_slide * (1.0 - Gc)


def _brush(xi, g, G, a, mu_stick, mu_slide):
    r"""Brush integral on nodes ``xi`` (pressure shape ``g``, cumulative ``G``, ``G[-1] = 1``).

    ``a = k theta l / sigma0`` (stick shear / sigma0 = a xi; ``inf`` for pure sliding), friction limit in the
    stick zone ``mu_stick``, shear coefficient in the slide zone ``mu_slide`` (1D arrays of one length M).
    Returns mu (M,), xi_c (M,) and the load fraction ahead of x_c, G(xi_c) (M,).
    """
    M = a.size
    mu = np.empty(M)
    xc = np.empty(M)
    Gxc = np.empty(M)
    pure = ~np.isfinite(a)
    a_eff = np.where(pure, 0.0, a)
    N = xi.size
    step = max(1, _MAX_CELLS // N)
    for lo in range(0, M, step):
        sl = slice(lo, min(M, lo + step))
        aa = a_eff[sl]
        ms = mu_stick[sl]
        d = ms[:, None] * g[None, :] - aa[:, None] * xi[None, :]  # stick margin (shear limit - stick shear)
        neg = d[:, 1:] <= 0.0
        has = neg.any(axis=1)
        i = np.where(has, np.argmax(neg, axis=1) + 1, N - 1)
        rows = np.arange(i.size)
        d0 = d[rows, i - 1]
        d1 = d[rows, i]
        den = d0 - d1
        t = np.where(den > 0, d0 / np.where(den > 0, den, 1.0), 0.0).clip(0.0, 1.0)
        h = xi[i] - xi[i - 1]
        x_c = xi[i - 1] + t * h
        g_c = g[i - 1] + t * (g[i] - g[i - 1])
        G_c = G[i - 1] + 0.5 * t * h * (g[i - 1] + g_c)
        x_c = np.where(has, x_c, 1.0)  # no crossing: the whole patch sticks
        G_c = np.where(has, G_c, 1.0)
        xc[sl] = x_c
        Gxc[sl] = G_c
        mu[sl] = 0.5 * aa * x_c**2 + mu_slide[sl] * (1.0 - G_c)
    mu[pure] = mu_slide[pure]
    xc[pure] = 0.0
    Gxc[pure] = 0.0
    return mu, xc, Gxc


def _sakai_nodes(n: float, n_points: int):
    c = Contact(1.0, 1.0, 1.0, {"sakai_n": n}, n_points=n_points)
    return c._xi, c._g, c._G


def _shares(y: np.ndarray) -> tuple[float, float]:
    """First-order variance shares of the row (n1) and column (n2) parameters of a (k, m) grid of values."""
    var = float(np.var(y))
    if var == 0.0:
        return 0.0, 0.0
    return float(np.var(y.mean(axis=1)) / var), float(np.var(y.mean(axis=0)) / var)


def _swings(y: np.ndarray) -> tuple[float, float]:
    """Mean range of y along n1 (axis 0) and along n2 (axis 1)."""
    return float(np.mean(np.ptp(y, axis=0))), float(np.mean(np.ptp(y, axis=1)))
