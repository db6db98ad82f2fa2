"""validation.distributions: tail probabilities against closed forms, and the randomized Halton design.

The distributions whose survival functions have elementary closed forms pin down each wrapper (argument order,
which tail): chi-square with 2 degrees of freedom is exponential, F with 2 numerator degrees of freedom is a
power law, Student t with one degree of freedom is Cauchy, the normal tail is erfc.
"""

import math
import subprocess
import sys

import numpy as np
import pytest

from validation import distributions as d


@pytest.mark.parametrize("x", [0.01, 0.7, 3.0, 25.0])
def test_chi2_with_two_degrees_of_freedom_is_exponential(x):
    assert d.chi2_sf(x, 2) == pytest.approx(math.exp(-x / 2), rel=1e-13)


@pytest.mark.parametrize("F, d2", [(0.3, 4.0), (2.0, 17.5), (9.0, 120.0)])
def test_f_with_two_numerator_degrees_of_freedom_is_a_power_law(F, d2):
    assert d.f_sf(F, 2, d2) == pytest.approx((1 + 2 * F / d2) ** (-d2 / 2), rel=1e-12)


@pytest.mark.parametrize("x, k", [(0.01, 2), (0.7, 2), (3.0, 4.5), (25.0, 30.0)])
def test_the_chi2_distribution_function_is_one_less_its_tail_and_exponential_with_two_dof(x, k):
    assert d.chi2_cdf(x, k) + d.chi2_sf(x, k) == pytest.approx(1.0, rel=1e-13)
    if k == 2:
        assert d.chi2_cdf(x, 2) == pytest.approx(-math.expm1(-x / 2), rel=1e-12)


@pytest.mark.parametrize("F, d2", [(0.3, 4.0), (2.0, 17.5), (9.0, 120.0)])
def test_the_f_distribution_function_is_one_less_the_power_law_tail(F, d2):
    assert d.f_cdf(F, 2, d2) == pytest.approx(1 - (1 + 2 * F / d2) ** (-d2 / 2), rel=1e-12)
    assert d.f_cdf(F, 5.5, d2) + d.f_sf(F, 5.5, d2) == pytest.approx(1.0, rel=1e-13)


@pytest.mark.parametrize("t", [-3.0, 0.0, 0.5, 40.0])
def test_t_with_one_degree_of_freedom_is_cauchy(t):
    assert d.t_sf(t, 1) == pytest.approx(0.5 - math.atan(t) / math.pi, rel=1e-13)


@pytest.mark.parametrize("p", [1e-7, 0.01, 0.3, 0.5, 0.9])
def test_the_t_quantile_inverts_the_cauchy_tail_and_with_infinite_dof_the_normal_one(p):
    # one degree of freedom: P(T > t) = 1/2 - atan(t) / pi, so t = tan(pi (1/2 - p))
    assert d.t_isf(p, 1) == pytest.approx(math.tan(math.pi * (0.5 - p)), rel=1e-10, abs=1e-14)
    z = d.t_isf(p, math.inf)
    assert 0.5 * math.erfc(z / math.sqrt(2)) == pytest.approx(p, rel=1e-10)
    assert d.t_sf(d.t_isf(p, 7.5), 7.5) == pytest.approx(p, rel=1e-10)


@pytest.mark.parametrize("z", [-2.0, 0.0, 1.3, 8.0])
def test_normal_tails_are_erfc(z):
    assert d.norm_sf(z) == pytest.approx(0.5 * math.erfc(z / math.sqrt(2)), rel=1e-13)
    assert d.norm_cdf(z) == pytest.approx(0.5 * math.erfc(-z / math.sqrt(2)), rel=1e-13)
    assert d.t_sf(z, math.inf) == pytest.approx(d.norm_sf(z), rel=1e-13)   # t with infinite dof is normal


def test_a_statistic_at_or_below_zero_has_survival_probability_one():
    assert d.chi2_sf(0.0, 3) == 1.0 and d.chi2_sf(-1.0, 3) == 1.0
    assert d.f_sf(0.0, 2, 5) == 1.0 and d.f_sf(-0.5, 2, 5) == 1.0
    assert d.chi2_cdf(0.0, 3) == 0.0 and d.f_cdf(-0.5, 2, 5) == 0.0


def test_halton_points_stratify_each_coordinate_and_depend_on_the_seed():
    # the first b^m points put one point in each of the b^m equal cells of coordinate j (base b = j-th prime)
    for k, n_per_dim in ((3, (16, 27, 25)),):
        for j, n in enumerate(n_per_dim):
            x = d.halton(k, n, seed=5)[:, j]
            assert np.all((x >= 0) & (x < 1))
            assert sorted(np.floor(x * n).astype(int)) == list(range(n))
    a, b = d.halton(2, 10, seed=1), d.halton(2, 10, seed=2)
    np.testing.assert_array_equal(a, d.halton(2, 10, seed=1))
    assert not np.allclose(a, b)
    assert d.halton(0, 5).shape == (5, 0) and d.halton(3, 0).shape == (0, 3)


def test_importing_and_diagnosing_never_loads_scipy_stats():
    """scipy.stats takes about half a second to import: no command of the diagnosis pays for it."""
    code = ("import sys, warnings; warnings.simplefilter('ignore'); import validation;"
            "validation.diagnose(validation.load_case('hidden_flash'), candidates=['microtexture'], probe=False);"
            "print('scipy.stats' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
