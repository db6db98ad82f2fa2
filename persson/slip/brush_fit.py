"""The brush model with a Stribeck-type sliding friction, and its fit to a measured mu(slip) curve alone."""

from __future__ import annotations

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
def fit_brush(slip, mu, *, sigma=None, law: str = "stribeck", sakai_n: float | None = 2.0, fixed: dict | None = None,
              p0: dict | None = None) -> "BrushFit":
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
        Exponent of the pressure law held fixed (default 2, parabolic); None fits it.
    fixed : dict, optional
        Further parameters held fixed.
    p0 : dict, optional
        An extra starting point.

    Returns
    -------
    BrushFit
        ``values``/``stderr``/``covariance`` by parameter (``fit["mu_static"]``, ``fit.std("mu_static")``),
        ``rms``, ``dof`` and the peak, the slip at the peak and the locked-wheel value with their standard
        uncertainties. The standard errors come from the Jacobian at the optimum
        (:func:`scipy.optimize.curve_fit`).
    """
    from .fitting import _fit, _propagate, _xy
    from .peaks import _curve_peak

    x, y, sig = _xy(slip, mu, sigma, "slip")
    if np.any((x <= 0) | (x > 1)):
        raise InputError("slip: expected slip ratios in (0, 1] (1 = locked wheel)")
    if law not in ("stribeck", "two_coefficient"):
        raise InputError(f"law: expected \"stribeck\" or \"two_coefficient\", got {law!r}")
    fixed = dict(fixed or {})
    if sakai_n is not None:
        fixed.setdefault("sakai_n", positive(sakai_n, "sakai_n"))
    if law == "two_coefficient":
        fixed["slip_c"] = 0.0
    names = ("initial_slope", "mu_static", "mu_dynamic", "slip_c", "sakai_n")
    bounds = dict(_BRUSH_BOUNDS)
    if law == "two_coefficient":
        bounds["slip_c"] = (0.0, 0.0)
    # starting values from the data: the slope through the origin below half the peak slip, the peak, the tail
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
    if "sakai_n" not in fixed:
        # the exponent free: start from the better of the fits with n = 2 and n = 4 held
        pre = []
        for n in (2.0, 4.0):
            try:
                pre.append(_fit(f"brush_{law}", _stribeck_law, names, bounds, x, y, sig, {**fixed, "sakai_n": n},
                                starts, (), tol=1e-9, maxfev=1000))
            except InputError:
                continue
        if pre:
            best = min(pre, key=lambda q: q["rms"])
            starts = [dict(zip(names, best["values"]))] + starts[:1]
    # the brush integral is piecewise smooth in the parameters (the stick boundary moves across the patch nodes):
    # tolerances at 1e-9 (tighter ones never trigger at the kinks) and a bounded number of evaluations per start
    parts = _fit(f"brush_{law}", _stribeck_law, names, bounds, x, y, sig, fixed, starts,
                 (PACEJKA_BOOK, SAKAI_1981, CANUDAS_2003), tol=1e-9, maxfev=1000)
    vals, cov = parts["values"], parts["covariance"]

    def pk(v):
        return _curve_peak(lambda ss: _stribeck_law(np.clip(ss, 1e-9, 1.0), *v), 1e-6, 1.0, 801)

    peak_mu, peak_std = _propagate(lambda v: pk(v)[0], vals, cov)
    sp_, sp_std = _propagate(lambda v: pk(v)[1], vals, cov)
    lk, lk_std = _propagate(lambda v: float(_stribeck_law(1.0, *v)), vals, cov)
    return BrushFit(**parts, peak_mu=peak_mu, peak_mu_std=peak_std, slip_at_peak=sp_, slip_at_peak_std=sp_std,
                    locked_mu=lk, locked_mu_std=lk_std)
