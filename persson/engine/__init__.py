"""The multiscale engine: :class:`Model` and its solver.

Bottom-up: :mod:`~persson.engine.conditions` (operating conditions, the solved state handed to effects, the
settings a temperature effect gives the solver), :mod:`~persson.engine.grid` (quadrature settings),
:mod:`~persson.engine.kernel_arrays` (the named tuples the kernels take), :mod:`~persson.engine.kernels` (numba
kernels: angular integrals, contact area, the q quadrature, hysteresis friction, the flash-temperature fixed point),
:mod:`~persson.engine.quadrature` (the PSD's quadrature rule and moments), :mod:`~persson.engine.tabulate` (modulus
and shift tables on a log-frequency grid), :mod:`~persson.engine.solver` (the kernel calls, the error estimate,
adaptive refinement and the flash temperature run with a temperature effect's settings),
:mod:`~persson.engine.results` (:class:`FrictionResult`),
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
