"""How often the diagnosis names a calibration error of the rig that the data carry (not a test).

Run: ``python benchmarks/rig_errors.py --n 40 --seed 1 [--out results.json]``

The cases are those of the blind study (``benchmarks/blind_study.py``, same seed: the same surfaces, compounds,
conditions, truths and noise), of its kinds with nothing or one effect hidden (``null`` and ``single``), and each
gets one error of the rig, drawn from its own random stream:

* ``gain``: every mu times g, 1 +- 0.05-0.15;
* ``offset``: every mu plus c p_ref / p (p_ref the geometric mean of the pressures), c = +-0.02-0.05;
* ``temperature``: the truth evaluated at T + dT, dT = +-2-8 K, the rows keeping T;
* ``speed``: the truth at s V, s = 1.15-1.3 or its inverse, the rows keeping V;
* ``slip``: the truth at slip + delta on the rows with slip < 1, delta = 0.005-0.02 (cases with a slip sweep only).

For a condition the truth is evaluated again at the shifted conditions (its converged grid) and the case's own
noise added to it. The diagnosis sees the case as a user would (:func:`validation.improve`, default candidates).
Printed per kind of error: in how many cases a rival of that kind is named (:mod:`validation.calibration`), with
its value within four standard errors of the truth or not; what the verdict answered; and the cases in which the
error was taken for a physical effect with no rival named.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import blind_study as bs  # noqa: E402

import validation  # noqa: E402
from validation.compare import json_text  # noqa: E402

KINDS = ("gain", "offset", "temperature", "speed", "slip")


def with_error(case, kind: str, rng) -> tuple[object, float]:
    """(measurements, true value): ``case``'s rows with an error of the rig of ``kind`` (module docstring)."""
    m = case.measurements
    noise = m.mu - case.mu_true   # the case's own noise (the rows were clipped at 0: kept as they are)
    sign = 1.0 if rng.random() < 0.5 else -1.0
    if kind == "gain":
        g = 1.0 + sign * rng.uniform(0.05, 0.15)
        return m.with_mu(np.clip(g * case.mu_true + noise, 0.0, None), mu_std=m.mu_std), g
    if kind == "offset":
        c = sign * rng.uniform(0.02, 0.05)
        p_ref = float(np.exp(np.mean(np.log(m.pressure))))
        return m.with_mu(np.clip(case.mu_true + c * p_ref / m.pressure + noise, 0.0, None), mu_std=m.mu_std), c
    if kind == "temperature":
        x = sign * rng.uniform(2.0, 8.0)
        shifted = dataclasses.replace(m, temperature=m.temperature + x, _checked=True)
    elif kind == "speed":
        x = rng.uniform(1.15, 1.3) ** sign
        shifted = dataclasses.replace(m, speed=m.speed * x, _checked=True)
    else:
        x = rng.uniform(0.005, 0.02)
        shifted = dataclasses.replace(m, slip=np.where(m.slip < 1.0, m.slip + x, m.slip), _checked=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mu = validation.predict(case.truth, shifted, case.truth_contact).mu
    return m.with_mu(np.clip(mu + noise, 0.0, None), mu_std=m.mu_std), x


def run(case, kind: str, seed: int) -> dict:
    """The case with an error of ``kind`` diagnosed, and what was named."""
    rng = np.random.default_rng([seed, case.index, 7919])
    m, true = with_error(case, kind, rng)
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        imp = validation.improve(case.model, m, contact=case.contact, fit=case.fit)
    cal = imp.selection.calibration if imp.selection is not None else None
    rivals = list(cal.rivals) if cal is not None else []
    same = [f for f in rivals if f.kind == kind]
    best = same[0] if same else None
    return {"index": case.index, "kind": case.kind, "hidden": sorted(case.hidden), "error": kind, "true": true,
            "verdict": imp.verdict, "found": sorted(imp.added), "sigma": case.sigma,
            "named": best is not None, "first": bool(rivals) and rivals[0].kind == kind,
            "value": None if best is None else best.value, "std": None if best is None else best.std,
            "within": bool(best is not None and abs(best.value - true) <= 4 * best.std),
            "rivals": [f"{f.kind} {f.value:.4g} +- {f.std:.2g} on {f.on}" for f in rivals],
            "seconds": time.perf_counter() - t0}


def summarize(results: list) -> str:
    lines = [f"{'error':<12}{'cases':>6}{'named':>7}{'first':>7}{'within 4 se':>12}   verdicts (found effects)"]
    for kind in KINDS:
        sel = [r for r in results if r["error"] == kind]
        if not sel:
            continue
        verdicts: dict = {}
        for r in sel:
            key = f"{r['verdict']} ({'+'.join(r['found']) or '-'})"
            verdicts[key] = verdicts.get(key, 0) + 1
        lines.append(f"{kind:<12}{len(sel):>6}{sum(r['named'] for r in sel):>7}{sum(r['first'] for r in sel):>7}"
                     f"{sum(r['within'] for r in sel):>12}   "
                     + ", ".join(f"{k}: {v}" for k, v in sorted(verdicts.items(), key=lambda t: -t[1])))
    missed = [r for r in results if not r["named"] and set(r["found"]) - set(r["hidden"])]
    lines.append(f"Taken for a physical effect with no rival of its kind named: {len(missed)} of {len(results)}"
                 + (" (" + "; ".join(f"case {r['index']} {r['error']} {r['true']:.3g} -> "
                                     f"{'+'.join(r['found'])}" for r in missed) + ")" if missed else ""))
    secs = [r["seconds"] for r in results]
    if secs:
        lines.append(f"Time per case: median {np.median(secs):.0f} s, max {max(secs):.0f} s ({len(results)} cases)")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=40, help="blind-study indices to draw from (default 40)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the study (default 1)")
    ap.add_argument("--out", default=None, help="JSON file for the per-case results (appended to when it exists)")
    args = ap.parse_args(argv)
    results = []
    if args.out and Path(args.out).exists():
        results = json.loads(Path(args.out).read_text(encoding="utf-8"))
    done = {r["index"] for r in results}
    k = 0
    for i in range(args.n):
        if bs.SCHEDULE[i % len(bs.SCHEDULE)] not in ("null", "single"):
            continue
        if i in done:
            k += 1
            continue
        case = bs.draw(i, args.seed)
        kinds = [e for e in KINDS if e != "slip" or bool(np.any(case.measurements.slip < 1.0))]
        case_kind = kinds[k % len(kinds)]
        k += 1
        r = run(case, case_kind, args.seed)
        results.append(r)
        named = f"named (value {r['value']:.4g})" if r["named"] else "not named"
        print(f"case {i:>3} {case.kind:<7} hidden {'+'.join(r['hidden']) or '-':<20} error {case_kind:<11} "
              f"{r['true']:+.4g} -> {r['verdict']:<17} {'+'.join(r['found']) or '-':<32} {named} "
              f"({r['seconds']:.0f} s)", flush=True)
        if args.out:
            json_text(results, args.out, overwrite=True)
    print()
    print(summarize(results))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
