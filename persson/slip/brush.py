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

Also here: the two-coefficient brush used to analyse trailer data (static limit :math:`\mu_s` in the stick zone,
dynamic :math:`\mu_D` in the slide zone, Sakai's n = 4 pressure) and its map over
:math:`n_1 = \mu_D/\mu_s` and :math:`n_2 = (\text{initial slope})/\mu_s`; :func:`fit_brush`, the brush model with a
Stribeck-type sliding friction fitted to a measured curve alone; and the DRFT kinematics (braking and driving).

Magic Formula fits, friction-speed laws and curve peaks are in :mod:`persson.slip`; plots in
:mod:`persson.slip.plots`.
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
from .references import PACEJKA_BOOK, SAKAI_1981

__all__ = ["brush_mu", "BrushCurve", "two_coefficient_mu", "BrushMap", "two_coefficient_map"]


_MAX_CELLS = 2_000_000  # rows x nodes per vectorised block of the brush integral


# =========================================================================================================
# Brush integral (vectorised)
# =========================================================================================================
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


@doi(PACEJKA_BOOK)
def brush_mu(contact: Contact, slip, mu_local, *, pressure: float, mu_static=None):
    r"""Brush-model friction for given local friction values (no friction model involved).

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

    Returns
    -------
    (mu, stick_fraction) : ndarrays of the broadcast shape
        Friction coefficient and :math:`x_c/l`.
    """
    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    s = _slip_array(slip)
    sigma0 = positive(pressure, "pressure")
    m = _mu_array(mu_local, "mu_local")
    mst = m if mu_static is None else _mu_array(mu_static, "mu_static")
    s, m, mst = _broadcast("slip, mu_local" if mu_static is None else "slip, mu_local, mu_static", s, m, mst)
    shape = s.shape
    a = _a_of(s.ravel(), contact, sigma0)
    mu, xc, _ = _brush(contact._xi, contact._g, contact._G, a, mst.ravel().astype(float),
                       m.ravel().astype(float))
    return mu.reshape(shape), xc.reshape(shape)


def _a_of(s: np.ndarray, contact: Contact, sigma0: float) -> np.ndarray:
    """a = k theta l / sigma0, theta = s / (1 - s); inf at s = 1."""
    with np.errstate(divide="ignore"):
        theta = np.where(s < 1.0, s / np.where(s < 1.0, 1.0 - s, 1.0), np.inf)
    return contact.stiffness * contact.length / sigma0 * theta


# =========================================================================================================
# Two-coefficient brush (trailer-data analysis)
# =========================================================================================================
@dataclass(frozen=True, eq=False)
class BrushCurve:
    """mu(slip) of the two-coefficient brush: ``slip``, ``mu`` and ``stick_fraction`` (x_c/l), same shape."""

    slip: np.ndarray
    mu: np.ndarray
    stick_fraction: np.ndarray
    mu_static: float
    mu_dynamic: float
    initial_slope: float
    sakai_n: float
    citations: tuple = (PACEJKA_BOOK, SAKAI_1981)


def _sakai_nodes(n: float, n_points: int):
    c = Contact(1.0, 1.0, 1.0, {"sakai_n": n}, n_points=n_points)
    return c._xi, c._g, c._G


@doi(PACEJKA_BOOK, SAKAI_1981)
def two_coefficient_mu(slip, *, mu_static: float, mu_dynamic: float, initial_slope: float,
                       sakai_n: float = 4.0, n_points: int = 401) -> BrushCurve:
    r"""Two-coefficient brush: stick up to the static limit :math:`\mu_s p`, slide with :math:`\mu_D p`.

    Same kinematics as :func:`mu_slip` (bristle displacement :math:`\theta x`, :math:`\theta = s/(1-s)`); the
    bristles stick while :math:`k\theta x < \mu_s p(x)` and slide behind the first point where the static
    limit is reached, with shear :math:`\mu_D p(x)`; Sakai's n-power pressure (n = 4 by default). In terms of the
    initial slope :math:`C_0 = k l/(2\sigma_0)`:

    .. math:: \mu(s) = C_0\theta\xi_c^2 + \mu_D\left[1 - \int_0^{\xi_c} \frac{p}{\sigma_0} d\xi\right],\qquad
        2C_0\theta\,\xi_c = \mu_s\, p(\xi_c)/\sigma_0 .

    With :math:`\mu_D < \mu_s` the curve has a peak above :math:`\mu_D` and falls to :math:`\mu_D` at full sliding.

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
    """
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
    xi, g, G = _sakai_nodes(number(sakai_n, "sakai_n"), n_points)
    sf = s.ravel().astype(float)
    with np.errstate(divide="ignore"):
        theta = np.where(sf < 1.0, sf / np.where(sf < 1.0, 1.0 - sf, 1.0), np.inf)
    a = 2.0 * c0 * theta
    mu, xc, _ = _brush(xi, g, G, a, np.full(sf.size, ms), np.full(sf.size, md))
    return BrushCurve(slip=s, mu=mu.reshape(s.shape), stick_fraction=xc.reshape(s.shape), mu_static=ms,
                      mu_dynamic=md, initial_slope=c0, sakai_n=float(sakai_n))


@dataclass(frozen=True, eq=False)
class BrushMap:
    r"""Peak of the two-coefficient brush over :math:`n_1 = \mu_D/\mu_s` and :math:`n_2 = C_0/\mu_s`.

    Attributes
    ----------
    n1 : ndarray (k,)
    n2 : ndarray (m,)
    peak_ratio : ndarray (k, m)
        :math:`\mu_{peak}/\mu_s`.
    slip_at_peak : ndarray (k, m)
        Slip ratio of the peak (the first slip reaching the maximum when the curve has a plateau).
    locked_ratio : ndarray (k,)
        :math:`\mu(s=1)/\mu_s = n_1`.
    sakai_n : float
    """

    n1: np.ndarray
    n2: np.ndarray
    peak_ratio: np.ndarray
    slip_at_peak: np.ndarray
    locked_ratio: np.ndarray
    sakai_n: float
    citations: tuple = (PACEJKA_BOOK, SAKAI_1981)

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


@doi(PACEJKA_BOOK, SAKAI_1981)
def two_coefficient_map(n1, n2, *, sakai_n: float = 4.0, n_slip: int = 400, n_points: int = 401) -> BrushMap:
    r"""Map of the peak :math:`\mu_{peak}/\mu_s` and the slip at the peak of the two-coefficient brush.

    With :math:`\mu_s = 1` the curve is :math:`n_2\theta\xi_c^2 + n_1[1 - G(\xi_c)]`, where the stick length
    :math:`\xi_c` (and the load fraction :math:`G(\xi_c)` ahead of it) depends on :math:`n_2\theta` only; the
    maximum over s is searched on ``n_slip`` log-spaced slips in [1e-4, 1] and refined locally (41 slips; the slip
    of the peak then by a parabola through the three best). Because the curve depends on :math:`n_2\theta`
    only, the peak ratio depends on :math:`n_1` (and n) alone and :math:`\theta_{peak} \propto 1/n_2`
    (:math:`\theta = s/(1-s)`); the map shows it over the grid all the same.

    Parameters
    ----------
    n1 : array_like
        :math:`\mu_D/\mu_s`, increasing, > 0 (<= 1 for a peak).
    n2 : array_like
        Initial slope / :math:`\mu_s`, increasing, > 0.
    sakai_n : float
        Exponent of Sakai's pressure law (default 4).
    """
    n1 = _increasing(n1, "n1")
    n2 = _increasing(n2, "n2")
    if np.any(n1 <= 0):
        raise InputError("n1: expected mu_D / mu_s > 0")
    if np.any(n2 <= 0):
        raise InputError("n2: expected initial slope / mu_s > 0")
    if isinstance(n_slip, bool) or not isinstance(n_slip, (int, np.integer)) or n_slip < 20:
        raise InputError(f"n_slip: expected an integer >= 20, got {n_slip!r}")
    xi, g, G = _sakai_nodes(number(sakai_n, "sakai_n"), n_points)
    s = np.geomspace(1e-4, 1.0, int(n_slip))

    def ratio(n1v, n2v, sv):
        """mu/mu_s for broadcastable n1, n2, s arrays (all same final shape)."""
        n1v, n2v, sv = np.broadcast_arrays(n1v, n2v, sv)
        sf = sv.ravel()
        with np.errstate(divide="ignore"):
            theta = np.where(sf < 1.0, sf / np.where(sf < 1.0, 1.0 - sf, 1.0), np.inf)
        a = 2.0 * n2v.ravel() * theta
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
    slip_at_peak = np.where(ok, np.exp(xv), sbest)
    return BrushMap(n1=n1, n2=n2, peak_ratio=peak_ratio, slip_at_peak=np.minimum(slip_at_peak, 1.0),
                    locked_ratio=n1.copy(), sakai_n=float(sakai_n))
