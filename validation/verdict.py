"""The verdict of a diagnosis and its plain-language explanation.

Verdicts (the noise and the lack-of-fit test are those of :mod:`validation.noise`):

``"nothing_missing"``
    the baseline is consistent with the noise (no lack of fit, no systematic pattern) and no candidate is both
    significant and plausible;
``"explained"``
    a significant, plausible candidate whose parameters the data identify leaves a residual consistent with the
    noise and without pattern;
``"partly_explained"``
    a significant, plausible candidate removes a real share of the misfit -- at least :data:`PARTLY_SHARE` (a
    quarter) of the misfit above the noise (:func:`misfit_share`) -- but lack of fit or a pattern remains; or it
    brings the residual to the noise level while the data do not identify one of its parameters (its 68 %
    interval spans the range searched): the effect is indicated, not established;
``"unexplained"``
    the baseline fails beyond the noise and no candidate is both significant and plausible, or the best one
    removes less than :data:`PARTLY_SHARE` of the misfit above the noise (it is named as the closest); after
    :func:`validation.improve`, also when the best set found is not credible. A verdict that rests on a marginal
    misfit alone (:data:`MARGINAL_P` < p < 0.01, no pattern, no candidate significant) says that the noise may be
    underestimated;
``"undetermined"``
    there is no independent noise estimate (no ``mu_std``, no replicates, too few rows along series): the data
    cannot say whether anything is missing beyond the noise. Significant, plausible candidates are named as
    *indicated*, with the parameters the data do and do not identify.

A candidate is *plausible* when none of its fitted parameters sits on a search bound or outside the range its
:class:`persson.effects.Parameter` declares plausible; an implausible one can be significant but is never the
explanation. Two candidates whose BIC differ by less than :data:`CLOSE_CALL` are a close call, flagged whatever
their signatures (10 BIC units is "very strong" evidence on the scale of Kass & Raftery, J. Am. Stat. Assoc. 90,
773 (1995)).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace

import numpy as np

from frictioncite import doi

from .candidates import KASS_RAFTERY_1995, SIGNIFICANCE_RULE
from .predict import mostly_extrapolated

__all__ = ["Verdict", "decide", "explain", "VERDICTS", "CLOSE_CALL", "PARTLY_SHARE", "misfit_share",
           "with_calibration", "with_outliers", "with_noise_trend", "with_localized", "MISSES"]

#: Lack-of-fit p-values above this (and below the test's 0.01) are marginal: an ``unexplained`` verdict that rests
#: on such a misfit alone, with no pattern and no candidate taking it up, says the noise estimate may be low.
MARGINAL_P = 1e-3

VERDICTS = ("nothing_missing", "explained", "partly_explained", "unexplained", "undetermined")
#: The verdicts of a model that misses the data (its misfit is then placed: :func:`with_localized`).
MISSES = ("partly_explained", "unexplained")
#: Delta BIC below which the top two candidates are a close call.
CLOSE_CALL = 10.0
#: Least share of the misfit above the noise a candidate must remove for ``partly_explained``: a quarter. Two
#: missing effects of similar size each remove about half of it alone, and less when their signatures overlap;
#: a candidate that takes a few per cent off a large misfit is not a partial explanation.
PARTLY_SHARE = 0.25

_WORDS = {"nothing_missing": "NOTHING MISSING", "explained": "EXPLAINED", "partly_explained": "PARTLY EXPLAINED",
          "unexplained": "UNEXPLAINED", "undetermined": "UNDETERMINED"}


@dataclass(frozen=True)
class Verdict:
    """What the diagnosis concludes.

    Attributes
    ----------
    verdict : str
        One of :data:`VERDICTS`.
    effect : str or None
        The explaining candidate (``explained`` and ``partly_explained``); for a set of effects, the first.
    lack_of_fit_p : float
        Lack-of-fit p-value of the verdict's model (the explaining candidate, else the baseline; NaN without a
        noise estimate).
    remaining_pattern : str
        Systematic structure left in that model's residual ("none detected (...)" when there is none).
    reason : str
        One sentence: why this verdict.
    close_call : tuple
        ``(first, second, delta_bic_gap)`` when the top two candidates are within :data:`CLOSE_CALL` BIC units,
        else ``()``.
    alternatives : tuple of str
        Plausible candidates within :data:`CLOSE_CALL` BIC units of the explaining one: the data do not tell
        them from it, so the explanation is not unique.
    indicated : tuple of str
        ``undetermined``: the significant, plausible candidates, best first.
    not_identified : tuple of str
        Parameters of the named (or first indicated) candidate whose 68 % interval spans the range searched.
    share : float
        Share of the misfit above the noise that the named (or closest) candidate removes (:func:`misfit_share`;
        NaN when not computed).
    closest : str or None
        ``unexplained``: the significant, plausible candidate that comes closest.
    effects : tuple of str
        The explaining set of effects (one effect for a single candidate; several for the set search of
        :func:`validation.improve`).
    calibration : str
        A calibration error of the rig that fits the rows as well as the named effects (or alone, where the
        verdict names none), in words; empty when none does (:mod:`validation.calibration`).
    outliers : str
        Rows farther from the verdict's model than noise would put any row, in words; empty when there are none
        (:mod:`validation.outliers`).
    caveats : tuple of str
        Parameters of the explaining effects that are credible but deserve a second look, each as
        ``"effect.parameter = value unit: why"`` (a best value outside the plausible range whose 68 % interval reaches
        into it, :attr:`validation.refit.Estimate.caveat`); the reason names them too.
    localized : str
        ``unexplained`` and ``partly_explained``: the family of rows (sliding, with slip, wet) that the verdict's
        model misses while the other rows are at the noise, and what rests on those rows, in words; empty when the
        misfit does not sit in one family (:mod:`validation.localize`).
    """

    verdict: str
    effect: str | None
    lack_of_fit_p: float
    remaining_pattern: str
    reason: str
    close_call: tuple = ()
    alternatives: tuple = ()
    indicated: tuple = ()
    not_identified: tuple = ()
    share: float = math.nan
    closest: str | None = None
    effects: tuple = ()
    calibration: str = ""
    outliers: str = ""
    caveats: tuple = ()
    localized: str = ""

    @property
    def headline(self) -> str:
        """The verdict in words, for the first line of texts and reports (with the rival calibration error and the
        outlying rows, if any)."""
        named = " + ".join(self.effects) if len(self.effects) > 1 else self.effect
        alt = (f" -- or as well by {', '.join(self.alternatives)} (within {CLOSE_CALL:g} BIC units: the data "
               "cannot tell them apart)" if self.alternatives else "")
        ind = f" ({', '.join(self.indicated)} indicated)" if self.indicated else ""
        cal = "".join(f" {t}" for t in (self.calibration, self.outliers, self.localized) if t)
        return (f"Verdict: {_WORDS[self.verdict]}" + (f" by {named}" if named else "") + ind + alt
                + f". {self.reason}{cal}")

    def as_dict(self) -> dict:
        """The verdict as a JSON-ready dict.

        Returns
        -------
        dict
            ``verdict``, ``effect``, ``effects``, ``lack_of_fit_p``, ``remaining_pattern``, ``reason``,
            ``alternatives``, ``indicated``, ``not_identified``, ``share``, ``closest``, ``calibration`` (the rival
            calibration error in words, empty when none), ``outliers`` (the outlying rows in words, empty when
            none), ``caveats`` (credible parameters that deserve a second look, empty when none) and ``localized``
            (the family of rows the misfit sits in, in words, empty when none).
        """
        return {"verdict": self.verdict, "effect": self.effect, "effects": list(self.effects),
                "lack_of_fit_p": self.lack_of_fit_p, "remaining_pattern": self.remaining_pattern,
                "reason": self.reason, "alternatives": list(self.alternatives), "indicated": list(self.indicated),
                "not_identified": list(self.not_identified), "share": self.share, "closest": self.closest,
                "calibration": self.calibration, "outliers": self.outliers, "caveats": list(self.caveats),
                "localized": self.localized}


def with_calibration(verdict: Verdict, check) -> Verdict:
    """``verdict`` naming the calibration error of ``check`` (a :class:`validation.calibration.CalibrationCheck`,
    or None) that rivals its answer; unchanged when none does."""
    if check is None or not check.rivals:
        return replace(verdict, calibration="")
    return replace(verdict, calibration=check.text())


def with_outliers(verdict: Verdict, outliers) -> Verdict:
    """``verdict`` naming the rows of ``outliers`` (a :class:`validation.outliers.Outliers`, or None)."""
    return replace(verdict, outliers="" if outliers is None else outliers.text())


def with_localized(verdict: Verdict, localized) -> Verdict:
    """``verdict`` naming the family of rows its model misses (``localized``, a
    :class:`validation.localize.Localized`, or None), for ``unexplained`` and ``partly_explained`` verdicts only:
    where the model fits the noise there is no misfit to place."""
    if localized is None or verdict.verdict not in MISSES:
        return replace(verdict, localized="")
    return replace(verdict, localized=localized.text())


def with_noise_trend(verdict: Verdict, noise) -> Verdict:
    """``verdict`` whose reason says, where the scatter of the data changes with the friction level
    (``noise.trend``, :mod:`validation.noise`), that the rows were weighted by a noise estimated from the data;
    unchanged otherwise, and for ``nothing_missing`` and ``undetermined``."""
    gamma = float(getattr(noise, "trend", 0.0) or 0.0)
    if gamma == 0.0 or verdict.verdict in ("nothing_missing", "undetermined"):
        return verdict
    return replace(verdict, reason=(
        f"{verdict.reason} Note: the scatter of these data {'grows' if gamma > 0 else 'falls'} with the friction "
        f"level (sigma proportional to mu^{gamma:.2f}, p = {noise.trend_p:.2g}); each row was weighted by the noise "
        "that law gives it, an estimate from these data. If the rig's noise is known, give mu_std per row and "
        "diagnose again."))


def misfit_share(rss0: float, k0: int, rss1: float, k1: int, n: int, noise, sigma_known: bool) -> float:
    r"""Share of the baseline's misfit above the noise that a model removes.

    With the misfit above the noise :math:`E = RSS/\sigma^2 - (n - k)` (:math:`\chi^2 - (n - k)` with
    ``mu_std``; its expectation is 0 for a model that is right), the share is :math:`(E_0 - E_1)/E_0`, clipped to
    [0, 1]; 1 when the baseline has no misfit above the noise; NaN without a noise estimate.
    """
    if not noise.known:
        return math.nan
    s2 = 1.0 if sigma_known else float(noise.sigma) ** 2
    e0 = rss0 / s2 - (n - k0)
    e1 = rss1 / s2 - (n - k1)
    if e0 <= 0:
        return 1.0
    return float(min(max((e0 - e1) / e0, 0.0), 1.0))


@doi(KASS_RAFTERY_1995)
def decide(baseline, candidates, noise) -> Verdict:
    """The :class:`Verdict` for a refitted ``baseline`` and ranked ``candidates`` (module docstring)."""
    ok = [c for c in candidates if c.status == "ok"]
    credible = [c for c in ok if c.credible]
    implausible = [c for c in ok if c.significant and not c.plausible]
    base_lack, base_pat = baseline.lack, baseline.pattern
    base_fails = (not base_lack.consistent) or base_pat.found
    close = ()
    if len(ok) >= 2 and ok[1].delta_bic - ok[0].delta_bic < CLOSE_CALL and ok[0].delta_bic < 0:
        close = (ok[0].effect, ok[1].effect, float(ok[1].delta_bic - ok[0].delta_bic))
    noise_txt = _noise_phrase(noise)
    n = baseline.residual.size
    sigma_known = noise.source == "mu_std"
    if not noise.known:
        return _undetermined(baseline, credible, implausible, noise, close)
    if credible:
        best = credible[0]
        alts = tuple(c.effect for c in ok if c is not best and c.plausible
                     and abs(c.delta_bic - best.delta_bic) < CLOSE_CALL)
        share = misfit_share(baseline.rss, baseline.n_params, best.rss, baseline.n_params + best.n_params, n, noise,
                             sigma_known)
        return judge(best.effect, (best.effect,), best.lack, best.pattern, best.not_identified, share,
                     best.delta_bic, noise_txt, close, alts, caveats=best.caveats)
    if base_fails:
        why = []
        if not base_lack.consistent:
            why.append(f"the baseline misses the data beyond the noise ({base_lack.describe()}; {noise_txt})")
        if base_pat.found:
            why.append(f"its residual has a systematic pattern ({base_pat.describe()})")
        joined = " and ".join(why)
        # the first letter only: str.capitalize() would lower the rest ("F = 6.4" -> "f = 6.4", "MPa" -> "mpa")
        reason = joined[:1].upper() + joined[1:] + ", and no candidate effect is both significant and plausible"
        if implausible:
            reason += (" (significant only with implausible parameters: "
                       + "; ".join(f"{c.effect}: {', '.join(c.issues)}" for c in implausible[:3]) + ")")
        if not base_pat.found and not implausible and base_lack.p_value > MARGINAL_P:
            # a small misfit with no shape, which no candidate takes up: as likely a noise estimate a little low
            # as missing physics (a chance of the test's size on a null case)
            reason += (f". Something outside the candidate list is missing, or the noise is underestimated: the "
                       f"misfit is marginal (p = {base_lack.p_value:.2g}, residual / noise = {base_lack.ratio:.2f}) "
                       "and shows no systematic pattern; check the noise estimate first.")
        else:
            reason += ". Something outside the candidate list is missing."
        return Verdict("unexplained", None, base_lack.p_value, base_pat.describe(), reason, close)
    reason = (f"The baseline is consistent with the noise ({base_lack.describe()}; {noise_txt}) and no candidate "
              "effect is both significant and plausible.")
    return Verdict("nothing_missing", None, base_lack.p_value, base_pat.describe(), reason, close)


def judge(name, effects, lack, pattern, not_identified, share, delta_bic, noise_txt, close=(), alts=(), *,
          caveats=()) -> Verdict:
    """The verdict on a credible model (a candidate, or a set of effects): ``explained`` when it fits the noise
    and the data identify its parameters, else ``partly_explained`` or ``unexplained`` by the share of the misfit
    above the noise it removes (module docstring). ``caveats``: its credible parameters that deserve a second look
    (``"effect.parameter = value unit: why"``), named in an ``explained`` verdict's reason."""
    fits = lack.consistent and not pattern.found
    words = " + ".join(effects)
    if fits and not not_identified:
        reason = (f"With {words} the residual is at the noise level ({lack.describe()}; {noise_txt}) "
                  "and shows no systematic pattern.")
        if caveats:
            # credible, but a reader taking the value at face value would take an implausible one
            reason += (f" {'A value deserves' if len(caveats) == 1 else 'Values deserve'} a second look: "
                       + "; ".join(caveats) + ".")
        return Verdict("explained", name, lack.p_value, pattern.describe(), reason, close, alts, share=share,
                       effects=tuple(effects), caveats=tuple(caveats))
    if fits:
        reason = (f"With {words} the residual is at the noise level ({lack.describe()}; {noise_txt}), but the "
                  f"data do not identify {', '.join(not_identified)} (the 68 % interval spans the whole range "
                  f"searched, or is open on one side): {words} is indicated, not established; measure where "
                  f"{'it acts' if len(not_identified) == 1 else 'they act'} to pin "
                  f"{'it' if len(not_identified) == 1 else 'them'} down.")
        return Verdict("partly_explained", name, lack.p_value, pattern.describe(), reason, close, alts,
                       not_identified=tuple(not_identified), share=share, effects=tuple(effects))
    why = []
    if not lack.consistent:
        why.append(f"its residual is still above the noise ({lack.describe()}; {noise_txt})")
    if pattern.found:
        why.append(f"a systematic pattern remains: {pattern.describe()}")
    removed = "" if math.isnan(share) else f"removes {100 * share:.0f} % of the misfit above the noise"
    if math.isnan(share) or share >= PARTLY_SHARE:
        reason = (f"{words} helps (delta BIC {delta_bic:+.1f}" + (f"; {removed}" if removed else "") + ") but "
                  + " and ".join(why) + ": something else is missing too.")
        return Verdict("partly_explained", name, lack.p_value, pattern.describe(), reason, close, alts,
                       not_identified=tuple(not_identified), share=share, effects=tuple(effects))
    reason = (f"The closest candidate, {words}, is significant (delta BIC {delta_bic:+.1f}) but {removed}, less "
              f"than the {100 * PARTLY_SHARE:.0f} % a partial explanation needs, and "
              + " and ".join(why) + ". The missing physics is not in the candidate list.")
    return Verdict("unexplained", None, lack.p_value, pattern.describe(), reason, close, share=share,
                   closest=name)


def _undetermined(baseline, credible, implausible, noise, close) -> Verdict:
    indicated = tuple(c.effect for c in credible)
    reason = (f"Without an independent noise estimate ({noise.description}) the data cannot say whether anything "
              "is missing beyond the noise.")
    not_identified = ()
    if credible:
        best = credible[0]
        not_identified = best.not_identified
        ident = [e.describe() for e in best.estimates if e.identified]
        reason += (f" {best.effect} is indicated (delta BIC {best.delta_bic:+.1f}, p = {best.p_value:.2g}): "
                   + (f"the data identify {'; '.join(ident)}" if ident else "the data identify none of its "
                      "parameters")
                   + (f", but not {', '.join(not_identified)} (the 68 % interval spans the range searched, or is "
                      "open on one side)" if not_identified and ident else "") + ".")
        if len(indicated) > 1:
            reason += f" Also indicated: {', '.join(indicated[1:])}."
    elif implausible:
        reason += (" Significant only with implausible parameters: "
                   + "; ".join(f"{c.effect} ({', '.join(c.issues)})" for c in implausible[:3]) + ".")
    else:
        reason += " No candidate is significant."
    reason += " Give a mu_std column or repeat some conditions."
    return Verdict("undetermined", None, math.nan, baseline.pattern.describe(), reason, close,
                   indicated=indicated, not_identified=tuple(not_identified))


def explain(verdict: Verdict, m, baseline, candidates, clusters, noise, *, extrapolated_share=None) -> str:
    """The plain-language explanation: the verdict first, then the baseline, the candidates, the ambiguities;
    ``extrapolated_share`` (per row, the share of the baseline's hysteresis that rests on the master curve's
    extrapolation) adds a caution where rows rest on it for more than half."""
    paras = [verdict.headline, _noise_paragraph(noise)]
    paras.append(_baseline_paragraph(m, baseline))
    caution = extrapolation_caution(m, baseline.residual, extrapolated_share)
    if caution:
        paras.append(caution)
    ok = [c for c in candidates if c.status == "ok"]
    sig = [c for c in ok if c.significant]
    credible = [c for c in sig if c.plausible]
    if credible:
        paras.append(_candidate_paragraph(m, baseline, credible[0],
                                          "Indicated" if verdict.verdict == "undetermined" else
                                          "Closest" if verdict.verdict == "unexplained" else "Most likely missing"))
    elif ok:
        t = ok[0]
        paras.append(f"No candidate is {'both significant and plausible' if sig else 'significant'} "
                     f"({SIGNIFICANCE_RULE}). The best, {t.effect}, changes BIC by {t.delta_bic:+.1f} "
                     f"(p = {t.p_value:.2g}) and RMSE {baseline.rmse:.3g} -> {t.rmse:.3g}.")
    else:
        paras.append("No candidate effect could be evaluated.")
    demoted = [c for c in sig if not c.plausible]
    if demoted:
        paras.append("Not credible despite a significant fit (a parameter on a search bound or outside its "
                     "plausible range): " + "; ".join(f"{c.effect} ({', '.join(c.issues)})" for c in demoted) + ".")
    others = [c for c in credible[1:4]]
    if others:
        paras.append("Also significant and plausible: " + ", ".join(f"{c.effect} (delta BIC {c.delta_bic:+.1f})"
                                                                     for c in others) + ".")
    if verdict.close_call:
        a, b, gap = verdict.close_call
        paras.append(f"Close call: {a} and {b} are within {gap:.1f} BIC units of each other (less than "
                     f"{CLOSE_CALL:g}); the data hardly prefer one to the other.")
    by = {c.effect: c for c in candidates}
    for cl in clusters:
        paras.append(_cluster_paragraph(cl, by))
    failed = [c for c in candidates if c.status.startswith("failed")]
    if failed:
        paras.append("Could not evaluate: " + "; ".join(f"{c.effect} ({c.status})" for c in failed) + ".")
    na = [c for c in candidates if c.status.startswith("not applicable")]
    if na:
        paras.append("Not applicable to these rows: " + "; ".join(
            f"{c.effect} ({c.status.partition(': ')[2]})" for c in na) + ".")
    none = [c for c in candidates if c.status == "no signature"]
    if none:
        paras.append("No signature on these measurements (switching them on changes no prediction): "
                     + ", ".join(c.effect for c in none) + ".")
    return "\n\n".join(paras)


def extrapolation_caution(m, residual, share) -> str:
    """A caution when some rows rest for more than half of their predicted hysteresis on the compound's master
    curve beyond its measured frequencies (``share`` per row, None when not known): how many, and which part of
    the baseline's misfit (sum of squared residuals) they carry. A misfit there may come from the modulus, which
    no candidate effect changes; "" when no row does."""
    over = mostly_extrapolated(share)
    k = int(over.size)
    if k == 0:
        return ""
    r2 = np.asarray(residual, dtype=float) ** 2
    part = float(np.sum(r2[over]) / np.sum(r2)) if np.sum(r2) > 0 else 0.0
    text = (f"Compound data: {k} of {m.n} rows rest for more than half of their predicted hysteresis on the master "
            f"curve beyond its measured frequencies (up to {float(np.max(share)):.0%}), and they carry "
            f"{part:.0%} of the baseline's misfit (sum of squared residuals).")
    if part >= 0.5:
        text += (" The missing piece may be the modulus there rather than an effect of the list: measurements of "
                 "the compound at lower temperatures or higher frequencies would tell.")
    return text


# ---- paragraphs --------------------------------------------------------------------------------------------
def _noise_phrase(noise) -> str:
    if not noise.known:
        return "no independent noise estimate"
    return f"noise {noise.sigma:.3g} from {noise.source}"


def _noise_paragraph(noise) -> str:
    if not noise.known:
        return (f"Noise: unknown ({noise.description}); the lack-of-fit test is not possible and every verdict "
                "rests on the significance tests and the residual's own scatter. Give a mu_std column or repeat "
                "some conditions.")
    return f"Noise: {noise.sigma:.3g} in mu, from {noise.description}."


def _baseline_paragraph(m, b) -> str:
    r = b.residual
    head = (f"Baseline ({', '.join(b.effects) or 'hysteresis only'}"
            + (f"; refitted {_fmt_estimates(b.estimates)}" if b.estimates else "") + f"): RMSE {b.rmse:.3g}, mean "
            f"residual {np.mean(r):+.3g} (measured - predicted; positive means the model predicts too little "
            f"friction); lack of fit: {b.lack.describe()}.")
    if b.pattern.found:
        return head + " Where it fails: " + b.pattern.describe() + "."
    return head + f" Systematic pattern: {b.pattern.describe()}."


def _candidate_paragraph(m, b, t, lead: str = "Most likely missing") -> str:
    ch = t.change
    r = b.residual
    sd = float(np.std(r, ddof=1)) if r.size > 1 else 1.0
    ch_sd = float(np.std(ch, ddof=1)) if ch.size > 1 else 0.0
    ch_ph = _factor_phrases(ch, m, max(sd, ch_sd, 1e-12))
    corr = _cos(ch - ch.mean(), r - r.mean())
    doc = _first_doc_line(t.instance)
    fixed = t.placeholders
    txt = (f"{lead}: {t.effect}" + (f" ({doc})" if doc else "") + ". Refitted: "
           + (_fmt_estimates(t.estimates) or "no free parameters")
           + (f"; placeholders kept: {', '.join(f'{k} = {v}' for k, v in fixed.items())}" if fixed else "")
           + (f"; baseline {_fmt_estimates(t.baseline_estimates)}" if t.baseline_estimates else "")
           + ". It changes the prediction "
           + ("(mean change per group) " + "; ".join(ch_ph) if ch_ph else "in a pattern")
           + f". That change follows the baseline residual (correlation {corr:+.2f}) and removes "
           f"{100 * t.explained:.1f} % of its sum of squares: RMSE {b.rmse:.3g} -> {t.rmse:.3g}, delta BIC "
           f"{t.delta_bic:+.1f}, p = {t.p_value:.2g} ({t.test} test); the score test of its signature gives "
           f"z = {t.score_z:+.1f}. With it, lack of fit: {t.lack.describe()}; remaining pattern: "
           f"{t.pattern.describe()}.")
    if t.notes:
        txt += " Fit notes: " + "; ".join(t.notes) + "."
    return txt


def _cluster_paragraph(cl, by) -> str:
    head = by[cl.effects[0]]
    gaps = [(e, by[e].delta_bic - head.delta_bic) for e in cl.effects[1:]]
    close = [e for e, g in gaps if g < CLOSE_CALL]
    txt = (f"Ambiguity: {', '.join(cl.effects)} move the predictions in nearly the same way on these rows "
           f"(|cos| {', '.join(f'{k}: {v:.3f}' for k, v in cl.cosines.items())}).")
    if close:
        txt += f" The data cannot tell {head.effect} from {', '.join(close)} (delta BIC within {CLOSE_CALL:g})."
    else:
        txt += (f" The data still prefer {head.effect} (by {min(g for _, g in gaps):.0f} BIC units or more), "
                "but that rests on the details of the fits.")
    for s in cl.separations:
        txt += f" To tell {s.effects[0]} from {s.effects[1]}, measure at {s.describe()}."
    for s in cl.separations_in_range:
        if not any(s.effects == t.effects and s.in_range for t in cl.separations):
            txt += f" Inside the measured ranges the largest difference is at {s.describe()}."
    return txt


# ---- helpers -----------------------------------------------------------------------------------------------
def _fmt_estimates(estimates) -> str:
    return ", ".join(e.describe() for e in estimates)


def _factor_phrases(values: np.ndarray, m, sd: float, z_min: float = 2.0) -> list[str]:
    """For each factor, where the group means of ``values`` (a change of mu) are largest and smallest."""
    from .compare import group_labels

    phrases = []
    for factor, (gid, labels) in group_labels(m).items():
        if factor == "series" or len(labels) < 2:
            continue
        means, zs = [], []
        for k in range(len(labels)):
            sel = gid == k
            nk = int(sel.sum())
            mk = float(np.mean(values[sel])) if nk else 0.0
            means.append(mk)
            zs.append(mk / (sd / math.sqrt(nk)) if nk and sd > 0 else 0.0)
        means, zs = np.array(means), np.array(zs)
        if np.max(np.abs(zs)) < z_min:
            continue
        hi_k, lo_k = int(np.argmax(means)), int(np.argmin(means))
        if means[hi_k] - means[lo_k] <= 0:
            continue
        big, small = (hi_k, lo_k) if abs(means[hi_k]) >= abs(means[lo_k]) else (lo_k, hi_k)
        word = "raises mu" if means[big] > 0 else "lowers mu"
        phrases.append(f"by {factor}, {means[big]:+.3f} ({word}) at {labels[big]} against {means[small]:+.3f} at "
                       f"{labels[small]}")
    return phrases


def _cos(a, b) -> float:
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    if na <= 1e-300 or nb <= 1e-300:
        return 0.0
    return float(a @ b) / (na * nb)


def _first_doc_line(obj) -> str:
    doc = (type(obj).__doc__ or "").strip()
    if not doc:
        return ""
    line = doc.splitlines()[0].strip().rstrip(".")
    line = re.sub(r":\w+:`([^`]*)`", r"\1", line).replace("``", "").replace("`", "")
    return line[:140]
