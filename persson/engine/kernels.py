r"""numba kernels of the Persson solver: angular tables, the wavevector quadrature, the hysteresis friction and the
self-consistent flash temperature.

Thin wrappers in :mod:`persson.engine.solver` prepare the arrays. The kernels that call one another live in this
one file on purpose: numba caches a compiled kernel by its own source file only, so a kernel calling a kernel of
another file would keep running the old code from the cache after that file changed. Three numerical ideas make
the solver accurate from soft to glassy rubber:

1. **Angular integrals tabulated once per call.** They depend on q, v and a_T only through the reduced frequency
   :math:`\omega = q v a_T`, so :math:`A_{re}(\omega) = \int_0^{2\pi} E'(\omega\cos\phi)^2 d\phi`,
   :math:`A_{im}(\omega) = \int_0^{2\pi} E''(\omega\cos\phi)^2 d\phi` and
   :math:`L(\omega) = \int_0^{2\pi} \cos\phi\, E''(\omega\cos\phi) d\phi` are tabulated on the modulus table's
   log-uniform frequency grid. With :math:`\cos\phi = 10^{-t}` each is a convolution in log frequency,
   :math:`\int_0^\infty K(t) F(\log_{10}\omega - t) dt`, which :func:`angular_convolution` evaluates exactly for
   the cubic (4-point Lagrange) interpolant of F between the grid nodes: uniform resolution in log frequency, so
   a glass transition crossed within a narrow window of angles near :math:`\phi = \pi/2` is still resolved.
2. **The contact weight integrated exactly.** With :math:`dG = \tfrac18 q^4 C A\, d\ln q`,

   .. math:: \mu = \int_0^{G(q_1)} R(G)\, S(P)\, P\, dG, \qquad R = 4 L / A,

   where :math:`P = \mathrm{erf}(1/(2\sqrt G))` is a known function of G and R depends on the modulus only (not
   on the PSD), so it is smooth. When :math:`|E|/\sigma_0` is large, G rises by orders of magnitude within the
   first q interval and P falls from 1 to almost 0 inside it: a rule sampling P at log-uniform nodes cannot see
   that boundary layer (errors of 10x were seen). Here each interval is cut at the PSD's breakpoints; on each
   piece G is known at its ends and middle (the PSD integrated exactly,
   :func:`persson.engine.quadrature.quadrature_rule`), R is interpolated by the quadratic in G through those three
   points, and the weight :math:`S(P)P` is integrated exactly (Gauss-Legendre in :math:`s = \sqrt G` on geometric
   pieces, where :math:`2 s\, S P` is smooth and bounded), :func:`interval_node_weights`. The heat source of the
   flash temperature, weight P dG, is integrated the same way (:func:`_flash_speed`).
3. **A built-in error estimate.** Every speed is also integrated on the coarse grid of every other node and on
   the coarser grid of every fourth; the differences estimate the error of the fine result
   (:func:`persson.engine.solver._relative_error`). The flash temperature uses two interleaved coarse grids
   instead, each a self-consistent solve of its own (:func:`persson.engine.solver._flash_error`).

The kernels take their arrays grouped in named tuples built once per call (:class:`Nodes`, :class:`QuadratureRule`,
:class:`AngularTables`, :class:`AngularShape`, :class:`ContactLaw`, :class:`SpeedFactors`, :class:`Outputs` and,
for the flash temperature, :class:`FlashSpeeds`, :class:`TemperatureTables`, :class:`HeatSource`,
:class:`FixedPoint`, defined in :mod:`persson.engine.kernel_arrays`), each field documented there, and are called
with keyword arguments.
Grids: nodes ``x`` = ln q (any increasing sequence; third-order interval rule for the non-uniform spacing), angular
tables uniform in log10 omega. A temperature T enters through ``shift`` = log10 a_T(T) and ``vshift`` = ln b_T(T)
relative to the table temperature (time-temperature superposition: E(omega, T) = b_T E(omega a_T, T_table));
per-scale strain factors f, g multiply E' and E'' (large-strain modulus).

An anisotropic PSD (:mod:`persson.engine.anisotropic`) runs through the same kernels: an :class:`AngularShape`
multiplies the isotropic angular integrals at every node by factors :math:`\rho(q, \theta, \omega)` of its sliding
direction (:func:`shape_factors`), and each row of the per-speed tuples is then one problem (a direction at a
speed), so the plain solve and the flash-temperature fixed point are the isotropic ones with C(q) the angular mean.
An isotropic PSD passes a shape without basis functions (:math:`\rho = 1`, not evaluated).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .borrow import borrowed
from .kernel_arrays import (AngularShape, AngularTables, ContactLaw, FixedPoint, FlashSpeeds, HeatSource, Nodes,
                            Outputs, QuadratureRule, SpeedFactors, TemperatureTables)

__all__ = ["QuadratureRule", "ContactLaw", "AngularTables", "AngularShape", "Nodes", "SpeedFactors", "Outputs",
           "angular_convolution", "angular_at", "shape_factors", "cumulative_weighted", "area", "contact_weight",
           "interval_node_weights", "friction_cumulative", "linear_at", "scale_factors", "contact_and_friction",
           "friction_kernel", "heat_matrix", "integrands_at", "heated_temperature",
           "flash_kernel", "heat_kernel", "heat_kernel_factors", "FlashSpeeds", "TemperatureTables",
           "HeatSource", "FixedPoint"]


# Gauss-Legendre nodes on [0, 1] for the product quadrature of the contact weight: 6 points per geometric piece
# of ratio up to 2 in s (the integrand 2 s w(s^2) is analytic there, error ~ 1e-9 relative per piece), 3 points
# on narrow pieces of ratio below 1.25 (error ~ (0.25/7)^6 ~ 1e-9).
_GL_X, _GL_W = np.polynomial.legendre.leggauss(6)
_GL_X = 0.5 * (_GL_X + 1.0)
_GL_W = 0.5 * _GL_W
_GL3_X, _GL3_W = np.polynomial.legendre.leggauss(3)
_GL3_X = 0.5 * (_GL3_X + 1.0)
_GL3_W = 0.5 * _GL3_W
_NARROW = 1.25
# 2 points where the piece spans less than 5 % in s (the error then falls as (0.05)^4 / 4320 ~ 1e-9)
_GL2_X, _GL2_W = np.polynomial.legendre.leggauss(2)
_GL2_X = 0.5 * (_GL2_X + 1.0)
_GL2_W = 0.5 * _GL2_W
_VERY_NARROW = 1.05
#: Below s = sqrt(G) = _S_MIN the weight is P = 1 to 1e-300 (erfc(10)); one Gauss piece covers [0, _S_MIN].
_S_MIN = 0.05


# ==================================================================================================== tables
@njit(cache=True)
def angular_convolution(F, c, out):
    r"""out_j = sum_d c_d F_{j-d}, with F clamped to F_0 below the table and to F_{n-1} above it: an angular
    integral on the log-frequency grid (:func:`persson.engine.tabulate.angular_table`).

    Parameters
    ----------
    F : ndarray (n,)
        The integrand on the uniform log10 omega grid (E'^2, E''^2 in Pa^2 or E'' in Pa).
    c : ndarray (m,)
        Product-integration weights c_d for d = -1 .. m - 2, stored at ``c[d + 1]``
        (:func:`persson.engine.tabulate.convolution_weights`); weights past the end of ``c`` are zero.
    out : ndarray (n,)
        Filled with the integral at every node, in the unit of F.
    """
    n = F.shape[0]
    m = c.shape[0]
    # suffix sums of c: the weight of every node below the table, folded onto F_0
    tail = np.zeros(m + 1)
    for k in range(m - 1, -1, -1):
        tail[k] = tail[k + 1] + c[k]
    for j in range(n):
        acc = 0.0
        hi = min(j, m - 2)  # largest d with its own node (F_{j-d}, j-d >= 0)
        for d in range(-1, hi + 1):
            idx = j - d
            if idx > n - 1:
                idx = n - 1
            acc += c[d + 1] * F[idx]
        if hi + 2 < m + 1:
            acc += tail[hi + 2] * F[0]
        out[j] = acc


@njit(cache=True)
def _cubic(tab, x):
    """4-point Lagrange interpolation of ``tab`` at fractional index ``x`` (clamped to the ends).

    Parameters
    ----------
    tab : ndarray (n,)
        Values on a uniform grid.
    x : float
        Fractional index into ``tab``.

    Returns
    -------
    float
    """
    im, i, ip, ip2, c0, c1, c2, c3 = _cubic_weights(x, tab.shape[0])
    return c0 * tab[im] + c1 * tab[i] + c2 * tab[ip] + c3 * tab[ip2]


@njit(cache=True)
def _cubic_weights(x, n):
    """The nodes and weights of :func:`_cubic` at fractional index ``x`` of a table of ``n`` values: one stencil
    serves every table on the same grid (the basis functions of an angular shape).

    Parameters
    ----------
    x : float
        Fractional index into the table.
    n : int
        Length of the table.

    Returns
    -------
    (int, int, int, int, float, float, float, float)
        The four nodes and their weights (clamped ends: the end node with weight 1).
    """
    if x <= 0.0:
        return 0, 0, 0, 0, 1.0, 0.0, 0.0, 0.0
    if x >= n - 1:
        return n - 1, n - 1, n - 1, n - 1, 1.0, 0.0, 0.0, 0.0
    i = int(x)
    t = x - i
    im = i - 1 if i >= 1 else 0
    ip2 = i + 2 if i + 2 < n else n - 1
    return (im, i, i + 1, ip2, -t * (t - 1.0) * (t - 2.0) / 6.0, (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0,
            -((t + 1.0) * t * (t - 2.0) / 2.0), (t + 1.0) * t * (t - 1.0) / 6.0)


@njit(cache=True)
def linear_at(tab, x):
    """Linear interpolation of ``tab`` at fractional index ``x`` (clamped to the ends).

    Parameters
    ----------
    tab : ndarray (n,)
        Values on a uniform grid.
    x : float
        Fractional index into ``tab``.

    Returns
    -------
    float
    """
    n = tab.shape[0]
    if x <= 0.0:
        return tab[0]
    if x >= n - 1:
        return tab[n - 1]
    i = int(x)
    f = x - i
    return tab[i] + f * (tab[i + 1] - tab[i])


@njit(cache=True)
def angular_at(lw, angular):
    """The angular integrals at one frequency, interpolated cubically in log10 omega.

    Parameters
    ----------
    lw : float
        log10 omega, omega in rad/s (at the table temperature).
    angular : AngularTables
        The tables.

    Returns
    -------
    (float, float, float)
        A_re and A_im (Pa^2), L (Pa).
    """
    x = (lw - angular.lw0) * angular.inv_dlw
    return (math.exp(_cubic(angular.ln_are, x)), math.exp(_cubic(angular.ln_aim, x)),
            math.exp(_cubic(angular.ln_l, x)))


@njit(cache=True)
def shape_factors(p, i, x, shape):
    r"""The factors :math:`\rho = \sum_j W_j v_j(\omega)` of an anisotropic PSD's angular shape that multiply the
    isotropic angular integrals A_re, A_im and L of problem ``p`` at node ``i`` (:mod:`persson.engine.anisotropic`);
    the basis functions interpolated cubically in log10 omega on the grid of the angular tables.

    Parameters
    ----------
    p : int
        The problem (one sliding direction at one speed).
    i : int
        The node.
    x : float
        Fractional index of log10 omega into the angular tables' grid.
    shape : AngularShape
        The angular shape (with at least one basis function).

    Returns
    -------
    (float, float, float)
        rho of A_re, A_im and L, 1.
    """
    d = shape.direction[p]
    w = shape.weights[d if shape.weights.shape[0] > 1 else 0, i]
    k = d if shape.v_re.shape[0] > 1 else 0
    v_re = shape.v_re[k]
    v_im = shape.v_im[k]
    v_l = shape.v_l[k]
    im, i0, ip, ip2, c0, c1, c2, c3 = _cubic_weights(x, v_re.shape[0])
    r_re = 0.0
    r_im = 0.0
    r_l = 0.0
    for j in range(w.shape[0]):
        wj = w[j]
        r_re += wj * (c0 * v_re[im, j] + c1 * v_re[i0, j] + c2 * v_re[ip, j] + c3 * v_re[ip2, j])
        r_im += wj * (c0 * v_im[im, j] + c1 * v_im[i0, j] + c2 * v_im[ip, j] + c3 * v_im[ip2, j])
        r_l += wj * (c0 * v_l[im, j] + c1 * v_l[i0, j] + c2 * v_l[ip, j] + c3 * v_l[ip2, j])
    return r_re, r_im, r_l


# ==================================================================================================== q rules
@njit(cache=True)
def cumulative_weighted(K, rule, out):
    r"""Cumulative :math:`G(q_i) = \int_{x_0}^{x_i} c(x) K(x) dx` from the product weights of the rough factor
    c = q^4 C(q), integrated exactly piece by piece between the PSD's own breakpoints; K (the smooth angular
    factor) is interpolated by the quadratic through the stencil of each interval. Where that would decrease G
    (K varying wildly between nodes) the interval takes the mean of K at its ends times the exact integral of c.

    Parameters
    ----------
    K : ndarray (n_q,)
        The angular factor A / 8 at the nodes, 1.
    rule : QuadratureRule
        The quadrature on the nodes (``W`` and ``stencil`` are used).
    out : ndarray (n_q,)
        Filled with G at every node (0 at the first).
    """
    n = K.shape[0]
    W = rule.W
    stencil = rule.stencil
    out[0] = 0.0
    for i in range(n - 1):
        a = stencil[i]
        inc = W[i, 0] * K[a] + W[i, 1] * K[a + 1] + W[i, 2] * K[a + 2]
        if inc < 0.0:
            inc = 0.5 * (K[i] + K[i + 1]) * (W[i, 0] + W[i, 1] + W[i, 2])
        out[i + 1] = out[i] + inc


@njit(cache=True)
def area(G, law):
    r"""Area of real contact P(G): :math:`\mathrm{erf}(1/(2\sqrt G))` (Persson 2001) when the law has no table,
    else the corrected area of :mod:`persson.contact.corrections` (ln P linear in ln G between nodes; P = erf(...)
    = 1 to double precision below the table, P ~ G^(-1/2) past it).

    Parameters
    ----------
    G : float
        Persson's G, 1.
    law : ContactLaw
        The contact law.

    Returns
    -------
    float
        A / A0.
    """
    if G <= 0.0:
        return 1.0
    tab = law.ln_P
    n = tab.shape[0]
    if n == 0:
        return math.erf(0.5 / math.sqrt(G))
    lg = math.log(G)
    x = (lg - law.ln_G0) * law.per_ln_G
    if x <= 0.0:
        return math.erf(0.5 / math.sqrt(G))
    if x >= n - 1:
        return math.exp(tab[n - 1] - 0.5 * (lg - (law.ln_G0 + (n - 1) / law.per_ln_G)))
    i = int(x)
    f = x - i
    return math.exp(tab[i] + f * (tab[i + 1] - tab[i]))


@njit(cache=True)
def contact_weight(G, law, kind):
    """The weight of dG in the friction (``kind`` 0) or in the flash-temperature heat source (``kind`` 1).

    Parameters
    ----------
    G : float
        Persson's G, 1.
    law : ContactLaw
        The contact law.
    kind : int
        0: S(P) P with S = gamma + (1 - gamma) P^2; 1: P.

    Returns
    -------
    float
    """
    P = area(G, law)
    if kind == 1:
        return P
    return _weight_of_area(P, law)


@njit(cache=True)
def _weight_of_area(P, law):
    """S(P) P with S = gamma + (1 - gamma) P^2 (Persson's interpolation of the stress factor, Yang & Persson 2008).

    Parameters
    ----------
    P : float
        Area of real contact A / A0.
    law : ContactLaw
        The contact law (its ``gamma``).

    Returns
    -------
    float
    """
    gamma = law.gamma
    return (gamma + (1.0 - gamma) * P * P) * P


@njit(cache=True, inline="always")
def _interval_weights(Ga, Gb, G0, G1, G2, use_quadratic, law, kind):
    r"""Weights (w0, w1, w2) with :math:`\int_{G_a}^{G_b} R(G)\, w(G)\, dG = \sum_m w_m R(G_m)` exactly for the
    quadratic R through (G0, G1, G2) (or the linear R through G0, G1 when ``use_quadratic`` is False; then w2 = 0).

    The contact weight w (:func:`contact_weight`) is integrated by Gauss-Legendre in :math:`s = \sqrt G` on
    pieces [s, 2s] (and one piece [0, 0.05]): :math:`2 s\, w(s^2)` is smooth and bounded (it tends to 2 gamma
    / sqrt(pi) as G grows, since P ~ 1/sqrt(pi G)), so a few pieces cover any rise of G.

    Parameters
    ----------
    Ga, Gb : float
        The range of G integrated over, Ga < Gb.
    G0, G1, G2 : float
        The interpolation nodes of R in G (G2 unused when ``use_quadratic`` is False).
    use_quadratic : bool
        Quadratic (True) or linear (False) R.
    law : ContactLaw
        The contact law.
    kind : int
        The weight (see :func:`contact_weight`).

    Returns
    -------
    (float, float, float)
        The weights of R(G0), R(G1), R(G2).

    Inlined into its callers (numba ``inline="always"``), so that ``kind`` and the law's kind are resolved where
    the weights are used: the flash iteration evaluates these weights for every interval at every step, and the
    general, branching form took about 1.6x as long there (same numbers, to the last bit).
    """
    # moments M_k = int u^k w dG of u = G - G1 (the middle node: well conditioned), then the weights from the
    # Lagrange basis written in u; one pass with no division per Gauss point
    m0 = 0.0
    m1 = 0.0
    m2 = 0.0
    if not Gb > Ga:
        return 0.0, 0.0, 0.0
    plain = law.ln_P.shape[0] == 0
    sa = math.sqrt(max(Ga, 0.0))
    sb = math.sqrt(Gb)
    lo = sa
    while lo < sb:
        hi = max(2.0 * lo, _S_MIN)
        if hi > sb:
            hi = sb
        span = hi - lo
        if lo > 0.0 and hi < _VERY_NARROW * lo:
            gx, gw = _GL2_X, _GL2_W
        elif lo > 0.0 and hi < _NARROW * lo:
            gx, gw = _GL3_X, _GL3_W
        else:
            gx, gw = _GL_X, _GL_W
        for k in range(gx.shape[0]):
            s = lo + span * gx[k]
            G = s * s
            wt = gw[k] * span * 2.0 * s * _weight_at(s, G, law, kind, plain)
            u = G - G1
            m0 += wt
            m1 += wt * u
            m2 += wt * u * u
        lo = hi
    d10 = G1 - G0
    if not use_quadratic:
        # linear through G0, G1: l0 = -u / d10, l1 = (u + d10) / d10
        return -m1 / d10, (m1 + d10 * m0) / d10, 0.0
    d21 = G2 - G1
    # l0 = u (u - d21) / (d10 (d10 + d21)), l1 = -(u + d10)(u - d21) / (d10 d21), l2 = u (u + d10) / (d21 (d10 + d21))
    w0 = (m2 - d21 * m1) / (d10 * (d10 + d21))
    w1 = -(m2 + (d10 - d21) * m1 - d10 * d21 * m0) / (d10 * d21)
    w2 = (m2 + d10 * m1) / (d21 * (d10 + d21))
    return w0, w1, w2


@njit(cache=True, inline="always")
def _weight_at(s, G, law, kind, plain):
    """:func:`contact_weight` at G = s^2; for Persson's erf law (``plain``) from s itself,
    P = erf(1/(2 s)), the same number without a square root (sqrt(s^2) is s exactly in IEEE arithmetic).

    Parameters
    ----------
    s : float
        sqrt(G), >= 0.
    G : float
        Persson's G, 1.
    law : ContactLaw
        The contact law.
    kind : int
        0: S(P) P; 1: P (see :func:`contact_weight`).
    plain : bool
        Whether the law is Persson's erf law (no correction table).

    Returns
    -------
    float
    """
    if not plain:
        return contact_weight(G, law, kind)
    P = math.erf(0.5 / s) if s > 0.0 else 1.0
    if kind == 1:
        return P
    return _weight_of_area(P, law)


@njit(cache=True)
def _quadratic_ok(G0, G1, G2):
    """Whether R may be interpolated quadratically in G: the three G nodes distinct and roughly evenly spaced
    (G close to proportional to ln q); else (a stretch where C ~ 0, a jump of the PSD) R is taken linear.

    Parameters
    ----------
    G0, G1, G2 : float
        G at the start, middle and end of a piece.

    Returns
    -------
    bool
    """
    d1 = G1 - G0
    d2 = G2 - G1
    if not (d1 > 0.0 and d2 > 0.0):
        return False
    r = d2 / d1
    return 0.05 < r < 20.0


@njit(cache=True)
def interval_node_weights(G, K, i, rule, law, kind):
    r"""Node weights (first stencil node a, w0, w1, w2) of interval i:
    :math:`\int_{G_i}^{G_{i+1}} F\, w(G)\, dG \approx \sum_m w_m F_{a+m}` for a factor F smooth in ln q.

    The interval is cut at the PSD's breakpoints into pieces. On each piece G is known at its ends and middle
    from the partial PSD weights (exact PSD, angular factor K quadratic in ln q), F there from its quadratic in
    ln q (the basis values of the rule), and F w dG is integrated with F quadratic in G through those three points
    and the weight w exact (:func:`_interval_weights`). F is never interpolated across a kink of the PSD, where
    G(ln q) bends.

    Parameters
    ----------
    G : ndarray (n_q,)
        G at the nodes, 1.
    K : ndarray (n_q,)
        The angular factor A / 8 at the nodes, 1.
    i : int
        The interval (nodes i, i + 1).
    rule : QuadratureRule
        The quadrature on the nodes.
    law : ContactLaw
        The contact law.
    kind : int
        The weight w (see :func:`contact_weight`).

    Returns
    -------
    (int, float, float, float)
        a and the weights of F_a, F_{a+1}, F_{a+2}.
    """
    basis = rule.basis
    partial = rule.partial
    a = rule.stencil[i]
    o0 = 0.0
    o1 = 0.0
    o2 = 0.0
    p0 = rule.piece_start[i]
    p1 = rule.piece_start[i + 1]
    for p in range(p0, p1):
        Gi = G[i]
        Glo = (Gi if p == p0
               else Gi + partial[p, 0, 0] * K[a] + partial[p, 0, 1] * K[a + 1] + partial[p, 0, 2] * K[a + 2])
        Gmid = Gi + partial[p, 1, 0] * K[a] + partial[p, 1, 1] * K[a + 1] + partial[p, 1, 2] * K[a + 2]
        Ghi = (G[i + 1] if p == p1 - 1
               else Gi + partial[p, 2, 0] * K[a] + partial[p, 2, 1] * K[a + 1] + partial[p, 2, 2] * K[a + 2])
        if not Ghi > Glo:
            continue
        if Glo < Gmid < Ghi and _quadratic_ok(Glo, Gmid, Ghi):
            w0, w1, w2 = _interval_weights(Glo, Ghi, Glo, Gmid, Ghi, True, law, kind)
        else:
            w0, w2, _ = _interval_weights(Glo, Ghi, Glo, Ghi, 0.0, False, law, kind)
            w1 = 0.0
        o0 += w0 * basis[p, 0, 0] + w1 * basis[p, 1, 0] + w2 * basis[p, 2, 0]
        o1 += w0 * basis[p, 0, 1] + w1 * basis[p, 1, 1] + w2 * basis[p, 2, 1]
        o2 += w0 * basis[p, 0, 2] + w1 * basis[p, 1, 2] + w2 * basis[p, 2, 2]
    return a, o0, o1, o2


@njit(cache=True)
def friction_cumulative(G, K, R, q, rule, law, out):
    r"""Cumulative hysteresis friction :math:`\int_0^{G(q_i)} R\, S(P) P\, dG` at every node and
    :math:`\int q^{-1} d\mu` over the whole range (the numerator of the excited-layer thickness), both with the
    node weights of :func:`interval_node_weights`.

    Parameters
    ----------
    G : ndarray (n_q,)
        G at the nodes, 1.
    K : ndarray (n_q,)
        The angular factor A / 8 at the nodes, 1.
    R : ndarray (n_q,)
        The ratio 4 L / A at the nodes, 1.
    q : ndarray (n_q,)
        The nodes, rad/m.
    rule : QuadratureRule
        The quadrature on the nodes.
    law : ContactLaw
        The contact law.
    out : ndarray (n_q,)
        Filled with the friction of the scales q0..q_i (0 at the first node).

    Returns
    -------
    float
        int q^-1 d mu, m.
    """
    n = G.shape[0]
    out[0] = 0.0
    layer = 0.0
    for i in range(n - 1):
        a, w0, w1, w2 = interval_node_weights(G, K, i, rule, law, 0)
        out[i + 1] = out[i] + w0 * R[a] + w1 * R[a + 1] + w2 * R[a + 2]
        layer += w0 * R[a] / q[a] + w1 * R[a + 1] / q[a + 1] + w2 * R[a + 2] / q[a + 2]
    return layer


# ==================================================================================================== friction
@njit(cache=True)
def scale_factors(lq10, lw_speed, q4C, shift, vshift, f, g, angular, shape, p, scale, K, dG, R, loss):
    r"""The factors of the integrands at every node: the angular factor :math:`K = A/8` of
    :math:`dG/d\ln q = q^4 C K`, the ratio R = 4 L / A and the loss integral L, with
    :math:`A = b_T^2 (f^2 A_{re}\rho_{re} + g^2 A_{im}\rho_{im}) / ((1-\nu^2)\sigma_0)^2` and
    :math:`L = b_T\, g\, L \rho_L / ((1-\nu^2)\sigma_0)` (:math:`\rho = 1` for an isotropic PSD,
    :func:`shape_factors` for an anisotropic one; C is then its angular mean).

    Parameters
    ----------
    lq10 : ndarray (n_q,)
        log10 q.
    lw_speed : float
        log10 of the sliding speed, m/s (the reduced frequency at a node is q v a_T).
    q4C : ndarray (n_q,)
        q^4 C(q), 1.
    shift, vshift : ndarray (n_q,)
        log10 a_T and ln b_T at every node, relative to the table temperature.
    f, g : ndarray (n_q,)
        Strain factors on E' and E'' at every node.
    angular : AngularTables
        The angular integrals at the table temperature.
    shape : AngularShape
        The angular shape of the PSD (no basis functions: isotropic).
    p : int
        The problem (row of ``shape.direction``; unused for an isotropic PSD).
    scale : float
        1 / ((1 - nu^2) sigma0), 1/Pa.
    K, dG, R, loss : ndarray (n_q,)
        Filled with K, dG/d ln q, R and L (all dimensionless).
    """
    nq = lq10.shape[0]
    shaped = shape.weights.shape[2] > 0
    for iq in range(nq):
        lw = lq10[iq] + lw_speed + shift[iq]
        are, aim, ll = angular_at(lw, angular)
        if shaped:
            r_re, r_im, r_l = shape_factors(p, iq, (lw - angular.lw0) * angular.inv_dlw, shape)
            are *= r_re
            aim *= r_im
            ll *= r_l
        b = math.exp(vshift[iq])
        fi = f[iq]
        gi = g[iq]
        A = b * b * (fi * fi * are + gi * gi * aim) * scale * scale
        Lq = b * gi * ll * scale
        K[iq] = 0.125 * A
        dG[iq] = q4C[iq] * K[iq]
        R[iq] = 4.0 * Lq / A
        loss[iq] = Lq


@njit(cache=True)
def contact_and_friction(iv, nodes, rule, law, K, out):
    """Given G, R and the loss of speed ``iv`` in ``out``: P(q), d mu/d ln q, the cumulative friction and the
    excited-layer numerator of that speed.

    Parameters
    ----------
    iv : int
        The speed (row of ``out``).
    nodes : Nodes
        The wavevector nodes.
    rule : QuadratureRule
        The quadrature on the nodes.
    law : ContactLaw
        The contact law.
    K : ndarray (n_q,)
        The angular factor A / 8 at the nodes, 1.
    out : Outputs
        Read: ``G``, ``ratio``, ``loss`` of row iv; filled: ``P``, ``dmu``, ``cum`` and ``layer`` of row iv.
    """
    nq = nodes.q.shape[0]
    G = out.G[iv]
    for iq in range(nq):
        P = area(G[iq], law)
        out.P[iv, iq] = P
        out.dmu[iv, iq] = 0.5 * nodes.q4C[iq] * _weight_of_area(P, law) * out.loss[iv, iq]
    out.layer[iv] = friction_cumulative(G, K, out.ratio[iv], nodes.q, rule, law, out.cum[iv])


@njit(cache=True)
def _solve_speed(iv, nodes, rule, speeds, angular, shape, law, coarse, coarse_rule, coarser, coarser_rule, out,
                 mu_coarse, mu_coarser, work):
    """One speed at its background temperature: G(q), P(q), d mu/d ln q and the cumulative hysteresis friction
    on the nodes, and the friction on the two sub-grids of the error estimate.

    Parameters
    ----------
    iv : int
        The speed (row of ``speeds`` and ``out``).
    nodes : Nodes
        The wavevector nodes.
    rule : QuadratureRule
        The quadrature on the nodes.
    speeds : SpeedFactors
        Speeds, stress scales and modulus factors.
    angular : AngularTables
        The angular integrals at the table temperature.
    shape : AngularShape
        The angular shape of the PSD (no basis functions: isotropic; then a problem is a speed).
    law : ContactLaw
        The contact law.
    coarse : ndarray of int64 (m,)
        Every other node (indices, with the last node); empty: mu alone, no sub-grids.
    coarse_rule : QuadratureRule
        The quadrature on ``coarse``.
    coarser : ndarray of int64 (m',)
        Every fourth node (indices, with the last node).
    coarser_rule : QuadratureRule
        The quadrature on ``coarser``.
    out : Outputs
        Row iv is filled.
    mu_coarse, mu_coarser : ndarray (n_speed,)
        Element iv is filled with mu on ``coarse`` and on ``coarser`` (left alone without sub-grids).
    work : ndarray (6, n_q)
        Work rows (borrowed, :func:`_friction_all`): K, then the sub-grids' (:func:`_coarse_mu`).
    """
    nq = nodes.q.shape[0]
    K = work[0]
    scale_factors(nodes.lq10, speeds.lv10[iv], nodes.q4C, speeds.shift[iv], speeds.vshift[iv], speeds.f[iv],
                  speeds.g[iv], angular, shape, iv, speeds.scale[iv], K, out.dG[iv], out.ratio[iv], out.loss[iv])
    cumulative_weighted(K, rule, out.G[iv])
    contact_and_friction(iv, nodes, rule, law, K, out)
    R = out.ratio[iv]
    out.mu[iv] = out.cum[iv, nq - 1]
    if coarse.shape[0] > 0:
        mu_coarse[iv] = _coarse_mu(nodes.q, K, R, law, coarse, coarse_rule, work)
        mu_coarser[iv] = _coarse_mu(nodes.q, K, R, law, coarser, coarser_rule, work)


@njit(cache=True)
def _coarse_mu(q, K, R, law, index, rule, work):
    """The hysteresis friction on a sub-grid of the nodes: the same rules with a larger step.

    Parameters
    ----------
    q : ndarray (n_q,)
        The nodes, rad/m.
    K : ndarray (n_q,)
        The angular factor A / 8 at the nodes, 1.
    R : ndarray (n_q,)
        The ratio 4 L / A at the nodes, 1.
    law : ContactLaw
        The contact law.
    index : ndarray of int64 (m,)
        The nodes of the sub-grid.
    rule : QuadratureRule
        The quadrature on the sub-grid.
    work : ndarray (6, n_q)
        Rows 1-5 hold the sub-grid's q, K, R, G and cumulative friction (row 0, K on the nodes, is left alone).

    Returns
    -------
    float
        mu on the sub-grid.
    """
    idx = index
    m = idx.shape[0]
    qc = work[1, :m]
    Kc = work[2, :m]
    Rc = work[3, :m]
    for k in range(m):
        qc[k] = q[idx[k]]
        Kc[k] = K[idx[k]]
        Rc[k] = R[idx[k]]
    Gc = work[4, :m]
    cumulative_weighted(Kc, rule, Gc)
    cc = work[5, :m]
    friction_cumulative(Gc, Kc, Rc, qc, rule, law, cc)
    return cc[m - 1]


def _friction_all(nodes, rule, speeds, angular, shape, law, coarse, coarse_rule, coarser, coarser_rule, out, mu_coarse,
                  mu_coarser, first, stride):
    """Hysteresis friction and contact area of the speeds ``first, first + stride, ...`` at their background
    temperature (see :func:`_solve_speed`): one thread's share (:func:`persson.engine.jit.threaded`).

    Parameters
    ----------
    nodes : Nodes
        The wavevector nodes.
    rule : QuadratureRule
        The quadrature on the nodes.
    speeds : SpeedFactors
        Speeds, stress scales and modulus factors.
    angular : AngularTables
        The angular integrals at the table temperature.
    shape : AngularShape
        The angular shape of the PSD (no basis functions: isotropic; then a problem is a speed).
    law : ContactLaw
        The contact law.
    coarse : ndarray of int64 (m,)
        Every other node (indices, with the last node); empty: mu alone, no sub-grids.
    coarse_rule : QuadratureRule
        The quadrature on ``coarse``.
    coarser : ndarray of int64 (m',)
        Every fourth node (indices, with the last node).
    coarser_rule : QuadratureRule
        The quadrature on ``coarser``.
    out : Outputs
        Filled for every speed.
    mu_coarse, mu_coarser : ndarray (n_speed,)
        Filled with mu on ``coarse`` and on ``coarser`` (left alone without sub-grids).
    first : int
        The first speed of this share.
    stride : int
        Step between the speeds of this share (the number of shares).

    Returns
    -------
    int
        The size of the share's work array, allocated once here and handed to every speed as a borrowed view
        (:mod:`persson.engine.borrow`: numba counted the references of the arrays a speed allocated with an atomic
        operation at every interval of the quadrature, 15 % of the kernel's time); reading it after the loop keeps
        it alive until every speed is done.
    """
    (nodes, rule, speeds, angular, shape, law, coarse, coarse_rule, coarser, coarser_rule, out, mu_coarse,
     mu_coarser) = borrowed((nodes, rule, speeds, angular, shape, law, coarse, coarse_rule, coarser, coarser_rule,
                             out, mu_coarse, mu_coarser))
    work = np.empty((6, nodes.q.shape[0]))
    lent = borrowed(work)
    for iv in range(first, speeds.lv10.shape[0], stride):
        _solve_speed(iv, nodes, rule, speeds, angular, shape, law, coarse, coarse_rule, coarser, coarser_rule, out,
                     mu_coarse, mu_coarser, lent)
    return work.size


#: Hysteresis friction and contact area of a share of the speeds (see :func:`_friction_all`); releases the GIL, so
#: that :func:`persson.engine.jit.threaded` runs the shares on several threads.
friction_kernel = njit(cache=True, nogil=True)(_friction_all)


# ==================================================================================================== flash temperature
# The temperature at scale q (Persson, J. Phys.: Condens. Matter 18, 7789 (2006)):
#   T_q = T0 + int_{q0}^{q} dq' g(q, q') f(q') = T0 + v sigma0 / (rho c_p P(q_m)) int_0^{G(q)} g(q, q'(G)) 2 q' R P dG
# since f dq' = v sigma0 / (rho c_p) P / P(q_m) L q'^4 C dq' and q'^4 C dq' = 8 q' dG / A (g the heat kernel,
# heat_kernel below). The weight P dG is integrated exactly on each interval (interval_node_weights, kind 1)
# against the quadratic in G of g(q, q') 2 q' R, as the friction integral is. The modulus at each scale is taken
# at that scale's temperature, so T_q is a fixed point, found per speed by _flash_speed in named steps: the
# heat-kernel matrix (heat_matrix), the integrands at a temperature profile (integrands_at), the temperature that
# profile's heat gives (heated_temperature), and the acceleration of the iteration (_anderson_step; _aitken and
# _relax_step where the mixing fails).
#: Smallest relaxation factor of the flash iteration (Aitken's factor is clamped to [_MIN_RELAX, 1]).
_MIN_RELAX = 1e-4
#: Fixed relaxation factor of the third start of the flash iteration (Krasnosel'skii-Mann, see :func:`_flash_speed`).
_MANN_RELAX = 0.5


def _flash_all(nodes, rule, speeds, angular, shape, law, temperature, heat, iteration, out, T_out, it_out, res_out,
               first, stride):
    """The self-consistent flash temperature and the friction of the speeds ``first, first + stride, ...`` (see
    :func:`_flash_speed`): one thread's share (:func:`persson.engine.jit.threaded`).

    Parameters
    ----------
    nodes : Nodes
        The wavevector nodes.
    rule : QuadratureRule
        The quadrature on the nodes.
    speeds : FlashSpeeds
        Speeds, stress scales, background temperatures and starting profiles.
    angular : AngularTables
        The angular integrals at the table temperature.
    shape : AngularShape
        The angular shape of the PSD (no basis functions: isotropic; then a problem is a speed).
    law : ContactLaw
        The contact law.
    temperature : TemperatureTables
        Shift and strain-factor tables.
    heat : HeatSource
        The heat kernel and source.
    iteration : FixedPoint
        Tolerance and iteration limit.
    out : Outputs
        Filled for every speed.
    T_out : ndarray (n_speed, n_q)
        Filled with the temperature at every scale, deg C.
    it_out : ndarray of int64 (n_speed,)
        Filled with the iterations used.
    res_out : ndarray (n_speed,)
        Filled with the last max |T_new - T|, K.
    first : int
        The first speed of this share.
    stride : int
        Step between the speeds of this share (the number of shares).

    Returns
    -------
    int
        The total size of the share's work arrays, allocated once here and handed to every speed as borrowed views
        (:mod:`persson.engine.borrow`: numba counted the references of the arrays a speed allocated with an atomic
        operation at every step of the iteration it passed them on at); reading them after the loop keeps them alive
        until every speed is done.
    """
    (nodes, rule, speeds, angular, shape, law, temperature, heat, iteration, out, T_out, it_out,
     res_out) = borrowed((nodes, rule, speeds, angular, shape, law, temperature, heat, iteration, out, T_out, it_out,
                          res_out))
    nq = nodes.q.shape[0]
    vectors = np.empty((5, nq))   # the profile, the map's image, K, the last residual, the previous profile
    H = np.empty((nq, nq))
    factors = np.empty((4, nq))
    nodes_first = np.empty(nq, dtype=np.int64)
    weights = np.empty((nq, 3))
    history = np.empty((2, _ANDERSON_DEPTH, nq))
    lent = borrowed((H, vectors[0], vectors[1], vectors[2], factors, nodes_first, weights, vectors[3], vectors[4],
                     history[0], history[1]))
    for iv in range(first, speeds.lv10.shape[0], stride):
        _flash_speed(iv, nodes, rule, speeds, angular, shape, law, temperature, heat, iteration, out, T_out, it_out,
                     res_out, lent)
    return vectors.size + H.size + factors.size + nodes_first.size + weights.size + history.size


#: Flash-temperature solver for a share of the speeds (see :func:`_flash_all`); releases the GIL, so that
#: :func:`persson.engine.jit.threaded` runs the shares on several threads.
flash_kernel = njit(cache=True, nogil=True)(_flash_all)


@njit(cache=True)
def _flash_speed(iv, nodes, rule, speeds, angular, shape, law, temperature, heat, iteration, out, T_out, it_out,
                 res_out, work):
    """Self-consistent flash temperature for one speed on the nodes.

    Fixed-point iteration from the starting profile, converged when max |T_new - T| < ``iteration.tol``,
    accelerated by Anderson mixing over the last ``_ANDERSON_DEPTH`` steps (D. G. Anderson, J. ACM 12, 547 (1965);
    H. F. Walker and P. Ni, SIAM J. Numer. Anal. 49, 1715 (2011); :func:`_anderson_step`). Where that fails
    within ``iteration.max_iter`` iterations, again from T0 with Aitken's dynamic relaxation (B. M. Irons and
    R. C. Tuck, Int. J. Numer. Meth. Eng. 1, 275 (1969)), and where that fails too, a third time from T0 with the
    fixed relaxation T <- (T + g(T)) / 2 (the Krasnosel'skii-Mann iteration: W. R. Mann, Proc. Am. Math. Soc. 4,
    506 (1953); M. A. Krasnosel'skii, Uspekhi Mat. Nauk 10, 123 (1955)). Both accelerations can stall near a
    near-fixed point (a "ghost" of a fold, where the residual has a small, non-zero minimum and the Jacobian an
    eigenvalue close to 1), and Aitken's factor then shrinks towards its floor; the half step, which converges
    wherever the Jacobian's eigenvalues lie in the disc |lambda + 1| < 2 (real ones above -3), keeps moving
    through it. The fixed point, and so the result to within the tolerance, does not depend on the
    acceleration: over the regime of ``benchmarks/accuracy.py`` the errors are those of the under-relaxed
    iteration it replaced, which took about 1.5 times as many iterations.

    Parameters
    ----------
    iv : int
        The speed (row of ``speeds``, ``out`` and ``T_out``).
    nodes : Nodes
        The wavevector nodes.
    rule : QuadratureRule
        The quadrature on the nodes.
    speeds : FlashSpeeds
        Speeds, stress scales, background temperatures and starting profiles.
    angular : AngularTables
        The angular integrals at the table temperature.
    shape : AngularShape
        The angular shape of the PSD (no basis functions: isotropic; then a problem is a speed).
    law : ContactLaw
        The contact law.
    temperature : TemperatureTables
        Shift and strain-factor tables.
    heat : HeatSource
        The heat kernel and source.
    iteration : FixedPoint
        Tolerance and iteration limit.
    out : Outputs
        Row iv is filled.
    T_out : ndarray (n_speed, n_q)
        Row iv is filled with the temperature profile, deg C.
    it_out : ndarray of int64 (n_speed,)
        Element iv is filled with the iterations used.
    res_out : ndarray (n_speed,)
        Element iv is filled with max |g(T) - T|, K: at convergence that of the last iterate (the profile
        returned is g of it); otherwise that of the profile returned itself (one more evaluation of the map, no
        step taken), so that the residual reported with an unconverged speed belongs to its profile.
    work : tuple of ndarray
        Work arrays of the speed, borrowed (:func:`_flash_all`): the heat matrix (n_q, n_q), the profile and the
        map's image, K, the integrands' factors (4, n_q), the node weights' first nodes and weights (n_q, 3), the
        last residual, the previous profile and the Anderson history (two of (depth, n_q)); set here for each
        speed where the iteration reads them before it writes them.
    """
    nq = nodes.q.shape[0]
    max_iter = iteration.max_iter
    T0 = speeds.T0[iv]
    H, T, T_new, K, factors, first, weights, r_prev, T_prev, dT, dR = work
    _heat_matrix_into(nodes.q, heat.erfcx[iv], heat.S1, heat.S2, heat.a_t0[iv], heat.D, H)
    T[:] = speeds.T_start[iv]
    r_prev[:] = 0.0
    dT[:] = 0.0
    dR[:] = 0.0
    # steps in the Anderson history; -1: no previous step to difference against (an int64, not the literal -1:
    # numba would compile _anderson_step once more for the literal's own type)
    n_hist = np.int64(-1)
    relax = 1.0
    res = 0.0
    it = 0
    for it in range(1, 3 * max_iter + 1):
        if it == max_iter + 1 or it == 2 * max_iter + 1:  # the previous start failed: start again from T0
            for i in range(nq):
                T[i] = T0
            relax = 1.0 if it == max_iter + 1 else _MANN_RELAX
        integrands_at(iv, T, nodes, rule, speeds, angular, shape, temperature, factors, K, out)
        res = _heat_balance(iv, T, T0, K, nodes, rule, law, speeds, heat, H, out, first, weights, T_new)
        if res < iteration.tol:
            for i in range(nq):
                T[i] = T_new[i]
            break
        if it <= max_iter:
            # undamped: a damping factor cut at each growth of the residual (tried) stalls the mixing on the
            # period-2 oscillation of a hot contact (a cold profile heats by hundreds of K, a hot one barely)
            n_hist = _anderson_step(T_new, T, T_prev, r_prev, dT, dR, n_hist)
            continue
        if max_iter + 1 < it <= 2 * max_iter:
            relax = _aitken(T_new, T, r_prev, relax)
        _relax_step(T_new, T, r_prev, relax)
    for i in range(nq):
        T_out[iv, i] = T[i]
    integrands_at(iv, T, nodes, rule, speeds, angular, shape, temperature, factors, K, out)
    if not res < iteration.tol:
        # the loop's last residual belongs to the profile before its last step: the one returned gets its own
        res = _heat_balance(iv, T, T0, K, nodes, rule, law, speeds, heat, H, out, first, weights, T_new)
    contact_and_friction(iv, nodes, rule, law, K, out)
    out.mu[iv] = out.cum[iv, nq - 1]
    it_out[iv] = it
    res_out[iv] = res


@njit(cache=True)
def _heat_balance(iv, T, T0, K, nodes, rule, law, speeds, heat, H, out, first, weights, T_new):
    """One application of the flash temperature's map: T_new = g(T) from the integrands of speed ``iv`` at the
    profile ``T`` (:func:`integrands_at`, already in ``out`` and ``K``): the heat source normalised by the contact
    area of the macro-asperity regions, the node weights of P dG on every interval
    (:func:`interval_node_weights`, kind 1) into ``first`` and ``weights``, and :func:`heated_temperature`.

    Parameters
    ----------
    iv : int
        The speed.
    T : ndarray (n_q,)
        The temperature profile, deg C.
    T0 : float
        The background temperature, deg C.
    K : ndarray (n_q,)
        The angular factor at the nodes (from :func:`integrands_at` at ``T``).
    nodes : Nodes
        The wavevector nodes.
    rule : QuadratureRule
        The quadrature on the nodes.
    law : ContactLaw
        The contact law.
    speeds : FlashSpeeds
        Speeds, stress scales, background temperatures and starting profiles.
    heat : HeatSource
        The heat kernel and source.
    H : ndarray (n_q, n_q)
        The heat matrix (:func:`heat_matrix`).
    out : Outputs
        Row ``iv`` holds G and the friction ratio at ``T``.
    first : ndarray of int64 (n_q,)
        Filled with the first stencil node of each interval.
    weights : ndarray (n_q, 3)
        Filled with the node weights of each interval.
    T_new : ndarray (n_q,)
        Filled with g(T), deg C.

    Returns
    -------
    float
        max |g(T) - T| over the nodes, K.
    """
    G = out.G[iv]
    P_m = area(_at_G(G, nodes.x, heat.x_m), law)
    source = speeds.v[iv] * heat.heat_factor[iv] / P_m
    for k in range(G.shape[0] - 1):
        first[k], weights[k, 0], weights[k, 1], weights[k, 2] = interval_node_weights(G, K, k, rule, law, 1)
    return heated_temperature(T, T0, source, H, out.ratio[iv], first, weights, T_new)


@njit(cache=True)
def heat_matrix(q, erfcx_q, S1, S2, a_t0, D):
    """g(q_i, q_j) 2 q_j for the nodes any interval below q_i can reach (j <= i + 1), from the speed-independent
    partial-fraction factors; near-diagonal pairs (S1 = S2 = 0) by the closed form of
    :func:`heat_kernel`.

    Parameters
    ----------
    q : ndarray (n_q,)
        The nodes, rad/m.
    erfcx_q : ndarray (n_q,)
        erfcx(2 q sqrt(a_t0)) at the nodes.
    S1, S2 : ndarray (n_q, n_q)
        The partial-fraction factors (:func:`heat_kernel_factors`).
    a_t0 : float
        D t0, m^2.
    D : float
        Thermal diffusivity, m^2/s.

    Returns
    -------
    ndarray (n_q, n_q)
        g(q_i, q_j) 2 q_j, s/m; zero for j > i + 1.
    """
    nq = q.shape[0]
    H = np.empty((nq, nq))
    _heat_matrix_into(q, erfcx_q, S1, S2, a_t0, D, H)
    return H


@njit(cache=True)
def _heat_matrix_into(q, erfcx_q, S1, S2, a_t0, D, H):
    """:func:`heat_matrix` written into ``H``, every element (zeros above the first superdiagonal).

    Parameters
    ----------
    q, erfcx_q, S1, S2, a_t0, D
        As for :func:`heat_matrix`.
    H : ndarray (n_q, n_q)
        Filled with the matrix.
    """
    nq = q.shape[0]
    H[:, :] = 0.0
    c0 = 2.0 / math.pi * math.sqrt(math.pi * a_t0) / D
    for i in range(nq):
        for j in range(min(i + 2, nq)):
            if S1[i, j] == 0.0 and S2[i, j] == 0.0:
                H[i, j] = heat_kernel(q[i], q[j], a_t0, D, erfcx_q[i], erfcx_q[j]) * 2.0 * q[j]
            else:
                H[i, j] = c0 + ((1.0 - erfcx_q[j]) * S1[i, j] + (1.0 - erfcx_q[i]) * S2[i, j]) / D


@njit(cache=True)
def integrands_at(iv, T, nodes, rule, speeds, angular, shape, temperature, factors, K, out):
    """The integrands of speed ``iv`` with the modulus of every scale at that scale's temperature: K, dG/d ln q,
    R and the loss at the nodes, and G(q).

    Parameters
    ----------
    iv : int
        The speed (row of ``speeds`` and ``out``).
    T : ndarray (n_q,)
        The temperature profile, deg C.
    nodes : Nodes
        The wavevector nodes.
    rule : QuadratureRule
        The quadrature on the nodes.
    speeds : FlashSpeeds
        Speeds and stress scales.
    angular : AngularTables
        The angular integrals at the table temperature.
    shape : AngularShape
        The angular shape of the PSD (no basis functions: isotropic).
    temperature : TemperatureTables
        Shift and strain-factor tables.
    factors : ndarray (4, n_q)
        Scratch, filled with log10 a_T, ln b_T and the strain factors f, g at every node.
    K : ndarray (n_q,)
        Filled with the angular factor A / 8.
    out : Outputs
        Filled: ``dG``, ``ratio``, ``loss`` and ``G`` of row iv.
    """
    _temperature_factors(T, temperature, factors[0], factors[1], factors[2], factors[3])
    scale_factors(nodes.lq10, speeds.lv10[iv], nodes.q4C, factors[0], factors[1], factors[2], factors[3], angular,
                  shape, iv, speeds.scale[iv], K, out.dG[iv], out.ratio[iv], out.loss[iv])
    cumulative_weighted(K, rule, out.G[iv])


@njit(cache=True)
def heated_temperature(T, T0, source, H, R, first, weights, T_new):
    """One application of the fixed-point map: the temperature at every node from the heat the integrands of
    ``T`` produce at the scales below it.

    Parameters
    ----------
    T : ndarray (n_q,)
        The current profile, deg C.
    T0 : float
        Background temperature, deg C.
    source : float
        v sigma0 / (rho c_p P(q_m)), K m/s.
    H : ndarray (n_q, n_q)
        g(q_i, q_j) 2 q_j (:func:`heat_matrix`).
    R : ndarray (n_q,)
        The ratio 4 L / A at the nodes.
    first : ndarray of int64 (n_q,)
        First stencil node of every interval (:func:`interval_node_weights`).
    weights : ndarray (n_q, 3)
        The weights of P dG on every interval at its three stencil nodes.
    T_new : ndarray (n_q,)
        Filled with the new profile, deg C.

    Returns
    -------
    float
        max |T_new - T| over the nodes, K.
    """
    nq = T.shape[0]
    res = 0.0
    # the interval weights times R once (not at every node), and two partial sums (one waits on every addition)
    c = np.empty((nq, 3))
    for k in range(nq - 1):     # the intervals (row nq - 1 of ``first`` and ``weights`` is not one)
        a = first[k]
        c[k, 0] = weights[k, 0] * R[a]
        c[k, 1] = weights[k, 1] * R[a + 1]
        c[k, 2] = weights[k, 2] * R[a + 2]
    for i in range(nq):
        acc0 = 0.0
        acc1 = 0.0
        Hi = H[i]
        k = 0
        while k + 1 < i:
            a = first[k]
            b = first[k + 1]
            acc0 += c[k, 0] * Hi[a] + c[k, 1] * Hi[a + 1] + c[k, 2] * Hi[a + 2]
            acc1 += c[k + 1, 0] * Hi[b] + c[k + 1, 1] * Hi[b + 1] + c[k + 1, 2] * Hi[b + 2]
            k += 2
        if k < i:
            a = first[k]
            acc0 += c[k, 0] * Hi[a] + c[k, 1] * Hi[a + 1] + c[k, 2] * Hi[a + 2]
        T_new[i] = T0 + source * (acc0 + acc1)
        d = abs(T_new[i] - T[i])
        if d > res:
            res = d
    return res


@njit(cache=True)
def _at_G(G, x, xm):
    """G at ln q = ``xm`` by the quadratic through the three nearest nodes (G is smooth in ln q).

    Parameters
    ----------
    G : ndarray (n_q,)
        G at the nodes.
    x : ndarray (n_q,)
        ln q of the nodes.
    xm : float
        ln q where G is wanted (clamped to the nodes' range).

    Returns
    -------
    float
    """
    n = x.shape[0]
    if xm <= x[0]:
        return G[0]
    if xm >= x[n - 1]:
        return G[n - 1]
    i = 0
    while i < n - 2 and x[i + 1] < xm:
        i += 1
    if n < 3:
        t = (xm - x[i]) / (x[i + 1] - x[i])
        return G[i] + t * (G[i + 1] - G[i])
    a = i if i + 2 < n else i - 1
    x0, x1, x2 = x[a], x[a + 1], x[a + 2]
    return (G[a] * (xm - x1) * (xm - x2) / ((x0 - x1) * (x0 - x2))
            + G[a + 1] * (xm - x0) * (xm - x2) / ((x1 - x0) * (x1 - x2))
            + G[a + 2] * (xm - x0) * (xm - x1) / ((x2 - x0) * (x2 - x1)))


@njit(cache=True)
def _aitken(T_new, T, r_prev, relax):
    """Aitken's dynamic relaxation factor (Irons & Tuck 1969): the factor that cancels the dominant mode of the
    last two residual vectors, clamped to [_MIN_RELAX, 1]. It rescues a hot contact whose map is strongly
    non-contractive (a cold profile heats to 10^4 K, a hot one barely heats: a period-2 oscillation whose residual
    hardly changes, so a residual-growth rule keeps the factor near 1).

    Parameters
    ----------
    T_new : ndarray (n_q,)
        The map's image of ``T``, deg C.
    T : ndarray (n_q,)
        The current profile, deg C.
    r_prev : ndarray (n_q,)
        The previous residual T_new - T, K.
    relax : float
        The previous factor.

    Returns
    -------
    float
        The new factor.
    """
    num = 0.0
    den = 0.0
    for i in range(T.shape[0]):
        dr = (T_new[i] - T[i]) - r_prev[i]
        num += r_prev[i] * dr
        den += dr * dr
    if den > 0.0:
        return min(1.0, max(_MIN_RELAX, -relax * num / den))
    return relax


#: Steps the Anderson mixing of the flash iteration remembers (:func:`_anderson_step`).
_ANDERSON_DEPTH = 3


@njit(cache=True)
def _anderson_step(T_new, T, T_prev, r_prev, dT, dR, n_hist):
    r"""One step of Anderson mixing (type II, Walker & Ni 2011) for the fixed point T = g(T).

    With the residual :math:`r_k = g(T_k) - T_k` and the columns :math:`\Delta T_i = T_{i+1} - T_i`,
    :math:`\Delta r_i = r_{i+1} - r_i` of the last ``_ANDERSON_DEPTH`` steps,

    .. math:: T_{k+1} = T_k + r_k - (\Delta T + \Delta r)\,\gamma,\qquad
              \gamma = \arg\min_\gamma \lVert r_k - \Delta r\,\gamma \rVert_2,

    undamped (mixing factor 1); without history the plain step :math:`T_k + r_k`. The least squares are solved by
    the normal equations with a relative ridge of 1e-10 on their diagonal (:func:`_solve_small`); a singular
    system falls back to the plain step. On a linear map the iteration is GMRES in disguise (Walker & Ni 2011):
    with a history as long as the dimension it lands on the fixed point.

    Parameters
    ----------
    T_new : ndarray (n_q,)
        The map's image g(T) of ``T``, deg C.
    T : ndarray (n_q,)
        The current profile, replaced by the next one, deg C.
    T_prev : ndarray (n_q,)
        The previous profile (read when ``n_hist`` >= 0), replaced by ``T``, deg C.
    r_prev : ndarray (n_q,)
        The previous residual (read when ``n_hist`` >= 0), replaced by T_new - T, K.
    dT, dR : ndarray (_ANDERSON_DEPTH, n_q)
        Ring buffers of the differences of profiles and of residuals (row ``i % _ANDERSON_DEPTH`` is step i).
    n_hist : int
        Steps in the history; -1 on the first step (no previous step to difference against).

    Returns
    -------
    int
        The new ``n_hist``.
    """
    nq = T.shape[0]
    m = _ANDERSON_DEPTH
    if n_hist >= 0:
        row = n_hist % m
        for i in range(nq):
            dT[row, i] = T[i] - T_prev[i]
            dR[row, i] = (T_new[i] - T[i]) - r_prev[i]
        n_hist += 1
    else:
        n_hist = 0
    k = min(n_hist, m)
    gamma = np.zeros(k)
    if k > 0:
        A = np.zeros((k, k))
        b = np.zeros(k)
        for a in range(k):
            for c in range(a, k):
                v = 0.0
                for i in range(nq):
                    v += dR[a, i] * dR[c, i]
                A[a, c] = v
                A[c, a] = v
            v = 0.0
            for i in range(nq):
                v += dR[a, i] * (T_new[i] - T[i])
            b[a] = v
        trace = 0.0
        for a in range(k):
            trace += A[a, a]
        if trace > 0.0:
            for a in range(k):
                A[a, a] += 1e-10 * trace
            gamma = _solve_small(A, b)
    for i in range(nq):
        r = T_new[i] - T[i]
        step = r
        for a in range(k):
            step -= (dT[a, i] + dR[a, i]) * gamma[a]
        T_prev[i] = T[i]
        r_prev[i] = r
        T[i] = T[i] + step
    return n_hist


@njit(cache=True)
def _solve_small(A, b):
    """The solution of the small system A x = b by Gaussian elimination with partial pivoting; zeros when A is
    singular to working precision (where ``np.linalg.solve`` would raise inside a kernel running on a thread).

    Parameters
    ----------
    A : ndarray (k, k)
        The matrix (overwritten).
    b : ndarray (k,)
        The right-hand side (overwritten).

    Returns
    -------
    ndarray (k,)
    """
    k = b.shape[0]
    scale = 0.0
    for a in range(k):
        scale = max(scale, abs(A[a, a]))
    for col in range(k):
        piv = col
        for r in range(col + 1, k):
            if abs(A[r, col]) > abs(A[piv, col]):
                piv = r
        if not abs(A[piv, col]) > 1e-14 * scale:
            return np.zeros(k)
        if piv != col:
            for c in range(k):
                A[col, c], A[piv, c] = A[piv, c], A[col, c]
            b[col], b[piv] = b[piv], b[col]
        for r in range(col + 1, k):
            f = A[r, col] / A[col, col]
            for c in range(col, k):
                A[r, c] -= f * A[col, c]
            b[r] -= f * b[col]
    x = np.zeros(k)
    for a in range(k - 1, -1, -1):
        v = b[a]
        for c in range(a + 1, k):
            v -= A[a, c] * x[c]
        x[a] = v / A[a, a]
    return x


@njit(cache=True)
def _relax_step(T_new, T, r_prev, relax):
    """T += relax (T_new - T), keeping the residual T_new - T in ``r_prev``.

    Parameters
    ----------
    T_new : ndarray (n_q,)
        The map's image of ``T``, deg C.
    T : ndarray (n_q,)
        The current profile, updated in place, deg C.
    r_prev : ndarray (n_q,)
        Filled with the residual T_new - T, K.
    relax : float
        The relaxation factor, in (0, 1].
    """
    for i in range(T.shape[0]):
        r_prev[i] = T_new[i] - T[i]
        T[i] = T[i] + relax * r_prev[i]


@njit(cache=True)
def _temperature_factors(T, temperature, shift, vshift, f, g):
    """Shift, vertical shift and strain factors at the temperature of every node, interpolated linearly in the
    tables.

    Parameters
    ----------
    T : ndarray (n_q,)
        The temperature profile, deg C.
    temperature : TemperatureTables
        The tables.
    shift, vshift, f, g : ndarray (n_q,)
        Filled with log10 a_T, ln b_T (relative to the table temperature) and the strain factors on E', E''.
    """
    nq = T.shape[0]
    per_node = temperature.f.shape[0] == nq
    for i in range(nq):
        xT = (T[i] - temperature.T_lo) * temperature.inv_dT
        shift[i] = linear_at(temperature.shift, xT)
        vshift[i] = linear_at(temperature.vshift, xT)
        r = i if per_node else 0
        f[i] = linear_at(temperature.f[r], xT)
        g[i] = linear_at(temperature.g[r], xT)


# ==================================================================================================== heat kernel
@njit(cache=True)
def heat_kernel(qi, qj, a, D, ex_i, ex_j):
    r"""Closed form of Persson's heat kernel g(q_i, q_j), s (Persson, J. Phys.: Condens. Matter 18, 7789 (2006)).

    .. math::
        g(q, q') = \frac{1}{\pi}\int_0^\infty dk\, \frac{1 - e^{-D k^2 t_0}}{D k^2}
                   \frac{4q'}{k^2 + 4q'^2}\frac{4q^2}{k^2 + 4q^2}

    With :math:`\alpha = 2q'`, :math:`\beta = 2q`, :math:`a = D t_0` and partial fractions of
    :math:`1/(k^2 (k^2+\alpha^2)(k^2+\beta^2))`, using
    :math:`\int_0^\infty (1-e^{-ak^2})k^{-2} dk = \sqrt{\pi a}` and
    :math:`\int_0^\infty (1-e^{-ak^2})(k^2+c^2)^{-1} dk = \frac{\pi}{2c}(1 - \mathrm{erfcx}(c\sqrt a))`.
    For alpha = beta (the diagonal) the double pole gives
    :math:`\int_0^\infty (1-e^{-ak^2})(k^2+c^2)^{-2}dk = \frac{\pi}{4c^3}(1-\mathrm{erfcx}(x))
    + \frac{\pi\sqrt a}{4c^2}(2x\,\mathrm{erfcx}(x) - 2/\sqrt\pi)`, :math:`x = c\sqrt a`.

    Parameters
    ----------
    qi : float
        q, the scale where the temperature is taken, rad/m.
    qj : float
        q', the scale where the heat is produced, rad/m.
    a : float
        D t0, m^2 (t0 the contact time of a macro-asperity contact region).
    D : float
        Thermal diffusivity, m^2/s.
    ex_i, ex_j : float
        erfcx(2 q_i sqrt(a)) and erfcx(2 q_j sqrt(a)), precomputed (scipy.special.erfcx).

    Returns
    -------
    float
        g(q_i, q_j), s.
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


def heat_kernel_factors(q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""Speed-independent factors of :func:`heat_kernel`: with :math:`\alpha = 2q_j`, :math:`\beta = 2q_i`,

    .. math:: g(q_i, q_j)\, 2q_j = \frac1D\left[\frac{2}{\pi}\sqrt{\pi a} + (1 - \mathrm{erfcx}(\alpha\sqrt a))
              S_1 + (1 - \mathrm{erfcx}(\beta\sqrt a)) S_2\right],\quad
              S_1 = \frac{\beta^2\, 2q_j}{\alpha^2(\alpha^2 - \beta^2)},\
              S_2 = \frac{\alpha\, 2q_j}{\beta(\beta^2 - \alpha^2)}

    (the partial fractions of :func:`heat_kernel`); both are 0 where :math:`|\alpha - \beta| \le 10^{-5}\beta`, the
    pairs the kernel evaluates by the double-pole formula instead. Returns (S1, S2), shape (n, n), rows i.
    """
    al = 2.0 * q[None, :]
    be = 2.0 * q[:, None]
    near = np.abs(al - be) <= 1e-5 * be
    with np.errstate(divide="ignore", invalid="ignore"):
        S1 = np.where(near, 0.0, be * be * al / (al * al * (al * al - be * be)))
        S2 = np.where(near, 0.0, al * al / (be * (be * be - al * al)))
    return np.ascontiguousarray(S1), np.ascontiguousarray(S2)
