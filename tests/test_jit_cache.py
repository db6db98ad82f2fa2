"""Each kernel compiled in parallel and on one thread has its own entry in numba's on-disk cache.

numba keys a cached function by its qualified name and first line, not by ``parallel=True``: two compilations
of one Python function would share one entry, and a cache filled by a one-thread process would serve the serial
code to the parallel dispatcher (every "parallel" kernel then ran on one thread).
"""

import pytest

from persson.engine import kernels
from persson.slip import heating_kernels

PAIRS = [(kernels.friction_parallel, kernels.friction_serial),
         (heating_kernels._march_parallel, heating_kernels._march_serial)]


@pytest.mark.parametrize("parallel, serial", PAIRS, ids=["friction", "march"])
def test_parallel_and_serial_kernels_are_cached_apart(parallel, serial):
    assert parallel.targetoptions.get("parallel") and not serial.targetoptions.get("parallel")
    assert parallel.py_func.__qualname__ != serial.py_func.__qualname__
    assert parallel.py_func.__code__ is serial.py_func.__code__          # the same code, compiled twice
    assert serial.py_func.__doc__ == parallel.py_func.__doc__
