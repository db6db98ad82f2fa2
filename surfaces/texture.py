r"""Texture metrics: Rq and rms slope (band-limited), mean profile depth (ISO 13473-1), estimated texture
depth, and Klüppel's height-difference correlation with its self-affine fit.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np


from frictioncite import doi

from ._util import band, positive
from .cutoffs import broken_power_law_fit
from .errors import InputError
from .maps import HeightMap
from .profiles import Profile, ProfileSet
from .psd import PSD, SelfAffine
from .spectra import PSD1D

__all__ = ["MPDResult", "mpd", "etd", "rq", "rms_slope", "HDC", "HDCFit", "hdc", "fit_hdc"]

_ISO_13473 = "iso:13473-1:2019"
_KLUEPPEL_2000 = "10.5254/1.3547607"


# ---------------------------------------------------------------------- Rq and rms slope


def rq(obj, q_min: float | None = None, q_max: float | None = None) -> float:
    r"""Rms height Rq (m), optionally band-limited to ``[q_min, q_max]`` (rad/m).

    * PSD / SelfAffine (2D): :math:`R_q^2 = 2\pi\int q\,C(q)\,dq`;
    * PSD1D: :math:`R_q^2 = 2\int C_{1D}(q)\,dq`;
    * ProfileSet / Profile: rms of the linearly detrended heights (no band), else from their 1D PSD;
    * HeightMap: rms about the mean plane (no band), else from its radially averaged PSD.
    """
    return _band_metric(obj, q_min, q_max, order=0)


def rms_slope(obj, q_min: float | None = None, q_max: float | None = None) -> float:
    r"""Rms slope, optionally band-limited to ``[q_min, q_max]`` (rad/m).

    * PSD / SelfAffine / HeightMap: the 2D rms gradient, :math:`\xi^2 = 2\pi\int q^3 C(q)\,dq`;
    * PSD1D, ProfileSet, Profile: the slope along the profile, :math:`2\int q^2 C_{1D}\,dq` (for an isotropic
      surface :math:`\xi^2` is twice this). Without a band, profiles use first differences.
    """
    return _band_metric(obj, q_min, q_max, order=1)


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
def mpd(profiles, *, segment_length: float = 0.1, spacing: float = 0.5e-3, spike_alpha: float = 6.0,
        lowpass_wavelength: float | None = 2.4e-3, highpass_wavelength: float | None = None,
        max_dropout_ratio: float = 0.10, max_spike_ratio: float = 0.05, min_valid_fraction: float = 0.5,
        x_range: tuple[float, float] | None = None) -> MPDResult:
    r"""Mean profile depth (MPD) per ISO 13473-1:2019.

    Where the standard leaves a choice (spike threshold, completeness of the last segment) the defaults follow
    the CAPTIF processing of captif-slp, the independent implementation the tests compare with. For each
    profile:

    1. dropouts are interpolated linearly (missing ends take the nearest valid value);
    2. the profile is resampled to ``spacing`` (0.5 mm) by averaging the samples of each cell
       :math:`((k-1)\Delta, k\Delta]` (profiles sampled coarser than ``spacing`` are kept as they are);
    3. spikes: where two adjacent resampled heights differ by :math:`|\Delta z| \ge \alpha\,\Delta x`, both
       samples are flagged, removed and interpolated (``spike_alpha`` = :math:`\alpha`; 6 by default, the
       CAPTIF processing value);
    4. a second-order Butterworth low-pass filter with cut-off wavelength 2.4 mm is applied forward and
       backward (zero phase), and, if ``highpass_wavelength`` is given, a second-order high-pass;
    5. the profile is cut into segments of ``segment_length`` (100 mm) from its start; segments with less
       than 90 % of their samples are dropped; without high-pass filter the least-squares line of each segment
       is subtracted (slope suppression);
    6. mean segment depth :math:`\mathrm{MSD} = \tfrac12(\max_{1st\ half} + \max_{2nd\ half}) - \bar z`;
    7. a segment is invalid when more than ``max_dropout_ratio`` (10 %) of its raw samples were dropouts or
       more than ``max_spike_ratio`` (5 %) of its samples were spikes; MPD is the mean MSD of the valid
       segments, and a profile is valid when at least ``min_valid_fraction`` (50 %) of its segments are.

    Parameters
    ----------
    profiles : ProfileSet, Profile, or path
        Heights in m (a path is read with :func:`surfaces.read_profiles`).
    segment_length, spacing : float
        m.
    spike_alpha : float
        Spike slope threshold :math:`\alpha` (dimensionless).
    lowpass_wavelength, highpass_wavelength : float or None
        Filter cut-off wavelengths, m (None: no filter).
    max_dropout_ratio, max_spike_ratio, min_valid_fraction : float
        Validity rules.
    x_range : (float, float), optional
        Evaluate only samples with x in this range (m).

    Returns
    -------
    MPDResult

    Raises
    ------
    InputError
        A profile shorter than one segment (naming file and column), bad options.
    """
    ps = _as_profiles(profiles)
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
                      stacklevel=2)
    return MPDResult(mpd=total, per_profile=tuple(per_profile), profile_valid=tuple(profile_valid),
                     is_valid=all(profile_valid), segment_profile=cat["profile"], segment_start=cat["start"],
                     msd=cat["msd"], dropout_ratio=cat["dropout_ratio"], spike_ratio=cat["spike_ratio"],
                     valid=valid, settings=settings, source=ps.source)


@doi(_ISO_13473)
def etd(mpd_value: float) -> float:
    r"""Estimated texture depth (m) from the mean profile depth (m), ISO 13473-1:
    :math:`\mathrm{ETD} = 0.2\,\mathrm{mm} + 0.8\,\mathrm{MPD}`."""
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
        """Klüppel's self-affine fit; see :func:`fit_hdc`."""
        return fit_hdc(self, lag_min=lag_min, lag_max=lag_max)


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
def hdc(profiles, n_lags: int = 48, max_lag_fraction: float = 0.25, detrend: str = "linear") -> HDC:
    r"""Height-difference correlation of profiles (Klüppel and Heinrich, Rubber Chem. Technol. 73, 578 (2000)).

    .. math:: C_z(\lambda) = \langle (z(x+\lambda) - z(x))^2 \rangle
              = \frac{1}{N_\lambda}\sum_i (z_{i+m} - z_i)^2, \quad \lambda = m\,\Delta x ,

    evaluated for all profiles at once per lag with cumulative sums and an FFT cross-correlation
    (:func:`scipy.signal.correlate`), on ``n_lags`` logarithmically spaced lags up to ``max_lag_fraction`` of
    the profile length; pairs of all profiles are pooled. Dropouts are filled, profiles resampled to a
    common spacing (the coarsest) and detrended first.

    Returns
    -------
    HDC
    """
    ps = _as_profiles(profiles).fill_dropouts()
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
def fit_hdc(data, lag_min: float | None = None, lag_max: float | None = None) -> HDCFit:
    r"""Fit Klüppel's self-affine form to a height-difference correlation, in log-log:

    .. math:: C_z(\lambda) = \xi_\perp^2 \left(\frac{\lambda}{\xi_\parallel}\right)^{2H} (\lambda<\xi_\parallel),
              \qquad C_z = \xi_\perp^2 \;(\lambda \ge \xi_\parallel)

    Parameters
    ----------
    data : HDC or ProfileSet
    lag_min, lag_max : float, optional
        Range of lags used, m.

    Returns
    -------
    HDCFit
    """
    h = data if isinstance(data, HDC) else hdc(data)
    m = band(h.lag, lag_min, lag_max, "fit_hdc") & (h.C_z > 0)
    if m.sum() < 5:
        raise InputError(f"fit_hdc ({h.source}): need >= 5 lags with C_z > 0, got {int(m.sum())}")
    a, s, b, resid = broken_power_law_fit(np.log(h.lag[m]), np.log(h.C_z[m]), flat="above")
    H = s / 2.0
    if not (np.isfinite(H) and 0.0 < H <= 1.05):
        raise InputError(f"fit_hdc ({h.source}): fitted H = {H:.3g} is outside (0, 1]")
    return HDCFit(hurst=float(H), xi_perp=math.exp(a / 2.0), xi_par=math.exp(b), rms_log_residual=resid)


# ---------------------------------------------------------------------- helpers


def _as_profiles(obj) -> ProfileSet:
    if isinstance(obj, ProfileSet):
        return obj
    if isinstance(obj, Profile):
        return ProfileSet((obj,), source=obj.source)
    if isinstance(obj, (str, Path)):
        from .io import read_profiles

        return read_profiles(obj)
    raise InputError(f"profiles: expected a ProfileSet, Profile or file path, got {type(obj).__name__}")


def _mpd_segments(p: Profile, seg: float, step: float, alpha: float, lowpass, highpass) -> dict:
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


def _band_metric(obj, q_min, q_max, order: int) -> float:
    banded = q_min is not None or q_max is not None
    if isinstance(obj, (PSD, SelfAffine)):
        table = obj.tabulate() if isinstance(obj, SelfAffine) else obj
        if banded:
            lo = table.q0 if q_min is None else max(positive(q_min, "q_min"), table.q0)
            hi = table.q1 if q_max is None else min(positive(q_max, "q_max"), table.q1)
            if not hi > lo:
                raise InputError(f"band [{q_min}, {q_max}] rad/m does not overlap the PSD [{table.q0:g}, {table.q1:g}]")
            table = table.with_cutoff(q0=lo, q1=hi)
        return math.sqrt(table.moment(1 if order == 0 else 3))
    if isinstance(obj, PSD1D):
        return obj.hrms(q_min, q_max) if order == 0 else obj.rms_slope(q_min, q_max)
    if isinstance(obj, HeightMap):
        if banded:
            return _band_metric(obj.psd(), q_min, q_max, order)
        return obj.detrend("plane").hrms() if order == 0 else obj.rms_slope()
    ps = _as_profiles(obj)
    if banded:
        return _band_metric(ps.psd(), q_min, q_max, order)
    prepared = ps.fill_dropouts().detrend("mean" if all(p.periodic for p in ps) else "linear")
    if order == 0:
        zz = np.concatenate([p.z for p in prepared])
        return float(np.sqrt(np.mean(zz * zz)))
    slopes = np.concatenate([np.diff(p.z) / np.diff(p.x) for p in prepared])
    return float(np.sqrt(np.mean(slopes * slopes)))


def _signal():
    """``scipy.signal``, imported on first use (it adds about 0.4 s to every start-up)."""
    from scipy import signal

    return signal
