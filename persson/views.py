r"""Views of sweeps and contact: matplotlib plots of band contributions and sweep results, and a pyvista 3D
rendering (off-screen, to PNG) of a height map with the real-contact regions at a chosen magnification.

The plots use :class:`matplotlib.figure.Figure` directly (no pyplot, no global backend switch) and every
function returns the figure; :func:`save_figure` writes it atomically.

Real contact in 3D: an approximation
------------------------------------
Persson's theory gives the *fraction* of the nominal area in contact at magnification
:math:`\zeta = q/q_0` (:math:`P(q) = A(q)/A_0`), not *where* the contacts are. :func:`contact_view` draws the
surface as seen at that magnification (the height map low-pass filtered to :math:`|q| \le \zeta q_0`) and
highlights the highest regions, with a threshold height chosen so that the highlighted area fraction equals
:math:`P(\zeta q_0)`: the rubber is taken to touch the summits first (a bearing-area picture). It ignores the
rubber's deformation between summits, the lateral shift of contact patches with sliding, and the fact that
the contact at magnification :math:`\zeta` is found on the contacts of lower magnifications; it is an
illustration, not an output of the theory.
"""

from __future__ import annotations

import math
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from frictioncite import doi

from .errors import InputError
from .io import _file_mode, atomic_write

__all__ = ["plot_bands", "plot_sweep", "save_figure", "contact_regions", "render_contact", "contact_view",
           "ContactView", "synthesize_heights"]


# ---------------------------------------------------------------------------------------------------------
# matplotlib
def plot_bands(table, *, speed: float | None = None, title: str = "", output: str = "mu_hysteresis"):
    """Bar chart of the contribution of each length-scale band (table of :func:`persson.sweeps.bands`).

    Parameters
    ----------
    table : persson.sweeps.Table
        With columns ``mode``, ``band``, ``q_low``, ``q_high`` (or ``q`` and ``dmu_dlog10q`` for the
        continuous kind: then a line plot of d mu / d log10 q against q).
    speed : float, optional
        Which sliding speed to show (default the first in the table).
    title : str
    output : str
        Output column shown per band (default ``mu_hysteresis``).

    Returns
    -------
    matplotlib.figure.Figure
        Bars grouped by band (wavelength range on the axis), one bar per mode and point; the total of each
        point is given in the legend.
    """
    from matplotlib.figure import Figure

    t = _at_speed(table, speed)
    if "mode" not in t:
        raise InputError("table: expected a band table (columns mode, band, q_low, q_high)")
    labels = _point_labels(t)
    fig = Figure(figsize=(10, 4.5), layout="constrained")
    ax = fig.add_subplot()
    v = t["speed_m_s"][0]
    if "dmu_dlog10q" in t:
        for pt in np.unique(t["point"]):
            s = t.where(point=pt)
            ax.semilogx(s["q"], s["dmu_dlog10q"], label=labels[pt] or None)
        ax.set_xlabel("wavevector q (rad/m)")
        ax.set_ylabel("d mu / d log10 q")
        top = ax.secondary_xaxis("top", functions=(_q_to_lambda_um, _q_to_lambda_um))
        top.set_xlabel("wavelength 2 pi / q (um)")
    else:
        modes = [m for m in ("restrict", "separate") if np.any(t["mode"] == m)]
        pts = list(np.unique(t["point"]))
        bands = t.where(mode=modes[0]) if modes else t
        edges = sorted({(int(b), lo, hi) for b, lo, hi in zip(bands["band"], bands["q_low"], bands["q_high"])})
        nb = len(edges)
        width = 0.8 / max(1, len(modes) * len(pts))
        k = 0
        for mode in modes:
            for pt in pts:
                s = t.where(mode=mode, point=pt)
                total = t.where(mode="total", point=pt)
                tot = f", total {total[output][0]:.3g}" if len(total) else ""
                y = np.full(nb, np.nan)
                for b, val in zip(s["band"], s[output]):
                    y[int(b)] = val
                lab = f"{'(a) restrict' if mode == 'restrict' else '(b) separate'}"
                lab += (f", {labels[pt]}" if labels[pt] else "") + tot + f" (sum {np.nansum(y):.3g})"
                ax.bar(np.arange(nb) + (k - (len(modes) * len(pts) - 1) / 2) * width, y, width,
                       label=lab, color=f"C{pts.index(pt) % 10}", hatch="//" if mode == "separate" else None,
                       alpha=0.9 if mode == "restrict" else 0.55, edgecolor="k", linewidth=0.3)
                k += 1
        ax.set_xticks(np.arange(nb))
        ax.set_xticklabels([_band_label(lo, hi) for _, lo, hi in edges], rotation=20, ha="right")
        ax.set_xlabel("band: wavelength range (q range in rad/m)")
        ax.set_ylabel(output)
    ax.set_title(title or f"contribution by length-scale band, v = {v:.3g} m/s")
    if ax.get_legend_handles_labels()[1]:
        ax.legend(fontsize=8)
    return fig


def plot_sweep(table, x: str, y="mu", *, by: str | None = None, speed: float | None = None, title: str = ""):
    """Outputs against one swept input, one line per value of the other inputs.

    Parameters
    ----------
    table : persson.sweeps.Table
        From :func:`persson.sweeps.grid` (band tables: the ``total`` rows are used).
    x : str
        Input on the horizontal axis: a parameter name (``pressure``, ``surface.q1``...) or a column.
    y : str or sequence of str
        Output column(s), one panel each (default ``mu``).
    by : str, optional
        Input that labels the lines (default: every other varying input).
    speed : float, optional
        Keep one speed (default: all speeds, as separate lines, unless ``x`` is the speed).
    title : str

    Returns
    -------
    matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    from .sweeps.params import CONDITIONS

    t = table.where(mode="total") if "mode" in table else table
    xcol = CONDITIONS.get(x, x)
    if xcol not in t:
        raise InputError(f"x: no column {x!r} in the table (columns {list(t.names)})")
    if speed is not None:
        t = _at_speed(t, speed)
    ys = [y] if isinstance(y, str) else list(y)
    for name in ys:
        if name not in t:
            raise InputError(f"y: no column {name!r} in the table (columns {list(t.names)})")
    inputs = _input_columns(t)
    others = [c for c in inputs if c != xcol and len(np.unique(t[c])) > 1]
    if by is not None:
        others = [CONDITIONS.get(by, by)]
    fig = Figure(figsize=(5 * len(ys), 4), layout="constrained")
    axes = fig.subplots(1, len(ys), squeeze=False)[0]
    keys = sorted({tuple(r[c] for c in others) for r in t.rows()}) if others else [()]
    xs = np.asarray(t[xcol], dtype=float)
    # log axis for the speed and for inputs spanning more than two decades
    logx = xcol == "speed_m_s" or (xs.size > 0 and np.all(xs > 0) and np.ptp(np.log10(xs)) > 2)
    for ax, name in zip(axes, ys):
        for key in keys:
            mask = np.ones(len(t), dtype=bool)
            for c, val in zip(others, key):
                mask &= t[c] == val
            s = t.take(np.flatnonzero(mask))
            order = np.argsort(s[xcol], kind="stable")
            lab = ", ".join(f"{_short(c)} = {val:.3g}" for c, val in zip(others, key)) or None
            ax.plot(s[xcol][order], s[name][order], "o-", label=lab)
        if logx:
            ax.set_xscale("log")
        ax.set_xlabel(xcol)
        ax.set_ylabel(name)
        if len(keys) > 1:
            ax.legend(fontsize=8)
    fig.suptitle(title or f"sweep over {x}")
    return fig


def save_figure(fig, path, dpi: int = 120, *, overwrite: bool = False) -> Path:
    """Save ``fig`` as PNG, atomically (complete or not at all); an existing file only with ``overwrite=True``."""
    from .io import check_overwrite

    path = check_overwrite(path, overwrite=overwrite)
    with atomic_write(path, "wb") as fh:
        fig.savefig(fh, format="png", dpi=dpi)
    return path


# ---------------------------------------------------------------------------------------------------------
# 3D contact view
@dataclass(frozen=True, eq=False)
class ContactView:
    """What :func:`contact_view` / :func:`render_contact` drew.

    Attributes
    ----------
    path : pathlib.Path
        The PNG written.
    magnification : float
        zeta = q / q_start (NaN when the area fraction was given directly).
    q : float
        Wavevector of the magnification, rad/m (NaN when not known).
    area_fraction : float
        The contact area fraction drawn (Persson's P(q) when from a model).
    threshold : float
        Height above which the surface is drawn as in contact, m.
    drawn_fraction : float
        Fraction of the map's samples highlighted (equals ``area_fraction`` up to the sample count).
    heights : ndarray (ny, nx)
        The heights drawn (m), after low-pass filtering to q for :func:`contact_view`.
    dx : float
        Sample spacing, m.
    """

    path: Path
    magnification: float
    q: float
    area_fraction: float
    threshold: float
    drawn_fraction: float
    heights: np.ndarray
    dx: float


def contact_regions(heights, area_fraction: float) -> tuple[np.ndarray, float]:
    """Mask of the highest samples covering ``area_fraction`` of the map, and the threshold height.

    Parameters
    ----------
    heights : array_like (ny, nx)
    area_fraction : float
        In [0, 1].

    Returns
    -------
    mask : ndarray of bool
    threshold : float
        ``mask = heights > threshold``; the threshold is the (1 - area_fraction) quantile.
    """
    z = np.asarray(heights, dtype=float)
    a = float(area_fraction)
    if not (math.isfinite(a) and 0.0 <= a <= 1.0):
        raise InputError(f"area_fraction: expected a value in [0, 1], got {area_fraction!r}")
    if z.ndim != 2 or not np.all(np.isfinite(z)):
        raise InputError("heights: expected a 2D array of finite heights (m)")
    k = int(round(a * z.size))
    if k == 0:
        return np.zeros(z.shape, dtype=bool), float(np.max(z))
    flat = np.sort(z.ravel())
    threshold = float(flat[z.size - k - 1]) if k < z.size else float(flat[0]) - 1.0
    return z > threshold, threshold


def render_contact(heights, area_fraction: float, path, *, dx: float | None = None,
                   vertical_exaggeration: float | None = None, window_size=(1200, 900), title: str = "",
                   magnification: float = math.nan, q: float = math.nan) -> ContactView:
    """Render a height map in 3D with its contact regions highlighted, off-screen, to a PNG (pyvista).

    Parameters
    ----------
    heights : surfaces.HeightMap or array_like (ny, nx)
        Measured or synthetic heights, m (a HeightMap carries its spacing).
    area_fraction : float
        Fraction of the area drawn in contact (the highest regions, see :func:`contact_regions`).
    path : path-like
        PNG file, written atomically.
    dx : float, optional
        Sample spacing, m (required for a plain array).
    vertical_exaggeration : float, optional
        Height scale factor (default: relief about 15 % of the map width).
    window_size : (int, int)
    title : str
    magnification, q : float
        Recorded in the returned :class:`ContactView`.

    Returns
    -------
    ContactView

    Raises
    ------
    RuntimeError
        When VTK cannot render off-screen (no OpenGL); the message says what to install.
    """
    z, dx = _heights(heights, dx)
    mask, threshold = contact_regions(z, area_fraction)
    try:
        import pyvista as pv
    except ImportError as exc:  # pragma: no cover - pyvista is a dependency
        raise RuntimeError(f"render_contact needs pyvista: {exc}") from None
    ny, nx = z.shape
    x = dx * np.arange(nx)
    y = dx * np.arange(ny)
    relief = float(np.ptp(z)) or 1.0
    scale = vertical_exaggeration if vertical_exaggeration is not None else 0.15 * max(x[-1], y[-1]) / relief
    X, Y = np.meshgrid(x, y)
    mesh = pv.StructuredGrid(X, Y, (z - z.mean()) * scale)
    # colours: grey-brown by height for the surface, red for the contact regions (order matches the points)
    shade = (z - z.min()) / relief
    base = np.stack([0.45 + 0.35 * shade, 0.42 + 0.3 * shade, 0.38 + 0.25 * shade], axis=-1)
    base[mask] = (0.85, 0.1, 0.1)
    # StructuredGrid points run in Fortran order of the (ny, nx) arrays
    mesh.point_data["rgb"] = (np.clip(base, 0, 1) * 255).astype(np.uint8).reshape(-1, 3, order="F")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=".png", dir=path.parent)
    os.close(fd)
    os.chmod(tmp, _file_mode())
    plotter = None
    try:
        plotter = pv.Plotter(off_screen=True, window_size=list(window_size))
        plotter.add_mesh(mesh, scalars="rgb", rgb=True, smooth_shading=True)
        if title:
            plotter.add_text(title, font_size=10)
        plotter.camera_position = "iso"
        plotter.camera.elevation = -10
        plotter.camera.zoom(1.5)
        plotter.screenshot(tmp)
        os.replace(tmp, path)
    except Exception as exc:
        raise RuntimeError(f"3D rendering failed ({type(exc).__name__}: {exc}); off-screen rendering needs an "
                           "OpenGL implementation: install a VTK build with OSMesa/EGL, or run under a virtual "
                           "framebuffer (xvfb-run)") from exc
    finally:
        if plotter is not None:
            plotter.close()
        if os.path.exists(tmp):
            os.unlink(tmp)
    return ContactView(path=path, magnification=float(magnification), q=float(q),
                       area_fraction=float(area_fraction), threshold=threshold,
                       drawn_fraction=float(mask.mean()), heights=z, dx=dx)


def contact_view(model, path, *, magnification: float = 10.0, speed: float = 1.0, temperature: float = 20.0,
                 pressure: float = 0.3e6, heights=None, dx: float | None = None, n: int = 256,
                 seed: int = 0, **render_options) -> ContactView:
    r"""3D view of the real contact of ``model`` at magnification ``zeta`` (PNG, off-screen).

    The area fraction is Persson's :math:`P(q)` of ``model.friction(speed, temperature, pressure)`` at
    :math:`q = \zeta q_{start}` (interpolated in ln q; :math:`q_{start}` the first wavevector the engine
    integrates from). The heights (a measured map, or a seeded synthetic map of the surface's PSD) are low-pass
    filtered to :math:`|q| \le \zeta q_{start}` and the highest regions covering :math:`P` are drawn in red
    (the approximation is described in the module docstring).

    Parameters
    ----------
    model : persson.Model
    path : path-like
        PNG written.
    magnification : float
        zeta >= 1.
    speed, temperature, pressure : float
        Operating point.
    heights : surfaces.HeightMap or array_like, optional
        Measured heights (m); default a synthetic map of ``model.surface`` (:func:`synthesize_heights`).
    dx : float, optional
        Spacing of a plain array, m.
    n : int
        Samples per side of the synthetic map.
    seed : int
        Seed of the synthetic map.
    **render_options
        Passed to :func:`render_contact`.

    Returns
    -------
    ContactView
    """
    zeta = float(magnification)
    if not (math.isfinite(zeta) and zeta >= 1.0):
        raise InputError(f"magnification: expected zeta >= 1, got {magnification!r}")
    r = model.friction(float(speed), temperature=temperature, pressure=pressure)
    q_all = np.asarray(r.q)
    qm = q_all[0] * zeta
    if qm > q_all[-1] * (1 + 1e-9):
        raise InputError(f"magnification: zeta = {zeta:g} reaches q = {qm:g} rad/m past q1 = {q_all[-1]:g} rad/m "
                         f"(largest zeta {q_all[-1] / q_all[0]:g})")
    P = float(np.interp(math.log(qm), np.log(q_all), np.asarray(r.area_q)[0]))
    if heights is None:
        z, dx = synthesize_heights(model.surface, n=n, seed=seed)
    else:
        z, dx = _heights(heights, dx)
    z = _low_pass(z, dx, qm)
    title = render_options.pop("title", f"contact at zeta = {zeta:g} (q = {qm:.3g} rad/m): A/A0 = {P:.3f}")
    return render_contact(z, P, path, dx=dx, title=title, magnification=zeta, q=qm, **render_options)


@doi("10.1088/0953-8984/17/1/R01")
def synthesize_heights(surface, n: int = 256, seed: int = 0, length: float | None = None):
    r"""Seeded periodic height map (m) with the isotropic PSD of ``surface``: ``(z, dx)``.

    Uses :func:`surfaces.synthetic.synthesize_map` when available; otherwise the same Fourier synthesis
    locally: white Gaussian noise filtered by :math:`\sqrt{C(|q|)}\,\Delta q` so that
    :math:`\langle|h_q|^2\rangle = C(q)(2\pi/L)^2` (Persson convention), side ``length`` (default
    :math:`2\pi/q_{start}`).
    """
    try:
        from surfaces.synthetic import synthesize_map
    except ImportError:
        synthesize_map = None
    if synthesize_map is not None:
        hm = synthesize_map(surface, n=n, length=length, seed=seed)
        return np.asarray(hm.z, dtype=float), float(hm.dx)
    n = int(n)
    L = 2 * math.pi / float(surface.q_range[0]) if length is None else float(length)
    dx = L / n
    rng = np.random.default_rng(seed)
    W = np.fft.rfft2(rng.standard_normal((n, n)))
    qx = 2 * np.pi * np.fft.rfftfreq(n, dx)
    qy = 2 * np.pi * np.fft.fftfreq(n, dx)
    qmag = np.hypot(qx[None, :], qy[:, None])
    F = n * (2 * math.pi / L) * np.sqrt(np.asarray(surface.C(qmag), dtype=float))
    F[0, 0] = 0.0
    return np.fft.irfft2(W * F, s=(n, n)), dx


# ---------------------------------------------------------------------------------------------------------
def _heights(heights, dx):
    if hasattr(heights, "z") and hasattr(heights, "dx"):
        z = np.asarray(heights.z, dtype=float)
        d = float(heights.dx)
    else:
        z = np.asarray(heights, dtype=float)
        if dx is None:
            raise InputError("dx: give the sample spacing (m) of a plain height array")
        d = float(dx)
    if z.ndim != 2 or min(z.shape) < 2 or not np.all(np.isfinite(z)):
        raise InputError(f"heights: expected a 2D array of finite heights (m), got shape {z.shape}")
    if not (math.isfinite(d) and d > 0):
        raise InputError(f"dx: expected a positive spacing in m, got {dx!r}")
    return z, d


def _low_pass(z, dx: float, q_max: float) -> np.ndarray:
    ny, nx = z.shape
    Z = np.fft.rfft2(z - z.mean())
    qx = 2 * np.pi * np.fft.rfftfreq(nx, dx)
    qy = 2 * np.pi * np.fft.fftfreq(ny, dx)
    Z[np.hypot(qx[None, :], qy[:, None]) > q_max * (1 + 1e-12)] = 0.0
    return np.fft.irfft2(Z, s=(ny, nx))


def _at_speed(table, speed):
    v = np.unique(table["speed_m_s"])
    if v.size == 0:
        raise InputError("table: empty")
    pick = v[0] if speed is None else v[np.argmin(np.abs(np.log(v / float(speed))))]
    return table.where(speed_m_s=pick)


def _input_columns(t) -> list[str]:
    names = list(t.names)
    end = names.index("speed_m_s")
    return names[1:end] + ["speed_m_s", "temperature_C", "pressure_Pa"]


def _point_labels(t) -> dict:
    cols = [c for c in _input_columns(t) if c != "speed_m_s" and len(np.unique(t[c])) > 1]
    out = {}
    for pt in np.unique(t["point"]):
        row = t.where(point=pt).rows()[0]
        out[pt] = ", ".join(f"{_short(c)} = {row[c]:.3g}" for c in cols)
    return out


def _short(col: str) -> str:
    return {"pressure_Pa": "p (Pa)", "temperature_C": "T (C)", "speed_m_s": "v (m/s)"}.get(col, col)


def _band_label(lo: float, hi: float) -> str:
    return f"{_length(2 * math.pi / hi)}-{_length(2 * math.pi / lo)}\n({lo:.2g}-{hi:.2g})"


def _length(m: float) -> str:
    if m >= 1e-3:
        return f"{m * 1e3:.3g} mm"
    if m >= 1e-6:
        return f"{m * 1e6:.3g} um"
    return f"{m * 1e9:.3g} nm"


def _q_to_lambda_um(q):
    q = np.asarray(q, dtype=float)
    with np.errstate(divide="ignore"):
        return 2 * np.pi / q * 1e6
