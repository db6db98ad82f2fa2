r"""Choosing the temperature law of a master curve by how well it predicts the isotherms.

Four laws are fitted to the shift factors :math:`\log_{10} a_T(T_k)` of the isotherms (all anchored at the
reference isotherm, where :math:`a_T = 1`):

* ``"wlf"``: WLF over all isotherms (or over ``wlf_range``), Williams, Landel & Ferry (1955);
* ``"arrhenius"``: one activation energy over all isotherms (Ferry 1980, ch. 11);
* ``"wlf+arrhenius"``: WLF above T_g, Arrhenius below it, continuous at T_g; T_g given, or the split between
  isotherms with the smallest BIC;
* ``"tabulated"``: the measured shift factors interpolated (:class:`materials.TabulatedShift`), continued
  outside the isotherms by the parametric law that predicts best.

A parametric law is fitted with its shape anchored at one isotherm and then moved by a constant: the
least-squares one in :math:`\log_{10} a_T`, or the one that minimises the misfit of its isotherms (the criterion
below) when that is clearly better (by :data:`OFFSET_GAIN`), so that an isotherm the law does not describe well
(the reference isotherm below T_g, say) does not drag the others off; a tabulated law passes through every
isotherm. Each law is scored by the misfit of the master curve it gives against the isotherms (see
:func:`materials.isotherm_misfit`): in sample, and by leave-one-isotherm-out cross-validation (each
isotherm's shift predicted by the law fitted to the other isotherms; T_g of ``"wlf+arrhenius"`` stays at its
all-isotherm value). The cross-validated misfit decides: it rewards a law for what it does between and beyond
the isotherms, where the friction engine uses it, and does not reward following noise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .errors import AccuracyWarning, InputError, ignoring
from .laws import UNDETERMINED_COVARIANCE, WLF, TemperatureShift, WLFArrhenius, WLFFit, fit_arrhenius, fit_wlf
from .shift import EXTRAPOLATED_SHIFT, TabulatedShift

__all__ = ["SHIFT_LAWS", "ShiftLawScore", "fit_shift_law", "score_shift_laws", "choose_shift_law"]

#: The laws, simplest first (ties in the cross-validated misfit go to the simpler law).
SHIFT_LAWS = ("wlf", "arrhenius", "wlf+arrhenius", "tabulated")

#: A simpler law is preferred when its cross-validated misfit is within this fraction of the best one, or within
#: :data:`TIE_ABS` of it (differences below 0.1 % of the moduli are the representation's own rounding).
TIE = 0.02
TIE_ABS = 1e-3

#: The misfit-minimising constant replaces the least-squares one only when it lowers the mean squared misfit by
#: more than this fraction (otherwise the difference is the moduli's noise, not the law's).
OFFSET_GAIN = 0.01


@dataclass(frozen=True, repr=False)
class ShiftLawScore:
    """How well one temperature law describes the isotherms.

    Attributes
    ----------
    name : str
        ``"wlf"``, ``"arrhenius"``, ``"wlf+arrhenius"``, ``"tabulated"`` (or ``"given"``).
    law : object or None
        The law fitted to all isotherms (None when it could not be fitted).
    offset : float
        Constant added to ``law.log10_aT`` to give the isotherms' shifts (see the module).
    misfit : float
        Log-RMS misfit of the master curve against the isotherms (see :func:`materials.isotherm_misfit`).
    misfit_loo : float
        The same with each isotherm predicted by the law fitted without it (inf when not computed).
    reason : str
        Why the law is unavailable, when it is.
    """

    name: str
    law: object | None
    misfit: float
    misfit_loo: float
    reason: str = ""
    offset: float = 0.0

    def log10_aT(self, T):
        """The shifts this law gives the isotherms: ``law.log10_aT(T) + offset`` (relative to the reference
        isotherm of the data)."""
        return np.asarray(self.law.log10_aT(T), dtype=float) + self.offset

    @property
    def available(self) -> bool:
        """Whether the law was fitted (``law`` set, ``misfit`` finite)."""
        return self.law is not None and math.isfinite(self.misfit)

    def __repr__(self) -> str:
        if not self.available:
            return f"ShiftLawScore({self.name}: unavailable, {self.reason})"
        return f"ShiftLawScore({self.name}: misfit {self.misfit:.4g}, cross-validated {self.misfit_loo:.4g})"


@doi("10.1021/ja01619a008", "isbn:978-0-471-04894-7", "10.1137/0717021")
def fit_shift_law(kind: str, T, log10_aT, T0: float, *, Tg=None, wlf_range=None, valid_from=None,
                  outside=None):
    r"""Fit one law to shift factors anchored at ``T0`` (where ``log10_aT`` is 0).

    Parameters
    ----------
    kind : {"wlf", "arrhenius", "wlf+arrhenius", "tabulated"}
    T, log10_aT : array_like
        Isotherm temperatures (deg C) and their shifts; the shift at ``T0`` is 0.
    T0 : float
        Anchor temperature, deg C (one of ``T``).
    Tg : float, optional
        Split of ``"wlf+arrhenius"`` (default: the split with the smallest BIC).
    wlf_range : (float, float), optional
        Temperatures whose shifts the WLF branch is fitted to.
    valid_from : float, optional
        The WLF branch must be finite down to this temperature (default the lowest of ``T``).
    outside : shift law, optional
        Continuation of ``"tabulated"`` beyond the isotherms.

    Returns
    -------
    shift law
        :class:`materials.TemperatureShift` (WLF), :class:`materials.Arrhenius`, :class:`materials.WLFArrhenius`
        or :class:`materials.TabulatedShift`, with :math:`a_T(T_0) = 1`.

    Raises
    ------
    InputError
        When the law cannot be fitted (too few isotherms, no WLF law fits, ...).
    """
    T = np.asarray(T, dtype=float)
    y = np.asarray(log10_aT, dtype=float)
    valid_from = float(T.min()) if valid_from is None else float(valid_from)
    if kind == "wlf":
        return TemperatureShift(_fit_wlf_part(T, y, T0, _mask(T, wlf_range, None), valid_from).wlf)
    if kind == "arrhenius":
        off = T != T0
        if not off.any():
            raise InputError("arrhenius: no isotherm away from the reference")
        return fit_arrhenius(T[off], y[off], T0, 0.0)
    if kind == "wlf+arrhenius":
        if Tg is None:
            Tg = best_split(T, y, wlf_range)
            if Tg is None:
                raise InputError("wlf+arrhenius: too few isotherms for a WLF branch (3) above an Arrhenius branch")
        m = _mask(T, wlf_range, Tg)
        below = T < Tg
        if m.sum() < 2:
            raise InputError(f"wlf+arrhenius: T_g = {Tg:g} C leaves {int(m.sum())} isotherm(s) for WLF")
        if not below.any():             # nothing to fit below T_g (a cross-validation fold): WLF alone
            return TemperatureShift(_fit_wlf_part(T, y, T0, m, valid_from).wlf)
        anchor = T0 if T0 in T[m] else float(T[m].min())
        y1 = y - float(y[T == anchor][0])
        wlf = _fit_wlf_part(T, y1, anchor, m, min(valid_from, Tg)).wlf
        arr = fit_arrhenius(T[below], y1[below], Tg, float(wlf.log10_aT(Tg)))
        return WLFArrhenius(wlf, arr, None if anchor == T0 else float(T0))
    if kind == "tabulated":
        return TabulatedShift(T, y, T_ref=T0, outside=outside, source="shift factors of the isotherms")
    raise InputError(f"shift_law: expected one of {', '.join(SHIFT_LAWS)} or 'auto', got {kind!r}")


def best_split(T, y, wlf_range=None):
    """The T_g between isotherms (midpoint) with the smallest BIC of WLF above + Arrhenius below (None if none).

    Each split needs three isotherms in the WLF branch and one below; BIC = n ln(SSE/n) + k ln n with k = 3
    (C1, C2, E_a).
    """
    T = np.asarray(T, dtype=float)
    y = np.asarray(y, dtype=float)
    order = np.argsort(T)
    Ts = T[order]
    best, best_tg = None, None
    for i in range(1, Ts.size - 2):
        Tg = 0.5 * (Ts[i - 1] + Ts[i])
        m = _mask(T, wlf_range, Tg)
        below = T < Tg
        if m.sum() < 3 or not below.any():
            continue
        i0 = int(np.flatnonzero(m)[np.argmin(T[m])])
        yy = y - y[i0]
        try:
            with ignoring(AccuracyWarning, UNDETERMINED_COVARIANCE):  # the split is chosen by the residuals alone
                fit = fit_wlf(T[m], yy[m], float(T[i0]), valid_from=Tg)
                arr = fit_arrhenius(T[below], yy[below], Tg, float(fit.wlf.log10_aT(Tg)))
        except InputError:
            continue
        sse = float(np.sum((yy[m] - fit.wlf.log10_aT(T[m])) ** 2)
                    + np.sum((yy[below] - arr.log10_aT(T[below])) ** 2))
        n = int(m.sum() + below.sum())
        bic = n * math.log(max(sse, 1e-12) / n) + 3 * math.log(n)
        if best is None or bic < best:
            best, best_tg = bic, float(Tg)
    return best_tg


@doi("10.1111/j.2517-6161.1974.tb00994.x")
def score_shift_laws(kinds, T_iso, log10_aT, T0, misfit_of, *, Tg=None, wlf_range=None) -> list[ShiftLawScore]:
    """Fit and score each law of ``kinds`` (see the module): in sample, and by leave-one-isotherm-out
    cross-validation (Stone 1974).

    Parameters
    ----------
    kinds : sequence of str
        Laws to score (from :data:`SHIFT_LAWS`).
    T_iso, log10_aT : ndarray
        Isotherm temperatures and shifts, anchored at ``T0`` (shift 0 there).
    misfit_of : callable
        ``misfit_of(law, isotherms)`` -> residuals (natural logs) of the points of those isotherms when the
        master curve shifts them by ``law.log10_aT`` (relative to the reference isotherm); ``isotherms`` is an
        array of isotherm indices.
    Tg, wlf_range
        As in :func:`fit_shift_law` (``Tg="auto"`` is the same as None).
    """
    from scipy import optimize
    Tg = None if isinstance(Tg, str) else Tg
    n = T_iso.size
    folds = [k for k in range(n) if T_iso[k] != T0]
    valid_from = float(T_iso.min())
    split = Tg if Tg is not None else best_split(T_iso, log10_aT, wlf_range)
    all_iso = np.arange(n)
    scores: dict[str, ShiftLawScore] = {}
    parametric = [k for k in kinds if k != "tabulated"]
    if "tabulated" in kinds:
        parametric = list(dict.fromkeys(parametric + [k for k in ("wlf", "wlf+arrhenius") if k not in parametric]))

    def fit(kind, keep, outside_kind=None, offset=True):
        outside = None
        if outside_kind is not None:
            outside = fit(outside_kind, keep, offset=False)[0]      # used through its differences only
        law = fit_shift_law(kind, T_iso[keep], log10_aT[keep], T0, Tg=split, wlf_range=wlf_range,
                            valid_from=valid_from, outside=outside)
        if kind == "tabulated" or not offset:
            return law, 0.0
        used = keep if kind != "wlf" or wlf_range is None else keep[_mask(T_iso[keep], wlf_range, None)]
        start = float(np.mean(log10_aT[used] - np.asarray(law.log10_aT(T_iso[used]), dtype=float)))
        return law, _best_offset(law, start, keep)

    def _best_offset(law, start, keep):
        # the constant that minimises the training isotherms' misfit, searched within a decade of the
        # least-squares one (the misfit is smooth in it); 1e-3 decades is far below any shift's uncertainty
        def cost(c):
            r = misfit_of(shifted(law, c), keep)
            return float(np.mean(r * r)) if np.all(np.isfinite(r)) else math.inf
        res = optimize.minimize_scalar(cost, bounds=(start - 1.0, start + 1.0), method="bounded",
                                       options={"xatol": 1e-3})
        # shifts that the law describes exactly keep their least-squares constant (0 at the reference)
        return float(res.x) if res.fun < cost(start) * (1.0 - OFFSET_GAIN) else start

    def shifted(law, offset):
        return ShiftLawScore("", law, 0.0, 0.0, offset=offset)

    def evaluate(kind, outside_kind=None):
        try:
            with _quiet_trials():
                law, offset = fit(kind, all_iso, outside_kind)
                r_in = misfit_of(shifted(law, offset), all_iso)
        except InputError as exc:
            return ShiftLawScore(kind, None, math.inf, math.inf, reason=str(exc))
        loo = []
        for k in folds:
            keep = all_iso[all_iso != k]
            try:
                with _quiet_trials():
                    loo.append(misfit_of(shifted(*fit(kind, keep, outside_kind)), np.array([k])))
            except InputError:
                loo.append(np.array([math.inf]))
        r_loo = np.concatenate(loo) if loo else np.zeros(0)
        return ShiftLawScore(kind, law, _rms(r_in), _rms(r_loo) if r_loo.size else math.inf, offset=offset)

    for kind in parametric:
        scores[kind] = evaluate(kind)
    if "tabulated" in kinds:
        usable = [s for s in scores.values() if s.available and math.isfinite(s.misfit_loo)]
        outside_kind = min(usable, key=lambda s: s.misfit_loo).name if usable else None
        scores["tabulated"] = evaluate("tabulated", outside_kind)
    return [scores[k] for k in kinds if k in scores]


def choose_shift_law(scores) -> ShiftLawScore:
    """The law with the smallest cross-validated misfit; a simpler law within :data:`TIE` (relative) or
    :data:`TIE_ABS` of it is preferred. A law whose cross-validation failed in a fold ranks last.

    Raises
    ------
    InputError
        No law could be fitted.
    """
    usable = [s for s in scores if s.available]
    if not usable:
        raise InputError("no temperature law fits these shift factors: "
                         + "; ".join(f"{s.name}: {s.reason}" for s in scores))
    # cross-validated misfits decide; without any (too few isotherms) the in-sample ones do
    cv = any(math.isfinite(s.misfit_loo) for s in usable)
    key = [s.misfit_loo if cv else s.misfit for s in usable]
    best = min(key)
    for s, k in zip(usable, key):           # usable keeps the order of SHIFT_LAWS: simplest first
        if k <= best * (1.0 + TIE) + TIE_ABS:
            return s
    return usable[int(np.argmin(key))]


# ---------------------------------------------------------------------------------------------- helpers

def _quiet_trials():
    """Silence what a trial law says while it is scored: a continuation of a tabulated law outside its table (a
    left-out isotherm lies outside by construction) and an undetermined WLF covariance (not used here)."""
    return ignoring(AccuracyWarning, EXTRAPOLATED_SHIFT, UNDETERMINED_COVARIANCE)


def _rms(r) -> float:
    r = np.asarray(r, dtype=float)
    if not np.all(np.isfinite(r)):
        return math.inf
    return float(np.sqrt(np.mean(r * r)))


def _mask(T, wlf_range, Tg):
    m = np.ones(T.size, dtype=bool)
    if wlf_range is not None:
        m &= (T >= wlf_range[0]) & (T <= wlf_range[1])
    if Tg is not None:
        m &= T >= Tg
    return m


def _fit_wlf_part(T, y, T0, m, valid_from) -> WLFFit:
    """WLF fit of the shifts in ``m`` anchored at T0 (C2 fixed at 101.6 K when one isotherm is off T0)."""
    off = m & (T != T0)
    if off.sum() >= 2:
        return fit_wlf(T[m | (T == T0)], y[m | (T == T0)], T0, valid_from=valid_from)
    if off.sum() == 1:
        C2 = 101.6
        dT = float(T[off][0] - T0)
        if C2 + dT <= 0:
            raise InputError(f"wlf: cannot fit WLF with the assumed C2 = {C2} K to these isotherms")
        g = -dT / (C2 + dT)
        C1 = float(y[off][0] / g)
        if not C1 > 0:
            raise InputError("wlf: the shift factors increase with temperature; no WLF law fits")
        return WLFFit(wlf=WLF(C1=C1, C2=C2, T_ref=T0), covariance=np.zeros((2, 2)), stderr=np.zeros(2), rms=0.0,
                      T_range=(float(min(T0, T[off][0])), float(max(T0, T[off][0]))), n_points=2)
    raise InputError("wlf: no isotherm away from the reference in the WLF range")
