"""Plots of the slip level (matplotlib, Agg; every function returns the figure; save with
:func:`persson.plots.save_figure`)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..errors import InputError  # noqa: E402

__all__ = ["plot_mu_slip", "plot_mu_speed", "plot_two_coefficient_map", "plot_slip_comparison", "plot_patch_profile"]


def plot_mu_slip(result, *, fits=None, ax=None, title: str = "", mark_peaks: bool = True):
    """Family of mu-slip curves, one per speed.

    Parameters
    ----------
    result : persson.slip.SlipResult
        With 2D arrays (slip along axis 0, speed along axis 1; e.g. from ``slip[:, None]``, ``speed[None, :]``)
        or 1D arrays (one curve).
    fits : sequence of persson.slip.MagicFormulaFit, optional
        Fitted curves drawn dashed, one per speed (same order as the columns).
    ax : matplotlib Axes, optional
    title : str
    mark_peaks : bool
        Mark the peak of each curve.
    """
    s = np.asarray(result.slip, dtype=float)
    mu = np.asarray(result.mu, dtype=float)
    V = np.asarray(result.speed, dtype=float)
    if mu.ndim == 1:
        s, mu, V = s[:, None], mu[:, None], V[:, None]
    if mu.ndim != 2 or mu.shape[0] < 2:
        raise InputError("result: expected mu over slips (axis 0) and speeds (axis 1)")
    s, V = np.broadcast_to(s, mu.shape), np.broadcast_to(V, mu.shape)
    fig, ax = _axes(ax)
    for j in range(mu.shape[1]):
        line, = ax.plot(100 * s[:, j], mu[:, j], "-", label=f"V = {V[0, j]:.3g} m/s")
        if mark_peaks and mu.shape[0] >= 3:
            from .peaks import peak

            pm, ps = peak(s[:, j], mu[:, j])
            ax.plot([100 * ps], [pm], "o", color=line.get_color(), ms=4)
        if fits is not None and j < len(fits) and fits[j] is not None:
            xx = np.linspace(0.0, 1.0, 400)
            ax.plot(100 * xx, fits[j](xx), "--", color=line.get_color(), lw=1)
    ax.set_xlabel("slip ratio s = (V - omega r)/V (%)")
    ax.set_ylabel("friction coefficient mu")
    ax.set_xlim(0, 100 * float(np.max(s)))
    ax.set_ylim(bottom=0)
    c = result.contact
    ax.set_title(title or f"brush model: l = {c.length * 1e3:g} mm, k = {c.stiffness:.3g} Pa/m, "
                          f"sigma0 = {result.pressure / 1e6:g} MPa, T0 = {result.temperature:g} C", fontsize=9)
    ax.legend(fontsize=8)
    return fig


def plot_mu_speed(speed, mu, *, fits=(), sigma=None, ax=None, title: str = "", logx: bool = True):
    """mu against speed with fitted friction-speed laws (:class:`persson.slip.FitResult`) and their parameters."""
    V = np.asarray(speed, dtype=float).ravel()
    m = np.asarray(mu, dtype=float).ravel()
    if V.size != m.size or V.size == 0 or np.any(V <= 0):
        raise InputError("speed, mu: expected equal-length arrays with speeds > 0")
    fig, ax = _axes(ax)
    if sigma is not None:
        ax.errorbar(V, m, yerr=np.broadcast_to(np.asarray(sigma, float), m.shape), fmt="ko", ms=3, label="data")
    else:
        ax.plot(V, m, "ko", ms=3, label="data")
    xx = np.geomspace(V.min(), V.max(), 300) if logx else np.linspace(V.min(), V.max(), 300)
    for f in fits:
        par = ", ".join(f"{n} = {v:.3g} ± {e:.2g}" for n, v, e in zip(f.names, f.values, f.stderr)
                        if n not in f.fixed)
        ax.plot(xx, f(xx), "-", label=f"{f.law}: {par}")
    if logx:
        ax.set_xscale("log")
    ax.set_xlabel("speed V (m/s)")
    ax.set_ylabel("friction coefficient mu")
    ax.set_title(title or "friction against speed", fontsize=9)
    ax.legend(fontsize=7)
    return fig


def plot_two_coefficient_map(bmap, ax=None):
    """Contours of peak mu / mu_s and of the slip at the peak over n1 = mu_D/mu_s and n2 = slope/mu_s."""
    if ax is None:
        fig, axes = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    else:
        fig, axes = ax.figure, [ax, None]
    X, Y = np.meshgrid(bmap.n2, bmap.n1)
    cs = axes[0].contourf(X, Y, bmap.peak_ratio, levels=20)
    fig.colorbar(cs, ax=axes[0], label="peak mu / mu_s")
    axes[0].set_xlabel("n2 = initial slope / mu_s")
    axes[0].set_ylabel("n1 = mu_D / mu_s")
    if axes[1] is not None:
        cs2 = axes[1].contourf(X, Y, 100 * bmap.slip_at_peak, levels=20)
        fig.colorbar(cs2, ax=axes[1], label="slip at peak (%)")
        axes[1].set_xlabel("n2 = initial slope / mu_s")
        axes[1].set_ylabel("n1 = mu_D / mu_s")
    fig.suptitle(f"two-coefficient brush, Sakai n = {bmap.sakai_n:g}")
    return fig


def plot_slip_comparison(slip, mu, *, mu_std=None, brush=None, magic_formula=None, persson=None, ax=None,
                         title: str = "", speed: float | None = None):
    """Measured mu(slip) against the brush model, the Magic Formula and the Persson model with the brush.

    Parameters
    ----------
    slip, mu : array_like
        The measured curve (one speed).
    mu_std : float or array_like, optional
        Standard uncertainties of ``mu`` (error bars).
    brush : persson.slip.BrushFit or callable, optional
        The brush-model fit (:func:`persson.slip.fit_brush`).
    magic_formula : persson.slip.MagicFormulaFit or MagicFormula or callable, optional
        A Magic Formula (:func:`persson.slip.fit_magic_formula`, :func:`persson.slip.magic_formula_from_peak`);
        its peak is marked.
    persson : persson.slip.SlipResult (1D over slip) or (slip, mu) pair or callable, optional
        The Persson model with the brush (:func:`persson.slip.mu_slip`, e.g. with patch heating).
    ax : matplotlib Axes, optional
    title : str
    speed : float, optional
        Rolling speed V of the curve (m/s), for the title.

    Returns
    -------
    matplotlib.figure.Figure
        Each model's legend entry gives its rms deviation from the measured points.
    """
    s = np.asarray(slip, dtype=float).ravel()
    m = np.asarray(mu, dtype=float).ravel()
    if s.size != m.size or s.size == 0 or not (np.all(np.isfinite(s)) and np.all(np.isfinite(m))):
        raise InputError("slip, mu: expected equal-length finite arrays")
    if np.any((s < 0) | (s > 1)):
        raise InputError("slip: expected slip ratios in [0, 1]")
    fig, ax = _axes(ax)
    if mu_std is not None:
        ax.errorbar(100 * s, m, yerr=np.broadcast_to(np.asarray(mu_std, dtype=float), m.shape), fmt="ko", ms=3,
                    label="measured")
    else:
        ax.plot(100 * s, m, "ko", ms=3, label="measured")
    lo = max(float(np.min(s[s > 0])) if np.any(s > 0) else 1e-3, 1e-4)
    xx = np.unique(np.concatenate([np.linspace(lo, 1.0, 300), s[s > 0]]))

    def rms_of(f):
        return float(np.sqrt(np.mean((np.asarray(f(np.clip(s, lo, 1.0)), dtype=float) - m) ** 2)))

    if brush is not None:
        ax.plot(100 * xx, brush(xx), "-", label=f"brush model (rms {rms_of(brush):.3g})")
    if magic_formula is not None:
        f = magic_formula.formula if hasattr(magic_formula, "formula") else magic_formula
        line, = ax.plot(100 * xx, f(xx), "--", label=f"Magic Formula (rms {rms_of(f):.3g})")
        if hasattr(magic_formula, "slip_at_peak") and hasattr(magic_formula, "peak_mu"):
            ax.plot([100 * magic_formula.slip_at_peak], [magic_formula.peak_mu], "^", color=line.get_color(), ms=6)
    if persson is not None:
        if hasattr(persson, "slip") and hasattr(persson, "mu"):
            ps_, pm_ = np.asarray(persson.slip, dtype=float).ravel(), np.asarray(persson.mu, dtype=float).ravel()
        elif callable(persson):
            ps_, pm_ = xx, np.asarray(persson(xx), dtype=float)
        else:
            ps_, pm_ = (np.asarray(a, dtype=float).ravel() for a in persson)
        if ps_.size != pm_.size or ps_.size < 2:
            raise InputError("persson: expected a curve over at least two slips")
        order = np.argsort(ps_)
        ps_, pm_ = ps_[order], pm_[order]
        dev = float(np.sqrt(np.mean((np.interp(s, ps_, pm_) - m) ** 2)))
        ax.plot(100 * ps_, pm_, "-.", lw=2, label=f"Persson + brush (rms {dev:.3g})")
    ax.set_xlabel("slip ratio s = (V - omega r)/V (%)")
    ax.set_ylabel("friction coefficient mu")
    ax.set_xlim(0, 100)
    ax.set_ylim(bottom=0)
    ax.set_title(title or ("friction against slip" + (f", V = {speed:.3g} m/s" if speed is not None else "")),
                 fontsize=9)
    ax.legend(fontsize=8)
    return fig


def plot_patch_profile(result, *, index=None, ax=None, title: str = ""):
    """Background temperature and shear stress along the contact patch (a :func:`persson.slip.mu_slip` result with
    patch heating).

    Parameters
    ----------
    result : persson.slip.SlipResult
        With ``result.patch`` (patch heating on, ``profiles=True``).
    index : sequence of index tuples, optional
        Which (slip[, speed]) entries to draw (default: up to five slips spread over the first speed).
    """
    prof = getattr(result, "patch", None)
    if prof is None:
        raise InputError("result: no profiles along the patch (needs a model with PatchHeating and profiles=True)")
    mu = np.asarray(result.mu, dtype=float)
    if index is None:
        if mu.ndim == 0:
            index = [()]
        else:
            n = mu.shape[0]
            rows = sorted(set(np.linspace(0, n - 1, min(5, n)).round().astype(int).tolist()))
            index = [(i,) + (0,) * (mu.ndim - 1) for i in rows]
    if ax is None:
        fig, axes = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    else:
        fig, axes = ax.figure, [ax, ax.twinx()]
    x = 1e3 * prof.x
    slip = np.broadcast_to(np.asarray(result.slip, dtype=float), mu.shape)
    speed = np.broadcast_to(np.asarray(result.speed, dtype=float), mu.shape)
    for idx in index:
        idx = tuple(idx)
        lab = f"s = {slip[idx]:.3g}, V = {speed[idx]:.3g} m/s"
        line, = axes[0].plot(x, prof.temperature[idx], "-", label=lab)
        axes[1].plot(x, prof.shear[idx], "-", color=line.get_color(), label=lab)
    axes[1].plot(x, prof.pressure / result.pressure, "k:", lw=1, label="p(x) / sigma0")
    axes[0].set_xlabel("x from the leading edge (mm)")
    axes[0].set_ylabel("background temperature (C)")
    axes[1].set_xlabel("x from the leading edge (mm)")
    axes[1].set_ylabel("shear stress / sigma0")
    axes[0].legend(fontsize=7)
    axes[1].legend(fontsize=7)
    fig.suptitle(title or "along the contact patch (patch heating)", fontsize=10)
    return fig


def _axes(ax):
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.4, 4.4), constrained_layout=True)
        return fig, ax
    return ax.figure, ax
