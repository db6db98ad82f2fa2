"""numba kernels of the Persson solver. Thin wrappers in :mod:`persson.model` prepare the arrays.

All kernels work on a uniform grid in ln q (trapezoid weights ``wq``), Gauss-Legendre angles on [0, pi/2]
(``cphi``, ``lcphi`` = log10 cos phi, ``wphi``) and a modulus table in log10 of the *reduced* angular
frequency (``lw0``, ``inv_dlw``, ``ln_re``, ``ln_im`` = ln E', ln E'' at the reference temperature of the
table). A temperature T enters through ``shift`` = log10 a_T(T) relative to the table's temperature.

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
def _angular(base, lcphi, cphi, wphi, lw0, inv_dlw, ln_re, ln_im):
    """Return (int_0^{2pi} |E|^2 dphi, int_0^{2pi} cos(phi) Im E dphi) at log10(q v a_T) = ``base``."""
    a2 = 0.0
    al = 0.0
    for k in range(cphi.shape[0]):
        lw = base + lcphi[k]
        er = math.exp(_lookup(lw, lw0, inv_dlw, ln_re))
        ei = math.exp(_lookup(lw, lw0, inv_dlw, ln_im))
        a2 += wphi[k] * (er * er + ei * ei)
        al += wphi[k] * cphi[k] * ei
    return 4.0 * a2, 4.0 * al


@njit(cache=True)
def _scale_pass(iv, lq10, lv10, q4C, wq, shift, lcphi, cphi, wphi, lw0, inv_dlw, ln_re, ln_im,
                scale, gamma, G_out, P_out, loss_out, dmu_out):
    """One speed: G(q), P(q), loss integral and d mu / d ln q along the q grid; returns mu_visc.

    G(q) = 1/8 int q'^3 C |E/((1-nu^2) sigma0)|^2 dphi dq'  (trapezoid in ln q, cumulative),
    P = erf(1/(2 sqrt G)), S = gamma + (1-gamma) P^2,
    d mu/d ln q = 1/2 q^4 C S P int cos(phi) Im E/((1-nu^2) sigma0) dphi.
    """
    nq = lq10.shape[0]
    G = 0.0
    g_prev = 0.0
    mu = 0.0
    for iq in range(nq):
        a2, al = _angular(lq10[iq] + lv10[iv] + shift[iq], lcphi, cphi, wphi, lw0, inv_dlw, ln_re, ln_im)
        g_here = 0.125 * q4C[iq] * a2 * scale * scale
        if iq > 0:
            # trapezoid in ln q: wq[iq] holds the half-step for the interval ending at iq
            G += 0.5 * (g_prev + g_here) * (lq10[iq] - lq10[iq - 1]) * 2.302585092994046
        g_prev = g_here
        if G > 0.0:
            P = math.erf(0.5 / math.sqrt(G))
        else:
            P = 1.0
        S = gamma + (1.0 - gamma) * P * P
        d = 0.5 * q4C[iq] * S * P * al * scale
        G_out[iv, iq] = G
        P_out[iv, iq] = P
        loss_out[iv, iq] = al * scale
        dmu_out[iv, iq] = d
        mu += wq[iq] * d
    return mu


@njit(cache=True, parallel=True)
def friction_kernel(lq10, lv10, q4C, wq, shift, lcphi, cphi, wphi, lw0, inv_dlw, ln_re, ln_im,
                    scale, gamma, G_out, P_out, loss_out, dmu_out, mu_out):
    """Hysteresis friction and contact area for every speed (prange over speeds).

    Parameters are documented in the module docstring; ``shift`` has shape (n_speed, n_q) and holds
    log10 a_T(T_q) relative to the table temperature; outputs have shape (n_speed, n_q) and (n_speed,).
    """
    for iv in prange(lv10.shape[0]):
        mu_out[iv] = _scale_pass(iv, lq10, lv10, q4C, wq, shift[iv], lcphi, cphi, wphi, lw0, inv_dlw,
                                 ln_re, ln_im, scale, gamma, G_out, P_out, loss_out, dmu_out)


def trapezoid_weights_ln(lq10: np.ndarray) -> np.ndarray:
    """Trapezoid weights for int f d(ln q) on the nodes ``10**lq10`` (any spacing)."""
    x = lq10 * math.log(10.0)
    w = np.zeros_like(x)
    dx = np.diff(x)
    w[:-1] += 0.5 * dx
    w[1:] += 0.5 * dx
    return w
