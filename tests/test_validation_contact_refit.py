"""validation: where a model's misfit sits in the rows with slip, the brush contact is refitted with the model's
parameters, and the verdict tells a contact given off (the refit brings every row to the noise, and the product of
stiffness and length the rows fix is the truth's) from a slip curve of another shape (the misfit stays).

The slip rows of the test case come from the engine on a converged grid (six times the default wavevector nodes,
a brush of 1601 nodes) with a softer, longer contact than the case gives: never from the diagnosis's own settings.
"""

import dataclasses
import importlib
import math
from types import SimpleNamespace

import numpy as np
import pytest

import persson
import validation
from validation.contact_refit import EARN, ContactRefit, defer_calibration, refit_contact
from validation.verdict import with_calibration
from validation.fitting import ParameterSpace, contact_parameters

#: A converged grid for the truth (finer than the diagnosis's default in every direction).
FINE = persson.GridSettings(q_per_decade=96, n_phi=64, omega_per_decade=120, temperature_step=0.1)


@pytest.fixture(scope="module")
def contact_off_case():
    """The shipped null case (nothing hidden) whose slip rows come from a contact a quarter as stiff and 1.5 times
    as long as the one the case gives."""
    case = validation.load_case("null")
    m = case.measurements
    s = m.slip < 1
    truth = dataclasses.replace(case.contact, stiffness=0.25 * case.contact.stiffness,
                                length=1.5 * case.contact.length, n_points=1601)
    mu_true = validation.predict(case.model.replace(grid=FINE), m, truth).mu
    mu = m.mu.copy()
    mu[s] = mu_true[s] + np.random.default_rng(5).normal(0.0, 0.004, int(s.sum()))
    return dataclasses.replace(case, measurements=m.with_mu(mu)), truth


def test_a_contact_given_off_is_found_by_the_refit_with_the_product_of_stiffness_and_length_it_fixes(
        contact_off_case):
    case, truth = contact_off_case
    dx = validation.diagnose(case, probe=False)
    assert dx.verdict.verdict in ("unexplained", "partly_explained")
    # the verdict quotes the baseline's tests as they read ("F = ...", "MPa"), case kept
    assert dx.baseline.lack.describe() in dx.verdict.reason and "MPa" in dx.baseline.pattern.describe()
    assert dx.baseline.pattern.describe() in dx.verdict.reason
    loc = dx.localized
    assert loc is not None and loc.family == "slip"
    cr = loc.contact
    assert isinstance(cr, ContactRefit) and cr.explains and cr.delta_bic <= -EARN and cr.p_value >= 0.01
    # the brush model's slip curve depends on stiffness x length: refitted together they correlate at -1 and fix
    # the truth's product, each factor need not be; no patch heating here to tell them apart, so the length does not
    # earn its place and the stiffness alone is kept, at the length given, with the same product
    assert cr.correlation < -0.9 and len(cr.both_fitted) == 2
    assert cr.both_fitted[0] * cr.both_fitted[1] == pytest.approx(truth.stiffness * truth.length, rel=0.1)
    assert cr.names == ("stiffness",) and cr.kept == (("length", case.contact.length),)
    assert cr.both_delta_bic > cr.delta_bic - EARN
    assert cr.fitted[0] * case.contact.length == pytest.approx(truth.stiffness * truth.length, rel=0.1)
    text = dx.verdict.localized
    assert "the contact given is off" in text and "product of stiffness and length" in text
    assert "length kept at 0.02 m as given" in text and "contact.stiffness in the fit" in text
    assert dx.as_dict()["localized"]["contact_refit"]["explains"] is True
    assert dx.as_dict()["localized"]["contact_refit"]["kept"] == {"length": case.contact.length}
    # an offset of the slip ratios moves the rise of a slip curve too: the rows prefer the contact here, so the
    # calibration check no longer names that offset as the rig's rival
    off = next(f for f in dx.calibration.fits if f.kind == "slip" and f.effects == ())
    assert cr.slip_offset == off.value and cr.slip_offset_gain == off.gain_over_set
    assert -cr.delta_bic - cr.slip_offset_gain >= EARN and "fits these rows less well" in text
    assert cr.preferred == "contact" and cr.effects == ()
    # here the offset does not bring the rows to the noise and is no rival of the baseline; where it is one, the
    # calibration check no longer names it, and says that the rows prefer the refitted contact
    assert not off.rival and dx.calibration.deferred == ()
    rival = dataclasses.replace(off, rival=True)
    check = dataclasses.replace(dx.calibration, fits=tuple(rival if f is off else f for f in dx.calibration.fits))
    assert rival in check.rivals
    deferred = defer_calibration(check, cr)
    assert [f for f, _, _ in deferred.deferred] == [rival] and rival not in deferred.rivals
    assert "slip ratios" in check.text() and "slip ratios" not in deferred.text()
    assert "slip ratios" not in with_calibration(dx.verdict, deferred).calibration
    d = deferred.as_dict()["deferred"][0]
    assert d["contact_better_by"] == pytest.approx(-cr.delta_bic - off.gain_over_set) and d["outcome"] == "explains"
    # only an offset fitted on the model the contact was refitted with is compared with it
    assert defer_calibration(check, dataclasses.replace(cr, effects=("adhesion",))) is check
    assert defer_calibration(check, dataclasses.replace(cr, delta_bic=-off.gain_over_set - 5.0)) is check
    # the report can cite what the sentence rests on: Chow's test and the brush model
    refs = " ".join(dx.references())
    assert "Chow" in refs and "Pacejka" in refs
    # the noise from local differences of every row is inflated by the misfit: the refit is judged against that of
    # the rows without slip, where the model fits
    m = case.measurements
    s = m.slip < 1
    assert dx.noise_estimate.source == "local differences" and cr.noise_from_rest
    rest = validation.estimate_noise(m.subset(~s), reference=dx.baseline.predicted[~s])
    assert cr.noise == pytest.approx(rest.sigma, rel=1e-12) and cr.noise < dx.noise_estimate.sigma
    assert "estimated from the rows without slip alone" in text
    # its figures are those of the model predicted again with the refitted contact, independently of the fit
    fitted = dataclasses.replace(case.contact, stiffness=cr.fitted[0])
    r = m.mu - validation.predict(dx.baseline.model, m, fitted).mu
    assert cr.slip_ratio == pytest.approx(math.sqrt(np.mean((r[s] / cr.noise) ** 2)), rel=1e-6)


def test_the_refit_is_not_made_again_where_the_contact_was_fitted_already():
    case = validation.load_case("null")
    space = ParameterSpace(contact_parameters(case.contact, ("stiffness", "length")))
    context = SimpleNamespace(settings=None, measurements=case.measurements)
    assert refit_contact(case.model, case.contact, space, case.measurements.mu, context) is None
    assert refit_contact(case.model, None, ParameterSpace(()), case.measurements.mu, context) is None


def test_the_text_of_a_contact_that_leaves_the_misfit_names_the_shape_of_the_slip_curve():
    stays = ContactRefit(names=("stiffness", "length"), given=(3e9, 0.02), fitted=(1.4e9, 0.026), p_value=2e-15,
                         ratio=4.97, slip_ratio=12.9, delta_bic=7.6, correlation=-0.999)
    assert not stays.explains
    assert "shape of the slip curve" in stays.text() and "3.64e+07 Pa against 6e+07 given" in stays.text()
    # a lower BIC is not enough: every row must be at the noise too
    assert not dataclasses.replace(stays, delta_bic=-50.0).explains
    assert dataclasses.replace(stays, delta_bic=-50.0, p_value=0.3).explains
    assert stays.as_dict()["correlation"] == -0.999 and stays.as_dict()["explains"] is False
    assert stays.outcome == "stays"


def test_a_contact_that_takes_most_of_the_misfit_but_not_all_says_so():
    most = ContactRefit(names=("stiffness", "length"), given=(3e9, 0.02), fitted=(1.3e8, 0.17), p_value=0.0095,
                        ratio=1.27, slip_ratio=1.40, delta_bic=-894.5, correlation=-0.999, slip_ratio_before=10.7)
    assert not most.explains and most.takes_most and most.outcome == "takes_most"
    assert "takes most of the misfit" in most.text() and "10.70 -> 1.40" in most.text()
    # more than half of the slip rows' residual left: the contact does not take most of it
    assert dataclasses.replace(most, slip_ratio=6.0).outcome == "stays"
    assert most.as_dict()["outcome"] == "takes_most"


def test_the_text_says_whether_the_rows_prefer_the_contact_or_an_offset_of_the_slip_ratios():
    refit = ContactRefit(names=("stiffness", "length"), given=(3e9, 0.02), fitted=(1.4e9, 0.015), p_value=0.4,
                         ratio=1.0, slip_ratio=1.0, delta_bic=-100.0, correlation=-0.999, slip_ratio_before=6.0)
    assert "offset of the slip ratios" not in refit.text()
    better = dataclasses.replace(refit, slip_offset=-0.003, slip_offset_gain=50.0)
    assert "less well: the refitted contact by 50.0 BIC units" in better.text()
    worse = dataclasses.replace(refit, slip_offset=-0.003, slip_offset_gain=130.0)
    assert "better, by 30.0 BIC units: check the slip measurement" in worse.text()
    tie = dataclasses.replace(refit, slip_offset=-0.003, slip_offset_gain=95.0)
    assert "cannot tell a contact given off from an offset" in tie.text()
    # an offset that earns less than the rule for an added parameter is not worth naming
    assert "offset" not in dataclasses.replace(refit, slip_offset=-0.003, slip_offset_gain=5.0).text()
    assert tie.as_dict()["slip_offset"] == -0.003 and refit.as_dict()["slip_offset"] is None
    assert (better.preferred, worse.preferred, tie.preferred, refit.preferred) == ("contact", "slip_offset", "either",
                                                                                    None)
    assert better.over_offset == 50.0 and tie.as_dict()["preferred"] == "either"


def test_the_length_is_kept_as_given_unless_refitting_it_with_the_stiffness_earns_its_place(monkeypatch):
    """The rule of the refit (validation.contact_refit): where stiffness and length correlate beyond -0.9, the
    stiffness alone is refitted too and reported unless the length lowers BIC by 10 units more."""
    import validation.contact_refit as cr_mod

    contact = SimpleNamespace(stiffness=3e9, length=0.02)
    both = ContactRefit(names=("stiffness", "length"), given=(3e9, 0.02), fitted=(1.0e9, 0.06), p_value=0.3,
                        ratio=1.0, slip_ratio=1.0, delta_bic=-100.0, correlation=-0.999, n_evals=60)
    alone = ContactRefit(names=("stiffness",), given=(3e9,), fitted=(1.5e9,), p_value=0.3, ratio=1.0, slip_ratio=1.0,
                         delta_bic=-97.0, n_evals=20)
    calls = []

    def fake(model, contact, space, predicted, context, names):
        calls.append(tuple(names))
        return both if tuple(names) == ("stiffness", "length") else alone

    monkeypatch.setattr(cr_mod, "_refit", fake)
    monkeypatch.setattr(cr_mod, "contact_value", lambda c, n: getattr(c, n))
    kept = refit_contact(None, contact, None, None, None)
    assert calls == [("stiffness", "length"), ("stiffness",)]
    assert kept.names == ("stiffness",) and kept.kept == (("length", 0.02),) and kept.n_evals == 80
    assert kept.correlation == -0.999 and kept.both_fitted == (1.0e9, 0.06) and kept.both_delta_bic == -100.0
    assert "length kept at 0.02 m as given" in kept.text()
    assert "the length refitted too changes BIC by -3.0 units" in kept.text()
    # the product the text gives is the refitted stiffness times the length kept
    assert "3e+07 Pa against 6e+07 given" in kept.text()
    # a length that earns 10 units more is refitted with the stiffness
    alone = dataclasses.replace(alone, delta_bic=-89.0)
    calls.clear()
    kept = refit_contact(None, contact, None, None, None)
    assert kept.names == ("stiffness", "length") and kept.kept == () and kept.n_evals == 80
    # estimates that do not trade: the stiffness is not refitted alone
    both = dataclasses.replace(both, correlation=-0.5)
    calls.clear()
    assert refit_contact(None, contact, None, None, None) is both and calls == [("stiffness", "length")]


def test_the_loop_refits_the_contact_too_and_sets_aside_the_offset_it_beats(contact_off_case, monkeypatch):
    improve_mod = importlib.import_module("validation.improve")   # the package's `improve` is the function
    case, truth = contact_off_case
    made = {}

    def as_rival(check, refit):
        # here the offset does not bring the rows to the noise and is no rival of the baseline; made one, the loop
        # must set it aside as the diagnosis does
        fits = tuple(dataclasses.replace(f, rival=True) if f.kind == "slip" and f.effects == () else f
                     for f in check.fits)
        made["check"] = dataclasses.replace(check, fits=fits)
        return defer_calibration(made["check"], refit)

    monkeypatch.setattr(improve_mod, "defer_calibration", as_rival)
    imp = validation.improve(case, probe=False)
    assert imp.verdict in ("unexplained", "partly_explained")
    cr = imp.localized.contact
    assert cr.explains and cr.names == ("stiffness",) and cr.effects == ()
    assert cr.fitted[0] * case.contact.length == pytest.approx(truth.stiffness * truth.length, rel=0.1)
    cal = imp.selection.calibration
    assert "slip ratios" in made["check"].text() and cal.deferred and cal is not made["check"]
    assert not any(f.kind == "slip" for f in cal.rivals) and "slip ratios" not in imp.final.calibration
    assert imp.as_dict()["calibration"]["deferred"][0]["outcome"] == "explains"
