"""Specification of the PSD conventions and conversions of :mod:`surfaces` (docs/conventions.md, issue 3).

Reference numbers are independent of the code under test: closed forms (Gamma functions), adaptive
quadrature (scipy.integrate.quad on the defining integrals) and the discrete Parseval identity.
"""

import math
import os

import numpy as np
import pytest
from scipy import integrate, special

import surfaces
from surfaces.spectra import periodogram_1d


def _abel_forward_quad(s, q):
    """C1D(q) = 2 int_q^inf k C(k) / sqrt(k^2 - q^2) dk by adaptive quadrature, split at the kinks of C.

    The (k - q)^-1/2 end point is handled by quad's algebraic weight; smooth pieces are integrated in
    ln k (power laws spanning decades defeat quad in k)."""
    edges = sorted({max(q, s.qL), *(e for e in (s.q0,) if e > q), s.q1})
    total = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        if a == q:
            total += integrate.quad(lambda k: 2 * k * s.C(k) / math.sqrt(k + q), a, b, weight="alg",
                                    wvar=(-0.5, 0.0), limit=400)[0]
        else:
            def in_log(t):
                return 2 * math.exp(2 * t) * s.C(math.exp(t)) / math.sqrt(math.exp(2 * t) - q * q)

            total += integrate.quad(in_log, math.log(a), math.log(b), limit=400)[0]
    return total


SURFACE = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=1e-4, qL=1e2)


@pytest.mark.parametrize("q", [50.0, 150.0, 999.0, 3e3, 1e5, 9e5])
def test_abel_forward_matches_quadrature(q):
    """The forward Abel transform (1D PSD of line scans) of a rolled-off self-affine PSD."""
    expected = _abel_forward_quad(SURFACE, q)
    assert surfaces.abel_forward(SURFACE, np.array([q]))[0] == pytest.approx(expected, rel=1e-6)


def test_abel_pair_preserves_variance():
    """h_rms^2 = int C1D dq (two-sided) = 2 pi int q C dq."""
    p1 = surfaces.PSD1D.from_isotropic(SURFACE, q=np.geomspace(1.0, SURFACE.q1 * 0.999999, 4000))
    var_1d = p1.moment(0)
    assert var_1d == pytest.approx(SURFACE.hrms() ** 2, rel=2e-3)


@pytest.mark.parametrize("H", [0.3, 0.5, 0.8, 0.95])
def test_gamma_form_and_inverse_abel_agree_on_pure_power_law(H):
    """Must show: both conversions of a pure power law C1D = A q^-(1+2H) agree to 1 %."""
    q = np.geomspace(1e2, 1e5, 61)
    p1 = surfaces.PSD1D(q, 3e-12 * q ** (-(1 + 2 * H)), q_r=q[-1])
    abel = p1.to_isotropic("abel")
    gamma = p1.to_isotropic("gamma")
    assert gamma.hurst == pytest.approx(H, abs=1e-9)
    assert np.max(np.abs(abel.C_values / gamma.C_values - 1)) < 0.01
    # and both equal the closed form Gamma(1+H)/(sqrt(pi) Gamma(H+1/2)) C1D/q
    closed = special.gamma(1 + H) / (math.sqrt(math.pi) * special.gamma(H + 0.5)) * p1.C_values / q
    np.testing.assert_allclose(gamma.C_values, closed, rtol=1e-12)


def test_gamma_factor_published_shortcuts():
    """docs/conventions.md: C = C1D/(2q) is exact at H = 0.5 and 15 % low at H = 0.8."""
    assert surfaces.gamma_factor(0.5) == pytest.approx(0.5, rel=1e-12)
    assert 0.5 / surfaces.gamma_factor(0.8) == pytest.approx(0.854, abs=0.002)


def test_inverse_abel_of_exact_1d_psd_recovers_rolled_off_surface():
    """Forward (quadrature-checked) then inverse: the 2D PSD with its roll-off comes back to 1 %."""
    q = np.geomspace(SURFACE.qL * 1.01, SURFACE.q1 / 10, 120)
    p1 = surfaces.PSD1D.from_isotropic(SURFACE, q=q)
    back = p1.to_isotropic(smoothing=0.0, hurst=0.8)
    inside = (back.q > 1.5 * SURFACE.qL) & (back.q < SURFACE.q1 / 30)
    ratio = back.C_values[inside] / SURFACE.C(back.q[inside])
    near_kink = np.abs(np.log(back.q[inside] / SURFACE.q0)) < 0.1  # C has a corner at q0: the spline rounds it
    assert np.max(np.abs(ratio[~near_kink] - 1)) < 0.005
    assert np.max(np.abs(ratio - 1)) < 0.02


def test_periodogram_parseval():
    """Discrete Parseval: the two-sided 1D PSD integrates to the variance (no window, zero mean)."""
    rng = np.random.default_rng(0)
    z = rng.standard_normal(1001)
    z -= z.mean()
    dx = 1e-4
    q, C = periodogram_1d(z, dx, None)
    dq = 2 * math.pi / (z.size * dx)
    assert 2 * np.sum(C) * dq == pytest.approx(np.mean(z**2), rel=1e-12)


def test_selfaffine_fit_on_exact_table():
    fit = surfaces.fit_self_affine(SURFACE, q_min=2e3, q_max=5e5)
    assert fit.hurst == pytest.approx(0.8, abs=1e-6)
    assert fit.C0 == pytest.approx(SURFACE.C0, rel=1e-5)
    assert fit.kind == "isotropic"


def test_rolloff_fit_on_exact_table():
    fit = surfaces.fit_rolloff(SURFACE.tabulate(32))
    assert fit.q0 == pytest.approx(SURFACE.q0, rel=0.02)
    assert fit.hurst == pytest.approx(0.8, abs=0.01)
    assert fit.model(q1=SURFACE.q1).C(3e4) == pytest.approx(SURFACE.C(3e4), rel=0.05)


def test_rolloff_fit_on_1d_psd_reports_isotropic_prefactor():
    q = np.geomspace(SURFACE.qL * 1.01, SURFACE.q1 / 10, 100)
    fit = surfaces.fit_rolloff(surfaces.PSD1D.from_isotropic(SURFACE, q=q))
    assert fit.kind == "1d"
    assert fit.hurst == pytest.approx(0.8, abs=0.03)
    assert fit.q0 == pytest.approx(SURFACE.q0, rel=0.35)  # C1D rolls off more gently than C


def test_extrapolate_tail_and_flags():
    table = SURFACE.with_cutoff(q1=1e5).tabulate(32)
    measured = surfaces.PSD(table.q, table.C_values, q_r=5e4, source="test")
    ext = measured.extrapolate(1e7)
    assert ext.extrapolated and ext.q_r == pytest.approx(5e4)
    assert ext.q_range[1] == pytest.approx(1e7)
    assert ext.hurst == pytest.approx(0.8, abs=1e-6)
    np.testing.assert_allclose(ext.C([2e5, 1e6]), SURFACE.C([2e5, 1e6]), rtol=1e-6)
    assert ext.cutoffs.extrapolated and ext.cutoffs.q_r == pytest.approx(5e4)
    # cutting the table below q_r leaves only measured data
    assert not ext.with_cutoff(q1=4e4).extrapolated
    # a given H is used as is
    steep = measured.extrapolate(1e6, hurst=0.5)
    assert steep.C(1e6) / steep.C(5e4) == pytest.approx((1e6 / 5e4) ** (-3.0), rel=1e-9)


def test_extrapolate_fits_the_tail_above_a_rolloff_inside_the_last_decade():
    """A short scan whose roll-off lies in its last decade (a fine sandpaper measured to 4e4 rad/m, roll-off at
    2.9e4): the last decade is mostly the plateau, whose log-log line is not the tail's power law. With the
    roll-off recorded, H comes from the part above it; without, from the roll-off law fitted on the table. Both
    against the closed form C = C0 (q/q0)^(-2(1+H)), H = 0.8."""
    H, q0, C0 = 0.8, 2.9e4, 1e-22
    q = np.geomspace(2.4e3, 4e4, 22)
    C = C0 * np.where(q < q0, 1.0, (q / q0) ** (-2 * (1 + H)))
    truth = C0 * (np.array([1e5, 6e5]) / q0) ** (-2 * (1 + H))
    with pytest.raises(surfaces.InputError, match="not self-affine"):   # the old default band
        surfaces.PSD(q, C).extrapolate(6e5, fit_band=(4e3, 4e4))
    for psd in (surfaces.PSD(q, C, q_rolloff=q0), surfaces.PSD(q, C)):
        ext = psd.extrapolate(6e5)
        assert ext.hurst == pytest.approx(H, abs=1e-6)
        np.testing.assert_allclose(ext.C([1e5, 6e5]), truth, rtol=1e-5)
    # a table with no power law at all is still refused
    with pytest.raises(surfaces.InputError, match="not self-affine"):
        surfaces.PSD(q, np.full(q.size, C0)).extrapolate(6e5)



def test_extrapolate_takes_the_recorded_hurst_where_the_table_cannot_give_one():
    """A scan whose limit lies just past the roll-off (a fine sandpaper, roll-off at 3e4 rad/m, measured to
    3.17e4): one point of the power law past the roll-off, too few for any fit. The exponent the table records (here
    from the model that made it, as a file's metadata would) continues the tail; the closed form
    C = C0 (q/q0)^(-2(1+H)) is the reference. Without a recorded exponent the extrapolation is refused: a roll-off
    law fitted to the table fits its one point past the break exactly with any slope (a break anywhere between the
    plateau and that point), so no exponent comes from it (the one the optimizer stopped at was 1.009 with one scipy
    and past 1.05 with the next); where the table can give H, its own fit wins over a recorded value."""
    H, q0, C0 = 0.71, 3.0e4, 1e-22
    q = np.append(np.geomspace(2.0e3, q0, 20), 3.17e4)
    C = C0 * np.where(q < q0, 1.0, (q / q0) ** (-2 * (1 + H)))
    truth = C0 * (np.array([1e5, 4.8e5]) / q0) ** (-2 * (1 + H))
    ext = surfaces.PSD(q, C, q_rolloff=q0, hurst=H).extrapolate(4.8e5)
    assert ext.hurst == pytest.approx(H, abs=1e-12)
    np.testing.assert_allclose(ext.C([1e5, 4.8e5]), truth, rtol=1e-9)
    with pytest.raises(surfaces.InputError, match=r"1 point\(s\) of the band above the fitted roll-off.*give hurst="):
        surfaces.PSD(q, C, q_rolloff=q0).extrapolate(4.8e5)
    # a table that holds a decade of the power law (H = 0.8) keeps its own exponent over a recorded 0.5
    table = SURFACE.with_cutoff(q1=1e5).tabulate(32)
    ext = surfaces.PSD(table.q, table.C_values, q_r=5e4, hurst=0.5).extrapolate(1e6)
    assert ext.hurst == pytest.approx(0.8, abs=1e-6)

def test_selfaffine_carries_cutoffs():
    c = SURFACE.cutoffs
    assert (c.qL, c.q0, c.q_r, c.q1, c.extrapolated) == (1e2, 1e3, None, 1e6, False)
    assert "q1=1e+06" in c.describe()


def test_psd_csv_round_trip(tmp_path):
    psd = surfaces.PSD([1e3, 1e4, 1e5], [1e-20, 1e-23, 1e-26], q_r=5e4, extrapolated=True, source="scan A",
                       qL=500.0, q_rolloff=2e3, hurst=0.75)
    path = psd.to_csv(tmp_path / "out" / "psd.csv")
    assert sorted(os.listdir(path.parent)) == ["psd.csv"]  # atomic: no temporary file left behind
    back = surfaces.read_psd(path)
    np.testing.assert_array_equal(back.q, psd.q)
    np.testing.assert_array_equal(back.C_values, psd.C_values)
    assert (back.q_r, back.extrapolated, back.qL, back.q_rolloff, back.hurst, back.source) == \
        (5e4, True, 500.0, 2e3, 0.75, "scan A")


def test_read_psd_plain_table_with_comments(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text("# measured\nq,C\n100,1e-18\n# mid comment\n1000,1e-21\n")
    psd = surfaces.read_psd(path)
    assert psd.q_range == (100.0, 1000.0) and not psd.extrapolated and psd.q_r is None


@pytest.mark.parametrize("text, expect", [
    ("", "empty"),
    ("q\n1\n2\n", "column 'C'"),
    ("q,C\n1,1e-20\n", "at least 2 data rows"),
    ("q,C\n1,1e-20\n2,abc\n", "line 3, column C"),
    ("q,C\n2,1e-20\n1,1e-21\n", "line 3, column q"),
    ("q,C\n1,1e-20\n2,-1\n", "line 3, column C"),
])
def test_read_psd_bad_input(tmp_path, text, expect):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(surfaces.InputError, match="bad.csv") as err:
        surfaces.read_psd(path)
    assert expect in str(err.value)
    assert isinstance(err.value, ValueError)


def test_reliability_limit_tip_radius_on_a_sinusoid():
    """Tip criterion: the stencil curvature min_x [h(x+l) - 2h(x) + h(x-l)]/l^2 of a sinusoid a sin(kx) is
    -a (2 - 2 cos kl)/l^2; q_r = 2 pi / l_c where it reaches -s/R (closed form solved with brentq)."""
    a, lam, dx = 1e-6, 50e-6, 0.05e-6
    k = 2 * math.pi / lam
    x = np.arange(0, 2e-3, dx)
    ps = surfaces.profiles_from_array(a * np.sin(k * x), dx=dx)
    R = 1.0 / (a * k * k)  # the tip just matches the peak curvature: the criterion s = 1/2 bites
    from scipy.optimize import brentq
    l_c = brentq(lambda ell: a * (2 - 2 * math.cos(k * ell)) / ell**2 - 0.5 / R, 1e-9, lam / 2)
    q_r = ps.reliability_limit(tip_radius=R)
    assert 2 * math.pi / q_r == pytest.approx(l_c, abs=1.01 * dx)
    assert surfaces.reliability_limit(dx=1e-3) == pytest.approx(math.pi / 1e-3)
    assert surfaces.reliability_limit(dx=1e-3, lateral_resolution=4e-3) == pytest.approx(math.pi / 4e-3)
    with pytest.raises(surfaces.InputError, match="profiles"):
        surfaces.reliability_limit(tip_radius=1e-6)


def test_band_limited_metrics_of_selfaffine():
    """Rq and rms slope on a band equal the closed-form moments of the power law."""
    H, C0 = SURFACE.hurst, SURFACE.C0
    qa, qb = 2e3, 2e5
    m1 = 2 * math.pi * C0 * (qb ** (-2 * H) - qa ** (-2 * H)) / (-2 * H)
    m3 = 2 * math.pi * C0 * (qb ** (2 - 2 * H) - qa ** (2 - 2 * H)) / (2 - 2 * H)
    assert surfaces.rq(SURFACE, qa, qb) == pytest.approx(math.sqrt(m1), rel=1e-6)
    assert surfaces.rms_slope(SURFACE, qa, qb) == pytest.approx(math.sqrt(m3), rel=1e-6)
    assert surfaces.rq(SURFACE) == pytest.approx(SURFACE.hrms(), rel=1e-9)


def test_noise_floor_does_not_stop_the_conversion():
    """A flat instrument-noise floor in the last decade: the tail H is clamped with a warning, C stays > 0,
    and the self-affine part below the floor is unchanged."""
    q = np.geomspace(1e2, 1e5, 61)
    p1 = surfaces.PSD1D(q, 1e-12 * q**-2.6 + 1e-21, q_r=q[-1])
    with pytest.warns(UserWarning, match="not self-affine"):
        iso = p1.to_isotropic()
    assert np.all(iso.C_values > 0)
    clean = surfaces.PSD1D(q, 1e-12 * q**-2.6, q_r=q[-1]).to_isotropic()
    low = q < 1e3
    np.testing.assert_allclose(iso.C_values[low], clean.C_values[low], rtol=0.05)
