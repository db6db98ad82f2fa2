r"""Global, joint refits from several starts, and the uncertainty and plausibility of every fitted parameter.

1. **Starts.** The given values and a scrambled Halton design (seeded, so a case always gives the same result)
   over the whole bounded box in ``u`` (log10 where the parameter declares ``log_scale``). Every start is
   evaluated; bounded least squares (:meth:`validation.fitting.Fitter.local`) runs from the given values and from
   the best distinct design points (for one parameter, from the design points that are local minima along it:
   the screen shows the basins). A local fit that enters the basin of an optimum found before stops there. The
   trial points are solved without the engine's quadrature-error estimate, the best one again with it
   (:meth:`validation.fitting.Fitter.settle`): the same mu unless the estimate refines a speed there, and then the
   whole search is made again with the estimate (noted). The best local optimum is the fit; the other optima
   within :math:`\Delta\chi^2 \le 1` (noise units) are "good" and their spread widens the intervals below.
2. **Standard errors.** Gauss-Newton covariance of the parameters at the optimum,
   :math:`C = s^2 (J^T W^2 J)^{-1}` with :math:`J` the central-difference Jacobian of the prediction and
   :math:`W = \mathrm{diag}(1/\sigma_i)` from ``mu_std`` (:math:`s^2 = 1`) or :math:`W = I` with
   :math:`s^2 = \hat\sigma^2` the independent noise variance (:mod:`validation.noise`). When the model fails
   its lack-of-fit test, :math:`s^2` is multiplied by the Birge ratio :math:`\max(1, \chi^2_\nu)` so that the errors
   include the misfit (Bates & Watts, Nonlinear Regression Analysis and Its Applications (1988), Sec. 2.3;
   Birge, Phys. Rev. 40, 207 (1932)). Errors in ``u`` are carried to the parameter by the delta method.
3. **Profile likelihood.** Where the optimum sits on a bound, the standard error is undefined, or the
   :math:`\chi^2` step one standard error away along the parameter differs from the quadratic prediction by more
   than a factor 2, the 68 % interval is the profile-likelihood one,
   :math:`\{x : \min_{\text{others}} \chi^2(x) - \chi^2_{min} \le s^2\}` (Venzon & Moolgavkar, Appl. Stat. 37,
   87 (1988); Raue et al., Bioinformatics 25, 1923 (2009)), found by stepping out from the optimum with the other
   parameters refitted; an end that reaches a bound is reported open there. The 95 % interval is
   :math:`\pm 1.96` standard errors where the :math:`\chi^2` step that far out is within a factor 2 of the
   quadratic one, else the profile at :math:`\Delta\chi^2 = 1.96^2 = 3.84`, the 95 % quantile of :math:`\chi^2`
   with one degree of freedom (S. S. Wilks, Ann. Math. Stat. 9, 60 (1938); Venzon & Moolgavkar, above). The 95 %
   profile continues from the points of the 68 % one; each side of each profile has model evaluations set aside for
   it (:data:`PROFILE_EVALS` per fitted parameter): falling back on :math:`\pm 1.96` standard errors where the
   likelihood is not quadratic made the 95 % intervals of skewed profiles (the flash temperature's macro-scale
   ratio) miss the truth several times as often as they should. Where the evaluations run out all the same, the end
   is extrapolated from the profile's two furthest points (a power law :math:`\Delta\chi^2 \propto t^p`,
   :math:`1 \le p \le 2`) and a note says so. Where the variance unit :math:`s^2` is itself estimated (from local
   differences or replicates, or a residual) on :math:`\nu` degrees of freedom, the half-widths are Student's
   :math:`t_\nu` quantiles and the profile thresholds their squares (:func:`t_quantiles`).
4. **Plausibility.** A parameter that ends on a search bound (a bound that is not one of its declared
   ``physical_limits``) or outside its declared plausible range makes the fit implausible; a physical limit
   (q_m = q0, a factor of 1, zero) is a legitimate optimum and says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from .deferred import Deferred, Lazy
from .distributions import t_isf
from .fitting import BudgetExhausted, Fitter, halton

__all__ = ["BUDGET_NOTE", "Estimate", "GlobalFit", "ParameterCovariance", "global_fit", "with_uncertainty",
           "issues_at", "plausible_start", "DataRange", "data_range", "t_quantiles", "PROFILE_EVALS"]

#: The note of a fit that stopped at its budget of model evaluations: its optimum may lie further on (a set search
#: continues such fits where they could change the answer, :meth:`validation.select.SetSearch.resume`).
BUDGET_NOTE = "the fit stopped at its budget of model evaluations (the best point found is used)"
#: A search whose best point needed the engine's q refinement, made again with the quadrature-error estimate.
ESTIMATE_NOTE = ("the search was made again with the engine's quadrature-error estimate at every trial point: its best "
                 "point needed a finer q grid than the trial points were solved on")

#: Distance in u (every coordinate) within which two starts of a global fit count as one: the later is not fitted.
DISTINCT = 0.1

#: Distance in u below which a fitted parameter is "on its bound".
BOUND_TOL = 2e-3


@dataclass(frozen=True)
class DataRange:
    """Measured ranges of a data set, handed to callable plausible ranges (see :class:`persson.effects.Parameter`).

    Attributes
    ----------
    speed, shifted_speed, temperature, pressure : (float, float)
        Sliding speed (m/s), sliding speed times a_T(T) (m/s at the material's reference temperature),
        temperature (C), pressure (Pa).
    """

    speed: tuple
    shifted_speed: tuple
    temperature: tuple
    pressure: tuple


def data_range(measurements, material) -> DataRange:
    """The :class:`DataRange` of ``measurements``, shifted with ``material.log10_aT`` when it has one."""
    m = measurements
    vs = m.sliding_speed
    if hasattr(material, "log10_aT"):
        shifted = vs * 10.0 ** np.asarray(material.log10_aT(m.temperature), dtype=float)
    else:
        shifted = vs
    return DataRange(speed=(float(vs.min()), float(vs.max())),
                     shifted_speed=(float(shifted.min()), float(shifted.max())),
                     temperature=(float(m.temperature.min()), float(m.temperature.max())),
                     pressure=(float(m.pressure.min()), float(m.pressure.max())))


@dataclass(frozen=True)
class Estimate:
    """A fitted parameter with its uncertainty.

    Attributes
    ----------
    key : str
        ``"effect.parameter"``, ``"gamma"`` or ``"contact.<name>"``.
    value : float
    std : float
        Standard error (inf when the data do not determine it).
    interval : (float, float)
        68 % interval.
    method : str
        ``"quadratic"`` (value +- std, or its log-scale equivalent) or ``"profile"`` (profile likelihood);
        ``" + starts"`` when the spread of equally good optima widened it.
    unit : str
    bound : str
        ``""``, ``"physical limit"`` or ``"search bound"``: where the value sits.
    plausible : (float, float)
        The declared plausible range (evaluated on the data's ranges).
    issue : str
        Why the value is not credible (on a search bound, outside the plausible range), else ``""``.
    search : (float, float)
        The bounds searched.
    log_scale : bool
        Whether the parameter was searched on a log scale (its interval is then judged in decades).
    one_sided : str
        ``""``, or where the data leave the parameter open when it ends on a search bound with its 68 % interval
        reaching back into the plausible range (``"above 0.4"``): bounded on one side only, so not identified.
    interval95 : (float, float)
        95 % interval: 1.96 standard errors where the chi^2 that far out is still quadratic, else the profile
        likelihood at delta chi^2 = 3.84 (computed where the 68 % interval may be profiled; elsewhere the
        quadratic one); never narrower than the 68 % interval. NaN when no uncertainty was computed. It may be
        given as a :class:`validation.deferred.Deferred`, computed when first read (``with_uncertainty(...,
        defer95=True)``).
    note95 : str
        How the 95 % interval was found where that is not as described above (``""`` else): extrapolated from a
        profile that ran out of model evaluations.
    caveat : str
        ``""``, or why a credible value deserves a second look: its best value lies outside the plausible range but
        its 68 % interval reaches into it (the data do not demand the implausible value, as for :attr:`one_sided`
        at a search bound).
    """

    key: str
    value: float
    std: float
    interval: tuple
    method: str
    unit: str = ""
    bound: str = ""
    plausible: tuple = (-math.inf, math.inf)
    issue: str = ""
    search: tuple = (-math.inf, math.inf)
    log_scale: bool = False
    one_sided: str = ""
    interval95: tuple = Lazy(default=(math.nan, math.nan))
    note95: str = Lazy(default="")
    caveat: str = ""

    @property
    def name(self) -> str:
        """The parameter's name: ``key`` after its last ``"."`` (``"gamma"`` for ``gamma``)."""
        return self.key.rpartition(".")[2]

    @property
    def identified(self) -> bool:
        """Whether the data limit the parameter: False when its 68 % interval spans the whole range searched, when
        it is bounded on one side only (:attr:`one_sided`), or when it changes no prediction on these rows."""
        if self.method.startswith("no effect") or self.one_sided:
            return False
        lo, hi = self.interval
        slo, shi = self.search
        if not (math.isfinite(slo) and math.isfinite(shi)) or any(math.isnan(x) for x in (lo, hi)):
            return True
        if self.log_scale and slo > 0:
            # in decades: on a range of 1e-12 to 1e6 m/s an interval from 0.4 m/s up does not span the range
            tol = 1e-6 * math.log(shi / slo)
            return not ((lo <= 0 or math.log(lo / slo) <= tol) and hi > 0 and math.log(shi / hi) <= tol)
        tol = 1e-6 * max(abs(slo), abs(shi), 1e-300)
        return not (lo <= slo + tol and hi >= shi - tol)

    def describe(self) -> str:
        """``"tau_f0 = 1.52e+06 +- 4.1e+04 Pa"`` or ``"v_ref = 3e-04 m/s (68 % 1.1e-04 - 8e-04, profile)"``."""
        u = f" {self.unit}" if self.unit and self.unit != "1" else ""
        if self.method == "quadratic" and math.isfinite(self.std):
            txt = f"{self.name} = {self.value:.4g} +- {self.std:.2g}{u}"
        else:
            lo, hi = self.interval
            txt = f"{self.name} = {self.value:.4g}{u} (68 % interval {lo:.3g} - {hi:.3g}, {self.method})"
        if self.bound == "physical limit":
            txt += " [at its physical limit]"
        if self.issue:
            txt += f" [{self.issue}]"
        if self.caveat:
            txt += f" [{self.caveat}]"
        if self.one_sided:
            txt += (f" [not identified: bounded on one side only, the data allow any value {self.one_sided} (plausible "
                    "ones included)]")
        elif not self.identified:
            txt += " [not identified: the interval spans the range searched]"
        return txt

    def as_dict(self) -> dict:
        """The estimate as a JSON-ready dict.

        Returns
        -------
        dict
            ``value``, ``std``, ``interval``, ``method``, ``unit``, ``bound``, ``plausible``, ``issue``, ``search``,
            ``identified``, ``one_sided``, ``interval95`` (the pairs as lists), ``note95`` and ``caveat``.
        """
        return {"value": self.value, "std": self.std, "interval": list(self.interval), "method": self.method,
                "unit": self.unit, "bound": self.bound, "plausible": list(self.plausible), "issue": self.issue,
                "search": list(self.search), "identified": self.identified, "one_sided": self.one_sided,
                "interval95": list(self.interval95), "note95": self.note95, "caveat": self.caveat}


@dataclass(frozen=True, eq=False)
class ParameterCovariance:
    r"""The Gauss-Newton covariance of a fit's parameters, in the fit's coordinates ``u`` (module docstring,
    item 2: :math:`C = s^2 (J^T W^2 J)^{-1}`, the Birge ratio included), with the map from ``u`` to the model.

    It is what the uncertainty band of a fitted model's curves needs (:func:`validation.band.band_half_width`):
    the curves' derivatives with respect to ``u`` and this matrix.

    Attributes
    ----------
    space : validation.fitting.ParameterSpace
        The fitted parameters and the map ``u -> model`` (and contact).
    u : ndarray (k,)
        The optimum.
    matrix : ndarray (k, k)
        Covariance in ``u`` (inf in rows and columns of directions the data do not determine).
    estimates : tuple of Estimate
        The parameters' estimates, in the order of ``space`` (may be given as a
        :class:`validation.deferred.Deferred`, computed when first read).
    """

    space: object
    u: np.ndarray
    matrix: np.ndarray
    estimates: tuple = Lazy(default=())

    @property
    def keys(self) -> tuple:
        """Keys of the fitted parameters, in the order of ``u`` and ``matrix``."""
        return self.space.keys

    def in_parameters(self) -> np.ndarray:
        r"""The covariance in the parameters' own units, :math:`D C D` with :math:`D = \mathrm{diag}(dx/du)`."""
        d = np.asarray([p.dx_du(p.from_u(float(x))) for p, x in zip(self.space.params, self.u)], dtype=float)
        return self.matrix * np.outer(d, d)

    def unavailable(self) -> str:
        """Why a linearised band from this covariance cannot be trusted ("" when it can): a parameter the data
        do not determine, or whose 68 % interval spans the range searched."""
        why = []
        diag = np.diag(self.matrix)
        for j, key in enumerate(self.keys):
            est = self.estimates[j] if j < len(self.estimates) else None
            if est is not None and est.method.startswith("no effect"):
                why.append(f"{key} changes no prediction on the measured rows")
            elif not (math.isfinite(float(diag[j])) and diag[j] >= 0):
                why.append(f"the data do not determine {key} (its variance is infinite)")
            elif est is not None and not est.identified:
                why.append(f"{key} is not identified (its 68 % interval spans the range searched)")
        return "; ".join(why)


@dataclass(frozen=True, eq=False)
class GlobalFit:
    """The outcome of :func:`global_fit`.

    Attributes
    ----------
    u : ndarray
        Best point in the unit box.
    chi2 : float
        Weighted residual sum of squares there.
    mu : ndarray
        Prediction there.
    model : persson.Model
    contact : persson.slip.Contact or None
    estimates : tuple of Estimate
        In the order of the fitter's parameter space.
    jacobian : ndarray
        d mu / d u at the optimum (unweighted), shape (n, k).
    n_starts, n_good : int
        Local fits run, and optima as good as the best (within one noise unit of chi2) among them.
    n_evals : int
    notes : tuple of str
    optima : tuple of (float, ndarray)
        chi2 and u of every local fit.
    covariance : ParameterCovariance or None
        The parameters' covariance (set by :func:`with_uncertainty`; None before, or when its budget ran out
        before the Jacobian).
    pending : validation.deferred.Deferred or None
        With ``with_uncertainty(..., defer=True)``: ``(estimates, notes)`` with the intervals, computed when first
        asked for (``estimates`` and ``notes`` are then those of the fit without its intervals).
    credibility : validation.deferred.Deferred or None
        With ``defer=True``: estimates with the 68 % intervals of the parameters that may make the fit implausible
        (on a search bound or outside their plausible range) and the others bare, computed when first asked for:
        what the fit's :attr:`issues` need, at a fraction of the cost of ``pending``.
    """

    u: np.ndarray
    chi2: float
    mu: np.ndarray
    model: object
    contact: object
    estimates: tuple
    jacobian: np.ndarray
    n_starts: int
    n_good: int
    n_evals: int
    notes: tuple = ()
    optima: tuple = ()
    covariance: ParameterCovariance | None = None
    pending: object = field(default=None, repr=False)
    credibility: object = field(default=None, repr=False)

    @property
    def values(self) -> dict:
        """``key -> value`` of every fitted parameter (empty until :func:`with_uncertainty` has added the estimates)."""
        return {e.key: e.value for e in self.estimates}

    @property
    def issues(self) -> tuple:
        """Why the fit is not credible (one phrase per implausible parameter); empty when it is."""
        return self.issues_of(self.estimates)

    @staticmethod
    def issues_of(estimates) -> tuple:
        """The phrases of :attr:`issues` for the estimates ``estimates`` (e.g. those of ``credibility``)."""
        return tuple(f"{_named(e)}: {e.issue}" for e in estimates if e.issue)

    @staticmethod
    def caveats_of(estimates) -> tuple:
        """``"effect.parameter = value unit: why"`` of each estimate among ``estimates`` that is credible but
        deserves a second look (:attr:`Estimate.caveat`)."""
        return tuple(f"{_named(e)}: {e.caveat}" for e in estimates if e.caveat)

    @property
    def n_effective(self) -> int:
        """Parameters that change the prediction (non-zero Jacobian column)."""
        if self.jacobian.shape[1] == 0:
            return 0
        norms = np.linalg.norm(self.jacobian, axis=0)
        return int(np.sum(norms > 1e-8 * max(float(norms.max()), 1e-300)))


# ==========================================================================================================
def global_fit(fitter: Fitter, u_given, *, seed: int = 0, n_screen: int | None = None, n_local: int = 3,
               extra_starts=(), screen_dims=None) -> GlobalFit:
    """Multi-start bounded least squares over ``fitter``'s whole box (module docstring, item 1).

    The result has no estimates yet: :func:`with_uncertainty` adds them once the noise is known.

    Parameters
    ----------
    fitter : Fitter
    u_given : array_like
        The given (physically informed) values in u: always a start.
    seed : int
        Seed of the Halton design.
    n_screen : int, optional
        Design points (default ``3 + 5 k``, at most 24).
    n_local : int
        Local fits from the given values and the best distinct design points.
    extra_starts : sequence of array_like
        Further starts fitted besides (e.g. a previous fit); one within :data:`DISTINCT` of an earlier start (every
        coordinate) is not fitted, and its local fit goes to the next distinct design point.
    screen_dims : sequence of int, optional
        The coordinates the design varies (default all); the others stay at ``u_given`` in the screen (e.g. the
        baseline's parameters, already at the optimum of a previous global fit), and every local fit is joint.
    """
    k = len(fitter.space)
    notes: dict[str, None] = {}
    u_given = np.clip(np.asarray(u_given, dtype=float), 0.0, 1.0)
    optima: list[tuple[float, np.ndarray]] = []
    n_starts = 0
    try:
        if k == 0:
            fitter.mu(np.zeros(0))
        else:
            starts = [u_given]
            for s in extra_starts:
                # a start next to an earlier one leads into the same basin: its local fit would pay again for the
                # same optimum (three sets' values that all held an effect where it does nothing), and its place
                # goes to a distinct design point
                s = np.clip(np.asarray(s, dtype=float), 0, 1)
                if all(np.max(np.abs(s - q)) > DISTINCT for q in starts):
                    starts.append(s)
            fitter.screen(starts)
            dims = np.arange(k) if screen_dims is None else np.asarray(screen_dims, dtype=int)
            n_scr = n_screen if n_screen is not None else min(3 + 5 * dims.size, 24)
            design = []
            for p in halton(dims.size, n_scr, seed=seed):
                q = u_given.copy()
                q[dims] = p
                design.append(q)
            screened = fitter.screen(design)
            if dims.size == 1:
                # on a line the screen shows the basins: only its local minima (the given values included) can
                # lead to distinct optima
                screened = _line_minima(screened + [(fitter.chi2(s), s) for s in starts], int(dims[0]))
            for c, p in screened:
                if len(starts) >= n_local + len(extra_starts):
                    break
                if math.isfinite(c) and all(np.max(np.abs(p - q)) > DISTINCT for q in starts):
                    starts.append(p)
            known = []
            for s in starts:
                if not math.isfinite(fitter.chi2(s)):
                    continue
                u, c = fitter.local(s, known=known)
                n_starts += 1
                optima.append((c, u))
                known.append((c, u, getattr(fitter, "last_hessian", None)))
    except BudgetExhausted:
        notes[BUDGET_NOTE] = None
    c_best, u_best = fitter.best
    if u_best is None:
        from .errors import InputError

        raise InputError("the model failed at every parameter value tried: " + "; ".join(list(fitter.errors)[:3]))
    if fitter.errors:
        notes["the model failed at some trial parameters (avoided by the fit): "
              + "; ".join(list(fitter.errors)[:2])] = None
    # the reported point solved with the quadrature-error estimate, which the trial points skip: where it refines a
    # speed there, the search ran on too coarse a grid near the optimum and is made again with the estimate
    settle = getattr(fitter, "settle", None)  # a fitter-like object without it solves every point one way
    mu_best, same = settle(u_best) if settle is not None else (fitter.mu(u_best), True)
    if not same and fitter.fast:
        fitter.search_with_estimate()
        again = global_fit(fitter, u_given, seed=seed, n_screen=n_screen, n_local=n_local, extra_starts=extra_starts,
                           screen_dims=screen_dims)
        return replace(again, notes=again.notes + (ESTIMATE_NOTE,))
    # the warnings of the fitted model, not those of trial points the search moved away from (a rough tail tried on
    # the way to the optimum says nothing about the model reported)
    notes.update(dict.fromkeys(fitter.notes_at(u_best)))
    return GlobalFit(u=u_best, chi2=c_best, mu=mu_best, model=fitter.model_at(u_best),
                     contact=fitter.contact_at(u_best), estimates=(), jacobian=np.zeros((fitter.y.size, 0)),
                     n_starts=n_starts, n_good=0, n_evals=fitter.n_evals, notes=tuple(notes),
                     optima=tuple(optima))


def _line_minima(points, j: int = 0) -> list:
    """The points ``(chi2, u)`` of a screen along coordinate ``j`` that are local minima along it, best first."""
    pts = sorted(((float(c), np.asarray(u, dtype=float)) for c, u in points if math.isfinite(c)),
                 key=lambda t: float(t[1][j]))
    out = []
    for i, (c, u) in enumerate(pts):
        left = pts[i - 1][0] if i > 0 else math.inf
        right = pts[i + 1][0] if i + 1 < len(pts) else math.inf
        if c <= left and c <= right:
            out.append((c, u))
    return sorted(out, key=lambda t: t[0])


def with_uncertainty(fitter: Fitter, fit: GlobalFit, *, s2: float, ranges: DataRange | None = None,
                     profile: bool = True, budget: int | None = None, misfit: bool = False,
                     dof: float = math.inf, reserve: bool | None = None, defer: bool = False,
                     defer95: bool = False, on_evals=None) -> GlobalFit:
    """``fit`` with an :class:`Estimate` per parameter (module docstring, items 2-4).

    Parameters
    ----------
    fitter : Fitter
        The fitter that made ``fit`` (its cache makes revisited points free).
    fit : GlobalFit
    s2 : float
        Variance unit of chi2: 1 with ``mu_std`` weights, else the noise variance (before the Birge ratio).
    ranges : DataRange, optional
        For callable plausible ranges.
    profile : bool
        Compute profile-likelihood intervals where the quadratic approximation fails.
    budget : int, optional
        Model evaluations allowed beyond those already spent (default ``6 k``, plus ``12 k^2`` with ``profile``).
    misfit : bool
        The model fails the lack-of-fit test: scale the errors by the Birge ratio.
    dof : float
        Degrees of freedom of ``s2`` (infinite when it is known, as with ``mu_std``; the noise estimate's otherwise):
        the intervals use Student's t quantiles with them (module docstring, item 3).
    reserve : bool, optional
        Give each side of each profile :data:`PROFILE_EVALS` evaluations per parameter beyond the budget (default:
        only when ``budget`` is not given; an explicit budget is a cap).
    defer : bool
        Compute the Jacobian and the covariance now, the estimates (their profiles) only when first asked for:
        the result's ``estimates`` are then the bare values (no intervals), ``covariance.estimates`` and
        ``pending`` (a :class:`validation.deferred.Deferred` of ``(estimates, notes)``) give the full ones, equal to
        what ``defer=False`` gives. For fits whose intervals may never be read (:mod:`validation.select`).
    defer95 : bool
        Compute the 95 % intervals (often the costlier profiles) when first read: each estimate's ``interval95`` and
        ``note95`` are then :class:`validation.deferred.Deferred` (with the budget of model evaluations left now),
        equal to what ``defer95=False`` gives; a 95 % interval extrapolated from its profile says so in its
        ``note95`` (and not in the fit's notes). With ``defer``, the 95 % intervals are deferred as well.
    on_evals : callable, optional
        With ``defer`` or ``defer95``: called with the number of model evaluations the deferred estimates spent,
        once they are computed.
    """
    k = len(fitter.space)
    if k == 0:
        return fit
    notes = dict.fromkeys(fit.notes)
    fitter.max_evals = fitter.n_evals + (budget if budget is not None else 6 * k + (12 * k * k if profile else 0))
    n = fitter.y.size
    u, c = fit.u, fit.chi2
    good = [v for cv, v in fit.optima if (cv - c) / s2 <= 1.0 and np.max(np.abs(v - u)) > 0.02]
    J = np.zeros((n, 0))
    matrix = None
    try:
        J = fitter.jacobian(u)
        s2_eff = s2 * max(1.0, c / max(n - k, 1) / s2) if misfit else s2
        if s2_eff > s2 * (1 + 1e-9):
            notes[f"standard errors include the misfit (scaled by the Birge ratio {math.sqrt(s2_eff / s2):.2f})"] = None
            dof = max(n - k, 1)     # the variance unit is now the fit's own residual variance
        Jw = J * fitter.w[:, None]
        matrix = _covariance(Jw.T @ Jw / s2_eff)
    except BudgetExhausted:
        notes["the uncertainty stopped at its budget of model evaluations"] = None

    def estimates_and_notes() -> tuple:
        out = dict(notes)
        if matrix is None:
            return _bare_estimates(fitter, u, ranges), out, False
        try:
            est = _estimates(fitter, u, c, J, s2_eff, good, ranges, profile, notes=out, dof=dof,
                             reserve=budget is None if reserve is None else reserve, defer95=defer95 or defer,
                             on_evals=on_evals, optima=fit.optima)
        except BudgetExhausted:
            out["the uncertainty stopped at its budget of model evaluations"] = None
            return _bare_estimates(fitter, u, ranges), out, False
        return est, out, True

    def finished(est, out) -> tuple:
        # a distinct optimum just outside the 68 % range (1 < delta chi2 <= 4) is inside the 95 % one: the local
        # standard errors above do not see it, so say where the best such one is
        near = sorted(((cv - c) / s2, i) for i, (cv, v) in enumerate(fit.optima)
                      if 1.0 < (cv - c) / s2 <= 4.0 and np.max(np.abs(v - u)) > 0.02)
        if near:
            d, i = near[0]
            v = fit.optima[i][1]
            where = ", ".join(f"{p.key} = {p.from_u(float(v[j])):.4g}" for j, p in enumerate(fitter.space.params))
            out[f"another local optimum fits almost as well ({where}; delta chi2 = {d:.2f}, inside the 95 % "
                "range): the standard errors describe the best optimum only"] = None
        return est, tuple(out)

    if defer and matrix is not None:
        def later() -> tuple:
            n0 = fitter.n_evals
            est, out, _ = estimates_and_notes()
            if on_evals is not None:
                on_evals(fitter.n_evals - n0)
            return finished(est, out)

        pending = Deferred(later)

        def credibility() -> tuple:
            # the 68 % intervals of the parameters that may make the fit implausible (those on a search bound or
            # outside their plausible range), the others bare: enough to judge the fit, at a fraction of the cost
            if pending.ready:
                return pending()[0]
            bare = _bare_estimates(fitter, u, ranges)
            n0 = fitter.n_evals
            try:
                est = _estimates(fitter, u, c, J, s2_eff, good, ranges, profile, notes={}, dof=dof,
                                 reserve=budget is None if reserve is None else reserve,
                                 only={j for j, e in enumerate(bare) if e.issue})
            except BudgetExhausted:
                est = bare
            if on_evals is not None:
                on_evals(fitter.n_evals - n0)
            return est

        covariance = ParameterCovariance(space=fitter.space, u=np.array(u, dtype=float), matrix=matrix,
                                         estimates=pending.part(0))
        return GlobalFit(u=u, chi2=c, mu=fit.mu, model=fit.model, contact=fit.contact,
                         estimates=_bare_estimates(fitter, u, ranges), jacobian=J, n_starts=fit.n_starts,
                         n_good=len(good), n_evals=fitter.n_evals, notes=tuple(notes), optima=fit.optima,
                         covariance=covariance, pending=pending, credibility=Deferred(credibility))
    est, out, ok = estimates_and_notes()
    covariance = (ParameterCovariance(space=fitter.space, u=np.array(u, dtype=float), matrix=matrix, estimates=est)
                  if ok else None)
    est, out = finished(est, out)
    return GlobalFit(u=u, chi2=c, mu=fit.mu, model=fit.model, contact=fit.contact, estimates=est,
                     jacobian=J, n_starts=fit.n_starts, n_good=len(good), n_evals=fitter.n_evals,
                     notes=out, optima=fit.optima, covariance=covariance)


# ==========================================================================================================
def issues_at(fitter: Fitter, u, ranges: DataRange | None = None) -> tuple:
    """Why the point ``u`` is implausible (search bounds, plausible ranges), before any uncertainty is computed."""
    return tuple(e.issue for e in _bare_estimates(fitter, np.asarray(u, dtype=float), ranges) if e.issue)


def plausible_start(space, u, ranges: DataRange | None = None, *, dims=None, limits: bool = False):
    """``u`` with every coordinate that sits on a search bound (not a physical limit) or outside its parameter's
    plausible range moved to the middle of that range (the geometric middle for a parameter varied in log10), or
    None when no coordinate needs it.

    A start for a joint fit whose values come from fits of its members alone: a parameter a member drove onto a
    bound or out of its plausible range stood in for something the member could not fit, often its partner's work,
    and a local fit from there may stay in that basin. With ``limits``, a coordinate on a physical limit is moved
    too: a legitimate optimum for the member alone (a flash temperature at q_m = q0, its largest heating) can be
    the same stand-in once a partner joins, and a local fit does not leave a limit its gradient points at.

    Parameters
    ----------
    space : validation.fitting.ParameterSpace
    u : array_like
        A point of the unit box (one coordinate per parameter of ``space``).
    ranges : DataRange, optional
        For plausible ranges given as functions of the data.
    dims : iterable of int, optional
        The coordinates that may move (default all).
    limits : bool
        Also move the coordinates on a physical limit.

    Returns
    -------
    ndarray or None
        The new point in the unit box, or None when no coordinate needs moving (every one off the search bounds,
        or on a physical limit without ``limits``, and inside its plausible range).
    """
    u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
    out = u.copy()
    for j in (range(len(space.params)) if dims is None else dims):
        p = space.params[j]
        x = p.from_u(u[j])
        lo, hi = p.plausible_range(ranges)
        lo, hi = max(lo, p.lo), min(hi, p.hi)
        if not lo < hi:
            continue
        on_bound = (u[j] < BOUND_TOL or u[j] > 1 - BOUND_TOL) and (limits or not p.is_physical_limit(x))
        outside = not _within(x, lo, hi)
        if on_bound or outside:
            out[j] = p.to_u(p.middle(lo, hi))
    return None if np.array_equal(out, u) else out


def _estimates(fitter, u, chi2, J, s2, good, ranges, profile, notes=None, dof=math.inf,
               reserve: bool = False, only=None, defer95: bool = False, on_evals=None, optima=()) -> tuple:
    """The estimates of every parameter at the optimum ``u`` (module docstring, items 2-4); ``reserve``: each
    side of each profile gets :data:`PROFILE_EVALS` model evaluations per parameter beyond the fitter's budget;
    ``only`` (a set of indices): the 68 % intervals of those parameters alone, the others bare, no 95 % ones;
    ``defer95``: the 95 % intervals computed when first read (with the budget left now; ``on_evals`` is told what
    they spent), their notes in each estimate's ``note95`` only; ``optima``: the ``(chi2, u)`` of the local optima
    the search found, those within the 95 % level of ``chi2`` inside each 95 % interval."""
    w = fitter.w
    Jw = J * w[:, None]
    H = Jw.T @ Jw / s2
    k = u.size
    cov = _covariance(H)
    out = []
    pending = []
    # the points each profile computed, by (parameter, side): the 95 % profile continues from the 68 % one
    memo: dict = {}
    z68, z95 = t_quantiles(dof)
    norms = np.linalg.norm(Jw, axis=0)
    bare = _bare_estimates(fitter, u, ranges) if only is not None else ()
    for j, p in enumerate(fitter.space.params):
        x = p.from_u(u[j])
        if only is not None and j not in only:
            out.append(bare[j])
            continue
        if norms[j] <= 1e-10 * max(float(norms.max()), 1e-300):
            # the parameter changes no prediction here: neither determined nor judged
            out.append(Estimate(key=p.key, value=float(x), std=math.inf, interval=(p.lo, p.hi),
                                method="no effect on these rows", unit=p.unit, search=(float(p.lo), float(p.hi)),
                                log_scale=bool(getattr(p, "log", False)), interval95=(p.lo, p.hi)))
            continue
        sd_u = math.sqrt(cov[j, j]) if math.isfinite(cov[j, j]) and cov[j, j] >= 0 else math.inf
        on_bound = u[j] < BOUND_TOL or u[j] > 1 - BOUND_TOL
        method = "quadratic"
        lo_u, hi_u = u[j] - z68 * sd_u, u[j] + z68 * sd_u
        try:
            if profile and (on_bound or not math.isfinite(sd_u) or sd_u > 0.25
                            or not _quadratic_ok(fitter, u, j, sd_u, H, chi2, s2)):
                lo_u, hi_u = _profile(fitter, u, j, chi2, s2, sd_u, k, H=H, memo=memo, level=z68 * z68,
                                      reserve=PROFILE_EVALS * k if reserve else 0)
                method = "profile"
        except BudgetExhausted:
            method = "quadratic (the profile ran out of model evaluations)"
        lo_u, hi_u = max(lo_u, 0.0), min(hi_u, 1.0)
        for g in good:
            lo_u, hi_u = min(lo_u, g[j]), max(hi_u, g[j])
            if "starts" not in method:
                method += " + starts"
        std = abs(p.dx_du(x)) * sd_u if math.isfinite(sd_u) else math.inf
        out.append(_estimate(p, x, std, (p.from_u(lo_u), p.from_u(hi_u)), method, u[j], ranges))
        pending.append((j, p, sd_u, method, lo_u, hi_u, len(out) - 1))
    if only is not None:
        return tuple(out)
    # the 95 % intervals after every 68 % one, so that their profiles never take the evaluations a 68 % profile
    # (and with it the judgement identified / not identified) needs
    left = fitter.max_evals - fitter.n_evals
    near95 = [np.asarray(v, dtype=float) for cv, v in optima if (cv - chi2) / s2 <= z95 * z95]

    def intervals95() -> dict:
        if defer95:
            fitter.max_evals = fitter.n_evals + left    # the budget they would have had at once
        n0 = fitter.n_evals
        found = {}
        for j, p, sd_u, method, lo_u, hi_u, i in pending:
            # a 95 % profile with evaluations of its own: the 68 % profiles must not leave it without (it would
            # then fall back on +- 1.96 standard errors exactly where the likelihood is not quadratic)
            lo95_u, hi95_u = _interval95(fitter, u, j, chi2, s2, sd_u, k, H, profile, method, memo=memo,
                                         ends68=(lo_u, hi_u), z=z95, z68=z68,
                                         reserve=PROFILE_EVALS * k if reserve else 0)
            note = ""
            if memo.pop(("extrapolated", j), False):
                note = "extrapolated from its profile (the profile ran out of model evaluations)"
                if notes is not None and not defer95:
                    notes[f"the 95 % interval of {p.key} is {note}"] = None
            lo95_u, hi95_u = min(lo95_u, lo_u), max(hi95_u, hi_u)  # never narrower than the 68 % interval
            # a local optimum within the 95 % level bounds the profile there from above (the others refitted can
            # only do better): its value belongs to the 95 % interval, which a profile stepping out from the best
            # optimum stops short of when the likelihood rises between the two
            for g in near95:
                lo95_u, hi95_u = min(lo95_u, g[j]), max(hi95_u, g[j])
            found[i] = ((p.from_u(lo95_u), p.from_u(hi95_u)), note)
        if defer95 and on_evals is not None:
            on_evals(fitter.n_evals - n0)
        return found

    if defer95:
        later = Deferred(intervals95)
        for *_, i in pending:
            out[i] = replace(out[i], interval95=Deferred(lambda i=i: later()[i][0]),
                             note95=Deferred(lambda i=i: later()[i][1]))
        return tuple(out)
    for i, (interval95, note) in intervals95().items():
        out[i] = replace(out[i], interval95=interval95, note95=note)
    return tuple(out)


#: Standard errors of a two-sided 95 % interval of a normal variable.
Z95 = 1.959963984540054
#: Model evaluations per fitted parameter set aside for each side of each profile (68 % or 95 %) of a fit with the
#: default budget, beyond what the others left (a refit of the other parameters costs about k + 2 evaluations, a
#: side about four refits): one profile must not starve the next one.
PROFILE_EVALS = 16


def t_quantiles(dof: float) -> tuple[float, float]:
    r"""The half-widths, in standard errors, of the 68.27 % and 95 % intervals when the variance unit has ``dof``
    degrees of freedom: Student's t quantiles :math:`t_{\nu}(0.8413)` and :math:`t_{\nu}(0.975)` (1 and 1.96 for a
    known variance). A profile interval uses their squares as its :math:`\Delta\chi^2 / s^2` threshold: the profile-t
    intervals of Bates & Watts, Nonlinear Regression Analysis and Its Applications (1988), Sec. 6.1.

    Parameters
    ----------
    dof : float
        Degrees of freedom (> 0; ``inf`` for a known variance).

    Returns
    -------
    (float, float)
    """
    if not math.isfinite(dof):
        return 1.0, Z95
    dof = max(float(dof), 1.0)
    return t_isf(0.5 * (1.0 - math.erf(1.0 / math.sqrt(2.0))), dof), t_isf(0.025, dof)


def _interval95(fitter, u, j, chi2, s2, sd_u, k, H, profile, method, memo=None, ends68=None, z: float = None,
                z68: float = 1.0, reserve: int = 0) -> tuple[float, float]:
    """The 95 % interval of parameter j in u: +- 1.96 standard errors where the chi^2 that far out (others fixed)
    is within a factor 2 of the quadratic one (:func:`_quadratic_ok`), else, where profiles are allowed, the
    profile likelihood at delta chi^2 = 1.96^2 (a likelihood flatter or steeper than quadratic beyond one standard
    error, which the 68 % interval's check does not see); clipped to the range searched.

    A 95 % profile continues from the points of the 68 % one (``memo``, see :func:`_profile`). Where it cannot run
    at all (no model evaluations left) after a profiled 68 % interval ``ends68``, each end is ``z / z68`` times as far
    from the optimum as the 68 % end on its side: the profile's asymmetry is kept (exact where the profile is
    quadratic in some monotone reparametrization that is linear near the optimum on each side). ``z``, ``z68``: the
    quantiles of the two intervals (1.96 and 1 with a known variance unit, :func:`t_quantiles`)."""
    z = Z95 if z is None else z
    if not math.isfinite(sd_u):
        return 0.0, 1.0
    lo, hi = u[j] - z * sd_u, u[j] + z * sd_u
    if profile:
        if reserve:
            fitter.max_evals = max(fitter.max_evals, fitter.n_evals + reserve)
        try:
            if method.startswith("profile") or not _quadratic_ok(fitter, u, j, z * sd_u, H, chi2, s2):
                lo, hi = _profile(fitter, u, j, chi2, s2, sd_u, k, H=H, level=z * z, memo=memo, reserve=reserve)
        except BudgetExhausted:
            if method.startswith("profile") and ends68 is not None:
                f = z / z68
                lo, hi = u[j] - f * (u[j] - ends68[0]), u[j] + f * (ends68[1] - u[j])
                if memo is not None:
                    memo[("extrapolated", j)] = True
    return max(lo, 0.0), min(hi, 1.0)


def _bare_estimates(fitter, u, ranges) -> tuple:
    return tuple(_estimate(p, p.from_u(u[j]), math.nan, (math.nan, math.nan), "none", u[j], ranges)
                 for j, p in enumerate(fitter.space.params))


def _estimate(p, x, std, interval, method, uj, ranges) -> Estimate:
    """The estimate of parameter ``p`` at ``x``, judged. On a search bound the data push it out of the range
    searched (the fit is not credible), except when its 68 % interval spans that whole range (the data do not
    determine it at all) or when the bound lies beyond the plausible range and the interval reaches back into it
    (the data bound it on one side only: an adhesive peak somewhere above the measured speeds). In both the
    likelihood at plausible values is within one unit of chi^2 of the bound's, and the parameter is reported as not
    identified rather than the fit as not credible."""
    bound = ""
    issue = ""
    plo, phi = p.plausible_range(ranges)
    est = Estimate(key=p.key, value=float(x), std=float(std), interval=tuple(float(v) for v in interval),
                   method=method, unit=p.unit, plausible=(plo, phi), search=(float(p.lo), float(p.hi)),
                   log_scale=bool(getattr(p, "log", False)))
    flat = not est.identified and not method.startswith("none")
    one_sided = ""
    if uj < BOUND_TOL or uj > 1 - BOUND_TOL:
        b = p.lo if uj < 0.5 else p.hi
        if p.is_physical_limit(b):
            bound = "physical limit"
        else:
            bound = "search bound"
            lo, hi = est.interval
            # a bound beyond the plausible range, with plausible values inside the interval: the bound is not
            # demanded (a bound that is itself plausible, reached with a narrow interval, is pushed against)
            implausible_bound = not _within(b, -math.inf, phi) if uj > 0.5 else not _within(b, plo, math.inf)
            if not flat and implausible_bound and _reaches(est.interval, plo, phi) and method != "none":
                one_sided = f"below {hi:.3g}" if uj < 0.5 else f"above {lo:.3g}"
            elif not flat:
                issue = (f"on the {'lower' if uj < 0.5 else 'upper'} search bound {b:g}: the data push it out of "
                         "the range searched")
    caveat = ""
    if not issue and not flat and not one_sided and not _within(x, plo, phi):
        if method != "none" and _reaches(est.interval, plo, phi):
            # as for a bound beyond the plausible range: plausible values lie within one unit of chi^2 of the best,
            # so the data do not demand the implausible value (a strain softening whose loss factor comes out at
            # 0.07 with an interval up to 0.27, against a plausible range from 0.1)
            caveat = f"best value outside the plausible range {plo:.3g} - {phi:.3g}; its 68 % interval reaches into it"
        else:
            issue = f"outside the plausible range {plo:.3g} - {phi:.3g}"
    return replace(est, bound=bound, issue=issue, one_sided=one_sided, caveat=caveat)


def _named(e) -> str:
    """``"effect.parameter = value unit"`` of an estimate (no unit for a dimensionless one)."""
    return f"{e.key} = {e.value:.3g}{(' ' + e.unit) if e.unit and e.unit != '1' else ''}"


def _within(x: float, lo: float, hi: float) -> bool:
    """Whether ``x`` lies in the plausible range ``lo`` - ``hi``, with a relative tolerance of 1e-9 (a value
    written with fewer digits than the range's end is still inside)."""
    return lo * (1 - 1e-9) - 1e-300 <= x <= hi * (1 + 1e-9) + 1e-300


def _reaches(interval, lo: float, hi: float) -> bool:
    """Whether the finite ``interval`` overlaps the plausible range ``lo`` - ``hi`` (tolerance of :func:`_within`)."""
    a, b = interval
    return (math.isfinite(a) and math.isfinite(b) and a <= hi * (1 + 1e-9) + 1e-300
            and b >= lo * (1 - 1e-9) - 1e-300)


def _covariance(H: np.ndarray) -> np.ndarray:
    """Inverse of the Gauss-Newton Hessian; directions it does not determine get infinite variance."""
    k = H.shape[0]
    if k == 0:
        return H
    vals, vecs = np.linalg.eigh(H)
    top = max(float(vals.max()), 1e-300)
    ok = vals > 1e-10 * top
    inv = np.where(ok, 1.0 / np.where(ok, vals, 1.0), 0.0)
    cov = (vecs * inv) @ vecs.T
    if not np.all(ok):
        # a parameter with weight in an undetermined direction is itself undetermined
        bad = np.any(np.abs(vecs[:, ~ok]) > 1e-3, axis=1)
        cov[bad, :] = np.inf
        cov[:, bad] = np.inf
    return cov


def _quadratic_ok(fitter, u, j, step, H, chi2, s2) -> bool:
    r"""Whether the chi2 ``step`` away along parameter j is within a factor 2 of the quadratic prediction, on both
    sides. The step follows the linearized profile (the other parameters moved by
    :math:`-H_{oo}^{-1} H_{oj}\,\delta u_j`, where the quadratic model puts their refitted values), on which the
    quadratic prediction is :math:`\delta u_j^2 / C_{jj}`: along the axis with the others fixed, a ridge of
    correlated parameters looks quadratic while the profile along it bends (two strain-softening factors; a
    parameter with the baseline's tau_f0), and its intervals then came out several times too narrow."""
    others, cond = _conditional(H, j)
    if cond is None:
        return False
    # the curvature of the profile, H_jj - H_jo H_oo^-1 H_oj = 1 / C_jj (the Schur complement)
    curvature = float(H[j, j] + (H[j, others] @ cond if others.size else 0.0))
    if not curvature > 0:
        return False
    expected = step * step * curvature
    for sign in (-1.0, 1.0):
        v = u.copy()
        v[j] = u[j] + sign * step
        if others.size:
            v[others] = u[others] + sign * step * cond
        if np.any(v < 0) or np.any(v > 1):
            return False
        d = (fitter.chi2(v) - chi2) / s2
        if not (0.5 * expected <= d <= 2.0 * expected):
            return False
    return True


def _profile(fitter, u, j, chi2, s2, sd_u, k, max_steps: int = 4, refine: int = 5, H=None,
             level: float = 1.0, memo: dict | None = None, reserve: int = 0) -> tuple[float, float]:
    r"""Ends of the profile-likelihood interval of parameter j in u at delta chi2 = ``level`` (1: 68 %; 3.84: 95 %;
    a bound when the profile stays below it).

    Steps out from the optimum (the others refitted at each step) until the profile exceeds ``level``, then refines
    the crossing by regula falsi in sqrt(delta chi2) (exact for a parabola, and converging for the linear rise of a
    profile at a bound). Each refit starts where the Gauss-Newton Hessian ``H`` at the optimum puts the other
    parameters for the new value of parameter j (:math:`\delta u_o = -H_{oo}^{-1} H_{oj}\,\delta u_j`), so that
    correlated parameters need few iterations. Where that linear step leaves the box, the start is clipped onto its
    edge, where an effect may vanish (an adhesion's tau_f0 = 0) and a refit started there stays: a refit so started
    that reads above ``level`` is repeated from the last point without the step (the lower of the two is the
    profile, each an upper bound on it; the repeat's model evaluations are not taken from the other profiles'
    budget). The first step is at most :data:`FIRST_STEP` per unit of :math:`\sqrt{\Delta\chi^2}` and the next
    ones at most four times the last, each refit starting from the last point below the level; an upper bracket more
    than 16 times the level is halved in distance, not interpolated.

    ``memo`` (a dict shared by the profiles of one fit) keeps every profile point, so that a profile at a higher
    ``level`` starts from the furthest point below it and brackets with the nearest one above. Where the model
    evaluations run out on a side after a point with delta chi2 of at least a tenth of ``level``, that side's end
    is extrapolated from its furthest points (:func:`_extrapolated_end`; ``memo[("extrapolated", j)]`` says so);
    with nothing to extrapolate from, :class:`~validation.fitting.BudgetExhausted` propagates. ``reserve``: model
    evaluations each side may spend beyond the fitter's budget (:data:`PROFILE_EVALS`).
    """
    others = np.array([i for i in range(k) if i != j], dtype=int)
    cond = _conditional(H, j)[1] if H is not None and others.size else None
    memo = {} if memo is None else memo
    root = math.sqrt(level)
    ends = []
    for sign in (-1.0, 1.0):
        edge = 0.0 if sign < 0 else 1.0
        room = abs(edge - u[j])
        if room < BOUND_TOL:
            ends.append(edge)
            continue
        points = memo.setdefault((j, sign), [])
        if reserve:
            fitter.max_evals = max(fitter.max_evals, fitter.n_evals + reserve)

        def delta(t, start):
            v = start.copy()
            v[j] = u[j] + sign * t
            plain = v.copy()
            clipped = False
            if cond is not None:
                moved = start[others] + cond * (v[j] - start[j])
                clipped = bool(np.any((moved < 0.0) | (moved > 1.0)))
                v[others] = np.clip(moved, 0.0, 1.0)
            if k > 1:
                v, c = fitter.local(v, fixed=(j,), max_nfev=6 * k)
                if clipped and (c - chi2) / s2 >= level:
                    # a linearized start that left the box lands on its edge, where an effect may vanish (an
                    # adhesion's tau_f0 = 0): the others then have no gradient and the refit stays there, far above
                    # the profile, and would end the interval. The last point's values without the extrapolation
                    # are a second start, the lower refit the profile (each is an upper bound on it); its
                    # evaluations are its own, so that the other profiles keep the budget they had
                    n0, cap = fitter.n_evals, fitter.max_evals
                    fitter.max_evals = max(cap, n0) + 6 * k * k
                    try:
                        v2, c2 = fitter.local(plain, fixed=(j,), max_nfev=6 * k)
                    finally:
                        fitter.max_evals = cap + (fitter.n_evals - n0)
                    if c2 < c:
                        v, c = v2, c2
            else:
                c = fitter.chi2(v)
            d = (c - chi2) / s2
            points.append((t, d, v))
            return d, v

        below = [p for p in points if p[1] < level]
        lo, start = (0.0, 0.0), u.copy()
        if below:
            t_lo, d_lo, start = max(below, key=lambda p: p[0])
            lo = (t_lo, d_lo)
        above = [p for p in points if p[1] >= level and p[0] > lo[0]]
        hi = min(((p[0], p[1]) for p in above), default=None)
        try:
            if hi is None and not (below and lo[0] >= room - 1e-12):
                # the first step at most FIRST_STEP (in u) per unit of sqrt(level): a refit started far along a
                # curved ridge (the linearized profile clipped at the bounds) can miss it, and its chi2 would then
                # bracket the crossing far too close to the optimum
                t = (min(root * sd_u if math.isfinite(sd_u) and sd_u > 1e-4 else 0.05 * root, FIRST_STEP * root, room)
                     if not below else _next_step(lo[0], lo[1], level, room))
                for _ in range(max_steps):
                    d, v = delta(t, start)
                    if d >= level:
                        hi = (t, d)
                        break
                    lo, start = (t, d), v
                    if t >= room - 1e-12:
                        break
                    t = _next_step(t, d, level, room)
            if hi is None:
                ends.append(edge)
                continue
            for _ in range(refine):
                a, b = math.sqrt(max(lo[1], 0.0)), math.sqrt(hi[1])
                t = lo[0] + (hi[0] - lo[0]) * (root - a) / max(b - a, 1e-12)
                if hi[1] > 16.0 * level:
                    # an upper point far beyond the level says little about where the crossing is (a refit that
                    # missed the ridge, or a profile that turns up steeply): halve the bracket in t instead
                    t = 0.5 * (lo[0] + hi[0])
                if hi[0] - lo[0] < 1e-4:
                    break
                d, v = delta(t, start)
                if d >= level:
                    hi = (t, d)
                else:
                    lo, start = (t, d), v
                if abs(d - level) < 0.02 * level:
                    break
        except BudgetExhausted:
            if hi is None:
                if lo[1] < 0.1 * level:
                    raise
                memo[("extrapolated", j)] = True
                ends.append(u[j] + sign * min(_extrapolated_end(points, lo, level), room))
                continue
        a, b = math.sqrt(max(lo[1], 0.0)), math.sqrt(hi[1])
        ends.append(u[j] + sign * (lo[0] + (hi[0] - lo[0]) * (root - a) / max(b - a, 1e-12)))
    lo_u, hi_u = sorted(ends)
    return lo_u, hi_u


#: Largest first step of a profile, in u per unit of sqrt(delta chi2) (see :func:`_profile`).
FIRST_STEP = 0.1


def _conditional(H: np.ndarray, j: int) -> tuple[np.ndarray, np.ndarray | None]:
    r"""(others, c): the indices of the parameters other than j, and where the quadratic model with Gauss-Newton
    Hessian ``H`` puts them per unit step of parameter j once refitted, :math:`c = -H_{oo}^{-1} H_{oj}` (None where
    that is not finite)."""
    others = np.array([i for i in range(H.shape[0]) if i != j], dtype=int)
    if not others.size:
        return others, np.zeros(0)
    cond = -np.linalg.lstsq(H[np.ix_(others, others)], H[others, j], rcond=1e-10)[0]
    return others, cond if np.all(np.isfinite(cond)) else None


def _extrapolated_end(points, lo, level: float) -> float:
    """Where a profile side that reached delta chi2 = ``lo[1]`` < ``level`` at distance ``lo[0]`` would cross
    ``level``: a power law d = a t^p through its two furthest points (``points``: (t, d, v)), the exponent clipped to
    1-2 (2 is a parabola, linear in sqrt(d); a profile that flattens beyond one standard error rises more slowly,
    and a parabola through its furthest point would put the end too close)."""
    t2, d2 = lo
    inner = [(t, d) for t, d, _ in points if 0.0 < t < t2 * (1 - 1e-9) and 0.0 < d < d2]
    p = 2.0
    if inner:
        t1, d1 = max(inner)
        p = min(max(math.log(d2 / d1) / math.log(t2 / t1), 1.0), 2.0)
    return t2 * (level / d2) ** (1.0 / p)


def _next_step(t: float, d: float, level: float, room: float) -> float:
    """The next distance from the optimum of a profile that reached delta chi2 = ``d`` at ``t``: where a parabola
    through the optimum would put 1.5 ``level``, at least 1.5 and at most 4 times as far, within ``room``."""
    return min(t * min(max(math.sqrt(1.5 * level / max(d, 1e-3 * level)), 1.5), 4.0), room)
