r"""numba kernel of the anisotropic engine's tables (:mod:`persson.engine.anisotropic`).

For an anisotropic PSD :math:`C(q, \phi) = \bar C(q)\, w(q, \phi)` and a sliding direction :math:`\theta` the
angular integrals of Persson's G(q) and friction integrand become

.. math:: \int_0^{2\pi} d\phi\, w(q, \phi)\, F(q v \cos(\phi - \theta)) =
          \int_0^{\pi/2} d\psi\, F(q v \cos\psi)\, w_s(\psi), \qquad
          w_s(\psi) = 2\,[w(\theta + \psi) + w(\theta - \psi)]

(F = :math:`E'^2`, :math:`E''^2` or :math:`\cos\psi\,E''`, each even about :math:`\psi = 0` and :math:`\pi/2`; w has
period :math:`\pi`). :math:`w_s` is interpolated by piecewise cubics on the uniform nodes :math:`\psi_j = j\pi/(2N)`
(mirrored at both ends), so the integral is :math:`\sum_j w_s(\psi_j) V_j(\omega)` with
:math:`V_j(\omega) = \int_0^{\pi/2} \beta_j(\psi) F(\omega\cos\psi)\, d\psi` for the cardinal functions
:math:`\beta_j` of that interpolation. With :math:`t = -\log_{10}\cos\psi` each :math:`V_j` is a convolution in log
frequency, evaluated exactly for the cubic interpolant of F on the modulus table's grid, as the isotropic
angular table (:func:`persson.engine.tabulate.angular_table`) is: :func:`basis_convolution`, called once per table
and angular resolution. The engine keeps :math:`v_j = V_j / \sum_k V_k` (a partition of unity) and multiplies the
isotropic tables by :math:`\rho = \sum_j \tfrac14 w_s(\psi_j) v_j`, which is 1 to rounding for an isotropic w.

That product, and everything after it (the q integrals, the contact weight, the flash-temperature fixed point),
runs in the engine's own kernels (:func:`persson.engine.kernels.shape_factors` and the kernels that call it):
numba caches a compiled kernel by its own source file only, so the kernels that call one another share the one
file :mod:`persson.engine.kernels`. This kernel calls none.
"""

from __future__ import annotations

from numba import njit

__all__ = ["basis_convolution"]


@njit(cache=True)
def basis_convolution(F, c, d_lo, d_hi, out):
    r"""out[j, i] = :math:`\sum_d` c[j, d + 1] F[i - d] for every cardinal function j, F clamped at both ends.

    Parameters
    ----------
    F : ndarray (n,)
        The function of log frequency on the modulus table's grid (:math:`E'^2`, :math:`E''^2` in Pa^2 or
        :math:`E''` in Pa).
    c : ndarray (n_basis, n_d)
        Product-integration weights: ``c[j, d + 1]`` multiplies F d nodes below (d = -1 .. n_d - 2), see
        :func:`persson.engine.anisotropic.basis_weights`.
    d_lo, d_hi : ndarray of int64 (n_basis,)
        First and last d with a non-zero weight, per cardinal function.
    out : ndarray (n_basis, n)
        Filled with the integral of every cardinal function against F at every node, in the unit of F.
    """
    n = F.shape[0]
    nb = c.shape[0]
    for j in range(nb):
        for i in range(n):
            acc = 0.0
            for d in range(d_lo[j], d_hi[j] + 1):
                k = i - d
                if k < 0:
                    k = 0
                elif k > n - 1:
                    k = n - 1
                acc += c[j, d + 1] * F[k]
            out[j, i] = acc
