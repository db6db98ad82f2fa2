r"""numba kernels of the anisotropic engine (:mod:`persson.engine.anisotropic`).

For an anisotropic PSD :math:`C(q, \phi) = \bar C(q)\, w(q, \phi)` and a sliding direction :math:`\theta` the
angular integrals of Persson's G(q) and friction integrand become

.. math:: \int_0^{2\pi} d\phi\, w(q, \phi)\, F(q v \cos(\phi - \theta)) =
          \int_0^{\pi/2} d\psi\, F(q v \cos\psi)\, w_s(\psi), \qquad
          w_s(\psi) = 2\,[w(\theta + \psi) + w(\theta - \psi)]

(F = :math:`E'^2`, :math:`E''^2` or :math:`\cos\psi\,E''`, each even about :math:`\psi = 0` and :math:`\pi/2`; w has
period :math:`\pi`). :math:`w_s` is interpolated by piecewise cubics on the uniform nodes :math:`\psi_j = j\pi/(2N)`
(mirrored at both ends), so the integral is :math:`\sum_j w_s(\psi_j) V_j(\omega)` with
:math:`V_j(\omega) = \int_0^{\pi/2} \beta_j(\psi) F(\omega\cos\psi)\, d\psi` for the cardinal functions
:math:`\beta_j` of that interpolation. With :math:`t = -\log_{10}\cos\psi` each :math:`V_j` is a convolution in log
frequency, evaluated exactly for the cubic interpolant of F on the modulus table's grid, as the isotropic
angular table (:func:`persson.engine.tabulate.angular_table`) is: :func:`basis_convolution`. The engine keeps
:math:`v_j = V_j / \sum_k V_k` (a partition of unity) and multiplies the isotropic table by
:math:`\rho = \sum_j \tfrac14 w_s(\psi_j) v_j`, which is 1 to rounding for an isotropic w.

The friction integral over q then runs exactly as in :mod:`persson.engine.kernels` (whose rules these kernels
call), one problem per (sliding direction, speed): :func:`friction_problems`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from .kernels import _coarse_mu, _cubic, _weight_of_area, angular_at, area, cumulative_weighted, friction_cumulative


@njit(cache=True)
def basis_convolution(F, c, d_lo, d_hi, out):
    r"""out[j, i] = :math:`\sum_d` c[j, d + 1] F[i - d] for every cardinal function j, F clamped at both ends.

    Parameters
    ----------
    F : ndarray (n,)
        The function of log frequency on the modulus table's grid (:math:`E'^2`, :math:`E''^2` or :math:`E''`).
    c : ndarray (n_basis, n_d)
        Product-integration weights: ``c[j, d + 1]`` multiplies F d nodes below (d = -1 .. n_d - 2), see
        :func:`persson.engine.anisotropic.basis_weights`.
    d_lo, d_hi : ndarray of int (n_basis,)
        First and last d with a non-zero weight, per cardinal function.
    out : ndarray (n_basis, n)
        Output.
    """
    n = F.shape[0]
    nb = c.shape[0]
    for j in range(nb):
        for i in range(n):
            acc = 0.0
            for d in range(d_lo[j], d_hi[j] + 1):
                k = i - d
                if k < 0:
                    k = 0
                elif k > n - 1:
                    k = n - 1
                acc += c[j, d + 1] * F[k]
            out[j, i] = acc


def _basis_lookup(lq10, lv10, shift, lw0, inv_dlw, v_re, v_im, v_l, out_re, out_im, out_l):
    """The normalised cardinal tables at the reduced frequency of every node and speed (cubic in log10 omega).

    Parameters
    ----------
    lq10 : ndarray (n_q,)
        log10 of the wavevector nodes, rad/m.
    lv10 : ndarray (n_speed,)
        log10 of the sliding speeds, m/s.
    shift : ndarray (n_speed,)
        log10 a_T of each speed's temperature relative to the table temperature.
    lw0 : float
        log10 omega (rad/s) of the tables' first node.
    inv_dlw : float
        Nodes per decade of the tables.
    v_re, v_im, v_l : ndarray (n_basis, n_omega)
        The cardinal tables of the E'^2, E''^2 and cos(psi) E'' integrals, normalised to sum 1 at every frequency.
    out_re, out_im, out_l : ndarray (n_q, n_basis, n_speed)
        Outputs: the tables at omega = q v a_T.
    """
    for s in prange(lv10.shape[0]):
        for i in range(lq10.shape[0]):
            x = (lq10[i] + lv10[s] + shift[s] - lw0) * inv_dlw
            for j in range(v_re.shape[0]):
                out_re[i, j, s] = _cubic(v_re[j], x)
                out_im[i, j, s] = _cubic(v_im[j], x)
                out_l[i, j, s] = _cubic(v_l[j], x)


#: :func:`_basis_lookup` compiled (one thread: it is cheap).
basis_lookup = njit(cache=True)(_basis_lookup)


def _problem_factors(pd, ps, lq10, lv10, shift, vshift, fq, gq, lw0, inv_dlw, ln_are, ln_aim, ln_l, scale, rho_re,
                     rho_im, rho_l, K, R, L):
    r"""The angular factors of every problem (direction, speed) at every node: K = A/8 of
    :math:`dG = q^4 \bar C K\, d\ln q`, the ratio R = 4 L / A and the loss integral L, with
    :math:`A = b_T^2 (f^2 A_{re}\rho_{re} + g^2 A_{im}\rho_{im}) s^2` and :math:`L = b_T\, g\, L_{iso}\rho_L\, s`.

    Parameters
    ----------
    pd, ps : ndarray of int (n_problem,)
        Direction and speed index of each problem.
    lq10 : ndarray (n_q,)
        log10 of the wavevector nodes, rad/m.
    lv10 : ndarray (n_speed,)
        log10 of the sliding speeds, m/s.
    shift, vshift : ndarray (n_speed,)
        log10 a_T and ln b_T of each speed's temperature relative to the table temperature.
    fq, gq : ndarray (n_speed, n_q)
        Per-scale factors on E' and E'' (1 without a per-scale modulus).
    lw0, inv_dlw : float
        First log10 omega (rad/s) and nodes per decade of the isotropic tables.
    ln_are, ln_aim, ln_l : ndarray (n_omega,)
        ln of the isotropic angular integrals of E'^2, E''^2 and cos(phi) E''
        (:class:`persson.engine.tabulate.AngularTable`).
    scale : ndarray (n_speed,)
        :math:`s = 1/((1-\nu^2)\sigma_0)`, 1/Pa.
    rho_re, rho_im, rho_l : ndarray (n_q, n_dir, n_speed)
        The anisotropic factors (1 for an isotropic angular shape).
    K, R, L : ndarray (n_problem, n_q)
        Outputs.
    """
    for p in prange(pd.shape[0]):
        k = pd[p]
        s = ps[p]
        b = math.exp(vshift[s])
        for i in range(lq10.shape[0]):
            are, aim, ll = angular_at(lq10[i] + lv10[s] + shift[s], lw0, inv_dlw, ln_are, ln_aim, ln_l)
            f = fq[s, i]
            g = gq[s, i]
            A = b * b * (f * f * are * rho_re[i, k, s] + g * g * aim * rho_im[i, k, s]) * scale[s] * scale[s]
            Lq = b * g * ll * rho_l[i, k, s] * scale[s]
            K[p, i] = 0.125 * A
            R[p, i] = 4.0 * Lq / A
            L[p, i] = Lq


#: :func:`_problem_factors` compiled.
problem_factors = njit(cache=True)(_problem_factors)


def _unidirectional_factors(pc, ps, lq10, lv10, shift, vshift, fq, gq, lw0, inv_dlw, ln_re, ln_im, scale, K, R, L):
    r"""The factors of :func:`_problem_factors` for a unidirectional PSD, whose angular integrals are point values:
    :math:`A = 2\pi |E(q v a_T c)|^2 s^2` and :math:`L = 2\pi c\, E''(q v a_T c)\, s`, c = |cos(alpha - theta)|.

    Parameters
    ----------
    pc : ndarray (n_problem,)
        c of each problem's direction (0: sliding along the ridges, read at the bottom of the table, where the
        modulus is the relaxed one).
    ps : ndarray of int (n_problem,)
        Speed index of each problem.
    lq10, lv10, shift, vshift, fq, gq, scale
        As :func:`_problem_factors`.
    lw0, inv_dlw : float
        First log10 omega (rad/s) and nodes per decade of the modulus tables.
    ln_re, ln_im : ndarray (n_omega,)
        ln E' and ln E'' at the table temperature (cubic in log10 omega, clamped at the ends).
    K, R, L : ndarray (n_problem, n_q)
        Outputs.
    """
    two_pi = 2.0 * math.pi
    for p in prange(pc.shape[0]):
        c = pc[p]
        s = ps[p]
        b = math.exp(vshift[s])
        lc = math.log10(c) if c > 0.0 else -1e300
        for i in range(lq10.shape[0]):
            x = (lq10[i] + lv10[s] + shift[s] + lc - lw0) * inv_dlw
            e1 = b * fq[s, i] * math.exp(_cubic(ln_re, x))
            e2 = b * gq[s, i] * math.exp(_cubic(ln_im, x))
            A = two_pi * (e1 * e1 + e2 * e2) * scale[s] * scale[s]
            Lq = two_pi * c * e2 * scale[s]
            K[p, i] = 0.125 * A
            R[p, i] = 4.0 * Lq / A
            L[p, i] = Lq


#: :func:`_unidirectional_factors` compiled.
unidirectional_factors = njit(cache=True)(_unidirectional_factors)


def _friction_problems(q, q4C, quad, K, R, L, law, coarse, quad_c, coarser, quad_cc, G_out, P_out, dmu_out,
                       cum_out, dG_out, layer_out, mu_out, mu_c, mu_cc):
    """G(q), P(q), d mu/d ln q and the cumulative friction of every problem, with the friction on the coarse and
    coarser sub-grids of the error estimate: the q rules of :func:`persson.engine.kernels._solve_speed` applied to
    each problem's angular factors (parallel over problems).

    Parameters
    ----------
    q : ndarray (n_q,)
        Wavevector nodes, rad/m.
    q4C : ndarray (n_q,)
        q^4 times the angular mean of the PSD at the nodes.
    quad : tuple
        The quadrature rule of the nodes (:func:`persson.engine.solver.quadrature_rule`).
    K, R, L : ndarray (n_problem, n_q)
        Angular factors (:func:`_problem_factors`).
    law : tuple
        The contact law (:func:`persson.engine.kernels.area`).
    coarse, coarser : ndarray of int
        Node indices of the coarse (every other) and coarser (every fourth) sub-grids.
    quad_c, quad_cc : tuple
        Their quadrature rules.
    G_out, P_out, dmu_out, cum_out, dG_out : ndarray (n_problem, n_q)
        Outputs: G, P, d mu/d ln q, the cumulative friction and dG/d ln q.
    layer_out, mu_out, mu_c, mu_cc : ndarray (n_problem,)
        Outputs: int q^-1 d mu, the friction, and the friction on the coarse and coarser sub-grids.
    """
    nq = q.shape[0]
    for p in prange(K.shape[0]):
        G = G_out[p]
        cumulative_weighted(K[p], quad[0], quad[1], G)
        for i in range(nq):
            P = area(G[i], law)
            P_out[p, i] = P
            dmu_out[p, i] = 0.5 * q4C[i] * _weight_of_area(P, law) * L[p, i]
            dG_out[p, i] = q4C[i] * K[p, i]
        layer_out[p] = friction_cumulative(G, K[p], R[p], q, quad, law, cum_out[p])
        mu_out[p] = cum_out[p, nq - 1]
        mu_c[p] = _coarse_mu(q, K[p], R[p], law, coarse, quad_c)
        mu_cc[p] = _coarse_mu(q, K[p], R[p], law, coarser, quad_cc)


#: :func:`_friction_problems` compiled, parallel over problems.
friction_problems = njit(cache=True, parallel=True)(_friction_problems)


def _friction_mu(q, quad, K, R, law, mu_out):
    """The hysteresis friction alone of every problem (parallel over problems): the coarser angular grid of the
    angular error estimate needs nothing else.

    Parameters
    ----------
    q : ndarray (n_q,)
        Wavevector nodes, rad/m.
    quad : tuple
        Their quadrature rule.
    K, R : ndarray (n_problem, n_q)
        Angular factors (:func:`_problem_factors`).
    law : tuple
        The contact law.
    mu_out : ndarray (n_problem,)
        Output.
    """
    nq = q.shape[0]
    for p in prange(K.shape[0]):
        G = np.empty(nq)
        cum = np.empty(nq)
        cumulative_weighted(K[p], quad[0], quad[1], G)
        friction_cumulative(G, K[p], R[p], q, quad, law, cum)
        mu_out[p] = cum[nq - 1]


#: :func:`_friction_mu` compiled, parallel over problems.
friction_mu = njit(cache=True, parallel=True)(_friction_mu)
