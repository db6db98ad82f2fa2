"""Running a numba kernel over independent speeds (or rows) on several threads.

The kernels loop over their problems with a start and a stride (``first``, ``stride``) and are compiled once,
without ``parallel=True``, releasing the GIL (``nogil=True``): :func:`threaded` runs the shares
``first = 0, 1, ..., T - 1`` with stride T on T threads, each writing its own rows of the outputs. Interleaved
shares balance problems whose cost grows along the list (speeds sorted by value: hot, slow-to-converge flash
temperatures at the fast end).

Why not ``prange``: a ``parallel=True`` compilation costs as much again as the serial one (4.8 s more for the
friction kernel, 13 s for the flash kernel on the development machine), paid on every first run, and numba keys
its on-disk cache by the function's name and line, not by its flags, so a serial and a parallel compilation of
one function shared one cache entry (whichever was compiled first served both: a cache filled by a one-thread
process made every "parallel" kernel serial). Threads also leave nothing spinning between calls.

The number of threads is numba's (``NUMBA_NUM_THREADS``, or ``numba.set_num_threads``), so that settings made for
numba, e.g. one thread per process in a distributed sweep, apply here as well.
"""

from __future__ import annotations

import concurrent.futures
import os
import threading

__all__ = ["threaded", "before_first_call"]


def threaded(kernel, n: int, *, min_items: int = 2, **arguments) -> None:
    """``kernel(**arguments, first=k, stride=T)`` for k = 0 .. T-1 on T threads (the calling thread takes k = 0).

    Parameters
    ----------
    kernel : numba dispatcher
        Compiled with ``nogil=True``; loops over its problems ``first, first + stride, ...`` and writes only their
        rows of the outputs.
    n : int
        Number of problems.
    min_items : int
        Fewer problems than this run on the calling thread alone (starting threads would cost more than it saves).
    **arguments
        The kernel's other arguments, by keyword.
    """
    if _BEFORE:
        _run_before(kernel)
    threads = min(_numba_threads(), int(n))
    if threads <= 1 or n < min_items:
        kernel(**arguments, first=0, stride=1)
        return
    pool = _pool(threads - 1)
    futures = [pool.submit(kernel, **arguments, first=k, stride=threads) for k in range(1, threads)]
    try:
        kernel(**arguments, first=0, stride=threads)
    finally:
        for f in futures:
            f.result()


def before_first_call(kernel, wait) -> None:
    """Run ``wait()`` before :func:`threaded` next runs ``kernel`` in this process, once (e.g. to wait for another
    process that is compiling it into numba's cache: :mod:`persson.warmup`).

    Parameters
    ----------
    kernel : numba dispatcher
    wait : callable
        Called without arguments; it must return (it may raise, which then reaches the kernel's caller).
    """
    _BEFORE[kernel] = wait


def _run_before(kernel) -> None:
    wait = _BEFORE.get(kernel)
    if wait is not None:
        wait()          # several threads may wait together: the callable must allow that
        _BEFORE.pop(kernel, None)


def _numba_threads() -> int:
    import numba

    return int(numba.get_num_threads())


def _pool(workers: int) -> concurrent.futures.ThreadPoolExecutor:
    """A thread pool of ``workers`` threads, kept for the next calls (threads are reused, not started per call)."""
    with _POOL_LOCK:
        pool = _POOLS.get(workers)
        if pool is None:
            pool = _POOLS[workers] = concurrent.futures.ThreadPoolExecutor(max_workers=workers,
                                                                          thread_name_prefix="persson-kernel")
        return pool


_POOLS: dict[int, concurrent.futures.ThreadPoolExecutor] = {}
#: What to run before a kernel's next call (:func:`before_first_call`).
_BEFORE: dict = {}
_POOL_LOCK = threading.Lock()


def _forget_pools_in_child() -> None:
    # a forked child (multiprocessing with "fork") inherits the pools without their threads: work handed to them
    # would never run, so the child starts its own
    global _POOL_LOCK
    _POOLS.clear()
    _BEFORE.clear()     # waits for the parent's own warm-up process: not this child's
    _POOL_LOCK = threading.Lock()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_pools_in_child)
