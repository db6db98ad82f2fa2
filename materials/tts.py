r"""Time-temperature superposition: automated shift factors, WLF and Arrhenius fits, change of T_ref.

The principle (Ferry 1980, ch. 11): for a thermorheologically simple material

.. math:: E(\omega, T) = b_T\, E(\omega a_T, T_{ref}),

so isotherms measured over a narrow frequency window, plotted against the reduced frequency
:math:`\omega a_T`, superpose into one master curve. :func:`shift_isotherms` finds :math:`\log_{10} a_T` (and
optionally :math:`\log_{10} b_T`) in two stages:

1. **pairwise** – adjacent isotherms, from the reference outwards: the shift minimising the mean squared
   mismatch in :math:`\log E'` and :math:`\log E''` (or :math:`\log\tan\delta`) over the overlap of the two
   shifted curves (each isotherm represented by a low-order polynomial in :math:`\log\omega`, allowed to reach
   ``extend`` decades beyond its data), searched on a grid over wide bounds (``max_step`` decades per step)
   and polished with a bounded scalar minimisation; the cost is divided by the number of overlapping points,
   so a small overlap is not favoured;
2. **global** – all shifts together: one smooth master curve per component, a penalised cubic B-spline
   (P-spline, Eilers & Marx 1996) in the reduced log-frequency, is fitted to all shifted points, and the
   shifts minimise its residual (variable projection: for given shifts the spline is a linear least-squares
   fit). This uses every overlap at once, not only neighbours.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from frictioncite import doi

from .errors import InputError
from .viscoelastic import WLF

__all__ = ["ShiftFactors", "shift_isotherms", "WLFFit", "fit_wlf", "Arrhenius", "fit_arrhenius",
           "TemperatureShift", "WLFArrhenius", "wlf_change_reference", "R_GAS"]

#: Gas constant, J/(mol K).
R_GAS = 8.314462618
_K0 = 273.15


# ==================================================================================================== results

@dataclass(frozen=True, eq=False, repr=False)
class ShiftFactors:
    r"""Shift factors of the isotherms of a DMA data set, relative to ``T_ref``.

    Attributes
    ----------
    T_C : ndarray
        Isotherm temperatures, deg C (increasing).
    log10_aT : ndarray
        Horizontal shifts: reduced frequency :math:`\omega a_T`.
    log10_bT : ndarray
        Vertical shifts (zeros unless asked for): :math:`E(\omega, T) = b_T E(\omega a_T, T_{ref})`.
    T_ref : float
        Reference temperature, deg C (:math:`a_T(T_{ref}) = 1`).
    method : str
        How they were obtained (``"automatic: E', E''"``, ``"user"``, ...).
    rms_log10 : float or None
        RMS mismatch (decades of modulus) of the shifted data about the smooth master curve, when computed.
    converged : bool
        False when the global refinement did not converge (also warned).
    rms_by_isotherm : ndarray or None
        That mismatch per isotherm (an isotherm far above the others does not superpose; warned).
    """

    T_C: np.ndarray
    log10_aT: np.ndarray
    log10_bT: np.ndarray
    T_ref: float
    method: str = "user"
    rms_log10: float | None = None
    converged: bool = True
    rms_by_isotherm: np.ndarray | None = None

    def __post_init__(self):
        T = np.array(self.T_C, dtype=float).ravel()
        a = np.array(self.log10_aT, dtype=float).ravel()
        b = np.zeros_like(a) if self.log10_bT is None else np.array(self.log10_bT, dtype=float).ravel()
        if not (T.size == a.size == b.size) or T.size == 0:
            raise InputError(f"shift factors: T_C, log10_aT and log10_bT must have the same non-zero length, "
                             f"got {T.size}, {a.size}, {b.size}")
        for name, v in (("T_C", T), ("log10_aT", a), ("log10_bT", b)):
            if not np.all(np.isfinite(v)):
                raise InputError(f"shift factors: {name} must be finite, got {v}")
        if not math.isfinite(self.T_ref):
            raise InputError(f"shift factors: T_ref must be finite, got {self.T_ref!r}")
        for name, v in (("T_C", T), ("log10_aT", a), ("log10_bT", b)):
            v.setflags(write=False)
            object.__setattr__(self, name, v)

    @property
    def aT(self) -> np.ndarray:
        """Horizontal shift factors a_T."""
        return 10.0 ** self.log10_aT

    @property
    def bT(self) -> np.ndarray:
        """Vertical shift factors b_T."""
        return 10.0 ** self.log10_bT

    def rereferenced(self, T_ref: float, log10_aT_at_new_ref: float, log10_bT_at_new_ref: float = 0.0):
        """The same shifts relative to a new reference temperature, given log aT (and log bT) there."""
        return replace(self, log10_aT=self.log10_aT - log10_aT_at_new_ref,
                       log10_bT=self.log10_bT - log10_bT_at_new_ref, T_ref=float(T_ref))

    def __repr__(self) -> str:
        rms = "" if self.rms_log10 is None else f", scatter {self.rms_log10:.3g} decades"
        return (f"ShiftFactors({self.T_C.size} isotherms {self.T_C.min():.4g}..{self.T_C.max():.4g} C, "
                f"log10 aT {self.log10_aT.max():.3g}..{self.log10_aT.min():.3g}, T_ref = {self.T_ref:.4g} C{rms})")

    def as_dict(self) -> dict:
        """Plain-data form (lists), e.g. for JSON."""
        return {"T_C": self.T_C.tolist(), "log10_aT": self.log10_aT.tolist(), "log10_bT": self.log10_bT.tolist(),
                "T_ref": self.T_ref, "method": self.method, "rms_log10": self.rms_log10,
                "converged": self.converged}


@doi("10.1021/ja01619a008")
@dataclass(frozen=True, eq=False, repr=False)
class WLFFit:
    r"""Least-squares WLF fit of shift factors, with its covariance.

    Attributes
    ----------
    wlf : WLF
        The fitted law, :math:`\log_{10} a_T = -C_1 (T-T_{ref})/(C_2 + T - T_{ref})`.
    covariance : ndarray, shape (2, 2)
        Covariance of (C1, C2) (scaled by the residual variance).
    stderr : ndarray, shape (2,)
        Standard errors of C1 and C2.
    rms : float
        RMS residual of log10 aT over the fitted points, decades.
    T_range : tuple of float
        Temperature range of the fitted points, deg C.
    n_points : int
        Number of isotherms used.
    """

    wlf: WLF
    covariance: np.ndarray
    stderr: np.ndarray
    rms: float
    T_range: tuple[float, float]
    n_points: int

    @property
    def C1(self) -> float:
        return self.wlf.C1

    @property
    def C2(self) -> float:
        return self.wlf.C2

    @property
    def T_ref(self) -> float:
        return self.wlf.T_ref

    def __repr__(self) -> str:
        return (f"WLFFit(C1 = {self.C1:.4g} +- {self.stderr[0]:.2g}, C2 = {self.C2:.4g} +- {self.stderr[1]:.2g} K, "
                f"T_ref = {self.T_ref:.4g} C, rms {self.rms:.3g} decades over {self.n_points} isotherms)")


@doi("isbn:978-0-471-04894-7")
@dataclass(frozen=True, repr=False)
class Arrhenius:
    r"""Arrhenius shift law, alone or as the branch below the glass transition of a WLF law.

    .. math:: \log_{10} a_T = \log_{10} a_T(T_g) + \frac{E_a}{R \ln 10}
              \left(\frac{1}{T + 273.15} - \frac{1}{T_g + 273.15}\right)

    (Ferry 1980, ch. 11). ``E_a`` in J/mol, temperatures in deg C. ``T_g`` is the anchor temperature where
    the value ``log10_aT_g`` is imposed: below a WLF law it is the glass transition (continuity with WLF); for
    a law on its own, :meth:`from_reference` anchors it at the reference temperature (``log10_aT_g = 0``).
    """

    E_a: float
    T_g: float
    log10_aT_g: float
    E_a_stderr: float | None = None

    kind = "arrhenius"

    def __post_init__(self):
        for name in ("E_a", "T_g", "log10_aT_g"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float, np.floating, np.integer)) and not isinstance(v, bool)
                    and math.isfinite(v)):
                raise InputError(f"Arrhenius.{name}: expected a finite number, got {v!r}")
        if self.E_a < 0:
            raise InputError(f"Arrhenius.E_a: expected an activation energy >= 0 J/mol, got {self.E_a}")
        if self.T_g <= -_K0:
            raise InputError(f"Arrhenius.T_g: expected a temperature above -273.15 C, got {self.T_g}")

    @classmethod
    def from_reference(cls, E_a: float, T_ref: float) -> "Arrhenius":
        """The Arrhenius law with activation energy ``E_a`` (J/mol) and :math:`a_T(T_{ref}) = 1`."""
        return cls(E_a=float(E_a), T_g=float(T_ref), log10_aT_g=0.0)

    @classmethod
    def from_mapping(cls, m) -> "Arrhenius":
        """From ``{"E_a": J/mol, "T_ref_C": deg C}`` (the case-file form)."""
        try:
            T_ref = m["T_ref_C"] if "T_ref_C" in m else m["T_ref"]
            return cls.from_reference(float(m["E_a"]), float(T_ref))
        except KeyError as exc:
            raise InputError(f"arrhenius: missing key {exc.args[0]!r} (expected E_a in J/mol and T_ref_C)") from None
        except (TypeError, ValueError):
            raise InputError(f"arrhenius: expected numbers for E_a and T_ref_C, got {dict(m)!r}") from None

    @property
    def T_ref(self) -> float:
        """Temperature where :math:`a_T = 1`, deg C (from the anchor; the anchor itself when it is 0 there)."""
        if self.log10_aT_g == 0.0:
            return float(self.T_g)
        if self.E_a == 0.0:
            raise InputError("Arrhenius: E_a = 0 and log10 aT != 0 everywhere; the law has no reference temperature")
        inv = 1.0 / (self.T_g + _K0) - self.log10_aT_g * R_GAS * math.log(10.0) / self.E_a
        if inv <= 0:
            raise InputError("Arrhenius: a_T = 1 is reached at no temperature above absolute zero")
        return 1.0 / inv - _K0

    def log10_aT(self, T):
        """log10 aT at ``T`` (deg C, vectorized); T must be above absolute zero."""
        TK = np.asarray(T, dtype=float) + _K0
        if not np.all(np.isfinite(TK)) or np.any(TK <= 0):
            raise InputError("temperature: expected finite temperatures above -273.15 C")
        out = self.log10_aT_g + self.E_a / (R_GAS * math.log(10.0)) * (1.0 / TK - 1.0 / (self.T_g + _K0))
        return out if np.ndim(out) else float(out)

    def with_T_ref(self, T_ref: float) -> "Arrhenius":
        """The same law with :math:`a_T(T_{ref}) = 1` at the new reference temperature."""
        return replace(self, log10_aT_g=self.log10_aT_g - float(self.log10_aT(float(T_ref))))

    def describe(self) -> str:
        """One line: the law and its constants."""
        return f"Arrhenius: E_a = {self.E_a / 1e3:.4g} kJ/mol, a_T = 1 at {self.T_ref:.4g} C"

    def __repr__(self) -> str:
        return f"Arrhenius(E_a={self.E_a:.6g}, T_g={self.T_g:.6g}, log10_aT_g={self.log10_aT_g:.6g})"


@dataclass(frozen=True, repr=False)
class TemperatureShift:
    r"""The temperature law of a master curve: WLF, with Arrhenius below ``arrhenius.T_g`` when given.

    .. math:: \log_{10} a_T(T) = L(T) - L(T_{ref}),\qquad
              L(T) = \begin{cases} \text{WLF}(T) & T \ge T_g \\ \text{Arrhenius}(T) & T < T_g \end{cases}

    (the Arrhenius branch is continuous with WLF at T_g). Normally ``T_ref`` is the WLF reference and
    :math:`L(T_{ref}) = 0`; a reference below T_g is allowed (then ``wlf`` alone does not give a_T).
    :meth:`law_at` says which law applies where. :class:`WLFArrhenius` builds one from plain constants.

    Parameters
    ----------
    wlf : WLF
    arrhenius : Arrhenius, optional
    T_ref_C : float, optional
        Reference temperature, deg C (default ``wlf.T_ref``).
    """

    wlf: WLF
    arrhenius: Arrhenius | None = None
    T_ref_C: float | None = None

    @property
    def kind(self) -> str:
        return "wlf" if self.arrhenius is None else "wlf+arrhenius"

    @property
    def T_ref(self) -> float:
        return self.wlf.T_ref if self.T_ref_C is None else float(self.T_ref_C)

    def _raw(self, T):
        T = np.asarray(T, dtype=float)
        if not np.all(np.isfinite(T)):
            raise InputError(f"temperature: expected finite temperatures in deg C, got {T!r}")
        if self.arrhenius is None:
            return np.asarray(self.wlf.log10_aT(T), dtype=float)
        below = T < self.arrhenius.T_g
        out = np.empty(T.shape)
        if np.any(~below):
            out[~below] = self.wlf.log10_aT(T[~below])
        if np.any(below):
            out[below] = self.arrhenius.log10_aT(T[below])
        return out

    def log10_aT(self, T):
        """log10 aT (deg C in, vectorized). Below T_g (if set) the Arrhenius law, else WLF."""
        out = self._raw(T)
        if self.T_ref_C is not None:
            out = out - self._raw(self.T_ref_C)
        return out if out.ndim else float(out)

    def law_at(self, T) -> np.ndarray:
        """'WLF' or 'Arrhenius' for each temperature."""
        T = np.asarray(T, dtype=float)
        if self.arrhenius is None:
            return np.full(T.shape, "WLF")
        return np.where(T < self.arrhenius.T_g, "Arrhenius", "WLF")

    def with_T_ref(self, T_ref: float) -> "TemperatureShift":
        """The same law referred to a new reference temperature.

        The WLF constants change exactly (:func:`wlf_change_reference`) when T_ref is above the WLF singularity;
        the Arrhenius branch is re-anchored so that the law is unchanged up to the constant.
        """
        T_ref = float(T_ref)
        if self.wlf.C2 + (T_ref - self.wlf.T_ref) > 0:
            new_wlf = wlf_change_reference(self.wlf, T_ref)
            offset = float(self.wlf.log10_aT(T_ref))
        else:                         # reference in the Arrhenius range, below the WLF singularity
            new_wlf, offset = self.wlf, 0.0
        arr = self.arrhenius
        if arr is not None:
            arr = replace(arr, log10_aT_g=arr.log10_aT_g - offset)
        out = type(self)(new_wlf, arr, None)
        if abs(out._raw(T_ref)) > 0:
            out = type(self)(new_wlf, arr, T_ref)
        return out

    def describe(self) -> str:
        """One line: the law and its constants."""
        w = self.wlf
        text = f"WLF: C1 = {w.C1:.4g}, C2 = {w.C2:.4g} K at T_ref = {w.T_ref:.4g} C"
        if self.arrhenius is not None:
            text += (f"; Arrhenius below T_g = {self.arrhenius.T_g:.4g} C (E_a = {self.arrhenius.E_a / 1e3:.4g} "
                     "kJ/mol)")
        if self.T_ref_C is not None:
            text += f"; a_T = 1 at {self.T_ref_C:.4g} C"
        return text

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.describe()})"


@doi("10.1021/ja01619a008", "isbn:978-0-471-04894-7")
class WLFArrhenius(TemperatureShift):
    r"""WLF above the glass transition ``T_g``, Arrhenius below it, continuous at ``T_g``.

    .. math:: \log_{10} a_T = \begin{cases} -\dfrac{C_1 (T - T_{ref})}{C_2 + T - T_{ref}} & T \ge T_g \\[1ex]
              \log_{10} a_T^{WLF}(T_g) + \dfrac{E_a}{R\ln 10}\left(\dfrac{1}{T + 273.15}
              - \dfrac{1}{T_g + 273.15}\right) & T < T_g \end{cases}

    (Williams, Landel & Ferry 1955; Ferry 1980, ch. 11). A :class:`TemperatureShift` whose Arrhenius branch
    is anchored on the WLF law; build it with :meth:`from_constants` or :meth:`from_mapping`.
    """

    @classmethod
    def from_constants(cls, C1: float, C2: float, T_ref: float, E_a: float, T_g: float) -> "WLFArrhenius":
        """From the WLF constants (C1, C2 in K, T_ref in deg C), the activation energy (J/mol) and T_g (deg C).

        Raises
        ------
        InputError
            T_g at or below the WLF singularity :math:`T_{ref} - C_2` (the WLF branch must be finite above T_g).
        """
        wlf = WLF(C1=C1, C2=C2, T_ref=T_ref)
        if not math.isfinite(T_g) or wlf.C2 + (T_g - wlf.T_ref) <= 0:
            raise InputError(f"WLFArrhenius: T_g = {T_g!r} C must lie above the WLF singularity "
                             f"{wlf.T_ref - wlf.C2:g} C")
        arr = Arrhenius(E_a=float(E_a), T_g=float(T_g), log10_aT_g=float(wlf.log10_aT(T_g)))
        out = cls(wlf, arr, None)
        return out if T_ref >= T_g else cls(wlf, arr, float(T_ref))

    @classmethod
    def from_mapping(cls, m) -> "WLFArrhenius":
        """From ``{"C1", "C2", "T_ref_C", "E_a", "T_g"}`` (the case-file form; E_a in J/mol, T_g in deg C)."""
        try:
            T_ref = m["T_ref_C"] if "T_ref_C" in m else m["T_ref"]
            return cls.from_constants(float(m["C1"]), float(m["C2"]), float(T_ref), float(m["E_a"]),
                                      float(m["T_g"]))
        except KeyError as exc:
            raise InputError(f"wlf+arrhenius: missing key {exc.args[0]!r} (expected C1, C2, T_ref_C, E_a, T_g)"
                             ) from None
        except (TypeError, ValueError):
            raise InputError(f"wlf+arrhenius: expected numbers for C1, C2, T_ref_C, E_a, T_g, got {dict(m)!r}"
                             ) from None


# ==================================================================================================== analysis

@doi("isbn:978-0-471-04894-7", "10.1214/ss/1038425655")
def shift_isotherms(dma, T_ref: float | None = None, *, using: str = "moduli", vertical: bool = False,
                    max_step: float = 8.0, extend: float = 1.0, refine: bool = True, smoothing: float = 0.3,
                    knots_per_decade: float = 4.0, robust: bool = True, reverse_tol: float = 0.1
                    ) -> ShiftFactors:
    r"""Horizontal (and optionally vertical) shift factors of DMA isotherms, found automatically.

    Parameters
    ----------
    dma : DMAData
        At least two isotherms with at least two frequencies each.
    T_ref : float, optional
        The isotherm nearest to ``T_ref`` is the reference (shift 0); default the middle isotherm. The shifts
        are relative to that isotherm's temperature, reported as ``T_ref`` of the result (use
        :func:`materials.master_curve` to refer them to an arbitrary temperature through the WLF fit).
    using : {"moduli", "tan_delta"}
        Horizontal shifts from :math:`\log E'` and :math:`\log E''` together, or from :math:`\log\tan\delta`
        alone (no vertical shift touches tan delta).
    vertical : bool
        Also find vertical shifts :math:`\log_{10} b_T` (E' and E'' shifted together). The pairwise stage then
        takes the horizontal shift from tan delta (untouched by b_T) and b_T from the mean mismatch of
        log E', log E''; the global stage fits all three with both shifts.
    max_step : float
        Largest shift between adjacent isotherms searched, decades: a warmer neighbour is searched over
        [-max_step, +reverse_tol] decades from the colder one (a_T decreases with temperature).
    reverse_tol : float
        How far (decades) a step may go the unphysical way (a_T increasing with T), to allow for noise.
    extend : float
        How far (decades) an isotherm's polynomial representation may be extrapolated when comparing
        neighbours whose windows barely overlap.
    refine : bool
        Run the global refinement of all shifts together (recommended).
    smoothing : float
        P-spline roughness penalty weight (per data point) in the global refinement.
    knots_per_decade : float
        B-spline knot density of the global master curve.
    robust : bool
        Soft-L1 loss in the global refinement, so that a few bad points (instrument resonance at the highest
        frequencies of cold isotherms) do not pull the shifts.

    Returns
    -------
    ShiftFactors

    Raises
    ------
    InputError
        One isotherm only, an isotherm with fewer than two frequencies, a bad option.
    """
    xs, Ys, T_iso, comps = _isotherm_arrays(dma, using, vertical)
    n = len(xs)
    if T_ref is None:
        ref = n // 2
    else:
        if not math.isfinite(T_ref):
            raise InputError(f"T_ref: expected a finite temperature in deg C, got {T_ref!r}")
        ref = int(np.argmin(np.abs(T_iso - T_ref)))
    if not (max_step > 0 and extend >= 0 and smoothing > 0 and knots_per_decade > 0):
        raise InputError("shift_isotherms: expected max_step > 0, extend >= 0, smoothing > 0, knots_per_decade > 0")

    # --- stage 1: pairwise, from the reference outwards
    log_aT = np.zeros(n)
    log_bT = np.zeros(n)
    extrapolated, failed, mismatch = [], [], []
    for k in range(ref + 1, n):       # warmer: shift to lower reduced frequency
        s, b, ok = _pair_shift(xs[k - 1] + log_aT[k - 1], Ys[k - 1] + log_bT[k - 1] * comps, xs[k], Ys[k], comps,
                               lo=log_aT[k - 1] - max_step, hi=log_aT[k - 1] + reverse_tol, extend=extend,
                               vertical=vertical, warmer=True)
        log_aT[k], log_bT[k] = s, b
        {"none": failed, "extrapolated": extrapolated, "mismatch": mismatch}.get(ok, []).append(T_iso[k])
    for k in range(ref - 1, -1, -1):  # colder: shift to higher reduced frequency
        s, b, ok = _pair_shift(xs[k + 1] + log_aT[k + 1], Ys[k + 1] + log_bT[k + 1] * comps, xs[k], Ys[k], comps,
                               lo=log_aT[k + 1] - reverse_tol, hi=log_aT[k + 1] + max_step, extend=extend,
                               vertical=vertical, warmer=False)
        log_aT[k], log_bT[k] = s, b
        {"none": failed, "extrapolated": extrapolated, "mismatch": mismatch}.get(ok, []).append(T_iso[k])
    if mismatch:
        warnings.warn(f"{dma.source}: the isotherm(s) at T = " + ", ".join(f"{t:.1f}" for t in mismatch)
                      + " C do not superpose on their neighbour at any shift within the bounds (rms mismatch "
                      "well above the scatter): too little overlap, or not thermorheologically simple; "
                      "check those shifts", stacklevel=2)
    if extrapolated:
        warnings.warn(f"{dma.source}: the isotherm(s) at T = " + ", ".join(f"{t:.1f}" for t in extrapolated)
                      + " C do not overlap their neighbour within the search bounds; they were placed by "
                      f"extrapolating the neighbours' trends (up to {extend:g} decades): check those shifts",
                      stacklevel=2)
    if failed:
        warnings.warn(f"{dma.source}: no overlap with the neighbouring isotherm for T = "
                      + ", ".join(f"{t:.1f}" for t in failed) + " C within +-" f"{max_step:g} decades; "
                      "these isotherms were placed by extrapolation (check the shifts)", stacklevel=2)

    method = "automatic: " + ("log tan delta" if using == "tan_delta" else "log E', log E''") + \
             (" + vertical bT" if vertical else "")
    rms = None
    by_iso = None
    converged = True
    if refine:
        log_aT, log_bT, rms, converged, by_iso = _global_refine(xs, Ys, comps, log_aT, log_bT, ref, vertical,
                                                                smoothing, knots_per_decade, robust, max_step,
                                                                reverse_tol)
        # scatter expected from the data alone: residual of a cubic in log omega through each isotherm
        noise = float(np.median([np.sqrt(np.mean((Y - np.column_stack(
            [np.polyval(np.polyfit(x, Y[:, j], min(3, x.size - 1)), x) for j in range(Y.shape[1])])) ** 2))
            for x, Y in zip(xs, Ys)]))
        bad = np.flatnonzero(by_iso > 3.0 * noise + 0.01)
        if bad.size:
            warnings.warn(f"{dma.source}: isotherm(s) at T = " + ", ".join(f"{T_iso[i]:.1f}" for i in bad)
                          + " C do not superpose on the master curve (rms mismatch "
                          + ", ".join(f"{by_iso[i]:.3f}" for i in bad)
                          + f" decades, against {noise:.3f} scatter within isotherms): check those shifts",
                          stacklevel=2)
        method += ", pairwise then global P-spline refinement"
        if not converged:
            warnings.warn(f"{dma.source}: global refinement of the shift factors did not converge; "
                          "the result is reported with converged=False", stacklevel=2)
    else:
        method += ", pairwise"
    # physically a_T decreases with T; a clear reversal is a sign of a bad isotherm
    steps = np.diff(log_aT)
    if np.any(steps > 0.2):
        bad = [f"{T_iso[i]:.1f}->{T_iso[i + 1]:.1f} C" for i in np.flatnonzero(steps > 0.2)]
        warnings.warn(f"{dma.source}: log10 aT increases with temperature between {', '.join(bad)} "
                      "(expected a decrease); check those isotherms", stacklevel=2)
    return ShiftFactors(T_C=T_iso.copy(), log10_aT=log_aT - log_aT[ref], log10_bT=log_bT - log_bT[ref],
                        T_ref=float(T_iso[ref]), method=method, rms_log10=rms, converged=converged,
                        rms_by_isotherm=by_iso)


@doi("10.1021/ja01619a008")
def fit_wlf(T_C, log10_aT, T_ref: float, *, T_range: tuple[float, float] | None = None,
            sigma=None, valid_from: float | None = None) -> WLFFit:
    r"""Fit the WLF constants C1, C2 to shift factors (T_ref fixed), with covariance.

    .. math:: \log_{10} a_T = -\frac{C_1 (T - T_{ref})}{C_2 + T - T_{ref}}

    (Williams, Landel & Ferry 1955). A linearised fit,
    :math:`(T-T_{ref})/(-\log a_T) = C_2/C_1 + (T-T_{ref})/C_1`, gives the start; a nonlinear least-squares
    fit (``scipy.optimize.curve_fit``) with :math:`C_2 > T_{ref} - T_{min}` (the singularity below the data)
    gives the result.

    Parameters
    ----------
    T_C, log10_aT : array_like
        Temperatures (deg C) and shift factors; the shifts must be referred to ``T_ref``
        (:math:`\log a_T(T_{ref}) = 0`).
    T_ref : float
        Reference temperature, deg C.
    T_range : (float, float), optional
        Use only points with T_range[0] <= T <= T_range[1] (the range where WLF holds, typically
        Tg to Tg + 100 K).
    sigma : array_like, optional
        Uncertainty of each log10 aT.
    valid_from : float, optional
        The law must be finite down to this temperature (deg C): the singularity
        :math:`T_{ref} - C_2` is kept below it (default: below the lowest fitted point).

    Returns
    -------
    WLFFit

    Raises
    ------
    InputError
        Fewer than two points off T_ref in range, or no WLF law fits (e.g. shifts increasing with T).
    """
    from scipy import optimize
    T = np.asarray(T_C, dtype=float).ravel()
    y = np.asarray(log10_aT, dtype=float).ravel()
    if T.size != y.size:
        raise InputError(f"fit_wlf: T_C and log10_aT differ in length ({T.size}, {y.size})")
    if not (np.all(np.isfinite(T)) and np.all(np.isfinite(y))):
        raise InputError("fit_wlf: T_C and log10_aT must be finite")
    sig = None if sigma is None else np.broadcast_to(np.asarray(sigma, dtype=float), T.shape)
    mask = np.ones(T.size, dtype=bool)
    if T_range is not None:
        lo, hi = T_range
        mask = (T >= lo) & (T <= hi)
    T, y = T[mask], y[mask]
    sig = None if sig is None else sig[mask]
    dT = T - T_ref
    off = np.abs(dT) > 1e-9
    if off.sum() < 2:
        raise InputError(f"fit_wlf: need at least two isotherms away from T_ref = {T_ref} C in the WLF range, "
                         f"got {int(off.sum())}")
    # start: linearised WLF
    C1_0, C2_0 = 10.0, 100.0
    good = off & (np.abs(y) > 1e-6) & (np.sign(-y) == np.sign(dT))
    if good.sum() >= 2:
        slope, icpt = np.polyfit(dT[good], dT[good] / (-y[good]), 1)
        if slope > 0 and icpt > 0:
            C1_0, C2_0 = 1.0 / slope, icpt / slope
    T_low = T.min() if valid_from is None else min(T.min(), valid_from)
    C2_min = max(1e-3, T_ref - T_low + 1e-3)
    C2_0 = max(C2_0, C2_min + 1.0)

    def model(dT, C1, C2):
        return -C1 * dT / (C2 + dT)

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", optimize.OptimizeWarning)
            popt, pcov = optimize.curve_fit(model, dT, y, p0=[C1_0, C2_0], sigma=sig,
                                            bounds=([1e-6, C2_min], [1e4, 1e5]), maxfev=20000)
    except (RuntimeError, ValueError) as exc:
        raise InputError(f"fit_wlf: no WLF law fits these shift factors ({exc})") from None
    resid = y - model(dT, *popt)
    if not np.all(np.isfinite(pcov)):
        # exact fit with 2 points: covariance undefined; report zeros with a warning rather than NaN
        warnings.warn("fit_wlf: covariance undetermined (as many points as parameters); reported as zeros",
                      stacklevel=2)
        pcov = np.zeros((2, 2))
    wlf = WLF(C1=float(popt[0]), C2=float(popt[1]), T_ref=float(T_ref))
    return WLFFit(wlf=wlf, covariance=pcov, stderr=np.sqrt(np.diag(pcov)), rms=float(np.sqrt(np.mean(resid ** 2))),
                  T_range=(float(T.min()), float(T.max())), n_points=int(T.size))


@doi("isbn:978-0-471-04894-7")
def fit_arrhenius(T_C, log10_aT, T_g: float, log10_aT_g: float) -> Arrhenius:
    r"""Fit the activation energy of the Arrhenius shift below ``T_g``, anchored at the WLF value at ``T_g``.

    .. math:: \log_{10} a_T - \log_{10} a_T(T_g) = \frac{E_a}{R\ln 10}\left(\frac1T - \frac1{T_g}\right)

    (absolute temperatures), a one-parameter linear least-squares fit with :math:`E_a \ge 0`; continuity at
    :math:`T_g` is imposed (Ferry 1980, ch. 11).

    Parameters
    ----------
    T_C, log10_aT : array_like
        Shift factors at temperatures below ``T_g`` (deg C).
    T_g : float
        Glass transition temperature, deg C, where the law hands over to WLF.
    log10_aT_g : float
        log10 aT at T_g from the WLF law.
    """
    T = np.asarray(T_C, dtype=float).ravel()
    y = np.asarray(log10_aT, dtype=float).ravel() - log10_aT_g
    if T.size == 0:
        raise InputError(f"fit_arrhenius: no isotherm below T_g = {T_g} C")
    x = (1.0 / (T + _K0) - 1.0 / (T_g + _K0)) / (R_GAS * math.log(10.0))
    if np.all(x == 0):
        raise InputError(f"fit_arrhenius: all isotherms at T_g = {T_g} C")
    Ea = max(float(np.dot(x, y) / np.dot(x, x)), 0.0)
    dof = max(T.size - 1, 1)
    s2 = float(np.sum((y - Ea * x) ** 2) / dof)
    se = math.sqrt(s2 / float(np.dot(x, x))) if T.size > 1 else None
    return Arrhenius(E_a=Ea, T_g=float(T_g), log10_aT_g=float(log10_aT_g), E_a_stderr=se)


@doi("10.1021/ja01619a008", "isbn:978-0-471-04894-7")
def wlf_change_reference(wlf: WLF, T_ref: float) -> WLF:
    r"""The same WLF law referred to a new reference temperature.

    With :math:`\Delta = T_{ref}' - T_{ref}`: :math:`C_2' = C_2 + \Delta`,
    :math:`C_1' = C_1 C_2 / C_2'` (exact; Ferry 1980, ch. 11). Raises if the new T_ref is at or below the
    singularity :math:`T_{ref} - C_2`.
    """
    return wlf.with_T_ref(T_ref)


# ==================================================================================================== helpers

def _isotherm_arrays(dma, using, vertical):
    """log10 omega and the log components per isotherm; comps[j] = 1 where a vertical shift applies."""
    if using not in ("moduli", "tan_delta"):
        raise InputError(f"using: expected 'moduli' or 'tan_delta', got {using!r}")
    if dma.n_isotherms < 2:
        raise InputError(f"{dma.source}: one isotherm only (T = {dma.T_isotherm[0]:.1f} C); time-temperature "
                         "superposition needs at least two isotherms")
    xs, Ys = [], []
    for k, idx in enumerate(dma.isotherm_indices()):
        if np.unique(dma.f_Hz[idx]).size < 2:
            raise InputError(f"{dma.source}: isotherm at T = {dma.T_isotherm[k]:.1f} C has fewer than two "
                             "frequencies; expected a frequency sweep")
        x = np.log10(dma.omega[idx])
        l1, l2 = np.log10(dma.E_storage[idx]), np.log10(dma.E_loss[idx])
        if vertical:
            Y = np.column_stack([l2 - l1, l1, l2])
        elif using == "tan_delta":
            Y = (l2 - l1)[:, None]
        else:
            Y = np.column_stack([l1, l2])
        xs.append(x)
        Ys.append(Y)
    if vertical:
        comps = np.array([0.0, 1.0, 1.0])
    elif using == "tan_delta":
        comps = np.array([0.0])
    else:
        comps = np.array([1.0, 1.0])
    return xs, Ys, np.asarray(dma.T_isotherm, dtype=float), comps


def _poly_deg(n):
    return 1 if n < 4 else (2 if n < 8 else 3)


def _pair_shift(xa, Ya, xb, Yb, comps, lo, hi, extend, vertical, warmer, step=0.02):
    """Shift s (and vertical b) placing isotherm b (x + s, Y + b) onto the already placed isotherm a.

    ``lo``, ``hi`` bound s (absolute, decades); ``warmer``: b is warmer than a.
    Returns (s, b, how): how is "overlap", "extrapolated" (no overlap of the data windows within the bounds;
    the neighbours' polynomial trends were extended by up to ``extend`` decades) or "none" (placed edge to edge).
    """
    from scipy import optimize
    m = Ya.shape[1]
    pa = [np.polyfit(xa, Ya[:, j], _poly_deg(xa.size)) for j in range(m)]
    pb = [np.polyfit(xb, Yb[:, j], _poly_deg(xb.size)) for j in range(m)]
    a_lo, a_hi = xa.min(), xa.max()
    b_lo, b_hi = xb.min(), xb.max()
    n_min = max(3, int(0.25 * min(xa.size, xb.size)))
    # horizontal-only components decide s when vertical shifts are on
    hj = [j for j in range(m) if comps[j] == 0] if vertical else list(range(m))
    vj = [j for j in range(m) if comps[j] == 1]

    def cost(s):
        extend = ext_used
        s = np.atleast_1d(np.asarray(s, dtype=float))[:, None]
        xb_s = xb[None, :] + s                                     # b's points in a's frame
        in_a = (xb_s >= a_lo - extend) & (xb_s <= a_hi + extend)
        xa_b = xa[None, :] - s                                     # a's points in b's frame
        in_b = (xa_b >= b_lo - extend) & (xa_b <= b_hi + extend)
        n_in = in_a.sum(axis=1) + in_b.sum(axis=1)
        ssq = np.zeros(s.shape[0])
        for j in hj:
            rb = Yb[None, :, j] - np.polyval(pa[j], xb_s)
            ra = Ya[None, :, j] - np.polyval(pb[j], xa_b)
            ssq += np.where(in_a, rb * rb, 0.0).sum(axis=1) + np.where(in_b, ra * ra, 0.0).sum(axis=1)
        out = ssq / np.maximum(n_in, 1) / len(hj)
        return np.where(n_in >= n_min, out, np.inf), in_a, in_b

    grid = np.arange(lo, hi + step / 2, step)
    # scatter of a's points about its own trend: the mismatch a good superposition should reach
    scatter = max(float(np.sqrt(np.mean((Ya[:, j] - np.polyval(pa[j], xa)) ** 2))) for j in hj)
    good_enough = 3.0 * scatter + 0.02
    # true overlap first; the polynomial trends are extrapolated only when that gives no (good) match
    ext_used = 0.0
    c, _, _ = cost(grid)
    best = float(np.min(c)) if np.any(np.isfinite(c)) else np.inf
    if extend > 0 and not math.sqrt(best) <= good_enough:
        ext_used = extend
        c_ext, _, _ = cost(grid)
        if np.any(np.isfinite(c_ext)) and float(np.min(c_ext)) < best:
            c = c_ext
        else:
            ext_used = 0.0
    i = int(np.argmin(c))
    res = optimize.minimize_scalar(lambda s: float(np.minimum(cost(s)[0][0], 1e300)), bounds=(grid[max(i - 1, 0)],
                                   grid[min(i + 1, grid.size - 1)]), method="bounded",
                                   options={"xatol": 1e-4})
    s = float(res.x) if np.isfinite(res.fun) and res.fun <= c[i] else float(grid[i])
    b = 0.0
    if vertical and vj:
        # vertical shift: mean log mismatch of E', E'' over the overlap at the chosen horizontal shift
        _, in_a, in_b = cost(s)
        diffs = []
        for j in vj:
            rb = Yb[:, j] - np.polyval(pa[j], xb + s)
            ra = Ya[:, j] - np.polyval(pb[j], xa - s)
            diffs.append(-rb[in_a[0]])
            diffs.append(ra[in_b[0]])
        d = np.concatenate(diffs)
        b = float(np.mean(d)) if d.size else 0.0
    how = "extrapolated" if ext_used > 0 else "overlap"
    # a neighbour that cannot be matched (rms mismatch far above the scatter about its own trend) is reported
    if how == "overlap" and math.sqrt(min(float(cost(s)[0][0]), c[i])) > good_enough:
        how = "mismatch"
    return s, b, how


def _global_refine(xs, Ys, comps, log_aT0, log_bT0, ref, vertical, smoothing, knots_per_decade, robust,
                   max_step, reverse_tol, max_move=2.0):
    """Refine all shifts together against one penalised B-spline master curve per component.

    The parameters are the steps between neighbouring isotherms (outwards from the reference), so that the
    physical bound on each step (a_T decreasing with T, up to ``reverse_tol``) is a simple box bound.
    """
    from scipy import interpolate, linalg, optimize
    n = len(xs)
    free = [k for k in range(n) if k != ref]
    sizes = np.array([x.size for x in xs])
    owner = np.repeat(np.arange(n), sizes)
    x_raw = np.concatenate(xs)
    Y = np.concatenate(Ys)                      # (N, m)
    N, m = Y.shape
    # fixed knots covering every reachable reduced frequency
    x0 = x_raw + log_aT0[owner]
    lo = x0.min() - max_move - 0.5
    hi = x0.max() + max_move + 0.5
    nseg = max(4, int(math.ceil((hi - lo) * knots_per_decade)))
    kdeg = 3
    inner = np.linspace(lo, hi, nseg + 1)
    t = np.concatenate([[lo] * kdeg, inner, [hi] * kdeg])
    nb = t.size - kdeg - 1
    D = np.diff(np.eye(nb), n=2, axis=0)
    lam = math.sqrt(smoothing * N / nb)
    P = lam * D

    nf = len(free)
    # s_free = C @ steps: each isotherm's shift is the sum of the steps on the path from the reference
    C = np.zeros((nf, nf))
    pos = {k: i for i, k in enumerate(free)}
    for i, k in enumerate(free):
        path = range(ref + 1, k + 1) if k > ref else range(k, ref)
        for j in path:
            C[i, pos[j]] = 1.0
    parent = np.array([k - 1 if k > ref else k + 1 for k in free])
    steps0 = log_aT0[free] - log_aT0[parent]

    def unpack(p):
        a = log_aT0.copy()
        b = log_bT0.copy() if vertical else np.zeros(n)
        a[free] = C @ p[:nf]
        if vertical:
            b[free] = p[len(free):]
        return a, b

    comp_rows = np.asarray(comps, dtype=float)

    PtP = P.T @ P
    n_pen = P.shape[0]
    npar = len(free) * (2 if vertical else 1)

    def solve(p):
        """Spline coefficients for shifts p; residuals and Kaufman's variable-projection Jacobian.

        Normal equations G c = B^T y with G = B^T B + P^T P (small, symmetric positive definite: the penalty
        makes it so even where no point falls on a basis function).
        """
        a, b = unpack(p)
        x = np.clip(x_raw + a[owner], lo, hi)
        B = interpolate.BSpline.design_matrix(x, t, kdeg).tocsr()   # sparse: 4 non-zeros per row
        Yc = Y - np.outer(b[owner], comp_rows)           # vertical shift acts on E', E'' only
        cho = linalg.cho_factor((B.T @ B).toarray() + PtP)
        coef = linalg.cho_solve(cho, B.T @ Yc)
        r = np.vstack([B @ coef - Yc, P @ coef])          # (N + n_pen, m)
        # slope of the fitted master curve at each point
        slope = np.column_stack([interpolate.BSpline(t, coef[:, j], kdeg).derivative()(x) for j in range(m)])
        # d(residual)/d(parameter) before projection, nonzero on data rows only: one column per (param, comp)
        V = np.zeros((N, npar, m))
        for i, k in enumerate(free):
            rows = np.flatnonzero(owner == k)
            V[rows, i, :] = slope[rows]
            if vertical:
                V[rows, len(free) + i, :] = comp_rows
        V = V.reshape(N, npar * m)
        X = linalg.cho_solve(cho, B.T @ V)
        W = np.vstack([V - B @ X, -(P @ X)])               # (I - A A^+) dA/dp c  (Kaufman 1975)
        W = W.reshape(N + n_pen, npar, m)
        J = W.transpose(2, 0, 1).reshape(m * (N + n_pen), npar)
        J[:, :nf] = J[:, :nf] @ C                          # chain rule: shifts = C @ steps
        return r.ravel(order="F"), J

    cache = {}

    def fun(p):
        key = p.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = solve(p)
        return cache[key][0]

    def jac(p):
        key = p.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = solve(p)
        return cache[key][1]

    residuals = fun

    p0 = np.concatenate([steps0] + ([log_bT0[free]] if vertical else []))
    lb = p0 - max_move
    ub = p0 + max_move
    warm = np.array([k > ref for k in free])
    lb[:nf] = np.maximum(lb[:nf], np.where(warm, -max_step, -reverse_tol))
    ub[:nf] = np.minimum(ub[:nf], np.where(warm, reverse_tol, max_step))
    p0[:nf] = np.clip(p0[:nf], lb[:nf], ub[:nf])
    if vertical:
        lb[len(free):] = p0[len(free):] - 1.0
        ub[len(free):] = p0[len(free):] + 1.0
    r0 = residuals(p0)
    kw = {}
    if robust:
        data_rows = np.concatenate([np.arange(N) + j * (N + P.shape[0]) for j in range(m)])
        mad = float(np.median(np.abs(r0[data_rows])))
        kw = {"loss": "soft_l1", "f_scale": max(3.0 * 1.4826 * mad, 1e-3)}
    # lsmr avoids a dense SVD of the Jacobian each iteration (many rows, few columns); scipy's 2-D subspace step
    # needs at least two parameters, so tiny problems use the exact solver
    solver = "lsmr" if p0.size > 2 else "exact"
    sol = optimize.least_squares(fun, p0, jac=jac, bounds=(lb, ub), x_scale=1.0, tr_solver=solver,
                                 xtol=1e-8, ftol=1e-10, gtol=1e-10, max_nfev=100 * (len(p0) + 1), **kw)
    a, b = unpack(sol.x)
    r = residuals(sol.x)
    data = np.stack([r[j * (N + P.shape[0]): j * (N + P.shape[0]) + N] for j in range(m)], axis=1)
    rms = float(np.sqrt(np.mean(data ** 2)))
    by_iso = np.sqrt(np.bincount(owner, weights=np.mean(data ** 2, axis=1), minlength=n) / sizes)
    return a, b, rms, bool(sol.status > 0), by_iso
