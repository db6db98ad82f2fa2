"""Surface roughness: profiles, height maps, power spectral densities (PSD), cut-offs, texture metrics.

Conventions (see ``docs/conventions.md``): SI units, wavevector q in rad/m, 2D isotropic PSD in Persson's convention

.. math:: C(q) = (2\\pi)^{-2} \\int d^2x \\langle h(\\mathbf{x}) h(0) \\rangle e^{-i\\mathbf{q}\\cdot\\mathbf{x}},
   \\qquad h_{rms}^2 = 2\\pi \\int q C(q) dq ,

and the two-sided 1D PSD of line scans :math:`C_{1D}(q) = (2\\pi)^{-1}\\int dx \\langle h(x)h(0)\\rangle e^{-iqx}`.

Typical use::

    import surfaces
    ps = surfaces.read_profiles("scan.csv")        # ProfileSet (profile CSV or a CAPTIF export)
    p1 = ps.psd()                                  # PSD1D, averaged over profiles, log-binned
    s = p1.to_isotropic()                          # surfaces.PSD, exact inverse Abel transform
    s = s.extrapolate(1e7)                         # tail past q_r, flagged as extrapolated
    surfaces.mpd(ps).mpd                           # mean profile depth (ISO 13473-1), m

This package knows nothing of rubber.
"""

from .anisotropy import AnisotropicPSD, Anisotropy, Stretched, Unidirectional, stretched, unidirectional
from .directional import DirectionalPSDs, directional_psds
from .cutoffs import RolloffFit, SelfAffineFit, fit_rolloff, fit_self_affine, reliability_limit
from .errors import AccuracyWarning, DataWarning, InputError, SurfacesWarning, UnitWarning
from .io import profiles_from_array, read_captif, read_height_map, read_profiles, read_profiles_csv
from .maps import HeightMap
from .profiles import Profile, ProfileSet
from .psd import PSD, Cutoffs, SelfAffine, read_psd
from .psd2d import PSD2D
from .spectra import PSD1D, abel_forward, gamma_factor
from .synthetic import example_road, synthesize_map, synthesize_profiles
from .texture import HDC, HDCFit, MPDResult, etd, fit_hdc, hdc, mpd, rms_slope, rq

__all__ = [
    "InputError", "SurfacesWarning", "DataWarning", "AccuracyWarning", "UnitWarning",
    # PSD objects
    "PSD", "SelfAffine", "PSD1D", "Cutoffs", "read_psd", "abel_forward", "gamma_factor",
    # anisotropic surfaces
    "PSD2D", "AnisotropicPSD", "Anisotropy", "Stretched", "Unidirectional", "stretched", "unidirectional",
    "DirectionalPSDs", "directional_psds",
    # data
    "Profile", "ProfileSet", "HeightMap",
    "read_profiles", "read_profiles_csv", "read_captif", "profiles_from_array", "read_height_map",
    # cut-offs and fits
    "SelfAffineFit", "RolloffFit", "fit_self_affine", "fit_rolloff", "reliability_limit",
    # synthesis
    "synthesize_map", "synthesize_profiles", "example_road",
    # texture
    "MPDResult", "mpd", "etd", "rq", "rms_slope", "HDC", "HDCFit", "hdc", "fit_hdc",
]
