"""Timing and outcome of the slip-curve fits: the multi-start Magic Formula fit and the brush fit with its peak held.

Run ``python benchmarks/bench_fits.py``. For Pacejka's dry- and wet-tarmac curves and two corners away from them
(40 noise-free slips from 0.025 to 1, and the same with noise 0.01), prints the median CPU time of
``fit_magic_formula`` and ``fit_brush``, the largest relative parameter error of the Magic Formula fit and the slip
at the brush fit's peak against the curve's own (closed form).
"""

from __future__ import annotations

import math
import statistics
import time
import warnings

CURVES = {"dry tarmac": (10.0, 1.9, 1.0, 0.97), "wet tarmac": (12.0, 2.3, 0.82, 1.0),
          "low C, E 0.3": (25.0, 1.3, 1.1, 0.3), "E -2": (6.0, 1.45, 0.7, -2.0)}


def _cpu(fn, repeats: int = 3):
    times, out = [], None
    for _ in range(repeats):
        t0 = time.process_time()
        out = fn()
        times.append(time.process_time() - t0)
    return statistics.median(times), out


def main() -> None:
    import numpy as np
    from scipy.optimize import brentq

    from persson import slip as ps

    warnings.simplefilter("ignore")
    s = np.linspace(0.025, 1.0, 40)
    print(f"{'curve':14s} {'noise':>6s} {'MF cpu (s)':>10s} {'MF max rel err':>15s} {'brush cpu (s)':>13s} "
          f"{'brush peak':>10s} {'exact peak':>10s}")
    for name, (B, C, D, E) in CURVES.items():
        X = math.tan(math.pi / (2 * C))
        exact = brentq(lambda x: B * x - E * (B * x - math.atan(B * x)) - X, 1e-9, 10.0)
        for noise in (0.0, 0.01):
            y = ps.magic_formula(s, B, C, D, E) + np.random.default_rng(3).normal(0.0, noise, s.size)
            t_mf, mf = _cpu(lambda: ps.fit_magic_formula(s, y))
            t_b, br = _cpu(lambda: ps.fit_brush(s, y), repeats=1)
            err = float(np.max(np.abs(mf.values / np.array([B, C, D, E]) - 1)))
            print(f"{name:14s} {noise:6.3f} {t_mf:10.3f} {err:15.2e} {t_b:13.3f} {br.slip_at_peak:10.4f} "
                  f"{exact:10.4f}")


if __name__ == "__main__":
    main()
