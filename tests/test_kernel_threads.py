"""The engine's kernels run their speeds (or rows) in interleaved shares on threads, compiled once.

A ``parallel=True`` compilation would cost as much again as the serial one on every first run, and numba keys
its on-disk cache by a function's name and line only, so a serial and a parallel compilation of one function
shared one entry (a cache filled by a one-thread process made every "parallel" kernel serial). The kernels are
compiled once, without ``parallel``, releasing the GIL; :func:`persson.engine.jit.threaded` runs the shares.
"""

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.engine import jit, kernels
from persson.slip import heating_kernels

KERNELS = [kernels.friction_kernel, kernels.flash_kernel, heating_kernels._march_kernel]


@pytest.mark.parametrize("kernel", KERNELS, ids=["friction", "flash", "march"])
def test_kernels_are_compiled_once_without_parallel_and_release_the_gil(kernel):
    assert not kernel.targetoptions.get("parallel") and kernel.targetoptions.get("nogil")


def test_threaded_runs_every_share_once_with_the_calling_thread_taking_the_first(monkeypatch):
    seen = []

    def kernel(*, out, first, stride):
        seen.append((first, stride))
        out[first::stride] += 1.0

    for threads in (1, 2, 3):
        seen.clear()
        out = np.zeros(7)
        monkeypatch.setattr(jit, "_numba_threads", lambda t=threads: t)   # the thread count numba would give
        jit.threaded(kernel, out.size, min_items=2, out=out)
        np.testing.assert_array_equal(out, np.ones(7))                 # each item exactly once
        assert sorted(seen) == [(k, threads) if threads > 1 else (0, 1) for k in range(threads)]
    seen.clear()
    jit.threaded(kernel, 1, min_items=2, out=np.zeros(1))             # too few items: one share, here
    assert seen == [(0, 1)]


def test_results_do_not_depend_on_the_number_of_threads():
    import numba

    m = persson.Model(surfaces.example_road(), materials.example_tread(), effects=[persson.effects.FlashTemperature()])
    v = np.geomspace(1e-4, 3.0, 24)
    before = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = m.friction(v)
        numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
        many = m.friction(v)
    finally:
        numba.set_num_threads(before)
    np.testing.assert_array_equal(one.mu, many.mu)
    np.testing.assert_array_equal(one.temperature_q, many.temperature_q)


def test_a_forked_child_runs_its_kernels_on_threads_of_its_own():
    """multiprocessing with "fork" after the engine ran: the child's pool must not be the parent's (whose threads
    do not exist in the child), or the child would wait forever."""
    import multiprocessing as mp
    import sys

    if sys.platform == "win32" or "fork" not in mp.get_all_start_methods():
        pytest.skip("no fork on this platform")
    jit._pool(1).submit(lambda: None).result()          # the parent's pool, with a live thread
    ctx = mp.get_context("fork")
    with ctx.Pool(1) as pool:
        result = pool.apply_async(_child_threaded)
        assert result.get(timeout=60) == 6.0


def _child_threaded():
    jit._numba_threads = lambda: 2                       # two shares, whatever numba's setting in this process
    out = np.zeros(6)
    jit.threaded(lambda *, out, first, stride: out.__setitem__(slice(first, None, stride), 1.0), 6, out=out)
    return float(out.sum())


@pytest.mark.skipif(__import__("numba").config.DISABLE_JIT, reason="counts references of compiled code only")
def test_a_borrowed_view_reads_and_writes_the_callers_arrays_in_nested_tuples_and_strided_layouts():
    """:func:`persson.engine.borrow.borrowed` gives a kernel its arguments' arrays without their reference counts
    (no meminfo, which numba's counting skips): the same data, shapes and strides (writes land in the caller's
    arrays), scalars and nesting kept."""
    from collections import namedtuple

    from numba import njit

    from persson.engine.borrow import borrowed

    Pair = namedtuple("Pair", ["values", "scale"])

    @njit
    def axpy(pair, table, out):
        counted = _has_meminfo(pair.values) and _has_meminfo(table) and _has_meminfo(out)
        pair, table, out = borrowed((pair, table, out))
        for i in range(out.shape[0]):
            for j in range(out.shape[1]):
                out[i, j] = pair.values[j] * pair.scale + table[i, j]
        uncounted = not (_has_meminfo(pair.values) or _has_meminfo(table) or _has_meminfo(out))
        return counted, uncounted, pair.values.strides[0], table.shape[0], table.strides[1]

    values = np.arange(10.0)[::2]                      # a strided view (layout "A")
    table = np.arange(15.0).reshape(5, 3).T            # a transposed one (strides of 8 and 24 bytes)
    out = np.zeros((3, 5))
    counted, uncounted, stride, rows, col_stride = axpy(Pair(values, 2.5), table, out)
    assert counted and uncounted
    np.testing.assert_array_equal(out, values * 2.5 + table)
    assert (stride, rows, col_stride) == (values.strides[0], table.shape[0], table.strides[1])


def test_a_borrowed_value_is_the_value_itself_in_the_interpreter():
    """Called from Python (or in a kernel run with the JIT off) nothing is counted, and nothing changes."""
    from persson.engine.borrow import borrowed

    pair = (np.arange(3.0), (np.ones(2), 0.5))
    assert borrowed(pair) is pair


def _meminfo_intrinsic():
    from numba.core import types
    from numba.extending import intrinsic

    @intrinsic
    def has_meminfo(typingctx, array):
        """Whether numba counts the references of ``array`` (its meminfo pointer is not null)."""
        def codegen(context, builder, signature, args):
            ary = context.make_array(signature.args[0])(context, builder, value=args[0])
            return builder.icmp_unsigned("!=", ary.meminfo, ary.meminfo.type(None))

        return types.boolean(array), codegen

    return has_meminfo


_has_meminfo = _meminfo_intrinsic()
