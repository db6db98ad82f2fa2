r"""Time-temperature superposition: the shift factors of DMA isotherms, found automatically.

The principle (Ferry 1980, ch. 11): for a thermorheologically simple material

.. math:: E(\omega, T) = b_T\, E(\omega a_T, T_{ref}),

so isotherms measured over a narrow frequency window, plotted against the reduced frequency
:math:`\omega a_T`, superpose into one master curve. :func:`shift_isotherms` finds :math:`\log_{10} a_T` (and
optionally :math:`\log_{10} b_T`) in two stages:

1. **pairwise** – adjacent isotherms, from the reference outwards: the shift minimising the mean squared
   mismatch in :math:`\log E'` and :math:`\log E''` (or :math:`\log\tan\delta`) over the overlap of the two
   shifted curves (each isotherm represented by a low-order polynomial in :math:`\log\omega`, allowed to reach
   ``extend`` decades beyond its data), searched on a grid over wide bounds (``max_step`` decades per step)
   and polished with a bounded scalar minimisation; the cost is divided by the number of overlapping points,
   so a small overlap is not favoured;
2. **global** – all shifts together: one smooth master curve per component, a penalised cubic B-spline
   (P-spline, Eilers & Marx 1996) in the reduced log-frequency, is fitted to all shifted points, and the
   shifts minimise its residual (variable projection: for given shifts the spline is a linear least-squares
   fit). This uses every overlap at once, not only neighbours.

The shift laws fitted to these shift factors (WLF, Arrhenius, both) and their fits live in
:mod:`materials.laws`; they are importable from here too, where they were first defined.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from frictioncite import doi

from .errors import AccuracyWarning, ConvergenceWarning, InputError, PhysicsWarning
from .laws import (R_GAS, Arrhenius, TemperatureShift, WLFArrhenius, WLFFit, fit_arrhenius, fit_wlf,
                   wlf_change_reference)

__all__ = ["ShiftFactors", "shift_isotherms", "WLFFit", "fit_wlf", "Arrhenius", "fit_arrhenius",
           "TemperatureShift", "WLFArrhenius", "wlf_change_reference", "R_GAS"]


# ==================================================================================================== results

@dataclass(frozen=True, eq=False, repr=False)
class ShiftFactors:
    r"""Shift factors of the isotherms of a DMA data set, relative to ``T_ref``.

    Attributes
    ----------
    T_C : ndarray
        Isotherm temperatures, deg C (increasing).
    log10_aT : ndarray
        Horizontal shifts: reduced frequency :math:`\omega a_T`.
    log10_bT : ndarray
        Vertical shifts (zeros unless asked for): :math:`E(\omega, T) = b_T E(\omega a_T, T_{ref})`.
    T_ref : float
        Reference temperature, deg C (:math:`a_T(T_{ref}) = 1`).
    method : str
        How they were obtained (``"automatic: E', E''"``, ``"user"``, ...).
    rms_log10 : float or None
        RMS mismatch (decades of modulus) of the shifted data about the smooth master curve, when computed.
    converged : bool
        False when the global refinement did not converge (also warned).
    rms_by_isotherm : ndarray or None
        That mismatch per isotherm (an isotherm far above the others does not superpose; warned).
    """

    T_C: np.ndarray
    log10_aT: np.ndarray
    log10_bT: np.ndarray
    T_ref: float
    method: str = "user"
    rms_log10: float | None = None
    converged: bool = True
    rms_by_isotherm: np.ndarray | None = None

    def __post_init__(self):
        T = np.array(self.T_C, dtype=float).ravel()
        a = np.array(self.log10_aT, dtype=float).ravel()
        b = np.zeros_like(a) if self.log10_bT is None else np.array(self.log10_bT, dtype=float).ravel()
        if not (T.size == a.size == b.size) or T.size == 0:
            raise InputError(f"shift factors: T_C, log10_aT and log10_bT must have the same non-zero length, "
                             f"got {T.size}, {a.size}, {b.size}")
        for name, v in (("T_C", T), ("log10_aT", a), ("log10_bT", b)):
            if not np.all(np.isfinite(v)):
                raise InputError(f"shift factors: {name} must be finite, got {v}")
        if not math.isfinite(self.T_ref):
            raise InputError(f"shift factors: T_ref must be finite, got {self.T_ref!r}")
        for name, v in (("T_C", T), ("log10_aT", a), ("log10_bT", b)):
            v.setflags(write=False)
            object.__setattr__(self, name, v)

    @property
    def aT(self) -> np.ndarray:
        """Horizontal shift factors a_T."""
        return 10.0 ** self.log10_aT

    @property
    def bT(self) -> np.ndarray:
        """Vertical shift factors b_T."""
        return 10.0 ** self.log10_bT

    def rereferenced(self, T_ref: float, log10_aT_at_new_ref: float, log10_bT_at_new_ref: float = 0.0):
        """The same shifts relative to a new reference temperature, given log aT (and log bT) there."""
        return replace(self, log10_aT=self.log10_aT - log10_aT_at_new_ref,
                       log10_bT=self.log10_bT - log10_bT_at_new_ref, T_ref=float(T_ref))

    def __repr__(self) -> str:
        rms = "" if self.rms_log10 is None else f", scatter {self.rms_log10:.3g} decades"
        return (f"ShiftFactors({self.T_C.size} isotherms {self.T_C.min():.4g}..{self.T_C.max():.4g} C, "
                f"log10 aT {self.log10_aT.max():.3g}..{self.log10_aT.min():.3g}, T_ref = {self.T_ref:.4g} C{rms})")

    def as_dict(self) -> dict:
        """Plain-data form (lists), e.g. for JSON."""
        return {"T_C": self.T_C.tolist(), "log10_aT": self.log10_aT.tolist(), "log10_bT": self.log10_bT.tolist(),
                "T_ref": self.T_ref, "method": self.method, "rms_log10": self.rms_log10,
                "converged": self.converged}

# ==================================================================================================== analysis

@doi("isbn:978-0-471-04894-7", "10.1214/ss/1038425655")
def shift_isotherms(dma, T_ref: float | None = None, *, using: str = "moduli", vertical: bool = False,
                    max_step: float = 8.0, extend: float = 1.0, refine: bool = True, smoothing: float = 0.3,
                    knots_per_decade: float = 4.0, robust: bool = True, reverse_tol: float = 0.1
                    ) -> ShiftFactors:
    r"""Horizontal (and optionally vertical) shift factors of DMA isotherms, found automatically.

    Parameters
    ----------
    dma : DMAData
        At least two isotherms with at least two frequencies each.
    T_ref : float, optional
        The isotherm nearest to ``T_ref`` is the reference (shift 0); default the middle isotherm. The shifts
        are relative to that isotherm's temperature, reported as ``T_ref`` of the result (use
        :func:`materials.master_curve` to refer them to an arbitrary temperature through the WLF fit).
    using : {"moduli", "tan_delta"}
        Horizontal shifts from :math:`\log E'` and :math:`\log E''` together, or from :math:`\log\tan\delta`
        alone (no vertical shift touches tan delta).
    vertical : bool
        Also find vertical shifts :math:`\log_{10} b_T` (E' and E'' shifted together). The pairwise stage then
        takes the horizontal shift from tan delta (untouched by b_T) and b_T from the mean mismatch of
        log E', log E''; the global stage fits all three with both shifts.
    max_step : float
        Largest shift between adjacent isotherms searched, decades: a warmer neighbour is searched over
        [-max_step, +reverse_tol] decades from the colder one (a_T decreases with temperature).
    reverse_tol : float
        How far (decades) a step may go the unphysical way (a_T increasing with T), to allow for noise.
    extend : float
        How far (decades) an isotherm's polynomial representation may be extrapolated when comparing
        neighbours whose windows barely overlap.
    refine : bool
        Run the global refinement of all shifts together (recommended).
    smoothing : float
        P-spline roughness penalty weight (per data point) in the global refinement.
    knots_per_decade : float
        B-spline knot density of the global master curve.
    robust : bool
        Soft-L1 loss in the global refinement, so that a few bad points (instrument resonance at the highest
        frequencies of cold isotherms) do not pull the shifts.

    Returns
    -------
    ShiftFactors

    Raises
    ------
    InputError
        One isotherm only, an isotherm with fewer than two frequencies, a bad option.
    """
    xs, Ys, T_iso, comps = _isotherm_arrays(dma, using, vertical)
    n = len(xs)
    if T_ref is None:
        ref = n // 2
    else:
        if not math.isfinite(T_ref):
            raise InputError(f"T_ref: expected a finite temperature in deg C, got {T_ref!r}")
        ref = int(np.argmin(np.abs(T_iso - T_ref)))
    if not (max_step > 0 and extend >= 0 and smoothing > 0 and knots_per_decade > 0):
        raise InputError("shift_isotherms: expected max_step > 0, extend >= 0, smoothing > 0, knots_per_decade > 0")

    # --- stage 1: pairwise, from the reference outwards
    log_aT = np.zeros(n)
    log_bT = np.zeros(n)
    extrapolated, failed, mismatch = [], [], []
    for k in range(ref + 1, n):       # warmer: shift to lower reduced frequency
        s, b, ok = _pair_shift(xs[k - 1] + log_aT[k - 1], Ys[k - 1] + log_bT[k - 1] * comps, xs[k], Ys[k], comps,
                               lo=log_aT[k - 1] - max_step, hi=log_aT[k - 1] + reverse_tol, extend=extend,
                               vertical=vertical, warmer=True)
        log_aT[k], log_bT[k] = s, b
        {"none": failed, "extrapolated": extrapolated, "mismatch": mismatch}.get(ok, []).append(T_iso[k])
    for k in range(ref - 1, -1, -1):  # colder: shift to higher reduced frequency
        s, b, ok = _pair_shift(xs[k + 1] + log_aT[k + 1], Ys[k + 1] + log_bT[k + 1] * comps, xs[k], Ys[k], comps,
                               lo=log_aT[k + 1] - reverse_tol, hi=log_aT[k + 1] + max_step, extend=extend,
                               vertical=vertical, warmer=False)
        log_aT[k], log_bT[k] = s, b
        {"none": failed, "extrapolated": extrapolated, "mismatch": mismatch}.get(ok, []).append(T_iso[k])
    if mismatch:
        warnings.warn(f"{dma.source}: the isotherm(s) at T = " + ", ".join(f"{t:.1f}" for t in mismatch)
                      + " C do not superpose on their neighbour at any shift within the bounds (rms mismatch "
                      "well above the scatter): too little overlap, or not thermorheologically simple; "
                      "check those shifts", AccuracyWarning, stacklevel=2)
    if extrapolated:
        warnings.warn(f"{dma.source}: the isotherm(s) at T = " + ", ".join(f"{t:.1f}" for t in extrapolated)
                      + " C do not overlap their neighbour within the search bounds; they were placed by "
                      f"extrapolating the neighbours' trends (up to {extend:g} decades): check those shifts",
                      AccuracyWarning, stacklevel=2)
    if failed:
        warnings.warn(f"{dma.source}: no overlap with the neighbouring isotherm for T = "
                      + ", ".join(f"{t:.1f}" for t in failed) + " C within +-" f"{max_step:g} decades; "
                      "these isotherms were placed by extrapolation (check the shifts)", AccuracyWarning,
                      stacklevel=2)

    method = "automatic: " + ("log tan delta" if using == "tan_delta" else "log E', log E''") + \
             (" + vertical bT" if vertical else "")
    rms = None
    by_iso = None
    converged = True
    if refine:
        log_aT, log_bT, rms, converged, by_iso = _global_refine(xs, Ys, comps, log_aT, log_bT, ref, vertical,
                                                                smoothing, knots_per_decade, robust, max_step,
                                                                reverse_tol)
        # scatter expected from the data alone: residual of a cubic in log omega through each isotherm
        noise = float(np.median([np.sqrt(np.mean((Y - np.column_stack(
            [np.polyval(np.polyfit(x, Y[:, j], min(3, x.size - 1)), x) for j in range(Y.shape[1])])) ** 2))
            for x, Y in zip(xs, Ys)]))
        bad = np.flatnonzero(by_iso > 3.0 * noise + 0.01)
        if bad.size:
            warnings.warn(f"{dma.source}: isotherm(s) at T = " + ", ".join(f"{T_iso[i]:.1f}" for i in bad)
                          + " C do not superpose on the master curve (rms mismatch "
                          + ", ".join(f"{by_iso[i]:.3f}" for i in bad)
                          + f" decades, against {noise:.3f} scatter within isotherms): check those shifts",
                          AccuracyWarning, stacklevel=2)
        method += ", pairwise then global P-spline refinement"
        if not converged:
            warnings.warn(f"{dma.source}: global refinement of the shift factors did not converge; "
                          "the result is reported with converged=False", ConvergenceWarning, stacklevel=2)
    else:
        method += ", pairwise"
    # physically a_T decreases with T; a clear reversal is a sign of a bad isotherm
    steps = np.diff(log_aT)
    if np.any(steps > 0.2):
        bad = [f"{T_iso[i]:.1f}->{T_iso[i + 1]:.1f} C" for i in np.flatnonzero(steps > 0.2)]
        warnings.warn(f"{dma.source}: log10 aT increases with temperature between {', '.join(bad)} "
                      "(expected a decrease); check those isotherms", PhysicsWarning, stacklevel=2)
    return ShiftFactors(T_C=T_iso.copy(), log10_aT=log_aT - log_aT[ref], log10_bT=log_bT - log_bT[ref],
                        T_ref=float(T_iso[ref]), method=method, rms_log10=rms, converged=converged,
                        rms_by_isotherm=by_iso)


# ==================================================================================================== helpers

def _isotherm_arrays(dma, using, vertical):
    """log10 omega and the log components per isotherm; comps[j] = 1 where a vertical shift applies."""
    if using not in ("moduli", "tan_delta"):
        raise InputError(f"using: expected 'moduli' or 'tan_delta', got {using!r}")
    if dma.n_isotherms < 2:
        raise InputError(f"{dma.source}: one isotherm only (T = {dma.T_isotherm[0]:.1f} C); time-temperature "
                         "superposition needs at least two isotherms")
    xs, Ys = [], []
    for k, idx in enumerate(dma.isotherm_indices()):
        if np.unique(dma.f_Hz[idx]).size < 2:
            raise InputError(f"{dma.source}: isotherm at T = {dma.T_isotherm[k]:.1f} C has fewer than two "
                             "frequencies; expected a frequency sweep")
        x = np.log10(dma.omega[idx])
        l1, l2 = np.log10(dma.E_storage[idx]), np.log10(dma.E_loss[idx])
        if vertical:
            Y = np.column_stack([l2 - l1, l1, l2])
        elif using == "tan_delta":
            Y = (l2 - l1)[:, None]
        else:
            Y = np.column_stack([l1, l2])
        xs.append(x)
        Ys.append(Y)
    if vertical:
        comps = np.array([0.0, 1.0, 1.0])
    elif using == "tan_delta":
        comps = np.array([0.0])
    else:
        comps = np.array([1.0, 1.0])
    return xs, Ys, np.asarray(dma.T_isotherm, dtype=float), comps


def _poly_deg(n):
    return 1 if n < 4 else (2 if n < 8 else 3)


def _pair_shift(xa, Ya, xb, Yb, comps, lo, hi, extend, vertical, warmer, step=0.02):
    """Shift s (and vertical b) placing isotherm b (x + s, Y + b) onto the already placed isotherm a.

    ``lo``, ``hi`` bound s (absolute, decades); ``warmer``: b is warmer than a.
    Returns (s, b, how): how is "overlap", "extrapolated" (no overlap of the data windows within the bounds;
    the neighbours' polynomial trends were extended by up to ``extend`` decades) or "none" (placed edge to edge).
    """
    from scipy import optimize
    m = Ya.shape[1]
    pa = [np.polyfit(xa, Ya[:, j], _poly_deg(xa.size)) for j in range(m)]
    pb = [np.polyfit(xb, Yb[:, j], _poly_deg(xb.size)) for j in range(m)]
    a_lo, a_hi = xa.min(), xa.max()
    b_lo, b_hi = xb.min(), xb.max()
    n_min = max(3, int(0.25 * min(xa.size, xb.size)))
    # horizontal-only components decide s when vertical shifts are on
    hj = [j for j in range(m) if comps[j] == 0] if vertical else list(range(m))
    vj = [j for j in range(m) if comps[j] == 1]

    def cost(s):
        extend = ext_used
        s = np.atleast_1d(np.asarray(s, dtype=float))[:, None]
        xb_s = xb[None, :] + s                                     # b's points in a's frame
        in_a = (xb_s >= a_lo - extend) & (xb_s <= a_hi + extend)
        xa_b = xa[None, :] - s                                     # a's points in b's frame
        in_b = (xa_b >= b_lo - extend) & (xa_b <= b_hi + extend)
        n_in = in_a.sum(axis=1) + in_b.sum(axis=1)
        ssq = np.zeros(s.shape[0])
        for j in hj:
            rb = Yb[None, :, j] - np.polyval(pa[j], xb_s)
            ra = Ya[None, :, j] - np.polyval(pb[j], xa_b)
            ssq += np.where(in_a, rb * rb, 0.0).sum(axis=1) + np.where(in_b, ra * ra, 0.0).sum(axis=1)
        out = ssq / np.maximum(n_in, 1) / len(hj)
        return np.where(n_in >= n_min, out, np.inf), in_a, in_b

    grid = np.arange(lo, hi + step / 2, step)
    # scatter of a's points about its own trend: the mismatch a good superposition should reach
    scatter = max(float(np.sqrt(np.mean((Ya[:, j] - np.polyval(pa[j], xa)) ** 2))) for j in hj)
    good_enough = 3.0 * scatter + 0.02
    # true overlap first; the polynomial trends are extrapolated only when that gives no (good) match
    ext_used = 0.0
    c, _, _ = cost(grid)
    best = float(np.min(c)) if np.any(np.isfinite(c)) else np.inf
    if extend > 0 and not math.sqrt(best) <= good_enough:
        ext_used = extend
        c_ext, _, _ = cost(grid)
        if np.any(np.isfinite(c_ext)) and float(np.min(c_ext)) < best:
            c = c_ext
        else:
            ext_used = 0.0
    i = int(np.argmin(c))
    res = optimize.minimize_scalar(lambda s: float(np.minimum(cost(s)[0][0], 1e300)), bounds=(grid[max(i - 1, 0)],
                                   grid[min(i + 1, grid.size - 1)]), method="bounded",
                                   options={"xatol": 1e-4})
    s = float(res.x) if np.isfinite(res.fun) and res.fun <= c[i] else float(grid[i])
    b = 0.0
    if vertical and vj:
        # vertical shift: mean log mismatch of E', E'' over the overlap at the chosen horizontal shift
        _, in_a, in_b = cost(s)
        diffs = []
        for j in vj:
            rb = Yb[:, j] - np.polyval(pa[j], xb + s)
            ra = Ya[:, j] - np.polyval(pb[j], xa - s)
            diffs.append(-rb[in_a[0]])
            diffs.append(ra[in_b[0]])
        d = np.concatenate(diffs)
        b = float(np.mean(d)) if d.size else 0.0
    how = "extrapolated" if ext_used > 0 else "overlap"
    # a neighbour that cannot be matched (rms mismatch far above the scatter about its own trend) is reported
    if how == "overlap" and math.sqrt(min(float(cost(s)[0][0]), c[i])) > good_enough:
        how = "mismatch"
    return s, b, how


def _global_refine(xs, Ys, comps, log_aT0, log_bT0, ref, vertical, smoothing, knots_per_decade, robust,
                   max_step, reverse_tol, max_move=2.0):
    """Refine all shifts together against one penalised B-spline master curve per component.

    The parameters are the steps between neighbouring isotherms (outwards from the reference), so that the
    physical bound on each step (a_T decreasing with T, up to ``reverse_tol``) is a simple box bound.
    """
    from scipy import interpolate, linalg, optimize
    n = len(xs)
    free = [k for k in range(n) if k != ref]
    sizes = np.array([x.size for x in xs])
    owner = np.repeat(np.arange(n), sizes)
    x_raw = np.concatenate(xs)
    Y = np.concatenate(Ys)                      # (N, m)
    N, m = Y.shape
    # fixed knots covering every reachable reduced frequency
    x0 = x_raw + log_aT0[owner]
    lo = x0.min() - max_move - 0.5
    hi = x0.max() + max_move + 0.5
    nseg = max(4, int(math.ceil((hi - lo) * knots_per_decade)))
    kdeg = 3
    inner = np.linspace(lo, hi, nseg + 1)
    t = np.concatenate([[lo] * kdeg, inner, [hi] * kdeg])
    nb = t.size - kdeg - 1
    D = np.diff(np.eye(nb), n=2, axis=0)
    lam = math.sqrt(smoothing * N / nb)
    P = lam * D

    nf = len(free)
    # s_free = C @ steps: each isotherm's shift is the sum of the steps on the path from the reference
    C = np.zeros((nf, nf))
    pos = {k: i for i, k in enumerate(free)}
    for i, k in enumerate(free):
        path = range(ref + 1, k + 1) if k > ref else range(k, ref)
        for j in path:
            C[i, pos[j]] = 1.0
    parent = np.array([k - 1 if k > ref else k + 1 for k in free])
    steps0 = log_aT0[free] - log_aT0[parent]

    def unpack(p):
        a = log_aT0.copy()
        b = log_bT0.copy() if vertical else np.zeros(n)
        a[free] = C @ p[:nf]
        if vertical:
            b[free] = p[len(free):]
        return a, b

    comp_rows = np.asarray(comps, dtype=float)

    PtP = P.T @ P
    n_pen = P.shape[0]
    npar = len(free) * (2 if vertical else 1)

    def solve(p):
        """Spline coefficients for shifts p; residuals and Kaufman's variable-projection Jacobian.

        Normal equations G c = B^T y with G = B^T B + P^T P (small, symmetric positive definite: the penalty
        makes it so even where no point falls on a basis function).
        """
        a, b = unpack(p)
        x = np.clip(x_raw + a[owner], lo, hi)
        B = interpolate.BSpline.design_matrix(x, t, kdeg).tocsr()   # sparse: 4 non-zeros per row
        Yc = Y - np.outer(b[owner], comp_rows)           # vertical shift acts on E', E'' only
        cho = linalg.cho_factor((B.T @ B).toarray() + PtP)
        coef = linalg.cho_solve(cho, B.T @ Yc)
        r = np.vstack([B @ coef - Yc, P @ coef])          # (N + n_pen, m)
        # slope of the fitted master curve at each point
        slope = np.column_stack([interpolate.BSpline(t, coef[:, j], kdeg).derivative()(x) for j in range(m)])
        # d(residual)/d(parameter) before projection, nonzero on data rows only: one column per (param, comp)
        V = np.zeros((N, npar, m))
        for i, k in enumerate(free):
            rows = np.flatnonzero(owner == k)
            V[rows, i, :] = slope[rows]
            if vertical:
                V[rows, len(free) + i, :] = comp_rows
        V = V.reshape(N, npar * m)
        X = linalg.cho_solve(cho, B.T @ V)
        W = np.vstack([V - B @ X, -(P @ X)])               # (I - A A^+) dA/dp c  (Kaufman 1975)
        W = W.reshape(N + n_pen, npar, m)
        J = W.transpose(2, 0, 1).reshape(m * (N + n_pen), npar)
        J[:, :nf] = J[:, :nf] @ C                          # chain rule: shifts = C @ steps
        return r.ravel(order="F"), J

    cache = {}

    def fun(p):
        key = p.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = solve(p)
        return cache[key][0]

    def jac(p):
        key = p.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = solve(p)
        return cache[key][1]

    residuals = fun

    p0 = np.concatenate([steps0] + ([log_bT0[free]] if vertical else []))
    lb = p0 - max_move
    ub = p0 + max_move
    warm = np.array([k > ref for k in free])
    lb[:nf] = np.maximum(lb[:nf], np.where(warm, -max_step, -reverse_tol))
    ub[:nf] = np.minimum(ub[:nf], np.where(warm, reverse_tol, max_step))
    p0[:nf] = np.clip(p0[:nf], lb[:nf], ub[:nf])
    if vertical:
        lb[len(free):] = p0[len(free):] - 1.0
        ub[len(free):] = p0[len(free):] + 1.0
    r0 = residuals(p0)
    kw = {}
    if robust:
        data_rows = np.concatenate([np.arange(N) + j * (N + P.shape[0]) for j in range(m)])
        mad = float(np.median(np.abs(r0[data_rows])))
        kw = {"loss": "soft_l1", "f_scale": max(3.0 * 1.4826 * mad, 1e-3)}
    # lsmr avoids a dense SVD of the Jacobian each iteration (many rows, few columns); scipy's 2-D subspace step
    # needs at least two parameters, so tiny problems use the exact solver
    solver = "lsmr" if p0.size > 2 else "exact"
    sol = optimize.least_squares(fun, p0, jac=jac, bounds=(lb, ub), x_scale=1.0, tr_solver=solver,
                                 xtol=1e-8, ftol=1e-10, gtol=1e-10, max_nfev=100 * (len(p0) + 1), **kw)
    a, b = unpack(sol.x)
    r = residuals(sol.x)
    data = np.stack([r[j * (N + P.shape[0]): j * (N + P.shape[0]) + N] for j in range(m)], axis=1)
    rms = float(np.sqrt(np.mean(data ** 2)))
    by_iso = np.sqrt(np.bincount(owner, weights=np.mean(data ** 2, axis=1), minlength=n) / sizes)
    return a, b, rms, bool(sol.status > 0), by_iso
