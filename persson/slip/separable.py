"""Least squares for curve laws whose parameters separate: some enter linearly, the rest nonlinearly.

Most friction-speed laws are linear in their levels (mu0, mu_c, mu_s, beta, b0, b1, ...) once their speed scales and
shape exponents are known. :func:`fit_separable` uses that (variable projection, Golub & Pereyra 1973): over a grid
of the nonlinear parameters it solves the linear ones exactly and keeps the best few points, which are then refined
together by bounded nonlinear least squares. The grid makes the fit global (no starting point to guess) and the
refinement makes it exact; the covariance is the Gauss-Newton one, :math:`s^2 (J^T J)^{-1}` with
:math:`s^2 = \\mathrm{SSE}/(n - k)` (or 1 when the standard uncertainties of mu are given), as ``curve_fit`` reports it.

The result is the dictionary of fields of :class:`persson.slip.FitResult`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from frictioncite import doi

from .._checks import number
from ..errors import AccuracyWarning, InputError
from .references import GOLUB_PEREYRA_1973

__all__ = ["Law", "fit_separable"]


@dataclass(frozen=True)
class Law:
    """A curve law split into linear and nonlinear parameters.

    Attributes
    ----------
    name : str
        The law's name (``"piarc"``, ``"gompertz"``, ...).
    func : callable
        ``func(*xs, *params)``: the law at the covariates ``xs`` (speed, and texture depth, BPN, ... where the law
        has them).
    names : tuple of str
        Parameter names in the order of ``func``.
    bounds : dict
        name -> (low, high); infinite bounds allowed.
    linear : tuple of str
        Parameters that enter linearly: :math:`f = \\sum_j p_j\\, g_j(x; \\theta)`.
    columns : callable
        ``columns(xs, theta)`` -> list of the functions :math:`g_j` (one per name in ``linear``); ``theta`` maps each
        nonlinear name to a float (refinement: each column then broadcasts to ``(n,)``) or to an array of shape
        ``(G, 1)`` (grid: each column broadcasts to ``(G, n)``).
    grid : callable
        ``grid(xs)`` -> dict nonlinear name -> 1D array, all of one length G: the candidate values.
    citations : tuple of str
    """

    name: str
    func: Callable
    names: tuple
    bounds: dict
    linear: tuple
    columns: Callable
    grid: Callable
    citations: tuple = field(default=())

    @property
    def nonlinear(self) -> tuple:
        """The parameters that enter nonlinearly."""
        return tuple(n for n in self.names if n not in self.linear)


@doi(GOLUB_PEREYRA_1973)
def fit_separable(law: Law, xs: tuple, y: np.ndarray, sigma: np.ndarray | None, *, fixed: dict | None = None,
                  starts: list | None = None, x=None, keep: int = 2, tol: float = 1e-12) -> dict:
    """Fit ``law`` to ``y`` at the covariates ``xs``: grid over the nonlinear parameters, refine all.

    Parameters
    ----------
    law : Law
    xs : tuple of ndarray
        The covariates, each of the length of ``y`` (speed first).
    y : ndarray
        Friction coefficients.
    sigma : ndarray or None
        Standard uncertainties of ``y`` (absolute); None: unknown, estimated from the residuals.
    fixed : dict, optional
        Parameters held at given values.
    starts : list of dict, optional
        Extra starting points for the refinement (values by name; missing names from the best grid point).
    x : ndarray, optional
        What the result stores as its ``x`` (default ``xs[0]``).
    keep : int
        Number of best grid points refined.
    tol : float
        ``ftol``, ``xtol`` and ``gtol`` of the refinement.

    Returns
    -------
    dict
        The fields of :class:`persson.slip.FitResult`.

    Raises
    ------
    InputError
        Unknown or all-fixed parameters, fewer points than free parameters, or no grid point with a finite misfit.
    """
    names = law.names
    fixed = _fixed(law, fixed)
    free = [n for n in names if n not in fixed]
    if not free:
        raise InputError(f"fixed: every parameter of {law.name} is fixed; nothing to fit")
    n = y.size
    if n <= len(free):
        raise InputError(f"speed, mu: {n} points cannot determine {len(free)} free parameters of {law.name} "
                         f"({', '.join(free)}); give more than {len(free)} rows")
    w = np.ones(n) if sigma is None else 1.0 / sigma
    lo = np.array([law.bounds[k][0] for k in free], dtype=float)
    hi = np.array([law.bounds[k][1] for k in free], dtype=float)
    idx = [names.index(k) for k in free]

    def full(p):
        v = np.array([fixed.get(k, np.nan) for k in names], dtype=float)
        v[idx] = p
        return v

    def resid(p):
        return (law.func(*xs, *full(p)) - y) * w

    free_nl = [k for k in law.nonlinear if k not in fixed]
    free_lin = [k for k in law.linear if k not in fixed]
    candidates = _grid_starts(law, xs, y, w, fixed, keep)
    for s in starts or ():
        base = dict(candidates[0]) if candidates else {}
        base.update({k: number(v, f"p0[{k!r}]") for k, v in s.items()})
        base["_sse"] = 0.0  # a given start is always refined
        candidates.insert(0, base)
    if not candidates:
        raise InputError(f"speed, mu: {law.name} has no finite value anywhere on its starting grid for these data")
    best_p, best_cost, converged = None, np.inf, True
    for cand in candidates:
        if best_p is not None and cand["_sse"] > 2.0 * best_cost:
            continue  # its grid point is twice as bad as the optimum already found: not worth a refinement
        p, ok = _project(law, xs, y, w, fixed, free, free_nl, free_lin, cand, tol)
        if p is None:
            continue
        with np.errstate(over="ignore", invalid="ignore"):
            r = resid(p)
        cost = float(r @ r)
        if np.isfinite(cost) and cost < best_cost * (1 - 1e-12):
            best_p, best_cost, converged = p, cost, ok
    if best_p is None:
        raise InputError(f"speed, mu: the {law.name} fit did not converge from any starting point")
    p = best_p
    values = full(p)
    r = y - law.func(*xs, *values)
    sse = float(r @ r)
    chi2 = float(((r * w) @ (r * w)))
    dof = n - len(free)
    notes = []
    if not converged:
        notes.append(f"{law.name}: the refinement stopped at its step limit in a flat valley of the misfit; the "
                     "parameters are poorly determined by these data")
    cov = _covariance(_jacobian(resid, p, lo, hi), chi2 / dof if sigma is None else 1.0)
    if not np.all(np.isfinite(cov)):
        msg = (f"{law.name}: the data do not determine every parameter (the Jacobian is rank deficient); the "
               "uncertainties of the undetermined ones are infinite")
        notes.append(msg)
        warnings.warn(msg, AccuracyWarning, stacklevel=3)
    notes += _correlated(law.name, free, cov)
    C = np.zeros((len(names), len(names)))
    C[np.ix_(idx, idx)] = cov
    stderr = np.sqrt(np.clip(np.diag(C), 0.0, None))
    at_bound = [free[i] for i in range(len(free)) if np.isclose(p[i], lo[i]) or np.isclose(p[i], hi[i])]
    if at_bound:
        notes.append(f"{law.name}: parameter(s) {at_bound} at their bound; the uncertainties there are not "
                     "meaningful")
    return dict(law=law.name, names=tuple(names), values=values, stderr=stderr, covariance=C,
                fixed=tuple(k for k in names if k in fixed), x=xs[0] if x is None else x, y=y, sigma=sigma,
                rms=math.sqrt(sse / n), dof=int(dof), notes=tuple(notes),
                citations=tuple(law.citations) + (GOLUB_PEREYRA_1973,), func=law.func)


# =========================================================================================================
# helpers
# =========================================================================================================
def _fixed(law: Law, fixed: dict | None) -> dict:
    fixed = dict(fixed or {})
    unknown = sorted(set(fixed) - set(law.names))
    if unknown:
        raise InputError(f"fixed: unknown parameter(s) {unknown} of {law.name} (has {list(law.names)})")
    return {k: number(v, f"fixed[{k!r}]") for k, v in fixed.items()}


def _grid_starts(law: Law, xs, y, w, fixed: dict, keep: int) -> list[dict]:
    """The ``keep`` best points of the grid, each with its linear parameters solved exactly."""
    grid = {k: np.asarray(v, dtype=float) for k, v in law.grid(xs).items()}
    G = len(next(iter(grid.values()))) if grid else 1
    theta = {k: np.full((G, 1), fixed[k]) if k in fixed else np.asarray(grid[k], dtype=float).reshape(G, 1)
             for k in law.nonlinear}
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        cols = [np.broadcast_to(c, (G, y.size)) for c in law.columns(xs, theta)]
    target = np.broadcast_to(y, (G, y.size)).copy()
    free_cols, free_lin = [], []
    for name, c in zip(law.linear, cols):
        if name in fixed:
            target -= fixed[name] * c
        else:
            free_cols.append(c)
            free_lin.append(name)
    ok = np.all(np.isfinite(target), axis=1)
    if free_cols:
        B = np.stack(free_cols, axis=2) * w[None, :, None]
        ok &= np.all(np.isfinite(B), axis=(1, 2))
        B = np.where(ok[:, None, None], B, 0.0)
        t = np.where(ok[:, None], target * w, 0.0)
        with np.errstate(all="ignore"):
            # normal equations, columns scaled to unit norm and a whisker of ridge: a grid needs no more accuracy
            norm = np.sqrt(np.sum(B * B, axis=1))
            norm = np.where(norm > 0, norm, 1.0)
            Bs = B / norm[:, None, :]
            A = np.swapaxes(Bs, 1, 2) @ Bs + 1e-12 * np.eye(Bs.shape[2])
            coef = np.linalg.solve(A, (np.swapaxes(Bs, 1, 2) @ t[:, :, None]))[:, :, 0] / norm
            r = t - (B @ coef[:, :, None])[:, :, 0]
        ok &= np.all(np.isfinite(coef), axis=1)
    else:
        coef = np.zeros((G, 0))
        r = np.where(ok[:, None], target * w, 0.0)
    sse = np.where(ok, np.sum(r * r, axis=1), np.inf)
    order = np.argsort(sse)
    out, seen = [], []
    for g in order:
        if not np.isfinite(sse[g]) or len(out) >= keep or (out and sse[g] > 4.0 * seen[0]):
            break  # a point four times worse than the best is not worth refining
        if any(abs(sse[g] - s) <= 1e-9 * max(s, 1e-300) for s in seen):
            continue
        seen.append(sse[g])
        start = {k: float(v[g, 0]) for k, v in theta.items() if k not in fixed}
        start.update({k: float(coef[g, j]) for j, k in enumerate(free_lin)})
        start["_sse"] = float(sse[g])
        out.append(start)
    return out


def _project(law: Law, xs, y, w, fixed, free, free_nl, free_lin, start: dict, tol: float):
    """Variable projection: minimise over the free nonlinear parameters with the free linear ones solved exactly.

    Returns the free parameter vector (in the order of ``free``; None when the refinement fails) and whether the
    refinement converged within its step limit.
    """
    from scipy.optimize import least_squares

    lo = np.array([law.bounds[k][0] for k in free_nl], dtype=float)
    hi = np.array([law.bounds[k][1] for k in free_nl], dtype=float)
    lin_lo = np.array([law.bounds[k][0] for k in free_lin], dtype=float)
    lin_hi = np.array([law.bounds[k][1] for k in free_lin], dtype=float)

    slots = [(k, None if k in fixed else free_nl.index(k)) for k in law.nonlinear]
    held = [(j, fixed[k]) for j, k in enumerate(law.linear) if k in fixed]
    solved = [j for j, k in enumerate(law.linear) if k not in fixed]
    yw = y * w

    def solve(theta):
        cols = law.columns(xs, {k: fixed[k] if i is None else float(theta[i]) for k, i in slots})
        target = yw.copy()
        for j, v in held:
            target -= v * w * cols[j]
        if not solved:
            return np.zeros(0), target
        B = np.empty((y.size, len(solved)))
        for jj, j in enumerate(solved):
            B[:, jj] = cols[j] * w
        if not (np.all(np.isfinite(B)) and np.all(np.isfinite(target))):
            return None, np.full(y.size, 1e150)
        coef = _bounded_lstsq(B, target, lin_lo, lin_hi)
        return coef, target - B @ coef

    theta0 = np.array([start.get(k, 1.0) for k in free_nl], dtype=float)
    if free_nl:
        theta0 = np.clip(theta0, np.nextafter(lo, np.inf), np.nextafter(hi, -np.inf))
        try:
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                res = least_squares(lambda th: solve(th)[1], theta0, jac="2-point", bounds=(lo, hi), method="trf",
                                    x_scale="jac", ftol=tol, xtol=tol, gtol=tol, max_nfev=60 * (len(free_nl) + 1))
        except ValueError:
            return None, False
        theta, ok = res.x, res.status != 0
    else:
        theta, ok = theta0, True
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        coef, r = solve(theta)
    if coef is None or not np.all(np.isfinite(r)):
        return None, False
    values = {**dict(zip(free_nl, theta)), **dict(zip(free_lin, coef))}
    return np.array([values[k] for k in free], dtype=float), ok


def _correlated(name: str, free: list, cov: np.ndarray, limit: float = 0.999) -> list[str]:
    """A note for each pair of parameters correlated beyond ``limit``: there the linearised errors mislead."""
    sd = np.sqrt(np.diag(cov))
    if not np.all(np.isfinite(cov)) or np.any(sd == 0):
        return []
    rho = cov / np.outer(sd, sd)
    pairs = [f"{free[i]}-{free[j]} {rho[i, j]:+.4f}" for i in range(len(free)) for j in range(i + 1, len(free))
             if abs(rho[i, j]) > limit]
    if not pairs:
        return []
    return [f"{name}: constants correlated beyond {limit} ({', '.join(pairs)}): the misfit has long curved valleys "
            "along which the linearised standard errors can understate the scatter"]


def _bounded_lstsq(B: np.ndarray, t: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Least squares of ``B c = t`` with ``lo <= c <= hi``: the worst violator is held at its bound and the rest
    solved again, until none violates (an active set that only grows; exact for one level, and for the two or three
    levels of these laws whenever the bounds that bind are those the unconstrained solution violates most)."""
    m = B.shape[1]
    c = np.zeros(m)
    held = np.zeros(m, dtype=bool)
    for _ in range(m + 1):
        free = ~held
        rhs = t - B[:, held] @ c[held]
        if np.any(free):
            c[free] = _lstsq(B[:, free], rhs)
        over = np.where(free, np.maximum(lo - c, c - hi), 0.0)
        j = int(np.argmax(over))
        if over[j] <= 0:
            break
        c[j] = lo[j] if c[j] < lo[j] else hi[j]
        held[j] = True
    return c


def _lstsq(B: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Least squares of a few columns: normal equations on unit-norm columns (fast), or an SVD when they are nearly
    dependent."""
    if B.shape[1] == 1:
        bb = float(B[:, 0] @ B[:, 0])
        return np.array([float(B[:, 0] @ t) / bb]) if bb > 0 else np.zeros(1)
    norm = np.sqrt(np.einsum("ij,ij->j", B, B))
    if np.all(norm > 0):
        Bs = B / norm
        A = Bs.T @ Bs
        if np.linalg.det(A) > 1e-8:  # the Gram determinant of unit columns: 0 when dependent
            return np.linalg.solve(A, Bs.T @ t) / norm
    return np.linalg.lstsq(B, t, rcond=None)[0]


def _jacobian(resid, p: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Central-difference Jacobian of the weighted residuals (one-sided at a bound)."""
    r0 = resid(p)
    J = np.empty((r0.size, p.size))
    for i in range(p.size):
        h = 1e-6 * max(abs(p[i]), 1e-6)
        up, dn = p.copy(), p.copy()
        up[i] = min(p[i] + h, hi[i])
        dn[i] = max(p[i] - h, lo[i])
        J[:, i] = (resid(up) - resid(dn)) / (up[i] - dn[i])
    return J


def _covariance(J: np.ndarray, scale: float) -> np.ndarray:
    """``scale (J^T J)^-1`` by SVD; directions the data do not determine get infinite variance."""
    _, s, VT = np.linalg.svd(J, full_matrices=False)
    tiny = np.finfo(float).eps * max(J.shape) * (s[0] if s.size else 0.0)
    good = s > tiny
    cov = (VT[good].T / s[good] ** 2) @ VT[good]
    if not np.all(good):
        bad = np.any(np.abs(VT[~good]) > 1e-8, axis=0)
        cov[bad, :] = np.inf
        cov[:, bad] = np.inf
    return cov * scale
