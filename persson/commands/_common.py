"""What every command shares: the output rules, user effect scripts, status lines, condition flags.

Command modules of other packages (``validation.commands``) use these too, so every command behaves alike.
"""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

from .._checks import plausible_pressure, plausible_temperature
from ..errors import InputError
from ..progress import StatusLine

__all__ = ["add_force", "add_effects", "add_quiet", "load_effect_scripts", "status_line", "print_notes",
           "condition_flags", "effect_scripts", "positive_values", "CASE_HELP", "VALUES_HELP"]

CASE_HELP = "case.toml, its folder, or the name of a shipped case such as 'example'"
#: The value syntax of --speeds and --pressures (as ``persson sweep --param``, ranges log-spaced by default).
VALUES_HELP = "v, v1,v2,... or min:max:n (log-spaced; min:max:n:lin for linear)"


def add_force(p) -> None:
    """``--force``: overwrite existing outputs."""
    p.add_argument("--force", action="store_true",
                   help="overwrite existing output files (by default an existing file is never overwritten)")


def add_effects(p) -> None:
    """``--effects SCRIPT.py`` (repeatable): user effects to register before the case is read."""
    p.add_argument("--effects", action="append", default=[], metavar="SCRIPT.py",
                   help="a Python file defining user effects (subclasses of persson.effects.Effect); repeatable")


def add_quiet(p) -> None:
    """``-q/--quiet``: no status lines on stderr."""
    p.add_argument("-q", "--quiet", action="store_true", help="no progress or status lines on stderr")


def load_effect_scripts(paths) -> list[str]:
    """Import user effect scripts (defining an Effect subclass registers it); returns the new effect names."""
    from ..effects import available

    before = set(available())
    for i, path in enumerate(paths):
        p = Path(path)
        if not p.is_file():
            raise InputError(f"--effects: file {p} does not exist")
        spec = importlib.util.spec_from_file_location(f"_persson_user_effects_{i}", p)
        mod = importlib.util.module_from_spec(spec)
        try:
            spec.loader.exec_module(mod)
        except Exception as exc:  # noqa: BLE001
            raise InputError(f"--effects {p}: the script failed: {type(exc).__name__}: {exc}") from None
    return sorted(set(available()) - before)


def effect_scripts(args) -> tuple[Path, ...]:
    """Load ``--effects`` scripts (saying which effects they added); returns them as inputs of the command."""
    paths = tuple(Path(p) for p in getattr(args, "effects", []) or [])
    new = load_effect_scripts(paths)
    if new:
        print(f"user effects registered: {', '.join(new)}", file=sys.stderr)
    return paths


def status_line(args, name: str) -> StatusLine:
    """The command's status line on stderr (silent with ``--quiet``)."""
    return StatusLine(f"persson {name}", enabled=not getattr(args, "quiet", False))


def print_notes(notes, stream=None) -> None:
    """Notes of building a case (cache hits and the like), on stderr."""
    for n in notes:
        print(f"note: {n}", file=stream or sys.stderr)


def positive_values(text: str, flag: str, unit: str):
    """Values > 0 of a flag such as ``--speeds`` or ``--pressures``: ``v``, ``v1,v2,...``, ``min:max:n``
    (log-spaced) or ``min:max:n:lin`` / ``min:max:n:log``; an InputError says what is wrong and what was expected.

    Parameters
    ----------
    text : str
        The flag's value.
    flag : str
        The flag, named in messages.
    unit : str
        The unit of the values (``"m/s"``, ``"Pa"``), named in messages.
    """
    import numpy as np

    from ..sweeps import parse_values

    where = f"{flag} {text!r}"
    t = str(text).strip()
    parts = [p.strip() for p in t.split(":")]
    if ":" in t:
        if len(parts) not in (3, 4) or (len(parts) == 4 and parts[3].lower() not in ("log", "lin", "linear",
                                                                                      "geom")):
            raise InputError(f"{where}: expected {VALUES_HELP}, in {unit}")
        if parts[2].lstrip("+-").isdigit() and int(parts[2]) < 1:
            raise InputError(f"{where}: n = {parts[2]} values; a range min:max:n needs n >= 1")
        if len(parts) == 3:
            t += ":log"
        log = t.lower().endswith((":log", ":geom"))
        try:
            lo, hi = float(parts[0]), float(parts[1])
        except ValueError:
            raise InputError(f"{where}: expected {VALUES_HELP}, in {unit}; {parts[0]!r} or {parts[1]!r} is not a "
                             "number") from None
        if log and (lo <= 0 or hi <= 0):
            raise InputError(f"{where}: expected values > 0 {unit}, got {min(lo, hi):g}; a range min:max:n is "
                             "log-spaced from min to max, so both must be > 0")
    try:
        v = parse_values(t, where)
    except InputError:
        raise InputError(f"{where}: expected {VALUES_HELP}, in {unit}") from None
    if np.any(v <= 0):
        raise InputError(f"{where}: expected values > 0 {unit}, got {float(v[np.argmax(v <= 0)]):g}")
    return v


def condition_flags(args) -> tuple[float | None, float | None]:
    """``--temperature`` / ``--pressure`` checked for unit slips (an error naming the flag)."""
    T = getattr(args, "temperature", None)
    p = getattr(args, "pressure", None)
    if T is not None:
        plausible_temperature(T, "--temperature (deg C)", strict=True)
    if p is not None:
        plausible_pressure(p, "--pressure (Pa)", strict=True)
    return T, p
