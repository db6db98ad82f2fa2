r"""Measured strain factors beyond the measured strains: extrapolation rules, the share of the hysteresis friction
that rests on them, and the spread of the friction between rules.

With measured strain factors (:class:`persson.effects.StrainSoftening` with ``factors``), the length scale q sees
the modulus softened at its local strain :math:`\varepsilon(q) = \kappa\,\xi(q)` (Persson, J. Phys.: Condens.
Matter 18, 7789 (2006); Lorenz et al., J. Chem. Phys. 142, 194701 (2015)). The rms slope :math:`\xi(q)` of a road
reaches 1-3 at the short-distance cut-off, so the local strain of the smallest scales (50-150 %) lies far beyond
the 10-30 % a DMA strain sweep reaches; on real treads most of the hysteresis friction comes from there. What the
factors do beyond the largest measured strain :math:`\varepsilon_{max}` is then a modelling choice, one of:

``"hold"`` (default)
    f and g keep their values at :math:`\varepsilon_{max}` (no further softening).
``"log_trend"``
    the measured trend continues linearly in :math:`\ln\varepsilon`:
    :math:`f(\varepsilon) = f(\varepsilon_{max}) + s_f\,\ln(\varepsilon/\varepsilon_{max})` with :math:`s_f` the
    least-squares slope of f against :math:`\ln\varepsilon` over the last measured decade of strain (at least the
    last two strains), per temperature of the table, interpolated linearly in T like the factors; likewise g. A
    falling trend stops at :data:`TREND_FLOOR` (5 % of the small-strain modulus, the lower bound of the constant
    factors) or at the measured end value when that is lower.
a table (:class:`materials.StrainFactors`, e.g. from :func:`materials.read_strain_factors`)
    the user's own factors at large strain (from another program, another test, a model of the compound); used as
    they are beyond :math:`\varepsilon_{max}`, the measured factors below it.

:func:`extrapolated_share` gives the share of :math:`\mu_{hys}` carried by the scales beyond
:math:`\varepsilon_{max}` (``FrictionResult.strain_extrapolated_share``); :func:`strain_extrapolation_spread`
computes the friction under each rule, the sensitivity of a result to the choice.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, PhysicsWarning
from ..notes import share_span

__all__ = ["RULES", "TREND_FLOOR", "SHARE_WARNING", "check_rule", "rule_name", "extrapolated_factors",
           "extrapolated_share", "report", "StrainExtrapolationSpread", "strain_extrapolation_spread"]

#: The named extrapolation rules (a table of factors is the third kind).
RULES = ("hold", "log_trend")
#: Smallest factor a falling log-trend reaches (the lower bound of the constant factors of StrainSoftening).
TREND_FLOOR = 0.05
#: Above this share of mu_hysteresis from scales beyond the measured strains a result warns (PhysicsWarning).
SHARE_WARNING = 0.5
#: Below this share the result carries no note.
_SHARE_NOTE = 0.01


def check_rule(rule):
    """``rule`` checked: one of :data:`RULES` or a table with ``factors(strain, T)`` (InputError otherwise)."""
    if isinstance(rule, str):
        if rule not in RULES:
            raise InputError(f"strain_softening.extrapolation: expected one of {', '.join(repr(r) for r in RULES)} "
                             f"or a table of factors (materials.read_strain_factors), got {rule!r}")
        return rule
    if callable(getattr(rule, "factors", None)) and hasattr(rule, "strain_range"):
        return rule
    raise InputError(f"strain_softening.extrapolation: expected one of {', '.join(repr(r) for r in RULES)} or "
                     f"materials.StrainFactors (a table of factors), got {type(rule).__name__}")


def rule_name(rule) -> str:
    """``"hold"``, ``"log_trend"`` or ``"table"``."""
    return rule if isinstance(rule, str) else "table"


def extrapolated_factors(factors, strain, T, rule="hold"):
    """(f, g) of the measured ``factors`` at ``strain`` and ``T`` (arrays that broadcast), continued beyond the
    largest measured strain by ``rule`` (see the module docstring).

    Parameters
    ----------
    factors : materials.StrainFactors
        The measured factors.
    strain : array_like
        Strain amplitudes (absolute).
    T : array_like
        Temperatures, deg C.
    rule : str or materials.StrainFactors
        ``"hold"``, ``"log_trend"`` or a table of factors used beyond the largest measured strain.
    """
    f, g = factors.factors(strain, T)
    if isinstance(rule, str) and rule == "hold":
        return f, g
    e, TT = np.broadcast_arrays(np.asarray(strain, dtype=float), np.asarray(T, dtype=float))
    e_max = float(factors.strain_range[1])
    beyond = e > e_max
    if not np.any(beyond):
        return f, g
    f, g = np.array(f, dtype=float), np.array(g, dtype=float)
    if isinstance(rule, str):  # log_trend
        s_f, s_g = _trend_slopes(factors)
        x = np.log(e[beyond] / e_max)
        Tb = TT[beyond]
        f_end, g_end = factors.factors(np.full(x.shape, e_max), Tb)
        nodes = np.asarray(factors.T_C, dtype=float)
        for out, end, s in ((f, f_end, s_f), (g, g_end, s_g)):
            trend = end + np.interp(Tb, nodes, s) * x
            out[beyond] = np.maximum(trend, np.minimum(TREND_FLOOR, end))
    else:
        tf, tg = rule.factors(e[beyond], TT[beyond])
        f[beyond], g[beyond] = tf, tg
    return f, g


def extrapolated_share(strain_q, mu_cumulative, strain_max: float) -> np.ndarray:
    r"""Share of the hysteresis friction carried by the scales whose local strain exceeds ``strain_max``.

    :math:`1 - \mu(q^*)/\mu_{hys}`, with :math:`\mu(q)` the friction carried by the scales :math:`q_0..q` and
    :math:`q^*` where the local strain reaches ``strain_max`` (the cumulative friction interpolated linearly in the
    strain between the nodes; the local strain grows with q).

    Parameters
    ----------
    strain_q : ndarray (n_q,)
        Local strain at the wavevector nodes (non-decreasing).
    mu_cumulative : ndarray (n_speed, n_q)
        Hysteresis friction of the scales up to each node (``FrictionResult.mu_cumulative``).
    strain_max : float
        Largest measured strain.

    Returns
    -------
    ndarray (n_speed,)
        In [0, 1]; 0 where the friction is 0.
    """
    eps = np.maximum.accumulate(np.asarray(strain_q, dtype=float))
    cum = np.atleast_2d(np.asarray(mu_cumulative, dtype=float))
    total = cum[:, -1]
    if eps[-1] <= strain_max:
        return np.zeros(total.shape)
    below = np.array([np.interp(strain_max, eps, row) for row in cum])
    with np.errstate(invalid="ignore", divide="ignore"):
        share = np.where(total > 0, 1.0 - below / np.where(total > 0, total, 1.0), 0.0)
    return np.clip(share, 0.0, 1.0)


def report(effect, result, slope):
    """``result`` with ``strain_extrapolated_share`` set and a note (a PhysicsWarning above one half) when the
    effect has measured factors; called by the model with the rms slope :math:`\\xi(q)` at ``result.q``."""
    factors = getattr(effect, "factors", None)
    if factors is None or result.mu_cumulative is None or not hasattr(factors, "strain_range"):
        return result
    strain_q = effect.strain_per_slope * np.asarray(slope, dtype=float)
    e_max = float(factors.strain_range[1])
    share = extrapolated_share(strain_q, result.mu_cumulative, e_max)
    out = float(share[0]) if result.scalar else share
    notes = result.notes
    top = float(np.max(share)) if share.size else 0.0
    if top >= _SHARE_NOTE:
        rng = share_span(share)
        how = {"hold": "held at their values there", "log_trend": "continued along the measured trend in log strain",
               "table": "taken from the user's table"}[rule_name(effect.extrapolation)]
        msg = (f"strain softening: {rng} of mu_hysteresis comes from length scales whose local strain (up to "
               f"{float(strain_q[-1]):.3g}) exceeds the largest measured strain {e_max:.3g}, where the factors are "
               f"{how} (extrapolation={rule_name(effect.extrapolation)!r}); persson.effects.strain_extrapolation_"
               "spread shows how much the friction depends on that choice")
        notes = notes + (msg,)
        if top > SHARE_WARNING:
            warnings.warn(msg, PhysicsWarning, stacklevel=4)
    return result.replace(strain_extrapolated_share=out, notes=notes)


@dataclass(frozen=True, eq=False)
class StrainExtrapolationSpread:
    """Friction under each extrapolation rule of the strain factors (:func:`strain_extrapolation_spread`).

    Attributes
    ----------
    speed : ndarray (n_speed,)
        Sliding speeds, m/s.
    temperature, pressure : float or ndarray
        Background temperature (deg C) and nominal pressure (Pa).
    rules : tuple of str
        The rules, in the order of the rows below (``"hold"``, ``"log_trend"``, ``"table"``).
    mu, mu_hysteresis, contact_area : ndarray (n_rule, n_speed)
        Friction coefficient, its hysteresis part and A/A0 under each rule.
    extrapolated_share : ndarray (n_speed,)
        Share of mu_hysteresis from scales beyond the largest measured strain (under the model's own rule).
    rule : str
        The model's own rule.
    """

    speed: np.ndarray
    temperature: object
    pressure: object
    rules: tuple
    mu: np.ndarray
    mu_hysteresis: np.ndarray
    contact_area: np.ndarray
    extrapolated_share: np.ndarray
    rule: str

    @property
    def spread(self) -> np.ndarray:
        """(max - min) / mean of mu over the rules, per speed: the relative sensitivity to the rule."""
        mean = np.mean(self.mu, axis=0)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(mean > 0, np.ptp(self.mu, axis=0) / np.where(mean > 0, mean, 1.0), 0.0)

    def summary(self) -> str:
        """A small text table: speed, the share beyond the measured strains, mu per rule and the spread."""
        head = f"{'speed m/s':>10} {'share':>6} " + " ".join(f"{'mu ' + r:>12}" for r in self.rules) + "  spread"
        rows = [head]
        for i, v in enumerate(self.speed):
            rows.append(f"{v:10.3g} {self.extrapolated_share[i]:6.0%} "
                        + " ".join(f"{self.mu[k, i]:12.4g}" for k in range(len(self.rules)))
                        + f"  {self.spread[i]:6.1%}")
        return "\n".join(rows)


def strain_extrapolation_spread(model, speed, temperature=20.0, pressure=0.3e6, *, rules=None
                                ) -> StrainExtrapolationSpread:
    """The friction of ``model`` under each extrapolation rule of its measured strain factors.

    Parameters
    ----------
    model : persson.Model
        With :class:`persson.effects.StrainSoftening` holding measured ``factors``.
    speed, temperature, pressure
        As :meth:`persson.Model.friction`.
    rules : sequence, optional
        Rules to compare (``"hold"``, ``"log_trend"``, tables); default both named rules, and the model's own
        table when it has one.

    Returns
    -------
    StrainExtrapolationSpread

    Raises
    ------
    InputError
        The model has no strain softening with measured factors.
    """
    effect = next((e for e in getattr(model, "effects", ()) if getattr(e, "name", "") == "strain_softening"), None)
    if effect is None or getattr(effect, "factors", None) is None:
        raise InputError("model: strain_extrapolation_spread needs the strain_softening effect with measured factors "
                         "(StrainSoftening(factors=materials.strain_factors(...)))")
    own = effect.extrapolation
    if rules is None:
        rules = list(RULES) + ([] if isinstance(own, str) else [own])
    rules = [check_rule(r) for r in rules]
    if not rules:
        raise InputError("rules: expected at least one extrapolation rule")
    mu, hys, area = [], [], []
    share = None
    for r in rules:
        with warnings.catch_warnings():  # the share is reported once, in the result, not once per rule
            warnings.filterwarnings("ignore", message="strain softening:", category=PhysicsWarning)
            res = model.with_effect(effect.with_parameters(extrapolation=r)).friction(
                speed, temperature=temperature, pressure=pressure)
        mu.append(np.atleast_1d(res.mu))
        hys.append(np.atleast_1d(res.mu_hysteresis))
        area.append(np.atleast_1d(res.contact_area))
        if share is None or (r == own if isinstance(own, str) else r is own):
            share = np.atleast_1d(res.strain_extrapolated_share)
    return StrainExtrapolationSpread(speed=np.atleast_1d(np.asarray(speed, dtype=float)), temperature=temperature,
                                     pressure=pressure, rules=tuple(rule_name(r) for r in rules), mu=np.array(mu),
                                     mu_hysteresis=np.array(hys), contact_area=np.array(area),
                                     extrapolated_share=share, rule=rule_name(own))


def _trend_slopes(factors):
    """Least-squares slopes of f and g against ln(strain) over the last measured decade, per temperature row."""
    x = np.log(np.asarray(factors.strain, dtype=float))
    if x.size < 2:
        n = np.asarray(factors.T_C).size
        return np.zeros(n), np.zeros(n)
    last = x >= x[-1] - math.log(10.0)
    if last.sum() < 2:
        last[-2:] = True
    xs = x[last] - x[last].mean()
    denom = float(xs @ xs)
    F = np.asarray(factors.storage_factor, dtype=float)[:, last]
    G = np.asarray(factors.loss_factor, dtype=float)[:, last]
    return (F - F.mean(axis=1, keepdims=True)) @ xs / denom, (G - G.mean(axis=1, keepdims=True)) @ xs / denom
