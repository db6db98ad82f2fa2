r"""Wet-road friction against speed, texture depth and BPN: the three-zone identity, Dijks' law and the product form.

Do, Marsac & Mosset (2004) start from the three zones of a tyre on a wet road (Moore 1975):
:math:`\mu = \mu_{dry} A_3/(A_1 + A_2 + A_3)` (:func:`three_zone_mu`), which they rewrite as
:math:`\mu = (\text{adhesion term})(1 - \text{hydrodynamic term})`. Here that product form is made concrete the
way Dijks (1974) split it: an adhesion term linear in the pendulum value (BPN, the microtexture) and a hydrodynamic
term growing with speed, the faster the smaller the texture depth (the macrotexture that drains the water):

.. math::
    \mu = (c_0 + c_1\,\mathrm{BPN})\,[1 - (d_0 + d_1/\mathrm{TD})\,V]        \qquad\text{(:func:`wet_product`)}

Multiplied out it has six terms, 1, V/TD, V, BPN, V BPN and V BPN/TD, and Dijks' law (:func:`dijks`) gives each its
own constant: the linear model whose constraints :math:`a_2 a_4 = a_1 a_6`, :math:`a_3 a_4 = a_1 a_5` the product
form obeys. Both need rows on several surfaces (texture depths and BPN values): on one surface the six constants
collapse into two and the fit says so.

Units: V in m/s, TD (the mean texture depth, MTD, of EN ISO 13473-1 / EN 13036-1) in m, BPN in pendulum units
(EN 13036-4; 0-150). With them a1 is dimensionless, a2 and d1 are in s, a3 and d0 in s/m, a4 and c1 per BPN, a5 in
s/m per BPN, a6 in s per BPN.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from ..errors import InputError
from .fitting import FitResult, _xy
from .references import DIJKS_1974, DO_2004, EN_13036_4, MOORE_1975
from .separable import Law, fit_separable

__all__ = ["three_zone_mu", "dijks", "fit_dijks", "wet_product", "fit_wet_product", "SurfaceLawFit", "DIJKS_TERMS"]

#: The six terms of Dijks' law, in the order of a1..a6.
DIJKS_TERMS = ("1", "V/TD", "V", "BPN", "V BPN", "V BPN/TD")


# =========================================================================================================
# The laws
# =========================================================================================================
@doi(DO_2004, MOORE_1975)
def three_zone_mu(mu_dry, a1, a2, a3):
    r"""Friction of the three-zone wet contact, :math:`\mu = \mu_{dry} A_3 / (A_1 + A_2 + A_3)` (Do et al. 2004, eq. 1).

    Equivalently :math:`\mu_{dry}[1 - (A_1 + A_2)/(A_1 + A_2 + A_3)]`: (adhesion) x (1 - hydrodynamic term).

    Parameters
    ----------
    mu_dry : array_like
        Friction developed in zone 3.
    a1, a2, a3 : array_like
        Areas (or shares) of zone 1 (water wedge), zone 2 (squeeze film, partial contact) and zone 3 (dry contact);
        any common unit, >= 0, not all zero.
    """
    A = [np.asarray(a, dtype=float) for a in (a1, a2, a3)]
    for name, a in zip(("a1", "a2", "a3"), A):
        if np.any(~np.isfinite(a)) or np.any(a < 0):
            raise InputError(f"{name}: expected finite areas >= 0")
    total = A[0] + A[1] + A[2]
    if np.any(total <= 0):
        raise InputError("a1, a2, a3: the three zones have no area together (a1 + a2 + a3 = 0)")
    return np.asarray(mu_dry, dtype=float) * A[2] / total


@doi(DIJKS_1974, DO_2004)
def dijks(speed, mtd, bpn, a1, a2, a3, a4, a5, a6):
    r"""Dijks' linear law :math:`\mu = a_1 + a_2 V/TD + a_3 V + a_4 B + a_5 V B + a_6 V B/TD` (B the BPN).

    Dijks (1974), as quoted by Do, Marsac & Mosset (2004), eq. 3. The quoted equation is garbled in the copy at
    hand (fractions and subscripts are scattered); it is read here as the six terms whose symbols it contains (four V,
    three BPN, two TD, a1..a6, five sums, two products) and which Do et al. call a simplification of the product form
    (adhesion)(1 - hydrodynamic term): they are exactly the terms of :func:`wet_product` multiplied out.

    Parameters
    ----------
    speed : array_like
        V, m/s.
    mtd : array_like
        Texture depth TD (mean texture depth), m.
    bpn : array_like
        British Pendulum Number (pendulum units).
    a1, a2, a3, a4, a5, a6 : float
        The constants (units in the module docstring).
    """
    V, TD, B = (np.asarray(a, dtype=float) for a in (speed, mtd, bpn))
    return a1 + a2 * V / TD + a3 * V + a4 * B + a5 * V * B + a6 * V * B / TD


@doi(DO_2004, DIJKS_1974, EN_13036_4)
def wet_product(speed, mtd, bpn, c0, c1, d0, d1):
    r"""Product form :math:`\mu = (c_0 + c_1 B)\,[1 - (d_0 + d_1/TD)\,V]`: adhesion x (1 - hydrodynamic term).

    Do, Marsac & Mosset (2004), eq. 2, with Dijks' (1974) split of the variables: the adhesion term depends on the
    microtexture (BPN, B), the hydrodynamic term on speed and macrotexture (texture depth TD).

    Parameters
    ----------
    speed : array_like
        V, m/s.
    mtd : array_like
        Texture depth TD, m.
    bpn : array_like
        British Pendulum Number.
    c0 : float
        Adhesion at BPN 0 (dimensionless).
    c1 : float
        Adhesion per BPN.
    d0 : float
        Hydrodynamic term per unit speed on a deep texture, s/m.
    d1 : float
        Its growth as the texture depth shrinks, s.
    """
    V, TD, B = (np.asarray(a, dtype=float) for a in (speed, mtd, bpn))
    return (c0 + c1 * B) * (1.0 - (d0 + d1 / TD) * V)


# =========================================================================================================
# Fits
# =========================================================================================================
@dataclass(frozen=True, eq=False)
class SurfaceLawFit(FitResult):
    """A fitted law of speed, texture depth and BPN (:func:`fit_dijks`, :func:`fit_wet_product`).

    A :class:`FitResult` whose ``x`` is the speed; ``mtd`` and ``bpn`` are the texture depths (m) and BPN of the
    rows. Call it as ``fit(speed, mtd, bpn)``; without ``mtd`` and ``bpn`` it uses those of the rows (then
    ``speed`` must have one value per row, or the rows must share one surface).
    """

    mtd: np.ndarray | None = None
    bpn: np.ndarray | None = None

    def __call__(self, speed, mtd=None, bpn=None):
        """The fitted law at ``speed`` (m/s) on the surface(s) ``mtd`` (m), ``bpn``."""
        V = np.asarray(speed, dtype=float)
        if mtd is None or bpn is None:
            one = np.ptp(self.mtd) == 0 and np.ptp(self.bpn) == 0
            if not one and V.shape != self.x.shape:
                raise InputError(f"mtd, bpn: {self.law} needs the texture depth and BPN of the surface; the fitted "
                                 "rows have several surfaces")
            if mtd is None:
                mtd = self.mtd[0] if one else self.mtd
            if bpn is None:
                bpn = self.bpn[0] if one else self.bpn
        return self.func(V, mtd, bpn, *self.values)


@doi(DIJKS_1974, DO_2004)
def fit_dijks(speed, mu, *, mtd, bpn, sigma=None) -> SurfaceLawFit:
    """Fit Dijks' six constants by linear least squares (exact; covariance :math:`s^2 (X^T X)^{-1}`).

    Parameters
    ----------
    speed, mu : array_like
        Speeds (> 0, m/s) and friction coefficients, one per row.
    mtd : float or array_like
        Texture depth of each row (m; one value for all rows is allowed but cannot determine the law).
    bpn : float or array_like
        BPN of each row.
    sigma : array_like, optional
        Standard uncertainties of mu.

    Returns
    -------
    SurfaceLawFit
        Parameters a1..a6.

    Raises
    ------
    InputError
        Bad input, or rows that do not determine the six constants (one surface, too few distinct texture depths,
        BPN values or speeds), with the reason.
    """
    V, y, sig, TD, B = _surface_rows(speed, mu, sigma, mtd, bpn, 6, "dijks")
    X = np.column_stack([np.ones_like(V), V / TD, V, B, V * B, V * B / TD])
    w = np.ones_like(y) if sig is None else 1.0 / sig
    Xw = X * w[:, None]
    norm = np.sqrt(np.sum(Xw**2, axis=0))
    U, s, VT = np.linalg.svd(Xw / norm, full_matrices=False)
    rank = int(np.sum(s > 1e-10 * s[0]))
    if rank < 6:
        raise InputError(f"speed, mtd, bpn: Dijks' six constants are not determined by these rows (design rank "
                         f"{rank} < 6): {_variety(V, TD, B)}. The slope against speed of each surface is one equation "
                         "for a2, a3, a5 and a6, and its level one for a1 and a4: the law needs speeds varied on at "
                         "least four surfaces whose texture depths and BPN values do not move together")
    coef = (VT.T @ ((U.T @ (y * w)) / s)) / norm
    r = y - X @ coef
    dof = y.size - 6
    scale = float((r * w) @ (r * w)) / dof if sig is None else 1.0
    cov = ((VT.T / s**2) @ VT) / np.outer(norm, norm) * scale
    return SurfaceLawFit(law="dijks", names=("a1", "a2", "a3", "a4", "a5", "a6"), values=coef,
                         stderr=np.sqrt(np.diag(cov)), covariance=cov, fixed=(), x=V, y=y, sigma=sig,
                         rms=math.sqrt(float(r @ r) / y.size), dof=dof, notes=(), citations=dijks.__citations__,
                         func=dijks, mtd=TD, bpn=B)


@doi(DO_2004, DIJKS_1974)
def fit_wet_product(speed, mu, *, mtd, bpn, sigma=None, fixed: dict | None = None) -> SurfaceLawFit:
    """Fit the product form (c0 + c1 BPN)(1 - (d0 + d1/TD) V) (see :func:`wet_product`, :func:`fit_dijks`).

    Global: the adhesion constants are solved exactly on a grid of the hydrodynamic ones, the best points refined.
    """
    V, y, sig, TD, B = _surface_rows(speed, mu, sigma, mtd, bpn, 4, "wet_product")
    if np.ptp(B) == 0 or np.ptp(TD) == 0:
        raise InputError(f"mtd, bpn: the product form needs rows on surfaces of different texture depth and BPN "
                         f"({_variety(V, TD, B)}); on one surface c0 and c1, d0 and d1 cannot be told apart")
    h = np.linspace(-1.0, 1.0, 21) / float(np.max(V))
    d0, d1 = (m.ravel() for m in np.meshgrid(h, h * float(np.median(TD)), indexing="ij"))
    law = Law("wet_product", wet_product, ("c0", "c1", "d0", "d1"),
              {"c0": (-10.0, 10.0), "c1": (-1.0, 1.0), "d0": (-np.inf, np.inf), "d1": (-np.inf, np.inf)},
              ("c0", "c1"), lambda xs, t: [g := 1.0 - (t["d0"] + t["d1"] / xs[1]) * xs[0], xs[2] * g],
              lambda xs: {"d0": d0, "d1": d1}, wet_product.__citations__)
    parts = fit_separable(law, (V, TD, B), y, sig, fixed=fixed)
    return SurfaceLawFit(**parts, mtd=TD, bpn=B)


# =========================================================================================================
# helpers
# =========================================================================================================
def _surface_rows(speed, mu, sigma, mtd, bpn, k: int, law: str):
    """Checked rows: speed > 0, and the texture depth (m) and BPN of each row."""
    V, y, sig = _xy(speed, mu, sigma, "speed")
    if np.any(V <= 0):
        i = int(np.argmax(V <= 0))
        raise InputError(f"speed: expected speeds > 0 m/s, got {V[i]:g} at index {i}")
    if y.size <= k:
        raise InputError(f"speed, mu: {y.size} points cannot determine {k} free parameters of {law}; give more than "
                         f"{k} rows")
    TD = texture_depth_m(mtd, "mtd", y.size)
    B = pendulum_number(bpn, "bpn", y.size)
    return V, y, sig, TD, B


def texture_depth_m(value, name: str, n: int | None = None, *, allow_zero: bool = False) -> np.ndarray:
    """A texture or tread depth in m per row, or InputError (a value above 20 mm looks like mm)."""
    a = _per_row(value, name, n)
    bad = (a < 0) if allow_zero else (a <= 0)
    if np.any(bad):
        i = int(np.argmax(bad))
        raise InputError(f"{name}: expected a depth {'>=' if allow_zero else '>'} 0 m, got {a[i]:g} at index {i}")
    if np.any(a > 0.02):
        i = int(np.argmax(a > 0.02))
        raise InputError(f"{name}: {a[i]:g} m at index {i} is more than 20 mm, deeper than road textures, tread "
                         f"grooves and wet-road water films; the value looks like millimetres: give metres ({a[i]:g} "
                         f"mm = {a[i] * 1e-3:g} m)")
    return a


def pendulum_number(value, name: str, n: int | None = None) -> np.ndarray:
    """British Pendulum Numbers per row (0-150), or InputError (values all <= 1.5 look like BPN/100)."""
    a = _per_row(value, name, n)
    if np.any(a <= 0) or np.any(a > 150):
        i = int(np.argmax((a <= 0) | (a > 150)))
        raise InputError(f"{name}: expected a British Pendulum Number in (0, 150], got {a[i]:g} at index {i}")
    if np.all(a <= 1.5):
        raise InputError(f"{name}: every value is <= 1.5 (largest {a.max():g}): that looks like BPN/100 or a "
                         "friction coefficient; give the pendulum reading in BPN units (e.g. 65)")
    return a


def _per_row(value, name: str, n: int | None) -> np.ndarray:
    if value is None:
        raise InputError(f"{name}: required")
    try:
        a = np.asarray(value, dtype=float).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected numbers, got {value!r}") from None
    if a.size == 0 or not np.all(np.isfinite(a)):
        raise InputError(f"{name}: expected finite numbers")
    if n is not None:
        if a.size == 1:
            a = np.full(n, a[0])
        elif a.size != n:
            raise InputError(f"{name}: expected one value or {n} values (one per row), got {a.size}")
    return a


def _variety(V, TD, B) -> str:
    surfaces = np.unique(np.column_stack([TD, B]), axis=0).shape[0]
    return (f"{surfaces} surface(s) (texture depth, BPN), {np.unique(TD).size} distinct texture depth(s), "
            f"{np.unique(B).size} distinct BPN value(s), {np.unique(V).size} distinct speed(s)")
