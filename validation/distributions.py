r"""Tail probabilities of the normal, Student t, chi-square and F distributions (and the t's quantile), and a
randomized Halton design.

The tail probabilities are the same special functions ``scipy.stats`` evaluates (``scipy.special.ndtr``, ``stdtr``,
``chdtrc``, ``fdtrc``: Cephes, Moshier 1989), called directly: importing ``scipy.stats`` costs about half a second,
which every ``persson diagnose`` would pay before its first fit. An argument at or below the distribution's lower
end gives the survival probability 1 (scipy.special returns NaN for a negative statistic).

The design points of the multi-start fits are a randomized Halton sequence (J. H. Halton, Numer. Math. 2, 84
(1960)) with random digit permutations (A. B. Owen, A randomized Halton algorithm in R, arXiv:1706.02808 (2017)),
the scheme of ``scipy.stats.qmc.Halton(scramble=True)``, again without the import.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special

__all__ = ["norm_sf", "norm_cdf", "t_sf", "t_isf", "chi2_sf", "chi2_cdf", "f_sf", "f_cdf", "halton"]


def norm_sf(z: float) -> float:
    r"""Standard normal survival function :math:`P(Z > z) = \Phi(-z)`."""
    return float(special.ndtr(-float(z)))


def norm_cdf(z: float) -> float:
    r"""Standard normal distribution function :math:`\Phi(z)`."""
    return float(special.ndtr(float(z)))


def t_sf(t: float, dof: float) -> float:
    r"""Student t survival function :math:`P(T_\nu > t)`, ``dof`` = :math:`\nu` > 0 (may be infinite: the normal)."""
    return float(special.stdtr(float(dof), -float(t)))


def t_isf(p: float, dof: float) -> float:
    r"""Student t upper quantile: the t with :math:`P(T_\nu > t) = p`, ``dof`` = :math:`\nu` > 0 (infinite: the
    normal's), 0 < p < 1 (``scipy.special.stdtrit``, ``ndtri``)."""
    p, dof = float(p), float(dof)
    return float(-special.ndtri(p) if not math.isfinite(dof) else -special.stdtrit(dof, p))


def chi2_sf(x: float, dof: float) -> float:
    r"""Chi-square survival function :math:`P(\chi^2_k > x)`; 1 for :math:`x \le 0`."""
    x = float(x)
    return 1.0 if x <= 0.0 else float(special.chdtrc(float(dof), x))


def chi2_cdf(x: float, dof: float) -> float:
    r"""Chi-square distribution function :math:`P(\chi^2_k \le x)` (``scipy.special.chdtr``); 0 for
    :math:`x \le 0`."""
    x = float(x)
    return 0.0 if x <= 0.0 else float(special.chdtr(float(dof), x))


def f_cdf(F: float, dfn: float, dfd: float) -> float:
    r"""F distribution function :math:`P(F_{d_1, d_2} \le F)` (``scipy.special.fdtr``); 0 for :math:`F \le 0`."""
    F = float(F)
    return 0.0 if F <= 0.0 else float(special.fdtr(float(dfn), float(dfd), F))


def f_sf(F: float, dfn: float, dfd: float) -> float:
    r"""F survival function :math:`P(F_{d_1, d_2} > F)`; 1 for :math:`F \le 0`."""
    F = float(F)
    return 1.0 if F <= 0.0 else float(special.fdtrc(float(dfn), float(dfd), F))


def halton(k: int, n: int, seed: int = 0) -> np.ndarray:
    r"""``n`` points of a randomized Halton sequence in :math:`[0, 1)^k`, reproducible for a given ``seed``.

    Coordinate j is the radical inverse of the point's index i = 0, 1, ... in the j-th prime base b, each digit
    mapped through its own random permutation of 0..b-1 (Owen 2017): :math:`x_{ij} = \sum_d \pi_{jd}(a_d(i))
    b^{-d-1}`, with :math:`a_d(i)` the digits of i. The first :math:`b^m` points keep the stratification of the
    plain sequence: one point in each interval :math:`[l b^{-m}, (l + 1) b^{-m})` of coordinate j.

    Parameters
    ----------
    k : int
        Dimension.
    n : int
        Number of points.
    seed : int
        Seed of the permutations.

    Returns
    -------
    ndarray, shape (n, k)
    """
    k, n = int(k), int(n)
    if k <= 0 or n <= 0:
        return np.zeros((max(n, 0), max(k, 0)))
    rng = np.random.default_rng(seed)
    index = np.arange(n, dtype=np.int64)
    out = np.zeros((n, k))
    for j, b in enumerate(_primes(k)):
        # digits beyond those of the largest index are all 0, each mapped to a random digit: enough of them that
        # their sum is below double precision
        n_digits = int(math.ceil(math.log(max(n, 2)) / math.log(b))) + int(math.ceil(53 * math.log(2) / math.log(b)))
        i = index.copy()
        scale = 1.0 / b
        for _ in range(n_digits):
            out[:, j] += rng.permutation(b)[i % b] * scale
            i //= b
            scale /= b
    return np.minimum(out, np.nextafter(1.0, 0.0))


def _primes(k: int) -> list[int]:
    """The first ``k`` primes."""
    out: list[int] = []
    c = 2
    while len(out) < k:
        if all(c % p for p in out if p * p <= c):
            out.append(c)
        c += 1
    return out
