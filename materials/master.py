r"""Master curves: DMA isotherms -> shift factors -> WLF (+ Arrhenius) -> causal Prony series.

:func:`master_curve` is the one-call path from :class:`~materials.dma.DMAData` to a :class:`MasterCurve`, the
material the friction engine evaluates: ``E(omega, T)`` (complex Young's modulus, vectorized, Im E odd in
omega), ``log10_aT(T)``, ``thermal``. A MasterCurve can also be built from a DESIGN.md master-curve table
(``f_Hz, E_storage_Pa, E_loss_Pa`` at T_ref) plus WLF constants (:func:`read_master_curve`), and written back
to one (:meth:`MasterCurve.to_table`).

.. math:: E(\omega, T) = b_T\, E_{ref}(\omega a_T),\qquad
          E_{ref}(\omega) = E_\infty + \sum_i E_i \frac{i\omega\tau_i}{1 + i\omega\tau_i}
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Mapping

import numpy as np

from frictioncite import doi

from .dma import DMAData
from .errors import InputError
from .prony_fit import FitQuality, fit_prony
from .tts import (ShiftFactors, TemperatureShift, WLFFit, fit_arrhenius, fit_wlf, shift_isotherms,
                  wlf_change_reference)
from .viscoelastic import WLF, Prony, Thermal, _reduced_omega

__all__ = ["MasterCurve", "ReducedData", "TabulatedModulus", "master_curve", "read_master_curve"]

_CITES = ("10.1021/ja01619a008", "isbn:978-0-471-04894-7", "10.1016/S0020-7683(98)00055-9",
          "10.1137/1.9781611971217")


@dataclass(frozen=True, eq=False)
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


@doi(*_CITES)
@dataclass(frozen=True, eq=False)
class MasterCurve:
    r"""A viscoelastic master curve: causal Prony series at T_ref plus a temperature shift law.

    .. math:: E(\omega, T) = b_T\, E_{ref}(\omega\, a_T(T))

    Attributes
    ----------
    prony : Prony
        Generalized Maxwell series at the reference temperature (no WLF of its own).
    shift : TemperatureShift
        WLF law (with Arrhenius below T_g when fitted); ``wlf`` and ``log10_aT`` come from it.
    quality : FitQuality
        RMS relative residual of the Prony series in E' and E'' over the (shifted) data.
    thermal : Thermal
        Density, specific heat, conductivity.
    shift_factors : ShiftFactors or None
        Per-isotherm shifts (None when built from a table).
    wlf_fit : WLFFit or None
        The WLF fit with its covariance (None when WLF constants were given).
    reduced : ReducedData or None
        The shifted data (for plots and checks).
    label : str
        Where it came from.
    notes : tuple of str
        What was done (shear conversion, extrapolated reference, ...).
    """

    prony: Prony
    shift: TemperatureShift
    quality: FitQuality
    thermal: Thermal = field(default_factory=Thermal)
    shift_factors: ShiftFactors | None = None
    wlf_fit: WLFFit | None = None
    reduced: ReducedData | None = None
    label: str = ""
    notes: tuple[str, ...] = ()

    # ---------------------------------------------------------------- the material interface
    @property
    def T_ref(self) -> float:
        """Reference temperature, deg C."""
        return self.shift.T_ref

    @property
    def wlf(self) -> WLF:
        """The WLF law (constants C1, C2 at T_ref)."""
        return self.shift.wlf

    def log10_aT(self, T):
        """log10 of the horizontal shift factor at ``T`` (deg C); WLF, Arrhenius below T_g when set."""
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
        return self.prony.E_reference(omega)

    def E(self, omega, T=None):
        """Complex Young's modulus E' + i E'', Pa, at ``omega`` (rad/s, any sign) and ``T`` (deg C).

        Vectorized; ``omega`` and ``T`` broadcast. Im E is odd in omega, E(0) = E_inf (real, finite).
        ``T=None`` means the reference temperature.
        """
        omega = np.asarray(omega, dtype=float)
        if T is None:
            return self.prony.E_reference(omega)
        T = np.asarray(T, dtype=float)
        E = self.prony.E_reference(_reduced_omega(omega, self.log10_aT(T)))
        if self.shift_factors is not None and np.any(self.shift_factors.log10_bT):
            E = E * 10.0 ** self.log10_bT(T)
        return E

    # ---------------------------------------------------------------- derived objects
    def with_thermal(self, thermal) -> "MasterCurve":
        """The same material with other thermal properties (a Thermal or a mapping as in the case file)."""
        th = _as_thermal(thermal)
        if th is None:
            raise InputError("with_thermal: expected materials.Thermal or a mapping, got None")
        return replace(self, thermal=th, prony=replace(self.prony, thermal=th))

    def with_T_ref(self, T_ref: float) -> "MasterCurve":
        r"""The same material referred to another reference temperature.

        Relaxation times scale by :math:`a_T(T_{ref}')` and moduli by :math:`b_T(T_{ref}')`; the WLF constants
        change exactly (:func:`materials.tts.wlf_change_reference`).
        """
        if not math.isfinite(T_ref):
            raise InputError(f"T_ref: expected a finite temperature in deg C, got {T_ref!r}")
        la = float(self.log10_aT(T_ref))
        lb = float(self.log10_bT(T_ref))
        scale = 10.0 ** lb
        p = self.prony
        prony = Prony(E_inf=p.E_inf * scale, E_i=p.E_i * scale, tau_i=p.tau_i * 10.0 ** la, wlf=None,
                      thermal=p.thermal, label=p.label)
        sf = None if self.shift_factors is None else self.shift_factors.rereferenced(T_ref, la, lb)
        red = self.reduced
        if red is not None:
            red = replace(red, omega=red.omega / 10.0 ** la, E_storage=red.E_storage / scale,
                          E_loss=red.E_loss / scale)
        fit = self.wlf_fit
        if fit is not None:
            fit = replace(fit, wlf=wlf_change_reference(fit.wlf, T_ref))
        return replace(self, prony=prony, shift=self.shift.with_T_ref(T_ref), shift_factors=sf, reduced=red,
                       wlf_fit=fit, notes=self.notes + (f"reference temperature changed to {T_ref:g} C",))

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
        """Write the DESIGN.md master-curve table ``f_Hz, E_storage_Pa, E_loss_Pa`` at T_ref, atomically.

        Parameters
        ----------
        path : str or Path
            Destination; written to a temporary file and renamed, so it is complete or absent.
        f_Hz : array_like, optional
            Frequencies (Hz, > 0). Default: log-spaced over the reduced-frequency window of the data (or of
            the relaxation times), ``per_decade`` per decade.

        Returns
        -------
        Path
            The path written. Comment lines give T_ref, the WLF constants and the fit quality.
        """
        from ._io import write_csv_atomic
        if f_Hz is None:
            if self.reduced is not None:
                lo, hi = np.log10(self.reduced.f_Hz.min()), np.log10(self.reduced.f_Hz.max())
            else:
                lo = -np.log10(2 * np.pi * self.prony.tau_i.max())
                hi = -np.log10(2 * np.pi * self.prony.tau_i.min())
            n = max(2, int(math.ceil((hi - lo) * per_decade)) + 1)
            f_Hz = np.logspace(lo, hi, n)
        f_Hz = np.asarray(f_Hz, dtype=float).ravel()
        if not (f_Hz.size > 0 and np.all(np.isfinite(f_Hz)) and np.all(f_Hz > 0)):
            raise InputError("to_table: f_Hz must be finite positive frequencies in Hz")
        E = self.E_reference(2 * np.pi * f_Hz)
        w = self.wlf
        comments = [f"master curve at T_ref = {self.T_ref:g} C ({self.label or 'materials.MasterCurve'})",
                    f"wlf = {{ C1 = {w.C1:.6g}, C2 = {w.C2:.6g}, T_ref_C = {w.T_ref:.6g} }}",
                    str(self.quality)]
        if self.shift.arrhenius is not None:
            a = self.shift.arrhenius
            comments.append(f"below T_g = {a.T_g:g} C: Arrhenius, E_a = {a.E_a:.6g} J/mol")
        comments.extend(self.notes)
        return write_csv_atomic(path, {"f_Hz": f_Hz, "E_storage_Pa": E.real, "E_loss_Pa": E.imag},
                                comments=comments)

    @classmethod
    def from_table(cls, path_or_table, wlf, *, thermal: Thermal | None = None, per_decade: float = 2.0,
                   label: str | None = None) -> "MasterCurve":
        """Build from a master-curve table (``f_Hz, E_storage_Pa, E_loss_Pa`` at T_ref) and WLF constants.

        Parameters
        ----------
        path_or_table : str, Path or mapping
            A CSV file, or a mapping with arrays ``f_Hz``, ``E_storage_Pa``, ``E_loss_Pa``.
        wlf : WLF, TemperatureShift or mapping
            ``{"C1": .., "C2": .., "T_ref_C": ..}`` as in the case file; T_ref is the table's temperature.
        thermal : Thermal, optional
        per_decade : float
            Relaxation times per decade of the Prony series fitted to the table (E(omega) is causal and
            defined at every frequency; the table is only its sample).
        """
        if isinstance(path_or_table, Mapping):
            try:
                f = np.asarray(path_or_table["f_Hz"], dtype=float)
                E1 = np.asarray(path_or_table["E_storage_Pa"], dtype=float)
                E2 = np.asarray(path_or_table["E_loss_Pa"], dtype=float)
            except KeyError as exc:
                raise InputError(f"master-curve table: missing column {exc.args[0]!r} "
                                 "(expected f_Hz, E_storage_Pa, E_loss_Pa)") from None
            source = "<table>"
            line = np.arange(f.size) + 1
        else:
            from ._io import read_csv_columns
            cols, line = read_csv_columns(path_or_table, ["f_Hz", "E_storage_Pa", "E_loss_Pa"])
            f, E1, E2 = cols["f_Hz"], cols["E_storage_Pa"], cols["E_loss_Pa"]
            source = str(path_or_table)
        for name, a in (("f_Hz", f), ("E_storage_Pa", E1), ("E_loss_Pa", E2)):
            ok = np.isfinite(a) & (a > 0)
            if not np.all(ok):
                i = int(np.flatnonzero(~ok)[0])
                raise InputError(f"{source}, line {int(line[i])}, column {name!r}: expected a positive number, "
                                 f"got {a[i]!r}")
        if f.size < 2:
            raise InputError(f"{source}: a master-curve table needs at least two rows")
        if np.unique(f).size != f.size:
            raise InputError(f"{source}: repeated frequencies in column 'f_Hz' (one row per frequency expected)")
        shift = _as_shift(wlf)
        thermal = _as_thermal(thermal)
        fit = fit_prony(2 * np.pi * f, E1, E2, per_decade=per_decade, thermal=thermal,
                        label=label or f"master-curve table {source}")
        return cls(prony=fit.prony, shift=shift, quality=fit.quality, thermal=thermal or Thermal(),
                   reduced=ReducedData(omega=2 * np.pi * f, E_storage=E1, E_loss=E2),
                   label=label or f"master-curve table {source}")

    def summary(self) -> str:
        """A few lines saying what this material is and how good its fit is."""
        w = self.wlf
        lines = [f"MasterCurve {self.label}".rstrip(),
                 f"  T_ref = {self.T_ref:g} C, WLF C1 = {w.C1:.4g}, C2 = {w.C2:.4g} K"
                 + (f" (+- {self.wlf_fit.stderr[0]:.2g}, {self.wlf_fit.stderr[1]:.2g})" if self.wlf_fit else ""),
                 f"  E_inf = {self.prony.E_inf:.4g} Pa, E_glassy = {self.prony.E_glassy:.4g} Pa",
                 f"  {self.quality}"]
        if self.shift.arrhenius is not None:
            lines.append(f"  Arrhenius below T_g = {self.shift.arrhenius.T_g:g} C, "
                         f"E_a = {self.shift.arrhenius.E_a / 1e3:.4g} kJ/mol")
        lines += [f"  note: {n}" for n in self.notes]
        return "\n".join(lines)


@dataclass(frozen=True, eq=False)
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


# ==================================================================================================== builder

@doi(*_CITES, "10.1214/ss/1038425655")
def master_curve(dma: DMAData, T_ref: float, *, shift_factors=None, using: str = "moduli",
                 vertical: bool = False, Tg: float | None = None, wlf_range: tuple[float, float] | None = None,
                 per_decade: float = 2.0, thermal: Thermal | None = None, label: str | None = None,
                 **shift_options) -> MasterCurve:
    r"""Build a master curve from DMA isotherms.

    Steps: shift factors (automatic, :func:`materials.tts.shift_isotherms`, or given), WLF fit with covariance
    (over ``wlf_range`` and/or above ``Tg``), Arrhenius below ``Tg`` when isotherms lie there, reference changed
    to ``T_ref`` exactly through the fitted law, and a causal Prony series fitted to the shifted data by NNLS
    (:func:`materials.prony_fit.fit_prony`), whose RMS relative residual is the reported ``quality``.

    Parameters
    ----------
    dma : DMAData
        At least two isotherms.
    T_ref : float
        Reference temperature, deg C.
    shift_factors : ShiftFactors, WLF, TemperatureShift, mapping {T_C: log10_aT} or array, optional
        User shift factors instead of the automatic ones. A mapping is matched to the nearest isotherm
        (within 3 K); an array must have one value per isotherm (increasing temperature). Values are taken
        relative to the temperature where they are 0 (or to ``T_ref`` if none is 0).
    using, vertical, **shift_options
        Passed to :func:`materials.tts.shift_isotherms` (``using="tan_delta"``, ``vertical=True``,
        ``max_step``, ``refine``, ...).
    Tg : float or "auto", optional
        Glass transition, deg C: WLF is fitted above it, an Arrhenius law below it. ``"auto"`` picks the
        split between isotherms that describes the shift factors best (BIC over WLF-only and every
        WLF-above/Arrhenius-below split with at least three isotherms above).
    wlf_range : (float, float), optional
        Temperature range (deg C) of the WLF fit.
    per_decade : float
        Relaxation times per decade of the Prony series.
    thermal : Thermal, optional
        Thermal properties carried by the material (default :class:`Thermal`).
    label : str, optional

    Returns
    -------
    MasterCurve

    Raises
    ------
    InputError
        Bad data or options (one isotherm, unmatched user shift factors, ...).
    """
    if not isinstance(dma, DMAData):
        raise InputError(f"dma: expected materials.DMAData (from materials.read_dma), got {type(dma).__name__}")
    if T_ref is None or not math.isfinite(float(T_ref)):
        raise InputError(f"T_ref: expected a finite temperature in deg C, got {T_ref!r}")
    T_ref = float(T_ref)
    if dma.n_isotherms < 2:
        raise InputError(f"{dma.source}: one isotherm only (T = {dma.T_isotherm[0]:.1f} C); a master curve "
                         "needs at least two isotherms")
    if not (isinstance(per_decade, (int, float)) and per_decade > 0):
        raise InputError(f"per_decade: expected a positive number of relaxation times per decade, got {per_decade!r}")
    thermal = _as_thermal(thermal)
    notes = list(dma.notes)
    dma = _linear_strain_only(dma, notes)

    # --- 1. shift factors relative to some T0
    if shift_factors is None:
        sf = shift_isotherms(dma, T_ref, using=using, vertical=vertical, **shift_options)
    else:
        sf = _user_shifts(dma, shift_factors, T_ref)
    T0 = sf.T_ref

    # --- 2. temperature law: WLF over its range (above Tg), Arrhenius below Tg
    T_iso, la = sf.T_C, sf.log10_aT
    wlf_fit = None
    if isinstance(shift_factors, (WLF, TemperatureShift)):
        shift = shift_factors if isinstance(shift_factors, TemperatureShift) else TemperatureShift(shift_factors)
        shift = shift.with_T_ref(T0) if abs(shift.T_ref - T0) > 0 else shift
    else:
        if isinstance(Tg, str):
            if Tg != "auto":
                raise InputError(f"Tg: expected a temperature in deg C, None or 'auto', got {Tg!r}")
            Tg = _auto_tg(T_iso, la, wlf_range)
            if Tg is not None:
                notes.append(f"T_g = {Tg:.1f} C chosen automatically (best WLF above + Arrhenius below)")
        in_wlf = _wlf_mask(T_iso, wlf_range, Tg)
        if not in_wlf.any():
            raise InputError(f"{dma.source}: no isotherm in the WLF range (wlf_range={wlf_range}, Tg={Tg})")
        # the WLF fit is anchored at the WLF-range isotherm nearest T0 (the shifts are exact there)
        i0 = int(np.flatnonzero(in_wlf)[np.argmin(np.abs(T_iso[in_wlf] - T0))])
        if i0 != int(np.argmin(np.abs(T_iso - T0))) or abs(la[i0]) > 0:
            sf = sf.rereferenced(float(T_iso[i0]), float(la[i0]), float(sf.log10_bT[i0]))
            T0, la = sf.T_ref, sf.log10_aT
        if np.sum(in_wlf & (np.abs(T_iso - T0) > 1e-9)) >= 2:
            wlf_fit = fit_wlf(T_iso[in_wlf], la[in_wlf], T0, valid_from=Tg)
        else:
            wlf_fit = _wlf_fixed_C2(T_iso[in_wlf], la[in_wlf], T0, dma.source)
        arr = None
        below = (~in_wlf) & (T_iso < (Tg if Tg is not None else -np.inf))
        if Tg is not None and below.any():
            arr = fit_arrhenius(T_iso[below], la[below], Tg, float(wlf_fit.wlf.log10_aT(Tg)))
            notes.append(f"Arrhenius shift below T_g = {Tg:g} C (E_a = {arr.E_a / 1e3:.4g} kJ/mol), WLF above")
        shift = TemperatureShift(wlf_fit.wlf, arr)
        if wlf_fit.rms > 0.25 or wlf_fit.C1 > 1e3 or wlf_fit.C2 > 1e4:
            msg = (f"{dma.source}: the WLF law describes the shift factors poorly (C1 = {wlf_fit.C1:.3g}, "
                   f"C2 = {wlf_fit.C2:.3g} K, rms {wlf_fit.rms:.2f} decades over {wlf_fit.T_range[0]:.1f} to "
                   f"{wlf_fit.T_range[1]:.1f} C)" + ("" if Tg is not None else
                   "; give Tg (Arrhenius below it), wlf_range, or Tg='auto'"))
            warnings.warn(msg, stacklevel=2)
            notes.append(msg)

    # --- 3. refer everything to T_ref
    if abs(T_ref - T0) > 0:
        if not (T_iso.min() <= T_ref <= T_iso.max()):
            msg = (f"T_ref = {T_ref:g} C lies outside the measured isotherms ({T_iso.min():.1f} to "
                   f"{T_iso.max():.1f} C): the reference is reached by extrapolating the fitted shift law")
            warnings.warn(msg, stacklevel=2)
            notes.append(msg)
        la_ref = float(shift.log10_aT(T_ref))
        lb_ref = float(np.interp(T_ref, sf.T_C, sf.log10_bT))
        sf = sf.rereferenced(T_ref, la_ref, lb_ref)
        shift = shift.with_T_ref(T_ref)
        if wlf_fit is not None:
            wlf_fit = replace(wlf_fit, wlf=shift.wlf)

    # --- 4. shifted data and the causal fit
    k = dma.isotherm
    omega_r = dma.omega * 10.0 ** sf.log10_aT[k]
    bT = 10.0 ** sf.log10_bT[k]
    E1, E2 = dma.E_storage / bT, dma.E_loss / bT
    label = label or f"master curve from {dma.source}"
    if dma.shear_converted:
        label += f" (shear data converted, nu = {dma.poisson:g})"
    fit = fit_prony(omega_r, E1, E2, per_decade=per_decade, thermal=thermal, label=label)
    quality = replace(fit.quality, shift_rms_log10=sf.rms_log10)
    return MasterCurve(prony=fit.prony, shift=shift, quality=quality, thermal=thermal or Thermal(),
                       shift_factors=sf, wlf_fit=wlf_fit,
                       reduced=ReducedData(omega=omega_r, E_storage=E1, E_loss=E2, T_C=np.asarray(dma.T_C)),
                       label=label, notes=tuple(notes))


def read_master_curve(path, wlf, *, thermal: Thermal | None = None, per_decade: float = 2.0,
                      label: str | None = None) -> MasterCurve:
    """Read a DESIGN.md master-curve table (``f_Hz, E_storage_Pa, E_loss_Pa``) with WLF constants.

    See :meth:`MasterCurve.from_table`.
    """
    return MasterCurve.from_table(path, wlf, thermal=thermal, per_decade=per_decade, label=label)


# ==================================================================================================== helpers

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
           f"smallest (linear) one ({int((~keep).sum())} points left out; use strain_softening_from_sweep for "
           "the rest)")
    warnings.warn(msg, stacklevel=3)
    notes.append(msg)
    return dma.select(keep)


def _as_shift(wlf) -> TemperatureShift:
    if isinstance(wlf, TemperatureShift):
        return wlf
    if isinstance(wlf, WLF):
        return TemperatureShift(wlf)
    if isinstance(wlf, Mapping):
        return TemperatureShift(WLF.from_mapping(wlf))
    raise InputError(f"wlf: expected materials.WLF or a mapping {{C1, C2, T_ref_C}}, got {wlf!r}")


def _user_shifts(dma: DMAData, given, T_ref: float) -> ShiftFactors:
    T_iso = np.asarray(dma.T_isotherm, dtype=float)
    if isinstance(given, ShiftFactors):
        vals = _match(T_iso, dict(zip(given.T_C.tolist(), given.log10_aT.tolist())), dma.source)
        b = _match(T_iso, dict(zip(given.T_C.tolist(), given.log10_bT.tolist())), dma.source)
        T0 = given.T_ref
        return ShiftFactors(T_C=T_iso, log10_aT=vals, log10_bT=b, T_ref=T0, method="user",
                            rms_log10=None)
    if isinstance(given, (WLF, TemperatureShift)):
        law = given if isinstance(given, TemperatureShift) else TemperatureShift(given)
        return ShiftFactors(T_C=T_iso, log10_aT=np.asarray(law.log10_aT(T_iso), dtype=float),
                            log10_bT=np.zeros_like(T_iso), T_ref=law.T_ref, method="user (shift law)")
    if isinstance(given, Mapping):
        try:
            table = {float(k): float(v) for k, v in given.items()}
        except (TypeError, ValueError):
            raise InputError("shift_factors: expected a mapping {T_C: log10_aT} of numbers") from None
        vals = _match(T_iso, table, dma.source)
        zero = [t for t, v in table.items() if v == 0.0]
        T0 = zero[0] if len(zero) == 1 else T_ref
        if len(zero) == 1:
            # refer to the isotherm matched to that temperature (the shifts are 0 there)
            T0 = float(T_iso[int(np.argmin(np.abs(T_iso - zero[0])))])
        return ShiftFactors(T_C=T_iso, log10_aT=vals, log10_bT=np.zeros_like(T_iso), T_ref=T0, method="user")
    arr = np.asarray(given, dtype=float).ravel()
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


def _wlf_mask(T_iso, wlf_range, Tg):
    m = np.ones(T_iso.size, dtype=bool)
    if wlf_range is not None:
        m &= (T_iso >= wlf_range[0]) & (T_iso <= wlf_range[1])
    if Tg is not None:
        m &= T_iso >= Tg
    return m


def _auto_tg(T_iso, la, wlf_range):
    """Split temperature minimising BIC of WLF above + Arrhenius below (None: WLF alone is best)."""
    n = T_iso.size

    def sse_of(Tg):
        m = _wlf_mask(T_iso, wlf_range, Tg)
        if m.sum() < 3:
            return None
        i0 = int(np.flatnonzero(m)[0])
        y = la - la[i0]
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                fit = fit_wlf(T_iso[m], y[m], float(T_iso[i0]), valid_from=Tg)
        except InputError:
            return None
        r = y[m] - fit.wlf.log10_aT(T_iso[m])
        sse = float(np.sum(r ** 2))
        below = ~m & (T_iso < (Tg if Tg is not None else -np.inf))
        k = 2
        if Tg is not None and below.any():
            arr = fit_arrhenius(T_iso[below], y[below], Tg, float(fit.wlf.log10_aT(Tg)))
            sse += float(np.sum((y[below] - arr.log10_aT(T_iso[below])) ** 2))
            k = 3
        used = m.sum() + below.sum()
        return used * math.log(max(sse, 1e-12) / used) + k * math.log(used)

    best_tg, best = None, sse_of(None)
    for i in range(1, n - 2):
        Tg = 0.5 * (T_iso[i - 1] + T_iso[i])
        b = sse_of(Tg)
        if b is not None and (best is None or b < best):
            best_tg, best = float(Tg), b
    return best_tg


def _wlf_fixed_C2(T, la, T0, source) -> WLFFit:
    """Two isotherms only: C2 fixed at the 'universal' 101.6 K (shifted to T0 via C2 ~ 51.6 + T0 - Tg...).

    With one point off the reference, only one constant can be fitted; C2 = 101.6 K is assumed and C1 fitted.
    """
    off = np.abs(T - T0) > 1e-9
    if not off.any():
        raise InputError(f"{source}: no isotherm away from the reference temperature to fit WLF")
    C2 = 101.6
    dT = T[off] - T0
    if np.any(C2 + dT <= 0):
        raise InputError(f"{source}: cannot fit WLF with the assumed C2 = {C2} K to these two isotherms")
    g = -dT / (C2 + dT)
    C1 = float(np.dot(g, la[off]) / np.dot(g, g))
    if not C1 > 0:
        raise InputError(f"{source}: shift factors increase with temperature; no WLF law fits")
    warnings.warn(f"{source}: only {int(off.sum()) + 1} isotherm(s) in the WLF range; C2 fixed at {C2} K, "
                  f"C1 = {C1:.3g} fitted", stacklevel=3)
    resid = la[off] - (-C1 * dT / (C2 + dT))
    return WLFFit(wlf=WLF(C1=C1, C2=C2, T_ref=T0), covariance=np.zeros((2, 2)), stderr=np.zeros(2),
                  rms=float(np.sqrt(np.mean(resid ** 2))), T_range=(float(T.min()), float(T.max())),
                  n_points=int(T.size))
