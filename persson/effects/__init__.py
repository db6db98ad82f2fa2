"""Effects: physics switched on top of the baseline (hysteresis friction and contact area).

Built in: :class:`FlashTemperature` (``flash_temperature``), :class:`Adhesion` (``adhesion``),
:class:`Microtexture` (``microtexture``), :class:`StrainSoftening` (``strain_softening``), :class:`Wet` (``wet``).
See :mod:`persson.effects.base` for how to write one.
"""

from .base import Conditions, Effect, Parameter, SolverState, available, effect_class, get
from .builtin import Adhesion, FlashTemperature, Microtexture, StrainSoftening, Wet

__all__ = [
    "Effect", "Parameter", "Conditions", "SolverState", "available", "effect_class", "get",
    "FlashTemperature", "Adhesion", "Microtexture", "StrainSoftening", "Wet",
]
