"""Result objects of the friction engine."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np
from ..notes import kinds

__all__ = ["FrictionResult", "FLASH_RISE_COMMENT"]

#: The comment that tables with a ``max_flash_temperature_K`` column carry above their header: the column is a
#: rise above the background temperature, not an absolute temperature.
FLASH_RISE_COMMENT = ("max_flash_temperature_K = flash temperature RISE of the hottest length scale above the "
                      "background temperature (K), not an absolute temperature")


@dataclass(frozen=True, eq=False)
class FrictionResult:
    """Friction, contact and per-scale detail for an array of sliding speeds.

    Scalar outputs (``mu``, ``mu_hysteresis``, ``mu_adhesion``, ``contact_area``, ``mean_separation``,
    ``penetration_depth``, ``max_flash_temperature``) have the shape of the ``speed`` argument (a float for a
    scalar speed). Per-scale arrays have shape (n_speed, n_q).

    Attributes
    ----------
    speed : ndarray
        Sliding speeds, m/s, shape (n_speed,).
    temperature : float or ndarray
        Background temperature T0, deg C (an array per speed when given per speed).
    pressure : float or ndarray
        Nominal pressure sigma0, Pa (an array per speed when given per speed).
    mu : float or ndarray
        Total friction coefficient: hysteresis + every effect's friction term.
    mu_hysteresis : float or ndarray
        Viscoelastic (hysteresis) contribution (Persson, J. Chem. Phys. 115, 3840 (2001), Eq. 1).
    mu_adhesion : float or ndarray
        Adhesive (contact-area shear) contribution; 0 without the adhesion effect.
    mu_terms : dict
        Every additional friction term by effect name.
    contact_area : float or ndarray
        Real contact area ratio A/A0 = P(q1).
    mean_separation : float or ndarray or None
        Average interfacial separation u_bar, m (None when not computed).
    penetration_depth : float or ndarray or None
        Penetration depth of the road asperities into the rubber, m (None when not computed).
    max_flash_temperature : float or ndarray
        Flash temperature RISE, K: the temperature of the hottest length scale minus the background temperature
        T0, max_q T(q) - T0 (Persson, J. Phys.: Condens. Matter 18, 7789 (2006)); not an absolute temperature
        (the hottest scale is at T0 + this rise, deg C). 0 without flash temperature. The same values as
        :attr:`flash_temperature_rise`; the name is kept for compatibility, and tables write it as
        ``max_flash_temperature_K``.
    flash_temperature_rise : float or ndarray
        (property) The flash temperature rise above T0, K: the same values as ``max_flash_temperature``, under
        a name that says what it is.
    q : ndarray (n_q,)
        Wavevector nodes, rad/m.
    area_q, G_q, temperature_q, dmu_dlnq : ndarray (n_speed, n_q)
        P(q), Persson's G(q), the temperature at scale q (deg C) and the hysteresis integrand d mu / d ln q.
    mu_cumulative : ndarray (n_speed, n_q)
        Hysteresis friction carried by the scales q0..q (the engine's integral of d mu up to each node; the last
        column is ``mu_hysteresis``). Differences between nodes are exact band contributions.
    load_share : float or ndarray
        Share of the nominal load carried by the asperity contact (1 unless a fluid film carries part of it,
        e.g. the hydrodynamic lift of ``Wet``); the hysteresis friction is normalised by the total load.
    error_estimate : float or ndarray
        Estimated relative error of ``mu_hysteresis`` from the wavevector quadrature: the difference from the
        same rules on every other node, divided by sqrt(21) (the rules are third order for smooth PSDs, second
        order across the kinks of a tabulated PSD), or the same estimate one level up (every fourth node) divided
        by a further 16 where that is larger, which catches a coarse and a fine result that agree by accident
        (the first term alone with the flash temperature; see ``benchmarks/accuracy.py``). Results whose estimate
        exceeds ``GridSettings.tolerance`` warn and say so in ``notes``.
    strain_extrapolated_share : float or ndarray or None
        With measured strain factors (``StrainSoftening(factors=...)``): the share of ``mu_hysteresis`` that comes
        from length scales whose local strain exceeds the largest measured strain, where the factors are
        extrapolated (see :mod:`persson.effects.strain`); None otherwise.
    modulus_extrapolated_share : float or ndarray or None
        For a compound measured over a known range of reduced frequencies (a :class:`materials.MasterCurve`, its
        ``frequency_range``): the share of ``mu_hysteresis`` that comes from frequencies outside that range, where
        the modulus is the master curve's extrapolation (each scale's angular band ``omega = q v cos(phi)``,
        weighted by ``cos(phi)`` as in the loss integral, at the scale's rubber temperature); None for a compound
        without a measured range (a Prony series given as such, a constant modulus).
    effects : tuple of str
        Names of the effects switched on.
    converged : bool
        Whether every self-consistent iteration converged (always True without flash temperature).
    iterations, residual : ndarray (n_speed,)
        Iterations of the flash-temperature iteration per speed, and its residual max |g(T) - T| over the scales
        (K; g the heat balance's map): below the tolerance where it converged, else that of the profile returned.
    notes : tuple of str
        Facts a reader must know (e.g. "PSD tail extrapolated past q_r").
    citations : tuple of str
        References (DOIs) of the physics used.
    """

    speed: np.ndarray
    temperature: float | np.ndarray
    pressure: float | np.ndarray
    mu: np.ndarray
    mu_hysteresis: np.ndarray
    mu_adhesion: np.ndarray
    contact_area: np.ndarray
    q: np.ndarray
    area_q: np.ndarray
    G_q: np.ndarray
    temperature_q: np.ndarray
    dmu_dlnq: np.ndarray
    mu_terms: dict = field(default_factory=dict)
    mu_cumulative: np.ndarray | None = None
    load_share: np.ndarray | float = 1.0
    error_estimate: np.ndarray | float | None = None
    mean_separation: np.ndarray | None = None
    penetration_depth: np.ndarray | None = None
    excited_layer_thickness: np.ndarray | None = None
    max_flash_temperature: np.ndarray | float = 0.0
    strain_extrapolated_share: np.ndarray | float | None = None
    modulus_extrapolated_share: np.ndarray | float | None = None
    effects: tuple = ()
    converged: bool = True
    iterations: np.ndarray | None = None
    residual: np.ndarray | None = None
    notes: tuple = ()
    citations: tuple = ()
    scalar: bool = False

    def __repr__(self) -> str:
        v = np.atleast_1d(self.speed)
        mu = np.atleast_1d(self.mu)
        speeds = f"v={v[0]:.3g} m/s" if v.size == 1 else f"{v.size} speeds {v.min():.3g}..{v.max():.3g} m/s"
        mus = f"mu={mu[0]:.4g}" if mu.size == 1 else f"mu {mu.min():.4g}..{mu.max():.4g}"
        area = np.atleast_1d(self.contact_area)
        extra = f", effects={list(self.effects)}" if self.effects else ""
        notes = f", {len(self.notes)} note(s)" if self.notes else ""
        return (f"FrictionResult({speeds}, {mus}, A/A0 {area.min():.3g}..{area.max():.3g}, "
                f"{self.q.size} q nodes{extra}{notes})")

    @property
    def flash_temperature_rise(self) -> np.ndarray | float:
        """Rise of the hottest length scale above the background temperature T0, K: max_q T(q) - T0 (0 without
        flash temperature); the same values as ``max_flash_temperature``."""
        return self.max_flash_temperature

    @property
    def note_kinds(self) -> tuple:
        """The kind of every note (:data:`persson.notes.KINDS`; None for a plain-text note)."""
        return kinds(self.notes)

    def replace(self, **changes) -> "FrictionResult":
        """Copy with fields changed (for effects' ``transform_result``)."""
        return dataclasses.replace(self, **changes)

    def as_table(self) -> dict[str, np.ndarray]:
        """Columns ``speed_m_s, T_C, pressure_Pa, mu, mu_hysteresis, mu_adhesion, contact_area``,
        ``max_flash_temperature_K`` (the flash temperature RISE above ``T_C``, K; not an absolute temperature)
        and, when computed, ``mean_separation_m``, ``penetration_depth_m``, ``strain_extrapolated_share``,
        ``modulus_extrapolated_share`` per speed."""
        cols = {
            "speed_m_s": self.speed,
            "T_C": np.broadcast_to(np.asarray(self.temperature, dtype=float), self.speed.shape),
            "pressure_Pa": np.broadcast_to(np.asarray(self.pressure, dtype=float), self.speed.shape),
            "mu": np.atleast_1d(self.mu),
            "mu_hysteresis": np.atleast_1d(self.mu_hysteresis),
            "mu_adhesion": np.atleast_1d(self.mu_adhesion),
            "contact_area": np.atleast_1d(self.contact_area),
            "max_flash_temperature_K": np.broadcast_to(np.atleast_1d(self.max_flash_temperature), self.speed.shape),
        }
        if self.mean_separation is not None:
            cols["mean_separation_m"] = np.atleast_1d(self.mean_separation)
        if self.penetration_depth is not None:
            cols["penetration_depth_m"] = np.atleast_1d(self.penetration_depth)
        if self.strain_extrapolated_share is not None:
            cols["strain_extrapolated_share"] = np.atleast_1d(self.strain_extrapolated_share)
        if self.modulus_extrapolated_share is not None:
            cols["modulus_extrapolated_share"] = np.atleast_1d(self.modulus_extrapolated_share)
        return cols
