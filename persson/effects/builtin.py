"""Built-in effects: flash temperature, adhesion, microtexture, strain softening, wet road.

Each is a frozen dataclass; its documented parameters (:class:`~persson.effects.base.Parameter`) are the
fields that diagnosis refits. Formulas cite their sources.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np
from scipy.special import erfcx

from frictioncite import doi

from .. import _kernels
from ..errors import ConvergenceWarning, InputError
from .base import Conditions, Effect, Parameter, SolverState

__all__ = ["FlashTemperature", "Adhesion", "Microtexture", "StrainSoftening", "Wet"]


@doi("10.1088/0953-8984/18/32/025")
@dataclass(frozen=True)
class FlashTemperature(Effect):
    r"""Persson's multiscale flash temperature, solved self-consistently with :math:`E(\omega, T_q)`.

    .. math::
        T_q = T_0 + \int_{q_0}^{q} dq'\, g(q, q') f(q'), \qquad
        f(q) = \frac{v q^4 C(q)}{\rho c_p}\frac{P(q)}{P(q_m)}\int_0^{2\pi} d\phi\,\cos\phi\,
        \frac{\mathrm{Im}\,E(q v \cos\phi, T_q)}{1 - \nu^2}

    with the heat kernel :math:`g` of :func:`persson._kernels.heat_kernel` (closed form, erfcx) and
    :math:`D = \lambda/(\rho c_p)` (Persson, J. Phys.: Condens. Matter 18, 7789 (2006), Eqs. 20-27).
    The heat produced at scale q' raises the temperature at the (smaller) scales q >= q'; it is produced in
    the macro-asperity contact regions, of area fraction P(q_m), during the contact time t0 = d / v of a
    macro-asperity contact of diameter d. Thermal properties come from ``material.thermal``.

    Parameters
    ----------
    macro_scale_ratio : float
        q_m / q0, the magnification at which the macro-asperity contact regions are defined (default 2).
    contact_diameter : float
        Diameter d of a macro-asperity contact region, m; 0 (default) means pi / q_m (half the wavelength).
    tol : float
        Convergence tolerance on max |T_new - T| over the scales, K (default 1e-3).
    max_iter : int
        Largest number of fixed-point iterations (default 300).
    """

    name = "flash_temperature"
    solver_role = "temperature"
    parameters = (
        Parameter("macro_scale_ratio", 2.0, (1.0, 100.0), "1", "q_m / q0 of the macro-asperity contact regions",
                  log_scale=True),
        Parameter("contact_diameter", 0.0, (0.0, 1.0), "m", "macro-asperity contact diameter (0: pi / q_m)"),
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

    def solve_temperature(self, *, q, C, lq10, lv10, q4C, wq, lcphi, cphi, wphi, table, shift_table, scale,
                          gamma, nu, conditions: Conditions, material, out, solved_type):
        """Run the self-consistent solver (called by the model; see :func:`persson._kernels.flash_kernel`)."""
        thermal = getattr(material, "thermal", None)
        if thermal is None:
            raise InputError("flash_temperature: the material has no thermal properties (material.thermal)")
        if not hasattr(material, "log10_aT"):
            raise InputError("flash_temperature: the material has no temperature dependence (log10_aT); "
                             "the flash temperature would not change the friction")
        G, P, loss, dmu, mu = out
        v = 10.0**lv10
        q_m = self.macro_scale_ratio * q[0]
        pos = float(np.interp(math.log(q_m), np.log(q), np.arange(q.size)))  # fractional node index of q_m
        i_m = min(int(pos), q.size - 1)
        f_m = pos - i_m
        d = self.contact_diameter if self.contact_diameter > 0 else math.pi / q_m
        D = thermal.diffusivity
        a = D * d / v
        EX = erfcx(2.0 * q[None, :] * np.sqrt(a)[:, None])
        pressure = np.broadcast_to(np.asarray(conditions.pressure, dtype=float), v.shape)
        heat_factor = np.ascontiguousarray(pressure / thermal.heat_capacity)
        T0 = np.ascontiguousarray(np.broadcast_to(np.asarray(conditions.temperature, dtype=float), v.shape))
        nv, nq = G.shape
        T_q = np.empty((nv, nq))
        iters = np.zeros(nv, dtype=np.int64)
        res = np.zeros(nv)
        _kernels.flash_kernel(q, lq10, lv10, v, q4C, wq, lcphi, cphi, wphi, table.lw0, 1.0 / table.dlw,
                              table.ln_re, table.ln_im, scale, gamma, T0, shift_table.T_lo,
                              1.0 / shift_table.dT, shift_table.shift, shift_table.vshift, EX, a, D, heat_factor,
                              i_m, f_m, self.tol,
                              int(self.max_iter), G, P, loss, dmu, mu, T_q, iters, res)
        top = shift_table.T_hi
        if np.any(T_q > top):
            warnings.warn(f"flash temperature exceeds the tabulated range (T > {top:g} C); the modulus is "
                          "clamped there: raise GridSettings.max_temperature_rise", ConvergenceWarning,
                          stacklevel=4)
        ok = res < self.tol
        return solved_type(q, G, P, T_q, dmu, loss, mu, bool(ok.all()), ok, iters, res)


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

    Parameters
    ----------
    tau_f0 : float
        Peak frictional shear stress, Pa (default 2 MPa).
    c : float
        Width parameter of the log-normal speed dependence, 1/decade^2 (default 0.1).
    v_ref : float
        Speed of the peak at the material's reference temperature, m/s (default 1e-2).
    """

    name = "adhesion"
    term_kind = "adhesion"
    parameters = (
        Parameter("tau_f0", 2.0e6, (0.0, 50.0e6), "Pa", "peak frictional shear stress in the real contact"),
        Parameter("c", 0.1, (0.0, 2.0), "1/decade^2", "width of the log-normal speed dependence"),
        Parameter("v_ref", 1.0e-2, (1e-12, 1e6), "m/s", "speed of the shear-stress peak at T_ref",
                  log_scale=True),
    )
    tau_f0: float = 2.0e6
    c: float = 0.1
    v_ref: float = 1.0e-2

    def shear_stress(self, speed, temperature, material) -> np.ndarray:
        """tau_f(v, T), Pa, for speeds (m/s) and temperatures (deg C) broadcast together."""
        log_aT = material.log10_aT(temperature) if hasattr(material, "log10_aT") else 0.0
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
    squares in log-log, unless given. A :class:`surfaces.SelfAffine` continues its own power law.

    Parameters
    ----------
    q1 : float
        New short-distance cut-off, rad/m (default 1e7 rad/m, i.e. wavelengths down to 0.6 um).
    hurst : float
        Hurst exponent of the tail; 0 (default) means fitted.
    """

    name = "microtexture"
    parameters = (
        Parameter("q1", 1.0e7, (1.0e2, 1.0e10), "rad/m", "short-distance cut-off of the extrapolated tail",
                  log_scale=True),
        Parameter("hurst", 0.0, (0.0, 1.0), "1", "Hurst exponent of the tail (0: fitted)"),
    )
    q1: float = 1.0e7
    hurst: float = 0.0

    def transform_surface(self, surface, conditions):
        lo, hi = (float(x) for x in surface.q_range)
        if self.q1 <= hi * (1 + 1e-12):
            return surface.with_cutoff(q1=self.q1) if self.q1 > lo else surface
        if not hasattr(surface, "extrapolate"):
            raise InputError(f"microtexture: the surface {type(surface).__name__} cannot extrapolate its tail")
        try:
            return surface.extrapolate(self.q1, hurst=self.hurst if self.hurst > 0 else None)
        except ValueError as exc:
            raise InputError(f"microtexture: {exc}; give hurst= explicitly") from None


@dataclass(frozen=True)
class StrainSoftening(Effect):
    r"""Large-strain modulus: constant factors on E' and E'' (Payne effect of filled rubber).

    .. math:: E_{large}(\omega, T) = f\, E'(\omega, T) + i\, g\, E''(\omega, T)

    In tread compounds the asperity-induced strains are of order unity, where the storage modulus of a filled
    compound drops to a fraction of its small-strain value (Payne, J. Appl. Polym. Sci. 6, 57 (1962);
    Lorenz, Persson et al., Eur. Phys. J. E 38, 1 (2015) use a strain-softened master curve for the
    friction). The factors are taken constant over frequency.

    Parameters
    ----------
    storage_factor : float
        f, factor on E' (default 0.5).
    loss_factor : float
        g, factor on E'' (default 0.7).
    """

    name = "strain_softening"
    parameters = (
        Parameter("storage_factor", 0.5, (0.05, 1.0), "1", "factor f on E' at large strain"),
        Parameter("loss_factor", 0.7, (0.05, 1.5), "1", "factor g on E'' at large strain"),
    )
    storage_factor: float = 0.5
    loss_factor: float = 0.7

    def transform_material(self, material, conditions):
        import materials

        return materials.StrainSoftened(material, self.storage_factor, self.loss_factor)


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
        Parameter("seal_fraction", 0.0, (0.0, 0.95), "1", "roughness fraction removed by sealed pools"),
        Parameter("seal_q", 1.0e4, (1.0, 1.0e10), "rad/m", "wavevector above which sealing acts", log_scale=True),
        Parameter("alpha", 1.0, (0.0, 100.0), "1", "empirical factor alpha of the bearing lift"),
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

    def __getattr__(self, name):
        if name in ("q_r", "extrapolated", "source"):
            return getattr(self.base, name)
        raise AttributeError(name)
