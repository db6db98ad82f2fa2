r"""Patch heating: the background temperature of the rubber builds up along the contact patch of a slipping wheel.

Physics
-------
In the contact patch of a braked wheel (brush model, :mod:`persson.slip`) the rubber slides on the counter-surface
(the disk of a DRFT-style tester, or the road) behind the stick zone with the local shear stress
:math:`\tau(x) = \mu\,p(x)` and the sliding speed :math:`v_s`. The frictional power per unit nominal area,
:math:`q(x) = \tau(x) v_s`, heats both solids. Persson splits the temperature of the rubber into a background
temperature that varies slowly in space and time and the flash temperature of the macro-asperity contacts on top
of it (Persson & Miyashita, "Tire tread block dynamics", arXiv:2602.22078 (2026); the flash part is
:class:`~persson.effects.FlashTemperature`). This effect supplies the background part along the patch.

Model (one-dimensional heat conduction in both bodies, Jaeger's high-Peclet moving-source limit). In the frame of
the patch, the counter-surface passes from the leading edge (:math:`x = 0`) to the trailing edge at the speed
:math:`V` and the tread at the wheel's circumferential speed :math:`V_r = \omega r = (1 - s)V` (braking slip
:math:`s`). Both enter at the background temperature :math:`T_0`. When :math:`V l / D \gg 1` heat flows only
normal to the surface over the patch, so each surface element is a semi-infinite solid heated by a flux
:math:`J_i(t)` for the time :math:`t = x / V_i` it has spent in the patch. The surface temperature of a
semi-infinite solid under a time-dependent flux is Duhamel's integral (Carslaw & Jaeger, *Conduction of Heat in
Solids*, 2nd ed. 1959, ch. II: the constant-flux solution :math:`2J\sqrt{t}/(e\sqrt\pi)` superposed in time)

.. math:: \Delta T_i(t) = \frac{1}{e_i\sqrt\pi}\int_0^t \frac{J_i(t')\,dt'}{\sqrt{t - t'}}
    = \frac{1}{e_i\sqrt{\pi V_i}}\int_0^x \frac{J_i(x')\,dx'}{\sqrt{x - x'}},
    \qquad e_i = \sqrt{\lambda_i\rho_i c_i}

(:math:`e_i` the thermal effusivity). With a common interface temperature (Blok's postulate, Blok 1937; Jaeger,
J. Proc. R. Soc. N.S.W. 76, 203 (1942)) and :math:`J_r + J_c = \eta q`, the Abel operator being the same for both
bodies, the flux splits in the constant ratio :math:`J_r : J_c = e_r\sqrt{V_r} : e_c\sqrt{V}` and

.. math:: T(x) = T_0 + \frac{\eta}{\sqrt\pi\,(e_r\sqrt{V_r} + e_c\sqrt{V})}
    \int_{x_c}^{x}\frac{\tau(x')\,v_s}{\sqrt{x - x'}}\,dx' ,
    \qquad \tau(x) = \mu\big(v_s, p(x), T(x)\big)\,p(x)\quad (x > x_c),

with :math:`x_c` the end of the stick zone (no sliding, no heat ahead of it). The local friction
:math:`\mu(v_s, p, T)` is the engine's sliding friction at the local pressure and the local background temperature
(with the flash temperature on top when the model has it). The equation is a Volterra equation of Abel type,
solved by marching along the patch (see :func:`patch_friction`).

Limits. :math:`\eta = 0`: no heating; the local friction still follows the local pressure :math:`p(x)`. Locked
wheel (:math:`s = 1`, pure sliding): :math:`V_r = 0`, the stationary rubber has reached the interface
temperature and takes no net flux, the counter-surface carries all the heat away, so the temperature along the
patch stays finite; :math:`\mu(s \to 1)` tends continuously to this value, which is what this effect means by the
friction at ``slip = 1``: the patch average
:math:`\mu = \frac{1}{\sigma_0 l}\int_0^l \mu(V, p(x), T(x))\,p(x)\,dx`. It needs the contact patch, so it acts
through :func:`persson.slip.mu_slip` and :func:`validation.predict` (rows with slip <= 1 and a contact);
:meth:`persson.Model.friction` alone is unchanged by it (a note says so).

Assumptions: perfect thermal contact over the nominal patch; no in-plane conduction (:math:`V l / D \gg 1` for the
counter-surface; the rubber's share vanishes where its Peclet number is small); the counter-surface enters the patch
at :math:`T_0` (a DRFT track warmed by earlier turns is a higher :math:`T_0`); constant thermal properties.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from frictioncite import doi
from materials.shift import extrapolated_shift_note

from ..effects.base import Effect, Parameter
from ..errors import InputError, PhysicsWarning
from ..notes import Note, kinds
from .heating_arrays import Patch, PatchRows
from .heating_kernels import march as _march
from .heating_tables import _Tables, _speed_nodes, _unit_weights
from .references import BLOK_1937, CARSLAW_JAEGER, JAEGER_1942, PERSSON_TREAD_2026

__all__ = ["PatchHeating", "PatchSolution", "patch_friction"]

_P_FLOOR = 0.02  # pressures below 2 % of sigma0 (the patch edges) are evaluated at 2 % of sigma0


# =========================================================================================================
# The effect
# =========================================================================================================
@doi(CARSLAW_JAEGER, JAEGER_1942, BLOK_1937, PERSSON_TREAD_2026)
@dataclass(frozen=True)
class PatchHeating(Effect):
    r"""Background temperature built up along the contact patch by the frictional power, and local pressure.

    See the module docstring for the model. The local friction along the patch is
    :math:`\mu(v_s, p(x), T(x))`, with

    .. math:: T(x) = T_0 + \frac{\eta}{\sqrt\pi\,(e_r\sqrt{(1-s)V} + e_c\sqrt{V})}
        \int_{x_c}^{x}\frac{\mu(x')\,p(x')\,v_s}{\sqrt{x - x'}}\,dx'.

    Parameters
    ----------
    counter_effusivity : float
        Thermal effusivity :math:`e_c = \sqrt{\lambda\rho c}` of the counter-surface (disk, road),
        W s^0.5 / (m^2 K) (default 1500, an asphalt or stone road; granite about 2400, steel about 13000, a
        sandpaper-covered disk lower). Fitted in log space; plausible 100-30000 (polymers to aluminium).
    heat_fraction : float
        :math:`\eta`, the fraction of the frictional power that heats the patch (default 1: all of it; less stands
        for heat leaving by paths the model leaves out, e.g. a thermal contact resistance or cooling).
    rubber_effusivity : float
        :math:`e_r` of the tread, W s^0.5 / (m^2 K); 0 (default) means :math:`\sqrt{\lambda\rho c_p}` of
        ``material.thermal``.
    max_rise : float
        Largest background temperature rise the table covers, K (default 250); a patch hotter than that is
        evaluated at T0 + max_rise and the result says so.
    points_per_decade : float
        Nodes per decade of sliding speed of the friction table (default 3; the distinct sliding speeds
        themselves when they are fewer).
    n_pressure : int
        Nodes of the table over the local pressure (default 6).
    temperature_points_per_decade : float
        Nodes of the table over the background temperature per decade of the time-temperature shift factor
        :math:`a_T` of the material (default 3; per 10 K for a material without ``log10_aT``). On this axis
        rubber friction is about as smooth as on the speed axis (exactly so for hysteresis without flash
        temperature, which depends on :math:`v a_T` only).

    Notes
    -----
    The friction is tabulated over (sliding speed, pressure, temperature) with one engine call at T0 and one
    over the heated temperatures (per-speed temperature and pressure arrays) and interpolated with four-point
    Lagrange polynomials in each variable. The temperature nodes lie on a lattice in :math:`\log_{10}a_T` that
    does not depend on this effect's parameters: a fit of them reuses the table (see
    :func:`patch_friction`).
    """

    name = "patch_heating"
    parameters = (
        Parameter("counter_effusivity", 1500.0, (50.0, 50000.0), "W s^0.5/(m^2 K)",
                  "thermal effusivity sqrt(lambda rho c) of the disk or road", log_scale=True,
                  plausible=(100.0, 30000.0)),
        Parameter("heat_fraction", 1.0, (0.0, 1.0), "1",
                  "fraction of the frictional power that heats the contact patch", physical_limits=(0.0, 1.0)),
    )
    counter_effusivity: float = 1500.0
    heat_fraction: float = 1.0
    rubber_effusivity: float = 0.0
    max_rise: float = 250.0
    points_per_decade: float = 3.0
    n_pressure: int = 6
    temperature_points_per_decade: float = 3.0

    def __post_init__(self):
        super().__post_init__()
        checks = (("rubber_effusivity", self.rubber_effusivity, 0.0, False),
                  ("max_rise", self.max_rise, 0.0, True), ("points_per_decade", self.points_per_decade, 0.0, True),
                  ("temperature_points_per_decade", self.temperature_points_per_decade, 0.0, True))
        for name, v, lo, strict in checks:
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) \
                    or not math.isfinite(v) or (v <= lo if strict else v < lo):
                raise InputError(f"patch_heating.{name}: expected a finite number {'>' if strict else '>='} "
                                 f"{lo:g}, got {v!r}")
        for name in ("n_pressure",):
            n = getattr(self, name)
            if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
                raise InputError(f"patch_heating.{name}: expected an integer >= 2, got {n!r}")

    def effusivity_of(self, material) -> float:
        r"""Thermal effusivity :math:`e_r = \sqrt{\lambda\rho c_p}` of the tread, W s^0.5/(m^2 K)."""
        if self.rubber_effusivity > 0:
            return float(self.rubber_effusivity)
        th = getattr(material, "thermal", None)
        if th is None:
            raise InputError("patch_heating: the material has no thermal properties (material.thermal); give "
                             "rubber_effusivity=")
        return math.sqrt(th.conductivity * th.density * th.specific_heat)

    def heat_factor(self, slip, speed, pressure, length, rubber_effusivity) -> np.ndarray:
        r""":math:`\Lambda = \eta\sigma_0 v_s\sqrt{l} / (\sqrt\pi(e_r\sqrt{(1-s)V} + e_c\sqrt V))`, K.

        The temperature rise is :math:`\Lambda\int_{\xi_c}^{\xi}(\mu g)(\xi')/\sqrt{\xi - \xi'}\,d\xi'` in the
        patch coordinate :math:`\xi = x/l`, with :math:`g = p/\sigma_0`.
        """
        s = np.asarray(slip, dtype=float)
        V = np.asarray(speed, dtype=float)
        Vr = np.clip(1.0 - s, 0.0, None) * V
        den = math.sqrt(math.pi) * (rubber_effusivity * np.sqrt(Vr) + self.counter_effusivity * np.sqrt(V))
        return self.heat_fraction * np.asarray(pressure, dtype=float) * s * V * math.sqrt(length) / den

    def rubber_share(self, slip, speed, rubber_effusivity) -> np.ndarray:
        r"""Fraction of the heat that flows into the tread, :math:`e_r\sqrt{V_r}/(e_r\sqrt{V_r} + e_c\sqrt V)`."""
        V = np.asarray(speed, dtype=float)
        a = rubber_effusivity * np.sqrt(np.clip(1.0 - np.asarray(slip, dtype=float), 0.0, None) * V)
        return a / (a + self.counter_effusivity * np.sqrt(V))

    def transform_result(self, result):
        note = Note("patch_heating acts on the contact patch (persson.slip.mu_slip, validation.predict); this "
                    "result is the local friction at the given temperature and pressure", "input")
        if note in result.notes:
            return result
        return result.replace(notes=tuple(result.notes) + (note,))


# =========================================================================================================
# Result of the patch computation
# =========================================================================================================
@dataclass(frozen=True, eq=False)
class PatchSolution:
    """Friction of the patch for each row, and what it took.

    Attributes
    ----------
    mu : ndarray (n,)
        Friction coefficient of the wheel (longitudinal force / load).
    stick_fraction : ndarray (n,)
        x_c / l.
    mu_local : ndarray (n,)
        Local sliding friction at (v_s, sigma0, T0), interpolated in the T0 slice of the table (in speed and
        pressure only; relative error about 1e-4 on a tread on a road).
    max_rise : ndarray (n,)
        Largest background temperature rise along the patch, K.
    xi : ndarray (N,)
        Patch nodes x / l.
    temperature, shear, mu_profile : ndarray (n, N) or None
        Background temperature (deg C), shear stress / sigma0 and local friction coefficient on the nodes
        (``profiles=True``).
    table_points : int
        Engine evaluations spent on the tables in this call (0 when a cached table served).
    engine_calls : int
        Engine calls made in this call.
    converged : bool
        Whether the engine's self-consistent iterations converged everywhere.
    notes : tuple of str
    """

    mu: np.ndarray
    stick_fraction: np.ndarray
    mu_local: np.ndarray
    max_rise: np.ndarray
    xi: np.ndarray
    temperature: np.ndarray | None
    shear: np.ndarray | None
    mu_profile: np.ndarray | None
    table_points: int
    engine_calls: int
    converged: bool
    notes: tuple

    @property
    def note_kinds(self) -> tuple:
        """The kind of every note (:data:`persson.notes.KINDS`; None for a plain-text note)."""
        return kinds(self.notes)


# =========================================================================================================
# Driver: tabulate once, march along the patch for every row
# =========================================================================================================
def patch_friction(model, heating: PatchHeating, contact, slip, speed, temperature, pressure, *,
                   profiles: bool = False, tables=None, warn_shift_range: bool = True) -> PatchSolution:
    r"""Brush-model friction with the local friction :math:`\mu(v_s, p(x), T(x))` along the patch.

    Parameters
    ----------
    model : persson.Model or object with ``friction(speed, temperature=, pressure=)`` (per-speed arrays)
        The local sliding friction (its own ``patch_heating`` effect is not used here: ``heating`` is).
    heating : PatchHeating
    contact : persson.slip.Contact
    slip, speed, temperature, pressure : array_like, one value per row (broadcast together)
        Braking slip in (0, 1], rolling speed V (m/s), background temperature T0 (deg C), mean pressure
        sigma0 (Pa).
    profiles : bool
        Also return T(x), the shear and mu(x) on the patch nodes.
    warn_shift_range : bool
        Raise the warning that the rubber left the shift law's fitted range (it is in the notes either way);
        False where the caller warns once for several solutions (:func:`persson.slip.mu_slip`). The range is
        that of the table nodes this solution interpolates (background, patch and flash temperatures), so a
        table kept in ``tables`` that an earlier, hotter solution has grown does not carry its note over.
    tables : dict, optional
        A cache (a dict the caller keeps) of friction tables: reused when the engine (:func:`engine_key`), the
        table settings (``max_rise``, ``n_pressure``, ``temperature_points_per_decade``), the contact's pressure
        shape and the rows' (T0, sigma0, v_s) are the same, whatever the heating strength, contact length or
        stiffness (e.g. in a fit of the counter-surface effusivity or the stiffness), and whatever the parameters
        of the model's :class:`persson.effects.Adhesion`: the adhesive term
        :math:`\tau_f(v, T_{q_1}) A/A_0 / \sigma_0` enters nothing else in the engine, and its factors
        :math:`A/A_0 / \sigma_0` and :math:`T_{q_1}` (the rubber temperature at q1) do not depend on ``tau_f0``,
        ``c``, ``v_ref`` or ``v_ref_temperature``, so the table keeps them apart (a fit of the adhesion with patch
        heating builds one table; a new one only when the friction at either value would pass 3 or fall below
        1e-3, where the engine's notes depend on its level; where the split cannot be checked, on a wet road or
        with ``c = 0``, for another ``tau_f0`` alone). It holds references to the model it was built with, so
        identities stay valid while it lives. Besides the current table the cache keeps the three built before it
        (under ``"older"``, the most recent first), each served again when its engine comes back: a fit's finite
        differences move one engine parameter, then one the table does not depend on (the counter-surface
        effusivity), whose engine is the point's own. A solution's notes, warnings and convergence are those of the
        engine calls that evaluated the table nodes it interpolates, so a table grown by a hotter patch does not
        pass its hot nodes' notes to a cooler solution.

    Returns
    -------
    PatchSolution

    Notes
    -----
    Numerics. For each (T0, sigma0) of the rows the friction is tabulated over the sliding speeds (their distinct
    values, or ``points_per_decade`` log-spaced nodes when those are fewer), the local pressure
    (``n_pressure`` nodes over the range of p(x), floored at 2 % of sigma0) and the background temperature on
    the lattice :math:`y_k = k/n_y`, :math:`y = \log_{10}a_T(T_0) - \log_{10}a_T(T)`,
    :math:`n_y` = ``temperature_points_per_decade``, from T0 up to :math:`T_0 + \Delta T_{max}(v)`
    (:math:`\Delta T_{max}` 1.15 times the rise the patch would reach with the friction held at its T0 value;
    more nodes are added where the patch gets hotter, each time up to 1.25 times the temperatures it reached,
    until every temperature of the solution lies below the table's top interval, where the stencil would be
    one-sided: the answer is then that of any taller table; at least 4 nodes per speed); values in between by
    tensor-product four-point Lagrange interpolation; a row whose sliding speed is a node's (the table's speed
    nodes are the rows' own speeds when those are few, e.g. a locked wheel at a few speeds) reads that node alone,
    the same values to the last bit, and where every row of a sweep does, each speed node reaches the temperatures
    of its own rows only instead of those of its hotter neighbours as well. The lattice does not depend on the
    heating parameters, so a table kept in ``tables`` serves any counter-surface effusivity or heat fraction and
    only grows (one engine call for the missing nodes) when a hotter patch needs a higher temperature range. A new
    table for the same rows with another engine first reaches 1.15 times the rises of the previous solution where
    the solver sees other problems (:func:`solver_key`; a joint fit with the flash temperature), and the previous
    table's range where it does not (its nodes are then problems just solved). Along the patch (the contact's
    nodes), the stick zone ends at the first sign change of :math:`\mu(v_s, p, T_0)p - k\theta x` (as in
    :func:`persson.slip.mu_slip`); behind it the
    Abel integral is evaluated by product integration (the shear piecewise linear between nodes, the kernel
    integrated exactly), implicitly at the new node (secant iteration, bisection as fallback). The stick part is
    integrated exactly, the slide part by the trapezoid rule, as in the brush model without heating.
    """
    from .contact import Contact

    if not isinstance(heating, PatchHeating):
        raise InputError(f"heating: expected persson.effects.PatchHeating, got {heating!r}")
    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    if not hasattr(model, "friction"):
        raise InputError(f"model: expected a persson.Model (or an object with friction(speed, temperature=, "
                         f"pressure=)), got {model!r}")
    s, V, T0, p0 = (np.atleast_1d(np.asarray(a, dtype=float)).ravel() for a in
                    np.broadcast_arrays(slip, speed, temperature, pressure))
    if np.any(~np.isfinite(s) | (s <= 0) | (s > 1)):
        raise InputError("slip: expected braking slip ratios in (0, 1]")
    if np.any(~np.isfinite(V) | (V <= 0)):
        raise InputError("speed: expected rolling speeds > 0 m/s")
    if np.any(~np.isfinite(p0) | (p0 <= 0)):
        raise InputError("pressure: expected mean pressures > 0 Pa")
    if np.any(~np.isfinite(T0)):
        raise InputError("temperature: expected finite temperatures")
    material = getattr(model, "material", None)
    e_r = heating.effusivity_of(material)
    vs = s * V
    lam = heating.heat_factor(s, V, p0, contact.length, e_r)
    with np.errstate(divide="ignore"):
        theta = np.where(s < 1.0, s / np.where(s < 1.0, 1.0 - s, 1.0), np.inf)
    a = contact.stiffness * contact.length / p0 * theta

    # ---- the (T0, sigma0) sweeps and their friction tables
    keys, sweep, vnodes, voff, V_lo, on_nodes = _sweeps(s, V, T0, p0, heating.points_per_decade, tables)
    g = contact._g
    g_lo = max(float(np.min(g)), _P_FLOOR)
    g_hi = max(float(np.max(g)), g_lo)
    n_g = 1 if g_hi - g_lo <= 1e-12 * g_hi else int(heating.n_pressure)
    gnodes = np.linspace(g_lo, g_hi, n_g)
    heated = heating.heat_fraction > 0

    # The table does not depend on how strongly the patch is heated (counter_effusivity, heat_fraction, e_r):
    # its temperature nodes lie on a lattice fixed by T0 and the material, so a fit of those parameters only adds
    # the nodes a hotter patch needs.
    cache_key = (heating.max_rise, n_g, heating.temperature_points_per_decade,
                 contact._g.tobytes(), keys.tobytes(), vnodes.tobytes(), voff.tobytes(), V_lo.tobytes())
    # a model whose adhesion is the built-in one keys its table without tau_f0: the table keeps the adhesive term
    # apart and serves any tau_f0 (a fit of the baseline's adhesion with patch heating, one table); a table that
    # keeps the term's factors as well (``separable``) serves any adhesion, and is keyed without it
    scale = _adhesion_scale(model)
    adhesion = None if scale is None else model.effect("adhesion")
    ekey = engine_key(model) if scale is None else ("adhesion scaled", engine_key(_with_tau_f0(model, 1.0)))
    skey = None if scale is None else ("adhesion separable", engine_key(_with_adhesion(model, _ANY_ADHESION)))
    engine = model.without("patch_heating") if "patch_heating" in getattr(model, "effect_names", ()) else model
    kept = tables is not None and (_serves(tables, cache_key, ekey, skey) or _recall(tables, cache_key, ekey, skey))
    if kept and (scale is None or tables["value"].rescale(adhesion, engine)):
        tab = tables["value"]
        tables["engine"] = ekey  # what the table's tau_f0-only split now holds
        calls0, points0 = tab.calls, tab.points
        tab.serve(on_nodes)
    else:
        calls0, points0 = 0, 0
        tab = _Tables(engine, keys, vnodes, voff, gnodes, V_lo, heating, adhesion_scale=scale, adhesion=adhesion,
                      on_nodes=on_nodes)
        if tables is not None:
            solver = solver_key(engine)
            if heated and tables.get("key") == cache_key and tables["value"].has_heated():
                # the same rows with another engine. Where the solver sees the same problems (an effect that only
                # adds a friction term changed, e.g. an adhesion the table cannot rescale), the previous table's
                # range is the first guess: its nodes are the problems the solver has just solved, which
                # persson.solver.reuse_solutions returns at once. Where the solver changed (a joint fit with the
                # flash temperature, the microtexture: every node costs a solve), the range that the previous
                # solution's own rises needed is, not the previous table's, which only ever grows and may lie far
                # above the rises of the fit's later evaluations. The march below widens it if the patch is hotter.
                reach = tables.get("reach")
                same = solver is not None and tables.get("solver") == solver
                tab.B[:] = tables["value"].B if reach is None or same else np.minimum(tables["value"].B, reach)
                tab._grow(np.ones(keys.shape[0], dtype=bool))
            older = tables.pop(_OLDER, [])
            rows_entry = tables.pop(_ROWS, None)
            if "value" in tables:
                older.insert(0, dict(tables))
                del older[_KEEP_OLDER:]
            tables.clear()
            tables.update(engine=ekey, separable=skey, key=cache_key, value=tab, model=model, solver=solver)
            tables[_OLDER] = older
            if rows_entry is not None:
                tables[_ROWS] = rows_entry
    xi = np.ascontiguousarray(contact._xi)
    gg = np.ascontiguousarray(contact._g)
    rows = PatchRows(sweep=sweep.astype(np.int64), log_speed=np.log(vs), stick_slope=a, heat_factor=lam)
    patch = Patch(xi=xi, g=gg, abel=_unit_weights(xi.size))
    if heated and not tab.has_heated():
        # the heating with the friction held at T0 bounds the temperature range the rows need (a kept table
        # with heated nodes goes straight to the march below, which grows it if the patch is hotter)
        pre = _march(rows=rows, patch=patch, lattice=tab.args(), axis=tab.targs(), profiles=False)
        tab.fill(pre.rise, vs, sweep)
    n_sweeps = keys.shape[0]
    for _ in range(6):
        out = _march(rows=rows, patch=patch, lattice=tab.args(), axis=tab.targs(), profiles=bool(profiles))
        mu, xc, rise, umax, Tprof, shear, muprof = out
        umax_top = _per_sweep_max(umax, sweep, n_sweeps)
        over = (umax_top > 1.0 + 1e-9) & ~np.array([tab.capped(c) for c in range(n_sweeps)], dtype=bool)
        if not over.any():
            break
        tab.extend(over, umax_top)
    if tables is not None and tables.get("value") is tab and heated:
        tables["reach"] = tab.range_for(rise, vs, sweep)
    # what the engine said at the nodes this solution interpolates (not at nodes a hotter solution added before)
    rise_top = _per_sweep_max(rise, sweep, n_sweeps)
    used = tab.used(rise_top)
    fill_notes, fill_warned, converged = tab.outcome(rise_top, used=used)
    notes = list(fill_notes)
    if over.any():
        converged = False
        notes.append(Note(f"patch_heating: the friction table did not reach the patch temperature at "
                          f"{int(over.sum())} condition(s); evaluated at the table's top", "accuracy"))
    hot = int(np.count_nonzero(rise_top > heating.max_rise * (1 + 1e-9)))
    if hot:
        notes.append(Note(f"patch_heating: background temperature rise above the table ({heating.max_rise:g} K cap) "
                          f"at {hot} condition(s); evaluated at the cap", "accuracy"))
    # the rubber's temperatures beyond the shift law's fitted range, over the table nodes this solution
    # interpolates (background, patch and flash temperatures): the same note whatever the table's history
    t_lo, t_hi = tab.rubber_range(rise_top, used=used)
    shift_note = extrapolated_shift_note(material, t_lo, t_hi) if material is not None else None
    if shift_note is not None:
        notes.append(Note(shift_note, "extrapolated"))
    mu_loc = tab.mu_at_sigma0(vs, sweep)
    # the engine's warnings, recorded while the table was filled, reach the caller as warnings (once each) as
    # well as in the notes
    for category, message in fill_warned:
        warnings.warn(message, category, stacklevel=2)
    if shift_note is not None and warn_shift_range:
        warnings.warn(shift_note, PhysicsWarning, stacklevel=2)
    return PatchSolution(mu=mu, stick_fraction=xc, mu_local=mu_loc, max_rise=rise, xi=xi.copy(),
                         temperature=Tprof if profiles else None, shear=shear if profiles else None,
                         mu_profile=muprof if profiles else None, table_points=tab.points - points0,
                         engine_calls=tab.calls - calls0,
                         converged=converged, notes=tuple(dict.fromkeys(notes)))


def _sweeps(s, V, T0, p0, points_per_decade, tables=None):
    """The (T0, sigma0) sweeps of the rows and their speed nodes: (keys, sweep of every row, speed nodes, their
    offsets per sweep, lowest rolling speed per sweep, whether every row of a sweep sits on a node). Kept in
    ``tables`` (the caller's cache) for the same rows, which a fit's every evaluation passes again."""
    rows_key = (float(points_per_decade), s.tobytes(), V.tobytes(), T0.tobytes(), p0.tobytes())
    if tables is not None and tables.get(_ROWS, (None,))[0] == rows_key:
        return tables[_ROWS][1]
    vs = s * V
    keys, sweep = np.unique(np.column_stack([T0, p0]), axis=0, return_inverse=True)
    sweep = np.asarray(sweep).ravel()
    vnode_list = [_speed_nodes(vs[sweep == c], points_per_decade) for c in range(keys.shape[0])]
    voff = np.zeros(len(vnode_list) + 1, dtype=np.int64)
    voff[1:] = np.cumsum([v.size for v in vnode_list])
    V_lo = np.array([float(np.min(V[sweep == c])) for c in range(keys.shape[0])])
    # sweeps whose rows all sit on speed nodes: each row reads its node alone (heating_kernels._speed_stencil)
    on_nodes = np.array([bool(np.all(np.isin(vs[sweep == c], vnode_list[c]))) for c in range(keys.shape[0])])
    out = (keys, sweep, np.concatenate(vnode_list), voff, V_lo, on_nodes)
    if tables is not None:
        tables[_ROWS] = (rows_key, out)
    return out


def _per_sweep_max(x, sweep, n_sweeps) -> np.ndarray:
    """The largest of ``x`` over the rows of each sweep (every sweep has rows)."""
    top = np.full(n_sweeps, -np.inf)
    np.maximum.at(top, sweep, x)
    return top


def _adhesion_scale(model) -> float | None:
    """tau_f0 of the model's adhesion when its table may keep the adhesive term apart (the built-in
    :class:`persson.effects.Adhesion`, the only such effect, tau_f0 > 0, on a :class:`persson.Model`), else None."""
    from ..effects.builtin import Adhesion

    effects = getattr(model, "effects", None)
    if effects is None or not hasattr(model, "replace"):
        return None
    found = [e for e in effects if getattr(e, "name", "") == "adhesion"]
    if len(found) != 1 or type(found[0]) is not Adhesion:
        return None
    tau = float(found[0].tau_f0)
    return tau if math.isfinite(tau) and tau > 0 else None


def _with_tau_f0(model, tau: float):
    """``model`` with its adhesion's tau_f0 replaced (see :func:`_adhesion_scale`)."""
    return _with_adhesion(model, {"tau_f0": tau})


#: The adhesion's parameters in the key of a table that serves any adhesion (:func:`patch_friction`).
_ANY_ADHESION = {"tau_f0": 1.0, "c": 0.0, "v_ref": 1.0, "v_ref_temperature": None}


def _with_adhesion(model, values: dict):
    """``model`` with its adhesion's parameters ``values`` replaced (see :func:`_adhesion_scale`)."""
    import dataclasses

    return model.replace(effects=tuple(dataclasses.replace(e, **values) if getattr(e, "name", "") == "adhesion"
                                       else e for e in model.effects))


#: Tables kept besides the current one in a ``tables`` cache of :func:`patch_friction` (the most recent first).
#: A finite-difference Jacobian of a fit that varies two parameters the engine depends on (e.g. a strain
#: softening's two factors beside the patch heating) evaluates, after the column that moved the second one, a
#: column that moves a parameter the table does not depend on (the counter-surface effusivity, the adhesion):
#: that column's engine is the one of the column before last, whose table is then still at hand.
_KEEP_OLDER = 3
_OLDER = "older"
#: The rows' sweeps and speed nodes of the last call (:func:`_sweeps`), in a ``tables`` cache.
_ROWS = "rows"


def _serves(tables: dict, cache_key, ekey, skey) -> bool:
    """Whether the current table of the cache ``tables`` serves the rows ``cache_key`` with the engine ``ekey``
    (or, for a table that keeps the adhesion's factors apart, any adhesion: ``skey``)."""
    return tables.get("key") == cache_key and (
        tables.get("engine") == ekey or (skey is not None and tables.get("separable") == skey
                                         and tables["value"].separable))


def _recall(tables: dict, cache_key, ekey, skey) -> bool:
    """Make an earlier table of the cache that serves (:func:`_serves`) the current one again, the current one kept
    among the earlier ones; False when none serves. The values at a table's nodes do not depend on which other
    nodes it holds, so a recalled table gives what a new one would: to rounding for a material tabulated at its own
    reference temperature (a master curve, :func:`persson.engine.solver.table_temperature`), to about 1e-9 for one
    tabulated at the median temperature of each call, the level at which the engine's value at a node then depends
    on the other points of the call that evaluated it."""
    older = tables.get(_OLDER) or []
    for i, entry in enumerate(older):
        if _serves(entry, cache_key, ekey, skey):
            rest = older[:i] + older[i + 1:]
            current = {k: v for k, v in tables.items() if k not in (_OLDER, _ROWS)}
            rows_entry = tables.get(_ROWS)
            tables.clear()
            tables.update(entry)
            tables[_OLDER] = ([current] if "value" in current else []) + rest
            if rows_entry is not None:
                tables[_ROWS] = rows_entry
            return True
    return False


def solver_key(model):
    """What the engine's solver sees of ``model``: :func:`engine_key` with only the effects that act before or
    inside the solver (on the conditions, the surface, the material, the temperature or the modulus). Two models
    with equal keys solve the same problems (they may differ in effects that only add a friction term, such as the
    adhesion); None for an object that is not a persson.Model (its solver is unknown)."""
    return _model_key(model, _acts_on_solver)


def engine_key(model):
    """What the engine's friction depends on: the model's surface and material (by identity), nu, gamma, grid,
    area correction and its effects other than patch heating (by value). Two models with equal keys give equal
    friction; an object that is not a persson.Model is keyed by its identity."""
    return _model_key(model, lambda effect: True) or ("object", id(model))


def _model_key(model, keep):
    """The key of :func:`engine_key` with the effects ``keep`` accepts (patch heating never); None for an object
    that is not a persson.Model."""
    if not all(hasattr(model, a) for a in ("surface", "material", "effects", "nu", "gamma")):
        return None
    return ("model", id(model.surface), id(model.material), model.nu, model.gamma, getattr(model, "grid", None),
            getattr(model, "correction", None),
            tuple(e for e in model.effects if getattr(e, "name", "") != "patch_heating" and keep(e)))


def _acts_on_solver(effect) -> bool:
    """Whether ``effect`` changes what the solver solves (any hook before or inside it; an object that is not a
    persson.effects.Effect counts as one that does)."""
    from ..effects.base import Effect

    if not isinstance(effect, Effect):
        return True
    hooks = ("transform_conditions", "transform_surface", "transform_material", "modulus_factors")
    return effect.solver_role is not None or any(getattr(type(effect), h) is not getattr(Effect, h) for h in hooks)
