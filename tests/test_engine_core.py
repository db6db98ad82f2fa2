"""Specification of the baseline Persson solver: hysteresis friction and real contact area.

References: Persson, J. Chem. Phys. 115, 3840 (2001); Persson et al., J. Phys.: Condens. Matter 17, R1 (2005).
"""

import functools
import math

import numpy as np
import pytest
from scipy import integrate
from scipy.special import erf, erfc

import materials
import persson
import surfaces

SIGMA0 = 0.3e6


def closed_form_constant_modulus(E_storage, E_loss, nu, sigma0, H, q0, q1, hrms):
    r"""A/A0 and mu for a frequency-independent modulus on a self-affine PSD, gamma = 1 (S = 1).

    With E constant, G(q) = (pi/4) (|E|/((1-nu^2) sigma0))^2 int_{q0}^{q} q'^3 C dq' does not depend on v,
    and q^3 C dq = (4 sigma0^2 / (pi E*^2)) dG, so
    mu = (8 E''_* sigma0 / (pi E*^2)) int_0^{G1} erf(1/(2 sqrt G)) dG, with (derived by parts)
    int_0^X erf(1/(2 sqrt G)) dG = X erf(u) + sqrt(X/pi) exp(-u^2) - erfc(u)/2,  u = 1/(2 sqrt X).
    The angular integral of cos(phi) Im E = E'' |cos phi| over [0, 2 pi] is 4 E''.
    """
    C0 = hrms**2 / (2 * math.pi * (q0 ** (-2 * H) - q1 ** (-2 * H)) / (2 * H))
    Es = abs(complex(E_storage, E_loss)) / (1 - nu**2)
    El = E_loss / (1 - nu**2)
    a = (math.pi / 4) * (Es / sigma0) ** 2 * C0 / (2 - 2 * H)
    X = a * (q1 ** (2 - 2 * H) - q0 ** (2 - 2 * H))
    u = 1 / (2 * math.sqrt(X))
    integral = X * erf(u) + math.sqrt(X / math.pi) * math.exp(-u * u) - 0.5 * erfc(u)
    return erf(u), 8 * El * sigma0 / (math.pi * Es**2) * integral


@pytest.fixture(scope="module")
def benchmark_model():
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6)
    m = materials.ConstantModulus(E_storage=5e6, E_loss=2e6)
    return persson.Model(s, m, nu=0.5, gamma=1.0)


def test_closed_form_reproduces_published_benchmark_numbers():
    area, mu = closed_form_constant_modulus(5e6, 2e6, 0.5, SIGMA0, 0.8, 1e3, 1e7, 20e-6)
    assert area == pytest.approx(0.26263, abs=5e-6)
    assert mu == pytest.approx(0.076014, abs=5e-7)


def test_default_grid_meets_closed_form_within_0p1_percent(benchmark_model):
    area, mu = closed_form_constant_modulus(5e6, 2e6, 0.5, SIGMA0, 0.8, 1e3, 1e7, 20e-6)
    r = benchmark_model.friction(np.array([1e-6, 1e-2, 1.0, 10.0]), temperature=20.0, pressure=SIGMA0)
    np.testing.assert_allclose(r.contact_area, area, rtol=1e-3)
    np.testing.assert_allclose(r.mu_hysteresis, mu, rtol=1e-3)
    # frequency-independent modulus: nothing depends on speed
    assert np.ptp(r.mu) < 1e-12


def test_constant_modulus_is_integrated_exactly_on_any_grid(benchmark_model):
    """With E constant, G is q^4 C times a constant (integrated exactly between the PSD's breakpoints) and
    d mu/dG = R S(P) P with R constant (the contact weight is integrated by Gauss-Legendre to ~1e-9 per piece):
    no grid error at all."""
    area, mu = closed_form_constant_modulus(5e6, 2e6, 0.5, SIGMA0, 0.8, 1e3, 1e7, 20e-6)
    for ppd in (4, 8, 32):
        r = benchmark_model.replace(grid=persson.GridSettings(q_per_decade=ppd)).friction(1.0, pressure=SIGMA0)
        assert r.mu == pytest.approx(mu, rel=1e-8)
        assert r.contact_area == pytest.approx(area, rel=1e-10)
        assert r.error_estimate < 1e-8


def test_scalar_speed_gives_scalars_and_per_scale_rows(benchmark_model):
    r = benchmark_model.friction(0.5, pressure=SIGMA0)
    assert isinstance(r.mu, float) and isinstance(r.contact_area, float)
    assert r.area_q.shape == (1, r.q.size) and r.G_q.shape == (1, r.q.size)
    assert r.area_q[0, 0] == 1.0 and np.all(np.diff(r.area_q[0]) <= 0)
    assert r.q[0] == pytest.approx(1e3) and r.q[-1] == pytest.approx(1e7)


def test_small_load_limit_area_proportional_to_pressure():
    """A/A0 -> sqrt(8/pi) sigma0 / (E* h'_rms) when G(q1) >> 1 (Persson 2001, Eq. 21 limit)."""
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6)
    m = materials.ConstantModulus(E_storage=5e6, E_loss=0.0)
    Es = 5e6 / 0.75
    for sigma0 in (1e2, 1e3):
        r = persson.Model(s, m, gamma=1.0).friction(1.0, pressure=sigma0)
        expected = math.sqrt(8 / math.pi) * sigma0 / (Es * s.rms_slope())
        assert r.contact_area == pytest.approx(expected, rel=2e-3)


def test_elastic_material_has_no_hysteresis_friction():
    s = surfaces.SelfAffine(hurst=0.7, q0=1e3, q1=1e6, hrms=10e-6)
    r = persson.Model(s, materials.ConstantModulus(5e6, 0.0)).friction([0.1, 1.0], pressure=SIGMA0)
    np.testing.assert_allclose(r.mu, 0.0, atol=1e-20)


# --- viscoelastic case against a slow independent quadrature ----------------------------------------------
PRONY = dict(E_inf=2e6, E_i=[5e6, 4e7, 3e8], tau_i=[1e-2, 1e-4, 1e-6])
VISCO_SURFACE = dict(hurst=0.75, q0=2e3, q1=1e6, hrms=30e-6)


def prony_modulus(E_inf, E_i, tau_i):
    r"""The Prony series written out in plain floats, independent of :class:`materials.Prony`.

    Generalized Maxwell model, :math:`E(\omega) = E_\infty + \sum_i E_i\, i\omega\tau_i / (1 + i\omega\tau_i)`
    (Ferry, Viscoelastic Properties of Polymers, 3rd ed., Wiley 1980, ch. 3; Tschoegl, The Phenomenological Theory of
    Linear Viscoelastic Behavior, Springer 1989, ch. 4). One scalar call costs a microsecond, which the adaptive
    angular quadratures below make hundreds of thousands of.
    """
    terms = tuple(zip(E_i, tau_i))

    def E(omega):
        real, imag = E_inf, 0.0
        for Ei, tau in terms:
            x = omega * tau
            d = Ei / (1.0 + x * x)
            real += d * x * x
            imag += d * x
        return complex(real, imag)

    return E


def slow_reference(surface, E, v, sigma0, nu, gamma, n_q=601):
    """Direct evaluation: adaptive quad over the angle at each q of a fine log grid, Simpson in ln q.

    ``E(omega) -> complex`` is the modulus (scalar calls).
    """
    q = np.geomspace(*surface.q_range, n_q)
    Es_scale = 1 / ((1 - nu**2) * sigma0)

    def ang(qq, f):
        return 4 * integrate.quad(lambda p: f(E(qq * v * math.cos(p))), 0, math.pi / 2,
                                  epsabs=0, epsrel=1e-10, limit=200)[0]

    abs2 = np.array([ang(qq, lambda e: abs(e) ** 2) for qq in q])
    loss = np.array([4 * integrate.quad(lambda p: math.cos(p) * E(qq * v * math.cos(p)).imag,
                                        0, math.pi / 2, epsabs=0, epsrel=1e-10, limit=200)[0] for qq in q])
    C = surface.C(q)
    x = np.log(q)
    gint = 0.125 * q**4 * C * abs2 * Es_scale**2
    G = integrate.cumulative_simpson(gint, x=x, initial=0.0)
    P = np.where(G > 0, erf(0.5 / np.sqrt(np.maximum(G, 1e-300))), 1.0)
    S = gamma + (1 - gamma) * P**2
    mu = integrate.simpson(0.5 * q**4 * C * S * P * loss * Es_scale, x=x)
    return mu, P[-1]


@functools.cache
def visco_reference(v):
    """(mu, A/A0) of the Prony compound on the viscoelastic test surface at speed v, by :func:`slow_reference`
    (computed once per speed for the tests that share it)."""
    return slow_reference(surfaces.SelfAffine(**VISCO_SURFACE), prony_modulus(**PRONY), v, SIGMA0, 0.5, 0.5)


@pytest.mark.parametrize("v", [1e-4, 1e-2, 1.0])
def test_viscoelastic_default_grid_matches_slow_quadrature(v):
    s = surfaces.SelfAffine(**VISCO_SURFACE)
    m = materials.Prony(**PRONY)
    mu_ref, area_ref = visco_reference(v)
    r = persson.Model(s, m, nu=0.5, gamma=0.5).friction(v, pressure=SIGMA0)
    assert r.mu_hysteresis == pytest.approx(mu_ref, rel=1e-3)
    assert r.contact_area == pytest.approx(area_ref, rel=1e-3)


def test_viscoelastic_grid_convergence_is_monotone_towards_reference():
    s = surfaces.SelfAffine(**VISCO_SURFACE)
    m = materials.Prony(**PRONY)
    mu_ref, _ = visco_reference(1e-2)
    errs = []
    for k in (1, 2, 4):
        g = persson.GridSettings(q_per_decade=8 * k, omega_per_decade=10 * k, max_refinement=0)
        errs.append(abs(persson.Model(s, m, grid=g).friction(1e-2, pressure=SIGMA0).mu / mu_ref - 1))
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 1e-3


def test_temperature_shifts_the_curve_by_wlf():
    """E(omega, T) = E(omega a_T, T_ref): mu(v, T) = mu(v a_T, T_ref) (time-temperature superposition)."""
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6)
    wlf = materials.WLF(C1=8.86, C2=101.6, T_ref=20.0)
    m = materials.Prony(wlf=wlf, **PRONY)
    model = persson.Model(s, m)
    aT = float(wlf.aT(50.0))
    v = np.array([1e-3, 1e-1])
    hot = model.friction(v, temperature=50.0, pressure=SIGMA0)
    ref = model.friction(v * aT, temperature=20.0, pressure=SIGMA0)
    np.testing.assert_allclose(hot.mu, ref.mu, rtol=2e-3)


def test_results_cite_the_physics(benchmark_model):
    r = benchmark_model.friction(1.0, pressure=SIGMA0)
    assert "10.1063/1.1388626" in r.citations


# --- bad input ----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, word", [
    (dict(speed=0.0), "speed"), (dict(speed=-1.0), "speed"), (dict(speed=[1.0, np.nan]), "speed"),
    (dict(speed=1.0, pressure=0.0), "pressure"), (dict(speed=1.0, pressure=-1e5), "pressure"),
    (dict(speed=1.0, pressure=np.nan), "pressure"), (dict(speed=1.0, temperature=np.nan), "temperature"),
    (dict(speed="fast"), "speed"),
])
def test_bad_conditions_raise_input_error_naming_the_argument(benchmark_model, kwargs, word):
    with pytest.raises(persson.InputError, match=word):
        benchmark_model.friction(**kwargs)


@pytest.mark.parametrize("kwargs, word", [
    (dict(nu=0.6), "nu"), (dict(nu=-0.1), "nu"), (dict(nu=np.nan), "nu"),
    (dict(gamma=1.5), "gamma"), (dict(gamma=-0.1), "gamma"), (dict(gamma=np.nan), "gamma"),
])
def test_bad_model_parameters_raise(kwargs, word):
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6)
    with pytest.raises(persson.InputError, match=word):
        persson.Model(s, materials.ConstantModulus(5e6, 2e6), **kwargs)


def test_bad_cutoffs_and_nan_surface_raise():
    with pytest.raises(surfaces.InputError, match="q1"):
        surfaces.SelfAffine(hurst=0.8, q0=1e7, q1=1e3, hrms=20e-6)
    with pytest.raises(surfaces.InputError, match="q1"):
        surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e3, hrms=20e-6)
    with pytest.raises(surfaces.InputError, match="hrms"):
        surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=np.nan)
    with pytest.raises(surfaces.InputError, match="row"):
        surfaces.PSD([1e3, 1e4, 1e5], [1e-20, np.nan, 1e-24])


def test_material_returning_nan_is_refused():
    class Broken:
        def E(self, omega, T=None):
            return np.full(np.shape(omega), np.nan + 0j)

    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6)
    with pytest.raises(persson.InputError, match="material"):
        persson.Model(s, Broken()).friction(1.0, pressure=SIGMA0)


# --- one temperature and pressure per speed ----------------------------------------------------------------
def _per_speed_vs_separate(model, rtol):
    v = np.array([1e-4, 1e-2, 0.3, 3.0, 0.3])
    T = np.array([0.0, 20.0, 35.0, 60.0, 20.0])
    p = np.array([0.2e6, 0.3e6, 0.5e6, 0.3e6, 0.8e6])
    r = model.friction(v, temperature=T, pressure=p)
    ref = np.array([model.friction(vi, temperature=Ti, pressure=pi).mu for vi, Ti, pi in zip(v, T, p)])
    area = np.array([model.friction(vi, temperature=Ti, pressure=pi).contact_area for vi, Ti, pi in zip(v, T, p)])
    np.testing.assert_allclose(r.mu, ref, rtol=rtol)
    np.testing.assert_allclose(r.contact_area, area, rtol=rtol)
    np.testing.assert_array_equal(r.temperature, T)
    np.testing.assert_array_equal(r.pressure, p)


def test_per_speed_temperature_and_pressure_equal_separate_calls():
    """Speeds at other temperatures are shifted onto one modulus table (WLF); they agree with separate calls."""
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6)
    m = materials.Prony(wlf=materials.WLF(8.86, 101.6, 20.0), **PRONY)
    _per_speed_vs_separate(persson.Model(s, m), rtol=1e-5)
    _per_speed_vs_separate(persson.Model(s, materials.example_tread(), effects=[persson.effects.FlashTemperature(),
                                                                               persson.effects.Adhesion()]),
                           rtol=1e-4)


def test_per_speed_temperature_applies_the_vertical_shift():
    class Shifted:
        """E(omega, T) = b_T E_ref(omega a_T): WLF horizontally, b_T = 1 + 0.01 (T - 20) vertically."""

        base = materials.Prony(**PRONY)
        wlf = materials.WLF(8.86, 101.6, 20.0)

        def log10_aT(self, T):
            return self.wlf.log10_aT(T)

        def log10_bT(self, T):
            return np.log10(1 + 0.01 * (np.asarray(T, dtype=float) - 20.0))

        def E(self, omega, T=None):
            T = 20.0 if T is None else T
            return 10 ** self.log10_bT(T) * self.base.E(np.asarray(omega) * 10 ** self.log10_aT(T))

    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6)
    _per_speed_vs_separate(persson.Model(s, Shifted()), rtol=1e-5)


def test_per_speed_temperature_without_shift_law_is_evaluated_per_temperature():
    class Heating:
        """Temperature-dependent, but with no shift law: each temperature gets its own table."""

        def E(self, omega, T=None):
            T = 20.0 if T is None else float(T)
            return (5e6 + 0.05e6 * T) + 1j * 2e6 * np.sign(omega)

    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=20e-6)
    _per_speed_vs_separate(persson.Model(s, Heating()), rtol=1e-12)


def _master_curve():
    """A measured master curve (the shipped example case's compound)."""
    import validation

    return validation.load_case("example").model.material


@pytest.mark.parametrize("material", ["prony", "master curve", "strain softened"])
@pytest.mark.parametrize("flash", [False, True])
@pytest.mark.filterwarnings("ignore:friction coefficient")  # the hot, slow rows: the compound's rubbery plateau
def test_a_speeds_friction_does_not_depend_on_the_other_conditions_of_its_call(material, flash):
    """A master-curve material is tabulated at its own T_ref, and every angular table reaches down to the same
    frequency: the friction at a condition is the same alone and in a call with colder, hotter and slower, faster
    or other-pressure rows (to rounding; with the call's median temperature as the table temperature and the
    table's bottom at each call's lowest frequency, these rows changed it by 2e-9 to 3e-8)."""
    base = {"prony": lambda: materials.Prony(wlf=materials.WLF(8.86, 101.6, 20.0), **PRONY),
            "master curve": _master_curve,
            "strain softened": lambda: materials.StrainSoftened(_master_curve(), storage_factor=0.6,
                                                                loss_factor=0.8)}[material]()
    effects = [persson.effects.FlashTemperature()] if flash else []
    model = persson.Model(surfaces.example_road(), base, effects=effects)
    v = np.array([1e-3, 1e-2, 0.1, 1.0])
    T = np.array([20.0, 20.0, 45.0, 45.0])
    p = np.full(4, 3e5)
    alone = np.array([model.friction(v[i], temperature=T[i], pressure=p[i]).mu for i in range(4)])
    for ve, Te, pe in ((np.array([1e-3, 0.1, 1.0, 3.0]), np.full(4, -10.0), p),          # colder
                       (np.array([1e-7, 1e-6, 1e-5, 1e-4]), np.full(4, 80.0), p),        # hotter and slower
                       (np.array([10.0, 20.0, 30.0, 30.0]), np.full(4, 20.0), p),        # faster
                       (v, T, np.full(4, 6e5))):                                         # another pressure
        together = model.friction(np.concatenate([v, ve]), temperature=np.concatenate([T, Te]),
                                  pressure=np.concatenate([p, pe])).mu[:4]
        np.testing.assert_allclose(together, alone, rtol=1e-13, atol=0)


def test_the_table_temperature_is_the_master_curves_reference_whatever_the_call():
    """:func:`persson.engine.solver.table_temperature`: T_ref for a material with a shift law and a reference
    temperature; the call's temperature (its median when they differ) for one without T_ref."""
    from persson.engine.solver import table_temperature

    prony = materials.Prony(wlf=materials.WLF(8.86, 101.6, 35.0), **PRONY)
    assert prony.T_ref == 35.0
    assert table_temperature(prony, np.array([0.0, 60.0, 80.0])) == 35.0
    assert table_temperature(_master_curve(), np.array([-20.0])) == _master_curve().T_ref

    class NoReference:
        def log10_aT(self, T):
            return -0.1 * (np.asarray(T, dtype=float) - 20.0)

    assert table_temperature(NoReference(), np.array([0.0, 10.0, 50.0])) == 10.0
    assert table_temperature(NoReference(), np.array([7.0, 7.0])) == 7.0
    still = materials.Prony(**PRONY)     # no shift law: no T_ref, temperature-independent
    assert still.T_ref is None and table_temperature(still, np.array([5.0, 9.0])) == 7.0


def test_every_angular_table_reaches_down_to_the_same_frequency():
    """Whatever the lowest frequency a call looks up, the table starts at ANGULAR_LOW (lower only where a call
    looks up within the pad of it), so a value at a given frequency comes from the same table nodes."""
    from persson.engine.tabulate import ANGULAR_LOW, ANGULAR_PAD_DECADES, angular_table

    m = materials.Prony(wlf=materials.WLF(8.86, 101.6, 20.0), **PRONY)
    a = angular_table(m, 20.0, -3.0, 8.0, 40)
    b = angular_table(m, 20.0, 2.0, 9.0, 40)
    assert a.lw0 == b.lw0 == ANGULAR_LOW
    n = a.ln_are.size - 3
    np.testing.assert_array_equal(a.ln_are[:n], b.ln_are[:n])
    deep = angular_table(m, 20.0, ANGULAR_LOW, 8.0, 40)
    assert deep.lw0 <= ANGULAR_LOW - ANGULAR_PAD_DECADES


@pytest.mark.parametrize("kwargs, word", [
    (dict(speed=[1.0, 2.0], temperature=[20.0]), "temperature"),
    (dict(speed=[1.0, 2.0], pressure=[3e5, np.nan]), "pressure"),
    (dict(speed=[1.0, 2.0], pressure=[3e5, -1.0]), "pressure"),
])
def test_bad_per_speed_conditions_raise(benchmark_model, kwargs, word):
    with pytest.raises(persson.InputError, match=word):
        benchmark_model.friction(**kwargs)


def test_friction_only_leaves_out_the_contact_geometry_and_nothing_else():
    """Inside ``persson.solver.friction_only()`` (the diagnosis's predictions) the results carry no mean separation
    and penetration depth; every friction number is the one computed outside it."""
    from persson.solver import friction_only

    m = persson.Model(surfaces.example_road(), materials.example_tread(), effects=[persson.effects.FlashTemperature()])
    v = np.geomspace(1e-3, 3.0, 5)
    full = m.friction(v, temperature=0.0)
    with friction_only():
        lean = m.friction(v, temperature=0.0)
    assert lean.mean_separation is None and lean.penetration_depth is None
    assert np.all(full.mean_separation > 0) and np.all(full.penetration_depth >= 0)
    for name in ("mu", "mu_hysteresis", "contact_area", "max_flash_temperature", "error_estimate"):
        np.testing.assert_array_equal(getattr(lean, name), getattr(full, name))
    assert "mean_separation_m" not in lean.as_table() and "mean_separation_m" in full.as_table()
