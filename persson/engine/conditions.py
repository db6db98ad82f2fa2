"""The operating conditions of a friction evaluation, the solved state handed to effects and the settings a
temperature effect gives the solver."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
import math
from typing import Any

import numpy as np

from ..errors import InputError

__all__ = ["Conditions", "SolverState", "TemperatureSolverOptions"]


@dataclass(frozen=True)
class Conditions:
    """Operating conditions of one friction evaluation.

    Parameters
    ----------
    speed : ndarray
        Sliding speeds, m/s, shape (n_speed,).
    temperature : float or ndarray
        Background (bulk) temperature T0, deg C: a float, or an array (n_speed,) when the call gave one
        temperature per speed. Write effects with numpy broadcasting so that both work.
    pressure : float or ndarray
        Nominal contact pressure sigma0 carried by the asperity contact, Pa (float, or per speed).
    nominal_pressure : float or ndarray
        Total nominal pressure on the contact, Pa (differs from ``pressure`` when a fluid film carries load).
    wet : bool
        Whether the interface is wet (adhesion off).
    extra : dict
        Free-form values effects pass to one another (read-only by convention).
    """

    speed: np.ndarray
    temperature: float | np.ndarray
    pressure: float | np.ndarray
    nominal_pressure: float | np.ndarray
    wet: bool = False
    extra: dict = field(default_factory=dict)

    def replace(self, **changes) -> "Conditions":
        """Copy with some fields changed."""
        return dataclasses.replace(self, **changes)


@dataclass(frozen=True, eq=False)
class SolverState:
    """What the solver found, handed to ``friction_term`` hooks.

    Attributes
    ----------
    conditions : Conditions
    surface, material : objects
        After the transform hooks.
    q : ndarray (n_q,)
        Wavevector nodes, rad/m.
    area_q : ndarray (n_speed, n_q)
        P(q) = A(q)/A0.
    G_q : ndarray (n_speed, n_q)
        Persson's G(q).
    temperature_q : ndarray (n_speed, n_q)
        Temperature seen at scale q, deg C.
    mu_hysteresis : ndarray (n_speed,)
    nu, gamma : float
    """

    conditions: Conditions
    surface: Any
    material: Any
    q: np.ndarray
    area_q: np.ndarray
    G_q: np.ndarray
    temperature_q: np.ndarray
    mu_hysteresis: np.ndarray
    nu: float
    gamma: float

    @property
    def contact_area(self) -> np.ndarray:
        """A/A0 at the largest wavevector q1, per speed."""
        return self.area_q[:, -1]

    @property
    def contact_temperature(self) -> np.ndarray:
        """Temperature at the smallest scale (q1), per speed, deg C."""
        return self.temperature_q[:, -1]


@dataclass(frozen=True)
class TemperatureSolverOptions:
    r"""Settings of the self-consistent flash temperature that an effect with ``solver_role = "temperature"``
    gives the solver (its ``temperature_solver_options`` hook); the solver runs the fixed point itself.

    The temperature at scale q is (Persson, J. Phys.: Condens. Matter 18, 7789 (2006), Eqs. 20-27)

    .. math::
        T_q = T_0 + \int_{q_0}^{q} dq'\, g(q, q') f(q'),\qquad
        f(q) = \frac{v\,\sigma_0}{\rho c_p}\frac{P(q)}{P(q_m)}\, q^4 C(q)\,
        \frac{1}{\sigma_0}\int_0^{2\pi} d\phi\,\cos\phi\,\frac{\mathrm{Im}\,E(q v\cos\phi, T_q)}{1-\nu^2}

    with Persson's heat kernel g, which depends on the diffusivity D and the contact time
    :math:`t_0 = d / v` of a macro-asperity contact region. Per speed the solver uses :math:`D t_0` =
    ``diffusivity * contact_diameter / v`` and the heat factor :math:`\sigma_0/(\rho c_p)` =
    ``pressure / heat_capacity``.

    Parameters
    ----------
    q_m : float
        Wavevector of the macro-asperity contact regions, rad/m; P(q_m) normalises the heat source.
    contact_diameter : float
        Diameter d of a macro-asperity contact region, m; the contact time at sliding speed v is d / v.
    diffusivity : float
        Thermal diffusivity D = lambda / (rho c_p) of the rubber, m^2/s.
    heat_capacity : float
        Volumetric heat capacity rho c_p of the rubber, J/(m^3 K).
    tol : float
        Convergence tolerance on max |T_new - T| over the scales, K.
    max_iter : int
        Most fixed-point iterations per start (the solver starts up to twice more: with Aitken's relaxation, then
        with the half step).
    notes : tuple of persson.notes.Note
        Facts every result solved with these settings carries (e.g. a q_m the effect had to assume).

    Raises
    ------
    InputError
        If a value is not finite and positive (``max_iter`` not an integer >= 1).
    """

    q_m: float
    contact_diameter: float
    diffusivity: float
    heat_capacity: float
    tol: float = 1e-3
    max_iter: int = 300
    notes: tuple = ()

    def __post_init__(self):
        for name in ("q_m", "contact_diameter", "diffusivity", "heat_capacity", "tol"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) \
                    or not (math.isfinite(v) and v > 0):
                raise InputError(f"TemperatureSolverOptions.{name}: expected a finite number > 0, got {v!r}")
        if isinstance(self.max_iter, bool) or not isinstance(self.max_iter, (int, np.integer)) or self.max_iter < 1:
            raise InputError(f"TemperatureSolverOptions.max_iter: expected an integer >= 1, got {self.max_iter!r}")
        object.__setattr__(self, "notes", tuple(self.notes))
