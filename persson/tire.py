r"""Tire-level curve laws and fits: Pacejka's Magic Formula on mu(slip), friction-speed laws on mu(V).

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

Friction-speed laws (V a speed in m/s: the slip speed or the test speed of the data):

* PIARC exponential (PIARC 1995, International Friction Index): :math:`\mu(V) = \mu_0 e^{-V/S_p}`
  (the IFI form :math:`F(S) = F_{60}\,e^{(60 - S)/S_p}` with S in km/h is :func:`piarc_ifi`);
* Do, Marsac & Mosset (2004) modified exponential, with the linear term of the issue's specification:
  :math:`\mu(V) = \mu_0 e^{-(V/V_s)^\alpha} + \beta V` (alpha = 1, beta = 0 is PIARC);
* Rado's log-normal model (Rado 1994): :math:`\mu(V) = \mu_L + (\mu_{peak} - \mu_L)
  \exp\{-[\ln(V/V_c)/C]^2\}` (:math:`\mu_L = 0` unless fitted).

Every fit uses :func:`scipy.optimize.curve_fit` (several starting points, the best kept) and returns a frozen
:class:`FitResult` with the parameters, their standard uncertainties and the covariance. Without ``sigma`` the
covariance is scaled by the residual variance (``absolute_sigma=False``); with ``sigma`` it is absolute.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from ._checks import finite_array, number
from .errors import InputError

__all__ = [
    "magic_formula", "magic_formula_simple", "MagicFormula", "SimpleMagicFormula", "magic_formula_from_points",
    "magic_formula_from_peak", "magic_formula_peak_B",
    "FitResult", "MagicFormulaFit", "fit_magic_formula", "peak",
    "piarc", "piarc_ifi", "do_marsac_mosset", "rado", "fit_speed_law", "fit_piarc", "fit_do_marsac_mosset",
    "fit_rado", "SPEED_LAWS", "MAGIC_FORMULA", "PIARC_1995", "DO_2004", "RADO_1994",
]

#: H. B. Pacejka, E. Bakker, The Magic Formula tyre model, Vehicle System Dynamics 21 (S1), 1-18 (1992).
MAGIC_FORMULA = "10.1080/00423119208969994"
#: Pacejka, Tire and Vehicle Dynamics (3rd ed. 2012), ch. 4 (Magic Formula): same key as persson.slip.
PACEJKA_BOOK = "isbn:9780080970165"
#: PIARC (World Road Association), International PIARC experiment to compare and harmonize texture and skid
#: resistance measurements, report 01.04.T (1995).
PIARC_1995 = "piarc:01.04.T-1995"
#: M.-T. Do, P. Marsac, A. Mosset, Tribology approach to predict the variation of tire/wet road friction with
#: slip speed, 5th Symposium on Pavement Surface Characteristics (SURF 2004), Toronto (HAL hal-00851262).
DO_2004 = "hal:hal-00851262"
#: Z. Rado, A study of road surface texture and its relationship to friction, PhD thesis, Pennsylvania State
#: University (1994).
RADO_1994 = "rado:psu-phd-1994"


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


def _curve_peak(f, lo: float = 0.0, hi: float = 1.0, n: int = 2001) -> tuple[float, float]:
    """(max f, argmax) of a smooth function on [lo, hi]: grid search then bounded Brent refinement."""
    from scipy.optimize import minimize_scalar

    s = np.linspace(lo, hi, n)
    y = f(s)
    j = int(np.argmax(y))
    if j == n - 1 or j == 0:
        return float(y[j]), float(s[j])
    r = minimize_scalar(lambda x: -float(f(np.asarray(x))), bounds=(s[j - 1], s[j + 1]), method="bounded",
                        options={"xatol": 1e-12})
    if r.success and -r.fun >= y[j]:
        return float(-r.fun), float(r.x)
    return float(y[j]), float(s[j])


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


# =========================================================================================================
# Fit results
# =========================================================================================================
class NamedParameters:
    """Access by name to the ``names``, ``values`` and ``stderr`` of a fit result (its ``_index`` names the error)."""

    def __getitem__(self, name: str) -> float:
        return float(self.values[self._index(name)])

    def std(self, name: str) -> float:
        """Standard uncertainty of the parameter ``name``."""
        return float(self.stderr[self._index(name)])

    @property
    def params(self) -> dict[str, float]:
        """Parameter values by name."""
        return {n: float(v) for n, v in zip(self.names, self.values)}

    @property
    def uncertainties(self) -> dict[str, float]:
        """Standard uncertainties by name."""
        return {n: float(v) for n, v in zip(self.names, self.stderr)}


@dataclass(frozen=True, eq=False)
class FitResult(NamedParameters):
    """A fitted curve law: parameters, standard uncertainties, covariance.

    Attributes
    ----------
    law : str
        Name of the law (``"magic_formula"``, ``"magic_formula_simple"``, ``"piarc"``, ``"do_marsac_mosset"``,
        ``"rado"``).
    names : tuple of str
        Parameter names, in the order of ``values``.
    values, stderr : ndarray
        Best-fit values and standard uncertainties (0 for parameters held fixed).
    covariance : ndarray
        Covariance of all parameters (rows/columns of fixed ones are 0).
    fixed : tuple of str
        Names of the parameters held fixed.
    x, y : ndarray
        The data (slip or speed, mu).
    sigma : ndarray or None
        Standard uncertainties of ``y`` given to the fit (absolute).
    rms : float
        Root-mean-square residual.
    dof : int
        Degrees of freedom (points - free parameters).
    notes : tuple of str
    citations : tuple of str
    """

    law: str
    names: tuple
    values: np.ndarray
    stderr: np.ndarray
    covariance: np.ndarray
    fixed: tuple
    x: np.ndarray
    y: np.ndarray
    sigma: np.ndarray | None
    rms: float
    dof: int
    notes: tuple = ()
    citations: tuple = ()
    func: object = field(default=None, repr=False)

    def __call__(self, x):
        """The fitted law at ``x``."""
        return self.func(np.asarray(x, dtype=float), *self.values)

    def propagate(self, quantity) -> tuple[float, float]:
        """Value and standard uncertainty of ``quantity(values)`` (a scalar function of the parameter vector),
        by linear propagation of the covariance (central differences)."""
        return _propagate(quantity, self.values, self.covariance)

    def _index(self, name: str) -> int:
        try:
            return self.names.index(name)
        except ValueError:
            raise InputError(f"parameter: {name!r} is not a parameter of {self.law} (has {list(self.names)})") from None


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


def _propagate(quantity, values, cov) -> tuple[float, float]:
    v0 = float(quantity(values))
    free = np.flatnonzero(np.diag(cov) > 0)
    if free.size == 0:
        return v0, 0.0
    grad = np.zeros(values.size)
    for i in free:
        h = 1e-6 * max(abs(values[i]), math.sqrt(cov[i, i]) * 1e-2, 1e-12)
        up = values.copy()
        dn = values.copy()
        up[i] += h
        dn[i] -= h
        grad[i] = (float(quantity(up)) - float(quantity(dn))) / (2 * h)
    var = float(grad @ cov @ grad)
    return v0, math.sqrt(max(var, 0.0))


def _fit(law, func, names, bounds, x, y, sigma, fixed, starts, citations, *, tol: float = 1e-14,
         maxfev: int = 20000) -> dict:
    """Multi-start curve_fit of ``func(x, *params)`` with some parameters fixed; the pieces of a FitResult."""
    from scipy.optimize import OptimizeWarning, curve_fit

    fixed = dict(fixed or {})
    unknown = sorted(set(fixed) - set(names))
    if unknown:
        raise InputError(f"fixed: unknown parameter(s) {unknown} of {law} (has {list(names)})")
    for k, v in fixed.items():
        fixed[k] = number(v, f"fixed[{k!r}]")
    free = [n for n in names if n not in fixed]
    if not free:
        raise InputError(f"fixed: every parameter of {law} is fixed; nothing to fit")
    if x.size <= len(free):
        raise InputError(f"x, mu: {x.size} points cannot determine {len(free)} free parameters of {law}")
    idx = [names.index(n) for n in free]
    lo = np.array([bounds[n][0] for n in free], dtype=float)
    hi = np.array([bounds[n][1] for n in free], dtype=float)

    def full(p):
        v = np.array([fixed.get(n, np.nan) for n in names], dtype=float)
        v[idx] = p
        return v

    def f(xx, *p):
        return func(xx, *full(np.asarray(p)))

    best = None
    notes = []
    for start in starts:
        p0 = np.array([start.get(n, 1.0) for n in free], dtype=float)
        p0 = np.clip(p0, lo + 1e-9 * (np.abs(lo) + 1), hi - 1e-9 * (np.abs(hi) + 1))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OptimizeWarning)
            try:
                p, cov = curve_fit(f, x, y, p0=p0, sigma=sigma, absolute_sigma=sigma is not None,
                                   bounds=(lo, hi), maxfev=maxfev, method="trf", x_scale="jac",
                                   ftol=tol, xtol=tol, gtol=tol)
            except (RuntimeError, ValueError):
                continue
        r = y - f(x, *p)
        w = r if sigma is None else r / sigma
        cost = float(w @ w)
        if best is None or cost < best[0] * (1 - 1e-12):
            best = (cost, p, cov)
    if best is None:
        raise InputError(f"x, mu: the {law} fit did not converge from any starting point")
    cost, p, cov = best
    values = full(p)
    n_all = len(names)
    C = np.zeros((n_all, n_all))
    if not np.all(np.isfinite(cov)):
        msg = f"{law}: the parameter covariance could not be estimated (parameters not all determined by the data)"
        notes.append(msg)
        warnings.warn(msg, RuntimeWarning, stacklevel=3)
        cov = np.where(np.isfinite(cov), cov, np.inf)
    C[np.ix_(idx, idx)] = cov
    stderr = np.sqrt(np.clip(np.diag(C), 0.0, None))
    at_bound = [free[i] for i in range(len(free)) if np.isclose(p[i], lo[i]) or np.isclose(p[i], hi[i])]
    if at_bound:
        msg = f"{law}: parameter(s) {at_bound} at their bound; the uncertainties there are not meaningful"
        notes.append(msg)
    resid = y - func(x, *values)
    return dict(law=law, names=tuple(names), values=values, stderr=stderr, covariance=C,
                fixed=tuple(n for n in names if n in fixed), x=x, y=y, sigma=sigma,
                rms=float(np.sqrt(np.mean(resid**2))), dof=int(x.size - len(free)), notes=tuple(notes),
                citations=tuple(citations), func=func)


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
    # characteristic points of the data for the starting values (Pacejka's relations between B, C, D, E and
    # the peak D, the asymptote y_a, the slope BCD and the slip of the peak x_m)
    j = int(np.argmax(y))
    D0 = float(max(y[j], 1e-3))
    xm = float(max(x[j], 1e-3))
    ya = float(y[np.argmax(x)])
    C0 = float(np.clip(1.0 + (1.0 - 2.0 / math.pi * math.asin(np.clip(ya / D0, -0.999, 0.999))), 1.05, 1.95))
    small = (x > 0) & (x <= 0.5 * xm)
    K0 = float(np.sum(x[small] * y[small]) / np.sum(x[small] ** 2)) if np.any(small) else 3.0 * D0 / xm
    K0 = max(K0, D0 / xm)
    B0 = K0 / (C0 * D0)
    Bx = B0 * xm
    E0 = float(np.clip((Bx - math.tan(math.pi / (2 * C0))) / (Bx - math.atan(Bx)), -5.0, 0.9)) if Bx > 1e-6 else 0.0
    if form == "BCDE":
        names = ("B", "C", "D", "E")
        func = magic_formula
        bounds = _MF_BOUNDS
        starts = [dict(B=B0, C=C0, D=D0, E=E0), dict(B=B0, C=C0, D=D0, E=0.0),
                  dict(B=2 * B0, C=1.5, D=D0, E=0.0), dict(B=0.5 * B0, C=1.9, D=D0, E=-1.0),
                  dict(B=B0, C=1.3, D=1.05 * D0, E=0.5)]
        law = "magic_formula"
    else:
        names = ("a", "b", "c", "d")
        func = magic_formula_simple
        bounds = _MFS_BOUNDS
        d0 = float(y[np.argmin(x)]) if x.min() == 0 else 0.0
        starts = [dict(a=D0 - d0, b=C0, c=B0, d=d0), dict(a=D0, b=C0, c=B0, d=0.0),
                  dict(a=D0, b=1.5, c=2 * B0, d=0.0), dict(a=D0, b=1.9, c=0.5 * B0, d=0.0)]
        law = "magic_formula_simple"
    if p0:
        starts.insert(0, {**starts[0], **{k: number(v, f"p0[{k!r}]") for k, v in p0.items()}})
    parts = _fit(law, func, names, bounds, x, y, sig, fixed, starts, (MAGIC_FORMULA, PACEJKA_BOOK))
    vals, cov = parts["values"], parts["covariance"]

    def pk(v):
        return _curve_peak(lambda s: func(s, *v))

    peak_mu, peak_std = _propagate(lambda v: pk(v)[0], vals, cov)
    sp, sp_std = _propagate(lambda v: pk(v)[1], vals, cov)
    lk, lk_std = _propagate(lambda v: func(1.0, *v), vals, cov)
    return MagicFormulaFit(**parts, peak_mu=peak_mu, peak_mu_std=peak_std, slip_at_peak=sp, slip_at_peak_std=sp_std,
                           locked_mu=float(lk), locked_mu_std=lk_std)


# =========================================================================================================
# Peak of a tabulated curve
# =========================================================================================================
def peak(slip, mu, axis: int = -1):
    """Peak mu and the slip at the peak of tabulated curve(s) mu(slip), along ``axis``.

    The discrete maximum is refined by the parabola through it and its two neighbours (in the slip variable);
    a maximum at either end of the range is returned as it is. ``slip`` is broadcast against ``mu``.

    Returns
    -------
    (peak_mu, slip_at_peak) : floats for one curve, arrays for several.
    """
    m = np.asarray(mu, dtype=float)
    try:
        s = np.broadcast_to(np.asarray(slip, dtype=float), m.shape)
    except ValueError:
        raise InputError(f"slip, mu: shapes {np.shape(slip)} and {m.shape} do not broadcast") from None
    if m.ndim == 0 or m.shape[axis] < 3:
        raise InputError("mu: expected at least three points along the slip axis")
    if not (np.all(np.isfinite(m)) and np.all(np.isfinite(s))):
        raise InputError("slip, mu: NaN or infinite values")
    m = np.moveaxis(m, axis, -1)
    s = np.moveaxis(s, axis, -1)
    n = m.shape[-1]
    j = np.argmax(m, axis=-1)
    jm = np.clip(j, 1, n - 2)
    take = lambda a, d: np.take_along_axis(a, (jm + d)[..., None], -1)[..., 0]  # noqa: E731
    x = np.stack([take(s, d) for d in (-1, 0, 1)])
    y = np.stack([take(m, d) for d in (-1, 0, 1)])
    from .slip import _parabola_vertex

    xv, yv, ok = _parabola_vertex(x, y)
    ok &= (j >= 1) & (j <= n - 2)
    pm = np.where(ok, yv, np.take_along_axis(m, j[..., None], -1)[..., 0])
    ps = np.where(ok, xv, np.take_along_axis(s, j[..., None], -1)[..., 0])
    if pm.ndim == 0:
        return float(pm), float(ps)
    return pm, ps


# =========================================================================================================
# Friction-speed laws
# =========================================================================================================
@doi(PIARC_1995)
def piarc(speed, mu0, Sp):
    r"""PIARC exponential friction-speed law :math:`\mu_0 e^{-V/S_p}` (V and the speed constant Sp in m/s)."""
    return mu0 * np.exp(-np.asarray(speed, dtype=float) / Sp)


@doi(PIARC_1995)
def piarc_ifi(S_km_h, F60, Sp_km_h):
    r"""PIARC / IFI form :math:`F(S) = F_{60}\,e^{(60 - S)/S_p}`, slip speed S and Sp in km/h.

    F60 is the friction at 60 km/h.

    Equal to :func:`piarc` with :math:`\mu_0 = F_{60} e^{60/S_p}` after converting the speeds to m/s.
    """
    return F60 * np.exp((60.0 - np.asarray(S_km_h, dtype=float)) / Sp_km_h)


@doi(DO_2004, PIARC_1995)
def do_marsac_mosset(speed, mu0, Vs, alpha, beta=0.0):
    r"""Do-Marsac-Mosset modified exponential :math:`\mu_0 e^{-(V/V_s)^\alpha} + \beta V` (V, Vs in m/s; beta in s/m).

    The stretched exponential is the law of Do, Marsac & Mosset (2004), a generalisation of the PIARC model
    (alpha = 1); the linear term :math:`\beta V` is the extension specified in issue 6 (the "modified
    exponential"). With alpha = 1 and beta = 0 it is exactly :func:`piarc` with Sp = Vs.
    """
    V = np.asarray(speed, dtype=float)
    return mu0 * np.exp(-((V / Vs) ** alpha)) + beta * V


@doi(RADO_1994)
def rado(speed, mu_peak, Vc, C, mu_locked=0.0):
    r"""Rado's log-normal model :math:`\mu_L + (\mu_{peak} - \mu_L)\exp\{-[\ln(V/V_c)/C]^2\}`.

    ``Vc`` the (critical) speed of the peak, m/s; ``C`` the shape (width) factor; ``mu_locked`` (:math:`\mu_L`)
    the level far from the peak (0 in Rado's three-parameter form).
    """
    V = np.asarray(speed, dtype=float)
    return mu_locked + (mu_peak - mu_locked) * np.exp(-((np.log(V / Vc) / C) ** 2))


#: name -> (function, parameter names, bounds)
SPEED_LAWS = {
    "piarc": (piarc, ("mu0", "Sp"), {"mu0": (1e-6, 10.0), "Sp": (1e-6, 1e6)}),
    "do_marsac_mosset": (do_marsac_mosset, ("mu0", "Vs", "alpha", "beta"),
                         {"mu0": (1e-6, 10.0), "Vs": (1e-6, 1e6), "alpha": (0.05, 10.0), "beta": (-10.0, 10.0)}),
    "rado": (rado, ("mu_peak", "Vc", "C", "mu_locked"),
             {"mu_peak": (1e-6, 10.0), "Vc": (1e-9, 1e6), "C": (1e-3, 100.0), "mu_locked": (0.0, 10.0)}),
}


def fit_speed_law(law: str, speed, mu, *, sigma=None, fixed: dict | None = None, p0: dict | None = None) -> FitResult:
    """Fit a friction-speed law (``"piarc"``, ``"do_marsac_mosset"``, ``"rado"``) to mu(V).

    Parameters
    ----------
    law : str
        A key of :data:`SPEED_LAWS`.
    speed, mu : array_like
        Speeds (> 0, m/s) and friction coefficients.
    sigma : array_like, optional
        Standard uncertainties of ``mu`` (absolute).
    fixed : dict, optional
        Parameters held fixed (e.g. ``{"alpha": 1.0, "beta": 0.0}``).
    p0 : dict, optional
        An extra starting point.
    """
    if law not in SPEED_LAWS:
        raise InputError(f"law: expected one of {sorted(SPEED_LAWS)}, got {law!r}")
    x, y, sig = _xy(speed, mu, sigma, "speed")
    if np.any(x <= 0):
        raise InputError("speed: expected speeds > 0 m/s")
    func, names, bounds = SPEED_LAWS[law]
    starts = _speed_starts(law, x, y)
    if p0:
        starts.insert(0, {**starts[0], **{k: number(v, f"p0[{k!r}]") for k, v in p0.items()}})
    parts = _fit(law, func, names, bounds, x, y, sig, fixed, starts, getattr(func, "__citations__", ()))
    return FitResult(**parts)


def _speed_starts(law, x, y):
    pos = y > 0
    if np.sum(pos) >= 2 and np.ptp(x[pos]) > 0:
        slope, icpt = np.polyfit(x[pos], np.log(y[pos]), 1)
        Sp0 = -1.0 / slope if slope < 0 else 10.0 * float(np.max(x))
        mu00 = float(np.exp(icpt))
    else:
        Sp0, mu00 = float(np.max(x)), float(np.max(y))
    if law == "piarc":
        return [dict(mu0=mu00, Sp=Sp0), dict(mu0=float(np.max(y)), Sp=float(np.median(x)))]
    if law == "do_marsac_mosset":
        return [dict(mu0=mu00, Vs=Sp0, alpha=1.0, beta=0.0), dict(mu0=mu00, Vs=Sp0, alpha=0.5, beta=0.0),
                dict(mu0=mu00, Vs=Sp0, alpha=2.0, beta=0.0), dict(mu0=float(np.max(y)), Vs=float(np.median(x)),
                                                               alpha=1.5, beta=0.0)]
    j = int(np.argmax(y))
    lx = np.log(x)
    w = max(float(np.ptp(lx)) / 3.0, 0.3)
    return [dict(mu_peak=float(y[j]), Vc=float(x[j]), C=w, mu_locked=float(np.min(y)) * 0.5),
            dict(mu_peak=float(y[j]), Vc=float(x[j]), C=2 * w, mu_locked=0.0),
            dict(mu_peak=float(y[j]), Vc=float(np.exp(np.mean(lx))), C=w, mu_locked=0.0)]


@doi(PIARC_1995)
def fit_piarc(speed, mu, *, sigma=None) -> FitResult:
    """Fit the PIARC exponential mu0 exp(-V/Sp) (see :func:`fit_speed_law`)."""
    return fit_speed_law("piarc", speed, mu, sigma=sigma)


@doi(DO_2004)
def fit_do_marsac_mosset(speed, mu, *, sigma=None, fixed: dict | None = None) -> FitResult:
    """Fit the Do-Marsac-Mosset law mu0 exp(-(V/Vs)^alpha) + beta V (``fixed`` e.g. ``{"beta": 0.0}``)."""
    return fit_speed_law("do_marsac_mosset", speed, mu, sigma=sigma, fixed=fixed)


@doi(RADO_1994)
def fit_rado(speed, mu, *, sigma=None, fit_mu_locked: bool = False) -> FitResult:
    """Fit Rado's log-normal law (``mu_locked`` held at 0 unless ``fit_mu_locked``)."""
    return fit_speed_law("rado", speed, mu, sigma=sigma, fixed=None if fit_mu_locked else {"mu_locked": 0.0})


# =========================================================================================================
# helpers
# =========================================================================================================
def _xy(x, y, sigma, xname: str):
    x = finite_array(x, xname).ravel()
    y = finite_array(y, "mu").ravel()
    if x.size != y.size:
        raise InputError(f"{xname}, mu: expected equal lengths, got {x.size} and {y.size}")
    sig = None
    if sigma is not None:
        sig = np.broadcast_to(finite_array(sigma, "sigma").ravel(), y.shape).astype(float) if np.size(sigma) in (1, y.size) \
            else None
        if sig is None:
            raise InputError(f"sigma: expected one value or {y.size} values")
        if np.any(sig <= 0):
            raise InputError("sigma: expected standard uncertainties > 0")
    return x, y, sig
