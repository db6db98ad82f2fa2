r"""The Stribeck curve: friction against :math:`H = \eta V / p` as a master curve, and the lubrication regimes.

Stribeck (1902) found that the friction of a lubricated contact depends on speed V, lubricant viscosity
:math:`\eta` and nominal pressure p only through :math:`H = \eta V/p`; Do, Marsac & Mosset (2004) propose the curve of
friction against ln H for tyres on wet roads, its three parts being the three zones of the contact patch:

* boundary lubrication (zone 3): the film is thin enough for the solids to touch; friction at its "static" level;
* mixed lubrication (zone 2): the film carries part of the load; friction falls with H;
* (elasto)hydrodynamic lubrication (zone 1): the film carries the load; friction at the viscous floor.

:func:`fit_stribeck_curve` fits the Stribeck law (:func:`persson.slip.stribeck`, with H in place of V) to rows
measured at several viscosities and pressures and reports how well they collapse; each row is named by its regime
from the fitted curve (:func:`lubrication_regime`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from .._checks import number, plausible_pressure
from ..errors import InputError
from .fitting import FitResult, _xy
from .references import DO_2004, STRIBECK_1902
from .separable import Law, fit_separable
from .speedlaws import _ALPHAS, _e, fit_speed_law, stribeck

__all__ = ["stribeck_parameter", "lubrication_regime", "fit_stribeck_curve", "StribeckCurve", "REGIMES"]

#: The regimes, from thin film to full film.
REGIMES = ("boundary", "mixed", "hydrodynamic")


@doi(STRIBECK_1902, DO_2004)
def stribeck_parameter(speed, viscosity, pressure):
    r"""The Stribeck parameter :math:`H = \eta V / p`, m (Do et al. 2004, section 3).

    Parameters
    ----------
    speed : array_like
        Sliding speed V, m/s (> 0).
    viscosity : array_like
        Lubricant (water) viscosity :math:`\eta`, Pa s (> 0; water at 20 C: 1.0e-3).
    pressure : array_like
        Nominal pressure p, Pa (> 0).
    """
    V, eta, p = (np.asarray(a, dtype=float) for a in (speed, viscosity, pressure))
    for name, a in (("speed", V), ("viscosity", eta), ("pressure", p)):
        if np.any(~np.isfinite(a)) or np.any(a <= 0):
            raise InputError(f"{name}: expected finite values > 0")
    return eta * V / p


@doi(STRIBECK_1902, DO_2004)
def lubrication_regime(H, Hs, alpha, *, boundary: float = 0.9, hydrodynamic: float = 0.1) -> tuple[str, ...]:
    r"""The lubrication regime at each H on a Stribeck curve with scale Hs and shape alpha.

    The share of the fall still to come, :math:`s = e^{-(H/H_s)^\alpha}` (1 at H = 0, 0 in full film), plays the part
    of the dry-contact share :math:`A_3/A` of the three-zone picture: ``"boundary"`` where
    :math:`s \ge` ``boundary``, ``"hydrodynamic"`` where :math:`s \le` ``hydrodynamic``, ``"mixed"`` between. The two
    thresholds are conventions (10 % of the fall at either end), not part of the cited works.
    """
    if not 0.0 < hydrodynamic < boundary < 1.0:
        raise InputError(f"boundary, hydrodynamic: expected 0 < hydrodynamic < boundary < 1, got {hydrodynamic!r}, "
                         f"{boundary!r}")
    s = _e(np.asarray(H, dtype=float), Hs, alpha)
    return tuple(np.where(s >= boundary, REGIMES[0], np.where(s <= hydrodynamic, REGIMES[2], REGIMES[1])).tolist())


@dataclass(frozen=True, eq=False)
class StribeckCurve:
    """Friction against H = eta V / p fitted as one master curve (:func:`fit_stribeck_curve`).

    Attributes
    ----------
    H : ndarray
        Stribeck parameter of each row, m.
    fit : FitResult
        The Stribeck law in H: ``mu_c, mu_s, Hs`` (m), ``alpha``, ``beta`` (1/m).
    share : ndarray
        :math:`e^{-(H/H_s)^\\alpha}` of each row: the share of the fall still to come.
    regime : tuple of str
        ``"boundary"``, ``"mixed"`` or ``"hydrodynamic"`` per row.
    groups : int
        Number of distinct (viscosity, pressure) pairs.
    rms : float
        Residual rms about the master curve.
    rms_speed : float
        Residual rms of the same law fitted against the speed alone (viscosity and pressure ignored): much larger
        than ``rms`` when the rows collapse in H and not in V.
    notes, citations : tuple of str
    """

    H: np.ndarray
    fit: FitResult
    share: np.ndarray
    regime: tuple
    groups: int
    rms: float
    rms_speed: float
    notes: tuple = ()
    citations: tuple = field(default=())

    @property
    def collapse_ratio(self) -> float:
        """``rms_speed / rms``: how much better H orders the rows than V does."""
        return self.rms_speed / self.rms if self.rms > 0 else math.inf

    def __call__(self, H):
        """The master curve at H (m)."""
        return self.fit(H)

    def plot(self, ax=None):
        """mu against H (log axis), each row coloured by its regime, with the master curve. Returns the figure."""
        from .plots import _axes  # matplotlib (Agg) only when a figure is asked for

        fig, ax = _axes(ax)
        ax.scatter(self.H, self.fit.y, s=12, c=[REGIMES.index(r) for r in self.regime], cmap="viridis", vmin=0,
                   vmax=2, label="data (colour: regime)")
        hh = np.geomspace(self.H.min(), self.H.max(), 300)
        ax.plot(hh, self.fit(hh), "k-", label="Stribeck law in H")
        ax.set_xscale("log")
        ax.set_xlabel("H = eta V / p (m)")
        ax.set_ylabel("friction coefficient mu")
        ax.set_title(f"Stribeck master curve: {self.groups} (eta, p) groups, rms {self.rms:.3g} "
                     f"(against V alone {self.rms_speed:.3g})", fontsize=8)
        ax.legend(fontsize=7)
        return fig


@doi(STRIBECK_1902, DO_2004)
def fit_stribeck_curve(speed, mu, *, viscosity, pressure, sigma=None, boundary: float = 0.9,
                       hydrodynamic: float = 0.1) -> StribeckCurve:
    """Fit friction against H = eta V / p as one Stribeck curve and name each row's lubrication regime.

    Parameters
    ----------
    speed, mu : array_like
        Sliding speeds (m/s) and friction coefficients, one per row.
    viscosity : float or array_like
        Lubricant viscosity of each row, Pa s.
    pressure : float or array_like
        Nominal pressure of each row, Pa.
    sigma : array_like, optional
        Standard uncertainties of mu.
    boundary, hydrodynamic : float
        Thresholds of :func:`lubrication_regime`.

    Returns
    -------
    StribeckCurve
    """
    V, y, sig = _xy(speed, mu, sigma, "speed")
    eta = _per_row(viscosity, "viscosity", V.size)
    p = _per_row(pressure, "pressure", V.size)
    if np.any(eta > 1.0):
        i = int(np.argmax(eta > 1.0))
        raise InputError(f"viscosity: {eta[i]:g} Pa s at index {i} is a thousand times water's; the value looks like "
                         "mPa s (cP): give Pa s (water at 20 C: 1.0e-3 Pa s)")
    plausible_pressure(p, "pressure")
    H = stribeck_parameter(V, eta, p)
    base = Law("stribeck", stribeck, ("mu_c", "mu_s", "Hs", "alpha", "beta"),
               {"mu_c": (0.0, 10.0), "mu_s": (0.0, 10.0), "Hs": (1e-30, 1.0), "alpha": (0.05, 10.0),
                "beta": (-np.inf, np.inf)},
               ("mu_c", "mu_s", "beta"), lambda xs, t: [1.0 - (e := _e(xs[0], t["Hs"], t["alpha"])), e, xs[0]],
               _h_grid, stribeck.__citations__)
    fit = FitResult(**fit_separable(base, (H,), y, sig))
    groups = int(np.unique(np.column_stack([eta, p]), axis=0).shape[0])
    notes = []
    if groups < 2:
        notes.append("one viscosity and one pressure: H is the speed rescaled, the rows cannot test a collapse")
    try:
        rms_speed = fit_speed_law("stribeck", V, y, sigma=sig).rms
    except InputError as exc:  # the speeds alone may not be fittable (e.g. repeated values)
        rms_speed = math.nan
        notes.append(f"the law against speed alone could not be fitted: {exc}")
    Hs, alpha = fit["Hs"], fit["alpha"]
    return StribeckCurve(H=H, fit=fit, share=_e(H, Hs, alpha),
                         regime=lubrication_regime(H, Hs, alpha, boundary=number(boundary, "boundary"),
                                                   hydrodynamic=number(hydrodynamic, "hydrodynamic")),
                         groups=groups, rms=fit.rms, rms_speed=rms_speed, notes=tuple(notes),
                         citations=fit_stribeck_curve.__citations__ + fit.citations)


def _h_grid(xs):
    H = xs[0]
    hs, a = np.meshgrid(np.geomspace(0.05 * H.min(), 100.0 * H.max(), 48), _ALPHAS, indexing="ij")
    return {"Hs": hs.ravel(), "alpha": a.ravel()}


def _per_row(value, name: str, n: int) -> np.ndarray:
    try:
        a = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected numbers, got {value!r}") from None
    if a.size == 1:
        a = np.full(n, a[0])
    if a.size != n:
        raise InputError(f"{name}: expected one value or {n} values (one per row), got {a.size}")
    if not np.all(np.isfinite(a)) or np.any(a <= 0):
        raise InputError(f"{name}: expected finite values > 0")
    return a
