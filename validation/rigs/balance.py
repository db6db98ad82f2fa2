r"""Force balance of a trailer's measuring tire: braking force, normal load, and the checks that find bad channels.

Each measuring tire hangs between a left and a right two-axis load cell and is braked through a chain (upper and
lower tensions :math:`F_{cu}, F_{cd}` at an angle :math:`\Delta\theta` from the horizontal). The balance of the
wheel assembly (Study on the influence of environmental conditions on road friction characteristics, Lubricants
11(7), 277 (2023), Eqs. 4-7):

.. math::

    F_{xL} + F_{xR} &= F_B + (F_{cu} + F_{cd})\cos\Delta\theta  && \text{(4, x forces)} \\
    F_{zL} + F_{zR} + (F_{cu} - F_{cd})\sin\Delta\theta + m g &= N  && \text{(5, z forces)} \\
    -l_L F_{zL} + l_R F_{zR} + l_s (F_{cu} - F_{cd})\sin\Delta\theta &= 0  && \text{(6, moment about x)} \\
    l_L F_{xL} - l_R F_{xR} + l_c (F_{cu} + F_{cd})\cos\Delta\theta &= 0  && \text{(7, moment about z)}

Eliminating the chain gives the article's Eqs. 8-10:

.. math::

    F_B = \left(1 + \frac{l_L}{l_c}\right) F_{xL} + \left(1 - \frac{l_R}{l_c}\right) F_{xR}, \quad
    N = \left(1 + \frac{l_L}{l_s}\right) F_{zL} + \left(1 - \frac{l_R}{l_s}\right) F_{zR} + m g, \quad
    \mu = F_B / N,

with :math:`l_c = l_s` in the article's Eq. 8 (the default here; a rig entry may give ``l_chain_m``). The article
prints Eq. 7 as :math:`(-l_L F_{xL} - l_R F_{zR}) + l_c(\dots)\cos\Delta\theta = 0`, which does not lead to its
Eq. 8; the form above is the one Eq. 8 follows from (same sign pattern as the printed Eq. 6 after the x-z swap,
:math:`F_{xR}` for the misprinted :math:`F_{zR}`), and it is the form checked here.

With the four cells alone the four equations have four unknowns (:math:`F_B`, N and the two chain components):
nothing is left to check. With the chain channels measured, Eqs. 6 and 7 become two redundant relations, and
their residuals

.. math::

    r_z = (F_{cu} - F_{cd})\sin\Delta\theta - (l_L F_{zL} - l_R F_{zR})/l_s, \qquad
    r_x = (F_{cu} + F_{cd})\cos\Delta\theta - (l_R F_{xR} - l_L F_{xL})/l_c

must stay at zero within the cells' noise. :func:`check_balance` flags the rows where they do not, the rows where a
channel is frozen (the same value sample after sample) and the rows where the reduced mu is impossible.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from ..errors import InputError
from .channels import TrailerRun
from .forces import TRAILER_2023, braking_force, normal_load
from .rig import TireMount, rig_from_dict

__all__ = ["braking_force", "normal_load", "moment_residuals", "check_balance", "BalanceCheck", "ChannelFlag",
           "zero_offset", "zero_offset_std", "noise_level", "TRAILER_2023", "MU_RANGE"]

#: Friction coefficients a braked tire on a road can show; outside, the cells or the rig are wrong.
MU_RANGE = (-0.1, 2.5)
_VON_NEUMANN = "vonneumann:ams-12-153-1941"
_MAD = "10.1080/01621459.1993.10476408"
#: Samples on each side of a flagged range used to measure the step of a channel there.
_EDGE = 15



@doi(TRAILER_2023)
def moment_residuals(raw: TrailerRun, k: int, tire: TireMount) -> tuple[np.ndarray, np.ndarray] | None:
    r"""Residuals of the moment balances of tire ``k`` (Eqs. 7 and 6), N; None without chain channels.

    :math:`r_x = (F_{cu} + F_{cd})\cos\Delta\theta - (l_R F_{xR} - l_L F_{xL})/l_c` and
    :math:`r_z = (F_{cu} - F_{cd})\sin\Delta\theta - (l_L F_{zL} - l_R F_{zR})/l_s` (module docstring).
    """
    if not raw.has_chain(k):
        return None
    fcu, fcd = raw.channel("fcu_{k}_N", k), raw.channel("fcd_{k}_N", k)
    th = np.radians(raw.channel("theta_{k}_deg", k))
    fxl, fxr = raw.channel("fxl_{k}_N", k), raw.channel("fxr_{k}_N", k)
    fzl, fzr = raw.channel("fzl_{k}_N", k), raw.channel("fzr_{k}_N", k)
    rx = (fcu + fcd) * np.cos(th) - (tire.l_right_m * fxr - tire.l_left_m * fxl) / tire.chain_arm_m
    rz = (fcu - fcd) * np.sin(th) - (tire.l_left_m * fzl - tire.l_right_m * fzr) / tire.l_span_m
    return rx, rz


@dataclass(frozen=True)
class ChannelFlag:
    """Samples of one tire that failed a check.

    Attributes
    ----------
    tire : int
        The tire (1-based).
    kind : str
        ``"frozen"`` (a channel repeats one value), ``"moment_x"`` (Eq. 7 does not close), ``"moment_z"`` (Eq. 6
        does not close) or ``"implausible"`` (mu outside :data:`MU_RANGE`).
    channels : tuple of str
        The channel at fault when it could be singled out, else every channel of the failed relation.
    start, stop : int
        The samples ``start:stop`` (0-based, ``stop`` excluded).
    message : str
        What failed, where, and by how much.
    """

    tire: int
    kind: str
    channels: tuple
    start: int
    stop: int
    message: str


@dataclass(frozen=True)
class BalanceCheck:
    """What :func:`check_balance` found.

    Attributes
    ----------
    flags : tuple of ChannelFlag
        Every failed range, by tire then sample.
    checked : tuple of int
        Tires whose moment balances (Eqs. 6-7) were checked (those with chain channels).
    noise : dict
        ``{(tire, "moment_x" | "moment_z"): sigma}``: the residuals' noise level, N, from successive differences.
    threshold : float
        Residuals beyond ``threshold`` times their noise level were flagged.
    n : int
        Number of samples of the run.
    notes : tuple of str
        What could not be checked, and why.
    """

    flags: tuple
    checked: tuple
    noise: dict
    threshold: float
    n: int
    notes: tuple = ()

    @property
    def ok(self) -> bool:
        """True when nothing was flagged."""
        return not self.flags

    def mask(self, k: int) -> np.ndarray:
        """Samples of tire ``k`` inside a flagged range (bool, one per sample)."""
        m = np.zeros(self.n, dtype=bool)
        for f in self.flags:
            if f.tire == k:
                m[f.start:f.stop] = True
        return m

    def summary(self) -> str:
        """The flags' messages and the notes, one per line ("force balance: no bad channel found" when none)."""
        lines = [f.message for f in self.flags] or ["force balance: no bad channel found"]
        return "\n".join(lines + list(self.notes))

    def __str__(self) -> str:
        return self.summary()


@doi(TRAILER_2023, _VON_NEUMANN, _MAD)
def check_balance(raw: TrailerRun, rig, *, threshold: float = 6.0, min_samples: int = 3,
                  frozen_samples: int = 10) -> BalanceCheck:
    """Find bad channels: frozen channels, moment balances that do not close, impossible friction.

    Parameters
    ----------
    raw : TrailerRun
        The raw channels (:func:`~validation.rigs.read_trailer`).
    rig : dict or Rig
        The rig.
    threshold : float
        A moment residual (module docstring) is flagged where it departs from its offset by more than
        ``threshold`` times its noise level. The offset is taken from the zero rows (interpolated in time, see
        :func:`zero_offset`), else from a straight line through the residual (Theil-Sen slope of its 1-s block
        medians, which a fault over part of the run does not move; a drift beyond the threshold is noted); the
        noise level is the robust scale (1.4826 times the
        median absolute deviation, Rousseeuw & Croux 1993) of the successive differences divided by sqrt(2)
        (von Neumann et al. 1941), which a slowly varying load does not inflate.
    min_samples : int
        A flagged range needs this many flagged samples (isolated single-sample spikes are not reported); flagged
        samples closer than this are merged into one range.
    frozen_samples : int
        A load-cell or chain-tension channel that repeats exactly the same value over this many measured samples
        in a row is frozen (a loaded cell's noise never does). Wheel speeds (often quantised by pulse counting) and
        the chain angle (which may be a constant) are not checked.

    Returns
    -------
    BalanceCheck
        Each flag names the tire, the channels (the one at fault when its step at the range's edges alone
        explains the residual's step), the rows, lines and times, and the size of the departure.
    """
    rig = rig_from_dict(rig)
    if isinstance(threshold, bool) or not isinstance(threshold, (int, float)) or not threshold > 0:
        raise InputError(f"threshold: expected a number > 0 (in noise levels), got {threshold!r}")
    for name, value in (("min_samples", min_samples), ("frozen_samples", frozen_samples)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 2:
            raise InputError(f"{name}: expected an integer >= 2, got {value!r}")
    measured = raw.measured
    flags: list[ChannelFlag] = []
    checked = []
    noise = {}
    notes = []
    for k in range(1, rig.n_tires + 1):
        tire = rig.tire(k)
        frozen = _frozen(raw, k, measured, frozen_samples)
        flags += frozen
        res = moment_residuals(raw, k, tire)
        if res is None:
            notes.append(f"tire {k}: no chain channels (fcu_{k}_N, fcd_{k}_N, theta_{k}_deg): its moment balances "
                         "(Eqs. 6-7) cannot be checked - four cells, four unknowns; only frozen channels and "
                         "impossible friction were looked for")
        else:
            checked.append(k)
            for kind, r, eq in (("moment_x", res[0], "7"), ("moment_z", res[1], "6")):
                off, blocks = zero_offset(raw, r)
                sigma = max(noise_level(r[measured]), 1e-9 * (1.0 + float(np.median(np.abs(r)))))
                if not blocks:
                    off, drift = _trend(raw, r)
                    if drift > threshold * sigma:
                        notes.append(f"tire {k}: the balance of Eq. {eq} drifts by {drift:.3g} N over the run "
                                     f"({drift / sigma:.0f} times its noise) and there are no zero rows to remove it: "
                                     "a load-cell offset drifts, and mu with it; record zero rows (column 'zero')")
                dev = r - off
                noise[(k, kind)] = sigma
                for a, b in _ranges(measured & (np.abs(dev) > threshold * sigma), min_samples):
                    flags.append(_balance_flag(raw, k, tire, kind, eq, dev, sigma, a, b, frozen))
        fb = braking_force(raw.channel("fxl_{k}_N", k), raw.channel("fxr_{k}_N", k), tire)
        nl = normal_load(raw.channel("fzl_{k}_N", k), raw.channel("fzr_{k}_N", k), tire)
        mu = (fb - zero_offset(raw, fb)[0]) / (nl - zero_offset(raw, nl)[0])
        bad = measured & ~((mu >= MU_RANGE[0]) & (mu <= MU_RANGE[1]))
        for a, b in _ranges(bad, min_samples):
            worst = a + int(np.argmax(np.abs(mu[a:b] - 0.5 * sum(MU_RANGE))))
            flags.append(ChannelFlag(
                tire=k, kind="implausible", channels=tuple(c.format(k=k) for c in ("fxl_{k}_N", "fxr_{k}_N",
                                                                                    "fzl_{k}_N", "fzr_{k}_N")),
                start=a, stop=b,
                message=f"{raw.source}: tire {k}: mu = F_B/N (Eqs. 8-10) reaches {mu[worst]:.3g} over "
                        f"{raw.rows_text(a, b)}, outside {MU_RANGE[0]:g}-{MU_RANGE[1]:g}: a load cell of tire {k} is "
                        "wrong there (sign, unit, a loose connector)"))
    flags.sort(key=lambda f: (f.tire, f.start, f.kind))
    return BalanceCheck(flags=tuple(flags), checked=tuple(checked), noise=noise, threshold=float(threshold),
                        n=raw.n, notes=tuple(notes))


def zero_offset(raw: TrailerRun, values) -> tuple[np.ndarray, int]:
    """Offset of ``values`` (one per sample) from the run's zero rows, and the number of zero blocks.

    Each block of consecutive zero rows (tires off the road: no force on the road) gives the median of
    ``values`` there at the block's mean time; between blocks the offset is linear in time, before the first
    and after the last it is held (a linear load-cell drift between zero readings is removed exactly). Without
    zero rows the offset is 0 and the block count 0.
    """
    offset, _, n_blocks = _zero_fit(raw, values)
    return offset, n_blocks


def zero_offset_std(raw: TrailerRun, values) -> np.ndarray:
    r"""Standard deviation of :func:`zero_offset` at each sample, from the noise inside the zero blocks.

    A block median of n samples of noise :math:`\sigma` (:func:`noise_level`) has the standard deviation
    :math:`\sqrt{\pi/2}\,\sigma/\sqrt n` (large-n efficiency of the median of Gaussian data); the linear
    interpolation :math:`(1-w) o_i + w o_{i+1}` has the variance :math:`(1-w)^2 v_i + w^2 v_{i+1}`. Zero
    without zero rows (the offsets are then not estimated at all, and the notes say so).
    """
    return _zero_fit(raw, values)[1]


@doi(_VON_NEUMANN, _MAD)
def noise_level(values) -> float:
    r"""Standard deviation of the sample-to-sample noise of ``values``, robust to slow changes and outliers.

    :math:`\sigma = 1.4826\,\mathrm{MAD}(\Delta y)/\sqrt 2`: the successive differences :math:`\Delta y` of white
    noise have variance :math:`2\sigma^2` (von Neumann et al. 1941) while a signal that changes slowly from sample
    to sample adds almost nothing to them; the median absolute deviation scaled by 1.4826 is the standard
    deviation of Gaussian data (Rousseeuw & Croux 1993) and ignores the few differences across a step or spike.
    Noise correlated over several samples is underestimated (say so where it matters).
    """
    d = np.diff(np.asarray(values, dtype=float))
    if d.size == 0:
        return 0.0
    return float(1.4826 * np.median(np.abs(d - np.median(d))) / math.sqrt(2.0))


# ==========================================================================================================
def _zero_fit(raw: TrailerRun, values):
    values = np.asarray(values, dtype=float)
    z = raw.zero
    if not np.any(z):
        return np.zeros_like(values), np.zeros_like(values), 0
    blocks = _ranges(z, 1, merge=False)
    t = raw.time
    times = np.array([t[a:b].mean() for a, b in blocks])
    levels = np.array([np.median(values[a:b]) for a, b in blocks])
    var = np.array([(math.pi / 2.0) * noise_level(values[a:b]) ** 2 / (b - a) for a, b in blocks])
    offset = np.interp(t, times, levels)
    j = np.clip(np.searchsorted(times, t) - 1, 0, len(blocks) - 1)
    j1 = np.minimum(j + 1, len(blocks) - 1)
    span = times[j1] - times[j]
    w = np.where(span > 0, np.clip((t - times[j]) / np.where(span > 0, span, 1.0), 0.0, 1.0), 0.0)
    std = np.sqrt((1.0 - w) ** 2 * var[j] + w ** 2 * var[j1])
    return offset, std, len(blocks)


def _trend(raw: TrailerRun, r) -> tuple[np.ndarray, float]:
    """A straight line through ``r`` robust to faults (Theil-Sen slope through 1-s block medians of the measured
    rows), and how far it drifts over the run."""
    from scipy.stats import theilslopes

    m = raw.measured
    t, x = raw.time[m], np.asarray(r, dtype=float)[m]
    per = max(round(1.0 / float(np.median(np.diff(t)))), 1) if t.size > 1 else 1
    nb = t.size // per
    if nb < 3:
        level = float(np.median(x))
        return np.full(raw.n, level), 0.0
    tb = t[:nb * per].reshape(nb, per).mean(axis=1)
    xb = np.median(x[:nb * per].reshape(nb, per), axis=1)
    slope, intercept = theilslopes(xb, tb)[:2]
    return intercept + slope * raw.time, abs(float(slope)) * float(t[-1] - t[0])


def _ranges(mask, min_count: int, *, merge: bool = True) -> list[tuple[int, int]]:
    """``(start, stop)`` of the runs of True in ``mask``; with ``merge``, runs closer than ``min_count`` samples
    are joined and runs with fewer than ``min_count`` True samples dropped."""
    m = np.asarray(mask, dtype=bool)
    if not m.any():
        return []
    edges = np.flatnonzero(np.diff(np.concatenate(([0], m.astype(np.int8), [0]))))
    starts, stops = edges[0::2], edges[1::2]
    if not merge:
        return list(zip(starts.tolist(), stops.tolist()))
    out = []
    a, b, count = int(starts[0]), int(stops[0]), int(stops[0] - starts[0])
    for s, e in zip(starts[1:].tolist(), stops[1:].tolist()):
        if s - b < min_count:
            b, count = e, count + (e - s)
            continue
        if count >= min_count:
            out.append((a, b))
        a, b, count = s, e, e - s
    if count >= min_count:
        out.append((a, b))
    return out


def _frozen(raw: TrailerRun, k: int, measured, frozen_samples: int) -> list[ChannelFlag]:
    # wheel speeds from pulse counts repeat legitimately, and a rig may record its chain angle as a constant
    names = ["fxl_{k}_N", "fxr_{k}_N", "fzl_{k}_N", "fzr_{k}_N", "fcu_{k}_N", "fcd_{k}_N"]
    out = []
    for pattern in names:
        name = pattern.format(k=k)
        if not raw.has(name):
            continue
        x = raw.columns[name]
        same = (np.diff(x) == 0) & measured[1:] & measured[:-1]
        for a, b in _ranges(same, 1, merge=False):
            if b - a + 1 >= frozen_samples:
                out.append(ChannelFlag(
                    tire=k, kind="frozen", channels=(name,), start=a, stop=b + 1,
                    message=f"{raw.source}: tire {k}: channel {name!r} is frozen at {x[a]:.6g} over "
                            f"{raw.rows_text(a, b + 1)} ({b - a + 1} samples with exactly the same value): a dead "
                            "sensor or a stalled acquisition"))
    return out


def _balance_flag(raw: TrailerRun, k: int, tire: TireMount, kind: str, eq: str, dev, sigma: float, a: int, b: int,
                  frozen: list) -> ChannelFlag:
    """A flag for the residual range ``a:b``, naming the channel whose step explains the residual's step."""
    names, coef = _coefficients(raw, k, tire, kind, a, b)
    culprit = [f.channels[0] for f in frozen if f.channels[0] in names and f.start < b and f.stop > a]
    for edge in ("start", "end"):
        if culprit:
            break
        jr = _step(dev, a, b, edge)
        if jr != 0.0:
            matches = [n for n in names if abs(coef[n] * _step(raw.columns[n], a, b, edge) - jr) <= 0.25 * abs(jr)]
            culprit = matches if len(matches) == 1 else []
    worst = a + int(np.argmax(np.abs(dev[a:b])))
    what = ("moment about z (Eq. 7: chain pull against the longitudinal cells)" if kind == "moment_x" else
            "moment about x (Eq. 6: chain pull against the vertical cells)")
    who = (f"channel {culprit[0]!r} is wrong there (its step matches the residual's)" if culprit else
           f"one of {', '.join(repr(n) for n in names)} is wrong there")
    return ChannelFlag(
        tire=k, kind=kind, channels=tuple(culprit) if culprit else tuple(names), start=a, stop=b,
        message=f"{raw.source}: tire {k}: the {what} does not close over {raw.rows_text(a, b)}: residual up to "
                f"{dev[worst]:.4g} N, {abs(dev[worst]) / sigma:.0f} times its noise ({sigma:.3g} N); {who}")


def _coefficients(raw: TrailerRun, k: int, tire: TireMount, kind: str, a: int, b: int):
    """Channels of the relation ``kind`` and d(residual)/d(channel), at the range's median chain state."""
    fcu = float(np.median(raw.channel("fcu_{k}_N", k)[a:b]))
    fcd = float(np.median(raw.channel("fcd_{k}_N", k)[a:b]))
    th = math.radians(float(np.median(raw.channel("theta_{k}_deg", k)[a:b])))
    if kind == "moment_x":
        lc = tire.chain_arm_m
        coef = {f"fxl_{k}_N": tire.l_left_m / lc, f"fxr_{k}_N": -tire.l_right_m / lc, f"fcu_{k}_N": math.cos(th),
                f"fcd_{k}_N": math.cos(th), f"theta_{k}_deg": -(fcu + fcd) * math.sin(th) * math.pi / 180.0}
    else:
        ls = tire.l_span_m
        coef = {f"fzl_{k}_N": -tire.l_left_m / ls, f"fzr_{k}_N": tire.l_right_m / ls, f"fcu_{k}_N": math.sin(th),
                f"fcd_{k}_N": -math.sin(th), f"theta_{k}_deg": (fcu - fcd) * math.cos(th) * math.pi / 180.0}
    return list(coef), coef


def _step(x, a: int, b: int, edge: str = "start") -> float:
    """Step of ``x`` at the start (or end) of the range ``a:b``: the straight lines fitted to the samples just
    inside and just outside, both evaluated at the edge (a channel that merely changes with the load does not
    step)."""
    x = np.asarray(x, dtype=float)
    w = min(_EDGE, b - a)
    at = a if edge == "start" else b
    if w < 2 or at - w < 0 or at + w > x.size:
        return 0.0
    i = np.arange(-w, w)
    inside, outside = (i >= 0, i < 0) if edge == "start" else (i < 0, i >= 0)
    seg = x[at - w:at + w]
    fit_in = np.polyfit(i[inside] + 0.5, seg[inside], 1)
    fit_out = np.polyfit(i[outside] + 0.5, seg[outside], 1)
    return float(np.polyval(fit_in, 0.0) - np.polyval(fit_out, 0.0))
