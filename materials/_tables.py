"""Reading the column tables that instruments and other programs export (not public).

A table is a text file of numeric rows, optionally preceded by a row of column names and a row of units;
``#`` lines are comments. The separator is recognised from the first numeric row: comma, tab, semicolon (then
a decimal comma is accepted) or white space. Units may also sit in the names (``f [Hz]``, ``E' (MPa)``,
``E_storage_Pa``). Trailing non-numeric lines (an instrument's sample name) are ignored and noted.

:func:`read_table` returns the raw table; :func:`pick_columns` finds the columns that play each role
(frequency, storage and loss modulus, temperature, strain) from their names or from the ``columns=`` option,
and converts them to the project's units (Hz, Pa, deg C, absolute strain) following ``units=``, the file's
units, the names' unit suffixes and the defaults, in that order.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from ._io import decode_text
from .errors import InputError
from .units import split_unit_suffix, to_celsius, unit_factor

__all__ = ["RawTable", "Column", "read_table", "pick_columns"]


@dataclass(frozen=True, eq=False)
class RawTable:
    """A numeric table as read: column names and units (None where the file has none), values, line numbers."""

    path: Path
    names: tuple[str, ...] | None
    units: tuple[str | None, ...]
    data: np.ndarray
    lines: np.ndarray
    notes: tuple[str, ...] = ()

    @property
    def n_columns(self) -> int:
        """Number of columns of ``data``."""
        return self.data.shape[1]

    def label(self, j: int) -> str:
        """How column ``j`` is named in messages."""
        return repr(self.names[j]) if self.names else f"{j + 1} (of a header-less table)"

    def __repr__(self) -> str:
        return f"RawTable({self.path.name!r}, {self.data.shape[0]} rows x {self.n_columns} columns)"


@dataclass(frozen=True, eq=False)
class Column:
    """One column picked for a role, converted to the project's unit."""

    values: np.ndarray
    where: str
    unit: str
    origin: str
    trusted: bool
    shear: bool = False
    name: str = ""


def read_table(path, *, encoding: str | None = None) -> RawTable:
    """Read a delimited numeric table with at most a names row and a units row before the data.

    Raises
    ------
    InputError
        Missing or empty file, more than two header rows, a non-numeric cell inside the data (naming the line
        and column), a row with the wrong number of fields.
    """
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such file")
    text, notes = decode_text(path, encoding)
    content = [(i + 1, ln) for i, ln in enumerate(text.splitlines())
               if ln.strip() and not ln.lstrip().startswith("#")]
    if not content:
        raise InputError(f"{path}: empty file (expected rows of numbers, optionally after a names row and a "
                         "units row)")
    first, sep, decimal_comma = _first_numeric_row(content)
    if first is None:
        raise InputError(f"{path}: no row of numbers found (expected numeric columns separated by commas, tabs, "
                         f"semicolons or spaces; line {content[0][0]}: {content[0][1].strip()[:60]!r})")
    header = content[:first]
    if len(header) > 2:
        raise InputError(f"{path}, line {header[2][0]}: expected at most a names row and a units row before the "
                         f"data, found {len(header)} non-numeric rows (comment extra lines out with '#')")
    rows = content[first:]
    ncol = len(_split(rows[0][1], sep, decimal_comma))
    # trailing lines that are not data rows (a sample name written after the data: another number of fields,
    # not numeric) are ignored and said; a bad cell in a data row is an error below
    while len(rows) > 1:
        cells = _split(rows[-1][1], sep, decimal_comma)
        if len(cells) == ncol or _numeric(cells):
            break
        notes.append(f"{path.name}, line {rows[-1][0]}: trailing non-data line ignored ({rows[-1][1].strip()[:40]!r})")
        rows = rows[:-1]
    names: tuple[str, ...] | None = None
    units: list[str | None] = [None] * ncol
    if header:
        raw_names = _header_cells(header[0][1], sep)
        if len(raw_names) != ncol:
            raise InputError(f"{path}, line {header[0][0]}: {len(raw_names)} column names for {ncol} data columns "
                             f"({', '.join(raw_names)}); pass columns=[...] to name them")
        split = [_bracket_unit(n) for n in raw_names]
        names = tuple(n for n, _ in split)
        units = [u for _, u in split]
        if len(header) == 2:
            row_units = [c.strip() for c in (header[1][1].split(sep) if sep else header[1][1].split())]
            if len(row_units) != ncol:
                raise InputError(f"{path}, line {header[1][0]}: {len(row_units)} units for {ncol} columns")
            units = [u.strip("[]()").strip() or None for u in row_units]
    if decimal_comma:
        notes.append(f"{path.name}: decimal commas read as decimal points")
    data = _parse_rows(path, rows, ncol, sep, decimal_comma, names)
    return RawTable(path=path, names=names, units=tuple(units), data=data, lines=np.array([r[0] for r in rows]),
                    notes=tuple(notes))


# ---------------------------------------------------------------------------------------------- roles

#: Names (lower case, without spaces, underscores, hyphens and dots) by which each role is recognised.
ALIASES = {
    "f": ("f", "freq", "frequency", "fr", "fred", "reducedfrequency", "fat", "far", "f*at"),
    "omega": ("omega", "w", "ω", "angularfrequency", "omegar", "wr", "omegaat", "wat"),
    "E_storage": ("estorage", "estor", "e'", "e1", "storagemodulus", "estoragemodulus", "storage", "eprime",
                  "youngsstoragemodulus"),
    "E_loss": ("eloss", 'e"', "e2", "lossmodulus", "elossmodulus", "loss", "edoubleprime", "youngslossmodulus"),
    "G_storage": ("gstorage", "gstor", "g'", "g1", "shearstoragemodulus", "gprime"),
    "G_loss": ("gloss", 'g"', "g2", "shearlossmodulus", "gdoubleprime"),
    "T": ("ts", "t", "temp", "temperature"),
    "strain": ("strain", "strainamplitude", "amplitude", "eps", "epsilon", "ε", "dynstrain", "dynamicstrain",
               "strainamp", "gamma", "γ"),
}

#: One-letter names are matched with their case: "f" is a frequency and "F" a force, "T" a temperature and "t" a
#: time (as in Eplexor exports).
_CASE_SENSITIVE = {"f": "f", "t": "T", "w": "w"}


def pick_columns(table: RawTable, *, required: Sequence[str], optional: Sequence[str] = (), columns=None,
                 units: Mapping[str, str] | None = None, defaults: Sequence[str] | None = None
                 ) -> dict[str, Column]:
    """Find and convert the columns of ``required`` and ``optional`` roles.

    Parameters
    ----------
    table : RawTable
    required, optional : sequence of {"f", "E_storage", "E_loss", "T", "strain"}
        Roles. ``f`` is matched by frequency (Hz) or angular frequency (rad/s) columns; ``E_storage`` and
        ``E_loss`` by shear columns too (``Column.shear`` says so; the caller converts).
    columns : sequence or mapping, optional
        The user's naming of the columns: a sequence names the file's columns in order (``"f_Hz"``,
        ``"E_storage_MPa"``, ``"T_C"``, ``"strain_pct"``, ``"omega"``...; ``None`` or ``"-"`` skips a column);
        a mapping gives for each role the file's column name or 0-based index. A unit suffix given here sets the
        unit; unlike ``units=`` it does not exempt the values from the range checks (unit slips).
    units : mapping, optional
        {role: unit}, already normalised (:func:`materials.units.normalise_units`).
    defaults : sequence of str, optional
        Role names of a header-less table's columns when ``columns`` is not given.

    Returns
    -------
    dict
        role -> :class:`Column` (values in Hz, Pa, deg C or absolute strain).
    """
    units = dict(units or {})
    assigned = _assign(table, required, optional, columns, defaults)
    out = {}
    for role, (j, name_role, name_unit, from_option) in assigned.items():
        where = f"{table.path}, column {table.label(j)}"
        shear = name_role in ("G_storage", "G_loss")
        omega = name_role == "omega"
        if role in units:
            unit, origin, trusted = units[role], "units option", True
        elif from_option and name_unit is not None:
            # a name such as E_storage_Pa labels a column (often copied from the docs), it does not vouch for the
            # values the way units= does: the range checks still apply
            unit, origin, trusted = name_unit, "columns option", False
        elif table.units[j] is not None:
            unit, origin, trusted = table.units[j], "file's units", False
        elif name_unit is not None:
            unit, origin, trusted = name_unit, "column name", False
        else:
            unit, origin, trusted = _DEFAULT_UNIT[name_role], "default", False
        values = table.data[:, j]
        factor = unit_factor("E_storage" if shear else ("f" if omega else role), unit, where=where, omega=omega)
        if role == "T":
            values = to_celsius(values, factor)
        else:
            values = values * factor
        out[role] = Column(values=values, where=where, unit=unit, origin=origin, trusted=trusted, shear=shear,
                           name=table.label(j))
    shear_flags = {out[r].shear for r in ("E_storage", "E_loss") if r in out}
    if len(shear_flags) > 1:
        raise InputError(f"{table.path}: one modulus column is a shear modulus (G) and the other a Young's "
                         "modulus (E); expected both of one kind")
    return out


_DEFAULT_UNIT = {"f": "Hz", "omega": "rad/s", "E_storage": "Pa", "E_loss": "Pa", "G_storage": "Pa", "G_loss": "Pa",
                 "T": "C", "strain": "-"}

_ROLE_FAMILY = {"f": "f", "omega": "f", "E_storage": "E_storage", "G_storage": "E_storage", "E_loss": "E_loss",
                "G_loss": "E_loss", "T": "T", "strain": "strain"}


def _norm(name: str) -> str:
    n = name.strip().lower().replace("\u2019", "'").replace("\u2032", "'").replace("''", '"')
    return re.sub(r"[\s_\-.]", "", n)


def _role_of(name: str) -> tuple[str | None, str | None]:
    """(role, unit from a name suffix) of a column name, or (None, None)."""
    base, suffix_unit = split_unit_suffix(name)
    for cand, unit in ((base, suffix_unit), (name, None)):
        key = _norm(cand)
        if key in _CASE_SENSITIVE and cand.strip() != _CASE_SENSITIVE[key]:
            continue
        for role, names in ALIASES.items():
            if key in names:
                return role, unit
    return None, None


def _assign(table, required, optional, columns, defaults):
    """role -> (column index, matched role name, unit from the name, named by the user)."""
    wanted = list(required) + [r for r in optional if r not in required]
    found: dict[str, tuple[int, str, str | None, bool]] = {}
    if columns is not None:
        if isinstance(columns, Mapping):
            for key, ref in columns.items():
                name_role, name_unit = _role_of(str(key))
                if name_role is None:
                    raise InputError(f"columns: unknown role {key!r} (expected f, omega, E_storage, E_loss, "
                                     "G_storage, G_loss, T or strain, optionally with a unit suffix such as _MPa)")
                found[_ROLE_FAMILY[name_role]] = (_column_index(table, ref), name_role, name_unit, True)
        else:
            if isinstance(columns, str):
                raise InputError(f"columns: expected a sequence of column names or a mapping, got {columns!r}")
            names = list(columns)
            if len(names) > table.n_columns:
                raise InputError(f"columns: {len(names)} names for a table of {table.n_columns} columns "
                                 f"({table.path})")
            for j, name in enumerate(names):
                if name is None or str(name).strip() in ("", "-"):
                    continue
                name_role, name_unit = _role_of(str(name))
                if name_role is None:
                    raise InputError(f"columns[{j}]: unknown column name {name!r} (expected f_Hz, omega, "
                                     "E_storage_Pa, E_loss_Pa, T_C, strain, ... or None to skip)")
                found[_ROLE_FAMILY[name_role]] = (j, name_role, name_unit, True)
    elif table.names is not None:
        for j, name in enumerate(table.names):
            name_role, name_unit = _role_of(name)
            if name_role is None:
                continue
            family = _ROLE_FAMILY[name_role]
            if family in wanted and family not in found:
                found[family] = (j, name_role, name_unit, False)
    else:
        if defaults is None or len(defaults) > table.n_columns:
            example = [_EXAMPLE_NAME[r] for r in wanted if r in _EXAMPLE_NAME]  # the columns this reader needs
            raise InputError(f"{table.path}: the table has no header row; name its columns with "
                             f"columns=[...] (e.g. {example})")
        for j, name in enumerate(defaults):
            name_role, name_unit = _role_of(name)
            found[_ROLE_FAMILY[name_role]] = (j, name_role, name_unit, False)
    missing = [r for r in required if r not in found]
    if missing:
        have = ", ".join(table.names) if table.names else f"{table.n_columns} unnamed columns"
        raise InputError(f"{table.path}: no column for {', '.join(_ROLE_TEXT[r] for r in missing)} (found {have}); "
                         "name the columns with columns=[...] or columns={role: name}")
    return {r: found[r] for r in wanted if r in found}


_EXAMPLE_NAME = {"strain": "strain_pct", "f": "f_Hz", "E_storage": "E_storage_Pa", "E_loss": "E_loss_Pa", "T": "T_C"}

_ROLE_TEXT = {"f": "the frequency (f_Hz, f or omega)",
              "E_storage": "the storage modulus (E_storage_Pa, E_storage, E_stor, E' or G')",
              "E_loss": "the loss modulus (E_loss_Pa, E_loss, E\" or G\")", "T": "the temperature (T_C, T)",
              "strain": "the strain amplitude (strain, strain_pct)"}


def _column_index(table, ref) -> int:
    if isinstance(ref, (int, np.integer)) and not isinstance(ref, bool):
        if not 0 <= int(ref) < table.n_columns:
            raise InputError(f"columns: index {ref} outside the table's {table.n_columns} columns ({table.path})")
        return int(ref)
    if isinstance(ref, str) and table.names is not None:
        low = [n.lower() for n in table.names]
        if ref.lower() in low:
            return low.index(ref.lower())
        raise InputError(f"columns: no column {ref!r} in {table.path} (found {', '.join(table.names)})")
    raise InputError(f"columns: expected a column name or a 0-based index, got {ref!r}")


# ---------------------------------------------------------------------------------------------- parsing

_SEPARATORS = (",", "\t", ";", None)


def _split(line: str, sep, decimal_comma=False) -> list[str]:
    cells = [c.strip() for c in (line.split(sep) if sep else line.split())]
    if decimal_comma:
        cells = [c.replace(",", ".") for c in cells]
    return cells


def _numeric(cells) -> bool:
    """Every non-empty cell a number (or nan/na), and at least one a number."""
    seen = False
    for c in cells:
        if c == "" or c.lower() in ("nan", "na"):
            continue
        try:
            float(c)
        except ValueError:
            return False
        seen = True
    return seen


def _first_numeric_row(content):
    for k, (_, ln) in enumerate(content[:50]):
        for sep in _SEPARATORS:
            cells = _split(ln, sep)
            if len(cells) >= 2 and _numeric(cells):
                return k, sep, False
            if sep in (";", "\t") and len(cells) >= 2 and _numeric(_split(ln, sep, True)):
                return k, sep, True
    return None, None, False


def _header_cells(line: str, sep) -> list[str]:
    if sep is not None:
        return [c.strip() for c in line.split(sep)]
    # white space separates the names; a bracketed unit ("f [Hz]") belongs to the name before it
    out: list[str] = []
    for tok in line.split():
        if out and re.fullmatch(r"[\[(][^\[\]()]*[\])]", tok):
            out[-1] = f"{out[-1]} {tok}"
        else:
            out.append(tok)
    return out


def _bracket_unit(name: str) -> tuple[str, str | None]:
    m = re.fullmatch(r"(.*?)\s*[\[(]([^\[\]()]*)[\])]\s*", name.strip())
    if m and m.group(1):
        return m.group(1).strip(), (m.group(2).strip() or None)
    return name.strip(), None


def _parse_rows(path, rows, ncol, sep, decimal_comma, names) -> np.ndarray:
    out = np.empty((len(rows), ncol))
    for r, (lineno, ln) in enumerate(rows):
        cells = _split(ln, sep, decimal_comma)
        if len(cells) < ncol:
            cells += [""] * (ncol - len(cells))
        elif len(cells) > ncol and any(cells[ncol:]):
            raise InputError(f"{path}, line {lineno}: {len(cells)} fields, expected {ncol}")
        for c in range(ncol):
            s = cells[c]
            if s == "" or s.lower() in ("nan", "na"):
                out[r, c] = np.nan
                continue
            try:
                out[r, c] = float(s)
            except ValueError:
                col = repr(names[c]) if names else str(c + 1)
                raise InputError(f"{path}, line {lineno}, column {col}: expected a number, got {s[:40]!r}") from None
    return out
