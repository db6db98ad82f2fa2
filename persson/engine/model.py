r"""The Persson friction model: surface + material + conditions + effects -> :class:`FrictionResult`.

Physics (Persson, J. Chem. Phys. 115, 3840 (2001); Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)):

.. math::
    \mu_{visc} = \frac12 \int_{q_0}^{q_1} dq\, q^3 C(q) S(q) P(q) \int_0^{2\pi} d\phi \cos\phi\,
        \frac{\mathrm{Im}\, E(q v \cos\phi, T_q)}{(1-\nu^2)\sigma_0}

.. math::
    P(q) = \mathrm{erf}\left(\frac{1}{2\sqrt{G(q)}}\right),\quad
    G(q) = \frac18 \int_{q_0}^{q} dq' q'^3 C(q') \int_0^{2\pi} d\phi
        \left|\frac{E(q' v\cos\phi, T_{q'})}{(1-\nu^2)\sigma_0}\right|^2

with :math:`S(q) = \gamma + (1-\gamma) P(q)^2` (Yang & Persson, J. Phys.: Condens. Matter 20, 215214 (2008)).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np


from frictioncite import citations_of, doi
from materials.shift import extrapolated_shift_note

from ..contact import corrections, separation
from . import directional, solver
from .anisotropic import is_anisotropic
from .._checks import (UnitWarning, low_road_friction, number, plausible_pressure, plausible_speed,
                      plausible_temperature, unit_slip_notes)
from .conditions import Conditions, SolverState
from ..effects.base import Effect
from ..errors import AccuracyWarning, ConvergenceWarning, InputError, PhysicsWarning
from .grid import GridSettings
from .quadrature import separation_moments as _separation_moments
from ..notes import Note, share_span
from .results import FrictionResult

__all__ = ["Model"]

_PAD_DECADES = 0.5


@doi("10.1063/1.1388626", "10.1088/0953-8984/17/1/R01", "10.1088/0953-8984/20/21/215214")
@dataclass(frozen=True, eq=False, repr=False)
class Model:
    """Persson rubber-friction model.

    Parameters
    ----------
    surface : surfaces.SelfAffine or surfaces.PSD or any object with ``C(q)`` and ``q_range``
        Isotropic 2D PSD (Persson convention); the integrals run over ``surface.q_range``.
    material : materials.ConstantModulus, materials.Prony, materials.MasterCurve, ...
        Any object with ``E(omega, T)`` (complex Young's modulus, Pa); ``log10_aT(T)`` for temperature shifts
        and ``thermal`` for the flash temperature.
    nu : float
        Poisson ratio, 0 <= nu <= 0.5 (default 0.5).
    gamma : float
        Parameter of S(q) = gamma + (1 - gamma) P^2, 0 <= gamma <= 1 (default 0.5; 1 gives S = 1).
    effects : sequence of Effect
        Effects switched on (see :mod:`persson.effects`).
    grid : GridSettings
        Numerical resolution; the defaults keep the quadrature error below 1e-3 of mu from soft to glassy rubber,
        and every result carries its own estimate (``error_estimate``).
    correction : {None, "yang-persson", "xu2024", "wang-muser"}
        Area correction of :mod:`persson.contact.corrections` (None, the default: Persson's P = erf(1/(2 sqrt G))).
        A correction raises the small-load contact area towards exact numerical contact mechanics and, through
        P in the friction integral, the hysteresis friction (by about 40 % on the example road): see
        ``docs/contact.md``.
    direction_deg : float, optional
        Sliding direction, degrees from the x axis of an anisotropic surface (``surfaces.stretched``,
        ``surfaces.unidirectional``, ``HeightMap.psd2d``), used when :meth:`friction` is not given one; None (the
        default) means 0 on an anisotropic surface (the result says so). An isotropic surface ignores it.

    Examples
    --------
    >>> import surfaces, materials, persson
    >>> s = surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6)
    >>> m = materials.ConstantModulus(E_storage=5e6, E_loss=2e6)
    >>> r = persson.Model(s, m, gamma=1.0).friction(1.0, temperature=20.0, pressure=0.3e6)
    >>> round(float(r.contact_area), 3)
    0.263
    """

    surface: object
    material: object
    nu: float = 0.5
    gamma: float = 0.5
    effects: tuple = ()
    grid: GridSettings = field(default_factory=GridSettings)
    correction: str | None = None
    direction_deg: float | None = None

    def __post_init__(self):
        nu = number(self.nu, "nu")
        if not 0.0 <= nu <= 0.5:
            raise InputError(f"nu: expected a Poisson ratio in [0, 0.5], got {nu}")
        gamma = number(self.gamma, "gamma")
        if not 0.0 <= gamma <= 1.0:
            raise InputError(f"gamma: expected a value in [0, 1], got {gamma}")
        if not (hasattr(self.surface, "C") and hasattr(self.surface, "q_range")):
            raise InputError("surface: expected a PSD object with C(q) and q_range (e.g. surfaces.SelfAffine)")
        q_lo, q_hi = (float(x) for x in self.surface.q_range)
        if not (math.isfinite(q_lo) and math.isfinite(q_hi) and 0 < q_lo < q_hi):
            raise InputError(f"surface: expected 0 < q0 < q1, got q_range = ({q_lo:g}, {q_hi:g}) rad/m")
        if not hasattr(self.material, "E"):
            raise InputError("material: expected an object with E(omega, T) (e.g. materials.ConstantModulus)")
        if isinstance(self.effects, Effect) or not hasattr(self.effects, "__iter__"):
            raise InputError(f"effects: expected a list of effects, e.g. effects=[{self.effects!r}], got "
                             f"{type(self.effects).__name__}")
        effects = tuple(self.effects)
        names = [getattr(e, "name", None) for e in effects]
        for e, n in zip(effects, names):
            if not isinstance(e, Effect):
                raise InputError(f"effects: expected persson.effects.Effect instances, got {e!r}")
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise InputError(f"effects: effect(s) {dup} given more than once")
        if sum(1 for e in effects if e.solver_role == "temperature") > 1:
            raise InputError("effects: at most one effect may set the temperature at each scale")
        if not isinstance(self.grid, GridSettings):
            raise InputError(f"grid: expected persson.GridSettings, got {self.grid!r}")
        from ..contact.corrections import check_correction

        object.__setattr__(self, "correction", check_correction(self.correction, gamma)[0])
        object.__setattr__(self, "nu", nu)
        object.__setattr__(self, "gamma", gamma)
        object.__setattr__(self, "effects", effects)
        if self.direction_deg is not None:
            if np.ndim(self.direction_deg) != 0:
                raise InputError(f"direction_deg: expected one sliding direction in degrees, got {self.direction_deg!r}"
                                 " (give several directions to friction(..., direction_deg=[...]))")
            object.__setattr__(self, "direction_deg",
                               float(directional.directions(self.direction_deg, "direction_deg", stacklevel=4)))

    # ----------------------------------------------------------------------------------------------------
    def friction(self, speed, temperature=20.0, pressure=0.3e6, direction_deg=None):
        """Friction, contact area and per-scale detail at the sliding speed(s) ``speed``.

        Parameters
        ----------
        speed : float or array_like
            Sliding speed(s), m/s, > 0.
        temperature : float or array_like
            Background temperature T0, deg C; an array gives one temperature per speed (same length).
        pressure : float or array_like
            Nominal contact pressure sigma0, Pa, > 0; an array gives one pressure per speed.
        direction_deg : float or array_like, optional
            Sliding direction(s), degrees from the x axis of an anisotropic surface (default the model's
            ``direction_deg``, else 0); an isotropic surface's friction does not depend on it.

        Returns
        -------
        FrictionResult or persson.engine.directional.DirectionalFriction
            ``temperature`` and ``pressure`` are floats when given as scalars, else arrays per speed. An array of
            directions gives a ``DirectionalFriction`` (mu per direction and speed, each direction's result, a
            polar plot).

        Notes
        -----
        Speeds with different temperatures share one modulus table through time-temperature superposition,
        E(omega, T) = b_T E(omega a_T, T_table), with ``log10_aT`` (and ``log10_bT`` when present) of the
        material; a material without ``log10_aT`` is evaluated at each distinct temperature separately. A
        material with a reference temperature ``T_ref`` (a master curve) is tabulated there whatever the call's
        temperatures (:func:`persson.engine.solver.table_temperature`), so that each speed's result is the same,
        to rounding, whatever other speeds, temperatures and pressures share its call.
        An anisotropic surface is solved with Persson's angular integrals over C(q, phi) and
        Im E(q v cos(phi - theta)) (:mod:`persson.engine.anisotropic`).
        """
        if direction_deg is not None or self.direction_deg is not None or is_anisotropic(self.surface):
            return directional.friction(self, speed, temperature, pressure, direction_deg)
        return self._friction(speed, temperature, pressure)

    def _friction(self, speed, temperature=20.0, pressure=0.3e6, *, solve=None) -> FrictionResult:
        """:meth:`friction` for one sliding direction; ``solve`` replaces :func:`persson.engine.solver.solve`
        (the anisotropic engine hands in each direction's solution)."""
        v, scalar = _speeds(speed)
        T0 = _per_speed(temperature, "temperature", v.size)
        sigma0 = _per_speed(pressure, "pressure", v.size)
        if np.any(sigma0 <= 0):
            i = int(np.argmax(sigma0 <= 0))
            raise InputError(f"pressure: expected a nominal pressure > 0 Pa, got {sigma0[i]:g}"
                             + (f" at index {i}" if np.ndim(pressure) else ""))
        # unit slips (MPa typed as Pa, kelvin as deg C) warn; below absolute zero is an error
        plausible_pressure(sigma0, "pressure", stacklevel=4)
        plausible_temperature(T0, "temperature", stacklevel=4)
        plausible_speed(v, "speed", stacklevel=4)
        # Conditions keep scalars for scalar arguments (effects written for one temperature keep working)
        T_c = T0 if np.ndim(temperature) else float(T0[0])
        p_c = sigma0 if np.ndim(pressure) else float(sigma0[0])
        cond = Conditions(speed=v, temperature=T_c, pressure=p_c, nominal_pressure=p_c)
        for e in self.effects:
            cond = e.transform_conditions(cond)
        surface, material = self.surface, self.material
        for e in self.effects:
            surface = e.transform_surface(surface, cond)
            material = e.transform_material(material, cond)
        thermal = next((e for e in self.effects if e.solver_role == "temperature"), None)

        modulus = next((e for e in self.effects if type(e).modulus_factors is not Effect.modulus_factors), None)
        solved = (solve or solver.solve)(surface, material, cond, self.grid, self.nu, self.gamma, thermal,
                                         self.correction, modulus)
        state = SolverState(conditions=cond, surface=surface, material=material, q=solved.q,
                            area_q=solved.P, G_q=solved.G, temperature_q=solved.T_q,
                            mu_hysteresis=solved.mu, nu=self.nu, gamma=self.gamma)
        terms: dict[str, np.ndarray] = {}
        for e in self.effects:
            t = e.friction_term(state)
            if t is None:
                continue
            t = np.broadcast_to(np.asarray(t, dtype=float), v.shape).copy()
            if not np.all(np.isfinite(t)):
                raise InputError(f"effect {e.name!r}: friction_term returned non-finite values")
            terms[e.term_kind or e.name] = terms.get(e.term_kind or e.name, 0.0) + t
        mu_adh = terms.get("adhesion", np.zeros_like(v))
        # The hysteresis acts on the load the asperities carry; normalise by the total nominal load.
        load_share = np.asarray(cond.pressure, dtype=float) / cond.nominal_pressure
        mu_hys = solved.mu * load_share
        mu_total = mu_hys + sum(terms.values(), np.zeros_like(v))

        notes = list(_surface_notes(surface)) + list(solved.notes)
        for msg in _physics_notes(self.surface, surface, solved, mu_total, self.effects):
            notes.append(msg)
            warnings.warn(msg, PhysicsWarning, stacklevel=3)
        # rubber temperatures (background + flash) beyond where the shift law was fitted: one note per call
        msg = extrapolated_shift_note(self.material, float(np.min(solved.T_q)), float(np.max(solved.T_q)))
        if msg is not None:
            notes.append(Note(msg, "extrapolated"))
            warnings.warn(msg, PhysicsWarning, stacklevel=3)
        loss_free = _loss_free_note(surface, material, solved, v, mu_total, self.gamma)
        if loss_free is not None:
            notes.append(Note(loss_free, "physics"))
            warnings.warn(loss_free, PhysicsWarning, stacklevel=3)
        for msg in unit_slip_notes(surface, mu_total, solved.P[:, -1], low_mu_explained=loss_free is not None):
            notes.append(Note(msg, "input"))
            warnings.warn(msg, UnitWarning, stacklevel=3)
        if not solved.converged:
            bad = np.flatnonzero(~solved.converged_each)
            msg = (f"flash temperature did not converge at {bad.size} of {v.size} speeds "
                   f"(max residual {np.max(solved.residual):.3g} K)")
            notes.append(Note(msg, "convergence"))
            warnings.warn(msg, ConvergenceWarning, stacklevel=3)
        # inside solver.friction_only() (a fit's many calls) the friction alone
        outside = (modulus_extrapolated_share(self.material, v, solved.q, solved.T_q, solved.mu_cumulative)
                   if solver.wants_extrapolated_share() else None)
        msg = None if outside is None else _outside_modulus_note(self.material, outside)
        if msg is not None:
            notes.append(Note(msg, "extrapolated"))
            if float(np.max(outside)) > MODULUS_SHARE_WARNING:
                warnings.warn(msg, PhysicsWarning, stacklevel=3)
        coarse_grid = solved.error_estimate > self.grid.tolerance
        if np.any(coarse_grid):
            bad = np.flatnonzero(coarse_grid)
            msg = (f"estimated quadrature error above the tolerance {self.grid.tolerance:g} at {bad.size} of "
                   f"{v.size} speeds (largest {np.max(solved.error_estimate):.2g}, at v = "
                   f"{v[bad[np.argmax(solved.error_estimate[bad])]]:.3g} m/s): raise GridSettings.q_per_decade")
            notes.append(Note(msg, "accuracy"))
            warnings.warn(msg, AccuracyWarning, stacklevel=3)
        out = _shape
        C_nodes = np.asarray(surface.C(solved.q), dtype=float)
        hrms = math.sqrt(solver.psd_moment(surface, solved.q, 1))
        if not solver.wants_contact_geometry():  # inside solver.friction_only(): the friction alone
            u_bar = depth = None
        elif hrms > 0:
            u_bar, per_load = solver.derived(
                solved, ("separation_and_energy", self.gamma, self.correction),
                lambda: separation.separation_and_energy(solved.q, C_nodes, solved.G, self.gamma,
                                                         correction=self.correction,
                                                         s=_separation_moments(surface, solved.q)))
            # the depth of the highest asperities, never less than the load-weighted mean 2 U_el / sigma0
            depth = separation.penetration_depth(u_bar, hrms, energy_per_load=per_load)
        else:  # no roughness: the rubber touches the flat everywhere
            u_bar = np.zeros(v.size)
            depth = np.zeros(v.size)

        result = FrictionResult(
            speed=v, temperature=float(T0[0]) if np.ndim(temperature) == 0 else T0,
            pressure=float(sigma0[0]) if np.ndim(pressure) == 0 else sigma0,
            mu=out(mu_total, scalar), mu_hysteresis=out(mu_hys, scalar), mu_adhesion=out(mu_adh, scalar),
            mu_terms={k: out(t, scalar) for k, t in terms.items()},
            contact_area=out(solved.P[:, -1], scalar),
            q=solved.q, area_q=solved.P, G_q=solved.G, temperature_q=solved.T_q, dmu_dlnq=solved.dmu,
            max_flash_temperature=out(np.max(solved.T_q, axis=1) - T0, scalar),
            mean_separation=None if u_bar is None else out(u_bar, scalar),
            penetration_depth=None if depth is None else out(depth, scalar),
            excited_layer_thickness=out(solved.excited_layer, scalar),
            mu_cumulative=solved.mu_cumulative * np.broadcast_to(np.asarray(load_share, dtype=float), v.shape)[:, None],
            load_share=out(np.broadcast_to(np.asarray(load_share, dtype=float), v.shape).copy(), scalar),
            error_estimate=out(solved.error_estimate, scalar),
            modulus_extrapolated_share=None if outside is None else out(outside, scalar),
            effects=tuple(e.name for e in self.effects), converged=bool(solved.converged),
            iterations=solved.iterations, residual=solved.residual, notes=tuple(notes),
            citations=citations_of(type(self), separation.mean_separation, surface, material,
                                   *(type(e) for e in self.effects), corrections.citations(self.correction)),
            scalar=scalar,
        )
        if modulus is not None and hasattr(modulus, "strain_report"):  # share of mu from unmeasured strains
            result = modulus.strain_report(result, np.sqrt(solver.moments_at_nodes(surface, solved.q, 3)))
        for e in self.effects:
            result = e.transform_result(result)
        return result

    def __repr__(self) -> str:
        extra = f", correction={self.correction!r}" if self.correction else ""
        extra += f", direction_deg={self.direction_deg:g}" if self.direction_deg is not None else ""
        grid = "" if self.grid == GridSettings() else f", grid={self.grid!r}"
        return (f"Model(surface={self.surface!r}, material={self.material!r}, nu={self.nu:g}, gamma={self.gamma:g}, "
                f"effects={list(self.effect_names)}{extra}{grid})")

    # ----------------------------------------------------------------------------------------------------
    def with_effect(self, effect: Effect) -> "Model":
        """A copy with ``effect`` added (replacing an effect of the same name)."""
        if not isinstance(effect, Effect):
            raise InputError(f"effect: expected a persson.effects.Effect, got {effect!r}")
        kept = tuple(e for e in self.effects if e.name != effect.name)
        return self.replace(effects=kept + (effect,))

    def without(self, name: str) -> "Model":
        """A copy without the effect called ``name``."""
        if name not in self.effect_names:
            raise InputError(f"without: no effect named {name!r} in the model (has {list(self.effect_names)})")
        return self.replace(effects=tuple(e for e in self.effects if e.name != name))

    def effect(self, name: str) -> Effect:
        """The effect called ``name``."""
        for e in self.effects:
            if e.name == name:
                return e
        raise InputError(f"effect: no effect named {name!r} in the model (has {list(self.effect_names)})")

    @property
    def effect_names(self) -> tuple[str, ...]:
        """Names of the effects switched on."""
        return tuple(e.name for e in self.effects)

    def replace(self, **changes) -> "Model":
        """Copy with fields changed (surface, material, nu, gamma, effects, grid)."""
        import dataclasses

        return dataclasses.replace(self, **changes)


# ---------------------------------------------------------------------------------------------------------
def _physics_notes(original, surface, solved, mu, effects):
    """Facts that make a result doubtful: the theory's small-slope assumption, friction above 3, a PSD cut by an
    effect, a surface without roughness."""
    slope = math.sqrt(max(solver.psd_moment(surface, solved.q, 3), 0.0))
    if slope == 0.0:
        yield Note("the surface has no roughness over its q range (C(q) = 0): full contact, no hysteresis "
                   "friction; check the profile or PSD", "physics")
    elif slope > _MAX_SLOPE:
        yield Note(f"rms slope {slope:.3g} over q = {solved.q[0]:.3g}..{solved.q[-1]:.3g} rad/m is far above 1: "
                   "Persson's theory assumes small slopes; check the short-wavelength cut-off q1 (an extrapolated "
                   "tail or an instrument noise floor often causes this)", "physics")
    if np.any(np.asarray(mu) > _MAX_MU):
        yield Note(f"friction coefficient up to {float(np.max(mu)):.3g} (> {_MAX_MU:g}): physically implausible "
                   "for rubber; check the surface's q1, the modulus units and the pressure", "physics")
    q_hi, q_hi0 = float(surface.q_range[1]), float(original.q_range[1])
    if q_hi < q_hi0 * (1 - 1e-9) and not any(getattr(e, "cuts_psd_on_purpose", False) for e in effects):
        names = [e.name for e in effects if hasattr(e, "q1")] or [e.name for e in effects]
        yield Note(f"the effects ({', '.join(names)}) cut the PSD at q1 = {q_hi:.4g} rad/m, below the surface's "
                   f"own q1 = {q_hi0:.4g} rad/m: the roughness between them is ignored", "input")


#: Above these the result carries a PhysicsWarning (small-slope theory; friction of rubber).
_MAX_SLOPE = 3.0
_MAX_MU = 3.0


def modulus_extrapolated_share(material, speed, q, temperature_q, mu_cumulative) -> np.ndarray | None:
    r"""Share of the hysteresis friction that comes from reduced frequencies outside the compound's measured range.

    At scale q the loss integral :math:`\int_0^{\pi/2} \cos\phi\, \mathrm{Im}\,E(q v \cos\phi)\, d\phi`
    (Persson, J. Chem. Phys. 115, 3840 (2001)) samples the reduced frequencies
    :math:`\omega_r = q v \cos\phi\, a_T(T_q)` from 0 up to :math:`\Omega = q v a_T`. With the weight
    :math:`\cos\phi` (the modulus held aside), the part of the band above the data's top :math:`\omega_{hi}` is
    :math:`\sqrt{1 - c_{hi}^2}` with :math:`c_{hi} = \min(1, \omega_{hi}/\Omega)`, the part below its bottom
    :math:`\omega_{lo}` is :math:`1 - \sqrt{1 - c_{lo}^2}`; each interval of the wavevector grid carries its own
    friction (the differences of ``mu_cumulative``) times the mean of these fractions at its ends.

    Parameters
    ----------
    material : object
        The compound; needs ``frequency_range`` (rad/s at its reference temperature, as
        :class:`materials.MasterCurve` has) and ``log10_aT``, else None is returned.
    speed : ndarray (n_speed,)
        Sliding speeds, m/s.
    q : ndarray (n_q,)
        Wavevector nodes, rad/m.
    temperature_q : ndarray (n_speed, n_q)
        Rubber temperature at each scale (background and flash), deg C.
    mu_cumulative : ndarray (n_speed, n_q)
        Hysteresis friction of the scales q0..q.

    Returns
    -------
    ndarray (n_speed,) or None
        In [0, 1]; 0 where the friction is 0.
    """
    rng, shift = getattr(material, "frequency_range", None), getattr(material, "log10_aT", None)
    if rng is None or not callable(shift):
        return None
    lo, hi = (float(x) for x in rng)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # a shift beyond its fitted temperatures has its own note
        log_aT = np.asarray(shift(np.asarray(temperature_q, dtype=float)), dtype=float)
    top = np.asarray(speed, dtype=float)[:, None] * np.asarray(q, dtype=float)[None, :] * 10.0 ** log_aT
    c_hi = np.clip(hi / top, 0.0, 1.0)
    c_lo = np.clip(lo / top, 0.0, 1.0)
    frac = np.clip(np.sqrt(1.0 - c_hi ** 2) + 1.0 - np.sqrt(1.0 - c_lo ** 2), 0.0, 1.0)
    cum = np.atleast_2d(np.asarray(mu_cumulative, dtype=float))
    part = np.sum(np.diff(cum, axis=1) * 0.5 * (frac[:, 1:] + frac[:, :-1]), axis=1)
    total = cum[:, -1]
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.clip(np.where(total > 0, part / np.where(total > 0, total, 1.0), 0.0), 0.0, 1.0)


#: Above this share of mu_hysteresis from frequencies outside the measured master curve a result warns
#: (PhysicsWarning); from 1 % on it carries a note.
MODULUS_SHARE_WARNING = 0.5
_MODULUS_SHARE_NOTE = 0.01


def _outside_modulus_note(material, share) -> str | None:
    top = float(np.max(share)) if np.size(share) else 0.0
    if top < _MODULUS_SHARE_NOTE:
        return None
    rng = share_span(share)
    lo, hi = material.frequency_range
    T_ref = getattr(material, "T_ref", None)
    at = f" at T_ref = {float(T_ref):g} C" if isinstance(T_ref, (int, float)) else ""
    return (f"{rng} of mu_hysteresis comes from reduced frequencies outside the measured master curve ({lo:.3g}-"
            f"{hi:.3g} rad/s{at}), where the modulus is its extrapolation (modulus_extrapolated_share per speed); "
            "measurements at lower temperatures or higher frequencies would cover the small scales")


def _loss_free_note(surface, material, solved, v, mu, gamma) -> str | None:
    r"""A friction coefficient below 1e-3 on a road-scale surface that the compound's own loss explains, as a
    message (None otherwise, and :func:`persson._checks.unit_slip_notes` then takes it for a unit slip).

    In small contact Persson's hysteresis friction for a modulus of constant phase :math:`\delta` tends to

    .. math:: \mu \to \frac{4\sqrt 2}{\pi^{3/2}}\, \gamma \sin\delta\; \xi(q_1)
              \approx 1.02\, \gamma \sin\delta\; \xi(q_1)

    (Persson, J. Chem. Phys. 115, 3840 (2001), with :math:`S = \gamma + (1 - \gamma) P^2` of Yang & Persson,
    J. Phys.: Condens. Matter 20, 215214 (2008); :math:`\xi(q_1)` the rms slope). A glassy rubber, or an unfilled
    one on its rubbery plateau, has :math:`\tan\delta` of 0.001-0.05 and so a friction that can fall below 1e-3 on
    any road. The low friction is taken as the compound's when the largest :math:`\tan\delta` at the frequencies
    the surface excites at the lowest-friction speed, :math:`\omega = q v \cos\phi` with :math:`\cos\phi` from
    0.1 to 1 (99.5 % of the :math:`\cos\phi`-weighted angular integral) at each scale's rubber temperature, is
    below :data:`_LOSS_FREE_TAN` and the friction is within 3 times that limit (a modulus rising with frequency gives
    somewhat more than the constant-phase value).
    """
    i = low_road_friction(surface, mu)
    if i is None:
        return None
    q = np.asarray(solved.q, dtype=float)
    T = np.asarray(solved.T_q, dtype=float)[i]
    cos_phi = np.geomspace(0.1, 1.0, 5)
    tan_max, E_lo, E_hi = 0.0, math.inf, 0.0
    for j in range(q.size):
        try:
            E = np.asarray(material.E(v[i] * q[j] * cos_phi, float(T[j])), dtype=complex)
        except (ValueError, ArithmeticError):  # a material that refuses these conditions: say what is known
            return None
        tan_max = max(tan_max, float(np.max(E.imag / E.real)))
        E_lo, E_hi = min(E_lo, float(np.min(np.abs(E)))), max(E_hi, float(np.max(np.abs(E))))
    xi = math.sqrt(max(solver.psd_moment(surface, q, 3), 0.0))
    limit = 4.0 * math.sqrt(2.0) / math.pi ** 1.5 * gamma * math.sin(math.atan(tan_max)) * xi
    m = float(np.atleast_1d(mu)[i])
    if not (tan_max < _LOSS_FREE_TAN and m <= 3.0 * limit):
        return None
    state = ("glassy" if E_lo > _GLASSY_E else "on its rubbery plateau" if E_hi < _GLASSY_E else
             "glassy at its smallest scales")
    return (f"friction coefficient {m:.3g} at {v[i]:.3g} m/s on a road-scale surface: the compound is nearly "
            f"loss-free at the frequencies this surface excites there ({state}: tan delta at most {tan_max:.2g} "
            f"for omega = {0.1 * v[i] * q[0]:.3g}-{v[i] * q[-1]:.3g} rad/s at {_span(T, 'C')}, |E| = "
            f"{_span((E_lo, E_hi), 'Pa')}), and Persson's hysteresis in small contact "
            f"is about 1.02 gamma sin(delta) times the rms slope ({xi:.3g}): at most {limit:.2g}. That is the "
            "compound's modulus, not a unit slip; check its loss at these frequencies (beyond the measured ones it "
            "is an extrapolation of the master curve, and a Prony series has no loss above its shortest relaxation "
            "time)")


def _span(x, unit: str) -> str:
    lo, hi = float(np.min(x)), float(np.max(x))
    return f"{lo:.3g} {unit}" if f"{lo:.3g}" == f"{hi:.3g}" else f"{lo:.3g} to {hi:.3g} {unit}"


#: Largest tan delta of a compound taken as nearly loss-free (rubber in its glass transition has 0.2-1.5, a filled
#: compound 0.1-0.2 on its rubbery plateau; a glassy polymer 0.001-0.05).
_LOSS_FREE_TAN = 0.05
#: Above this |E| (Pa) the rubber is called glassy in the message (rubbery plateaus are 1-20 MPa, glasses ~1 GPa).
_GLASSY_E = 1.0e8


def _surface_notes(surface):
    q_r = getattr(surface, "q_r", None)
    q_hi = float(surface.q_range[1])
    if getattr(surface, "extrapolated", False) or (q_r is not None and q_hi > q_r * (1 + 1e-9)):
        yield Note(f"PSD tail extrapolated past the instrument reliability limit q_r = {q_r:g} rad/m "
                   f"to q1 = {q_hi:g} rad/m" if q_r is not None else "PSD tail extrapolated", "extrapolated")


def _shape(a: np.ndarray, scalar: bool):
    return float(a[0]) if scalar else a


def _per_speed(value, name: str, n: int) -> np.ndarray:
    """A scalar or an array of length n (one value per speed) as a float array of length n."""
    if np.ndim(value) == 0:
        return np.full(n, number(value, name))
    try:
        a = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected a number or an array of numbers, got {value!r}") from None
    if a.size != n:
        raise InputError(f"{name}: expected a scalar or one value per speed ({n}), got {a.size} values")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name}: NaN or infinite value at index {int(np.argmax(~np.isfinite(a)))}")
    return a


def _speeds(speed) -> tuple[np.ndarray, bool]:
    try:
        v = np.asarray(speed, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"speed: expected a number or an array of numbers in m/s, got {speed!r}") from None
    scalar = v.ndim == 0
    v = np.atleast_1d(v).ravel()
    if v.size == 0:
        raise InputError("speed: expected at least one speed")
    if not np.all(np.isfinite(v)):
        raise InputError(f"speed: NaN or infinite value at index {int(np.argmax(~np.isfinite(v)))}")
    if np.any(v <= 0):
        raise InputError(f"speed: expected speeds > 0 m/s, got {v[np.argmax(v <= 0)]:g} at index "
                         f"{int(np.argmax(v <= 0))}")
    return np.ascontiguousarray(v), scalar
