"""validation: where a model's misfit sits -- the family of rows (sliding, with slip, wet) it misses while it fits
the others -- is named in the verdict, with what rests on those rows; nothing is said on pure noise beyond the
test's level, nor when the misfit is everywhere.

The tests' p-values are checked against scipy.stats (chi^2 with the noise known, F with an estimated one, the
fitted parameters shared out over the families in proportion to their rows), the false-alarm rate by simulation.
"""

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy import stats

import validation
from validation.localize import ALPHA, REFIT_STEPS, localize_misfit
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
    # a Jacobian that does not match the rows is refused naming it (one that refits nothing places nothing)
    r = _fitted(_bump(m, 25 * SIGMA), _trade_jacobian(m))
    with pytest.raises(validation.InputError, match=r"refit\.jacobian: expected .* \(56 rows"):
        localize_misfit(r, _known(m.n), m, "m", n_params=2, refit=SimpleNamespace(jacobian=np.ones((m.n - 1, 2))))
    with pytest.raises(validation.InputError, match="non-finite"):
        localize_misfit(r, _known(m.n), m, "m", n_params=2,
                        refit=SimpleNamespace(jacobian=np.full((m.n, 2), math.nan)))
    assert localize_misfit(r, _known(m.n), m, "m", n_params=2, refit=SimpleNamespace(jacobian=np.zeros((m.n, 0)))) \
        is None


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


def _trade_jacobian(m):
    """d mu / d u of a linear model whose two parameters act on every row (an offset) and on the sliding rows (a
    trend in log speed): fitted to every row, the offset trades a misfit of the rows with slip for one elsewhere."""
    return np.column_stack([np.ones(m.n), np.where(m.slip >= 1, np.log10(m.speed), 0.0)])


def _fitted(y, J):
    """The residual of the least-squares fit of the columns ``J`` to ``y`` (the joint fit)."""
    return y - J @ np.linalg.lstsq(J, y, rcond=None)[0]


def test_parameters_that_trade_the_slip_rows_misfit_are_refitted_to_the_other_rows_as_in_chows_test():
    m = _rows()
    J = _trade_jacobian(m)
    r = _fitted(_bump(m, 25 * SIGMA) + np.random.default_rng(1).normal(0.0, SIGMA, m.n), J)
    # at the joint fit every family is missed: without the refit nothing is placed
    assert localize_misfit(r, _known(m.n), m, "m", n_params=2) is None
    loc = localize_misfit(r, _known(m.n), m, "m", n_params=2, refit=SimpleNamespace(jacobian=J))
    assert loc is not None and loc.family == "slip" and loc.traded == 2 and loc.n_evals == 0
    # Chow's predictive test, computed independently: the rest refitted alone, the family tested on what it adds
    s = m.slip < 1
    rss_rest = float(np.sum(_fitted(r[~s], J[~s]) ** 2)) / SIGMA ** 2
    total = float(np.sum(r ** 2)) / SIGMA ** 2
    assert loc.rest_p == pytest.approx(stats.chi2.sf(rss_rest, 46 - 2), rel=1e-9)
    assert loc.rest_ratio == pytest.approx(math.sqrt(rss_rest / 44), rel=1e-9)
    assert loc.p_value == pytest.approx(stats.chi2.sf(total - rss_rest, 10), rel=1e-6, abs=1e-300)
    assert loc.share == pytest.approx((total - rss_rest) / total, rel=1e-9)
    assert loc.rest_p >= 0.05 and loc.p_value < ALPHA
    text = loc.text()
    assert "refitted to the other 46 rows alone, its 2 fitted parameters" in text and "trade" in text
    assert loc.as_dict()["traded"] == 2


def test_with_an_estimated_noise_the_refit_tests_are_f_tests():
    m = _rows()
    J = _trade_jacobian(m)
    r = _fitted(_bump(m, 25 * SIGMA) + np.random.default_rng(2).normal(0.0, SIGMA, m.n), J)
    loc = localize_misfit(r, _estimated(m.n, dof=17.0), m, "m", n_params=2, refit=SimpleNamespace(jacobian=J))
    s = m.slip < 1
    rss_rest = float(np.sum(_fitted(r[~s], J[~s]) ** 2)) / SIGMA ** 2
    total = float(np.sum(r ** 2)) / SIGMA ** 2
    assert loc.family == "slip"
    assert loc.rest_p == pytest.approx(stats.f.sf(rss_rest / 44, 44, 17.0), rel=1e-9)
    assert loc.p_value == pytest.approx(stats.f.sf((total - rss_rest) / 10, 10, 17.0), rel=1e-6)


def test_a_nonlinear_model_is_refitted_to_the_other_rows_by_evaluated_gauss_newton_steps():
    """mu = a + exp(b) x: the refit's evaluated steps reach the optimum a least-squares solver finds."""
    from scipy.optimize import least_squares

    m = _rows()
    x = np.log10(m.speed) + 3.0

    def mu_of(u, rows=slice(None)):
        return u[0] + np.exp(u[1]) * x[rows]

    truth = mu_of(np.array([0.4, math.log(0.05)]))
    y = truth + _bump(m, 25 * SIGMA) + np.random.default_rng(7).normal(0.0, SIGMA, m.n)
    u_joint = least_squares(lambda u: mu_of(u) - y, [0.5, math.log(0.03)], xtol=1e-14, ftol=1e-14).x
    J = np.column_stack([np.ones(m.n), np.exp(u_joint[1]) * x])
    calls = []

    def predict(du, measurements):
        calls.append(du)
        return mu_of(u_joint + du)

    mm = m.with_mu(y)
    r = y - mu_of(u_joint)
    loc = localize_misfit(r, _known(m.n), mm, "m", n_params=2, refit=SimpleNamespace(jacobian=J, predict=predict))
    assert loc is not None and loc.family == "slip" and 1 <= loc.n_evals <= 3 * REFIT_STEPS   # three families
    rest = m.slip >= 1
    u_rest = least_squares(lambda u: mu_of(u, rest) - y[rest], u_joint, xtol=1e-14, ftol=1e-14).x
    rss_rest = float(np.sum((y[rest] - mu_of(u_rest, rest)) ** 2)) / SIGMA ** 2
    assert loc.rest_ratio == pytest.approx(math.sqrt(rss_rest / (rest.sum() - 2)), rel=1e-3)
    # a step the model cannot take places nothing; the evaluations it cost are told all the same
    told = []
    assert localize_misfit(r, _known(m.n), mm, "m", n_params=2, on_evals=told.append,
                           refit=SimpleNamespace(jacobian=J, predict=lambda du, mmm: None)) is None
    assert sum(told) >= 1
    told = []
    loc = localize_misfit(r, _known(m.n), mm, "m", n_params=2, on_evals=told.append,
                          refit=SimpleNamespace(jacobian=J, predict=predict))
    assert sum(told) == loc.n_evals


def test_on_pure_noise_the_refit_adds_at_most_alpha_to_the_false_placements():
    m = _rows()
    J = _trade_jacobian(m)
    refit = SimpleNamespace(jacobian=J)
    rng = np.random.default_rng(12)
    n_sim = 3000
    plain = with_refit = 0
    for _ in range(n_sim):
        r = _fitted(rng.normal(0.0, SIGMA, m.n), J)
        plain += localize_misfit(r, _known(m.n), m, "m", n_params=2) is not None
        with_refit += localize_misfit(r, _known(m.n), m, "m", n_params=2, refit=refit) is not None
    # each path is a Bonferroni test at ALPHA over the families; their union at most 2 ALPHA (sd 5.4 at 3000)
    assert with_refit - plain <= n_sim * ALPHA + 3 * math.sqrt(n_sim * ALPHA)
    assert with_refit <= 2 * n_sim * ALPHA + 3 * math.sqrt(2 * n_sim * ALPHA)


def test_the_refit_needs_other_rows_to_spare_beyond_the_parameters():
    def placed(n_sliding):
        m = _rows(n_sliding=n_sliding, n_slip=10, n_wet=0)
        lv = np.where(m.slip >= 1, np.log10(m.speed), 0.0)
        J = np.column_stack([np.ones(m.n), lv, lv ** 2])
        r = _fitted(_bump(m, 25 * SIGMA) + np.random.default_rng(4).normal(0.0, SIGMA, m.n), J)
        return localize_misfit(r, _known(m.n), m, "m", n_params=3, refit=SimpleNamespace(jacobian=J))

    # four sliding rows, three parameters: one degree of freedom left, fewer than MIN_ROWS
    assert placed(4) is None or placed(4).traded == 0
    # twelve: nine to spare, and the misfit is placed after the refit
    assert placed(12) is not None and placed(12).family == "slip" and placed(12).traded == 3


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


@pytest.fixture(scope="module")
def traded_case(magic_formula_case):
    """The same, with the adhesion's interfacial shear strength fitted with the model: fitted to every row, it
    trades the misfit of the slip rows for one on the sliding rows."""
    return dataclasses.replace(magic_formula_case, fit=("adhesion.tau_f0",))


def test_the_diagnosis_places_a_slip_curve_of_another_model_in_the_slip_rows(magic_formula_case):
    dx = validation.diagnose(magic_formula_case, probe=False)
    assert dx.verdict.verdict in ("unexplained", "partly_explained")
    assert dx.localized is not None and dx.localized.family == "slip"
    assert dx.verdict.localized and dx.verdict.localized in dx.explanation
    assert dx.as_dict()["localized"]["family"] == "slip"
    assert "sits in the 10 rows with slip" in render_report([dx])
    # the brush contact refitted with the rest leaves the misfit: the slip curve's shape is what the model lacks
    assert dx.localized.contact is not None and not dx.localized.contact.explains
    assert "shape of the slip curve" in dx.verdict.localized


def test_where_a_fitted_parameter_trades_the_misfit_the_diagnosis_refits_it_to_the_other_rows(
        traded_case):
    dx = validation.diagnose(traded_case, probe=False)
    assert dx.verdict.verdict in ("unexplained", "partly_explained")
    # at the joint fit adhesion.tau_f0 moves the sliding rows off the noise to meet the slip rows
    b = dx.baseline
    assert localize_misfit(traded_case.measurements.mu - b.predicted, dx.noise_estimate, traded_case.measurements,
                           "the baseline", n_params=b.n_params) is None
    assert dx.localized is not None and dx.localized.family == "slip" and dx.localized.traded == 1
    assert "refitted to the other 60 rows alone, its 1 fitted parameter leaves" in dx.verdict.localized
    assert dx.as_dict()["localized"]["traded"] == 1


def test_the_loop_places_it_there_too_in_its_verdict_json_and_report(traded_case):
    imp = validation.improve(traded_case, probe=False)
    assert imp.verdict in ("unexplained", "partly_explained")
    assert imp.localized is not None and imp.localized.family == "slip" and imp.localized.traded == 1
    assert imp.localized.contact is not None and imp.localized.contact.outcome == "stays"
    assert imp.final.localized in imp.final.headline
    assert imp.as_dict()["localized"]["family"] == "slip"
    assert imp.as_diagnosis().localized is imp.localized
    assert "sits in the 10 rows with slip" in render_report([imp])
