"""The DMA file formats: parsing one file into columns in Hz, Pa and deg C (internal to :mod:`materials.dma`).

Formats (described for users in ``docs/materials.md``):

* **long table** (the project's own): CSV with a header row ``T_C, f_Hz, E_storage_Pa, E_loss_Pa`` and an
  optional ``strain`` column (strain amplitude, dimensionless) and optional ``isotherm`` column; shear data may
  be given as ``G_storage_Pa, G_loss_Pa`` instead. Lines starting with ``#`` are comments.
* **pyvisco** CSV: two header rows, names (``f, E_stor, E_loss, T, Set``; or ``G_stor, G_loss``) then units
  (``Hz, MPa, MPa, C, -``).
* **Eplexor** text export: whitespace-separated columns, a names row (``Index Ts t f ... E' E" ...``) then a
  units row in brackets (``[Hz]``, ``[MPa]``, ``[°C]`` with a Latin-1 degree sign); one isotherm per file, the
  file name carrying the nominal temperature (``T20.txt``); a trailing non-numeric line is ignored.

:func:`read_part` parses one file into a dict of columns (``T_C``, ``f_Hz``, ``E_storage``, ``E_loss``,
``strain``, ``isotherm``, ``line``, ``shear``, ``notes``, the ``names`` and ``units`` each column was read with);
:func:`apply_units` applies the units a user declares and checks the rest for unit slips; :func:`expand` turns a
file, folder or list into files; :func:`condense_notes` merges the notes of many files.
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from ._io import column_of, decode_text, is_numeric_row, parse_rows
from .errors import InputError
from .units import check_moduli, check_temperatures, to_celsius, unit_factor

__all__ = ["read_part", "apply_units", "expand", "natural_key", "condense_notes"]

_PRESSURE_UNITS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9, "n/m2": 1.0, "n/mm2": 1e6, "n/mm^2": 1e6}


def read_part(path: Path, *, format: str | None, encoding: str | None) -> dict:
    """The columns of one DMA file (``format`` forced, or recognised from its header), see the module."""
    text, notes = decode_text(path, encoding)
    lines = text.splitlines()
    content = [(i + 1, ln) for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith("#")]
    if not content:
        raise InputError(f"{path}: empty file (expected a header row and data rows)")
    fmt = format or _detect(path, content)
    if fmt == "long":
        out = _parse_long(path, content)
    elif fmt == "pyvisco":
        out = _parse_pyvisco(path, content)
    elif fmt == "eplexor":
        out = _parse_eplexor(path, content)
    else:
        raise InputError(f"format: expected 'long', 'pyvisco' or 'eplexor', got {format!r}")
    out["notes"] = notes + out.get("notes", [])
    return out


def apply_units(path: Path, part: dict, units: dict) -> None:
    """Convert a parsed file's columns to the declared ``units`` and check the rest for unit slips.

    Each parser reports the unit it read every column in (``part["units"]``: role -> (unit, factor or kind)).
    A declared unit replaces it; then temperatures and moduli are checked (:mod:`materials.units`), the
    declared ones only for impossible values.
    """
    read = part["units"]
    names = part["names"]
    for role in ("f", "E_storage", "E_loss", "T"):
        if role not in units:
            continue
        unit_read, conv_read = read[role]
        where = f"{path}, column {names[role]!r}"
        conv_new = unit_factor(role, units[role], where=where)
        key = "f_Hz" if role == "f" else ("T_C" if role == "T" else role)
        if role == "T":
            raw = part[key] + 273.15 if conv_read == "K" else part[key]
            part[key] = to_celsius(raw, conv_new)
        else:
            part[key] = part[key] / conv_read * conv_new
        read[role] = (units[role], conv_new)
    check_temperatures(part["T_C"], where=f"{path}, column {names['T']!r}", lines=part["line"],
                       trusted="T" in units)
    unit_E = read["E_storage"][0]
    origin = "units option" if "E_storage" in units else part["origins"].get("E_storage", "default")
    check_moduli(part["E_storage"], part["E_loss"],
                 where=f"{path}, columns {names['E_storage']!r} and {names['E_loss']!r}", unit=unit_E,
                 trusted="E_storage" in units, source_unit=origin)


def expand(path) -> list[Path]:
    """The files behind ``path``: a file, a folder (its ``*.csv`` and ``*.txt``, in natural order) or a list."""
    if isinstance(path, (str, os.PathLike)):
        p = Path(path)
        if p.is_dir():
            files = sorted([q for q in p.iterdir() if q.suffix.lower() in (".csv", ".txt") and q.is_file()],
                           key=natural_key)
            if not files:
                raise InputError(f"{p}: folder holds no *.csv or *.txt DMA files")
            return files
        if not p.exists():
            raise InputError(f"{p}: no such file")
        return [p]
    try:
        items = list(path)
    except TypeError:
        raise InputError(f"path: expected a file, a folder or a list of files, got {path!r}") from None
    if not items:
        raise InputError("path: empty list of files")
    out = []
    for item in items:
        out.extend(expand(item))
    return out


def natural_key(p: Path):
    """Sort key of a file name: T5 before T10; numbers with a sign compare numerically."""
    return [(0, float(t), "") if re.fullmatch(r"-?\d+(\.\d+)?", t) else (1, 0.0, t)
            for t in re.split(r"(-?\d+(?:\.\d+)?)", p.stem) if t]


def condense_notes(notes):
    """One note per kind when many files say the same thing (Latin-1, trailing line, nominal temperature)."""
    kinds = {"latin": [], "trailing": [], "nominal": []}
    out = []
    for n in notes:
        if "decoded as Latin-1" in n:
            kinds["latin"].append(n.split(":")[0])
        elif "trailing non-data line ignored" in n:
            kinds["trailing"].append(n.split(",")[0])
        elif "nominal temperature" in n:
            kinds["nominal"].append(n)
        else:
            out.append(n)
    if len(kinds["latin"]) > 2:
        out.insert(0, f"{len(kinds['latin'])} files decoded as Latin-1 (not valid UTF-8)")
    else:
        out[:0] = [f"{f}: decoded as Latin-1 (not valid UTF-8)" for f in kinds["latin"]]
    if len(kinds["trailing"]) > 2:
        out.append(f"a trailing non-data line (sample name) ignored in {len(kinds['trailing'])} files")
    else:
        out.extend(n for n in notes if "trailing non-data line ignored" in n)
    if len(kinds["nominal"]) > 2:
        nominal = [re.search(r"nominal temperature (\S+) C", n).group(1) for n in kinds["nominal"]]
        out.append("nominal temperatures from the file names: " + ", ".join(nominal)
                   + " C; the isotherms use the measured temperatures")
    else:
        out.extend(kinds["nominal"])
    return out


# ==================================================================================================== parsers

def _detect(path: Path, content) -> str:
    header = content[0][1]
    if "," in header:
        names = [c.strip().lower() for c in header.split(",")]
        if "t_c" in names or "f_hz" in names:
            return "long"
        if len(content) > 1 and not is_numeric_row(content[1][1].split(",")):
            return "pyvisco"
        return "long"
    names = header.split()
    if "f" in names and any(n in names for n in ("E'", "G'", "E\"", "G\"")):
        return "eplexor"
    raise InputError(f"{path}, line {content[0][0]}: unrecognised DMA format: expected a CSV header "
                     "'T_C,f_Hz,E_storage_Pa,E_loss_Pa', a pyvisco two-row header, or an Eplexor export "
                     f"(columns f, E', E\"); got {header.strip()[:80]!r}")


def _parse_long(path, content) -> dict:
    header_line, header = content[0]
    names = [c.strip() for c in header.split(",")]
    jT = column_of(path, names, "T_C")
    jf = column_of(path, names, "f_Hz")
    jE1 = column_of(path, names, "E_storage_Pa", required=False)
    shear = False
    if jE1 is None:
        jG1 = column_of(path, names, "G_storage_Pa", required=False)
        if jG1 is None:
            raise InputError(f"{path}: missing column 'E_storage_Pa' (or 'G_storage_Pa' for shear data); "
                             f"found columns: {', '.join(names)}")
        jE1, jE2, shear = jG1, column_of(path, names, "G_loss_Pa"), True
    else:
        jE2 = column_of(path, names, "E_loss_Pa")
    js = column_of(path, names, "strain", required=False)
    ji = column_of(path, names, "isotherm", required=False)
    rows = content[1:]
    if not rows:
        raise InputError(f"{path}: no data rows after the header on line {header_line}")
    data = parse_rows(path, rows, names, ",")
    return {"T_C": data[:, jT], "f_Hz": data[:, jf], "E_storage": data[:, jE1], "E_loss": data[:, jE2],
            "strain": None if js is None else data[:, js], "isotherm": None if ji is None else
            _labels(path, data[:, ji], rows, "isotherm"),
            "line": np.array([r[0] for r in rows]), "shear": shear,
            "names": {"T": names[jT], "f": names[jf], "E_storage": names[jE1], "E_loss": names[jE2]},
            "units": {"T": ("C", "C"), "f": ("Hz", 1.0), "E_storage": ("Pa", 1.0), "E_loss": ("Pa", 1.0)},
            "origins": {"E_storage": "column name"}}


def _labels(path, values, rows, name):
    bad = ~np.isfinite(values)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise InputError(f"{path}, line {rows[i][0]}, column {name!r}: expected an isotherm label (integer)")
    return values.astype(int)


def _parse_pyvisco(path, content) -> dict:
    names = [c.strip() for c in content[0][1].split(",")]
    if len(content) < 3:
        raise InputError(f"{path}: expected a names row, a units row and data rows (pyvisco CSV)")
    units = [c.strip() for c in content[1][1].split(",")]
    units += [""] * (len(names) - len(units))
    if column_of(path, names, "t", required=False) is not None and column_of(path, names, "f", required=False) is None:
        raise InputError(f"{path}: time-domain pyvisco data (column 't'); expected frequency-domain columns "
                         "f, E_stor, E_loss, T")
    jf = column_of(path, names, "f", "omega")
    jT = column_of(path, names, "T")
    j1 = column_of(path, names, "E_stor", required=False)
    shear = False
    if j1 is None:
        j1 = column_of(path, names, "G_stor", required=False)
        if j1 is None:
            raise InputError(f"{path}: missing column 'E_stor' (or 'G_stor'); found columns: {', '.join(names)}")
        j2, shear = column_of(path, names, "G_loss"), True
    else:
        j2 = column_of(path, names, "E_loss")
    jset = column_of(path, names, "Set", required=False)
    rows = content[2:]
    data = parse_rows(path, rows, names, ",")
    out = _converted(path, data, names, units, jf, j1, j2, jT)
    out.update({"strain": None, "isotherm": None if jset is None else _labels(path, data[:, jset], rows, names[jset]),
                "line": np.array([r[0] for r in rows]), "shear": shear})
    return out


def _parse_eplexor(path, content) -> dict:
    names = content[0][1].split()
    if len(content) < 3:
        raise InputError(f"{path}: expected a names row, a units row and data rows (Eplexor export)")
    units = [u.strip("[]") for u in content[1][1].split()]
    if len(units) != len(names):
        raise InputError(f"{path}, line {content[1][0]}: {len(units)} units for {len(names)} columns")
    jf = column_of(path, names, "f")
    jT = column_of(path, names, "Ts", "T", "Temp")
    shear = False
    j1 = column_of(path, names, "E'", required=False)
    if j1 is None:
        j1 = column_of(path, names, "G'", required=False)
        if j1 is None:
            raise InputError(f"{path}: missing column \"E'\" (or \"G'\"); found columns: {', '.join(names)}")
        j2, shear = column_of(path, names, 'G"', "G''"), True
    else:
        j2 = column_of(path, names, 'E"', "E''")
    rows = content[2:]
    # a trailing line that is not a data row (instrument sample name) is ignored and noted
    notes = []
    while rows and len(rows[-1][1].split()) != len(names) and not is_numeric_row(rows[-1][1].split()):
        notes.append(f"{path.name}, line {rows[-1][0]}: trailing non-data line ignored ({rows[-1][1].strip()[:40]!r})")
        rows = rows[:-1]
    if not rows:
        raise InputError(f"{path}: no data rows")
    data = parse_rows(path, rows, names, None)
    out = _converted(path, data, names, units, jf, j1, j2, jT)
    T = out["T_C"]
    m = re.search(r"T_?(-?\d+(?:\.\d+)?)", path.stem)
    if m:
        notes.append(f"{path.name}: nominal temperature {m.group(1)} C (from the file name); measured "
                     f"{np.nanmin(T):.2f} to {np.nanmax(T):.2f} C")
    out.update({"strain": None, "isotherm": np.zeros(len(rows), dtype=int), "line": np.array([r[0] for r in rows]),
                "shear": shear, "notes": notes})
    return out


def _converted(path, data, names, units, jf, j1, j2, jT) -> dict:
    """Columns of a file with a units row, in Hz, Pa and deg C, and the unit each was read in."""
    ff = _freq_factor(path, names[jf], units[jf])
    m1 = _modulus_factor(path, names[j1], units[j1], default="MPa")
    m2 = _modulus_factor(path, names[j2], units[j2], default="MPa")
    T = _to_celsius(path, names[jT], units[jT], data[:, jT])
    kind = "K" if (units[jT] or "").strip().lower() in ("k", "kelvin") else "C"
    return {"T_C": T, "f_Hz": data[:, jf] * ff, "E_storage": data[:, j1] * m1, "E_loss": data[:, j2] * m2,
            "names": {"T": names[jT], "f": names[jf], "E_storage": names[j1], "E_loss": names[j2]},
            "units": {"T": (units[jT] or "C", kind), "f": (units[jf] or "Hz", ff),
                      "E_storage": (units[j1] or "MPa", m1), "E_loss": (units[j2] or "MPa", m2)},
            "origins": {"E_storage": "units row" if (units[j1] or "").strip() not in ("", "-") else "default"}}


def _modulus_factor(path, name, unit, default):
    u = (unit or default).strip().lower().replace(" ", "")
    if u in ("", "-"):
        u = default.lower()
    if u not in _PRESSURE_UNITS:
        raise InputError(f"{path}: column {name!r}: unknown modulus unit {unit!r} (expected Pa, kPa, MPa or GPa)")
    return _PRESSURE_UNITS[u]


def _freq_factor(path, name, unit):
    u = (unit or "").strip().lower().replace(" ", "")
    if name.lower() == "omega" or u in ("rad/s", "1/s"):
        return 1.0 / (2.0 * np.pi)
    if u in ("hz", "", "-"):
        return 1.0
    if u == "khz":
        return 1e3
    raise InputError(f"{path}: column {name!r}: unknown frequency unit {unit!r} (expected Hz or rad/s)")


def _to_celsius(path, name, unit, T):
    u = (unit or "").strip().replace("\u00b0", "").replace("º", "").strip().lower()
    if u in ("c", "degc", "", "-", "celsius"):
        return T
    if u in ("k", "kelvin"):
        return T - 273.15
    raise InputError(f"{path}: column {name!r}: unknown temperature unit {unit!r} (expected C or K)")
