"""Timing of :func:`persson.slip.fit_speed_laws`: every friction-speed law fitted to 20 points and ranked, warm.

Run ``python benchmarks/bench_speed_laws.py``. Prints the median time (after a warm-up that imports scipy and fills
the caches) of:

* ``fit_speed_laws`` on 20 speeds of one surface (an inverse S, Do-Marsac-Mosset with alpha = 3, noise 0.01): the
  seven laws of speed alone;
* the same on 20 rows of four surfaces with texture depth and BPN: the seven laws plus Dijks and the product form;
* each law alone on the 20 speeds.

Target (issue 28): all fits of ``fit_speed_laws`` for 20 points in <= 1 s.
"""

from __future__ import annotations

import os
import statistics
import sys
import time
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from persson import slip as ps  # noqa: E402


def timed(fn, repeats: int):
    """Median wall-clock and CPU seconds of ``fn()`` (the CPU time of this process is what a loaded, shared machine
    does not inflate)."""
    fn()  # warm-up
    wall, cpu = [], []
    for _ in range(repeats):
        t, c = time.perf_counter(), time.process_time()
        fn()
        wall.append(time.perf_counter() - t)
        cpu.append(time.process_time() - c)
    return statistics.median(wall), statistics.median(cpu)


def main(repeats: int = 5) -> None:
    rng = np.random.default_rng(0)
    V = np.linspace(1.0, 30.0, 20)
    mu = ps.do_marsac_mosset(V, 0.75, 18.0, 3.0) + rng.normal(0, 0.01, V.size)
    Vs = np.tile(np.linspace(3.0, 25.0, 5), 4)
    TD = np.repeat([0.4e-3, 0.9e-3, 1.6e-3, 2.5e-3], 5)
    BPN = np.repeat([45.0, 70.0, 58.0, 52.0], 5)
    mu_s = ps.wet_product(Vs, TD, BPN, 0.1, 0.009, 0.012, 4e-6) + rng.normal(0, 0.005, Vs.size)
    warnings.simplefilter("ignore")  # undetermined constants of ill-suited laws are warned about; not timed here
    (w1, c1), (w2, c2) = (timed(lambda: ps.fit_speed_laws(V, mu), repeats),
                          timed(lambda: ps.fit_speed_laws(Vs, mu_s, mtd=TD, bpn=BPN), repeats))
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; times are wall (CPU of this process)")
    print(f"fit_speed_laws, 20 speeds of one surface ({len(ps.fit_speed_laws(V, mu))} laws): {w1:.3f} s "
          f"({c1:.3f} s) (target <= 1 s)")
    print(f"fit_speed_laws, 20 rows on 4 surfaces with MTD and BPN "
          f"({len(ps.fit_speed_laws(Vs, mu_s, mtd=TD, bpn=BPN))} laws): {w2:.3f} s ({c2:.3f} s)")
    for law in ps.SPEED_LAW_NAMES[:7]:
        w, c = timed(lambda: ps.fit_speed_laws(V, mu, laws=[law]), repeats)
        print(f"  {law:<17} {1e3 * w:7.1f} ms ({1e3 * c:6.1f} ms)")


if __name__ == "__main__":
    main()
