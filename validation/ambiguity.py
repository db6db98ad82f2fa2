r"""Ambiguity between candidate effects: near-parallel signatures, and the measurement that would separate them.

Candidates whose projected signatures -- at the given parameters, or the refitted changes :math:`f_{refit} - f_0`
-- have :math:`|\cos| >` :data:`COSINE_THRESHOLD` (with the baseline's Jacobian projected out) form a cluster.
For each pair (cluster head vs other) both refitted models are evaluated on a probe grid of conditions (sliding
speeds one decade beyond the data, the measured temperatures and 20 K beyond, the measured pressures and a factor
2 beyond, slip ratios 0.02-0.3 when a contact is given) and the condition with the largest :math:`|\Delta\mu|` is
reported as the measurement that would separate them (and the largest one inside the measured ranges).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .measurements import Measurements
from .predict import dry_model, wet_model

__all__ = ["Ambiguity", "Separation", "clusters", "separate", "COSINE_THRESHOLD"]

COSINE_THRESHOLD = 0.95


@dataclass(frozen=True)
class Separation:
    """The condition where two refitted candidate models differ most.

    Attributes
    ----------
    effects : (str, str)
    speed : float
        Rolling speed V, m/s (the sliding speed is slip * speed).
    slip : float
    temperature : float
    pressure : float
    wet : bool
    mu : (float, float)
        Predictions of the two models there.
    difference : float
        mu[0] - mu[1].
    in_range : bool
        Whether the condition lies inside the measured ranges.
    """

    effects: tuple
    speed: float
    slip: float
    temperature: float
    pressure: float
    wet: bool
    mu: tuple
    difference: float
    in_range: bool

    def describe(self) -> str:
        vs = self.speed * self.slip
        where = (f"sliding speed {vs:.3g} m/s" + (f" (slip {self.slip:g} at V = {self.speed:.3g} m/s)"
                                                  if self.slip < 1 else "")
                 + f", {self.temperature:g} C, {self.pressure / 1e6:g} MPa" + (", wet" if self.wet else ""))
        return (f"{where}: {self.effects[0]} predicts {self.mu[0]:.3f}, {self.effects[1]} {self.mu[1]:.3f} "
                f"(difference {self.difference:+.3f})")

    def as_dict(self) -> dict:
        return {"effects": list(self.effects), "speed_m_s": self.speed, "slip": self.slip,
                "sliding_speed_m_s": self.speed * self.slip, "T_C": self.temperature,
                "pressure_Pa": self.pressure, "wet": self.wet, "mu": list(self.mu), "difference": self.difference,
                "in_measured_range": self.in_range}


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
    """The clusters with their separating conditions; returns (clusters, engine calls)."""
    by_name = {c.effect: c for c in results}
    cond = _probe_conditions(m, contact)
    vs = m.sliding_speed
    rng = dict(v=(vs.min(), vs.max()), T=(m.temperature.min(), m.temperature.max()),
               p=(m.pressure.min(), m.pressure.max()))
    cache = {}
    calls = 0
    out = []
    for cl in clusters:
        seps, seps_in = [], []
        head = cl.effects[0]
        for other in cl.effects[1:]:
            rows = {}
            for nm in (head, other):
                if nm not in cache:
                    try:
                        cache[nm], c = _evaluate_probe(by_name[nm].model, cond, by_name[nm].contact or contact)
                        calls += c
                    except Exception:  # noqa: BLE001
                        cache[nm] = None
                rows[nm] = cache[nm]
            if rows[head] is None or rows[other] is None or len(rows[head]) != len(rows[other]):
                continue
            a, b = rows[head], rows[other]
            diffs = np.array([ra[5] - rb[5] for ra, rb in zip(a, b)])
            inside = np.array([rng["v"][0] / 1.001 <= ra[0] * ra[1] <= rng["v"][1] * 1.001
                               and rng["T"][0] <= ra[2] <= rng["T"][1] and rng["p"][0] <= ra[3] <= rng["p"][1]
                               for ra in a])
            i = int(np.argmax(np.abs(diffs)))
            seps.append(_sep(head, other, a[i], b[i], bool(inside[i])))
            if np.any(inside):
                j = int(np.flatnonzero(inside)[np.argmax(np.abs(diffs[inside]))])
                seps_in.append(_sep(head, other, a[j], b[j], True))
        out.append(Ambiguity(effects=cl.effects, cosines=cl.cosines, separations=tuple(seps),
                             separations_in_range=tuple(seps_in)))
    return out, calls


# ---- helpers -----------------------------------------------------------------------------------------------
def _proj(v, Q, w):
    vw = v * w
    return vw - Q @ (Q.T @ vw) if Q.shape[1] else vw


def _cos(a, b) -> float:
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    if na <= 1e-300 or nb <= 1e-300:
        return 0.0
    return float(a @ b) / (na * nb)


def _probe_conditions(m: Measurements, contact):
    vs = m.sliding_speed
    lo, hi = float(vs.min()), float(vs.max())
    speeds = np.geomspace(max(lo / 10, 1e-9), min(hi * 10, 100.0), 13)
    T = np.unique(m.temperature)
    if T.size > 5:
        T = np.quantile(m.temperature, [0, 0.25, 0.5, 0.75, 1.0])
    T = np.unique(np.concatenate([T, [T.min() - 20.0, T.max() + 20.0]]))
    p = np.unique(m.pressure)
    if p.size > 3:
        p = np.quantile(m.pressure, [0, 0.5, 1.0])
    p = np.unique(np.concatenate([p, [p.min() / 2, p.max() * 2]]))
    wets = (False, True) if np.any(m.wet) else (False,)
    slips = np.array([0.02, 0.05, 0.1, 0.3]) if contact is not None else np.zeros(0)
    V_slip = float(np.median(m.speed[~m.is_sliding])) if np.any(~m.is_sliding) else float(np.median(m.speed))
    return speeds, T, p, wets, slips, V_slip


def _evaluate_probe(model, cond, contact):
    """Rows (V, slip, T, p, wet, mu) of ``model`` on the probe grid."""
    from persson.slip import mu_slip

    speeds, Ts, ps, wets, slips, V_slip = cond
    rows = []
    calls = 0
    for wet in wets:
        mg = wet_model(model) if wet else dry_model(model)
        for T in Ts:
            for p in ps:
                vs_slip = slips * V_slip
                allv = np.unique(np.concatenate([speeds, vs_slip]))
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    r = mg.friction(allv, temperature=float(T), pressure=float(p))
                calls += 1
                mu = np.atleast_1d(r.mu)
                for v, x in zip(allv, mu):
                    if np.any(np.isclose(v, speeds, rtol=1e-12, atol=0)):
                        rows.append((float(v), 1.0, float(T), float(p), wet, float(x)))
                if slips.size:
                    def local(v, allv=allv, mu=mu):
                        return np.interp(np.log(v), np.log(allv), mu)

                    res = mu_slip(local, slips, V_slip, temperature=float(T), pressure=float(p), contact=contact)
                    for s, x in zip(slips, np.atleast_1d(res.mu)):
                        rows.append((V_slip, float(s), float(T), float(p), wet, float(x)))
    return rows, calls


def _sep(a_name, b_name, ra, rb, inside) -> Separation:
    return Separation(effects=(a_name, b_name), speed=ra[0], slip=ra[1], temperature=ra[2], pressure=ra[3],
                      wet=bool(ra[4]), mu=(ra[5], rb[5]), difference=ra[5] - rb[5], in_range=inside)
