"""Viscoelastic materials: DMA data, time-temperature superposition, WLF, Prony master curves.

Conventions (see DESIGN.md): SI units, angular frequency omega in rad/s, temperatures in degrees Celsius,
E the complex **Young's** modulus E = E' + i E'' with Im E odd in omega. This package knows nothing of surfaces.

Every material exposes ``E(omega, T)`` (complex, vectorized) and ``thermal`` (:class:`Thermal`); those of this
package also ``log10_aT(T)``.

Typical use::

    import materials
    dma = materials.read_dma("dma.csv")                 # long CSV, pyvisco CSV or Eplexor export(s)
    m = materials.master_curve(dma, T_ref=20.0)         # shifts, WLF, causal Prony fit
    m.E(omega, T); m.wlf; m.shift_factors; m.quality
    m.to_table("master_curve.csv")
    m2 = materials.read_master_curve("master_curve.csv", wlf={"C1": 8.86, "C2": 101.6, "T_ref_C": 20.0})
    tread = materials.example_tread()                   # synthetic, documented
"""

from .errors import InputError
from .viscoelastic import WLF, ConstantModulus, Prony, Thermal
from .examples import example_tread
from .dma import DMAData, read_dma, read_dma_long, read_eplexor, read_pyvisco
from .tts import (Arrhenius, ShiftFactors, TemperatureShift, WLFFit, fit_arrhenius, fit_wlf, shift_isotherms,
                  wlf_change_reference)
from .prony_fit import FitQuality, PronyFit, fit_prony
from .master import MasterCurve, ReducedData, TabulatedModulus, master_curve, read_master_curve
from .strain import StrainSoftened, StrainSoftening, strain_softening_from_sweep

_LAZY_PLOTS = ("plot_master_curve", "plot_shift_factors")


def __getattr__(name):
    # matplotlib is imported only when a plot is asked for
    if name in _LAZY_PLOTS:
        from . import plots
        return getattr(plots, name)
    raise AttributeError(f"module 'materials' has no attribute {name!r}")


__all__ = [
    "InputError", "WLF", "Thermal", "ConstantModulus", "Prony", "example_tread",
    "DMAData", "read_dma", "read_dma_long", "read_pyvisco", "read_eplexor",
    "ShiftFactors", "shift_isotherms", "WLFFit", "fit_wlf", "Arrhenius", "fit_arrhenius", "TemperatureShift",
    "wlf_change_reference",
    "FitQuality", "PronyFit", "fit_prony",
    "MasterCurve", "ReducedData", "TabulatedModulus", "master_curve", "read_master_curve",
    "StrainSoftening", "StrainSoftened", "strain_softening_from_sweep",
    "plot_master_curve", "plot_shift_factors",
]
