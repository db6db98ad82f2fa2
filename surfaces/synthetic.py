r"""Synthetic surfaces: seeded Fourier synthesis of isotropic height maps and line profiles from any PSD,
and the documented example road.

Heights are sums of Fourier modes on a periodic grid,

.. math:: h(\mathbf x) = \sum_{\mathbf q} a_{\mathbf q} e^{i\mathbf q\cdot\mathbf x}, \qquad
          \langle |a_{\mathbf q}|^2\rangle = C(|\mathbf q|)\,\Delta q_x \Delta q_y ,

(line profiles: :math:`\langle |a_q|^2\rangle = C_{1D}(|q|)\,\Delta q`), so that the synthetic surface has
the requested PSD in the Persson convention. The modes are the Fourier transform of seeded white Gaussian
noise scaled by the square root of the PSD (Gaussian heights); with ``random_amplitude=False`` only the phases
are random and every mode has exactly the expected amplitude (Persson et al. 2005, Sec. 2; Jacobs et al.
2017, Sec. 3).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import fft

from frictioncite import doi

from ._util import positive
from .errors import InputError
from .maps import HeightMap
from .profiles import Profile, ProfileSet
from .psd import SelfAffine
from .spectra import PSD1D, abel_forward

__all__ = ["synthesize_map", "synthesize_profiles", "example_road"]

_PERSSON_2005 = "10.1088/0953-8984/17/1/R01"
_JACOBS_2017 = "10.1088/2051-672X/aa51f8"


@doi(_PERSSON_2005, _JACOBS_2017)
def synthesize_map(psd, n: int = 512, *, length: float | None = None, ny: int | None = None,
                   seed: int | None = None, random_amplitude: bool = True) -> HeightMap:
    """Periodic isotropic height map with the 2D PSD ``psd``.

    Parameters
    ----------
    psd : surfaces.PSD or surfaces.SelfAffine (or anything with ``C(q)`` and ``q_range``)
        Isotropic 2D PSD, Persson convention. Modes with :math:`|q|` outside its support get zero amplitude;
        modes past the grid's Nyquist wavevector cannot be represented (the map is band-limited).
    n : int
        Samples along x.
    length : float, optional
        Side length along x, m. Default :math:`2\\pi/q_{start}`, so the lowest wavevector of the PSD is the
        fundamental of the map.
    ny : int, optional
        Samples along y (default ``n``; same spacing as x).
    seed : int, optional
        Seed of :func:`numpy.random.default_rng`; the same seed gives the same map.
    random_amplitude : bool
        True: Gaussian random field (random amplitudes and phases). False: random phases, amplitudes exactly
        :math:`\\sqrt{C\\,\\Delta q^2}` (less scatter of the realized PSD).

    Returns
    -------
    HeightMap
        ``periodic=True``.
    """
    n = _count(n, "n")
    ny = n if ny is None else _count(ny, "ny")
    lo = float(psd.q_range[0])
    L = 2.0 * math.pi / lo if length is None else positive(length, "length")
    dx = L / n
    rng = np.random.default_rng(seed)
    W = fft.rfft2(rng.standard_normal((ny, n)))
    if not random_amplitude:
        W = W / np.maximum(np.abs(W), 1e-300) * math.sqrt(n * ny)
    qx = 2 * np.pi * fft.rfftfreq(n, dx)
    qy = 2 * np.pi * fft.fftfreq(ny, dx)
    qmag = np.hypot(qx[None, :], qy[:, None])
    dq2 = (2 * np.pi) ** 2 / (L * ny * dx)
    qmag[0, 0] = lo  # the mean (q = 0) gets no amplitude: placeholder avoids C(0), zeroed below
    F = np.sqrt(n * ny * np.asarray(psd.C(qmag), dtype=float) * dq2)
    F[0, 0] = 0.0
    z = fft.irfft2(W * F, s=(ny, n))
    return HeightMap(z, dx=dx, dy=dx, periodic=True, source=f"synthetic map (seed={seed}) of {_label(psd)}")


@doi(_PERSSON_2005, _JACOBS_2017)
def synthesize_profiles(psd, n_profiles: int = 1, n: int = 4096, *, length: float | None = None,
                        seed: int | None = None, random_amplitude: bool = True) -> ProfileSet:
    """Periodic line profiles with the PSD ``psd``.

    Parameters
    ----------
    psd : surfaces.PSD, surfaces.SelfAffine or surfaces.PSD1D
        A 2D isotropic PSD (then the profiles are line scans across that surface: their 1D PSD is the
        Abel transform :func:`surfaces.spectra.abel_forward`) or directly a 1D PSD.
    n_profiles : int
        Number of independent profiles.
    n : int
        Samples per profile.
    length : float, optional
        Profile length, m; default :math:`2\\pi/q_{start}`.
    seed : int, optional
        Seed of :func:`numpy.random.default_rng`.
    random_amplitude : bool
        See :func:`synthesize_map`.

    Returns
    -------
    ProfileSet
        Periodic profiles named ``synthetic 1``, ``synthetic 2``...
    """
    n = _count(n, "n")
    n_profiles = _count(n_profiles, "n_profiles", minimum=1)
    lo = float(psd.q_range[0])
    L = 2.0 * math.pi / lo if length is None else positive(length, "length")
    dx = L / n
    q = 2 * np.pi * fft.rfftfreq(n, dx)
    C1 = np.zeros_like(q)
    C1[1:] = psd.C(q[1:]) if isinstance(psd, PSD1D) else _c1d_on(psd, q[1:])
    rng = np.random.default_rng(seed)
    W = fft.rfft(rng.standard_normal((n_profiles, n)), axis=-1)
    if not random_amplitude:
        W = W / np.maximum(np.abs(W), 1e-300) * math.sqrt(n)
    F = np.sqrt(n * C1 * (2 * np.pi / L))
    z = fft.irfft(W * F, n=n, axis=-1)
    x = dx * np.arange(n)
    src = f"synthetic profiles (seed={seed}) of {_label(psd)}"
    return ProfileSet(tuple(Profile(x, row, name=f"synthetic {i + 1}", source=src, periodic=True)
                            for i, row in enumerate(z)), source=src)


@doi(_PERSSON_2005, "10.1063/1.1388626")
def example_road() -> SelfAffine:
    r"""A synthetic, road-like isotropic PSD for demonstrations: **not a measurement**.

    ``SelfAffine(hurst=0.8, q0=2*pi/5 mm, q1=1e7 rad/m, hrms=0.35 mm, qL=2*pi/0.1 m)``, i.e.

    .. math:: C(q) = C_0 q^{-2(1+H)} \; (q_0 \le q \le q_1), \qquad C = C_0 q_0^{-2(1+H)} \; (q_L \le q < q_0),

    with :math:`C_0 \approx 1.6\times10^{-3}` m^4 (rad/m)^3.6 and an rms slope of about 3.9 (dominated by the
    extrapolated microtexture).

    Where the numbers come from:

    * H = 0.8: the Hurst exponent used for road surfaces in Persson's rubber-friction theory (Persson,
      J. Chem. Phys. 115, 3840 (2001); Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)). The real
      CAPTIF chip-seal scans in ``shared/data/road_profiles``, analysed with this package
      (``read_profiles(...).psd().to_isotropic()``), give H = 0.72-0.78 between 1.3e3 and 2e4 rad/m.
    * Roll-off :math:`q_0 = 2\pi/5\,\mathrm{mm} \approx 1.26\times10^3` rad/m: the PSD of an asphalt flattens
      at wavelengths of the order of its largest stones (a few mm for a fine, dense asphalt). The coarse
      CAPTIF chip seal rolls off near 200 rad/m (about 30 mm) by :func:`surfaces.fit_rolloff`.
    * :math:`q_L = 2\pi/0.1\,\mathrm{m}`: the 100 mm segment of the ISO 13473-1 mean profile depth.
    * :math:`h_{rms}` = 0.35 mm: synthetic profiles of this PSD have a mean profile depth of about 0.7 mm
      (:func:`surfaces.mpd`), a fine road texture; the CAPTIF chip seal has Rq = 2.5 mm and MPD = 3.0-3.4 mm.
    * :math:`q_1 = 10^7` rad/m (wavelength 0.6 um): a micrometre-scale short-distance cut-off as in Persson's
      road calculations, far past a road profilometer's reliability limit (CAPTIF: Nyquist 8.4e4 rad/m), so
      everything above about 1e5 rad/m is the power law continued, not data.

    Returns
    -------
    SelfAffine
    """
    return SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e7, hrms=0.35e-3, qL=2 * math.pi / 0.1)


def _c1d_on(psd, q: np.ndarray) -> np.ndarray:
    """Abel transform of ``psd`` at the FFT wavevectors ``q``: exact on a 256-per-decade grid, log-log
    interpolated in between (C1D is smooth; exact evaluation at every FFT point would cost n x knots)."""
    if q.size <= 1024:
        return abel_forward(psd, q)
    n_grid = int(math.ceil(256 * math.log10(q[-1] / q[0]))) + 1
    grid = np.geomspace(q[0], q[-1], max(n_grid, 2))
    Cg = abel_forward(psd, grid)
    pos = Cg > 0
    if pos.sum() < 2:
        return abel_forward(psd, q)
    out = np.exp(np.interp(np.log(q), np.log(grid[pos]), np.log(Cg[pos])))
    return np.where(q <= grid[pos][-1] * (1 + 1e-12), out, 0.0)


def _count(v, name: str, minimum: int = 4) -> int:
    try:
        i = int(v)
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected an integer, got {v!r}") from None
    if i != v or i < minimum:
        raise InputError(f"{name}: expected an integer >= {minimum}, got {v!r}")
    return i


def _label(psd) -> str:
    return getattr(psd, "source", "") or type(psd).__name__
