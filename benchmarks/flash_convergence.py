"""Convergence of the flash-temperature fixed point over hot conditions.

Run: ``python benchmarks/flash_convergence.py``.

Four compounds (soft to glassy) x five surfaces (those of ``benchmarks/accuracy.py``) x three road temperatures
(-20, 0, 20 C) x three pressures (0.1, 0.3, 1 MPa) x twelve speeds (1e-3..30 m/s): 2160 speeds, each solved on the
default grid without refinement (``max_refinement=0``), so that every speed is solved from T0 by the iteration
itself. Prints how many did not converge (residual >= the tolerance), the iterations per speed and the time.

``--save FILE.npz`` keeps mu and the residual of every speed; ``--compare FILE.npz`` compares with such a file
(e.g. written by another version of the solver): the largest relative difference of mu where both converged.

``--wide``: a wider regime instead, -40 / -20 / 0 / 40 C x 0.02 / 0.1 / 1 / 5 MPa x 14 speeds (1e-4..100 m/s), 4480
speeds; ``--refine`` solves with the default refinement (``max_refinement`` 3) instead of none.
"""

from __future__ import annotations

import argparse
import itertools
import sys
import time
import warnings
from pathlib import Path

import numpy as np

import persson

sys.path.insert(0, str(Path(__file__).resolve().parent))
from accuracy import compounds, surfaces_  # noqa: E402

SPEEDS = np.geomspace(1e-3, 30.0, 12)
TEMPERATURES = (-20.0, 0.0, 20.0)
PRESSURES = (0.1e6, 0.3e6, 1e6)


WIDE_SPEEDS = np.geomspace(1e-4, 100.0, 14)
WIDE_TEMPERATURES = (-40.0, -20.0, 0.0, 40.0)
WIDE_PRESSURES = (0.02e6, 0.1e6, 1e6, 5e6)


def run(wide: bool = False, refine: bool = False) -> dict:
    """{"compound|surface|T|p": array (2, n_speed) of mu and the residual, K}."""
    out = {}
    effect = persson.effects.FlashTemperature()
    grid = persson.GridSettings() if refine else persson.GridSettings(max_refinement=0)
    speeds, temps, press = ((WIDE_SPEEDS, WIDE_TEMPERATURES, WIDE_PRESSURES) if wide
                            else (SPEEDS, TEMPERATURES, PRESSURES))
    for (cname, m), (sname, s) in itertools.product(compounds().items(), surfaces_().items()):
        model = persson.Model(s, m, effects=[effect], grid=grid)
        for T, p in itertools.product(temps, press):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                r = model.friction(speeds, temperature=T, pressure=p)
            out[f"{cname}|{sname}|{T:g}|{p:g}"] = (np.asarray(r.mu), np.asarray(r.residual),
                                                   np.asarray(r.iterations))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--save", default=None, help="write mu and residuals to this .npz")
    ap.add_argument("--compare", default=None, help="compare with a .npz written by --save")
    ap.add_argument("--wide", action="store_true", help="the wider regime (-40..40 C, 0.02-5 MPa, 1e-4..100 m/s)")
    ap.add_argument("--refine", action="store_true", help="with the default refinement instead of none")
    args = ap.parse_args(argv)
    tol = persson.effects.FlashTemperature().tol
    t = time.perf_counter()
    res = run(wide=args.wide, refine=args.refine)
    seconds = time.perf_counter() - t
    residual = np.concatenate([r for _, r, _ in res.values()])
    its = np.concatenate([i for _, _, i in res.values()])
    print(f"{residual.size} speeds: {int(np.sum(residual >= tol))} not converged (residual >= {tol:g} K); "
          f"iterations per speed mean {its.mean():.1f}, median {np.median(its):.0f}, max {its.max()}; {seconds:.1f} s")
    if args.save:
        np.savez(args.save, **{k: np.vstack([mu, r]) for k, (mu, r, _) in res.items()})
    if args.compare:
        other = np.load(args.compare)
        worst, where = 0.0, ""
        for k, (mu, r, _) in res.items():
            if k not in other.files:
                continue
            ok = (r < tol) & (other[k][1] < tol)
            if ok.any():
                d = float(np.max(np.abs(mu[ok] / other[k][0][ok] - 1)))
                if d > worst:
                    worst, where = d, k
        print(f"largest relative difference of mu where both converged: {worst:.2e} ({where})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
