"""Every numba kernel documents each of its parameters, in the order of its signature.

A kernel is any numba dispatcher (an object with ``py_func``: ``@njit`` functions and ``njit(...)(f)`` wrappers)
defined in a module of ``persson``, ``surfaces`` or ``materials``. Its numpydoc ``Parameters`` section must name
the signature's parameters, the same names in the same order (``a, b : float`` documents two).
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

PACKAGES = ("persson", "surfaces", "materials")
ROOT = Path(__file__).resolve().parents[1]


def kernel_modules() -> list[str]:
    """Modules of the packages whose source uses numba (importing only those keeps the test fast)."""
    names = []
    for package in PACKAGES:
        for info in pkgutil.walk_packages([str(ROOT / package)], prefix=f"{package}."):
            path = ROOT.joinpath(*info.name.split("."))
            source = path / "__init__.py" if info.ispkg else path.with_suffix(".py")
            if source.is_file() and "numba" in source.read_text(encoding="utf-8"):
                names.append(info.name)
    return sorted(names)


def kernels() -> dict[str, object]:
    """Every numba dispatcher by qualified name of its Python function, once per function."""
    found = {}
    for name in kernel_modules():
        module = importlib.import_module(name)
        for obj in vars(module).values():
            func = getattr(obj, "py_func", None)
            if func is not None and func.__module__ == name:
                found[f"{name}.{func.__name__}"] = func
    return found


def documented_parameters(doc: str | None) -> list[str] | None:
    """The names in the numpydoc Parameters section of ``doc`` (None when it has none)."""
    lines = inspect.cleandoc(doc or "").splitlines()
    for i in range(len(lines) - 1):
        if lines[i].strip() == "Parameters" and re.fullmatch(r"-{3,}", lines[i + 1].strip()):
            break
    else:
        return None
    body = []
    for j in range(i + 2, len(lines)):
        if j + 1 < len(lines) and re.fullmatch(r"-{3,}", lines[j + 1].strip()):
            break  # the next section's title
        body.append(lines[j])
    indent = min((len(ln) - len(ln.lstrip()) for ln in body if ln.strip()), default=0)
    names = []
    for ln in body:
        if ln.strip() and len(ln) - len(ln.lstrip()) == indent:
            names += [n.strip() for n in ln.split(" : ")[0].split(",")]
    return names


def test_the_packages_have_kernels_and_the_parser_reads_numpydoc():
    found = kernels()
    assert len(found) > 40  # engine, flash temperature, patch heating, separation
    assert documented_parameters("""One line.

    Parameters
    ----------
    a, b : ndarray (n,)
        Two arrays.
    c : float
        A number, with a line
        that goes on.

    Returns
    -------
    float
    """) == ["a", "b", "c"]
    assert documented_parameters("No sections.") is None


def test_every_kernel_documents_each_parameter_in_signature_order():
    problems = []
    for name, func in sorted(kernels().items()):
        signature = list(inspect.signature(func).parameters)
        documented = documented_parameters(func.__doc__)
        if documented is None:
            problems.append(f"{name}: no Parameters section (signature {signature})")
        elif documented != signature:
            problems.append(f"{name}: documents {documented}, signature is {signature}")
    assert not problems, "kernels whose docstrings do not match their signatures:\n" + "\n".join(problems)


@pytest.mark.parametrize("module", ["persson.engine.kernel_arrays", "persson.slip.heating_arrays"])
def test_every_argument_bundle_documents_its_fields_in_order(module):
    # the named tuples the kernels take are documented like kernel parameters
    mod = importlib.import_module(module)
    bundles = [obj for obj in vars(mod).values()
               if isinstance(obj, type) and issubclass(obj, tuple) and hasattr(obj, "_fields")
               and obj.__module__ == module]
    assert bundles
    for cls in bundles:
        assert documented_parameters(cls.__doc__) == list(cls._fields), cls.__name__


def test_a_helper_of_a_fast_math_kernel_serves_no_other_kernel():
    """numba compiles a kernel's callees with the kernel's fast-math flags and keeps (and caches) that compilation as
    the callee's own: a helper shared by a fast-math kernel and another caller would round differently in the other
    caller depending on which of the two compiled it first. So the helpers a fast-math kernel calls are its own.
    (The patch march once carried "reassoc"; the T0 slice and the full interpolation it shares with other kernels
    then differed in the last bit wherever the march had been compiled first.)"""
    found = kernels()

    def direct(func):
        module = importlib.import_module(func.__module__)
        return {f"{func.__module__}.{n}" for n in func.__code__.co_names
                if hasattr(getattr(module, n, None), "py_func")}

    def callees(func):   # transitively: a callee's callees are compiled with the same flags
        seen, todo = set(), list(direct(func))
        while todo:
            helper = todo.pop()
            if helper not in seen and helper in found:
                seen.add(helper)
                todo += direct(found[helper])
        return seen

    shared = {}
    fast = []
    for name, func in found.items():
        dispatcher = getattr(importlib.import_module(func.__module__), func.__name__, None)
        if not (getattr(dispatcher, "targetoptions", {}) or {}).get("fastmath"):
            continue
        fast.append(name)
        for helper in callees(func):
            others = [other for other, f in found.items() if other != name and helper in direct(f)
                      and other not in callees(func)]
            if others:
                shared[helper] = others
    assert "persson.tread.kernels.march" in fast            # the check sees the flags where they are set
    assert shared == {}
