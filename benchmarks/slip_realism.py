"""The realistic road case against the published reference curves: the table and the figure of docs/slip.md.

Run ``python benchmarks/slip_realism.py [--figure docs/figures/slip_realism.png [--force]]``. It evaluates
:func:`persson.slip.example_road_case` (a passenger-car tire on a dry asphalt of rms slope 1.38, the synthetic
filled tread :func:`materials.example_tire_tread`, patch heating with the flash temperature, adhesion) at
20, 60 and 100 km/h and road temperatures 0, 20 and 40 C, with the brush stiffness of the tread (from the compound)
in series with the carcass and belt of the measured 205/60R15 tire of Pacejka's book and, for comparison, of the
tread alone (a rigid belt). It prints, per case, the initial slope of mu(s), the peak mu, the slip at the peak, the
locked-wheel mu and their ratio, and the published references: Pacejka's Magic Formula for a dry tarmac
(B, C, D, E = 10, 1.9, 1, 0.97), Burckhardt's dry asphalt (c1, c2, c3 = 1.2801, 23.99, 0.52) and the measured tire
(Pacejka 2006, Table A3.1, at 5.4 kN). Two variants show what raising the friction level to a tire's does to the
shape of the curve (20 C): strain softening (f, g = 0.5, 0.7) with an adhesive shear stress of 10 MPa, and S = 1
(gamma = 1) with strain softening and 5 MPa (``benchmarks/published_friction.py`` has the full sensitivity table).
Takes two to three minutes on a busy 2-core machine.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from persson import slip as ps  # noqa: E402

KMH = np.array([20.0, 60.0, 100.0])
TEMPERATURES = (0.0, 20.0, 40.0)
SLIPS = np.concatenate([np.geomspace(0.002, 0.5, 36), [0.6, 0.75, 0.9, 1.0]])
LOAD = 0.3e6 * 0.12 * 0.15


def references(slip):
    """(label, mu) of the three published curves."""
    from persson.slip.road import tire_magic_formula

    B, C, D, E = ps.MF_DRY_TARMAC
    return [("Magic Formula, dry tarmac (Pacejka)", ps.magic_formula(slip, B, C, D, E)),
            ("Burckhardt, dry asphalt", ps.burckhardt(slip, *ps.BURCKHARDT_DRY_ASPHALT)),
            ("measured tire 205/60R15 at 5.4 kN (Pacejka 2006)", ps.magic_formula(slip, *tire_magic_formula(LOAD)))]


def summary(slip, mu):
    pk, at = ps.peak(slip, mu)
    return float(pk), float(at), float(mu[-1]), float(mu[-1] / pk)


def run(case, temperatures=TEMPERATURES):
    """{T0: [SlipResult per speed]}."""
    return {T0: case.curves(SLIPS, KMH / 3.6, T0) for T0 in temperatures}


def variants(case):
    """(label, RoadCase) with a tire's friction level reached by inputs the case leaves at their defaults."""
    import dataclasses

    from persson.effects import Adhesion, StrainSoftening

    def with_effects(effects, **options):
        m = case.model
        return dataclasses.replace(case, model=ps.road_model(m.surface, m.material, effects=effects, grid=m.grid,
                                                             **options))

    return [("softening 0.5/0.7 + tau_f0 10 MPa", with_effects((Adhesion(tau_f0=10e6), StrainSoftening()))),
            ("gamma 1 + softening 0.5/0.7 + tau_f0 5 MPa",
             with_effects((Adhesion(tau_f0=5e6), StrainSoftening()), gamma=1.0))]


def main(figure=None, force=False):
    import dataclasses

    case = ps.example_road_case()
    tread_alone = dataclasses.replace(case, carcass_stiffness=None)
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the notes of each result are printed below instead
        derived = run(case)
        alone = run(tread_alone)
        varied = [(label, run(c, (20.0,))) for label, c in variants(case)]
    elapsed = time.perf_counter() - t0
    print(f"example_road_case: rms slope {case.model.surface.rms_slope():.3g}, sigma0 = {case.pressure / 1e6:g} MPa, "
          f"patch {case.length} x {case.width} m, carcass {case.carcass_stiffness:.3g} Pa/m; {elapsed:.0f} s")
    print("| stiffness | T0 (C) | V (km/h) | initial slope | peak mu | slip at peak | locked mu | locked/peak |")
    print("|---|---|---|---|---|---|---|---|")
    for label, res in [("tread + carcass", derived), ("tread alone", alone)] + varied:
        for T0, rows in res.items():
            for V, r in zip(KMH, rows):
                pk, at, lk, ratio = summary(SLIPS, r.mu)
                print(f"| {label} | {T0:g} | {V:g} | {r.contact.initial_slope(case.pressure):.3g} | {pk:.3f} | "
                      f"{at:.3f} | {lk:.3f} | {ratio:.2f} |")
    for label, mu in references(SLIPS):
        pk, at, lk, ratio = summary(SLIPS, mu)
        print(f"| {label} | | | | {pk:.3f} | {at:.3f} | {lk:.3f} | {ratio:.2f} |")
    notes = {n for res in [derived, alone] + [v for _, v in varied] for rows in res.values() for r in rows
             for n in r.notes}
    for n in sorted(notes):
        print("note:", n)
    if figure:
        print("figure:", plot(derived, alone, varied, figure, force))


def plot(derived, alone, varied, path, force=False):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from persson.plots import save_figure

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6), constrained_layout=True)
    for ax in axes[:2]:
        for (label, mu), style in zip(references(SLIPS), ("k-", "k--", "k:")):
            ax.plot(SLIPS, mu, style, lw=2, label=label)
        ax.set_xlabel("braking slip s")
        ax.set_ylabel("mu")
        ax.set_ylim(0, 1.5)
    ax = axes[0]
    for V, r, c in zip(KMH, derived[20.0], ("C0", "C1", "C3")):
        ax.plot(SLIPS, r.mu, color=c, label=f"model, {V:g} km/h")
    ax.plot(SLIPS, alone[20.0][0].mu, color="C0", ls="--", label="model, 20 km/h, tread alone")
    ax.set_title("the case: tread + carcass, T0 = 20 C")
    ax.legend(fontsize=8, loc="upper right")
    ax = axes[1]
    ax.plot(SLIPS, derived[20.0][0].mu, color="C0", label="the case")
    for (label, res), c in zip(varied, ("C2", "C4")):
        ax.plot(SLIPS, res[20.0][0].mu, color=c, label=label)
        ax.plot(SLIPS, res[20.0][-1].mu, color=c, ls="--", label=f"{label}, 100 km/h")
    ax.set_title("raising the level: T0 = 20 C, 20 km/h (dashed 100 km/h)")
    ax.legend(fontsize=8, loc="upper right")
    ax = axes[2]
    for T0, c in zip(TEMPERATURES, ("C0", "C2", "C3")):
        pk = [summary(SLIPS, r.mu)[0] for r in derived[T0]]
        lk = [summary(SLIPS, r.mu)[2] for r in derived[T0]]
        ax.plot(KMH, pk, "o-", color=c, label=f"peak, T0 = {T0:g} C")
        ax.plot(KMH, lk, "s--", color=c, label=f"locked, T0 = {T0:g} C")
    ax.set_xlabel("speed (km/h)")
    ax.set_ylabel("mu")
    ax.set_title("the case: peak and locked mu")
    ax.legend(fontsize=8)
    return save_figure(fig, path, overwrite=force)


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--figure", help="write the figure (PNG) here")
    p.add_argument("--force", action="store_true", help="replace an existing figure")
    a = p.parse_args()
    main(a.figure, a.force)
