"""DMA frequency sweeps: the :class:`DMAData` container and the readers for the supported file formats.

Formats (described for users in ``docs/materials.md``):

* **long table** (the project's own): CSV with a header row ``T_C, f_Hz, E_storage_Pa, E_loss_Pa`` and an
  optional ``strain`` column (strain amplitude, dimensionless) and optional ``isotherm`` column; shear data may
  be given as ``G_storage_Pa, G_loss_Pa`` instead. Lines starting with ``#`` are comments.
* **pyvisco** CSV: two header rows, names (``f, E_stor, E_loss, T, Set``; or ``G_stor, G_loss``) then units
  (``Hz, MPa, MPa, C, -``).
* **Eplexor** text export: whitespace-separated columns, a names row (``Index Ts t f ... E' E" ...``) then a
  units row in brackets (``[Hz]``, ``[MPa]``, ``[°C]`` with a Latin-1 degree sign); one isotherm per file, the
  file name carrying the nominal temperature (``T20.txt``); a trailing non-numeric line is ignored.

Every reader returns Young's moduli in Pa; shear moduli are converted with :math:`E = 2(1+\\nu) G` and the
result says so (``DMAData.shear_converted``, ``DMAData.notes``). Likely unit slips are refused with a message
naming the file and column (:mod:`materials.units`): moduli in MPa under ``_Pa`` headers, temperatures in
kelvin, an isotherm below absolute zero; ``units=`` declares the units when the file's own are wrong or absent.
"""

from __future__ import annotations

import os
import re
import warnings
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Sequence

import numpy as np

from .errors import InputError
from .units import check_moduli, check_temperatures, normalise_units, to_celsius, unit_factor

__all__ = ["DMAData", "read_dma", "read_dma_long", "read_pyvisco", "read_eplexor"]

#: Temperature spread (K) within one isotherm above which a warning is given (the data are kept).
DRIFT_WARN_K = 2.0


@dataclass(frozen=True, eq=False, repr=False)
class DMAData:
    """DMA frequency sweeps (isotherms) as Young's moduli, one row per measured point.

    Build with :meth:`from_arrays` (validates) or a reader (:func:`read_dma`). Arrays are read-only.

    Attributes
    ----------
    T_C : ndarray
        Measured temperature of each point, deg C.
    f_Hz : ndarray
        Frequency of each point, Hz (> 0).
    E_storage, E_loss : ndarray
        Storage and loss Young's moduli E', E'', Pa (> 0).
    isotherm : ndarray of int
        Isotherm index of each point, 0 .. n_isotherms-1 in order of increasing temperature.
    T_isotherm : ndarray
        Temperature of each isotherm, deg C (median of its measured temperatures).
    strain : ndarray or None
        Strain amplitude of each point (dimensionless), when the source has one.
    source : str
        File name(s) or ``"<arrays>"``; used in messages.
    line : ndarray of int
        Line number of each point in its source file (1-based; 0 for arrays), used in messages.
    shear_converted : bool
        True when the source held shear moduli G', G'' converted here with E = 2(1+nu)G.
    poisson : float or None
        The Poisson ratio used for that conversion.
    notes : tuple of str
        What was done to the data on reading (conversions, encoding, dropped rows).
    """

    T_C: np.ndarray
    f_Hz: np.ndarray
    E_storage: np.ndarray
    E_loss: np.ndarray
    isotherm: np.ndarray
    T_isotherm: np.ndarray
    strain: np.ndarray | None = None
    source: str = "<arrays>"
    line: np.ndarray | None = None
    shear_converted: bool = False
    poisson: float | None = None
    notes: tuple[str, ...] = ()

    # ---------------------------------------------------------------- construction
    @classmethod
    def from_arrays(cls, T_C, f_Hz, E_storage, E_loss, *, strain=None, isotherm=None, source="<arrays>",
                    line=None, shear=False, poisson=0.5, isotherm_tol=1.0, drop_bad=False,
                    notes: Sequence[str] = (), check_units: bool = True) -> "DMAData":
        """Validate point arrays and group them into isotherms.

        Parameters
        ----------
        T_C, f_Hz, E_storage, E_loss : array_like
            Temperature (deg C), frequency (Hz), storage and loss modulus (Pa) of each point. With
            ``shear=True`` the moduli are shear moduli G', G'' and are converted to Young's moduli.
        strain : array_like, optional
            Strain amplitude of each point (dimensionless, > 0).
        isotherm : array_like of int, optional
            Isotherm label of each point (e.g. pyvisco's ``Set``). Without it, points are grouped by temperature:
            sorted temperatures separated by more than ``isotherm_tol`` K start a new isotherm.
        source : str
            Name used in messages.
        line : array_like of int, optional
            Line number of each point in the source file (for messages).
        shear : bool
            The moduli are shear moduli; E = 2(1+nu)G is applied.
        poisson : float
            Poisson ratio nu for the shear conversion (-1 < nu <= 0.5).
        isotherm_tol : float
            Gap in temperature (K) that separates isotherms when ``isotherm`` is not given.
        drop_bad : bool
            False (default): a non-finite value, a non-positive frequency or modulus raises :class:`InputError`.
            True: such rows are dropped with a warning naming them.
        notes : sequence of str
            Notes to keep (e.g. from the reader).
        check_units : bool
            Refuse moduli outside any polymer's range (MPa passed as Pa) and temperatures that look like
            kelvin (:mod:`materials.units`). Temperatures below absolute zero are always refused.

        Raises
        ------
        InputError
            Naming the source, the line and the column of the first bad value or likely unit slip.
        """
        notes = list(notes)
        cols = {"T_C": T_C, "f_Hz": f_Hz, "E_storage": E_storage, "E_loss": E_loss}
        arr = {}
        for name, v in cols.items():
            try:
                arr[name] = np.array(v, dtype=float).ravel()
            except (TypeError, ValueError):
                raise InputError(f"{source}: column {name!r}: expected numbers") from None
        n = arr["T_C"].size
        for name, a in arr.items():
            if a.size != n:
                raise InputError(f"{source}: column {name!r} has {a.size} values, expected {n} (as T_C)")
        if n == 0:
            raise InputError(f"{source}: no data rows (expected columns T_C, f_Hz, E_storage_Pa, E_loss_Pa)")
        line = np.zeros(n, dtype=int) if line is None else np.asarray(line, dtype=int).ravel()
        if line.size != n:
            raise InputError(f"{source}: 'line' has {line.size} values, expected {n}")
        if strain is not None:
            strain = np.array(strain, dtype=float).ravel()
            if strain.size != n:
                raise InputError(f"{source}: column 'strain' has {strain.size} values, expected {n}")
            arr["strain"] = strain
        if isotherm is not None:
            isotherm = np.asarray(isotherm).ravel()
            if isotherm.size != n:
                raise InputError(f"{source}: column 'isotherm' has {isotherm.size} values, expected {n}")

        # --- unit slips and impossible temperatures
        check_temperatures(arr["T_C"], where=f"{source}, column 'T_C'", lines=line, trusted=not check_units)
        if check_units:
            check_moduli(arr["E_storage"], arr["E_loss"], where=f"{source}, columns 'E_storage', 'E_loss'",
                         unit="Pa")

        # --- bad values: raise (naming line and column) or drop with a warning
        bad = _screen(source, line, arr, drop_bad)
        if bad.any():
            notes.append(f"dropped {int(bad.sum())} bad rows ({_row_list(line, np.flatnonzero(bad))})")
            keep = ~bad
            arr = {k: a[keep] for k, a in arr.items()}
            line = line[keep]
            if isotherm is not None:
                isotherm = isotherm[keep]
            n = int(keep.sum())
            if n == 0:
                raise InputError(f"{source}: no valid data rows left")

        if shear:
            if not (isinstance(poisson, (int, float)) and -1.0 < poisson <= 0.5):
                raise InputError(f"poisson: expected -1 < nu <= 0.5 for the shear conversion, got {poisson!r}")
            factor = 2.0 * (1.0 + poisson)
            arr["E_storage"] = arr["E_storage"] * factor
            arr["E_loss"] = arr["E_loss"] * factor
            notes.append(f"shear moduli G', G'' converted to Young's moduli E = 2(1+nu)G with nu = {poisson:g}")

        # --- isotherms: by label, or by gaps in temperature
        T = arr["T_C"]
        if isotherm is None:
            if not (isotherm_tol > 0):
                raise InputError(f"isotherm_tol: expected a positive temperature gap in K, got {isotherm_tol!r}")
            order = np.argsort(T, kind="stable")
            new_group = np.concatenate([[0], np.diff(T[order]) > isotherm_tol]).astype(int)
            labels = np.empty(n, dtype=int)
            labels[order] = np.cumsum(new_group)
        else:
            _, labels = np.unique(isotherm, return_inverse=True)
        n_iso = int(labels.max()) + 1
        T_iso = np.array([np.median(T[labels == k]) for k in range(n_iso)])
        rank = np.empty(n_iso, dtype=int)
        rank[np.argsort(T_iso, kind="stable")] = np.arange(n_iso)
        labels = rank[labels]
        T_iso = np.sort(T_iso)

        # --- duplicates: identical rows are dropped, repeated (isotherm, f[, strain]) are averaged; both warned
        strain_arr = arr.get("strain")
        key_cols = [labels.astype(float), arr["f_Hz"]] + ([strain_arr] if strain_arr is not None else [])
        keys = np.stack(key_cols, axis=1)
        uniq, first, inverse, counts = np.unique(keys, axis=0, return_index=True, return_inverse=True,
                                                 return_counts=True)
        inverse = inverse.ravel()
        if np.any(counts > 1):
            dup_groups = np.flatnonzero(counts > 1)
            values = np.stack([arr["T_C"], arr["E_storage"], arr["E_loss"]], axis=1)
            identical = [np.all(values[inverse == g] == values[inverse == g][0]) for g in dup_groups]
            dup_rows = np.flatnonzero(np.isin(inverse, dup_groups) & ~np.isin(np.arange(n), first))
            kind = "identical duplicate rows dropped" if all(identical) else \
                "rows repeating the same isotherm and frequency averaged"
            msg = f"{source}: {kind} ({_row_list(line, dup_rows)})"
            warnings.warn(msg, stacklevel=2)
            notes.append(msg)
            # average in log space (moduli) and linear (temperature); keep the first line number
            sums = lambda a: np.bincount(inverse, weights=a, minlength=uniq.shape[0]) / counts
            order_first = first
            new = {"T_C": sums(arr["T_C"]), "f_Hz": arr["f_Hz"][order_first],
                   "E_storage": np.exp(sums(np.log(arr["E_storage"]))),
                   "E_loss": np.exp(sums(np.log(arr["E_loss"])))}
            if strain_arr is not None:
                new["strain"] = strain_arr[order_first]
            # restore file order
            fo = np.argsort(order_first, kind="stable")
            arr = {k: v[fo] for k, v in new.items()}
            labels = labels[order_first][fo]
            line = line[order_first][fo]

        # --- temperature drift inside an isotherm: kept, but said
        drift = []
        for k in range(n_iso):
            Tk = arr["T_C"][labels == k]
            if Tk.max() - Tk.min() > DRIFT_WARN_K:
                drift.append(f"{T_iso[k]:.1f} C (spread {Tk.max() - Tk.min():.1f} K)")
        if drift:
            msg = (f"{source}: temperature drifts by more than {DRIFT_WARN_K:g} K within isotherm(s) "
                   + ", ".join(drift) + "; each isotherm is assigned its median temperature")
            warnings.warn(msg, stacklevel=2)
            notes.append(msg)

        frozen = {k: _ro(v) for k, v in arr.items()}
        return cls(T_C=frozen["T_C"], f_Hz=frozen["f_Hz"], E_storage=frozen["E_storage"],
                   E_loss=frozen["E_loss"], isotherm=_ro(labels), T_isotherm=_ro(T_iso),
                   strain=frozen.get("strain"), source=source, line=_ro(line), shear_converted=bool(shear),
                   poisson=float(poisson) if shear else None, notes=tuple(notes))

    # ---------------------------------------------------------------- views
    def __len__(self) -> int:
        return int(self.f_Hz.size)

    def __repr__(self) -> str:
        strain = "" if self.strain is None else f", strain {self.strain.min():.3g} to {self.strain.max():.3g}"
        return (f"DMAData({len(self)} points, {self.n_isotherms} isotherms {self.T_isotherm.min():.4g} to "
                f"{self.T_isotherm.max():.4g} C, {self.f_Hz.min():.3g} to {self.f_Hz.max():.3g} Hz{strain}"
                + (", shear converted" if self.shear_converted else "") + f", {self.source})")

    @property
    def n_isotherms(self) -> int:
        """Number of isotherms."""
        return int(self.T_isotherm.size)

    @property
    def omega(self) -> np.ndarray:
        """Angular frequency of each point, rad/s."""
        return 2.0 * np.pi * self.f_Hz

    @property
    def tan_delta(self) -> np.ndarray:
        """Loss factor E''/E' of each point."""
        return self.E_loss / self.E_storage

    @property
    def E(self) -> np.ndarray:
        """Complex Young's modulus E' + i E'' of each point, Pa."""
        return self.E_storage + 1j * self.E_loss

    def isotherm_indices(self) -> list[np.ndarray]:
        """Point indices of each isotherm (sorted by frequency), in order of increasing temperature."""
        out = []
        for k in range(self.n_isotherms):
            idx = np.flatnonzero(self.isotherm == k)
            out.append(idx[np.argsort(self.f_Hz[idx], kind="stable")])
        return out

    def select(self, mask) -> "DMAData":
        """A new DMAData with the points where ``mask`` is true (isotherms renumbered)."""
        mask = np.asarray(mask, dtype=bool)
        if mask.shape != self.f_Hz.shape:
            raise InputError(f"select: mask must have shape {self.f_Hz.shape}, got {mask.shape}")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out = DMAData.from_arrays(
                self.T_C[mask], self.f_Hz[mask], self.E_storage[mask], self.E_loss[mask],
                strain=None if self.strain is None else self.strain[mask], isotherm=self.isotherm[mask],
                source=self.source, line=self.line[mask], notes=self.notes)
        return replace(out, shear_converted=self.shear_converted, poisson=self.poisson)

    def to_csv(self, path) -> Path:
        """Write the long DMA table ``T_C, f_Hz, E_storage_Pa, E_loss_Pa[, strain]`` atomically (docs/materials.md)."""
        from ._io import write_csv_atomic
        cols = {"T_C": self.T_C, "f_Hz": self.f_Hz, "E_storage_Pa": self.E_storage, "E_loss_Pa": self.E_loss}
        if self.strain is not None:
            cols["strain"] = self.strain
        comments = [f"DMA data from {self.source}"] + list(self.notes)
        return write_csv_atomic(path, cols, comments=comments)


# ==================================================================================================== readers

def read_dma(path, *, format: str | None = None, poisson: float = 0.5, encoding: str | None = None,
             isotherm_tol: float = 1.0, drop_bad: bool = False, units=None) -> DMAData:
    """Read DMA frequency sweeps from a file, a list of files or a folder of files.

    Parameters
    ----------
    path : str, Path or sequence of them
        A file; a folder (all ``*.csv`` and ``*.txt`` files in it, e.g. one Eplexor export per isotherm);
        or a list of files. Points from several files are combined (each Eplexor file is one isotherm).
    format : {"long", "pyvisco", "eplexor"}, optional
        Force a format; by default it is recognised from the header.
    poisson : float
        Poisson ratio used to convert shear moduli G to Young's moduli, E = 2(1+nu)G.
    encoding : str, optional
        Text encoding. By default UTF-8 (with or without BOM) is tried, then Latin-1 (Eplexor exports).
    isotherm_tol : float
        Temperature gap (K) separating isotherms where the file has no isotherm label.
    drop_bad : bool
        Drop rows with non-finite, non-positive frequency or modulus (with a warning) instead of raising.
    units : mapping, optional
        The units of the columns, overriding the file's: ``{"E": "MPa", "T": "K", "f": "rad/s"}`` (keys ``f``,
        ``E`` or ``E_storage``/``E_loss``, ``T``). Declared units skip the range checks that catch unit slips.

    Returns
    -------
    DMAData

    Raises
    ------
    InputError
        Missing file or column, unreadable bytes, a bad value (naming file, line and column), a likely unit
        slip (moduli in MPa under a ``_Pa`` header, temperatures in kelvin, below absolute zero).
    """
    paths = _expand(path)
    units = normalise_units(units)
    parts = []
    for p in paths:
        part = _read_one(p, format=format, encoding=encoding)
        _apply_units(p, part, units)
        parts.append(part)
    if len(paths) == 1:
        source = str(paths[0])
    elif len({p.parent for p in paths}) == 1:
        source = f"{paths[0].parent}/ ({len(paths)} files: {paths[0].name} ... {paths[-1].name})"
    else:
        source = f"{len(paths)} files ({paths[0]} ... {paths[-1]})"
    cols: dict[str, list] = {"T_C": [], "f_Hz": [], "E_storage": [], "E_loss": [], "line": [], "iso": [],
                             "strain": []}
    shear = {part["shear"] for part in parts}
    if len(shear) > 1:
        raise InputError(f"{source}: files mix shear (G) and Young's (E) moduli; read them separately")
    has_strain = {part["strain"] is not None for part in parts}
    if len(has_strain) > 1:
        raise InputError(f"{source}: some files have a 'strain' column and some do not")
    notes = []
    offset = 0
    for p, part in zip(paths, parts):
        bad = _screen(str(p), part["line"], part, drop_bad)
        if bad.any():
            notes.append(f"{p.name}: dropped {int(bad.sum())} bad rows ({_row_list(part['line'], np.flatnonzero(bad))})")
            for k in ("T_C", "f_Hz", "E_storage", "E_loss", "line", "strain", "isotherm"):
                if part.get(k) is not None:
                    part[k] = np.asarray(part[k])[~bad]
            if part["line"].size == 0:
                raise InputError(f"{p}: no valid data rows left")
        for k in ("T_C", "f_Hz", "E_storage", "E_loss", "line"):
            cols[k].append(part[k])
        iso = part["isotherm"]
        if iso is None:
            iso = _group_by_temperature(part["T_C"], isotherm_tol)
        cols["iso"].append(np.asarray(iso, dtype=int) + offset)
        offset += int(np.max(iso)) + 1
        if part["strain"] is not None:
            cols["strain"].append(part["strain"])
        notes.extend(part["notes"])
    cat = {k: np.concatenate(v) if v else None for k, v in cols.items()}
    notes = _condense_notes(notes)
    return DMAData.from_arrays(cat["T_C"], cat["f_Hz"], cat["E_storage"], cat["E_loss"],
                               strain=cat["strain"], isotherm=cat["iso"], source=source, line=cat["line"],
                               shear=shear.pop(), poisson=poisson, drop_bad=drop_bad, notes=notes,
                               check_units=False)


def read_dma_long(path, **kw) -> DMAData:
    """Read the long DMA table (docs/materials.md); see :func:`read_dma` for the keywords."""
    return read_dma(path, format="long", **kw)


def read_pyvisco(path, **kw) -> DMAData:
    """Read a pyvisco two-header-row CSV (frequency domain); see :func:`read_dma` for the keywords."""
    return read_dma(path, format="pyvisco", **kw)


def read_eplexor(path, **kw) -> DMAData:
    """Read Eplexor text exports (a file, a list or a folder); see :func:`read_dma` for the keywords."""
    return read_dma(path, format="eplexor", **kw)


# ==================================================================================================== helpers

_PRESSURE_UNITS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9, "n/m2": 1.0, "n/mm2": 1e6, "n/mm^2": 1e6}


def _apply_units(path: Path, part: dict, units: dict) -> None:
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


def _expand(path) -> list[Path]:
    if isinstance(path, (str, os.PathLike)):
        p = Path(path)
        if p.is_dir():
            files = sorted([q for q in p.iterdir() if q.suffix.lower() in (".csv", ".txt") and q.is_file()],
                           key=_natural_key)
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
        out.extend(_expand(item))
    return out


def _natural_key(p: Path):
    # T5 before T10; numbers with a sign compare numerically
    return [(0, float(t), "") if re.fullmatch(r"-?\d+(\.\d+)?", t) else (1, 0.0, t)
            for t in re.split(r"(-?\d+(?:\.\d+)?)", p.stem) if t]


def _decode(path: Path, encoding: str | None) -> tuple[str, list[str]]:
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


def _read_one(path: Path, *, format: str | None, encoding: str | None) -> dict:
    text, notes = _decode(path, encoding)
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


def _detect(path: Path, content) -> str:
    header = content[0][1]
    if "," in header:
        names = [c.strip().lower() for c in header.split(",")]
        if "t_c" in names or "f_hz" in names:
            return "long"
        if len(content) > 1 and not _is_numeric_row(content[1][1].split(",")):
            return "pyvisco"
        return "long"
    names = header.split()
    if "f" in names and any(n in names for n in ("E'", "G'", "E\"", "G\"")):
        return "eplexor"
    raise InputError(f"{path}, line {content[0][0]}: unrecognised DMA format: expected a CSV header "
                     "'T_C,f_Hz,E_storage_Pa,E_loss_Pa', a pyvisco two-row header, or an Eplexor export "
                     f"(columns f, E', E\"); got {header.strip()[:80]!r}")


def _is_numeric_row(cells) -> bool:
    try:
        [float(c) for c in cells if c.strip()]
        return any(c.strip() for c in cells)
    except ValueError:
        return False


def _table(path: Path, rows, names, sep) -> np.ndarray:
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


def _col(path, names, *candidates, required=True):
    low = [n.lower() for n in names]
    for cand in candidates:
        if cand.lower() in low:
            return low.index(cand.lower())
    if required:
        raise InputError(f"{path}: missing column {candidates[0]!r} (found columns: {', '.join(names)})")
    return None


def _parse_long(path, content) -> dict:
    header_line, header = content[0]
    names = [c.strip() for c in header.split(",")]
    jT = _col(path, names, "T_C")
    jf = _col(path, names, "f_Hz")
    jE1 = _col(path, names, "E_storage_Pa", required=False)
    shear = False
    if jE1 is None:
        jG1 = _col(path, names, "G_storage_Pa", required=False)
        if jG1 is None:
            raise InputError(f"{path}: missing column 'E_storage_Pa' (or 'G_storage_Pa' for shear data); "
                             f"found columns: {', '.join(names)}")
        jE1, jE2, shear = jG1, _col(path, names, "G_loss_Pa"), True
    else:
        jE2 = _col(path, names, "E_loss_Pa")
    js = _col(path, names, "strain", required=False)
    ji = _col(path, names, "isotherm", required=False)
    rows = content[1:]
    if not rows:
        raise InputError(f"{path}: no data rows after the header on line {header_line}")
    data = _table(path, rows, names, ",")
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
    if _col(path, names, "t", required=False) is not None and _col(path, names, "f", required=False) is None:
        raise InputError(f"{path}: time-domain pyvisco data (column 't'); expected frequency-domain columns "
                         "f, E_stor, E_loss, T")
    jf = _col(path, names, "f", "omega")
    jT = _col(path, names, "T")
    j1 = _col(path, names, "E_stor", required=False)
    shear = False
    if j1 is None:
        j1 = _col(path, names, "G_stor", required=False)
        if j1 is None:
            raise InputError(f"{path}: missing column 'E_stor' (or 'G_stor'); found columns: {', '.join(names)}")
        j2, shear = _col(path, names, "G_loss"), True
    else:
        j2 = _col(path, names, "E_loss")
    jset = _col(path, names, "Set", required=False)
    rows = content[2:]
    data = _table(path, rows, names, ",")
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
    jf = _col(path, names, "f")
    jT = _col(path, names, "Ts", "T", "Temp")
    shear = False
    j1 = _col(path, names, "E'", required=False)
    if j1 is None:
        j1 = _col(path, names, "G'", required=False)
        if j1 is None:
            raise InputError(f"{path}: missing column \"E'\" (or \"G'\"); found columns: {', '.join(names)}")
        j2, shear = _col(path, names, 'G"', "G''"), True
    else:
        j2 = _col(path, names, 'E"', "E''")
    rows = content[2:]
    # a trailing line that is not a data row (instrument sample name) is ignored and noted
    notes = []
    while rows and len(rows[-1][1].split()) != len(names) and not _is_numeric_row(rows[-1][1].split()):
        notes.append(f"{path.name}, line {rows[-1][0]}: trailing non-data line ignored ({rows[-1][1].strip()[:40]!r})")
        rows = rows[:-1]
    if not rows:
        raise InputError(f"{path}: no data rows")
    data = _table(path, rows, names, None)
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


def _group_by_temperature(T, tol):
    T = np.asarray(T, dtype=float)
    labels = np.zeros(T.size, dtype=int)
    finite = np.isfinite(T)
    if finite.any():
        order = np.argsort(np.where(finite, T, np.inf), kind="stable")
        Ts = T[order]
        gaps = np.concatenate([[0], (np.diff(Ts) > tol) & np.isfinite(Ts[1:])]).astype(int)
        labels[order] = np.cumsum(gaps)
    return labels


_CHECKS = (("T_C", "a finite temperature in deg C", False),
           ("f_Hz", "a positive frequency in Hz", True),
           ("E_storage", "a positive storage modulus", True),
           ("E_loss", "a positive loss modulus", True),
           ("strain", "a positive strain amplitude", True))


def _screen(source, line, arr, drop_bad) -> np.ndarray:
    """Rows with a non-finite value or a non-positive frequency, modulus or strain.

    Raises :class:`InputError` naming the first one, or (``drop_bad``) warns naming them and returns the mask.
    """
    n = arr["T_C"].size
    bad = np.zeros(n, dtype=bool)
    messages = []
    for name, expected, positive in _CHECKS:
        a = arr.get(name)
        if a is None:
            continue
        ok = np.isfinite(a) & (a > 0) if positive else np.isfinite(a)
        if not np.all(ok):
            idx = np.flatnonzero(~ok)
            msg = (f"{_where(source, line, idx[0])}, column {name!r}: expected {expected}, got {a[idx[0]]!r}"
                   + (f" ({idx.size} such rows)" if idx.size > 1 else ""))
            if not drop_bad:
                raise InputError(msg)
            bad |= ~ok
            messages.append(msg)
    if bad.any():
        warnings.warn(f"{source}: dropped {int(bad.sum())} bad rows ({_row_list(line, np.flatnonzero(bad))}): "
                      + "; ".join(messages), stacklevel=3)
    return bad


def _condense_notes(notes):
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


def _where(source, line, i) -> str:
    ln = int(line[i]) if line is not None else 0
    return f"{source}, line {ln}" if ln > 0 else f"{source}, row {i}"


def _row_list(line, idx, limit=8) -> str:
    idx = np.asarray(idx)
    labels = [f"line {int(line[i])}" if line[i] > 0 else f"row {int(i)}" for i in idx[:limit]]
    more = f" and {idx.size - limit} more" if idx.size > limit else ""
    return ", ".join(labels) + more


def _ro(a):
    a = np.asarray(a)
    a.setflags(write=False)
    return a
