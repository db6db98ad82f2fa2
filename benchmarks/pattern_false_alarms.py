"""False-alarm rate of the remaining-pattern tests and of the lack-of-fit test on noise-only data (not a test).

Run: ``python benchmarks/pattern_false_alarms.py [--n 200] [--seed 1] [--cases example,null,...]
[--blind 18:41,18:51]`` (``--blind SEED:INDEX``: cases of ``benchmarks/blind_study.py`` instead of shipped ones)

For each case the diagnosis is run once; its verdict's model (the explaining candidate, else the refitted
baseline) is taken as the truth. Each simulation adds fresh Gaussian noise to that model's prediction (the noise
level the diagnosis estimated; ``mu_std`` where the case gives it) and judges the residual the way a diagnosis
does: the noise is estimated again from the simulated data (same source as the case: ``mu_std``, replicates or
local differences), the residual is that of the model refitted to the simulated data, and
:func:`validation.remaining_pattern` and :func:`validation.lack_of_fit` are applied. The refit is linearised: the
residual is the noise with its projection onto the columns of the model's (weighted) Jacobian at the optimum
removed, :math:`r = (I - J (J^T W^2 J)^{-1} J^T W^2)\\,\\varepsilon` -- exact to first order in the noise, and the
noise here is small (about 1 % of mu). Every simulated residual is pure noise, so every finding is a false alarm.

Prints, per case: the number of simulations, the false-alarm rate of the pattern tests (any family), of each
family, of the lack-of-fit test, and of either (what would turn a right ``explained`` into ``partly_explained``),
with the binomial 95 % upper bound; the rate at which :func:`validation.outliers.outlying_rows` names a row
(its nominal level is :data:`validation.outliers.ALPHA`); and the rate at which
:func:`validation.localize.localize_misfit` places a misfit in one family of rows (sliding, with slip, wet; its
nominal level is at most :data:`validation.localize.ALPHA` without the refit of the model's parameters to the rows
outside a family, at most twice that with it; the refit is linear here, as the simulation is; a verdict states it
only when it misses the data, so this is an upper bound of the rate at which a verdict would).
"""

from __future__ import annotations

import argparse
import time
import warnings
from types import SimpleNamespace

import numpy as np
from scipy import stats

import validation
from validation.fitting import Fitter, ParameterSpace
from validation.noise import _group_findings, _runs_finding, _trend_findings, estimate_noise, lack_of_fit
from validation.noise import remaining_pattern
from validation.localize import ALPHA as LOCALIZE_ALPHA
from validation.localize import localize_misfit
from validation.outliers import ALPHA, outlying_rows

DEFAULT_CASES = ("example", "hidden_flash", "hidden_adhesion", "hidden_microtexture", "hidden_strain_softening",
                 "null")


def truth_model(case):
    """(model, contact, Jacobian of the prediction in u, number of fitted parameters, diagnosis) of the verdict's
    model of ``case``."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        dx = validation.diagnose(case, probe=False)
    ctx = dx.context
    c = dx.explaining
    if c is not None:
        model, contact, names = c.model, c.contact, list(case.fit) + [f"{c.effect}.{p}" for p in c.free]
    else:
        model, contact, names = dx.baseline.model, dx.baseline.contact, list(case.fit)
    space = ParameterSpace(ctx.parameters(model, names))
    s = ctx.settings
    fitter = Fitter(s.predictor, s.y, s.w, model, space, max_evals=10 ** 6, contact=contact)
    u = space.u_of(model, contact)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mu = fitter.mu(u)
        J = fitter.jacobian(u) if len(space) else np.zeros((mu.size, 0))
    return mu, J, len(space), dx


def simulate(case, n_sim: int, rng) -> dict:
    """False alarms of the pattern and lack-of-fit tests on ``n_sim`` noise-only simulations of ``case``."""
    mu, J, k, dx = truth_model(case)
    m = case.measurements
    ne = dx.noise_estimate
    sigma = m.mu_std if m.mu_std is not None else np.full(m.n, ne.sigma if ne.known else 0.01)
    w = 1.0 / sigma
    Jw = J * w[:, None]
    # the refit's residual: the noise minus its weighted projection onto the Jacobian's columns
    if k:
        Q = np.linalg.qr(Jw)[0]
    # the localization's refit of the parameters to the rows outside a family, linear as the simulation is
    refit = SimpleNamespace(jacobian=J) if k else None
    counts = {"pattern": 0, "groups": 0, "runs": 0, "trends": 0, "lack_of_fit": 0, "either": 0, "outliers": 0,
              "localized": 0}
    for _ in range(n_sim):
        eps = rng.normal(0.0, sigma)
        ew = eps * w
        r = (ew - Q @ (Q.T @ ew)) / w if k else eps
        sim = m.with_mu(np.clip(mu + eps, 0.0, None), mu_std=m.mu_std)
        noise = estimate_noise(sim, reference=mu)
        pat = remaining_pattern(r, sim, noise)
        lof = lack_of_fit(r, k, noise)
        sig = noise.row_sigma if noise.known else np.full(m.n, float(np.std(r, ddof=1)))
        dof = noise.dof if noise.known else max(r.size - 1, 1)
        counts["groups"] += bool(_group_findings(r, sim, sig, dof)[1])
        counts["runs"] += bool(_runs_finding(r, sim, sig, dof)[1])
        counts["trends"] += bool(_trend_findings(r, sim, sig, dof)[1])
        counts["pattern"] += pat.found
        counts["lack_of_fit"] += not lof.consistent
        counts["either"] += pat.found or not lof.consistent
        counts["outliers"] += outlying_rows(r, noise, sim, "the model") is not None
        counts["localized"] += localize_misfit(r, noise, sim, "the model", n_params=k,
                                               refit=refit) is not None
    return {"case": case.name, "n": n_sim, "noise_source": ne.source, "model": " + ".join(
        (dx.explaining.effect,) if dx.explaining else ("baseline",)), **counts}


def _blind_case(item: str):
    """The case ``SEED:INDEX`` of :mod:`blind_study` as a :class:`validation.Case` (the data the diagnosis sees)."""
    from pathlib import Path

    import blind_study

    seed, index = (int(x) for x in item.split(":"))
    c = blind_study.draw(index, seed)
    return validation.Case(name=f"blind {seed}:{index}", path=Path("."), model=c.model, measurements=c.measurements,
                           contact=c.contact, fit=c.fit)


def upper95(k: int, n: int) -> float:
    """One-sided 95 % Clopper-Pearson upper bound of a rate seen k times in n."""
    return 1.0 if k >= n else float(stats.beta.ppf(0.95, k + 1, n - k))


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200, help="simulations per case (default 200)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", default=",".join(DEFAULT_CASES), help="comma-separated shipped case names")
    ap.add_argument("--blind", default="", help="comma-separated SEED:INDEX cases of blind_study.py (instead of "
                                                "--cases)")
    args = ap.parse_args(argv)
    rng = np.random.default_rng(args.seed)
    t0 = time.perf_counter()
    rows = []
    blind = [item.strip() for item in args.blind.split(",") if item.strip()]
    for item in blind:
        if len(item.split(":")) != 2 or not all(x.strip().isdigit() for x in item.split(":")):
            ap.error(f"--blind: {item!r} is not SEED:INDEX (two integers, e.g. 18:41)")
    cases = [_blind_case(item) for item in blind] if blind else \
        [validation.load_case(name.strip()) for name in args.cases.split(",")]
    for case in cases:
        rows.append(simulate(case, args.n, rng))
    print(f"{'case':<26}{'model':<20}{'noise':<18}{'n':>5}{'pattern':>9}{'(95% up)':>9}{'groups':>8}{'runs':>7}"
          f"{'trends':>8}{'LOF':>7}{'either':>8}{'rows':>7}{'family':>8}")
    tot = {k: 0 for k in ("pattern", "lack_of_fit", "either", "outliers", "localized", "n")}
    for r in rows:
        n = r["n"]
        print(f"{r['case']:<26}{r['model']:<20}{r['noise_source']:<18}{n:>5}{100 * r['pattern'] / n:>8.1f}%"
              f"{100 * upper95(r['pattern'], n):>8.1f}%{100 * r['groups'] / n:>7.1f}%{100 * r['runs'] / n:>6.1f}%"
              f"{100 * r['trends'] / n:>7.1f}%{100 * r['lack_of_fit'] / n:>6.1f}%{100 * r['either'] / n:>7.1f}%"
              f"{100 * r['outliers'] / n:>6.1f}%{100 * r['localized'] / n:>7.1f}%")
        for k in tot:
            tot[k] += r[k]
    n = tot["n"]
    print(f"{'all':<64}{n:>5}{100 * tot['pattern'] / n:>8.1f}%{100 * upper95(tot['pattern'], n):>8.1f}%"
          f"{'':>22}{100 * tot['lack_of_fit'] / n:>7.1f}%{100 * tot['either'] / n:>7.1f}%"
          f"{100 * tot['outliers'] / n:>6.1f}% ({100 * upper95(tot['outliers'], n):.1f}% up)"
          f"{100 * tot['localized'] / n:>7.1f}% ({100 * upper95(tot['localized'], n):.1f}% up)")
    print(f"({time.perf_counter() - t0:.0f} s; pattern alarms per case must stay at or below 2 %; rows named as "
          f"outlying: nominal {100 * ALPHA:g} % per case; a misfit placed in one family of rows: at most "
          f"{100 * LOCALIZE_ALPHA:g} % without the refit of the parameters to the other rows, "
          f"{200 * LOCALIZE_ALPHA:g} % with it)")


if __name__ == "__main__":
    main()
