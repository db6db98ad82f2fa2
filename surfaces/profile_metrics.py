r"""Texture metrics of a set of profiles: mean profile depth (ISO 13473-1) and height-difference correlation.

The computations behind :func:`surfaces.mpd`, :func:`surfaces.hdc` and :func:`surfaces.fit_hdc` (documented
there), on a :class:`surfaces.ProfileSet`: the mean profile depth of ISO 13473-1:2019 and Klüppel and Heinrich's
height-difference correlation :math:`C_z(\lambda) = \langle (z(x+\lambda) - z(x))^2\rangle` with its self-affine
fit (Rubber Chem. Technol. 73, 578 (2000)). They use only what a profile set offers (iteration over profiles with
``x``, ``z``, ``dx``, ``n``, ``where``; ``source``, ``crop``, ``fill_dropouts``, ``resample``, ``detrend``), so
that :class:`surfaces.ProfileSet` has them as methods and :mod:`surfaces.texture` adds the other inputs (a single
profile, a file).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from ._util import band, positive
from .errors import DataWarning, InputError
from .powerlaw import broken_power_law_fit

__all__ = ["MPDResult", "etd", "mean_profile_depth", "HDC", "HDCFit", "height_difference_correlation",
           "fit_height_difference_correlation"]

_ISO_13473 = "iso:13473-1:2019"
_KLUEPPEL_2000 = "10.5254/1.3547607"


# ---------------------------------------------------------------------- MPD (ISO 13473-1)


@dataclass(frozen=True, eq=False)
class MPDResult:
    """Mean profile depth per ISO 13473-1 with its segments.

    Attributes
    ----------
    mpd : float
        Mean of the valid mean segment depths (MSD) of all profiles, m (NaN, with a warning, when no
        segment is valid).
    per_profile : tuple of float
        MPD of each profile, m.
    profile_valid : tuple of bool
        Whether each profile has at least ``min_valid_fraction`` valid segments.
    is_valid : bool
        All profiles valid.
    segment_profile, segment_start, msd, dropout_ratio, spike_ratio, valid : numpy.ndarray
        Per segment: profile index, start position (m, from the profile start), MSD (m), fraction of raw
        samples that were dropouts, fraction of resampled samples flagged as spikes, validity.
    settings : dict
        The options used.
    source : str
    """

    mpd: float
    per_profile: tuple
    profile_valid: tuple
    is_valid: bool
    segment_profile: np.ndarray
    segment_start: np.ndarray
    msd: np.ndarray
    dropout_ratio: np.ndarray
    spike_ratio: np.ndarray
    valid: np.ndarray
    settings: dict
    source: str = ""

    def __repr__(self) -> str:
        return (f"MPDResult(mpd={self.mpd * 1e3:.4g} mm, {len(self.per_profile)} profiles, "
                f"{self.n_valid}/{self.valid.size} valid segments, is_valid={self.is_valid}"
                + (f", source={self.source!r}" if self.source else "") + ")")

    @property
    def etd(self) -> float:
        """Estimated texture depth from the MPD (m), see :func:`etd`."""
        return etd(self.mpd)

    @property
    def n_valid(self) -> int:
        """Number of valid segments."""
        return int(self.valid.sum())


@doi(_ISO_13473)
def mean_profile_depth(ps, *, segment_length: float = 0.1, spacing: float = 0.5e-3, spike_alpha: float = 6.0,
                       lowpass_wavelength: float | None = 2.4e-3, highpass_wavelength: float | None = None,
                       max_dropout_ratio: float = 0.10, max_spike_ratio: float = 0.05, min_valid_fraction: float = 0.5,
                       x_range: tuple[float, float] | None = None) -> MPDResult:
    """Mean profile depth per ISO 13473-1 of the profile set ``ps``: steps, options and results as in
    :func:`surfaces.mpd` (which also takes a single profile or a file)."""
    seg = positive(segment_length, "segment_length")
    step = positive(spacing, "spacing")
    alpha = positive(spike_alpha, "spike_alpha")
    if x_range is not None:
        ps = ps.crop(*x_range)
    settings = dict(segment_length=seg, spacing=step, spike_alpha=alpha, lowpass_wavelength=lowpass_wavelength,
                    highpass_wavelength=highpass_wavelength, max_dropout_ratio=max_dropout_ratio,
                    max_spike_ratio=max_spike_ratio, min_valid_fraction=min_valid_fraction, x_range=x_range)
    rows = []
    per_profile, profile_valid = [], []
    for ip, p in enumerate(ps):
        segs = _mpd_segments(p, seg, step, alpha, lowpass_wavelength, highpass_wavelength)
        ok = (segs["dropout_ratio"] <= max_dropout_ratio) & (segs["spike_ratio"] <= max_spike_ratio)
        segs["valid"] = ok
        segs["profile"] = np.full(ok.size, ip)
        rows.append(segs)
        per_profile.append(float(segs["msd"][ok].mean()) if ok.any() else math.nan)
        profile_valid.append(bool(ok.mean() >= min_valid_fraction))
    cat = {k: np.concatenate([r[k] for r in rows]) for k in rows[0]}
    valid = cat["valid"]
    total = float(cat["msd"][valid].mean()) if valid.any() else math.nan
    if not valid.any():
        warnings.warn(f"mpd ({ps.source}): no valid segment (dropout or spike ratio too high); MPD is NaN",
                      DataWarning, stacklevel=3)
    return MPDResult(mpd=total, per_profile=tuple(per_profile), profile_valid=tuple(profile_valid),
                     is_valid=all(profile_valid), segment_profile=cat["profile"], segment_start=cat["start"],
                     msd=cat["msd"], dropout_ratio=cat["dropout_ratio"], spike_ratio=cat["spike_ratio"],
                     valid=valid, settings=settings, source=ps.source)


@doi(_ISO_13473)
def etd(mpd_value: float) -> float:
    r"""Estimated texture depth (m) from the mean profile depth (m), ISO 13473-1:
    :math:`\mathrm{ETD} = 0.2\,\mathrm{mm} + 0.8\,\mathrm{MPD}`.

    Examples
    --------
    >>> print(round(etd(1.0e-3), 9))                  # MPD 1 mm
    0.001
    """
    return 0.2e-3 + 0.8 * float(mpd_value)


# ---------------------------------------------------------------------- height-difference correlation


@dataclass(frozen=True, eq=False)
class HDC:
    r"""Height-difference correlation :math:`C_z(\lambda) = \langle (z(x+\lambda) - z(x))^2\rangle`.

    Attributes
    ----------
    lag : numpy.ndarray
        :math:`\lambda`, m.
    C_z : numpy.ndarray
        m^2.
    counts : numpy.ndarray
        Number of height pairs averaged at each lag.
    source : str
    """

    lag: np.ndarray
    C_z: np.ndarray
    counts: np.ndarray
    source: str = ""

    def __repr__(self) -> str:
        return (f"HDC({self.lag.size} lags, {self.lag[0]:.4g}-{self.lag[-1]:.4g} m"
                + (f", source={self.source!r}" if self.source else "") + ")")

    def fit(self, lag_min: float | None = None, lag_max: float | None = None) -> "HDCFit":
        """Klüppel's self-affine fit; see :func:`surfaces.fit_hdc`."""
        return fit_height_difference_correlation(self, lag_min=lag_min, lag_max=lag_max)


@dataclass(frozen=True)
class HDCFit:
    r"""Fit of :math:`C_z(\lambda) = \xi_\perp^2 (\lambda/\xi_\parallel)^{2H}` for :math:`\lambda < \xi_\parallel`,
    :math:`\xi_\perp^2` above (Klüppel and Heinrich 2000).

    Attributes
    ----------
    hurst : float
        H.
    xi_perp : float
        Vertical correlation length, m (:math:`\xi_\perp^2` is the plateau, :math:`2 h_{rms}^2` for a
        stationary surface).
    xi_par : float
        Lateral correlation length, m.
    rms_log_residual : float
    """

    hurst: float
    xi_perp: float
    xi_par: float
    rms_log_residual: float

    def C_z(self, lag):
        """The fitted model at ``lag`` (m), m^2."""
        lag = np.asarray(lag, dtype=float)
        return self.xi_perp**2 * np.minimum(lag / self.xi_par, 1.0) ** (2.0 * self.hurst)


@doi(_KLUEPPEL_2000)
def height_difference_correlation(ps, n_lags: int = 48, max_lag_fraction: float = 0.25,
                                  detrend: str = "linear") -> HDC:
    """Height-difference correlation of the profile set ``ps``; method and options as in :func:`surfaces.hdc`
    (which also takes a single profile or a file)."""
    ps = ps.fill_dropouts()
    h = max(p.dx for p in ps)
    ps = ps.resample(h).detrend(detrend)
    n_min = min(p.n for p in ps)
    m_max = max(1, int(n_min * float(max_lag_fraction)))
    lags = np.unique(np.round(np.geomspace(1, m_max, int(n_lags))).astype(int))
    S = np.zeros(lags.size)
    N = np.zeros(lags.size)
    for p in ps:
        z = p.z
        n = z.size
        c2 = np.concatenate([[0.0], np.cumsum(z * z)])
        corr = _signal().correlate(z, z, mode="full", method="fft")[n - 1:]  # corr[m] = sum_i z_{i+m} z_i
        tail_sq = c2[n] - c2[lags]          # sum_{i >= m} z_i^2
        head_sq = c2[n - lags]              # sum_{i < n-m} z_i^2
        S += tail_sq + head_sq - 2.0 * corr[lags]
        N += n - lags
    return HDC(lag=lags * h, C_z=np.maximum(S, 0.0) / N, counts=N.astype(int), source=ps.source)


@doi(_KLUEPPEL_2000)
def fit_height_difference_correlation(h: HDC, lag_min: float | None = None, lag_max: float | None = None) -> HDCFit:
    """Klüppel's self-affine fit of the height-difference correlation ``h``; model and options as in
    :func:`surfaces.fit_hdc` (which also takes profiles)."""
    m = band(h.lag, lag_min, lag_max, "fit_hdc") & (h.C_z > 0)
    if m.sum() < 5:
        raise InputError(f"fit_hdc ({h.source}): need >= 5 lags with C_z > 0, got {int(m.sum())}")
    a, s, b, resid = broken_power_law_fit(np.log(h.lag[m]), np.log(h.C_z[m]), flat="above")
    H = s / 2.0
    if not (np.isfinite(H) and 0.0 < H <= 1.05):
        raise InputError(f"fit_hdc ({h.source}): fitted H = {H:.3g} is outside (0, 1]")
    return HDCFit(hurst=float(H), xi_perp=math.exp(a / 2.0), xi_par=math.exp(b), rms_log_residual=resid)


# ---------------------------------------------------------------------- helpers


def _mpd_segments(p, seg: float, step: float, alpha: float, lowpass, highpass) -> dict:
    """Per-segment MSD, dropout and spike ratios of one profile (ISO 13473-1 steps 1-6)."""
    raw = p.z
    drop = np.isnan(raw)
    x = p.x - p.x[0]
    z = np.interp(x, x[~drop], raw[~drop])  # dropout correction, ends held at the nearest valid value
    if p.dx < step * (1 - 1e-6):
        g = np.ceil(x / step - 1e-9).astype(int)
        g[g == 0] = 1                          # the first cell is closed on the left
        cells, inv = np.unique(g, return_inverse=True)
        zr = np.bincount(inv, weights=z) / np.bincount(inv)
        xr = cells * step
        h = step
    else:
        xr, zr, h = x, z, p.dx
    # Spikes: steps between neighbours of at least alpha * spacing; flag both ends, interpolate over them.
    jump = np.abs(np.diff(zr)) >= alpha * h * (1 - 1e-9)
    spike = np.zeros(zr.size, dtype=bool)
    spike[1:] |= jump
    spike[:-1] |= jump
    if spike.any():
        if spike.all():
            raise InputError(f"{p.where}: every sample is flagged as a spike (spike_alpha too small?)")
        zr = np.interp(xr, xr[~spike], zr[~spike])
    fs = 1.0 / h
    if lowpass is not None:
        sos = _signal().butter(2, 1.0 / positive(lowpass, "lowpass_wavelength"), btype="low", fs=fs, output="sos")
        zr = _signal().sosfiltfilt(sos, zr)
    if highpass is not None:
        sos = _signal().butter(2, 1.0 / positive(highpass, "highpass_wavelength"), btype="high", fs=fs, output="sos")
        zr = _signal().sosfiltfilt(sos, zr)
    # Segments (k seg, (k+1) seg], the first closed on the left.
    s_res = np.maximum(np.ceil(xr / seg - 1e-9).astype(int) - 1, 0)
    s_raw = np.maximum(np.ceil(x / seg - 1e-9).astype(int) - 1, 0)
    n_seg = int(s_res.max()) + 1
    n_expected = seg / h
    pts = np.bincount(s_res, minlength=n_seg)
    complete = np.flatnonzero(pts / n_expected >= 0.9)
    if complete.size == 0:
        raise InputError(f"{p.where}: profile length {(x[-1]) * 1e3:.1f} mm is shorter than one MPD segment "
                         f"({seg * 1e3:g} mm)")
    drop_ratio = np.bincount(s_raw, weights=drop, minlength=n_seg) / np.maximum(np.bincount(s_raw, minlength=n_seg), 1)
    spike_ratio = np.bincount(s_res, weights=spike, minlength=n_seg) / np.maximum(pts, 1)
    msd = np.empty(complete.size)
    for i, k in enumerate(complete):
        xs, zs = xr[s_res == k], zr[s_res == k]
        if highpass is None:  # slope suppression by linear regression
            zs = zs - np.polyval(np.polyfit(xs, zs, 1), xs)
        half = zs.size >> 1
        msd[i] = 0.5 * (zs[:half].max() + zs[half:].max()) - zs.mean()
    return {"start": complete * seg, "msd": msd, "dropout_ratio": drop_ratio[complete],
            "spike_ratio": spike_ratio[complete]}


def _signal():
    """``scipy.signal``, imported on first use (it adds about 0.4 s to every start-up)."""
    from scipy import signal

    return signal
