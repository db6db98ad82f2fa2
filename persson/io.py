"""Small I/O helpers: atomic file writing and CSV tables."""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

import numpy as np

__all__ = ["atomic_write", "write_csv"]


@contextlib.contextmanager
def atomic_write(path, mode: str = "w", **kwargs):
    """Open a temporary file beside ``path``; on success rename it to ``path`` (all or nothing).

    The file is written completely or not at all: on an exception the temporary file is removed and an
    existing ``path`` is left untouched.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    os.chmod(tmp, _file_mode())
    try:
        with os.fdopen(fd, mode, **kwargs) as fh:
            yield fh
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_csv(path, columns: dict, comments: tuple[str, ...] = ()) -> Path:
    """Write equal-length ``columns`` (name -> 1D array or list) as a CSV with a header row, atomically."""
    names = list(columns)
    cols = [np.asarray(columns[n]) for n in names]
    n = {c.shape[0] for c in cols}
    if len(n) != 1:
        raise ValueError(f"write_csv: columns of unequal length {sorted(n)}")
    with atomic_write(path, "w", newline="") as fh:
        for c in comments:
            fh.write(f"# {c}\n")
        fh.write(",".join(names) + "\n")
        for row in zip(*cols):
            fh.write(",".join(_fmt(x) for x in row) + "\n")
    return Path(path)


def _fmt(x) -> str:
    if isinstance(x, (float, np.floating)):
        return repr(float(x))
    return str(x)


def _file_mode() -> int:
    # mkstemp creates 0600 files; give the final file the permissions open() would (0666 minus the umask).
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask
