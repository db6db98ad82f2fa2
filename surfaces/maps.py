r"""2D height maps and their radially averaged isotropic PSD (Persson convention).

For a map of :math:`N_x \times N_y` samples with spacings :math:`\Delta x, \Delta y`,

.. math:: C(\mathbf q) = \frac{\Delta x\,\Delta y}{(2\pi)^2 N_x N_y\,\overline{w^2}}
          \Big|\sum_{\mathbf x} w(\mathbf x) h(\mathbf x) e^{-i\mathbf q\cdot\mathbf x}\Big|^2 ,

so that :math:`\sum_{\mathbf q} C(\mathbf q)\,\Delta q_x \Delta q_y = \langle h^2\rangle` (window w, default
Hann for non-periodic maps); :math:`C(q)` is the mean over annuli on a logarithmic grid
(Jacobs, Junge, Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017), Sec. 2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import fft

from frictioncite import doi

from ._util import flat_after_detrend, positive, span
from .errors import InputError
from .profiles import Profile, ProfileSet
from .psd import PSD
from .psd2d import PSD2D, periodogram_2d
from .psdfit import with_estimated_rolloff

__all__ = ["HeightMap"]

_DETREND_2D = ("none", "mean", "plane", "quadratic")


@dataclass(frozen=True, eq=False)
class HeightMap:
    """A 2D height map on a uniform grid.

    Parameters
    ----------
    z : array_like, shape (ny, nx)
        Heights, m (finite).
    dx : float
        Spacing along x (columns), m.
    dy : float, optional
        Spacing along y (rows), m; default ``dx``.
    periodic : bool
        True for periodic maps (synthetic surfaces): no window needed.
    source : str
        Origin, for messages.
    """

    z: np.ndarray
    dx: float
    dy: float | None = None
    periodic: bool = False
    source: str = ""

    def __post_init__(self):
        where = self.source or "HeightMap"
        z = np.array(self.z, dtype=float)
        if z.ndim != 2 or min(z.shape) < 2:
            raise InputError(f"{where}: expected a 2D array of at least 2 x 2 heights, got shape {z.shape}")
        if not np.isfinite(z).all():
            raise InputError(f"{where}: {int((~np.isfinite(z)).sum())} heights are NaN or infinite; "
                             "height maps must be complete")
        z.setflags(write=False)
        object.__setattr__(self, "z", z)
        object.__setattr__(self, "dx", positive(self.dx, "dx"))
        object.__setattr__(self, "dy", positive(self.dx if self.dy is None else self.dy, "dy"))

    def __repr__(self) -> str:
        ny, nx = self.z.shape
        return (f"HeightMap({ny} x {nx}, dx={self.dx:.4g} m, dy={self.dy:.4g} m, z {span(self.z, 'm')}"
                + (", periodic" if self.periodic else "") + (f", source={self.source!r}" if self.source else "") + ")")

    @property
    def shape(self) -> tuple[int, int]:
        """(ny, nx)."""
        return self.z.shape

    @property
    def size(self) -> tuple[float, float]:
        """Physical size (Lx, Ly) = (nx dx, ny dy), m."""
        return self.z.shape[1] * self.dx, self.z.shape[0] * self.dy

    def hrms(self) -> float:
        """Rms height about the mean, m."""
        return float(np.std(self.z))

    def rms_slope(self) -> float:
        r"""Rms gradient :math:`\sqrt{\langle|\nabla h|^2\rangle}` from central differences (periodic maps: wrap)."""
        if self.periodic:
            gx = (np.roll(self.z, -1, axis=1) - np.roll(self.z, 1, axis=1)) / (2 * self.dx)
            gy = (np.roll(self.z, -1, axis=0) - np.roll(self.z, 1, axis=0)) / (2 * self.dy)
        else:
            gy, gx = np.gradient(self.z, self.dy, self.dx)
        return float(np.sqrt(np.mean(gx**2 + gy**2)))

    def rows(self) -> ProfileSet:
        """The rows as line profiles along x (sharing x)."""
        x = self.dx * np.arange(self.z.shape[1])
        src = self.source or "height map"
        return ProfileSet(tuple(Profile(x, row, name=f"row {i}", source=src, periodic=self.periodic)
                                for i, row in enumerate(self.z)), source=src)

    def columns(self) -> ProfileSet:
        """The columns as line profiles along y."""
        return HeightMap(self.z.T, self.dy, self.dx, self.periodic, self.source).rows()

    def detrend(self, kind: str = "plane") -> "HeightMap":
        """Subtract the least-squares surface of ``kind`` in {"none", "mean", "plane", "quadratic"}."""
        if kind not in _DETREND_2D:
            raise InputError(f"detrend: expected one of {_DETREND_2D}, got {kind!r}")
        if kind == "none":
            return self
        ny, nx = self.z.shape
        Y, X = np.meshgrid(np.linspace(-1, 1, ny), np.linspace(-1, 1, nx), indexing="ij")
        cols = [np.ones_like(X)]
        if kind in ("plane", "quadratic"):
            cols += [X, Y]
        if kind == "quadratic":
            cols += [X * X, X * Y, Y * Y]
        A = np.stack([c.ravel() for c in cols], axis=1)
        coef, *_ = np.linalg.lstsq(A, self.z.ravel(), rcond=None)
        return HeightMap(self.z - (A @ coef).reshape(self.z.shape), self.dx, self.dy, self.periodic, self.source)

    @doi("10.1088/2051-672X/aa51f8", "10.1088/0953-8984/17/1/R01")
    def psd(self, window: str | None = "auto", detrend: str = "auto", n_per_decade: int = 20,
            q_r: float | None = None) -> PSD:
        r"""Radially averaged isotropic 2D PSD (Persson convention), see the module docstring.

        Parameters
        ----------
        window : str or None
            "auto": none for periodic maps, else a separable Hann window; or a
            :func:`scipy.signal.get_window` name applied along both axes; or None.
        detrend : str
            "auto" (mean for periodic maps, plane otherwise) or none/mean/plane/quadratic.
        n_per_decade : int
            Log bins per decade.
        q_r : float, optional
            Reliability limit, rad/m; default the Nyquist wavevector :math:`\pi/\max(\Delta x, \Delta y)`.
            Annuli past it are incomplete on the square grid and are not returned.

        Returns
        -------
        surfaces.PSD
            With ``qL`` = :math:`2\pi/\max(L_x, L_y)`, ``q_r`` and (when a plateau is seen) ``q_rolloff`` set.
        """
        kind = detrend if detrend != "auto" else ("mean" if self.periodic else "plane")
        h = self.detrend(kind).z
        if flat_after_detrend(self.z, h):
            raise InputError(f"{self.source or 'HeightMap'}: no roughness: the heights are constant (or a {kind} "
                             f"only) after detrending ({kind}); the PSD would be zero, the contact full (A/A0 = 1) "
                             "and mu = 0")
        ny, nx = h.shape
        win = (None if self.periodic else "hann") if window == "auto" else window
        if win in (None, "none", "boxcar"):
            w = np.ones_like(h)
        else:
            w = np.outer(_signal().get_window(win, ny), _signal().get_window(win, nx))
        Z = fft.rfft2(w * h)
        C = self.dx * self.dy * np.abs(Z) ** 2 / ((2 * np.pi) ** 2 * nx * ny * np.mean(w**2))
        qx = 2 * np.pi * fft.rfftfreq(nx, self.dx)
        qy = 2 * np.pi * fft.fftfreq(ny, self.dy)
        qmag = np.hypot(qx[None, :], qy[:, None])
        # rfft2 keeps half the plane: interior columns stand for two modes (+q and -q).
        mult = np.full(qx.size, 2.0)
        mult[0] = 1.0
        if nx % 2 == 0:
            mult[-1] = 1.0
        weight = np.broadcast_to(mult[None, :], C.shape)
        q_lim = math.pi / max(self.dx, self.dy) if q_r is None else positive(q_r, "q_r")
        sel = (qmag > 0) & (qmag <= min(q_lim, math.pi / max(self.dx, self.dy)) * (1 + 1e-12))
        q_sel, C_sel, w_sel = qmag[sel], C[sel], weight[sel]
        b = np.floor(n_per_decade * np.log10(q_sel) + 1e-9).astype(int)
        b -= b.min()
        wsum = np.bincount(b, weights=w_sel)
        keep = wsum > 0
        q_bin = np.exp(np.bincount(b, weights=w_sel * np.log(q_sel))[keep] / wsum[keep])
        C_bin = np.bincount(b, weights=w_sel * C_sel)[keep] / wsum[keep]
        ok = C_bin > 0
        Lmax = max(self.size)
        return with_estimated_rolloff(PSD(q_bin[ok], C_bin[ok], q_r=q_lim, extrapolated=False,
                                          source=f"{self.source or 'height map'} (radial average)",
                                          qL=2 * math.pi / Lmax))

    @doi("10.1088/2051-672X/aa51f8", "10.1088/0953-8984/17/1/R01")
    def psd2d(self, window: str | None = "auto", detrend: str = "auto", n_per_decade: int = 20,
              q_r: float | None = None, smoothing_deg: float = 5.0) -> PSD2D:
        r"""The 2-D PSD :math:`C(q_x, q_y)` without radial averaging (Persson convention), windowed as :meth:`psd`.

        Parameters
        ----------
        window, detrend, n_per_decade, q_r
            As :meth:`psd` (the angular mean of the result is exactly that radial PSD).
        smoothing_deg : float
            Angular smoothing of the polar description used by the friction engine, degrees
            (:class:`surfaces.PSD2D`).

        Returns
        -------
        surfaces.PSD2D
            The periodogram on the full grid of wavevectors (``qx``, ``qy``, ``C_grid``), its angular mean
            (``radial``), its principal directions and anisotropy (``anisotropy()``).
        """
        kind = detrend if detrend != "auto" else ("mean" if self.periodic else "plane")
        h = self.detrend(kind).z
        if flat_after_detrend(self.z, h):
            raise InputError(f"{self.source or 'HeightMap'}: no roughness: the heights are constant (or a {kind} "
                             f"only) after detrending ({kind}); the PSD would be zero")
        ny, nx = h.shape
        win = (None if self.periodic else "hann") if window == "auto" else window
        if win in (None, "none", "boxcar"):
            w = np.ones_like(h)
        else:
            w = np.outer(_signal().get_window(win, ny), _signal().get_window(win, nx))
        qx, qy, C = periodogram_2d(h, self.dx, self.dy, w)
        q_lim = math.pi / max(self.dx, self.dy) if q_r is None else min(positive(q_r, "q_r"),
                                                                         math.pi / max(self.dx, self.dy))
        return PSD2D(qx, qy, C, q_r=q_lim, qL=2 * math.pi / max(self.size), source=self.source or "height map",
                     n_per_decade=n_per_decade, smoothing_deg=smoothing_deg)


def _signal():
    """``scipy.signal``, imported on first use (it adds about 0.4 s to every start-up)."""
    from scipy import signal

    return signal
