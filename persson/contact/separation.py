r"""Interfacial separation, penetration depth and excited-layer thickness.

Mean separation (Persson, Phys. Rev. Lett. 99, 125502 (2007); Yang & Persson, J. Phys.: Condens. Matter 20,
215214 (2008), Eq. 11, at magnification zeta = 1):

.. math::
    \bar u = \sqrt{\pi} \int_{q_0}^{q_1} dq\, q^2 C(q) w(q) \int_{\sigma_0}^{\infty} \frac{dp'}{p'}
             \left[\gamma + 3(1-\gamma)P^2(q, p')\right] e^{-[w(q) p'/E^*]^2},
    \qquad w(q) = \left(\pi \int_{q_0}^{q} dq' q'^3 C(q')\right)^{-1/2}

with :math:`P(q, p') = \mathrm{erf}(p' w(q)/E^*)`. Writing :math:`w(q)\sigma_0/E^* = 1/(2\sqrt{G(q)})`
(exact for an elastic solid, where :math:`G = (\pi/4)(E^*/\sigma_0)^2\int q^3 C dq`) and substituting
:math:`t = p' w / E^*` gives

.. math::
    \bar u = \sqrt{\pi} \int_{q_0}^{q_1} dq\, q^2 C(q) w(q)\, J\!\left(G(q)\right),\quad
    J = \int_x^\infty \frac{dt}{t}\left[\gamma + 3(1-\gamma)\mathrm{erf}^2 t\right] e^{-t^2}
      = \frac{\gamma}{2} E_1(x^2) + 3(1-\gamma) \int_x^\infty \frac{\mathrm{erf}^2 t\, e^{-t^2}}{t}dt,
    \quad x = \frac{1}{2\sqrt G}.

The same formula holds with an area correction (:mod:`persson.contact.corrections`) when J is the kernel of the
corrected area, :func:`persson.contact.corrections.separation_kernel` (the relation between u_bar and the elastic
energy, :math:`\bar u = \int_{\sigma_0}^\infty dp\, p^{-1}\, d(U_{el}/A_0)/dp`, kept).
Numerically the q integral runs over :math:`s = (\int_{q_0}^{q} q'^3 C dq')^{1/2}`, since
:math:`\sqrt\pi q^2 C w\, dq = 2\, ds / q` is regular at q0 where w(q) diverges (:func:`integral_over_s`):
s and its inverse q(s) are exact for a PSD that is a power law between nodes, ln G is linear in ln s between
nodes (exact for an elastic solid), intervals are split until ln G changes by at most 0.5 across each, and each
part is a 4-point Gauss-Legendre panel in ln s. Any grid, uniform or not, coarse or fine: for an elastic solid
the result is accurate to about 1e-6 (the tabulated kernel) on any node set.
When the nodes do not include the PSD's kinks (the engine's log-uniform grid and a roll-off between two nodes),
the caller passes s from the PSD's exact moments (``s=``; :func:`persson.engine.quadrature.separation_moments`).
For a viscoelastic solid sliding at speed v the engine's G(q, v) (with the modulus at the excitation
frequencies) replaces the elastic G, which keeps P(q) = erf(1/(2 sqrt G)) and u_bar consistent.
At small pressure only the gamma term diverges: sigma0 ~ exp(-u_bar / u0) with
:math:`u_0 = \sqrt{\pi}\,\gamma \int q^2 C(q) w(q) dq` (Persson 2007).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy import special

from frictioncite import doi

from .corrections import _table as _corrections_table
from .corrections import (GFMD_GAP_GAMMA, WANG_MUSER_A, check_correction, check_gap_correction,
                          separation_kernel_ln)
from ..errors import InputError

__all__ = ["mean_separation", "separation_and_energy", "separation_decay_length", "small_load_factor",
           "penetration_depth", "elastic_energy_per_load", "excited_layer_thickness", "integral_over_s",
           "segment_moments", "moment_from_start", "PENETRATION_DEFINITIONS"]

#: Names of the penetration-depth definitions of :func:`penetration_depth`.
PENETRATION_DEFINITIONS = ("persson", "load-weighted", "kluppel")


@doi("10.1103/PhysRevLett.99.125502", "10.1088/0953-8984/20/21/215214")
def mean_separation(q, C, G, gamma: float, *, correction: str | None = None,
                    gap_correction: str = "area", s=None) -> np.ndarray:
    """Average interfacial separation u_bar, m, per row of ``G``.

    Parameters
    ----------
    q : ndarray (n_q,)
        Wavevectors, rad/m, strictly increasing from q0 to q1 (any spacing).
    C : ndarray (n_q,)
        PSD, m^4, > 0 (taken as a power law between nodes).
    G : ndarray (n_speed, n_q)
        Persson's G(q) (0 at q0).
    gamma : float
        Parameter of Yang & Persson (2008); 1 recovers Persson (2007).
    correction : {None, "yang-persson", "xu2024", "wang-muser"}
        Area correction (:mod:`persson.contact.corrections`); None is uncorrected Persson theory.
    gap_correction : {"area", "persson", "xu2024-hybrid", "gfmd-gap"} or None
        Energy law of the separation (:mod:`persson.contact.corrections`); "area" follows the area law.
    s : ndarray (n_q,), optional
        s_i = (int_{q0}^{q_i} q^3 C dq)^(1/2) at the nodes (dimensionless), when it is known more exactly
        than from the nodes (a PSD with a kink between two nodes, such as a roll-off: the solver's moments
        integrate between the PSD's breakpoints). Default: C taken as a power law between nodes.

    Returns
    -------
    ndarray (n_speed,)
        u_bar, m.
    """
    return _separation_and_energy(q, C, G, gamma, correction, gap_correction, energy=False, s=s)[0]


@doi("10.1103/PhysRevLett.99.125502", "10.1088/0953-8984/20/21/215214")
def separation_and_energy(q, C, G, gamma: float, *, correction: str | None = None,
                          gap_correction: str = "area", s=None) -> tuple[np.ndarray, np.ndarray]:
    """(:func:`mean_separation`, :func:`elastic_energy_per_load`) in one pass over the nodes (what a friction
    result reports: the separation and the load-weighted penetration depth). Same arguments."""
    return _separation_and_energy(q, C, G, gamma, correction, gap_correction, energy=True, s=s)


def _separation_and_energy(q, C, G, gamma, correction, gap_correction, energy, s=None):
    correction, gamma = check_correction(correction, gamma)
    gap = check_gap_correction(gap_correction, correction, gamma)
    q = np.asarray(q, dtype=float)
    C = np.asarray(C, dtype=float)
    G = np.atleast_2d(np.asarray(G, dtype=float))

    def kernel(lng, s, q):
        return separation_kernel_ln(lng, correction, gamma, gap)

    s = _s(q, C) if s is None else _checked_s(s, q)
    first = _first_interval(q, C, s, G, kernel, 0.0, True)
    U = _energy_first(q, C, s, G, correction, gamma, gap) if energy else None
    if q.size < 3:
        return 2.0 * first, (None if U is None else 0.5 * math.pi * U)
    # the other intervals: the same 4-point rule as integral_over_s, in a compiled loop (the hot path of
    # every friction call)
    tab = _corrections_table(correction, gamma, gap)
    slope = (tab.J[-1] - tab.J[-2]) / (tab.lnG[-1] - tab.lnG[-2])
    qr, Cr, sr, lnGr = _refined(q, C, s, np.log(np.maximum(G, 1e-300)))
    rest = _kernel_sum(lnG=lnGr, q=qr, C=Cr, s=sr, lnG_first=tab.lnG[0], lnG_last=tab.lnG[-1],
                       inv_step=tab.inv_step, lnJ=tab.lnJ_floor, J_last=tab.J[-1], slope_last=slope, glx=_GL_X,
                       glw=_GL_W)
    if energy:
        Gr = np.exp(lnGr)
        Gr[:, 0] = G[:, 0]
        # E*_q / sigma0 on each (refined) interval: [(dG/dm3) / (pi/4)]^(1/2), m3 = s^2
        e = np.sqrt(np.maximum(np.diff(Gr, axis=1), 0.0) / np.diff(sr * sr) / (math.pi / 4.0))
        U = 0.5 * math.pi * (U + _energy_sum(lnGr, qr, Cr, sr, e, tab.lnG[0], tab.lnG[-1], tab.inv_step, tab.lnW,
                                             _GL_X, _GL_W))
    return 2.0 * (first + rest), U


def _energy_first(q, C, s, G, correction, gamma, gap):
    """int_0^{s_1} (E*_q / sigma0) W 2 s ds / q: the first interval of the elastic energy per unit load (without
    its factor pi/2); E*_q / sigma0 = [(dG/dm3) / (pi/4)]^(1/2) is constant there (G is proportional to m3 = s^2
    from G = 0 at q0, exact for an elastic solid)."""
    tab = _corrections_table(correction, gamma, gap)
    e0 = np.sqrt(np.maximum(G[:, 1] - G[:, 0], 0.0) / (s[1] ** 2 - s[0] ** 2) / (math.pi / 4.0))
    return _energy_first_sum(np.ascontiguousarray(G[:, 1]), e0, q[0], q[1], C[0], C[1], s[1], _G_NEGLIGIBLE,
                             tab.lnG[0], tab.lnG[-1], tab.inv_step, tab.lnW, _GL_X, _GL_W)


@doi("10.1103/PhysRevLett.99.125502")
def separation_decay_length(q, C, gamma: float, *, correction: str | None = None,
                            gap_correction: str = "area") -> float:
    r"""u0 of the large-separation law :math:`\sigma_0 \propto \exp(-\bar u/u_0)`, m:
    :math:`u_0 = \sqrt\pi\,\gamma\int_{q_0}^{q_1} q^2 C(q) w(q) dq` (Persson 2007).

    At small load the energy weight is :math:`W \approx S_e(0)\,P_e` with :math:`P_e \approx k/\sqrt{\pi G}`, so
    the kernel grows as :math:`(S_e(0)\,k/2)\ln G` and :math:`\gamma` becomes :math:`S_e(0)\,k` in u0: with an
    area correction of Yang-Persson type followed by the energy (``gap_correction="area"``) the area is
    :math:`1/\sqrt\gamma` times larger and :math:`\gamma` becomes :math:`\sqrt\gamma`; ``"gfmd-gap"`` gives
    its own :math:`\gamma_g`.
    """
    correction, gamma = check_correction(correction, gamma)
    gap = check_gap_correction(gap_correction, correction, gamma)
    q = np.asarray(q, dtype=float)
    C = np.asarray(C, dtype=float)
    g_eff = small_load_factor(correction, gamma, gap)
    # int ds/q: 4-point Gauss-Legendre in s per interval, q(s) exact between nodes (regular also at q0)
    s = _s(q, C)
    half = 0.5 * np.diff(s)
    su = (0.5 * (s[:-1] + s[1:]))[:, None] + half[:, None] * _GL_X[None, :]
    qu = _q_at_moment(q, C, su * su - s[:-1, None] ** 2)
    return 2.0 * g_eff * float(np.sum(half[:, None] * _GL_W[None, :] / qu))


def small_load_factor(correction, gamma: float, gap_correction: str = "area") -> float:
    """The factor S_e(0) k that takes the place of gamma in u0 (:func:`separation_decay_length`)."""
    gap = check_gap_correction(gap_correction, correction, gamma)
    if gap in ("persson", "gfmd-gap"):
        return gamma if gap == "persson" else GFMD_GAP_GAMMA
    if gap == "xu2024-hybrid":
        return math.sqrt(gamma)                 # S_WM(0) = gamma on the xu2024 area, 1/sqrt(gamma) times larger
    if correction is None:
        return gamma
    if correction == "wang-muser":
        return math.sqrt(WANG_MUSER_A)
    return math.sqrt(gamma)


@doi("10.1103/PhysRevLett.99.125502", "10.5254/1.3547607", "10.1098/rspa.1966.0242")
def penetration_depth(u_bar, hrms: float, *, definition: str = "persson", n_sigma: float = 3.0,
                      energy_per_load=None) -> np.ndarray:
    r"""Penetration depth of the road asperities into the rubber, m.

    The rubber's mean surface lies at :math:`\bar u` above the mean plane of the hard surface (Persson 2007:
    :math:`\bar u` is the average separation of the two mean planes); a point of the hard surface at height z in
    contact pushes the rubber's surface :math:`z - \bar u` above that mean surface.

    ``"load-weighted"``
        The load-weighted mean of that penetration over the real contact,

        .. math:: \delta_p = \frac{\int p(x)\,[z(x) - \bar u]\,d^2x}{\int p(x)\,d^2x} = \frac{2\,U_{el}}{A_0\sigma_0},

        the second form by Clapeyron's theorem (the elastic energy of a linear solid is half the work of its surface
        tractions on its surface displacements, and the fluctuating displacement is :math:`z - \bar u` where
        the traction acts; for a Hertzian asperity :math:`\delta_p` is 4/5 of the indentation depth). It needs
        the elastic energy per unit load, ``energy_per_load`` :math:`= U_{el}/(A_0\sigma_0)`
        (:func:`elastic_energy_per_load`). Positive and continuous at every load: at small load, where
        :math:`\sigma_0 \propto e^{-\bar u/u_0}` and :math:`U_{el}/A_0 = \int_{\bar u}^\infty \sigma_0\,d\bar u
        = u_0\sigma_0`, it tends to :math:`2 u_0` (each asperity in contact is pressed in by the same depth
        whatever their number); at full contact it falls as :math:`1/\sigma_0` (the pressure is spread over high
        and low points alike).
    ``"persson"`` (default)
        The depth of the highest asperities: their tops are taken at :math:`z_{top} = n_\sigma h_{rms}`
        (``n_sigma = 3``: the 99.87 % quantile of the Gaussian height distribution), buried
        :math:`n_\sigma h_{rms} - \bar u` deep, and never less deep than the load-weighted mean penetration (the
        deepest asperity is pressed in at least as far as the load-weighted mean of all of them):

        .. math:: \delta = \max\left(n_\sigma h_{rms} - \bar u,\; \delta_p\right).

        Where the rubber's mean surface lies above the quantile (:math:`\bar u > n_\sigma h_{rms}` at small loads,
        with contact on still higher tops) the depth is :math:`\delta_p`, positive and continuous; without
        ``energy_per_load`` it is :math:`\max(n_\sigma h_{rms} - \bar u, 0)`, 0 there. The quantile is a convention
        of this package, not a result of the theory; the depth moves one-to-one with it.
    ``"kluppel"``
        Mean penetration of the asperities that reach above the rubber's mean surface: the mean excess height
        of the height distribution above :math:`d = \bar u`, as in the Greenwood-Williamson-type description of
        Klüppel & Heinrich (Rubber Chem. Technol. 73, 578 (2000)) (the integrals
        :math:`F_n(t) = \int_t^\infty (s-t)^n \phi(s) ds` of Greenwood & Williamson, Proc. R. Soc. A 295, 300
        (1966)). For a Gaussian, with :math:`t = \bar u/h_{rms}`:

        .. math:: \delta = h_{rms}\,\frac{F_1(t)}{F_0(t)} = h_{rms}\left[\frac{\varphi(t)}{Q(t)} - t\right],

        :math:`\varphi` the standard normal density, Q its upper tail. A geometric estimate (every point above
        :math:`\bar u` counted, pressed or not); it does not depend on ``n_sigma``.

    Parameters
    ----------
    u_bar : float or array_like
        Mean interfacial separation, m (>= 0).
    hrms : float
        RMS height of the hard surface, m (> 0).
    definition : {"persson", "load-weighted", "kluppel"}
        Which definition.
    n_sigma : float
        Height of the asperity tops in units of h_rms ("persson" only), > 0.
    energy_per_load : float or array_like, optional
        :math:`U_{el}/(A_0\sigma_0)`, m, broadcast against ``u_bar``: required by "load-weighted", the lower
        bound of "persson".

    Returns
    -------
    ndarray
        Penetration depth, m, >= 0, shape of ``u_bar`` (broadcast with ``energy_per_load``).
    """
    if definition not in PENETRATION_DEFINITIONS:
        raise InputError(f"definition: expected one of {list(PENETRATION_DEFINITIONS)}, got {definition!r}")
    u = np.asarray(u_bar, dtype=float)
    h = float(hrms)
    if not (math.isfinite(h) and h > 0):
        raise InputError(f"hrms: expected an rms height > 0 m, got {hrms!r}")
    e = None
    if energy_per_load is not None:
        e = np.asarray(energy_per_load, dtype=float)
        if not np.all(np.isfinite(e)) or np.any(e < 0):
            raise InputError("energy_per_load: expected finite values >= 0 m")
    if definition == "load-weighted":
        if e is None:
            raise InputError("energy_per_load: the 'load-weighted' penetration depth needs the elastic energy per "
                             "unit load U_el/(A0 sigma0) in m (elastic_energy_per_load)")
        return np.broadcast_to(2.0 * e, np.broadcast_shapes(u.shape, e.shape)).copy()
    if definition == "persson":
        n = float(n_sigma)
        if isinstance(n_sigma, bool) or not (math.isfinite(n) and n > 0):
            raise InputError(f"n_sigma: expected a number of standard deviations > 0, got {n_sigma!r}")
        return np.maximum(n * h - u, 0.0 if e is None else 2.0 * e)
    # phi(t)/Q(t) = sqrt(2/pi) / erfcx(t/sqrt 2): no underflow of Q at large t (the Mills ratio).
    t = u / h
    return h * (math.sqrt(2.0 / math.pi) / special.erfcx(t / math.sqrt(2.0)) - t)


@doi("10.1088/0953-8984/20/21/215214")
def elastic_energy_per_load(q, C, G, gamma: float, *, correction: str | None = None,
                            gap_correction: str = "area", s=None) -> np.ndarray:
    r"""Elastic energy per unit nominal area and unit load, :math:`U_{el}/(A_0\sigma_0)`, m, per row of ``G``.

    Yang & Persson (2008): :math:`U_{el}/A_0 = \frac{\pi}{2}\int dq\, q^2 C\, E^*_q\, W(G(q))`, W the energy
    weight of :func:`persson.contact.corrections.energy_weight`. The effective modulus at scale q is the one
    that G implies, :math:`E^*_q = \sigma_0\,[(dG/dm_3)/(\pi/4)]^{1/2}` (:math:`m_3 = \int q^3 C dq`): exact for an
    elastic solid (:math:`G = (\pi/4)(E^*/\sigma_0)^2 m_3`), a definition for a viscoelastic one. So
    :math:`U_{el}/(A_0\sigma_0)` depends on G alone. Half of :math:`2U_{el}/(A_0\sigma_0)`, the load-weighted
    penetration depth (:func:`penetration_depth`).

    Parameters
    ----------
    q, C : ndarray (n_q,)
        Nodes (rad/m, increasing) and PSD (m^4, > 0; a power law between nodes).
    G : ndarray (n, n_q)
        Persson's G(q) (0 at q0, increasing).
    gamma, correction, gap_correction, s
        As in :func:`mean_separation`.

    Returns
    -------
    ndarray (n,)
        :math:`U_{el}/(A_0\sigma_0)`, m.
    """
    return _separation_and_energy(q, C, G, gamma, correction, gap_correction, energy=True, s=s)[1]


@doi("10.1063/1.1388626")
def excited_layer_thickness(q, dmu_dlnq) -> np.ndarray:
    r"""Thickness of the rubber layer that the roughness deforms, m, weighted by ``dmu_dlnq``:

    .. math:: \ell = \frac{\int q^{-1}\, dw}{\int dw}

    A deformation of wavevector q decays as :math:`e^{-qz}` into the rubber (Persson 2001, Sec. 2), so the
    weighted mean of 1/q is the depth that carries the weight: the dissipated energy (``dmu_dlnq`` of the
    friction result, the excited layer of the hysteresis) or the stored elastic energy per ln q (the strained
    layer of a contact). Any grid in q.

    Parameters
    ----------
    q : ndarray (n_q,)
        Wavevectors, rad/m.
    dmu_dlnq : ndarray (n_q,) or (n, n_q)
        The weight per ln q (>= 0).

    Returns
    -------
    ndarray (n,)
        The thickness, m (1/q0 where the weight vanishes).
    """
    q = np.asarray(q, dtype=float)
    d = np.atleast_2d(np.asarray(dmu_dlnq, dtype=float))
    x = np.log(q)
    num = _integrate().trapezoid(d / q, x=x, axis=-1)
    den = _integrate().trapezoid(d, x=x, axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.where(den > 0, num / np.where(den > 0, den, 1.0), 1.0 / q[0])
    return out


# ---------------------------------------------------------------------------------------------------------
# 4-point Gauss-Legendre rule on [-1, 1] (an interval spans a few hundredths of ln s: error far below 1e-9)
_GL_X, _GL_W = np.polynomial.legendre.leggauss(4)
# J(G) vanishes to double precision below this G (J ~ exp(-1/(4G))) and P(G) = 1 (erfc(50) ~ 1e-1088)
_G_NEGLIGIBLE = 1e-4


def integral_over_s(q, C, G, f, below=0.0, log_g: bool = False) -> np.ndarray:
    r""":math:`\int_0^{s_{end}} f(G(s), s, q(s))\, ds / q(s)` per row of G,
    :math:`s = (\int_{q_0}^{q} q'^3 C dq')^{1/2}`.

    Integrals over q of the form :math:`\int dq\, q^2 C w(q)\, F(G(q))` (:math:`w \propto 1/s`, the separation)
    or :math:`\int dq\, q^2 C\, F(G(q)) = \int 2 s F\, ds/q` (the elastic energy) have this form with a
    regular integrand. Each interval of the nodes is one 4-point Gauss-Legendre panel in ln s, with ln G
    linear in ln s inside it (exact for an elastic solid, where G is proportional to s^2) and q(s) the
    inverse of the exact moment of the power law between the nodes; any spacing of the nodes. On the first
    interval, where G rises from 0 at q0 and F(G) may change from its G = 0 value to a logarithmic growth
    within a tiny part of it, G = G_1 (s/s_1)^2 and panels of width <= 1 in ln s run from where G = 1e-4 to
    s_1; below that point the integral is ``below(s_lo, q_lo)`` (a function of s and q there, or a
    constant).

    Parameters
    ----------
    q, C : ndarray (n_q,)
        Nodes (rad/m, increasing) and PSD (m^4, > 0).
    G : ndarray (m, n_q)
        Persson's G at the nodes, 0 at q0, increasing.
    f : callable
        ``f(G, s, q)`` vectorised (broadcasting shapes), the integrand times q.
    below : float or callable
        Integral over s < s_lo (q < q_lo), where G < 1e-4: ``below(s_lo, q_lo)`` with arrays (m,), or a
        constant (default 0).
    log_g : bool
        Pass ln G instead of G to ``f`` (saves an exp and a log per point).

    Returns
    -------
    ndarray (m,)
    """
    q = np.asarray(q, dtype=float)
    C = np.asarray(C, dtype=float)
    G = np.atleast_2d(np.asarray(G, dtype=float))
    s = _s(q, C)
    first = _first_interval(q, C, s, G, f, below, log_g)
    if q.size < 3:
        return first
    return first + _other_intervals(*_refined(q, C, s, np.log(np.maximum(G, 1e-300))), f, log_g)


def _first_interval(q, C, s, G, f, below, log_g):
    G1 = np.maximum(G[:, 1], 0.0)
    ls1 = math.log(s[1])
    span = np.where(G1 > _G_NEGLIGIBLE, 0.5 * np.log(np.maximum(G1, _G_NEGLIGIBLE) / _G_NEGLIGIBLE), 0.0)
    n_panels = max(1, int(math.ceil(float(span.max()) / 1.0)))
    width = span / n_panels                                                  # (m,)
    centres = (np.arange(n_panels) + 0.5)[:, None] + 0.5 * _GL_X[None, :]    # (panels, 8) in panel units
    u = ls1 - span[:, None, None] + width[:, None, None] * centres[None]     # ln s, (m, panels, 8)
    su = np.exp(u)
    lnGu = np.log(np.maximum(G1, 1e-300))[:, None, None] + 2.0 * (u - ls1)
    qu = _q_at_moment(q[:2], C[:2], (su * su).reshape(1, -1)).reshape(su.shape)
    val = 0.5 * width * np.einsum("mpk,k->m", f(lnGu if log_g else np.exp(lnGu), su, qu) * su / qu, _GL_W)
    if not callable(below):
        return val + below
    s_lo = s[1] * np.exp(-span)
    q_lo = _q_at_moment(q[:2], C[:2], (s_lo * s_lo)[None, :])[0]
    return val + below(s_lo, q_lo)


def _other_intervals(q, C, s, lnG, f, log_g):
    lns = np.log(s[1:])
    a, b = lns[:-1], lns[1:]
    half = 0.5 * (b - a)                                                     # (n-2,)
    u = (0.5 * (a + b))[:, None] + half[:, None] * _GL_X[None, :]            # (n-2, k)
    frac = (u - a[:, None]) / (2.0 * half[:, None])
    lnG = lnG[:, 1:]
    lnGu = lnG[:, :-1, None] + (lnG[:, 1:, None] - lnG[:, :-1, None]) * frac[None]
    su = np.exp(u)
    qu = _q_at_moment(q[1:], C[1:], su * su - s[1:-1, None] ** 2)
    vals = f(lnGu if log_g else np.exp(lnGu), su[None], qu[None]) * (su / qu)[None]
    return np.einsum("mik,i,k->m", vals, half, _GL_W)


# largest change of ln G across one Gauss-Legendre panel (the integrands turn on over about one e-fold of G)
_MAX_DLNG = 0.5


def _refined(q, C, s, lnG):
    """The nodes with every interval past the first split into equal parts in ln s until ln G changes by at
    most 0.5 across each (ln G linear in ln s, q(s) exact, C the power law): the same integrals on a grid
    the 4-point rule resolves, whatever the spacing given. Returns (q, C, s, lnG) unchanged when it is fine."""
    d = np.max(np.abs(np.diff(lnG[:, 1:], axis=1)), axis=0) if q.size > 2 else np.zeros(0)
    parts = np.minimum(np.ceil(d / _MAX_DLNG), 256).astype(int)
    if parts.size == 0 or parts.max() <= 1:
        return q, C, s, lnG
    n = q.size
    idx = np.repeat(np.arange(1, n - 1), parts)                  # the interval of every new node (its left end)
    start = np.repeat(np.cumsum(parts) - parts, parts)
    t = (np.arange(idx.size) - start) / parts[idx - 1]           # 0 at the original node, then j/k
    ls = np.log(np.where(s > 0, s, 1.0))                          # s[0] = 0 is never a left end here
    si = np.where(t == 0, s[idx], np.exp(ls[idx] + (ls[idx + 1] - ls[idx]) * t))
    L = np.log(q[idx + 1] / q[idx])
    kexp = np.log(C[idx + 1] / C[idx]) / L
    e = 4.0 + kexp
    x = (si * si - s[idx] ** 2) / (C[idx] * q[idx] ** 4)
    small = np.abs(e * x) < 1e-12
    qi = q[idx] * np.where(small, np.exp(x), np.exp(np.log1p(e * x) / np.where(small, 1.0, e)))
    qi = np.where(t == 0, q[idx], qi)
    Ci = np.where(t == 0, C[idx], C[idx] * (qi / q[idx]) ** kexp)
    Gi = lnG[:, idx] + (lnG[:, idx + 1] - lnG[:, idx]) * t[None, :]
    return (np.concatenate([q[:1], qi, q[-1:]]), np.concatenate([C[:1], Ci, C[-1:]]),
            np.concatenate([s[:1], si, s[-1:]]), np.concatenate([lnG[:, :1], Gi, lnG[:, -1:]], axis=1))


@njit(cache=True)
def _kernel_sum(lnG, q, C, s, lnG_first, lnG_last, inv_step, lnJ, J_last, slope_last, glx, glw):
    """Sum over the intervals i >= 1 of int J(G(s)) / q ds, as :func:`_other_intervals` with f the separation
    kernel J (ln J interpolated linearly on its uniform table in ln G, J continued linearly in ln G past its end).

    Parameters
    ----------
    lnG : ndarray (m, n)
        ln G at the nodes, one row per speed (or pressure).
    q : ndarray (n,)
        Wavevector nodes, rad/m.
    C : ndarray (n,)
        The PSD at the nodes, m^4 (a power law between nodes).
    s : ndarray (n,)
        s = (int_{q0}^{q} q'^3 C dq')^(1/2) at the nodes, 1.
    lnG_first : float
        ln G of the kernel table's first node (J vanishes below it).
    lnG_last : float
        ln G of its last node.
    inv_step : float
        Nodes of the table per unit ln G.
    lnJ : ndarray (n_table,)
        ln J on the table.
    J_last : float
        J at the last node.
    slope_last : float
        dJ / d ln G past the last node.
    glx, glw : ndarray (k,)
        Gauss-Legendre nodes and weights on [-1, 1].

    Returns
    -------
    ndarray (m,)
        The sum, m (the separation is twice the first interval's part plus this).
    """
    m, n = lnG.shape
    out = np.zeros(m)
    top = lnJ.size - 1.000001
    for i in range(1, n - 1):
        a = math.log(s[i])
        b = math.log(s[i + 1])
        half = 0.5 * (b - a)
        mid = 0.5 * (a + b)
        e = 4.0 + math.log(C[i + 1] / C[i]) / math.log(q[i + 1] / q[i])
        base = C[i] * q[i] ** 4
        for j in range(glx.size):
            u = mid + half * glx[j]
            su = math.exp(u)
            frac = (u - a) / (2.0 * half)
            x = (su * su - s[i] * s[i]) / base
            if abs(e * x) < 1e-12:
                qu = q[i] * math.exp(x)
            else:
                qu = q[i] * math.exp(math.log1p(e * x) / e)
            wgt = half * glw[j] * su / qu
            for r in range(m):
                lg = lnG[r, i] + (lnG[r, i + 1] - lnG[r, i]) * frac
                if lg < lnG_first:
                    continue
                if lg > lnG_last:
                    out[r] += wgt * (J_last + slope_last * (lg - lnG_last))
                    continue
                t = min((lg - lnG_first) * inv_step, top)
                k = int(t)
                t -= k
                out[r] += wgt * math.exp(lnJ[k] + t * (lnJ[k + 1] - lnJ[k]))
    return out


@njit(cache=True)
def _energy_sum(lnG, q, C, s, e, lnG_first, lnG_last, inv_step, lnW, glx, glw):
    """sum over the intervals i >= 1 of int e_i W(G(s)) 2 s / q ds, the elastic energy per unit load of
    :func:`elastic_energy_per_load` without its factor pi/2 (the 4-point rule of :func:`integral_over_s`).

    Parameters
    ----------
    lnG : ndarray (m, n)
        ln G at the nodes, per row; ln G is linear in ln s between nodes.
    q, C, s : ndarray (n,)
        Nodes (rad/m), PSD (m^4, a power law between nodes) and s = (int_{q0}^{q} q'^3 C dq')^(1/2) there.
    e : ndarray (m, n - 1)
        E*_q / sigma0 on each interval (constant there).
    lnG_first, lnG_last, inv_step : float
        First and last node of the uniform table of ln W in ln G and the nodes per unit ln G.
    lnW : ndarray
        ln W of the energy weight on the table (W = 1 below it, ln W falls with slope -1/2 past it).
    glx, glw : ndarray
        Gauss-Legendre nodes and weights on [-1, 1].
    """
    m, n = lnG.shape
    out = np.zeros(m)
    top = lnW.size - 1.000001
    W_last = lnW[lnW.size - 1]
    for i in range(1, n - 1):
        a = math.log(s[i])
        b = math.log(s[i + 1])
        half = 0.5 * (b - a)
        mid = 0.5 * (a + b)
        k = 4.0 + math.log(C[i + 1] / C[i]) / math.log(q[i + 1] / q[i])
        base = C[i] * q[i] ** 4
        for j in range(glx.size):
            u = mid + half * glx[j]
            su = math.exp(u)
            frac = (u - a) / (2.0 * half)
            x = (su * su - s[i] * s[i]) / base
            if abs(k * x) < 1e-12:
                qu = q[i] * math.exp(x)
            else:
                qu = q[i] * math.exp(math.log1p(k * x) / k)
            wgt = half * glw[j] * su / qu * 2.0 * su
            for r in range(m):
                lg = lnG[r, i] + (lnG[r, i + 1] - lnG[r, i]) * frac
                if lg < lnG_first:
                    w = 1.0
                elif lg > lnG_last:
                    w = math.exp(W_last - 0.5 * (lg - lnG_last))
                else:
                    t = min((lg - lnG_first) * inv_step, top)
                    kk = int(t)
                    t -= kk
                    w = math.exp(lnW[kk] + t * (lnW[kk + 1] - lnW[kk]))
                out[r] += wgt * e[r, i] * w
    return out


@njit(cache=True)
def _energy_first_sum(G1, e0, q0, q1, C0, C1, s1, G_lo, lnG_first, lnG_last, inv_step, lnW, glx, glw):
    """The first interval of :func:`_energy_sum`: int_0^{s1} e0 W(G(s)) 2 s / q ds with G = G1 (s/s1)^2.

    Parameters
    ----------
    G1, e0 : ndarray (m,)
        G at the second node and E*_q / sigma0 on the interval, per row.
    q0, q1, C0, C1 : float
        The interval's nodes (rad/m) and PSD there (m^4, a power law between them).
    s1 : float
        s = (int_{q0}^{q1} q^3 C dq)^(1/2).
    G_lo : float
        Below this G the weight W is 1 to double precision: that part is e0 int q^2 C dq in closed form.
    lnG_first, lnG_last, inv_step, lnW, glx, glw
        As in :func:`_energy_sum`.
    """
    m = G1.size
    out = np.zeros(m)
    kexp = math.log(C1 / C0) / math.log(q1 / q0)
    k = 4.0 + kexp                      # exponent of the moment int q^3 C dq
    base = C0 * q0 ** 4
    e2 = 3.0 + kexp                     # exponent of int q^2 C dq
    top = lnW.size - 1.000001
    W_last = lnW[lnW.size - 1]
    ls1 = math.log(s1)
    for r in range(m):
        if e0[r] <= 0.0:
            continue
        span = 0.5 * math.log(G1[r] / G_lo) if G1[r] > G_lo else 0.0
        # W = 1 from q0 to where G = G_lo: e0 int_{q0}^{q_lo} q^2 C dq
        s_lo = s1 * math.exp(-span)
        x = s_lo * s_lo / base
        q_lo = q0 * math.exp(x) if abs(k * x) < 1e-12 else q0 * math.exp(math.log1p(k * x) / k)
        eL = e2 * math.log(q_lo / q0)
        if abs(eL) < 1e-10:
            mom = C0 * q0 ** 3 * math.log(q_lo / q0)
        else:
            mom = C0 * q0 ** 3 * math.expm1(eL) / e2
        acc = mom
        if span > 0.0:
            n_panels = int(math.ceil(span))
            width = span / n_panels
            for p in range(n_panels):
                for j in range(glx.size):
                    u = ls1 - span + width * (p + 0.5 + 0.5 * glx[j])
                    su = math.exp(u)
                    lg = math.log(G1[r]) + 2.0 * (u - ls1)
                    x = su * su / base
                    qu = q0 * math.exp(x) if abs(k * x) < 1e-12 else q0 * math.exp(math.log1p(k * x) / k)
                    if lg < lnG_first:
                        w = 1.0
                    elif lg > lnG_last:
                        w = math.exp(W_last - 0.5 * (lg - lnG_last))
                    else:
                        t = min((lg - lnG_first) * inv_step, top)
                        kk = int(t)
                        t -= kk
                        w = math.exp(lnW[kk] + t * (lnW[kk + 1] - lnW[kk]))
                    acc += 0.5 * width * glw[j] * w * 2.0 * su * su / qu
        out[r] = e0[r] * acc
    return out


def _q_at_moment(q, C, dm3):
    """q inside interval i (rows of ``dm3``) where int_{q_i}^{q} q'^3 C dq' = dm3, C a power law between nodes:
    q = q_i (1 + e dm3 / (C_i q_i^4))^(1/e), e = 4 + k (q_i exp(dm3 / (C_i q_i^4)) for e = 0)."""
    L = np.diff(np.log(q))
    k = np.diff(np.log(C)) / L
    e = (4.0 + k)[:, None]
    x = dm3 / (C[:-1] * q[:-1] ** 4)[:, None]
    small = np.abs(e * x) < 1e-12
    return q[:-1, None] * np.where(small, np.exp(x), np.exp(np.log1p(e * x) / np.where(small, 1.0, e)))


def _s(q: np.ndarray, C: np.ndarray) -> np.ndarray:
    # Integration variable s = sqrt(int_{q0}^{q} q'^3 C dq'): sqrt(pi) q^2 C w(q) dq = 2 ds / q, which removes
    # the integrable 1/sqrt(q - q0) singularity of w at q0. Exact per interval for a log-log-linear C.
    return np.sqrt(np.concatenate([[0.0], np.cumsum(segment_moments(q, C, 3))]))


def _checked_s(s, q) -> np.ndarray:
    s = np.asarray(s, dtype=float)
    if s.shape != q.shape or not np.all(np.isfinite(s)) or s[0] != 0.0 or np.any(np.diff(s) <= 0):
        raise InputError(f"s: expected the root of the cumulative moment at the {q.size} nodes (0 at q0, "
                         f"increasing), got shape {s.shape}")
    return s


def moment_from_start(q, C, q_end, n: int) -> np.ndarray:
    r""":math:`\int_{q_0}^{q_{end}} q^n C\, dq` for ``q_end`` (array) inside the first interval of the nodes,
    C the power law through the first two nodes (the formula of :func:`segment_moments`)."""
    k = math.log(C[1] / C[0]) / math.log(q[1] / q[0])
    e = n + 1.0 + k
    eL = e * np.log(np.asarray(q_end, dtype=float) / q[0])
    ratio = np.where(np.abs(eL) < 1e-10, eL / e if e != 0 else np.log(np.asarray(q_end) / q[0]),
                     np.expm1(eL) / (e if e != 0 else 1.0))
    return C[0] * q[0] ** (n + 1) * ratio


def segment_moments(q: np.ndarray, C: np.ndarray, n: int) -> np.ndarray:
    r""":math:`\int_{q_i}^{q_{i+1}} q^n C(q)\,dq` per interval, exact for C a power law between nodes.

    With :math:`C = C_i (q/q_i)^k` on the interval, :math:`k = \ln(C_{i+1}/C_i)/\ln(q_{i+1}/q_i)`, the
    integral is :math:`C_i q_i^{n+1} (e^{eL}-1)/e`, :math:`e = n+1+k`, :math:`L = \ln(q_{i+1}/q_i)`.
    """
    q = np.asarray(q, dtype=float)
    C = np.asarray(C, dtype=float)
    pos = (C[:-1] > 0) & (C[1:] > 0)
    Cp = np.where(C > 0, C, 1.0)
    L = np.diff(np.log(q))
    k = np.where(pos, np.diff(np.log(Cp)) / L, 0.0)
    e = n + 1.0 + k
    eL = e * L
    small = np.abs(eL) < 1e-10
    ratio = np.where(small, L * (1.0 + 0.5 * eL), np.expm1(eL) / np.where(small, 1.0, e))
    exact = Cp[:-1] * q[:-1] ** (n + 1) * ratio
    # a node with C = 0 (an edge of the support): the trapezoid in q of q^n C on that interval
    trap = 0.5 * (q[:-1] ** n * C[:-1] + q[1:] ** n * C[1:]) * np.diff(q)
    return np.where(pos, exact, trap)


def _integrate():
    """``scipy.integrate``, imported on first use: it costs about 0.5 s at start-up for every CLI command."""
    from scipy import integrate

    return integrate
