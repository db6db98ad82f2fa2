"""Viscoelastic materials: DMA data, time-temperature superposition, WLF, Prony master curves.

Conventions (see DESIGN.md): SI units, angular frequency omega in rad/s, temperatures in degrees Celsius,
E the complex **Young's** modulus E = E' + i E'' with Im E odd in omega. This package knows nothing of surfaces.

Every material exposes ``E(omega, T)`` (complex, vectorized) and ``thermal`` (:class:`Thermal`).
"""

from .errors import InputError
from .viscoelastic import WLF, ConstantModulus, Prony, Thermal

__all__ = ["InputError", "WLF", "Thermal", "ConstantModulus", "Prony"]
