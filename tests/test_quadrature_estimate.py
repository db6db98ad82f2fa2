"""The quadrature-error estimate reads the solution and never changes it: a search may skip it at its trial points.

Inside ``persson.solver.quadrature_estimate(False)`` the engine solves every speed on the base nodes alone, without
the sub-grids of the estimate (plain solve) or the two coarse self-consistent solves (flash temperature). The
friction is then the full solve's to the last bit wherever the full solve refines no speed, and the base-node
friction of ``max_refinement=0`` where it would. The fits of the diagnosis solve their trial points so and their
reported point with the estimate (``Fitter.settle``); where the estimate refines that point, the search is made
again with it everywhere.
"""

import math
import warnings

import numpy as np
import pytest

import materials
import persson
import surfaces
import validation
from persson.effects import PatchHeating
from persson.slip import Contact, patch_friction
from persson.solver import quadrature_estimate, reuse_solutions
from validation.candidates import note_kind
from validation.fitting import Fitter, ParameterSpace, free_parameters
from validation.predict import Predictor
from validation.refit import ESTIMATE_NOTE, global_fit

V = np.geomspace(1e-3, 3.0, 6)

# the example road's rms slope is above 1 (a warning that says nothing about the quadrature)
pytestmark = pytest.mark.filterwarnings("ignore::persson.errors.PhysicsWarning")


def _road(*effects, **grid):
    return persson.Model(surfaces.example_road(), materials.example_tread(), effects=list(effects),
                         grid=persson.GridSettings(**grid))


def _glassy():
    """Glass transition centred at tau = 1e-8 s at 20 C: rubbery 3 MPa, glassy 2 GPa (|E|/sigma0 up to 1e5)."""
    tau = np.logspace(-14, -2, 25)
    w = np.exp(-0.5 * ((np.log10(tau) + 8.0) / 2.0) ** 2)
    return materials.Prony(E_inf=3e6, E_i=(2e9 - 3e6) * w / w.sum(), tau_i=tau, wlf=materials.WLF(8.86, 101.6, 20.0))


@pytest.mark.parametrize("speeds, temperature", [(V, 0.0), (np.geomspace(1e-8, 1e-5, 4), 80.0)],
                         ids=["cold", "hot and slow"])
@pytest.mark.parametrize("flash", [False, True], ids=["plain", "flash temperature"])
def test_without_the_estimate_the_friction_is_the_same_to_the_last_bit_where_nothing_is_refined(flash, speeds,
                                                                                                  temperature):
    model = _road(*([persson.effects.FlashTemperature()] if flash else []))
    full = model.friction(speeds, temperature=temperature)
    # nothing refined: every estimate below the third of the tolerance that triggers a refinement
    assert np.all(full.error_estimate < model.grid.tolerance / 3)
    with quadrature_estimate(False):
        lean = model.friction(speeds, temperature=temperature)
    assert np.all(np.isnan(lean.error_estimate))          # not estimated, and it says so
    for name in ("mu", "contact_area", "max_flash_temperature", "mu_cumulative", "temperature_q"):
        np.testing.assert_array_equal(getattr(lean, name), getattr(full, name))


@pytest.mark.parametrize("flash", [False, True], ids=["plain", "flash temperature"])
def test_without_the_estimate_a_hard_corner_is_solved_on_the_base_nodes_alone(flash):
    """Glassy rubber, cold and fast at low pressure on a coarse grid with a tight tolerance (1e-5): the full solve
    refines (its friction moves),
    the lean one is the base-node solve of max_refinement = 0, bit for bit, with no accuracy warning (nothing was
    estimated)."""
    effects = [persson.effects.FlashTemperature()] if flash else []
    s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=2e-4)
    v, T, p = np.array([0.3, 3.0, 30.0]), -20.0, 0.02e6

    def model(**grid):
        return persson.Model(s, _glassy(), effects=effects, grid=persson.GridSettings(q_per_decade=4, tolerance=1e-5,
                                                                                       **grid))

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        base = model(max_refinement=0).friction(v, temperature=T, pressure=p)
        refined = model().friction(v, temperature=T, pressure=p)
    assert np.any(base.error_estimate > model().grid.tolerance / 3)      # the corner is hard on this grid
    assert np.any(refined.mu != base.mu)                                  # and the full solve refines it
    with warnings.catch_warnings():
        warnings.simplefilter("error", persson.errors.AccuracyWarning)
        warnings.filterwarnings("ignore", category=persson.errors.PhysicsWarning)
        with quadrature_estimate(False):
            lean = model().friction(v, temperature=T, pressure=p)
    np.testing.assert_array_equal(lean.mu, base.mu)
    assert np.all(np.isnan(lean.error_estimate))


def test_kept_solutions_are_keyed_by_the_setting():
    """A solution kept without the estimate never serves a call that wants it (and the other way round)."""
    model = _road()
    with reuse_solutions() as memo:
        with quadrature_estimate(False):
            lean = model.friction(V, temperature=20.0)
        full = model.friction(V, temperature=20.0)
        with quadrature_estimate(False):
            again = model.friction(V, temperature=20.0)
    assert len(memo) == 2
    assert np.all(np.isnan(lean.error_estimate)) and np.all(np.isfinite(full.error_estimate))
    assert np.all(np.isnan(again.error_estimate))


class _Spy:
    """The engine, recording whether each of its calls estimated the quadrature error."""

    effect_names = ()

    def __init__(self, model):
        self.model = model
        self.material = model.material
        self.estimated = []

    def friction(self, speed, temperature=20.0, pressure=0.3e6):
        r = self.model.friction(speed, temperature=temperature, pressure=pressure)
        self.estimated.append(bool(np.all(np.isfinite(r.error_estimate))))
        return r


def test_patch_heating_tables_are_solved_with_the_estimate_inside_a_search():
    """The tables of the patch-heating march outlive the call that fills them and serve later calls with the
    estimate: they are always filled with it, so a search that skips it elsewhere builds the same table."""
    spy = _Spy(_road())
    heating = PatchHeating()
    contact = Contact(0.02, 0.01, 3.0e9, "parabolic", n_points=41)
    slip = np.array([0.05, 0.2, 1.0])
    with quadrature_estimate(False):
        lean = patch_friction(spy, heating, contact, slip, 2.0, 20.0, 0.3e6)
    assert spy.estimated and all(spy.estimated)
    full = patch_friction(_Spy(_road()), heating, contact, slip, 2.0, 20.0, 0.3e6)
    np.testing.assert_array_equal(lean.mu, full.mu)


def _adhesion_fit(model, tau_true=2e5):
    """Eight sliding rows with mu_std; the adhesion's tau_f0 fitted from 1e5 Pa."""
    rows = validation.Measurements.from_arrays(slip=1.0, speed=np.geomspace(1e-3, 1.0, 8), temperature=20.0,
                                               pressure=3e5, mu=0.5, mu_std=0.01)
    truth = model.with_effect(persson.effects.Adhesion(tau_f0=tau_true, c=0.1, v_ref=1e-2))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        y = validation.predict(truth, rows).mu + np.random.default_rng(5).normal(0.0, 0.01, rows.n)
    start = model.with_effect(persson.effects.Adhesion(tau_f0=1e5, c=0.1, v_ref=1e-2))
    space = ParameterSpace(free_parameters(start.effect("adhesion"), names=["tau_f0"]))
    predictor = Predictor(rows.with_mu(y, mu_std=np.full(rows.n, 0.01)))
    fitter = Fitter(predictor, y, np.full(rows.n, 100.0), start, space, max_evals=40)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit = global_fit(fitter, space.u_of(start), n_screen=4, n_local=1)
        reported = predictor.predict(fit.model).mu          # solved with the estimate, outside any search
    return fitter, fit, y, reported


@pytest.mark.parametrize("hard", [False, True], ids=["nothing refined", "refined at the optimum"])
def test_a_fits_reported_point_is_the_prediction_with_the_estimate(hard):
    """The reported mu and chi2 are those of the prediction solved with the estimate, bit for bit. Where nothing
    is refined the search keeps skipping the estimate; where the estimate refines the reported point (a grid with
    a tolerance of 1e-7), the search is made again with it at every trial point."""
    grid = dict(q_per_decade=6, tolerance=1e-7) if hard else {}
    fitter, fit, y, reported = _adhesion_fit(_road(**grid))
    np.testing.assert_array_equal(fit.mu, reported)
    assert fit.chi2 == pytest.approx(float(np.sum(((y - reported) * 100.0) ** 2)), rel=1e-12)
    assert fitter.fast is (not hard)
    assert (ESTIMATE_NOTE in fit.notes) is hard            # a search made again says so
    assert note_kind(ESTIMATE_NOTE) == "refined_search"
    assert math.isfinite(fit.chi2) and 0.0 < fit.u[0] < 1.0


def test_the_diagnosis_reports_the_same_numbers_as_a_search_with_the_estimate_everywhere(monkeypatch):
    """On a shipped case (whose fits refine no reported point) the diagnosis with the estimate skipped at the
    trial points gives every number of its JSON as with the estimate at every point; only the count of model
    evaluations (the reported points solved again) and the timing differ."""
    case = validation.load_case("hidden_adhesion")

    def strip(d):
        out = d.to_dict()
        for key in ("seconds", "n_evaluations"):
            out["baseline"].pop(key, None)
        return out

    lean = strip(validation.diagnose(case.model, case.measurements, contact=case.contact))
    init = Fitter.__init__

    def everywhere(self, *args, **kwargs):
        init(self, *args, **kwargs)
        self.fast = False

    monkeypatch.setattr(Fitter, "__init__", everywhere)
    full = strip(validation.diagnose(case.model, case.measurements, contact=case.contact))
    assert lean == full
