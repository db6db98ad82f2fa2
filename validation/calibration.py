r"""Could a calibration error of the rig explain what a physical effect explains?

A friction rig measures two forces, and mu is their ratio. A gain error of either load cell scales every measured
mu by one factor; a zero offset of the friction force adds :math:`\Delta F_x / F_z`, which falls as 1/p with the
nominal pressure p (the contact patch fixed). Neither is a physical effect of the rubber, but either can be
mistaken for one: a loss modulus 8 % higher (strain softening with a loss factor of 1.08) raises the hysteresis
friction almost uniformly, as a gain of 1.08 on the friction force does.

For each set of effects the diagnosis fitted that is a proper subset of its answer (the baseline included), this
module fits the two calibration errors to the measured rows on top of that set's fitted prediction :math:`f`,
each in closed form (weighted linear least squares in one parameter, weights :math:`w = 1/\sigma_\mu` or ones):

.. math:: \text{gain:}\quad \mu = s f, \qquad
          \hat s = \frac{\sum w^2 y f}{\sum w^2 f^2}, \qquad
          \operatorname{se}(\hat s) = \sqrt{\frac{s^2}{\sum w^2 f^2}},

.. math:: \text{offset:}\quad \mu = f + c\,\frac{p_{ref}}{p}, \qquad
          \hat c = \frac{\sum w^2 (y - f) d}{\sum w^2 d^2}, \quad d = \frac{p_{ref}}{p},

with :math:`p_{ref}` the geometric mean of the rows' pressures (with one pressure the offset is a constant) and
:math:`s^2` the variance unit of the fits (1 with ``mu_std``, else the noise variance), scaled by the Birge
ratio where the calibrated model misses the noise (R. T. Birge, Phys. Rev. 40, 207 (1932); weighted least
squares: N. R. Draper, H. Smith, Applied Regression Analysis, 3rd ed., Wiley (1998)). Each is scored by the BIC
of the set with one more parameter (:func:`validation.candidates.bic`); the set's other parameters stay at their
fitted values, so the BIC is an upper bound of that of a joint fit, and a calibration error named here fits at
least as well as said.

A calibration error is a **rival** of the answer when it is plausible (a gain within :data:`GAIN_RANGE`, an offset
of at most :data:`OFFSET_LIMIT` in mu at :math:`p_{ref}`: a rig further out has a fault that shows without a
model), earns its own parameter (its BIC more than :data:`EARN` units below that of its set) and comes within
:data:`BAND` BIC units of the answer (or beats it). The data then cannot tell
the answer's extra effects from a calibration error: the diagnosis says so and asks for the rig's calibration to
be checked (a reference surface, the load cells against weights). Nothing is changed in the answer itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .candidates import SCHWARZ_1978, bic

__all__ = ["CalibrationFit", "CalibrationCheck", "check_calibration", "GAIN_RANGE", "OFFSET_LIMIT"]

#: Gains of the measured mu taken as a plausible calibration error (a rig more than 30 % off is faulty).
GAIN_RANGE = (0.7, 1.3)
#: Largest |offset| of the measured mu at the reference pressure taken as a plausible zero offset.
OFFSET_LIMIT = 0.1
#: BIC units within which a calibration error fits as well as the answer: the set search's band of equally
#: supported sets (``validation.select.EQUAL``).
BAND = 10.0
#: BIC units a calibration error must gain over its set alone to count: what an effect must earn to stay in a set
#: (``validation.select.STAY``); both "very strong" evidence (Kass & Raftery, J. Am. Stat. Assoc. 90, 773 (1995)).
EARN = 10.0
#: N. R. Draper, H. Smith, Applied Regression Analysis, 3rd ed., Wiley (1998): least squares in one parameter.
DRAPER_SMITH_1998 = "isbn:9780471170822"


@dataclass(frozen=True)
class CalibrationFit:
    """One calibration error fitted on top of one set of effects.

    Attributes
    ----------
    kind : str
        ``"gain"`` (measured mu = gain x model) or ``"offset"`` (measured mu = model + offset p_ref / p).
    on : str
        Label of the set of effects it is fitted on (``"(baseline)"`` for none).
    effects : tuple of str
        That set's effects.
    value : float
        The gain (1 = none), or the offset in mu at ``p_ref``.
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
        Within :data:`GAIN_RANGE` or :data:`OFFSET_LIMIT`.
    rival : bool
        Plausible, earns its parameter and within :data:`BAND` BIC units of the answer (module docstring).
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

    @property
    def at_noise(self) -> bool:
        """Whether the residual is consistent with the noise and shows no pattern (False without a noise estimate:
        nothing can be said)."""
        return bool(self.lack.test != "none" and self.lack.consistent and not self.pattern.found)

    def describe(self) -> str:
        """The error in words: what the measured mu would read, with its standard error."""
        if self.kind == "gain":
            pct = 100.0 * (self.value - 1.0)
            return (f"the measured mu reading {abs(pct):.1f} % {'high' if pct >= 0 else 'low'} (gain "
                    f"{self.value:.4g} +- {self.std:.2g})")
        return (f"a zero offset of the friction force adding {self.value:+.3g} +- {self.std:.2g} to mu at "
                f"{self.p_ref / 1e6:.3g} MPa (as p_ref / p)")

    def as_dict(self) -> dict:
        """The fit as a JSON-ready dict: every attribute, ``lack_of_fit`` (its ``as_dict``), ``remaining_pattern``
        (in words), ``at_noise`` and ``description``."""
        return {"kind": self.kind, "on": self.on, "effects": list(self.effects), "value": self.value,
                "std": self.std, "p_ref": self.p_ref, "bic": self.bic, "gain_over_set": self.gain_over_set,
                "delta_bic": self.delta_bic, "rmse": self.rmse, "lack_of_fit": self.lack.as_dict(),
                "remaining_pattern": self.pattern.describe(), "at_noise": self.at_noise,
                "plausible": self.plausible, "rival": self.rival, "description": self.describe()}


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
    """

    answer: str
    answer_effects: tuple
    answer_bic: float
    fits: tuple

    @property
    def rivals(self) -> tuple:
        """The fits that rival the answer, lowest BIC first."""
        return tuple(f for f in self.fits if f.rival)

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
        else:
            what = (f"A calibration error of the rig fits these rows: {best.on} with {best.describe()} (BIC "
                    f"{best.delta_bic:+.1f} against {self.answer}")
        what += (f"; {best.lack.describe()}" if best.lack.test != "none" else "") + ")"
        if best.at_noise:
            what += ", at the noise level"
        others = [f"{f.on} with {f.describe()} ({f.delta_bic:+.1f})" for f in r[1:3]]
        if others:
            what += "; also " + "; ".join(others)
        tail = (f"Before taking {' + '.join(extra)} as physics, check the rig's calibration (the load cells against "
                "known weights, a reference surface)." if extra else
                "Check the rig's calibration (the load cells against known weights, a reference surface).")
        return what + ". " + tail

    def as_dict(self) -> dict:
        """``answer``, ``answer_effects``, ``answer_bic``, ``rivals`` (the descriptions) and ``fits``
        (:meth:`CalibrationFit.as_dict`)."""
        return {"answer": self.answer, "answer_effects": list(self.answer_effects), "answer_bic": self.answer_bic,
                "rivals": [f.describe() + f" on {f.on}" for f in self.rivals],
                "fits": [f.as_dict() for f in self.fits]}


# ==========================================================================================================
@doi(DRAPER_SMITH_1998, SCHWARZ_1978)
def check_calibration(sets, answer, context) -> CalibrationCheck:
    """A gain and an offset of the measured mu fitted on top of each of ``sets`` and compared with ``answer``
    (module docstring).

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

    Returns
    -------
    CalibrationCheck
    """
    label, answer_effects, answer_bic = answer
    s = context.settings
    y, w, n = np.asarray(s.y, dtype=float), np.asarray(s.w, dtype=float), s.y.size
    p = np.asarray(context.measurements.pressure, dtype=float)
    p_ref = float(np.exp(np.mean(np.log(p))))
    d = p_ref / p
    w2 = w * w
    fits = []
    for set_label, effects, f, k, set_bic in sets:
        if not (set(effects) < set(answer_effects) or (not answer_effects and not effects)):
            continue
        f = np.asarray(f, dtype=float)
        for kind, basis in (("gain", f), ("offset", d)):
            target = y if kind == "gain" else y - f
            norm = float(np.sum(w2 * basis * basis))
            if not norm > 0.0:
                continue
            value = float(np.sum(w2 * target * basis)) / norm
            model = value * f if kind == "gain" else f + value * d
            r = y - model
            rss = float(np.sum(w2 * r * r))
            b = bic(rss, n, k + 1, s.sigma_known)
            var = rss / max(n - k - 1, 1)
            unit = context.s2 if math.isfinite(context.s2) and context.s2 > 0 else var
            std = math.sqrt(max(unit, var) / norm)  # the Birge ratio's scaling where the fit misses the noise
            plausible = (GAIN_RANGE[0] <= value <= GAIN_RANGE[1] if kind == "gain" else abs(value) <= OFFSET_LIMIT)
            earns = set_bic - b > EARN
            fits.append(CalibrationFit(
                kind=kind, on=set_label, effects=tuple(effects), value=value, std=std, p_ref=p_ref, bic=b,
                gain_over_set=set_bic - b, delta_bic=b - answer_bic, rmse=float(np.sqrt(np.mean(r * r))),
                lack=context.lack_of_fit(r, k + 1), pattern=context.pattern(r), plausible=plausible,
                rival=bool(plausible and earns and b - answer_bic < BAND)))
    fits.sort(key=lambda c: c.bic)
    return CalibrationCheck(answer=label, answer_effects=tuple(answer_effects), answer_bic=float(answer_bic),
                            fits=tuple(fits))
