"""validation.improve: the answer of a set search is judged against the noise left by its own prediction.

Without ``mu_std`` or replicates the noise comes from differences of neighbouring rows along each series, on the
data less the best-fitting prediction at hand: what that prediction leaves of the data's curvature enters the
differences as if it were noise (the pseudo-residuals of Gasser, Sroka & Jennen-Steinmetz remove a straight line
through three rows, not a curve). The first diagnosis has only its single candidates; a set found later that fits
better is judged against the noise its own residual gives, so that a set which only bends a curve into the data's
shape is not called explained against a noise its predecessors inflated.

Rows: 3 series x 10 speeds, x = log10(v / 1 mm/s) / 3 from 0 to 1, true noise 0.003 in mu. Data: 0.5 + x^2 +
0.03 (x - 0.5) + noise. The first diagnosis's best fit is a line in x (its residual keeps the curvature, and the
local estimate triples); the answer is 0.5 + x^2, whose residual is the straight 0.03 (x - 0.5), three times the
noise in rms and invisible to the local differences.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

import validation
from validation.improve import _judged_against_answer
from validation.noise import estimate_noise, lack_of_fit
from validation.refit import Estimate
from validation.select import EffectSet, Selection

SIGMA = 0.003


@pytest.fixture(scope="module")
def rows():
    v = np.geomspace(1e-3, 1.0, 10)
    m = validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, 3),
                                            temperature=np.repeat([10.0, 25.0, 40.0], 10), pressure=3e5, mu=0.5)
    x = np.log10(m.speed / 1e-3) / 3.0
    mu = 0.5 + x**2 + 0.03 * (x - 0.5) + np.random.default_rng(7).normal(0.0, SIGMA, m.n)
    return m.with_mu(mu), x


def _answer(m, predicted, n_params=2):
    r = m.mu - predicted
    est = (Estimate(key="a.p", value=1.0, std=0.1, interval=(0.9, 1.1), method="quadratic"),
           Estimate(key="b.p", value=1.0, std=0.1, interval=(0.9, 1.1), method="quadratic"))
    return EffectSet(effects=("a", "b"), model=None, contact=None, predicted=predicted, rss=float(r @ r), bic=0.0,
                     rmse=float(np.sqrt(np.mean(r * r))), n_params=n_params, estimates=est, lack=None, pattern=None)


def _first_diagnosis(baseline, *candidates):
    return SimpleNamespace(baseline=SimpleNamespace(predicted=baseline),
                           candidates=[SimpleNamespace(predicted=c) for c in candidates])


def test_a_set_that_bends_the_curve_into_the_data_misses_the_noise_its_own_residual_gives(rows):
    m, x = rows
    line = np.polyval(np.polyfit(x, m.mu, 1), x)        # the least-squares line through the data
    first = estimate_noise(m, reference=line)
    # the premise: the line's residual keeps the curvature, and the local differences take it for noise
    assert first.source == "local differences" and first.sigma > 2.5 * SIGMA
    answer = _answer(m, 0.5 + x**2)
    assert lack_of_fit(m.mu - answer.predicted, 2, first).consistent     # "at the noise" against that noise
    sel = Selection(best=answer, visited=(answer,))
    noise, judged = _judged_against_answer(first, sel, _first_diagnosis(np.full(m.n, 0.5), line), m)
    # the noise on the data less the answer: the differences of the noise alone (its straight residual drops out)
    assert noise.source == "local differences"
    assert 0.6 * SIGMA < noise.sigma < 1.5 * SIGMA, noise.sigma
    assert "less the answer's prediction" in noise.description
    # the answer's residual, 0.03 (x - 0.5), is three times that noise: it misses it
    assert not judged.best.lack.consistent and judged.best.lack.p_value < 1e-3
    assert judged.best.pattern is not None and judged.best.pattern.found
    # the set keeps its fit; only how it is judged changes, in the sets listed as well
    assert judged.best.rss == answer.rss and judged.best.effects == answer.effects
    assert judged.visited == (judged.best,)


def test_an_answer_at_the_noise_stays_at_the_noise(rows):
    m, x = rows
    truth = 0.5 + x**2 + 0.03 * (x - 0.5)
    line = np.polyval(np.polyfit(x, m.mu, 1), x)
    first = estimate_noise(m, reference=line)
    answer = _answer(m, truth)
    noise, judged = _judged_against_answer(first, Selection(best=answer, visited=(answer,)),
                                           _first_diagnosis(np.full(m.n, 0.5), line), m)
    assert 0.6 * SIGMA < noise.sigma < 1.5 * SIGMA
    assert judged.best.lack.consistent and not judged.best.pattern.found


def test_the_noise_stays_when_a_fit_of_the_first_diagnosis_fits_as_well_or_the_noise_is_given(rows):
    m, x = rows
    answer = _answer(m, 0.5 + x**2)
    sel = Selection(best=answer, visited=(answer,))
    # a candidate of the first diagnosis already fitted better: its residual gave the noise
    first = estimate_noise(m, reference=0.5 + x**2 + 0.03 * (x - 0.5))
    noise, judged = _judged_against_answer(first, sel, _first_diagnosis(np.full(m.n, 0.5),
                                                                       0.5 + x**2 + 0.03 * (x - 0.5)), m)
    assert noise is first and judged is sel
    # mu_std is the noise, whatever the fits
    given = estimate_noise(m.with_mu(m.mu, mu_std=np.full(m.n, SIGMA)))
    noise, judged = _judged_against_answer(given, sel, _first_diagnosis(np.full(m.n, 0.5)), m)
    assert noise is given and judged is sel
    # nothing added: the baseline's verdict is the first diagnosis's
    none = EffectSet(effects=(), model=None, contact=None, predicted=np.full(m.n, 0.5), rss=1.0, bic=0.0, rmse=0.1,
                     n_params=0, estimates=(), lack=None, pattern=None)
    line = np.polyval(np.polyfit(x, m.mu, 1), x)
    first = estimate_noise(m, reference=line)
    noise, judged = _judged_against_answer(first, Selection(best=none, visited=(none,)),
                                           _first_diagnosis(np.full(m.n, 0.5), line), m)
    assert noise is first
