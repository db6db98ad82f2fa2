r"""The tread on the road, step 2: time march of the patterned tread over road profiles; maps and rankings.

The element tool presented in "Tire/pavement friction: presentation of a comprehensive physical tool through
advanced contact modelling" (its equation numbers are used throughout this package; the element model of M. Kane and
co-workers, with water: Kane, Do, Cerezo, Rado & Khelifi, Int. J. Pavement Eng. (2017),
doi:10.1080/10298436.2017.1369776):

1. step 1, the static footprint (:class:`persson.tread.Tire`): length L, width, the pressure's shape along L;
2. the tread is a row (one per road profile: a 2-D grid) of elements of spacing :math:`\Delta x_e`, each a Kelvin
   unit with, per unit area, :math:`k = E'(\omega, T)/h` and :math:`c = E''(\omega, T)/(\omega h)` (h the tread
   depth, :math:`\omega = v_s/\Delta x` the rate at which road elements pass under a sliding element), so that
   :math:`k + i\omega c` is the complex stiffness :math:`E^*/h` of the rubber layer at that frequency; grooves
   take elements away; the belt carries the footprint's pressure shape (the static pressure on a smooth road);
3. the road (:mod:`persson.tread.road`): road elements and their slope angles;
4. time march (:mod:`persson.tread.kernels`): the material moves through the footprint at (1 - s)V and slides
   over the road at sV (Eq. 6); normal forces from the Kelvin units (Eq. 3 out of contact); the base
   height solved at every step for the load balance (Eq. 4); tangential force of a sliding element, Eq. 2;
   :math:`\mu(t) = \sum T/W` (Eq. 5). With a finite slip stiffness (the default) an element entering the
   footprint adheres, its shear (belt and tread, the brush model) growing with the sliding distance, until its
   force reaches the friction cone of Eq. 2, then slides until it leaves the footprint; the shear acts on the
   force, not on the element's path over the road. With ``slip_stiffness=None`` every contacting element slides
   (the paper's equations as written);
5. :math:`\mu_{loc}` (:mod:`persson.tread.local`): the Persson engine on the scales finer than the road elements;
6. wet (:mod:`persson.tread.wet`): the pseudo-hydrodynamic bearing of Eq. 7 takes :math:`W_h` off the asperities;
   no adhesion in :math:`\mu_{loc}`.

Steady friction: the time average of :math:`\mu(t)` after the transient (the time the road needs to move one
footprint length under the tyre plus five relaxation times C/K of the elements), with its standard error from
block averages (Flyvbjerg & Petersen, J. Chem. Phys. 91, 461 (1989)).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from frictioncite import citations_of, doi

from .._checks import finite_array, number, plausible_temperature, positive
from ..errors import AccuracyWarning, InputError, PhysicsWarning
from . import kernels
from .local import LocalFriction, constant_friction, local_friction
from .results import Ranking, SlipMap, TreadResult
from .road import TOOL_PAPER, Road, as_road, contact_surface
from .tire import Tire
from .wet import KANE_2017, Water, wet_state

__all__ = ["simulate", "slip_map", "rank_surfaces", "DEFAULT_SLIPS", "TOOL_PAPER", "FLYVBJERG_1989"]

#: H. Flyvbjerg, H. G. Petersen, Error estimates on averages of correlated data, J. Chem. Phys. 91, 461 (1989).
FLYVBJERG_1989 = "10.1063/1.457480"
#: C. Spearman (1904) and M. G. Kendall (1938): the rank correlations of :func:`rank_surfaces`.
SPEARMAN_1904 = "10.2307/1412159"
KENDALL_1938 = "10.1093/biomet/30.1-2.81"

#: Slip ratios of a default map: dense below 0.3, where the ABS peak lies.
DEFAULT_SLIPS = (0.02, 0.05, 0.08, 0.1, 0.12, 0.15, 0.2, 0.3, 0.5, 0.7, 1.0)
#: Default tread element spacing, m (or the road element size when coarser): converged to about 0.3 % in mu
#: against 0.1 mm elements on road-like profiles (tests/test_tread_convergence.py).
DEFAULT_ELEMENT = 0.2e-3
_N_SHAPE = 1025
_N_PRESSURE = 4096
_JAM_NOTE = 0.01
#: Share of mu carried by capped (self-locking) contacts above which the result is flagged.
_SHARE_WARN = 0.05


@doi(TOOL_PAPER, KANE_2017, FLYVBJERG_1989)
def simulate(tire: Tire, road, material, speed: float, slip: float, temperature: float = 20.0, mu_loc=None,
             water: Water | None = None, **options) -> TreadResult:
    r"""Friction of the tyre's tread on ``road`` at one slip ratio and speed, with its time trace.

    Parameters
    ----------
    tire : Tire
        Size, load, inflation, tread depth and pattern (step 1 gives the footprint).
    road : surfaces.Profile, surfaces.ProfileSet, persson.tread.Road or path
        The road profiles (one tread row per profile), in metres.
    material : object
        The tread compound with ``E(omega, T)`` (e.g. :func:`materials.master_curve`).
    speed : float
        Vehicle speed V, m/s (> 0).
    slip : float
        Braking slip ratio s in (0, 1]; 1 is the locked wheel.
    temperature : float
        Background temperature of tread and road, deg C.
    mu_loc : float, LocalFriction or None
        Local friction of Eq. 2: a number (used as is), a table from :func:`persson.tread.local_friction`,
        or None: tabulated from the Persson engine on the scales finer than the road elements.
    water : Water or None
        None: dry. A :class:`Water` film: pseudo-hydrodynamic lift and no adhesion.
    **options
        ``element_size`` (m, default 0.2 mm or the road element size if coarser), ``road_element`` (road element
        size, m; default the profiles' spacing), ``rows`` (number of profiles used), ``dt`` (s; default the largest
        step that skips no road element and no patch element, times ``courant``), ``courant`` (default 1),
        ``stiffness`` (Pa/m) and ``damping`` (Pa s/m) per unit area instead of the compound's,
        ``microtexture``, ``q1``, ``adhesion``, ``local_effects`` (see :func:`persson.tread.local_friction`),
        ``n_blocks`` (10), ``jam_min`` (0.1: the smallest Eq. 2 denominator; flanks steeper than
        :math:`\tan\alpha = (1 - \text{jam\_min})/\mu_{loc}` are self-locking for Eq. 2 and their force is capped
        there and booked in ``jammed_share``), ``face`` (m; None: a point contact at the element's tip; a length:
        the element's flat contact face, resting on the road's upper envelope over that length, see
        :func:`persson.tread.contact_surface`).

    Returns
    -------
    TreadResult
        ``.mu, .mu_std, .time, .mu_t`` and the contact fraction, penetration, diagnostics and notes. An
        AccuracyWarning says when more than 5 % of ``mu`` is carried by self-locking contacts (``jammed_share``).

    Raises
    ------
    InputError
        Naming the argument: slip outside (0, 1], a speed <= 0, a road too short for the footprint, a time step
        that would skip road elements, an element size larger than the footprint, unknown options.
    """
    setup = _Setup.make(tire, road, material, temperature, water, options)
    s = _slip(slip)
    V = positive(speed, "speed")
    local = setup.local_table(mu_loc, [s * V])
    pts = setup.points(np.array([s]), np.array([V]), local)
    mu_t, c_t, p_t, residual, jammed, stuck, _, final, jam_t = kernels.march(
        z=setup.z_contact, tan_alpha=setup.tan_alpha, dx_road=setup.road.dx, x_start=setup.x_start,
        n_steps=int(pts.n_steps[0]),
        dt=float(pts.dt[0]), v_slide=float(pts.v_slide[0]), v_roll=float(pts.v_roll[0]), n_elem=setup.n_elem,
        dx_elem=setup.dx_elem, land=pts.land, shape=setup.shape, offset_scale=float(pts.offset_scale[0]),
        stiffness=float(pts.stiffness[0]), damping=float(pts.damping[0]),
        shear_stiffness=float(pts.shear_stiffness[0]), area=setup.area, load=float(pts.load[0]),
        load_total=tire.load, p0=pts.p0, dp=pts.dp, mu_table=pts.mu_table[0],
        jam_min=setup.jam_min, probe=-1)
    k = int(pts.skip[0])
    mean, err = kernels.block_mean(mu_t[k:], setup.n_blocks)
    share = float(np.mean(jam_t[k:]))
    notes = list(setup.notes) + [n for ns in pts.notes for n in ns] + list(local.notes)
    notes += _diagnostics(residual, jammed, share, float(mean), setup.jam_min)
    time = (np.arange(mu_t.size) + 1.0) * float(pts.dt[0])
    return TreadResult(
        mu=float(mean), mu_std=float(err), time=time, mu_t=mu_t, contact_fraction=float(np.mean(c_t[k:])),
        contact_t=c_t, penetration=float(np.mean(p_t[k:])), penetration_t=p_t, slip=s, speed=V,
        sliding_speed=s * V, temperature=setup.temperature, lift=float(pts.lift[0]), transient=k * float(pts.dt[0]),
        load_residual=float(residual), stuck_fraction=float(stuck), jammed_fraction=float(jammed),
        jammed_share=share,
        stiffness=float(pts.stiffness[0]), damping=float(pts.damping[0]),
        shear_stiffness=float(pts.shear_stiffness[0]), element_size=setup.dx_elem, dt=float(pts.dt[0]),
        final_state=_final_state(final, setup), notes=tuple(dict.fromkeys(notes)),
        citations=citations_of(simulate, tire, local, setup.road))


@doi(TOOL_PAPER, KANE_2017, FLYVBJERG_1989)
def slip_map(tire: Tire, road, material, slips=DEFAULT_SLIPS, speeds=(16.7,), temperature: float = 20.0,
             water: Water | None = None, mu_loc=None, **options) -> SlipMap:
    """Steady friction over slip ratios and speeds; ABS peak and locked wheel per speed.

    Parameters
    ----------
    tire, road, material, temperature, water, mu_loc, **options
        As for :func:`simulate`.
    slips : array_like
        Slip ratios in (0, 1] (default :data:`DEFAULT_SLIPS`); the locked wheel (slip 1) is always computed.
    speeds : array_like
        Vehicle speeds, m/s.

    Returns
    -------
    SlipMap
        ``.mu`` of shape (n_speed, n_slip), ``.peak_mu, .peak_slip, .locked_mu`` per speed. The local friction
        is tabulated once for all points, and the points run in parallel.
    """
    setup = _Setup.make(tire, road, material, temperature, water, options)
    s_req = np.array([_slip(x) for x in np.atleast_1d(finite_array(slips, "slips")).ravel()])
    if np.unique(s_req).size != s_req.size:
        raise InputError("slips: expected distinct slip ratios")
    V = np.atleast_1d(finite_array(speeds, "speeds")).ravel()
    if np.any(V <= 0):
        raise InputError(f"speeds: expected vehicle speeds > 0 m/s, got {V.min():g}")
    s_all = np.unique(np.append(s_req, 1.0))
    S, VV = np.meshgrid(s_all, V)
    local = setup.local_table(mu_loc, (S * VV).ravel())
    pts = setup.points(S.ravel(), VV.ravel(), local)
    stats = kernels.march_points(
        z=setup.z_contact, tan_alpha=setup.tan_alpha, dx_road=setup.road.dx, x_start=setup.x_start,
        n_steps=pts.n_steps, dt=pts.dt,
        v_slide=pts.v_slide, v_roll=pts.v_roll, n_elem=setup.n_elem, dx_elem=setup.dx_elem, land=pts.land,
        shape=setup.shape, offset_scale=pts.offset_scale, stiffness=pts.stiffness, damping=pts.damping,
        shear_stiffness=pts.shear_stiffness, area=setup.area, load=pts.load, load_total=tire.load,
        p0=pts.p0, dp=pts.dp, mu_table=pts.mu_table, jam_min=setup.jam_min, skip=pts.skip,
        n_blocks=setup.n_blocks)
    shape = S.shape
    mu_all = stats[:, 0].reshape(shape)
    err_all = stats[:, 1].reshape(shape)
    cols = np.searchsorted(s_all, s_req)
    ipk = np.argmax(mu_all, axis=1)
    rows = np.arange(V.size)
    notes = list(setup.notes) + [n for ns in pts.notes for n in ns] + list(local.notes)
    worst = int(np.argmax(stats[:, 7] / np.maximum(np.abs(stats[:, 0]), 1e-300)))
    notes += _diagnostics(float(stats[:, 4].max()), float(stats[:, 5].max()), float(stats[worst, 7]),
                          float(stats[worst, 0]), setup.jam_min)
    return SlipMap(
        slips=s_req, speeds=V, mu=mu_all[:, cols], mu_std=err_all[:, cols],
        contact_fraction=stats[:, 2].reshape(shape)[:, cols], penetration=stats[:, 3].reshape(shape)[:, cols],
        lift=pts.lift.reshape(shape)[:, cols], peak_mu=mu_all[rows, ipk], peak_slip=s_all[ipk],
        peak_std=err_all[rows, ipk], locked_mu=mu_all[:, -1], locked_std=err_all[:, -1],
        jammed_share=stats[:, 7].reshape(shape)[:, cols],
        temperature=setup.temperature, notes=tuple(dict.fromkeys(notes)),
        citations=citations_of(slip_map, tire, local, setup.road))


@doi(TOOL_PAPER, SPEARMAN_1904, KENDALL_1938)
def rank_surfaces(surfaces: dict, tire: Tire, material, speed: float = 16.7, measured=None,
                  temperature: float = 20.0, water: Water | None = None, slips=DEFAULT_SLIPS, mu_loc=None,
                  **options) -> Ranking:
    """Rank road surfaces by predicted ABS-peak and locked-wheel friction (Fig. 8 of the paper).

    Parameters
    ----------
    surfaces : dict
        name -> road (anything :func:`simulate` accepts); each gets its own local-friction table.
    tire, material, temperature, water, mu_loc, **options
        As for :func:`simulate`.
    speed : float
        Vehicle speed, m/s.
    measured : dict, optional
        name -> ``(peak, locked)`` or ``{"peak": x, "locked": y}`` (either may be None): measured friction to
        correlate with (Spearman's rho and Kendall's tau, :mod:`scipy.stats`).
    slips : array_like
        Slip ratios searched for the peak.

    Returns
    -------
    Ranking
    """
    if not isinstance(surfaces, dict) or not surfaces:
        raise InputError("surfaces: expected a non-empty dict name -> road")
    names = tuple(str(n) for n in surfaces)
    maps = {}
    for name, rd in surfaces.items():
        try:
            maps[str(name)] = slip_map(tire, rd, material, slips=slips, speeds=[speed], temperature=temperature,
                                       water=water, mu_loc=mu_loc, **options)
        except InputError as exc:
            raise InputError(f"surface {name!r}: {exc}") from None
    peak = np.array([maps[n].peak_mu[0] for n in names])
    locked = np.array([maps[n].locked_mu[0] for n in names])
    from scipy import stats

    out = dict(names=names, speed=float(speed), peak_mu=peak,
               peak_std=np.array([maps[n].peak_std[0] for n in names]), locked_mu=locked,
               locked_std=np.array([maps[n].locked_std[0] for n in names]),
               peak_rank=stats.rankdata(-peak, method="min").astype(int),
               locked_rank=stats.rankdata(-locked, method="min").astype(int), maps=maps)
    notes = []
    if measured is not None:
        m_peak, m_locked = _measured(measured, names)
        out["measured_peak"], out["measured_locked"] = m_peak, m_locked
        sp, kd = {}, {}
        for key, pred, meas in (("peak", peak, m_peak), ("locked", locked, m_locked)):
            ok = np.isfinite(meas)
            if ok.sum() < 3:
                notes.append(f"{key}: {int(ok.sum())} measured surfaces; rank correlations need at least 3")
                continue
            r = stats.spearmanr(pred[ok], meas[ok])
            t = stats.kendalltau(pred[ok], meas[ok])
            sp[key] = (float(r.statistic), float(r.pvalue))
            kd[key] = (float(t.statistic), float(t.pvalue))
        out["spearman"], out["kendall"] = sp, kd
    for n in names:
        notes += [f"{n}: {x}" for x in maps[n].notes]
    return Ranking(**out, notes=tuple(dict.fromkeys(notes)),
                   citations=citations_of(rank_surfaces, *maps.values()))


# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class _Points:
    """Per-point arguments of the kernels."""

    v_slide: np.ndarray
    v_roll: np.ndarray
    dt: np.ndarray
    n_steps: np.ndarray
    skip: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    shear_stiffness: np.ndarray
    offset_scale: np.ndarray
    load: np.ndarray
    lift: np.ndarray
    mu_table: np.ndarray
    p0: float
    dp: float
    land: np.ndarray
    notes: tuple


_OPTIONS = ("element_size", "road_element", "rows", "dt", "courant", "stiffness", "damping", "microtexture", "q1",
            "adhesion", "local_effects", "n_blocks", "jam_min", "face")


@dataclass(frozen=True, eq=False)
class _Setup:
    """Geometry and options shared by the points of one tyre on one road."""

    tire: Tire
    road: Road
    material: object
    temperature: float
    water: Water | None
    n_elem: int
    dx_elem: float
    area: float
    shape: np.ndarray
    land_fraction: float
    y_rows: np.ndarray
    x_start: float
    travel: float
    z_contact: np.ndarray
    tan_alpha: np.ndarray
    options: dict
    n_blocks: int
    jam_min: float
    notes: tuple

    @classmethod
    def make(cls, tire, road, material, temperature, water, options) -> "_Setup":
        if not isinstance(tire, Tire):
            raise InputError(f"tire: expected persson.tread.Tire, got {type(tire).__name__}")
        unknown = sorted(set(options) - set(_OPTIONS))
        if unknown:
            raise InputError(f"unknown option(s) {unknown}; known: {', '.join(_OPTIONS)}")
        if water is not None and not isinstance(water, Water):
            raise InputError(f"water: expected persson.tread.Water or None, got {type(water).__name__}")
        if not callable(getattr(material, "E", None)):
            raise InputError(f"material: expected an object with E(omega, T), got {type(material).__name__}")
        T = float(plausible_temperature(temperature, "temperature")[()])
        rd = as_road(road, options.get("road_element"))
        rows = options.get("rows")
        if rows is not None:
            rows = int(number(rows, "rows"))
            if not 1 <= rows <= rd.n_rows:
                raise InputError(f"rows: expected 1..{rd.n_rows} (the road's profiles), got {rows}")
            rd = Road(rd.z[:rows], rd.dx, rd.names[:rows], rd.source, rd.profiles, rd.notes)
        fp = tire.footprint
        if options.get("element_size") is None:
            dx_e = max(rd.dx, DEFAULT_ELEMENT)
        else:
            dx_e = positive(options["element_size"], "element_size")
        n_elem = int(round(fp.length / dx_e))
        if n_elem < 4:
            raise InputError(f"element_size: {dx_e:g} m leaves {n_elem} elements on the {fp.length:.4g} m footprint; "
                             "expected at least 4")
        notes = list(rd.notes) + list(fp.notes)
        length = n_elem * dx_e
        x_start = length + rd.dx
        travel = rd.length - x_start - 2.0 * rd.dx
        if travel < length:
            raise InputError(f"road: the profiles are {rd.length:.4g} m long, too short for the {length:.4g} m "
                             f"footprint: at least {2 * length + 3 * rd.dx:.4g} m are needed (the footprint and one "
                             "footprint length of travel)")
        if travel < 5 * length:
            notes.append(f"road: {travel:.3g} m of travel is under five footprint lengths; the standard error rests "
                         "on few independent stretches of road")
        width_row = fp.width / rd.n_rows
        y_rows = -fp.width / 2 + (np.arange(rd.n_rows) + 0.5) * width_row
        from ..slip.contact import _parse_distribution

        # scipy's trapezoid: numpy's is np.trapezoid from numpy 2.0, np.trapz before
        from scipy.integrate import trapezoid

        _, _, shape_fn = _parse_distribution(tire.pressure_distribution)
        xi = np.linspace(0.0, 1.0, _N_SHAPE)
        shape = np.asarray(shape_fn(xi), dtype=float)
        shape = shape / trapezoid(shape, xi)
        x_probe = np.arange(4096) * dx_e
        land_fraction = float(np.mean(tire.land(x_probe[:, None], y_rows[None, :])))
        if land_fraction <= 0:
            raise InputError("tire.grooves: the rows of elements all fall in grooves; no rubber touches the road")
        n_blocks = int(number(options.get("n_blocks", 10), "n_blocks"))
        if n_blocks < 2:
            raise InputError(f"n_blocks: expected an integer >= 2, got {n_blocks}")
        jam = number(options.get("jam_min", 0.1), "jam_min")
        if not 0.0 < jam <= 1.0:
            raise InputError(f"jam_min: expected 0 < jam_min <= 1, got {jam:g}")
        face = options.get("face")
        if face is not None:
            face = positive(face, "face")
            if face > length / 4:
                raise InputError(f"face: {face:g} m is more than a quarter of the {length:.4g} m footprint; "
                                 "expected the contact face of one tread element (m)")
        z_contact, tan_alpha = contact_surface(rd, face)
        return cls(tire=tire, road=rd, material=material, temperature=T, water=water, n_elem=n_elem, dx_elem=dx_e,
                   area=dx_e * width_row, shape=shape, land_fraction=land_fraction, y_rows=y_rows, x_start=x_start,
                   travel=travel, z_contact=z_contact, tan_alpha=tan_alpha, options=dict(options),
                   n_blocks=n_blocks, jam_min=jam, notes=tuple(notes))

    def local_table(self, mu_loc, sliding_speeds) -> LocalFriction:
        """mu_loc as given, or tabulated from the engine over ``sliding_speeds``."""
        if isinstance(mu_loc, LocalFriction):
            if not mu_loc.covers(sliding_speeds):
                raise InputError("mu_loc: the table does not span the sliding speeds of this run "
                                 f"({np.min(sliding_speeds):.3g}-{np.max(sliding_speeds):.3g} m/s)")
            if not mu_loc.constant and mu_loc.wet != (self.water is not None):
                raise InputError(f"mu_loc: the table is for a {'wet' if mu_loc.wet else 'dry'} road, the run is "
                                 f"{'wet' if self.water is not None else 'dry'}")
            return mu_loc
        if mu_loc is not None:
            return constant_friction(mu_loc)
        o = self.options
        return local_friction(self.road, self.material, temperature=self.temperature, speeds=sliding_speeds,
                              wet=self.water is not None, microtexture=o.get("microtexture"), q1=o.get("q1"),
                              adhesion=o.get("adhesion", True), effects=tuple(o.get("local_effects", ())))

    def points(self, slips: np.ndarray, speeds: np.ndarray, local: LocalFriction) -> _Points:
        """Kernel arguments of the points (slips[i], speeds[i])."""
        o = self.options
        t = self.tire
        fp = t.footprint
        dx_r, dx_e = self.road.dx, self.dx_elem
        v_s = slips * speeds
        v_r = (1.0 - slips) * speeds
        courant = positive(o.get("courant", 1.0), "courant")
        if courant > 1.0:
            raise InputError(f"courant: {courant:g} > 1 would skip road elements; expected 0 < courant <= 1")
        dt_auto = courant * np.minimum(dx_r / v_s, np.where(v_r > 0, dx_e / np.where(v_r > 0, v_r, 1.0), np.inf))
        if o.get("dt") is not None:
            dt = np.full(v_s.shape, positive(o["dt"], "dt"))
            bad = v_s * dt > dx_r * (1 + 1e-9)
            if np.any(bad):
                i = int(np.argmax(bad))
                raise InputError(f"dt: {dt[i]:g} s would skip road elements: at sliding speed {v_s[i]:g} m/s an "
                                 f"element moves {v_s[i] * dt[i] * 1e3:.4g} mm per step, more than the "
                                 f"{dx_r * 1e3:.4g} mm road elements; expected dt <= {dx_r / v_s[i]:.4g} s")
            bad = v_r * dt > dx_e * (1 + 1e-9)
            if np.any(bad):
                i = int(np.argmax(bad))
                raise InputError(f"dt: {dt[i]:g} s moves the tread {v_r[i] * dt[i] * 1e3:.4g} mm through the "
                                 f"footprint per step, more than one {dx_e * 1e3:.4g} mm element; expected "
                                 f"dt <= {dx_e / v_r[i]:.4g} s")
        else:
            dt = dt_auto
        n_steps = np.floor(self.travel / speeds / dt).astype(np.int64)
        if np.any(n_steps < 20 * self.n_blocks):
            raise InputError(f"dt: {int(n_steps.min())} steps over the road; expected at least {20 * self.n_blocks}")
        h = t.tread_depth
        omega = v_s / dx_r
        with np.errstate(all="ignore"):
            E = np.asarray(self.material.E(omega, self.temperature), dtype=complex) * np.ones_like(omega)
        if o.get("stiffness") is not None:
            k_a = np.full(v_s.shape, positive(o["stiffness"], "stiffness"))
        else:
            k_a = E.real / h
        if o.get("damping") is not None:
            c = number(o["damping"], "damping")
            if c < 0:
                raise InputError(f"damping: expected a value >= 0 Pa s/m, got {c:g}")
            c_a = np.full(v_s.shape, c)
        else:
            c_a = E.imag / (omega * h)
        if not (np.all(np.isfinite(k_a)) and np.all(k_a > 0) and np.all(np.isfinite(c_a)) and np.all(c_a >= 0)):
            raise InputError("material: E(omega, T) gave a non-positive storage or negative loss modulus at the "
                             f"excitation frequencies {omega.min():.3g}-{omega.max():.3g} rad/s")
        K = k_a * self.area
        C = c_a * self.area
        Kt = np.full(v_s.shape, fp.shear_stiffness * self.area)
        sigma_land = fp.mean_pressure / self.land_fraction
        offset = sigma_land * self.area / K
        lift = np.zeros(v_s.shape)
        notes: list[tuple] = []
        if self.water is not None:
            etd = self.road.texture_depth() if self.water.outlet_gap is None else None
            for i in range(v_s.size):
                ws = wet_state(self.water, t, self.road, float(speeds[i]), float(slips[i]), texture_depth=etd)
                lift[i] = ws.lift
                # one set of notes per speed, from its locked-wheel point (the largest slip)
                if slips[i] == slips[speeds == speeds[i]].max():
                    notes.append(tuple(f"V = {speeds[i]:g} m/s: {x}" for x in ws.notes))
        load = t.load - lift
        relax = np.where(K > 0, 5.0 * C / K, 0.0)
        t_tr = fp.length / speeds + relax
        skip = np.ceil(t_tr / dt).astype(np.int64)
        cap = n_steps // 2
        if np.any(skip > cap):
            notes.append(("the transient (a footprint length of travel plus five relaxation times) was cut to half "
                          "of the run at some points: the road is short for these conditions and the mean still "
                          "holds part of the start-up (use profiles longer than three footprint lengths)",))
            skip = np.minimum(skip, cap)
        notes = [n for n in notes if n]
        # the kernel reads mu_loc(p) on a fine uniform grid of p (no logarithm per element and step): the
        # table's ln p interpolation resampled, exact at its nodes to the resampling
        if local.constant:
            table = np.vstack([local.row(float(v)) for v in v_s])
            p0, dp = 0.0, 1.0
        else:
            lp = np.log(local.pressures)
            grid = np.linspace(local.pressures[0], local.pressures[-1], _N_PRESSURE)
            table = np.vstack([np.interp(np.log(grid), lp, local.row(float(v))) for v in v_s])
            p0, dp = float(grid[0]), float(grid[1] - grid[0])
        n_mat = self.n_elem + int(n_steps.max()) + 2
        coord = np.concatenate([-np.arange(self.n_elem) * self.dx_elem,
                                np.arange(1, n_mat - self.n_elem + 1) * self.dx_elem])
        land = np.ascontiguousarray(t.land(coord[None, :], self.y_rows[:, None]))
        return _Points(v_slide=v_s, v_roll=v_r, dt=dt, n_steps=n_steps, skip=skip, stiffness=K, damping=C,
                       shear_stiffness=Kt, offset_scale=offset, load=load, lift=lift,
                       mu_table=np.ascontiguousarray(table), p0=p0, dp=dp, land=land,
                       notes=tuple(notes))


def _final_state(final: np.ndarray, setup: _Setup) -> dict:
    n = setup.n_elem
    rows = np.repeat(np.arange(setup.road.n_rows), n)
    return {"x": final[0], "xi": final[1], "y": setup.y_rows[rows], "row": rows, "compression": final[2],
            "force": final[3], "rubber": final[4] > 0.5, "element_size": setup.dx_elem,
            "row_width": setup.area / setup.dx_elem}


def _slip(value) -> float:
    s = number(value, "slip")
    if not 0.0 < s <= 1.0:
        raise InputError(f"slip: expected a braking slip ratio in (0, 1] (1 = locked wheel), got {s:g}")
    return s


def _diagnostics(residual: float, jammed: float, share: float, mu: float, jam_min: float) -> list[str]:
    notes = []
    if residual > 1e-9:
        notes.append(f"load balance: largest relative error {residual:.3g} (expected <= 1e-9)")
    if jammed > _JAM_NOTE:
        msg = (f"{jammed:.1%} of the contacts met flanks too steep for Eq. 2 (tan alpha near 1/mu_loc); their "
               "tangential force was capped (denominator held at jam_min): the road is that sharp at its element "
               "size, which no finer time step changes")
        notes.append(msg)
        warnings.warn(msg, PhysicsWarning, stacklevel=3)
    if share > _SHARE_WARN * abs(mu) and share > 1e-3:
        msg = (f"{share:.3g} of mu = {mu:.3g} ({share / abs(mu):.0%}) is carried by the contacts on flanks at the "
               f"self-locking limit of Eq. 2, whose force scales as 1/jam_min (jam_min = {jam_min:g}): that part "
               "measures the cap, not the road; the mean of Eq. 2 over such flanks has no finite limit without the "
               "rubber's own deformation (see the docs, 'Sharp textures')")
        notes.append(msg)
        warnings.warn(msg, AccuracyWarning, stacklevel=3)
    return notes


def _measured(measured, names) -> tuple[np.ndarray, np.ndarray]:
    if not isinstance(measured, dict):
        raise InputError("measured: expected a dict name -> (peak, locked) or {'peak': .., 'locked': ..}")
    unknown = sorted(set(map(str, measured)) - set(names))
    if unknown:
        raise InputError(f"measured: surfaces {unknown} are not among the surfaces {list(names)}")
    peak = np.full(len(names), np.nan)
    locked = np.full(len(names), np.nan)
    for i, n in enumerate(names):
        v = measured.get(n)
        if v is None:
            continue
        if isinstance(v, dict):
            extra = set(v) - {"peak", "locked"}
            if extra:
                raise InputError(f"measured[{n!r}]: unknown keys {sorted(extra)}; expected 'peak', 'locked'")
            pk, lk = v.get("peak"), v.get("locked")
        else:
            try:
                pk, lk = v
            except (TypeError, ValueError):
                raise InputError(f"measured[{n!r}]: expected (peak, locked), got {v!r}") from None
        if pk is not None:
            peak[i] = number(pk, f"measured[{n!r}] peak")
        if lk is not None:
            locked[i] = number(lk, f"measured[{n!r}] locked")
    return peak, locked
