"""Specification of the first-run warm-up: the heated patch's kernel compiled in a second process (persson.warmup).

On a fresh install numba compiles every kernel on its first call. The patch's march does not depend on the
engine's kernels, so a command that will fit patch heating starts a second process that compiles it while the
first compiles the engine's; the march's first call waits for that process and loads the kernel from numba's
cache. What must hold: the second process compiles exactly the types every patch-heating solution uses (else
the wait buys nothing), the first process then loads instead of compiling, and nothing is started when the cache
already holds the kernel or the user switched the warm-up off.
"""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numba
import numpy as np
import pytest

import materials
import persson
import surfaces
from persson import warmup
from persson.effects import PatchHeating
from persson.engine import jit
from persson.slip import Contact, heating_kernels, patch_friction

ROOT = Path(__file__).resolve().parents[1]


def _march_types(monkeypatch, run) -> list:
    """The numba types of the arguments of every call of the march kernel made by ``run()``."""
    seen = []
    real = heating_kernels.threaded

    def spy(kernel, n, **arguments):
        if kernel is heating_kernels._march_kernel:
            seen.append(tuple((k, numba.typeof(v)) for k, v in sorted(arguments.items())))
        return real(kernel, n, **arguments)

    monkeypatch.setattr(heating_kernels, "threaded", spy)
    run()
    monkeypatch.setattr(heating_kernels, "threaded", real)
    return seen


@pytest.mark.filterwarnings("ignore::persson.PhysicsWarning")   # the example road's rms slope (irrelevant here)
def test_the_warmup_compiles_the_types_of_a_real_patch_heating_solution(monkeypatch):
    grid = persson.GridSettings(q_per_decade=8, n_phi=16, omega_per_decade=16, tolerance=1e-2)
    contact = Contact(0.02, 0.01, 3.0e9, "parabolic")
    slips = np.array([0.02, 0.2, 1.0])

    def engine_patch(model, profiles):
        def run():
            patch_friction(model, PatchHeating(), contact, slips, 2.0, 10.0, 0.4e6, profiles=profiles)
        return run

    plain = persson.Model(surfaces.example_road(), materials.example_tread(), grid=grid)
    flash = plain.with_effect(persson.effects.FlashTemperature())
    real = (_march_types(monkeypatch, engine_patch(plain, False)) + _march_types(monkeypatch, engine_patch(plain, True))
            + _march_types(monkeypatch, engine_patch(flash, False)))
    warm = _march_types(monkeypatch, warmup.compile_march)
    assert real and warm
    assert {t for t in real} == {warm[0]}


def test_a_registered_wait_runs_once_before_the_kernel_and_not_again():
    log = []

    def kernel(first, stride, out):
        log.append(("kernel", first, stride))

    jit.before_first_call(kernel, lambda: log.append("wait"))
    jit.threaded(kernel, 1, min_items=10, out=None)
    jit.threaded(kernel, 1, min_items=10, out=None)
    assert log == ["wait", ("kernel", 0, 1), ("kernel", 0, 1)]
    assert kernel not in jit._BEFORE


def test_nothing_is_started_when_the_cache_holds_the_kernel_or_the_user_switched_it_off(monkeypatch):
    warmup.compile_march()      # this process has the kernel now, and numba's cache holds it
    assert warmup._cached(heating_kernels._march_kernel)
    assert warmup.start() is False
    monkeypatch.setattr(warmup, "_cached", lambda kernel: False)
    monkeypatch.setenv(warmup.ENV, "0")
    assert warmup.start() is False
    monkeypatch.delenv(warmup.ENV)
    monkeypatch.setattr(sys, "frozen", True, raising=False)   # a frozen application cannot run python -m
    assert warmup.start() is False
    assert heating_kernels._march_kernel not in jit._BEFORE


@pytest.mark.slow
def test_on_a_cold_cache_the_second_process_compiles_and_this_one_loads(tmp_path):
    # a fresh numba cache, as on a fresh install: the parent starts the warm-up, then runs a patch solution whose
    # march must come from the cache (a hit, no compilation here); a later process finds it and starts nothing
    script = textwrap.dedent("""
        import persson.warmup as w
        from persson.slip import heating_kernels as hk
        started = w.start()
        w.compile_march()
        st = hk._march_kernel.stats
        print(started, sum(st.cache_hits.values()), sum(st.cache_misses.values()))
    """)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"), PYTHONPATH=str(ROOT))
    env.pop(warmup.ENV, None)
    first = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=600,
                           cwd=tmp_path)
    assert first.returncode == 0, first.stderr
    assert first.stdout.split() == ["True", "1", "0"]
    again = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, timeout=600,
                           cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    assert again.stdout.split() == ["False", "1", "0"]
