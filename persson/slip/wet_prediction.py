r"""mu(V) predicted for a new surface from its MPD, BPN, the water depth, the tread depth and the device.

:func:`predict_speed_curve` puts the relations of :mod:`.texture_laws` together (Do, Marsac & Mosset 2004): mu0
from the BPN, the Stribeck speed Vs from the MPD (the device's own Vs-MPD law, or the blank-tyre slip law with the
device's slip ratio), alpha (and optionally Vs) from the ratio of water depth to tread depth, and
:math:`\mu = \mu_0 e^{-(V/V_s)^\alpha} + \beta V`. The MPD may come from the surface's profiles
(:func:`surfaces.mpd`), its standard error from the scatter of the profiles.

The uncertainty of every regression (the covariance of its constants, and the scatter of the surfaces about it: a
new surface scatters as much) and of the MPD is carried into mu(V) by linear propagation (central differences on
the stacked inputs); the test suite checks it against a Monte-Carlo draw.

Do et al. did not manage to combine its two relations for Vs; here the blank-tyre (or device) value is taken as the
saturated one and multiplied by the WD/TD relation's ratio of its value at WD/TD to its saturated value, an
assumption each prediction states in its notes.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from .._checks import number
from ..errors import InputError, PhysicsWarning
from .references import DO_2004
from .texture_laws import ALPHA_WATER_LAW, BLANK_TIRE_SLIP_LAW, MPD_REFERENCE_M, Relation
from .wetlaws import pendulum_number, texture_depth_m

__all__ = ["WetRelations", "predict_speed_curve", "SpeedCurvePrediction"]


@dataclass(frozen=True)
class WetRelations:
    """The relations a prediction uses (see :func:`predict_speed_curve`).

    Attributes
    ----------
    mu0_bpn : Relation
        mu0 against BPN for the device (:func:`fit_mu0_bpn`).
    vs_mpd : Relation, optional
        The device's Vs against MPD (:func:`fit_vs_mpd`). Without it Vs comes from the slip law.
    mpd_exponent : (float, float), optional
        The MPD exponent a and its standard error, for the slip route.
    slip_law : Relation
        log10 b against log10 slip (default :data:`BLANK_TIRE_SLIP_LAW`).
    alpha_water : Relation
        alpha against WD/TD (default :data:`ALPHA_WATER_LAW`).
    vs_water : Relation, optional
        Vs against WD/TD (:func:`fit_water_ratio` with ``name="vs_water"``); scales the blank-tyre Vs by its value at
        WD/TD over its saturated value. Without it Vs is the blank-tyre (saturated) value.
    """

    mu0_bpn: Relation
    vs_mpd: Relation | None = None
    mpd_exponent: tuple | None = None
    slip_law: Relation = BLANK_TIRE_SLIP_LAW
    alpha_water: Relation = ALPHA_WATER_LAW
    vs_water: Relation | None = None


@dataclass(frozen=True, eq=False)
class SpeedCurvePrediction:
    """mu(V) = mu0 exp(-(V/Vs)^alpha) + beta V predicted for a surface, with standard uncertainties.

    Attributes
    ----------
    speed, mu : ndarray
        m/s, friction.
    std : ndarray
        Standard uncertainty of mu for this surface: the constants of the regressions and the scatter of surfaces
        about them.
    std_parameters : ndarray
        From the constants of the regressions alone (the mean curve of surfaces like this one).
    mu0, Vs, alpha : (float, float)
        Value and standard uncertainty (Vs in m/s).
    mpd, water_depth, tread_depth, bpn : float
        The inputs (m, m, m, BPN); ``slip`` the slip ratio or None.
    notes, citations : tuple of str
    """

    speed: np.ndarray
    mu: np.ndarray
    std: np.ndarray
    std_parameters: np.ndarray
    mu0: tuple
    Vs: tuple
    alpha: tuple
    mpd: float
    water_depth: float
    tread_depth: float
    bpn: float
    slip: float | None = None
    notes: tuple = ()
    citations: tuple = field(default=())

    def interval(self, k: float = 2.0) -> tuple[np.ndarray, np.ndarray]:
        """mu -+ k std."""
        return self.mu - k * self.std, self.mu + k * self.std


@doi(DO_2004)
def predict_speed_curve(speed, relations: WetRelations, *, bpn, water_depth, tread_depth, mpd=None, profiles=None,
                        mpd_std: float = 0.0, slip=None, beta: float = 0.0) -> SpeedCurvePrediction:
    """Predict mu(V) for a new surface from its MPD, BPN, the water depth, the tread depth and the device.

    Parameters
    ----------
    speed : array_like
        Slip speeds, m/s (> 0).
    relations : WetRelations
    bpn : float
        British Pendulum Number of the surface.
    water_depth : float
        Water depth WD, m (>= 0).
    tread_depth : float
        Tread depth TD of the tyre, m (0 for a blank tyre).
    mpd : float, optional
        Mean profile depth, m; or ``profiles`` (anything :func:`surfaces.mpd` reads), whose per-profile scatter
        gives ``mpd_std``.
    mpd_std : float
        Standard uncertainty of the MPD, m.
    slip : float, optional
        Slip ratio of the measuring wheel (the slip route for Vs, without ``relations.vs_mpd``).
    beta : float
        Viscous term, s/m (Do et al. find it negligible: 0).

    Returns
    -------
    SpeedCurvePrediction
    """
    V = np.asarray(speed, dtype=float).ravel()
    if V.size == 0 or not np.all(np.isfinite(V)) or np.any(V <= 0):
        raise InputError("speed: expected finite speeds > 0 m/s")
    notes = []
    m, m_std = _mpd(mpd, profiles, mpd_std, notes)
    B = float(pendulum_number(bpn, "bpn")[0])
    wd = float(texture_depth_m(water_depth, "water_depth", allow_zero=True)[0])
    td = float(texture_depth_m(tread_depth, "tread_depth", allow_zero=True)[0])
    ratio = math.inf if td == 0 else wd / td
    if wd == 0:
        notes.append("water depth 0: the relations were made on wet roads")
    rel = relations
    if rel.vs_mpd is None and (slip is None or rel.mpd_exponent is None):
        raise InputError("relations: give the device's Vs-MPD relation (vs_mpd), or the slip ratio (slip) with "
                         "relations.mpd_exponent = (a, std) for the blank-tyre slip law")
    if rel.vs_mpd is not None and slip is not None:
        notes.append("slip not used: the device's own Vs-MPD relation gives Vs")
    k = None if slip is None else number(slip, "slip")
    if k is not None and not 0 < k <= 1:
        raise InputError(f"slip: expected a slip ratio in (0, 1], got {k:g}")
    # the relations used and the value of their regressor for this surface
    used = {"mu0": (rel.mu0_bpn, B), "alpha": (rel.alpha_water, ratio),
            "vs": (rel.vs_mpd, m) if rel.vs_mpd is not None else (rel.slip_law, k)}
    if rel.vs_water is not None:
        used["vs_water"] = (rel.vs_water, ratio)
        notes.append("Vs = saturated Vs x (Vs(WD/TD) / Vs(saturated)) from the WD/TD relation: an assumption, the "
                     "relations of Do et al. were not combined by them")
    for r, x in used.values():
        _check_range(r, x, notes)

    # every uncertain input as one vector z: the constants of each relation, the MPD exponent (slip route), the MPD,
    # and one offset per relation for the scatter of surfaces about it; mu(V) = F(z) is linearised about z0
    z = _Inputs()
    for key, (r, _) in used.items():
        z.add(key, r.values, r.covariance)
    a, a_std = rel.mpd_exponent if rel.vs_mpd is None else (0.0, 0.0)
    z.add("a", [number(a, "mpd_exponent[0]")], [[number(a_std, "mpd_exponent[1]") ** 2]])
    z.add("mpd", [m], [[m_std**2]])
    for key, (r, _) in used.items():
        z.add(f"scatter_{key}", [0.0], [[r.residual_std**2]], scatter=True)

    def constants(v):
        def level(key, x):
            return float(used[key][0].design(x) @ v[key]) + v[f"scatter_{key}"][0]

        mpd_now = v["mpd"][0]
        if rel.vs_mpd is not None:
            log_vs = level("vs", mpd_now)
        else:
            log_vs = level("vs", k) + v["a"][0] * math.log10(mpd_now / MPD_REFERENCE_M)
        vs = 10.0**log_vs
        if "vs_water" in used:
            vs *= level("vs_water", ratio) / float(used["vs_water"][0].design(math.inf) @ v["vs_water"])
        return level("mu0", B), vs, level("alpha", ratio)

    def curve(zv):
        mu0, vs, alpha = constants(z.split(zv))
        return np.concatenate([mu0 * np.exp(-((V / vs) ** alpha)) + beta * V, [mu0, vs, alpha]])

    out = curve(z.values)
    nv = V.size
    if out[nv] <= 0 or out[nv + 2] <= 0:
        raise InputError(f"bpn, water_depth, tread_depth: the relations give mu0 = {out[nv]:.3g} and alpha = "
                         f"{out[nv + 2]:.3g} for this surface; both must be > 0 (the inputs lie far outside the rows "
                         "the relations were fitted to)")
    J = _jacobian(curve, z.values, z.scales)
    var_p = np.einsum("ij,jk,ik->i", J, z.covariance(scatter=False), J)
    var_t = var_p + np.einsum("ij,jk,ik->i", J, z.covariance(scatter=True), J)
    sd_t, sd_p = np.sqrt(var_t), np.sqrt(var_p)
    if not np.any(var_t > 0):
        notes.append("no input carries an uncertainty (published constants only): std is 0")
    outside = [n for n in notes if "outside the fitted range" in n]
    if outside:
        warnings.warn("; ".join(outside), PhysicsWarning, stacklevel=2)
    return SpeedCurvePrediction(speed=V, mu=out[:nv], std=sd_t[:nv], std_parameters=sd_p[:nv],
                                mu0=(float(out[nv]), float(sd_t[nv])), Vs=(float(out[nv + 1]), float(sd_t[nv + 1])),
                                alpha=(float(out[nv + 2]), float(sd_t[nv + 2])), mpd=m, water_depth=wd,
                                tread_depth=td, bpn=B, slip=k, notes=tuple(notes),
                                citations=predict_speed_curve.__citations__)


# =========================================================================================================
# helpers
# =========================================================================================================
def _mpd(mpd, profiles, mpd_std, notes) -> tuple[float, float]:
    if (mpd is None) == (profiles is None):
        raise InputError("mpd, profiles: give exactly one (the MPD in m, or profiles to compute it from)")
    sd = number(mpd_std, "mpd_std")
    if profiles is not None:
        import surfaces

        res = surfaces.mpd(profiles)
        if not math.isfinite(res.mpd):
            raise InputError("profiles: no valid MPD segment (dropouts or spikes); cannot predict")
        per = np.array([p for p, ok in zip(res.per_profile, res.profile_valid) if ok and math.isfinite(p)])
        if per.size >= 2 and sd == 0:
            sd = float(np.std(per, ddof=1) / math.sqrt(per.size))
            notes.append(f"MPD {res.mpd * 1e3:.3g} mm from {per.size} profiles (standard error {sd * 1e3:.2g} mm)")
        mpd = res.mpd
    m = float(texture_depth_m(mpd, "mpd")[0])
    if sd < 0:
        raise InputError(f"mpd_std: expected >= 0, got {sd:g}")
    return m, sd


def _check_range(r: Relation, x: float, notes: list) -> None:
    lo, hi = r.x_range
    if r.kind == "ramp":
        return  # constant beyond saturation; the ramp itself spans 0..saturation
    if r.n and not (lo * (1 - 1e-9) <= x <= hi * (1 + 1e-9)):
        notes.append(f"{r.name}{' (' + r.device + ')' if r.device else ''}: x = {x:.4g} outside the fitted range "
                     f"{lo:.4g}-{hi:.4g} (extrapolated)")


class _Inputs:
    """Uncertain inputs stacked into one vector, with their covariance split into constants and scatter."""

    def __init__(self):
        self._names, self._slices, self._values, self._blocks = [], {}, [], []

    def add(self, name, values, cov, *, scatter: bool = False):
        start = len(self._values)
        self._values += [float(v) for v in values]
        self._slices[name] = slice(start, len(self._values))
        self._blocks.append((self._slices[name], np.asarray(cov, dtype=float), scatter))

    @property
    def values(self) -> np.ndarray:
        return np.array(self._values)

    @property
    def scales(self) -> np.ndarray:
        """Step scale of each input: its standard uncertainty, else its size."""
        sd = np.sqrt(np.clip(np.diag(self.covariance(False) + self.covariance(True)), 0.0, None))
        return np.where(sd > 0, sd, np.maximum(np.abs(self.values), 1e-6))

    def covariance(self, scatter: bool) -> np.ndarray:
        n = len(self._values)
        C = np.zeros((n, n))
        for sl, cov, is_scatter in self._blocks:
            if is_scatter == scatter:
                C[sl, sl] = cov
        return C

    def split(self, z) -> dict:
        return {name: z[sl] for name, sl in self._slices.items()}


def _jacobian(f, z: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """Central differences with steps of 1e-4 of each input's scale (the curve is smooth on that scale)."""
    f0 = f(z)
    J = np.empty((f0.size, z.size))
    for i in range(z.size):
        h = 1e-4 * scale[i]
        up, dn = z.copy(), z.copy()
        up[i] += h
        dn[i] -= h
        J[:, i] = (f(up) - f(dn)) / (2 * h)
    return J
