"""Time of reducing a friction trailer's raw channels (validation.rigs): read, force-balance check, reduce, peaks.

Usage::

    python benchmarks/bench_rigs.py [--minutes 10] [--hz 100] [--step 1.0] [--repeat 3]

Writes a synthetic three-tire run (``--minutes`` at ``--hz``: 60,000 samples for 10 minutes at 100 Hz; load cells,
wheel speeds, chain channels, zero rows at both ends) to a temporary CSV, then times, best of ``--repeat``:

* ``read_trailer`` (parsing and checking the file),
* ``check_balance`` (frozen channels, moment balances),
* ``reduce`` with alignment (which runs the balance check again),
* ``peak_lock_along_road`` over ``--step`` m bins.

Target (issue 29): the reduction of a 10-minute run at 100 Hz with three tires in <= 2 s.
"""

from __future__ import annotations

import argparse
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

RIG = {"tires": [
    dict(wheel_radius_m=0.30, offset_m=0.00, l_left_m=0.12, l_right_m=0.10, l_span_m=0.45, mass_kg=20.0),
    dict(wheel_radius_m=0.31, offset_m=0.78, l_left_m=0.11, l_right_m=0.12, l_span_m=0.40, mass_kg=22.0),
    dict(wheel_radius_m=0.30, offset_m=1.67, l_left_m=0.12, l_right_m=0.10, l_span_m=0.45, mass_kg=20.0),
]}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--minutes", type=float, default=10.0)
    ap.add_argument("--hz", type=float, default=100.0)
    ap.add_argument("--step", type=float, default=1.0, help="road bin of the peak/lock identification, m")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    from validation import rigs

    with tempfile.TemporaryDirectory(prefix="persson-bench-") as folder:
        path = Path(folder) / "run.csv"
        n = _write(path, args.minutes, args.hz)
        print(f"{n} samples, 3 tires, {path.stat().st_size / 1e6:.1f} MB")
        raw = _best("read_trailer", args.repeat, lambda: rigs.read_trailer(path, RIG))
    _best("check_balance", args.repeat, lambda: rigs.check_balance(raw, RIG))
    rows = _best("reduce (aligned)", args.repeat, lambda: rigs.reduce(raw, RIG, align=True))
    _best("reduce (not aligned)", args.repeat, lambda: rigs.reduce(raw, RIG, align=False))
    prof = _best(f"peak_lock_along_road ({args.step:g} m)", args.repeat,
                 lambda: rigs.peak_lock_along_road(rows, step_m=args.step))
    print(f"{rows.n} rows, {prof.n} positions, {int(prof.identified.sum())} identified; balance: "
          f"{'ok' if rows.balance.ok else rows.balance.summary()}")
    return 0


def _best(label: str, repeat: int, fn):
    times = []
    out = None
    for _ in range(max(repeat, 1)):
        t = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = fn()
        times.append(time.perf_counter() - t)
    print(f"{label:34s} {min(times):8.3f} s (best of {len(times)})")
    return out


def _write(path: Path, minutes: float, hz: float) -> int:
    """A three-tire run on a road whose friction level wanders, with noise (see tests/test_rigs.py)."""
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 60.0 * minutes, 1.0 / hz)
    n = t.size
    v = 12.0 + 0.4 * np.sin(2 * np.pi * t / 9.0)
    x = 12.0 * t + 0.4 * 9.0 / (2 * np.pi) * (1.0 - np.cos(2 * np.pi * t / 9.0))
    zero = (t < 2.0) | (t >= t[-1] - 2.0)
    cols = {"t_s": t, "v_m_s": v, "zero": zero.astype(float)}
    for k, (tire, s) in enumerate(zip(RIG["tires"], (0.05, 0.14, 0.35)), start=1):
        lL, lR, ls, m, r = (tire[c] for c in ("l_left_m", "l_right_m", "l_span_m", "mass_kg", "wheel_radius_m"))
        road = x - tire["offset_m"]
        D = 1.0 + 0.15 * np.sin(2 * np.pi * road / 300.0)
        mu = D * np.sin(1.65 * np.arctan(12.0 * s))
        load = 500.0 + 15.0 * np.sin(2 * np.pi * t / 1.3 + k)
        fb, nl = np.where(zero, 0.0, mu * load), np.where(zero, 0.0, load)
        fcu, fcd = 250.0 + fb * r / 0.1, np.full(n, 250.0)
        th = np.radians(4.0 + k)
        cx, cz = (fcu + fcd) * np.cos(th), (fcu - fcd) * np.sin(th)
        fxl, fxr = np.linalg.solve(np.array([[1.0, 1.0], [lL, -lR]]), np.stack([fb + cx, -ls * cx]))
        fzl, fzr = np.linalg.solve(np.array([[1.0, 1.0], [-lL, lR]]), np.stack([nl - cz - m * 9.80665, -ls * cz]))
        e = rng.standard_normal((6, n))
        cols.update({f"fxl_{k}_N": fxl + 2 * e[0] + 0.05 * t, f"fxr_{k}_N": fxr + 2 * e[1],
                     f"fzl_{k}_N": fzl + 2 * e[2], f"fzr_{k}_N": fzr + 2 * e[3],
                     f"omega_{k}_rad_s": v * (1.0 - s) / r + 0.002 * v / r * e[4],
                     f"fcu_{k}_N": fcu + e[5], f"fcd_{k}_N": fcd + rng.standard_normal(n),
                     f"theta_{k}_deg": np.full(n, 4.0 + k)})
    names = list(cols)
    np.savetxt(path, np.column_stack([cols[c] for c in names]), delimiter=",", header=",".join(names), comments="",
               fmt="%.6f")
    return n


if __name__ == "__main__":
    raise SystemExit(main())
