"""Time and peak memory of reading a long profile: the profile CSV and the CAPTIF export (surfaces.read_profiles).

Usage::

    python benchmarks/bench_readers.py [--points 10000000] [--folder DIR]

Writes a synthetic profile of ``--points`` samples in both formats (kept in ``--folder`` for reuse; default a
temporary folder), then reads each file in a fresh Python process and reports the wall time of the read and the
peak resident memory of that process (``ru_maxrss``, which includes the interpreter and numpy, about 0.1 GB).
Target (issue 13): 1e7 points in <= 15 s and <= 1 GB.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

_READ = """
import resource, sys, time
t0 = time.perf_counter()
import surfaces
t1 = time.perf_counter()
ps = surfaces.read_profiles(sys.argv[1], **({"trim_plates": False} if sys.argv[2] == "captif" else {}))
t2 = time.perf_counter()
print(f"{t2 - t1:.3f} {ps[0].n} {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss}")
"""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--points", type=int, default=10_000_000)
    ap.add_argument("--folder", default=None, help="where the test files are written (and reused)")
    args = ap.parse_args(argv)
    folder = Path(args.folder) if args.folder else Path(tempfile.mkdtemp(prefix="persson-bench-"))
    folder.mkdir(parents=True, exist_ok=True)
    files = {"csv": folder / f"profile_{args.points}.csv", "captif": folder / f"profile_{args.points}.dat"}
    for kind, path in files.items():
        if not path.is_file():
            t = time.perf_counter()
            _write(path, kind, args.points)
            print(f"wrote {path} ({path.stat().st_size / 1e6:.0f} MB) in {time.perf_counter() - t:.0f} s")
    print(f"{'format':8s} {'points':>10s} {'read s':>8s} {'peak GB':>8s}")
    for kind, path in files.items():
        out = subprocess.run([sys.executable, "-c", _READ, str(path), kind], capture_output=True, text=True,
                             check=True).stdout.split()
        peak = int(out[2]) / 1024**2  # ru_maxrss is in KiB on Linux
        print(f"{kind:8s} {int(out[1]):10d} {float(out[0]):8.2f} {peak:8.2f}")
    return 0


def _write(path: Path, kind: str, n: int) -> None:
    rng = np.random.default_rng(0)
    block = 1_000_000
    with open(path, "w", newline="" if kind == "csv" else None) as fh:
        if kind == "csv":
            fh.write("x_mm,z_mm\n")
        else:
            fh.write("Road Name\tBENCH\t\nRef Station\t0\t\n*****DATA*****\t\t\n"
                     "Data Point No:\tDistance (mm)\tDepth (mm)\n")
        z0 = 0.0
        for start in range(0, n, block):
            i = np.arange(start, min(n, start + block))
            x = i * 0.0375
            z = z0 + np.cumsum(rng.normal(scale=0.01, size=i.size))
            z0 = z[-1]
            if kind == "csv":
                lines = [f"{a:.4f},{b:.4f}" for a, b in zip(x.tolist(), z.tolist())]
            else:
                lines = [f"{k + 1}.000\t{a:.3f}\t{b:.3f}" for k, a, b in zip(i.tolist(), x.tolist(), z.tolist())]
            fh.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    sys.exit(main())
