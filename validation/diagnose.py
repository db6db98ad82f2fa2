r"""Diagnosis of the physical effect missing from a model, with a verdict a user can trust.

For a baseline model and measurements:

1. **Baseline** (:mod:`validation.candidates`): its fitted parameters (``[model] fit``: effect parameters,
   ``gamma``, ``contact.*``) are refitted globally (multi-start, :mod:`validation.refit`).
2. **Candidates**: every registered effect not in the model (or the ``candidates`` given): signature, score test,
   global joint refit with the baseline's parameters, BIC and likelihood-ratio test
   (:data:`SIGNIFICANCE_RULE`).
3. **Noise** (:mod:`validation.noise`), independent of the models judged: ``mu_std``, else replicate rows, else
   local differences along the series (on the data minus the best-fitting model's smooth prediction, which only
   removes curvature). Every model (the baseline and each candidate) gets a lack-of-fit test against it and a
   search for systematic patterns left in its residual.
4. **Uncertainty and plausibility** of every fitted parameter (standard errors scaled by the noise, profile
   likelihood where needed; search bounds and declared plausible ranges).
5. **Ranking** by :math:`\Delta BIC` (best first; candidates without a signature have 0, failed ones come last),
   **ambiguity clusters** of near-parallel signatures with the conditions that would separate them
   (:mod:`validation.ambiguity`), and close calls (:math:`|\Delta BIC|` within 10 of each other).
6. **Verdict** (:mod:`validation.verdict`): ``nothing_missing``, ``explained``, ``partly_explained`` or
   ``unexplained``, stated first in the explanation, the text and the JSON.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from .ambiguity import COSINE_THRESHOLD, Ambiguity, Separation, clusters as find_clusters, separate
from .calibration import SetFit, check_calibration
from .candidates import (DELTA_BIC_THRESHOLD, P_THRESHOLD, SIGNIFICANCE_RULE, Baseline, BaselineFit, Candidate,
                         FitSettings, bic, finish_candidate, fit_baseline, fit_candidate, note_kind)
from .compare import json_text
from .contact_refit import defer_calibration, refit_contact, with_slip_offset
from .deferred import Deferred, Lazy
from .errors import InputError
from .fitting import CONTACT, FreeParameter, ParameterSpace, contact_parameters, free_parameters
from .localize import localize_misfit
from .measurements import Measurements
from .noise import NoiseEstimate, estimate_noise, lack_of_fit, remaining_pattern
from .outliers import outlying_rows
from .predict import Predictor, mostly_extrapolated
from .refit import data_range, issues_at, with_uncertainty
from .verdict import (MISSES, Verdict, decide, explain, with_calibration, with_localized, with_noise_trend,
                      with_outliers)

__all__ = ["Diagnosis", "Baseline", "Candidate", "Ambiguity", "Separation", "diagnose_single", "SIGNIFICANCE_RULE",
           "DELTA_BIC_THRESHOLD", "P_THRESHOLD", "COSINE_THRESHOLD"]


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """Ranked candidate effects for a baseline and measurements, and the verdict.

    Attributes
    ----------
    measurements : Measurements
    contact : persson.slip.Contact or None
        The contact as given (the refitted one, when ``contact.*`` is fitted, is ``baseline.contact``).
    baseline : Baseline
    candidates : tuple of Candidate
        Best first (by delta_BIC).
    clusters : tuple of Ambiguity
    explanation : str
        Plain language: the verdict first, then the failure pattern and why the top effect fits it (written when
        first read where the baseline's intervals are deferred: a set search's later steps).
    rule : str
        The significance rule.
    sigma_known : bool
        Whether the likelihood uses mu_std.
    noise : float
        Noise level in mu: the independent estimate (``noise_estimate``); NaN without one (``null`` in the
        JSON; the verdict is then ``undetermined``).
    n_evaluations : int
        Model evaluations (each one prediction of every row).
    seconds : float
        Wall time.
    name : str
    verdict : validation.verdict.Verdict
    noise_estimate : validation.noise.NoiseEstimate
    modulus_extrapolated_share : ndarray or None
        Per row, the share of the refitted baseline's hysteresis that rests on the master curve's extrapolation
        beyond its measured frequencies (the explanation cautions where rows rest on it for more than half; JSON
        ``baseline.rows_mostly_extrapolated``); None when not known.
    calibration : validation.calibration.CalibrationCheck or None
        A gain and a zero offset of the measured mu fitted on the baseline and compared with the verdict's
        candidate (a rival is named in the verdict; JSON ``calibration``); with the set search, the selection's.
    outliers : validation.outliers.Outliers or None
        Rows farther from the verdict's model than noise would put any row (named in the verdict; JSON
        ``outliers``); None when there are none.
    localized : validation.localize.Localized or None
        ``unexplained`` and ``partly_explained``: the family of rows (sliding, with slip, wet) the verdict's model
        misses while it fits the other rows (named in the verdict; JSON ``localized``); None when the misfit does
        not sit in one family.
    n_diagnostic_evaluations : int
        The part of ``n_evaluations`` spent on what the diagnosis reports besides the fits: the separating
        measurements' predictions, the localization's refits and the contact's refit (the set search of
        :func:`validation.improve` sets its budgets from the fits alone).
    """

    measurements: Measurements
    contact: object
    baseline: Baseline
    candidates: tuple
    clusters: tuple
    explanation: str = Lazy()
    rule: str
    sigma_known: bool
    noise: float
    n_evaluations: int
    seconds: float
    name: str = ""
    verdict: Verdict | None = None
    noise_estimate: NoiseEstimate | None = None
    selection: object = None
    context: object = field(default=None, repr=False)
    modulus_extrapolated_share: np.ndarray | None = field(default=None, repr=False)
    calibration: object = field(default=None, repr=False)
    outliers: object = None
    localized: object = None
    n_diagnostic_evaluations: int = 0

    @property
    def n_fit_evaluations(self) -> int:
        """The model evaluations of the fits: ``n_evaluations`` less ``n_diagnostic_evaluations``."""
        return self.n_evaluations - self.n_diagnostic_evaluations

    @property
    def noise_known(self) -> bool:
        """Whether the noise level comes from an independent estimate."""
        return self.noise_estimate is not None and self.noise_estimate.known

    @property
    def citations(self) -> tuple:
        """References of the statistics (BIC, evidence scale, noise, pattern tests, and where the verdict places the
        misfit, its tests and the contact's refit) and of the physics of the baseline and the candidates."""
        from frictioncite import citations_of

        from .noise import estimate_noise, remaining_pattern
        from .verdict import decide

        effects = [type(c.instance) for c in self.candidates if c.instance is not None]
        placed = () if self.localized is None else (localize_misfit,) + (
            () if self.localized.contact is None else (refit_contact,))
        return citations_of(bic, decide, estimate_noise, remaining_pattern, *placed, type(self.baseline.model),
                            *(type(e) for e in self.baseline.model.effects), *effects)

    def references(self) -> list:
        """The :attr:`citations` as formatted references."""
        from frictioncite import references

        return references(self.citations)

    @property
    def top(self) -> Candidate | None:
        """The best-ranked candidate (None when there are none)."""
        return self.candidates[0] if self.candidates else None

    @property
    def significant(self) -> tuple:
        """The significant candidates, best first (plausible or not)."""
        return tuple(c for c in self.candidates if c.significant)

    @property
    def best(self) -> Candidate | None:
        """The best credible candidate: significant and plausible (None when there is none)."""
        return next((c for c in self.candidates if c.credible), None)

    @property
    def explaining(self) -> Candidate | None:
        """The candidate the verdict names (``explained`` or ``partly_explained``), else None."""
        return self.candidate(self.verdict.effect) if self.verdict and self.verdict.effect else None

    def candidate(self, name: str) -> Candidate:
        """The candidate of effect ``name``.

        Returns
        -------
        Candidate

        Raises
        ------
        InputError
            No candidate has that name.
        """
        for c in self.candidates:
            if c.effect == name:
                return c
        raise InputError(f"no candidate named {name!r}; candidates: {[c.effect for c in self.candidates]}")

    def as_dict(self) -> dict:
        """The ``persson diagnose --json`` layout.

        Top level: ``verdict``, ``noise``, ``noise_source``, ``lack_of_fit_p``, ``remaining_pattern`` (and
        ``verdict_effect``, ``verdict_reason``, ``close_call``, ``noise_dof``, ``noise_trend_exponent`` and
        ``noise_trend_p``: a scatter that changes with mu, :mod:`validation.noise`), then ``baseline`` (``rmse``,
        ``effects``, the BIC, the refitted parameters with ``parameters_std`` and ``intervals``, its lack of fit,
        the significance rule, the explanation, the cost) and ``candidates``, best first: ``effect``, ``rmse``,
        ``delta_bic``, ``significant``, ``parameters``, ``parameters_std``, ``intervals``, ``plausible``,
        ``issues``, the test statistics and, for members of an ambiguity cluster, ``ambiguity``; ``calibration``
        (:meth:`validation.calibration.CalibrationCheck.as_dict`; with the set search, the selection's) and
        ``outliers`` (:meth:`validation.outliers.Outliers.as_dict`, None when there are none) and ``localized``
        (:meth:`validation.localize.Localized.as_dict`, None when the misfit does not sit in one family of rows).
        """
        b = self.baseline
        v = self.verdict
        ne = self.noise_estimate
        amb = {}
        for cl in self.clusters:
            for e in cl.effects:
                amb[e] = cl.as_dict()
        cands = []
        for c in self.candidates:
            d = c.as_dict()
            if c.effect in amb:
                d["ambiguity"] = amb[c.effect]
            cands.append(d)
        out = {
            "verdict": v.verdict, "noise": self.noise if self.noise_known else None, "noise_source": ne.source,
            "lack_of_fit_p": v.lack_of_fit_p, "remaining_pattern": v.remaining_pattern,
            "verdict_effect": v.effect, "verdict_effects": list(v.effects),
            "verdict_alternatives": list(v.alternatives), "verdict_reason": v.reason,
            "indicated": list(v.indicated), "not_identified": list(v.not_identified), "misfit_share": v.share,
            "closest": v.closest, "caveats": list(v.caveats),
            "close_call": list(v.close_call[:2]) + [v.close_call[2]] if v.close_call else None,
            "noise_dof": ne.dof, "noise_description": ne.description,
            "noise_trend_exponent": ne.trend, "noise_trend_p": ne.trend_p if math.isfinite(ne.trend_p) else None,
            "citations": list(self.citations), "references": self.references(),
            "baseline": {"rmse": b.rmse, "effects": list(b.effects), "bic": b.bic, "rss": b.rss,
                         "fitted": dict(b.fitted), "parameters_std": {e.key: e.std for e in b.estimates},
                         "intervals": {e.key: list(e.interval) for e in b.estimates},
                         "estimates": {e.key: e.as_dict() for e in b.estimates},
                         "contact": _contact_dict(b.contact),
                         "n_params": b.n_params, "sigma": b.sigma, "rmse_given": b.rmse_given,
                         "lack_of_fit": b.lack.as_dict(), "remaining_pattern": b.pattern.describe(),
                         "n": self.measurements.n, "noise": self.noise, "sigma_known": self.sigma_known,
                         "rule": self.rule, "explanation": self.explanation, "name": self.name,
                         "n_evaluations": self.n_evaluations,
                         "n_diagnostic_evaluations": self.n_diagnostic_evaluations, "seconds": self.seconds,
                         "notes": list(b.notes),
                         "notes_detail": [{"kind": note_kind(t), "text": t} for t in b.notes],
                         "rows_mostly_extrapolated": (None if self.modulus_extrapolated_share is None else
                                                      int(mostly_extrapolated(self.modulus_extrapolated_share).size))},
            "candidates": cands,
            "calibration": None if self.calibration is None else self.calibration.as_dict(),
            "outliers": None if self.outliers is None else self.outliers.as_dict(),
            "localized": None if self.localized is None else self.localized.as_dict(),
        }
        if self.selection is not None:
            out.update(self.selection.as_dict())
        return out

    def to_dict(self) -> dict:
        """Alias of :meth:`as_dict` (the ``--json`` layout)."""
        return self.as_dict()

    def to_json(self, path=None, *, overwrite: bool = False) -> str:
        """JSON text of :meth:`as_dict`; written atomically to ``path`` when given (an existing file only with
        ``overwrite=True``)."""
        return json_text(self.as_dict(), path, overwrite=overwrite)

    def table_text(self) -> str:
        """The verdict line, then the ranking as aligned plain text."""
        b = self.baseline
        lines = [self.verdict.headline,
                 (f"noise {self.noise:.3g} ({self.noise_estimate.source})" if self.noise_known else
                  "noise unknown (no independent estimate)") + "; baseline "
                 f"{list(b.effects) or ['(hysteresis only)']}: RMSE {b.rmse:.4g}, lack-of-fit p = "
                 f"{b.lack.p_value:.2g}".replace("nan", "- (no test)")
                 + (f", fitted {', '.join(e.describe() for e in b.estimates)}" if b.estimates else ""),
                 f"{'rank':<5}{'effect':<20}{'RMSE':>9}{'dBIC':>10}{'p':>10}{'LOF p':>9}  {'sig':<4}{'plaus':<6}"
                 "parameters (+- standard error)"]
        for i, c in enumerate(self.candidates, 1):
            if c.status != "ok":
                lines.append(f"{i:<5}{c.effect:<20}{'-':>9}{'-':>10}{'-':>10}{'-':>9}  {'no':<4}{'-':<6}({c.status})")
                continue
            lof = f"{c.lack.p_value:>9.2g}" if self.noise_known else f"{'-':>9}"
            par = ", ".join(e.describe() for e in c.estimates) or "no free parameters"
            lines.append(f"{i:<5}{c.effect:<20}{c.rmse:>9.4g}{c.delta_bic:>+10.1f}{c.p_value:>10.2g}"
                         f"{lof}  {'YES' if c.significant else 'no':<4}"
                         f"{'yes' if c.plausible else 'NO':<6}{par}")
        return "\n".join(lines)

    def text(self) -> str:
        """What ``persson diagnose`` prints: the verdict and the ranking, then the explanation (and, with the set
        search, the sets of effects)."""
        txt = self.table_text() + "\n\n" + self.explanation
        if self.selection is not None:
            txt += "\n\n" + self.selection.text()
        return txt

    def summary(self) -> str:
        """The same as :meth:`text`."""
        return self.text()

    def figures(self) -> dict:
        """Matplotlib figures (Agg) of the diagnosis.

        Returns
        -------
        dict
            ``"signatures"``: the baseline residual and the refitted changes of the top candidates; ``"residual_slip"``
            (when slip rows exist): the residual against the slip ratio. Each value a ``matplotlib.figure.Figure``.
        """
        from . import plots

        figs = {"signatures": plots.plot_signatures(self)}
        if self.measurements.has_slip_rows:
            figs["residual_slip"] = plots.plot_residual_slip(self)
        return figs


# ==========================================================================================================
def diagnose_single(model, measurements: Measurements | None = None, candidates=None, contact=None, *, fit=None,
                    parameters: dict | None = None, n_starts: int = 3, seed: int = 0, probe: bool = True,
                    name: str = "", max_evals: int | None = None, noise: NoiseEstimate | None = None,
                    refit_baseline: bool = True, progress=None, predictor=None,
                    check_conditions: bool = True, defer95: bool = False, defer_baseline: bool = False,
                    defer_candidates: bool = False, on_evals=None) -> Diagnosis:
    """Each candidate effect added alone to ``model``, ranked, and the verdict: :func:`validation.diagnose` with
    ``search="single"`` (its parameters, less ``search``). ``check_conditions=False`` leaves out the fits of a
    temperature offset and a speed factor in the calibration check (:mod:`validation.calibration`), for a diagnosis
    whose answer a set search judges again. ``defer95``: the 95 % intervals are computed when first read, and
    ``on_evals`` is told the model evaluations they spend then (they are not in ``n_evaluations``), for the
    diagnoses of a set search's steps, which report 68 % intervals only; ``defer_baseline``: the baseline's
    intervals too, and the explanation that shows them (a step's baseline is the set the search fitted already);
    ``defer_candidates``: the candidates' intervals too (:func:`validation.candidates.finish_candidate` with
    ``defer``), computed when read: the verdict reads those of the candidate it names, a set search those of the
    sets it reports."""
    t_start = time.perf_counter()
    model, measurements, contact, fit, name = _unpack(model, measurements, contact, fit, name)
    from persson.effects import Effect, available

    m = measurements
    if predictor is None or predictor.measurements is not m:
        predictor = Predictor(m, contact)
    sigma_known = m.mu_std is not None
    # a noise that changes with mu (validation.noise: trend) weights each row by it, relative to the reference level
    weighted = not sigma_known and noise is not None and noise.known and noise.trend != 0.0
    w = 1.0 / m.mu_std if sigma_known else (noise.sigma / noise.row_sigma if weighted else np.ones(m.n))
    settings = FitSettings(predictor=predictor, y=m.mu, w=w,
                           sigma_known=sigma_known, seed=seed, n_local=max(1, n_starts), max_evals=max_evals,
                           contact=contact)
    parameters = dict(parameters or {})
    ranges = data_range(m, model.material)

    base_space = ParameterSpace(_baseline_params(model, _fit_names(fit, model), contact))
    base = fit_baseline(model, base_space, settings, global_search=refit_baseline)
    effects = _candidates(candidates, model, available, Effect)
    trials = []
    t_fits = time.perf_counter()
    for i, eff in enumerate(effects):
        if progress is not None:
            left = ("" if i == 0 else
                    f", about {(time.perf_counter() - t_fits) / i * (len(effects) - i):.0f} s left")
            progress(f"fitting {eff.name}{left}", i, len(effects))
        trials.append(fit_candidate(eff, base, settings, parameters.get(eff.name)))
    n_eval = base.n_evals + sum(t.n_evals for t in trials)

    if noise is None:
        noise = _estimate_noise(m, base, trials)
        if not sigma_known and noise.known and noise.trend != 0.0:
            # the fits were made with one noise level for every row; they are made again, each row weighted by its
            # own (the noise estimated here), and both passes are counted
            dx = diagnose_single(model, m, candidates, contact, fit=fit, parameters=parameters, n_starts=n_starts,
                                 seed=seed, probe=probe, name=name, max_evals=max_evals, noise=noise,
                                 refit_baseline=refit_baseline, progress=progress, predictor=predictor,
                                 check_conditions=check_conditions, defer95=defer95, defer_baseline=defer_baseline,
                                 defer_candidates=defer_candidates, on_evals=on_evals)
            return replace(dx, n_evaluations=dx.n_evaluations + n_eval, seconds=time.perf_counter() - t_start)
    ctx = FitContext(settings=settings, noise=noise, ranges=ranges, measurements=m,
                     s2=1.0 if sigma_known else (noise.sigma ** 2 if noise.known else
                                                 base.rss / max(m.n - base.k_eff, 1)),
                     dof=math.inf if sigma_known else (noise.dof if noise.known else max(m.n - base.k_eff, 1)))
    s2, lof, pattern = ctx.s2, ctx.lack_of_fit, ctx.pattern
    baseline = ctx.finish(base, defer=defer_baseline, defer95=defer95, on_evals=on_evals)
    n_eval += baseline.fit.n_evals - base.fit.n_evals if base.fit is not None else 0
    bic0 = baseline.bic
    results = []
    contenders = _contenders(trials, base, bic0, m.n, sigma_known)
    for t in trials:
        # profile likelihoods (costly) only where they can matter: the two best fits that look significant; a
        # small budget for one that is implausible anyway (its interval only says how far the data push it)
        profile = t in contenders
        k = len(t.fitter.space) if t.fitter is not None else 0
        budget = 14 * k if profile and issues_at(t.fitter, t.fit.u, ranges) else None
        c = finish_candidate(t, base, settings, s2=s2, ranges=ranges, profile=profile, lack_of_fit=lof, dof=ctx.dof,
                             pattern_of=pattern, budget=budget, defer95=defer95, defer=defer_candidates,
                             on_evals=on_evals)
        n_eval += c.n_evals - t.n_evals
        results.append(c)
    results.sort(key=lambda c: (_rank_group(c.status), c.delta_bic if math.isfinite(c.delta_bic) else math.inf))

    clusters = find_clusters(results, base.Q, settings.w)
    n_diagnostic = 0    # the evaluations of what is reported besides the fits (Diagnosis.n_diagnostic_evaluations)
    if probe and clusters:
        clusters, used = separate(clusters, results, m, contact)
        n_eval += used
        n_diagnostic += used
    verdict = decide(baseline, results, noise)
    named = next((c for c in results if c.effect == verdict.effect), None) if verdict.effect else None
    calibration = _calibration_check(named, baseline, ctx, conditions=check_conditions)
    verdict = with_calibration(verdict, calibration)
    outliers = _outliers(named, baseline, m, noise)
    spent = []          # the model evaluations of the localization's refits, placed or not
    localized = _localized(named, baseline, m, noise, refitted=tuple(_fit_names(fit, model)),
                           contact=contact, refit=verdict.verdict in MISSES, on_evals=spent.append)
    n_eval += sum(spent)
    n_diagnostic += sum(spent)
    if localized is not None and localized.family == "slip" and verdict.verdict in MISSES:
        localized = _with_contact_refit(localized, named, baseline, ctx, contact, calibration)
        refit_evals = localized.contact.n_evals if localized.contact is not None else 0
        n_eval += refit_evals
        n_diagnostic += refit_evals
        # an offset of the slip ratios the refitted contact fits better is no longer the rig's rival
        calibration = defer_calibration(calibration, localized.contact)
        verdict = with_calibration(verdict, calibration)
    verdict = with_noise_trend(with_localized(with_outliers(verdict, outliers), localized), noise)
    localized = localized if verdict.localized else None
    # the baseline at its optimum again, in full: its solutions are kept by the predictor, so this costs no solve
    extrapolated = predictor.predict(baseline.model, full=True).modulus_extrapolated_share
    explanation = Deferred(lambda: explain(verdict, m, baseline, results, clusters, noise,
                                           extrapolated_share=extrapolated))
    if not defer_baseline:
        explanation = explanation()
    if progress is not None:
        progress(f"{len(effects)} candidates fitted", len(effects), len(effects))
    return Diagnosis(measurements=m, contact=contact, baseline=baseline, candidates=tuple(results),
                     clusters=tuple(clusters), explanation=explanation, rule=SIGNIFICANCE_RULE,
                     sigma_known=sigma_known, noise=_noise_level(noise), n_evaluations=n_eval,
                     seconds=time.perf_counter() - t_start, name=name, verdict=verdict, noise_estimate=noise,
                     context=ctx, modulus_extrapolated_share=extrapolated, calibration=calibration,
                     outliers=outliers, localized=localized, n_diagnostic_evaluations=n_diagnostic)


def _outliers(named, baseline, measurements, noise):
    """The rows far from the verdict's model (that of ``named``, the candidate the verdict names, else the
    baseline): :func:`validation.outliers.outlying_rows`."""
    if named is not None and named.predicted is not None:
        return outlying_rows(measurements.mu - named.predicted, noise, measurements,
                             f"the baseline + {named.effect}")
    return outlying_rows(measurements.mu - baseline.predicted, noise, measurements, "the baseline")


def _localized(named, baseline, measurements, noise, refitted=(), contact=None, refit=False, on_evals=None):
    """The family of rows the verdict's model (that of ``named``, else the baseline) misses while it fits the
    others: :func:`validation.localize.localize_misfit` (``refitted``: the baseline parameters refitted). With
    ``refit``, where no family is missed alone, also after a refit of the model's parameters to the rows outside
    each family (``contact``: the settings' contact, for a model fitted without one of its own; ``on_evals``: told
    the model evaluations of that refit)."""
    if named is not None and named.predicted is not None:
        refit = None if not refit else SetFit.of(named.model, named.contact or contact, named.covariance,
                                                 named.jacobian)
        return localize_misfit(measurements.mu - named.predicted, noise, measurements,
                               f"the baseline + {named.effect}", n_params=baseline.n_params + named.n_params,
                               refitted=refitted, refit=refit, on_evals=on_evals)
    fit = baseline.fit
    refit = None if not refit or fit is None else SetFit.of(baseline.model, baseline.contact or contact,
                                                            fit.covariance, fit.jacobian)
    return localize_misfit(measurements.mu - baseline.predicted, noise, measurements, "the baseline",
                           n_params=baseline.n_params, refitted=refitted, refit=refit, on_evals=on_evals)


def _with_contact_refit(localized, named, baseline, ctx, contact, calibration=None):
    """``localized`` (a misfit placed in the rows with slip) with the verdict's model (that of ``named``, else the
    baseline) refitted with the brush contact's stiffness and length: :func:`validation.contact_refit.refit_contact`
    (left as it is when the model's fit cannot be restarted), compared with the offset of the slip ratios that
    ``calibration`` fitted on the same model."""
    if named is not None and named.predicted is not None:
        start = SetFit.of(named.model, named.contact or contact, named.covariance, named.jacobian)
        if start is None:
            return localized
        model, at, space, predicted = named.model, named.contact or contact, start.space, named.predicted
    else:
        fit = baseline.fit
        if fit is not None and fit.covariance is None:
            return localized
        space = ParameterSpace(()) if fit is None else fit.covariance.space
        model, at, predicted = baseline.model, baseline.contact or contact, baseline.predicted
    effects = (named.effect,) if named is not None and named.predicted is not None else ()
    return replace(localized, contact=with_slip_offset(refit_contact(model, at, space, predicted, ctx), calibration,
                                                       effects))


def _calibration_check(named, baseline, ctx, conditions=True):
    """A gain and a zero offset of the measured mu on the baseline (and, with ``conditions``, an offset of the
    recorded temperatures, a factor on the recorded speeds and an offset of the slip ratios), against ``named``, the
    candidate the verdict names (the baseline itself when None); on top of ``named`` too when it misses the noise:
    :func:`validation.calibration.check_calibration`."""
    answer = ("(baseline)", (), baseline.bic) if named is None else (named.effect, (named.effect,), named.bic)
    sets = [("(baseline)", (), baseline.predicted, baseline.n_params, baseline.bic)]
    on_answer = named is not None and named.predicted is not None and not _at_noise(named)
    if on_answer:
        sets.append((named.effect, (named.effect,), named.predicted, named.n_params, named.bic))
    contact = ctx.settings.contact
    fit = baseline.fit
    refits = {frozenset(): SetFit.of(baseline.model, baseline.contact or contact,
                                     None if fit is None else fit.covariance, None if fit is None else fit.jacobian)}
    if named is not None:
        refits[frozenset((named.effect,))] = SetFit.of(named.model, named.contact or contact, named.covariance,
                                                       named.jacobian)
    return check_calibration(sets, answer, ctx,
                             baseline=(baseline.model, baseline.contact or contact, baseline.n_params,
                                       baseline.bic) if conditions else None,
                             conditions=[(named.effect, (named.effect,), named.model, named.contact or contact,
                                          named.n_params, named.bic)] if conditions and on_answer else (),
                             on_answer=on_answer, refits={k: r for k, r in refits.items() if r is not None})


def _at_noise(c) -> bool:
    """Whether the fit ``c`` (a candidate) leaves a residual consistent with the noise and no pattern."""
    return bool(c.lack is not None and c.lack.consistent and not (c.pattern is not None and c.pattern.found))


@dataclass(frozen=True, eq=False)
class FitContext:
    """What the fits of one diagnosis share once the noise is known (reused by the set search).

    Attributes
    ----------
    settings : validation.candidates.FitSettings
    noise : validation.noise.NoiseEstimate
    ranges : validation.refit.DataRange
    measurements : Measurements
    s2 : float
        Variance unit of the weighted chi2 for the uncertainties (1 with ``mu_std``, else the noise variance;
        the baseline's residual variance without a noise estimate).
    dof : float
        Degrees of freedom of ``s2`` (infinite with ``mu_std``; the noise estimate's, or the baseline residual's):
        the parameter intervals use Student's t quantiles with them (:func:`validation.refit.t_quantiles`).
    """

    settings: object
    noise: NoiseEstimate
    ranges: object
    measurements: Measurements
    s2: float
    dof: float = math.inf

    def lack_of_fit(self, residual, k):
        """The lack-of-fit test of ``residual`` (measured - predicted, per row), with ``k`` fitted parameters, against
        the noise.

        Returns
        -------
        validation.noise.LackOfFit
        """
        return lack_of_fit(residual, k, self.noise)

    def pattern(self, residual):
        """Systematic structure left in ``residual`` (measured - predicted, per row) beyond the noise.

        Returns
        -------
        validation.noise.Pattern
        """
        return remaining_pattern(residual, self.measurements, self.noise)

    def parameters(self, model, names) -> list[FreeParameter]:
        """The free parameters ``names`` (``"effect.parameter"``, ``"gamma"``, ``"contact.*"``) of ``model``."""
        return _baseline_params(model, _fit_names(names, model), self.settings.contact)

    def finish(self, base: BaselineFit, *, defer: bool = False, defer95: bool = False, on_evals=None) -> Baseline:
        """Uncertainties, lack of fit and pattern of a fitted model (a baseline, or a set of effects).

        ``defer``: the parameters' intervals are computed when first read (the baseline's ``estimates`` and
        ``notes``; ``fit.pending``, see :func:`validation.refit.with_uncertainty`); ``defer95``: only the 95 % ones;
        ``on_evals`` is called with the model evaluations they spent."""
        return _finish_baseline(base, self.settings, self.s2, self.ranges, self.lack_of_fit, self.pattern,
                                dof=self.dof, defer=defer, defer95=defer95, on_evals=on_evals)


# ==========================================================================================================
def _estimate_noise(m: Measurements, base: BaselineFit, trials) -> NoiseEstimate:
    """The independent noise estimate; the local one on the data minus the best-fitting prediction (smooth)."""
    best_chi2, reference = base.rss, base.predicted
    for t in trials:
        if t.fit is not None and t.fit.chi2 < best_chi2:
            best_chi2, reference = t.fit.chi2, t.fit.mu
    return estimate_noise(m, reference=reference)


def _contenders(trials, base: BaselineFit, bic0: float, n: int, sigma_known: bool) -> list:
    """The (at most two) fitted candidates with the lowest BIC among those that look significant."""
    scored = [(bic(t.fit.chi2, n, base.k_eff + len(t.free), sigma_known) - bic0, i) for i, t in enumerate(trials)
              if t.fit is not None]
    return [trials[i] for d, i in sorted(scored) if d < DELTA_BIC_THRESHOLD][:2]


def _finish_baseline(base: BaselineFit, settings: FitSettings, s2, ranges, lof, pattern,
                     dof: float = math.inf, defer: bool = False, defer95: bool = False,
                     on_evals=None) -> Baseline:
    fit = base.fit
    y, w, n = settings.y, settings.w, settings.n
    f0 = base.predicted
    r0 = y - f0
    lack = lof(r0, base.k_eff)
    if fit is not None:
        fit = with_uncertainty(base.fitter, fit, s2=s2, ranges=ranges, profile=True, misfit=not lack.consistent,
                               dof=dof, defer=defer, defer95=defer95, on_evals=on_evals)
    sigma_hat = math.sqrt(base.rss / max(n - base.k_eff, 1))
    sigma_mu = sigma_hat * float(np.sqrt(np.mean(1.0 / w ** 2))) if settings.sigma_known else sigma_hat
    pending = None if fit is None else fit.pending
    if pending is not None:
        # deferred: the estimates and the notes their intervals add, when first read
        estimates, notes = pending.part(0), pending.part(1)
    else:
        estimates, notes = (fit.estimates, tuple(fit.notes)) if fit is not None else ((), ())
    return Baseline(model=base.model, effects=tuple(base.model.effect_names),
                    fitted=base.space.values(base.model, base.contact) if len(base.space) else {}, predicted=f0,
                    residual=r0, rmse=float(np.sqrt(np.mean(r0 ** 2))), rss=base.rss,
                    bic=bic(base.rss, n, base.k_eff, settings.sigma_known), n_params=base.k_eff, sigma=sigma_mu,
                    rmse_given=float(np.sqrt(np.mean((y - base.given) ** 2))), contact=base.contact,
                    estimates=estimates, lack=lack, pattern=pattern(r0), notes=notes, fit=fit)


def _noise_level(noise: NoiseEstimate) -> float:
    """The independent noise level, NaN without one (a residual's own scatter is not a noise estimate)."""
    return float(noise.sigma) if noise.known else math.nan


def _rank_group(status: str) -> int:
    """Fitted candidates first (by delta BIC), then those without signature, not applicable, failed."""
    if status.startswith("failed"):
        return 2
    return 1 if status.startswith("not applicable") else 0


def _contact_dict(contact) -> dict | None:
    if contact is None:
        return None
    return {"length_m": contact.length, "width_m": contact.width, "stiffness_Pa_per_m": contact.stiffness,
            "pressure_distribution": contact.pressure_distribution
            if isinstance(contact.pressure_distribution, (str, dict)) else "custom"}


def _unpack(model, measurements, contact, fit, name):
    from .case import Case

    if isinstance(model, Case):
        case = model
        model = case.model
        measurements = case.measurements if measurements is None else measurements
        contact = case.contact if contact is None else contact
        fit = case.fit if fit is None else fit
        name = name or case.name
    if measurements is None:
        raise InputError("measurements: give the measurements (validation.read_measurements) or a Case")
    if not isinstance(measurements, Measurements):
        raise InputError(f"measurements: expected validation.Measurements, got {type(measurements).__name__}")
    if not hasattr(model, "effects") or not hasattr(model, "friction"):
        raise InputError(f"model: expected a persson.Model, got {type(model).__name__}")
    if contact is None:
        contact = measurements.contact
    return model, measurements, contact, tuple(fit or ()), name


def _fit_names(fit, model) -> tuple:
    from .case import parse_fit_names

    return parse_fit_names(list(fit), model, "fit")


def _baseline_params(model, fit_names, contact) -> list[FreeParameter]:
    out = []
    for key in fit_names:
        if key == "gamma":
            out.append(FreeParameter(effect="", name="gamma", lo=0.0, hi=1.0, log=False, unit="1",
                                     physical_limits=(0.0, 1.0)))
            continue
        eff, _, par = key.partition(".")
        if eff == CONTACT:
            out.extend(contact_parameters(contact, [par]))
        else:
            out.extend(free_parameters(model.effect(eff), names=[par]))
    return out


def _candidates(candidates, model, available, Effect) -> list:
    present = set(model.effect_names)
    out = []
    if candidates is None:
        for nm, cls in available().items():
            if nm in present:
                continue
            try:
                out.append(cls())
            except Exception as exc:  # noqa: BLE001
                out.append(_Broken(nm, f"cannot build {cls.__name__}() with default parameters: {exc}"))
        return out
    if isinstance(candidates, (str, Effect)):
        candidates = [candidates]
    seen = set()
    for c in candidates:
        if isinstance(c, str):
            from persson.effects import effect_class

            try:
                cls = effect_class(c)
            except ValueError as exc:
                raise InputError(f"candidates: {exc}") from None
            try:
                inst = cls()
            except Exception as exc:  # noqa: BLE001
                inst = _Broken(c, f"cannot build {cls.__name__}() with default parameters: {exc}")
        elif isinstance(c, Effect):
            inst = c
        elif isinstance(c, type) and issubclass(c, Effect):
            inst = c()
        else:
            raise InputError(f"candidates: expected effect names or persson.effects.Effect instances, got {c!r}")
        if inst.name in present:
            raise InputError(f"candidates: {inst.name!r} is already in the model (effects {sorted(present)})")
        if inst.name in seen:
            raise InputError(f"candidates: {inst.name!r} given twice")
        seen.add(inst.name)
        out.append(inst)
    return out


@dataclass(frozen=True)
class _Broken:
    """A candidate that could not even be built (reported as failed)."""

    name: str
    error: str
