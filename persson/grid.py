"""Numerical grid of the solver: wavevector nodes, angle nodes and the modulus table.

The defaults meet the documented accuracy: the closed-form benchmark (constant modulus, self-affine PSD) to about
5e-7 and a viscoelastic Prony case to about 1e-4 of a slow adaptive quadrature (the tests require 1e-3, see
``tests/test_engine_core.py``).
Raise them for convergence studies; lower them for quick scans.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError

__all__ = ["GridSettings"]


@dataclass(frozen=True)
class GridSettings:
    """Resolution of the Persson solver.

    Parameters
    ----------
    q_per_decade : int
        Wavevector nodes per decade of q (log-uniform; third-order quadrature in ln q). Default 32.
    n_phi : int
        Gauss-Legendre nodes for the angle on [0, pi/2]. Default 24.
    omega_per_decade : int
        Nodes per decade of the tabulated modulus (linear interpolation of ln E', ln E'' in log omega).
        Default 40.
    temperature_step : float
        Step, K, of the tabulated temperature shift log10 a_T(T) used when the temperature varies with q
        (flash temperature). Default 0.25 K.
    max_temperature_rise : float
        Largest flash-temperature rise, K, the shift table covers. Default 400 K.
    """

    q_per_decade: int = 32
    n_phi: int = 24
    omega_per_decade: int = 40
    temperature_step: float = 0.25
    max_temperature_rise: float = 400.0

    def __post_init__(self):
        for name, lo in (("q_per_decade", 4), ("n_phi", 4), ("omega_per_decade", 4)):
            v = getattr(self, name)
            if not isinstance(v, (int, np.integer)) or v < lo:
                raise InputError(f"grid.{name}: expected an integer >= {lo}, got {v!r}")
        for name in ("temperature_step", "max_temperature_rise"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"grid.{name}: expected a positive number, got {v!r}")

    def q_nodes(self, q_start: float, q_end: float) -> np.ndarray:
        """Log-uniform wavevector nodes from ``q_start`` to ``q_end`` (both included), rad/m."""
        n = max(3, int(math.ceil(self.q_per_decade * math.log10(q_end / q_start))) + 1)
        return np.geomspace(q_start, q_end, n)

    def angle_nodes(self) -> tuple[np.ndarray, np.ndarray]:
        """Gauss-Legendre nodes phi and weights on [0, pi/2] (read-only arrays)."""
        return _gauss_legendre_quarter(self.n_phi)


@functools.lru_cache(maxsize=16)
def _gauss_legendre_quarter(n: int) -> tuple[np.ndarray, np.ndarray]:
    # Pure function of n, cached: leggauss costs milliseconds at every friction call otherwise.
    x, w = np.polynomial.legendre.leggauss(n)
    phi, wphi = 0.25 * math.pi * (x + 1.0), 0.25 * math.pi * w
    phi.setflags(write=False)
    wphi.setflags(write=False)
    return phi, wphi
