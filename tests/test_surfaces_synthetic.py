"""Synthetic surfaces and the road from profiles to isotropic PSD (issue 3, Must show 1 and 3).

The reference is the SelfAffine model the surfaces are synthesized from; band-limited moments of the truth
are computed by adaptive quadrature, independently of the code under test.
"""

import math

import numpy as np
import pytest
from scipy import integrate

import surfaces


def _band_moment(s, n, a, b):
    """2 pi int_a^b q^n C(q) dq by quadrature in ln q, split at the roll-off."""
    edges = sorted({a, *(e for e in (s.q0,) if a < e < b), b})
    f = lambda t: math.exp((n + 1) * t) * float(s.C(math.exp(t)))  # noqa: E731
    return 2 * math.pi * sum(integrate.quad(f, math.log(lo), math.log(hi), limit=200)[0]
                             for lo, hi in zip(edges[:-1], edges[1:]))


@pytest.fixture(scope="module")
def map_rows_psd():
    """A 1024 x 1024 isotropic self-affine map (H = 0.8) cut into its 1024 row profiles.

    Random phases with exact amplitudes: the realization has exactly the discretized true PSD, so the test
    measures the analysis, not the luck of the draw (a Gaussian map scatters h_rms by several % through
    its few long-wave modes)."""
    L = 0.1
    qL = 2 * math.pi / L
    truth = surfaces.SelfAffine(hurst=0.8, q0=8 * qL, q1=1e9, hrms=50e-6, qL=qL)  # q1 past the grid
    hmap = surfaces.synthesize_map(truth, 1024, seed=11, random_amplitude=False)
    p1 = hmap.rows().psd()
    return truth, hmap, p1, p1.to_isotropic()


def test_map_rows_to_isotropic_recovers_true_psd(map_rows_psd):
    """Must show: median ratio of C(q) within 5 % on [3 q0, q_r/3]; h_rms, rms slope within 5 %."""
    truth, hmap, p1, iso = map_rows_psd
    assert hmap.shape == (1024, 1024)
    q_r = p1.q_r
    assert q_r == pytest.approx(math.pi / hmap.dx)
    band = (iso.q >= 3 * truth.q0) & (iso.q <= q_r / 3)
    assert band.sum() >= 15
    median_ratio = np.median(iso.C_values[band] / truth.C(iso.q[band]))
    assert median_ratio == pytest.approx(1.0, abs=0.05)
    a, b = iso.q_range
    assert iso.hrms() == pytest.approx(math.sqrt(_band_moment(truth, 1, a, b)), rel=0.05)
    assert iso.rms_slope() == pytest.approx(math.sqrt(_band_moment(truth, 3, a, b)), rel=0.05)
    assert iso.q_r == pytest.approx(q_r) and not iso.extrapolated
    # the result carries its cut-offs: qL of the scan and the roll-off found by the flat + power-law fit
    assert iso.cutoffs.qL == pytest.approx(2 * math.pi / 0.1)
    assert iso.cutoffs.q0 == pytest.approx(truth.q0, rel=0.1)


def test_map_rows_fitted_hurst(map_rows_psd):
    truth, _, p1, iso = map_rows_psd
    lo, hi = 3 * truth.q0, p1.q_r / 3
    assert surfaces.fit_self_affine(iso, lo, hi).hurst == pytest.approx(0.8, abs=0.05)
    assert surfaces.fit_self_affine(p1, lo, hi).hurst == pytest.approx(0.8, abs=0.05)


def test_radially_averaged_map_psd(map_rows_psd):
    """The 2D PSD by radial averaging of the same map, same convention: median ratio within 5 %."""
    truth, hmap, _, _ = map_rows_psd
    psd2d = hmap.psd()
    band = (psd2d.q >= 3 * truth.q0) & (psd2d.q <= psd2d.q_r / 3)
    assert np.median(psd2d.C_values[band] / truth.C(psd2d.q[band])) == pytest.approx(1.0, abs=0.05)
    # variance: the radial PSD integrates to the map's variance (modes inside the Nyquist disc)
    assert psd2d.hrms() == pytest.approx(hmap.hrms(), rel=0.05)


def test_windowed_psd_of_a_non_periodic_map():
    """A map cut out of a larger one is not periodic: the Hann window keeps the steep spectrum clean."""
    truth = surfaces.SelfAffine(hurst=0.8, q0=4e3, q1=1e9, hrms=1e-5, qL=2 * math.pi / 2e-3)
    big = surfaces.synthesize_map(truth, 512, seed=4, random_amplitude=False)
    piece = surfaces.HeightMap(big.z[:256, :256], dx=big.dx)
    psd2d = piece.psd()
    band = (psd2d.q >= 3 * truth.q0) & (psd2d.q <= psd2d.q_r / 3)
    assert np.median(psd2d.C_values[band] / truth.C(psd2d.q[band])) == pytest.approx(1.0, abs=0.1)


@pytest.mark.parametrize("H", [0.4, 0.8])
def test_round_trip_hurst_from_synthetic_profiles(H):
    """Must show: SelfAffine -> synthetic line profiles -> fitted H within 0.05 (1D and isotropic fits)."""
    truth = surfaces.SelfAffine(hurst=H, q0=2e3, q1=2e6, hrms=1e-4, qL=2e2)
    ps = surfaces.synthesize_profiles(truth, n_profiles=8, n=2**14, seed=5)
    p1 = ps.psd()
    band = (3 * truth.q0, p1.q_r / 3)
    assert surfaces.fit_self_affine(p1, *band).hurst == pytest.approx(H, abs=0.05)
    iso = p1.to_isotropic()
    fit = surfaces.fit_self_affine(iso, *band)
    assert fit.hurst == pytest.approx(H, abs=0.05)
    q_mid = math.sqrt(band[0] * band[1])  # C0 alone is ill-conditioned (intercept at q = 1 rad/m)
    assert fit.C(q_mid) == pytest.approx(float(truth.C(q_mid)), rel=0.1)


def test_profiles_have_the_variance_and_slope_of_the_surface():
    """Isotropy: a line scan has the 2D h_rms^2 and half the 2D mean square slope (all modes below the
    profile's Nyquist wavevector: a band in q_x is not a band in |q|)."""
    truth = surfaces.SelfAffine(hurst=0.7, q0=2e3, q1=1e5, hrms=1e-4, qL=2e2)
    ps = surfaces.synthesize_profiles(truth, n_profiles=16, n=4096, length=2 * math.pi / 2e2, seed=2,
                                      random_amplitude=False)
    p1 = ps.psd()
    assert p1.q_r > truth.q1
    assert surfaces.rq(ps) == pytest.approx(truth.hrms(), rel=0.03)
    assert surfaces.rms_slope(p1) == pytest.approx(truth.rms_slope() / math.sqrt(2), rel=0.03)
    # Parseval: the log-binned 1D PSD integrates to the mean square height of the (mean-detrended) profiles
    assert surfaces.rq(p1) == pytest.approx(surfaces.rq(ps), rel=1e-9)


def test_synthesis_is_seeded():
    s = surfaces.example_road().with_cutoff(q1=1e5)
    a = surfaces.synthesize_map(s, 64, seed=3)
    b = surfaces.synthesize_map(s, 64, seed=3)
    c = surfaces.synthesize_map(s, 64, seed=4)
    np.testing.assert_array_equal(a.z, b.z)
    assert not np.allclose(a.z, c.z)
    assert a.periodic and a.size[0] == pytest.approx(0.1)


def test_height_difference_correlation_matches_psd_and_fit():
    """C_z(lambda) = 4 int_0^inf C1D(q) (1 - cos q lambda) dq (quadrature), and Klüppel's fit recovers H and
    the plateau 2 h_rms^2."""
    truth = surfaces.SelfAffine(hurst=0.7, q0=2e3, q1=1e6, hrms=1e-4, qL=1e2)
    ps = surfaces.synthesize_profiles(truth, n_profiles=8, n=2**14, seed=9)
    h = surfaces.hdc(ps, n_lags=30)
    qs = np.geomspace(truth.qL * 1.0001, truth.q1 * 0.9999, 3000)
    p1 = surfaces.PSD1D.from_isotropic(truth, q=qs)
    for lag in h.lag[[3, 10, 18]]:
        f = lambda t: 4 * math.exp(t) * float(p1.C(math.exp(t))) * (1 - math.cos(math.exp(t) * lag))  # noqa: E731
        expected = integrate.quad(f, math.log(qs[0]), math.log(qs[-1]), limit=400)[0]
        assert float(np.interp(lag, h.lag, h.C_z)) == pytest.approx(expected, rel=0.15)
    fit = surfaces.fit_hdc(h, lag_max=0.02)
    assert fit.hurst == pytest.approx(0.7, abs=0.1)
    assert fit.xi_perp == pytest.approx(math.sqrt(2) * truth.hrms(), rel=0.2)
    assert 0.1 / truth.q0 < fit.xi_par < 10 / truth.q0


def test_example_road_is_documented_and_road_like():
    s = surfaces.example_road()
    assert isinstance(s, surfaces.SelfAffine)
    assert s.hurst == pytest.approx(0.8)
    assert 1e6 <= s.q1 <= 1e7
    assert 100e-6 <= s.hrms() <= 1e-3
    assert s.qL == pytest.approx(2 * math.pi / 0.1)
    assert 2 * math.pi / 10e-3 <= s.q0 <= 2 * math.pi / 2e-3
    assert "not a measurement" in surfaces.example_road.__doc__
    assert surfaces.example_road.__citations__
