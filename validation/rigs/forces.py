"""Braking force and normal load of a trailer's measuring tire from its two load cells (Eqs. 8-9 of the trailer
article; the derivation and the checks built on it are in :mod:`validation.rigs.balance`)."""

from __future__ import annotations

import numpy as np

from frictioncite import doi

from .rig import TireMount

__all__ = ["braking_force", "normal_load", "GRAVITY", "TRAILER_2023"]

#: Standard gravity, m/s^2.
GRAVITY = 9.80665
#: Study on the influence of environmental conditions on road friction characteristics, Lubricants 11(7), 277
#: (2023): the trailer, its force balance (Eqs. 4-10), tire offsets and three-point identification.
TRAILER_2023 = "10.3390/lubricants11070277"


@doi(TRAILER_2023)
def braking_force(fxl, fxr, tire: TireMount) -> np.ndarray:
    r"""Braking force of a tire from its two longitudinal cells (Eq. 8 of the trailer article).

    :math:`F_B = (1 + l_L/l_c) F_{xL} + (1 - l_R/l_c) F_{xR}`, :math:`l_c` = ``tire.chain_arm_m`` (l_s unless the
    rig gives ``l_chain_m``).

    Parameters
    ----------
    fxl, fxr : array_like
        Longitudinal forces of the left and right load cells, N.
    tire : TireMount
        The tire's lever arms.

    Returns
    -------
    ndarray
        F_B, N.
    """
    lc = tire.chain_arm_m
    return (1.0 + tire.l_left_m / lc) * np.asarray(fxl, dtype=float) + \
        (1.0 - tire.l_right_m / lc) * np.asarray(fxr, dtype=float)


@doi(TRAILER_2023)
def normal_load(fzl, fzr, tire: TireMount) -> np.ndarray:
    r"""Normal load of a tire from its two vertical cells and the mass below them (Eq. 9 of the trailer article).

    :math:`N = (1 + l_L/l_s) F_{zL} + (1 - l_R/l_s) F_{zR} + m g`.

    Parameters
    ----------
    fzl, fzr : array_like
        Vertical forces of the left and right load cells (compression positive), N.
    tire : TireMount
        The tire's lever arms and ``mass_kg``.

    Returns
    -------
    ndarray
        N, newtons.
    """
    ls = tire.l_span_m
    return (1.0 + tire.l_left_m / ls) * np.asarray(fzl, dtype=float) + \
        (1.0 - tire.l_right_m / ls) * np.asarray(fzr, dtype=float) + tire.mass_kg * GRAVITY
