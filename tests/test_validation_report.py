"""validation report: what a reader sees is labelled and honest (issue 25, item 7).

* the flash temperature is a rise above the background temperature: ``FrictionResult.flash_temperature_rise``
  (the same values as ``max_flash_temperature``, which keeps its name), and tables say so above their header;
* the "systematic deviations" of a comparison name every group with |z| >= 3, in the summary and the report,
  however many there are (more than six here);
* measured points carry error bars exactly when ``mu_std`` is given, on the speed and slip plots;
* a fitted model's curves carry a 68 % band from its parameters' covariance (the delta method): on adhesion, whose
  friction is linear in ``tau_f0``, the band's half-width equals the closed form of weighted linear least squares,
  |d mu/d tau_f0| / sqrt(sum_i (g_i / sigma_i)^2) with g_i = d mu_i / d tau_f0 at the measured rows (computed from
  two engine calls, independently of the fit); a model without a covariance, or with a parameter the data do not
  determine, has no band and says why.
"""

from dataclasses import replace

import numpy as np
import pytest

import materials
import persson
import surfaces
import validation
from persson.slip import Contact
from validation import plots
from validation import report as rep
from validation.compare import comparison_from
from validation.fitting import Fitter, ParameterSpace, free_parameters
from validation.predict import Prediction, Predictor
from validation.refit import global_fit, with_uncertainty

SURFACE = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e5, hrms=1e-4)
BASE = persson.Model(SURFACE, materials.example_tread())
TAU_TRUE = 2e5


def _adhesion(tau_f0, c=0.1):
    return BASE.with_effect(persson.effects.Adhesion(tau_f0=tau_f0, c=c, v_ref=1e-2))


def _fit(data, start, names):
    """The fit's own path: global fit, then the Gauss-Newton uncertainty (mu_std weights, s^2 = 1)."""
    space = ParameterSpace(free_parameters(start.effect("adhesion"), names=names))
    fitter = Fitter(Predictor(data), data.mu, 1.0 / data.mu_std, start, space, max_evals=60)
    fit = global_fit(fitter, space.u_of(start), n_screen=0, n_local=1)
    return with_uncertainty(fitter, fit, s2=1.0, profile=False)


@pytest.fixture(scope="module")
def adhesion_fit():
    """Eight sliding rows at 20 C with mu_std, adhesion data with noise; tau_f0 fitted."""
    v = np.geomspace(1e-3, 1.0, 8)
    std = np.linspace(0.01, 0.02, v.size)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=v, temperature=20.0, pressure=3e5, mu=0.5,
                                               mu_std=std)
    mu = validation.predict(_adhesion(TAU_TRUE), rows).mu + np.random.default_rng(3).normal(0.0, std)
    data = rows.with_mu(mu, mu_std=std)
    fit = _fit(data, _adhesion(1e5), ["tau_f0"])
    return data, fit


def _bands(fig):
    # fill_between's collection: a FillBetweenPolyCollection from matplotlib 3.10, a PolyCollection before
    return [c for ax in fig.axes for c in ax.collections
            if type(c).__name__ in ("FillBetweenPolyCollection", "PolyCollection")]


def _errorbars(fig):
    return [c for ax in fig.axes for c in ax.containers if type(c).__name__ == "ErrorbarContainer"]


# ---- the flash temperature is a rise ------------------------------------------------------------------------
def test_flash_temperature_rise_is_the_hottest_scale_above_the_background():
    model = BASE.with_effect(persson.effects.FlashTemperature())
    r = model.friction([0.01, 1.0], temperature=20.0, pressure=3e5)
    rise = r.flash_temperature_rise
    np.testing.assert_array_equal(rise, r.max_flash_temperature)
    np.testing.assert_allclose(rise, r.temperature_q.max(axis=1) - 20.0, rtol=1e-12)
    assert rise[1] > rise[0] > 0.0
    assert "RISE" in type(r).__doc__ and "flash_temperature_rise" in type(r).__doc__
    np.testing.assert_array_equal(r.as_table()["max_flash_temperature_K"], rise)   # the column keeps its name
    t = persson.sweeps.grid(BASE, speed=[0.01, 1.0])
    assert any("RISE" in c and "max_flash_temperature_K" in c for c in t.comments)


# ---- every systematic deviation -----------------------------------------------------------------------------
def test_every_group_with_a_systematic_deviation_is_named():
    temps = np.arange(8) * 10.0                       # eight temperature groups, each biased by +-0.05
    v = np.geomspace(1e-3, 1.0, 4)
    m = validation.Measurements.from_arrays(slip=1.0, speed=np.tile(v, temps.size),
                                            temperature=np.repeat(temps, v.size), pressure=3e5, mu=0.5)
    bias = np.repeat(np.where(np.arange(temps.size) % 2 == 0, 0.05, -0.05), v.size)
    wiggle = np.random.default_rng(0).normal(0.0, 0.002, m.n)
    pred = m.mu - bias - wiggle
    cmp = comparison_from(BASE, m, None, Prediction(mu=pred, mu_local=pred), name="many")
    worst = cmp.worst_groups()
    assert len([g for g in worst if g.factor == "temperature"]) == 8 and len(worst) > 6
    summary = cmp.summary()
    for g in worst:
        assert f"{g.factor} {g.label}: bias" in summary, g
    html = rep._deviations_html(cmp)
    assert f"{len(worst)} groups" in html
    for g in worst:
        assert f"{g.factor} {g.label}: bias" in html


# ---- error bars -----------------------------------------------------------------------------------------------
def test_measured_points_carry_error_bars_exactly_when_mu_std_is_given(adhesion_fit):
    data, fit = adhesion_fit
    contact = Contact(0.02, 0.01, 3e9, "parabolic")
    slips = np.array([0.02, 0.1, 1.0])
    rows = validation.Measurements.from_arrays(slip=slips, speed=1.0, temperature=20.0, pressure=3e5,
                                               mu=[0.3, 0.4, 0.45], mu_std=0.01, contact=contact)
    for m in (rows, rows.with_mu(rows.mu)):           # with mu_std, then without
        cmp = validation.compare(fit.model, m)
        figs = cmp.figures()
        assert set(figs) == {"mu_speed", "mu_slip", "residuals"}
        for name in ("mu_speed", "mu_slip"):
            assert bool(_errorbars(figs[name])) == (m.mu_std is not None), name
        assert not _bands(figs["mu_speed"]) and not _bands(figs["mu_slip"])   # not fitted: no band
    import matplotlib.pyplot as plt

    plt.close("all")


def test_log_axes_are_labelled_with_powers_of_ten_in_plain_text(adhesion_fit):
    """Decades read 10 to a superscript power (no mathtext to typeset), other ticks their value."""
    sup = dict(zip("-0123456789", "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079"))
    for e in range(-12, 13):
        assert plots._log_label(10.0**e) == "10" + "".join(sup[c] for c in str(e))
    assert plots._log_label(2e-3) == "0.002" and plots._log_label(0.0) == "" and plots._log_label(np.nan) == ""
    data, fit = adhesion_fit
    fig = validation.compare(fit.model, data).figures()["mu_speed"]
    fig.canvas.draw()
    ax = fig.axes[0]
    labels = {t.get_text() for t in ax.get_xticklabels() if t.get_visible() and t.get_text()}
    lo, hi = ax.get_xlim()
    expected = {plots._log_label(10.0**e) for e in range(int(np.ceil(np.log10(lo))), int(np.floor(np.log10(hi))) + 1)}
    assert expected and expected <= labels and not any("$" in t for t in labels)
    import matplotlib.pyplot as plt

    plt.close("all")


# ---- uncertainty bands ------------------------------------------------------------------------------------------
def test_band_of_a_linear_parameter_matches_weighted_least_squares(adhesion_fit):
    data, fit = adhesion_fit
    (est,) = fit.estimates
    assert est.method == "quadratic" and est.identified
    cmp = replace(validation.compare(fit.model, data, name="adhesion fitted"), covariance=fit.covariance)
    assert cmp.has_band
    fig = plots.plot_mu_speed(cmp)
    (band,) = _bands(fig)
    assert _errorbars(fig)
    xy = band.get_paths()[0].vertices
    x, inverse = np.unique(np.round(np.log10(xy[:, 0]), 9), return_inverse=True)
    width = np.array([np.ptp(xy[inverse == i, 1]) for i in range(x.size)])
    # independent: mu is linear in tau_f0, so d mu / d tau_f0 = (mu(tau) - mu(0)) / tau exactly
    speeds = 10.0 ** x

    def slope(v):
        return (_adhesion(TAU_TRUE).friction(v, temperature=20.0, pressure=3e5).mu
                - BASE.friction(v, temperature=20.0, pressure=3e5).mu) / TAU_TRUE

    sd_tau = 1.0 / np.sqrt(np.sum((slope(data.speed) / data.mu_std) ** 2))
    assert est.std == pytest.approx(sd_tau, rel=1e-3)
    expected = np.abs(slope(speeds)) * sd_tau
    # linear in the parameter, the delta method is exact (up to the finite-difference step): 0.1 %, not 20 %
    np.testing.assert_allclose(width / 2.0, expected, rtol=1e-3)
    assert "68 %" in fig.axes[0].get_legend().get_title().get_text()
    html = rep._band_caption_html(cmp)
    assert "68 % (1 sigma) band" in html and "adhesion.tau_f0" in html
    import matplotlib.pyplot as plt

    plt.close("all")


def test_band_of_two_correlated_parameters_matches_an_independent_linearisation():
    """tau_f0 and v_ref (fitted in log10) of a speed-dependent adhesion: the band against J C J^T built here in
    the parameters' own units, with derivatives and covariance from direct engine calls (not the fit's)."""
    v = np.geomspace(1e-4, 1.0, 9)
    std = np.full(v.size, 0.01)
    rows = validation.Measurements.from_arrays(slip=1.0, speed=v, temperature=20.0, pressure=3e5, mu=0.5,
                                               mu_std=std)
    truth = persson.effects.Adhesion(tau_f0=TAU_TRUE, c=0.3, v_ref=1e-2)
    mu = validation.predict(BASE.with_effect(truth), rows).mu + np.random.default_rng(5).normal(0.0, std)
    data = rows.with_mu(mu, mu_std=std)
    start = BASE.with_effect(persson.effects.Adhesion(tau_f0=1.5e5, c=0.3, v_ref=2e-2))
    fit = _fit(data, start, ["tau_f0", "v_ref"])
    assert all(e.identified and np.isfinite(e.std) for e in fit.estimates)
    cmp = replace(validation.compare(fit.model, data), covariance=fit.covariance)
    (band,) = _bands(plots.plot_mu_speed(cmp))
    xy = band.get_paths()[0].vertices
    x, inverse = np.unique(np.round(np.log10(xy[:, 0]), 9), return_inverse=True)
    width = np.array([np.ptp(xy[inverse == i, 1]) for i in range(x.size)])
    theta = {e.name: e.value for e in fit.estimates}

    def jac(speeds):
        cols = []
        for name in ("tau_f0", "v_ref"):
            d = 1e-3 * theta[name]
            mus = [BASE.with_effect(persson.effects.Adhesion(**{**theta, "c": 0.3, name: theta[name] + s * d}))
                   .friction(speeds, temperature=20.0, pressure=3e5).mu for s in (1.0, -1.0)]
            cols.append((mus[0] - mus[1]) / (2.0 * d))
        return np.column_stack(cols)

    Jd = jac(data.speed) / std[:, None]
    C = np.linalg.inv(Jd.T @ Jd)
    assert abs(C[0, 1]) / np.sqrt(C[0, 0] * C[1, 1]) > 0.1          # the cross term matters
    Jc = jac(10.0 ** x)
    expected = np.sqrt(np.einsum("ij,jk,ik->i", Jc, C, Jc))
    np.testing.assert_allclose(width / 2.0, expected, rtol=0.2)
    import matplotlib.pyplot as plt

    plt.close("all")


def test_no_band_without_a_covariance_or_with_an_undetermined_parameter(adhesion_fit):
    from validation.band import band_note

    data, fit = adhesion_fit
    plain = validation.compare(fit.model, data)
    assert not plain.has_band and not _bands(plots.plot_mu_speed(plain))
    # with c = 0 the shear stress does not depend on v_ref: its fit changes no prediction
    flat = _fit(data, _adhesion(TAU_TRUE, c=0.0), ["v_ref"])
    note = band_note(flat.covariance, ("adhesion.v_ref",))
    assert note.startswith("no uncertainty band") and "adhesion.v_ref" in note
    cmp = replace(plain, covariance=flat.covariance, band_note=note)
    fig = plots.plot_mu_speed(cmp)
    assert not cmp.has_band and not _bands(fig)
    assert any(note in t.get_text() for t in fig.texts)
    assert "adhesion.v_ref" in rep._band_caption_html(cmp)
    assert band_note(None, ()).startswith("no uncertainty band: no parameter was fitted")
    import matplotlib.pyplot as plt

    plt.close("all")
