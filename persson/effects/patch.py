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
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

from frictioncite import doi

from ..errors import InputError
from .base import Effect, Parameter

__all__ = ["PatchHeating", "PatchSolution", "patch_friction", "CARSLAW_JAEGER", "JAEGER_1942", "BLOK_1937",
           "PERSSON_TREAD_2026"]

#: H. S. Carslaw, J. C. Jaeger, Conduction of Heat in Solids, 2nd ed., Oxford (1959), ch. II.
CARSLAW_JAEGER = "isbn:9780198533689"
#: J. C. Jaeger, Moving sources of heat and the temperature at sliding contacts, J. Proc. R. Soc. N.S.W. 76,
#: 203-224 (1942).
JAEGER_1942 = "jaeger:jprsnsw-76-203-1942"
#: H. Blok, Theoretical study of temperature rise at surfaces of actual contact under oiliness lubricating
#: conditions, General Discussion on Lubrication and Lubricants, IMechE, London, vol. 2, 222-235 (1937).
BLOK_1937 = "blok:imeche-lubrication-1937"
#: B. N. J. Persson, N. Miyashita, Tire tread block dynamics, arXiv:2602.22078 (2026): background and flash
#: temperature.
PERSSON_TREAD_2026 = "arxiv:2602.22078"

_PARALLEL_MIN_ROWS = 4
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
        note = ("patch_heating acts on the contact patch (persson.slip.mu_slip, validation.predict); this result "
                "is the local friction at the given temperature and pressure")
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


# =========================================================================================================
# Driver: tabulate once, march along the patch for every row
# =========================================================================================================
def patch_friction(model, heating: PatchHeating, contact, slip, speed, temperature, pressure, *,
                   profiles: bool = False, tables=None) -> PatchSolution:
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
    tables : dict, optional
        A cache (a dict the caller keeps) of friction tables: reused when the engine (:func:`engine_key`), the
        table settings (``max_rise``, ``n_pressure``, ``temperature_points_per_decade``), the contact's pressure
        shape and the rows' (T0, sigma0, v_s) are the same, whatever the heating strength, contact length or
        stiffness (e.g. in a fit of the counter-surface effusivity or the stiffness). It holds references to the
        model it was built with, so identities stay valid while it lives.

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
    more nodes are added if the patch gets hotter; at least 4 nodes per speed); values in between by
    tensor-product four-point Lagrange interpolation. The lattice does not depend on the heating parameters, so
    a table kept in ``tables`` serves any counter-surface effusivity or heat fraction and only grows (one engine
    call for the missing nodes) when a hotter patch needs a higher temperature range. Along the patch (the
    contact's nodes), the stick zone ends at the first sign change of :math:`\mu(v_s, p, T_0)p - k\theta x` (as in :func:`persson.slip.mu_slip`); behind it the
    Abel integral is evaluated by product integration (the shear piecewise linear between nodes, the kernel
    integrated exactly), implicitly at the new node (secant iteration, bisection as fallback). The stick part is
    integrated exactly, the slide part by the trapezoid rule, as in the brush model without heating.
    """
    from ..slip import Contact

    if not isinstance(heating, PatchHeating):
        raise InputError(f"heating: expected persson.effects.PatchHeating, got {heating!r}")
    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    if not hasattr(model, "friction"):
        raise InputError(f"model: expected a persson.Model (or an object with friction(speed, temperature=, "
                         f"pressure=)), got {model!r}")
    s, V, T0, p0 = (np.atleast_1d(np.asarray(a, dtype=float)).ravel() for a in
                    np.broadcast_arrays(slip, speed, temperature, pressure))
    n = s.size
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
    keys, sweep = np.unique(np.column_stack([T0, p0]), axis=0, return_inverse=True)
    sweep = np.asarray(sweep).ravel()
    g = contact._g
    g_lo = max(float(np.min(g)), _P_FLOOR)
    g_hi = max(float(np.max(g)), g_lo)
    n_g = 1 if g_hi - g_lo <= 1e-12 * g_hi else int(heating.n_pressure)
    gnodes = np.linspace(g_lo, g_hi, n_g)
    heated = heating.heat_fraction > 0
    vnode_list = []
    for c in range(keys.shape[0]):
        vnode_list.append(_speed_nodes(vs[sweep == c], heating.points_per_decade))
    voff = np.zeros(len(vnode_list) + 1, dtype=np.int64)
    voff[1:] = np.cumsum([v.size for v in vnode_list])
    vnodes = np.concatenate(vnode_list)
    V_lo = np.array([float(np.min(V[sweep == c])) for c in range(keys.shape[0])])

    # The table does not depend on how strongly the patch is heated (counter_effusivity, heat_fraction, e_r):
    # its temperature nodes lie on a lattice fixed by T0 and the material, so a fit of those parameters only adds
    # the nodes a hotter patch needs.
    cache_key = (heating.max_rise, n_g, heating.temperature_points_per_decade,
                 contact._g.tobytes(), keys.tobytes(), vnodes.tobytes(), voff.tobytes(), V_lo.tobytes())
    ekey = engine_key(model)
    if tables is not None and tables.get("engine") == ekey and tables.get("key") == cache_key:
        tab = tables["value"]
        calls0, points0 = tab.calls, tab.points
    else:
        calls0, points0 = 0, 0
        engine = model.without("patch_heating") if "patch_heating" in getattr(model, "effect_names", ()) else model
        tab = _Tables(engine, keys, vnodes, voff, gnodes, V_lo, heating)
        if tables is not None:
            tables.clear()
            tables.update(engine=ekey, key=cache_key, value=tab, model=model)
    xi = np.ascontiguousarray(contact._xi)
    gg = np.ascontiguousarray(contact._g)
    W = _unit_weights(xi.size)
    rows = sweep.astype(np.int64)
    lvs = np.log(vs)
    # each row costs about N^2 operations (the Abel sums): threads pay off from a few rows on
    march = _march_parallel if n >= _PARALLEL_MIN_ROWS else _march_serial
    if heated and not tab.has_heated():
        # the heating with the friction held at T0 bounds the temperature range the rows need (a kept table
        # with heated nodes goes straight to the march below, which grows it if the patch is hotter)
        pre = march(rows, lvs, a, lam, xi, gg, W, *tab.args(), *tab.targs(), False)
        tab.fill(pre[2], vs, sweep)
    for _ in range(6):
        out = march(rows, lvs, a, lam, xi, gg, W, *tab.args(), *tab.targs(), bool(profiles))
        mu, xc, rise, umax, Tprof, shear, muprof = out
        over = np.zeros(keys.shape[0], dtype=bool)
        for c in range(keys.shape[0]):
            over[c] = bool(np.max(umax[sweep == c]) > 1.0 + 1e-9) and not tab.capped(c)
        if not over.any():
            break
        tab.extend(over, np.array([float(np.max(umax[sweep == c])) for c in range(keys.shape[0])]))
    notes = list(tab.notes)
    converged = tab.converged
    if over.any():
        converged = False
        notes.append(f"patch_heating: the friction table did not reach the patch temperature at {int(over.sum())} "
                     f"condition(s); evaluated at the table's top")
    hot = [c for c in range(keys.shape[0]) if float(np.max(rise[sweep == c])) > heating.max_rise * (1 + 1e-9)]
    if hot:
        notes.append(f"patch_heating: background temperature rise above the table ({heating.max_rise:g} K cap) at "
                     f"{len(hot)} condition(s); evaluated at the cap")
    mu_loc = tab.mu_at_sigma0(vs, sweep)
    return PatchSolution(mu=mu, stick_fraction=xc, mu_local=mu_loc, max_rise=rise, xi=xi.copy(),
                         temperature=Tprof if profiles else None, shear=shear if profiles else None,
                         mu_profile=muprof if profiles else None, table_points=tab.points - points0,
                         engine_calls=tab.calls - calls0,
                         converged=converged, notes=tuple(dict.fromkeys(notes)))


def engine_key(model):
    """What the engine's friction depends on: the model's surface and material (by identity), nu, gamma, grid and
    its effects other than patch heating (by value). Two models with equal keys give equal friction."""
    if all(hasattr(model, a) for a in ("surface", "material", "effects", "nu", "gamma")):
        return ("model", id(model.surface), id(model.material), model.nu, model.gamma, getattr(model, "grid", None),
                tuple(e for e in model.effects if getattr(e, "name", "") != "patch_heating"))
    return ("object", id(model))


def _speed_nodes(v: np.ndarray, per_decade: float) -> np.ndarray:
    """Table nodes in sliding speed: the distinct values when they are few, else log-spaced nodes spanning them
    (at least four, spacing at most 1/``per_decade`` decade)."""
    u = np.unique(v)
    lo, hi = math.log10(float(u[0])), math.log10(float(u[-1]))
    n_int = max(3, int(math.ceil((hi - lo) * per_decade - 1e-9)))
    if u.size <= n_int + 1:
        return u
    return 10.0 ** np.linspace(lo, hi, n_int + 1)


def _temperature_counts(ymax: np.ndarray, per_decade: float) -> np.ndarray:
    """Temperature nodes of each speed node that reach ``ymax`` (decades of a_T) on the lattice of spacing
    1/``per_decade``: at least 4 (cubic interpolation) when ``ymax`` > 0, else 1 (the T0 slice alone)."""
    x = np.asarray(ymax, dtype=float) * per_decade
    n = np.ceil(np.maximum(x, 0.0) - 1e-9).astype(np.int64) + 1
    n = np.where(x > 0.0, np.maximum(n, 4), 1)
    return np.clip(n, 1, _MAX_NU).astype(np.int64)


_NY = 1025  # nodes of the fine y(T) table per sweep from T0 to T0 + max_rise (and as many again above)
_MAX_NU = 512  # most temperature nodes of one speed node


class _Tables:
    r"""Friction tables of every (T0, sigma0) sweep over (v, g = p/sigma0, y).

    The temperature coordinate is :math:`y(T) = \log_{10}a_T(T_0) - \log_{10}a_T(T)` (decades of the shift factor;
    :math:`(T - T_0)/10` K for a material without ``log10_aT``), tabulated finely (``_NY`` nodes from T0 to
    T0 + max_rise, continued as far again so that the lattice node above the cap has its temperature) and
    interpolated linearly. The temperature nodes lie on the lattice :math:`y_k = k h`, :math:`h` = 1 /
    ``temperature_points_per_decade``, the same for every heating strength: a table grows (more nodes per speed) as
    the patch gets hotter and is never refilled. Layout: for the global v node i (``voff`` delimits the sweeps), a
    block of shape (n_g, nu[i]) at ``vtoff[i]`` in ``values``, holding the nodes k = 0 .. nu[i] - 1.
    """

    def __init__(self, model, keys, vnodes, voff, gnodes, V_lo, heating):
        import warnings

        self.model = model
        self.T0 = np.ascontiguousarray(keys[:, 0])
        self.sig0 = np.ascontiguousarray(keys[:, 1])
        self.vnodes = vnodes
        self.lv = np.ascontiguousarray(np.log(vnodes))
        self.voff = voff
        self.gnodes = gnodes
        self.hy = 1.0 / float(heating.temperature_points_per_decade)
        self.V_lo = np.ascontiguousarray(V_lo)
        self.cap = float(heating.max_rise)
        self.points = 0
        self.calls = 0
        self.converged = True
        self.notes: list[str] = []
        self._warnings = warnings
        nc = keys.shape[0]
        ng = gnodes.size
        self._capped = np.zeros(nc, dtype=bool)
        self.B = np.zeros(nc)  # temperature range of this call: dT_max(v) = min(B v / sqrt(v + V_lo), cap)
        self.dTf = self.cap / (_NY - 1)
        self.yT = np.empty((nc, 2 * _NY - 1))
        la = getattr(model, "material", None)
        la = getattr(la, "log10_aT", None)
        for c in range(nc):
            self.yT[c] = _shift_coordinate(la, self.T0[c], self.T0[c] + self.dTf * np.arange(2 * _NY - 1))
        self.ycap = np.ascontiguousarray(self.yT[:, _NY - 1])
        # the T0 slice (k = 0) of every sweep, one engine call
        V_, G_ = [], []
        for c in range(nc):
            a, b = np.meshgrid(vnodes[voff[c]:voff[c + 1]], gnodes, indexing="ij")
            V_.append(a.ravel())
            G_.append(b.ravel() * self.sig0[c])
        T_ = [np.full(int(voff[c + 1] - voff[c]) * ng, self.T0[c]) for c in range(nc)]
        mu = self._call(np.concatenate(V_), np.concatenate(T_), np.concatenate(G_))
        # blocks[c]: (n_v of sweep c, n_g, capacity) friction values; nus[c]: nodes filled at each speed node
        self.blocks = [mu.reshape(-1, ng)[voff[c]:voff[c + 1], :, None].copy() for c in range(nc)]
        self.nus = [np.ones(voff[c + 1] - voff[c], dtype=np.int64) for c in range(nc)]
        self.mu_max = np.array([float(np.max(b)) for b in self.blocks])
        self._layout()

    def _layout(self):
        """Flatten the blocks into (values, vtoff, nu) for the kernels."""
        parts = []
        for c, blk in enumerate(self.blocks):
            for i in range(blk.shape[0]):
                parts.append(np.ascontiguousarray(blk[i, :, :self.nus[c][i]]).ravel())
        self.nu = np.concatenate(self.nus).astype(np.int64)
        sizes = np.array([p_.size for p_ in parts], dtype=np.int64)
        self.vtoff = np.zeros(sizes.size + 1, dtype=np.int64)
        self.vtoff[1:] = np.cumsum(sizes)
        self.values = np.concatenate(parts)

    def dT_max(self, c, v):
        return np.minimum(self.B[c] * v / np.sqrt(v + self.V_lo[c]), self.cap)

    def y_of(self, c, T):
        return np.interp(T, self.T0[c] + self.dTf * np.arange(self.yT.shape[1]), self.yT[c])

    def T_of(self, c, y):
        return np.interp(y, self.yT[c], self.T0[c] + self.dTf * np.arange(self.yT.shape[1]))

    def fill(self, rise0, vs, sweep):
        """Make the table reach the temperatures of this call. ``rise0``: the rise of every row with the friction
        held at its T0 value (an upper bound when the friction falls with temperature); the range covers 1.15
        times it."""
        nc = self.B.size
        for c in range(nc):
            sel = sweep == c
            v = vs[sel]
            need = rise0[sel] * np.sqrt(v + self.V_lo[c]) / v
            self.B[c] = 1.15 * float(np.max(need)) if need.size else 0.0
            if not self.B[c] > 0:
                self.B[c] = 1e-6 * self.cap  # nothing slides: a tiny range keeps the table regular
        self._grow(np.ones(nc, dtype=bool))

    def _grow(self, which):
        """Add the lattice nodes that the sweeps ``which`` need for their current range and are missing."""
        ng = self.gnodes.size
        V_, T_, P_, where = [], [], [], []
        for c in np.flatnonzero(which):
            vv = self.vnodes[self.voff[c]:self.voff[c + 1]]
            ymax = np.minimum(self.y_of(c, self.T0[c] + self.dT_max(c, vv)), self.ycap[c])
            self._capped[c] = self._capped[c] or bool(np.any(ymax >= self.ycap[c] * (1 - 1e-12)))
            # a row between speed nodes interpolates over the four around it: each node covers the range of the
            # two above it as well, and the last four that of the last
            reach = ymax.copy()
            for d in (1, 2):
                reach[:-d] = np.maximum(reach[:-d], ymax[d:])
            reach[-4:] = np.maximum(reach[-4:], ymax[-1])
            n_new = np.maximum(_temperature_counts(reach, 1.0 / self.hy), self.nus[c])
            grow = np.flatnonzero(n_new > self.nus[c])
            if grow.size == 0:
                continue
            blk = self.blocks[c]
            if int(n_new.max()) > blk.shape[2]:
                bigger = np.zeros((blk.shape[0], ng, max(int(n_new.max()), 2 * blk.shape[2])))
                bigger[:, :, :blk.shape[2]] = blk
                self.blocks[c] = bigger
            for i in grow:
                k = np.arange(self.nus[c][i], n_new[i])
                T = self.T_of(c, k * self.hy)
                G, TT = np.meshgrid(self.gnodes, T, indexing="ij")
                V_.append(np.full(G.size, vv[i]))
                P_.append(G.ravel() * self.sig0[c])
                T_.append(TT.ravel())
                where.append((c, i, int(self.nus[c][i]), int(n_new[i])))
            self.nus[c] = n_new
        if not where:
            return
        mu = self._call(np.concatenate(V_), np.concatenate(T_), np.concatenate(P_))
        k = 0
        for c, i, n0, n1 in where:
            m = ng * (n1 - n0)
            self.blocks[c][i, :, n0:n1] = mu[k:k + m].reshape(ng, n1 - n0)
            k += m
        for c in np.flatnonzero(which):
            self.mu_max[c] = max(self.mu_max[c], float(np.max(self.blocks[c])))
        self._layout()

    def targs(self):
        """The temperature arguments of the march kernel."""
        return (self.T0, self.hy, self.cap, self.mu_max, self.yT, self.dTf)

    def has_heated(self) -> bool:
        """Whether every sweep has temperature nodes above T0."""
        return all(int(n.min()) > 1 for n in self.nus)

    def capped(self, c) -> bool:
        return bool(self._capped[c])

    def extend(self, over, umax):
        """Raise the temperature range of the sweeps ``over`` (the patch got hotter than the bound) and grow."""
        for c in np.flatnonzero(over):
            self.B[c] *= 1.25 * float(umax[c])
        self._grow(over)

    def _call(self, v, T, p):
        from .._checks import UnitWarning

        with self._warnings.catch_warnings(record=True) as caught:
            self._warnings.simplefilter("always")
            r = self.model.friction(v, temperature=T, pressure=p)
        for w in caught:
            if issubclass(w.category, UnitWarning):
                continue  # the table's temperatures are degrees Celsius by construction
            self.notes.append(f"{w.category.__name__}: {w.message}")
        self.notes.extend(getattr(r, "notes", ()) or ())
        self.converged = self.converged and bool(getattr(r, "converged", True))
        self.points += v.size
        self.calls += 1
        mu = np.atleast_1d(np.asarray(r.mu, dtype=float))
        if mu.shape != v.shape:
            raise InputError(f"model: friction returned {mu.shape} values for {v.size} speeds")
        bad = ~np.isfinite(mu) | (mu < 0)
        if np.any(bad):
            j = int(np.argmax(bad))
            raise InputError(f"model: local sliding friction {mu[j]!r} at v_s = {v[j]:g} m/s, T = {T[j]:g} C, "
                             f"p = {p[j]:g} Pa; expected a finite value >= 0")
        return mu

    def args(self):
        """The table arguments of the kernels."""
        return (self.lv, self.voff, self.gnodes, self.values, self.vtoff, self.nu)

    def mu_at_sigma0(self, vs, sweep):
        """mu(v_s, sigma0, T0) of every row, interpolated in the T0 slice of the table."""
        return _interp_rows(sweep.astype(np.int64), np.log(vs), *self.args())


def _shift_coordinate(log10_aT, T0: float, T: np.ndarray) -> np.ndarray:
    """y(T) = log10 a_T(T0) - log10 a_T(T) on the increasing temperatures ``T`` (from T0), or (T - T0)/10 when the
    material has no usable shift factor (none, or not finite and increasing in y over the table's first half).
    Beyond the first half (above the cap) a y that stops increasing is continued linearly."""
    import warnings

    half = (T.size + 1) // 2
    y = None
    if log10_aT is not None:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # extrapolated shift factors: the engine's own calls report them
                y = float(np.asarray(log10_aT(T0), dtype=float)) - np.asarray(log10_aT(T), dtype=float)
        except Exception:  # noqa: BLE001  (an unusual material: fall back to kelvin)
            y = None
    if y is None or y.shape != T.shape or not (np.all(np.isfinite(y[:half])) and np.all(np.diff(y[:half]) > 0)):
        return (T - T0) / 10.0
    ok = np.isfinite(y) & np.concatenate([[True], np.diff(y) > 0])
    bad = np.flatnonzero(~ok)
    if bad.size:
        j = int(bad[0])  # >= half
        slope = (y[j - 1] - y[half - 2]) / (T[j - 1] - T[half - 2])
        y[j:] = y[j - 1] + slope * (T[j:] - T[j - 1])
    return y


# =========================================================================================================
# Numba kernels
# =========================================================================================================
def _unit_weights(N: int) -> np.ndarray:
    r"""Product-integration weights of the Abel kernel on a uniform grid of unit spacing.

    For a segment from node j to node j+1 evaluated at node k = j + d (d >= 1), with f linear on the segment,
    :math:`\int f/\sqrt{x_k - x'}\,dx' = h^{1/2}(w_l[d] f_j + w_r[d] f_{j+1})`; see :func:`_segment_weights`.
    Returns shape (2, N) (column 0 unused).
    """
    W = np.zeros((2, N))
    for dd in range(1, N):
        W[0, dd], W[1, dd] = _segment_weights(float(dd), float(dd - 1), 1.0)
    return W


@njit(cache=True)
def _segment_weights(A, B, hs):
    r"""Weights (w_l, w_r) of :math:`\int_{x_k-A}^{x_k-B} f(x')/\sqrt{x_k - x'}\,dx'` for f linear on the
    segment of length hs = A - B (values f_l at its left end, f_r at its right end).

    Exact: :math:`I_0 = 2(\sqrt A - \sqrt B)`, :math:`I_1 = \int (x' - x_l)/\sqrt{x_k - x'} = A I_0 -
    \tfrac23(A^{3/2} - B^{3/2})`, :math:`w_r = I_1/h_s`, :math:`w_l = I_0 - w_r`; written without cancellation
    as :math:`w_l = h_s(2\sqrt A + 4\sqrt B)/(3(\sqrt A + \sqrt B)^2)`,
    :math:`w_r = h_s(4\sqrt A + 2\sqrt B)/(3(\sqrt A + \sqrt B)^2)`.
    """
    ra = np.sqrt(A)
    rb = np.sqrt(B)
    den = 3.0 * (ra + rb) * (ra + rb)
    return hs * (2.0 * ra + 4.0 * rb) / den, hs * (4.0 * ra + 2.0 * rb) / den


@njit(cache=True)
def _lagrange(nodes, start, n, x, w):
    """Four-point (or n-point when n < 4) Lagrange weights at x (clamped into the node range); returns k0."""
    m = 4 if n >= 4 else n
    if n == 1:
        w[0] = 1.0
        return start
    lo = nodes[start]
    hi = nodes[start + n - 1]
    if x < lo:
        x = lo
    elif x > hi:
        x = hi
    # interval j with nodes[j] <= x < nodes[j+1]
    j = 0
    a, b = 0, n - 1
    while b - a > 1:
        mid = (a + b) // 2
        if nodes[start + mid] <= x:
            a = mid
        else:
            b = mid
    j = a
    k0 = j - 1
    if k0 < 0:
        k0 = 0
    if k0 > n - m:
        k0 = n - m
    for i in range(m):
        xi = nodes[start + k0 + i]
        wi = 1.0
        for k in range(m):
            if k != i:
                xk = nodes[start + k0 + k]
                wi *= (x - xk) / (xi - xk)
        w[i] = wi
    return start + k0


@njit(cache=True)
def _lagrange_uniform(n, x, w):
    """Lagrange weights at x on the n uniform nodes 0, 1, .., n - 1 (four nearest; n when n < 4; x clamped into
    [0, n - 1]); returns k0."""
    if n == 1:
        w[0] = 1.0
        return 0
    if x < 0.0:
        x = 0.0
    elif x > n - 1.0:
        x = n - 1.0
    m = 4 if n >= 4 else n
    j = int(x)
    if j > n - 2:
        j = n - 2
    k0 = j - 1
    if k0 < 0:
        k0 = 0
    if k0 > n - m:
        k0 = n - m
    for i in range(m):
        wi = 1.0
        for k in range(m):
            if k != i:
                wi *= (x - (k0 + k)) / (i - k)
        w[i] = wi
    return k0


@njit(cache=True)
def _interp(c, lv, gq, x, lvn, voff, gnodes, values, vtoff, nu, wv, wg, wu):
    """mu of sweep c at (ln v, g, x = y/h) by tensor-product Lagrange interpolation (clamped at 0)."""
    nv = voff[c + 1] - voff[c]
    ng = gnodes.size
    iv = _lagrange(lvn, voff[c], nv, lv, wv)
    ig = _lagrange(gnodes, 0, ng, gq, wg)
    mv = 4 if nv >= 4 else nv
    mg = 4 if ng >= 4 else ng
    return _mu_at(iv, wv, mv, ig, wg, mg, x, values, vtoff, nu, wu)


@njit(cache=True)
def _interp_rows(sweep, lvs, lvn, voff, gnodes, values, vtoff, nu):
    """mu at (v_s, p = sigma0, T0) for every row."""
    out = np.empty(sweep.size)
    wv = np.empty(4)
    wg = np.empty(4)
    wu = np.empty(4)
    for r in range(sweep.size):
        out[r] = _interp(sweep[r], lvs[r], 1.0, 0.0, lvn, voff, gnodes, values, vtoff, nu, wv, wg, wu)
    return out


@njit(cache=True)
def _y_at(yT, c, dT, dTf):
    """y(T0 + dT) of sweep c by linear interpolation in its fine table (clamped to the table)."""
    n = yT.shape[1]
    x = dT / dTf
    if x <= 0.0:
        return yT[c, 0]
    j = int(x)
    if j >= n - 1:
        return yT[c, n - 1]
    t = x - j
    return yT[c, j] + t * (yT[c, j + 1] - yT[c, j])


@njit(cache=True)
def _x_at(yT, c, dT, cap, dTf, hy):
    """Lattice coordinate y(T0 + dT)/h of sweep c, the rise taken at the cap above it."""
    return _y_at(yT, c, dT if dT < cap else cap, dTf) / hy


@njit(cache=True)
def _mu_at(iv, wv, mv, ig, wg, mg, x, values, vtoff, nu, wu):
    """Interpolated mu at the temperature lattice coordinate x = y/h, with the speed weights (iv, wv) and the
    pressure weights (ig, wg) already known."""
    out = 0.0
    for a in range(mv):
        node = iv + a
        n_u = nu[node]
        ku = _lagrange_uniform(n_u, x, wu)
        m_u = 4 if n_u >= 4 else n_u
        base = vtoff[node]
        acc_g = 0.0
        for b in range(mg):
            row = base + (ig + b) * n_u + ku
            acc = 0.0
            for k in range(m_u):
                acc += wu[k] * values[row + k]
            acc_g += wg[b] * acc
        out += wv[a] * acc_g
    return out if out > 0.0 else 0.0


def _march_all(sweep, lvs, a_all, lam_all, xi, g, W, lvn, voff, gnodes, values, vtoff, nu, T0s, hy, cap, mu_max,
               yT, dTf, profiles):
    """March along the patch for every row (see :func:`patch_friction`), in parallel over the rows. ``umax`` of a
    row: its highest y over the top of the table at its speed (> 1: the table must grow; temperatures above
    T0 + cap are taken at the cap)."""
    n = sweep.size
    N = xi.size
    mu_out = np.empty(n)
    xc_out = np.empty(n)
    rise = np.zeros(n)
    umax = np.zeros(n)
    Tprof = np.zeros((n if profiles else 1, N))
    shear = np.zeros((n if profiles else 1, N))
    muprof = np.zeros((n if profiles else 1, N))
    glo = gnodes[0]
    ng = gnodes.size
    # pressure weights of every patch node (those of the stick/slide boundary are computed per row)
    IG = np.empty(N, dtype=np.int64)
    WG = np.empty((N + 1, 4))
    for j in range(N):
        gj = g[j] if g[j] > glo else glo
        IG[j] = _lagrange(gnodes, 0, ng, gj, WG[j])
    for r in prange(n):
        _march_row(r, sweep, lvs, a_all, lam_all, xi, g, W, lvn, voff, gnodes, values, vtoff, nu, T0s, hy, cap,
                   mu_max, yT, dTf, profiles, IG, WG, mu_out, xc_out, rise, umax, Tprof, shear, muprof)
    return mu_out, xc_out, rise, umax, Tprof, shear, muprof


#: The march on every row in parallel (prange over the rows), and on one thread for few rows.
_march_parallel = njit(cache=True, parallel=True)(_march_all)
_march_serial = njit(cache=True)(_march_all)


@njit(cache=True)
def _march_row(r, sweep, lvs, a_all, lam_all, xi, g, W, lvn, voff, gnodes, values, vtoff, nu, T0s, hy, cap, mu_max,
               yT, dTf, profiles, IG, WG, mu_out, xc_out, rise, umax, Tprof, shear, muprof):
    """March along the patch for row r (see :func:`patch_friction`); writes the row's outputs."""
    N = xi.size
    h = xi[1] - xi[0]
    sh = np.sqrt(h)
    wv = np.empty(4)
    wu = np.empty(4)
    wgc = np.empty(4)
    y = np.empty(N + 1)
    gy = np.empty(N + 1)
    f = np.empty(N + 1)
    Ty = np.empty(N + 1)
    d = np.empty(N)
    mu0 = np.empty(N)
    glo = gnodes[0]
    ng = gnodes.size
    mg = 4 if ng >= 4 else ng
    c = sweep[r]
    lv = lvs[r]
    a = a_all[r]
    lam = lam_all[r]
    T0 = T0s[c]
    v = np.exp(lv)
    nv = voff[c + 1] - voff[c]
    iv = _lagrange(lvn, voff[c], nv, lv, wv)
    mv = 4 if nv >= 4 else nv
    ytop = (nu[iv] - 1) * hy  # the table's top at this speed: the lowest over the four speed nodes
    for k in range(1, mv):
        yk = (nu[iv + k] - 1) * hy
        if yk < ytop:
            ytop = yk
    # stick limit at T0 (u = 0)
    for j in range(N):
        mu0[j] = _mu_at(iv, wv, mv, IG[j], WG[j], mg, 0.0, values, vtoff, nu, wu)
    pure = not np.isfinite(a)
    i = -1
    xc = 0.0
    if pure:
        i = 0
    else:
        for j in range(N):
            d[j] = mu0[j] * g[j] - a * xi[j]
        for j in range(1, N):
            if d[j] <= 0.0:
                i = j
                break
    if i < 0:  # the whole patch sticks
        mu_out[r] = 0.5 * a
        xc_out[r] = 1.0
        if profiles:
            for j in range(N):
                Tprof[r, j] = T0
                shear[r, j] = a * xi[j]
                muprof[r, j] = mu0[j]
        return
    # slide points: y[0] = x_c (when between nodes), then the nodes behind it; node of slide point k: jk
    first_special = False
    if pure:
        j0 = 0
    else:
        t = 0.0
        den = d[i - 1] - d[i]
        if den > 0.0:
            t = d[i - 1] / den
        t = min(max(t, 0.0), 1.0)
        xc = xi[i - 1] + t * h
        j0 = i
        if xi[i] - xc > 1e-12:
            first_special = True
    M = 0
    if first_special:
        gc = g[i - 1] + t * (g[i] - g[i - 1])
        y[0] = xc
        gy[0] = gc
        M = 1
        igc = _lagrange(gnodes, 0, ng, gc if gc > glo else glo, wgc)
        f[0] = _mu_at(iv, wv, mv, igc, wgc, mg, 0.0, values, vtoff, nu, wu) * gc
    off = M - j0  # slide index of node j is j + off
    for j in range(j0, N):
        y[M] = xi[j]
        gy[M] = g[j]
        M += 1
    if not first_special:
        f[0] = mu0[j0] * gy[0]
    Ty[0] = T0
    hs = y[1] - y[0] if M > 1 else h
    ru = 0.0
    for k in range(1, M):
        # known part of the Abel integral at y[k]; ck multiplies the unknown f[k]
        S = 0.0
        ck = 0.0
        jstart = 0
        if first_special:
            wl, wr = _segment_weights(y[k] - y[0], y[k] - y[1], hs)
            if k == 1:
                S += wl * f[0]
                ck = wr
            else:
                S += wl * f[0] + wr * f[1]
            jstart = 1
        for jj in range(jstart, k):
            dd = k - jj
            if jj + 1 == k:
                S += sh * W[0, dd] * f[jj]
                ck = sh * W[1, dd]
            else:
                S += sh * (W[0, dd] * f[jj] + W[1, dd] * f[jj + 1])
        # solve F(T) = T - T0 - lam (S + ck g mu(T)) = 0 (secant from the previous node, bisection fallback)
        jn = k - off
        ig = IG[jn]
        base = T0 + lam * S
        coef = lam * ck * gy[k]
        Ta = Ty[k - 1] if Ty[k - 1] > base else base
        ma = _mu_at(iv, wv, mv, ig, WG[jn], mg, _x_at(yT, c, Ta - T0, cap, dTf, hy), values, vtoff, nu, wu)
        Fa = Ta - base - coef * ma
        Tb = base + coef * ma
        ok = abs(Fa) <= 1e-10 * (1.0 + abs(Ta))
        T = Ta
        if not ok:
            for it in range(40):
                mb = _mu_at(iv, wv, mv, ig, WG[jn], mg, _x_at(yT, c, Tb - T0, cap, dTf, hy), values, vtoff,
                            nu, wu)
                Fb = Tb - base - coef * mb
                if abs(Fb) <= 1e-10 * (1.0 + abs(Tb)):
                    T = Tb
                    ok = True
                    break
                if Fb == Fa:
                    break
                Tn = Tb - Fb * (Tb - Ta) / (Fb - Fa)
                Ta, Fa = Tb, Fb
                Tb = Tn
        if not ok:  # bisection on F, F(base) <= 0 <= F(base + coef mu_max)
            lo_ = base
            hi_ = base + coef * mu_max[c] * 1.5 + 1e-12
            for it in range(200):
                mid = 0.5 * (lo_ + hi_)
                mm = _mu_at(iv, wv, mv, ig, WG[jn], mg, _x_at(yT, c, mid - T0, cap, dTf, hy), values, vtoff,
                            nu, wu)
                if mid - base - coef * mm > 0.0:
                    hi_ = mid
                else:
                    lo_ = mid
                if hi_ - lo_ < 1e-10 * (1.0 + abs(mid)):
                    break
            T = 0.5 * (lo_ + hi_)
        x = _x_at(yT, c, T - T0, cap, dTf, hy)
        m = _mu_at(iv, wv, mv, ig, WG[jn], mg, x, values, vtoff, nu, wu)
        if ytop > 0.0:
            u = x * hy / ytop
        elif x > 0.0:
            u = 2.0  # heated, but the table has only the T0 slice here
        else:
            u = 0.0
        if u > ru:
            ru = u
        Ty[k] = T
        f[k] = m * gy[k]
    # wheel friction: stick part exactly, slide part by the trapezoid rule
    tot = 0.0 if pure else 0.5 * a * xc * xc
    for k in range(1, M):
        tot += 0.5 * (y[k] - y[k - 1]) * (f[k] + f[k - 1])
    mu_out[r] = tot
    xc_out[r] = xc
    mx = 0.0
    for k in range(M):
        if Ty[k] - T0 > mx:
            mx = Ty[k] - T0
    rise[r] = mx
    umax[r] = ru
    if profiles:
        for j in range(N):
            if j < j0:
                Tprof[r, j] = T0
                shear[r, j] = a * xi[j]
                muprof[r, j] = mu0[j]
            else:
                k = j + off
                Tprof[r, j] = Ty[k]
                shear[r, j] = f[k]
                muprof[r, j] = f[k] / gy[k] if gy[k] > 0.0 else mu0[j]
