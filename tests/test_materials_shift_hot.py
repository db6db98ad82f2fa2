"""Shift laws for hot rubber: WLF handing over to Arrhenius below T_g and above T_upper, their fits, the tabulated
law continued the same way, and the rule by which a friction result says that the shift law is extrapolated."""

import math
import pickle
import warnings

import numpy as np
import pytest

import materials
import persson
import surfaces
from materials import InputError

R = 8.314462618
LN10 = math.log(10.0)
C1, C2, T_REF = 8.86, 101.6, 20.0


def wlf_closed(T, C1=C1, C2=C2, T_ref=T_REF):
    return -C1 * (T - T_ref) / (C2 + T - T_ref)


def ferry_activation_energy(T, C1=C1, C2=C2, T_ref=T_REF):
    # Ferry (1980), ch. 11: apparent activation energy of WLF, 2.303 R c1 c2 T^2 / (c2 + T - T0)^2
    return LN10 * R * C1 * C2 * (T + 273.15) ** 2 / (C2 + T - T_ref) ** 2


def hand_over_closed(T, T_up, C1=C1, C2=C2, T_ref=T_REF):
    """WLF below T_up, Arrhenius above with Ferry's activation energy at T_up (written out here, not the package)."""
    T = np.asarray(T, dtype=float)
    Ea = ferry_activation_energy(T_up, C1, C2, T_ref)
    arr = wlf_closed(T_up, C1, C2, T_ref) + Ea / (R * LN10) * (1 / (T + 273.15) - 1 / (T_up + 273.15))
    return np.where(T > T_up, arr, wlf_closed(T, C1, C2, T_ref))


def one_sided_slopes(f, x, h=1e-3):
    """Left and right derivatives at x, second order (each from one side only)."""
    right = (-3 * f(x) + 4 * f(x + h) - f(x + 2 * h)) / (2 * h)
    left = (3 * f(x) - 4 * f(x - h) + f(x - 2 * h)) / (2 * h)
    return left, right


# ---------------------------------------------------------------------------------------------- the laws

def test_both_hand_overs_are_continuous_in_log_aT_and_its_slope():
    Tg, T_up = -30.0, 70.0
    law = materials.WLFArrhenius.from_constants(C1, C2, T_REF, T_g=Tg, T_upper=T_up)
    f = lambda t: float(law.log10_aT(t))  # noqa: E731
    for T_h in (Tg, T_up):
        assert f(T_h - 1e-9) == pytest.approx(f(T_h + 1e-9), abs=1e-9)
        left, right = one_sided_slopes(f, T_h)
        wlf_slope = -C1 * C2 / (C2 + T_h - T_REF) ** 2
        assert left == pytest.approx(wlf_slope, rel=1e-5) and right == pytest.approx(wlf_slope, rel=1e-5)
    # each branch is its closed form; the activation energies are Ferry's apparent ones at the hand-overs
    T = np.array([-60.0, -40.0, 0.0, 50.0, 90.0, 200.0])
    np.testing.assert_allclose(law.log10_aT(T)[2:], hand_over_closed(T[2:], T_up), rtol=1e-12, atol=1e-12)
    assert law.upper.E_a == pytest.approx(ferry_activation_energy(T_up), rel=1e-12)
    assert law.arrhenius.E_a == pytest.approx(ferry_activation_energy(Tg), rel=1e-12)
    assert list(law.law_at([-40.0, 0.0, 90.0])) == ["Arrhenius", "WLF", "Arrhenius"]
    # far above the hand-over the Arrhenius law shifts more than WLF would: its activation energy stays at the
    # hand-over value while WLF's falls (towards R ln10 C1 C2)
    assert law.log10_aT(200.0) < wlf_closed(200.0) - 0.5
    # moving the reference keeps the shape; pickling keeps the law
    moved = law.with_T_ref(40.0)
    np.testing.assert_allclose(moved.log10_aT(T), law.log10_aT(T) - law.log10_aT(40.0), atol=1e-12)
    np.testing.assert_allclose(pickle.loads(pickle.dumps(law)).log10_aT(T), law.log10_aT(T), rtol=0, atol=0)


def test_the_hand_over_from_an_activation_energy_is_where_wlf_has_that_slope():
    wlf = materials.WLF(C1, C2, T_REF)
    law = materials.with_arrhenius_above(wlf, E_a=70e3)
    # Ferry's activation energy at the found temperature is the one asked for
    assert ferry_activation_energy(law.T_upper) == pytest.approx(70e3, rel=1e-12)
    with pytest.raises(InputError, match="meets it in slope nowhere"):
        materials.with_arrhenius_above(wlf, E_a=0.5 * LN10 * R * C1 * C2)
    with pytest.raises(InputError, match="T_upper or the activation energy"):
        materials.TemperatureShift(wlf).with_upper(70.0, E_a=70e3)
    with pytest.raises(InputError, match="above T_g"):
        materials.WLFArrhenius.from_constants(C1, C2, T_REF, 250e3, -10.0, T_upper=-20.0)
    # the case-file form, and a Prony material that takes the law
    law = materials.shift.as_shift_law({"C1": C1, "C2": C2, "T_ref_C": T_REF, "T_upper": 70.0})
    assert law.T_upper == 70.0 and law.arrhenius is None
    tread = materials.with_arrhenius_above(materials.example_tread(), 70.0)
    assert tread.wlf.T_upper == 70.0 and tread.E(1e3, 20.0) == materials.example_tread().E(1e3, 20.0)


def test_fit_recovers_the_constants_and_the_hand_over_from_shift_factors():
    C1_t, C2_t, T_up = 9.3, 96.0, 65.0
    T = np.arange(-20.0, 141.0, 10.0)
    y = hand_over_closed(T, T_up, C1_t, C2_t, T_REF)
    fit = materials.fit_wlf(T, y, T_REF, T_upper="fit")
    assert fit.C1 == pytest.approx(C1_t, rel=1e-6) and fit.C2 == pytest.approx(C2_t, rel=1e-6)
    assert fit.T_upper == pytest.approx(T_up, abs=1e-4) and fit.rms < 1e-8
    # the hand-over given: C1, C2 from every isotherm, those above it included
    given = materials.fit_wlf(T, y, T_REF, T_upper=T_up)
    assert given.C1 == pytest.approx(C1_t, rel=1e-8) and given.upper.E_a == pytest.approx(
        ferry_activation_energy(T_up, C1_t, C2_t), rel=1e-7)
    # WLF alone cannot describe these shifts
    assert materials.fit_wlf(T, y, T_REF).rms > 100 * fit.rms
    # with noise of 0.02 decades the hand-over comes back within three standard errors
    rng = np.random.default_rng(7)
    noisy = materials.fit_wlf(T, y + rng.normal(0.0, 0.02, T.size), T_REF, T_upper="fit")
    assert abs(noisy.T_upper - T_up) < 3 * noisy.T_upper_stderr < 30.0
    law = noisy.law
    assert law.fitted_range == (-20.0, 140.0) and materials.fitted_temperature_range(law) == (-20.0, 140.0)


def test_a_tabulated_law_continues_with_the_same_hand_over():
    T_tab = np.arange(-30.0, 61.0, 10.0)
    tab = materials.TabulatedShift(T_tab, wlf_closed(T_tab), T_upper=70.0)
    T = np.array([65.0, 70.0, 75.0, 120.0, 200.0])
    with pytest.warns(UserWarning, match="outside the shift-factor table"):
        out = tab.log10_aT(T)
    np.testing.assert_allclose(out, hand_over_closed(T, 70.0), atol=1e-6)    # the WLF fit of the table, then Arrhenius
    f = lambda t: float(tab.log10_aT(t))  # noqa: E731
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        left, right = one_sided_slopes(f, 70.0)
    assert left == pytest.approx(right, rel=1e-5)
    assert "Arrhenius above 70 C" in tab.describe()
    assert pickle.loads(pickle.dumps(tab)).T_upper == 70.0
    assert materials.with_arrhenius_above(tab.with_T_ref(0.0), 80.0).T_upper == 80.0


# ---------------------------------------------------------------------------------------------- the warning rule

def test_the_note_names_the_range_and_what_continues_it():
    law = materials.TemperatureShift(materials.WLF(C1, C2, T_REF), fitted_range=(-20.0, 60.0))
    note = materials.extrapolated_shift_note
    assert note(law, -20.0, 60.0) is None and note(law, -20.9, 60.9) is None     # 1 K: isotherm scatter
    text = note(law, 20.0, 61.5)
    assert text.startswith(materials.SHIFT_RANGE_NOTE) and "(-20 to 60 C)" in text and "above" in text
    assert "with_arrhenius_above" in text                                          # the WLF law continued
    hot = law.with_upper(70.0)
    assert "Arrhenius above (E_a" in note(hot, 20.0, 150.0) and note(hot, 20.0, 150.0) == note(hot, 0.0, 300.0)
    assert note(materials.WLF(C1, C2, T_REF), -100.0, 500.0) is None               # no fitted range, no rule


@pytest.fixture(scope="module")
def fitted_material():
    tread = materials.example_tread()
    law = materials.TemperatureShift(tread.wlf, fitted_range=(-20.0, 60.0)).with_upper(70.0)
    return materials.Prony(tread.E_inf, tread.E_i, tread.tau_i, wlf=law, thermal=tread.thermal)


def test_a_flash_beyond_the_fitted_range_warns_once_and_notes_it(fitted_material):
    road = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3)
    grid = persson.GridSettings(q_per_decade=12, n_phi=16, omega_per_decade=20, tolerance=1e-2)
    model = persson.Model(road, fitted_material, effects=[persson.effects.FlashTemperature()], grid=grid)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = model.friction([3.0, 30.0], temperature=20.0, pressure=0.3e6)
    hot = float(np.max(r.temperature_q))
    assert hot > 62.0                                  # the flash takes the rubber beyond the fitted 60 C
    said = [w for w in caught if materials.SHIFT_RANGE_NOTE in str(w.message)]
    assert len(said) == 1 and issubclass(said[0].category, persson.PhysicsWarning)
    assert sum(materials.SHIFT_RANGE_NOTE in n for n in r.notes) == 1
    # slow sliding stays inside the range: nothing said
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        cool = model.friction([1e-4, 1e-3], temperature=20.0, pressure=0.3e6)
    assert float(np.max(cool.temperature_q)) < 60.0
    assert not any(materials.SHIFT_RANGE_NOTE in str(w.message) for w in caught)
    assert not any(materials.SHIFT_RANGE_NOTE in n for n in cool.notes)


def test_a_heated_patch_beyond_the_fitted_range_warns_once_per_slip_curve(fitted_material):
    # the friction tables call the engine several times and collect its notes; the curve says it once
    from persson import slip as ps

    road = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e5, hrms=0.2e-3)
    grid = persson.GridSettings(q_per_decade=12, n_phi=16, omega_per_decade=20, tolerance=1e-2)
    model = persson.Model(road, fitted_material, effects=[ps.PatchHeating()], grid=grid)
    contact = ps.Contact(0.12, 0.15, 1e8, n_points=51)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = ps.mu_slip(model, np.array([0.05, 0.3, 1.0]), 30.0, temperature=40.0, contact=contact)
    assert float(np.max(r.patch.temperature)) > 61.0
    assert sum(materials.SHIFT_RANGE_NOTE in str(w.message) for w in caught) == 1
    assert sum(materials.SHIFT_RANGE_NOTE in n for n in r.notes) == 1


def test_a_case_file_hands_the_wlf_law_over_to_arrhenius_above_T_upper_C(tmp_path):
    from persson.case import read_case

    case = tmp_path / "case.toml"
    case.write_text('[surface]\nexample = "road"\n[material]\nexample = "tread"\nT_upper_C = 90\n')
    m = read_case(case).model.material
    wlf = materials.example_tread().wlf
    # WLF's apparent activation energy at the hand-over, E = R ln10 C1 C2 T^2 / (C2 + T - T_ref)^2 (T in K)
    Tu = 90.0 + 273.15
    E = R * LN10 * wlf.C1 * wlf.C2 * Tu**2 / (wlf.C2 + 90.0 - wlf.T_ref) ** 2
    for T in (100.0, 150.0, 200.0):
        arrhenius = float(wlf.log10_aT(90.0)) + E / (R * LN10) * (1.0 / (T + 273.15) - 1.0 / Tu)
        assert float(m.log10_aT(T)) == pytest.approx(arrhenius, abs=1e-9)
    for T in (-20.0, 20.0, 89.0):
        assert float(m.log10_aT(T)) == pytest.approx(float(wlf.log10_aT(T)), abs=1e-12)
    case.write_text('[surface]\nexample = "road"\n[material]\nexample = "tread"\nT_upper_C = -90\n')
    with pytest.raises(persson.InputError, match="T_upper_C"):
        read_case(case)


def test_a_kept_friction_table_does_not_carry_a_hotter_solutions_note_over(fitted_material):
    # a fit keeps one table for every heating strength (the lattice does not depend on it): a hot solution grows
    # it beyond the fitted range; a cool one that follows says what a fresh table says, nothing
    from persson import slip as ps

    road = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e5, hrms=0.2e-3)
    grid = persson.GridSettings(q_per_decade=12, n_phi=16, omega_per_decade=20, tolerance=1e-2)
    model = persson.Model(road, fitted_material, grid=grid)
    contact = ps.Contact(0.12, 0.15, 1e8, n_points=51)
    rows = dict(slip=np.array([0.05, 0.3, 1.0]), speed=30.0, temperature=40.0, pressure=0.3e6)
    hot, cool = ps.PatchHeating(), ps.PatchHeating(heat_fraction=0.02)
    kept = {}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        first = ps.patch_friction(model, hot, contact, tables=kept, **rows)
        assert float(np.max(first.max_rise)) > 21.0        # 40 C + the rise: beyond the fitted 60 C
        assert sum(materials.SHIFT_RANGE_NOTE in n for n in first.notes) == 1
        caught.clear()
        after = ps.patch_friction(model, cool, contact, tables=kept, **rows)
        assert after.engine_calls == 0                     # the kept table served it
        warned_after = [str(w.message) for w in caught]
        fresh = ps.patch_friction(model, cool, contact, tables={}, **rows)
    assert float(np.max(after.max_rise)) < 19.0
    assert not any(materials.SHIFT_RANGE_NOTE in n for n in after.notes)
    assert not any(materials.SHIFT_RANGE_NOTE in m for m in warned_after)
    assert after.notes == fresh.notes
    np.testing.assert_allclose(after.mu, fresh.mu, rtol=1e-9)
