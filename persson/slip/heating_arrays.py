"""The arrays the patch-heating kernels take (:mod:`persson.slip.heating_kernels`), grouped in named tuples built
once per call, each field with its shape and unit: the rows of a patch computation, the patch, and the friction
lattice with its temperature coordinate (:class:`persson.slip.heating_tables._Tables`); and what the march returns.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

__all__ = ["PatchRows", "Patch", "FrictionLattice", "TemperatureAxis", "MarchOutputs"]


class PatchRows(NamedTuple):
    """The rows of a patch computation (one slip, speed, temperature and pressure each).

    Parameters
    ----------
    sweep : ndarray of int64 (n,)
        The (T0, sigma0) sweep of each row (its friction table).
    log_speed : ndarray (n,)
        ln v_s, v_s the sliding speed in m/s.
    stick_slope : ndarray (n,)
        a = k l theta / sigma0, the slope of the bristle stress k u / sigma0 in x / l (theta = s / (1 - s));
        inf for pure sliding (s = 1).
    heat_factor : ndarray (n,)
        Lambda = eta sigma0 v_s sqrt(l) / (sqrt(pi) (e_r sqrt(V_r) + e_c sqrt(V))), K
        (:meth:`persson.slip.heating.PatchHeating.heat_factor`).
    """

    sweep: np.ndarray
    log_speed: np.ndarray
    stick_slope: np.ndarray
    heat_factor: np.ndarray


class Patch(NamedTuple):
    """The contact patch on its nodes.

    Parameters
    ----------
    xi : ndarray (N,)
        Uniform nodes x / l from the leading edge (0) to the trailing edge (1).
    g : ndarray (N,)
        Pressure p(x) / sigma0 at the nodes.
    abel : ndarray (2, N)
        Product-integration weights of the Abel kernel on a grid of unit spacing
        (:func:`persson.slip.heating_tables._unit_weights`; column 0 unused).
    """

    xi: np.ndarray
    g: np.ndarray
    abel: np.ndarray


class MarchOutputs(NamedTuple):
    """What the march returns per row.

    Parameters
    ----------
    mu : ndarray (n,)
        Friction coefficient of the wheel.
    stick_fraction : ndarray (n,)
        x_c / l, the end of the stick zone.
    rise : ndarray (n,)
        Largest background temperature rise along the patch, K.
    table_use : ndarray (n,)
        Highest (y + h) reached over the top of the row's temperature table, h its spacing (> 1: a point lies in
        the table's top interval, where its interpolation is one-sided, or above the top: the table must grow).
    temperature, shear, mu_profile : ndarray (n, N) or (1, N)
        Background temperature (deg C), shear / sigma0 and local friction at the nodes (one unused row without
        profiles).
    """

    mu: np.ndarray
    stick_fraction: np.ndarray
    rise: np.ndarray
    table_use: np.ndarray
    temperature: np.ndarray
    shear: np.ndarray
    mu_profile: np.ndarray


class FrictionLattice(NamedTuple):
    """The friction tables of every (T0, sigma0) sweep over (ln v_s, g = p / sigma0, y)
    (:class:`persson.slip.heating_tables._Tables`).

    Parameters
    ----------
    log_speed : ndarray (n_v,)
        ln v_s of the speed nodes of all sweeps, m/s; sweep c has the nodes ``v_offset[c]`` .. ``v_offset[c+1] - 1``.
    v_offset : ndarray of int64 (n_sweeps + 1,)
        Where each sweep's speed nodes start.
    g_nodes : ndarray (n_g,)
        Pressure nodes p / sigma0, increasing.
    values : ndarray
        Friction coefficients: for speed node i, a block of shape (n_g, ``n_temperature[i]``) at
        ``value_offset[i]``, its columns the temperature nodes y_k = k h.
    value_offset : ndarray of int64 (n_v + 1,)
        Where each speed node's block starts.
    n_temperature : ndarray of int64 (n_v,)
        Temperature nodes of each speed node (1: the T0 slice alone).
    """

    log_speed: np.ndarray
    v_offset: np.ndarray
    g_nodes: np.ndarray
    values: np.ndarray
    value_offset: np.ndarray
    n_temperature: np.ndarray


class TemperatureAxis(NamedTuple):
    """The temperature coordinate y(T) = log10 a_T(T0) - log10 a_T(T) of the lattice, per sweep.

    Parameters
    ----------
    T0 : ndarray (n_sweeps,)
        Background temperature of each sweep, deg C.
    h : float
        Spacing of the lattice in y, decades of a_T.
    cap : float
        Largest temperature rise tabulated, K (hotter points are evaluated at the cap).
    mu_max : ndarray (n_sweeps,)
        Largest friction in each sweep's table (bounds the bisection of
        :func:`persson.slip.heating_kernels._node_temperature`).
    y_fine : ndarray (n_sweeps, n_fine)
        y at T0 + k ``dT_fine``, decades.
    dT_fine : float
        Step of ``y_fine``, K.
    """

    T0: np.ndarray
    h: float
    cap: float
    mu_max: np.ndarray
    y_fine: np.ndarray
    dT_fine: float
