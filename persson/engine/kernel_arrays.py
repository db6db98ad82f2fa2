"""The arrays the engine's numba kernels take, grouped in named tuples built once per call
(:mod:`persson.engine.kernels`), each field with its shape and unit.

numba passes named tuples to compiled functions as cheaply as their fields one by one, and a kernel reads
``nodes.q4C`` instead of its 20th positional argument. They are not nested: a parallel loop of numba takes one
level of tuples only.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = ["QuadratureRule", "ContactLaw", "AngularTables", "AngularShape", "Nodes", "SpeedFactors", "Outputs",
           "FlashSpeeds", "TemperatureTables", "HeatSource", "FixedPoint"]


class QuadratureRule(NamedTuple):
    """The wavevector quadrature on the nodes x = ln q (:func:`persson.engine.quadrature.quadrature_rule`).

    Parameters
    ----------
    W : ndarray (n_q - 1, 3)
        ``W[i, m]``: integral over interval i of the Lagrange basis function m of its quadratic stencil times
        q^4 C(q), in ln q (the PSD integrated exactly between its breakpoints), m^4 rad^4/m^4 = 1.
    stencil : ndarray of int64 (n_q - 1,)
        First node of the quadratic stencil of each interval (nodes stencil[i] .. stencil[i] + 2).
    piece_start : ndarray of int64 (n_q,)
        First piece of each interval: interval i is cut at the PSD's breakpoints into the pieces
        ``piece_start[i]`` .. ``piece_start[i + 1] - 1``.
    basis : ndarray (n_pieces, 3, 3)
        ``basis[p, k, m]``: the Lagrange basis function m of the piece's interval at the start (k = 0), middle
        (k = 1) and end (k = 2) of piece p.
    partial : ndarray (n_pieces, 3, 3)
        ``partial[p, k, m]``: the integral of basis function m times q^4 C from the interval's start to point k of
        piece p (G there, given the angular factor at the stencil nodes).
    """

    W: np.ndarray
    stencil: np.ndarray
    piece_start: np.ndarray
    basis: np.ndarray
    partial: np.ndarray


class ContactLaw(NamedTuple):
    """The area of real contact P(G) and the stress factor S(P) (:func:`persson.engine.kernels.area`,
    :func:`persson.engine.kernels.contact_weight`).

    Parameters
    ----------
    gamma : float
        gamma of S(P) = gamma + (1 - gamma) P^2 (Yang & Persson 2008), 1.
    ln_P : ndarray (n,)
        ln P of an area correction on a uniform grid of ln G; empty for Persson's erf law.
    ln_G0 : float
        ln G at the first node of ``ln_P``.
    per_ln_G : float
        Nodes of ``ln_P`` per unit ln G.
    """

    gamma: float
    ln_P: np.ndarray
    ln_G0: float
    per_ln_G: float


class AngularTables(NamedTuple):
    """The angular integrals of the modulus at the table temperature on a uniform grid of log10 omega (rad/s)
    (:class:`persson.engine.tabulate.AngularTable`).

    Parameters
    ----------
    lw0 : float
        log10 omega of the first node, omega in rad/s.
    inv_dlw : float
        Nodes per decade of omega.
    ln_are, ln_aim : ndarray (n_omega,)
        ln of A_re = int_0^{2 pi} E'(omega cos phi)^2 dphi and A_im (the same of E''), E in Pa: ln Pa^2.
    ln_l : ndarray (n_omega,)
        ln of L = int_0^{2 pi} cos phi E''(omega cos phi) dphi, ln Pa.
    """

    lw0: float
    inv_dlw: float
    ln_are: np.ndarray
    ln_aim: np.ndarray
    ln_l: np.ndarray


class AngularShape(NamedTuple):
    r"""The angular shape of an anisotropic PSD for the problems of a call (:mod:`persson.engine.anisotropic`): the
    factors :math:`\rho(q, \theta, \omega) = \sum_j W_j(q, \theta)\, v_j(\omega)` that multiply the isotropic
    angular integrals (:class:`AngularTables`). Each problem is one sliding direction at one speed (a row of the
    per-speed tuples). No basis functions (``n_basis`` = 0): an isotropic PSD, rho = 1.

    Parameters
    ----------
    direction : ndarray of int64 (n_problem,)
        The sliding direction of each problem: its row of ``weights`` and, with one table per direction, of the
        tables (empty for an isotropic PSD).
    weights : ndarray (n_dir, n_q, n_basis) or (1, n_q, n_basis)
        ``W[d, i, j]``: the weight of basis function j at node i for direction d ((1/4) w_s(q_i, psi_j) for a
        pointwise shape, 1 for the unidirectional limit), 1; one row shared by all directions when the first axis
        is 1.
    v_re, v_im, v_l : ndarray (n_table, n_omega, n_basis)
        The basis functions on the log-frequency grid of the angular tables (the normalised cardinal tables of the
        A_re, A_im and L integrals, 1; or, for the unidirectional limit, the ratio of its point value to the
        isotropic integral), one table per direction (``n_table`` = n_dir) or one shared (``n_table`` = 1).
    """

    direction: np.ndarray
    weights: np.ndarray
    v_re: np.ndarray
    v_im: np.ndarray
    v_l: np.ndarray


class Nodes(NamedTuple):
    """The wavevector nodes and the PSD on them (their :class:`QuadratureRule` travels beside them: numba's parallel
    loops take one level of tuples only).

    Parameters
    ----------
    q : ndarray (n_q,)
        Wavevector nodes, rad/m, increasing.
    x : ndarray (n_q,)
        ln q.
    lq10 : ndarray (n_q,)
        log10 q.
    q4C : ndarray (n_q,)
        q^4 C(q), 1 (C in m^4, Persson's convention).
    """

    q: np.ndarray
    x: np.ndarray
    lq10: np.ndarray
    q4C: np.ndarray


class SpeedFactors(NamedTuple):
    """Per speed: the speed, the stress scale and the modulus factors at every node (the solve without flash
    temperature, where the temperature of a speed is its background temperature at every scale).

    Parameters
    ----------
    lv10 : ndarray (n_speed,)
        log10 of the sliding speed, m/s.
    scale : ndarray (n_speed,)
        1 / ((1 - nu^2) sigma0), 1/Pa.
    shift : ndarray (n_speed, n_q)
        log10 a_T(T) - log10 a_T(T_table), decades.
    vshift : ndarray (n_speed, n_q)
        ln b_T(T) - ln b_T(T_table).
    f, g : ndarray (n_speed, n_q)
        Strain factors on E' and E'' (1 without a per-scale modulus).
    """

    lv10: np.ndarray
    scale: np.ndarray
    shift: np.ndarray
    vshift: np.ndarray
    f: np.ndarray
    g: np.ndarray


class Outputs(NamedTuple):
    """Per-speed and per-scale outputs the kernels fill (row iv: speed iv).

    Parameters
    ----------
    G : ndarray (n_speed, n_q)
        Persson's G(q), 1.
    P : ndarray (n_speed, n_q)
        Area of real contact P(q) = A(q)/A0.
    dmu : ndarray (n_speed, n_q)
        d mu / d ln q.
    cum : ndarray (n_speed, n_q)
        Hysteresis friction of the scales q0..q (last column: mu).
    dG : ndarray (n_speed, n_q)
        dG / d ln q.
    ratio : ndarray (n_speed, n_q)
        R = 4 L / A, the factor the contact weight S(P) P dG multiplies.
    loss : ndarray (n_speed, n_q)
        The loss integral int cos(phi) b_T g E''(omega cos phi) dphi / ((1 - nu^2) sigma0), 1.
    layer : ndarray (n_speed,)
        int q^-1 d mu (numerator of the excited-layer thickness), m.
    mu : ndarray (n_speed,)
        Hysteresis friction.
    """

    G: np.ndarray
    P: np.ndarray
    dmu: np.ndarray
    cum: np.ndarray
    dG: np.ndarray
    ratio: np.ndarray
    loss: np.ndarray
    layer: np.ndarray
    mu: np.ndarray


class FlashSpeeds(NamedTuple):
    """Per speed: the speed, the stress scale, the background temperature and the start of the iteration.

    Parameters
    ----------
    lv10 : ndarray (n_speed,)
        log10 of the sliding speed, m/s.
    v : ndarray (n_speed,)
        Sliding speed, m/s.
    scale : ndarray (n_speed,)
        1 / ((1 - nu^2) sigma0), 1/Pa.
    T0 : ndarray (n_speed,)
        Background temperature, deg C.
    T_start : ndarray (n_speed, n_q)
        Temperature profile the iteration starts from, deg C (T0 at every node, or a solution of the same
        problem on other nodes).
    """

    lv10: np.ndarray
    v: np.ndarray
    scale: np.ndarray
    T0: np.ndarray
    T_start: np.ndarray


class TemperatureTables(NamedTuple):
    """The temperature dependence of the modulus, tabulated on a uniform temperature grid.

    Parameters
    ----------
    T_lo : float
        First temperature of the tables, deg C.
    inv_dT : float
        Nodes per kelvin.
    shift : ndarray (n_T,)
        log10 a_T(T) - log10 a_T(T_table), decades.
    vshift : ndarray (n_T,)
        ln b_T(T) - ln b_T(T_table).
    f, g : ndarray (n_q, n_T) or (1, n_T)
        Strain factors on E' and E'' at every temperature: one row per node, or a single row shared by all.
    """

    T_lo: float
    inv_dT: float
    shift: np.ndarray
    vshift: np.ndarray
    f: np.ndarray
    g: np.ndarray


class HeatSource(NamedTuple):
    """The heat kernel and the strength of the heat source per speed.

    Parameters
    ----------
    erfcx : ndarray (n_speed, n_q)
        erfcx(2 q sqrt(D t0)) at every node.
    S1, S2 : ndarray (n_q, n_q)
        Speed-independent partial-fraction factors of the heat kernel
        (:func:`persson.engine.kernels.heat_kernel_factors`).
    a_t0 : ndarray (n_speed,)
        D t0, m^2 (t0 the contact time of a macro-asperity contact region).
    D : float
        Thermal diffusivity, m^2/s.
    heat_factor : ndarray (n_speed,)
        sigma0 / (rho c_p), K.
    x_m : float
        ln q_m, q_m the wavevector of the macro-asperity contact regions (rad/m): P(q_m) normalises the source.
    """

    erfcx: np.ndarray
    S1: np.ndarray
    S2: np.ndarray
    a_t0: np.ndarray
    D: float
    heat_factor: np.ndarray
    x_m: float


class FixedPoint(NamedTuple):
    """Controls of the fixed-point iteration.

    Parameters
    ----------
    tol : float
        Converged when max |T_new - T| over the nodes is below it, K.
    max_iter : int
        Iterations of each start: the first (Anderson mixing), the second (Aitken's relaxation) and the third
        (the half step T <- (T + g(T)) / 2).
    """

    tol: float
    max_iter: int
