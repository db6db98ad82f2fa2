r"""A slow, independent quadrature of Persson's integrals for an anisotropic PSD and a sliding direction, to check
:mod:`persson.engine.anisotropic` against.

It shares no numerics with the engine: the 2-D PSD is read through ``C2d(qx, qy)`` (Cartesian evaluation, not the
angular-mean-times-shape form the engine integrates), the modulus through ``material.E`` itself, and the angular
integral

.. math:: \int_0^{2\pi} d\phi\, C(q, \phi)\, F(q v\cos(\phi - \theta))
          = \int_0^{\pi/2} d\psi\, F(q v \cos\psi)\,[C(\theta+\psi) + C(\theta-\psi) + C(\theta+\pi-\psi) +
          C(\theta+\pi+\psi)]

is a composite Gauss-Legendre rule: 32 panels (8 points each) in :math:`\psi` up to :math:`\cos\psi = 0.1`, then half-decade
panels in :math:`t = -\log_{10}\cos\psi` to 24 decades (where a glass transition crossed near
:math:`\psi = \pi/2` lives). The q integrals are one adaptive ODE solve in :math:`x = \ln q` (DOP853), whose step
control resolves the boundary layer near :math:`q_0` of glassy rubber (Persson, J. Chem. Phys. 115, 3840 (2001);
S(P) of Yang & Persson, J. Phys.: Condens. Matter 20, 215214 (2008)):

.. math:: \frac{dG}{dx} = \frac{q^4}{8} \frac{\int d\phi\, C |E|^2}{((1-\nu^2)\sigma_0)^2},\qquad
          \frac{d\mu}{dx} = \frac{q^4}{2} S(P) P \frac{\int d\phi\, \cos(\phi-\theta)\, C\, \mathrm{Im}\,E}
          {(1-\nu^2)\sigma_0} .

When the angular shape :math:`C(q, \phi)/\bar C(q)` does not change with q (a stretched power law) the angular
integrals are tabulated once in log frequency (cubic splines of their logarithms); otherwise they are computed at
every step of the ODE solve. Seconds per speed and direction: for verification only.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import integrate, interpolate, special

from frictioncite import doi

from .reference import ReferenceResult, flash_fixed_point, flash_nodes, heat_matrix

__all__ = ["reference_directional_friction", "reference_directional_flash_friction"]


@doi("10.1063/1.1388626", "10.1088/0953-8984/20/21/215214")
def reference_directional_friction(surface, material, speed, direction_deg, temperature=20.0, pressure=0.3e6, *,
                                   nu: float = 0.5, gamma: float = 0.5, rtol: float = 1e-9,
                                   per_step: bool | None = None, omega_per_decade: int = 20) -> ReferenceResult:
    """Hysteresis friction and contact area of ``surface`` sliding along ``direction_deg``, per speed.

    Parameters
    ----------
    surface : anisotropic PSD
        With ``C2d(qx, qy)`` and ``q_range`` (its angular mean ``C(q)`` is not used).
    material : object
        ``E(omega, T)``, evaluated at ``temperature`` directly.
    speed : float or array_like
        Sliding speeds, m/s.
    direction_deg : float
        Sliding direction, degrees from the x axis.
    temperature, pressure : float
        Background temperature (deg C) and nominal pressure (Pa).
    nu, gamma : float
    rtol : float
        Relative tolerance of the ODE solve.
    per_step : bool, optional
        Compute the angular integrals at every ODE step (True) or tabulate them in frequency (False, valid only
        for an angular shape independent of q). Default: tabulate when the shape is the same at q0, at the middle
        of the support and at q1.
    omega_per_decade : int
        Density of the frequency tables (tabulated mode).

    Returns
    -------
    ReferenceResult
    """
    v = np.atleast_1d(np.asarray(speed, dtype=float))
    theta = math.radians(float(direction_deg))
    q0, q1 = (float(x) for x in surface.q_range)
    psi, wpsi = _angular_rule()
    cpsi = np.cos(psi)

    def weights(q):
        return _folded_weights(surface, theta, psi, wpsi, q)

    if per_step is None:
        ref = weights(q0) / max(float(np.sum(weights(q0))), 1e-300)
        per_step = not all(np.allclose(weights(qq) / max(float(np.sum(weights(qq))), 1e-300), ref, rtol=1e-9,
                                       atol=1e-14 * ref.max()) for qq in (math.sqrt(q0 * q1), q1))
    s = 1.0 / ((1.0 - nu * nu) * pressure)
    mus, areas, layers = [], [], []
    if not per_step:
        # C(q, phi) = C(q0, phi) f(q): f read along the angle where the PSD is largest
        shape = weights(q0)
        k = int(np.argmax(shape))
        phi_k = theta + psi[k] if np.any(shape) else theta
        c0 = float(surface.C2d(q0 * math.cos(phi_k), q0 * math.sin(phi_k)))
        lw_lo, lw_hi = math.log10(q0 * v.min()) - 0.1, math.log10(q1 * v.max()) + 0.1
        lw = np.linspace(lw_lo, lw_hi, max(8, int(math.ceil((lw_hi - lw_lo) * omega_per_decade)) + 1))
        A, L = _frequency_tables(material, temperature, shape, cpsi, lw)
        lnA = interpolate.CubicSpline(lw, np.log(A))
        lnL = interpolate.CubicSpline(lw, np.log(np.maximum(L, 1e-300)))
    for vi in v:
        lv = math.log10(vi)

        def angular(q, vi=vi, lv=lv):
            if per_step:
                c = weights(q)
                E = np.asarray(material.E(q * vi * cpsi, temperature), dtype=complex)
                return float(np.sum(c * np.abs(E) ** 2)), float(np.sum(c * cpsi * E.imag))
            f = float(surface.C2d(q * math.cos(phi_k), q * math.sin(phi_k))) / c0
            w = math.log10(q) + lv
            return f * float(np.exp(lnA(w))), f * float(np.exp(lnL(w)))

        def rhs(x, y, angular=angular):
            q = math.exp(x)
            a, l_ = angular(q)
            P = float(special.erf(0.5 / math.sqrt(y[0]))) if y[0] > 0 else 1.0
            dmu = 0.5 * q**4 * (gamma + (1.0 - gamma) * P * P) * P * l_ * s
            return [0.125 * q**4 * a * s * s, dmu, dmu / q]

        sol = integrate.solve_ivp(rhs, (math.log(q0), math.log(q1)), [0.0, 0.0, 0.0], method="DOP853", rtol=rtol,
                                  atol=1e-300, first_step=1e-12)
        G1, mu, layer = sol.y[0, -1], sol.y[1, -1], sol.y[2, -1]
        mus.append(mu)
        areas.append(float(special.erf(0.5 / math.sqrt(G1))) if G1 > 0 else 1.0)
        layers.append(layer / mu if mu > 0 else 1.0 / q0)
    return ReferenceResult(mu=np.array(mus), contact_area=np.array(areas), excited_layer=np.array(layers))


@doi("10.1088/0953-8984/18/32/025")
def reference_directional_flash_friction(surface, material, speed, direction_deg, temperature=20.0, pressure=0.3e6,
                                         *, nu: float = 0.5, gamma: float = 0.5, macro_scale_ratio: float = 2.0,
                                         contact_diameter: float = 0.0, nodes_per_decade: int = 100,
                                         tol: float = 1e-6, max_iter: int = 200,
                                         omega_per_decade: int = 20) -> ReferenceResult:
    r"""Friction of ``surface`` sliding along ``direction_deg`` with Persson's flash temperature, by plain
    fixed-point iteration: the anisotropic counterpart of :func:`persson.engine.reference.reference_flash_friction`.

    .. math::
        T_q = T_0 + \int_{q_0}^{q} dq'\, g(q, q') f(q'),\qquad
        f(q) = \frac{v q^4}{\rho c_p} \frac{P(q)}{P(q_m)} \int_0^{2\pi} d\phi\,\cos(\phi - \theta)\,
        C(q, \phi)\, \frac{\mathrm{Im}\,E(q v \cos(\phi - \theta), T_q)}{1-\nu^2}

    (Persson, J. Phys.: Condens. Matter 18, 7789 (2006), with the isotropic PSD of its heat source replaced by the
    angular integral over :math:`C(q, \phi)`, as in the friction itself). The angular integrals use this module's
    Cartesian reading of ``C2d`` and composite rule, tabulated in log frequency at ``temperature`` and read at
    :math:`\log_{10}(q v) + \log_{10} a_T(T_q) - \log_{10} a_T(T_0)` (the material's own shift law): valid for an
    angular shape independent of q (a stretched power law), which is checked. G, P and mu come from an adaptive ODE
    solve with the current T_q; the heat integral is the trapezoid rule on ``nodes_per_decade`` log-spaced nodes plus
    nodes graded geometrically towards q0 (:func:`persson.engine.reference.flash_nodes`). The heat kernel g is the
    closed form :func:`persson.engine.kernels.heat_kernel` (checked against quadrature in ``tests/test_effects.py``).
    Seconds per speed: for verification only.

    Returns
    -------
    ReferenceResult
        With ``temperature_q`` on ``q_eval``.
    """
    v = np.atleast_1d(np.asarray(speed, dtype=float))
    theta = math.radians(float(direction_deg))
    q0, q1 = (float(x) for x in surface.q_range)
    psi, wpsi = _angular_rule()
    cpsi = np.cos(psi)

    def weights(q):
        return _folded_weights(surface, theta, psi, wpsi, q)

    shape = weights(q0)
    for qq in (math.sqrt(q0 * q1), q1):
        w_ = weights(qq)
        if not np.allclose(w_ / w_.sum(), shape / shape.sum(), rtol=1e-9, atol=1e-14 * shape.max() / shape.sum()):
            raise ValueError("reference_directional_flash_friction: the angular shape of the PSD changes with q")
    k = int(np.argmax(shape))
    phi_k = theta + psi[k]
    c0 = float(surface.C2d(q0 * math.cos(phi_k), q0 * math.sin(phi_k)))
    th = material.thermal
    D, rc = th.diffusivity, th.heat_capacity
    q_m = macro_scale_ratio * q0
    d = contact_diameter if contact_diameter > 0 else math.pi / q_m
    q = flash_nodes(q0, q1, nodes_per_decade)
    x = np.log(q)
    fq = np.array([float(surface.C2d(qi * math.cos(phi_k), qi * math.sin(phi_k))) for qi in q]) / c0
    s = 1.0 / ((1.0 - nu * nu) * pressure)
    # the hottest temperature is unknown in advance: tabulate down to 500 K above the background
    lw_lo = math.log10(q0 * v.min()) - 0.1 + min(0.0, float(material.log10_aT(temperature + 500.0))
                                                 - float(material.log10_aT(temperature)))
    lw_hi = math.log10(q1 * v.max()) + 0.1
    lw = np.linspace(lw_lo, lw_hi, max(8, int(math.ceil((lw_hi - lw_lo) * omega_per_decade)) + 1))
    A, L = _frequency_tables(material, temperature, shape, cpsi, lw)
    # one spline of both logarithms: a single evaluation per ODE step
    ln_al = interpolate.CubicSpline(lw, np.column_stack([np.log(A), np.log(np.maximum(L, 1e-300))]))
    mus, areas, layers, Ts = [], [], [], []
    for vi in v:
        lv = math.log10(vi)

        def heat_source(T, vi=vi, lv=lv):
            shift = np.asarray(material.log10_aT(T) - material.log10_aT(temperature), dtype=float)

            def rhs(xx, y):
                qq = math.exp(xx)
                f = float(np.interp(xx, x, fq))
                w = xx / math.log(10.0) + lv + float(np.interp(xx, x, shift))
                P = float(special.erf(0.5 / math.sqrt(y[0]))) if y[0] > 0 else 1.0
                a_w, l_w = np.exp(ln_al(w))
                dmu = 0.5 * qq**4 * f * (gamma + (1.0 - gamma) * P * P) * P * l_w * s
                return [0.125 * qq**4 * f * a_w * s * s, dmu, dmu / qq]

            sol = integrate.solve_ivp(rhs, (x[0], x[-1]), [0.0, 0.0, 0.0], method="DOP853", rtol=1e-10,
                                      atol=1e-300, first_step=1e-12, dense_output=True)
            P = special.erf(0.5 / np.sqrt(np.maximum(sol.sol(x)[0], 1e-300)))
            Gm = float(sol.sol(math.log(q_m))[0])
            Pm = float(special.erf(0.5 / math.sqrt(Gm))) if Gm > 0 else 1.0
            w = x / math.log(10.0) + lv + shift
            return vi * q**4 * fq / rc * P / Pm * np.exp(ln_al(w)[:, 1]) / (1.0 - nu * nu), sol

        T, sol = flash_fixed_point(q, float(temperature), heat_matrix(q, D * d / vi, D), heat_source, tol, max_iter)
        mus.append(sol.y[1, -1])
        areas.append(float(special.erf(0.5 / math.sqrt(sol.y[0, -1]))) if sol.y[0, -1] > 0 else 1.0)
        layers.append(sol.y[2, -1] / sol.y[1, -1])
        Ts.append(T)
    return ReferenceResult(mu=np.array(mus), contact_area=np.array(areas), excited_layer=np.array(layers),
                           q_eval=q, temperature_q=np.array(Ts))


def _folded_weights(surface, theta: float, psi: np.ndarray, wpsi: np.ndarray, q: float) -> np.ndarray:
    """C(q, theta +- psi ...) summed over the four folded copies, times the weights, at the quadrature angles."""
    phis = (theta + psi, theta - psi, theta + math.pi - psi, theta + math.pi + psi)
    return wpsi * sum(np.asarray(surface.C2d(q * np.cos(p), q * np.sin(p)), dtype=float) for p in phis)


def _frequency_tables(material, temperature: float, shape: np.ndarray, cpsi: np.ndarray, lw: np.ndarray):
    """sum_psi shape |E(omega cos psi)|^2 and sum_psi shape cos(psi) E''(omega cos psi) at omega = 10^lw, in blocks
    of frequencies (vectorised, bounded memory)."""
    A, L = np.empty(lw.size), np.empty(lw.size)
    for i in range(0, lw.size, 16):
        E = np.asarray(material.E(10.0 ** lw[i:i + 16, None] * cpsi, temperature), dtype=complex)
        A[i:i + 16] = np.abs(E) ** 2 @ shape
        L[i:i + 16] = E.imag @ (shape * cpsi)
    return A, L


def _angular_rule(n_psi_panels: int = 32, n_gauss: int = 8, t_split: float = 1.0, t_max: float = 24.0):
    """Nodes and weights in psi on [0, pi/2]: uniform panels up to cos(psi) = 10^-t_split, then half-decade panels
    in t = -log10 cos(psi) (dpsi = ln 10 10^-t / sqrt(1 - 10^-2t) dt)."""
    g, w = np.polynomial.legendre.leggauss(n_gauss)
    g, w = 0.5 * (g + 1.0), 0.5 * w
    psi_s = math.acos(10.0 ** (-t_split))
    a = np.linspace(0.0, psi_s, n_psi_panels + 1)
    psi1 = (a[:-1, None] + np.diff(a)[:, None] * g).ravel()
    w1 = (np.diff(a)[:, None] * w).ravel()
    edges = np.arange(t_split, t_max + 1e-9, 0.5)
    t = (edges[:-1, None] + np.diff(edges)[:, None] * g).ravel()
    y = 10.0 ** (-t)
    jac = math.log(10.0) * y / np.sqrt(-np.expm1(-2.0 * math.log(10.0) * t))
    w2 = (np.diff(edges)[:, None] * w).ravel() * jac
    return np.concatenate([psi1, np.arccos(y)]), np.concatenate([w1, w2])
