r"""Strain softening (Payne effect): large-strain moduli from small-strain master curves and strain sweeps.

Persson's friction theory uses the small-strain (linear) modulus, but the rubber in asperity contacts is
strained by order unity; Lorenz et al. (2015) and Persson (2001) replace it by an effective large-strain
modulus obtained from DMA strain sweeps,

.. math:: E'(\omega, T; \varepsilon) = f(\varepsilon, T)\, E'(\omega, T),\qquad
          E''(\omega, T; \varepsilon) = g(\varepsilon, T)\, E''(\omega, T),

with :math:`f, g` the storage and loss moduli of a strain sweep at temperature T normalised by their
small-strain values, assumed independent of frequency (Lorenz et al. 2015, Sec. II).

* :func:`read_strain_sweep` reads strain sweeps (E', E'' against strain amplitude at one or more
  temperatures) from the usual exports; :class:`StrainSweep` holds them.
* :func:`strain_factors` turns them into :class:`StrainFactors`: f and g on a (temperature, strain) grid,
  evaluated by ``factors(strain, T)`` for arrays of any shape.
* :class:`StrainSoftening` (strain only) and :class:`StrainSoftened` (a material with constant factors) are the
  simpler forms.
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from frictioncite import doi

from ._dma_formats import expand, natural_key
from ._tables import pick_columns, read_table
from .dma import DMAData
from .errors import InputError
from .units import check_moduli, check_strains, check_temperatures, normalise_units

__all__ = ["StrainSoftening", "StrainSoftened", "strain_softening_from_sweep", "StrainSweep", "StrainFactors",
           "read_strain_sweep", "strain_factors"]


@doi("10.1063/1.4919221", "10.1063/1.1388626")
@dataclass(frozen=True, eq=False, repr=False)
class StrainSoftening:
    r"""Softening factors f(strain) on E' and g(strain) on E'' (1 at small strain).

    Interpolated linearly in :math:`\log\varepsilon`, held constant outside the tabulated strains.

    Attributes
    ----------
    strain : ndarray
        Strain amplitudes (dimensionless, > 0, increasing).
    storage_factor, loss_factor : ndarray
        f and g at those strains (> 0).
    source : str
        Where they come from.
    """

    strain: np.ndarray
    storage_factor: np.ndarray
    loss_factor: np.ndarray
    source: str = ""

    def __post_init__(self):
        s = np.array(self.strain, dtype=float).ravel()
        f = np.array(self.storage_factor, dtype=float).ravel()
        g = np.array(self.loss_factor, dtype=float).ravel()
        if not (s.size == f.size == g.size and s.size > 0):
            raise InputError(f"StrainSoftening: strain, storage_factor, loss_factor must have the same non-zero "
                             f"length, got {s.size}, {f.size}, {g.size}")
        for name, a in (("strain", s), ("storage_factor", f), ("loss_factor", g)):
            if not (np.all(np.isfinite(a)) and np.all(a > 0)):
                raise InputError(f"StrainSoftening.{name}: expected finite positive values, got {a}")
        order = np.argsort(s)
        s, f, g = s[order], f[order], g[order]
        if np.any(np.diff(s) == 0):
            raise InputError("StrainSoftening.strain: repeated strain amplitudes")
        for name, a in (("strain", s), ("storage_factor", f), ("loss_factor", g)):
            a.setflags(write=False)
            object.__setattr__(self, name, a)

    @classmethod
    def constant(cls, storage_factor: float, loss_factor: float) -> "StrainSoftening":
        """Strain-independent factors f, g (e.g. taken at the typical contact strain)."""
        return cls(np.array([1.0]), np.array([storage_factor]), np.array([loss_factor]), source="constant")

    def factors(self, strain):
        """(f, g) at strain amplitude(s) ``strain``."""
        e = np.asarray(strain, dtype=float)
        if not (np.all(np.isfinite(e)) and np.all(e > 0)):
            raise InputError(f"strain: expected positive strain amplitudes, got {strain!r}")
        if self.strain.size == 1:
            return np.full(e.shape, self.storage_factor[0]), np.full(e.shape, self.loss_factor[0])
        x = np.log(e)
        xs = np.log(self.strain)
        return np.interp(x, xs, self.storage_factor), np.interp(x, xs, self.loss_factor)

    def __repr__(self) -> str:
        if self.strain.size == 1:
            return f"StrainSoftening(constant f = {self.storage_factor[0]:.4g}, g = {self.loss_factor[0]:.4g})"
        return (f"StrainSoftening({self.strain.size} strains {self.strain[0]:.3g} to {self.strain[-1]:.3g}, f "
                f"{self.storage_factor.min():.3g}..{self.storage_factor.max():.3g}, g {self.loss_factor.min():.3g}.."
                f"{self.loss_factor.max():.3g}" + (f", {self.source}" if self.source else "") + ")")


@doi("10.1063/1.4919221", "10.1063/1.1388626")
@dataclass(frozen=True, eq=False, repr=False)
class StrainSoftened:
    r"""A material with E' scaled by ``storage_factor`` and E'' by ``loss_factor`` (large-strain modulus).

    .. math:: E_{\varepsilon}(\omega, T) = f\,\mathrm{Re}\,E(\omega, T) + i\, g\,\mathrm{Im}\,E(\omega, T)

    Exposes the same interface as the material it wraps: ``E(omega, T)``, ``thermal`` and, when the wrapped
    material has it, ``log10_aT`` (``hasattr`` is False otherwise).

    Parameters
    ----------
    material : object
        Anything with ``E(omega, T)``.
    storage_factor, loss_factor : float
        f and g (> 0).
    """

    material: object
    storage_factor: float = 1.0
    loss_factor: float = 1.0

    def __post_init__(self):
        if not callable(getattr(self.material, "E", None)):
            raise InputError("StrainSoftened: material must have a method E(omega, T)")
        for name in ("storage_factor", "loss_factor"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float, np.floating)) and math.isfinite(v) and v > 0):
                raise InputError(f"StrainSoftened.{name}: expected a positive number, got {v!r}")

    @classmethod
    def from_softening(cls, material, softening, strain: float, T: float | None = None) -> "StrainSoftened":
        """Factors f, g of ``softening`` (a :class:`StrainSoftening`, or :class:`StrainFactors` at temperature
        ``T``) at one strain amplitude."""
        if isinstance(softening, StrainFactors):
            f, g = softening.factors(float(strain), T)
        else:
            f, g = softening.factors(float(strain))
        return cls(material, float(f), float(g))

    def __repr__(self) -> str:
        return (f"StrainSoftened(f = {self.storage_factor:.4g}, g = {self.loss_factor:.4g} on "
                f"{self.material!r})")

    def E(self, omega, T=None):
        """Complex large-strain Young's modulus, Pa."""
        E = self.material.E(omega, T)
        return self.storage_factor * E.real + 1j * self.loss_factor * E.imag

    @property
    def thermal(self):
        """Thermal properties of the wrapped material."""
        return self.material.thermal

    @property
    def scaled_modulus(self) -> tuple:
        """(wrapped material, f, g): E of this material is f Re E + i g Im E of the wrapped one at every omega
        and T, so tables of the wrapped material serve it, scaled (the engine's angular tables do so)."""
        return self.material, float(self.storage_factor), float(self.loss_factor)

    @property
    def log10_aT(self):
        """The wrapped material's ``log10_aT`` (AttributeError when it has none)."""
        # a property, so that hasattr() reflects the wrapped material
        return self.material.log10_aT

    @property
    def log10_bT(self):
        """The wrapped material's ``log10_bT``, its vertical shift (AttributeError when it has none)."""
        # vertical shift of the wrapped material (AttributeError, i.e. none, when it has none)
        return self.material.log10_bT

    @property
    def T_ref(self):
        """Reference temperature of the wrapped material, deg C."""
        return self.material.T_ref

    @property
    def wlf(self):
        """The WLF law of the wrapped material (its ``wlf``)."""
        return self.material.wlf


@doi("10.1063/1.4919221")
def strain_softening_from_sweep(dma, *, reference_strain: float | None = None) -> StrainSoftening:
    r"""Softening factors from DMA strain sweeps (points with a ``strain`` column).

    Points are grouped by isotherm and frequency; in each group E' and E'' are divided by their values at
    the smallest strain (or at ``reference_strain``, interpolated in log strain), giving
    :math:`f(\varepsilon) = E'(\varepsilon)/E'(\varepsilon_0)` and :math:`g = E''(\varepsilon)/E''(\varepsilon_0)`
    (Lorenz et al. 2015). Groups are combined by the median at each strain of the union of the strain grids
    (each group interpolated in log strain within its own range).

    Raises
    ------
    InputError
        No ``strain`` column, or no group with at least two strains.
    """
    if getattr(dma, "strain", None) is None:
        raise InputError(f"{dma.source}: no 'strain' column; strain softening needs strain sweeps")
    groups = {}
    for idx in dma.isotherm_indices():
        for f in np.unique(dma.f_Hz[idx]):
            g = idx[dma.f_Hz[idx] == f]
            if np.unique(dma.strain[g]).size >= 2:
                groups[(int(dma.isotherm[g[0]]), float(f))] = g[np.argsort(dma.strain[g])]
    if not groups:
        raise InputError(f"{dma.source}: no isotherm/frequency with at least two strain amplitudes")
    grid = np.unique(np.concatenate([dma.strain[g] for g in groups.values()]))
    F, G = [], []
    for g in groups.values():
        xs = np.log(dma.strain[g])
        e0 = dma.strain[g][0] if reference_strain is None else reference_strain
        x0 = math.log(e0)
        if not xs[0] - 1e-12 <= x0 <= xs[-1] + 1e-12:
            raise InputError(f"reference_strain: {e0} lies outside a sweep ({dma.strain[g][0]:g} to "
                             f"{dma.strain[g][-1]:g})")
        E1_0 = np.exp(np.interp(x0, xs, np.log(dma.E_storage[g])))
        E2_0 = np.exp(np.interp(x0, xs, np.log(dma.E_loss[g])))
        inside = (np.log(grid) >= xs[0] - 1e-12) & (np.log(grid) <= xs[-1] + 1e-12)
        f = np.full(grid.size, np.nan)
        gg = np.full(grid.size, np.nan)
        f[inside] = np.interp(np.log(grid[inside]), xs, dma.E_storage[g]) / E1_0
        gg[inside] = np.interp(np.log(grid[inside]), xs, dma.E_loss[g]) / E2_0
        F.append(f)
        G.append(gg)
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "All-NaN slice", RuntimeWarning)      # a strain no sweep reached
        f_med = np.nanmedian(np.array(F), axis=0)
        g_med = np.nanmedian(np.array(G), axis=0)
    return StrainSoftening(grid, f_med, g_med, source=f"strain sweeps in {dma.source} ({len(groups)} sweeps)")


# ==================================================================================================== sweeps

@dataclass(frozen=True, eq=False, repr=False)
class StrainSweep:
    """DMA strain sweeps: E' and E'' against strain amplitude, one row per measured point.

    Attributes
    ----------
    T_C : ndarray
        Temperature of each point, deg C.
    strain : ndarray
        Strain amplitude of each point (absolute, > 0: 0.01 is 1 %).
    E_storage, E_loss : ndarray
        Young's moduli E', E'', Pa (> 0).
    f_Hz : ndarray or None
        Frequency of each point, Hz, when the source has one.
    source : str
        File name(s) or ``"<arrays>"``.
    line : ndarray of int
        Line of each point in its file (0 for arrays).
    notes : tuple of str
        What was done on reading.
    """

    T_C: np.ndarray
    strain: np.ndarray
    E_storage: np.ndarray
    E_loss: np.ndarray
    f_Hz: np.ndarray | None = None
    source: str = "<arrays>"
    line: np.ndarray | None = None
    notes: tuple[str, ...] = ()

    @classmethod
    def from_arrays(cls, T_C, strain, E_storage, E_loss, *, f_Hz=None, source: str = "<arrays>", line=None,
                    notes=()) -> "StrainSweep":
        """Validate point arrays (temperature deg C, absolute strain, moduli in Pa, optional frequency Hz).

        Raises
        ------
        InputError
            Different lengths, or a non-finite or non-positive value (naming the row or line and the column).
        """
        cols = {"T_C": T_C, "strain": strain, "E_storage": E_storage, "E_loss": E_loss}
        if f_Hz is not None:
            cols["f_Hz"] = f_Hz
        arr = {}
        for name, v in cols.items():
            try:
                arr[name] = np.array(v, dtype=float).ravel()
            except (TypeError, ValueError):
                raise InputError(f"{source}: column {name!r}: expected numbers") from None
        n = arr["strain"].size
        for name, a in arr.items():
            if a.size != n:
                raise InputError(f"{source}: column {name!r} has {a.size} values, expected {n} (as strain)")
        if n == 0:
            raise InputError(f"{source}: no strain-sweep rows")
        line = np.zeros(n, dtype=int) if line is None else np.asarray(line, dtype=int).ravel()
        for name, a in arr.items():
            ok = np.isfinite(a) if name == "T_C" else np.isfinite(a) & (a > 0)
            if not ok.all():
                i = int(np.flatnonzero(~ok)[0])
                at = f"line {int(line[i])}" if line[i] > 0 else f"row {i}"
                what = "a finite temperature" if name == "T_C" else f"a positive {name.replace('_', ' ')}"
                raise InputError(f"{source}, {at}, column {name!r}: expected {what}, got {a[i]!r}")
        for a in arr.values():
            a.setflags(write=False)
        return cls(T_C=arr["T_C"], strain=arr["strain"], E_storage=arr["E_storage"], E_loss=arr["E_loss"],
                   f_Hz=arr.get("f_Hz"), source=source, line=line, notes=tuple(notes))

    @classmethod
    def from_dma(cls, dma) -> "StrainSweep":
        """The strain sweeps held in a :class:`materials.DMAData` with a ``strain`` column."""
        if getattr(dma, "strain", None) is None:
            raise InputError(f"{dma.source}: no 'strain' column; strain factors need strain sweeps")
        return cls.from_arrays(dma.T_C, dma.strain, dma.E_storage, dma.E_loss, f_Hz=dma.f_Hz, source=dma.source,
                               line=dma.line, notes=dma.notes)

    def __len__(self) -> int:
        return int(self.strain.size)

    def __repr__(self) -> str:
        return (f"StrainSweep({len(self)} points, strain {self.strain.min():.3g} to {self.strain.max():.3g}, "
                f"T {self.T_C.min():.4g} to {self.T_C.max():.4g} C, {self.source})")


def read_strain_sweep(path, *, columns=None, units=None, T: float | None = None, poisson: float = 0.5,
                      encoding: str | None = None) -> StrainSweep:
    r"""Read DMA strain sweeps (E', E'' against strain amplitude) from a file, a folder or a list of files.

    Each file is a delimited table (comma, tab, semicolon or white space) with a names row and optionally a
    units row, as DMA software exports it; a header-less file needs ``columns=``. Columns are recognised by
    name: strain amplitude (``strain``, ``strain_pct``, ``Strain [%]``, ``amplitude``, ``eps``), storage and
    loss modulus (``E_storage_Pa``, ``E'``, ``E_stor``, ``G'``, ... in Pa, kPa, MPa or GPa), temperature
    (``T_C``, ``T``, ``Ts``, ``Temp``) and frequency (``f_Hz``, ``f``; optional). The project's long DMA table
    with a ``strain`` column is read too.

    Units come from ``units=``, the units row or bracket, a name suffix (``_pct``, ``_MPa``), else the defaults
    (absolute strain, Pa, deg C, Hz); unit slips are refused (strain above 1 read as absolute, moduli outside
    any polymer's range, temperatures below absolute zero or looking like kelvin).

    Parameters
    ----------
    path : str, Path or sequence of them
        A file; a folder (its ``*.csv``, ``*.txt`` and ``*.dat`` files); or a list of files.
    columns : sequence or mapping, optional
        Names of the file's columns in order (``["strain_pct", "E_storage_MPa", "E_loss_MPa"]``) or
        ``{"strain": name or index, ...}``.
    units : mapping, optional
        ``{"strain": "%" | "-", "E": "MPa", "T": "C" | "K", "f": "Hz"}``.
    T : float, optional
        Temperature (deg C) of files without a temperature column; by default taken from the file name
        (``T20.txt``, ``sweep_T-10.csv``).
    poisson : float
        Poisson ratio for shear moduli, :math:`E = 2(1+\nu)G`.
    encoding : str, optional

    Returns
    -------
    StrainSweep

    Raises
    ------
    InputError
        Missing file or column, unknown unit, a unit slip, a bad value (naming file, line and column).
    """
    files = _expand_sweeps(path, expand)
    units = normalise_units(units)
    parts = []
    notes: list[str] = []
    for p in files:
        table = read_table(p, encoding=encoding)
        cols = pick_columns(table, required=("strain", "E_storage", "E_loss"), optional=("T", "f"), columns=columns,
                            units=units, defaults=None)
        c1, c2, cs = cols["E_storage"], cols["E_loss"], cols["strain"]
        check_moduli(c1.values, c2.values, where=f"{c1.where} and {c2.where}", unit=c1.unit, trusted=c1.trusted,
                     source_unit=c1.origin)
        check_strains(cs.values, where=cs.where, unit=cs.unit, trusted=cs.trusted)
        E1, E2 = c1.values, c2.values
        if c1.shear:
            if not (isinstance(poisson, (int, float)) and -1.0 < poisson <= 0.5):
                raise InputError(f"poisson: expected -1 < nu <= 0.5 for the shear conversion, got {poisson!r}")
            E1, E2 = 2.0 * (1.0 + poisson) * E1, 2.0 * (1.0 + poisson) * E2
            notes.append(f"{p.name}: shear moduli converted to Young's moduli E = 2(1+nu)G with nu = {poisson:g}")
        if "T" in cols:
            temp = cols["T"].values
            check_temperatures(temp, where=cols["T"].where, lines=table.lines, trusted=cols["T"].trusted)
        else:
            T_file = _temperature_of(p, T)
            temp = np.full(E1.size, T_file)
            notes.append(f"{p.name}: temperature {T_file:g} C " + ("(from T=)" if T is not None else
                                                                   "(from the file name)"))
        f = cols["f"].values if "f" in cols else None
        parts.append((temp, cs.values, E1, E2, f, table.lines))
        notes.extend(table.notes)
    has_f = {part[4] is not None for part in parts}
    cat = [np.concatenate([part[i] for part in parts]) for i in (0, 1, 2, 3, 5)]
    f_all = np.concatenate([part[4] for part in parts]) if has_f == {True} else None
    source = str(files[0]) if len(files) == 1 else f"{len(files)} files ({files[0].name} ... {files[-1].name})"
    return StrainSweep.from_arrays(cat[0], cat[1], cat[2], cat[3], f_Hz=f_all, source=source, line=cat[4],
                                   notes=notes)


@doi("10.1063/1.4919221", "10.1063/1.1388626")
@dataclass(frozen=True, eq=False, repr=False)
class StrainFactors:
    r"""Strain factors :math:`f(\varepsilon, T) = E'(\varepsilon, T)/E'(\varepsilon_0, T)` and
    :math:`g(\varepsilon, T) = E''(\varepsilon, T)/E''(\varepsilon_0, T)` on a grid (Lorenz et al. 2015).

    ``factors(strain, T)`` interpolates bilinearly, in :math:`\ln\varepsilon` and in T:

    * between the tabulated strains linearly in :math:`\ln\varepsilon`; below the smallest strain the value
      there (the linear regime, 1 for measured sweeps); above the largest strain the value at the largest
      strain (no extrapolation of the softening);
    * between the tabulated temperatures linearly in T; outside them the nearest temperature's curve.

    A grid with one strain (or one temperature) is independent of strain (or temperature).

    Attributes
    ----------
    strain : ndarray, shape (n_strain,)
        Strain amplitudes of the grid (absolute, increasing, > 0).
    T_C : ndarray, shape (n_T,)
        Temperatures of the grid, deg C (increasing).
    storage_factor, loss_factor : ndarray, shape (n_T, n_strain)
        f and g on the grid (> 0). Read-only; with ``strain`` and ``T_C`` they are all a compiled kernel needs
        to reproduce :meth:`factors`.
    source : str
        Where they come from.
    """

    strain: np.ndarray
    T_C: np.ndarray
    storage_factor: np.ndarray
    loss_factor: np.ndarray
    source: str = ""

    def __post_init__(self):
        s = np.array(self.strain, dtype=float).ravel()
        T = np.array(self.T_C, dtype=float).ravel()
        F = np.array(self.storage_factor, dtype=float)
        G = np.array(self.loss_factor, dtype=float)
        if s.size == 0 or T.size == 0:
            raise InputError("StrainFactors: need at least one strain and one temperature")
        for name, a in (("storage_factor", F), ("loss_factor", G)):
            if a.shape != (T.size, s.size):
                raise InputError(f"StrainFactors.{name}: expected shape (n_T, n_strain) = ({T.size}, {s.size}), "
                                 f"got {a.shape}")
            if not (np.all(np.isfinite(a)) and np.all(a > 0)):
                raise InputError(f"StrainFactors.{name}: expected finite positive factors")
        if not (np.all(np.isfinite(s)) and np.all(s > 0) and np.all(np.diff(s) > 0)):
            raise InputError("StrainFactors.strain: expected finite positive increasing strain amplitudes")
        if not (np.all(np.isfinite(T)) and np.all(np.diff(T) > 0)):
            raise InputError("StrainFactors.T_C: expected finite increasing temperatures in deg C")
        for name, a in (("strain", s), ("T_C", T), ("storage_factor", F), ("loss_factor", G)):
            a.setflags(write=False)
            object.__setattr__(self, name, a)
        object.__setattr__(self, "_ln_strain", np.log(s))

    def __reduce__(self):
        return (StrainFactors, (self.strain, self.T_C, self.storage_factor, self.loss_factor, self.source))

    @classmethod
    def constant(cls, storage_factor: float, loss_factor: float) -> "StrainFactors":
        """Factors independent of strain and temperature (e.g. taken at a typical contact strain)."""
        for name, v in (("storage_factor", storage_factor), ("loss_factor", loss_factor)):
            if not (isinstance(v, (int, float, np.floating)) and math.isfinite(v) and v > 0):
                raise InputError(f"StrainFactors.constant: {name} must be a positive number, got {v!r}")
        return cls(np.array([1.0]), np.array([0.0]), np.array([[float(storage_factor)]]),
                   np.array([[float(loss_factor)]]), source="constant")

    @classmethod
    def from_softening(cls, softening: StrainSoftening) -> "StrainFactors":
        """The same factors as a temperature-independent :class:`StrainSoftening`."""
        return cls(softening.strain, np.array([0.0]), softening.storage_factor[None, :],
                   softening.loss_factor[None, :], source=softening.source)

    @property
    def is_constant(self) -> bool:
        """True when f and g depend on neither strain nor temperature."""
        return bool(np.all(self.storage_factor == self.storage_factor.flat[0])
                    and np.all(self.loss_factor == self.loss_factor.flat[0]))

    @property
    def strain_range(self) -> tuple[float, float]:
        """Smallest and largest strain amplitude of the grid (absolute)."""
        return float(self.strain[0]), float(self.strain[-1])

    @property
    def temperature_range(self) -> tuple[float, float] | None:
        """Temperatures of the grid, deg C (None when the factors do not depend on temperature)."""
        return None if self.T_C.size == 1 else (float(self.T_C[0]), float(self.T_C[-1]))

    def factors(self, strain, T=None):
        r"""(f, g) at strain amplitudes ``strain`` (absolute, >= 0) and temperatures ``T`` (deg C).

        ``strain`` and ``T`` broadcast against each other; the result has their broadcast shape. ``T`` may be
        omitted when the factors do not depend on temperature. Strain 0 gives the small-strain value.

        Raises
        ------
        InputError
            NaN or negative strain, non-finite T, T missing for temperature-dependent factors, shapes that do
            not broadcast.
        """
        e = np.asarray(strain, dtype=float)
        if np.isnan(e).any() or np.any(e < 0):
            raise InputError("strain: expected strain amplitudes >= 0 (absolute, 0.01 = 1 %), got NaN or negative "
                             "values")
        if T is None:
            if self.T_C.size > 1:
                raise InputError(f"T: these strain factors depend on temperature ({self.T_C[0]:g} to "
                                 f"{self.T_C[-1]:g} C); give T")
            T = self.T_C[0]
        T = np.asarray(T, dtype=float)
        if not np.all(np.isfinite(T)):
            raise InputError("T: expected finite temperatures in deg C")
        try:
            e, T = np.broadcast_arrays(e, T)
        except ValueError:
            raise InputError(f"factors: strain of shape {e.shape} and T of shape {T.shape} do not broadcast") from None
        with np.errstate(divide="ignore"):
            x = np.log(e)
        i0, i1, wx = _bracket(x, self._ln_strain)
        j0, j1, wT = _bracket(T, self.T_C)
        out = []
        for table in (self.storage_factor, self.loss_factor):
            lo = (1.0 - wx) * table[j0, i0] + wx * table[j0, i1]
            hi = (1.0 - wx) * table[j1, i0] + wx * table[j1, i1]
            out.append((1.0 - wT) * lo + wT * hi)
        return out[0], out[1]

    def __repr__(self) -> str:
        if self.is_constant:
            return (f"StrainFactors(constant f = {self.storage_factor.flat[0]:.4g}, "
                    f"g = {self.loss_factor.flat[0]:.4g})")
        temps = ("any T" if self.T_C.size == 1 else
                 f"{self.T_C.size} temperatures {self.T_C[0]:.4g} to {self.T_C[-1]:.4g} C")
        return (f"StrainFactors({self.strain.size} strains {self.strain[0]:.3g} to {self.strain[-1]:.3g}, {temps}, "
                f"f {self.storage_factor.min():.3g}..{self.storage_factor.max():.3g}, g "
                f"{self.loss_factor.min():.3g}..{self.loss_factor.max():.3g}"
                + (f", {self.source}" if self.source else "") + ")")


@doi("10.1063/1.4919221")
def strain_factors(sweeps, *, reference_strain: float | None = None, isotherm_tol: float = 1.0) -> StrainFactors:
    r"""Strain factors f(strain, T), g(strain, T) from DMA strain sweeps.

    The points are grouped into sweeps: by temperature (sorted temperatures more than ``isotherm_tol`` K apart
    start a new group; the group's temperature is the median) and, within a temperature, by frequency. Each
    sweep is normalised by its own small-strain moduli,

    .. math:: f_j = E'(\varepsilon_j)/E'(\varepsilon_0),\qquad g_j = E''(\varepsilon_j)/E''(\varepsilon_0),

    with :math:`\varepsilon_0` the sweep's smallest strain (or ``reference_strain``, interpolated linearly in
    :math:`\ln\varepsilon`), as in Lorenz et al. (2015). The grid's strains are those of all sweeps; each sweep
    is interpolated linearly in :math:`\ln\varepsilon` within its own range, sweeps at several frequencies of one
    temperature are combined by the median (the factors are taken as frequency-independent), and at strains
    beyond a temperature's sweeps its curve is held at its end values (1 below the smallest strain unless
    ``reference_strain`` is larger).

    Parameters
    ----------
    sweeps : StrainSweep, DMAData with a strain column, or a sequence of them
    reference_strain : float, optional
        Strain amplitude (absolute) of the linear modulus; must lie within every sweep.
    isotherm_tol : float
        Temperature gap (K) separating sweeps.

    Returns
    -------
    StrainFactors

    Raises
    ------
    InputError
        No sweep with two strains, a reference strain outside a sweep, bad input.
    """
    parts = _as_sweeps(sweeps)
    T = np.concatenate([p.T_C for p in parts])
    e = np.concatenate([p.strain for p in parts])
    E1 = np.concatenate([p.E_storage for p in parts])
    E2 = np.concatenate([p.E_loss for p in parts])
    f = np.concatenate([p.f_Hz if p.f_Hz is not None else np.full(p.strain.size, np.nan) for p in parts])
    source = parts[0].source if len(parts) == 1 else f"{len(parts)} strain-sweep sets"
    if not (isinstance(isotherm_tol, (int, float)) and isotherm_tol > 0):
        raise InputError(f"isotherm_tol: expected a positive temperature gap in K, got {isotherm_tol!r}")
    if reference_strain is not None and not (isinstance(reference_strain, (int, float))
                                             and math.isfinite(reference_strain) and reference_strain > 0):
        raise InputError(f"reference_strain: expected a positive absolute strain amplitude, got {reference_strain!r}")
    order = np.argsort(T, kind="stable")
    group = np.empty(T.size, dtype=int)
    group[order] = np.cumsum(np.concatenate([[0], np.diff(T[order]) > isotherm_tol]))
    grid = np.unique(e)
    grid = grid[np.concatenate([[True], np.diff(np.log(grid)) > 1e-9])]
    xg = np.log(grid)
    T_nodes, F_rows, G_rows = [], [], []
    n_sweeps = 0
    for gi in range(int(group.max()) + 1):
        in_g = np.flatnonzero(group == gi)
        F_sweeps, G_sweeps = [], []
        for freq in _unique_with_nan(f[in_g]):
            idx = in_g[np.isnan(f[in_g])] if np.isnan(freq) else in_g[f[in_g] == freq]
            idx = idx[np.argsort(e[idx], kind="stable")]
            if np.unique(e[idx]).size < 2:
                continue
            Fs, Gs = _normalised(e[idx], E1[idx], E2[idx], xg, reference_strain, source, float(np.median(T[idx])))
            F_sweeps.append(Fs)
            G_sweeps.append(Gs)
        if not F_sweeps:
            continue
        n_sweeps += len(F_sweeps)
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", "All-NaN slice", RuntimeWarning)   # a strain no sweep reached
            F_rows.append(_hold_ends(np.nanmedian(np.array(F_sweeps), axis=0)))
            G_rows.append(_hold_ends(np.nanmedian(np.array(G_sweeps), axis=0)))
        T_nodes.append(float(np.median(T[in_g])))
    if not F_rows:
        raise InputError(f"{source}: no sweep (temperature and frequency) with at least two strain amplitudes")
    return StrainFactors(grid, np.array(T_nodes), np.array(F_rows), np.array(G_rows),
                         source=f"strain sweeps in {source} ({n_sweeps} sweeps at {len(T_nodes)} temperatures)")


# ==================================================================================================== helpers

def _as_sweeps(sweeps) -> list:
    items = sweeps if isinstance(sweeps, (list, tuple)) else [sweeps]
    if not items:
        raise InputError("sweeps: empty list")
    out = []
    for s in items:
        if isinstance(s, StrainSweep):
            out.append(s)
        elif isinstance(s, DMAData):
            out.append(StrainSweep.from_dma(s))
        else:
            raise InputError(f"sweeps: expected materials.StrainSweep (from read_strain_sweep) or DMAData with a "
                             f"strain column, got {type(s).__name__}")
    return out


def _unique_with_nan(a):
    vals = np.unique(a[~np.isnan(a)]).tolist()
    return vals + ([math.nan] if np.isnan(a).any() else [])


def _normalised(e, E1, E2, xg, reference_strain, source, T):
    """f and g of one sweep on the grid ln strains ``xg`` (NaN outside the sweep's range)."""
    xs = np.log(e)
    # repeated strains within a sweep are averaged
    u, inv = np.unique(xs, return_inverse=True)
    l1 = np.bincount(inv, weights=np.log(E1)) / np.bincount(inv)
    l2 = np.bincount(inv, weights=np.log(E2)) / np.bincount(inv)
    x0 = u[0] if reference_strain is None else math.log(reference_strain)
    if not u[0] - 1e-12 <= x0 <= u[-1] + 1e-12:
        raise InputError(f"reference_strain: {reference_strain} lies outside the sweep at {T:g} C of {source} "
                         f"({math.exp(u[0]):g} to {math.exp(u[-1]):g})")
    r1 = np.exp(l1 - np.interp(x0, u, l1))
    r2 = np.exp(l2 - np.interp(x0, u, l2))
    inside = (xg >= u[0] - 1e-12) & (xg <= u[-1] + 1e-12)
    F = np.full(xg.size, np.nan)
    G = np.full(xg.size, np.nan)
    F[inside] = np.interp(xg[inside], u, r1)
    G[inside] = np.interp(xg[inside], u, r2)
    return F, G


def _hold_ends(v):
    """NaN before the first value and beyond the last value hold those values (clamping)."""
    v = np.array(v, dtype=float)
    ok = np.flatnonzero(np.isfinite(v))
    v[: ok[0]] = v[ok[0]]
    v[ok[-1] + 1:] = v[ok[-1]]
    gaps = ~np.isfinite(v)
    if gaps.any():
        idx = np.arange(v.size)
        v[gaps] = np.interp(idx[gaps], idx[~gaps], v[~gaps])
    return v



def _expand_sweeps(path, expand) -> list:
    if isinstance(path, (str, Path)) and Path(path).is_dir():
        files = sorted(q for q in Path(path).iterdir()
                       if q.is_file() and q.suffix.lower() in (".csv", ".txt", ".dat"))
        if not files:
            raise InputError(f"{path}: folder holds no *.csv, *.txt or *.dat strain-sweep files")
        return sorted(files, key=natural_key)
    return expand(path)


def _temperature_of(path: Path, T, hint: str = "columns naming a temperature column") -> float:
    """``T`` (deg C) checked, or the temperature in ``path``'s name (``T20``, ``T-5.5C``); ``hint`` says in the
    error what else the caller accepts."""
    if T is not None:
        try:
            T = float(T)
        except (TypeError, ValueError):
            raise InputError(f"T: expected a temperature in deg C, got {T!r}") from None
        if not math.isfinite(T) or T < -273.15:
            raise InputError(f"T: expected a temperature in deg C above -273.15, got {T!r}")
        return T
    m = re.search(r"(?:^|[_\-\s])T_?(-?\d+(?:\.\d+)?)(?:C)?(?:$|[_\-\s])", path.stem)
    if not m:
        raise InputError(f"{path}: no temperature column and none in the file name (e.g. T20.txt); pass T= "
                         f"(deg C) or {hint}")
    return float(m.group(1))


def _bracket(x, nodes):
    """Indices of the nodes around x and the weight of the upper one, x clamped to the nodes' range."""
    n = nodes.size
    if n == 1:
        zero = np.zeros(x.shape, dtype=np.intp)
        return zero, zero, np.zeros(x.shape)
    xc = np.clip(x, nodes[0], nodes[-1])
    i0 = np.clip(np.searchsorted(nodes, xc, side="right") - 1, 0, n - 2)
    w = (xc - nodes[i0]) / (nodes[i0 + 1] - nodes[i0])
    return i0, i0 + 1, w
