"""``persson demo``: the whole validation loop on the shipped example case (synthetic DRFT-style data).

compare -> diagnose -> improve (add the best significant effect, refit, repeat) -> one HTML report; prints where
every output went.
"""

from __future__ import annotations

import time
from pathlib import Path

from persson.commands._common import add_force, add_quiet, print_notes, status_line

from . import warm_patch_kernel

NAME = "demo"
HELP = ("run the whole loop on the shipped example case: compare the model with (synthetic) measured friction, "
        "diagnose the missing effect, add it and watch the error fall; writes an HTML report (plots embedded), "
        "a CSV and JSON")

_DEFAULT_DIR = "persson-demo"
_FILES = ("comparison.csv", "diagnosis.json", "steps.json", "report.html")


def add_arguments(p):
    p.add_argument("-o", "--output-dir", default=None,
                   help=f"folder for the outputs (default ./{_DEFAULT_DIR}; when it holds an earlier demo, the next "
                        f"free name ./{_DEFAULT_DIR}-2, ...)")
    add_force(p)
    add_quiet(p)


def _progress(status):
    """Step verdicts printed as lines; the fraction done and the time left on the status line."""
    def call(*args):
        if len(args) == 1 and isinstance(args[0], str) and ": RMSE " in args[0]:
            status.echo("  " + args[0])
        else:
            status(*args)

    return call


def run(args) -> int:
    from persson.io import Outputs, free_path

    import validation

    t0 = time.perf_counter()
    if args.output_dir is None and not args.force:
        out = free_path(Path(_DEFAULT_DIR))
        if out != Path(_DEFAULT_DIR):
            print(f"./{_DEFAULT_DIR} holds an earlier run; writing to ./{out} (--force overwrites, -o chooses)")
    else:
        out = Path(args.output_dir or _DEFAULT_DIR)
    status = status_line(args, NAME)
    path = validation.case_path("example")
    from persson.case import parse_case

    parsed = parse_case(path)
    with Outputs(f"persson {NAME}", inputs=parsed.inputs, force=args.force) as outs:
        folder = outs.folder(out, names=_FILES, what="-o")
        with status.phase("reading the example case"):
            case = validation.load_case(path, progress=status)
        warm_patch_kernel(case)
        print_notes(case.spec.notes)
        print(f"example case {case.path} (synthetic data, see validation/cases/README.md)")
        print(f"  {case.measurements.describe()}")
        print(f"  baseline effects: {', '.join(case.model.effect_names) or 'none'}; "
              f"fitted: {', '.join(case.fit) or 'none'}")
        print("\n1. compare")
        with status.phase(f"predicting {case.measurements.n} measured rows (the first run compiles the engine)"):
            cmp = validation.compare(case.model, case.measurements, case.contact, name=case.name)
        print(cmp.summary())
        cmp.to_csv(folder / "comparison.csv", comments=(f"case {case.path}",))
        print("\n2-3. diagnose, add the effects the data support, test every combination reached")
        with status.phase("diagnose, find the set of effects the data support"):
            imp = validation.improve(case, progress=_progress(status))
        dx = imp.steps[0].diagnosis
        print(dx.table_text())
        print()
        print(dx.explanation)
        print()
        print("4. watch the error fall")
        print(imp.table_text())
        dx.to_json(folder / "diagnosis.json")
        imp.to_json(folder / "steps.json")
        validation.write_report([case, cmp, dx, imp], folder / "report.html",
                                title="persson demo: validation loop on the example case (synthetic data)")
    print()
    for p in outs.written:
        print(f"wrote {p.resolve()}")
    print(f"demo finished in {time.perf_counter() - t0:.1f} s")
    return 0
