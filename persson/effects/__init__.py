"""Effects: physics switched on top of the baseline (hysteresis friction and contact area).

Built in: :class:`FlashTemperature` (``flash_temperature``), :class:`Adhesion` (``adhesion``),
:class:`Microtexture` (``microtexture``), :class:`StrainSoftening` (``strain_softening``), :class:`Wet` (``wet``),
:class:`PatchHeating` (``patch_heating``: temperature and pressure along the contact patch of a slipping wheel).
See :mod:`persson.effects.base` for how to write one; :mod:`persson.effects.strain` holds the extrapolation rules of
measured strain factors and :func:`strain_extrapolation_spread`; a temperature effect returns its
:class:`TemperatureSolverOptions` and the solver runs the flash temperature with them.
"""

from ..engine.conditions import Conditions, SolverState, TemperatureSolverOptions
from .base import Effect, Parameter, available, effect_class, get
from .builtin import Adhesion, FlashTemperature, Microtexture, StrainSoftening, Wet
from .strain import StrainExtrapolationSpread, strain_extrapolation_spread
from ..slip.heating import PatchHeating

__all__ = [
    "Effect", "Parameter", "Conditions", "SolverState", "TemperatureSolverOptions", "available", "effect_class", "get",
    "FlashTemperature", "Adhesion", "Microtexture", "StrainSoftening", "Wet", "PatchHeating",
    "StrainExtrapolationSpread", "strain_extrapolation_spread",
]
