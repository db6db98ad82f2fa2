"""Readers: profile CSV (``docs/conventions.md``), CAPTIF road-profiler text exports, plain arrays, 2D height maps.

Units are always explicit: CSV columns carry them in their names (``x_mm``, ``z1_um``), instrument exports
in their column headers (``Distance (mm)``), arrays and images through arguments. Everything is converted
to metres. Bad input raises :class:`surfaces.InputError` naming the file, column and line.
"""

from __future__ import annotations

import io
import math
import re
import warnings
from pathlib import Path

import numpy as np

from ._util import positive, unit_factor
from .errors import InputError, UnitWarning
from .maps import HeightMap
from .profiles import Profile, ProfileSet

__all__ = ["read_profiles", "read_profiles_csv", "read_captif", "profiles_from_array", "read_height_map"]

_CSV_COLUMN = re.compile(r"^(?P<axis>x|z\d*)_(?P<unit>.+)$")
_CAPTIF_MARKER = "*****DATA*****"
_CAPTIF_COLUMN = re.compile(r"^(?P<name>Distance|Depth)\s*\((?P<unit>[^)]*)\)$")
_NAN_TOKENS = ("", "nan", "NaN", "NAN", "na", "NA")


def read_profiles(path, format: str = "auto", **options) -> ProfileSet:
    """Read line profiles from a file (or several files) into a :class:`ProfileSet`.

    Parameters
    ----------
    path : str, path-like, or sequence of them
        One file, or several files of the same surface (their profiles are pooled).
    format : {"auto", "csv", "captif"}
        "csv": the profile CSV of ``docs/conventions.md`` (:func:`read_profiles_csv`); "captif": the tab-separated CAPTIF
        road-profiler export (:func:`read_captif`); "auto" recognizes a CAPTIF export by its
        ``*****DATA*****`` line and reads anything else as CSV.
    **options
        Passed to the reader (e.g. ``trim_plates=False`` for CAPTIF, ``delimiter=";"`` for CSV).

    Returns
    -------
    ProfileSet
    """
    if isinstance(path, (list, tuple)):
        return ProfileSet.concatenate([read_profiles(p, format=format, **options) for p in path])
    if not isinstance(path, (str, Path)):
        raise InputError(f"path: expected a profile file name (or a list of them), got {path!r}")
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: file not found")
    if format == "auto":
        format = "captif" if _looks_like_captif(path) else "csv"
    if format == "csv":
        return read_profiles_csv(path, **options)
    if format == "captif":
        return read_captif(path, **options)
    raise InputError(f"format: expected 'auto', 'csv' or 'captif', got {format!r}")


def read_profiles_csv(path, delimiter: str = ",") -> ProfileSet:
    """Read the profile CSV (``docs/conventions.md``, "Files").

    One column ``x_<unit>`` and one or more ``z_<unit>`` / ``z1_<unit>``, ``z2_<unit>``... (parallel scans
    sharing x); unit in {m, mm, um}. Lines starting with ``#`` are comments. Empty cells or ``NaN`` are
    dropouts. Other columns are ignored.

    The numbers are parsed in blocks by numpy's C reader (about 10 s and 0.5 GB for 1e7 rows); a block that
    does not parse cleanly is read again line by line to name the offending line and column.

    Raises
    ------
    InputError
        Empty file, no data rows, missing x or z column, unknown unit, non-numeric cell, x missing or not
        strictly increasing, a profile with no valid sample. The message names file, column and line.
    """
    path = Path(path)
    with open(path, encoding="utf-8-sig", errors="replace") as fh:  # -sig: a byte-order mark is no column name
        header, header_line = _csv_header(fh, path, delimiter)
        x_cols, z_cols = [], []
        for j, name in enumerate(header):
            m = _CSV_COLUMN.match(name)
            if not m:
                continue
            factor = unit_factor(m["unit"], f"{path}, column {name}")
            (x_cols if m["axis"] == "x" else z_cols).append((j, name, factor))
        if len(x_cols) != 1 or not z_cols:
            raise InputError(f"{path}, line {header_line}: expected one x_<unit> column and at least one z_<unit> "
                             f"(or z1_<unit>, z2_<unit>...) column, unit in m/mm/um; found columns {header}")
        cols = [x_cols[0]] + z_cols
        data = _numeric_body(fh, path, header_line + 1, delimiter, [j for j, _, _ in cols],
                             [name for _, name, _ in cols], len(header))
    if data.shape[0] == 0:
        raise InputError(f"{path}: no data rows after the header (line {header_line})")
    jx, xname, fx = x_cols[0]
    x = data[:, 0] * fx
    if np.isnan(x).any():
        i = int(np.argmax(np.isnan(x)))
        raise InputError(f"{path}, line {_data_line(path, header_line, i)}, column {xname}: x is missing; every "
                         "row needs a position")
    bad = np.flatnonzero(np.diff(x) <= 0)
    if bad.size:
        i = bad[0] + 1
        raise InputError(f"{path}, line {_data_line(path, header_line, i)}, column {xname}: x must be strictly "
                         f"increasing ({data[i, 0]:g} follows {data[i - 1, 0]:g})")
    profiles = []
    for k, (j, name, fz) in enumerate(z_cols, start=1):
        z = data[:, k] * fz
        _check_road_heights(x, z, f"{path}, column {name}", m_unit=name.split("_", 1)[1])
        profiles.append(Profile(x, z, name=name, source=str(path)))
    return ProfileSet(tuple(profiles), source=str(path))


def read_captif(path, trim_plates: bool = True, plate_threshold: float = 30e-3, plate_buffer: float = 2e-3,
                invert: bool = False) -> ProfileSet:
    """Read a CAPTIF road-profiler text export (tab-separated).

    Layout: a header block of ``key<TAB>value`` lines ending with a ``*****DATA*****`` line, then the column
    names ``Data Point No:``, ``Distance (mm)``, ``Depth (mm)``, then one sample per line; dropouts are
    ``NaN``. ``Depth`` is read as the relative height (as captif-slp does), in the unit of its header.

    Parameters
    ----------
    path : str or path-like
    trim_plates : bool
        CAPTIF scans start and end on reference plates standing well above the road (about 47 mm). When
        True (default) the profile is cut to the road between them: from ``plate_buffer`` after the last
        plate sample of the first half to ``plate_buffer`` before the first plate sample of the second half
        (captif-slp's ``detect_plates``). The raw dropout fraction is kept in ``meta``.
    plate_threshold : float
        Height (m) above which a sample belongs to a plate.
    plate_buffer : float
        Margin (m) kept clear of the plate edges.
    invert : bool
        Use ``-Depth`` as height (for exports where depth grows downwards).

    Returns
    -------
    ProfileSet
        One profile named ``Depth (mm)``; ``meta`` holds the header fields, ``raw_dropout_fraction`` and the
        trimmed range ``x_start_m``/``x_end_m``.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: file not found")
    with open(path, encoding="latin-1") as fh:
        meta, names, i_cols = _captif_header(fh, path)
        found = {}
        for j, name in enumerate(names):
            m = _CAPTIF_COLUMN.match(name)
            if m:
                found[m["name"]] = (j, name, unit_factor(m["unit"].strip(), f"{path}, column {name!r}"))
        for need in ("Distance", "Depth"):
            if need not in found:
                raise InputError(f"{path}, line {i_cols + 1}: missing column '{need} (<unit>)'; found {names}")
        (jx, xname, fx), (jz, zname, fz) = found["Distance"], found["Depth"]
        data = _numeric_body(fh, path, i_cols + 2, "\t", [jx, jz], [xname, zname], None, quote_names=True)
    if data.shape[0] == 0:
        raise InputError(f"{path}: no data rows after the column header (line {i_cols + 1})")
    x, z = data[:, 0] * fx, data[:, 1] * fz
    if invert:
        z = -z
    if np.isnan(x).any():
        i = int(np.argmax(np.isnan(x)))
        raise InputError(f"{path}, line {_data_line(path, i_cols + 1, i, 'latin-1')}, column {xname!r}: distance "
                         "is missing")
    meta["raw_dropout_fraction"] = float(np.isnan(z).mean())
    where = f"{path}, column {zname!r}"
    if np.isnan(z).all():
        raise InputError(f"{where}: all values are missing (NaN); expected depths")
    bad = np.flatnonzero(np.diff(x) <= 0)
    if bad.size:
        raise InputError(f"{path}, line {_data_line(path, i_cols + 1, bad[0] + 1, 'latin-1')}, column {xname!r}: "
                         "distance must be strictly increasing")
    if trim_plates:
        lo, hi = _plate_limits(x, z, positive(plate_threshold, "plate_threshold"), float(plate_buffer))
        keep = (x >= lo) & (x < hi)
        if keep.sum() < 2:
            raise InputError(f"{where}: nothing left between the reference plates ({lo:g} m to {hi:g} m)")
        meta["x_start_m"], meta["x_end_m"] = float(x[keep][0]), float(x[keep][-1])
        x, z = x[keep], z[keep]
    profile = Profile(x, z, name=zname, source=str(path))
    return ProfileSet((profile,), source=str(path), meta=meta)


def profiles_from_array(z, *, dx: float | None = None, x=None, z_unit: str = "m", x_unit: str = "m",
                        names=None, periodic: bool = False, source: str = "array") -> ProfileSet:
    """Profiles from plain arrays.

    Parameters
    ----------
    z : array_like, shape (n,) or (n_profiles, n)
        Heights in ``z_unit``; NaN = dropout.
    dx : float, optional
        Spacing in ``x_unit`` (give ``dx`` or ``x``).
    x : array_like, optional
        Positions in ``x_unit``, strictly increasing, shared by all profiles.
    z_unit, x_unit : {"m", "mm", "um"}
    names : sequence of str, optional
        Profile names (default ``z1``, ``z2``...).
    periodic : bool
        True for periodic data (no window, mean detrend in :meth:`ProfileSet.psd`).
    source : str
        Label used in messages.
    """
    arr = np.atleast_2d(np.asarray(z, dtype=float))
    if arr.ndim != 2 or arr.shape[1] < 2:
        raise InputError(f"{source}: z: expected shape (n,) or (n_profiles, n) with n >= 2, got {np.shape(z)}")
    fz = unit_factor(z_unit, "z_unit")
    fx = unit_factor(x_unit, "x_unit")
    if (dx is None) == (x is None):
        raise InputError(f"{source}: give exactly one of dx= and x= (in x_unit = {x_unit!r})")
    if x is None:
        xs = positive(dx, "dx") * fx * np.arange(arr.shape[1])
    else:
        xs = np.asarray(x, dtype=float) * fx
        if xs.shape != (arr.shape[1],):
            raise InputError(f"{source}: x has shape {xs.shape}, expected ({arr.shape[1]},) like the rows of z")
    names = [f"z{i + 1}" for i in range(arr.shape[0])] if names is None else list(names)
    if len(names) != arr.shape[0]:
        raise InputError(f"{source}: {len(names)} names for {arr.shape[0]} profiles")
    return ProfileSet(tuple(Profile(xs, row * fz, name=str(nm), source=source, periodic=periodic)
                            for nm, row in zip(names, arr)), source=source)


def read_height_map(path, *, dx: float, dy: float | None = None, unit: str | None = None,
                    height_scale: float | None = None, offset: float = 0.0, periodic: bool = False) -> HeightMap:
    """Read a 2D height map: ``.npy`` (numbers) or a grayscale TIFF/PNG (8- or 16-bit, via scikit-image).

    Heights are ``(value - offset) * scale`` with scale from ``unit`` (``.npy`` in m/mm/um) or
    ``height_scale`` (metres per stored unit, e.g. per gray level). Images need ``height_scale``: a gray
    level has no unit.

    Parameters
    ----------
    path : str or path-like
    dx : float
        Pixel spacing along x, m.
    dy : float, optional
        Pixel spacing along y, m (default ``dx``).
    unit : {"m", "mm", "um"}, optional
        Unit of the values of a ``.npy`` file.
    height_scale : float, optional
        Metres per stored unit (required for images; alternative to ``unit`` for ``.npy``).
    offset : float
        Stored value of zero height (e.g. 32768 for some 16-bit exports).
    periodic : bool
        True if the map is periodic.

    Returns
    -------
    HeightMap
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: file not found")
    suffix = path.suffix.lower()
    if suffix == ".npy":
        try:
            raw = np.load(path, allow_pickle=False)
        except ValueError as exc:
            raise InputError(f"{path}: not a plain numeric .npy array ({exc})") from None
        if (unit is None) == (height_scale is None):
            raise InputError(f"{path}: give exactly one of unit= ('m', 'mm', 'um') and height_scale= (m per value)")
        scale = unit_factor(unit, f"{path}: unit") if unit is not None else positive(height_scale, "height_scale")
    elif suffix in (".tif", ".tiff", ".png"):
        from skimage import io as skio  # optional heavy import, only for images

        try:
            raw = skio.imread(path)
        except Exception as exc:  # noqa: BLE001 - any decoder failure is bad input
            raise InputError(f"{path}: cannot read the image ({exc})") from None
        if raw.ndim != 2:
            raise InputError(f"{path}: expected a single-channel (grayscale) height image, got shape {raw.shape}")
        if height_scale is None:
            raise InputError(f"{path}: height_scale= (metres per gray level) is required for images")
        if unit is not None:
            raise InputError(f"{path}: images take height_scale= (m per gray level), not unit=")
        scale = positive(height_scale, "height_scale")
    else:
        raise InputError(f"{path}: unknown height-map format {suffix!r}; expected .npy, .tif, .tiff or .png")
    if raw.dtype.kind not in "uif":
        raise InputError(f"{path}: expected numeric heights, got dtype {raw.dtype}")
    z = (raw.astype(float) - float(offset)) * scale
    return HeightMap(z, dx=positive(dx, "dx"), dy=dy, periodic=periodic, source=str(path))


# ---------------------------------------------------------------------- helpers


#: A profile this long (m) is a road or pavement scan, whose rms height is 0.05-5 mm; below 1 um (or above 5 cm) the
#: heights are in another unit than the column says.
_ROAD_SPAN_M = 0.05
_ROAD_HRMS_M = (1.0e-6, 0.05)


def _check_road_heights(x, z, where: str, m_unit: str) -> None:
    """UnitWarning when a road-length profile has heights no road has (mm read as um, um read as mm)."""
    ok = np.isfinite(z)
    if ok.sum() < 3 or x[-1] - x[0] < _ROAD_SPAN_M:
        return
    h = float(np.std(z[ok]))
    lo, hi = _ROAD_HRMS_M
    if 0 < h < lo or h > hi:
        what = "below a micrometre" if h < lo else "above 5 cm"
        warnings.warn(f"{where}: a profile {x[-1] - x[0]:.3g} m long with an rms height of {h:.3g} m "
                      f"({what}); road and pavement textures are 0.05-5 mm rms: are the heights really in "
                      f"{m_unit}? Name the column with the unit they are in (z_m, z_mm or z_um)",
                      UnitWarning, stacklevel=4)


def _looks_like_captif(path: Path) -> bool:
    with open(path, encoding="latin-1") as fh:
        for _, line in zip(range(30), fh):
            if line.strip().startswith(_CAPTIF_MARKER):
                return True
    return False


def _csv_header(fh, path: Path, delimiter: str) -> tuple[list[str], int]:
    """(header fields, its line number), reading ``fh`` up to and including the header row."""
    for ln, line in enumerate(fh, start=1):
        text = line.strip()
        if text and not text.startswith("#"):
            return [f.strip() for f in text.split(delimiter)], ln
    raise InputError(f"{path}: empty file (no header row); expected columns x_<unit>, z_<unit>...")


def _captif_header(fh, path: Path) -> tuple[dict, list[str], int]:
    """(header fields, column names, 0-based index of the column-name line), reading ``fh`` up to it."""
    meta = {}
    i = -1
    for i, ln in enumerate(fh):
        if ln.strip().startswith(_CAPTIF_MARKER):
            break
        key, _, value = ln.rstrip("\r\n").partition("\t")
        if key.strip():
            meta[key.strip()] = value.strip().strip("\t")
    else:
        raise InputError(f"{path}: not a CAPTIF export: no '{_CAPTIF_MARKER}' line ending the header")
    i_marker = i
    for i, ln in enumerate(fh, start=i_marker + 1):
        if ln.strip():
            return meta, [c.strip() for c in ln.rstrip("\r\n").split("\t")], i
    raise InputError(f"{path}: no column header after '{_CAPTIF_MARKER}' (line {i_marker + 1})")


#: Text per block handed to numpy's reader: large enough to amortise the call, small enough to keep the
#: memory at the size of the result.
_BLOCK_CHARS = 1 << 23
_EMPTY_FIELD = {",": re.compile(r"(?m)(^|,)[ \t]*(?=,|$)")}


def _numeric_body(fh, path: Path, first_line: int, delimiter: str, usecols: list[int], names: list[str],
                  ncol: int | None, quote_names: bool = False) -> np.ndarray:
    """The numeric columns ``usecols`` of the rest of ``fh`` as a float array (n_rows, len(usecols)).

    Blocks of whole lines go to :func:`numpy.loadtxt`; empty cells and ``NaN`` are dropouts (NaN). A block
    that numpy cannot parse (an odd missing-value token, a bad cell, a row with the wrong number of fields,
    comment lines) is parsed line by line, which names the line and column of a bad cell.
    """
    parts = []
    line = first_line
    while True:
        text = fh.read(_BLOCK_CHARS)
        if not text:
            break
        if not text.endswith("\n"):
            text += fh.readline()  # complete the last line of the block
        n_lines = text.count("\n") + (0 if text.endswith("\n") else 1)
        parts.append(_parse_block(text, n_lines, line, path, delimiter, usecols, names, ncol, quote_names))
        line += n_lines
    if not parts:
        return np.empty((0, len(usecols)))
    return parts[0] if len(parts) == 1 else np.concatenate(parts)


def _parse_block(text, n_lines, first_line, path, delimiter, usecols, names, ncol, quote_names) -> np.ndarray:
    # rows of the expected width without comments or blank lines can go to numpy as they are
    plain = ("#" not in text and "\n\n" not in text and not text.startswith("\n") and text.strip() != "" and (
        ncol is None or text.count(delimiter) == (ncol - 1) * n_lines))
    if plain:
        for fill in (False, True):
            try:
                with warnings.catch_warnings():     # numpy's "empty input" warning: handled below
                    warnings.filterwarnings("ignore", "loadtxt: input contained no data", UserWarning)
                    a = np.loadtxt(io.StringIO(_fill_empty(text, delimiter) if fill else text), delimiter=delimiter,
                                   usecols=usecols, ndmin=2, dtype=float)
            except ValueError:
                continue
            if a.shape[0] == n_lines:
                return a
    return _parse_lines(text.splitlines(), first_line, path, delimiter, usecols, names, ncol, quote_names)


def _fill_empty(text: str, delimiter: str) -> str | None:
    """Empty (or blank) cells written as ``nan`` so numpy reads them as dropouts."""
    pattern = _EMPTY_FIELD.get(delimiter)
    if pattern is None:
        d = re.escape(delimiter)
        pattern = _EMPTY_FIELD[delimiter] = re.compile(rf"(?m)(^|{d})[ ]*(?={d}|$)")
    return pattern.sub(r"\1nan", text)


def _parse_lines(lines, first_line, path, delimiter, usecols, names, ncol, quote_names) -> np.ndarray:
    """Line by line: comments and blank lines skipped, every cell checked (the exact, slow path)."""
    rows = []
    need = max(usecols) + 1
    for k, line in enumerate(lines):
        ln = first_line + k
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        fields = [f.strip() for f in line.split(delimiter)]
        if ncol is not None and len(fields) != ncol:
            raise InputError(f"{path}, line {ln}: expected {ncol} fields like the header, got {len(fields)}")
        row = []
        for j, name in zip(usecols, names):
            col = repr(name) if quote_names else name
            cell = fields[j] if len(fields) >= need else None
            if cell is None:
                raise InputError(f"{path}, line {ln}, column {col}: missing value (the line has {len(fields)} "
                                 "fields)")
            if cell in _NAN_TOKENS:
                row.append(math.nan)
                continue
            try:
                row.append(float(cell))
            except ValueError:
                raise InputError(f"{path}, line {ln}, column {col}: expected a number, got {cell!r}") from None
        rows.append(row)
    return np.array(rows, dtype=float).reshape(-1, len(usecols))


def _data_line(path: Path, header_line: int, i: int, encoding: str = "utf-8") -> int:
    """Line number of the ``i``-th data row after the header line (only on the error path: rescans)."""
    seen = -1
    with open(path, encoding=encoding, errors="replace") as fh:
        for ln, line in enumerate(fh, start=1):
            if ln <= header_line:
                continue
            text = line.strip()
            if not text or text.startswith("#"):
                continue
            seen += 1
            if seen == i:
                return ln
    return header_line + 1 + i


def _plate_limits(x: np.ndarray, z: np.ndarray, threshold: float, buffer: float) -> tuple[float, float]:
    """Road range between the reference plates: [first road x after the first plate + buffer,
    first plate x of the second half - buffer). No plate: the whole profile."""
    valid = ~np.isnan(z)
    idx = np.maximum.accumulate(np.where(valid, np.arange(z.size), 0))  # forward-fill dropouts
    z_ff = np.where(valid[idx], z[idx], -np.inf)
    plate = z_ff > threshold
    mid = int(math.ceil(z.size / 2))
    lo, hi = -np.inf, np.inf
    first = np.flatnonzero(plate[:mid])
    if first.size and first[-1] + 1 < z.size:
        lo = x[first[-1] + 1] + buffer
    second = np.flatnonzero(plate[mid:])
    if second.size:
        hi = x[mid + second[0]] - buffer
    return lo, hi

