"""Specification of the effects: flash temperature, adhesion, wet, microtexture, strain softening, separation."""

import math
from dataclasses import dataclass

import numpy as np
import pytest
from scipy import integrate, special

import materials
import persson
import surfaces
from persson.engine import kernels as _kernels
from persson.effects import Adhesion, Effect, FlashTemperature, Microtexture, Parameter, StrainSoftening, Wet
from persson.contact.separation import separation_decay_length

ROAD = surfaces.SelfAffine(hurst=0.8, q0=2 * np.pi / 5e-3, q1=1e6, hrms=0.3e-3, qL=2 * np.pi / 0.05)
TREAD = materials.example_tread()
SIGMA0 = 0.3e6


# --- flash temperature ------------------------------------------------------------------------------------
@pytest.mark.parametrize("qi, qj, a", [(1e3, 1e3, 1e-9), (1e4, 2e3, 1e-9), (1e5, 1e3, 1e-6), (3e5, 2.99999e5, 1e-10),
                                       (1e6, 1e6, 1e-12), (2e3, 1e3, 1e-4)])
def test_heat_kernel_closed_form_equals_quadrature(qi, qj, a):
    D = 1.2e-7

    def integrand(k):
        return ((-math.expm1(-a * k * k)) / (D * k * k) * 4 * qj / (k * k + 4 * qj * qj)
                * 4 * qi * qi / (k * k + 4 * qi * qi))

    # integrate in ln k (the integrand spans many decades of k); breakpoints at the kernel's corner scales
    corners = sorted({math.log(2 * qi), math.log(2 * qj), -0.5 * math.log(a)})
    edges = [corners[0] - 40.0, *corners, corners[-1] + 40.0]
    ref = sum(integrate.quad(lambda u: integrand(math.exp(u)) * math.exp(u), lo, hi, epsabs=0, epsrel=1e-12,
                             limit=500)[0] for lo, hi in zip(edges[:-1], edges[1:])) / math.pi
    ex_i = special.erfcx(2 * qi * math.sqrt(a))
    ex_j = special.erfcx(2 * qj * math.sqrt(a))
    assert _kernels.heat_kernel(qi, qj, a, D, ex_i, ex_j) == pytest.approx(ref, rel=1e-6)


@pytest.fixture(scope="module")
def flash_pair():
    v = np.array([1e-6, 0.1, 1.0, 10.0])
    base = persson.Model(ROAD, TREAD).friction(v, temperature=20.0, pressure=SIGMA0)
    hot = persson.Model(ROAD, TREAD, effects=[FlashTemperature()]).friction(v, temperature=20.0, pressure=SIGMA0)
    return v, base, hot


def test_flash_temperature_negligible_at_creep_speed(flash_pair):
    v, base, hot = flash_pair
    assert hot.mu[0] == pytest.approx(base.mu[0], rel=5e-3)
    assert hot.max_flash_temperature[0] < 0.05


def test_flash_temperature_lowers_friction_at_sliding_speeds(flash_pair):
    v, base, hot = flash_pair
    assert np.all(hot.mu[1:] < base.mu[1:])
    assert np.all(np.diff(hot.max_flash_temperature) > 0)  # hotter the faster
    assert hot.converged and np.all(hot.residual < 1e-3)
    # temperature grows towards the small scales (heat from every larger scale adds up)
    assert np.all(np.diff(hot.temperature_q[-1]) >= -1e-9)


def test_flash_temperature_independent_of_tolerance():
    v = np.array([0.1, 1.0, 10.0])
    r1 = persson.Model(ROAD, TREAD, effects=[FlashTemperature(tol=1e-3)]).friction(v, pressure=SIGMA0)
    r2 = persson.Model(ROAD, TREAD, effects=[FlashTemperature(tol=1e-4)]).friction(v, pressure=SIGMA0)
    np.testing.assert_allclose(r1.mu, r2.mu, rtol=1e-4)
    np.testing.assert_allclose(r1.max_flash_temperature, r2.max_flash_temperature, atol=2e-3)


def test_flash_temperature_non_convergence_is_reported_and_warned():
    with pytest.warns(persson.ConvergenceWarning):
        r = persson.Model(ROAD, TREAD, effects=[FlashTemperature(max_iter=1)]).friction([1.0, 10.0], pressure=SIGMA0)
    assert not r.converged and any("did not converge" in n for n in r.notes)


def test_flash_temperature_needs_a_temperature_dependent_material():
    with pytest.raises(persson.InputError, match="temperature"):
        persson.Model(ROAD, materials.ConstantModulus(5e6, 2e6),
                      effects=[FlashTemperature()]).friction(1.0, pressure=SIGMA0)


def test_real_contact_area_about_one_percent_at_abs_speeds(flash_pair):
    r = persson.Model(ROAD, TREAD, effects=[FlashTemperature()]).friction(np.geomspace(0.1, 1.0, 3), pressure=SIGMA0)
    assert np.all((r.contact_area > 0.003) & (r.contact_area < 0.05))


# --- adhesion and wet ---------------------------------------------------------------------------------------
def test_adhesion_peak_equals_tau_f0_times_area_over_pressure():
    ad = Adhesion(tau_f0=3e6, c=0.2, v_ref=1e-3)
    T = 50.0
    v_peak = ad.v_ref / float(TREAD.wlf.aT(T))
    r = persson.Model(ROAD, TREAD, effects=[ad]).friction(v_peak, temperature=T, pressure=SIGMA0)
    assert r.mu_adhesion == pytest.approx(3e6 * r.contact_area / SIGMA0, rel=1e-12)
    assert r.mu == pytest.approx(r.mu_hysteresis + r.mu_adhesion, rel=1e-12)
    # one decade away the shear stress falls by exp(-c)
    r2 = persson.Model(ROAD, TREAD, effects=[ad]).friction(10 * v_peak, temperature=T, pressure=SIGMA0)
    assert r2.mu_adhesion == pytest.approx(3e6 * math.exp(-0.2) * r2.contact_area / SIGMA0, rel=1e-12)


def test_the_adhesive_peak_is_plausible_within_a_decade_of_the_shifted_speeds_and_pickles():
    """v_ref's plausible range follows the data (the measured sliding speeds shifted to T_ref, a decade wider on
    each side), and the parameters survive pickling (sent to a process pool with a fitted effect)."""
    import pickle
    from types import SimpleNamespace

    ranges = SimpleNamespace(shifted_speed=(1e-4, 3.0))
    (v_ref,) = [p for p in Adhesion.parameters if p.name == "v_ref"]
    assert v_ref.plausible_range(ranges) == pytest.approx((1e-5, 30.0), rel=1e-12)
    back = pickle.loads(pickle.dumps(Adhesion.parameters))
    assert [p.plausible_range(ranges) for p in back] == [p.plausible_range(ranges) for p in Adhesion.parameters]


def test_wet_removes_adhesion():
    model = persson.Model(ROAD, TREAD, effects=[Adhesion()])
    dry = model.friction([1e-3, 1.0], pressure=SIGMA0)
    wet = model.with_effect(Wet()).friction([1e-3, 1.0], pressure=SIGMA0)
    assert np.all(dry.mu_adhesion > 0)
    np.testing.assert_array_equal(wet.mu_adhesion, 0.0)
    np.testing.assert_allclose(wet.mu, dry.mu_hysteresis, rtol=1e-12)


def test_hydrodynamic_lift_formula_and_load_sharing():
    w = Wet(lift=1.0, eta=1e-3, h_in=2e-4, h_out=1e-4, contact_length=0.1, contact_width=0.1)
    a = 2.0
    expected = 6 * 1e-3 * 10.0 * 0.1 * 0.1**2 / (1e-4**2 * (a - 1) ** 2) * (math.log(a) - 2 * (a - 1) / (a + 1))
    assert w.lift_force(10.0) == pytest.approx(expected, rel=1e-12)
    r_dry = persson.Model(ROAD, TREAD).friction([0.01, 10.0], pressure=SIGMA0)
    r_wet = persson.Model(ROAD, TREAD, effects=[w]).friction([0.01, 10.0], pressure=SIGMA0)
    assert r_wet.mu[1] < r_dry.mu[1]  # lift takes load off the asperities at speed
    assert r_wet.mu[0] == pytest.approx(r_dry.mu[0], rel=2e-3)  # negligible at low speed


def test_sealing_reduces_hysteresis():
    r0 = persson.Model(ROAD, TREAD, effects=[Wet()]).friction(1.0, pressure=SIGMA0)
    r1 = persson.Model(ROAD, TREAD, effects=[Wet(seal_fraction=0.5, seal_q=1e4)]).friction(1.0, pressure=SIGMA0)
    assert r1.mu < r0.mu


# --- microtexture and strain softening ----------------------------------------------------------------------
def test_microtexture_extends_tail_with_fitted_hurst():
    true = surfaces.SelfAffine(hurst=0.7, q0=1e3, q1=1e7, C0=1e-6)
    measured = surfaces.PSD(np.geomspace(1e3, 1e5, 81), true.C(np.geomspace(1e3, 1e5, 81)), q_r=1e5)
    ext = Microtexture(q1=1e7).transform_surface(measured, None)
    assert ext.q_range[1] == pytest.approx(1e7)
    assert ext.extrapolated
    qq = np.geomspace(2e5, 9e6, 7)
    np.testing.assert_allclose(ext.C(qq), true.C(qq), rtol=1e-6)
    r = persson.Model(measured, TREAD, effects=[Microtexture(q1=1e7)]).friction(1.0, pressure=SIGMA0)
    assert any("extrapolated" in n for n in r.notes)


def test_microtexture_cut_below_the_first_wavevector_is_refused_not_ignored():
    """q1 <= q0 would remove every length scale: an error naming both, never the surface returned unchanged (which
    made mu jump from the bare surface's value to 0 as q1 crossed q0)."""
    measured = surfaces.PSD(np.geomspace(1e3, 1e5, 81), 1e-20 * np.geomspace(1e3, 1e5, 81) ** -3.6, q_r=1e5)
    for q1 in (9e2, 1e3):
        with pytest.raises(persson.InputError, match=r"q1 = (900|1000) rad/m lies at or below .* q0 = 1000"):
            Microtexture(q1=q1).transform_surface(measured, None)
    cut = Microtexture(q1=2e3).transform_surface(measured, None)
    assert cut.q_range == pytest.approx((1e3, 2e3))


def test_strain_softening_scales_the_modulus():
    e = StrainSoftening(storage_factor=0.4, loss_factor=0.6)
    m = e.transform_material(TREAD, None)
    w = np.array([1.0, 1e4])
    np.testing.assert_allclose(m.E(w, 20.0).real, 0.4 * TREAD.E(w, 20.0).real)
    np.testing.assert_allclose(m.E(w, 20.0).imag, 0.6 * TREAD.E(w, 20.0).imag)
    assert m.log10_aT(40.0) == TREAD.log10_aT(40.0)


# --- effects API ------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ConstantShear(Effect):
    """A user effect written outside the package: a constant extra friction term."""

    name = "test_constant_shear"
    parameters = (Parameter("mu0", 0.05, (0.0, 1.0), "1", "extra friction"),)
    mu0: float = 0.05

    def friction_term(self, state):
        return np.full_like(state.conditions.speed, self.mu0)


def test_user_defined_effect_works_without_package_changes():
    assert "test_constant_shear" in persson.effects.available()
    model = persson.Model(ROAD, TREAD)
    r0 = model.friction([0.01, 1.0], pressure=SIGMA0)
    r1 = model.with_effect(ConstantShear(mu0=0.07)).friction([0.01, 1.0], pressure=SIGMA0)
    np.testing.assert_allclose(r1.mu - r0.mu, 0.07, rtol=1e-12)
    assert r1.mu_terms["test_constant_shear"] == pytest.approx([0.07, 0.07])
    assert model.with_effect(ConstantShear()).without("test_constant_shear").effect_names == ()


def test_an_effect_defined_with_register_false_acts_but_is_no_candidate():
    """``class E(Effect, register=False)``: the effect acts in a model exactly as a registered one (the same
    constant term), but it is not in the registry, so no diagnosis tries it and no case file finds it by name."""

    @dataclass(frozen=True)
    class HiddenShear(Effect, register=False):
        name = "test_hidden_shear"
        parameters = (Parameter("mu0", 0.05, (0.0, 1.0), "1", "extra friction"),)
        mu0: float = 0.05

        def friction_term(self, state):
            return np.full_like(state.conditions.speed, self.mu0)

    assert "test_hidden_shear" not in persson.effects.available()
    with pytest.raises(ValueError, match="test_hidden_shear"):
        persson.effects.effect_class("test_hidden_shear")
    model = persson.Model(ROAD, TREAD)
    r0 = model.friction([0.01, 1.0], pressure=SIGMA0)
    r1 = model.with_effect(HiddenShear(mu0=0.07)).friction([0.01, 1.0], pressure=SIGMA0)
    np.testing.assert_allclose(r1.mu - r0.mu, 0.07, rtol=1e-12)


def test_effect_parameters_are_validated_and_listed():
    assert {"flash_temperature", "adhesion", "microtexture", "strain_softening", "wet"} <= set(
        persson.effects.available())
    with pytest.raises(persson.InputError, match="tau_f0"):
        Adhesion(tau_f0=-1.0)
    with pytest.raises(persson.InputError, match="unknown"):
        Adhesion().with_parameters(nonsense=1.0)
    assert Adhesion().with_parameters(c=0.3).c == 0.3
    with pytest.raises(persson.InputError, match="no effect"):
        persson.Model(ROAD, TREAD).without("adhesion")


# --- interfacial separation ---------------------------------------------------------------------------------
def _yang_persson_direct(surface, Es, sigma0, gamma, n=400):
    """Direct double integral of Yang & Persson (2008) Eq. 11 with quad over p' at each q."""
    q = np.geomspace(*surface.q_range, n)
    C = surface.C(q)
    m3 = integrate.cumulative_trapezoid(q**4 * C, np.log(q), initial=0.0)
    out = np.zeros_like(q)
    for i in range(1, q.size):
        w = 1 / math.sqrt(math.pi * m3[i])

        def f(lp):  # integrand in ln p' (dp'/p' = d ln p')
            p = math.exp(lp)
            P = special.erf(p * w / Es)
            return (gamma + 3 * (1 - gamma) * P * P) * math.exp(-((w * p / Es) ** 2))

        top = math.log(10 * Es / w)  # exp(-100) beyond
        lo = math.log(sigma0)
        out[i] = 0.0 if lo >= top else q[i] ** 3 * C[i] * w * integrate.quad(f, lo, top, limit=200,
                                                                             epsabs=0, epsrel=1e-10)[0]
    return math.sqrt(math.pi) * integrate.trapezoid(out, np.log(q))


@pytest.mark.parametrize("gamma", [1.0, 0.5])
def test_mean_separation_matches_direct_double_integral_for_elastic_solid(gamma):
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6)
    m = materials.ConstantModulus(5e6, 0.0)
    r = persson.Model(s, m, gamma=gamma, grid=persson.GridSettings(q_per_decade=64)).friction(1.0, pressure=SIGMA0)
    ref = _yang_persson_direct(s, 5e6 / 0.75, SIGMA0, gamma)
    assert r.mean_separation == pytest.approx(ref, rel=2e-3)


def test_large_separation_law_sigma_exp_minus_u_over_u0():
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6)
    m = materials.ConstantModulus(5e6, 0.0)
    model = persson.Model(s, m, gamma=0.5, grid=persson.GridSettings(q_per_decade=64))
    p = np.array([1e1, 1e2])
    u = np.array([model.friction(1.0, pressure=x).mean_separation for x in p])
    slope = -(u[1] - u[0]) / math.log(p[1] / p[0])  # -du/dln(sigma0) -> u0
    q = np.geomspace(1e3, 1e6, 193)
    assert slope == pytest.approx(separation_decay_length(q, s.C(q), 0.5), rel=0.02)


def test_separation_falls_and_penetration_grows_linearly_with_pressure():
    model = persson.Model(ROAD, TREAD, effects=[FlashTemperature()])
    p = np.linspace(0.3e6, 0.8e6, 6)
    rs = [model.friction(1.0, pressure=x) for x in p]
    u = np.array([r.mean_separation for r in rs])
    d = np.array([r.penetration_depth for r in rs])
    assert np.all(np.diff(u) < 0) and np.all(np.diff(d) > 0)
    # "about linear": a straight line describes the rise to within 10 % of its size over tire pressures
    # (the exact law is concave, u_bar ~ -u0 ln sigma0 asymptotically).
    resid = d - np.polyval(np.polyfit(p, d, 1), p)
    assert np.max(np.abs(resid)) < 0.1 * (d.max() - d.min())
