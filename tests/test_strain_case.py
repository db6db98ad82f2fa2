"""Measured strain factors from a case file, and what the friction owes to strains nobody measured.

Strain sweeps declared in ``[material] strain_sweeps`` drive the strain_softening effect with per-scale factors,
exactly as ``read_strain_sweep`` + ``strain_factors`` + ``StrainSoftening(factors=...)`` do in a script; a declared
input that would not be used is refused. Beyond the largest measured strain the factors follow a documented rule
(hold, log-linear trend, a user table), and every result reports the share of mu_hysteresis that comes from there.
"""

import math
import warnings

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.effects import StrainSoftening, strain_extrapolation_spread
from persson.engine.reference import reference_friction

GRID = persson.GridSettings(q_per_decade=8)
ROAD = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e5, hrms=0.2e-3)
TREAD = materials.example_tread()
SWEEP_TEMPERATURES = (0, 25, 50)
#: Largest strain of the sweeps: 32 %, as in real tread data.
STRAIN_PCT = np.geomspace(0.1, 32.0, 10)


def kraus_factors(strain, T):
    """Payne effect of a filled compound (Kraus form): E' falls to 25-40 % of its linear value around 2 % strain, E''
    goes through a maximum there."""
    x = (np.asarray(strain) / 0.02) ** 1.2
    f = (0.25 + 0.003 * T) + (0.75 - 0.003 * T) / (1 + x)
    return f, f + 1.5 * x / (1 + x) ** 2


def write_case(folder, model_extra="", material_extra='strain_sweeps = ["sweeps"]', effects='["strain_softening"]'):
    """A case folder: a road PSD table, a master curve, strain sweeps as a DMA exports them (%, MPa, one file per
    temperature), and a case.toml."""
    folder.mkdir(parents=True, exist_ok=True)
    ROAD.tabulate(6).to_csv(folder / "surface_psd.csv", overwrite=True)
    f = np.logspace(-8, 14, 45)
    E = TREAD.E(2 * np.pi * f, 20.0)
    persson.io.write_csv(folder / "master_curve.csv", {"f_Hz": f, "E_storage_Pa": E.real, "E_loss_Pa": E.imag},
                         overwrite=True)
    sweeps = folder / "sweeps"
    sweeps.mkdir(exist_ok=True)
    for T in SWEEP_TEMPERATURES:
        fs, gs = kraus_factors(STRAIN_PCT / 100, T)
        rows = "".join(f"{s:.6g}\t{8.0 * (1 - T / 100) * a:.8g}\t{2.0 * (1 - T / 120) * b:.8g}\n"
                       for s, a, b in zip(STRAIN_PCT, fs, gs))
        (sweeps / f"sweep_T{T}.txt").write_text("Strain\tE'\tE''\n[%]\t[MPa]\t[MPa]\n" + rows)
    (folder / "case.toml").write_text(f"""name = "tread"
[surface]
psd = "surface_psd.csv"
[material]
master_curve = "master_curve.csv"
wlf = {{ C1 = 8.86, C2 = 101.6, T_ref_C = 20.0 }}
{material_extra}
[model]
effects = {effects}
grid = {{ q_per_decade = 8 }}
{model_extra}
[conditions]
speeds_m_s = [0.01, 1.0]
""")
    return folder / "case.toml"


@pytest.fixture(scope="module")
def case_dir(tmp_path_factory):
    return write_case(tmp_path_factory.mktemp("tread")).parent


def read(path):
    from persson.case.loader import read_case

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", persson.PhysicsWarning)
        return read_case(path)


def friction(model, v=(0.01, 1.0)):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", persson.PhysicsWarning)
        return model.friction(np.array(v), temperature=20.0, pressure=0.3e6)


# ---------------------------------------------------------------------------------------------------------
def test_case_strain_sweeps_give_the_numbers_of_the_api(case_dir):
    spec = read(case_dir / "case.toml")
    sweeps = materials.read_strain_sweep(case_dir / "sweeps")
    api = persson.Model(spec.model.surface, spec.model.material, grid=GRID,
                        effects=[StrainSoftening(factors=materials.strain_factors(sweeps))])
    a, b = friction(spec.model), friction(api)
    np.testing.assert_allclose(a.mu, b.mu, rtol=1e-12)
    np.testing.assert_allclose(a.contact_area, b.contact_area, rtol=1e-12)
    # and they are not the constant factors of old (f = 0.5, g = 0.7), which the case file used to run with
    const = friction(spec.model.replace(effects=(StrainSoftening(),)))
    assert np.all(np.abs(a.mu / const.mu - 1) > 0.02)


def test_a_factor_table_in_the_case_is_read_as_the_api_reads_it(case_dir, tmp_path):
    folder = tmp_path / "table"
    write_case(folder, material_extra="", model_extra='[model.strain_softening]\nfactors = "factors.txt"')
    (folder / "factors.txt").write_text("# exported factors\nstrain_pct f g\n0.1 1.0 1.0\n5 0.55 1.3\n"
                                        "50 0.3 0.8\n")
    spec = read(folder / "case.toml")
    table = materials.read_strain_factors(folder / "factors.txt")
    assert table.strain_range == pytest.approx((1e-3, 0.5))
    api = spec.model.replace(effects=(StrainSoftening(factors=table),))
    np.testing.assert_allclose(friction(spec.model).mu, friction(api).mu, rtol=1e-12)
    assert folder / "factors.txt" in spec.inputs  # a command never writes over it


@pytest.mark.parametrize("material_extra, model_extra, words", [
    ('strain_sweeps = ["sweeps"]', '[model.strain_softening]\nfactors = "constant"',
     ["factors = 'constant'", "would not be used"]),
    ('strain_sweeps = ["sweeps"]', '[model.strain_softening]\nstorage_factor = 0.4',
     ["storage_factor", "not used with measured factors"]),
    ("", '[model.strain_softening]\nstrain_per_slope = 0.7', ["strain_per_slope", "only with measured factors"]),
    ("", '[model.strain_softening]\nfactors = "sweeps"', ["factors = \"sweeps\" needs strain sweeps"]),
    ("", '[model.strain_softening]\nfactors = "nowhere.txt"', ["[model.strain_softening] factors", "nowhere.txt",
                                                                 "does not exist"]),
])
def test_declared_inputs_that_would_not_be_used_are_refused(tmp_path, material_extra, model_extra, words):
    path = write_case(tmp_path / "c", material_extra=material_extra, model_extra=model_extra)
    with pytest.raises(persson.InputError) as err:
        read(path)
    for w in words:
        assert w in str(err.value)


def test_strain_sweeps_without_the_effect_are_refused(tmp_path):
    path = write_case(tmp_path / "c", effects="[]")
    with pytest.raises(persson.InputError, match="strain_sweeps .* strain_softening effect, which is not switched on"):
        read(path)


# ---------------------------------------------------------------------------------------------------------
def rms_slope_up_to(q):
    """xi(q) of the self-affine road in closed form: xi^2 = 2 pi C0 (q^(2-2H) - q0^(2-2H)) / (2 - 2H)."""
    H = ROAD.hurst
    return np.sqrt(2 * math.pi * ROAD.C0 * (q ** (2 - 2 * H) - ROAD.q0 ** (2 - 2 * H)) / (2 - 2 * H))


def sweep_table():
    e = STRAIN_PCT / 100
    f, g = zip(*(kraus_factors(e, T) for T in SWEEP_TEMPERATURES))
    return materials.StrainFactors(e, np.array(SWEEP_TEMPERATURES, float), np.array(f), np.array(g))


def test_extrapolated_share_matches_the_reference_quadrature():
    """The share of mu from scales beyond the largest measured strain, against an independent adaptive quadrature:
    1 - mu(q*)/mu(q1), q* where the local strain 0.5 xi(q*) reaches 32 % (closed form for the power law). Cold and
    fast (-10 C, 3 m/s: a stiff compound, the corner where the loss peak sweeps through the scales)."""
    sf, T, v = sweep_table(), -10.0, 3.0
    e_max = sf.strain_range[1]
    H, C0, q0 = ROAD.hurst, ROAD.C0, ROAD.q0
    q_star = ((2 * e_max) ** 2 * (2 - 2 * H) / (2 * math.pi * C0) + q0 ** (2 - 2 * H)) ** (1 / (2 - 2 * H))
    assert ROAD.q0 < q_star < ROAD.q1

    # the factors at the closed-form local strain, on a fine grid in ln q (a 4000-node interpolant: the quadrature
    # calls it thousands of times)
    x = np.linspace(math.log(ROAD.q0), math.log(ROAD.q1), 4001)
    f_x, g_x = sf.factors(0.5 * rms_slope_up_to(np.exp(x)), T)

    def factors(q):
        return float(np.interp(math.log(q), x, f_x)), float(np.interp(math.log(q), x, g_x))

    ref = reference_friction(ROAD, TREAD, v, T, 0.3e6, modulus_factors=factors, q_eval=[q_star, ROAD.q1],
                             rtol=1e-7, omega_per_decade=20)
    share_ref = 1 - ref.mu_at[0, 0] / ref.mu_at[0, 1]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", persson.PhysicsWarning)
        r = persson.Model(ROAD, TREAD, effects=[StrainSoftening(factors=sf)]).friction([v], temperature=T)
    assert 0.3 < share_ref < 0.99
    assert r.strain_extrapolated_share[0] == pytest.approx(share_ref, abs=1e-3)


def test_a_share_above_one_half_warns_and_every_share_is_noted(case_dir):
    spec = read(case_dir / "case.toml")
    with pytest.warns(persson.PhysicsWarning, match=r"of mu_hysteresis comes from length scales whose local strain"):
        r = spec.model.friction([0.01, 1.0], temperature=20.0, pressure=0.3e6)
    assert np.all(r.strain_extrapolated_share > 0.5)
    assert any("largest measured strain 0.32" in n for n in r.notes)
    assert "strain_extrapolated_share" in r.as_table()
    # with the constant factors there is nothing measured to exceed: no share, no note
    plain = friction(spec.model.replace(effects=(StrainSoftening(),)))
    assert plain.strain_extrapolated_share is None


def test_log_trend_continues_the_measured_line_and_a_table_takes_over():
    """Factors linear in ln(strain) over the last decade are continued exactly by the log-trend rule (to the floor
    of 5 %); a user table gives the factors past the measured strains."""
    e = np.geomspace(1e-3, 0.1, 9)
    f = 1.0 - 0.1 * np.log(e / 1e-3)          # slope -0.1 per unit ln(strain)
    g = 1.0 + 0.05 * np.log(e / 1e-3)
    sf = materials.StrainFactors(e, np.array([20.0]), f[None, :], g[None, :])
    eff = StrainSoftening(factors=sf, strain_per_slope=1.0, extrapolation="log_trend")
    strain = np.array([0.05, 0.3, 1.0, 100.0])
    fe, ge = eff.modulus_factors(strain, 20.0)
    line_f = 1.0 - 0.1 * np.log(strain / 1e-3)
    np.testing.assert_allclose(fe[:3], line_f[:3], rtol=1e-12)
    assert fe[3] == pytest.approx(0.05)  # the floor, not a negative modulus
    np.testing.assert_allclose(ge, 1.0 + 0.05 * np.log(strain / 1e-3), rtol=1e-12)
    held, _ = StrainSoftening(factors=sf, strain_per_slope=1.0).modulus_factors(strain, 20.0)
    np.testing.assert_allclose(held[1:], f[-1])
    user = materials.StrainFactors(np.array([0.1, 1.0]), np.array([0.0]), np.array([[0.4, 0.2]]),
                                   np.array([[1.2, 0.6]]))
    ft, gt = StrainSoftening(factors=sf, strain_per_slope=1.0, extrapolation=user).modulus_factors(strain, 20.0)
    assert ft[0] == pytest.approx(fe[0])  # below the largest measured strain: the measured factors
    assert ft[1] == pytest.approx(0.4 + (0.2 - 0.4) * math.log(3.0) / math.log(10.0))  # the table, in ln(strain)
    np.testing.assert_allclose(ft[2:], [0.2, 0.2])
    np.testing.assert_allclose(gt[2:], [0.6, 0.6])
    with pytest.raises(persson.InputError, match="extrapolation: expected one of 'hold', 'log_trend'"):
        StrainSoftening(factors=sf, extrapolation="linear")


def test_the_spread_between_rules_shows_the_sensitivity(case_dir):
    spec = read(case_dir / "case.toml")
    sp = strain_extrapolation_spread(spec.model, [0.01, 1.0])
    assert sp.rules == ("hold", "log_trend") and sp.rule == "hold"
    assert np.all(sp.extrapolated_share > 0.5)
    # the sweeps fall with strain up to 32 %: continuing that trend softens the smallest scales further
    assert np.all(sp.mu_hysteresis[1] < sp.mu_hysteresis[0])
    assert np.all(sp.spread > 0.05)
    assert "spread" in sp.summary()
    # a smooth surface whose strains stay inside the sweeps: the rules agree exactly
    smooth = spec.model.replace(surface=surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e4, hrms=2e-6))
    calm = strain_extrapolation_spread(smooth, [1.0])
    assert calm.extrapolated_share[0] == 0.0
    assert calm.spread[0] == 0.0
    with pytest.raises(persson.InputError, match="needs the strain_softening effect with measured factors"):
        strain_extrapolation_spread(spec.model.replace(effects=()), 1.0)


# ---------------------------------------------------------------------------------------------------------
def test_factor_tables_as_other_programs_export_them(tmp_path):
    # header-less: strain, f, g (absolute strain)
    (tmp_path / "plain.dat").write_text("0.001 1 1\n0.01 0.8 1.2\n0.1 0.5 0.9\n")
    a = materials.read_strain_factors(tmp_path / "plain.dat")
    assert a.temperature_range is None
    np.testing.assert_allclose(a.factors(0.01)[0], 0.8)
    # names and a units row, one file per temperature
    for T, k in ((0, 1.0), (40, 0.9)):
        (tmp_path / "tab" / "x").parent.mkdir(exist_ok=True)
        (tmp_path / "tab" / f"factors_T{T}.txt").write_text(
            f"Strain\tE'/E'0\tE''/E''0\n[%]\t[-]\t[-]\n0.1\t1\t1\n10\t{0.5 * k:g}\t{1.1 * k:g}\n")
    b = materials.read_strain_factors(tmp_path / "tab")
    assert b.temperature_range == (0.0, 40.0)
    np.testing.assert_allclose(b.factors(0.1, 20.0)[0], 0.5 * 0.95)
    # a temperature column in a long table
    (tmp_path / "long.csv").write_text("T_C,strain,f,g\n0,0.001,1,1\n0,0.1,0.5,1.2\n30,0.001,1,1\n30,0.1,0.6,1.1\n")
    c = materials.read_strain_factors(tmp_path / "long.csv")
    np.testing.assert_allclose(c.factors(0.1, 15.0), (0.55, 1.15))


@pytest.mark.parametrize("text, words", [
    ("strain,f,g\n0.1,1,1\n10,0.5,0.9\n", ["column 'strain'", "look like percent"]),
    ("strain_pct,E_storage_MPa,E_loss_MPa\n0.1,8,2\n10,4,2.2\n", ["no column for the storage factor",
                                                                  "read_strain_sweep"]),
    ("strain_pct,f,g\n0.1,8.1,2\n10,4,2.2\n", ["column 'f'", "moduli, not factors"]),
    ("strain_pct,f,g\n0.1,1,1\n10,-0.5,2.2\n", ["line 3", "column 'f'", "positive factor"]),
])
def test_bad_factor_tables_name_the_file_and_column(tmp_path, text, words):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(materials.InputError) as err:
        materials.read_strain_factors(path)
    assert str(path) in str(err.value)
    for w in words:
        assert w in str(err.value)
