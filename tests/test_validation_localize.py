"""validation: where a model's misfit sits -- the family of rows (sliding, with slip, wet) it misses while it fits
the others -- is named in the verdict, with what rests on those rows; nothing is said on pure noise beyond the
test's level, nor when the misfit is everywhere.

The tests' p-values are checked against scipy.stats (chi^2 with the noise known, F with an estimated one, the
fitted parameters shared out over the families in proportion to their rows), the false-alarm rate by simulation.
"""

import dataclasses
import math

import numpy as np
import pytest
from scipy import stats

import validation
from validation.localize import ALPHA, localize_misfit
from validation.report import render_report
from validation.noise import NoiseEstimate
from validation.verdict import Verdict, with_localized

SIGMA = 0.01
SLIPS = np.array([0.005, 0.01, 0.02, 0.04, 0.07, 0.1, 0.2, 0.35, 0.6, 0.85])


def _rows(n_sliding=40, n_slip=10, n_wet=6):
    """Sliding rows over four decades of speed, one slip sweep, wet sliding rows."""
    v = np.geomspace(1e-3, 3.0, n_sliding)
    slip = np.r_[np.ones(n_sliding), SLIPS[:n_slip], np.ones(n_wet)]
    speed = np.r_[v, np.ones(n_slip), np.geomspace(1e-2, 1.0, n_wet)]
    wet = np.r_[np.zeros(n_sliding + n_slip, dtype=bool), np.ones(n_wet, dtype=bool)]
    return validation.Measurements.from_arrays(slip=slip, speed=speed, temperature=20.0, pressure=3e5, mu=0.5,
                                               wet=wet)


def _known(n, sigma=SIGMA):
    return NoiseEstimate(source="mu_std", sigma=sigma, dof=math.inf, row_sigma=np.full(n, sigma), description="")


def _estimated(n, dof=20.0, sigma=SIGMA):
    return NoiseEstimate(source="local differences", sigma=sigma, dof=dof, row_sigma=np.full(n, sigma),
                         description="")


def _bump(m, height=8 * SIGMA):
    """A peak the brush model does not give: a hump in log slip on the rows with slip."""
    r = np.zeros(m.n)
    s = m.slip < 1
    r[s] = height * np.exp(-0.5 * (np.log10(m.slip[s] / 0.05) / 0.3) ** 2)
    return r


def test_a_misfit_on_the_slip_rows_alone_is_placed_there_with_the_closed_form_tests():
    m = _rows()
    rng = np.random.default_rng(1)
    r = _bump(m) + rng.normal(0.0, SIGMA, m.n)
    k = 2
    loc = localize_misfit(r, _known(m.n), m, "the baseline", n_params=k)
    assert loc is not None and loc.family == "slip" and loc.n_rows == 10 and loc.rest_rows == 46
    z2 = (r / SIGMA) ** 2
    s = m.slip < 1
    d_slip, d_rest = 10 * (m.n - k) / m.n, 46 * (m.n - k) / m.n
    assert loc.p_value == pytest.approx(stats.chi2.sf(z2[s].sum(), d_slip), rel=1e-9)
    assert loc.rest_p == pytest.approx(stats.chi2.sf(z2[~s].sum(), d_rest), rel=1e-9)
    assert loc.ratio == pytest.approx(math.sqrt(z2[s].sum() / d_slip), rel=1e-12)
    assert loc.share == pytest.approx(z2[s].sum() / z2.sum(), rel=1e-12)
    text = loc.text()
    assert "10 rows with slip" in text and "slip model" in text and "contact.stiffness" in text
    assert loc.as_dict()["family"] == "slip" and loc.as_dict()["text"] == text


def test_with_the_contact_refitted_the_slip_rows_point_at_the_shape_of_the_slip_curve():
    m = _rows()
    r = _bump(m) + np.random.default_rng(1).normal(0.0, SIGMA, m.n)
    loc = localize_misfit(r, _known(m.n), m, "the baseline", refitted=("contact.stiffness", "contact.length"))
    assert "were refitted with the rest" in loc.text() and "refit the contact" not in loc.text()
    # one of the two is not enough to rule the contact out
    loc = localize_misfit(r, _known(m.n), m, "the baseline", refitted=("contact.stiffness",))
    assert "refit the contact" in loc.text()


def test_with_an_estimated_noise_the_tests_are_f_tests():
    m = _rows()
    r = _bump(m) + np.random.default_rng(2).normal(0.0, SIGMA, m.n)
    loc = localize_misfit(r, _estimated(m.n, dof=17.0), m, "m")
    z2 = (r / SIGMA) ** 2
    s = m.slip < 1
    assert loc.family == "slip"
    assert loc.p_value == pytest.approx(stats.f.sf(z2[s].sum() / 10, 10, 17.0), rel=1e-9)
    assert loc.rest_p == pytest.approx(stats.f.sf(z2[~s].sum() / 46, 46, 17.0), rel=1e-9)
    assert loc.rest_low_p == pytest.approx(stats.f.cdf(z2[~s].sum() / 46, 46, 17.0), rel=1e-9)


def test_wet_rows_missed_alone_point_at_the_wet_model():
    m = _rows()
    r = np.random.default_rng(3).normal(0.0, SIGMA, m.n)
    r[m.wet] -= 6 * SIGMA
    loc = localize_misfit(r, _known(m.n), m, "m")
    assert loc.family == "wet" and "wet model" in loc.text()


@pytest.mark.parametrize("noise", ["known", "estimated"])
def test_on_pure_noise_a_family_is_named_in_at_most_alpha_of_the_data_sets(noise):
    m = _rows()
    est = _known(m.n) if noise == "known" else _estimated(m.n, dof=30.0)
    rng = np.random.default_rng(11)
    n_sim = 3000
    named = 0
    for _ in range(n_sim):
        if noise == "estimated":
            # the estimate scatters as a chi^2 with its degrees of freedom, independent of the rows tested
            est = dataclasses.replace(est, sigma=SIGMA * math.sqrt(rng.chisquare(30.0) / 30.0))
            est = dataclasses.replace(est, row_sigma=np.full(m.n, est.sigma))
        named += localize_misfit(rng.normal(0.0, SIGMA, m.n), est, m, "m") is not None
    # at most ALPHA (Bonferroni over three families): binomial(3000, 0.01) has mean 30, sd 5.4
    assert named <= n_sim * ALPHA + 3 * math.sqrt(n_sim * ALPHA)


def test_nothing_is_said_when_every_family_or_none_is_missed_or_only_one_family_is_measured():
    m = _rows()
    rng = np.random.default_rng(4)
    everywhere = rng.normal(0.0, 3 * SIGMA, m.n)
    assert localize_misfit(everywhere, _known(m.n), m, "m") is None
    # the slip rows missed, the sliding rows too (less): no single family
    r = _bump(m) + rng.normal(0.0, SIGMA, m.n)
    r[(m.slip >= 1) & ~m.wet] += 2 * SIGMA
    assert localize_misfit(r, _known(m.n), m, "m") is None
    only_sliding = _rows(n_slip=0, n_wet=0)
    r = rng.normal(0.0, SIGMA, only_sliding.n)
    r[:5] += 20 * SIGMA
    assert localize_misfit(r, _known(only_sliding.n), only_sliding, "m") is None
    none = NoiseEstimate(source="none", sigma=math.nan, dof=0.0, row_sigma=np.full(m.n, math.nan), description="")
    assert localize_misfit(_bump(m), none, m, "m") is None


def test_rows_scattering_less_than_a_local_difference_estimate_flag_it_as_inflated():
    m = _rows()
    rng = np.random.default_rng(5)
    r = _bump(m, 30 * SIGMA) + rng.normal(0.0, SIGMA, m.n)
    # an estimate twice the true noise, as the curvature of a misfit makes it
    loc = localize_misfit(r, _estimated(m.n, sigma=2 * SIGMA), m, "m")
    assert loc.family == "slip" and loc.noise_inflated and loc.rest_low_p < ALPHA
    assert "likely inflated" in loc.text()
    loc = localize_misfit(r, _estimated(m.n, sigma=SIGMA), m, "m")
    assert loc.family == "slip" and not loc.noise_inflated and "inflated" not in loc.text()
    # with the noise given per row, no estimate can be inflated by the data
    assert not localize_misfit(r, _known(m.n, 2 * SIGMA), m, "m").noise_inflated


def test_a_residual_that_does_not_match_the_rows_is_refused_naming_the_argument():
    m = _rows()
    with pytest.raises(validation.InputError, match="residual: expected one finite value per row"):
        localize_misfit(np.zeros(m.n - 1), _known(m.n), m, "m")
    r = np.zeros(m.n)
    r[0] = math.inf
    with pytest.raises(validation.InputError, match="residual"):
        localize_misfit(r, _known(m.n), m, "m")


def test_only_a_verdict_that_misses_the_data_names_the_family():
    m = _rows()
    loc = localize_misfit(_bump(m) + np.random.default_rng(6).normal(0.0, SIGMA, m.n), _known(m.n), m, "m")
    assert loc is not None
    unexplained = Verdict("unexplained", None, 1e-9, "a pattern", "The baseline misses the data.")
    v = with_localized(unexplained, loc)
    assert v.localized == loc.text() and v.localized in v.headline and v.as_dict()["localized"] == loc.text()
    explained = Verdict("explained", "adhesion", 0.5, "none detected", "At the noise.", effects=("adhesion",))
    assert with_localized(explained, loc).localized == ""
    assert with_localized(unexplained, None).localized == ""


@pytest.fixture(scope="module")
def magic_formula_case():
    """The shipped null case (nothing hidden) with its slip sweep replaced by a Magic Formula curve (Pacejka &
    Bakker 1992) whose peak the brush model does not give: the sliding and wet rows stay at the noise."""
    case = validation.load_case("null")
    m = case.measurements
    s = m.slip < 1
    last = np.argmax(np.where(s, m.slip, -1.0))
    mu = m.mu.copy()
    mu[s] = m.mu[last] / np.sin(1.5 * np.arctan(30.0 * m.slip[last])) * np.sin(1.5 * np.arctan(30.0 * m.slip[s]))
    mu[s] += np.random.default_rng(3).normal(0.0, 0.01, int(s.sum()))
    return dataclasses.replace(case, measurements=m.with_mu(mu))


def test_the_diagnosis_places_a_slip_curve_of_another_model_in_the_slip_rows(magic_formula_case):
    dx = validation.diagnose(magic_formula_case, probe=False)
    assert dx.verdict.verdict in ("unexplained", "partly_explained")
    assert dx.localized is not None and dx.localized.family == "slip"
    assert dx.verdict.localized and dx.verdict.localized in dx.explanation
    assert dx.as_dict()["localized"]["family"] == "slip"
    assert "sits in the 10 rows with slip" in render_report([dx])


def test_the_loop_places_it_there_too_in_its_verdict_json_and_report(magic_formula_case):
    imp = validation.improve(magic_formula_case, probe=False)
    assert imp.verdict in ("unexplained", "partly_explained")
    assert imp.localized is not None and imp.localized.family == "slip"
    assert imp.final.localized in imp.final.headline
    assert imp.as_dict()["localized"]["family"] == "slip"
    assert imp.as_diagnosis().localized is imp.localized
    assert "sits in the 10 rows with slip" in render_report([imp])
