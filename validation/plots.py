"""Plots of comparisons, diagnoses and improvement steps (matplotlib, Agg; each function returns the figure)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

__all__ = ["plot_mu_speed", "plot_mu_slip", "plot_residuals", "plot_signatures", "plot_steps", "plot_residual_slip"]

_MAX_PANELS = 4
_MAX_SLIP_CURVES = 8


def plot_mu_speed(cmp, curve_points: int = 40):
    """Measured (points, error bars from mu_std) and predicted (lines) mu against sliding speed.

    One panel per pressure, one colour per temperature; wet rows hollow markers and dashed lines. Only the
    pure-sliding rows (slip = 1) are shown. Every curve comes from one prediction of the model's own path
    (:class:`validation.predict.Predictor`: the contact patch with patch heating, ``Wet`` on wet rows). A fitted
    model (``cmp.covariance``) is drawn with its 68 % band (shaded, :mod:`validation.band`); a fitted model
    without one says why under the figure (``cmp.band_note``).
    """
    m = cmp.measurements
    sl = m.is_sliding
    pressures = np.unique(m.pressure[sl]) if np.any(sl) else np.array([])
    if pressures.size > _MAX_PANELS:
        pressures = pressures[np.linspace(0, pressures.size - 1, _MAX_PANELS).round().astype(int)]
    n = max(1, pressures.size)
    fig, axes = plt.subplots(1, n, figsize=(4.6 * n + 0.6, 4.0), squeeze=False, sharey=True)
    fig.subplots_adjust(left=0.35 / n + 0.04, right=0.98, bottom=0.13, top=0.86, wspace=0.08)
    axes = axes[0]
    if not np.any(sl):
        axes[0].text(0.5, 0.5, "no pure-sliding rows (slip = 1)", ha="center", va="center",
                     transform=axes[0].transAxes)
        return _light(fig)
    temps = np.unique(m.temperature[sl])
    colors = {T: c for T, c in zip(temps, _temperature_colors(temps.size))}
    curves = {}
    for p in pressures:
        for T in temps:
            for wet in (False, True):
                sel = sl & (m.pressure == p) & (m.temperature == T) & (m.wet == wet)
                if np.any(sel):
                    v = m.speed[sel]
                    curves[(p, T, wet)] = np.geomspace(v.min() / 1.5, v.max() * 1.5, curve_points)
    mu, hw = _predict_curves(cmp, {k: (np.ones(v.size), v, k[1], k[0], k[2]) for k, v in curves.items()})
    for ax, p in zip(axes, pressures):
        for T in temps:
            for wet in (False, True):
                sel = sl & (m.pressure == p) & (m.temperature == T) & (m.wet == wet)
                if not np.any(sel):
                    continue
                v = m.speed[sel]
                c = colors[T]
                lab = f"{T:g} C" + (" wet" if wet else "")
                kw = dict(mfc="none") if wet else {}
                if m.mu_std is not None:
                    ax.errorbar(v, m.mu[sel], yerr=m.mu_std[sel], fmt="o", color=c, ms=4, capsize=2, label=lab,
                                **kw)
                else:
                    ax.plot(v, m.mu[sel], "o", color=c, ms=4, label=lab, **kw)
                if mu is not None:
                    key = (p, T, wet)
                    ax.plot(curves[key], mu[key], "--" if wet else "-", color=c, lw=1.2)
                    if hw is not None:
                        ax.fill_between(curves[key], mu[key] - hw[key], mu[key] + hw[key], color=c, alpha=0.2,
                                        lw=0)
        ax.set_xscale("log")
        ax.set_xlabel("sliding speed v (m/s)")
        ax.set_title(f"sigma0 = {p / 1e6:g} MPa", fontsize=9)
        ax.grid(alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, title=_band_legend(cmp, hw), title_fontsize=7)
    axes[0].set_ylabel("friction coefficient mu")
    _band_caption(fig, cmp, hw)
    fig.suptitle(f"{cmp.name}: mu(v), effects {', '.join(cmp.effects) or 'none'}", fontsize=10)
    return _light(fig)


def _temperature_colors(n: int):
    """Distinct colours from cold (blue) to hot (red), none too pale to see."""
    if n == 1:
        return [plt.cm.turbo(0.15)]
    return [plt.cm.turbo(x) for x in np.linspace(0.1, 0.9, n)]


def plot_mu_slip(cmp, curve_points: int = 40):
    """Measured (points, error bars from mu_std) and predicted (lines) mu against slip ratio, one curve per series
    / condition (the model's own prediction path: the brush model, with patch heating along the patch when the
    model has it); a fitted model with its 68 % band, as in :func:`plot_mu_speed`."""
    m = cmp.measurements
    rows = ~m.is_sliding
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    fig.subplots_adjust(left=0.11, right=0.97, bottom=0.13, top=0.91)
    if not np.any(rows):
        ax.text(0.5, 0.5, "no rows with slip < 1", ha="center", va="center", transform=ax.transAxes)
        return _light(fig)
    keys = {}
    for i in np.flatnonzero(rows):
        k = (m.series[i], float(m.speed[i]), float(m.temperature[i]), float(m.pressure[i]), bool(m.wet[i]))
        keys.setdefault(k, []).append(i)
    shown = list(keys.items())[:_MAX_SLIP_CURVES]
    grids = {}
    for k, idx in shown:
        ser, V, T, p, wet = k
        s = np.geomspace(max(float(m.slip[idx].min()) / 1.5, 1e-4), 1.0, curve_points)
        grids[k] = (s, np.full(s.size, V), T, p, wet)
    mu, hw = _predict_curves(cmp, grids)
    for j, (k, idx) in enumerate(shown):
        ser, V, T, p, wet = k
        # the sliding rows (slip = 1) of the same condition belong to the curve
        same = (m.is_sliding & (m.speed == V) & (m.temperature == T) & (m.pressure == p) & (m.wet == wet))
        idx = np.concatenate([np.asarray(idx), np.flatnonzero(same)])
        c = f"C{j % 10}"
        lab = (f"{ser}: " if ser else "") + f"V={V:g} m/s, {T:g} C, {p / 1e6:g} MPa" + (" wet" if wet else "")
        if m.mu_std is not None:
            ax.errorbar(m.slip[idx], m.mu[idx], yerr=m.mu_std[idx], fmt="o", color=c, ms=4, capsize=2, label=lab)
        else:
            ax.plot(m.slip[idx], m.mu[idx], "o", color=c, ms=4, label=lab)
        if mu is not None:
            ax.plot(grids[k][0], mu[k], "-", color=c, lw=1.2)
            if hw is not None:
                ax.fill_between(grids[k][0], mu[k] - hw[k], mu[k] + hw[k], color=c, alpha=0.2, lw=0)
    if len(keys) > _MAX_SLIP_CURVES:
        ax.text(0.01, 0.01, f"{len(keys) - _MAX_SLIP_CURVES} more curves not shown", transform=ax.transAxes,
                fontsize=7)
    ax.set_xscale("log")
    ax.set_xlabel("slip ratio s")
    ax.set_ylabel("friction coefficient mu")
    ax.set_title(f"{cmp.name}: mu(slip)", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, title=_band_legend(cmp, hw), title_fontsize=7)
    _band_caption(fig, cmp, hw)
    return _light(fig)


def _predict_curves(cmp, curves: dict):
    """``(key -> mu, key -> band half-width or None)`` of the model along each curve ``key -> (slip, speed, T, p,
    wet)``: the curves in one prediction (mu None when the model fails there: a plot must not hide the
    comparison), and with a covariance (:attr:`Comparison.has_band`) the 68 % band by the delta method, 2 k more
    predictions for k fitted parameters through the same path (:func:`validation.band.band_half_width`)."""
    import warnings

    from .band import band_half_width
    from .measurements import Measurements
    from .predict import Predictor

    if not curves:
        return {}, None
    parts = [[np.broadcast_to(np.asarray(x, dtype=float), np.shape(c[0])) for x in c] for c in curves.values()]
    cols = [np.concatenate([p[i] for p in parts]) for i in range(5)]
    band = None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            rows = Measurements.from_arrays(slip=cols[0], speed=cols[1], temperature=cols[2], pressure=cols[3],
                                            mu=np.zeros(cols[0].size), wet=cols[4].astype(bool),
                                            source="plotted curves")
            predictor = Predictor(rows, cmp.contact)
            mu = predictor.predict(cmp.model).mu
            if cmp.has_band:
                try:
                    band = band_half_width(cmp.covariance, cmp.model, cmp.contact,
                                           lambda model, contact: predictor.predict(model, contact=contact).mu)
                except Exception:  # noqa: BLE001  (a perturbed model may fail: the curves still stand)
                    band = None
    except Exception:  # noqa: BLE001
        return None, None
    out, hw, k = {}, {}, 0
    for key, p in zip(curves, parts):
        out[key] = mu[k:k + p[0].size]
        if band is not None:
            hw[key] = band[k:k + p[0].size]
        k += p[0].size
    return out, (hw if band is not None else None)


def _band_legend(cmp, hw) -> str:
    """The legend's title: what points, lines and the shaded band are."""
    m = cmp.measurements
    title = "points: measured" + (" (bars: +- mu_std)" if m.mu_std is not None else "") + ", lines: model"
    if hw is not None:
        widest = max((float(np.max(a)) for a in hw.values() if np.size(a)), default=0.0)
        # a narrow band is invisible at the scale of the plot: its size says that it is there
        title += f"\nshaded: model 68 % band (1 sigma of the fitted parameters, at most +-{widest:.2g})"
    return title


def _band_caption(fig, cmp, hw) -> None:
    """Under the figure, why a fitted model's curves carry no band."""
    note = cmp.band_note or ("no uncertainty band: the band's predictions failed" if cmp.has_band and hw is None
                             else "")
    if note:
        fig.text(0.01, 0.005, note, fontsize=6.5, color="0.3", va="bottom")


def _light(fig):
    """Log axes without minor ticks and with plain-text labels (10\u207b\u00b3 in Unicode superscripts): minor ticks and
    the mathtext of matplotlib's default log labels cost most of the drawing time and say nothing more."""
    from matplotlib.ticker import FuncFormatter, NullLocator

    for ax in fig.axes:
        for axis, scale in ((ax.xaxis, ax.get_xscale()), (ax.yaxis, ax.get_yscale())):
            if scale == "log":
                axis.set_minor_locator(NullLocator())
                axis.set_major_formatter(FuncFormatter(_log_label))
    return fig


_SUPERSCRIPT = str.maketrans("-0123456789", "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079")


def _log_label(x, pos=None) -> str:
    """A log axis's tick label: 10 to a Unicode-superscript power at a decade, the number itself elsewhere."""
    if not (x > 0 and np.isfinite(x)):
        return ""
    e = round(float(np.log10(x)))
    if abs(np.log10(x) - e) < 1e-9:
        return "10" + str(e).translate(_SUPERSCRIPT)
    return f"{x:g}"


def plot_residuals(cmp):
    """Residual maps: against sliding speed, temperature, pressure, and over the (speed, temperature) plane."""
    m = cmp.measurements
    r = cmp.residual
    vs = m.sliding_speed
    fig, axes = plt.subplots(2, 2, figsize=(10, 7))
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.07, top=0.93, wspace=0.22, hspace=0.25)
    mk = np.where(m.is_sliding, "o", "x")
    ax = axes[0, 0]
    sc = None
    tlo, thi = float(m.temperature.min()), float(m.temperature.max())
    if thi <= tlo:
        tlo, thi = tlo - 1.0, thi + 1.0
    for marker in ("o", "x"):
        sel = mk == marker
        if np.any(sel):
            sc = ax.scatter(vs[sel], r[sel], c=m.temperature[sel], cmap="coolwarm", vmin=tlo, vmax=thi,
                            marker=marker, s=18, label="slip = 1" if marker == "o" else "slip < 1")
    ax.set_xscale("log")
    ax.set_xlabel("sliding speed slip*V (m/s)")
    ax.set_ylabel("residual (measured - predicted)")
    if sc is not None:
        fig.colorbar(sc, ax=ax, label="T (C)")
    ax.legend(fontsize=7)
    ax = axes[0, 1]
    sc = ax.scatter(m.temperature, r, c=np.log10(vs), cmap="viridis", s=18)
    fig.colorbar(sc, ax=ax, label="log10 sliding speed")
    ax.set_xlabel("temperature T0 (C)")
    ax = axes[1, 0]
    sc = ax.scatter(m.pressure / 1e6, r, c=np.log10(vs), cmap="viridis", s=18)
    fig.colorbar(sc, ax=ax, label="log10 sliding speed")
    ax.set_xlabel("pressure (MPa)")
    ax.set_ylabel("residual")
    ax = axes[1, 1]
    lim = float(np.max(np.abs(r))) or 1.0
    sc = ax.scatter(vs, m.temperature, c=r, cmap="RdBu_r", vmin=-lim, vmax=lim, s=30, edgecolors="k",
                    linewidths=0.3)
    fig.colorbar(sc, ax=ax, label="residual (red: model too low)")
    ax.set_xscale("log")
    ax.set_xlabel("sliding speed (m/s)")
    ax.set_ylabel("temperature (C)")
    for a in axes.ravel():
        a.grid(alpha=0.3)
    for a in (axes[0, 0], axes[0, 1], axes[1, 0]):
        a.axhline(0.0, color="k", lw=0.8)
    fig.suptitle(f"{cmp.name}: residuals, RMSE {cmp.rmse:.3g}, bias {cmp.bias:+.3g}", fontsize=10)
    return _light(fig)


def plot_signatures(dx, n_top: int = 3):
    """Baseline residual and the refitted change of the top candidates against row (sorted by speed)."""
    m = dx.measurements
    order = np.lexsort((m.sliding_speed, m.pressure, m.temperature, m.wet))
    fig, ax = plt.subplots(figsize=(10, 4))
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.13, top=0.91)
    x = np.arange(m.n)
    ax.plot(x, dx.baseline.residual[order], "ko", ms=3, label="baseline residual")
    for j, c in enumerate([c for c in dx.candidates if c.change is not None][:n_top]):
        ax.plot(x, c.change[order], "-", color=f"C{j}", lw=1.3,
                label=f"{c.effect} (refitted): dBIC {c.delta_bic:+.1f}")
    # mark the condition blocks
    T, p = m.temperature[order], m.pressure[order]
    edges = np.flatnonzero((np.diff(T) != 0) | (np.diff(p) != 0)) + 0.5
    for e in edges:
        ax.axvline(e, color="0.85", lw=0.8)
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xlabel("row (grouped by wet, temperature, pressure; speed increasing within a group)")
    ax.set_ylabel("mu")
    ax.set_title("what is missing: the residual and how each candidate effect moves the prediction", fontsize=10)
    ax.legend(fontsize=7)
    return fig


def plot_steps(improvement):
    """RMSE after each improvement step (watch the error fall)."""
    steps = improvement.steps
    fig, ax = plt.subplots(figsize=(6, 3.6))
    fig.subplots_adjust(left=0.11, right=0.97, bottom=0.2, top=0.9)
    x = np.arange(len(steps))
    ax.plot(x, [s.rmse for s in steps], "o-", color="C3")
    for i, s in enumerate(steps):
        ax.annotate(f"{s.rmse:.3g}", (i, s.rmse), textcoords="offset points", xytext=(5, 5), fontsize=8)
    ax.set_xticks(x)
    ax.set_xticklabels([s.describe() if s.action != "baseline" else "baseline" for s in steps], rotation=15,
                       fontsize=8)
    if improvement.noise is not None and np.isfinite(improvement.noise):
        ax.axhline(improvement.noise, color="0.5", ls="--", lw=1, label=f"noise estimate {improvement.noise:.3g}")
        ax.legend(fontsize=8)
    ax.set_ylabel("RMSE")
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.set_title("RMSE after each change of the set of effects", fontsize=10)
    return fig


def plot_residual_slip(dx):
    """Residual against slip ratio (rows with slip < 1, and the sliding rows at slip = 1): the baseline's, and the
    explaining candidate's when the verdict names one, with the noise band."""
    m = dx.measurements
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    fig.subplots_adjust(left=0.13, right=0.97, bottom=0.13, top=0.91)
    s = m.slip
    series = [("baseline", dx.baseline.residual, "ko")]
    cand = dx.explaining
    if cand is not None:
        series.append((f"with {cand.effect}", m.mu - cand.predicted, "C3s"))
    for label, r, style in series:
        ax.plot(s, r, style, ms=4, alpha=0.8, label=label, mfc="none" if style.startswith("C") else None)
    if np.isfinite(dx.noise):
        ax.axhspan(-2 * dx.noise, 2 * dx.noise, color="0.85", zorder=0,
                   label=f"+- 2 x noise ({dx.noise_estimate.source})")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xscale("log")
    ax.set_xlabel("slip ratio s (1 = pure sliding)")
    ax.set_ylabel("residual (measured - predicted)")
    ax.set_title("residual vs slip ratio", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    return _light(fig)
