"""Model predictions for measurement rows, batched: one engine call per (temperature, pressure, wet) group.

* ``slip == 1`` rows: the sliding friction ``model.friction(V, T, sigma0).mu``;
* ``slip < 1`` rows: the brush model :func:`persson.slip.mu_slip` (contact from the case), whose local friction
  mu(v_s) is the same model at the sliding speeds v_s = s V;
* ``wet`` rows: the model with :class:`persson.effects.Wet` (the model's own ``wet`` effect when it has one, else
  ``Wet()`` at its defaults); dry rows use the model without any ``wet`` effect.
* a model with :class:`persson.effects.PatchHeating`: every row, sliding ones included (``slip = 1``, the locked
  wheel), goes through the contact patch with the local pressure and the background temperature along it
  (:func:`persson.slip.patch_friction`); this needs the contact.

All sliding speeds a group needs (V of its sliding rows and s V of its slip rows) go into one
``model.friction`` call; the slip rows then reuse those values through the callable form of ``mu_slip``. With
patch heating each wet/dry group takes two engine calls (the friction table at T0, then over the heated
temperatures) for all its rows.
"""

from __future__ import annotations

import warnings
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np

from .errors import InputError
from .measurements import Measurements

__all__ = ["Prediction", "predict", "Predictor", "wet_model", "dry_model", "mostly_extrapolated", "MOSTLY_EXTRAPOLATED"]


@dataclass(frozen=True, eq=False)
class Prediction:
    """Predicted friction for every measurement row.

    Attributes
    ----------
    mu : ndarray
        Predicted friction coefficient per row.
    mu_local : ndarray
        Local sliding friction mu(v_s) at each row's sliding speed, T0 and sigma0 (equals ``mu`` on sliding rows
        unless the model has patch heating, which heats the locked wheel's patch too).
    converged : bool
        Whether every self-consistent iteration (flash temperature) converged.
    notes : tuple of str
        Notes of the friction results (extrapolated tails, convergence), without repeats.
    modulus_extrapolated_share : ndarray or None
        Per row, the share of the hysteresis friction at its sliding point (v_s, T0, sigma0) that comes from
        reduced frequencies outside the compound's measured master curve
        (``persson.FrictionResult.modulus_extrapolated_share``); on rows predicted with patch heating, at the
        sliding point before the patch heats the rubber (the heated patch lowers the reduced frequencies, so the
        share beyond the top of the data is at most this one). None when the compound has no measured range and
        in a fit's predictions (:meth:`Predictor.predict` without ``full``).
    """

    mu: np.ndarray
    mu_local: np.ndarray
    converged: bool = True
    notes: tuple = ()
    modulus_extrapolated_share: np.ndarray | None = None


#: A row rests mostly on the master curve's extrapolation when more than this share of its predicted hysteresis
#: comes from reduced frequencies beyond the curve's data.
MOSTLY_EXTRAPOLATED = 0.5


def mostly_extrapolated(share) -> np.ndarray:
    """Indices of the rows that rest mostly on the master curve's extrapolation (``share`` per row, as
    :attr:`Prediction.modulus_extrapolated_share`; empty when it is None)."""
    if share is None:
        return np.empty(0, dtype=int)
    return np.flatnonzero(np.asarray(share, dtype=float) > MOSTLY_EXTRAPOLATED)


def predict(model, measurements: Measurements, contact=None) -> Prediction:
    """Predict every measurement row with ``model`` (see the module docstring).

    Parameters
    ----------
    model : persson.Model
    measurements : Measurements
    contact : persson.slip.Contact, optional
        Needed when some rows have slip < 1 (default: ``measurements.contact``).

    Returns
    -------
    Prediction
    """
    return Predictor(measurements, contact).predict(model, full=True)


def wet_model(model):
    """The model used on wet rows: with its own ``wet`` effect, else with ``Wet()`` added."""
    from persson.effects import Wet

    return model if "wet" in model.effect_names else model.with_effect(Wet())


def dry_model(model):
    """The model used on dry rows: without a ``wet`` effect."""
    return model.without("wet") if "wet" in model.effect_names else model


class Predictor:
    """Reusable, batched predictor for one set of measurement rows (used by compare and diagnose).

    Parameters
    ----------
    measurements : Measurements
    contact : persson.slip.Contact or None
    """

    def __init__(self, measurements: Measurements, contact=None):
        if not isinstance(measurements, Measurements):
            raise InputError(f"measurements: expected validation.Measurements, got {type(measurements).__name__}")
        m = measurements
        if contact is None:
            contact = m.contact
        if m.has_slip_rows:
            from persson.slip import Contact

            if contact is None:
                i = int(np.argmax(m.slip < 1))
                raise InputError(f"{m.row_label(i)}: rows with slip < 1 need the brush model: give contact= "
                                 "(persson.slip.Contact) or a [contact] table in the case file")
            if not isinstance(contact, Contact):
                raise InputError(f"contact: expected persson.slip.Contact, got {contact!r}")
        self.measurements = m
        self.contact = contact
        self.n_calls = 0
        self._patch_tables: dict = {}  # friction tables of patch heating, per wet/dry group
        # solutions of the engine kept across predictions: a fit of parameters that do not enter the solver
        # (adhesion, the patch heating, the contact) solves each set of conditions once
        self._solutions: OrderedDict = OrderedDict()
        # One engine call per wet/dry group: every distinct (sliding speed, temperature, pressure) of the rows
        # is one "speed" of that call (the engine takes a temperature and a pressure per speed).
        by_wet: dict[bool, list[int]] = {}
        for i in range(m.n):
            by_wet.setdefault(bool(m.wet[i]), []).append(i)
        self.groups = []
        for wet, idx in by_wet.items():
            idx = np.asarray(idx, dtype=int)
            s = m.slip[idx]
            points, inverse = np.unique(np.column_stack([s * m.speed[idx], m.temperature[idx], m.pressure[idx]]),
                                        axis=0, return_inverse=True)
            inverse = np.asarray(inverse).ravel()
            sweeps = []
            slip_rows = np.flatnonzero(s < 1.0)
            if slip_rows.size:
                Tp, which = np.unique(np.column_stack([m.temperature[idx[slip_rows]], m.pressure[idx[slip_rows]]]),
                                      axis=0, return_inverse=True)
                which = np.asarray(which).ravel()
                for k, (T, p) in enumerate(Tp):
                    at = (points[:, 1] == T) & (points[:, 2] == p)
                    sweeps.append(_SlipSweep(T=float(T), p=float(p), rows=idx[slip_rows[which == k]],
                                             points=np.flatnonzero(at)))
            self.groups.append(_Group(wet=wet, idx=idx, points=points, inverse=inverse, slide=idx[s >= 1.0],
                                      sweeps=tuple(sweeps)))

    def predict(self, model, contact=None, *, full: bool = False) -> Prediction:
        """Predictions of ``model`` for every row (with ``contact`` instead of the predictor's, when given: e.g.
        a refitted one). A fit's predictions read the friction alone (:func:`persson.solver.friction_only`);
        ``full=True`` keeps the share of the friction from the master curve's extrapolation
        (``Prediction.modulus_extrapolated_share``), for a one-off prediction."""
        if contact is not None and contact is not self.contact:
            import copy

            other = copy.copy(self)
            other.contact = contact
            try:
                return other.predict(model, full=full)
            finally:
                self.n_calls = other.n_calls
        if not (hasattr(model, "friction") and hasattr(model, "effect_names")):
            raise InputError(f"model: expected a persson.Model, got {type(model).__name__}")
        from persson.solver import friction_only, reuse_solutions

        # predictions read the friction (and, in full, the share of it from the master curve's extrapolation): the
        # contact geometry of each result would cost a fifth of a solve
        with reuse_solutions(self._solutions), friction_only(share=full):
            return self._predict(model, full)

    def _predict(self, model, full: bool = False) -> Prediction:
        m = self.measurements
        mu = np.empty(m.n)
        mu_loc = np.empty(m.n)
        notes: dict[str, None] = {}
        raised: dict[tuple, None] = {}
        converged = True
        dry = wet = None
        share = np.empty(m.n)
        shared = True   # every group gave its share
        for g in self.groups:
            if g.wet:
                if wet is None:
                    wet = wet_model(model)
                mg = wet
            else:
                if dry is None:
                    dry = dry_model(model)
                mg = dry
            if "patch_heating" in mg.effect_names:
                sol = self._patch(mg, g.idx, g.wet)
                mu[g.idx] = sol.mu
                mu_loc[g.idx] = sol.mu_local
                notes.update(dict.fromkeys(sol.notes))
                converged = converged and bool(sol.converged)
                at = self._patch_share(mg, g) if full and shared else None
                if at is None:
                    shared = False
                else:
                    share[g.idx] = at
                continue
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                r = mg.friction(g.points[:, 0], temperature=g.points[:, 1], pressure=g.points[:, 2])
            self.n_calls += 1
            for note in r.notes:
                notes[note] = None
            for w in caught:  # the engine's warnings are among its notes already: each once, and warned below
                raised[(w.category, str(w.message))] = None
                notes[str(w.message)] = None
            converged = converged and bool(r.converged)
            mu_g = np.atleast_1d(np.asarray(r.mu, dtype=float))
            if not np.all(np.isfinite(mu_g)):
                bad = g.points[int(np.argmax(~np.isfinite(mu_g)))]
                raise InputError(f"model: non-finite friction at v = {bad[0]:g} m/s, T = {bad[1]:g} C, "
                                 f"p = {bad[2]:g} Pa")
            mu_loc[g.idx] = mu_g[g.inverse]
            if r.modulus_extrapolated_share is None:
                shared = False
            elif shared:
                share[g.idx] = np.atleast_1d(np.asarray(r.modulus_extrapolated_share, dtype=float))[g.inverse]
            if g.slide.size:
                mu[g.slide] = mu_loc[g.slide]
            for sw in g.sweeps:
                mu[sw.rows] = self._brush(sw, g.points[sw.points, 0], mu_g[sw.points], m.slip[sw.rows],
                                          m.speed[sw.rows])
        for category, message in raised:
            warnings.warn(message, category, stacklevel=2)
        return Prediction(mu=mu, mu_local=mu_loc, converged=converged, notes=tuple(notes),
                          modulus_extrapolated_share=share if shared else None)

    def _patch(self, model, rows, key):
        """Patch-heating predictions of ``rows`` (one table, two engine calls; the table is kept per wet/dry group
        and reused while only the contact changes, e.g. in a fit of the contact stiffness)."""
        from persson.slip import patch_friction


        if self.contact is None:
            raise InputError("patch_heating: the model heats the contact patch, which needs the contact: give "
                             "contact= (persson.slip.Contact) or a [contact] table in the case file")
        m = self.measurements
        sol = patch_friction(model, model.effect("patch_heating"), self.contact, m.slip[rows], m.speed[rows],
                             m.temperature[rows], m.pressure[rows], tables=self._patch_tables.setdefault(key, {}))
        self.n_calls += sol.engine_calls
        if not np.all(np.isfinite(sol.mu)):
            raise InputError("model: non-finite friction along the contact patch")
        return sol

    def _patch_share(self, model, g) -> np.ndarray | None:
        """The extrapolated share of the rows of a patch-heating group, at their sliding points (v_s, T0, sigma0)
        before the patch heats them (one engine call without the patch heating; None when the compound has no
        measured range). The patch's tables keep the friction only; a heated patch takes the rubber to lower
        reduced frequencies, so the share beyond the top of the data is at most this one."""
        engine = model.without("patch_heating")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the engine's warnings are the patch solution's already
            r = engine.friction(g.points[:, 0], temperature=g.points[:, 1], pressure=g.points[:, 2])
        self.n_calls += 1
        if r.modulus_extrapolated_share is None:
            return None
        return np.atleast_1d(np.asarray(r.modulus_extrapolated_share, dtype=float))[g.inverse]

    def _brush(self, sw, speeds, mu_s, slip, V):
        """mu(slip, V) of the brush model for the rows of one (T, p) slip sweep, from precomputed mu(v_s)."""
        from persson.slip import mu_slip

        order = np.argsort(speeds)
        speeds, mu_s = speeds[order], mu_s[order]

        def local(vs):
            vs = np.asarray(vs, dtype=float)
            j = np.clip(np.searchsorted(speeds, vs), 0, speeds.size - 1)
            jm = np.clip(j - 1, 0, speeds.size - 1)
            pick = np.where(np.abs(speeds[jm] - vs) < np.abs(speeds[j] - vs), jm, j)
            if np.any(np.abs(speeds[pick] - vs) > 1e-9 * vs):
                raise InputError("internal: sliding speed not in the precomputed set")
            return mu_s[pick]

        res = mu_slip(local, slip, V, temperature=sw.T, pressure=sw.p, contact=self.contact)
        return np.atleast_1d(np.asarray(res.mu, dtype=float))

    # ---- curves for plots -----------------------------------------------------------------------------------
    def curve(self, model, speeds, T: float, p: float, wet: bool) -> np.ndarray:
        """Sliding friction of ``model`` at ``speeds`` (one call), dry or wet (with patch heating and a contact:
        the locked wheel's patch, as on sliding rows)."""
        mg = wet_model(model) if wet else dry_model(model)
        if "patch_heating" in mg.effect_names and self.contact is not None:
            from persson.slip import patch_friction

            v = np.atleast_1d(np.asarray(speeds, dtype=float))
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                sol = patch_friction(mg, mg.effect("patch_heating"), self.contact, np.ones(v.size), v, T, p)
            self.n_calls += sol.engine_calls
            return sol.mu
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = mg.friction(np.asarray(speeds, dtype=float), temperature=T, pressure=p)
        self.n_calls += 1
        return np.atleast_1d(np.asarray(r.mu, dtype=float))

    def slip_curve(self, model, slips, V: float, T: float, p: float, wet: bool) -> np.ndarray:
        """mu(slip) of the brush model at rolling speed ``V`` (one friction call)."""
        from persson.slip import mu_slip

        if self.contact is None:
            raise InputError("slip curves need a contact (persson.slip.Contact)")
        mg = wet_model(model) if wet else dry_model(model)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            res = mu_slip(mg, np.asarray(slips, dtype=float), float(V), temperature=T, pressure=p,
                          contact=self.contact)
        self.n_calls += 1
        return np.atleast_1d(np.asarray(res.mu, dtype=float))


@dataclass(frozen=True, eq=False)
class _SlipSweep:
    T: float
    p: float
    rows: np.ndarray      # measurement rows with slip < 1 at this (T, p)
    points: np.ndarray    # indices into the group's points at this (T, p)


@dataclass(frozen=True, eq=False)
class _Group:
    wet: bool
    idx: np.ndarray       # measurement rows of the group
    points: np.ndarray    # distinct (sliding speed, T, p), shape (n, 3)
    inverse: np.ndarray   # row of idx -> its point
    slide: np.ndarray     # rows with slip = 1
    sweeps: tuple         # _SlipSweep per (T, p) of the slip rows
