"""persson: rubber friction from Persson's multiscale contact theory.

Pipeline: a surface PSD (:mod:`surfaces`) and a viscoelastic material (:mod:`materials`) go into a
:class:`Model`; ``Model.friction(speed, temperature, pressure)`` returns a :class:`FrictionResult`.
Effects (:mod:`persson.effects`) add physics on top of the baseline; :mod:`persson.slip` turns sliding friction
into friction vs slip ratio; :mod:`persson.sweeps` runs band and parameter studies. :func:`contact` gives the
contact mechanics alone (area, separation, elastic energy, penetration depth vs pressure); :mod:`persson.tread`
drives a patterned tyre tread over measured road profiles (ABS-peak and locked-wheel friction, wet and dry).
"""

from . import _moved

_moved.install()  # old module paths (persson.model, persson.tire, ...) keep importing

from . import effects, slip, sweeps, tread  # noqa: E402
from .contact.mechanics import ContactResult, contact  # noqa: E402
from .engine.grid import GridSettings  # noqa: E402
from .engine.model import Model  # noqa: E402
from .engine.results import FrictionResult  # noqa: E402
from .errors import AccuracyWarning, ConvergenceWarning, InputError, PhysicsWarning  # noqa: E402

tire = slip  # the curve laws of the earlier persson.tire module live in persson.slip

__version__ = "0.1.0"

__all__ = ["Model", "FrictionResult", "GridSettings", "InputError", "ConvergenceWarning", "AccuracyWarning",
           "PhysicsWarning", "effects", "slip",
           "sweeps", "tire", "tread", "contact", "ContactResult", "__version__"]
