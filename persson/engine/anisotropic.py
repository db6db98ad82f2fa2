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
from .conditions import Conditions
from .solver import _SAFETY, Solved, _relative_error, _subset, prepare
from ..errors import InputError

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
        A temperature-solver effect (flash temperature): not available on an anisotropic surface.
    theta_deg : ndarray (n_dir,)
        Sliding directions, degrees.

    Returns
    -------
    list of Solved
        One per direction, per speed and wavevector node as the isotropic solver's.
    """
    if thermal is not None:
        raise InputError(f"effects: {thermal.name!r} (a temperature solver) is not available with an anisotropic "
                         "surface yet; the flash temperature of a sliding direction needs the heat source of that "
                         "direction: remove the effect, or use the surface's angular mean (surface.to_isotropic())")
    theta = np.radians(np.asarray(theta_deg, dtype=float).ravel())
    T = np.broadcast_to(np.asarray(cond.temperature, dtype=float), cond.speed.shape)
    if np.all(T == T[0]) or hasattr(material, "log10_aT"):
        return _solve_group(aniso, surface, material, cond, grid, nu, gamma, correction, modulus, theta)
    # a material without a shift law: one modulus table per temperature, merged back speed by speed
    out = None
    for t in np.unique(T):
        idx = np.flatnonzero(T == t)
        part = _solve_group(aniso, surface, material, _subset(cond, idx), grid, nu, gamma, correction, modulus,
                            theta)
        out = [_empty_like(p, T.size) for p in part] if out is None else out
        out = [_put(o, idx, p) for o, p in zip(out, part)]
    return out


# ---------------------------------------------------------------------------------------------------------
def _solve_group(aniso, surface, material, cond, grid, nu, gamma, correction, modulus, theta) -> list[Solved]:
    """One modulus table for every speed; q refined per problem (direction, speed) where the estimate is high."""
    nd, nv = theta.size, cond.speed.size
    prep = prepare(surface, material, cond, grid, nu, gamma=gamma, correction=correction, modulus=modulus)
    pd, ps = np.repeat(np.arange(nd), nv), np.tile(np.arange(nv), nd)
    angular = _Angular(aniso, prep, material, theta, grid)
    out = _run(prep, angular, pd, ps)
    for level in range(1, grid.max_refinement + 1):
        bad = np.flatnonzero(out["err_q"] > grid.tolerance / _SAFETY)
        if bad.size == 0:
            break
        speeds = np.unique(ps[bad])
        sub = prepare(surface, material, _subset(cond, speeds), grid, nu, gamma=gamma, correction=correction,
                      modulus=modulus, refine=level, nodes=prep.q)
        where = np.searchsorted(speeds, ps[bad])
        fine = _run(sub, angular.on(sub), pd[bad], where, n_basis=out["n"])
        stride = 2**level
        for name in _PER_SCALE:
            out[name][bad] = fine[name][:, ::stride]
        for name in ("mu", "layer", "err_q", "err_a"):
            out[name][bad] = fine[name]
    err = out["err_q"] + out["err_a"]
    notes = []
    if out["n"] and np.any(out["err_a"] > grid.tolerance / 10.0):
        notes.append(f"angular resolution: {out['n']} intervals on [0, pi/2] (the most) leave an estimated angular "
                     f"error up to {float(np.max(out['err_a'])):.2g}: the angular shape of the PSD is very narrow")
    res = []
    for k in range(nd):
        p = slice(k * nv, (k + 1) * nv)
        mu = out["mu"][p]
        res.append(Solved(q=prep.q, G=out["G"][p], P=out["P"][p], T_q=np.repeat(prep.T0[:, None], prep.q.size, 1),
                          dmu=out["dmu"][p], loss=out["L"][p], dG=out["dG"][p], ratio=out["R"][p],
                          mu_cumulative=out["cum"][p], mu=mu, error_estimate=err[p],
                          excited_layer=np.where(mu > 0, out["layer"][p] / np.where(mu > 0, mu, 1.0),
                                                 1.0 / prep.q[0]),
                          converged=True, converged_each=np.ones(nv, dtype=bool), iterations=np.zeros(nv, np.int64),
                          residual=np.zeros(nv), notes=tuple(notes)))
    return res


_PER_SCALE = ("G", "P", "dmu", "cum", "dG", "R", "L")


def _run(prep, angular, pd, ps, n_basis=None) -> dict:
    """The friction of the problems (``pd[p]``, ``ps[p]``) on the nodes of ``prep``, with the angular estimate.

    The angular grid doubles from its start until the estimate is below a tenth of the tolerance (or at
    ``n_basis`` when given: the refinement in q keeps the grid the first pass chose)."""
    if angular.unidirectional:
        out = _solve_factors(prep, *angular.unidirectional_factors(pd, ps))
        out.update(err_a=np.zeros(pd.size), n=0)
        return out
    n = angular.start if n_basis is None else n_basis
    angular.weights(n)  # the finest first: the coarser grids' weights are every other of its values
    quarter = _mu_only(prep, *angular.factors(pd, ps, n // 4))
    half = _mu_only(prep, *angular.factors(pd, ps, n // 2))
    while True:
        cur = _solve_factors(prep, *angular.factors(pd, ps, n))
        # the coarsest grid takes part once it resolves the shape's width (half the starting resolution)
        err_a = _angular_error(cur["mu"], half, quarter if n // 4 >= angular.start // 2 else None, angular.kinks)
        if n_basis is not None or np.max(err_a) <= angular.tolerance / 10.0 or n >= _N_MAX:
            cur.update(err_a=err_a, n=n)
            return cur
        quarter, half, n = half, cur["mu"], 2 * n


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


def _mu_only(prep, K, R, L) -> np.ndarray:
    """The hysteresis friction of every problem from its angular factors, nothing else."""
    mu = np.empty(K.shape[0])
    _ak.friction_mu(prep.q, prep.quad, K, R, prep.law, mu)
    return mu


def _solve_factors(prep, K, R, L) -> dict:
    """The q integrals of every problem from its angular factors (n_problem, n_q)."""
    n, nq = K.shape
    out = {k: np.empty((n, nq)) for k in ("G", "P", "dmu", "cum", "dG")}
    out.update(R=R, L=L, layer=np.empty(n), mu=np.empty(n))
    mu_c, mu_cc = np.empty(n), np.empty(n)
    _ak.friction_problems(prep.q, prep.q4C, prep.quad, K, R, L, prep.law, prep.coarse, prep.quad_coarse,
                          prep.coarser, prep.quad_coarser, out["G"], out["P"], out["dmu"], out["cum"], out["dG"],
                          out["layer"], out["mu"], mu_c, mu_cc)
    out["err_q"] = _relative_error(out["mu"], mu_c, mu_cc)
    return out


class _Angular:
    """The angular factors of one anisotropic surface on the nodes of a prepared problem, per direction and speed."""

    def __init__(self, aniso, prep, material, theta, grid, _tables=None):
        self.aniso, self.prep, self.material, self.theta, self.grid = aniso, prep, material, theta, grid
        self.tolerance = grid.tolerance
        self.unidirectional = hasattr(aniso, "wave_angle_deg")
        t = prep.table
        self.lw = t.lw0 + t.dlw * np.arange(t.ln_are.size)
        # the modulus on the angular table's grid (shifted speeds read it as the isotropic tables are read)
        self._tables = {} if _tables is None else _tables
        if not self.unidirectional:
            # a surface that does not say otherwise may have kinks in angle: the safe estimate
            self.kinks = bool(getattr(aniso, "angular_kinks", True))
            width = getattr(aniso, "angular_width", None) or 0.25
            self.start = int(min(_N_MAX, max(_N_MIN, 2 ** math.ceil(math.log2(2.0 * math.pi / width)))))
            self._shape = {}

    def on(self, prep) -> "_Angular":
        """The same surface and directions on the nodes of another prepared problem (same modulus table)."""
        return _Angular(self.aniso, prep, self.material, self.theta, self.grid, self._tables)

    # --- a PSD with a pointwise angular shape
    def factors(self, pd, ps, n):
        prep = self.prep
        rho = self._rho(n)
        K = np.empty((pd.size, prep.q.size))
        R, L = np.empty_like(K), np.empty_like(K)
        t = prep.table
        _ak.problem_factors(pd, ps, prep.lq10, prep.lv10, prep.shift[:, 0].copy(), prep.vshift[:, 0].copy(),
                            prep.fq, prep.gq, t.lw0, 1.0 / t.dlw, t.ln_are, t.ln_aim, t.ln_l, prep.scale, *rho, K, R, L)
        return K, R, L

    def _rho(self, n):
        r""":math:`\rho` (n_q, n_dir, n_speed): the shape's weights times the cardinal tables at every node."""
        prep = self.prep
        v = self._cardinal(n)
        nq, nv, nb = prep.q.size, prep.v.size, n + 1
        V = [np.empty((nq, nb, nv)) for _ in range(3)]
        t = prep.table
        _ak.basis_lookup(prep.lq10, prep.lv10, prep.shift[:, 0].copy(), t.lw0, 1.0 / t.dlw, *v, *V)
        W = self.weights(n)  # (n_q, n_dir, n_basis)
        return [np.matmul(W, Vx) for Vx in V]

    def weights(self, n) -> np.ndarray:
        """(1/4) w_s(psi_j) at every node and direction: the mean of the shape at theta + psi_j and theta - psi_j."""
        key = n
        W = self._shape.get(key)
        if W is None:
            fine = self._shape.get("fine")
            if fine is not None and fine[0] % n == 0:
                W = np.ascontiguousarray(fine[1][:, :, :: fine[0] // n])
            else:
                psi = np.arange(n + 1) * (0.5 * math.pi / n)
                phi = np.concatenate([self.theta[:, None] + psi, self.theta[:, None] - psi], axis=1)
                q = self.prep.q
                w = self.aniso.angular_shape(q, np.broadcast_to(phi, (q.size,) + phi.shape))
                w = np.asarray(w, dtype=float)
                if not np.all(np.isfinite(w)) or np.any(w < 0):
                    raise InputError("surface: the angular shape of the PSD must be finite and >= 0")
                W = np.ascontiguousarray(0.5 * (w[..., : n + 1] + w[..., n + 1:]))
                fine_n = self._shape.get("fine", (0,))[0]
                if n > fine_n:
                    self._shape["fine"] = (n, W)
            self._shape[key] = W
        return W

    def _cardinal(self, n):
        """The normalised cardinal tables v_j (3 arrays (n + 1, n_omega)) on the angular table's grid."""
        t = self.prep.table
        key = ("v", n, t.lw0, t.ln_are.size)
        v = self._tables.get(key)
        if v is None:
            E = self._modulus()
            v = []
            for F, power in ((E.real**2, 0), (E.imag**2, 0), (E.imag, 1)):
                c, lo, hi = basis_weights(n, int(round(1.0 / self.prep.table.dlw)), power)
                V = np.empty((n + 1, F.size))
                _ak.basis_convolution(np.ascontiguousarray(F), c, lo, hi, V)
                total = V.sum(axis=0)
                good = total > 1e-300
                v.append(np.ascontiguousarray(np.where(good, V / np.where(good, total, 1.0), 1.0 / (n + 1))))
            self._tables[key] = v
        return v

    def _modulus(self) -> np.ndarray:
        t = self.prep.table
        key = ("E", t.lw0, t.ln_are.size)
        E = self._tables.get(key)
        if E is None:
            E = np.asarray(self.material.E(10.0**self.lw, t.T0), dtype=complex)
            E = E.real + 1j * np.maximum(E.imag, 1e-30 * float(np.max(np.abs(E))))
            self._tables[key] = E
        return E

    # --- the unidirectional limit
    def unidirectional_factors(self, pd, ps):
        prep = self.prep
        alpha = math.radians(float(self.aniso.wave_angle_deg))
        c = np.abs(np.cos(alpha - self.theta))
        c = np.where(c < 1e-15, 0.0, c)
        lo, per_decade, ln_re, ln_im = self._modulus_uni(c)
        K = np.empty((pd.size, prep.q.size))
        R, L = np.empty_like(K), np.empty_like(K)
        _ak.unidirectional_factors(np.ascontiguousarray(c[pd]), ps, prep.lq10, prep.lv10,
                                   prep.shift[:, 0].copy(), prep.vshift[:, 0].copy(), prep.fq, prep.gq, lo,
                                   per_decade, ln_re, ln_im, prep.scale, K, R, L)
        return K, R, L

    def _modulus_uni(self, c):
        """ln E', ln E'' on a grid reaching the lowest frequency q v a_T |cos| of any direction (12 decades below
        the slowest speed's at most: a direction along the ridges reads the relaxed modulus there)."""
        prep = self.prep
        t = prep.table
        per_decade = int(round(1.0 / t.dlw))
        lw_hi = t.lw0 + t.dlw * (t.ln_are.size - 1)
        low = math.log10(prep.q[0]) + float(np.min(prep.lv10 + prep.shift[:, 0]))
        cmin = float(np.min(c[c > 0])) if np.any(c > 0) else 1.0
        lw_lo = low + max(math.log10(cmin), -12.0) - 0.5
        if np.any(c == 0.0):  # sliding along the ridges: the relaxed modulus, 12 decades below any excitation
            lw_lo = min(lw_lo, low - 12.0)
        key = ("uni", round(lw_lo * per_decade), round(lw_hi * per_decade))
        tab = self._tables.get(key)
        if tab is None:
            lo = math.floor(lw_lo * per_decade) / per_decade
            lw = lo + np.arange(int(round((lw_hi - lo) * per_decade)) + 4) / per_decade
            E = np.asarray(self.material.E(10.0**lw, t.T0), dtype=complex)
            if not np.all(np.isfinite(E)) or np.any(E.real <= 0):
                raise InputError(f"material: E(omega, T) must be finite with E' > 0 down to omega = {10**lo:.3g} "
                                 "rad/s (read by sliding along the ridges of a unidirectional surface)")
            floor = 1e-30 * float(np.max(np.abs(E)))
            tab = (float(lo), float(per_decade), np.log(E.real), np.log(np.maximum(E.imag, floor)))
            self._tables[key] = tab
        return tab


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
