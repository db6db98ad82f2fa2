"""``persson diagnose CASE [--json FILE]``: which physical effect is missing from the case's model."""

from __future__ import annotations

from pathlib import Path

NAME = "diagnose"
HELP = ("rank the effects that could be missing from a case's model (signature, score test, bounded refit, BIC); "
        "prints the ranking and a plain-language explanation; --json writes the result")


def add_arguments(p):
    p.add_argument("case", help="case.toml (or its folder, or the name of a shipped case such as 'example')")
    p.add_argument("--json", default=None, metavar="FILE",
                   help='write {"baseline": {"rmse", "effects"}, "candidates": [{"effect", "rmse", "delta_bic", '
                        '"significant", "parameters"}, ...]} (best first) to FILE')
    p.add_argument("--candidates", default=None,
                   help="comma-separated effect names to test (default: every registered effect not in the model)")
    p.add_argument("--effects", action="append", default=[], metavar="SCRIPT.py",
                   help="a Python file defining user effects (subclasses of persson.effects.Effect); repeatable")
    p.add_argument("--seed", type=int, default=0, help="seed of the screening design (default 0)")


def load_effect_scripts(paths) -> list[str]:
    """Import user effect scripts (defining an Effect subclass registers it); returns the new effect names."""
    import importlib.util

    from persson.effects import available

    from ..errors import InputError

    before = set(available())
    for i, path in enumerate(paths):
        p = Path(path)
        if not p.is_file():
            raise InputError(f"--effects: file {p} does not exist")
        spec = importlib.util.spec_from_file_location(f"_persson_user_effects_{i}", p)
        mod = importlib.util.module_from_spec(spec)
        try:
            spec.loader.exec_module(mod)
        except Exception as exc:  # noqa: BLE001
            raise InputError(f"--effects {p}: the script failed: {type(exc).__name__}: {exc}") from None
    return sorted(set(available()) - before)


def run(args) -> int:
    import time

    import validation

    new = load_effect_scripts(args.effects)
    if new:
        print(f"user effects registered: {', '.join(new)}")
    case = validation.load_case(args.case)
    cands = None
    if args.candidates:
        cands = [c.strip() for c in args.candidates.split(",") if c.strip()]
    t0 = time.perf_counter()
    dx = validation.diagnose(case, candidates=cands, seed=args.seed)
    dt = time.perf_counter() - t0
    print(f"case {case.name}: {case.measurements.describe()}")
    print(dx.table_text())
    print()
    print(dx.explanation)
    print()
    print(f"diagnosis took {dt:.1f} s ({dx.n_evaluations} model evaluations); rule: {dx.rule}")
    if args.json:
        dx.to_json(args.json)
        print(f"wrote {Path(args.json).resolve()}")
    else:
        print("(nothing written; --json FILE writes the result)")
    return 0
