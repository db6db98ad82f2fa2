"""The brush model driven by the Persson engine: mu-slip family, plots, CSV, case contact.

Contact parameters (documented choice, tire-like patch): contact length l = 0.1 m and width w = 0.15 m of a
passenger-car tire, mean pressure sigma0 = 0.3 MPa (about the inflation pressure), parabolic pressure, and shear
stiffness k = 9e7 Pa/m, i.e. k ~ G/h with G ~ 1.1 MPa (the example tread at low frequency, E ~ 3.4 MPa / 3) and an
effective height h ~ 12 mm (8 mm tread plus carcass compliance). The initial slope is then
k l/(2 sigma0) = 15, within the longitudinal slip stiffness C_Fkappa / F_z ~ 10-20 of passenger tires (Pacejka,
Tire and Vehicle Dynamics, ch. 1 and 3).
"""

import math

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson import slip as ps
from persson import slip as tire

SIGMA0 = 0.3e6
CONTACT = dict(length=0.1, width=0.15, stiffness=9.0e7, pressure_distribution="parabolic")
SLIPS = np.concatenate([np.geomspace(0.01, 0.6, 30), [0.8, 1.0]])
SPEEDS = np.array([0.3, 1.0, 3.0, 10.0])

flash_missing = getattr(persson.effects, "FlashTemperature", None) is None


def road():
    make = getattr(surfaces, "example_road", None)
    if make is not None:
        return make()
    return surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.35e-3)


@pytest.fixture(scope="module")
def family():
    model = persson.Model(road(), materials.example_tread(), effects=[persson.effects.FlashTemperature()])
    c = ps.Contact(**CONTACT)
    return ps.mu_slip(model, SLIPS[:, None], SPEEDS[None, :], temperature=20.0, pressure=SIGMA0, contact=c)


@pytest.mark.skipif(flash_missing, reason="persson.effects.FlashTemperature not available yet")
def test_engine_family_peak_and_locked_wheel(family):
    r = family
    assert r.mu.shape == (SLIPS.size, SPEEDS.size)
    assert r.converged
    assert r.friction.speed.size == np.unique(np.round(SLIPS[:, None] * SPEEDS[None, :], 12)).size
    peak_mu, slip_at_peak = r.peak(axis=0)
    j1 = int(np.flatnonzero(SPEEDS == 1.0)[0])
    print(f"\npeak mu {np.round(peak_mu, 4)} at slip {np.round(slip_at_peak, 4)}; locked mu {np.round(r.mu[-1], 4)}")
    assert 0.05 <= slip_at_peak[j1] <= 0.30
    assert peak_mu[j1] > r.mu[-1, j1]  # a real peak above the locked-wheel value
    locked = r.mu[-1]
    assert np.all(np.diff(locked) < 0)  # locked-wheel mu falls with speed
    # locked wheel is the engine's sliding friction at V
    assert np.allclose(locked, r.friction.mu[np.searchsorted(r.friction.speed, SPEEDS)], rtol=1e-12)
    # the Magic Formula describes the computed 1 m/s curve
    f = tire.fit_magic_formula(SLIPS, r.mu[:, j1])
    assert f.peak_mu == pytest.approx(peak_mu[j1], rel=0.03)
    assert f.locked_mu == pytest.approx(locked[j1], rel=0.03)


def constant_modulus_family():
    model = persson.Model(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6),
                          materials.ConstantModulus(E_storage=5e6, E_loss=2e6))
    c = ps.Contact(**CONTACT)
    return ps.mu_slip(model, SLIPS[:, None], SPEEDS[None, :], pressure=SIGMA0, contact=c)


def test_plots_and_csv(tmp_path):
    from matplotlib.figure import Figure

    from persson.plots import save_figure
    from persson.slip.plots import plot_mu_slip, plot_mu_speed, plot_two_coefficient_map

    r = constant_modulus_family()
    fits = [tire.fit_magic_formula(SLIPS, r.mu[:, j]) for j in range(SPEEDS.size)]
    fig = plot_mu_slip(r, fits=fits)
    assert isinstance(fig, Figure)
    assert len(fig.axes[0].get_legend().get_texts()) == SPEEDS.size
    p = save_figure(fig, tmp_path / "mu_slip.png")
    assert p.stat().st_size > 1000

    V = np.linspace(1.0, 30.0, 25)
    mu = tire.do_marsac_mosset(V, 0.8, 15.0, 1.5, 0.002) + np.random.default_rng(0).normal(0, 0.003, V.size)
    laws = [tire.fit_piarc(V, mu), tire.fit_do_marsac_mosset(V, mu), tire.fit_rado(V, mu)]
    fig2 = plot_mu_speed(V, mu, fits=laws)
    assert len(fig2.axes[0].get_lines()) == 1 + len(laws)
    assert save_figure(fig2, tmp_path / "mu_v.png").stat().st_size > 1000

    bm = ps.two_coefficient_map(np.linspace(0.5, 1.0, 6), np.linspace(5, 40, 8))
    fig3 = plot_two_coefficient_map(bm)
    assert save_figure(fig3, tmp_path / "map.png").stat().st_size > 1000

    out = r.to_csv(tmp_path / "mu_slip.csv")
    lines = [ln for ln in out.read_text().splitlines() if not ln.startswith("#")]
    assert lines[0].split(",")[:4] == ["slip", "speed_m_s", "sliding_speed_m_s", "mu"]
    assert len(lines) == 1 + SLIPS.size * SPEEDS.size


def test_case_contact_spec():
    # the form persson.case.CaseSpec.contact_model() builds from [contact]
    c = ps.Contact(length=0.02, width=0.01, stiffness=3.0e9, pressure_distribution={"sakai_n": 4.0})
    assert c.kind == "sakai" and c.sakai_n == 4.0
    assert c.initial_slope(SIGMA0) == pytest.approx(3.0e9 * 0.02 / (2 * SIGMA0))
