r"""Master curves: DMA isotherms or a master-curve table -> the material the friction engine evaluates.

.. math:: E(\omega, T) = b_T\, E_{ref}(\omega\, a_T(T))

:func:`master_curve` builds a :class:`MasterCurve` from DMA isotherms: shift factors, a temperature law chosen
by how well it predicts the isotherms (:mod:`materials.shiftfit`), and a representation of the reference curve
:math:`E_{ref}`: an interpolated table (nodes of a smooth curve through the shifted data, used as measured;
:class:`materials.curves.InterpolatedModulus`) or a causal Prony series (generalized Maxwell solid,
:func:`materials.fit_prony`),

.. math:: E_{ref}(\omega) = E_\infty + \sum_i E_i \frac{i\omega\tau_i}{1 + i\omega\tau_i}.

:func:`read_master_curve` reads a master-curve table (the project's ``f_Hz, E_storage_Pa, E_loss_Pa``, pyvisco's
``f, E_stor, E_loss`` with units, instrument exports) and uses it as measured. :func:`isotherm_misfit` is the
measure of quality used throughout. The file formats and options are described in ``docs/materials.md``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Mapping

import numpy as np

from frictioncite import doi

from .curves import CausalityCheck, InterpolatedModulus, causality_check, smooth_master
from .dma import DMAData
from .errors import InputError
from .prony_fit import FitQuality, fit_prony, quality_of
from .shift import SHIFT_LAW_TYPES, SingleTemperature, as_shift_law
from .shiftfit import SHIFT_LAWS, ShiftLawScore, choose_shift_law, score_shift_laws
from .tts import ShiftFactors, TemperatureShift, WLFFit, shift_isotherms
from .viscoelastic import WLF, Prony, Thermal, _reduced_omega

__all__ = ["MasterCurve", "ReducedData", "TabulatedModulus", "master_curve", "read_master_curve",
           "isotherm_misfit", "FITS"]

_CITES = ("10.1021/ja01619a008", "isbn:978-0-471-04894-7", "10.1016/S0020-7683(98)00055-9",
          "10.1137/1.9781611971217", "10.1137/0717021")

#: Representations of the reference curve: ``"table"`` (interpolated nodes), ``"prony"`` (causal Prony series),
#: ``"auto"`` (for DMA data the better of the two against the isotherms; for a table, the table).
FITS = ("auto", "table", "prony")

#: In ``fit="auto"``, the Prony series (causal by construction) is kept when its misfit is within this fraction
#: of the table's.
PRONY_TIE = 0.02


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
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
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
        from .strain import StrainSoftened
        if softening is not None:
            if strain is None:
                raise InputError("at_strain: give the strain amplitude with the softening curve")
            return StrainSoftened.from_softening(self, softening, strain)
        return StrainSoftened(self, 1.0 if storage_factor is None else storage_factor,
                              1.0 if loss_factor is None else loss_factor)

    # ---------------------------------------------------------------- files
    def to_table(self, path, f_Hz=None, *, per_decade: int = 10) -> Path:
        """Write the master-curve table ``f_Hz, E_storage_Pa, E_loss_Pa`` at T_ref, atomically.

        Parameters
        ----------
        path : str or Path
            Destination; written to a temporary file and renamed, so it is complete or absent.
        f_Hz : array_like, optional
            Frequencies (Hz, > 0). Default: an interpolated curve's own nodes (so that reading the table back
            gives the same material); otherwise log-spaced over the data window, ``per_decade`` per decade.

        Returns
        -------
        Path
            The path written. Comment lines give T_ref, the shift law and the fit quality.
        """
        from ._io import write_csv_atomic
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
                                comments=comments)

    @classmethod
    def from_table(cls, path_or_table, wlf=None, *, shift=None, fit: str = "table", T_ref: float | None = None,
                   thermal: Thermal | None = None, per_decade: float = 2.0, label: str | None = None,
                   columns=None, units=None, poisson: float = 0.5, encoding: str | None = None) -> "MasterCurve":
        """Build from a master-curve table (a file, or a mapping with ``f_Hz``, ``E_storage_Pa``, ``E_loss_Pa``).

        See :func:`read_master_curve` for the parameters.
        """
        if isinstance(path_or_table, Mapping):
            f, E1, E2, source, lines = _table_from_mapping(path_or_table)
            notes = []
        else:
            f, E1, E2, source, lines, notes = _read_table_columns(path_or_table, columns, units, poisson, encoding)
        f, E1, E2 = _merge_repeated(f, E1, E2, source, lines, notes)
        law = _table_law(wlf, shift, T_ref, source)
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
                warnings.warn(msg, stacklevel=3)
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
        return self.source.thermal

    @property
    def T_ref(self):
        return self.source.T_ref

    def log10_aT(self, T):
        return self.source.log10_aT(T)

    def E_reference(self, omega):
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
    """
    E = material.E(dma.omega, dma.T_C)
    if np.any(E.real <= 0) or np.any(E.imag <= 0) or not np.all(np.isfinite(E)):
        raise InputError("isotherm_misfit: the material gives a non-positive or non-finite modulus at a data point")
    r1 = np.log(E.real / dma.E_storage)
    r2 = np.log(E.imag / dma.E_loss)
    return float(np.sqrt(0.5 * (np.mean(r1 * r1) + np.mean(r2 * r2))))


# ==================================================================================================== builder

@doi(*_CITES, "10.1214/ss/1038425655")
def master_curve(dma: DMAData, T_ref: float, *, shift_law: str = "auto", shift_factors=None, Tg=None,
                 wlf_range: tuple[float, float] | None = None, fit: str = "auto", progress=None,
                 using: str = "moduli", vertical: bool = False, per_decade: float = 2.0,
                 thermal: Thermal | None = None, label: str | None = None, **shift_options) -> MasterCurve:
    r"""Build a master curve from DMA isotherms.

    Steps: (1) shift factors of the isotherms (automatic, :func:`materials.tts.shift_isotherms`, or given);
    (2) the reference curve from the shifted data (``fit``); (3) the temperature law (``shift_law``), chosen by
    its cross-validated misfit against the isotherms (:mod:`materials.shiftfit`); (4) everything referred to
    ``T_ref`` exactly through that law. The result's ``misfit`` is :func:`isotherm_misfit` against ``dma`` and
    ``scores`` lists every law considered.

    Parameters
    ----------
    dma : DMAData
        At least two isotherms.
    T_ref : float
        Reference temperature, deg C.
    shift_law : {"auto", "wlf", "wlf+arrhenius", "arrhenius", "tabulated"}
        ``"auto"`` (default) fits all four and keeps the one with the smallest leave-one-isotherm-out misfit
        (a simpler law within 2 % of it is preferred).
    shift_factors : optional
        Shifts to use instead of the automatic ones: a shift law (``materials.WLF``, ``WLFArrhenius``,
        ``Arrhenius``, ``TabulatedShift``, e.g. from :func:`materials.read_shift_factors`), which is then also
        the material's law; or per-isotherm values (``ShiftFactors``, a mapping ``{T_C: log10_aT}`` matched to
        the nearest isotherm within 3 K, or an array with one value per isotherm), to which the laws are fitted.
    Tg : float or "auto", optional
        Glass transition (deg C) where ``"wlf+arrhenius"`` hands over from WLF to Arrhenius; default (or
        ``"auto"``) the split between isotherms with the smallest BIC.
    wlf_range : (float, float), optional
        Temperature range (deg C) of the WLF fit.
    fit : {"auto", "table", "prony"}
        Representation of the reference curve. ``"table"``: nodes (10 per decade) of a smooth curve through the
        shifted data (penalised B-splines, :func:`materials.curves.smooth_master`; E' made non-decreasing),
        interpolated and extrapolated like a measured table. ``"prony"``: a causal Prony series fitted by NNLS
        (``per_decade`` relaxation times per decade). ``"auto"``: the one with the smaller misfit against the
        isotherms; the Prony series when within 2 % (causal by construction).
    progress : callable, optional
        Called as ``progress(message, fraction)`` (a short status string and a fraction of the work done, or
        None) at each stage, for long fits.
    using, vertical, **shift_options
        Passed to :func:`materials.tts.shift_isotherms` (``using="tan_delta"``, ``vertical=True``,
        ``max_step``, ``refine``, ...).
    per_decade : float
        Relaxation times per decade of a Prony series.
    thermal : Thermal or mapping, optional
        Thermal properties carried by the material (default :class:`Thermal`).
    label : str, optional

    Returns
    -------
    MasterCurve

    Raises
    ------
    InputError
        Bad data or options (one isotherm, unmatched user shift factors, unknown shift law, ...).
    """
    if not isinstance(dma, DMAData):
        raise InputError(f"dma: expected materials.DMAData (from materials.read_dma), got {type(dma).__name__}")
    try:
        T_ref = float(T_ref)
    except (TypeError, ValueError):
        raise InputError(f"T_ref: expected a finite temperature in deg C, got {T_ref!r}") from None
    if not math.isfinite(T_ref):
        raise InputError(f"T_ref: expected a finite temperature in deg C, got {T_ref!r}")
    if shift_law != "auto" and shift_law not in SHIFT_LAWS:
        raise InputError(f"shift_law: expected 'auto' or one of {', '.join(SHIFT_LAWS)}, got {shift_law!r}")
    if fit not in FITS:
        raise InputError(f"fit: expected one of {', '.join(FITS)}, got {fit!r}")
    if Tg is not None and not (Tg == "auto" or (isinstance(Tg, (int, float)) and math.isfinite(Tg))):
        raise InputError(f"Tg: expected a temperature in deg C, None or 'auto', got {Tg!r}")
    if Tg is not None and Tg != "auto" and shift_law in ("wlf", "arrhenius"):
        raise InputError(f"Tg: a glass transition applies to shift_law='wlf+arrhenius' (or 'auto'), not "
                         f"{shift_law!r}")
    if wlf_range is not None:
        try:
            lo, hi = (float(v) for v in wlf_range)
        except (TypeError, ValueError):
            raise InputError(f"wlf_range: expected (T_min, T_max) in deg C, got {wlf_range!r}") from None
        if not lo < hi:
            raise InputError(f"wlf_range: expected T_min < T_max, got {wlf_range!r}")
        wlf_range = (lo, hi)
    if dma.n_isotherms < 2:
        raise InputError(f"{dma.source}: one isotherm only (T = {dma.T_isotherm[0]:.1f} C); a master curve "
                         "needs at least two isotherms")
    if not (isinstance(per_decade, (int, float)) and per_decade > 0):
        raise InputError(f"per_decade: expected a positive number of relaxation times per decade, got {per_decade!r}")
    report = _progress(progress)
    thermal = _as_thermal(thermal)
    notes = list(dma.notes)
    dma = _linear_strain_only(dma, notes)
    label = label or f"master curve from {dma.source}"
    if dma.shear_converted:
        label += f" (shear data converted, nu = {dma.poisson:g})"

    # --- 1. shift factors of the isotherms, anchored at the isotherm nearest T_ref
    report("shifting the isotherms", 0.0)
    given_law = _given_law(shift_factors)
    if given_law is not None:
        if shift_law != "auto":
            raise InputError(f"shift_law={shift_law!r} conflicts with shift_factors=<a shift law>: give one")
        T_iso = np.asarray(dma.T_isotherm, dtype=float)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            la_law = np.asarray(given_law.log10_aT(T_iso), dtype=float)
        _forward(caught, notes)
        sf = ShiftFactors(T_C=T_iso, log10_aT=la_law, log10_bT=np.zeros_like(T_iso), T_ref=float(given_law.T_ref),
                          method="given shift law")
    elif shift_factors is None:
        sf = shift_isotherms(dma, T_ref, using=using, vertical=vertical, **shift_options)
    else:
        sf = _user_shifts(dma, shift_factors, T_ref)
    sf = _anchor(sf, T_ref, wlf_range, Tg if given_law is None else None)
    T0 = sf.T_ref

    # --- 2. the reference curve at T0 from the shifted data
    report("fitting the reference curve", 0.5)
    k = dma.isotherm
    lb_pt = sf.log10_bT[k]
    omega_0 = dma.omega * 10.0 ** sf.log10_aT[k]
    E1_0, E2_0 = dma.E_storage / 10.0 ** lb_pt, dma.E_loss / 10.0 ** lb_pt
    reps = _representations(fit, omega_0, E1_0, E2_0, per_decade, thermal, label)

    def residuals(rep, la_pt, idx):
        E = rep.E_reference(dma.omega[idx] * 10.0 ** la_pt) * 10.0 ** lb_pt[idx]
        return np.concatenate([np.log(E.real / dma.E_storage[idx]), np.log(E.imag / dma.E_loss[idx])])

    measured = {name: _rms(residuals(rep, sf.log10_aT[k], np.arange(k.size))) for name, (rep, _) in reps.items()}
    rep_name = _choose_representation(measured)
    rep, rep_info = reps[rep_name]
    if len(reps) > 1:
        notes.append("reference curve: " + ", ".join(f"{n} misfit {measured[n]:.4g}" for n in reps)
                     + f" against the isotherms with their own shifts; {rep_name} kept")

    # --- 3. the temperature law
    report("choosing the temperature law", 0.7)
    point_T = np.asarray(dma.T_C, dtype=float)
    points_of = dma.isotherm_indices()

    def misfit_of(law, isotherms):
        idx = np.concatenate([points_of[i] for i in isotherms])
        return residuals(rep, np.asarray(law.log10_aT(point_T[idx]), dtype=float), idx)

    if given_law is not None:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            law = given_law.with_T_ref(T0) if abs(float(given_law.T_ref) - T0) > 0 else given_law
            score = ShiftLawScore("given", law, 0.0, math.inf)
            score = replace(score, misfit=_rms(misfit_of(score, np.arange(dma.n_isotherms))))
        scores = [score]
        chosen = score
    else:
        kinds = SHIFT_LAWS if shift_law == "auto" else (shift_law,)
        scores = score_shift_laws(kinds, sf.T_C, sf.log10_aT, T0, misfit_of, Tg=Tg, wlf_range=wlf_range)
        chosen = choose_shift_law(scores)
        if shift_law == "auto":
            notes.append("temperature law: " + "; ".join(
                f"{s.name} misfit {s.misfit:.4g} (cross-validated {s.misfit_loo:.4g})" if s.available
                else f"{s.name} unavailable" for s in scores) + f"; {chosen.name} kept")
    law = chosen.law
    wlf_fit = _wlf_fit_of(law, sf)
    _warn_poor_wlf(law, wlf_fit, sf, dma.source, notes, shift_law)

    # --- 4. everything referred to T_ref
    report("referring to T_ref", 0.9)
    if not (sf.T_C.min() <= T_ref <= sf.T_C.max()):
        msg = (f"T_ref = {T_ref:g} C lies outside the measured isotherms ({sf.T_C.min():.1f} to "
               f"{sf.T_C.max():.1f} C): the reference is reached by extrapolating the temperature law")
        warnings.warn(msg, stacklevel=2)
        notes.append(msg)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        la_ref = float(chosen.log10_aT(T_ref))         # the law's shift of T_ref relative to the data's frame
    lb_ref = float(np.interp(T_ref, sf.T_C, sf.log10_bT))
    prony = rep if rep_name == "prony" else None
    curve = rep if rep_name == "table" else None
    prony, curve = _rescaled(prony, curve, la_ref, lb_ref)
    sf = sf.rereferenced(T_ref, la_ref, lb_ref)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        law = law.with_T_ref(T_ref) if abs(float(law.T_ref) - T_ref) > 0 else law
    if wlf_fit is not None and getattr(law, "wlf", None) is not None:
        wlf_fit = replace(wlf_fit, wlf=law.wlf)
    notes.append(f"temperature law ({chosen.name}): {_describe(law)}")
    omega_r = dma.omega * 10.0 ** sf.log10_aT[k]
    bT = 10.0 ** sf.log10_bT[k]
    E1, E2 = dma.E_storage / bT, dma.E_loss / bT
    quality = replace(quality_of(prony or curve, omega_r, E1, E2, representation=rep_name),
                      shift_rms_log10=sf.rms_log10)
    check = None
    if curve is not None:
        check = causality_check(curve.omega, curve.E_storage, curve.E_loss, scatter=rep_info)
        if not check.ok:
            msg = check.message(dma.source)
            warnings.warn(msg, stacklevel=2)
            notes.append(msg)
    mc = MasterCurve(prony=prony, curve=curve, shift=law, quality=quality, thermal=thermal or Thermal(),
                     shift_factors=sf, wlf_fit=wlf_fit,
                     reduced=ReducedData(omega=omega_r, E_storage=E1, E_loss=E2, T_C=np.asarray(dma.T_C)),
                     label=label, notes=tuple(notes), scores=tuple(scores), causality=check)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mc = replace(mc, misfit=isotherm_misfit(mc, dma))
    report("master curve done", 1.0)
    return mc


def read_master_curve(path, wlf=None, *, shift=None, fit: str = "table", columns=None, units=None,
                      T_ref: float | None = None, thermal: Thermal | None = None, per_decade: float = 2.0,
                      label: str | None = None, poisson: float = 0.5, encoding: str | None = None) -> MasterCurve:
    r"""Read a master-curve table (frequency, E', E'' at one temperature) and use it as measured.

    Accepted files: the project's ``f_Hz, E_storage_Pa, E_loss_Pa``; pyvisco's master curve (``f, E_stor,
    E_loss`` then a units row ``Hz, MPa, MPa``); instrument and spreadsheet exports separated by commas, tabs,
    semicolons or spaces, with a names row (units in brackets or as suffixes: ``f [Hz]``, ``E' (MPa)``,
    ``E_storage_MPa``), optionally a units row, or no header at all (then the columns are frequency in Hz, E'
    and E'' in Pa unless ``columns=``/``units=`` say otherwise). Shear moduli (``G'``, ``G_storage``) are
    converted with :math:`E = 2(1+\nu)G`. Rows repeating a frequency (within 1e-9) are merged (geometric mean)
    with a warning.

    Parameters
    ----------
    path : str or Path
    wlf : WLF, TemperatureShift or mapping, optional
        The table's WLF law (``{"C1": .., "C2": .., "T_ref_C": ..}`` as in the case file).
    shift : shift law or mapping, optional
        Any shift law instead (e.g. ``materials.read_shift_factors("shift.csv")``, a ``WLFArrhenius``).
        Give ``wlf`` or ``shift``; with neither, give ``T_ref`` and the material is usable at that temperature
        only (:class:`materials.SingleTemperature`: any other temperature raises).
    fit : {"table", "auto", "prony"}
        ``"table"`` (default; ``"auto"`` is the same for a table): the nodes are interpolated (PCHIP in
        log-log; every node reproduced exactly) and extrapolated with flat E' and a power-law E''
        (:class:`materials.curves.InterpolatedModulus`), and a Kramers-Kronig check warns where the table
        looks non-causal. ``"prony"``: a causal Prony series is fitted instead and its misfit reported.
    columns : sequence or mapping, optional
        Names of the file's columns in order (e.g. ``["f_Hz", "E_storage_MPa", "E_loss_MPa"]``, ``None`` to
        skip one), or ``{"f": name or index, "E_storage": ..., "E_loss": ...}``.
    units : mapping, optional
        ``{"f": "Hz" | "rad/s", "E": "Pa" | "kPa" | "MPa" | "GPa"}``: the user's word, overriding the file.
    T_ref : float, optional
        Temperature of the table, deg C (default the shift law's reference temperature).
    thermal : Thermal or mapping, optional
    per_decade : float
        Relaxation times per decade for ``fit="prony"``.
    label : str, optional
    poisson : float
        Poisson ratio for shear data.
    encoding : str, optional

    Returns
    -------
    MasterCurve

    Raises
    ------
    InputError
        Missing columns, unknown units, moduli outside any polymer's range (a Pa/MPa slip), bad values, no
        shift law and no T_ref (naming the file, line, column or argument).
    """
    return MasterCurve.from_table(path, wlf, shift=shift, fit=fit, T_ref=T_ref, thermal=thermal,
                                  per_decade=per_decade, label=label, columns=columns, units=units,
                                  poisson=poisson, encoding=encoding)


# ==================================================================================================== helpers

def _progress(progress):
    if progress is None:
        return lambda message, fraction=None: None
    if not callable(progress):
        raise InputError(f"progress: expected a callable progress(message, fraction), got {progress!r}")
    return lambda message, fraction=None: progress(message, fraction)


def _rms(r) -> float:
    r = np.asarray(r, dtype=float)
    return float(np.sqrt(np.mean(r * r))) if np.all(np.isfinite(r)) else math.inf


def _describe(law) -> str:
    d = getattr(law, "describe", None)
    return d() if callable(d) else type(law).__name__


def _forward(caught, notes):
    """Re-issue caught warnings once each and keep them as notes."""
    for msg in dict.fromkeys(str(w.message) for w in caught):
        warnings.warn(msg, stacklevel=3)
        notes.append(msg)


def _representations(fit, omega, E1, E2, per_decade, thermal, label) -> dict:
    """{"table": (InterpolatedModulus, scatter), "prony": (Prony, None)} as asked by ``fit``."""
    out = {}
    if fit in ("auto", "table"):
        w, s1, s2, scatter = smooth_master(np.log10(omega), np.log(E1), np.log(E2))
        out["table"] = (InterpolatedModulus(w, s1, s2, source="smoothed shifted isotherms"), scatter)
    if fit in ("auto", "prony"):
        out["prony"] = (fit_prony(omega, E1, E2, per_decade=per_decade, thermal=thermal, label=label).prony, None)
    return out


def _choose_representation(misfits: dict) -> str:
    if len(misfits) == 1:
        return next(iter(misfits))
    return "prony" if misfits["prony"] <= misfits["table"] * (1.0 + PRONY_TIE) else "table"


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


def _given_law(shift_factors):
    """The shift law in ``shift_factors`` (a law object or a mapping of its constants), else None."""
    if shift_factors is None or isinstance(shift_factors, ShiftFactors):
        return None
    if isinstance(shift_factors, SHIFT_LAW_TYPES):
        return shift_factors
    if isinstance(shift_factors, Mapping) and any(isinstance(key, str) and key in ("C1", "E_a")
                                                  for key in shift_factors):
        return as_shift_law(shift_factors, name="shift_factors")
    if callable(getattr(shift_factors, "log10_aT", None)) and hasattr(shift_factors, "T_ref"):
        return shift_factors
    return None


def _anchor(sf: ShiftFactors, T_ref: float, wlf_range, Tg) -> ShiftFactors:
    """Shift factors referred to the isotherm nearest T_ref (inside ``wlf_range`` and above ``Tg`` when given)."""
    T = sf.T_C
    m = np.ones(T.size, dtype=bool)
    if wlf_range is not None:
        m &= (T >= wlf_range[0]) & (T <= wlf_range[1])
    if isinstance(Tg, (int, float)):
        m &= T >= Tg
    if not m.any():
        raise InputError(f"no isotherm in the WLF range (wlf_range={wlf_range}, Tg={Tg}); isotherms span "
                         f"{T.min():.1f} to {T.max():.1f} C")
    i0 = int(np.flatnonzero(m)[np.argmin(np.abs(T[m] - T_ref))])
    if T[i0] == sf.T_ref and sf.log10_aT[i0] == 0.0:
        return sf
    return sf.rereferenced(float(T[i0]), float(sf.log10_aT[i0]), float(sf.log10_bT[i0]))


def _wlf_fit_of(law, sf: ShiftFactors) -> WLFFit | None:
    """The WLF fit with covariance behind a WLF-based law, refitted on its isotherms (None otherwise)."""
    if not isinstance(law, TemperatureShift):
        return None
    from .tts import fit_wlf
    w = law.wlf
    T, y = sf.T_C, sf.log10_aT
    m = T >= (law.arrhenius.T_g if law.arrhenius is not None else -np.inf)
    y = y - float(np.interp(w.T_ref, T, y)) if w.T_ref not in T else y - float(y[T == w.T_ref][0])
    if np.sum(m & (T != w.T_ref)) < 2:
        return None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            fit = fit_wlf(T[m], y[m], w.T_ref, valid_from=(law.arrhenius.T_g if law.arrhenius else T.min()))
    except InputError:
        return None
    return replace(fit, wlf=w)


def _warn_poor_wlf(law, wlf_fit, sf, source, notes, shift_law):
    if wlf_fit is None or not isinstance(law, TemperatureShift):
        return
    if wlf_fit.rms > 0.25 or wlf_fit.C1 > 1e3 or wlf_fit.C2 > 1e4:
        msg = (f"{source}: the WLF law describes the shift factors poorly (C1 = {wlf_fit.C1:.3g}, "
               f"C2 = {wlf_fit.C2:.3g} K, rms {wlf_fit.rms:.2f} decades over {wlf_fit.T_range[0]:.1f} to "
               f"{wlf_fit.T_range[1]:.1f} C)" + ("; shift_law='auto' compares it with the other laws"
                                                 if shift_law != "auto" else ""))
        warnings.warn(msg, stacklevel=3)
        notes.append(msg)


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


def _linear_strain_only(dma: DMAData, notes: list) -> DMAData:
    """With strain sweeps mixed in, keep the smallest strain of each (isotherm, frequency): the linear modulus."""
    if dma.strain is None:
        return dma
    key = dma.isotherm * 1e12 + np.round(np.log10(dma.f_Hz), 9) * 1e3
    order = np.lexsort((dma.strain, key))
    first = np.ones(order.size, dtype=bool)
    first[1:] = key[order][1:] != key[order][:-1]
    keep = np.zeros(dma.f_Hz.size, dtype=bool)
    keep[order[first]] = True
    if keep.all():
        return dma
    msg = (f"{dma.source}: several strain amplitudes per isotherm and frequency; the master curve uses the "
           f"smallest (linear) one ({int((~keep).sum())} points left out; use materials.strain_factors for "
           "the rest)")
    warnings.warn(msg, stacklevel=3)
    notes.append(msg)
    return dma.select(keep)


def _table_law(wlf, shift, T_ref, source):
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


def _table_from_mapping(table):
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


def _read_table_columns(path, columns, units, poisson, encoding):
    from ._tables import pick_columns, read_table
    from .units import check_moduli, normalise_units
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


def _merge_repeated(f, E1, E2, source, lines, notes):
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
    warnings.warn(msg, stacklevel=4)
    notes.append(msg)
    return gmean(f), gmean(E1), gmean(E2)


def _user_shifts(dma: DMAData, given, T_ref: float) -> ShiftFactors:
    T_iso = np.asarray(dma.T_isotherm, dtype=float)
    if isinstance(given, ShiftFactors):
        vals = _match(T_iso, dict(zip(given.T_C.tolist(), given.log10_aT.tolist())), dma.source)
        b = _match(T_iso, dict(zip(given.T_C.tolist(), given.log10_bT.tolist())), dma.source)
        return ShiftFactors(T_C=T_iso, log10_aT=vals, log10_bT=b, T_ref=given.T_ref, method="user",
                            rms_log10=None)
    if isinstance(given, Mapping):
        try:
            table = {float(k): float(v) for k, v in given.items()}
        except (TypeError, ValueError):
            raise InputError("shift_factors: expected a mapping {T_C: log10_aT} of numbers, or a shift law") from None
        vals = _match(T_iso, table, dma.source)
        zero = [t for t, v in table.items() if v == 0.0]
        T0 = float(T_iso[int(np.argmin(np.abs(T_iso - zero[0])))]) if len(zero) == 1 else T_ref
        return ShiftFactors(T_C=T_iso, log10_aT=vals, log10_bT=np.zeros_like(T_iso), T_ref=T0, method="user")
    try:
        arr = np.asarray(given, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"shift_factors: expected a shift law, ShiftFactors, a mapping {{T_C: log10_aT}} or one "
                         f"value per isotherm, got {type(given).__name__}") from None
    if arr.size != T_iso.size:
        raise InputError(f"shift_factors: expected {T_iso.size} values (one per isotherm, increasing T), "
                         f"got {arr.size}")
    zero = np.flatnonzero(arr == 0.0)
    T0 = float(T_iso[zero[0]]) if zero.size == 1 else T_ref
    return ShiftFactors(T_C=T_iso, log10_aT=arr, log10_bT=np.zeros_like(T_iso), T_ref=T0, method="user")


def _match(T_iso, table: dict, source, tol=3.0) -> np.ndarray:
    keys = np.array(sorted(table))
    out = np.empty(T_iso.size)
    for i, T in enumerate(T_iso):
        j = int(np.argmin(np.abs(keys - T)))
        if abs(keys[j] - T) > tol:
            raise InputError(f"shift_factors: no value for the isotherm at {T:.1f} C of {source} "
                             f"(nearest given temperature {keys[j]:g} C, tolerance {tol:g} K)")
        out[i] = table[keys[j]]
    return out
