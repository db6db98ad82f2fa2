"""DMA frequency sweeps: the :class:`DMAData` container and the readers for the supported file formats.

Formats (described for users in ``docs/materials.md``; parsed in :mod:`materials._dma_formats`): the project's
long table ``T_C, f_Hz, E_storage_Pa, E_loss_Pa`` (optional ``strain`` and ``isotherm`` columns; shear data as
``G_storage_Pa, G_loss_Pa``), pyvisco's two-header-row CSV, and Eplexor text exports (one isotherm per file).

Every reader returns Young's moduli in Pa; shear moduli are converted with :math:`E = 2(1+\\nu) G` and the
result says so (``DMAData.shear_converted``, ``DMAData.notes``). Likely unit slips are refused with a message
naming the file and column (:mod:`materials.units`): moduli in MPa under ``_Pa`` headers, temperatures in
kelvin, an isotherm below absolute zero; ``units=`` declares the units when the file's own are wrong or absent.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Sequence

import numpy as np

from ._dma_formats import apply_units, condense_notes, expand, read_part
from ._io import write_csv_atomic
from .errors import DataWarning, InputError
from .units import check_moduli, check_temperatures, normalise_units

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
            warnings.warn(msg, DataWarning, stacklevel=2)
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
            warnings.warn(msg, DataWarning, stacklevel=2)
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
        with warnings.catch_warnings():      # what the data say was said when they were read
            warnings.simplefilter("ignore", DataWarning)
            out = DMAData.from_arrays(
                self.T_C[mask], self.f_Hz[mask], self.E_storage[mask], self.E_loss[mask],
                strain=None if self.strain is None else self.strain[mask], isotherm=self.isotherm[mask],
                source=self.source, line=self.line[mask], notes=self.notes)
        return replace(out, shear_converted=self.shear_converted, poisson=self.poisson)

    def to_csv(self, path, *, overwrite: bool = False) -> Path:
        """Write the long DMA table ``T_C, f_Hz, E_storage_Pa, E_loss_Pa[, strain]`` atomically (docs/materials.md);
        an existing file only with ``overwrite=True``."""
        cols = {"T_C": self.T_C, "f_Hz": self.f_Hz, "E_storage_Pa": self.E_storage, "E_loss_Pa": self.E_loss}
        if self.strain is not None:
            cols["strain"] = self.strain
        comments = [f"DMA data from {self.source}"] + list(self.notes)
        return write_csv_atomic(path, cols, comments=comments, overwrite=overwrite)


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
    paths = expand(path)
    units = normalise_units(units)
    parts = []
    for p in paths:
        part = read_part(p, format=format, encoding=encoding)
        apply_units(p, part, units)
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
    notes = condense_notes(notes)
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
                      + "; ".join(messages), DataWarning, stacklevel=3)
    return bad


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
