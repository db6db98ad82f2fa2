"""Measured friction (DRFT-style): reading, checking and holding the rows.

Format (``docs/conventions.md``, "Files"): a CSV with a header row; lines starting with ``#`` are comments. Columns
``slip, speed_m_s, T_C, pressure_Pa, mu`` are required; ``mu_std`` (standard deviation of mu, e.g. from
repeats), ``wet`` (0/1, also true/false/yes/no), ``series`` (a free label, e.g. the name of a run) and
``position_m`` (where along a road the row was measured, m: rows reduced from a friction trailer) are
optional. ``speed_m_s`` is the rolling reference speed V; the sliding speed is ``slip * V``; ``slip = 1`` is
pure sliding. Other columns are ignored.

Road and tyre columns, optional, for the friction-speed laws of wet roads (:func:`persson.slip.fit_speed_laws`,
:mod:`persson.slip.texture_laws`): ``water_depth_m`` (water film, m), ``tread_depth_m`` (tyre tread depth, m; 0 for a
blank tyre), ``bpn`` (British Pendulum Number of the surface), ``mpd_m`` (mean profile depth, m) and ``device`` (a
label of the measuring device).

Checks (each failure raises :class:`~validation.InputError` naming the file, the line, the data row and the
column; values that merely look odd give a :class:`~validation.UnitWarning`):

* a missing required column, a non-number in a numeric column, NaN or infinity;
* ``slip`` outside (0, 1] (values in (1, 100] are said to look like percent);
* ``speed_m_s <= 0``; speeds above 150 m/s are refused as "looks like km/h or mm/s"; a largest speed above
  40 m/s (144 km/h, beyond rubber-friction testers) is warned about as "looks like km/h";
* ``T_C`` below -273.15 C is refused; temperatures that all lie in 200-450 are refused as "looks like kelvin";
  a temperature above 150 C is warned about;
* ``pressure_Pa <= 0``; pressures that all lie below 1000 Pa are refused as "looks like kPa, MPa or bar" (tread
  contact pressures are 1e4-1e7 Pa); a pressure below 1e4 Pa or above 1e8 Pa is warned about;
* ``mu < 0``; ``mu`` above 5 is warned about;
* ``mu_std <= 0`` or given on some rows and empty on others; ``wet`` not 0/1; ``position_m`` not a finite number;
* ``water_depth_m``, ``tread_depth_m`` < 0, ``mpd_m`` <= 0, any of them above 0.03 m (refused as "looks like mm": a
  water depth of 2 is 2 mm, not 2 m); ``bpn`` outside (0, 150], or all <= 1.5 (refused as "looks like BPN/100");
  these four given on some rows and empty on others;
* rows of a file that repeat another row exactly (same slip, speed, temperature, pressure, wet and mu) are
  warned about (:class:`DuplicateRowsWarning`, naming the lines): a copy-pasted block counts twice in every fit.
"""

from __future__ import annotations

import csv
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .errors import InputError, UnitWarning

__all__ = ["Measurements", "read_measurements", "REQUIRED_COLUMNS", "OPTIONAL_COLUMNS", "DuplicateRowsWarning"]

#: Columns every measurement file must have.
REQUIRED_COLUMNS = ("slip", "speed_m_s", "T_C", "pressure_Pa", "mu")
#: Columns a measurement file may have.
OPTIONAL_COLUMNS = ("mu_std", "wet", "series", "position_m", "water_depth_m", "tread_depth_m", "bpn", "mpd_m",
                    "device")
#: Optional numeric road and tyre columns -> attribute (water and tread depth, MPD in m; BPN).
ROAD_COLUMNS = {"water_depth_m": "water_depth", "tread_depth_m": "tread_depth", "bpn": "bpn", "mpd_m": "mpd"}

_TRUE = {"1", "1.0", "true", "yes", "y", "wet"}


class DuplicateRowsWarning(UserWarning):
    """Rows of a measurement file repeat other rows exactly (conditions and mu): likely pasted twice."""
_FALSE = {"0", "0.0", "false", "no", "n", "dry", ""}


@dataclass(frozen=True, eq=False)
class Measurements:
    """Measured friction coefficients, one entry per row (read-only arrays of equal length).

    Attributes
    ----------
    slip : ndarray
        Braking slip ratio s in (0, 1]; 1 is pure sliding.
    speed : ndarray
        Rolling reference speed V, m/s (the sliding speed is ``slip * speed``).
    temperature : ndarray
        Background temperature T0, deg C.
    pressure : ndarray
        Nominal pressure sigma0, Pa.
    mu : ndarray
        Measured friction coefficient.
    mu_std : ndarray or None
        Standard deviation of ``mu`` per row (None when the file has no ``mu_std`` column).
    wet : ndarray of bool
        Whether the row was measured wet.
    series : tuple of str
        Label per row ("" when the file has no ``series`` column).
    source : str
        Where the rows came from (file path or a description).
    lines : ndarray of int
        Line number of each row in the source file (1-based; 0 when built from arrays).
    contact : persson.slip.Contact or None
        The brush model of the test wheel, when known (set by :func:`validation.load_case` from the case's
        ``[contact]`` table); used for rows with slip < 1 when no contact is passed explicitly.
    position : ndarray or None
        Road position of each row, m (None when the file has no ``position_m`` column): rows reduced from a
        friction trailer's channels (:mod:`validation.rigs`).
    water_depth, tread_depth, mpd : ndarray or None
        Water depth, tyre tread depth (0: blank tyre) and mean profile depth per row, m (None without the column).
    bpn : ndarray or None
        British Pendulum Number per row.
    device : tuple of str
        Measuring device per row ("" without the column).
    """

    slip: np.ndarray
    speed: np.ndarray
    temperature: np.ndarray
    pressure: np.ndarray
    mu: np.ndarray
    mu_std: np.ndarray | None = None
    wet: np.ndarray | None = None
    series: tuple = ()
    source: str = "<arrays>"
    lines: np.ndarray | None = None
    contact: object = None
    position: np.ndarray | None = None
    _checked: bool = field(default=False, repr=False, compare=False)
    water_depth: np.ndarray | None = None
    tread_depth: np.ndarray | None = None
    bpn: np.ndarray | None = None
    mpd: np.ndarray | None = None
    device: tuple = ()

    def __post_init__(self):
        if self._checked:
            return
        checked = _check_arrays(
            {"slip": self.slip, "speed_m_s": self.speed, "T_C": self.temperature, "pressure_Pa": self.pressure,
             "mu": self.mu, "mu_std": self.mu_std, "wet": self.wet, "position_m": self.position,
             **{c: getattr(self, a) for c, a in ROAD_COLUMNS.items()}, "device": self.device},
            self.series, self.source, self.lines)
        for k, v in checked.items():
            object.__setattr__(self, k, v)

    # ------------------------------------------------------------------------------------------------------
    @classmethod
    def from_arrays(cls, *, slip, speed, temperature, pressure, mu, mu_std=None, wet=None, series=None,
                    source: str = "<arrays>", contact=None, position=None, water_depth=None, tread_depth=None,
                    bpn=None, mpd=None, device=None) -> "Measurements":
        """Measurements from arrays (scalars broadcast), with the same checks as :func:`read_measurements`."""
        names = ("slip", "speed", "temperature", "pressure", "mu")
        arrays = [_float_argument(a, name, source) for a, name in zip((slip, speed, temperature, pressure, mu), names)]
        try:
            arrays = [np.array(a) for a in np.broadcast_arrays(*arrays)]
        except ValueError:
            raise InputError(f"{source}: slip, speed, temperature, pressure and mu do not broadcast together "
                             f"(shapes {[a.shape for a in arrays]})") from None
        n = arrays[0].size
        arrays = [a.ravel() for a in arrays]

        def per_row(value, name):
            try:
                return np.broadcast_to(value, (n,)).copy()
            except ValueError:
                raise InputError(f"{source}: {name} has shape {np.shape(value)}; expected a scalar or one value per "
                                 f"row ({n} rows)") from None

        std = None if mu_std is None else per_row(_float_argument(mu_std, "mu_std", source), "mu_std")
        w = None if wet is None else per_row(np.asarray(wet), "wet")
        ser = () if series is None else tuple(str(s) for s in per_row(np.asarray(series, dtype=object), "series"))
        pos = None if position is None else per_row(_float_argument(position, "position_m", source), "position_m")
        road = {a: None if v is None else per_row(_float_argument(v, c, source), c)
                for (c, a), v in zip(ROAD_COLUMNS.items(), (water_depth, tread_depth, bpn, mpd))}
        dev = () if device is None else tuple(str(d) for d in per_row(np.asarray(device, dtype=object), "device"))
        return cls(slip=arrays[0], speed=arrays[1], temperature=arrays[2], pressure=arrays[3], mu=arrays[4],
                   mu_std=std, wet=w, series=ser, source=source, contact=contact, position=pos, **road, device=dev)

    @property
    def n(self) -> int:
        """Number of rows."""
        return int(self.mu.size)

    def __len__(self) -> int:
        return self.n

    @property
    def sliding_speed(self) -> np.ndarray:
        """Sliding speed v_s = slip * V, m/s."""
        return self.slip * self.speed

    @property
    def is_sliding(self) -> np.ndarray:
        """True for pure-sliding rows (slip == 1)."""
        return self.slip >= 1.0

    @property
    def has_slip_rows(self) -> bool:
        """Whether any row has slip < 1 (needs the brush model and a contact)."""
        return bool(np.any(self.slip < 1.0))

    @property
    def series_labels(self) -> tuple[str, ...]:
        """Distinct non-empty series labels, in order of appearance."""
        return tuple(dict.fromkeys(s for s in self.series if s))

    def row_label(self, i: int) -> str:
        """``'<source>, line L'`` (or ``'row i'``) of row ``i``, for messages."""
        line = int(self.lines[i]) if self.lines is not None else 0
        return f"{self.source}, line {line}" if line > 0 else f"{self.source}, row {i}"

    def subset(self, mask) -> "Measurements":
        """The rows selected by a boolean mask or an index array."""
        idx = np.arange(self.n)[np.asarray(mask)]
        if idx.size == 0:
            raise InputError(f"{self.source}: the selection is empty")
        return Measurements(
            slip=self.slip[idx], speed=self.speed[idx], temperature=self.temperature[idx],
            pressure=self.pressure[idx], mu=self.mu[idx],
            mu_std=None if self.mu_std is None else self.mu_std[idx], wet=self.wet[idx],
            series=tuple(self.series[i] for i in idx), source=self.source, lines=self.lines[idx],
            contact=self.contact, position=None if self.position is None else self.position[idx], _checked=True,
            **{a: None if getattr(self, a) is None else getattr(self, a)[idx] for a in ROAD_COLUMNS.values()},
            device=tuple(self.device[i] for i in idx) if self.device else ())

    def with_contact(self, contact) -> "Measurements":
        """A copy that carries ``contact`` (the brush model of the test wheel)."""
        import dataclasses

        return dataclasses.replace(self, contact=contact, _checked=True)

    def with_mu(self, mu, mu_std=None, source: str | None = None) -> "Measurements":
        """A copy with other friction values (e.g. synthetic data on the same conditions)."""
        return Measurements(slip=self.slip, speed=self.speed, temperature=self.temperature,
                            pressure=self.pressure, mu=np.asarray(mu, dtype=float), mu_std=mu_std, wet=self.wet,
                            series=self.series, source=self.source if source is None else source,
                            lines=self.lines, contact=self.contact, position=self.position,
                            **{a: getattr(self, a) for a in ROAD_COLUMNS.values()}, device=self.device)

    def as_table(self) -> dict[str, np.ndarray]:
        """Columns in the file format (``wet`` as 0/1; ``mu_std``, ``series`` and ``position_m`` only when present)."""
        cols = {"slip": self.slip, "speed_m_s": self.speed, "T_C": self.temperature,
                "pressure_Pa": self.pressure, "mu": self.mu}
        if self.mu_std is not None:
            cols["mu_std"] = self.mu_std
        cols["wet"] = self.wet.astype(int)
        if any(self.series):
            cols["series"] = np.asarray(self.series, dtype=object)
        if self.position is not None:
            cols["position_m"] = self.position
        for c, a in ROAD_COLUMNS.items():
            if getattr(self, a) is not None:
                cols[c] = getattr(self, a)
        if any(self.device):
            cols["device"] = np.asarray(self.device, dtype=object)
        return cols

    def to_csv(self, path, comments: tuple[str, ...] = (), *, overwrite: bool = False) -> Path:
        """Write the rows in the measurement format, atomically (complete or not at all); an existing file (the
        one they were read from included) only with ``overwrite=True``."""
        from persson.io import atomic_write, check_overwrite

        check_overwrite(path, overwrite=overwrite)
        cols = self.as_table()
        names = list(cols)
        with atomic_write(path, "w", newline="") as fh:
            for c in comments:
                for line in str(c).splitlines():
                    fh.write(f"# {line}\n")
            fh.write(",".join(names) + "\n")
            for i in range(self.n):
                cells = []
                for k in names:
                    v = cols[k][i]
                    if k in ("series", "device"):
                        cells.append(_csv_text(str(v)))
                    elif k == "wet":
                        cells.append(str(int(v)))
                    else:
                        cells.append(f"{float(v):.6g}" if k in ("mu", "mu_std") else f"{float(v):.10g}")
                fh.write(",".join(cells) + "\n")
        return Path(path)

    def __repr__(self) -> str:
        return f"Measurements({self.describe()}; source={self.source!r})"

    def describe(self) -> str:
        """One line: rows, slip rows, speed/temperature/pressure ranges, wet rows."""
        vs = self.sliding_speed
        parts = [f"{self.n} rows ({int(np.sum(self.is_sliding))} sliding, {int(np.sum(~self.is_sliding))} "
                 f"with slip < 1)",
                 f"sliding speed {vs.min():.3g}-{vs.max():.3g} m/s",
                 f"T {self.temperature.min():g}-{self.temperature.max():g} C",
                 f"pressure {self.pressure.min() / 1e6:g}-{self.pressure.max() / 1e6:g} MPa"]
        if np.any(self.wet):
            parts.append(f"{int(np.sum(self.wet))} wet")
        return ", ".join(parts)


# ==========================================================================================================
def read_measurements(path) -> Measurements:
    """Read a DRFT-style measurement CSV (see the module docstring for the columns and the checks).

    Parameters
    ----------
    path : str or path-like
        The CSV file.

    Returns
    -------
    Measurements

    Raises
    ------
    InputError
        A missing file or column, text in a numeric column, a value out of range: the message names the file,
        the line (and data row) and the column.

    Warns
    -----
    UnitWarning
        Values that look like another unit but are not impossible.
    """
    if not isinstance(path, (str, Path)):
        raise InputError(f"path: expected the measurements file's name, got {path!r}")
    path = Path(path)
    if not path.is_file():
        raise InputError(f"measurements file {path} does not exist")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(f"{path}: not a UTF-8 text file ({exc})") from None
    header: list[str] | None = None
    header_line = 0
    rows: list[tuple[int, list[str]]] = []
    for lineno, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        cells = [c.strip() for c in next(csv.reader([line]))]
        if not any(cells):  # a row of empty cells (",,,,": spreadsheet exports) is a blank line
            continue
        if header is None:
            header = cells
            header_line = lineno
        else:
            if len(cells) > len(header) and any(cells[len(header):]):
                raise InputError(f"{path}, line {lineno} (data row {len(rows) + 1}): {len(cells)} fields, but the "
                                 f"header (line {header_line}) has {len(header)} columns; a comma inside a value "
                                 "(e.g. a series name) must be quoted: \"sliding, 5 C\"")
            rows.append((lineno, cells))
    if header is None:
        raise InputError(f"{path}: no header row; expected columns {', '.join(REQUIRED_COLUMNS)}")
    dup = sorted({h for h in header if header.count(h) > 1 and h})
    if dup:
        raise InputError(f"{path}, line {header_line}: column(s) {dup} appear more than once in the header")
    missing = [c for c in REQUIRED_COLUMNS if c not in header]
    if missing:
        hint = ""
        lower = {h.lower(): h for h in header}
        for m in missing:
            for alt in (m.lower(), m.split("_")[0].lower()):
                if alt in lower and lower[alt] != m:
                    hint = f" (found {lower[alt]!r}; columns must be named exactly, with the unit: {m!r})"
                    break
        raise InputError(f"{path}, line {header_line}: missing column(s) {', '.join(repr(m) for m in missing)}"
                         f"{hint}; found {header}; expected {', '.join(REQUIRED_COLUMNS)} (+ optional "
                         f"{', '.join(OPTIONAL_COLUMNS)})")
    if not rows:
        raise InputError(f"{path}: no data rows below the header (line {header_line})")
    col = {name: header.index(name) for name in REQUIRED_COLUMNS + OPTIONAL_COLUMNS if name in header}
    n = len(rows)
    lines = np.array([ln for ln, _ in rows], dtype=int)
    values: dict[str, np.ndarray] = {}
    for name in REQUIRED_COLUMNS + ("mu_std", "position_m") + tuple(ROAD_COLUMNS):
        if name not in col:
            continue
        j = col[name]
        out = np.empty(n)
        for i, (lineno, cells) in enumerate(rows):
            cell = cells[j] if j < len(cells) else ""
            if cell == "" and name not in REQUIRED_COLUMNS:
                out[i] = np.nan
                continue
            try:
                out[i] = float(cell)
            except ValueError:
                got = repr(cell) if cell else "an empty cell"
                raise InputError(f"{path}, line {lineno} (data row {i + 1}), column {name!r}: expected a number, "
                                 f"got {got}") from None
        values[name] = out
    wet = np.zeros(n, dtype=bool)
    if "wet" in col:
        j = col["wet"]
        for i, (lineno, cells) in enumerate(rows):
            cell = (cells[j] if j < len(cells) else "").lower()
            if cell in _TRUE:
                wet[i] = True
            elif cell not in _FALSE:
                raise InputError(f"{path}, line {lineno} (data row {i + 1}), column 'wet': expected 0 or 1 "
                                 f"(or true/false), got {cell!r}")
    series = ()
    if "series" in col:
        j = col["series"]
        series = tuple((cells[j] if j < len(cells) else "") for _, cells in rows)
    device = ()
    if "device" in col:
        j = col["device"]
        device = tuple((cells[j] if j < len(cells) else "") for _, cells in rows)
    meas = Measurements(slip=values["slip"], speed=values["speed_m_s"], temperature=values["T_C"],
                        pressure=values["pressure_Pa"], mu=values["mu"], mu_std=values.get("mu_std"), wet=wet,
                        series=series, source=str(path), lines=lines, position=values.get("position_m"),
                        **{a: values.get(c) for c, a in ROAD_COLUMNS.items()}, device=device)
    _warn_duplicates(meas)
    return meas


def _warn_duplicates(meas: Measurements) -> None:
    """Warn about rows identical to an earlier row in conditions and mu, naming both lines."""
    rows = np.column_stack([meas.slip, meas.speed, meas.temperature, meas.pressure, meas.wet.astype(float),
                            meas.mu])
    _, first, inverse = np.unique(rows, axis=0, return_index=True, return_inverse=True)
    inverse = np.asarray(inverse).ravel()
    dup = np.flatnonzero(first[inverse] != np.arange(meas.n))
    if dup.size == 0:
        return
    pairs = [f"line {int(meas.lines[i])} = line {int(meas.lines[first[inverse[i]]])}" for i in dup[:5]]
    more = f" and {dup.size - 5} more" if dup.size > 5 else ""
    warnings.warn(f"{meas.source}: {dup.size} row(s) repeat an earlier row exactly (slip, speed, temperature, "
                  f"pressure, wet and mu): {'; '.join(pairs)}{more}. Duplicated rows count twice in every fit: "
                  "remove them unless they are genuine repeats", DuplicateRowsWarning, stacklevel=3)


# ==========================================================================================================
def _where(source: str, lines, i: int, column: str) -> str:
    line = int(lines[i]) if lines is not None and i < len(lines) else 0
    if line > 0:
        return f"{source}, line {line} (data row {i + 1}), column {column!r}"
    return f"{source}, row {i}, column {column!r}"


def _check_arrays(cols: dict, series, source: str, lines) -> dict:
    """Validate and freeze the columns; returns the attribute values."""
    n = None
    out = {}
    names = {"slip": "slip", "speed_m_s": "speed", "T_C": "temperature", "pressure_Pa": "pressure", "mu": "mu"}
    for col, attr in names.items():
        try:
            a = np.array(cols[col], dtype=float).ravel()
        except (TypeError, ValueError):
            raise InputError(f"{source}: column {col!r}: expected numbers") from None
        if n is None:
            n = a.size
        elif a.size != n:
            raise InputError(f"{source}: column {col!r} has {a.size} values, expected {n}")
        bad = ~np.isfinite(a)
        if np.any(bad):
            i = int(np.argmax(bad))
            raise InputError(f"{_where(source, lines, i, col)}: expected a finite number, got {a[i]!r}")
        out[attr] = a
    if n == 0:
        raise InputError(f"{source}: no rows")
    if lines is not None:
        lines = np.asarray(lines, dtype=int).ravel()
        if lines.size != n:
            lines = None
    # --- slip
    s = out["slip"]
    bad = (s <= 0) | (s > 1)
    if np.any(bad):
        i = int(np.argmax(bad))
        if np.all((s > 0) & (s <= 100)) and np.any(s > 1):
            raise InputError(f"{_where(source, lines, i, 'slip')}: slip = {s[i]:g} lies outside (0, 1]; the "
                             "column looks like percent: give the slip ratio (e.g. 0.05, not 5; 1 = pure sliding)")
        raise InputError(f"{_where(source, lines, i, 'slip')}: expected a slip ratio in (0, 1] (1 = pure "
                         f"sliding), got {s[i]:g}")
    # --- speed
    v = out["speed"]
    if np.any(v <= 0):
        i = int(np.argmax(v <= 0))
        raise InputError(f"{_where(source, lines, i, 'speed_m_s')}: expected a speed > 0 m/s, got {v[i]:g}")
    if np.any(v > 150.0):
        i = int(np.argmax(v > 150.0))
        raise InputError(f"{_where(source, lines, i, 'speed_m_s')}: {v[i]:g} m/s is beyond any rubber-friction "
                         "test; the column looks like km/h or mm/s: convert to m/s")
    if v.max() > 40.0:
        warnings.warn(f"{source}: column 'speed_m_s' reaches {v.max():g} m/s ({v.max() * 3.6:g} km/h); "
                      "check that it is not in km/h", UnitWarning, stacklevel=4)
    # --- temperature
    T = out["temperature"]
    if np.any(T < -273.15):
        i = int(np.argmax(T < -273.15))
        raise InputError(f"{_where(source, lines, i, 'T_C')}: {T[i]:g} C is below absolute zero")
    if np.all((T >= 200.0) & (T <= 450.0)):
        raise InputError(f"{_where(source, lines, 0, 'T_C')}: every temperature lies in 200-450: the column "
                         "looks like kelvin; give degrees Celsius (T_C = T_K - 273.15)")
    if np.any(T > 150.0):
        i = int(np.argmax(T > 150.0))
        warnings.warn(f"{_where(source, lines, i, 'T_C')}: {T[i]:g} C is hotter than tread compounds are tested; "
                      "check the unit (deg C expected)", UnitWarning, stacklevel=4)
    # --- pressure
    p = out["pressure"]
    if np.any(p <= 0):
        i = int(np.argmax(p <= 0))
        raise InputError(f"{_where(source, lines, i, 'pressure_Pa')}: expected a pressure > 0 Pa, got {p[i]:g}")
    if np.all(p < 1000.0):
        raise InputError(f"{_where(source, lines, 0, 'pressure_Pa')}: every pressure is below 1000 Pa (largest "
                         f"{p.max():g}); the column looks like kPa, MPa or bar: give Pa (0.3 MPa = 3e5 Pa)")
    if np.any(p < 1e4) or np.any(p > 1e8):
        i = int(np.argmax((p < 1e4) | (p > 1e8)))
        warnings.warn(f"{_where(source, lines, i, 'pressure_Pa')}: {p[i]:g} Pa is outside the usual 1e4-1e8 Pa of "
                      "rubber friction tests; check the unit (Pa expected)", UnitWarning, stacklevel=4)
    # --- mu
    mu = out["mu"]
    if np.any(mu < 0):
        i = int(np.argmax(mu < 0))
        raise InputError(f"{_where(source, lines, i, 'mu')}: expected a friction coefficient >= 0, got {mu[i]:g}")
    if np.any(mu > 5.0):
        i = int(np.argmax(mu > 5.0))
        warnings.warn(f"{_where(source, lines, i, 'mu')}: mu = {mu[i]:g} is unusually large; check the column "
                      "(a force in N instead of a coefficient?)", UnitWarning, stacklevel=4)
    # --- mu_std
    std = cols.get("mu_std")
    if std is not None:
        std = np.array(std, dtype=float).ravel()
        if std.size != n:
            raise InputError(f"{source}: column 'mu_std' has {std.size} values, expected {n}")
        nan = np.isnan(std)
        if np.all(nan):
            std = None
        else:
            if np.any(nan):
                i = int(np.argmax(nan))
                raise InputError(f"{_where(source, lines, i, 'mu_std')}: empty; give mu_std on every row or on "
                                 "none")
            bad = ~np.isfinite(std) | (std <= 0)
            if np.any(bad):
                i = int(np.argmax(bad))
                raise InputError(f"{_where(source, lines, i, 'mu_std')}: expected a standard deviation > 0, got "
                                 f"{std[i]:g}")
    out["mu_std"] = std
    # --- position (optional; any finite number: a road position may be negative)
    pos = cols.get("position_m")
    if pos is not None:
        try:
            pos = np.array(pos, dtype=float).ravel()
        except (TypeError, ValueError):
            raise InputError(f"{source}: column 'position_m': expected numbers") from None
        if pos.size != n:
            raise InputError(f"{source}: column 'position_m' has {pos.size} values, expected {n}")
        bad = ~np.isfinite(pos)
        if np.any(bad):
            i = int(np.argmax(bad))
            raise InputError(f"{_where(source, lines, i, 'position_m')}: expected a finite road position in m, "
                             f"got {pos[i]!r}")
    out["position"] = pos
    # --- wet
    w = cols.get("wet")
    if w is None:
        w = np.zeros(n, dtype=bool)
    else:
        w = np.asarray(w).ravel()
        if w.size != n:
            raise InputError(f"{source}: column 'wet' has {w.size} values, expected {n}")
        if w.dtype != bool:
            wf = np.empty(n)
            for i, x in enumerate(w.tolist()):  # numbers 0/1, or the reader's words (true/false, yes/no, ...)
                key = x.strip().lower() if isinstance(x, str) else None
                if key in _TRUE or key in _FALSE:
                    wf[i] = float(key in _TRUE)
                    continue
                try:
                    wf[i] = float(x)
                except (TypeError, ValueError):
                    wf[i] = np.nan
                if wf[i] not in (0.0, 1.0):
                    raise InputError(f"{_where(source, lines, i, 'wet')}: expected 0 or 1 (or true/false), got {x!r}")
            w = wf == 1.0
    out["wet"] = w
    ser = tuple(str(x) for x in series) if series else ()
    if ser and len(ser) != n:
        raise InputError(f"{source}: column 'series' has {len(ser)} values, expected {n}")
    out["series"] = ser or ("",) * n
    out["lines"] = lines if lines is not None else np.zeros(n, dtype=int)
    out.update(_check_road_columns(cols, source, lines, n))
    for k in ("slip", "speed", "temperature", "pressure", "mu", "mu_std", "wet", "lines", "position",
              *ROAD_COLUMNS.values()):
        if out.get(k) is not None:
            out[k].setflags(write=False)
    return out


def _check_road_columns(cols: dict, source: str, lines, n: int) -> dict:
    """The optional road and tyre columns: depths in m (above 0.03 m looks like mm), BPN in (0, 150]."""
    out = {}
    for col, attr in ROAD_COLUMNS.items():
        a = cols.get(col)
        if a is None:
            out[attr] = None
            continue
        a = np.array(a, dtype=float).ravel()
        if a.size != n:
            raise InputError(f"{source}: column {col!r} has {a.size} values, expected {n}")
        nan = np.isnan(a)
        if np.all(nan):
            out[attr] = None
            continue
        if np.any(~np.isfinite(a)):
            i = int(np.argmax(~np.isfinite(a)))
            what = "empty" if nan[i] else f"{a[i]!r}"
            raise InputError(f"{_where(source, lines, i, col)}: {what}; give {col} on every row (a finite number) "
                             "or on none")
        if col == "bpn":
            bad = (a <= 0) | (a > 150)
            if np.any(bad):
                i = int(np.argmax(bad))
                raise InputError(f"{_where(source, lines, i, col)}: expected a British Pendulum Number in (0, 150], "
                                 f"got {a[i]:g}")
            if np.all(a <= 1.5):
                raise InputError(f"{_where(source, lines, 0, col)}: every value is <= 1.5: the column looks like "
                                 "BPN/100 or a friction coefficient; give the pendulum reading (e.g. 65)")
        else:
            bad = (a <= 0) if col == "mpd_m" else (a < 0)
            if np.any(bad):
                i = int(np.argmax(bad))
                raise InputError(f"{_where(source, lines, i, col)}: expected a depth {'>' if col == 'mpd_m' else '>='}"
                                 f" 0 m, got {a[i]:g}")
            if np.any(a > 0.03):
                i = int(np.argmax(a > 0.03))
                raise InputError(f"{_where(source, lines, i, col)}: {a[i]:g} m is more than 30 mm, deeper than any "
                                 f"road texture, tread or wet-road water film: the column looks like millimetres; "
                                 f"give metres ({a[i]:g} mm = {a[i] * 1e-3:g} m)")
        out[attr] = a
    dev = cols.get("device")
    dev = tuple(str(d) for d in dev) if dev is not None and len(dev) else ()
    if dev and len(dev) != n:
        raise InputError(f"{source}: column 'device' has {len(dev)} values, expected {n}")
    out["device"] = dev
    return out


def _float_argument(value, name: str, source: str) -> np.ndarray:
    """``value`` as a 1D-or-more float array, or InputError naming the argument and the offending entry."""
    try:
        return np.atleast_1d(np.asarray(value, dtype=float))
    except (TypeError, ValueError):
        pass
    flat = np.atleast_1d(np.asarray(value, dtype=object)).ravel()
    for i, x in enumerate(flat):
        try:
            float(x)
        except (TypeError, ValueError):
            raise InputError(f"{source}, row {i}, column {name!r}: expected a number, got {x!r}") from None
    raise InputError(f"{source}: column {name!r}: expected numbers, got {value!r}")


def _csv_text(s: str) -> str:
    if any(c in s for c in ',"\n\r'):
        return '"' + s.replace('"', '""') + '"'
    return s
