r"""Contact mechanics of Persson's theory on its own: area, separation, elastic energy, penetration depth.

:func:`contact` answers the contact-mechanics questions for a rough hard surface pressed against a rubber (or
any elastic solid) at one or many nominal pressures:

* the area of real contact :math:`A/A_0 = P(q_1)` and its scale dependence P(q) (Persson, J. Chem. Phys. 115,
  3840 (2001)), optionally corrected (:mod:`persson.contact.corrections`);
* the mean interfacial separation :math:`\bar u` (Persson, Phys. Rev. Lett. 99, 125502 (2007); Yang &
  Persson, J. Phys.: Condens. Matter 20, 215214 (2008));
* the elastic energy stored per unit nominal area (Yang & Persson 2008)

  .. math:: \frac{U_{el}}{A_0} = \frac{E^*}{4}\int d^2q\, q\, C(q)\, W(q)
            = \frac{\pi E^*}{2}\int_{q_0}^{q_1} dq\, q^2 C(q)\, P(q)\left[\gamma + (1-\gamma) P^2(q)\right],

  which tends to :math:`E^* m_2/4` (:math:`m_2 = 2\pi\int q^2 C dq`) at full contact, and is tied to the
  separation by :math:`\bar u(\sigma_0) = \int_{\sigma_0}^\infty dp\, p^{-1}\, d(U_{el}/A_0)/dp` (Persson 2007);
* the penetration depth of the asperities into the rubber, by the definitions of
  :func:`persson.contact.separation.penetration_depth`;
* the thickness of the deformed layer (:func:`persson.contact.separation.excited_layer_thickness`).

Two ways in. **Elastic**: give the effective modulus :math:`E^* = E/(1-\nu^2)` as a number; everything is then
computed here, with :math:`G(q) = (\pi/4)(E^*/\sigma_0)^2\int_{q_0}^q q'^3 C dq'` integrated exactly for a PSD
that is a power law between nodes. **Viscoelastic**: give a material and a sliding speed; the friction engine
(:class:`persson.Model`) supplies G(q) with the modulus at the excitation frequencies, and the elastic energy
uses the scale-dependent effective modulus that this G implies,
:math:`E^*_q = \sigma_0 [dG/dq\,/\,((\pi/4) q^3 C)]^{1/2}` (exact for an elastic solid, a definition for a
viscoelastic one).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from frictioncite import citations_of, doi

from . import corrections, separation
from .._checks import (UnitWarning, finite_array, number, plausible_modulus, plausible_pressure, plausible_speed,
                       plausible_temperature, unit_slip_notes)
from ..errors import InputError
from ..notes import Note, kinds

__all__ = ["contact", "ContactResult"]


@doi("10.1063/1.1388626", "10.1103/PhysRevLett.99.125502", "10.1088/0953-8984/20/21/215214")
def contact(surface, material_or_Estar, pressure, *, speed=None, temperature: float = 20.0, gamma: float = 0.5,
            nu: float = 0.5, correction: str | None = None, gap_correction: str = "area",
            penetration: str = "persson", n_sigma: float = 3.0, q_per_decade: int = 32,
            grid=None, direction_deg: float | None = None) -> "ContactResult":
    r"""Contact area, separation, elastic energy and penetration depth at the nominal pressure(s) ``pressure``.

    Parameters
    ----------
    surface : surfaces.SelfAffine or surfaces.PSD or any object with ``C(q)`` and ``q_range``
        The hard rough surface (isotropic 2D PSD, Persson convention); integrals run over ``q_range``.
    material_or_Estar : float or material
        A number is the effective modulus :math:`E^* = E/(1-\nu^2)`, Pa (elastic contact; ``nu`` is then not
        used). A material (``E(omega, T)``, e.g. :class:`materials.MasterCurve`) needs ``speed``.
    pressure : float or array_like
        Nominal pressure(s) :math:`\sigma_0`, Pa, > 0.
    speed : float, optional
        Sliding speed, m/s (viscoelastic material only).
    temperature : float
        Background temperature, deg C (viscoelastic material only).
    gamma : float
        Parameter of :math:`S = \gamma + (1-\gamma)P^2` (Yang & Persson 2008), in the energy, the separation and
        the corrections; 0 <= gamma <= 1 (default 0.5, as :class:`persson.Model`).
    nu : float
        Poisson ratio of the material (viscoelastic path), 0 <= nu <= 0.5.
    correction : {None, "yang-persson", "xu2024", "wang-muser"}
        Area correction (:mod:`persson.contact.corrections`); None (default) is uncorrected Persson theory.
    gap_correction : {"area", "persson", "xu2024-hybrid", "gfmd-gap"} or None
        Law of the elastic energy and the separation (:mod:`persson.contact.corrections`): ``"area"`` (default)
        follows the area law, ``"persson"`` (or None) is uncorrected whatever the area, ``"gfmd-gap"`` is fitted
        to GFMD mean gaps.
    penetration : {"persson", "load-weighted", "kluppel"}
        Definition reported as ``penetration_depth`` (every one is in ``penetration_depths``):
        :func:`persson.contact.separation.penetration_depth`.
    n_sigma : float
        Height of the asperity tops in units of h_rms for the "persson" penetration depth (default 3).
    q_per_decade : int
        Wavevector nodes per decade of the elastic computation (the surface's own nodes and kinks are added).
    grid : persson.GridSettings, optional
        Numerical settings of the engine (viscoelastic path).
    direction_deg : float, optional
        Sliding direction, degrees from the x axis of an anisotropic surface (viscoelastic path; default 0). An
        anisotropic surface pressed without sliding (the elastic path) has the contact of its angular mean
        :math:`\bar C(q)` exactly (Persson's G(q) at rest depends on nothing else), so it takes no direction.

    Returns
    -------
    ContactResult
        Scalar outputs are floats for a scalar ``pressure``, else arrays per pressure.

    Examples
    --------
    >>> import surfaces, persson
    >>> s = surfaces.SelfAffine(hurst=0.8, q0=1e4, q1=1e6, rms_slope=0.5)
    >>> r = persson.contact(s, 1e6, 1e3)           # E* = 1 MPa, sigma0 = 1 kPa
    >>> round(r.contact_area / (8 / 3.141592653589793) ** 0.5 / (1e3 / 1e6 / 0.5), 4)
    1.0
    """
    correction, gamma = corrections.check_correction(correction, gamma)
    gap = corrections.check_gap_correction(gap_correction, correction, gamma)
    if penetration not in separation.PENETRATION_DEFINITIONS:
        raise InputError(f"penetration: expected one of {list(separation.PENETRATION_DEFINITIONS)}, "
                         f"got {penetration!r}")
    n_sigma = number(n_sigma, "n_sigma")
    if n_sigma <= 0:
        raise InputError(f"n_sigma: expected a number of standard deviations > 0, got {n_sigma:g}")
    p, scalar = _pressures(pressure)
    _check_surface(surface)
    plausible_pressure(p, "pressure", stacklevel=3)  # the unit checks of Model.friction: MPa typed as Pa warns
    if isinstance(material_or_Estar, (int, float, np.integer, np.floating)) and not isinstance(material_or_Estar,
                                                                                                bool):
        if speed is not None or direction_deg is not None:
            name = "speed" if speed is not None else "direction_deg"
            raise InputError(f"{name}: an elastic contact (material_or_Estar given as E*, a number) takes no "
                             f"{'speed' if speed is not None else 'sliding direction'}; pass a viscoelastic "
                             "material to use a sliding speed (and direction)")
        Es = number(material_or_Estar, "material_or_Estar")
        if Es <= 0:
            raise InputError(f"material_or_Estar: expected an effective modulus E* > 0 Pa, got {Es:g}")
        plausible_modulus(Es, "material_or_Estar (E*)", stacklevel=3)
        core = _elastic(surface, Es, p, gamma, correction, gap, q_per_decade)
    elif hasattr(material_or_Estar, "E"):
        if speed is None:
            raise InputError("speed: a viscoelastic material needs a sliding speed in m/s (or give the effective "
                             "modulus E* as a number for an elastic contact)")
        v = number(speed, "speed")
        if v <= 0:
            raise InputError(f"speed: expected a sliding speed > 0 m/s, got {v:g}")
        plausible_speed(v, "speed", stacklevel=3)
        plausible_temperature(number(temperature, "temperature"), "temperature", stacklevel=3)
        core = _viscoelastic(surface, material_or_Estar, p, v, number(temperature, "temperature"), nu, gamma,
                             correction, gap, grid, direction_deg)
    else:
        raise InputError(f"material_or_Estar: expected E* in Pa (a number) or a material with E(omega, T), "
                         f"got {material_or_Estar!r}")

    notes = list(core["notes"])
    for msg in unit_slip_notes(surface, (), core["P"][:, -1]):  # full contact on a road: a unit slip
        notes.append(msg)
        warnings.warn(msg, UnitWarning, stacklevel=2)
    if correction is not None and gap == "area":
        notes.append(f"the separation and the elastic energy follow the {correction!r} area: at small loads they are "
                     "further from exact solutions than uncorrected theory (GFMD mean gap +57 % at p/E* = 1e-4, "
                     "against +29 %); gap_correction='gfmd-gap' is within 7 % of GFMD up to p/E* = 0.025")
    depths = {name: separation.penetration_depth(core["u_bar"], core["hrms"], definition=name, n_sigma=n_sigma,
                                                 energy_per_load=core["U"] / p)
              for name in separation.PENETRATION_DEFINITIONS}
    cites = citations_of(contact, corrections.citations(correction, gap), separation.mean_separation,
                         separation.excited_layer_thickness, surface,
                         separation.penetration_depth if penetration == "kluppel" else ())
    out = (lambda a: float(a[0])) if scalar else (lambda a: a)
    return ContactResult(
        pressure=out(p), E_star=core["E_star"], speed=None if speed is None else float(speed),
        temperature=None if speed is None else float(temperature), gamma=gamma, correction=correction,
        contact_area=out(core["P"][:, -1]), mean_separation=out(core["u_bar"]),
        elastic_energy=out(core["U"]), penetration_depth=out(depths[penetration]), penetration=penetration,
        n_sigma=n_sigma, penetration_depths={k: out(v) for k, v in depths.items()},
        excited_layer_thickness=out(core["layer"]), excited_layer_weight=core["layer_weight"],
        q=core["q"], area_q=core["P"], G_q=core["G"], hrms=core["hrms"], rms_slope=core["slope"],
        notes=tuple(notes), citations=cites, scalar=scalar, gap_correction=gap)


@dataclass(frozen=True, eq=False)
class ContactResult:
    """Contact mechanics per nominal pressure (see :func:`contact`).

    Scalar outputs have the shape of the ``pressure`` argument (floats for a scalar); per-scale arrays have
    shape (n_pressure, n_q).

    Attributes
    ----------
    pressure : float or ndarray
        Nominal pressures sigma0, Pa.
    E_star : float or None
        Effective modulus E/(1-nu^2), Pa, of an elastic contact (None on the viscoelastic path).
    speed, temperature : float or None
        Sliding speed (m/s) and background temperature (deg C) of a viscoelastic contact.
    gamma : float
        Parameter of S = gamma + (1-gamma) P^2.
    correction : str or None
        Area correction used (None: uncorrected Persson theory).
    gap_correction : str
        Law of the elastic energy and the separation (``"area"``: the area law's).
    contact_area : float or ndarray
        Real contact area ratio A/A0 = P(q1).
    mean_separation : float or ndarray
        Mean interfacial separation u_bar, m.
    elastic_energy : float or ndarray
        Elastic energy stored per unit nominal area U_el/A0, J/m^2.
    penetration_depth : float or ndarray
        Penetration depth by the definition ``penetration``, m.
    penetration : str
        The definition of ``penetration_depth`` ("persson", "load-weighted" or "kluppel").
    n_sigma : float
        Height of the asperity tops in h_rms for the "persson" depth.
    penetration_depths : dict
        Every definition's depth, m, by name.
    excited_layer_thickness : float or ndarray
        Mean depth 1/q of the deformation, weighted by ``excited_layer_weight``, m.
    excited_layer_weight : str
        "elastic energy" (elastic contact) or "dissipation" (viscoelastic: the friction engine's excited layer).
    q : ndarray (n_q,)
        Wavevector nodes, rad/m.
    area_q, G_q : ndarray (n_pressure, n_q)
        P(q) = A(q)/A0 (corrected when ``correction`` is set) and Persson's G(q).
    hrms, rms_slope : float
        RMS height (m) and rms slope of the surface over its support.
    notes : tuple of str
        Facts a reader must know (e.g. an extrapolated PSD tail).
    citations : tuple of str
        References (DOIs) of the physics used.
    """

    pressure: float | np.ndarray
    E_star: float | None
    speed: float | None
    temperature: float | None
    gamma: float
    correction: str | None
    contact_area: float | np.ndarray
    mean_separation: float | np.ndarray
    elastic_energy: float | np.ndarray
    penetration_depth: float | np.ndarray
    penetration: str
    n_sigma: float
    penetration_depths: dict
    excited_layer_thickness: float | np.ndarray
    excited_layer_weight: str
    q: np.ndarray
    area_q: np.ndarray
    G_q: np.ndarray
    hrms: float
    rms_slope: float
    notes: tuple = ()
    citations: tuple = ()
    scalar: bool = False
    gap_correction: str = "area"

    def __repr__(self) -> str:
        p = np.atleast_1d(self.pressure)
        a = np.atleast_1d(self.contact_area)
        u = np.atleast_1d(self.mean_separation)
        how = (f"E*={self.E_star:.4g} Pa" if self.E_star is not None
               else f"v={self.speed:g} m/s, T={self.temperature:g} C")
        rng = (lambda x, f: f"{f(x.min())}" if x.size == 1 else f"{f(x.min())}-{f(x.max())}")
        return (f"ContactResult({p.size} pressure{'s' if p.size > 1 else ''} {rng(p, lambda x: f'{x:.3g}')} Pa, "
                f"{how}, A/A0 {rng(a, lambda x: f'{x:.3g}')}, u_bar {rng(u, lambda x: f'{x:.3g}')} m, "
                f"correction={self.correction}, gap_correction={self.gap_correction})")

    @property
    def note_kinds(self) -> tuple:
        """The kind of every note (:data:`persson.notes.KINDS`; None for a plain-text note)."""
        return kinds(self.notes)

    def as_table(self) -> dict[str, np.ndarray]:
        """Columns per pressure: ``pressure_Pa, contact_area, mean_separation_m, elastic_energy_J_m2,
        penetration_depth_m, penetration_<definition>_m..., excited_layer_thickness_m``."""
        cols = {
            "pressure_Pa": np.atleast_1d(self.pressure),
            "contact_area": np.atleast_1d(self.contact_area),
            "mean_separation_m": np.atleast_1d(self.mean_separation),
            "elastic_energy_J_m2": np.atleast_1d(self.elastic_energy),
            "penetration_depth_m": np.atleast_1d(self.penetration_depth),
        }
        for name, d in self.penetration_depths.items():
            cols[f"penetration_{name.replace('-', '_')}_m"] = np.atleast_1d(d)
        cols["excited_layer_thickness_m"] = np.atleast_1d(self.excited_layer_thickness)
        return cols


# ---------------------------------------------------------------------------------------------------------
def _elastic(surface, Es: float, p: np.ndarray, gamma: float, correction, gap, q_per_decade) -> dict:
    q = _nodes(surface, q_per_decade)
    C = _psd_on(surface, q)
    m3 = np.concatenate([[0.0], np.cumsum(separation.segment_moments(q, C, 3))])
    G = (math.pi / 4.0) * (Es / p[:, None]) ** 2 * m3[None, :]
    P = corrections.corrected_area(G, correction, gamma)
    u_bar = separation.mean_separation(q, C, G, gamma, correction=correction, gap_correction=gap)

    def w_of(g):
        return corrections.energy_weight(g, correction, gamma, gap)

    # U/A0 = (pi E*/2) int q^2 C W dq = (pi E*/2) int W(G) 2 s ds / q; W = 1 where G < 1e-4 (s < s_lo)
    energy = separation.integral_over_s(q, C, G, lambda g, s, qq: w_of(g) * 2.0 * s,
                                        below=lambda s_lo, q_lo: separation.moment_from_start(q, C, q_lo, 2))
    U = 0.5 * math.pi * Es * energy
    # the layer deformed: the energy-weighted mean of 1/q, int q C W dq / int q^2 C W dq
    layer = separation.integral_over_s(q, C, G, lambda g, s, qq: w_of(g) * 2.0 * s / qq,
                                       below=lambda s_lo, q_lo: separation.moment_from_start(q, C, q_lo, 1)) / energy
    return dict(q=q, G=G, P=P, u_bar=u_bar, U=U, layer=layer, layer_weight="elastic energy", E_star=Es,
                hrms=_hrms(surface, q, C), slope=_slope(surface, q, C), notes=_notes(surface))


def _viscoelastic(surface, material, p, v, T, nu, gamma, correction, gap, grid, direction_deg=None) -> dict:
    from ..engine.model import Model
    from ..engine.quadrature import separation_moments

    kwargs = {} if grid is None else {"grid": grid}
    model = Model(surface, material, nu=nu, gamma=gamma, **kwargs)
    if direction_deg is not None and np.ndim(direction_deg) != 0:
        raise InputError(f"direction_deg: expected one sliding direction in degrees, got {direction_deg!r}")
    r = model.friction(np.full(p.size, v), temperature=T, pressure=p, direction_deg=direction_deg)
    q = np.asarray(r.q, dtype=float)
    G = np.atleast_2d(r.G_q)
    C = _psd_on(surface, q)
    P = np.atleast_2d(r.area_q) if correction is None else corrections.corrected_area(G, correction, gamma)
    s = separation_moments(surface, q)
    if correction is None and gap in ("area", "persson"):
        u_bar = np.atleast_1d(r.mean_separation)
    else:
        u_bar = separation.mean_separation(q, C, G, gamma, correction=correction, gap_correction=gap, s=s)
    U = p * separation.elastic_energy_per_load(q, C, G, gamma, correction=correction, gap_correction=gap, s=s)
    return dict(q=q, G=G, P=P, u_bar=u_bar, U=U, layer=np.atleast_1d(r.excited_layer_thickness),
                layer_weight="dissipation", E_star=None, hrms=_hrms(surface, q, C), slope=_slope(surface, q, C),
                notes=tuple(r.notes))


def _pressures(pressure) -> tuple[np.ndarray, bool]:
    p = finite_array(pressure, "pressure")
    if p.ndim > 1:
        raise InputError(f"pressure: expected a number or a 1-D array of pressures, got shape {p.shape}")
    if np.any(p <= 0):
        i = int(np.argmax(p.ravel() <= 0))
        raise InputError(f"pressure: expected nominal pressures > 0 Pa, got {p.ravel()[i]:g}"
                         + (f" at index {i}" if p.ndim else ""))
    return np.atleast_1d(p).astype(float), p.ndim == 0


def _check_surface(surface) -> None:
    if not (hasattr(surface, "C") and hasattr(surface, "q_range")):
        raise InputError("surface: expected a PSD object with C(q) and q_range (e.g. surfaces.SelfAffine)")
    lo, hi = (float(x) for x in surface.q_range)
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise InputError(f"surface: expected 0 < q0 < q1, got q_range = ({lo:g}, {hi:g}) rad/m")


def _nodes(surface, per_decade) -> np.ndarray:
    """Log-uniform nodes over the support plus the surface's own nodes (a table) and kinks (a roll-off)."""
    if isinstance(per_decade, bool) or not isinstance(per_decade, (int, np.integer)) or per_decade < 4:
        raise InputError(f"q_per_decade: expected an integer >= 4, got {per_decade!r}")
    lo, hi = (float(x) for x in surface.q_range)
    n = max(2, int(math.ceil(per_decade * math.log10(hi / lo))) + 1)
    q = np.geomspace(lo, hi, n)
    extra = [np.atleast_1d(np.asarray(getattr(surface, "q", []), dtype=float))]
    for name in ("q0", "q_rolloff"):
        x = getattr(surface, name, None)
        if isinstance(x, (int, float)) and lo < x < hi:
            extra.append(np.array([float(x)]))
    q = np.union1d(q, np.concatenate(extra))
    q = q[(q >= lo) & (q <= hi)]
    # drop nodes closer than 1e-9 in ln q (a table node next to a grid node)
    keep = np.concatenate([[True], np.diff(np.log(q)) > 1e-9])
    q = q[keep]
    if q[-1] < hi:  # the end node was the one dropped: put it back in place of its neighbour
        q[-1] = hi
    return q


def _psd_on(surface, q) -> np.ndarray:
    C = np.asarray(surface.C(q), dtype=float)
    bad = ~np.isfinite(C) | (C <= 0)
    if np.any(bad):
        raise InputError(f"surface: C(q) must be finite and > 0 on its support, got {C[bad][0]!r} at "
                         f"q = {q[bad][0]:g} rad/m")
    return C


def _hrms(surface, q, C) -> float:
    """The surface's own (exact) rms height when it has one, else the moment of the nodes."""
    if callable(getattr(surface, "hrms", None)):
        return float(surface.hrms())
    return math.sqrt(2.0 * math.pi * float(np.sum(separation.segment_moments(q, C, 1))))


def _slope(surface, q, C) -> float:
    if callable(getattr(surface, "rms_slope", None)):
        return float(surface.rms_slope())
    return math.sqrt(2.0 * math.pi * float(np.sum(separation.segment_moments(q, C, 3))))


def _notes(surface) -> tuple[str, ...]:
    out = ()
    if getattr(surface, "extrapolated", False):
        q_r = getattr(surface, "q_r", None)
        out = (Note(f"PSD tail extrapolated past q_r = {q_r:.4g} rad/m" if q_r else "PSD tail extrapolated",
                    "extrapolated"),)
    if getattr(surface, "is_anisotropic", False):
        out += (Note("anisotropic surface pressed without sliding: its contact is that of the angular mean of its PSD",
                     "assumed"),)
    return out
