"""Speed of the tread-element tool (run: ``python benchmarks/bench_tread.py``; not run by the tests).

The case of the issue: a 20-slip x 5-speed map over a 1.2 m road profile at 0.1 mm with a 15 cm footprint,
warm numba cache; targets <= 10 s on 2 cores for the map, <= 0.2 s for one (slip, speed) point, <= 1 GB of
memory. The profile is synthetic (seeded) with road-like texture; the local friction is the Persson engine's on
the scales finer than 0.1 mm (tabulated once, timed separately). Prints wall and CPU times (CPU summed over the
numba threads: on a shared machine it is the figure to compare), the number of time steps and element-steps,
the CPU time per element-step, and the peak resident memory.

Options: ``--element SIZE`` (tread element spacing, m; default the package's), ``--threads N`` (numba threads).
"""

from __future__ import annotations

import argparse
import math
import resource
import time

import numpy as np


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--element", type=float, default=None, help="tread element spacing, m")
    ap.add_argument("--threads", type=int, default=None, help="numba threads (default: all)")
    args = ap.parse_args()
    import numba

    if args.threads:
        numba.set_num_threads(args.threads)
    import materials
    import surfaces
    from persson import tread
    from persson.tread.simulate import DEFAULT_ELEMENT

    sa = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.15e-3, qL=2 * math.pi / 0.1)
    profile = surfaces.synthesize_profiles(sa, n_profiles=1, n=12000, length=1.2, seed=1)
    road = tread.as_road(profile)
    # a load that makes the footprint 15 cm long
    load = 4000.0
    for _ in range(30):
        t = tread.Tire(diameter=0.63, width=0.205, load=load, inflation_pressure=2.2e5, tread_depth=8e-3,
                       grooves=tread.Grooves(width=8e-3, pitch=30e-3))
        load *= (0.15 / t.footprint.length) ** 2
    fp = t.footprint
    material = materials.example_tread()
    slips = np.linspace(0.05, 1.0, 20)
    speeds = np.array([5.0, 10.0, 15.0, 20.0, 25.0])
    es = DEFAULT_ELEMENT if args.element is None else args.element
    opts = {"element_size": es}

    w = time.perf_counter()
    local = tread.local_friction(road, material, speeds=[slips.min() * speeds.min(), speeds.max()])
    t_local = time.perf_counter() - w
    # warm-up: compile or load the cached kernels
    tread.slip_map(t, road.crop(0.4), material, slips=[0.5], speeds=[10.0], mu_loc=0.5, **opts)
    tread.simulate(t, road.crop(0.4), material, speed=10.0, slip=0.5, mu_loc=0.5, **opts)

    w, c = time.perf_counter(), time.process_time()
    r = tread.simulate(t, road, material, speed=16.7, slip=1.0, mu_loc=local, **opts)
    t_point, c_point = time.perf_counter() - w, time.process_time() - c
    w, c = time.perf_counter(), time.process_time()
    r2 = tread.simulate(t, road, material, speed=16.7, slip=0.15, mu_loc=local, **opts)
    t_point2 = time.perf_counter() - w
    w, c = time.perf_counter(), time.process_time()
    m = tread.slip_map(t, road, material, slips=slips, speeds=speeds, mu_loc=local, **opts)
    t_map, c_map = time.perf_counter() - w, time.process_time() - c
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # MiB (Linux reports KiB)

    n_elem = round(fp.length / es)
    print(f"footprint {fp.length * 1e3:.1f} mm x {fp.width * 1e3:.1f} mm at {t.load:.0f} N; road 1.2 m at 0.1 mm; "
          f"elements {es * 1e3:g} mm ({n_elem} along the footprint); numba threads {numba.get_num_threads()}")
    print(f"local friction table ({local.mu.shape[0]} speeds x {local.mu.shape[1]} pressures): {t_local:.2f} s")
    print(f"one point, locked wheel at 16.7 m/s: {t_point:.3f} s wall, {c_point:.3f} s CPU, {r.time.size} steps, "
          f"{r.time.size * n_elem / 1e6:.1f} M element-steps ({c_point / (r.time.size * n_elem) * 1e9:.1f} ns CPU "
          f"each); mu = {r.mu:.4f} +- {r.mu_std:.4f}")
    print(f"one point, slip 0.15 at 16.7 m/s: {t_point2:.3f} s wall; mu = {r2.mu:.4f} +- {r2.mu_std:.4f}")
    print(f"map 20 slips x 5 speeds: {t_map:.2f} s wall, {c_map:.2f} s CPU; peak mu per speed "
          f"{np.round(m.peak_mu, 3).tolist()} at slips {np.round(m.peak_slip, 2).tolist()}, locked "
          f"{np.round(m.locked_mu, 3).tolist()}")
    print(f"peak resident memory: {rss:.0f} MiB")


if __name__ == "__main__":
    main()
