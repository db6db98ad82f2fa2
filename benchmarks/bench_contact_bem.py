"""Persson's contact mechanics and its corrections against boundary elements (tamaas) on the same surfaces.

Run ``python benchmarks/bench_contact_bem.py`` (``--quick`` for the coarse grids alone, ``--json FILE`` to keep the
raw numbers, ``--from-json FILE`` to print the tables again from them; about 10-20 minutes on one core). Needs the
optional extra ``bem`` (``pip install tamaas``); without it the script says so and exits.

For each surface a periodic random-phase realisation of an isotropic power-law PSD (tamaas ``Isopowerlaw2D``:
flat from k_l to the roll-off k_r, then k^-2(1+H) up to k_s, wavenumbers in units of 2 pi / L) is pressed on an
elastic half-space (E* = 1) by the Polonsky-Keer-Rey solver at nominal pressures p = (p/E*h') E* h' (h' the rms
slope of the realisation). The BEM gives

* the real contact area A/A0 (fraction of nodes with positive pressure),
* the mean separation u_bar = mean(displacement - height) (the gap is zero in contact),
* the elastic energy U_el/A0 = mean((p - sigma0)(u - mean u)) / 2,
* the load-weighted penetration depth mean(p (z - u_bar)) / sigma0, which equals 2 U_el / (A0 sigma0) (Clapeyron's
  theorem; both are printed as a check).

The theory (``persson.contact``) runs on the continuous PSD of the realisation (``surfaces.SelfAffine`` with the same
k_l, k_r, k_s, H and the realisation's rms slope). Every BEM surface is solved on two grids, 16 and 32 nodes per
shortest wavelength, so the discretisation error of the BEM itself shows in the tables (the area of small contact
spots converges slowly with the grid: Yastrebov, Anciaux & Molinari, Tribol. Lett. 56, 171 (2014)).

Tamaas: G. Anciaux, L. Frérot et al., https://gitlab.com/tamaas/tamaas (J. Open Source Softw. 5, 2121 (2020)).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import time

#: (name, H, k_l, k_r, k_s): the surfaces of the table
SURFACES = (("H=0.8, roll-off", 0.8, 2, 4, 32), ("H=0.5, no roll-off", 0.5, 4, 4, 32))
#: nominal pressures in units of E* h'
LOADS = (0.002, 0.01, 0.03, 0.1)
#: theory variants: (label, area correction, gap correction, gamma)
VARIANTS = (("Persson", None, "area", 0.5), ("yang-persson", "yang-persson", "area", 0.5),
            ("xu2024", "xu2024", "area", 0.5), ("wang-muser", "wang-muser", "area", 0.5),
            ("xu2024-hybrid", "xu2024", "xu2024-hybrid", 0.42), ("gfmd-gap", None, "gfmd-gap", 0.5))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="coarse grids only (16 nodes per shortest wavelength)")
    ap.add_argument("--json", default=None, help="write the raw numbers to this JSON file (not overwritten)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--from-json", default=None, help="re-print the tables from a --json file (theory recomputed)")
    args = ap.parse_args(argv)
    if args.from_json:
        with open(args.from_json) as fh:
            out = json.load(fh)
        for res in out:
            res["theory"] = theory(res)
        print_tables(out)
        return 0
    try:
        import tamaas  # noqa: F401
    except ImportError:
        print("tamaas is not installed (pip install tamaas, or the 'bem' extra): nothing to compare; skipped")
        return 0
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    resolutions = (16,) if args.quick else (16, 32)
    out = []
    for name, H, kl, kr, ks in SURFACES:
        for px in resolutions:
            t0 = time.perf_counter()
            bem = solve_bem(H, kl, kr, ks, ks * px, LOADS, args.seed)
            print(f"# {name}: {ks * px}^2 nodes ({px} per shortest wavelength), {time.perf_counter() - t0:.0f} s")
            out.append(dict(surface=name, H=H, k_l=kl, k_r=kr, k_s=ks, px=px, loads=list(LOADS), **bem))
    for res in out:
        res["theory"] = theory(res)
    print_tables(out)
    if args.json:
        from persson.io import atomic_write

        if os.path.exists(args.json):
            raise SystemExit(f"--json: {args.json} exists; not overwritten")
        with atomic_write(args.json) as fh:
            json.dump(out, fh, indent=1)
        print(f"wrote {os.path.abspath(args.json)}")
    return 0


def solve_bem(H, kl, kr, ks, N, loads, seed) -> dict:
    """BEM (Polonsky-Keer-Rey, tamaas) on an N x N periodic grid of unit size; E* = 1."""
    import numpy as np
    import tamaas as tm

    tm.set_log_level(tm.LogLevel.error)
    spectrum = tm.Isopowerlaw2D()
    spectrum.q0, spectrum.q1, spectrum.q2, spectrum.hurst = kl, kr, ks, H
    gen = tm.SurfaceGeneratorRandomPhase2D([N, N])
    gen.spectrum = spectrum
    gen.random_seed = seed
    h = np.array(gen.buildSurface())
    k = 2.0 * math.pi * np.fft.fftfreq(N, d=1.0 / N)
    kx, ky = np.meshgrid(k, k, indexing="ij")
    hk = np.fft.fft2(h) / N**2
    slope = float(np.sqrt(np.sum((kx**2 + ky**2) * np.abs(hk) ** 2)))
    hrms = float(h.std())
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [N, N])
    model.E, model.nu = 1.0, 0.0
    solver = tm.PolonskyKeerRey(model, h, 1e-8)
    rows = {"area": [], "u_bar": [], "U_el": [], "depth_clapeyron": [], "depth_direct": []}
    for pr in loads:
        p0 = pr * slope
        solver.solve(p0)
        p = np.array(model.traction)
        u = np.array(model.displacement)
        u_bar = float(np.mean(u - h))
        U = 0.5 * float(np.mean((p - p.mean()) * (u - u.mean())))
        rows["area"].append(float(np.mean(p > 0)))
        rows["u_bar"].append(u_bar)
        rows["U_el"].append(U)
        rows["depth_clapeyron"].append(2.0 * U / p0)
        rows["depth_direct"].append(float(np.mean(p * (h - u_bar))) / p0)
    return dict(N=N, hrms=hrms, rms_slope=slope, **rows)


def theory(res) -> dict:
    """persson.contact on the continuous PSD of the realisation, for every variant."""
    import numpy as np

    import persson
    import surfaces
    from persson.contact import separation

    two_pi = 2.0 * math.pi
    s = surfaces.SelfAffine(hurst=res["H"], q0=two_pi * res["k_r"], q1=two_pi * res["k_s"], qL=two_pi * res["k_l"],
                            rms_slope=res["rms_slope"])
    p = np.array(res["loads"]) * res["rms_slope"]
    out = {"hrms": s.hrms()}
    q = np.geomspace(*s.q_range, 2001)
    for label, corr, gap, gamma in VARIANTS:
        r = persson.contact(s, 1.0, p, correction=corr, gap_correction=gap, gamma=gamma)
        out[label] = dict(area=r.contact_area.tolist(), u_bar=r.mean_separation.tolist(),
                          U_el=r.elastic_energy.tolist(), depth=r.penetration_depths["load-weighted"].tolist(),
                          u0=separation.separation_decay_length(q, s.C(q), gamma, correction=corr, gap_correction=gap))
    return out


def print_tables(out) -> None:
    for res in out:
        if res["px"] != max(r["px"] for r in out if r["surface"] == res["surface"]):
            continue
        coarse = next((r for r in out if r["surface"] == res["surface"] and r["px"] < res["px"]), None)
        th = res["theory"]
        h = res["hrms"]
        print(f"\n## {res['surface']}: H = {res['H']}, k = {res['k_l']}/{res['k_r']}/{res['k_s']}, "
              f"{res['N']}^2 nodes; h_rms BEM {h:.4g}, theory {th['hrms']:.4g}")
        labels = [v[0] for v in VARIANTS]
        for key, title, scale in (("area", "A/A0", 1.0), ("u_bar", "u_bar / h_rms", 1.0 / h),
                                  ("U_el", "U_el / (E* h_rms h')", 1.0 / (h * res["rms_slope"])),
                                  ("depth", "2 U_el / (sigma0 h_rms)", 1.0 / h)):
            bem_key = "depth_clapeyron" if key == "depth" else key
            print(f"\n{title}: BEM ({res['px']} px{'; ' + str(coarse['px']) + ' px' if coarse else ''}) and the "
                  "theory's deviation from it")
            print("| p/E*h' | BEM | " + " | ".join(labels) + " |")
            print("| --- " * (2 + len(labels)) + "|")
            for i, pr in enumerate(res["loads"]):
                b = res[bem_key][i]
                cell = f"{b * scale:.4g}" + (f" ({coarse[bem_key][i] * scale:.4g})" if coarse else "")
                devs = [f"{100 * (th[lab][key][i] / b - 1):+.0f} %" for lab in labels]
                print(f"| {pr:g} | {cell} | " + " | ".join(devs) + " |")
        u = res["u_bar"]
        lo = res["loads"]
        u0 = -(u[1] - u[0]) / math.log(lo[1] / lo[0]) / h
        print(f"\ndecay length u0/h_rms: BEM {u0:.3f} (loads {lo[0]:g}-{lo[1]:g}); theory "
              + ", ".join(f"{lab} {th[lab]['u0'] / th['hrms']:.3f}" for lab in labels))
        gap = max(abs(a / b - 1) for a, b in zip(res["depth_direct"], res["depth_clapeyron"]))
        print(f"Clapeyron check: mean(p (z - u_bar))/sigma0 vs 2 U_el/sigma0 agree to {gap:.1e}")


if __name__ == "__main__":
    raise SystemExit(main())
