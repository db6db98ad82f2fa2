"""Old module paths of the engine, kept importable after the package was organised into wings.

User scripts and pickled objects (cached cases, sweep tasks) name modules such as ``persson.model`` or
``persson.effects.patch``; each such path now resolves to the module that holds the code, the same module object
(``persson.model is persson.engine.model``), so pickles, ``from persson.model import Model`` and monkeypatching
by old path all keep working. The finder answers only for the names below and is consulted after the normal
import system.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys

#: Old module path -> the module that holds its code now.
MOVED = {
    "persson.model": "persson.engine.model",
    "persson.solver": "persson.engine.solver",
    "persson._kernels": "persson.engine.kernels",
    "persson.grid": "persson.engine.grid",
    "persson.tabulate": "persson.engine.tabulate",
    "persson.results": "persson.engine.results",
    "persson.reference": "persson.engine.reference",
    "persson.corrections": "persson.contact.corrections",
    "persson.separation": "persson.contact.separation",
    "persson.case_schema": "persson.case.schema",
    "persson.case_cache": "persson.case.cache",
    "persson.cli": "persson.commands.cli",
    "persson.slip_plots": "persson.slip.plots",
    "persson.tire": "persson.slip",
    "persson.effects.patch": "persson.slip.heating",
}


class _Alias(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finder and loader that make an old module path an alias of the module's new home."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname not in MOVED:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec):
        module = importlib.import_module(MOVED[spec.name])
        # the import system overwrites __spec__ with this alias spec; keep the real one to put back
        spec.loader_state = module.__spec__
        return module

    def exec_module(self, module):
        """Nothing to run: the module was executed under its new name. Only its own ``__spec__`` is put back, so
        that its relative imports keep resolving against its real package."""
        module.__spec__ = module.__spec__.loader_state


def install() -> None:
    """Put the alias finder on ``sys.meta_path`` once (after the normal finders)."""
    if not any(isinstance(f, _Alias) for f in sys.meta_path):
        sys.meta_path.append(_Alias())
