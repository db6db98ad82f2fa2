"""``persson demo``: the whole validation loop on the shipped example case (synthetic DRFT-style data).

compare -> diagnose -> improve (add the best significant effect, refit, repeat) -> one HTML report; prints where
every output went.
"""

from __future__ import annotations

import time
from pathlib import Path

NAME = "demo"
HELP = ("run the whole loop on the shipped example case: compare the model with (synthetic) measured friction, "
        "diagnose the missing effect, add it and watch the error fall; writes an HTML report (plots embedded), "
        "a CSV and JSON")


def add_arguments(p):
    p.add_argument("-o", "--output-dir", default="persson-demo", help="folder for the outputs (default ./persson-demo)")


def run(args) -> int:
    import validation

    t0 = time.perf_counter()
    out = Path(args.output_dir)
    case = validation.load_case(validation.case_path("example"))
    print(f"example case {case.path} (synthetic data, see validation/cases/README.md)")
    print(f"  {case.measurements.describe()}")
    print(f"  baseline effects: {', '.join(case.model.effect_names) or 'none'}; "
          f"fitted: {', '.join(case.fit) or 'none'}")
    print("\n1. compare")
    cmp = validation.compare(case.model, case.measurements, case.contact, name=case.name)
    print(cmp.summary())
    csv = cmp.to_csv(out / "comparison.csv", comments=(f"case {case.path}",))
    print("\n2-3. diagnose, add the best significant effect, repeat")
    imp = validation.improve(case, progress=lambda msg: print("  " + msg))
    dx = imp.steps[0].diagnosis
    print(dx.table_text())
    print()
    print(dx.explanation)
    print()
    print("4. watch the error fall")
    print(imp.table_text())
    js = out / "diagnosis.json"
    dx.to_json(js)
    steps = out / "steps.json"
    imp.to_json(steps)
    report = validation.write_report([case, cmp, dx, imp], out / "report.html",
                                     title="persson demo: validation loop on the example case (synthetic data)")
    print(f"\nwrote {csv.resolve()}")
    print(f"wrote {Path(js).resolve()}")
    print(f"wrote {Path(steps).resolve()}")
    print(f"wrote {report.resolve()}")
    print(f"demo finished in {time.perf_counter() - t0:.1f} s")
    return 0
