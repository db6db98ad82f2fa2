"""Bounded least squares of model parameters against measurements: the parameter space and the fitter.

Parameters are mapped to ``u`` in [0, 1]: linearly between their bounds, or linearly in log10 for parameters
documented with ``log_scale=True`` (and a positive lower bound). :class:`Fitter` evaluates the weighted residuals
``(mu_measured - mu_model) / mu_std`` (weights 1 without ``mu_std``) at any ``u``, caches every prediction, and
runs ``scipy.optimize.least_squares`` (trust-region reflective, bounds [0, 1], two-point finite differences) from
a start, optionally with some coordinates held fixed (for profile likelihoods); :mod:`validation.refit` builds the
multi-start global fit and the uncertainties on it. Besides effect parameters and ``gamma``, a space may hold the
brush model's contact parameters (:data:`CONTACT_PARAMETERS`, keys ``"contact.<name>"``).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from . import distributions
from .errors import InputError

__all__ = ["FreeParameter", "ParameterSpace", "free_parameters", "release_placeholders", "contact_parameters",
           "contact_value", "Fitter", "BudgetExhausted", "halton", "CONTACT", "CONTACT_PARAMETERS"]

#: Pseudo-effect name of the brush model's contact parameters (``"contact.stiffness"`` ...).
CONTACT = "contact"


@dataclass(frozen=True)
class FreeParameter:
    """A parameter varied by a fit.

    Attributes
    ----------
    effect : str
        Effect name ("" for the model's ``gamma``, ``"contact"`` for the brush model's contact).
    name : str
        Parameter name.
    lo, hi : float
        Bounds of the search.
    log : bool
        Varied in log10.
    unit : str
    physical_limits : tuple of float
        Bounds that are physical limits (an optimum there is legitimate); the others are search bounds.
    plausible : (float, float), callable or None
        The documented plausible range (see :class:`persson.effects.Parameter`); None: the bounds.
    """

    effect: str
    name: str
    lo: float
    hi: float
    log: bool
    unit: str = ""
    physical_limits: tuple = ()
    plausible: object = None

    @property
    def key(self) -> str:
        """``"effect.name"`` (or ``"gamma"``)."""
        return f"{self.effect}.{self.name}" if self.effect else self.name

    def to_u(self, x: float) -> float:
        """The coordinate u in [0, 1] of the value ``x`` (clipped to the bounds; linear in log10 when ``log``)."""
        x = min(max(float(x), self.lo), self.hi)
        if self.log:
            return (math.log10(x) - math.log10(self.lo)) / (math.log10(self.hi) - math.log10(self.lo))
        return (x - self.lo) / (self.hi - self.lo)

    def from_u(self, u: float) -> float:
        """The value at the coordinate ``u`` (clipped to [0, 1]; linear in log10 when ``log``), within the bounds."""
        u = min(max(float(u), 0.0), 1.0)
        if self.log:
            x = 10.0 ** (math.log10(self.lo) + u * (math.log10(self.hi) - math.log10(self.lo)))
        else:
            x = self.lo + u * (self.hi - self.lo)
        return min(max(x, self.lo), self.hi)

    def dx_du(self, x: float) -> float:
        """Derivative of the value with respect to u at value ``x``."""
        if self.log:
            return float(x) * math.log(10.0) * (math.log10(self.hi) - math.log10(self.lo))
        return self.hi - self.lo

    def middle(self, lo: float | None = None, hi: float | None = None) -> float:
        """The middle of ``[lo, hi]`` (default: the search bounds): geometric for a parameter varied in log10,
        arithmetic otherwise -- the point of the unit box halfway between them."""
        lo = self.lo if lo is None else float(lo)
        hi = self.hi if hi is None else float(hi)
        return math.sqrt(lo * hi) if self.log else 0.5 * (lo + hi)

    def plausible_range(self, data_range=None) -> tuple[float, float]:
        """The plausible (lo, hi) (callables evaluated on ``data_range``); the bounds when none is declared."""
        p = self.plausible
        if p is None or (callable(p) and data_range is None):
            return self.lo, self.hi
        lo, hi = p(data_range) if callable(p) else p
        return float(lo), float(hi)

    def is_physical_limit(self, x: float) -> bool:
        """Whether ``x`` sits on one of the ``physical_limits`` (within 1e-9, relative for limits beyond 1 in size)."""
        return any(abs(float(x) - float(b)) <= 1e-9 * max(1.0, abs(float(b))) for b in self.physical_limits)


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
        """Keys of the parameters (``"effect.name"``, ``"gamma"``, ``"contact.<name>"``), in order."""
        return tuple(p.key for p in self.params)

    def values_from_u(self, u) -> dict[str, float]:
        """``key -> value`` of every parameter at the point ``u`` of the unit box (one coordinate per parameter)."""
        return {p.key: p.from_u(x) for p, x in zip(self.params, np.atleast_1d(u))}

    def apply(self, model, u):
        """``model`` with the parameters set from ``u`` (effect order kept)."""
        if not self.params:
            return model
        vals = self.values_from_u(u)
        changes: dict[str, dict] = {}
        gamma = None
        for p in self.params:
            if p.effect == CONTACT:
                continue
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

    @property
    def has_contact(self) -> bool:
        """Whether some parameters belong to the brush model's contact."""
        return any(p.effect == CONTACT for p in self.params)

    def apply_contact(self, contact, u):
        """``contact`` with its ``contact.*`` parameters set from ``u`` (``contact`` itself when there are none)."""
        if not self.has_contact:
            return contact
        from persson.slip import Contact

        vals = self.values_from_u(u)
        kw = dict(length=contact.length, width=contact.width, stiffness=contact.stiffness,
                  pressure_distribution=contact.pressure_distribution, n_points=contact.n_points)
        for p in self.params:
            if p.effect == CONTACT:
                if p.name == "sakai_n":
                    kw["pressure_distribution"] = {"sakai_n": vals[p.key]}
                else:
                    kw[p.name] = vals[p.key]
        return Contact(**kw)

    def u_of(self, model, contact=None) -> np.ndarray:
        """Current values of the parameters in ``model`` (and ``contact``) as u."""
        vals = self.values(model, contact)
        return np.asarray([p.to_u(vals[p.key]) for p in self.params], dtype=float)

    def values(self, model, contact=None) -> dict[str, float]:
        """Current values of the parameters in ``model`` (and ``contact``)."""
        out = {}
        for p in self.params:
            if p.effect == CONTACT:
                out[p.key] = contact_value(contact, p.name)
            else:
                out[p.key] = float(getattr(model.effect(p.effect), p.name) if p.effect else model.gamma)
        return out


#: The brush model's contact parameters a fit may vary (``"contact.<name>"`` in ``[model] fit``): search bounds and
#: plausible ranges. The stiffness per unit area is k ~ G / h (tread shear modulus G of 0.5-5 MPa over a tread
#: depth h of 1-20 mm, lowered by the carcass in series), so 1e7-3e10 Pa/m is plausible; contact lengths run from a
#: few mm (laboratory wheels) to 0.3 m (truck tires); Sakai's exponent n is 2 for the parabolic law and grows
#: towards the uniform one (Sakai, Int. J. Vehicle Design 2 (1981)).
CONTACT_PARAMETERS = {
    "stiffness": dict(lo=1e6, hi=1e12, log=True, unit="Pa/m", plausible=(1e7, 3e10)),
    "length": dict(lo=1e-3, hi=0.5, log=True, unit="m", plausible=(3e-3, 0.3)),
    "sakai_n": dict(lo=0.5, hi=50.0, log=True, unit="1", plausible=(1.0, 20.0)),
}


def contact_parameters(contact, names) -> list[FreeParameter]:
    """The :class:`FreeParameter` of the contact parameters ``names`` (keys of :data:`CONTACT_PARAMETERS`)."""
    out = []
    for n in names:
        if n not in CONTACT_PARAMETERS:
            raise InputError(f"contact.{n}: not a fittable contact parameter; fittable: "
                             f"{sorted(CONTACT_PARAMETERS)}")
        if contact is None:
            raise InputError(f"contact.{n}: the case has no contact (add a [contact] table)")
        contact_value(contact, n)   # checks that the value exists (e.g. a Sakai exponent)
        spec = CONTACT_PARAMETERS[n]
        out.append(FreeParameter(effect=CONTACT, name=n, lo=spec["lo"], hi=spec["hi"], log=spec["log"],
                                 unit=spec["unit"], plausible=spec["plausible"]))
    return out


def contact_value(contact, name: str) -> float:
    """The value of the contact parameter ``name`` (the parabolic law is Sakai's n = 2)."""
    if name == "sakai_n":
        n = contact.sakai_n
        if n is None:
            raise InputError(f"contact.sakai_n: the contact's pressure distribution "
                             f"{contact.pressure_distribution!r} has no Sakai exponent to fit (give "
                             "\"parabolic\" or { sakai_n = ... })")
        return float(n)
    return float(getattr(contact, name))


def free_parameters(effect, names=None, release: bool = False) -> list[FreeParameter]:
    """The parameters of ``effect`` a refit varies.

    Rule (when ``names`` is None): every documented parameter (``effect.parameters``) with a numeric value, finite
    bounds lo < hi and ``fittable`` set, except

    * one holding its ``sentinel`` (a placeholder such as ``Microtexture.hurst = 0``, "fitted on the PSD", or
      ``FlashTemperature.contact_diameter = 0``, "pi / q_m"): never varied, since the placeholder is not a value
      on the scale of the others and would make the objective discontinuous;
    * one whose documented default lies on a bound (a switch, e.g. ``Wet.seal_fraction = 0`` meaning "off"),
      unless ``release`` is True (used when the effect has no signature at all at its given values).

    ``names`` lists the parameters to vary explicitly; a named parameter with a sentinel is varied over its
    plausible range (which excludes the placeholder), and one declared not ``fittable`` is an error.
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
        if not getattr(p, "fittable", True):
            if names is not None:
                raise InputError(f"{effect.name}.{p.name}: cannot be fitted ({p.doc})")
            continue
        try:
            lo, hi = (float(b) for b in p.bounds)
        except (TypeError, ValueError):
            continue
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            continue
        sentinel = getattr(p, "sentinel", None)
        if sentinel is not None:
            if names is None:
                continue
            plo, phi = p.plausible_range() if hasattr(p, "plausible_range") else (lo, hi)
            lo, hi = (max(lo, plo), min(hi, phi))
            if not (lo < hi) or lo <= sentinel <= hi:
                raise InputError(f"{effect.name}.{p.name}: its plausible range does not exclude the placeholder "
                                 f"{sentinel:g}; it cannot be fitted")
        elif names is None and not release:
            d = float(p.default)
            if abs(d - lo) <= 1e-12 * max(1.0, abs(lo)) or abs(d - hi) <= 1e-12 * max(1.0, abs(hi)):
                continue
        log = bool(getattr(p, "log_scale", False)) and lo > 0
        out.append(FreeParameter(effect=effect.name, name=p.name, lo=lo, hi=hi, log=log, unit=p.unit,
                                 physical_limits=tuple(getattr(p, "physical_limits", ())),
                                 plausible=getattr(p, "plausible", None)))
    return out


def release_placeholders(effect):
    """``effect`` with every fittable parameter that holds its placeholder set to a value to fit instead: for a
    candidate whose placeholder cannot be computed on a case (e.g. ``Microtexture.hurst = 0``, "fitted on the
    PSD's last decade", on a PSD table that ends at its roll-off, with no self-affine tail to fit).

    Each such parameter starts at the middle of its plausible range (the geometric middle for a ``log_scale``
    one) and is varied over that range (:func:`free_parameters` with explicit names).

    Parameters
    ----------
    effect : persson.effects.Effect

    Returns
    -------
    (effect, names, released) or None
        The effect with the placeholders replaced, the names of the parameters to vary (those
        :func:`free_parameters` varies by default, and the released ones), and ``{name: start value}`` of the
        released ones; None when no parameter holds a placeholder it could leave.
    """
    import dataclasses

    released = {}
    for p in getattr(effect, "parameters", ()):
        sentinel = getattr(p, "sentinel", None)
        if sentinel is None or not getattr(p, "fittable", True) or getattr(effect, p.name, None) != sentinel:
            continue
        try:
            # the range a fit that names the parameter varies it over: its plausible range, without the placeholder
            (fp,) = free_parameters(effect, names=[p.name])
        except InputError:
            continue
        released[p.name] = fp.middle()
    if not released:
        return None
    names = [q.name for q in free_parameters(effect)] + list(released)
    return dataclasses.replace(effect, **released), names, released


class BudgetExhausted(Exception):
    """Raised by :meth:`Fitter.mu` when the fit's budget of model evaluations is spent."""


#: Distance in u (every coordinate) within which a local fit has joined the basin of an optimum found before.
MERGE_TOL = 0.02


class _Merged(Exception):
    """A local fit reached the basin of a known optimum (see :meth:`Fitter.local`)."""

    def __init__(self, chi2, u):
        super().__init__()
        self.chi2 = chi2
        self.u = u


class Fitter:
    """Weighted least squares of ``predictor.predict(space.apply(model, u))`` against ``y``.

    Every prediction is cached by ``u`` (rounded to 1e-12), so revisiting a point is free, and the best point
    seen is remembered, as are the warnings of each evaluation (:meth:`notes_at`; all of them in ``notes``).

    The trial points of the search are solved without the engine's quadrature-error estimate
    (:func:`persson.solver.quadrature_estimate`; about half of a solve's work), the reported point with it
    (:meth:`settle`): both give the same mu to the last bit wherever the estimate refines no speed, and where
    it would refine the reported point, the search is made again with the estimate at every trial point
    (:func:`validation.refit.global_fit`). ``fast = False`` solves every point with the estimate.

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
        Budget of model evaluations (:class:`BudgetExhausted` is raised when it runs out).
    contact : persson.slip.Contact, optional
        The brush model's contact, varied by the ``contact.*`` parameters of ``space``.
    """

    def __init__(self, predictor, y, w, model, space: ParameterSpace, max_evals: int = 200, contact=None):
        self.predictor = predictor
        self.y = np.asarray(y, dtype=float)
        self.w = np.asarray(w, dtype=float)
        self.model = model
        self.space = space
        self.contact = contact
        self.max_evals = int(max_evals)
        self.n_evals = 0
        self._cache: dict = {}
        self.best = (math.inf, None)
        self.errors: dict[str, None] = {}
        self.notes: dict[str, None] = {}
        self._notes_at: dict = {}
        self._penalty = (np.abs(self.y) + 10.0) * self.w * 10.0
        self.last_hessian = None
        self.fast = True

    def mu(self, u):
        """Predicted mu at ``u`` (None when the model failed there)."""
        u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
        key = tuple(np.round(u, 12))
        if key in self._cache:
            return self._cache[key]
        if self.n_evals >= self.max_evals:
            raise BudgetExhausted()
        self.n_evals += 1
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                mu = self._predict(u)
            here = tuple(dict.fromkeys(f"{w.category.__name__}: {w.message}" for w in caught))
            self.notes.update(dict.fromkeys(here))
            if here:
                self._notes_at[key] = here
            if not np.all(np.isfinite(mu)):
                raise InputError("non-finite prediction")
        except Exception as exc:  # noqa: BLE001  (an effect may fail at some parameters; the fit avoids them)
            self.errors[f"{type(exc).__name__}: {exc}"] = None
            mu = None
        self._cache[key] = mu
        if mu is not None:
            c = float(np.sum(((self.y - mu) * self.w) ** 2))
            if c < self.best[0]:
                self.best = (c, np.array(u))
        return mu

    def settle(self, u):
        """The prediction at ``u`` solved with the engine's quadrature-error estimate and the refinement it drives,
        as a reported point must be (the search's trial points skip it, see the class docstring), and whether it is
        the search's own prediction there: the same to the last bit unless the estimate refined a speed. The
        warnings of this solve become those at ``u`` (:meth:`notes_at`). Not counted against the budget (it belongs
        to the result, not to the search).

        Returns
        -------
        (mu, same) : (ndarray or None, bool)
            None where the model fails; ``same`` False then too.
        """
        u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
        key = tuple(np.round(u, 12))
        if not self.fast:
            if key not in self._cache:
                self.max_evals = max(self.max_evals, self.n_evals + 1)
            mu = self.mu(u)
            return mu, mu is not None
        searched = self._cache.get(key)
        self.n_evals += 1
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                mu = self._predict(u, estimate=True)
            if not np.all(np.isfinite(mu)):
                raise InputError("non-finite prediction")
        except Exception as exc:  # noqa: BLE001  (as in mu(): recorded, the point reported as failed)
            self.errors[f"{type(exc).__name__}: {exc}"] = None
            return None, False
        here = tuple(dict.fromkeys(f"{w.category.__name__}: {w.message}" for w in caught))
        self.notes.update(dict.fromkeys(here))
        self._notes_at[key] = here
        return mu, searched is not None and bool(np.array_equal(mu, searched))

    def search_with_estimate(self) -> None:
        """Solve every trial point with the quadrature-error estimate from now on (``fast = False``), forgetting
        the predictions and the best point made without it; the budget starts again from the evaluations spent."""
        self.fast = False
        self.max_evals += self.n_evals
        self._cache.clear()
        self._notes_at.clear()
        self.best = (math.inf, None)
        self.last_hessian = None

    def adopt(self, other: "Fitter", prefix) -> None:
        """Take over the predictions ``other`` has made, ``other``'s space being this one's with the leading
        coordinates held at ``prefix`` (e.g. a candidate's own parameters at the baseline's fitted values): the
        same models, so they need not be evaluated again."""
        prefix = np.asarray(prefix, dtype=float)
        for key, mu in other._cache.items():
            u = np.concatenate([prefix, np.asarray(key, dtype=float)])
            self._cache.setdefault(tuple(np.round(u, 12)), mu)
            if mu is not None:
                c = float(np.sum(((self.y - mu) * self.w) ** 2))
                if c < self.best[0]:
                    self.best = (c, u)
        self.errors.update(other.errors)
        self.notes.update(other.notes)
        for key, here in other._notes_at.items():
            u = np.concatenate([prefix, np.asarray(key, dtype=float)])
            self._notes_at.setdefault(tuple(np.round(u, 12)), here)

    def notes_at(self, u) -> tuple:
        """The warnings the model gave at ``u`` (an evaluated point; empty otherwise), as ``"Category: message"``.
        :attr:`notes` holds those of every evaluation, trial points of the search included."""
        u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
        return self._notes_at.get(tuple(np.round(u, 12)), ())

    def chi2(self, u) -> float:
        """Weighted residual sum of squares at ``u`` (inf where the model failed)."""
        mu = self.mu(u)
        return math.inf if mu is None else float(np.sum(((self.y - mu) * self.w) ** 2))

    def resid(self, u):
        """Weighted residuals at ``u`` (a large penalty where the model failed)."""
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
            except BudgetExhausted:
                break
        return sorted(out, key=lambda t: t[0])

    def local(self, u0, fixed=(), max_nfev: int | None = None, known=()) -> tuple[np.ndarray, float]:
        """Bounded least squares (trust-region reflective) from ``u0``; the coordinates in ``fixed`` stay put.

        ``known`` lists optima ``(chi2, u)`` or ``(chi2, u, H)`` found before (``H`` the Gauss-Newton Hessian
        there, see :attr:`last_hessian`): a fit whose iterate is no better than one of them and comes within
        :data:`MERGE_TOL` of it (every coordinate), or inside the region where its chi2 rises by less than its
        residual variance ``chi2 / (n - k)`` (predicted by ``H``), stops there: it has entered the same basin, and
        the multi-start search would otherwise pay for converging to it again.

        Returns the end point and its chi2; :attr:`last_hessian` holds the Gauss-Newton Hessian there (full
        coordinates, zero rows for the fixed ones). Raises :class:`BudgetExhausted` when the budget runs out.
        """
        u0 = np.clip(np.asarray(u0, dtype=float), 0.0, 1.0)
        free = np.array([j for j in range(u0.size) if j not in set(fixed)], dtype=int)
        self.last_hessian = None
        if free.size == 0:
            return u0, self.chi2(u0)
        dof = max(self.y.size - u0.size, 1)
        known = [(float(k[0]), np.asarray(k[1], dtype=float), k[2] if len(k) > 2 else None)
                 for k in known if math.isfinite(k[0])]

        def full(v):
            u = u0.copy()
            u[free] = v
            return u

        def resid(v):
            u = full(v)
            r = self.resid(u)
            if known:
                c = float(r @ r)
                for ck, uk, Hk in known:
                    if c < ck:
                        continue
                    du = u - uk
                    if np.max(np.abs(du)) <= MERGE_TOL or (
                            Hk is not None and np.max(np.abs(du)) <= 5 * MERGE_TOL
                            and float(du @ Hk @ du) <= ck / dof):
                        raise _Merged(ck, uk)
            return r

        try:
            res = optimize.least_squares(resid, u0[free], bounds=(0.0, 1.0), method="trf", diff_step=2e-3,
                                         x_scale=1.0, ftol=1e-5, xtol=1e-4, gtol=1e-10,
                                         max_nfev=max_nfev or 12 * (free.size + 1))
        except _Merged as m:
            return m.u.copy(), m.chi2
        u = full(np.clip(res.x, 0.0, 1.0))
        if res.jac is not None and np.all(np.isfinite(res.jac)):
            H = np.zeros((u0.size, u0.size))
            H[np.ix_(free, free)] = res.jac.T @ res.jac
            self.last_hessian = H
        return u, self.chi2(u)

    def jacobian(self, u, h: float = 2e-3) -> np.ndarray:
        """Jacobian d mu / d u at ``u`` by central differences (one-sided at a bound), unweighted."""
        u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
        cols = []
        for j in range(u.size):
            up, dn = u.copy(), u.copy()
            up[j] = min(u[j] + h, 1.0)
            dn[j] = max(u[j] - h, 0.0)
            f_up, f_dn = self.mu(up), self.mu(dn)
            if f_up is None or f_dn is None or up[j] <= dn[j]:
                cols.append(np.zeros_like(self.y))
                continue
            cols.append((f_up - f_dn) / (up[j] - dn[j]))
        return np.column_stack(cols) if cols else np.zeros((self.y.size, 0))

    def model_at(self, u):
        """The model with the effect parameters set from ``u``."""
        return self.space.apply(self.model, u)

    def contact_at(self, u):
        """The contact with the ``contact.*`` parameters set from ``u`` (the fitter's contact when none)."""
        return self.space.apply_contact(self.contact, u)

    def _predict(self, u, estimate: bool = False):
        from persson.solver import quadrature_estimate

        model = self.space.apply(self.model, u)
        contact = self.space.apply_contact(self.contact, u) if self.space.has_contact else None
        with quadrature_estimate(estimate or not self.fast):
            return self.predictor.predict(model, contact=contact).mu


def halton(k: int, n: int, seed: int = 0) -> np.ndarray:
    """``n`` randomized Halton points in [0, 1]^k (reproducible for a given seed), kept off the bounds
    (:func:`validation.distributions.halton`)."""
    if k == 0 or n <= 0:
        return np.zeros((0, k))
    return 0.02 + 0.96 * distributions.halton(k, n, seed=seed)
