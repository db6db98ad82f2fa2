"""Parameter names and value ranges of sweeps: parse ``name=lo:hi:n`` and set a parameter on a model.

Parameter names
---------------
``speed``, ``temperature``, ``pressure``
    Operating conditions (m/s, deg C, Pa); columns ``speed_m_s``, ``temperature_C``, ``pressure_Pa``.
``nu``, ``gamma``, ``grid.<field>``
    Model fields (``grid.q_per_decade`` etc. take integers); the numerical settings the engine uses (not
    ``grid.n_phi``, kept for old scripts but unused).
``surface.<name>``
    The surface, rebuilt. :class:`surfaces.SelfAffine`: ``hurst`` (at constant rms height), ``hrms``
    (at constant H and cut-offs), ``q0``, ``q1``, ``qL`` (at constant C0: the same power law over another
    support) and ``C0``. A tabulated :class:`surfaces.PSD`: ``q0``, ``q1`` (restriction of the table, see
    ``with_cutoff``) and ``hrms`` (C scaled by a constant). Other surfaces: ``q0``/``q1`` through
    ``with_cutoff`` and any numeric dataclass field. ``hrms`` is applied after the other surface parameters of
    the same point, so the requested rms height holds over the final support.
``material.<name>[.<name>...]``
    A numeric field of the material, nested through dataclasses: ``material.E_loss``, ``material.wlf.C1``,
    ``material.thermal.conductivity``. Statistics of a fit (``quality``, ``causality``, ``scores``) describe the
    material, they do not enter its modulus: they are not sweepable.

Only these physical parameters (and the engine's numerical settings) are sweepable: any other name is an error that
suggests the closest sweepable one.
``<effect>.<parameter>`` (or ``effects.<effect>.<parameter>``)
    A parameter of an effect switched on in the model, e.g. ``adhesion.tau_f0``.
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np

from .._checks import finite_array, number
from ..errors import InputError

__all__ = ["CONDITIONS", "parse_param", "parse_values", "set_parameter", "apply_parameters", "sweepable"]

#: Condition parameters and the table columns that hold them.
CONDITIONS = {"speed": "speed_m_s", "temperature": "temperature_C", "pressure": "pressure_Pa"}
_ALIASES = {v: k for k, v in CONDITIONS.items()}
_NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"


def canonical(name: str) -> str:
    """Canonical form of a parameter name (``pressure_Pa`` -> ``pressure``, ``effects.x.y`` -> ``x.y``)."""
    if not isinstance(name, str) or not name.strip():
        raise InputError(f"params: expected a parameter name, got {name!r}")
    name = name.strip()
    name = _ALIASES.get(name, name)
    if name.startswith("effects."):
        name = name[len("effects."):]
    if name.startswith("model.") and name.count(".") == 1:
        name = name[len("model."):]
    return name


def parse_param(spec: str, argument: str = "--param") -> tuple[str, np.ndarray]:
    """Parse ``NAME=VALUES`` (see :func:`parse_values`) into ``(name, values)``.

    Raises
    ------
    InputError
        Naming ``argument`` and the spec when it is malformed.
    """
    if not isinstance(spec, str) or "=" not in spec:
        raise InputError(f"{argument} {spec!r}: expected NAME=VALUES, e.g. pressure=0.1e6:0.9e6:5")
    name, _, text = spec.partition("=")
    name = name.strip()
    if not name:
        raise InputError(f"{argument} {spec!r}: missing parameter name before '='")
    return canonical(name), parse_values(text, f"{argument} {spec!r}")


def parse_values(values, argument: str = "values") -> np.ndarray:
    """Values of a sweep parameter from text or a sequence.

    Text forms: ``lo:hi:n`` (``n`` values, linear), ``lo:hi:n:log`` (log-spaced, lo and hi > 0),
    ``v1,v2,...`` (a list), ``v`` (one value). Sequences are taken as they are.

    Returns
    -------
    ndarray
        1D, finite, at least one value.

    Raises
    ------
    InputError
        Naming ``argument``: a malformed range (not numbers, n < 1, log with a value <= 0), an empty list,
        NaN or infinite values.
    """
    if isinstance(values, str):
        text = values.strip()
        if ":" in text:
            parts = [p.strip() for p in text.split(":")]
            log = False
            if len(parts) == 4 and parts[3].lower() in ("log", "geom"):
                log = True
                parts = parts[:3]
            elif len(parts) == 4 and parts[3].lower() in ("lin", "linear"):
                parts = parts[:3]
            if len(parts) != 3 or not all(re.fullmatch(_NUMBER, p) for p in parts[:2]) \
                    or not re.fullmatch(r"\d+", parts[2]):
                raise InputError(f"{argument}: malformed range {text!r}; expected lo:hi:n or lo:hi:n:log "
                                 "(numbers lo, hi and a whole number n >= 1)")
            lo, hi, n = float(parts[0]), float(parts[1]), int(parts[2])
            if n < 1:
                raise InputError(f"{argument}: malformed range {text!r}: n must be >= 1")
            if n == 1 and lo != hi:
                raise InputError(f"{argument}: malformed range {text!r}: n = 1 needs lo == hi")
            if log:
                if lo <= 0 or hi <= 0:
                    raise InputError(f"{argument}: malformed range {text!r}: a log range needs lo, hi > 0")
                out = np.geomspace(lo, hi, n)
            else:
                out = np.linspace(lo, hi, n)
        else:
            items = [p.strip() for p in text.split(",")]
            if not text or not all(re.fullmatch(_NUMBER, p) for p in items):
                raise InputError(f"{argument}: malformed values {text!r}; expected lo:hi:n, lo:hi:n:log or "
                                 "v1,v2,...")
            out = np.array([float(p) for p in items])
    else:
        out = values
    return finite_array(out, argument).ravel()


def apply_parameters(model, values: dict):
    """``model`` with the non-condition parameters ``values`` (name -> number) set, ``hrms`` last."""
    items = [(canonical(k), v) for k, v in values.items()]
    items = [kv for kv in items if kv[0] not in CONDITIONS]
    items.sort(key=lambda kv: kv[0] == "surface.hrms")  # stable: hrms after the other surface parameters
    for name, value in items:
        model = set_parameter(model, name, value)
    return model


def set_parameter(model, name: str, value):
    """A copy of ``model`` with the parameter ``name`` (see the module docstring) set to ``value``.

    Raises
    ------
    InputError
        Unknown parameter name (the message lists the sweepable names of this model), or a value the
        component rejects.
    """
    name = canonical(name)
    value = number(value, f"params: {name!r}")
    if name in CONDITIONS:
        raise InputError(f"params: {name!r} is an operating condition, not a model parameter")
    head, _, rest = name.partition(".")
    if head in ("grid", "material") and name not in sweepable(model):
        raise _unknown(model, name)
    if name in ("nu", "gamma"):
        return model.replace(**{name: value})
    if head == "grid" and rest:
        grid = model.grid
        if not any(f.name == rest for f in dataclasses.fields(grid)):
            raise _unknown(model, name)
        return model.replace(grid=_replace(grid, rest, value, name))
    if head == "surface" and rest:
        return model.replace(surface=_set_surface(model, model.surface, rest, value, name))
    if head == "material" and rest:
        return model.replace(material=_replace_path(model, model.material, rest.split("."), value, name))
    if rest and head in model.effect_names and "." not in rest:
        e = model.effect(head)
        fields = {f.name for f in dataclasses.fields(e)}
        if rest not in fields:
            import difflib

            known = [p.name for p in e.parameters] or sorted(fields)
            close = difflib.get_close_matches(rest, known, n=1, cutoff=0.6)
            hint = f"; did you mean '{head}.{close[0]}'?" if close else ""
            raise InputError(f"params: unknown parameter {name!r}{hint}: effect {head!r} has parameters {known}")
        current = getattr(e, rest)
        new = e.with_parameters(**{rest: _like(current, value, name)})
        return model.replace(effects=tuple(new if x.name == head else x for x in model.effects))
    raise _unknown(model, name)


def sweepable(model) -> list[str]:
    """Names of the parameters of ``model`` a sweep can vary (for messages and ``--help``)."""
    out = list(CONDITIONS) + ["nu", "gamma"]
    out += [f"grid.{f.name}" for f in dataclasses.fields(model.grid)
            if f.name not in _UNUSED_GRID and _is_number(getattr(model.grid, f.name))]
    out += [f"surface.{n}" for n in _surface_names(model.surface)]
    out += [f"material.{n}" for n in _numeric_paths(model.material)]
    for e in model.effects:
        if e.name == "length_scale_band":
            continue
        names = [p.name for p in e.parameters] or [f.name for f in dataclasses.fields(e)
                                                    if _is_number(getattr(e, f.name))]
        out += [f"{e.name}.{n}" for n in names]
    return out


# ---------------------------------------------------------------------------------------------------------
def _unknown(model, name: str) -> InputError:
    import difflib

    known = sweepable(model)
    close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
    hint = f"; did you mean {close[0]!r}?" if close else ""
    why = ""
    if name.split(".")[0] == "grid" and name.split(".")[-1] in _UNUSED_GRID:
        why = " (the engine does not use it: sweeping it changes nothing)"
    elif set(name.split(".")) & _NOT_PHYSICAL:
        why = " (a statistic of the material's fit, not a property that enters the modulus)"
    return InputError(f"params: unknown parameter name {name!r}{why}{hint}; this model can sweep "
                      f"{', '.join(known)}")


#: GridSettings fields the engine no longer reads.
_UNUSED_GRID = ("n_phi",)
#: Dataclass fields that describe how a material was fitted (statistics), not what it is.
_NOT_PHYSICAL = {"quality", "causality", "scores", "misfit", "misfit_loo"}


def _is_number(v) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool)


def _like(current, value: float, name: str):
    """``value`` as an int when the current value is an int."""
    if isinstance(current, (int, np.integer)) and not isinstance(current, bool):
        if value != int(value):
            raise InputError(f"params: {name!r} takes whole numbers, got {value!r}")
        return int(value)
    return value


def _replace(obj, field_name: str, value, name: str):
    current = getattr(obj, field_name)
    if not _is_number(current):
        raise InputError(f"params: {name!r} is not a numeric parameter (it holds {type(current).__name__})")
    try:
        return dataclasses.replace(obj, **{field_name: _like(current, value, name)})
    except (TypeError, ValueError) as exc:
        raise InputError(f"params: {name!r} cannot be set on {type(obj).__name__}: {exc}") from None


def _replace_path(model, obj, path: list[str], value, name: str):
    head = path[0]
    if not dataclasses.is_dataclass(obj) or not any(f.name == head for f in dataclasses.fields(obj)):
        raise _unknown(model, name)
    if len(path) == 1:
        return _replace(obj, head, value, name)
    inner = _replace_path(model, getattr(obj, head), path[1:], value, name)
    try:
        return dataclasses.replace(obj, **{head: inner})
    except (TypeError, ValueError) as exc:
        raise InputError(f"params: {name!r} = {value:g}: {exc}") from None


def _numeric_paths(obj, prefix: str = "", depth: int = 0) -> list[str]:
    if not dataclasses.is_dataclass(obj) or depth > 3:
        return []
    out = []
    for f in dataclasses.fields(obj):
        if f.name in _NOT_PHYSICAL:
            continue
        v = getattr(obj, f.name, None)
        if _is_number(v):
            out.append(prefix + f.name)
        elif dataclasses.is_dataclass(v):
            out += _numeric_paths(v, prefix + f.name + ".", depth + 1)
    return out


def _surface_names(surface) -> list[str]:
    import surfaces

    if isinstance(surface, surfaces.SelfAffine):
        return ["hurst", "hrms", "q0", "q1", "qL", "C0"]
    if isinstance(surface, surfaces.PSD):
        return ["q0", "q1", "hrms"]
    out = ["q0", "q1"] if hasattr(surface, "with_cutoff") else []
    return out + [n for n in _numeric_paths(surface) if n not in out]


def _set_surface(model, s, attr: str, value: float, name: str):
    import surfaces

    try:
        if isinstance(s, surfaces.SelfAffine):
            H, q0, q1, qL, C0 = s.hurst, s.q0, s.q1, s.qL, s.C0
            if attr == "hrms":
                return surfaces.SelfAffine(H, q0, q1, hrms=value, qL=qL)
            if attr == "hurst":
                return surfaces.SelfAffine(value, q0, q1, hrms=s.hrms(), qL=qL)
            if attr in ("q0", "q1", "qL", "C0"):
                kw = dict(hurst=H, q0=q0, q1=q1, C0=C0, qL=qL)
                kw[attr] = value
                return surfaces.SelfAffine(**kw)
            raise _unknown(model, name)
        if isinstance(s, surfaces.PSD):
            if attr in ("q0", "q1"):
                return s.with_cutoff(**{attr: value})
            if attr == "hrms":
                if value <= 0:
                    raise InputError(f"hrms: expected a positive number, got {value:g}")
                k = (value / s.hrms()) ** 2
                return surfaces.PSD(s.q, s.C_values * k, q_r=s.q_r, extrapolated=s.extrapolated, source=s.source,
                                    qL=s.qL, q_rolloff=s.q_rolloff, hurst=s.hurst)
            raise _unknown(model, name)
        if attr in ("q0", "q1") and hasattr(s, "with_cutoff"):
            return s.with_cutoff(**{attr: value})
        return _replace_path(model, s, attr.split("."), value, name)
    except ValueError as exc:  # the InputErrors of surfaces, materials and persson all subclass ValueError
        if isinstance(exc, InputError) and str(exc).startswith("params:"):
            raise
        raise InputError(f"params: {name!r} = {value:g}: {exc}") from None
