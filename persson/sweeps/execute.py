"""Running the tasks of a sweep: serially, in local processes, or on a Dask cluster; progress and interruption.

Every backend runs the same pure function on the same pickled task, so the results are bit for bit the same.
"""

from __future__ import annotations

import concurrent.futures as cf
import math
import multiprocessing
import os
import sys
import time
from typing import Callable

from ..errors import InputError

__all__ = ["SweepInterrupted", "Progress", "run_tasks", "describe_scheduler"]


class SweepInterrupted(KeyboardInterrupt):
    """A sweep stopped by Ctrl-C (KeyboardInterrupt): carries the points computed so far.

    It is a :class:`KeyboardInterrupt`, so a script still stops on Ctrl-C unless it catches it.

    Attributes
    ----------
    table : persson.sweeps.Table
        The rows of the tasks that finished (in task order), comments saying the table is partial.
    done, total : int
        Tasks finished and tasks in the sweep.
    checkpoint : pathlib.Path or None
        The checkpoint CSV holding the same rows, when one was asked for.
    """

    def __init__(self, table, done: int, total: int, checkpoint=None):
        self.table = table
        self.done = done
        self.total = total
        self.checkpoint = checkpoint
        where = f"; rows also in {checkpoint}" if checkpoint else ""
        super().__init__(f"sweep interrupted after {done} of {total} tasks: the {len(table)} rows computed "
                         f"are in .table{where}")


class Progress:
    """Plain-text progress bar on stderr (no dependency).

    Parameters
    ----------
    total : int
        Number of tasks.
    mode : None, bool or callable
        None: show the bar only once the sweep has run for ``after_s`` seconds (long sweeps).
        True / False: always / never. A callable is called as ``mode(done, total)`` after each task instead.
    stream : file, optional
        Default ``sys.stderr``.
    after_s : float
        Delay before the bar appears in the automatic mode.
    """

    def __init__(self, total: int, mode=None, stream=None, after_s: float = 2.0, label: str = "sweep"):
        self.total = int(total)
        self.callback: Callable | None = mode if callable(mode) else None
        self.mode = None if callable(mode) else mode
        self.stream = stream if stream is not None else sys.stderr
        self.after_s = float(after_s)
        self.label = label
        self.start = time.monotonic()
        self.shown = False
        self._last = 0.0
        self._tty = bool(getattr(self.stream, "isatty", lambda: False)())

    def update(self, done: int) -> None:
        """Report ``done`` finished tasks."""
        if self.callback is not None:
            self.callback(done, self.total)
            return
        if self.mode is False:
            return
        now = time.monotonic()
        elapsed = now - self.start
        if self.mode is None and elapsed < self.after_s and not self.shown:
            return
        final = done >= self.total
        # a TTY is redrawn in place (at most 10 times a second); a log gets a line every 10 s and at the end
        if not final and now - self._last < (0.1 if self._tty else 10.0) and self.shown:
            return
        self._last = now
        self.shown = True
        frac = done / self.total if self.total else 1.0
        width = 30
        bar = "#" * int(round(frac * width)) + "-" * (width - int(round(frac * width)))
        eta = (elapsed / done * (self.total - done)) if done else math.nan
        eta_text = f", {eta:.0f} s left" if done and not final else ""
        text = f"{self.label} [{bar}] {done}/{self.total} ({100 * frac:.0f} %), {elapsed:.0f} s{eta_text}"
        if self._tty:
            self.stream.write("\r" + text + ("\n" if final else ""))
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def close(self) -> None:
        """End the bar's line if one is open."""
        if self.shown and self._tty:
            self.stream.write("\n")
            self.stream.flush()
            self.shown = False


def describe_scheduler(scheduler, workers=None) -> str:
    """Short text for messages: ``serial``, ``processes (n)``, ``dask <address>``, ``executor``."""
    kind = _kind(scheduler)
    if kind == "serial":
        return "serial"
    if kind == "processes":
        return f"{_workers(workers)} local processes"
    if kind == "dask-address":
        return f"dask scheduler {scheduler}"
    if kind == "dask-client":
        return f"dask client {getattr(scheduler, 'scheduler', '')}".strip()
    return type(scheduler).__name__


def run_tasks(func, tasks: list, results: dict, *, scheduler=None, workers: int | None = None,
              progress: Progress | None = None, on_result: Callable | None = None) -> dict:
    """Run ``func(task)`` for each task; store ``results[i]`` as task ``i`` finishes.

    Parameters
    ----------
    func : callable
        A module-level (picklable) pure function.
    tasks : list
        Picklable task objects; tasks whose index is already in ``results`` are skipped.
    results : dict
        Filled in place (so the caller keeps what finished when an exception, e.g. KeyboardInterrupt, escapes).
    scheduler : None, "serial", "processes", a Dask scheduler address ("tcp://host:port"), a
        ``distributed.Client``, or a :class:`concurrent.futures.Executor`.
    workers : int, optional
        Number of local processes for ``"processes"`` (default: the CPU count).
    progress : Progress, optional
    on_result : callable, optional
        Called as ``on_result(i, result)`` in this process after each task.
    """
    todo = [i for i in range(len(tasks)) if i not in results]
    kind = _kind(scheduler)

    def done(i, res):
        results[i] = res
        if on_result is not None:
            on_result(i, res)
        if progress is not None:
            progress.update(len(results))

    if kind == "serial" or not todo:
        for i in todo:
            done(i, func(tasks[i]))
        return results
    if kind in ("processes", "executor"):
        own = kind == "processes"
        ex = (cf.ProcessPoolExecutor(max_workers=_workers(workers), mp_context=multiprocessing.get_context("spawn"),
                                     initializer=_init_worker) if own else scheduler)
        futs = {}
        try:
            futs = {ex.submit(func, tasks[i]): i for i in todo}
            for fut in cf.as_completed(futs):
                done(futs[fut], fut.result())
        except BaseException:
            for f in futs:
                f.cancel()
            if own:
                ex.shutdown(wait=False, cancel_futures=True)
            raise
        if own:
            ex.shutdown(wait=True)
        return results
    # Dask
    import distributed

    client = distributed.Client(scheduler) if kind == "dask-address" else scheduler
    futs = {}
    try:
        futs = {client.submit(func, tasks[i], pure=False): i for i in todo}
        for fut in distributed.as_completed(list(futs)):
            done(futs[fut], fut.result())
    except BaseException:
        try:
            client.cancel(list(futs))
        except Exception:  # pragma: no cover - best effort on a broken connection
            pass
        raise
    finally:
        if kind == "dask-address":
            client.close()
    return results


# ---------------------------------------------------------------------------------------------------------
def _kind(scheduler) -> str:
    if scheduler is None or (isinstance(scheduler, str) and scheduler.strip().lower() in ("serial", "")):
        return "serial"
    if isinstance(scheduler, str):
        s = scheduler.strip()
        if s.lower() in ("processes", "process", "local"):
            return "processes"
        if "://" in s or (":" in s and s.rsplit(":", 1)[1].isdigit()):
            _need_distributed()
            return "dask-address"
        raise InputError(f"scheduler: expected 'serial', 'processes', a Dask scheduler address such as "
                         f"'tcp://host:8786', a distributed.Client or an Executor, got {scheduler!r}")
    if type(scheduler).__module__.split(".")[0] == "distributed" and hasattr(scheduler, "submit"):
        return "dask-client"
    if isinstance(scheduler, cf.Executor):
        return "executor"
    raise InputError(f"scheduler: expected 'serial', 'processes', a Dask scheduler address, a distributed.Client "
                     f"or a concurrent.futures.Executor, got {scheduler!r}")


def _need_distributed():
    try:
        import distributed  # noqa: F401
    except ImportError:  # pragma: no cover - dask is an optional dependency
        raise InputError("scheduler: a Dask scheduler address needs dask.distributed "
                         "(pip install 'dask[distributed]')") from None


def _workers(workers) -> int:
    if workers is None:
        return max(1, os.cpu_count() or 1)
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InputError(f"workers: expected a number of processes >= 1, got {workers!r}")
    return workers


def _init_worker():  # pragma: no cover - runs in the worker processes
    """One numba thread per worker process (the processes already use the cores)."""
    try:
        import numba

        numba.set_num_threads(1)
    except Exception:
        pass
