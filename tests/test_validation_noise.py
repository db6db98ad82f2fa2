"""validation.noise: the model-free noise estimates, the lack-of-fit tests and the pattern search.

Every number is checked against an independent computation: the textbook formulas written out here with numpy and
scipy (Gasser-Sroka-Jennen-Steinmetz pseudo-residuals, Satterthwaite's degrees of freedom, the pure-error F test of
Draper & Smith, the Wald-Wolfowitz runs test), and Monte-Carlo checks of unbiasedness and calibration.
"""

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy import stats

import validation
from validation.noise import (ALPHA, estimate_noise, lack_of_fit, remaining_pattern, series_of)


def _one_series(mu, n=None, speeds=None, mu_std=None, T=20.0):
    speeds = np.geomspace(1e-3, 1.0, len(mu)) if speeds is None else speeds
    return validation.Measurements.from_arrays(slip=1.0, speed=speeds, temperature=T, pressure=3e5, mu=mu,
                                               mu_std=mu_std)


def _grid(mu_fn, rng, sigma=0.01, temps=(0.0, 20.0, 40.0), n_speed=10):
    v = np.geomspace(1e-3, 1.0, n_speed)
    V = np.tile(v, len(temps))
    T = np.repeat(temps, n_speed)
    mu = mu_fn(np.log10(V), T) + rng.normal(0, sigma, V.size)
    return validation.Measurements.from_arrays(slip=1.0, speed=V, temperature=T, pressure=3e5, mu=mu)


# ---- local differences -------------------------------------------------------------------------------------------
def test_local_estimate_equals_the_second_difference_formula_for_equal_spacing():
    rng = np.random.default_rng(1)
    y = 0.5 + rng.normal(0, 0.01, 20)
    m = _one_series(y)
    ne = estimate_noise(m)
    assert ne.source == "local differences"
    # equal spacing in log speed: a = b = 1/2, c^2 = 2/3, so c e = (y[i-1] - 2 y[i] + y[i+1]) / sqrt(6)
    d2 = (y[:-2] - 2 * y[1:-1] + y[2:]) / math.sqrt(6.0)
    assert ne.sigma ** 2 == pytest.approx(np.mean(d2 ** 2), rel=1e-10)
    # Satterthwaite: m^2 / ||B B^T||_F^2 with lag-1 correlation -4/6 and lag-2 correlation 1/6
    mm = d2.size
    frob = mm + 2 * (mm - 1) * (4 / 6) ** 2 + 2 * (mm - 2) * (1 / 6) ** 2
    assert ne.dof == pytest.approx(mm ** 2 / frob, rel=1e-10)


def test_local_estimate_removes_a_linear_trend_exactly():
    y = 0.3 + 0.05 * np.log10(np.geomspace(1e-3, 1.0, 20))
    rng = np.random.default_rng(2)
    noise = rng.normal(0, 0.01, y.size)
    a = estimate_noise(_one_series(y + noise)).sigma
    b = estimate_noise(_one_series(0.7 + noise)).sigma
    assert a == pytest.approx(b, rel=1e-9)


def test_local_estimate_is_unbiased_and_its_dof_describe_its_scatter():
    """Monte Carlo over 400 data sets: the mean of sigma^2 is sigma^2, its variance 2 sigma^4 / dof."""
    rng = np.random.default_rng(3)
    est = []
    for _ in range(400):
        m = _grid(lambda lv, T: 0.5 + 0.1 * lv, rng)
        ne = estimate_noise(m)
        est.append(ne.sigma ** 2)
    est = np.array(est)
    s2 = 1e-4
    assert abs(est.mean() - s2) < 3 * est.std() / math.sqrt(est.size)
    assert est.var() == pytest.approx(2 * s2 ** 2 / ne.dof, rel=0.2)


def test_series_are_the_rows_that_differ_in_one_condition():
    m = validation.Measurements.from_arrays(
        slip=[1, 1, 1, 1, 0.05, 0.1, 0.2, 1, 1, 1], speed=[0.01, 0.1, 1, 0.5, 1, 1, 1, 0.3, 0.3, 0.3],
        temperature=[20, 20, 20, 40, 20, 20, 20, 0, 10, 30], pressure=3e5, mu=0.5)
    series = {axis: sorted(idx.tolist()) for idx, x, axis in series_of(m)}
    assert series["log10 sliding speed"] == [0, 1, 2]
    assert series["log10 slip"] == [4, 5, 6]
    assert series["temperature"] == [7, 8, 9]
    assert 3 not in np.concatenate([idx for idx, _, _ in series_of(m)])


# ---- replicates and mu_std -----------------------------------------------------------------------------------
def test_replicates_give_the_pure_error_and_the_classical_lack_of_fit_test():
    rng = np.random.default_rng(4)
    v = np.repeat(np.geomspace(1e-3, 1.0, 8), 3)
    x = np.log10(v)
    y = 0.5 + 0.02 * x ** 2 + rng.normal(0, 0.01, v.size)
    m = _one_series(y, speeds=v)
    ne = estimate_noise(m)
    assert ne.source == "replicates" and ne.n_groups == 8
    means = np.array([y[i * 3:(i + 1) * 3].mean() for i in range(8)])
    ss_pe = float(np.sum((y - np.repeat(means, 3)) ** 2))
    assert ne.pure_error == pytest.approx(ss_pe, rel=1e-12)
    assert ne.sigma == pytest.approx(math.sqrt(ss_pe / 16), rel=1e-12)
    # a straight line in log speed misses the curvature: Draper & Smith's F test rejects it
    A = np.column_stack([np.ones_like(x), x])
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    r = y - A @ coef
    lof = lack_of_fit(r, 2, ne)
    F = ((np.sum(r ** 2) - ss_pe) / (8 - 2)) / (ss_pe / 16)
    assert lof.test == "F" and lof.dof == (6, 16)
    assert lof.statistic == pytest.approx(F, rel=1e-10)
    assert lof.p_value == pytest.approx(stats.f.sf(F, 6, 16), rel=1e-10)
    assert not lof.consistent
    # the right model (with the quadratic term) passes
    A2 = np.column_stack([A, x ** 2])
    r2 = y - A2 @ np.linalg.lstsq(A2, y, rcond=None)[0]
    assert lack_of_fit(r2, 3, ne).consistent


# ---- a scatter that changes with the friction level ---------------------------------------------------------------
def _replicates_at_levels(rng, levels, n_rep=4, rel=0.05, gamma=1.0):
    """Replicate rows at conditions whose true mu are ``levels``, noise sd = rel * mean level * (mu/mean)^gamma."""
    v = np.repeat(np.geomspace(1e-3, 1.0, len(levels)), n_rep)
    mu_true = np.repeat(levels, n_rep)
    ref = float(np.exp(np.mean(np.log(levels))))
    sd = rel * ref * (mu_true / ref) ** gamma
    return _one_series(mu_true + rng.normal(0.0, sd), speeds=v)


def _proportional_series(rng):
    """Five speed series (0-40 C, 15 speeds each) whose true mu spans 0.15-1.05, with noise in proportion to mu (3 %
    of the mean at the mean level); returns the measurements and the true mu."""
    temps, n_speed = (0.0, 10.0, 20.0, 30.0, 40.0), 15
    v = np.tile(np.geomspace(1e-3, 1.0, n_speed), len(temps))
    T = np.repeat(temps, n_speed)
    mu_true = 0.15 + 0.9 * (np.log10(v) + 3.0) / 3.0 * (1.0 - T / 80.0)
    sd = 0.03 * mu_true / np.mean(mu_true)
    m = validation.Measurements.from_arrays(slip=1.0, speed=v, temperature=T, pressure=3e5,
                                            mu=mu_true + rng.normal(0.0, sd))
    return m, mu_true


def test_replicate_scatter_in_proportion_to_mu_is_found_at_its_maximum_likelihood_exponent():
    """The exponent is the maximum of the chi^2 likelihood of the group sums of squares, found here independently
    by a brute-force search over both the scale and the exponent."""
    rng = np.random.default_rng(31)
    levels = np.geomspace(0.2, 1.2, 12)
    m = _replicates_at_levels(rng, levels, n_rep=4)
    ne = estimate_noise(m)
    assert ne.source == "replicates"
    assert ne.trend_p < 0.01 and ne.trend != 0.0
    # independent: SS_g ~ sigma_g^2 chi^2(3), sigma_g = s (mean_g / gbar)^gamma, log-likelihood over a grid
    y = m.mu.reshape(12, 4)
    means, ss = y.mean(axis=1), ((y - y.mean(axis=1, keepdims=True)) ** 2).sum(axis=1)
    x = np.log(means) - np.mean(np.log(means))
    gammas = np.linspace(0.0, 1.0, 3001)
    log_s2 = np.linspace(-12.0, -4.0, 801)
    G, L = np.meshgrid(gammas, log_s2, indexing="ij")
    var = np.exp(L[..., None] + 2.0 * G[..., None] * x)
    ll = np.sum(-1.5 * np.log(var) - ss / (2.0 * var), axis=-1)
    ig, il = np.unravel_index(np.argmax(ll), ll.shape)
    assert ne.trend == pytest.approx(gammas[ig], abs=2e-3)
    assert abs(ne.trend - 1.0) < 0.5
    # sigma is the level at the geometric mean of the group means, each row's noise the law at its group's mean
    assert ne.sigma == pytest.approx(math.exp(0.5 * log_s2[il]), rel=0.01)
    gbar = math.exp(np.mean(np.log(means)))
    assert ne.row_sigma == pytest.approx(ne.sigma * np.repeat(means / gbar, 4) ** ne.trend, rel=1e-10)
    assert ne.dof == 36 - 1
    # the pure error in the units of the reference level: each group's scatter over its noise factor
    f = np.repeat((means / gbar) ** ne.trend, 4)
    assert ne.pure_error == pytest.approx(np.sum(((y.ravel() - np.repeat(means, 4)) / f) ** 2), rel=1e-10)
    assert "each row weighted by its own" in ne.description and ne.as_dict()["trend_exponent"] == ne.trend


def test_the_lack_of_fit_test_weighs_each_row_by_its_noise():
    """With sigma_i = s f_i, F = sum (r_i / f_i)^2 / (n - k) / s^2 (local differences); the right model passes, and
    with one noise level (f = 1) the statistic is the unweighted one exactly."""
    m, mu_true = _proportional_series(np.random.default_rng(35))
    ne = estimate_noise(m, reference=mu_true)
    assert ne.trend != 0.0
    r = m.mu - mu_true
    lof = lack_of_fit(r, 0, ne)
    f = ne.row_sigma / ne.sigma
    assert lof.statistic == pytest.approx(np.sum((r / f) ** 2) / r.size / ne.sigma ** 2, rel=1e-12)
    assert lof.consistent
    flat = replace(ne, row_sigma=np.full(r.size, ne.sigma), trend=0.0)
    assert lack_of_fit(r, 0, flat).statistic == float(np.sum(r * r)) / r.size / ne.sigma ** 2


def test_local_difference_scatter_in_proportion_to_mu_is_found():
    m, mu_true = _proportional_series(np.random.default_rng(32))
    ne = estimate_noise(m, reference=mu_true)
    assert ne.source == "local differences"
    assert ne.trend_p < 0.01 and 0.5 < ne.trend < 1.5


@pytest.mark.parametrize("kind", ["replicates", "local differences"])
def test_a_constant_scatter_is_rarely_called_a_trend(kind):
    """300 noise-only data sets with one noise level over a friction range of 6x: the test of a trend keeps its
    1 % level (at most 3 % here; binomial: P(more than 9 of 300 | 1 %) < 0.1 %)."""
    rng = np.random.default_rng(33 if kind == "replicates" else 34)
    found = 0
    for _ in range(300):
        if kind == "replicates":
            m = _replicates_at_levels(rng, np.geomspace(0.2, 1.2, 10), n_rep=3, gamma=0.0)
        else:
            m = _grid(lambda lv, T: 0.2 + 0.33 * (lv + 3.0) * (1.0 - T / 80.0), rng, sigma=0.02, n_speed=12)
        ne = estimate_noise(m)
        assert ne.source == kind and math.isfinite(ne.trend_p)
        found += ne.trend != 0.0
    assert found <= 9


def test_rows_at_zero_friction_keep_a_finite_noise_level():
    """The corner of a vanishing friction (a locked, lubricated or clipped reading): a group measured at mu = 0
    cannot enter the fit of the law (its level has no logarithm), and its rows get the floor of a tenth of the
    reference level, not a zero or NaN noise that would make their weights infinite."""
    rng = np.random.default_rng(36)
    levels = np.concatenate([[0.0], np.geomspace(0.2, 1.2, 12)])
    mu_true = np.repeat(levels, 4)
    m = _one_series(mu_true + rng.normal(0.0, 0.05 * mu_true), speeds=np.repeat(np.geomspace(1e-3, 1.0, 13), 4))
    assert np.all(m.mu[:4] == 0.0)
    ne = estimate_noise(m)
    assert ne.trend > 0 and np.all(np.isfinite(ne.row_sigma)) and np.all(ne.row_sigma > 0)
    means = m.mu.reshape(13, 4).mean(axis=1)
    gbar = math.exp(np.mean(np.log(means[1:])))
    assert ne.row_sigma[:4] == pytest.approx(ne.sigma * 0.1 ** ne.trend, rel=1e-10)
    assert ne.row_sigma[4:] == pytest.approx(ne.sigma * np.repeat(means[1:] / gbar, 4) ** ne.trend, rel=1e-10)
    lof = lack_of_fit(m.mu - 0.9 * np.repeat(means, 4), 2, ne)
    assert math.isfinite(lof.statistic) and math.isfinite(ne.pure_error)


def test_no_trend_test_with_mu_std():
    m = _one_series(np.linspace(0.2, 1.0, 12), mu_std=np.linspace(0.01, 0.05, 12))
    ne = estimate_noise(m)
    assert math.isnan(ne.trend_p) and ne.trend == 0.0 and ne.as_dict()["trend_p"] is None


def test_a_verdict_on_data_whose_scatter_grows_with_mu_says_so():
    from validation.verdict import Verdict, with_noise_trend

    rng = np.random.default_rng(31)
    ne = estimate_noise(_replicates_at_levels(rng, np.geomspace(0.2, 1.2, 12)))
    assert ne.trend > 0
    v = Verdict(verdict="unexplained", effect=None, lack_of_fit_p=1e-4, remaining_pattern="a pattern", reason="R.")
    out = with_noise_trend(v, ne)
    assert out.reason.startswith("R. Note: the scatter of these data grows with the friction level")
    assert "each row was weighted" in out.reason and out.verdict == "unexplained"
    # nothing to warn about where nothing is missing, or where the noise shows no trend
    assert with_noise_trend(replace(v, verdict="nothing_missing"), ne).reason == "R."
    assert with_noise_trend(v, replace(ne, trend=0.0)).reason == "R."


def test_mu_std_gives_a_chi2_test():
    rng = np.random.default_rng(5)
    std = np.linspace(0.005, 0.02, 10)
    y = 0.5 + rng.normal(0, 1, 10) * std
    m = _one_series(y, mu_std=std)
    ne = estimate_noise(m)
    assert ne.source == "mu_std" and ne.sigma == pytest.approx(np.sqrt(np.mean(std ** 2)))
    r = y - 0.5
    lof = lack_of_fit(r, 0, ne)
    chi2 = float(np.sum((r / std) ** 2))
    assert lof.statistic == pytest.approx(chi2) and lof.p_value == pytest.approx(stats.chi2.sf(chi2, 10))


def test_too_few_rows_give_no_noise_estimate_and_no_test():
    m = validation.Measurements.from_arrays(slip=1.0, speed=[0.01, 0.1], temperature=[10, 30], pressure=3e5,
                                            mu=[0.4, 0.5])
    ne = estimate_noise(m)
    assert ne.source == "none" and math.isnan(ne.sigma) and not ne.known
    lof = lack_of_fit(np.array([0.1, -0.1]), 0, ne)
    assert lof.test == "none" and lof.consistent and math.isnan(lof.p_value)


def test_local_lack_of_fit_test_is_calibrated_or_conservative():
    """Under the model (pure noise residual) the test rejects at most about ALPHA of the time."""
    rng = np.random.default_rng(6)
    rejected = 0
    n = 300
    for _ in range(n):
        m = _grid(lambda lv, T: 0.5 + 0.0 * lv, rng)
        rejected += not lack_of_fit(m.mu - 0.5, 0, estimate_noise(m)).consistent
    assert rejected / n <= ALPHA + 3 * math.sqrt(ALPHA / n)


def test_local_lack_of_fit_test_sees_a_misfit_twice_the_noise():
    rng = np.random.default_rng(7)
    m = _grid(lambda lv, T: 0.5 + 0.02 * np.sin(2.5 * lv) + 0.0004 * (T - 20), rng)
    lof = lack_of_fit(m.mu - 0.5, 0, estimate_noise(m))
    assert not lof.consistent and lof.ratio > 1.5


def test_bad_reference_names_the_argument():
    m = _one_series(np.full(6, 0.5))
    with pytest.raises(validation.InputError, match="reference"):
        estimate_noise(m, reference=np.ones(3))


# ---- patterns -------------------------------------------------------------------------------------------------
def _slip_rows(rng, resid_fn, sigma=0.005):
    s = np.array([0.005, 0.01, 0.02, 0.04, 0.07, 0.1, 0.15, 0.2, 0.35, 0.6, 0.85])
    S = np.tile(s, 3)
    V = np.repeat([0.5, 1.0, 2.0], s.size)
    r = resid_fn(np.log10(S)) + rng.normal(0, sigma, S.size)
    m = validation.Measurements.from_arrays(slip=S, speed=V, temperature=20.0, pressure=3e5, mu=0.5 + r)
    return m, r


def test_a_hump_along_the_slip_curves_is_found_and_described():
    rng = np.random.default_rng(8)
    m, r = _slip_rows(rng, lambda ls: 0.04 * np.exp(-((ls + 1.0) / 0.35) ** 2))
    ne = estimate_noise(m)
    pat = remaining_pattern(r, m, ne)
    assert pat.found
    text = "; ".join(pat.findings)
    assert "rises then falls with slip" in text
    assert "sign runs" in text
    assert pat.describe().endswith("more")      # the text names the strongest three


def test_pure_noise_shows_no_pattern():
    rng = np.random.default_rng(9)
    m, r = _slip_rows(rng, lambda ls: 0.0 * ls)
    ne = estimate_noise(m)
    pat = remaining_pattern(r, m, ne)
    assert not pat.found and pat.describe().startswith("none detected")


def test_a_shift_at_one_temperature_is_found_as_a_group():
    rng = np.random.default_rng(10)
    m = _grid(lambda lv, T: 0.5 + 0.0 * lv, rng, temps=(0.0, 10.0, 20.0, 30.0, 40.0))
    r = m.mu - 0.5 + np.where(m.temperature == 40.0, 0.02, 0.0)
    pat = remaining_pattern(r, m, estimate_noise(m.with_mu(m.mu)))
    assert pat.found and any("by temperature" in f and "40 C" in f for f in pat.findings)


def test_runs_test_matches_wald_wolfowitz():
    """One series whose residual keeps its sign in long blocks: the pooled z equals the textbook formula."""
    signs = np.array([1, 1, 1, 1, 1, 1, -1, -1, -1, -1, -1, -1, 1, 1, 1, 1, 1, 1], dtype=float)
    r = 0.01 * signs
    m = _one_series(0.5 + r)
    ne = estimate_noise(_one_series(0.5 + np.random.default_rng(0).normal(0, 0.01, signs.size)))
    pat = remaining_pattern(r, m, ne)
    n1, n2 = 12, 6
    n = n1 + n2
    E = 1 + 2 * n1 * n2 / n
    V = 2 * n1 * n2 * (2 * n1 * n2 - n) / (n * n * (n - 1))
    p = stats.norm.cdf((3 - E) / math.sqrt(V))
    assert any(f"runs test p = {p:.2g}" in f for f in pat.findings)


def test_pattern_search_on_pure_noise_keeps_its_false_alarm_rate():
    """300 residuals of pure noise on a DRFT-like grid (3 temperatures x 2 pressures x 9 speeds and a slip sweep),
    the noise estimated from the data each time: the pattern search calls at most its nominal rate PATTERN_ALPHA
    (1.5 %) of them systematic (three binomial standard errors of margin)."""
    from validation.noise import PATTERN_ALPHA

    rng = np.random.default_rng(12)
    v = np.geomspace(1e-3, 3.0, 9)
    T, p, V = np.meshgrid([0.0, 20.0, 40.0], [2e5, 5e5], v, indexing="ij")
    s = np.array([0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.4, 0.8])
    m0 = validation.Measurements.from_arrays(slip=np.concatenate([np.ones(V.size), s]),
                                             speed=np.concatenate([V.ravel(), np.ones(s.size)]),
                                             temperature=np.concatenate([T.ravel(), np.full(s.size, 20.0)]),
                                             pressure=np.concatenate([p.ravel(), np.full(s.size, 3e5)]), mu=0.5)
    n, found = 300, 0
    for _ in range(n):
        r = rng.normal(0, 0.01, m0.n)
        m = m0.with_mu(0.5 + r)
        found += remaining_pattern(r, m, estimate_noise(m, reference=np.full(m.n, 0.5))).found
    assert found / n <= PATTERN_ALPHA + 3 * math.sqrt(PATTERN_ALPHA / n)


def test_a_diagnosis_weights_each_row_by_a_noise_that_grows_with_mu():
    """The shipped null case with noise in proportion to mu: the diagnosis finds the trend, refits with each row
    weighted by s / sigma_i, counts both passes, and finds nothing missing; with one noise level every weight is
    exactly 1."""
    case = validation.load_case("null")
    m = case.measurements
    mu = validation.predict(case.model, m, case.contact).mu
    rng = np.random.default_rng(0)
    meas = m.with_mu(np.clip(mu + rng.normal(0.0, 0.03 * mu / mu.mean()), 0.0, None))
    kw = dict(contact=case.contact, fit=case.fit, candidates=["microtexture"])
    dx = validation.diagnose(case.model, meas, **kw)
    ne = dx.noise_estimate
    assert ne.source == "local differences" and ne.trend > 0.5 and ne.trend_p < 0.01
    w = dx.context.settings.w
    assert w == pytest.approx(ne.sigma / ne.row_sigma, rel=1e-12) and w.max() / w.min() > 3
    once = validation.diagnose(case.model, meas, noise=ne, **kw)       # the weighted pass alone
    assert np.array_equal(once.context.settings.w, w)
    assert dx.n_evaluations > once.n_evaluations
    assert dx.verdict.verdict == once.verdict.verdict == "nothing_missing"
    flat = validation.diagnose(case.model, m.with_mu(np.clip(mu + rng.normal(0.0, 0.01, m.n), 0.0, None)), **kw)
    assert flat.noise_estimate.trend == 0.0 and np.all(flat.context.settings.w == 1.0)
