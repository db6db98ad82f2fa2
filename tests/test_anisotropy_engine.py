"""Friction and contact of anisotropic surfaces against the sliding direction (Persson's general expressions with
the angular integral over C(q, phi) and Im E(q v cos(phi - theta))).

Checked against: the isotropic engine (an isotropic PSD given in 2-D), an independent brute-force quadrature of
the 2-D integrals (``persson.engine.anisotropic_reference``: Cartesian C(qx, qy), the material's own E, an adaptive
ODE in ln q) at the corners of the regime, and the closed form of the unidirectional limit with a constant modulus.
"""

import functools
import math
import warnings

import numpy as np
import pytest
from scipy import special

import materials
import persson
import surfaces
from persson.case import read_case
from persson.engine.anisotropic_reference import reference_directional_friction
from persson.engine.directional import DirectionalFriction

WLF = materials.WLF(8.86, 101.6, 20.0)
TREAD = materials.example_tread()
BASE = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=10e-6)


def glassy():
    """Glass transition at tau = 1e-8 s at 20 C: rubbery 3 MPa, glassy 2 GPa (|E|/sigma0 up to 1e5)."""
    tau = np.logspace(-14, -2, 25)
    w = np.exp(-0.5 * ((np.log10(tau) + 8.0) / 2.0) ** 2)
    return materials.Prony(E_inf=3e6, E_i=(2e9 - 3e6) * w / w.sum(), tau_i=tau, wlf=WLF)


def soft():
    """Soft compound: 0.5 MPa rubbery, 50 MPa glassy, broad transition."""
    tau = np.logspace(-10, 0, 21)
    w = np.exp(-0.5 * ((np.log10(tau) + 7.0) / 2.5) ** 2)
    return materials.Prony(E_inf=0.5e6, E_i=(50e6 - 0.5e6) * w / w.sum(), tau_i=tau, wlf=WLF)


def quiet(fn, *args, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", persson.PhysicsWarning)
        return fn(*args, **kwargs)


# --- an isotropic PSD given in 2-D is today's engine ---------------------------------------------------------
class Isotropic2D(surfaces.AnisotropicPSD):
    """An isotropic PSD written as a general 2-D PSD (no shortcut: C_polar(q, phi) = C(q))."""

    def __init__(self, base):
        self.base, self.q_range, self.source = base, base.q_range, "isotropic in 2-D"

    def C(self, q):
        return self.base.C(q)

    def C_polar(self, q, phi):
        return self.base.C(np.broadcast_arrays(q, phi)[0])


@pytest.mark.parametrize("surface", [surfaces.stretched(BASE, 1.0, 30.0), Isotropic2D(BASE)],
                         ids=["stretched by 1", "general 2-D"])
def test_an_isotropic_psd_given_in_2d_reproduces_the_isotropic_engine_in_every_direction(surface):
    v = np.array([1e-4, 3e-2, 3.0])
    effects = [persson.effects.Adhesion(tau_f0=0.2e6)]
    iso = persson.Model(BASE, TREAD, effects=effects).friction(v, temperature=10.0, pressure=0.2e6)
    r = persson.Model(surface, TREAD, effects=effects).friction(v, temperature=10.0, pressure=0.2e6,
                                                                  direction_deg=[0.0, 17.0, 90.0, 333.0])
    for name in ("mu", "mu_hysteresis", "mu_adhesion", "contact_area", "error_estimate"):
        got, want = getattr(r, name), np.broadcast_to(getattr(iso, name), getattr(r, name).shape)
        assert got == pytest.approx(want, rel=1e-6), name
    assert r.results[2].G_q == pytest.approx(iso.G_q, rel=1e-6)


# --- the brute-force 2-D quadrature at the corners of the regime ---------------------------------------------
ROAD = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3)
CORNERS = {
    # name: (material, surface, speed m/s, temperature C, pressure Pa, direction deg)
    "glassy cold fast low pressure": (glassy, surfaces.stretched(ROAD, 4.0, 20.0), 30.0, -20.0, 0.02e6, 65.0),
    "soft hot slow high pressure": (soft, surfaces.stretched(surfaces.SelfAffine(
        hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.35e-3), 3.0, 0.0), 1e-8, 80.0, 2e6, 45.0),
    "very rough": (lambda: TREAD, surfaces.stretched(surfaces.SelfAffine(hurst=0.6, q0=1e3, q1=1e8, hrms=30e-6),
                                                     2.0, 120.0), 1.0, 20.0, 0.3e6, 10.0),
    "very smooth, strongly anisotropic": (lambda: TREAD, surfaces.stretched(surfaces.SelfAffine(
        hurst=0.9, q0=1e4, q1=1e8, hrms=0.1e-6), 8.0, 0.0), 1e-2, 20.0, 0.3e6, 30.0),
}


@functools.lru_cache(maxsize=None)
def corner(name):
    make, s, v, T, p, th = CORNERS[name]
    m = make()
    return quiet(persson.Model(s, m).friction, v, temperature=T, pressure=p, direction_deg=th), \
        reference_directional_friction(s, m, v, th, T, p, rtol=1e-8)


@pytest.mark.parametrize("name", list(CORNERS))
def test_default_settings_agree_with_the_brute_force_2d_quadrature_and_say_how_well(name):
    r, ref = corner(name)
    err = abs(r.mu_hysteresis / ref.mu[0] - 1.0)
    assert err < 1e-3
    assert r.contact_area == pytest.approx(ref.contact_area[0], rel=1e-3)
    # the built-in estimate (q and angular Richardson) is not below the true error
    assert err <= 3.0 * r.error_estimate < r.error_estimate * 3 + 1e-3


# --- the unidirectional limit: closed form with a constant modulus -------------------------------------------
class PowerLaw1D:
    """C1D = A q^-(1+2H) on [q0, q1] (two-sided 1-D PSD, m^3)."""

    def __init__(self, A, H, q0, q1):
        self.A, self.H, self.q_range = A, H, (q0, q1)

    def C(self, q):
        q = np.asarray(q, dtype=float)
        return np.where((q >= self.q_range[0]) & (q <= self.q_range[1]), self.A * q ** (-1 - 2 * self.H), 0.0)


def unidirectional_closed_form(p, E, sigma0, cos_angle, nu=0.5):
    r"""gamma = 1: G1 = |E|^2 s^2 m / 4 with m = int q^2 C1D dq, s = 1/((1-nu^2) sigma0), and
    mu = 4 c E'' / (|E|^2 s) int_0^G1 P dG, int_0^G erf(1/(2 sqrt g)) dg = (G + 1/2) erf(1/(2 sqrt G))
    + sqrt(G/pi) exp(-1/(4G)) - 1/2."""
    s = 1.0 / ((1 - nu * nu) * sigma0)
    (q0, q1), H = p.q_range, p.H
    m = p.A * (q1 ** (2 - 2 * H) - q0 ** (2 - 2 * H)) / (2 - 2 * H)
    G = 0.25 * abs(E) ** 2 * s * s * m
    x = 0.5 / math.sqrt(G)
    integral = (G + 0.5) * special.erf(x) + math.sqrt(G / math.pi) * math.exp(-1 / (4 * G)) - 0.5
    return 4 * abs(cos_angle) * E.imag / (abs(E) ** 2 * s) * integral, special.erf(x)


def test_the_unidirectional_limit_has_the_closed_form_of_its_1d_problem():
    p = PowerLaw1D(2e-14, 0.8, 1e3, 1e6)
    E = 5e6 + 2e6j
    m = materials.ConstantModulus(E_storage=E.real, E_loss=E.imag)
    model = persson.Model(surfaces.unidirectional(p, angle_deg=20.0), m, gamma=1.0)
    r = model.friction(0.1, pressure=0.3e6, direction_deg=[20.0, 50.0, 110.0, 200.0])
    mu0, area = unidirectional_closed_form(p, E, 0.3e6, 1.0)
    # sliding along the wavevectors (across the ridges) is the 1-D problem; at 30 deg from it the loss scales with
    # cos 30; along the ridges there is no hysteresis; the static contact does not depend on the direction
    assert r.mu_hysteresis == pytest.approx(mu0 * np.array([1.0, math.cos(math.radians(30)), 0.0, 1.0]),
                                            rel=1e-8, abs=1e-15)
    assert r.contact_area == pytest.approx(np.full(4, area), rel=1e-9)


def test_sliding_along_the_grooves_reads_the_relaxed_modulus():
    p = PowerLaw1D(2e-14, 0.8, 1e3, 1e6)
    r = persson.Model(surfaces.unidirectional(p, angle_deg=0.0), TREAD).friction(
        [1e-3, 10.0], direction_deg=[0.0, 90.0])
    along = r.results[1]
    assert np.all(along.mu_hysteresis == 0.0)
    # the rubber is indented but never excited: the contact of the relaxed modulus E(0) = E_inf, at every speed
    relaxed = persson.Model(surfaces.unidirectional(p), materials.ConstantModulus(E_storage=TREAD.E_inf,
                                                                                 E_loss=1e-9)).friction(1.0)
    assert along.contact_area == pytest.approx(np.full(2, relaxed.contact_area), rel=1e-4)
    assert np.all(r.mu_hysteresis[0] > 0)


# --- physics of a stretched surface --------------------------------------------------------------------------
@pytest.fixture(scope="module")
def rose():
    s = surfaces.stretched(BASE, ratio=3.0, angle_deg=30.0)
    th = np.array([30.0, 60.0, 0.0, 120.0, 90.0, 150.0, 210.0, 300.0])
    return th, persson.Model(s, TREAD).friction([1e-3, 1.0], direction_deg=th)


def test_friction_is_largest_sliding_across_the_ridges_and_symmetric_under_half_turns(rose):
    th, r = rose
    mu = r.mu
    k = {t: i for i, t in enumerate(th)}
    assert np.all(mu[k[120.0]] >= mu.max(axis=0) * (1 - 1e-12))  # across the ridges (30 + 90)
    assert np.all(mu[k[30.0]] <= mu.min(axis=0) * (1 + 1e-12))  # along them
    assert mu[k[210.0]] == pytest.approx(mu[k[30.0]], rel=1e-12)  # theta + 180
    assert mu[k[300.0]] == pytest.approx(mu[k[120.0]], rel=1e-12)
    assert mu[k[60.0]] == pytest.approx(mu[k[0.0]], rel=1e-12)  # mirror about the ridges
    assert mu[k[150.0]] == pytest.approx(mu[k[90.0]], rel=1e-12)
    assert np.all(mu[k[120.0]] > 1.5 * mu[k[30.0]])


def test_a_direction_result_is_the_single_direction_call(rose):
    th, r = rose
    one = persson.Model(surfaces.stretched(BASE, ratio=3.0, angle_deg=30.0), TREAD).friction([1e-3, 1.0],
                                                                                            direction_deg=90.0)
    assert isinstance(one, persson.FrictionResult) and one.notes[0].startswith("sliding direction 90 deg")
    assert one.mu == pytest.approx(r.at(90.0).mu, rel=1e-12)
    assert r.mu.shape == (th.size, 2) and isinstance(r, DirectionalFriction)
    t = r.as_table()
    assert t["direction_deg"].size == 2 * th.size and set(t["direction_deg"]) == set(th)
    fig = r.polar_plot()
    assert fig.axes[0].name == "polar"


def test_adhesion_follows_the_contact_area_of_each_direction(rose):
    s = surfaces.stretched(BASE, ratio=3.0, angle_deg=30.0)
    ad = persson.effects.Adhesion(tau_f0=1e6, c=0.0)
    r = persson.Model(s, TREAD, effects=[ad]).friction(1.0, pressure=0.3e6, direction_deg=[30.0, 120.0])
    assert r.mu_adhesion == pytest.approx(1e6 * r.contact_area / 0.3e6, rel=1e-12)
    assert r.contact_area[0] != pytest.approx(r.contact_area[1], rel=1e-3)


def test_effects_that_change_the_psd_act_on_its_angular_mean_and_keep_its_shape():
    short = surfaces.stretched(BASE.with_cutoff(q1=1e5), ratio=3.0, angle_deg=30.0)
    extended = persson.Model(short, TREAD, effects=[persson.effects.Microtexture(q1=1e6)])
    r = quiet(extended.friction, [1e-3, 1.0], direction_deg=[30.0, 120.0])
    full = persson.Model(surfaces.stretched(BASE, 3.0, 30.0), TREAD).friction([1e-3, 1.0], direction_deg=[30.0, 120.0])
    assert r.mu == pytest.approx(full.mu, rel=1e-9)  # a stretched power law continues its own law


def test_contact_of_an_anisotropic_surface():
    s = surfaces.stretched(BASE, ratio=3.0, angle_deg=30.0)
    # pressed without sliding: the contact of the angular mean of the PSD, exactly
    at_rest = persson.contact(s, 2e6, [0.1e6, 0.5e6])
    mean = persson.contact(s.to_isotropic(), 2e6, [0.1e6, 0.5e6])
    assert at_rest.contact_area == pytest.approx(mean.contact_area, rel=1e-6)
    assert any("angular mean" in n for n in at_rest.notes)
    sliding = [persson.contact(s, TREAD, 0.3e6, speed=1.0, direction_deg=d).contact_area for d in (30.0, 120.0)]
    assert sliding[0] > sliding[1]  # across the ridges the rubber is excited more: stiffer, less contact
    with pytest.raises(persson.InputError, match="direction"):
        persson.contact(s, 2e6, 0.3e6, direction_deg=30.0)


# --- bad input -----------------------------------------------------------------------------------------------
def test_a_direction_in_radians_warns_in_scripts_and_is_refused_in_a_case_file(tmp_path):
    model = persson.Model(surfaces.stretched(BASE, 2.0), TREAD)
    with pytest.warns(persson.errors.UnitWarning, match="radians.*90 degrees"):
        model.friction(1.0, direction_deg=math.pi / 2)
    with pytest.raises(persson.InputError, match="direction_deg"):
        model.friction(1.0, direction_deg=[0.0, float("nan")])
    with pytest.raises(persson.InputError, match="one sliding direction"):
        persson.Model(BASE, TREAD, direction_deg=[0.0, 90.0])
    case = tmp_path / "case.toml"
    case.write_text('[surface]\nexample = "road"\nstretch = { ratio = 3.0, angle_deg = 0.0 }\n'
                    '[material]\nexample = "tread"\n[conditions]\nsliding_direction_deg = 1.5708\n')
    with pytest.raises(persson.InputError, match=r"sliding_direction_deg.*radians"):
        read_case(case)


def test_a_case_file_carries_the_stretch_and_the_sliding_direction(tmp_path):
    case = tmp_path / "case.toml"
    case.write_text('[surface]\nexample = "road"\nstretch = { ratio = 3.0, angle_deg = 30.0 }\n'
                    '[material]\nexample = "tread"\n[conditions]\nsliding_direction_deg = 120\n')
    spec = read_case(case)
    assert isinstance(spec.model.surface, surfaces.Stretched) and spec.model.direction_deg == 120.0
    r = quiet(spec.model.friction, 1.0)
    assert r.notes[0].startswith("sliding direction 120 deg")
    case.write_text('[surface]\nexample = "road"\nunidirectional_deg = 90\n[material]\nexample = "tread"\n')
    with pytest.raises(persson.InputError, match="unidirectional_deg applies only with profiles"):
        read_case(case)


# --- the flash temperature against the sliding direction ------------------------------------------------------
FLASH_CORNERS = {
    # name: (material, temperature C, pressure Pa, speeds m/s, smallest rise of the hottest scale at the top speed, K)
    "tread, middle": (lambda: TREAD, 10.0, 0.2e6, [1e-3, 0.3, 10.0], 1.0),
    "glassy cold fast low pressure": (glassy, -20.0, 0.02e6, [1e-2, 3.0, 30.0], 1.0),
    "soft hot slow high pressure": (soft, 80.0, 2e6, [1e-8, 1e-3, 1.0], 0.05),
}


@pytest.mark.parametrize("surface", [surfaces.stretched(BASE, 1.0, 30.0), Isotropic2D(BASE)],
                         ids=["stretched by 1", "general 2-D"])
@pytest.mark.parametrize("corner", list(FLASH_CORNERS))
def test_an_isotropic_psd_in_2d_reproduces_the_isotropic_flash_temperature_in_every_direction(surface, corner):
    make, T, p, v, rise = FLASH_CORNERS[corner]
    v = np.array(v)
    effects = [persson.effects.FlashTemperature(tol=1e-8)]
    iso = persson.Model(BASE, make(), effects=effects).friction(v, temperature=T, pressure=p)
    r = persson.Model(surface, make(), effects=effects).friction(v, temperature=T, pressure=p,
                                                                  direction_deg=[0.0, 17.0, 90.0])
    assert iso.max_flash_temperature[-1] > rise  # the flash temperature does something here
    for res in r.results:
        np.testing.assert_allclose(res.mu, iso.mu, rtol=1e-6)
        np.testing.assert_allclose(res.max_flash_temperature, iso.max_flash_temperature, rtol=1e-6)


@pytest.mark.slow
def test_the_flash_temperature_across_ridges_matches_an_independent_fixed_point_iteration():
    """A rough road stretched 3x along x, 1 m/s, 20 C: sliding across the ridges heats the rubber by ~25 K, three
    times more than sliding along them. The brute-force reference (Cartesian C2d, plain fixed point, trapezoid heat
    integral) converges at second order in its node spacing: extrapolated from 20 and 40 nodes per decade."""
    from persson.engine.anisotropic_reference import reference_directional_flash_friction

    base = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3)
    s = surfaces.stretched(base, 3.0, 0.0)
    kw = dict(temperature=20.0, pressure=0.3e6)
    r = persson.Model(s, TREAD, effects=[persson.effects.FlashTemperature(tol=1e-7)]).friction(
        1.0, direction_deg=[0.0, 90.0], **kw)
    across = r.at(90.0)
    along = r.at(0.0)
    assert across.mu_hysteresis > 2.0 * along.mu_hysteresis
    assert across.max_flash_temperature > 2.0 * along.max_flash_temperature
    coarse, fine = (reference_directional_flash_friction(s, TREAD, 1.0, 90.0, nodes_per_decade=n, tol=1e-4, **kw)
                    for n in (20, 40))
    mu_ref = fine.mu[0] + (fine.mu[0] - coarse.mu[0]) / 3.0
    dT_ref = np.max(fine.temperature_q) - 20.0
    assert abs(fine.mu[0] / coarse.mu[0] - 1) < 1e-2  # the extrapolation is a small correction
    assert across.mu_hysteresis == pytest.approx(mu_ref, rel=1e-3)
    assert across.max_flash_temperature == pytest.approx(dT_ref, rel=1e-3)


def test_the_estimate_covers_the_error_where_the_shape_has_kinks_in_angle():
    # a plateau below the roll-off: some directions reach it at a given q, others not (kinks in angle)
    s = surfaces.stretched(surfaces.SelfAffine(hurst=0.8, q0=3e3, q1=3e4, hrms=5e-6, qL=1e3), 3.0, 45.0)
    r = persson.Model(s, TREAD).friction(1e-2, direction_deg=100.0)
    fine_grid = persson.GridSettings(q_per_decade=96, tolerance=1e-7, max_refinement=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", persson.AccuracyWarning)
        fine = persson.Model(s, TREAD, grid=fine_grid).friction(1e-2, direction_deg=100.0)
    err = abs(r.mu_hysteresis / fine.mu_hysteresis - 1.0)
    assert fine.error_estimate < 0.1 * err  # the converged value, by its own estimate
    assert 1e-6 < err <= 3.0 * r.error_estimate


@pytest.mark.slow
def test_the_flash_temperature_of_soft_rubber_hot_and_slow_matches_the_fixed_point_iteration():
    """Soft compound at 80 C and 2 MPa sliding at 1 cm/s across the ridges of a rough road stretched 3x: the
    corner where the rubber is rubbery and the heating small (about 1 K); reference extrapolated from 20 and 40
    nodes per decade as above."""
    from persson.engine.anisotropic_reference import reference_directional_flash_friction

    base = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3)
    s = surfaces.stretched(base, 3.0, 0.0)
    kw = dict(temperature=80.0, pressure=2e6)
    r = persson.Model(s, soft(), effects=[persson.effects.FlashTemperature(tol=1e-7)]).friction(
        1e-2, direction_deg=90.0, **kw)
    coarse, fine = (reference_directional_flash_friction(s, soft(), 1e-2, 90.0, nodes_per_decade=n, tol=1e-4, **kw)
                    for n in (20, 40))
    mu_ref = fine.mu[0] + (fine.mu[0] - coarse.mu[0]) / 3.0
    assert np.max(fine.temperature_q) - 80.0 > 0.5
    assert r.mu_hysteresis == pytest.approx(mu_ref, rel=1e-3)
    assert r.max_flash_temperature == pytest.approx(np.max(fine.temperature_q) - 80.0, rel=1e-3)
