"""The import graph of the project's packages: layered, without cycles.

A module may import only modules below it. The graph is read from the source with :mod:`ast`, so an import
hidden inside a function (the usual way round a cycle) counts like one at the top of a module: both run the
other module's body, and both make the two modules impossible to read or test one without the other.
``surfaces`` knows nothing of rubber and ``materials`` nothing of surfaces; neither knows the engine
(``persson``) nor the validation loop (``validation``), which are built on them.
"""

from __future__ import annotations

import ast
from functools import lru_cache
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("persson", "surfaces", "materials", "validation")
BASE_PACKAGES = ("surfaces", "materials")  # the foundations: never import the engine or the validation loop
UPPER_PACKAGES = ("persson", "validation")


def import_graph(packages=PACKAGES, root=ROOT) -> dict[str, dict[str, int]]:
    """Modules of ``packages`` under ``root`` and the modules of those packages each one imports.

    Parameters
    ----------
    packages : sequence of str
        Top-level package names (folders under ``root``); only imports between their modules are kept.
    root : Path
        Folder holding the packages.

    Returns
    -------
    dict
        ``{module: {imported module: line of the first such import}}``. A package's ``__init__`` is the node
        named after the package. ``from pkg import name`` is an import of ``pkg.name`` when that is a module,
        else of ``pkg``; ``import a.b.c`` is an import of the longest prefix that is a module.
    """
    return _graph(tuple(packages), tuple(packages), Path(root))


def find_cycles(packages=PACKAGES, root=ROOT) -> list[list[tuple[str, int]]]:
    """One import cycle for every strongly connected group of modules (and every module importing itself).

    Parameters
    ----------
    packages : sequence of str
        Packages whose modules form the graph (see :func:`import_graph`).
    root : Path
        Folder holding the packages.

    Returns
    -------
    list of list of (str, int)
        Each cycle as ``[(module, line), ...]``: the module and the line where it imports the next one; the last
        one imports the first. Empty when the graph is acyclic.
    """
    graph = import_graph(packages, root)
    cycles = []
    for group in _strongly_connected(graph):
        if len(group) > 1 or next(iter(group)) in graph[next(iter(group))]:
            cycles.append(_cycle_within(graph, group))
    return cycles


def chain(cycle: list[tuple[str, int]]) -> str:
    """A cycle as one readable line: ``a (line 3) -> b (line 12) -> a``."""
    return " -> ".join(f"{m} (line {line})" for m, line in cycle) + f" -> {cycle[0][0]}"


def upward_imports(lower=BASE_PACKAGES, upper=UPPER_PACKAGES, root=ROOT) -> list[str]:
    """Imports from a module of ``lower`` into a module of ``upper``, as ``"module:line -> target"``."""
    graph = _graph(tuple(lower), tuple(lower) + tuple(upper), Path(root))
    return sorted(f"{m}:{line} -> {t}" for m, targets in graph.items() for t, line in targets.items()
                  if _top(t) in upper)


# --- the project's packages --------------------------------------------------------------------------------


@pytest.mark.parametrize("packages", [
    ("surfaces",),
    ("materials",),
    ("surfaces", "materials"),
    ("persson",),
    ("validation",),
    PACKAGES,
], ids=lambda p: "+".join(p))
def test_no_import_cycles(packages):
    cycles = find_cycles(packages)
    assert not cycles, "import cycles:\n" + "\n".join(chain(c) for c in cycles)


def test_surfaces_and_materials_import_neither_the_engine_nor_the_validation_loop():
    assert not upward_imports(), "upward imports:\n" + "\n".join(upward_imports())


def test_surfaces_and_materials_know_nothing_of_each_other():
    assert not upward_imports(("surfaces",), ("materials",)) and not upward_imports(("materials",), ("surfaces",))


def test_every_module_of_the_packages_is_in_the_graph():
    graph = import_graph()
    assert {"surfaces", "surfaces.psd", "materials", "materials.master", "persson", "validation"} <= set(graph)
    assert graph["materials"] and graph["surfaces"]  # the package __init__ files import their modules


def test_every_source_file_compiles_without_warnings():
    """An invalid escape in a string (a ``\\sigma`` in a docstring that is not raw) is a DeprecationWarning on
    Python 3.11, a SyntaxWarning on 3.12 and meant to become an error: every file of the packages, the benchmarks
    and the tests compiles with warnings turned into errors."""
    import warnings

    files = [p for d in PACKAGES + ("benchmarks", "tests") for p in sorted((ROOT / d).rglob("*.py"))]
    assert len(files) > 100
    for path in files:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            compile(path.read_text(encoding="utf-8"), str(path), "exec")


# --- the checker itself, on a small made-up tree ------------------------------------------------------------


@pytest.fixture(scope="module")
def toy(tmp_path_factory):
    """Two packages: ``low`` with a cycle closed inside a function and through ``from . import``; ``high``."""
    root = tmp_path_factory.mktemp("toy")
    files = {
        "low/__init__.py": "from .a import f\n",
        "low/a.py": "import os\nfrom .b import g\n\ndef f():\n    return g()\n",
        "low/b.py": "def g():\n    from . import c\n    return c.h()\n",
        "low/c.py": "import numpy as np\n\n\ndef h():\n    from low import a  # closes the cycle\n    return 1\n",
        "low/d.py": "from low.c import h\nimport low.b\n",
        "low/sub/__init__.py": "from ..d import h\n",
        "low/sub/e.py": "from .. import d\nfrom . import *\n",
        "high/__init__.py": "import low.sub.e\n",
        "high/up.py": "from high import up\n",
        "low/leak.py": "def peek():\n    import high.up\n",
    }
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    return root


def test_the_graph_resolves_relative_submodule_and_function_level_imports(toy):
    g = import_graph(("low", "high"), toy)
    assert g["low"] == {"low.a": 1}
    assert g["low.a"] == {"low.b": 2}
    assert g["low.b"] == {"low.c": 2}  # inside a function, and `from . import c` names the submodule
    assert g["low.c"] == {"low.a": 5}
    assert g["low.d"] == {"low.c": 1, "low.b": 2}
    assert g["low.sub"] == {"low.d": 1}
    assert g["low.sub.e"] == {"low.d": 1, "low.sub": 2}
    assert g["high"] == {"low.sub.e": 1} and g["high.up"] == {"high.up": 1}


def test_the_checker_reports_each_cycle_as_a_chain(toy):
    cycles = find_cycles(("low", "high"), toy)
    chains = sorted(chain(c) for c in cycles)
    assert len(chains) == 2
    assert "high.up (line 1) -> high.up" in chains
    abc = next(c for c in cycles if len(c) == 3)
    assert {m for m, _ in abc} == {"low.a", "low.b", "low.c"}
    for (m, line), (nxt, _) in zip(abc, abc[1:] + abc[:1]):
        assert import_graph(("low", "high"), toy)[m][nxt] == line
    assert find_cycles(("low",), toy) and not find_cycles(("low",), toy / "missing")


def test_the_checker_reports_an_upward_import(toy):
    assert upward_imports(("low",), ("high",), toy) == ["low.leak:2 -> high.up"]


# --- helpers -----------------------------------------------------------------------------------------------


def _top(module: str) -> str:
    return module.split(".", 1)[0]


def _graph(sources: tuple[str, ...], targets: tuple[str, ...], root: Path) -> dict[str, dict[str, int]]:
    """Imports of the modules of ``sources`` into modules of ``targets`` (only the sources are parsed)."""
    files = _module_files(targets, root)
    return {name: _imports_of(name, path, files) for name, path in _module_files(sources, root).items()}


@lru_cache(maxsize=None)
def _module_files(packages: tuple[str, ...], root: Path) -> dict[str, Path]:
    files = {}
    for package in packages:
        for path in sorted((root / package).rglob("*.py")):
            parts = path.relative_to(root).with_suffix("").parts
            files[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return files


def _imports_of(module: str, path: Path, files: dict[str, Path]) -> dict[str, int]:
    is_package = path.name == "__init__.py"
    targets: dict[str, int] = {}

    def add(name: str, line: int) -> None:
        while name and name not in files:  # `import a.b.C` of something that is no module: its module
            name = name.rpartition(".")[0]
        if name:
            targets.setdefault(name, line)

    for level, name, aliases, line in _import_statements(path):
        if aliases is None:                # import a.b, c
            add(name, line)
            continue
        base = _absolute(module, is_package, level, name)
        for alias in aliases:
            sub = f"{base}.{alias}"
            add(sub if alias != "*" and sub in files else base, line)
    return dict(sorted(targets.items(), key=lambda kv: kv[1]))


@lru_cache(maxsize=None)
def _import_statements(path: Path) -> tuple:
    """(level, module, imported names or None for ``import``, line) of every import statement in the file."""
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), filename=str(path))):
        if isinstance(node, ast.Import):
            out.extend((0, alias.name, None, node.lineno) for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            out.append((node.level, node.module, tuple(alias.name for alias in node.names), node.lineno))
    return tuple(out)


def _absolute(module: str, is_package: bool, level: int, name: str | None) -> str:
    if level == 0:
        return name or ""
    parts = module.split(".") if is_package else module.split(".")[:-1]
    parts = parts[: len(parts) - (level - 1)]
    return ".".join(parts + ([name] if name else []))


def _strongly_connected(graph: dict[str, dict[str, int]]) -> list[set[str]]:
    """Tarjan's algorithm (iterative): the strongly connected components of ``graph``."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    groups = []
    for start in graph:
        if start in index:
            continue
        work = [(start, iter(graph[start]))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next((c for c in children if c in graph), None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(graph[child])))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                group = set()
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    group.add(member)
                    if member == node:
                        break
                groups.append(group)
    return groups


def _cycle_within(graph: dict[str, dict[str, int]], group: set[str]) -> list[tuple[str, int]]:
    """A shortest cycle through the alphabetically first module of a strongly connected ``group``."""
    start = min(group)
    previous = {start: None}
    frontier = [start]
    while frontier:  # breadth first, inside the group, back to start
        following = []
        for node in frontier:
            for child in graph[node]:
                if child == start:
                    path = [node]
                    while previous[path[-1]] is not None:
                        path.append(previous[path[-1]])
                    path.reverse()
                    return [(m, graph[m][n]) for m, n in zip(path, path[1:] + [start])]
                if child in group and child not in previous:
                    previous[child] = node
                    following.append(child)
        frontier = following
    raise AssertionError(f"no cycle through {start} in {sorted(group)}")
