r"""numba kernels of the Persson solver. Thin wrappers in :mod:`persson.engine.model` prepare the arrays.

Three numerical ideas make the solver accurate from soft to glassy rubber:

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
   piece G is known at its ends and middle (the PSD integrated exactly, :func:`persson.engine.solver.quadrature_rule`),
   R is interpolated by the quadratic in G through those three points, and the weight :math:`S(P)P` is integrated
   exactly (Gauss-Legendre in :math:`s = \sqrt G` on geometric pieces, where :math:`2 s\, S P` is smooth and
   bounded), :func:`interval_node_weights`.

3. **A built-in error estimate.** Every speed is also integrated on the coarse grid of every other node and on
   the coarser grid of every fourth; the differences estimate the error of the fine result
   (:func:`persson.engine.solver._relative_error`). The flash temperature uses the coarse grid alone.

Grids: nodes ``x`` = ln q (any increasing sequence; third-order interval rule for the non-uniform spacing),
modulus tables uniform in log10 omega (``lw0``, ``inv_dlw``), holding ln A_re, ln A_im, ln L of the table
temperature. A temperature T enters through ``shift`` = log10 a_T(T) and ``vshift`` = ln b_T(T) relative to the
table temperature (time-temperature superposition: E(omega, T) = b_T E(omega a_T, T_table)); per-scale strain
factors f, g multiply E' and E'' (large-strain modulus).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

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
_LN10 = math.log(10.0)


# ==================================================================================================== tables
@njit(cache=True)
def angular_convolution(F, c, out):
    r"""out_j = sum_d c_d F_{j-d} with F clamped to F_0 below the table and to F_{n-1} above it.

    ``c`` holds the product-integration weights c_d for d = -1 .. len(c)-2 (``c[d + 1]``), see
    :func:`persson.engine.tabulate.convolution_weights`; weights past the end of ``c`` are zero.
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
    """4-point Lagrange interpolation of ``tab`` at fractional index ``x`` (clamped to the ends)."""
    n = tab.shape[0]
    if x <= 0.0:
        return tab[0]
    if x >= n - 1:
        return tab[n - 1]
    i = int(x)
    t = x - i
    im = i - 1 if i >= 1 else 0
    ip = i + 1
    ip2 = i + 2 if i + 2 < n else n - 1
    return (-t * (t - 1.0) * (t - 2.0) / 6.0 * tab[im] + (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0 * tab[i]
            - (t + 1.0) * t * (t - 2.0) / 2.0 * tab[ip] + (t + 1.0) * t * (t - 1.0) / 6.0 * tab[ip2])


@njit(cache=True)
def _linear(tab, x):
    """Linear interpolation of ``tab`` at fractional index ``x`` (clamped to the ends)."""
    n = tab.shape[0]
    if x <= 0.0:
        return tab[0]
    if x >= n - 1:
        return tab[n - 1]
    i = int(x)
    f = x - i
    return tab[i] + f * (tab[i + 1] - tab[i])


@njit(cache=True)
def angular_at(lw, lw0, inv_dlw, ln_are, ln_aim, ln_l):
    """(A_re, A_im, L) at log10 omega = ``lw`` from the log tables (cubic in log10 omega)."""
    x = (lw - lw0) * inv_dlw
    return math.exp(_cubic(ln_are, x)), math.exp(_cubic(ln_aim, x)), math.exp(_cubic(ln_l, x))


# ==================================================================================================== q rules
@njit(cache=True)
def cumulative_weighted(K, W, stencil, out):
    r"""Cumulative :math:`G(q_i) = \int_{x_0}^{x_i} c(x) K(x) dx` from product weights of the rough factor c.

    ``W[i, m]`` = :math:`\int_{x_i}^{x_{i+1}} \ell_m(x) c(x) dx`, with :math:`\ell_m` the Lagrange basis of the
    quadratic through the nodes ``stencil[i] + m`` (m = 0, 1, 2) and c = q^4 C(q) integrated exactly piece by
    piece between the PSD's own breakpoints (:func:`persson.engine.solver.quadrature_rule`); K (the smooth angular factor)
    is interpolated by that quadratic. Where that would decrease G (K varying wildly between nodes) the interval
    takes the mean of K at its ends times the exact integral of c.
    """
    n = K.shape[0]
    out[0] = 0.0
    for i in range(n - 1):
        a = stencil[i]
        inc = W[i, 0] * K[a] + W[i, 1] * K[a + 1] + W[i, 2] * K[a + 2]
        if inc < 0.0:
            inc = 0.5 * (K[i] + K[i + 1]) * (W[i, 0] + W[i, 1] + W[i, 2])
        out[i + 1] = out[i] + inc


@njit(cache=True)
def area(G, law):
    r"""Area of real contact P(G) of the contact law ``law`` = (gamma, ln P table, ln G of its first node,
    nodes per unit ln G): :math:`\mathrm{erf}(1/(2\sqrt G))` (Persson 2001) when the table is empty, else the
    corrected area of :mod:`persson.contact.corrections` (ln P linear in ln G between nodes; P = erf(...) = 1 to double
    precision below the table, P ~ G^(-1/2) past it)."""
    if G <= 0.0:
        return 1.0
    tab = law[1]
    n = tab.shape[0]
    if n == 0:
        return math.erf(0.5 / math.sqrt(G))
    lg = math.log(G)
    x = (lg - law[2]) * law[3]
    if x <= 0.0:
        return math.erf(0.5 / math.sqrt(G))
    if x >= n - 1:
        return math.exp(tab[n - 1] - 0.5 * (lg - (law[2] + (n - 1) / law[3])))
    i = int(x)
    f = x - i
    return math.exp(tab[i] + f * (tab[i + 1] - tab[i]))


@njit(cache=True)
def contact_weight(G, law, kind):
    """P(G) (``kind`` 1) or S(P) P with S = gamma + (1 - gamma) P^2 (``kind`` 0), gamma = ``law[0]``."""
    P = area(G, law)
    if kind == 1:
        return P
    return _weight_of_area(P, law)


@njit(cache=True)
def _weight_of_area(P, law):
    """S(P) P with S = gamma + (1 - gamma) P^2 (Persson's interpolation of the stress factor, gamma = ``law[0]``)."""
    gamma = law[0]
    return (gamma + (1.0 - gamma) * P * P) * P


@njit(cache=True)
def _interval_weights(Ga, Gb, G0, G1, G2, use_quadratic, law, kind):
    r"""Weights (w0, w1, w2) with :math:`\int_{G_a}^{G_b} R(G)\, w(G)\, dG = \sum_m w_m R(G_m)` exactly for the
    quadratic R through (G0, G1, G2) (or the linear R through G0, G1 when ``use_quadratic`` is False; then w2 = 0).

    The contact weight w (:func:`contact_weight`) is integrated by Gauss-Legendre in :math:`s = \sqrt G` on
    pieces [s, 2s] (and one piece [0, 0.05]): :math:`2 s\, w(s^2)` is smooth and bounded (it tends to 2 gamma
    / sqrt(pi) as G grows, since P ~ 1/sqrt(pi G)), so a few pieces cover any rise of G.
    """
    # moments M_k = int u^k w dG of u = G - G1 (the middle node: well conditioned), then the weights from the
    # Lagrange basis written in u; one pass with no division per Gauss point
    m0 = 0.0
    m1 = 0.0
    m2 = 0.0
    if not Gb > Ga:
        return 0.0, 0.0, 0.0
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
            wt = gw[k] * span * 2.0 * s * contact_weight(G, law, kind)
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


@njit(cache=True)
def _quadratic_ok(Ga, Gb, G0, G1, G2):
    """Quadratic interpolation in G is meaningful when the three G nodes are distinct and roughly evenly spaced
    (G close to proportional to ln q); else (a stretch where C ~ 0, a jump of the PSD) R is taken linear."""
    d1 = G1 - G0
    d2 = G2 - G1
    if not (d1 > 0.0 and d2 > 0.0):
        return False
    r = d2 / d1
    return 0.05 < r < 20.0


@njit(cache=True)
def interval_node_weights(G, K, i, quad, law, kind):
    r"""Node weights (first stencil node a, w0, w1, w2) of interval i:
    :math:`\int_{G_i}^{G_{i+1}} F\, w(G)\, dG \approx \sum_m w_m F_{a+m}` for a factor F smooth in ln q.

    The interval is cut at the PSD's breakpoints into pieces (``quad`` = (W, stencil, piece start, Lb, Wp) of
    :func:`persson.engine.solver.quadrature_rule`). On each piece G is known at its ends and middle from the partial
    PSD weights ``Wp`` (exact PSD, angular factor K quadratic in ln q), F there from its quadratic in ln q
    (basis values ``Lb``), and F w dG is integrated with F quadratic in G through those three points and the weight
    w exact (:func:`_interval_weights`). F is never interpolated across a kink of the PSD, where G(ln q) bends.
    """
    st = quad[1]
    pstart = quad[2]
    Lb = quad[3]
    Wp = quad[4]
    a = st[i]
    o0 = 0.0
    o1 = 0.0
    o2 = 0.0
    p0 = pstart[i]
    p1 = pstart[i + 1]
    for p in range(p0, p1):
        Gi = G[i]
        Glo = Gi if p == p0 else Gi + Wp[p, 0, 0] * K[a] + Wp[p, 0, 1] * K[a + 1] + Wp[p, 0, 2] * K[a + 2]
        Gmid = Gi + Wp[p, 1, 0] * K[a] + Wp[p, 1, 1] * K[a + 1] + Wp[p, 1, 2] * K[a + 2]
        Ghi = G[i + 1] if p == p1 - 1 else Gi + Wp[p, 2, 0] * K[a] + Wp[p, 2, 1] * K[a + 1] + Wp[p, 2, 2] * K[a + 2]
        if not Ghi > Glo:
            continue
        if Glo < Gmid < Ghi and _quadratic_ok(Glo, Ghi, Glo, Gmid, Ghi):
            w0, w1, w2 = _interval_weights(Glo, Ghi, Glo, Gmid, Ghi, True, law, kind)
        else:
            w0, w2, _ = _interval_weights(Glo, Ghi, Glo, Ghi, 0.0, False, law, kind)
            w1 = 0.0
        o0 += w0 * Lb[p, 0, 0] + w1 * Lb[p, 1, 0] + w2 * Lb[p, 2, 0]
        o1 += w0 * Lb[p, 0, 1] + w1 * Lb[p, 1, 1] + w2 * Lb[p, 2, 1]
        o2 += w0 * Lb[p, 0, 2] + w1 * Lb[p, 1, 2] + w2 * Lb[p, 2, 2]
    return a, o0, o1, o2


@njit(cache=True)
def friction_cumulative(G, K, R, q, quad, law, out):
    r"""Cumulative hysteresis friction :math:`\int_0^{G(q_i)} R\, S(P) P\, dG` at every node (``out``) and,
    returned, :math:`\int q^{-1} d\mu` over the whole range (the numerator of the excited-layer thickness),
    both with the node weights of :func:`interval_node_weights`."""
    n = G.shape[0]
    out[0] = 0.0
    layer = 0.0
    for i in range(n - 1):
        a, w0, w1, w2 = interval_node_weights(G, K, i, quad, law, 0)
        out[i + 1] = out[i] + w0 * R[a] + w1 * R[a + 1] + w2 * R[a + 2]
        layer += w0 * R[a] / q[a] + w1 * R[a + 1] / q[a + 1] + w2 * R[a + 2] / q[a + 2]
    return layer


# ==================================================================================================== friction
@njit(cache=True)
def _scales(iv, lq10, lv10, q4C, shift, vshift, fq, gq, lw0, inv_dlw, ln_are, ln_aim, ln_l, scale,
            K, gG, R, L):
    r"""Per node: the angular factor :math:`K = A/8` of the G integrand :math:`g = q^4 C K`, the ratio
    R = 4 L / A and the loss integral L, with :math:`A = b_T^2 (f^2 A_{re} + g^2 A_{im}) / ((1-\nu^2)\sigma_0)^2`
    and :math:`L = b_T\, g\, L / ((1-\nu^2)\sigma_0)` (``fq``, ``gq``: strain factors on E', E'')."""
    nq = lq10.shape[0]
    for iq in range(nq):
        are, aim, ll = angular_at(lq10[iq] + lv10[iv] + shift[iq], lw0, inv_dlw, ln_are, ln_aim, ln_l)
        b = math.exp(vshift[iq])
        f = fq[iq]
        g = gq[iq]
        A = b * b * (f * f * are + g * g * aim) * scale * scale
        Lq = b * g * ll * scale
        K[iq] = 0.125 * A
        gG[iq] = q4C[iq] * K[iq]
        R[iq] = 4.0 * Lq / A
        L[iq] = Lq


@njit(cache=True)
def _solve_speed(iv, q, lq10, lv10, q4C, quad, shift, vshift, fq, gq, lw0, inv_dlw, ln_are, ln_aim, ln_l, scale,
                 law, coarse, quad_c, coarser, quad_cc, G_out, P_out, dmu_out, cum_out, gG_out, R_out, L_out,
                 layer_out):
    """One speed: G(q), P(q), d mu/d ln q and the cumulative hysteresis friction on the nodes; returns
    (mu, mu on the coarse sub-grid ``coarse`` of node indices with its quadrature rule ``quad_c``, mu on the
    coarser sub-grid ``coarser`` with ``quad_cc``)."""
    nq = lq10.shape[0]
    gG = gG_out[iv]
    R = R_out[iv]
    K = np.empty(nq)
    _scales(iv, lq10, lv10, q4C, shift, vshift, fq, gq, lw0, inv_dlw, ln_are, ln_aim, ln_l, scale, K, gG, R,
            L_out[iv])
    G = G_out[iv]
    cumulative_weighted(K, quad[0], quad[1], G)
    for iq in range(nq):
        P = area(G[iq], law)
        P_out[iv, iq] = P
        dmu_out[iv, iq] = 0.5 * q4C[iq] * _weight_of_area(P, law) * L_out[iv, iq]
    layer_out[iv] = friction_cumulative(G, K, R, q, quad, law, cum_out[iv])
    return (cum_out[iv, nq - 1], _coarse_mu(q, K, R, law, coarse, quad_c),
            _coarse_mu(q, K, R, law, coarser, quad_cc))


@njit(cache=True)
def _coarse_mu(q, K, R, law, coarse, quad_c):
    """The hysteresis friction on the sub-grid ``coarse`` (node indices): same rules, a larger step."""
    m = coarse.shape[0]
    qc = np.empty(m)
    Kc = np.empty(m)
    Rc = np.empty(m)
    for k in range(m):
        qc[k] = q[coarse[k]]
        Kc[k] = K[coarse[k]]
        Rc[k] = R[coarse[k]]
    Gc = np.empty(m)
    cumulative_weighted(Kc, quad_c[0], quad_c[1], Gc)
    cc = np.empty(m)
    friction_cumulative(Gc, Kc, Rc, qc, quad_c, law, cc)
    return cc[m - 1]


def _friction_all(q, lq10, lv10, q4C, quad, shift, vshift, fq, gq, lw0, inv_dlw, ln_are, ln_aim, ln_l, scale,
                  law, coarse, quad_c, coarser, quad_cc, G_out, P_out, dmu_out, cum_out, gG_out, R_out, L_out,
                  layer_out, mu_out, mu_coarse, mu_coarser):
    for iv in prange(lv10.shape[0]):
        mu, mc, mcc = _solve_speed(iv, q, lq10, lv10, q4C, quad, shift[iv], vshift[iv], fq[iv], gq[iv], lw0,
                                   inv_dlw, ln_are, ln_aim, ln_l, scale[iv], law, coarse, quad_c, coarser, quad_cc,
                                   G_out, P_out, dmu_out, cum_out, gG_out, R_out, L_out, layer_out)
        mu_out[iv] = mu
        mu_coarse[iv] = mc
        mu_coarser[iv] = mcc


#: Hysteresis friction and contact area for every speed, in parallel over speeds (prange). Arguments: nodes
#: ``q`` and ``lq10`` = log10 q (n_q,), ``lv10`` (n_speed,), ``q4C`` = q^4 C(q) (n_q,), the quadrature rule
#: ``quad`` of :func:`persson.engine.solver.quadrature_rule`, ``shift`` and ``vshift`` (n_speed, n_q), strain factors
#: ``fq``, ``gq`` (n_speed, n_q), the log tables, ``scale`` = 1/((1-nu^2) sigma0) per speed, the contact law
#: (:func:`area`), the coarse
#: and coarser node indices with their quadrature rules, outputs (n_speed, n_q) and (n_speed,).
friction_parallel = njit(cache=True, parallel=True)(_friction_all)
#: The same on one thread, for calls with few speeds (no thread start-up).
friction_serial = njit(cache=True)(_friction_all)


# ==================================================================================================== flash
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
def _at_G(G, x, xm):
    """G at ln q = ``xm`` by the quadratic through the three nearest nodes (G is smooth in ln q)."""
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


@njit(cache=True)
def _flash_speed(iv, q, x, lq10, lv10, v, q4C, quad, lw0, inv_dlw, ln_are, ln_aim, ln_l, scale, law, T0, T_start,
                 T_lo, inv_dT, shift_tab, vshift_tab, f_tab, g_tab, EX, S1, S2, a_t0, D, heat_factor, x_m, tol,
                 max_iter, G_out, P_out, dmu_out, cum_out, gG_out, R_out, L_out, T_out, layer_out):
    r"""Self-consistent flash temperature for one speed on the nodes ``q``; returns (mu, iterations, residual).

    .. math::
        T_q = T_0 + \int_{q_0}^{q} dq'\, g(q, q') f(q')
            = T_0 + \frac{v\,\sigma_0}{\rho c_p P(q_m)} \int_0^{G(q)} g(q, q'(G))\, 2 q'\, R\, P\, dG

    since :math:`f\,dq' = \frac{v \sigma_0}{\rho c_p}\frac{P}{P(q_m)} L\, q'^4 C\, dq'` and
    :math:`q'^4 C dq' = 8 q' dG / A`. The weight P dG is integrated exactly on each interval
    (:func:`interval_weights`, ``kind`` 1) against the quadratic in G of :math:`g(q, q') 2 q' R`.
    Fixed-point iteration from ``T_start`` (T0 at every node, or a solution of the same problem on other nodes),
    converged when max |T_new - T| < ``tol``: under-relaxed by a factor that halves whenever the residual grows;
    where that fails within ``max_iter`` iterations, again from T0 with Aitken's dynamic relaxation
    (B. M. Irons and R. C. Tuck, Int. J. Numer. Meth. Eng. 1, 275 (1969)).
    """
    nq = q.shape[0]
    # g(q_i, q_j) 2 q_j for the nodes any interval below q_i can reach (j <= i + 1), from the speed-independent
    # partial-fraction factors S1, S2 (:func:`heat_kernel_factors`); near-diagonal pairs by the closed form
    H = np.zeros((nq, nq))
    c0 = 2.0 / math.pi * math.sqrt(math.pi * a_t0) / D
    for i in range(nq):
        for j in range(min(i + 2, nq)):
            if S1[i, j] == 0.0 and S2[i, j] == 0.0:
                H[i, j] = heat_kernel(q[i], q[j], a_t0, D, EX[i], EX[j]) * 2.0 * q[j]
            else:
                H[i, j] = c0 + ((1.0 - EX[j]) * S1[i, j] + (1.0 - EX[i]) * S2[i, j]) / D
    T = T_start.copy()
    Tn = np.empty(nq)
    shift = np.empty(nq)
    vshift = np.empty(nq)
    fq = np.empty(nq)
    gq = np.empty(nq)
    wts = np.empty((nq, 4))
    K = np.empty(nq)
    G = G_out[iv]
    R = R_out[iv]
    r_prev = np.zeros(nq)
    relax = 1.0
    res_prev = 1e300
    res = 0.0
    it = 0
    for it in range(1, 2 * max_iter + 1):
        if it == max_iter + 1:  # the residual-growth rule failed: start again with Aitken's relaxation
            for i in range(nq):
                T[i] = T0
            relax = 1.0
        _temperature_factors(T, T_lo, inv_dT, shift_tab, vshift_tab, f_tab, g_tab, shift, vshift, fq, gq)
        _scales(iv, lq10, lv10, q4C, shift, vshift, fq, gq, lw0, inv_dlw, ln_are, ln_aim, ln_l, scale,
                K, gG_out[iv], R, L_out[iv])
        cumulative_weighted(K, quad[0], quad[1], G)
        Gm = _at_G(G, x, x_m)
        Pm = area(Gm, law)
        pre = v * heat_factor / Pm
        for k in range(nq - 1):
            a, w0, w1, w2 = interval_node_weights(G, K, k, quad, law, 1)
            wts[k, 0] = a
            wts[k, 1] = w0
            wts[k, 2] = w1
            wts[k, 3] = w2
        res = 0.0
        for i in range(nq):
            acc = 0.0
            for k in range(i):
                a = int(wts[k, 0])
                acc += (wts[k, 1] * H[i, a] * R[a] + wts[k, 2] * H[i, a + 1] * R[a + 1]
                        + wts[k, 3] * H[i, a + 2] * R[a + 2])
            Tn[i] = T0 + pre * acc
            d = abs(Tn[i] - T[i])
            if d > res:
                res = d
        if res < tol:
            for i in range(nq):
                T[i] = Tn[i]
            break
        if it <= max_iter:
            # under-relaxation halved whenever the residual grows, recovering slowly while it falls
            if res > res_prev:
                relax = max(0.5 * relax, 1.0 / 64.0)
            else:
                relax = min(1.0, 1.25 * relax)
            res_prev = res
        elif it > max_iter + 1:
            relax = _aitken(Tn, T, r_prev, relax)
        _relax_step(Tn, T, r_prev, relax)
    _temperature_factors(T, T_lo, inv_dT, shift_tab, vshift_tab, f_tab, g_tab, shift, vshift, fq, gq)
    for i in range(nq):
        T_out[iv, i] = T[i]
    _scales(iv, lq10, lv10, q4C, shift, vshift, fq, gq, lw0, inv_dlw, ln_are, ln_aim, ln_l, scale, K,
            gG_out[iv], R, L_out[iv])
    cumulative_weighted(K, quad[0], quad[1], G)
    for iq in range(nq):
        P = area(G[iq], law)
        P_out[iv, iq] = P
        dmu_out[iv, iq] = 0.5 * q4C[iq] * _weight_of_area(P, law) * L_out[iv, iq]
    layer_out[iv] = friction_cumulative(G, K, R, q, quad, law, cum_out[iv])
    return cum_out[iv, nq - 1], it, res


@njit(cache=True)
def _aitken(Tn, T, r_prev, relax):
    """Aitken's dynamic relaxation factor (Irons & Tuck 1969): the factor that cancels the dominant mode of the
    last two residual vectors r = Tn - T (``r_prev`` the previous one), clamped to [_MIN_RELAX, 1]. It rescues a
    hot contact whose map is strongly non-contractive (a cold profile heats to 10^4 K, a hot one barely heats: a
    period-2 oscillation whose residual hardly changes, so a residual-growth rule keeps the factor near 1)."""
    num = 0.0
    den = 0.0
    for i in range(T.shape[0]):
        dr = (Tn[i] - T[i]) - r_prev[i]
        num += r_prev[i] * dr
        den += dr * dr
    if den > 0.0:
        return min(1.0, max(_MIN_RELAX, -relax * num / den))
    return relax


@njit(cache=True)
def _relax_step(Tn, T, r_prev, relax):
    """T += relax (Tn - T), keeping the residual Tn - T in ``r_prev``."""
    for i in range(T.shape[0]):
        r_prev[i] = Tn[i] - T[i]
        T[i] = T[i] + relax * r_prev[i]


#: Smallest relaxation factor of the flash iteration (Aitken's factor is clamped to [_MIN_RELAX, 1]).
_MIN_RELAX = 1e-4


@njit(cache=True)
def _temperature_factors(T, T_lo, inv_dT, shift_tab, vshift_tab, f_tab, g_tab, shift, vshift, fq, gq):
    """Shift, vertical shift and strain factors at the temperature of every node (tables on a uniform T grid;
    ``f_tab``/``g_tab`` have one row per node, or a single row shared by all)."""
    nq = T.shape[0]
    per_node = f_tab.shape[0] == nq
    for i in range(nq):
        xT = (T[i] - T_lo) * inv_dT
        shift[i] = _linear(shift_tab, xT)
        vshift[i] = _linear(vshift_tab, xT)
        r = i if per_node else 0
        fq[i] = _linear(f_tab[r], xT)
        gq[i] = _linear(g_tab[r], xT)


def _flash_all(q, x, lq10, lv10, v, q4C, quad, lw0, inv_dlw, ln_are, ln_aim, ln_l, scale, law, T0, T_start, T_lo,
               inv_dT, shift_tab, vshift_tab, f_tab, g_tab, EX, S1, S2, a_t0, D, heat_factor, x_m, tol, max_iter,
               G_out, P_out, dmu_out, cum_out, gG_out, R_out, L_out, T_out, layer_out, mu_out, it_out, res_out):
    for iv in prange(lv10.shape[0]):
        mu, it, res = _flash_speed(iv, q, x, lq10, lv10, v[iv], q4C, quad, lw0, inv_dlw, ln_are, ln_aim, ln_l,
                                   scale[iv], law, T0[iv], T_start[iv], T_lo, inv_dT, shift_tab, vshift_tab, f_tab,
                                   g_tab, EX[iv], S1, S2, a_t0[iv], D, heat_factor[iv], x_m, tol, max_iter, G_out,
                                   P_out, dmu_out, cum_out, gG_out, R_out, L_out, T_out, layer_out)
        mu_out[iv] = mu
        it_out[iv] = it
        res_out[iv] = res


#: Flash-temperature solver for every speed, in parallel over speeds (see :func:`_flash_speed`).
flash_parallel = njit(cache=True, parallel=True)(_flash_all)
#: The same on one thread, for calls with few speeds.
flash_serial = njit(cache=True)(_flash_all)
