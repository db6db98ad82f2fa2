
from __future__ import annotations

import numpy as np

from frictioncite import doi

from .._checks import number
from ..errors import InputError
from .fitting import FitResult, _fit, _xy
from .references import DO_2004, PIARC_1995, RADO_1994

__all__ = ["piarc", "piarc_ifi", "do_marsac_mosset", "rado", "SPEED_LAWS", "fit_speed_law", "fit_piarc",
           "fit_do_marsac_mosset", "fit_rado"]


# =========================================================================================================
# Friction-speed laws
# =========================================================================================================
@doi(PIARC_1995)
def piarc(speed, mu0, Sp):
    r"""PIARC exponential friction-speed law :math:`\mu_0 e^{-V/S_p}` (V and the speed constant Sp in m/s)."""
    return mu0 * np.exp(-np.asarray(speed, dtype=float) / Sp)


@doi(PIARC_1995)
def piarc_ifi(S_km_h, F60, Sp_km_h):
    r"""PIARC / IFI form :math:`F(S) = F_{60}\,e^{(60 - S)/S_p}`, slip speed S and Sp in km/h.

    F60 is the friction at 60 km/h.

    Equal to :func:`piarc` with :math:`\mu_0 = F_{60} e^{60/S_p}` after converting the speeds to m/s.
    """
    return F60 * np.exp((60.0 - np.asarray(S_km_h, dtype=float)) / Sp_km_h)


@doi(DO_2004, PIARC_1995)
def do_marsac_mosset(speed, mu0, Vs, alpha, beta=0.0):
    r"""Do-Marsac-Mosset modified exponential :math:`\mu_0 e^{-(V/V_s)^\alpha} + \beta V` (V, Vs in m/s; beta in s/m).

    The stretched exponential is the law of Do, Marsac & Mosset (2004), a generalisation of the PIARC model
    (alpha = 1); the linear term :math:`\beta V` is the extension specified in issue 6 (the "modified
    exponential"). With alpha = 1 and beta = 0 it is exactly :func:`piarc` with Sp = Vs.
    """
    V = np.asarray(speed, dtype=float)
    return mu0 * np.exp(-((V / Vs) ** alpha)) + beta * V


@doi(RADO_1994)
def rado(speed, mu_peak, Vc, C, mu_locked=0.0):
    r"""Rado's log-normal model :math:`\mu_L + (\mu_{peak} - \mu_L)\exp\{-[\ln(V/V_c)/C]^2\}`.

    ``Vc`` the (critical) speed of the peak, m/s; ``C`` the shape (width) factor; ``mu_locked`` (:math:`\mu_L`)
    the level far from the peak (0 in Rado's three-parameter form).
    """
    V = np.asarray(speed, dtype=float)
    return mu_locked + (mu_peak - mu_locked) * np.exp(-((np.log(V / Vc) / C) ** 2))


#: name -> (function, parameter names, bounds)
SPEED_LAWS = {
    "piarc": (piarc, ("mu0", "Sp"), {"mu0": (1e-6, 10.0), "Sp": (1e-6, 1e6)}),
    "do_marsac_mosset": (do_marsac_mosset, ("mu0", "Vs", "alpha", "beta"),
                         {"mu0": (1e-6, 10.0), "Vs": (1e-6, 1e6), "alpha": (0.05, 10.0), "beta": (-10.0, 10.0)}),
    "rado": (rado, ("mu_peak", "Vc", "C", "mu_locked"),
             {"mu_peak": (1e-6, 10.0), "Vc": (1e-9, 1e6), "C": (1e-3, 100.0), "mu_locked": (0.0, 10.0)}),
}


def fit_speed_law(law: str, speed, mu, *, sigma=None, fixed: dict | None = None, p0: dict | None = None) -> FitResult:
    """Fit a friction-speed law (``"piarc"``, ``"do_marsac_mosset"``, ``"rado"``) to mu(V).

    Parameters
    ----------
    law : str
        A key of :data:`SPEED_LAWS`.
    speed, mu : array_like
        Speeds (> 0, m/s) and friction coefficients.
    sigma : array_like, optional
        Standard uncertainties of ``mu`` (absolute).
    fixed : dict, optional
        Parameters held fixed (e.g. ``{"alpha": 1.0, "beta": 0.0}``).
    p0 : dict, optional
        An extra starting point.
    """
    if law not in SPEED_LAWS:
        raise InputError(f"law: expected one of {sorted(SPEED_LAWS)}, got {law!r}")
    x, y, sig = _xy(speed, mu, sigma, "speed")
    if np.any(x <= 0):
        raise InputError("speed: expected speeds > 0 m/s")
    func, names, bounds = SPEED_LAWS[law]
    starts = _speed_starts(law, x, y)
    if p0:
        starts.insert(0, {**starts[0], **{k: number(v, f"p0[{k!r}]") for k, v in p0.items()}})
    parts = _fit(law, func, names, bounds, x, y, sig, fixed, starts, getattr(func, "__citations__", ()))
    return FitResult(**parts)


def _speed_starts(law, x, y):
    pos = y > 0
    if np.sum(pos) >= 2 and np.ptp(x[pos]) > 0:
        slope, icpt = np.polyfit(x[pos], np.log(y[pos]), 1)
        Sp0 = -1.0 / slope if slope < 0 else 10.0 * float(np.max(x))
        mu00 = float(np.exp(icpt))
    else:
        Sp0, mu00 = float(np.max(x)), float(np.max(y))
    if law == "piarc":
        return [dict(mu0=mu00, Sp=Sp0), dict(mu0=float(np.max(y)), Sp=float(np.median(x)))]
    if law == "do_marsac_mosset":
        return [dict(mu0=mu00, Vs=Sp0, alpha=1.0, beta=0.0), dict(mu0=mu00, Vs=Sp0, alpha=0.5, beta=0.0),
                dict(mu0=mu00, Vs=Sp0, alpha=2.0, beta=0.0), dict(mu0=float(np.max(y)), Vs=float(np.median(x)),
                                                               alpha=1.5, beta=0.0)]
    j = int(np.argmax(y))
    lx = np.log(x)
    w = max(float(np.ptp(lx)) / 3.0, 0.3)
    return [dict(mu_peak=float(y[j]), Vc=float(x[j]), C=w, mu_locked=float(np.min(y)) * 0.5),
            dict(mu_peak=float(y[j]), Vc=float(x[j]), C=2 * w, mu_locked=0.0),
            dict(mu_peak=float(y[j]), Vc=float(np.exp(np.mean(lx))), C=w, mu_locked=0.0)]


@doi(PIARC_1995)
def fit_piarc(speed, mu, *, sigma=None) -> FitResult:
    """Fit the PIARC exponential mu0 exp(-V/Sp) (see :func:`fit_speed_law`)."""
    return fit_speed_law("piarc", speed, mu, sigma=sigma)


@doi(DO_2004)
def fit_do_marsac_mosset(speed, mu, *, sigma=None, fixed: dict | None = None) -> FitResult:
    """Fit the Do-Marsac-Mosset law mu0 exp(-(V/Vs)^alpha) + beta V (``fixed`` e.g. ``{"beta": 0.0}``)."""
    return fit_speed_law("do_marsac_mosset", speed, mu, sigma=sigma, fixed=fixed)


@doi(RADO_1994)
def fit_rado(speed, mu, *, sigma=None, fit_mu_locked: bool = False) -> FitResult:
    """Fit Rado's log-normal law (``mu_locked`` held at 0 unless ``fit_mu_locked``)."""
    return fit_speed_law("rado", speed, mu, sigma=sigma, fixed=None if fit_mu_locked else {"mu_locked": 0.0})
