"""Least-squares fits of curve laws with parameter covariance: :class:`FitResult` and the shared fitting helper."""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from .._checks import finite_array, number
from ..errors import AccuracyWarning, InputError

__all__ = ["FitResult"]


# =========================================================================================================
# Fit results
# =========================================================================================================
class NamedParameters:
    """Access by name to the ``names``, ``values`` and ``stderr`` of a fit result (its ``_index`` names the error)."""

    def __getitem__(self, name: str) -> float:
        return float(self.values[self._index(name)])

    def std(self, name: str) -> float:
        """Standard uncertainty of the parameter ``name``."""
        return float(self.stderr[self._index(name)])

    @property
    def params(self) -> dict[str, float]:
        """Parameter values by name."""
        return {n: float(v) for n, v in zip(self.names, self.values)}

    @property
    def uncertainties(self) -> dict[str, float]:
        """Standard uncertainties by name."""
        return {n: float(v) for n, v in zip(self.names, self.stderr)}


@dataclass(frozen=True, eq=False)
class FitResult(NamedParameters):
    """A fitted curve law: parameters, standard uncertainties, covariance.

    Attributes
    ----------
    law : str
        Name of the law (``"magic_formula"``, ``"magic_formula_simple"``, ``"piarc"``, ``"do_marsac_mosset"``,
        ``"rado"``).
    names : tuple of str
        Parameter names, in the order of ``values``.
    values, stderr : ndarray
        Best-fit values and standard uncertainties (0 for parameters held fixed).
    covariance : ndarray
        Covariance of all parameters (rows/columns of fixed ones are 0).
    fixed : tuple of str
        Names of the parameters held fixed.
    x, y : ndarray
        The data (slip or speed, mu).
    sigma : ndarray or None
        Standard uncertainties of ``y`` given to the fit (absolute).
    rms : float
        Root-mean-square residual.
    dof : int
        Degrees of freedom (points - free parameters).
    notes : tuple of str
    citations : tuple of str
    """

    law: str
    names: tuple
    values: np.ndarray
    stderr: np.ndarray
    covariance: np.ndarray
    fixed: tuple
    x: np.ndarray
    y: np.ndarray
    sigma: np.ndarray | None
    rms: float
    dof: int
    notes: tuple = ()
    citations: tuple = ()
    func: object = field(default=None, repr=False)

    def __call__(self, x):
        """The fitted law at ``x``."""
        return self.func(np.asarray(x, dtype=float), *self.values)

    def propagate(self, quantity) -> tuple[float, float]:
        """Value and standard uncertainty of ``quantity(values)`` (a scalar function of the parameter vector),
        by linear propagation of the covariance (central differences)."""
        return _propagate(quantity, self.values, self.covariance)

    def _index(self, name: str) -> int:
        try:
            return self.names.index(name)
        except ValueError:
            raise InputError(f"parameter: {name!r} is not a parameter of {self.law} (has {list(self.names)})") from None


def _propagate(quantity, values, cov) -> tuple[float, float]:
    v0 = float(quantity(values))
    free = np.flatnonzero(np.diag(cov) > 0)
    if free.size == 0:
        return v0, 0.0
    grad = np.zeros(values.size)
    for i in free:
        h = 1e-6 * max(abs(values[i]), math.sqrt(cov[i, i]) * 1e-2, 1e-12)
        up = values.copy()
        dn = values.copy()
        up[i] += h
        dn[i] -= h
        grad[i] = (float(quantity(up)) - float(quantity(dn))) / (2 * h)
    var = float(grad @ cov @ grad)
    return v0, math.sqrt(max(var, 0.0))


def _fit(law, func, names, bounds, x, y, sigma, fixed, starts, citations, *, tol: float = 1e-14,
         maxfev: int = 20000, agree: int | None = None) -> dict:
    """Multi-start curve_fit of ``func(x, *params)`` with some parameters fixed; the pieces of a FitResult.

    ``agree``: stop once that many starts have reached the best residual found (to 1e-9), or one has fitted
    exactly (the starts are then expected best first, e.g. screened by their residual)."""
    from scipy.optimize import OptimizeWarning, curve_fit

    fixed = dict(fixed or {})
    unknown = sorted(set(fixed) - set(names))
    if unknown:
        raise InputError(f"fixed: unknown parameter(s) {unknown} of {law} (has {list(names)})")
    for k, v in fixed.items():
        fixed[k] = number(v, f"fixed[{k!r}]")
    free = [n for n in names if n not in fixed]
    if not free:
        raise InputError(f"fixed: every parameter of {law} is fixed; nothing to fit")
    if x.size <= len(free):
        raise InputError(f"x, mu: {x.size} points cannot determine {len(free)} free parameters of {law}")
    idx = [names.index(n) for n in free]
    lo = np.array([bounds[n][0] for n in free], dtype=float)
    hi = np.array([bounds[n][1] for n in free], dtype=float)

    def full(p):
        v = np.array([fixed.get(n, np.nan) for n in names], dtype=float)
        v[idx] = p
        return v

    def f(xx, *p):
        return func(xx, *full(np.asarray(p)))

    best = None
    n_best = 0
    scale = float(y @ y) if sigma is None else float((y / sigma) @ (y / sigma))
    notes = []
    for start in starts:
        p0 = np.array([start.get(n, 1.0) for n in free], dtype=float)
        p0 = np.clip(p0, lo + 1e-9 * (np.abs(lo) + 1), hi - 1e-9 * (np.abs(hi) + 1))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OptimizeWarning)
            try:
                p, cov = curve_fit(f, x, y, p0=p0, sigma=sigma, absolute_sigma=sigma is not None,
                                   bounds=(lo, hi), maxfev=maxfev, method="trf", x_scale="jac",
                                   ftol=tol, xtol=tol, gtol=tol)
            except (RuntimeError, ValueError):
                continue
        r = y - f(x, *p)
        w = r if sigma is None else r / sigma
        cost = float(w @ w)
        if best is None or cost < best[0] * (1 - 1e-9):
            n_best = 1                      # a new best
        elif cost <= best[0] * (1 + 1e-9):
            n_best += 1                     # the best reached again from another start
        if best is None or cost < best[0] * (1 - 1e-12):
            best = (cost, p, cov)
        if agree and (n_best >= agree or best[0] <= 1e-28 * scale):
            break
    if best is None:
        raise InputError(f"x, mu: the {law} fit did not converge from any starting point")
    cost, p, cov = best
    values = full(p)
    n_all = len(names)
    C = np.zeros((n_all, n_all))
    if not np.all(np.isfinite(cov)):
        msg = f"{law}: the parameter covariance could not be estimated (parameters not all determined by the data)"
        notes.append(msg)
        warnings.warn(msg, AccuracyWarning, stacklevel=3)
        cov = np.where(np.isfinite(cov), cov, np.inf)
    C[np.ix_(idx, idx)] = cov
    stderr = np.sqrt(np.clip(np.diag(C), 0.0, None))
    at_bound = [free[i] for i in range(len(free)) if np.isclose(p[i], lo[i]) or np.isclose(p[i], hi[i])]
    if at_bound:
        msg = f"{law}: parameter(s) {at_bound} at their bound; the uncertainties there are not meaningful"
        notes.append(msg)
    resid = y - func(x, *values)
    return dict(law=law, names=tuple(names), values=values, stderr=stderr, covariance=C,
                fixed=tuple(n for n in names if n in fixed), x=x, y=y, sigma=sigma,
                rms=float(np.sqrt(np.mean(resid**2))), dof=int(x.size - len(free)), notes=tuple(notes),
                citations=tuple(citations), func=func)


# =========================================================================================================
# helpers
# =========================================================================================================
def _xy(x, y, sigma, xname: str):
    x = finite_array(x, xname).ravel()
    y = finite_array(y, "mu").ravel()
    if x.size != y.size:
        raise InputError(f"{xname}, mu: expected equal lengths, got {x.size} and {y.size}")
    sig = None
    if sigma is not None:
        sig = np.broadcast_to(finite_array(sigma, "sigma").ravel(), y.shape).astype(float) if np.size(sigma) in (1, y.size) \
            else None
        if sig is None:
            raise InputError(f"sigma: expected one value or {y.size} values")
        if np.any(sig <= 0):
            raise InputError("sigma: expected standard uncertainties > 0")
    return x, y, sig
