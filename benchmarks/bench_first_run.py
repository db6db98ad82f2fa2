"""Wall time of the first and the second ``persson demo`` (the README's first-run claim).

Usage::

    python benchmarks/bench_first_run.py

The first run starts with an empty numba cache (``NUMBA_CACHE_DIR`` points at a new folder, so the kernels are
compiled as on a fresh install; the project's own cache is left alone), the second reuses what the first compiled.
Each run is a fresh process in its own empty folder; the load average of the machine is printed beside the times,
since on a shared machine the numbers grow with it.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def main() -> int:
    with tempfile.TemporaryDirectory(prefix="persson-first-run-") as tmp:
        env = dict(os.environ, NUMBA_CACHE_DIR=str(Path(tmp) / "numba-cache"))
        for label in ("first (cold numba cache)", "second"):
            work = Path(tempfile.mkdtemp(dir=tmp))
            load = os.getloadavg()[0]
            t = time.perf_counter()
            subprocess.run([sys.executable, "-m", "persson", "demo", "-q"], cwd=work, env=env, check=True,
                           capture_output=True, text=True)
            print(f"persson demo, {label:<26} {time.perf_counter() - t:7.1f} s   (load average {load:.1f}, "
                  f"{os.cpu_count()} cores)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
