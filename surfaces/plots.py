"""Plots (matplotlib, Agg): profiles, 1D and 2D PSDs with fitted models and cut-offs, height maps, HDC.

Every function returns the :class:`matplotlib.figure.Figure` (nothing is shown); pass ``ax=`` to draw into
an existing axes.
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg", force=False)  # headless: reports and CI have no display

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .psd import SelfAffine  # noqa: E402
from .spectra import gamma_factor  # noqa: E402

__all__ = ["plot_profiles", "plot_psd1d", "plot_psd", "plot_height_map", "plot_hdc"]


def plot_profiles(profiles, ax=None, max_profiles: int = 3, unit: str = "mm"):
    """Heights along x of the first ``max_profiles`` profiles; dropouts are gaps."""
    fig, ax = _fig_ax(ax)
    f = {"m": 1.0, "mm": 1e3, "um": 1e6}[unit]
    for p in list(profiles)[:max_profiles]:
        ax.plot(p.x * f, p.z * f, lw=0.6, label=f"{p.name} ({p.dropout_fraction:.1%} dropouts)")
    ax.set_xlabel(f"x ({unit})")
    ax.set_ylabel(f"height ({unit})")
    ax.set_title(getattr(profiles, "source", "") or "profiles", fontsize="small")
    ax.legend(fontsize="small")
    return fig


def plot_psd1d(psd1d, fit=None, ax=None):
    """1D PSD with its per-bin spread, an optional self-affine fit and the cut-offs qL and q_r marked."""
    fig, ax = _fig_ax(ax)
    q, C = psd1d.q, psd1d.C_values
    ax.loglog(q, C, ".-", ms=3, lw=0.8, label=r"$C_{1D}(q)$")
    lo = np.maximum(C - psd1d.spread, C * 1e-3)
    ax.fill_between(q, lo, C + psd1d.spread, alpha=0.25, lw=0, label="spread")
    if fit is not None:  # a SelfAffineFit of kind "1d": C1D = (C0 / Gamma factor) q^-(1+2H)
        qq = np.geomspace(fit.q_min, fit.q_max, 50)
        ax.loglog(qq, fit.C0 / gamma_factor(fit.hurst) * qq ** (-(1 + 2 * fit.hurst)), "k--", lw=1,
                  label=f"fit, H = {fit.hurst:.2f}")
    _mark(ax, {"q_L": psd1d.qL, "q_r": psd1d.q_r})
    ax.set_xlabel("q (rad/m)")
    ax.set_ylabel(r"$C_{1D}$ (m$^3$)")
    ax.legend(fontsize="small")
    return fig


def plot_psd(psd, fit=None, ax=None):
    """Isotropic 2D PSD; a fitted model (SelfAffineFit, RolloffFit or SelfAffine) dashed; cut-offs
    qL, q0, q_r, q1 marked; an extrapolated tail drawn dotted."""
    fig, ax = _fig_ax(ax)
    table = psd.tabulate() if isinstance(psd, SelfAffine) else psd
    q, C = table.q, table.C_values
    cut = psd.cutoffs
    if cut.extrapolated and cut.q_r is not None:
        i_r = max(int(np.searchsorted(q, cut.q_r * (1 + 1e-9))) - 1, 0)
        ax.loglog(q[:i_r + 1], C[:i_r + 1], "-", lw=1.2, label="C(q)")
        ax.loglog(q[i_r:], C[i_r:], ":", lw=1.2, label="extrapolated tail")
    else:
        ax.loglog(q, C, "-", lw=1.2, label="C(q)")
    if fit is not None:
        model = fit if isinstance(fit, SelfAffine) else (fit.model(q1=q[-1]) if hasattr(fit, "q0") else fit.model())
        qq = np.geomspace(*model.q_range, 100)
        ax.loglog(qq, model.C(qq), "k--", lw=1, label=f"fit, H = {model.hurst:.2f}")
    q0 = cut.q0 if cut.q0 is not None else getattr(fit, "q0", None)
    _mark(ax, {"q_L": cut.qL, "q_0": q0, "q_r": cut.q_r, "q_1": cut.q1})
    ax.set_xlabel("q (rad/m)")
    ax.set_ylabel(r"$C(q)$ (m$^4$)")
    ax.legend(fontsize="small")
    return fig


def plot_height_map(hmap, ax=None, unit: str = "um"):
    """Image of a height map."""
    fig, ax = _fig_ax(ax)
    f = {"m": 1.0, "mm": 1e3, "um": 1e6}[unit]
    Lx, Ly = hmap.size
    im = ax.imshow(hmap.z * f, origin="lower", extent=(0, Lx * 1e3, 0, Ly * 1e3), cmap="viridis")
    fig.colorbar(im, ax=ax, label=f"height ({unit})")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    return fig


def plot_hdc(h, fit=None, ax=None):
    """Height-difference correlation with Klüppel's fit."""
    fig, ax = _fig_ax(ax)
    ax.loglog(h.lag, h.C_z, ".", ms=4, label=r"$C_z(\lambda)$")
    if fit is not None:
        ax.loglog(h.lag, fit.C_z(h.lag), "k--", lw=1,
                  label=rf"fit H={fit.hurst:.2f}, $\xi_\perp$={fit.xi_perp:.3g} m, $\xi_\parallel$={fit.xi_par:.3g} m")
    ax.set_xlabel(r"$\lambda$ (m)")
    ax.set_ylabel(r"$C_z$ (m$^2$)")
    ax.legend(fontsize="small")
    return fig


def _fig_ax(ax):
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
        return fig, ax
    return ax.figure, ax


def _mark(ax, marks: dict) -> None:
    for name, value in marks.items():
        if value is not None:
            ax.axvline(value, color="0.5", lw=0.7, ls="--")
            ax.annotate(f"${name}$", (value, 1.0), xycoords=("data", "axes fraction"), fontsize="small",
                        ha="left", va="top", rotation=90)
