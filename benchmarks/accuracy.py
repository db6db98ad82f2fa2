"""Accuracy of the default solver settings over the operating regime (run: ``python benchmarks/accuracy.py``).

For every combination of compound (soft to glassy), surface (sandpaper to road, a PSD table that starts
abruptly at q0), sliding speed (1e-8..30 m/s), temperature (-20..80 C) and nominal pressure (0.02..2 MPa) it
computes mu_hysteresis with the default :class:`persson.GridSettings` and with a converged setting (256 q nodes
and 160 modulus nodes per decade, the temperature-shift table every 0.01 K instead of 0.25 K), with and without
the flash temperature, and prints

* the worst relative error of the defaults, per compound and surface, and overall;
* how the built-in ``error_estimate`` compares with the true error (ratio estimate / true where the true error
  exceeds 1e-6);
* the converged setting against the independent adaptive quadrature of :mod:`persson.engine.reference` at the corners,
  and, with the flash temperature, against its independent fixed-point iteration (the glassy corner and a tread);
* the table of the stiff-regime accuracy report (the glassy compound on a road).

Options: ``--quick`` (fewer conditions), ``--no-flash``, ``--no-reference``.
"""

from __future__ import annotations

import argparse
import itertools
import math
import sys
import time
import warnings

import numpy as np

import materials
import persson
import surfaces

CONVERGED = persson.GridSettings(q_per_decade=256, omega_per_decade=160, temperature_step=0.01)
SPEEDS = np.array([1e-8, 1e-6, 1e-4, 1e-2, 1.0, 30.0])
TEMPERATURES = (-20.0, 20.0, 80.0)
PRESSURES = (0.02e6, 0.3e6, 2e6)


def compounds() -> dict:
    """Soft to glassy: the example tread, a compound with its glass transition at tau = 1e-8 s (61 Prony terms),
    a narrow single-peak compound (one Prony term per decade) and a soft, low-modulus compound."""
    wlf = materials.WLF(8.86, 101.6, 20.0)
    tau = np.logspace(-14, -2, 61)
    w = np.exp(-0.5 * ((np.log10(tau) + 8.0) / 2.0) ** 2)
    glassy = materials.Prony(E_inf=3e6, E_i=(2e9 - 3e6) * w / w.sum(), tau_i=tau, wlf=wlf, label="glassy")
    tau_n = np.logspace(-9, -3, 7)
    wn = np.exp(-0.5 * ((np.log10(tau_n) + 6.0) / 0.8) ** 2)
    narrow = materials.Prony(E_inf=2e6, E_i=(5e8 - 2e6) * wn / wn.sum(), tau_i=tau_n, wlf=wlf, label="narrow")
    tau_s = np.logspace(-10, 0, 31)
    ws = np.exp(-0.5 * ((np.log10(tau_s) + 7.0) / 2.5) ** 2)
    soft = materials.Prony(E_inf=0.5e6, E_i=(50e6 - 0.5e6) * ws / ws.sum(), tau_i=tau_s, wlf=wlf, label="soft")
    return {"tread": materials.example_tread(), "glassy": glassy, "narrow": narrow, "soft": soft}


def surfaces_() -> dict:
    """Sandpaper (H 0.6 and 0.9, q1/q0 = 1e5 and 1e4), the example road, and a PSD table with noise that starts
    abruptly at q0 (no roll-off)."""
    rng = np.random.default_rng(1)
    q = np.geomspace(2e3, 2e7, 161)
    C = 1e-22 * (q / 2e3) ** (-2 * 1.8) * np.exp(0.2 * rng.standard_normal(q.size))
    table = surfaces.PSD(q, C)
    return {
        "sandpaper H0.6": surfaces.SelfAffine(hurst=0.6, q0=1e3, q1=1e8, hrms=30e-6),
        "sandpaper H0.9": surfaces.SelfAffine(hurst=0.9, q0=1e4, q1=1e8, hrms=10e-6),
        "road": surfaces.example_road(),
        "rough road": surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3),
        "table": table,
    }


def run(quick: bool, flash: bool, reference: bool) -> int:
    comps = compounds()
    surfs = surfaces_()
    temps = TEMPERATURES[::2] if quick else TEMPERATURES
    press = PRESSURES[::2] if quick else PRESSURES
    effect_sets = [("hysteresis", ())] + ([("flash", (persson.effects.FlashTemperature(tol=1e-6),))] if flash else [])
    worst = {}
    ratios = []
    t_start = time.time()
    for (cname, m), (sname, s), (label, eff) in itertools.product(comps.items(), surfs.items(), effect_sets):
        if label == "flash" and quick and sname.startswith("sandpaper H0.9"):
            continue
        default = persson.Model(s, m, effects=eff)
        converged = default.replace(grid=CONVERGED)
        for T, p in itertools.product(temps, press):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                a = default.friction(SPEEDS, temperature=T, pressure=p)
                b = converged.friction(SPEEDS, temperature=T, pressure=p)
            err = np.abs(a.mu_hysteresis / b.mu_hysteresis - 1)
            key = (cname, sname, label)
            i = int(np.argmax(err))
            if key not in worst or err[i] > worst[key][0]:
                worst[key] = (float(err[i]), SPEEDS[i], T, p)
            ratios.extend(zip(err.tolist(), np.atleast_1d(a.error_estimate).tolist()))
    print(f"default grid {persson.GridSettings()} vs converged {CONVERGED.q_per_decade}/{CONVERGED.omega_per_decade}"
          f" ({time.time() - t_start:.0f} s)")
    print(f"{'compound':8s} {'surface':16s} {'physics':10s} {'worst rel. error':>16s}  at (v m/s, T C, p MPa)")
    for (c, s, lab), (e, v, T, p) in sorted(worst.items()):
        print(f"{c:8s} {s:16s} {lab:10s} {e:16.2e}  ({v:.0e}, {T:g}, {p / 1e6:g})")
    for lab in {k[2] for k in worst}:
        print(f"worst over the regime, {lab}: {max(e for k, (e, *_) in worst.items() if k[2] == lab):.2e}")
    if ratios:
        r = np.array(ratios)
        for floor in (1e-6, 1e-5, 2e-5):
            k = r[:, 0] > floor
            x = r[k, 1] / r[k, 0]
            print(f"error_estimate / true error where the true error > {floor:g}: n = {x.size}, median "
                  f"{np.median(x):.2f}, within a factor 3: {np.mean((x > 1 / 3) & (x < 3)):.1%} "
                  f"({np.sum(x < 1 / 3)} more than 3x low, {np.sum(x > 3)} more than 3x high), "
                  f"min {x.min():.2f}, max {x.max():.2f}")
    stiff_table()
    if reference:
        reference_check(comps, surfs)
        if flash:
            flash_reference_check(comps, surfs)
    return 0


def stiff_table() -> None:
    """The glassy compound on a rough road at the conditions of the stiff-regime accuracy report."""
    m = compounds()["glassy"]
    s = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3)
    print("\nstiff regime (glassy compound, rough road): mu_hysteresis by q nodes per decade (fixed grids; the "
          "default column with its adaptive refinement)")
    rows = [(1.0, 20.0, 0.3e6), (10.0, 20.0, 0.3e6), (10.0, 0.0, 0.1e6), (30.0, 0.0, 0.1e6)]
    grids = [8, 16, persson.GridSettings().q_per_decade, 64, 256]
    print(f"{'v, T, sigma0':22s}" + "".join(f"{g:>10d}" for g in grids) + "   estimate(default)")
    for v, T, p in rows:
        vals = []
        est = None
        for g in grids:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                grid = persson.GridSettings(q_per_decade=g, omega_per_decade=160 if g == 256 else 40,
                                            max_refinement=0 if g != persson.GridSettings().q_per_decade else 3)
                r = persson.Model(s, m, grid=grid).friction(v, temperature=T, pressure=p)
            vals.append(r.mu_hysteresis)
            if g == persson.GridSettings().q_per_decade:
                est = r.error_estimate
        print(f"{v:g} m/s, {T:g} C, {p / 1e6:g} MPa".ljust(22) + "".join(f"{x:10.5f}" for x in vals) + f"   {est:.1e}")


def reference_check(comps, surfs) -> None:
    """The converged engine against the independent adaptive quadrature (persson.engine.reference) at the corners."""
    from persson.engine.reference import reference_friction

    print("\nconverged setting vs independent adaptive quadrature (persson.engine.reference)")
    corners = [("glassy", "rough road", 30.0, -20.0, 0.02e6), ("glassy", "sandpaper H0.6", 1.0, 0.0, 0.1e6),
               ("soft", "road", 1e-8, 80.0, 2e6), ("narrow", "table", 1e-2, 20.0, 0.3e6),
               ("tread", "sandpaper H0.9", 1e-4, -20.0, 0.02e6)]
    for c, s, v, T, p in corners:
        t = time.time()
        ref = reference_friction(surfs[s], comps[c], v, T, p)
        mu_ref, area_ref = ref.mu, ref.contact_area
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = persson.Model(surfs[s], comps[c], grid=CONVERGED).friction(v, temperature=T, pressure=p)
            d = persson.Model(surfs[s], comps[c]).friction(v, temperature=T, pressure=p)
        print(f"{c:7s} {s:15s} v={v:g} T={T:g} p={p / 1e6:g} MPa: mu ref {mu_ref[0]:.6g}, converged "
              f"{r.mu_hysteresis / mu_ref[0] - 1:+.1e}, default {d.mu_hysteresis / mu_ref[0] - 1:+.1e}; "
              f"A/A0 ref {area_ref[0]:.4g}, default {d.contact_area / area_ref[0] - 1:+.1e} ({time.time() - t:.0f} s)")


def flash_reference_check(comps, surfs) -> None:
    """The engine with the flash temperature (default and converged settings) against the independent fixed-point
    iteration (persson.engine.reference.reference_flash_friction) at 160 and 320 nodes per decade, extrapolated
    with the observed order of the last three densities (80, 160, 320)."""
    from persson.engine.reference import reference_flash_friction

    print("\nflash temperature vs the independent fixed-point iteration (persson.engine.reference)")
    corners = [("glassy", "rough road", 3.0, -20.0, 0.02e6), ("tread", "rough road", 1.0, 20.0, 0.3e6)]
    for c, s, v, T, p in corners:
        t = time.time()
        mus = [reference_flash_friction(surfs[s], comps[c], v, T, p, nodes_per_decade=n, tol=1e-6).mu[0]
               for n in (80, 160, 320)]
        ratio = (mus[1] - mus[0]) / (mus[2] - mus[1])
        mu_ref = mus[2] + (mus[2] - mus[1]) / (ratio - 1.0) if ratio > 1.5 else math.nan
        effects = [persson.effects.FlashTemperature(tol=1e-8)]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            d = persson.Model(surfs[s], comps[c], effects=effects).friction(v, temperature=T, pressure=p)
            r = persson.Model(surfs[s], comps[c], effects=effects, grid=CONVERGED).friction(v, temperature=T,
                                                                                          pressure=p)
        print(f"{c:7s} {s:15s} v={v:g} T={T:g} p={p / 1e6:g} MPa: reference {mus[0]:.6g} {mus[1]:.6g} {mus[2]:.6g} "
              f"(80/160/320 per decade; order {math.log2(ratio):.2f}) -> {mu_ref:.6g}; converged "
              f"{r.mu_hysteresis / mu_ref - 1:+.1e}, default {d.mu_hysteresis / mu_ref - 1:+.1e} "
              f"(estimate {d.error_estimate:.1e}); flash rise {float(d.max_flash_temperature):.0f} K "
              f"({time.time() - t:.0f} s)")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--no-flash", action="store_true")
    ap.add_argument("--no-reference", action="store_true")
    a = ap.parse_args(argv)
    return run(a.quick, not a.no_flash, not a.no_reference)


if __name__ == "__main__":
    sys.exit(main())
