"""Compiling one kernel both in parallel and on one thread, each with its own entry in numba's on-disk cache.

numba names a function's cache files after its qualified name and first line, and keys the entries inside by the
signature and the machine, not by the compilation flags (``numba.core.caching._CacheImpl``,
``IndexDataCacheFile._index_key``, numba 0.58-0.68). ``njit(cache=True, parallel=True)(f)`` and
``njit(cache=True)(f)`` of one function therefore share one entry: whichever is compiled first is loaded for both
afterwards, and a cache filled by a one-thread process (a test run) left every "parallel" kernel serial, at half
the speed on two cores. :func:`serial_twin` gives the one-thread compilation a function of its own name.
"""

from __future__ import annotations

import types

__all__ = ["serial_twin"]


def serial_twin(func: types.FunctionType) -> types.FunctionType:
    """A copy of the plain Python function ``func`` (same code, globals and docstring) named ``<name>_serial``, to be
    compiled without ``parallel=True`` next to ``func`` compiled with it."""
    twin = types.FunctionType(func.__code__, func.__globals__, func.__name__ + "_serial", func.__defaults__,
                              func.__closure__)
    twin.__qualname__ = func.__qualname__ + "_serial"
    twin.__doc__ = func.__doc__
    twin.__module__ = func.__module__
    return twin
