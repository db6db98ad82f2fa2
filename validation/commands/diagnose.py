"""``persson diagnose CASE [--json FILE]``: which physical effect is missing from the case's model."""

from __future__ import annotations

import sys
import time
from pathlib import Path

from persson.commands._common import (CASE_HELP, add_effects, add_force, add_quiet, effect_scripts, print_notes,
                                      status_line)

from . import warm_patch_kernel

NAME = "diagnose"
HELP = ("rank the effects that could be missing from a case's model (signature, score test, bounded refit, BIC); "
        "prints the ranking and a plain-language explanation; --json writes the result")


def add_arguments(p):
    p.add_argument("case", help=CASE_HELP)
    p.add_argument("--json", default=None, metavar="FILE",
                   help='write {"verdict", "baseline": {"rmse", "effects"}, "candidates": [{"effect", "rmse", '
                        '"delta_bic", "significant", "parameters"}, ...]} (best first) to FILE; "-" writes it to '
                        "stdout (the text then goes to stderr)")
    p.add_argument("--candidates", default=None,
                   help="comma-separated effect names to test (default: every registered effect not in the model)")
    p.add_argument("--seed", type=int, default=0, help="seed of the screening design (default 0)")
    p.add_argument("--search", choices=("single", "sets"), default="single",
                   help="single: each candidate added alone (default); sets: also search combinations of effects "
                        "(forward steps with backward elimination and swaps; names every set within 10 BIC units)")
    add_effects(p)
    add_force(p)
    add_quiet(p)


def run(args) -> int:
    from persson.case import parse_case
    from persson.io import Outputs

    import validation

    scripts = effect_scripts(args)
    to_stdout = args.json == "-"
    text = sys.stderr if to_stdout else sys.stdout  # the JSON alone goes to stdout
    parsed = parse_case(args.case)
    status = status_line(args, NAME)
    cands = None
    if args.candidates:
        cands = [c.strip() for c in args.candidates.split(",") if c.strip()]
    with Outputs(f"persson {NAME}", inputs=parsed.inputs + scripts, force=args.force) as outs:
        js = outs.file(args.json, "--json") if args.json and not to_stdout else None
        with status.phase(f"reading {parsed.path.name}"):
            case = validation.load_case(parsed.path, progress=status)
        warm_patch_kernel(case, cands)
        print_notes(case.spec.notes)
        t0 = time.perf_counter()
        with status.phase("diagnosing (screening every candidate effect, refitting the best)"):
            dx = validation.diagnose(case, candidates=cands, seed=args.seed, search=args.search, progress=status)
        dt = time.perf_counter() - t0
        print(f"case {case.name}: {case.measurements.describe()}", file=text)
        print(dx.table_text(), file=text)
        print(file=text)
        print(dx.explanation, file=text)
        print(file=text)
        print("References: " + "; ".join(dx.references()), file=text)
        print(file=text)
        print(f"diagnosis took {dt:.1f} s ({dx.n_evaluations} model evaluations); rule: {dx.rule}", file=text)
        if js is not None:
            dx.to_json(js)
        elif to_stdout:
            sys.stdout.write(dx.to_json() + "\n")
    for path in outs.written:
        print(f"wrote {Path(path).resolve()}", file=text)
    if not args.json:
        print("(nothing written; --json FILE writes the result)", file=text)
    return 0
