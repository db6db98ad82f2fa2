r"""Where two fitted models differ most: the measurement that would tell them apart.

Both models are evaluated on a grid of probe conditions with exactly the prediction path of the fit
(:class:`validation.predict.Predictor`: the engine on sliding rows, the brush model on slip rows, patch heating
along the contact patch, ``Wet`` on wet rows), and the condition with the largest :math:`|\Delta\mu|` is the
measurement to make. The probe grid spans the measured conditions and reaches beyond them: dry sliding at speeds
from half a decade below to half a decade above the measured ones, at the lowest and highest measured temperatures
and 20 K beyond, and at the lowest and highest measured pressures and a factor 2 beyond; wet sliding at the same
speeds where wet rows were measured (and 20 K beyond); and, when the case has a contact, slip ratios 0.02-0.3 at
the measured rolling speed where slip rows were measured (and 20 K beyond).

**Inside the measured conditions** is judged on the combination of conditions, not axis by axis (a cold fast row
is new even when cold rows and fast rows were both measured): a probe condition is inside when its distance to
the nearest measured row is below 1 in scaled condition space,

.. math:: d^2 = \left(\frac{\Delta\log_{10} v_s}{s_v}\right)^2 + \left(\frac{\Delta T}{s_T}\right)^2
    + \left(\frac{\Delta\log_{10}\sigma_0}{s_p}\right)^2 + \left(\frac{\Delta\log_{10} s}{s_s}\right)^2,

with the wet flag matching and the scales of :data:`SCALES` (half a decade of sliding speed, 10 K, a factor 1.5
of pressure, a factor 2 of slip): a condition between measured rows of a usual test grid (3 speeds per decade,
a temperature every 20 K) is inside, one 20 K or a decade of speed away from any measured row is not. The scales
are fixed, not taken from the spacing of the data: a sparse grid does not make its gaps "measured". A distance of
exactly 1 is outside: the probe speeds half a decade beyond the measured ones lie there by construction, and in
floating point they came out at 1 - 2e-16 or 1 + 2e-16 depending on the numpy version, so the boundary is drawn
a part in 1e9 below 1 (:data:`INSIDE`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from .measurements import Measurements

__all__ = ["Separation", "probe_rows", "scaled_distance", "separation", "SCALES", "INSIDE"]

#: Scale of each condition in the distance to the nearest measured row: decades of sliding speed, kelvin,
#: decades of pressure, decades of slip.
SCALES = {"speed": 0.5, "temperature": 10.0, "pressure": math.log10(1.5), "slip": math.log10(2.0)}
_FASTEST = 30.0  # m/s: probes stop below the speeds a measurement reader would take for km/h
_BEYOND = 10.0 ** 0.5  # probe speeds reach half a decade beyond the measured ones
#: A probe condition is inside the measured conditions when its scaled distance to the nearest measured row is below
#: this (module docstring: exactly 1 is outside, whatever the rounding).
INSIDE = 1.0 - 1e-9


@dataclass(frozen=True)
class Separation:
    """The condition where two fitted models differ most.

    Attributes
    ----------
    effects : (str, str)
        The two models (an effect name, or effects joined by ``" + "`` for a set of effects).
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
        Whether the condition lies inside the measured conditions (``distance`` < :data:`INSIDE`, 1 less a part in
        1e9).
    distance : float
        Scaled distance to the nearest measured row (module docstring; inf when no row has its wet flag).
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
    distance: float = math.nan

    def describe(self) -> str:
        """One sentence: the condition (sliding speed, with slip and rolling speed when slip < 1, temperature, pressure,
        wet or dry), whether it lies inside the measured conditions, and the two predictions with their difference."""
        vs = self.speed * self.slip
        where = (f"sliding speed {vs:.3g} m/s" + (f" (slip {self.slip:g} at V = {self.speed:.3g} m/s)"
                                                  if self.slip < 1 else "")
                 + f", {self.temperature:g} C, {self.pressure / 1e6:g} MPa, " + ("wet" if self.wet else "dry"))
        inside = ("inside the measured conditions" if self.in_range else
                  f"outside the measured conditions (distance {self.distance:.1f} to the nearest measured row)")
        return (f"{where} ({inside}): {self.effects[0]} predicts {self.mu[0]:.3f}, {self.effects[1]} "
                f"{self.mu[1]:.3f} (difference {self.difference:+.3f})")

    def as_dict(self) -> dict:
        """The separation as a JSON-ready dict.

        Returns
        -------
        dict
            ``effects``, ``speed_m_s``, ``slip``, ``sliding_speed_m_s``, ``T_C`` (deg C), ``pressure_Pa``, ``wet``,
            ``mu`` (the two predictions), ``difference``, ``in_measured_range`` and ``distance_to_measured``.
        """
        return {"effects": list(self.effects), "speed_m_s": self.speed, "slip": self.slip,
                "sliding_speed_m_s": self.speed * self.slip, "T_C": self.temperature,
                "pressure_Pa": self.pressure, "wet": self.wet, "mu": list(self.mu), "difference": self.difference,
                "in_measured_range": self.in_range, "distance_to_measured": self.distance}


def probe_rows(m: Measurements, contact=None) -> Measurements:
    """The probe conditions of measurements ``m`` (module docstring) as measurement rows (mu = 0)."""
    vs = m.sliding_speed
    lo, hi = float(vs.min()), float(vs.max())
    speeds = np.geomspace(max(lo / _BEYOND, 1e-9), min(hi * _BEYOND, _FASTEST), 6)
    T = np.unique([m.temperature.min(), m.temperature.max()])
    T = np.unique(np.concatenate([T, [T.min() - 20.0, T.max() + 20.0]]))
    p = np.unique(m.pressure)
    if p.size > 2:
        p = np.array([p.min(), p.max()])
    p = np.unique(np.concatenate([p, [p.min() / 2.0, p.max() * 2.0]]))
    cols = {k: [] for k in ("slip", "speed", "temperature", "pressure", "wet")}

    def add(slip, speed, temperature, pressure, wet):
        for k, v in zip(cols, (slip, speed, temperature, pressure, wet)):
            cols[k].append(np.ravel(v))

    def around(rows):
        """The (T, p) of ``rows`` and 20 K beyond the coldest and the warmest of them (at their pressures)."""
        Tp = {(float(t), float(q)) for t, q in zip(m.temperature[rows], m.pressure[rows])}
        lo, hi = min(t for t, _ in Tp), max(t for t, _ in Tp)
        Tp |= {(lo - 20.0, q) for t, q in Tp if t == lo} | {(hi + 20.0, q) for t, q in Tp if t == hi}
        return sorted(Tp)

    for Tk in T:
        for pk in p:
            add(np.ones(speeds.size), speeds, np.full(speeds.size, Tk), np.full(speeds.size, pk),
                np.zeros(speeds.size, dtype=bool))
    if np.any(m.wet):   # wet: where wet rows were measured, and 20 K beyond
        for Tk, pk in around(m.wet):
            add(np.ones(speeds.size), speeds, np.full(speeds.size, Tk), np.full(speeds.size, pk),
                np.ones(speeds.size, dtype=bool))
    if contact is not None:   # slip: at the measured rolling speed, where slip rows were measured and beyond
        slips = np.array([0.02, 0.05, 0.1, 0.3])
        rolling = ~m.is_sliding
        V = float(np.median(m.speed[rolling] if np.any(rolling) else m.speed))
        for wet in (False, True):
            rows = (rolling if np.any(rolling) else np.ones(m.n, dtype=bool)) & (m.wet == wet)
            if np.any(rows):
                for Tk, pk in around(rows):
                    add(slips, np.full(slips.size, V), np.full(slips.size, Tk), np.full(slips.size, pk),
                        np.full(slips.size, wet))
    arr = {k: np.concatenate(v) for k, v in cols.items()}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # probes beyond the data may look unusual to the unit checks
        return Measurements.from_arrays(slip=arr["slip"], speed=arr["speed"], temperature=arr["temperature"],
                                        pressure=arr["pressure"], mu=np.zeros(arr["slip"].size),
                                        wet=arr["wet"].astype(bool), source="probe conditions", contact=contact)


def scaled_distance(rows: Measurements, m: Measurements) -> np.ndarray:
    """Scaled distance of each of ``rows`` to the nearest row of ``m`` with the same wet flag (module docstring)."""
    def coords(x):
        return np.column_stack([np.log10(x.sliding_speed), x.temperature, np.log10(x.pressure),
                                np.log10(x.slip)])

    a, b = coords(rows), coords(m)
    scale = np.array(list(SCALES.values()))
    out = np.full(rows.n, np.inf)
    for wet in (False, True):
        sel, ref = rows.wet == wet, m.wet == wet
        if not (np.any(sel) and np.any(ref)):
            continue
        d = (a[sel][:, None, :] - b[ref][None, :, :]) / scale
        out[sel] = np.sqrt(np.min(np.sum(d * d, axis=2), axis=1))
    return out


def separation(names, predictions, probe: Measurements, distance, inside: bool = False) -> Separation | None:
    """The :class:`Separation` of two models from their ``predictions`` on the ``probe`` rows.

    Parameters
    ----------
    names : (str, str)
    predictions : (ndarray, ndarray)
        mu of each model on every probe row.
    probe : Measurements
        The probe rows (:func:`probe_rows`).
    distance : ndarray
        :func:`scaled_distance` of the probe rows to the measured ones.
    inside : bool
        Only the rows inside the measured conditions (None when there are none).
    """
    a, b = (np.asarray(x, dtype=float) for x in predictions)
    diff = np.abs(a - b)
    if inside:
        ok = distance < INSIDE
        if not np.any(ok):
            return None
        diff = np.where(ok, diff, -1.0)
    i = int(np.argmax(diff))
    return Separation(effects=tuple(names), speed=float(probe.speed[i]), slip=float(probe.slip[i]),
                      temperature=float(probe.temperature[i]), pressure=float(probe.pressure[i]),
                      wet=bool(probe.wet[i]), mu=(float(a[i]), float(b[i])), difference=float(a[i] - b[i]),
                      in_range=bool(distance[i] < INSIDE), distance=float(distance[i]))

