"""``persson report CASE -o FILE``: compare, diagnose, improve and write one self-contained HTML report."""

from __future__ import annotations

from pathlib import Path

NAME = "report"
HELP = ("the whole validation loop on a case (compare, diagnose, add the best significant effect until none is "
        "left) written as one self-contained HTML report")


def add_arguments(p):
    p.add_argument("case", help="case.toml (or its folder, or the name of a shipped case such as 'example')")
    p.add_argument("-o", "--output", default=None, help="HTML file (default: ./<case name>_report.html)")
    p.add_argument("--no-improve", action="store_true", help="compare and diagnose only (no improvement loop)")
    p.add_argument("--max-steps", type=int, default=4, help="largest number of effects added (default 4)")
    p.add_argument("--effects", action="append", default=[], metavar="SCRIPT.py",
                   help="a Python file defining user effects (subclasses of persson.effects.Effect); repeatable")
    p.add_argument("--json", default=None, metavar="FILE", help="also write the first diagnosis as JSON")


def run(args) -> int:
    import validation

    from .diagnose import load_effect_scripts

    new = load_effect_scripts(args.effects)
    if new:
        print(f"user effects registered: {', '.join(new)}")
    case = validation.load_case(args.case)
    out = Path(args.output) if args.output else Path(f"{case.name}_report.html")
    cmp = validation.compare(case.model, case.measurements, case.contact, name=case.name)
    print(cmp.summary())
    if args.no_improve:
        dx = validation.diagnose(case)
        items = [case, cmp, dx]
    else:
        imp = validation.improve(case, max_steps=args.max_steps, progress=print)
        dx = imp.steps[0].diagnosis
        items = [case, cmp, dx, imp]
        print(imp.table_text())
    print(dx.table_text())
    validation.write_report(items, out)
    print(f"wrote {out.resolve()}")
    if args.json:
        dx.to_json(args.json)
        print(f"wrote {Path(args.json).resolve()}")
    return 0
