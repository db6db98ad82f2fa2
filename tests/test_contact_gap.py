"""Specification of the gap and energy corrections (``gap_correction``) of ``persson.contact`` against GFMD mean gaps.

GFMD reference data: Green's function molecular dynamics by Y. Zhou, published with Xu, Zhu, Xiao & Zhou, "A new
fudge factor for Persson's theory of purely normal elastic rough surface contact", Tribol. Lett. 72 (2024),
doi:10.1007/s11249-024-01838-4, public repository github.com/xylcsi/PerssonModelFudgeFactor (commit d3341a6):
Data/GFMD_final_results_low_from_Zhou.mat and ..._high_from_Zhou.mat hold the distribution of interfacial gaps
(gap_GFMD_*, in units of h_rms; PDF_GFMD_*, normalised to the non-contact fraction 1 - A/A0) at 12 loads. The
mean gaps below are the first moments of those distributions, integral of g PDF(g) dg by the trapezoid rule on
their 64-node grids, computed for this file. Surface as in test_contact_corrections.py (E* = 1 Pa, q from 1e4 to
1e6 rad/m without roll-off, H = 0.8, h_rms = 6 um).
"""

import math

import numpy as np
import pytest
from scipy import special

import surfaces
from persson.contact import contact, corrections, separation

HRMS = 6e-6
SURFACE = surfaces.SelfAffine(hurst=0.8, q0=1e4, q1=1e6, hrms=HRMS)
GAP_P = np.array([1.00e-04, 1.00e-03, 5.00e-03, 1.00e-02, 1.50e-02, 2.50e-02, 4.00e-02, 6.50e-02, 8.60e-02,
                  1.13e-01, 1.47e-01, 1.91e-01])
GFMD_GAP = HRMS * np.array([2.629041, 1.882970, 1.180626, 0.853967, 0.664398, 0.439821, 0.264415, 0.127707,
                            0.073888, 0.038362, 0.017517, 0.006483])
LOW = slice(0, 6)   # p/E* <= 0.025: the loads the "gfmd-gap" weight was fitted to


@pytest.fixture(scope="module")
def gaps():
    """u_bar / u_bar(GFMD) - 1 of every gap law at the GFMD loads (xu2024 area, gamma = 0.5)."""
    return {gap: contact(SURFACE, 1.0, GAP_P, correction="xu2024", gap_correction=gap).mean_separation / GFMD_GAP - 1
            for gap in corrections.GAP_CORRECTIONS}


def test_a_corrected_area_followed_by_the_energy_worsens_the_small_load_gap(gaps):
    # the numbers: +27 % uncorrected, +55 % corrected at p/E* = 1e-4 (+29 % and +57 % from the gap
    # distributions' first moments)
    assert gaps["persson"][0] == pytest.approx(0.294, abs=0.01)
    assert gaps["area"][0] == pytest.approx(0.568, abs=0.01)
    assert np.all(gaps["area"][:4] > gaps["persson"][:4])


def test_the_gfmd_gap_weight_is_the_least_squares_fit_to_the_small_load_gfmd_gaps():
    # refit gamma_g independently: Persson's uncorrected energy with gamma = gamma_g is the same weight
    def rms(g):
        u = contact(SURFACE, 1.0, GAP_P[LOW], gamma=g).mean_separation
        return math.sqrt(np.mean(np.log(u / GFMD_GAP[LOW]) ** 2))

    g = corrections.GFMD_GAP_GAMMA
    assert rms(g) < min(rms(g - 0.01), rms(g + 0.01))
    np.testing.assert_allclose(contact(SURFACE, 1.0, GAP_P, gap_correction="gfmd-gap").mean_separation,
                               contact(SURFACE, 1.0, GAP_P, gamma=g).mean_separation, rtol=1e-12)


def test_gfmd_gap_weight_meets_gfmd_at_small_loads_whatever_the_area_correction(gaps):
    assert np.max(np.abs(gaps["gfmd-gap"][LOW])) < 0.08
    a = contact(SURFACE, 1.0, GAP_P[LOW], correction="wang-muser", gap_correction="gfmd-gap").mean_separation
    np.testing.assert_allclose(a, GFMD_GAP[LOW] * (1 + gaps["gfmd-gap"][LOW]), rtol=1e-12)
    # its decay length u0 is gamma_g / gamma times Persson's
    q = np.geomspace(*SURFACE.q_range, 1001)
    u0 = separation.separation_decay_length(q, SURFACE.C(q), 0.5, gap_correction="gfmd-gap")
    assert u0 == pytest.approx(separation.separation_decay_length(q, SURFACE.C(q), 0.5)
                               * corrections.GFMD_GAP_GAMMA / 0.5, rel=1e-12)


def test_energy_weights_are_their_published_formulas():
    G = np.array([1e-3, 0.05, 0.3, 2.0, 40.0, 1e6])
    P = special.erf(0.5 / np.sqrt(G))

    def s_wm(a, A):  # Wang & Müser (2017), as implemented by Xu et al. (2024)
        return a - 2 / 9 * A**2 + (11 / 9 - a) * A**4

    gamma = 0.42
    Pxu = corrections.corrected_area(G, "xu2024", gamma)
    np.testing.assert_allclose(corrections.energy_weight(G, "xu2024", gamma, "xu2024-hybrid"), Pxu * s_wm(gamma, Pxu),
                               rtol=1e-5)
    Pwm = corrections.corrected_area(G, "wang-muser", 0.5)
    np.testing.assert_allclose(corrections.energy_weight(G, "wang-muser", 0.5, "area"), Pwm * s_wm(5 / 9, Pwm),
                               rtol=1e-5)
    np.testing.assert_allclose(corrections.energy_weight(G, "yang-persson", 0.5, "persson"),
                               P * (0.5 + 0.5 * P**2), rtol=1e-5)
    g = corrections.GFMD_GAP_GAMMA
    np.testing.assert_allclose(corrections.energy_weight(G, None, 0.5, "gfmd-gap"), P * (g + (1 - g) * P**2),
                               rtol=1e-5)


@pytest.mark.parametrize("correction, gap", [("xu2024", "xu2024-hybrid"), ("wang-muser", "area"),
                                             ("yang-persson", "gfmd-gap")])
def test_separation_is_the_pressure_integral_of_the_energy_for_every_gap_law(correction, gap):
    # u_bar(p) = int_p^inf (dU/dp') dp'/p' (Persson 2007): differences between two loads, by Gauss-Legendre in ln p
    x, w = np.polynomial.legendre.leggauss(24)
    a, b = math.log(2e-3), math.log(2e-2)
    lnp = 0.5 * (a + b) + 0.5 * (b - a) * x
    h = 1e-4
    U = [contact(SURFACE, 1.0, np.exp(lnp + d), correction=correction, gap_correction=gap).elastic_energy
         for d in (-h, h)]
    dU_dlnp = (U[1] - U[0]) / (2 * h)
    integral = 0.5 * (b - a) * np.sum(w * dU_dlnp / np.exp(lnp))
    u = contact(SURFACE, 1.0, np.exp([a, b]), correction=correction, gap_correction=gap).mean_separation
    assert u[0] - u[1] == pytest.approx(integral, rel=2e-4)


def test_gap_correction_is_reported_and_cited_and_bad_names_fail():
    from persson import InputError

    r = contact(SURFACE, 1.0, 0.01, correction="xu2024", gap_correction="xu2024-hybrid", gamma=0.42)
    assert r.gap_correction == "xu2024-hybrid" and "wang-muser:tribol-lett-65-2017" in r.citations
    assert contact(SURFACE, 1.0, 0.01, gap_correction=None).gap_correction == "persson"
    # a corrected area with the gap following it says what that costs
    assert any("gfmd-gap" in n for n in contact(SURFACE, 1.0, 0.01, correction="xu2024").notes)
    assert not contact(SURFACE, 1.0, 0.01, correction="xu2024", gap_correction="gfmd-gap").notes
    with pytest.raises(InputError, match="gap_correction"):
        contact(SURFACE, 1.0, 0.01, gap_correction="bem")
