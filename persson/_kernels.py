"""numba kernels of the Persson solver. Thin wrappers in :mod:`persson.model` prepare the arrays.

All kernels work on a uniform grid in ln q (quadrature weights ``wq``, third-order interval rule), Gauss-Legendre angles on [0, pi/2]
(``cphi``, ``lcphi`` = log10 cos phi, ``wphi``) and a modulus table in log10 of the *reduced* angular
frequency (``lw0``, ``inv_dlw``, ``ln_re``, ``ln_im`` = ln E', ln E'' at the reference temperature of the
table). A temperature T enters through ``shift`` = log10 a_T(T) and ``vshift`` = ln b_T(T), both relative to the
table's temperature (time-temperature superposition: E(omega, T) = b_T E(omega a_T, T_table)).

Angular integrals use the parity of the modulus (|E|^2 even, Im E odd in omega):
int_0^{2pi} dphi f(q v cos phi) = 4 int_0^{pi/2} dphi f(...) for f = |E|^2 and f = cos(phi) Im E.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange


@njit(cache=True, fastmath=False)
def _lookup(lw, lw0, inv_dlw, tab):
    """Linear interpolation of ``tab`` (uniform in log10 omega), clamped at both ends."""
    x = (lw - lw0) * inv_dlw
    n = tab.shape[0]
    if x <= 0.0:
        return tab[0]
    if x >= n - 1:
        return tab[n - 1]
    i = int(x)
    f = x - i
    return tab[i] + f * (tab[i + 1] - tab[i])


@njit(cache=True)
def _angular(base, lnb, lcphi, cphi, wphi, lw0, inv_dlw, ln_re, ln_im):
    """Return (int_0^{2pi} |E|^2 dphi, int_0^{2pi} cos(phi) Im E dphi) at log10(q v a_T) = ``base``,
    with the moduli multiplied by the vertical shift exp(``lnb``) = b_T."""
    a2 = 0.0
    al = 0.0
    for k in range(cphi.shape[0]):
        lw = base + lcphi[k]
        er = math.exp(_lookup(lw, lw0, inv_dlw, ln_re) + lnb)
        ei = math.exp(_lookup(lw, lw0, inv_dlw, ln_im) + lnb)
        a2 += wphi[k] * (er * er + ei * ei)
        al += wphi[k] * cphi[k] * ei
    return 4.0 * a2, 4.0 * al


@njit(cache=True)
def _scale_pass(iv, lq10, lv10, q4C, wq, shift, vshift, lcphi, cphi, wphi, lw0, inv_dlw, ln_re, ln_im,
                scale, gamma, G_out, P_out, loss_out, dmu_out):
    """One speed: G(q), P(q), loss integral and d mu / d ln q along the q grid; returns mu_visc.

    G(q) = 1/8 int q'^3 C |E/((1-nu^2) sigma0)|^2 dphi dq' (cumulative, :func:`_cumulative_quadratic`),
    P = erf(1/(2 sqrt G)), S = gamma + (1-gamma) P^2,
    d mu/d ln q = 1/2 q^4 C S P int cos(phi) Im E/((1-nu^2) sigma0) dphi, integrated with the weights ``wq``.
    """
    nq = lq10.shape[0]
    g = np.empty(nq)
    for iq in range(nq):
        a2, al = _angular(lq10[iq] + lv10[iv] + shift[iq], vshift[iq], lcphi, cphi, wphi, lw0, inv_dlw,
                          ln_re, ln_im)
        g[iq] = 0.125 * q4C[iq] * a2 * scale * scale
        loss_out[iv, iq] = al * scale
    _cumulative_quadratic(g, lq10, G_out[iv])
    mu = 0.0
    for iq in range(nq):
        G = G_out[iv, iq]
        P = math.erf(0.5 / math.sqrt(G)) if G > 0.0 else 1.0
        S = gamma + (1.0 - gamma) * P * P
        d = 0.5 * q4C[iq] * S * P * loss_out[iv, iq]
        P_out[iv, iq] = P
        dmu_out[iv, iq] = d
        mu += wq[iq] * d
    return mu


@njit(cache=True)
def _cumulative_quadratic(f, lq10, out):
    r"""Cumulative integral of ``f`` over ln q on a uniform grid, third order.

    Each interval uses the quadratic through its two nodes and the next one (the previous one for the last
    interval): :math:`\int_{x_i}^{x_{i+1}} f\,dx \approx \frac{h}{12}(5 f_i + 8 f_{i+1} - f_{i+2})`.
    Where that would decrease the integral of a positive integrand (a jump by more than a factor 13 between
    nodes) the interval falls back to the trapezoid rule.
    """
    n = f.shape[0]
    out[0] = 0.0
    for i in range(n - 1):
        h = (lq10[i + 1] - lq10[i]) * 2.302585092994046
        if n < 3:
            inc = 0.5 * h * (f[i] + f[i + 1])
        elif i + 2 < n:
            inc = h / 12.0 * (5.0 * f[i] + 8.0 * f[i + 1] - f[i + 2])
        else:
            inc = h / 12.0 * (-f[i - 1] + 8.0 * f[i] + 5.0 * f[i + 1])
        if inc < 0.0:
            inc = 0.5 * h * (f[i] + f[i + 1])
        out[i + 1] = out[i] + inc


@njit(cache=True, parallel=True)
def friction_kernel(lq10, lv10, q4C, wq, shift, vshift, lcphi, cphi, wphi, lw0, inv_dlw, ln_re, ln_im,
                    scale, gamma, G_out, P_out, loss_out, dmu_out, mu_out):
    """Hysteresis friction and contact area for every speed (prange over speeds).

    Parameters are documented in the module docstring; ``shift`` and ``vshift`` have shape (n_speed, n_q) and
    hold log10 a_T(T) and ln b_T(T) relative to the table temperature; ``scale`` = 1/((1-nu^2) sigma0) per speed;
    outputs have shape (n_speed, n_q) and (n_speed,).
    """
    for iv in prange(lv10.shape[0]):
        mu_out[iv] = _scale_pass(iv, lq10, lv10, q4C, wq, shift[iv], vshift[iv], lcphi, cphi, wphi, lw0,
                                 inv_dlw, ln_re, ln_im, scale[iv], gamma, G_out, P_out, loss_out, dmu_out)


def quadrature_weights_ln(lq10: np.ndarray) -> np.ndarray:
    """Weights for int f d(ln q) on the uniform-in-log nodes ``10**lq10``: the sum over the intervals of the
    same third-order interval rule as :func:`_cumulative_quadratic` (trapezoid for fewer than 3 nodes)."""
    x = lq10 * math.log(10.0)
    n = x.size
    w = np.zeros(n)
    h = np.diff(x)
    if n < 3:
        w[:-1] += 0.5 * h
        w[1:] += 0.5 * h
        return w
    for i in range(n - 1):
        if i + 2 < n:
            w[i:i + 3] += h[i] / 12.0 * np.array([5.0, 8.0, -1.0])
        else:
            w[i - 1:i + 2] += h[i] / 12.0 * np.array([-1.0, 8.0, 5.0])
    return w


# --- flash temperature (Persson, J. Phys.: Condens. Matter 18, 7789 (2006)) -----------------------------------
@njit(cache=True)
def heat_kernel(qi, qj, a, D, ex_i, ex_j):
    r"""Closed form of Persson's heat kernel g(q_i, q_j), s.

    .. math::
        g(q, q') = \frac{1}{\pi}\int_0^\infty dk\, \frac{1 - e^{-D k^2 t_0}}{D k^2}
                   \frac{4q'}{k^2 + 4q'^2}\frac{4q^2}{k^2 + 4q^2}

    With :math:`\alpha = 2q'`, :math:`\beta = 2q`, :math:`a = D t_0` and partial fractions of
    :math:`1/(k^2 (k^2+\alpha^2)(k^2+\beta^2))`, using
    :math:`\int_0^\infty (1-e^{-ak^2})k^{-2} dk = \sqrt{\pi a}` and
    :math:`\int_0^\infty (1-e^{-ak^2})(k^2+c^2)^{-1} dk = \frac{\pi}{2c}(1 - \mathrm{erfcx}(c\sqrt a))`.
    ``ex_i`` = erfcx(2 q_i sqrt(a)), ``ex_j`` = erfcx(2 q_j sqrt(a)) are precomputed (scipy.special.erfcx).
    For alpha = beta (the diagonal) the double pole gives
    :math:`\int_0^\infty (1-e^{-ak^2})(k^2+c^2)^{-2}dk = \frac{\pi}{4c^3}(1-\mathrm{erfcx}(x))
    + \frac{\pi\sqrt a}{4c^2}(2x\,\mathrm{erfcx}(x) - 2/\sqrt\pi)`, :math:`x = c\sqrt a`.
    """
    al = 2.0 * qj
    be = 2.0 * qi
    sa = math.sqrt(a)
    pi = math.pi
    pre = 2.0 * al * be * be / (pi * D)
    base = math.sqrt(pi * a) / (al * al * be * be)
    rel = abs(al - be) / be
    if rel > 1e-5:
        B = 1.0 / (al * al * (al * al - be * be))
        Cc = 1.0 / (be * be * (be * be - al * al))
        I1 = base + B * (pi / (2.0 * al)) * (1.0 - ex_j) + Cc * (pi / (2.0 * be)) * (1.0 - ex_i)
    else:
        c = 0.5 * (al + be)
        ex = 0.5 * (ex_i + ex_j)
        x = c * sa
        J1 = (pi / (2.0 * c)) * (1.0 - ex)
        J2 = (pi / (4.0 * c**3)) * (1.0 - ex) + (pi * sa / (4.0 * c * c)) * (2.0 * x * ex - 2.0 / math.sqrt(pi))
        I1 = math.sqrt(pi * a) / c**4 - J1 / c**4 - J2 / (c * c)
    return pre * I1


@njit(cache=True)
def _shift_at(T, T_lo, inv_dT, shift_tab):
    return _lookup(T, T_lo, inv_dT, shift_tab)


@njit(cache=True, parallel=True)
def flash_kernel(q, lq10, lv10, v, q4C, wq, lcphi, cphi, wphi, lw0, inv_dlw, ln_re, ln_im, scale, gamma,
                 T0, T_lo, inv_dT, shift_tab, vshift_tab, EX, a_t0, D, heat_factor, i_m, f_m, tol, max_iter,
                 G_out, P_out, loss_out, dmu_out, mu_out, T_out, it_out, res_out):
    r"""Hysteresis friction with Persson's self-consistent flash temperature, per speed in parallel.

    .. math::
        T_q = T_0 + \int_{q_0}^{q} dq'\, g(q, q') f(q'),\quad
        f(q) = \frac{v q^4 C(q)}{\rho c_p} \frac{P(q)}{P(q_m)} \int_0^{2\pi} d\phi \cos\phi
               \frac{\mathrm{Im}\,E(q v\cos\phi, T_q)}{1-\nu^2}

    Fixed-point iteration with adaptive under-relaxation: the relaxation factor halves whenever the residual
    max |T_new - T| grows, and recovers slowly while it falls. ``heat_factor`` = sigma0 / (rho c_p) per speed
    turns the loss integral held by ``loss_out`` (divided by (1-nu^2) sigma0) into the temperature source.
    """
    nq = q.shape[0]
    for iv in prange(lv10.shape[0]):
        g = np.zeros((nq, nq))
        for i in range(nq):
            for j in range(i + 1):
                g[i, j] = heat_kernel(q[i], q[j], a_t0[iv], D, EX[iv, i], EX[iv, j])
        T = np.full(nq, T0[iv])
        Tn = np.empty(nq)
        shift = np.empty(nq)
        vshift = np.empty(nq)
        f = np.empty(nq)
        relax = 1.0
        res_prev = 1e300
        res = 0.0
        it = 0
        for it in range(1, max_iter + 1):
            for i in range(nq):
                shift[i] = _shift_at(T[i], T_lo, inv_dT, shift_tab)
                vshift[i] = _shift_at(T[i], T_lo, inv_dT, vshift_tab)
            _scale_pass(iv, lq10, lv10, q4C, wq, shift, vshift, lcphi, cphi, wphi, lw0, inv_dlw, ln_re, ln_im,
                        scale[iv], gamma, G_out, P_out, loss_out, dmu_out)
            # P(q_m), linear in ln q between the nodes around q_m
            Pm = P_out[iv, i_m] + f_m * (P_out[iv, min(i_m + 1, nq - 1)] - P_out[iv, i_m])
            for j in range(nq):
                f[j] = v[iv] * q4C[j] * heat_factor[iv] * P_out[iv, j] / Pm * loss_out[iv, j]
            res = 0.0
            for i in range(nq):
                acc = 0.0
                if i > 0:
                    for j in range(i + 1):
                        # trapezoid in q on [q_0, q_i]
                        if j == 0:
                            wj = 0.5 * (q[1] - q[0])
                        elif j == i:
                            wj = 0.5 * (q[i] - q[i - 1])
                        else:
                            wj = 0.5 * (q[j + 1] - q[j - 1])
                        acc += wj * g[i, j] * f[j]
                Tn[i] = T0[iv] + acc
                d = abs(Tn[i] - T[i])
                if d > res:
                    res = d
            if res < tol:
                for i in range(nq):
                    T[i] = Tn[i]
                break
            if res > res_prev:
                relax = max(0.5 * relax, 1.0 / 64.0)
            else:
                relax = min(1.0, 1.25 * relax)
            res_prev = res
            for i in range(nq):
                T[i] = T[i] + relax * (Tn[i] - T[i])
        for i in range(nq):
            shift[i] = _shift_at(T[i], T_lo, inv_dT, shift_tab)
            vshift[i] = _shift_at(T[i], T_lo, inv_dT, vshift_tab)
            T_out[iv, i] = T[i]
        mu_out[iv] = _scale_pass(iv, lq10, lv10, q4C, wq, shift, vshift, lcphi, cphi, wphi, lw0, inv_dlw,
                                 ln_re, ln_im, scale[iv], gamma, G_out, P_out, loss_out, dmu_out)
        it_out[iv] = it
        res_out[iv] = res
