"""The geometry of a friction trailer: one entry per measuring tire, from a dict or a case file's ``[rig]`` table.

A rig is ``{"tires": [{...}, ...]}`` (in case.toml: ``[[rig.tires]]`` tables), one entry per tire k = 1, 2, ...
in the order of the raw file's channels, each with

* ``wheel_radius_m`` - rolling radius r of the tire, m (slip, Eq. 1 of the trailer article);
* ``offset_m`` - fore/aft position of the tire's contact behind the first tire's, m (0 for the first tire;
  negative for a tire ahead of it);
* ``l_left_m``, ``l_right_m``, ``l_span_m`` - the lever arms l_L, l_R and l_s of the left and right load cells
  in the force balance (Eqs. 6-9);
* ``mass_kg`` - m, the mass below the load cells whose weight the cells do not see (Eq. 9);

and optionally

* ``l_chain_m`` - l_c, the arm of the chain pull in the moment about the vertical axis (Eq. 7); Eq. 8 takes
  l_c = l_s, which is the default;
* ``slip`` - a fixed slip ratio set by the sprocket tooth ratio, used when the file has no ``omega_k_rad_s``.

Source: Study on the influence of environmental conditions on road friction characteristics, Lubricants 11(7),
277 (2023), Section 2.3 (Eqs. 4-10) and Section 3.2 (tire offsets).
"""

from __future__ import annotations

import difflib
import math
from dataclasses import dataclass
from pathlib import Path

from ..errors import InputError

__all__ = ["TireMount", "Rig", "rig_from_dict", "load_rig", "TIRE_KEYS", "OPTIONAL_TIRE_KEYS"]

#: Keys every ``[[rig.tires]]`` entry must have.
TIRE_KEYS = ("wheel_radius_m", "offset_m", "l_left_m", "l_right_m", "l_span_m", "mass_kg")
#: Keys a ``[[rig.tires]]`` entry may have.
OPTIONAL_TIRE_KEYS = ("l_chain_m", "slip")
_RIG_KEYS = ("tires", "name")


@dataclass(frozen=True)
class TireMount:
    """One measuring tire of the rig (SI units; see the module docstring for the meaning of each field)."""

    wheel_radius_m: float
    offset_m: float
    l_left_m: float
    l_right_m: float
    l_span_m: float
    mass_kg: float
    l_chain_m: float | None = None
    slip: float | None = None

    @property
    def chain_arm_m(self) -> float:
        """l_c of Eq. 7: ``l_chain_m`` when given, else l_s (the assumption behind Eq. 8)."""
        return self.l_span_m if self.l_chain_m is None else self.l_chain_m


@dataclass(frozen=True)
class Rig:
    """A friction trailer: its measuring tires, in the order of the raw file's channels (tire k = index + 1)."""

    tires: tuple[TireMount, ...]
    name: str = ""
    source: str = "rig"

    @property
    def n_tires(self) -> int:
        """Number of measuring tires."""
        return len(self.tires)

    def tire(self, k: int) -> TireMount:
        """Tire ``k`` (1-based, as in the column names)."""
        if not 1 <= k <= self.n_tires:
            raise InputError(f"{self.source}: tire {k} does not exist; the rig has tires 1-{self.n_tires}")
        return self.tires[k - 1]


def rig_from_dict(rig, *, source: str = "rig") -> Rig:
    """Check a rig given as a dict (or the parsed ``[rig]`` table of a case file) and return a :class:`Rig`.

    Parameters
    ----------
    rig : dict or Rig
        ``{"tires": [{"wheel_radius_m": ..., "offset_m": ..., "l_left_m": ..., "l_right_m": ...,
        "l_span_m": ..., "mass_kg": ...}, ...]}``, optionally ``"name"``; a :class:`Rig` is returned unchanged.
    source : str
        Where the rig came from, named in every message (e.g. ``"case.toml: [rig]"``).

    Returns
    -------
    Rig

    Raises
    ------
    InputError
        Not a table, no tires, an unknown key (with "did you mean ..."), a missing key, a value that is not a
        number or is out of range; lengths in mm or cm (a wheel radius above 2 m, a lever arm above 5 m, an
        offset beyond 30 m) and masses that look like a weight in N (above 500 kg) are refused as unit slips.
    """
    if isinstance(rig, Rig):
        return rig
    if not isinstance(rig, dict):
        raise InputError(f"{source}: expected a table {{\"tires\": [...]}} (in case.toml: [[rig.tires]] tables), "
                         f"got {type(rig).__name__}")
    for key in rig:
        if key not in _RIG_KEYS:
            raise InputError(f"{source}: unknown key {key!r}{_suggest(key, _RIG_KEYS)}; keys: "
                             f"{', '.join(_RIG_KEYS)}")
    tires = rig.get("tires")
    if not isinstance(tires, (list, tuple)) or not tires:
        raise InputError(f"{source}: expected 'tires', a list with one table per measuring tire (in case.toml: "
                         f"[[rig.tires]] tables with keys {', '.join(TIRE_KEYS)})")
    name = rig.get("name", "")
    if not isinstance(name, str):
        raise InputError(f"{source}: 'name' must be text, got {name!r}")
    return Rig(tires=tuple(_tire(t, i, source) for i, t in enumerate(tires)), name=name, source=source)


def load_rig(path) -> Rig:
    """The ``[rig]`` table of a case file (``[[rig.tires]]`` entries), checked by :func:`rig_from_dict`.

    Parameters
    ----------
    path : str or path-like
        The case file (TOML).

    Raises
    ------
    InputError
        A missing or unreadable file, invalid TOML, no ``[rig]`` table, or a bad rig (see :func:`rig_from_dict`).
    """
    try:
        import tomllib
    except ModuleNotFoundError:  # Python < 3.11
        import tomli as tomllib

    path = Path(path)
    if not path.is_file():
        raise InputError(f"case file {path} does not exist")
    try:
        parsed = tomllib.loads(path.read_text(encoding="utf-8-sig"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"{path}: not a valid TOML file ({exc})") from None
    if "rig" not in parsed:
        raise InputError(f"{path}: no [rig] table; describe each measuring tire in a [[rig.tires]] table with keys "
                         f"{', '.join(TIRE_KEYS)}")
    return rig_from_dict(parsed["rig"], source=f"{path}: [rig]")


# ==========================================================================================================
#: (key, smallest allowed, largest allowed, whether the smallest is allowed, unit-slip hint above the largest)
_LIMITS = {
    "wheel_radius_m": (0.02, 2.0, False, "looks like mm or cm: give metres (a trailer wheel is 0.2-0.4 m)"),
    "offset_m": (-30.0, 30.0, True, "looks like mm or cm: give metres (a trailer is a few metres long)"),
    "l_left_m": (0.0, 5.0, True, "looks like mm or cm: give metres"),
    "l_right_m": (0.0, 5.0, True, "looks like mm or cm: give metres"),
    "l_span_m": (0.0, 5.0, False, "looks like mm or cm: give metres"),
    "l_chain_m": (0.0, 5.0, False, "looks like mm or cm: give metres"),
    "mass_kg": (0.0, 500.0, True, ("looks like a weight in N or a mass in g: give kg (the hub and wheel below "
                                   "the load cells weigh some 10-50 kg)")),
    "slip": (-0.5, 1.0, True, "is not a slip ratio: give (V - omega r)/V, e.g. 0.1 (not 10 %)"),
}


def _tire(t, i: int, source: str) -> TireMount:
    where = f"{source}: tires[{i}] (tire {i + 1})"
    if not isinstance(t, dict):
        raise InputError(f"{where}: expected a table with keys {', '.join(TIRE_KEYS)}, got {t!r}")
    known = TIRE_KEYS + OPTIONAL_TIRE_KEYS
    for key in t:
        if key not in known:
            raise InputError(f"{where}: unknown key {key!r}{_suggest(key, known)}; keys: {', '.join(TIRE_KEYS)} "
                             f"(optional {', '.join(OPTIONAL_TIRE_KEYS)})")
    missing = [k for k in TIRE_KEYS if k not in t]
    if missing:
        raise InputError(f"{where}: missing key(s) {', '.join(repr(k) for k in missing)}; every tire needs "
                         f"{', '.join(TIRE_KEYS)}")
    values = {k: _value(t[k], k, where) for k in known if k in t}
    return TireMount(**values)


def _value(x, key: str, where: str) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        raise InputError(f"{where}: {key} = {x!r}: expected a number")
    x = float(x)
    lo, hi, lo_ok, hint = _LIMITS[key]
    if not math.isfinite(x):
        raise InputError(f"{where}: {key} = {x}: expected a finite number")
    if x > hi or (key == "offset_m" and x < lo):
        raise InputError(f"{where}: {key} = {x:g} {hint}")
    if x < lo or (x == lo and not lo_ok):
        raise InputError(f"{where}: {key} = {x:g}: expected a value {'>=' if lo_ok else '>'} {lo:g}")
    return x


def _suggest(name, candidates) -> str:
    match = difflib.get_close_matches(str(name).lower(), [c.lower() for c in candidates], n=1, cutoff=0.6)
    if not match:
        return ""
    best = next(c for c in candidates if c.lower() == match[0])
    return f"; did you mean {best!r}?"
