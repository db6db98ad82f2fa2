"""A blind study of the diagnosis loop: random cases with known hidden physics (not a test).

Run: ``python benchmarks/blind_study.py --n 100 --seed 1 [--out results.json] [--kinds single,pair]``

Each case is drawn at random and made by a path independent of the diagnosis:

* **surface**: a self-affine PSD (Hurst exponent 0.7-0.9, roll-off wavelength 0.2-10 mm, hrms 20 um-0.5 mm: a
  sandpaper or a road), tabulated to 1e6 rad/m -- or, when the microtexture is hidden, only to a profilometer
  limit q_r of 3e4-1.6e5 rad/m while the truth keeps the analytic power law to q1 = 6-20 q_r;
* **compound**: a generalized Maxwell solid with a log-normal relaxation spectrum (centre, width, rubbery and
  glassy moduli and WLF constants drawn at random);
* **conditions**: 2-3 temperatures, 1-2 pressures (at least 3 combinations), 7-9 sliding speeds over 3.5-4.5
  decades, a slip sweep with a contact (always with patch heating), wet rows in some cases;
* **hidden physics**: none; one effect (adhesion, flash temperature, microtexture, strain softening, patch
  heating); a pair; wet rows with nothing hidden; or physics outside the candidate list, chosen by ``--outside``:
  ``filler`` (the default), a Cole-Cole filler relaxation of the compound that shifts with an Arrhenius law
  instead of WLF; ``shift``, a compound whose true WLF constants are not those of the master curve the case is
  given (each of C1 and C2 off by a factor 0.7-1.4: a master curve shifted with another compound's or a textbook's
  constants); ``pressure``, a friction that falls with the nominal pressure as a power law (exponent 0.1-0.3,
  :class:`PressureLaw`) beyond what the engine's contact mechanics give; ``slip``, slip rows made by another
  model than the brush model, a Magic Formula curve (:func:`magic_formula_rows`: peak at 3-20 % slip, 1.0-1.4 times
  the friction at the sweep's largest slip, which it meets there); ``contact``, slip rows of a brush contact whose
  tread stiffness is 2-5 times higher or lower and whose length is 0.6-1.6 times that of the contact the case is
  given (a wrong input rather than missing physics: the diagnosis should place the misfit in the rows with slip
  and find that the contact refitted explains it); ``mixed``, filler or shift at random;
* **truth**: the engine on a converged grid (6x the default wavevector nodes, 3x the modulus table, a 2.5x finer
  temperature table, a brush model with 1601 nodes), never the diagnosis's settings;
* **noise**: Gaussian (with ``--noise proportional``, each row's standard deviation in proportion to its true mu,
  the level below at the case's mean mu), its level set by an effect-to-noise ratio (rms of the hidden physics'
  change of mu over the noise; for a pair, that of the weaker effect) drawn log-uniformly from 0.5-20 (0.004-0.02
  in mu without hidden physics); given as ``mu_std`` in 30 % of the cases, as replicate rows in 20 %, else left to
  the local-difference estimate;
* **distinguishable ratio**: what is left of the hidden effect after a refit of every other free parameter (the
  case's fitted ones, those of the other hidden effect of a pair) to the noise-free truth, over the noise: the part
  a diagnosis can see at all (a strain softening under a fitted adhesion is largely absorbed by it); for physics
  outside the candidates, what the best single candidate fitted with the baseline leaves of it;
* **separable ratio** r (where the distinguishable ratio is 2 or more): what the closest other candidate set,
  fitted with the baseline to the noise-free truth, leaves of it (rms), over the noise (sets of one candidate for a
  hidden single effect, of one or two for a pair or outside physics). n r^2 is the chi^2 by which that set misses
  the truth on n rows: below 10 it lies within the band in which the selection calls sets equally supported, and no
  selection can be expected to tell them apart (a tie, which the verdict should name).

The diagnosis sees the case as a user would (:func:`validation.improve` with the default candidates) and the
outcome is compared with the truth. Printed: the confusion matrix (hidden physics against the set of effects
found), the misses named among the equally supported sets, false alarms on null and wet cases, calibration errors of
the rig named as rivals (none of the cases has one), physics outside the candidates called ``explained``, the
verdicts that place the misfit in one family of rows (:mod:`validation.localize`; "after a refit" where the
model's parameters had to be refitted to the other rows to find it) and, where that is the rows with slip, whether
the brush contact refitted explains it (:mod:`validation.contact_refit`), detection against the
effect-to-noise and the distinguishable ratios, and the coverage of the reported 68 % and 95 % intervals of the
parameters of a hidden effect found alone.

A case that raises (in its drawing or its diagnosis) is printed and recorded with its error and traceback, the study
goes on, the summary lists it first and leaves it out of every figure, and a later run on the same ``--out`` file
tries it again.
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import sys
import time
import traceback
import warnings
from dataclasses import dataclass, field, replace

import numpy as np

import frictionerrors
import materials
import persson
import surfaces
import validation
from persson import effects as fx
from persson.slip import Contact
from validation.compare import json_text

#: The truth's resolution: far finer than the diagnosis's defaults (16 q nodes and 40 modulus nodes per decade).
TRUTH_GRID = persson.GridSettings(q_per_decade=96, n_phi=64, omega_per_decade=120, temperature_step=0.1)
SINGLES = ("adhesion", "flash_temperature", "microtexture", "strain_softening", "patch_heating")
PAIRS = (("microtexture", "flash_temperature"), ("flash_temperature", "adhesion"), ("adhesion", "strain_softening"),
         ("microtexture", "adhesion"), ("patch_heating", "adhesion"))
#: The mix of kinds, in the order cases cycle through it.
SCHEDULE = ("single", "null", "single", "pair", "single", "outside", "single", "wet", "single", "pair")
RATIO_BINS = (0.5, 1.0, 2.0, 5.0, 20.0)


@dataclass
class BlindCase:
    """One drawn case: what the diagnosis gets and what is true."""

    index: int
    kind: str
    hidden: dict                       # effect -> true parameters (free ones)
    model: object                      # the case's baseline model (default grid)
    measurements: object
    contact: object
    fit: tuple
    ratio: float                       # effect-to-noise ratio (nan without hidden physics)
    sigma: float
    distinguishable: float             # the part of the effect no refit of the other parameters absorbs, / sigma
    noise_kind: str
    separable: float = math.nan        # what the closest other candidate set leaves of the truth, / sigma
    closest: tuple = ()                # that set
    notes: dict = field(default_factory=dict)
    truth: object = None               # the truth's model (converged grid), its contact and noise-free mu
    truth_contact: object = None
    mu_true: object = None


# ==========================================================================================================
#: The kinds of physics outside the candidate list (``--outside``; module docstring).
OUTSIDE = ("filler", "shift", "pressure", "slip", "contact", "mixed")
#: The noise models (``--noise``; module docstring).
NOISE = ("constant", "proportional")


def draw(index: int, seed: int, outside: str = "filler", noise: str = "constant") -> BlindCase:
    """The case ``index`` of the study with seed ``seed`` (module docstring); ``outside``: the physics outside the
    candidates of an ``outside`` case (one of :data:`OUTSIDE`); ``noise``: the noise's standard deviation the same
    on every row (``"constant"``) or in proportion to the true mu of the row (``"proportional"``)."""
    if outside not in OUTSIDE:
        raise ValueError(f"outside: expected one of {', '.join(OUTSIDE)}, got {outside!r}")
    if noise not in NOISE:
        raise ValueError(f"noise: expected one of {', '.join(NOISE)}, got {noise!r}")
    rng = np.random.default_rng([seed, index])
    kind = SCHEDULE[index % len(SCHEDULE)]
    hidden_names: tuple = ()
    if kind == "single":
        hidden_names = (SINGLES[(index // len(SCHEDULE) + index) % len(SINGLES)],)
    elif kind == "pair":
        hidden_names = PAIRS[(index // len(SCHEDULE) * 2 + index) % len(PAIRS)]
    micro = "microtexture" in hidden_names
    truth_surface, case_surface = _surfaces(rng, micro)
    material = _compound(rng)
    temps = np.sort(rng.choice([-5.0, 5.0, 15.0, 25.0, 35.0, 45.0], size=int(rng.integers(2, 4)), replace=False))
    # at least three (temperature, pressure) series, so that a noise estimate has the rows it needs
    pressures = np.sort(rng.choice([0.15e6, 0.25e6, 0.4e6, 0.6e6], size=2 if temps.size < 3 else
                                   int(rng.integers(1, 3)), replace=False))
    speeds = np.geomspace(10 ** rng.uniform(-4.0, -3.0), 10 ** rng.uniform(0.0, 0.5), int(rng.integers(7, 10)))
    with_slip = "patch_heating" in hidden_names or rng.random() < 0.6 or (kind == "outside" and
                                                                          outside in ("slip", "contact"))
    wet_rows = kind == "wet" or (kind in ("null", "single") and rng.random() < 0.2 and "adhesion" not in hidden_names)
    replicate = rng.random() < 0.2
    use_std = not replicate and rng.random() < 0.375
    rows = []
    for T in temps:
        for p in pressures:
            for v in speeds:
                for _ in range(2 if replicate else 1):
                    rows.append((1.0, float(f"{v:.4g}"), T, p, False))
    if with_slip:
        for s in (0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.4, 0.8):
            rows.append((s, 1.0, float(temps[len(temps) // 2]), float(pressures[0]), False))
    if wet_rows:
        for v in speeds[::max(1, speeds.size // 6)]:
            rows.append((1.0, float(f"{v:.4g}"), float(temps[0]), float(pressures[-1]), True))
    slip, V, T, p, wet = (np.array(x) for x in zip(*rows))
    skeleton = validation.Measurements.from_arrays(slip=slip, speed=V, temperature=T, pressure=p, mu=0.5,
                                                   wet=wet.astype(bool), source=f"blind case {index}")
    contact_case = Contact(0.02, 0.01, 3e9, "parabolic") if with_slip or "patch_heating" in hidden_names else None
    contact_truth = Contact(0.02, 0.01, 3e9, "parabolic", n_points=1601) if contact_case is not None else None
    # the baseline: hysteresis only, or with adhesion (tau_f0 fitted, given off its true value)
    base_eff, fit = [], ()
    base_true = []
    if "adhesion" not in hidden_names and rng.random() < 0.5:
        tau = rng.uniform(0.5e6, 2.0e6)
        base_true.append(fx.Adhesion(tau_f0=tau, c=0.1, v_ref=1e-2))
        base_eff.append(fx.Adhesion(tau_f0=tau * rng.uniform(0.6, 1.5), c=0.1, v_ref=1e-2))
        fit = ("adhesion.tau_f0",)
    hidden = {n: _hidden_params(n, rng, material, skeleton, truth_surface, case_surface) for n in hidden_names}
    case_model = persson.Model(case_surface, material, effects=base_eff)
    truth_effects = list(base_true)
    for n, par in hidden.items():
        if n == "microtexture":
            continue  # the truth's surface carries the tail itself (the analytic power law)
        truth_effects.append(fx.get(n, **par))
    truth_material = material
    notes = {}
    if kind == "outside":
        if outside == "mixed":
            # drawn apart from the case's own generator
            outside = ("filler", "shift")[int(np.random.default_rng([seed, index, 1]).integers(2))]
        if outside == "filler":
            filler = {"delta_E": rng.uniform(4e6, 10e6), "f_ref_Hz": 10 ** rng.uniform(2.0, 4.0),
                      "alpha": rng.uniform(0.3, 0.5), "E_a": rng.uniform(40e3, 80e3)}
            truth_material = ArrheniusFiller(material, **filler)
            notes["filler"] = filler
        elif outside == "pressure":
            law = {"exponent": rng.uniform(0.1, 0.3), "p_ref": 0.3e6}
            truth_effects.append(PressureLaw(**law))
            notes["pressure"] = law
        elif outside == "slip":
            pass    # the slip rows of the truth are replaced below, once computed
        elif outside == "contact":
            # drawn apart from the case's own generator, so that the rest of the case is that of the other kinds
            crng = np.random.default_rng([seed, index, 3])
            factor = 10 ** (crng.choice((-1.0, 1.0)) * crng.uniform(math.log10(2.0), math.log10(5.0)))
            true_contact = {"stiffness": contact_truth.stiffness * factor,
                            "length": contact_truth.length * crng.uniform(0.6, 1.6)}
            contact_truth = replace(contact_truth, **true_contact)
            notes["contact"] = {"true": true_contact, "given": {"stiffness": contact_case.stiffness,
                                                                "length": contact_case.length}}
        else:
            wlf = material.wlf
            shift = {"C1": wlf.C1 * 10 ** rng.uniform(math.log10(0.7), math.log10(1.4)),
                     "C2": wlf.C2 * 10 ** rng.uniform(math.log10(0.7), math.log10(1.4)), "T_ref": wlf.T_ref}
            truth_material = replace(material, wlf=materials.WLF(**shift), label="blind study compound, true shift")
            notes["shift"] = {"true": shift, "given": {"C1": wlf.C1, "C2": wlf.C2, "T_ref": wlf.T_ref}}
    truth = persson.Model(truth_surface, truth_material, effects=truth_effects, grid=TRUTH_GRID)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mu_true = validation.predict(truth, skeleton, contact_truth).mu
        if kind == "outside" and outside == "slip":
            # drawn apart from the case's own generator, so that the rest of the case is that of the other kinds
            mu_true, notes["slip"] = magic_formula_rows(slip, mu_true, np.random.default_rng([seed, index, 2]))
        # the size of the hidden physics: the truth's change of mu when it is taken away (for a pair, each effect
        # alone, and the weaker one counts)
        withouts, free = [], []
        if len(hidden) > 1:
            for n in hidden:
                surf = case_surface if n == "microtexture" else truth_surface
                eff = [e for e in truth_effects if e.name != n]
                withouts.append(persson.Model(surf, truth_material, effects=eff, grid=TRUTH_GRID))
                # what a diagnosis would refit with the other hidden effect in the model
                free.append(tuple(fit) + tuple(f"{m}.{q.name}" for m in hidden if m not in (n, "microtexture")
                                               for q in fx.get(m).parameters if q.fittable))
        else:
            withouts.append(persson.Model(case_surface, material, effects=base_true, grid=TRUTH_GRID))
            free.append(tuple(fit))
        # for a contact given off, the hidden change is that of the contact: the withouts take the one given
        contact_without = contact_truth if "contact" not in notes else replace(contact_truth,
                                                                                **notes["contact"]["given"])
        effect_rms = min(float(np.sqrt(np.mean((mu_true - validation.predict(w, skeleton, contact_without).mu)
                                               ** 2))) for w in withouts)
        unabsorbed, known = math.nan, {}
        # the sets are added to this (tau_f0 refitted)
        baseline = persson.Model(case_surface, material, effects=base_true)
        truth_rows = validation.Measurements.from_arrays(slip=slip, speed=V, temperature=T, pressure=p, mu=mu_true,
                                                         wet=wet.astype(bool), contact=contact_case)
        if kind in ("single", "pair"):
            unabsorbed = min(_unabsorbed_rms(w, truth_rows, contact_case, names) for w, names in zip(withouts, free))
        elif kind == "outside":
            # what the best single candidate, fitted with the baseline, leaves of the outside physics
            unabsorbed = _closest_other_set("single", (), baseline, truth_rows, contact_case, fit, known)[0]
    if kind in ("null", "wet"):
        ratio, sigma = math.nan, 10 ** rng.uniform(math.log10(0.004), math.log10(0.02))
    else:
        ratio = 10 ** rng.uniform(math.log10(0.5), math.log10(20.0))
        sigma = float(np.clip(effect_rms / ratio, 0.002, 0.05))
        ratio = effect_rms / sigma
    distinguishable = unabsorbed / sigma if kind in ("single", "pair", "outside") else math.nan
    separable, closest = math.nan, ()
    if distinguishable >= 2:
        # only where the hidden physics shows at all: a fit per candidate set, the slowest part of a draw
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            rms, closest = _closest_other_set(kind, hidden_names, baseline, truth_rows, contact_case, fit, known)
        separable = rms / sigma
    # proportional noise: each row's standard deviation in proportion to its mu (a force sensor's relative error),
    # sigma at the case's mean mu
    scale = mu_true / float(np.mean(mu_true)) if noise == "proportional" else np.ones(mu_true.size)
    mu = np.clip(mu_true + rng.normal(0.0, sigma, mu_true.size) * scale, 0.0, None)
    meas = validation.Measurements.from_arrays(slip=slip, speed=V, temperature=T, pressure=p, mu=np.round(mu, 6),
                                               mu_std=sigma * scale if use_std else None,
                                               wet=wet.astype(bool), source=f"blind case {index}", contact=contact_case)
    return BlindCase(index=index, kind=kind, hidden=hidden, model=case_model, measurements=meas,
                     contact=contact_case, fit=fit, ratio=ratio, sigma=sigma, distinguishable=distinguishable,
                     separable=separable, closest=closest,
                     noise_kind="mu_std" if use_std else "replicates" if replicate else "local differences",
                     notes=notes, truth=truth, truth_contact=contact_truth, mu_true=mu_true)


def _closest_other_set(kind, hidden, base, truth_rows, contact, fit, known) -> tuple[float, tuple]:
    """(rms, set): the candidate set other than the hidden one whose fit to the noise-free truth (with the baseline
    and its fitted parameters) leaves the least of it. Sets of one candidate for a hidden single effect (a larger set
    that fits as well loses on its parameter count), of one or two otherwise (physics outside the candidates may be
    absorbed by two together). Where this is within the noise, no selection can tell the answer from that set.
    ``known``: rms already computed for some sets."""
    pool = [n for n in SINGLES if not (n == "patch_heating" and contact is None) and n not in base.effect_names]
    best = (math.inf, ())
    for k in range(1, (1 if kind == "single" else 2) + 1):
        for names in itertools.combinations(pool, k):
            if set(names) == set(hidden):
                continue
            if names not in known:
                try:
                    known[names] = _set_rms(base, names, truth_rows, contact, fit, release=False)
                except frictionerrors.InputError:
                    # a placeholder the case cannot compute (Microtexture.hurst on a PSD table that ends at its
                    # roll-off): fitted instead, as the diagnosis does (validation.fitting.release_placeholders)
                    known[names] = _set_rms(base, names, truth_rows, contact, fit, release=True)
            best = min(best, (known[names], names))
    return best


def _set_rms(base, names, truth_rows, contact, fit, release: bool) -> float:
    """:func:`_unabsorbed_rms` of the baseline ``base`` with the candidates ``names`` added, their parameters free
    (with ``release``, those holding a placeholder as well, from the middle of their plausible range)."""
    from validation.fitting import release_placeholders

    model, free = base, tuple(fit)
    for n in names:
        e = fx.get(n)
        own = [q.name for q in e.parameters if q.fittable]
        released = release_placeholders(e) if release else None
        if released is not None:
            e, own, _ = released
        model = model.with_effect(e)
        free += tuple(f"{n}.{q}" for q in own)
    return _unabsorbed_rms(model, truth_rows, contact, free)


def _unabsorbed_rms(without, truth_rows, contact, names) -> float:
    """rms of the truth minus the best fit of ``without`` (the truth less one hidden effect, at the diagnosis's
    default grid) with the parameters ``names`` free (the case's fitted ones and those of its other hidden effect):
    the part of the hidden effect that nothing else in the model absorbs, which is what a diagnosis can detect."""
    from validation.candidates import FitSettings, fit_baseline
    from validation.diagnose import _baseline_params
    from validation.fitting import ParameterSpace
    from validation.predict import Predictor

    model = persson.Model(without.surface, without.material, effects=list(without.effects))
    settings = FitSettings(predictor=Predictor(truth_rows, contact), y=truth_rows.mu, w=np.ones(truth_rows.n),
                           sigma_known=False, contact=contact)
    base = fit_baseline(model, ParameterSpace(_baseline_params(model, names, contact)), settings)
    return math.sqrt(base.rss / truth_rows.n)


@dataclass(frozen=True, eq=False)
class ArrheniusFiller:
    r"""A compound with an extra Cole-Cole relaxation of its filler network whose relaxation time follows an
    Arrhenius law, :math:`\tau(T) = \tau_{ref}\exp[E_a/R (1/T - 1/T_{ref})]`, not the compound's WLF law (Cole &
    Cole, J. Chem. Phys. 9, 341 (1941)); no ``log10_aT``, so the engine evaluates it at each temperature."""

    base: object
    delta_E: float
    f_ref_Hz: float
    alpha: float
    E_a: float

    @property
    def thermal(self):
        return self.base.thermal

    def E(self, omega, T):
        omega = np.asarray(omega, dtype=float)
        T = np.asarray(T, dtype=float)
        tau = np.exp(self.E_a / 8.314462618 * (1.0 / (T + 273.15) - 1.0 / 293.15)) / (2 * math.pi * self.f_ref_Hz)
        x = (1j * omega * tau) ** self.alpha
        return self.base.E(omega, T) + self.delta_E * x / (1.0 + x)


@dataclass(frozen=True)
class PressureLaw(fx.Effect, register=False):
    r"""Friction that falls with the nominal pressure as a power law beyond what the engine's contact mechanics
    give: the hysteresis friction times :math:`(\sigma_0/\sigma_{ref})^{-n}` (an empirical load law of the kind
    fitted to tread-block data, e.g. Schallamach, Wear 6, 375 (1963), not a candidate of the diagnosis). The
    local pressure along a contact patch is the ``sigma_0`` of each point of it."""

    # not registered: physics the candidates must not contain
    name = "outside_pressure"
    parameters = (fx.Parameter("exponent", 0.2, (0.0, 1.0), "1", "n of the power law"),
                  fx.Parameter("p_ref", 0.3e6, (1e3, 1e8), "Pa", "pressure at which the factor is 1"))
    exponent: float = 0.2
    p_ref: float = 0.3e6

    def friction_term(self, state):
        factor = (np.asarray(state.conditions.pressure, dtype=float) / self.p_ref) ** (-self.exponent)
        return state.mu_hysteresis * (factor - 1.0)



def magic_formula_rows(slip, mu, rng) -> tuple[np.ndarray, dict]:
    r"""``mu`` with its slip rows (slip < 1) replaced by a Magic Formula curve, physics of another model than the
    brush model the diagnosis uses: :math:`\mu(s) = D \sin(C \arctan(B s - E (B s - \arctan B s)))` (Pacejka &
    Bakker, Vehicle System Dynamics 21 (sup1), 1 (1992); the longitudinal force against the slip ratio), C drawn
    from 1.3-1.8, E from -1 to 0.3, the peak at a slip drawn log-uniformly from 0.03-0.2 (which sets B), and D such
    that the curve meets the given ``mu`` at the largest slip of the rows (the rows of one sweep: one rolling speed,
    temperature and pressure); the draw is repeated until the peak is at most 1.4 times that value.

    Returns
    -------
    (ndarray, dict)
        The new ``mu`` and the curve's parameters.
    """
    from scipy.optimize import brentq

    rows = np.flatnonzero(np.asarray(slip) < 1.0)
    out = np.array(mu, dtype=float)
    if rows.size == 0:
        return out, {}
    s_last = float(np.asarray(slip)[rows].max())
    last = rows[np.argmax(np.asarray(slip)[rows])]
    # drawn until the peak is 1.0-1.4 times the value at the largest slip (a C near 2 with a peak at small slip
    # would fall to a third of its peak at large slip, which tread rubber on a road does not)
    while True:
        C, E = rng.uniform(1.3, 1.8), rng.uniform(-1.0, 0.3)
        s_peak = 10 ** rng.uniform(math.log10(0.03), math.log10(0.2))
        # the peak: C arctan(phi(B s)) = pi / 2 (phi increases with x for E <= 1)
        x_peak = brentq(lambda x: _phi(x, E) - math.tan(math.pi / (2.0 * C)), 1e-9, 1e6)
        B = x_peak / s_peak
        over = 1.0 / _mf_shape(s_last, B, C, E)
        if over <= 1.4:
            break
    D = float(mu[last] * over)
    out[rows] = D * _mf_shape(np.asarray(slip)[rows], B, C, E)
    return out, {"B": float(B), "C": float(C), "D": D, "E": float(E), "peak_slip": float(s_peak),
                 "peak_over_last": float(over)}


def _phi(x, E):
    return x - E * (x - np.arctan(x))


def _mf_shape(s, B, C, E):
    """The Magic Formula's sin(C arctan(B s - E (B s - arctan B s))) (:func:`magic_formula_rows`)."""
    return np.sin(C * np.arctan(_phi(B * np.asarray(s, dtype=float), E)))


def _surfaces(rng, micro: bool):
    """(truth surface, case surface): a sandpaper or a road, tabulated; with the microtexture hidden the case's
    table stops at a profilometer limit q_r while the truth continues the power law."""
    H = rng.uniform(0.7, 0.9)
    if rng.random() < 0.5:   # a road
        lam0, hrms = 10 ** rng.uniform(-3.0, -2.0), 10 ** rng.uniform(-4.0, math.log10(5e-4))
    else:                    # a sandpaper
        lam0, hrms = 10 ** rng.uniform(math.log10(2e-4), math.log10(8e-4)), 10 ** rng.uniform(math.log10(2e-5),
                                                                                               math.log10(8e-5))
    q0 = 2 * math.pi / lam0
    if micro:
        q_r = 10 ** rng.uniform(4.5, 5.2)
        q1_true = q_r * 10 ** rng.uniform(0.8, 1.3)
        sa = surfaces.SelfAffine(hurst=H, q0=q0, q1=q1_true, hrms=hrms, qL=q0 / rng.uniform(4.0, 15.0))
        full = sa.tabulate(n_per_decade=32)
        cut = sa.with_cutoff(q1=q_r).tabulate(n_per_decade=16)
        case = surfaces.PSD(cut.q, cut.C_values, q_r=float(cut.q[-1]), qL=cut.qL, q_rolloff=cut.q_rolloff,
                            hurst=cut.hurst, source="blind study: measured to q_r")
        return full, case
    sa = surfaces.SelfAffine(hurst=H, q0=q0, q1=1.0e6, hrms=hrms, qL=q0 / rng.uniform(4.0, 15.0))
    tab = sa.tabulate(n_per_decade=16)
    return sa.tabulate(n_per_decade=32), tab


def _compound(rng):
    """A generalized Maxwell solid: log-normal spectrum (3 terms per decade), WLF shift at 20 C."""
    tau = np.logspace(-15, 3, 55)
    centre, width = rng.uniform(-11.5, -9.5), rng.uniform(1.4, 2.0)
    w = np.exp(-(np.log10(tau) - centre) ** 2 / (2 * width ** 2)) + 0.01 * np.exp(
        -(np.log10(tau) - centre - 4.0) ** 2 / (2 * 2.5 ** 2))
    E_inf, E_glassy = rng.uniform(2e6, 5e6), rng.uniform(1e9, 3e9)
    E_i = w / w.sum() * (E_glassy - E_inf)
    return materials.Prony(E_inf=E_inf, E_i=E_i, tau_i=tau, wlf=materials.WLF(C1=rng.uniform(8.0, 10.0),
                                                                             C2=rng.uniform(90.0, 115.0),
                                                                             T_ref=20.0),
                           label="blind study compound")


def _hidden_params(name, rng, material, rows, truth_surface, case_surface) -> dict:
    if name == "adhesion":
        vs = rows.sliding_speed * 10.0 ** np.asarray(material.log10_aT(rows.temperature))
        return {"tau_f0": rng.uniform(0.5e6, 3e6), "c": rng.uniform(0.05, 0.3),
                "v_ref": 10 ** rng.uniform(math.log10(vs.min()) + 0.5, math.log10(vs.max()) - 0.5)}
    if name == "flash_temperature":
        return {"macro_scale_ratio": 10 ** rng.uniform(math.log10(1.5), math.log10(6.0))}
    if name == "microtexture":
        return {"q1": float(truth_surface.q_range[1])}
    if name == "strain_softening":
        return {"storage_factor": rng.uniform(0.5, 0.85), "loss_factor": rng.uniform(0.6, 0.95)}
    if name == "patch_heating":
        return {"counter_effusivity": 10 ** rng.uniform(math.log10(300.0), math.log10(3000.0))}
    raise ValueError(name)


# ==========================================================================================================
def run(case: BlindCase) -> dict:
    """Diagnose ``case`` as a user would and compare the outcome with the truth."""
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        imp = validation.improve(case.model, case.measurements, contact=case.contact, fit=case.fit)
    found = tuple(sorted(imp.added))
    truth = tuple(sorted(case.hidden))
    out = {"index": case.index, "kind": case.kind, "hidden": truth, "found": found, "verdict": imp.verdict,
           "ratio": case.ratio, "distinguishable": case.distinguishable, "separable": case.separable,
           "closest": list(case.closest), "sigma": case.sigma,
           "noise": case.noise_kind, "rows": case.measurements.n,
           "noise_estimate": imp.noise, "seconds": time.perf_counter() - t0, "n_evaluations": imp.n_evaluations,
           "supported": [list(s.effects) for s in imp.selection.supported] if imp.selection else [],
           "resumed": list(imp.selection.resumed) if imp.selection else [],
           "calibration_rivals": [f"{f.describe()} on {f.on}" for f in imp.selection.calibration.rivals]
           if imp.selection is not None and imp.selection.calibration is not None else [],
           "localized": None if imp.localized is None else imp.localized.family,
           "contact_refit": None if imp.localized is None or imp.localized.contact is None else
           imp.localized.contact.outcome,
           "traded": 0 if imp.localized is None else imp.localized.traded,
           # BIC units by which the refitted contact beats an offset of the slip ratios (negative: the offset wins)
           "contact_vs_offset": _contact_vs_offset(imp.localized),
           # rivals of the rig's calibration set aside because the refitted contact fits the rows better
           "calibration_deferred": [f"{f.describe()} on {f.on}" for f, _, _ in imp.selection.calibration.deferred]
           if imp.selection is not None and imp.selection.calibration is not None else [],
           # the contact parameters refitted and those kept as given (the length, where the rows fix only k l)
           "contact_names": None if imp.localized is None or imp.localized.contact is None else
           list(imp.localized.contact.names),
           "coverage": []}
    if case.kind == "outside":
        out["outside"] = next((k for k in ("shift", "pressure", "slip", "contact") if k in case.notes), "filler")
    if case.kind in ("single", "pair") and set(found) == set(truth):
        est = {e.key: e for e in imp.selection.best.estimates}
        for eff, params in case.hidden.items():
            for p, true in params.items():
                e = est.get(f"{eff}.{p}")
                if e is None:
                    continue
                lo, hi = e.interval
                in68 = lo <= true <= hi
                lo95, hi95 = e.interval95
                in95 = lo95 <= true <= hi95
                # as the study counted before intervals had a 95 % end of their own: 1.96 times the 68 % sides
                in95_gauss = e.value - 1.96 * (e.value - lo) <= true <= e.value + 1.96 * (hi - e.value)
                out["coverage"].append({"parameter": f"{eff}.{p}", "true": true, "value": e.value,
                                        "interval": [lo, hi], "interval95": [lo95, hi95], "in68": bool(in68),
                                        "in95": bool(in95), "in95_gauss": bool(in95_gauss)})
    return out


def _contact_vs_offset(localized):
    """-delta BIC of the refitted contact less the slip offset's gain (None without both)."""
    c = None if localized is None else localized.contact
    if c is None or not math.isfinite(c.slip_offset_gain):
        return None
    return float(-c.delta_bic - c.slip_offset_gain)


def right(r: dict) -> bool:
    """The outcome is right: nothing found on null and wet cases, exactly the hidden set otherwise, never
    ``explained`` for physics outside the candidates."""
    if r["kind"] in ("null", "wet"):
        return not r["found"] and r["verdict"] == "nothing_missing"
    if r["kind"] == "outside":
        return r["verdict"] != "explained"
    return set(r["found"]) == set(r["hidden"])


#: Sets whose fits to the noise-free truth differ by less than this in chi^2 (n r^2, r the separable ratio) are
#: within the band in which the selection calls sets equally supported (10 BIC units): a tie, not a miss.
TIE_GAP = 10.0


def _gap(r: dict) -> float:
    """n r^2: the chi^2 by which the closest other candidate set misses the noise-free truth (inf: not computed)."""
    sep = _value(r, "separable")
    return math.inf if math.isnan(sep) else r["rows"] * sep ** 2


def _value(r: dict, key: str) -> float:
    """``r[key]`` as a float, NaN where missing or not computed (JSON writes NaN as null)."""
    v = r.get(key)
    return math.nan if v is None else float(v)


def summarize(results: list) -> str:
    lines = []
    failed = [r for r in results if "error" in r]
    results = [r for r in results if "error" not in r]
    if failed:
        lines.append("Cases that raised (left out of every figure below; a later run on the same --out retries them): "
                     + "; ".join(f"case {r['index']} ({r['kind']}): {r['error']}" for r in failed))
    rows = sorted({"+".join(r["hidden"]) or r["kind"] for r in results})
    cols = ["(none)"] + list(SINGLES) + ["two or more"]
    short = {"(none)": "none", "adhesion": "adh", "flash_temperature": "flash", "microtexture": "micro",
             "strain_softening": "strain", "patch_heating": "patch", "two or more": "2+"}
    lines.append("Confusion matrix (rows: hidden physics; columns: effects found; counts)")
    lines.append(f"  {'hidden':<40}" + "".join(f"{short[c]:>8}" for c in cols) + f"{'right':>8}")
    for name in rows:
        sel = [r for r in results if ("+".join(r["hidden"]) or r["kind"]) == name]
        counts = {c: 0 for c in cols}
        for r in sel:
            f = r["found"]
            counts["(none)" if not f else f[0] if len(f) == 1 else "two or more"] += 1
        lines.append(f"  {name:<40}" + "".join(f"{counts[c]:>8}" for c in cols)
                     + f"{sum(right(r) for r in sel):>5}/{len(sel)}")
    hid = [r for r in results if r["kind"] in ("single", "pair")]
    named = [r for r in hid if not right(r) and sorted(r["hidden"]) in [sorted(x) for x in r["supported"]]]
    lines.append(f"Hidden effects missed but named among the equally supported sets (the verdict says the data cannot "
                 f"tell them apart): {len(named)} of {sum(not right(r) for r in hid)} misses"
                 + (" (cases " + ", ".join(str(r["index"]) for r in named) + ")" if named else ""))
    nw = [r for r in results if r["kind"] in ("null", "wet")]
    fa = [r for r in nw if not right(r)]
    lines.append(f"False alarms on null and wet cases: {len(fa)} of {len(nw)}" + (
        " (" + "; ".join(f"case {r['index']}: {r['verdict']} {r['found']}" for r in fa) + ")" if fa else ""))
    cal = [r for r in results if r.get("calibration_rivals")]
    if any("calibration_rivals" in r for r in results):
        lines.append(f"A calibration error of the rig named as a rival (no case has one): {len(cal)} of "
                     f"{sum('calibration_rivals' in r for r in results)}" + (" (" + "; ".join(
                         f"case {r['index']}: {r['calibration_rivals'][0]}" for r in cal) + ")" if cal else ""))
    gone = [r for r in results if r.get("calibration_deferred")]
    if gone:
        lines.append(f"  offsets of the slip ratios no longer named because the refitted contact fits better by 10 "
                     f"BIC units: {len(gone)} (" + ", ".join(f"case {r['index']}" for r in gone) + ")")
    out = [r for r in results if r["kind"] == "outside"]
    lines.append(f"Physics outside the candidates called explained: {sum(r['verdict'] == 'explained' for r in out)} "
                 f"of {len(out)} (verdicts: {', '.join(r['verdict'] for r in out) or '-'})")
    physics = sorted({r.get("outside", "filler") for r in out})
    if len(physics) > 1:
        lines.append("  by physics: " + "; ".join(
            f"{ph} {sum(r['verdict'] == 'explained' for r in out if r.get('outside', 'filler') == ph)} of "
            f"{sum(r.get('outside', 'filler') == ph for r in out)}" for ph in physics))
    far = [r for r in out if r.get("distinguishable", math.nan) >= 2]
    if far:
        lines.append(f"  of those that no single candidate absorbs (distinguishable ratio >= 2, what the best "
                     f"candidate fitted to the noise-free truth leaves, over the noise): "
                     f"{sum(r['verdict'] == 'explained' for r in far)} of {len(far)}; the others: " + ", ".join(
                         f"case {r['index']} {r['distinguishable']:.2f} {r['verdict']}"
                         for r in out if r not in far))
    tied = [r for r in out if _value(r, "distinguishable") >= 2 and _value(r, "separable") < 2]
    if tied:
        lines.append("  of those, absorbed by a set of two candidates (separable ratio < 2): " + ", ".join(
            f"case {r['index']} {'+'.join(r['closest'])} {r['separable']:.2f} {r['verdict']}" for r in tied))
    placed = [r for r in results if r.get("localized")]
    if any("localized" in r for r in results):
        lines.append(f"Misfit placed in one family of rows by the verdict (validation.localize): {len(placed)} of "
                     f"{len(results)}" + (" (" + ", ".join(
                         f"case {r['index']} {r['kind']} {r['localized']}" + (" after a refit" if r.get("traded")
                                                                              else "")
                         for r in placed) + ")" if placed else ""))
    refits = [r for r in results if r.get("contact_refit")]
    if refits:
        lines.append(f"  the brush contact refitted where it is in the rows with slip: explains the misfit in "
                     f"{sum(r['contact_refit'] == 'explains' for r in refits)} of {len(refits)}, takes most of it in "
                     f"{sum(r['contact_refit'] == 'takes_most' for r in refits)}" + " (" + ", ".join(
                         f"case {r['index']} {r.get('outside', r['kind'])} {r['contact_refit']}" for r in refits)
                     + ")")
        alone = [r for r in refits if r.get("contact_names") == ["stiffness"]]
        if any("contact_names" in r for r in refits):
            lines.append(f"  the stiffness refitted alone, the length kept as given (the rows fix only their product): "
                         f"{len(alone)} of {len(refits)}")
        vs = [r["contact_vs_offset"] for r in refits if r.get("contact_vs_offset") is not None]
        if vs:
            lines.append(f"  against an offset of the slip ratios fitted on the same model: the contact better by 10 "
                         f"BIC units or more in {sum(v >= 10 for v in vs)}, the offset in {sum(v <= -10 for v in vs)}, "
                         f"within 10 in {sum(abs(v) < 10 for v in vs)} (of {len(vs)})")
    for key, title in (("ratio", "the effect-to-noise ratio (the truth's change of mu without the effect)"),
                       ("distinguishable", "the distinguishable ratio (what a refit of the other parameters leaves "
                                           "of that change)")):
        if not any(key in r for r in results):
            continue
        lines.append(f"Detection against {title} (right / cases)")
        for kind in ("single", "pair"):
            sel = [r for r in results if r["kind"] == kind and key in r]
            parts = []
            for lo, hi in zip((0.0,) + RATIO_BINS[1:-1], RATIO_BINS[1:-1] + (math.inf,)):
                b = [r for r in sel if lo <= r[key] < hi]
                parts.append(f"{lo:g}-{hi:g}: {sum(right(r) for r in b)}/{len(b)}")
            ge2 = [r for r in sel if r[key] >= 2]
            lines.append(f"  {kind:<7} " + ", ".join(parts)
                         + f"; at ratio >= 2: {sum(right(r) for r in ge2)}/{len(ge2)}")
            if key == "distinguishable" and any(not math.isnan(_value(r, "separable")) for r in ge2):
                ties = [r for r in ge2 if _gap(r) < TIE_GAP]
                sep = [r for r in ge2 if r not in ties]
                lines.append(f"          where no other set comes within {TIE_GAP:g} units of chi^2 of the truth (n "
                             f"times the separable ratio squared): {sum(right(r) for r in sep)}/{len(sep)}"
                             + ("; the others: " + ", ".join(
                                 f"case {r['index']} {'ok' if right(r) else 'missed'} ({'+'.join(r['closest'])}: "
                                 f"{r['separable']:.2f}, {_gap(r):.1f})" for r in ties) if ties else ""))
    cov = [c for r in results for c in r["coverage"]]
    if cov:
        lines.append(f"Coverage of the reported intervals (parameters of hidden effects found exactly, {len(cov)} "
                     f"parameters): 68 %: {100 * np.mean([c['in68'] for c in cov]):.0f} %, 95 %: "
                     f"{100 * np.mean([c['in95'] for c in cov]):.0f} % (1.96 times the 68 % sides: "
                     f"{100 * np.mean([c.get('in95_gauss', c['in95']) for c in cov]):.0f} %)")
    secs = [r["seconds"] for r in results]
    lines.append(f"Time per case: median {np.median(secs):.0f} s, max {max(secs):.0f} s ({len(results)} cases)")
    # model evaluations do not depend on the machine or its load: the figure to compare between versions
    evals = [r["n_evaluations"] for r in results if "n_evaluations" in r]
    if evals:
        lines.append(f"Model evaluations per case: median {np.median(evals):.0f}, max {max(evals)}, "
                     f"{sum(evals)} in all")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=100, help="number of cases (default 100)")
    ap.add_argument("--seed", type=int, default=1, help="seed of the study (default 1)")
    ap.add_argument("--start", type=int, default=0, help="index of the first case (to split a study in parts)")
    ap.add_argument("--kinds", default="", help="comma-separated kinds to run (null, wet, single, pair, outside)")
    ap.add_argument("--outside", default="filler", choices=OUTSIDE,
                    help="the physics outside the candidates of the outside cases (default filler)")
    ap.add_argument("--noise", default="constant", choices=NOISE,
                    help="the noise's standard deviation the same on every row (constant, the default) or in "
                         "proportion to the row's true mu (proportional)")
    ap.add_argument("--out", default=None, help="JSON file for the per-case results (appended to when it exists)")
    args = ap.parse_args(argv)
    kinds = set(filter(None, args.kinds.split(",")))
    results = []
    if args.out:
        from pathlib import Path

        if Path(args.out).is_file():
            results = json.loads(Path(args.out).read_text())
    # a case that raised is tried again by the next run on the same file
    results = [r for r in results if "error" not in r]
    done = {(r["index"]) for r in results}
    for i in range(args.start, args.start + args.n):
        if i in done or (kinds and SCHEDULE[i % len(SCHEDULE)] not in kinds):
            continue
        try:
            case = draw(i, args.seed, outside=args.outside, noise=args.noise)
            r = run(case)
        except Exception as exc:  # noqa: BLE001  (one case's failure must not end a study of hours)
            # recorded and reported, not hidden: the summary lists it, and a later run retries it
            results.append({"index": i, "kind": SCHEDULE[i % len(SCHEDULE)], "error": f"{type(exc).__name__}: {exc}",
                            "traceback": traceback.format_exc()})
            print(f"case {i:>3} {SCHEDULE[i % len(SCHEDULE)]:<8} RAISED {type(exc).__name__}: {exc}", flush=True)
            if args.out:
                json_text(results, args.out, overwrite=True)
            continue
        results.append(r)
        print(f"case {i:>3} {case.kind:<8} hidden {'+'.join(r['hidden']) or '-':<36} ratio {r['ratio']:6.2f} "
              f"({r['distinguishable']:6.2f}, {_value(r, 'separable'):6.2f}) "
              f"{r['rows']:>3} rows {r['noise']:<18} -> {r['verdict']:<17} {'+'.join(r['found']) or '-':<36} "
              f"{'ok' if right(r) else 'WRONG'} ({r['seconds']:.0f} s)", flush=True)
        if args.out:
            json_text(results, args.out, overwrite=True)  # the study appends to its own file
    print()
    print(summarize(results))
    return 0


if __name__ == "__main__":
    sys.exit(main())
