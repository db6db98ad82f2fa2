"""Plots of master curves and shift factors (matplotlib, Agg canvas; each function returns the Figure).

The figures are built with :class:`matplotlib.figure.Figure` and an Agg canvas, so they work without a display
and do not touch pyplot's global state; save them with ``fig.savefig(path)``.
"""

from __future__ import annotations

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from .errors import AccuracyWarning, InputError, ignoring
from .shift import EXTRAPOLATED_SHIFT

__all__ = ["plot_master_curve", "plot_shift_factors"]


def plot_master_curve(master, *, n_points: int = 400, show_data: bool = True, title: str | None = None) -> Figure:
    """E', E'' and tan delta against reduced frequency f a_T at T_ref: the master curve and the shifted data.

    Parameters
    ----------
    master : MasterCurve
        Or any material with ``E_reference``/``E`` and, for the data points, ``reduced``.
    n_points : int
        Points of the fitted curve.
    show_data : bool
        Plot the shifted data (coloured by measurement temperature) when available.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        Two panels: moduli (log-log) and tan delta.
    """
    red = getattr(master, "reduced", None)
    if red is not None:
        lo, hi = np.log10(red.omega.min()) - 0.5, np.log10(red.omega.max()) + 0.5
    elif getattr(master, "frequency_range", None) is not None:
        lo, hi = (np.log10(v) for v in master.frequency_range)
        lo, hi = lo - 1, hi + 1
    else:
        raise InputError("plot_master_curve: expected a MasterCurve (with .reduced or .frequency_range)")
    w = np.logspace(lo, hi, n_points)
    E = master.E_reference(w) if hasattr(master, "E_reference") else master.E(w)
    f = w / (2 * np.pi)
    fig = Figure(figsize=(7.0, 7.0))
    FigureCanvasAgg(fig)
    ax1, ax2 = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    if show_data and red is not None:
        c = red.T_C if red.T_C is not None else None
        kw = dict(s=8, alpha=0.6, cmap="coolwarm", c=c) if c is not None else dict(s=8, alpha=0.6)
        sc = ax1.scatter(red.f_Hz, red.E_storage, marker="o", label="E' data (shifted)", **kw)
        ax1.scatter(red.f_Hz, red.E_loss, marker="s", label="E'' data (shifted)", **kw)
        ax2.scatter(red.f_Hz, red.E_loss / red.E_storage, marker="o", **kw)
        if c is not None:
            fig.colorbar(sc, ax=[ax1, ax2], label="measured at T (C)")
    what = "Prony fit" if getattr(master, "representation", "prony") == "prony" else "interpolated"
    ax1.loglog(f, E.real, "k-", lw=1.5, label=f"E' ({what})")
    ax1.loglog(f, E.imag, "k--", lw=1.5, label=f"E'' ({what})")
    ax2.semilogx(f, E.imag / E.real, "k-", lw=1.5)
    ax1.set_ylabel("modulus (Pa)")
    ax2.set_ylabel("tan delta")
    ax2.set_xlabel("reduced frequency f a_T (Hz)")
    T_ref = getattr(master, "T_ref", None)
    q = getattr(master, "quality", None)
    ttl = title or (f"master curve at T_ref = {T_ref:g} C" if T_ref is not None else "master curve")
    if q is not None:
        ttl += f"\nRMS rel. residual E' {100 * q.rms_rel_storage:.1f} %, E'' {100 * q.rms_rel_loss:.1f} %"
    ax1.set_title(ttl, fontsize=10)
    ax1.legend(fontsize=8, loc="best")
    ax1.grid(True, which="both", alpha=0.3)
    ax2.grid(True, which="both", alpha=0.3)
    return fig


def plot_shift_factors(master, *, title: str | None = None) -> Figure:
    """log10 a_T of the isotherms against temperature, with the fitted WLF (and Arrhenius) law.

    Parameters
    ----------
    master : MasterCurve
        With ``shift_factors`` and ``shift``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    sf = getattr(master, "shift_factors", None)
    if sf is None:
        raise InputError("plot_shift_factors: this material has no per-isotherm shift factors "
                         "(built from a table?)")
    fig = Figure(figsize=(6.5, 4.5))
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    ax.plot(sf.T_C, sf.log10_aT, "o", label=f"isotherms ({sf.method})")
    shift = master.shift
    T = np.linspace(sf.T_C.min() - 5, sf.T_C.max() + 5, 300)
    wlf = getattr(shift, "wlf", None)
    if getattr(shift, "kind", "") == "wlf" and wlf is not None:
        T = T[T > wlf.T_ref - wlf.C2 + 1]           # the WLF law is singular below T_ref - C2
    with ignoring(AccuracyWarning, EXTRAPOLATED_SHIFT):     # extrapolating a tabulated law is the point here
        y = np.asarray(shift.log10_aT(T), dtype=float)
    describe = getattr(shift, "describe", None)
    text = describe() if callable(describe) else type(shift).__name__
    ax.plot(T, y, "k-", label=text if len(text) < 90 else text[:87] + "...")
    if np.any(sf.log10_bT):
        ax2 = ax.twinx()
        ax2.plot(sf.T_C, sf.log10_bT, "s", color="tab:red", ms=4, label="log10 b_T")
        ax2.set_ylabel("log10 b_T", color="tab:red")
    ax.axhline(0.0, color="0.7", lw=0.8)
    ax.set_xlabel("temperature (C)")
    ax.set_ylabel("log10 a_T")
    ax.set_title(title or "shift factors", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    return fig
