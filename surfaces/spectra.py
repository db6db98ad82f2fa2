r"""Line-scan (1D) power spectra and their exact link to the isotropic 2D PSD.

Persson's convention (``docs/conventions.md``). A line scan has the two-sided 1D PSD

.. math:: C_{1D}(q) = \frac{1}{2\pi}\int dx\,\langle h(x)h(0)\rangle e^{-iqx}, \qquad
          h_{rms}^2 = \int_{-\infty}^{\infty} C_{1D}(q)\,dq ,

and for an isotropic surface it is the Abel transform of the 2D PSD :math:`C(q)`
(Persson et al., J. Phys.: Condens. Matter 17, R1 (2005), appendix; Jacobs, Junge, Pastewka,
Surf. Topogr.: Metrol. Prop. 5, 013001 (2017), Sec. 2)

.. math:: C_{1D}(q) = 2\int_q^\infty \frac{k\,C(k)}{\sqrt{k^2-q^2}}dk, \qquad
          C(q) = -\frac{1}{\pi}\int_q^\infty \frac{C_{1D}'(k)}{\sqrt{k^2-q^2}}dk .

Both integrals are evaluated after the substitution :math:`k^2 = q^2 + u^2`, which removes the inverse
square-root singularity (:math:`dk/\sqrt{k^2-q^2} = du/k`), with Gauss-Legendre quadrature on short
sub-intervals; a power-law tail to infinity is integrated in closed form with the regularized incomplete
Beta function. For a pure power law :math:`C_{1D} = A q^{-(1+2H)}` the pair reduces to

.. math:: C(q) = \frac{\Gamma(1+H)}{\sqrt{\pi}\,\Gamma(H+1/2)}\,\frac{C_{1D}(q)}{q} .
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from ._util import band, loglog_interp, optional_positive, positive
from .errors import AccuracyWarning, InputError
from .powerlaw import gamma_factor, loglog_line
from .psd import PSD, SelfAffine
from .psdfit import SelfAffineFit, fit_table_self_affine, with_estimated_rolloff

__all__ = ["PSD1D", "abel_forward", "gamma_factor", "periodogram_1d", "log_bin"]

_JACOBS_2017 = "10.1088/2051-672X/aa51f8"
_PERSSON_2005 = "10.1088/0953-8984/17/1/R01"
#: Gauss-Legendre order per sub-interval of the Abel integrals; sub-intervals span <= 1/64 decade.
_GL_ORDER = 8
_KNOTS_PER_DECADE = 64
_REL_ERROR_FLOOR = 0.1
_CHUNK = 128


@dataclass(frozen=True, eq=False)
class PSD1D:
    r"""Two-sided 1D PSD of line scans (Persson convention), on a log-binned grid.

    Parameters
    ----------
    q : array_like
        Bin centres (geometric mean of the wavevectors pooled in the bin), rad/m, strictly increasing.
    C : array_like
        Mean two-sided :math:`C_{1D}` in the bin, m^3, > 0.
    spread : array_like, optional
        Per-bin spread, m^3: the standard deviation across profiles of the per-profile bin means when at
        least two profiles contribute, else the standard deviation of the periodogram ordinates in the bin.
    stderr : array_like, optional
        Standard error of ``C`` (``spread`` over the square root of the number of profiles, or of
        ordinates for a single profile), m^3.
    counts : array_like of int, optional
        Number of periodogram ordinates pooled in each bin (over all profiles).
    widths : array_like, optional
        Bandwidth of each bin, rad/m: the summed spacing :math:`2\pi/L` of the ordinates in the bin, per
        contributing profile. Default: from the grid (edges at the geometric midpoints).
    n_profiles : int
        Number of profiles averaged.
    qL : float, optional
        :math:`2\pi/L` of the longest profile, rad/m.
    q_r : float, optional
        Reliability limit (default Nyquist :math:`\pi/\Delta x` of the coarsest profile), rad/m.
    source : str
        Provenance (file names).
    history : tuple of str
        Preparation steps applied (dropout filling with fractions, resampling, detrending, window).
    """

    q: np.ndarray
    C_values: np.ndarray
    spread: np.ndarray
    stderr: np.ndarray
    counts: np.ndarray
    widths: np.ndarray
    n_profiles: int = 1
    qL: float | None = None
    q_r: float | None = None
    source: str = ""
    history: tuple = field(default_factory=tuple)

    def __init__(self, q, C, spread=None, stderr=None, counts=None, n_profiles: int = 1, qL: float | None = None,
                 q_r: float | None = None, source: str = "", history=(), widths=None):
        where = f"PSD1D ({source})" if source else "PSD1D"
        q = np.array(q, dtype=float).ravel()
        C = np.array(C, dtype=float).ravel()
        if q.size < 2 or q.size != C.size:
            raise InputError(f"{where}: q and C must have the same length >= 2, got {q.size} and {C.size}")
        if not (np.isfinite(q).all() and np.isfinite(C).all()):
            raise InputError(f"{where}: q and C must be finite")
        if (q <= 0).any() or (np.diff(q) <= 0).any():
            raise InputError(f"{where}: q must be > 0 and strictly increasing")
        if (C <= 0).any():
            raise InputError(f"{where}: C must be > 0 (row {int(np.argmax(C <= 0))})")
        spread = np.zeros_like(C) if spread is None else np.array(spread, dtype=float).ravel()
        stderr = np.zeros_like(C) if stderr is None else np.array(stderr, dtype=float).ravel()
        counts = np.ones(C.size, dtype=int) if counts is None else np.array(counts, dtype=int).ravel()
        if widths is None:
            mid = np.sqrt(q[1:] * q[:-1])
            edges = np.concatenate([[q[0] ** 2 / mid[0]], mid, [q[-1] ** 2 / mid[-1]]])
            widths = np.diff(edges)
        widths = np.array(widths, dtype=float).ravel()
        for name, arr in (("spread", spread), ("stderr", stderr), ("counts", counts), ("widths", widths)):
            if arr.shape != C.shape:
                raise InputError(f"{where}: {name} must have the length of C ({C.size}), got {arr.size}")
        if not (widths > 0).all():
            raise InputError(f"{where}: widths must be > 0 rad/m")
        for arr in (q, C, spread, stderr, counts, widths):
            arr.setflags(write=False)
        object.__setattr__(self, "q", q)
        object.__setattr__(self, "C_values", C)
        object.__setattr__(self, "spread", spread)
        object.__setattr__(self, "stderr", stderr)
        object.__setattr__(self, "counts", counts)
        object.__setattr__(self, "widths", widths)
        object.__setattr__(self, "n_profiles", int(n_profiles))
        object.__setattr__(self, "qL", optional_positive(qL, "qL"))
        object.__setattr__(self, "q_r", optional_positive(q_r, "q_r"))
        object.__setattr__(self, "source", str(source))
        object.__setattr__(self, "history", tuple(history))

    def __repr__(self) -> str:
        return (f"PSD1D({self.q.size} points, q {self.q[0]:.4g}-{self.q[-1]:.4g} rad/m, hrms={self.hrms():.4g} m, "
                f"{self.n_profiles} profile{'s' if self.n_profiles != 1 else ''}"
                + (f", q_r={self.q_r:.4g}" if self.q_r is not None else "")
                + (f", source={self.source!r}" if self.source else "") + ")")

    # ------------------------------------------------------------------ construction from a 2D PSD
    @classmethod
    @doi(_PERSSON_2005, _JACOBS_2017)
    def from_isotropic(cls, psd, q=None, n_per_decade: int = 32) -> "PSD1D":
        r"""The 1D PSD of line scans across an isotropic surface with 2D PSD ``psd`` (forward Abel transform).

        .. math:: C_{1D}(q) = 2\int_q^\infty \frac{k\,C(k)}{\sqrt{k^2-q^2}}\,dk

        Parameters
        ----------
        psd : surfaces.PSD or surfaces.SelfAffine
            Isotropic 2D PSD.
        q : array_like, optional
            Where to evaluate, rad/m; default a log grid over the support of ``psd``.
        n_per_decade : int
            Density of the default grid.
        """
        lo, hi = psd.q_range
        if q is None:
            n = max(8, int(math.ceil(n_per_decade * math.log10(hi / lo))) + 1)
            q = np.geomspace(lo, hi, n)[:-1]  # C1D(q1) = 0: stop one point short
        q = np.asarray(q, dtype=float)
        C1 = abel_forward(psd, q)
        if (C1 <= 0).any():
            raise InputError(f"q: C1D vanishes at q >= {q[C1 <= 0][0]:g} rad/m (past the support of the PSD)")
        return cls(q, C1, qL=lo, q_r=getattr(psd, "q_r", None), source=f"Abel transform of {psd.source or 'PSD'}")

    # ------------------------------------------------------------------ basic interface
    @property
    def q_range(self) -> tuple[float, float]:
        """(first, last) bin centre, rad/m."""
        return float(self.q[0]), float(self.q[-1])

    def C(self, q):
        """:math:`C_{1D}` at ``q`` (rad/m), log-log interpolation, zero outside the table."""
        return loglog_interp(q, self.q, self.C_values)

    def moment(self, n: int, q_min: float | None = None, q_max: float | None = None) -> float:
        r"""Two-sided moment :math:`\int_{-\infty}^{\infty} |q|^n C_{1D}\,dq \approx 2\sum_b q_b^n C_b w_b`.

        The sum runs over the bins whose centre lies in ``[q_min, q_max]`` (default all), each weighted by its
        bandwidth :math:`w_b`; for profiles of one length ``moment(0)`` is exactly the mean square height of
        the prepared profiles (discrete Parseval identity)."""
        m = np.ones(self.q.size, dtype=bool)
        if q_min is not None:
            m &= self.q >= positive(q_min, "q_min") * (1 - 1e-12)
        if q_max is not None:
            m &= self.q <= positive(q_max, "q_max") * (1 + 1e-12)
        if not m.any():
            raise InputError(f"band [{q_min}, {q_max}] rad/m contains no bin of the table "
                             f"[{self.q[0]:g}, {self.q[-1]:g}]")
        return 2.0 * float(np.sum(self.q[m] ** n * self.C_values[m] * self.widths[m]))

    def hrms(self, q_min: float | None = None, q_max: float | None = None) -> float:
        r"""Profile rms height (band-limited), m: :math:`h_{rms}^2 = 2\int C_{1D}\,dq`."""
        return math.sqrt(self.moment(0, q_min, q_max))

    def rms_slope(self, q_min: float | None = None, q_max: float | None = None) -> float:
        r"""Rms slope along the profile (band-limited): :math:`2\int q^2 C_{1D}\,dq`. For an isotropic surface
        the 2D rms slope is :math:`\sqrt{2}` times this."""
        return math.sqrt(self.moment(2, q_min, q_max))

    def with_band(self, q_min: float | None = None, q_max: float | None = None) -> "PSD1D":
        """The bins inside ``[q_min, q_max]``."""
        m = band(self.q, q_min, q_max, "PSD1D.with_band")
        return PSD1D(self.q[m], self.C_values[m], self.spread[m], self.stderr[m], self.counts[m], self.n_profiles,
                     self.qL, self.q_r, self.source, self.history, self.widths[m])

    def fit_self_affine(self, q_min: float | None = None, q_max: float | None = None) -> SelfAffineFit:
        """Self-affine fit (H, C0 of the equivalent isotropic PSD) on a band; see :func:`surfaces.fit_self_affine`."""
        if q_max is None and self.q_r is not None:
            q_max = self.q_r
        return fit_table_self_affine(self.q, self.C_values, "1d", q_min, q_max,
                                     where=self.source or type(self).__name__)

    # ------------------------------------------------------------------ 1D -> 2D
    @doi(_PERSSON_2005, _JACOBS_2017)
    def to_isotropic(self, method: str = "abel", *, q_min: float | None = None, q_max: float | None = None,
                     hurst: float | None = None, smoothing: float | None = None,
                     tail_band: tuple[float, float] | None = None) -> PSD:
        r"""Isotropic 2D PSD :math:`C(q)` of the surface the profiles were scanned on.

        ``method="abel"`` (default) evaluates the exact inverse Abel transform

        .. math:: C(q) = -\frac{1}{\pi}\int_q^\infty \frac{C_{1D}'(k)}{\sqrt{k^2-q^2}}\,dk

        on a smooth representation of the data: :math:`\ln C_{1D}` is fitted with a cubic smoothing spline in
        :math:`\ln q` (weights :math:`1/((\sigma_C/C)^2 + 0.1^2)` from the standard error of each bin; smoothing
        by generalized cross-validation unless ``smoothing`` is given). Where the smoothed :math:`C_{1D}` rises
        with q (noise; an isotropic surface with a monotone C has a monotone :math:`C_{1D}`) its derivative is
        set to zero, which keeps C positive. Past ``q_max`` the data are extended by the power law
        :math:`C_{1D}(q_{max})(q/q_{max})^{-(1+2H)}` with H fitted on ``tail_band`` (default the last decade
        below ``q_max``) or given. The tail's contribution is integrated in closed form,
        :math:`\int_{q_m}^\infty k^{-s}(k^2-q^2)^{-1/2}dk = \tfrac12 q^{-s} B(\tfrac s2,\tfrac12)\,
        I_{(q/q_m)^2}(\tfrac s2, \tfrac12)`.

        ``method="gamma"`` uses the power-law form
        :math:`C(q) = \Gamma(1+H)/(\sqrt\pi\,\Gamma(H+\tfrac12))\;C_{1D}(q)/q` with H fitted on the band (or
        given): exact for a pure power law only.

        Parameters
        ----------
        method : {"abel", "gamma"}
        q_min, q_max : float, optional
            Band of the result, rad/m. Default: from the first bin to the reliability limit ``q_r``.
        hurst : float, optional
            Hurst exponent for the tail (abel) or the power-law form (gamma); default fitted.
        smoothing : float, optional
            Smoothing parameter lambda of :func:`scipy.interpolate.make_smoothing_spline`; ``None`` = GCV,
            ``0`` = interpolate the data.
        tail_band : (float, float), optional
            Band (rad/m) for the fit of the tail's H (abel).

        Returns
        -------
        surfaces.PSD
            Tabulated on the bins inside the band, with ``q_r``, ``qL`` and ``hurst`` set, ``q_rolloff`` from
            :func:`surfaces.fit_rolloff` when a plateau is seen, and ``extrapolated=False`` (nothing past
            ``q_r`` is returned).
        """
        from scipy import interpolate
        hi_default = self.q_r if self.q_r is not None else self.q[-1]
        m = band(self.q, q_min, hi_default if q_max is None else q_max, "to_isotropic")
        q, C1 = self.q[m], self.C_values[m]
        # Weights 1/var(ln C): the relative standard error of each bin plus a 10 % floor, so that neither a
        # few very precise bins nor sampling statistics alone (profiles differ more than the periodogram
        # scatter suggests) dictate the smoothing.
        rel = self.stderr[m] / C1
        w = 1.0 / (rel**2 + _REL_ERROR_FLOOR**2)
        if method == "gamma":
            H = hurst if hurst is not None else self._fit_hurst(q, C1)
            C2 = gamma_factor(_check_hurst(H)) * C1 / q
            H_out = float(H)
        elif method == "abel":
            if q.size < 5:
                raise InputError(f"to_isotropic: {q.size} bins in the band are too few for the inverse-Abel "
                                 "conversion (need >= 5); use method='gamma' or a wider band")
            x, y = np.log(q), np.log(C1)
            lam = None if smoothing is None else float(smoothing)
            spline = interpolate.make_smoothing_spline(x, y, w=w / w.mean(), lam=lam)
            if hurst is None:
                lo_t, hi_t = tail_band if tail_band is not None else (q[-1] / 10.0, q[-1])
                sel = (q >= lo_t * (1 - 1e-12)) & (q <= hi_t * (1 + 1e-12))
                if sel.sum() < 3:
                    sel = np.arange(q.size) >= q.size - 3
                H_out = self._fit_hurst(q[sel], C1[sel], strict=False)
            else:
                H_out = _check_hurst(hurst)
            C2 = _inverse_abel(q, spline, beta_tail=1.0 + 2.0 * H_out)
        else:
            raise InputError(f"method: expected 'abel' or 'gamma', got {method!r}")
        if (C2 <= 0).any() or not np.isfinite(C2).all():
            bad = q[~(C2 > 0)][0]
            raise InputError(f"to_isotropic ({self.source}): the inverse Abel transform is not positive at "
                             f"q = {bad:g} rad/m (C1D rises too steeply there); smooth more (smoothing=...), "
                             "narrow the band or use method='gamma'")
        return with_estimated_rolloff(PSD(q, C2, q_r=self.q_r, extrapolated=False, source=self.source, qL=self.qL,
                                          hurst=H_out))

    def _fit_hurst(self, q, C1, strict: bool = True) -> float:
        slope, _, _ = loglog_line(q, C1, where=f"PSD1D ({self.source})")
        H = (-slope - 1.0) / 2.0
        if strict or 0.0 < H <= 1.0:
            return _check_hurst(H, fitted=True)
        # The tail only shapes C near the top of the band; a noise floor (H < 0) must not stop the conversion.
        clamped = min(max(H, 0.01), 1.0)
        warnings.warn(f"to_isotropic ({self.source}): the 1D PSD is not self-affine on [{q[0]:.3g}, {q[-1]:.3g}] "
                      f"rad/m (fitted H = {H:.2f}, e.g. an instrument noise floor); the tail past the band uses "
                      f"H = {clamped:.2f}. Lower q_max (e.g. to the reliability limit) or give hurst=.",
                      AccuracyWarning, stacklevel=3)
        return clamped


# ---------------------------------------------------------------------- public helpers


@doi(_PERSSON_2005, _JACOBS_2017)
def abel_forward(psd, q) -> np.ndarray:
    r""":math:`C_{1D}(q) = 2\int_q^\infty k\,C(k)/\sqrt{k^2-q^2}\,dk = 2\int_0^\infty C(\sqrt{q^2+u^2})\,du`.

    Parameters
    ----------
    psd : surfaces.PSD or surfaces.SelfAffine or object with ``C(q)`` and ``q_range``
        Isotropic 2D PSD (zero outside its support).
    q : array_like
        Wavevectors, rad/m (> 0).

    Returns
    -------
    numpy.ndarray
        :math:`C_{1D}(q)` in m^3; zero for q past the support.
    """
    from scipy import special
    q = np.asarray(q, dtype=float)
    if (q <= 0).any() or not np.isfinite(q).all():
        raise InputError("q: expected finite wavevectors > 0 rad/m")
    knots = _knots_of(psd)
    t, wt = special.roots_legendre(_GL_ORDER)
    flat = q.reshape(-1)
    out = np.empty(flat.size)
    for start in range(0, flat.size, _CHUNK):  # bounded memory: chunk x knots x order evaluations
        kq = flat[start:start + _CHUNK, None]
        lo = np.maximum(knots[:-1][None, :], kq)
        hi = np.maximum(knots[1:][None, :], kq)
        u_lo, u_hi = np.sqrt(lo**2 - kq**2), np.sqrt(hi**2 - kq**2)
        half = 0.5 * (u_hi - u_lo)
        u = 0.5 * (u_hi + u_lo)[..., None] + half[..., None] * t
        # Evaluate inside each sub-interval: clip away round-off that would fall outside the support.
        k = np.clip(np.sqrt(kq[..., None] ** 2 + u**2), lo[..., None], hi[..., None])
        vals = np.asarray(psd.C(k), dtype=float)
        out[start:start + _CHUNK] = 2.0 * np.sum(half * np.sum(vals * wt, axis=-1), axis=-1)
    return out.reshape(q.shape)


def periodogram_1d(z: np.ndarray, dx: float, window=None) -> tuple[np.ndarray, np.ndarray]:
    r"""Two-sided 1D PSD (Persson convention) of one uniformly sampled profile at :math:`q_k = 2\pi k/L`, k >= 1.

    Uses :func:`scipy.signal.periodogram` (density scaling, window power normalized so that the variance
    is preserved): :math:`C_{1D}(q) = P_{two\text{-}sided}(f)/(2\pi)` with :math:`q = 2\pi f`.
    The Nyquist ordinate of an even-length profile is dropped (it is aliased).

    Parameters
    ----------
    z : numpy.ndarray
        Heights, m, finite (fill dropouts first); shape (n,) or (n_profiles, n) for profiles sharing dx.
    dx : float
        Spacing, m.
    window : str or None
        Any :func:`scipy.signal.get_window` name; ``None``/"none"/"boxcar" for no window.

    Returns
    -------
    q, C1D : numpy.ndarray
    """
    win = "boxcar" if window in (None, "none", "boxcar") else window
    f, P = _signal().periodogram(z, fs=1.0 / dx, window=win, detrend=False, return_onesided=True, scaling="density",
                              axis=-1)
    # one-sided -> two-sided: scipy doubled every ordinate except DC and (even n) Nyquist.
    n_interior = (np.shape(z)[-1] - 1) // 2
    return 2.0 * np.pi * f[1:n_interior + 1], P[..., 1:n_interior + 1] / 2.0 / (2.0 * np.pi)


def log_bin(q_list, C_list, n_per_decade: int = 20, dq_list=None):
    """Average periodogram ordinates of several profiles on a common logarithmic grid.

    Bin b collects the ordinates with ``floor(n_per_decade * log10(q)) == b`` (bins anchored at whole
    decades, so profiles of different lengths share bins).

    Parameters
    ----------
    q_list, C_list : sequences of numpy.ndarray
        Per-profile wavevectors and ordinates.
    n_per_decade : int
        Bins per decade.
    dq_list : sequence of float, optional
        Spacing of each profile's ordinates (2 pi / L), rad/m; default ``q[0]`` (ordinates at k dq, k >= 1).

    Returns
    -------
    q, C, spread, stderr, counts, widths : numpy.ndarray
        See :class:`PSD1D`; empty bins are left out.
    """
    if n_per_decade < 1:
        raise InputError(f"n_per_decade: expected an integer >= 1, got {n_per_decade!r}")
    b_all = [np.floor(n_per_decade * np.log10(q) + 1e-9).astype(int) for q in q_list]
    b0 = min(int(b.min()) for b in b_all)
    nb = max(int(b.max()) for b in b_all) - b0 + 1
    count = np.zeros((len(q_list), nb))
    s1 = np.zeros_like(count)
    s2 = np.zeros_like(count)
    slq = np.zeros(nb)
    band = np.zeros(nb)
    dq_list = [q[0] for q in q_list] if dq_list is None else dq_list
    for p, (b, q, C) in enumerate(zip(b_all, q_list, C_list)):
        idx = b - b0
        count[p] = np.bincount(idx, minlength=nb)
        band += count[p] * dq_list[p]
        s1[p] = np.bincount(idx, weights=C, minlength=nb)
        s2[p] = np.bincount(idx, weights=C * C, minlength=nb)
        slq += np.bincount(idx, weights=np.log(q), minlength=nb)
    n = count.sum(axis=0)
    keep = n > 0
    n, count, s1, s2, slq, band = n[keep], count[:, keep], s1[:, keep], s2[:, keep], slq[keep], band[keep]
    C = s1.sum(axis=0) / n
    with np.errstate(invalid="ignore", divide="ignore"):
        per_profile = np.where(count > 0, s1 / np.where(count > 0, count, 1), np.nan)
        n_prof = (count > 0).sum(axis=0)
        across = np.nanstd(per_profile, axis=0, ddof=1) if len(q_list) > 1 else np.zeros_like(C)
        within_var = np.maximum(s2.sum(axis=0) / n - C**2, 0.0) * n / np.maximum(n - 1, 1)
    within = np.where(n > 1, np.sqrt(within_var), C)  # one exponential ordinate: std = mean
    multi = n_prof >= 2
    spread = np.where(multi, np.nan_to_num(across), within)
    stderr = np.where(multi, spread / np.sqrt(np.maximum(n_prof, 1)), within / np.sqrt(n))
    widths = band / np.maximum(n_prof, 1)  # bandwidth per contributing profile
    return np.exp(slq / n), C, spread, stderr, n.astype(int), widths


# ---------------------------------------------------------------------- private helpers


def _check_hurst(H, fitted: bool = False) -> float:
    H = float(H)
    if not (np.isfinite(H) and 0.0 < H <= 1.0):
        how = "fitted" if fitted else "given"
        raise InputError(f"hurst: the {how} Hurst exponent {H:.3g} is outside (0, 1]; the band is not self-affine "
                         "there: choose another band or give hurst=")
    return H


def _knots_of(psd) -> np.ndarray:
    """Break points of a PSD: between consecutive knots C is smooth (a power law for tabulated PSDs)."""
    if isinstance(psd, PSD):
        return np.asarray(psd.q, dtype=float)
    if isinstance(psd, SelfAffine):
        return psd.tabulate(_KNOTS_PER_DECADE).q
    lo, hi = (float(v) for v in psd.q_range)
    return np.geomspace(lo, hi, max(2, int(math.ceil(_KNOTS_PER_DECADE * math.log10(hi / lo))) + 1))


def _inverse_abel(q: np.ndarray, spline, beta_tail: float) -> np.ndarray:
    r"""Inverse Abel transform of :math:`C_{1D} = \exp(s(\ln k))` on ``[q[0], q[-1]]`` plus a power-law tail.

    .. math:: C(q) = \frac{1}{\pi}\left[\int_0^{u_m} g(\sqrt{q^2+u^2})\,du + \text{tail}\right],\quad
              g(k) = -\frac{C_{1D}'(k)}{k} = -\frac{C_{1D}(k)}{k^2}\,s'(\ln k)
    """
    from scipy import special
    q_m = q[-1]
    ds = spline.derivative()
    n_k = max(2, int(math.ceil(_KNOTS_PER_DECADE * math.log10(q_m / q[0]))) + 1)
    knots = np.union1d(np.geomspace(q[0], q_m, n_k), q)
    kq = q[:, None]
    lo = np.maximum(knots[:-1][None, :], kq)
    hi = np.maximum(knots[1:][None, :], kq)
    u_lo, u_hi = np.sqrt(lo**2 - kq**2), np.sqrt(hi**2 - kq**2)
    t, wt = special.roots_legendre(_GL_ORDER)
    half = 0.5 * (u_hi - u_lo)
    u = 0.5 * (u_hi + u_lo)[..., None] + half[..., None] * t
    k = np.clip(np.sqrt(kq[..., None] ** 2 + u**2), lo[..., None], hi[..., None])
    x = np.log(k)
    # Only the falling parts of C1D contribute: a rise of the smoothed C1D (noise, a few long waves) would
    # make C negative; it is treated as flat (documented regularization, exact where C1D decreases).
    g = -np.exp(spline(x)) * np.minimum(ds(x), 0.0) / k**2
    body = np.sum(half * np.sum(g * wt, axis=-1), axis=-1)
    # Tail: C1D = C_m (k/q_m)^-beta for k > q_m, so -C1D'(k) = beta C_m q_m^beta k^(-beta-1).
    C_m = float(np.exp(spline(math.log(q_m))))
    a = 0.5 * (beta_tail + 1.0)
    integral = 0.5 * q ** (-(beta_tail + 1.0)) * special.beta(a, 0.5) * special.betainc(a, 0.5, (q / q_m) ** 2)
    tail = beta_tail * C_m * q_m**beta_tail * integral
    return (body + tail) / math.pi


def _signal():
    """``scipy.signal``, imported on first use (it adds about 0.4 s to every start-up)."""
    from scipy import signal

    return signal
