"""Validation cases: a ``case.toml`` (model, contact, measurements) loaded in one call.

Built on :func:`persson.case.read_case`. Keys this module reads beyond it:

``[model] fit = ["adhesion.tau_f0", ...]``
    baseline parameters fitted to the measurements by :func:`validation.diagnose` (``<effect>.<parameter>`` of an
    effect switched on in the baseline, or ``gamma``); default none.
``[measurements] file = "measurements.csv"``
    required here (the file is read by :func:`validation.read_measurements`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from .errors import InputError
from .measurements import Measurements, read_measurements

__all__ = ["Case", "load_case", "shipped_cases", "case_path", "parse_fit_names"]

_CASES_DIR = Path(__file__).resolve().parent / "cases"


@dataclass(frozen=True, eq=False)
class Case:
    """A loaded validation case.

    Attributes
    ----------
    name : str
    path : Path
        The ``case.toml``.
    model : persson.Model
        The baseline model (surface, material, baseline effects).
    measurements : Measurements
        Carrying the case's contact (``measurements.contact``), so that
        ``validation.compare(case.model, case.measurements)`` handles slip rows.
    contact : persson.slip.Contact or None
        Brush model of the wheel (None when the file has no ``[contact]`` table).
    fit : tuple of str
        Baseline parameters to fit (``[model] fit``).
    spec : persson.case.CaseSpec
        The parsed case file (``spec.raw`` is the whole TOML).
    rig : validation.rigs.Rig or None
        The friction trailer of the ``[rig]`` table (None without one), for :func:`validation.rigs.reduce`.
    """

    name: str
    path: Path
    model: object
    measurements: Measurements
    contact: object = None
    fit: tuple = ()
    spec: object = field(default=None, repr=False)
    rig: object = None

    def __repr__(self) -> str:
        return (f"Case({self.name!r}, path={str(self.path)!r}, effects={list(self.model.effect_names)}, "
                f"fit={list(self.fit)}, {self.measurements.describe()}"
                + (", with contact" if self.contact is not None else "") + ")")

    @property
    def folder(self) -> Path:
        """The folder of the case file."""
        return self.path.parent


def load_case(path, *, progress=None) -> Case:
    """Read a ``case.toml`` (or its folder, or the name of a shipped case) with its measurements.

    Parameters
    ----------
    path : str or path-like
        The case file, its folder, or the name of a case shipped in ``validation/cases`` (e.g. ``"example"``).
    progress : callable, optional
        Called with short status texts while slow parts run (see :mod:`persson.progress`).

    Returns
    -------
    Case

    Raises
    ------
    InputError
        The case file or a file it names is missing or malformed (the message names the file and the key), the
        measurements are bad (file, line, column), or rows with slip < 1 have no ``[contact]`` table.
    """
    from persson.case import read_case

    p = Path(path)
    if not p.exists() and not p.suffix and (_CASES_DIR / str(path) / "case.toml").is_file():
        p = _CASES_DIR / str(path)
    if p.is_dir():
        p = p / "case.toml"
    try:
        spec = read_case(p, progress=progress)
    except InputError:
        raise
    except ValueError as exc:  # persson / surfaces / materials InputError (all ValueError subclasses)
        raise InputError(str(exc) if str(p) in str(exc) else f"{p}: {exc}") from None
    if spec.measurements is None:
        raise InputError(f"{p}: no [measurements] table; add [measurements] file = \"measurements.csv\"")
    meas = read_measurements(spec.measurements)
    contact = None
    if spec.contact:
        try:
            contact = spec.contact_model()
        except ValueError as exc:
            raise InputError(f"{p}: [contact]: {exc}") from None
    if contact is None and meas.has_slip_rows:
        raise InputError(f"{p}: {spec.measurements} has rows with slip < 1, which need the brush model: add a "
                         "[contact] table (length_m, width_m, stiffness_Pa_per_m)")
    if contact is not None:
        meas = meas.with_contact(contact)
    fit = parse_fit_names(spec.raw.get("model", {}).get("fit", []), spec.model, str(p))
    rig = None
    if "rig" in spec.raw:
        from .rigs import rig_from_dict

        rig = rig_from_dict(spec.raw["rig"], source=f"{p}: [rig]")
    return Case(name=spec.name, path=p, model=spec.model, measurements=meas, contact=contact, fit=fit, spec=spec,
                rig=rig)


def parse_fit_names(names, model, where: str = "fit") -> tuple[str, ...]:
    """Check ``["effect.parameter", ...]`` against the model's effects; returns the names as a tuple."""
    if isinstance(names, str):
        names = [names]
    if not isinstance(names, (list, tuple)) or not all(isinstance(n, str) for n in names):
        raise InputError(f"{where}: [model] fit must be a list of \"effect.parameter\" names, got {names!r}")
    out = []
    for n in names:
        if n == "gamma":
            out.append(n)
            continue
        eff, dot, par = n.partition(".")
        if not dot:
            raise InputError(f"{where}: [model] fit: {n!r} is not of the form \"effect.parameter\" (or gamma)")
        if eff == "contact":
            from .fitting import CONTACT_PARAMETERS

            if par not in CONTACT_PARAMETERS:
                raise InputError(f"{where}: [model] fit: {n!r}: the contact has no fittable parameter {par!r} "
                                 f"(fittable: {sorted(CONTACT_PARAMETERS)})")
            out.append(n)
            continue
        if eff not in model.effect_names:
            raise InputError(f"{where}: [model] fit: {n!r} names the effect {eff!r}, which is not in the baseline "
                             f"(effects = {list(model.effect_names)})")
        e = model.effect(eff)
        documented = [p.name for p in e.parameters]
        if par not in documented:
            raise InputError(f"{where}: [model] fit: {n!r}: {eff} has no fittable parameter {par!r} "
                             f"(documented: {documented})")
        out.append(n)
    if len(set(out)) != len(out):
        raise InputError(f"{where}: [model] fit lists a parameter twice: {out}")
    return tuple(out)


def shipped_cases() -> dict[str, Path]:
    """The validation cases shipped with the package: name -> case.toml."""
    if not _CASES_DIR.is_dir():
        return {}
    return {d.name: d / "case.toml" for d in sorted(_CASES_DIR.iterdir()) if (d / "case.toml").is_file()}


def case_path(name: str) -> Path:
    """The ``case.toml`` of the shipped case ``name``."""
    cases = shipped_cases()
    if name not in cases:
        raise InputError(f"no shipped case named {name!r}; shipped: {sorted(cases)}")
    return cases[name]
