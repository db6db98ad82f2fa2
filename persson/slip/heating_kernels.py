r"""numba kernels of patch heating: the march along the contact patch and the friction lattice it reads.

The march (:func:`_march_row`, one row of :func:`persson.slip.patch_friction`) takes named steps: the speed
stencil of the row in the lattice (:func:`_speed_stencil`) and the top of its temperature table
(:func:`_table_top`), the friction at T0 along the patch (:func:`_stick_limit`), the end of the stick zone
(:func:`_stick_edge`), the points that slide (:func:`_slide_points`), and for each of them the known part of the
Abel integral (:func:`_abel_known_part`) and the temperature there, the root of the implicit heat balance
(:func:`_node_temperature`); then the wheel's friction (:func:`_wheel_friction`) and the profiles. The friction at
a (speed, pressure, temperature) point is interpolated in the tables of :class:`persson.slip.heating_tables._Tables`
(tensor-product Lagrange interpolation, :func:`_mu_at`). The arrays come grouped in named tuples, each field
documented there (:mod:`persson.slip.heating_arrays`): :class:`~persson.slip.heating_arrays.PatchRows`,
:class:`~persson.slip.heating_arrays.Patch`, :class:`~persson.slip.heating_arrays.FrictionLattice`,
:class:`~persson.slip.heating_arrays.TemperatureAxis`. The kernels that call one another live in this one file:
numba caches a kernel by its own source file only. The helpers the march calls at every patch node take their
arrays out of the tuples once per row and are inlined into it (``inline="always"``): numba counts references at
every access to a tuple's field, which in the loop over the nodes cost a fifth of the march's time.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..engine.borrow import borrowed
from ..engine.jit import threaded
from .heating_arrays import MarchOutputs

#: The integer 0 as an int64 for the kernels' calls: a literal 0 would make numba compile the callee once more
#: for the literal's own type.
_ZERO = np.int64(0)


# ==================================================================================================== march
def march(rows, patch, lattice, axis, profiles: bool, min_rows: int = 4) -> MarchOutputs:
    """March along the patch for every row (see :func:`persson.slip.patch_friction`), the rows shared between
    threads (:func:`persson.engine.jit.threaded`; each row costs about N^2 operations, the Abel sums, so threads pay
    off from ``min_rows`` rows on).

    Parameters
    ----------
    rows, patch, lattice, axis, profiles
        As for :func:`_march_all` (the rows, the patch, the friction tables, their temperature axis, and whether to
        fill the per-node profiles).
    min_rows : int
        Fewer rows than this are marched on the calling thread alone.

    Returns
    -------
    MarchOutputs
    """
    n = rows.sweep.size
    N = patch.xi.size
    m = n if profiles else 1
    out = MarchOutputs(np.empty(n), np.empty(n), np.zeros(n), np.zeros(n), np.zeros((m, N)), np.zeros((m, N)),
                       np.zeros((m, N)))
    threaded(_march_kernel, n, min_items=min_rows, rows=rows, patch=patch, lattice=lattice, axis=axis,
             profiles=bool(profiles), out=out)
    return out


def _march_all(rows, patch, lattice, axis, profiles, out, first, stride):
    """March along the patch for the rows ``first, first + stride, ...`` (see :func:`_march_row`): one thread's
    share (:func:`march`).

    Parameters
    ----------
    rows : PatchRows
        The rows.
    patch : Patch
        The patch nodes and pressure.
    lattice : FrictionLattice
        The friction tables.
    axis : TemperatureAxis
        Their temperature coordinate.
    profiles : bool
        Whether to fill the per-node profiles.
    out : MarchOutputs
        Filled for the rows of this share.
    first : int
        The first row of this share.
    stride : int
        Step between the rows of this share (the number of shares).

    Returns
    -------
    int
        The total size of the share's own arrays (the pressure stencils, the Abel weights and the rows' scratch
        arrays, allocated once here). The rows use borrowed views of them (:func:`persson.engine.borrow.borrowed`):
        numba counted the references of an array allocated in the kernel with an atomic operation at every patch
        point it was passed on at, 60 % of the march's time (sampled with ``perf``). Reading the arrays' sizes after
        the loop keeps them alive until every row is done.
    """
    rows, patch, lattice, axis, out = borrowed((rows, patch, lattice, axis, out))
    g_first, g_weights = _pressure_stencils(patch.g, lattice.g_nodes)
    abel_weights = _combined_abel_weights(patch.abel)
    N = patch.xi.size
    nu_max = 1
    for v in range(lattice.n_temperature.size):
        if lattice.n_temperature[v] > nu_max:
            nu_max = lattice.n_temperature[v]
    scratch = (np.empty(4), np.empty(4), np.empty(N), np.empty(N + 1), np.empty(N + 1), np.empty(N + 1),
               np.empty(N + 1), np.empty(lattice.g_nodes.size * nu_max))
    b_first, b_weights, b_abel, b_scratch = borrowed((g_first, g_weights, abel_weights, scratch))
    for r in range(first, rows.sweep.size, stride):
        _march_row(r, rows, patch, lattice, axis, profiles, b_first, b_weights, b_abel, b_scratch, out)
    kept = g_first.size + g_weights.size + abel_weights.size
    for a in scratch:
        kept += a.size
    return kept


#: The march over a share of the rows; releases the GIL, so that :func:`march` runs the shares on several threads.
_march_kernel = njit(cache=True, nogil=True)(_march_all)


@njit(cache=True)
def _march_row(r, rows, patch, lattice, axis, profiles, g_first, g_weights, abel_weights, scratch, out):
    """March along the patch for row r: the stick zone, then the temperature and shear at every sliding point,
    solved point by point from the leading edge; writes the row's outputs.

    Parameters
    ----------
    r : int
        The row.
    rows : PatchRows
        The rows.
    patch : Patch
        The patch nodes and pressure.
    lattice : FrictionLattice
        The friction tables.
    axis : TemperatureAxis
        Their temperature coordinate.
    profiles : bool
        Whether to fill the per-node profiles.
    g_first : ndarray of int64 (N,)
        First pressure node of the stencil of every patch node (:func:`_pressure_stencils`).
    g_weights : ndarray (N + 1, 4)
        Its interpolation weights.
    abel_weights : ndarray (N,)
        The Abel weights of a shear value at each distance, reversed (:func:`_combined_abel_weights`).
    scratch : tuple of ndarray
        Work arrays of the row (:func:`_march_all`): the speed and temperature weights (4,), the friction at T0 at
        the patch nodes (N,), the sliding points' y, p / sigma0, shear and temperature (N + 1,), and the row's
        speed-contracted table (n_g times the most temperature nodes of a speed node).
    out : MarchOutputs
        Row r is filled.
    """
    xi = patch.xi
    g = patch.g
    N = xi.size
    h = xi[1] - xi[0]
    w_speed, w_temperature, mu_T0, y, g_slide, shear, T_slide, contracted = scratch
    c = rows.sweep[r]
    a = rows.stick_slope[r]
    T0 = axis.T0[c]
    iv, mv = _speed_stencil(lattice, c, rows.log_speed[r], w_speed)
    mg = min(4, lattice.g_nodes.size)
    y_top = _table_top(lattice.n_temperature, iv, mv, axis.h)
    n_min = _speed_contract_into(lattice, iv, w_speed, mv, contracted)
    _stick_limit(iv, w_speed, mv, g_first, g_weights, mg, lattice, mu_T0)
    pure = not np.isfinite(a)
    i, t = _stick_edge(mu_T0, g, xi, a, pure)
    if i < 0:  # the whole patch sticks
        out.mu[r] = 0.5 * a
        out.stick_fraction[r] = 1.0
        if profiles:
            _write_profiles(r, T0, a, xi, mu_T0, N, _ZERO, np.empty(0), np.empty(0), np.empty(0), out)
        return
    xc = 0.0 if pure else xi[i - 1] + t * h
    # the sliding points: x_c when it lies between nodes, then the nodes behind it
    n_slide, first_node, edge_point = _slide_points(i, t, xc, pure, iv, w_speed, mv, mg, lattice, w_temperature,
                                                    mu_T0, xi, g, y, g_slide, shear)
    T_slide[0] = T0
    h_first = y[1] - y[0] if n_slide > 1 else h
    sqrt_h = np.sqrt(h)
    top_use = 0.0
    lam = rows.heat_factor[r]
    abel = patch.abel
    # the arrays out of the tuples once, not at every point (numba counts references at every access)
    values, value_offset, n_temperature = lattice.values, lattice.value_offset, lattice.n_temperature
    y_fine, cap, dT_fine, h_y, mu_max = axis.y_fine, axis.cap, axis.dT_fine, axis.h, axis.mu_max[c]
    slope = np.nan
    for k in range(1, n_slide):
        known, own_weight = _abel_known_part(k, y, shear, abel, abel_weights, sqrt_h, edge_point, h_first)
        # the temperature at point k solves T = T0 + lam (known + own_weight g mu(T))
        j = k + first_node - (1 if edge_point else 0)  # the patch node of point k
        base = T0 + lam * known
        coef = lam * own_weight * g_slide[k]
        # first guess: the temperature extrapolated from the points before (it rises smoothly along the patch;
        # quadratically from the third point on), which saves the root search about one friction evaluation per point
        if k >= 3:
            guess = 3.0 * (T_slide[k - 1] - T_slide[k - 2]) + T_slide[k - 3]
        elif k == 2:
            guess = 2.0 * T_slide[1] - T_slide[0]
        else:
            guess = T_slide[0]
        T, mu, slope = _node_temperature(base, coef, guess, slope, T0, mu_max, c, iv, w_speed, mv, g_first[j],
                                         g_weights[j], mg, values, value_offset, n_temperature, y_fine, cap, dT_fine,
                                         h_y, w_temperature, contracted, n_min)
        x = _x_at(y_fine, c, T - T0, cap, dT_fine, h_y)
        use = _table_use(x, h_y, y_top)
        if use > top_use:
            top_use = use
        T_slide[k] = T
        shear[k] = mu * g_slide[k]
    out.mu[r] = _wheel_friction(y, shear, n_slide, a, xc, pure)
    out.stick_fraction[r] = xc
    rise = 0.0
    for k in range(n_slide):
        if T_slide[k] - T0 > rise:
            rise = T_slide[k] - T0
    out.rise[r] = rise
    out.table_use[r] = top_use
    if profiles:
        _write_profiles(r, T0, a, xi, mu_T0, first_node, first_node - (1 if edge_point else 0), T_slide, shear,
                        g_slide, out)


@njit(cache=True)
def _pressure_stencils(g, g_nodes):
    """The pressure interpolation stencil of every patch node (pressures below the first node taken there).

    Parameters
    ----------
    g : ndarray (N,)
        p / sigma0 at the patch nodes.
    g_nodes : ndarray (n_g,)
        The lattice's pressure nodes.

    Returns
    -------
    (ndarray of int64 (N,), ndarray (N + 1, 4))
        First stencil node and weights of every patch node.
    """
    N = g.size
    glo = g_nodes[0]
    ng = g_nodes.size
    first = np.empty(N, dtype=np.int64)
    weights = np.empty((N + 1, 4))
    for j in range(N):
        gj = g[j] if g[j] > glo else glo
        first[j] = _lagrange(g_nodes, _ZERO, ng, gj, weights[j])
    return first, weights


@njit(cache=True)
def _speed_stencil(lattice, c, log_speed, w_speed):
    """The speed nodes of sweep c around the row's speed and their Lagrange weights.

    Parameters
    ----------
    lattice : FrictionLattice
        The friction tables.
    c : int
        The sweep.
    log_speed : float
        ln v_s of the row, m/s.
    w_speed : ndarray (4,)
        Filled with the weights.

    Returns
    -------
    (int, int)
        The first speed node (global index) and the number of nodes (4, or fewer in a short sweep; 1 for a row
        whose speed is a node's).

    A row on a node reads that node alone: its four-point weights are exactly one there and zero at the other
    three, so the values are those of the four-point stencil to the last bit, and the nodes around it need not
    reach the row's temperatures (:meth:`persson.slip.heating_tables._Tables._grow`).
    """
    nv = lattice.v_offset[c + 1] - lattice.v_offset[c]
    iv = _lagrange(lattice.log_speed, lattice.v_offset[c], nv, log_speed, w_speed)
    mv = 4 if nv >= 4 else nv
    for a in range(mv):
        if lattice.log_speed[iv + a] == log_speed:
            w_speed[0] = 1.0
            return iv + a, 1
    return iv, mv


@njit(cache=True)
def _table_top(n_temperature, iv, mv, h):
    """The top of the temperature table at a row's speed: the lowest over its speed nodes, in y.

    Parameters
    ----------
    n_temperature : ndarray of int64 (n_v,)
        Temperature nodes of every speed node.
    iv : int
        First speed node of the stencil.
    mv : int
        Speed nodes in the stencil.
    h : float
        Spacing of the lattice in y, decades.

    Returns
    -------
    float
        y of the top, decades (0: only the T0 slice).
    """
    y_top = (n_temperature[iv] - 1) * h
    for k in range(1, mv):
        yk = (n_temperature[iv + k] - 1) * h
        if yk < y_top:
            y_top = yk
    return y_top


@njit(cache=True)
def _stick_limit(iv, w_speed, mv, g_first, g_weights, mg, lattice, mu_T0):
    """The friction at T0 (the stick limit) at every patch node.

    Parameters
    ----------
    iv : int
        First speed node of the row's stencil.
    w_speed : ndarray (4,)
        Its weights.
    mv : int
        Speed nodes in the stencil.
    g_first : ndarray of int64 (N,)
        First pressure node of every patch node's stencil.
    g_weights : ndarray (N + 1, 4)
        Their weights.
    mg : int
        Pressure nodes in a stencil.
    lattice : FrictionLattice
        The friction tables.
    mu_T0 : ndarray (N,)
        Filled with the friction at T0.
    """
    # the arrays out of the tuple once, not at every node (numba counts references at every access)
    values, value_offset, n_temperature = lattice.values, lattice.value_offset, lattice.n_temperature
    for j in range(mu_T0.size):
        mu_T0[j] = _mu_T0(iv, w_speed, mv, g_first[j], g_weights[j], mg, values, value_offset, n_temperature)


@njit(cache=True, inline="always")
def _mu_T0(iv, wv, mv, ig, wg, mg, values, value_offset, n_temperature):
    """:func:`_mu_at` on the T0 slice (x = 0), where the temperature weights are exactly (1, 0, 0, 0): the slice's
    values read directly, which gives the same number (a product by 1 and a sum with 0 are exact), four times
    faster (the stick limit is evaluated at every patch node of every row).

    Parameters
    ----------
    iv, wv, mv, ig, wg, mg, values, value_offset, n_temperature
        As for :func:`_mu_at`.

    Returns
    -------
    float
    """
    out = 0.0
    for a in range(mv):
        node = iv + a
        base = value_offset[node] + ig * n_temperature[node]
        acc_g = 0.0
        for b in range(mg):
            acc_g += wg[b] * values[base + b * n_temperature[node]]
        out += wv[a] * acc_g
    return out if out > 0.0 else 0.0


@njit(cache=True)
def _stick_edge(mu_T0, g, xi, a, pure):
    """The end of the stick zone: the first node where the bristle stress a x / l reaches the friction limit
    mu(T0) p / sigma0, and where between that node and the one before the difference changes sign (linear).

    Parameters
    ----------
    mu_T0 : ndarray (N,)
        Friction at T0 at the nodes.
    g : ndarray (N,)
        p / sigma0 at the nodes.
    xi : ndarray (N,)
        The nodes x / l.
    a : float
        The bristle stress slope (:class:`~persson.slip.heating_arrays.PatchRows`).
    pure : bool
        Pure sliding: no stick zone.

    Returns
    -------
    (int, float)
        The first sliding node i (0 for pure sliding, -1 when the whole patch sticks) and the fraction t in
        [0, 1] of the interval (i - 1, i) where the stick zone ends.
    """
    if pure:
        return 0, 0.0
    N = xi.size
    d = np.empty(N)
    for j in range(N):
        d[j] = mu_T0[j] * g[j] - a * xi[j]
    i = -1
    for j in range(1, N):
        if d[j] <= 0.0:
            i = j
            break
    if i < 0:
        return -1, 0.0
    t = 0.0
    den = d[i - 1] - d[i]
    if den > 0.0:
        t = d[i - 1] / den
    return i, min(max(t, 0.0), 1.0)


@njit(cache=True)
def _slide_points(i, t, xc, pure, iv, w_speed, mv, mg, lattice, w_temperature, mu_T0, xi, g, y, g_slide, shear):
    """The sliding points: the stick edge x_c when it lies between nodes, then the nodes from i on, with their
    pressure and the shear of the first point (at T0: no heat has been produced ahead of it).

    Parameters
    ----------
    i : int
        The first sliding node.
    t : float
        Fraction of the interval (i - 1, i) where the stick zone ends.
    xc : float
        x_c / l.
    pure : bool
        Pure sliding.
    iv : int
        First speed node of the row's stencil.
    w_speed : ndarray (4,)
        Its weights.
    mv : int
        Speed nodes in the stencil.
    mg : int
        Pressure nodes in a stencil.
    lattice : FrictionLattice
        The friction tables.
    w_temperature : ndarray (4,)
        Scratch for the temperature weights.
    mu_T0 : ndarray (N,)
        Friction at T0 at the nodes.
    xi : ndarray (N,)
        The nodes x / l.
    g : ndarray (N,)
        p / sigma0 at the nodes.
    y : ndarray (N + 1,)
        Filled with x / l of the sliding points.
    g_slide : ndarray (N + 1,)
        Filled with p / sigma0 at them.
    shear : ndarray (N + 1,)
        Element 0 is filled with the shear / sigma0 of the first point.

    Returns
    -------
    (int, int, bool)
        The number of sliding points, the first sliding node and whether point 0 is the stick edge between nodes.
    """
    N = xi.size
    edge_point = (not pure) and xi[i] - xc > 1e-12
    n_slide = 0
    if edge_point:
        gc = g[i - 1] + t * (g[i] - g[i - 1])
        y[0] = xc
        g_slide[0] = gc
        n_slide = 1
        glo = lattice.g_nodes[0]
        w_edge = np.empty(4)
        ig = _lagrange(lattice.g_nodes, _ZERO, lattice.g_nodes.size, gc if gc > glo else glo, w_edge)
        shear[0] = _mu_at(iv, w_speed, mv, ig, w_edge, mg, 0.0, lattice.values, lattice.value_offset,
                          lattice.n_temperature, w_temperature) * gc
    first_node = 0 if pure else i
    for j in range(first_node, N):
        y[n_slide] = xi[j]
        g_slide[n_slide] = g[j]
        n_slide += 1
    if not edge_point:
        shear[0] = mu_T0[first_node] * g_slide[0]
    return n_slide, first_node, edge_point


@njit(cache=True, inline="always")
def _abel_known_part(k, y, shear, abel, abel_weights, sqrt_h, edge_point, h_first):
    r"""The Abel integral :math:`\int_{y_0}^{y_k} \tau(y')/\sqrt{y_k - y'}\,dy'` at sliding point k, split into
    the part of the points before k (known) and the weight of the unknown shear at k itself; the shear is linear
    between points, the kernel integrated exactly (:func:`_segment_weights`).

    Each shear value m before k enters through the two segments it ends, with the weight of distance k - m
    (:func:`_combined_abel_weights`); the first point of the uniform run only through the segment it starts. The
    sum, N^2 / 2 terms per row (a seventh of the march's time), is a dot product of two forward runs of memory
    (the weights held reversed), BLAS's ``ddot``.

    Parameters
    ----------
    k : int
        The sliding point, >= 1.
    y : ndarray (N + 1,)
        x / l of the sliding points (uniform after point 0 or 1).
    shear : ndarray (N + 1,)
        Shear / sigma0 at the points before k.
    abel : ndarray (2, N)
        The unit Abel weights of the uniform spacing (:class:`~persson.slip.heating_arrays.Patch`).
    abel_weights : ndarray (N,)
        Their sums per shear value, reversed: distance d at N - 1 - d (:func:`_combined_abel_weights`).
    sqrt_h : float
        sqrt of the node spacing.
    edge_point : bool
        Whether point 0 is the stick edge between nodes (its segment is shorter).
    h_first : float
        Length of the first segment, y[1] - y[0].

    Returns
    -------
    (float, float)
        The known part and the weight of the shear at k.
    """
    known = 0.0
    start = 0
    if edge_point:
        wl, wr = _segment_weights(y[k] - y[0], y[k] - y[1], h_first)
        if k == 1:
            return wl * shear[0], wr
        known += wl * shear[0] + wr * shear[1]
        start = 1
    # the uniform segments start .. k: shear[start] ends none of them, shear[m > start] ends segment m - 1
    s0 = abel[0, k - start] * shear[start]
    # the weights are held reversed (distance d at N - 1 - d): the shear values start + 1 .. k - 1 meet the weights
    # N - k + start .. N - 2, both runs forward in memory, a dot product (BLAS). Not fast-math in the march: numba
    # compiles a function's callees with its fast-math flags and caches them so, and the interpolations the march
    # calls would then round differently wherever they were called from after it
    N = abel_weights.shape[0]
    a0 = N - k + start
    b0 = start + 1
    n = k - start - 1
    acc = np.dot(abel_weights[a0:a0 + n], shear[b0:b0 + n]) if n > 0 else 0.0
    return known + sqrt_h * (s0 + acc), sqrt_h * abel[1, 1]


@njit(cache=True)
def _combined_abel_weights(abel):
    """The weight of a shear value at distance d before the point evaluated, from both segments it ends and
    starts: ``abel[0, d] + abel[1, d + 1]`` (the second term absent at the last distance), held in reverse order
    (distance d at N - 1 - d), as :func:`_abel_known_part` reads them.

    Parameters
    ----------
    abel : ndarray (2, N)
        The unit Abel weights (:class:`~persson.slip.heating_arrays.Patch`).

    Returns
    -------
    ndarray (N,)
        Element N - 1 - d: the weight at distance d (0 at d = 0).
    """
    N = abel.shape[1]
    w = np.zeros(N)
    for d in range(1, N):
        w[N - 1 - d] = abel[0, d] + (abel[1, d + 1] if d + 1 < N else 0.0)
    return w


@njit(cache=True, inline="always")
def _node_temperature(base, coef, T_prev, slope, T0, mu_max, c, iv, w_speed, mv, ig, w_pressure, mg, values,
                      value_offset, n_temperature, y_fine, cap, dT_fine, h, w_temperature, contracted, n_min):
    """The temperature at a sliding point: the root of F(T) = T - base - coef mu(T), by the secant method from
    the previous point's temperature, with bisection on [base, base + 1.5 coef mu_max] where the secant fails;
    and the friction there (the last evaluation of the root search, not repeated by the caller).

    The secant's second point is a Newton step from the first guess with the slope of mu(T) that the point before
    ended with (mu(T) varies smoothly along the patch; F' = 1 - coef mu'), which saves about one friction
    evaluation per point against a fixed-point step; without a usable slope (the first point, after a bisection, an
    F' outside 0.2-5), the fixed-point step T = base + coef mu(guess). Either way the root is found to the same
    tolerance, |F| <= 1e-10 (1 + |T|).

    Parameters
    ----------
    base : float
        T0 + Lambda (known part of the Abel integral), deg C.
    coef : float
        Lambda times the weight of the point's own shear times p / sigma0 there, K.
    T_prev : float
        The first guess, deg C (extrapolated from the points before).
    slope : float
        d mu / dT the point before ended with, 1/K (NaN: none).
    T0 : float
        Background temperature of the sweep, deg C.
    mu_max : float
        Largest friction in the sweep's table (bounds the bisection).
    c : int
        The sweep.
    iv : int
        First speed node of the row's stencil.
    w_speed : ndarray (4,)
        Its weights.
    mv : int
        Speed nodes in the stencil.
    ig : int
        First pressure node of the point's stencil.
    w_pressure : ndarray (4,)
        Its weights.
    mg : int
        Pressure nodes in a stencil.
    values, value_offset, n_temperature : ndarray
        The friction lattice (:class:`~persson.slip.heating_arrays.FrictionLattice`).
    y_fine : ndarray (n_sweeps, n_fine)
        Its temperature coordinate y at T0 + k ``dT_fine`` (:class:`~persson.slip.heating_arrays.TemperatureAxis`).
    cap : float
        Largest rise tabulated, K.
    dT_fine : float
        Step of ``y_fine``, K.
    h : float
        Spacing of the lattice in y, decades.
    w_temperature : ndarray (4,)
        Scratch for the temperature weights.
    contracted, n_min : ndarray, int
        The row's table summed over its speed stencil (:func:`_speed_contracted`).

    Returns
    -------
    (float, float, float)
        The temperature, deg C, mu there, and d mu / dT from the last secant step, 1/K (NaN after a bisection).
    """
    Ta = T_prev if T_prev > base else base
    ma = _mu_row(iv, w_speed, mv, ig, w_pressure, mg, _x_at(y_fine, c, Ta - T0, cap, dT_fine, h), values,
                value_offset, n_temperature, w_temperature, contracted, n_min)
    Fa = Ta - base - coef * ma
    Tb = base + coef * ma
    if abs(Fa) <= 1e-10 * (1.0 + abs(Ta)):
        return Ta, ma, slope
    d = 1.0 - coef * slope  # F' with the previous point's slope (NaN fails both tests)
    if 0.2 < d < 5.0:
        Tb = Ta - Fa / d
    for _ in range(40):
        mb = _mu_row(iv, w_speed, mv, ig, w_pressure, mg, _x_at(y_fine, c, Tb - T0, cap, dT_fine, h), values,
                    value_offset, n_temperature, w_temperature, contracted, n_min)
        Fb = Tb - base - coef * mb
        if abs(Fb) <= 1e-10 * (1.0 + abs(Tb)):
            return Tb, mb, (mb - ma) / (Tb - Ta) if Tb != Ta else slope
        if Fb == Fa:
            break
        Tn = Tb - Fb * (Tb - Ta) / (Fb - Fa)
        Ta, Fa, ma = Tb, Fb, mb
        Tb = Tn
    # bisection on F, F(base) <= 0 <= F(base + coef mu_max)
    lo = base
    hi = base + coef * mu_max * 1.5 + 1e-12
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        mm = _mu_row(iv, w_speed, mv, ig, w_pressure, mg, _x_at(y_fine, c, mid - T0, cap, dT_fine, h), values,
                    value_offset, n_temperature, w_temperature, contracted, n_min)
        if mid - base - coef * mm > 0.0:
            hi = mid
        else:
            lo = mid
        if hi - lo < 1e-10 * (1.0 + abs(mid)):
            break
    T = 0.5 * (lo + hi)
    return T, _mu_row(iv, w_speed, mv, ig, w_pressure, mg, _x_at(y_fine, c, T - T0, cap, dT_fine, h), values,
                     value_offset, n_temperature, w_temperature, contracted, n_min), np.nan


@njit(cache=True, inline="always")
def _table_use(x, h, y_top):
    """How far up its temperature table the four-point stencil of a point reached: (y + h) / y_top (> 1: the point
    lies in the table's top interval, where the stencil is one-sided, or above the top).

    A point in the interval [k h, (k + 1) h] interpolates on the nodes k - 1 .. k + 2 when the table has them: as
    on a lattice without end. The table that keeps every point below its top interval therefore gives the answer
    of any taller table, whatever the calls that grew it (:func:`persson.slip.patch_friction` widens it until it
    does).

    Parameters
    ----------
    x : float
        The point's lattice coordinate y / h.
    h : float
        Spacing of the lattice in y, decades.
    y_top : float
        The table's top at the row's speed, decades.

    Returns
    -------
    float
        (y + h) / y_top; 2 when heated with only the T0 slice tabulated, 0 when not heated.
    """
    if x <= 0.0:
        return 0.0
    if y_top > 0.0:
        return (x + 1.0) * h / y_top
    return 2.0  # heated, but the table has only the T0 slice here


@njit(cache=True)
def _wheel_friction(y, shear, n_slide, a, xc, pure):
    """The wheel's friction coefficient: the stick part a x_c^2 / 2 exactly, the slide part by the trapezoid rule.

    Parameters
    ----------
    y : ndarray (N + 1,)
        x / l of the sliding points.
    shear : ndarray (N + 1,)
        Shear / sigma0 at them.
    n_slide : int
        The number of sliding points.
    a : float
        The bristle stress slope (:class:`~persson.slip.heating_arrays.PatchRows`).
    xc : float
        x_c / l.
    pure : bool
        Pure sliding: no stick part.

    Returns
    -------
    float
    """
    tot = 0.0 if pure else 0.5 * a * xc * xc
    for k in range(1, n_slide):
        tot += 0.5 * (y[k] - y[k - 1]) * (shear[k] + shear[k - 1])
    return tot


@njit(cache=True)
def _write_profiles(r, T0, a, xi, mu_T0, first_node, offset, T_slide, shear, g_slide, out):
    """Row r of the profiles: T0, the bristle stress and the stick limit in the stick zone (nodes before
    ``first_node``), the marched values behind it.

    Parameters
    ----------
    r : int
        The row.
    T0 : float
        Background temperature, deg C.
    a : float
        The bristle stress slope (:class:`~persson.slip.heating_arrays.PatchRows`).
    xi : ndarray (N,)
        The nodes x / l.
    mu_T0 : ndarray (N,)
        Friction at T0 at the nodes.
    first_node : int
        The first sliding node (N: the whole patch sticks).
    offset : int
        first_node minus the index of its sliding point (1 when point 0 is the stick edge between nodes, else 0).
    T_slide, shear, g_slide : ndarray (N + 1,)
        Temperature (deg C), shear / sigma0 and p / sigma0 at the sliding points.
    out : MarchOutputs
        Row r of ``temperature``, ``shear`` and ``mu_profile`` is filled.
    """
    for j in range(xi.size):
        if j < first_node:
            out.temperature[r, j] = T0
            out.shear[r, j] = a * xi[j]
            out.mu_profile[r, j] = mu_T0[j]
        else:
            k = j - offset
            out.temperature[r, j] = T_slide[k]
            out.shear[r, j] = shear[k]
            out.mu_profile[r, j] = shear[k] / g_slide[k] if g_slide[k] > 0.0 else mu_T0[j]


# ==================================================================================================== lattice
@njit(cache=True)
def _segment_weights(A, B, hs):
    r"""Weights (w_l, w_r) of :math:`\int_{x_k-A}^{x_k-B} f(x')/\sqrt{x_k - x'}\,dx'` for f linear on the
    segment of length hs = A - B (values f_l at its left end, f_r at its right end).

    Exact: :math:`I_0 = 2(\sqrt A - \sqrt B)`, :math:`I_1 = \int (x' - x_l)/\sqrt{x_k - x'} = A I_0 -
    \tfrac23(A^{3/2} - B^{3/2})`, :math:`w_r = I_1/h_s`, :math:`w_l = I_0 - w_r`; written without cancellation
    as :math:`w_l = h_s(2\sqrt A + 4\sqrt B)/(3(\sqrt A + \sqrt B)^2)`,
    :math:`w_r = h_s(4\sqrt A + 2\sqrt B)/(3(\sqrt A + \sqrt B)^2)`.

    Parameters
    ----------
    A : float
        Distance from the segment's left end to x_k.
    B : float
        Distance from its right end to x_k (>= 0).
    hs : float
        Length of the segment, A - B.

    Returns
    -------
    (float, float)
        w_l, w_r.
    """
    ra = np.sqrt(A)
    rb = np.sqrt(B)
    den = 3.0 * (ra + rb) * (ra + rb)
    return hs * (2.0 * ra + 4.0 * rb) / den, hs * (4.0 * ra + 2.0 * rb) / den


@njit(cache=True)
def _lagrange(nodes, start, n, x, w):
    """Four-point (or n-point when n < 4) Lagrange weights at x on increasing nodes (x clamped into their range).

    Parameters
    ----------
    nodes : ndarray
        Node coordinates; the n nodes used are ``nodes[start:start + n]``.
    start : int
        First node.
    n : int
        Number of nodes, >= 1.
    x : float
        Where to interpolate.
    w : ndarray (4,)
        Filled with the weights (first min(4, n)).

    Returns
    -------
    int
        Index (into ``nodes``) of the first node of the stencil.
    """
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
    a, b = 0, n - 1
    while b - a > 1:
        mid = (a + b) // 2
        if nodes[start + mid] <= x:
            a = mid
        else:
            b = mid
    k0 = a - 1
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
    """Lagrange weights at x on the n uniform nodes 0, 1, .., n - 1 (the four nearest; n when n < 4; x clamped into
    [0, n - 1]).

    Parameters
    ----------
    n : int
        Number of nodes, >= 1.
    x : float
        Where to interpolate, in node units.
    w : ndarray (4,)
        Filled with the weights.

    Returns
    -------
    int
        The first node of the stencil.
    """
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
    if m == 4:
        # the cubic's weights written out: the general product's divisions cost most of an interpolation
        t = x - k0
        t1, t2, t3 = t - 1.0, t - 2.0, t - 3.0
        a = t * t1
        b = t2 * t3
        w[0] = -t1 * b * (1.0 / 6.0)
        w[1] = t * b * 0.5
        w[2] = -a * t3 * 0.5
        w[3] = a * t2 * (1.0 / 6.0)
        return k0
    for i in range(m):
        wi = 1.0
        for k in range(m):
            if k != i:
                wi *= (x - (k0 + k)) / (i - k)
        w[i] = wi
    return k0


@njit(cache=True)
def _interp(c, lv, gq, x, lattice, wv, wg, wu):
    """mu of sweep c at (ln v_s, g, x = y / h) by tensor-product Lagrange interpolation (clamped at 0).

    Parameters
    ----------
    c : int
        The sweep.
    lv : float
        ln v_s, m/s.
    gq : float
        p / sigma0.
    x : float
        Lattice coordinate y / h of the temperature.
    lattice : FrictionLattice
        The friction tables.
    wv, wg, wu : ndarray (4,)
        Scratch for the speed, pressure and temperature weights.

    Returns
    -------
    float
    """
    nv = lattice.v_offset[c + 1] - lattice.v_offset[c]
    ng = lattice.g_nodes.size
    iv = _lagrange(lattice.log_speed, lattice.v_offset[c], nv, lv, wv)
    ig = _lagrange(lattice.g_nodes, _ZERO, ng, gq, wg)
    mv = 4 if nv >= 4 else nv
    mg = 4 if ng >= 4 else ng
    return _mu_at(iv, wv, mv, ig, wg, mg, x, lattice.values, lattice.value_offset, lattice.n_temperature, wu)


@njit(cache=True)
def _interp_rows(sweep, log_speed, lattice):
    """mu at (v_s, p = sigma0, T0) of every row.

    Parameters
    ----------
    sweep : ndarray of int64 (n,)
        The sweep of each row.
    log_speed : ndarray (n,)
        ln v_s of each row, m/s.
    lattice : FrictionLattice
        The friction tables.

    Returns
    -------
    ndarray (n,)
    """
    out = np.empty(sweep.size)
    wv = np.empty(4)
    wg = np.empty(4)
    wu = np.empty(4)
    for r in range(sweep.size):
        out[r] = _interp(sweep[r], log_speed[r], 1.0, 0.0, lattice, wv, wg, wu)
    return out


@njit(cache=True)
def _y_at(y_fine, c, dT, dT_fine):
    """y(T0 + dT) of sweep c by linear interpolation in its fine table (clamped to the table).

    Parameters
    ----------
    y_fine : ndarray (n_sweeps, n_fine)
        y at T0 + k ``dT_fine`` (:class:`~persson.slip.heating_arrays.TemperatureAxis`).
    c : int
        The sweep.
    dT : float
        Temperature rise, K.
    dT_fine : float
        Step of the fine table, K.

    Returns
    -------
    float
        y, decades.
    """
    n = y_fine.shape[1]
    x = dT / dT_fine
    if x <= 0.0:
        return y_fine[c, 0]
    j = int(x)
    if j >= n - 1:
        return y_fine[c, n - 1]
    t = x - j
    return y_fine[c, j] + t * (y_fine[c, j + 1] - y_fine[c, j])


@njit(cache=True)
def _x_at(y_fine, c, dT, cap, dT_fine, h):
    """Lattice coordinate y(T0 + dT) / h of sweep c, a rise above the cap taken at the cap.

    Parameters
    ----------
    y_fine : ndarray (n_sweeps, n_fine)
        y at T0 + k ``dT_fine`` (:class:`~persson.slip.heating_arrays.TemperatureAxis`).
    c : int
        The sweep.
    dT : float
        Temperature rise, K.
    cap : float
        Largest rise tabulated, K.
    dT_fine : float
        Step of ``y_fine``, K.
    h : float
        Spacing of the lattice in y, decades.

    Returns
    -------
    float
    """
    return _y_at(y_fine, c, dT if dT < cap else cap, dT_fine) / h


@njit(cache=True)
def _speed_contracted(lattice, iv, wv, mv):
    """A row's friction table summed over its speed stencil with the speed weights, on the temperature nodes that
    every node of the stencil has: ``out[b * n_min + k]`` for pressure node b and temperature node k.

    Where the temperature stencil is the same for all the speed nodes (below the top of the shortest table,
    :func:`_mu_row`), interpolating in it gives the tensor-product value of :func:`_mu_at` (to rounding) at a
    quarter of the cost: the march evaluates it several times at every patch node.

    Parameters
    ----------
    lattice : FrictionLattice
        The friction tables.
    iv : int
        First speed node of the row's stencil.
    wv : ndarray (4,)
        Its weights.
    mv : int
        Speed nodes in the stencil.

    Returns
    -------
    (ndarray, int)
        The contracted table (n_g * n_min,) and n_min, the fewest temperature nodes in the stencil.
    """
    ng = lattice.g_nodes.size
    out = np.zeros(ng * np.max(lattice.n_temperature[iv:iv + mv]))
    n_min = _speed_contract_into(lattice, iv, wv, mv, out)
    return out[:ng * n_min], n_min


@njit(cache=True)
def _speed_contract_into(lattice, iv, wv, mv, out):
    """:func:`_speed_contracted` written into ``out``.

    Parameters
    ----------
    lattice, iv, wv, mv
        As for :func:`_speed_contracted`.
    out : ndarray
        At least n_g times the stencil's fewest temperature nodes long; its first n_g * n_min entries are filled,
        the others left alone.

    Returns
    -------
    int
        n_min, the fewest temperature nodes in the stencil.
    """
    n_temperature = lattice.n_temperature
    values = lattice.values
    n_min = n_temperature[iv]
    for a in range(1, mv):
        if n_temperature[iv + a] < n_min:
            n_min = n_temperature[iv + a]
    ng = lattice.g_nodes.size
    out[:ng * n_min] = 0.0
    for a in range(mv):
        node = iv + a
        n_u = n_temperature[node]
        base = lattice.value_offset[node]
        for b in range(ng):
            for k in range(n_min):
                out[b * n_min + k] += wv[a] * values[base + b * n_u + k]
    return n_min


@njit(cache=True, inline="always")
def _mu_row(iv, wv, mv, ig, wg, mg, x, values, value_offset, n_temperature, wu, contracted, n_min):
    """:func:`_mu_at` from the row's speed-contracted table (:func:`_speed_contracted`) where the four-point
    temperature stencil is the same on every speed node (n_min >= 4 and int(x) <= n_min - 3: :func:`_lagrange_uniform`
    then picks the same nodes and weights whatever the table's length), else :func:`_mu_at` itself.

    Parameters
    ----------
    iv, wv, mv, ig, wg, mg, x, values, value_offset, n_temperature, wu
        As for :func:`_mu_at`.
    contracted, n_min : ndarray, int
        From :func:`_speed_contracted`.

    Returns
    -------
    float
    """
    if n_min >= 4 and x < n_min - 2.0:
        k0 = _lagrange_uniform(n_min, x, wu)
        out = 0.0
        for b in range(mg):
            row = (ig + b) * n_min + k0
            out += wg[b] * (wu[0] * contracted[row] + wu[1] * contracted[row + 1] + wu[2] * contracted[row + 2]
                            + wu[3] * contracted[row + 3])
        return out if out > 0.0 else 0.0
    return _mu_at(iv, wv, mv, ig, wg, mg, x, values, value_offset, n_temperature, wu)


@njit(cache=True)
def _mu_at(iv, wv, mv, ig, wg, mg, x, values, value_offset, n_temperature, wu):
    """Interpolated mu at the temperature lattice coordinate x = y / h, with the speed weights (iv, wv) and the
    pressure weights (ig, wg) already known (clamped at 0).

    Parameters
    ----------
    iv : int
        First speed node of the stencil (global index).
    wv : ndarray (4,)
        Its weights.
    mv : int
        Speed nodes in the stencil.
    ig : int
        First pressure node of the stencil.
    wg : ndarray (4,)
        Its weights.
    mg : int
        Pressure nodes in the stencil.
    x : float
        Lattice coordinate y / h of the temperature.
    values, value_offset, n_temperature : ndarray
        The friction values, the offsets of the speed nodes' blocks and their temperature nodes
        (:class:`~persson.slip.heating_arrays.FrictionLattice`; passed as arrays: this is the innermost kernel).
    wu : ndarray (4,)
        Scratch for the temperature weights.

    Returns
    -------
    float
    """
    out = 0.0
    for a in range(mv):
        node = iv + a
        n_u = n_temperature[node]
        ku = _lagrange_uniform(n_u, x, wu)
        m_u = 4 if n_u >= 4 else n_u
        base = value_offset[node]
        acc_g = 0.0
        for b in range(mg):
            row = base + (ig + b) * n_u + ku
            acc = 0.0
            for k in range(m_u):
                acc += wu[k] * values[row + k]
            acc_g += wg[b] * acc
        out += wv[a] * acc_g
    return out if out > 0.0 else 0.0
