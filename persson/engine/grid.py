"""Numerical grid of the solver: wavevector nodes, the modulus table and the error tolerance.

The method (see :mod:`persson.engine.kernels`) integrates the contact weight S(P) P dG exactly and the angular integrals
exactly on the modulus table, so the defaults are accurate from soft to glassy rubber: the worst relative error of
mu over the regime grid of ``benchmarks/accuracy.py`` (speeds 1e-8..30 m/s, -20..80 C, 0.02..2 MPa, |E|/sigma0
from 10 to 1e5, sandpaper to road surfaces) is documented in the README. Every result carries its own estimate
(``FrictionResult.error_estimate``) and a warning names the speeds where it exceeds ``tolerance``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError

__all__ = ["GridSettings"]


@dataclass(frozen=True)
class GridSettings:
    """Resolution of the Persson solver.

    Parameters
    ----------
    q_per_decade : int
        Wavevector nodes per decade of q (log-uniform; third-order rules in ln q). Default 16.
    n_phi : int
        Not used: the angular integrals are computed exactly for the tabulated modulus (a convolution in log
        frequency, see :func:`persson.engine.tabulate.angular_table`). Kept so that existing scripts keep working.
    omega_per_decade : int
        Nodes per decade of the tabulated modulus and of its angular integrals (cubic interpolation in log
        omega). Default 40.
    temperature_step : float
        Step, K, of the tabulated temperature shift log10 a_T(T) used when the temperature varies with q
        (flash temperature). Default 0.25 K.
    max_temperature_rise : float
        Flash-temperature rise, K, the shift table covers at first. Default 400 K. Speeds whose temperature
        leaves it are solved again with a table widened up to 8x this (3200 K by default); beyond that the
        modulus is clamped, with a ``ConvergenceWarning``.
    tolerance : float
        Relative error of mu the solver aims at, judged by the built-in error estimate: speeds whose estimate
        exceeds a third of it (the estimate is within a factor 3 of the true error) are solved again on refined
        grids (``max_refinement``); a result still above the tolerance warns
        (:class:`persson.AccuracyWarning`) and says so in its notes. Default 1e-3.
    max_refinement : int
        Most times every q interval is halved for the speeds whose estimate exceeds ``tolerance`` or whose flash
        temperature did not converge (default 3, i.e. up to 8 times the nodes; 0 switches the adaptive refinement
        off). Independently of it, a speed whose flash temperature climbs so steeply that the reduced frequency
        q v a_T(T_q) moves by more than 6 grid steps across an interval gets nodes there.
    extra_q : tuple of float
        Additional wavevector nodes, rad/m (e.g. band edges, so that band contributions are exact sums over
        intervals); nodes outside the surface's q range are ignored.
    """

    q_per_decade: int = 16
    n_phi: int = 24
    omega_per_decade: int = 40
    temperature_step: float = 0.25
    max_temperature_rise: float = 400.0
    tolerance: float = 1e-3
    extra_q: tuple = ()
    max_refinement: int = 3

    def __post_init__(self):
        for name, lo in (("q_per_decade", 4), ("n_phi", 4), ("omega_per_decade", 8), ("max_refinement", 0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
                raise InputError(f"grid.{name}: expected an integer >= {lo}, got {v!r}")
        for name in ("temperature_step", "max_temperature_rise", "tolerance"):
            v = getattr(self, name)
            if isinstance(v, bool) or not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"grid.{name}: expected a positive number, got {v!r}")
        try:
            extra = tuple(float(q) for q in np.atleast_1d(np.asarray(self.extra_q, dtype=float)))
        except (TypeError, ValueError):
            raise InputError(f"grid.extra_q: expected wavevectors in rad/m, got {self.extra_q!r}") from None
        if not all(math.isfinite(q) and q > 0 for q in extra):
            raise InputError(f"grid.extra_q: expected finite wavevectors > 0 rad/m, got {self.extra_q!r}")
        object.__setattr__(self, "extra_q", extra)

    def q_nodes(self, q_start: float, q_end: float) -> np.ndarray:
        """Wavevector nodes from ``q_start`` to ``q_end`` (both included), rad/m.

        Log-uniform with an odd number of nodes (so that every other node forms the uniform coarse grid of the
        error estimate; every fourth, the coarser grid, keeps the last node and may end with a shorter interval),
        at least 9 (the coarser grid's quadratic rule needs three nodes: a surface cut to a fraction of a decade,
        such as a microtexture cut-off just above q0), plus ``extra_q`` inside the range.
        """
        n = max(9, int(math.ceil(self.q_per_decade * math.log10(q_end / q_start))) + 1)
        n += 1 - n % 2
        q = np.geomspace(q_start, q_end, n)
        q[0], q[-1] = q_start, q_end
        extra = [e for e in self.extra_q if q_start < e < q_end]
        if extra:
            x = np.log(q)
            keep = [e for e in extra if np.min(np.abs(x - math.log(e))) > 1e-9]
            if keep:
                q = np.unique(np.concatenate([q, keep]))
        return q

    def angle_nodes(self) -> tuple[np.ndarray, np.ndarray]:
        """Gauss-Legendre nodes phi and weights on [0, pi/2] (read-only arrays)."""
        return _gauss_legendre_quarter(self.n_phi)


import functools  # noqa: E402


@functools.lru_cache(maxsize=16)
def _gauss_legendre_quarter(n: int) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    phi, wphi = 0.25 * math.pi * (x + 1.0), 0.25 * math.pi * w
    phi.setflags(write=False)
    wphi.setflags(write=False)
    return phi, wphi
