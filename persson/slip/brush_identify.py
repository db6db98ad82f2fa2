r"""The two-coefficient brush identified from a Magic Formula: the road-friction trailer article's Figure 18.

The article (Study on the influence of environmental conditions on road friction characteristics, Lubricants
11(7), 277 (2023), Section 4.1) describes a measured curve by the Magic Formula and then by the two-coefficient
brush with Sakai's n = 4 pressure (:func:`~persson.slip.two_coefficient_mu`), taking the formula's locked mu as
the dynamic coefficient and adjusting the static one, the brush's initial slope being the formula's (its Eq. 21
writes the stiffness through abc, the slope of :math:`a\sin(b\arctan cs)`). Here, for a Magic Formula
:math:`f(s)` (Pacejka & Bakker 1992):

* :math:`\mu_D = f(1)`, the locked-wheel value;
* :math:`C_0 = f'(0)` (BCD, or abc for the simple form);
* :math:`\mu_s` minimises :math:`\sum_i [\mu_{brush}(s_i) - f(s_i)]^2` on ``n_slip`` evenly spaced slips
  :math:`s_i = i/n_{slip}`, i = 1 ... n_slip (the article does not state its criterion; this is the least-squares
  one over the measured range), searched in :math:`[\max(\mu_D, f_{max}/2),\ 20 f_{max}]`;
* :math:`n_1 = \mu_D/\mu_s`, :math:`n_2 = C_0/\mu_s` (the article's Eq. 25).

The brush is evaluated exactly: for Sakai's law :math:`p/\sigma_0 = \frac{n+1}{n}(1 - |2\xi - 1|^n)` the stick
length :math:`\xi_c` solves :math:`2u\xi = p(\xi)/\sigma_0`, :math:`u = C_0\theta/\mu_s` (for n = 4 the cubic whose
root is the article's Eq. 20), and the load ahead of it is
:math:`G(\xi_c) = \frac{n+1}{n}[\xi_c - (1 + \mathrm{sign}(w)|w|^{n+1})/(2(n+1))]`, :math:`w = 2\xi_c - 1`; so
:math:`\mu = C_0\theta\xi_c^2 + \mu_D[1 - G(\xi_c)]`. Both terms are tabulated once per call against u (the root
by bisection at 16385 evenly spaced u) and interpolated linearly: error in mu 2e-8 for n = 4, below 1e-6 for
0.5 <= n <= 10.

Uncertainties (standard deviations) go through the identification linearly (GUM, JCGM 100:2008, 5.1): the
covariance of the formula's parameters (given, or from a :class:`~persson.slip.MagicFormulaFit`, or from the
points' standard uncertainties through the three-point identification's implicit-function Jacobian) times the
Jacobian of :math:`(\mu_s, \mu_D, C_0, n_1, n_2)`, by central differences of the whole identification. They do not
include the brush's model error (the difference between the brush and the formula, reported as ``rms``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .._checks import finite_array, number
from ..errors import InputError
from .brush import BrushCurve, _kinematics, _theta, two_coefficient_mu
from .fitting import FitResult
from .magic import MagicFormula, SimpleMagicFormula, fit_magic_formula, magic_formula, magic_formula_from_points
from .magic import magic_formula_simple
from .references import MAGIC_FORMULA, PACEJKA_BOOK, SAKAI_1981, TRAILER_2023

__all__ = ["identify_two_coefficient", "BrushIdentification"]

_GUM = "jcgm:100-2008"
#: Order of the identified quantities in ``BrushIdentification.covariance``.
_OUT = ("mu_static", "mu_dynamic", "initial_slope", "n1", "n2")
_N_COARSE = 33     # log-spaced mu_s of the coarse search
_N_GOLDEN = 48     # golden-section steps in the bracketing coarse cells (bracket x 0.618^48 ~ 1e-10 in ln mu_s)
_STEP = 1e-3       # relative step of the central differences (absolute 1e-3 for parameters near 0)


@dataclass(frozen=True, eq=False)
class BrushIdentification:
    r"""Two-coefficient brush identified from a Magic Formula (:func:`identify_two_coefficient`).

    Values are floats for one formula, arrays (one per formula) for a sequence; NaN only for formulas given as
    None (the notes list them).

    Attributes
    ----------
    mu_static, mu_dynamic, initial_slope, n1, n2 : float or ndarray
        :math:`\mu_s`, :math:`\mu_D = f(1)`, :math:`C_0 = f'(0)`, :math:`n_1 = \mu_D/\mu_s`, :math:`n_2 = C_0/\mu_s`.
    mu_static_std, mu_dynamic_std, initial_slope_std, n1_std, n2_std : float or ndarray or None
        Standard deviations propagated from the formula's covariance; None when the input carries none.
    covariance : ndarray or None
        Covariance of (mu_static, mu_dynamic, initial_slope, n1, n2), shape (5, 5) or (N, 5, 5).
    peak_mu, slip_at_peak, peak_ratio, locked_mu : float or ndarray
        The identified brush's peak on 0 < s <= 1, its slip, :math:`n_3 = \mu_{peak}/\mu_s`, and :math:`\mu(1)`
        (equal to :math:`\mu_D` except with the linear kinematics while :math:`n_2 < n + 1`).
    rms, max_deviation : float or ndarray
        Root-mean-square and largest absolute difference between the brush and the formula on the slips used.
    at_bound : bool or ndarray
        Whether :math:`\mu_s` lies at an end of the searched range (the identification is then doubtful).
    formula : MagicFormula or SimpleMagicFormula or tuple
        The formula(s) identified from.
    sakai_n : float
    kinematics : str
    n_slip : int
    notes : tuple of str
    citations : tuple of str
    """

    mu_static: object
    mu_dynamic: object
    initial_slope: object
    n1: object
    n2: object
    mu_static_std: object
    mu_dynamic_std: object
    initial_slope_std: object
    n1_std: object
    n2_std: object
    covariance: np.ndarray | None
    peak_mu: object
    slip_at_peak: object
    peak_ratio: object
    locked_mu: object
    rms: object
    max_deviation: object
    at_bound: object
    formula: object
    sakai_n: float
    kinematics: str
    n_slip: int
    notes: tuple = ()
    citations: tuple = (TRAILER_2023, PACEJKA_BOOK, SAKAI_1981, MAGIC_FORMULA)

    def curve(self, slip, index: int | None = None, *, n_points: int = 401,
              length: float | None = None) -> BrushCurve:
        """The identified brush's mu(slip) with its adhesion and sliding terms (:func:`two_coefficient_mu`);
        ``index`` picks one formula of a sequence."""
        vals = [self.mu_static, self.mu_dynamic, self.initial_slope]
        if np.ndim(self.mu_static):
            if index is None:
                raise InputError(f"index: the identification holds {np.size(self.mu_static)} brushes; give the one "
                                 "to evaluate")
            vals = [np.asarray(v)[index] for v in vals]
        ms, md, c0 = (float(v) for v in vals)
        if not np.isfinite(ms):
            raise InputError(f"index: no brush was identified for formula {index} (it was None)")
        return two_coefficient_mu(slip, mu_static=ms, mu_dynamic=md, initial_slope=c0, sakai_n=self.sakai_n,
                                  n_points=n_points, kinematics=self.kinematics, length=length)


@doi(TRAILER_2023, PACEJKA_BOOK, SAKAI_1981, MAGIC_FORMULA, _GUM)
def identify_two_coefficient(curve, mu=None, *, sigma=None, slip_std=None, covariance=None, sakai_n: float = 4.0,
                             kinematics: str = "pacejka", n_slip: int = 100) -> BrushIdentification:
    r"""Identify the two-coefficient brush from a Magic Formula: :math:`\mu_D` its locked mu, :math:`\mu_s` free.

    See the module docstring for the criterion and the propagation of uncertainties.

    Parameters
    ----------
    curve : MagicFormula, SimpleMagicFormula, MagicFormulaFit, sequence of them, or array_like of slips
        The formula (a :class:`~persson.slip.MagicFormulaFit` brings its covariance), several formulas of one
        form (None entries give NaN), or the slips of measured points (then ``mu`` is required).
    mu : array_like, optional
        Friction values of the points: three points identify the formula exactly
        (:func:`~persson.slip.magic_formula_from_points`, E = 0), more are fitted
        (:func:`~persson.slip.fit_magic_formula`; E held at 0 for four points).
    sigma : float or array_like, optional
        Standard uncertainties of ``mu`` (points only).
    slip_std : float or array_like, optional
        Standard uncertainties of the slips (three points only).
    covariance : array_like, optional
        Covariance of the formula's parameters in the order (B, C, D[, E]) or (a, b, c[, d]): shape (p, p), or
        (N, p, p) for N formulas; p = 3 holds E (or d).
    sakai_n : float
        Exponent of Sakai's pressure law (> 0; 4, the article's).
    kinematics : {"pacejka", "linear"}
        :math:`\theta = s/(1-s)` or the article's :math:`\Delta x = s x`.
    n_slip : int
        Evenly spaced slips in (0, 1] of the least-squares criterion (>= 10).

    Returns
    -------
    BrushIdentification

    Raises
    ------
    InputError
        Bad points, formulas of mixed forms, a covariance of the wrong shape, a formula whose locked mu is < 0,
        whose initial slope is <= 0 or whose maximum on (0, 1] is <= 0.
    """
    kin = _kinematics(kinematics)
    n = number(sakai_n, "sakai_n")
    if n <= 0:
        raise InputError(f"sakai_n: expected an exponent > 0, got {n:g}")
    if isinstance(n_slip, bool) or not isinstance(n_slip, (int, np.integer)) or n_slip < 10:
        raise InputError(f"n_slip: expected an integer >= 10, got {n_slip!r}")
    form, params, cov, formulas, scalar = _parse(curve, mu, sigma, slip_std, covariance)
    missing = np.flatnonzero(~np.all(np.isfinite(params), axis=1))
    ok = np.ones(params.shape[0], dtype=bool)
    ok[missing] = False
    table = _sakai_table(n)
    s = np.arange(1, int(n_slip) + 1) / int(n_slip)
    theta = _theta(s, kin)
    out = {k: np.full(params.shape[0], np.nan) for k in _OUT + ("rms", "max_deviation", "peak_mu", "slip_at_peak",
                                                               "locked_mu")}
    at_bound = np.zeros(params.shape[0], dtype=bool)
    cov_out = None
    if np.any(ok):
        p = params[ok]
        _check_formulas(form, p, np.flatnonzero(ok))
        values, bound = _identify(form, p, s, theta, n, table)
        for k, v in zip(_OUT, values, strict=True):
            out[k][ok] = v
        at_bound[ok] = bound
        ms, md, c0 = values[0], values[1], values[2]
        peak, s_peak, locked = _brush_peak(ms, md, c0, kin, n, table)
        out["peak_mu"][ok], out["slip_at_peak"][ok] = peak, s_peak
        out["locked_mu"][ok] = locked
        diff = _brush_exact(ms[:, None], md[:, None], c0[:, None], theta[None, :], n, table) \
            - _formula(form, p, s)
        out["rms"][ok] = np.sqrt(np.mean(diff**2, axis=1))
        out["max_deviation"][ok] = np.max(np.abs(diff), axis=1)
        if cov is not None:
            cov_out = np.full((params.shape[0], 5, 5), np.nan)
            cov_out[ok] = _propagate(form, p, cov[ok], s, theta, n, table)
    notes = []
    if missing.size:
        notes.append(f"{missing.size} formula(s) missing (None), NaN there: index {_list(missing)}")
    if np.any(at_bound):
        notes.append(f"mu_s at an end of the searched range [max(mu_D, peak/2), 20 peak] for index "
                     f"{_list(np.flatnonzero(at_bound))}: the brush does not describe that curve")
    stuck = ok & (kin == "linear") & (out["n2"] < n + 1.0)
    if np.any(stuck):
        notes.append(f"linear kinematics with n2 < n + 1 = {n + 1:g} for index {_list(np.flatnonzero(stuck))}: the "
                     f"brush keeps a stick zone at the locked wheel, its mu(1) differs from mu_D")
    std = {k: None for k in _OUT}
    if cov_out is not None:
        diag = np.sqrt(np.clip(np.diagonal(cov_out, axis1=1, axis2=2), 0.0, None))
        std = {k: diag[:, i] for i, k in enumerate(_OUT)}

    def pick(a):
        if a is None:
            return None
        return (float(a[0]) if a.dtype.kind == "f" else bool(a[0])) if scalar else a

    peak_ratio = out["peak_mu"] / out["mu_static"]
    return BrushIdentification(
        **{k: pick(out[k]) for k in _OUT}, **{f"{k}_std": pick(std[k]) for k in _OUT},
        covariance=None if cov_out is None else (cov_out[0] if scalar else cov_out),
        peak_mu=pick(out["peak_mu"]), slip_at_peak=pick(out["slip_at_peak"]), peak_ratio=pick(peak_ratio),
        locked_mu=pick(out["locked_mu"]), rms=pick(out["rms"]), max_deviation=pick(out["max_deviation"]),
        at_bound=pick(at_bound), formula=formulas[0] if scalar else tuple(formulas), sakai_n=n, kinematics=kin,
        n_slip=int(n_slip), notes=tuple(notes))


# =========================================================================================================
# Helpers: input, the exact brush, the batched search, the propagation
# =========================================================================================================
def _parse(curve, mu, sigma, slip_std, covariance):
    """(form, params (N, 4), covariance (N, 4, 4) or None, formulas, scalar) of the accepted inputs."""
    if mu is not None:
        if covariance is not None:
            raise InputError("covariance: give it with a formula, not with points (give sigma, slip_std)")
        return _from_points(curve, mu, sigma, slip_std)
    if sigma is not None or slip_std is not None:
        raise InputError("sigma, slip_std: uncertainties of points need the points (slip and mu); with a formula "
                         "give its covariance")
    if isinstance(curve, FitResult):
        if not hasattr(curve, "formula") or curve.law not in ("magic_formula", "magic_formula_simple"):
            raise InputError(f"curve: expected a Magic Formula fit, got a {curve.law!r} fit")
        if covariance is not None:
            raise InputError("covariance: the Magic Formula fit carries its own covariance")
        f = curve.formula
        form, p = _params(f, "curve")
        return form, p[None, :], np.asarray(curve.covariance, dtype=float)[None, :, :], [f], True
    scalar = isinstance(curve, (MagicFormula, SimpleMagicFormula))
    formulas = [curve] if scalar else list(curve) if isinstance(curve, (list, tuple)) else None
    if not formulas:
        raise InputError(f"curve: expected a MagicFormula, a SimpleMagicFormula, a Magic Formula fit, a sequence "
                         f"of formulas, or the slips of points with mu=..., got {curve!r}")
    forms, rows = set(), []
    for i, f in enumerate(formulas):
        if f is None:
            rows.append(np.full(4, np.nan))
            continue
        form, p = _params(f, f"curve[{i}]" if not scalar else "curve")
        forms.add(form)
        rows.append(p)
    if len(forms) > 1:
        raise InputError("curve: the formulas mix the B, C, D, E form and the simple form a, b, c, d")
    if not forms:
        raise InputError("curve: every formula is None")
    params = np.array(rows)
    cov = None
    if covariance is not None:
        c = finite_array(covariance, "covariance")
        c = c[None] if c.ndim == 2 else c
        if c.ndim != 3 or c.shape[0] != params.shape[0] or c.shape[1] != c.shape[2] or c.shape[1] not in (3, 4):
            raise InputError(f"covariance: expected shape (p, p) or ({params.shape[0]}, p, p) with p = 3 or 4 (the "
                             f"formula's parameters in order), got {np.shape(covariance)}")
        cov = np.zeros((params.shape[0], 4, 4))
        k = c.shape[1]
        cov[:, :k, :k] = c
        if np.any(np.diagonal(c, axis1=1, axis2=2) < 0):
            raise InputError("covariance: negative variance on the diagonal")
    return forms.pop(), params, cov, formulas, scalar


def _params(f, name):
    if isinstance(f, MagicFormula):
        return "BCDE", np.array([f.B, f.C, f.D, f.E], dtype=float)
    if isinstance(f, SimpleMagicFormula):
        return "simple", np.array([f.a, f.b, f.c, f.d], dtype=float)
    raise InputError(f"{name}: expected a MagicFormula or SimpleMagicFormula, got {f!r}")


def _from_points(slip, mu, sigma, slip_std):
    s = finite_array(slip, "slip").ravel()
    m = finite_array(mu, "mu").ravel()
    if s.size != m.size or s.size < 3:
        raise InputError(f"slip, mu: expected three or more points of equal length, got {s.size} and {m.size}")
    sig = None if sigma is None else np.broadcast_to(finite_array(sigma, "sigma"), m.shape).astype(float)
    if sig is not None and np.any(sig < 0):
        raise InputError("sigma: expected standard uncertainties >= 0")
    if s.size > 3:
        if slip_std is not None:
            raise InputError("slip_std: supported for three points (the exact identification); for a fit fold the "
                             "slip uncertainty into sigma")
        fit = fit_magic_formula(s, m, sigma=sig, fixed={"E": 0.0} if s.size == 4 else None)
        f = fit.formula
        return "BCDE", _params(f, "curve")[1][None, :], np.asarray(fit.covariance, dtype=float)[None], [f], True
    f = magic_formula_from_points(s, m)
    p = _params(f, "curve")[1]
    if sig is None and slip_std is None:
        return "BCDE", p[None, :], None, [f], True
    ss = np.zeros(3) if slip_std is None else np.broadcast_to(finite_array(slip_std, "slip_std"), s.shape)
    if np.any(ss < 0):
        raise InputError("slip_std: expected standard uncertainties >= 0")
    var = (np.zeros(3) if sig is None else sig**2)
    cov = np.zeros((1, 4, 4))
    cov[0, :3, :3] = _three_point_covariance(p, s, var, ss)
    return "BCDE", p[None, :], cov, [f], True


@doi(MAGIC_FORMULA, _GUM)
def _three_point_covariance(p, s, var_mu, slip_std):
    r"""Covariance of (B, C, D) of the formula through three points (E = 0): :math:`dq = J^{-1}(d\mu - f'(s)ds)`."""
    B, C, D = p[:3]
    x = B * s
    phi = np.arctan(x)
    cos = np.cos(C * phi)
    J = np.stack([D * cos * C * s / (1 + x * x), D * cos * phi, np.sin(C * phi)], axis=1)
    slope = D * cos * C * B / (1 + x * x)
    Jinv = np.linalg.inv(J)
    return Jinv @ np.diag(var_mu + (slope * slip_std) ** 2) @ Jinv.T


def _formula(form, p, s):
    """f(s) for parameter rows p (N, 4) at slips s (S,) -> (N, S)."""
    cols = [p[:, k:k + 1] for k in range(4)]
    return magic_formula(s[None, :], *cols) if form == "BCDE" else magic_formula_simple(s[None, :], *cols)


def _slope_and_lock(form, p):
    C0 = p[:, 0] * p[:, 1] * p[:, 2]  # BCD, or abc
    return C0, _formula(form, p, np.ones(1))[:, 0]


def _check_formulas(form, p, index):
    c0, lock = _slope_and_lock(form, p)
    peak = np.max(_formula(form, p, np.linspace(0.0, 1.0, 201)[1:]), axis=1)
    for name, value, bad, what in (("initial slope", c0, c0 <= 0, "> 0"), ("locked mu f(1)", lock, lock < 0, ">= 0"),
                                   ("largest mu on (0, 1]", peak, peak <= 0, "> 0")):
        if np.any(bad):
            k = int(np.argmax(bad))
            raise InputError(f"curve: formula {int(index[k])} has the {name} {value[k]:g}; the brush needs {what}")


def _identify(form, p, s, theta, n, table):
    """(mu_s, mu_D, C0, n1, n2) and at_bound for parameter rows p (the batched search of the module docstring)."""
    c0, md = _slope_and_lock(form, p)
    target = _formula(form, p, s)
    peak = np.max(target, axis=1)
    lo = np.log(np.maximum(md, 0.5 * peak))
    hi = np.log(20.0 * peak)

    def cost(log_ms):  # log_ms (N, K) -> (N, K)
        ms = np.exp(log_ms)[..., None]
        mu = _brush_exact(ms, md[:, None, None], c0[:, None, None], theta, n, table)
        return np.sum((mu - target[:, None, :]) ** 2, axis=-1)

    grid = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, _N_COARSE)[None, :]
    j = np.argmin(cost(grid), axis=1)
    rows = np.arange(p.shape[0])
    a = grid[rows, np.clip(j - 1, 0, _N_COARSE - 1)]
    b = grid[rows, np.clip(j + 1, 0, _N_COARSE - 1)]
    r = 0.5 * (np.sqrt(5.0) - 1.0)
    x1, x2 = b - r * (b - a), a + r * (b - a)
    f = cost(np.stack([x1, x2], axis=1))
    f1, f2 = f[:, 0], f[:, 1]
    for _ in range(_N_GOLDEN):
        left = f1 < f2  # the minimum lies in [a, x2]
        b = np.where(left, x2, b)
        a = np.where(left, a, x1)
        x_new = np.where(left, b - r * (b - a), a + r * (b - a))
        f_new = cost(x_new[:, None])[:, 0]
        x1, x2, f1, f2 = (np.where(left, x_new, x2), np.where(left, x1, x_new),
                          np.where(left, f_new, f2), np.where(left, f1, f_new))
    ms = np.exp(0.5 * (a + b))
    at_bound = (j == 0) | (j == _N_COARSE - 1)
    return (ms, md, c0, md / ms, c0 / ms), at_bound


def _brush_peak(ms, md, c0, kin, n, table):
    """Peak on 0 < s <= 1 (2000 slips, then the vertex of the parabola through the best three), its slip, mu(1)."""
    dense = np.linspace(0.0, 1.0, 2001)[1:]
    mu = _brush_exact(ms[:, None], md[:, None], c0[:, None], _theta(dense, kin)[None, :], n, table)
    rows = np.arange(ms.size)
    j = np.argmax(mu, axis=1)
    jm = np.clip(j, 1, dense.size - 2)
    y0, y1, y2 = mu[rows, jm - 1], mu[rows, jm], mu[rows, jm + 1]
    curv = y0 - 2.0 * y1 + y2
    with np.errstate(divide="ignore", invalid="ignore"):
        shift = np.where(curv < 0, 0.5 * (y0 - y2) / curv, 0.0)
    h = dense[1] - dense[0]
    sv = np.clip(dense[jm] + np.clip(shift, -1.0, 1.0) * h, dense[0], 1.0)
    mv = _brush_exact(ms, md, c0, _theta(sv, kin), n, table)
    better = (j == jm) & (mv > mu[rows, j])
    return np.where(better, mv, mu[rows, j]), np.where(better, sv, dense[j]), mu[:, -1]


def _propagate(form, p, cov, s, theta, n, table):
    """Covariance (N, 5, 5) of (mu_s, mu_D, C0, n1, n2) from the parameters' (N, 4, 4) by central differences."""
    N = p.shape[0]
    h = np.where(np.abs(p) < 1e-12, _STEP, _STEP * np.abs(p))
    varied = np.flatnonzero(np.any(np.diagonal(cov, axis1=1, axis2=2) > 0, axis=0))
    stack = []
    for k in varied:
        for sign in (1.0, -1.0):
            q = p.copy()
            q[:, k] += sign * h[:, k]
            stack.append(q)
    J = np.zeros((N, 5, 4))
    if stack:
        vals, _ = _identify(form, np.concatenate(stack), s, theta, n, table)
        vals = np.stack(vals, axis=1).reshape(len(varied), 2, N, 5)
        for i, k in enumerate(varied):
            J[:, :, k] = (vals[i, 0] - vals[i, 1]) / (2.0 * h[:, k, None])
    return np.einsum("nik,nkl,njl->nij", J, cov, J)


def _sakai_table(n: float, size: int = 16385):
    r"""Tables of the brush's two terms on evenly spaced :math:`u = C_0\theta/\mu_s` in [0, n + 1], Sakai's law.

    At each node the stick length :math:`\xi_c` (the first root of :math:`p(\xi)/\sigma_0 = 2u\xi`, on the branch
    where :math:`p/(\sigma_0\xi)` decreases: all of (0, 1] for n >= 1, [1/2, 1] below) is found by bisection to
    machine precision; then the adhesion term per :math:`\mu_s`, :math:`A = u\xi_c^2`, and the load fraction behind
    the stick zone, :math:`H = 1 - G(\xi_c)`. Beyond u = n + 1 the first crossing is at the leading edge
    (:math:`\xi_c = 0`: A = 0, H = 1). Returns (du, A, H).
    """
    u = np.linspace(0.0, n + 1.0, size)
    u_solve = u.copy()
    u_solve[-1] *= 1.0 - 1e-13  # the last node holds the limit from below (xi_c jumps to 0 at n + 1 when n <= 1)
    lo = np.full(size, 0.0 if n >= 1.0 else 0.5)
    hi = np.ones(size)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        sticks = (n + 1.0) / n * (1.0 - np.abs(2.0 * mid - 1.0) ** n) > 2.0 * u_solve * mid
        lo, hi = np.where(sticks, mid, lo), np.where(sticks, hi, mid)
    x = 0.5 * (lo + hi)
    w = 2.0 * x - 1.0
    G = (n + 1.0) / n * (x - (1.0 + np.sign(w) * np.abs(w) ** (n + 1.0)) / (2.0 * (n + 1.0)))
    return u[1] - u[0], u * x * x, 1.0 - G


def _brush_exact(mu_s, mu_d, c0, theta, n, table):
    r"""mu of the two-coefficient brush with Sakai's law (broadcast over all arguments; theta may be inf):
    :math:`\mu_s A(u) + \mu_D H(u)`, the terms interpolated linearly in the tables of :func:`_sakai_table`."""
    du, A_t, H_t = table
    with np.errstate(invalid="ignore", over="ignore"):
        r = np.nan_to_num(c0 * theta / mu_s / du, posinf=A_t.size)
    inside = r < A_t.size - 1
    i = np.minimum(r.astype(np.int64), A_t.size - 2)
    f = r - i
    A = np.where(inside, A_t[i] + f * (A_t[i + 1] - A_t[i]), 0.0)
    H = np.where(inside, H_t[i] + f * (H_t[i + 1] - H_t[i]), 1.0)
    return mu_s * A + mu_d * H


def _list(idx, most: int = 8) -> str:
    shown = ", ".join(str(int(i)) for i in idx[:most])
    return shown + (f" and {idx.size - most} more" if idx.size > most else "")
