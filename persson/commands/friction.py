"""``persson friction CASE``: friction, contact area and flash temperature vs speed for a case file."""

from __future__ import annotations

from pathlib import Path

import numpy as np

NAME = "friction"
HELP = "compute mu(v), A/A0(v) for a case.toml; writes CSV (and PNG with --plot)"


def add_arguments(p):
    p.add_argument("case", help="case.toml (or its folder)")
    p.add_argument("-o", "--output", default=None, help="output CSV (default: <case name>_friction.csv here)")
    p.add_argument("--temperature", type=float, default=None, help="background temperature, deg C")
    p.add_argument("--pressure", type=float, default=None, help="nominal pressure, Pa")
    p.add_argument("--speeds", default=None, help="min:max:n log-spaced sliding speeds, m/s")
    p.add_argument("--plot", action="store_true", help="also write a PNG plot beside the CSV")


def run(args) -> int:
    from ..case import read_case
    from ..errors import InputError
    from ..io import write_csv

    case = read_case(args.case)
    speeds = case.speeds
    if args.speeds:
        try:
            lo, hi, n = args.speeds.split(":")
            speeds = np.geomspace(float(lo), float(hi), int(n))
        except ValueError:
            raise InputError(f"--speeds: expected min:max:n, got {args.speeds!r}") from None
    T = case.temperature if args.temperature is None else args.temperature
    p = case.pressure if args.pressure is None else args.pressure
    r = case.model.friction(speeds, temperature=T, pressure=p)
    out = Path(args.output) if args.output else Path(f"{case.name}_friction.csv")
    comments = (f"case {case.path}", f"temperature_C={T}", f"pressure_Pa={p}",
                f"effects={','.join(r.effects) or 'none'}", *r.notes)
    write_csv(out, r.as_table(), comments=comments)
    print(f"wrote {out.resolve()}")
    if args.plot:
        from ..plots import plot_friction, save_figure

        png = save_figure(plot_friction(r, title=case.name), out.with_suffix(".png"))
        print(f"wrote {png.resolve()}")
    return 0
