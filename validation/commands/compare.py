"""``persson compare CASE``: the case's model against its measurements; residual tables, plots, CSV."""

from __future__ import annotations

from pathlib import Path

from persson.commands._common import (CASE_HELP, add_effects, add_force, add_quiet, effect_scripts, print_notes,
                                      status_line)

from . import warm_patch_kernel

NAME = "compare"
HELP = ("compare a case's model with its measurements: RMSE, bias, where it fails (by speed, temperature, "
        "pressure, slip, wet/dry); writes a per-row CSV, a JSON summary and PNG plots")


def add_arguments(p):
    p.add_argument("case", help=CASE_HELP)
    p.add_argument("-o", "--output-dir", default=None,
                   help="folder for the outputs (default: ./<case name>-compare)")
    p.add_argument("--no-plots", action="store_true", help="do not write the PNG plots")
    add_force(p)
    add_effects(p)
    add_quiet(p)


def run(args) -> int:
    from persson.case import parse_case
    from persson.io import Outputs

    import validation

    scripts = effect_scripts(args)
    parsed = parse_case(args.case)
    name = parsed.name
    out = Path(args.output_dir) if args.output_dir else Path(f"{name}-compare")
    status = status_line(args, NAME)
    csv_name, json_name = f"{name}_comparison.csv", f"{name}_comparison.json"
    with Outputs(f"persson {NAME}", inputs=parsed.inputs + scripts, force=args.force) as outs:
        folder = outs.folder(out, names=(csv_name, json_name),
                             patterns=() if args.no_plots else (f"{name}_*.png",), what="-o")
        with status.phase(f"reading {parsed.path.name}"):
            case = validation.load_case(parsed.path, progress=status)
        warm_patch_kernel(case, ())
        print_notes(case.spec.notes)
        with status.phase(f"predicting {case.measurements.n} measured rows"):
            cmp = validation.compare(case.model, case.measurements, case.contact, name=case.name)
        print(cmp.summary())
        print()
        print(cmp.table_text())
        print()
        cmp.to_csv(folder / csv_name, comments=(f"case {case.path}",))
        cmp.to_json(folder / json_name)
        if not args.no_plots:
            cmp.save_plots(folder, prefix=f"{name}_")
    for path in outs.written:
        print(f"wrote {path.resolve()}")
    return 0
