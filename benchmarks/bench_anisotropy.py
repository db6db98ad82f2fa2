"""Timing and accuracy of the anisotropic engine: mu for 36 sliding directions x 30 speeds.

Run ``python benchmarks/bench_anisotropy.py`` (``--accuracy`` adds the comparison with the brute-force 2-D
quadrature of ``persson.engine.anisotropic_reference`` at a few conditions, about a second each). Prints:

* warm ``Model.friction(speeds, direction_deg=...)`` with 36 directions (every 10 deg) x 30 speeds (1e-6 .. 10 m/s)
  of ``materials.example_tread()`` at 20 C and 0.3 MPa, median of repeats, on: the example road stretched 3x and
  10x, the 2-D PSD of a synthetic stretched height map (``HeightMap.psd2d``), the unidirectional limit of the
  road's line scans, and an isotropic PSD given in 2-D; beside it the isotropic engine's 30-speed call;
* the largest error estimate of each;
* the first call in a fresh process with the numba cache warm (import + load + first call).

The target is 1 s for 36 x 30 on two cores with a warm cache; run it with ``NUMBA_NUM_THREADS=2`` (and
``taskset -c 0,1``) to measure that.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import textwrap
import time
import warnings

import numpy as np

SPEEDS = np.geomspace(1e-6, 10.0, 30)
DIRECTIONS = np.arange(36) * 10.0


def surfaces_to_time():
    import surfaces

    road = surfaces.example_road()
    stretched = surfaces.stretched(road, 3.0, 30.0)
    # a synthetic map of a stretched surface (5 cm, 512^2) and its measured 2-D PSD
    s_map = surfaces.stretched(surfaces.SelfAffine(hurst=0.8, q0=2 * np.pi / 5e-3, q1=3e4, hrms=0.2e-3,
                                                   qL=2 * np.pi / 0.05), 3.0, 30.0)
    n, L = 512, 0.05
    q = 2 * np.pi * np.fft.fftfreq(n, L / n)
    QX, QY = np.meshgrid(q, q)
    C = s_map.C2d(QX, QY)
    C[0, 0] = 0.0
    W = np.fft.fft2(np.random.default_rng(1).standard_normal((n, n)))
    z = np.fft.ifft2(W * np.sqrt(C) * n * (2 * np.pi / L)).real
    psd2d = surfaces.HeightMap(z, L / n, periodic=True).psd2d()
    scans = surfaces.PSD1D.from_isotropic(road.with_cutoff(q1=1e6))
    return {
        "road stretched 3x": stretched,
        "road stretched 10x": surfaces.stretched(road, 10.0, 30.0),
        "HeightMap.psd2d (512^2)": psd2d,
        "unidirectional (road scans)": surfaces.unidirectional(scans, 30.0),
        "isotropic given in 2-D": surfaces.stretched(road, 1.0),
    }


def warm(model, repeats: int = 7):
    """Median wall time and processor time (all threads), s, of the 36 x 30 call after a warm-up; its result.

    On a shared machine the processor time is the steadier number: the wall time of an unloaded two-core
    machine is about half of it where the work runs in parallel."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = model.friction(SPEEDS, temperature=20.0, pressure=0.3e6, direction_deg=DIRECTIONS)
        wall, cpu = [], []
        for _ in range(repeats):
            t, c = time.perf_counter(), time.process_time()
            model.friction(SPEEDS, temperature=20.0, pressure=0.3e6, direction_deg=DIRECTIONS)
            wall.append(time.perf_counter() - t)
            cpu.append(time.process_time() - c)
    return statistics.median(wall), statistics.median(cpu), r


def first_call() -> float:
    code = textwrap.dedent("""
        import time
        t0 = time.perf_counter()
        import warnings
        import numpy as np
        import materials, persson, surfaces
        warnings.simplefilter("ignore")
        s = surfaces.stretched(surfaces.example_road(), 3.0, 30.0)
        persson.Model(s, materials.example_tread()).friction(np.geomspace(1e-6, 10, 30),
                                                             direction_deg=np.arange(36) * 10.0)
        print(time.perf_counter() - t0)
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(out.stdout.strip().splitlines()[-1])


def accuracy():
    """Engine vs the brute-force 2-D quadrature: relative error of mu and the engine's own estimate."""
    import materials
    import persson
    import surfaces
    from persson.engine.anisotropic_reference import reference_directional_friction

    tread = materials.example_tread()
    road = surfaces.SelfAffine(hurst=0.8, q0=2 * np.pi / 5e-3, q1=1e6, hrms=0.2e-3)
    print("\naccuracy against the brute-force 2-D quadrature (example tread, 0.3 MPa)")
    print(f"{'surface':28s} {'v m/s':>8s} {'T C':>5s} {'dir':>5s} {'mu':>10s} {'rel. error':>11s} {'estimate':>9s}")
    for ratio in (2.0, 10.0):
        s = surfaces.stretched(road, ratio, 30.0)
        for v, T in ((1e-4, 20.0), (1.0, 0.0), (10.0, 20.0)):
            for th in (0.0, 30.0, 75.0, 120.0):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    r = persson.Model(s, tread).friction(v, temperature=T, pressure=0.3e6, direction_deg=th)
                ref = reference_directional_friction(s, tread, v, th, T, 0.3e6, rtol=1e-9)
                err = r.mu_hysteresis / ref.mu[0] - 1.0
                print(f"{'road stretched %gx' % ratio:28s} {v:8.2g} {T:5.0f} {th:5.0f} {r.mu_hysteresis:10.5g} "
                      f"{err:11.2e} {r.error_estimate:9.2e}")
    # an angular shape that changes with q (a roll-off plateau): the reference integrates the angles at every
    # step of its ODE solve (about ten seconds per condition)
    s = surfaces.stretched(surfaces.SelfAffine(hurst=0.8, q0=3e3, q1=3e4, hrms=5e-6, qL=1e3), 3.0, 45.0)
    for v, th in ((1e-2, 100.0), (1.0, 10.0)):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = persson.Model(s, tread).friction(v, temperature=20.0, pressure=0.3e6, direction_deg=th)
        ref = reference_directional_friction(s, tread, v, th, 20.0, 0.3e6, rtol=1e-9)
        print(f"{'plateau, stretched 3x':28s} {v:8.2g} {20.0:5.0f} {th:5.0f} {r.mu_hysteresis:10.5g} "
              f"{r.mu_hysteresis / ref.mu[0] - 1.0:11.2e} {r.error_estimate:9.2e}")


def main():
    import materials
    import persson

    tread = materials.example_tread()
    print(f"mu for {DIRECTIONS.size} directions x {SPEEDS.size} speeds, example tread, 20 C, 0.3 MPa (warm)")
    print(f"{'surface':32s} {'wall s':>8s} {'cpu s':>8s} {'max estimate':>13s}")
    for name, s in surfaces_to_time().items():
        t, c, r = warm(persson.Model(s, tread))
        print(f"{name:32s} {t:8.3f} {c:8.3f} {float(np.max(r.error_estimate)):13.2e}")
    import surfaces

    iso = persson.Model(surfaces.example_road(), tread)
    iso.friction(SPEEDS)
    times = []
    for _ in range(7):
        t = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            iso.friction(SPEEDS)
        times.append(time.perf_counter() - t)
    print(f"{'isotropic engine, 30 speeds':32s} {statistics.median(times):8.3f}")
    print(f"first 36 x 30 call in a fresh process (warm numba cache): {first_call():.2f} s")
    if "--accuracy" in sys.argv:
        accuracy()


if __name__ == "__main__":
    main()
