"""validation: rows too far from the model to be noise are named, by their line in the file, and nothing else is.

The threshold is the two-sided Bonferroni one at level ALPHA for n rows: with pure Gaussian noise a data set has
a row beyond it with probability at most ALPHA, which is checked against the closed form
P(max |z| > t) = 1 - (1 - erfc(t / sqrt 2))^n and by simulation.
"""

import math

import numpy as np
import pytest
from scipy import stats

import materials
import persson
import surfaces
import validation
from validation.noise import NoiseEstimate
from validation.outliers import ALPHA, MAX_ROWS, outlying_rows

SIGMA = 0.005


def _known(n, sigma=SIGMA):
    return NoiseEstimate(source="mu_std", sigma=sigma, dof=math.inf, row_sigma=np.full(n, sigma), description="")


def _rows(n):
    return validation.Measurements.from_arrays(slip=1.0, speed=np.geomspace(1e-3, 1.0, n), temperature=20.0,
                                               pressure=3e5, mu=0.5)


def _threshold(n):
    """A row at 10 sigma is named; the threshold it is compared with is reported."""
    r = np.zeros(n)
    r[0] = 10 * SIGMA
    return outlying_rows(r, _known(n), _rows(n), "m").threshold


@pytest.mark.parametrize("n", [20, 150, 2000])
def test_pure_noise_has_a_row_beyond_the_threshold_in_alpha_of_the_data_sets(n):
    t = _threshold(n)
    # the chance that any of n independent standard normal values exceeds t in magnitude
    p_any = 1.0 - (1.0 - math.erfc(t / math.sqrt(2.0))) ** n
    assert 0.99 * ALPHA < p_any <= ALPHA


def test_the_rate_on_simulated_noise_matches_the_level():
    n, n_sim = 100, 4000
    rng = np.random.default_rng(5)
    rows, noise = _rows(n), _known(n)
    named = sum(outlying_rows(rng.normal(0.0, SIGMA, n), noise, rows, "m") is not None for _ in range(n_sim))
    # binomial(4000, 0.01): mean 40, sd 6.3
    assert 15 <= named <= 65


def test_with_an_estimated_noise_the_threshold_is_students():
    n = 150
    r = np.zeros(n)
    r[3] = 10 * SIGMA
    est = NoiseEstimate(source="local differences", sigma=SIGMA, dof=20.0, row_sigma=np.full(n, SIGMA),
                        description="")
    out = outlying_rows(r, est, _rows(n), "m")
    assert out.threshold == pytest.approx(stats.t.isf(ALPHA / (2 * n), 20.0), rel=1e-12)
    assert out.threshold > _threshold(n)


def test_two_faulty_rows_are_named_by_their_lines_farthest_first(tmp_path):
    n = 60
    rng = np.random.default_rng(7)
    rows = _rows(n)
    mu = 0.5 + rng.normal(0.0, SIGMA, n)
    mu[[11, 40]] += [-6 * SIGMA * 1.5, 8 * SIGMA * 1.5]
    path = rows.with_mu(mu, mu_std=np.full(n, SIGMA)).to_csv(tmp_path / "m.csv", comments=("a comment",))
    m = validation.read_measurements(path)
    out = outlying_rows(m.mu - 0.5, _known(n), m, "the baseline")
    assert out.rows == (40, 11) and out.z[0] > 0 > out.z[1]
    assert out.lines == (int(m.lines[40]), int(m.lines[11])) and out.lines[0] > 40  # header and comment first
    text = out.text()
    assert f"line {out.lines[0]}" in text and "m.csv" in text and "2 rows lie" in text
    assert out.as_dict()["rows"] == [40, 11]


def test_many_rows_far_off_are_a_misfit_not_faults_and_without_noise_nothing_is_said():
    n = 150
    r = np.zeros(n)
    r[: MAX_ROWS + 1] = 10 * SIGMA
    assert outlying_rows(r, _known(n), _rows(n), "m") is None
    r = np.zeros(n)
    r[0] = 10 * SIGMA
    none = NoiseEstimate(source="none", sigma=math.nan, dof=0.0, row_sigma=np.full(n, math.nan), description="")
    assert outlying_rows(r, none, _rows(n), "m") is None
    assert outlying_rows(np.zeros(n), _known(n), _rows(n), "m") is None


def test_the_diagnosis_and_the_loop_name_a_faulty_row_in_their_verdicts():
    surface = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=3e-4)
    model = persson.Model(surface, materials.example_tread())
    v = np.geomspace(1e-3, 1.0, 10)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, 3),
                                               temperature=np.repeat([10.0, 25.0, 40.0], 10), pressure=3e5,
                                               mu=0.5, mu_std=SIGMA)
    mu = validation.predict(model, rows).mu + np.random.default_rng(3).normal(0.0, SIGMA, rows.n)
    mu[17] += 12 * SIGMA
    m = rows.with_mu(mu, mu_std=np.full(rows.n, SIGMA))
    dx = validation.diagnose(model, m, candidates=["adhesion"])
    assert dx.outliers is not None and dx.outliers.rows == (17,)
    assert "row 17" in dx.verdict.outliers and dx.verdict.outliers in dx.explanation
    assert dx.verdict.outliers.startswith("A row lies") and "Check it for a fault" in dx.verdict.outliers
    assert dx.as_dict()["outliers"]["rows"] == [17]
    imp = validation.improve(model, m, candidates=["adhesion"])
    assert imp.outliers is not None and imp.outliers.rows == (17,)
    assert "row 17" in imp.final.headline and imp.as_dict()["outliers"]["z"][0] > imp.outliers.threshold


def test_a_residual_that_does_not_match_the_rows_is_refused_naming_the_argument():
    n = 20
    with pytest.raises(validation.InputError, match="residual: expected one finite value per row"):
        outlying_rows(np.zeros(n - 1), _known(n), _rows(n), "m")
    r = np.zeros(n)
    r[2] = math.nan
    with pytest.raises(validation.InputError, match="residual"):
        outlying_rows(r, _known(n), _rows(n), "m")
