r"""Temperature shift laws in closed form, and their least-squares fits to shift factors.

Time-temperature superposition (Ferry 1980, ch. 11) refers a modulus measured at temperature T to a reference
temperature through the horizontal shift factor :math:`a_T`,

.. math:: E(\omega, T) = b_T\, E(\omega\, a_T(T),\ T_{ref}).

The laws here give :math:`\log_{10} a_T` in closed form: :class:`WLF` (Williams, Landel & Ferry 1955),
:class:`Arrhenius` (below the glass transition), and :class:`TemperatureShift` / :class:`WLFArrhenius` (WLF
above T_g, Arrhenius below, continuous at T_g). Every law offers ``log10_aT(T)``, ``T_ref``,
``with_T_ref(T)``, ``kind`` and ``describe()`` (the interface shared with :mod:`materials.shift`).
:func:`as_shift_law` turns the case-file mappings of constants into laws. :func:`fit_wlf` and
:func:`fit_arrhenius` fit the laws to measured shift factors, :class:`WLFFit` carrying the WLF covariance.
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
           "WLFFit", "fit_wlf", "fit_arrhenius", "R_GAS", "UNDETERMINED_COVARIANCE"]

#: Gas constant, J/(mol K).
R_GAS = 8.314462618
_K0 = 273.15

#: Start of the text of the warning :func:`fit_wlf` gives when its covariance is undetermined (for filters).
UNDETERMINED_COVARIANCE = "fit_wlf: covariance undetermined"


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


def as_shift_law(law, *, name: str = "shift"):
    """A shift-law object from a law, a WLF mapping ``{C1, C2, T_ref_C}``, a WLF+Arrhenius mapping
    ``{C1, C2, T_ref_C, E_a, T_g}`` or an Arrhenius mapping ``{E_a, T_ref_C}``.

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
        if {"C1", "C2"} <= keys and {"E_a", "T_g"} <= keys:
            return WLFArrhenius.from_mapping(law)
        if {"C1", "C2"} <= keys:
            return WLF.from_mapping(law)
        if "E_a" in keys:
            return Arrhenius.from_mapping(law)
        raise InputError(f"{name}: a mapping needs C1, C2, T_ref_C (WLF), plus E_a, T_g (WLF+Arrhenius), or "
                         f"E_a, T_ref_C (Arrhenius); got keys {sorted(keys)}")
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
        with warnings.catch_warnings():     # an undetermined covariance is said below
            warnings.filterwarnings("ignore", "Covariance of the parameters could not be estimated",
                                    optimize.OptimizeWarning)
            popt, pcov = optimize.curve_fit(model, dT, y, p0=[C1_0, C2_0], sigma=sig,
                                            bounds=([1e-6, C2_min], [1e4, 1e5]), maxfev=20000)
    except (RuntimeError, ValueError) as exc:
        raise InputError(f"fit_wlf: no WLF law fits these shift factors ({exc})") from None
    resid = y - model(dT, *popt)
    if not np.all(np.isfinite(pcov)):
        # exact fit with 2 points: covariance undefined; report zeros with a warning rather than NaN
        warnings.warn(f"{UNDETERMINED_COVARIANCE} (as many points as parameters); reported as zeros",
                      AccuracyWarning, stacklevel=2)
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
