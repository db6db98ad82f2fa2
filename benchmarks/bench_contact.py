"""Timing of ``persson.contact``: pressure curves, elastic and viscoelastic, and the separation integral.

Run ``python benchmarks/bench_contact.py``. Prints the median wall time (after warm-up) of

* an elastic 100-pressure curve (E* = 4 MPa, 1e3 .. 1e7 Pa) on ``surfaces.example_road()``, uncorrected and with
  the ``xu2024`` area correction;
* a viscoelastic 100-pressure curve (``materials.example_tread()`` at 1 m/s, 20 C), which runs the friction engine;
* ``persson.contact.separation.mean_separation`` alone for 100 rows of G on 161 nodes (the part every friction call
  pays).
"""

from __future__ import annotations

import statistics
import time


def _median(fn, repeats: int = 15) -> float:
    fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> None:
    import numpy as np

    import materials
    import persson
    import surfaces
    from persson.contact import separation

    road, tread = surfaces.example_road(), materials.example_tread()
    p = np.geomspace(1e3, 1e7, 100)
    q = np.geomspace(*road.q_range, 161)
    C = road.C(q)
    m3 = np.concatenate([[0.0], np.cumsum(separation.segment_moments(q, C, 3))])
    G = np.pi / 4 * (4e6 / p[:, None]) ** 2 * m3[None, :]
    rows = [
        ("elastic, 100 pressures", lambda: persson.contact(road, 4e6, p)),
        ("elastic, 100 pressures, xu2024", lambda: persson.contact(road, 4e6, p, correction="xu2024")),
        ("viscoelastic, 100 pressures", lambda: persson.contact(road, tread, p, speed=1.0, temperature=20.0)),
        ("mean_separation, 100 x 161", lambda: separation.mean_separation(q, C, G, 0.5)),
    ]
    print(f"{'what':40s} {'median (ms)':>12s}")
    for name, fn in rows:
        print(f"{name:40s} {1e3 * _median(fn):12.2f}")


if __name__ == "__main__":
    main()
