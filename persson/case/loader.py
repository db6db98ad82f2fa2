"""Case files (``case.toml``): one study bound together.

Every section and key is declared in :mod:`persson.case.schema` and documented in ``docs/conventions.md``
("The case file"); an unknown key is an error ("did you mean ..."), and every value is type-checked with its key
named. :func:`parse_case` reads and checks the file without building anything (fast: the command line uses it to
check its outputs before computing); :func:`read_case` builds the :class:`~persson.Model` (surface, material,
Poisson ratio, gamma, baseline effects) and the operating conditions; :func:`validation.load_case` adds the
measurements. Paths in the file are relative to the file's folder.

A master curve built from DMA isotherms is cached by the content of its input files and options (see
:mod:`persson.case.cache`), so a second run on the same case does not refit it.
"""

from __future__ import annotations

import inspect
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np

from .._checks import plausible_pressure, plausible_speed, plausible_temperature
from .schema import check_case, suggest
from ..errors import InputError
from ..engine.model import Model

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["CaseSpec", "CaseFile", "read_case", "parse_case", "resolve_case", "shipped_cases", "build_surface",
           "build_material"]

#: Entry-point group through which installed packages offer shipped cases (name -> case.toml).
CASES_GROUP = "persson.cases"
#: Entry-point group naming a folder of cases inside a package ("package:folder"); read without importing it.
CASE_FOLDERS_GROUP = "persson.case_folders"

_DEFAULT_SPEEDS = (1e-6, 10.0, 50)


@dataclass(frozen=True, eq=False)
class CaseFile:
    """A case file read and checked against the schema, nothing built yet.

    Attributes
    ----------
    name : str
    path : Path
        The ``case.toml``.
    raw : dict
        The checked content (numbers as floats; ``Tg`` renamed ``Tg_C``).
    inputs : tuple of Path
        Every file the case reads (the case file, PSD, profiles, DMA files, master curve, shift factors,
        strain sweeps, measurements): a command never writes over them.
    """

    name: str
    path: Path
    raw: dict
    inputs: tuple = ()

    def __repr__(self) -> str:
        return f"CaseFile({self.name!r}, path={str(self.path)!r}, {len(self.inputs)} input files)"


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
        The whole checked TOML.
    inputs : tuple of Path
        Every file the case reads.
    notes : tuple of str
        What building the case did that a user should know (e.g. the master curve came from the cache).
    strain_factors : object or None
        Strain-softening factors from ``[material] strain_sweeps`` (``materials.strain_factors``), if given.
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
    inputs: tuple = ()
    notes: tuple = ()
    strain_factors: object = None

    def __repr__(self) -> str:
        m = self.model
        return (f"CaseSpec({self.name!r}, path={str(self.path)!r}, surface={type(m.surface).__name__}, "
                f"material={type(m.material).__name__}, effects={list(m.effect_names)}, "
                f"{self.speeds.size} speeds {self.speeds.min():.3g}-{self.speeds.max():.3g} m/s, "
                f"T={self.temperature:g} C, p={self.pressure:g} Pa"
                + (f", measurements={self.measurements.name!r}" if self.measurements else "") + ")")

    def contact_model(self):
        """The :class:`persson.slip.Contact` of the ``[contact]`` table (InputError when absent)."""
        if not self.contact:
            raise InputError(f"{self.path}: no [contact] table (needed for slip < 1)")
        from ..slip.contact import Contact

        c = self.contact
        missing = [k for k in ("length_m", "width_m", "stiffness_Pa_per_m") if k not in c]
        if missing:
            raise InputError(f"{self.path}: [contact] needs {', '.join(repr(k) for k in missing)}")
        extra = {"n_points": int(c["n_points"])} if "n_points" in c else {}
        return Contact(length=float(c["length_m"]), width=float(c["width_m"]),
                       stiffness=float(c["stiffness_Pa_per_m"]),
                       pressure_distribution=c.get("pressure_distribution", "parabolic"), **extra)


# ---------------------------------------------------------------------------------------------------------
def read_case(path, *, progress: Callable | None = None) -> CaseSpec:
    """Read a ``case.toml`` into a :class:`CaseSpec`.

    Parameters
    ----------
    path : str or path-like
        The case file, its folder, or the name of a shipped case (e.g. ``"example"``).
    progress : callable, optional
        Called with short status texts while slow parts run (reading profiles, building a master curve); see
        :mod:`persson.progress`.

    Raises
    ------
    InputError
        Naming the file and the key when something is unknown, missing, of the wrong type, implausible (a
        pressure or temperature in the wrong unit) or points at a missing file.
    """
    case = parse_case(path)
    raw, path = case.raw, case.path
    base = path.parent
    notes: list[str] = []
    _say(progress, "reading the surface")
    surface = build_surface(raw["surface"], base, path)
    mat_tab = raw["material"]
    _say(progress, "building the material")
    material = build_material(mat_tab, base, path, progress=progress, notes=notes)
    strain = _strain_factors(mat_tab, base, path)
    nu = float(mat_tab.get("poisson", 0.5))
    model_tab = raw.get("model", {})
    gamma = float(model_tab.get("gamma", 0.5))
    effects = _effects(model_tab, path, strain=strain, base=base)
    notes += _assumption_notes(raw, path)
    kwargs: dict[str, Any] = {}
    if "grid" in model_tab:
        from ..engine.grid import GridSettings

        with _key(path, "model", "grid"):
            kwargs["grid"] = GridSettings(**model_tab["grid"])
    cond = raw.get("conditions", {})
    if "sliding_direction_deg" in cond:
        kwargs["direction_deg"] = float(cond["sliding_direction_deg"])
    try:
        model = Model(surface, material, nu=nu, gamma=gamma, effects=effects, **kwargs)
    except InputError as exc:
        raise InputError(f"{path}: {exc}") from None
    speeds = _speeds(cond, path)
    T = float(cond.get("temperature_C", 20.0))
    p = float(cond.get("pressure_Pa", 0.3e6))
    plausible_temperature(T, f"{path}: [conditions] temperature_C", strict=True)
    plausible_pressure(p, f"{path}: [conditions] pressure_Pa", strict=True)
    mfile = raw.get("measurements", {}).get("file")
    return CaseSpec(name=case.name, path=path, model=model, speeds=speeds, temperature=T, pressure=p,
                    contact=dict(raw.get("contact", {})), measurements=None if mfile is None else base / mfile,
                    raw=raw, inputs=case.inputs, notes=tuple(notes), strain_factors=strain)


def parse_case(path) -> CaseFile:
    """Read and check a case file (schema, required tables, named files exist) without building anything.

    Parameters
    ----------
    path : str or path-like
        The case file, its folder, or the name of a shipped case.

    Returns
    -------
    CaseFile
    """
    path = resolve_case(path)
    if path.suffix.lower() in _TABLE_SUFFIXES:
        raise InputError(f"{path}: expected a case file (case.toml) or its folder, got a {path.suffix} table; a "
                         "case file names its inputs, e.g. [surface] psd = \"surface_psd.csv\" (see "
                         "docs/conventions.md, \"The case file\")")
    try:
        text = path.read_text(encoding="utf-8-sig")  # -sig: a byte-order mark (Windows editors) is not TOML
    except UnicodeDecodeError as exc:
        raise InputError(f"{path}: not a UTF-8 text file ({exc})") from None
    try:
        parsed = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: not a valid TOML file ({exc}){_looks_like_a_table(text)}") from None
    raw = check_case(parsed, str(path))
    for section in ("surface", "material"):
        if section not in raw:
            raise InputError(f"{path}: missing [{section}] table (see docs/conventions.md, \"The case file\")")
    _check_combinations(raw, path)
    inputs = [path] + _input_files(raw, path)
    return CaseFile(name=str(raw.get("name", path.parent.name)), path=path, raw=raw, inputs=tuple(inputs))


def resolve_case(path) -> Path:
    """The ``case.toml`` of a path, a folder, or the name of a shipped case (InputError when none)."""
    if not isinstance(path, (str, Path)):
        raise InputError(f"case: expected a case file, its folder or a shipped case's name, got {path!r}")
    p = Path(path)
    if p.is_dir():
        p = p / "case.toml"
    if p.is_file():
        return p
    if not p.exists() and isinstance(path, str) and "/" not in path and "\\" not in path and not p.suffix:
        cases = shipped_cases()
        if path in cases:
            return cases[path]
        raise InputError(f"case {path!r}: no such file or folder, and no shipped case of that name"
                         f"{suggest(path, cases)}; shipped cases: {', '.join(sorted(cases)) or 'none installed'}")
    if Path(path).is_dir():
        raise InputError(f"case folder {Path(path)} has no case.toml")
    raise InputError(f"case file {p} does not exist")


def shipped_cases() -> dict[str, Path]:
    """Cases shipped by installed packages: name -> case.toml.

    Two entry-point groups declare them: ``persson.case_folders`` (``name = "package:folder"``, a folder of case
    folders inside an installed package, found without importing the package, which keeps CLI start-up fast) and
    ``persson.cases`` (``name = "module:function"``, a function returning name -> case.toml).
    """
    import importlib.util
    from importlib.metadata import entry_points

    out: dict[str, Path] = {}
    for ep in entry_points(group=CASE_FOLDERS_GROUP):
        try:
            spec = importlib.util.find_spec(ep.module)
            roots = list(spec.submodule_search_locations or ()) if spec is not None else []
        except (ImportError, ValueError):
            continue
        for root in roots:
            folder = Path(root) / (ep.attr or "")
            if folder.is_dir():
                out.update({d.name: d / "case.toml" for d in folder.iterdir() if (d / "case.toml").is_file()})
    for ep in entry_points(group=CASES_GROUP):
        try:
            out.update({str(k): Path(v) for k, v in ep.load()().items()})
        except Exception:  # noqa: BLE001 - a broken plug-in must not hide the others
            continue
    return dict(sorted(out.items()))


# ---------------------------------------------------------------------------------------------------------
#: Relative tolerance within which a case's q1 equals the last q of its PSD table (values written with 6 digits).
_Q_RTOL = 1e-6


def build_surface(tab: dict, base: Path, path: Path):
    """The surface PSD of a ``[surface]`` table (checked by :func:`parse_case`)."""
    import surfaces

    key = next(k for k in ("psd", "profiles", "example") if k in tab)
    if key == "example":
        s = surfaces.example_road()
    elif key == "psd":
        with _key(path, "surface", "psd"):
            s = surfaces.read_psd(_file(base, tab["psd"], path, "surface", "psd"))
    else:
        files = [_file(base, f, path, "surface", "profiles") for f in tab["profiles"]]
        with _key(path, "surface", "read_options"):
            sets = [surfaces.read_profiles(f, **tab.get("read_options", {})) for f in files]
        ps = sets[0] if len(sets) == 1 else surfaces.ProfileSet.concatenate(sets)
        with _key(path, "surface", "psd_options"):
            p1 = ps.psd(**tab.get("psd_options", {}))
        if "unidirectional_deg" in tab:
            s = surfaces.unidirectional(p1, angle_deg=tab["unidirectional_deg"])
        else:
            with _key(path, "surface", "isotropic_options"):
                s = p1.to_isotropic(**tab.get("isotropic_options", {}))
    if "q_rolloff" in tab:
        with _key(path, "surface", "q_rolloff"):
            s = s.with_rolloff(float(tab["q_rolloff"]))
    if "q0" in tab or "q1" in tab:
        q0 = tab.get("q0")
        q1 = tab.get("q1")
        lo, hi = s.q_range
        if q1 is not None and float(q1) > hi * (1 + _Q_RTOL):
            raise InputError(f"{path}: [surface] q1 = {float(q1):.10g} rad/m lies past the PSD's last q = "
                             f"{hi:.10g} rad/m (relative difference {float(q1) / hi - 1:.2g}); nothing is "
                             "extrapolated unless asked: switch on the microtexture effect "
                             "([model] effects = [\"microtexture\"]) to extend the tail")
        if "unidirectional_deg" in tab:
            raise InputError(f"{path}: [surface] q0 and q1 do not apply to a unidirectional surface (its band is "
                             "that of the profiles' 1-D PSD): give psd_options = {{ ... }} or remove them")
        if q1 is not None and float(q1) > hi:
            q1 = hi  # the table's last q written with fewer digits: the same wavevector
        if q0 is not None and lo * (1 - _Q_RTOL) <= float(q0) < lo:
            q0 = lo
        with _key(path, "surface", "q0" if q1 is None else "q1"):
            s = s.with_cutoff(q0=None if q0 is None else float(q0), q1=None if q1 is None else float(q1))
    if "stretch" in tab:
        with _key(path, "surface", "stretch"):
            s = surfaces.stretched(s, ratio=tab["stretch"]["ratio"], angle_deg=tab["stretch"]["angle_deg"])
    return s


def build_material(tab: dict, base: Path, path: Path, *, progress: Callable | None = None,
                   notes: list | None = None):
    """The material of a ``[material]`` table: a master-curve table, DMA isotherms, or the example tread.

    DMA isotherms are shifted by the case's ``wlf`` law or ``shift_factors`` table when given, else by automated
    time-temperature superposition at ``T_ref_C`` (options ``shift_law``, ``Tg_C``, ``wlf_range_C``,
    ``shift_options``, ``fit``); the result is cached by the content of the files and the options.
    """
    import materials

    notes = [] if notes is None else notes
    key = next(k for k in ("master_curve", "dma", "example") if k in tab)
    thermal = None
    if "thermal" in tab:
        with _key(path, "material", "thermal"):
            thermal = materials.Thermal(**tab["thermal"])
    if key == "example":
        m = materials.example_tread()
    elif key == "master_curve":
        m = _master_curve_table(tab, base, path)
    else:
        m = _master_curve_from_dma(tab, base, path, progress, notes)
    if thermal is not None:
        m = _with_thermal(m, thermal)
    if "T_upper_C" in tab:
        m = _with_upper(m, float(tab["T_upper_C"]), path)
    return m


def _master_curve_table(tab: dict, base: Path, path: Path):
    import materials

    f = _file(base, tab["master_curve"], path, "material", "master_curve")
    wlf = _wlf(tab, path)
    kwargs = dict(tab.get("master_curve_options", {}))
    if "shift_factors" in tab:
        kwargs["shift"] = _shift_table(tab, base, path)
    if "fit" in tab:
        kwargs["fit"] = tab["fit"]
    if wlf is None and "shift" not in kwargs:
        raise InputError(f"{path}: [material] master_curve needs wlf = {{ C1 = ..., C2 = ..., T_ref_C = ... }} or "
                         "shift_factors = \"file\"")
    return _call(materials.read_master_curve, path, "master_curve", f, wlf, **kwargs)


def _master_curve_from_dma(tab: dict, base: Path, path: Path, progress, notes: list):
    import materials

    from .cache import cached

    source = _dma_source(tab["dma"], base, path)
    files = _expand_dma(source)
    read_opts = dict(tab.get("dma_options", {}))
    kwargs: dict[str, Any] = {}
    wlf = _wlf(tab, path)
    if wlf is not None:
        # The case gives the compound's WLF law: use it as the shift factors instead of fitting new ones.
        if "T_ref_C" in tab and float(tab["T_ref_C"]) != wlf.T_ref:
            raise InputError(f"{path}: [material] T_ref_C = {tab['T_ref_C']:g} differs from wlf T_ref_C = "
                             f"{wlf.T_ref:g}; the WLF constants hold for their own reference: give one of them")
        T_ref = wlf.T_ref
        kwargs["shift_factors"] = wlf
    else:
        T_ref = float(tab.get("T_ref_C", 20.0))
        if "shift_factors" in tab:
            kwargs["shift_factors"] = _shift_table(tab, base, path)
    for case_key, arg in (("shift_law", "shift_law"), ("Tg_C", "Tg"), ("fit", "fit")):
        if case_key in tab:
            kwargs[arg] = tab[case_key]
    if "wlf_range_C" in tab:
        kwargs["wlf_range"] = tuple(tab["wlf_range_C"])
    kwargs.update(tab.get("shift_options", {}))
    shift_files = [_file(base, tab["shift_factors"], path, "material", "shift_factors")] \
        if "shift_factors" in tab and wlf is None else []
    options = {"T_ref": T_ref, "read": read_opts, "wlf": None if wlf is None else [wlf.C1, wlf.C2, wlf.T_ref],
               **{k: v for k, v in kwargs.items() if k != "shift_factors"}}

    def build():
        with _key(path, "material", "dma"):
            dma = _call(materials.read_dma, path, "dma_options", source, **read_opts)
        _say(progress, f"fitting the master curve of {len(files)} DMA file(s)")
        extra = {"progress": progress} if progress is not None and _accepts(materials.master_curve, "progress") \
            else {}
        return _call(materials.master_curve, path, _material_key(kwargs), dma, T_ref, **kwargs, **extra)

    return cached("master_curve", files + shift_files, options, build, notes=notes, inputs=files)


def _material_key(kwargs: dict) -> str:
    """The case key most likely at fault when ``materials.master_curve`` refuses its arguments."""
    for case_key, arg in (("shift_law", "shift_law"), ("Tg_C", "Tg"), ("wlf_range_C", "wlf_range"),
                          ("fit", "fit")):
        if arg in kwargs:
            return case_key
    return "dma"


def _strain_factors(tab: dict, base: Path, path: Path):
    if "strain_sweeps" not in tab:
        if "strain_options" in tab:
            raise InputError(f"{path}: [material] strain_options is given without strain_sweeps")
        return None
    import materials

    files = _sweep_files(tab["strain_sweeps"], base, path)
    opts = dict(tab.get("strain_options", {}))
    read = _function(materials, "read_strain_sweep", path, "strain_sweeps")
    factors = _function(materials, "strain_factors", path, "strain_sweeps")
    read_opts = {k: v for k, v in opts.items() if _accepts(read, k)}
    fit_opts = {k: v for k, v in opts.items() if k not in read_opts}
    sweeps = [_call(read, path, "strain_sweeps", f, **read_opts) for f in files]
    return _call(factors, path, "strain_options", sweeps, **fit_opts)


def _sweep_files(names: list, base: Path, path: Path) -> list[Path]:
    """The strain-sweep files of ``[material] strain_sweeps``: files, or folders of ``*.csv``, ``*.txt``, ``*.dat``
    files (one sweep or one temperature each, as DMA software exports them)."""
    out: list[Path] = []
    for name in names:
        p = base / name
        if p.is_dir():
            found = sorted(f for f in p.iterdir() if f.is_file() and f.suffix.lower() in (".csv", ".txt", ".dat"))
            if not found:
                raise InputError(f"{path}: [material] strain_sweeps: folder {p} holds no *.csv, *.txt or *.dat "
                                 "strain-sweep files")
            out += found
        else:
            out.append(_file(base, name, path, "material", "strain_sweeps"))
    return out


def _shift_table(tab: dict, base: Path, path: Path):
    import materials

    f = _file(base, tab["shift_factors"], path, "material", "shift_factors")
    read = _function(materials, "read_shift_factors", path, "shift_factors")
    return _call(read, path, "shift_factors", f)


def _wlf(tab: dict, path: Path):
    if "wlf" not in tab:
        return None
    import materials

    with _key(path, "material", "wlf"):
        return materials.WLF.from_mapping(tab["wlf"])


def _dma_source(value: list, base: Path, path: Path):
    """A file, a folder or a list of files (relative to the case) as read_dma takes it."""
    out = []
    for name in value:
        p = base / name
        if not p.exists():
            raise InputError(f"{path}: [material] dma: {p} does not exist (expected a DMA file, a list of files or "
                             "a folder of isotherm files)")
        out.append(p)
    return out[0] if len(out) == 1 else out


def _expand_dma(source) -> list[Path]:
    items = source if isinstance(source, list) else [source]
    out: list[Path] = []
    for p in items:
        if p.is_dir():
            out += sorted(f for f in p.iterdir() if f.is_file() and not f.name.startswith("."))
        else:
            out.append(p)
    return out


def _with_upper(material, T_upper: float, path: Path):
    """``material`` with its shift law handing over to an Arrhenius law above ``T_upper`` (deg C)
    (:func:`materials.with_arrhenius_above`: a WLF law, a tabulated one beyond its table)."""
    import materials

    with _key(path, "material", "T_upper_C"):
        return materials.with_arrhenius_above(material, T_upper)


def _with_thermal(material, thermal):
    import dataclasses

    if dataclasses.is_dataclass(material) and any(f.name == "thermal" for f in dataclasses.fields(material)):
        return dataclasses.replace(material, thermal=thermal)
    if hasattr(material, "with_thermal"):
        return material.with_thermal(thermal)
    raise InputError(f"material {type(material).__name__} does not carry thermal properties")


def _effects(model_tab: dict, path: Path, *, strain=None, base: Path | None = None) -> tuple:
    from .. import effects as fx

    names = model_tab.get("effects", [])
    if strain is not None and "strain_softening" not in names:
        raise InputError(f"{path}: [material] strain_sweeps are used only by the strain_softening effect, which is "
                         "not switched on: add \"strain_softening\" to [model] effects (or remove strain_sweeps)")
    out = []
    for n in names:
        params = dict(model_tab.get(n, {}))
        if n == "strain_softening":
            params = _strain_softening(params, strain, base if base is not None else path.parent, path)
        with _key(path, f"model.{n}", None):
            out.append(fx.get(n, **params))
    return tuple(out)


#: The values of [model.strain_softening] factors that are not file names.
_FACTOR_SOURCES = ("sweeps", "constant")


def _strain_softening(params: dict, strain, base: Path, path: Path) -> dict:
    """The StrainSoftening arguments of ``[model.strain_softening]``: measured factors from ``[material]
    strain_sweeps`` unless ``factors`` says otherwise (``"constant"``, or a factor table ``"file"``); keys that the
    chosen factors would not use are refused."""
    where = f"{path}: [model.strain_softening]"
    given = params.pop("factors", None)
    if given is None:
        source = "sweeps" if strain is not None else "constant"
    elif isinstance(given, str) and given.strip():
        source = given if given in _FACTOR_SOURCES else "file"
    else:
        raise InputError(f"{where} factors: expected \"sweeps\" (the strain sweeps of [material]), \"constant\" "
                         f"(storage_factor, loss_factor) or a factor table file name in quotes, got {given!r}")
    if source == "sweeps":
        if strain is None:
            raise InputError(f"{where} factors = \"sweeps\" needs strain sweeps: [material] strain_sweeps = "
                             "[\"sweep.csv\", ...]")
        params["factors"] = strain
    elif strain is not None:
        instead = "the constant factors" if source == "constant" else f"the factor table {given!r}"
        raise InputError(f"{where} factors = {given!r}: {instead} would replace the strain sweeps of [material] "
                         "strain_sweeps, which would not be used: remove one of the two")
    elif source == "file":
        params["factors"] = _factor_table(base, given, path, "factors")
    measured = source != "constant"
    unused = [k for k in (("storage_factor", "loss_factor") if measured else ("strain_per_slope", "extrapolation"))
              if k in params]
    if unused:
        why = ("a constant factor is not used with measured factors (strain sweeps or a factor table)" if measured
               else "it is used only with measured factors ([material] strain_sweeps or factors = \"file\")")
        raise InputError(f"{where} {unused[0]}: {why}; remove it")
    ext = params.get("extrapolation")
    if isinstance(ext, str) and ext not in _strain_rules():
        params["extrapolation"] = _factor_table(base, ext, path, "extrapolation")
    return params


def _strain_rules() -> tuple:
    from ..effects.strain import RULES

    return RULES


def _factor_table(base: Path, name: str, path: Path, key: str):
    import materials

    f = _file(base, name, path, "model.strain_softening", key)
    with _key(path, "model.strain_softening", key):
        return materials.read_strain_factors(f)


def _assumption_notes(raw: dict, path: Path) -> list[str]:
    """What the case leaves to defaults or switches off without saying so, as notes (and warnings)."""
    import warnings

    from ..errors import PhysicsWarning

    notes = []
    effects = raw.get("model", {}).get("effects", [])
    mat = raw["material"]
    if "flash_temperature" in effects and "thermal" not in mat and "example" not in mat:
        import materials

        t = materials.Thermal()
        notes.append(f"{path.name}: [material] has no thermal table; the flash temperature uses the defaults "
                     f"density = {t.density:g} kg/m^3, specific_heat = {t.specific_heat:g} J/(kg K), conductivity "
                     f"= {t.conductivity:g} W/(m K): give the compound's in [material] thermal = {{ ... }}")
    if "wet" in effects and "adhesion" in effects:
        msg = (f"{path}: [model] effects: wet removes adhesion (no adhesive friction on a wet road), so "
               "mu_adhesion = 0 in every computation of this case (persson friction, sweep); compare and "
               "diagnose use the wet effect for the rows marked wet only")
        notes.append(msg)
        warnings.warn(msg, PhysicsWarning, stacklevel=3)
    return notes


def _speeds(cond: dict, path: Path) -> np.ndarray:
    if "speeds_m_s" in cond:
        v = np.asarray(cond["speeds_m_s"], dtype=float).ravel()
        key = "speeds_m_s"
    else:
        lo, hi, n = cond.get("speed_range_m_s", _DEFAULT_SPEEDS)
        v = np.geomspace(float(lo), float(hi), int(n))
        key = "speed_range_m_s"
    plausible_speed(v, f"{path}: [conditions] {key}", stacklevel=3)
    return v


#: Suffixes of tables (PSD, profiles, DMA, measurements) that are not case files.
_TABLE_SUFFIXES = (".csv", ".txt", ".dat", ".tsv")


def _looks_like_a_table(text: str) -> str:
    """A hint when a file that is not TOML looks like a CSV table (a PSD or profile given instead of a case)."""
    first = next((ln.strip() for ln in text.splitlines() if ln.strip() and not ln.strip().startswith("#")), "")
    if "," in first and "=" not in first and "[" not in first:
        return ("; it looks like a CSV table (first row " + repr(first[:40]) + "): expected a case file (case.toml) "
                "that names its tables, e.g. [surface] psd = \"surface_psd.csv\"")
    return ""


# ---------------------------------------------------------------------------------------------------------
# Rules across keys (the schema checks each key alone).
_ONE_OF = {"surface": ("psd", "profiles", "example"), "material": ("master_curve", "dma", "example")}
#: Keys that only make sense beside one of the alternatives above.
_ONLY_WITH = {
    ("surface", "read_options"): ("profiles",), ("surface", "psd_options"): ("profiles",),
    ("surface", "isotropic_options"): ("profiles",), ("surface", "q_rolloff"): ("psd", "profiles"),
    ("surface", "unidirectional_deg"): ("profiles",),
    ("material", "dma_options"): ("dma",), ("material", "shift_law"): ("dma",), ("material", "Tg_C"): ("dma",),
    ("material", "wlf_range_C"): ("dma",), ("material", "shift_options"): ("dma",),
    ("material", "T_ref_C"): ("dma",), ("material", "master_curve_options"): ("master_curve",),
    ("material", "shift_factors"): ("dma", "master_curve"), ("material", "fit"): ("dma", "master_curve"),
    ("material", "wlf"): ("dma", "master_curve"),
}


def _check_combinations(raw: dict, path: Path) -> None:
    for section, alternatives in _ONE_OF.items():
        tab = raw[section]
        given = [k for k in alternatives if k in tab]
        if len(given) != 1:
            raise InputError(f"{path}: [{section}] needs exactly one of {', '.join(alternatives)} (got "
                             f"{', '.join(given) or 'none'})")
    for (section, key), needs in _ONLY_WITH.items():
        tab = raw.get(section, {})
        if key in tab and not any(n in tab for n in needs):
            raise InputError(f"{path}: [{section}] {key} applies only with {' or '.join(needs)}; it would be "
                             "ignored here: remove it")
    mat = raw["material"]
    if "wlf" in mat and "shift_factors" in mat:
        raise InputError(f"{path}: [material] give wlf or shift_factors, not both")
    surf = raw["surface"]
    if "stretch" in surf and "unidirectional_deg" in surf:
        raise InputError(f"{path}: [surface] give stretch or unidirectional_deg, not both")
    if "unidirectional_deg" in surf and "isotropic_options" in surf:
        raise InputError(f"{path}: [surface] isotropic_options do not apply to a unidirectional surface (no 1-D -> "
                         "2-D conversion): remove them")
    cond = raw.get("conditions", {})
    if "speeds_m_s" in cond and "speed_range_m_s" in cond:
        raise InputError(f"{path}: [conditions] give speeds_m_s or speed_range_m_s, not both")


def _input_files(raw: dict, path: Path) -> list[Path]:
    """Every file the case names (checked to exist), in order."""
    base = path.parent
    out: list[Path] = []
    surf, mat = raw["surface"], raw["material"]
    if "psd" in surf:
        out.append(_file(base, surf["psd"], path, "surface", "psd"))
    for f in surf.get("profiles", []):
        out.append(_file(base, f, path, "surface", "profiles"))
    if "master_curve" in mat:
        out.append(_file(base, mat["master_curve"], path, "material", "master_curve"))
    if "dma" in mat:
        out += _expand_dma(_dma_source(mat["dma"], base, path))
    if "shift_factors" in mat:
        out.append(_file(base, mat["shift_factors"], path, "material", "shift_factors"))
    out += _sweep_files(mat.get("strain_sweeps", []), base, path)
    soft = raw.get("model", {}).get("strain_softening", {})
    for key in ("factors", "extrapolation"):
        value = soft.get(key)
        if isinstance(value, str) and value not in _FACTOR_SOURCES + _strain_rules():
            out.append(_file(base, value, path, "model.strain_softening", key))
    if "file" in raw.get("measurements", {}):
        out.append(_file(base, raw["measurements"]["file"], path, "measurements", "file"))
    elif "measurements" in raw:
        raise InputError(f"{path}: [measurements] needs file = \"...\"")
    return out


def _file(base: Path, name: str, path: Path, section: str, key: str) -> Path:
    f = base / name
    if not f.is_file():
        what = "is a folder; expected a file" if f.is_dir() else "does not exist"
        raise InputError(f"{path}: [{section}] {key}: file {f} {what}")
    return f


class _key:
    """Context: a ValueError or TypeError raised while using one key is re-raised naming the file and key."""

    def __init__(self, path: Path, section: str, key: str | None):
        self.where = f"{path}: [{section}]" + (f" {key}" if key else "")
        self.path = str(path)

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        if exc_type is None or not issubclass(exc_type, (ValueError, TypeError)):
            return False
        text = str(exc)
        if issubclass(exc_type, ValueError) and self.path in text:
            return False  # already names the file
        raise InputError(f"{self.where}: {text}") from None


def _call(fn, path: Path, key: str, *args, **kwargs):
    """``fn(*args, **kwargs)``; a refused keyword or bad value becomes an InputError naming the case key."""
    section = "material"
    for name in kwargs:
        if not _accepts(fn, name):
            raise InputError(f"{path}: [{section}] {key}: this version of the materials package does not accept "
                             f"{name!r} in {fn.__name__}()")
    with _key(path, section, key):
        return fn(*args, **kwargs)


def _function(module, name: str, path: Path, key: str):
    fn = getattr(module, name, None)
    if fn is None:
        raise InputError(f"{path}: [material] {key}: this version of the materials package has no {name}()")
    return fn


def _accepts(fn, name: str) -> bool:
    try:
        params = inspect.signature(fn).parameters
    except (TypeError, ValueError):  # pragma: no cover
        return True
    return name in params or any(p.kind is p.VAR_KEYWORD for p in params.values())


def _say(progress, text: str) -> None:
    if progress is not None:
        progress(text)
