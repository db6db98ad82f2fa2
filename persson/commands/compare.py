"""``persson compare CASE``: the case's model against its measurements; residual tables, plots, CSV."""

from __future__ import annotations

from pathlib import Path

NAME = "compare"
HELP = ("compare a case's model with its measurements: RMSE, bias, where it fails (by speed, temperature, "
        "pressure, slip, wet/dry); writes a per-row CSV, a JSON summary and PNG plots")


def add_arguments(p):
    p.add_argument("case", help="case.toml (or its folder, or the name of a shipped case such as 'example')")
    p.add_argument("-o", "--output-dir", default=None,
                   help="folder for the outputs (default: ./<case name>-compare)")
    p.add_argument("--no-plots", action="store_true", help="do not write the PNG plots")


def run(args) -> int:
    import validation

    case = validation.load_case(args.case)
    cmp = validation.compare(case.model, case.measurements, case.contact, name=case.name)
    out = Path(args.output_dir) if args.output_dir else Path(f"{case.name}-compare")
    print(cmp.summary())
    print()
    print(cmp.table_text())
    print()
    csv = cmp.to_csv(out / f"{case.name}_comparison.csv", comments=(f"case {case.path}",))
    js = out / f"{case.name}_comparison.json"
    cmp.to_json(js)
    print(f"wrote {csv.resolve()}")
    print(f"wrote {js.resolve()}")
    if not args.no_plots:
        for png in cmp.save_plots(out, prefix=f"{case.name}_"):
            print(f"wrote {Path(png).resolve()}")
    return 0
