"""The tidy result table of sweeps: one row per point, inputs and outputs as columns."""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from ..errors import InputError
from ..io import write_csv

__all__ = ["Table", "read_table"]


@dataclass(frozen=True, eq=False)
class Table:
    """An immutable column table (one row per point) that saves to CSV.

    Parameters
    ----------
    columns : mapping of str to array_like
        Column name -> 1D values, all of the same length. Numbers become float (or bool / int) arrays, text
        becomes object arrays of str. The arrays are stored read-only.
    comments : tuple of str
        Lines written as ``# ...`` comments above the CSV header (what the table is, partial or complete).

    Examples
    --------
    >>> t = Table({"pressure_Pa": [1e5, 2e5], "mu": [0.5, 0.6]})
    >>> len(t), t.names
    (2, ('pressure_Pa', 'mu'))
    >>> t.where(pressure_Pa=2e5)["mu"]
    array([0.6])
    """

    columns: Mapping[str, np.ndarray]
    comments: tuple = field(default=())

    def __post_init__(self):
        cols: dict[str, np.ndarray] = {}
        n = None
        for name, values in dict(self.columns).items():
            if not isinstance(name, str) or not name:
                raise InputError(f"Table: column names must be non-empty strings, got {name!r}")
            a = _as_column(values)
            if a.ndim != 1:
                raise InputError(f"Table: column {name!r} must be 1D, got shape {a.shape}")
            if n is None:
                n = a.shape[0]
            elif a.shape[0] != n:
                raise InputError(f"Table: column {name!r} has {a.shape[0]} rows, expected {n}")
            a.setflags(write=False)
            cols[name] = a
        object.__setattr__(self, "columns", cols)
        object.__setattr__(self, "comments", tuple(str(c) for c in self.comments))

    # ------------------------------------------------------------------------------------------------
    @property
    def names(self) -> tuple[str, ...]:
        """Column names, in order."""
        return tuple(self.columns)

    def __len__(self) -> int:
        return 0 if not self.columns else next(iter(self.columns.values())).shape[0]

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self.columns[name]
        except KeyError:
            raise KeyError(f"no column {name!r}; columns: {list(self.columns)}") from None

    def __contains__(self, name: str) -> bool:
        return name in self.columns

    def __repr__(self) -> str:
        return f"Table({len(self)} rows; columns: {', '.join(self.names)})"

    def rows(self) -> list[dict[str, Any]]:
        """The rows as dicts of Python scalars (column name -> value)."""
        names = self.names
        cols = [self.columns[n].tolist() for n in names]
        return [dict(zip(names, vals)) for vals in zip(*cols)]

    def where(self, **equal) -> "Table":
        """Rows whose columns equal the given values (exact comparison), e.g. ``t.where(mode="restrict")``."""
        keep = np.ones(len(self), dtype=bool)
        for name, value in equal.items():
            keep &= self[name] == value
        return self.take(np.flatnonzero(keep))

    def take(self, index) -> "Table":
        """Rows at the integer positions (or boolean mask) ``index``."""
        return Table({k: v[index] for k, v in self.columns.items()}, self.comments)

    def with_comments(self, *comments: str) -> "Table":
        """A copy with other comment lines."""
        return Table(self.columns, tuple(comments))

    def equals(self, other: "Table") -> bool:
        """Same column names, same order and exactly equal values (NaN equals NaN)."""
        if not isinstance(other, Table) or self.names != other.names or len(self) != len(other):
            return False
        for n in self.names:
            a, b = self.columns[n], other.columns[n]
            if a.dtype.kind == "f" and b.dtype.kind == "f":
                if not np.array_equal(a, b, equal_nan=True):
                    return False
            elif not np.array_equal(a, b):
                return False
        return True

    def to_csv(self, path, comments: tuple[str, ...] | None = None, *, overwrite: bool = False) -> Path:
        """Write the table as CSV (header row, ``#`` comments), atomically: complete or not at all; an existing
        file only with ``overwrite=True``.

        Floats are written with ``repr`` (they read back bit for bit with :func:`read_table`).

        Returns
        -------
        pathlib.Path
        """
        return write_csv(path, self.columns, comments=self.comments if comments is None else tuple(comments),
                         overwrite=overwrite)

    def to_pandas(self):
        """A :class:`pandas.DataFrame` of the table (pandas is optional: ImportError when absent)."""
        import pandas as pd

        return pd.DataFrame({k: np.asarray(v) for k, v in self.columns.items()})

    @staticmethod
    def concat(tables) -> "Table":
        """Rows of ``tables`` one after the other (same column names required); comments of the first."""
        tables = list(tables)
        if not tables:
            return Table({})
        names = tables[0].names
        for t in tables[1:]:
            if t.names != names:
                raise InputError(f"Table.concat: column names differ: {names} vs {t.names}")
        return Table({n: np.concatenate([t.columns[n] for t in tables]) for n in names},
                     tables[0].comments)


def read_table(path) -> Table:
    """Read a CSV written by :meth:`Table.to_csv` (``#`` comments kept, numbers as float, True/False as bool).

    Raises
    ------
    InputError
        Missing file, no header, or rows of the wrong length (naming the file and line).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: table not found")
    comments: list[str] = []
    header = None
    rows: list[list[str]] = []
    with open(path, encoding="utf-8", newline="") as fh:
        for lineno, line in enumerate(fh, start=1):
            if line.startswith("#"):
                comments.append(line[1:].strip())
                continue
            if not line.strip():
                continue
            fields = next(csv.reader([line]))
            if header is None:
                header = fields
                continue
            if len(fields) != len(header):
                raise InputError(f"{path}, line {lineno}: expected {len(header)} fields, got {len(fields)}")
            rows.append(fields)
    if header is None:
        raise InputError(f"{path}: no header row")
    cols = {name: _parse_column([r[j] for r in rows]) for j, name in enumerate(header)}
    return Table(cols, tuple(comments))


# ---------------------------------------------------------------------------------------------------------
def _as_column(values) -> np.ndarray:
    a = np.asarray(values)
    if a.dtype.kind in "fiub":
        return np.array(a, copy=True)
    if a.dtype.kind in "US":
        return a.astype(str).astype(object)
    return np.array(a, dtype=object, copy=True)


def _parse_column(texts: list[str]) -> np.ndarray:
    if texts and all(t in ("True", "False") for t in texts):
        return np.array([t == "True" for t in texts], dtype=bool)
    try:
        vals = [float(t) for t in texts]
    except ValueError:
        return np.array(texts, dtype=object)
    if all(math.isfinite(v) and v == int(v) and "." not in t and "e" not in t.lower() and "inf" not in t.lower()
           for v, t in zip(vals, texts)) and texts:
        return np.array([int(t) for t in texts], dtype=np.int64)
    return np.array(vals, dtype=float)
