r"""Texture metrics: Rq and rms slope (band-limited), mean profile depth (ISO 13473-1), estimated texture
depth, and Klüppel's height-difference correlation with its self-affine fit.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from frictioncite import doi

from ._util import positive
from .errors import InputError
from .io import read_profiles
from .maps import HeightMap
from .profile_metrics import (HDC, HDCFit, MPDResult, etd, fit_height_difference_correlation,
                              height_difference_correlation, mean_profile_depth)
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
    return mean_profile_depth(_as_profiles(profiles), segment_length=segment_length, spacing=spacing,
                              spike_alpha=spike_alpha, lowpass_wavelength=lowpass_wavelength,
                              highpass_wavelength=highpass_wavelength, max_dropout_ratio=max_dropout_ratio,
                              max_spike_ratio=max_spike_ratio, min_valid_fraction=min_valid_fraction,
                              x_range=x_range)


# ---------------------------------------------------------------------- height-difference correlation


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
    return height_difference_correlation(_as_profiles(profiles), n_lags=n_lags,
                                         max_lag_fraction=max_lag_fraction, detrend=detrend)


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
    return fit_height_difference_correlation(h, lag_min=lag_min, lag_max=lag_max)


# ---------------------------------------------------------------------- helpers


def _as_profiles(obj) -> ProfileSet:
    if isinstance(obj, ProfileSet):
        return obj
    if isinstance(obj, Profile):
        return ProfileSet((obj,), source=obj.source)
    if isinstance(obj, (str, Path)):
        return read_profiles(obj)
    raise InputError(f"profiles: expected a ProfileSet, Profile or file path, got {type(obj).__name__}")


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
