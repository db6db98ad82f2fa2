"""Small file helpers shared by the readers and writers of :mod:`materials` (not public)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from .errors import InputError

__all__ = ["write_csv_atomic", "read_csv_columns"]


def write_csv_atomic(path, columns: Mapping[str, np.ndarray], comments: Sequence[str] = ()) -> Path:
    """Write a CSV (``#`` comment lines, a header row, data rows) completely or not at all.

    The text goes to a temporary file in the destination folder, which is then renamed over ``path``
    (``os.replace`` is atomic on POSIX and Windows), so a reader never sees a half-written file.
    """
    path = Path(path)
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
    from .dma import _col, _decode, _table

    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such file")
    text, _ = _decode(path, encoding)
    content = [(i + 1, ln) for i, ln in enumerate(text.splitlines())
               if ln.strip() and not ln.lstrip().startswith("#")]
    if not content:
        raise InputError(f"{path}: empty file (expected a header row {', '.join(required)} and data rows)")
    names = [c.strip() for c in content[0][1].split(",")]
    idx = {k: _col(path, names, k) for k in required}
    for k in optional:
        j = _col(path, names, k, required=False)
        if j is not None:
            idx[k] = j
    rows = content[1:]
    if not rows:
        raise InputError(f"{path}: no data rows after the header")
    data = _table(path, rows, names, ",")
    return {k: data[:, j] for k, j in idx.items()}, np.array([r[0] for r in rows])


def _file_mode() -> int:
    # mkstemp creates 0600 files; give the final file the permissions open() would (0666 minus the umask).
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask
