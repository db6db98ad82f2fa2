r"""Temperature shift laws in closed form, and their least-squares fits to shift factors.

Time-temperature superposition (Ferry 1980, ch. 11) refers a modulus measured at temperature T to a reference
temperature through the horizontal shift factor :math:`a_T`,

.. math:: E(\omega, T) = b_T\, E(\omega\, a_T(T),\ T_{ref}).

The laws here give :math:`\log_{10} a_T` in closed form: :class:`WLF` (Williams, Landel & Ferry 1955),
:class:`Arrhenius`, and :class:`TemperatureShift` / :class:`WLFArrhenius`: WLF between two hand-over
temperatures, an Arrhenius law below the glass transition T_g and another above T_upper (about T_g + 100 K, where
WLF stops describing the shifts: Ferry 1980, ch. 11; Dealy & Plazek 2009), each continuous with WLF in
:math:`\log_{10} a_T` (and, when its activation energy is derived rather than fitted, in the slope). Every law
offers ``log10_aT(T)``, ``T_ref``, ``with_T_ref(T)``, ``kind`` and ``describe()`` (the interface shared with
:mod:`materials.shift`). :func:`as_shift_law` turns the case-file mappings of constants into laws.
:func:`fit_wlf` (optionally with the hand-over above T_upper) and :func:`fit_arrhenius` fit the laws to measured
shift factors, :class:`WLFFit` carrying the WLF covariance. :func:`wlf_activation_energy` is Ferry's apparent
activation energy of a WLF law, the activation energy that makes a hand-over continuous in slope.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace
from typing import Mapping

import numpy as np

from frictioncite import doi

from .errors import AccuracyWarning, InputError

__all__ = ["WLF", "Arrhenius", "TemperatureShift", "WLFArrhenius", "as_shift_law", "wlf_change_reference",
           "wlf_activation_energy", "WLFFit", "fit_wlf", "fit_arrhenius", "R_GAS", "UNDETERMINED_COVARIANCE",
           "DEALY_PLAZEK_2009"]

#: Gas constant, J/(mol K).
R_GAS = 8.314462618
_K0 = 273.15

#: Start of the text of the warning :func:`fit_wlf` gives when its covariance is undetermined (for filters).
UNDETERMINED_COVARIANCE = "fit_wlf: covariance undetermined"

#: J. M. Dealy, D. J. Plazek, Time-temperature superposition - a users guide, Rheology Bulletin 78 (2), 16-31
#: (2009): WLF from T_g to about T_g + 100 K, an Arrhenius law well above.
DEALY_PLAZEK_2009 = "dealy-plazek:rheol-bull-78-16-2009"


# ==================================================================================================== laws

@doi("10.1021/ja01619a008")
@dataclass(frozen=True)
class WLF:
    r"""Williams-Landel-Ferry shift factor.

    .. math:: \log_{10} a_T = -\frac{C_1 (T - T_{ref})}{C_2 + T - T_{ref}}

    (Williams, Landel & Ferry, J. Am. Chem. Soc. 77, 3701 (1955), Eq. 7), so that
    :math:`E(\omega, T) = b_T E(\omega a_T, T_{ref})`.

    Parameters
    ----------
    C1 : float
        Dimensionless WLF constant (> 0).
    C2 : float
        WLF constant, K (> 0).
    T_ref : float
        Reference temperature, deg C.

    Examples
    --------
    >>> wlf = WLF(C1=8.86, C2=101.6, T_ref=20.0)
    >>> print(round(wlf.log10_aT(30.0), 4))               # 10 K warmer: relaxation 10**0.79 times faster
    -0.7939
    >>> print(round(wlf.with_T_ref(30.0).log10_aT(20.0), 4))   # the same law referred to 30 C
    0.7939
    """

    C1: float
    C2: float
    T_ref: float

    kind = "wlf"

    def __post_init__(self):
        for name in ("C1", "C2", "T_ref"):
            v = getattr(self, name)
            if not isinstance(v, (int, float, np.floating, np.integer)) or not math.isfinite(v):
                raise InputError(f"WLF.{name}: expected a finite number, got {v!r}")
        if self.C1 <= 0 or self.C2 <= 0:
            raise InputError(f"WLF: expected C1 > 0 and C2 > 0 K, got C1={self.C1}, C2={self.C2}")

    def log10_aT(self, T):
        """log10 of the shift factor at temperature(s) ``T`` (deg C). Raises below the WLF singularity."""
        dT = np.asarray(T, dtype=float) - self.T_ref
        if not np.all(np.isfinite(dT)):
            raise InputError(f"temperature: expected finite temperatures in deg C, got {T!r}")
        if np.any(self.C2 + dT <= 0):
            raise InputError(f"temperature: WLF (C2={self.C2} K, T_ref={self.T_ref} C) is singular at or below "
                             f"T = {self.T_ref - self.C2:g} C")
        return -self.C1 * dT / (self.C2 + dT)

    def aT(self, T):
        """Shift factor a_T (dimensionless)."""
        return 10.0 ** self.log10_aT(T)

    def with_T_ref(self, T_ref: float) -> "WLF":
        r"""The same law referred to another reference temperature (exact, Ferry 1980, ch. 11).

        With :math:`\Delta = T_{ref}' - T_{ref}`: :math:`C_2' = C_2 + \Delta`, :math:`C_1' = C_1 C_2 / C_2'`.

        Raises
        ------
        InputError
            The new reference is at or below the singularity :math:`T_{ref} - C_2`.
        """
        C2n = self.C2 + (float(T_ref) - self.T_ref)
        if not C2n > 0:
            raise InputError(f"T_ref: {T_ref} C is at or below the WLF singularity {self.T_ref - self.C2:g} C")
        return WLF(C1=self.C1 * self.C2 / C2n, C2=C2n, T_ref=float(T_ref))

    def describe(self) -> str:
        """One line: the law and its constants."""
        return f"WLF: C1 = {self.C1:.4g}, C2 = {self.C2:.4g} K at T_ref = {self.T_ref:.4g} C"

    @classmethod
    def from_mapping(cls, m) -> "WLF":
        """Build from a mapping with keys ``C1``, ``C2`` and ``T_ref_C`` (or ``T_ref``)."""
        try:
            T_ref = m["T_ref_C"] if "T_ref_C" in m else m["T_ref"]
            return cls(C1=float(m["C1"]), C2=float(m["C2"]), T_ref=float(T_ref))
        except KeyError as exc:
            raise InputError(f"wlf: missing key {exc.args[0]!r} (expected C1, C2, T_ref_C)") from None


@doi("isbn:978-0-471-04894-7")
@dataclass(frozen=True, repr=False)
class Arrhenius:
    r"""Arrhenius shift law, alone or as the branch below the glass transition of a WLF law.

    .. math:: \log_{10} a_T = \log_{10} a_T(T_g) + \frac{E_a}{R \ln 10}
              \left(\frac{1}{T + 273.15} - \frac{1}{T_g + 273.15}\right)

    (Ferry 1980, ch. 11). ``E_a`` in J/mol, temperatures in deg C. ``T_g`` is the anchor temperature where
    the value ``log10_aT_g`` is imposed: below a WLF law it is the glass transition (continuity with WLF); for
    a law on its own, :meth:`from_reference` anchors it at the reference temperature (``log10_aT_g = 0``).

    Examples
    --------
    >>> law = Arrhenius.from_reference(E_a=100e3, T_ref=-40.0)    # 100 kJ/mol, a_T = 1 at -40 C
    >>> print(round(law.log10_aT(-50.0), 3))
    1.004
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



@doi("10.1021/ja01619a008", "isbn:978-0-471-04894-7")
def wlf_activation_energy(wlf: WLF, T):
    r"""Apparent activation energy of a WLF law at temperature(s) ``T`` (deg C), J/mol.

    .. math:: \Delta H_a(T) = R\ln 10\;\frac{C_1 C_2\,(T + 273.15)^2}{(C_2 + T - T_{ref})^2}
        = -R\ln 10\,\frac{d\log_{10}a_T}{d(1/T)}

    (Ferry 1980, ch. 11). An Arrhenius law with this activation energy, anchored at the WLF value at ``T``, has the
    same :math:`\log_{10} a_T` and the same slope there: the hand-over of :class:`TemperatureShift` is continuous
    in both. It falls with temperature towards :math:`R\ln 10\,C_1 C_2` (WLF flattens far above T_g).

    Raises
    ------
    InputError
        ``T`` at or below the WLF singularity :math:`T_{ref} - C_2`.
    """
    T = np.asarray(T, dtype=float)
    x = wlf.C2 + T - wlf.T_ref
    if not np.all(np.isfinite(T)) or np.any(x <= 0):
        raise InputError(f"temperature: expected finite temperatures above the WLF singularity "
                         f"{wlf.T_ref - wlf.C2:g} C, got {T!r}")
    out = R_GAS * math.log(10.0) * wlf.C1 * wlf.C2 * (T + _K0) ** 2 / x ** 2
    return out if out.ndim else float(out)


def _upper_temperature(wlf: WLF, E_a: float) -> float:
    """The temperature (deg C) where the WLF law's apparent activation energy is ``E_a`` (closed form)."""
    floor = R_GAS * math.log(10.0) * wlf.C1 * wlf.C2
    if not (math.isfinite(E_a) and E_a > floor):
        raise InputError(f"E_a_upper: the WLF law's apparent activation energy falls from infinity at its singularity "
                         f"to {floor / 1e3:.4g} kJ/mol far above it; an Arrhenius law of {E_a / 1e3:.4g} kJ/mol "
                         "meets it in slope nowhere (expected a larger E_a, or give T_upper)")
    r = math.sqrt(E_a / floor)
    T_inf = wlf.T_ref - wlf.C2 + _K0          # Vogel temperature, K
    return r * T_inf / (r - 1.0) - _K0


@doi("10.1021/ja01619a008", "isbn:978-0-471-04894-7", DEALY_PLAZEK_2009)
@dataclass(frozen=True, repr=False)
class TemperatureShift:
    r"""The temperature law of a master curve: WLF, with Arrhenius hand-overs below ``T_g`` and above ``T_upper``.

    .. math:: \log_{10} a_T(T) = L(T) - L(T_{ref}),\qquad
              L(T) = \begin{cases} \text{Arrhenius}_{low}(T) & T < T_g \\ \text{WLF}(T) & T_g \le T \le T_{upper}
              \\ \text{Arrhenius}_{up}(T) & T > T_{upper} \end{cases}

    WLF describes the shifts between the glass transition and about T_g + 100 K (Williams, Landel & Ferry 1955;
    Ferry 1980, ch. 11; Dealy & Plazek 2009); below T_g the glass falls out of equilibrium and above T_g + 100 K
    the shifts follow an Arrhenius law. Each Arrhenius branch is anchored on the WLF value at its hand-over
    (continuous in :math:`\log_{10}a_T`). The upper branch built by :meth:`with_upper` has the WLF law's apparent
    activation energy there (:func:`wlf_activation_energy`), so it is continuous in the slope as well; the
    lower branch is continuous in slope when its activation energy is derived the same way
    (:meth:`WLFArrhenius.from_constants` without ``E_a``), and keeps the kink of the glass transition when
    ``E_a`` was fitted to shifts below T_g. Normally ``T_ref`` is the WLF reference and :math:`L(T_{ref}) = 0`; a
    reference in an Arrhenius range is allowed. :meth:`law_at` says which law applies where.

    Parameters
    ----------
    wlf : WLF
    arrhenius : Arrhenius, optional
        The branch below ``arrhenius.T_g``.
    T_ref_C : float, optional
        Reference temperature, deg C (default ``wlf.T_ref``).
    upper : Arrhenius, optional
        The branch above ``upper.T_g`` (= :attr:`T_upper`), anchored on the WLF value there; build it with
        :meth:`with_upper`.
    fitted_range : (float, float), optional
        Temperatures (deg C) of the shift factors the law was fitted to, when known: beyond them a friction
        calculation says that the law is extrapolated (see :func:`materials.fitted_temperature_range`).
    """

    wlf: WLF
    arrhenius: Arrhenius | None = None
    T_ref_C: float | None = None
    upper: Arrhenius | None = None
    fitted_range: tuple[float, float] | None = None

    def __post_init__(self):
        up = self.upper
        if up is not None:
            if self.wlf.C2 + (up.T_g - self.wlf.T_ref) <= 0:
                raise InputError(f"T_upper: {up.T_g:g} C is at or below the WLF singularity "
                                 f"{self.wlf.T_ref - self.wlf.C2:g} C")
            if self.arrhenius is not None and up.T_g <= self.arrhenius.T_g:
                raise InputError(f"T_upper: the upper hand-over ({up.T_g:g} C) must lie above T_g "
                                 f"({self.arrhenius.T_g:g} C)")
            gap = abs(up.log10_aT_g - float(self.wlf.log10_aT(up.T_g)))
            if gap > 1e-9 * max(1.0, abs(up.log10_aT_g)):
                raise InputError(f"upper: the Arrhenius branch is not anchored on the WLF value at {up.T_g:g} C "
                                 f"(off by {gap:.3g} decades); build it with TemperatureShift.with_upper")
        if self.fitted_range is not None:
            try:
                lo, hi = (float(t) for t in self.fitted_range)
            except (TypeError, ValueError):
                raise InputError(f"fitted_range: expected (low, high) in deg C, got {self.fitted_range!r}") from None
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
                raise InputError(f"fitted_range: expected finite temperatures low <= high, got {self.fitted_range!r}")
            object.__setattr__(self, "fitted_range", (lo, hi))

    @property
    def kind(self) -> str:
        """``"wlf"`` for WLF alone, ``"wlf+arrhenius"`` with an Arrhenius branch (below T_g or above T_upper)."""
        return "wlf" if self.arrhenius is None and self.upper is None else "wlf+arrhenius"

    @property
    def T_ref(self) -> float:
        """Reference temperature, deg C: ``T_ref_C``, default the WLF law's."""
        return self.wlf.T_ref if self.T_ref_C is None else float(self.T_ref_C)

    @property
    def T_g(self) -> float | None:
        """Lower hand-over (glass transition), deg C, or None."""
        return None if self.arrhenius is None else float(self.arrhenius.T_g)

    @property
    def T_upper(self) -> float | None:
        """Upper hand-over, deg C, or None (WLF continued without bound)."""
        return None if self.upper is None else float(self.upper.T_g)

    def _raw(self, T):
        T = np.asarray(T, dtype=float)
        if not np.all(np.isfinite(T)):
            raise InputError(f"temperature: expected finite temperatures in deg C, got {T!r}")
        if self.arrhenius is None and self.upper is None:
            return np.asarray(self.wlf.log10_aT(T), dtype=float)
        below = T < self.arrhenius.T_g if self.arrhenius is not None else np.zeros(T.shape, dtype=bool)
        above = T > self.upper.T_g if self.upper is not None else np.zeros(T.shape, dtype=bool)
        mid = ~(below | above)
        out = np.empty(T.shape)
        for mask, law in ((mid, self.wlf), (below, self.arrhenius), (above, self.upper)):
            if np.any(mask):
                out[mask] = law.log10_aT(T[mask])
        return out

    def log10_aT(self, T):
        """log10 aT (deg C in, vectorized): Arrhenius below T_g and above T_upper (where set), WLF between."""
        out = self._raw(T)
        if self.T_ref_C is not None:
            out = out - self._raw(self.T_ref_C)
        return out if out.ndim else float(out)

    def law_at(self, T) -> np.ndarray:
        """'WLF' or 'Arrhenius' for each temperature."""
        T = np.asarray(T, dtype=float)
        arr = np.zeros(T.shape, dtype=bool)
        if self.arrhenius is not None:
            arr |= T < self.arrhenius.T_g
        if self.upper is not None:
            arr |= T > self.upper.T_g
        return np.where(arr, "Arrhenius", "WLF")

    def with_upper(self, T_upper: float | None = None, *, E_a: float | None = None) -> "TemperatureShift":
        r"""The same law handing over to an Arrhenius law above ``T_upper``, continuous in value and slope.

        Give the hand-over temperature (the activation energy is then the WLF law's apparent one there,
        :func:`wlf_activation_energy`), or the activation energy ``E_a`` (J/mol; the hand-over is then where WLF
        has that apparent activation energy, in closed form). A common choice is T_g + 100 K (Ferry 1980,
        ch. 11; Dealy & Plazek 2009).

        Raises
        ------
        InputError
            Both or neither given; a hand-over at or below T_g or the WLF singularity; an ``E_a`` that WLF
            never reaches.
        """
        if (T_upper is None) == (E_a is None):
            raise InputError("with_upper: give the hand-over temperature T_upper or the activation energy E_a above "
                             "it (continuity of the slope fixes the other)")
        if T_upper is None:
            T_upper = _upper_temperature(self.wlf, float(E_a))
        T_upper = float(T_upper)
        if not math.isfinite(T_upper):
            raise InputError(f"T_upper: expected a temperature in deg C, got {T_upper!r}")
        if self.wlf.C2 + (T_upper - self.wlf.T_ref) <= 0:
            raise InputError(f"T_upper: {T_upper:g} C is at or below the WLF singularity "
                             f"{self.wlf.T_ref - self.wlf.C2:g} C")
        E = wlf_activation_energy(self.wlf, T_upper)
        up = Arrhenius(E_a=float(E), T_g=T_upper, log10_aT_g=float(self.wlf.log10_aT(T_upper)))
        return replace(self, upper=up)

    def with_T_ref(self, T_ref: float) -> "TemperatureShift":
        """The same law referred to a new reference temperature.

        The WLF constants change exactly (:func:`wlf_change_reference`) when T_ref is above the WLF singularity;
        the Arrhenius branches are re-anchored so that the law is unchanged up to the constant.
        """
        T_ref = float(T_ref)
        if self.wlf.C2 + (T_ref - self.wlf.T_ref) > 0:
            new_wlf = wlf_change_reference(self.wlf, T_ref)
            offset = float(self.wlf.log10_aT(T_ref))
        else:                         # reference in the Arrhenius range, below the WLF singularity
            new_wlf, offset = self.wlf, 0.0
        arr, up = self.arrhenius, self.upper
        if arr is not None:
            arr = replace(arr, log10_aT_g=arr.log10_aT_g - offset)
        if up is not None:
            up = replace(up, log10_aT_g=up.log10_aT_g - offset)
        out = type(self)(new_wlf, arr, None, up, self.fitted_range)
        if abs(out._raw(T_ref)) > 0:
            out = type(self)(new_wlf, arr, T_ref, up, self.fitted_range)
        return out

    def describe(self) -> str:
        """One line: the law and its constants."""
        w = self.wlf
        text = f"WLF: C1 = {w.C1:.4g}, C2 = {w.C2:.4g} K at T_ref = {w.T_ref:.4g} C"
        if self.arrhenius is not None:
            text += (f"; Arrhenius below T_g = {self.arrhenius.T_g:.4g} C (E_a = {self.arrhenius.E_a / 1e3:.4g} "
                     "kJ/mol)")
        if self.upper is not None:
            text += (f"; Arrhenius above {self.upper.T_g:.4g} C (E_a = {self.upper.E_a / 1e3:.4g} kJ/mol, "
                     "continuous in log a_T and slope)")
        if self.T_ref_C is not None:
            text += f"; a_T = 1 at {self.T_ref_C:.4g} C"
        return text

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.describe()})"


@doi("10.1021/ja01619a008", "isbn:978-0-471-04894-7", DEALY_PLAZEK_2009)
class WLFArrhenius(TemperatureShift):
    r"""WLF between the hand-overs, Arrhenius below the glass transition ``T_g`` and (optionally) above
    ``T_upper``, continuous at each.

    .. math:: \log_{10} a_T = \begin{cases} \log_{10} a_T^{WLF}(T_g) + \dfrac{E_a}{R\ln 10}\left(\dfrac{1}{T + 273.15}
              - \dfrac{1}{T_g + 273.15}\right) & T < T_g \\[1ex]
              -\dfrac{C_1 (T - T_{ref})}{C_2 + T - T_{ref}} & T_g \le T \le T_{upper} \\[1ex]
              \log_{10} a_T^{WLF}(T_{upper}) + \dfrac{E_{a,up}}{R\ln 10}\left(\dfrac{1}{T + 273.15}
              - \dfrac{1}{T_{upper} + 273.15}\right) & T > T_{upper} \end{cases}

    (Williams, Landel & Ferry 1955; Ferry 1980, ch. 11; Dealy & Plazek 2009). A :class:`TemperatureShift`
    whose Arrhenius branches are anchored on the WLF law; build it with :meth:`from_constants` or
    :meth:`from_mapping`.
    """

    @classmethod
    def from_constants(cls, C1: float, C2: float, T_ref: float, E_a: float | None = None, T_g: float | None = None,
                       *, T_upper: float | None = None, E_a_upper: float | None = None,
                       fitted_range: tuple[float, float] | None = None) -> "WLFArrhenius":
        r"""From the WLF constants (C1, C2 in K, T_ref in deg C) and the hand-overs.

        Parameters
        ----------
        C1, C2, T_ref : float
            The WLF law.
        E_a : float, optional
            Activation energy below T_g, J/mol (fitted to shifts below T_g: continuous in value only). Without it
            the branch below T_g takes the WLF law's apparent activation energy at T_g
            (:func:`wlf_activation_energy`): continuous in value and slope.
        T_g : float, optional
            Lower hand-over (glass transition), deg C.
        T_upper, E_a_upper : float, optional
            The upper hand-over: its temperature (deg C) or the activation energy above it (J/mol), one of them
            (see :meth:`TemperatureShift.with_upper`).
        fitted_range : (float, float), optional
            Temperatures the constants were fitted to, deg C.

        Raises
        ------
        InputError
            No hand-over given, ``E_a`` without ``T_g``, a hand-over at or below the WLF singularity
            :math:`T_{ref} - C_2` or T_upper below T_g.
        """
        wlf = WLF(C1=C1, C2=C2, T_ref=T_ref)
        if T_g is None and E_a is not None:
            raise InputError("WLFArrhenius: E_a is the activation energy below T_g; give T_g too")
        if T_g is None and T_upper is None and E_a_upper is None:
            raise InputError("WLFArrhenius: give a hand-over, T_g (below it Arrhenius) and/or T_upper or E_a_upper "
                             "(above it Arrhenius)")
        arr = None
        if T_g is not None:
            if not math.isfinite(T_g) or wlf.C2 + (T_g - wlf.T_ref) <= 0:
                raise InputError(f"WLFArrhenius: T_g = {T_g!r} C must lie above the WLF singularity "
                                 f"{wlf.T_ref - wlf.C2:g} C")
            Ea = wlf_activation_energy(wlf, T_g) if E_a is None else float(E_a)
            arr = Arrhenius(E_a=float(Ea), T_g=float(T_g), log10_aT_g=float(wlf.log10_aT(T_g)))
        out = cls(wlf, arr, None, None, fitted_range)
        if T_upper is not None or E_a_upper is not None:
            out = out.with_upper(T_upper, E_a=E_a_upper)
        return out if arr is None or T_ref >= arr.T_g else replace(out, T_ref_C=float(T_ref))

    @classmethod
    def from_mapping(cls, m) -> "WLFArrhenius":
        """From ``{"C1", "C2", "T_ref_C"}`` with ``"T_g"`` (and optionally ``"E_a"``) and/or ``"T_upper"`` or
        ``"E_a_upper"`` (the case-file form; E_a in J/mol, temperatures in deg C)."""
        try:
            T_ref = m["T_ref_C"] if "T_ref_C" in m else m["T_ref"]
            opt = {k: (None if m.get(k) is None else float(m[k])) for k in ("E_a", "T_g", "T_upper", "E_a_upper")}
            if opt["E_a"] is not None and opt["T_g"] is None:
                raise KeyError("T_g")
            return cls.from_constants(float(m["C1"]), float(m["C2"]), float(T_ref), opt["E_a"], opt["T_g"],
                                      T_upper=opt["T_upper"], E_a_upper=opt["E_a_upper"])
        except KeyError as exc:
            raise InputError(f"wlf+arrhenius: missing key {exc.args[0]!r} (expected C1, C2, T_ref_C and T_g "
                             "[with E_a] and/or T_upper or E_a_upper)") from None
        except (TypeError, ValueError):
            raise InputError(f"wlf+arrhenius: expected numbers for C1, C2, T_ref_C, E_a, T_g, T_upper, E_a_upper, "
                             f"got {dict(m)!r}") from None


def as_shift_law(law, *, name: str = "shift"):
    """A shift-law object from a law, a WLF mapping ``{C1, C2, T_ref_C}``, a WLF+Arrhenius mapping
    ``{C1, C2, T_ref_C, T_g [, E_a]}`` and/or ``{..., T_upper}`` (or ``E_a_upper``), or an Arrhenius mapping
    ``{E_a, T_ref_C}``.

    A law is any object with ``log10_aT(T)`` and ``T_ref`` (the laws of this module, and
    :class:`materials.TabulatedShift`, :class:`materials.SingleTemperature` of :mod:`materials.shift`); it is
    returned as it is.

    Raises
    ------
    InputError
        Naming the argument and what was expected.

    Examples
    --------
    >>> as_shift_law({"C1": 8.86, "C2": 101.6, "T_ref_C": 20.0})      # the case-file form
    WLF(C1=8.86, C2=101.6, T_ref=20.0)
    """
    if isinstance(law, (WLF, Arrhenius, TemperatureShift)):
        return law
    if isinstance(law, Mapping):
        keys = set(law)
        if {"C1", "C2"} <= keys and keys & {"E_a", "T_g", "T_upper", "E_a_upper"}:
            return WLFArrhenius.from_mapping(law)
        if {"C1", "C2"} <= keys:
            return WLF.from_mapping(law)
        if "E_a" in keys:
            return Arrhenius.from_mapping(law)
        raise InputError(f"{name}: a mapping needs C1, C2, T_ref_C (WLF), plus T_g [E_a] and/or T_upper "
                         f"(WLF+Arrhenius), or E_a, T_ref_C (Arrhenius); got keys {sorted(keys)}")
    if callable(getattr(law, "log10_aT", None)) and hasattr(law, "T_ref"):
        return law
    raise InputError(f"{name}: expected a shift law (materials.WLF, Arrhenius, WLFArrhenius, TabulatedShift) or a "
                     f"mapping of its constants, got {law!r}")


@doi("10.1021/ja01619a008", "isbn:978-0-471-04894-7")
def wlf_change_reference(wlf: WLF, T_ref: float) -> WLF:
    r"""The same WLF law referred to a new reference temperature.

    With :math:`\Delta = T_{ref}' - T_{ref}`: :math:`C_2' = C_2 + \Delta`,
    :math:`C_1' = C_1 C_2 / C_2'` (exact; Ferry 1980, ch. 11). Raises if the new T_ref is at or below the
    singularity :math:`T_{ref} - C_2`.
    """
    return wlf.with_T_ref(T_ref)


# ==================================================================================================== fits

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
    upper : Arrhenius or None
        The Arrhenius branch above the hand-over ``upper.T_g`` (``fit_wlf(..., T_upper=...)``), continuous with
        the WLF law in value and slope.
    T_upper_stderr : float or None
        Standard error of the hand-over temperature when it was fitted (``T_upper="fit"``), K.
    """

    wlf: WLF
    covariance: np.ndarray
    stderr: np.ndarray
    rms: float
    T_range: tuple[float, float]
    n_points: int
    upper: Arrhenius | None = None
    T_upper_stderr: float | None = None

    @property
    def T_upper(self) -> float | None:
        """The upper hand-over, deg C (None: WLF alone)."""
        return None if self.upper is None else float(self.upper.T_g)

    @property
    def law(self) -> TemperatureShift:
        """The fitted law as a :class:`TemperatureShift` (with its upper branch and its fitted range)."""
        return TemperatureShift(self.wlf, None, None, self.upper, self.T_range)

    @property
    def C1(self) -> float:
        """WLF constant C1 of the fitted law."""
        return self.wlf.C1

    @property
    def C2(self) -> float:
        """WLF constant C2 of the fitted law, K."""
        return self.wlf.C2

    @property
    def T_ref(self) -> float:
        """Reference temperature of the fitted law, deg C."""
        return self.wlf.T_ref

    def __repr__(self) -> str:
        up = ""
        if self.upper is not None:
            se = "" if self.T_upper_stderr is None else f" +- {self.T_upper_stderr:.2g}"
            up = f", Arrhenius above {self.T_upper:.4g}{se} C"
        return (f"WLFFit(C1 = {self.C1:.4g} +- {self.stderr[0]:.2g}, C2 = {self.C2:.4g} +- {self.stderr[1]:.2g} K, "
                f"T_ref = {self.T_ref:.4g} C{up}, rms {self.rms:.3g} decades over {self.n_points} isotherms)")


@doi("10.1021/ja01619a008")
def fit_wlf(T_C, log10_aT, T_ref: float, *, T_range: tuple[float, float] | None = None,
            sigma=None, valid_from: float | None = None, T_upper=None) -> WLFFit:
    r"""Fit the WLF constants C1, C2 to shift factors (T_ref fixed), with covariance; optionally with the
    Arrhenius hand-over above ``T_upper``.

    .. math:: \log_{10} a_T = -\frac{C_1 (T - T_{ref})}{C_2 + T - T_{ref}}

    (Williams, Landel & Ferry 1955). A linearised fit,
    :math:`(T-T_{ref})/(-\log a_T) = C_2/C_1 + (T-T_{ref})/C_1`, gives the start; a nonlinear least-squares
    fit (``scipy.optimize.curve_fit``) with :math:`C_2 > T_{ref} - T_{min}` (the singularity below the data)
    gives the result. With ``T_upper`` the model above the hand-over is the Arrhenius law continuous with WLF in
    value and slope (activation energy :func:`wlf_activation_energy` at ``T_upper``; Ferry 1980, ch. 11), so the
    points above it constrain C1 and C2 too; ``T_upper="fit"`` fits the hand-over as a third parameter (it needs
    shift factors on both sides of it).

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
    T_upper : float or "fit", optional
        Hand-over to the Arrhenius law above it, deg C (None: WLF everywhere).

    Returns
    -------
    WLFFit
        With ``upper`` (the Arrhenius branch) and ``law`` (the :class:`TemperatureShift`) when ``T_upper`` is given.

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

    p0, lo_b, hi_b, f = [C1_0, C2_0], [1e-6, C2_min], [1e4, 1e5], model
    fit_upper = isinstance(T_upper, str)
    if fit_upper and T_upper != "fit":
        raise InputError(f"fit_wlf: T_upper must be a temperature in deg C or 'fit', got {T_upper!r}")
    if T_upper is not None and not fit_upper:
        dTa = float(T_upper) - T_ref
        if not math.isfinite(dTa) or dTa <= -C2_min:
            raise InputError(f"fit_wlf: T_upper = {T_upper!r} C must lie above the lowest fitted temperature")

        def f(dT, C1, C2):
            return _with_upper(dT, C1, C2, dTa, T_ref)
    starts = [p0]
    if fit_upper:
        if np.sum(dT > np.median(dT)) < 2 or T.size < 4:
            raise InputError("fit_wlf: T_upper='fit' needs at least four isotherms, two of them in the upper half")
        lo_b, hi_b = lo_b + [float(dT.min())], hi_b + [float(dT.max())]
        starts = [p0 + [float(np.quantile(dT, q))] for q in (0.5, 0.7, 0.85)]

        def f(dT, C1, C2, dTa):
            return _with_upper(dT, C1, C2, dTa, T_ref)
    best = None
    for start in starts:
        try:
            with warnings.catch_warnings():     # an undetermined covariance is said below
                warnings.filterwarnings("ignore", "Covariance of the parameters could not be estimated",
                                        optimize.OptimizeWarning)
                popt, pcov = optimize.curve_fit(f, dT, y, p0=start, sigma=sig, bounds=(lo_b, hi_b), maxfev=20000)
        except (RuntimeError, ValueError) as exc:
            err = exc
            continue
        sse = float(np.sum((y - f(dT, *popt)) ** 2))
        if best is None or sse < best[0]:
            best = (sse, popt, pcov)
    if best is None:
        raise InputError(f"fit_wlf: no WLF law fits these shift factors ({err})") from None
    _, popt, pcov = best
    resid = y - f(dT, *popt)
    npar = popt.size
    if not np.all(np.isfinite(pcov)):
        # exact fit with 2 points: covariance undefined; report zeros with a warning rather than NaN
        warnings.warn(f"{UNDETERMINED_COVARIANCE} (as many points as parameters); reported as zeros",
                      AccuracyWarning, stacklevel=2)
        pcov = np.zeros((npar, npar))
    wlf = WLF(C1=float(popt[0]), C2=float(popt[1]), T_ref=float(T_ref))
    upper, se_up = None, None
    if T_upper is not None:
        upper = TemperatureShift(wlf).with_upper(T_ref + float(popt[2]) if fit_upper else float(T_upper)).upper
        se_up = float(math.sqrt(pcov[2, 2])) if fit_upper else None
    return WLFFit(wlf=wlf, covariance=pcov[:2, :2], stderr=np.sqrt(np.diag(pcov[:2, :2])),
                  rms=float(np.sqrt(np.mean(resid ** 2))), T_range=(float(T.min()), float(T.max())),
                  n_points=int(T.size), upper=upper, T_upper_stderr=se_up)


def _with_upper(dT, C1, C2, dTa, T_ref):
    """log10 aT of WLF (C1, C2 at T_ref) handing over above T_ref + dTa to the Arrhenius law continuous in value and
    slope (the least-squares model of :func:`fit_wlf` with ``T_upper``)."""
    TaK = T_ref + dTa + _K0
    ya = -C1 * dTa / (C2 + dTa)
    arr = ya + C1 * C2 * TaK ** 2 / (C2 + dTa) ** 2 * (1.0 / (T_ref + dT + _K0) - 1.0 / TaK)
    return np.where(dT > dTa, arr, -C1 * dT / (C2 + dT))


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
