r"""Ambiguity between candidate effects: near-parallel signatures, and the measurement that would separate them.

Candidates whose projected signatures -- at the given parameters, or the refitted changes :math:`f_{refit} - f_0`
-- have :math:`|\cos| >` :data:`COSINE_THRESHOLD` (with the baseline's Jacobian projected out) form a cluster.
For each pair (cluster head vs other) both refitted models are evaluated on the probe conditions of
:mod:`validation.probe` with the fit's own prediction path, and the condition with the largest
:math:`|\Delta\mu|` is reported as the measurement that would separate them (and the largest one inside the
measured conditions, judged by the distance to the nearest measured row).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .probe import Separation, probe_rows, scaled_distance, separation

__all__ = ["Ambiguity", "Separation", "Probe", "clusters", "separate", "COSINE_THRESHOLD"]

COSINE_THRESHOLD = 0.95


@dataclass(frozen=True)
class Ambiguity:
    """Candidates with near-parallel signatures, and where to measure to tell them apart.

    Attributes
    ----------
    effects : tuple of str
        Best-ranked first.
    cosines : dict
        ``"a|b" -> max(|cos| of projected signatures, |cos| of projected refitted changes)``.
    separations : tuple of Separation
        For the head and each other member: the largest difference on the probe grid.
    separations_in_range : tuple of Separation
        The same restricted to the measured ranges.
    """

    effects: tuple
    cosines: dict
    separations: tuple = ()
    separations_in_range: tuple = ()

    def as_dict(self) -> dict:
        """The cluster as a JSON-ready dict.

        Returns
        -------
        dict
            ``effects``, ``cosines``, ``separations`` and ``separations_in_measured_range`` (each a list of
            :meth:`Separation.as_dict`).
        """
        return {"effects": list(self.effects), "cosines": dict(self.cosines),
                "separations": [s.as_dict() for s in self.separations],
                "separations_in_measured_range": [s.as_dict() for s in self.separations_in_range]}


# ==========================================================================================================
def clusters(results, Q, w) -> list:
    """Clusters of ok candidates (ranked) whose projected signatures or changes are near-parallel."""
    ok = [c for c in results if c.status == "ok" and c.signature is not None]
    if len(ok) < 2:
        return []
    sig = [_proj(c.signature, Q, w) for c in ok]
    chg = [_proj(c.change, Q, w) for c in ok]
    parent = list(range(len(ok)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    cosines = {}
    for i in range(len(ok)):
        for j in range(i + 1, len(ok)):
            c = max(abs(_cos(sig[i], sig[j])), abs(_cos(chg[i], chg[j])))
            if c > COSINE_THRESHOLD:
                cosines[(i, j)] = c
                parent[find(j)] = find(i)
    groups: dict[int, list[int]] = {}
    for i in range(len(ok)):
        groups.setdefault(find(i), []).append(i)
    out = []
    for members in groups.values():
        if len(members) < 2:
            continue
        members.sort()  # results are ranked, so the first is the best
        cs = {f"{ok[i].effect}|{ok[j].effect}": round(c, 4) for (i, j), c in cosines.items()
              if i in members and j in members}
        out.append(Ambiguity(effects=tuple(ok[i].effect for i in members), cosines=cs))
    return out


def separate(clusters, results, m, contact):
    """The clusters with their separating conditions (:mod:`validation.probe`); returns (clusters, engine calls)."""
    by_name = {c.effect: c for c in results}
    probe = Probe(m, contact)
    out = []
    for cl in clusters:
        seps, seps_in = [], []
        head = cl.effects[0]
        for other in cl.effects[1:]:
            pair = probe.pair((head, other), [(by_name[e].model, by_name[e].contact or contact) for e in (head, other)])
            if pair is None:
                continue
            seps.append(pair[0])
            if pair[1] is not None:
                seps_in.append(pair[1])
        out.append(Ambiguity(effects=cl.effects, cosines=cl.cosines, separations=tuple(seps),
                             separations_in_range=tuple(seps_in)))
    return out, probe.calls


class Probe:
    """Predictions of fitted models on the probe conditions of measurements ``m`` (:mod:`validation.probe`),
    through :class:`validation.predict.Predictor` (one per contact), each model evaluated once."""

    def __init__(self, m, contact):
        from .predict import Predictor

        self.rows = probe_rows(m, contact)
        self.distance = scaled_distance(self.rows, m)
        self.predictor = Predictor(self.rows, contact)
        self.calls = 0
        self._mu: dict = {}

    def mu(self, model, contact):
        """Predicted mu of ``model`` with ``contact`` on every probe row (computed once per model and contact, then
        reused); None when the prediction fails."""
        key = (id(model), id(contact))
        if key not in self._mu:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # notes of a probe beyond the data are not the fit's notes
                n0 = self.predictor.n_calls
                try:
                    self._mu[key] = (model, self.predictor.predict(model, contact=contact).mu)
                except Exception:  # noqa: BLE001  (a model that fails beyond the data separates nothing)
                    self._mu[key] = (model, None)
                self.calls += self.predictor.n_calls - n0
        return self._mu[key][1]

    def pair(self, names, models):
        """(largest difference anywhere, largest inside the measured conditions or None), or None."""
        a, b = (self.mu(mod, con) for mod, con in models)
        if a is None or b is None:
            return None
        return (separation(names, (a, b), self.rows, self.distance),
                separation(names, (a, b), self.rows, self.distance, inside=True))


# ---- helpers -----------------------------------------------------------------------------------------------
def _proj(v, Q, w):
    vw = v * w
    return vw - Q @ (Q.T @ vw) if Q.shape[1] else vw


def _cos(a, b) -> float:
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    if na <= 1e-300 or nb <= 1e-300:
        return 0.0
    return float(a @ b) / (na * nb)
