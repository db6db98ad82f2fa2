"""persson: rubber friction from Persson's multiscale contact theory.

Pipeline: a surface PSD (:mod:`surfaces`) and a viscoelastic material (:mod:`materials`) go into a
:class:`Model`; ``Model.friction(speed, temperature, pressure)`` returns a :class:`FrictionResult`.
Effects (:mod:`persson.effects`) add physics on top of the baseline; :mod:`persson.slip` turns sliding friction
into friction vs slip ratio; :mod:`persson.sweeps` runs band and parameter studies.
"""

from . import effects, slip, sweeps, tire
from .errors import ConvergenceWarning, InputError
from .grid import GridSettings
from .model import Model
from .results import FrictionResult

__version__ = "0.1.0"

__all__ = ["Model", "FrictionResult", "GridSettings", "InputError", "ConvergenceWarning", "effects", "slip",
           "sweeps", "tire", "__version__"]
