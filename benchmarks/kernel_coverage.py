"""Line coverage of the numba kernel modules, measured with the JIT off.

Run ``python benchmarks/kernel_coverage.py [--quick] [--jobs N] [--jit] [pytest arguments ...]``. It runs the
kernel tests under coverage.py (``pip install coverage``) with ``NUMBA_DISABLE_JIT=1`` and prints, for every module
of ``persson``, ``surfaces`` and ``materials`` that defines numba kernels, its statements, the lines not run and
the line coverage, then each kernel below full coverage with its missed lines, and the time taken.

With the JIT on, coverage.py sees only the Python around the kernels: a compiled kernel's body never runs as
Python, so its lines read as missed (``--jit`` shows it). With ``NUMBA_DISABLE_JIT=1`` numba hands back the plain
Python functions and the tests run them line by line; ``prange`` becomes ``range``. That is slow: the engine's
kernels run 100-1000x slower as Python (a flash-temperature speed on a road takes about 2 s instead of 10 ms), and
the patch-heating tests, which tabulate the engine's friction at hundreds of points, take minutes each. The default
tests are the kernel tests (``tests/test_engine_*.py``, ``tests/test_effects.py``, ``tests/test_flash_geometry.py``,
``tests/test_slip_patch.py``, ``tests/test_contact*.py``): an hour or more with the JIT off on two cores (the first
seven of the patch tests took a quarter of an hour). ``--quick`` runs a subset that reaches every kernel in a few
minutes (:data:`QUICK_TESTS`: the effects, the flash geometry, contact, the engine's properties and warnings, and
the patch tests whose friction is a closed form): 92 % of the kernel lines in 135 s on two cores, where the same
tests with the JIT on take 25 s and reach 30 % (the module-level lines and the Python around the kernels). Pass
test files, node ids or ``-k`` expressions to choose others, and ``--jobs N`` to spread the test files over N
processes (coverage combines their data).
"""

from __future__ import annotations

import argparse
import ast
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("persson", "surfaces", "materials")
KERNEL_TESTS = ("tests/test_engine_*.py", "tests/test_effects.py", "tests/test_flash_geometry.py",
                "tests/test_slip_patch.py", "tests/test_contact*.py")
#: Tests that reach every kernel with the JIT off in minutes (the patch tests here take their friction from a
#: formula, not from tables of the engine's friction).
QUICK_TESTS = ("tests/test_effects.py", "tests/test_flash_geometry.py", "tests/test_contact.py",
               "tests/test_contact_corrections.py", "tests/test_contact_penetration.py",
               "tests/test_engine_properties.py", "tests/test_engine_warnings.py",
               "tests/test_slip_patch.py::test_without_heating_the_local_friction_follows_speed_and_local_pressure",
               "tests/test_slip_patch.py::test_temperature_along_the_patch_matches_the_closed_form_abel_solution",
               "tests/test_slip_patch.py::test_partition_of_the_heat_between_tread_and_counter_surface",
               "tests/test_slip_patch.py::test_a_patch_hotter_than_the_table_says_so",
               "tests/test_slip_patch.py::test_bad_input_to_the_patch")


def kernel_modules() -> list[Path]:
    """Source files that define numba kernels (``njit`` decorators or ``njit(...)(f)`` calls)."""
    files = []
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            if any(_is_njit(node) for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))):
                files.append(path)
    return files


def kernels_of(path: Path) -> dict[str, tuple[int, int]]:
    """The kernels of a module by name: the first and last line of each function that numba compiles (decorated
    with ``njit``, or wrapped by ``name = njit(...)(function)``)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    functions = {node.name: node for node in tree.body if isinstance(node, ast.FunctionDef)}
    wrapped = {arg.id for node in ast.walk(tree) if isinstance(node, ast.Call) and _is_njit(node.func)
               for arg in node.args if isinstance(arg, ast.Name)}
    return {name: (node.lineno, node.end_lineno) for name, node in functions.items()
            if name in wrapped or any(_is_njit(d) for d in node.decorator_list)}


def _is_njit(node) -> bool:
    if isinstance(node, ast.Call):
        node = node.func
    return isinstance(node, (ast.Name, ast.Attribute)) and getattr(node, "id", getattr(node, "attr", "")) == "njit"


def run(pytest_args: list[str], jobs: int, jit: bool, data_file: Path) -> float:
    """Run the tests under coverage (``jobs`` processes over the test files); returns the wall time, s."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]).rstrip(os.pathsep))
    if not jit:
        env["NUMBA_DISABLE_JIT"] = "1"
    files = [a for a in pytest_args if not a.startswith("-") and (ROOT / a.split("::")[0]).exists()]
    options = [a for a in pytest_args if a not in files]
    shares = [files[i::jobs] for i in range(jobs)] if files and jobs > 1 else [files]
    include = ",".join(str(p) for p in kernel_modules())
    t = time.perf_counter()
    procs = [subprocess.Popen([sys.executable, "-m", "coverage", "run", "--parallel-mode", f"--data-file={data_file}",
                               f"--include={include}", "-m", "pytest", "-q", "-p", "no:cacheprovider", *options,
                               *share], cwd=ROOT, env=env) for share in shares if share or not files]
    codes = [p.wait() for p in procs]
    wall = time.perf_counter() - t
    if any(c not in (0, 1) for c in codes):  # 1: some test failed; the coverage is still meaningful
        raise SystemExit(f"pytest exited with {codes}")
    subprocess.run([sys.executable, "-m", "coverage", "combine", f"--data-file={data_file}", str(data_file.parent)],
                   cwd=ROOT, check=True, capture_output=True)
    return wall


def report(data_file: Path) -> None:
    import coverage

    cov = coverage.Coverage(data_file=str(data_file))
    cov.load()
    total_statements = total_missed = 0
    print(f"{'kernel module':<40}{'statements':>11}{'missed':>8}{'coverage':>10}")
    partial = []
    for path in kernel_modules():
        _, statements, _, missing, _ = cov.analysis2(str(path))
        total_statements += len(statements)
        total_missed += len(missing)
        name = str(path.relative_to(ROOT))
        print(f"{name:<40}{len(statements):>11}{len(missing):>8}{_percent(statements, missing):>10}")
        for kernel, (first, last) in kernels_of(path).items():
            lines = [n for n in statements if first <= n <= last]
            missed = [n for n in missing if first <= n <= last]
            if missed:
                partial.append((f"{name}:{kernel}", lines, missed))
    print(f"{'all kernel modules':<40}{total_statements:>11}{total_missed:>8}"
          f"{100.0 * (1 - total_missed / max(total_statements, 1)):>9.1f}%")
    if partial:
        print("\nkernels not fully covered (missed lines):")
        for name, lines, missed in partial:
            print(f"  {name:<60} {_percent(lines, missed):>7}  {_ranges(missed)}")


def _percent(statements, missing) -> str:
    return f"{100.0 * (1 - len(missing) / max(len(statements), 1)):.1f}%"


def _ranges(lines: list[int]) -> str:
    out, start, prev = [], None, None
    for n in sorted(lines):
        if start is None:
            start = prev = n
        elif n == prev + 1:
            prev = n
        else:
            out.append(f"{start}-{prev}" if prev > start else f"{start}")
            start = prev = n
    if start is not None:
        out.append(f"{start}-{prev}" if prev > start else f"{start}")
    return ", ".join(out)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--jobs", type=int, default=1, help="pytest processes over the test files (default 1)")
    parser.add_argument("--jit", action="store_true", help="keep the JIT on (to see what coverage misses then)")
    parser.add_argument("--quick", action="store_true", help="the quick subset of the kernel tests (QUICK_TESTS)")
    args, pytest_args = parser.parse_known_args(argv)
    if args.quick:
        pytest_args += list(QUICK_TESTS)
    elif not any(not a.startswith("-") for a in pytest_args):
        pytest_args += sorted(str(p.relative_to(ROOT)) for pattern in KERNEL_TESTS for p in ROOT.glob(pattern))
    with tempfile.TemporaryDirectory() as folder:
        data_file = Path(folder) / ".coverage"
        wall = run(pytest_args, max(1, args.jobs), args.jit, data_file)
        report(data_file)
    print(f"\n{'JIT on' if args.jit else 'NUMBA_DISABLE_JIT=1'}: tests ran in {wall:.0f} s "
          f"({max(1, args.jobs)} process(es), {os.cpu_count()} cores); {' '.join(pytest_args)}")


if __name__ == "__main__":
    main()
