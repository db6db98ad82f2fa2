"""Timing of the two-coefficient brush identified from Magic Formulas (the trailer article's Figure 18).

Run ``python benchmarks/bench_brush_identify.py``. Prints the median time (after a warm-up) of
:func:`persson.slip.identify_two_coefficient` on the seed's Magic Formula (peak 1.156 at 11 %, 0.679 at 93 %):

* one formula without and with its covariance (the propagation re-identifies at 8 perturbed parameter sets);
* 200 formulas in one call (a road of 200 positions), without and with covariances;
* the peak-ratio map of the article's Figure 20 (8 x 11 points) with each kinematics.
"""

from __future__ import annotations

import os
import statistics
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from persson import slip as ps  # noqa: E402


def timed(fn, repeats: int = 3) -> float:
    fn()
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main() -> None:
    fit = ps.magic_formula_from_peak(0.11, 1.156, 0.93, 0.679, sigma=0.01, peak_slip_std=0.005)
    many = [fit.formula] * 200
    cov = np.repeat(fit.covariance[None], 200, axis=0)
    n1, n2 = np.linspace(0.1, 0.8, 8), np.linspace(1.0, 6.0, 11)
    cases = {
        "one formula": lambda: ps.identify_two_coefficient(fit.formula),
        "one formula with covariance": lambda: ps.identify_two_coefficient(fit),
        "200 formulas": lambda: ps.identify_two_coefficient(many),
        "200 formulas with covariances": lambda: ps.identify_two_coefficient(many, covariance=cov),
        "map 8 x 11, pacejka": lambda: ps.two_coefficient_map(n1, n2),
        "map 8 x 11, linear": lambda: ps.two_coefficient_map(n1, n2, kinematics="linear"),
    }
    for name, fn in cases.items():
        print(f"{name:32s} {timed(fn):7.3f} s")


if __name__ == "__main__":
    main()
