"""Numba kernels of the patch-heating march (interpolation in the friction lattice and the march along the patch)."""

from __future__ import annotations

import numpy as np
from numba import njit, prange


@njit(cache=True)
def _segment_weights(A, B, hs):
    r"""Weights (w_l, w_r) of :math:`\int_{x_k-A}^{x_k-B} f(x')/\sqrt{x_k - x'}\,dx'` for f linear on the
    segment of length hs = A - B (values f_l at its left end, f_r at its right end).

    Exact: :math:`I_0 = 2(\sqrt A - \sqrt B)`, :math:`I_1 = \int (x' - x_l)/\sqrt{x_k - x'} = A I_0 -
    \tfrac23(A^{3/2} - B^{3/2})`, :math:`w_r = I_1/h_s`, :math:`w_l = I_0 - w_r`; written without cancellation
    as :math:`w_l = h_s(2\sqrt A + 4\sqrt B)/(3(\sqrt A + \sqrt B)^2)`,
    :math:`w_r = h_s(4\sqrt A + 2\sqrt B)/(3(\sqrt A + \sqrt B)^2)`.
    """
    ra = np.sqrt(A)
    rb = np.sqrt(B)
    den = 3.0 * (ra + rb) * (ra + rb)
    return hs * (2.0 * ra + 4.0 * rb) / den, hs * (4.0 * ra + 2.0 * rb) / den


@njit(cache=True)
def _lagrange(nodes, start, n, x, w):
    """Four-point (or n-point when n < 4) Lagrange weights at x (clamped into the node range); returns k0."""
    m = 4 if n >= 4 else n
    if n == 1:
        w[0] = 1.0
        return start
    lo = nodes[start]
    hi = nodes[start + n - 1]
    if x < lo:
        x = lo
    elif x > hi:
        x = hi
    # interval j with nodes[j] <= x < nodes[j+1]
    j = 0
    a, b = 0, n - 1
    while b - a > 1:
        mid = (a + b) // 2
        if nodes[start + mid] <= x:
            a = mid
        else:
            b = mid
    j = a
    k0 = j - 1
    if k0 < 0:
        k0 = 0
    if k0 > n - m:
        k0 = n - m
    for i in range(m):
        xi = nodes[start + k0 + i]
        wi = 1.0
        for k in range(m):
            if k != i:
                xk = nodes[start + k0 + k]
                wi *= (x - xk) / (xi - xk)
        w[i] = wi
    return start + k0


@njit(cache=True)
def _lagrange_uniform(n, x, w):
    """Lagrange weights at x on the n uniform nodes 0, 1, .., n - 1 (four nearest; n when n < 4; x clamped into
    [0, n - 1]); returns k0."""
    if n == 1:
        w[0] = 1.0
        return 0
    if x < 0.0:
        x = 0.0
    elif x > n - 1.0:
        x = n - 1.0
    m = 4 if n >= 4 else n
    j = int(x)
    if j > n - 2:
        j = n - 2
    k0 = j - 1
    if k0 < 0:
        k0 = 0
    if k0 > n - m:
        k0 = n - m
    for i in range(m):
        wi = 1.0
        for k in range(m):
            if k != i:
                wi *= (x - (k0 + k)) / (i - k)
        w[i] = wi
    return k0


@njit(cache=True)
def _interp(c, lv, gq, x, lvn, voff, gnodes, values, vtoff, nu, wv, wg, wu):
    """mu of sweep c at (ln v, g, x = y/h) by tensor-product Lagrange interpolation (clamped at 0)."""
    nv = voff[c + 1] - voff[c]
    ng = gnodes.size
    iv = _lagrange(lvn, voff[c], nv, lv, wv)
    ig = _lagrange(gnodes, 0, ng, gq, wg)
    mv = 4 if nv >= 4 else nv
    mg = 4 if ng >= 4 else ng
    return _mu_at(iv, wv, mv, ig, wg, mg, x, values, vtoff, nu, wu)


@njit(cache=True)
def _interp_rows(sweep, lvs, lvn, voff, gnodes, values, vtoff, nu):
    """mu at (v_s, p = sigma0, T0) for every row."""
    out = np.empty(sweep.size)
    wv = np.empty(4)
    wg = np.empty(4)
    wu = np.empty(4)
    for r in range(sweep.size):
        out[r] = _interp(sweep[r], lvs[r], 1.0, 0.0, lvn, voff, gnodes, values, vtoff, nu, wv, wg, wu)
    return out


@njit(cache=True)
def _y_at(yT, c, dT, dTf):
    """y(T0 + dT) of sweep c by linear interpolation in its fine table (clamped to the table)."""
    n = yT.shape[1]
    x = dT / dTf
    if x <= 0.0:
        return yT[c, 0]
    j = int(x)
    if j >= n - 1:
        return yT[c, n - 1]
    t = x - j
    return yT[c, j] + t * (yT[c, j + 1] - yT[c, j])


@njit(cache=True)
def _x_at(yT, c, dT, cap, dTf, hy):
    """Lattice coordinate y(T0 + dT)/h of sweep c, the rise taken at the cap above it."""
    return _y_at(yT, c, dT if dT < cap else cap, dTf) / hy


@njit(cache=True)
def _mu_at(iv, wv, mv, ig, wg, mg, x, values, vtoff, nu, wu):
    """Interpolated mu at the temperature lattice coordinate x = y/h, with the speed weights (iv, wv) and the
    pressure weights (ig, wg) already known."""
    out = 0.0
    for a in range(mv):
        node = iv + a
        n_u = nu[node]
        ku = _lagrange_uniform(n_u, x, wu)
        m_u = 4 if n_u >= 4 else n_u
        base = vtoff[node]
        acc_g = 0.0
        for b in range(mg):
            row = base + (ig + b) * n_u + ku
            acc = 0.0
            for k in range(m_u):
                acc += wu[k] * values[row + k]
            acc_g += wg[b] * acc
        out += wv[a] * acc_g
    return out if out > 0.0 else 0.0


def _march_all(sweep, lvs, a_all, lam_all, xi, g, W, lvn, voff, gnodes, values, vtoff, nu, T0s, hy, cap, mu_max,
               yT, dTf, profiles):
    """March along the patch for every row (see :func:`patch_friction`), in parallel over the rows. ``umax`` of a
    row: its highest y over the top of the table at its speed (> 1: the table must grow; temperatures above
    T0 + cap are taken at the cap)."""
    n = sweep.size
    N = xi.size
    mu_out = np.empty(n)
    xc_out = np.empty(n)
    rise = np.zeros(n)
    umax = np.zeros(n)
    Tprof = np.zeros((n if profiles else 1, N))
    shear = np.zeros((n if profiles else 1, N))
    muprof = np.zeros((n if profiles else 1, N))
    glo = gnodes[0]
    ng = gnodes.size
    # pressure weights of every patch node (those of the stick/slide boundary are computed per row)
    IG = np.empty(N, dtype=np.int64)
    WG = np.empty((N + 1, 4))
    for j in range(N):
        gj = g[j] if g[j] > glo else glo
        IG[j] = _lagrange(gnodes, 0, ng, gj, WG[j])
    for r in prange(n):
        _march_row(r, sweep, lvs, a_all, lam_all, xi, g, W, lvn, voff, gnodes, values, vtoff, nu, T0s, hy, cap,
                   mu_max, yT, dTf, profiles, IG, WG, mu_out, xc_out, rise, umax, Tprof, shear, muprof)
    return mu_out, xc_out, rise, umax, Tprof, shear, muprof


#: The march on every row in parallel (prange over the rows), and on one thread for few rows.
_march_parallel = njit(cache=True, parallel=True)(_march_all)


_march_serial = njit(cache=True)(_march_all)


@njit(cache=True)
def _march_row(r, sweep, lvs, a_all, lam_all, xi, g, W, lvn, voff, gnodes, values, vtoff, nu, T0s, hy, cap, mu_max,
               yT, dTf, profiles, IG, WG, mu_out, xc_out, rise, umax, Tprof, shear, muprof):
    """March along the patch for row r (see :func:`patch_friction`); writes the row's outputs."""
    N = xi.size
    h = xi[1] - xi[0]
    sh = np.sqrt(h)
    wv = np.empty(4)
    wu = np.empty(4)
    wgc = np.empty(4)
    y = np.empty(N + 1)
    gy = np.empty(N + 1)
    f = np.empty(N + 1)
    Ty = np.empty(N + 1)
    d = np.empty(N)
    mu0 = np.empty(N)
    glo = gnodes[0]
    ng = gnodes.size
    mg = 4 if ng >= 4 else ng
    c = sweep[r]
    lv = lvs[r]
    a = a_all[r]
    lam = lam_all[r]
    T0 = T0s[c]
    v = np.exp(lv)
    nv = voff[c + 1] - voff[c]
    iv = _lagrange(lvn, voff[c], nv, lv, wv)
    mv = 4 if nv >= 4 else nv
    ytop = (nu[iv] - 1) * hy  # the table's top at this speed: the lowest over the four speed nodes
    for k in range(1, mv):
        yk = (nu[iv + k] - 1) * hy
        if yk < ytop:
            ytop = yk
    # stick limit at T0 (u = 0)
    for j in range(N):
        mu0[j] = _mu_at(iv, wv, mv, IG[j], WG[j], mg, 0.0, values, vtoff, nu, wu)
    pure = not np.isfinite(a)
    i = -1
    xc = 0.0
    if pure:
        i = 0
    else:
        for j in range(N):
            d[j] = mu0[j] * g[j] - a * xi[j]
        for j in range(1, N):
            if d[j] <= 0.0:
                i = j
                break
    if i < 0:  # the whole patch sticks
        mu_out[r] = 0.5 * a
        xc_out[r] = 1.0
        if profiles:
            for j in range(N):
                Tprof[r, j] = T0
                shear[r, j] = a * xi[j]
                muprof[r, j] = mu0[j]
        return
    # slide points: y[0] = x_c (when between nodes), then the nodes behind it; node of slide point k: jk
    first_special = False
    if pure:
        j0 = 0
    else:
        t = 0.0
        den = d[i - 1] - d[i]
        if den > 0.0:
            t = d[i - 1] / den
        t = min(max(t, 0.0), 1.0)
        xc = xi[i - 1] + t * h
        j0 = i
        if xi[i] - xc > 1e-12:
            first_special = True
    M = 0
    if first_special:
        gc = g[i - 1] + t * (g[i] - g[i - 1])
        y[0] = xc
        gy[0] = gc
        M = 1
        igc = _lagrange(gnodes, 0, ng, gc if gc > glo else glo, wgc)
        f[0] = _mu_at(iv, wv, mv, igc, wgc, mg, 0.0, values, vtoff, nu, wu) * gc
    off = M - j0  # slide index of node j is j + off
    for j in range(j0, N):
        y[M] = xi[j]
        gy[M] = g[j]
        M += 1
    if not first_special:
        f[0] = mu0[j0] * gy[0]
    Ty[0] = T0
    hs = y[1] - y[0] if M > 1 else h
    ru = 0.0
    for k in range(1, M):
        # known part of the Abel integral at y[k]; ck multiplies the unknown f[k]
        S = 0.0
        ck = 0.0
        jstart = 0
        if first_special:
            wl, wr = _segment_weights(y[k] - y[0], y[k] - y[1], hs)
            if k == 1:
                S += wl * f[0]
                ck = wr
            else:
                S += wl * f[0] + wr * f[1]
            jstart = 1
        for jj in range(jstart, k):
            dd = k - jj
            if jj + 1 == k:
                S += sh * W[0, dd] * f[jj]
                ck = sh * W[1, dd]
            else:
                S += sh * (W[0, dd] * f[jj] + W[1, dd] * f[jj + 1])
        # solve F(T) = T - T0 - lam (S + ck g mu(T)) = 0 (secant from the previous node, bisection fallback)
        jn = k - off
        ig = IG[jn]
        base = T0 + lam * S
        coef = lam * ck * gy[k]
        Ta = Ty[k - 1] if Ty[k - 1] > base else base
        ma = _mu_at(iv, wv, mv, ig, WG[jn], mg, _x_at(yT, c, Ta - T0, cap, dTf, hy), values, vtoff, nu, wu)
        Fa = Ta - base - coef * ma
        Tb = base + coef * ma
        ok = abs(Fa) <= 1e-10 * (1.0 + abs(Ta))
        T = Ta
        if not ok:
            for it in range(40):
                mb = _mu_at(iv, wv, mv, ig, WG[jn], mg, _x_at(yT, c, Tb - T0, cap, dTf, hy), values, vtoff,
                            nu, wu)
                Fb = Tb - base - coef * mb
                if abs(Fb) <= 1e-10 * (1.0 + abs(Tb)):
                    T = Tb
                    ok = True
                    break
                if Fb == Fa:
                    break
                Tn = Tb - Fb * (Tb - Ta) / (Fb - Fa)
                Ta, Fa = Tb, Fb
                Tb = Tn
        if not ok:  # bisection on F, F(base) <= 0 <= F(base + coef mu_max)
            lo_ = base
            hi_ = base + coef * mu_max[c] * 1.5 + 1e-12
            for it in range(200):
                mid = 0.5 * (lo_ + hi_)
                mm = _mu_at(iv, wv, mv, ig, WG[jn], mg, _x_at(yT, c, mid - T0, cap, dTf, hy), values, vtoff,
                            nu, wu)
                if mid - base - coef * mm > 0.0:
                    hi_ = mid
                else:
                    lo_ = mid
                if hi_ - lo_ < 1e-10 * (1.0 + abs(mid)):
                    break
            T = 0.5 * (lo_ + hi_)
        x = _x_at(yT, c, T - T0, cap, dTf, hy)
        m = _mu_at(iv, wv, mv, ig, WG[jn], mg, x, values, vtoff, nu, wu)
        if ytop > 0.0:
            u = x * hy / ytop
        elif x > 0.0:
            u = 2.0  # heated, but the table has only the T0 slice here
        else:
            u = 0.0
        if u > ru:
            ru = u
        Ty[k] = T
        f[k] = m * gy[k]
    # wheel friction: stick part exactly, slide part by the trapezoid rule
    tot = 0.0 if pure else 0.5 * a * xc * xc
    for k in range(1, M):
        tot += 0.5 * (y[k] - y[k - 1]) * (f[k] + f[k - 1])
    mu_out[r] = tot
    xc_out[r] = xc
    mx = 0.0
    for k in range(M):
        if Ty[k] - T0 > mx:
            mx = Ty[k] - T0
    rise[r] = mx
    umax[r] = ru
    if profiles:
        for j in range(N):
            if j < j0:
                Tprof[r, j] = T0
                shear[r, j] = a * xi[j]
                muprof[r, j] = mu0[j]
            else:
                k = j + off
                Tprof[r, j] = Ty[k]
                shear[r, j] = f[k]
                muprof[r, j] = f[k] / gy[k] if gy[k] > 0.0 else mu0[j]
