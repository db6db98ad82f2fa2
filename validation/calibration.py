r"""Could a calibration error of the rig explain what a physical effect explains?

A friction rig measures two forces, and mu is their ratio. A gain error of either load cell scales every measured
mu by one factor; a zero offset of the friction force adds :math:`\Delta F_x / F_z`, which falls as 1/p with the
nominal pressure p (the contact patch fixed). Neither is a physical effect of the rubber, but either can be
mistaken for one: a loss modulus 8 % higher (strain softening with a loss factor of 1.08) raises the hysteresis
friction almost uniformly, as a gain of 1.08 on the friction force does. So can an offset of the recorded rubber
temperature (a pyrometer's emissivity): through the WLF shift every row moves along the master curve; and so can a
factor on the recorded speeds (a wheel's effective rolling radius, an encoder): every row moves along log v, and
where the flash temperature acts, its heating moves with it.

For each set of effects the diagnosis fitted that is a proper subset of its answer (the baseline included), this
module fits the two calibration errors to the measured rows on top of that set's fitted prediction :math:`f`,
each in closed form (weighted linear least squares in one parameter, weights :math:`w = 1/\sigma_\mu` or ones):

.. math:: \text{gain:}\quad \mu = s f, \qquad
          \hat s = \frac{\sum w^2 y f}{\sum w^2 f^2}, \qquad
          \operatorname{se}(\hat s) = \sqrt{\frac{s^2}{\sum w^2 f^2}},

.. math:: \text{offset:}\quad \mu = f + c\,\frac{p_{ref}}{p}, \qquad
          \hat c = \frac{\sum w^2 (y - f) d}{\sum w^2 d^2}, \quad d = \frac{p_{ref}}{p},

where the rows name two or more measuring devices (``Measurements.device``), a gain per device
(:math:`\mu = s_D f` on the rows of device D, :math:`\hat s_D` the gain's formula over D's rows alone: the
design's columns do not overlap, so the fit is block-diagonal, one parameter per device; plausible when every gain
is), since devices that measured different conditions let one device's calibration pass for physics;

and, on the baseline and on each set one effect short of the answer, the errors of the recorded conditions: an
offset :math:`\Delta T` of the temperatures (every row predicted at :math:`T + \Delta T`), a factor :math:`s_v`
on the speeds (every row predicted at :math:`s_v V`, the slip unchanged, fitted as :math:`x = \ln s_v`) and, where
at least three rows have slip < 1, an offset :math:`\delta` of their slip ratios (predicted at
:math:`s + \delta`: a wheel's effective rolling radius off the one assumed; the horizontal shift :math:`S_H` of
the Magic Formula, H. B. Pacejka, E. Bakker, Veh. Syst. Dyn. 21 (sup1), 1 (1992)). Each goes through the fit's
own prediction path, by Gauss-Newton steps from 0: the first with the central-difference derivative
:math:`J = \partial\mu/\partial x` at 0, the next with the secant between the last two points (Broyden's update,
exact in one parameter; Seber & Wild, Nonlinear Regression, Wiley (1989), sec. 14.1), until a step is shorter than
a twentieth of the standard error (at most five), the best point evaluated kept, and its standard error
:math:`\sqrt{s^2 / \sum w^2 J^2}` as for the gain (three to seven predictions of the set each);
with :math:`p_{ref}` the geometric mean of the rows' pressures (with one pressure the offset is a constant) and
:math:`s^2` the variance unit of the fits (1 with ``mu_std``, else the noise variance), scaled by the Birge
ratio where the calibrated model misses the noise (R. T. Birge, Phys. Rev. 40, 207 (1932); weighted least
squares: N. R. Draper, H. Smith, Applied Regression Analysis, 3rd ed., Wiley (1998)). Each is scored by the BIC
of the set with one more parameter (one per device; :func:`validation.candidates.bic`), first with the set's own
parameters held at their fitted values. A fitted parameter of the set may have taken up part of the error (a
fitted shear stress part of a zero offset); so where the linear estimate of a joint step could make the error a
rival (weighted least squares of the residual on the set's Jacobian d mu / d u and the error's column together),
the step is taken: the set is predicted at its stepped parameters (with the stepped condition for an error of
the conditions), the closed-form errors are solved again on that prediction, and the result is kept where it fits
better (one prediction; Seber & Wild, sec. 14.1). Either way the BIC is that of a real prediction, an upper bound
of the joint optimum: a calibration error named here fits at least as well as said. The standard errors of a
joint step come from the joint design, so they include the correlation with the set's parameters.

A calibration error is a **rival** of the answer when it is plausible (a gain within :data:`GAIN_RANGE`, an offset
of at most :data:`OFFSET_LIMIT` in mu at :math:`p_{ref}`, a temperature offset of at most :data:`TEMPERATURE_LIMIT`,
a speed factor within :data:`SPEED_RANGE`, a slip offset of at most :data:`SLIP_LIMIT`: a rig further out has a
fault that shows without a model), earns its own parameter (its BIC more than :data:`EARN` units below that of
its set) and comes within :data:`BAND` BIC units of the answer (or beats it). The data then cannot tell the
answer's extra effects from a calibration error: the diagnosis says so and asks for the measurement to be checked
(the load cells against weights, a reference surface, the thermometer, the wheel's rolling radius). Where the
answer itself misses the noise, every error is also fitted on top of it, and one that brings the residual to the
noise level is named as what the answer leaves (on top of the answer, or of the baseline when that is the answer,
a rival must reach the noise level: earning a parameter is not enough there). Nothing is changed in the answer
itself. An offset of the slip ratios that a refit of the brush contact on the same model beats by :data:`BAND`
units (where the verdict places the misfit in the rows with slip, :mod:`validation.contact_refit`) is set aside
as :attr:`CalibrationCheck.deferred`, not named as a rival: a contact given off moves the slip curve's rise as that
offset does, and the rows prefer the contact.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .band import SEBER_WILD_1989
from .candidates import SCHWARZ_1978, bic

__all__ = ["CalibrationFit", "CalibrationCheck", "SetFit", "check_calibration", "GAIN_RANGE", "OFFSET_LIMIT",
           "TEMPERATURE_LIMIT", "SPEED_RANGE", "SLIP_LIMIT"]

#: Gains of the measured mu taken as a plausible calibration error (a rig more than 30 % off is faulty).
GAIN_RANGE = (0.7, 1.3)
#: Largest |offset| of the measured mu at the reference pressure taken as a plausible zero offset.
OFFSET_LIMIT = 0.1
#: Largest |offset| of the recorded temperatures taken as plausible, K (a pyrometer's emissivity or a probe's
#: position is often off by a few K; more is a fault that shows without a model).
TEMPERATURE_LIMIT = 10.0
#: The range the temperature offset is searched in, K.
TEMPERATURE_SEARCH = 15.0
#: Factors on the recorded speeds taken as plausible (symmetric in log speed: friction depends on log v; a wheel's
#: effective rolling radius or an encoder more than 30 % off is a fault that shows without a model).
SPEED_RANGE = (1.0 / 1.3, 1.3)
#: The largest factor (or its inverse) the speed error is searched to.
SPEED_SEARCH = 1.5
#: Largest |offset| of the recorded slip ratios taken as plausible (a wheel's effective rolling radius 3 % off
#: the one assumed shifts every slip by about 0.03: Pacejka's horizontal shift S_H of the Magic Formula).
SLIP_LIMIT = 0.03
#: The range the slip offset is searched in.
SLIP_SEARCH = 0.05
#: The conditions' errors: (step of the central difference, half-width of the search), in the fitted coordinate
#: (dT in K; ln s for the speed factor s; the slip offset).
_CONDITIONS = {"temperature": (0.5, TEMPERATURE_SEARCH), "speed": (math.log(1.02), math.log(SPEED_SEARCH)),
               "slip": (0.002, SLIP_SEARCH)}
#: The values a condition's error may take in a joint step (dT in K, the speed factor, the slip offset).
_VALUE_RANGE = {"temperature": (-TEMPERATURE_SEARCH, TEMPERATURE_SEARCH),
                "speed": (1.0 / SPEED_SEARCH, SPEED_SEARCH), "slip": (-SLIP_SEARCH, SLIP_SEARCH)}
#: Fewest rows with slip < 1 for a slip offset to be fitted.
_MIN_SLIP_ROWS = 3
#: The smallest slip (and 1 less the largest) a shifted slip row keeps.
_SLIP_FLOOR = 1e-6
#: Most Gauss-Newton steps of a condition's error.
_CONDITION_STEPS = 5
#: A step shorter than this many standard errors ends the Gauss-Newton steps.
_CONDITION_TOL = 0.05
#: What to check for each kind of error.
_ADVICE = {"gain": "the rig's calibration (the load cells against known weights, a reference surface)",
           "offset": "the rig's calibration (the friction force's zero with the wheel lifted, a reference surface)",
           "temperature": "the temperature measurement (a pyrometer's emissivity, where and when the probe reads)",
           "speed": "the speed measurement (the wheel's effective rolling radius, the encoder)",
           "slip": "the slip measurement (the wheel's effective rolling radius, the slip's zero at free rolling)",
           "device_gains": "each device's calibration (the load cells against known weights, a reference surface "
                           "measured on every device)"}
#: BIC units within which a calibration error fits as well as the answer: the set search's band of equally
#: supported sets (``validation.select.EQUAL``).
BAND = 10.0
#: BIC units a calibration error must gain over its set alone to count: what an effect must earn to stay in a set
#: (``validation.select.STAY``); both "very strong" evidence (Kass & Raftery, J. Am. Stat. Assoc. 90, 773 (1995)).
EARN = 10.0
#: N. R. Draper, H. Smith, Applied Regression Analysis, 3rd ed., Wiley (1998): least squares in one parameter.
DRAPER_SMITH_1998 = "isbn:9780471170822"
#: H. B. Pacejka, E. Bakker, The Magic Formula tyre model, Vehicle System Dynamics 21 (sup1), 1 (1992): the
#: horizontal shift S_H of a slip curve, the slip offset here.
MAGIC_FORMULA_1992 = "10.1080/00423119208969994"


@dataclass(frozen=True)
class CalibrationFit:
    """One calibration error fitted on top of one set of effects.

    Attributes
    ----------
    kind : str
        ``"gain"`` (measured mu = gain x model), ``"offset"`` (measured mu = model + offset p_ref / p),
        ``"temperature"`` (measured mu = model at the recorded temperature + value), ``"speed"`` (measured mu =
        model at value x the recorded speed), ``"slip"`` (measured mu = model at the recorded slip + value, rows
        with slip < 1) or ``"device_gains"`` (measured mu = gain of the row's device x model,
        one gain per device: :attr:`per_device`).
    on : str
        Label of the set of effects it is fitted on (``"(baseline)"`` for none).
    effects : tuple of str
        That set's effects.
    value : float
        The gain (1 = none), the offset in mu at ``p_ref``, the temperature offset in K, the speed factor (1 =
        none), the slip offset, or the device gain farthest from 1.
    std : float
        Its standard error.
    p_ref : float
        Reference pressure of the offset, Pa (geometric mean of the rows' pressures).
    bic : float
        BIC of the set with the calibration error (one parameter more).
    gain_over_set : float
        BIC of the set alone minus :attr:`bic` (what the calibration parameter earns).
    delta_bic : float
        :attr:`bic` minus the BIC of the answer it is compared with.
    rmse : float
        Unweighted root mean square residual.
    lack : validation.noise.LackOfFit
        Its residual tested against the noise.
    pattern : validation.noise.Pattern
        Systematic structure left in its residual.
    plausible : bool
        Within :data:`GAIN_RANGE` (every device's gain), :data:`OFFSET_LIMIT`, :data:`TEMPERATURE_LIMIT`,
        :data:`SPEED_RANGE` or :data:`SLIP_LIMIT`.
    rival : bool
        Plausible, earns its parameter and within :data:`BAND` BIC units of the answer (module docstring).
    per_device : tuple of (str, float, float)
        For ``"device_gains"``: (device, gain, standard error) per device; empty otherwise.
    joint : bool
        The set's own parameters were refitted with the error (one Gauss-Newton step of both; the standard errors
        then include their correlation); False: held at their fitted values.
    """

    kind: str
    on: str
    effects: tuple
    value: float
    std: float
    p_ref: float
    bic: float
    gain_over_set: float
    delta_bic: float
    rmse: float
    lack: object
    pattern: object
    plausible: bool
    rival: bool
    per_device: tuple = ()
    joint: bool = False

    @property
    def at_noise(self) -> bool:
        """Whether the residual is consistent with the noise and shows no pattern (False without a noise estimate:
        nothing can be said)."""
        return bool(self.lack.test != "none" and self.lack.consistent and not self.pattern.found)

    def describe(self) -> str:
        """The error in words: what the measured mu would read, with its standard error."""
        if self.kind == "gain":
            return (f"the measured mu reading {_percent_off(self.value, 'high', 'low')} (gain {self.value:.4g} +- "
                    f"{self.std:.2g})")
        if self.kind == "device_gains":
            each = ", ".join(f"{d or '(unlabelled)'} {g:.4g} +- {sd:.2g}" for d, g, sd in self.per_device)
            far = next(d for d, g, _ in self.per_device if g == self.value)
            return (f"the measured mu of device {far or '(unlabelled)'} reading "
                    f"{_percent_off(self.value, 'high', 'low')} (a gain per device: {each})")
        if self.kind == "slip":
            return (f"the slip ratios {abs(self.value):.3g} {'higher' if self.value >= 0 else 'lower'} than recorded "
                    f"(a slip offset of {self.value:+.3g} +- {self.std:.2g})")
        if self.kind == "speed":
            return (f"the speeds {_percent_off(self.value, 'higher', 'lower')} than recorded (a speed factor of "
                    f"{self.value:.4g} +- {self.std:.2g})")
        if self.kind == "temperature":
            return (f"the rubber {abs(self.value):.1f} K {'warmer' if self.value >= 0 else 'colder'} than recorded "
                    f"(a temperature offset of {self.value:+.2f} +- {self.std:.2g} K)")
        return (f"a zero offset of the friction force adding {self.value:+.3g} +- {self.std:.2g} to mu at "
                f"{self.p_ref / 1e6:.3g} MPa (as p_ref / p)")

    def as_dict(self) -> dict:
        """The fit as a JSON-ready dict: every attribute (``per_device`` as a list of ``{"device", "gain", "std"}``),
        ``lack_of_fit`` (its ``as_dict``), ``remaining_pattern`` (in words), ``at_noise`` and ``description``."""
        return {"kind": self.kind, "on": self.on, "effects": list(self.effects), "value": self.value,
                "std": self.std, "p_ref": self.p_ref, "bic": self.bic, "gain_over_set": self.gain_over_set,
                "delta_bic": self.delta_bic, "rmse": self.rmse, "lack_of_fit": self.lack.as_dict(),
                "remaining_pattern": self.pattern.describe(), "at_noise": self.at_noise,
                "plausible": self.plausible, "rival": self.rival, "description": self.describe(),
                "per_device": [{"device": d, "gain": g, "std": sd} for d, g, sd in self.per_device],
                "joint": self.joint}


@dataclass(frozen=True)
class CalibrationCheck:
    """The calibration errors fitted against an answer of the diagnosis.

    Attributes
    ----------
    answer : str
        Label of the answer (the best set of effects, the explaining candidate or the baseline).
    answer_effects : tuple of str
    answer_bic : float
    fits : tuple of CalibrationFit
        Every fit, lowest BIC first.
    deferred : tuple of (CalibrationFit, float, str)
        Rivals that a refit of the brush contact on the same model fits the rows better than, by 10 BIC units or
        more (:func:`validation.contact_refit.defer_calibration`): each with those BIC units and the refit's
        outcome. They are not named as rivals (:attr:`rivals`): where the misfit sits in the rows with slip, an
        offset of the slip ratios and a contact given off move the slip curve's rise alike, and the rows prefer
        the contact.
    """

    answer: str
    answer_effects: tuple
    answer_bic: float
    fits: tuple
    deferred: tuple = ()

    @property
    def rivals(self) -> tuple:
        """The fits that rival the answer, lowest BIC first (less those :attr:`deferred` to a refitted
        contact)."""
        gone = {id(f) for f, _, _ in self.deferred}
        return tuple(f for f in self.fits if f.rival and id(f) not in gone)

    def text(self) -> str:
        """A paragraph on the rivals (empty when there is none)."""
        r = self.rivals
        if not r:
            return ""
        best = r[0]
        extra = [e for e in self.answer_effects if e not in best.effects]
        if extra:
            how = "better than" if best.delta_bic < -BAND else "as well as"
            what = (f"A calibration error of the rig fits these rows {how} {' + '.join(extra)}: "
                    f"{best.on} with {best.describe()} (BIC {best.delta_bic:+.1f} against {self.answer}")
        elif self.answer_effects:  # on top of the answer: what it leaves
            what = (f"A calibration error of the rig fits what {self.answer} leaves: {best.on} with "
                    f"{best.describe()} (BIC {best.delta_bic:+.1f} against {self.answer} alone")
        else:
            what = (f"A calibration error of the rig fits these rows: {best.on} with {best.describe()} (BIC "
                    f"{best.delta_bic:+.1f} against {self.answer}")
        what += (f"; {best.lack.describe()}" if best.lack.test != "none" else "") + ")"
        if best.at_noise:
            what += ", at the noise level"
        others = [f"{f.on} with {f.describe()} ({f.delta_bic:+.1f})" for f in r[1:3]]
        if others:
            what += "; also " + "; ".join(others)
        how = _ADVICE[best.kind]
        tail = (f"Before taking {' + '.join(extra)} as physics, check {how}." if extra else f"Check {how}.")
        return what + ". " + tail

    def as_dict(self) -> dict:
        """``answer``, ``answer_effects``, ``answer_bic``, ``rivals`` (the descriptions), ``fits``
        (:meth:`CalibrationFit.as_dict`) and ``deferred`` (``description``, ``on``, ``contact_better_by`` in BIC
        units and the contact refit's ``outcome``, per :attr:`deferred` rival)."""
        return {"answer": self.answer, "answer_effects": list(self.answer_effects), "answer_bic": self.answer_bic,
                "rivals": [f.describe() + f" on {f.on}" for f in self.rivals],
                "fits": [f.as_dict() for f in self.fits],
                "deferred": [{"description": f.describe(), "on": f.on, "contact_better_by": by, "outcome": outcome}
                             for f, by, outcome in self.deferred]}


# ==========================================================================================================
@doi(DRAPER_SMITH_1998, SCHWARZ_1978, SEBER_WILD_1989, MAGIC_FORMULA_1992)
def check_calibration(sets, answer, context, baseline=None, conditions=(), on_answer=False,
                      refits=None) -> CalibrationCheck:
    """A gain and an offset of the measured mu (and a gain per device where the rows name several) fitted on top
    of each of ``sets``, and the errors of the recorded conditions (an offset of the temperatures, a factor on the
    speeds, an offset of the slip ratios) on the baseline and on the sets one effect short of the answer, each
    compared with ``answer`` (module docstring).

    Parameters
    ----------
    sets : iterable of (label, effects, predicted, n_params, bic)
        Fitted sets of effects: label, effects (tuple of str), prediction per row, number of fitted parameters, BIC.
        Those whose effects are not a proper subset of the answer's are skipped (the answer itself included,
        unless it is the baseline: then the errors are fitted on it).
    answer : (label, effects, bic)
        The diagnosis' answer.
    context : validation.diagnose.FitContext
        The fits' data, weights, noise and tests.
    baseline : (model, contact, n_params, bic), optional
        The fitted baseline, for the errors of the recorded conditions (:func:`_condition_error`); None: none
        fitted on it.
    conditions : iterable of (label, effects, model, contact, n_params, bic)
        Further fitted sets to fit the conditions' errors on: those one effect short of the answer are used (their
        predictions taken from ``sets``), and the answer itself with ``on_answer``; the others are skipped.
    on_answer : bool
        Fit every error on top of the answer itself too (when it misses the noise: a calibration error may be what
        it leaves); the answer must then be among ``sets`` (and ``conditions``).
    refits : dict, optional
        frozenset of effects -> :class:`SetFit`: for those sets, an error whose linear estimate could make a rival
        is refitted together with the set's parameters (one Gauss-Newton step, checked by a prediction).

    Returns
    -------
    CalibrationCheck
    """
    label, answer_effects, answer_bic = answer
    p = np.asarray(context.measurements.pressure, dtype=float)
    p_ref = float(np.exp(np.mean(np.log(p))))
    d = p_ref / p
    devices = _devices(context.measurements)
    refits = dict(refits or {})
    closed = ("gain", "offset") + (("device_gains",) if len(devices) > 1 else ())
    fits = []
    for set_label, effects, f, k, set_bic in sets:
        if not (set(effects) < set(answer_effects) or (set(effects) == set(answer_effects)
                                                       and (on_answer or not answer_effects))):
            continue
        on = _On(set_label, tuple(effects), k, set_bic, float(answer_bic), p_ref, context,
                 refits.get(frozenset(effects)))
        f = np.asarray(f, dtype=float)
        for kind in closed:
            est = _closed_form(kind, f, d, devices, context)
            if est is None:
                continue
            rec = _record(kind, on, *est)
            if on.refit is not None:
                rec = _joint_closed_form(kind, est, d, devices, on) or rec
            fits.append(rec)
    targets = [] if baseline is None else [("(baseline)", (), *baseline)]  # the answer or a proper subset of it
    targets += [c for c in conditions if c[1] and (
        (set(c[1]) < set(answer_effects) and len(c[1]) == len(answer_effects) - 1)
        or (on_answer and set(c[1]) == set(answer_effects)))]
    for set_label, effects, model, contact, k, set_bic in targets:
        f0 = next((f for _, e, f, *_ in sets if set(e) == set(effects)), None)
        on = _On(set_label, tuple(effects), k, set_bic, float(answer_bic), p_ref, context,
                 refits.get(frozenset(effects)))
        for kind in _CONDITIONS:
            if kind == "slip" and int(np.sum(context.measurements.slip < 1.0)) < _MIN_SLIP_ROWS:
                continue
            t = None if f0 is None else _condition_error(kind, model, contact, f0, context)
            if t is None:
                continue
            value, J, pred = t
            rec = _record(kind, on, np.array([value]), pred, J[:, None], None)
            if on.refit is not None:
                rec = _joint_condition(kind, value, J, pred, on) or rec
            fits.append(rec)
    # on top of the answer itself a rival must explain what the answer leaves, not merely earn its parameter
    fits = [dataclasses.replace(c, rival=c.rival and c.at_noise) if set(c.effects) == set(answer_effects) else c
            for c in fits]
    fits.sort(key=lambda c: c.bic)
    return CalibrationCheck(answer=label, answer_effects=tuple(answer_effects), answer_bic=float(answer_bic),
                            fits=tuple(fits))


@dataclass(frozen=True)
class SetFit:
    """What the joint step of a calibration error needs of a fitted set (:func:`check_calibration`): its model and
    contact, the map from the fit's coordinates u to them, the optimum and d mu / d u there.

    Attributes
    ----------
    model : persson.Model
    contact : persson.slip.Contact or None
    space : validation.fitting.ParameterSpace
    u : ndarray (k,)
    jacobian : ndarray (rows, k)
        Unweighted.
    """

    model: object
    contact: object
    space: object
    u: np.ndarray
    jacobian: np.ndarray

    @classmethod
    def of(cls, model, contact, covariance, jacobian) -> "SetFit | None":
        """From a fit's covariance (its space and optimum) and Jacobian; None when either is missing or they do not
        match."""
        if covariance is None or jacobian is None:
            return None
        J = np.asarray(jacobian, dtype=float)
        u = np.asarray(covariance.u, dtype=float)
        if J.ndim != 2 or J.shape[1] != u.size or u.size == 0 or not np.all(np.isfinite(J)):
            return None
        return cls(model=model, contact=contact, space=covariance.space, u=u, jacobian=J)

    def predict(self, du, measurements) -> np.ndarray | None:
        """The set's prediction of ``measurements`` with its parameters at u + ``du`` (clipped to the box); None
        where the model fails."""
        u = np.clip(self.u + np.asarray(du, dtype=float), 0.0, 1.0)
        try:
            mu = _quiet_prediction(self.space.apply(self.model, u), measurements,
                                   self.space.apply_contact(self.contact, u))
        except Exception:  # noqa: BLE001  (a step the model cannot take is not taken)
            return None
        return mu if np.all(np.isfinite(mu)) else None


@dataclass(frozen=True)
class _On:
    """The set an error is fitted on, and what its record is compared with."""

    label: str
    effects: tuple
    k: int
    set_bic: float
    answer_bic: float
    p_ref: float
    context: object
    refit: SetFit | None


def _closed_form(kind, f, d, devices, context):
    """(values, prediction, d prediction / d values (rows x values), device groups or None) of the closed-form
    error ``kind`` on top of the set's prediction ``f`` (module docstring), or None where it is undetermined."""
    s = context.settings
    y, w = np.asarray(s.y, dtype=float), np.asarray(s.w, dtype=float)
    w2 = w * w
    if kind == "device_gains":
        masks = [mask for _, mask in devices]
        norms = [float(np.sum(w2[mask] * f[mask] ** 2)) for mask in masks]
        if not all(n > 0.0 for n in norms):
            return None
        g = np.array([float(np.sum(w2[mask] * y[mask] * f[mask])) / n for mask, n in zip(masks, norms)])
        columns = np.column_stack([np.where(mask, f, 0.0) for mask in masks])
        return g, columns @ g, columns, [label for label, _ in devices]
    basis = f if kind == "gain" else d
    norm = float(np.sum(w2 * basis * basis))
    if not norm > 0.0:
        return None
    target = y if kind == "gain" else y - f
    value = float(np.sum(w2 * target * basis)) / norm
    return np.array([value]), (value * f if kind == "gain" else f + value * d), basis[:, None], None


def _record(kind, on, values, predicted, columns, groups, joint=False):
    """The record of one calibration error at ``values`` (one per device for ``"device_gains"``): its BIC with
    as many parameters more than the set's, its standard errors from the design ``columns`` (d prediction / d
    parameter; with ``joint``, the set's own columns first, then the error's), its tests and whether it rivals."""
    ctx = on.context
    s = ctx.settings
    y, w, n = np.asarray(s.y, dtype=float), np.asarray(s.w, dtype=float), s.y.size
    values = np.asarray(values, dtype=float)
    extra = values.size
    r = y - predicted
    rss = float(np.sum((w * r) ** 2))
    b = bic(rss, n, on.k + extra, s.sigma_known)
    var = rss / max(n - on.k - extra, 1)
    unit = ctx.s2 if math.isfinite(ctx.s2) and ctx.s2 > 0 else var
    unit = max(unit, var)  # Birge-scaled where the fit misses the noise
    std = _standard_errors(columns, w, unit)[-extra:]
    if kind == "device_gains":
        i = int(np.argmax(np.abs(values - 1.0)))
        per_device = tuple((label, float(g), float(sd)) for label, g, sd in zip(groups, values, std))
        plausible = bool(np.all((GAIN_RANGE[0] <= values) & (values <= GAIN_RANGE[1])))
    else:
        i, per_device = 0, ()
        plausible = _plausible(kind, float(values[0]))
    earns = on.set_bic - b > EARN
    return CalibrationFit(kind=kind, on=on.label, effects=on.effects, value=float(values[i]), std=float(std[i]),
                          p_ref=on.p_ref, bic=b, gain_over_set=on.set_bic - b, delta_bic=b - on.answer_bic,
                          rmse=float(np.sqrt(np.mean(r * r))), lack=ctx.lack_of_fit(r, on.k + extra),
                          pattern=ctx.pattern(r), plausible=plausible,
                          rival=bool(plausible and earns and b - on.answer_bic < BAND), per_device=per_device,
                          joint=bool(joint))


def _plausible(kind, value) -> bool:
    if kind == "gain":
        return GAIN_RANGE[0] <= value <= GAIN_RANGE[1]
    if kind == "offset":
        return abs(value) <= OFFSET_LIMIT
    if kind == "temperature":
        return abs(value) <= TEMPERATURE_LIMIT
    if kind == "slip":
        return abs(value) <= SLIP_LIMIT
    return SPEED_RANGE[0] <= value <= SPEED_RANGE[1]


def _standard_errors(columns, w, unit) -> np.ndarray:
    """sqrt of the diagonal of unit (C^T W^2 C)^-1 (inf for a direction the columns do not determine)."""
    A = np.asarray(columns, dtype=float) * w[:, None]
    H = A.T @ A
    try:
        cov = np.linalg.pinv(H)
    except np.linalg.LinAlgError:
        return np.full(H.shape[0], math.inf)
    diag = np.diag(cov)
    return np.where(diag > 0, np.sqrt(np.abs(diag) * unit), math.inf)


def _joint_closed_form(kind, est, d, devices, on):
    """The error ``kind`` refitted together with the set's own parameters: one Gauss-Newton step of both from the
    error alone (``est``, :func:`_closed_form`), the set predicted at its stepped parameters and the error solved
    again on that prediction. Tried only where the step's linear estimate could make a rival; kept where the
    prediction fits better than the error alone. Returns the new record or None."""
    values, predicted, columns, groups = est
    J = on.refit.jacobian
    if kind == "gain":
        set_columns = values[0] * J
    elif kind == "device_gains":  # mu = g_D f(u) on the rows of device D
        set_columns = sum(g * mask for g, (_, mask) in zip(values, devices))[:, None] * J
    else:
        set_columns = J
    step = _linear_step(set_columns, columns, predicted, on)
    if step is None:
        return None
    du, _ = step
    f2 = on.refit.predict(du, on.context.measurements)
    if f2 is None:
        return None
    est2 = _closed_form(kind, f2, d, devices, on.context)
    if est2 is None:
        return None
    values2, predicted2, columns2, groups2 = est2
    if _rss(predicted2, on) >= _rss(predicted, on):
        return None
    return _record(kind, on, values2, predicted2, np.column_stack([set_columns, columns2]), groups2, joint=True)


def _joint_condition(kind, value, J_value, predicted, on):
    """The error of a recorded condition refitted together with the set's own parameters: one Gauss-Newton step of
    both from the error alone (at ``value``, where d mu / d value is ``J_value``), the set predicted at the stepped
    parameters and condition. As :func:`_joint_closed_form` otherwise."""
    columns = J_value[:, None]
    step = _linear_step(on.refit.jacobian, columns, predicted, on)
    if step is None:
        return None
    du, dv = step
    lo, hi = _VALUE_RANGE[kind]
    value2 = float(np.clip(value + dv[0], lo, hi))
    f2 = on.refit.predict(du, _shifted(on.context.measurements, kind, value2))
    if f2 is None or _rss(f2, on) >= _rss(predicted, on):
        return None
    return _record(kind, on, np.array([value2]), f2, np.column_stack([on.refit.jacobian, columns]), None, joint=True)


def _linear_step(set_columns, error_columns, predicted, on):
    """(d u, d values): the weighted least-squares step of the set's parameters and the error's on the residual at
    ``predicted``, or None when its linear estimate could not make a rival (no gain, or a BIC that does not earn
    the error's parameters or misses the band of the answer)."""
    s = on.context.settings
    y, w, n = np.asarray(s.y, dtype=float), np.asarray(s.w, dtype=float), s.y.size
    A = np.column_stack([set_columns, error_columns])
    r = y - predicted
    sol, *_ = np.linalg.lstsq(A * w[:, None], r * w, rcond=None)
    if not np.all(np.isfinite(sol)):
        return None
    rss_lin = float(np.sum((w * (r - A @ sol)) ** 2))
    b_lin = bic(rss_lin, n, on.k + error_columns.shape[1], s.sigma_known)
    b_now = bic(_rss(predicted, on), n, on.k + error_columns.shape[1], s.sigma_known)
    if not (b_lin < b_now - 1.0 and on.set_bic - b_lin > EARN and b_lin - on.answer_bic < BAND):
        return None
    k = set_columns.shape[1]
    return sol[:k], sol[k:]


def _percent_off(factor: float, more: str, less: str) -> str:
    """``"12.2 % high"``: how far ``factor`` is from 1, in per cent, with the word for its side."""
    pct = 100.0 * (factor - 1.0)
    return f"{abs(pct):.1f} % {more if pct >= 0 else less}"


def _rss(predicted, on) -> float:
    s = on.context.settings
    return float(np.sum((np.asarray(s.w, dtype=float) * (np.asarray(s.y, dtype=float) - predicted)) ** 2))


def _quiet_prediction(model, measurements, contact) -> np.ndarray:
    """mu of ``model`` on ``measurements`` through the fit's prediction path, its warnings silenced (those of a
    trial point at shifted conditions or stepped parameters are not the fit's notes)."""
    import warnings

    from .predict import predict

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return np.asarray(predict(model, measurements, contact).mu, dtype=float)


def _shifted(m, kind, value):
    """The rows ``m`` at the conditions shifted by the error ``kind`` of ``value`` (dT in K, the speed factor, the
    slip offset): rows that slide stay sliding; a slip row stays a slip row, its slip kept inside (0, 1)."""
    if kind == "temperature":
        return dataclasses.replace(m, temperature=m.temperature + value, _checked=True)
    if kind == "speed":
        return dataclasses.replace(m, speed=m.speed * value, _checked=True)
    slip = np.where(m.slip < 1.0, np.clip(m.slip + value, _SLIP_FLOOR, 1.0 - _SLIP_FLOOR), m.slip)
    return dataclasses.replace(m, slip=slip, _checked=True)


def _devices(m):
    """(label, row mask) of each measuring device of ``m`` with at least two rows, in order of first appearance;
    empty when the rows name fewer than two devices (rows without a label form a device of their own)."""
    labels = tuple(str(d) for d in (getattr(m, "device", ()) or ()))
    if len(set(labels)) < 2:
        return []
    arr = np.asarray(labels, dtype=object)
    out = [(label, arr == label) for label in dict.fromkeys(labels)]
    return out if all(int(mask.sum()) >= 2 for _, mask in out) else []


def _condition_error(kind, model, contact, f0, context):
    """The error of the recorded conditions of ``kind`` (``"temperature"``: an offset dT in K; ``"speed"``: a factor
    on the recorded speeds, fitted as x = ln s; ``"slip"``: an offset of the recorded slip ratios of the rows with
    slip < 1, kept within (0, 1)) that fits the rows best with ``model`` (every row predicted at the shifted
    condition through the fit's prediction path; ``f0`` its prediction at x = 0): up to :data:`_CONDITION_STEPS`
    Gauss-Newton steps from 0, clipped to the search range of :data:`_CONDITIONS`, the first with the
    central-difference derivative at 0 and each next with the secant through the last two points, until a step is
    shorter than :data:`_CONDITION_TOL` standard errors; the best point evaluated kept (three to seven
    predictions). Returns (the value: dT, the factor s or the slip offset; d mu / d value per row there; the
    prediction there), or None where the model fails. Its parameters stay at their fitted values."""
    m = context.measurements
    s = context.settings
    y, w = np.asarray(s.y, dtype=float), np.asarray(s.w, dtype=float)
    h, search = _CONDITIONS[kind]

    def at(x):
        return _quiet_prediction(model, _shifted(m, kind, math.exp(x) if kind == "speed" else float(x)), contact)

    try:
        J = (at(h) - at(-h)) / (2 * h)
        norm = float(np.sum((w * J) ** 2))
        if not (np.all(np.isfinite(J)) and norm > 0):
            return None
        x, f = 0.0, np.asarray(f0, dtype=float)
        best = (float(np.sum((w * (y - f)) ** 2)), x, f, J)
        unit = context.s2 if math.isfinite(context.s2) and context.s2 > 0 else 0.0
        for _ in range(_CONDITION_STEPS):
            x_new = float(np.clip(x + float(np.sum(w * w * (y - f) * J)) / norm, -search, search))
            # a step far below the standard error changes nothing that is reported
            if abs(x_new - x) <= _CONDITION_TOL * math.sqrt(unit / norm):
                break
            f_new = at(x_new)
            if not np.all(np.isfinite(f_new)):
                break
            # the secant between the last two points (Broyden's update, exact for one parameter): the derivative
            # follows the curvature of mu(x) at no extra prediction
            J_new = (f_new - f) / (x_new - x)
            if float(np.sum((w * J_new) ** 2)) > 0.0:
                J, norm = J_new, float(np.sum((w * J_new) ** 2))
            x, f = x_new, f_new
            c = float(np.sum((w * (y - f)) ** 2))
            if c < best[0]:
                best = (c, x, f, J)
    except Exception:  # noqa: BLE001  (a model that fails at shifted conditions has no error to offer)
        return None
    _, x, f, J = best
    if kind == "speed":  # d mu / d s = (d mu / d ln s) / s
        return math.exp(x), J / math.exp(x), f
    return x, J, f
