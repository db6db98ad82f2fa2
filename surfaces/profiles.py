"""Line profiles (scans) and their preparation: dropouts, spikes, detrending, resampling, 1D PSD.

A :class:`ProfileSet` holds one or more :class:`Profile` (heights in m along x in m). Profiles of one CSV
file share x; profiles from several files may have their own x and length: the 1D PSD averages them on a
common logarithmic grid. Every preparation step returns a new set and is recorded in ``history``.
"""

from __future__ import annotations

import math
import types
import warnings
from dataclasses import dataclass, field, replace

import numpy as np

from frictioncite import doi

from ._util import flat_after_detrend, optional_positive, positive, span
from .cutoffs import reliability_limit
from .errors import DataWarning, InputError
from .profile_metrics import height_difference_correlation, mean_profile_depth
from .spectra import PSD1D, log_bin, periodogram_1d

__all__ = ["Profile", "ProfileSet"]

#: Relative tolerance on the sample positions for a profile to count as uniformly sampled: exports that
#: round x (CAPTIF: 0.0375 mm written as 0.037/0.038) are uniform grids with rounding noise.
_UNIFORM_TOL = 0.05
_DETREND_DEGREE = {"none": None, "mean": 0, "linear": 1, "quadratic": 2}


@dataclass(frozen=True, eq=False)
class Profile:
    """One line scan.

    Parameters
    ----------
    x : numpy.ndarray
        Positions, m, strictly increasing.
    z : numpy.ndarray
        Heights, m; NaN marks a dropout (missing sample).
    name : str
        Column name or label (used in messages).
    source : str
        File or origin (used in messages).
    dropouts : numpy.ndarray of bool, optional
        Samples missing in the raw data (kept through filling, so the fraction stays reportable).
    periodic : bool
        True for periodic data (synthetic surfaces, rows of a periodic map): no window, no linear detrend.
    history : tuple of str
        Preparation steps applied.
    """

    x: np.ndarray
    z: np.ndarray
    name: str = "z"
    source: str = ""
    dropouts: np.ndarray | None = None
    periodic: bool = False
    history: tuple = ()

    def __post_init__(self):
        x = np.asarray(self.x, dtype=float)
        z = np.asarray(self.z, dtype=float)
        if x.ndim != 1 or z.shape != x.shape:
            raise InputError(f"{self.where}: x and z must be 1D of the same length, got {x.shape} and {z.shape}")
        if x.size < 2:
            raise InputError(f"{self.where}: a profile needs at least 2 samples, got {x.size}")
        if not np.isfinite(x).all():
            raise InputError(f"{self.where}: x must be finite (row {int(np.argmax(~np.isfinite(x)))})")
        bad = np.flatnonzero(np.diff(x) <= 0)
        if bad.size:
            raise InputError(f"{self.where}: x must be strictly increasing; sample {bad[0] + 1} "
                             f"(x = {x[bad[0] + 1]:g} m) does not follow sample {bad[0]} (x = {x[bad[0]]:g} m)")
        if np.isinf(z).any():
            raise InputError(f"{self.where}: infinite height at sample {int(np.argmax(np.isinf(z)))}")
        if np.isnan(z).all():
            raise InputError(f"{self.where}: all values are missing (NaN or empty); expected heights")
        drop = np.isnan(z) if self.dropouts is None else np.asarray(self.dropouts, dtype=bool)
        if drop.shape != z.shape:
            raise InputError(f"{self.where}: dropouts mask must have the shape of z")
        for arr in (x, z, drop):
            arr.setflags(write=False)
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "z", z)
        object.__setattr__(self, "dropouts", drop)
        object.__setattr__(self, "history", tuple(self.history))

    def __repr__(self) -> str:
        return (f"Profile({self.name!r}, {self.n} samples, dx={self.dx:.4g} m, length={self.length:.4g} m, "
                f"z {span(self.z, 'm')}, dropouts {self.dropout_fraction:.1%}"
                + (", periodic" if self.periodic else "") + (f", source={self.source!r}" if self.source else "") + ")")

    @property
    def where(self) -> str:
        """``"<source>, column <name>"`` for error messages."""
        return f"{self.source or '<array>'}, column {self.name}"

    @property
    def n(self) -> int:
        """Number of samples."""
        return int(self.x.size)

    @property
    def dx(self) -> float:
        """Mean sample spacing, m."""
        return float((self.x[-1] - self.x[0]) / (self.x.size - 1))

    @property
    def length(self) -> float:
        """Length n * dx, m (the period seen by the discrete Fourier transform)."""
        return self.n * self.dx

    @property
    def is_uniform(self) -> bool:
        """True when x deviates from the uniform grid by less than 5 % of the spacing."""
        grid = self.x[0] + self.dx * np.arange(self.n)
        return bool(np.max(np.abs(self.x - grid)) <= _UNIFORM_TOL * self.dx)

    @property
    def dropout_fraction(self) -> float:
        """Fraction of samples missing in the raw data."""
        return float(self.dropouts.mean())

    @property
    def missing_fraction(self) -> float:
        """Fraction of samples missing now (NaN)."""
        return float(np.isnan(self.z).mean())

    def _with(self, step: str | None = None, **changes) -> "Profile":
        hist = self.history + ((step,) if step else ())
        return replace(self, history=hist, **changes)


@dataclass(frozen=True, eq=False)
class ProfileSet:
    """A set of line scans with preparation steps and the averaged 1D PSD.

    Parameters
    ----------
    profiles : sequence of Profile
    source : str
        Origin (file names), for messages and reports.
    meta : mapping
        Instrument header fields (e.g. the CAPTIF header block), read-only.

    Examples
    --------
    Two random walks (self-affine, H = 1/2) of 2048 heights 10 um apart, as read from a file with
    ``surfaces.read_profiles("scan.csv")``:

    >>> import numpy as np, surfaces
    >>> z = np.cumsum(np.random.default_rng(0).normal(size=(2, 2048)), axis=1) * 1e-6
    >>> ps = surfaces.profiles_from_array(z, dx=10e-6)
    >>> len(ps), ps[0].n
    (2, 2048)
    >>> psd2d = ps.psd().to_isotropic()            # averaged line-scan PSD -> isotropic 2D PSD
    >>> isinstance(psd2d, surfaces.PSD)
    True
    >>> print(f"reliable up to q_r = pi / dx = {psd2d.q_r:.5g} rad/m")
    reliable up to q_r = pi / dx = 3.1416e+05 rad/m
    """

    profiles: tuple
    source: str = ""
    meta: types.MappingProxyType = field(default_factory=lambda: types.MappingProxyType({}))

    def __post_init__(self):
        profiles = tuple(self.profiles)
        if not profiles:
            raise InputError(f"{self.source or 'ProfileSet'}: no profiles")
        if not all(isinstance(p, Profile) for p in profiles):
            raise InputError("ProfileSet: expected Profile objects")
        object.__setattr__(self, "profiles", profiles)
        object.__setattr__(self, "meta", types.MappingProxyType(dict(self.meta)))

    def __repr__(self) -> str:
        n = [p.n for p in self.profiles]
        samples = f"{n[0]} samples" if min(n) == max(n) else f"{min(n)}-{max(n)} samples"
        names = ", ".join(self.names[:4]) + (", ..." if len(self) > 4 else "")
        return (f"ProfileSet({len(self)} profile{'s' if len(self) != 1 else ''} [{names}], {samples}, "
                f"dx={self.profiles[0].dx:.4g} m" + (f", source={self.source!r}" if self.source else "") + ")")

    # ------------------------------------------------------------------ container
    def __len__(self) -> int:
        return len(self.profiles)

    def __iter__(self):
        return iter(self.profiles)

    def __getitem__(self, i) -> Profile:
        return self.profiles[i]

    @classmethod
    def concatenate(cls, sets) -> "ProfileSet":
        """One set with the profiles of all ``sets`` (e.g. several files of one surface)."""
        sets = list(sets)
        if not sets:
            raise InputError("ProfileSet.concatenate: no sets given")
        meta = {}
        for s in sets:
            meta.update(s.meta)
        return cls(tuple(p for s in sets for p in s.profiles), source="; ".join(s.source for s in sets), meta=meta)

    @property
    def names(self) -> tuple[str, ...]:
        """Profile names."""
        return tuple(p.name for p in self.profiles)

    @property
    def dropout_fraction(self) -> np.ndarray:
        """Fraction of raw samples missing, per profile."""
        return np.array([p.dropout_fraction for p in self.profiles])

    @property
    def history(self) -> tuple[str, ...]:
        """Preparation steps of the first profile (all profiles go through the same steps)."""
        return self.profiles[0].history

    def _map(self, fn) -> "ProfileSet":
        return ProfileSet(tuple(fn(p) for p in self.profiles), source=self.source, meta=self.meta)

    # ------------------------------------------------------------------ preparation
    def crop(self, x_min: float | None = None, x_max: float | None = None) -> "ProfileSet":
        """Keep the samples with ``x_min <= x <= x_max`` (m)."""
        def one(p: Profile) -> Profile:
            keep = np.ones(p.n, dtype=bool)
            if x_min is not None:
                keep &= p.x >= float(x_min)
            if x_max is not None:
                keep &= p.x <= float(x_max)
            if keep.sum() < 2:
                raise InputError(f"{p.where}: fewer than 2 samples in [{x_min}, {x_max}] m")
            return p._with(f"cropped to [{p.x[keep][0]:.6g}, {p.x[keep][-1]:.6g}] m", x=p.x[keep], z=p.z[keep],
                           dropouts=p.dropouts[keep])
        return self._map(one)

    def fill_dropouts(self, max_fraction: float = 0.2) -> "ProfileSet":
        """Interpolate dropouts linearly; missing samples at the ends take the nearest valid value
        (the ISO 13473-1 dropout correction).

        Parameters
        ----------
        max_fraction : float
            Refuse (InputError) a profile with more than this fraction of missing samples.
        """
        limit = float(max_fraction)

        def one(p: Profile) -> Profile:
            miss = np.isnan(p.z)
            if not miss.any():
                return p
            frac = float(miss.mean())
            if frac > limit:
                raise InputError(f"{p.where}: {frac:.1%} of the samples are dropouts (NaN), more than the "
                                 f"allowed max_fraction = {limit:.1%}")
            z = np.interp(p.x, p.x[~miss], p.z[~miss])  # np.interp holds the end values: ISO end correction
            return p._with(f"filled {frac:.2%} dropouts by linear interpolation", z=z)
        return self._map(one)

    def remove_spikes(self, threshold: float = 6.0, window: int = 5) -> "ProfileSet":
        r"""Replace spikes by linear interpolation.

        A sample is a spike when its distance from the running median (``window`` samples) exceeds
        ``threshold`` times the robust scale of the sample-to-sample variation,
        :math:`1.4826\,\mathrm{MAD}(\Delta z)/\sqrt 2` (floored at 0.1 % of the standard deviation of the
        profile).
        Dropouts must be filled first. (The ISO 13473-1 slope-threshold rule used for MPD lives in
        :func:`surfaces.mpd`.)
        """
        thr = positive(threshold, "threshold")
        if int(window) < 3 or int(window) % 2 == 0:
            raise InputError(f"window: expected an odd integer >= 3, got {window!r}")

        # imported here: scipy.ndimage costs every process that loads a case ~40 ms, and only this step needs it
        from scipy import ndimage

        def one(p: Profile) -> Profile:
            _require_filled(p, "remove_spikes")
            r = p.z - ndimage.median_filter(p.z, size=int(window), mode="nearest")
            # Robust scale of the sample-to-sample variation (MAD of first differences / sqrt 2): the MAD of
            # r itself is often 0 because the median of a window is mostly its own centre sample.
            d = np.diff(p.z)
            sigma = max(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(2.0), 1e-3 * np.std(p.z))
            spikes = np.abs(r) > thr * sigma if sigma > 0 else np.zeros(p.n, dtype=bool)
            if not spikes.any():
                return p._with("spike check: none found")
            z = np.interp(p.x, p.x[~spikes], p.z[~spikes])
            return p._with(f"removed {int(spikes.sum())} spikes ({spikes.mean():.2%})", z=z)
        return self._map(one)

    def detrend(self, kind: str = "linear") -> "ProfileSet":
        """Subtract the least-squares polynomial of ``kind`` in {"none", "mean", "linear", "quadratic"}."""
        if kind not in _DETREND_DEGREE:
            raise InputError(f"detrend: expected one of {sorted(_DETREND_DEGREE)}, got {kind!r}")
        deg = _DETREND_DEGREE[kind]
        if deg is None:
            return self
        out = list(self.profiles)
        for idx in _shared_x_groups(self.profiles):  # one least-squares solve per group of profiles sharing x
            x = self.profiles[idx[0]].x
            for i in idx:
                _require_filled(self.profiles[i], "detrend")
            t = (x - x.mean()) / (0.5 * (x[-1] - x[0]))  # scaled for a well-conditioned fit
            Z = np.stack([self.profiles[i].z for i in idx], axis=1)
            coef = np.polynomial.polynomial.polyfit(t, Z, deg)
            trend = np.polynomial.polynomial.polyval(t, coef)  # shape (n_profiles, n)
            for j, i in enumerate(idx):
                out[i] = self.profiles[i]._with(f"detrend {kind}", z=self.profiles[i].z - trend[j])
        return ProfileSet(tuple(out), source=self.source, meta=self.meta)

    def resample(self, dx: float | None = None, method: str = "auto") -> "ProfileSet":
        """Resample to uniform spacing ``dx`` (m; default the mean spacing of each profile).

        ``method``: "linear" (interpolation), "mean" (average of the samples in each cell of width dx,
        which low-pass filters; used when coarsening) or "auto" (mean when dx > 1.5 x the old spacing).
        A profile that is already uniform up to rounding of x and keeps its spacing is only snapped to the
        exact grid. Dropouts must be filled first.
        """
        step = optional_positive(dx, "dx")
        if method not in ("auto", "linear", "mean"):
            raise InputError(f"method: expected 'auto', 'linear' or 'mean', got {method!r}")

        def one(p: Profile) -> Profile:
            _require_filled(p, "resample")
            h = p.dx if step is None else step
            n = int(math.floor((p.x[-1] - p.x[0]) / h * (1 + 1e-9))) + 1
            grid = p.x[0] + h * np.arange(n)
            if abs(h - p.dx) <= 1e-9 * h and p.is_uniform:
                return p._with("snapped x to the uniform grid", x=grid)
            how = method if method != "auto" else ("mean" if h > 1.5 * p.dx else "linear")
            if how == "linear":
                z = np.interp(grid, p.x, p.z)
            else:
                edges = np.concatenate([grid - h / 2, [grid[-1] + h / 2]])
                from scipy import stats  # lazily: scipy.stats slows every start-up

                z = stats.binned_statistic(p.x, p.z, "mean", bins=edges).statistic
                empty = np.isnan(z)
                if empty.any():  # cells without a sample (gaps): interpolate from the neighbours
                    z[empty] = np.interp(grid[empty], grid[~empty], z[~empty])
            drop = np.interp(grid, p.x, p.dropouts.astype(float)) > 0.5
            return p._with(f"resampled ({how}) to dx = {h:.6g} m", x=grid, z=z, dropouts=drop)
        return self._map(one)

    def prepare(self, max_dropout_fraction: float = 0.2, spikes: bool = False, detrend: str = "linear",
                dx: float | None = None) -> "ProfileSet":
        """The usual chain: fill dropouts, optionally remove spikes, resample to uniform spacing, detrend."""
        ps = self.fill_dropouts(max_dropout_fraction)
        if spikes:
            ps = ps.remove_spikes()
        if dx is not None or not all(p.is_uniform for p in ps):
            ps = ps.resample(dx)
        return ps.detrend(detrend)

    # ------------------------------------------------------------------ analysis
    @doi("10.1088/0953-8984/17/1/R01", "10.1088/2051-672X/aa51f8")
    def psd(self, window: str | None = "auto", detrend: str = "auto", n_per_decade: int = 20,
            q_r: float | None = None, max_dropout_fraction: float = 0.2) -> PSD1D:
        r"""Averaged two-sided 1D PSD of the profiles (Persson convention), log-binned, with per-bin spread.

        .. math:: C_{1D}(q) = \frac{1}{2\pi}\int dx\,\langle h(x)h(0)\rangle e^{-iqx}, \qquad
                  \int_{-\infty}^{\infty} C_{1D}\,dq = h_{rms}^2

        Each profile is prepared (dropouts filled, refused above ``max_dropout_fraction``; resampled to
        uniform spacing if needed; detrended), windowed and transformed with :func:`scipy.signal.periodogram`;
        the ordinates of all profiles are pooled in logarithmic bins (:func:`surfaces.spectra.log_bin`).

        Parameters
        ----------
        window : str or None
            "auto" (default): Hann for measured profiles, none for periodic ones; or any
            :func:`scipy.signal.get_window` name, or None.
        detrend : str
            "auto" (mean for periodic profiles, linear otherwise) or one of none/mean/linear/quadratic.
        n_per_decade : int
            Log bins per decade.
        q_r : float, optional
            Reliability limit, rad/m. Default: Nyquist :math:`\pi/\Delta x` of the coarsest profile.
        max_dropout_fraction : float
            Dropout fraction above which a profile is refused.

        Returns
        -------
        PSD1D
        """
        ps = self
        if any(np.isnan(p.z).any() for p in ps):
            ps = ps.fill_dropouts(max_dropout_fraction)
        if not all(p.is_uniform for p in ps):
            ps = ps.resample()
        periodic = all(p.periodic for p in ps)
        kind = detrend if detrend != "auto" else ("mean" if periodic else "linear")
        ps = ps.detrend(kind)
        _refuse_flat(self, ps, kind)
        wins = [(None if p.periodic else "hann") if window == "auto" else window for p in ps]
        q_list, C_list = [None] * len(ps), [None] * len(ps)
        for idx in _shared_x_groups(ps.profiles, extra=wins):  # one FFT call per group sharing x and window
            p = ps[idx[0]]
            if p.n < 4:
                raise InputError(f"{p.where}: too short for a spectrum ({p.n} samples)")
            q, C = periodogram_1d(np.stack([ps[i].z for i in idx]), p.dx, wins[idx[0]])
            for j, i in enumerate(idx):
                q_list[i], C_list[i] = q, C[j]
        q, C, spread, stderr, counts, widths = log_bin(q_list, C_list, n_per_decade,
                                                       dq_list=[2 * math.pi / p.length for p in ps])
        keep = C > 0
        q_lim = min(math.pi / p.dx for p in ps) if q_r is None else positive(q_r, "q_r")
        fr = self.dropout_fraction
        drop = (", ".join(f"{p.name}: {f:.2%}" for p, f in zip(self, fr)) if fr.size <= 5 else
                f"min {fr.min():.2%}, median {np.median(fr):.2%}, max {fr.max():.2%} over {fr.size} profiles")
        history = ps.history + (f"window {'/'.join(sorted({str(w) for w in wins}))}", f"raw dropout fractions {drop}")
        return PSD1D(q[keep], C[keep], spread[keep], stderr[keep], counts[keep], n_profiles=len(ps),
                     qL=2.0 * math.pi / max(p.length for p in ps), q_r=q_lim, source=self.source, history=history,
                     widths=widths[keep])

    def reliability_limit(self, tip_radius: float | None = None, lateral_resolution: float | None = None,
                          safety_factor: float = 0.5) -> float:
        """Reliability limit q_r (rad/m) from the sampling, and optionally the lateral resolution and a stylus
        tip radius (see :func:`surfaces.reliability_limit`)."""
        ps = self.fill_dropouts(1.0)
        return reliability_limit(dx=max(p.dx for p in ps), lateral_resolution=lateral_resolution,
                                 tip_radius=tip_radius, profiles=ps if tip_radius is not None else None,
                                 safety_factor=safety_factor)

    def mpd(self, **options):
        """Mean profile depth per ISO 13473-1; see :func:`surfaces.mpd`."""
        return mean_profile_depth(self, **options)

    def hdc(self, **options):
        """Height-difference correlation; see :func:`surfaces.hdc`."""
        return height_difference_correlation(self, **options)


def _shared_x_groups(profiles, extra=None) -> list[list[int]]:
    """Indices of profiles grouped by identical sample positions (and equal ``extra[i]``), in order."""
    groups: dict = {}
    for i, p in enumerate(profiles):
        key = (p.n, float(p.x[0]), float(p.x[-1]), str(extra[i]) if extra is not None else None)
        bucket = groups.setdefault(key, [])
        # Same first/last x and length is almost always the same grid; confirm cheaply before pooling.
        for members in bucket:
            if profiles[members[0]].x is p.x or np.array_equal(profiles[members[0]].x, p.x):
                members.append(i)
                break
        else:
            bucket.append([i])
    return sorted((m for bucket in groups.values() for m in bucket), key=lambda m: m[0])


def _require_filled(p: Profile, step: str) -> None:
    if np.isnan(p.z).any():
        raise InputError(f"{p.where}: {step} needs complete data; {np.isnan(p.z).mean():.1%} of the samples are "
                         "dropouts (NaN): call fill_dropouts() first")


def _refuse_flat(raw: "ProfileSet", detrended: "ProfileSet", kind: str) -> None:
    """A surface without roughness has no PSD: Persson's theory would give full contact (A/A0 = 1) and mu = 0.

    All profiles flat is an error; some flat ones are warned about (they add zero power to the average).
    """
    flat = [p.name for p, d in zip(raw, detrended) if flat_after_detrend(p.z, d.z)]
    if not flat:
        return
    what = f"constant (or a {kind} trend only) after detrending ({kind})"
    if len(flat) == len(raw):
        raise InputError(f"{raw.source or '<array>'}: no roughness: the heights of "
                         f"{'the profile' if len(flat) == 1 else 'every profile'} ({', '.join(flat[:5])}) are "
                         f"{what}; the PSD would be zero, the contact full (A/A0 = 1) and mu = 0. Check the height "
                         "column (a constant or reference column?)")
    warnings.warn(f"{raw.source or '<array>'}: profile(s) {', '.join(flat[:5])}"
                  f"{' ...' if len(flat) > 5 else ''} have heights {what}; they add no roughness and lower the "
                  "averaged PSD", DataWarning, stacklevel=3)
