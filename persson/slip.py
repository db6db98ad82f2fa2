r"""Friction against slip ratio: the steady-state brush model of a braked rubber wheel, and DRFT kinematics.

Geometry and conventions (DESIGN.md, "Slip"). A wheel rolls and is braked on a moving counter-surface (the
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

Also here: the two-coefficient brush used to analyse trailer data (static limit :math:`\mu_s` in the stick zone,
dynamic :math:`\mu_D` in the slide zone, Sakai's n = 4 pressure) and its map over
:math:`n_1 = \mu_D/\mu_s` and :math:`n_2 = (\text{initial slope})/\mu_s`; and the DRFT kinematics.

Magic Formula fits, friction-speed laws and curve peaks are in :mod:`persson.tire`; plots in
:mod:`persson.slip_plots`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from frictioncite import citations_of, doi

from ._checks import finite_array, number, positive
from .errors import InputError

__all__ = [
    "Contact", "SlipResult", "mu_slip", "brush_mu", "BrushCurve", "two_coefficient_mu", "BrushMap",
    "two_coefficient_map", "Kinematics", "drft_kinematics", "drft_from_angular", "drft_speeds",
    "PACEJKA_BOOK", "SAKAI_1981",
]

#: H. B. Pacejka, Tire and Vehicle Dynamics (3rd ed., 2012), brush model: chapter 3.
PACEJKA_BOOK = "isbn:9780080970165"
#: H. Sakai, Theoretical and experimental studies on the dynamic properties of tyres (Int. J. Vehicle Design, 1981).
SAKAI_1981 = "sakai:ijvd-1981"

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
        2 (1981), as specified in DESIGN.md ("Sakai's n-power form"; the absolute value makes odd and
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
        function).
    converged : bool
        Whether the friction model's self-consistent iterations converged at every sliding speed.
    notes : tuple of str
    citations : tuple of str
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
        force_N``."""
        cols = {
            "slip": self.slip, "speed_m_s": self.speed, "sliding_speed_m_s": self.sliding_speed, "mu": self.mu,
            "mu_local": self.mu_local, "stick_fraction": self.stick_fraction, "stick_length_m": self.stick_length,
            "force_N": self.force,
        }
        return {k: np.atleast_1d(np.asarray(v, dtype=float)).ravel() for k, v in cols.items()}

    def to_csv(self, path, comments: tuple[str, ...] = ()):
        """Write :meth:`as_table` as a CSV (atomically), with the conditions and contact as comment lines."""
        from .io import write_csv

        c = self.contact
        head = (f"brush model: T0 = {self.temperature:g} C, sigma0 = {self.pressure:g} Pa, l = {c.length:g} m, "
                f"w = {c.width:g} m, k = {c.stiffness:g} Pa/m, pressure = {c.pressure_distribution!r}",)
        return write_csv(path, self.as_table(), comments=head + tuple(comments) + tuple(self.notes))


@doi(PACEJKA_BOOK)
def mu_slip(model, slip, speed, *, temperature: float = 20.0, pressure: float = 0.3e6,
            contact: Contact) -> SlipResult:
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

    Returns
    -------
    SlipResult
        ``.mu`` etc. with the broadcast shape of ``slip`` and ``speed``; the friction model is evaluated once,
        at the distinct sliding speeds s V.

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
# DRFT kinematics
# =========================================================================================================
@doi(PACEJKA_BOOK)
@dataclass(frozen=True, eq=False)
class Kinematics:
    r"""Wheel-on-disk (DRFT) kinematics of braking slip.

    Attributes
    ----------
    speed : ndarray or float
        Rolling reference speed V, m/s: the disk's surface speed under the wheel,
        :math:`V = \Omega_{disk} R_{track}`.
    wheel_speed : ndarray or float
        Circumferential wheel speed :math:`\omega r`, m/s (r the effective rolling radius).
    slip : ndarray or float
        :math:`s = (V - \omega r)/V`; 0 free rolling, 1 locked wheel (pure sliding).
    sliding_speed : ndarray or float
        :math:`v_s = V - \omega r = sV`, m/s.
    omega_wheel, omega_disk : ndarray or float or None
        Angular speeds, rad/s, when the radii are known.
    """

    speed: np.ndarray
    wheel_speed: np.ndarray
    slip: np.ndarray
    sliding_speed: np.ndarray
    omega_wheel: np.ndarray | None = None
    omega_disk: np.ndarray | None = None


def drft_kinematics(wheel_speed, disk_speed) -> Kinematics:
    """Slip ratio and sliding speed from the wheel's circumferential speed and the disk's surface speed (m/s).

    Raises
    ------
    InputError
        ``disk_speed`` <= 0, ``wheel_speed`` < 0, or ``wheel_speed`` > ``disk_speed`` (driving slip: outside the
        braking brush model).
    """
    Vw = finite_array(wheel_speed, "wheel_speed")
    V = finite_array(disk_speed, "disk_speed")
    if np.any(V <= 0):
        raise InputError(f"disk_speed: expected a surface speed > 0 m/s, got {np.min(V):g}")
    if np.any(Vw < 0):
        raise InputError(f"wheel_speed: expected a circumferential speed >= 0 m/s, got {np.min(Vw):g}")
    Vw, V = _broadcast("wheel_speed, disk_speed", Vw, V)
    if np.any(Vw > V * (1 + 1e-12)):
        raise InputError("wheel_speed: exceeds disk_speed (driving slip); the brush model here covers braking, "
                         "0 <= wheel_speed <= disk_speed")
    vs = np.clip(V - Vw, 0.0, None)
    s = vs / V
    return Kinematics(speed=_sc(V), wheel_speed=_sc(Vw), slip=_sc(s), sliding_speed=_sc(vs))


def drft_from_angular(omega_wheel, omega_disk, *, wheel_radius: float, track_radius: float) -> Kinematics:
    """Kinematics from angular speeds (rad/s), the wheel's effective rolling radius and the track radius (m)."""
    r = positive(wheel_radius, "wheel_radius")
    R = positive(track_radius, "track_radius")
    ww = finite_array(omega_wheel, "omega_wheel")
    wd = finite_array(omega_disk, "omega_disk")
    if np.any(wd <= 0):
        raise InputError(f"omega_disk: expected an angular speed > 0 rad/s, got {np.min(wd):g}")
    if np.any(ww < 0):
        raise InputError(f"omega_wheel: expected an angular speed >= 0 rad/s, got {np.min(ww):g}")
    k = drft_kinematics(ww * r, wd * R)
    return Kinematics(k.speed, k.wheel_speed, k.slip, k.sliding_speed, omega_wheel=_sc(np.asarray(ww, float)),
                      omega_disk=_sc(np.asarray(wd, float)))


def drft_speeds(slip, speed, *, wheel_radius: float | None = None, track_radius: float | None = None) -> Kinematics:
    """Wheel speed and sliding speed (and angular speeds, when the radii are given) for a slip ratio and speed V.

    ``slip`` in [0, 1] (0: free rolling; 1: locked wheel), ``speed`` V > 0 m/s.
    """
    s = finite_array(slip, "slip")
    if np.any((s < 0) | (s > 1)):
        raise InputError(f"slip: expected braking slip ratios in [0, 1], got {s[(s < 0) | (s > 1)].ravel()[0]:g}")
    V = _speed_array(speed)
    s, V = _broadcast("slip, speed", s, V)
    Vw = (1.0 - s) * V
    ww = wd = None
    if wheel_radius is not None:
        ww = _sc(Vw / positive(wheel_radius, "wheel_radius"))
    if track_radius is not None:
        wd = _sc(V / positive(track_radius, "track_radius"))
    return Kinematics(speed=_sc(V), wheel_speed=_sc(Vw), slip=_sc(s), sliding_speed=_sc(s * V),
                      omega_wheel=ww, omega_disk=wd)


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
