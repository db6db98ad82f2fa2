"""``persson contact CASE_OR_PSD``: real contact area, separation, elastic energy and penetration depth vs pressure."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._common import CASE_HELP, VALUES_HELP, add_force, add_quiet, positive_values, print_notes, status_line

NAME = "contact"
HELP = ("contact mechanics vs nominal pressure for a case or a PSD table: A/A0, mean separation, elastic energy, "
        "penetration depth; writes CSV (and PNG with --plot)")

_EPILOG = """\
examples:
  persson contact surface_psd.csv --estar 4e6 --pressures 1e4:1e6:20 -o contact.csv --plot
  persson contact case.toml --speed 1.0 --pressures 0.1e6,0.3e6,0.8e6
  persson contact case.toml --estar 10e6 --pressures 1e5:1e6:10 --correction xu2024 --penetration kluppel

A PSD table (columns q in rad/m, C in m^4) needs --estar, the effective modulus E/(1-nu^2) in Pa. A case uses
its material at the sliding speed --speed (viscoelastic), or --estar instead (elastic). An existing output is
overwritten only with --force.
"""


def add_arguments(p):
    import argparse

    p.formatter_class = argparse.RawDescriptionHelpFormatter
    p.epilog = _EPILOG
    p.add_argument("source", metavar="CASE_OR_PSD", help=f"a PSD table (.csv) or a case: {CASE_HELP}")
    p.add_argument("--pressures", required=True, help=f"nominal pressures, Pa: {VALUES_HELP}")
    p.add_argument("--estar", type=float, default=None,
                   help="effective modulus E* = E/(1-nu^2), Pa: elastic contact (required for a PSD table)")
    p.add_argument("--speed", type=float, default=None,
                   help="sliding speed, m/s: the case's viscoelastic material at this speed")
    p.add_argument("--temperature", type=float, default=None,
                   help="background temperature, deg C (default: the case's)")
    p.add_argument("--gamma", type=float, default=None,
                   help="gamma of S = gamma + (1-gamma) P^2 (default: the case's, else 0.5)")
    p.add_argument("--correction", choices=("none", "yang-persson", "xu2024", "wang-muser"), default="none",
                   help="area correction (default none: uncorrected Persson theory)")
    p.add_argument("--gap-correction", choices=("area", "persson", "xu2024-hybrid", "gfmd-gap"), default="area",
                   help="law of the elastic energy and the separation (default area: the area law's)")
    p.add_argument("--penetration", choices=("persson", "load-weighted", "kluppel"), default="persson",
                   help="definition of the penetration_depth_m column (every one is written)")
    p.add_argument("--n-sigma", type=float, default=3.0,
                   help="height of the asperity tops in h_rms for the 'persson' penetration depth (default 3)")
    p.add_argument("-o", "--output", default=None, help="output CSV (default: <name>_contact.csv here)")
    p.add_argument("--plot", action="store_true", help="also write a PNG of A/A0 and u_bar vs pressure")
    add_force(p)
    add_quiet(p)


def run(args) -> int:
    from ..contact.mechanics import contact
    from ..errors import InputError
    from ..io import Outputs, write_csv

    from .._checks import plausible_modulus, plausible_speed, plausible_temperature

    pressures = parse_pressures(args.pressures)
    # the unit checks of `persson friction`: a slip here gives full contact or none, silently
    if args.estar is not None:
        plausible_modulus(args.estar, "--estar (Pa)", strict=True)
    if args.temperature is not None:
        plausible_temperature(args.temperature, "--temperature (deg C)", strict=True)
    if args.speed is not None:
        if not args.speed > 0:
            raise InputError(f"--speed: expected a sliding speed > 0 m/s, got {args.speed:g}")
        plausible_speed(args.speed, "--speed (m/s)")
    src = Path(args.source)
    is_table = src.suffix.lower() == ".csv"
    if is_table:
        if not src.is_file():
            raise InputError(f"PSD table {src} does not exist")
        if args.estar is None:
            raise InputError(f"--estar: a PSD table ({src.name}) needs the effective modulus E* in Pa")
        if args.speed is not None:
            raise InputError("--speed: a PSD table has no material; give --estar for an elastic contact")
        name, inputs = src.stem, (src,)
    else:
        from ..case.loader import parse_case

        if args.estar is not None and args.speed is not None:
            raise InputError("--estar and --speed: give one (--estar: elastic; --speed: the case's material)")
        if args.estar is None and args.speed is None:
            raise InputError("--speed: give the sliding speed in m/s for the case's viscoelastic material, or "
                             "--estar (Pa) for an elastic contact")
        parsed = parse_case(args.source)
        name, inputs = parsed.name, parsed.inputs
    correction = None if args.correction == "none" else args.correction
    out = Path(args.output) if args.output else Path(f"{name}_contact.csv")
    status = status_line(args, NAME)
    with Outputs(f"persson {NAME}", inputs=inputs, force=args.force) as outs:
        csv = outs.file(out, "-o")
        png = outs.file(out.with_suffix(".png"), "--plot") if args.plot else None
        if is_table:
            import surfaces

            surface = surfaces.read_psd(src)
            material, gamma, nu, T, where = args.estar, 0.5, 0.5, 20.0, f"PSD {src}"
        else:
            from ..case.loader import read_case

            with status.phase(f"reading {parsed.path.name}"):
                spec = read_case(parsed.path, progress=status)
            print_notes(spec.notes)
            surface = spec.model.surface
            material = args.estar if args.estar is not None else spec.model.material
            gamma, nu, T, where = spec.model.gamma, spec.model.nu, spec.temperature, f"case {spec.path}"
        if args.gamma is not None:
            gamma = args.gamma
        if args.temperature is not None:
            T = args.temperature
        with status.phase(f"contact at {pressures.size} pressures"):
            r = contact(surface, material, pressures, speed=args.speed, temperature=T, gamma=gamma, nu=nu,
                        correction=correction, gap_correction=args.gap_correction, penetration=args.penetration,
                        n_sigma=args.n_sigma)
        how = (f"E_star_Pa={r.E_star!r}" if r.E_star is not None
               else f"speed_m_s={r.speed!r}, temperature_C={r.temperature!r}, poisson={nu!r}")
        comments = (where, how, f"gamma={r.gamma!r}", f"correction={r.correction or 'none'}",
                    f"gap_correction={r.gap_correction}",
                    f"penetration_depth_m: {r.penetration} definition (n_sigma={r.n_sigma!r})",
                    f"excited_layer_thickness_m weighted by {r.excited_layer_weight}",
                    f"hrms_m={r.hrms!r}, rms_slope={r.rms_slope!r}", *r.notes)
        write_csv(csv, r.as_table(), comments=comments)
        if png is not None:
            from ..plots import save_figure

            save_figure(plot_contact(r, title=name), png)
    for path in outs.written:
        print(f"wrote {path.resolve()}")
    return 0


def parse_pressures(text: str) -> np.ndarray:
    """``p``, ``p1,p2,...`` or ``min:max:n`` (log-spaced) as pressures in Pa (> 0, checked for unit slips: 0.3 is
    0.3 MPa typed as Pa), or InputError."""
    from .._checks import plausible_pressure

    p = positive_values(text, "--pressures", "Pa")
    plausible_pressure(p, f"--pressures {text!r} (Pa)", strict=True)
    return p


def plot_contact(result, title: str = ""):
    """A/A0 and u_bar against the nominal pressure (log axes)."""
    from .. import plots  # noqa: F401  (selects the Agg backend before pyplot is imported)

    import matplotlib.pyplot as plt

    p = np.atleast_1d(result.pressure)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    ax1.loglog(p, np.atleast_1d(result.contact_area), "C0o-", ms=3)
    ax1.set_xlabel("nominal pressure (Pa)")
    ax1.set_ylabel("real contact area A/A0")
    ax2.semilogx(p, np.atleast_1d(result.mean_separation) * 1e6, "C1o-", ms=3)
    ax2.set_xlabel("nominal pressure (Pa)")
    ax2.set_ylabel("mean separation u_bar (um)")
    what = (f"E* = {result.E_star:.3g} Pa" if result.E_star is not None
            else f"v = {result.speed:g} m/s, T = {result.temperature:g} C")
    fig.suptitle(f"{title}: {what}, correction {result.correction or 'none'}" if title else what)
    return fig
