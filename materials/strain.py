r"""Strain softening (Payne effect): large-strain moduli from small-strain master curves.

Persson's friction theory uses the small-strain (linear) modulus, but the rubber in asperity contacts is
strained by order unity; Lorenz et al. (2015) and Persson (2001) replace it by an effective large-strain
modulus obtained from DMA strain sweeps,

.. math:: E'(\omega, T; \varepsilon) = f(\varepsilon)\, E'(\omega, T),\qquad
          E''(\omega, T; \varepsilon) = g(\varepsilon)\, E''(\omega, T),

with :math:`f, g` the storage and loss moduli of a strain sweep normalised by their small-strain values,
assumed independent of frequency and temperature.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .errors import InputError

__all__ = ["StrainSoftening", "StrainSoftened", "strain_softening_from_sweep"]


@doi("10.1063/1.4919221", "10.1063/1.1388626")
@dataclass(frozen=True, eq=False)
class StrainSoftening:
    r"""Softening factors f(strain) on E' and g(strain) on E'' (1 at small strain).

    Interpolated linearly in :math:`\log\varepsilon`, held constant outside the tabulated strains.

    Attributes
    ----------
    strain : ndarray
        Strain amplitudes (dimensionless, > 0, increasing).
    storage_factor, loss_factor : ndarray
        f and g at those strains (> 0).
    source : str
        Where they come from.
    """

    strain: np.ndarray
    storage_factor: np.ndarray
    loss_factor: np.ndarray
    source: str = ""

    def __post_init__(self):
        s = np.array(self.strain, dtype=float).ravel()
        f = np.array(self.storage_factor, dtype=float).ravel()
        g = np.array(self.loss_factor, dtype=float).ravel()
        if not (s.size == f.size == g.size and s.size > 0):
            raise InputError(f"StrainSoftening: strain, storage_factor, loss_factor must have the same non-zero "
                             f"length, got {s.size}, {f.size}, {g.size}")
        for name, a in (("strain", s), ("storage_factor", f), ("loss_factor", g)):
            if not (np.all(np.isfinite(a)) and np.all(a > 0)):
                raise InputError(f"StrainSoftening.{name}: expected finite positive values, got {a}")
        order = np.argsort(s)
        s, f, g = s[order], f[order], g[order]
        if np.any(np.diff(s) == 0):
            raise InputError("StrainSoftening.strain: repeated strain amplitudes")
        for name, a in (("strain", s), ("storage_factor", f), ("loss_factor", g)):
            a.setflags(write=False)
            object.__setattr__(self, name, a)

    @classmethod
    def constant(cls, storage_factor: float, loss_factor: float) -> "StrainSoftening":
        """Strain-independent factors f, g (e.g. taken at the typical contact strain)."""
        return cls(np.array([1.0]), np.array([storage_factor]), np.array([loss_factor]), source="constant")

    def factors(self, strain):
        """(f, g) at strain amplitude(s) ``strain``."""
        e = np.asarray(strain, dtype=float)
        if not (np.all(np.isfinite(e)) and np.all(e > 0)):
            raise InputError(f"strain: expected positive strain amplitudes, got {strain!r}")
        if self.strain.size == 1:
            return np.full(e.shape, self.storage_factor[0]), np.full(e.shape, self.loss_factor[0])
        x = np.log(e)
        xs = np.log(self.strain)
        return np.interp(x, xs, self.storage_factor), np.interp(x, xs, self.loss_factor)


@doi("10.1063/1.4919221", "10.1063/1.1388626")
@dataclass(frozen=True, eq=False)
class StrainSoftened:
    r"""A material with E' scaled by ``storage_factor`` and E'' by ``loss_factor`` (large-strain modulus).

    .. math:: E_{\varepsilon}(\omega, T) = f\,\mathrm{Re}\,E(\omega, T) + i\, g\,\mathrm{Im}\,E(\omega, T)

    Exposes the same interface as the material it wraps: ``E(omega, T)``, ``thermal`` and, when the wrapped
    material has it, ``log10_aT`` (``hasattr`` is False otherwise).

    Parameters
    ----------
    material : object
        Anything with ``E(omega, T)``.
    storage_factor, loss_factor : float
        f and g (> 0).
    """

    material: object
    storage_factor: float = 1.0
    loss_factor: float = 1.0

    def __post_init__(self):
        if not callable(getattr(self.material, "E", None)):
            raise InputError("StrainSoftened: material must have a method E(omega, T)")
        for name in ("storage_factor", "loss_factor"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float, np.floating)) and math.isfinite(v) and v > 0):
                raise InputError(f"StrainSoftened.{name}: expected a positive number, got {v!r}")

    @classmethod
    def from_softening(cls, material, softening: StrainSoftening, strain: float) -> "StrainSoftened":
        """Factors f(strain), g(strain) of ``softening`` at one strain amplitude."""
        f, g = softening.factors(float(strain))
        return cls(material, float(f), float(g))

    def E(self, omega, T=None):
        """Complex large-strain Young's modulus, Pa."""
        E = self.material.E(omega, T)
        return self.storage_factor * E.real + 1j * self.loss_factor * E.imag

    @property
    def thermal(self):
        return self.material.thermal

    @property
    def log10_aT(self):
        # a property, so that hasattr() reflects the wrapped material
        return self.material.log10_aT

    @property
    def log10_bT(self):
        # vertical shift of the wrapped material (AttributeError, i.e. none, when it has none)
        return self.material.log10_bT

    @property
    def T_ref(self):
        return self.material.T_ref

    @property
    def wlf(self):
        return self.material.wlf


@doi("10.1063/1.4919221")
def strain_softening_from_sweep(dma, *, reference_strain: float | None = None) -> StrainSoftening:
    r"""Softening factors from DMA strain sweeps (points with a ``strain`` column).

    Points are grouped by isotherm and frequency; in each group E' and E'' are divided by their values at
    the smallest strain (or at ``reference_strain``, interpolated in log strain), giving
    :math:`f(\varepsilon) = E'(\varepsilon)/E'(\varepsilon_0)` and :math:`g = E''(\varepsilon)/E''(\varepsilon_0)`
    (Lorenz et al. 2015). Groups are combined by the median at each strain of the union of the strain grids
    (each group interpolated in log strain within its own range).

    Raises
    ------
    InputError
        No ``strain`` column, or no group with at least two strains.
    """
    if getattr(dma, "strain", None) is None:
        raise InputError(f"{dma.source}: no 'strain' column; strain softening needs strain sweeps")
    groups = {}
    for idx in dma.isotherm_indices():
        for f in np.unique(dma.f_Hz[idx]):
            g = idx[dma.f_Hz[idx] == f]
            if np.unique(dma.strain[g]).size >= 2:
                groups[(int(dma.isotherm[g[0]]), float(f))] = g[np.argsort(dma.strain[g])]
    if not groups:
        raise InputError(f"{dma.source}: no isotherm/frequency with at least two strain amplitudes")
    grid = np.unique(np.concatenate([dma.strain[g] for g in groups.values()]))
    F, G = [], []
    for g in groups.values():
        xs = np.log(dma.strain[g])
        e0 = dma.strain[g][0] if reference_strain is None else reference_strain
        x0 = math.log(e0)
        if not xs[0] - 1e-12 <= x0 <= xs[-1] + 1e-12:
            raise InputError(f"reference_strain: {e0} lies outside a sweep ({dma.strain[g][0]:g} to "
                             f"{dma.strain[g][-1]:g})")
        E1_0 = np.exp(np.interp(x0, xs, np.log(dma.E_storage[g])))
        E2_0 = np.exp(np.interp(x0, xs, np.log(dma.E_loss[g])))
        inside = (np.log(grid) >= xs[0] - 1e-12) & (np.log(grid) <= xs[-1] + 1e-12)
        f = np.full(grid.size, np.nan)
        gg = np.full(grid.size, np.nan)
        f[inside] = np.interp(np.log(grid[inside]), xs, dma.E_storage[g]) / E1_0
        gg[inside] = np.interp(np.log(grid[inside]), xs, dma.E_loss[g]) / E2_0
        F.append(f)
        G.append(gg)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        f_med = np.nanmedian(np.array(F), axis=0)
        g_med = np.nanmedian(np.array(G), axis=0)
    return StrainSoftening(grid, f_med, g_med, source=f"strain sweeps in {dma.source} ({len(groups)} sweeps)")
