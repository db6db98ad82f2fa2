"""Kinematics of a DRFT-style tester (a braked or driven wheel on a disk): slip ratio, sliding speed, wheel and disk speeds."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .._checks import finite_array, positive
from ..errors import InputError
from ._arrays import _broadcast, _sc, _speed_array
from .references import PACEJKA_BOOK

__all__ = ["Kinematics", "drft_kinematics", "drft_from_angular", "drft_speeds"]


# =========================================================================================================
# DRFT kinematics
# =========================================================================================================
@doi(PACEJKA_BOOK)
@dataclass(frozen=True, eq=False)
class Kinematics:
    r"""Wheel-on-disk (DRFT) or wheel-on-road kinematics of longitudinal slip, braking and driving.

    Speeds are magnitudes along the rolling direction. :math:`V` is the rolling reference speed: the surface
    speed of the counter-surface under the wheel centre (:math:`V = \Omega_{disk} R_{track}` on a DRFT, the
    vehicle speed on a road); :math:`V_w = \omega r` the circumferential speed of the wheel (r its effective
    rolling radius). Braking: :math:`V_w < V`; driving: :math:`V_w > V`; free rolling: :math:`V_w = V`.

    Attributes
    ----------
    speed : ndarray or float
        V, m/s (> 0).
    wheel_speed : ndarray or float
        :math:`V_w = \omega r`, m/s (>= 0).
    slip : ndarray or float
        Braking slip ratio :math:`s = (V - V_w)/V` (the convention of docs/slip.md and the ``slip`` column of measurements):
        0 free rolling, 1 locked wheel (pure sliding); negative when driving.
    longitudinal_slip : ndarray or float
        :math:`\kappa = (V_w - V)/V = -s`, the SAE J670 / ISO 8855 sign used by Pacejka's Magic Formula: positive
        when driving, -1 for a locked wheel.
    driving_slip : ndarray or float
        :math:`s_d = (V_w - V)/V_w` when driving (0 when braking): 0 free rolling, 1 a wheel spinning on a
        standing surface.
    sliding_speed : ndarray or float
        :math:`v_s = |V - V_w|`, m/s (= sV when braking).
    theoretical_slip : ndarray or float
        :math:`\theta = |V - V_w|/V_w`, the bristle displacement per unit distance from the leading edge of the
        brush model (:math:`s/(1-s)` braking, :math:`s_d` driving; inf for a locked wheel).
    braking, driving : ndarray or bool
        Which rows brake (:math:`V_w < V`) and which drive (:math:`V_w > V`).
    omega_wheel, omega_disk : ndarray or float or None
        Angular speeds, rad/s, when the radii are known.
    """

    speed: np.ndarray
    wheel_speed: np.ndarray
    slip: np.ndarray
    sliding_speed: np.ndarray
    omega_wheel: np.ndarray | None = None
    omega_disk: np.ndarray | None = None
    longitudinal_slip: np.ndarray | None = None
    driving_slip: np.ndarray | None = None
    theoretical_slip: np.ndarray | None = None
    braking: np.ndarray | None = None
    driving: np.ndarray | None = None


def _kinematics(Vw: np.ndarray, V: np.ndarray, **angular) -> Kinematics:
    vs = np.abs(V - Vw)
    s = (V - Vw) / V
    drive = Vw > V
    with np.errstate(divide="ignore", invalid="ignore"):
        theta = np.where(Vw > 0, vs / np.where(Vw > 0, Vw, 1.0), np.inf)
        sd = np.where(drive, (Vw - V) / np.where(drive, Vw, 1.0), 0.0)
    b = Vw < V
    return Kinematics(speed=_sc(V), wheel_speed=_sc(Vw), slip=_sc(s), sliding_speed=_sc(vs),
                      longitudinal_slip=_sc((Vw - V) / V), driving_slip=_sc(sd), theoretical_slip=_sc(theta),
                      braking=b if b.ndim else bool(b), driving=drive if drive.ndim else bool(drive), **angular)


@doi(PACEJKA_BOOK)
def drft_kinematics(wheel_speed, disk_speed) -> Kinematics:
    r"""Slip ratios and sliding speed from the wheel's circumferential speed and the disk's surface speed (m/s).

    ``disk_speed`` is V (the counter-surface speed under the wheel centre), ``wheel_speed`` :math:`V_w = \omega r`.
    Braking (:math:`V_w < V`) gives ``slip`` in (0, 1]; driving (:math:`V_w > V`) a negative ``slip`` and
    ``driving_slip`` in (0, 1) (see :class:`Kinematics` for every convention). The brush model
    (:func:`mu_slip`) takes the braking rows.

    Raises
    ------
    InputError
        ``disk_speed`` <= 0, ``wheel_speed`` < 0, or shapes that do not broadcast.
    """
    Vw = finite_array(wheel_speed, "wheel_speed")
    V = finite_array(disk_speed, "disk_speed")
    if np.any(V <= 0):
        raise InputError(f"disk_speed: expected a surface speed > 0 m/s, got {np.min(V):g}")
    if np.any(Vw < 0):
        raise InputError(f"wheel_speed: expected a circumferential speed >= 0 m/s, got {np.min(Vw):g}")
    Vw, V = _broadcast("wheel_speed, disk_speed", Vw, V)
    return _kinematics(Vw.astype(float), V.astype(float))


@doi(PACEJKA_BOOK)
def drft_from_angular(omega_wheel, omega_disk, *, wheel_radius: float, track_radius: float) -> Kinematics:
    r"""Kinematics from angular speeds (rad/s, magnitudes), the wheel's effective rolling radius r and the track
    radius R (the distance from the disk axis to the wheel centre line), m: :math:`V = \Omega_{disk} R`,
    :math:`V_w = \omega r`. See :func:`drft_kinematics`."""
    r = positive(wheel_radius, "wheel_radius")
    R = positive(track_radius, "track_radius")
    ww = finite_array(omega_wheel, "omega_wheel")
    wd = finite_array(omega_disk, "omega_disk")
    if np.any(wd <= 0):
        raise InputError(f"omega_disk: expected an angular speed > 0 rad/s, got {np.min(wd):g}")
    if np.any(ww < 0):
        raise InputError(f"omega_wheel: expected an angular speed >= 0 rad/s, got {np.min(ww):g}")
    ww, wd = _broadcast("omega_wheel, omega_disk", ww, wd)
    return _kinematics(ww * r, wd * R, omega_wheel=_sc(ww), omega_disk=_sc(wd))


@doi(PACEJKA_BOOK)
def drft_speeds(slip, speed, *, wheel_radius: float | None = None, track_radius: float | None = None) -> Kinematics:
    r"""Wheel speed, sliding speed (and angular speeds, when the radii are given) for a slip ratio and speed V.

    ``slip`` is the braking slip :math:`s = (V - V_w)/V <= 1` (0 free rolling, 1 locked wheel; negative values
    are driving: :math:`V_w = (1 - s)V > V`), ``speed`` V > 0 m/s.
    """
    s = finite_array(slip, "slip")
    if np.any(s > 1):
        raise InputError(f"slip: expected slip ratios s = (V - omega r)/V <= 1 (1 = locked wheel), got "
                         f"{s[s > 1].ravel()[0]:g}")
    V = _speed_array(speed)
    s, V = _broadcast("slip, speed", s, V)
    Vw = (1.0 - s) * V
    ang = {}
    if wheel_radius is not None:
        ang["omega_wheel"] = _sc(Vw / positive(wheel_radius, "wheel_radius"))
    if track_radius is not None:
        ang["omega_disk"] = _sc(V / positive(track_radius, "track_radius"))
    return _kinematics(Vw.astype(float), V.astype(float), **ang)
