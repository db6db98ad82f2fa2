"""The schema of ``case.toml``: every section and key, its type and its meaning, declared once.

:func:`check_case` validates a parsed file against it: an unknown section or key is an error with a
"did you mean ..." suggestion, every value is type-checked with its key named, and effect tables
``[model.<effect>]`` are checked against the effect's fields. :func:`markdown` renders the same declarations as
the reference in ``docs/conventions.md`` (``python -m persson.case.schema docs/conventions.md`` rewrites that
section; a test fails when the two drift apart).

To add a key, add one :class:`Key` to :data:`KEYS` (and run the command above).
"""

from __future__ import annotations

import dataclasses
import difflib
import importlib
import inspect
import math
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from ..errors import InputError

__all__ = ["Key", "KEYS", "SECTIONS", "check_case", "markdown", "write_docs", "suggest"]


# ---------------------------------------------------------------------------------------------------------
# Value kinds: a name for the docs and a check that returns the (normalised) value or raises naming the key.
@dataclass(frozen=True)
class Kind:
    """A value type of the schema: ``text`` names it in the docs, ``check(value, where)`` validates it."""

    text: str
    check: Callable[[Any, str], Any]
    subkeys: Callable[[], dict] | None = None  # for tables with known keys: name -> doc


def _expected(where: str, what: str, value) -> InputError:
    return InputError(f"{where}: expected {what}, got {_show(value)}")


def _show(value) -> str:
    if isinstance(value, dict):
        return "a table {" + ", ".join(f"{k} = {_show(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(_show(v) for v in value) + "]"
    return repr(value)


def _number(value, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _expected(where, "a number", value)
    x = float(value)
    if not math.isfinite(x):
        raise _expected(where, "a finite number", value)
    return x


def _positive(value, where: str) -> float:
    x = _number(value, where)
    if x <= 0:
        raise _expected(where, "a number > 0", value)
    return x


def _integer(value, where: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise _expected(where, "an integer", value)
    return int(value)


def _boolean(value, where: str) -> bool:
    if not isinstance(value, bool):
        raise _expected(where, "true or false", value)
    return value


def _text(value, where: str) -> str:
    if not isinstance(value, str):
        raise _expected(where, "text in quotes", value)
    return value


def _file(value, where: str) -> str:
    if not isinstance(value, str) or not value.strip():
        raise _expected(where, "a file name in quotes (relative to the case file's folder)", value)
    return value


def _files(value, where: str) -> list[str]:
    items = value if isinstance(value, list) else [value]
    if not items:
        raise _expected(where, "a file name or a non-empty list of file names", value)
    for i, v in enumerate(items):
        if not isinstance(v, str) or not v.strip():
            raise _expected(where if len(items) == 1 else f"{where}[{i}]",
                            "a file name in quotes (or a list of them)", v)
    return list(items)


def _text_list(value, where: str) -> list[str]:
    items = value if isinstance(value, list) else None
    if items is None or not all(isinstance(v, str) for v in items):
        raise _expected(where, 'a list of names in quotes, e.g. ["adhesion"]', value)
    return list(items)


def _text_or_list(value, where: str) -> list[str]:
    return _text_list([value] if isinstance(value, str) else value, where)


def _choice(*choices: str) -> Kind:
    def check(value, where):
        if value not in choices:
            hint = suggest(value, choices) if isinstance(value, str) else ""
            raise InputError(f"{where}: expected one of {', '.join(repr(c) for c in choices)}, got "
                             f"{_show(value)}{hint}")
        return value

    return Kind(" | ".join(f'"{c}"' for c in choices), check)


def _number_or_auto(value, where: str):
    if value == "auto":
        return "auto"
    if isinstance(value, str):
        raise _expected(where, 'a number or "auto"', value)
    try:
        return _number(value, where)
    except InputError:
        raise _expected(where, 'a number or "auto"', value) from None


def _pair(value, where: str) -> list[float]:
    if not isinstance(value, list) or len(value) != 2:
        raise _expected(where, "[low, high] (two numbers)", value)
    lo, hi = (_number(v, f"{where}[{i}]") for i, v in enumerate(value))
    if not hi > lo:
        raise _expected(where, "[low, high] with high > low", value)
    return [lo, hi]


def _speeds(value, where: str) -> list[float]:
    items = value if isinstance(value, list) else [value]
    if not items:
        raise _expected(where, "a speed or a list of speeds > 0, m/s", value)
    return [_positive(v, f"{where}[{i}]" if isinstance(value, list) else where) for i, v in enumerate(items)]


def _speed_range(value, where: str) -> list:
    if not isinstance(value, list) or len(value) != 3:
        raise _expected(where, "[min, max, n] (log-spaced speeds, m/s)", value)
    lo, hi = _positive(value[0], f"{where}[0]"), _positive(value[1], f"{where}[1]")
    n = _integer(value[2], f"{where}[2]")
    if n < 1 or not hi >= lo:
        raise _expected(where, "[min, max, n] with max >= min > 0 and n >= 1", value)
    return [lo, hi, n]


def _pressure_distribution(value, where: str):
    if isinstance(value, dict):
        _check_keys(value, {"sakai_n": None}, where)
        if "sakai_n" not in value:
            raise _expected(where, '"uniform", "parabolic" or { sakai_n = n }', value)
        return {"sakai_n": _positive(value["sakai_n"], f"{where} sakai_n")}
    if value not in ("uniform", "parabolic"):
        hint = suggest(value, ("uniform", "parabolic")) if isinstance(value, str) else ""
        raise InputError(f"{where}: expected \"uniform\", \"parabolic\" or {{ sakai_n = n }}, got "
                         f"{_show(value)}{hint}")
    return value


def _length(value, where: str) -> float:
    x = _positive(value, where)
    if x > 1.0:
        raise InputError(f"{where}: {x:g} m is longer than any contact patch of a wheel or tire (0.01-0.3 m); "
                         f"expected metres ({x:g} mm = {x * 1e-3:g} m)")
    return x


def _range(lo: float, hi: float) -> Kind:
    def check(value, where):
        x = _number(value, where)
        if not lo <= x <= hi:
            raise _expected(where, f"a number in [{lo:g}, {hi:g}]", value)
        return x

    return Kind(f"number in [{lo:g}, {hi:g}]", check)


def _fields_of(target: str, exclude=()) -> Kind:
    """A table whose keys are the fields of the dataclass ``target`` ("module:Class"), type-checked."""

    def fields():
        cls = _resolve(target)
        if cls is None:
            return None
        return {f.name: f for f in dataclasses.fields(cls) if f.init and not f.name.startswith("_")
                and f.name not in exclude}

    def check(value, where):
        if not isinstance(value, dict):
            raise _expected(where, "a table { key = value, ... }", value)
        known = fields()
        if known is None:
            return dict(value)
        _check_keys(value, known, where)
        return {k: _field_value(known[k], v, f"{where} {k}") for k, v in value.items()}

    def subkeys():
        known = fields() or {}
        return {k: _field_type_text(f) for k, f in known.items()}

    return Kind("table", check, subkeys)


def _options_of(*targets: str, extra=(), exclude=()) -> Kind:
    """A table of keyword options passed to the callables ``targets`` ("module:function"): keys are checked
    against their parameters (when a target takes ``**kwargs``, or cannot be imported, any key passes)."""

    def names():
        out: set[str] = set(extra)
        for t in targets:
            fn = _resolve(t)
            if fn is None:
                return None
            try:
                params = list(inspect.signature(fn).parameters.values())
            except (TypeError, ValueError):  # pragma: no cover - builtins without signatures
                return None
            if any(p.kind is p.VAR_KEYWORD for p in params):
                return None
            # the first positional parameter (self, the path, the data) is given by the case itself
            positional = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
            skip = {positional[0].name} if positional else set()
            if t.endswith("shift_isotherms"):
                skip |= {"T_ref"}
            out |= {p.name for p in params if p.name not in skip and p.kind is not p.VAR_POSITIONAL}
        return out - set(exclude)

    def check(value, where):
        if not isinstance(value, dict):
            raise _expected(where, "a table { option = value, ... }", value)
        allowed = names()
        if allowed is not None:
            _check_keys(value, dict.fromkeys(sorted(allowed)), where)
        return dict(value)

    def subkeys():
        allowed = names()
        return None if allowed is None else dict.fromkeys(sorted(allowed), "")

    return Kind("table of options", check, subkeys)


def _wlf(value, where: str) -> dict:
    if not isinstance(value, dict):
        raise _expected(where, "a table { C1 = ..., C2 = ..., T_ref_C = ... }", value)
    _check_keys(value, {"C1": None, "C2": None, "T_ref_C": None}, where)
    missing = [k for k in ("C1", "C2", "T_ref_C") if k not in value]
    if missing:
        raise InputError(f"{where}: missing {', '.join(missing)} (expected {{ C1 = ..., C2 = ..., T_ref_C = ... }})")
    return {k: _number(value[k], f"{where} {k}") for k in ("C1", "C2", "T_ref_C")}


def _degrees(value, where: str) -> float:
    """An angle in degrees; one that looks like radians (within 2 pi, with a fraction) is refused."""
    from ..engine.directional import directions

    return float(directions(_number(value, where), where, strict=True))


def _stretch(value, where: str) -> dict:
    if not isinstance(value, dict):
        raise _expected(where, "a table { ratio = ..., angle_deg = ... }", value)
    _check_keys(value, {"ratio": None, "angle_deg": None}, where)
    if "ratio" not in value:
        raise InputError(f"{where}: missing ratio (expected {{ ratio = 3.0, angle_deg = 0.0 }}, ratio >= 1)")
    ratio = _number(value["ratio"], f"{where} ratio")
    if ratio < 1.0:
        raise _expected(f"{where} ratio", "a stretch factor >= 1 (ridges along angle_deg; for a ratio r < 1 give "
                        "1/r and angle_deg + 90)", value["ratio"])
    return {"ratio": ratio, "angle_deg": _degrees(value.get("angle_deg", 0.0), f"{where} angle_deg")}


NUMBER = Kind("number", _number)
POSITIVE = Kind("number > 0", _positive)
LENGTH = Kind("number in (0, 1]", _length)
TEXT = Kind("text", _text)
FILE = Kind("file", _file)
FILES = Kind("file or list of files", _files)
NAMES = Kind("list of names", _text_list)
NAME_OR_NAMES = Kind("name or list of names", _text_or_list)
NUMBER_OR_AUTO = Kind('number or "auto"', _number_or_auto)
PAIR = Kind("[low, high]", _pair)
SPEEDS = Kind("number or list of numbers > 0", _speeds)
SPEED_RANGE = Kind("[min, max, n]", _speed_range)
PRESSURE_DISTRIBUTION = Kind('"uniform" | "parabolic" | { sakai_n = n }', _pressure_distribution)
INTEGER = Kind("integer", _integer)
BOOLEAN = Kind("true | false", _boolean)
WLF_TABLE = Kind("{ C1, C2, T_ref_C }", _wlf, lambda: {"C1": "", "C2": "K", "T_ref_C": "deg C"})
DEGREES = Kind("number (degrees)", _degrees)
STRETCH = Kind("{ ratio, angle_deg }", _stretch, lambda: {"ratio": ">= 1", "angle_deg": "deg"})


# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Key:
    """One key of the case file.

    Parameters
    ----------
    section : str
        ``""`` for the top level, else the table name (``"material"``, ``"model"``...).
    name : str
    kind : Kind
    doc : str
        Meaning, with units and what it is passed to (one or two sentences).
    default : str
        The default as documentation text (``""``: no default / not used when absent).
    """

    section: str
    name: str
    kind: Kind
    doc: str
    default: str = ""


#: Sections (tables) of a case file and what they hold; ``[model.<effect>]`` tables are checked separately.
SECTIONS: dict[str, str] = {
    "": "Keys outside any table.",
    "surface": "The road or sandpaper: exactly one of `psd`, `profiles`, `example`.",
    "material": "The tread compound: exactly one of `master_curve`, `dma`, `example`.",
    "contact": "Brush model of the test wheel, needed for measurements with slip < 1.",
    "model": "Physics switched on, and parameters fitted by the validation loop. Each effect switched on may "
             "have its own table `[model.<effect>]` with its parameters (listed below).",
    "conditions": "Operating conditions used by `persson friction` and `persson sweep`.",
    "measurements": "Measured friction, used by `persson compare`, `diagnose`, `report`.",
    "tire": "The tyre on the road, used by `persson tread` (the tread-element tool, `persson.tread`): the tyre, "
            "its pattern, the water and the map's slips and speeds. The road is `[surface] profiles` (or synthetic "
            "profiles of `psd` / `example`); the temperature is `[conditions] temperature_C`.",
    "rig": "The friction trailer whose raw channels `validation.rigs` reduces: one `[[rig.tires]]` table per "
           "measuring tire, in the order of the channel file's tires (docs/rigs.md).",
}

_READ_OPTIONS = _options_of("surfaces:read_profiles_csv", "surfaces:read_captif", extra=("format",))

# --- [tire]: the tread-element tool (persson.tread); its tables are checked here, built by persson.tread.case
def _subtable(what: str, required: tuple, **keys: Kind) -> Kind:
    """A table with known keys (``name=kind``), ``required`` among them."""

    def check(value, where):
        if not isinstance(value, dict):
            raise _expected(where, f"a table {{ {', '.join(f'{k} = ...' for k in required)} }}", value)
        _check_keys(value, keys, where)
        missing = [k for k in required if k not in value]
        if missing:
            raise InputError(f"{where}: missing {', '.join(missing)} ({what})")
        return {k: keys[k].check(v, f"{where} {k}") for k, v in value.items()}

    return Kind("{ " + ", ".join(keys) + " }", check, lambda: {k: kd.text for k, kd in keys.items()})


def _slips(value, where: str) -> list[float]:
    items = value if isinstance(value, list) else [value]
    out = [_number(v, f"{where}[{i}]" if isinstance(value, list) else where) for i, v in enumerate(items)]
    if not out or any(not 0.0 < x <= 1.0 for x in out):
        raise _expected(where, "slip ratios in (0, 1] (1 = locked wheel)", value)
    return out


_TIRE_KEYS = (
    Key("tire", "diameter_m", POSITIVE, "Free outer diameter of the tyre, m."),
    Key("tire", "width_m", POSITIVE, "Section width, m."),
    Key("tire", "load_N", POSITIVE, "Normal load on the wheel, N."),
    Key("tire", "inflation_pressure_Pa", POSITIVE, "Inflation (gauge) pressure, Pa (2.2 bar = 2.2e5)."),
    Key("tire", "tread_depth_m", POSITIVE, "Rubber thickness of the tread, m."),
    Key("tire", "slip_stiffness", POSITIVE, "Longitudinal slip stiffness per unit load (initial slope of "
        "mu(slip)); sets the elements' shear stiffness.", "20"),
    Key("tire", "rigid_elements", BOOLEAN, "true: elements rigid in shear, every contacting element slides "
        "(the paper's equations as written; `slip_stiffness` unused).", "false"),
    Key("tire", "pressure_distribution", PRESSURE_DISTRIBUTION, "Pressure along the footprint.", '"parabolic"'),
    Key("tire", "vertical_stiffness_N_per_m", POSITIVE, "Vertical stiffness at 2.2 bar, N/m.",
        "the reference tyre's, scaled with sqrt(width x diameter)"),
    Key("tire", "grooves", Kind("table", lambda v, w: _GROOVES.check(v, w), lambda: _GROOVES.subkeys()),
        "Straight grooves: `{ width_m, pitch_m, depth_m, angle_deg }` (angle from the lateral direction; "
        "0 lateral, 90 circumferential; depth default the tread depth).", "none (slick)"),
    Key("tire", "footprint_image", Kind("table", lambda v, w: _IMAGE.check(v, w), lambda: _IMAGE.subkeys()),
        "Pattern from a footprint image instead of `grooves`: `{ file, pixel_m, rubber }` (rubber \"dark\" "
        "or \"bright\")."),
    Key("tire", "water", Kind("table", lambda v, w: _WATER.check(v, w), lambda: _WATER.subkeys()),
        "Wet road: `{ thickness_m, viscosity_Pa_s, density_kg_m3, alpha, beta, outlet_gap_m }` (only "
        "`thickness_m` is required).", "dry"),
    Key("tire", "speeds_m_s", SPEEDS, "Vehicle speeds of the map, m/s.", "[16.7]"),
    Key("tire", "slips", Kind("slip or list of slips in (0, 1]", _slips), "Slip ratios of the map.",
        "11 slips from 0.02 to 1"),
    Key("tire", "mu_loc", _range(0.0, 3.0), "Constant local friction instead of the engine's on the "
        "sub-resolution scales."),
    Key("tire", "q1", POSITIVE, "Short-distance cut-off of the extrapolated microtexture for mu_loc, rad/m.",
        "1e6"),
    Key("tire", "flash_temperature", BOOLEAN, "Flash temperature in mu_loc.", "false"),
    Key("tire", "adhesion", BOOLEAN, "Adhesion in mu_loc on a dry road.", "true"),
    Key("tire", "element_size_m", POSITIVE, "Tread element spacing, m.", "0.2 mm"),
    Key("tire", "road_element_m", POSITIVE, "Road element size, m.", "the profiles' spacing"),
    Key("tire", "contact_length_m", POSITIVE, "Measured footprint length, m, instead of the model's (the "
        "model's footprint shape is that of a 205/60 R15 reference tyre; its area is within 10 % of ink prints)."),
    Key("tire", "contact_width_m", POSITIVE, "Measured footprint width, m, instead of the model's."),
    Key("tire", "face_m", POSITIVE, "Length of an element's flat contact face: the element rests on the road's "
        "upper envelope over it (none: a point contact at the element's tip).", "none"),
)
_GROOVES = _subtable("groove width and pitch", ("width_m", "pitch_m"), width_m=POSITIVE, pitch_m=POSITIVE,
                     depth_m=POSITIVE, angle_deg=_range(-90.0, 90.0))
_IMAGE = _subtable("image file and pixel size", ("file", "pixel_m"), file=FILE, pixel_m=POSITIVE,
                   rubber=_choice("dark", "bright"))
_WATER = _subtable("water depth", ("thickness_m",), thickness_m=POSITIVE, viscosity_Pa_s=POSITIVE,
                   density_kg_m3=POSITIVE, alpha=_range(0.0, 1.0e4), beta=_range(0.0, 1.0e4), outlet_gap_m=POSITIVE)


# --- [rig]: a friction trailer's measuring tires (validation.rigs builds the rig; the keys are checked here)
_RIG_TIRE = _subtable("the tire's rolling radius, offset, lever arms and mass",
                      ("wheel_radius_m", "offset_m", "l_left_m", "l_right_m", "l_span_m", "mass_kg"),
                      wheel_radius_m=POSITIVE, offset_m=NUMBER, l_left_m=NUMBER, l_right_m=NUMBER,
                      l_span_m=POSITIVE, mass_kg=NUMBER, l_chain_m=POSITIVE, slip=_range(0.0, 1.0))


def _rig_tires(value, where: str) -> list:
    if not isinstance(value, list) or not value:
        raise _expected(where, "one [[rig.tires]] table per measuring tire", value)
    return [_RIG_TIRE.check(t, f"{where}[{i}]") for i, t in enumerate(value)]


_RIG_KEYS = (
    Key("rig", "name", TEXT, "Name of the rig, used in messages."),
    Key("rig", "tires", Kind("[[rig.tires]] tables", _rig_tires, _RIG_TIRE.subkeys),
        "One table per measuring tire: `wheel_radius_m`, `offset_m` (fore/aft position of its contact behind "
        "the first tire's), `l_left_m`, `l_right_m`, `l_span_m` (lever arms of the load cells), `mass_kg` (below "
        "the cells), optional `l_chain_m` and `slip` (a fixed slip when the file has no wheel speed)."),
)

#: Every key, one declaration each (in the order of the docs).
KEYS: tuple[Key, ...] = (
    Key("", "name", TEXT, "Name of the study, used in output file names and reports.", "the case folder's name"),
    # --- surface
    Key("surface", "psd", FILE, "PSD table: columns `q` (rad/m) and `C` (m^4), 2D isotropic."),
    Key("surface", "profiles", FILES, "Profile files (CSV with `x_<unit>`, `z_<unit>` columns, or CAPTIF "
        "exports); their profiles are pooled into one PSD."),
    Key("surface", "example", _choice("road"), "The package's synthetic example road instead of files."),
    Key("surface", "q0", POSITIVE, "Long-wavelength cut-off, rad/m: the integrals start here.",
        "the PSD's first q"),
    Key("surface", "q1", POSITIVE, "Short-distance cut-off, rad/m: the integrals end here (not past the PSD's "
        "last q; the `microtexture` effect extends the tail).", "the PSD's last q"),
    Key("surface", "q_rolloff", POSITIVE, "Roll-off wavevector, rad/m: the PSD is flat below it. Sets the "
        "macro-asperity scale of the flash temperature; without it a PSD table's roll-off is fitted "
        "(`surfaces.fit_rolloff`) and the result says so.", "the PSD file's `# q_rolloff`, else fitted"),
    Key("surface", "stretch", STRETCH, "An anisotropic surface: the PSD stretched `ratio` times along "
        "`angle_deg` (degrees from the x axis; the ridges run along it), `{ ratio = 3.0, angle_deg = 0.0 }`.",
        "isotropic"),
    Key("surface", "unidirectional_deg", DEGREES, "The profiles, scanned across the ridges of a polished or "
        "brushed surface, as its unidirectional limit C1D(q) delta(q_perp): the direction of their wavevectors "
        "(of the scans), degrees from the x axis."),
    Key("surface", "read_options", _READ_OPTIONS, "Options of the profile readers, e.g. "
        "`{ delimiter = \";\" }` (CSV) or `{ trim_plates = false }` (CAPTIF), `format`."),
    Key("surface", "psd_options", _options_of("surfaces:ProfileSet.psd"),
        "Options of the 1D PSD of the profiles, e.g. `{ window = \"hann\", n_per_decade = 20 }`."),
    Key("surface", "isotropic_options", _options_of("surfaces:PSD1D.to_isotropic"),
        "Options of the 1D -> 2D conversion, e.g. `{ q_max = 2e4 }` to stop below an instrument noise floor."),
    # --- material
    Key("material", "master_curve", FILE, "Master-curve table `f_Hz, E_storage_Pa, E_loss_Pa` at the "
        "reference temperature; needs `wlf` (or `shift_factors`)."),
    Key("material", "master_curve_options",
        _options_of("materials:read_master_curve", exclude=("wlf", "shift", "fit", "thermal")),
        "Options of the master-curve reader (e.g. `columns`, `units`)."),
    Key("material", "dma", FILES, "DMA isotherms: a file, a list of files, or a folder (e.g. an Eplexor "
        "export); shifted into a master curve."),
    Key("material", "dma_options", _options_of("materials:read_dma"),
        "Options of the DMA reader, e.g. `{ format = \"eplexor\", drop_bad = true }`."),
    Key("material", "example", _choice("tread"), "The package's example tread compound instead of files."),
    Key("material", "wlf", WLF_TABLE,
        "WLF constants: log10 aT = -C1 (T - T_ref) / (C2 + T - T_ref). With `dma`, the isotherms are shifted "
        "by this law instead of fitted shifts."),
    Key("material", "shift_factors", FILE, "Measured shift factors: a table of temperature (deg C) and "
        "a_T (or log10 a_T); interpolated between the temperatures."),
    Key("material", "shift_law", _choice("auto", "wlf", "wlf+arrhenius", "arrhenius", "tabulated"),
        "Shift law of the master curve built from `dma`.", '"auto" (by fit quality)'),
    Key("material", "T_ref_C", NUMBER, "Reference temperature of the master curve built from `dma`, deg C.",
        "20"),
    Key("material", "Tg_C", NUMBER_OR_AUTO, "Glass transition temperature, deg C, or \"auto\" (estimated from "
        "the DMA data): below it an Arrhenius law may take over from WLF.", "none"),
    Key("material", "Tg", NUMBER_OR_AUTO, "Older spelling of `Tg_C` (accepted)."),
    Key("material", "T_upper_C", NUMBER, "Temperature, deg C, above which the WLF shift law hands over to an "
        "Arrhenius law, continuous in log10 aT and its slope (WLF holds up to about Tg + 100 K; Ferry 1980, ch. 11). "
        "For flash and patch temperatures far above the DMA range; applies to a WLF law (given or fitted) and to "
        "the continuation of `shift_factors` beyond their table.", "none"),
    Key("material", "wlf_range_C", PAIR, "Temperatures [low, high], deg C, over which the WLF law is fitted.",
        "all isotherms"),
    Key("material", "shift_options", _options_of("materials:shift_isotherms"),
        "Options of the automated time-temperature superposition, e.g. `{ smoothing = 0.3 }`."),
    Key("material", "fit", _choice("auto", "table", "prony"), "How the master curve is represented: the "
        "shifted data as a table, a Prony series, or the better of the two.", '"auto"'),
    Key("material", "strain_sweeps", FILES, "Strain-sweep files or folders of them (modulus vs strain amplitude, "
        "e.g. one file per temperature) of the compound: "
        "the per-scale factors of the `strain_softening` effect (which must be switched on; see "
        "`[model.strain_softening]`)."),
    Key("material", "strain_options", _options_of("materials:read_strain_sweep", "materials:strain_factors"),
        "Options of the strain-sweep reader and of the softening factors."),
    Key("material", "poisson", _range(0.0, 0.5), "Poisson ratio nu; the effective modulus is E/(1 - nu^2).",
        "0.5"),
    Key("material", "thermal", _fields_of("materials:Thermal"), "Thermal properties for the flash "
        "temperature: density (kg/m^3), specific_heat (J/(kg K)), conductivity (W/(m K))."),
    # --- contact
    Key("contact", "length_m", LENGTH, "Contact length in the rolling direction, m (at most 1 m: a tire's is "
        "0.1-0.2 m)."),
    Key("contact", "width_m", LENGTH, "Contact width, m (at most 1 m)."),
    Key("contact", "stiffness_Pa_per_m", POSITIVE, "Shear stiffness of the tread per unit area per unit "
        "displacement, Pa/m (about G/h for a layer of shear modulus G and thickness h)."),
    Key("contact", "pressure_distribution", PRESSURE_DISTRIBUTION, "Pressure along the contact: "
        "6 sigma0 (x/l)(1 - x/l), uniform, or Sakai's n-power law.", '"parabolic"'),
    Key("contact", "n_points", INTEGER, "Nodes along the contact patch (>= 11).", "401"),
    # --- model
    Key("model", "gamma", _range(0.0, 1.0), "gamma of S(q) = gamma + (1 - gamma) P(q)^2.", "0.5"),
    Key("model", "effects", NAMES, "Effects switched on in the baseline, e.g. `[\"adhesion\"]`.", "[]"),
    Key("model", "fit", NAME_OR_NAMES, "Baseline parameters fitted to the measurements by the validation "
        "loop: `\"<effect>.<parameter>\"` of an effect switched on, or `\"gamma\"`.", "[]"),
    Key("model", "grid", _fields_of("persson.engine.grid:GridSettings"), "Numerical resolution "
        "(`persson.GridSettings` fields, e.g. `{ q_per_decade = 48 }`).", "the defaults"),
    # --- conditions
    Key("conditions", "speeds_m_s", SPEEDS, "Sliding speeds, m/s.", "50 speeds from 1e-6 to 10 m/s"),
    Key("conditions", "speed_range_m_s", SPEED_RANGE, "Log-spaced sliding speeds [min, max, n], m/s (instead "
        "of `speeds_m_s`)."),
    Key("conditions", "temperature_C", NUMBER, "Background temperature, deg C.", "20"),
    Key("conditions", "pressure_Pa", POSITIVE, "Nominal contact pressure, Pa (1 kPa to 100 MPa).", "3e5"),
    Key("conditions", "sliding_direction_deg", DEGREES, "Sliding direction, degrees from the x axis of the "
        "surface; it matters on an anisotropic surface (`[surface] stretch` or `unidirectional_deg`). A value "
        "that looks like radians (within 2 pi, with a fraction) is refused.", "0"),
    # --- measurements
    Key("measurements", "file", FILE, "Measured friction CSV: `slip, speed_m_s, T_C, pressure_Pa, mu` "
        "(optional `mu_std, wet, series, position_m, water_depth_m, tread_depth_m, bpn, mpd_m, device`)."),
    *_TIRE_KEYS,
    *_RIG_KEYS,
)


# ---------------------------------------------------------------------------------------------------------
def check_case(raw: dict, where: str = "case.toml") -> dict:
    """Validate a parsed case file against the schema; returns a copy with numbers as floats.

    Parameters
    ----------
    raw : dict
        The parsed TOML.
    where : str
        The file, named in every message.

    Raises
    ------
    InputError
        An unknown section or key (with "did you mean ..."), a value of the wrong type (naming the section
        and key), an effect table for an unknown effect or with an unknown parameter.
    """
    by_section = _keys_by_section()
    out: dict = {}
    for name, value in raw.items():
        if isinstance(value, dict):
            if name not in by_section or name == "":
                raise InputError(f"{where}: unknown section [{name}]{suggest(name, _sections(), brackets=True)}; sections: "
                                 f"{', '.join(f'[{s}]' for s in _sections())}")
            out[name] = _check_section(name, value, by_section[name], where)
        elif name in by_section and name != "":
            raise InputError(f"{where}: {name} must be a table [{name}] with keys, got {name} = {_show(value)}")
        else:
            out[name] = _check_value(by_section[""], "", name, value, where)
    return out


def _check_section(section: str, table: dict, keys: dict, where: str) -> dict:
    out = {}
    effects = _effect_classes() if section == "model" else {}
    for name, value in table.items():
        if section == "model" and isinstance(value, dict) and name not in keys:
            out[name] = _check_effect_table(name, value, effects, where)
            continue
        out[name] = _check_value(keys, section, name, value, where)
    if section == "model":
        _check_effect_names(out, effects, where)
    if section == "material" and "Tg" in out:
        if "Tg_C" in out:
            raise InputError(f"{where}: [material] gives both Tg_C and its older spelling Tg; keep Tg_C")
        out["Tg_C"] = out.pop("Tg")
    return out


def _check_value(keys: dict, section: str, name: str, value, where: str):
    label = f"[{section}]" if section else "the top level"
    if name not in keys:
        tables = [f"[{section}.{e}]" for e in _effect_classes()] if section == "model" else []
        raise InputError(f"{where}: unknown key {name!r} in {label}{suggest(name, list(keys))}; keys of {label}: "
                         f"{', '.join(keys)}" + (f"; effect tables: {', '.join(tables)}" if tables else ""))
    key = keys[name]
    return key.kind.check(value, f"{where}: [{section}] {name}" if section else f"{where}: {name}")


def _check_effect_table(name: str, table: dict, effects: dict, where: str) -> dict:
    if name not in effects:
        names = [f"model.{e}" for e in effects] + ["model.grid"]
        raise InputError(f"{where}: unknown section [model.{name}]{suggest('model.' + name, names, brackets=True)};"
                         f" effect tables: {', '.join(f'[model.{e}]' for e in effects)}")
    fields = _effect_fields(effects[name])
    label = f"{where}: [model.{name}]"
    _check_keys(table, fields, label, what=f"parameter of the {name} effect")
    return {k: _field_value(fields[k], v, f"{label} {k}") for k, v in table.items()}


def _check_effect_names(model: dict, effects: dict, where: str) -> None:
    for n in model.get("effects", []):
        if n not in effects:
            raise InputError(f"{where}: [model] effects: unknown effect {n!r}{suggest(n, list(effects))}; "
                             f"available: {', '.join(effects)}")
    on = set(model.get("effects", []))
    for name, value in model.items():
        if isinstance(value, dict) and name in effects and name not in on:
            raise InputError(f"{where}: [model.{name}] sets parameters of the {name} effect, which is not switched "
                             f"on: add \"{name}\" to [model] effects (or remove the table)")


def _check_keys(table: dict, known, where: str, what: str = "key") -> None:
    for k in table:
        if k not in known:
            raise InputError(f"{where}: unknown {what} {k!r}{suggest(k, list(known))}; known: "
                             f"{', '.join(known) or 'none'}")


def suggest(name: str, candidates, brackets: bool = False) -> str:
    """``"; did you mean 'x'?"`` for the closest candidate (case-insensitive), or ``""``."""
    if not isinstance(name, str):
        return ""
    lower = {str(c).lower(): str(c) for c in candidates}
    match = difflib.get_close_matches(name.lower(), list(lower), n=1, cutoff=0.6)
    if not match:
        return ""
    best = lower[match[0]]
    return f"; did you mean [{best}]?" if brackets else f"; did you mean {best!r}?"


# ---------------------------------------------------------------------------------------------------------
def _field_value(f, value, where: str):
    kind = _field_kind(f)
    return kind.check(value, where) if kind is not None else value


def _field_kind(f) -> Kind | None:
    t = f.type if isinstance(f.type, str) else getattr(f.type, "__name__", str(f.type))
    t = t.replace(" ", "")
    if t in ("float", "int|float", "float|int"):
        return NUMBER
    if t == "int":
        return INTEGER
    if t == "bool":
        return BOOLEAN
    if t == "str":
        return TEXT
    if t in ("float|None", "None|float"):
        return Kind("number", lambda v, w: _number(v, w))
    return None  # anything else is checked by the object itself


def _field_type_text(f) -> str:
    kind = _field_kind(f)
    text = kind.text if kind is not None else "value"
    default = f.default if f.default is not dataclasses.MISSING else None
    return f"{text}, default {default!r}" if default is not None else text


def _effect_fields(cls) -> dict:
    return {f.name: f for f in dataclasses.fields(cls) if f.init and not f.name.startswith("_")}


def _effect_classes() -> dict:
    from ..effects import available

    return available()


def _keys_by_section() -> dict[str, dict[str, Key]]:
    out: dict[str, dict[str, Key]] = {s: {} for s in SECTIONS}
    for k in KEYS:
        out[k.section][k.name] = k
    return out


def _sections() -> list[str]:
    return [s for s in SECTIONS if s]


def _resolve(target: str):
    module, _, attr = target.partition(":")
    try:
        obj = importlib.import_module(module)
        for part in attr.split("."):
            obj = getattr(obj, part)
        return obj
    except (ImportError, AttributeError):
        return None


# ---------------------------------------------------------------------------------------------------------
BEGIN = "<!-- case-keys: generated by `python -m persson.case.schema docs/conventions.md`; do not edit -->"
END = "<!-- case-keys: end -->"


def markdown() -> str:
    """The reference of every case-file key (Markdown), as in ``docs/conventions.md``."""
    lines = [BEGIN, ""]
    by_section = _keys_by_section()
    for section, doc in SECTIONS.items():
        lines.append(f"#### {'Top level' if not section else f'[{section}]'}")
        lines.append("")
        lines.append(doc)
        lines.append("")
        lines.append("| key | type | default | meaning |")
        lines.append("| --- | --- | --- | --- |")
        for k in by_section[section].values():
            lines.append(f"| `{k.name}` | {_cell(k.kind.text)} | {_cell(k.default or '-')} | {_cell(k.doc)}"
                         f"{_subkeys(k)} |")
        lines.append("")
    lines.append("#### [model.&lt;effect&gt;]")
    lines.append("")
    lines.append("Parameters of an effect switched on in `[model] effects` (other fields of the effect's class "
                 "are accepted too). Built-in effects:")
    lines.append("")
    lines.append("| table | key | default | unit | meaning |")
    lines.append("| --- | --- | --- | --- | --- |")
    from ..effects import builtin  # the built-in effects only: user effects document themselves

    builtin_classes = {name: cls for name, cls in _effect_classes().items() if cls.__module__ == builtin.__name__}
    for name, cls in builtin_classes.items():
        for p in cls.parameters:
            lines.append(f"| `[model.{name}]` | `{p.name}` | {p.default:g} | {p.unit} | {_cell(p.doc)} |")
        others = [f for f in _effect_fields(cls) if f not in {p.name for p in cls.parameters}]
        if others:
            lines.append(f"| `[model.{name}]` | {', '.join(f'`{f}`' for f in others)} | | | other options "
                         f"of `{cls.__name__}` |")
    lines.append("")
    lines.append(END)
    return "\n".join(lines)


def write_docs(path) -> bool:
    """Rewrite the generated section of ``path`` (between the markers); returns True when it changed."""
    path = Path(path)
    text = path.read_text(encoding="utf-8-sig")
    if BEGIN not in text or END not in text:
        raise InputError(f"{path}: markers {BEGIN!r} ... {END!r} not found")
    head, rest = text.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    new = head + markdown() + tail
    if new == text:
        return False
    from ..io import atomic_write

    with atomic_write(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(new)
    return True


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _subkeys(k: Key) -> str:
    if k.kind.subkeys is None:
        return ""
    sub = k.kind.subkeys()
    if not sub:
        return ""
    return " Keys: " + ", ".join(f"`{n}`" for n in sub) + "."


if __name__ == "__main__":  # pragma: no cover - documentation tool
    target = sys.argv[1] if len(sys.argv) > 1 else "docs/conventions.md"
    print(f"{target}: {'updated' if write_docs(target) else 'already up to date'}")
