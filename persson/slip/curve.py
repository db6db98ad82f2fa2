"""Friction against slip ratio from a friction model: :func:`mu_slip` (brush model, optionally with patch heating) and :func:`predict_slip`."""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from frictioncite import citations_of, doi

from materials.shift import SHIFT_RANGE_NOTE

from .._checks import finite_array, number, positive
from ..errors import InputError, PhysicsWarning
from ..notes import kinds
from ._arrays import _broadcast, _slip_array, _speed_array
from .brush import _a_of, _brush
from .contact import Contact
from .references import PACEJKA_BOOK

__all__ = ["SlipResult", "PatchProfile", "mu_slip", "predict_slip", "ROAD_SPEED"]

#: Rolling speeds from which :func:`mu_slip` notes a model without frictional heating, m/s (18 km/h: a sliding
#: tread heats by tens of kelvin there).
ROAD_SPEED = 5.0


# =========================================================================================================
# mu(slip, V) from a friction model
# =========================================================================================================
@dataclass(frozen=True, eq=False)
class SlipResult:
    """Friction against slip ratio and speed from the brush model.

    Array attributes have the broadcast shape of the ``slip`` and ``speed`` arguments (floats when both are
    scalars).

    Attributes
    ----------
    slip : ndarray or float
        Braking slip ratio s = (V - omega r)/V.
    speed : ndarray or float
        Rolling reference speed V, m/s.
    sliding_speed : ndarray or float
        v_s = s V, m/s.
    mu : ndarray or float
        Friction coefficient of the wheel (longitudinal force / normal load).
    mu_local : ndarray or float
        Local sliding friction mu(v_s) of the friction model.
    stick_length : ndarray or float
        Length x_c of the stick (adhesion) zone from the leading edge, m; the slide zone is x_c < x <= l.
    stick_fraction : ndarray or float
        x_c / l (1: the whole patch sticks; 0: pure sliding).
    force : ndarray or float
        Longitudinal (braking) force mu sigma0 l w, N.
    load : float
        Normal load sigma0 l w, N.
    temperature, pressure : float
        Background temperature T0 (deg C) and mean pressure sigma0 (Pa) of the friction model.
    contact : Contact
    friction : FrictionResult or None
        The friction model's result at the distinct sliding speeds ``friction.speed`` (None for a plain
        function, and with patch heating, where the engine is evaluated on a table: see ``patch``).
    converged : bool
        Whether the friction model's self-consistent iterations converged at every sliding speed.
    notes : tuple of str
    citations : tuple of str
    patch : PatchProfile or None
        With patch heating: the temperature, shear and local friction along the patch for every (slip, speed).
    """

    slip: np.ndarray
    speed: np.ndarray
    sliding_speed: np.ndarray
    mu: np.ndarray
    mu_local: np.ndarray
    stick_length: np.ndarray
    stick_fraction: np.ndarray
    force: np.ndarray
    load: float
    temperature: float
    pressure: float
    contact: Contact
    friction: object = None
    converged: bool = True
    notes: tuple = ()
    citations: tuple = ()
    patch: object = None

    @property
    def note_kinds(self) -> tuple:
        """The kind of every note (:data:`persson.notes.KINDS`; None for a plain-text note)."""
        return kinds(self.notes)

    @property
    def slide_fraction(self):
        """1 - x_c / l, the fraction of the patch length that slides."""
        return 1.0 - self.stick_fraction

    def peak(self, axis: int = 0):
        """(peak mu, slip at peak) along ``axis`` (the axis over which the slip varies).

        See :func:`persson.slip.peak`.
        """
        from .peaks import peak

        return peak(np.asarray(self.slip), np.asarray(self.mu), axis=axis)

    def as_table(self) -> dict[str, np.ndarray]:
        """Flat columns ``slip, speed_m_s, sliding_speed_m_s, mu, mu_local, stick_fraction, stick_length_m,
        force_N`` (and ``max_temperature_rise_K`` with patch heating)."""
        cols = {
            "slip": self.slip, "speed_m_s": self.speed, "sliding_speed_m_s": self.sliding_speed, "mu": self.mu,
            "mu_local": self.mu_local, "stick_fraction": self.stick_fraction, "stick_length_m": self.stick_length,
            "force_N": self.force,
        }
        if self.patch is not None:
            cols["max_temperature_rise_K"] = self.patch.max_rise
        return {k: np.atleast_1d(np.asarray(v, dtype=float)).ravel() for k, v in cols.items()}

    def to_csv(self, path, comments: tuple[str, ...] = (), *, overwrite: bool = False):
        """Write :meth:`as_table` as a CSV (atomically), with the conditions and contact as comment lines; an
        existing file only with ``overwrite=True``."""
        from ..io import write_csv

        c = self.contact
        head = (f"brush model: T0 = {self.temperature:g} C, sigma0 = {self.pressure:g} Pa, l = {c.length:g} m, "
                f"w = {c.width:g} m, k = {c.stiffness:g} Pa/m, pressure = {c.pressure_distribution!r}",)
        return write_csv(path, self.as_table(), comments=head + tuple(comments) + tuple(self.notes),
                         overwrite=overwrite)


@dataclass(frozen=True, eq=False)
class PatchProfile:
    """What happens along the contact patch, for every (slip, speed) of a :func:`mu_slip` call with patch heating.

    Attributes
    ----------
    x : ndarray (N,)
        Distance from the leading edge, m (the contact's nodes).
    temperature : ndarray (..., N)
        Background temperature of the rubber at x, deg C (T0 in the stick zone); leading axes those of
        ``SlipResult.mu``.
    shear : ndarray (..., N)
        Shear stress over the mean pressure, tau(x)/sigma0 (k theta x / sigma0 in the stick zone).
    mu_local : ndarray (..., N)
        Local friction coefficient mu(v_s, p(x), T(x)) (at T0 in the stick zone: the sticking limit).
    pressure : ndarray (N,)
        p(x), Pa.
    max_rise : ndarray or float
        Largest background temperature rise along the patch, K.
    heating : persson.effects.PatchHeating
    table_points : int
        Engine evaluations spent on the friction table.
    engine_calls : int
    """

    x: np.ndarray
    temperature: np.ndarray
    shear: np.ndarray
    mu_local: np.ndarray
    pressure: np.ndarray
    max_rise: np.ndarray
    heating: object
    table_points: int
    engine_calls: int


@doi(PACEJKA_BOOK)
def mu_slip(model, slip, speed, *, temperature: float = 20.0, pressure: float = 0.3e6,
            contact: Contact, profiles: bool = True) -> SlipResult:
    r"""Friction coefficient against braking slip ratio and speed (steady-state brush model).

    Parameters
    ----------
    model : persson.Model or callable
        The local sliding friction :math:`\mu(v_s, T_0, \sigma_0)`: a :class:`persson.Model` (with its effects)
        or any object with ``friction(speed, temperature=, pressure=)`` returning ``.mu``; or a plain function
        ``mu(v_s)`` of an array of sliding speeds (then ``temperature`` is not used).
    slip : float or array_like
        Braking slip ratio s = (V - omega r)/V in (0, 1]; 1 is pure sliding.
    speed : float or array_like
        Rolling reference speed V, m/s (> 0). Broadcast against ``slip`` (e.g. ``slip[:, None]`` and
        ``speed[None, :]`` for a family of curves).
    temperature : float
        Background temperature T0, deg C.
    pressure : float
        Mean contact pressure sigma0, Pa (> 0): the pressure of the friction model and of the brush.
    contact : Contact
        The contact patch.
    profiles : bool
        With patch heating, keep the profiles along the patch (``SlipResult.patch``; default True).

    Returns
    -------
    SlipResult
        ``.mu`` etc. with the broadcast shape of ``slip`` and ``speed``; the friction model is evaluated once,
        at the distinct sliding speeds s V (with patch heating: once on a table over speed, pressure and
        temperature, plus once at T0 to bound the heating; see :func:`persson.slip.patch_friction`).

    Notes
    -----
    The model is used as given. At road speeds (V >= :data:`ROAD_SPEED`) a
    :class:`persson.Model` without :class:`~persson.effects.PatchHeating` and
    :class:`~persson.effects.FlashTemperature` leaves out the frictional heating that shapes a measured curve
    (the fall behind the peak, the hot locked wheel): the result notes it, and :func:`persson.slip.road_model`
    or :func:`persson.slip.with_road_heating` give the model with both, the documented choice at road speeds.
    Rubber temperatures beyond the range where the shift law was fitted are warned once per call
    (:class:`PhysicsWarning`, see :func:`materials.extrapolated_shift_note`) and noted.

    Raises
    ------
    InputError
        Slip outside (0, 1], speed <= 0, non-finite values, pressure <= 0, a contact that is not a
        :class:`Contact`, or a friction model returning negative or non-finite friction.
    """
    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    s = _slip_array(slip)
    V = _speed_array(speed)
    T0 = number(temperature, "temperature")
    sigma0 = positive(pressure, "pressure")
    try:
        s_b, V_b = np.broadcast_arrays(s, V)
    except ValueError:
        raise InputError(f"slip, speed: shapes {s.shape} and {V.shape} do not broadcast") from None
    shape = s_b.shape
    scalar = shape == ()
    s_f = s_b.ravel().astype(float)
    V_f = V_b.ravel().astype(float)
    vs = s_f * V_f
    heating = _heating_of(model)
    if heating is not None:
        return _mu_slip_patch(model, heating, s_f, V_f, T0, sigma0, contact, shape, profiles)
    road_note = _road_speed_note(model, V_f)
    v_unique, inverse = _distinct(vs)
    mu_u, fr = _local_friction(model, v_unique, T0, sigma0)
    mu_loc = mu_u[inverse]
    a = _a_of(s_f, contact, sigma0)
    mu, xc, _ = _brush(contact._xi, contact._g, contact._G, a, mu_loc, mu_loc)
    load = contact.load(sigma0)

    def out(x):
        x = np.asarray(x, dtype=float).reshape(shape)
        return float(x) if scalar else x

    notes = tuple(getattr(fr, "notes", ()) or ()) + road_note
    converged = bool(getattr(fr, "converged", True))
    return SlipResult(
        slip=out(s_f), speed=out(V_f), sliding_speed=out(vs), mu=out(mu), mu_local=out(mu_loc),
        stick_length=out(xc * contact.length), stick_fraction=out(xc), force=out(mu * load), load=load,
        temperature=T0, pressure=sigma0, contact=contact, friction=fr, converged=converged, notes=notes,
        citations=citations_of(mu_slip, contact.citations, fr if fr is not None else ()),
    )


def _heating_of(model):
    """The model's PatchHeating effect, or None."""
    names = getattr(model, "effect_names", ())
    if "patch_heating" in names:
        return model.effect("patch_heating")
    return None


def _road_speed_note(model, V: np.ndarray) -> tuple[str, ...]:
    """A note when a Model without frictional heating is asked for road speeds (see :func:`mu_slip`)."""
    names = getattr(model, "effect_names", None)
    if names is None or float(np.max(V)) < ROAD_SPEED:
        return ()
    missing = [n for n in ("flash_temperature", "patch_heating") if n not in names]
    if not missing:
        return ()
    return (f"slip curve at road speeds (V >= {ROAD_SPEED:g} m/s) without {' and '.join(missing)}: the flash "
            "temperature and the heating along the patch shape the fall behind the peak and the locked wheel; "
            "persson.slip.road_model (or with_road_heating) has both",)


def _warn_shift_range(notes) -> tuple[str, ...]:
    """Warn once for the notes that say the rubber left the shift law's fitted range (the friction tables collect
    them from their engine calls without raising them); the notes, with those in their plain form, once."""
    out, said = [], None
    for n in notes:
        i = n.find(SHIFT_RANGE_NOTE)
        if i > 0 and n[:i].rstrip().endswith(":"):         # "PhysicsWarning: <note>" as the tables record it
            n = n[i:]
        if n.startswith(SHIFT_RANGE_NOTE) and said is None:
            said = n
        out.append(n)
    if said is not None:
        warnings.warn(said, PhysicsWarning, stacklevel=4)
    return tuple(dict.fromkeys(out))


def _mu_slip_patch(model, heating, s_f, V_f, T0, sigma0, contact, shape, profiles) -> SlipResult:
    from .heating import patch_friction

    sol = patch_friction(model, heating, contact, s_f, V_f, T0, sigma0, profiles=profiles, warn_shift_range=False)
    scalar = shape == ()
    load = contact.load(sigma0)

    def out(x):
        x = np.asarray(x, dtype=float).reshape(shape)
        return float(x) if scalar else x

    prof = None
    if profiles:
        N = sol.xi.size
        prof = PatchProfile(x=sol.xi * contact.length, temperature=sol.temperature.reshape(shape + (N,)),
                            shear=sol.shear.reshape(shape + (N,)), mu_local=sol.mu_profile.reshape(shape + (N,)),
                            pressure=sigma0 * contact._g.copy(), max_rise=out(sol.max_rise), heating=heating,
                            table_points=sol.table_points, engine_calls=sol.engine_calls)
    vs = s_f * V_f
    return SlipResult(
        slip=out(s_f), speed=out(V_f), sliding_speed=out(vs), mu=out(sol.mu), mu_local=out(sol.mu_local),
        stick_length=out(sol.stick_fraction * contact.length), stick_fraction=out(sol.stick_fraction),
        force=out(sol.mu * load), load=load, temperature=T0, pressure=sigma0, contact=contact, friction=None,
        converged=sol.converged, notes=_warn_shift_range(sol.notes + _road_speed_note(model, V_f)),
        citations=citations_of(mu_slip, contact.citations, type(heating), model), patch=prof,
    )


def _distinct(v: np.ndarray, rtol: float = 1e-12):
    """Distinct values of ``v`` (merging values within ``rtol``) and the index of each element in them."""
    order = np.argsort(v, kind="stable")
    vs = v[order]
    new = np.empty(vs.size, dtype=bool)
    new[0] = True
    new[1:] = vs[1:] > vs[:-1] * (1.0 + rtol)
    group = np.cumsum(new) - 1
    inverse = np.empty(v.size, dtype=np.intp)
    inverse[order] = group
    return np.ascontiguousarray(vs[new]), inverse


def _local_friction(model, v: np.ndarray, T0: float, sigma0: float):
    if hasattr(model, "friction"):
        fr = model.friction(v, temperature=T0, pressure=sigma0)
        mu = np.atleast_1d(np.asarray(fr.mu, dtype=float))
    elif callable(model):
        fr = None
        try:
            mu = np.asarray(model(v), dtype=float)
        except InputError:
            raise
        except Exception as exc:  # noqa: BLE001
            raise InputError(f"model: the friction function failed on the sliding speeds: {exc}") from None
        try:
            mu = np.broadcast_to(mu, v.shape).astype(float)
        except ValueError:
            raise InputError(f"model: the friction function returned shape {mu.shape} for {v.size} speeds") from None
    else:
        raise InputError("model: expected a persson.Model (or an object with friction(speed, temperature=, "
                         f"pressure=)) or a function mu(sliding_speed), got {model!r}")
    if mu.shape != v.shape:
        raise InputError(f"model: friction returned {mu.shape} values for {v.size} sliding speeds")
    bad = ~np.isfinite(mu) | (mu < 0)
    if np.any(bad):
        j = int(np.argmax(bad))
        raise InputError(f"model: local sliding friction {mu[j]!r} at v_s = {v[j]:g} m/s; expected a finite "
                         "value >= 0")
    return mu, fr


# =========================================================================================================
# Contact and effect parameters fitted through the friction model
# =========================================================================================================
@doi(PACEJKA_BOOK)
def predict_slip(model, slip, speed, *, temperature=20.0, pressure=0.3e6, contact: Contact, cache: dict | None = None):
    r"""Brush-model friction for rows with their own slip, speed, temperature and pressure (1D arrays, broadcast).

    With patch heating in ``model``: :func:`persson.slip.patch_friction` (one table for all rows);
    without: the brush model with the engine's friction at each row's (v_s, T0, sigma0), one engine call.
    ``cache`` (a dict the caller keeps) reuses the engine's values while only the contact changes.

    Returns
    -------
    ndarray
        mu per row.
    """
    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    s = _slip_array(slip)
    V = _speed_array(speed)
    T = finite_array(temperature, "temperature")
    p = finite_array(pressure, "pressure")
    if np.any(p <= 0):
        raise InputError("pressure: expected mean pressures > 0 Pa")
    s, V, T, p = (a.ravel().astype(float) for a in _broadcast("slip, speed, temperature, pressure", s, V, T, p))
    heating = _heating_of(model)
    if heating is not None:
        from .heating import patch_friction

        return patch_friction(model, heating, contact, s, V, T, p, tables=cache).mu
    from .heating import engine_key

    pts = np.column_stack([s * V, T, p])
    key = pts.tobytes()
    ekey = engine_key(model)
    if cache is not None and cache.get("engine") == ekey and cache.get("key") == key:
        mu_loc = cache["value"]
    else:
        if not hasattr(model, "friction"):
            raise InputError(f"model: expected a persson.Model (or an object with friction(speed, temperature=, "
                             f"pressure=)), got {model!r}")
        uniq, inv = np.unique(pts, axis=0, return_inverse=True)
        r = model.friction(uniq[:, 0], temperature=uniq[:, 1], pressure=uniq[:, 2])
        m = np.atleast_1d(np.asarray(r.mu, dtype=float))
        if not np.all(np.isfinite(m) & (m >= 0)):
            raise InputError("model: non-finite or negative local friction")
        mu_loc = m[np.asarray(inv).ravel()]
        if cache is not None:
            cache.update(engine=ekey, key=key, value=mu_loc, model=model)
    with np.errstate(divide="ignore"):
        theta = np.where(s < 1.0, s / np.where(s < 1.0, 1.0 - s, 1.0), np.inf)
    a = contact.stiffness * contact.length / p * theta
    mu, _, _ = _brush(contact._xi, contact._g, contact._G, a, mu_loc, mu_loc)
    return mu
