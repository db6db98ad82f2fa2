"""Timing of the compiled kernels on the calls a diagnosis makes (run: ``python benchmarks/bench_kernels.py``).

Runs ``validation.diagnose`` on a shipped case once, recording every call of the three threaded kernels (the
hysteresis friction, the flash temperature and the heated patch's march, through
:func:`persson.engine.jit.threaded`), then replays those calls: for each kernel, the best of ``--repeat`` passes
over all its calls on one thread and on two. A change to a kernel is measured on the work the kernels really do in
a diagnosis, apart from Python and from the machine's other load.

``--save FILE`` keeps the recorded inputs (each array once, however many calls share it; some 100-300 MB for a
shipped case), ``--load FILE`` replays them instead of running a diagnosis, so that two source trees replay the
same calls (``PYTHONPATH=/other/tree python benchmarks/bench_kernels.py --load FILE``); ``--outputs FILE`` writes
what the replay computed, and ``--compare A B`` compares two such files output by output: the same to the last bit,
or the largest relative difference. That is how a change meant to leave every number alone is checked.

``--perf`` samples the replay on one thread with ``perf`` (Linux) and prints the compiled functions that took the
time (``perf`` cannot name the JIT's code by itself: the script compiles the kernels afresh in a temporary numba
cache and writes ``/tmp/perf-PID.map`` from their code libraries, so the first run pays the compilation).
"""

from __future__ import annotations

import argparse
import collections
import hashlib
import os
import pickle
import re
import subprocess
import sys
import tempfile
import time

KERNELS = ("friction", "flash", "march")
#: The kernels' output arguments (persson.engine.kernels, persson.slip.heating_kernels).
OUTPUTS = {"out", "T_out", "it_out", "res_out", "mu_coarse", "mu_coarser"}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="hidden_flash", help="the shipped case (or case folder) to diagnose")
    ap.add_argument("--repeat", type=int, default=4, help="passes over the calls per kernel and thread count")
    ap.add_argument("--threads", default="1,2", help="comma-separated thread counts to time")
    ap.add_argument("--save", default=None, help="pickle the recorded kernel inputs to this file")
    ap.add_argument("--load", default=None, help="replay the kernel inputs of this file (no diagnosis)")
    ap.add_argument("--outputs", default=None, help="pickle the replayed outputs to this file")
    ap.add_argument("--compare", nargs=2, default=None, metavar=("A", "B"), help="compare two --outputs files")
    ap.add_argument("--perf", action="store_true", help="sample the one-thread replay with perf (Linux)")
    args = ap.parse_args(argv)
    if args.compare:
        return _compare(*args.compare)
    if args.perf:
        # compiled afresh in a cache of its own, so that the code libraries still hold their functions' names
        os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="bench-kernels-numba-")
    calls = _load(args.load) if args.load else _record(args.case)
    if args.save:
        with open(args.save, "wb") as f:
            pickle.dump(calls, f, protocol=pickle.HIGHEST_PROTOCOL)
    kernels = _kernels()
    print(f"{len(calls)} kernel calls ({', '.join(f'{k} {sum(c[0] == k for c in calls)}' for k in KERNELS)})")
    if args.perf:
        _perf(calls, kernels)
    else:
        _time(calls, kernels, [int(t) for t in args.threads.split(",")], args.repeat)
    if args.outputs:
        with open(args.outputs, "wb") as f:
            pickle.dump(_replay(calls, kernels), f, protocol=pickle.HIGHEST_PROTOCOL)
    return 0


def _kernels() -> dict:
    from persson.engine import kernels
    from persson.slip import heating_kernels

    return {"friction": kernels.friction_kernel, "flash": kernels.flash_kernel, "march": heating_kernels._march_kernel}


def _record(case_name: str) -> list:
    """(kernel, n, arguments) of every threaded kernel call of a diagnosis of ``case_name``, the arguments copied
    as they were at the call (an array shared by several calls is stored once while its content is unchanged)."""
    import validation
    from persson.engine import jit

    by_name = {v: k for k, v in _kernels().items()}
    kept: dict = {}
    calls = []
    original = jit.threaded

    def recording(kernel, n, *, min_items=2, **arguments):
        # the outputs are kept as zeros of their shapes: the kernels write them before they read them
        inputs = {k: _zeros(v) if k in OUTPUTS else _copied(v, kept) for k, v in arguments.items()}
        calls.append((by_name[kernel], int(n), inputs))
        return original(kernel, n, min_items=min_items, **arguments)

    patched = [m for name, m in list(sys.modules.items())
               if name.split(".")[0] in ("persson", "validation") and getattr(m, "threaded", None) is original]
    for m in patched:
        m.threaded = recording
    try:
        validation.diagnose(validation.load_case(case_name))
    finally:
        for m in patched:
            m.threaded = original
    return calls


class _Zeros(collections.namedtuple("_Zeros", ["shape", "dtype"])):
    """An output array to be created as zeros at the replay (stored as its shape and dtype only)."""


def _zeros(value):
    import numpy as np

    if isinstance(value, np.ndarray):
        return _Zeros(value.shape, value.dtype.str)
    return type(value)(*(_zeros(v) for v in value))


def _copied(value, kept: dict):
    import numpy as np

    if isinstance(value, np.ndarray):
        key = (id(value), hashlib.blake2b(np.ascontiguousarray(value).view(np.uint8), digest_size=16).digest())
        if key not in kept:
            kept[key] = (value, value.copy())   # the original kept alive, so that its id is not reused
        return kept[key][1]
    if isinstance(value, dict):
        return {k: _copied(v, kept) for k, v in value.items()}
    if isinstance(value, tuple):
        items = [_copied(v, kept) for v in value]
        return type(value)(*items) if hasattr(value, "_fields") else tuple(items)
    return value


def _load(path: str) -> list:
    with open(path, "rb") as f:
        return pickle.load(f)


def _fresh(arguments):
    """The arguments with every array copied and the outputs created (a replay writes its outputs into them)."""
    import copy

    import numpy as np

    def made(value):
        if isinstance(value, _Zeros):
            return np.zeros(value.shape, dtype=value.dtype)
        if isinstance(value, tuple) and hasattr(value, "_fields"):
            return type(value)(*(made(v) for v in value))
        return value

    return {k: made(v) if k in OUTPUTS else copy.deepcopy(v) for k, v in arguments.items()}


def _replay(calls, kernels, threads: int = 1) -> list:
    import numba

    from persson.engine.jit import threaded

    numba.set_num_threads(threads)
    out = []
    for name, n, arguments in calls:
        a = _fresh(arguments)
        threaded(kernels[name], n, **a)
        out.append((name, a))
    return out


def _time(calls, kernels, thread_counts, repeat):
    import numba

    from persson.engine.jit import threaded

    fresh = [(name, n, _fresh(a)) for name, n, a in calls]   # copied once: the passes time the kernels alone
    print(f"{'kernel':<10}{'calls':>7}" + "".join(f"{f'{t} thread(s), s':>20}" for t in thread_counts))
    for name in KERNELS:
        mine = [(n, a) for k, n, a in fresh if k == name]
        if not mine:
            continue
        line = f"{name:<10}{len(mine):>7}"
        for t in thread_counts:
            numba.set_num_threads(t)
            best = float("inf")
            for _ in range(repeat):
                start = time.perf_counter()
                for n, a in mine:
                    threaded(kernels[name], n, **a)
                best = min(best, time.perf_counter() - start)
            line += f"{best:>20.3f}"
        print(line)


def _perf(calls, kernels):
    """Sample the one-thread replay with perf and print the compiled functions that took the time."""
    first = {}
    for call in calls:
        first.setdefault(call[0], call)
    _replay(list(first.values()), kernels)   # compile every kernel before sampling
    names = []
    for kernel in kernels.values():
        for compiled in kernel.overloads.values():
            library = compiled.library
            for name in set(re.findall(r'define[^@]*@"?([^"(\s]+)"?\(', library.get_llvm_str())):
                try:
                    address = library.get_pointer_to_function(name)
                except Exception:  # noqa: BLE001  (a declaration the library does not define)
                    continue
                if address:
                    names.append((address, name))
    names.sort()
    with open(f"/tmp/perf-{os.getpid()}.map", "w") as f:
        for i, (address, name) in enumerate(names):
            size = names[i + 1][0] - address if i + 1 < len(names) else 4096
            f.write(f"{address:x} {size:x} {_short(name)}\n")
    import numba

    from persson.engine.jit import threaded

    numba.set_num_threads(1)
    fresh = [(name, n, _fresh(a)) for name, n, a in calls]   # copied before sampling: the kernels alone are sampled
    data = tempfile.mktemp(prefix="bench-kernels-", suffix=".perf")
    sampler = subprocess.Popen(["perf", "record", "-F", "4000", "-o", data, "-p", str(os.getpid())],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(1.0)
    for name, n, a in fresh:
        threaded(kernels[name], n, **a)
    sampler.send_signal(2)
    sampler.wait()
    report = subprocess.run(["perf", "report", "-i", data, "--no-children", "--sort", "sym", "--stdio"],
                            capture_output=True, text=True).stdout
    shares = collections.Counter()
    for line in report.splitlines():
        m = re.match(r"\s*([\d.]+)%\s+\[\.\]\s+(\S+)", line)
        if m:
            shares[m.group(2)] += float(m.group(1))
    print(f"perf: {len(names)} compiled functions named; share of the samples (all kernels, one thread):")
    for name, share in shares.most_common(20):
        print(f"  {share:6.2f} %  {name}")
    # NRT_incref / NRT_decref are numba's reference counting (see persson.engine.borrow); libm's __erf and exp the
    # contact weights and the angular tables


def _short(mangled: str) -> str:
    """A readable name for a numba-mangled symbol: module path and function (``persson.engine.kernels.area``)."""
    m = re.match(r"_ZN((?:\d+\w+?)+?)B\d+v\d+", mangled) or re.match(r"_ZN((?:\d+[A-Za-z_]\w*)+)", mangled)
    if not m:
        return mangled[:80]
    parts, s = [], m.group(1)
    while s:
        d = re.match(r"(\d+)", s)
        if not d:
            break
        k = int(d.group(1))
        start = len(d.group(1))
        parts.append(s[start:start + k])
        s = s[start + k:]
    return ".".join(parts) or mangled[:80]


def _compare(path_a: str, path_b: str) -> int:
    """Print, per kernel output, how many calls differ and the largest relative difference; 0 when all equal."""
    import numpy as np

    a, b = _load(path_a), _load(path_b)
    if len(a) != len(b):
        print(f"different calls: {len(a)} against {len(b)}")
        return 1
    worst: dict = {}
    for (name, xa), (_, xb) in zip(a, b):
        for (path, u), (_, v) in zip(_leaves(xa), _leaves(xb)):
            same = np.array_equal(u, v, equal_nan=True) if u.shape == v.shape else False
            diff = 0.0
            if not same and u.shape == v.shape and u.dtype.kind == "f" and u.size:
                with np.errstate(invalid="ignore", divide="ignore"):
                    rel = np.abs(u - v) / np.maximum(np.abs(u), 1e-300)
                diff = float(np.nanmax(rel))
            w = worst.setdefault((name, path), [0, 0, 0.0])
            w[0] += 1
            w[1] += not same
            w[2] = max(w[2], diff)
    differing = {k: w for k, w in worst.items() if w[1]}
    for (name, path), (n, n_diff, diff) in sorted(differing.items()):
        print(f"{name:<10}{path:<30} {n_diff}/{n} calls differ, largest relative difference {diff:.2e}")
    print(f"{len(a)} calls compared: " + ("every output the same to the last bit" if not differing else
                                          f"{len(differing)} outputs differ"))
    return 0 if not differing else 1


def _leaves(value, path=""):
    import numpy as np

    if isinstance(value, np.ndarray):
        yield path, value
    elif isinstance(value, dict):
        for k, v in value.items():
            yield from _leaves(v, f"{path}.{k}")
    elif isinstance(value, tuple):
        fields = getattr(value, "_fields", None)
        for i, v in enumerate(value):
            yield from _leaves(v, f"{path}.{fields[i]}" if fields else f"{path}[{i}]")


if __name__ == "__main__":
    sys.exit(main())
