r"""Friction against speed on wet roads: the laws of one speed variable and their fits.

Each law is a function of the speed (m/s) and its constants, and has a fit ``fit_<law>(speed, mu)`` that returns a
:class:`~persson.slip.FitResult` (values, standard errors, covariance). The laws (Do, Marsac & Mosset 2004 review
them and relate their constants to the road):

* :func:`piarc` (Leu & Henry 1978; PIARC 1995) and its IFI form :func:`piarc_ifi`;
* :func:`do_marsac_mosset`, the "modified exponential" (Do et al. 2004, eq. 8), PIARC for alpha = 1, beta = 0;
* :func:`stribeck`, the full static Stribeck law (Lampaert et al. 2002; Do et al. eq. 7), the modified exponential
  for mu_c = 0;
* :func:`gompertz`, the Gompertz function (van den Bol, cited by Do et al., eq. 6);
* :func:`la_torre`, the inverse-S law of La Torre & Domenichini (2001) (Do et al. eq. 5);
* :func:`rado`, Rado's log-normal peak (1994);
* :func:`three_zone`, the three zones of the wet contact patch with a speed law for each (Moore 1975).

Laws that also depend on texture depth and BPN (Dijks 1974, the product form) are in :mod:`.wetlaws`; ranking the
laws by information criteria is :func:`persson.slip.fit_speed_laws`.

Every fit is global: the parameters that enter linearly are solved exactly on a grid of the others, and the best
grid points are refined (:func:`~persson.slip.separable.fit_separable`).
"""

from __future__ import annotations

import functools

import numpy as np

from frictioncite import doi

from .._checks import number
from ..errors import InputError
from .fitting import FitResult, _xy
from .references import (CANUDAS_2003, DO_2004, GOMPERTZ_1825, HORNE_DREHER_1963, LA_TORRE_2001, LAMPAERT_2002,
                         LEU_HENRY_1978, MOORE_1975, PIARC_1995, RADO_1994)
from .separable import Law, fit_separable

__all__ = ["piarc", "piarc_ifi", "do_marsac_mosset", "rado", "gompertz", "la_torre", "stribeck", "three_zone",
           "three_zone_fractions", "SPEED_LAWS", "fit_speed_law", "fit_piarc", "fit_do_marsac_mosset", "fit_rado",
           "fit_gompertz", "fit_la_torre", "fit_stribeck", "fit_three_zone"]


# =========================================================================================================
# Friction-speed laws
# =========================================================================================================
@doi(PIARC_1995, LEU_HENRY_1978)
def piarc(speed, mu0, Sp):
    r"""PIARC exponential friction-speed law :math:`\mu_0 e^{-V/S_p}` (V and the speed constant Sp in m/s).

    Leu & Henry (1978), :math:`\mu = c_0 e^{c_1 V}`; PIARC (1995) named :math:`S_p = -1/c_1` the speed constant.
    """
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

    Do, Marsac & Mosset (2004), eq. 8: the Stribeck law (:func:`stribeck`) with the Coulomb level mu_c = 0; mu0
    is the friction at zero speed, Vs the Stribeck speed, beta V a viscous term. With alpha = 1 and beta = 0 it is
    exactly :func:`piarc` with Sp = Vs.
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


@doi(GOMPERTZ_1825, DO_2004)
def gompertz(speed, alpha, beta, gamma, delta):
    r"""Gompertz friction-speed law :math:`\mu = \alpha + \gamma \exp[-\exp(\beta - \delta V)]`.

    Do, Marsac & Mosset (2004), eq. 6, from M. E. van den Bol; the function is Gompertz's (1825). With
    :math:`\delta > 0` and :math:`\gamma < 0` it falls in an inverse S from :math:`\alpha` (low speed) to
    :math:`\alpha + \gamma` (high speed), steepest at :math:`V = \beta/\delta`, where it has dropped by
    :math:`|\gamma|/e`.

    Parameters
    ----------
    speed : array_like
        V, m/s.
    alpha, gamma : float
        Friction levels (dimensionless).
    beta : float
        Dimensionless.
    delta : float
        s/m.
    """
    V = np.asarray(speed, dtype=float)
    return alpha + gamma * np.exp(-np.exp(beta - delta * V))


@doi(LA_TORRE_2001, DO_2004)
def la_torre(speed, b0, b1, b2, b3, b4, mu_ref=1.0):
    r"""La Torre & Domenichini's inverse-S law :math:`\mu = \mu_{ref}\,[b_0 + b_1 / (1 + e^{b_2 + b_3 V^{b_4}})]`.

    La Torre & Domenichini (2001), as quoted by Do, Marsac & Mosset (2004), eq. 5, for the friction at the peak of
    the friction-slip curve (mu_peak) and for the locked wheel (mu_locked) alike. The quoted text of the equation is
    garbled in the copy at hand (the exponent of V appears as a loose subscript): the exponent is read as
    :math:`b_2 + b_3 V^{b_4}`, the only reading with the five constants b0..b4 the text lists and a single sum in the
    exponent.

    Parameters
    ----------
    speed : array_like
        V, m/s.
    b0, b1 : float
        Levels relative to ``mu_ref``: :math:`\mu \to \mu_{ref} b_0` at high speed (b3 > 0) and
        :math:`\mu_{ref}(b_0 + b_1/(1 + e^{b_2}))` at V = 0.
    b2 : float
        Dimensionless.
    b3 : float
        (s/m)^b4. Coefficients published for V in km/h convert as :math:`b_3 = b_{3,\mathrm{km/h}}\,3.6^{b_4}`
        (the road-friction literature of this law quotes speeds in km/h).
    b4 : float
        Exponent of V (> 0).
    mu_ref : float
        The reference friction, measured under specified conditions (default 1: b0 and b1 are then frictions).
    """
    V = np.asarray(speed, dtype=float)
    return mu_ref * (b0 + b1 * _logistic(b2 + b3 * V**b4))


@doi(LAMPAERT_2002, CANUDAS_2003, DO_2004)
def stribeck(speed, mu_c, mu_s, Vs, alpha, beta=0.0):
    r"""The static Stribeck law :math:`\mu = \mu_c + (\mu_s - \mu_c)\,e^{-(V/V_s)^\alpha} + \beta V`.

    Lampaert, Swevers & Al-Bender (2002) (Do, Marsac & Mosset 2004, eq. 7); the friction of the brush elements of
    Canudas-de-Wit et al. (2003) is the same law without beta. With ``mu_c = 0`` it is the modified exponential
    :func:`do_marsac_mosset` with mu0 = mu_s.

    Parameters
    ----------
    speed : array_like
        V, m/s.
    mu_c : float
        Coulomb friction: the level the exponential falls to.
    mu_s : float
        "Static" friction, at V = 0.
    Vs : float
        Stribeck speed, m/s.
    alpha : float
        Shape exponent (1: exponential; larger: an inverse S).
    beta : float
        Viscous coefficient, s/m.
    """
    V = np.asarray(speed, dtype=float)
    return mu_c + (mu_s - mu_c) * np.exp(-((V / Vs) ** alpha)) + beta * V


@doi(MOORE_1975, HORNE_DREHER_1963, DO_2004)
def three_zone(speed, mu_dry, V1, V2):
    r"""Three-zone wet contact :math:`\mu = \mu_{dry} A_3 / (A_1 + A_2 + A_3)` with a speed law for each zone.

    Do, Marsac & Mosset (2004), eq. 1: friction is made in zone 3 (dry contact) of the three zones of a tyre on a
    wet road (Moore 1975): zone 1, in front, where the water wedge lifts the tread; zone 2, where the tread drapes
    onto the asperities through a squeezed film; zone 3. The speed laws of the zones (:func:`three_zone_fractions`)
    are this package's two-constant reading of the classical scalings, not a formula of those papers:

    * zone 1 carries the water's inertial pressure :math:`\rho V^2/2` (Horne & Dreher 1963), so its share of the
      footprint grows as :math:`(V/V_1)^2`; at :math:`V_1` (the hydroplaning speed) it covers the footprint;
    * zone 2 is the length rolled during the squeeze-film time :math:`t_s` (Moore 1975): its share is
      :math:`V t_s / L = V/V_2`.

    So :math:`\mu = \mu_{dry}\max[0,\, 1 - V/V_2 - (V/V_1)^2]`, the product form
    (adhesion) x (1 - hydrodynamic term) with a linear and a quadratic hydrodynamic term.

    Parameters
    ----------
    speed : array_like
        V, m/s.
    mu_dry : float
        Friction in zone 3.
    V1 : float
        Speed at which zone 1 alone would cover the footprint, m/s.
    V2 : float
        Footprint length over the squeeze-film time, m/s.
    """
    return mu_dry * three_zone_fractions(speed, V1, V2)[2]


def three_zone_fractions(speed, V1, V2):
    r"""Shares :math:`A_1/A, A_2/A, A_3/A` of the footprint at speed(s) V (see :func:`three_zone`).

    :math:`A_1/A = \min[(V/V_1)^2, 1]`, :math:`A_2/A = \min(V/V_2, 1 - A_1/A)`, :math:`A_3/A = 1 - A_1/A - A_2/A`.
    """
    V = np.asarray(speed, dtype=float)
    a1 = np.minimum((V / V1) ** 2, 1.0)
    a2 = np.minimum(V / V2, 1.0 - a1)
    return a1, a2, 1.0 - a1 - a2


# =========================================================================================================
# The laws as fits see them: linear levels, a grid of the nonlinear constants
# =========================================================================================================
def _logistic(z):
    """1 / (1 + e^z) without overflow."""
    return 0.5 * (1.0 - np.tanh(0.5 * np.asarray(z, dtype=float)))


def _speed_grid(V, lo=0.05, hi=100.0, n=48):
    return np.geomspace(lo * float(np.min(V)), hi * float(np.max(V)), n)


def _product(*axes):
    mesh = np.meshgrid(*axes, indexing="ij")
    return [m.ravel() for m in mesh]


_ALPHAS = np.array([0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0])


def _piarc_grid(xs):
    return {"Sp": _speed_grid(xs[0], n=80)}


def _stretched_grid(xs):
    Vs, a = _product(_speed_grid(xs[0]), _ALPHAS)
    return {"Vs": Vs, "alpha": a}


def _rado_grid(xs):
    V = xs[0]
    Vc, C = _product(_speed_grid(V, 0.01, 100.0, 40), np.geomspace(0.1, 20.0, 24))
    return {"Vc": Vc, "C": C}


def _inverse_s_centres(V):
    lo, hi = float(np.min(V)), float(np.max(V))
    span = max(hi - lo, 1e-3 * hi)
    return np.linspace(lo - 0.5 * span, hi + 0.5 * span, 24), span


def _gompertz_grid(xs):
    centre, span = _inverse_s_centres(xs[0])
    c, width, sign = _product(centre, np.geomspace(span / 60.0, 5.0 * span, 20), np.array([-1.0, 1.0]))
    delta = sign / width
    return {"beta": delta * c, "delta": delta}


def _la_torre_grid(xs):
    V = xs[0]
    lo, hi = float(np.min(V)), float(np.max(V))
    centre = np.geomspace(0.5 * lo, 2.0 * hi, 16)
    c, b4, s = _product(centre, np.array([0.5, 1.0, 2.0, 3.0, 5.0]), np.geomspace(0.3, 30.0, 10))
    return {"b2": -s, "b3": s / c**b4, "b4": b4}


def _three_zone_grid(xs):
    V1, V2 = _product(_speed_grid(xs[0], 0.5, 300.0, 30), _speed_grid(xs[0], 0.5, 3000.0, 30))
    return {"V1": V1, "V2": V2}


def _e(V, Vs, alpha):
    return np.exp(-((V / Vs) ** alpha))


_INF = np.inf
_LAWS = {
    "piarc": Law("piarc", piarc, ("mu0", "Sp"), {"mu0": (1e-6, 10.0), "Sp": (1e-6, 1e6)}, ("mu0",),
                 lambda xs, t: [np.exp(-xs[0] / t["Sp"])], _piarc_grid, piarc.__citations__),
    "do_marsac_mosset": Law(
        "do_marsac_mosset", do_marsac_mosset, ("mu0", "Vs", "alpha", "beta"),
        {"mu0": (1e-6, 10.0), "Vs": (1e-6, 1e6), "alpha": (0.05, 10.0), "beta": (-10.0, 10.0)}, ("mu0", "beta"),
        lambda xs, t: [_e(xs[0], t["Vs"], t["alpha"]), xs[0]], _stretched_grid, do_marsac_mosset.__citations__),
    "rado": Law(
        "rado", rado, ("mu_peak", "Vc", "C", "mu_locked"),
        {"mu_peak": (1e-6, 10.0), "Vc": (1e-9, 1e6), "C": (1e-3, 100.0), "mu_locked": (0.0, 10.0)},
        ("mu_peak", "mu_locked"),
        lambda xs, t: [g := np.exp(-((np.log(xs[0] / t["Vc"]) / t["C"]) ** 2)), 1.0 - g], _rado_grid,
        rado.__citations__),
    "gompertz": Law(
        "gompertz", gompertz, ("alpha", "beta", "gamma", "delta"),
        {"alpha": (-10.0, 10.0), "beta": (-1e4, 1e4), "gamma": (-10.0, 10.0), "delta": (-1e4, 1e4)},
        ("alpha", "gamma"), lambda xs, t: [np.ones_like(xs[0]), np.exp(-np.exp(t["beta"] - t["delta"] * xs[0]))],
        _gompertz_grid, gompertz.__citations__),
    "la_torre": Law(
        "la_torre", la_torre, ("b0", "b1", "b2", "b3", "b4"),
        {"b0": (-100.0, 100.0), "b1": (-100.0, 100.0), "b2": (-1e4, 1e4), "b3": (0.0, _INF), "b4": (0.05, 20.0)},
        ("b0", "b1"), lambda xs, t: [np.ones_like(xs[0]), _logistic(t["b2"] + t["b3"] * xs[0] ** t["b4"])],
        _la_torre_grid, la_torre.__citations__),
    "stribeck": Law(
        "stribeck", stribeck, ("mu_c", "mu_s", "Vs", "alpha", "beta"),
        {"mu_c": (0.0, 10.0), "mu_s": (0.0, 10.0), "Vs": (1e-6, 1e6), "alpha": (0.05, 10.0), "beta": (-10.0, 10.0)},
        ("mu_c", "mu_s", "beta"),
        lambda xs, t: [1.0 - (e := _e(xs[0], t["Vs"], t["alpha"])), e, xs[0]], _stretched_grid,
        stribeck.__citations__),
    "three_zone": Law(
        "three_zone", three_zone, ("mu_dry", "V1", "V2"), {"mu_dry": (1e-6, 10.0), "V1": (1e-3, 1e6),
                                                           "V2": (1e-3, 1e7)},
        ("mu_dry",), lambda xs, t: [three_zone_fractions(xs[0], t["V1"], t["V2"])[2]], _three_zone_grid,
        three_zone.__citations__),
}

#: name -> (function, parameter names, bounds)
SPEED_LAWS = {name: (law.func, law.names, law.bounds) for name, law in _LAWS.items()}


def fit_speed_law(law: str, speed, mu, *, sigma=None, fixed: dict | None = None, p0: dict | None = None,
                  mu_ref: float = 1.0) -> FitResult:
    """Fit a friction-speed law of :data:`SPEED_LAWS` to mu(V).

    Parameters
    ----------
    law : str
        A key of :data:`SPEED_LAWS` (``"piarc"``, ``"do_marsac_mosset"``, ``"rado"``, ``"gompertz"``,
        ``"la_torre"``, ``"stribeck"``, ``"three_zone"``).
    speed, mu : array_like
        Speeds (> 0, m/s) and friction coefficients.
    sigma : array_like, optional
        Standard uncertainties of ``mu`` (absolute). Without them the uncertainties of the parameters are scaled by
        the scatter of the residuals.
    fixed : dict, optional
        Parameters held fixed (e.g. ``{"alpha": 1.0, "beta": 0.0}``).
    p0 : dict, optional
        An extra starting point (the fit is global without one).
    mu_ref : float
        The reference friction of :func:`la_torre` (ignored by the other laws).

    Returns
    -------
    FitResult

    Raises
    ------
    InputError
        An unknown law or parameter, speeds <= 0, NaN, unequal lengths, no more points than free parameters, a fit
        that converges from no starting point.
    """
    if law not in _LAWS:
        raise InputError(f"law: expected one of {sorted(_LAWS)}, got {law!r}")
    x, y, sig = _xy(speed, mu, sigma, "speed")
    if np.any(x <= 0):
        i = int(np.argmax(x <= 0))
        raise InputError(f"speed: expected speeds > 0 m/s, got {x[i]:g} at index {i}")
    if law == "la_torre":
        return _fit_la_torre(x, y, sig, fixed, p0, mu_ref)
    parts = fit_separable(_LAWS[law], (x,), y, sig, fixed=fixed, starts=[p0] if p0 else None)
    return FitResult(**parts)


def _fit_la_torre(V, y, sigma, fixed, p0, mu_ref) -> FitResult:
    """La Torre's law fitted in the reduced speed u = V / V_m (V_m the geometric mean speed), then mapped back.

    In u the exponent reads b2 + b3' u^b4 with b3' = b3 V_m^b4, which trades off far less against b4 than b3 does
    (the refinement converged in a fifth of the steps in trials). The law is unchanged by (b0, b1, b2, b3) -> (b0 + b1, -b1, -b2,
    -b3): the fit keeps b3 >= 0, so that mu_ref b0 is the high-speed level and the constants are unique.
    """
    ref = number(mu_ref, "mu_ref")
    if ref <= 0:
        raise InputError(f"mu_ref: expected a reference friction > 0, got {ref:g}")
    fixed = dict(fixed or {})
    Vm = float(np.exp(np.mean(np.log(V))))
    if "b3" in fixed:
        if "b4" not in fixed:
            raise InputError("fixed: la_torre's b3 can be held fixed only together with b4 (the fit works with "
                             "b3 V_m^b4)")
        fixed["b3"] = number(fixed["b3"], "fixed['b3']") * Vm ** number(fixed["b4"], "fixed['b4']")
    starts = None
    if p0:
        starts = [dict(p0)]
        if "b3" in p0:
            starts[0]["b3"] = number(p0["b3"], "p0['b3']") * Vm ** number(p0.get("b4", 1.0), "p0['b4']")
    base = _LAWS["la_torre"]
    func = functools.partial(la_torre, mu_ref=ref)
    spec = Law(base.name, func, base.names, base.bounds, base.linear,
               lambda xs, t: [np.full_like(xs[0], ref), ref * _logistic(t["b2"] + t["b3"] * xs[0] ** t["b4"])],
               base.grid, base.citations)
    parts = fit_separable(spec, (V / Vm,), y, sigma, fixed=fixed, starts=starts, x=V)
    b0, b1, b2, b3u, b4 = parts["values"]
    T = np.eye(5)  # d(public)/d(fitted)
    T[3, 3] = Vm**-b4
    T[3, 4] = -b3u * np.log(Vm) * Vm**-b4
    values = np.array([b0, b1, b2, b3u * Vm**-b4, b4])
    with np.errstate(invalid="ignore"):
        C = T @ parts["covariance"] @ T.T
    C = np.where(np.isnan(C), np.inf, C)
    parts.update(values=values, covariance=C, stderr=np.sqrt(np.clip(np.diag(C), 0.0, None)), func=func)
    return FitResult(**parts)


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


@doi(GOMPERTZ_1825, DO_2004)
def fit_gompertz(speed, mu, *, sigma=None, fixed: dict | None = None) -> FitResult:
    """Fit the Gompertz law alpha + gamma exp(-exp(beta - delta V)) (see :func:`gompertz`, :func:`fit_speed_law`)."""
    return fit_speed_law("gompertz", speed, mu, sigma=sigma, fixed=fixed)


@doi(LA_TORRE_2001, DO_2004)
def fit_la_torre(speed, mu, *, mu_ref: float = 1.0, sigma=None, fixed: dict | None = None) -> FitResult:
    """Fit La Torre & Domenichini's inverse S mu_ref (b0 + b1 / (1 + exp(b2 + b3 V^b4))) to peak or locked friction.

    ``mu_ref`` is given, not fitted (it multiplies b0 and b1). See :func:`la_torre`, :func:`fit_speed_law`.
    """
    return fit_speed_law("la_torre", speed, mu, sigma=sigma, fixed=fixed, mu_ref=mu_ref)


@doi(LAMPAERT_2002, DO_2004)
def fit_stribeck(speed, mu, *, sigma=None, fixed: dict | None = None) -> FitResult:
    """Fit the Stribeck law mu_c + (mu_s - mu_c) exp(-(V/Vs)^alpha) + beta V (see :func:`stribeck`)."""
    return fit_speed_law("stribeck", speed, mu, sigma=sigma, fixed=fixed)


@doi(MOORE_1975, DO_2004)
def fit_three_zone(speed, mu, *, sigma=None, fixed: dict | None = None) -> FitResult:
    """Fit the three-zone law mu_dry max(0, 1 - V/V2 - (V/V1)^2) (see :func:`three_zone`)."""
    return fit_speed_law("three_zone", speed, mu, sigma=sigma, fixed=fixed)
