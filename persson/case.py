"""Case files (``case.toml``): one study bound together (DESIGN.md "Formats on disk").

:func:`read_case` builds the :class:`~persson.Model` (surface, material, Poisson ratio, gamma, baseline effects)
and the operating conditions; :func:`validation.load_case` adds the measurements. Paths in the file are relative
to the file's folder. Sections beyond DESIGN.md that this reader accepts:

``[conditions]``
    ``speeds_m_s = [...]`` or ``speed_range_m_s = [min, max, n]`` (log-spaced), ``temperature_C``,
    ``pressure_Pa`` -- used by ``persson friction``.
``[surface] example = "road"`` / ``[material] example = "tread"``
    the package's documented synthetic examples instead of files.
``[surface] profiles = [...]``
    with optional ``read_options``, ``psd_options`` and ``isotropic_options`` tables passed to
    :func:`surfaces.read_profiles`, :meth:`surfaces.ProfileSet.psd` and :meth:`surfaces.PSD1D.to_isotropic`
    (e.g. ``isotropic_options = { q_max = 2e4 }`` to stop the measured band below an instrument noise floor).
``[material] dma = "dma.csv"``
    with ``wlf = {...}`` the isotherms are shifted by that WLF law; without it the shifts are found by automated
    time-temperature superposition at ``T_ref_C`` (default 20 C).
"""

from __future__ import annotations

import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .errors import InputError
from .model import Model

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["CaseSpec", "read_case", "build_surface", "build_material"]


@dataclass(frozen=True, eq=False)
class CaseSpec:
    """A parsed case file.

    Attributes
    ----------
    name : str
    path : Path
        The case file.
    model : persson.Model
        Surface, material and baseline effects.
    speeds : ndarray
        Sliding speeds for ``persson friction``, m/s.
    temperature : float
        Background temperature, deg C.
    pressure : float
        Nominal pressure, Pa.
    contact : dict
        The ``[contact]`` table (brush model of the wheel), empty when absent.
    measurements : Path or None
        The measurements file named in ``[measurements]``.
    raw : dict
        The whole parsed TOML.
    """

    name: str
    path: Path
    model: Model
    speeds: np.ndarray
    temperature: float
    pressure: float
    contact: dict = field(default_factory=dict)
    measurements: Path | None = None
    raw: dict = field(default_factory=dict)

    def contact_model(self):
        """The :class:`persson.slip.Contact` of the ``[contact]`` table (InputError when absent)."""
        if not self.contact:
            raise InputError(f"{self.path}: no [contact] table (needed for slip < 1)")
        from .slip import Contact

        c = self.contact
        try:
            return Contact(length=float(c["length_m"]), width=float(c["width_m"]),
                           stiffness=float(c["stiffness_Pa_per_m"]),
                           pressure_distribution=_pressure_distribution(c.get("pressure_distribution", "parabolic")))
        except KeyError as exc:
            raise InputError(f"{self.path}: [contact] needs {exc.args[0]!r}") from None


def read_case(path) -> CaseSpec:
    """Read a ``case.toml`` into a :class:`CaseSpec`.

    Raises
    ------
    InputError
        Naming the file and the key when something is missing, malformed or points at a missing file.
    """
    path = Path(path)
    if path.is_dir():
        path = path / "case.toml"
    if not path.is_file():
        raise InputError(f"case file {path} does not exist")
    try:
        raw = tomllib.loads(path.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise InputError(f"{path}: not a valid TOML file ({exc})") from None
    base = path.parent
    surface = build_surface(_table(raw, "surface", path), base, path)
    mat_tab = _table(raw, "material", path)
    material = build_material(mat_tab, base, path)
    nu = float(mat_tab.get("poisson", 0.5))
    model_tab = raw.get("model", {})
    gamma = float(model_tab.get("gamma", 0.5))
    effects = _effects(model_tab, path)
    kwargs: dict[str, Any] = {}
    if "grid" in model_tab:
        from .grid import GridSettings

        kwargs["grid"] = GridSettings(**model_tab["grid"])
    try:
        model = Model(surface, material, nu=nu, gamma=gamma, effects=effects, **kwargs)
    except InputError as exc:
        raise InputError(f"{path}: {exc}") from None
    cond = raw.get("conditions", {})
    speeds = _speeds(cond, path)
    meas = raw.get("measurements", {})
    mpath = None
    if meas:
        if "file" not in meas:
            raise InputError(f"{path}: [measurements] needs file = \"...\"")
        mpath = base / meas["file"]
        if not mpath.is_file():
            raise InputError(f"{path}: [measurements] file {mpath} does not exist")
    return CaseSpec(name=str(raw.get("name", path.parent.name)), path=path, model=model, speeds=speeds,
                    temperature=float(cond.get("temperature_C", 20.0)),
                    pressure=float(cond.get("pressure_Pa", 0.3e6)), contact=dict(raw.get("contact", {})),
                    measurements=mpath, raw=raw)


def build_surface(tab: dict, base: Path, path: Path):
    """The surface PSD of a ``[surface]`` table."""
    import surfaces

    keys = [k for k in ("psd", "profiles", "example") if k in tab]
    if len(keys) != 1:
        raise InputError(f"{path}: [surface] needs exactly one of psd, profiles, example (got {keys})")
    key = keys[0]
    if key == "example":
        if tab["example"] != "road":
            raise InputError(f"{path}: [surface] example must be \"road\", got {tab['example']!r}")
        s = surfaces.example_road()
    elif key == "psd":
        s = surfaces.read_psd(_file(base, tab["psd"], path, "surface.psd"))
    else:
        files = tab["profiles"] if isinstance(tab["profiles"], list) else [tab["profiles"]]
        sets = [surfaces.read_profiles(_file(base, f, path, "surface.profiles"), **tab.get("read_options", {}))
                for f in files]
        ps = sets[0] if len(sets) == 1 else surfaces.ProfileSet.concatenate(sets)
        try:
            s = ps.psd(**tab.get("psd_options", {})).to_isotropic(**tab.get("isotropic_options", {}))
        except TypeError as exc:
            raise InputError(f"{path}: [surface] psd_options / isotropic_options: {exc}") from None
    if "q0" in tab or "q1" in tab:
        q0 = tab.get("q0")
        q1 = tab.get("q1")
        lo, hi = s.q_range
        if q1 is not None and float(q1) > hi * (1 + 1e-9):
            raise InputError(f"{path}: [surface] q1 = {float(q1):g} rad/m lies past the PSD's last q = {hi:g}; "
                             "nothing is extrapolated unless asked: switch on the microtexture effect "
                             "([model] effects = [\"microtexture\"]) to extend the tail")
        s = s.with_cutoff(q0=None if q0 is None else float(q0), q1=None if q1 is None else float(q1))
    return s


def build_material(tab: dict, base: Path, path: Path):
    """The material of a ``[material]`` table (master curve + WLF, DMA data, or the example tread)."""
    import materials

    keys = [k for k in ("master_curve", "dma", "example") if k in tab]
    if len(keys) != 1:
        raise InputError(f"{path}: [material] needs exactly one of master_curve, dma, example (got {keys})")
    thermal = None
    if "thermal" in tab:
        try:
            thermal = materials.Thermal(**tab["thermal"])
        except TypeError as exc:
            raise InputError(f"{path}: [material] thermal: {exc}") from None
    key = keys[0]
    if key == "example":
        if tab["example"] != "tread":
            raise InputError(f"{path}: [material] example must be \"tread\", got {tab['example']!r}")
        m = materials.example_tread()
    elif key == "master_curve":
        if "wlf" not in tab:
            raise InputError(f"{path}: [material] master_curve needs wlf = {{ C1 = ..., C2 = ..., T_ref_C = ... }}")
        wlf = materials.WLF.from_mapping(tab["wlf"])
        m = materials.read_master_curve(_file(base, tab["master_curve"], path, "material.master_curve"), wlf=wlf)
    else:
        dma = materials.read_dma(_file(base, tab["dma"], path, "material.dma"))
        if "wlf" in tab:
            # The case gives the compound's WLF law: use it as the shift factors instead of fitting new ones.
            wlf = materials.WLF.from_mapping(tab["wlf"])
            m = materials.master_curve(dma, T_ref=wlf.T_ref, shift_factors=wlf)
        else:
            m = materials.master_curve(dma, T_ref=float(tab.get("T_ref_C", 20.0)))
    if thermal is not None:
        m = _with_thermal(m, thermal)
    return m


def _with_thermal(material, thermal):
    import dataclasses

    if dataclasses.is_dataclass(material) and any(f.name == "thermal" for f in dataclasses.fields(material)):
        return dataclasses.replace(material, thermal=thermal)
    if hasattr(material, "with_thermal"):
        return material.with_thermal(thermal)
    raise InputError(f"material {type(material).__name__} does not carry thermal properties")


def _effects(model_tab: dict, path: Path) -> tuple:
    from . import effects as fx

    names = model_tab.get("effects", [])
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
        raise InputError(f"{path}: [model] effects must be a list of effect names")
    out = []
    for n in names:
        params = model_tab.get(n, {})
        try:
            out.append(fx.get(n, **params))
        except TypeError as exc:
            raise InputError(f"{path}: [model.{n}]: {exc}") from None
        except InputError as exc:
            raise InputError(f"{path}: [model] effects: {exc}") from None
    return tuple(out)


def _speeds(cond: dict, path: Path) -> np.ndarray:
    if "speeds_m_s" in cond:
        v = np.asarray(cond["speeds_m_s"], dtype=float).ravel()
    elif "speed_range_m_s" in cond:
        try:
            lo, hi, n = cond["speed_range_m_s"]
            v = np.geomspace(float(lo), float(hi), int(n))
        except (TypeError, ValueError):
            raise InputError(f"{path}: [conditions] speed_range_m_s must be [min, max, n]") from None
    else:
        v = np.geomspace(1e-6, 10.0, 50)
    if v.size == 0 or not np.all(np.isfinite(v)) or np.any(v <= 0):
        raise InputError(f"{path}: [conditions] speeds must be finite and > 0 m/s")
    return v


def _pressure_distribution(spec):
    if isinstance(spec, dict):
        if "sakai_n" in spec:
            return {"sakai_n": float(spec["sakai_n"])}
        raise InputError(f"[contact] pressure_distribution: expected \"uniform\", \"parabolic\" or "
                         f"{{ sakai_n = n }}, got {spec!r}")
    return str(spec)


def _table(raw: dict, key: str, path: Path) -> dict:
    tab = raw.get(key)
    if not isinstance(tab, dict):
        raise InputError(f"{path}: missing [{key}] table")
    return tab


def _file(base: Path, name, path: Path, key: str) -> Path:
    if not isinstance(name, str):
        raise InputError(f"{path}: {key} must be a file name, got {name!r}")
    f = base / name
    if not f.is_file():
        raise InputError(f"{path}: {key} file {f} does not exist")
    return f
