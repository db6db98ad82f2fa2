"""Plots of friction results (matplotlib, Agg; every function returns the figure)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .io import atomic_write  # noqa: E402

__all__ = ["plot_friction", "plot_scales", "save_figure"]


def plot_friction(result, title: str = "", ax=None):
    """mu (total, hysteresis, adhesion) and A/A0 against sliding speed (log axis)."""
    if ax is None:
        fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
    else:
        fig, ax2 = ax.figure, None
    v = result.speed
    ax.semilogx(v, np.atleast_1d(result.mu), "k-", label="mu total")
    ax.semilogx(v, np.atleast_1d(result.mu_hysteresis), "C0--", label="hysteresis")
    if np.any(np.atleast_1d(result.mu_adhesion) > 0):
        ax.semilogx(v, np.atleast_1d(result.mu_adhesion), "C1:", label="adhesion")
    ax.set_xlabel("sliding speed v (m/s)")
    ax.set_ylabel("friction coefficient")
    ax.set_title(title or f"T0 = {result.temperature:g} C, sigma0 = {result.pressure / 1e6:g} MPa")
    ax.legend()
    if ax2 is not None:
        ax2.loglog(v, np.atleast_1d(result.contact_area), "C2-")
        ax2.set_xlabel("sliding speed v (m/s)")
        ax2.set_ylabel("real contact area A/A0")
    return fig


def plot_scales(result, index: int = 0):
    """Per-scale detail at one speed: P(q), d mu/d ln q and T(q)."""
    fig, axes = plt.subplots(1, 3, figsize=(13, 3.8), constrained_layout=True)
    q = result.q
    axes[0].loglog(q, result.area_q[index])
    axes[0].set_ylabel("P(q) = A(q)/A0")
    axes[1].semilogx(q, result.dmu_dlnq[index])
    axes[1].set_ylabel("d mu / d ln q")
    axes[2].semilogx(q, result.temperature_q[index])
    axes[2].set_ylabel("T(q) (C)")
    for a in axes:
        a.set_xlabel("q (rad/m)")
    fig.suptitle(f"v = {result.speed[index]:.3g} m/s")
    return fig


def save_figure(fig, path, dpi: int = 120, *, overwrite: bool = False) -> Path:
    """Save ``fig`` as PNG atomically and close it; an existing file only with ``overwrite=True``."""
    from .io import check_overwrite

    path = check_overwrite(path, overwrite=overwrite)
    with atomic_write(path, "wb") as fh:
        fig.savefig(fh, format="png", dpi=dpi)
    plt.close(fig)
    return path
