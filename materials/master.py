r"""Master curves from DMA isotherms or a master-curve table: the material the friction engine evaluates.

.. math:: E(\omega, T) = b_T\, E_{ref}(\omega\, a_T(T))

:func:`master_curve` builds a :class:`MasterCurve` from DMA isotherms in four named steps: the shift factors of
the isotherms (:func:`materials.tts.shift_isotherms`, or given), the reference curve :math:`E_{ref}` from the
shifted data (an interpolated table of a smooth curve through them, :class:`materials.curves.InterpolatedModulus`,
or a causal Prony series, :func:`materials.fit_prony`), the temperature law chosen by how well it predicts the
isotherms (:mod:`materials.shiftfit`), and everything referred to ``T_ref`` through that law.
:func:`read_master_curve` reads a master-curve table (the project's ``f_Hz, E_storage_Pa, E_loss_Pa``, pyvisco's
``f, E_stor, E_loss`` with units, instrument exports) and uses it as measured. The material itself,
:class:`MasterCurve` with :class:`ReducedData`, :class:`TabulatedModulus` and the measure of quality
:func:`isotherm_misfit`, is defined in :mod:`materials.mastercurve` and importable from here. The file formats and
options are described in ``docs/materials.md``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace
from typing import Mapping

import numpy as np

from frictioncite import doi

from .curves import InterpolatedModulus, causality_check, smooth_master
from .dma import DMAData
from .errors import AccuracyWarning, DataWarning, InputError, PhysicsWarning, ignoring
from .laws import UNDETERMINED_COVARIANCE, TemperatureShift, WLFFit, fit_wlf
from .mastercurve import (_CITES, FITS, MasterCurve, ReducedData, TabulatedModulus, _as_thermal, _describe,
                          _rescaled, isotherm_misfit)
from .prony_fit import fit_prony, quality_of
from .shift import EXTRAPOLATED_SHIFT, SHIFT_LAW_TYPES, as_shift_law
from .shiftfit import SHIFT_LAWS, ShiftLawScore, choose_shift_law, score_shift_laws
from .tts import ShiftFactors, shift_isotherms
from .viscoelastic import Thermal

__all__ = ["MasterCurve", "ReducedData", "TabulatedModulus", "master_curve", "read_master_curve",
           "isotherm_misfit", "FITS"]

#: In ``fit="auto"``, the Prony series (causal by construction) is kept when its misfit is within this fraction
#: of the table's.
PRONY_TIE = 0.02


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
    T_ref, wlf_range = _checked_options(dma, T_ref, shift_law=shift_law, fit=fit, Tg=Tg, wlf_range=wlf_range,
                                        per_decade=per_decade)
    report = _progress(progress)
    thermal = _as_thermal(thermal)
    notes = list(dma.notes)
    dma = _linear_strain_only(dma, notes)
    label = label or f"master curve from {dma.source}"
    if dma.shear_converted:
        label += f" (shear data converted, nu = {dma.poisson:g})"

    report("shifting the isotherms", 0.0)
    given_law = _given_law(shift_factors)
    if given_law is not None and shift_law != "auto":
        raise InputError(f"shift_law={shift_law!r} conflicts with shift_factors=<a shift law>: give one")
    sf = _isotherm_shifts(dma, T_ref, shift_factors, given_law, notes, using=using, vertical=vertical,
                          **shift_options)
    sf = _anchor(sf, T_ref, wlf_range, Tg if given_law is None else None)

    report("fitting the reference curve", 0.5)
    reference = _reference_curve(dma, sf, fit, per_decade=per_decade, thermal=thermal, label=label, notes=notes)

    report("choosing the temperature law", 0.7)
    chosen, scores = _temperature_law(dma, sf, reference, shift_law, given_law, Tg=Tg, wlf_range=wlf_range,
                                      notes=notes)
    wlf_fit = _wlf_fit_of(chosen.law, sf)
    _warn_poor_wlf(chosen.law, wlf_fit, sf, dma.source, notes, shift_law)

    report("referring to T_ref", 0.9)
    mc = _referred_to(T_ref, dma, sf, reference, chosen, wlf_fit, thermal=thermal, label=label, notes=notes,
                      scores=scores)
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


# ==================================================================================================== the steps

@dataclass(frozen=True, eq=False)
class _Reference:
    """The reference curve fitted to the shifted isotherms, at the temperature of the anchor isotherm.

    ``name`` is ``"table"`` or ``"prony"``; ``curve`` the :class:`InterpolatedModulus` or :class:`Prony`;
    ``scatter`` the smoothing scatter of a table (for its causality check), None for a Prony series;
    ``log10_bT`` the vertical shift of each data point.
    """

    name: str
    curve: object
    scatter: object
    log10_bT: np.ndarray


def _checked_options(dma, T_ref, *, shift_law, fit, Tg, wlf_range, per_decade) -> tuple[float, tuple | None]:
    """The options of :func:`master_curve` checked: ``T_ref`` as a float and ``wlf_range`` as a pair of floats."""
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
    return T_ref, wlf_range


def _isotherm_shifts(dma: DMAData, T_ref: float, shift_factors, given_law, notes: list, *, using, vertical,
                     **shift_options) -> ShiftFactors:
    """Step 1: the shift factor of each isotherm, from a given law, given values, or found automatically."""
    if given_law is not None:
        T_iso = np.asarray(dma.T_isotherm, dtype=float)
        # what the law says of the isotherms (a tabulated law continued outside its table) is said once, and noted
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            la_law = np.asarray(given_law.log10_aT(T_iso), dtype=float)
        _forward(caught, notes)
        return ShiftFactors(T_C=T_iso, log10_aT=la_law, log10_bT=np.zeros_like(T_iso), T_ref=float(given_law.T_ref),
                            method="given shift law")
    if shift_factors is None:
        return shift_isotherms(dma, T_ref, using=using, vertical=vertical, **shift_options)
    return _user_shifts(dma, shift_factors, T_ref)


def _reference_curve(dma: DMAData, sf: ShiftFactors, fit: str, *, per_decade, thermal, label,
                     notes: list) -> _Reference:
    """Step 2: the reference curve through the isotherms shifted by ``sf``, as a table or a Prony series."""
    k = dma.isotherm
    lb_pt = sf.log10_bT[k]
    omega_0 = dma.omega * 10.0 ** sf.log10_aT[k]
    E1_0, E2_0 = dma.E_storage / 10.0 ** lb_pt, dma.E_loss / 10.0 ** lb_pt
    reps = _representations(fit, omega_0, E1_0, E2_0, per_decade, thermal, label)
    everything = np.arange(k.size)
    measured = {name: _rms(_log_residuals(rep, dma, sf.log10_aT[k], lb_pt, everything))
                for name, (rep, _) in reps.items()}
    name = _choose_representation(measured)
    if len(reps) > 1:
        notes.append("reference curve: " + ", ".join(f"{n} misfit {measured[n]:.4g}" for n in reps)
                     + f" against the isotherms with their own shifts; {name} kept")
    curve, scatter = reps[name]
    return _Reference(name=name, curve=curve, scatter=scatter, log10_bT=lb_pt)


def _temperature_law(dma: DMAData, sf: ShiftFactors, reference: _Reference, shift_law: str, given_law, *, Tg,
                     wlf_range, notes: list) -> tuple[ShiftLawScore, list[ShiftLawScore]]:
    """Step 3: the temperature law (given, or the best of ``shift_law``) and the scores of those considered."""
    point_T = np.asarray(dma.T_C, dtype=float)
    points_of = dma.isotherm_indices()

    def misfit_of(law, isotherms):
        idx = np.concatenate([points_of[i] for i in isotherms])
        la_pt = np.asarray(law.log10_aT(point_T[idx]), dtype=float)
        return _log_residuals(reference.curve, dma, la_pt, reference.log10_bT, idx)

    T0 = sf.T_ref
    if given_law is not None:
        with ignoring(AccuracyWarning, EXTRAPOLATED_SHIFT):   # said in step 1, for the isotherms
            law = given_law.with_T_ref(T0) if abs(float(given_law.T_ref) - T0) > 0 else given_law
            score = ShiftLawScore("given", law, 0.0, math.inf)
            score = replace(score, misfit=_rms(misfit_of(score, np.arange(dma.n_isotherms))))
        return score, [score]
    kinds = SHIFT_LAWS if shift_law == "auto" else (shift_law,)
    scores = score_shift_laws(kinds, sf.T_C, sf.log10_aT, T0, misfit_of, Tg=Tg, wlf_range=wlf_range)
    chosen = choose_shift_law(scores)
    if shift_law == "auto":
        notes.append("temperature law: " + "; ".join(
            f"{s.name} misfit {s.misfit:.4g} (cross-validated {s.misfit_loo:.4g})" if s.available
            else f"{s.name} unavailable" for s in scores) + f"; {chosen.name} kept")
    return chosen, scores


def _referred_to(T_ref: float, dma: DMAData, sf: ShiftFactors, reference: _Reference, chosen: ShiftLawScore,
                 wlf_fit: WLFFit | None, *, thermal, label, notes: list, scores) -> MasterCurve:
    """Step 4: the curve, the shifts and the law referred to ``T_ref`` exactly through the law; the material."""
    if not (sf.T_C.min() <= T_ref <= sf.T_C.max()):
        msg = (f"T_ref = {T_ref:g} C lies outside the measured isotherms ({sf.T_C.min():.1f} to "
               f"{sf.T_C.max():.1f} C): the reference is reached by extrapolating the temperature law")
        warnings.warn(msg, AccuracyWarning, stacklevel=3)
        notes.append(msg)
    # a T_ref outside a tabulated law's table was just said; the law's own warning would repeat it
    with ignoring(AccuracyWarning, EXTRAPOLATED_SHIFT):
        la_ref = float(chosen.log10_aT(T_ref))         # the law's shift of T_ref relative to the data's frame
    lb_ref = float(np.interp(T_ref, sf.T_C, sf.log10_bT))
    prony = reference.curve if reference.name == "prony" else None
    curve = reference.curve if reference.name == "table" else None
    prony, curve = _rescaled(prony, curve, la_ref, lb_ref)
    sf = sf.rereferenced(T_ref, la_ref, lb_ref)
    law = chosen.law
    with ignoring(AccuracyWarning, EXTRAPOLATED_SHIFT):
        law = law.with_T_ref(T_ref) if abs(float(law.T_ref) - T_ref) > 0 else law
    if wlf_fit is not None and getattr(law, "wlf", None) is not None:
        wlf_fit = replace(wlf_fit, wlf=law.wlf)
    notes.append(f"temperature law ({chosen.name}): {_describe(law)}")
    k = dma.isotherm
    omega_r = dma.omega * 10.0 ** sf.log10_aT[k]
    bT = 10.0 ** sf.log10_bT[k]
    E1, E2 = dma.E_storage / bT, dma.E_loss / bT
    quality = replace(quality_of(prony or curve, omega_r, E1, E2, representation=reference.name),
                      shift_rms_log10=sf.rms_log10)
    check = None
    if curve is not None:
        check = causality_check(curve.omega, curve.E_storage, curve.E_loss, scatter=reference.scatter)
        if not check.ok:
            msg = check.message(dma.source)
            warnings.warn(msg, PhysicsWarning, stacklevel=3)
            notes.append(msg)
    mc = MasterCurve(prony=prony, curve=curve, shift=law, quality=quality, thermal=thermal or Thermal(),
                     shift_factors=sf, wlf_fit=wlf_fit,
                     reduced=ReducedData(omega=omega_r, E_storage=E1, E_loss=E2, T_C=np.asarray(dma.T_C)),
                     label=label, notes=tuple(notes), scores=tuple(scores), causality=check)
    # points measured outside a given law's table were said in step 1
    with ignoring(AccuracyWarning, EXTRAPOLATED_SHIFT):
        return replace(mc, misfit=isotherm_misfit(mc, dma))


# ==================================================================================================== helpers

def _log_residuals(curve, dma: DMAData, log10_aT, log10_bT, idx) -> np.ndarray:
    """ln(model/measured) of E' and E'' at the data points ``idx``, shifted by ``log10_aT`` (of those points)
    and ``log10_bT`` (of every point). A non-positive model modulus gives a non-finite residual, which
    :func:`_rms` scores as an infinite misfit."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        E = curve.E_reference(dma.omega[idx] * 10.0 ** log10_aT) * 10.0 ** log10_bT[idx]
        return np.concatenate([np.log(E.real / dma.E_storage[idx]), np.log(E.imag / dma.E_loss[idx])])


def _forward(caught, notes):
    """Give each distinct caught warning again (its own category) and keep it as a note."""
    first = {}
    for w in caught:
        first.setdefault(str(w.message), w.category)
    for msg, category in first.items():
        warnings.warn(msg, category, stacklevel=4)
        notes.append(msg)


def _progress(progress):
    """``progress`` as a callable ``report(message, fraction)`` (a no-op for None)."""
    if progress is None:
        return lambda message, fraction=None: None
    if not callable(progress):
        raise InputError(f"progress: expected a callable progress(message, fraction), got {progress!r}")
    return lambda message, fraction=None: progress(message, fraction)


def _rms(r) -> float:
    """Root mean square of the residuals ``r``; infinite when any is not finite."""
    r = np.asarray(r, dtype=float)
    return float(np.sqrt(np.mean(r * r))) if np.all(np.isfinite(r)) else math.inf


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
    """The representation kept: the Prony series unless the table fits clearly better (:data:`PRONY_TIE`)."""
    if len(misfits) == 1:
        return next(iter(misfits))
    return "prony" if misfits["prony"] <= misfits["table"] * (1.0 + PRONY_TIE) else "table"


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


def _user_shifts(dma: DMAData, given, T_ref: float) -> ShiftFactors:
    """Per-isotherm shifts given by the user (ShiftFactors, a mapping {T_C: log10_aT} or one value per
    isotherm), matched to the isotherms; the reference is where the given shift is 0, else ``T_ref``."""
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
    """The value of ``table`` ({T_C: value}) at the temperature nearest each isotherm, within ``tol`` K."""
    keys = np.array(sorted(table))
    out = np.empty(T_iso.size)
    for i, T in enumerate(T_iso):
        j = int(np.argmin(np.abs(keys - T)))
        if abs(keys[j] - T) > tol:
            raise InputError(f"shift_factors: no value for the isotherm at {T:.1f} C of {source} "
                             f"(nearest given temperature {keys[j]:g} C, tolerance {tol:g} K)")
        out[i] = table[keys[j]]
    return out


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
    w = law.wlf
    T, y = sf.T_C, sf.log10_aT
    m = T >= (law.arrhenius.T_g if law.arrhenius is not None else -np.inf)
    y = y - float(np.interp(w.T_ref, T, y)) if w.T_ref not in T else y - float(y[T == w.T_ref][0])
    if np.sum(m & (T != w.T_ref)) < 2:
        return None
    try:
        with ignoring(AccuracyWarning, UNDETERMINED_COVARIANCE):   # the covariance of a refit with two points
            fit = fit_wlf(T[m], y[m], w.T_ref, valid_from=(law.arrhenius.T_g if law.arrhenius else T.min()))
    except InputError:
        return None
    return replace(fit, wlf=w)


def _warn_poor_wlf(law, wlf_fit, sf, source, notes, shift_law):
    """Warn (and note) when the WLF fit behind a WLF law describes the shift factors poorly."""
    if wlf_fit is None or not isinstance(law, TemperatureShift):
        return
    if wlf_fit.rms > 0.25 or wlf_fit.C1 > 1e3 or wlf_fit.C2 > 1e4:
        msg = (f"{source}: the WLF law describes the shift factors poorly (C1 = {wlf_fit.C1:.3g}, "
               f"C2 = {wlf_fit.C2:.3g} K, rms {wlf_fit.rms:.2f} decades over {wlf_fit.T_range[0]:.1f} to "
               f"{wlf_fit.T_range[1]:.1f} C)" + ("; shift_law='auto' compares it with the other laws"
                                                 if shift_law != "auto" else ""))
        warnings.warn(msg, AccuracyWarning, stacklevel=3)
        notes.append(msg)


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
    warnings.warn(msg, DataWarning, stacklevel=3)
    notes.append(msg)
    return dma.select(keep)
