"""The acceleration of the flash temperature's fixed point: Anderson mixing (Anderson 1965; Walker & Ni 2011).

On a linear map g(T) = M T + c the mixed iteration is GMRES in disguise: with a history as long as the dimension
it lands on the fixed point (I - M)^-1 c, computed here by numpy's LAPACK solve, even where the plain iteration
diverges (an eigenvalue of M below -1: the period-2 oscillation of a contact that a cold start overheats).
"""

import numpy as np

from persson.engine import kernels


def _mixed(M, c, T, steps):
    n = T.size
    T = T.copy()
    T_prev, r_prev = np.empty(n), np.empty(n)
    dT = np.zeros((kernels._ANDERSON_DEPTH, n))
    dR = np.zeros((kernels._ANDERSON_DEPTH, n))
    n_hist = -1
    for _ in range(steps):
        n_hist = kernels._anderson_step(M @ T + c, T, T_prev, r_prev, dT, dR, n_hist)
    return T


def test_anderson_mixing_lands_on_the_fixed_point_of_a_linear_map_where_plain_iteration_diverges():
    rng = np.random.default_rng(3)
    Q, _ = np.linalg.qr(rng.standard_normal((3, 3)))
    M = Q @ np.diag([-2.5, 0.6, -0.3]) @ Q.T          # a hot contact's flip: plain iteration diverges
    c = rng.standard_normal(3)
    exact = np.linalg.solve(np.eye(3) - M, c)
    T0 = np.zeros(3)
    plain = T0.copy()
    for _ in range(8):
        plain = M @ plain + c
    assert np.max(np.abs(plain - exact)) > 10.0
    T = _mixed(M, c, T0, steps=3 + 2)                   # first step, three differences, one more
    np.testing.assert_allclose(T, exact, rtol=0, atol=1e-9)


def test_small_solve_matches_lapack_and_refuses_a_singular_system():
    rng = np.random.default_rng(4)
    A = rng.standard_normal((3, 3))
    A = A @ A.T + 0.1 * np.eye(3)
    b = rng.standard_normal(3)
    np.testing.assert_allclose(kernels._solve_small(A.copy(), b.copy()), np.linalg.solve(A, b), rtol=1e-12)
    singular = np.array([[1.0, 2.0, 0.0], [2.0, 4.0, 0.0], [0.0, 0.0, 0.0]])
    np.testing.assert_array_equal(kernels._solve_small(singular, np.ones(3)), np.zeros(3))
