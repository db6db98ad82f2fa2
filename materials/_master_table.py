"""Reading a master-curve table: its columns and units, repeated frequencies, and the law that shifts it.

The helpers behind :meth:`materials.MasterCurve.from_table` and :func:`materials.read_master_curve` (the formats
are described in ``docs/materials.md``): each returns plain arrays and notes, and refuses bad input with an
:class:`~materials.errors.InputError` that names the file, line and column.
"""

from __future__ import annotations

import math
import warnings
from typing import Mapping

import numpy as np

from ._tables import pick_columns, read_table
from .errors import DataWarning, InputError
from .laws import WLF, TemperatureShift
from .shift import SingleTemperature, as_shift_law
from .units import check_moduli, normalise_units

__all__ = ["table_law", "table_from_mapping", "read_table_columns", "merge_repeated"]


def table_law(wlf, shift, T_ref, source):
    """The shift law of a master-curve table, referred to the table's temperature."""
    if wlf is not None and shift is not None:
        raise InputError("give the table's shift law as wlf= or as shift=, not both")
    given = shift if shift is not None else wlf
    if given is None:
        if T_ref is None:
            raise InputError(f"{source}: a master-curve table needs its shift law (wlf={{C1, C2, T_ref_C}} or "
                             "shift=<shift law>, e.g. materials.read_shift_factors(...)), or T_ref= to use it at "
                             "that one temperature")
        try:
            T_ref = float(T_ref)
        except (TypeError, ValueError):
            raise InputError(f"T_ref: expected a temperature in deg C, got {T_ref!r}") from None
        if not math.isfinite(T_ref):
            raise InputError(f"T_ref: expected a finite temperature in deg C, got {T_ref!r}")
        return SingleTemperature(T_ref, source=source)
    name = "shift" if shift is not None else "wlf"
    if isinstance(given, WLF) or (isinstance(given, Mapping) and name == "wlf" and "E_a" not in given):
        law = TemperatureShift(given if isinstance(given, WLF) else WLF.from_mapping(given))
    else:
        law = as_shift_law(given, name=name)
        if isinstance(law, WLF):
            law = TemperatureShift(law)
    if T_ref is not None:
        try:
            T_ref = float(T_ref)
        except (TypeError, ValueError):
            raise InputError(f"T_ref: expected a temperature in deg C, got {T_ref!r}") from None
        if abs(T_ref - float(law.T_ref)) > 0:
            law = law.with_T_ref(T_ref)
    return law


def table_from_mapping(table):
    """``(f, E1, E2, source, lines)`` of a mapping with ``f_Hz``, ``E_storage_Pa``, ``E_loss_Pa`` (rows numbered
    from 1)."""
    try:
        f = np.asarray(table["f_Hz"], dtype=float).ravel()
        E1 = np.asarray(table["E_storage_Pa"], dtype=float).ravel()
        E2 = np.asarray(table["E_loss_Pa"], dtype=float).ravel()
    except KeyError as exc:
        raise InputError(f"master-curve table: missing column {exc.args[0]!r} "
                         "(expected f_Hz, E_storage_Pa, E_loss_Pa)") from None
    except (TypeError, ValueError):
        raise InputError("master-curve table: expected numbers in f_Hz, E_storage_Pa, E_loss_Pa") from None
    if not (f.size == E1.size == E2.size):
        raise InputError(f"master-curve table: columns of different lengths ({f.size}, {E1.size}, {E2.size})")
    source = "<table>"
    lines = np.arange(f.size) + 1
    _check_positive(source, lines, {"f_Hz": f, "E_storage_Pa": E1, "E_loss_Pa": E2}, rows=True)
    return f, E1, E2, source, lines


def read_table_columns(path, columns, units, poisson, encoding):
    """``(f, E1, E2, source, lines, notes)`` of a master-curve file: Hz and Young's moduli in Pa (shear
    converted with ``poisson``), checked for bad values and unit slips."""
    table = read_table(path, encoding=encoding)
    cols = pick_columns(table, required=("f", "E_storage", "E_loss"), columns=columns,
                        units=normalise_units(units), defaults=("f_Hz", "E_storage_Pa", "E_loss_Pa"))
    f, E1, E2 = cols["f"].values, cols["E_storage"].values, cols["E_loss"].values
    source = str(table.path)
    notes = list(table.notes)
    _check_positive(source, table.lines, {cols["f"].name: f, cols["E_storage"].name: E1,
                                          cols["E_loss"].name: E2})
    c1 = cols["E_storage"]
    check_moduli(E1, E2, where=f"{c1.where} and {cols['E_loss'].where}", unit=c1.unit, trusted=c1.trusted,
                 source_unit=c1.origin)
    if c1.shear:
        if not (isinstance(poisson, (int, float)) and -1.0 < poisson <= 0.5):
            raise InputError(f"poisson: expected -1 < nu <= 0.5 for the shear conversion, got {poisson!r}")
        E1, E2 = 2.0 * (1.0 + poisson) * E1, 2.0 * (1.0 + poisson) * E2
        notes.append(f"shear moduli G', G'' converted to Young's moduli E = 2(1+nu)G with nu = {poisson:g}")
    return f, E1, E2, source, table.lines, notes


def merge_repeated(f, E1, E2, source, lines, notes):
    """Merge rows whose frequencies agree within 1e-9 (relative): geometric mean, with a warning."""
    order = np.argsort(f, kind="stable")
    f, E1, E2, lines = f[order], E1[order], E2[order], np.asarray(lines)[order]
    new = np.concatenate([[True], np.diff(np.log(f)) > 1e-9])
    if new.all():
        return f, E1, E2
    group = np.cumsum(new) - 1
    n = int(group[-1]) + 1
    count = np.bincount(group, minlength=n)

    first = np.flatnonzero(new)

    def gmean(a):
        # groups of one keep their value exactly; repeated rows are averaged in log
        merged = np.exp(np.bincount(group, weights=np.log(a), minlength=n) / count)
        return np.where(count == 1, a[first], merged)

    repeated = [int(lines[i]) for i in np.flatnonzero(~new)]
    msg = (f"{source}: {len(repeated)} row(s) repeat the frequency of another row (lines "
           + ", ".join(str(v) for v in repeated[:8]) + (" ..." if len(repeated) > 8 else "")
           + "); merged by their geometric mean")
    warnings.warn(msg, DataWarning, stacklevel=4)
    notes.append(msg)
    return gmean(f), gmean(E1), gmean(E2)



# ==================================================================================================== helpers

def _check_positive(source, lines, columns: dict, rows: bool = False):
    """Every value finite and positive; the first bad one is named by line (file) or row (mapping) and column."""
    for name, a in columns.items():
        ok = np.isfinite(a) & (a > 0)
        if not np.all(ok):
            i = int(np.flatnonzero(~ok)[0])
            where = f"row {i + 1}, column {name!r}" if rows else f"line {int(lines[i])}, column {name}"
            raise InputError(f"{source}, {where}: expected a positive number, got {a[i]!r}")
    f = next(iter(columns.values()))
    if f.size < 2:
        raise InputError(f"{source}: a master-curve table needs at least two rows")
