r"""Is it the contact or the slip model? The brush contact refitted where the misfit sits in the rows with slip.

Rows with slip rest on the brush model (Pacejka, Tire and Vehicle Dynamics, 3rd ed. 2012, Sec. 3.2; Persson's
slip model, :mod:`persson.slip`) besides the friction law the sliding rows test. When the verdict places a model's
misfit in them (:mod:`validation.localize`), two explanations remain: the contact the case gives is off (its
tread stiffness sets the initial slope of the slip curve, its length where the patch starts to slide), or the slip
curve has a shape no brush contact gives. The first is checked here, as a calibration error of the rig is
(:mod:`validation.calibration`): the model is refitted with the contact's stiffness and length added to its
fitted parameters (those of the contact not fitted already), from the fitted values and a design over the contact's
coordinates (:func:`validation.refit.global_fit` with ``screen_dims``, every local fit joint), and judged by

* the lack-of-fit test of every row against the noise (:func:`validation.noise.lack_of_fit`, with the two
  parameters more), and
* Schwarz's criterion (BIC), which the contact must lower by :data:`EARN` units, as any added effect must
  (Kass & Raftery, J. Am. Stat. Assoc. 90, 773 (1995)).

A noise estimated from local differences along the rows' series is made on the data less the model's prediction,
and where the model misses the rows with slip by a curve, the curvature of that misfit inflates it
(:mod:`validation.localize`); the refit is then judged against the same estimate made on the other rows alone,
where the model fits (the rows with slip left out; as the original where the other rows cannot give one). A noise
given per row (``mu_std``) or estimated from replicate rows does not depend on the model and is used as it is.

The contact *explains* the misfit when both hold; it *takes most* of it when BIC falls by :data:`EARN` and the
rows with slip come to at most :data:`MOST` of their residual over the noise without every row coming to the noise
(the contact given is off, and something else is missing too); else the misfit stays where it was placed, and the
rows with slip after the refit are reported (their residual over the noise), so that the verdict can say the slip
curve's shape is what the brush model lacks.

In the brush model a slip curve depends on the tread stiffness :math:`k` and the patch length :math:`l` only
through :math:`k l` (Pacejka 2012, Sec. 3.2: written in :math:`x/l`, a bristle sticks while
:math:`k\,\theta\,l\,(x/l) < \mu\,p(x)`, and the stuck zone adds :math:`k\,\theta\,l\,(x_c/l)^2/(2\sigma_0)`
to :math:`\mu`), patch heating aside, which depends on the time :math:`l/V` a point spends in the patch: the rows fix
the product :math:`k l` and hardly each factor, and the text then gives that product. Where the two estimates
correlate at -:data:`TRADE_OFF` or below, the stiffness is refitted alone, the length kept as given, and that refit
is the one reported unless the length earns its place (lowers BIC by :data:`EARN` more, as an added effect must): a
length free to drift along the valley of constant :math:`k l` can reach values far from any tyre's for a
small gain, and the stiffness alone at the given length carries the same product.

Where the calibration check (:mod:`validation.calibration`) fitted an offset of the slip ratios on the same model,
the two are compared by BIC (:func:`with_slip_offset`): an offset that the refitted contact beats by :data:`EARN`
units is no longer named as the rig's rival (:func:`defer_calibration`), and one that beats the contact by as much
is named before it.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from frictioncite import doi

from .candidates import KASS_RAFTERY_1995, bic
from .fitting import CONTACT, Fitter, ParameterSpace, contact_parameters, contact_value
from .noise import ALPHA as LOF_ALPHA
from .noise import estimate_noise, lack_of_fit
from .refit import global_fit

__all__ = ["ContactRefit", "refit_contact", "with_slip_offset", "defer_calibration", "CONTACT_NAMES", "EARN",
           "MOST", "TRADE_OFF"]

#: The contact's parameters refitted (those of :data:`validation.fitting.CONTACT_PARAMETERS` that shape a slip
#: curve of the brush model: its initial slope and the slip at which the patch slides).
CONTACT_NAMES = ("stiffness", "length")
#: Least decrease of BIC for the refitted contact to count (the rule for an added effect).
EARN = 10.0
#: Most residual over the noise of the rows with slip, as a share of the one before, for a refitted contact that does
#: not bring every row to the noise to count as taking most of the misfit.
MOST = 0.5
#: Correlation of the two contact parameters' estimates beyond which the text says that the rows fix only a
#: combination of them.
TRADE_OFF = 0.9
#: H. B. Pacejka, Tire and Vehicle Dynamics, 3rd ed., Butterworth-Heinemann (2012).
PACEJKA_2012 = "isbn:9780080970165"

_UNITS = {"stiffness": "Pa/m", "length": "m"}


@dataclass(frozen=True)
class ContactRefit:
    """The brush contact refitted with a model's other fitted parameters.

    Attributes
    ----------
    names : tuple of str
        The contact parameters refitted (``"stiffness"``, ``"length"``).
    given, fitted : tuple of float
        Their values as given and as refitted (SI: Pa/m, m).
    p_value : float
        The lack-of-fit test of every row after the refit (NaN without a test).
    ratio : float
        Residual over the noise of every row after the refit.
    slip_ratio : float
        Residual over the noise of the rows with slip after the refit (root mean square of r / sigma).
    slip_ratio_before : float
        The same before the refit.
    delta_bic : float
        BIC after the refit less BIC before (negative: better).
    noise : float
        The noise level the refit is judged against (its reference level where it changes with mu).
    noise_from_rest : bool
        That level was estimated from local differences of the rows without slip alone (module docstring).
    slip_offset, slip_offset_gain : float
        An offset of the recorded slip ratios fitted on the same model by the calibration check
        (:mod:`validation.calibration`), and what it lowers BIC by (NaN: none fitted; :func:`with_slip_offset`): at
        small slips it moves a slip curve's rise as a softer contact does, and the text says which the rows
        prefer.
    correlation : float
        The correlation of the two contact parameters' estimates in the refit of both (from the weighted Jacobian at
        the optimum; NaN where only one was refitted): near +-1 the rows fix a combination of them, not each.
    n_evals : int
        Model evaluations of the refit (of both, and of the stiffness alone where it was made).
    kept : tuple of (str, float)
        Contact parameters refitted with the others but then kept as given, with their values: the length, where
        the rows fix only the product of stiffness and length and refitting the length does not lower BIC by
        :data:`EARN` more than the stiffness alone (module docstring); empty otherwise.
    both_fitted : tuple of float
        Where a parameter was kept: the values of the refit of both (empty otherwise).
    both_delta_bic : float
        Where a parameter was kept: the BIC change of the refit of both (NaN otherwise).
    effects : tuple of str
        The effects of the model refitted (empty: the baseline); set by :func:`with_slip_offset`.
    """

    names: tuple
    given: tuple
    fitted: tuple
    p_value: float
    ratio: float
    slip_ratio: float
    delta_bic: float
    correlation: float = math.nan
    n_evals: int = 0
    slip_ratio_before: float = math.nan
    noise: float = math.nan
    noise_from_rest: bool = False
    slip_offset: float = math.nan
    slip_offset_gain: float = math.nan
    kept: tuple = ()
    both_fitted: tuple = ()
    both_delta_bic: float = math.nan
    effects: tuple = ()

    @property
    def over_offset(self) -> float:
        """BIC units by which the refitted contact fits the rows better than the offset of the slip ratios fitted
        on the same model (negative: the offset fits better; NaN: no offset that earns :data:`EARN` units)."""
        if not (self.slip_offset_gain >= EARN):
            return math.nan
        return -self.delta_bic - self.slip_offset_gain

    @property
    def preferred(self) -> str | None:
        """What the rows prefer, the refitted contact or the offset of the slip ratios: ``"contact"`` or
        ``"slip_offset"`` by :data:`EARN` BIC units or more, ``"either"`` within them; None without an offset that
        earns :data:`EARN` units."""
        d = self.over_offset
        if not math.isfinite(d):
            return None
        return "contact" if d >= EARN else "slip_offset" if d <= -EARN else "either"

    @property
    def explains(self) -> bool:
        """The refitted contact brings every row to the noise (lack of fit p >= 0.01) and lowers BIC by at least
        :data:`EARN`."""
        return math.isfinite(self.p_value) and self.p_value >= LOF_ALPHA and self.delta_bic <= -EARN

    @property
    def takes_most(self) -> bool:
        """Short of :attr:`explains`, the refitted contact lowers BIC by at least :data:`EARN` and takes the rows with
        slip to at most half their residual over the noise: the contact given is off, and something else too."""
        return (not self.explains and self.delta_bic <= -EARN
                and self.slip_ratio <= MOST * self.slip_ratio_before)

    @property
    def outcome(self) -> str:
        """``"explains"``, ``"takes_most"`` or ``"stays"``."""
        return "explains" if self.explains else "takes_most" if self.takes_most else "stays"

    def values_text(self) -> str:
        """``"stiffness 3.2e+08 Pa/m against 1e+08 given, length 0.12 m against 0.1"``."""
        return ", ".join(f"{n} {f:.3g} {_UNITS.get(n, '')} against {g:.3g}" + (" given" if i == 0 else "")
                         for i, (n, g, f) in enumerate(zip(self.names, self.given, self.fitted)))

    def text(self) -> str:
        """What the refit says: the contact given is off, or the misfit is the slip curve's shape; and whether the
        rows prefer it to an offset of the slip ratios."""
        return self._refit_text() + self._offset_text()

    def _offset_text(self) -> str:
        preferred, diff = self.preferred, self.over_offset
        if preferred is None:   # no offset fitted, or one that earns nothing
            return ""
        offset = f" An offset of the slip ratios ({self.slip_offset:+.3g}, the calibration check's) fits these rows"
        if preferred == "contact":
            return f"{offset} less well: the refitted contact by {diff:.1f} BIC units."
        if preferred == "slip_offset":
            return (f"{offset} better, by {-diff:.1f} BIC units: check the slip measurement (the wheel's effective "
                    f"rolling radius, the slip's zero at free rolling) before the contact.")
        return (f"{offset} as well (within {EARN:g} BIC units): the rows cannot tell a contact given off from an "
                f"offset of the rig's slip.")

    def _refit_text(self) -> str:
        values = self.values_text()
        against = (f"; against a noise of {self.noise:.3g} estimated from the rows without slip alone, where the "
                   f"model fits" if self.noise_from_rest else "")
        if self.kept:
            kept = dict(self.kept)
            scale = float(np.prod(list(kept.values())))
            given, fitted = (float(np.prod(v)) * scale for v in (self.given, self.fitted))
            held = ", ".join(f"{n} kept at {v:.3g} {_UNITS.get(n, '')} as given" for n, v in kept.items())
            values = (f"{values}, {held}: the rows fix the product of stiffness and length ({fitted:.3g} Pa against "
                      f"{given:.3g} given): refitted together the two correlate at {self.correlation:+.2f}, and "
                      f"the length refitted too changes BIC by {self.both_delta_bic - self.delta_bic:+.1f} units, "
                      f"short of the {EARN:g} it must lower it by")
        elif self.correlation <= -TRADE_OFF and self.names == CONTACT_NAMES:
            given, fitted = (float(np.prod(v)) for v in (self.given, self.fitted))
            values = (f"the product of stiffness and length {fitted:.3g} Pa against {given:.3g} given, which the "
                      f"rows fix rather than each: {values}, correlation {self.correlation:+.2f}")
        elif abs(self.correlation) >= TRADE_OFF:
            values += f"; the rows fix a combination of the two, not each: correlation {self.correlation:+.2f}"
        if self.explains:
            return (f"Refitted with the rest ({values}), the brush contact brings every row to the "
                    f"noise (residual / noise {self.ratio:.2f}, lack of fit p = {self.p_value:.2g}, BIC "
                    f"{self.delta_bic:+.1f}{against}): the contact given is off, not the slip model; refit it "
                    f"({', '.join(f'contact.{n}' for n in self.names)} in the fit) or measure it.")
        if self.takes_most:
            return (f"Refitted with the rest ({values}), the brush contact takes most of the misfit of the rows with "
                    f"slip (residual / noise {self.slip_ratio_before:.2f} -> {self.slip_ratio:.2f}, BIC "
                    f"{self.delta_bic:+.1f}) but not all (every row {self.ratio:.2f}, lack of fit p = "
                    f"{self.p_value:.2g}{against}): the contact given is off, and what remains may be the shape of "
                    f"the slip curve or physics of rolling with slip that the model lacks.")
        return (f"Refitted with the rest ({values}), the brush contact leaves the rows with slip at "
                f"residual / noise {self.slip_ratio:.2f} (every row {self.ratio:.2f}, lack of fit p = "
                f"{self.p_value:.2g}, BIC {self.delta_bic:+.1f}{against}): not the contact's stiffness or length but "
                f"the shape of the slip curve is what the brush model misses (its peak, or its fall beyond the "
                f"peak), or physics of rolling with slip.")

    def as_dict(self) -> dict:
        """``names``, ``given``, ``fitted``, ``p_value``, ``ratio``, ``slip_ratio``, ``slip_ratio_before``,
        ``delta_bic``, ``explains``, ``outcome``, ``noise``, ``noise_from_rest``, ``slip_offset`` and
        ``slip_offset_gain`` (null without one), ``preferred`` (:attr:`preferred`), ``correlation`` (of the two
        refitted together; null where they were not), ``kept`` (name -> value), ``both_fitted`` and
        ``both_delta_bic`` (null where nothing was kept), ``effects``, ``n_evaluations`` and ``text``."""
        return {"names": list(self.names), "given": list(self.given), "fitted": list(self.fitted),
                "p_value": self.p_value, "ratio": self.ratio, "slip_ratio": self.slip_ratio,
                "slip_ratio_before": self.slip_ratio_before, "outcome": self.outcome, "noise": self.noise,
                "noise_from_rest": self.noise_from_rest,
                "slip_offset": self.slip_offset if math.isfinite(self.slip_offset) else None,
                "slip_offset_gain": self.slip_offset_gain if math.isfinite(self.slip_offset_gain) else None,
                "delta_bic": self.delta_bic, "explains": self.explains,
                "correlation": self.correlation if math.isfinite(self.correlation) else None,
                "preferred": self.preferred, "kept": dict(self.kept), "both_fitted": list(self.both_fitted) or None,
                "both_delta_bic": self.both_delta_bic if math.isfinite(self.both_delta_bic) else None,
                "effects": list(self.effects), "n_evaluations": self.n_evals,
                "text": self.text()}


# ==========================================================================================================
@doi(PACEJKA_2012, KASS_RAFTERY_1995)
def refit_contact(model, contact, space, predicted, context, *, names=CONTACT_NAMES) -> ContactRefit | None:
    """The model refitted with the brush contact's ``names`` added to its fitted parameters (module docstring).

    Parameters
    ----------
    model : persson.Model
        The model at its fitted parameters.
    contact : persson.slip.Contact or None
        Its contact at the fitted parameters.
    space : validation.fitting.ParameterSpace
        The parameters fitted with it (empty: none); the refit starts from their values in ``model``.
    predicted : array_like (n,)
        The model's prediction of the rows (before the refit).
    context : validation.diagnose.FitContext
        The settings (predictor, data, weights) and the noise.
    names : sequence of str
        The contact parameters to refit; those already in ``space`` are left out. Where they are stiffness and
        length and their estimates correlate beyond -:data:`TRADE_OFF`, the stiffness is refitted alone too, and
        kept unless the length earns :data:`EARN` BIC units (module docstring).

    Returns
    -------
    ContactRefit or None
        None without a contact, without rows with slip, or when every one of ``names`` is fitted already.
    """
    both = _refit(model, contact, space, predicted, context, names)
    if both is None or both.names != CONTACT_NAMES or not both.correlation <= -TRADE_OFF:
        return both
    alone = _refit(model, contact, space, predicted, context, ("stiffness",))
    if alone is None or alone.delta_bic > both.delta_bic + EARN:
        return dataclasses.replace(both, n_evals=both.n_evals + (alone.n_evals if alone is not None else 0))
    return dataclasses.replace(alone, correlation=both.correlation, n_evals=alone.n_evals + both.n_evals,
                               kept=(("length", contact_value(contact, "length")),), both_fitted=both.fitted,
                               both_delta_bic=both.delta_bic)


def _refit(model, contact, space, predicted, context, names) -> ContactRefit | None:
    """The refit of :func:`refit_contact` with exactly ``names`` (less those in ``space``)."""
    s = context.settings
    m = context.measurements
    slip = np.asarray(m.slip, dtype=float) < 1.0
    names = tuple(n for n in names if f"{CONTACT}.{n}" not in space.keys)
    if contact is None or not names or not np.any(slip):
        return None
    y, w = np.asarray(s.y, dtype=float), np.asarray(s.w, dtype=float)
    full = space + ParameterSpace(contact_parameters(contact, names))
    fitter = Fitter(s.predictor, y, w, model, full, max_evals=s.budget(len(full)), contact=contact)
    fit = global_fit(fitter, full.u_of(model, contact), seed=s.seed, n_local=s.n_local,
                     screen_dims=range(len(space), len(full)))
    k0 = len(space)
    # the derivatives at the optimum belong to the result, not to the search: they never run out of budget
    fitter.max_evals = max(fitter.max_evals, fitter.n_evals + 2 * len(full))
    correlation = _correlation(fitter.jacobian(fit.u) * w[:, None], k0) if len(names) == 2 else math.nan
    rss0 = float(np.sum(((y - np.asarray(predicted, dtype=float)) * w) ** 2))
    rss = float(np.sum(((y - fit.mu) * w) ** 2))
    residual = y - fit.mu
    noise, from_rest = _judging_noise(context, predicted, slip)
    lof = lack_of_fit(residual, k0 + len(names), noise)
    sigma = np.asarray(noise.row_sigma, dtype=float) if noise.known else np.full(y.size, math.nan)
    z = residual[slip] / sigma[slip]
    z0 = (y - np.asarray(predicted, dtype=float))[slip] / sigma[slip]
    return ContactRefit(names=names, given=tuple(contact_value(contact, n) for n in names),
                        fitted=tuple(contact_value(fit.contact, n) for n in names), p_value=float(lof.p_value),
                        ratio=float(lof.ratio), slip_ratio=float(np.sqrt(np.mean(z * z))),
                        delta_bic=bic(rss, y.size, k0 + len(names), s.sigma_known) - bic(rss0, y.size, k0,
                                                                                          s.sigma_known),
                        correlation=correlation, n_evals=fitter.n_evals,
                        slip_ratio_before=float(np.sqrt(np.mean(z0 * z0))), noise=float(noise.sigma),
                        noise_from_rest=from_rest)


def with_slip_offset(refit: ContactRefit | None, calibration, effects) -> ContactRefit | None:
    """``refit`` with the offset of the slip ratios that the calibration check fitted on the same model (the set of
    ``effects``), for the text's comparison; ``refit`` itself when there is none.

    Parameters
    ----------
    refit : ContactRefit or None
    calibration : validation.calibration.CalibrationCheck or None
    effects : sequence of str
        The effects of the model the contact was refitted with (empty: the baseline).
    """
    if refit is None:
        return refit
    refit = dataclasses.replace(refit, effects=tuple(effects))
    if calibration is None:
        return refit
    fits = _slip_offsets(calibration, effects)
    if not fits:
        return refit
    best = max(fits, key=lambda f: f.gain_over_set)
    return dataclasses.replace(refit, slip_offset=float(best.value), slip_offset_gain=float(best.gain_over_set))


@doi(KASS_RAFTERY_1995)
def defer_calibration(check, refit: ContactRefit | None):
    """``check`` (a :class:`validation.calibration.CalibrationCheck`, or None) with the offsets of the slip ratios
    that ``refit`` fits the rows better than, by :data:`EARN` BIC units or more, deferred to it: they stay among its
    fits but are no longer named as the rig's rivals (:attr:`validation.calibration.CalibrationCheck.deferred`).

    Only offsets fitted on the model the contact was refitted with (the same effects, :attr:`ContactRefit.effects`)
    are compared: the two then differ by one parameter and BIC weighs them alike. ``check`` itself when nothing is
    deferred.
    """
    if check is None or refit is None:
        return check
    deferred = tuple((f, float(-refit.delta_bic - f.gain_over_set), refit.outcome)
                     for f in _slip_offsets(check, refit.effects) if f.rival)
    deferred = tuple(d for d in deferred if d[1] >= EARN)
    return check if not deferred else dataclasses.replace(check, deferred=deferred)


def _slip_offsets(check, effects) -> list:
    """The offsets of the slip ratios among ``check``'s fits made on the model of ``effects`` (any order)."""
    return [f for f in check.fits if f.kind == "slip" and frozenset(f.effects) == frozenset(effects)]


def _judging_noise(context, predicted, slip):
    """(noise, from the other rows): the noise to judge the refit by (module docstring): with a local-difference
    estimate, the same estimate made on the rows without slip alone (with the model's prediction as reference),
    its level carried to every row in the proportions of the original; else, or where those rows give none, the
    context's."""
    noise = context.noise
    if noise.source != "local differences" or not noise.known or np.all(slip):
        return noise, False
    rest = ~slip
    est = estimate_noise(context.measurements.subset(rest), reference=np.asarray(predicted, dtype=float)[rest])
    if est.source != "local differences" or not est.known or not noise.sigma > 0:
        return noise, False
    factor = est.sigma / noise.sigma
    return dataclasses.replace(noise, sigma=est.sigma, dof=est.dof,
                               row_sigma=np.asarray(noise.row_sigma, dtype=float) * factor,
                               description=f"{est.description}, on the rows without slip"), True


def _correlation(J, first: int) -> float:
    """The correlation of the estimates of the coordinates ``first`` and ``first + 1`` from the weighted Jacobian
    ``J`` (the pseudo-inverse of J^T J; NaN where either is not determined)."""
    cov = np.linalg.pinv(J.T @ J)
    a, b, c = cov[first, first], cov[first + 1, first + 1], cov[first, first + 1]
    return float(c / math.sqrt(a * b)) if a > 0 and b > 0 else math.nan
