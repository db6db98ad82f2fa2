"""``persson report CASE -o FILE``: compare, diagnose, improve and write one self-contained HTML report."""

from __future__ import annotations

from pathlib import Path

from persson.commands._common import (CASE_HELP, add_effects, add_force, add_quiet, effect_scripts, print_notes,
                                      status_line)

NAME = "report"
HELP = ("the whole validation loop on a case (compare, diagnose, add the best significant effect until none is "
        "left) written as one self-contained HTML report")


def add_arguments(p):
    p.add_argument("case", help=CASE_HELP)
    p.add_argument("-o", "--output", default=None, help="HTML file (default: ./<case name>_report.html)")
    p.add_argument("--no-improve", action="store_true", help="compare and diagnose only (no improvement loop)")
    p.add_argument("--max-steps", type=int, default=4, help="largest number of effects added (default 4)")
    p.add_argument("--json", default=None, metavar="FILE",
                   help="also write the first diagnosis as JSON ('-': to stdout, the text then goes to stderr)")
    p.add_argument("--candidates", default=None,
                   help="comma-separated effect names to test (default: every registered effect not in the model)")
    add_effects(p)
    add_force(p)
    add_quiet(p)


def run(args) -> int:
    from persson.case import parse_case
    from persson.io import Outputs

    import validation

    import sys

    scripts = effect_scripts(args)
    to_stdout = args.json == "-"
    text = sys.stderr if to_stdout else sys.stdout  # the JSON alone goes to stdout
    parsed = parse_case(args.case)
    out = Path(args.output) if args.output else Path(f"{parsed.name}_report.html")
    status = status_line(args, NAME)
    with Outputs(f"persson {NAME}", inputs=parsed.inputs + scripts, force=args.force) as outs:
        html = outs.file(out, "-o")
        js = outs.file(args.json, "--json") if args.json and not to_stdout else None
        with status.phase(f"reading {parsed.path.name}"):
            case = validation.load_case(parsed.path, progress=status)
        print_notes(case.spec.notes)
        with status.phase(f"predicting {case.measurements.n} measured rows"):
            cmp = validation.compare(case.model, case.measurements, case.contact, name=case.name)
        print(cmp.summary(), file=text)
        cands = [c.strip() for c in args.candidates.split(",") if c.strip()] if args.candidates else None
        if args.no_improve:
            with status.phase("diagnosing"):
                dx = validation.diagnose(case, candidates=cands, progress=status)
            items = [case, cmp, dx]
        else:
            with status.phase("diagnose, find the set of effects the data support"):
                imp = validation.improve(case, candidates=cands, max_steps=args.max_steps, progress=status)
            dx = imp.steps[0].diagnosis
            items = [case, cmp, dx, imp]
            print(imp.table_text(), file=text)
        print(dx.table_text(), file=text)
        with status.phase("writing the report"):
            validation.write_report(items, html)
        if js is not None:
            dx.to_json(js)
        elif to_stdout:
            sys.stdout.write(dx.to_json() + "\n")
    for path in outs.written:
        print(f"wrote {path.resolve()}", file=text)
    return 0
