"""Plots of the tread-element tool: the mu-slip-speed surface, peak/locked bars per surface, a 3D view of the tread.

matplotlib (Agg) for the first two (each returns its figure; save with :func:`persson.plots.save_figure`);
pyvista, off-screen, for the view (writes a PNG atomically).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

__all__ = ["plot_slip_map", "plot_peak_locked", "view_tread"]


def plot_slip_map(m, title: str = ""):
    """The mu-slip-speed surface of a :class:`~persson.tread.SlipMap` (3D when it has several speeds and slips,
    else curves), with the ABS peak marked."""
    S, V = np.meshgrid(m.slips, m.speeds)
    if m.speeds.size > 1 and m.slips.size > 1:
        fig = plt.figure(figsize=(8, 6), constrained_layout=True)
        ax = fig.add_subplot(projection="3d")
        ax.plot_surface(S, V * 3.6, m.mu, cmap="viridis", edgecolor="k", linewidth=0.3, alpha=0.9)
        ax.scatter(m.peak_slip, m.speeds * 3.6, m.peak_mu, color="r", s=20, label="ABS peak")
        ax.set_xlabel("slip ratio")
        ax.set_ylabel("speed (km/h)")
        ax.set_zlabel("friction coefficient")
        ax.legend(loc="upper left")
    else:
        fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
        for i, v in enumerate(m.speeds):
            ax.errorbar(m.slips, m.mu[i], yerr=m.mu_std[i], marker="o", ms=3, capsize=2,
                        label=f"{v * 3.6:.0f} km/h")
        ax.plot(m.peak_slip, m.peak_mu, "r*", ms=10, label="ABS peak")
        ax.set_xlabel("slip ratio")
        ax.set_ylabel("friction coefficient")
        ax.legend()
    ax.set_title(title or f"tread on road, T = {m.temperature:g} C")
    return fig


def plot_peak_locked(results, measured=None, title: str = ""):
    """Bars of ABS-peak and locked-wheel friction per surface (Fig. 8 of the paper).

    Parameters
    ----------
    results : Ranking or dict
        A :class:`~persson.tread.Ranking`, or name -> :class:`~persson.tread.SlipMap` (its first speed).
    measured : dict, optional
        name -> (peak, locked) measured, drawn as hatched bars beside the predictions (a Ranking brings its own).
    title : str
    """
    if hasattr(results, "peak_mu") and hasattr(results, "names"):
        names = list(results.names)
        peak, pstd = results.peak_mu, results.peak_std
        locked, lstd = results.locked_mu, results.locked_std
        mp = results.measured_peak
        ml = results.measured_locked
    else:
        names = list(results)
        peak = np.array([results[n].peak_mu[0] for n in names])
        pstd = np.array([results[n].peak_std[0] for n in names])
        locked = np.array([results[n].locked_mu[0] for n in names])
        lstd = np.array([results[n].locked_std[0] for n in names])
        mp = ml = None
    if measured is not None:
        mp = np.array([np.nan if measured.get(n) is None else measured[n][0] for n in names], dtype=float)
        ml = np.array([np.nan if measured.get(n) is None else measured[n][1] for n in names], dtype=float)
    x = np.arange(len(names))
    fig, axes = plt.subplots(1, 2, figsize=(max(7, 1.2 * len(names) + 4), 4), constrained_layout=True,
                             sharey=True)
    for ax, pred, err, meas, what, colour in ((axes[0], peak, pstd, mp, "peak (ABS)", "tab:red"),
                                              (axes[1], locked, lstd, ml, "locked wheel", "tab:green")):
        w = 0.38 if meas is not None else 0.7
        ax.bar(x - (w / 2 if meas is not None else 0), pred, w, yerr=err, color=colour, capsize=3, label="model")
        if meas is not None:
            ax.bar(x + w / 2, meas, w, color="white", edgecolor=colour, hatch="//", label="measured")
            ax.legend()
        ax.set_xticks(x, names, rotation=30)
        ax.set_title(what)
    axes[0].set_ylabel("friction coefficient")
    if title:
        fig.suptitle(title)
    return fig


def view_tread(tire, road, path, *, result=None, speed: float = 16.7, slip: float = 1.0, material=None,
               temperature: float = 20.0, mu_loc=None, water=None, vertical_exaggeration: float = 20.0,
               window_size=(1400, 800), **options) -> Path:
    """3D view of the tread elements on the road at the end of a march, off-screen, to a PNG (pyvista).

    The road under the footprint is drawn as a surface (one strip per profile, heights exaggerated), the rubber
    elements as columns from the belt down to their tips, coloured by their normal force (grey: off the road).

    Parameters
    ----------
    tire : Tire
    road : anything :func:`persson.tread.simulate` accepts
    path : path-like
        PNG file, written atomically.
    result : TreadResult, optional
        A finished march to draw; otherwise one is run with ``speed``, ``slip``, ``material``, ``temperature``,
        ``mu_loc``, ``water`` and ``options``.
    vertical_exaggeration : float
        Height scale factor.
    window_size : (int, int)

    Returns
    -------
    Path
        The PNG written.

    Raises
    ------
    RuntimeError
        When VTK cannot render off-screen (no OpenGL).
    """
    from .road import as_road
    from .simulate import simulate

    if result is None:
        if material is None:
            raise ValueError("view_tread: give a result or the material to run one")
        result = simulate(tire, road, material, speed=speed, slip=slip, temperature=temperature, mu_loc=mu_loc,
                          water=water, **options)
    rd = as_road(road, options.get("road_element"))
    st = result.final_state
    import pyvista as pv

    ex = vertical_exaggeration
    xr = st["x"][st["rubber"]]
    x0, x1 = float(np.min(xr)) - 2 * rd.dx, float(np.max(xr)) + 2 * rd.dx
    j0, j1 = max(0, int(x0 / rd.dx)), min(rd.z.shape[1] - 1, int(x1 / rd.dx) + 1)
    xs = np.arange(j0, j1 + 1) * rd.dx
    half = st["row_width"] / 2
    rows = np.unique(st["row"])
    edges = np.concatenate([[st["y"][st["row"] == r][0] - half, st["y"][st["row"] == r][0] + half] for r in rows])
    zs = np.repeat(rd.z[rows, j0:j1 + 1], 2, axis=0) * ex
    X, Y = np.meshgrid(xs, edges)
    surface = pv.StructuredGrid(X, Y, zs)
    blocks = []
    forces = []
    rubber = st["rubber"]
    top = float(np.max(zs)) + 0.2 * tire.tread_depth * ex
    idx = np.flatnonzero(rubber)
    every = max(1, idx.size // (300 * rows.size))  # a few hundred columns per row are enough to see
    for i in idx[::every]:
        r = st["row"][i]
        zt = np.interp(st["x"][i], np.arange(rd.z.shape[1]) * rd.dx, rd.z[r]) * ex
        tip = zt if st["force"][i] > 0 else zt + 0.05 * tire.tread_depth * ex
        blocks.append(pv.Box(bounds=(st["x"][i] - 0.4 * st["element_size"], st["x"][i] + 0.4 * st["element_size"],
                                     st["y"][i] - 0.9 * half, st["y"][i] + 0.9 * half, tip, top)))
        forces.append(st["force"][i])
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".png", dir=path.parent)
    os.close(fd)
    plotter = None
    try:
        plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
        plotter.add_mesh(surface, color="tan", smooth_shading=True)
        if blocks:
            tread = pv.MultiBlock(blocks).combine()
            per_cell = np.repeat(np.asarray(forces), blocks[0].n_cells)
            tread.cell_data["force_N"] = per_cell
            plotter.add_mesh(tread, scalars="force_N", cmap="inferno", opacity=0.85,
                             scalar_bar_args={"title": "element force (N)"})
        plotter.add_text(f"slip {result.slip:g}, {result.speed * 3.6:.0f} km/h, mu = {result.mu:.3f} "
                         f"(heights x{ex:g})", font_size=10)
        plotter.camera_position = "iso"
        plotter.screenshot(tmp)
        os.replace(tmp, path)
    except Exception as exc:
        raise RuntimeError(f"3D rendering failed ({type(exc).__name__}: {exc}); off-screen rendering needs an "
                           "OpenGL implementation (a VTK build with OSMesa/EGL, or xvfb-run)") from exc
    finally:
        if plotter is not None:
            plotter.close()
        if os.path.exists(tmp):
            os.unlink(tmp)
    return path
