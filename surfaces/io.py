"""Readers: profile CSV (DESIGN.md), CAPTIF road-profiler text exports, plain arrays, 2D height maps.

Units are always explicit: CSV columns carry them in their names (``x_mm``, ``z1_um``), instrument exports
in their column headers (``Distance (mm)``), arrays and images through arguments. Everything is converted
to metres. Bad input raises :class:`surfaces.InputError` naming the file, column and line.
"""

from __future__ import annotations

import io
import math
import re
from pathlib import Path

import numpy as np

from ._util import positive, unit_factor
from .errors import InputError
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
        "csv": the DESIGN.md profile CSV (:func:`read_profiles_csv`); "captif": the tab-separated CAPTIF
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
    """Read the DESIGN.md profile CSV.

    One column ``x_<unit>`` and one or more ``z_<unit>`` / ``z1_<unit>``, ``z2_<unit>``... (parallel scans
    sharing x); unit in {m, mm, um}. Lines starting with ``#`` are comments. Empty cells or ``NaN`` are
    dropouts. Other columns are ignored.

    Raises
    ------
    InputError
        Empty file, no data rows, missing x or z column, unknown unit, non-numeric cell, x missing or not
        strictly increasing, a profile with no valid sample. The message names file, column and line.
    """
    path = Path(path)
    header, header_line, rows = _csv_rows(path, delimiter)
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
    if not rows:
        raise InputError(f"{path}: no data rows after the header (line {header_line})")
    lines = [ln for ln, _ in rows]
    ncol = len(header)
    for ln, fields in rows:
        if len(fields) != ncol:
            raise InputError(f"{path}, line {ln}: expected {ncol} fields like the header, got {len(fields)}")
    table = np.array([f for _, f in rows], dtype=object)
    jx, xname, fx = x_cols[0]
    x = _column(table[:, jx], path, xname, lines) * fx
    if np.isnan(x).any():
        i = int(np.argmax(np.isnan(x)))
        raise InputError(f"{path}, line {lines[i]}, column {xname}: x is missing; every row needs a position")
    bad = np.flatnonzero(np.diff(x) <= 0)
    if bad.size:
        i = bad[0] + 1
        raise InputError(f"{path}, line {lines[i]}, column {xname}: x must be strictly increasing "
                         f"({table[i, jx]} follows {table[i - 1, jx]})")
    profiles = []
    for j, name, fz in z_cols:
        z = _column(table[:, j], path, name, lines) * fz
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
    lines = path.read_text(encoding="latin-1").splitlines()
    try:
        i_marker = next(i for i, ln in enumerate(lines) if ln.strip().startswith(_CAPTIF_MARKER))
    except StopIteration:
        raise InputError(f"{path}: not a CAPTIF export: no '{_CAPTIF_MARKER}' line ending the header") from None
    meta = {}
    for ln in lines[:i_marker]:
        key, _, value = ln.partition("\t")
        if key.strip():
            meta[key.strip()] = value.strip().strip("\t")
    i_cols = next((i for i in range(i_marker + 1, len(lines)) if lines[i].strip()), None)
    if i_cols is None:
        raise InputError(f"{path}: no column header after '{_CAPTIF_MARKER}' (line {i_marker + 1})")
    names = [c.strip() for c in lines[i_cols].split("\t")]
    found = {}
    for j, name in enumerate(names):
        m = _CAPTIF_COLUMN.match(name)
        if m:
            found[m["name"]] = (j, name, unit_factor(m["unit"].strip(), f"{path}, column {name!r}"))
    for need in ("Distance", "Depth"):
        if need not in found:
            raise InputError(f"{path}, line {i_cols + 1}: missing column '{need} (<unit>)'; found {names}")
    (jx, xname, fx), (jz, zname, fz) = found["Distance"], found["Depth"]
    body = "\n".join(lines[i_cols + 1:])
    if not body.strip():
        raise InputError(f"{path}: no data rows after the column header (line {i_cols + 1})")
    try:
        data = np.loadtxt(io.StringIO(body), delimiter="\t", usecols=(jx, jz), ndmin=2)
    except ValueError:
        _raise_bad_captif_line(path, lines, i_cols, (jx, jz), names)
    x, z = data[:, 0] * fx, data[:, 1] * fz
    if invert:
        z = -z
    if np.isnan(x).any():
        i = int(np.argmax(np.isnan(x)))
        raise InputError(f"{path}, line {i_cols + 2 + i}, column {xname!r}: distance is missing")
    meta["raw_dropout_fraction"] = float(np.isnan(z).mean())
    where = f"{path}, column {zname!r}"
    if np.isnan(z).all():
        raise InputError(f"{where}: all values are missing (NaN); expected depths")
    bad = np.flatnonzero(np.diff(x) <= 0)
    if bad.size:
        raise InputError(f"{path}, line {i_cols + 3 + bad[0]}, column {xname!r}: distance must be strictly "
                         "increasing")
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


def _looks_like_captif(path: Path) -> bool:
    with open(path, encoding="latin-1") as fh:
        for _, line in zip(range(30), fh):
            if line.strip().startswith(_CAPTIF_MARKER):
                return True
    return False


def _csv_rows(path: Path, delimiter: str):
    """(header, header line number, [(line number, fields)]) of a comment-aware CSV."""
    header, header_line, rows = None, 0, []
    with open(path, encoding="utf-8", errors="replace") as fh:
        for ln, line in enumerate(fh, start=1):
            text = line.strip()
            if not text or text.startswith("#"):
                continue
            fields = [f.strip() for f in text.split(delimiter)]
            if header is None:
                header, header_line = fields, ln
            else:
                rows.append((ln, fields))
    if header is None:
        raise InputError(f"{path}: empty file (no header row); expected columns x_<unit>, z_<unit>...")
    return header, header_line, rows


def _column(cells: np.ndarray, path: Path, name: str, lines: list[int]) -> np.ndarray:
    """Float column; empty/NaN cells -> NaN; a non-numeric cell raises naming file, line, column."""
    cells = np.where(np.isin(cells, _NAN_TOKENS), "nan", cells).astype(str)
    try:
        return cells.astype(float)
    except ValueError:
        for i, c in enumerate(cells):
            try:
                float(c)
            except ValueError:
                raise InputError(f"{path}, line {lines[i]}, column {name}: expected a number, got {c!r}") from None
        raise


def _raise_bad_captif_line(path, lines, i_cols, cols, names):
    for i in range(i_cols + 1, len(lines)):
        if not lines[i].strip():
            continue
        fields = lines[i].split("\t")
        for j in cols:
            try:
                float(fields[j])
            except (IndexError, ValueError):
                got = fields[j] if j < len(fields) else "<missing>"
                raise InputError(f"{path}, line {i + 1}, column {names[j]!r}: expected a number, got {got!r}") from None
    raise InputError(f"{path}: cannot parse the data rows")


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

