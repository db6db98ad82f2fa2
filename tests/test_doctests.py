"""The examples in the docstrings run, and show what they say (``>>>`` lines are checked like tests).

Every module of the packages in :data:`PACKAGES` whose source holds an example is run with :mod:`doctest`; an
example that is never run goes stale. The examples are kept cheap (no fits over many isotherms, no friction
runs), so that this file stays a fraction of a second.
"""

from __future__ import annotations

import doctest
import importlib
import pkgutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: Packages whose examples are run (``persson`` and ``validation`` may join once their examples are cheap).
PACKAGES = ("surfaces", "materials")


def modules_with_examples(packages=PACKAGES) -> list[str]:
    """Names of the modules of ``packages`` whose source contains a ``>>>`` example."""
    names = []
    for package in packages:
        for path in sorted((ROOT / package).rglob("*.py")):
            if ">>>" in path.read_text(encoding="utf-8"):
                parts = path.relative_to(ROOT).with_suffix("").parts
                names.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return names


def run_examples(module_name: str) -> doctest.TestResults:
    """Run the examples of one module (ellipsis and white-space differences allowed)."""
    module = importlib.import_module(module_name)
    return doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE, report=True)


@pytest.mark.parametrize("module_name", modules_with_examples())
def test_the_examples_of_the_module_run(module_name):
    result = run_examples(module_name)
    assert result.attempted > 0, f"{module_name}: examples found in the source but none collected"
    assert result.failed == 0, f"{module_name}: {result.failed} of {result.attempted} examples failed (see above)"


def test_the_packages_have_examples_to_run():
    """The list is not empty by accident: the modules known to carry examples are found."""
    found = set(modules_with_examples())
    assert {"materials.laws", "materials.mastercurve", "surfaces.psd", "surfaces.profiles"} <= found
    assert all(pkgutil.resolve_name(name) for name in found)
