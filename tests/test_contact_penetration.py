"""Specification of the penetration depths (``persson.contact.separation.penetration_depth``) on a Gaussian surface.

Both definitions take the hard surface's heights as Gaussian (standard deviation h_rms) and the rubber's mean
surface at u_bar above their mean plane. "persson": the asperity tops at n_sigma h_rms, depth n_sigma h_rms - u.
"kluppel": the mean excess height of the asperities reaching above the rubber, h F1(t)/F0(t) with
Greenwood & Williamson's F_n(t) = int_t^inf (s - t)^n phi(s) ds, t = u/h (Kluppel & Heinrich 2000). Checked here
against quadrature of those integrals, a Monte-Carlo Gaussian surface and the tail asymptotics.
"""

import math
import warnings

import numpy as np
import pytest
from scipy import integrate, stats

import surfaces
from persson import InputError
from persson.contact import contact
from persson.contact.separation import penetration_depth, separation_decay_length

H_RMS = 0.1e-3


def test_persson_depth_is_three_rms_heights_minus_the_separation_bounded_by_the_load_weighted_depth():
    u = np.array([0.0, 0.05e-3, 0.2e-3, 0.5e-3])
    np.testing.assert_allclose(penetration_depth(u, H_RMS), np.maximum(3 * H_RMS - u, 0.0), rtol=0, atol=0)
    e = np.full(4, 0.04e-3)  # U_el / (A0 sigma0)
    np.testing.assert_allclose(penetration_depth(u, H_RMS, energy_per_load=e), np.maximum(3 * H_RMS - u, 2 * e),
                               rtol=0, atol=0)


# --- the load-weighted depth 2 U_el / sigma0 (Clapeyron), the default ----------------------------------------
GFMD_SURFACE = surfaces.SelfAffine(hurst=0.8, q0=1e4, q1=1e6, hrms=6e-6)


def _yang_persson_energy_by_quadrature(p, Es=1.0, gamma=0.5):
    """U_el/A0 = (pi E*/2) int q^2 C P S dq, P = erf(1/(2 sqrt G)), G = (pi/4)(E*/p)^2 int q^3 C dq, by adaptive
    quadrature in ln q of the closed-form power law (no code of the package)."""
    H, q0, q1, h = 0.8, 1e4, 1e6, 6e-6
    C0 = h**2 * H / math.pi / (q0 ** (-2 * H) - q1 ** (-2 * H))

    def f(lnq):
        q = math.exp(lnq)
        G = math.pi / 4 * (Es / p) ** 2 * C0 * (q ** (2 - 2 * H) - q0 ** (2 - 2 * H)) / (2 - 2 * H)
        P = math.erf(0.5 / math.sqrt(G)) if G > 0 else 1.0
        return q**3 * C0 * q ** (-2 - 2 * H) * P * (gamma + (1 - gamma) * P * P)

    pts = np.log(np.geomspace(q0, q1, 41))
    with warnings.catch_warnings():  # where P drops from 1 within a tiny range of q, quad reports its roundoff
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        total = sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-9, limit=200)[0] for a, b in zip(pts[:-1], pts[1:]))
    return math.pi * Es / 2 * total


def test_load_weighted_depth_is_twice_the_energy_per_load_of_an_independent_quadrature():
    p = np.array([1e-6, 1e-3, 0.05, 0.4])
    r = contact(GFMD_SURFACE, 1.0, p, penetration="load-weighted")
    assert r.penetration == "load-weighted"
    ref = np.array([2 * _yang_persson_energy_by_quadrature(x) / x for x in p])
    np.testing.assert_allclose(r.penetration_depth, ref, rtol=2e-5)


def test_default_depth_stays_positive_and_continuous_where_the_rubber_is_above_three_rms_heights():
    # below p/E* = 1e-4 u_bar > 3 h_rms (A/A0 = 6e-4): 3 h_rms - u_bar is negative, and the depth of the highest
    # asperities is the load-weighted depth, which tends smoothly to 2 u0 (sigma0 ~ exp(-u_bar/u0),
    # U_el = u0 sigma0)
    p = np.concatenate([np.geomspace(1e-9, 1e-5, 5), np.geomspace(1.08e-5, 1e-3, 60)])
    r = contact(GFMD_SURFACE, 1.0, p)
    low = r.mean_separation > 3 * 6e-6
    assert low.sum() >= 8 and np.all(r.contact_area > 0)
    d = r.penetration_depth
    lw = r.penetration_depths["load-weighted"]
    np.testing.assert_array_equal(d[low], lw[low])
    np.testing.assert_array_equal(d, np.maximum(3 * 6e-6 - r.mean_separation, lw))
    # positive, rising with the load, and without a jump where the two bounds cross (p ratio 1.08 per step)
    assert np.all(d > 0) and np.all(np.diff(d) >= 0) and np.max(np.diff(np.log(d[5:]))) < 0.06
    q = np.geomspace(*GFMD_SURFACE.q_range, 2001)
    u0 = separation_decay_length(q, GFMD_SURFACE.C(q), 0.5)
    assert d[0] == pytest.approx(2 * u0, rel=2e-3)


def test_friction_result_reports_the_load_weighted_depth_of_the_contact_module():
    import materials
    import persson

    road = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=H_RMS, qL=2 * math.pi / 0.1)
    tread = materials.example_tread()
    p = np.array([0.3e6, 0.8e6])
    r = contact(road, tread, p, speed=1.0, temperature=20.0)
    f = persson.Model(road, tread).friction(np.full(2, 1.0), temperature=20.0, pressure=p)
    np.testing.assert_allclose(f.penetration_depth, r.penetration_depths["persson"], rtol=1e-12)
    assert np.all(r.penetration_depths["persson"] >= r.penetration_depths["load-weighted"])
    np.testing.assert_allclose(r.penetration_depths["load-weighted"], 2 * r.elastic_energy / p, rtol=1e-12)


@pytest.mark.parametrize("n_sigma", [1.0, 2.5, 3.719])  # 3.719: the 99.99 % quantile
def test_persson_depth_puts_the_tops_at_the_chosen_quantile(n_sigma):
    u = 0.07e-3
    d = penetration_depth(u, H_RMS, definition="persson", n_sigma=n_sigma)
    top = u + d
    # the tops lie at the height that a fraction Q(n_sigma) of a Gaussian surface exceeds
    assert stats.norm.sf(top / H_RMS) == pytest.approx(stats.norm.sf(n_sigma), rel=1e-12)


@pytest.mark.parametrize("t", [0.0, 0.3, 1.0, 2.5, 6.0])
def test_kluppel_depth_is_the_ratio_F1_over_F0_of_a_gaussian(t):
    F0 = integrate.quad(lambda s: stats.norm.pdf(s), t, np.inf, epsabs=0, epsrel=1e-12)[0]
    F1 = integrate.quad(lambda s: (s - t) * stats.norm.pdf(s), t, np.inf, epsabs=0, epsrel=1e-12)[0]
    d = penetration_depth(t * H_RMS, H_RMS, definition="kluppel")
    assert d == pytest.approx(H_RMS * F1 / F0, rel=1e-9)


def test_kluppel_depth_on_a_sampled_gaussian_surface():
    rng = np.random.default_rng(15)
    z = rng.normal(0.0, H_RMS, 2_000_000)
    for u in (0.0, 0.05e-3, 0.15e-3):
        excess = z[z > u] - u
        sem = excess.std() / math.sqrt(excess.size)
        assert penetration_depth(u, H_RMS, definition="kluppel") == pytest.approx(excess.mean(), abs=4 * sem)


def test_kluppel_depth_far_above_the_surface_follows_the_mills_ratio():
    # phi(t)/Q(t) - t = 1/t - 2/t^3 + 10/t^5 - 74/t^7 + ... for large t: no underflow, no cancellation
    for t in (20.0, 50.0, 200.0):
        d = penetration_depth(t * H_RMS, H_RMS, definition="kluppel")
        assert d == pytest.approx(H_RMS * (1 / t - 2 / t**3 + 10 / t**5 - 74 / t**7), rel=1e-6)


def test_depths_never_negative_and_kluppel_ignores_n_sigma():
    u = np.linspace(0.0, 1e-3, 11)
    assert np.all(penetration_depth(u, H_RMS, n_sigma=2.0) >= 0)
    np.testing.assert_array_equal(penetration_depth(u, H_RMS, definition="kluppel", n_sigma=1.0),
                                  penetration_depth(u, H_RMS, definition="kluppel", n_sigma=5.0))


def test_contact_reports_both_definitions_and_the_chosen_one():
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=H_RMS)
    r = contact(s, 10e6, np.array([0.1e6, 0.5e6]), penetration="kluppel", n_sigma=2.0)
    np.testing.assert_allclose(r.penetration_depth, r.penetration_depths["kluppel"])
    np.testing.assert_allclose(r.penetration_depths["persson"],
                               np.maximum(2.0 * H_RMS - r.mean_separation, r.penetration_depths["load-weighted"]))
    np.testing.assert_allclose(r.penetration_depths["kluppel"],
                               penetration_depth(r.mean_separation, H_RMS, definition="kluppel"))
    assert "10.5254/1.3547607" in r.citations


@pytest.mark.parametrize("kwargs, word", [(dict(definition="gw"), "definition"), (dict(n_sigma=-1.0), "n_sigma"),
                                          (dict(hrms=0.0), "hrms")])
def test_bad_arguments_are_named(kwargs, word):
    args = dict(hrms=H_RMS)
    args.update(kwargs)
    with pytest.raises(InputError, match=word):
        penetration_depth(1e-5, **args)
    with pytest.raises(InputError, match="energy_per_load"):
        penetration_depth(1e-5, H_RMS, definition="load-weighted")


# --- docs/contact.md, "Can the tire magnitudes be reproduced?" ------------------------------------------------
def test_the_documented_road_table_and_its_conclusions():
    import materials

    road = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=H_RMS, qL=2 * math.pi / 0.1)
    tread = materials.example_tread()
    p = np.array([0.3e6, 0.8e6])
    # rows of the table (mm): u_bar, persson, kluppel, excited layer at 0.3 and 0.8 MPa
    documented = {(20.0, 1.0): ([0.039, 0.011], [0.26, 0.29], [0.067, 0.076], [0.042, 0.031], [0.106, 0.077]),
                  (0.0, 30.0): ([0.154, 0.101], [0.15, 0.20], [0.043, 0.052], [0.142, 0.135], [0.135, 0.129])}
    q = np.geomspace(*road.q_range, 2001)
    u0 = separation_decay_length(q, road.C(q), 0.5)
    assert u0 * 1e3 == pytest.approx(0.063, abs=0.0005)
    for (T, v), (u, dp, dk, layer, dl) in documented.items():
        r = contact(road, tread, p, speed=v, temperature=T)
        np.testing.assert_allclose(r.mean_separation * 1e3, u, rtol=0.05)
        np.testing.assert_allclose(r.penetration_depths["persson"] * 1e3, dp, rtol=0.05)
        np.testing.assert_allclose(r.penetration_depths["kluppel"] * 1e3, dk, rtol=0.05)
        np.testing.assert_allclose(r.excited_layer_thickness * 1e3, layer, rtol=0.05)
        np.testing.assert_allclose(r.penetration_depths["load-weighted"] * 1e3, dl, rtol=0.05)
        # the conclusions: the persson depth rises by at most u0 ln(8/3); the kluppel depth by < 25 %
        rise = np.diff(r.penetration_depths["persson"])[0]
        assert 0 < rise <= u0 * math.log(8 / 3)
        assert r.penetration_depths["kluppel"][1] / r.penetration_depths["kluppel"][0] < 1.25
