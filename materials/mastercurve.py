r"""The master-curve material: a complex modulus at a reference temperature and a temperature shift law.

.. math:: E(\omega, T) = b_T\, E_{ref}(\omega\, a_T(T))

:class:`MasterCurve` is what :func:`materials.master_curve` builds from DMA isotherms and what
:meth:`MasterCurve.from_table` (:func:`materials.read_master_curve`) makes of a master-curve table. The reference
curve :math:`E_{ref}` is an interpolated table (:class:`materials.curves.InterpolatedModulus`) or a causal Prony
series (generalized Maxwell solid, Park & Schapery 1999),

.. math:: E_{ref}(\omega) = E_\infty + \sum_i E_i \frac{i\omega\tau_i}{1 + i\omega\tau_i};

the shift law is any of :mod:`materials.laws` or :mod:`materials.shift`. :class:`TabulatedModulus` is a fast
interpolating copy, :class:`ReducedData` the shifted data behind a curve, and :func:`isotherm_misfit` the measure
of quality used throughout.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Mapping

import numpy as np

from frictioncite import doi

from . import _master_table as table_file
from ._io import write_csv_atomic
from .curves import CausalityCheck, InterpolatedModulus, causality_check
from .dma import DMAData
from .errors import AccuracyWarning, InputError, PhysicsWarning, ignoring
from .laws import WLF, TemperatureShift, WLFFit
from .prony_fit import FitQuality, fit_prony, quality_of
from .shift import EXTRAPOLATED_SHIFT, SingleTemperature
from .shiftfit import ShiftLawScore
from .strain import StrainSoftened
from .tts import ShiftFactors
from .viscoelastic import Prony, Thermal, _reduced_omega

__all__ = ["MasterCurve", "ReducedData", "TabulatedModulus", "isotherm_misfit", "FITS"]

_CITES = ("10.1021/ja01619a008", "isbn:978-0-471-04894-7", "10.1016/S0020-7683(98)00055-9",
          "10.1137/1.9781611971217", "10.1137/0717021")

#: Representations of the reference curve: ``"table"`` (interpolated nodes), ``"prony"`` (causal Prony series),
#: ``"auto"`` (for DMA data the better of the two against the isotherms; for a table, the table).
FITS = ("auto", "table", "prony")


@dataclass(frozen=True, eq=False, repr=False)
class ReducedData:
    """The data behind a master curve, shifted to the reference temperature.

    ``omega`` is the reduced angular frequency omega a_T (rad/s); ``E_storage``, ``E_loss`` are divided by b_T;
    ``T_C`` is the temperature each point was measured at (None for a master-curve table).
    """

    omega: np.ndarray
    E_storage: np.ndarray
    E_loss: np.ndarray
    T_C: np.ndarray | None = None

    @property
    def f_Hz(self) -> np.ndarray:
        """Reduced frequency omega a_T / (2 pi), Hz."""
        return self.omega / (2.0 * np.pi)

    def __repr__(self) -> str:
        return (f"ReducedData({self.omega.size} points, {self.f_Hz.min():.3g} to {self.f_Hz.max():.3g} Hz at "
                "T_ref)")


@doi(*_CITES)
@dataclass(frozen=True, eq=False, repr=False)
class MasterCurve:
    r"""A viscoelastic master curve: the complex modulus at T_ref and a temperature shift law.

    .. math:: E(\omega, T) = b_T\, E_{ref}(\omega\, a_T(T))

    Attributes
    ----------
    prony : Prony or None
        Generalized Maxwell series at the reference temperature, when that is the representation.
    shift : shift law
        :class:`materials.TemperatureShift` (WLF), :class:`materials.WLFArrhenius`, :class:`materials.Arrhenius`,
        :class:`materials.TabulatedShift` or :class:`materials.SingleTemperature`; ``log10_aT`` delegates to it.
    quality : FitQuality
        RMS relative residual of the representation in E' and E'' over the (shifted) data.
    thermal : Thermal
        Density, specific heat, conductivity.
    shift_factors : ShiftFactors or None
        Per-isotherm shifts (None when built from a table).
    wlf_fit : WLFFit or None
        The WLF fit with its covariance, when the law has a fitted WLF branch.
    reduced : ReducedData or None
        The shifted data, or the table's nodes (for plots and checks).
    label : str
        Where it came from.
    notes : tuple of str
        What was done (law chosen and why, extrapolated reference, causality warnings, ...).
    curve : InterpolatedModulus or None
        The interpolated reference curve, when that is the representation.
    misfit : float or None
        :func:`isotherm_misfit` of this material against the isotherms it was built from.
    scores : tuple of ShiftLawScore
        Misfit of every temperature law considered (in sample and cross-validated).
    causality : CausalityCheck or None
        Kramers-Kronig check of the interpolated curve.
    """

    prony: Prony | None
    shift: object
    quality: FitQuality
    thermal: Thermal = field(default_factory=Thermal)
    shift_factors: ShiftFactors | None = None
    wlf_fit: WLFFit | None = None
    reduced: ReducedData | None = None
    label: str = ""
    notes: tuple[str, ...] = ()
    curve: InterpolatedModulus | None = None
    misfit: float | None = None
    scores: tuple[ShiftLawScore, ...] = ()
    causality: CausalityCheck | None = None

    def __post_init__(self):
        if (self.prony is None) == (self.curve is None):
            raise InputError("MasterCurve: give exactly one representation, prony= or curve=")

    # ---------------------------------------------------------------- the material interface
    @property
    def T_ref(self) -> float:
        """Reference temperature, deg C."""
        return float(self.shift.T_ref)

    @property
    def wlf(self) -> WLF | None:
        """The WLF law (constants C1, C2 at T_ref) of the shift law, when it has one."""
        return self.shift if isinstance(self.shift, WLF) else getattr(self.shift, "wlf", None)

    @property
    def representation(self) -> str:
        """``"table"`` (interpolated nodes) or ``"prony"`` (causal Prony series)."""
        return "table" if self.curve is not None else "prony"

    @property
    def frequency_range(self) -> tuple[float, float]:
        """Angular frequencies (rad/s, at T_ref) covered by the data; beyond them E is extrapolated."""
        if self.reduced is not None:
            return float(self.reduced.omega.min()), float(self.reduced.omega.max())
        if self.curve is not None:
            return self.curve.frequency_range
        return float(1.0 / self.prony.tau_i.max()), float(1.0 / self.prony.tau_i.min())

    @property
    def temperature_range(self) -> tuple[float, float] | None:
        """Temperatures (deg C) of the isotherms (or of a shift-factor table); None for a table without one."""
        if self.shift_factors is not None:
            return float(self.shift_factors.T_C.min()), float(self.shift_factors.T_C.max())
        rng = getattr(self.shift, "T_range", None)
        return None if rng is None else (float(rng[0]), float(rng[1]))

    def extrapolated(self, omega, T) -> np.ndarray:
        """True where E(omega, T) lies outside the data: reduced frequency outside :attr:`frequency_range`, or
        T outside :attr:`temperature_range` (broadcast of ``omega`` and ``T``)."""
        omega = np.abs(np.asarray(omega, dtype=float))
        T = np.asarray(T, dtype=float)
        with ignoring(AccuracyWarning, EXTRAPOLATED_SHIFT):     # extrapolation is what is asked about
            w_r = np.abs(_reduced_omega(omega, self.log10_aT(T)))
        lo, hi = self.frequency_range
        out = (w_r < lo * (1 - 1e-12)) | (w_r > hi * (1 + 1e-12))
        rng = self.temperature_range
        if rng is not None:
            out = out | (T < rng[0]) | (T > rng[1])
        return out

    def log10_aT(self, T):
        """log10 of the horizontal shift factor at ``T`` (deg C), from the shift law :attr:`shift`."""
        return self.shift.log10_aT(T)

    def log10_bT(self, T):
        """log10 of the vertical shift factor (0 unless vertical shifts were fitted; interpolated, clamped)."""
        T = np.asarray(T, dtype=float)
        sf = self.shift_factors
        if sf is None or not np.any(sf.log10_bT):
            return np.zeros(T.shape) if T.ndim else 0.0
        return np.interp(T, sf.T_C, sf.log10_bT)

    def E_reference(self, omega):
        """Complex modulus at T_ref, Pa."""
        if self.curve is not None:
            return self.curve.E_reference(omega)
        return self.prony.E_reference(omega)

    def E(self, omega, T=None):
        """Complex Young's modulus E' + i E'', Pa, at ``omega`` (rad/s, any sign) and ``T`` (deg C).

        Vectorized; ``omega`` and ``T`` broadcast. Im E is odd in omega, E(0) is real. ``T=None`` means the
        reference temperature. Outside :attr:`frequency_range` the representation extrapolates (see
        ``docs/materials.md``).
        """
        omega = np.asarray(omega, dtype=float)
        if T is None:
            return self.E_reference(omega)
        T = np.asarray(T, dtype=float)
        E = self.E_reference(_reduced_omega(omega, self.log10_aT(T)))
        if self.shift_factors is not None and np.any(self.shift_factors.log10_bT):
            E = E * 10.0 ** self.log10_bT(T)
        return E

    # ---------------------------------------------------------------- derived objects
    def with_thermal(self, thermal) -> "MasterCurve":
        """The same material with other thermal properties (a Thermal or a mapping as in the case file)."""
        th = _as_thermal(thermal)
        if th is None:
            raise InputError("with_thermal: expected materials.Thermal or a mapping, got None")
        prony = None if self.prony is None else replace(self.prony, thermal=th)
        return replace(self, thermal=th, prony=prony)

    def with_T_ref(self, T_ref: float) -> "MasterCurve":
        r"""The same material referred to another reference temperature.

        Relaxation times (or node frequencies) scale by :math:`a_T(T_{ref}')` and moduli by
        :math:`b_T(T_{ref}')`; the shift law is re-referred exactly (WLF constants by
        :func:`materials.tts.wlf_change_reference`).
        """
        if not math.isfinite(T_ref):
            raise InputError(f"T_ref: expected a finite temperature in deg C, got {T_ref!r}")
        la = float(self.log10_aT(T_ref))
        lb = float(self.log10_bT(T_ref))
        prony, curve = _rescaled(self.prony, self.curve, la, lb)
        sf = None if self.shift_factors is None else self.shift_factors.rereferenced(T_ref, la, lb)
        red = self.reduced
        if red is not None:
            red = replace(red, omega=red.omega / 10.0 ** la, E_storage=red.E_storage / 10.0 ** lb,
                          E_loss=red.E_loss / 10.0 ** lb)
        shift = self.shift.with_T_ref(T_ref)
        fit = self.wlf_fit
        if fit is not None and getattr(shift, "wlf", None) is not None:
            fit = replace(fit, wlf=shift.wlf)
        return replace(self, prony=prony, curve=curve, shift=shift, shift_factors=sf, reduced=red, wlf_fit=fit,
                       notes=self.notes + (f"reference temperature changed to {T_ref:g} C",))

    def tabulated(self, omega_min: float = 1e-10, omega_max: float = 1e22, per_decade: int = 50
                  ) -> "TabulatedModulus":
        """A fast interpolating copy of this material (log-omega table of the reference curve).

        See :class:`TabulatedModulus`; relative interpolation error about 1e-3 at 50 points per decade.
        """
        return TabulatedModulus.from_material(self, omega_min, omega_max, per_decade)

    def at_strain(self, strain=None, softening=None, *, storage_factor=None, loss_factor=None):
        """The large-strain material: E' and E'' multiplied by f(strain), g(strain).

        Give either ``softening`` (a :class:`materials.StrainSoftening`) and ``strain``, or the two factors.
        Returns :class:`materials.StrainSoftened`.
        """
        if softening is not None:
            if strain is None:
                raise InputError("at_strain: give the strain amplitude with the softening curve")
            return StrainSoftened.from_softening(self, softening, strain)
        return StrainSoftened(self, 1.0 if storage_factor is None else storage_factor,
                              1.0 if loss_factor is None else loss_factor)

    # ---------------------------------------------------------------- files
    def to_table(self, path, f_Hz=None, *, per_decade: int = 10, overwrite: bool = False) -> Path:
        """Write the master-curve table ``f_Hz, E_storage_Pa, E_loss_Pa`` at T_ref, atomically.

        Parameters
        ----------
        path : str or Path
            Destination; written to a temporary file and renamed, so it is complete or absent.
        f_Hz : array_like, optional
            Frequencies (Hz, > 0). Default: an interpolated curve's own nodes (so that reading the table back
            gives the same material); otherwise log-spaced over the data window, ``per_decade`` per decade.
        overwrite : bool
            Replace an existing file (default: refused).

        Returns
        -------
        Path
            The path written. Comment lines give T_ref, the shift law and the fit quality.
        """
        if f_Hz is None:
            if self.curve is not None:
                f_Hz = self.curve.omega / (2 * np.pi)
            else:
                lo, hi = (np.log10(v / (2 * np.pi)) for v in self.frequency_range)
                n = max(2, int(math.ceil((hi - lo) * per_decade)) + 1)
                f_Hz = np.logspace(lo, hi, n)
        f_Hz = np.asarray(f_Hz, dtype=float).ravel()
        if not (f_Hz.size > 0 and np.all(np.isfinite(f_Hz)) and np.all(f_Hz > 0)):
            raise InputError("to_table: f_Hz must be finite positive frequencies in Hz")
        E = self.E_reference(2 * np.pi * f_Hz)
        comments = [f"master curve at T_ref = {self.T_ref:g} C ({self.label or 'materials.MasterCurve'})"]
        w = self.wlf
        if w is not None and isinstance(self.shift, (WLF, TemperatureShift)):
            comments.append(f"wlf = {{ C1 = {w.C1:.6g}, C2 = {w.C2:.6g}, T_ref_C = {w.T_ref:.6g} }}")
        comments.append(f"shift law: {_describe(self.shift)}")
        comments.append(str(self.quality))
        comments.extend(self.notes)
        return write_csv_atomic(path, {"f_Hz": f_Hz, "E_storage_Pa": E.real, "E_loss_Pa": E.imag},
                                comments=comments, overwrite=overwrite)

    @classmethod
    def from_table(cls, path_or_table, wlf=None, *, shift=None, fit: str = "table", T_ref: float | None = None,
                   thermal: Thermal | None = None, per_decade: float = 2.0, label: str | None = None,
                   columns=None, units=None, poisson: float = 0.5, encoding: str | None = None) -> "MasterCurve":
        """Build from a master-curve table (a file, or a mapping with ``f_Hz``, ``E_storage_Pa``, ``E_loss_Pa``).

        See :func:`materials.read_master_curve` for the parameters.
        """
        if isinstance(path_or_table, Mapping):
            f, E1, E2, source, lines = table_file.table_from_mapping(path_or_table)
            notes = []
        else:
            f, E1, E2, source, lines, notes = table_file.read_table_columns(path_or_table, columns, units, poisson,
                                                                            encoding)
        f, E1, E2 = table_file.merge_repeated(f, E1, E2, source, lines, notes)
        law = table_file.table_law(wlf, shift, T_ref, source)
        thermal = _as_thermal(thermal)
        label = label or f"master-curve table {source}"
        omega = 2 * np.pi * f
        if fit not in FITS:
            raise InputError(f"fit: expected one of {', '.join(FITS)}, got {fit!r}")
        curve = prony = check = None
        if fit == "prony":
            pf = fit_prony(omega, E1, E2, per_decade=per_decade, thermal=thermal, label=label)
            prony, quality = pf.prony, pf.quality
            notes.append(f"Prony series fitted to the table (fit='prony'): {quality}")
        else:
            curve = InterpolatedModulus(omega, E1, E2, source=source)
            quality = quality_of(curve, omega, E1, E2, representation="table")
            check = causality_check(curve.omega, curve.E_storage, curve.E_loss)
            if not check.ok:
                msg = check.message(source)
                warnings.warn(msg, PhysicsWarning, stacklevel=3)
                notes.append(msg)
        if isinstance(law, SingleTemperature):
            notes.append(law.describe())
        return cls(prony=prony, curve=curve, shift=law, quality=quality, thermal=thermal or Thermal(),
                   reduced=ReducedData(omega=omega, E_storage=E1, E_loss=E2), label=label, notes=tuple(notes),
                   causality=check)

    # ---------------------------------------------------------------- text
    def summary(self) -> str:
        """A few lines saying what this material is and how good its fit is."""
        lines = [f"MasterCurve {self.label}".rstrip(),
                 f"  T_ref = {self.T_ref:g} C; shift law: {_describe(self.shift)}"]
        if self.wlf_fit is not None:
            lines.append(f"  WLF fit: C1 = {self.wlf_fit.C1:.4g} +- {self.wlf_fit.stderr[0]:.2g}, "
                         f"C2 = {self.wlf_fit.C2:.4g} +- {self.wlf_fit.stderr[1]:.2g} K")
        if self.prony is not None:
            lines.append(f"  Prony series: E_inf = {self.prony.E_inf:.4g} Pa, E_glassy = {self.prony.E_glassy:.4g} Pa")
        lo, hi = self.frequency_range
        lines.append(f"  data: {lo / (2 * np.pi):.3g} to {hi / (2 * np.pi):.3g} Hz at T_ref"
                     + ("" if self.temperature_range is None else
                        f", {self.temperature_range[0]:.4g} to {self.temperature_range[1]:.4g} C"))
        lines.append(f"  {self.quality}")
        if self.misfit is not None:
            lines.append(f"  misfit against the isotherms (log-RMS): {self.misfit:.4g}")
        for s in self.scores:
            lines.append(f"    {s!r}")
        lines += [f"  note: {n}" for n in self.notes]
        return "\n".join(lines)

    def __repr__(self) -> str:
        mis = "" if self.misfit is None else f", misfit {self.misfit:.3g}"
        return (f"MasterCurve({self.representation}, T_ref = {self.T_ref:g} C, {_describe(self.shift)}{mis}"
                + (f", {self.label!r}" if self.label else "") + ")")


@dataclass(frozen=True, eq=False, repr=False)
class TabulatedModulus:
    r"""Fast evaluation of a master curve: log E', log E'' tabulated on a log reduced-frequency grid.

    Inside the grid :math:`\log_{10}E'` and :math:`\log_{10}E''` are interpolated linearly in
    :math:`\log_{10}|\omega a_T|`; outside it (and at omega = 0) the exact reference curve is used. Im E is odd
    in omega. Exposes ``E(omega, T)``, ``log10_aT``, ``thermal`` like the material it copies.
    """

    source: object
    log10_omega: np.ndarray
    log10_E_storage: np.ndarray
    log10_E_loss: np.ndarray

    @classmethod
    def from_material(cls, material, omega_min=1e-10, omega_max=1e22, per_decade=50) -> "TabulatedModulus":
        """Tabulate the reference modulus of ``material`` on a logarithmic grid of angular frequency.

        Parameters
        ----------
        material : object
            Anything with ``E_reference(omega)``, ``thermal``, ``T_ref`` and ``log10_aT(T)`` (e.g. a
            :class:`MasterCurve`).
        omega_min, omega_max : float
            Ends of the grid, rad/s.
        per_decade : int
            Grid points per decade (at least 2).

        Returns
        -------
        TabulatedModulus

        Raises
        ------
        InputError
            An invalid grid, or a non-positive E' or E'' of the material on it.
        """
        if not (0 < omega_min < omega_max and per_decade >= 2):
            raise InputError("tabulated: expected 0 < omega_min < omega_max and per_decade >= 2")
        x = np.linspace(math.log10(omega_min), math.log10(omega_max),
                        int(math.ceil((math.log10(omega_max) - math.log10(omega_min)) * per_decade)) + 1)
        E = material.E_reference(10.0 ** x)
        if np.any(E.imag <= 0) or np.any(E.real <= 0):
            raise InputError("tabulated: the material has a non-positive E' or E'' on the grid; use it directly")
        return cls(material, x, np.log10(E.real), np.log10(E.imag))

    @property
    def thermal(self):
        """Thermal properties of the tabulated material."""
        return self.source.thermal

    @property
    def T_ref(self):
        """Reference temperature of the tabulated material, deg C."""
        return self.source.T_ref

    def log10_aT(self, T):
        """log10 of the horizontal shift factor at ``T`` (deg C), from the tabulated material."""
        return self.source.log10_aT(T)

    def E_reference(self, omega):
        """Complex modulus at T_ref, Pa: interpolated on the grid, the tabulated material's own outside it (and at
        omega = 0); Im E is odd in omega."""
        omega = np.asarray(omega, dtype=float)
        aw = np.abs(omega)
        with np.errstate(divide="ignore"):
            x = np.log10(aw)
        inside = (x >= self.log10_omega[0]) & (x <= self.log10_omega[-1])
        re = 10.0 ** np.interp(x, self.log10_omega, self.log10_E_storage)
        im = 10.0 ** np.interp(x, self.log10_omega, self.log10_E_loss) * np.sign(omega)
        out = re + 1j * im
        if not np.all(inside):
            out = np.where(inside, out, self.source.E_reference(omega))
        return out

    def E(self, omega, T=None):
        """Complex Young's modulus, Pa (see :meth:`MasterCurve.E`)."""
        omega = np.asarray(omega, dtype=float)
        if T is None:
            return self.E_reference(omega)
        T = np.asarray(T, dtype=float)
        E = self.E_reference(_reduced_omega(omega, self.log10_aT(T)))
        if hasattr(self.source, "log10_bT"):
            lb = self.source.log10_bT(T)
            if np.any(lb):
                E = E * 10.0 ** lb
        return E

    def __repr__(self) -> str:
        return (f"TabulatedModulus({self.log10_omega.size} points, omega 1e{self.log10_omega[0]:.3g} to "
                f"1e{self.log10_omega[-1]:.3g} rad/s, of {self.source!r})")


# ==================================================================================================== quality

def isotherm_misfit(material, dma: DMAData) -> float:
    r"""Log-RMS misfit of a material against DMA isotherms.

    .. math:: M = \sqrt{\frac{1}{2N}\sum_{i=1}^{N}\left[\ln\frac{E'(\omega_i, T_i)}{E'_i}\right]^2
              + \left[\ln\frac{E''(\omega_i, T_i)}{E''_i}\right]^2}

    over the N measured points :math:`(\omega_i, T_i, E'_i, E''_i)`, with :math:`T_i` the temperature measured
    at each point and :math:`E(\omega, T)` the material's modulus. Natural logarithms: M = 0.1 is a typical
    deviation of about 10 %.

    Parameters
    ----------
    material : object
        Anything with ``E(omega, T)``.
    dma : DMAData

    Returns
    -------
    float

    Raises
    ------
    InputError
        When the material gives a non-positive E' or E'' at a data point.

    Examples
    --------
    >>> import numpy as np, materials
    >>> tread = materials.example_tread()
    >>> f, T = np.tile([1.0, 10.0, 100.0], 2), np.repeat([0.0, 20.0], 3)
    >>> E = tread.E(2 * np.pi * f, T)
    >>> dma = materials.DMAData.from_arrays(T, f, E.real, E.imag)
    >>> isotherm_misfit(tread, dma)                # against the material the data came from
    0.0
    >>> print(round(isotherm_misfit(tread, materials.DMAData.from_arrays(T, f, 1.1 * E.real, 1.1 * E.imag)), 4))
    0.0953
    """
    E = material.E(dma.omega, dma.T_C)
    if np.any(E.real <= 0) or np.any(E.imag <= 0) or not np.all(np.isfinite(E)):
        raise InputError("isotherm_misfit: the material gives a non-positive or non-finite modulus at a data point")
    r1 = np.log(E.real / dma.E_storage)
    r2 = np.log(E.imag / dma.E_loss)
    return float(np.sqrt(0.5 * (np.mean(r1 * r1) + np.mean(r2 * r2))))


# ==================================================================================================== helpers

def _describe(law) -> str:
    d = getattr(law, "describe", None)
    return d() if callable(d) else type(law).__name__



def _rescaled(prony, curve, la: float, lb: float):
    """The representation at a reference whose shift is ``la`` (log10 aT) and ``lb`` (log10 bT)."""
    if la == 0.0 and lb == 0.0:
        return prony, curve
    scale = 10.0 ** lb
    if prony is not None:
        prony = Prony(E_inf=prony.E_inf / scale, E_i=prony.E_i / scale, tau_i=prony.tau_i * 10.0 ** la, wlf=None,
                      thermal=prony.thermal, label=prony.label)
    if curve is not None:
        curve = curve.scaled(10.0 ** -la, 1.0 / scale)
    return prony, curve



def _as_thermal(thermal) -> Thermal | None:
    """Thermal, a mapping {density, specific_heat, conductivity} (the case-file form) or None."""
    if thermal is None or isinstance(thermal, Thermal):
        return thermal
    if isinstance(thermal, Mapping):
        unknown = set(thermal) - {"density", "specific_heat", "conductivity"}
        if unknown:
            raise InputError(f"thermal: unknown keys {sorted(unknown)} (expected density, specific_heat, "
                             "conductivity)")
        return Thermal(**{k: float(v) for k, v in thermal.items()})
    raise InputError(f"thermal: expected materials.Thermal or a mapping, got {thermal!r}")

