"""Specification of ``persson.contact``: contact area, separation and elastic energy of Persson's theory.

Every number is compared with an independent computation written here: closed forms (the small-load slope
sqrt(8/pi), full contact), a nested adaptive quadrature of Yang & Persson's separation integral, the
large-separation law of Persson (2007), the energy-separation relation u = int dU/p, and exact scaling laws.
"""

import functools
import math
import warnings

import numpy as np
import pytest
from scipy import integrate, special

import materials
import persson
import surfaces
from persson.contact import separation
from persson.contact import ContactResult, contact

# The surface of the GFMD data of Xu et al. (2024) (public repository xylcsi/PerssonModelFudgeFactor, scripts
# Fig_2_program.m): E* = 1 Pa, qL = qr = 1e4 rad/m (no roll-off), qs = 100 qL, H = 0.8, h_rms = 6 um.
H, Q0, Q1, HRMS = 0.8, 1e4, 1e6, 6e-6
GFMD_SURFACE = surfaces.SelfAffine(hurst=H, q0=Q0, q1=Q1, hrms=HRMS)
C0 = HRMS**2 * H / math.pi / (Q0 ** (-2 * H) - Q1 ** (-2 * H))   # h_rms^2 = 2 pi int q C dq


def _m3(q):
    """int_{q0}^{q} q'^3 C0 q'^(-2-2H) dq' (closed form)."""
    return C0 * (q ** (2 - 2 * H) - Q0 ** (2 - 2 * H)) / (2 - 2 * H)


@functools.lru_cache(maxsize=None)
def reference_mean_separation(Es, p, gamma):
    """Yang & Persson (2008) Eq. 11 by nested adaptive quadrature:
    u = sqrt(pi) int dq q^2 C w int_{w p/E*}^inf dt/t [g + 3(1-g) erf^2 t] exp(-t^2), w = (pi m3(q))^-1/2,
    with q = q0 + tau^2 removing the 1/sqrt(q - q0) of w."""
    def inner(x):
        if x > 30:
            return 0.0
        f = lambda t: (gamma + 3 * (1 - gamma) * math.erf(t) ** 2) * math.exp(-t * t) / t  # noqa: E731
        return integrate.quad(f, x, max(x, 1.0) + 30.0, limit=400, epsabs=0, epsrel=1e-11)[0]

    def outer(tau):
        q = Q0 + tau * tau
        w = 1.0 / math.sqrt(math.pi * _m3(q))
        return q * q * C0 * q ** (-2 - 2 * H) * w * inner(p * w / Es) * 2 * tau

    T = math.sqrt(Q1 - Q0)
    edges = [0.0, *np.geomspace(1e-6 * T, T, 40)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", integrate.IntegrationWarning)
        total = sum(integrate.quad(outer, a, b, limit=200, epsabs=0, epsrel=1e-9)[0]
                    for a, b in zip(edges[:-1], edges[1:]))
    return math.sqrt(math.pi) * total


# --- the area of real contact --------------------------------------------------------------------------------
def test_area_is_the_closed_form_erf_of_the_rms_slope():
    # G(q1) = (E* h' / p)^2 / 8 for an elastic solid, so A/A0 = erf(sqrt(2) p / (E* h')) exactly
    slope = GFMD_SURFACE.rms_slope()
    p = np.geomspace(1e-6, 3.0, 25)
    r = contact(GFMD_SURFACE, 1.0, p)
    np.testing.assert_allclose(r.contact_area, special.erf(math.sqrt(2) * p / slope), rtol=1e-12)


def test_small_load_area_is_linear_with_slope_sqrt_8_over_pi():
    Es, slope = 7e6, 0.8
    s = surfaces.SelfAffine(hurst=0.7, q0=1e3, q1=1e7, rms_slope=slope, qL=1e2)
    p = 1e-6 * Es * slope
    r = contact(s, Es, p)
    assert r.contact_area / (p / (Es * slope)) == pytest.approx(math.sqrt(8 / math.pi), rel=1e-9)


def test_issue_numbers_uncorrected_theory_against_gfmd_at_one_percent_of_E_star():
    # Issue 15: uncorrected theory 0.0576 vs GFMD 0.0779 at p/E* = 0.01 (GFMD: see test_contact_corrections.py)
    assert contact(GFMD_SURFACE, 1.0, 0.01).contact_area == pytest.approx(0.0576, abs=5e-5)


def test_per_scale_area_falls_from_one_at_q0_to_the_contact_area():
    r = contact(GFMD_SURFACE, 1.0, np.array([1e-3, 0.1]))
    assert np.all(r.area_q[:, 0] == 1.0)
    assert np.all(np.diff(r.area_q, axis=1) <= 0)
    np.testing.assert_allclose(r.area_q[:, -1], r.contact_area)


# --- the mean separation --------------------------------------------------------------------------------------
@pytest.mark.parametrize("p, gamma", [(1e-3, 0.5), (1e-2, 0.5), (1e-2, 1.0), (0.24, 0.5),
                                      pytest.param(1e-5, 0.5, marks=pytest.mark.slow)])
def test_mean_separation_equals_an_independent_quadrature_of_yang_persson(p, gamma):
    r = contact(GFMD_SURFACE, 1.0, p, gamma=gamma)
    assert r.mean_separation == pytest.approx(reference_mean_separation(1.0, p, gamma), rel=2e-5)


def test_mean_separation_of_an_elastic_solid_is_accurate_on_any_grid():
    # the engine's grid may be non-uniform and coarse: random node sets, down to a single inner node
    rng = np.random.default_rng(3)
    for p in (1e-3, 1e-2):
        ref = reference_mean_separation(1.0, p, 0.5)
        for n in (3, 5, 17, 65):
            q = np.sort(np.concatenate([[Q0, Q1], np.exp(rng.uniform(math.log(Q0), math.log(Q1), n - 2))]))
            G = (math.pi / 4) * (1.0 / p) ** 2 * _m3(q)
            u = separation.mean_separation(q, GFMD_SURFACE.C(q), G[None, :], 0.5)[0]
            assert u == pytest.approx(ref, rel=2e-6), n


def test_large_separation_law_sigma_proportional_to_exp_minus_u_over_u0():
    # Persson (2007): at small load sigma0 ~ exp(-u/u0), u0 = sqrt(pi) gamma int q^2 C w dq
    gamma = 0.5

    def f(tau):
        q = Q0 + tau * tau
        return q * q * C0 * q ** (-2 - 2 * H) / math.sqrt(math.pi * _m3(q)) * 2 * tau if tau > 0 else 0.0

    T = math.sqrt(Q1 - Q0)
    edges = [0.0, *np.geomspace(1e-6 * T, T, 30)]
    u0 = math.sqrt(math.pi) * gamma * sum(integrate.quad(f, a, b, epsrel=1e-11, limit=200)[0]
                                          for a, b in zip(edges[:-1], edges[1:]))
    p = np.array([1e-12, 1e-11])
    u = contact(GFMD_SURFACE, 1.0, p, gamma=gamma).mean_separation
    assert -(u[1] - u[0]) / math.log(10.0) == pytest.approx(u0, rel=1e-4)
    q = np.geomspace(Q0, Q1, 2001)
    assert separation.separation_decay_length(q, GFMD_SURFACE.C(q), gamma) == pytest.approx(u0, rel=1e-4)


@pytest.mark.parametrize("correction", ["yang-persson", "xu2024"])
@pytest.mark.parametrize("gamma", [0.3, 0.5])
def test_corrected_separation_decays_with_sqrt_gamma_in_place_of_gamma(correction, gamma):
    # P_c = P / sqrt(gamma) at small load makes W ~ sqrt(gamma) P: u0 = sqrt(pi) sqrt(gamma) int q^2 C w dq
    p = np.array([1e-12, 1e-11])
    u = contact(GFMD_SURFACE, 1.0, p, gamma=gamma, correction=correction).mean_separation
    q = np.geomspace(Q0, Q1, 2001)
    u0 = separation.separation_decay_length(q, GFMD_SURFACE.C(q), gamma, correction=correction)
    assert u0 == pytest.approx(math.sqrt(gamma) / gamma * separation.separation_decay_length(
        q, GFMD_SURFACE.C(q), gamma), rel=1e-12)
    assert -(u[1] - u[0]) / math.log(10.0) == pytest.approx(u0, rel=1e-3)


@pytest.mark.parametrize("correction", [None, "yang-persson", "xu2024"])
def test_separation_is_the_pressure_integral_of_the_elastic_energy(correction):
    # Persson (2007): A0 p = -dU/du, i.e. u(p) = int_p^inf (dU/dp') dp'/p'; U and u are computed by different
    # routes (the area map vs the separation kernel), so this ties them together.
    lp = np.linspace(math.log(1e-3), math.log(30.0), 2001)  # u = 0 and U = const past p/E* = 30 here
    p = np.exp(lp)
    r = contact(GFMD_SURFACE, 1.0, p, correction=correction)
    f = np.gradient(r.elastic_energy, lp) / p
    tail = integrate.cumulative_trapezoid(f[::-1], -lp[::-1], initial=0.0)[::-1]
    for target in (1e-2, 1e-1):
        i = int(np.argmin(abs(p - target)))
        assert tail[i] == pytest.approx(r.mean_separation[i], rel=2e-5)


# --- the elastic energy ---------------------------------------------------------------------------------------
def test_elastic_energy_tends_to_the_full_contact_closed_form():
    # full contact: U/A0 = (pi E*/2) int q^2 C dq = E* m2 / 4
    Es = 3e6
    full = math.pi * Es / 2 * C0 * (Q1 ** (1 - 2 * H) - Q0 ** (1 - 2 * H)) / (1 - 2 * H)
    r = contact(GFMD_SURFACE, Es, np.array([1e3 * Es, 0.2 * Es]))
    assert r.elastic_energy[0] == pytest.approx(full, rel=1e-10)
    assert 0.95 * full < r.elastic_energy[1] < 0.995 * full   # not yet flattened at 0.2 E* (A/A0 = 0.85)


def test_elastic_energy_small_load_limit_is_linear_in_load():
    # at small load only the largest wavelengths stay in contact: W = P S ~ gamma P ~ p, so U ~ p
    r = contact(GFMD_SURFACE, 1.0, np.array([1e-9, 1e-8]))
    assert r.elastic_energy[1] / r.elastic_energy[0] == pytest.approx(10.0, rel=0.05)


def test_mean_separation_across_a_roll_off_between_nodes_takes_the_exact_moments():
    """On nodes that skip the roll-off at q0 (the engine's log-uniform grid), a power law through the nodes
    misplaces s = (int q^3 C dq)^(1/2) beyond the kink, and u_bar is off by 2.6e-3 at 16 nodes per decade; with s
    from the PSD's moments integrated between its breakpoints it is within 5e-4 of the path with the kink as a
    node, and the error falls with the spacing (the interval that holds the kink)."""
    from persson.engine.quadrature import separation_moments

    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6, qL=3e2)
    Es, p = 5e6 / 0.75, np.array([1e3, 3e4])
    ref = contact(s, Es, p).mean_separation
    errors = []
    for per_decade in (8, 16):
        q = np.geomspace(3e2, 1e6, int(per_decade * math.log10(1e6 / 3e2)) + 1)
        assert np.min(np.abs(np.log(q / 1e3))) > 0.04                     # no node near the kink
        sq = separation_moments(s, q)
        G = math.pi / 4 * (Es / p[:, None]) ** 2 * sq[None, :] ** 2       # exact for an elastic solid
        exact = separation.mean_separation(q, s.C(q), G, 0.5, s=sq)
        nodes_only = separation.mean_separation(q, s.C(q), G, 0.5)
        errors.append(np.max(np.abs(exact / ref - 1)))
        assert np.max(np.abs(nodes_only / ref - 1)) > 2.5 * errors[-1]        # 3x at 8, 6x at 16 per decade
    assert errors[1] < 5e-4 and errors[0] / errors[1] > 3
    with pytest.raises(persson.InputError, match="s: expected"):
        separation.mean_separation(q, s.C(q), G, 0.5, s=sq[::-1])


# --- viscoelastic path ------------------------------------------------------------------------------------------
def test_viscoelastic_path_with_a_constant_modulus_equals_the_elastic_path():
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6, qL=3e2)
    E, nu = 5e6, 0.5
    p = np.array([1e3, 3e4, 0.3e6, 3e6])
    el = contact(s, E / (1 - nu**2), p)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ve = contact(s, materials.ConstantModulus(E, 0.0), p, speed=1.0, nu=nu)
    np.testing.assert_allclose(ve.contact_area, el.contact_area, rtol=1e-4)
    np.testing.assert_allclose(ve.mean_separation, el.mean_separation, rtol=1e-3)
    np.testing.assert_allclose(ve.elastic_energy, el.elastic_energy, rtol=1e-3)
    assert ve.E_star is None and ve.excited_layer_weight == "dissipation"
    assert el.E_star == pytest.approx(E / 0.75) and el.excited_layer_weight == "elastic energy"


def test_viscoelastic_contact_agrees_with_the_friction_result():
    road, tread = surfaces.example_road(), materials.example_tread()
    p = np.array([0.3e6, 0.8e6])
    r = contact(road, tread, p, speed=1.0, temperature=20.0)
    f = persson.Model(road, tread).friction(np.full(2, 1.0), temperature=20.0, pressure=p)
    np.testing.assert_allclose(r.contact_area, f.contact_area, rtol=1e-12)
    np.testing.assert_allclose(r.mean_separation, f.mean_separation, rtol=1e-12)
    np.testing.assert_allclose(r.excited_layer_thickness, f.excited_layer_thickness, rtol=1e-12)
    assert np.all(np.diff(r.contact_area) > 0) and np.all(np.diff(r.mean_separation) < 0)


# --- corners: very low and very high load, glassy and soft, very rough and very smooth -------------------------
@pytest.mark.parametrize("Es", [1e5, 3e9])  # soft rubber, glassy polymer
def test_exact_scaling_of_heights_and_pressure(Es):
    # heights x lam and pressure x lam leave G unchanged: A/A0 the same, u and h_rms x lam, U x lam^2
    lam = 1e-3
    rough = surfaces.SelfAffine(hurst=0.6, q0=1e3, q1=1e8, hrms=1e-4, qL=1e2)
    smooth = surfaces.SelfAffine(hurst=0.6, q0=1e3, q1=1e8, C0=rough.C0 * lam**2, qL=1e2)
    p = np.array([1e-8, 1e-3, 10.0]) * Es * rough.rms_slope()
    a, b = contact(rough, Es, p), contact(smooth, Es, p * lam)
    np.testing.assert_allclose(b.contact_area, a.contact_area, rtol=1e-12)
    np.testing.assert_allclose(b.mean_separation, a.mean_separation * lam, rtol=1e-9)
    np.testing.assert_allclose(b.elastic_energy, a.elastic_energy * lam**2, rtol=1e-9)
    np.testing.assert_allclose(b.penetration_depth, a.penetration_depth * lam, rtol=1e-9, atol=1e-300)


def test_extreme_loads_stay_finite_and_ordered():
    p = np.array([1e-15, 1e-9, 1e-3, 1.0, 1e3])
    r = contact(GFMD_SURFACE, 1.0, p)
    for name in ("contact_area", "mean_separation", "elastic_energy", "penetration_depth",
                 "excited_layer_thickness"):
        assert np.all(np.isfinite(getattr(r, name))), name
    assert np.all(np.diff(r.contact_area) > 0) and np.all(np.diff(r.mean_separation) < 0)
    assert r.contact_area[-1] == 1.0 and r.mean_separation[-1] < 1e-30 * HRMS
    assert r.penetration_depths["persson"][-1] == pytest.approx(3 * HRMS)
    assert r.penetration_depths["kluppel"][-1] == pytest.approx(math.sqrt(2 / math.pi) * HRMS)


# --- the result object and bad input -----------------------------------------------------------------------
def test_result_is_frozen_scalar_for_scalar_pressure_and_tabulates():
    r = contact(GFMD_SURFACE, 2e6, 1e4)
    assert isinstance(r, ContactResult) and isinstance(r.contact_area, float)
    with pytest.raises(AttributeError):
        r.contact_area = 0.5
    assert r.area_q.shape == (1, r.q.size) and r.G_q.shape == r.area_q.shape
    t = r.as_table()
    assert list(t) == ["pressure_Pa", "contact_area", "mean_separation_m", "elastic_energy_J_m2",
                       "penetration_depth_m", "penetration_persson_m", "penetration_load_weighted_m",
                       "penetration_kluppel_m",
                       "excited_layer_thickness_m"]
    assert all(v.shape == (1,) for v in t.values())
    text = repr(r)
    assert "ContactResult(1 pressure" in text and "E*=2e+06 Pa" in text and len(text) < 200
    assert "10.1103/PhysRevLett.99.125502" in r.citations and r.hrms == pytest.approx(HRMS)


def test_package_exports_contact():
    assert persson.contact is contact and persson.ContactResult is ContactResult


@pytest.mark.parametrize("kwargs, word", [
    (dict(material_or_Estar=-1.0), "material_or_Estar"),
    (dict(material_or_Estar="soft"), "material_or_Estar"),
    (dict(pressure=-1.0), "pressure"),
    (dict(pressure=[1.0, float("nan")]), "pressure"),
    (dict(pressure=np.ones((2, 2))), "pressure"),
    (dict(speed=1.0), "speed"),
    (dict(material_or_Estar=materials.ConstantModulus(5e6, 1e6)), "speed"),
    (dict(correction="fudge"), "correction"),
    (dict(gamma=1.5), "gamma"),
    (dict(penetration="deep"), "penetration"),
    (dict(n_sigma=0.0), "n_sigma"),
    (dict(surface=object()), "surface"),
])
def test_bad_input_names_the_argument(kwargs, word):
    args = dict(surface=GFMD_SURFACE, material_or_Estar=1e6, pressure=1e4)
    args.update(kwargs)
    with pytest.raises(persson.InputError, match=word):
        contact(args.pop("surface"), args.pop("material_or_Estar"), args.pop("pressure"), **args)


# --- surfaces given by their rms slope ---------------------------------------------------------------------
def test_self_affine_surface_takes_the_rms_slope_as_amplitude():
    # the surface of the contact-mechanics challenge (Muser et al., Tribol. Lett. 65, 118 (2017)) is given by its
    # rms gradient g = 1 (H = 0.8, L = 0.1 mm, roll-off 20 um, E* = 25 MPa, reference load 0.01 E*, as used in
    # Fig_3d_program.m of github.com/xylcsi/PerssonModelFudgeFactor); the short cut-off does not enter here
    s = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 20e-6, q1=2 * math.pi / 0.1e-6, qL=2 * math.pi / 0.1e-3,
                            rms_slope=1.0)
    assert s.rms_slope() == pytest.approx(1.0, rel=1e-12)
    ref = surfaces.SelfAffine(hurst=0.8, q0=s.q0, q1=s.q1, qL=s.qL, C0=s.C0)
    assert ref.hrms() == pytest.approx(s.hrms(), rel=1e-12)
    # p = 0.01 E* on the challenge surface: uncorrected Persson theory gives erf(sqrt(2) 0.01)
    assert contact(s, 25e6, 0.25e6).contact_area == pytest.approx(special.erf(math.sqrt(2) * 0.01), rel=1e-12)


@pytest.mark.parametrize("extra", [dict(hrms=1e-6), dict(C0=1e-20), dict(hrms=1e-6, C0=1e-20)])
def test_rms_slope_conflicts_with_other_amplitudes(extra):
    with pytest.raises(surfaces.InputError, match="rms_slope"):
        surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, rms_slope=0.5, **extra)
