"""``persson sweep CASE``: length-scale band contributions and parameter grids for a case file (CSV)."""

from __future__ import annotations

import sys
from pathlib import Path

NAME = "sweep"
HELP = ("friction by length-scale band and/or over a parameter grid for a case.toml; writes a CSV with one row "
        "per point (serial, local processes or a Dask cluster)")

_EPILOG = """\
examples:
  persson sweep case.toml --bands decades --param pressure=0.1e6:0.9e6:5 -o results.csv
  persson sweep case.toml --param surface.q1=1e5:1e7:5:log --param temperature=0,20,40 --speeds 1e-3:1:7
  persson sweep case.toml --bands continuous --speeds 1.0 --plot
  persson sweep case.toml --param adhesion.tau_f0=1e6:4e6:4 --scheduler tcp://scheduler:8786

values: lo:hi:n (linear), lo:hi:n:log (log-spaced), v1,v2,... or a single v.
parameters: speed, temperature, pressure, nu, gamma, grid.<field>, surface.<name> (hurst, hrms, q0, q1, qL, C0),
material.<name> (e.g. material.wlf.C1), <effect>.<parameter> (e.g. adhesion.tau_f0).
"""


def add_arguments(p):
    import argparse

    p.formatter_class = argparse.RawDescriptionHelpFormatter
    p.epilog = _EPILOG
    p.add_argument("case", help="case.toml (or its folder)")
    p.add_argument("--bands", default=None,
                   help="length-scale bands: decades, linear_q, linear_length, continuous, or edges q0,q1,... "
                        "in rad/m")
    p.add_argument("--n-bands", type=int, default=None, help="number of bands of a named kind")
    p.add_argument("--band-mode", choices=("restrict", "separate", "both"), default=None,
                   help="restrict: the full surface's integrand over each band (bands add up to the total); "
                        "separate: each band as a surface of its own; both (default; restrict for continuous)")
    p.add_argument("--param", action="append", default=[], metavar="NAME=VALUES",
                   help="a swept parameter (repeat for a grid)")
    p.add_argument("--speeds", default=None,
                   help="sliding speed(s), m/s: v, v1,v2,... or min:max:n (log-spaced); default the case's")
    p.add_argument("--temperature", type=float, default=None, help="background temperature, deg C")
    p.add_argument("--pressure", type=float, default=None, help="nominal pressure, Pa")
    p.add_argument("-o", "--output", default=None, help="output CSV (default: <case name>_sweep.csv here)")
    p.add_argument("--scheduler", default=None,
                   help="serial (default), processes, or a Dask scheduler address such as tcp://host:8786")
    p.add_argument("--workers", type=int, default=None, help="processes for --scheduler processes")
    p.add_argument("--checkpoint", default=None, help="CSV rewritten with the finished rows as the sweep runs")
    p.add_argument("--plot", action="store_true", help="also write a PNG plot beside the CSV")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--progress", dest="progress", action="store_true", default=None,
                   help="always show the progress bar (default: on sweeps longer than 2 s)")
    g.add_argument("--no-progress", dest="progress", action="store_false", help="never show the progress bar")


def run(args) -> int:
    from ..case import read_case
    from ..errors import InputError
    from .. import sweeps

    case = read_case(args.case)
    params = {}
    for spec in args.param:
        name, values = sweeps.parse_param(spec, "--param")
        if name in params:
            raise InputError(f"--param {spec!r}: parameter {name!r} given twice")
        params[name] = values
    speeds = case.speeds if args.speeds is None else _speeds(args.speeds)
    bands = None
    if args.bands is not None:
        text = args.bands.strip()
        if text and (text[0].isdigit() or text[0] == "."):
            try:
                bands = [float(x) for x in text.split(",")]
            except ValueError:
                raise InputError(f"--bands: expected a kind or comma-separated edges in rad/m, got {text!r}") from None
        else:
            bands = text
    elif args.n_bands is not None or args.band_mode is not None:
        raise InputError("--n-bands / --band-mode: give --bands too")
    T = case.temperature if args.temperature is None else args.temperature
    p = case.pressure if args.pressure is None else args.pressure
    out = Path(args.output) if args.output else Path(f"{case.name}_sweep.csv")
    try:
        table = sweeps.grid(case.model, params, speed=speeds, temperature=T, pressure=p, bands=bands,
                            n_bands=args.n_bands, band_mode=args.band_mode, scheduler=args.scheduler,
                            workers=args.workers, progress=args.progress, checkpoint=args.checkpoint)
    except sweeps.SweepInterrupted as exc:
        path = exc.table.with_comments(f"case {case.path}", *exc.table.comments).to_csv(out) \
            if len(exc.table) else None
        print(f"persson sweep: interrupted after {exc.done} of {exc.total} tasks", file=sys.stderr)
        if path is not None:
            print(f"wrote {path.resolve()} (partial: {len(exc.table)} rows)")
        return 130
    table = table.with_comments(f"case {case.path}", *table.comments)
    path = table.to_csv(out)
    print(f"wrote {path.resolve()} ({len(table)} rows)")
    if args.checkpoint:
        print(f"wrote {Path(args.checkpoint).resolve()} (checkpoint)")
    if args.plot:
        from ..views import plot_bands, plot_sweep, save_figure

        if bands is not None:
            fig = plot_bands(table, title=case.name)
        else:
            x = next((n for n in params if n != "speed"), "speed")
            fig = plot_sweep(table, x=x, title=case.name)
        png = save_figure(fig, out.with_suffix(".png"))
        print(f"wrote {png.resolve()}")
    return 0


def _speeds(text: str):
    import numpy as np

    from ..errors import InputError
    from ..sweeps import parse_values

    t = text.strip()
    parts = t.split(":")
    if len(parts) == 3:  # min:max:n is log-spaced for speeds
        t = t + ":log"
    v = parse_values(t, f"--speeds {text!r}")
    if np.any(v <= 0):
        raise InputError(f"--speeds {text!r}: expected speeds > 0 m/s")
    return v
