"""validation: the search over sets of effects (issue 32), on small problems whose answer is known by construction.

Three test effects act on 30 sliding rows (3 temperatures x 10 speeds, known noise ``mu_std`` = 0.005), with
x = log10(v / 1 mm/s) / 3 running from 0 to 1 over the speeds:

* ``test_texture`` adds a constant ``a`` and marks the surface as textured;
* ``test_heat`` adds ``h x^2`` on a textured surface only: without the texture it has no signature at all (like
  the flash temperature on a road whose PSD stops short until the microtexture is in the model);
* ``test_slope`` adds ``k x``: it mimics part of the heat's rise.

The data are baseline + texture (a = 0.05) + heat (h = 0.15). A path that never revisits a choice takes the slope
first (it fits the data better than the constant), then the texture, then the heat, and keeps all three. The set
search must end with {texture, heat}: the heat becomes visible once the texture is in, and the slope, made
redundant by the heat, is removed by the backward elimination (dropping it costs less than 10 BIC units).

Two near-parallel candidates (``test_line`` = k x, the truth, and ``test_bend`` = k (x + 0.15 x^2)) are equally
supported: both are named, each with parameters and intervals, with the measurement that separates them.

A look-alike ``test_mimic`` = b + k x fits the texture + heat data better than the texture alone and takes the
texture's place on the stepwise path; with it in, the texture adds nothing (its constant is the mimic's) and the heat
stays invisible (no texture), so the path ends short of the noise. The pairs it did not reach are then explored:
texture + heat is found, fits at the noise, and replaces the mimic.

An ``test_ember`` (-h x^2) acts only where the texture exceeds 0.03: with texture 0.055 + ember 0.09 the texture
alone fits about 0.025, where the ember does nothing, and the mimic takes the path; the pair is out of reach of the
gain rule and of a screen linearized at the texture's single fit, and is fitted all the same when exploring.

With a weaker heat the mimic fits at the noise and the path stops there; texture + heat, never on the path, is
screened (a linearized joint fit, exact for these linear effects) and fitted: it ties with the mimic (h = 0.008,
named as equally supported) or fits better by more than 10 BIC units (h = 0.015, replaces it). Both effects are
linear in their parameters, so every chi2 is checked against numpy's least squares.
"""

import math
from dataclasses import dataclass

import numpy as np
import pytest

import materials
import persson
import surfaces
import validation
from persson.effects import Effect, Parameter

SURFACE = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e5, hrms=1e-4)
TREAD = materials.example_tread()
SIGMA = 0.005


def _x(state):
    return np.log10(state.conditions.speed / 1e-3) / 3.0


@pytest.fixture(scope="module")
def effects():
    """The test effects, registered in a throw-away copy of the registry for the module."""
    from persson.effects import base

    saved = base._REGISTRY
    base._REGISTRY = dict(saved)

    @dataclass(frozen=True)
    class Texture(Effect):
        """A constant added to mu; marks the surface as textured."""

        name = "test_texture"
        parameters = (Parameter("a", 0.02, (0.0, 0.3), "1", "constant added to mu", physical_limits=(0.0,)),)
        a: float = 0.02

        def transform_conditions(self, conditions):
            return conditions.replace(extra={**conditions.extra, "texture": self.a})

        def friction_term(self, state):
            return np.full_like(state.conditions.speed, self.a)

    @dataclass(frozen=True)
    class Heat(Effect):
        """h x^2 on a textured surface, nothing without the texture."""

        name = "test_heat"
        parameters = (Parameter("h", 0.05, (0.0, 1.0), "1", "rise over the speeds", physical_limits=(0.0,)),)
        h: float = 0.05

        def friction_term(self, state):
            textured = state.conditions.extra.get("texture", 0.0) > 0.0
            return self.h * _x(state) ** 2 * (1.0 if textured else 0.0)

    @dataclass(frozen=True)
    class Slope(Effect):
        """k x."""

        name = "test_slope"
        parameters = (Parameter("k", 0.05, (-1.0, 1.0), "1", "slope over the speeds"),)
        k: float = 0.05

        def friction_term(self, state):
            return self.k * _x(state)

    @dataclass(frozen=True)
    class Line(Effect):
        """k x (the truth of the parallel pair)."""

        name = "test_line"
        parameters = (Parameter("k", 0.05, (0.0, 1.0), "1", "slope", physical_limits=(0.0,)),)
        k: float = 0.05

        def friction_term(self, state):
            return self.k * _x(state)

    @dataclass(frozen=True)
    class Bend(Effect):
        """k (x + 0.15 x^2): nearly parallel to the line on the measured speeds."""

        name = "test_bend"
        parameters = (Parameter("k", 0.05, (0.0, 1.0), "1", "slope", physical_limits=(0.0,)),)
        k: float = 0.05

        def friction_term(self, state):
            x = _x(state)
            return self.k * (x + 0.15 * x * x)

    @dataclass(frozen=True)
    class Mimic(Effect):
        """b + k x: takes the texture's constant and part of the heat's rise, but no curvature."""

        name = "test_mimic"
        parameters = (Parameter("b", 0.02, (0.0, 0.3), "1", "constant", physical_limits=(0.0,)),
                      Parameter("k", 0.05, (-1.0, 1.0), "1", "slope over the speeds"))
        b: float = 0.02
        k: float = 0.05

        def friction_term(self, state):
            return self.b + self.k * _x(state)

    @dataclass(frozen=True)
    class Marker(Effect):
        """m (T - 25 C) / 15 (no mean over the temperatures); marks the surface as textured."""

        name = "test_marker"
        parameters = (Parameter("m", 0.02, (0.0, 0.3), "1", "rise over the temperatures", physical_limits=(0.0,)),)
        m: float = 0.02

        def transform_conditions(self, conditions):
            return conditions.replace(extra={**conditions.extra, "texture": self.m})

        def friction_term(self, state):
            return self.m * (np.broadcast_to(state.conditions.temperature, state.conditions.speed.shape) - 25.0) / 15.0

    @dataclass(frozen=True)
    class Swing(Effect):
        """h x^2 on a textured surface, -h x^2 / 2 on a plain one: alone it can only lower the rise it makes with
        the texture."""

        name = "test_swing"
        parameters = (Parameter("h", 0.05, (0.0, 1.0), "1", "rise over the speeds", physical_limits=(0.0,)),)
        h: float = 0.05

        def friction_term(self, state):
            textured = state.conditions.extra.get("texture", 0.0) > 0.0
            return self.h * _x(state) ** 2 * (1.0 if textured else -0.5)

    @dataclass(frozen=True)
    class Floor(Effect):
        """A constant a, plausible from 0.03 up (searched from 0)."""

        name = "test_floor"
        parameters = (Parameter("a", 0.05, (0.0, 0.3), "1", "constant", physical_limits=(0.0,),
                                plausible=(0.03, 0.3)),)
        a: float = 0.05

        def friction_term(self, state):
            return np.full_like(state.conditions.speed, self.a)

    @dataclass(frozen=True)
    class Ramp(Effect):
        """k x, plausible from 0.05 up (searched from 0)."""

        name = "test_ramp"
        parameters = (Parameter("k", 0.1, (0.0, 1.0), "1", "slope", physical_limits=(0.0,), plausible=(0.05, 1.0)),)
        k: float = 0.1

        def friction_term(self, state):
            return self.k * _x(state)

    @dataclass(frozen=True)
    class Lean(Effect):
        """m (0.3 + x): a look-alike of floor + ramp that fits better than either alone."""

        name = "test_lean"
        parameters = (Parameter("m", 0.1, (0.0, 1.0), "1", "slope", physical_limits=(0.0,)),)
        m: float = 0.1

        def friction_term(self, state):
            return self.m * (0.3 + _x(state))

    @dataclass(frozen=True)
    class Capped(Effect):
        """A rise h x^2 on any surface, searched only up to 0.05 (a third of the heat's in the deferral test)."""

        name = "test_capped"
        parameters = (Parameter("h", 0.02, (0.0, 0.05), "1", "rise over the speeds", physical_limits=(0.0,)),)
        h: float = 0.02

        def friction_term(self, state):
            return self.h * _x(state) ** 2

    @dataclass(frozen=True)
    class Ember(Effect):
        """-h x^2 where the texture exceeds 0.05, a fixed -0.01 x that h does not change where it is below 0.03
        (like a flash temperature beside a microtexture cut off too early to reach the scales it heats), linearly
        from one to the other in between."""

        name = "test_ember"
        parameters = (Parameter("h", 0.05, (0.0, 1.0), "1", "fall over the speeds", physical_limits=(0.0,)),)
        h: float = 0.05

        def friction_term(self, state):
            s = min(max((state.conditions.extra.get("texture", 0.0) - 0.03) / 0.02, 0.0), 1.0)
            return -s * self.h * _x(state) ** 2 - (1.0 - s) * 0.01 * _x(state)

    @dataclass(frozen=True)
    class Bump(Effect):
        """A narrow peak b exp(-(x - c)^2 / (2 0.05^2)) at c, plausible over the speeds measured (0 <= c <= 1) and
        searched far beyond: placed off the rows, it does nothing (an adhesion whose peak speed a fit has pushed
        past every measured speed)."""

        name = "test_bump"
        parameters = (Parameter("b", 0.05, (0.0, 0.3), "1", "height", physical_limits=(0.0,)),
                      Parameter("c", 0.5, (-10.0, 10.0), "1", "position", plausible=(0.0, 1.0)))
        b: float = 0.05
        c: float = 0.5

        def friction_term(self, state):
            return self.b * np.exp(-0.5 * ((_x(state) - self.c) / 0.05) ** 2)

    @dataclass(frozen=True)
    class Level(Effect):
        """A constant a, plausible from 0.03 to 0.06 (searched 0 - 0.3)."""

        name = "test_level"
        parameters = (Parameter("a", 0.04, (0.0, 0.3), "1", "constant", physical_limits=(0.0,),
                                plausible=(0.03, 0.06)),)
        a: float = 0.04

        def friction_term(self, state):
            return np.full_like(state.conditions.speed, self.a)

    @dataclass(frozen=True)
    class Tilt(Effect):
        """k x, plausible from 0.03 to 0.1 (searched 0 - 1)."""

        name = "test_tilt"
        parameters = (Parameter("k", 0.05, (0.0, 1.0), "1", "slope", physical_limits=(0.0,),
                                plausible=(0.03, 0.1)),)
        k: float = 0.05

        def friction_term(self, state):
            return self.k * _x(state)

    yield {"texture": Texture, "heat": Heat, "slope": Slope, "line": Line, "bend": Bend, "mimic": Mimic,
           "marker": Marker, "swing": Swing, "floor": Floor, "ramp": Ramp, "lean": Lean, "capped": Capped,
           "ember": Ember, "bump": Bump, "level": Level, "tilt": Tilt}
    base._REGISTRY = saved


def _data(truth, seed):
    v = np.geomspace(1e-3, 1.0, 10)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, 3),
                                               temperature=np.repeat([10.0, 25.0, 40.0], 10), pressure=3e5, mu=0.5,
                                               mu_std=SIGMA)
    mu = validation.predict(truth, rows).mu + np.random.default_rng(seed).normal(0, SIGMA, rows.n)
    return rows.with_mu(mu, mu_std=np.full(rows.n, SIGMA))


@pytest.fixture(scope="module")
def hidden_pair(effects):
    """Data with texture + heat; the improvement loop over the slope, the texture and the heat."""
    base = persson.Model(SURFACE, TREAD)
    truth = base.with_effect(effects["texture"](a=0.05)).with_effect(effects["heat"](h=0.15))
    m = _data(truth, 1)
    cands = [effects["slope"](), effects["texture"](), effects["heat"]()]
    imp = validation.improve(base, m, candidates=cands)
    return imp


def test_an_effect_invisible_until_another_is_added_is_found(hidden_pair):
    imp = hidden_pair
    dx0 = imp.steps[0].diagnosis
    # at first the heat has no signature at all (there is no texture), and the slope fits best
    assert dx0.candidate("test_heat").status == "no signature"
    assert dx0.verdict.verdict == "partly_explained" and dx0.verdict.effect == "test_slope", dx0.text()
    assert set(imp.added) == {"test_texture", "test_heat"}, imp.table_text()
    assert imp.verdict == "explained", imp.table_text()
    best = imp.selection.best
    assert set(best.effects) == {"test_texture", "test_heat"}
    est = {e.key: e for e in best.estimates}
    assert abs(est["test_texture.a"].value - 0.05) <= 3 * est["test_texture.a"].std
    assert abs(est["test_heat.h"].value - 0.15) <= 3 * est["test_heat.h"].std
    # a calibration error of the recorded conditions could take the place of either effect: it is fitted on the
    # baseline and on each fitted set one effect short of the answer
    on = {c.on for c in imp.selection.calibration.fits if c.kind == "speed"}
    short = {s.label for s in imp.selection.visited if len(s.effects) == 1 and set(s.effects) < set(best.effects)}
    assert short and on == {"(baseline)"} | short


def test_an_effect_made_redundant_by_a_later_one_is_removed(hidden_pair):
    imp = hidden_pair
    actions = [(s.action, s.added, s.removed) for s in imp.steps]
    # the path: slope, texture, heat added; then the slope removed (backward elimination)
    assert ("added", "test_slope", None) in actions and ("removed", None, "test_slope") in actions, actions
    removal = next(s for s in imp.steps if s.action == "removed")
    assert removal.delta_bic < validation.select.STAY           # dropping it cost less than 10 BIC units
    assert "test_slope" not in imp.model.effect_names
    # the rule holds for every effect of the final set, and the costs are the refits without each
    sel = imp.selection
    assert set(sel.drop_costs) == {"test_texture", "test_heat"}
    assert all(cost > validation.select.STAY for cost in sel.drop_costs.values())
    # every model of the search is a joint refit: the final set's BIC is its own chi2 + k ln n
    n = imp.measurements.n
    chi2 = float(np.sum(((imp.measurements.mu - best_prediction(imp)) / SIGMA) ** 2))
    assert sel.best.bic == pytest.approx(chi2 + sel.best.n_params * np.log(n), rel=1e-9)
    data = imp.as_dict()
    assert data["best_set"]["effects"] and set(data["best_set"]["effects"]) == {"test_texture", "test_heat"}
    actions = [s["action"] for s in data["steps"]]
    assert actions[0] == "baseline" and "removed" in actions


@pytest.fixture(scope="module")
def passed_over(effects):
    """Data with texture + heat; the loop over the mimic, the texture and the heat."""
    base = persson.Model(SURFACE, TREAD)
    truth = base.with_effect(effects["texture"](a=0.05)).with_effect(effects["heat"](h=0.15))
    m = _data(truth, 3)
    return validation.improve(base, m, candidates=[effects["mimic"](), effects["texture"](), effects["heat"]()])


def test_a_pair_the_stepwise_path_passed_over_is_found_by_exploring_pairs(passed_over):
    imp = passed_over
    dx0 = imp.steps[0].diagnosis
    assert dx0.candidate("test_heat").status == "no signature"
    assert dx0.verdict.effect == "test_mimic", dx0.text()
    # the stepwise path: the mimic, then nothing credible helps (texture redundant, heat still invisible) ...
    assert imp.steps[1].action == "added" and imp.steps[1].added == "test_mimic", imp.table_text()
    # ... so the pairs it did not reach are fitted, and texture + heat replaces the mimic
    explored = [s for s in imp.steps if s.action == "explored"]
    assert len(explored) == 1 and set(explored[0].effects) == {"test_texture", "test_heat"}, imp.table_text()
    assert explored[0].removed == "test_mimic" and explored[0].delta_bic < -10.0
    assert set(imp.added) == {"test_texture", "test_heat"} and imp.verdict == "explained", imp.table_text()
    sel = imp.selection
    assert set(sel.best.effects) == {"test_texture", "test_heat"} and sel.explored
    assert all(cost > validation.select.STAY for cost in sel.drop_costs.values())
    est = {e.key: e for e in sel.best.estimates}
    assert abs(est["test_heat.h"].value - 0.15) <= 3 * est["test_heat.h"].std
    data = imp.as_dict()
    assert data["explored"] and "explored" in [st["action"] for st in data["steps"]]
    assert "exploring pairs" in sel.text().lower()
    from validation.report import _selection_html

    assert "exploring pairs" in _selection_html(sel).lower()


def test_a_pair_whose_partner_acts_only_far_from_the_first_ones_single_fit_is_fitted_when_exploring(effects):
    """Texture (a = 0.055) + ember (h = 0.09): mu = baseline + 0.055 - 0.09 x^2. The texture alone fits the mean, a
    of about 0.025, below the 0.03 where the ember starts to act, so the ember's own fit changes the predictions by a
    fixed amount and identifies nothing. The mimic (a line) takes the path and leaves a curvature the noise cannot
    hide. The pair texture + ember is out of reach of the gain rule (the two single fits gain far less than half of
    what the mimic gained) and of the screen (linearized at the texture's single fit, where the ember does nothing):
    it is fitted jointly, from a global search, and replaces the mimic."""
    base = persson.Model(SURFACE, TREAD)
    truth = base.with_effect(effects["texture"](a=0.055)).with_effect(effects["ember"](h=0.09))
    m = _data(truth, 5)
    imp = validation.improve(base, m, candidates=[effects["mimic"](), effects["texture"](), effects["ember"]()])
    dx0 = imp.steps[0].diagnosis
    texture, ember, mimic = (dx0.candidate(n) for n in ("test_texture", "test_ember", "test_mimic"))
    assert texture.significant and texture.parameters["a"] < 0.03 and dx0.verdict.effect == "test_mimic"
    assert ember.status == "ok" and not ember.significant and not ember.identified
    gain = dx0.baseline.bic - texture.bic + max(dx0.baseline.bic - ember.bic, 0.0)
    assert gain < 0.5 * (dx0.baseline.bic - mimic.bic)          # out of reach of the gain rule
    explored = [s for s in imp.steps if s.action == "explored"]
    assert len(explored) == 1 and set(explored[0].effects) == {"test_texture", "test_ember"}, imp.table_text()
    assert set(imp.added) == {"test_texture", "test_ember"} and imp.verdict == "explained", imp.table_text()
    est = {e.key: e for e in imp.selection.best.estimates}
    for key, true in (("test_texture.a", 0.055), ("test_ember.h", 0.09)):
        assert abs(est[key].value - true) <= 3 * est[key].std, est[key]


def test_a_path_ending_at_the_noise_stays_when_no_pair_fits_better(hidden_pair, parallel):
    for imp in (hidden_pair, parallel):
        assert imp.selection.explored == () and "explored" not in [s.action for s in imp.steps]


def best_prediction(imp):
    return validation.predict(imp.model, imp.measurements).mu


@pytest.fixture(scope="module")
def parallel(effects):
    base = persson.Model(SURFACE, TREAD)
    m = _data(base.with_effect(effects["line"](k=0.1)), 2)
    return validation.improve(base, m, candidates=[effects["line"](), effects["bend"]()])


def test_two_parallel_candidates_are_both_named_with_the_measurement_that_separates_them(parallel):
    imp = parallel
    dx0 = imp.steps[0].diagnosis
    first, other = imp.added[0], ({"test_line", "test_bend"} - {imp.added[0]}).pop()
    # the step keeps the alternative its diagnosis named ("or as well by"), in the record and the JSON
    assert imp.steps[1].alternatives == (other,), imp.table_text()
    assert imp.as_dict()["steps"][1]["alternatives"] == [other]
    assert f"or as well by {other}" in imp.table_text()
    assert dx0.clusters and set(dx0.clusters[0].effects) == {"test_line", "test_bend"}
    # the result names both sets, each with parameters and intervals, and what would separate them
    sel = imp.selection
    assert [s.effects for s in sel.supported] == [(other,)]
    assert sel.supported[0].bic - sel.best.bic < validation.select.EQUAL
    for s in (sel.best,) + sel.supported:
        (e,) = s.estimates
        assert e.std > 0 and e.interval[0] < e.value < e.interval[1]
    (sep,) = sel.separations
    assert set(sep.effects) == {first, other} and sep.wet is False
    # half a decade beyond the fastest row: a scaled distance of 1 (to rounding), which is outside
    assert abs(sep.difference) > 0 and not sep.in_range and sep.distance >= validation.probe.INSIDE
    # the difference is the models' own predictions at that condition
    cond = validation.Measurements.from_arrays(slip=sep.slip, speed=sep.speed, temperature=sep.temperature,
                                               pressure=sep.pressure, mu=0.0)
    mu = [validation.predict(s.model, cond).mu[0] for s in (sel.best, sel.supported[0])]
    assert mu == pytest.approx(list(sep.mu), rel=1e-9)
    assert imp.final.alternatives == (other,) and "cannot tell them apart" in imp.final.headline
    assert "Equally supported" in sel.text() and "measure at" in sel.text()
    data = imp.as_dict()
    assert data["equally_supported"][0]["effects"] == [other] and data["set_separations"]


def test_a_set_that_fits_better_but_is_not_credible_is_reported_as_set_aside():
    """A set with a lower BIC than the best whose parameter ran to its search bound is not the answer, but the user
    reads that it fitted better and why it was set aside (the effect may act beyond the range searched)."""
    from validation.refit import Estimate
    from validation.select import EffectSet, Selection

    def effect_set(effects, bic, issue=""):
        est = tuple(Estimate(key=f"{e}.p", value=1.0, std=0.1, interval=(0.9, 1.1), method="quadratic",
                             issue=issue if e == effects[-1] else "") for e in effects)
        return EffectSet(effects=effects, model=None, contact=None, predicted=np.zeros(3), rss=1.0, bic=bic,
                         rmse=0.1, n_params=len(effects), estimates=est, lack=None, pattern=None)

    best = effect_set(("flash",), -100.0)
    aside = effect_set(("flash", "adhesion"), -106.7, issue="on the upper search bound 1e+06")
    worse_odd = effect_set(("adhesion",), -50.0, issue="outside the plausible range")
    sel = Selection(best=best, visited=(aside, best, worse_odd))
    assert sel.set_aside == (aside,)
    text = sel.text()
    assert "Set aside although they fit better (not credible): flash + adhesion (-6.7: adhesion.p = 1: on the upper " \
           "search bound 1e+06)" in text
    assert "Other sets fitted: adhesion (+50.0)." in text
    d = sel.as_dict()["set_aside"]
    assert d == [{"effects": ["flash", "adhesion"], "delta_bic": pytest.approx(-6.7), "issues":
                  ["adhesion.p = 1: on the upper search bound 1e+06"]}]
    assert Selection(best=best, visited=(best, worse_odd)).set_aside == ()


def test_a_candidate_not_credible_alone_is_tried_as_a_swap_once_a_partner_is_in():
    """Strain softening fitted better than microtexture at the first step, but its factors left their plausible
    range (the adhesion's part was missing): the path took microtexture, then adhesion. The swap microtexture ->
    strain softening is tried as well as the named alternatives, and made when the set is credible and better."""
    from validation.refit import Estimate
    from validation.select import EffectSet, SetSearch

    def effect_set(effects, bic, issue=""):
        est = tuple(Estimate(key=f"{e}.p", value=1.0, std=0.1, interval=(0.9, 1.1), method="quadratic",
                             issue=issue if e == "strain" else "") for e in effects)
        return EffectSet(effects=effects, model=None, contact=None, predicted=np.zeros(3), rss=1.0, bic=bic,
                         rmse=0.1, n_params=len(effects), estimates=est, lack=None, pattern=None)

    def search_with(pair_issue):
        search = SetSearch(None, (), None)
        for s in (effect_set(("micro",), -90.0), effect_set(("strain",), -95.0, "outside the plausible range"),
                  effect_set(("adhesion",), -60.0), effect_set(("micro", "adhesion"), -120.0),
                  effect_set(("strain", "adhesion"), -131.0, pair_issue)):
            search.sets[s.key] = s
        search.instances.update(micro=object(), strain=object(), adhesion=object())
        search.alternatives["micro"] = ()
        search.set_aside["micro"] = ("strain",)
        return search

    changes = search_with("").prune(("micro", "adhesion"))
    assert changes == [("swapped", "micro", "strain", pytest.approx(11.0), ("strain", "adhesion"))]
    # a swap to a set that is still not credible is not made
    assert search_with("outside the plausible range").prune(("micro", "adhesion")) == []


def test_a_pair_of_two_candidates_that_showed_nothing_alone_is_screened_and_found(effects):
    """The marker (m (T - 25)/15, m = 0.002) shows nothing alone, and the heat has no signature without it (a
    flash temperature on a PSD that stops short, beside a microtexture whose own change is within the noise). The
    slope k x takes the heat's rise and the path stops there; the pair of the two quiet candidates, which no step
    fits, is screened (a linearized joint fit from the marker's, exact for these linear effects) and fitted: it
    fits better than the slope by more than 10 BIC units (least squares) and replaces it."""
    base = persson.Model(SURFACE, TREAD)
    truth = base.with_effect(effects["marker"](m=0.002)).with_effect(effects["heat"](h=0.03))
    m = _data(truth, 5)
    imp = validation.improve(base, m, candidates=[effects["slope"](), effects["marker"](), effects["heat"]()])
    dx0 = imp.steps[0].diagnosis
    assert dx0.candidate("test_heat").status == "no signature"
    assert not dx0.candidate("test_marker").significant and dx0.verdict.effect == "test_slope", dx0.text()
    assert imp.steps[1].added == "test_slope", imp.table_text()
    explored = [s for s in imp.steps if s.action == "explored"]
    assert len(explored) == 1 and set(explored[0].effects) == {"test_marker", "test_heat"}, imp.table_text()
    assert set(imp.selection.best.effects) == {"test_marker", "test_heat"}, imp.selection.text()
    # the gain is the least-squares one: the slope k x against m t + h x^2 (one and two parameters)
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    t = (m.temperature - 25.0) / 15.0
    chi2_slope, _ = _linear_chi2(m, base, [x])
    chi2_pair, (mm, h) = _linear_chi2(m, base, [t, x * x])
    assert mm > 0 and h > 0
    gain = chi2_slope - chi2_pair - np.log(m.n)
    assert gain > validation.select.STAY
    assert explored[0].delta_bic == pytest.approx(-gain, abs=0.05)


def test_two_candidates_each_too_weak_alone_are_screened_together_when_nothing_was_significant(effects):
    """Nothing is significant alone: the marker (m = 0.002) is within the noise, and the swing, which lowers the
    friction as h x^2 / 2 on a plain surface, can only fit h = 0 to a rise. Together (the marker makes the surface
    textured and the swing then raises it as h x^2) they are the truth. With no significant candidate the path
    adds nothing; every pair of credible quiet candidates is screened, and this one is found."""
    base = persson.Model(SURFACE, TREAD)
    truth = base.with_effect(effects["marker"](m=0.002)).with_effect(effects["swing"](h=0.05))
    m = _data(truth, 6)
    imp = validation.improve(base, m, candidates=[effects["marker"](), effects["swing"]()])
    dx0 = imp.steps[0].diagnosis
    assert not any(c.significant for c in dx0.candidates) and dx0.verdict.verdict == "unexplained", dx0.text()
    assert all(c.status == "ok" for c in dx0.candidates)
    explored = [s for s in imp.steps if s.action == "explored"]
    assert len(explored) == 1 and set(explored[0].effects) == {"test_marker", "test_swing"}, imp.table_text()
    assert imp.verdict == "explained" and set(imp.added) == {"test_marker", "test_swing"}
    # the gain over the baseline is the non-negative least-squares one of m t + h x^2 (two parameters; m -> 0+
    # still marks the surface textured)
    from scipy.optimize import nnls

    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    t = (m.temperature - 25.0) / 15.0
    y = m.mu - validation.predict(base, m).mu
    (mm, h), norm = nnls(np.column_stack([t, x * x]) / SIGMA, y / SIGMA)
    assert h > 0
    chi2_base = float(np.sum((y / SIGMA) ** 2))
    assert explored[0].delta_bic == pytest.approx(norm ** 2 - chi2_base + 2 * np.log(m.n), abs=0.05)


def test_a_pair_of_two_significant_candidates_behind_a_look_alike_of_both_is_found(effects):
    """floor (a) + ramp (k x) is the truth; the lean m (0.3 + x) fits better than either alone and takes the path.
    On top of it neither partner is credible (the floor's a falls below its plausible 0.03, the ramp's k to 0), and
    swaps replace one effect at a time, so no step fits the pair. When the path ends short of the noise, the pairs
    of the significant candidates are fitted too: floor + ramp fits at the noise and replaces the lean."""
    base = persson.Model(SURFACE, TREAD)
    truth = base.with_effect(effects["floor"](a=0.05)).with_effect(effects["ramp"](k=0.1))
    m = _data(truth, 7)
    imp = validation.improve(base, m, candidates=[effects["lean"](), effects["floor"](), effects["ramp"]()])
    dx0 = imp.steps[0].diagnosis
    assert dx0.verdict.effect == "test_lean" and all(c.significant for c in dx0.candidates), dx0.text()
    assert imp.steps[1].added == "test_lean", imp.table_text()
    explored = [s for s in imp.steps if s.action == "explored"]
    assert len(explored) == 1 and set(explored[0].effects) == {"test_floor", "test_ramp"}, imp.table_text()
    assert imp.verdict == "explained" and set(imp.selection.best.effects) == {"test_floor", "test_ramp"}
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    chi2_pair, (a, k) = _linear_chi2(m, base, [np.ones_like(x), x])
    assert imp.selection.best.rss == pytest.approx(chi2_pair, rel=1e-3)


# ---------------------------------------------------------------------------------------------- pairs that tie
def _weak_heat(effects, h):
    """Data with texture + a weak heat ``h``; the loop over the mimic, the texture and the heat."""
    base = persson.Model(SURFACE, TREAD)
    truth = base.with_effect(effects["texture"](a=0.05)).with_effect(effects["heat"](h=h))
    m = _data(truth, 3)
    cands = [effects["mimic"](), effects["texture"](), effects["heat"]()]
    return base, m, cands, validation.improve(base, m, candidates=cands)


@pytest.fixture(scope="module")
def tie_at_noise(effects):
    """h = 0.008: the mimic b + k x fits the data at the noise (its misfit, the heat's curvature left after a line,
    is about 0.09 h rms against a noise of 0.005), and the heat is invisible without the texture."""
    return _weak_heat(effects, 0.008)


@pytest.fixture(scope="module")
def better_at_noise(effects):
    """h = 0.015: the mimic still passes the lack-of-fit test, but texture + heat fits better by more than 10."""
    return _weak_heat(effects, 0.015)


def _linear_chi2(m, base, columns):
    """chi2 of the best least-squares combination of ``columns`` added to the baseline (numpy, no engine fit)."""
    y = m.mu - validation.predict(base, m).mu
    A = np.column_stack(columns)
    coef = np.linalg.lstsq(A, y, rcond=None)[0]
    return float(np.sum(((y - A @ coef) / SIGMA) ** 2)), coef


def test_a_pair_that_ties_with_a_path_ending_at_the_noise_is_named_and_the_lower_bic_is_the_answer(tie_at_noise):
    """The path takes the mimic and ends at the noise; texture + heat, never on it, is screened and fitted. The two
    tie (within 10 BIC units), so both are named; the best set fitted -- the lower BIC, every effect earning its
    place -- is the answer, here the pair (a step "preferred"), with the mimic equally supported."""
    base, m, _, imp = tie_at_noise
    dx0 = imp.steps[0].diagnosis
    assert dx0.candidate("test_heat").status == "no signature"
    # the path: the mimic, at the noise; texture + heat was never on it
    assert imp.steps[1].action == "added" and imp.steps[1].added == "test_mimic", imp.table_text()
    # both are linear in their parameters: their chi2 are least-squares problems (two parameters each, so the BIC
    # difference is the chi2 difference)
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    chi2_mimic, _ = _linear_chi2(m, base, [np.ones(m.n), x])
    chi2_pair, (a, h) = _linear_chi2(m, base, [np.ones(m.n), x * x])
    chi2_texture, _ = _linear_chi2(m, base, [np.ones(m.n)])
    assert a > 0 and h > 0
    assert 0 < chi2_mimic - chi2_pair < validation.select.EQUAL     # a tie, the pair a little better
    assert chi2_texture - chi2_pair > validation.select.STAY + np.log(m.n)   # the heat earns its place
    sel = imp.selection
    assert set(imp.added) == {"test_texture", "test_heat"} and imp.verdict == "explained", imp.table_text()
    assert imp.steps[-1].action == "preferred" and imp.steps[-1].removed == "test_mimic"
    assert sel.preferred and "better than test_mimic, which the search reached" in sel.preferred[0]
    from validation.report import _selection_html

    assert "The best set fitted, in place of the answer the search reached: " in _selection_html(sel)
    assert imp.as_dict()["preferred"] == list(sel.preferred)
    assert imp.as_dict()["replaced"] == [] and not sel.replaced      # every parameter of the mimic is identified
    assert "test_mimic -> test_texture + test_heat (preferred)" in imp.steps[-1].describe().replace(
        "test_heat + test_texture", "test_texture + test_heat")
    mimic = {s.effects: s for s in sel.supported}.get(("test_mimic",))
    assert mimic is not None, sel.text()
    assert mimic.bic - sel.best.bic == pytest.approx(chi2_mimic - chi2_pair, abs=0.05)
    # the verdict names it: the data cannot tell the mimic from texture + heat
    assert "test_mimic" in imp.final.alternatives
    assert not sel.explored and "explored" not in [s.action for s in imp.steps]


def test_the_screen_of_a_pair_is_its_joint_least_squares_fit_when_the_model_is_linear(tie_at_noise):
    """One Gauss-Newton step from the texture's fit, with the heat's change at a few points of its range: exact for
    effects linear in their parameters, and so is the short fit that follows it below a limit."""
    from validation.diagnose import diagnose_single
    from validation.select import SetSearch

    base, m, cands, _ = tie_at_noise
    dx = diagnose_single(base, m, cands)
    search = SetSearch(base, (), dx.context)
    search.record(dx, (), 0)
    for c in dx.candidates:
        search.instances.setdefault(c.effect, c.instance)
        search.free.setdefault(c.effect, tuple(c.free))
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    chi2_pair, _ = _linear_chi2(m, base, [np.ones(m.n), x * x])
    n_before = search.n_evals
    bound, reached = search.screen_pair("test_texture", "test_heat")
    assert bound == pytest.approx(chi2_pair + 2 * np.log(m.n), abs=1e-3) and reached == np.inf   # no limit: no fit
    assert search.n_evals - n_before <= 2 * 1 + 2 * 1 + 3          # 2 k_a + 2 k_b + 3 model evaluations
    # below a limit, a short fit from the best point reaches the optimum (linear: one Gauss-Newton step)
    bound2, reached = search.screen_pair("test_texture", "test_heat", limit=bound + 1.0)
    assert bound2 == bound and reached == pytest.approx(bound, abs=1e-2)
    # the heat does nothing on top of the mimic (no texture): the bound is the mimic's own chi2, with the heat's
    # parameter counted
    mimic = search.sets[frozenset({"test_mimic"})]
    chi2_mimic, _ = _linear_chi2(m, base, [np.ones(m.n), x])
    assert mimic.rss == pytest.approx(chi2_mimic, rel=1e-4)
    assert search.screen_pair("test_mimic", "test_heat")[0] == pytest.approx(mimic.rss + 3 * np.log(m.n), rel=1e-9)


def test_a_pair_better_than_a_path_ending_at_the_noise_replaces_it(better_at_noise):
    base, m, _, imp = better_at_noise
    # the mimic passes the lack-of-fit test ...
    assert imp.steps[1].added == "test_mimic" and imp.steps[1].lack_of_fit_p > 0.01, imp.table_text()
    # ... but texture + heat, screened and fitted, is better by more than 10 BIC units (least squares: both linear)
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    gain = _linear_chi2(m, base, [np.ones(m.n), x])[0] - _linear_chi2(m, base, [np.ones(m.n), x * x])[0]
    assert gain > validation.select.STAY
    explored = [s for s in imp.steps if s.action == "explored"]
    assert len(explored) == 1 and explored[0].removed == "test_mimic", imp.table_text()
    assert explored[0].delta_bic == pytest.approx(-gain, abs=0.05)
    assert set(imp.selection.best.effects) == {"test_texture", "test_heat"} and imp.verdict == "explained"
    assert imp.selection.explored and "found by exploring pairs" in imp.stopped


# ---------------------------------------------------------------------------------------------- fits stopped early
def _recorded_search(effects):
    """A set search on texture + heat data (a = 0.05, h = 0.15) holding the baseline's diagnosis over the texture,
    the heat and the mimic: (baseline, measurements, search)."""
    from validation.diagnose import diagnose_single
    from validation.select import SetSearch

    base = persson.Model(SURFACE, TREAD)
    m = _data(base.with_effect(effects["texture"](a=0.05)).with_effect(effects["heat"](h=0.15)), 1)
    dx = diagnose_single(base, m, [effects["texture"](), effects["heat"](), effects["mimic"]()])
    search = SetSearch(base, (), dx.context)
    search.record(dx, (), 0)
    for c in dx.candidates:
        search.instances.setdefault(c.effect, c.instance)
        search.free.setdefault(c.effect, tuple(c.free))
    return base, m, search


def test_a_fit_stopped_at_its_budget_within_reach_is_continued_and_can_change_the_answer(effects):
    """A fit that runs out of model evaluations reports the best point it reached: an upper bound on its BIC. Such a
    set within 10 BIC units of the answer is fitted again from that point with a budget of its own, and replaces
    the answer when it then fits better by more than 10 BIC units; one further away is left alone. Texture + heat,
    recorded as stopped at its starting values 5 BIC units behind the texture alone, is continued to its
    least-squares optimum (both effects are linear); the mimic, recorded as stopped 15 units behind, is not."""
    from dataclasses import replace

    from validation.refit import BUDGET_NOTE
    from validation.report import _selection_html

    base, m, search = _recorded_search(effects)
    texture, heat, mimic = effects["texture"](), effects["heat"](), effects["mimic"]()
    alone = search.sets[frozenset({"test_texture"})]
    assert not alone.budget_stopped

    def stopped(effects_, model, delta):
        fit = replace(alone, effects=effects_, model=model, bic=alone.bic + delta, notes=(BUDGET_NOTE,),
                      source="a fit stopped at its budget")
        search.sets[fit.key] = fit
        return fit

    pair = stopped(("test_texture", "test_heat"), base.with_effect(texture).with_effect(heat), 5.0)
    far = stopped(("test_mimic",), base.with_effect(mimic), 15.0)
    assert pair.budget_stopped and far.budget_stopped
    n0 = search.n_evals
    better = search.resume(("test_texture",))
    assert search.n_evals > n0
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    chi2_pair, (a, h) = _linear_chi2(m, base, [np.ones(m.n), x * x])
    continued = search.sets[frozenset({"test_texture", "test_heat"})]
    assert continued.rss == pytest.approx(chi2_pair, rel=1e-4) and not continued.budget_stopped
    assert continued.bic == pytest.approx(chi2_pair + 2 * np.log(m.n), rel=1e-6)
    est = {e.key: e.value for e in continued.estimates}
    assert est["test_texture.a"] == pytest.approx(a, rel=1e-3) and est["test_heat.h"] == pytest.approx(h, rel=1e-3)
    assert better == ("test_texture", "test_heat") and continued.bic < alone.bic - validation.select.STAY
    assert search.sets[frozenset({"test_mimic"})] is far                   # 15 units behind: out of reach
    assert len(search.resumed) == 1 and search.resumed[0].startswith("test_texture + test_heat (BIC")
    sel = search.finish(better)
    assert sel.best is continued and sel.resumed == tuple(search.resumed)
    assert "continued past their budget" in sel.text() and "continued past their budget" in _selection_html(sel)
    assert sel.as_dict()["resumed"] == list(search.resumed)
    # nothing is continued twice beyond its rounds, and a search without stopped fits in reach does nothing
    assert search.resume(better) is None and len(search.resumed) == 1


def test_a_step_that_continues_a_stopped_fit_says_so():
    from validation.improve import Step

    common = dict(index=3, effects=("a", "b"), parameters={}, fitted=(), rmse=0.1, bic=1.0, delta_bic=-20.0,
                  model=None, diagnosis=None)
    assert Step(added="b", removed="c", action="resumed", **common).describe() == "c -> b (resumed)"
    assert Step(added="b", removed=None, action="resumed", **common).describe() == "+ b (resumed)"
    assert Step(added=None, removed="c", action="resumed", **common).describe() == "- c (resumed)"


def test_a_credible_fit_is_not_traded_for_a_continuation_outside_the_plausible_ranges(monkeypatch):
    """A set named at credible values stays named: when its continued fit is better but leaves a plausible range,
    the credible fit is kept; a credible continuation that fits better by more than 10 BIC units wins."""
    from validation.refit import BUDGET_NOTE, Estimate
    from validation.select import EffectSet, SetSearch

    def effect_set(effects, bic, issue="", notes=()):
        est = tuple(Estimate(key=f"{e}.p", value=1.0, std=0.1, interval=(0.9, 1.1), method="quadratic", issue=issue)
                    for e in effects)
        return EffectSet(effects=effects, model=None, contact=None, predicted=np.zeros(3), rss=1.0, bic=bic,
                         rmse=0.1, n_params=len(effects), estimates=est, lack=None, pattern=None, notes=notes)

    search = SetSearch(None, (), None)
    answer, stopped = effect_set(("a",), -100.0), effect_set(("b",), -95.0, notes=(BUDGET_NOTE,))
    for s in (answer, stopped):
        search.sets[s.key] = s
    monkeypatch.setattr(search, "_continue", lambda s: effect_set(("b",), -120.0, "outside the plausible range"))
    assert search.resume(("a",)) is None
    assert search.sets[frozenset({"b"})] is stopped and search.resumed == []
    search._continued.clear()
    monkeypatch.setattr(search, "_continue", lambda s: effect_set(("b",), -120.0))
    assert search.resume(("a",)) == ("b",) and search.sets[frozenset({"b"})].bic == -120.0
    assert search.resumed == ["b (BIC -95.0 where its fit stopped, -120.0 continued)"]


def test_a_better_subset_of_a_larger_set_within_reach_replaces_an_answer_that_misses_the_noise(effects):
    """Backward elimination acts on the path's own set; a larger set fitted on the way may contain a better one that
    no step fitted. With texture + heat data and the mimic as the answer (it misses the noise: no curvature), the set
    mimic + texture + heat lies within reach; its subsets are refitted, and texture + heat -- the truth, never fitted
    before -- fits at the noise (its chi2 that of numpy's least squares) and replaces the mimic. An answer at the
    noise is left alone."""
    from validation.improve import Step
    from validation.report import _selection_html
    from validation.select import STAY

    base, m, search = _recorded_search(effects)
    truth = frozenset({"test_texture", "test_heat"})
    answer = search.get(("test_mimic",))
    larger = search.get(("test_mimic", "test_texture", "test_heat"), warm=(answer,))
    assert truth not in search.sets and larger.bic < answer.bic + validation.select.EQUAL
    n0 = search.n_evals
    better = search.reduce(("test_mimic",))
    assert search.n_evals > n0 and set(better) == set(truth)
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    chi2_pair, _ = _linear_chi2(m, base, [np.ones(m.n), x * x])
    found = search.sets[truth]
    assert found.rss == pytest.approx(chi2_pair, rel=1e-4) and found.bic < answer.bic - STAY
    assert len(search.reduced) == 1 and search.reduced[0].startswith("test_texture + test_heat (")
    sel = search.finish(better)
    assert set(sel.best.effects) == set(truth) and sel.reduced == tuple(search.reduced)
    said = "Subsets of the sets within reach"
    assert said in sel.text() and said in _selection_html(sel)
    assert sel.as_dict()["reduced"] == list(search.reduced)
    # at the noise: nothing to do
    assert search.reduce(better) is None and len(search.reduced) == 1
    common = dict(index=3, effects=("a", "b"), parameters={}, fitted=(), rmse=0.1, bic=1.0, delta_bic=-20.0,
                  model=None, diagnosis=None)
    assert Step(added="b", removed="c", action="reduced", **common).describe() == "c -> b (reduced)"


def _stand_in_set(effects, bic, at_noise=False, issue="", notes=()):
    """A fitted set with one parameter per effect, ``issue`` on each (not credible when given), at the noise or not."""
    from types import SimpleNamespace

    from validation.refit import Estimate
    from validation.select import EffectSet

    est = tuple(Estimate(key=f"{e}.p", value=1.0, std=0.1, interval=(0.9, 1.1), method="quadratic", issue=issue)
                for e in effects)
    return EffectSet(effects=tuple(effects), model=None, contact=None, predicted=np.zeros(3), rss=1.0, bic=bic,
                     rmse=0.1, n_params=len(effects), estimates=est, lack=SimpleNamespace(consistent=at_noise),
                     pattern=None, notes=notes)


def test_an_answer_at_the_noise_that_is_not_credible_has_the_fits_stopped_within_reach_continued(monkeypatch):
    """An answer at the noise is left to the pair screen -- unless it is not credible, which explains nothing
    (blind case 21-13: an adhesion whose peak speed ran to the search bound stood in for the hidden flash
    temperature + microtexture at the noise, while adhesion + flash temperature + microtexture had stopped at its
    budget 7.6 BIC units better; continued, it fell 20 units below the answer, and the backward elimination left
    the hidden pair). The credible answer at the noise: nothing continued."""
    from validation.refit import BUDGET_NOTE
    from validation.select import SetSearch

    def search_with(answer):
        search = SetSearch(None, (), None)
        for s in (answer, _stand_in_set(("a", "b", "c"), -7.6, notes=(BUDGET_NOTE,))):
            search.sets[s.key] = s
        monkeypatch.setattr(search, "_continue", lambda s: _stand_in_set(s.effects, -20.0, at_noise=True))
        return search

    credible = search_with(_stand_in_set(("a", "b"), 0.0, at_noise=True))
    assert credible.resume(("a", "b")) is None and credible.resumed == []
    assert credible.sets[frozenset("abc")].bic == -7.6
    aside = search_with(_stand_in_set(("a", "b"), 0.0, at_noise=True, issue="on the upper search bound"))
    assert aside.resume(("a", "b")) == ("a", "b", "c") and aside.sets[frozenset("abc")].bic == -20.0
    assert aside.resumed == ["a + b + c (BIC -7.6 where its fit stopped, -20.0 continued)"]


def test_an_answer_at_the_noise_that_is_not_credible_has_the_subsets_of_the_sets_within_reach_fitted(monkeypatch):
    """The same for the subsets of the sets within reach: an answer at the noise that is not credible does not
    stop the look, and the credible subset b + c of a + b + c, never fitted and 20 units better, replaces it."""
    from validation.select import SetSearch

    def search_with(answer):
        search = SetSearch(None, (), None)
        for s in (answer, _stand_in_set(("a", "b", "c"), -5.0, at_noise=True)):
            search.sets[s.key] = s
        fitted = []

        def fit(effects, warm):
            fitted.append(frozenset(effects))
            return _stand_in_set(effects, -20.0 if set(effects) == {"b", "c"} else 3.0, at_noise=True)

        monkeypatch.setattr(search, "_fit", fit)
        return search, fitted

    search, fitted = search_with(_stand_in_set(("a", "b"), 0.0, at_noise=True))
    assert search.reduce(("a", "b")) is None and fitted == []
    search, fitted = search_with(_stand_in_set(("a", "b"), 0.0, at_noise=True, issue="outside the plausible range"))
    assert search.reduce(("a", "b")) == ("b", "c")
    assert set(fitted) == {frozenset("bc"), frozenset("ac")}     # a + b, the answer, is fitted already
    assert search.reduced == ["b + c (20.0 BIC units better than a + b; a subset of a set within reach of it)"]


def test_a_subset_whose_fit_stopped_at_its_budget_far_behind_is_refitted_from_the_set_within_reach(monkeypatch):
    """A subset fitted on the way but stopped at its budget reports only an upper bound on its BIC (blind case
    26-93: adhesion fitted on top of the flash temperature stopped 600 units behind, while flash temperature +
    strain softening + adhesion tied with the answer; refitted from that set's values, flash temperature + adhesion,
    the hidden pair, came out best). It is refitted once, from the values of the set within reach, and the better
    of its two fits is kept; a subset that reached its optimum is not fitted again, and a refit that does worse
    leaves the first fit in place."""
    from validation.refit import BUDGET_NOTE
    from validation.select import SetSearch

    search = SetSearch(None, (), None)
    answer = _stand_in_set(("a", "b"), 0.0, at_noise=True, issue="on the upper search bound")
    stopped = _stand_in_set(("a", "c"), 600.0, notes=(BUDGET_NOTE,))
    finished = _stand_in_set(("b", "c"), 50.0)
    for s in (answer, _stand_in_set(("a", "b", "c"), 0.0, at_noise=True), stopped, finished):
        search.sets[s.key] = s
    warm_from = []

    def fit(effects, warm):
        warm_from.append((frozenset(effects), tuple(w.key for w in warm)))
        return _stand_in_set(effects, -8.0 if set(effects) == {"a", "c"} else 900.0, at_noise=True)

    monkeypatch.setattr(search, "_fit", fit)
    assert search.reduce(("a", "b")) is None           # 8 units better: not the 10 an effect needs to stay
    assert warm_from == [(frozenset("ac"), (frozenset("abc"),))]
    assert search.sets[frozenset("ac")].bic == -8.0 and search.sets[frozenset("bc")] is finished
    # once only (a second look fits the subsets of a + c, now within reach itself); a refit that does worse keeps
    # the first fit
    search.reduce(("a", "b"))
    assert [k for k, _ in warm_from].count(frozenset("ac")) == 1
    search2 = SetSearch(None, (), None)
    for s in (answer, _stand_in_set(("a", "b", "c"), 0.0, at_noise=True), stopped):
        search2.sets[s.key] = s
    monkeypatch.setattr(search2, "_fit", lambda effects, warm: _stand_in_set(effects, 700.0, at_noise=True))
    assert search2.reduce(("a", "b")) is None and search2.sets[frozenset("ac")] is stopped


def test_a_step_diagnosis_computes_its_baseline_intervals_and_explanation_when_read(effects):
    """The diagnoses of a search's later steps refit the set the search fitted already (their baseline): its
    intervals, and the explanation that shows them, are computed when first read, with the model evaluations they
    spend reported then, and equal those of the same diagnosis computed at once."""
    from validation.deferred import is_ready
    from validation.diagnose import diagnose_single

    base = persson.Model(SURFACE, TREAD).with_effect(effects["texture"](a=0.04))
    truth = persson.Model(SURFACE, TREAD).with_effect(effects["texture"](a=0.05)).with_effect(effects["heat"](h=0.15))
    m = _data(truth, 3)

    def run(defer):
        told = []
        dx = diagnose_single(base, m, [effects["heat"]()], fit=["test_texture.a"], refit_baseline=False,
                             defer95=defer, defer_baseline=defer, on_evals=told.append)
        return dx, told

    now, told_now = run(False)
    later, told = run(True)
    assert told_now == [] and told == []
    assert not is_ready(later, "explanation") and not is_ready(later.baseline, "estimates")
    assert later.verdict.verdict == now.verdict.verdict and later.baseline.bic == now.baseline.bic
    assert later.explanation == now.explanation
    assert later.baseline.estimates == now.baseline.estimates and later.baseline.notes == now.baseline.notes
    assert told and all(n >= 0 for n in told)
    (a,) = later.baseline.estimates
    assert a.key == "test_texture.a" and math.isfinite(a.std) and a.std > 0
    assert [e.interval95 for c in later.candidates for e in c.estimates] == \
        [e.interval95 for c in now.candidates for e in c.estimates]


def test_a_step_diagnosis_computes_a_candidates_intervals_when_read(effects):
    """In a step's diagnosis a candidate's intervals are computed when first read: those of the candidate the
    verdict names at once (its identification decides the verdict), those of a plausible contender only when read,
    those of a candidate with a parameter out of its plausible range at once (they judge its plausibility); every
    judgement, and every interval once read, is that of the same diagnosis computed at once, and the set search
    records the contender as a set whose intervals are still deferred."""
    from validation.deferred import is_ready
    from validation.diagnose import diagnose_single
    from validation.select import SetSearch

    base = persson.Model(SURFACE, TREAD).with_effect(effects["texture"](a=0.04))
    truth = persson.Model(SURFACE, TREAD).with_effect(effects["texture"](a=0.05)).with_effect(effects["heat"](h=0.15))
    m = _data(truth, 3)

    def run(defer):
        told = []
        dx = diagnose_single(base, m, [effects["heat"](), effects["slope"](), effects["capped"]()],
                             fit=["test_texture.a"], refit_baseline=False, defer95=True, defer_baseline=True,
                             defer_candidates=defer, on_evals=told.append)
        return dx, told

    now, _ = run(False)
    later, told = run(True)
    by = {c.effect: c for c in later.candidates}
    heat, slope, capped = by["test_heat"], by["test_slope"], by["test_capped"]
    assert later.verdict.effect == "test_heat" and slope.significant and slope.plausible and slope.fit is not None
    assert is_ready(heat, "estimates") and not is_ready(slope, "estimates") and not slope.fit.pending.ready
    # pushed against its search bound: judged on its intervals, computed at once
    assert any(e.issue for e in capped.fit.estimates) and capped.fit.pending.ready and not capped.plausible
    spent = sum(told)
    search = SetSearch(base, ["test_texture.a"], later.context)
    search.record(later, (), 1)
    recorded = search.sets[frozenset(["test_slope"])]
    assert recorded.clean and recorded.plausible and not is_ready(recorded, "estimates")
    assert not slope.fit.pending.ready and sum(told) == spent
    assert later.n_evaluations <= now.n_evaluations
    for a, b in zip(later.candidates, now.candidates):
        assert (a.effect, a.plausible, a.issues, a.bic, a.significant) == (b.effect, b.plausible, b.issues, b.bic,
                                                                          b.significant)
        assert a.estimates == b.estimates and a.baseline_estimates == b.baseline_estimates and a.notes == b.notes
        assert [e.interval95 for e in a.estimates] == [e.interval95 for e in b.estimates]
    assert slope.fit.pending.ready and sum(told) >= spent
    assert recorded.estimates == slope.baseline_estimates + slope.estimates
    assert later.verdict == now.verdict and later.explanation == now.explanation


def _joint_refit_of_texture_and_bump(effects, b: float, c: float) -> None:
    """Data with texture (a = 0.05) + bump (b = 0.08 at c = 0.5); the texture diagnosed, the bump's own fit left
    at ``b``, ``c``: the joint refit of the pair must reach its least-squares optimum (closed form at the fitted peak
    position: both effects are then linear in their heights), credible and at the noise."""
    from validation.diagnose import diagnose_single
    from validation.select import SetSearch

    base = persson.Model(SURFACE, TREAD)
    texture, bump = effects["texture"], effects["bump"]
    m = _data(base.with_effect(texture(a=0.05)).with_effect(bump(b=0.08, c=0.5)), 1)
    dx = diagnose_single(base, m, [texture()])
    search = SetSearch(base, (), dx.context)
    search.record(dx, (), 0)
    search.instances["test_bump"] = bump(b=b, c=c)
    search.free["test_bump"] = ("b", "c")
    pair = search.get(("test_texture", "test_bump"))
    est = {e.key: e.value for e in pair.estimates}
    assert est["test_bump.c"] == pytest.approx(0.5, abs=0.01)
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    chi2, (a, h) = _linear_chi2(m, base, [np.ones(m.n), np.exp(-0.5 * ((x - est["test_bump.c"]) / 0.05) ** 2)])
    assert pair.rss == pytest.approx(chi2, rel=1e-3)
    assert est["test_texture.a"] == pytest.approx(a, rel=1e-2) and est["test_bump.b"] == pytest.approx(h, rel=1e-2)
    assert pair.plausible and validation.select.fits_at_noise(pair)


def test_a_joint_refit_leaves_the_basin_where_a_members_own_fit_pushed_it_out_of_its_plausible_range(effects):
    """Texture (a = 0.05) + bump (b = 0.08 at c = 0.5). The bump's own fit, made without the texture, left its
    peak at c = 8, far past the speeds measured, where it does nothing: a local fit of the pair from the members'
    values cannot move it (no gradient), and a design over the box of the three parameters rarely lands within a
    peak's width of the truth. The joint refit also starts with every parameter a member pushed onto a search bound
    or out of its plausible range at the middle of that range (c = 0.5), and reaches the least-squares optimum of
    the pair (closed form at the true peak position: both effects are then linear in their heights)."""
    _joint_refit_of_texture_and_bump(effects, b=0.2, c=8.0)


def test_a_joint_refit_starts_a_member_its_own_fit_switched_off_from_its_declared_defaults(effects):
    """Texture (a = 0.05) + bump (b = 0.08 at c = 0.5). The bump's own fit ended at zero height (its physical limit,
    a legitimate optimum: the bump alone did nothing useful) with its peak at c = 0.9, inside its plausible range:
    nothing there is on a search bound or implausible, so no parameter is moved to the middle of its range, and at
    zero height the peak's position has no gradient. The joint refit also starts the bump at its declared defaults
    (b = 0.05, c = 0.5, where a candidate's diagnosis starts) and reaches the least-squares optimum of the pair."""
    _joint_refit_of_texture_and_bump(effects, b=0.0, c=0.9)


def test_the_default_start_moves_only_the_members_own_parameters_and_keeps_placeholders():
    """The members' parameters go to their declared defaults (flash temperature: macro_scale_ratio = 2; microtexture:
    q1 = 1e7 rad/m); a baseline's parameter stays, and so does a parameter whose default is a placeholder computed
    from the model (the microtexture's Hurst exponent 0: fitted on the PSD's last decade). Nothing to move: None."""
    from persson import effects as fx
    from validation.fitting import FreeParameter, ParameterSpace
    from validation.select import _default_start

    flash, micro = fx.get("flash_temperature", macro_scale_ratio=125.0), fx.get("microtexture", q1=1.3e5, hurst=0.8)

    class _Model:
        def effect(self, name):
            return {"flash_temperature": flash, "microtexture": micro}[name]

    space = ParameterSpace([FreeParameter("adhesion", "tau_f0", 0.0, 5e7, log=False),
                            FreeParameter("microtexture", "q1", 1e2, 1e10, log=True),
                            FreeParameter("microtexture", "hurst", 0.0, 1.0, log=False),
                            FreeParameter("flash_temperature", "macro_scale_ratio", 1.0, 1e3, log=True)])
    u = np.array([space.params[0].to_u(2e6), space.params[1].to_u(1.3e5), 0.8, space.params[3].to_u(125.0)])
    out = _default_start(space, _Model(), u, ("microtexture", "flash_temperature"))
    vals = space.values_from_u(out)
    assert vals["flash_temperature.macro_scale_ratio"] == pytest.approx(2.0)
    assert vals["microtexture.q1"] == pytest.approx(1e7)
    assert out[0] == u[0] and out[2] == u[2]
    only = _default_start(space, _Model(), u, ("flash_temperature",))
    assert np.array_equal(only[:3], u[:3])
    assert _default_start(space, _Model(), out, ("microtexture", "flash_temperature")) is None


def test_two_candidates_each_implausible_alone_are_fitted_together(effects):
    """Level (a = 0.045, plausible 0.03 - 0.06) + tilt (k = 0.06, plausible 0.03 - 0.1). Alone, each takes the
    other's part and leaves its plausible range (the level fits the mean, about 0.075; the tilt, forced through the
    origin, about 0.13): both are significant, neither is credible, and the stepwise path adds nothing. The pair of
    the significant candidates that are implausible alone is fitted jointly; it is credible, fits at the noise, and
    its parameters are numpy's least squares."""
    base = persson.Model(SURFACE, TREAD)
    level, tilt = effects["level"], effects["tilt"]
    m = _data(base.with_effect(level(a=0.045)).with_effect(tilt(k=0.06)), 1)
    imp = validation.improve(base, m, candidates=[level(), tilt()])
    dx0 = imp.steps[0].diagnosis
    for name in ("test_level", "test_tilt"):
        c = dx0.candidate(name)
        assert c.significant and not c.plausible, imp.table_text()
    assert dx0.verdict.verdict == "unexplained"
    assert set(imp.added) == {"test_level", "test_tilt"} and imp.verdict == "explained", imp.table_text()
    assert imp.steps[1].action == "explored"
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    chi2, (a, k) = _linear_chi2(m, base, [np.ones(m.n), x])
    best = imp.selection.best
    assert best.rss == pytest.approx(chi2, rel=1e-4)
    est = {e.key: e.value for e in best.estimates}
    assert est["test_level.a"] == pytest.approx(a, rel=1e-3) and est["test_tilt.k"] == pytest.approx(k, rel=1e-3)


def _mimic_not_credible(monkeypatch):
    """Make the set {mimic} report a parameter on a search bound, as a set does whose own profiles, computed when
    read, put a parameter out of the range searched where its step's quicker intervals had not (on a blind case an
    adhesion whose peak speed ran off to 1e6 m/s while it stood in for a flash temperature + microtexture pair)."""
    from validation.select import EffectSet

    issues = EffectSet.issues.fget
    monkeypatch.setattr(EffectSet, "issues", property(
        lambda s: ("test_mimic.k = 1: on the upper search bound 1: the data push it out of the range searched",)
        if s.effects == ("test_mimic",) else issues(s)))


def test_a_path_whose_set_is_not_credible_explores_the_pairs_it_did_not_reach(effects, monkeypatch):
    """Texture + heat (h = 0.015) fits better than the mimic the path took by more than 10 BIC units. With the
    mimic's set not credible, the pairs are explored as for a path that ends short of the noise, the pair replaces
    it, and the text says why."""
    _mimic_not_credible(monkeypatch)
    base, m, cands, imp = _weak_heat(effects, 0.015)
    assert set(imp.added) == {"test_texture", "test_heat"} and imp.verdict == "explained", imp.table_text()
    assert any(s.action == "explored" for s in imp.steps)
    assert "test_mimic is not credible" in imp.stopped


def test_a_credible_set_that_ties_with_a_best_set_that_is_not_credible_takes_its_place(effects, monkeypatch):
    """h = 0.008: texture + heat only ties with the mimic (the closed-form least squares of both: within 10 BIC
    units). The mimic, not credible, explains nothing; the credible pair the data support as well takes its place (a
    step "preferred"), and the verdict is on the pair (blind case 17-13: an adhesion with its peak speed at 1e4 m/s
    fitting 2.5 BIC units better than the flash temperature + microtexture pair it stood in for)."""
    _mimic_not_credible(monkeypatch)
    base, m, cands, imp = _weak_heat(effects, 0.008)
    x = np.log10(m.sliding_speed / 1e-3) / 3.0
    chi2_mimic, _ = _linear_chi2(m, base, [np.ones(m.n), x])
    chi2_pair, _ = _linear_chi2(m, base, [np.ones(m.n), x * x])
    assert abs(chi2_mimic - chi2_pair) < validation.select.EQUAL      # two parameters each: a tie in BIC too
    assert set(imp.added) == {"test_texture", "test_heat"} and imp.verdict == "explained", imp.table_text()
    step = imp.steps[-1]
    assert step.action == "preferred" and step.removed == "test_mimic", imp.table_text()
    assert set(step.added.split(" + ")) == {"test_texture", "test_heat"}
    sel = imp.selection
    assert sel.preferred and "test_mimic, which is not credible: test_mimic.k = 1" in sel.preferred[0]
    assert "credible and within 10 BIC units of test_mimic, which is not credible" in imp.stopped
    assert "The best set fitted, in place of the answer the search reached: " in sel.text()
    assert imp.as_dict()["preferred"] == list(sel.preferred)
    # the mimic is no longer an answer, nor equally supported: where it fits better it is set aside, with its reason
    assert all(s.effects != ("test_mimic",) for s in sel.supported)
    if chi2_mimic < chi2_pair:
        assert [s.effects for s in sel.set_aside] == [("test_mimic",)]


def test_a_best_set_that_is_not_credible_is_not_called_explained(effects, monkeypatch):
    """With the mimic the only candidate, nothing credible comes within 10 BIC units of it: it stays the best set;
    not credible, it explains nothing, and the verdict says so."""
    _mimic_not_credible(monkeypatch)
    base = persson.Model(SURFACE, TREAD)
    m = _data(base.with_effect(effects["texture"](a=0.05)).with_effect(effects["heat"](h=0.008)), 3)
    imp = validation.improve(base, m, candidates=[effects["mimic"]()])
    assert imp.added == ("test_mimic",), imp.table_text()
    assert imp.verdict == "unexplained" and imp.final.effect is None
    assert "test_mimic is the best set the search found, but it is not credible" in imp.final.reason
    assert not imp.selection.preferred and "preferred" not in [s.action for s in imp.steps]
    # the loop stopped at the noise with the mimic; its stop text names the verdict that overrides that
    assert imp.stopped.startswith("explained: with test_mimic"), imp.stopped
    assert "the final verdict is unexplained: test_mimic is the best set the search found" in imp.stopped


def test_a_step_candidate_fit_also_starts_with_the_sets_parameters_moved_off_their_limits(effects, monkeypatch):
    """In a step of the improvement loop the baseline is a set fitted without the candidate, and the candidate's
    screen varies the candidate's parameters only. A member on a physical limit may be standing in for the
    candidate (case 9-19 of the blind study: a flash temperature held at q_m = q0 while it did an adhesion's work,
    30 BIC units behind the basin of the truth): the candidate's fit gets one more start with that parameter in the
    middle of its range (the texture's a: 0.15, the middle of 0 - 0.3) and the candidate's own values as given. A
    baseline searched globally in the same diagnosis (the first step) gets no such start."""
    from validation import candidates as C
    from validation.diagnose import _baseline_params
    from validation.fitting import ParameterSpace
    from validation.predict import Predictor

    plain = persson.Model(SURFACE, TREAD)
    rows = _data(plain, 5)
    rows = rows.with_mu(0.9 * rows.mu, mu_std=rows.mu_std)    # below the plain model: the texture's a goes to 0
    settings = C.FitSettings(predictor=Predictor(rows, None), y=rows.mu, w=1.0 / rows.mu_std, sigma_known=True)
    model = plain.with_effect(effects["texture"](a=0.0))
    space = ParameterSpace(_baseline_params(model, ["test_texture.a"], None))
    seen = []
    real = C.global_fit

    def spy(fitter, u_given, **kw):
        seen.append((np.array(u_given), [np.array(s) for s in kw.get("extra_starts", ())]))
        return real(fitter, u_given, **kw)

    monkeypatch.setattr(C, "global_fit", spy)
    for searched in (False, True):
        base = C.fit_baseline(model, space, settings, global_search=searched)
        assert base.u[0] == 0.0 and base.searched is searched
        seen.clear()
        trial = C.fit_candidate(effects["slope"](), base, settings)
        assert trial.fit is not None
        (u_given, extra), = seen
        if searched:
            assert extra == []
        else:
            (start,) = extra
            values = trial.fitter.space.values_from_u(start)
            assert values["test_texture.a"] == pytest.approx(0.15)
            assert start[1] == u_given[1]


class _Fitted:
    """A stand-in for a fitted set: what :meth:`SetSearch.prefer` reads of one."""

    def __init__(self, effects, bic, plausible=True, not_identified=()):
        self.effects, self.bic, self.plausible = tuple(effects), float(bic), plausible
        self.not_identified = tuple(not_identified)
        self.key = frozenset(self.effects)
        self.label = " + ".join(self.effects) or "(baseline)"
        self.issues = () if plausible else (f"{self.label}: a parameter on its search bound",)


def _search_of(*sets):
    from validation.select import SetSearch

    search = SetSearch(None, (), None)       # no context: a set not given here would have to be fitted, and fails
    search.sets = {s.key: s for s in sets}
    return search


def test_the_best_set_fitted_is_the_lowest_bic_credible_set_whose_every_effect_earns_its_place():
    """In order of BIC below the answer A: E is not credible; A + B is a superset of A whose B earns 3 units only
    (the subset A, fitted already, shows it: the subset B is never fitted); C + D is credible and dropping C or D
    costs 17 and 22 units: it is the best set fitted."""
    from validation.select import STAY

    sets = [_Fitted(("A",), 0.0), _Fitted(("E",), -5.0, plausible=False), _Fitted(("A", "B"), -3.0),
            _Fitted(("C", "D"), -2.0), _Fitted(("C",), 20.0), _Fitted(("D",), 15.0), _Fitted((), 40.0)]
    search = _search_of(*sets)
    assert search.prefer(("A",)) == ("C", "D")
    assert "C + D (2.0 BIC units better than A, which the search reached" in search.preferred[0]
    assert len(search.sets) == len(sets)             # no subset was fitted
    # C + D with an effect that does not earn its place (dropping D costs 9 units): nothing better to take
    sets[5] = _Fitted(("D",), -2.0 + STAY - 1.0)
    assert _search_of(*sets).prefer(("A",)) is None
    # nothing below a credible answer, nothing above it counts; an empty answer is left alone
    assert _search_of(_Fitted(("A",), 0.0), _Fitted(("C",), 1.0), _Fitted((), 30.0)).prefer(("A",)) is None
    assert _search_of(_Fitted((), 0.0), _Fitted(("C",), -1.0)).prefer(()) is None


def test_an_answer_that_is_not_credible_gives_way_to_a_credible_set_within_ten_bic_units():
    """A is not credible: the credible C, 6 units behind, takes its place (the data support both, only C
    physically); one 12 units behind does not (more than EQUAL = 10)."""
    from validation.select import EQUAL

    base = _Fitted((), 60.0)
    search = _search_of(_Fitted(("A",), 0.0, plausible=False), _Fitted(("C",), 6.0), base)
    assert search.prefer(("A",)) == ("C",)
    assert "C (+6.0 BIC units from A, which is not credible: A: a parameter on its search bound)" in search.preferred[0]
    assert _search_of(_Fitted(("A",), 0.0, plausible=False), _Fitted(("C",), EQUAL + 2.0), base).prefer(("A",)) is None


def test_a_set_with_a_parameter_the_data_do_not_identify_does_not_replace_an_identified_answer():
    """C + D fits 3 units better than the answer A, but its D.q is not identified (its 68 % interval spans the range
    searched: a flash temperature whose q_m runs to where it acts fully, not charged in the BIC; blind case 14-32):
    it does not replace A, whose parameters are all identified, and the next set below A, the identified E, does.
    An answer with a parameter not identified itself, or one that is not credible, is replaced by C + D."""
    sets = [_Fitted(("A",), 0.0), _Fitted(("C", "D"), -3.0, not_identified=("D.q",)), _Fitted(("E",), -1.0),
            _Fitted(("C",), 20.0), _Fitted(("D",), 15.0), _Fitted((), 40.0)]
    assert _search_of(*sets).prefer(("A",)) == ("E",)
    sets[2] = _Fitted(("E",), 1.0)
    assert _search_of(*sets).prefer(("A",)) is None
    sets[0] = _Fitted(("A",), 0.0, not_identified=("A.k",))
    assert _search_of(*sets).prefer(("A",)) == ("C", "D")
    sets[0] = _Fitted(("A",), 0.0, plausible=False)
    assert _search_of(*sets).prefer(("A",)) == ("C", "D")


class _Candidate:
    """A stand-in for a candidate of the baseline's diagnosis: what :meth:`SetSearch.replace_unidentified` reads."""

    def __init__(self, effect, bic, significant=True, status="ok"):
        self.effect, self.bic, self.significant, self.status = effect, float(bic), significant, status
        self.instance, self.free = f"{effect} as fitted", ("k",)


def _replacing(sets, fits, candidates, n_evals=10):
    """A search over the stand-in ``sets`` whose joint refits return the stand-ins ``fits`` (by effects), each
    counting ``n_evals`` model evaluations; the refits asked for are listed in ``search.asked``."""
    search = _search_of(*sets)
    search.asked = []

    def fit(effects, warm):
        search.asked.append((tuple(effects), tuple(w.label for w in warm)))
        search.n_evals += n_evals
        return fits[frozenset(effects)]

    search._fit = fit
    first = type("Diagnosis", (), {"candidates": tuple(candidates)})()
    return search, first


def test_an_effect_the_data_do_not_identify_is_replaced_in_turn_by_each_credible_candidate():
    """The answer A + B ends at the noise with A.k not identified (a strain softening whose loss factor runs onto
    its bound beside a microtexture, standing in for a flash temperature: blind case 19-13). Each credible candidate
    fitted alone on the baseline is fitted in A's place, from the answer's values and its own single fit: the
    significant ones first, the better single fit first (D, then C), then the one that showed nothing alone (E: a
    flash temperature invisible until the microtexture is in, blind case 19-89), then the one with no signature at
    all (G, from the answer's values alone); not F (not credible alone), nor B (in the answer already). Then A is
    kept and the same candidates take the identified B's place, in the same order. The best set fitted then
    answers (:meth:`prefer`): C + B, 12 BIC units better, with both effects earning their place."""
    sets = [_Fitted(("A", "B"), 0.0, not_identified=("A.k",)), _Fitted(("A",), 30.0), _Fitted(("B",), 25.0),
            _Fitted(("C",), 40.0), _Fitted(("D",), 35.0), _Fitted(("E",), 60.0), _Fitted(("F",), 20.0, plausible=False),
            _Fitted((), 80.0)]
    fits = {frozenset("CB"): _Fitted(("C", "B"), -12.0), frozenset("DB"): _Fitted(("D", "B"), 4.0),
            frozenset("EB"): _Fitted(("E", "B"), 9.0), frozenset("GB"): _Fitted(("G", "B"), 7.0)}
    fits.update({frozenset("A" + e): _Fitted(("A", e), 3.0) for e in "DCEG"})
    candidates = [_Candidate("A", 30.0), _Candidate("B", 25.0), _Candidate("C", 40.0), _Candidate("D", 35.0),
                  _Candidate("E", 60.0, significant=False), _Candidate("F", 20.0),
                  _Candidate("G", math.nan, significant=False, status="no signature")]
    search, first = _replacing(sets, fits, candidates)
    assert search.replace_unidentified(("A", "B"), first) is None
    assert search.asked == [(("D", "B"), ("A + B", "D")), (("C", "B"), ("A + B", "C")), (("E", "B"), ("A + B", "E")),
                            (("G", "B"), ("A + B",)), (("A", "D"), ("A + B", "D")), (("A", "C"), ("A + B", "C")),
                            (("A", "E"), ("A + B", "E")), (("A", "G"), ("A + B",))]
    assert search.instances["G"] == "G as fitted" and search.free["G"] == ("k",)
    assert search.replaced[0] == ("D + B (D in place of A, whose A.k the data do not identify): +4.0 BIC units from "
                                  "A + B")
    assert "-12.0 BIC units from A + B" in search.replaced[1]
    assert search.prefer(("A", "B")) == ("C", "B")
    assert search.replaced[4] == ("A + D (D in place of B, beside A.k, which the data do not identify): +3.0 BIC "
                                  "units from A + B")
    # asked twice, nothing is fitted again
    search.replace_unidentified(("A", "B"), first)
    assert len(search.asked) == 8


def test_an_effect_the_data_do_not_identify_is_kept_while_its_partner_takes_another_effects_place():
    """Blind case 23-89 (flash temperature + microtexture, 64 rows): the answer B + A is an adhesion B beside a
    flash temperature A whose q_m runs to where it does nothing (A.k not identified); the microtexture C and the
    flash temperature each fitted worse than the baseline alone (+3.1 and +12.3 BIC units), so no step paired
    them, and C in A's place fits 4.5 units worse than the answer. Kept, A acts once C is in B's place: A + C fits
    4.2 units better, with both parameters identified, and answers."""
    sets = [_Fitted(("B", "A"), 0.0, not_identified=("A.k",)), _Fitted(("B",), 63.0), _Fitted(("A",), 154.0),
            _Fitted(("C",), 145.0), _Fitted((), 142.0)]
    fits = {frozenset("BC"): _Fitted(("B", "C"), 4.5), frozenset("CA"): _Fitted(("C", "A"), -4.2)}
    candidates = [_Candidate("B", 63.0), _Candidate("A", 154.0, significant=False),
                  _Candidate("C", 145.0, significant=False)]
    search, first = _replacing(sets, fits, candidates)
    search.replace_unidentified(("B", "A"), first)
    assert [a for a, _ in search.asked] == [("B", "C"), ("C", "A")]
    assert search.prefer(("B", "A")) == ("C", "A")


def test_replacing_an_unidentified_effect_stops_at_its_budget_and_leaves_an_identified_answer_alone():
    """With a budget of 10 model evaluations the first refit spends it, and the second is not made (said so);
    an answer whose parameters are all identified has nothing replaced."""
    sets = [_Fitted(("A", "B"), 0.0, not_identified=("A.k",)), _Fitted(("C",), 40.0), _Fitted(("D",), 35.0)]
    fits = {frozenset("CB"): _Fitted(("C", "B"), -12.0), frozenset("DB"): _Fitted(("D", "B"), 4.0)}
    candidates = [_Candidate("C", 40.0), _Candidate("D", 35.0)]
    search, first = _replacing(sets, fits, candidates)
    search.replace_unidentified(("A", "B"), first, budget=10)
    assert search.asked == [(("D", "B"), ("A + B", "D"))]
    assert search.replaced[-1] == ("the replacements stopped at their budget of 10 model evaluations (1 of 4 sets "
                                   "fitted)")
    sets[0] = _Fitted(("A", "B"), 0.0)
    search, first = _replacing(sets, fits, candidates)
    search.replace_unidentified(("A", "B"), first)
    assert search.asked == [] and search.replaced == []


def test_a_candidate_not_credible_alone_is_explored_with_each_credible_significant_one():
    """The path took L, a look-alike of the pair A + M, and nothing credible came on top of it (blind case 27-29:
    strain softening took the place of a microtexture + adhesion whose peak lies at the slowest speeds). A was
    significant alone but not credible (the adhesion's peak speed ran to its bound), M credible but behind L, so A
    was never M's alternative and the pair was never fitted. Exploring pairs fits A with each credible significant
    candidate (the gain rule applies: together they gain at least half of what the path gained); A + M, 40 units
    better than L, is the answer. The set of two candidates not credible alone is not fitted where a credible one
    exists."""
    sets = [_Fitted(("L",), -100.0), _Fitted(("M",), -98.0), _Fitted(("A",), -60.0, plausible=False),
            _Fitted(("W",), -55.0, plausible=False), _Fitted((), 0.0)]
    fits = {frozenset("AM"): _Fitted(("A", "M"), -140.0), frozenset("AL"): _Fitted(("A", "L"), -101.0),
            frozenset("LM"): _Fitted(("L", "M"), -102.0), frozenset("WM"): _Fitted(("W", "M"), -99.0),
            frozenset("WL"): _Fitted(("W", "L"), -99.0)}
    search, _ = _replacing(sets, fits, ())
    first = type("Diagnosis", (), {"candidates": tuple(_Candidate(e, b) for e, b in
                                                       (("L", -100.0), ("M", -98.0), ("A", -60.0), ("W", -55.0))),
                                   "baseline": _Fitted((), 0.0)})()
    assert set(search.explore(("L",), first)) == {"A", "M"}
    asked = {frozenset(e) for e, _ in search.asked}
    assert frozenset("AM") in asked and frozenset("AW") not in asked
    assert "A + M (40.0 BIC units better than L" in search.explored[0]


def test_the_search_budgets_count_its_fits_not_what_a_diagnosis_reports_besides(effects, monkeypatch):
    """The looks of the search (exploring pairs, continuing stopped fits, subsets) are given as many model
    evaluations as the fits before them took. What a diagnosis reports besides its fits (the separating
    measurements, the localization's and the contact's refits) is counted in ``n_evaluations`` but not in those
    budgets: with 500 such evaluations added to every diagnosis, the budgets, the path and the answer are those of
    the search without them, and the total grows by exactly 500 a diagnosis."""
    import importlib

    diagnose_module = importlib.import_module("validation.diagnose")
    select_module = importlib.import_module("validation.select")
    base = persson.Model(SURFACE, TREAD)
    truth = base.with_effect(effects["texture"](a=0.05)).with_effect(effects["heat"](h=0.15))
    m = _data(truth, 3)

    def run(extra):
        budgets, diagnoses = [], []
        explore = select_module.SetSearch.explore
        localized = diagnose_module._localized

        def recording_explore(self, *args, budget=None, **kwargs):
            budgets.append(budget)
            return explore(self, *args, budget=budget, **kwargs)

        def costly_localized(*args, on_evals=None, **kwargs):
            diagnoses.append(1)
            if on_evals is not None:
                on_evals(extra)
            return localized(*args, on_evals=on_evals, **kwargs)

        with monkeypatch.context() as mp:
            mp.setattr(select_module.SetSearch, "explore", recording_explore)
            mp.setattr(diagnose_module, "_localized", costly_localized)
            imp = validation.improve(base, m, candidates=[effects["mimic"](), effects["texture"](),
                                                          effects["heat"]()])
        return imp, budgets, len(diagnoses)

    plain, budgets, n_dx = run(0)
    costly, costly_budgets, n_dx2 = run(500)
    assert budgets and costly_budgets == budgets and n_dx2 == n_dx >= 2
    assert [(s.action, s.effects) for s in costly.steps] == [(s.action, s.effects) for s in plain.steps]
    assert set(costly.selection.best.effects) == set(plain.selection.best.effects) == {"test_texture", "test_heat"}
    assert costly.n_evaluations == plain.n_evaluations + 500 * n_dx
    dx0 = costly.steps[0].diagnosis
    assert dx0.n_diagnostic_evaluations >= 500 and dx0.as_dict()["baseline"]["n_diagnostic_evaluations"] >= 500


def test_without_a_known_noise_the_answer_is_judged_against_the_noise_of_its_own_residual(effects):
    """The pair texture + heat found by the loop fits the data better than every single fit of the first
    diagnosis (the heat shows nothing alone): the local-difference noise is estimated again on the data less the
    pair's prediction, and the final verdict, the loop's stop reason and the reported noise use it
    (:func:`validation.improve._judged_against_answer`, tested on its own in ``test_validation_answer_noise``)."""
    base = persson.Model(SURFACE, TREAD)
    truth = base.with_effect(effects["texture"](a=0.05)).with_effect(effects["heat"](h=0.15))
    m = _data(truth, 1)
    m = validation.Measurements.from_arrays(slip=m.slip, speed=m.speed, temperature=m.temperature,
                                            pressure=m.pressure, mu=m.mu)           # no mu_std: local differences
    imp = validation.improve(base, m, candidates=[effects["slope"](), effects["texture"](), effects["heat"]()])
    assert set(imp.added) == {"test_texture", "test_heat"}, imp.table_text()
    first = imp.steps[0].diagnosis.noise_estimate
    assert first.source == "local differences"
    again = validation.noise.estimate_noise(m, reference=imp.selection.best.predicted)
    assert imp.noise == again.sigma != first.sigma and imp.noise_source == "local differences"
    assert f"{again.sigma:.3g} (the steps against {first.sigma:.3g})" in imp.stopped
    assert imp.verdict == "explained" and "on the data less this set's prediction" in imp.final.reason
    lack = validation.noise.lack_of_fit(m.mu - imp.selection.best.predicted, imp.selection.best.n_params, again)
    assert imp.selection.best.lack.p_value == lack.p_value
    # a noise given by the caller is the noise of every judgement
    given = imp.steps[0].diagnosis.noise_estimate
    imp2 = validation.improve(base, m, candidates=[effects["slope"](), effects["texture"](), effects["heat"]()],
                              noise=given)
    assert imp2.noise == given.sigma and "the steps against" not in imp2.stopped


def test_the_cost_of_an_effect_is_read_from_the_sets_own_values_when_the_subset_kept_sits_in_a_worse_optimum(
        monkeypatch):
    """Blind draw 41, case 4: a patch heating's own fit stopped in a worse optimum (chi^2 539 on 36 rows), the
    pair with a strain softening found the right one with the softening's factors at 1.00 and 1.02 (doing
    nothing), and the softening seemed to earn 494 BIC units against the subset kept. The set's own values less
    the softening bound the subset's chi^2 from above: read there, the subset is fitted again from them and the
    softening costs nothing (:meth:`validation.select.SetSearch.dropped`)."""
    from types import SimpleNamespace

    from validation.select import EffectSet, SetSearch

    n = 36
    y = np.zeros(n)

    def effect_set(effects, bic, model=None):
        return EffectSet(effects=effects, model=model, contact=None, predicted=np.zeros(n), rss=1.0, bic=bic,
                         rmse=0.1, n_params=2 + 2 * ("strain" in effects), estimates=(), lack=None, pattern=None)

    def search_with(chi2_without):
        mu = np.full(n, math.sqrt(chi2_without / n))          # a prediction whose chi2 against y = 0 is chi2_without
        predictor = SimpleNamespace(predict=lambda model, contact=None: SimpleNamespace(mu=mu))
        ctx = SimpleNamespace(settings=SimpleNamespace(predictor=predictor, y=y, w=np.ones(n), n=n, sigma_known=True,
                                                       contact=None))
        search = SetSearch(None, (), ctx)
        pair_model = SimpleNamespace(effect_names=("patch", "strain"), without=lambda name: "the pair less it")
        pair = effect_set(("patch", "strain"), 51.2, pair_model)
        search.sets[pair.key] = pair
        search.sets[frozenset({"patch"})] = effect_set(("patch",), 545.7)    # the worse optimum, kept
        search.free["strain"] = ("storage_factor", "loss_factor")
        fits = []

        def refit(effects, warm):
            fits.append((effects, warm))
            return effect_set(effects, 44.3)
        monkeypatch.setattr(search, "_fit", refit)
        return search, pair, fits

    search, pair, fits = search_with(37.7)            # at the pair's values less the softening: BIC 37.7 + 2 ln 36
    sub = search.dropped(pair, "strain")
    assert fits == [(("patch",), (pair,))]              # fitted again, from the pair's values
    assert sub.bic == 44.3 and search.sets[frozenset({"patch"})] is sub
    assert sub.bic - pair.bic < validation.select.STAY  # the softening does not earn its place
    assert search.n_evals == 1                          # one prediction to read the bound
    # where the pair's values less the effect read far worse, the effect does something there: the fit kept stands
    search, pair, fits = search_with(400.0)
    assert search.dropped(pair, "strain").bic == 545.7 and fits == []
