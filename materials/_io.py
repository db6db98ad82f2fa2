"""Small file helpers shared by the readers and writers of :mod:`materials` (not public).

Writing a CSV atomically; decoding a text file (UTF-8, else Latin-1, refusing UTF-16 and binary); parsing rows of
cells to floats and finding columns by name, with errors that name the file, line and column.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from .errors import InputError

__all__ = ["write_csv_atomic", "read_csv_columns", "decode_text", "parse_rows", "column_of", "is_numeric_row"]


def write_csv_atomic(path, columns: Mapping[str, np.ndarray], comments: Sequence[str] = (), *,
                     overwrite: bool = False) -> Path:
    """Write a CSV (``#`` comment lines, a header row, data rows) completely or not at all; an existing file only
    with ``overwrite=True`` (the rule of every writer of the project).

    The text goes to a temporary file in the destination folder, which is then renamed over ``path``
    (``os.replace`` is atomic on POSIX and Windows), so a reader never sees a half-written file.
    """
    path = Path(path)
    if path.is_dir():
        raise InputError(f"{path}: is a folder; expected a file name")
    if path.exists() and not overwrite:
        raise InputError(f"{path}: the file exists; pass overwrite=True to replace it (or choose another name)")
    names = list(columns)
    data = np.column_stack([np.asarray(columns[k], dtype=float).ravel() for k in names])
    if not np.all(np.isfinite(data)):
        raise InputError(f"{path}: refusing to write non-finite values")
    lines = [f"# {ln}" for c in comments for ln in str(c).splitlines()]
    lines.append(",".join(names))
    # shortest decimal form that reads back to the same double: a table written and read again is the same table
    lines.extend(",".join(repr(float(v)) for v in row) for row in data)
    text = "\n".join(lines) + "\n"
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
        except OSError:
            pass
        raise
    return path


def read_csv_columns(path, required: Sequence[str], optional: Sequence[str] = (),
                     encoding: str | None = None) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Read named columns of a CSV with one header row (``#`` comments allowed).

    Returns the columns (case-insensitive names, keyed as given in ``required``/``optional``) and the file line
    number of each data row. A missing column or an unparsable cell raises :class:`InputError`.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such file")
    text, _ = decode_text(path, encoding)
    content = [(i + 1, ln) for i, ln in enumerate(text.splitlines())
               if ln.strip() and not ln.lstrip().startswith("#")]
    if not content:
        raise InputError(f"{path}: empty file (expected a header row {', '.join(required)} and data rows)")
    names = [c.strip() for c in content[0][1].split(",")]
    idx = {k: column_of(path, names, k) for k in required}
    for k in optional:
        j = column_of(path, names, k, required=False)
        if j is not None:
            idx[k] = j
    rows = content[1:]
    if not rows:
        raise InputError(f"{path}: no data rows after the header")
    data = parse_rows(path, rows, names, ",")
    return {k: data[:, j] for k, j in idx.items()}, np.array([r[0] for r in rows])


def decode_text(path: Path, encoding: str | None) -> tuple[str, list[str]]:
    """The text of ``path`` and notes: ``encoding`` if given, else UTF-8 (with or without BOM), else Latin-1
    (noted). UTF-16 and binary files (NUL bytes) are refused with a hint."""
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"{path}: cannot read ({exc.strerror})") from None
    notes = []
    if encoding is not None:
        try:
            return raw.decode(encoding), notes
        except (UnicodeDecodeError, LookupError) as exc:
            raise InputError(f"{path}: not valid {encoding} text ({exc}); expected {encoding} bytes") from None
    if raw[:2] in (b"\xff\xfe", b"\xfe\xff") or b"\x00" in raw[:4096]:
        raise InputError(f"{path}: wrong encoding: the file holds NUL bytes (UTF-16 or binary); expected UTF-8 "
                         "or Latin-1 text (re-save as UTF-8, or pass encoding=...)")
    try:
        return raw.decode("utf-8-sig"), notes
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
        notes.append(f"{path.name}: decoded as Latin-1 (not valid UTF-8)")
        return text, notes


def is_numeric_row(cells) -> bool:
    """True when every non-empty cell is a number and at least one is not empty."""
    try:
        [float(c) for c in cells if c.strip()]
        return any(c.strip() for c in cells)
    except ValueError:
        return False


def parse_rows(path: Path, rows, names, sep) -> np.ndarray:
    """Parse data rows to floats; a bad cell raises naming line and column."""
    ncol = len(names)
    out = np.empty((len(rows), ncol))
    for r, (lineno, ln) in enumerate(rows):
        cells = [c.strip() for c in (ln.split(sep) if sep else ln.split())]
        if len(cells) < ncol:
            cells += [""] * (ncol - len(cells))
        elif len(cells) > ncol and any(cells[ncol:]):
            raise InputError(f"{path}, line {lineno}: {len(cells)} fields, expected {ncol} ({', '.join(names)})")
        for c in range(ncol):
            s = cells[c]
            if s == "" or s.lower() in ("nan", "na"):
                out[r, c] = np.nan
                continue
            try:
                out[r, c] = float(s)
            except ValueError:
                raise InputError(f"{path}, line {lineno}, column {names[c]!r}: expected a number, "
                                 f"got {s[:40]!r}") from None
    return out


def column_of(path, names, *candidates, required=True):
    """Index of the first of ``candidates`` among the column ``names`` (case-insensitive); a missing required
    column raises naming the file and the columns found, an optional one gives None."""
    low = [n.lower() for n in names]
    for cand in candidates:
        if cand.lower() in low:
            return low.index(cand.lower())
    if required:
        raise InputError(f"{path}: missing column {candidates[0]!r} (found columns: {', '.join(names)})")
    return None


def _file_mode() -> int:
    # mkstemp creates 0600 files; give the final file the permissions open() would (0666 minus the umask).
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask
