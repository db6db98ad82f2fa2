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
conduction into the tread and the counter-surface; see :mod:`persson.effects.patch`). The friction is then
tabulated once per call over (sliding speed, pressure, temperature) and interpolated; ``slip = 1`` is the
locked wheel, the patch average of the heated sliding friction (the limit of the curve). :func:`fit_slip` fits
contact and effect parameters of such a model to measured curves, with standard errors.

Also here: the two-coefficient brush used to analyse trailer data (static limit :math:`\mu_s` in the stick zone,
dynamic :math:`\mu_D` in the slide zone, Sakai's n = 4 pressure) and its map over
:math:`n_1 = \mu_D/\mu_s` and :math:`n_2 = (\text{initial slope})/\mu_s`; :func:`fit_brush`, the brush model with a
Stribeck-type sliding friction fitted to a measured curve alone; and the DRFT kinematics (braking and driving).

Magic Formula fits, friction-speed laws and curve peaks are in :mod:`persson.tire`; plots in
:mod:`persson.slip_plots`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from frictioncite import citations_of, doi

from ._checks import finite_array, number, positive
from .errors import InputError
from .tire import FitResult, NamedParameters

__all__ = [
    "Contact", "SlipResult", "mu_slip", "brush_mu", "BrushCurve", "two_coefficient_mu", "BrushMap",
    "two_coefficient_map", "Kinematics", "drft_kinematics", "drft_from_angular", "drft_speeds",
    "PatchProfile", "CONTACT_PARAMETERS", "stribeck_brush_mu", "fit_brush", "BrushFit", "fit_slip", "SlipFit",
    "predict_slip", "PACEJKA_BOOK", "SAKAI_1981", "CANUDAS_2003",
]

#: H. B. Pacejka, Tire and Vehicle Dynamics (3rd ed., 2012), brush model: chapter 3.
PACEJKA_BOOK = "isbn:9780080970165"
#: H. Sakai, Theoretical and experimental studies on the dynamic properties of tyres (Int. J. Vehicle Design, 1981).
SAKAI_1981 = "sakai:ijvd-1981"
#: C. Canudas-de-Wit, P. Tsiotras, E. Velenis, M. Basset, G. Gissinger, Dynamic friction models for road/tire
#: longitudinal interaction, Vehicle System Dynamics 39 (3), 189-226 (2003): Stribeck-type friction of the
#: brush elements, g(v) = mu_C + (mu_S - mu_C) exp(-|v/v_s|^alpha).
CANUDAS_2003 = "10.1076/vesd.39.3.189.14152"

_MAX_CELLS = 2_000_000  # rows x nodes per vectorised block of the brush integral


# =========================================================================================================
# Contact
# =========================================================================================================
@doi(PACEJKA_BOOK)
@dataclass(frozen=True)
class Contact:
    r"""Contact patch of the brush model.

    Parameters
    ----------
    length : float
        Contact length :math:`l` in the rolling direction, m (> 0).
    width : float
        Contact width :math:`w`, m (> 0). The friction coefficient does not depend on it; forces do
        (load :math:`\sigma_0 l w`).
    stiffness : float
        Shear stiffness of the tread per unit contact area per unit displacement, :math:`k`, Pa/m (> 0).
        For a rubber layer of shear modulus G and thickness h, :math:`k \approx G/h` (tread + carcass
        compliance in series lower it). The initial slope of mu(s) is :math:`k l/(2\sigma_0)`.
    pressure_distribution : str, dict or callable
        ``"parabolic"`` (default): :math:`p = 6\sigma_0 (x/l)(1-x/l)`;
        ``"uniform"``: :math:`p = \sigma_0`;
        ``{"sakai_n": n}`` (n > 0): Sakai's n-power law
        :math:`p(x) = \sigma_0 \frac{n+1}{n}\left[1 - \left|2x/l - 1\right|^n\right]`, normalised to the mean
        :math:`\sigma_0` (the mean of :math:`1-|\xi|^n` on [-1, 1] is n/(n+1)). n = 2 is the parabolic law,
        larger n flatter, towards the uniform law as n -> infinity. Source: H. Sakai, Int. J. Vehicle Design
        2 (1981) ("Sakai's n-power form"; the absolute value makes odd and
        non-integer n symmetric; for even n it is Sakai's polynomial);
        a callable ``f(xi)``: the shape :math:`p/\sigma_0` as a function of :math:`\xi = x/l \in [0, 1]`
        (vectorised, finite, >= 0); it must integrate to the load, i.e. :math:`\int_0^1 f\,d\xi = 1`
        within 0.1 %.
    n_points : int
        Nodes along the patch (>= 11, default 401; error of mu about 1e-5 for the parabolic law).

    Raises
    ------
    InputError
        Naming the argument: non-positive or non-finite sizes or stiffness, an unknown distribution, a negative
        pressure, or a pressure that does not integrate to the load.
    """

    length: float
    width: float
    stiffness: float
    pressure_distribution: object = "parabolic"
    n_points: int = 401
    _kind: str = field(init=False, repr=False, compare=False, default="")
    _sakai_n: float = field(init=False, repr=False, compare=False, default=float("nan"))
    _xi: np.ndarray = field(init=False, repr=False, compare=False, default=None)
    _g: np.ndarray = field(init=False, repr=False, compare=False, default=None)
    _G: np.ndarray = field(init=False, repr=False, compare=False, default=None)
    _shape: object = field(init=False, repr=False, compare=False, default=None)

    def __post_init__(self):
        for name in ("length", "width", "stiffness"):
            v = number(getattr(self, name), f"contact.{name}")
            if v <= 0:
                raise InputError(f"contact.{name}: expected a value > 0, got {v:g}")
            object.__setattr__(self, name, v)
        n = self.n_points
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 11:
            raise InputError(f"contact.n_points: expected an integer >= 11, got {n!r}")
        object.__setattr__(self, "n_points", int(n))
        kind, sakai_n, shape = _parse_distribution(self.pressure_distribution)
        object.__setattr__(self, "_kind", kind)
        object.__setattr__(self, "_sakai_n", sakai_n)
        xi = np.linspace(0.0, 1.0, self.n_points)
        g = np.asarray(shape(xi), dtype=float)
        if g.shape != xi.shape or not np.all(np.isfinite(g)) or np.any(g < 0):
            raise InputError("contact.pressure_distribution: the pressure must be finite and >= 0 on 0 <= x <= l")
        h = np.diff(xi)
        G = np.concatenate(([0.0], np.cumsum(0.5 * h * (g[1:] + g[:-1]))))
        if not G[-1] > 0:
            raise InputError("contact.pressure_distribution: the pressure is zero everywhere on the patch")
        # normalise the discrete load to exactly sigma0 l (the continuous one was checked to 0.1 %)
        object.__setattr__(self, "_xi", xi)
        object.__setattr__(self, "_g", g / G[-1])
        object.__setattr__(self, "_G", G / G[-1])
        object.__setattr__(self, "_shape", shape)

    def __hash__(self):
        return hash((self.length, self.width, self.stiffness, repr(self.pressure_distribution), self.n_points))

    # ------------------------------------------------------------------------------------------------------
    @property
    def kind(self) -> str:
        """``"uniform"``, ``"parabolic"``, ``"sakai"`` or ``"custom"``."""
        return self._kind

    @property
    def sakai_n(self) -> float | None:
        """Exponent n of Sakai's law (2 for ``"parabolic"``, None for uniform and custom)."""
        if self._kind == "parabolic":
            return 2.0
        return self._sakai_n if self._kind == "sakai" else None

    @property
    def citations(self) -> tuple[str, ...]:
        """References of the brush model (and of Sakai's pressure law when used)."""
        return (PACEJKA_BOOK, SAKAI_1981) if self._kind == "sakai" else (PACEJKA_BOOK,)

    def shape(self, xi) -> np.ndarray:
        r"""Pressure shape :math:`p/\sigma_0` at :math:`\xi = x/l` (zero outside [0, 1]); mean 1 on [0, 1]."""
        xi = np.asarray(xi, dtype=float)
        f = self._shape
        inside = (xi >= 0) & (xi <= 1)
        out = np.zeros_like(xi)
        out[inside] = np.asarray(f(xi[inside]), dtype=float)
        return out

    def pressure(self, x, pressure: float) -> np.ndarray:
        """Normal pressure p(x), Pa, at distance ``x`` (m) from the leading edge, for the mean ``pressure``."""
        sigma0 = positive(pressure, "pressure")
        return sigma0 * self.shape(np.asarray(x, dtype=float) / self.length)

    def load(self, pressure: float) -> float:
        """Normal load sigma0 l w, N."""
        return positive(pressure, "pressure") * self.length * self.width

    def initial_slope(self, pressure: float) -> float:
        r"""Initial slope :math:`d\mu/ds|_{s\to 0} = k l / (2\sigma_0)` of the brush model."""
        return self.stiffness * self.length / (2.0 * positive(pressure, "pressure"))

    def full_sliding_slip(self, mu: float, pressure: float) -> float:
        r"""Slip at which the stick zone vanishes for a **constant** local friction ``mu``.

        For a pressure that vanishes at the leading edge, :math:`\theta_{sl} = \mu\, p'(0)/k`, i.e.
        :math:`6\mu\sigma_0/(kl)` (parabolic) and :math:`2(n+1)\mu\sigma_0/(kl)` (Sakai), and
        :math:`s_{sl} = \theta_{sl}/(1+\theta_{sl})`. With a pressure > 0 at the leading edge (uniform) some of the
        patch sticks at every slip < 1, and 1.0 is returned. For a custom shape p'(0) is estimated from the
        first node.
        """
        mu = number(mu, "mu")
        sigma0 = positive(pressure, "pressure")
        if mu < 0:
            raise InputError(f"mu: expected a friction coefficient >= 0, got {mu:g}")
        if self._kind == "uniform" or self._g[0] > 0:
            return 1.0
        if self._kind == "parabolic":
            dg0 = 6.0
        elif self._kind == "sakai":
            dg0 = 2.0 * (self._sakai_n + 1.0)
        else:
            dg0 = self._g[1] / self._xi[1]
        theta = mu * sigma0 * dg0 / (self.stiffness * self.length)
        return theta / (1.0 + theta)

    # ------------------------------------------------------------------------------------------------------
    def parameter_values(self) -> dict[str, float]:
        """The fittable contact parameters (:data:`CONTACT_PARAMETERS`) and their values; ``sakai_n`` only for a
        parabolic (n = 2) or Sakai pressure."""
        out = {"length": self.length, "stiffness": self.stiffness}
        if self.sakai_n is not None:
            out["sakai_n"] = float(self.sakai_n)
        return out

    def with_parameters(self, **values) -> "Contact":
        """Copy with some parameters changed: ``length``, ``width``, ``stiffness``, ``n_points``,
        ``pressure_distribution``, or ``sakai_n`` (sets the pressure to Sakai's law with that exponent; a parabolic
        contact is Sakai's n = 2). Validated like the constructor (InputError naming the parameter)."""
        import dataclasses

        known = {"length", "width", "stiffness", "n_points", "pressure_distribution", "sakai_n"}
        unknown = sorted(set(values) - known)
        if unknown:
            raise InputError(f"contact: unknown parameter(s) {unknown}; known: {sorted(known)}")
        if "sakai_n" in values:
            if "pressure_distribution" in values:
                raise InputError("contact: give sakai_n or pressure_distribution, not both")
            if self._kind not in ("parabolic", "sakai"):
                raise InputError(f"contact.sakai_n: the contact's pressure is {self._kind!r}, not Sakai's n-power law")
            values = dict(values)
            values["pressure_distribution"] = {"sakai_n": number(values.pop("sakai_n"), "contact.sakai_n")}
        return dataclasses.replace(self, **values)


def _contact_parameters():
    from .effects.base import Parameter

    return (
        Parameter("length", 0.02, (1.0e-4, 1.0), "m", "contact length l in the rolling direction", log_scale=True,
                  plausible=(1.0e-3, 0.3)),
        Parameter("stiffness", 3.0e9, (1.0e5, 1.0e13), "Pa/m",
                  "shear stiffness k of the tread per unit area per unit displacement", log_scale=True,
                  plausible=(1.0e6, 1.0e11)),
        Parameter("sakai_n", 2.0, (0.5, 50.0), "1", "exponent of Sakai's pressure law (2: parabolic)",
                  log_scale=True, plausible=(1.0, 20.0)),
    )


#: The contact parameters a fit may vary (name, default, bounds, unit, meaning, log scale, plausible range: a
#: tread's k ~ G/h with G ~ 0.5-5 MPa, h ~ 1-20 mm; patches from a small test wheel to a truck tire), as for
#: effects: ``"contact.length"``, ``"contact.stiffness"``, ``"contact.sakai_n"`` in :func:`fit_slip`.
CONTACT_PARAMETERS = _contact_parameters()


def _parse_distribution(spec):
    """(kind, sakai_n, shape function of xi) of a pressure-distribution specification."""
    if isinstance(spec, str):
        key = spec.strip().lower()
        if key == "uniform":
            return "uniform", float("nan"), lambda xi: np.ones_like(np.asarray(xi, dtype=float))
        if key == "parabolic":
            return "parabolic", float("nan"), lambda xi: 6.0 * np.asarray(xi) * (1.0 - np.asarray(xi))
        raise InputError(f"contact.pressure_distribution: expected \"uniform\", \"parabolic\", "
                         f"{{\"sakai_n\": n}} or a callable, got {spec!r}")
    if isinstance(spec, dict):
        if set(spec) != {"sakai_n"}:
            raise InputError(f"contact.pressure_distribution: a mapping must be {{\"sakai_n\": n}}, got {spec!r}")
        n = number(spec["sakai_n"], "contact.pressure_distribution.sakai_n")
        if n <= 0:
            raise InputError(f"contact.pressure_distribution.sakai_n: expected n > 0, got {n:g}")

        def sakai(xi, n=n):
            xi = np.asarray(xi, dtype=float)
            return (n + 1.0) / n * (1.0 - np.abs(2.0 * xi - 1.0) ** n)

        return "sakai", n, sakai
    if callable(spec):
        xi = np.linspace(0.0, 1.0, 2001)
        try:
            g = np.asarray(spec(xi), dtype=float)
        except Exception as exc:  # noqa: BLE001  (a user function failing is bad input)
            raise InputError(f"contact.pressure_distribution: the callable failed on x/l in [0, 1]: {exc}") from None
        if g.shape != xi.shape or not np.all(np.isfinite(g)):
            raise InputError("contact.pressure_distribution: the callable must return finite values of the "
                             "shape of its argument x/l")
        if np.any(g < 0):
            raise InputError(f"contact.pressure_distribution: negative pressure at x/l = {xi[np.argmax(g < 0)]:.4g}")
        from scipy.integrate import simpson

        total = float(simpson(g, x=xi))
        if not abs(total - 1.0) <= 1e-3:
            raise InputError(f"contact.pressure_distribution: the pressure integrates to {total:.6g} times the load "
                             "sigma0*l*w; expected 1 (the shape p/sigma0 on x/l in [0, 1] must have mean 1)")
        return "custom", float("nan"), spec
    raise InputError(f"contact.pressure_distribution: expected \"uniform\", \"parabolic\", {{\"sakai_n\": n}} or "
                     f"a callable, got {spec!r}")


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
# mu(slip, V) from a friction model
# =========================================================================================================
@dataclass(frozen=True, eq=False)
class SlipResult:
    """Friction against slip ratio and speed from the brush model.

    Array attributes have the broadcast shape of the ``slip`` and ``speed`` arguments (floats when both are
    scalars).

    Attributes
    ----------
    slip : ndarray or float
        Braking slip ratio s = (V - omega r)/V.
    speed : ndarray or float
        Rolling reference speed V, m/s.
    sliding_speed : ndarray or float
        v_s = s V, m/s.
    mu : ndarray or float
        Friction coefficient of the wheel (longitudinal force / normal load).
    mu_local : ndarray or float
        Local sliding friction mu(v_s) of the friction model.
    stick_length : ndarray or float
        Length x_c of the stick (adhesion) zone from the leading edge, m; the slide zone is x_c < x <= l.
    stick_fraction : ndarray or float
        x_c / l (1: the whole patch sticks; 0: pure sliding).
    force : ndarray or float
        Longitudinal (braking) force mu sigma0 l w, N.
    load : float
        Normal load sigma0 l w, N.
    temperature, pressure : float
        Background temperature T0 (deg C) and mean pressure sigma0 (Pa) of the friction model.
    contact : Contact
    friction : FrictionResult or None
        The friction model's result at the distinct sliding speeds ``friction.speed`` (None for a plain
        function, and with patch heating, where the engine is evaluated on a table: see ``patch``).
    converged : bool
        Whether the friction model's self-consistent iterations converged at every sliding speed.
    notes : tuple of str
    citations : tuple of str
    patch : PatchProfile or None
        With patch heating: the temperature, shear and local friction along the patch for every (slip, speed).
    """

    slip: np.ndarray
    speed: np.ndarray
    sliding_speed: np.ndarray
    mu: np.ndarray
    mu_local: np.ndarray
    stick_length: np.ndarray
    stick_fraction: np.ndarray
    force: np.ndarray
    load: float
    temperature: float
    pressure: float
    contact: Contact
    friction: object = None
    converged: bool = True
    notes: tuple = ()
    citations: tuple = ()
    patch: object = None

    @property
    def slide_fraction(self):
        """1 - x_c / l, the fraction of the patch length that slides."""
        return 1.0 - self.stick_fraction

    def peak(self, axis: int = 0):
        """(peak mu, slip at peak) along ``axis`` (the axis over which the slip varies).

        See :func:`persson.tire.peak`.
        """
        from .tire import peak

        return peak(np.asarray(self.slip), np.asarray(self.mu), axis=axis)

    def as_table(self) -> dict[str, np.ndarray]:
        """Flat columns ``slip, speed_m_s, sliding_speed_m_s, mu, mu_local, stick_fraction, stick_length_m,
        force_N`` (and ``max_temperature_rise_K`` with patch heating)."""
        cols = {
            "slip": self.slip, "speed_m_s": self.speed, "sliding_speed_m_s": self.sliding_speed, "mu": self.mu,
            "mu_local": self.mu_local, "stick_fraction": self.stick_fraction, "stick_length_m": self.stick_length,
            "force_N": self.force,
        }
        if self.patch is not None:
            cols["max_temperature_rise_K"] = self.patch.max_rise
        return {k: np.atleast_1d(np.asarray(v, dtype=float)).ravel() for k, v in cols.items()}

    def to_csv(self, path, comments: tuple[str, ...] = ()):
        """Write :meth:`as_table` as a CSV (atomically), with the conditions and contact as comment lines."""
        from .io import write_csv

        c = self.contact
        head = (f"brush model: T0 = {self.temperature:g} C, sigma0 = {self.pressure:g} Pa, l = {c.length:g} m, "
                f"w = {c.width:g} m, k = {c.stiffness:g} Pa/m, pressure = {c.pressure_distribution!r}",)
        return write_csv(path, self.as_table(), comments=head + tuple(comments) + tuple(self.notes))


@dataclass(frozen=True, eq=False)
class PatchProfile:
    """What happens along the contact patch, for every (slip, speed) of a :func:`mu_slip` call with patch heating.

    Attributes
    ----------
    x : ndarray (N,)
        Distance from the leading edge, m (the contact's nodes).
    temperature : ndarray (..., N)
        Background temperature of the rubber at x, deg C (T0 in the stick zone); leading axes those of
        ``SlipResult.mu``.
    shear : ndarray (..., N)
        Shear stress over the mean pressure, tau(x)/sigma0 (k theta x / sigma0 in the stick zone).
    mu_local : ndarray (..., N)
        Local friction coefficient mu(v_s, p(x), T(x)) (at T0 in the stick zone: the sticking limit).
    pressure : ndarray (N,)
        p(x), Pa.
    max_rise : ndarray or float
        Largest background temperature rise along the patch, K.
    heating : persson.effects.PatchHeating
    table_points : int
        Engine evaluations spent on the friction table.
    engine_calls : int
    """

    x: np.ndarray
    temperature: np.ndarray
    shear: np.ndarray
    mu_local: np.ndarray
    pressure: np.ndarray
    max_rise: np.ndarray
    heating: object
    table_points: int
    engine_calls: int


@doi(PACEJKA_BOOK)
def mu_slip(model, slip, speed, *, temperature: float = 20.0, pressure: float = 0.3e6,
            contact: Contact, profiles: bool = True) -> SlipResult:
    r"""Friction coefficient against braking slip ratio and speed (steady-state brush model).

    Parameters
    ----------
    model : persson.Model or callable
        The local sliding friction :math:`\mu(v_s, T_0, \sigma_0)`: a :class:`persson.Model` (with its effects)
        or any object with ``friction(speed, temperature=, pressure=)`` returning ``.mu``; or a plain function
        ``mu(v_s)`` of an array of sliding speeds (then ``temperature`` is not used).
    slip : float or array_like
        Braking slip ratio s = (V - omega r)/V in (0, 1]; 1 is pure sliding.
    speed : float or array_like
        Rolling reference speed V, m/s (> 0). Broadcast against ``slip`` (e.g. ``slip[:, None]`` and
        ``speed[None, :]`` for a family of curves).
    temperature : float
        Background temperature T0, deg C.
    pressure : float
        Mean contact pressure sigma0, Pa (> 0): the pressure of the friction model and of the brush.
    contact : Contact
        The contact patch.
    profiles : bool
        With patch heating, keep the profiles along the patch (``SlipResult.patch``; default True).

    Returns
    -------
    SlipResult
        ``.mu`` etc. with the broadcast shape of ``slip`` and ``speed``; the friction model is evaluated once,
        at the distinct sliding speeds s V (with patch heating: once on a table over speed, pressure and
        temperature, plus once at T0 to bound the heating; see :func:`persson.effects.patch.patch_friction`).

    Raises
    ------
    InputError
        Slip outside (0, 1], speed <= 0, non-finite values, pressure <= 0, a contact that is not a
        :class:`Contact`, or a friction model returning negative or non-finite friction.
    """
    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    s = _slip_array(slip)
    V = _speed_array(speed)
    T0 = number(temperature, "temperature")
    sigma0 = positive(pressure, "pressure")
    try:
        s_b, V_b = np.broadcast_arrays(s, V)
    except ValueError:
        raise InputError(f"slip, speed: shapes {s.shape} and {V.shape} do not broadcast") from None
    shape = s_b.shape
    scalar = shape == ()
    s_f = s_b.ravel().astype(float)
    V_f = V_b.ravel().astype(float)
    vs = s_f * V_f
    heating = _heating_of(model)
    if heating is not None:
        return _mu_slip_patch(model, heating, s_f, V_f, T0, sigma0, contact, shape, profiles)
    v_unique, inverse = _distinct(vs)
    mu_u, fr = _local_friction(model, v_unique, T0, sigma0)
    mu_loc = mu_u[inverse]
    a = _a_of(s_f, contact, sigma0)
    mu, xc, _ = _brush(contact._xi, contact._g, contact._G, a, mu_loc, mu_loc)
    load = contact.load(sigma0)

    def out(x):
        x = np.asarray(x, dtype=float).reshape(shape)
        return float(x) if scalar else x

    notes = tuple(getattr(fr, "notes", ()) or ())
    converged = bool(getattr(fr, "converged", True))
    return SlipResult(
        slip=out(s_f), speed=out(V_f), sliding_speed=out(vs), mu=out(mu), mu_local=out(mu_loc),
        stick_length=out(xc * contact.length), stick_fraction=out(xc), force=out(mu * load), load=load,
        temperature=T0, pressure=sigma0, contact=contact, friction=fr, converged=converged, notes=notes,
        citations=citations_of(mu_slip, contact.citations, fr if fr is not None else ()),
    )


def _heating_of(model):
    """The model's PatchHeating effect, or None."""
    names = getattr(model, "effect_names", ())
    if "patch_heating" in names:
        return model.effect("patch_heating")
    return None


def _mu_slip_patch(model, heating, s_f, V_f, T0, sigma0, contact, shape, profiles) -> SlipResult:
    from .effects.patch import patch_friction

    sol = patch_friction(model, heating, contact, s_f, V_f, T0, sigma0, profiles=profiles)
    scalar = shape == ()
    load = contact.load(sigma0)

    def out(x):
        x = np.asarray(x, dtype=float).reshape(shape)
        return float(x) if scalar else x

    prof = None
    if profiles:
        N = sol.xi.size
        prof = PatchProfile(x=sol.xi * contact.length, temperature=sol.temperature.reshape(shape + (N,)),
                            shear=sol.shear.reshape(shape + (N,)), mu_local=sol.mu_profile.reshape(shape + (N,)),
                            pressure=sigma0 * contact._g.copy(), max_rise=out(sol.max_rise), heating=heating,
                            table_points=sol.table_points, engine_calls=sol.engine_calls)
    vs = s_f * V_f
    return SlipResult(
        slip=out(s_f), speed=out(V_f), sliding_speed=out(vs), mu=out(sol.mu), mu_local=out(sol.mu_local),
        stick_length=out(sol.stick_fraction * contact.length), stick_fraction=out(sol.stick_fraction),
        force=out(sol.mu * load), load=load, temperature=T0, pressure=sigma0, contact=contact, friction=None,
        converged=sol.converged, notes=sol.notes,
        citations=citations_of(mu_slip, contact.citations, type(heating), model), patch=prof,
    )


def _distinct(v: np.ndarray, rtol: float = 1e-12):
    """Distinct values of ``v`` (merging values within ``rtol``) and the index of each element in them."""
    order = np.argsort(v, kind="stable")
    vs = v[order]
    new = np.empty(vs.size, dtype=bool)
    new[0] = True
    new[1:] = vs[1:] > vs[:-1] * (1.0 + rtol)
    group = np.cumsum(new) - 1
    inverse = np.empty(v.size, dtype=np.intp)
    inverse[order] = group
    return np.ascontiguousarray(vs[new]), inverse


def _local_friction(model, v: np.ndarray, T0: float, sigma0: float):
    if hasattr(model, "friction"):
        fr = model.friction(v, temperature=T0, pressure=sigma0)
        mu = np.atleast_1d(np.asarray(fr.mu, dtype=float))
    elif callable(model):
        fr = None
        try:
            mu = np.asarray(model(v), dtype=float)
        except InputError:
            raise
        except Exception as exc:  # noqa: BLE001
            raise InputError(f"model: the friction function failed on the sliding speeds: {exc}") from None
        try:
            mu = np.broadcast_to(mu, v.shape).astype(float)
        except ValueError:
            raise InputError(f"model: the friction function returned shape {mu.shape} for {v.size} speeds") from None
    else:
        raise InputError("model: expected a persson.Model (or an object with friction(speed, temperature=, "
                         f"pressure=)) or a function mu(sliding_speed), got {model!r}")
    if mu.shape != v.shape:
        raise InputError(f"model: friction returned {mu.shape} values for {v.size} sliding speeds")
    bad = ~np.isfinite(mu) | (mu < 0)
    if np.any(bad):
        j = int(np.argmax(bad))
        raise InputError(f"model: local sliding friction {mu[j]!r} at v_s = {v[j]:g} m/s; expected a finite "
                         "value >= 0")
    return mu, fr


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


def _parabola_vertex(x, y):
    """Vertex (x_v, y_v) of the parabola through three points (arrays stacked on axis 0) and a validity mask."""
    x0, x1, x2 = x
    y0, y1, y2 = y
    d01 = (y1 - y0) / np.where(x1 != x0, x1 - x0, 1.0)
    d12 = (y2 - y1) / np.where(x2 != x1, x2 - x1, 1.0)
    c2 = (d12 - d01) / np.where(x2 != x0, x2 - x0, 1.0)
    ok = c2 < 0
    c2s = np.where(ok, c2, -1.0)
    # y = y1 + b (x - x1) + c2 (x - x0)(x - x1) ... written about x1: slope at x1 = d01 + c2 (x1 - x0)
    b1 = d01 + c2s * (x1 - x0)
    xv = x1 - b1 / (2.0 * c2s)
    yv = y1 - b1**2 / (4.0 * c2s)
    ok &= (xv >= x0) & (xv <= x2)
    return np.where(ok, xv, x1), np.where(ok, yv, y1), ok


# =========================================================================================================
# Brush model fitted to a measured curve (no friction model)
# =========================================================================================================
def _stribeck_law(slip, initial_slope, mu_static, mu_dynamic, slip_c, sakai_n, n_points=201):
    """mu(slip) of the Stribeck brush (see :func:`stribeck_brush_mu`), vectorised over slip."""
    s = np.asarray(slip, dtype=float)
    sf = s.ravel()
    xi, g, G = _sakai_nodes(float(sakai_n), n_points)
    with np.errstate(divide="ignore"):
        theta = np.where(sf < 1.0, sf / np.where(sf < 1.0, 1.0 - sf, 1.0), np.inf)
        decay = np.exp(-sf / slip_c) if slip_c > 0 else np.zeros_like(sf)
    slide = mu_dynamic + (mu_static - mu_dynamic) * decay
    mu, _, _ = _brush(xi, g, G, 2.0 * initial_slope * theta, np.full(sf.size, float(mu_static)), slide)
    return mu.reshape(s.shape)


@doi(PACEJKA_BOOK, SAKAI_1981, CANUDAS_2003)
def stribeck_brush_mu(slip, *, initial_slope: float, mu_static: float, mu_dynamic: float, slip_c: float,
                      sakai_n: float = 2.0, n_points: int = 201) -> BrushCurve:
    r"""Brush model whose sliding friction falls from the static to the dynamic value with the sliding speed.

    The brush of :func:`mu_slip` (bristle displacement :math:`\theta x`, :math:`\theta = s/(1-s)`, Sakai's
    pressure law, n = 2 parabolic) with the friction limit :math:`\mu_s p(x)` in the stick zone and, in the slide
    zone, the Stribeck-type law used for the brush elements of tire friction models (Canudas-de-Wit et al.,
    Vehicle System Dynamics 39, 189 (2003): :math:`g(v) = \mu_C + (\mu_S - \mu_C)e^{-|v/v_s|^\alpha}`), here with
    :math:`\alpha = 1` and at one rolling speed V, where :math:`v_s/v_c = s/s_c`:

    .. math:: \mu_{slide}(s) = \mu_D + (\mu_s - \mu_D)\,e^{-s/s_c}, \qquad
        \mu(s) = C_0\theta\xi_c^2 + \int_{\xi_c}^1 \mu_{slide}(s)\,\frac{p}{\sigma_0}\,d\xi,\quad
        2C_0\theta\xi_c = \mu_s\,p(\xi_c)/\sigma_0,

    :math:`C_0 = k l/(2\sigma_0)` the initial slope. ``slip_c = 0`` is the two-coefficient brush
    (:func:`two_coefficient_mu`). The curve rises with slope :math:`C_0`, peaks, and falls towards
    :math:`\mu_D + (\mu_s - \mu_D)e^{-1/s_c}` at the locked wheel.

    Parameters
    ----------
    slip : array_like
        Slip ratios in (0, 1].
    initial_slope : float
        :math:`C_0` (> 0).
    mu_static, mu_dynamic : float
        :math:`\mu_s > 0`, :math:`\mu_D \ge 0`.
    slip_c : float
        Decay slip :math:`s_c = v_c/V` (>= 0).
    sakai_n : float
        Exponent of Sakai's pressure law (2: parabolic).
    """
    s = _slip_array(slip)
    c0 = positive(initial_slope, "initial_slope")
    ms = positive(mu_static, "mu_static")
    md = number(mu_dynamic, "mu_dynamic")
    sc = number(slip_c, "slip_c")
    if md < 0:
        raise InputError(f"mu_dynamic: expected a value >= 0, got {md:g}")
    if sc < 0:
        raise InputError(f"slip_c: expected a value >= 0, got {sc:g}")
    n = positive(sakai_n, "sakai_n")
    xi, g, G = _sakai_nodes(n, n_points)
    sf = s.ravel().astype(float)
    with np.errstate(divide="ignore"):
        theta = np.where(sf < 1.0, sf / np.where(sf < 1.0, 1.0 - sf, 1.0), np.inf)
        decay = np.exp(-sf / sc) if sc > 0 else np.zeros_like(sf)
    mu, xc, _ = _brush(xi, g, G, 2.0 * c0 * theta, np.full(sf.size, ms), md + (ms - md) * decay)
    return BrushCurve(slip=s, mu=mu.reshape(s.shape), stick_fraction=xc.reshape(s.shape), mu_static=ms,
                      mu_dynamic=md, initial_slope=c0, sakai_n=n, citations=(PACEJKA_BOOK, SAKAI_1981, CANUDAS_2003))


@dataclass(frozen=True, eq=False)
class BrushFit(FitResult):
    """A brush-model fit (:func:`fit_brush`): parameters with standard errors and the curve's characteristics.

    Attributes (in addition to :class:`persson.tire.FitResult`)
    ----------------------------------------------------------
    peak_mu, peak_mu_std, slip_at_peak, slip_at_peak_std, locked_mu, locked_mu_std : float
        Largest mu on 0 < s <= 1, its slip, mu at s = 1, each with its standard uncertainty (linear
        propagation of the covariance).
    """

    peak_mu: float = 0.0
    peak_mu_std: float = 0.0
    slip_at_peak: float = 0.0
    slip_at_peak_std: float = 0.0
    locked_mu: float = 0.0
    locked_mu_std: float = 0.0

_BRUSH_BOUNDS = {"initial_slope": (1e-2, 1e5), "mu_static": (1e-3, 10.0), "mu_dynamic": (0.0, 10.0),
                 "slip_c": (1e-4, 100.0), "sakai_n": (0.5, 50.0)}


@doi(PACEJKA_BOOK, SAKAI_1981, CANUDAS_2003)
def fit_brush(slip, mu, *, sigma=None, law: str = "stribeck", sakai_n: float | None = 2.0, fixed: dict | None = None,
              p0: dict | None = None) -> "BrushFit":
    r"""Fit the brush model to a measured mu(slip) curve at one speed, with standard errors.

    Parameters
    ----------
    slip, mu : array_like
        Slip ratios in (0, 1] and friction coefficients (more points than free parameters).
    sigma : float or array_like, optional
        Standard uncertainties of ``mu``. Given: the covariance is absolute
        (:math:`(J^T W J)^{-1}`, :math:`W = \sigma^{-2}`); without: it is scaled by the residual variance
        :math:`\chi^2/(n - k)` (the misfit of the law is then part of the error).
    law : {"stribeck", "two_coefficient"}
        ``"stribeck"`` (default): :func:`stribeck_brush_mu`, parameters ``initial_slope``, ``mu_static``,
        ``mu_dynamic``, ``slip_c``, ``sakai_n``; ``"two_coefficient"``: the same with ``slip_c = 0``
        (:func:`two_coefficient_mu`).
    sakai_n : float or None
        Exponent of the pressure law held fixed (default 2, parabolic); None fits it.
    fixed : dict, optional
        Further parameters held fixed.
    p0 : dict, optional
        An extra starting point.

    Returns
    -------
    BrushFit
        ``values``/``stderr``/``covariance`` by parameter (``fit["mu_static"]``, ``fit.std("mu_static")``),
        ``rms``, ``dof`` and the peak, the slip at the peak and the locked-wheel value with their standard
        uncertainties. The standard errors come from the Jacobian at the optimum
        (:func:`scipy.optimize.curve_fit`).
    """
    from .tire import _curve_peak, _fit, _propagate, _xy

    x, y, sig = _xy(slip, mu, sigma, "slip")
    if np.any((x <= 0) | (x > 1)):
        raise InputError("slip: expected slip ratios in (0, 1] (1 = locked wheel)")
    if law not in ("stribeck", "two_coefficient"):
        raise InputError(f"law: expected \"stribeck\" or \"two_coefficient\", got {law!r}")
    fixed = dict(fixed or {})
    if sakai_n is not None:
        fixed.setdefault("sakai_n", positive(sakai_n, "sakai_n"))
    if law == "two_coefficient":
        fixed["slip_c"] = 0.0
    names = ("initial_slope", "mu_static", "mu_dynamic", "slip_c", "sakai_n")
    bounds = dict(_BRUSH_BOUNDS)
    if law == "two_coefficient":
        bounds["slip_c"] = (0.0, 0.0)
    # starting values from the data: the slope through the origin below half the peak slip, the peak, the tail
    j = int(np.argmax(y))
    sp = float(max(x[j], 1e-3))
    small = x <= 0.5 * sp
    c0 = float(np.sum(x[small] * y[small]) / np.sum(x[small] ** 2)) if np.any(small) else 2.0 * y[j] / sp
    c0 = float(np.clip(max(c0, y[j] / sp), 1e-2, 1e5))
    ytail = float(y[np.argmax(x)])
    starts = [dict(initial_slope=c0, mu_static=1.1 * y[j], mu_dynamic=ytail, slip_c=max(2 * sp, 1e-3), sakai_n=2.0),
              dict(initial_slope=c0, mu_static=1.3 * y[j], mu_dynamic=0.8 * ytail, slip_c=max(5 * sp, 1e-3),
                   sakai_n=4.0),
              dict(initial_slope=2 * c0, mu_static=y[j], mu_dynamic=ytail, slip_c=max(0.5 * sp, 1e-3), sakai_n=2.0)]
    if p0:
        starts.insert(0, {**starts[0], **{k: number(v, f"p0[{k!r}]") for k, v in p0.items()}})
    if "sakai_n" not in fixed:
        # the exponent free: start from the better of the fits with n = 2 and n = 4 held
        pre = []
        for n in (2.0, 4.0):
            try:
                pre.append(_fit(f"brush_{law}", _stribeck_law, names, bounds, x, y, sig, {**fixed, "sakai_n": n},
                                starts, (), tol=1e-9, maxfev=1000))
            except InputError:
                continue
        if pre:
            best = min(pre, key=lambda q: q["rms"])
            starts = [dict(zip(names, best["values"]))] + starts[:1]
    # the brush integral is piecewise smooth in the parameters (the stick boundary moves across the patch nodes):
    # tolerances at 1e-9 (tighter ones never trigger at the kinks) and a bounded number of evaluations per start
    parts = _fit(f"brush_{law}", _stribeck_law, names, bounds, x, y, sig, fixed, starts,
                 (PACEJKA_BOOK, SAKAI_1981, CANUDAS_2003), tol=1e-9, maxfev=1000)
    vals, cov = parts["values"], parts["covariance"]

    def pk(v):
        return _curve_peak(lambda ss: _stribeck_law(np.clip(ss, 1e-9, 1.0), *v), 1e-6, 1.0, 801)

    peak_mu, peak_std = _propagate(lambda v: pk(v)[0], vals, cov)
    sp_, sp_std = _propagate(lambda v: pk(v)[1], vals, cov)
    lk, lk_std = _propagate(lambda v: float(_stribeck_law(1.0, *v)), vals, cov)
    return BrushFit(**parts, peak_mu=peak_mu, peak_mu_std=peak_std, slip_at_peak=sp_, slip_at_peak_std=sp_std,
                    locked_mu=lk, locked_mu_std=lk_std)


# =========================================================================================================
# Contact and effect parameters fitted through the friction model
# =========================================================================================================
@doi(PACEJKA_BOOK)
def predict_slip(model, slip, speed, *, temperature=20.0, pressure=0.3e6, contact: Contact, cache: dict | None = None):
    r"""Brush-model friction for rows with their own slip, speed, temperature and pressure (1D arrays, broadcast).

    With patch heating in ``model``: :func:`persson.effects.patch.patch_friction` (one table for all rows);
    without: the brush model with the engine's friction at each row's (v_s, T0, sigma0), one engine call.
    ``cache`` (a dict the caller keeps) reuses the engine's values while only the contact changes.

    Returns
    -------
    ndarray
        mu per row.
    """
    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    s = _slip_array(slip)
    V = _speed_array(speed)
    T = finite_array(temperature, "temperature")
    p = finite_array(pressure, "pressure")
    if np.any(p <= 0):
        raise InputError("pressure: expected mean pressures > 0 Pa")
    s, V, T, p = (a.ravel().astype(float) for a in _broadcast("slip, speed, temperature, pressure", s, V, T, p))
    heating = _heating_of(model)
    if heating is not None:
        from .effects.patch import patch_friction

        return patch_friction(model, heating, contact, s, V, T, p, tables=cache).mu
    from .effects.patch import engine_key

    pts = np.column_stack([s * V, T, p])
    key = pts.tobytes()
    ekey = engine_key(model)
    if cache is not None and cache.get("engine") == ekey and cache.get("key") == key:
        mu_loc = cache["value"]
    else:
        if not hasattr(model, "friction"):
            raise InputError(f"model: expected a persson.Model (or an object with friction(speed, temperature=, "
                             f"pressure=)), got {model!r}")
        uniq, inv = np.unique(pts, axis=0, return_inverse=True)
        r = model.friction(uniq[:, 0], temperature=uniq[:, 1], pressure=uniq[:, 2])
        m = np.atleast_1d(np.asarray(r.mu, dtype=float))
        if not np.all(np.isfinite(m) & (m >= 0)):
            raise InputError("model: non-finite or negative local friction")
        mu_loc = m[np.asarray(inv).ravel()]
        if cache is not None:
            cache.update(engine=ekey, key=key, value=mu_loc, model=model)
    with np.errstate(divide="ignore"):
        theta = np.where(s < 1.0, s / np.where(s < 1.0, 1.0 - s, 1.0), np.inf)
    a = contact.stiffness * contact.length / p * theta
    mu, _, _ = _brush(contact._xi, contact._g, contact._G, a, mu_loc, mu_loc)
    return mu


@dataclass(frozen=True, eq=False)
class SlipFit(NamedParameters):
    r"""Contact and effect parameters of a friction model fitted to measured mu(slip, V) (:func:`fit_slip`).

    Attributes
    ----------
    names : tuple of str
        Fitted parameters (``"contact.stiffness"``, ``"patch_heating.counter_effusivity"``, ``"gamma"``, ...).
    values, stderr : ndarray
        Best-fit values and standard uncertainties.
    covariance, correlation : ndarray (k, k)
    model, contact : the fitted model and contact
    predicted, residual : ndarray (n,)
    rms : float
        Root-mean-square residual.
    chi2 : float
        Weighted residual sum of squares (:math:`\sum r^2/\sigma^2`; the plain sum without ``sigma``).
    dof : int
        n - k.
    sigma : ndarray or None
        The standard uncertainties given.
    lack_of_fit_p : float or None
        With ``sigma``: :math:`P(\chi^2_{dof} \ge \chi^2)`, small when the model cannot describe the data within
        their uncertainties (None without ``sigma``).
    n_evaluations : int
    notes : tuple of str
    """

    names: tuple
    values: np.ndarray
    stderr: np.ndarray
    covariance: np.ndarray
    correlation: np.ndarray
    model: object
    contact: Contact
    predicted: np.ndarray
    residual: np.ndarray
    rms: float
    chi2: float
    dof: int
    sigma: np.ndarray | None
    lack_of_fit_p: float | None
    n_evaluations: int
    notes: tuple = ()

    @property
    def reduced_chi2(self) -> float:
        """chi2 / dof."""
        return self.chi2 / max(self.dof, 1)

    def summary(self) -> str:
        lines = [f"{n} = {v:.6g} +- {e:.3g}" for n, v, e in zip(self.names, self.values, self.stderr)]
        lines.append(f"rms {self.rms:.4g}, chi2 {self.chi2:.4g} on {self.dof} dof"
                     + (f", lack-of-fit p = {self.lack_of_fit_p:.3g}" if self.lack_of_fit_p is not None else ""))
        return "\n".join(lines + list(self.notes))

    def _index(self, name):
        try:
            return self.names.index(name)
        except ValueError:
            raise InputError(f"parameter: {name!r} was not fitted (fitted: {list(self.names)})") from None


def _fit_parameter(name: str, model, contact: Contact):
    """(spec, getter, setter) of a fit parameter name."""
    from .effects.base import Parameter

    if name == "gamma":
        spec = Parameter("gamma", 0.5, (0.0, 1.0), "1", "gamma of S(q)")
        return spec, (lambda m, c: float(m.gamma)), (lambda m, c, v: (m.replace(gamma=v), c))
    if "." not in name:
        raise InputError(f"vary: {name!r}: expected \"contact.<parameter>\", \"<effect>.<parameter>\" or \"gamma\"")
    owner, par = name.split(".", 1)
    if owner == "contact":
        specs = {p.name: p for p in CONTACT_PARAMETERS}
        if par not in specs:
            raise InputError(f"vary: {name!r}: the contact has {sorted(specs)}")
        if par == "sakai_n" and contact.sakai_n is None:
            raise InputError(f"vary: {name!r}: the contact's pressure is {contact.kind!r}, not Sakai's n-power law")
        return (specs[par], (lambda m, c: float(c.parameter_values()[par])),
                (lambda m, c, v: (m, c.with_parameters(**{par: v}))))
    if owner not in getattr(model, "effect_names", ()):
        raise InputError(f"vary: {name!r}: the model has no effect {owner!r} (has {list(model.effect_names)})")
    eff = model.effect(owner)
    specs = {p.name: p for p in eff.parameters}
    if par not in specs:
        raise InputError(f"vary: {name!r}: {owner} has the documented parameters {sorted(specs)}")
    return (specs[par], (lambda m, c: float(getattr(m.effect(owner), par))),
            (lambda m, c, v: (m.with_effect(m.effect(owner).with_parameters(**{par: v})), c)))


@doi(PACEJKA_BOOK)
def fit_slip(model, slip, speed, mu, *, temperature=20.0, pressure=0.3e6, contact: Contact,
             vary=("contact.stiffness",), sigma=None, p0: dict | None = None, bounds: dict | None = None,
             max_nfev: int = 200) -> SlipFit:
    r"""Fit contact and effect parameters of a friction model to measured mu(slip, V), with standard errors.

    Weighted least squares (:func:`scipy.optimize.least_squares`, trust region with bounds; log-scale parameters
    in log space) of the brush-model prediction :func:`predict_slip` (with patch heating when the model has it).
    The covariance is :math:`(J^TJ)^{-1}` of the weighted residuals at the optimum, :math:`J` by central
    differences (step 1e-3 of each scaled parameter), scaled by :math:`\chi^2/(n - k)` when ``sigma`` is not
    given.

    Parameters
    ----------
    model : persson.Model
    slip, speed, mu : array_like
        Measured rows (slip in (0, 1], V in m/s), broadcast together.
    temperature, pressure : float or array_like
        T0 (deg C) and sigma0 (Pa) per row.
    contact : Contact
    vary : sequence of str
        Parameters to fit: ``"contact.stiffness"``, ``"contact.length"``, ``"contact.sakai_n"``,
        ``"<effect>.<parameter>"`` (a documented parameter of an effect in the model, e.g.
        ``"patch_heating.counter_effusivity"``) or ``"gamma"``. Bounds and scales come from
        :data:`CONTACT_PARAMETERS` and the effects' :class:`~persson.effects.Parameter` specifications.
    sigma : float or array_like, optional
        Standard uncertainties of ``mu``.
    p0 : dict, optional
        Starting values by name (default: the current values).
    bounds : dict, optional
        ``name -> (lo, hi)`` narrowing the documented bounds.
    max_nfev : int
        Largest number of model evaluations of the optimiser.

    Returns
    -------
    SlipFit
    """
    from scipy.optimize import least_squares
    from scipy.stats import chi2 as chi2_dist

    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    s = _slip_array(slip)
    V = _speed_array(speed)
    y = finite_array(mu, "mu")
    T = finite_array(temperature, "temperature")
    p = finite_array(pressure, "pressure")
    s, V, y, T, p = (a.ravel().astype(float) for a in _broadcast("slip, speed, mu, temperature, pressure",
                                                                   s, V, y, T, p))
    n = y.size
    sig = None
    if sigma is not None:
        sig = np.broadcast_to(finite_array(sigma, "sigma").ravel(), y.shape).astype(float) \
            if np.size(sigma) in (1, n) else None
        if sig is None or np.any(sig <= 0):
            raise InputError(f"sigma: expected one value or {n} values, all > 0")
    names = tuple(vary)
    if not names:
        raise InputError("vary: expected at least one parameter to fit")
    if len(set(names)) != len(names):
        raise InputError(f"vary: parameters given twice in {list(names)}")
    k = len(names)
    if n <= k:
        raise InputError(f"mu: {n} rows cannot determine {k} parameters")
    pars = [_fit_parameter(nm, model, contact) for nm in names]
    lo = np.empty(k)
    hi = np.empty(k)
    logs = np.zeros(k, dtype=bool)
    x0 = np.empty(k)
    for i, (nm, (spec, get, _)) in enumerate(zip(names, pars)):
        a, b = (float(v) for v in spec.bounds)
        if bounds and nm in bounds:
            a, b = max(a, number(bounds[nm][0], f"bounds[{nm!r}]")), min(b, number(bounds[nm][1], f"bounds[{nm!r}]"))
        logs[i] = bool(spec.log_scale) and a > 0
        v0 = number(p0[nm], f"p0[{nm!r}]") if p0 and nm in p0 else get(model, contact)
        if not a <= v0 <= b:
            raise InputError(f"p0[{nm!r}]: {v0:g} lies outside the bounds [{a:g}, {b:g}] {spec.unit}")
        lo[i], hi[i] = (math.log(a), math.log(b)) if logs[i] else (a, b)
        x0[i] = math.log(v0) if logs[i] else v0
    w = 1.0 / sig if sig is not None else np.ones(n)
    cache: dict = {}
    count = [0]

    def build(x):
        m, c = model, contact
        for i, (_, _, setter) in enumerate(pars):
            v = math.exp(x[i]) if logs[i] else float(x[i])
            m, c = setter(m, c, v)
        return m, c

    def resid(x):
        m, c = build(np.clip(x, lo, hi))
        count[0] += 1
        return (predict_slip(m, s, V, temperature=T, pressure=p, contact=c, cache=cache) - y) * w

    span = np.where(np.isfinite(hi - lo), hi - lo, 1.0)
    x0 = np.clip(x0, lo + 1e-9 * span, hi - 1e-9 * span)
    res = least_squares(resid, x0, bounds=(lo, hi), method="trf", x_scale="jac", diff_step=1e-4,
                        max_nfev=int(max_nfev), xtol=1e-10, ftol=1e-12, gtol=1e-10)
    x = res.x
    r0 = resid(x)
    # Jacobian by central differences at the optimum (steps inside the bounds)
    J = np.empty((n, k))
    for i in range(k):
        h = 1e-3 * max(1.0, abs(x[i])) if not logs[i] else 1e-3
        up, dn = x.copy(), x.copy()
        up[i] = min(x[i] + h, hi[i])
        dn[i] = max(x[i] - h, lo[i])
        J[:, i] = (resid(up) - resid(dn)) / (up[i] - dn[i])
    chi2 = float(r0 @ r0)
    dof = n - k
    notes = []
    try:
        cov_x = np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov_x = np.linalg.pinv(J.T @ J)
        notes.append("the parameters are not all determined by the data (singular normal matrix)")
    if sig is None:
        cov_x = cov_x * chi2 / max(dof, 1)
    vals = np.where(logs, np.exp(x), x)
    D = np.where(logs, vals, 1.0)
    cov = cov_x * D[:, None] * D[None, :]
    std = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(std, std)
    corr = np.where(np.isfinite(corr), corr, 0.0)
    at_bound = [nm for i, nm in enumerate(names) if min(x[i] - lo[i], hi[i] - x[i]) < 1e-6 * span[i]]
    if at_bound:
        notes.append(f"parameter(s) {at_bound} at their bound; their uncertainties are not meaningful")
    if not res.success:
        notes.append(f"the optimiser stopped: {res.message}")
    m_fit, c_fit = build(x)
    pred = y + r0 / w
    p_lof = float(chi2_dist.sf(chi2, dof)) if sig is not None else None
    return SlipFit(names=names, values=vals, stderr=std, covariance=cov, correlation=corr, model=m_fit,
                   contact=c_fit, predicted=pred, residual=y - pred, rms=float(np.sqrt(np.mean((y - pred) ** 2))),
                   chi2=chi2, dof=dof, sigma=sig, lack_of_fit_p=p_lof, n_evaluations=count[0], notes=tuple(notes))


# =========================================================================================================
# DRFT kinematics
# =========================================================================================================
@doi(PACEJKA_BOOK)
@dataclass(frozen=True, eq=False)
class Kinematics:
    r"""Wheel-on-disk (DRFT) or wheel-on-road kinematics of longitudinal slip, braking and driving.

    Speeds are magnitudes along the rolling direction. :math:`V` is the rolling reference speed: the surface
    speed of the counter-surface under the wheel centre (:math:`V = \Omega_{disk} R_{track}` on a DRFT, the
    vehicle speed on a road); :math:`V_w = \omega r` the circumferential speed of the wheel (r its effective
    rolling radius). Braking: :math:`V_w < V`; driving: :math:`V_w > V`; free rolling: :math:`V_w = V`.

    Attributes
    ----------
    speed : ndarray or float
        V, m/s (> 0).
    wheel_speed : ndarray or float
        :math:`V_w = \omega r`, m/s (>= 0).
    slip : ndarray or float
        Braking slip ratio :math:`s = (V - V_w)/V` (the convention of docs/slip.md and the ``slip`` column of measurements):
        0 free rolling, 1 locked wheel (pure sliding); negative when driving.
    longitudinal_slip : ndarray or float
        :math:`\kappa = (V_w - V)/V = -s`, the SAE J670 / ISO 8855 sign used by Pacejka's Magic Formula: positive
        when driving, -1 for a locked wheel.
    driving_slip : ndarray or float
        :math:`s_d = (V_w - V)/V_w` when driving (0 when braking): 0 free rolling, 1 a wheel spinning on a
        standing surface.
    sliding_speed : ndarray or float
        :math:`v_s = |V - V_w|`, m/s (= sV when braking).
    theoretical_slip : ndarray or float
        :math:`\theta = |V - V_w|/V_w`, the bristle displacement per unit distance from the leading edge of the
        brush model (:math:`s/(1-s)` braking, :math:`s_d` driving; inf for a locked wheel).
    braking, driving : ndarray or bool
        Which rows brake (:math:`V_w < V`) and which drive (:math:`V_w > V`).
    omega_wheel, omega_disk : ndarray or float or None
        Angular speeds, rad/s, when the radii are known.
    """

    speed: np.ndarray
    wheel_speed: np.ndarray
    slip: np.ndarray
    sliding_speed: np.ndarray
    omega_wheel: np.ndarray | None = None
    omega_disk: np.ndarray | None = None
    longitudinal_slip: np.ndarray | None = None
    driving_slip: np.ndarray | None = None
    theoretical_slip: np.ndarray | None = None
    braking: np.ndarray | None = None
    driving: np.ndarray | None = None


def _kinematics(Vw: np.ndarray, V: np.ndarray, **angular) -> Kinematics:
    vs = np.abs(V - Vw)
    s = (V - Vw) / V
    drive = Vw > V
    with np.errstate(divide="ignore", invalid="ignore"):
        theta = np.where(Vw > 0, vs / np.where(Vw > 0, Vw, 1.0), np.inf)
        sd = np.where(drive, (Vw - V) / np.where(drive, Vw, 1.0), 0.0)
    b = Vw < V
    return Kinematics(speed=_sc(V), wheel_speed=_sc(Vw), slip=_sc(s), sliding_speed=_sc(vs),
                      longitudinal_slip=_sc((Vw - V) / V), driving_slip=_sc(sd), theoretical_slip=_sc(theta),
                      braking=b if b.ndim else bool(b), driving=drive if drive.ndim else bool(drive), **angular)


@doi(PACEJKA_BOOK)
def drft_kinematics(wheel_speed, disk_speed) -> Kinematics:
    r"""Slip ratios and sliding speed from the wheel's circumferential speed and the disk's surface speed (m/s).

    ``disk_speed`` is V (the counter-surface speed under the wheel centre), ``wheel_speed`` :math:`V_w = \omega r`.
    Braking (:math:`V_w < V`) gives ``slip`` in (0, 1]; driving (:math:`V_w > V`) a negative ``slip`` and
    ``driving_slip`` in (0, 1) (see :class:`Kinematics` for every convention). The brush model
    (:func:`mu_slip`) takes the braking rows.

    Raises
    ------
    InputError
        ``disk_speed`` <= 0, ``wheel_speed`` < 0, or shapes that do not broadcast.
    """
    Vw = finite_array(wheel_speed, "wheel_speed")
    V = finite_array(disk_speed, "disk_speed")
    if np.any(V <= 0):
        raise InputError(f"disk_speed: expected a surface speed > 0 m/s, got {np.min(V):g}")
    if np.any(Vw < 0):
        raise InputError(f"wheel_speed: expected a circumferential speed >= 0 m/s, got {np.min(Vw):g}")
    Vw, V = _broadcast("wheel_speed, disk_speed", Vw, V)
    return _kinematics(Vw.astype(float), V.astype(float))


@doi(PACEJKA_BOOK)
def drft_from_angular(omega_wheel, omega_disk, *, wheel_radius: float, track_radius: float) -> Kinematics:
    r"""Kinematics from angular speeds (rad/s, magnitudes), the wheel's effective rolling radius r and the track
    radius R (the distance from the disk axis to the wheel centre line), m: :math:`V = \Omega_{disk} R`,
    :math:`V_w = \omega r`. See :func:`drft_kinematics`."""
    r = positive(wheel_radius, "wheel_radius")
    R = positive(track_radius, "track_radius")
    ww = finite_array(omega_wheel, "omega_wheel")
    wd = finite_array(omega_disk, "omega_disk")
    if np.any(wd <= 0):
        raise InputError(f"omega_disk: expected an angular speed > 0 rad/s, got {np.min(wd):g}")
    if np.any(ww < 0):
        raise InputError(f"omega_wheel: expected an angular speed >= 0 rad/s, got {np.min(ww):g}")
    ww, wd = _broadcast("omega_wheel, omega_disk", ww, wd)
    return _kinematics(ww * r, wd * R, omega_wheel=_sc(ww), omega_disk=_sc(wd))


@doi(PACEJKA_BOOK)
def drft_speeds(slip, speed, *, wheel_radius: float | None = None, track_radius: float | None = None) -> Kinematics:
    r"""Wheel speed, sliding speed (and angular speeds, when the radii are given) for a slip ratio and speed V.

    ``slip`` is the braking slip :math:`s = (V - V_w)/V <= 1` (0 free rolling, 1 locked wheel; negative values
    are driving: :math:`V_w = (1 - s)V > V`), ``speed`` V > 0 m/s.
    """
    s = finite_array(slip, "slip")
    if np.any(s > 1):
        raise InputError(f"slip: expected slip ratios s = (V - omega r)/V <= 1 (1 = locked wheel), got "
                         f"{s[s > 1].ravel()[0]:g}")
    V = _speed_array(speed)
    s, V = _broadcast("slip, speed", s, V)
    Vw = (1.0 - s) * V
    ang = {}
    if wheel_radius is not None:
        ang["omega_wheel"] = _sc(Vw / positive(wheel_radius, "wheel_radius"))
    if track_radius is not None:
        ang["omega_disk"] = _sc(V / positive(track_radius, "track_radius"))
    return _kinematics(Vw.astype(float), V.astype(float), **ang)


# =========================================================================================================
# validation helpers
# =========================================================================================================
def _slip_array(slip) -> np.ndarray:
    s = finite_array(slip, "slip")
    bad = (s <= 0) | (s > 1)
    if np.any(bad):
        j = int(np.argmax(bad.ravel()))
        raise InputError(f"slip: expected slip ratios in (0, 1] (1 = pure sliding), got {s.ravel()[j]:g} at index {j}")
    return s


def _speed_array(speed) -> np.ndarray:
    V = finite_array(speed, "speed")
    bad = V <= 0
    if np.any(bad):
        j = int(np.argmax(bad.ravel()))
        raise InputError(f"speed: expected speeds > 0 m/s, got {V.ravel()[j]:g} at index {j}")
    return V


def _mu_array(mu, name: str) -> np.ndarray:
    m = finite_array(mu, name)
    if np.any(m < 0):
        raise InputError(f"{name}: expected friction coefficients >= 0, got {np.min(m):g}")
    return m


def _increasing(values, name: str) -> np.ndarray:
    a = finite_array(values, name).ravel()
    if a.size < 2 or np.any(np.diff(a) <= 0):
        raise InputError(f"{name}: expected at least two strictly increasing values")
    return a


def _broadcast(names: str, *arrays):
    """np.broadcast_arrays, or InputError naming the arguments when their shapes do not broadcast."""
    try:
        return np.broadcast_arrays(*arrays)
    except ValueError:
        shapes = " and ".join(str(np.shape(a)) for a in arrays)
        raise InputError(f"{names}: shapes {shapes} do not broadcast") from None


def _sc(a):
    a = np.asarray(a, dtype=float)
    return float(a) if a.ndim == 0 else a
