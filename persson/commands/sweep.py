"""``persson sweep CASE``: length-scale band contributions and parameter grids for a case file (CSV)."""

from __future__ import annotations

import sys
from pathlib import Path

from ._common import (CASE_HELP, add_effects, add_force, add_quiet, condition_flags, effect_scripts, print_notes,
                      status_line)

NAME = "sweep"
HELP = ("friction by length-scale band and/or over a parameter grid for a case; writes a CSV with one row "
        "per point (serial, local processes or a Dask cluster)")

_EPILOG = """\
examples:
  persson sweep case.toml --bands decades --param pressure=0.1e6:0.9e6:5 -o results.csv
  persson sweep case.toml --param surface.q1=1e5:1e7:5:log --param temperature=0,20,40 --speeds 1e-3:1:7
  persson sweep case.toml --bands continuous --speeds 1.0 --plot
  persson sweep case.toml --param adhesion.tau_f0=1e6:4e6:4 --scheduler tcp://scheduler:8786
  persson sweep example --bands decades -o example_bands.csv

An existing output is overwritten only with --force; Ctrl-C keeps it and writes the finished rows to
<output>.partial.csv beside it.

values: lo:hi:n (linear), lo:hi:n:log (log-spaced), v1,v2,... or a single v.
parameters: speed, temperature, pressure, nu, gamma, grid.<field>, surface.<name> (hurst, hrms, q0, q1, qL, C0),
material.<name> (e.g. material.wlf.C1), <effect>.<parameter> (e.g. adhesion.tau_f0).
"""


def add_arguments(p):
    import argparse

    p.formatter_class = argparse.RawDescriptionHelpFormatter
    p.epilog = _EPILOG
    p.add_argument("case", help=CASE_HELP)
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
    p.add_argument("-o", "--output", default=None, help="output CSV (default: <case name>_sweep.csv here); its "
                   "max_flash_temperature_K column is the flash temperature rise above the background "
                   "temperature, K")
    p.add_argument("--scheduler", default=None,
                   help="serial (default), processes, or a Dask scheduler address such as tcp://host:8786")
    p.add_argument("--workers", type=int, default=None, help="processes for --scheduler processes")
    p.add_argument("--checkpoint", default=None, help="CSV rewritten with the finished rows as the sweep runs")
    p.add_argument("--plot", action="store_true", help="also write a PNG plot beside the CSV")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--progress", dest="progress", action="store_true", default=None,
                   help="always show the progress bar (default: on sweeps longer than 2 s)")
    g.add_argument("--no-progress", dest="progress", action="store_false", help="never show the progress bar")
    add_force(p)
    add_effects(p)
    add_quiet(p)


def run(args) -> int:
    from .._checks import plausible_pressure, plausible_speed, plausible_temperature
    from ..case.loader import parse_case, read_case
    from ..errors import InputError
    from ..io import Outputs, check_output
    from .. import sweeps

    scripts = effect_scripts(args)
    T_flag, p_flag = condition_flags(args)
    params = {}
    for spec in args.param:
        name, values = sweeps.parse_param(spec, "--param")
        if name in params:
            raise InputError(f"--param {spec!r}: parameter {name!r} given twice")
        if name == "pressure":
            plausible_pressure(values, f"--param {spec!r} (Pa)", strict=True)
        elif name == "temperature":
            plausible_temperature(values, f"--param {spec!r} (deg C)", strict=True)
        elif name == "speed":
            plausible_speed(values, f"--param {spec!r} (m/s)")
        params[name] = values
    speeds = None if args.speeds is None else _speeds(args.speeds)
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
    case = parse_case(args.case)
    out = Path(args.output) if args.output else Path(f"{case.name}_sweep.csv")
    inputs = case.inputs + scripts
    status = status_line(args, NAME)
    progress = False if args.quiet and args.progress is None else args.progress
    with Outputs(f"persson {NAME}", inputs=inputs, force=args.force) as outs:
        csv = outs.file(out, "-o")
        png = outs.file(out.with_suffix(".png"), "--plot") if args.plot else None
        if args.checkpoint:
            # the checkpoint is rewritten as the sweep runs: it is the user's running copy, not staged
            check_output(args.checkpoint, inputs=(*inputs, out), force=args.force, what="--checkpoint")
        partial = outs.partial_for(out)
        with status.phase(f"reading {case.path.name}"):
            spec = read_case(case.path, progress=status)
        print_notes(spec.notes)
        speeds = spec.speeds if speeds is None else speeds
        T = spec.temperature if T_flag is None else T_flag
        p = spec.pressure if p_flag is None else p_flag
        try:
            table = sweeps.grid(spec.model, params, speed=speeds, temperature=T, pressure=p, bands=bands,
                                n_bands=args.n_bands, band_mode=args.band_mode, scheduler=args.scheduler,
                                workers=args.workers, progress=progress, checkpoint=args.checkpoint,
                                partial=partial)
        except sweeps.SweepInterrupted as exc:
            print(f"persson {NAME}: stopped after {exc.done} of {exc.total} tasks ({len(exc.table)} rows)",
                  file=sys.stderr)
            raise
        table = table.with_comments(f"case {spec.path}", *spec.notes, *table.comments)
        table.to_csv(csv)
        if png is not None:
            from ..views import plot_bands, plot_sweep, save_figure

            if bands is not None:
                fig = plot_bands(table, title=spec.name)
            else:
                x = next((n for n in params if n != "speed"), "speed")
                fig = plot_sweep(table, x=x, title=spec.name)
            save_figure(fig, png)
    print(f"wrote {outs.written[0].resolve()} ({len(table)} rows)")
    for path in outs.written[1:]:
        print(f"wrote {path.resolve()}")
    if args.checkpoint:
        print(f"wrote {Path(args.checkpoint).resolve()} (checkpoint)")
    return 0


def _speeds(text: str):
    from .._checks import plausible_speed
    from ._common import positive_values

    v = positive_values(text, "--speeds", "m/s")  # min:max:n is log-spaced for speeds
    plausible_speed(v, f"--speeds {text!r} (m/s)")
    return v
