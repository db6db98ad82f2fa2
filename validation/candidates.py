r"""Fitting the baseline and each candidate effect: signature, score test, global joint refit, statistics.

For measurements ``y`` with weights :math:`w_i = 1/\sigma_i` (``mu_std``, else 1):

1. **Baseline.** Its fitted parameters (``[model] fit``) are refitted globally (:func:`validation.refit.global_fit`);
   :math:`f_0` is its prediction, :math:`r = y - f_0`, and :math:`Q` an orthonormal basis (QR) of the weighted
   Jacobian :math:`W J_b` at the optimum.
2. **Signature** of a candidate: :math:`d = f(\text{baseline} + \text{effect at its given parameters}) - f_0`.
3. **Score test** along the projected signature :math:`d_\perp = (I - QQ^T) W d`:
   :math:`z = d_\perp^T W r / (\hat\sigma \lVert d_\perp\rVert)`, N(0, 1) under the baseline, with
   :math:`\hat\sigma = 1` with ``mu_std``, else :math:`\sqrt{RSS_0/(n - k_b)}` (Rao's score test).
4. **Global joint refit** of the candidate's free parameters together with the baseline's fitted ones
   (:func:`validation.refit.global_fit`: the given values and a seeded Halton design over the whole box, then
   bounded least squares from the best starts). The baseline's own refit is a start too, so the joint fit is
   never worse than the baseline.
5. **Information criterion.** :math:`BIC = \chi^2 + k \ln n` with ``mu_std``, else
   :math:`n \ln(RSS/n) + k \ln n` (sigma profiled out); :math:`k` counts fitted parameters that change the
   prediction (Schwarz, Ann. Stat. 6, 461 (1978)).
6. **Significance**: :math:`\Delta BIC < -10` ("very strong" on the Kass & Raftery scale, JASA 90, 773 (1995))
   **and** the likelihood-ratio test rejects the baseline at 1 %: with ``mu_std``
   :math:`\chi^2_0 - \chi^2_1 \sim \chi^2(k_c)`; without, the F test
   :math:`F = \frac{(RSS_0 - RSS_1)/k_c}{RSS_1/(n - k_b - k_c)}`. The test treats the candidate as nesting the
   baseline, which holds for effects that vanish at some parameter value and approximately otherwise.
7. **Uncertainty and plausibility** of every fitted parameter (:func:`validation.refit.with_uncertainty`), once
   the noise is known; a candidate with a parameter on a search bound or outside its plausible range is
   *implausible*: it can be significant, but never the diagnosis' explanation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from . import distributions
from .deferred import Deferred, Lazy
from .errors import InputError
from .fitting import Fitter, ParameterSpace, free_parameters, halton, release_placeholders
from .refit import GlobalFit, data_range, global_fit, plausible_start, with_uncertainty

__all__ = ["Baseline", "Candidate", "SIGNIFICANCE_RULE", "DELTA_BIC_THRESHOLD", "P_THRESHOLD", "bic",
           "fit_baseline", "fit_candidate", "finish_candidate", "FitSettings", "not_applicable", "note_kind",
           "NOTE_KINDS"]

#: G. Schwarz, Estimating the dimension of a model, Ann. Stat. 6, 461 (1978): the BIC.
SCHWARZ_1978 = "10.1214/aos/1176344136"
#: R. E. Kass, A. E. Raftery, Bayes factors, J. Am. Stat. Assoc. 90, 773 (1995): delta BIC > 10 is "very strong"
#: evidence.
KASS_RAFTERY_1995 = "10.1080/01621459.1995.10476572"

DELTA_BIC_THRESHOLD = -10.0
P_THRESHOLD = 0.01
SIGNIFICANCE_RULE = (f"significant when delta_BIC < {DELTA_BIC_THRESHOLD:g} and the likelihood-ratio test "
                     f"(chi2 with mu_std, else F) gives p < {P_THRESHOLD:g}")


@dataclass(frozen=True, eq=False)
class Baseline:
    """The baseline model after refitting its fitted parameters.

    Attributes
    ----------
    model : persson.Model
    effects : tuple of str
    fitted : dict
        Refitted baseline parameters, ``"effect.parameter" -> value``.
    predicted, residual : ndarray
    rmse : float
        Root-mean-square residual (unweighted) of the refitted baseline.
    rss : float
        Weighted residual sum of squares (chi2 with mu_std).
    bic : float
    n_params : int
        Fitted parameters counted in the BIC.
    sigma : float
        Residual standard deviation sqrt(RSS/(n - k)) (with mu_std: the rms of mu_std times sqrt(chi2/(n - k))).
    rmse_given : float
        RMSE of the model with the parameter values as given in the case (before the refit).
    contact : persson.slip.Contact or None
        The brush model's contact (refitted when ``contact.*`` parameters are fitted).
    estimates : tuple of validation.refit.Estimate
        The fitted parameters with their uncertainties (computed when first read where the fit deferred them:
        :func:`validation.refit.with_uncertainty` with ``defer=True``).
    lack : validation.noise.LackOfFit or None
    pattern : validation.noise.Pattern or None
    notes : tuple of str
        The fit's notes, those of its intervals included (computed with them).
    """

    model: object
    effects: tuple
    fitted: dict
    predicted: np.ndarray
    residual: np.ndarray
    rmse: float
    rss: float
    bic: float
    n_params: int
    sigma: float
    rmse_given: float
    contact: object = None
    estimates: tuple = Lazy(default=())
    lack: object = None
    pattern: object = None
    notes: tuple = Lazy(default=())
    fit: GlobalFit | None = field(default=None, repr=False)


@dataclass(frozen=True, eq=False)
class Candidate:
    """One candidate effect, refitted jointly with the baseline's parameters.

    Attributes
    ----------
    effect : str
    instance : persson.effects.Effect or None
        The effect with its refitted parameters.
    model : persson.Model or None
        Baseline + effect, everything refitted.
    parameters : dict
        The effect's documented parameters after the refit (placeholders at their placeholder value).
    free : tuple of str
        Parameters refitted (the others held at their given values).
    baseline_parameters : dict
        The baseline's fitted parameters, refitted jointly.
    rmse, rss, bic, delta_bic, p_value : float
    test : str
        ``"F"`` or ``"chi2"`` (likelihood-ratio test against the baseline).
    score_z, score_p : float
    cosine : float
        Correlation of the projected signature with the weighted baseline residual.
    explained : float
        Fraction of the baseline's weighted residual sum of squares removed.
    significant : bool
    status : str
        ``"ok"``, ``"no signature"`` or ``"failed: ..."``.
    signature, change, predicted : ndarray or None
    n_params : int
        Candidate parameters counted in the BIC.
    n_evals : int
    notes : tuple of str
        Fit warnings.
    estimates : tuple of validation.refit.Estimate
        The candidate's fitted parameters with uncertainties (``free`` order).
    baseline_estimates : tuple of validation.refit.Estimate
    plausible : bool
        False when a fitted parameter sits on a search bound or outside its plausible range.
    issues : tuple of str
        Why it is implausible.
    lack : validation.noise.LackOfFit or None
        Its residual tested against the noise.
    pattern : validation.noise.Pattern or None
        Systematic structure left in its residual.
    contact : persson.slip.Contact or None
    n_starts, n_good : int
        Local fits run; optima as good as the best among them.
    covariance : validation.refit.ParameterCovariance or None
        The joint covariance of every fitted parameter (the baseline's first), for the uncertainty band of the
        model's curves.
    jacobian : ndarray (rows, parameters) or None
        d mu / d u of the prediction at the optimum, in the coordinates of :attr:`covariance` (unweighted).
    fit : validation.refit.GlobalFit or None
        The joint fit with its uncertainty. In the diagnoses of a set search's steps
        (:func:`finish_candidate` with ``defer``) ``estimates``, ``baseline_estimates`` and ``notes`` may be computed
        when first read, from this fit's ``pending`` intervals.
    """

    effect: str
    instance: object
    model: object
    parameters: dict
    free: tuple
    baseline_parameters: dict
    rmse: float
    rss: float
    bic: float
    delta_bic: float
    p_value: float
    test: str
    score_z: float
    score_p: float
    cosine: float
    explained: float
    significant: bool
    status: str
    signature: np.ndarray | None = None
    change: np.ndarray | None = None
    predicted: np.ndarray | None = None
    n_params: int = 0
    n_evals: int = 0
    notes: tuple = Lazy(default=())
    estimates: tuple = Lazy(default=())
    baseline_estimates: tuple = Lazy(default=())
    plausible: bool = True
    issues: tuple = ()
    lack: object = None
    pattern: object = None
    contact: object = None
    n_starts: int = 0
    n_good: int = 0
    covariance: object = field(default=None, repr=False)
    jacobian: object = field(default=None, repr=False)
    fit: GlobalFit | None = field(default=None, repr=False)

    @property
    def credible(self) -> bool:
        """Significant and plausible: fit to be the diagnosis' explanation."""
        return self.status == "ok" and self.significant and self.plausible

    @property
    def not_identified(self) -> tuple:
        """Fitted parameters the data do not limit (68 % interval spanning the range searched)."""
        return tuple(e.name for e in self.estimates if not e.identified)

    @property
    def caveats(self) -> tuple:
        """Credible fitted parameters that deserve a second look, as ``"effect.parameter = value unit: why"``
        (:attr:`validation.refit.Estimate.caveat`)."""
        return GlobalFit.caveats_of(self.estimates)

    @property
    def identified(self) -> bool:
        """Whether the data limit every fitted parameter of the effect."""
        return not self.not_identified

    @property
    def applicable(self) -> bool:
        """False when the effect cannot act on these rows (e.g. wet without wet rows)."""
        return not self.status.startswith("not applicable")

    @property
    def placeholders(self) -> dict:
        """Parameters holding a placeholder (e.g. ``hurst = 0``, "fitted on the PSD"): name -> meaning."""
        out = {}
        for p in getattr(self.instance, "parameters", ()):
            s = getattr(p, "sentinel", None)
            if s is not None and self.parameters.get(p.name) == s:
                out[p.name] = f"{s:g}: {getattr(p, 'sentinel_doc', '') or 'placeholder'}"
        return out

    def as_dict(self) -> dict:
        """The candidate's entry of the ``persson diagnose --json`` ``candidates`` list.

        Returns
        -------
        dict
            ``effect``, ``rmse``, ``delta_bic``, ``significant``, ``parameters``, ``parameters_std``, ``intervals`` and
            ``estimates`` (by parameter name), ``placeholders``, ``plausible``, ``issues``, ``lack_of_fit_p``,
            ``remaining_pattern``, ``bic``, ``p_value``, ``test``, ``score_z``, ``score_p``, ``cosine``, ``explained``,
            ``free``, ``baseline_parameters``, ``baseline_parameters_std``, ``n_params``, ``n_starts``,
            ``n_good_starts``, ``status``, ``notes``, ``notes_detail``, ``identified`` and ``not_identified``.
        """
        est = {e.name: e for e in self.estimates}
        return {"effect": self.effect, "rmse": self.rmse, "delta_bic": self.delta_bic,
                "significant": bool(self.significant), "parameters": dict(self.parameters),
                "parameters_std": {k: e.std for k, e in est.items()},
                "intervals": {k: list(e.interval) for k, e in est.items()},
                "estimates": {k: e.as_dict() for k, e in est.items()},
                "placeholders": self.placeholders,
                "plausible": bool(self.plausible), "issues": list(self.issues),
                "lack_of_fit_p": None if self.lack is None else self.lack.p_value,
                "remaining_pattern": None if self.pattern is None else self.pattern.describe(),
                "bic": self.bic, "p_value": self.p_value, "test": self.test, "score_z": self.score_z,
                "score_p": self.score_p, "cosine": self.cosine, "explained": self.explained,
                "free": list(self.free), "baseline_parameters": dict(self.baseline_parameters),
                "baseline_parameters_std": {e.key: e.std for e in self.baseline_estimates},
                "n_params": self.n_params, "n_starts": self.n_starts, "n_good_starts": self.n_good,
                "status": self.status, "notes": list(self.notes),
                "notes_detail": [{"kind": note_kind(n), "text": n} for n in self.notes],
                "identified": [e.name for e in self.estimates if e.identified],
                "not_identified": list(self.not_identified)}


@dataclass(frozen=True, eq=False)
class FitSettings:
    """What every fit of one diagnosis shares.

    Attributes
    ----------
    predictor : validation.predict.Predictor
    y, w : ndarray
        Measured mu and weights 1/mu_std (ones without).
    sigma_known : bool
    seed : int
    n_local : int
        Local least-squares fits per global fit.
    max_evals : int or None
        Budget per fit (default ``40 + 25 k``).
    contact : persson.slip.Contact or None
    """

    predictor: object
    y: np.ndarray
    w: np.ndarray
    sigma_known: bool
    seed: int = 0
    n_local: int = 3
    max_evals: int | None = None
    contact: object = None

    @property
    def n(self) -> int:
        """Number of measured rows."""
        return self.y.size

    def budget(self, k: int) -> int:
        """Budget of model evaluations of a fit of ``k`` parameters: ``max_evals``, default ``40 + 25 k``."""
        return self.max_evals or 40 + 25 * k


@doi(SCHWARZ_1978)
def bic(rss: float, n: int, k: int, sigma_known: bool) -> float:
    r"""Schwarz's criterion for a Gaussian likelihood: :math:`\chi^2 + k\ln n` with known sigma, else
    :math:`n\ln(RSS/n) + k\ln n` (sigma profiled out) (Schwarz, Ann. Stat. 6, 461 (1978))."""
    if sigma_known:
        return float(rss + k * math.log(n))
    return float(n * math.log(max(rss, 1e-300) / n) + k * math.log(n))


# ==========================================================================================================
@dataclass(frozen=True, eq=False)
class BaselineFit:
    """The baseline's global fit before the noise is known (see :func:`fit_baseline`)."""

    model: object
    space: ParameterSpace
    fitter: Fitter | None
    fit: GlobalFit | None
    u: np.ndarray
    predicted: np.ndarray
    given: np.ndarray
    Q: np.ndarray
    k_eff: int
    rss: float
    contact: object
    n_evals: int
    searched: bool = True   # its parameters were searched globally here (False: polished from a previous fit)


def fit_baseline(model, space: ParameterSpace, settings: FitSettings, global_search: bool = True,
                 extra_starts=()) -> BaselineFit:
    """Refit of the baseline's ``space`` (none: the model as given): global, or a local polish of the given values
    (``global_search=False``, for values that come from a previous global fit); ``extra_starts`` (points in u)
    are fitted from besides (e.g. the values of a related fit)."""
    s = settings
    f_given = s.predictor.predict(model).mu
    evals = 1
    if len(space):
        fitter = Fitter(s.predictor, s.y, s.w, model, space, max_evals=s.budget(len(space)), contact=s.contact)
        u0 = space.u_of(model, s.contact)
        if global_search:
            fit = global_fit(fitter, u0, seed=s.seed, n_local=s.n_local, extra_starts=extra_starts)
        else:
            fit = global_fit(fitter, u0, seed=s.seed, n_screen=0, n_local=1, extra_starts=extra_starts)
        # the derivatives at the optimum belong to the result, not to the search: they never run out of budget
        fitter.max_evals = max(fitter.max_evals, fitter.n_evals + 2 * len(space))
        J = fitter.jacobian(fit.u) * s.w[:, None]
        evals += fitter.n_evals
        norms = np.linalg.norm(J, axis=0)
        keep = norms > 1e-10 * max(float(norms.max()), 1e-300)
        Q = np.linalg.qr(J[:, keep])[0] if np.any(keep) else np.zeros((s.n, 0))
        return BaselineFit(model=fit.model, space=space, fitter=fitter, fit=fit, u=fit.u, predicted=fit.mu,
                           given=f_given, Q=Q, k_eff=int(keep.sum()),
                           rss=float(np.sum(((s.y - fit.mu) * s.w) ** 2)), contact=fit.contact, n_evals=evals,
                           searched=global_search)
    return BaselineFit(model=model, space=space, fitter=None, fit=None, u=np.zeros(0), predicted=f_given,
                       given=f_given, Q=np.zeros((s.n, 0)), k_eff=0, rss=float(np.sum(((s.y - f_given) * s.w) ** 2)),
                       contact=s.contact, n_evals=evals)


@dataclass(frozen=True, eq=False)
class Trial:
    """A candidate after its global fit, before the noise is known (see :func:`fit_candidate`)."""

    effect: object
    free: tuple
    fitter: Fitter | None = None
    fit: GlobalFit | None = None
    signature: np.ndarray | None = None
    score_z: float = 0.0
    cosine: float = 0.0
    n_evals: int = 0
    notes: tuple = ()
    failed: Candidate | None = None


def fit_candidate(eff, base: BaselineFit, settings: FitSettings, names=None) -> Trial:
    """Signature, score test and global joint fit of one candidate effect (module docstring, items 2-4)."""
    s = settings
    name = eff.name
    bic0 = bic(base.rss, s.n, base.k_eff, s.sigma_known)
    if getattr(eff, "error", None):
        return Trial(effect=eff, free=(), failed=_failed(name, eff.error, bic0))
    why = not_applicable(eff, s.predictor.measurements, s.contact)
    if why:
        return Trial(effect=eff, free=(), failed=_failed(name, why, bic0, status="not applicable"))
    scale = max(float(np.max(np.abs(s.y))), 1e-12)
    tiny = 1e-9 * scale
    f0 = base.predicted
    try:
        model_c = base.model.with_effect(eff)
        cand = free_parameters(eff, names=names)
    except Exception as exc:  # noqa: BLE001  (a user effect may refuse the model)
        return Trial(effect=eff, free=(), failed=_failed(name, str(exc), bic0))
    notes: dict[str, None] = {}
    probe = Fitter(s.predictor, s.y, s.w, model_c, ParameterSpace(cand), max_evals=8, contact=base.contact)
    u_c0 = probe.space.u_of(model_c, base.contact)
    f_sig = probe.mu(u_c0)
    spent = 0   # evaluations of a probe given up for another
    if f_sig is None and names is None:
        # a placeholder this case cannot compute (Microtexture.hurst on a PSD table that ends at its roll-off):
        # the parameter is fitted over its plausible range instead
        released = _released_probe(eff, base, s)
        if released is not None:
            error = "; ".join(list(probe.errors)[:1]) or "evaluation failed"
            spent = probe.n_evals
            if released[5] is None:     # it fails there too: the first failure is the one to report
                spent += released[3].n_evals
            else:
                eff, model_c, cand, probe, u_c0, f_sig, starts = released
                notes.update(dict.fromkeys(_released_notes(eff, cand, starts, error)))
    if f_sig is None:
        return Trial(effect=eff, free=(), n_evals=spent + probe.n_evals,
                     failed=_failed(name, "; ".join(list(probe.errors)[:2]) or "evaluation failed", bic0,
                                    spent + probe.n_evals))
    d = f_sig - f0
    if np.max(np.abs(d)) <= tiny and names is None:
        released = free_parameters(eff, release=True)
        if len(released) > len(cand):
            cand = released
            probe = Fitter(s.predictor, s.y, s.w, model_c, ParameterSpace(cand), max_evals=8 + probe.n_evals,
                           contact=base.contact)
            u_c0 = probe.space.u_of(model_c, base.contact)
            notes["no signature at the given values: parameters on their bounds released"] = None
    z, cos = _score(d, s, base, scale)
    kc = len(cand)
    if kc:
        probe.screen(list(halton(kc, 2, seed=s.seed)))
    if (probe.max_change(f0) if kc else float(np.max(np.abs(d)))) <= tiny:
        return Trial(effect=eff, free=tuple(q.name for q in cand), n_evals=spent + probe.n_evals,
                     failed=_no_signature(name, model_c, cand, d, f0, s, bic0, base.rss,
                                          spent + probe.n_evals))
    evals = spent + probe.n_evals
    space = base.space + ParameterSpace(cand)
    fitter = Fitter(s.predictor, s.y, s.w, model_c, space, max_evals=s.budget(len(space)), contact=base.contact)
    fitter.adopt(probe, base.u)
    u_given = np.concatenate([base.u, u_c0])
    try:
        # after a global search of the baseline's parameters, the design varies the candidate's own (the
        # baseline's stay at their optimum in the screen; every local fit is joint)
        dims = None if base.searched else np.arange(len(base.space), len(space))
        extra = ()
        if not base.searched and len(base.space):
            # the baseline's values come from a fit without this candidate (a set of the improvement loop): one of
            # them on a bound, a physical limit or out of its plausible range may have stood in for the candidate
            # (a flash temperature held at q_m = q0 while it did an adhesion's work), and the screen does not move
            # them; one more start has them in the middle of their plausible ranges
            fresh = plausible_start(space, u_given, data_range(s.predictor.measurements, base.model.material),
                                    dims=range(len(base.space)), limits=True)
            extra = () if fresh is None else (fresh,)
        fit = global_fit(fitter, u_given, seed=s.seed, n_local=s.n_local, screen_dims=dims, extra_starts=extra)
    except InputError as exc:
        return Trial(effect=eff, free=(), n_evals=evals + fitter.n_evals,
                     failed=_failed(name, str(exc), bic0, evals + fitter.n_evals))
    notes.update(dict.fromkeys(fit.notes))
    return Trial(effect=eff, free=tuple(q.name for q in cand), fitter=fitter, fit=fit, signature=d, score_z=z,
                 cosine=cos, n_evals=evals + fitter.n_evals, notes=tuple(notes))


def _released_probe(eff, base: BaselineFit, settings: FitSettings):
    """The first evaluation of :func:`fit_candidate` again with the placeholders of ``eff`` released
    (:func:`validation.fitting.release_placeholders`): ``(effect, model, free parameters, probe, u, mu, starts)``,
    ``mu`` None where the model fails there too; None where ``eff`` holds no placeholder it can leave."""
    s = settings
    released = release_placeholders(eff)
    if released is None:
        return None
    eff_r, names_r, starts = released
    try:
        model_r = base.model.with_effect(eff_r)
        cand_r = free_parameters(eff_r, names=names_r)
    except Exception:  # noqa: BLE001  (a user effect may refuse the value)
        return None
    probe = Fitter(s.predictor, s.y, s.w, model_r, ParameterSpace(cand_r), max_evals=8, contact=base.contact)
    u0 = probe.space.u_of(model_r, base.contact)
    return eff_r, model_r, cand_r, probe, u0, probe.mu(u0), starts


def _released_notes(eff, free, starts: dict, error: str) -> list[str]:
    """What a candidate's notes say of the placeholders :func:`_released_probe` released (``free``: its free
    parameters, which carry the ranges searched)."""
    specs = {p.name: p for p in eff.parameters}
    ranges = {q.name: (q.lo, q.hi) for q in free}
    return [f"{eff.name}.{name}: its placeholder ({specs[name].sentinel_doc or 'computed'}) cannot be computed on "
            f"these data ({error}); fitted over its plausible range {ranges[name][0]:g} - {ranges[name][1]:g} "
            "instead" for name in starts]


def finish_candidate(trial: Trial, base: BaselineFit, settings: FitSettings, *, s2: float, ranges,
                     profile: bool, lack_of_fit, pattern_of, budget: int | None = None,
                     dof: float = math.inf, defer95: bool = False, defer: bool = False,
                     on_evals=None) -> Candidate:
    """Statistics, uncertainty and plausibility of a fitted candidate (module docstring, items 5-7).

    ``lack_of_fit(residual, k)`` and ``pattern_of(residual)`` test a residual against the noise; ``dof``: the
    degrees of freedom of ``s2``; ``defer95``, ``on_evals``: the 95 % intervals computed when first read
    (:func:`validation.refit.with_uncertainty`); ``defer``: all the intervals (the candidate's ``estimates``,
    ``baseline_estimates`` and ``notes``) of a candidate with no parameter on a search bound or outside its
    plausible range; one with such a parameter has them computed at once, for its plausibility.
    """
    if trial.failed is not None:
        return trial.failed
    s = settings
    n = s.n
    name = trial.effect.name
    kb = len(base.space)
    misfit = not lack_of_fit(s.y - trial.fit.mu, base.k_eff + len(trial.free)).consistent
    fit = with_uncertainty(trial.fitter, trial.fit, s2=s2, ranges=ranges, profile=profile, misfit=misfit,
                           budget=budget, dof=dof, defer95=defer95, defer=defer, on_evals=on_evals)
    f1 = fit.mu
    r1 = s.y - f1
    rss0, rss1 = base.rss, float(np.sum((r1 * s.w) ** 2))
    jac_c = fit.jacobian[:, kb:]
    kc = len(trial.free)
    k_eff_c = kc
    if jac_c.shape[1]:
        norms = np.linalg.norm(jac_c, axis=0)
        k_eff_c = int(np.sum(norms > 1e-8 * max(float(norms.max()), 1e-300))) or kc
    k1 = base.k_eff + k_eff_c
    bic0 = bic(rss0, n, base.k_eff, s.sigma_known)
    bic1 = bic(rss1, n, k1, s.sigma_known)
    p = _likelihood_ratio_p(rss0, rss1, max(k_eff_c, 1), n - k1, s.sigma_known)
    dbic = bic1 - bic0
    significant = bool(dbic < DELTA_BIC_THRESHOLD and p < P_THRESHOLD)
    inst = fit.model.effect(name)
    lack = lack_of_fit(r1, k1)
    if fit.pending is None:
        issues = fit.issues
        notes = tuple(dict.fromkeys(trial.notes + fit.notes))
        estimates, baseline_estimates = fit.estimates[kb:], fit.estimates[:kb]
    else:
        pending = fit.pending
        # bare estimates flag every parameter on a bound or outside its range, a superset of the issues the intervals
        # leave: without any, the candidate is plausible; with one, all its intervals are computed now, so that the
        # judgement is that of the full estimates (the same profiles, within the same budget)
        issues = fit.issues_of(pending()[0]) if any(e.issue for e in fit.estimates) else ()
        notes = Deferred(lambda: tuple(dict.fromkeys(trial.notes + pending()[1])))
        estimates, baseline_estimates = Deferred(lambda: pending()[0][kb:]), Deferred(lambda: pending()[0][:kb])
    return Candidate(effect=name, instance=inst, model=fit.model, parameters=_effect_params(inst),
                     free=trial.free, baseline_parameters=base.space.values(fit.model, fit.contact) if kb else {},
                     rmse=float(np.sqrt(np.mean(r1 ** 2))), rss=rss1, bic=bic1, delta_bic=float(dbic), p_value=p,
                     test="chi2" if s.sigma_known else "F", score_z=trial.score_z,
                     score_p=float(2 * distributions.norm_sf(abs(trial.score_z))), cosine=trial.cosine,
                     explained=float(1.0 - rss1 / rss0) if rss0 > 0 else 0.0, significant=significant, status="ok",
                     signature=trial.signature, change=f1 - base.predicted, predicted=f1, n_params=k_eff_c,
                     n_evals=trial.n_evals + fit.n_evals - trial.fit.n_evals, notes=notes,
                     estimates=estimates, baseline_estimates=baseline_estimates, plausible=not issues,
                     issues=issues, lack=lack, pattern=pattern_of(r1), contact=fit.contact,
                     n_starts=fit.n_starts, n_good=fit.n_good, covariance=fit.covariance,
                     jacobian=fit.jacobian if fit.covariance is not None else None, fit=fit)


# ==========================================================================================================
def _score(d, s: FitSettings, base: BaselineFit, scale: float) -> tuple[float, float]:
    """Score statistic and cosine of the projected signature against the weighted baseline residual."""
    rw = (s.y - base.predicted) * s.w
    dw = d * s.w
    Q = base.Q
    dperp = dw - Q @ (Q.T @ dw) if Q.shape[1] else dw
    nd, nr = float(np.linalg.norm(dperp)), float(np.linalg.norm(rw))
    if nd <= 1e-12 * max(scale, 1.0):
        return 0.0, 0.0
    sigma = 1.0 if s.sigma_known else math.sqrt(base.rss / max(s.n - base.k_eff, 1))
    return float(dperp @ rw) / (sigma * nd), (float(dperp @ rw) / (nd * nr) if nr > 0 else 0.0)


def _likelihood_ratio_p(rss0, rss1, dfc, dfd, sigma_known) -> float:
    if rss1 >= rss0:
        return 1.0
    if sigma_known:
        return distributions.chi2_sf(rss0 - rss1, dfc)
    F = ((rss0 - rss1) / dfc) / max(rss1 / max(dfd, 1), 1e-300)
    return distributions.f_sf(F, dfc, max(dfd, 1))


def not_applicable(effect, measurements, contact) -> str:
    """Why ``effect`` cannot act on these rows ("" when it can): the wet effect without wet rows, patch heating
    without a contact patch (no slip rows and no ``[contact]``)."""
    from persson.effects import PatchHeating, Wet

    if isinstance(effect, Wet) and not np.any(measurements.wet):
        return "no wet rows: the wet effect acts on rows measured wet only"
    if isinstance(effect, PatchHeating) and contact is None:
        return ("no contact patch: patch heating acts along the contact of a wheel, and these data have no slip "
                "rows and no [contact]")
    return ""


#: Machine-readable kinds of the notes a fit or a diagnosis attaches (the first pattern found in the text).
NOTE_KINDS = (
    ("budget", ("budget of model evaluations", "ran out of model evaluations")),
    ("model_failed", ("the model failed",)),
    ("misfit_in_errors", ("Birge ratio",)),
    ("other_optimum", ("another local optimum",)),
    ("refined_search", ("made again with the engine's quadrature-error estimate",)),
    ("released_bounds", ("parameters on their bounds released",)),
    ("no_signature", ("changes no prediction",)),
    ("extrapolated_psd", ("PSD tail extrapolated", "extrapolated past")),
    ("convergence", ("ConvergenceWarning", "did not converge")),
    ("accuracy", ("AccuracyWarning", "quadrature error")),
    ("physics", ("PhysicsWarning",)),
    ("patch_table", ("patch_heating:",)),
)


def note_kind(text: str) -> str:
    """The kind of a note (:data:`NOTE_KINDS`), ``"other"`` when none matches."""
    for kind, patterns in NOTE_KINDS:
        if any(p in text for p in patterns):
            return kind
    return "other"


def _failed(name: str, msg: str, bic0: float, evals: int = 0, status: str = "failed") -> Candidate:
    return Candidate(effect=name, instance=None, model=None, parameters={}, free=(), baseline_parameters={},
                     rmse=math.nan, rss=math.nan, bic=math.nan, delta_bic=math.inf, p_value=1.0, test="-",
                     score_z=0.0, score_p=1.0, cosine=0.0, explained=0.0, significant=False,
                     status=f"{status}: {msg}", n_evals=evals)


def _no_signature(name, model_c, cand, d, f0, s: FitSettings, bic0, rss0, evals) -> Candidate:
    r = s.y - f0
    inst = model_c.effect(name)
    return Candidate(effect=name, instance=inst, model=model_c, parameters=_effect_params(inst),
                     free=tuple(q.name for q in cand), baseline_parameters={}, rmse=float(np.sqrt(np.mean(r ** 2))),
                     rss=rss0, bic=bic0, delta_bic=0.0, p_value=1.0, test="chi2" if s.sigma_known else "F",
                     score_z=0.0, score_p=1.0, cosine=0.0, explained=0.0, significant=False, status="no signature",
                     signature=d, change=np.zeros_like(f0), predicted=f0, n_params=0, n_evals=evals,
                     notes=("switching it on changes no prediction for these measurements",))


def _effect_params(e) -> dict:
    out = {}
    for p in getattr(e, "parameters", ()):
        v = getattr(e, p.name, None)
        if isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool):
            out[p.name] = float(v)
    return out
