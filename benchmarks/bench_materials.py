"""Timing of the materials package: master curves from real DMA data, table evaluation, strain factors.

Run ``python benchmarks/bench_materials.py [DATA_DIR]`` (default ``../shared/data/dma`` relative to the project
root). Prints, with the median of repeats where cheap:

* ``master_curve`` with the defaults (automatic shifts, temperature law by cross-validation, representation by
  misfit) on the pyvisco sample (T_ref = -5 C) and the Eplexor export (T_ref = 50 C), with the misfit of every
  option (shift law x representation): the numbers quoted in docs/materials.md;
* one evaluation of ``E(omega, T)`` on 1e5 points, interpolated table against Prony series;
* one ``StrainFactors.factors`` call on a (q, T) grid of 1e6 points.
"""

from __future__ import annotations

import statistics
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import materials

ROOT = Path(__file__).resolve().parents[1]


def timed(fn, repeats=1):
    """(result of the last call, median wall time in s)."""
    times, out = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return out, statistics.median(times)


def master_curves(data: Path) -> None:
    sets = (("pyvisco", data / "pyvisco" / "freq_user_raw.csv", -5.0), ("eplexor", data / "eplexor", 50.0))
    print("master curves from DMA (misfit = log-RMS against the isotherms)")
    for name, path, T_ref in sets:
        if not path.exists():
            print(f"  {name}: {path} not present, skipped")
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            dma = materials.read_dma(path)
            m, t = timed(lambda: materials.master_curve(dma, T_ref=T_ref))
            print(f"  {name}: default {m.misfit:.4f} ({m.representation}, {m.shift.kind}) in {t:.2f} s")
            for fit in ("table", "prony"):
                row = []
                for law in ("wlf", "arrhenius", "wlf+arrhenius", "tabulated"):
                    mm = materials.master_curve(dma, T_ref=T_ref, shift_law=law, fit=fit)
                    row.append(f"{law} {mm.misfit:.4f}")
                print(f"    {fit:5s}: " + ", ".join(row))


def evaluation() -> None:
    tread = materials.example_tread()
    f = np.logspace(-8, 14, 177)
    E = tread.E(2 * np.pi * f, 20.0)
    wlf = {"C1": 8.86, "C2": 101.6, "T_ref_C": 20.0}
    mapping = {"f_Hz": f, "E_storage_Pa": E.real, "E_loss_Pa": E.imag}
    table = materials.MasterCurve.from_table(mapping, wlf)
    prony = materials.MasterCurve.from_table(mapping, wlf, fit="prony")
    w = np.logspace(-6, 12, 100_000)
    for name, m in (("table", table), ("prony", prony)):
        _, t = timed(lambda: m.E(w, 35.0), repeats=7)
        print(f"  E(omega, T) on 1e5 points, {name}: {1e3 * t:.1f} ms")


def strain() -> None:
    T = np.array([0.0, 10.0, 30.0, 50.0])
    e = np.geomspace(1e-3, 0.5, 15)
    rows = [(t, s, 8e6 * (0.3 + 0.7 / (1 + s / 0.02)), 2e6 * (0.4 + 0.6 / (1 + s / 0.02))) for t in T for s in e]
    Ts, ss, E1, E2 = map(np.array, zip(*rows))
    sf = materials.strain_factors(materials.StrainSweep.from_arrays(Ts, ss, E1, E2))
    q_strain = np.geomspace(1e-4, 1.0, 1000)[:, None]
    temps = np.linspace(0.0, 60.0, 1000)[None, :]
    _, t = timed(lambda: sf.factors(q_strain, temps), repeats=5)
    print(f"  StrainFactors.factors on a 1000 x 1000 grid: {1e3 * t:.0f} ms")


def main(argv) -> None:
    data = Path(argv[1]) if len(argv) > 1 else ROOT.parent / "shared" / "data" / "dma"
    master_curves(data)
    print("evaluation")
    evaluation()
    strain()


if __name__ == "__main__":
    main(sys.argv)
