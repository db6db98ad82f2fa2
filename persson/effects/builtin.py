"""Built-in effects: flash temperature, adhesion, microtexture, strain softening, wet road.

Each is a frozen dataclass; its documented parameters (:class:`~persson.effects.base.Parameter`) are the
fields that diagnosis refits. Formulas cite their sources.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from ..errors import InputError
from ..engine.conditions import Conditions, SolverState, TemperatureSolverOptions
from ..notes import Note
from . import strain as _strain
from .base import Effect, Parameter

__all__ = ["FlashTemperature", "Adhesion", "Microtexture", "StrainSoftening", "Wet"]


@doi("10.1088/0953-8984/18/32/025", "arxiv:2602.22078")
@dataclass(frozen=True)
class FlashTemperature(Effect):
    r"""Persson's multiscale flash temperature, solved self-consistently with :math:`E(\omega, T_q)`.

    .. math::
        T_q = T_0 + \int_{q_0}^{q} dq'\, g(q, q') f(q'), \qquad
        f(q) = \frac{v q^4 C(q)}{\rho c_p}\frac{P(q)}{P(q_m)}\int_0^{2\pi} d\phi\,\cos\phi\,
        \frac{\mathrm{Im}\,E(q v \cos\phi, T_q)}{1 - \nu^2}

    with the heat kernel :math:`g` of :func:`persson.engine.kernels.heat_kernel` (closed form, erfcx) and
    :math:`D = \lambda/(\rho c_p)` (Persson, J. Phys.: Condens. Matter 18, 7789 (2006), Eqs. 20-27).
    The heat produced at scale q' raises the temperature at the (smaller) scales q >= q'; it is produced in
    the macro-asperity contact regions, of area fraction P(q_m), during the contact time t0 = d / v of a
    macro-asperity contact of diameter d. Thermal properties come from ``material.thermal``.

    The macro-asperity geometry is a property of the surface, not of the scan: the macro-asperity contacts are
    those seen at the scale of the largest asperities, the PSD's roll-off (the aggregate size of a road), and
    their diameter is nearly independent of the modulus and the pressure for a large nominal contact
    (Persson & Miyashita, arXiv:2602.22078 (2026)). So q_m = ``macro_scale_ratio`` times the roll-off
    wavevector of the PSD (``SelfAffine.q0``, ``PSD.q_rolloff``; the first q of a table that declares no
    roll-off, with a note in the result) and d = pi / q_m (half its wavelength) unless ``contact_diameter`` is
    given. On a road with a 5 mm roll-off that is d = 1.25 mm; a scan 0.4 m long no longer makes it 10 cm.
    A larger q_m (smaller, hotter hot spots of shorter contact time) lowers the friction at high speed.

    Parameters
    ----------
    macro_scale_ratio : float
        q_m / q_roll-off, the magnification at which the macro-asperity contact regions are defined (default 2).
    contact_diameter : float
        Diameter d of a macro-asperity contact region, m; 0 (default) means pi / q_m (half the wavelength).
    tol : float
        Convergence tolerance on max |T_new - T| over the scales, K (default 1e-3).
    max_iter : int
        Largest number of fixed-point iterations per start (default 300; a speed that does not converge with
        Anderson mixing starts again with Aitken's relaxation, then with the half step T <- (T + g(T)) / 2).
    """

    name = "flash_temperature"
    solver_role = "temperature"
    parameters = (
        Parameter("macro_scale_ratio", 2.0, (1.0, 1000.0), "1",
                  "q_m / q_roll-off of the macro-asperity contact regions",
                  log_scale=True, physical_limits=(1.0,)),
        Parameter("contact_diameter", 0.0, (0.0, 1.0), "m", "macro-asperity contact diameter (0: pi / q_m)",
                  sentinel=0.0, sentinel_doc="pi / q_m", fittable=False),
    )
    macro_scale_ratio: float = 2.0
    contact_diameter: float = 0.0
    tol: float = 1e-3
    max_iter: int = 300

    def __post_init__(self):
        super().__post_init__()
        if not (math.isfinite(self.tol) and self.tol > 0):
            raise InputError(f"flash_temperature.tol: expected a positive tolerance in K, got {self.tol!r}")
        if not (isinstance(self.max_iter, (int, np.integer)) and self.max_iter >= 1):
            raise InputError(f"flash_temperature.max_iter: expected a positive integer, got {self.max_iter!r}")

    def temperature_solver_options(self, *, surface, material, q) -> TemperatureSolverOptions:
        """The settings of the self-consistent flash temperature on the wavevector nodes ``q`` (rad/m): q_m and d
        from the PSD's roll-off (see the class), D and rho c_p from ``material.thermal``; the solver runs it.

        Raises
        ------
        InputError
            If the material has no thermal properties or no temperature dependence (``log10_aT``).
        """
        thermal = getattr(material, "thermal", None)
        if thermal is None:
            raise InputError("flash_temperature: the material has no thermal properties (material.thermal)")
        if not hasattr(material, "log10_aT"):
            raise InputError("flash_temperature: the material has no temperature dependence (log10_aT); "
                             "the flash temperature would not change the friction")
        q_roll = _rolloff(surface)
        notes = _default_thermal_note(thermal)
        if q_roll is None or not q[0] <= q_roll < q[-1]:
            q_roll, note = _fitted_rolloff(surface, q, self.macro_scale_ratio)
            notes += (note,)
        q_m = min(self.macro_scale_ratio * q_roll, q[-1])
        d = self.contact_diameter if self.contact_diameter > 0 else math.pi / q_m
        return TemperatureSolverOptions(q_m=q_m, contact_diameter=d, diffusivity=thermal.diffusivity,
                                        heat_capacity=thermal.heat_capacity, tol=self.tol,
                                        max_iter=int(self.max_iter), notes=notes)


def _fitted_rolloff(surface, q, ratio: float) -> tuple[float, str]:
    """The roll-off of a PSD table that declares none, fitted (:func:`surfaces.fit_rolloff`: flat below q0,
    self-affine above), with a note; where no plateau can be fitted, the first q, with a note and a PhysicsWarning."""
    import warnings

    from ..engine.memo import per_object
    from ..errors import PhysicsWarning

    table = _table_of(surface)
    fitted = None if table is None else per_object(table, ("fitted_rolloff",), lambda: (_fit_rolloff(table),))[0]
    if fitted is not None and q[0] <= fitted < q[-1]:
        return fitted, Note(f"flash temperature: the PSD declares no roll-off; the roll-off fitted to it "
                            f"(surfaces.fit_rolloff), {fitted:.4g} rad/m, sets the macro-asperity scale q_m = "
                            f"{ratio:g} x {fitted:.4g} rad/m: give [surface] q_rolloff (PSD.with_rolloff) to "
                            "choose it", "assumed")
    msg = (f"flash temperature: the PSD declares no roll-off and none can be fitted (no plateau at its long "
           f"wavelengths); the macro-asperity scale q_m is {ratio:g} x its first q ({q[0]:.4g} rad/m), which makes "
           "the hot spots as large as the scan: give [surface] q_rolloff (PSD.with_rolloff) or "
           "FlashTemperature(contact_diameter=...)")
    warnings.warn(msg, PhysicsWarning, stacklevel=5)
    return float(q[0]), Note(msg, "assumed")


def _table_of(surface):
    """The tabulated PSD (with ``q`` and ``C_values``) inside wrappers (``base``, ``surface``), or None."""
    for _ in range(8):
        if surface is None:
            return None
        if hasattr(surface, "C_values") and hasattr(surface, "q"):
            return surface
        surface = getattr(surface, "base", None) or getattr(surface, "surface", None)
    return None


def _fit_rolloff(table):
    from surfaces.psdfit import with_estimated_rolloff

    return with_estimated_rolloff(table.with_rolloff(None) if table.q_rolloff is not None else table).q_rolloff


def _default_thermal_note(thermal) -> tuple:
    """A note when the thermal properties are the materials package's defaults (likely not the compound's)."""
    try:
        default = type(thermal)()
    except TypeError:
        return ()
    if thermal != default:
        return ()
    return (Note(f"flash temperature: the thermal properties are the defaults of {type(thermal).__name__} (density "
                 f"{thermal.density:g} kg/m^3, specific heat {thermal.specific_heat:g} J/(kg K), conductivity "
                 f"{thermal.conductivity:g} W/(m K)), not the compound's unless they were given", "assumed"),)


def _rolloff(surface):
    """The roll-off wavevector of a PSD (rad/m): ``q_rolloff`` of a table, ``q0`` of a self-affine model, looked
    up through wrappers (``base``, ``surface``); None when not declared."""
    for _ in range(8):
        qr = getattr(surface, "q_rolloff", None)
        if qr is not None:
            return float(qr)
        if hasattr(surface, "hurst") and hasattr(surface, "C0") and hasattr(surface, "q0"):
            return float(surface.q0)
        surface = getattr(surface, "base", None) or getattr(surface, "surface", None)
        if surface is None:
            return None
    return None


def _within_a_decade_of_the_shifted_speeds(ranges) -> tuple:
    """The plausible range of the adhesive peak's speed: the measured sliding speeds shifted to the reference
    temperature (``ranges.shifted_speed``, m/s), widened by a decade on each side (a module-level function, not a
    lambda, so that the effect's parameters can be pickled)."""
    return ranges.shifted_speed[0] / 10.0, ranges.shifted_speed[1] * 10.0


@doi("10.1088/0953-8984/17/1/R01")
@dataclass(frozen=True)
class Adhesion(Effect):
    r"""Adhesive friction from the shear stress in the area of real contact.

    .. math::
        \mu_{adh} = \frac{\tau_f(v, T) P(q_1)}{\sigma_0},\qquad
        \tau_f = \tau_{f0}\exp\left(-c\left[\log_{10}\frac{v a_T(T)}{v_{ref}}\right]^2\right)

    (Persson et al., J. Phys.: Condens. Matter 17, R1 (2005), Sec. 8; the log-normal speed dependence of the
    frictional shear stress as in Lorenz, Persson et al., Eur. Phys. J. E 38, 1 (2015)). T is the
    temperature at q1 (the flash temperature when that effect is on, else T0); a_T from the material.
    ``sigma0`` is the total nominal pressure. On a wet surface (:class:`Wet`) the term is zero.

    ``v_ref`` is the sliding speed of the shear-stress peak at the temperature ``v_ref_temperature``: by default
    the material's reference temperature (where a_T = 1), or any temperature of the user's choice, e.g. the test
    temperature at which the peak was observed; the peak then lies at :math:`v_{ref}\, a_T(T_{ref,v})/a_T(T)`
    at temperature T (time-temperature superposition of the shear-stress process, Grosch 1963).

    Parameters
    ----------
    tau_f0 : float
        Peak frictional shear stress, Pa (default 2 MPa).
    c : float
        Width parameter of the log-normal speed dependence, 1/decade^2 (default 0.1).
    v_ref : float
        Speed of the peak at ``v_ref_temperature``, m/s (default 1e-2).
    v_ref_temperature : float or None
        Temperature of ``v_ref``, deg C; None (default) is the material's reference temperature.
    """

    name = "adhesion"
    term_kind = "adhesion"
    parameters = (
        # plausible: tau_f of rubber on rough and smooth substrates is of order 1-10 MPa (Persson et al. 2005,
        # Sec. 8; Lorenz et al. 2015); a peak narrower than ~1.4 decades (c > 0.5) is not seen in those data; the
        # peak must lie where the measurements can see it (measured sliding speeds times a_T, +- one decade)
        Parameter("tau_f0", 2.0e6, (0.0, 50.0e6), "Pa", "peak frictional shear stress in the real contact",
                  plausible=(0.0, 10.0e6), physical_limits=(0.0,)),
        Parameter("c", 0.1, (0.0, 2.0), "1/decade^2", "width of the log-normal speed dependence",
                  plausible=(0.0, 0.5), physical_limits=(0.0,)),
        Parameter("v_ref", 1.0e-2, (1e-12, 1e6), "m/s", "speed of the shear-stress peak at T_ref",
                  log_scale=True,
                  plausible=_within_a_decade_of_the_shifted_speeds),
    )
    tau_f0: float = 2.0e6
    c: float = 0.1
    v_ref: float = 1.0e-2
    v_ref_temperature: float | None = None

    def __post_init__(self):
        super().__post_init__()
        t = self.v_ref_temperature
        if t is not None and (isinstance(t, bool) or not isinstance(t, (int, float, np.integer, np.floating))
                              or not math.isfinite(t) or t < -273.15):
            raise InputError(f"adhesion.v_ref_temperature: expected a temperature in deg C or None, got {t!r}")

    def shear_stress(self, speed, temperature, material) -> np.ndarray:
        """tau_f(v, T), Pa, for speeds (m/s) and temperatures (deg C) broadcast together."""
        has_shift = hasattr(material, "log10_aT")
        log_aT = material.log10_aT(temperature) if has_shift else 0.0
        if has_shift and self.v_ref_temperature is not None:
            log_aT = np.asarray(log_aT, dtype=float) - float(material.log10_aT(float(self.v_ref_temperature)))
        x = np.log10(np.asarray(speed, dtype=float)) + np.asarray(log_aT, dtype=float) - math.log10(self.v_ref)
        return self.tau_f0 * np.exp(-self.c * x * x)

    def friction_term(self, state: SolverState):
        cond = state.conditions
        if cond.wet:
            return np.zeros_like(cond.speed)
        tau = self.shear_stress(cond.speed, state.contact_temperature, state.material)
        return tau * state.contact_area / cond.nominal_pressure


@doi("10.1088/0953-8984/17/1/R01")
@dataclass(frozen=True)
class Microtexture(Effect):
    r"""Extend the PSD past its reliability limit q_r to q1 with the self-affine tail.

    .. math:: C(q) = C(q_r) (q / q_r)^{-2(1 + H)},\qquad q_r < q \le q_1

    (self-affine fractal PSD, Persson et al., J. Phys.: Condens. Matter 17, R1 (2005), Eq. 10), through
    :meth:`surfaces.PSD.extrapolate`: H is fitted on the last decade below q_r (or the table end) by least
    squares in log-log, above the roll-off where that lies inside the decade, unless given; where that part of
    the table is too short or not a power law, the exponent the PSD records (``hurst`` in its file's metadata)
    serves. A :class:`surfaces.SelfAffine` continues its own power law.

    Parameters
    ----------
    q1 : float
        New short-distance cut-off, rad/m (default 1e7 rad/m, i.e. wavelengths down to 0.6 um).
    hurst : float
        Hurst exponent of the tail; 0 (default) means fitted.
    """

    name = "microtexture"
    parameters = (
        # plausible q1: the microtexture (wavelengths below 0.5 mm, ISO 13473-1) is kept, down to ~6 nm
        Parameter("q1", 1.0e7, (1.0e2, 1.0e10), "rad/m", "short-distance cut-off of the extrapolated tail",
                  log_scale=True, plausible=(1.2e4, 1.0e9)),
        Parameter("hurst", 0.0, (0.0, 1.0), "1", "Hurst exponent of the tail (0: fitted)",
                  plausible=(0.5, 1.0), sentinel=0.0,
                  sentinel_doc="fitted on the PSD's last decade, or the one the PSD records"),
    )
    q1: float = 1.0e7
    hurst: float = 0.0

    def transform_surface(self, surface, conditions):
        lo, hi = (float(x) for x in surface.q_range)
        if not self.q1 > lo:
            # a cut-off below the roughness's first wavevector would leave no roughness at all, not the surface
            # as it is
            raise InputError(f"microtexture: q1 = {self.q1:.6g} rad/m lies at or below the surface's first "
                             f"wavevector q0 = {lo:.6g} rad/m: it would remove every length scale of the roughness; "
                             "expected q1 > q0")
        if self.q1 <= hi * (1 + 1e-12):
            return surface.with_cutoff(q1=self.q1)
        if not hasattr(surface, "extrapolate"):
            raise InputError(f"microtexture: the surface {type(surface).__name__} cannot extrapolate its tail")
        try:
            return surface.extrapolate(self.q1, hurst=self.hurst if self.hurst > 0 else None)
        except ValueError as exc:
            raise InputError(f"microtexture: {exc}; give hurst= explicitly") from None


@doi("10.1063/1.4919221")
@dataclass(frozen=True)
class StrainSoftening(Effect):
    r"""Large-strain modulus of filled rubber (Payne effect): constant factors, or measured factors at the local
    strain of every length scale.

    With constant factors (the default)

    .. math:: E_{large}(\omega, T) = f\, E'(\omega, T) + i\, g\, E''(\omega, T).

    With measured strain sweeps (``factors``, a :class:`materials.StrainFactors` built by
    :func:`materials.strain_factors`), each length scale sees the modulus at its own strain:

    .. math:: E(\omega, T, q) = f(\varepsilon(q), T)\, E'(\omega, T) + i\, g(\varepsilon(q), T)\, E''(\omega, T),
              \qquad \varepsilon(q) = \kappa\, \xi(q),\quad
              \xi(q)^2 = 2\pi\int_{q_0}^{q} q'^3 C(q')\, dq'

    inside G(q), the friction integral and the flash temperature (T the temperature of the scale). The strain
    of the asperity contacts at magnification q grows with the rms slope :math:`\xi(q)` of the roughness up to
    that scale; Persson's estimate takes half of it, :math:`\kappa = 1/2` (Persson, J. Phys.: Condens. Matter 18,
    7789 (2006); the strain-sweep modulus of Lorenz, Oh, Nam, Jeon & Persson, J. Chem. Phys. 142, 194701
    (2015)); :math:`\kappa` = ``strain_per_slope`` is a parameter (kappa = 1 takes the strain equal to the slope).
    Payne, J. Appl. Polym. Sci. 6, 57 (1962) for the effect itself.

    Beyond the largest measured strain the factors follow ``extrapolation`` (:mod:`persson.effects.strain`):
    ``"hold"`` keeps their values there, ``"log_trend"`` continues the measured trend linearly in
    :math:`\ln\varepsilon`, a table of factors (:func:`materials.read_strain_factors`) gives them. The result
    reports the share of :math:`\mu_{hys}` that comes from those scales (``strain_extrapolated_share``, a note,
    and a PhysicsWarning above one half); :func:`persson.effects.strain_extrapolation_spread` compares the rules.

    Parameters
    ----------
    storage_factor : float
        f, constant factor on E' (default 0.5); not used when ``factors`` is given.
    loss_factor : float
        g, constant factor on E'' (default 0.7); not used when ``factors`` is given.
    factors : materials.StrainFactors, optional
        Measured f(strain, T), g(strain, T): switches on the per-scale modulus.
    strain_per_slope : float
        kappa of the local strain kappa xi(q) (default 0.5).
    extrapolation : {"hold", "log_trend"} or materials.StrainFactors
        The factors beyond the largest measured strain (default ``"hold"``); used with ``factors`` only.
    """

    name = "strain_softening"
    parameters = (
        # plausible: filled tread compounds keep 10-100 % of E' at large strain and 10-150 % of E'' (the loss
        # modulus peaks at intermediate strain; Payne 1962)
        Parameter("storage_factor", 0.5, (0.05, 1.0), "1", "factor f on E' at large strain",
                  plausible=(0.1, 1.0), physical_limits=(1.0,)),
        Parameter("loss_factor", 0.7, (0.05, 1.5), "1", "factor g on E'' at large strain",
                  plausible=(0.1, 1.5), physical_limits=(1.0,)),
        Parameter("strain_per_slope", 0.5, (0.05, 2.0), "1", "local strain per unit rms slope (measured factors)",
                  plausible=(0.25, 1.0), fittable=False),
    )
    storage_factor: float = 0.5
    loss_factor: float = 0.7
    factors: object = None
    strain_per_slope: float = 0.5
    extrapolation: object = "hold"

    def __post_init__(self):
        super().__post_init__()
        if self.factors is not None and not callable(getattr(self.factors, "factors", None)):
            raise InputError("strain_softening.factors: expected materials.StrainFactors (with factors(strain, T)), "
                             f"got {type(self.factors).__name__}")
        rule = _strain.check_rule(self.extrapolation)
        if rule != "hold" and self.factors is not None and not hasattr(self.factors, "strain_range"):
            raise InputError(f"strain_softening.extrapolation = {_strain.rule_name(rule)!r} needs the largest measured "
                             f"strain of the factors (strain_range), which {type(self.factors).__name__} lacks")

    def transform_material(self, material, conditions):
        if self.factors is not None:
            return material
        import materials

        return materials.StrainSoftened(material, self.storage_factor, self.loss_factor)

    def modulus_factors(self, slope, temperature):
        if self.factors is None:
            return None
        f, g = _strain.extrapolated_factors(self.factors, self.strain_per_slope * np.asarray(slope, dtype=float),
                                            np.asarray(temperature, dtype=float), self.extrapolation)
        return np.asarray(f, dtype=float), np.asarray(g, dtype=float)

    def strain_report(self, result, slope):
        """``result`` with the share of mu_hysteresis from scales beyond the measured strains
        (``strain_extrapolated_share``, a note, a PhysicsWarning above one half); ``slope`` is the rms slope
        xi(q) at ``result.q``. Called by the model; unchanged without measured factors."""
        return _strain.report(self, result, slope)


@doi("10.1088/0953-8984/17/1/R01")
@dataclass(frozen=True)
class Wet(Effect):
    r"""Wet road: no adhesion, optional sealing effect and hydrodynamic lift.

    * Adhesion off: the water film prevents direct rubber-road contact in the shear-stress sense.
    * Sealing (Persson et al., J. Phys.: Condens. Matter 17, R1 (2005), Sec. 9): water trapped in sealed
      pools of the road cavities carries part of the local load and smooths the short-wavelength roughness;
      modelled by scaling C(q) by (1 - ``seal_fraction``) for q > ``seal_q``.
    * Hydrodynamic lift by the pseudo-hydrodynamic bearing of the wet-road literature (tilted-pad bearing,
      e.g. Persson et al. 2005 Sec. 9 and the inclined-slider solution of Reynolds' equation):

      .. math::
          W_h = \frac{6 \alpha \eta V \beta l L^2}{H_{out}^2 (a - 1)^2}
                \left[\ln a - \frac{2 (a - 1)}{a + 1}\right],\qquad a = H_{in}/H_{out}

      which takes part of the load off the asperity contact: sigma_asp = sigma0 - W_h / (L l) (at least
      ``min_asperity_fraction`` of sigma0). Friction is normalised by the total load.

    Parameters
    ----------
    seal_fraction : float
        Fraction of the short-wavelength roughness removed by sealed pools (default 0: off).
    seal_q : float
        Wavevector above which sealing acts, rad/m (default 1e4).
    lift : float
        1 to switch the hydrodynamic lift on, 0 (default) off.
    eta : float
        Water viscosity, Pa s (default 1e-3).
    h_in, h_out : float
        Inlet and outlet film thickness, m (defaults 1e-3, 1e-4).
    contact_length, contact_width : float
        L and l of the contact patch, m (defaults 0.1, 0.1).
    alpha, beta : float
        Empirical factors of the bearing formula (defaults 1).
    """

    name = "wet"
    parameters = (
        Parameter("seal_fraction", 0.0, (0.0, 0.95), "1", "roughness fraction removed by sealed pools",
                  physical_limits=(0.0,)),
        Parameter("seal_q", 1.0e4, (1.0, 1.0e10), "rad/m", "wavevector above which sealing acts", log_scale=True,
                  plausible=(1.0e2, 1.0e8)),
        Parameter("alpha", 1.0, (0.0, 100.0), "1", "empirical factor alpha of the bearing lift",
                  plausible=(0.0, 10.0), physical_limits=(0.0,)),
    )
    seal_fraction: float = 0.0
    seal_q: float = 1.0e4
    lift: float = 0.0
    eta: float = 1.0e-3
    h_in: float = 1.0e-3
    h_out: float = 1.0e-4
    contact_length: float = 0.1
    contact_width: float = 0.1
    alpha: float = 1.0
    beta: float = 1.0
    min_asperity_fraction: float = 0.05

    def __post_init__(self):
        super().__post_init__()
        if self.lift and not (self.h_in > self.h_out > 0):
            raise InputError(f"wet: expected h_in > h_out > 0 m, got h_in={self.h_in}, h_out={self.h_out}")

    def lift_force(self, speed) -> np.ndarray:
        """Hydrodynamic load W_h (N) at speed(s) V (m/s)."""
        a = self.h_in / self.h_out
        bracket = math.log(a) - 2.0 * (a - 1.0) / (a + 1.0)
        L, l = self.contact_length, self.contact_width
        return (6.0 * self.alpha * self.eta * np.asarray(speed, dtype=float) * self.beta * l * L**2
                / (self.h_out**2 * (a - 1.0) ** 2) * bracket)

    def transform_conditions(self, conditions: Conditions) -> Conditions:
        cond = conditions.replace(wet=True)
        if self.lift:
            lifted = self.lift_force(cond.speed) / (self.contact_length * self.contact_width)
            floor = self.min_asperity_fraction * cond.nominal_pressure
            cond = cond.replace(pressure=np.maximum(cond.nominal_pressure - lifted, floor))
        return cond

    def transform_surface(self, surface, conditions):
        if self.seal_fraction <= 0:
            return surface
        return _Sealed(surface, self.seal_fraction, self.seal_q)

    def transform_result(self, result):
        if "adhesion" not in result.effects:
            return result
        return result.replace(notes=result.notes + ("wet: wet removes adhesion (no adhesive friction on a wet "
                                                    "road): the adhesion effect contributes mu_adhesion = 0",))


@dataclass(frozen=True, eq=False)
class _Sealed:
    """A PSD with C(q) scaled by (1 - fraction) above ``q_seal``."""

    base: object
    fraction: float
    q_seal: float

    @property
    def q_range(self):
        return self.base.q_range

    def C(self, q):
        q = np.asarray(q, dtype=float)
        return np.where(q > self.q_seal, 1.0 - self.fraction, 1.0) * self.base.C(q)

    def breakpoints(self):
        f = getattr(self.base, "breakpoints", None)
        return np.append(np.asarray(f() if callable(f) else (), dtype=float), self.q_seal)

    def __getattr__(self, name):
        if name in ("q_r", "extrapolated", "source"):
            return getattr(self.base, name)
        raise AttributeError(name)
