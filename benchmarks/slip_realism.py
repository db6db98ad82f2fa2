"""The realistic road case against the published reference curves: the table and the figure of docs/slip.md.

Run ``python benchmarks/slip_realism.py [--figure docs/figures/slip_realism.png]``. It evaluates
:func:`persson.slip.example_road_case` (a passenger-car tire on a dry asphalt of rms slope 1.38, the synthetic
filled tread :func:`materials.example_tire_tread`, patch heating with the flash temperature, adhesion) at
20, 60 and 100 km/h and road temperatures 0, 20 and 40 C, with the tread stiffness derived from the compound and,
for comparison, with the slip stiffness of a measured passenger-car tire (initial slope 20 of mu(s): Pacejka's
brush stiffness as fitted to tires, which includes the belt). It prints, per case, the peak mu, the slip at the
peak, the locked-wheel mu and their ratio, and the published references: Pacejka's Magic Formula for a dry tarmac
(B, C, D, E = 10, 1.9, 1, 0.97) and Burckhardt's dry asphalt (c1, c2, c3 = 1.2801, 23.99, 0.52).
Takes about a minute on a busy 2-core machine.
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
#: Initial slope of mu(s) of a measured passenger-car tire (slip stiffness / load), for the comparison
TIRE_SLOPE = 20.0


def references(slip):
    """(label, mu) of the two published curves."""
    B, C, D, E = ps.MF_DRY_TARMAC
    return [("Magic Formula, dry tarmac (Pacejka)", ps.magic_formula(slip, B, C, D, E)),
            ("Burckhardt, dry asphalt", ps.burckhardt(slip, *ps.BURCKHARDT_DRY_ASPHALT))]


def summary(slip, mu):
    pk, at = ps.peak(slip, mu)
    return float(pk), float(at), float(mu[-1]), float(mu[-1] / pk)


def run(case, given_stiffness=False):
    """{T0: [SlipResult per speed]}."""
    out = {}
    for T0 in TEMPERATURES:
        if not given_stiffness:
            out[T0] = case.curves(SLIPS, KMH / 3.6, T0)
            continue
        k = 2.0 * case.pressure * TIRE_SLOPE / case.length
        out[T0] = [ps.mu_slip(case.model, SLIPS, V, temperature=T0, pressure=case.pressure,
                              contact=ps.Contact(case.length, case.width, k)) for V in KMH / 3.6]
    return out


def main(figure=None):
    case = ps.example_road_case()
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the notes of each result are printed below instead
        derived = run(case)
        given = run(case, given_stiffness=True)
    elapsed = time.perf_counter() - t0
    print(f"example_road_case: rms slope {case.model.surface.rms_slope():.3g}, sigma0 = {case.pressure / 1e6:g} MPa, "
          f"patch {case.length} x {case.width} m; {elapsed:.0f} s")
    print("| stiffness | T0 (C) | V (km/h) | initial slope | peak mu | slip at peak | locked mu | locked/peak |")
    print("|---|---|---|---|---|---|---|---|")
    for label, res in (("from the compound", derived), (f"tire, slope {TIRE_SLOPE:g}", given)):
        for T0, rows in res.items():
            for V, r in zip(KMH, rows):
                pk, at, lk, ratio = summary(SLIPS, r.mu)
                print(f"| {label} | {T0:g} | {V:g} | {r.contact.initial_slope(case.pressure):.3g} | {pk:.3f} | "
                      f"{at:.3f} | {lk:.3f} | {ratio:.2f} |")
    for label, mu in references(SLIPS):
        pk, at, lk, ratio = summary(SLIPS, mu)
        print(f"| {label} | | | | {pk:.3f} | {at:.3f} | {lk:.3f} | {ratio:.2f} |")
    notes = {n for res in (derived, given) for rows in res.values() for r in rows for n in r.notes}
    for n in sorted(notes):
        print("note:", n)
    if figure:
        print("figure:", plot(derived, given, figure))


def plot(derived, given, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from persson.plots import save_figure

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6), constrained_layout=True)
    for ax, res, title in ((axes[0], derived, "tread stiffness from the compound"),
                           (axes[1], given, f"slip stiffness of a tire (initial slope {TIRE_SLOPE:g})")):
        for (label, mu), style in zip(references(SLIPS), ("k-", "k--")):
            ax.plot(SLIPS, mu, style, lw=2, label=label)
        for V, r, c in zip(KMH, res[20.0], ("C0", "C1", "C3")):
            ax.plot(SLIPS, r.mu, color=c, label=f"model, {V:g} km/h")
        ax.set_xlabel("braking slip s")
        ax.set_ylabel("mu")
        ax.set_ylim(0, 1.4)
        ax.set_title(f"{title}, T0 = 20 C")
        ax.legend(fontsize=8, loc="upper right")
    ax = axes[2]
    for T0, c in zip(TEMPERATURES, ("C0", "C2", "C3")):
        pk = [summary(SLIPS, r.mu)[0] for r in derived[T0]]
        lk = [summary(SLIPS, r.mu)[2] for r in derived[T0]]
        ax.plot(KMH, pk, "o-", color=c, label=f"peak, T0 = {T0:g} C")
        ax.plot(KMH, lk, "s--", color=c, label=f"locked, T0 = {T0:g} C")
    ax.set_xlabel("speed (km/h)")
    ax.set_ylabel("mu")
    ax.set_title("model (stiffness from the compound)")
    ax.legend(fontsize=8)
    return save_figure(fig, path)


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--figure", help="write the figure (PNG) here")
    main(p.parse_args().figure)
