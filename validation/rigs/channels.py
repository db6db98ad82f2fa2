"""Raw channels of a friction trailer: the file format, the reader and the checks.

Format (``docs/conventions.md``, "Friction-trailer channels"): a CSV with a header row, lines starting with ``#``
are comments, one row per sample (typically 100 Hz). Columns:

* ``t_s`` - time, s, strictly increasing;
* ``v_m_s`` - vehicle speed V, m/s (> 0 on measured rows);
* per measuring tire k = 1, 2, ... (the rig's order): ``fxl_k_N``, ``fxr_k_N`` (longitudinal forces of the left
  and right load cells, N), ``fzl_k_N``, ``fzr_k_N`` (vertical forces of the two cells, N) and ``omega_k_rad_s``
  (wheel angular speed, rad/s; may be left out for a tire whose rig entry gives a fixed ``slip``);
* optional: ``x_m`` (distance travelled, m, non-decreasing: used instead of integrating the speed), ``zero``
  (1 on rows recorded with the measuring tires off the road, whose readings are the load-cell offsets; 0 on
  measured rows), and per tire the chain channels ``fcu_k_N``, ``fcd_k_N`` (upper and lower chain tensions, N) and
  ``theta_k_deg`` (chain angle from the horizontal, degrees), all three or none, which make the moment balances
  (Eqs. 6-7) checkable.

Other columns are ignored. Checks (each failure raises :class:`~validation.InputError` naming the file, the line,
the data row and the column): a missing channel, channels of a tire the rig does not have, a non-number, NaN or
infinity, a time that does not increase, a speed <= 0 on a measured row (the slip of Eq. 1 and the running position
need a moving trailer), a speed above 70 m/s ("looks like km/h"), a negative wheel speed, a normal load (Eq. 9)
<= 0 on a measured row, wheel speeds whose median rolling speed omega r is 60/(2 pi) or 180/pi times the vehicle
speed (rpm or deg/s instead of rad/s) or whose median slip lies outside (-0.5, 1], a chain angle beyond 90 degrees,
a ``zero`` column that is not 0/1.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError
from .forces import GRAVITY, normal_load
from .rig import Rig, rig_from_dict

__all__ = ["TrailerRun", "read_trailer", "tire_columns", "CHAIN_COLUMNS", "FORCE_COLUMNS", "GRAVITY"]

#: Load-cell columns of tire k (format with ``k``).
FORCE_COLUMNS = ("fxl_{k}_N", "fxr_{k}_N", "fzl_{k}_N", "fzr_{k}_N")
#: Optional chain columns of tire k: upper and lower tension, angle from the horizontal.
CHAIN_COLUMNS = ("fcu_{k}_N", "fcd_{k}_N", "theta_{k}_deg")
_OMEGA = "omega_{k}_rad_s"
_TOP = ("t_s", "v_m_s")
_OPTIONAL_TOP = ("x_m", "zero")
#: Largest vehicle speed accepted, m/s (252 km/h): larger values are a km/h column.
_MAX_SPEED = 70.0


@dataclass(frozen=True, eq=False)
class TrailerRun:
    """Raw channels of one trailer run (read-only arrays, one value per sample).

    Attributes
    ----------
    columns : dict of str to ndarray
        The channels by column name (``t_s``, ``v_m_s``, ``fxl_1_N``, ...); ``zero`` is always present (all 0
        when the file has no such column).
    n_tires : int
        Number of measuring tires (the rig's).
    source : str
        The file (or a description).
    lines : ndarray of int
        Line of each sample in the file (1-based; 0 when built from arrays).
    """

    columns: dict
    n_tires: int
    source: str = "<arrays>"
    lines: np.ndarray | None = field(default=None, repr=False)

    @classmethod
    def from_columns(cls, columns: dict, rig, *, source: str = "<arrays>") -> "TrailerRun":
        """A run from arrays keyed by column name, with the same checks as :func:`read_trailer`.

        Parameters
        ----------
        columns : dict of str to array_like
            Channels named as in the file format (see the module docstring); other keys are ignored.
        rig : dict or Rig
            The rig (:func:`~validation.rigs.rig_from_dict`): its tires decide which channels are required.
        source : str
            A description named in messages.
        """
        rig = rig_from_dict(rig)
        _require(list(columns), rig, source)
        cols = {}
        n = None
        for name in _wanted(columns, rig):
            try:
                a = np.array(columns[name], dtype=float).ravel()
            except (TypeError, ValueError):
                raise InputError(f"{source}: column {name!r}: expected numbers") from None
            if n is None:
                n = a.size
            elif a.size != n:
                raise InputError(f"{source}: column {name!r} has {a.size} values, expected {n} (as column 't_s')")
            cols[name] = a
        return _checked(cols, rig, source, None, header_line=0)

    # ---------------------------------------------------------------------------------------------------------
    @property
    def n(self) -> int:
        """Number of samples."""
        return int(self.columns["t_s"].size)

    def __len__(self) -> int:
        return self.n

    @property
    def time(self) -> np.ndarray:
        """t, s."""
        return self.columns["t_s"]

    @property
    def speed(self) -> np.ndarray:
        """Vehicle speed V, m/s."""
        return self.columns["v_m_s"]

    @property
    def zero(self) -> np.ndarray:
        """True on rows recorded with the tires off the road (load-cell offsets)."""
        return self.columns["zero"] > 0.5

    @property
    def measured(self) -> np.ndarray:
        """True on measured rows (``zero == 0``)."""
        return ~self.zero

    def has(self, name: str) -> bool:
        """Whether the run has the column ``name``."""
        return name in self.columns

    def channel(self, name: str, k: int | None = None) -> np.ndarray:
        """Column ``name`` (a pattern with ``{k}`` for per-tire channels, e.g. ``"fxl_{k}_N"``)."""
        key = name.format(k=k) if k is not None else name
        if key not in self.columns:
            raise InputError(f"{self.source}: no column {key!r}")
        return self.columns[key]

    def has_chain(self, k: int) -> bool:
        """Whether tire ``k`` has the chain channels (tensions and angle)."""
        return all(c.format(k=k) in self.columns for c in CHAIN_COLUMNS)

    def where(self, i: int, column: str | None = None) -> str:
        """``'<file>, line L (data row i+1), column c'`` of sample ``i``, for messages."""
        return _where(self.source, self.lines, i, column)

    def rows_text(self, start: int, stop: int) -> str:
        """``'rows a-b (lines ..., t = ... s)'`` of the samples ``start:stop``, for messages."""
        a, b = start, stop - 1
        text = f"rows {a + 1}-{b + 1}" if b > a else f"row {a + 1}"
        if self.lines is not None and self.lines[a] > 0:
            text += f" (lines {self.lines[a]}-{self.lines[b]}" if b > a else f" (line {self.lines[a]}"
            text += f", t = {self.time[a]:.6g}-{self.time[b]:.6g} s)"
        else:
            text += f" (t = {self.time[a]:.6g}-{self.time[b]:.6g} s)"
        return text


def read_trailer(path, rig) -> TrailerRun:
    """Read a friction trailer's raw channels (see the module docstring for the columns and the checks).

    Parameters
    ----------
    path : str or path-like
        The CSV file.
    rig : dict or Rig
        The rig (``{"tires": [...]}`` or :func:`~validation.rigs.load_rig`): it decides the channels required
        and the normal-load check.

    Returns
    -------
    TrailerRun

    Raises
    ------
    InputError
        A missing file or channel, a bad value: the message names the file, the line, the data row and the
        column.
    """
    rig = rig_from_dict(rig)
    path = Path(path)
    if not path.is_file():
        raise InputError(f"trailer file {path} does not exist")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"{path}: not a UTF-8 text file ({exc})") from None
    header, header_line, data, lines = _split(text)
    if header is None:
        raise InputError(f"{path}: no header row; expected columns {', '.join(tire_columns(rig, 1))}, ...")
    dup = sorted({h for h in header if h and header.count(h) > 1})
    if dup:
        raise InputError(f"{path}, line {header_line}: column(s) {dup} appear more than once in the header")
    _require(header, rig, f"{path}, line {header_line}")
    if not data:
        raise InputError(f"{path}: no data rows below the header (line {header_line})")
    wanted = _wanted(dict.fromkeys(header), rig)
    idx = [header.index(c) for c in wanted]
    values = _parse(data, lines, idx, wanted, len(header), str(path))
    cols = {name: values[:, j].copy() for j, name in enumerate(wanted)}
    return _checked(cols, rig, str(path), lines, header_line=header_line)


def tire_columns(rig, k: int) -> tuple[str, ...]:
    """Required columns of tire ``k`` (1-based) of ``rig``: the four load cells and, without a fixed slip, omega."""
    tire = rig_from_dict(rig).tire(k)
    cols = tuple(c.format(k=k) for c in FORCE_COLUMNS)
    return cols if tire.slip is not None else cols + (_OMEGA.format(k=k),)


# ==========================================================================================================
def _split(text: str):
    header = None
    header_line = 0
    data: list[str] = []
    lines: list[int] = []
    for lineno, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#") or not stripped.strip(","):
            continue
        if header is None:
            header = [c.strip() for c in next(csv.reader([line]))]
            header_line = lineno
        else:
            data.append(line)
            lines.append(lineno)
    return header, header_line, data, np.asarray(lines, dtype=int)


def _wanted(available: dict, rig: Rig) -> list[str]:
    names = list(_TOP) + [c for c in _OPTIONAL_TOP if c in available]
    for k in range(1, rig.n_tires + 1):
        names += [c for c in tire_columns(rig, k)]
        if rig.tire(k).slip is not None and _OMEGA.format(k=k) in available:
            names.append(_OMEGA.format(k=k))
        names += [c.format(k=k) for c in CHAIN_COLUMNS if c.format(k=k) in available]
    return names


def _require(header, rig: Rig, where: str) -> None:
    cols = set(header)
    missing = [c for c in _TOP if c not in cols]
    for k in range(1, rig.n_tires + 1):
        missing += [c for c in tire_columns(rig, k) if c not in cols]
    if missing:
        hints = []
        lower = {h.lower().replace(" ", ""): h for h in header}
        for m in missing:
            close = _close(m, list(lower))
            if close:
                hints.append(f"{lower[close]!r} for {m!r}")
        hint = f" (found {', '.join(hints)}: columns must be named exactly, with the unit)" if hints else ""
        raise InputError(f"{where}: missing column(s) {', '.join(repr(m) for m in missing)}{hint}; the rig has "
                         f"{rig.n_tires} tire(s): each needs {', '.join(FORCE_COLUMNS)} and {_OMEGA} (unless its "
                         f"rig entry gives a fixed slip), plus t_s and v_m_s")
    for k in range(1, rig.n_tires + 1):
        chain = [c.format(k=k) for c in CHAIN_COLUMNS]
        have = [c for c in chain if c in cols]
        if have and len(have) != len(chain):
            raise InputError(f"{where}: tire {k} has chain channel(s) {have} but not "
                             f"{[c for c in chain if c not in cols]}: give all of {chain} or none")
    extra = sorted({int(h.split("_")[1]) for h in header if _tire_of(h) is not None and _tire_of(h) > rig.n_tires})
    if extra:
        raise InputError(f"{where}: the file has channels of tire(s) {extra} but the rig describes "
                         f"{rig.n_tires} tire(s): add them to the rig (one [[rig.tires]] table each)")


def _tire_of(name: str):
    parts = name.split("_")
    if len(parts) >= 3 and parts[0] in ("fxl", "fxr", "fzl", "fzr", "omega", "fcu", "fcd", "theta") \
            and parts[1].isdigit():
        return int(parts[1])
    return None


def _close(name: str, candidates) -> str | None:
    import difflib

    match = difflib.get_close_matches(name.lower(), candidates, n=1, cutoff=0.75)
    return match[0] if match else None


def _parse(data: list[str], lines: np.ndarray, idx: list[int], names: list[str], n_header: int,
           source: str) -> np.ndarray:
    """The wanted columns as floats: one fast C parse; on failure a scan that names the bad cell."""
    try:
        values = np.loadtxt(data, delimiter=",", usecols=idx, ndmin=2, dtype=float, comments=None)
        if values.shape == (len(data), len(idx)) and np.all(np.isfinite(values)):
            return values
    except ValueError:
        pass
    out = np.empty((len(data), len(idx)))
    for i, line in enumerate(data):
        cells = [c.strip() for c in line.split(",")]
        for j, (col, name) in enumerate(zip(idx, names)):
            cell = cells[col] if col < len(cells) else ""
            try:
                x = float(cell)
            except ValueError:
                got = repr(cell) if cell else "an empty cell"
                extra = f" (the row has {len(cells)} cells, the header {n_header})" if col >= len(cells) else ""
                raise InputError(f"{_where(source, lines, i, name)}: expected a number, got {got}{extra}") from None
            if not math.isfinite(x):
                raise InputError(f"{_where(source, lines, i, name)}: expected a finite number, got {cell!r}")
            out[i, j] = x
    return out


def _checked(cols: dict, rig: Rig, source: str, lines, *, header_line: int) -> TrailerRun:
    """Check the channels (see the module docstring); returns the frozen run."""
    n = cols["t_s"].size
    if n < 2:
        raise InputError(f"{source}: {n} sample(s); a run needs at least two")
    if lines is not None:
        lines = np.asarray(lines, dtype=int)
    for name, a in cols.items():
        bad = ~np.isfinite(a)
        if np.any(bad):
            i = int(np.argmax(bad))
            raise InputError(f"{_where(source, lines, i, name)}: expected a finite number, got {a[i]!r}")
    # --- zero rows
    if "zero" in cols:
        z = cols["zero"]
        bad = (z != 0) & (z != 1)
        if np.any(bad):
            i = int(np.argmax(bad))
            raise InputError(f"{_where(source, lines, i, 'zero')}: expected 0 (measured row) or 1 (tires off the "
                             f"road: load-cell offsets), got {z[i]:g}")
    else:
        cols["zero"] = np.zeros(n)
    measured = cols["zero"] < 0.5
    if not np.any(measured):
        raise InputError(f"{source}: every row is a zero row (column 'zero' = 1): nothing was measured")
    # --- time
    t = cols["t_s"]
    dt = np.diff(t)
    if np.any(dt <= 0):
        i = int(np.argmax(dt <= 0)) + 1
        raise InputError(f"{_where(source, lines, i, 't_s')}: time {t[i]:.9g} s does not come after the previous "
                         f"row's {t[i - 1]:.9g} s; time must increase from row to row")
    # --- speed
    v = cols["v_m_s"]
    bad = (measured & (v <= 0)) | (v < 0)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise InputError(f"{_where(source, lines, i, 'v_m_s')}: vehicle speed {v[i]:g} m/s on a measured row; the "
                         "slip (V - omega r)/V and the running position need a moving trailer: cut the standing "
                         "part or mark it as a zero row (column 'zero' = 1, tires off the road)")
    if np.any(v > _MAX_SPEED):
        i = int(np.argmax(v > _MAX_SPEED))
        raise InputError(f"{_where(source, lines, i, 'v_m_s')}: {v[i]:g} m/s ({v[i] * 3.6:g} km/h) is beyond a "
                         "friction trailer; the column looks like km/h: convert to m/s")
    if "x_m" in cols:
        dx = np.diff(cols["x_m"])
        if np.any(dx < 0):
            i = int(np.argmax(dx < 0)) + 1
            raise InputError(f"{_where(source, lines, i, 'x_m')}: distance {cols['x_m'][i]:g} m is less than the "
                             f"previous row's {cols['x_m'][i - 1]:g} m; the distance travelled cannot decrease")
    # --- per tire: normal load (Eq. 9) and wheel speed
    for k in range(1, rig.n_tires + 1):
        tire = rig.tire(k)
        fzl, fzr = cols[f"fzl_{k}_N"], cols[f"fzr_{k}_N"]
        N = normal_load(fzl, fzr, tire)
        bad = measured & (N <= 0)
        if np.any(bad):
            i = int(np.argmax(bad))
            raise InputError(f"{_where(source, lines, i, f'fzl_{k}_N')} and 'fzr_{k}_N': normal load of tire {k} "
                             f"(Eq. 9: (1 + l_L/l_s) F_zL + (1 - l_R/l_s) F_zR + m g) is {N[i]:.6g} N from "
                             f"F_zL = {fzl[i]:g} N, F_zR = {fzr[i]:g} N; a load must be > 0: check the cells' sign "
                             f"(compression positive), their unit (N) and the rig's lever arms")
        if f"theta_{k}_deg" in cols:
            th = cols[f"theta_{k}_deg"]
            if np.any(np.abs(th) > 90):
                i = int(np.argmax(np.abs(th) > 90))
                raise InputError(f"{_where(source, lines, i, f'theta_{k}_deg')}: chain angle {th[i]:g} deg; "
                                 "expected degrees from the horizontal, within +-90")
        name = f"omega_{k}_rad_s"
        if name not in cols:
            continue
        w = cols[name]
        if np.any(w < 0):
            i = int(np.argmax(w < 0))
            raise InputError(f"{_where(source, lines, i, name)}: wheel speed {w[i]:g} rad/s; expected >= 0 (a "
                             "braked wheel turns forwards; flip the channel's sign if it counts backwards)")
        ratio = float(np.median(w[measured] * tire.wheel_radius_m / v[measured]))
        for factor, unit in ((60.0 / (2 * math.pi), "rpm"), (180.0 / math.pi, "deg/s")):
            if abs(ratio / factor - 1.0) < 0.25:
                raise InputError(f"{source}: column {name!r}: the median rolling speed omega r is {ratio:.3g} times "
                                 f"the vehicle speed, as if omega were in {unit}: give rad/s (and check "
                                 f"wheel_radius_m = {tire.wheel_radius_m:g} m)")
        if not -0.5 < 1.0 - ratio <= 1.0:
            raise InputError(f"{source}: column {name!r}: the median slip 1 - omega r / V is {1.0 - ratio:.3g}; "
                             f"expected a braking slip in 0-1: check the unit (rad/s), the wheel radius "
                             f"(wheel_radius_m = {tire.wheel_radius_m:g} m) and the speed column (m/s)")
    for a in cols.values():
        a.setflags(write=False)
    if lines is not None:
        lines.setflags(write=False)
    return TrailerRun(columns=cols, n_tires=rig.n_tires, source=source, lines=lines)


def _where(source: str, lines, i: int, column: str | None) -> str:
    col = f", column {column!r}" if column else ""
    line = int(lines[i]) if lines is not None and i < len(lines) else 0
    if line > 0:
        return f"{source}, line {line} (data row {i + 1}){col}"
    return f"{source}, row {i + 1}{col}"
