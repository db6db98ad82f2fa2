r"""From raw channels to mu-slip rows along the road: zero offsets, Eqs. 1 and 8-10, running position, alignment.

Per sample and tire (Study on the influence of environmental conditions on road friction characteristics,
Lubricants 11(7), 277 (2023)):

* braking force and normal load from the load cells (Eqs. 8-9, :mod:`validation.rigs.balance`), less their
  offsets read on the zero rows (tires off the road), linear in time between zero blocks;
* :math:`\mu = F_B/N` (Eq. 10);
* slip :math:`s = (V - \omega r)/V` (Eq. 1), or the rig's fixed slip (sprocket tooth ratio);
* running position :math:`x(t) = x_0 + \int_0^t V\,dt'` (trapezoidal rule; the ``x_m`` column when present).

Tire k's contact lies ``offset_m`` behind the first tire's, so at time t it touches the road at
:math:`x(t) - \mathrm{offset}_k`: the tires see the same road point at different samples, about
:math:`\mathrm{offset}_k/(V\,\Delta t)` samples apart (at 40 km/h and 100 Hz the article's tires read it at samples
n, n + 7 and n + 15). With ``align=True`` each tire's mu, slip and speed are interpolated, linearly in road
position and only between two consecutive good samples, to the road positions of the first tire's samples, where
every tire has been; the article rounds the shift to whole samples at a constant speed, which this reduces to.
With ``align=False`` every tire's sample is put at the first tire's position (the article's "without correction").
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, replace

import numpy as np

from frictioncite import doi

from ..errors import ChannelWarning, InputError
from .balance import (TRAILER_2023, BalanceCheck, _zero_fit, braking_force, check_balance, noise_level,
                      normal_load)
from .channels import TrailerRun
from .rig import rig_from_dict

__all__ = ["reduce", "TrailerRows", "running_position"]


@doi(TRAILER_2023)
@dataclass(frozen=True, eq=False)
class TrailerRows:
    """Reduced rows: one per tire and road position (read-only arrays of equal length).

    Attributes
    ----------
    position : ndarray
        Road position, m (column ``position_m``).
    tire : ndarray of int
        The tire (1-based).
    slip : ndarray
        Slip ratio (Eq. 1).
    speed : ndarray
        Vehicle speed V, m/s (column ``speed_m_s``).
    mu : ndarray
        F_B / N (Eq. 10).
    time : ndarray
        When the tire was at that position, s.
    mu_std : ndarray or None
        Standard error of ``mu`` per row (binned rows, :meth:`binned`); None for single samples.
    n_samples : ndarray or None
        Samples averaged into each row (binned rows); None for single samples.
    aligned : bool
        Whether the tires' offsets were corrected (positions are road positions of each tire's contact).
    noise : tuple of float
        Per tire, the standard deviation of one sample's mu from sample to sample (successive differences of the
        raw samples, :func:`~validation.rigs.balance.noise_level`).
    slip_noise : tuple of float
        The same for the slip.
    offset_std : tuple of float
        Per tire, the standard deviation of mu that the zero-row offsets leave (their own noise,
        :func:`~validation.rigs.balance.zero_offset_std`; root mean square over the run): an error shared by all
        rows of the tire, which averaging does not reduce. 0 without zero rows (the offsets are then not
        estimated, and the notes say so).
    source : str
        The raw file.
    balance : BalanceCheck or None
        The force-balance check of the raw channels (None when not run).
    notes : tuple of str
        Offsets, alignment, samples left out.
    """

    position: np.ndarray
    tire: np.ndarray
    slip: np.ndarray
    speed: np.ndarray
    mu: np.ndarray
    time: np.ndarray
    mu_std: np.ndarray | None = None
    n_samples: np.ndarray | None = None
    aligned: bool = True
    noise: tuple = ()
    slip_noise: tuple = ()
    offset_std: tuple = ()
    source: str = "<arrays>"
    balance: BalanceCheck | None = field(default=None, repr=False)
    notes: tuple = ()

    def __post_init__(self):
        for name in ("position", "tire", "slip", "speed", "mu", "time", "mu_std", "n_samples"):
            a = getattr(self, name)
            if a is not None:
                a = np.array(a)  # a copy: the caller's arrays stay writable
                a.setflags(write=False)
                object.__setattr__(self, name, a)

    @property
    def n(self) -> int:
        """Number of rows."""
        return int(self.mu.size)

    def __len__(self) -> int:
        return self.n

    @property
    def position_m(self) -> np.ndarray:
        """Column ``position_m``: :attr:`position`."""
        return self.position

    @property
    def speed_m_s(self) -> np.ndarray:
        """Column ``speed_m_s``: :attr:`speed`."""
        return self.speed

    def __getitem__(self, column: str) -> np.ndarray:
        """A column of :meth:`as_table` by name (``rows["position_m"]``)."""
        table = self.as_table()
        if column not in table:
            raise InputError(f"rows: no column {column!r}; columns: {', '.join(table)}")
        return table[column]

    @property
    def tires(self) -> tuple[int, ...]:
        """The tires present, in order."""
        return tuple(int(k) for k in np.unique(self.tire))

    def subset(self, mask) -> "TrailerRows":
        """The rows selected by a boolean mask or an index array."""
        idx = np.arange(self.n)[np.asarray(mask)]
        pick = {k: (None if getattr(self, k) is None else getattr(self, k)[idx])
                for k in ("position", "tire", "slip", "speed", "mu", "time", "mu_std", "n_samples")}
        return replace(self, **pick)

    def for_tire(self, k: int) -> "TrailerRows":
        """The rows of tire ``k``."""
        return self.subset(self.tire == k)

    def as_table(self) -> dict[str, np.ndarray]:
        """Columns ``position_m, tire, slip, speed_m_s, mu, t_s`` (+ ``mu_std, n_samples`` when binned)."""
        cols = {"position_m": self.position, "tire": self.tire, "slip": self.slip, "speed_m_s": self.speed,
                "mu": self.mu, "t_s": self.time}
        if self.mu_std is not None:
            cols["mu_std"] = self.mu_std
            cols["n_samples"] = self.n_samples
        return cols

    def to_csv(self, path, comments: tuple[str, ...] = (), *, overwrite: bool = False):
        """Write :meth:`as_table` as a CSV with the notes as comments, atomically (complete or not at all)."""
        from persson.io import write_csv

        head = (f"reduced from {self.source}", "aligned to road positions" if self.aligned else "not aligned")
        return write_csv(path, self.as_table(), comments=head + tuple(comments) + tuple(self.notes),
                         overwrite=overwrite)  # an existing file only if asked

    def to_measurements(self, *, temperature, pressure, wet=False, series: str | None = None, contact=None):
        """The rows as :class:`~validation.Measurements` (with ``position_m``), for compare, diagnose and reports.

        Parameters
        ----------
        temperature : float or array_like
            Background temperature, deg C (the trailer's channels do not carry it).
        pressure : float or array_like
            Nominal contact pressure of the tires, Pa.
        wet : bool or array_like
            Whether the run was wet.
        series : str, optional
            Label of the run; each row's series is ``"<series>, tire k"`` (``"tire k"`` without it).
        contact : persson.slip.Contact, optional
            Brush model of the tires (needed to predict rows with slip < 1).

        Returns
        -------
        Measurements
            ``mu_std`` is the binned rows' standard error, or each tire's sample noise (:attr:`noise`) for single
            samples (None where a tire shows no noise at all).

        Raises
        ------
        InputError
            A row with slip <= 0 (a free-rolling or driven tire) or mu < 0, naming the tire and position.
        """
        from ..measurements import Measurements

        for bad, what in ((self.slip <= 0, "slip"), (self.slip > 1, "slip"), (self.mu < 0, "mu")):
            if np.any(bad):
                i = int(np.argmax(bad))
                raise InputError(f"{self.source}: row {i + 1} (tire {int(self.tire[i])}, position "
                                 f"{self.position[i]:.6g} m): {what} = {getattr(self, what)[i]:.4g}; measurement rows "
                                 f"need a braking slip in (0, 1] and mu >= 0: select the braked rows first, e.g. "
                                 f"rows.subset((rows.slip > 0) & (rows.mu >= 0))")
        if self.mu_std is not None:
            std = self.mu_std
        else:
            sig = np.array([self.noise[k - 1] if k - 1 < len(self.noise) else 0.0 for k in self.tires])
            std = None if np.any(sig <= 0) else np.asarray(self.noise)[self.tire - 1]
        labels = np.array([f"{series}, tire {k}" if series else f"tire {k}" for k in self.tire], dtype=object)
        return Measurements.from_arrays(slip=self.slip, speed=self.speed, temperature=temperature, pressure=pressure,
                                        mu=self.mu, mu_std=std, wet=np.broadcast_to(np.asarray(wet, dtype=bool),
                                                                                    (self.n,)),
                                        series=labels, source=self.source, contact=contact, position=self.position)

    def binned(self, step_m: float, *, start_m: float | None = None) -> "TrailerRows":
        """Rows averaged per tire over road bins of ``step_m`` metres, with their standard errors.

        Each row is a bin's centre; slip, speed, mu and time are the bin means, ``mu_std`` the standard error of
        the mean mu, :math:`\\sqrt{\\max(\\sigma_k, s)^2/n + \\sigma_{0,k}^2}` with :math:`\\sigma_k` the tire's
        sample noise (:attr:`noise`), s the scatter inside the bin (which also holds the road's own variation, so the
        error is not underestimated where the friction changes inside a bin) and :math:`\\sigma_{0,k}` what the
        zero offsets leave (:attr:`offset_std`). Bins with fewer than 2 samples are left out.
        """
        b = bin_rows(self, step_m, start_m=start_m)
        keep = b.n >= 2
        bins, tires = np.nonzero(keep)
        return replace(self, position=b.centre[bins], tire=np.asarray(self.tires)[tires], slip=b.slip[keep],
                       speed=b.speed[keep], mu=b.mu[keep], time=b.time[keep], mu_std=b.mu_se[keep],
                       n_samples=b.n[keep], notes=self.notes + (f"binned over {step_m:g} m",))


@dataclass(frozen=True)
class Bins:
    """Per road bin (rows) and tire (columns, in ``rows.tires`` order): counts, means and standard errors
    (``mu_se_common``: the part of ``mu_se`` the zero offsets leave, shared by every bin of a tire)."""

    edges: np.ndarray
    centre: np.ndarray
    n: np.ndarray
    slip: np.ndarray
    mu: np.ndarray
    speed: np.ndarray
    time: np.ndarray
    mu_se: np.ndarray
    slip_se: np.ndarray
    mu_se_common: np.ndarray


def bin_rows(rows: TrailerRows, step_m: float, *, start_m: float | None = None) -> Bins:
    """Means and standard errors per (road bin, tire): see :meth:`TrailerRows.binned`."""
    step = float(step_m) if not isinstance(step_m, bool) else float("nan")
    if not (np.isfinite(step) and step > 0):
        raise InputError(f"step_m: expected a bin length > 0 in m, got {step_m!r}")
    if rows.n == 0:
        raise InputError(f"{rows.source}: no rows to bin")
    lo = float(np.min(rows.position)) if start_m is None else float(start_m)
    nb = int(np.floor((float(np.max(rows.position)) - lo) / step)) + 1
    if nb > 10_000_000 or nb < 1:
        raise InputError(f"step_m = {step:g} m over positions {lo:g}-{np.max(rows.position):g} m: "
                         f"{nb} bins; choose a longer step or a start_m below the first position")
    tires = np.asarray(rows.tires)
    col = np.searchsorted(tires, rows.tire)
    b = np.floor((rows.position - lo) / step).astype(np.int64)
    inside = (b >= 0) & (b < nb)
    idx = b[inside] * tires.size + col[inside]
    size = nb * tires.size

    def total(x):
        return np.bincount(idx, weights=x[inside], minlength=size).reshape(nb, tires.size)

    n = np.bincount(idx, minlength=size).reshape(nb, tires.size)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = {name: total(getattr(rows, name)) / n for name in ("slip", "mu", "speed", "time")}
        se = {}
        for name, noise in (("mu", rows.noise), ("slip", rows.slip_noise)):
            x = getattr(rows, name)
            dev = x[inside] - mean[name].ravel()[idx]
            var = np.bincount(idx, weights=dev * dev, minlength=size).reshape(nb, tires.size) / np.maximum(n - 1, 1)
            sig = np.array([noise[k - 1] if k - 1 < len(noise) else 0.0 for k in tires])
            se[name] = np.sqrt(np.maximum(var, sig[None, :] ** 2) / n)
        off = np.array([rows.offset_std[k - 1] if k - 1 < len(rows.offset_std) else 0.0 for k in tires])
        se["mu"] = np.sqrt(se["mu"] ** 2 + off[None, :] ** 2)
        common = np.broadcast_to(off[None, :], n.shape).copy()
    edges = lo + step * np.arange(nb + 1)
    return Bins(edges=edges, centre=0.5 * (edges[:-1] + edges[1:]), n=n, slip=mean["slip"], mu=mean["mu"],
                speed=mean["speed"], time=mean["time"], mu_se=se["mu"], slip_se=se["slip"], mu_se_common=common)


@doi(TRAILER_2023)
def running_position(raw: TrailerRun, *, start_m: float = 0.0) -> np.ndarray:
    r"""Distance travelled at each sample, m: ``start_m`` plus :math:`\int V\,dt` (trapezoidal rule), or the
    file's ``x_m`` column shifted to start at ``start_m``."""
    from scipy.integrate import cumulative_trapezoid

    if raw.has("x_m"):
        x = raw.columns["x_m"]
        return x - x[0] + start_m
    return start_m + cumulative_trapezoid(raw.speed, raw.time, initial=0.0)


@doi(TRAILER_2023)
def reduce(raw: TrailerRun, rig, align: bool = True, *, start_m: float = 0.0, check: bool = True,
           threshold: float = 6.0, exclude_flagged: bool = True) -> TrailerRows:
    """Reduce a trailer run's raw channels to rows (position, tire, slip, speed, mu): see the module docstring.

    Parameters
    ----------
    raw : TrailerRun
        The channels (:func:`~validation.rigs.read_trailer`).
    rig : dict or Rig
        The rig the run was recorded with.
    align : bool
        Correct the tires' fore/aft offsets (rows at common road positions) or not (every tire at the first
        tire's position, as recorded).
    start_m : float
        Road position of the first tire at the first sample, m (e.g. from a positioning plate), so that runs over
        the same road share positions.
    check : bool
        Run :func:`~validation.rigs.check_balance` first.
    threshold : float
        Its threshold (in noise levels).
    exclude_flagged : bool
        Leave the flagged samples of a tire out (a :class:`~validation.ChannelWarning` says which).

    Returns
    -------
    TrailerRows

    Raises
    ------
    InputError
        A rig with another number of tires than the run, a tire left without good samples, a normal load <= 0
        after the offsets are removed.

    Warns
    -----
    ChannelWarning
        Samples left out because a channel failed the force-balance check.
    """
    rig = rig_from_dict(rig)
    if isinstance(start_m, bool) or not isinstance(start_m, (int, float)) or not np.isfinite(start_m):
        raise InputError(f"start_m: expected the road position of the first sample in m, got {start_m!r}")
    if not isinstance(raw, TrailerRun):
        raise InputError(f"raw: expected the channels read by read_trailer (a TrailerRun), got {type(raw).__name__}")
    if raw.n_tires != rig.n_tires:
        raise InputError(f"rig: {rig.n_tires} tire(s), but the run {raw.source} was read with {raw.n_tires}")
    x = running_position(raw, start_m=float(start_m))
    measured = raw.measured
    t, v = raw.time, raw.speed
    bal = check_balance(raw, rig, threshold=threshold) if check else None
    notes = []
    cols = []
    offset_std = []
    n_blocks = 0
    for k in range(1, rig.n_tires + 1):
        tire = rig.tire(k)
        fb = braking_force(raw.channel("fxl_{k}_N", k), raw.channel("fxr_{k}_N", k), tire)
        nl = normal_load(raw.channel("fzl_{k}_N", k), raw.channel("fzr_{k}_N", k), tire)
        off_b, sd_b, n_blocks = _zero_fit(raw, fb)
        off_n, sd_n, _ = _zero_fit(raw, nl)
        nl = nl - off_n
        good = measured.copy()
        if bal is not None and exclude_flagged:
            flagged = bal.mask(k) & measured
            if flagged.any():
                good &= ~flagged
                notes.append(f"tire {k}: {int(flagged.sum())} sample(s) left out by the force-balance check")
        if np.any(good & (nl <= 0)):
            i = int(np.argmax(good & (nl <= 0)))
            raise InputError(f"{raw.where(i, f'fzl_{k}_N')}: the normal load of tire {k} less its zero-row offset "
                             f"is {nl[i]:.4g} N; check the zero rows (column 'zero': tires off the road)")
        if not good.any():
            raise InputError(f"{raw.source}: tire {k} has no good sample left (see the force-balance check)")
        mu = np.where(good, (fb - off_b) / np.where(nl > 0, nl, 1.0), 0.0)
        sd_mu = np.sqrt(sd_b ** 2 + (mu * sd_n) ** 2) / np.where(nl > 0, nl, 1.0)
        offset_std.append(float(np.sqrt(np.mean(sd_mu[good] ** 2))))
        if raw.has(f"omega_{k}_rad_s"):
            slip = 1.0 - raw.channel("omega_{k}_rad_s", k) * tire.wheel_radius_m / np.where(v > 0, v, 1.0)
        else:
            slip = np.full(raw.n, tire.slip)
        cols.append((x - tire.offset_m, good, mu, slip))
    if n_blocks:
        notes.append(f"load-cell offsets of F_B and N read on {n_blocks} block(s) of zero rows, linear in time "
                     "between them")
    else:
        notes.append("no zero rows (column 'zero'): the load cells are taken as zeroed; a drifting offset goes "
                     "straight into mu")
    if bal is not None and bal.flags and exclude_flagged:
        warnings.warn(f"{raw.source}: samples left out of the reduction:\n" +
                      "\n".join(f.message for f in bal.flags), ChannelWarning, stacklevel=2)
    noise = tuple(noise_level(mu[good]) for _, good, mu, _ in cols)
    slip_noise = tuple(noise_level(slip[good]) for _, good, _, slip in cols)
    parts = _aligned(cols, t, v, measured) if align else _unaligned(cols, t, v)
    if align:
        vm = float(np.median(v[measured]))
        dt = float(np.median(np.diff(t)))
        shifts = ", ".join(f"tire {k}: {(rig.tire(k).offset_m - rig.tire(1).offset_m) / (vm * dt):.3g}"
                           for k in range(2, rig.n_tires + 1))
        notes.append(f"aligned: each tire's mu interpolated to the road positions of tire 1 (offsets at the median "
                     f"speed {vm:.3g} m/s and {1 / dt:.4g} Hz, in samples: {shifts or 'none'})")
    else:
        notes.append("not aligned: every tire's samples at tire 1's position (the tires' offsets not corrected)")
    pos, tire_no, slip, speed, mu, time = (np.concatenate([p[i] for p in parts]) for i in range(6))
    return TrailerRows(position=pos, tire=tire_no, slip=slip, speed=speed, mu=mu, time=time, aligned=bool(align),
                       noise=noise, slip_noise=slip_noise, offset_std=tuple(offset_std), source=raw.source,
                       balance=bal, notes=tuple(notes))


# ==========================================================================================================
def _unaligned(cols, t, v):
    ref = cols[0][0]
    out = []
    for k, (_, good, mu, slip) in enumerate(cols, start=1):
        out.append((ref[good], np.full(int(good.sum()), k), slip[good], v[good], mu[good], t[good]))
    return out


def _aligned(cols, t, v, measured):
    """Each tire interpolated to tire 1's road positions inside the stretch every tire covered."""
    lo = max(float(road[measured].min()) for road, *_ in cols)
    hi = min(float(road[measured].max()) for road, *_ in cols)
    ref = cols[0][0]
    X = ref[measured & (ref >= lo) & (ref <= hi)]
    if X.size == 0:
        raise InputError("the run is shorter than the tires' offsets: no road position was passed by every tire")
    out = []
    for k, (road, good, mu, slip) in enumerate(cols, start=1):
        j = np.clip(np.searchsorted(road, X, side="right") - 1, 0, road.size - 1)
        exact = good[j] & (road[j] == X)
        j1 = np.minimum(j + 1, road.size - 1)
        span = road[j1] - road[j]
        between = good[j] & good[j1] & (j1 == j + 1) & (span > 0)
        ok = exact | between
        w = np.where(between & ~exact, (X - road[j]) / np.where(span > 0, span, 1.0), 0.0)[ok]
        jj, jn = j[ok], j1[ok]
        slip_x, v_x, mu_x, t_x = ((1.0 - w) * y[jj] + w * y[jn] for y in (slip, v, mu, t))
        out.append((X[ok], np.full(int(ok.sum()), k), slip_x, v_x, mu_x, t_x))
    return out
