r"""Temperature shift laws as objects, and the reader of tabulated shift factors.

A shift law maps a temperature to the horizontal shift factor of time-temperature superposition,

.. math:: E(\omega, T) = b_T\, E(\omega\, a_T(T),\ T_{ref}),

and every law of this package offers the same small interface:

* ``log10_aT(T)``: :math:`\log_{10} a_T` at temperatures ``T`` (deg C, vectorized; a float for a scalar);
* ``T_ref``: the temperature where :math:`a_T = 1`, deg C;
* ``with_T_ref(T)``: the same law referred to another temperature;
* ``kind`` (``"wlf"``, ``"arrhenius"``, ``"wlf+arrhenius"``, ``"tabulated"``, ``"single temperature"``) and
  ``describe()`` (one line).

The laws: :class:`materials.WLF`, :class:`materials.Arrhenius`, :class:`materials.WLFArrhenius` (WLF between
T_g and an upper hand-over, Arrhenius beyond), :class:`TabulatedShift` (measured shift factors interpolated,
continued beyond the table the same way) and :class:`SingleTemperature` (a master curve usable at its own
temperature only).

For hot rubber (a flash or a heated contact patch takes it 100 K and more above the road), two helpers:
:func:`with_arrhenius_above` gives a law, a master curve or a Prony material the Arrhenius hand-over above a
stated temperature, and :func:`extrapolated_shift_note` states the rule by which a friction calculation says
that its temperatures left the range where the shift law was fitted (:func:`fitted_temperature_range`).
"""

from __future__ import annotations

import math
import re
import warnings
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from frictioncite import doi

from ._tables import _column_index, _role_of, read_table
from .errors import AccuracyWarning, InputError, PhysicsWarning, ignoring
from .laws import (DEALY_PLAZEK_2009, UNDETERMINED_COVARIANCE, WLF, Arrhenius, TemperatureShift, WLFFit,
                   _upper_temperature, as_shift_law, fit_wlf)
from .units import check_temperatures, normalise_units, to_celsius, unit_factor

__all__ = ["TabulatedShift", "SingleTemperature", "read_shift_factors", "as_shift_law", "SHIFT_LAW_TYPES",
           "EXTRAPOLATED_SHIFT", "with_arrhenius_above", "fitted_temperature_range", "extrapolated_shift_note",
           "SHIFT_RANGE_NOTE"]

_K0 = 273.15

#: Temperatures this close (K) outside a table are continued without a warning: the measured temperatures of a
#: DMA isotherm scatter by about this much around the isotherm's own.
QUIET_MARGIN_K = 1.0

#: Text of the warning given when a tabulated shift is continued outside its table (a regular expression, for
#: filters that silence that warning and no other).
EXTRAPOLATED_SHIFT = ".*temperatures outside the shift-factor table"

#: Start of the note (and :class:`PhysicsWarning`) of a friction result whose rubber temperatures left the range
#: where the shift law was fitted (:func:`extrapolated_shift_note`).
SHIFT_RANGE_NOTE = "shift law used outside the temperatures it was fitted to"


@doi("10.1137/0717021", "10.1021/ja01619a008")
@dataclass(frozen=True, eq=False, repr=False)
class TabulatedShift:
    r"""Measured shift factors :math:`\log_{10} a_T(T_k)` used as a shift law.

    Inside the table, :math:`\log_{10} a_T` is interpolated by a monotone piecewise-cubic Hermite interpolant
    in T (PCHIP, Fritsch & Carlson 1980): it passes through every node, and between nodes it stays within
    their values (a monotone table gives a monotone law). Outside the table the law continues with
    ``outside`` (by default the WLF fit of the table, Williams, Landel & Ferry 1955), anchored at the nearest
    end of the table so that it is continuous there:

    .. math:: \log_{10} a_T(T) = \log_{10} a_T(T_{end}) + L(T) - L(T_{end}),\qquad T \notin [T_1, T_n],

    and a warning says that the shift is extrapolated (not within :data:`QUIET_MARGIN_K` of the table). With
    ``T_upper`` the continuation hands over to an Arrhenius law above that temperature, continuous in value and
    slope (:meth:`materials.TemperatureShift.with_upper`; Ferry 1980, ch. 11; Dealy & Plazek 2009), as the hot
    rubber of a flash or a heated contact patch needs.

    Parameters
    ----------
    T_C : array_like
        Temperatures of the table, deg C (distinct; sorted on construction).
    log10_aT : array_like
        :math:`\log_{10} a_T` at those temperatures.
    T_ref : float, optional
        Reference temperature, deg C: the table is re-referenced so that :math:`a_T(T_{ref}) = 1`. By default
        the temperature where the table is 0 (a node, or the crossing of the interpolant).
    outside : shift law, optional
        The law that continues the table (any object with ``log10_aT``). Default: the WLF fit of the table.
    source : str
        Where the table came from (in messages).
    T_upper : float, optional
        Hand-over of the continuation to an Arrhenius law, deg C (needs a WLF continuation: the default one, a
        :class:`materials.WLF` or a :class:`materials.TemperatureShift` as ``outside``).

    Attributes
    ----------
    outside_fit : WLFFit or None
        The WLF fit used outside the table (None when ``outside`` was given).
    """

    T_C: np.ndarray
    log10_aT_nodes: np.ndarray
    T_ref_C: float | None = None
    outside: object | None = None
    source: str = "<table>"
    outside_fit: WLFFit | None = field(default=None)
    T_upper: float | None = None

    kind = "tabulated"

    def __init__(self, T_C, log10_aT, T_ref: float | None = None, outside=None, source: str = "<table>",
                 T_upper: float | None = None):
        from scipy import interpolate
        T = np.array(T_C, dtype=float).ravel()
        y = np.array(log10_aT, dtype=float).ravel()
        if T.size != y.size or T.size < 2:
            raise InputError(f"{source}: a shift-factor table needs at least two (T, log10 aT) pairs of equal "
                             f"length, got {T.size} and {y.size}")
        if not (np.all(np.isfinite(T)) and np.all(np.isfinite(y))):
            raise InputError(f"{source}: temperatures and shift factors must be finite numbers")
        if np.any(T <= -_K0):
            raise InputError(f"{source}: temperature {T.min():g} C is below absolute zero; expected deg C")
        order = np.argsort(T, kind="stable")
        T, y = T[order], y[order]
        if np.any(np.diff(T) == 0):
            i = int(np.flatnonzero(np.diff(T) == 0)[0])
            raise InputError(f"{source}: temperature {T[i]:g} C appears twice in the shift-factor table")
        if outside is not None and not callable(getattr(outside, "log10_aT", None)):
            raise InputError(f"outside: expected a shift law with log10_aT(T), got {type(outside).__name__}")
        object.__setattr__(self, "source", str(source))
        object.__setattr__(self, "outside", outside)
        object.__setattr__(self, "T_C", T)
        object.__setattr__(self, "log10_aT_nodes", y)
        object.__setattr__(self, "outside_fit", None)
        object.__setattr__(self, "_pchip", interpolate.PchipInterpolator(T, y, extrapolate=False))
        if outside is None:
            object.__setattr__(self, "outside_fit", _wlf_fit_of_table(T, y, source))
        object.__setattr__(self, "T_upper", None if T_upper is None else float(T_upper))
        object.__setattr__(self, "_continuation", self._continuation_law())
        T_ref = self._zero() if T_ref is None else float(T_ref)
        if not math.isfinite(T_ref):
            raise InputError(f"T_ref: expected a finite temperature in deg C, got {T_ref!r}")
        with ignoring(AccuracyWarning, EXTRAPOLATED_SHIFT):      # a reference outside the table is the user's
            offset = float(self._raw(np.array([T_ref]))[0])
        if offset != 0.0:
            y = y - offset
            object.__setattr__(self, "log10_aT_nodes", y)
            object.__setattr__(self, "_pchip", interpolate.PchipInterpolator(T, y, extrapolate=False))
        object.__setattr__(self, "T_ref_C", T_ref)
        for a in (self.T_C, self.log10_aT_nodes):
            a.setflags(write=False)

    def __reduce__(self):
        # rebuilt from its defining data (the interpolant is derived)
        return (_rebuild_tabulated, (self.T_C, self.log10_aT_nodes, self.T_ref_C, self.outside, self.source,
                                     self.T_upper))

    # ---------------------------------------------------------------- the law
    @property
    def T_ref(self) -> float:
        """Temperature where :math:`a_T = 1`, deg C."""
        return float(self.T_ref_C)

    @property
    def T_range(self) -> tuple[float, float]:
        """Temperatures covered by the table, deg C."""
        return float(self.T_C[0]), float(self.T_C[-1])

    @property
    def fitted_range(self) -> tuple[float, float]:
        """The temperatures the law rests on: the table's (see :func:`fitted_temperature_range`)."""
        return self.T_range

    @property
    def wlf(self) -> WLF | None:
        """The WLF law used outside the table (its fit, or ``outside`` when that is a WLF law), else None."""
        if self.outside_fit is not None:
            return self.outside_fit.wlf
        law = self.outside
        return law if isinstance(law, WLF) else getattr(law, "wlf", None)

    def log10_aT(self, T):
        """:math:`\\log_{10} a_T` at ``T`` (deg C, vectorized). Outside the table: continued, with a warning."""
        T = np.asarray(T, dtype=float)
        if not np.all(np.isfinite(T)):
            raise InputError(f"temperature: expected finite temperatures in deg C, got {T!r}")
        out = self._raw(T)
        return out if out.ndim else float(out)

    def _raw(self, T: np.ndarray) -> np.ndarray:
        lo, hi = self.T_range
        T1 = np.atleast_1d(T)
        out = np.asarray(self._pchip(T1), dtype=float)
        below, above = T1 < lo, T1 > hi
        if np.any(T1 < lo - QUIET_MARGIN_K) or np.any(T1 > hi + QUIET_MARGIN_K):
            warnings.warn(f"{self.source}: temperatures outside the shift-factor table ({lo:g} to {hi:g} C): "
                          f"a_T extrapolated with {self._outside_text()}, continuous at the table's ends",
                          AccuracyWarning, stacklevel=3)
        if below.any() or above.any():
            for mask, T_end, y_end in ((below, lo, self.log10_aT_nodes[0]), (above, hi, self.log10_aT_nodes[-1])):
                if mask.any():
                    out[mask] = y_end + self._continue(T1[mask], T_end)
        return out.reshape(np.shape(T))

    def _continuation_law(self):
        """The law that continues the table (through its differences): ``outside`` or the WLF fit, with the
        Arrhenius hand-over above ``T_upper`` when set; None without either."""
        law = self.outside if self.outside is not None else (
            None if self.outside_fit is None else self.outside_fit.wlf)
        if self.T_upper is None or law is None:
            if law is None and self.T_upper is not None:
                raise InputError(f"{self.source}: T_upper needs a WLF continuation of the table (too few points for "
                                 "a WLF fit); give outside=materials.WLF(...)")
            return law
        if isinstance(law, WLF):
            law = TemperatureShift(law)
        if not isinstance(law, TemperatureShift):
            raise InputError(f"T_upper: the continuation of the table ({type(law).__name__}) has no WLF law to hand "
                             "over from; give outside=materials.WLF(...) or a TemperatureShift")
        return law.with_upper(self.T_upper)

    def _continue(self, T, T_end):
        law = self._continuation
        if law is None:
            raise InputError(f"{self.source}: cannot extrapolate the shift factors outside {self.T_range[0]:g} to "
                             f"{self.T_range[1]:g} C (no WLF fit of the table); give outside=<shift law>")
        try:
            return np.asarray(law.log10_aT(T), dtype=float) - float(law.log10_aT(T_end))
        except InputError as exc:
            raise InputError(f"{self.source}: temperature outside the shift-factor table ({self.T_range[0]:g} to "
                             f"{self.T_range[1]:g} C) where its continuation fails: {exc}") from None

    def _outside_text(self) -> str:
        up = "" if self.T_upper is None else (f"; Arrhenius above {self.T_upper:g} C "
                                              f"(E_a = {self._continuation.upper.E_a / 1e3:.4g} kJ/mol)")
        if self.outside is not None:
            d = getattr(self.outside, "describe", None)
            # the continuation is used through its differences only: its own reference is beside the point
            text = re.sub(r"[;,] a_T = 1 at [^;]*", "", d()) if callable(d) else type(self.outside).__name__
            return text + up
        if self.outside_fit is None:
            return "nothing (no WLF fit of the table)"
        return (f"the WLF fit of the table ({self.outside_fit.wlf.describe()}, rms {self.outside_fit.rms:.2g} "
                f"decades){up}")

    def _zero(self) -> float:
        """The temperature where the table is 0: a node, or the crossing of the interpolant."""
        y = self.log10_aT_nodes
        zero = np.flatnonzero(y == 0.0)
        if zero.size:
            return float(self.T_C[zero[0]])
        cross = np.flatnonzero(np.sign(y[:-1]) != np.sign(y[1:]))
        if cross.size == 0:
            raise InputError(f"{self.source}: the shift factors are never 1 (log10 aT never 0) in the table; give "
                             "T_ref= (the reference temperature of the table)")
        i = int(cross[0])
        from scipy.optimize import brentq
        return float(brentq(lambda t: float(self._pchip(t)), self.T_C[i], self.T_C[i + 1], xtol=1e-12))

    def with_T_ref(self, T_ref: float) -> "TabulatedShift":
        """The same law with :math:`a_T(T_{ref}) = 1` at another temperature."""
        return TabulatedShift(self.T_C, self.log10_aT_nodes, T_ref=float(T_ref), outside=self.outside,
                              source=self.source, T_upper=self.T_upper)

    def describe(self) -> str:
        """One line: the table and its continuation."""
        lo, hi = self.T_range
        return (f"tabulated a_T ({self.T_C.size} temperatures, {lo:g} to {hi:g} C, a_T = 1 at {self.T_ref:.4g} C); "
                f"outside: {self._outside_text()}")

    def __repr__(self) -> str:
        return f"TabulatedShift({self.describe()})"


@dataclass(frozen=True)
class SingleTemperature:
    """The 'law' of a master curve known at one temperature only: :math:`a_T = 1` there, undefined elsewhere.

    ``log10_aT(T)`` is 0 at ``T_ref`` (within ``tol`` K) and raises :class:`InputError` at any other
    temperature, so that a material without a shift law is never used at a temperature it does not describe.
    """

    T_ref: float
    tol: float = 1e-6
    source: str = ""

    kind = "single temperature"

    def log10_aT(self, T):
        """0 at ``T_ref``; :class:`InputError` elsewhere."""
        T = np.asarray(T, dtype=float)
        if not np.all(np.isfinite(T)) or np.any(np.abs(T - self.T_ref) > self.tol):
            bad = T[~(np.abs(T - self.T_ref) <= self.tol)].ravel()
            raise InputError(f"{self.source or 'master curve'}: known at T_ref = {self.T_ref:g} C only (no shift "
                             f"law given), asked at T = {bad[0]:g} C; give wlf= or shift= (e.g. "
                             "materials.read_shift_factors(...)) to use it at other temperatures")
        out = np.zeros(T.shape)
        return out if out.ndim else 0.0

    def with_T_ref(self, T_ref: float) -> "SingleTemperature":
        """Itself when ``T_ref`` is its temperature (within ``tol``); :class:`InputError` at any other."""
        if abs(float(T_ref) - self.T_ref) > self.tol:
            raise InputError(f"T_ref: a master curve known at {self.T_ref:g} C only cannot be referred to {T_ref} C")
        return self

    def describe(self) -> str:
        """One line: the only temperature at which the master curve is usable (no shift law)."""
        return f"single temperature: usable at T = {self.T_ref:g} C only (no shift law)"


#: The shift-law classes of this package (any object with ``log10_aT`` and ``T_ref`` works too; see
#: :func:`as_shift_law`, defined with the closed-form laws in :mod:`materials.laws`).
SHIFT_LAW_TYPES = (WLF, Arrhenius, TemperatureShift, TabulatedShift, SingleTemperature)


# ==================================================================================================== reader

def read_shift_factors(path, *, columns=None, units=None, T_ref: float | None = None, outside=None,
                       encoding: str | None = None, T_upper: float | None = None) -> TabulatedShift:
    r"""Read a table of shift factors (temperature and :math:`a_T` or :math:`\log_{10} a_T`) as a shift law.

    The file is a delimited table (comma, tab, semicolon or white space), with or without a names row and a
    units row; pyvisco's ``*__shift_factors.csv`` (``T, log_aT`` then ``C, -``) is read as is.

    * The temperature column is named ``T``, ``T_C``, ``T_K``, ``Temp`` or ``Temperature`` (unit from the units
      row, the name or ``units={'T': 'K'}``; deg C by default).
    * The shift column is :math:`\log_{10} a_T` when named ``log_aT``, ``log10_aT``, ``logaT``...,
      :math:`\ln a_T` when named ``ln_aT``, and :math:`a_T` when named ``aT`` or ``a_T``.
    * A header-less two-column table is read as (T in deg C, shift) with the shift's kind recognised from the
      values: any value <= 0 means :math:`\log_{10} a_T` (:math:`a_T` is positive); values spanning more than
      four decades with a 1 among them mean :math:`a_T`; anything else is ambiguous and refused (name the
      columns).

    Parameters
    ----------
    path : str or Path
    columns : sequence or mapping, optional
        Names of the file's columns in order, e.g. ``("T_C", "log10_aT")``, ``("T_K", "aT")``,
        ``("T_C", "ln_aT")``; or a mapping ``{"T": <column name or index>, "log10_aT": <...>}``.
    units : mapping, optional
        ``{"T": "C" or "K"}``.
    T_ref : float, optional
        Reference temperature (deg C) of the returned law; default the temperature where the table is 0.
    outside : shift law, optional
        Continuation outside the table (default: the WLF fit of the table).
    encoding : str, optional
    T_upper : float, optional
        Hand-over of the continuation to an Arrhenius law above this temperature, deg C (see
        :class:`TabulatedShift`).

    Returns
    -------
    TabulatedShift

    Raises
    ------
    InputError
        Missing or ambiguous columns, non-positive :math:`a_T`, repeated temperatures, temperatures below
        absolute zero or looking like kelvin, unknown units (naming the file, line and column).
    """
    table = read_table(path, encoding=encoding)
    units = normalise_units(units)
    jT, T_unit_name, kind, jS, from_option = _shift_columns(table, columns, _role_of)
    where_T = f"{table.path}, column {table.label(jT)}"
    if "T" in units:
        T_unit, trusted = units["T"], True
    elif from_option and T_unit_name is not None:
        T_unit, trusted = T_unit_name, True
    elif table.units[jT] is not None:
        T_unit, trusted = table.units[jT], False
    else:
        T_unit, trusted = (T_unit_name or "C"), False
    T = to_celsius(table.data[:, jT], unit_factor("T", T_unit, where=where_T))
    raw = table.data[:, jS]
    where_S = f"{table.path}, column {table.label(jS)}"
    for name, v, where in (("temperature", T, where_T), ("shift factor", raw, where_S)):
        bad = ~np.isfinite(v)
        if bad.any():
            i = int(np.flatnonzero(bad)[0])
            raise InputError(f"{where}, line {int(table.lines[i])}: expected a {name}, got an empty or NaN cell")
    check_temperatures(T, where=where_T, lines=table.lines, trusted=trusted)
    if kind is None:
        kind = _kind_from_values(raw, where_S)
    if kind == "aT":
        if np.any(raw <= 0):
            i = int(np.flatnonzero(raw <= 0)[0])
            raise InputError(f"{where_S}, line {int(table.lines[i])}: a_T must be > 0, got {raw[i]:g} (a log10 a_T "
                             "column? name it log10_aT)")
        y = np.log10(raw)
    elif kind == "ln_aT":
        y = raw / math.log(10.0)
    else:
        y = raw
    if np.unique(T).size != T.size:
        vals, counts = np.unique(T, return_counts=True)
        i = int(np.flatnonzero(T == vals[counts > 1][0])[1])
        raise InputError(f"{where_T}, line {int(table.lines[i])}: temperature {T[i]:g} C appears twice")
    order = np.argsort(T)
    rises = np.flatnonzero(np.diff(y[order]) > 0.05)
    if rises.size:
        pairs = ", ".join(f"{T[order][i]:g}->{T[order][i + 1]:g} C" for i in rises[:4])
        warnings.warn(f"{table.path}: log10 a_T increases with temperature between {pairs} (a_T normally "
                      "decreases as the temperature rises); check the table", PhysicsWarning, stacklevel=2)
    return TabulatedShift(T, y, T_ref=T_ref, outside=outside, source=str(table.path), T_upper=T_upper)


# ==================================================================================================== hot rubber

@doi("isbn:978-0-471-04894-7", DEALY_PLAZEK_2009)
def with_arrhenius_above(obj, T_upper: float | None = None, *, E_a: float | None = None):
    r"""``obj`` with its shift law handing over to an Arrhenius law above ``T_upper`` (or where WLF's apparent
    activation energy is ``E_a``), continuous in :math:`\log_{10} a_T` and its slope.

    WLF describes the shifts from the glass transition to about T_g + 100 K; above, they follow an Arrhenius law
    (Ferry 1980, ch. 11; Dealy & Plazek 2009). A flash temperature or a heated contact patch takes tread rubber
    there. The activation energy of the upper branch is the WLF law's apparent one at the hand-over
    (:func:`materials.wlf_activation_energy`).

    Parameters
    ----------
    obj : shift law or material
        A :class:`materials.WLF`, :class:`materials.TemperatureShift` (or :class:`materials.WLFArrhenius`),
        :class:`TabulatedShift` (its continuation beyond the table hands over), or a material holding one of
        these as ``shift`` (:class:`materials.MasterCurve`) or ``wlf`` (:class:`materials.Prony`).
    T_upper : float, optional
        Hand-over temperature, deg C.
    E_a : float, optional
        Activation energy above the hand-over, J/mol (instead of ``T_upper``).

    Returns
    -------
    The same kind of object, with the hand-over.

    Raises
    ------
    InputError
        A law without a WLF part, both or neither of ``T_upper`` and ``E_a``, a hand-over the WLF law cannot
        take (at or below its singularity or T_g; an ``E_a`` it never reaches).
    """
    import dataclasses

    if isinstance(obj, WLF):
        return TemperatureShift(obj).with_upper(T_upper, E_a=E_a)
    if isinstance(obj, TemperatureShift):
        return obj.with_upper(T_upper, E_a=E_a)
    if isinstance(obj, TabulatedShift):
        if (T_upper is None) == (E_a is None):
            raise InputError("with_arrhenius_above: give T_upper or E_a")
        if T_upper is None:
            wlf = obj.wlf
            if wlf is None:
                raise InputError(f"{obj.source}: the continuation of the table has no WLF law; give T_upper")
            T_upper = _upper_temperature(wlf, float(E_a))
        return TabulatedShift(obj.T_C, obj.log10_aT_nodes, T_ref=obj.T_ref, outside=obj.outside, source=obj.source,
                              T_upper=float(T_upper))
    for attr in ("shift", "wlf"):
        law = getattr(obj, attr, None)
        if law is not None and dataclasses.is_dataclass(obj) and attr in {f.name for f in dataclasses.fields(obj)}:
            return dataclasses.replace(obj, **{attr: with_arrhenius_above(law, T_upper, E_a=E_a)})
    raise InputError(f"with_arrhenius_above: expected a WLF-based shift law or a material holding one, got "
                     f"{type(obj).__name__}")


def fitted_temperature_range(material) -> tuple[float, float] | None:
    """The temperatures (deg C) where the shift law of ``material`` was fitted, or None when unknown.

    The isotherms of a :class:`materials.MasterCurve` built from DMA data (``temperature_range``), the table of a
    :class:`TabulatedShift`, or the ``fitted_range`` a :class:`materials.TemperatureShift` carries (set by
    ``WLFFit.law`` and given by the user for constants from a data sheet). A law given by constants alone (a bare
    :class:`materials.WLF`) has none.
    """
    rng = getattr(material, "temperature_range", None)
    if rng is not None and not callable(rng):
        return float(rng[0]), float(rng[1])
    for law in (material, getattr(material, "shift", None), getattr(material, "wlf", None)):
        rng = getattr(law, "fitted_range", None)
        if rng is not None:
            return float(rng[0]), float(rng[1])
    return None


def extrapolated_shift_note(material, T_min: float, T_max: float) -> str | None:
    r"""The note a friction result carries when its rubber temperatures leave the range where the shift law was
    fitted; None when they stay inside it (or the range is unknown).

    The rule: the coldest and hottest temperatures at which the rubber's modulus was evaluated (the background
    temperature, plus the flash temperature at every length scale and the heating along the contact patch where
    those effects are on) are compared with :func:`fitted_temperature_range`; more than :data:`QUIET_MARGIN_K`
    outside it, :math:`a_T` there comes from the law's continuation, which the note names. The text depends on the
    material only (not on the temperatures reached, which the result carries), so that a fit that calls the
    engine many times collects one note.

    Parameters
    ----------
    material : material or shift law
    T_min, T_max : float
        Coldest and hottest rubber temperatures of the calculation, deg C.
    """
    rng = fitted_temperature_range(material)
    if rng is None:
        return None
    lo, hi = rng
    cold, hot = T_min < lo - QUIET_MARGIN_K, T_max > hi + QUIET_MARGIN_K
    if not (cold or hot):
        return None
    side = "above and below" if cold and hot else ("above" if hot else "below")
    return (f"{SHIFT_RANGE_NOTE} ({lo:g} to {hi:g} C): the rubber is evaluated {side} it (background, flash and "
            f"patch temperatures); a_T there is {_continuation_text(material, hot)}")


def _continuation_text(material, hot: bool) -> str:
    """How a material's shift law continues beyond its fitted range (for :func:`extrapolated_shift_note`)."""
    law = material
    if not isinstance(material, SHIFT_LAW_TYPES):
        law = getattr(material, "shift", None) or getattr(material, "wlf", None) or material
    if isinstance(law, TabulatedShift):
        return f"continued with {law._outside_text()}"
    if isinstance(law, TemperatureShift) and hot:
        if law.upper is not None:
            return (f"WLF up to {law.upper.T_g:g} C, Arrhenius above (E_a = {law.upper.E_a / 1e3:.4g} kJ/mol, "
                    "continuous in log a_T and slope)")
        return ("the WLF law continued, beyond the about T_g + 100 K up to which WLF holds (Ferry 1980): "
                "materials.with_arrhenius_above sets the Arrhenius hand-over")
    d = getattr(law, "describe", None)
    return f"the law's own continuation ({d() if callable(d) else type(law).__name__})"


# ==================================================================================================== helpers

def _rebuild_tabulated(T, y, T_ref, outside, source, T_upper=None):
    return TabulatedShift(T, y, T_ref=T_ref, outside=outside, source=source, T_upper=T_upper)


def _wlf_fit_of_table(T, y, source) -> WLFFit | None:
    """The WLF fit of a table (None when it has too few points or no WLF law fits)."""
    if T.size < 3:
        return None
    i0 = T.size // 2
    try:
        with ignoring(AccuracyWarning, UNDETERMINED_COVARIANCE):   # only the continuation is used, not its errors
            fit = fit_wlf(T, y - y[i0], float(T[i0]))
    except InputError:
        return None
    return fit


_LOG10_NAMES = ("log10at", "logat", "lgat", "log10(at)", "log(at)", "loga", "log10a", "logshift", "log10shift",
                "logshiftfactor", "log10shiftfactor")
_LN_NAMES = ("lnat", "ln(at)", "lna")
_LINEAR_NAMES = ("at", "shiftfactor")


def _shift_columns(table, columns, role_of):
    """(T column, T unit from its name, shift kind or None, shift column, named by the user)."""
    def kind_of(name):
        n = name.strip().lower().replace(" ", "").replace("_", "").replace("-", "")
        if n in _LOG10_NAMES:
            return "log10_aT"
        if n in _LN_NAMES:
            return "ln_aT"
        if n in _LINEAR_NAMES:
            return "aT"
        return None

    if columns is not None:
        if isinstance(columns, Mapping):
            jT = jS = None
            T_unit = kind = None
            for key, ref in columns.items():
                role, unit = role_of(str(key))
                j = _index(table, ref)
                if role == "T":
                    jT, T_unit = j, unit
                elif kind_of(str(key)):
                    jS, kind = j, kind_of(str(key))
                else:
                    raise InputError(f"columns: unknown key {key!r} (expected T, T_C or T_K and log10_aT, aT or "
                                     "ln_aT)")
            if jT is None or jS is None:
                raise InputError("columns: give both the temperature and the shift column, e.g. "
                                 "{'T_C': 'Temp', 'log10_aT': 'shift'}")
            return jT, T_unit, kind, jS, True
        names = list(columns)
        if len(names) > table.n_columns:
            raise InputError(f"columns: {len(names)} names for a table of {table.n_columns} columns")
        jT = jS = None
        T_unit = kind = None
        for j, name in enumerate(names):
            if name is None or str(name).strip() in ("", "-"):
                continue
            role, unit = role_of(str(name))
            if role == "T":
                jT, T_unit = j, unit
            elif kind_of(str(name)):
                jS, kind = j, kind_of(str(name))
            else:
                raise InputError(f"columns[{j}]: unknown column name {name!r} (expected T_C or T_K, and log10_aT, "
                                 "aT or ln_aT)")
        if jT is None or jS is None:
            raise InputError("columns: name the temperature and the shift column, e.g. ('T_C', 'log10_aT')")
        return jT, T_unit, kind, jS, True
    if table.names is not None:
        jT = T_unit = None
        for j, name in enumerate(table.names):
            role, unit = role_of(name)
            if role == "T":
                jT, T_unit = j, unit
                break
        shift_cols = [(j, kind_of(n)) for j, n in enumerate(table.names) if j != jT and kind_of(n)]
        if jT is not None and shift_cols:
            return jT, T_unit, shift_cols[0][1], shift_cols[0][0], False
        if table.n_columns == 2:
            jT = 0 if jT is None else jT
            return jT, T_unit, None, 1 - jT, False
        raise InputError(f"{table.path}: expected a temperature column (T, T_C) and a shift column (log10_aT, aT); "
                         f"found {', '.join(table.names)}; name them with columns=('T_C', 'log10_aT')")
    if table.n_columns != 2:
        raise InputError(f"{table.path}: a header-less shift-factor table must have two columns (T, shift), found "
                         f"{table.n_columns}; name them with columns=[...]")
    return 0, None, None, 1, False


def _index(table, ref) -> int:
    return _column_index(table, ref)


def _kind_from_values(v, where) -> str:
    if np.any(v <= 0):
        return "log10_aT"
    span = float(np.log10(v.max() / v.min()))
    if np.any(v == 1.0) and span > 4:
        return "aT"
    raise InputError(f"{where}: cannot tell whether the column holds a_T or log10 a_T (all values positive, "
                     f"{v.min():g} to {v.max():g}); name the columns, e.g. columns=('T_C', 'log10_aT') or "
                     "columns=('T_C', 'aT')")
