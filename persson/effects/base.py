"""The effects API: baseline physics plus a list of effects, each a small frozen dataclass.

An effect has a ``name``, documented ``parameters`` (:class:`Parameter`: default, bounds, unit, doc) stored as
dataclass fields, and overrides one or more hooks:

``transform_conditions(conditions)``
    change the operating conditions (e.g. load carried by a water film).
``transform_surface(surface, conditions)``
    change the PSD (e.g. extrapolate the tail to q1).
``transform_material(material, conditions)``
    change the modulus (e.g. large-strain softening).
``solver_role = "temperature"`` with ``temperature_solver_options(surface=, material=, q=)``
    set the temperature at each scale: the effect returns the settings
    (:class:`~persson.engine.conditions.TemperatureSolverOptions`) and the solver runs the self-consistent
    flash temperature with them.
``friction_term(state)``
    add a friction contribution per speed (e.g. adhesion), given the solved :class:`SolverState`.
``transform_result(result)``
    post-process the finished :class:`~persson.engine.results.FrictionResult`.

A user effect is written in a script with no change to the package::

    from dataclasses import dataclass
    from persson.effects import Effect, Parameter

    @dataclass(frozen=True)
    class Ploughing(Effect):
        name = "ploughing"
        parameters = (Parameter("k", 0.01, (0.0, 0.5), "1", "friction per decade of speed"),)
        k: float = 0.01

        def friction_term(self, state):
            return self.k * np.log10(state.conditions.speed / 1e-3).clip(0)

Defining the class registers it, so :func:`available` and :func:`validation.diagnose` see it; a class defined as
``class Ploughing(Effect, register=False)`` is not registered (a model can use it, but no diagnosis tries it as a
candidate and no case file finds it by name).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ..engine.conditions import Conditions, SolverState, TemperatureSolverOptions
from ..errors import InputError

__all__ = ["Parameter", "Effect", "available", "effect_class", "get"]


_REGISTRY: dict[str, type] = {}


@dataclass(frozen=True)
class Parameter:
    """Specification of one effect parameter.

    Parameters
    ----------
    name : str
        Field name on the effect.
    default : float
        Default value.
    bounds : (float, float)
        Physically sensible range; refits stay inside.
    unit : str
        SI unit (``"1"`` for dimensionless).
    doc : str
        One-line meaning.
    log_scale : bool
        Whether fits should vary the parameter in log space (positive, spans decades).
    plausible : (float, float) or callable, optional
        Physically plausible range, narrower than ``bounds`` where the physics says so (e.g. a frictional shear
        stress of at most 10 MPa). A callable receives the measured ranges of a data set (an object with
        ``speed``, ``shifted_speed``, ``temperature`` and ``pressure``, each a ``(min, max)`` pair; the shifted
        speed is the sliding speed times a_T(T), i.e. referred to the material's reference temperature) and
        returns ``(lo, hi)``. None (default): ``bounds``. A fitted value outside it is flagged as implausible.
    physical_limits : tuple of float
        The bounds that are physical limits (e.g. 0 for "none of it", 1 for "a factor of one"): a fit that ends
        there has found a legitimate optimum. Any other bound is only the edge of the range searched.
    sentinel : float, optional
        A placeholder value with a special meaning (e.g. 0 for "computed automatically"); it is never varied by
        a fit and never reported as a fitted value.
    sentinel_doc : str
        What the placeholder means, e.g. ``"pi / q_m"``.
    fittable : bool
        Whether a fit may vary the parameter (default True).
    """

    name: str
    default: float
    bounds: tuple[float, float]
    unit: str
    doc: str
    log_scale: bool = False
    plausible: Any = None
    physical_limits: tuple = ()
    sentinel: float | None = None
    sentinel_doc: str = ""
    fittable: bool = True

    def plausible_range(self, data_range=None) -> tuple[float, float]:
        """The plausible ``(lo, hi)``: ``plausible`` (evaluated on ``data_range`` when callable), else ``bounds``.

        A callable ``plausible`` without a ``data_range`` gives the bounds.
        """
        p = self.plausible
        if p is None or (callable(p) and data_range is None):
            return float(self.bounds[0]), float(self.bounds[1])
        lo, hi = p(data_range) if callable(p) else p
        return float(lo), float(hi)

    def is_physical_limit(self, value: float) -> bool:
        """Whether ``value`` is one of the ``physical_limits`` (to 1e-9 relative)."""
        return any(abs(float(value) - float(b)) <= 1e-9 * max(1.0, abs(float(b))) for b in self.physical_limits)


@dataclass(frozen=True)
class Effect:
    """Base class of effects. Subclasses are frozen dataclasses with a class attribute ``name``."""

    name: ClassVar[str] = ""
    parameters: ClassVar[tuple[Parameter, ...]] = ()
    #: ``"temperature"`` for an effect that takes part in the solver by setting the temperature at each scale.
    solver_role: ClassVar[str | None] = None
    #: Key under which ``friction_term`` is reported; ``"adhesion"`` feeds ``FrictionResult.mu_adhesion``.
    term_kind: ClassVar[str | None] = None

    def __init_subclass__(cls, register: bool = True, **kwargs):
        # ``class E(Effect, register=False)``: an effect kept out of the registry (not a candidate of a diagnosis,
        # not found by name), e.g. physics a study hides from the diagnosis it tests
        super().__init_subclass__(**kwargs)
        name = cls.__dict__.get("name")
        if name and register:
            taken = _REGISTRY.get(name)
            if taken is not None and _is_builtin(taken) and not _same_class(taken, cls):
                raise InputError(f"effect {cls.__qualname__}: the name {name!r} is taken by the built-in effect "
                                 f"{taken.__module__}.{taken.__qualname__}; give your effect another name (e.g. "
                                 f"name = \"my_{name}\"), or subclass {taken.__qualname__} to change it")
            _REGISTRY[name] = cls

    def __post_init__(self):
        for p in self.parameters:
            v = getattr(self, p.name)
            if isinstance(v, np.ndarray) and v.ndim == 0:
                v = v[()]
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
                raise InputError(f"{self.name}.{p.name}: expected a number in {p.unit} (e.g. {p.default:g}), got "
                                 f"{v!r} ({type(v).__name__})")
            if not math.isfinite(v):
                raise InputError(f"{self.name}.{p.name}: expected a finite number, got {v!r}")
            lo, hi = p.bounds
            if not lo <= v <= hi:
                raise InputError(f"{self.name}.{p.name}: expected a value in [{lo:g}, {hi:g}] {p.unit}, got {v:g}")

    # --- hooks (identity by default) -------------------------------------------------------------------
    def transform_conditions(self, conditions: Conditions) -> Conditions:
        """Return changed operating conditions."""
        return conditions

    def transform_surface(self, surface, conditions: Conditions):
        """Return a changed surface PSD."""
        return surface

    def transform_material(self, material, conditions: Conditions):
        """Return a changed material."""
        return material

    def friction_term(self, state: SolverState):
        """Return an additional friction coefficient per speed (shape (n_speed,)) or None."""
        return None

    def temperature_solver_options(self, *, surface, material, q) -> TemperatureSolverOptions | None:
        """Settings of the self-consistent temperature at each scale, for an effect with
        ``solver_role = "temperature"`` (None, the default, for any other effect).

        Parameters
        ----------
        surface : PSD object
            The surface after the transform hooks (``C(q)``, ``q_range``, and a roll-off where it declares one).
        material : material object
            The material after the transform hooks (``thermal`` for the thermal properties).
        q : ndarray (n_q,)
            The wavevector nodes of the solve, rad/m.

        Returns
        -------
        TemperatureSolverOptions or None
        """
        return None

    def modulus_factors(self, slope, temperature):
        r"""Factors (f, g) on E' and E'' at each length scale, or None (the default: no per-scale modulus).

        ``slope`` is the rms slope of the surface up to each scale, :math:`\xi(q)` (so the local strain of a
        scale can be estimated from it) and ``temperature`` the temperature there (deg C); both are arrays that
        broadcast together, and f, g must have their broadcast shape. The solver tabulates them once per call
        and multiplies E' by f and E'' by g inside G(q), the friction integral and the flash temperature.
        """
        return None

    def transform_result(self, result):
        """Return a post-processed result."""
        return result

    # --- parameters --------------------------------------------------------------------------------------
    def parameter_values(self) -> dict[str, float]:
        """Current values of the documented parameters."""
        return {p.name: getattr(self, p.name) for p in self.parameters}

    def with_parameters(self, **values) -> "Effect":
        """Copy with some parameters changed (validated against their bounds)."""
        names = {f.name for f in dataclasses.fields(self)}
        unknown = sorted(set(values) - names)
        if unknown:
            raise InputError(f"{self.name}: unknown parameter(s) {unknown}; known: {sorted(names)}")
        return dataclasses.replace(self, **values)

    @property
    def citations(self) -> tuple[str, ...]:
        """References of the physics this effect implements."""
        return tuple(getattr(type(self), "__citations__", ()))


def available() -> dict[str, type]:
    """Registered effect classes by name (built-in and user-defined), sorted by name.

    The built-in effects register when :mod:`persson.effects` is imported, which any import of this module does
    first (it is the package's parent), so the registry never imports what registers in it."""
    return dict(sorted(_REGISTRY.items()))


def effect_class(name: str) -> type:
    """The effect class registered under ``name``."""
    reg = available()
    if name not in reg:
        raise InputError(f"effect: unknown effect {name!r}; available: {sorted(reg)}")
    return reg[name]


def get(name: str, **parameters) -> Effect:
    """An instance of the effect ``name`` with the given parameters (others at their defaults).

    Raises
    ------
    InputError
        An unknown effect, or a parameter the effect does not have (with the closest name).
    """
    cls = effect_class(name)
    known = [f.name for f in dataclasses.fields(cls) if f.init and not f.name.startswith("_")]
    for key in parameters:
        if key not in known:
            import difflib

            close = difflib.get_close_matches(key, known, n=1, cutoff=0.6)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise InputError(f"{name}: unknown parameter {key!r}{hint}; known: {', '.join(known) or 'none'}")
    return cls(**parameters)


def _is_builtin(cls) -> bool:
    return cls.__module__.startswith("persson.")


def _same_class(a, b) -> bool:
    # a module imported again (a reloaded package, a script run twice) defines the same class anew
    return (a.__module__, a.__qualname__) == (b.__module__, b.__qualname__)
