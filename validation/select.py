r"""Selection over sets of effects: which combination of candidate effects the data support.

A set :math:`S` of effects added to the baseline is a model whose parameters -- the baseline's fitted ones and
the free parameters of every effect in :math:`S` -- are refitted jointly from global starts
(:func:`validation.refit.global_fit`), and judged by its BIC (Schwarz, Ann. Stat. 6, 461 (1978)). A set fitted
for the first time starts from its members' fitted values and, first among the others, from the same values with
every parameter a member pushed onto a search bound or out of its plausible range moved to the middle of that range
(:func:`validation.refit.plausible_start`): fitted alone, a member may stand in for the partner it lacks, and the
joint fit from there can stay in that basin; next, from the same values with the members' own parameters at their
declared defaults (a member that did nothing alone is left where it still does nothing, with no gradient to leave
by). The search (:func:`validation.improve`) is stepwise:

1. **forward**: the diagnosis of the current set names the credible candidate that helps most (its joint refit is
   the new set);
2. **backward elimination**: after each addition, every effect added earlier is dropped in turn (a joint refit of
   the others); an effect whose removal costs less than :data:`STAY` BIC units is removed (the cheapest first,
   then again) -- it no longer earns its parameters once a later effect is in;
3. **swaps**: every effect added earlier is replaced in turn by each of the alternatives its own step named
   (plausible candidates within 10 BIC units of it when it was chosen) and by each candidate that fitted better at
   that step but was not credible alone (a partner may make it credible: a strain softening whose factors leave
   their plausible range unless the adhesion takes its part); a swap to a credible set that lowers the BIC is made.

4. **exploring pairs**: when the path ends short of the noise (no credible candidate helps, yet the model misses
   the data), the pairs it could not reach are fitted jointly: each of the (at most three best) credible
   significant candidates of the baseline's diagnosis with every candidate that showed nothing alone (an effect
   invisible until its partner is in, while a look-alike of the partner took the path) and with each of the
   other two (a look-alike of both members took the path, on top of which neither partner is credible) --
   where the two single fits together gain at least half of what the path gained (BIC) over the baseline --, the
   pairs of the better single fits first, within as many model evaluations as the path took. When no candidate
   was significant alone, every pair of credible candidates that changed the predictions alone is screened as in
   item 5 (two effects that each fit too little alone may fit together); when candidates were significant alone
   but none credible, the pairs of the three best of them are fitted jointly first (each may stand in for the
   partner it lacks: an adhesion whose peak speed runs off to 1e6 m/s beside a microtexture whose H sits on 1);
   when some were credible, each of the three best that are not is paired with each credible significant one
   under the gain rule, after the pairs of credible candidates (an adhesion peaking at the slowest speeds beside a
   microtexture, both passed over for a strain softening that mimics the pair).
   Last, within the same budget, each of the credible significant candidates with every candidate whose
   parameters the data do not identify alone: such a partner may act only once the first moves far from its own
   single fit (a flash temperature beside a microtexture whose cut-off must reach several times past where it
   fitted alone), where neither the gain rule nor a screen linearized at that single fit can see it. The best
   credible pair continues the
   search when it fits better than the path's set by more than :data:`STAY` BIC units (a step ``"explored"``),
   at most once.
5. **pairs that tie**: a path that ends at the noise may have taken a look-alike of a pair whose second member
   showed nothing alone (a flash temperature invisible until the microtexture is in, while an adhesion fits the
   same rows): the pair fits as well, and the data cannot tell them apart, but no step ever fitted it. Each pair
   of a credible significant candidate (the three best) with a candidate that showed nothing alone (no
   signature, or parameters the data do not identify; one that acted alone only where its own gain could make the
   pair tie), and each pair of a credible candidate that showed nothing alone with one that changed no prediction
   at all alone (no signature, or no effect on the rows: a flash temperature on a PSD that stops short, beside a
   microtexture whose own change is within the noise: neither member is ever significant alone), is screened: a
   bound from a linearized joint fit from the first one's fit (its Jacobian, and the change the quiet one makes
   at a few points of its range: one Gauss-Newton step, the quiet one's amplitude kept positive), about ten model
   evaluations; where the bound comes within :data:`EQUAL` of the path's set (a
   pair that contains the path's set: better by more than :data:`STAY`), two bounded Gauss-Newton steps of the
   pair itself give a value it reaches, and the pairs that reach within :data:`EQUAL` of that limit are refitted
   jointly, the most promising first, within as many model evaluations as the path took. A pair that ties is
   named among the equally supported sets (and is the answer where it fits better, item 8); one better by more
   than :data:`STAY` replaces the path's set (as in step 4). The screen serves step 4 too, for the pairs the gain
   rule leaves out.
6. **fits stopped at their budget**: a fit that runs out of model evaluations (40 + 25 k for k parameters) reports
   the best point it reached, so its BIC is only an upper bound. A candidate fitted on top of a set varies its own
   parameters in its design, and the local fits that start there can run out before they leave the set's values
   (a flash temperature held at its bound by the look-alike it replaced). When the search ends with an answer that
   misses the noise, or one that is not credible (at the noise or not, it explains nothing: an adhesion whose peak
   speed runs to the search bound standing in for a flash temperature + microtexture pair), every such set within
   :data:`EQUAL` BIC units of it (itself included) is fitted again by a global search of all its parameters from
   the point it reached, with a budget of its own, the best first, within half the model evaluations the search
   took before this item (a second time if the first took it further and it stopped again; a credible fit is kept
   when its continuation is not); a credible set that then fits better than the answer by more than :data:`STAY`
   replaces it (a step ``"resumed"``). This is done when the path added effects and the noise is known (a baseline left
   alone is the first diagnosis' judgement, made with its significance tests); a credible answer at the noise is
   left to the pair screen (item 5).
7. **subsets of the sets within reach**: backward elimination acts on the path's own set only, and a larger set
   fitted on the way (a candidate on top of the path's set, a pair the exploration fitted) may tie with the answer
   because it contains a better set: the path's set plus the true partner of an effect the path took a look-alike
   for, whose subset without the look-alike is the truth (a flash temperature + microtexture pair hidden behind an
   adhesion: the adhesion is fitted first, the microtexture next, and the flash temperature on top of both only
   ties; the pair without the adhesion was never fitted). When the search ends with an answer that misses the
   noise or is not credible, every set fitted with two or more effects within :data:`EQUAL` BIC units of it
   (credible or not) has each of its effects dropped in turn; the subsets not fitted yet, and those whose fit
   stopped at its budget of model evaluations (its BIC only an upper bound: a candidate fitted on top of a step's set
   varies its own parameters first, and may stop far from the pair's optimum), are refitted jointly from its
   values, the subsets of the better sets first, within the same half of the model evaluations as item 6 (those
   taken before it: a budget that grew with the continued fits could let three-effect sets run for minutes). A
   credible subset that fits better than the answer by more than :data:`STAY` replaces it (a step ``"reduced"``);
   the others count for the equally supported sets. Done under the conditions of item 6.
8. **the best set fitted**: the path's answer is the set its steps reached, and a set fitted on the way off the
   path (a pair the screen of item 5 fitted) can fit better by less than :data:`STAY`, so that no step above took
   it (an adhesion that the path took, on three parameters, against the flash temperature + microtexture pair it
   stands in for, on two, 3.9 BIC units better). And an answer with a parameter on a search bound or outside its
   plausible range explains nothing (the verdict on it is ``unexplained``), even where it fits best. So at the end
   of the search, the fitted set with the lowest BIC that is credible and whose every effect earns its place
   (:data:`STAY`) replaces the answer where it fits better than the answer (lower BIC), or, when the answer is not
   credible, where it comes within :data:`EQUAL` BIC units of it (the data support both, only one of them
   physically): a step ``"preferred"``. A set with a parameter the data do not identify does not replace a credible
   answer whose parameters are all identified (the BIC counts the parameters that change the prediction, so it
   flatters such a set: a flash temperature whose q_m runs to where it acts fully). An answer replaced that is not
   credible is then set aside, one that is credible is named among the equally supported sets.
9. **an answer the data do not pin down**: an effect of the answer with a parameter the data do not identify (its
   68 % interval spans the range searched or is open on one side) may be standing in for another candidate, and
   the swaps of item 3 try only the alternatives named when it was added (a strain softening taken first, whose
   loss factor runs onto its bound once the microtexture is in, while the hidden pair is flash temperature +
   microtexture: the flash temperature, significant alone but far behind, was never fitted beside the
   microtexture). Before item 8, each such effect is replaced in turn by each credible candidate fitted alone on
   the baseline -- the significant ones first, the better single fits first, then those that showed nothing alone
   (an effect invisible until its partner is in), then those with no signature at all. Then each such effect is
   kept and the same candidates take the place of each other effect of the answer, in the same order: the effect
   left open may act only beside a partner the answer lacks, while another effect of the answer stands in for the
   pair (an adhesion fitting what flash temperature + microtexture do, beside a flash temperature whose q_m runs to
   where it does nothing, each member of the pair fitting worse than the baseline alone). The sets not fitted yet
   are refitted jointly from the answer's values and the replacement's single fit, within half the model
   evaluations the search took, and compete in item 8 and for the equally supported sets
   (:attr:`Selection.replaced` says what was fitted). Done when the noise is known.

The intervals of a set fitted here (its profile likelihoods, often costlier than the fit) are computed when first
read (:class:`EffectSet`): for the sets reported, and for a set whose credibility depends on them (a parameter on a
search bound or outside its plausible range: the 68 % profiles of those parameters alone); the diagnoses of the
steps after the first compute their 95 % intervals when read as well, and the 68 % ones of every candidate but
the one their verdict names and those with a parameter on a bound or out of its range, whose intervals decide
their credibility (:func:`validation.candidates.finish_candidate` with ``defer``). The evaluations they spend are
counted then (:meth:`SetSearch.spent`), so the budgets above count the fits and the intervals that were read.

A set the path reached that turns out not credible once its own intervals are computed (its step judged it on
quicker ones) has the pairs the path did not reach explored as in item 4 (:func:`validation.improve`).

The search stops when the verdict on the current set says stop, and a final pass applies the rule to every effect:
**an effect stays only if dropping it from the final joint model costs more than** :data:`STAY` **BIC units**
("very strong" evidence, Kass & Raftery, J. Am. Stat. Assoc. 90, 773 (1995)). The result names the best set and
every set within :data:`EQUAL` BIC units of it among the sets fitted on the way (equally supported models;
supersets of another listed set are left out unless their extra effects earn more than :data:`STAY` BIC units),
each with its parameters and intervals, and the measurement that would separate each from the best
(:mod:`validation.probe`). Last, a calibration error of the rig (a gain or a zero offset of the measured mu) is
fitted on top of every subset of the best set that was fitted: one that fits as well as the effects it replaces is
named as their rival (:mod:`validation.calibration`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import lsq_linear

from frictioncite import doi

from .band import SEBER_WILD_1989
from .calibration import SetFit, check_calibration
from .candidates import KASS_RAFTERY_1995, SCHWARZ_1978, bic, fit_baseline
from .deferred import Deferred, Lazy, is_ready, raw
from .fitting import BudgetExhausted, Fitter, ParameterSpace, halton
from .refit import BUDGET_NOTE, GlobalFit, plausible_start

__all__ = ["EffectSet", "Selection", "SetSearch", "STAY", "EQUAL"]

#: BIC units an effect must be worth to stay in the final model (dropping it must cost more).
STAY = 10.0
#: Sets within this many BIC units of the best are equally supported.
EQUAL = 10.0


@dataclass(frozen=True, eq=False)
class EffectSet:
    """A set of effects added to the baseline, every parameter refitted jointly.

    Attributes
    ----------
    effects : tuple of str
        The effects added to the baseline, in the order they were added.
    model : persson.Model
    contact : persson.slip.Contact or None
    predicted : ndarray
        Prediction per row.
    rss, bic, rmse : float
        Weighted residual sum of squares (chi2 with ``mu_std``), Schwarz's criterion, root-mean-square residual.
    n_params : int
        Fitted parameters that change the prediction (the baseline's included).
    estimates : tuple of validation.refit.Estimate
        Every fitted parameter with its uncertainty (the baseline's first).
    lack : validation.noise.LackOfFit
    pattern : validation.noise.Pattern
    source : str
        Where the fit comes from (``"diagnosis of step 2"``, ``"joint refit"``).
    notes : tuple of str
    covariance : validation.refit.ParameterCovariance or None
        The joint covariance of the fitted parameters (None when none were fitted).
    jacobian : ndarray (rows, parameters) or None
        d mu / d u of the prediction at the optimum, in the coordinates of :attr:`covariance` (unweighted).
    fit_notes : tuple of str or None
        The notes of the fit itself, before its uncertainties (None: as :attr:`notes`).
    fitted : dict or None
        ``"effect.parameter" -> value`` of every fitted parameter (None: from :attr:`estimates`).
    clean : bool
        Every fitted parameter lies off its search bounds and inside its plausible range, so that no interval can
        make the set implausible (:attr:`issues` is then empty without the intervals being computed).
    credibility : validation.deferred.Deferred or None
        The estimates with the 68 % intervals of the parameters that may make the set implausible, the others bare
        (:attr:`validation.refit.GlobalFit.credibility`): :attr:`issues` reads them until :attr:`estimates` are
        computed.

    The joint refits of a :class:`SetSearch` give :attr:`estimates` and :attr:`notes` as a
    :class:`validation.deferred.Deferred`: their profile-likelihood intervals are computed when first read (for the
    sets reported, and for those whose credibility depends on an interval), not for every set fitted.
    """

    effects: tuple
    model: object
    contact: object
    predicted: np.ndarray
    rss: float
    bic: float
    rmse: float
    n_params: int
    estimates: tuple = Lazy()
    lack: object
    pattern: object
    source: str = ""
    notes: tuple = Lazy(default=())
    covariance: object = field(default=None, repr=False)
    jacobian: object = field(default=None, repr=False)
    fit_notes: tuple | None = field(default=None, repr=False)
    fitted: dict | None = field(default=None, repr=False)
    clean: bool = field(default=False, repr=False)
    credibility: object = field(default=None, repr=False)

    @property
    def key(self) -> frozenset:
        """The effects as a frozenset: the identity of the set, whatever the order of addition."""
        return frozenset(self.effects)

    @property
    def label(self) -> str:
        """``"a + b"`` (``"(baseline)"`` for the empty set)."""
        return " + ".join(self.effects) or "(baseline)"

    @property
    def issues(self) -> tuple:
        """Why the fit is not credible (parameters on search bounds or outside their plausible ranges)."""
        if self.clean:
            return ()
        # before the intervals are computed, those that judge credibility are enough (see ``credibility``)
        est = self.estimates if self.credibility is None or is_ready(self, "estimates") else self.credibility()
        return tuple(f"{e.key} = {e.value:.3g}: {e.issue}" for e in est if e.issue)

    @property
    def plausible(self) -> bool:
        """Whether every fitted parameter is credible (no :attr:`issues`)."""
        return not self.issues

    @property
    def budget_stopped(self) -> bool:
        """Whether its fit stopped at its budget of model evaluations (its BIC is then an upper bound: the optimum
        may lie further on)."""
        return BUDGET_NOTE in (self.notes if self.fit_notes is None else self.fit_notes)

    @property
    def not_identified(self) -> tuple:
        """Parameters of the added effects whose 68 % interval spans the range searched."""
        return tuple(e.key for e in self.estimates if not e.identified and e.key.partition(".")[0] in self.effects)

    @property
    def caveats(self) -> tuple:
        """Credible parameters of the added effects that deserve a second look, as ``"effect.parameter = value
        unit: why"`` (:attr:`validation.refit.Estimate.caveat`)."""
        return GlobalFit.caveats_of(e for e in self.estimates if e.key.partition(".")[0] in self.effects)

    def parameters(self) -> dict:
        """``"effect.parameter" -> value`` of every fitted parameter."""
        if self.fitted is not None:
            return dict(self.fitted)
        return {e.key: e.value for e in self.estimates}

    def as_dict(self, best_bic: float | None = None) -> dict:
        """The set as a JSON-ready dict.

        Parameters
        ----------
        best_bic : float, optional
            BIC of the best set, for ``delta_bic`` (None without).

        Returns
        -------
        dict
            ``effects``, ``label``, ``bic``, ``delta_bic``, ``rmse``, ``n_params``, ``parameters``, ``parameters_std``,
            ``intervals``, ``estimates`` (by parameter key), ``plausible``, ``issues``, ``not_identified``,
            ``lack_of_fit_p``, ``remaining_pattern``, ``source`` and ``notes``.
        """
        return {"effects": list(self.effects), "label": self.label, "bic": self.bic,
                "delta_bic": None if best_bic is None else self.bic - best_bic, "rmse": self.rmse,
                "n_params": self.n_params, "parameters": self.parameters(),
                "parameters_std": {e.key: e.std for e in self.estimates},
                "intervals": {e.key: list(e.interval) for e in self.estimates},
                "estimates": {e.key: e.as_dict() for e in self.estimates},
                "plausible": self.plausible, "issues": list(self.issues),
                "not_identified": list(self.not_identified),
                "lack_of_fit_p": None if self.lack is None else self.lack.p_value,
                "remaining_pattern": None if self.pattern is None else self.pattern.describe(),
                "source": self.source, "notes": list(self.notes)}

    def describe(self) -> str:
        """One line: the label, BIC, RMSE and every fitted parameter with its uncertainty (and how a 95 % interval
        was found where it was extrapolated)."""
        par = ", ".join(e.describe() for e in self.estimates) or "no fitted parameters"
        extrapolated = "".join(f" (the 95 % interval of {e.key} is {e.note95})" for e in self.estimates if e.note95)
        return f"{self.label}: BIC {self.bic:.1f}, RMSE {self.rmse:.4g}; {par}{extrapolated}"


@dataclass(frozen=True, eq=False)
class Selection:
    """The outcome of the search over sets of effects.

    Attributes
    ----------
    best : EffectSet
        The set with the lowest BIC among those whose every effect earns its place (:data:`STAY`).
    supported : tuple of EffectSet
        Other sets within :data:`EQUAL` BIC units of the best (equally supported by the data), best first.
    drop_costs : dict
        ``effect -> BIC(best without it) - BIC(best)`` (each more than :data:`STAY`).
    separations : tuple of validation.probe.Separation
        For each supported set: where its predictions differ most from the best's.
    visited : tuple of EffectSet
        Every set fitted, lowest BIC first.
    removed : tuple of str
        Effects added on the way and removed by the backward elimination, swaps or the final rule (in words).
    explored : tuple of str
        What the exploration of pairs (:meth:`SetSearch.explore`) found beyond the stepwise path, in words: a set
        that fits better than the path's, or that it stopped at its budget (empty when neither; pairs that tie
        with the best are among :attr:`supported`).
    resumed : tuple of str
        The fits that had stopped at their budget of model evaluations within reach of the best set and were
        continued (:meth:`SetSearch.resume`), in words, with their BIC before and after.
    reduced : tuple of str
        What refitting the subsets of the sets within reach of the best (:meth:`SetSearch.reduce`) found, in words:
        a subset that fits better than the path's set, or that it stopped at its budget (empty when neither).
    preferred : tuple of str
        A set fitted on the way that took the place of the search's answer (:meth:`SetSearch.prefer`), in words:
        one that fits better with every effect earning its place, or a credible one within :data:`EQUAL` BIC units
        of an answer that is not credible (empty when none did).
    replaced : tuple of str
        The sets fitted with an effect of the answer whose parameters the data do not identify replaced by another
        candidate, or kept beside another candidate in place of one of the answer's other effects
        (:meth:`SetSearch.replace_unidentified`), in words, with their BIC against the answer's (empty when
        none were fitted); one that fits better is the answer by :attr:`preferred`.
    calibration : validation.calibration.CalibrationCheck or None
        A gain and a zero offset of the measured mu fitted on top of each subset of the best set, an offset of the
        recorded temperatures and a factor on the recorded speeds on the baseline and on the subsets one effect
        short of it: a calibration error of the rig that fits as well as the best set's extra effects is a rival
        of them
        (:func:`validation.calibration.check_calibration`).
    """

    best: EffectSet
    supported: tuple = ()
    drop_costs: dict = field(default_factory=dict)
    separations: tuple = ()
    separations_in_range: tuple = ()
    visited: tuple = ()
    removed: tuple = ()
    explored: tuple = ()
    resumed: tuple = ()
    reduced: tuple = ()
    calibration: object = None
    preferred: tuple = ()
    replaced: tuple = ()

    @property
    def equally_supported(self) -> bool:
        """Whether another set is within :data:`EQUAL` BIC units of the best."""
        return bool(self.supported)

    @property
    def set_aside(self) -> tuple:
        """Sets fitted on the way that fit better than the best (lower BIC) but are not credible (a parameter on a
        search bound or outside its plausible range), lowest BIC first: the data may be saying that an effect acts
        beyond the range its parameters were searched in, which the user should see."""
        return tuple(s for s in self.visited if s.bic < self.best.bic - 1e-9 and not s.plausible)

    def as_dict(self) -> dict:
        """The selection's part of the ``--json`` layout.

        Returns
        -------
        dict
            ``best_set`` and ``equally_supported`` (:meth:`EffectSet.as_dict` with ``delta_bic`` to the best),
            ``drop_costs``, ``set_separations`` and ``set_separations_in_measured_range``
            (:meth:`validation.probe.Separation.as_dict`), ``sets`` (every set fitted: ``effects``, ``bic``,
            ``delta_bic``, ``rmse``, ``plausible``, ``source``), ``set_aside`` (``effects``, ``delta_bic``, ``issues``),
            ``removed``, ``explored``, ``resumed``, ``reduced``, ``replaced``, ``preferred`` and ``calibration``
            (:meth:`validation.calibration.CalibrationCheck.as_dict`, None when not checked).
        """
        b = self.best.bic
        return {"best_set": self.best.as_dict(b), "equally_supported": [s.as_dict(b) for s in self.supported],
                "drop_costs": dict(self.drop_costs),
                "set_separations": [s.as_dict() for s in self.separations],
                "set_separations_in_measured_range": [s.as_dict() for s in self.separations_in_range],
                "sets": [{"effects": list(s.effects), "bic": s.bic, "delta_bic": s.bic - b, "rmse": s.rmse,
                          "plausible": s.plausible, "source": s.source} for s in self.visited],
                "set_aside": [{"effects": list(s.effects), "delta_bic": s.bic - b, "issues": list(s.issues)}
                              for s in self.set_aside],
                "removed": list(self.removed), "explored": list(self.explored), "resumed": list(self.resumed),
                "reduced": list(self.reduced), "replaced": list(self.replaced), "preferred": list(self.preferred),
                "calibration": None if self.calibration is None else self.calibration.as_dict()}

    def text(self) -> str:
        """Plain text: the best set and the cost of dropping each of its effects, the equally supported sets and where
        to measure to tell them apart, then what the exploration and the continued fits found, the effects removed,
        the sets set aside and up to six other sets fitted (delta BIC)."""
        if self.drop_costs:
            lines = [f"Best set of effects: {self.best.label} (BIC {self.best.bic:.1f}); dropping "
                     + ", ".join(f"{k} would cost {v:.1f}" for k, v in self.drop_costs.items())
                     + f" BIC units (an effect stays when that is more than {STAY:g})."]
        else:
            lines = [f"Best set of effects: none added, the baseline (BIC {self.best.bic:.1f})."]
        lines.append("  " + self.best.describe())
        if self.supported:
            lines.append(f"Equally supported (within {EQUAL:g} BIC units):")
            for s in self.supported:
                lines.append(f"  {s.describe()} (delta BIC {s.bic - self.best.bic:+.1f})")
            for sep in self.separations:
                lines.append(f"  to tell them apart, measure at {sep.describe()}")
            for sep in self.separations_in_range:
                lines.append(f"  inside the measured conditions the largest difference is at {sep.describe()}")
        if self.calibration is not None and self.calibration.rivals:
            lines.append(self.calibration.text())
        if self.explored:
            lines.append("Exploring pairs beyond the stepwise path: " + "; ".join(self.explored) + ".")
        if self.resumed:
            lines.append("Fits continued past their budget of model evaluations: " + "; ".join(self.resumed) + ".")
        if self.reduced:
            lines.append("Subsets of the sets within reach: " + "; ".join(self.reduced) + ".")
        if self.replaced:
            lines.append("Refitted around an effect the data do not identify: " + "; ".join(self.replaced) + ".")
        if self.preferred:
            lines.append("The best set fitted, in place of the answer the search reached: "
                         + "; ".join(self.preferred) + ".")
        if self.removed:
            lines.append("Removed on the way: " + "; ".join(self.removed) + ".")
        aside = self.set_aside
        if aside:
            lines.append("Set aside although they fit better (not credible): " + "; ".join(
                f"{s.label} ({s.bic - self.best.bic:+.1f}: {'; '.join(s.issues)})" for s in aside) + ".")
        ranked = [s for s in self.visited if s is not self.best and s not in aside][:6]
        if ranked:
            lines.append("Other sets fitted: " + "; ".join(f"{s.label} ({s.bic - self.best.bic:+.1f})"
                                                          for s in ranked) + ".")
        return "\n".join(lines)


class SetSearch:
    """The sets of effects fitted during one improvement loop, and joint refits of new ones.

    Parameters
    ----------
    base_model : persson.Model
        The baseline as given (its ``fit`` parameters are refitted in every set).
    base_fit : tuple of str
        The baseline's fitted parameters (``[model] fit``).
    context : validation.diagnose.FitContext
        What every fit shares (the predictor, data, weights, noise, ranges).
    """

    def __init__(self, base_model, base_fit, context):
        self.base_model = base_model
        self.base_fit = tuple(base_fit)
        self.ctx = context
        self.sets: dict[frozenset, EffectSet] = {}
        self.free: dict[str, tuple] = {}          # effect -> its free parameters (as first fitted)
        self.instances: dict[str, object] = {}    # effect -> an instance (the values last fitted)
        self.alternatives: dict[str, tuple] = {}  # effect -> alternatives named when it was added
        # effect -> candidates that fitted better when it was added but were not credible alone (a parameter out of
        # its plausible range or on a bound): tried as swaps too, since a partner may make them credible
        self.set_aside: dict[str, tuple] = {}
        self.n_evals = 0
        self.removed: list[str] = []
        self.explored: list[str] = []
        self.resumed: list[str] = []
        self.reduced: list[str] = []
        self.preferred: list[str] = []
        self.replaced: list[str] = []
        self._continued: dict[frozenset, int] = {}    # set -> times its fit was continued
        self._refitted: set[frozenset] = set()        # sets whose budget-stopped fit was redone from a superset
        self._jacobians: dict[str, np.ndarray] = {}   # effect -> weighted Jacobian of its single fit
        self._bounds: dict[tuple, float] = {}          # (set, its BIC, effect dropped) -> BIC at the set's values

    # ---- recording fits made by diagnoses --------------------------------------------------------------
    def record(self, dx, effects: tuple, step: int) -> None:
        """The sets a diagnosis of the set ``effects`` fitted: that set, and it plus each fitted candidate."""
        b = dx.baseline
        self._keep(_from_baseline(tuple(effects), b, f"diagnosis of step {step}"))
        for c in dx.candidates:
            if c.status != "ok":
                continue
            self.free.setdefault(c.effect, tuple(c.free))
            self.instances.setdefault(c.effect, c.instance)
            self._keep(_from_candidate(tuple(effects) + (c.effect,), c, b.n_params, f"diagnosis of step {step}"))

    def _keep(self, s: EffectSet) -> EffectSet:
        old = self.sets.get(s.key)
        if old is None or s.bic < old.bic - 1e-9:
            self.sets[s.key] = s
            for e in s.effects:
                try:
                    self.instances[e] = s.model.effect(e)
                except Exception:  # noqa: BLE001
                    pass
        return self.sets[s.key]

    # ---- joint refits ----------------------------------------------------------------------------------
    def get(self, effects, warm=()) -> EffectSet:
        """The joint refit of the set ``effects`` (fitted now, from global starts and the ``warm`` sets' values,
        unless fitted before)."""
        key = frozenset(effects)
        if key in self.sets:
            return self.sets[key]
        return self._keep(self._fit(tuple(effects), warm))

    @doi(SCHWARZ_1978, KASS_RAFTERY_1995)
    def _fit(self, effects: tuple, warm) -> EffectSet:
        ctx = self.ctx
        model = self.base_model
        for e in effects:
            model = model.with_effect(self.instances[e])
        names = list(self.base_fit) + [f"{e}.{p}" for e in effects for p in self.free.get(e, ())]
        space = ParameterSpace(ctx.parameters(model, names))
        starts = []
        for w in warm:
            vals = w.parameters()
            u = space.u_of(model, w.contact or ctx.settings.contact)
            for j, p in enumerate(space.params):
                if p.key in vals:
                    u[j] = p.to_u(vals[p.key])
            starts.append(u)
        # the members' values come from fits without each other: a parameter one of them drove onto a search bound
        # or out of its plausible range was standing in for its partner, and the joint fit from there can stay in
        # that basin (an adhesion pushed to v_ref = 1e6 m/s by a microtexture's work): a start with those
        # parameters in the middle of their plausible ranges comes first
        given = space.u_of(model, ctx.settings.contact)
        # an effect that did nothing alone (a flash temperature without the microtexture that gives it a signature)
        # was left wherever its fit wandered, often where it still does nothing, and a local fit has no gradient
        # there to leave by: the members' own parameters at their declared defaults (where each candidate's
        # diagnosis starts) are a start too
        informed = _default_start(space, model, given, effects)
        if informed is not None:
            starts.insert(0, informed)
        fresh = plausible_start(space, given, ctx.ranges)
        if fresh is not None:
            starts.insert(0, fresh)
        return self._global_refit(effects, model, space, ctx.settings, starts, "joint refit")

    def _global_refit(self, effects: tuple, model, space, settings, starts, source: str) -> EffectSet:
        """The global fit of ``space`` on ``model`` (and the ``starts`` in u), finished with uncertainties, lack of
        fit and pattern, as the set ``effects``; its model evaluations are counted."""
        base = fit_baseline(model, space, settings, global_search=True, extra_starts=starts)
        self.n_evals += base.n_evals
        # the intervals (profiles: often more evaluations than the fit) when first read, and counted then
        b = self.ctx.finish(base, defer=True, on_evals=self.spent)
        self.n_evals += (b.fit.n_evals - base.fit.n_evals) if b.fit is not None and base.fit is not None else 0
        return _from_baseline(effects, b, source)

    def dropped(self, s: EffectSet, f: str) -> EffectSet:
        """The fit of the set ``s`` less the effect ``f``, for the cost of ``f`` (backward elimination and the final
        rule): the fit kept (or made now from ``s``'s values, :meth:`get`) and, where ``f`` then seems to earn its
        place, the subset evaluated once at ``s``'s own values of the parameters it keeps; where that reads within
        :data:`STAY` BIC units of ``s`` and below the fit kept, the subset is fitted again from there.

        A subset fitted earlier from other starts (a step's diagnosis) may sit in a worse optimum than the one the
        superset found, where ``f`` does nothing: a patch heating whose own fit stopped at a counter-surface
        effusivity of 3264 (chi^2 539 on 36 rows; true 329) was found again at 337 beside a strain softening with
        factors 1.00 and 1.02, which then seemed to earn 494 BIC units (blind draw 41, case 4). The set's values less
        ``f`` bound the subset's best chi^2 from above, so a cost read from a worse fit is not the cost of ``f``.
        """
        rest = tuple(e for e in s.effects if e != f)
        sub = self.get(rest, warm=(s,))
        if sub.bic - s.bic < STAY or f not in getattr(s.model, "effect_names", ()):
            return sub
        key = (s.key, s.bic, f)    # the backward elimination and the final rule ask again for the same set
        if key not in self._bounds:
            self._bounds[key] = self._bic_without(s, f)
        at = self._bounds[key]
        if not (math.isfinite(at) and at < sub.bic - 1e-9 and at - s.bic < STAY):
            return sub
        return self._keep(self._fit(rest, (s,)))

    def _bic_without(self, s: EffectSet, f: str) -> float:
        """BIC of the set ``s`` less the effect ``f`` at ``s``'s own values (one model evaluation; NaN where the
        model fails), its parameters counted as ``s``'s less ``f``'s free ones."""
        st = self.ctx.settings
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # a prediction between fits: a refit from here records its notes
                mu = st.predictor.predict(s.model.without(f), contact=s.contact or st.contact).mu
        except Exception:  # noqa: BLE001  (a set without one of its effects may fail: the fit kept stands)
            return math.nan
        self.n_evals += 1
        chi2 = float(np.sum(((st.y - np.asarray(mu, dtype=float)) * st.w) ** 2))
        return bic(chi2, st.n, max(s.n_params - len(self.free.get(f, ())), 0), st.sigma_known)

    def spent(self, n: int) -> None:
        """Count ``n`` model evaluations spent by deferred intervals (a set's, or those of a step's diagnosis)."""
        self.n_evals += int(n)

    # ---- the search steps ------------------------------------------------------------------------------
    def prune(self, current: tuple, progress=None) -> list[tuple]:
        """Backward elimination and swaps on the set ``current`` (module docstring, items 2 and 3).

        Returns the changes made, in order: ``("removed", effect, cost, new set)`` or
        ``("swapped", effect, replacement, gain, new set)``; the last new set is the result.
        """
        changes = []
        seen = {frozenset(current)}
        while len(current) > 1:
            s = self.get(current)
            last = current[-1]
            costs = {}
            for f in current[:-1]:
                if progress is not None:
                    progress(f"backward elimination: refitting without {f}")
                costs[f] = self.dropped(s, f).bic - s.bic
            f = min(costs, key=costs.get) if costs else None
            if f is not None and costs[f] < STAY:
                current = tuple(e for e in current if e != f)
                self.removed.append(f"{f} (dropping it cost {costs[f]:+.1f} BIC units once {last} was in)")
                changes.append(("removed", f, costs[f], current))
                if frozenset(current) in seen:
                    break
                seen.add(frozenset(current))
                continue
            best = None
            for f in current[:-1]:
                for g in self.alternatives.get(f, ()) + self.set_aside.get(f, ()):
                    if g in current or g not in self.instances:
                        continue
                    trial = tuple(g if e == f else e for e in current)
                    if frozenset(trial) in seen:
                        continue
                    if progress is not None:
                        progress(f"swap: {g} instead of {f}")
                    t = self.get(trial, warm=(s,))
                    gain = s.bic - t.bic
                    if gain > 1e-6 and t.plausible and (best is None or gain > best[3]):
                        best = (f, g, trial, gain)
            if best is None:
                break
            f, g, trial, gain = best
            self.removed.append(f"{f} (swapped for {g}, {gain:.1f} BIC units better)")
            changes.append(("swapped", f, g, gain, trial))
            current = trial
            seen.add(frozenset(current))
        return changes

    def explore(self, current: tuple, first, budget: int | None = None, progress=None, top: int = 3,
                at_noise: bool = False) -> tuple | None:
        """Pairs the stepwise path did not reach (module docstring, items 4 and 5): for a path that ended short of
        the noise, or (``at_noise``) for one that ended at it, where only the pairs the screen finds within
        :data:`EQUAL` BIC units of ``current`` are fitted.

        ``first`` is the diagnosis of the baseline: each of its credible significant candidates (the ``top`` best
        by BIC) is paired with every candidate that fitted but showed nothing alone, or had no signature at all (an
        effect invisible until another is in: the pairs a stepwise path cannot reach once a look-alike of the
        partner is in), and with the other credible significant ones, where the two single fits together gain at
        least half of what the path gained over the baseline; the significant candidates that are not credible
        alone (the three best) are paired with the credible significant ones under the same rule (fitted after the
        pairs of credible candidates), or, where none is credible, with each other; with no significant candidate,
        the pairs of credible quiet ones are screened (:meth:`screen_pair`). Each pair not fitted yet is refitted
        jointly, from the values of its single fits, the pairs of the better single fits first, until ``budget``
        model evaluations are spent. Returns the effects of the best
        credible pair fitted here when it fits better than ``current`` by more than :data:`STAY` BIC units (the
        evidence an effect needs to stay), else None.
        """
        ok = [c for c in first.candidates if c.status == "ok" and frozenset({c.effect}) in self.sets]
        significant = sorted((c for c in ok if c.significant and self.sets[frozenset({c.effect})].plausible),
                             key=lambda c: c.bic)[:top]
        quiet = [c for c in ok if not c.significant] + self._unsigned(first)
        # a pair far behind the path would need its partner to do most of the work: only pairs whose members'
        # single fits together gain at least half of what the path gained over the baseline
        base_bic = first.baseline.bic
        need = 0.5 * (base_bic - self.get(current).bic)

        def gain(c):
            return max(base_bic - c.bic, 0.0) if c.status == "ok" and math.isfinite(c.bic) else 0.0

        pairs = {}
        behind = set()   # pairs fitted after the others: a member not credible alone is the weaker hypothesis
        if not at_noise:
            # with every quiet candidate, and with each other: the path may have taken a look-alike of both members
            # of a pair (a strain softening fitting as well as an adhesion or a microtexture alone), on top of which
            # neither partner is credible, and swaps replace one effect at a time
            for i, a in enumerate(significant):
                for b in quiet + significant[i + 1:]:
                    key = frozenset({a.effect, b.effect})
                    if key not in self.sets and key not in pairs and gain(a) + gain(b) >= need:
                        pairs[key] = ((a.effect, b.effect), min(a.bic, b.bic if b.status == "ok" else math.inf))
            # a significant candidate that is implausible alone may be standing in for a partner it lacks (an
            # adhesion whose peak speed runs off to 1e6 m/s, a microtexture whose H sits on 1, while together they
            # fit at the noise), and a partner may make it credible, as in the swaps
            aside = sorted((c for c in ok if c.significant and not self.sets[frozenset({c.effect})].plausible),
                           key=lambda c: c.bic)[:top]
            if significant:
                # with each credible significant candidate (the path took a look-alike of the pair, and the
                # implausible member, fitting worse alone, was never its alternative: an adhesion with its peak at
                # the slowest speeds beside a microtexture, behind a strain softening), where the gain rule allows,
                # after the pairs of credible candidates
                for a in aside:
                    for b in significant:
                        key = frozenset({a.effect, b.effect})
                        if key not in self.sets and key not in pairs and gain(a) + gain(b) >= need:
                            pairs[key] = ((b.effect, a.effect), min(a.bic, b.bic))
                            behind.add(key)
            else:
                # every significant candidate is implausible alone, so the path added nothing: the pairs of the
                # three best are fitted jointly, the better single fits first
                for i, a in enumerate(aside):
                    for b in aside[i + 1:]:
                        key = frozenset({a.effect, b.effect})
                        if key not in self.sets and key not in pairs:
                            pairs[key] = ((a.effect, b.effect), min(a.bic, b.bic))
        start = self.n_evals
        order = (sorted((v for k, v in pairs.items() if k not in behind), key=lambda t: t[1])
                 + sorted((pairs[k] for k in behind), key=lambda t: t[1]))
        # superadditive pairs the gain rule cannot see: screened by a linearized joint fit; a candidate that changed
        # no prediction at all alone (a flash temperature on a PSD that stops short of the scales it heats) is
        # screened with every credible candidate that showed nothing either (the microtexture that makes it act)
        now_bic = self.get(current).bic
        invisible = [c for c in quiet if _changes_nothing(c)]
        credible_quiet = [c for c in quiet if c.status == "ok" and not _changes_nothing(c)
                          and self.sets[frozenset({c.effect})].plausible]
        partners = [(a, quiet) for a in significant] + [(a, invisible) for a in credible_quiet]
        if not at_noise and not significant:
            # nothing was significant alone, so the path added nothing: two effects may each move the friction too
            # little alone and still fit together (a microtexture and a flash temperature, each fitted alone to a
            # road whose PSD stops short, push the same rows in opposite directions); every pair of credible quiet
            # candidates is screened
            partners += [(a, credible_quiet) for a in credible_quiet]
        screened = []
        seen = set()
        for a, others in partners:
            for b in others:
                key = frozenset({a.effect, b.effect})
                if key in self.sets or key in pairs or a.effect == b.effect or (a.effect, b.effect) in seen:
                    continue
                seen.add((a.effect, b.effect))
                # a candidate that acted alone adds about its own gain: the pair can tie only when that is enough;
                # one that showed nothing (no signature, or parameters the data do not identify) may be invisible
                # until its partner is in, whatever the partner's own fit
                if b.status == "ok" and b.identified and a.bic - gain(b) >= now_bic + EQUAL:
                    continue
                if budget is not None and self.n_evals - start >= budget:
                    break
                if progress is not None:
                    progress(f"screening: {a.effect} with {b.effect}")
                # a superset of the current set is never listed beside it: it counts only if it could replace it
                limit = now_bic - STAY if a.effect in current else now_bic + EQUAL
                bound, reached = self.screen_pair(a.effect, b.effect, limit=limit)
                # the short fit reaches within EQUAL of the limit: the joint fit, which can only do better, may tie
                if bound < limit and reached < limit + EQUAL:
                    pairs[key] = ((a.effect, b.effect), reached)
                    screened.append(((a.effect, b.effect), reached))
        order += sorted(screened, key=lambda t: t[1])
        if not at_noise:
            # a significant candidate with one whose parameters the data do not identify alone: the partner may act
            # only once the first moves far from its own single fit (a flash temperature on a PSD that stops short,
            # beside a microtexture whose cut-off must reach several times past where it fitted alone), which
            # neither the gain rule nor a screen linearized at that single fit can see; fitted jointly last, within
            # the budget
            late = []
            for a in significant:
                for b in quiet:
                    key = frozenset({a.effect, b.effect})
                    if key in self.sets or key in pairs or a.effect == b.effect or (b.status == "ok" and b.identified):
                        continue
                    pairs[key] = ((a.effect, b.effect), a.bic)
                    late.append(pairs[key])
            order += sorted(late, key=lambda t: t[1])
        todo = [((a, b), tuple(self.sets[k] for k in (frozenset({a}), frozenset({b})) if k in self.sets),
                 f"exploring: {a} with {b}") for (a, b), _ in order]
        fitted, stopped = self._fit_in_turn(todo, budget, start, progress)
        if stopped:
            what = "the pairs that may tie" if at_noise else "the exploration"
            self.explored.append(f"{what} stopped at its budget of {budget} model evaluations "
                                 f"({len(fitted)} of {len(pairs)} pairs fitted)")
        now = self.get(current)
        best = _better(fitted, now)
        if best is None:
            return None
        self.explored.append(f"{best.label} ({now.bic - best.bic:.1f} BIC units better than {now.label}, which the "
                             "stepwise path reached)")
        return tuple(best.effects)

    @doi(SEBER_WILD_1989, SCHWARZ_1978)
    def screen_pair(self, a: str, b: str, limit: float | None = None) -> tuple[float, float]:
        r"""The BIC the pair {a, b} may reach (module docstring, item 5): a bound, and, when the bound is below
        ``limit``, a value the pair does reach.

        The bound: from the single fit of ``a`` (weighted residual :math:`r`, Jacobian :math:`J_a` of its
        parameters), with ``b`` switched on at its fitted values and at :math:`2 + 2k_b` Halton points of its box
        (the change :math:`g` it makes), the least squares :math:`\min_{\delta, t \ge 0} |r - J_a \delta - t g|^2`
        (one Gauss-Newton step of the joint fit, Seber & Wild, Nonlinear Regression, Wiley 1989, Sec. 14.1; a
        negative amplitude, which would turn the effect round, counts as none), the best over the points. Exact
        when both effects are linear in their parameters; otherwise optimistic as a rule, and far so where no
        parameter value of ``b`` makes a change as small as the scaled one (a flash temperature whose every
        setting moves the friction a lot): hence the second value, the best of two bounded Gauss-Newton steps of the
        pair's joint fit (its Jacobian by central differences, the step by bounded linear least squares,
        :func:`scipy.optimize.lsq_linear`) from the point whose bound was best: a value the pair reaches, which the
        joint fit can only improve on.

        Returns
        -------
        (bound, reached) : tuple of float
            BIC units; ``reached`` is inf when the bound is not below ``limit`` (no fit made) or ``limit`` is None.
        """
        ctx, st = self.ctx, self.ctx.settings
        sa = self.sets[frozenset({a})]
        contact = sa.contact or st.contact
        names_a = list(self.base_fit) + [f"{a}.{p}" for p in self.free.get(a, ())]
        if a not in self._jacobians:
            space_a = ParameterSpace(ctx.parameters(sa.model, names_a))
            fa = Fitter(st.predictor, st.y, st.w, sa.model, space_a, max_evals=4 * len(space_a) + 4, contact=contact)
            self._jacobians[a] = fa.jacobian(fa.space.u_of(sa.model, contact)) * st.w[:, None]
            self.n_evals += fa.n_evals
        Ja = self._jacobians[a]
        model = sa.model.with_effect(self.instances[b])
        space = ParameterSpace(ctx.parameters(model, names_a + [f"{b}.{p}" for p in self.free.get(b, ())]))
        dims = np.array([j for j, p in enumerate(space.params) if p.key.partition(".")[0] == b], dtype=int)
        k = sa.n_params + dims.size
        fitter = Fitter(st.predictor, st.y, st.w, model, space,
                        max_evals=3 + 2 * max(dims.size, 1) + 1 + _GN_STEPS * (2 * len(space) + 1), contact=contact)
        u0 = space.u_of(model, contact)
        r = (st.y - sa.predicted) * st.w
        points = [u0]
        for p in halton(dims.size, 2 + 2 * dims.size, seed=0) if dims.size else ():
            q = u0.copy()
            q[dims] = p
            points.append(q)
        best, start = math.inf, None
        for q in points:
            mu = fitter.mu(q)
            if mu is None:
                continue
            g = (mu - sa.predicted) * st.w
            A = np.column_stack([Ja, g])
            coef = np.linalg.lstsq(A, r, rcond=None)[0]
            if not coef[-1] > 0.0:
                A = Ja
                coef = np.linalg.lstsq(A, r, rcond=None)[0] if A.shape[1] else np.zeros(0)
            res = r - A @ coef
            if float(res @ res) < best:
                best, start = float(res @ res), q
        bound = bic(best, st.n, k, st.sigma_known) if math.isfinite(best) else math.inf
        reached = math.inf
        if limit is not None and bound < limit and start is not None:
            u = start
            try:
                for _ in range(_GN_STEPS):
                    u = _gauss_newton_step(fitter, u)
            except BudgetExhausted:
                pass
            c = fitter.best[0]
            reached = bic(c, st.n, k, st.sigma_known) if math.isfinite(c) else math.inf
        self.n_evals += fitter.n_evals
        return bound, reached

    def resume(self, current: tuple, budget: int | None = None, progress=None, rounds: int = 2) -> tuple | None:
        """Continue the fits that stopped at their budget of model evaluations where they could change the answer
        (module docstring, item 6).

        A fit that stopped at its budget reports the best point it reached: its BIC is an upper bound, and the set
        may fit better. When ``current`` misses the noise (lack of fit, or a pattern left), or is not credible (at
        the noise, a credible ``current`` is left to the pair screen, :meth:`explore`), every such set within
        :data:`EQUAL` BIC units of it, itself included, is fitted again from that point with a budget of its own
        (:meth:`_continue`), the best first, at most ``rounds`` times (once when a continuation gains nothing),
        until none is left within reach or ``budget`` model evaluations are spent. A credible fit is kept when its
        continuation leaves the plausible ranges. Returns the effects of the best credible set that then fits
        better than ``current`` by more than :data:`STAY` BIC units, else None.
        """
        current = tuple(current)
        now = self.get(current)
        if fits_at_noise(now) and now.plausible:
            return None
        start = self.n_evals
        continued = set()
        for _ in range(rounds):
            now = self.get(current)
            todo = sorted((s for s in self.sets.values() if s.budget_stopped and s.bic < now.bic + EQUAL
                           and self._continued.get(s.key, 0) < rounds), key=lambda s: s.bic)
            if not todo:
                break
            for s in todo:
                if budget is not None and self.n_evals - start >= budget:
                    break
                if progress is not None:
                    progress(f"continuing the fit of {s.label}, stopped at its budget of model evaluations")
                self._continued[s.key] = self._continued.get(s.key, 0) + 1
                cont = self._continue(s)
                # a credible fit is not traded for one that leaves the plausible ranges (a set listed as equally
                # supported at credible values stays listed)
                new = self._keep(cont) if cont.plausible or not s.plausible else s
                continued.add(s.key)
                if new.bic < s.bic - 0.05:
                    self.resumed.append(f"{s.label} (BIC {s.bic:.1f} where its fit stopped, {new.bic:.1f} continued)")
                else:
                    self._continued[s.key] = rounds       # it went no further: once is enough
        now = self.get(current)
        # only a set this continuation moved: the others were judged by the path already
        better = [self.sets[k] for k in continued if self.sets[k].plausible and self.sets[k].bic < now.bic - STAY]
        return min(better, key=lambda s: s.bic).effects if better else None

    def reduce(self, current: tuple, budget: int | None = None, progress=None) -> tuple | None:
        """The subsets of the sets within reach of the answer (module docstring, item 7).

        When ``current`` misses the noise or is not credible, every fitted set of two or more effects within
        :data:`EQUAL` BIC units of it (credible or not, ``current`` itself left to the backward elimination) has each
        effect dropped in turn; each subset not fitted yet, or fitted only until its budget stopped it, is refitted
        jointly from that set's values (:meth:`get`; the better of the two fits is kept), the subsets of the better
        sets first, until ``budget`` model evaluations are spent. Returns the effects of the best credible subset
        fitted here when it fits better than ``current`` by more than :data:`STAY` BIC units, else None.
        """
        current = tuple(current)
        now = self.get(current)
        if fits_at_noise(now) and now.plausible:
            return None
        start = self.n_evals
        within = sorted((t for t in self.sets.values() if len(t.effects) >= 2 and t.key != now.key
                         and t.bic < now.bic + EQUAL), key=lambda t: t.bic)
        todo = [(sub, (t,), f"refitting {' + '.join(sub)}, a subset of {t.label}")
                for t in within for sub in (tuple(e for e in t.effects if e != f) for f in t.effects)]
        fitted, stopped = self._fit_in_turn(todo, budget, start, progress, refit_stopped=True)
        if stopped:
            self.reduced.append(f"the subsets of the sets within reach stopped at their budget of {budget} model "
                                f"evaluations ({len(fitted)} fitted)")
        best = _better(fitted, now)
        if best is None:
            return None
        self.reduced.append(f"{best.label} ({now.bic - best.bic:.1f} BIC units better than {now.label}; a subset of "
                            "a set within reach of it)")
        return tuple(best.effects)

    def replace_unidentified(self, current: tuple, first, budget: int | None = None, progress=None) -> None:
        """Fit the sets with each effect of ``current`` whose parameters the data do not identify replaced by each
        credible candidate of the baseline's diagnosis ``first`` (module docstring, item 9).

        An effect with a parameter the data leave open may be standing in for another (a strain softening whose loss
        factor runs onto its bound beside a microtexture, while the hidden pair is flash temperature +
        microtexture): the swaps of :meth:`prune` try only the alternatives named when it was added, which need not
        include that one. The replacements are the candidates of ``first`` fitted alone and credible there (the
        significant ones, the better single fits first, then those that showed nothing alone), then those with no
        signature (never fitted alone); then each such effect is kept and the same replacements take the place of
        each other effect of ``current`` (the effect left open may act only beside a partner that ``current``
        lacks). Each set not fitted yet is refitted jointly from the values of ``current``
        and of the replacement's single fit (the values of ``current`` alone for one with no signature), in that
        order, until ``budget`` model evaluations are spent. Nothing is returned: the sets fitted here compete in
        :meth:`prefer` (which takes the best credible one whose every effect earns its place, where it fits better)
        and for the equally supported sets; :attr:`Selection.replaced` says what was fitted.
        """
        current = tuple(current)
        if not current:
            return
        now = self.get(current)
        loose = [e for e in current if any(k.partition(".")[0] == e for k in now.not_identified)]
        if not loose:
            return
        fitted_alone = [c for c in first.candidates if c.status == "ok" and c.effect not in current
                        and frozenset({c.effect}) in self.sets and self.sets[frozenset({c.effect})].plausible]
        # the significant ones first, then those that showed nothing alone (a flash temperature on a PSD that stops
        # short is invisible until the microtexture is in, and an effect left open may stand in for its partner)
        singles = sorted(fitted_alone, key=lambda c: (not c.significant, c.bic))
        singles += [c for c in self._unsigned(first) if c.effect not in current]
        # the effects left open first; then each of them is kept and the others are replaced: it may act only
        # beside a partner that the answer lacks, while another effect of the answer stands in for the pair (a
        # flash temperature whose q_m runs to where it does nothing, beside an adhesion that fits what flash
        # temperature + microtexture do, each of those two fitting worse than the baseline alone)
        todo = []
        for f in loose + [e for e in current if e not in loose]:
            beside = "" if f in loose else f", beside {', '.join(loose)}"
            for c in singles:
                trial = tuple(c.effect if e == f else e for e in current)
                alone = self.sets.get(frozenset({c.effect}))
                todo.append((trial, (now,) if alone is None else (now, alone),
                             f"refitting with {c.effect} in place of {f}{beside}"))
        start = self.n_evals
        fitted, stopped = self._fit_in_turn(todo, budget, start, progress)
        for t in fitted:
            gone = next(e for e in current if e not in t.effects)
            came = next(e for e in t.effects if e not in current)
            if gone in loose:
                why = ", ".join(k for k in now.not_identified if k.partition(".")[0] == gone)
                said = f"{came} in place of {gone}, whose {why} the data do not identify"
            else:
                why = ", ".join(k for k in now.not_identified)
                said = f"{came} in place of {gone}, beside {why}, which the data do not identify"
            self.replaced.append(f"{t.label} ({said}): {t.bic - now.bic:+.1f} BIC units from {now.label}")
        if stopped:
            self.replaced.append(f"the replacements stopped at their budget of {budget} model evaluations "
                                 f"({len(fitted)} of {len(todo)} sets fitted)")

    def prefer(self, current: tuple, progress=None) -> tuple | None:
        """The best set of those fitted, in place of the path's answer (module docstring, item 8).

        The fitted sets that fit better than ``current`` (lower BIC) -- or, when ``current`` is not credible (a
        parameter on a search bound or outside its plausible range), within :data:`EQUAL` BIC units of it -- are
        taken in order of BIC; the first that is credible and whose every effect earns its place (dropping it costs
        at least :data:`STAY` BIC units; the subsets not fitted yet are fitted from its values) is returned, else
        None (and None for an empty ``current``). A set with a parameter the data do not identify does not replace a
        credible ``current`` whose parameters are all identified.
        """
        current = tuple(current)
        if not current:
            return None
        now = self.get(current)
        credible = now.plausible
        limit = now.bic if credible else now.bic + EQUAL
        close = sorted((s for s in self.sets.values() if s.effects and s.key != now.key and s.bic < limit - 1e-9),
                       key=lambda s: s.bic)
        for s in close:
            if not s.plausible:
                continue
            if progress is not None:
                progress(f"checking the effects of {s.label}")
            # the final rule would take apart a set one of whose effects does not earn its place (a superset of the
            # answer that fits a few units better, say) and leave the answer; the subsets fitted already are looked
            # at first, so that such a set costs no new fit
            subsets = sorted((tuple(e for e in s.effects if e != f) for f in s.effects),
                             key=lambda t: frozenset(t) not in self.sets)
            if any(self.get(t, warm=(s,)).bic - s.bic < STAY for t in subsets):
                continue
            # a parameter the data do not identify (a flash temperature whose q_m runs to where it acts fully) is
            # not charged in the BIC, which counts the parameters that change the prediction: such a set does not
            # replace a credible answer whose parameters are all identified (it could make only "indicated"); asked
            # last, since it may need the set's profiles
            if credible and s.not_identified and not now.not_identified:
                continue
            if credible:
                self.preferred.append(f"{s.label} ({now.bic - s.bic:.1f} BIC units better than {now.label}, which "
                                      "the search reached, with every effect earning its place)")
            else:
                self.preferred.append(f"{s.label} ({s.bic - now.bic:+.1f} BIC units from {now.label}, which is not "
                                      f"credible: {'; '.join(now.issues)})")
            return tuple(s.effects)
        return None

    def _unsigned(self, first) -> list:
        """The candidates of the diagnosis ``first`` with no signature that can be fitted in a set (an instance to
        start from), their instances and free parameters registered for :meth:`get`."""
        out = []
        for c in first.candidates:
            if c.status == "no signature" and c.instance is not None:
                self.instances.setdefault(c.effect, c.instance)
                self.free.setdefault(c.effect, tuple(c.free))
                out.append(c)
        return out

    def _fit_in_turn(self, todo, budget: int | None, start: int, progress=None,
                     refit_stopped: bool = False) -> tuple[list, bool]:
        """Fit the sets ``todo`` (``(effects, warm, message)`` each; :meth:`get`) not fitted yet, in turn, until
        ``budget`` model evaluations counted from ``start`` (:attr:`n_evals` then) are spent; returns the sets
        fitted and whether the budget stopped them. With ``refit_stopped``, a set whose fit stopped at its budget is
        fitted again from the ``warm`` sets' values (once; the better fit is kept)."""
        fitted = []
        for effects, warm, message in todo:
            key = frozenset(effects)
            old = self.sets.get(key)
            again = refit_stopped and old is not None and old.budget_stopped and key not in self._refitted
            if old is not None and not again:
                continue
            if budget is not None and self.n_evals - start >= budget:
                return fitted, True
            if progress is not None:
                progress(message)
            if again:
                self._refitted.add(key)
                fitted.append(self._keep(self._fit(tuple(effects), warm)))
            else:
                fitted.append(self.get(effects, warm=warm))
        return fitted, False

    def _continue(self, s: EffectSet) -> EffectSet:
        """The refit of ``s`` from its fitted values with a budget of model evaluations of its own: a global search
        over all its parameters (Halton design and local fits, :func:`validation.refit.global_fit`)."""
        ctx = self.ctx
        names = list(self.base_fit) + [f"{e}.{p}" for e in s.effects for p in self.free.get(e, ())]
        space = ParameterSpace(ctx.parameters(s.model, names))
        settings = ctx.settings if s.contact is None else replace(ctx.settings, contact=s.contact)
        # a global search of every parameter from that point: a fit that ran out of evaluations may have left
        # the basin of the optimum unvisited (a candidate fitted on top of a set varies its own parameters only)
        return self._global_refit(s.effects, s.model, space, settings, (), f"{s.source}, continued")

    def finish(self, current: tuple, probe=None) -> Selection:
        """The final rule (every effect of the best set earns more than :data:`STAY` BIC units), the equally
        supported sets and the measurements that separate them (module docstring)."""
        current = tuple(current)
        while current:
            s = self.get(current)
            costs = {f: self.dropped(s, f).bic - s.bic for f in current}
            f = min(costs, key=costs.get)
            if costs[f] >= STAY:
                break
            self.removed.append(f"{f} (dropping it from the final set cost only {costs[f]:+.1f} BIC units)")
            current = tuple(e for e in current if e != f)
        best = self.get(current)
        costs = {f: self.get(tuple(e for e in current if e != f)).bic - best.bic for f in current}
        visited = sorted(self.sets.values(), key=lambda s: s.bic)
        close = [s for s in visited if s is not best and s.bic - best.bic < EQUAL and s.plausible
                 and not (best.key < s.key)]
        # a superset of a listed set is left out when its extra effects do not earn their place (STAY)
        supported = [s for s in close if not any(o.key < s.key and s.bic > o.bic - STAY for o in close + [best])]
        seps, seps_in = [], []
        if probe is not None:
            for s in supported:
                pair = probe.pair((best.label, s.label), [(best.model, best.contact), (s.model, s.contact)])
                if pair is not None:
                    seps.append(pair[0])
                    if pair[1] is not None:
                        seps_in.append(pair[1])
        base = self.sets.get(frozenset())
        calibration = check_calibration([(s.label, s.effects, s.predicted, s.n_params, s.bic) for s in visited],
                                        (best.label, best.effects, best.bic), self.ctx,
                                        baseline=None if base is None else (base.model, base.contact or
                                                                            self.ctx.settings.contact,
                                                                            base.n_params, base.bic),
                                        conditions=[(s.label, s.effects, s.model,
                                                     s.contact or self.ctx.settings.contact, s.n_params, s.bic)
                                                    for s in visited if s.effects],
                                        on_answer=not fits_at_noise(best),
                                        refits={s.key: r for s in visited if (r := SetFit.of(
                                            s.model, s.contact or self.ctx.settings.contact, s.covariance,
                                            s.jacobian)) is not None})
        # what the selection reports, computed now (so that its model evaluations are counted with the search's):
        # the intervals of the sets it names, and the credibility of every set fitted
        for s in (best, *supported):
            _ = s.notes, [e.interval95 for e in s.estimates]
        for s in visited:
            _ = s.plausible
        return Selection(best=best, supported=tuple(supported), drop_costs=costs, separations=tuple(seps),
                         separations_in_range=tuple(seps_in), visited=tuple(visited), removed=tuple(self.removed),
                         explored=tuple(self.explored), resumed=tuple(self.resumed), reduced=tuple(self.reduced),
                         preferred=tuple(self.preferred), replaced=tuple(self.replaced),
                         calibration=calibration)


def _default_start(space, model, u, effects) -> np.ndarray | None:
    """``u`` with the parameters of the ``effects`` at their declared defaults (:class:`persson.effects.Parameter`,
    the values a candidate's diagnosis starts from), or None where that changes nothing. A default that is a
    placeholder (a value computed from the model, such as ``q1 = 0``) keeps the coordinate as it is."""
    u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
    out = u.copy()
    for j, p in enumerate(space.params):
        if p.effect not in effects:
            continue
        try:
            declared = {q.name: q for q in model.effect(p.effect).parameters}[p.name]
        except (LookupError, AttributeError, ValueError):
            continue
        if declared.sentinel is not None and declared.default == declared.sentinel:
            continue
        out[j] = p.to_u(declared.default)
    return None if np.array_equal(out, u) else out


def fits_at_noise(s: EffectSet) -> bool:
    """Whether the set fits at the noise level: lack of fit consistent with the noise, no pattern left."""
    return bool(s.lack is not None and s.lack.consistent and not (s.pattern is not None and s.pattern.found))


def _changes_nothing(c) -> bool:
    """Whether a candidate of a diagnosis changed no prediction alone: no signature, or a fit whose every parameter
    has no effect on the rows."""
    if c.status == "no signature":
        return True
    est = getattr(c, "estimates", ()) or ()
    return bool(est) and all(e.method == "no effect on these rows" for e in est)


def _better(fitted, now: EffectSet) -> EffectSet | None:
    """The best credible set of ``fitted`` when it fits better than ``now`` by more than :data:`STAY` BIC units (the
    evidence an effect needs to stay), else None."""
    # credibility last: it may need the intervals of a set
    best = min((t for t in fitted if t.bic < now.bic - STAY and t.plausible), key=lambda t: t.bic, default=None)
    return best


def _from_baseline(effects: tuple, b, source: str) -> EffectSet:
    """The set ``effects`` as the refitted baseline ``b`` (a :class:`validation.candidates.Baseline`); its intervals
    stay deferred where ``b``'s are (:func:`validation.refit.with_uncertainty` with ``defer=True``)."""
    fit = b.fit
    pending = None if fit is None else fit.pending
    extra = {}
    if pending is not None:
        extra = dict(fit_notes=tuple(fit.notes), fitted={e.key: e.value for e in fit.estimates},
                     # without intervals the estimates flag every parameter on a bound or out of its range
                     clean=not any(e.issue for e in fit.estimates), credibility=fit.credibility)
    return EffectSet(effects=tuple(effects), model=b.model, contact=b.contact, predicted=b.predicted, rss=b.rss,
                     bic=b.bic, rmse=b.rmse, n_params=b.n_params, estimates=raw(b, "estimates"), lack=b.lack,
                     pattern=b.pattern, source=source, notes=raw(b, "notes"), covariance=_covariance_of(b),
                     jacobian=_jacobian_of(b), **extra)


def _from_candidate(effects: tuple, c, n_base: int, source: str) -> EffectSet:
    """The set ``effects`` as the fitted candidate ``c`` of a diagnosis (a :class:`validation.candidates.Candidate`,
    ``n_base`` the parameters of that diagnosis' baseline); its intervals stay deferred where ``c``'s are
    (:func:`validation.candidates.finish_candidate` with ``defer``)."""
    fit = c.fit
    extra = {}
    if fit is not None and fit.pending is not None and not fit.pending.ready:
        # the fit's notes before its intervals hold the budget note (the intervals add their own, not that one);
        # a candidate with a bare issue has its intervals already (finish_candidate), so a deferred one is clean
        extra = dict(fit_notes=tuple(fit.notes), fitted={e.key: e.value for e in fit.estimates}, clean=True)
        estimates = Deferred(lambda: c.baseline_estimates + c.estimates)
        notes = Deferred(lambda: tuple(c.notes))
    else:
        estimates, notes = c.baseline_estimates + c.estimates, tuple(c.notes)
    return EffectSet(effects=tuple(effects), model=c.model, contact=c.contact, predicted=c.predicted, rss=c.rss,
                     bic=c.bic, rmse=c.rmse, n_params=n_base + c.n_params, estimates=estimates, lack=c.lack,
                     pattern=c.pattern, source=source, notes=notes, covariance=c.covariance, jacobian=c.jacobian,
                     **extra)


def _covariance_of(baseline):
    """The covariance of a refitted baseline's parameters (None when it has none)."""
    fit = getattr(baseline, "fit", None)
    return None if fit is None else fit.covariance


def _jacobian_of(baseline):
    """d mu / d u of a refitted baseline's prediction at its optimum (None without a covariance)."""
    fit = getattr(baseline, "fit", None)
    return None if fit is None or fit.covariance is None else fit.jacobian


#: Gauss-Newton steps of the pair screen's second value (:meth:`SetSearch.screen_pair`).
_GN_STEPS = 2


def _gauss_newton_step(fitter, u):
    """One bounded Gauss-Newton step of ``fitter``'s weighted least squares from ``u`` (in the unit box): the
    Jacobian by central differences, the step from :func:`scipy.optimize.lsq_linear` within the box; returns the new
    point (evaluated, so that ``fitter.best`` holds the best point seen)."""
    u = np.asarray(u, dtype=float)
    r = fitter.resid(u)
    J = fitter.jacobian(u) * fitter.w[:, None]
    step = lsq_linear(J, r, bounds=(-u, 1.0 - u)).x
    new = np.clip(u + step, 0.0, 1.0)
    fitter.chi2(new)
    return new
