"""The multiscale engine: :class:`Model` and its solver.

Bottom-up: :mod:`~persson.engine.conditions` (operating conditions, the solved state handed to effects),
:mod:`~persson.engine.grid` (quadrature settings), :mod:`~persson.engine.kernels` (numba kernels: angular
integrals, contact area, flash temperature), :mod:`~persson.engine.tabulate` (modulus and shift tables on a
log-frequency grid), :mod:`~persson.engine.solver` (the q quadrature with its error estimate, adaptive refinement
and the flash-temperature fixed point), :mod:`~persson.engine.results` (:class:`FrictionResult`),
:mod:`~persson.engine.model` (:class:`Model`, the public entry point) and :mod:`~persson.engine.reference` (a slow,
independent quadrature the tests compare with). Anisotropic surfaces and sliding directions:
:mod:`~persson.engine.anisotropic_kernels` and :mod:`~persson.engine.anisotropic` (Persson's angular integrals over
C(q, phi) per direction), :mod:`~persson.engine.directional` (``Model.friction(..., direction_deg=...)`` and its
result for many directions) and :mod:`~persson.engine.anisotropic_reference` (a brute-force 2-D quadrature).
"""

from .conditions import Conditions, SolverState
from .grid import GridSettings
from .model import Model
from .results import FrictionResult

__all__ = ["Model", "FrictionResult", "GridSettings", "Conditions", "SolverState"]
