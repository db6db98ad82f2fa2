"""Timing of the workflow commands the issues set goals for (run: ``python benchmarks/bench_workflow.py``).

* ``persson diagnose`` of the shipped cases ``hidden_flash`` (150 rows) and ``example`` (74 rows);
* ``validation.improve`` of the blind case ``blind_two`` (two hidden effects to add);
* ``persson demo`` (the whole loop, report included), warm;
* with ``--sweep``: ``persson sweep`` of the example case over 6 decade bands x 3 pressures.

Each command runs in a fresh process (numba cache warm after a first untimed run), wall time from start to exit,
and the CPU time of the process (user + system, all threads; Python's bytecode cache on, as in an installation):
on a machine shared with other work the wall time grows with the load while the CPU time barely does, so the CPU
time is the fairer figure to compare.

``--baseline PATH`` times a second checkout (e.g. ``git worktree add /tmp/base <commit>``, or an exported tree)
with the same commands, each pair back to back (the two trees alternate, ``--repeat`` times; the best of each is
kept), and prints the ratios.
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def timed(args: list[str], cwd: str, tree: Path) -> tuple[float, float]:
    """(wall s, CPU s) of ``python ARGS`` in a new process importing the packages of ``tree``."""
    env = dict(os.environ, PYTHONPATH=str(tree))
    # warm caches include Python's bytecode: a shell that switches it off (PYTHONDONTWRITEBYTECODE) would make every
    # command compile the packages' sources again (about 0.3 s), which an installed package never does
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run([sys.executable, *args], cwd=cwd, check=True, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def commands(tmp: str, tree: Path, sweep: bool) -> list[tuple[str, list[str]]]:
    blind_two = ROOT / "tests" / "data" / "blind" / "blind_two"
    out = [
        ("diagnose: hidden_flash (150 rows)", ["-m", "persson", "diagnose", "hidden_flash", "--json",
                                               str(Path(tmp) / "dx1.json"), "--force", "-q"]),
        ("diagnose: example (74 rows)", ["-m", "persson", "diagnose", "example", "--json", str(Path(tmp) / "dx2.json"),
                                         "--force", "-q"]),
        ("improve: blind_two (two effects to add)",
         ["-c", f"import validation; validation.improve(validation.load_case({str(blind_two)!r}))"]),
        ("demo: compare, diagnose, improve, report", ["-m", "persson", "demo", "-o", str(Path(tmp) / "demo"),
                                                      "--force", "-q"]),
    ]
    if sweep:
        out.insert(0, ("sweep: 6 decade bands x 3 pressures",
                       ["-m", "persson", "sweep", "example", "--bands", "decades", "--n-bands", "6", "--param",
                        "pressure=0.2e6:0.6e6:3", "-o", str(Path(tmp) / "sweep.csv"), "--force", "--no-progress"]))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--baseline", default=None, help="a second source tree to time the same commands with")
    ap.add_argument("--repeat", type=int, default=1, help="timed runs of each command per tree (best kept)")
    ap.add_argument("--sweep", action="store_true", help="also time persson sweep")
    ap.add_argument("--only", default="", help="run only the commands whose label contains this text")
    args = ap.parse_args(argv)
    trees = [("this", ROOT)] + ([("baseline", Path(args.baseline).resolve())] if args.baseline else [])
    with tempfile.TemporaryDirectory() as tmp:
        cmds = [c for c in commands(tmp, ROOT, args.sweep) if args.only in c[0]]
        for _, tree in trees:   # warm the numba caches of each tree (compiled into its own __pycache__)
            timed(["-c", "import validation; validation.compare(*(lambda c: (c.model, c.measurements))"
                         "(validation.load_case('example')))"], tmp, tree)
        best: dict = {}
        for label, cmd in cmds:
            for _ in range(args.repeat):
                for name, tree in trees:
                    load = os.getloadavg()[0]
                    wall, cpu = timed(cmd, tmp, tree)
                    old = best.get((label, name))
                    if old is None or wall < old[0]:
                        best[(label, name)] = (wall, cpu, load)
    print(f"{os.cpu_count()} cores; best of {args.repeat}; wall s / CPU s (load average at the start)")
    head = f"{'command':<44}" + "".join(f"{n:>30}" for n, _ in trees)
    if args.baseline:
        head += f"{'ratio wall':>12}{'ratio CPU':>11}"
    print(head)
    for label, _ in cmds:
        line = f"{label:<44}"
        for name, _ in trees:
            wall, cpu, load = best[(label, name)]
            line += f"{wall:>12.1f} / {cpu:>6.1f} ({load:4.1f})"
        if args.baseline:
            (w0, c0, _), (w1, c1, _) = best[(label, "this")], best[(label, "baseline")]
            line += f"{w1 / w0:>12.2f}{c1 / c0:>11.2f}"
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
