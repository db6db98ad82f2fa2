"""Specification of the wet-road friction-speed laws (persson.slip): every law of Do, Marsac & Mosset (2004) fitted
with honest standard errors, their limits, the ranking by information criteria, the Stribeck master curve and the
refusal of bad input.

Reference numbers are independent of the fitting code: synthetic curves from known constants plus Gaussian noise
of known size, closed-form identities between the laws, the Gaussian log-likelihood from scipy.stats, and the
Stribeck curve drawn in H = eta V / p.
"""

import math

import numpy as np
import pytest
from scipy import stats

from persson import slip as ps
from persson.errors import AccuracyWarning, InputError

NOISE = 0.004
V = np.linspace(1.0, 30.0, 24)
# four surfaces (texture depth m, BPN) x six speeds: the least that determines Dijks' six constants
TD = np.repeat([0.4e-3, 0.9e-3, 1.6e-3, 2.5e-3], 6)
BPN = np.repeat([45.0, 70.0, 58.0, 52.0], 6)
VS = np.tile(np.linspace(3.0, 25.0, 6), 4)

LAWS = {  # law -> (function of the rows, true constants, parameters held fixed, noise)
    "piarc": (lambda p: ps.piarc(V, *p), (0.8, 20.0), None, NOISE),
    "do_marsac_mosset": (lambda p: ps.do_marsac_mosset(V, *p), (0.75, 18.0, 2.5, 0.002), None, NOISE),
    "stribeck": (lambda p: ps.stribeck(V, *p), (0.25, 0.8, 12.0, 2.0, 0.003), None, NOISE),
    "gompertz": (lambda p: ps.gompertz(V, *p), (0.8, 3.0, -0.55, 0.2), None, NOISE),
    # five constants for an S: b3 and b4 trade off along a curved valley, linear errors hold at lower noise only
    "la_torre": (lambda p: ps.la_torre(V, *p), (0.25, 0.55, -3.0, 0.2, 1.0), None, 0.001),
    "rado": (lambda p: ps.rado(V, *p), (0.9, 8.0, 1.5, 0.0), {"mu_locked": 0.0}, NOISE),
    "three_zone": (lambda p: ps.three_zone(V, *p), (0.8, 45.0, 60.0), None, NOISE),
    "dijks": (lambda p: ps.dijks(VS, TD, BPN, *p), (0.1, -4e-7, -1.2e-3, 9e-3, -1.08e-4, -3.6e-8), None, NOISE),
    "wet_product": (lambda p: ps.wet_product(VS, TD, BPN, *p), (0.1, 0.009, 0.012, 4e-6), None, NOISE),
}
REPEATS = 8


def fit(law, mu, fixed=None):
    if law in ("dijks", "wet_product"):
        f = ps.fit_dijks if law == "dijks" else ps.fit_wet_product
        return f(VS, mu, mtd=TD, bpn=BPN)
    return ps.fit_speed_law(law, V, mu, fixed=fixed)


@pytest.fixture(scope="module")
def repeated_fits():
    """Each law fitted to noisy copies of its own curve: the z-scores (estimate - truth) / standard error."""
    rng = np.random.default_rng(2004)
    z = {}
    for law, (curve, true, fixed, noise) in LAWS.items():
        clean = curve(true)
        rows = []
        for _ in range(REPEATS):
            r = fit(law, clean + rng.normal(0.0, noise, clean.size), fixed)
            free = [i for i, n in enumerate(r.names) if n not in r.fixed]
            rows.append((r.values[free] - np.asarray(true)[free]) / r.stderr[free])
        z[law] = np.array(rows)
    return z


def test_every_law_recovers_its_constants_within_its_standard_errors(repeated_fits):
    for law, z in repeated_fits.items():
        assert np.all(np.isfinite(z)), law
        assert np.max(np.abs(z)) < 5.0, law  # no fit lost in another basin
        assert abs(np.mean(z)) < 0.8, law  # no bias beyond the scatter


def test_standard_errors_agree_with_the_scatter_of_repeated_fits(repeated_fits):
    # z-scores have unit spread when the reported standard errors match the scatter of the estimates
    spread = {law: float(np.sqrt(np.mean(z**2))) for law, z in repeated_fits.items()}
    for law, s in spread.items():  # a handful of repeats per law: only a factor-two error shows here
        assert 0.5 < s < 1.8, (law, s)
    # pooled over the laws (about 300 z-scores; t-distributed with ~20 degrees of freedom: spread ~1.05)
    pooled = float(np.sqrt(np.mean(np.concatenate([z.ravel() for z in repeated_fits.values()]) ** 2)))
    assert 0.8 < pooled < 1.3, pooled


# ----------------------------------------------------------------------------------------------- limits
def test_modified_exponential_with_alpha_1_and_beta_0_is_piarc():
    assert np.array_equal(ps.do_marsac_mosset(V, 0.8, 20.0, 1.0, 0.0), ps.piarc(V, 0.8, 20.0))
    mu = ps.piarc(V, 0.8, 20.0) + np.random.default_rng(1).normal(0, NOISE, V.size)
    p = ps.fit_piarc(V, mu)
    d = ps.fit_do_marsac_mosset(V, mu, fixed={"alpha": 1.0, "beta": 0.0})
    assert d["Vs"] == pytest.approx(p["Sp"], rel=1e-7) and d.std("Vs") == pytest.approx(p.std("Sp"), rel=1e-4)


def test_stribeck_with_zero_coulomb_friction_is_the_modified_exponential():
    assert np.array_equal(ps.stribeck(V, 0.0, 0.8, 15.0, 2.0, 0.003), ps.do_marsac_mosset(V, 0.8, 15.0, 2.0, 0.003))
    mu = ps.do_marsac_mosset(V, 0.8, 15.0, 2.0, 0.003) + np.random.default_rng(2).normal(0, NOISE, V.size)
    s = ps.fit_stribeck(V, mu, fixed={"mu_c": 0.0})
    d = ps.fit_do_marsac_mosset(V, mu)
    for a, b in (("mu_s", "mu0"), ("Vs", "Vs"), ("alpha", "alpha"), ("beta", "beta")):
        assert s[a] == pytest.approx(d[b], rel=1e-6) and s.std(a) == pytest.approx(d.std(b), rel=1e-3)


def test_closed_forms_of_the_other_laws():
    # Gompertz: plateaus alpha and alpha + gamma, steepest at beta/delta where it has fallen by |gamma|/e
    assert ps.gompertz(1e-9, 0.8, 30.0, -0.5, 2.0) == pytest.approx(0.8)
    assert ps.gompertz(1e3, 0.8, 30.0, -0.5, 2.0) == pytest.approx(0.3)
    assert ps.gompertz(15.0, 0.8, 30.0, -0.5, 2.0) == pytest.approx(0.8 - 0.5 / math.e, rel=1e-12)
    # La Torre: the law is unchanged by (b0, b1, b2, b3) -> (b0 + b1, -b1, -b2, -b3); mu_ref scales it
    assert np.allclose(ps.la_torre(V, 0.3, 0.5, -4, 0.01, 2), ps.la_torre(V, 0.8, -0.5, 4, -0.01, 2), rtol=1e-13)
    assert np.allclose(ps.la_torre(V, 0.3, 0.5, -4, 0.01, 2, mu_ref=0.7), 0.7 * ps.la_torre(V, 0.3, 0.5, -4, 0.01, 2))
    assert ps.la_torre(0.0, 0.3, 0.5, -4.0, 0.01, 2.0) == pytest.approx(0.3 + 0.5 / (1 + math.exp(-4.0)))
    # coefficients published for V in km/h: b3 (m/s) = b3 (km/h) 3.6^b4 gives the same law in m/s
    b3_kmh, b4 = 0.002, 1.3
    assert np.allclose(ps.la_torre(V, 0.3, 0.5, -4.0, b3_kmh * 3.6**b4, b4),
                       0.3 + 0.5 / (1 + np.exp(-4.0 + b3_kmh * (3.6 * V) ** b4)), rtol=1e-13)
    # three zones: the shares add up to 1, and mu = mu_dry A3 / (A1 + A2 + A3) (Do et al. eq. 1)
    a1, a2, a3 = ps.three_zone_fractions(V, 45.0, 60.0)
    assert np.allclose(a1 + a2 + a3, 1.0) and np.allclose(a1, (V / 45.0) ** 2) and np.allclose(a2, V / 60.0)
    assert np.allclose(ps.three_zone(V, 0.8, 45.0, 60.0), ps.three_zone_mu(0.8, a1 * 7, a2 * 7, a3 * 7))
    assert ps.three_zone(200.0, 0.8, 45.0, 60.0) == 0.0  # the footprint lifted
    # the product form multiplied out is Dijks' law with a2 a4 = a1 a6 and a3 a4 = a1 a5
    c0, c1, d0, d1 = 0.1, 0.009, 0.012, 4e-6
    a = (c0, -c0 * d1, -c0 * d0, c1, -c1 * d0, -c1 * d1)
    assert np.allclose(ps.wet_product(VS, TD, BPN, c0, c1, d0, d1), ps.dijks(VS, TD, BPN, *a), rtol=1e-13)
    assert np.allclose(ps.dijks(VS, TD, BPN, *LAWS["dijks"][1]), ps.wet_product(VS, TD, BPN, *LAWS["wet_product"][1]))


def test_the_blank_tyre_law_of_do_marsac_mosset():
    # V_s = 117 kappa^0.9 MPD_mm^a km/h (Do et al. eq. 9; log10 b = 0.90 log10 kappa + 2.07, 10^2.07 = 117.5)
    for kappa, mpd_mm, a in ((0.86, 0.8, 0.45), (0.14, 2.5, 0.6), (1.0, 1.0, 0.3)):
        vs_kmh = ps.blank_tire_vs(mpd_mm * 1e-3, kappa, a) * 3.6
        assert vs_kmh == pytest.approx(10**2.07 * kappa**0.9 * mpd_mm**a, rel=1e-12)
        assert vs_kmh == pytest.approx(117 * kappa**0.9 * mpd_mm**a, rel=5e-3)


# ---------------------------------------------------------------------------------------------- ranking
def test_information_criteria_are_the_gaussian_likelihood():
    r = np.random.default_rng(3).normal(0, 0.01, 15)
    n, k = r.size, 3
    s_hat = math.sqrt(r @ r / n)
    m2logL = -2 * np.sum(stats.norm.logpdf(r, scale=s_hat))
    aic, aicc, bic = ps.information_criteria(r, k)
    assert aic == pytest.approx(m2logL + 2 * (k + 1), rel=1e-12)
    assert aicc == pytest.approx(aic + 2 * (k + 1) * (k + 2) / (n - k - 2), rel=1e-12)
    assert bic == pytest.approx(m2logL + (k + 1) * math.log(n), rel=1e-12)
    aic_s, _, bic_s = ps.information_criteria(r, k, sigma=0.01)
    assert aic_s == pytest.approx(-2 * np.sum(stats.norm.logpdf(r, scale=0.01)) + 2 * k, rel=1e-12)
    assert ps.information_criteria(r[:5], 3)[1] == math.inf  # AICc needs n > K + 1


def test_the_table_ranks_the_generating_law_first_and_applies_the_acceptance_rule():
    rng = np.random.default_rng(7)
    mu = ps.piarc(V, 0.8, 20.0) + rng.normal(0, 0.01, V.size)
    with pytest.warns(AccuracyWarning, match="three_zone"):  # an exponential does not need the quadratic zone
        table = ps.fit_speed_laws(V, mu, laws=["piarc", "do_marsac_mosset", "stribeck", "three_zone"],
                                  criterion="bic")
    assert math.isinf(table["three_zone"].std["V1"])
    assert table.best.law == "piarc" and table.best.delta == 0.0
    assert table.laws[0] == "piarc" and sum(f.weight for f in table) == pytest.approx(1.0)
    assert table["piarc"].params["Sp"] == pytest.approx(20.0, abs=4 * table["piarc"].std["Sp"])
    # an inverse S (alpha = 3, Do et al.'s saturated value): PIARC cannot follow it
    mu = ps.do_marsac_mosset(V, 0.75, 18.0, 3.0) + rng.normal(0, 0.01, V.size)
    table = ps.fit_speed_laws(V, mu, laws=["piarc", "do_marsac_mosset", "gompertz"])
    assert table.best.law in ("do_marsac_mosset", "gompertz") and table["piarc"].delta > 10
    assert table["do_marsac_mosset"].accepted and not table["piarc"].accepted
    assert table["piarc"].sse > ps.ACCEPTANCE_SSE > table["do_marsac_mosset"].sse
    assert "10.1214/aos/1176344136" in table.citations and "hal:hal-00851262" in table.citations
    assert "do_marsac_mosset" in table.summary() and len(table.to_rows()) == 3


def test_the_corners_exact_flat_and_few_rows():
    # an exact curve: its law fits to rounding, every criterion stays finite
    exact = ps.fit_speed_laws(V, ps.piarc(V, 0.8, 20.0), laws=["piarc", "do_marsac_mosset", "gompertz"])
    assert exact.best.law == "piarc" and exact.best.sse < 1e-20 and all(math.isfinite(f.aicc) for f in exact)
    # no speed dependence at all: PIARC's speed constant runs off, undetermined (its error dwarfs it)
    flat = 0.6 + np.random.default_rng(8).normal(0, 0.01, V.size)
    piarc = ps.fit_speed_laws(V, flat, laws=["piarc"])["piarc"]
    assert piarc.params["Sp"] > 1e3 and piarc.std["Sp"] > piarc.params["Sp"]
    # four rows: AICc needs n > K + 1 for every law here, so the table ranks by BIC and says so
    few = ps.fit_speed_laws(V[:4], ps.piarc(V[:4], 0.8, 20.0) + [0.01, -0.01, 0.005, 0.0], laws=["piarc", "rado"])
    assert few.criterion == "bic" and any("ranked by BIC" in n for n in few.notes)
    assert few["rado"].k == 3 and few["rado"].params["mu_locked"] == 0.0  # Rado's three-constant form by default


def test_laws_of_texture_depth_and_bpn_join_the_table_only_with_several_surfaces():
    mu = ps.wet_product(VS, TD, BPN, *LAWS["wet_product"][1]) + np.random.default_rng(4).normal(0, NOISE, VS.size)
    table = ps.fit_speed_laws(VS, mu, laws=["piarc", "dijks", "wet_product"], mtd=TD, bpn=BPN)
    assert table.best.law == "wet_product" and table["piarc"].delta > 50
    one = slice(0, 6)
    table = ps.fit_speed_laws(VS[one], mu[one], laws=["piarc", "dijks", "wet_product"], mtd=TD[one], bpn=BPN[one])
    assert table.laws == ("piarc",)
    assert "free parameters" in table.skipped["dijks"] and "surfaces" in table.skipped["wet_product"]
    with pytest.raises(InputError, match="four surfaces"):
        ps.fit_dijks(VS[:18], mu[:18], mtd=TD[:18], bpn=BPN[:18])  # three surfaces: four slopes unknown
    assert "needs the texture depth" in ps.fit_speed_laws(V, ps.piarc(V, 0.8, 20.0), laws=["piarc", "dijks"]).skipped[
        "dijks"]


def test_the_engine_prediction_side_by_side():
    class Curve:  # stands for persson.Model: its prediction is a PIARC curve with Sp = 25 m/s
        effects = ()

        def friction(self, speed, *, temperature, pressure):
            return type("R", (), {"mu": ps.piarc(speed, 0.7, 25.0), "notes": ()})()

    table = ps.speed_laws_from_model(Curve(), V, temperature=20.0, pressure=3e5, laws=["piarc", "gompertz"])
    assert table["piarc"].params["Sp"] == pytest.approx(25.0, rel=1e-8) and table["piarc"].sse < 1e-20
    assert "engine prediction at 20 C, 0.3 MPa" in table.source and any("noise-free" in n for n in table.notes)


def test_the_plot_shows_the_data_and_every_law():
    mu = ps.piarc(V, 0.8, 20.0) + np.random.default_rng(5).normal(0, 0.01, V.size)
    table = ps.fit_speed_laws(V, mu, laws=["piarc", "do_marsac_mosset"])
    fig = table.plot()
    assert len(fig.axes[0].get_lines()) == 1 + 2 and len(fig.axes[0].get_legend().get_texts()) == 3


# ----------------------------------------------------------------------------------------- Stribeck curve
def test_rows_at_several_viscosities_and_pressures_collapse_on_the_stribeck_curve():
    rng = np.random.default_rng(6)
    eta = np.repeat([1e-3, 3e-3, 1e-2], 12)
    p = np.tile(np.repeat([2e5, 6e5], 6), 3)
    speed = np.tile(np.geomspace(0.5, 30.0, 6), 6)
    H = eta * speed / p
    assert np.allclose(ps.stribeck_parameter(speed, eta, p), H)
    true = (0.15, 0.8, 2e-8, 2.0, 0.0)
    mu = ps.stribeck(H, *true) + rng.normal(0, NOISE, H.size)
    curve = ps.fit_stribeck_curve(speed, mu, viscosity=eta, pressure=p)
    assert curve.groups == 6
    assert 0.7 * NOISE < curve.rms < 1.3 * NOISE  # one curve in H carries every group to the noise
    assert curve.rms_speed > 10 * NOISE and curve.collapse_ratio > 10  # in V alone they do not collapse
    for name, t in zip(("mu_c", "mu_s", "Hs", "alpha"), true):
        assert abs(curve.fit[name] - t) < 4 * curve.fit.std(name), name
    share = np.exp(-((H / 2e-8) ** 2))  # the regimes of the true curve, away from the 10 % / 90 % thresholds
    clear = (share > 0.97) | (share < 0.03) | ((share > 0.15) & (share < 0.85))
    expected = np.where(share >= 0.9, "boundary", np.where(share <= 0.1, "hydrodynamic", "mixed"))
    assert np.all(np.array(curve.regime)[clear] == expected[clear])
    assert set(curve.regime) == {"boundary", "mixed", "hydrodynamic"}


# ------------------------------------------------------------------------------------------- bad input
def test_bad_input_is_refused_with_the_reason():
    mu = ps.piarc(V, 0.8, 20.0)
    with pytest.raises(InputError, match=r"speed: expected speeds > 0 m/s, got -1 at index 0"):
        ps.fit_speed_laws(np.r_[-1.0, V[1:]], mu)
    with pytest.raises(InputError, match="speed"):
        ps.fit_gompertz(V - 5.0, mu)
    with pytest.raises(InputError, match="5 points cannot determine 5 free parameters of stribeck"):
        ps.fit_stribeck(V[:5], mu[:5])
    small = ps.fit_speed_laws(V[:4], mu[:4], laws=["piarc", "stribeck", "la_torre"])
    assert small.laws == ("piarc",) and "4 points cannot determine 5" in small.skipped["stribeck"]
    with pytest.raises(InputError, match="no law could be fitted.*stribeck: speed, mu: 3 points"):
        ps.fit_speed_laws(V[:3], mu[:3], laws=["stribeck"])
    with pytest.raises(InputError, match="look like km/h"):
        ps.fit_speed_laws(V * 10, mu)
    with pytest.raises(InputError, match="mu: expected friction coefficients >= 0"):
        ps.fit_speed_laws(V, mu - 0.5)
    with pytest.raises(InputError, match="unknown law"):
        ps.fit_speed_laws(V, mu, laws=["coulomb"])
    with pytest.raises(InputError, match="millimetres"):
        ps.fit_speed_laws(VS, VS * 0 + 0.5, mtd=TD * 1e3, bpn=BPN)  # texture depth in mm
    with pytest.raises(InputError, match="BPN/100"):
        ps.fit_dijks(VS, VS * 0 + 0.5, mtd=TD, bpn=BPN / 100)
    with pytest.raises(InputError, match="b3 can be held fixed only together with b4"):
        ps.fit_la_torre(V, mu, fixed={"b3": 0.01})
