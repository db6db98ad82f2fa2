"""Analytic viscoelastic models: a constant complex modulus and the generalized Maxwell (Prony) solid.

Each material exposes ``E(omega, T)``: the complex Young's modulus at angular frequency ``omega`` (rad/s,
any sign, Im E odd in omega) and temperature ``T`` (deg C), vectorized, plus ``thermal`` properties. The
temperature enters through a shift law of :mod:`materials.laws` (:class:`WLF` is importable from here too).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .errors import InputError
from .laws import WLF, as_shift_law

__all__ = ["WLF", "Thermal", "ConstantModulus", "Prony"]


@dataclass(frozen=True)
class Thermal:
    """Thermal properties of the rubber (used by the flash temperature).

    Parameters
    ----------
    density : float
        Mass density rho, kg/m^3.
    specific_heat : float
        Specific heat c_p, J/(kg K).
    conductivity : float
        Thermal conductivity lambda, W/(m K).

    Examples
    --------
    >>> print(f"{Thermal().diffusivity:.3g} m^2/s")
    1.39e-07 m^2/s
    """

    density: float = 1200.0
    specific_heat: float = 1500.0
    conductivity: float = 0.25

    def __post_init__(self):
        for name in ("density", "specific_heat", "conductivity"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InputError(f"thermal.{name}: expected a positive number, got {v!r}")

    @property
    def diffusivity(self) -> float:
        """Thermal diffusivity D = lambda / (rho c_p), m^2/s."""
        return self.conductivity / (self.density * self.specific_heat)

    @property
    def heat_capacity(self) -> float:
        """Volumetric heat capacity rho c_p, J/(m^3 K)."""
        return self.density * self.specific_heat


@dataclass(frozen=True)
class ConstantModulus:
    """Frequency- and temperature-independent complex modulus, E = E' + i E'' sign(omega).

    Parameters
    ----------
    E_storage : float
        Storage modulus E', Pa (> 0).
    E_loss : float
        Loss modulus E'' at omega > 0, Pa (>= 0). Im E is odd in omega (zero at omega = 0).
    thermal : Thermal
        Thermal properties.
    """

    E_storage: float
    E_loss: float
    thermal: Thermal = field(default_factory=Thermal)

    def __post_init__(self):
        for name in ("E_storage", "E_loss"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
                raise InputError(f"{name}: expected a modulus in Pa (a number), got {v!r} ({type(v).__name__})")
        if not (math.isfinite(self.E_storage) and self.E_storage > 0):
            raise InputError(f"E_storage: expected a positive modulus in Pa, got {self.E_storage!r}")
        if not (math.isfinite(self.E_loss) and self.E_loss >= 0):
            raise InputError(f"E_loss: expected a non-negative modulus in Pa, got {self.E_loss!r}")

    def E(self, omega, T=None):
        """Complex Young's modulus, Pa, at ``omega`` (rad/s); ``T`` is ignored."""
        omega = np.asarray(omega, dtype=float)
        if np.isnan(omega).any():
            raise InputError("omega: NaN angular frequency (expected numbers in rad/s)")
        return self.E_storage + 1j * self.E_loss * np.sign(omega)


@dataclass(frozen=True, eq=False, repr=False)
class Prony:
    r"""Generalized Maxwell solid (Prony series) with WLF time-temperature superposition.

    .. math::
        E(\omega, T_{ref}) = E_\infty + \sum_i E_i \frac{i\omega\tau_i}{1 + i\omega\tau_i},
        \qquad E(\omega, T) = E(\omega a_T, T_{ref})

    Causal by construction (each term is a Debye relaxation); Im E is odd in omega.

    Parameters
    ----------
    E_inf : float
        Relaxed (rubbery) modulus, Pa (>= 0).
    E_i : array_like
        Relaxation strengths, Pa (>= 0).
    tau_i : array_like
        Relaxation times at T_ref, s (> 0).
    wlf : WLF, another shift law or mapping, optional
        Shift law (any object with ``log10_aT``: :class:`WLF`, :class:`materials.WLFArrhenius`,
        :class:`materials.TabulatedShift`, ...; or a mapping of WLF constants); ``None`` makes the material
        temperature-independent.
    thermal : Thermal
        Thermal properties.
    label : str
        Free-text description (e.g. ``"synthetic"`` or the data source); shown in reports.

    Examples
    --------
    >>> m = Prony(E_inf=1e6, E_i=[9e6], tau_i=[1e-3])     # one Debye term: relaxed 1 MPa, glassy 10 MPa
    >>> complex(m.E(1e3))                                  # at omega tau = 1: half of the term, in phase and out
    (5500000+4500000j)
    """

    E_inf: float
    E_i: np.ndarray
    tau_i: np.ndarray
    wlf: WLF | None = None
    thermal: Thermal = field(default_factory=Thermal)
    label: str = ""

    def __post_init__(self):
        E_i = np.array(self.E_i, dtype=float, copy=True).ravel()
        tau_i = np.array(self.tau_i, dtype=float, copy=True).ravel()
        if E_i.size != tau_i.size or E_i.size == 0:
            raise InputError(f"Prony: E_i and tau_i must have the same non-zero length, got {E_i.size}, {tau_i.size}")
        if not (np.all(np.isfinite(E_i)) and np.all(E_i >= 0)):
            raise InputError("Prony.E_i: expected finite non-negative moduli in Pa")
        if not (np.all(np.isfinite(tau_i)) and np.all(tau_i > 0)):
            raise InputError("Prony.tau_i: expected finite positive relaxation times in s")
        if not (math.isfinite(self.E_inf) and self.E_inf >= 0):
            raise InputError(f"Prony.E_inf: expected a non-negative modulus in Pa, got {self.E_inf!r}")
        E_i.setflags(write=False)
        tau_i.setflags(write=False)
        object.__setattr__(self, "E_i", E_i)
        object.__setattr__(self, "tau_i", tau_i)
        if self.wlf is not None and not isinstance(self.wlf, WLF):
            # any shift law (WLF+Arrhenius, Arrhenius, a tabulated a_T) or a mapping of its constants
            object.__setattr__(self, "wlf", as_shift_law(self.wlf, name="Prony.wlf"))

    @property
    def T_ref(self) -> float | None:
        """Reference temperature of ``tau_i``, deg C: the shift law's (None without one, when the material does not
        depend on temperature)."""
        return None if self.wlf is None else float(self.wlf.T_ref)

    def log10_aT(self, T):
        """log10 of the WLF shift factor (0 when no WLF is set or T is None)."""
        if self.wlf is None or T is None:
            return np.zeros_like(np.asarray(0.0 if T is None else T, dtype=float))
        return self.wlf.log10_aT(T)

    def E_reference(self, omega):
        """Complex modulus at the reference temperature, Pa (vectorized over any shape of ``omega``)."""
        return _maxwell_sum(self.E_inf, self.E_i, self.tau_i, np.asarray(omega, dtype=float))

    def E(self, omega, T=None):
        """Complex Young's modulus, Pa, at ``omega`` (rad/s) and temperature ``T`` (deg C).

        ``omega`` and ``T`` broadcast against each other. The reduced frequency is formed in log space, so
        that an extreme shift (cold rubber) saturates at the glassy modulus instead of overflowing; E(0) = E_inf.
        """
        omega = np.asarray(omega, dtype=float)
        if T is None:
            return self.E_reference(omega)
        return self.E_reference(_reduced_omega(omega, self.log10_aT(T)))

    @property
    def E_glassy(self) -> float:
        """High-frequency limit E_inf + sum E_i, Pa."""
        return float(self.E_inf + self.E_i.sum())

    def __repr__(self) -> str:
        lt = np.log10(self.tau_i)
        text = (f"Prony({self.E_i.size} terms, E_inf = {self.E_inf:.4g} Pa, E_glassy = {self.E_glassy:.4g} Pa, "
                f"tau 1e{lt.min():.3g}..1e{lt.max():.3g} s")
        if self.wlf is not None:
            d = getattr(self.wlf, "describe", None)
            text += f", {d() if callable(d) else type(self.wlf).__name__}"
        return text + (f", {self.label!r})" if self.label else ")")


# --------------------------------------------------------------------------------------------------------------
# helpers

#: |omega tau| is clipped here: the Debye terms are then exact to double precision (1/x^2 < 1e-300) and x^2
#: never overflows.
_X_MAX = 1e150


def _reduced_omega(omega, log10_aT):
    """omega * 10**log10_aT without overflow: the product is clipped to +-1e300 rad/s (E is glassy there).

    Where the product is representable it is formed directly, so that log10_aT = 0 returns omega exactly.
    """
    omega = np.asarray(omega, dtype=float)
    lg = np.asarray(log10_aT, dtype=float)
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        mag = np.log10(np.abs(omega)) + lg
        direct = omega * 10.0 ** np.minimum(lg, 300.0)
    clipped = np.sign(omega) * 10.0 ** np.minimum(mag, 300.0)
    out = np.where((mag < 299.0) & np.isfinite(direct), direct, clipped)
    return np.where(omega == 0.0, 0.0, out)


def _maxwell_sum(E_inf, E_i, tau_i, omega):
    r"""E_inf + sum_i E_i (i w tau_i)/(1 + i w tau_i), evaluated stably for any omega (rad/s)."""
    if np.isnan(omega).any():
        raise InputError("omega: NaN angular frequency (expected numbers in rad/s)")
    x = np.clip(omega[..., None] * tau_i, -_X_MAX, _X_MAX)
    d = 1.0 / (1.0 + x * x)
    real = (E_i * (x * x * d)).sum(axis=-1)
    imag = (E_i * (x * d)).sum(axis=-1)
    return (E_inf + real) + 1j * imag
