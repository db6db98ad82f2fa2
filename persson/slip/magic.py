r"""Pacejka's Magic Formula on mu(slip): the curve, its identification from a few points, and its fits.

Friction-speed laws on mu(V) are in :mod:`persson.slip.speedlaws`.

Magic Formula (Pacejka & Bakker 1992; Pacejka, *Tire and Vehicle Dynamics*, ch. 4):

* B, C, D, E form: :math:`\mu(s) = D\sin\{C\arctan[Bs - E(Bs - \arctan Bs)]\}`
  (D peak value, C shape factor, B stiffness factor, E curvature factor; initial slope BCD);
* the simple form used with road-friction trailers: :math:`\mu(s) = a\sin(b\arctan(cs)) + d`
  (the B, C, D form with E = 0 plus an offset d).

Peak mu, slip at the peak and locked-wheel mu (:math:`\mu(s=1)`) are computed from the fitted curve on
:math:`0 \le s \le 1`, with standard uncertainties by linear propagation of the parameter covariance. A peak can
be declared: :func:`magic_formula_from_peak` identifies the curve from the peak and one or two locked-wheel values
(the peak's value and position are two conditions), and ``fit_magic_formula(..., peak=(s_p, mu_p))`` fits a full
curve with the peak held there.

Every fit uses :func:`scipy.optimize.curve_fit` (several starting points, the best kept) and returns a frozen
:class:`FitResult` with the parameters, their standard uncertainties and the covariance. Without ``sigma`` the
covariance is scaled by the residual variance (``absolute_sigma=False``); with ``sigma`` it is absolute.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .._checks import finite_array, number
from ..errors import InputError
from .fitting import FitResult, _fit, _propagate, _xy
from .peaks import _curve_peak
from .references import MAGIC_FORMULA, PACEJKA_BOOK

__all__ = ["magic_formula", "magic_formula_simple", "MagicFormula", "SimpleMagicFormula",
           "magic_formula_from_points", "magic_formula_peak_B", "magic_formula_from_peak", "MagicFormulaFit",
           "fit_magic_formula", "PACEJKA_TYPICAL"]


# =========================================================================================================
# Magic Formula
# =========================================================================================================
@doi(MAGIC_FORMULA, PACEJKA_BOOK)
def magic_formula(slip, B, C, D, E=0.0):
    r"""Pacejka's Magic Formula :math:`D\sin\{C\arctan[Bs - E(Bs - \arctan Bs)]\}` (vectorised)."""
    x = B * np.asarray(slip, dtype=float)
    return D * np.sin(C * np.arctan(x - E * (x - np.arctan(x))))


@doi(MAGIC_FORMULA, PACEJKA_BOOK)
def magic_formula_simple(slip, a, b, c, d=0.0):
    r"""Simple Magic Formula of road-friction trailers :math:`a\sin(b\arctan(cs)) + d` (vectorised)."""
    return a * np.sin(b * np.arctan(c * np.asarray(slip, dtype=float))) + d


@dataclass(frozen=True)
class _CurveCharacteristics:
    def __call__(self, slip):  # pragma: no cover - overridden
        raise NotImplementedError

    @property
    def peak_mu(self) -> float:
        """Largest mu on 0 <= s <= 1."""
        return _curve_peak(self)[0]

    @property
    def slip_at_peak(self) -> float:
        """Slip of the largest mu on 0 <= s <= 1 (1.0 when the curve still rises at s = 1)."""
        return _curve_peak(self)[1]

    @property
    def locked_mu(self) -> float:
        """Locked-wheel (pure sliding) mu, i.e. mu at s = 1."""
        return float(self(1.0))


@doi(MAGIC_FORMULA, PACEJKA_BOOK)
@dataclass(frozen=True)
class MagicFormula(_CurveCharacteristics):
    """The B, C, D, E Magic Formula as an object: call it with slips; ``peak_mu``, ``slip_at_peak``, ``locked_mu``."""

    B: float
    C: float
    D: float
    E: float = 0.0

    def __call__(self, slip):
        return magic_formula(slip, self.B, self.C, self.D, self.E)

    @property
    def initial_slope(self) -> float:
        """d mu / d s at s = 0: B C D."""
        return self.B * self.C * self.D


@doi(MAGIC_FORMULA, PACEJKA_BOOK)
@dataclass(frozen=True)
class SimpleMagicFormula(_CurveCharacteristics):
    """The simple form a sin(b atan(c s)) + d as an object."""

    a: float
    b: float
    c: float
    d: float = 0.0

    def __call__(self, slip):
        return magic_formula_simple(slip, self.a, self.b, self.c, self.d)

    @property
    def initial_slope(self) -> float:
        """d mu / d s at s = 0: a b c."""
        return self.a * self.b * self.c


@doi(MAGIC_FORMULA, PACEJKA_BOOK)
def magic_formula_from_points(slip, mu, *, E: float = 0.0) -> MagicFormula:
    r"""Identify B, C, D of the Magic Formula (E given, 0 by default) from three (slip, mu) points.

    Solves :math:`D\sin\{C\arctan[Bs_i - E(Bs_i - \arctan Bs_i)]\} = \mu_i`, i = 1..3, exactly (three equations,
    three unknowns) by a multi-start least-squares solve. Typical choice: a point on the rising branch, one near
    the peak and the locked-wheel point (s = 1).

    Raises
    ------
    InputError
        Not three points, slips outside (0, 1] or repeated, mu <= 0, or no Magic Formula through the points.
    """
    from scipy.optimize import least_squares

    s = finite_array(slip, "slip").ravel()
    m = finite_array(mu, "mu").ravel()
    if s.size != 3 or m.size != 3:
        raise InputError(f"slip, mu: expected exactly three points, got {s.size} and {m.size}")
    if np.any((s <= 0) | (s > 1)):
        raise InputError("slip: expected three slip ratios in (0, 1]")
    if np.unique(s).size != 3:
        raise InputError("slip: the three slip ratios must differ")
    if np.any(m <= 0):
        raise InputError("mu: expected three friction values > 0")
    E = number(E, "E")
    order = np.argsort(s)
    s, m = s[order], m[order]

    def res(p):
        B, C, D = np.exp(p)
        return (magic_formula(s, B, C, D, E) - m) / m

    best = None
    mmax = float(m.max())
    for B0 in (3.0, 10.0, 30.0, 100.0):
        for C0 in (0.8, 1.3, 1.7, 2.2):
            for D0 in (mmax, 1.2 * mmax):
                r = least_squares(res, np.log([B0, C0, D0]), method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                                  max_nfev=4000)
                if best is None or r.cost < best.cost:
                    best = r
        if best is not None and best.cost < 1e-24:
            break
    if best is None or not np.max(np.abs(res(best.x))) < 1e-8:
        raise InputError(f"slip, mu: no Magic Formula (E = {E:g}) passes through the points "
                         f"{list(zip(s.round(6), m.round(6)))}")
    B, C, D = (float(v) for v in np.exp(best.x))
    return MagicFormula(B=B, C=C, D=D, E=E)


def magic_formula_peak_B(peak_slip: float, C: float, E: float = 0.0) -> float:
    r"""The B that puts the maximum of :math:`D\sin\{C\arctan[Bs - E(Bs - \arctan Bs)]\}` at ``peak_slip``.

    The sine peaks where :math:`C\arctan\phi = \pi/2`, :math:`\phi(x) = x - E(x - \arctan x)`, i.e.
    :math:`\phi(B s_p) = \tan(\pi/(2C))` (needs C > 1; :math:`\phi` increases for E < 1, so the root is unique:
    for E = 0, :math:`B = \tan(\pi/2C)/s_p`; Pacejka, Tire and Vehicle Dynamics, ch. 4, the peak and the curvature
    factor).
    """
    from scipy.optimize import brentq

    sp = number(peak_slip, "peak_slip")
    C = number(C, "C")
    E = number(E, "E")
    if not 0 < sp <= 1:
        raise InputError(f"peak_slip: expected a slip ratio in (0, 1], got {sp:g}")
    if not C > 1:
        raise InputError(f"C: a Magic Formula with a peak needs C > 1, got {C:g}")
    if not E < 1:
        raise InputError(f"E: expected E < 1 (phi must increase), got {E:g}")
    t = math.tan(math.pi / (2.0 * C))
    if E == 0:
        return t / sp

    def phi(x):
        return x - E * (x - math.atan(x)) - t

    hi = 2.0 * (t + abs(E) * math.pi / 2.0) / (1.0 - E) + 1.0
    return brentq(phi, 0.0, hi, xtol=1e-15, rtol=1e-15) / sp


@doi(MAGIC_FORMULA, PACEJKA_BOOK)
def magic_formula_from_peak(peak_slip, peak_mu, slip, mu, *, E=None, sigma=None,
                            peak_slip_std: float = 0.0) -> "MagicFormulaFit":
    r"""Magic Formula identified from a declared peak and one or two further points (locked-wheel values).

    The peak point gives two conditions, its value (:math:`D = \mu_{peak}`) and its position
    (:func:`magic_formula_peak_B`); each further point :math:`(s_i, \mu_i)` one more:

    * one point: B, C, D with E given (0 by default): the usual three-point identification from the peak and
      the locked value (e.g. peak 1.156 at 11 %, 0.679 at 93 %);
    * two points: B, C, D and E.

    Parameters
    ----------
    peak_slip, peak_mu : float
        The declared peak: slip ratio in (0, 1) and its friction value (> 0).
    slip, mu : float or array_like
        One or two further points, slips in (peak_slip, 1] (the falling branch) or below the peak, mu > 0 and below
        ``peak_mu``.
    E : float, optional
        Curvature factor held (one point only; default 0).
    sigma : float or array_like, optional
        Standard uncertainties of the friction values: one value for all, or one per value in the order
        (peak_mu, mu_1[, mu_2]). With ``peak_slip_std`` they give the standard uncertainties of B, C, D, E and of the
        curve's characteristics, by linear propagation through the identification (central differences).
        Without them the uncertainties are 0 and a note says so.
    peak_slip_std : float
        Standard uncertainty of the declared peak slip.

    Returns
    -------
    MagicFormulaFit
        ``law = "magic_formula"``, exact through the points (``rms`` 0, ``dof`` 0); ``slip_at_peak`` and
        ``peak_mu`` are the declared ones.

    Raises
    ------
    InputError
        Bad points, or no Magic Formula with a peak (C > 1, E < 1) through them.
    """
    sp = number(peak_slip, "peak_slip")
    mp = number(peak_mu, "peak_mu")
    if not 0 < sp < 1:
        raise InputError(f"peak_slip: expected a slip ratio in (0, 1), got {sp:g}")
    if mp <= 0:
        raise InputError(f"peak_mu: expected a friction value > 0, got {mp:g}")
    xs = finite_array(slip, "slip").ravel()
    ys = finite_array(mu, "mu").ravel()
    if xs.size != ys.size or xs.size not in (1, 2):
        raise InputError(f"slip, mu: expected one or two further points, got {xs.size} slips and {ys.size} values")
    if np.any((xs <= 0) | (xs > 1)) or np.any(np.isclose(xs, sp)):
        raise InputError("slip: expected slip ratios in (0, 1], different from the peak slip")
    if np.any((ys <= 0) | (ys >= mp)):
        raise InputError("mu: expected values > 0 and below the declared peak")
    if xs.size == 2 and E is not None:
        raise InputError("E: with two further points E is identified; give E only with one point")
    if xs.size == 2 and np.isclose(xs[0], xs[1]):
        raise InputError("slip: the two further points must differ")
    E0 = 0.0 if E is None else number(E, "E")
    solve_E = xs.size == 2
    inputs = np.concatenate([[sp, mp], ys])
    sig = None
    if sigma is not None:
        sg = finite_array(sigma, "sigma").ravel()
        if sg.size not in (1, 1 + ys.size) or np.any(sg < 0):
            raise InputError(f"sigma: expected one value or {1 + ys.size} values >= 0 (peak_mu, then the points)")
        sig = np.broadcast_to(sg, (1 + ys.size,)).astype(float)
    sps = number(peak_slip_std, "peak_slip_std")
    if sps < 0:
        raise InputError(f"peak_slip_std: expected a value >= 0, got {sps:g}")

    def identify(inp):
        return _identify_peak(inp[0], inp[1], xs, inp[2:], E0, solve_E)

    B, C, D, Ev = identify(inputs)
    values = np.array([B, C, D, Ev])
    var_in = np.concatenate([[sps**2], (sig**2 if sig is not None else np.zeros(1 + ys.size))])
    cov = np.zeros((4, 4))
    if np.any(var_in > 0):
        J = np.zeros((4, inputs.size))
        for i in np.flatnonzero(var_in > 0):
            h = 1e-6 * max(abs(inputs[i]), 1e-3)
            up, dn = inputs.copy(), inputs.copy()
            up[i] += h
            dn[i] -= h
            J[:, i] = (np.array(identify(up)) - np.array(identify(dn))) / (2 * h)
        cov = J @ np.diag(var_in) @ J.T
    notes = () if np.any(var_in > 0) else ("exact identification: give sigma= (and peak_slip_std=) for the "
                                           "uncertainties",)
    stderr = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    func = magic_formula
    fixed = () if solve_E else ("E",)
    x_all = np.concatenate([[sp], xs])
    y_all = np.concatenate([[mp], ys])
    # curve characteristics: the peak is the declared one; its uncertainty is that of the inputs
    lk, lk_std = _propagate(lambda v: func(1.0, *v), values, cov)
    return MagicFormulaFit(law="magic_formula", names=("B", "C", "D", "E"), values=values, stderr=stderr,
                           covariance=cov, fixed=fixed, x=x_all, y=y_all, sigma=sig, rms=0.0, dof=0, notes=notes,
                           citations=(MAGIC_FORMULA, PACEJKA_BOOK), func=func, peak_mu=mp,
                           peak_mu_std=float(sig[0]) if sig is not None else 0.0, slip_at_peak=sp,
                           slip_at_peak_std=sps, locked_mu=float(lk), locked_mu_std=lk_std)


def _identify_peak(sp, mp, xs, ys, E0, solve_E):
    """(B, C, D, E) through the peak (sp, mp) with zero slope there and the points (xs, ys)."""
    from scipy.optimize import brentq, least_squares

    def curve(C, E, x):
        B = magic_formula_peak_B(sp, C, E)
        return magic_formula(x, B, C, mp, E)

    if not solve_E:
        def f(C):
            return float(curve(C, E0, xs[0])) - ys[0]

        grid = np.linspace(1.0 + 1e-6, 2.0 - 1e-9, 400) if xs[0] > sp else np.linspace(1.0 + 1e-6, 3.0, 400)
        vals = np.array([f(c) for c in grid])
        idx = np.flatnonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) <= 0)
        if idx.size == 0:
            raise InputError(f"slip, mu: no Magic Formula (E = {E0:g}) with its peak at ({sp:g}, {mp:g}) passes "
                             f"through ({xs[0]:g}, {ys[0]:g})")
        j = int(idx[0])
        C = brentq(f, grid[j], grid[j + 1], xtol=1e-14, rtol=1e-14)
        return magic_formula_peak_B(sp, C, E0), C, mp, E0

    def res(p):
        C, E = p
        return (curve(C, E, xs) - ys) / ys

    best = None
    for C0 in (1.2, 1.5, 1.7, 1.9):
        for Ei in (-1.0, 0.0, 0.5):
            try:
                r = least_squares(res, [C0, Ei], bounds=([1.0 + 1e-6, -20.0], [3.0, 1.0 - 1e-6]), xtol=1e-15,
                                  ftol=1e-15, gtol=1e-15, max_nfev=2000)
            except (ValueError, InputError):
                continue
            if best is None or r.cost < best.cost:
                best = r
    if best is None or not np.max(np.abs(res(best.x))) < 1e-9:
        raise InputError(f"slip, mu: no Magic Formula with its peak at ({sp:g}, {mp:g}) passes through "
                         f"{list(zip(np.round(xs, 6), np.round(ys, 6)))}")
    C, E = (float(v) for v in best.x)
    return magic_formula_peak_B(sp, C, E), C, mp, E


def _fit_with_peak(x, y, sig, peak, fixed, p0):
    """Magic Formula fit with the peak held at the declared point (see fit_magic_formula)."""
    try:
        sp, mp = (float(v) for v in peak)
    except (TypeError, ValueError):
        raise InputError(f"peak: expected (slip_at_peak, peak_mu), got {peak!r}") from None
    sp = number(sp, "peak[0]")
    mp = number(mp, "peak[1]")
    if not 0 < sp < 1 or mp <= 0:
        raise InputError(f"peak: expected a slip in (0, 1) and a value > 0, got ({sp:g}, {mp:g})")
    fixed = dict(fixed or {})
    unknown = sorted(set(fixed) - {"E"})
    if unknown:
        raise InputError(f"fixed: with a declared peak only E can be fixed, got {unknown}")

    def func(xx, C, E):
        return magic_formula(xx, magic_formula_peak_B(sp, C, E), C, mp, E)

    starts = [dict(C=c, E=e) for c in (1.3, 1.6, 1.9) for e in (0.0, -0.5, 0.5)]
    if p0:
        starts.insert(0, {**starts[0], **{k: number(v, f"p0[{k!r}]") for k, v in p0.items() if k in ("C", "E")}})
    bounds = {"C": (1.0 + 1e-6, 3.0), "E": (-20.0, 1.0 - 1e-6)}
    parts = _fit("magic_formula", func, ("C", "E"), bounds, x, y, sig, fixed, starts, (MAGIC_FORMULA, PACEJKA_BOOK))
    C, E = parts["values"]
    covCE = parts["covariance"]
    B = magic_formula_peak_B(sp, C, E)
    J = np.zeros((4, 2))  # d(B, C, D, E) / d(C, E)
    for i, h in enumerate((1e-6, 1e-6)):
        up = [C, E]
        dn = [C, E]
        up[i] += h
        dn[i] -= h
        J[0, i] = (magic_formula_peak_B(sp, *up) - magic_formula_peak_B(sp, *dn)) / (2 * h)
    J[1, 0] = 1.0
    J[3, 1] = 1.0
    cov = J @ covCE @ J.T
    values = np.array([B, C, mp, E])
    stderr = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    lk, lk_std = _propagate(lambda v: magic_formula(1.0, *v), values, cov)
    notes = tuple(parts["notes"]) + (f"peak held at the declared ({sp:g}, {mp:g})",)
    return MagicFormulaFit(law="magic_formula", names=("B", "C", "D", "E"), values=values, stderr=stderr,
                           covariance=cov, fixed=("D",) + tuple(parts["fixed"]), x=x, y=y, sigma=sig,
                           rms=parts["rms"], dof=parts["dof"], notes=notes, citations=parts["citations"],
                           func=magic_formula, peak_mu=mp, peak_mu_std=0.0, slip_at_peak=sp, slip_at_peak_std=0.0,
                           locked_mu=float(lk), locked_mu_std=lk_std)


@dataclass(frozen=True, eq=False)
class MagicFormulaFit(FitResult):
    """A Magic Formula fit with the curve characteristics and their standard uncertainties.

    Attributes (in addition to :class:`FitResult`)
    ----------------------------------------------
    peak_mu, peak_mu_std : float
        Largest mu of the fitted curve on 0 <= s <= 1.
    slip_at_peak, slip_at_peak_std : float
        Its slip ratio.
    locked_mu, locked_mu_std : float
        mu at s = 1 (locked wheel).
    """

    peak_mu: float = float("nan")
    peak_mu_std: float = float("nan")
    slip_at_peak: float = float("nan")
    slip_at_peak_std: float = float("nan")
    locked_mu: float = float("nan")
    locked_mu_std: float = float("nan")

    @property
    def formula(self):
        """The fitted curve as a :class:`MagicFormula` or :class:`SimpleMagicFormula`."""
        p = self.params
        return MagicFormula(**p) if self.law == "magic_formula" else SimpleMagicFormula(**p)


# =========================================================================================================
# Magic Formula fits
# =========================================================================================================
_MF_BOUNDS = {"B": (1e-3, 1e4), "C": (1e-3, 3.0), "D": (1e-6, 10.0), "E": (-20.0, 1.0)}


_MFS_BOUNDS = {"a": (1e-6, 10.0), "b": (1e-3, 3.0), "c": (1e-3, 1e4), "d": (-5.0, 5.0)}


@doi(MAGIC_FORMULA, PACEJKA_BOOK)
def fit_magic_formula(slip, mu, *, form: str = "BCDE", sigma=None, fixed: dict | None = None,
                      p0: dict | None = None, peak=None) -> MagicFormulaFit:
    r"""Fit the Magic Formula to a measured or computed mu(slip) curve.

    Parameters
    ----------
    slip, mu : array_like
        Slip ratios in [0, 1] and friction coefficients (same length; more points than free parameters).
    form : {"BCDE", "simple"}
        ``"BCDE"``: :math:`D\sin\{C\arctan[Bs - E(Bs - \arctan Bs)]\}` (parameters B, C, D, E);
        ``"simple"``: :math:`a\sin(b\arctan(cs)) + d` (parameters a, b, c, d).
    sigma : array_like, optional
        Standard uncertainties of ``mu`` (absolute); without it the covariance is scaled by the residuals.
    fixed : dict, optional
        Parameters held fixed, e.g. ``{"E": 0.0}`` or ``{"d": 0.0}``.
    p0 : dict, optional
        A starting point (tried in addition to the built-in ones).
    peak : (float, float), optional
        A declared peak ``(slip_at_peak, peak_mu)`` the curve must have (``form="BCDE"`` only): D is the peak value
        and B follows from C and E through the peak condition (:func:`magic_formula_peak_B`), so only C (> 1) and
        E are fitted; their covariance is propagated to B (D is held, standard uncertainty 0).

    Returns
    -------
    MagicFormulaFit
        Parameters with standard uncertainties, and ``peak_mu``, ``slip_at_peak``, ``locked_mu`` (each with
        ``*_std``).
    """
    x, y, sig = _xy(slip, mu, sigma, "slip")
    if np.any((x < 0) | (x > 1)):
        raise InputError("slip: expected slip ratios in [0, 1]")
    if form not in ("BCDE", "simple"):
        raise InputError(f"form: expected \"BCDE\" or \"simple\", got {form!r}")
    if peak is not None:
        if form != "BCDE":
            raise InputError("peak: a declared peak is supported for form=\"BCDE\" only")
        return _fit_with_peak(x, y, sig, peak, fixed, p0)
    if form == "BCDE":
        names, func, bounds, law = ("B", "C", "D", "E"), magic_formula, _MF_BOUNDS, "magic_formula"
    else:
        names, func, bounds, law = ("a", "b", "c", "d"), magic_formula_simple, _MFS_BOUNDS, "magic_formula_simple"
    # multi-start: the data's characteristic points, the literature shapes and a grid of shapes, screened by
    # their residual; a local fit from each of the best (and from p0)
    starts = _screened(_magic_starts(x, y, form), func, names, bounds, x, y, sig, fixed)
    if p0:
        starts.insert(0, {**starts[0], **{k: number(v, f"p0[{k!r}]") for k, v in p0.items()}})
    parts = _fit(law, func, names, bounds, x, y, sig, fixed, starts, (MAGIC_FORMULA, PACEJKA_BOOK), agree=3)
    vals, cov = parts["values"], parts["covariance"]

    def pk(v):
        return _curve_peak(lambda s: func(s, *v))

    peak_mu, peak_std = _propagate(lambda v: pk(v)[0], vals, cov)
    sp, sp_std = _propagate(lambda v: pk(v)[1], vals, cov)
    lk, lk_std = _propagate(lambda v: func(1.0, *v), vals, cov)
    return MagicFormulaFit(**parts, peak_mu=peak_mu, peak_mu_std=peak_std, slip_at_peak=sp, slip_at_peak_std=sp_std,
                           locked_mu=float(lk), locked_mu_std=lk_std)


#: Typical Magic Formula coefficients (B, C, D, E) of the longitudinal force by road surface, from Pacejka's
#: tables as quoted in the Simscape Driveline documentation (MathWorks, "Tire-Road Interaction (Magic
#: Formula)"): starting points of :func:`fit_magic_formula` (shapes; D and B are rescaled to the data).
PACEJKA_TYPICAL = {"dry tarmac": (10.0, 1.9, 1.0, 0.97), "wet tarmac": (12.0, 2.3, 0.82, 1.0),
                   "snow": (5.0, 2.0, 0.3, 1.0), "ice": (4.0, 2.0, 0.1, 1.0)}

# shape factors and curvature factors of the grid of starting shapes (C > 1: a curve with a peak)
_GRID_C = (1.15, 1.35, 1.6, 1.9, 2.3, 2.8)
_GRID_E = (-3.0, -1.0, 0.0, 0.5, 0.8, 0.95, 0.99)
# starts kept for a local fit after screening by their residual
_N_LOCAL = 10


def _magic_starts(x, y, form: str) -> list[dict]:
    """Starting points of the Magic Formula fit: the data's characteristic points (Pacejka's relations between
    B, C, D, E and the peak D, the asymptote, the slope BCD and the slip of the peak), the literature shapes of
    :data:`PACEJKA_TYPICAL` and a grid of shapes (C, E), each with D the data's peak and B putting the curve's peak
    at the data's (:func:`magic_formula_peak_B`)."""
    j = int(np.argmax(y))
    D0 = float(max(y[j], 1e-3))
    xm = float(min(max(x[j], 1e-3), 1.0))
    ya = float(y[np.argmax(x)])
    C0 = float(np.clip(1.0 + (1.0 - 2.0 / math.pi * math.asin(np.clip(ya / D0, -0.999, 0.999))), 1.05, 1.95))
    small = (x > 0) & (x <= 0.5 * xm)
    K0 = float(np.sum(x[small] * y[small]) / np.sum(x[small] ** 2)) if np.any(small) else 3.0 * D0 / xm
    K0 = max(K0, D0 / xm)
    B0 = K0 / (C0 * D0)
    Bx = B0 * xm
    E0 = float(np.clip((Bx - math.tan(math.pi / (2 * C0))) / (Bx - math.atan(Bx)), -5.0, 0.9)) if Bx > 1e-6 else 0.0
    shapes = [(B0, C0, E0), (B0, C0, 0.0), (2 * B0, 1.5, 0.0), (0.5 * B0, 1.9, -1.0), (B0, 1.3, 0.5)]
    for B, C, _, E in PACEJKA_TYPICAL.values():
        shapes.append((B, C, E))
        shapes.append((None, C, E))
    shapes += [(None, C, E) for C in _GRID_C for E in _GRID_E]
    starts = []
    for B, C, E in shapes:
        E = min(E, 0.999)
        if B is None:
            try:
                B = magic_formula_peak_B(xm, C, E)
            except (InputError, ValueError):
                continue
        if form == "BCDE":
            starts.append(dict(B=B, C=C, D=D0, E=E))
        elif abs(E) < 1e-12:  # the simple form is the B, C, D form with E = 0, plus an offset
            d0 = float(y[np.argmin(x)]) if x.min() == 0 else 0.0
            starts += [dict(a=D0 - d0, b=C, c=B, d=d0), dict(a=D0, b=C, c=B, d=0.0)]
    return starts


def _screened(starts, func, names, bounds, x, y, sig, fixed) -> list[dict]:
    """The starts with the smallest residual (at most ``_N_LOCAL``, distinct), the best first: a local fit from
    each of them finds the global optimum of every curve the grid of shapes covers."""
    fixed = dict(fixed or {})
    w = 1.0 if sig is None else 1.0 / sig
    scored = []
    for st in starts:
        v = [fixed.get(n, st.get(n, 1.0)) for n in names]
        v = [min(max(float(val), bounds[n][0]), bounds[n][1]) for n, val in zip(names, v)]
        with np.errstate(all="ignore"):
            r = (func(x, *v) - y) * w
        cost = float(r @ r)
        if math.isfinite(cost):
            scored.append((cost, dict(zip(names, v))))
    scored.sort(key=lambda t: t[0])
    out = []
    for _, st in scored:
        if not any(all(math.isclose(st[n], o[n], rel_tol=1e-6, abs_tol=1e-9) for n in names) for o in out):
            out.append(st)
        if len(out) == _N_LOCAL:
            break
    return out or starts[:1]
