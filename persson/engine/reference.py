r"""Slow, independent reference quadratures of the Persson integrals, for verification.

They share no numerics with the engine (:mod:`persson.engine.kernels`): the angular integrals are high-order
Gauss-Legendre quadratures of ``material.E`` itself on half-decade panels in :math:`t = -\log_{10}\cos\phi`,
tabulated on a log-frequency grid and interpolated by cubic splines (they are smooth: angle averages of the
modulus), and the q integrals are one adaptive ODE solve (:func:`scipy.integrate.solve_ivp`, DOP853) in
:math:`x = \ln q` for

.. math::
    \frac{dG}{dx} = \frac18 q^4 C(q) \frac{A(q v a_T)}{((1-\nu^2)\sigma_0)^2},\qquad
    \frac{d\mu}{dx} = \frac12 q^4 C(q) S(P) P \frac{L(q v a_T)}{(1-\nu^2)\sigma_0},\qquad
    P = \mathrm{erf}\frac{1}{2\sqrt G}

(Persson, J. Chem. Phys. 115, 3840 (2001); S(P) = gamma + (1-gamma) P^2, Yang & Persson, J. Phys.: Condens. Matter
20, 215214 (2008)), whose step control resolves the boundary layer near q0 where G grows by orders of magnitude
(glassy rubber) and P falls from 1 to almost 0. The flash temperature (:func:`reference_flash_friction`) is a
plain fixed-point iteration on a fine wavevector grid graded towards q0, with the trapezoid rule for the heat
integral. Seconds per speed: use them to check the engine, not to compute with.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import integrate, interpolate, special

from frictioncite import doi

__all__ = ["ReferenceResult", "reference_friction", "reference_flash_friction", "flash_nodes"]


@dataclass(frozen=True, eq=False)
class ReferenceResult:
    """Reference values per speed.

    Attributes
    ----------
    mu : ndarray
        Hysteresis friction.
    contact_area : ndarray
        A/A0 = P(q1).
    excited_layer : ndarray
        Friction-weighted mean of 1/q, m.
    q_eval : ndarray or None
        The wavevectors of ``mu_at`` and ``G_at``.
    mu_at, G_at : ndarray (n_speed, len(q_eval)) or None
        Cumulative friction and G(q) at ``q_eval``.
    temperature_q : ndarray or None
        Flash temperature at ``q_eval`` (flash reference only), deg C.
    """

    mu: np.ndarray
    contact_area: np.ndarray
    excited_layer: np.ndarray
    q_eval: np.ndarray | None = None
    mu_at: np.ndarray | None = None
    G_at: np.ndarray | None = None
    temperature_q: np.ndarray | None = None


@doi("10.1063/1.1388626", "10.1088/0953-8984/20/21/215214")
def reference_friction(surface, material, speed, temperature=20.0, pressure=0.3e6, *, nu: float = 0.5,
                       gamma: float = 0.5, rtol: float = 1e-10, omega_per_decade: int = 40,
                       q_eval=None, modulus_factors=None) -> ReferenceResult:
    """Hysteresis friction and contact area by adaptive quadrature, per speed.

    Parameters
    ----------
    surface : PSD-like
        ``C(q)`` and ``q_range``.
    material : object
        ``E(omega, T)`` (evaluated at the temperature directly; no shift law is assumed).
    speed : float or array_like
        Sliding speeds, m/s.
    temperature, pressure : float
        Background temperature, deg C, and nominal pressure, Pa.
    nu, gamma : float
    rtol : float
        Relative tolerance of the ODE solve.
    omega_per_decade : int
        Density of the spline tables of the angular integrals.
    q_eval : array_like, optional
        Wavevectors (rad/m, inside the q range) at which to return the cumulative friction and G too.
    modulus_factors : callable, optional
        ``modulus_factors(q) -> (f, g)``: factors on E' and E'' at wavevector q (a per-scale modulus, e.g. strain
        softening at the local strain), at the background temperature.

    Returns
    -------
    ReferenceResult
    """
    v = np.atleast_1d(np.asarray(speed, dtype=float))
    q0, q1 = (float(x) for x in surface.q_range)
    tab = _AngularSplines(material, float(temperature), math.log10(q0 * v.min()) - 0.1,
                          math.log10(q1 * v.max()) + 0.1, omega_per_decade, rtol)
    xq = None if q_eval is None else np.log(np.atleast_1d(np.asarray(q_eval, dtype=float)))
    out = {k: np.empty(v.size) for k in ("mu", "area", "layer")}
    mu_at = None if xq is None else np.empty((v.size, xq.size))
    G_at = None if xq is None else np.empty((v.size, xq.size))
    s = 1.0 / ((1.0 - nu * nu) * pressure)
    for i, vi in enumerate(v):
        lv = math.log10(vi)

        def rhs(x, y):
            q = math.exp(x)
            q4C = q**4 * float(surface.C(q))
            w = x / math.log(10.0) + lv
            f, g = (1.0, 1.0) if modulus_factors is None else modulus_factors(q)
            P = _P(y[0])
            dmu = 0.5 * q4C * (gamma + (1.0 - gamma) * P * P) * P * g * tab.L(w) * s
            return [0.125 * q4C * tab.A(w, f, g) * s * s, dmu, dmu / q]

        sol = _ode(rhs, math.log(q0), math.log(q1), 3, rtol, dense=xq is not None)
        G1, out["mu"][i], layer = sol.y[0, -1], sol.y[1, -1], sol.y[2, -1]
        out["area"][i] = _P(G1)
        out["layer"][i] = layer / out["mu"][i] if out["mu"][i] > 0 else 1.0 / q0
        if xq is not None:
            y = sol.sol(xq)
            G_at[i], mu_at[i] = y[0], y[1]
    return ReferenceResult(mu=out["mu"], contact_area=out["area"], excited_layer=out["layer"],
                           q_eval=None if xq is None else np.exp(xq), mu_at=mu_at, G_at=G_at)


@doi("10.1088/0953-8984/18/32/025")
def reference_flash_friction(surface, material, speed, temperature=20.0, pressure=0.3e6, *, nu: float = 0.5,
                             gamma: float = 0.5, macro_scale_ratio: float = 2.0, contact_diameter: float = 0.0,
                             nodes_per_decade: int = 400, tol: float = 1e-6, max_iter: int = 200,
                             omega_per_decade: int = 40) -> ReferenceResult:
    r"""Friction with Persson's flash temperature by plain fixed-point iteration on a fine graded grid.

    .. math::
        T_q = T_0 + \int_{q_0}^{q} dq'\, g(q, q') f(q'),\qquad
        f(q) = \frac{v q^4 C(q)}{\rho c_p} \frac{P(q)}{P(q_m)} \int_0^{2\pi} d\phi\,\cos\phi\,
        \frac{\mathrm{Im}\,E(q v \cos\phi, T_q)}{1-\nu^2}

    (Persson, J. Phys.: Condens. Matter 18, 7789 (2006)), the modulus at T_q by the material's shift law
    (``log10_aT``), q_m = ``macro_scale_ratio`` q0, t0 = d / v with d = ``contact_diameter`` or pi/q_m. The heat
    kernel g is the closed form of :func:`persson.engine.kernels.heat_kernel`, itself checked against quadrature in k
    (``tests/test_effects.py``). G and P come from an adaptive ODE solve with the current T_q; the heat integral is
    the trapezoid rule in q on ``nodes_per_decade`` log-spaced nodes plus nodes graded geometrically towards q0,
    where P falls steeply for glassy rubber (:func:`flash_nodes`).

    Returns
    -------
    ReferenceResult
        With ``temperature_q`` on ``q_eval`` = the grid.
    """
    v = np.atleast_1d(np.asarray(speed, dtype=float))
    q0, q1 = (float(x) for x in surface.q_range)
    th = material.thermal
    D, rc = th.diffusivity, th.heat_capacity
    q_m = macro_scale_ratio * q0
    d = contact_diameter if contact_diameter > 0 else math.pi / q_m
    q = flash_nodes(q0, q1, nodes_per_decade)
    x = np.log(q)
    s = 1.0 / ((1.0 - nu * nu) * pressure)
    # the shift at the hottest temperature is unknown in advance: tabulate 30 decades below T0's lowest frequency
    lw_lo = math.log10(q0 * v.min()) - 0.1 + min(0.0, float(material.log10_aT(temperature + 500.0))
                                                 - float(material.log10_aT(temperature)))
    tab = _AngularSplines(material, float(temperature), lw_lo, math.log10(q1 * v.max()) + 0.1, omega_per_decade,
                          1e-10)
    mus, areas, layers, Ts = [], [], [], []
    for vi in v:
        lv = math.log10(vi)

        def heat_source(T, vi=vi, lv=lv):
            shift = np.asarray(material.log10_aT(T) - material.log10_aT(temperature), dtype=float)

            def rhs(xx, y):
                qq = math.exp(xx)
                q4C = qq**4 * float(surface.C(qq))
                w = xx / math.log(10.0) + lv + float(np.interp(xx, x, shift))
                P = _P(y[0])
                dmu = 0.5 * q4C * (gamma + (1.0 - gamma) * P * P) * P * tab.L(w) * s
                return [0.125 * q4C * tab.A(w) * s * s, dmu, dmu / qq]

            sol = _ode(rhs, x[0], x[-1], 3, 1e-10, dense=True)
            P = np.array([_P(Gi) for Gi in sol.sol(x)[0]])
            Pm = _P(float(sol.sol(math.log(q_m))[0]))
            w = x / math.log(10.0) + lv + shift
            f = vi * q**4 * surface.C(q) / rc * P / Pm * np.array([tab.L(wi) for wi in w]) / (1.0 - nu * nu)
            return f, sol

        T, sol = flash_fixed_point(q, float(temperature), heat_matrix(q, D * d / vi, D), heat_source, tol, max_iter)
        mus.append(sol.y[1, -1])
        areas.append(_P(sol.y[0, -1]))
        layers.append(sol.y[2, -1] / sol.y[1, -1])
        Ts.append(T)
    return ReferenceResult(mu=np.array(mus), contact_area=np.array(areas), excited_layer=np.array(layers),
                           q_eval=q, temperature_q=np.array(Ts))


def flash_nodes(q0: float, q1: float, nodes_per_decade: int) -> np.ndarray:
    r"""The nodes of the flash references: ``nodes_per_decade`` log-spaced from q0 to q1, and nodes graded
    geometrically in :math:`q - q_0` from :math:`10^{-12} q_0` to :math:`10^{-2} q_0`, a quarter as dense per decade
    (at least 60).

    Near q0 the heat source of glassy rubber falls like :math:`(q - q_0)^{-1/2}` (P falls as G grows linearly from
    zero) and the temperature rises like :math:`\sqrt{q - q_0}`; the graded nodes integrate that start, and they are
    refined with the rest: with a fixed number of them (60) the reference converged to a value 4e-4 from the
    engine's on a glassy compound with a 190 K flash (its differences fell only from 2.6e-5 to 8e-6 between 320 and
    1280 nodes per decade); refined with the rest it converges to the engine's within 4e-5.
    """
    n = int(math.ceil(nodes_per_decade * math.log10(q1 / q0))) + 1
    n_graded = max(60, int(math.ceil(nodes_per_decade * 10 / 4)))
    return np.unique(np.concatenate([np.geomspace(q0, q1, n), q0 * (1.0 + np.geomspace(1e-12, 1e-2, n_graded))]))


def heat_matrix(q: np.ndarray, a: float, D: float) -> np.ndarray:
    """The heat kernel g(q_i, q_j) for j <= i (zero above the diagonal) of Persson's flash temperature on the nodes
    ``q``, with a = D t0 (:func:`persson.engine.kernels.heat_kernel`, its closed form)."""
    from .kernels import heat_kernel

    ex = special.erfcx(2.0 * q * math.sqrt(a))
    g = np.zeros((q.size, q.size))
    for i in range(q.size):
        for j in range(i + 1):
            g[i, j] = heat_kernel(q[i], q[j], a, D, ex[i], ex[j])
    return g


def flash_fixed_point(q: np.ndarray, T0: float, g: np.ndarray, heat_source, tol: float, max_iter: int):
    r"""Plain fixed-point iteration of :math:`T_q = T_0 + \int_{q_0}^{q} dq'\, g(q, q') f(q')` (trapezoid rule on
    ``q``), where ``heat_source(T)`` returns f on the nodes and the solution it was computed with; under-relaxed,
    the relaxation halved whenever the residual grows (the fixed point can oscillate when hot).

    Returns
    -------
    (T, solution) : the temperatures on ``q`` (deg C) and ``heat_source``'s solution at the last evaluation.
    """
    T = np.full(q.size, T0)
    relax, res_prev = 1.0, np.inf
    for _ in range(max_iter):
        f, sol = heat_source(T)
        T_new = T0 + np.array([integrate.trapezoid(g[i, :i + 1] * f[:i + 1], q[:i + 1]) if i else 0.0
                               for i in range(q.size)])
        res = np.max(np.abs(T_new - T))
        if res < tol:
            return T_new, sol
        relax = 0.5 * relax if res > res_prev else min(1.0, 1.25 * relax)
        res_prev = res
        T = T + relax * (T_new - T)
    return T, sol


# ---------------------------------------------------------------------------------------------------------
class _AngularSplines:
    r"""A(omega) and L(omega) on a log-frequency grid, cubic splines of their logs.

    Each angular integral is computed over :math:`t = -\log_{10}\cos\phi` on panels of half a decade with
    48-point Gauss-Legendre rules of the material's own E (with :math:`t = u^2` on the first panel, where
    :math:`d\phi/dt \sim t^{-1/2}`), out to 40 decades; vectorised over the grid.
    """

    def __init__(self, material, T, lw_lo, lw_hi, per_decade, rtol):
        lw = np.linspace(lw_lo, lw_hi, max(8, int(math.ceil((lw_hi - lw_lo) * per_decade)) + 1))
        Are, Aim, L = _angular_integrals(material, T, lw)
        self._lnAre = interpolate.CubicSpline(lw, np.log(Are))
        self._lnAim = interpolate.CubicSpline(lw, np.log(np.maximum(Aim, 1e-300)))
        self._lnL = interpolate.CubicSpline(lw, np.log(np.maximum(L, 1e-300)))

    def A(self, lw, f=1.0, g=1.0):
        return float(f * f * np.exp(self._lnAre(lw)) + g * g * np.exp(self._lnAim(lw)))

    def L(self, lw):
        return float(np.exp(self._lnL(lw)))


def _angular_integrals(material, T, lw: np.ndarray):
    """4 int_0^{pi/2} of (E'^2, E''^2, cos(phi) E'') dphi at omega cos(phi), omega = 10^lw."""
    ln10 = math.log(10.0)
    g, w = np.polynomial.legendre.leggauss(48)
    g, w = 0.5 * (g + 1.0), 0.5 * w
    panel = 0.5
    # first panel in u = sqrt(t / panel): t = panel u^2, dt = 2 panel u du
    t_parts = [panel * g * g] + [panel * (k + g) for k in range(1, 80)]
    w_parts = [panel * 2.0 * g * w] + [panel * w for _ in range(1, 80)]
    t = np.concatenate(t_parts)
    wt = np.concatenate(w_parts)
    jac = ln10 * 10.0 ** (-t) / np.sqrt(-np.expm1(-2.0 * ln10 * t))
    Are, Aim, L = np.empty(lw.size), np.empty(lw.size), np.empty(lw.size)
    for i, x in enumerate(lw):
        E = np.asarray(material.E(10.0 ** (x - t), T), dtype=complex)
        Are[i] = 4.0 * np.sum(wt * jac * E.real**2)
        Aim[i] = 4.0 * np.sum(wt * jac * E.imag**2)
        L[i] = 4.0 * np.sum(wt * jac * 10.0 ** (-t) * E.imag)
    return Are, Aim, L


def _P(G: float) -> float:
    return float(special.erf(0.5 / math.sqrt(G))) if G > 0 else 1.0


def _ode(rhs, x0, x1, n, rtol, dense):
    return integrate.solve_ivp(rhs, (x0, x1), [0.0] * n, method="DOP853", rtol=rtol, atol=1e-300,
                               first_step=1e-12, dense_output=dense)
