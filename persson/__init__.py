"""persson: rubber friction from Persson's multiscale contact theory.

Pipeline: a surface PSD (:mod:`surfaces`) and a viscoelastic material (:mod:`materials`) go into a
:class:`Model`; ``Model.friction(speed, temperature, pressure)`` returns a :class:`FrictionResult`.
Effects (:mod:`persson.effects`) add physics on top of the baseline; :mod:`persson.slip` turns sliding friction
into friction vs slip ratio; :mod:`persson.sweeps` runs band and parameter studies. :func:`contact` gives the
contact mechanics alone (area, separation, elastic energy, penetration depth vs pressure).
"""

from . import effects, slip, sweeps, tire
from .contact import ContactResult, contact
from .errors import AccuracyWarning, ConvergenceWarning, InputError, PhysicsWarning
from .grid import GridSettings
from .model import Model
from .results import FrictionResult

__version__ = "0.1.0"

__all__ = ["Model", "FrictionResult", "GridSettings", "InputError", "ConvergenceWarning", "AccuracyWarning",
           "PhysicsWarning", "effects", "slip",
           "sweeps", "tire", "contact", "ContactResult", "__version__"]
