"""``persson tread CASE``: the tyre on the road (tread-element tool): mu over slip and speed, ABS peak, locked wheel."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._common import CASE_HELP, add_force, add_quiet, condition_flags, print_notes, status_line

NAME = "tread"
HELP = ("the tyre on the road: a patterned tread marched over the case's road profiles; mu(slip, speed), ABS peak "
        "and locked wheel; writes CSV (and PNG with --plot)")

_EPILOG = """\
examples:
  persson tread case.toml
  persson tread case.toml --speeds 8.3,16.7,25 --slips 0.05,0.1,0.15,0.2,0.5,1 -o map.csv --plot
  persson tread case.toml --wet 1e-3 --view

The case needs a [tire] section (docs/conventions.md, "The case file") and a road: [surface] profiles (measured
line scans; a PSD or the example road gets synthetic profiles). Two CSV files are written: the map (one row per
speed and slip) and <output>_summary.csv (ABS peak and locked wheel per speed). An existing output is
overwritten only with --force.
"""


def add_arguments(p):
    import argparse

    p.formatter_class = argparse.RawDescriptionHelpFormatter
    p.epilog = _EPILOG
    p.add_argument("case", help=CASE_HELP)
    p.add_argument("-o", "--output", default=None, help="output CSV (default: <case name>_tread.csv here)")
    p.add_argument("--speeds", default=None, help="vehicle speeds, m/s: v1,v2,... (default: the case's)")
    p.add_argument("--slips", default=None, help="slip ratios in (0, 1]: s1,s2,... (default: the case's)")
    p.add_argument("--temperature", type=float, default=None, help="background temperature, deg C")
    p.add_argument("--wet", type=float, default=None, metavar="THICKNESS_M",
                   help="water depth, m (overrides the case's [tire] water thickness)")
    p.add_argument("--dry", action="store_true", help="ignore the case's water: a dry road")
    p.add_argument("--plot", action="store_true",
                   help="also write PNGs: the mu-slip-speed surface and the peak/locked bars")
    p.add_argument("--view", action="store_true", help="also write a PNG of the tread on the road (pyvista)")
    add_force(p)
    add_quiet(p)


def run(args) -> int:
    from ..errors import InputError
    from ..io import Outputs, write_csv
    from ..tread import slip_map
    from ..tread.case import read_tread_case
    from ..tread.wet import Water

    T_flag, _ = condition_flags(args)
    speeds = _numbers(args.speeds, "--speeds") if args.speeds else None
    slips = _numbers(args.slips, "--slips") if args.slips else None
    if args.wet is not None and args.dry:
        raise InputError("--wet and --dry: give one of them")
    from ..case.loader import parse_case

    case_file = parse_case(args.case)
    out = Path(args.output) if args.output else Path(f"{case_file.name}_tread.csv")
    summary = out.with_name(out.stem + "_summary" + (out.suffix or ".csv"))
    status = status_line(args, NAME)
    with Outputs(f"persson {NAME}", inputs=case_file.inputs, force=args.force) as outs:
        csv = outs.file(out, "-o")
        csv_sum = outs.file(summary, "summary")
        png = outs.file(out.with_suffix(".png"), "--plot") if args.plot else None
        png_bars = outs.file(out.with_name(out.stem + "_bars.png"), "--plot") if args.plot else None
        png_view = outs.file(out.with_name(out.stem + "_view.png"), "--view") if args.view else None
        with status.phase(f"reading {case_file.path.name}"):
            case = read_tread_case(case_file.path, progress=status)
        for f in case.inputs:  # a footprint image is an input too
            if Path(f).resolve() in {Path(x).resolve() for x in (out, summary)}:
                raise InputError(f"-o {out}: is one of the case's input files")
        print_notes(case.notes)
        water = case.water
        if args.dry:
            water = None
        elif args.wet is not None:
            base = water if water is not None else Water(thickness=args.wet)
            from dataclasses import replace

            water = replace(base, thickness=args.wet)
        T = case.temperature if T_flag is None else T_flag
        V = case.speeds if speeds is None else speeds
        S = case.slips if slips is None else slips
        with status.phase(f"tread march at {V.size} speeds x {S.size} slips"):
            m = slip_map(case.tire, case.road, case.material, slips=S, speeds=V, temperature=T, water=water,
                         mu_loc=case.mu_loc, **case.options)
        fp = case.tire.footprint
        comments = (f"case {case.path}", f"temperature_C={T}",
                    f"footprint {fp.length * 1e3:.4g} mm x {fp.width * 1e3:.4g} mm, mean pressure "
                    f"{fp.mean_pressure:.4g} Pa", "wet: " + (f"water {water.thickness:g} m" if water else "dry"),
                    *m.notes)
        write_csv(csv, m.as_table(), comments=comments)
        write_csv(csv_sum, m.summary_table(), comments=comments[:4])
        if png is not None:
            from ..plots import save_figure
            from ..tread.plots import plot_peak_locked, plot_slip_map

            save_figure(plot_slip_map(m, title=case.name), png)
            save_figure(plot_peak_locked({case.name: m}, title=case.name), png_bars)
        if png_view is not None:
            from ..tread.plots import view_tread

            view_tread(case.tire, case.road, png_view, speed=float(V[0]), slip=float(S[-1]), material=case.material,
                       temperature=T, mu_loc=case.mu_loc, water=water, **case.options)
    for path in outs.written:
        print(f"wrote {path.resolve()}")
    return 0


def _numbers(text: str, flag: str) -> np.ndarray:
    from ..errors import InputError

    try:
        values = np.array([float(x) for x in text.split(",") if x.strip()])
    except ValueError:
        raise InputError(f"{flag}: expected numbers separated by commas, got {text!r}") from None
    if values.size == 0 or not np.all(np.isfinite(values)):
        raise InputError(f"{flag}: expected numbers separated by commas, got {text!r}")
    return values
