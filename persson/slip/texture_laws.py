r"""The constants of the modified exponential from the road and the tyre, and mu(V) predicted for a new surface.

Do, Marsac & Mosset (2004, sections 5-6) relate the constants of :math:`\mu = \mu_0 e^{-(V/V_s)^\alpha}` to what can
be measured:

* :math:`\mu_0` to the microtexture, through the pendulum value: :func:`fit_mu0_bpn` (linear, per device: the
  offset between mu0 and BPN depends on the tyre);
* the Stribeck speed to the macrotexture: :math:`V_s = b\,\mathrm{MPD}^a`, fitted per device by regressing
  log Vs on log MPD (:func:`fit_vs_mpd`, :func:`fit_vs_mpd_by_device`); for blank tyres b follows the slip ratio
  of the device, :math:`\log b = 0.90 \log\kappa + 2.07` (Vs in km/h, MPD in mm), i.e.
  :math:`V_s = 117\,\kappa^{0.9}\,\mathrm{MPD}^a` (:func:`blank_tire_vs`, :data:`BLANK_TIRE_SLIP_LAW`,
  :func:`fit_b_slip`);
* alpha and Vs to the ratio of water depth to tread depth WD/TD: alpha rises from 1 (PIARC) to 3 and Vs falls, both
  saturating at WD/TD = 1, where the water fills the tread pattern (:func:`fit_water_ratio`,
  :data:`ALPHA_WATER_LAW`). Do et al. show the trend and the saturation point, not a formula: the relation here
  is the simplest one with both, a straight ramp up to the saturation ratio and a constant beyond.

:func:`persson.slip.predict_speed_curve` (:mod:`.wet_prediction`) puts them together for a new surface.

Units: SI (MPD, water and tread depths in m, Vs in m/s); b is the Stribeck speed at MPD = 1 mm. Do et al.'s
2.07 (km/h) is 2.07 - log10(3.6) = 1.51 in m/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from .._checks import number
from ..errors import InputError
from .references import DO_2004, EN_13036_4
from .wetlaws import pendulum_number, texture_depth_m

__all__ = ["Relation", "fit_vs_mpd", "fit_vs_mpd_by_device", "fit_b_slip", "blank_tire_vs", "fit_water_ratio",
           "fit_mu0_bpn", "BLANK_TIRE_SLIP_LAW", "ALPHA_WATER_LAW", "MPD_REFERENCE_M"]

#: MPD at which b is the Stribeck speed: 1 mm.
MPD_REFERENCE_M = 1.0e-3


@dataclass(frozen=True, eq=False)
class Relation:
    """A regression between a measurable quantity x and a constant y of the speed law.

    Attributes
    ----------
    name : str
        ``"vs_mpd"``, ``"b_slip"``, ``"alpha_water"``, ``"vs_water"``, ``"mu0_bpn"``.
    kind : str
        ``"power"``: :math:`\\log_{10} y = p_0 \\log_{10}(x/x_{ref}) + p_1`; ``"linear"``: :math:`y = p_0 + p_1 x`;
        ``"ramp"``: :math:`y = p_0 + (p_1 - p_0)\\min(x/x_{sat}, 1)`.
    names : tuple of str
        Names of the two constants p0, p1.
    values : ndarray
    covariance : ndarray
        2 x 2 (zero for published constants used as they are).
    residual_std : float
        Scatter of the rows about the relation (in log10 units for ``"power"``): a new surface scatters as much.
    n : int
        Rows fitted (0 for published constants).
    x_range : (float, float)
        Range of x in the rows: outside it a prediction extrapolates.
    reference : float
        :math:`x_{ref}` (power) or :math:`x_{sat}` (ramp).
    device : str
    citations : tuple of str
    """

    name: str
    kind: str
    names: tuple
    values: np.ndarray
    covariance: np.ndarray
    residual_std: float
    n: int
    x_range: tuple
    reference: float = 1.0
    device: str = ""
    citations: tuple = field(default=())

    @property
    def params(self) -> dict[str, float]:
        """The constants p0, p1 by name."""
        return {k: float(v) for k, v in zip(self.names, self.values)}

    @property
    def std(self) -> dict[str, float]:
        """Standard uncertainties of the constants by name (0 for published constants used as they are)."""
        return {k: float(math.sqrt(max(c, 0.0))) for k, c in zip(self.names, np.diag(self.covariance))}

    def design(self, x) -> np.ndarray:
        """Rows d(x) with ``d @ values`` the (log10 for power) value at x."""
        x = np.asarray(x, dtype=float)
        if self.kind == "power":
            return np.stack([np.log10(x / self.reference), np.ones_like(x)], axis=-1)
        if self.kind == "linear":
            return np.stack([np.ones_like(x), x], axis=-1)
        r = np.minimum(x / self.reference, 1.0)
        return np.stack([1.0 - r, r], axis=-1)

    def __call__(self, x):
        """The relation at x."""
        return self._unscale(self.design(x) @ self.values)

    def predict(self, x) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Value, standard uncertainty from the constants alone, and with the rows' scatter added (a new surface),
        in the units of y (power laws by the delta method)."""
        d = self.design(x)
        z = d @ self.values
        sp = np.sqrt(np.einsum("...i,ij,...j->...", d, self.covariance, d))
        st = np.sqrt(sp**2 + self.residual_std**2)
        y = self._unscale(z)
        scale = y * math.log(10.0) if self.kind == "power" else 1.0
        return y, sp * scale, st * scale

    def _unscale(self, z):
        return 10.0**z if self.kind == "power" else z


#: Do, Marsac & Mosset's blank-tyre law log10 b = 0.90 log10(slip) + 2.07 (b in km/h), here with b in m/s; their
#: fit's uncertainty is not published (zero here). Their slips ranged 0.14-1.
BLANK_TIRE_SLIP_LAW = Relation("b_slip", "power", ("c", "log10_b1"), np.array([0.90, 2.07 - math.log10(3.6)]),
                               np.zeros((2, 2)), 0.0, 0, (0.14, 1.0), 1.0, "blank tyres", (DO_2004,))

#: alpha from 1 (PIARC) at WD/TD = 0 to 3 at WD/TD >= 1 (Do et al., Fig. 6 and section 5.4), without uncertainty.
ALPHA_WATER_LAW = Relation("alpha_water", "ramp", ("y0", "y_sat"), np.array([1.0, 3.0]), np.zeros((2, 2)), 0.0, 0,
                           (0.0, 5.0), 1.0, "", (DO_2004,))


@doi(DO_2004)
def fit_vs_mpd(mpd, vs, *, device: str = "") -> Relation:
    """Fit :math:`V_s = b\\,(\\mathrm{MPD}/1\\,\\mathrm{mm})^a` by regressing log10 Vs on log10 MPD (Do et al. 2004).

    Parameters
    ----------
    mpd : array_like
        Mean profile depth of each surface, m.
    vs : array_like
        Fitted Stribeck speed of the device on each surface, m/s.
    device : str
        Label.

    Returns
    -------
    Relation
        Constants ``a`` and ``log10_b`` (b in m/s).
    """
    x = texture_depth_m(mpd, "mpd")
    y = _positive(vs, "vs", x.size)
    return _fit_relation("vs_mpd", "power", ("a", "log10_b"), x, np.log10(y), MPD_REFERENCE_M, device)


def fit_vs_mpd_by_device(mpd, vs, device) -> dict[str, Relation]:
    """:func:`fit_vs_mpd` for each device label in ``device`` (one per row)."""
    x = texture_depth_m(mpd, "mpd")
    y = _positive(vs, "vs", x.size)
    labels = np.asarray([str(d) for d in np.broadcast_to(np.asarray(device, dtype=object), x.shape)])
    return {d: fit_vs_mpd(x[labels == d], y[labels == d], device=d) for d in dict.fromkeys(labels.tolist())}


@doi(DO_2004)
def fit_b_slip(slip, b) -> Relation:
    """Fit :math:`\\log_{10} b = c \\log_{10}\\kappa + \\log_{10} b_1` over devices of slip ratio kappa (b in m/s).

    Do et al. found c = 0.90, log10 b1 = 2.07 with b in km/h (1.51 in m/s) for blank tyres.
    """
    k = _positive(slip, "slip")
    if np.any(k > 1):
        raise InputError(f"slip: expected slip ratios in (0, 1], got {k.max():g} (percent? give 0.86, not 86)")
    return _fit_relation("b_slip", "power", ("c", "log10_b1"), k, np.log10(_positive(b, "b", k.size)), 1.0, "")


@doi(DO_2004)
def blank_tire_vs(mpd, slip, a, *, slip_law: Relation = BLANK_TIRE_SLIP_LAW):
    """Stribeck speed of a blank tyre, :math:`V_s = b(\\kappa)\\,(\\mathrm{MPD}/1\\,\\mathrm{mm})^a`, m/s.

    With the default slip law, :math:`V_s = 117\\,\\kappa^{0.9}\\,\\mathrm{MPD_{mm}}^a` km/h (Do et al. 2004, eq. 9).

    Parameters
    ----------
    mpd : array_like
        Mean profile depth, m.
    slip : float
        Slip ratio of the measuring wheel, (0, 1].
    a : float
        The device's MPD exponent.
    slip_law : Relation
        log10 b against log10 slip.
    """
    k = number(slip, "slip")
    if not 0 < k <= 1:
        raise InputError(f"slip: expected a slip ratio in (0, 1], got {k:g}")
    x = texture_depth_m(mpd, "mpd")
    return slip_law(k) * (x / MPD_REFERENCE_M) ** number(a, "a")


@doi(DO_2004)
def fit_water_ratio(ratio, y, *, saturation: float = 1.0, name: str = "alpha_water") -> Relation:
    """Fit :math:`y = y_0 + (y_{sat} - y_0)\\min(r/r_{sat}, 1)` against r = WD/TD (alpha or Vs; Do et al., Figs. 5-6).

    Parameters
    ----------
    ratio : array_like
        Water depth over tread depth of each row (>= 0; ``inf`` for blank tyres).
    y : array_like
        alpha, or Vs (m/s), of each row.
    saturation : float
        :math:`r_{sat}`: 1 in Do et al. (water fills the tread pattern).
    name : str
        ``"alpha_water"`` or ``"vs_water"``.
    """
    r = np.asarray(ratio, dtype=float).ravel()
    if r.size == 0 or np.any(np.isnan(r)) or np.any(r < 0):
        raise InputError("ratio: expected water depth / tread depth values >= 0")
    sat = number(saturation, "saturation")
    if sat <= 0:
        raise InputError(f"saturation: expected a ratio > 0, got {sat:g}")
    yy = np.asarray(y, dtype=float).ravel()
    if yy.size != r.size or not np.all(np.isfinite(yy)):
        raise InputError(f"y: expected {r.size} finite values")
    if np.all(r >= sat) or np.all(r <= 0):
        raise InputError(f"ratio: every row lies {'at or beyond' if np.all(r >= sat) else 'at'} one end of the ramp; "
                         f"y0 and y_sat need rows below and above the saturation ratio {sat:g}")
    return _fit_relation(name, "ramp", ("y0", "y_sat"), r, yy, sat, "")


@doi(DO_2004, EN_13036_4)
def fit_mu0_bpn(bpn, mu0, *, device: str = "") -> Relation:
    """Fit :math:`\\mu_0 = c_0 + c_1\\,\\mathrm{BPN}` over surfaces (per device; Do et al. 2004, Fig. 7)."""
    x = pendulum_number(bpn, "bpn")
    yy = _positive(mu0, "mu0", x.size)
    return _fit_relation("mu0_bpn", "linear", ("c0", "c1"), x, yy, 1.0, device)


# =========================================================================================================
# helpers
# =========================================================================================================
def _fit_relation(name, kind, names, x, y, reference, device) -> Relation:
    """Ordinary least squares of y on the relation's design; covariance s^2 (X^T X)^-1."""
    rel = Relation(name, kind, names, np.zeros(2), np.zeros((2, 2)), 0.0, x.size, (float(x.min()), float(x.max())),
                   float(reference), str(device), (DO_2004,))
    X = rel.design(x)
    if x.size < 3:
        raise InputError(f"{name}: {x.size} row(s) cannot fit two constants with a scatter; give at least three")
    if np.linalg.matrix_rank(X) < 2:
        where = "all x equal, or all beyond saturation" if kind == "ramp" else "all x equal"
        raise InputError(f"{name}: the rows do not vary the regressor ({where}); two constants need at least two "
                         "distinct values")
    coef, *_ = np.linalg.lstsq(X, y, rcond=None)
    r = y - X @ coef
    s2 = float(r @ r) / (x.size - 2)
    cov = np.linalg.inv(X.T @ X) * s2
    return Relation(name, kind, names, coef, cov, math.sqrt(s2), x.size, rel.x_range, float(reference), str(device),
                    (DO_2004,))


def _positive(value, name: str, n: int | None = None) -> np.ndarray:
    try:
        a = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected numbers, got {value!r}") from None
    if a.size == 0 or not np.all(np.isfinite(a)) or np.any(a <= 0):
        raise InputError(f"{name}: expected finite values > 0")
    if n is not None and a.size != n:
        raise InputError(f"{name}: expected {n} values (one per row), got {a.size}")
    return a
