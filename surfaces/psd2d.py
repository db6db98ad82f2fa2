r"""The measured 2-D PSD :math:`C(q_x, q_y)` of a height map, without radial averaging (Persson's convention).

For a map of :math:`N_x \times N_y` heights (spacings :math:`\Delta x, \Delta y`, window w)

.. math:: C(\mathbf q) = \frac{\Delta x\,\Delta y}{(2\pi)^2 N_x N_y\,\overline{w^2}}
          \Big|\sum_{\mathbf x} w(\mathbf x) h(\mathbf x) e^{-i\mathbf q\cdot\mathbf x}\Big|^2 ,
          \qquad \sum_{\mathbf q} C(\mathbf q)\,\Delta q_x\Delta q_y = \langle h^2\rangle

(Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017), Sec. 2), the same periodogram whose
annular mean is :meth:`surfaces.HeightMap.psd`. :class:`PSD2D` keeps the grid and describes it in polar form
:math:`C(q, \phi) = \bar C(q)\, w(q, \phi)`: :math:`\bar C` the annular mean on logarithmic bins (exactly the
radial PSD of the map) and :math:`w` the angular shape of each bin, the periodogram averaged in angle with a
periodic Gaussian kernel (``smoothing_deg``; wider where an annulus holds few Fourier modes, at the longest
wavelengths), so that the friction engine can integrate it against the modulus in every sliding direction.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from ._util import finite_float, positive
from .anisotropy import AnisotropicPSD, Anisotropy
from .errors import InputError
from .psd import PSD
from .psdfit import with_estimated_rolloff

__all__ = ["PSD2D"]

_JACOBS_2017 = "10.1088/2051-672X/aa51f8"
_PERSSON_2005 = "10.1088/0953-8984/17/1/R01"
#: Angular grid of the shape table over [0, pi): 0.5 degree.
_N_ANGLES = 360


@doi(_JACOBS_2017, _PERSSON_2005)
@dataclass(frozen=True, eq=False, init=False)
class PSD2D(AnisotropicPSD):
    r"""A tabulated 2-D PSD :math:`C(q_x, q_y)` (m^4, Persson's convention) and its polar description.

    Parameters
    ----------
    qx : array_like, shape (nx,)
        Wavevectors of the columns, rad/m (e.g. ``2 pi fftfreq(nx, dx)``, any order).
    qy : array_like, shape (ny,)
        Wavevectors of the rows, rad/m.
    C : array_like, shape (ny, nx)
        PSD values, m^4, finite and >= 0.
    q_r : float, optional
        Reliability limit, rad/m: modes beyond it are not used. Default the largest full circle of the grid,
        :math:`\min(\max|q_x|, \max|q_y|)`.
    qL : float, optional
        :math:`2\pi/L` of the measurement, rad/m.
    source : str
        Origin, for messages and reports.
    n_per_decade : int
        Logarithmic bins per decade of the angular mean (as :meth:`surfaces.HeightMap.psd`).
    smoothing_deg : float
        Standard deviation, degrees, of the periodic Gaussian that averages the periodogram in angle (at least
        the mean spacing of the Fourier modes of each annulus).

    Attributes
    ----------
    radial : surfaces.PSD
        The angular mean :math:`\bar C(q)` on logarithmic bins (with ``q_rolloff`` when a plateau is seen).
    shape_table : ndarray (n_bins, 360)
        Angular shape :math:`w` of every bin at the angles ``(k + 1/2) 0.5`` degrees, mean 1.
    """

    qx: np.ndarray
    qy: np.ndarray
    C_grid: np.ndarray
    radial: PSD
    shape_table: np.ndarray
    smoothing_deg: float
    source: str

    def __init__(self, qx, qy, C, *, q_r: float | None = None, qL: float | None = None, source: str = "",
                 n_per_decade: int = 20, smoothing_deg: float = 5.0):
        where = f"PSD2D ({source})" if source else "PSD2D"
        qx = np.array(qx, dtype=float).ravel()
        qy = np.array(qy, dtype=float).ravel()
        C = np.array(C, dtype=float)
        if C.shape != (qy.size, qx.size):
            raise InputError(f"{where}: C must have shape (len(qy), len(qx)) = ({qy.size}, {qx.size}), got {C.shape}")
        for name, a in (("qx", qx), ("qy", qy)):
            if not np.all(np.isfinite(a)):
                raise InputError(f"{where}: {name} has a NaN or infinite value at index "
                                 f"{int(np.argmax(~np.isfinite(a)))}")
        bad = ~np.isfinite(C)
        if bad.any():
            i, j = np.argwhere(bad)[0]
            raise InputError(f"{where}: C is not finite at row {i}, column {j} (qy = {qy[i]:g}, qx = {qx[j]:g} "
                             "rad/m)")
        neg = C < 0
        if neg.any():
            i, j = np.argwhere(neg)[0]
            raise InputError(f"{where}: C must be >= 0 m^4 (a power spectrum), got {C[i, j]:g} at row {i}, column "
                             f"{j} (qy = {qy[i]:g}, qx = {qx[j]:g} rad/m)")
        if isinstance(n_per_decade, bool) or not isinstance(n_per_decade, (int, np.integer)) or n_per_decade < 1:
            raise InputError(f"n_per_decade: expected an integer >= 1, got {n_per_decade!r}")
        sigma = positive(smoothing_deg, "smoothing_deg")
        q_full = min(float(np.max(np.abs(qx))), float(np.max(np.abs(qy))))
        q_lim = q_full if q_r is None else min(positive(q_r, "q_r"), q_full)
        if not q_lim > 0:
            raise InputError(f"{where}: the grid has no wavevector > 0 (qx, qy all zero)")
        QX, QY = np.meshgrid(qx, qy)
        Q = np.hypot(QX, QY)
        sel = (Q > 0) & (Q <= q_lim * (1 + 1e-12))
        Qs, Cs = Q[sel], C[sel]
        if not np.any(Cs > 0):
            raise InputError(f"{where}: C is zero at every wavevector up to {q_lim:g} rad/m: no roughness")
        radial, table = _polar(Qs, np.mod(np.arctan2(QY[sel], QX[sel]), math.pi), Cs, int(n_per_decade),
                               math.radians(sigma), q_lim, qL, source)
        for a in (qx, qy, C, table):
            a.setflags(write=False)
        object.__setattr__(self, "qx", qx)
        object.__setattr__(self, "qy", qy)
        object.__setattr__(self, "C_grid", C)
        object.__setattr__(self, "radial", radial)
        object.__setattr__(self, "shape_table", table)
        object.__setattr__(self, "smoothing_deg", sigma)
        object.__setattr__(self, "source", str(source))

    def __repr__(self) -> str:
        return (f"PSD2D({self.qy.size} x {self.qx.size} grid, q {self.q_range[0]:.4g}-{self.q_range[1]:.4g} rad/m, "
                f"hrms={self.hrms():.4g} m" + (f", source={self.source!r}" if self.source else "") + ")")

    # --- the isotropic interface: the angular mean
    @property
    def q_range(self) -> tuple[float, float]:
        """Support (first and last radial bin), rad/m."""
        return self.radial.q_range

    @property
    def q_r(self):
        """Reliability limit, rad/m: the ``q_r`` given, at most (and by default) the largest full circle of the grid."""
        return self.radial.q_r

    @property
    def qL(self):
        """2 pi / L of the measurement, rad/m (None when not given)."""
        return self.radial.qL

    @property
    def q_rolloff(self):
        """Roll-off wavevector of the angular mean, rad/m, when a plateau is seen (else None)."""
        return self.radial.q_rolloff

    #: The shape is smooth in angle (a Gaussian average, interpolated by cubics).
    angular_kinks = False

    @property
    def angular_width(self) -> float:
        """Width of the narrowest feature of the angular shape, radians: twice the angular smoothing."""
        return 2.0 * math.radians(self.smoothing_deg)

    def C(self, q) -> np.ndarray:
        """Angular mean at ``q`` (rad/m), log-log interpolation of the radial bins, zero outside them."""
        return self.radial.C(q)

    def breakpoints(self) -> np.ndarray:
        """The radial bins (the angular mean is log-log linear between them)."""
        return self.radial.q

    def to_isotropic(self) -> PSD:
        """The angular mean (:attr:`radial`), the same table as :meth:`surfaces.HeightMap.psd` of the map."""
        return self.radial

    # --- the angular shape
    def C_polar(self, q, phi) -> np.ndarray:
        r""":math:`C(q, \phi) = \bar C(q)\, w(q, \phi)`, m^4 (``phi`` in radians from the x axis)."""
        q, phi = np.broadcast_arrays(np.asarray(q, dtype=float), np.asarray(phi, dtype=float))
        return np.asarray(self.radial.C(q), dtype=float) * self._shape(q, phi)

    def angular_shape(self, q, phi) -> np.ndarray:
        """The angular shape w(q, phi) (mean 1), see :meth:`surfaces.AnisotropicPSD.angular_shape`."""
        q = np.atleast_1d(np.asarray(q, dtype=float))
        phi = np.asarray(phi, dtype=float)
        if phi.shape[:1] != q.shape:
            raise InputError(f"angular_shape: expected phi with one row per wavevector ({q.size}), got shape "
                             f"{phi.shape}")
        # one interpolated row of the table per wavevector, then the periodic cubic in the angle
        index = np.broadcast_to(np.arange(q.size).reshape((q.size,) + (1,) * (phi.ndim - 1)), phi.shape)
        return _periodic_cubic(self._rows(q), index, phi)

    def slope_tensor(self, q_min: float | None = None, q_max: float | None = None) -> np.ndarray:
        r"""The slope tensor summed over the Fourier modes of the grid in the band (the data, not the smoothed
        shape): :math:`M = \sum \mathbf q\mathbf q^T C\,\Delta q_x\Delta q_y` on a uniform grid."""
        dqx, dqy = _spacing(self.qx), _spacing(self.qy)
        if dqx is None or dqy is None:
            return super().slope_tensor(q_min, q_max)
        a = self.q_range[0] if q_min is None else positive(q_min, "q_min")
        b = self.q_r if q_max is None else positive(q_max, "q_max")
        QX, QY = np.meshgrid(self.qx, self.qy)
        Q = np.hypot(QX, QY)
        m = (Q >= a * (1 - 1e-12)) & (Q <= b * (1 + 1e-12))
        w = self.C_grid[m] * dqx * dqy
        qx, qy = QX[m], QY[m]
        return np.array([[np.sum(w * qx * qx), np.sum(w * qx * qy)], [np.sum(w * qx * qy), np.sum(w * qy * qy)]])

    def anisotropy(self, q_min: float | None = None, q_max: float | None = None) -> Anisotropy:
        """Principal directions and slope ratio from the modes of the grid (see :meth:`slope_tensor`)."""
        lo = self.q_range[0] if q_min is None else positive(q_min, "q_min")
        hi = self.q_r if q_max is None else positive(q_max, "q_max")
        return Anisotropy.from_tensor(self.slope_tensor(lo, hi), lo, hi)

    def _shape(self, q: np.ndarray, phi: np.ndarray) -> np.ndarray:
        """w at (q, phi) of any shapes: linear in ln q between the bins (held beyond them), periodic cubic in phi."""
        u, inv = np.unique(q, return_inverse=True)
        return _periodic_cubic(self._rows(u), inv.reshape(q.shape), phi)

    def _rows(self, q: np.ndarray) -> np.ndarray:
        """The angular shape rows at the wavevectors ``q`` (n,): linear in ln q between the bins' rows."""
        tab = self.shape_table
        nb = tab.shape[0]
        u = np.interp(np.log(np.maximum(q, 1e-300)), np.log(self.radial.q), np.arange(nb, dtype=float))
        i0 = np.minimum(np.floor(u).astype(np.int64), max(nb - 2, 0))
        t = np.clip(u - i0, 0.0, 1.0)[:, None]
        return (1.0 - t) * tab[i0] + t * tab[np.minimum(i0 + 1, nb - 1)]


# ---------------------------------------------------------------------------------------------------------
def _polar(Q, phi, C, n_per_decade, sigma, q_lim, qL, source):
    """The radial PSD (annular means on log bins) and the angular shape of every bin."""
    b = np.floor(n_per_decade * np.log10(Q) + 1e-9).astype(np.int64)
    b -= b.min()
    nb = int(b.max()) + 1
    count = np.bincount(b, minlength=nb).astype(float)
    keep = count > 0
    q_bin = np.exp(np.bincount(b, weights=np.log(Q), minlength=nb)[keep] / count[keep])
    C_bin = np.bincount(b, weights=C, minlength=nb)[keep] / count[keep]
    # angular histograms per bin, smoothed by a periodic Gaussian (Fourier multiplier of harmonic e^{2 i m phi})
    k = np.minimum((phi * (_N_ANGLES / math.pi)).astype(np.int64), _N_ANGLES - 1)
    idx = b * _N_ANGLES + k
    S = np.bincount(idx, weights=C, minlength=nb * _N_ANGLES).reshape(nb, _N_ANGLES)[keep]
    N = np.bincount(idx, minlength=nb * _N_ANGLES).reshape(nb, _N_ANGLES)[keep].astype(float)
    # an annulus of n modes holds about n/2 distinct angles over pi: no finer resolution than their spacing
    sig = np.maximum(sigma, 2.0 * math.pi / count[keep])
    m = np.arange(_N_ANGLES // 2 + 1)
    mult = np.exp(-0.5 * (2.0 * m[None, :] * sig[:, None]) ** 2)
    Ss = np.fft.irfft(np.fft.rfft(S, axis=1) * mult, n=_N_ANGLES, axis=1)
    Ns = np.fft.irfft(np.fft.rfft(N, axis=1) * mult, n=_N_ANGLES, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(Ns > 1e-9 * Ns.max(axis=1, keepdims=True), Ss / Ns, C_bin[:, None])
    w = np.maximum(w, 0.0) / np.where(C_bin > 0, C_bin, 1.0)[:, None]
    mean = w.mean(axis=1, keepdims=True)
    w = np.where(mean > 0, w / np.where(mean > 0, mean, 1.0), 1.0)
    ok = C_bin > 0
    radial = with_estimated_rolloff(PSD(q_bin[ok], C_bin[ok], q_r=q_lim, extrapolated=False,
                                        source=f"{source or 'PSD2D'} (radial average)", qL=qL))
    return radial, np.ascontiguousarray(w[ok])


def _periodic_cubic(rows: np.ndarray, index: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """4-point Lagrange interpolation at the angles ``phi`` of the tables ``rows[index]`` (each over [0, pi),
    sampled at (k + 1/2) pi/n); ``index`` and ``phi`` have the same shape. Clipped at 0."""
    na = rows.shape[1]
    flat = np.ascontiguousarray(rows).ravel()
    base = np.asarray(index, dtype=np.int64) * na
    x = np.mod(phi, math.pi) * (na / math.pi) - 0.5
    j = np.floor(x).astype(np.int64)
    f = x - j
    wts = (-f * (f - 1) * (f - 2) / 6, (f + 1) * (f - 1) * (f - 2) / 2, -(f + 1) * f * (f - 2) / 2,
           (f + 1) * f * (f - 1) / 6)
    out = np.zeros(phi.shape)
    for d, wd in zip((-1, 0, 1, 2), wts):
        out += wd * flat[base + np.mod(j + d, na)]
    return np.maximum(out, 0.0)


def _spacing(q: np.ndarray) -> float | None:
    """The step of a uniform grid (any order, e.g. fftfreq), or None when the values are not evenly spaced."""
    u = np.unique(q)
    if u.size < 2:
        return None
    d = np.diff(u)
    return float(d.mean()) if np.allclose(d, d.mean(), rtol=1e-6) else None


def periodogram_2d(h: np.ndarray, dx: float, dy: float, w: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Windowed 2-D periodogram (Persson's convention, see the module docstring) on the full plane.

    Parameters
    ----------
    h : ndarray (ny, nx)
        Heights (detrended), m.
    dx, dy : float
        Spacings along x (columns) and y (rows), m.
    w : ndarray (ny, nx)
        Window.

    Returns
    -------
    qx (nx,), qy (ny,), C (ny, nx)
        Wavevectors in increasing order (rad/m) and the PSD, m^4.
    """
    ny, nx = h.shape
    Z = np.fft.fftshift(np.fft.fft2(w * h))
    C = finite_float(dx, "dx") * finite_float(dy, "dy") * np.abs(Z) ** 2 / ((2 * np.pi) ** 2 * nx * ny
                                                                           * float(np.mean(w**2)))
    qx = 2 * np.pi * np.fft.fftshift(np.fft.fftfreq(nx, dx))
    qy = 2 * np.pi * np.fft.fftshift(np.fft.fftfreq(ny, dy))
    return qx, qy, C
