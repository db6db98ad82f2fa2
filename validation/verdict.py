"""The verdict of a diagnosis and its plain-language explanation.

Verdicts (the noise and the lack-of-fit test are those of :mod:`validation.noise`):

``"nothing_missing"``
    the baseline is consistent with the noise (no lack of fit, no systematic pattern) and no candidate is both
    significant and plausible;
``"explained"``
    a significant, plausible candidate leaves a residual consistent with the noise and without pattern;
``"partly_explained"``
    a significant, plausible candidate helps, but lack of fit or a pattern remains;
``"unexplained"``
    the baseline fails beyond the noise and no candidate is both significant and plausible.

A candidate is *plausible* when none of its fitted parameters sits on a search bound or outside the range its
:class:`persson.effects.Parameter` declares plausible; an implausible one can be significant but is never the
explanation. Two candidates whose BIC differ by less than :data:`CLOSE_CALL` are a close call, flagged whatever
their signatures.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from .candidates import SIGNIFICANCE_RULE

__all__ = ["Verdict", "decide", "explain", "VERDICTS", "CLOSE_CALL"]

VERDICTS = ("nothing_missing", "explained", "partly_explained", "unexplained")
#: Delta BIC below which the top two candidates are a close call.
CLOSE_CALL = 10.0


@dataclass(frozen=True)
class Verdict:
    """What the diagnosis concludes.

    Attributes
    ----------
    verdict : str
        One of :data:`VERDICTS`.
    effect : str or None
        The explaining candidate (``explained`` and ``partly_explained``).
    lack_of_fit_p : float
        Lack-of-fit p-value of the verdict's model (the explaining candidate, else the baseline).
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
    """

    verdict: str
    effect: str | None
    lack_of_fit_p: float
    remaining_pattern: str
    reason: str
    close_call: tuple = ()
    alternatives: tuple = ()

    @property
    def headline(self) -> str:
        """The verdict in words, for the first line of texts and reports."""
        words = {"nothing_missing": "NOTHING MISSING", "explained": "EXPLAINED",
                 "partly_explained": "PARTLY EXPLAINED", "unexplained": "UNEXPLAINED"}[self.verdict]
        alt = (f" -- or as well by {', '.join(self.alternatives)} (within {CLOSE_CALL:g} BIC units: the data "
               "cannot tell them apart)" if self.alternatives else "")
        return f"Verdict: {words}" + (f" by {self.effect}" if self.effect else "") + alt + f". {self.reason}"


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
    if credible:
        best = credible[0]
        alts = tuple(c.effect for c in ok if c is not best and c.plausible
                     and abs(c.delta_bic - best.delta_bic) < CLOSE_CALL)
        fits = best.lack.consistent and not best.pattern.found
        if fits:
            reason = (f"With {best.effect} the residual is at the noise level ({best.lack.describe()}; {noise_txt}) "
                      "and shows no systematic pattern.")
            return Verdict("explained", best.effect, best.lack.p_value, best.pattern.describe(), reason, close, alts)
        why = []
        if not best.lack.consistent:
            why.append(f"its residual is still above the noise ({best.lack.describe()}; {noise_txt})")
        if best.pattern.found:
            why.append(f"a systematic pattern remains: {best.pattern.describe()}")
        reason = f"{best.effect} helps (delta BIC {best.delta_bic:+.1f}) but " + " and ".join(why) + \
            ": something else is missing too."
        return Verdict("partly_explained", best.effect, best.lack.p_value, best.pattern.describe(), reason, close,
                       alts)
    if base_fails:
        why = []
        if not base_lack.consistent:
            why.append(f"the baseline misses the data beyond the noise ({base_lack.describe()}; {noise_txt})")
        if base_pat.found:
            why.append(f"its residual has a systematic pattern ({base_pat.describe()})")
        reason = " and ".join(why).capitalize() + ", and no candidate effect is both significant and plausible"
        if implausible:
            reason += (" (significant only with implausible parameters: "
                       + "; ".join(f"{c.effect}: {', '.join(c.issues)}" for c in implausible[:3]) + ")")
        reason += ". Something outside the candidate list is missing."
        return Verdict("unexplained", None, base_lack.p_value, base_pat.describe(), reason, close)
    reason = (f"The baseline is consistent with the noise ({base_lack.describe()}; {noise_txt}) and no candidate "
              "effect is both significant and plausible.")
    if not noise.known:
        reason += " Without an independent noise estimate this rests on the significance tests alone."
    return Verdict("nothing_missing", None, base_lack.p_value, base_pat.describe(), reason, close)


def explain(verdict: Verdict, m, baseline, candidates, clusters, noise) -> str:
    """The plain-language explanation: the verdict first, then the baseline, the candidates, the ambiguities."""
    paras = [verdict.headline, _noise_paragraph(noise)]
    paras.append(_baseline_paragraph(m, baseline))
    ok = [c for c in candidates if c.status == "ok"]
    sig = [c for c in ok if c.significant]
    credible = [c for c in sig if c.plausible]
    if credible:
        paras.append(_candidate_paragraph(m, baseline, credible[0]))
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
    none = [c for c in candidates if c.status == "no signature"]
    if none:
        paras.append("No signature on these measurements (switching them on changes no prediction): "
                     + ", ".join(c.effect for c in none) + ".")
    return "\n\n".join(paras)


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


def _candidate_paragraph(m, b, t) -> str:
    ch = t.change
    r = b.residual
    sd = float(np.std(r, ddof=1)) if r.size > 1 else 1.0
    ch_sd = float(np.std(ch, ddof=1)) if ch.size > 1 else 0.0
    ch_ph = _factor_phrases(ch, m, max(sd, ch_sd, 1e-12))
    corr = _cos(ch - ch.mean(), r - r.mean())
    doc = _first_doc_line(t.instance)
    fixed = t.placeholders
    txt = (f"Most likely missing: {t.effect}" + (f" ({doc})" if doc else "") + ". Refitted: "
           + (_fmt_estimates(t.estimates) or "no free parameters")
           + (f"; placeholders kept: {', '.join(f'{k} = {v}' for k, v in fixed.items())}" if fixed else "")
           + (f"; baseline {_fmt_estimates(t.baseline_estimates)}" if t.baseline_estimates else "")
           + ". It changes the prediction " + ("(mean change per group) " + "; ".join(ch_ph) if ch_ph else "in a pattern")
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
