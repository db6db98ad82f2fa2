"""Timing of the friction engine: 100-speed curves, compile time and start-up with a warm numba cache.

Run ``python benchmarks/bench_friction.py``. Prints a small table:

* warm 100-speed curve (1e-8 .. 10 m/s, default grid, ``surfaces.example_road()`` with
  ``materials.example_tread()`` at 20 C and 0.3 MPa), baseline and with flash temperature (median of repeats),
  and with a strain-dependent modulus at every scale (``StrainSoftening(factors=...)``, synthetic strain sweeps),
  alone and with the flash temperature;
* warm calls with 1 and 10 speeds (small calls run on one thread);
* first call in a fresh process with an *empty* numba cache (compilation included);
* first result in a fresh process with the numba cache warm (import + first call), which users see
  on every run after the first.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import textwrap
import time

SNIPPET = textwrap.dedent("""
    import time
    t0 = time.perf_counter()
    import numpy as np
    import materials, persson, surfaces
    s = surfaces.example_road()
    m = materials.example_tread()
    effects = [persson.effects.FlashTemperature()] if {flash} else []
    r = persson.Model(s, m, effects=effects).friction(np.geomspace(1e-8, 10.0, 100), temperature=20.0, pressure=0.3e6)
    print(time.perf_counter() - t0)
""")


def strain_factors():
    """Synthetic strain sweeps of a filled compound: E' falls to 30 %, E'' to 60 % around 10 % strain."""
    import numpy as np

    import materials

    strain = np.geomspace(1e-4, 3.0, 30)
    T = np.array([0.0, 60.0])
    f = np.array([0.3 + 0.7 / (1 + (strain / 0.1) ** 1.2), 0.4 + 0.6 / (1 + (strain / 0.1) ** 1.2)])
    g = np.array([0.6 + 0.4 / (1 + strain / 0.1), 0.7 + 0.3 / (1 + strain / 0.1)])
    return materials.StrainFactors(strain, T, f, g, source="synthetic")


def warm_curve(flash: bool, strain: bool = False, n_speeds: int = 100, repeats: int = 20) -> float:
    """Median wall time, s, of an ``n_speeds`` curve after warm-up."""
    import warnings

    import numpy as np

    import materials
    import persson
    import surfaces

    effects = [persson.effects.FlashTemperature()] if flash else []
    if strain:
        effects.append(persson.effects.StrainSoftening(factors=strain_factors()))
    model = persson.Model(surfaces.example_road(), materials.example_tread(), effects=effects)
    warnings.simplefilter("ignore")  # the example road's rms slope (3.9) is warned on every call
    v = np.geomspace(1e-8, 10.0, n_speeds)
    model.friction(v, temperature=20.0, pressure=0.3e6)
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        model.friction(v, temperature=20.0, pressure=0.3e6)
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def fresh_process(flash: bool, cache_dir: str) -> float:
    """Wall time, s, from interpreter start to the first result in a new process using ``cache_dir``."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    t = time.perf_counter()
    subprocess.run([sys.executable, "-c", SNIPPET.format(flash=flash)], check=True, env=env,
                   capture_output=True, text=True)
    return time.perf_counter() - t


def main() -> None:
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        for flash in (False, True):
            label = "flash temperature" if flash else "baseline"
            cold = fresh_process(flash, cache)  # empty cache: compiles and writes it
            warm_start = fresh_process(flash, cache)  # cache warm
            rows.append((label, warm_curve(flash), cold, warm_start))
    print(f"{'100-speed curve':<20} {'warm call (ms)':>15} {'first process, cold cache (s)':>31} "
          f"{'new process, warm cache (s)':>29}")
    for label, warm, cold, start in rows:
        print(f"{label:<20} {warm * 1e3:>15.1f} {cold:>31.2f} {start:>29.2f}")
    lin = rows[0][1]
    for label, flash in (("strain-dependent", False), ("strain + flash", True)):
        t = warm_curve(flash, strain=True)
        print(f"{label:<20} {t * 1e3:>15.1f}   ({t / (rows[1][1] if flash else lin):.2f} x the same without strain)")
    for n in (1, 10):
        print(f"{n:>3} speed(s), baseline {warm_curve(False, n_speeds=n) * 1e3:.2f} ms, "
              f"flash {warm_curve(True, n_speeds=n) * 1e3:.2f} ms")
    print(f"(numba {__import__('numba').__version__}, {os.cpu_count()} cores, "
          f"NUMBA_NUM_THREADS={os.environ.get('NUMBA_NUM_THREADS', 'default')})")


if __name__ == "__main__":
    main()
