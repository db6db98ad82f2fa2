"""The brush model with a Stribeck-type sliding friction, and its fit to a measured mu(slip) curve alone."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .._checks import number, positive
from ..errors import InputError
from ._arrays import _slip_array
from .brush import BrushCurve, _brush, _sakai_nodes
from .fitting import FitResult
from .references import CANUDAS_2003, PACEJKA_BOOK, SAKAI_1981

__all__ = ["stribeck_brush_mu", "BrushFit", "fit_brush"]


# =========================================================================================================
# Brush model fitted to a measured curve (no friction model)
# =========================================================================================================
def _stribeck_law(slip, initial_slope, mu_static, mu_dynamic, slip_c, sakai_n, n_points=201):
    """mu(slip) of the Stribeck brush (see :func:`stribeck_brush_mu`), vectorised over slip."""
    s = np.asarray(slip, dtype=float)
    sf = s.ravel()
    xi, g, G = _sakai_nodes(float(sakai_n), n_points)
    with np.errstate(divide="ignore"):
        theta = np.where(sf < 1.0, sf / np.where(sf < 1.0, 1.0 - sf, 1.0), np.inf)
        decay = np.exp(-sf / slip_c) if slip_c > 0 else np.zeros_like(sf)
    slide = mu_dynamic + (mu_static - mu_dynamic) * decay
    mu, _, _ = _brush(xi, g, G, 2.0 * initial_slope * theta, np.full(sf.size, float(mu_static)), slide)
    return mu.reshape(s.shape)


@doi(PACEJKA_BOOK, SAKAI_1981, CANUDAS_2003)
def stribeck_brush_mu(slip, *, initial_slope: float, mu_static: float, mu_dynamic: float, slip_c: float,
                      sakai_n: float = 2.0, n_points: int = 201) -> BrushCurve:
    r"""Brush model whose sliding friction falls from the static to the dynamic value with the sliding speed.

    The brush of :func:`mu_slip` (bristle displacement :math:`\theta x`, :math:`\theta = s/(1-s)`, Sakai's
    pressure law, n = 2 parabolic) with the friction limit :math:`\mu_s p(x)` in the stick zone and, in the slide
    zone, the Stribeck-type law used for the brush elements of tire friction models (Canudas-de-Wit et al.,
    Vehicle System Dynamics 39, 189 (2003): :math:`g(v) = \mu_C + (\mu_S - \mu_C)e^{-|v/v_s|^\alpha}`), here with
    :math:`\alpha = 1` and at one rolling speed V, where :math:`v_s/v_c = s/s_c`:

    .. math:: \mu_{slide}(s) = \mu_D + (\mu_s - \mu_D)\,e^{-s/s_c}, \qquad
        \mu(s) = C_0\theta\xi_c^2 + \int_{\xi_c}^1 \mu_{slide}(s)\,\frac{p}{\sigma_0}\,d\xi,\quad
        2C_0\theta\xi_c = \mu_s\,p(\xi_c)/\sigma_0,

    :math:`C_0 = k l/(2\sigma_0)` the initial slope. ``slip_c = 0`` is the two-coefficient brush
    (:func:`two_coefficient_mu`). The curve rises with slope :math:`C_0`, peaks, and falls towards
    :math:`\mu_D + (\mu_s - \mu_D)e^{-1/s_c}` at the locked wheel.

    Parameters
    ----------
    slip : array_like
        Slip ratios in (0, 1].
    initial_slope : float
        :math:`C_0` (> 0).
    mu_static, mu_dynamic : float
        :math:`\mu_s > 0`, :math:`\mu_D \ge 0`.
    slip_c : float
        Decay slip :math:`s_c = v_c/V` (>= 0).
    sakai_n : float
        Exponent of Sakai's pressure law (2: parabolic).
    """
    s = _slip_array(slip)
    c0 = positive(initial_slope, "initial_slope")
    ms = positive(mu_static, "mu_static")
    md = number(mu_dynamic, "mu_dynamic")
    sc = number(slip_c, "slip_c")
    if md < 0:
        raise InputError(f"mu_dynamic: expected a value >= 0, got {md:g}")
    if sc < 0:
        raise InputError(f"slip_c: expected a value >= 0, got {sc:g}")
    n = positive(sakai_n, "sakai_n")
    xi, g, G = _sakai_nodes(n, n_points)
    sf = s.ravel().astype(float)
    with np.errstate(divide="ignore"):
        theta = np.where(sf < 1.0, sf / np.where(sf < 1.0, 1.0 - sf, 1.0), np.inf)
        decay = np.exp(-sf / sc) if sc > 0 else np.zeros_like(sf)
    mu, xc, _ = _brush(xi, g, G, 2.0 * c0 * theta, np.full(sf.size, ms), md + (ms - md) * decay)
    return BrushCurve(slip=s, mu=mu.reshape(s.shape), stick_fraction=xc.reshape(s.shape), mu_static=ms,
                      mu_dynamic=md, initial_slope=c0, sakai_n=n, citations=(PACEJKA_BOOK, SAKAI_1981, CANUDAS_2003))


@dataclass(frozen=True, eq=False)
class BrushFit(FitResult):
    """A brush-model fit (:func:`fit_brush`): parameters with standard errors and the curve's characteristics.

    Attributes (in addition to :class:`persson.slip.FitResult`)
    ----------------------------------------------------------
    peak_mu, peak_mu_std, slip_at_peak, slip_at_peak_std, locked_mu, locked_mu_std : float
        Largest mu on 0 < s <= 1, its slip, mu at s = 1, each with its standard uncertainty (linear
        propagation of the covariance).
    """

    peak_mu: float = 0.0
    peak_mu_std: float = 0.0
    slip_at_peak: float = 0.0
    slip_at_peak_std: float = 0.0
    locked_mu: float = 0.0
    locked_mu_std: float = 0.0


_BRUSH_BOUNDS = {"initial_slope": (1e-2, 1e5), "mu_static": (1e-3, 10.0), "mu_dynamic": (0.0, 10.0),
                 "slip_c": (1e-4, 100.0), "sakai_n": (0.5, 50.0)}


@doi(PACEJKA_BOOK, SAKAI_1981, CANUDAS_2003)
def fit_brush(slip, mu, *, sigma=None, law: str = "stribeck", sakai_n: float | None = None, fixed: dict | None = None,
              p0: dict | None = None, peak="auto") -> "BrushFit":
    r"""Fit the brush model to a measured mu(slip) curve at one speed, with standard errors.

    Parameters
    ----------
    slip, mu : array_like
        Slip ratios in (0, 1] and friction coefficients (more points than free parameters).
    sigma : float or array_like, optional
        Standard uncertainties of ``mu``. Given: the covariance is absolute
        (:math:`(J^T W J)^{-1}`, :math:`W = \sigma^{-2}`); without: it is scaled by the residual variance
        :math:`\chi^2/(n - k)` (the misfit of the law is then part of the error).
    law : {"stribeck", "two_coefficient"}
        ``"stribeck"`` (default): :func:`stribeck_brush_mu`, parameters ``initial_slope``, ``mu_static``,
        ``mu_dynamic``, ``slip_c``, ``sakai_n``; ``"two_coefficient"``: the same with ``slip_c = 0``
        (:func:`two_coefficient_mu`).
    sakai_n : float or None
        Exponent of Sakai's pressure law held fixed (2: parabolic); None (default) fits it (a parabolic pressure
        often cannot follow a measured curve: on the dry Magic Formula curve below its least-squares rms is 0.0067
        against 0.0016 with the exponent fitted).
    fixed : dict, optional
        Further parameters held fixed.
    p0 : dict, optional
        An extra starting point.
    peak : "auto", "data", None or float
        Where the fitted curve's maximum must lie. Least squares trades the peak against the rest of the curve
        when the brush law cannot follow the data's shape (on the dry Magic Formula curve B, C, D, E = 10, 1.9,
        1, 0.97 it puts the peak at 12.4 % slip instead of 18.0 %). The data's peak is located by the Magic
        Formula fit of the data (:func:`fit_magic_formula`, which reproduces any Magic Formula curve exactly), with
        its standard uncertainty :math:`\sigma_{s_p}`. ``"auto"`` (default): the least-squares fit, unless the
        Magic Formula describes the data better (smaller rms) and puts the peak more than :math:`2\sigma_{s_p}`
        away from the fit's: then the fit is repeated with its maximum held there, and the notes say so.
        ``"data"``: always held at the data's peak. A float: held at that slip. None: least squares only.
        A held peak is one more residual, the distance in slip of the curve's maximum (on 49 nodes within 0.06 of
        :math:`s_p`, refined by the parabola through the best three) from :math:`s_p`, its weight raised from 10 to
        3000 per unit data residual in three steps starting from the least-squares solution (a stationarity
        condition alone is met by a plateau); the uncertainty of :math:`s_p` is propagated to the parameters
        (:math:`\Sigma + g g^T \sigma_{s_p}^2`, :math:`g = dp/ds_p` by refits at :math:`s_p \pm \delta`).

    Returns
    -------
    BrushFit
        ``values``/``stderr``/``covariance`` by parameter (``fit["mu_static"]``, ``fit.std("mu_static")``),
        ``rms``, ``dof`` and the peak, the slip at the peak and the locked-wheel value with their standard
        uncertainties. The standard errors come from the Jacobian at the optimum
        (:func:`scipy.optimize.curve_fit`, or :func:`scipy.optimize.least_squares` with a held peak).
    """
    from .fitting import _fit, _xy

    x, y, sig = _xy(slip, mu, sigma, "slip")
    if np.any((x <= 0) | (x > 1)):
        raise InputError("slip: expected slip ratios in (0, 1] (1 = locked wheel)")
    if law not in ("stribeck", "two_coefficient"):
        raise InputError(f"law: expected \"stribeck\" or \"two_coefficient\", got {law!r}")
    held = _peak_option(peak)
    fixed = dict(fixed or {})
    if sakai_n is not None:
        fixed.setdefault("sakai_n", positive(sakai_n, "sakai_n"))
    if law == "two_coefficient":
        fixed["slip_c"] = 0.0
    bounds = dict(_BRUSH_BOUNDS)
    if law == "two_coefficient":
        bounds["slip_c"] = (0.0, 0.0)
    cites = (PACEJKA_BOOK, SAKAI_1981, CANUDAS_2003)
    starts = _brush_starts(x, y, p0)
    if "sakai_n" not in fixed:
        # the exponent free: start from the better of the fits with n = 2 and n = 4 held
        pre = []
        for n in (2.0, 4.0):
            try:
                pre.append(_fit(f"brush_{law}", _stribeck_law, _NAMES, bounds, x, y, sig, {**fixed, "sakai_n": n},
                                starts, (), tol=1e-9, maxfev=1000))
            except InputError:
                continue
        if pre:
            best = min(pre, key=lambda q: q["rms"])
            starts = [dict(zip(_NAMES, best["values"]))] + starts[:1]
    # the brush integral is piecewise smooth in the parameters (the stick boundary moves across the patch nodes):
    # tolerances at 1e-9 (tighter ones never trigger at the kinks) and a bounded number of evaluations per start
    parts = _fit(f"brush_{law}", _stribeck_law, _NAMES, bounds, x, y, sig, fixed, starts, cites, tol=1e-9,
                 maxfev=1000)
    sp, sp_std, note = _held_peak(held, x, y, sig, parts)
    if sp is not None:
        parts = _held_fit(law, x, y, sig, fixed, bounds, dict(zip(_NAMES, parts["values"])), cites, sp, sp_std,
                          note)
    elif note is not None:
        parts["notes"] = tuple(parts["notes"]) + (note,)
    vals, cov = parts["values"], parts["covariance"]
    (peak_mu, sp_, lk), (peak_std, sp_std_, lk_std) = _propagate_all(
        lambda v: (*_peak_of(v), float(_stribeck_law(1.0, *v))), vals, cov)
    return BrushFit(**parts, peak_mu=peak_mu, peak_mu_std=peak_std, slip_at_peak=sp_, slip_at_peak_std=sp_std_,
                    locked_mu=lk, locked_mu_std=lk_std)


_NAMES = ("initial_slope", "mu_static", "mu_dynamic", "slip_c", "sakai_n")
# weights of the residual of a held peak (its distance in slip, per unit data residual), raised in steps
_PEAK_WEIGHTS = (10.0, 300.0, 3000.0)


def _propagate_all(quantities, values, cov):
    """Values and standard uncertainties of the scalars ``quantities(values)`` (a tuple), by linear propagation of
    the covariance with central differences (one pair of evaluations per free parameter for all of them)."""
    v0 = np.array(quantities(values), dtype=float)
    free = np.flatnonzero(np.diag(cov) > 0)
    grad = np.zeros((v0.size, values.size))
    for i in free:
        h = 1e-6 * max(abs(values[i]), math.sqrt(cov[i, i]) * 1e-2, 1e-12)
        up, dn = values.copy(), values.copy()
        up[i] += h
        dn[i] -= h
        grad[:, i] = (np.array(quantities(up)) - np.array(quantities(dn))) / (2 * h)
    var = np.einsum("ki,ij,kj->k", grad, np.where(np.isfinite(cov), cov, 0.0), grad)
    std = np.sqrt(np.clip(var, 0.0, None))
    if not np.all(np.isfinite(cov[np.ix_(free, free)])):
        std = np.full(v0.size, np.inf)
    return tuple(float(a) for a in v0), tuple(float(a) for a in std)


def _peak_option(peak):
    if peak is None or (isinstance(peak, str) and peak in ("auto", "data")):
        return peak
    if isinstance(peak, str) or isinstance(peak, bool):
        raise InputError(f"peak: expected \"auto\", \"data\", None or a slip in (0, 1), got {peak!r}")
    sp = number(peak, "peak")
    if not 0.0 < sp < 1.0:
        raise InputError(f"peak: expected a slip in (0, 1), got {sp:g}")
    return float(sp)


def _held_peak(held, x, y, sig, parts):
    """(slip to hold the maximum at or None, its standard uncertainty, note) for the ``peak`` option ``held``."""
    if held is None:
        return None, 0.0, None
    if isinstance(held, float):
        return held, 0.0, f"peak held at the declared slip {held:g}"
    sp, sp_std, mf_rms = _data_peak(x, y, sig)
    if sp is None:
        return None, 0.0, "no interior peak in the data: least squares only" if held == "data" else None
    if not math.isfinite(sp_std):  # the Magic Formula's covariance is undetermined: the peak's spread unknown
        return None, 0.0, ("the data's peak could not be located with an uncertainty (Magic Formula covariance "
                           "undetermined): least squares only")
    if held == "data":
        return sp, sp_std, f"peak held at the data's peak, slip {sp:.4g} +- {sp_std:.2g} (Magic Formula fit)"
    fit_sp = _peak_of(parts["values"])[1]
    if mf_rms < parts["rms"] and abs(fit_sp - sp) > 2.0 * sp_std:
        return sp, sp_std, (f"peak held at the data's peak, slip {sp:.4g} +- {sp_std:.2g} (Magic Formula fit, "
                            f"rms {mf_rms:.2g}); least squares alone put it at {fit_sp:.4g} (rms {parts['rms']:.2g})")
    return None, 0.0, None


def _brush_starts(x, y, p0) -> list[dict]:
    """Starting values from the data: the slope through the origin below half the peak slip, the peak, the tail."""
    j = int(np.argmax(y))
    sp = float(max(x[j], 1e-3))
    small = x <= 0.5 * sp
    c0 = float(np.sum(x[small] * y[small]) / np.sum(x[small] ** 2)) if np.any(small) else 2.0 * y[j] / sp
    c0 = float(np.clip(max(c0, y[j] / sp), 1e-2, 1e5))
    ytail = float(y[np.argmax(x)])
    starts = [dict(initial_slope=c0, mu_static=1.1 * y[j], mu_dynamic=ytail, slip_c=max(2 * sp, 1e-3), sakai_n=2.0),
              dict(initial_slope=c0, mu_static=1.3 * y[j], mu_dynamic=0.8 * ytail, slip_c=max(5 * sp, 1e-3),
                   sakai_n=4.0),
              dict(initial_slope=2 * c0, mu_static=y[j], mu_dynamic=ytail, slip_c=max(0.5 * sp, 1e-3), sakai_n=2.0)]
    if p0:
        starts.insert(0, {**starts[0], **{k: number(v, f"p0[{k!r}]") for k, v in p0.items()}})
    return starts


def _peak_of(v) -> tuple[float, float]:
    from .peaks import _curve_peak

    return _curve_peak(lambda ss: _stribeck_law(np.clip(ss, 1e-9, 1.0), *v), 1e-6, 1.0, 801)


def _data_peak(x, y, sig):
    """(slip at the peak, its standard uncertainty, rms) of the Magic Formula fit of the data; (None, 0, inf) when
    the data have no interior peak or the fit fails."""
    import warnings

    from .magic import fit_magic_formula

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # an undetermined covariance only widens sigma_sp; it is not the result
            mf = fit_magic_formula(x, y, sigma=sig)
    except InputError:
        return None, 0.0, math.inf
    sp = float(mf.slip_at_peak)
    if not (x.min() < sp < min(x.max(), 1.0)) or not math.isfinite(sp):
        return None, 0.0, math.inf
    return sp, float(mf.slip_at_peak_std), float(mf.rms)


def _held_fit(law, x, y, sig, fixed, bounds, start, cites, sp, sp_std, note) -> dict:
    """Least squares with the curve's maximum held at ``sp``: the distance of the maximum from ``sp`` (located on a
    local grid, refined by the parabola through the best three nodes) is an extra residual whose weight rises in
    three steps from ``start`` (continuation keeps the path near the least-squares optimum); the covariance adds
    the propagated uncertainty of ``sp``."""
    from scipy.optimize import least_squares

    free = [n for n in _NAMES if n not in fixed]
    lo = np.array([bounds[n][0] for n in free], dtype=float)
    hi = np.array([bounds[n][1] for n in free], dtype=float)
    w_data = 1.0 if sig is None else 1.0 / sig
    w_peak = 1.0 if sig is None else 1.0 / float(np.min(sig))

    def full(p):
        v = np.array([fixed.get(n, np.nan) for n in _NAMES], dtype=float)
        v[[_NAMES.index(n) for n in free]] = p
        return v

    def solve(s_peak, p, steps, nfev):
        g = _local_grid(s_peak)
        xg = np.concatenate([x, g])
        for w in steps:
            def res(q):
                m = _stribeck_law(xg, *full(q))  # the data and the local grid in one evaluation
                return np.concatenate([(m[:x.size] - y) * w_data, [w * w_peak * (_grid_peak(g, m[x.size:]) - s_peak)]])

            p = np.clip(p, lo + 1e-12 * (np.abs(lo) + 1), hi - 1e-12 * (np.abs(hi) + 1))
            r = least_squares(res, p, bounds=(lo, hi), x_scale="jac", xtol=1e-10, ftol=1e-10, gtol=1e-10,
                              max_nfev=nfev)
            p = r.x
        return r

    p0 = np.array([start[n] for n in free], dtype=float)
    r = solve(sp, p0, _PEAK_WEIGHTS, 80)
    vals = full(r.x)
    resid = y - _stribeck_law(x, *vals)
    n_free = len(free)
    dof = int(x.size - n_free + 1)   # the held peak is one condition on the parameters
    J = r.jac
    try:
        cov_free = np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov_free = np.full((n_free, n_free), np.inf)
    if sig is None:  # scaled by the residual variance of the data (the held peak fits exactly)
        cov_free = cov_free * float(resid @ resid) / max(dof, 1)
    if sp_std > 1e-6:
        # sensitivity of the parameters to the held slip, by refits from the optimum
        d = max(sp_std, 1e-3)
        g = (solve(sp + d, r.x, _PEAK_WEIGHTS[-1:], 40).x - solve(sp - d, r.x, _PEAK_WEIGHTS[-1:], 40).x) / (2 * d)
        cov_free = cov_free + np.outer(g, g) * sp_std**2
    idx = [_NAMES.index(n) for n in free]
    cov = np.zeros((len(_NAMES), len(_NAMES)))
    cov[np.ix_(idx, idx)] = cov_free
    notes = [note]
    at_bound = [free[i] for i in range(n_free) if np.isclose(r.x[i], lo[i]) or np.isclose(r.x[i], hi[i])]
    if at_bound:
        notes.append(f"brush_{law}: parameter(s) {at_bound} at their bound; the uncertainties there are not "
                     "meaningful")
    return dict(law=f"brush_{law}", names=_NAMES, values=vals, stderr=np.sqrt(np.clip(np.diag(cov), 0.0, None)),
                covariance=cov, fixed=tuple(n for n in _NAMES if n in fixed), x=x, y=y, sigma=sig,
                rms=float(np.sqrt(np.mean(resid**2))), dof=dof, notes=tuple(notes), citations=tuple(cites),
                func=_stribeck_law)


def _local_grid(s_peak) -> np.ndarray:
    """Slips within 0.06 of ``s_peak`` (49 nodes) on which the held maximum is located."""
    return np.linspace(max(s_peak - 0.06, 1e-4), min(s_peak + 0.06, 1.0), 49)


def _grid_peak(g, m) -> float:
    """Slip of the largest of the values ``m`` on the grid ``g``, refined by the parabola through the best three
    nodes: a piecewise smooth function of the curve's parameters."""
    from .peaks import _parabola_vertex

    j = int(np.clip(np.argmax(m), 1, g.size - 2))
    return float(_parabola_vertex(g[j - 1:j + 2], m[j - 1:j + 2])[0])
