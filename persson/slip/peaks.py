"""Peaks of mu(slip) curves: the largest value and its slip, from samples or from a curve."""

from __future__ import annotations

import numpy as np

from ..errors import InputError

__all__ = ["peak"]


def _parabola_vertex(x, y):
    """Vertex (x_v, y_v) of the parabola through three points (arrays stacked on axis 0) and a validity mask."""
    x0, x1, x2 = x
    y0, y1, y2 = y
    d01 = (y1 - y0) / np.where(x1 != x0, x1 - x0, 1.0)
    d12 = (y2 - y1) / np.where(x2 != x1, x2 - x1, 1.0)
    c2 = (d12 - d01) / np.where(x2 != x0, x2 - x0, 1.0)
    ok = c2 < 0
    c2s = np.where(ok, c2, -1.0)
    # y = y1 + b (x - x1) + c2 (x - x0)(x - x1) ... written about x1: slope at x1 = d01 + c2 (x1 - x0)
    b1 = d01 + c2s * (x1 - x0)
    xv = x1 - b1 / (2.0 * c2s)
    yv = y1 - b1**2 / (4.0 * c2s)
    ok &= (xv >= x0) & (xv <= x2)
    return np.where(ok, xv, x1), np.where(ok, yv, y1), ok


def _curve_peak(f, lo: float = 0.0, hi: float = 1.0, n: int = 2001) -> tuple[float, float]:
    """(max f, argmax) of a smooth function on [lo, hi]: grid search then bounded Brent refinement."""
    from scipy.optimize import minimize_scalar

    s = np.linspace(lo, hi, n)
    y = f(s)
    j = int(np.argmax(y))
    if j == n - 1 or j == 0:
        return float(y[j]), float(s[j])
    r = minimize_scalar(lambda x: -float(f(np.asarray(x))), bounds=(s[j - 1], s[j + 1]), method="bounded",
                        options={"xatol": 1e-12})
    if r.success and -r.fun >= y[j]:
        return float(-r.fun), float(r.x)
    return float(y[j]), float(s[j])


# =========================================================================================================
# Peak of a tabulated curve
# =========================================================================================================
def peak(slip, mu, axis: int = -1):
    """Peak mu and the slip at the peak of tabulated curve(s) mu(slip), along ``axis``.

    The discrete maximum is refined by the parabola through it and its two neighbours (in the slip variable);
    a maximum at either end of the range is returned as it is. ``slip`` is broadcast against ``mu``.

    Returns
    -------
    (peak_mu, slip_at_peak) : floats for one curve, arrays for several.
    """
    m = np.asarray(mu, dtype=float)
    try:
        s = np.broadcast_to(np.asarray(slip, dtype=float), m.shape)
    except ValueError:
        raise InputError(f"slip, mu: shapes {np.shape(slip)} and {m.shape} do not broadcast") from None
    if m.ndim == 0 or m.shape[axis] < 3:
        raise InputError("mu: expected at least three points along the slip axis")
    if not (np.all(np.isfinite(m)) and np.all(np.isfinite(s))):
        raise InputError("slip, mu: NaN or infinite values")
    m = np.moveaxis(m, axis, -1)
    s = np.moveaxis(s, axis, -1)
    n = m.shape[-1]
    j = np.argmax(m, axis=-1)
    jm = np.clip(j, 1, n - 2)
    take = lambda a, d: np.take_along_axis(a, (jm + d)[..., None], -1)[..., 0]  # noqa: E731
    x = np.stack([take(s, d) for d in (-1, 0, 1)])
    y = np.stack([take(m, d) for d in (-1, 0, 1)])
    xv, yv, ok = _parabola_vertex(x, y)
    ok &= (j >= 1) & (j <= n - 2)
    pm = np.where(ok, yv, np.take_along_axis(m, j[..., None], -1)[..., 0])
    ps = np.where(ok, xv, np.take_along_axis(s, j[..., None], -1)[..., 0])
    if pm.ndim == 0:
        return float(pm), float(ps)
    return pm, ps
