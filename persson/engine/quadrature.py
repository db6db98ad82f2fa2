r"""The wavevector quadrature of the engine on the PSD: the rule of the G and friction integrals
(:func:`quadrature_rule`) and spectral moments (:func:`psd_moment`, :func:`cumulative_moment`), each integrating the
PSD exactly between its breakpoints (Gauss-Legendre on power-law pieces), memoised per surface object.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from .kernel_arrays import QuadratureRule
from .memo import per_object
from .quadrature_kernels import assemble_rule

__all__ = ["quadrature_rule", "psd_moment", "cumulative_moment", "moments_at_nodes", "separation_moments",
           "psd_breakpoints"]


def quadrature_rule(surface, x: np.ndarray, n_gauss: int = 6) -> QuadratureRule:
    """:func:`_quadrature_rule`, memoised per surface object and nodes (a pure function of both: repeated calls
    on one surface, as in fits and sweeps, skip the PSD quadrature)."""
    return per_object(surface, ("rule", x.tobytes(), n_gauss), lambda: _quadrature_rule(surface, x, n_gauss))


def _quadrature_rule(surface, x: np.ndarray, n_gauss: int = 6) -> QuadratureRule:
    r"""The wavevector quadrature on the nodes ``x`` = ln q, a :class:`~persson.engine.kernels.QuadratureRule`
    (W, stencil, piece_start, basis, partial).

    The rough factor :math:`c = q^4 C(q)` of the G integrand is integrated exactly (Gauss-Legendre, ``n_gauss``
    points, between the PSD's breakpoints: a tabulated PSD is a power law between its rows, a roll-off has a kink)
    against the Lagrange basis :math:`\ell_m` of the quadratic in ln q through the nodes ``stencil[i] + m``
    (i, i+1, i+2; i-1, i, i+1 for the last interval):

    * ``W[i, m]`` = :math:`\int_{x_i}^{x_{i+1}} \ell_m c\, dx`, the weights of G (see
      :func:`persson.engine.kernels.cumulative_weighted`);
    * the intervals are cut at the PSD's breakpoints into pieces (``piece_start[i]`` .. ``piece_start[i+1]`` - 1 are
      interval i's); for each piece p and its start, middle and end point k, ``partial[p, k, m]`` =
      :math:`\int_{x_i}^{x_k} \ell_m c\, dx` (G there) and ``basis[p, k, m]`` = :math:`\ell_m(x_k)`, used by
      :func:`persson.engine.kernels.interval_node_weights`.

    So G is exact for any PSD to the interpolation of the smooth angular factor, and the friction integrand is
    never interpolated across a kink of the PSD.
    """
    n = x.size
    st = np.where(np.arange(n - 1) + 2 < n, np.arange(n - 1), np.arange(n - 1) - 1).astype(np.int64)
    br = np.log(psd_breakpoints(surface))
    br = br[(br > x[0]) & (br < x[-1])]
    edges = np.unique(np.concatenate([x, br]))
    edges = edges[np.concatenate([[True], np.diff(edges) > 1e-12 * np.abs(edges[1:]).clip(1.0)])]
    lo, hi = edges[:-1], edges[1:]
    mid = 0.5 * (lo + hi)
    interval = np.clip(np.searchsorted(x, mid) - 1, 0, n - 2).astype(np.int64)
    g, w = _gauss_legendre(n_gauss)
    seg = np.stack([np.stack([lo, mid], -1), np.stack([mid, hi], -1)], axis=1)  # (np, 2 halves, [from, to])
    pts = 0.5 * (seg[..., 0] + seg[..., 1])[..., None] + 0.5 * (seg[..., 1] - seg[..., 0])[..., None] * g
    wts = 0.5 * (seg[..., 1] - seg[..., 0])[..., None] * w                 # (np, 2, n_gauss)
    qq = np.exp(pts)
    c = qq**4 * np.asarray(surface.C(qq.ravel()), dtype=float).reshape(qq.shape)
    start = np.searchsorted(interval, np.arange(n)).astype(np.int64)     # first piece of each interval
    # the integrals of each piece's quadratic Lagrange basis l_m against c, summed piece by piece
    W, Lb, Wp = assemble_rule(np.ascontiguousarray(x, dtype=float), st, interval, start, lo, mid, hi,
                              np.ascontiguousarray(pts), np.ascontiguousarray(wts), np.ascontiguousarray(c))
    return QuadratureRule(W=W, stencil=st, piece_start=start, basis=Lb, partial=Wp)


def psd_moment(surface, q: np.ndarray, n: int) -> float:
    """Spectral moment 2 pi int_{q0}^{q1} q^n C(q) dq over the nodes' range (the last of
    :func:`moments_at_nodes`)."""
    return float(moments_at_nodes(surface, q, n)[-1])


def moments_at_nodes(surface, q: np.ndarray, n: int) -> np.ndarray:
    """:func:`cumulative_moment` at the nodes ``q``, memoised per surface object and nodes like
    :func:`quadrature_rule` (read-only: the rms slope, the mean separation's ``s`` and the total moments of one
    solution all read it)."""
    q = np.asarray(q, dtype=float)

    def compute():
        m = cumulative_moment(surface, q, n)
        m.setflags(write=False)
        return m

    return per_object(surface, ("moments", q.tobytes(), int(n)), compute)


def separation_moments(surface, q: np.ndarray) -> np.ndarray:
    """(int_{q0}^{q_i} q^3 C dq)^(1/2) at every node, the integration variable of the mean separation
    (:func:`persson.contact.separation.mean_separation`, its ``s``), exact across the PSD's breakpoints between
    nodes (from :func:`moments_at_nodes`)."""
    s = np.sqrt(np.maximum(moments_at_nodes(surface, q, 3) / (2.0 * math.pi), 0.0))
    s[0] = 0.0
    return s


def cumulative_moment(surface, q: np.ndarray, n: int, n_gauss: int = 6) -> np.ndarray:
    """2 pi int_{q0}^{q_i} q^n C(q) dq at every node (the rms slope squared up to q_i for n = 3), by
    Gauss-Legendre between the nodes and the PSD's breakpoints (exact to rounding for power-law pieces)."""
    x = np.log(np.asarray(q, dtype=float))
    br = np.log(psd_breakpoints(surface))
    edges = np.unique(np.concatenate([x, br[(br > x[0]) & (br < x[-1])]]))
    g, w = _gauss_legendre(n_gauss)
    lo, hi = edges[:-1, None], edges[1:, None]
    pts = 0.5 * (lo + hi) + 0.5 * (hi - lo) * g
    qq = np.exp(pts)
    f = qq ** (n + 1) * np.asarray(surface.C(qq.ravel()), dtype=float).reshape(qq.shape)
    piece = 2.0 * math.pi * np.sum(0.5 * (hi - lo) * w * f, axis=1)
    cum = np.concatenate([[0.0], np.cumsum(piece)])
    return cum[np.searchsorted(edges, x)]


def psd_breakpoints(surface) -> np.ndarray:
    """Wavevectors (rad/m) where the PSD or its log-log slope jumps: ``surface.breakpoints()`` when the surface
    provides it (tabulated PSDs: their rows; a self-affine PSD with a plateau: its roll-off), else none."""
    f = getattr(surface, "breakpoints", None)
    if f is None:
        return np.empty(0)
    b = np.asarray(f() if callable(f) else f, dtype=float).ravel()
    return b[np.isfinite(b) & (b > 0)]


@functools.lru_cache(maxsize=4)
def _gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    # pure function of n, cached (leggauss costs a millisecond at every call otherwise)
    g, w = np.polynomial.legendre.leggauss(n)
    g.setflags(write=False)
    w.setflags(write=False)
    return g, w
