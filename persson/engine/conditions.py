"""The operating conditions of a friction evaluation and the solved state handed to effects."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["Conditions", "SolverState"]


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
