"""A first run on a fresh install: the heated patch's kernel compiled in a second process, beside this one.

numba compiles a kernel on its first call and keeps it in its on-disk cache for every later run. On a fresh
install (or after an upgrade) a command that fits patch heating, such as ``persson demo``, compiles the engine's
friction kernel, its flash-temperature kernel and the heated patch's march one after the other (about 5, 9 and
7 s on a 2-core development machine). The march does not need the engine's kernels to be compiled: its types are
fixed by the patch's arrays, not by the friction model that fills them. :func:`start` therefore compiles it in a
second process, on another core, while this one goes on (imports, the engine's kernels, the first fits); the
march's first call here waits for that process (:func:`persson.engine.jit.before_first_call`), and numba then
loads what it compiled from the cache instead of compiling it again.

Nothing is started when the cache already holds the march (every run after the first), when numba's compilation
is switched off, or when the environment sets ``PERSSON_WARMUP=0``. If the second process fails or takes longer
than :data:`WAIT_S`, this one compiles the kernel itself, as it would have without it; a process still running
when this one exits is stopped.

Run as ``python -m persson.warmup`` it is the second process: it compiles the march and exits.
"""

from __future__ import annotations

import atexit
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

__all__ = ["start", "WAIT_S", "ENV"]

#: The environment variable that switches the warm-up off (``0``).
ENV = "PERSSON_WARMUP"
#: Longest wait for the second process, s; past it this process compiles the kernel itself.
WAIT_S = 300.0


def start() -> bool:
    """Compile the heated patch's march kernel in a second process when numba's cache does not hold it yet.

    Call it early in a run that will use patch heating (the command-line tools do when a case has a contact
    patch). The march's first call in this process waits for the second one.

    Returns
    -------
    bool
        Whether a second process was started (False when the cache already holds the kernel, a warm-up has
        already started in this process, ``PERSSON_WARMUP=0``, numba does not compile, or the interpreter is a
        frozen application's).
    """
    from .engine import jit
    from .slip import heating_kernels

    kernel = heating_kernels._march_kernel
    # a frozen application's executable is the application, not a Python that runs -m
    if (os.environ.get(ENV, "1") == "0" or getattr(sys, "frozen", False) or kernel in jit._BEFORE
            or _cached(kernel)):
        return False
    env = dict(os.environ, **{ENV: "0"})
    # the second process must import this very package (and so share its numba cache), whatever sys.path the
    # caller set up
    root = str(Path(__file__).resolve().parents[1])
    env["PYTHONPATH"] = os.pathsep.join([root] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
    try:
        proc = subprocess.Popen([sys.executable, "-m", "persson.warmup"], env=env, stdin=subprocess.DEVNULL,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    except OSError:
        return False
    jit.before_first_call(kernel, lambda: _wait(proc))
    atexit.register(_stop, proc)
    return True


def compile_march() -> None:
    """Run the march once, on a patch whose local friction is a closed formula (no engine kernel is compiled):
    numba compiles the march and its helpers for the argument types of every patch-heating solution and writes
    them to its cache."""
    from materials import example_tread

    from .effects import PatchHeating
    from .slip import Contact, patch_friction

    contact = Contact(0.02, 0.01, 3.0e9, "parabolic")
    patch_friction(_Formula(example_tread()), PatchHeating(), contact, np.array([0.05, 0.3, 1.0]), 1.0, 20.0,
                   0.3e6)


# ----------------------------------------------------------------------------------------------------------
def _cached(kernel) -> bool:
    """Whether numba's on-disk cache holds a compilation of ``kernel`` for this version of its source (True when
    that cannot be told: then nothing is started)."""
    try:
        return bool(kernel._cache._cache_file._load_index())
    except Exception:  # noqa: BLE001  (numba's cache internals, or no cache at all: do nothing)
        return True


def _wait(proc) -> None:
    try:
        proc.wait(timeout=WAIT_S)
    except subprocess.TimeoutExpired:
        _stop(proc)


def _stop(proc) -> None:
    if proc.poll() is None:
        proc.terminate()
        try:
            proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()


class _Formula:
    """A local friction given by a formula of speed and temperature (what the patch needs of a model)."""

    effect_names = ()

    def __init__(self, material):
        self.material = material

    def friction(self, speed, temperature=20.0, pressure=0.3e6):
        v, T, _ = np.broadcast_arrays(np.asarray(speed, dtype=float), np.asarray(temperature, dtype=float),
                                      np.asarray(pressure, dtype=float))
        return _Mu(0.9 + 0.05 * np.log10(v) - 0.002 * (T - 20.0))


class _Mu:
    def __init__(self, mu):
        self.mu = mu


if __name__ == "__main__":
    compile_march()
