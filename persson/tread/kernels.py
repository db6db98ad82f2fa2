r"""Numba kernels of the tread-element tool: the time march of a patterned tread over road profiles.

The physics is documented in :mod:`persson.tread.simulate` and ``docs/tread.md``; this module holds only the
compiled loops. Every kernel is called with keyword arguments (by :func:`persson.tread.simulate` and
:func:`persson.tread.slip_map`).

Model marched (the element tool whose paper "Tire/pavement friction: presentation of a comprehensive physical tool
through advanced contact modelling" numbers the equations used here, Eqs. 2-6; the element model of M. Kane and
co-workers, Int. J. Pavement Eng., doi:10.1080/10298436.2017.1369776):

* tread elements on a regular lattice of spacing ``dx_elem`` in each of ``n_rows`` rows; each row slides over its
  own road profile; all rows share one tread-base height ``b`` (the belt);
* material moves through the patch from the leading edge (patch position 0) to the trailing edge at the rolling
  speed ``v_roll`` = (1 - s) V; an element leaving at the trailing edge is replaced by a fresh one at the leading
  edge (undeformed), whose land/groove state is read from ``land`` by its material index;
* the tread surface moves over the road at ``v_slide`` = s V (Eq. 6); with ``shear_stiffness`` infinite every
  contacting element slides (the paper's model); with a finite one an element touching down adheres, its shear w
  (belt and tread, the brush model) growing by the sliding distance, until the force ``shear_stiffness * w``
  reaches the friction cone of Eq. 2; from then on it slides (force on the cone) until it leaves the patch. The
  shear changes the force, not the path over the road: the normal forces never depend on the adhesion state, which
  keeps the march stable and its result independent of the time step;
* normal force of an element in contact: Kelvin unit :math:`F = K u + C \dot u`, :math:`u` the compression
  (road height under the tip minus the unloaded tip height ``b + offset``), backward Euler in time; out of
  contact :math:`K u + C \dot u = 0` (Eq. 3), solved exactly, :math:`u \propto e^{-K t/C}`;
* the base height ``b`` is solved at every step so that the contact forces carry the load ``load``
  (Eq. 4) exactly: the forces are piecewise linear and monotone in ``b`` and the exact root is found by a
  Newton iteration that ends when the set of contacting elements stops changing;
* tangential force of a sliding element, Eq. 2:
  :math:`T = F (\sin\alpha + \mu\cos\alpha)/(\cos\alpha - \mu\sin\alpha)`, with
  :math:`\tan\alpha` the road's local slope under the tip and :math:`\mu` the local friction
  :math:`\mu_{loc}` at the element's nominal pressure ``F / area``; friction :math:`\mu(t) = \sum T / W`
  (Eq. 5) with ``load_total`` the tyre load W. On a flank with :math:`\tan\alpha \to 1/\mu` the denominator
  vanishes (a self-locking wedge): it is held at ``jam_min`` and the force of those contacts is traced apart
  (``jam_t``), being set by the cap rather than by the road.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

__all__ = ["march", "march_points"]


@njit(cache=True, fastmath={"reassoc", "contract", "arcp"})
def march(z, tan_alpha, dx_road, x_start, n_steps, dt, v_slide, v_roll, n_elem, dx_elem, land, shape, offset_scale,
          stiffness, damping, shear_stiffness, area, load, load_total, p0, dp, mu_table, jam_min, probe):
    r"""March one (slip, speed) point; return the time traces and the march diagnostics.

    Parameters
    ----------
    z : ndarray, shape (n_rows, n_road)
        Road heights of each row's profile at the road elements, m (x = j * dx_road).
    tan_alpha : ndarray, shape (n_rows, n_road)
        Local slope :math:`\tan\alpha` at the road elements (central differences), interpolated linearly between
        them like the heights.
    dx_road : float
        Road element size, m.
    x_start : float
        Road position of the patch's leading edge at t = 0, m (>= patch length).
    n_steps : int
        Number of time steps.
    dt : float
        Time step, s (``v_slide * dt <= dx_road``: no road element skipped).
    v_slide : float
        Sliding speed s V of the tread base over the road, m/s.
    v_roll : float
        Speed (1 - s) V of the tread material through the patch, m/s.
    n_elem : int
        Elements per row (the patch length is ``n_elem * dx_elem``).
    dx_elem : float
        Element spacing along the patch, m.
    land : ndarray of bool, shape (n_rows, n_material)
        Rubber (True) or groove (False) of each material element; column m is the m-th element to enter the
        patch (the first ``n_elem`` fill it at t = 0, front first). Needs ``n_material >= n_elem + shifts``.
    shape : ndarray, shape (n_shape,)
        Static pressure shape p / sigma0 on a uniform grid of the patch position xi / L in [0, 1] (leading edge
        first); the belt sits ``offset_scale * (max(shape) - shape)`` above its lowest point.
    offset_scale : float
        sigma0 * area / stiffness, m: the belt offset per unit of the shape.
    stiffness : float
        Normal stiffness K of one element, N/m (> 0).
    damping : float
        Normal damping C of one element, N s/m (>= 0).
    shear_stiffness : float
        Tangential stiffness of one element, N/m; ``inf`` makes the tip follow the base (pure sliding).
    area : float
        Nominal area of one element, m^2 (its pressure is F / area).
    load : float
        Load carried by the elements (the tyre load less any hydrodynamic lift), N (> 0).
    load_total : float
        Tyre load W that normalises the friction, N.
    p0 : float
        First pressure of ``mu_table``, Pa.
    dp : float
        Spacing of ``mu_table`` in pressure, Pa (any value > 0 when it has one entry).
    mu_table : ndarray, shape (n_p,)
        Local friction at the sliding speed on a uniform grid of pressure (fine enough for linear interpolation);
        clamped at its ends.
    jam_min : float
        Smallest denominator :math:`\cos\alpha - \mu\sin\alpha` (divided by :math:`\cos\alpha`) used in
        Eq. 2; steeper flanks are capped there and counted.
    probe : int
        Patch position (0 = leading edge) of the row-0 element whose compression is recorded; -1 for none.

    Returns
    -------
    mu_t, contact_t, penetration_t : ndarray, shape (n_steps,)
        Friction coefficient, fraction of rubber elements in contact, mean compression of the contacting
        elements (m) at each step.
    residual : float
        Largest relative load-balance error :math:`|\sum F - W| / W` over the steps.
    jammed : float
        Fraction of the contact element-steps whose Eq. 2 denominator was capped at ``jam_min``.
    stuck : float
        Fraction of the contact element-steps that adhered (inside the friction cone; 0 for pure sliding).
    probe_t : ndarray, shape (n_steps,) or (0,)
        Compression of the probed element at each step, m (empty without a probe).
    final : ndarray, shape (5, n_rows * n_elem)
        State after the last step, one column per element in patch order (row by row, leading edge first): road
        position of the tip (m), patch position (m), compression (m), normal force (N, 0 out of contact or in a
        groove), 1 for rubber and 0 for groove.
    jam_t : ndarray, shape (n_steps,)
        The part of ``mu_t`` carried by contacts whose Eq. 2 denominator was capped at ``jam_min``: the friction
        that scales with the cap (1/jam_min) rather than with the road.
    """
    n_rows = z.shape[0]
    n_road = z.shape[1]
    n_mat = land.shape[1]
    n_tot = n_rows * n_elem
    u = np.zeros(n_tot)             # compression of each slot
    w = np.zeros(n_tot)             # shear displacement of the element (belt and tread)
    slide = np.zeros(n_tot, dtype=np.bool_)  # has reached the friction cone since it entered the patch
    rubber = np.zeros(n_tot, dtype=np.bool_)
    a = np.zeros(n_tot)             # a_i: F_i = kappa * max(0, a_i - b)
    offs = np.zeros(n_elem)
    mu_t = np.zeros(n_steps)
    jam_t = np.zeros(n_steps)
    probe_t = np.zeros(n_steps if probe >= 0 else 0)
    contact_t = np.zeros(n_steps)
    pen_t = np.zeros(n_steps)
    rigid = not (shear_stiffness < np.inf)
    kappa = stiffness + damping / dt
    c_dt = damping / dt
    decay = math.exp(-stiffness * dt / damping) if damping > 0.0 else 0.0
    c_kappa = c_dt / kappa
    inv_dp = 1.0 / dp
    inv_dx = 1.0 / dx_road
    inv_area = 1.0 / area
    inv_kt = 1.0 / shear_stiffness
    n_shape = shape.shape[0]
    shape_step = (n_shape - 1) / (n_elem * dx_elem)
    g_max = 0.0
    for i in range(n_shape):
        g_max = max(g_max, shape[i])
    # slot k holds the element at patch position phase + ((k - head) mod n_elem) * dx_elem
    head = 0
    phase = 0.0
    next_mat = n_elem
    n_rubber = 0
    for r in range(n_rows):
        for k in range(n_elem):
            e = r * n_elem + k
            rubber[e] = land[r, k]
            if rubber[e]:
                n_rubber += 1
    x_front = x_start
    b = 0.0
    b_set = False
    target = load / kappa
    residual = 0.0
    n_jam = 0
    n_stuck = 0
    n_contact_steps = 0
    offs_phase = -1.0
    # the belt offset at the element lattice (patch positions j dx_elem), interpolated in the phase at every step
    lattice_offs = np.empty(n_elem + 1)
    for j in range(n_elem + 1):
        s = j * dx_elem * shape_step
        i0 = int(s)
        if i0 > n_shape - 2:
            i0 = n_shape - 2
        lattice_offs[j] = offset_scale * (g_max - shape[i0] - (s - i0) * (shape[i0 + 1] - shape[i0]))
    # tread elements on a multiple of the road grid share the interpolation weight: one floor per step, not per tip
    ratio = int(round(dx_elem / dx_road))
    lattice = ratio >= 1 and abs(dx_elem / dx_road - ratio) < 1e-9
    for n in range(n_steps):
        # material motion through the patch: at most one new element per step (dt is chosen so)
        phase += v_roll * dt
        x_front += (v_roll + v_slide) * dt
        if phase >= dx_elem:
            phase -= dx_elem
            head = (head - 1) % n_elem
            m = next_mat if next_mat < n_mat else n_mat - 1
            next_mat += 1
            for r in range(n_rows):
                e = r * n_elem + head
                if rubber[e]:
                    n_rubber -= 1
                rubber[e] = land[r, m]
                if rubber[e]:
                    n_rubber += 1
                u[e] = 0.0
                # it entered phase / v_roll ago: its shear after this step's increment is v_slide * phase / v_roll
                w[e] = v_slide * (phase / v_roll - dt)
                slide[e] = False
        # belt offsets at the patch positions (shared by the rows; unchanged while the phase is: locked wheel)
        if phase != offs_phase:
            offs_phase = phase
            g = phase / dx_elem
            for j in range(n_elem):
                offs[j] = lattice_offs[j] + g * (lattice_offs[j + 1] - lattice_offs[j])
        # the road under each tip: a_i = z(tip) - offset - C/(dt kappa) u_i, so that F_i = kappa (a_i - b)
        a_max = -np.inf
        total = 0.0  # sum of max(0, a_i - b) and its count at the previous step's b (the Newton warm start)
        m_act = 0
        front = x_front - phase
        pos = front * inv_dx
        i_front = int(math.floor(pos))
        f_front = pos - i_front
        for r in range(n_rows):
            e0 = r * n_elem
            for j in range(n_elem):
                k = head + j
                if k >= n_elem:
                    k -= n_elem
                e = e0 + k
                if not rubber[e]:
                    a[e] = -np.inf
                    continue
                # the tread surface follows the road at the sliding speed (Eq. 6)
                if lattice:
                    i = i_front - j * ratio
                    f = f_front
                else:
                    pos = (front - j * dx_elem) * inv_dx
                    i = int(math.floor(pos))
                    f = pos - i
                if i < 0:
                    i = 0
                    f = 0.0
                elif i > n_road - 2:
                    i = n_road - 2
                    f = 1.0
                zt = z[r, i] + f * (z[r, i + 1] - z[r, i])
                ae = zt - offs[j] - c_kappa * u[e]
                a[e] = ae
                if ae > a_max:
                    a_max = ae
                if ae > b:
                    total += ae - b
                    m_act += 1
        # base height: sum_i max(0, a_i - b) = target, exact (piecewise linear, convex, decreasing): Newton steps
        # until the contact set stops changing (the last step was then exact)
        m_prev = -1
        if not b_set or m_act == 0:
            b_set = True
            b = a_max - target  # the highest element alone carries the load: at or left of the root
            m_act = -1
        for it in range(200):
            if m_act < 0:
                total = 0.0
                cnt = 0
                for e in range(n_tot):  # grooves hold a = -inf: never in contact
                    d = a[e] - b
                    if d > 0.0:
                        total += d
                        cnt += 1
                m_act = cnt
            if m_act == m_prev:
                break
            b = b + (total - target) / m_act
            m_prev = m_act
            m_act = -1
        # element states and forces
        sum_f = 0.0
        sum_t = 0.0
        sum_tj = 0.0
        n_c = 0
        sum_u = 0.0
        for r in range(n_rows):
            e0 = r * n_elem
            for j in range(n_elem):
                k = head + j
                if k >= n_elem:
                    k -= n_elem
                e = e0 + k
                if not rubber[e]:
                    continue
                d = a[e] - b
                u_c = d + c_kappa * u[e]      # the road under the tip less the unloaded tip height
                if d > 0.0:
                    force = kappa * d
                    u[e] = u_c
                    sum_f += force
                    n_c += 1
                    sum_u += u_c
                    mu = _table(mu_table, p0, inv_dp, force * inv_area)
                    if lattice:
                        i = i_front - j * ratio
                        f = f_front
                    else:
                        pos = (front - j * dx_elem) * inv_dx
                        i = int(math.floor(pos))
                        f = pos - i
                    if i < 0:
                        i = 0
                        f = 0.0
                    elif i > n_road - 2:
                        i = n_road - 2
                        f = 1.0
                    t = tan_alpha[r, i] + f * (tan_alpha[r, i + 1] - tan_alpha[r, i])
                    den = 1.0 - mu * t
                    capped = den < jam_min
                    if capped:
                        den = jam_min
                        n_jam += 1
                    t_max = force * (t + mu) / den
                    if rigid or slide[e]:
                        tang = t_max
                        w[e] = max(t_max, 0.0) * inv_kt
                    else:
                        # brush: an adhering element shears (belt and tread) by the sliding distance until its
                        # force reaches the friction cone of Eq. 2; from then on it slides until it leaves the patch
                        w_trial = w[e] + v_slide * dt
                        t_trial = shear_stiffness * w_trial
                        den2 = 1.0 + mu * t
                        capped2 = den2 < jam_min
                        if capped2:
                            den2 = jam_min
                        t_min = force * (t - mu) / den2
                        if t_trial >= t_max:
                            tang = t_max
                            slide[e] = True
                            w[e] = max(t_max, 0.0) * inv_kt
                        elif t_trial < t_min:
                            tang = t_min
                            capped = capped2
                            slide[e] = True
                            w[e] = 0.0
                        else:
                            tang = t_trial
                            capped = False
                            w[e] = w_trial
                            n_stuck += 1
                    sum_t += tang
                    if capped:
                        sum_tj += tang
                else:
                    u_free = u[e] * decay
                    u[e] = u_c if u_c >= u_free else u_free
                    # off the road the element keeps its shear and its state (mostly the belt's deformation)
        n_contact_steps += n_c
        if probe >= 0:
            k = head + probe
            probe_t[n] = u[k - n_elem if k >= n_elem else k]
        mu_t[n] = sum_t / load_total
        jam_t[n] = sum_tj / load_total
        contact_t[n] = n_c / n_rubber if n_rubber > 0 else 0.0
        pen_t[n] = sum_u / n_c if n_c > 0 else 0.0
        err = abs(sum_f - load) / load
        if err > residual:
            residual = err
    jammed = n_jam / n_contact_steps if n_contact_steps > 0 else 0.0
    stuck = n_stuck / n_contact_steps if n_contact_steps > 0 else 0.0
    final = np.zeros((5, n_tot))
    for r in range(n_rows):
        for j in range(n_elem):
            k = head + j
            if k >= n_elem:
                k -= n_elem
            e = r * n_elem + k
            c = r * n_elem + j
            final[0, c] = x_front - phase - j * dx_elem
            final[1, c] = phase + j * dx_elem
            final[2, c] = u[e]
            final[3, c] = kappa * (a[e] - b) if (rubber[e] and a[e] > b) else 0.0
            final[4, c] = 1.0 if rubber[e] else 0.0
    return mu_t, contact_t, pen_t, residual, jammed, stuck, probe_t, final, jam_t


@njit(cache=True, parallel=True)
def march_points(z, tan_alpha, dx_road, x_start, n_steps, dt, v_slide, v_roll, n_elem, dx_elem, land, shape,
                 offset_scale, stiffness, damping, shear_stiffness, area, load, load_total, p0, dp, mu_table,
                 jam_min, skip, n_blocks):
    r"""March several (slip, speed) points in parallel and reduce each to its steady statistics.

    Parameters
    ----------
    z : ndarray, shape (n_rows, n_road)
        Road heights, m (shared by all points).
    tan_alpha : ndarray, shape (n_rows, n_road)
        Local slopes of the road elements (see :func:`march`).
    dx_road : float
        Road element size, m.
    x_start : float
        Road position of the leading edge at t = 0, m.
    n_steps : ndarray of int64, shape (n_points,)
        Time steps of each point.
    dt : ndarray, shape (n_points,)
        Time step of each point, s.
    v_slide, v_roll : ndarray, shape (n_points,)
        Sliding speed s V and rolling speed (1 - s) V of each point, m/s.
    n_elem : int
        Elements per row.
    dx_elem : float
        Element spacing, m.
    land : ndarray of bool, shape (n_rows, n_material)
        Rubber/groove state by material index (see :func:`march`), long enough for every point.
    shape : ndarray, shape (n_shape,)
        Static pressure shape along the patch (see :func:`march`).
    offset_scale : ndarray, shape (n_points,)
        Belt offset per unit shape of each point, m.
    stiffness, damping, shear_stiffness : ndarray, shape (n_points,)
        K (N/m), C (N s/m) and the tangential stiffness (N/m, ``inf``: pure sliding) of one element, per point.
    area : float
        Nominal area of one element, m^2.
    load : ndarray, shape (n_points,)
        Load carried by the elements at each point, N.
    load_total : float
        Tyre load W, N.
    p0, dp : float
        Pressure grid of ``mu_table``, Pa (see :func:`march`).
    mu_table : ndarray, shape (n_points, n_p)
        Local friction of each point on that grid.
    jam_min : float
        Smallest Eq. 2 denominator (see :func:`march`).
    skip : ndarray of int64, shape (n_points,)
        Steps of the transient left out of the averages.
    n_blocks : int
        Blocks of the block average (standard error of the mean).

    Returns
    -------
    stats : ndarray, shape (n_points, 8)
        Per point: mean mu, standard error of the mean mu, mean contact fraction, mean penetration (m), largest
        relative load-balance error, jammed fraction, stuck fraction, and the part of the mean mu carried by the
        jammed contacts (see :func:`march`).
    """
    n_points = v_slide.shape[0]
    stats = np.zeros((n_points, 8))
    for i in prange(n_points):
        mu_t, c_t, p_t, res, jam, stk, _, _, jam_t = march(
            z, tan_alpha, dx_road, x_start, n_steps[i], dt[i], v_slide[i], v_roll[i], n_elem, dx_elem, land, shape,
            offset_scale[i], stiffness[i], damping[i], shear_stiffness[i], area, load[i], load_total, p0,
            dp, mu_table[i], jam_min, np.int64(-1))  # int64, not a literal: march compiles once for both callers
        mean, err = block_mean(mu_t[skip[i]:], n_blocks)
        stats[i, 0] = mean
        stats[i, 1] = err
        stats[i, 2] = np.mean(c_t[skip[i]:])
        stats[i, 3] = np.mean(p_t[skip[i]:])
        stats[i, 4] = res
        stats[i, 5] = jam
        stats[i, 6] = stk
        stats[i, 7] = np.mean(jam_t[skip[i]:])
    return stats


@njit(cache=True)
def block_mean(x, n_blocks):
    r"""Mean of a correlated series and its standard error from block averages.

    Parameters
    ----------
    x : ndarray
        The series (after the transient).
    n_blocks : int
        Number of equal blocks (>= 2); the last ``len(x) % n_blocks`` samples are left out of the error only.

    Returns
    -------
    mean : float
        Mean of all of ``x``.
    stderr : float
        Standard deviation of the block means divided by sqrt(n_blocks) (Flyvbjerg & Petersen 1989).
    """
    n = x.shape[0]
    mean = np.mean(x)
    size = n // n_blocks
    if size < 1 or n_blocks < 2:
        return mean, np.nan
    means = np.empty(n_blocks)
    for k in range(n_blocks):
        means[k] = np.mean(x[k * size:(k + 1) * size])
    return mean, np.std(means) * math.sqrt(1.0 / (n_blocks - 1))


@njit(cache=True)
def _table(values, x0, inv_dx, x):
    """Linear interpolation of ``values`` on the uniform grid x0 + i / inv_dx; clamped at its ends.

    Parameters
    ----------
    values : ndarray (n,)
        Tabulated values (the local friction on its pressure grid).
    x0 : float
        Abscissa of the first node (same unit as ``x``).
    inv_dx : float
        Nodes per unit of the abscissa (1 / node spacing).
    x : float
        Where to interpolate.

    Returns
    -------
    float
        The interpolated value; the end values outside the grid.
    """
    n = values.shape[0]
    s = (x - x0) * inv_dx
    if s <= 0.0:
        return values[0]
    if s >= n - 1:
        return values[n - 1]
    i = int(s)
    return values[i] + (s - i) * (values[i + 1] - values[i])
