r"""Interfacial separation, penetration depth and excited-layer thickness.

Mean separation (Persson, Phys. Rev. Lett. 99, 125502 (2007); Yang & Persson, J. Phys.: Condens. Matter 20,
215214 (2008), Eq. 11, at magnification zeta = 1):

.. math::
    \bar u = \sqrt{\pi} \int_{q_0}^{q_1} dq\, q^2 C(q) w(q) \int_{\sigma_0}^{\infty} \frac{dp'}{p'}
             \left[\gamma + 3(1-\gamma) P^2(q, p')\right] e^{-[w(q) p'/E^*]^2},
    \qquad w(q) = \left(\pi \int_{q_0}^{q} dq' q'^3 C(q')\right)^{-1/2}

with :math:`P(q, p') = \mathrm{erf}(p' w(q)/E^*)`. Writing :math:`w(q)\sigma_0/E^* = 1/(2\sqrt{G(q)})`
(exact for an elastic solid, where :math:`G = (\pi/4)(E^*/\sigma_0)^2\int q^3 C dq`) and substituting
:math:`t = p' w / E^*` gives

.. math::
    \bar u = \sqrt{\pi} \int_{q_0}^{q_1} dq\, q^2 C(q) w(q)\, J\!\left(\frac{1}{2\sqrt{G(q)}}\right),\quad
    J(x) = \int_x^\infty \frac{dt}{t}\left[\gamma + 3(1-\gamma)\mathrm{erf}^2 t\right] e^{-t^2}
         = \frac{\gamma}{2} E_1(x^2) + 3(1-\gamma) K(x).

Numerically the q integral runs over :math:`s = (\int_{q_0}^{q} q'^3 C dq')^{1/2}`, since
:math:`\sqrt\pi q^2 C w\, dq = 2\, ds / q` is regular at q0 where w(q) diverges.
For a viscoelastic solid sliding at speed v the engine's G(q, v) (with the modulus at the excitation
frequencies) replaces the elastic G, which keeps P(q) = erf(1/(2 sqrt G)) and u_bar consistent.
At small pressure only the gamma term diverges: sigma0 ~ exp(-u_bar / u0) with
:math:`u_0 = \sqrt{\pi}\,\gamma \int q^2 C(q) w(q) dq` (Persson 2007).
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy import integrate, special

from frictioncite import doi

__all__ = ["mean_separation", "separation_decay_length", "penetration_depth", "excited_layer_thickness"]


@doi("10.1103/PhysRevLett.99.125502", "10.1088/0953-8984/20/21/215214")
def mean_separation(q, C, G, gamma: float) -> np.ndarray:
    """Average interfacial separation u_bar, m, per row of ``G``.

    Parameters
    ----------
    q : ndarray (n_q,)
        Wavevectors, rad/m, log-uniform from q0 to q1.
    C : ndarray (n_q,)
        PSD, m^4.
    G : ndarray (n_speed, n_q)
        Persson's G(q) (0 at q0).
    gamma : float
        Parameter of Yang & Persson (2008); 1 recovers Persson (2007).

    Returns
    -------
    ndarray (n_speed,)
        u_bar, m.
    """
    q = np.asarray(q, dtype=float)
    C = np.asarray(C, dtype=float)
    G = np.atleast_2d(np.asarray(G, dtype=float))
    s = _s(q, C)
    x = 0.5 / np.sqrt(np.maximum(G, 1e-300))
    J = _J(x, gamma)
    rest = integrate.trapezoid(J[:, 1:] / q[1:], x=s[1:], axis=-1)
    return 2.0 * (_first_interval(q, s, G, gamma) + rest)


@doi("10.1103/PhysRevLett.99.125502")
def separation_decay_length(q, C, gamma: float) -> float:
    r"""u0 of the large-separation law :math:`\sigma_0 \propto \exp(-\bar u/u_0)`, m:
    :math:`u_0 = \sqrt\pi\,\gamma\int_{q_0}^{q_1} q^2 C(q) w(q) dq` (Persson 2007)."""
    q = np.asarray(q, dtype=float)
    C = np.asarray(C, dtype=float)
    return 2.0 * gamma * float(integrate.trapezoid(1.0 / q, x=_s(q, C)))


def penetration_depth(u_bar, hrms: float) -> np.ndarray:
    r"""Penetration depth of the road asperities into the rubber, m: :math:`\delta = 3 h_{rms} - \bar u`.

    The highest road asperities are taken at :math:`3 h_{rms}` above the mean plane of the road (the 99.87 %
    quantile of a Gaussian height distribution); the rubber's mean surface lies :math:`\bar u` above that
    plane, so the asperity tops are buried :math:`3h_{rms} - \bar u` deep (0 when the rubber does not reach
    them).
    """
    return np.maximum(3.0 * hrms - np.asarray(u_bar, dtype=float), 0.0)


@doi("10.1063/1.1388626")
def excited_layer_thickness(q, dmu_dlnq) -> np.ndarray:
    r"""Thickness of the rubber layer where the hysteresis is dissipated, m:

    .. math:: \ell = \frac{\int q^{-1}\, d\mu}{\int d\mu}

    A deformation of wavevector q decays as :math:`e^{-qz}` into the rubber (Persson 2001, Sec. 2), so the
    friction-weighted mean of 1/q is the depth that carries the dissipation.
    """
    q = np.asarray(q, dtype=float)
    d = np.atleast_2d(np.asarray(dmu_dlnq, dtype=float))
    x = np.log(q)
    num = integrate.trapezoid(d / q, x=x, axis=-1)
    den = integrate.trapezoid(d, x=x, axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.where(den > 0, num / np.where(den > 0, den, 1.0), 1.0 / q[0])
    return out


def _first_interval(q, s, G, gamma):
    """int_0^{s_1} J(x(s)) / q ds on the first interval, where J has a log singularity at small pressure.

    Near q0, m3 = s^2 grows linearly in q and G(q) proportionally to m3 (G is a q-integral starting at q0),
    so G = G_1 (s/s_1)^2 and q = q0 + (q1 - q0)(s/s_1)^2 there; a geometric sub-grid in s resolves the
    logarithm.
    """
    t = np.concatenate([[0.0], np.geomspace(1e-12, 1.0, 241)])
    Gs = G[:, 1:2] * t**2
    x = 0.5 / np.sqrt(np.maximum(Gs, 1e-300))
    qs = q[0] + (q[1] - q[0]) * t**2
    return integrate.trapezoid(_J(x, gamma) / qs, x=s[1] * t, axis=-1)


def _s(q: np.ndarray, C: np.ndarray) -> np.ndarray:
    # Integration variable s = sqrt(int_{q0}^{q} q'^3 C dq'): sqrt(pi) q^2 C w(q) dq = 2 ds / q, which removes
    # the integrable 1/sqrt(q - q0) singularity of w at q0.
    return np.sqrt(integrate.cumulative_trapezoid(q**4 * C, x=np.log(q), initial=0.0))


def _J(x: np.ndarray, gamma: float) -> np.ndarray:
    """J(x) = gamma/2 E1(x^2) + 3 (1 - gamma) int_x^inf erf(t)^2 exp(-t^2) / t dt (x > 0).

    Interpolated in ln x in a cached table: J is smooth in ln x and tends to -gamma ln x + const as x -> 0
    (E1(x^2) ~ -euler_gamma - 2 ln x), which the table continues linearly below its first node.
    """
    lx_tab, J_tab = _J_table(float(gamma))
    lx = np.log(np.maximum(np.asarray(x, dtype=float), 1e-300))
    out = np.interp(lx, lx_tab, J_tab, right=0.0)
    below = lx < lx_tab[0]
    if np.any(below):
        out = np.where(below, J_tab[0] - gamma * (lx - lx_tab[0]), out)
    return out


@functools.lru_cache(maxsize=8)
def _J_table(gamma: float) -> tuple[np.ndarray, np.ndarray]:
    # Pure function of gamma, cached: the exact E1 and the K table on 80 nodes per e-fold of x.
    lx = np.linspace(math.log(1e-12), math.log(30.0), 3300)
    x = np.exp(lx)
    J = 0.5 * gamma * special.exp1(x * x)
    if gamma < 1.0:
        J = J + 3.0 * (1.0 - gamma) * _K(x)
    J[-1] = 0.0
    lx.setflags(write=False)
    J.setflags(write=False)
    return lx, J


def _K(x: np.ndarray) -> np.ndarray:
    """K(x) = int_x^inf erf(t)^2 exp(-t^2) / t dt, interpolated in a cached table."""
    t, tail = _K_table()
    return np.interp(x, t, tail, right=0.0)


@functools.lru_cache(maxsize=1)
def _K_table() -> tuple[np.ndarray, np.ndarray]:
    # erf(t)^2 ~ 4 t^2 / pi near 0, so the integrand is regular; the table is a pure constant, built once.
    t = np.concatenate([[0.0], np.geomspace(1e-6, 8.0, 4000)])
    f = np.zeros_like(t)
    f[1:] = special.erf(t[1:]) ** 2 * np.exp(-t[1:] ** 2) / t[1:]
    cum = integrate.cumulative_trapezoid(f, t, initial=0.0)
    tail = cum[-1] - cum
    t.setflags(write=False)
    tail.setflags(write=False)
    return t, tail
