"""Timing of friction against slip with patch heating: a 40-slip x 3-speed sweep, warm.

Run ``python benchmarks/bench_slip.py``. Prints, for ``surfaces.example_road()`` with ``materials.example_tread()``
at 20 C and 0.3 MPa, a DRFT-like contact (l = 20 mm, w = 10 mm, k = 3e9 Pa/m, parabolic pressure, 401 nodes),
40 slips log-spaced from 0.5 % to 100 % at V = 0.3, 1 and 3 m/s (median of repeats after a warm-up):

* the brush model alone (mu(v_s) at T0, sigma0: one engine call);
* with :class:`persson.effects.PatchHeating` (two engine calls on the friction table, then the march along the
  patch), without and with the flash temperature;
* the engine evaluations spent on the table and the time of the march alone;
* one prediction of the 150 rows of the shipped case ``hidden_flash`` with patch heating (validation path).

Target (issue 16): the heated 40 x 3 sweep in <= 2 s warm.
"""

from __future__ import annotations

import os
import statistics
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

import materials  # noqa: E402
import persson  # noqa: E402
import surfaces  # noqa: E402
from persson import slip as ps  # noqa: E402
from persson.effects import FlashTemperature, PatchHeating  # noqa: E402

SLIPS = np.geomspace(0.005, 1.0, 40)
SPEEDS = np.array([0.3, 1.0, 3.0])


def timed(fn, repeats: int):
    fn()  # warm-up (compilation, caches)
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def main(repeats: int = 5) -> None:
    road, tread = surfaces.example_road(), materials.example_tread()
    contact = ps.Contact(length=0.02, width=0.01, stiffness=3.0e9, pressure_distribution="parabolic")
    rows = []
    for label, effects in [("brush, no heating", []),
                           ("patch heating", [PatchHeating()]),
                           ("patch heating + flash temperature", [PatchHeating(), FlashTemperature()]),
                           ("brush + flash temperature, no heating", [FlashTemperature()])]:
        model = persson.Model(road, tread, effects=effects)
        t, r = timed(lambda: ps.mu_slip(model, SLIPS[:, None], SPEEDS[None, :], temperature=20.0, pressure=0.3e6,
                                        contact=contact), repeats)
        pts = r.patch.table_points if r.patch is not None else r.friction.speed.size
        peak, at = r.peak(axis=0)
        rows.append((label, t, pts, peak, at, np.atleast_1d(r.mu)[-1]))
    print(f"40 slips x 3 speeds ({SPEEDS.tolist()} m/s), median of {repeats} warm runs")
    print(f"{'model':<40}{'time s':>8}{'engine pts':>12}  peak mu / slip at peak / locked mu per speed")
    for label, t, pts, peak, at, locked in rows:
        print(f"{label:<40}{t:>8.3f}{pts:>12d}  {np.round(peak, 3)} / {np.round(at, 3)} / {np.round(locked, 3)}")

    # the march alone (the table cached, as in a fit varying only the contact)
    from persson.slip import patch_friction

    model = persson.Model(road, tread, effects=[PatchHeating()])
    s, V = (a.ravel() for a in np.broadcast_arrays(SLIPS[:, None], SPEEDS[None, :]))
    cache: dict = {}
    t, _ = timed(lambda: patch_friction(model, model.effect("patch_heating"), contact, s, V, 20.0, 0.3e6,
                                        tables=cache), repeats)
    print(f"{'march along the patch only (table cached)':<40}{t:>8.3f}")

    import validation
    from validation.predict import Predictor

    case = validation.load_case("hidden_flash")
    pred = Predictor(case.measurements, case.contact)
    m = case.model.with_effect(PatchHeating())
    t, p = timed(lambda: pred.predict(m), max(1, repeats // 2))
    tp, _ = timed(lambda: pred.predict(case.model), repeats)
    print(f"{'hidden_flash, 150 rows, patch heating':<40}{t:>8.3f}   (without: {tp:.3f} s)")
    print(f"machine load average: {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
