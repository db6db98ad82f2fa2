r"""Tables of strain factors as other programs export them: :func:`read_strain_factors`.

A strain-factor table gives the large-strain moduli of a compound already normalised,
:math:`f(\varepsilon) = E'(\varepsilon)/E'(\varepsilon_0)` and
:math:`g(\varepsilon) = E''(\varepsilon)/E''(\varepsilon_0)` (Lorenz, Oh, Nam, Jeon & Persson, J. Chem. Phys.
142, 194701 (2015)), against the strain amplitude and optionally the temperature: the form in which friction
programs and earlier studies hand them on. :func:`read_strain_factors` turns one into
:class:`materials.StrainFactors`, the object :func:`materials.strain_factors` builds from raw strain sweeps, so
either can drive the per-scale modulus of the friction engine.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from frictioncite import doi

from ._dma_formats import expand, natural_key
from ._tables import _column_index, _norm, _role_of, read_table
from .errors import InputError
from .strain import StrainFactors, _temperature_of
from .units import check_strains, check_temperatures, normalise_units, split_unit_suffix, to_celsius, unit_factor

__all__ = ["read_strain_factors"]

#: Names (normalised: lower case without spaces, underscores, hyphens and dots) of the factor columns.
_F_NAMES = ("f", "fstorage", "storagefactor", "estoragefactor", "e'/e'0", "e'/e0'", "e'/e0", "e'/e'(0)", "e'ratio",
            "e'norm", "e'rel", "f(strain)", "f(eps)", "storage")
_G_NAMES = ("g", "gloss", "lossfactor", "elossfactor", 'e"/e"0', 'e"/e0"', 'e"/e0', 'e"/e"(0)', 'e"ratio', 'e"norm',
            'e"rel', "g(strain)", "g(eps)", "loss")
#: Largest factor a normalised table holds; above it the columns are moduli (use read_strain_sweep).
_MAX_FACTOR = 5.0


@doi("10.1063/1.4919221")
def read_strain_factors(path, *, columns=None, units=None, T: float | None = None, encoding: str | None = None,
                        isotherm_tol: float = 1.0) -> StrainFactors:
    r"""Read a table of strain factors f (on E') and g (on E'') against the strain amplitude.

    Each file is a delimited table (comma, tab, semicolon or white space) with a names row and optionally a units
    row, or a header-less table of three columns: strain, f, g. Columns are recognised by name: the strain
    amplitude (``strain``, ``strain_pct``, ``Strain [%]``, ``amplitude``, ``eps``), the factors (``f``,
    ``storage_factor``, ``E'/E'0``; ``g``, ``loss_factor``, ``E''/E''0``) and optionally the temperature (``T_C``,
    ``T``, ``Temp``). Without a temperature column the factors hold at every temperature, or, for several files,
    the temperature of each comes from ``T=`` or its name (``T20.txt``).

    Parameters
    ----------
    path : str, Path or sequence of them
        A file; a folder (its ``*.csv``, ``*.txt`` and ``*.dat`` files); or a list of files.
    columns : sequence or mapping, optional
        Names of the file's columns in order (``["strain_pct", "f", "g"]``; ``None`` or ``"-"`` skips one) or
        ``{"strain": name or index, "f": ..., "g": ..., "T": ...}``.
    units : mapping, optional
        ``{"strain": "%" | "-", "T": "C" | "K"}``.
    T : float, optional
        Temperature (deg C) of files without a temperature column (several files only).
    encoding : str, optional
    isotherm_tol : float
        Temperature gap (K) separating the temperatures of one table.

    Returns
    -------
    StrainFactors
        On the union of the tables' strains (each temperature interpolated linearly in ln strain within its own
        strains and held at its end values beyond them), as :func:`materials.strain_factors`.

    Raises
    ------
    InputError
        Missing file or column, a strain in percent read as absolute, non-positive factors, factors that look like
        moduli (above 5: read the sweeps with :func:`materials.read_strain_sweep` instead), naming file, line and
        column.
    """
    files = _files(path)
    units = normalise_units(units)
    Ts, strains, Fs, Gs = [], [], [], []
    for p in files:
        table = read_table(p, encoding=encoding)
        cols = _columns(table, columns)
        j_e = cols["strain"]
        where_e = f"{p}, column {table.label(j_e)}"
        name_unit = split_unit_suffix(table.names[j_e])[1] if table.names else None
        if isinstance(columns, (list, tuple)) and columns[j_e] is not None:
            name_unit = split_unit_suffix(str(columns[j_e]))[1] or name_unit
        unit = units.get("strain") or table.units[j_e] or name_unit or "-"
        e = table.data[:, j_e] * unit_factor("strain", unit, where=where_e)
        check_strains(table.data[:, j_e], where=where_e, unit=unit, trusted="strain" in units)
        f, g = table.data[:, cols["f"]], table.data[:, cols["g"]]
        for name, j, a in (("f", cols["f"], f), ("g", cols["g"], g)):
            bad = ~(np.isfinite(a) & (a > 0))
            if bad.any():
                i = int(np.argmax(bad))
                raise InputError(f"{p}, line {int(table.lines[i])}, column {table.label(j)}: expected a positive "
                                 f"factor {name}, got {a[i]!r}")
            if a.max() > _MAX_FACTOR:
                raise InputError(f"{p}, column {table.label(j)}: values up to {a.max():g} are moduli, not factors "
                                 f"(a factor {name} is E(strain)/E(small strain), about 0.1-2); read strain sweeps "
                                 "with materials.read_strain_sweep")
        bad = ~(np.isfinite(e) & (e > 0))
        if bad.any():
            i = int(np.argmax(bad))
            raise InputError(f"{where_e}, line {int(table.lines[i])}: expected a strain amplitude > 0, got "
                             f"{table.data[i, j_e]!r}")
        if "T" in cols:
            j_T = cols["T"]
            u_T = units.get("T") or table.units[j_T] or (split_unit_suffix(table.names[j_T])[1] if table.names
                                                         else None) or "C"
            temp = to_celsius(table.data[:, j_T], unit_factor("T", u_T, where=f"{p}, column {table.label(j_T)}"))
            check_temperatures(temp, where=f"{p}, column {table.label(j_T)}", lines=table.lines,
                               trusted="T" in units)
        elif len(files) > 1 or T is not None:
            temp = np.full(e.size, _temperature_of(p, T, "give every file a temperature column"))
        else:
            temp = np.full(e.size, math.nan)  # one table for every temperature
        Ts.append(temp)
        strains.append(e)
        Fs.append(f)
        Gs.append(g)
    T_all, e_all, F_all, G_all = (np.concatenate(a) for a in (Ts, strains, Fs, Gs))
    source = str(files[0]) if len(files) == 1 else f"{len(files)} files ({files[0].name} ... {files[-1].name})"
    if np.isnan(T_all).any() and not np.isnan(T_all).all():
        raise InputError(f"{source}: some files give a temperature and some do not; give T= or a temperature "
                         "column in every file")
    return _grid(e_all, T_all, F_all, G_all, isotherm_tol, source)


# ---------------------------------------------------------------------------------------------------------
def _files(path) -> list[Path]:
    if isinstance(path, (str, Path)) and Path(path).is_dir():
        found = sorted((q for q in Path(path).iterdir() if q.is_file() and q.suffix.lower() in (".csv", ".txt",
                                                                                                  ".dat")),
                       key=natural_key)
        if not found:
            raise InputError(f"{path}: folder holds no *.csv, *.txt or *.dat strain-factor tables")
        return found
    if path is None:
        raise InputError("path: expected a strain-factor table file, a folder or a list of files, got None")
    return expand(path)


def _columns(table, columns) -> dict[str, int]:
    """role ('strain', 'f', 'g', 'T') -> column index."""
    found: dict[str, int] = {}
    if columns is not None:
        if isinstance(columns, dict):
            for role, ref in columns.items():
                if role not in ("strain", "f", "g", "T"):
                    raise InputError(f"columns: unknown role {role!r} (expected strain, f, g or T)")
                found[role] = _column_index(table, ref)
        else:
            if isinstance(columns, str):
                raise InputError(f"columns: expected a sequence of column names or a mapping, got {columns!r}")
            for j, name in enumerate(columns):
                if name is None or str(name).strip() in ("", "-"):
                    continue
                role = _role(str(name))
                if role is None:
                    raise InputError(f"columns[{j}]: unknown column name {name!r} (expected strain or strain_pct, f, "
                                     "g, T_C, or None to skip)")
                found[role] = j
    elif table.names is not None:
        for j, name in enumerate(table.names):
            role = _role(name)
            if role is not None and role not in found:
                found[role] = j
    elif table.n_columns == 3:
        found = {"strain": 0, "f": 1, "g": 2}
    else:
        raise InputError(f"{table.path}: the table has no header row and {table.n_columns} columns; name them with "
                         "columns=[...] (e.g. ['strain_pct', 'f', 'g', 'T_C'])")
    missing = [r for r in ("strain", "f", "g") if r not in found]
    if missing:
        have = ", ".join(table.names) if table.names else f"{table.n_columns} unnamed columns"
        moduli = table.names is not None and any((_role_of(n)[0] or "").startswith(("E_", "G_")) for n in table.names)
        hint = ("; the table holds moduli: it is a strain sweep, read it with materials.read_strain_sweep (in a "
                "case file: [material] strain_sweeps)" if moduli else
                "; name the columns with columns=['strain_pct', 'f', 'g'] or columns={'strain': ..., 'f': ..., "
                "'g': ...}")
        raise InputError(f"{table.path}: no column for {', '.join(_ROLE_TEXT[r] for r in missing)} (found {have})"
                         f"{hint}")
    return found


_ROLE_TEXT = {"strain": "the strain amplitude (strain, strain_pct)", "f": "the storage factor f (f, E'/E'0)",
              "g": "the loss factor g (g, E''/E''0)"}


def _role(name: str) -> str | None:
    key = _norm(name)  # factors are dimensionless: no unit suffix (f_Hz is a frequency, not a factor)
    if key in _F_NAMES:
        return "f"
    if key in _G_NAMES:
        return "g"
    role, _ = _role_of(name)
    return role if role in ("strain", "T") else None


def _grid(e, T, F, G, tol, source) -> StrainFactors:
    """The points on the union of their strains, one row per temperature (or one row for all)."""
    grid = np.unique(e)
    xg = np.log(grid)
    if np.isnan(T).all():
        groups = [np.arange(e.size)]
        T_nodes = [0.0]
    else:
        order = np.argsort(T, kind="stable")
        label = np.empty(T.size, dtype=int)
        label[order] = np.cumsum(np.concatenate([[0], np.diff(T[order]) > tol]))
        groups = [np.flatnonzero(label == k) for k in range(int(label.max()) + 1)]
        T_nodes = [float(np.median(T[idx])) for idx in groups]
    rows_f, rows_g = [], []
    for idx in groups:
        x, inv = np.unique(np.log(e[idx]), return_inverse=True)
        f = np.bincount(inv, weights=F[idx]) / np.bincount(inv)   # repeated strains averaged
        g = np.bincount(inv, weights=G[idx]) / np.bincount(inv)
        xc = np.clip(xg, x[0], x[-1])  # held at the end values beyond this temperature's strains
        rows_f.append(np.interp(xc, x, f))
        rows_g.append(np.interp(xc, x, g))
    n = len(T_nodes)
    return StrainFactors(grid, np.array(T_nodes), np.array(rows_f), np.array(rows_g),
                         source=f"strain-factor table {source} ({grid.size} strains"
                                + (f", {n} temperatures)" if n > 1 and not np.isnan(T).all() else ")"))
