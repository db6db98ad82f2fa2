r"""The numerical core behind :meth:`persson.Model.friction`: grids, tables and the kernel calls.

:func:`solve` turns (surface, material, conditions) into G(q), P(q), d mu/d ln q, the cumulative hysteresis
friction, the temperature at each scale and a quadrature-error estimate per speed. The method
(:mod:`persson.engine.kernels`): angular integrals tabulated once per call on the modulus table (exact product
integration in log frequency), the contact weight S(P) P dG integrated exactly in G, and an embedded coarse-grid
estimate of the q-quadrature error. With a temperature effect the solver asks the effect for its settings
(``temperature_solver_options``, a :class:`~persson.engine.conditions.TemperatureSolverOptions`) and runs the
self-consistent flash temperature itself (:func:`run_temperature`, :func:`persson.engine.kernels.flash_kernel`).
"""

from __future__ import annotations

import contextlib
import contextvars
import functools
import math
import warnings
from collections import OrderedDict
from dataclasses import dataclass, replace

import numpy as np
from scipy.special import erfcx

from . import kernels as _kernels
from .conditions import Conditions, TemperatureSolverOptions
from ..errors import ConvergenceWarning, InputError
from .grid import GridSettings
from .jit import threaded
from ..notes import Note
from .quadrature import (cumulative_moment, moments_at_nodes, psd_breakpoints, psd_moment,  # noqa: F401
                         quadrature_rule)  # (public here too)
from .tabulate import ShiftTable, angular_table, relative_shifts, shift_table

__all__ = ["Solved", "Prepared", "solve", "prepare", "run_plain", "run_flash", "run_temperature",
           "temperature_options", "reuse_solutions", "friction_only", "quadrature_estimate", "table_temperature"]

#: Speeds below which a call runs on one thread (handing shares to threads costs more than it saves). The flash
#: solver costs milliseconds per speed, so it goes to threads from two speeds.
_PARALLEL_MIN_SPEEDS = 16
_PARALLEL_MIN_SPEEDS_FLASH = 2
#: Most halvings of the first wavevector step towards q0 with the flash temperature (see :func:`_graded_nodes`).
_MAX_GRADING = 30
#: Halvings of the first step with a per-scale modulus: the strain at the first node falls by 2^-10 ~ 1e-3.
_STRAIN_GRADING = 20


@dataclass(frozen=True, eq=False)
class Solved:
    r"""Solver output per speed (rows) and wavevector node (columns).

    Attributes
    ----------
    q : ndarray (n_q,)
        Wavevector nodes, rad/m.
    G, P, T_q, dmu, loss : ndarray (n_speed, n_q)
        Persson's G(q), P(q) = A(q)/A0, the temperature at scale q (deg C), d mu/d ln q and the loss integral
        int cos(phi) Im E dphi / ((1 - nu^2) sigma0).
    dG : ndarray (n_speed, n_q)
        dG/d ln q.
    ratio : ndarray (n_speed, n_q)
        R = d mu / (S(P) P dG) = 4 L / A, the smooth factor the contact weight multiplies.
    mu_cumulative : ndarray (n_speed, n_q)
        Hysteresis friction carried by the scales q0..q (the last column is ``mu``).
    mu : ndarray (n_speed,)
    error_estimate : ndarray (n_speed,)
        Estimated relative error of ``mu`` from the q quadrature (fine vs coarse grid).
    excited_layer : ndarray (n_speed,)
        Friction-weighted mean of 1/q, :math:`\int q^{-1} d\mu / \int d\mu`, m.
    converged : bool
    converged_each, iterations, residual : ndarray (n_speed,)
    """

    q: np.ndarray
    G: np.ndarray
    P: np.ndarray
    T_q: np.ndarray
    dmu: np.ndarray
    loss: np.ndarray
    dG: np.ndarray
    ratio: np.ndarray
    mu_cumulative: np.ndarray
    mu: np.ndarray
    error_estimate: np.ndarray
    excited_layer: np.ndarray
    converged: bool
    converged_each: np.ndarray
    iterations: np.ndarray
    residual: np.ndarray
    notes: tuple = ()


@dataclass(frozen=True, eq=False)
class Prepared:
    """Arrays the kernels need for one group of speeds sharing a modulus table.

    ``shape`` is None for an isotropic PSD. For an anisotropic one (:mod:`persson.engine.anisotropic`) every "speed"
    is one problem, a sliding direction at a speed, and ``shape`` gives the kernels its angular shape:
    ``shape.kernel(q, table)`` is the :class:`~persson.engine.kernel_arrays.AngularShape` on the nodes ``q`` and the
    grid of the angular table ``table``, ``shape.subset(problems)`` the shape of some of the problems.
    """

    q: np.ndarray
    x: np.ndarray
    lq10: np.ndarray
    C: np.ndarray
    q4C: np.ndarray
    quad: _kernels.QuadratureRule
    coarse: np.ndarray
    quad_coarse: _kernels.QuadratureRule
    coarser: np.ndarray | None  # None with the flash temperature
    quad_coarser: _kernels.QuadratureRule | None
    surface: object
    v: np.ndarray
    lv10: np.ndarray
    T0: np.ndarray
    pressure: np.ndarray
    scale: np.ndarray
    table: object
    shift: np.ndarray | None
    vshift: np.ndarray | None
    shift_table: object | None
    fq: np.ndarray
    gq: np.ndarray
    f_tab: np.ndarray
    g_tab: np.ndarray
    law: _kernels.ContactLaw
    modulus: object = None
    s_v: np.ndarray | None = None
    b_v: np.ndarray | None = None
    shape: object = None

    @property
    def n_speed(self) -> int:
        """Number of speeds (for an anisotropic PSD, of problems: a sliding direction at a speed)."""
        return self.v.size

    @functools.cached_property
    def kernel_nodes(self) -> _kernels.Nodes:
        """The nodes and the PSD on them, as the kernels take them (the rule is ``quad``)."""
        return _kernels.Nodes(q=self.q, x=self.x, lq10=self.lq10, q4C=self.q4C)

    @functools.cached_property
    def kernel_angular(self) -> _kernels.AngularTables:
        """The angular integrals of the modulus table, as the kernels take them."""
        return _angular_arrays(self.table)

    @functools.cached_property
    def kernel_shape(self) -> _kernels.AngularShape:
        """The angular shape of the PSD on the nodes, as the kernels take it (no basis functions: isotropic)."""
        if self.shape is None:
            return _kernels.AngularShape(direction=np.zeros(0, dtype=np.int64), weights=np.zeros((1, 1, 0)),
                                         v_re=np.zeros((1, 1, 0)), v_im=np.zeros((1, 1, 0)), v_l=np.zeros((1, 1, 0)))
        return self.shape.kernel(self.q, self.table)

    def nodes(self, idx: np.ndarray) -> "Prepared":
        """The same problem on the sub-grid of node indices ``idx`` (for the coarse-grid error estimate)."""
        per_node = self.f_tab.shape[0] == self.q.size
        x = self.x[idx]
        coarse = _coarse_indices(idx.size)
        return replace(self, q=self.q[idx], x=x, lq10=self.lq10[idx], C=self.C[idx], q4C=self.q4C[idx],
                       quad=quadrature_rule(self.surface, x), coarse=coarse,
                       quad_coarse=quadrature_rule(self.surface, x[coarse]), coarser=None, quad_coarser=None,
                       shift=None if self.shift is None else np.ascontiguousarray(self.shift[:, idx]),
                       vshift=None if self.vshift is None else np.ascontiguousarray(self.vshift[:, idx]),
                       fq=np.ascontiguousarray(self.fq[:, idx]), gq=np.ascontiguousarray(self.gq[:, idx]),
                       f_tab=np.ascontiguousarray(self.f_tab[idx]) if per_node else self.f_tab,
                       g_tab=np.ascontiguousarray(self.g_tab[idx]) if per_node else self.g_tab)

    def renode(self, speeds: np.ndarray, q: np.ndarray) -> "Prepared":
        """The speeds ``speeds`` alone on the nodes ``q`` (inside this problem's q range), with its tables."""
        return _assemble(self.surface, np.asarray(q, dtype=float), self.v[speeds], self.T0[speeds],
                         self.pressure[speeds], self.scale[speeds], self.table, self.shift_table, self.s_v[speeds],
                         self.b_v[speeds], self.modulus, self.law,
                         None if self.shape is None else self.shape.subset(speeds))


@contextlib.contextmanager
def reuse_solutions(memo: OrderedDict | None = None, size: int = 8):
    """Inside this context, :func:`solve` returns the stored solution of a problem it has solved before.

    A problem is the same when the surface and the material are the same objects, the conditions are equal
    (speeds, temperatures, pressures, wet) and the settings and the solver's effects (temperature, per-scale
    modulus) are equal by value. Effects that only add a friction term (adhesion) do not enter the solver, so a
    fit of their parameters, or of anything downstream of the solver, solves each set of conditions once.

    Parameters
    ----------
    memo : OrderedDict, optional
        The store, kept by the caller to reuse solutions across contexts (a new one by default). The stored
        arrays are shared between results: callers must not modify them in place.
    size : int
        Most problems kept (least recently used dropped first).
    """
    memo = OrderedDict() if memo is None else memo
    token = _MEMO.set((memo, int(size)))
    try:
        yield memo
    finally:
        _MEMO.reset(token)


@contextlib.contextmanager
def friction_only(*, share: bool = False):
    """Inside this context, :meth:`persson.Model.friction` skips the contact geometry: the mean separation and
    the penetration depth (their own quadrature over q, about a fifth of a plain solve) are left out, and the
    results carry None there, as they do for ``modulus_extrapolated_share`` (with its note) unless ``share`` is
    True. For callers that read the friction alone many times over, such as the fits of the diagnosis (and, with
    ``share``, their one-off predictions); everything else in the result is unchanged."""
    token = _FRICTION_ONLY.set(True)
    kept = _SHARE.set(bool(share))
    try:
        yield
    finally:
        _SHARE.reset(kept)
        _FRICTION_ONLY.reset(token)


@contextlib.contextmanager
def quadrature_estimate(enabled: bool):
    """Inside ``quadrature_estimate(False)``, :func:`solve` skips the built-in estimate of the q-quadrature error
    and the refinement it drives: every speed is solved on the base nodes alone (the sub-grids of the plain
    solve and the two coarse self-consistent solves of the flash temperature, about as much work again as the
    solve, are left out) and ``error_estimate`` is NaN (not estimated). A speed whose flash temperature did not
    converge is still solved again on refined nodes, and the nodes a steep temperature front needs are still
    inserted. Where the full solve refines no speed, mu is the same to the last bit (the estimate only reads the
    solution); where it would, mu differs from the full solve's by about the estimate.

    For the trial points of a search, whose reported point is solved again with the estimate (the fits of the
    diagnosis, :meth:`validation.fitting.Fitter.settle`). ``quadrature_estimate(True)`` restores the estimate
    inside such a context (e.g. for a table built once and reused by full solves). Solutions kept by
    :func:`reuse_solutions` are keyed by the setting."""
    token = _ESTIMATE.set(bool(enabled))
    try:
        yield
    finally:
        _ESTIMATE.reset(token)


def wants_contact_geometry() -> bool:
    """False inside :func:`friction_only`."""
    return not _FRICTION_ONLY.get()


def wants_extrapolated_share() -> bool:
    """False inside :func:`friction_only` unless it was asked to keep the share."""
    return _SHARE.get()


#: Set by :func:`quadrature_estimate`.
_ESTIMATE: contextvars.ContextVar = contextvars.ContextVar("persson_quadrature_estimate", default=True)

#: Set by :func:`friction_only`.
_FRICTION_ONLY: contextvars.ContextVar = contextvars.ContextVar("persson_friction_only", default=False)
_SHARE: contextvars.ContextVar = contextvars.ContextVar("persson_extrapolated_share", default=True)

#: The store of :func:`reuse_solutions` in the current context (None: every call solves).
_MEMO: contextvars.ContextVar = contextvars.ContextVar("persson_solver_memo", default=None)


def solve(surface, material, cond: Conditions, grid: GridSettings, nu: float, gamma: float, thermal,
          correction: str | None = None, modulus=None) -> Solved:
    """Solve every speed of ``cond``, grouped by temperature when the material cannot shift between them.

    Speeds at different temperatures share one modulus table through time-temperature superposition
    (``material.log10_aT``); a material without it is evaluated at each distinct temperature separately.
    ``correction`` names an area correction of :mod:`persson.contact.corrections` (None: Persson's erf law);
    ``modulus`` is an effect whose ``modulus_factors`` give per-scale factors on E' and E'' (strain softening at
    the local strain of each scale), or None. Inside :func:`reuse_solutions` a problem solved before is not
    solved again.
    """
    active = _MEMO.get()
    key = None if active is None else _memo_key(surface, material, cond, grid, nu, gamma, thermal, correction,
                                                 modulus)
    if key is not None:
        memo, size = active
        hit = memo.get(key)
        if hit is not None:
            memo.move_to_end(key)
            return hit[2]
        solved = _solve(surface, material, cond, grid, nu, gamma, thermal, correction, modulus)
        memo[key] = (surface, material, solved, {})  # the objects stay alive, so their ids stay theirs
        while len(memo) > size:
            memo.popitem(last=False)
        return solved
    return _solve(surface, material, cond, grid, nu, gamma, thermal, correction, modulus)


def derived(solved: Solved, key: tuple, compute):
    """``compute()``, a quantity derived from ``solved`` alone (e.g. the mean separation), kept with the solution
    inside :func:`reuse_solutions` so that a reused solution does not derive it again."""
    active = _MEMO.get()
    entry = None if active is None else next((e for e in active[0].values() if e[2] is solved), None)
    if entry is None:
        return compute()
    if key not in entry[3]:
        entry[3][key] = compute()
    return entry[3][key]


def _memo_key(surface, material, cond, grid, nu, gamma, thermal, correction, modulus):
    """The key of a problem for :func:`reuse_solutions` (None when it cannot be keyed, e.g. an unhashable
    effect or free-form ``extra`` conditions)."""
    if cond.extra:
        return None
    shape = cond.speed.shape
    arrays = tuple(np.ascontiguousarray(np.broadcast_to(np.asarray(a, dtype=float), shape)).tobytes()
                   for a in (cond.speed, cond.temperature, cond.pressure, cond.nominal_pressure))
    key = (id(surface), id(material), arrays, bool(cond.wet), grid, float(nu), float(gamma), thermal, correction,
           modulus, _ESTIMATE.get())
    try:
        hash(key)
    except TypeError:
        return None
    return key


def _solve(surface, material, cond, grid, nu, gamma, thermal, correction, modulus) -> Solved:
    shape = cond.speed.shape
    T = np.broadcast_to(np.asarray(cond.temperature, dtype=float), shape)
    if np.all(T == T[0]) or hasattr(material, "log10_aT"):
        return _solve_group(surface, material, cond, grid, nu, gamma, thermal, correction, modulus)
    p = np.broadcast_to(np.asarray(cond.pressure, dtype=float), shape)
    p_nom = np.broadcast_to(np.asarray(cond.nominal_pressure, dtype=float), shape)
    parts = []
    for t in np.unique(T):
        idx = np.flatnonzero(T == t)
        sub = cond.replace(speed=cond.speed[idx], temperature=T[idx], pressure=p[idx], nominal_pressure=p_nom[idx])
        parts.append((idx, _solve_group(surface, material, sub, grid, nu, gamma, thermal, correction, modulus)))
    n = T.size
    first = parts[0][1]
    merged = {}
    for name in _PER_SCALE + _PER_SPEED:
        ref = getattr(first, name)
        arr = np.empty((n,) + ref.shape[1:], dtype=ref.dtype)
        for idx, part in parts:
            arr[idx] = getattr(part, name)
        merged[name] = arr
    notes = tuple(dict.fromkeys(n for _, part in parts for n in part.notes))
    return Solved(q=first.q, converged=bool(merged["converged_each"].all()), notes=notes, **merged)


def _solve_group(surface, material, cond, grid, nu, gamma, thermal, correction, modulus, shape=None) -> Solved:
    """Solve, then re-solve the speeds whose error estimate exceeds ``grid.tolerance / 3`` on grids refined 2x, 4x, ...
    (up to ``grid.max_refinement`` halvings of every interval): the grid adapts per speed where the integrand
    is hard (e.g. a narrow loss peak swept by a steep flash temperature), and the per-scale arrays of a refined
    speed are its values at the base nodes, which every refined grid contains. ``shape``: the angular shape of an
    anisotropic PSD, whose problems (a direction at a speed) are the speeds of ``cond`` (see :class:`Prepared`)."""
    solved = _solve_once(surface, material, cond, grid, nu, gamma, thermal, correction, modulus, 0, shape=shape)
    for level in range(1, grid.max_refinement + 1):
        # aim a factor 3 below the tolerance: the estimate is within a factor 3 of the true error
        # (a flash temperature that did not converge is tried again on the finer grid too)
        bad = np.flatnonzero((solved.error_estimate > grid.tolerance / _SAFETY) | ~solved.converged_each)
        if bad.size == 0:
            break
        # with the shift table the coarser solve needed, so that a hot speed is not solved clamped first again
        rise = _rise(grid, solved.T_q[bad], np.broadcast_to(np.asarray(cond.temperature, dtype=float),
                                                              cond.speed.shape)[bad])
        fine = _solve_once(surface, material, _subset(cond, bad), grid, nu, gamma, thermal, correction, modulus,
                           level, solved.q, rise=rise, shape=None if shape is None else shape.subset(bad))
        solved = _merge(solved, bad, fine, 2**level)
    return solved


def _solve_once(surface, material, cond, grid, nu, gamma, thermal, correction, modulus, refine,
                q_base=None, rise=None, shape=None) -> Solved:
    """One solve on the grid's nodes refined ``refine`` times. With the flash temperature, the speeds whose
    temperature leaves the shift table (which covers ``rise``, by default ``grid.max_temperature_rise``, above the
    background) are solved again with a wider table (:func:`_rise`), up to ``_RISE_WIDENING`` times
    ``grid.max_temperature_rise``: a table clamped below the solution's temperature would give the modulus a kink
    there, an error of the model's input that no refinement of q removes and the error estimate cannot see."""
    rise = grid.max_temperature_rise if rise is None else rise
    estimate = _ESTIMATE.get()
    table_grid = grid if rise == grid.max_temperature_rise else replace(grid, max_temperature_rise=rise)
    prep = prepare(surface, material, cond, table_grid, nu, gamma=gamma, correction=correction,
                   flash=thermal is not None, modulus=modulus, refine=refine, nodes=q_base, shape=shape)
    if thermal is None:
        solved = run_plain(prep, estimate=estimate)
        return solved if estimate else replace(solved, error_estimate=np.full(prep.n_speed, np.nan))
    options = temperature_options(thermal, prep, material)
    solved = run_temperature(prep, options, estimate=estimate)
    T0 = prep.T0
    limit = _RISE_WIDENING * grid.max_temperature_rise
    prep_top = np.full(T0.size, float(T0.max()) + grid.max_temperature_rise)  # the table of the settings
    top = np.full(T0.size, prep.shift_table.T_hi)  # each speed's table top
    while rise < limit:
        hot = np.flatnonzero(solved.T_q.max(axis=1) > top)
        if hot.size == 0:
            break
        rise = min(limit, max(2.0 * rise, _rise(grid, solved.T_q[hot], T0[hot])))
        sub = _subset(cond, hot)
        # on the first solve's nodes, so that the results merge node by node
        prep = prepare(surface, material, sub, replace(grid, max_temperature_rise=rise), nu, gamma=gamma,
                       correction=correction, flash=True, modulus=modulus, nodes=solved.q,
                       shape=None if shape is None else shape.subset(hot))
        solved = _merge(solved, hot, run_temperature(prep, options, estimate=estimate), 1)
        top[hot] = prep.shift_table.T_hi
    widened = (top > prep_top) & (solved.T_q.max(axis=1) > prep_top)
    if np.any(widened):
        solved = replace(solved, notes=solved.notes + (Note(
            f"flash temperature up to {float(solved.T_q.max()):.4g} C at {int(widened.sum())} of {widened.size} "
            f"speeds, above the {grid.max_temperature_rise:g} K rise the shift table covers at first (widened): far "
            "above any measured isotherm, the modulus there is the shift law's extrapolation", "extrapolated"),))
    over = solved.T_q.max(axis=1) > top
    if np.any(over):
        msg = (f"flash temperature exceeds the tabulated range at {int(over.sum())} of {over.size} speeds "
               f"(T > {float(top[over].min()):g} C); the modulus is clamped there: raise "
               "GridSettings.max_temperature_rise")
        warnings.warn(msg, ConvergenceWarning, stacklevel=5)
        solved = replace(solved, notes=solved.notes + (Note(msg, "convergence"),))
    return solved


#: Most the shift table is widened, as a multiple of ``GridSettings.max_temperature_rise``, where the flash
#: temperature leaves it (:func:`_solve_once`).
_RISE_WIDENING = 8.0


def _rise(grid: GridSettings, T_q: np.ndarray, T0: np.ndarray) -> float:
    """The temperature rise, K, a shift table needs for the profiles ``T_q`` (n_speed, n_q) above the background
    temperatures ``T0``: the setting, or 1.25x the rise reached, at most ``_RISE_WIDENING`` x the setting."""
    need = 1.25 * float(np.max(T_q) - np.min(T0)) if T_q.size else 0.0
    return min(_RISE_WIDENING * grid.max_temperature_rise, max(grid.max_temperature_rise, need))


def _subset(cond: Conditions, idx: np.ndarray) -> Conditions:
    n = cond.speed.size

    def pick(a):
        return a if np.ndim(a) == 0 else np.broadcast_to(np.asarray(a, dtype=float), (n,))[idx]

    return cond.replace(speed=cond.speed[idx], temperature=pick(cond.temperature), pressure=pick(cond.pressure),
                        nominal_pressure=pick(cond.nominal_pressure))


def _merge(base: Solved, idx: np.ndarray, fine: Solved, stride: int) -> Solved:
    """``base`` with the speeds ``idx`` replaced by ``fine`` (solved on a grid ``stride`` times as dense)."""
    out = {}
    for name in _PER_SCALE:
        a = getattr(base, name).copy()
        a[idx] = getattr(fine, name)[:, ::stride]
        out[name] = a
    for name in _PER_SPEED:
        a = getattr(base, name).copy()
        a[idx] = getattr(fine, name)
        out[name] = a
    notes = tuple(dict.fromkeys(base.notes + fine.notes))
    return Solved(q=base.q, converged=bool(out["converged_each"].all()), notes=notes, **out)


_PER_SCALE = ("G", "P", "T_q", "dmu", "loss", "dG", "ratio", "mu_cumulative")
_SAFETY = 3.0
_PER_SPEED = ("mu", "error_estimate", "excited_layer", "converged_each", "iterations", "residual")


def prepare(surface, material, cond: Conditions, grid: GridSettings, nu: float, *, gamma: float = 0.5,
            correction: str | None = None, flash: bool = False, modulus=None, refine: int = 0,
            nodes=None, shape=None) -> Prepared:
    """Nodes, PSD, modulus tables and temperature shifts for the speeds of ``cond``.

    ``refine`` halves every interval that many times (the adaptive refinement of :func:`solve`), of ``nodes``
    when given (the nodes of a first solve) instead of the grid's.
    With the flash temperature, nodes graded geometrically towards q0 are added (:func:`_graded_nodes`): there
    T_q rises like the square root of q - q0 (the heat source is proportional to P, which falls like
    (q - q0)^(-1/2) where G grows linearly from zero), a non-smooth start that the regular grid would
    integrate with first-order accuracy only. ``shape``: the angular shape of an anisotropic PSD (see
    :class:`Prepared`).

    Raises
    ------
    InputError
        Bad q range, a PSD that is not finite and >= 0, a pressure <= 0 after the effects, a bad modulus.
    """
    q_lo, q_hi = (float(x) for x in surface.q_range)
    if not (0 < q_lo < q_hi):
        raise InputError(f"surface: expected 0 < q0 < q1 after the effects, got ({q_lo:g}, {q_hi:g}) rad/m")
    q = grid.q_nodes(q_lo, q_hi)
    v = np.ascontiguousarray(cond.speed, dtype=float)
    lv10 = np.log10(v)
    T0 = np.ascontiguousarray(np.broadcast_to(np.asarray(cond.temperature, dtype=float), v.shape))
    pressure = np.ascontiguousarray(np.broadcast_to(np.asarray(cond.pressure, dtype=float), v.shape))
    if not np.all(np.isfinite(pressure)) or np.any(pressure <= 0):
        raise InputError("pressure: the pressure on the asperity contact must stay > 0 Pa after the effects")
    scale = np.ascontiguousarray(1.0 / ((1.0 - nu * nu) * pressure))
    # one modulus table at T_table; other temperatures are shifted onto it
    T_table = table_temperature(material, T0)
    s_v, b_v = relative_shifts(material, T0, T_table)
    if flash:
        # nodes on the lattice k * step, whatever the call's temperatures: a speed's shifts then do not depend on
        # the other speeds of the call
        step = grid.temperature_step
        stab = shift_table(material, T_table, step * math.floor(float(T0.min()) / step),
                           float(T0.max()) + grid.max_temperature_rise, step)
        s_lo, s_hi = float(stab.shift.min()), float(stab.shift.max())
    else:
        s_lo, s_hi = float(s_v.min()), float(s_v.max())
        stab = None
    table = angular_table(material, T_table, math.log10(q_lo) + lv10.min() + s_lo,
                          math.log10(q_hi) + lv10.max() + s_hi, grid.omega_per_decade)
    if nodes is not None:
        q = np.asarray(nodes, dtype=float)
    elif flash:
        q = _graded_nodes(q, surface, table, lv10 + s_v, b_v, scale)
    if modulus is not None and nodes is None:
        # the local strain kappa xi(q) rises like sqrt(q - q0) from q0 (xi^2 is an integral from q0), so the
        # modulus factors start non-smoothly there: grade the first interval as for the flash temperature
        x0, h = math.log(q[0]), math.log(q[1] / q[0])
        q = np.unique(np.concatenate([q, np.exp(x0 + h * 2.0 ** -np.arange(1, _STRAIN_GRADING + 1))]))
    if refine:
        # 2^refine - 1 geometric points inside every interval: the nodes above are every 2^refine-th node
        k = 2**refine
        x = np.log(q)
        t = np.arange(k) / k
        q = np.exp(np.append((x[:-1, None] + np.diff(x)[:, None] * t).ravel(), x[-1]))
    return _assemble(surface, q, v, T0, pressure, scale, table, stab, s_v, b_v, modulus,
                     contact_law(gamma, correction), shape)


def table_temperature(material, T) -> float:
    r"""The temperature of the modulus table of a call at the temperatures ``T`` (deg C).

    A material whose modulus is a master curve, :math:`E(\omega, T) = b_T E(\omega a_T, T_{ref})` (it has
    ``log10_aT`` and a reference temperature ``T_ref``: :class:`materials.MasterCurve`, :class:`materials.Prony`
    with a shift law, their tabulated and strain-softened forms), is tabulated at ``T_ref`` whatever the call's
    temperatures: the table is then the same in every call, exact at any temperature (the law is the material's
    own: time-temperature superposition, M. L. Williams, R. F. Landel, J. D. Ferry, J. Am. Chem. Soc. 77, 3701
    (1955)), and a speed's friction does not depend on the other speeds and temperatures of its call. Otherwise the
    table is at the call's temperature, or at the median of its temperatures when they differ (a material with
    ``log10_aT`` and no ``T_ref`` is shifted onto it by time-temperature superposition; one without
    ``log10_aT`` is solved at each temperature separately).

    Parameters
    ----------
    material : object
        The material of the call.
    T : ndarray
        The temperatures of the call's speeds, deg C.

    Returns
    -------
    float
        The table temperature, deg C.
    """
    T = np.asarray(T, dtype=float)
    T_ref = getattr(material, "T_ref", None) if hasattr(material, "log10_aT") else None
    if isinstance(T_ref, (int, float, np.floating)) and not isinstance(T_ref, bool) and math.isfinite(T_ref):
        return float(T_ref)
    return float(T.flat[0]) if np.all(T == T.flat[0]) else float(np.median(T))


def _assemble(surface, q, v, T0, pressure, scale, table, stab, s_v, b_v, modulus, law, shape=None) -> Prepared:
    """The :class:`Prepared` problem on the nodes ``q`` from its tables (``stab`` is None without the flash
    temperature) and per-speed arrays (``s_v``, ``b_v``: the speeds' background shifts onto the table)."""
    flash = stab is not None
    C = np.asarray(surface.C(q), dtype=float)
    if C.shape != q.shape or not np.all(np.isfinite(C)) or np.any(C < 0):
        raise InputError("surface: C(q) must return finite values >= 0 m^4 of the shape of q")
    x = np.log(q)
    nq, nv = q.size, v.size
    shifts = None if flash else np.ascontiguousarray(np.repeat(s_v[:, None], nq, axis=1))
    vshifts = None if flash else np.ascontiguousarray(np.repeat(b_v[:, None], nq, axis=1))
    fq = gq = np.ones((nv, nq))
    f_tab = g_tab = np.ones((1, 2))
    if modulus is not None:
        slope = np.sqrt(moments_at_nodes(surface, q, 3))
        if flash:
            T_grid = stab.T_lo + stab.dT * np.arange(stab.shift.size)
            f_tab, g_tab = _factors(modulus, slope[:, None], T_grid[None, :], (nq, T_grid.size))
        else:
            fq, gq = _factors(modulus, slope[None, :], T0[:, None], (nv, nq))
    coarse = _coarse_indices(nq)
    # the coarser grid serves the plain path's three-level estimate only (see run_flash)
    coarser = None if flash else _coarser_indices(nq)
    return Prepared(q=q, x=x, lq10=np.log10(q), C=C, q4C=q**4 * C, quad=quadrature_rule(surface, x), coarse=coarse,
                    quad_coarse=quadrature_rule(surface, x[coarse]), coarser=coarser,
                    quad_coarser=None if flash else quadrature_rule(surface, x[coarser]), surface=surface, v=v,
                    lv10=np.log10(v), T0=T0, pressure=pressure, scale=scale, table=table, shift=shifts,
                    vshift=vshifts, shift_table=stab, fq=fq, gq=gq, f_tab=f_tab, g_tab=g_tab, law=law,
                    modulus=modulus, s_v=s_v, b_v=b_v, shape=shape)


def _graded_nodes(q: np.ndarray, surface, table, lw_speed: np.ndarray, ln_b: np.ndarray,
                  scale: np.ndarray) -> np.ndarray:
    r"""``q`` plus nodes :math:`q_0 e^{h 2^{-k}}`, k = 1..L, graded towards q0 (h the first step in ln q).

    L is the number of halvings from h down to the scale :math:`1/g_0` where G reaches 1, with
    :math:`g_0 = dG/d\ln q` at q0 for the stiffest speed (the background temperature): below it G < 1, P = 1 and
    the temperature rises linearly, which the quadratic rules integrate exactly.
    """
    x0, h = math.log(q[0]), math.log(q[1] / q[0])
    c0 = q[0] ** 4 * float(np.asarray(surface.C(q[0]), dtype=float))
    # A_re + A_im at log10(q0 v a_T) of every speed, by the kernels' cubic interpolation of the table's logs
    # (vectorised: a fit's table solves have thousands of speeds); only the number of halvings depends on it
    x = (math.log10(q[0]) + np.asarray(lw_speed, dtype=float) - table.lw0) * (1.0 / table.dlw)
    ends = _cubic_at(table.ln_are, x), _cubic_at(table.ln_aim, x)
    g0 = float(np.max(0.125 * c0 * np.exp(2.0 * np.asarray(ln_b, dtype=float)) * (np.exp(ends[0]) + np.exp(ends[1]))
                      * np.asarray(scale, dtype=float) ** 2, initial=0.0))
    levels = int(min(_MAX_GRADING, max(0.0, math.ceil(math.log2(max(g0 * h, 1.0))) + 1)))
    if levels == 0:
        return q
    return np.unique(np.concatenate([q, np.exp(x0 + h * 2.0 ** -np.arange(1, levels + 1))]))


def _cubic_at(tab: np.ndarray, x: np.ndarray) -> np.ndarray:
    """``tab`` at the fractional indices ``x`` by four-point Lagrange interpolation, clamped to the ends: the
    vectorised form of :func:`persson.engine.kernels._cubic`."""
    n = tab.size
    i = np.clip(np.floor(x).astype(np.int64), 0, n - 2)
    t = x - i
    c = (-t * (t - 1.0) * (t - 2.0) / 6.0 * tab[np.maximum(i - 1, 0)]
         + (t + 1.0) * (t - 1.0) * (t - 2.0) / 2.0 * tab[i]
         - (t + 1.0) * t * (t - 2.0) / 2.0 * tab[i + 1]
         + (t + 1.0) * t * (t - 1.0) / 6.0 * tab[np.minimum(i + 2, n - 1)])
    return np.where(x <= 0.0, tab[0], np.where(x >= n - 1, tab[n - 1], c))


def run_plain(prep: Prepared, *, estimate: bool = True) -> Solved:
    """Hysteresis friction and contact area at the background temperature of each speed
    (:func:`persson.engine.kernels.friction_kernel`), with the three-level error estimate (``estimate=False``:
    without it, the error estimate zero; the anisotropic engine's coarser angular grids need mu alone)."""
    nv, nq = prep.n_speed, prep.q.size
    out = _outputs(nv, nq)
    mu_c = np.zeros(nv)
    mu_cc = np.zeros(nv)
    skip = np.zeros(0, dtype=np.int64)
    threaded(_kernels.friction_kernel, nv, min_items=_PARALLEL_MIN_SPEEDS, nodes=prep.kernel_nodes, rule=prep.quad,
             speeds=_kernels.SpeedFactors(lv10=prep.lv10, scale=prep.scale, shift=prep.shift, vshift=prep.vshift,
                                          f=prep.fq, g=prep.gq),
             angular=prep.kernel_angular, shape=prep.kernel_shape, law=prep.law,
             coarse=prep.coarse if estimate else skip, coarse_rule=prep.quad_coarse,
             coarser=prep.coarser if estimate else skip, coarser_rule=prep.quad_coarser, out=out, mu_coarse=mu_c,
             mu_coarser=mu_cc)
    T_q = np.repeat(prep.T0[:, None], nq, axis=1)
    ok = np.ones(nv, dtype=bool)
    err = _relative_error(out.mu, mu_c, mu_cc) if estimate else np.zeros(nv)
    return _solved(prep, out, T_q, err, ok, np.zeros(nv, dtype=np.int64), np.zeros(nv))


def temperature_options(effect, prep: Prepared, material) -> TemperatureSolverOptions:
    """The flash-temperature settings of the temperature effect ``effect`` for the problem ``prep``
    (its ``temperature_solver_options`` hook, given the surface and the material after the transform hooks and
    the nodes of ``prep``).

    Raises
    ------
    InputError
        If the effect gives no :class:`~persson.engine.conditions.TemperatureSolverOptions`.
    """
    options = effect.temperature_solver_options(surface=prep.surface, material=material, q=prep.q)
    if not isinstance(options, TemperatureSolverOptions):
        raise InputError(f"effect {getattr(effect, 'name', effect)!r}: an effect with solver_role = 'temperature' "
                         "must return persson.effects.TemperatureSolverOptions from temperature_solver_options(), "
                         f"got {options!r}")
    return options


def run_temperature(prep: Prepared, options: TemperatureSolverOptions, *, estimate: bool = True) -> Solved:
    """The self-consistent flash temperature of every speed of ``prep`` with the settings ``options``
    (:func:`run_flash`): per speed the contact time d / v and the heat factor sigma0 / (rho c_p); the result
    carries the options' notes. ``estimate=False``: no error estimate (NaN, see :func:`quadrature_estimate`)."""
    solved = run_flash(prep, q_m=options.q_m, a_t0=options.diffusivity * options.contact_diameter / prep.v,
                       diffusivity=options.diffusivity, heat_factor=prep.pressure / options.heat_capacity,
                       tol=options.tol, max_iter=int(options.max_iter), estimate=estimate)
    return replace(solved, notes=solved.notes + options.notes) if options.notes else solved


def run_flash(prep: Prepared, *, q_m: float, a_t0: np.ndarray, diffusivity: float,
              heat_factor: np.ndarray, tol: float, max_iter: int, estimate: bool = True) -> Solved:
    """The self-consistent flash temperature (:func:`persson.engine.kernels._flash_speed`) for every speed,
    with its nodes refined where a temperature front is steep and its two-grid error estimate.

    Parameters
    ----------
    prep : Prepared
        From :func:`prepare` with ``flash=True``.
    q_m : float
        Wavevector of the macro-asperity contact regions, rad/m (P(q_m) normalises the heat source).
    a_t0 : ndarray (n_speed,)
        D t0 per speed, m^2 (t0 the contact time of a macro-asperity contact region).
    diffusivity : float
        Thermal diffusivity D, m^2/s.
    heat_factor : ndarray (n_speed,)
        sigma0 / (rho c_p) per speed, K.
    tol : float
        Convergence tolerance on max |Delta T|, K.
    max_iter : int
        Iterations per start of the fixed point.
    estimate : bool
        Whether to estimate the error (:func:`_flash_error`); False: the error estimate is NaN (not estimated).
    """
    args = (q_m, a_t0, diffusivity, heat_factor, tol, max_iter)
    out, T_q, it, res = _flash(prep, *args)
    err = _flash_error(prep, out.mu, T_q, res < tol, args) if estimate else np.full(prep.n_speed, np.nan)
    budget = _FRONT_STEP * float(np.max(np.diff(prep.lq10)))
    # one vectorised test for all speeds; only the few with a steep front pay for the per-speed solves
    jump = np.abs(np.diff(_reduced_frequency(prep, prep.x, T_q), axis=-1))
    steep = np.any(jump > _FRONT_MARGIN * budget, axis=1)
    for s in np.flatnonzero(steep):
        _resolve_front(prep, s, args, budget, out, T_q, it, res, err if estimate else None)
    return _solved(prep, out, T_q, err, res < tol, it, res)


#: Largest change of the reduced frequency log10(q a_T(T_q)) across one interval, in units of the grid's step in
#: log10 q, before :func:`run_flash` inserts nodes (:func:`_front_nodes`).
_FRONT_STEP = 4.0
#: An interval is cut only where the change exceeds this many budgets (a settled front adds no nodes again).
_FRONT_MARGIN = 1.5
#: Most rounds of node insertion per speed (the front moves as it is resolved; it settles in 2-4 rounds).
_FRONT_ROUNDS = 6


def _front_nodes(prep: Prepared, x: np.ndarray, T: np.ndarray, budget: float) -> np.ndarray:
    r"""Nodes to add so that the reduced frequency changes by at most ``budget`` decades per interval.

    With the flash temperature the integrands depend on q through the modulus at the reduced frequency
    :math:`\log_{10}(q\,v\,a_T(T_q))`. Where :math:`T_q` climbs steeply (a self-consistent heating front: on a
    real road 100-200 K within half a decade of q, with WLF shifts of 0.3 decade per K) this frequency sweeps many
    decades per interval of a grid that is uniform in ln q, and the loss peak falls between the nodes: on such a
    road 24, 48 and 96 nodes per decade gave mu 30-100 %, 17 % and 12 % high, and 192 or more agreed to 1e-5.
    Intervals whose change exceeds ``_FRONT_MARGIN`` x ``budget`` (the margin keeps a settled front from adding
    nodes again) are cut into ceil(change / ``budget``) log-uniform parts; returns the new nodes' ln q.
    """
    d = np.abs(np.diff(_reduced_frequency(prep, x, T)))
    bad = np.flatnonzero(d > _FRONT_MARGIN * budget)
    if bad.size == 0:
        return np.empty(0)
    parts = np.ceil(d[bad] / budget).astype(np.int64)
    return np.concatenate([x[i] + (x[i + 1] - x[i]) * np.arange(1, k) / k for i, k in zip(bad, parts)])


def _reduced_frequency(prep: Prepared, x: np.ndarray, T: np.ndarray) -> np.ndarray:
    """log10(q a_T(T_q)) relative to the table temperature at ln q = ``x`` (any leading shape of ``T``), by the
    same shift table the kernel interpolates."""
    st = prep.shift_table
    return x / math.log(10.0) + np.interp(T, st.T_lo + st.dT * np.arange(st.shift.size), st.shift)


def _resolve_front(prep, s, args, budget, out, T_q, it, res, err):
    """Solve speed ``s`` again on nodes refined where its temperature front is steep (:func:`_front_nodes`),
    round by round until the front is resolved, and write its results at the nodes of ``prep`` (all kept) into
    ``out``, ``T_q``, ``it``, ``res`` and ``err`` (None: not estimated)."""
    q_m, a_t0, D, heat_factor, tol, max_iter = args
    sub_args = (q_m, a_t0[[s]], D, heat_factor[[s]], tol, max_iter)
    x = prep.x
    new = _front_nodes(prep, x, T_q[s], budget)  # not empty: the caller found the front steep
    Ts, ok = T_q[[s]], res[s] < tol
    for _ in range(_FRONT_ROUNDS):
        x_old, x = x, np.union1d(x, new)
        sub = prep.renode(np.array([s]), np.exp(x))
        # from the last round's temperature where it converged (the front moves little between rounds)
        start = np.interp(x, x_old, Ts[0])[None, :] if ok else None
        o, Ts, its, rs = _flash(sub, *sub_args, T_start=start)
        if start is not None and not rs[0] < tol:  # rare: again from T0, as the first solve
            o, Ts, its, rs = _flash(sub, *sub_args)
        ok = rs[0] < tol
        new = _front_nodes(prep, x, Ts[0], budget)
        if new.size == 0:
            break
    at = np.searchsorted(x, prep.x)  # the base nodes are kept exactly (ln q values copied, not recomputed)
    for name in _SCALE_KEYS:
        getattr(out, name)[s] = getattr(o, name)[0, at]
    out.mu[s], out.layer[s] = o.mu[0], o.layer[0]
    T_q[s], it[s], res[s] = Ts[0, at], its[0], rs[0]
    if err is not None:
        err[s] = _flash_error(sub, o.mu, Ts, rs < tol, sub_args)[0]


def _flash_error(prep: Prepared, mu: np.ndarray, T_q: np.ndarray, ok: np.ndarray, args: tuple) -> np.ndarray:
    r"""The estimated relative error of the flash-temperature friction ``mu`` on the nodes of ``prep`` (temperature
    profiles ``T_q``, converged where ``ok``): the root mean square of the two-level estimates
    (:func:`_relative_error`) from the even-numbered and from the odd-numbered nodes (each with both end points),
    plus the error of the temperature tables (:func:`_table_error`),

    .. math:: \varepsilon = \sqrt{\tfrac12\left(\varepsilon_{\rm even}^2 + \varepsilon_{\rm odd}^2\right)}
              + \varepsilon_T.

    Two levels only: a self-consistent temperature can rise by 100 K within a decade of q (heating softens the
    rubber, which raises the heating), and on every fourth node that front is often unresolved, so a third level
    read 100-1000x high on a real road (28 of 30 converged speeds flagged). A single coarse grid, on the other
    hand, often agrees with the fine one by accident before the grids reach the asymptotic range (the error
    changes sign between them): over the regime of ``benchmarks/accuracy.py``, without refinement, the even nodes
    alone read more than 3x low at 22 of 878 conditions with errors above 1e-6, the two interleaved grids together
    at 4: three speeds whose temperature did not converge (they are refined, :func:`_solve_group`) and one whose
    modulus was clamped at the top of the shift table (now widened, :func:`_solve_once`). Every grid reads the
    same temperature tables, so their error adds to the quadrature's: the two errors have different causes and
    may add up.

    Each coarse solve starts from the fine solution at its nodes where it converged, so that the coarse solve
    converges in a few iterations; from T0 where not (a coarse solve started from a fine non-solution stays near
    it, and the estimate would read small).
    """
    tol = args[4]
    T_start = np.where(ok[:, None], T_q, prep.T0[:, None])
    err = []
    for idx in (prep.coarse, _odd_indices(prep.q.size)):
        sub = prep.nodes(idx)
        out, T_c, _, res = _flash(sub, *args, T_start=T_start[:, idx])
        mu_c = out.mu
        if idx is prep.coarse:  # the tables' error, on the even-numbered nodes (half the cost of the fine ones)
            table = _table_error(sub, mu_c, T_c, res < tol, mu)
            table = _table_feedback(sub, mu_c, T_c, res < tol, mu, args, table)
        if np.any(res >= tol):  # rare: a warm start that did not converge; again from T0, as the fine solve
            mu_c = np.where(res < tol, mu_c, _flash(sub, *args)[0].mu)
        err.append(_relative_error(mu, mu_c))
    return np.sqrt(0.5 * (err[0] ** 2 + err[1] ** 2)) + table


def _table_error(prep: Prepared, mu: np.ndarray, T_q: np.ndarray, ok: np.ndarray, mu_ref: np.ndarray) -> np.ndarray:
    r"""The relative error (relative to ``mu_ref``) that the temperature tables add to the flash-temperature
    friction ``mu`` on the nodes of ``prep`` at its converged temperature profiles ``T_q`` (n_speed, n_q; rows where
    ``ok``, 0 elsewhere): ``mu`` against the friction on the same nodes with every table (log10 a_T, ln b_T and
    per-scale modulus factors) interpolated quadratically instead of linearly between its nodes,

    .. math:: \varepsilon_T = \left|\mu[f_{\rm lin} + \tfrac12 t(t-1)\,\Delta^2 f] - \mu[f_{\rm lin}]\right|
              / |\mu_{\rm ref}|,

    t the fraction of the table step h at each node's temperature and :math:`\Delta^2 f` the table's second
    difference (mean of the two about the step). Linear interpolation errs by :math:`\tfrac12 t(1-t) h^2 f''`
    (K. E. Atkinson, An Introduction to Numerical Analysis, 2nd ed., Wiley 1989, Thm. 3.2), always to the same side
    where f is convex, and :math:`\Delta^2 f = h^2 f'' + O(h^4)`: for the WLF law
    :math:`f'' = 2 C_1 C_2 / (C_2 + T - T_{ref})^3` with the steep constants C1 = 10.2, C2 = 86.4 K, 40 K below
    T_ref, the error is up to 1.4e-4 decade at h = 0.25 K. The quadrature estimate cannot see it: every grid
    reads the same tables.

    One evaluation of the friction per speed on a fixed profile (no fixed-point iteration), on the even-numbered
    nodes of the error estimate (about 5 % of the flash solve): the profile is not solved again with the
    corrected tables, so the heating's feedback (a stiffer rubber heats differently, which moves the modulus
    further) is left out; near a thermal runaway it amplifies the error (see ``docs/conventions.md``). Solving
    again would cost a warm-started flash solve per speed (about a third of the whole solve).
    """
    st = prep.shift_table
    nv, nq = T_q.shape
    if st is None or not np.any(ok):
        return np.zeros(nv)
    # a speed whose temperature did not converge is refined anyway: evaluated at T0, its error left at 0
    x = (np.where(ok[:, None], T_q, prep.T0[:, None]) - st.T_lo) / st.dT
    (shift, d_shift), (vshift, d_vshift) = (_between_nodes(tab[None, :], x) for tab in (st.shift, st.vshift))
    (f, d_f), (g, d_g) = _between_nodes(prep.f_tab, x), _between_nodes(prep.g_tab, x)
    mu_quadratic = _friction_at(prep, shift + d_shift, vshift + d_vshift, f + d_f, g + d_g)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.abs(mu_quadratic - mu) / np.abs(mu_ref)
    return np.where(ok & (np.abs(mu_ref) > 0), rel, 0.0)


#: Relative size of the temperature tables' error (:func:`_table_error`, on a fixed profile) above which the
#: heating's feedback on it is measured (:func:`_table_feedback`): 1/50 of the default tolerance.
_TABLE_FEEDBACK_MIN = 2e-5


def _table_feedback(prep: Prepared, mu: np.ndarray, T_q: np.ndarray, ok: np.ndarray, mu_ref: np.ndarray,
                    args: tuple, fixed: np.ndarray) -> np.ndarray:
    r"""The tables' error with the heating's feedback, where the fixed-profile estimate ``fixed``
    (:func:`_table_error`) exceeds :data:`_TABLE_FEEDBACK_MIN`; ``fixed`` elsewhere.

    Those speeds are solved again on the nodes of ``prep`` (warm-started from their profiles ``T_q``) with every
    temperature table at half its step, the new midpoints on the quadratic through the neighbouring nodes (the
    correction of :func:`_table_error` at t = 1/2). Linear interpolation errs as the square of the step, so the
    error of the tables at their own step is, by Richardson's extrapolation,

    .. math:: \varepsilon_T = \tfrac43\,|\mu_h - \mu_{h/2}| / |\mu_{\rm ref}|

    (L. F. Richardson, Phil. Trans. R. Soc. A 210, 307 (1911)), now with the temperature profile that the
    changed modulus heats to. Near a thermal runaway that feedback multiplies the fixed-profile error: a narrow loss
    peak at -20 C and 1 m/s on a rough road heats by 11 K, and the fixed-profile term read 3.7x below the error a
    0.01 K table shows (``benchmarks/accuracy.py``). The larger of the two estimates is kept; a speed whose solve
    does not converge keeps ``fixed``. It costs a warm-started solve on half the nodes for those speeds only.
    """
    sel = np.flatnonzero(ok & (fixed > _TABLE_FEEDBACK_MIN))
    st = prep.shift_table
    if sel.size == 0 or st is None:
        return fixed
    q_m, a_t0, D, heat_factor, tol, max_iter = args
    halved = ShiftTable(T_lo=st.T_lo, dT=0.5 * st.dT, shift=_halved(st.shift), vshift=_halved(st.vshift))
    half = _assemble(prep.surface, prep.q, prep.v[sel], prep.T0[sel], prep.pressure[sel], prep.scale[sel],
                     prep.table, halved, prep.s_v[sel], prep.b_v[sel], prep.modulus, prep.law,
                     None if prep.shape is None else prep.shape.subset(sel))
    out, _, _, res = _flash(half, q_m, a_t0[sel], D, heat_factor[sel], tol, max_iter, T_start=T_q[sel])
    with np.errstate(divide="ignore", invalid="ignore"):
        rich = (4.0 / 3.0) * np.abs(out.mu - mu[sel]) / np.abs(mu_ref[sel])
    good = (res < tol) & np.isfinite(rich)
    err = fixed.copy()
    err[sel[good]] = np.maximum(fixed[sel[good]], rich[good])
    return err


def _halved(tab: np.ndarray) -> np.ndarray:
    """The table ``tab`` (nodes along its last axis) at half its step: the nodes kept, the midpoints where
    :func:`_between_nodes` puts them (at t = 1/2: linear plus its quadratic term, so the same curve)."""
    n = tab.shape[-1]
    rows = np.reshape(tab, (-1, n))
    out = np.empty((rows.shape[0], 2 * n - 1))
    out[:, ::2] = rows
    mid = np.arange(n - 1)[None, :] + 0.5
    for r in range(rows.shape[0]):
        linear, quadratic = _between_nodes(rows[r:r + 1], mid)
        out[r, 1::2] = (linear + quadratic)[0]
    return out.reshape(tab.shape[:-1] + (2 * n - 1,))


def _between_nodes(tab: np.ndarray, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The tables ``tab`` (one row per node, or one row for all) at the fractional indices ``x`` (n_speed, n_q)
    as :func:`persson.engine.kernels.linear_at` reads them (clamped at the ends), and the quadratic term
    t (t - 1) / 2 Delta^2 that the linear interpolation leaves out (zero at the nodes and outside the table)."""
    n = tab.shape[1]
    i = np.clip(np.floor(x).astype(np.int64), 0, n - 2)
    t = np.clip(x - i, 0.0, 1.0)
    rows = np.arange(x.shape[1])[None, :] if tab.shape[0] == x.shape[1] else 0
    a, b = tab[rows, i], tab[rows, i + 1]
    if n < 3 or np.all(tab == tab[0, 0]):  # a constant table (no vertical shift, no modulus factors): exact
        return a + t * (b - a), np.zeros(x.shape)
    d2 = tab[:, :-2] - 2.0 * tab[:, 1:-1] + tab[:, 2:]  # centred on nodes 1 .. n-2
    c = 0.5 * (d2[rows, np.clip(i - 1, 0, n - 3)] + d2[rows, np.clip(i, 0, n - 3)])
    return a + t * (b - a), 0.5 * t * (t - 1.0) * c


def _friction_at(prep: Prepared, shift: np.ndarray, vshift: np.ndarray, f: np.ndarray, g: np.ndarray) -> np.ndarray:
    """mu of every speed of ``prep`` on its nodes with the given log10 a_T, ln b_T and modulus factors at every
    node (n_speed, n_q): the flash kernel's last evaluation (the same per-node factors and rules,
    :func:`persson.engine.kernels.friction_kernel`) without its table look-ups."""
    nv, nq = shift.shape
    out = _outputs(nv, nq)
    skip = np.zeros(0, dtype=np.int64)
    arrays = {name: np.ascontiguousarray(a, dtype=float) for name, a in
              (("lv10", prep.lv10), ("scale", prep.scale), ("shift", shift), ("vshift", vshift), ("f", f), ("g", g))}
    threaded(_kernels.friction_kernel, nv, min_items=_PARALLEL_MIN_SPEEDS_FLASH, nodes=prep.kernel_nodes,
             rule=prep.quad, speeds=_kernels.SpeedFactors(**arrays), angular=prep.kernel_angular,
             shape=prep.kernel_shape, law=prep.law, coarse=skip, coarse_rule=prep.quad_coarse, coarser=skip,
             coarser_rule=prep.quad_coarse, out=out, mu_coarse=np.zeros(nv), mu_coarser=np.zeros(nv))
    return out.mu


def _flash(prep, q_m, a_t0, D, heat_factor, tol, max_iter, T_start=None):
    """Run the flash kernel on the nodes of ``prep`` from ``T_start`` (n_speed, n_q; None: the background
    temperature); returns the per-scale outputs, T_q, iterations and residuals."""
    nv, nq = prep.n_speed, prep.q.size
    out = _outputs(nv, nq)
    if T_start is None:
        T_start = np.repeat(prep.T0[:, None], nq, axis=1)
    T_q = np.empty((nv, nq))
    it = np.zeros(nv, dtype=np.int64)
    res = np.zeros(nv)
    EX = erfcx(2.0 * prep.q[None, :] * np.sqrt(a_t0)[:, None])
    st = prep.shift_table
    S1, S2 = _heat_factors(prep.q.tobytes())
    threaded(
        _kernels.flash_kernel, nv, min_items=_PARALLEL_MIN_SPEEDS_FLASH, nodes=prep.kernel_nodes, rule=prep.quad,
        speeds=_kernels.FlashSpeeds(lv10=prep.lv10, v=prep.v, scale=prep.scale, T0=prep.T0,
                                    T_start=np.ascontiguousarray(T_start, dtype=float)),
        angular=prep.kernel_angular, shape=prep.kernel_shape, law=prep.law,
        temperature=_kernels.TemperatureTables(T_lo=st.T_lo, inv_dT=1.0 / st.dT, shift=st.shift,
                                               vshift=st.vshift, f=prep.f_tab, g=prep.g_tab),
        heat=_kernels.HeatSource(erfcx=np.ascontiguousarray(EX), S1=S1, S2=S2,
                                 a_t0=np.ascontiguousarray(a_t0, dtype=float), D=float(D),
                                 heat_factor=np.ascontiguousarray(heat_factor, dtype=float),
                                 x_m=math.log(q_m)),
        iteration=_kernels.FixedPoint(tol=float(tol), max_iter=int(max_iter)),
        out=out, T_out=T_q, it_out=it, res_out=res)
    return out, T_q, it, res


@functools.lru_cache(maxsize=16)
def _heat_factors(q_bytes: bytes) -> tuple[np.ndarray, np.ndarray]:
    """:func:`persson.engine.kernels.heat_kernel_factors` of the nodes (their bytes), kept for the next solves on
    the same nodes (a fit solves its fine and coarse grids again at every evaluation). The kernels only read
    them."""
    return _kernels.heat_kernel_factors(np.frombuffer(q_bytes, dtype=float))


def contact_law(gamma: float, correction: str | None = None) -> _kernels.ContactLaw:
    """The contact law the kernels take (:func:`persson.engine.kernels.area`): gamma and, for an area correction of
    :mod:`persson.contact.corrections`, its table of ln P_c on a uniform grid of ln G."""
    if correction is None or (float(gamma) == 1.0 and correction != "wang-muser"):
        return _kernels.ContactLaw(gamma=float(gamma), ln_P=np.empty(0), ln_G0=0.0, per_ln_G=1.0)
    from ..contact.corrections import _table, check_correction

    correction, gamma = check_correction(correction, gamma)
    tab = _table(correction, gamma)
    return _kernels.ContactLaw(gamma=float(gamma), ln_P=np.ascontiguousarray(tab.lnP), ln_G0=float(tab.lnG[0]),
                               per_ln_G=float(tab.inv_step))


def _factors(effect, slope, T, shape):
    """f, g of ``effect.modulus_factors`` broadcast to ``shape``, checked (finite, > 0)."""
    out = effect.modulus_factors(slope, T)
    if out is None:
        return np.ones(shape), np.ones(shape)
    f, g = (np.ascontiguousarray(np.broadcast_to(np.asarray(a, dtype=float), shape)) for a in out)
    if not (np.all(np.isfinite(f)) and np.all(np.isfinite(g)) and np.all(f > 0) and np.all(g > 0)):
        raise InputError(f"effect {effect.name!r}: modulus_factors must return finite factors > 0")
    return f, g


# ---------------------------------------------------------------------------------------------------------
def _outputs(nv: int, nq: int) -> _kernels.Outputs:
    """Empty output arrays of the kernels for ``nv`` speeds on ``nq`` nodes."""
    return _kernels.Outputs(**{k: np.empty((nv, nq)) for k in _SCALE_KEYS}, mu=np.empty(nv), layer=np.empty(nv))


#: The kernels' per-scale outputs (see :func:`_outputs`).
_SCALE_KEYS = ("G", "P", "dmu", "cum", "dG", "ratio", "loss")


def _angular_arrays(table) -> _kernels.AngularTables:
    """The angular integrals of a :class:`~persson.engine.tabulate.AngularTable` as the kernels take them."""
    return _kernels.AngularTables(lw0=table.lw0, inv_dlw=1.0 / table.dlw, ln_are=table.ln_are,
                                  ln_aim=table.ln_aim, ln_l=table.ln_l)


def _solved(prep, out, T_q, err, ok, it, res) -> Solved:
    return Solved(q=prep.q, G=out.G, P=out.P, T_q=T_q, dmu=out.dmu, loss=out.loss, dG=out.dG,
                  ratio=out.ratio, mu_cumulative=out.cum, mu=out.mu, error_estimate=err,
                  excited_layer=np.where(out.mu > 0, out.layer / np.where(out.mu > 0, out.mu, 1.0),
                                         1.0 / prep.q[0]),
                  converged=bool(np.all(ok)), converged_each=np.asarray(ok, dtype=bool), iterations=it,
                  residual=res)


def _relative_error(mu: np.ndarray, mu_coarse: np.ndarray, mu_coarser: np.ndarray | None = None) -> np.ndarray:
    r"""The estimated relative error of the fine result ``mu`` from the same rules on every other node
    (``mu_coarse``) and on every fourth (``mu_coarser``; without it, the first term alone):

    .. math:: \varepsilon = \max\left(\frac{|\mu - \mu_2|}{\sqrt{21}},\
              \frac{|\mu_2 - \mu_4|}{16\sqrt{21}}\right) \Big/ |\mu|.

    For a rule of order p the coarse error is 2^p times the fine one, so fine - coarse = (2^p - 1) x (fine error)
    (Richardson). The rules are third order where the PSD is smooth and second order across the kinks of a
    tabulated PSD; dividing by sqrt(21), the geometric mean of 2^3 - 1 and 2^2 - 1, keeps the first term within a
    factor 1.6 of the error for either order. Before the grids reach that asymptotic range the error can change
    sign between the coarse and the fine grid, and the two results then agree by accident (the first term alone
    read 30x low in such cases). The second term is the same estimate one level up, divided by a further
    16 = 2^4, the most these rules gain per halving (third order plus a margin): the fine error cannot be
    much smaller than that unless it is itself passing through zero, so the estimate errs on the safe side.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.abs(mu - mu_coarse)
        if mu_coarser is not None:
            d = np.maximum(d, np.abs(mu_coarse - mu_coarser) / _PER_HALVING_MAX)
        e = d / _RICHARDSON / np.abs(mu)
    return np.where(np.abs(mu) > 0, e, 0.0)


_PER_HALVING_MAX = 16.0
_RICHARDSON = math.sqrt(21.0)


def _coarser_indices(n: int) -> np.ndarray:
    """Every other node of the coarse grid (:func:`_coarse_indices`): every fourth node, with the last one."""
    coarse = _coarse_indices(n)
    return np.ascontiguousarray(coarse[_coarse_indices(coarse.size)], dtype=np.int64)


def _odd_indices(n: int) -> np.ndarray:
    """The odd-numbered nodes with the first and the last one: the coarse grid interleaved with
    :func:`_coarse_indices`."""
    return np.ascontiguousarray(np.unique(np.concatenate([[0], np.arange(1, n, 2), [n - 1]])), dtype=np.int64)


def _coarse_indices(n: int) -> np.ndarray:
    """Every other node, always with the last one."""
    idx = np.arange(0, n, 2)
    if idx[-1] != n - 1:
        idx = np.append(idx, n - 1)
    return np.ascontiguousarray(idx, dtype=np.int64)
