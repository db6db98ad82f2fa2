r"""Friction and contact of an anisotropic surface sliding in a given direction (Persson's general expressions).

For a PSD :math:`C(\mathbf q) = C(q, \phi)` and sliding along the angle :math:`\theta` from the x axis (Persson,
J. Chem. Phys. 115, 3840 (2001); Carbone, Lorenz, Persson & Wohlers, Eur. Phys. J. E 29, 275 (2009); Afferrante,
Putignano, Menga & Carbone, Eur. Phys. J. E 42, 80 (2019))

.. math::
    G(q) = \frac18\int_{q_0}^{q} dq'\, q'^3 \int_0^{2\pi} d\phi\, C(q', \phi)
           \left|\frac{E(q' v\cos(\phi - \theta), T)}{(1-\nu^2)\sigma_0}\right|^2 ,\qquad
    P(q) = \mathrm{erf}\frac{1}{2\sqrt{G(q)}},

.. math::
    \mu = \frac12\int_{q_0}^{q_1} dq\, q^3 S(q) P(q)\int_0^{2\pi} d\phi\, \cos(\phi - \theta)\, C(q, \phi)\,
          \frac{\mathrm{Im}\,E(q v\cos(\phi - \theta), T)}{(1-\nu^2)\sigma_0} .

With :math:`C = \bar C(q)\, w(q, \phi)` (angular mean times angular shape, :mod:`surfaces.anisotropy`) the angular
integrals are the isotropic engine's tables times factors :math:`\rho(q, \theta, \omega)` (1 for an isotropic
shape), computed by product integration against the cubic interpolant of the shape on a uniform grid of
:math:`N` angles (:mod:`persson.engine.anisotropic_kernels`); the unidirectional limit, a delta in angle, reads the
modulus at :math:`q v |\cos(\alpha - \theta)|` directly. The q integrals, the contact weight, the effects and the
result are exactly those of the isotropic engine (:mod:`persson.engine.solver`), per direction and speed.

Error estimate: the q-quadrature estimate of the isotropic engine plus the angular one (:func:`_angular_error`:
Richardson between the angular grid, its every other node and every fourth; the rule is fourth order for a smooth
shape, second order across a kink of it, and :math:`\sqrt{45}` is the geometric mean of :math:`2^4 - 1` and
:math:`2^2 - 1`). N doubles (from a start set by the shape's width) until that estimate is
below a tenth of ``GridSettings.tolerance`` or N reaches 1024; speeds whose q estimate exceeds a third of the
tolerance are refined in q as in the isotropic engine.
"""

from __future__ import annotations

import functools
import math
from dataclasses import replace

import numpy as np

from frictioncite import doi

from . import anisotropic_kernels as _ak
from . import solver as _solver
from .conditions import Conditions
from .kernel_arrays import AngularShape
from .solver import _SAFETY, Solved, _subset, prepare
from ..errors import InputError
from ..notes import Note

__all__ = ["is_anisotropic", "solve_directions", "basis_weights", "angular_error_factor"]

#: Largest number of angular intervals on [0, pi/2]; smallest.
_N_MAX = 1024
_N_MIN = 16
#: Richardson factor of the angular estimate: the geometric mean of 2^4 - 1 and 2^2 - 1; for a shape with kinks in
#: angle, 2^2 - 1 (second order).
angular_error_factor = math.sqrt(45.0)
_KINK_FACTOR = 3.0
#: Decades of t = -log10 cos(psi) the cardinal weights cover (as the isotropic table's weights).
_T_MAX = 20.0
_GL = np.polynomial.legendre.leggauss(8)


def is_anisotropic(surface) -> bool:
    """Whether ``surface`` is an anisotropic PSD (``surfaces.Stretched``, ``Unidirectional``, ``PSD2D``...)."""
    return bool(getattr(surface, "is_anisotropic", False))


@doi("10.1063/1.1388626", "carbone:epje-29-275-2009", "10.1140/epje/i2019-11844-5")
def solve_directions(aniso, surface, material, cond: Conditions, grid, nu: float, gamma: float, thermal,
                     correction, modulus, theta_deg: np.ndarray) -> list[Solved]:
    """Solve every speed of ``cond`` in every sliding direction ``theta_deg`` (degrees from the x axis).

    Parameters
    ----------
    aniso : anisotropic PSD
        The model's surface: its angular shape (or, for a unidirectional PSD, the direction of its wavevectors).
    surface : PSD
        The surface after the effects' ``transform_surface``: its ``C(q)`` (the angular mean, possibly extended or
        sealed by an effect) is the radial factor; the angular shape stays the surface's own.
    material, cond, grid, nu, gamma, correction, modulus
        As :func:`persson.engine.solver.solve`.
    thermal : Effect or None
        A temperature effect (the flash temperature): its settings (``temperature_solver_options``) drive the
        self-consistent temperature of every direction and speed (:func:`_solve_flash`).
    theta_deg : ndarray (n_dir,)
        Sliding directions, degrees.

    Returns
    -------
    list of Solved
        One per direction, per speed and wavevector node as the isotropic solver's.
    """
    theta = np.radians(np.asarray(theta_deg, dtype=float).ravel())
    T = np.broadcast_to(np.asarray(cond.temperature, dtype=float), cond.speed.shape)
    solve = _solve_group if thermal is None else functools.partial(_solve_flash, thermal=thermal)
    if np.all(T == T[0]) or hasattr(material, "log10_aT"):
        return solve(aniso, surface, material, cond, grid, nu, gamma, correction, modulus, theta)
    # a material without a shift law: one modulus table per temperature, merged back speed by speed
    out = None
    for t in np.unique(T):
        idx = np.flatnonzero(T == t)
        part = solve(aniso, surface, material, _subset(cond, idx), grid, nu, gamma, correction, modulus, theta)
        out = [_empty_like(p, T.size) for p in part] if out is None else out
        out = [_put(o, idx, p) for o, p in zip(out, part)]
    return out


# ---------------------------------------------------------------------------------------------------------
def _solve_group(aniso, surface, material, cond, grid, nu, gamma, correction, modulus, theta) -> list[Solved]:
    """One modulus table for every problem (a direction at a speed: the "speeds" of the solver); q refined per
    problem where the estimate is high, at the angular resolution the first pass chose."""
    nd, nv = theta.size, cond.speed.size
    cond_p, angular = _problems(aniso, material, cond, theta, grid)
    prep = prepare(surface, material, cond_p, grid, nu, gamma=gamma, correction=correction, modulus=modulus)
    solved, err_a, n = _run(prep, angular)
    for level in range(1, grid.max_refinement + 1):
        bad = np.flatnonzero(solved.error_estimate > grid.tolerance / _SAFETY)
        if bad.size == 0:
            break
        sub = prepare(surface, material, _subset(cond_p, bad), grid, nu, gamma=gamma, correction=correction,
                      modulus=modulus, refine=level, nodes=prep.q)
        fine, err_a[bad], _ = _run(sub, angular.subset(bad), n_basis=n)
        solved = _solver._merge(solved, bad, fine, 2**level)
    notes = []
    if n and np.any(err_a > grid.tolerance / 10.0):
        notes.append(Note(f"angular resolution: {n} intervals on [0, pi/2] (the most) leave an estimated angular "
                          f"error up to {float(np.max(err_a)):.2g}: the angular shape of the PSD is very narrow",
                          "accuracy"))
    return _by_direction(replace(solved, error_estimate=solved.error_estimate + err_a), nd, nv, notes)


def _solve_flash(aniso, surface, material, cond, grid, nu, gamma, correction, modulus, theta, *,
                 thermal) -> list[Solved]:
    r"""The self-consistent flash temperature of every direction and speed (Persson, J. Phys.: Condens. Matter 18,
    7789 (2006), Eqs. 20-27, with the heat source of the sliding direction):

    .. math:: f(q) = \frac{v\,\sigma_0}{\rho c_p}\frac{P(q)}{P(q_m)}\, q^4\, \frac{1}{\sigma_0}
              \int_0^{2\pi} d\phi\,\cos\phi\, C(q, \phi + \theta)\,\frac{\mathrm{Im}\,E(q v\cos\phi, T_q)}{1-\nu^2} ,

    the isotropic source with :math:`C(q)` times the angular integral replaced by the integral over
    :math:`C(q, \phi)`: the loss integral L of every node multiplied by its factor :math:`\rho_L` at that node's
    temperature (and G(q), P(q) with theirs), so that the fixed point, its refinement where a temperature front is
    steep, the widening of the shift table and the two-grid error estimate are the isotropic solver's
    (:func:`persson.engine.solver._solve_group`), one problem (a direction at a speed) per row.

    The angular resolution starts where the isothermal problem converges (:func:`_run`, cheap beside the fixed
    point) and doubles while the angular estimate of the flash result (:func:`_flash_angular_error`) exceeds a
    tenth of the tolerance.
    """
    nd, nv = theta.size, cond.speed.size
    cond_p, angular = _problems(aniso, material, cond, theta, grid)
    n = 0
    if not angular.unidirectional:
        plain = prepare(surface, material, cond_p, grid, nu, gamma=gamma, correction=correction, modulus=modulus)
        n = _run(plain, angular)[2]
    while True:
        solved = _solver._solve_group(surface, material, cond_p, grid, nu, gamma, thermal, correction, modulus,
                                      shape=angular.level(n))
        if angular.unidirectional:
            err_a = np.zeros(nd * nv)
            break
        err_a = _flash_angular_error(solved, angular, n, surface, material, cond_p, grid, nu, gamma, correction,
                                     modulus, thermal)
        if np.max(err_a) <= grid.tolerance / 10.0 or n >= _N_MAX:
            break
        n *= 2
    notes = []
    if n and np.any(err_a > grid.tolerance / 10.0):
        notes.append(Note(f"angular resolution: {n} intervals on [0, pi/2] (the most) leave an estimated angular "
                          f"error up to {float(np.max(err_a)):.2g} of the flash-temperature friction: the angular "
                          "shape of the PSD is very narrow", "accuracy"))
    return _by_direction(replace(solved, error_estimate=solved.error_estimate + err_a), nd, nv, notes)


def _flash_angular_error(solved, angular, n, surface, material, cond_p, grid, nu, gamma, correction, modulus,
                         thermal) -> np.ndarray:
    """The angular estimate (:func:`_angular_error`) of the flash-temperature friction of every problem: the
    fixed point on the base nodes with N, N/2 and N/4 angular intervals, each started from the solution (a few
    iterations), so that the three differ by their angular rule alone (a speed refined in q or at a temperature
    front has the same base-grid error in all three)."""
    T0 = np.broadcast_to(np.asarray(cond_p.temperature, dtype=float), cond_p.speed.shape)
    rise = _solver._rise(grid, solved.T_q, T0)
    start = np.where(solved.converged_each[:, None], solved.T_q, T0[:, None])
    mu = []
    for m in (n, n // 2, n // 4):
        prep = prepare(surface, material, cond_p, replace(grid, max_temperature_rise=rise), nu, gamma=gamma,
                       correction=correction, flash=True, modulus=modulus, nodes=solved.q, shape=angular.level(m))
        options = _solver.temperature_options(thermal, prep, material)
        args = (options.q_m, options.diffusivity * options.contact_diameter / prep.v, options.diffusivity,
                prep.pressure / options.heat_capacity, options.tol, int(options.max_iter))
        out, _, _, res = _solver._flash(prep, *args, T_start=start)
        m_mu = out.mu
        if np.any(res >= options.tol):  # rare: a warm start that did not converge; again from T0
            m_mu = np.where(res < options.tol, m_mu, _solver._flash(prep, *args)[0].mu)
        mu.append(m_mu)
    return _angular_error(mu[0], mu[1], mu[2] if n // 4 >= angular.start // 2 else None, angular.kinks)


def _problems(aniso, material, cond, theta, grid):
    """The conditions of every problem, direction k at speed s in row k n_speed + s, and their angular shape."""
    nd, nv = theta.size, cond.speed.size
    return (_subset(cond, np.tile(np.arange(nv), nd)),
            _Angular(aniso, material, theta, np.repeat(np.arange(nd), nv), grid))


def _by_direction(solved: Solved, nd: int, nv: int, notes: list) -> list[Solved]:
    """The problems of ``solved`` as one :class:`Solved` per direction (speeds in rows), each with ``notes``."""
    out = []
    for k in range(nd):
        p = slice(k * nv, (k + 1) * nv)
        fields = {name: getattr(solved, name)[p] for name in _solver._PER_SCALE + _solver._PER_SPEED}
        out.append(Solved(q=solved.q, converged=bool(np.all(fields["converged_each"])),
                          notes=tuple(dict.fromkeys(solved.notes + tuple(notes))), **fields))
    return out


def _run(prep, angular, n_basis=None) -> tuple[Solved, np.ndarray, int]:
    """The friction of the problems of ``prep`` with the angular estimate: (solution, angular estimate, N).

    The angular grid doubles from its start until the estimate is below a tenth of the tolerance (or stays at
    ``n_basis`` when given: the refinement in q keeps the grid the first pass chose)."""
    if angular.unidirectional:
        return _solver.run_plain(replace(prep, shape=angular.level(0))), np.zeros(prep.n_speed), 0
    n = angular.start if n_basis is None else n_basis
    angular.weights_for(prep.q, n, angular.direction)  # the finest first: the coarser grids' are every other
    quarter = _mu_only(prep, angular.level(n // 4))
    half = _mu_only(prep, angular.level(n // 2))
    while True:
        cur = _solver.run_plain(replace(prep, shape=angular.level(n)))
        # the coarsest grid takes part once it resolves the shape's width (half the starting resolution)
        err_a = _angular_error(cur.mu, half, quarter if n // 4 >= angular.start // 2 else None, angular.kinks)
        if n_basis is not None or np.max(err_a) <= angular.tolerance / 10.0 or n >= _N_MAX:
            return cur, err_a, n
        quarter, half, n = half, cur.mu, 2 * n


def _angular_error(mu, mu_half, mu_quarter, kinks: bool) -> np.ndarray:
    r"""The estimated relative angular error of ``mu`` from the same problem on every other angle (``mu_half``)
    and every fourth (``mu_quarter``, None while that grid is coarser than half the shape's width: then the first
    term alone):

    .. math:: \varepsilon = \max\left(|\mu_N - \mu_{N/2}|,\ |\mu_{N/2} - \mu_{N/4}| / 16\right)
              \big/ f\, |\mu_N| ,

    f = :math:`\sqrt{45}` for a smooth angular shape (Richardson; the second term, the same one level up divided
    by 2^4, the most the fourth-order rule gains per halving, keeps two grids that agree by accident from reading
    small), f = 3 = 2^2 - 1 for a shape with kinks in angle (``kinks``: a stretched roll-off or table, crossed at
    some angles only): across a kink the cubics are second order, with an error that depends on where the kink
    falls between the angles (:math:`\sqrt{45}` read 8x low there, 3 reads 1.8x low)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.abs(mu - mu_half)
        if mu_quarter is not None:
            d = np.maximum(d, np.abs(mu_half - mu_quarter) / 16.0)
        e = d / (_KINK_FACTOR if kinks else angular_error_factor) / np.abs(mu)
    return np.where(np.abs(mu) > 0, e, 0.0)


def _mu_only(prep, shape) -> np.ndarray:
    """The hysteresis friction of every problem with the angular shape ``shape``, without the q estimate."""
    return _solver.run_plain(replace(prep, shape=shape), estimate=False).mu


# ---------------------------------------------------------------------------------------------------------
class _Angular:
    """The angular shape of one anisotropic surface for the problems of a call (direction ``direction[p]`` of
    ``theta`` for problem p): the weights of its cardinal functions at the nodes and their tables on the grid of
    the angular tables, memoised, and :meth:`level` for the kernels at a given angular resolution."""

    def __init__(self, aniso, material, theta, direction, grid):
        self.aniso, self.material, self.theta, self.direction = aniso, material, theta, direction
        self.tolerance = grid.tolerance
        self.unidirectional = hasattr(aniso, "wave_angle_deg")
        self._tables = {}
        self._weights = {}
        self.kinks, self.start = False, 0
        if not self.unidirectional:
            # a surface that does not say otherwise may have kinks in angle: the safe estimate
            self.kinks = bool(getattr(aniso, "angular_kinks", True))
            width = getattr(aniso, "angular_width", None) or 0.25
            self.start = int(min(_N_MAX, max(_N_MIN, 2 ** math.ceil(math.log2(2.0 * math.pi / width)))))

    def subset(self, problems) -> "_Angular":
        """The same surface for the problems ``problems`` alone (sharing the memoised tables)."""
        out = _Angular.__new__(_Angular)
        out.__dict__.update(self.__dict__)
        out.direction = self.direction[problems]
        return out

    def level(self, n: int) -> "_Shape":
        """The shape with ``n`` angular intervals on [0, pi/2] (0: the unidirectional limit), for the solver."""
        return _Shape(self, n, self.direction)

    # --- a PSD with a pointwise angular shape
    def weights_for(self, q: np.ndarray, n: int, direction: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`weights` of the directions the problems ``direction`` slide in, and each problem's row of it."""
        dirs, row = np.unique(direction, return_inverse=True)
        W = self.weights(q, n, None if dirs.size == self.theta.size else dirs)
        return W, np.ascontiguousarray(row, dtype=np.int64)

    def weights(self, q: np.ndarray, n: int, dirs: np.ndarray | None = None) -> np.ndarray:
        """(1/4) w_s(psi_j) at every direction of ``dirs`` (default all), node and angle, (n_dir, n_q, n + 1):
        the mean of the shape at theta + psi_j and theta - psi_j."""
        theta = self.theta if dirs is None else self.theta[dirs]
        memo = self._weights.setdefault((q.tobytes(), None if dirs is None else dirs.tobytes()), {})
        W = memo.get(n)
        if W is None:
            fine = memo.get("fine")
            if fine is not None and fine[0] % n == 0:
                W = np.ascontiguousarray(fine[1][:, :, :: fine[0] // n])
            else:
                psi = np.arange(n + 1) * (0.5 * math.pi / n)
                phi = np.concatenate([theta[:, None] + psi, theta[:, None] - psi], axis=1)
                w = np.asarray(self.aniso.angular_shape(q, np.broadcast_to(phi, (q.size,) + phi.shape)), dtype=float)
                if not np.all(np.isfinite(w)) or np.any(w < 0):
                    raise InputError("surface: the angular shape of the PSD must be finite and >= 0")
                W = np.ascontiguousarray((0.5 * (w[..., : n + 1] + w[..., n + 1:])).transpose(1, 0, 2))
                if n > memo.get("fine", (0,))[0]:
                    memo["fine"] = (n, W)
            memo[n] = W
        if len(self._weights) > 64:
            self._weights.clear()
        return W

    def cardinal(self, n: int, table) -> list[np.ndarray]:
        """The normalised cardinal tables v_j, 3 arrays (1, n_omega, n + 1), on the grid of the angular table."""
        key = ("v", n, table.lw0, table.ln_are.size)
        v = self._tables.get(key)
        if v is None:
            E = self._modulus(table)
            v = []
            for F, power in ((E.real**2, 0), (E.imag**2, 0), (E.imag, 1)):
                c, lo, hi = basis_weights(n, int(round(1.0 / table.dlw)), power)
                V = np.empty((n + 1, F.size))
                _ak.basis_convolution(np.ascontiguousarray(F), c, lo, hi, V)
                total = V.sum(axis=0)
                good = total > 1e-300
                V = np.where(good, V / np.where(good, total, 1.0), 1.0 / (n + 1))
                v.append(np.ascontiguousarray(V.T)[None])
            self._tables[key] = v
        return v

    def _modulus(self, table) -> np.ndarray:
        key = ("E", table.lw0, table.ln_are.size)
        E = self._tables.get(key)
        if E is None:
            E = np.asarray(self.material.E(10.0**table.log10_omega, table.T0), dtype=complex)
            E = E.real + 1j * np.maximum(E.imag, 1e-30 * float(np.max(np.abs(E))))
            self._tables[key] = E
        return E

    # --- the unidirectional limit
    def ratios(self, table) -> list[np.ndarray]:
        r"""The unidirectional limit's angular integrals, point values, over the isotropic ones on the grid of the
        angular table, 3 arrays (n_dir, n_omega, 1):
        :math:`2\pi E'(\omega c)^2 / A_{re}(\omega)`, :math:`2\pi E''(\omega c)^2 / A_{im}(\omega)` and
        :math:`2\pi c\, E''(\omega c) / L(\omega)`, c = |cos(alpha - theta)| (sliding along the ridges, c = 0:
        the relaxed modulus, 12 decades below the table)."""
        key = ("uni", table.lw0, table.ln_are.size)
        r = self._tables.get(key)
        if r is None:
            alpha = math.radians(float(self.aniso.wave_angle_deg))
            c = np.abs(np.cos(alpha - self.theta))
            c = np.where(c < 1e-15, 0.0, c)
            lw = table.log10_omega
            # the frequency read: omega c, at least 12 decades below the table (c -> 0 reads the relaxed modulus)
            lw_c = np.maximum(lw[None, :] + np.log10(np.maximum(c, 1e-300))[:, None], lw[0] - 12.0)
            E = np.asarray(self.material.E(10.0**lw_c, table.T0), dtype=complex)
            if not np.all(np.isfinite(E)) or np.any(E.real <= 0):
                raise InputError(f"material: E(omega, T) must be finite with E' > 0 down to omega = "
                                 f"{10**float(lw_c.min()):.3g} rad/s (read by sliding along the ridges of a "
                                 "unidirectional surface)")
            loss = np.maximum(E.imag, 1e-30 * float(np.max(np.abs(E))))
            two_pi = 2.0 * math.pi
            r = [np.ascontiguousarray(x[:, :, None]) for x in
                 (two_pi * E.real**2 / np.exp(table.ln_are), two_pi * loss**2 / np.exp(table.ln_aim),
                  two_pi * c[:, None] * loss / np.exp(table.ln_l))]
            self._tables[key] = r
        return r


class _Shape:
    """The angular shape of the problems of a call at one angular resolution, as :class:`persson.engine.solver.
    Prepared` takes it: :meth:`kernel` on any nodes, :meth:`subset` for some of the problems."""

    def __init__(self, angular: _Angular, n: int, direction: np.ndarray):
        self.angular, self.n, self.direction = angular, n, direction

    def subset(self, problems) -> "_Shape":
        return _Shape(self.angular, self.n, self.direction[problems])

    def kernel(self, q: np.ndarray, table) -> AngularShape:
        """The :class:`~persson.engine.kernel_arrays.AngularShape` on the nodes ``q`` and the grid of ``table``
        (the weights of the directions these problems slide in alone)."""
        a = self.angular
        if a.unidirectional:
            dirs, direction = np.unique(self.direction, return_inverse=True)
            v = [np.ascontiguousarray(x[dirs]) for x in a.ratios(table)]
            return AngularShape(direction=np.ascontiguousarray(direction, dtype=np.int64),
                                weights=np.ones((1, q.size, 1)), v_re=v[0], v_im=v[1], v_l=v[2])
        W, direction = a.weights_for(q, self.n, self.direction)
        v = a.cardinal(self.n, table)
        return AngularShape(direction=direction, weights=W, v_re=v[0], v_im=v[1], v_l=v[2])


# ---------------------------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=16)
def basis_weights(n: int, per_decade: int, power: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    r"""Product-integration weights of the cardinal functions of the angular interpolation.

    :math:`V_j(\ell) = \int_0^{\pi/2} \beta_j(\psi)\, (\cos\psi)^p F(\ell + \log_{10}\cos\psi)\, d\psi =
    \sum_d c_{j,d} F(\ell - d\Delta)` for F interpolated by 4-point Lagrange polynomials on the grid of step
    :math:`\Delta = 1/` ``per_decade`` (the convention of :func:`persson.engine.tabulate.convolution_weights`) and
    :math:`\beta_j` the cardinal functions of the piecewise-cubic interpolation on :math:`\psi_j = j\pi/(2n)`,
    j = 0..n, mirrored at 0 and :math:`\pi/2`. Each piece between the angular nodes and the cells of the frequency
    grid is integrated by 8-point Gauss-Legendre, in :math:`\psi` up to :math:`t = -\log_{10}\cos\psi = t_s`
    (where the last angular interval starts) and in t beyond it, to :math:`t = 20`; the rest, in closed form, on
    the clamped end of the table.

    Returns
    -------
    c : ndarray (n + 1, n_d)
        ``c[j, d + 1]`` for d = -1 .. n_d - 2.
    d_lo, d_hi : ndarray of int (n + 1,)
        The non-zero range of d per j.
    """
    h = 0.5 * math.pi / n
    dt = 1.0 / per_decade
    n_cells = int(math.ceil(_T_MAX * per_decade))
    c = np.zeros((n + 1, n_cells + 3))
    gx, gw = _GL
    # part 1: in psi, cut at the angular nodes and at the cell edges, up to t_s
    t_s = math.ceil(max(3.0, -math.log10(math.sin(h)) + 0.05) * per_decade) / per_decade
    psi_s = math.acos(10.0 ** (-t_s))
    cells = np.arccos(10.0 ** (-dt * np.arange(1, int(round(t_s * per_decade)))))
    edges = np.unique(np.concatenate([np.arange(n + 1) * h, cells, [psi_s]]))
    edges = edges[edges <= psi_s]
    a, b = edges[:-1, None], edges[1:, None]
    psi = (0.5 * (a + b) + 0.5 * (b - a) * gx).ravel()
    wpsi = (0.5 * (b - a) * gw).ravel()
    mid_t = -np.log10(np.cos(0.5 * (a + b))).ravel()
    cell = np.repeat(np.floor(mid_t / dt).astype(np.int64), gx.size)
    _accumulate(c, psi, wpsi * np.cos(psi) ** power, -np.log10(np.cos(psi)), cell, h, n, dt)
    # part 2: in t, cell by cell, from t_s to 20 decades (all of it inside the last angular interval)
    m = np.arange(int(round(t_s * per_decade)), n_cells)
    tt = ((m[:, None] + 0.5 * (gx + 1.0)) * dt).ravel()
    y = 10.0 ** (-tt)
    jac = math.log(10.0) * y / np.sqrt(-np.expm1(-2.0 * math.log(10.0) * tt))
    _accumulate(c, np.arccos(y), np.tile(0.5 * dt * gw, m.size) * jac * y**power, tt, np.repeat(m, gx.size), h, n,
                dt)
    # beyond 20 decades: the rest of the integral of (cos psi)^p dpsi, on the clamped bottom of the table, at
    # psi = pi/2 where only the last cardinal function is 1
    Y = 10.0 ** (-n_cells * dt)
    c[n, -1] += math.asin(Y) if power == 0 else 1.0 - math.sqrt(1.0 - Y * Y)
    nz = c != 0.0
    d_lo = np.argmax(nz, axis=1) - 1
    d_hi = c.shape[1] - 2 - np.argmax(nz[:, ::-1], axis=1)
    c.setflags(write=False)
    return c, np.ascontiguousarray(d_lo, dtype=np.int64), np.ascontiguousarray(d_hi, dtype=np.int64)


def _accumulate(c, psi, weight, t, cell, h, n, dt):
    """Add the quadrature points (psi, weight, t in cell ``cell``) to the weights c[j, d + 1]."""
    # the cardinal functions: cubic Lagrange on nodes i-1..i+2 of the angular interval i, mirrored at the ends
    i = np.minimum(np.floor(psi / h).astype(np.int64), n - 1)
    u = psi / h - i
    lag_psi = (-u * (u - 1) * (u - 2) / 6, (u + 1) * (u - 1) * (u - 2) / 2, -(u + 1) * u * (u - 2) / 2,
               (u + 1) * u * (u - 1) / 6)
    # the frequency cell: F(l - t) is the cubic in tau = 1 - (t/dt - cell) through the nodes d = cell + 1 - r
    tau = 1.0 - (t / dt - cell)
    lag_t = (-tau * (tau - 1) * (tau - 2) / 6, (tau + 1) * (tau - 1) * (tau - 2) / 2,
             -(tau + 1) * tau * (tau - 2) / 2, (tau + 1) * tau * (tau - 1) / 6)
    for a, la in zip((-1, 0, 1, 2), lag_psi):
        j = i + a
        j = np.where(j < 0, -j, np.where(j > n, 2 * n - j, j))
        for r, lr in zip((-1, 0, 1, 2), lag_t):
            d = cell + 1 - r
            np.add.at(c, (j, d + 1), weight * la * lr)


def _empty_like(s: Solved, n: int) -> Solved:
    fields = {}
    for name in ("G", "P", "T_q", "dmu", "loss", "dG", "ratio", "mu_cumulative"):
        fields[name] = np.empty((n, s.q.size))
    for name in ("mu", "error_estimate", "excited_layer", "residual"):
        fields[name] = np.empty(n)
    return Solved(q=s.q, converged=True, converged_each=np.ones(n, dtype=bool),
                  iterations=np.zeros(n, dtype=np.int64), notes=(), **fields)


def _put(base: Solved, idx: np.ndarray, part: Solved) -> Solved:
    for name in ("G", "P", "T_q", "dmu", "loss", "dG", "ratio", "mu_cumulative", "mu", "error_estimate",
                 "excited_layer", "residual", "converged_each", "iterations"):
        getattr(base, name)[idx] = getattr(part, name)
    return replace(base, notes=tuple(dict.fromkeys(base.notes + part.notes)))
