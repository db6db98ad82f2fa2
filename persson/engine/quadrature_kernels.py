"""numba kernel of the wavevector quadrature rule (:func:`persson.engine.quadrature.quadrature_rule`).

The rule is rebuilt for every new surface a fit makes (a microtexture's cut-off, the sealing of a wet road), and in
numpy its few hundred small array operations cost about 0.4 ms per rule whatever the number of nodes. The PSD's
values at the Gauss points stay with the caller (the surface is Python); this kernel assembles the weights from
them, with the same operations in the same order as the array expressions it replaces, so the rule is the same to
the last bit. Kept in a file of its own: numba caches a kernel by its source file.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["assemble_rule"]


@njit(cache=True)
def assemble_rule(x, stencil, interval, start, lo, mid, hi, pts, wts, c):
    r"""The arrays of a :class:`~persson.engine.kernel_arrays.QuadratureRule` from the PSD factor at the Gauss
    points of every piece (see :func:`persson.engine.quadrature._quadrature_rule`).

    Parameters
    ----------
    x : ndarray (n,)
        The nodes, ln q.
    stencil : ndarray of int64 (n - 1,)
        First node of each interval's quadratic stencil.
    interval : ndarray of int64 (n_pieces,)
        The interval of each piece.
    start : ndarray of int64 (n,)
        First piece of each interval.
    lo, mid, hi : ndarray (n_pieces,)
        Start, middle and end of each piece, ln q.
    pts, wts, c : ndarray (n_pieces, 2, n_gauss)
        Gauss points (ln q), weights and the factor :math:`q^4 C(q)` there, on the two halves of each piece.

    Returns
    -------
    W : ndarray (n - 1, 3)
        :math:`\int \ell_m c\, dx` over each interval.
    basis : ndarray (n_pieces, 3, 3)
        :math:`\ell_m` at the start, middle and end of each piece.
    partial : ndarray (n_pieces, 3, 3)
        :math:`\int \ell_m c\, dx` from the interval's start to the start, middle and end of each piece.
    """
    n = x.shape[0]
    npc = lo.shape[0]
    ng = pts.shape[2]
    half = np.zeros((npc, 2, 3))
    piece = np.empty((npc, 3))
    basis = np.empty((npc, 3, 3))
    for p in range(npc):
        a = stencil[interval[p]]
        x0, x1, x2 = x[a], x[a + 1], x[a + 2]
        d0 = (x0 - x1) * (x0 - x2)
        d1 = (x1 - x0) * (x1 - x2)
        d2 = (x2 - x0) * (x2 - x1)
        for k in range(2):
            for g in range(ng):
                t = pts[p, k, g]
                wc = wts[p, k, g] * c[p, k, g]
                half[p, k, 0] += wc * ((t - x1) * (t - x2) / d0)
                half[p, k, 1] += wc * ((t - x0) * (t - x2) / d1)
                half[p, k, 2] += wc * ((t - x0) * (t - x1) / d2)
        for m in range(3):
            piece[p, m] = half[p, 0, m] + half[p, 1, m]
        for k in range(3):
            t = lo[p] if k == 0 else (mid[p] if k == 1 else hi[p])
            basis[p, k, 0] = (t - x1) * (t - x2) / d0
            basis[p, k, 1] = (t - x0) * (t - x2) / d1
            basis[p, k, 2] = (t - x0) * (t - x1) / d2
    # the integral before each piece within its interval: a running sum over all pieces, less the sum before the
    # interval's first piece (cumsum - piece, as the array form has it)
    cum = np.empty((npc, 3))
    run = np.zeros(3)
    for p in range(npc):
        for m in range(3):
            run[m] = piece[p, m] if p == 0 else run[m] + piece[p, m]
            cum[p, m] = run[m] - piece[p, m]
    partial = np.empty((npc, 3, 3))
    W = np.zeros((n - 1, 3))
    for p in range(npc):
        first = start[interval[p]]
        for m in range(3):
            before = cum[p, m] - cum[first, m]
            partial[p, 0, m] = before
            partial[p, 1, m] = before + half[p, 0, m]
            partial[p, 2, m] = before + piece[p, m]
            W[interval[p], m] += piece[p, m]
    return W, basis, partial
