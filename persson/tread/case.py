"""The ``[tire]`` section of a case file: the tyre, its pattern, the water and the map for ``persson tread``.

The keys are declared (and type-checked by :func:`persson.case.parse_case`) in :mod:`persson.case.schema` and
documented in ``docs/conventions.md``; this module builds the objects. The road is the case's
``[surface] profiles``; a case with a PSD (``psd`` or ``example``) gets synthetic profiles of that PSD (1.2 m at
0.1 mm, fixed seed), and says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError
from .pattern import Grooves, read_footprint
from .simulate import DEFAULT_SLIPS
from .tire import Tire
from .wet import Water

__all__ = ["TreadCase", "read_tread_case"]

_REQUIRED = ("diameter_m", "width_m", "load_N", "inflation_pressure_Pa", "tread_depth_m")


@dataclass(frozen=True, eq=False)
class TreadCase:
    """A case file's tyre, road, material and map settings.

    Attributes
    ----------
    name : str
    path : Path
    tire : Tire
    road : object
        The profiles (a :class:`surfaces.ProfileSet`).
    material : object
    temperature : float
        deg C.
    speeds, slips : ndarray
    water : Water or None
    mu_loc : float or None
    options : dict
        Keyword options for :func:`persson.tread.slip_map`.
    inputs : tuple of Path
        Every file the case reads.
    notes : tuple of str
    """

    name: str
    path: Path
    tire: Tire
    road: object
    material: object
    temperature: float
    speeds: np.ndarray
    slips: np.ndarray
    water: Water | None = None
    mu_loc: float | None = None
    options: dict = field(default_factory=dict)
    inputs: tuple = ()
    notes: tuple = ()


def read_tread_case(path, *, progress=None) -> TreadCase:
    """Read a case file with a ``[tire]`` section.

    Parameters
    ----------
    path : str or path-like
        The case file, its folder or a shipped case's name.
    progress : callable, optional
        Status texts while slow parts run.

    Raises
    ------
    InputError
        Naming the file and key: no ``[tire]`` section, a missing tyre key, a pattern given twice, a missing
        image file, or anything :func:`persson.case.parse_case` refuses.
    """
    from ..case.loader import build_material, parse_case

    case = parse_case(path)
    raw, path = case.raw, case.path
    base = path.parent
    tab = raw.get("tire")
    if not tab:
        raise InputError(f"{path}: no [tire] section (the tyre for persson tread; see docs/conventions.md, "
                         "\"The case file\")")
    missing = [k for k in _REQUIRED if k not in tab]
    if missing:
        raise InputError(f"{path}: [tire] needs {', '.join(repr(k) for k in missing)}")
    if "grooves" in tab and "footprint_image" in tab:
        raise InputError(f"{path}: [tire] give grooves or footprint_image, not both")
    notes: list[str] = []
    inputs = list(case.inputs)
    pattern = None
    if "grooves" in tab:
        g = tab["grooves"]
        pattern = _named(path, "grooves", Grooves, width=g["width_m"], pitch=g["pitch_m"], depth=g.get("depth_m"),
                         angle_deg=g.get("angle_deg", 0.0))
    elif "footprint_image" in tab:
        im = tab["footprint_image"]
        f = base / im["file"]
        if not f.is_file():
            raise InputError(f"{path}: [tire] footprint_image file: {f} does not exist")
        inputs.append(f)
        pattern = _named(path, "footprint_image", read_footprint, f, im["pixel_m"], rubber=im.get("rubber", "dark"))
    kw = {}
    if tab.get("rigid_elements", False):
        kw["slip_stiffness"] = None
    elif "slip_stiffness" in tab:
        kw["slip_stiffness"] = tab["slip_stiffness"]
    if "pressure_distribution" in tab:
        kw["pressure_distribution"] = tab["pressure_distribution"]
    if "vertical_stiffness_N_per_m" in tab:
        kw["vertical_stiffness"] = tab["vertical_stiffness_N_per_m"]
    if "contact_length_m" in tab:
        kw["contact_length"] = tab["contact_length_m"]
    if "contact_width_m" in tab:
        kw["contact_width"] = tab["contact_width_m"]
    tire = _named(path, "", Tire, diameter=tab["diameter_m"], width=tab["width_m"], load=tab["load_N"],
                  inflation_pressure=tab["inflation_pressure_Pa"], tread_depth=tab["tread_depth_m"],
                  grooves=pattern, **kw)
    water = None
    if "water" in tab:
        w = tab["water"]
        names = {"thickness_m": "thickness", "viscosity_Pa_s": "viscosity", "density_kg_m3": "density",
                 "alpha": "alpha", "beta": "beta", "outlet_gap_m": "outlet_gap"}
        water = _named(path, "water", Water, **{names[k]: v for k, v in w.items()})
    if progress is not None:
        progress("reading the road profiles")
    road = _road(raw["surface"], base, path, notes)
    if progress is not None:
        progress("building the material")
    material = build_material(raw["material"], base, path, progress=progress, notes=notes)
    T = float(raw.get("conditions", {}).get("temperature_C", 20.0))
    speeds = np.asarray(tab.get("speeds_m_s", [16.7]), dtype=float)
    slips = np.asarray(tab.get("slips", DEFAULT_SLIPS), dtype=float)
    options = {}
    for key, opt in (("q1", "q1"), ("element_size_m", "element_size"), ("road_element_m", "road_element"),
                     ("adhesion", "adhesion"), ("face_m", "face")):
        if key in tab:
            options[opt] = tab[key]
    if tab.get("flash_temperature", False):
        from ..effects import FlashTemperature

        options["local_effects"] = (FlashTemperature(),)
    return TreadCase(name=case.name, path=path, tire=tire, road=road, material=material, temperature=T,
                     speeds=speeds, slips=slips, water=water, mu_loc=tab.get("mu_loc"), options=options,
                     inputs=tuple(inputs), notes=tuple(notes) + tire.footprint.notes)


def _road(surf: dict, base: Path, path: Path, notes: list):
    import surfaces

    if "profiles" in surf:
        sets = []
        for name in surf["profiles"]:
            try:
                sets.append(surfaces.read_profiles(base / name, **surf.get("read_options", {})))
            except InputError as exc:
                raise InputError(f"{path}: [surface] profiles: {exc}") from None
        return sets[0] if len(sets) == 1 else surfaces.ProfileSet.concatenate(sets)
    from ..case.loader import build_surface

    psd = build_surface(surf, base, path)
    dx = 1.0e-4
    if math.pi / dx > float(psd.q_range[1]):
        dx = math.pi / float(psd.q_range[1])
    notes.append(f"road: synthetic profile of the case's PSD (1.2 m at {dx * 1e3:.3g} mm, seed 0); give [surface] "
                 "profiles for a measured road")
    n = int(round(1.2 / dx))
    return surfaces.synthesize_profiles(psd, n_profiles=1, n=n, length=n * dx, seed=0)


def _named(path: Path, key: str, fn, *args, **kwargs):
    try:
        return fn(*args, **kwargs)
    except InputError as exc:
        where = f"[tire] {key}" if key else "[tire]"
        raise InputError(f"{path}: {where}: {exc}") from None
