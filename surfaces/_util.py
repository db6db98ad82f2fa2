"""Small private helpers shared by the modules of :mod:`surfaces`: units, argument checks, atomic writes."""

from __future__ import annotations

import math
import os
import tempfile
from pathlib import Path

import numpy as np

from .errors import InputError

#: Length units accepted in column names and arguments, as factors to metres.
LENGTH_UNITS: dict[str, float] = {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6}


def unit_factor(unit: str, where: str) -> float:
    """Factor that converts ``unit`` to metres; ``where`` names the file/column/argument for the message."""
    try:
        return LENGTH_UNITS[unit]
    except (KeyError, TypeError):
        raise InputError(f"{where}: unknown length unit {unit!r}; expected one of m, mm, um") from None


def finite_float(value, name: str) -> float:
    """``value`` as a finite float, or InputError naming the argument ``name``."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected a number, got {value!r}") from None
    if not math.isfinite(x):
        raise InputError(f"{name}: expected a finite number, got {x}")
    return x


def positive(value, name: str) -> float:
    """``value`` as a finite float > 0, or InputError naming the argument ``name``."""
    x = finite_float(value, name)
    if x <= 0:
        raise InputError(f"{name}: expected a positive number, got {x:g}")
    return x


def optional_positive(value, name: str) -> float | None:
    """Like :func:`positive`, but ``None`` passes through."""
    return None if value is None else positive(value, name)


def band(q: np.ndarray, q_min, q_max, what: str) -> np.ndarray:
    """Boolean mask of ``q`` inside ``[q_min, q_max]`` (None = open end); InputError if fewer than 2 points."""
    lo = -np.inf if q_min is None else positive(q_min, "q_min")
    hi = np.inf if q_max is None else positive(q_max, "q_max")
    if not hi > lo:
        raise InputError(f"{what}: expected q_max > q_min, got q_min={lo:g}, q_max={hi:g} rad/m")
    mask = (q >= lo * (1 - 1e-12)) & (q <= hi * (1 + 1e-12))
    if mask.sum() < 2:
        raise InputError(f"{what}: fewer than 2 points of the table lie in [{lo:g}, {hi:g}] rad/m "
                         f"(table covers [{q[0]:g}, {q[-1]:g}] rad/m)")
    return mask


def span(a: np.ndarray, unit: str) -> str:
    """``"-1.2e-05 to 3.4e-05 m"`` for reprs (NaN ignored; ``"all missing"`` when nothing is left)."""
    a = np.asarray(a, dtype=float)
    if not np.isfinite(a).any():
        return "all missing"
    return f"{np.nanmin(a):.4g} to {np.nanmax(a):.4g} {unit}"


def flat_after_detrend(raw: np.ndarray, detrended: np.ndarray, rtol: float = 1e-9) -> bool:
    """True when heights are constant (or pure trend): the detrended rms is round-off of the raw heights.

    A constant or straight-line profile leaves residuals of about 1e-16 of its height after detrending, so the
    test is relative to the largest raw height (an all-zero profile is flat too).
    """
    scale = float(np.nanmax(np.abs(raw))) if np.isfinite(raw).any() else 0.0
    resid = float(np.sqrt(np.nanmean(np.square(detrended)))) if np.isfinite(detrended).any() else 0.0
    return resid <= rtol * scale


def atomic_write_text(path, text: str) -> Path:
    """Write ``text`` to ``path`` completely or not at all (temporary file in the same folder, then rename)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.chmod(tmp, _file_mode())
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    return path


def powerlaw_segments_integral(q: np.ndarray, C: np.ndarray, n: float) -> np.ndarray:
    r"""Exact :math:`\int_{q_i}^{q_{i+1}} q^n C(q)\,dq` for ``C`` a power law on each segment (log-log linear)."""
    qa, qb, Ca, Cb = q[:-1], q[1:], C[:-1], C[1:]
    r = np.log(qb / qa)
    s = np.log(Cb / Ca) / r
    p = n + s + 1.0
    fa = Ca * qa ** (n + 1)
    with np.errstate(over="ignore", invalid="ignore"):
        general = fa * np.expm1(p * r) / p
    return np.where(np.abs(p * r) < 1e-10, fa * r, general)


def loglog_interp(q_new, q: np.ndarray, C: np.ndarray) -> np.ndarray:
    """Log-log linear interpolation of ``C(q)`` at ``q_new``; zero outside ``[q[0], q[-1]]``."""
    q_new = np.asarray(q_new, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        lq = np.log(np.clip(q_new, q[0], q[-1]))
    out = np.exp(np.interp(lq, np.log(q), np.log(C)))
    inside = (q_new >= q[0] * (1 - 1e-12)) & (q_new <= q[-1] * (1 + 1e-12))
    return np.where(inside, out, 0.0)


def _file_mode() -> int:
    # mkstemp creates 0600 files; give the final file the permissions open() would (0666 minus the umask).
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask
