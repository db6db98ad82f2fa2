"""Timing of the workflow commands the issues set goals for (run: ``python benchmarks/bench_workflow.py``).

* ``persson sweep`` of the shipped example case over 6 decade bands x 3 pressures (goal: 60 s on 2 cores);
* ``persson diagnose`` of the 150-row shipped case ``hidden_flash`` (goal: 60 s on 2 cores);
* ``persson demo`` (the whole loop).

Each command runs in a fresh process (numba cache warm after a first untimed run), wall time from start to exit.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import validation


def timed(args: list[str], cwd: str) -> float:
    """Wall time, s, of ``python -m persson ARGS`` in a new process."""
    t = time.perf_counter()
    subprocess.run([sys.executable, "-m", "persson", *args], cwd=cwd, check=True, capture_output=True, text=True)
    return time.perf_counter() - t


def main() -> None:
    example = str(validation.case_path("example"))
    flash = str(validation.case_path("hidden_flash"))
    with tempfile.TemporaryDirectory() as tmp:
        out = str(Path(tmp) / "sweep.csv")
        sweep = ["sweep", example, "--bands", "decades", "--n-bands", "6", "--param", "pressure=0.2e6:0.6e6:3",
                 "-o", out, "--no-progress"]
        timed(sweep, tmp)  # warm the numba cache
        rows = [
            ("sweep: 6 decade bands x 3 pressures", timed(sweep, tmp)),
            ("diagnose: hidden_flash (150 rows)", timed(["diagnose", flash, "--json", str(Path(tmp) / "dx.json")], tmp)),
            ("demo: compare, diagnose, improve, report", timed(["demo", "-o", str(Path(tmp) / "demo")], tmp)),
        ]
    for label, seconds in rows:
        print(f"{label:<45} {seconds:8.1f} s")


if __name__ == "__main__":
    main()
