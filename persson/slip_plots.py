"""Plots of the slip level (matplotlib, Agg; every function returns the figure; save with
:func:`persson.plots.save_figure`)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .errors import InputError  # noqa: E402

__all__ = ["plot_mu_slip", "plot_mu_speed", "plot_two_coefficient_map"]


def plot_mu_slip(result, *, fits=None, ax=None, title: str = "", mark_peaks: bool = True):
    """Family of mu-slip curves, one per speed.

    Parameters
    ----------
    result : persson.slip.SlipResult
        With 2D arrays (slip along axis 0, speed along axis 1; e.g. from ``slip[:, None]``, ``speed[None, :]``)
        or 1D arrays (one curve).
    fits : sequence of persson.tire.MagicFormulaFit, optional
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
            from .tire import peak

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
    """mu against speed with fitted friction-speed laws (:class:`persson.tire.FitResult`) and their parameters."""
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


def _axes(ax):
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.4, 4.4), constrained_layout=True)
        return fig, ax
    return ax.figure, ax
