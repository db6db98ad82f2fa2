"""Bounded least-squares refits of effect parameters against measurements (used by diagnose and improve).

Parameters are mapped to ``u`` in [0, 1]: linearly between their bounds, or linearly in log10 for parameters
documented with ``log_scale=True`` (and a positive lower bound). ``scipy.optimize.least_squares`` (trust-region
reflective, bounds [0, 1], two-point finite differences with a step of 5e-3 of the range) minimises the weighted
residuals ``(mu_measured - mu_model) / mu_std`` (weights 1 without ``mu_std``), from the effect's given values and
the best point of a small screening design (a scrambled Halton sequence over the bounds, seeded, so the result is
reproducible). A single parameter is instead scanned on a grid and refined by bounded Brent minimisation
(:meth:`Fitter.scan_1d`), which is robust to small jumps of the response.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from .errors import InputError

__all__ = ["FreeParameter", "ParameterSpace", "free_parameters", "Fitter", "FitResult"]


@dataclass(frozen=True)
class FreeParameter:
    """A parameter varied by a fit.

    Attributes
    ----------
    effect : str
        Effect name ("" for the model's ``gamma``).
    name : str
        Parameter name.
    lo, hi : float
        Bounds.
    log : bool
        Varied in log10.
    unit : str
    """

    effect: str
    name: str
    lo: float
    hi: float
    log: bool
    unit: str = ""

    @property
    def key(self) -> str:
        """``"effect.name"`` (or ``"gamma"``)."""
        return f"{self.effect}.{self.name}" if self.effect else self.name

    def to_u(self, x: float) -> float:
        x = min(max(float(x), self.lo), self.hi)
        if self.log:
            return (math.log10(x) - math.log10(self.lo)) / (math.log10(self.hi) - math.log10(self.lo))
        return (x - self.lo) / (self.hi - self.lo)

    def from_u(self, u: float) -> float:
        u = min(max(float(u), 0.0), 1.0)
        if self.log:
            x = 10.0 ** (math.log10(self.lo) + u * (math.log10(self.hi) - math.log10(self.lo)))
        else:
            x = self.lo + u * (self.hi - self.lo)
        return min(max(x, self.lo), self.hi)


class ParameterSpace:
    """An ordered set of :class:`FreeParameter` and the map u -> model."""

    def __init__(self, params=()):
        self.params = tuple(params)
        keys = [p.key for p in self.params]
        if len(set(keys)) != len(keys):
            raise InputError(f"parameters listed twice: {keys}")

    def __len__(self) -> int:
        return len(self.params)

    def __add__(self, other: "ParameterSpace") -> "ParameterSpace":
        return ParameterSpace(self.params + other.params)

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(p.key for p in self.params)

    def values_from_u(self, u) -> dict[str, float]:
        return {p.key: p.from_u(x) for p, x in zip(self.params, np.atleast_1d(u))}

    def apply(self, model, u):
        """``model`` with the parameters set from ``u`` (effect order kept)."""
        if not self.params:
            return model
        vals = self.values_from_u(u)
        changes: dict[str, dict] = {}
        gamma = None
        for p in self.params:
            if p.effect:
                changes.setdefault(p.effect, {})[p.name] = vals[p.key]
            else:
                gamma = vals[p.key]
        effects = tuple(e.with_parameters(**changes[e.name]) if e.name in changes else e for e in model.effects)
        missing = set(changes) - {e.name for e in model.effects}
        if missing:
            raise InputError(f"parameters of effects not in the model: {sorted(missing)}")
        kw = {"effects": effects}
        if gamma is not None:
            kw["gamma"] = gamma
        return model.replace(**kw)

    def u_of(self, model) -> np.ndarray:
        """Current values of the parameters in ``model`` as u."""
        out = []
        for p in self.params:
            x = getattr(model.effect(p.effect), p.name) if p.effect else model.gamma
            out.append(p.to_u(x))
        return np.asarray(out, dtype=float)

    def values(self, model) -> dict[str, float]:
        """Current values of the parameters in ``model``."""
        return {p.key: float(getattr(model.effect(p.effect), p.name) if p.effect else model.gamma)
                for p in self.params}


def free_parameters(effect, names=None, release: bool = False) -> list[FreeParameter]:
    """The parameters of ``effect`` a refit varies.

    Rule (when ``names`` is None): every documented parameter (``effect.parameters``) with a numeric value and
    finite bounds lo < hi, except those whose documented default lies on a bound -- such a default is a switch
    or an "automatic" sentinel (e.g. ``Microtexture.hurst = 0`` meaning "fitted", ``Wet.seal_fraction = 0``
    meaning "off") and is held fixed, unless ``release`` is True (used when the effect has no signature at all
    at its given values). ``names`` lists the parameters to vary explicitly.
    """
    specs = {p.name: p for p in getattr(effect, "parameters", ())}
    if names is not None:
        unknown = [n for n in names if n not in specs]
        if unknown:
            raise InputError(f"{effect.name}: no documented parameter(s) {unknown}; documented: {sorted(specs)}")
        chosen = [specs[n] for n in names]
    else:
        chosen = list(specs.values())
    out = []
    for p in chosen:
        v = getattr(effect, p.name, None)
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
            continue
        try:
            lo, hi = (float(b) for b in p.bounds)
        except (TypeError, ValueError):
            continue
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            continue
        if names is None and not release:
            d = float(p.default)
            if abs(d - lo) <= 1e-12 * max(1.0, abs(lo)) or abs(d - hi) <= 1e-12 * max(1.0, abs(hi)):
                continue
        log = bool(getattr(p, "log_scale", False)) and lo > 0
        out.append(FreeParameter(effect=effect.name, name=p.name, lo=lo, hi=hi, log=log, unit=p.unit))
    return out


@dataclass(frozen=True, eq=False)
class FitResult:
    """Outcome of a :class:`Fitter` run."""

    u: np.ndarray
    model: object
    mu: np.ndarray
    chi2: float
    jac: np.ndarray | None
    n_evals: int
    notes: tuple = ()


class _Budget(Exception):
    pass


class Fitter:
    """Weighted least squares of ``predictor.predict(space.apply(model, u))`` against ``y``.

    Parameters
    ----------
    predictor : validation.predict.Predictor
    y : ndarray
        Measured mu.
    w : ndarray
        Weights 1 / mu_std (ones without mu_std).
    model : persson.Model
        The model whose parameters ``space`` varies.
    space : ParameterSpace
    max_evals : int
        Budget of model evaluations (the best point seen is returned when it runs out).
    """

    def __init__(self, predictor, y, w, model, space: ParameterSpace, max_evals: int = 200):
        self.predictor = predictor
        self.y = np.asarray(y, dtype=float)
        self.w = np.asarray(w, dtype=float)
        self.model = model
        self.space = space
        self.max_evals = int(max_evals)
        self.n_evals = 0
        self._cache: dict = {}
        self._best = (math.inf, None)
        self.errors: dict[str, None] = {}
        self.notes: dict[str, None] = {}
        self._penalty = (np.abs(self.y) + 10.0) * self.w * 10.0

    def mu(self, u):
        """Predicted mu at ``u`` (None when the model failed there)."""
        u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
        key = tuple(np.round(u, 12))
        if key in self._cache:
            return self._cache[key]
        if self.n_evals >= self.max_evals:
            raise _Budget()
        self.n_evals += 1
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                pred = self.predictor.predict(self.space.apply(self.model, u))
            mu = pred.mu
            for w in caught:
                self.notes[f"{w.category.__name__}: {w.message}"] = None
            if not np.all(np.isfinite(mu)):
                raise InputError("non-finite prediction")
        except _Budget:
            raise
        except Exception as exc:  # noqa: BLE001  (an effect may fail at some parameters; the fit avoids them)
            self.errors[f"{type(exc).__name__}: {exc}"] = None
            mu = None
        self._cache[key] = mu
        if mu is not None:
            c = float(np.sum(((self.y - mu) * self.w) ** 2))
            if c < self._best[0]:
                self._best = (c, np.array(u))
        return mu

    def chi2(self, u) -> float:
        mu = self.mu(u)
        return math.inf if mu is None else float(np.sum(((self.y - mu) * self.w) ** 2))

    def resid(self, u):
        mu = self.mu(u)
        if mu is None:
            return self._penalty
        return (self.y - mu) * self.w

    def max_change(self, f0) -> float:
        """Largest |mu - f0| over every prediction evaluated so far."""
        out = 0.0
        for mu in self._cache.values():
            if mu is not None:
                out = max(out, float(np.max(np.abs(mu - f0))))
        return out

    def screen(self, points) -> list[tuple[float, np.ndarray]]:
        """chi2 at each point (within the budget), sorted best first."""
        out = []
        for p in points:
            try:
                out.append((self.chi2(p), np.asarray(p, dtype=float)))
            except _Budget:
                break
        return sorted(out, key=lambda t: t[0])

    def run(self, starts, max_nfev: int | None = None) -> FitResult:
        """Least squares from each start; the best result (or best point seen if the budget runs out)."""
        k = len(self.space)
        jac = None
        best_jac = None
        if k == 0:
            self.mu(np.zeros(0))
        for x0 in starts:
            x0 = np.clip(np.asarray(x0, dtype=float), 0.0, 1.0)
            if k == 0:
                break
            try:
                res = optimize.least_squares(self.resid, x0, bounds=(np.zeros(k), np.ones(k)), method="trf",
                                             diff_step=5e-3, x_scale=1.0, ftol=1e-4, xtol=1e-3, gtol=1e-8,
                                             max_nfev=max_nfev or 30 * (k + 1))
                jac = res.jac
                c = self.chi2(res.x)
                if c <= self._best[0] + 1e-12 * max(1.0, c):
                    best_jac = jac
            except _Budget:
                self.notes["fit stopped at its evaluation budget"] = None
                break
        c, u = self._best
        if u is None:
            raise InputError("the model failed at every parameter value tried: " + "; ".join(list(self.errors)[:3]))
        mu = self._cache[tuple(np.round(np.clip(u, 0, 1), 12))]
        return FitResult(u=u, model=self.space.apply(self.model, u), mu=mu, chi2=c, jac=best_jac,
                         n_evals=self.n_evals, notes=tuple(self.notes))


    def scan_1d(self, u_given: float, n_grid: int = 13) -> FitResult:
        """One parameter: a grid of ``n_grid`` interior points plus the given value, then bounded Brent
        minimisation (``scipy.optimize.minimize_scalar``) between the best point's neighbours.

        Robust where the response is piecewise smooth with small jumps (e.g. a parameter that moves a scale
        across the solver's q grid), where finite-difference gradients mislead least squares.
        """
        if len(self.space) != 1:
            raise InputError("scan_1d needs exactly one parameter")
        grid = (np.arange(n_grid) + 0.5) / n_grid
        pts = np.concatenate([[float(u_given)], grid])
        vals = []
        for x in pts:
            try:
                vals.append(self.chi2([x]))
            except _Budget:
                vals.append(math.inf)
                break
        i = int(np.argmin(vals))
        x0 = float(pts[i])
        h = 1.0 / n_grid
        lo, hi = max(0.0, x0 - h), min(1.0, x0 + h)

        def f(x):
            return self.chi2([x])

        try:
            optimize.minimize_scalar(f, bounds=(lo, hi), method="bounded", options={"xatol": 2e-3, "maxiter": 14})
        except _Budget:
            self.notes["fit stopped at its evaluation budget"] = None
        c, u = self._best
        if u is None:
            raise InputError("the model failed at every parameter value tried: " + "; ".join(list(self.errors)[:3]))
        mu = self._cache[tuple(np.round(np.clip(u, 0, 1), 12))]
        return FitResult(u=u, model=self.space.apply(self.model, u), mu=mu, chi2=c, jac=None,
                         n_evals=self.n_evals, notes=tuple(self.notes))


def halton(k: int, n: int, seed: int = 0) -> np.ndarray:
    """``n`` scrambled Halton points in [0, 1]^k (reproducible for a given seed), kept off the bounds."""
    if k == 0 or n <= 0:
        return np.zeros((0, k))
    from scipy.stats import qmc

    pts = qmc.Halton(d=k, scramble=True, seed=seed).random(n)
    return 0.02 + 0.96 * pts
