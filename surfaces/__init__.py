"""Surface roughness: profiles, height maps, power spectral densities (PSD), cut-offs, texture metrics.

Conventions (see DESIGN.md): SI units, wavevector q in rad/m, 2D isotropic PSD in Persson's convention

.. math:: C(q) = (2\\pi)^{-2} \\int d^2x \\langle h(\\mathbf{x}) h(0) \\rangle e^{-i\\mathbf{q}\\cdot\\mathbf{x}},
   \\qquad h_{rms}^2 = 2\\pi \\int q C(q) dq .

This package knows nothing of rubber.
"""

from .errors import InputError
from .psd import PSD, SelfAffine

__all__ = ["InputError", "PSD", "SelfAffine"]
