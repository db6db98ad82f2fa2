"""Anisotropic surfaces: the 2-D PSD of a height map, the unidirectional limit, the stretched surface and scans
along and across the ridges. Persson's convention throughout: h_rms^2 = int d^2q C(q), the angular mean
C(q) = (1/2 pi) int C(q, phi) dphi is an isotropic PSD of the same h_rms and rms slope."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import simpson

import frictionerrors
import surfaces
from surfaces.spectra import log_bin

BASE = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=10e-6)
PLATEAU = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=10e-6, qL=1e2)


def synthesize(psd, n, length, seed):
    """A periodic map whose modes have the 2-D PSD ``psd.C2d`` (Gaussian random field, Persson's convention)."""
    dx = length / n
    q = 2 * np.pi * np.fft.fftfreq(n, dx)
    QX, QY = np.meshgrid(q, q)
    C = psd.C2d(QX, QY)
    C[0, 0] = 0.0
    W = np.fft.fft2(np.random.default_rng(seed).standard_normal((n, n)))
    z = np.fft.ifft2(W * np.sqrt(C) * n * (2 * np.pi / length)).real
    return surfaces.HeightMap(z, dx, periodic=True, source=f"synthetic {psd!r}")


def brute_angular_mean(psd, q, n=40_000):
    phi = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    return np.array([np.mean(psd.C_polar(qi, phi)) for qi in np.atleast_1d(q)])


# --- stretched -----------------------------------------------------------------------------------------------
def test_ratio_one_is_the_isotropic_surface():
    s = surfaces.stretched(PLATEAU, ratio=1.0, angle_deg=37.0)
    q = np.geomspace(1e2, 1e6, 17)
    assert np.array_equal(s.C(q), PLATEAU.C(q))
    assert np.array_equal(s.C_polar(q, 0.3 * q / q), PLATEAU.C(q))
    assert s.hrms() == pytest.approx(PLATEAU.hrms(), rel=1e-12)
    assert s.anisotropy().slope_ratio == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize("base", [BASE, PLATEAU, BASE.tabulate(16)], ids=["power law", "with plateau", "table"])
def test_angular_mean_is_the_average_over_the_angles(base):
    s = surfaces.stretched(base, ratio=4.0, angle_deg=25.0)
    q = np.array([1.05e2, 3e2, 9.9e2, 1.2e3, 3.3e4, 9.9e5])
    q = q[(q >= s.q_range[0]) & (q <= s.q_range[1])]
    assert s.C(q) == pytest.approx(brute_angular_mean(s, q), rel=1e-8)
    # and the moments are those of the angular mean: h_rms^2 = int d^2q C = 2 pi int q C dq (Simpson in ln q)
    x = np.linspace(*np.log(s.q_range), 1201)
    assert s.hrms() ** 2 == pytest.approx(2 * np.pi * simpson(np.exp(2 * x) * s.C(np.exp(x)), x=x), rel=1e-5)


def test_stretching_puts_the_ridges_along_the_angle_and_reduces_the_slope_along_them():
    s = surfaces.stretched(BASE, ratio=3.0, angle_deg=30.0)
    a = s.anisotropy()
    assert a.ridge_angle_deg == pytest.approx(30.0, abs=1e-9)
    assert a.steepest_angle_deg == pytest.approx(120.0, abs=1e-9)
    assert 2.5 < a.slope_ratio < 3.0  # 3 without cut-offs; the common circular cut-offs mix the directions
    assert a.rms_slope_steepest**2 + a.rms_slope_ridge**2 == pytest.approx(s.rms_slope() ** 2, rel=1e-9)
    # ridges along 30 and along 210 deg are the same surface
    assert surfaces.stretched(BASE, 3.0, 210.0).C_polar(1e4, 0.4) == pytest.approx(s.C_polar(1e4, 0.4), rel=1e-14)


def test_the_shape_of_a_stretched_power_law_does_not_change_with_q():
    s = surfaces.stretched(BASE, ratio=5.0, angle_deg=0.0)
    phi = np.linspace(0, np.pi, 7)
    w = s.angular_shape(np.array([2e3, 2e5]), np.stack([phi, phi]))
    assert w[0] == pytest.approx(w[1], rel=1e-9)
    assert np.argmax(w[0]) == 3  # largest across the ridges (90 deg)


# --- unidirectional ------------------------------------------------------------------------------------------
class PowerLaw1D:
    """C1D = A q^-(1+2H) on [q0, q1] (two-sided 1-D PSD, m^3)."""

    def __init__(self, A, H, q0, q1):
        self.A, self.H, self.q_range = A, H, (q0, q1)

    def C(self, q):
        q = np.asarray(q, dtype=float)
        return np.where((q >= self.q_range[0]) & (q <= self.q_range[1]), self.A * q ** (-1 - 2 * self.H), 0.0)


def test_unidirectional_psd_has_the_heights_and_slopes_of_its_profiles():
    p = PowerLaw1D(1e-12, 0.8, 1e3, 1e6)
    s = surfaces.unidirectional(p, angle_deg=90.0)
    H, (q0, q1) = p.H, p.q_range
    # h_rms^2 = int over both signs of q of C1D; slope^2 = the same with q^2
    h2 = 2 * p.A * (q0 ** (-2 * H) - q1 ** (-2 * H)) / (2 * H)
    m2 = 2 * p.A * (q1 ** (2 - 2 * H) - q0 ** (2 - 2 * H)) / (2 - 2 * H)
    assert s.hrms() ** 2 == pytest.approx(h2, rel=1e-10)
    assert s.rms_slope() ** 2 == pytest.approx(m2, rel=1e-10)
    assert s.C(2e4) == pytest.approx(p.C(2e4) / (np.pi * 2e4), rel=1e-14)
    a = s.anisotropy()
    assert (a.steepest_angle_deg, a.ridge_angle_deg, a.slope_ratio) == (90.0, 0.0, math.inf)


def test_a_height_map_with_grooves_along_x_gives_the_unidirectional_psd():
    n, dx = 256, 1e-4
    f = np.cumsum(np.random.default_rng(3).standard_normal(n)) * 1e-6
    f -= np.linspace(f[0], f[-1], n)  # periodic: no jump across the edge
    hm = surfaces.HeightMap(np.tile(f[:, None], (1, n)), dx, periodic=True)  # h(x, y) = f(y)
    p2 = hm.psd2d()
    # all the power sits on the line qx = 0: C(q) = C1D(qy) delta(qx)
    assert np.max(p2.C_grid[:, p2.qx != 0]) <= 1e-12 * np.max(p2.C_grid)
    a = p2.anisotropy()
    assert a.ridge_angle_deg == 0.0 and a.steepest_angle_deg == 90.0 and a.slope_ratio > 1e5
    # its angular mean is that of the unidirectional PSD of the scans across the grooves, C1D / (pi q), with the
    # two-sided 1-D periodogram C1D(q_k) = dy |F_k|^2 / (2 pi n) of the groove profile averaged on the same bins
    k = np.arange(1, n // 2)
    c1d = dx * np.abs(np.fft.fft(f)[k]) ** 2 / (2 * np.pi * n)
    q_b, c_b, *_ = log_bin([2 * np.pi * k / (n * dx)], [c1d], 20)
    uni = surfaces.unidirectional(surfaces.PSD1D(q_b, c_b), angle_deg=90.0)
    q = p2.radial.q[(p2.radial.q > 20 * 2 * np.pi / (n * dx)) & (p2.radial.q < 0.5 * np.pi / dx)]
    assert p2.C(q) == pytest.approx(uni.C(q), rel=0.1)  # the annuli's lattice counts, nothing else


# --- the 2-D PSD of a height map -----------------------------------------------------------------------------
@pytest.fixture(scope="module")
def stretched_map():
    s = surfaces.stretched(surfaces.SelfAffine(hurst=0.8, q0=2e3, q1=6e4, hrms=5e-6), ratio=3.0, angle_deg=30.0)
    return s, synthesize(s, 256, 0.02, seed=11)


def test_psd2d_of_a_map_keeps_the_radial_psd_and_finds_the_ridges(stretched_map):
    s, hm = stretched_map
    p2 = hm.psd2d()
    radial = hm.psd()
    assert np.allclose(p2.radial.q, radial.q, rtol=1e-12) and np.allclose(p2.radial.C_values, radial.C_values,
                                                                            rtol=1e-9)
    # Parseval: the modes sum to the mean square height of the map
    dq = 2 * np.pi / 0.02
    assert np.sum(p2.C_grid) * dq * dq == pytest.approx(np.mean((hm.z - hm.z.mean()) ** 2), rel=1e-12)
    a, exact = p2.anisotropy(2e3, 6e4), s.anisotropy(2e3, 6e4)
    assert a.ridge_angle_deg == pytest.approx(30.0, abs=3.0)
    assert a.slope_ratio == pytest.approx(exact.slope_ratio, rel=0.1)
    cut = p2.with_cutoff(q0=3e3, q1=3e4)  # a band of it keeps its angular shape
    assert cut.q_range == (3e3, 3e4) and cut.anisotropy().ridge_angle_deg == pytest.approx(a.ridge_angle_deg, abs=3)
    # the smoothed angular shape has mean 1 and peaks across the ridges
    phi = np.linspace(0, np.pi, 360, endpoint=False)
    w = p2.angular_shape(np.array([1e4]), phi[None, :])[0]
    assert np.mean(w) == pytest.approx(1.0, abs=1e-3)
    assert abs((np.degrees(phi[np.argmax(w)]) - 120.0 + 90) % 180 - 90) < 10


def test_scans_along_and_across_the_ridges_give_the_two_1d_psds(stretched_map):
    s, hm = stretched_map
    # rows run along x, columns along y; rotate the question: ridges along 30 deg, so take a map stretched along x
    s0 = surfaces.stretched(s.base, ratio=3.0, angle_deg=0.0)
    hm0 = synthesize(s0, 256, 0.02, seed=5)
    d = surfaces.directional_psds(across=hm0.columns(), along=hm0.rows(), angle_deg=0.0)
    assert d.slope_ratio() == pytest.approx(s0.anisotropy(*d.band()).slope_ratio, rel=0.15)
    uni = d.unidirectional()
    assert uni.wave_angle_deg == 90.0 and uni.ridge_angle_deg == 0.0
    model = d.stretched()
    assert isinstance(model, surfaces.Stretched) and model.angle_deg == 0.0 and model.ratio == d.slope_ratio()


# --- bad input -----------------------------------------------------------------------------------------------
def test_a_2d_psd_with_negative_values_is_refused_naming_the_cell():
    q = np.linspace(-1e4, 1e4, 9)
    C = np.full((9, 9), 1e-20)
    C[2, 5] = -1e-22
    with pytest.raises(surfaces.InputError, match=r"C must be >= 0.*row 2, column 5"):
        surfaces.PSD2D(q, q, C)
    C[2, 5] = np.nan
    with pytest.raises(surfaces.InputError, match="not finite at row 2, column 5"):
        surfaces.PSD2D(q, q, C)
    with pytest.raises(surfaces.InputError, match="shape"):
        surfaces.PSD2D(q, q[:5], np.ones((9, 9)))


def test_angles_in_radians_warn_and_bad_stretches_are_refused():
    with pytest.warns(frictionerrors.UnitWarning, match="radians.*45 degrees"):
        surfaces.stretched(BASE, 2.0, angle_deg=math.pi / 4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        surfaces.stretched(BASE, 2.0, angle_deg=45.0)  # whole degrees: no warning
    with pytest.raises(surfaces.InputError, match=r"ratio=2.*angle_deg=120"):
        surfaces.stretched(BASE, 0.5, angle_deg=30.0)
    with pytest.raises(surfaces.InputError, match="1-D line-scan PSD"):
        surfaces.unidirectional(BASE)
    with pytest.raises(surfaces.InputError, match="no pointwise"):
        surfaces.unidirectional(PowerLaw1D(1e-12, 0.8, 1e3, 1e6)).C2d(1e4, 0.0)
