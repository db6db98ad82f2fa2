"""``persson friction CASE``: friction, contact area and flash temperature vs speed for a case file."""

from __future__ import annotations

from pathlib import Path

from ._common import (CASE_HELP, VALUES_HELP, add_effects, add_force, add_quiet, condition_flags, effect_scripts,
                      positive_values, print_notes, status_line)

NAME = "friction"
HELP = "compute mu(v), A/A0(v) for a case; writes CSV (and PNG with --plot)"


def add_arguments(p):
    p.add_argument("case", help=CASE_HELP)
    p.add_argument("-o", "--output", default=None, help="output CSV (default: <case name>_friction.csv here); its "
                   "max_flash_temperature_K column is the flash temperature rise above the background "
                   "temperature, K")
    p.add_argument("--temperature", type=float, default=None, help="background temperature, deg C")
    p.add_argument("--pressure", type=float, default=None, help="nominal pressure, Pa")
    p.add_argument("--speeds", default=None, help=f"sliding speed(s), m/s: {VALUES_HELP}")
    p.add_argument("--plot", action="store_true", help="also write a PNG plot beside the CSV")
    add_force(p)
    add_effects(p)
    add_quiet(p)


def run(args) -> int:
    from .._checks import plausible_speed
    from ..case.loader import parse_case, read_case
    from ..engine.results import FLASH_RISE_COMMENT
    from ..io import Outputs, write_csv

    scripts = effect_scripts(args)
    T_flag, p_flag = condition_flags(args)
    speeds = None
    if args.speeds is not None:
        speeds = positive_values(args.speeds, "--speeds", "m/s")
        plausible_speed(speeds, f"--speeds {args.speeds!r} (m/s)")
    case = parse_case(args.case)
    out = Path(args.output) if args.output else Path(f"{case.name}_friction.csv")
    status = status_line(args, NAME)
    with Outputs(f"persson {NAME}", inputs=case.inputs + scripts, force=args.force) as outs:
        csv = outs.file(out, "-o")
        png = outs.file(out.with_suffix(".png"), "--plot") if args.plot else None
        with status.phase(f"reading {case.path.name}"):
            spec = read_case(case.path, progress=status)
        print_notes(spec.notes)
        speeds = spec.speeds if speeds is None else speeds
        T = spec.temperature if T_flag is None else T_flag
        p = spec.pressure if p_flag is None else p_flag
        with status.phase(f"friction at {speeds.size} speeds"):
            r = spec.model.friction(speeds, temperature=T, pressure=p)
        comments = (f"case {spec.path}", f"temperature_C={T}", f"pressure_Pa={p}",
                    f"effects={','.join(r.effects) or 'none'}", FLASH_RISE_COMMENT, *spec.notes, *r.notes)
        write_csv(csv, r.as_table(), comments=comments)
        if png is not None:
            from ..plots import plot_friction, save_figure

            save_figure(plot_friction(r, title=spec.name), png)
    for path in outs.written:
        print(f"wrote {path.resolve()}")
    return 0
