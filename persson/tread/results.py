"""Results of the tread-element tool: one (slip, speed) point, a mu(slip, speed) map, a ranking of surfaces."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["TreadResult", "SlipMap", "Ranking"]


@dataclass(frozen=True, eq=False)
class TreadResult:
    """Friction of a tyre tread on a road at one slip ratio and speed (:func:`persson.tread.simulate`).

    Attributes
    ----------
    mu : float
        Steady friction coefficient: the time average of ``mu_t`` after the transient.
    mu_std : float
        Standard error of ``mu`` from block averages (statistical, over the road sampled).
    time : ndarray
        Times of the steps, s.
    mu_t : ndarray
        Friction coefficient at each step (Eq. 5).
    contact_fraction : float
        Mean fraction of the rubber elements in contact with the road (steady part).
    contact_t : ndarray
        Contact fraction at each step.
    penetration : float
        Mean compression of the contacting elements (how deep the road's asperities indent the tread), m.
    penetration_t : ndarray
        Penetration at each step, m.
    slip, speed, sliding_speed : float
        Slip ratio s, vehicle speed V (m/s) and sliding speed s V (m/s).
    temperature : float
        Background temperature, deg C.
    lift : float
        Hydrodynamic lift of the water film, N (0 when dry).
    transient : float
        Time left out of the averages, s.
    load_residual : float
        Largest relative error of the load balance (Eq. 4) over the steps.
    stuck_fraction : float
        Share of the contact element-steps that adhered (force inside the friction cone: the brush model's
        adhesion zone).
    jammed_fraction : float
        Share of the contact element-steps on flanks too steep for Eq. 2 (denominator capped).
    jammed_share : float
        The part of ``mu`` carried by those capped contacts: it scales as 1/jam_min, so a result where it is a
        sizeable part of ``mu`` measures the cap rather than the road (an AccuracyWarning says so above 5 %).
    stiffness, damping, shear_stiffness : float
        Normal stiffness K (N/m), damping C (N s/m) and shear stiffness (N/m) of one element.
    element_size : float
        Element spacing along the patch, m.
    dt : float
        Time step, s.
    final_state : dict
        The tread after the last step, one entry per element: ``x`` (road position of the tip, m), ``xi``
        (position in the footprint from the leading edge, m), ``y`` (lateral position of its row, m), ``row``,
        ``compression`` (m), ``force`` (N), ``rubber`` (bool); and ``element_size``, ``row_width`` (m).
    notes : tuple of str
    citations : tuple of str
    """

    mu: float
    mu_std: float
    time: np.ndarray
    mu_t: np.ndarray
    contact_fraction: float
    contact_t: np.ndarray
    penetration: float
    penetration_t: np.ndarray
    slip: float
    speed: float
    sliding_speed: float
    temperature: float
    lift: float = 0.0
    transient: float = 0.0
    load_residual: float = 0.0
    stuck_fraction: float = 0.0
    jammed_fraction: float = 0.0
    stiffness: float = float("nan")
    damping: float = float("nan")
    shear_stiffness: float = float("nan")
    element_size: float = float("nan")
    dt: float = float("nan")
    final_state: dict = field(default_factory=dict, repr=False)
    notes: tuple = ()
    citations: tuple = ()
    jammed_share: float = 0.0

    def __repr__(self) -> str:
        return (f"TreadResult(mu={self.mu:.4g} +- {self.mu_std:.2g}, slip={self.slip:g}, speed={self.speed:g} m/s, "
                f"contact {self.contact_fraction:.1%}, {self.time.size} steps, {len(self.notes)} notes)")


@dataclass(frozen=True, eq=False)
class SlipMap:
    """mu over slip ratios and speeds (:func:`persson.tread.slip_map`).

    Attributes
    ----------
    slips : ndarray, shape (n_slip,)
    speeds : ndarray, shape (n_speed,)
        Vehicle speeds, m/s.
    mu, mu_std : ndarray, shape (n_speed, n_slip)
        Steady friction and its standard error.
    contact_fraction, penetration : ndarray, shape (n_speed, n_slip)
    lift : ndarray, shape (n_speed, n_slip)
        Hydrodynamic lift, N.
    peak_mu, peak_slip : ndarray, shape (n_speed,)
        ABS peak: the largest mu over the slips, and the slip where it is (a grid value).
    peak_std : ndarray, shape (n_speed,)
        Standard error of ``peak_mu``.
    locked_mu, locked_std : ndarray, shape (n_speed,)
        Locked wheel (slip 1) and its standard error.
    temperature : float
    notes : tuple of str
    citations : tuple of str
    jammed_share : ndarray, shape (n_speed, n_slip) or None
        The part of ``mu`` carried by contacts capped at the self-locking limit of Eq. 2 (see
        :class:`TreadResult`).
    """

    slips: np.ndarray
    speeds: np.ndarray
    mu: np.ndarray
    mu_std: np.ndarray
    contact_fraction: np.ndarray
    penetration: np.ndarray
    lift: np.ndarray
    peak_mu: np.ndarray
    peak_slip: np.ndarray
    peak_std: np.ndarray
    locked_mu: np.ndarray
    locked_std: np.ndarray
    temperature: float
    notes: tuple = ()
    citations: tuple = ()
    jammed_share: np.ndarray | None = None

    def as_table(self) -> dict[str, np.ndarray]:
        """Long table: one row per (speed, slip): ``speed_m_s, slip, mu, mu_std, contact_fraction,
        penetration_m, lift_N``."""
        S, V = np.meshgrid(self.slips, self.speeds)
        return {"speed_m_s": V.ravel(), "slip": S.ravel(), "mu": self.mu.ravel(), "mu_std": self.mu_std.ravel(),
                "contact_fraction": self.contact_fraction.ravel(), "penetration_m": self.penetration.ravel(),
                "lift_N": self.lift.ravel()}

    def summary_table(self) -> dict[str, np.ndarray]:
        """One row per speed: ``speed_m_s, peak_mu, peak_std, peak_slip, locked_mu, locked_std``."""
        return {"speed_m_s": self.speeds, "peak_mu": self.peak_mu, "peak_std": self.peak_std,
                "peak_slip": self.peak_slip, "locked_mu": self.locked_mu, "locked_std": self.locked_std}

    def __repr__(self) -> str:
        return (f"SlipMap({self.speeds.size} speeds x {self.slips.size} slips, peak mu "
                f"{np.round(self.peak_mu, 3).tolist()}, locked mu {np.round(self.locked_mu, 3).tolist()})")


@dataclass(frozen=True, eq=False)
class Ranking:
    """Surfaces ranked by ABS-peak and locked-wheel friction (:func:`persson.tread.rank_surfaces`).

    Attributes
    ----------
    names : tuple of str
        The surfaces, in the order given.
    speed : float
        Vehicle speed, m/s.
    peak_mu, peak_std, locked_mu, locked_std : ndarray, shape (n_surfaces,)
        Predicted friction and standard errors.
    peak_rank, locked_rank : ndarray of int
        Rank of each surface, 1 = highest friction.
    measured_peak, measured_locked : ndarray or None
        The measurements given, same order (NaN where a surface has none).
    spearman, kendall : dict
        ``{"peak": (rho, p_value), "locked": (rho, p_value)}`` against the measurements (empty without).
    maps : dict
        name -> :class:`SlipMap`.
    notes : tuple of str
    citations : tuple of str
    """

    names: tuple
    speed: float
    peak_mu: np.ndarray
    peak_std: np.ndarray
    locked_mu: np.ndarray
    locked_std: np.ndarray
    peak_rank: np.ndarray
    locked_rank: np.ndarray
    measured_peak: np.ndarray | None = None
    measured_locked: np.ndarray | None = None
    spearman: dict = field(default_factory=dict)
    kendall: dict = field(default_factory=dict)
    maps: dict = field(default_factory=dict, repr=False)
    notes: tuple = ()
    citations: tuple = ()

    def as_table(self) -> dict[str, np.ndarray]:
        """One row per surface (``surface`` as index 0..n-1 order of ``names``)."""
        out = {"peak_mu": self.peak_mu, "peak_std": self.peak_std, "peak_rank": self.peak_rank,
               "locked_mu": self.locked_mu, "locked_std": self.locked_std, "locked_rank": self.locked_rank}
        if self.measured_peak is not None:
            out["measured_peak"] = self.measured_peak
        if self.measured_locked is not None:
            out["measured_locked"] = self.measured_locked
        return out
