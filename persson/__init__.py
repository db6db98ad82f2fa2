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

from . import effects, slip  # noqa: E402
from .contact.mechanics import ContactResult, contact  # noqa: E402
from .engine.grid import GridSettings  # noqa: E402
from .engine.model import Model  # noqa: E402
from .engine.results import FrictionResult  # noqa: E402
from .errors import AccuracyWarning, ConvergenceWarning, InputError, PhysicsWarning  # noqa: E402

tire = slip  # the curve laws of the earlier persson.tire module live in persson.slip

__version__ = "0.1.0"

#: Subpackages imported when first named (``persson.tread``, ``from persson import sweeps``): the tread-element
#: tool and the sweeps are not needed to compute or diagnose friction, and importing them costs about 30 ms at
#: every start-up of a command that does not use them.
_LAZY = ("sweeps", "tread")

__all__ = ["Model", "FrictionResult", "GridSettings", "InputError", "ConvergenceWarning", "AccuracyWarning",
           "PhysicsWarning", "effects", "slip",
           "sweeps", "tire", "tread", "contact", "ContactResult", "__version__"]


def __getattr__(name: str):
    """The subpackages of :data:`_LAZY`, imported on first use (PEP 562)."""
    if name in _LAZY:
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
