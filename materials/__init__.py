"""Viscoelastic materials: DMA data, time-temperature superposition, shift laws, master curves, strain factors.

Conventions (see docs/materials.md and docs/conventions.md): SI units, angular frequency omega in rad/s,
temperatures in degrees Celsius, E the complex **Young's** modulus E = E' + i E'' with Im E odd in omega. This
package knows nothing of surfaces.

Every material exposes ``E(omega, T)`` (complex, vectorized) and ``thermal`` (:class:`Thermal`); those of this
package also ``log10_aT(T)``.

Typical use::

    import materials
    dma = materials.read_dma("dma.csv")                 # long CSV, pyvisco CSV or Eplexor export(s)
    m = materials.master_curve(dma, T_ref=20.0)         # shifts, law chosen by fit quality, curve
    m.E(omega, T); m.shift; m.misfit; m.scores; m.frequency_range
    m.to_table("master_curve.csv")
    aT = materials.read_shift_factors("shift_factors.csv")          # a TabulatedShift
    m2 = materials.read_master_curve("master_curve.csv", shift=aT)  # the table used as measured
    sf = materials.strain_factors(materials.read_strain_sweep("sweeps.csv"))
    sf = materials.read_strain_factors("factors.txt")  # a table of strain, f, g exported by another program
    f, g = sf.factors(strain, T)
    tread = materials.example_tread()                   # synthetic, documented
"""

from .errors import AccuracyWarning, ConvergenceWarning, DataWarning, InputError, MaterialsWarning, PhysicsWarning
from .laws import (WLF, Arrhenius, TemperatureShift, WLFArrhenius, WLFFit, fit_arrhenius, fit_wlf,
                   wlf_activation_energy, wlf_change_reference)
from .viscoelastic import ConstantModulus, Prony, Thermal
from .examples import example_tire_tread, example_tread
from .dma import DMAData, read_dma, read_dma_long, read_eplexor, read_pyvisco
from .tts import ShiftFactors, shift_isotherms
from .shift import (SHIFT_RANGE_NOTE, SingleTemperature, TabulatedShift, extrapolated_shift_note,
                    fitted_temperature_range, read_shift_factors, with_arrhenius_above)
from .shiftfit import ShiftLawScore
from .prony_fit import FitQuality, PronyFit, fit_prony
from .curves import CausalityCheck, InterpolatedModulus, causality_check
from .mastercurve import MasterCurve, ReducedData, TabulatedModulus, isotherm_misfit
from .master import master_curve, read_master_curve
from .strain import (StrainFactors, StrainSoftened, StrainSoftening, StrainSweep, read_strain_sweep,
                     strain_factors, strain_softening_from_sweep)
from .strain_table import read_strain_factors

_LAZY_PLOTS = ("plot_master_curve", "plot_shift_factors")


def __getattr__(name):
    # matplotlib is imported only when a plot is asked for
    if name in _LAZY_PLOTS:
        from . import plots
        return getattr(plots, name)
    raise AttributeError(f"module 'materials' has no attribute {name!r}")


__all__ = [
    "InputError", "MaterialsWarning", "DataWarning", "AccuracyWarning", "ConvergenceWarning", "PhysicsWarning",
    "WLF", "Thermal", "ConstantModulus", "Prony", "example_tread", "example_tire_tread",
    "DMAData", "read_dma", "read_dma_long", "read_pyvisco", "read_eplexor",
    "ShiftFactors", "shift_isotherms", "WLFFit", "fit_wlf", "Arrhenius", "fit_arrhenius", "TemperatureShift",
    "WLFArrhenius", "TabulatedShift", "SingleTemperature", "read_shift_factors", "ShiftLawScore",
    "wlf_change_reference", "wlf_activation_energy", "with_arrhenius_above", "fitted_temperature_range",
    "extrapolated_shift_note", "SHIFT_RANGE_NOTE",
    "FitQuality", "PronyFit", "fit_prony", "InterpolatedModulus", "CausalityCheck", "causality_check",
    "MasterCurve", "ReducedData", "TabulatedModulus", "master_curve", "read_master_curve", "isotherm_misfit",
    "StrainSoftening", "StrainSoftened", "strain_softening_from_sweep",
    "StrainSweep", "StrainFactors", "read_strain_sweep", "strain_factors", "read_strain_factors",
    "plot_master_curve", "plot_shift_factors",
]
