"""The contact patch of a slipping wheel: length, width, pressure distribution and tread stiffness (:class:`Contact`),
and the tread geometry that gives the stiffness from the compound (:class:`Tread`)."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from .._checks import number, positive
from ..errors import InputError
from .references import GENT_2012, PACEJKA_BOOK, SAKAI_1981, TIMOSHENKO_GERE

__all__ = ["Contact", "CONTACT_PARAMETERS", "Tread"]


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
            if name in ("length", "width") and v > 1.0:  # no wheel's contact patch is a metre long
                raise InputError(f"contact.{name}: {v:g} m is larger than any contact patch of a wheel or tire "
                                 f"(0.01-0.3 m); expected metres ({v:g} mm = {v * 1e-3:g} m)")
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

    @classmethod
    def from_tread(cls, length: float, width: float, tread: "Tread", material, *, speed: float,
                   temperature: float = 20.0, pressure_distribution="parabolic", n_points: int = 401,
                   carcass_stiffness: float | None = None) -> "Contact":
        r"""The contact patch with the tread stiffness derived from the compound (:meth:`Tread.stiffness`), in series
        with the compliance of the tire's carcass and belt when ``carcass_stiffness`` is given.

        The brush of a tire is the tread element on the belt: the road's shear passes through the rubber block and
        then through the belt and carcass, so the two compliances add (springs in series),

        .. math:: \frac{1}{k} = \frac{1}{k_{tread}(\omega, T_0)} + \frac{1}{k_c},

        the effective tread-element stiffness :math:`c_p` of Pacejka's brush model, which a tire's measured slip
        stiffness :math:`C_{F\kappa} = 2 c_p a^2` gives (*Tire and Vehicle Dynamics*, ch. 3; the belt's in-plane
        deformation in the tread simulation model of the same chapter). :math:`k_c` is the carcass and belt's
        share, per unit contact area (Pa/m), taken independent of speed and temperature (the belt is steel and
        cord, not rubber); :func:`persson.slip.road.carcass_stiffness` derives it from a tire's measured slip
        stiffness.

        Parameters
        ----------
        length, width : float
            Contact length and width, m.
        tread : Tread
            Tread depth, block length and land ratio.
        material : material
            The tread compound (``E(omega, T)``, complex Young's modulus, Pa).
        speed : float
            Rolling speed V, m/s: the tread is loaded at the angular frequency :math:`\pi V / l`.
        temperature : float
            Temperature of the tread blocks, deg C (the background temperature T0).
        pressure_distribution, n_points
            As for :class:`Contact`.
        carcass_stiffness : float, optional
            :math:`k_c`, Pa/m (> 0); None (default) leaves the tread alone (a rigid belt).
        """
        if not isinstance(tread, Tread):
            raise InputError(f"tread: expected a persson.slip.Tread, got {tread!r}")
        k = tread.stiffness(material, speed=speed, temperature=temperature, contact_length=length)
        if carcass_stiffness is not None:
            k = 1.0 / (1.0 / k + 1.0 / positive(carcass_stiffness, "carcass_stiffness"))
        return cls(length=length, width=width, stiffness=k, pressure_distribution=pressure_distribution,
                   n_points=n_points)

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


# =========================================================================================================
# Tread geometry: the brush stiffness from the compound
# =========================================================================================================
@doi(PACEJKA_BOOK, GENT_2012, TIMOSHENKO_GERE)
@dataclass(frozen=True)
class Tread:
    r"""Tread geometry that sets the shear stiffness of the brush from the compound's modulus.

    A tread block of height h (the tread depth) and length b in the rolling direction, bonded to the belt and held
    flat on the road by the contact pressure, sheared by the stress :math:`\tau` on its face, deflects in shear
    and in bending. As a beam with both ends kept parallel (Timoshenko & Gere, *Mechanics of Materials*:
    bending deflection :math:`F h^3 / (12 E I)` added to the shear deflection :math:`F h / (G A)`; for rubber
    :math:`E = 3G` and :math:`I = A b^2/12`, the bonded rubber block in shear of Gent, *Engineering with Rubber*,
    ch. 3), its stiffness per unit area per unit displacement is

    .. math:: k = \lambda\,\frac{G(\omega, T_0)}{h}\,\frac{1}{1 + h^2/(3 b^2)},
        \qquad G = \frac{|E^*(\omega, T_0)|}{2(1 + \nu)},\qquad \omega = \frac{\pi V}{l},

    the brush stiffness :math:`k = G/h` of Pacejka (*Tire and Vehicle Dynamics*, ch. 3) with the bending of the
    block and the land ratio :math:`\lambda` (the share of the nominal contact area that is rubber: the grooves
    carry no shear). The modulus is taken at the tread's own temperature T0 (the frictional heat stays in a thin
    surface layer) and at the frequency of one loading per passage through the patch: a block is sheared from the
    leading to the trailing edge in the time :math:`l/V`, half a period of :math:`\omega = \pi V / l`.

    What it leaves out: the belt of a tire, whose deformation along the patch makes a tire's measured slip
    stiffness (15-30 times the load) several times lower than its tread's; for a tire the slip at the peak
    predicted from the tread alone is a lower bound. (A uniform deflection of the carcass does not change the
    steady-state curve.) Give the :class:`Contact` a measured ``stiffness`` where that matters.

    Parameters
    ----------
    depth : float
        Tread depth h (block height), m (> 0; a new passenger-car tread about 8 mm).
    block_length : float
        Block length b in the rolling direction, m (> 0; passenger-car blocks 20-40 mm).
    land_ratio : float
        Rubber share of the nominal contact area, 0 < lambda <= 1 (default 1; a passenger-car tread about 0.7).
    nu : float
        Poisson ratio of the compound (default 0.5).

    Examples
    --------
    >>> import materials
    >>> tread = Tread(depth=8e-3, block_length=25e-3)
    >>> k = tread.stiffness(materials.example_tread(), speed=20.0, temperature=20.0, contact_length=0.12)
    >>> print(f"{k:.3g} Pa/m")
    2.05e+08 Pa/m
    """

    depth: float
    block_length: float
    land_ratio: float = 1.0
    nu: float = 0.5

    def __post_init__(self):
        for name in ("depth", "block_length"):
            object.__setattr__(self, name, positive(getattr(self, name), f"tread.{name}"))
        lam = number(self.land_ratio, "tread.land_ratio")
        if not 0.0 < lam <= 1.0:
            raise InputError(f"tread.land_ratio: expected a rubber share in (0, 1], got {lam:g}")
        object.__setattr__(self, "land_ratio", lam)
        nu = number(self.nu, "tread.nu")
        if not 0.0 <= nu <= 0.5:
            raise InputError(f"tread.nu: expected a Poisson ratio in [0, 0.5], got {nu:g}")
        object.__setattr__(self, "nu", nu)

    @property
    def bending_factor(self) -> float:
        r""":math:`1/(1 + h^2/(3 b^2))`, the share of the pure-shear stiffness left by the bending of the block."""
        return 1.0 / (1.0 + self.depth ** 2 / (3.0 * self.block_length ** 2))

    def frequency(self, speed: float, contact_length: float) -> float:
        r"""Angular frequency of the loading, :math:`\pi V / l`, rad/s."""
        return math.pi * positive(speed, "speed") / positive(contact_length, "contact_length")

    def shear_modulus(self, material, *, speed: float, temperature: float, contact_length: float) -> float:
        r""":math:`|G^*| = |E^*(\pi V / l, T_0)| / (2(1 + \nu))`, Pa."""
        if not hasattr(material, "E"):
            raise InputError(f"material: expected an object with E(omega, T), got {material!r}")
        w = self.frequency(speed, contact_length)
        E = complex(np.asarray(material.E(np.array([w]), number(temperature, "temperature")), dtype=complex)[0])
        if not (math.isfinite(E.real) and math.isfinite(E.imag) and abs(E) > 0):
            raise InputError(f"material: E(omega={w:.4g} rad/s, T={temperature:g} C) = {E!r}; expected a finite, "
                             "nonzero modulus")
        return abs(E) / (2.0 * (1.0 + self.nu))

    def stiffness(self, material, *, speed: float, temperature: float, contact_length: float) -> float:
        """Brush stiffness k per unit area per unit displacement, Pa/m (the formula of the class)."""
        G = self.shear_modulus(material, speed=speed, temperature=temperature, contact_length=contact_length)
        return self.land_ratio * G / self.depth * self.bending_factor


def _contact_parameters():
    from ..effects.base import Parameter

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
            return "uniform", float("nan"), _uniform_pressure
        if key == "parabolic":
            return "parabolic", float("nan"), _parabolic_pressure
        raise InputError(f"contact.pressure_distribution: expected \"uniform\", \"parabolic\", "
                         f"{{\"sakai_n\": n}} or a callable, got {spec!r}")
    if isinstance(spec, dict):
        if set(spec) != {"sakai_n"}:
            raise InputError(f"contact.pressure_distribution: a mapping must be {{\"sakai_n\": n}}, got {spec!r}")
        n = number(spec["sakai_n"], "contact.pressure_distribution.sakai_n")
        if n <= 0:
            raise InputError(f"contact.pressure_distribution.sakai_n: expected n > 0, got {n:g}")
        return "sakai", n, functools.partial(_sakai_pressure, n=n)
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


# the shapes p / sigma0 of x / l are module-level functions, not closures, so that a Contact can be pickled (sent
# to a process pool, kept with a case or a result)
def _uniform_pressure(xi):
    """A uniform pressure: 1 along the patch."""
    return np.ones_like(np.asarray(xi, dtype=float))


def _parabolic_pressure(xi):
    """The parabolic pressure 6 x (1 - x) of x = x/l (mean 1)."""
    return 6.0 * np.asarray(xi) * (1.0 - np.asarray(xi))


def _sakai_pressure(xi, n):
    """Sakai's n-power pressure (n + 1) / n (1 - |2 x - 1|^n) of x = x/l (mean 1): H. Sakai, Int. J. Vehicle
    Design 2 (1981), as in :class:`Contact`."""
    xi = np.asarray(xi, dtype=float)
    return (n + 1.0) / n * (1.0 - np.abs(2.0 * xi - 1.0) ** n)
