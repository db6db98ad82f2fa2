r"""Corrections to the contact area of Persson's theory, written as maps of G.

Uncorrected Persson theory (Persson, J. Chem. Phys. 115, 3840 (2001)) gives the area of real contact at
magnification q as

.. math:: P(q) = \mathrm{erf}\!\left(\frac{1}{2\sqrt{G(q)}}\right),\qquad
          G(q) = \frac{\pi}{4}\left(\frac{E^*}{\sigma_0}\right)^2 \int_{q_0}^{q} dq'\, q'^3 C(q')

(for a viscoelastic solid :math:`G(q)` carries the modulus at the excitation frequencies). Against exact
numerical solutions (Green's function molecular dynamics, GFMD) it is 25-35 % low at small loads, where the
area is proportional to the load with a slope :math:`\sqrt{8/\pi}` instead of about 2. The corrections here
are published empirical fixes. Each one replaces :math:`P(G)` by another function :math:`P_c(G)` of the same
:math:`G` and a parameter :math:`\gamma` (the one of :math:`S = \gamma + (1-\gamma)P^2`), so a solver that
computes G(q) uses them unchanged:

``"yang-persson"``
    The correction factor :math:`S(P) = \gamma + (1-\gamma) P^2` of Yang & Persson (J. Phys.: Condens. Matter
    20, 215214 (2008)), the factor the friction integral already carries, applied to the growth of G (the
    variance of the contact pressure) as in Almqvist et al. (J. Mech. Phys. Solids 59, 2355 (2011),
    arXiv:1102.5412) and, under the name "YP08", in Xu et al. (Tribol. Lett. 72 (2024)):
    :math:`dG_c = S(P(G_c))\, dG`. The equation is autonomous, so :math:`G_c` is a function of :math:`G`
    alone:

    .. math:: G = \int_0^{G_c} \frac{dg}{\gamma + (1-\gamma)\,\mathrm{erf}^2(1/(2\sqrt g))},\qquad
              P_c = \mathrm{erf}\!\left(\frac{1}{2\sqrt{G_c}}\right).

``"xu2024"``
    The fudge factor of Xu, Zhu, Xiao & Zhou, "A new fudge factor for Persson's theory of purely normal
    elastic rough surface contact", Tribol. Lett. 72 (2024): the pressure variance of full contact is scaled
    by :math:`\gamma + (1-\gamma)P_c` at the present scale only, so :math:`P_c` solves

    .. math:: P_c = \mathrm{erf}\!\left(\frac{1}{2\sqrt{G\,(\gamma + (1-\gamma) P_c)}}\right).

Both tend to :math:`P_c = P/\sqrt\gamma` at small load (the slope :math:`\sqrt{8/(\pi\gamma)}`, 2.26 for
:math:`\gamma = 0.5`) and to :math:`P` at full contact. With :math:`\gamma = 0.5` both are within 6 % of the
GFMD areas of Xu et al. (2024) over the whole load range (``tests/test_contact_corrections.py``).

How a friction solver uses them: the hysteresis friction integrates the weight
:math:`S(P)\,P\,dG` (:math:`q^3 C dq` is proportional to dG), so the corrected friction replaces P(G) by
:func:`corrected_area` everywhere, S included; :func:`weight_antiderivative` gives
:math:`\Phi(G) = \int_0^G S(P_c(g)) P_c(g)\, dg` for a quadrature that integrates the weight exactly. The
interfacial separation uses :func:`separation_kernel`, the same :math:`P_c` through the elastic energy.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy import special

from frictioncite import doi

from ..errors import InputError

__all__ = ["CORRECTIONS", "corrected_area", "weight_antiderivative", "separation_kernel", "separation_kernel_ln",
           "check_correction", "citations"]

#: Names of the area corrections (``None`` is uncorrected Persson theory).
CORRECTIONS = ("yang-persson", "xu2024")

_CITES = {None: ("10.1063/1.1388626",),
          "yang-persson": ("10.1088/0953-8984/20/21/215214", "arxiv:1102.5412", "10.1007/s11249-024-01838-4"),
          "xu2024": ("10.1007/s11249-024-01838-4",)}


def check_correction(correction, gamma) -> tuple[str | None, float]:
    """Validate ``correction`` (None or a name of :data:`CORRECTIONS`) and ``gamma``; returns them.

    Raises
    ------
    InputError
        Naming the argument and the accepted values.
    """
    if correction is not None and correction not in CORRECTIONS:
        raise InputError(f"correction: expected None or one of {list(CORRECTIONS)}, got {correction!r}")
    try:
        g = float(gamma)
    except (TypeError, ValueError):
        raise InputError(f"gamma: expected a number in [0, 1], got {gamma!r}") from None
    if isinstance(gamma, bool) or not math.isfinite(g) or not 0.0 <= g <= 1.0:
        raise InputError(f"gamma: expected a number in [0, 1], got {gamma!r}")
    if correction is not None and g <= 0.0:
        raise InputError(f"gamma: the {correction!r} correction needs gamma > 0 (it divides by it), got {g:g}")
    return correction, g


def citations(correction) -> tuple[str, ...]:
    """References (DOIs or arXiv keys) of ``correction`` (None: Persson 2001)."""
    return _CITES[correction]


@doi("10.1063/1.1388626", "10.1088/0953-8984/20/21/215214", "10.1007/s11249-024-01838-4")
def corrected_area(G, correction: str | None = None, gamma: float = 0.5) -> np.ndarray:
    r"""Area of real contact :math:`P_c(G)` at a scale where Persson's G has the value ``G``.

    Parameters
    ----------
    G : array_like
        Persson's :math:`G(q) \ge 0` (dimensionless), any shape.
    correction : {None, "yang-persson", "xu2024"}
        None gives :math:`P = \mathrm{erf}(1/(2\sqrt G))` (Persson 2001); the others are described in the
        module docstring (Yang & Persson 2008 factor applied to dG; Xu et al. 2024).
    gamma : float
        Parameter of :math:`S(P) = \gamma + (1-\gamma)P^2`, 0 < gamma <= 1 for a correction (1 switches the
        correction off).

    Returns
    -------
    ndarray
        :math:`P_c \in (0, 1]`, shape of ``G``; 1 where G = 0.
    """
    correction, gamma = check_correction(correction, gamma)
    G = np.maximum(np.asarray(G, dtype=float), 0.0)
    if correction is None or gamma == 1.0:
        return _erf_area(G)
    tab = _table(correction, gamma)
    return _from_table(G, tab.lnG, tab.lnP, small=_erf_area, slope=-0.5)


@doi("10.1063/1.1388626", "10.1088/0953-8984/20/21/215214", "10.1007/s11249-024-01838-4")
def weight_antiderivative(G, correction: str | None = None, gamma: float = 0.5) -> np.ndarray:
    r""":math:`\Phi(G) = \int_0^G S(P_c(g))\,P_c(g)\,dg` with :math:`S(P) = \gamma + (1-\gamma)P^2`.

    The hysteresis friction is :math:`\mu = \frac12\int dq\, q^3 C\, S P \int d\phi \cos\phi\,
    \mathrm{Im}E/((1-\nu^2)\sigma_0)` and :math:`dG = \frac18 q^3 C \int d\phi |E/((1-\nu^2)\sigma_0)|^2 dq`,
    so on an interval where the ratio of the two angular integrals is r, its contribution is
    :math:`4 r\,[\Phi(G_b) - \Phi(G_a)]`. For a frequency-independent modulus (r constant) the whole
    integral is :math:`4 r\,\Phi(G(q_1))`.

    Parameters
    ----------
    G : array_like
        Persson's G >= 0, any shape.
    correction, gamma
        As in :func:`corrected_area`.

    Returns
    -------
    ndarray
        :math:`\Phi(G)`, shape of ``G`` (:math:`\Phi \approx G` for small G).
    """
    correction, gamma = check_correction(correction, gamma)
    G = np.maximum(np.asarray(G, dtype=float), 0.0)
    tab = _table(correction, gamma)
    # ln Phi is nearly linear in ln G (slope 1 at small G, 1/2 at large G): interpolate it there
    out = np.exp(np.interp(np.log(np.maximum(G, 1e-300)), tab.lnG, np.log(tab.Phi)))
    small = G <= tab.G_min
    out = np.where(small, G, out)  # P = S = 1 to 1e-300 below G_min: Phi = G
    big = G > tab.G_max
    if np.any(big):
        # P_c ~ a G^-1/2 and S ~ gamma far out: Phi grows by 2 gamma a (sqrt G - sqrt G_max)
        a = tab.P_end * math.sqrt(tab.G_max)
        out = np.where(big, tab.Phi[-1] + 2.0 * gamma * a * (np.sqrt(G) - math.sqrt(tab.G_max)), out)
    return out


@doi("10.1103/PhysRevLett.99.125502", "10.1088/0953-8984/20/21/215214")
def separation_kernel(G, correction: str | None = None, gamma: float = 0.5) -> np.ndarray:
    r"""Kernel :math:`J_c(G)` of the mean separation :math:`\bar u = \sqrt\pi\int dq\, q^2 C w\, J_c(G(q))`.

    Persson (Phys. Rev. Lett. 99, 125502 (2007)) obtains :math:`\bar u(\sigma_0)` from the elastic energy,
    :math:`\bar u = \int_{\sigma_0}^\infty \frac{dp}{p}\,\frac{d}{dp}\frac{U_{el}}{A_0}`, with (Yang &
    Persson 2008) :math:`U_{el}/A_0 = \frac{\pi E^*}{2}\int dq\, q^2 C\, W`, :math:`W = P\,S(P)`. With
    :math:`G \propto 1/p^2` at fixed q this becomes

    .. math:: J_c(G) = \sqrt\pi\int_0^G \sqrt g\left(-\frac{dW}{dg}\right)dg
              = \sqrt\pi\left[\sqrt G\,V(G) - \frac12\int_0^G \frac{V(g)}{\sqrt g}\,dg\right],\quad V = 1 - W,

    evaluated here with :math:`W = P_c S(P_c)`. For ``correction=None`` it equals the closed form
    :math:`J(x) = \frac\gamma2 E_1(x^2) + 3(1-\gamma)\int_x^\infty \mathrm{erf}^2(t) e^{-t^2} dt/t`,
    :math:`x = 1/(2\sqrt G)`, of :mod:`persson.contact.separation`.

    Parameters
    ----------
    G : array_like
        Persson's G >= 0, any shape.
    correction, gamma
        As in :func:`corrected_area`.

    Returns
    -------
    ndarray
        :math:`J_c(G) \ge 0`, shape of ``G``; it grows as :math:`c\ln G` for large G.
    """
    correction, gamma = check_correction(correction, gamma)
    G = np.maximum(np.asarray(G, dtype=float), 0.0)
    return separation_kernel_ln(np.log(np.maximum(G, 1e-300)), correction, gamma)


def separation_kernel_ln(lnG, correction: str | None = None, gamma: float = 0.5) -> np.ndarray:
    """:func:`separation_kernel` of ``exp(lnG)``, for callers that hold ln G (arguments not re-checked)."""
    tab = _table(correction, gamma)
    lnG = np.asarray(lnG, dtype=float)
    # ln J is smooth in ln G, also where J is exponentially small (J ~ exp(-1/(4G))): linear interpolation of
    # ln J on the uniform table, by index arithmetic (the hot path of the separation integral)
    x = np.array((lnG - tab.lnG[0]) * tab.inv_step, dtype=float)
    np.maximum(x, 0.0, out=x)
    np.minimum(x, tab.lnG.size - 1.000001, out=x)
    i = x.astype(np.intp)
    x -= i
    lnJ = tab.lnJ_floor[i]
    x *= tab.lnJ_floor[i + 1] - lnJ
    x += lnJ
    out = np.exp(x, out=x)
    big = lnG > tab.lnG[-1]
    if np.any(big):
        slope = (tab.J[-1] - tab.J[-2]) / (tab.lnG[-1] - tab.lnG[-2])
        out = np.where(big, tab.J[-1] + slope * (lnG - tab.lnG[-1]), out)
    return np.where(lnG < tab.lnG[0], 0.0, out)


# ---------------------------------------------------------------------------------------------------------
class _Table:
    """P_c, Phi and J_c on a grid in ln G (pure data; cached per correction and gamma)."""

    __slots__ = ("lnG", "lnP", "Phi", "J", "lnJ_floor", "inv_step", "G_min", "G_max", "P_end")

    def __init__(self, lnG, lnP, Phi, J):
        self.lnG, self.lnP, self.Phi, self.J = lnG, lnP, Phi, J
        # ln J, floored at -800 where J underflows (exp(-800) = 0): finite, so interpolation never makes NaN
        self.lnJ_floor = np.log(np.maximum(J, math.exp(-700.0)))
        self.lnJ_floor[J <= math.exp(-700.0)] = -800.0
        self.inv_step = (lnG.size - 1) / (lnG[-1] - lnG[0])  # the grid is uniform (np.linspace)
        for a in (lnG, lnP, Phi, J, self.lnJ_floor):
            a.setflags(write=False)
        self.G_min = math.exp(lnG[0])
        self.G_max = math.exp(lnG[-1])
        self.P_end = math.exp(lnP[-1])


# Table range: below G = 1e-7 every P equals 1 to double precision (erfc(1/(2 sqrt G)) < 1e-300 already at
# 1e-3); 1e28 covers p/E* down to about 1e-14 h'. 400 nodes per e-fold: tables accurate to about 1e-6.
_LNG_MIN, _LNG_MAX, _PER_EFOLD = math.log(1e-7), math.log(1e28), 400


@functools.lru_cache(maxsize=16)
def _table(correction: str | None, gamma: float) -> _Table:
    n = int(round((_LNG_MAX - _LNG_MIN) * _PER_EFOLD)) + 1
    if correction == "yang-persson":
        # Tabulate in ln G_c: G(G_c) = int_0^Gc dg / S(P(g)) (S = 1 below the first node, to 1e-300).
        lnGc = np.linspace(_LNG_MIN, _LNG_MAX + math.log(1.0 / gamma) + 1.0, n + 400)
        Gc = np.exp(lnGc)
        P = _erf_area(Gc)
        f = Gc / (gamma + (1.0 - gamma) * P * P)
        G_of = Gc[0] + _integrate().cumulative_simpson(f, x=lnGc, initial=0.0)
        lnG = np.linspace(_LNG_MIN, _LNG_MAX, n)
        Gc_at = np.exp(np.interp(lnG, np.log(G_of), lnGc))
        P = _erf_area(Gc_at)
        x = 0.5 / np.sqrt(Gc_at)
        # dP/dlnG = dP/dlnGc * dlnGc/dlnG, dG_c/dG = S(P)
        dP = -x / math.sqrt(math.pi) * np.exp(-x * x) * np.exp(lnG) / Gc_at * (gamma + (1.0 - gamma) * P * P)
    else:
        lnG = np.linspace(_LNG_MIN, _LNG_MAX, n)
        G = np.exp(lnG)
        if correction is None:
            P = _erf_area(G)
            x = 0.5 / np.sqrt(G)
            dP = -x / math.sqrt(math.pi) * np.exp(-x * x)
        else:
            P = _xu_root(G, gamma)
            m = gamma + (1.0 - gamma) * P
            y = 0.5 / np.sqrt(G * m)
            e = -y / math.sqrt(math.pi) * np.exp(-y * y)  # dP/dlnG at fixed m
            dP = e / (1.0 - e * (1.0 - gamma) / m)         # implicit differentiation through m(P)
    G = np.exp(lnG)
    W = P * (gamma + (1.0 - gamma) * P * P)
    dW = (gamma + 3.0 * (1.0 - gamma) * P * P) * dP      # dW/dlnG <= 0
    Phi = G[0] + _integrate().cumulative_simpson(W * G, x=lnG, initial=0.0)
    # J_c = sqrt(pi) int_0^G sqrt(g) (-dW/dg) dg = sqrt(pi) int sqrt(g) (-dW/dlng) dlng (no cancellation)
    J = math.sqrt(math.pi) * _integrate().cumulative_simpson(-dW * np.sqrt(G), x=lnG, initial=0.0)
    return _Table(lnG, np.log(P), Phi, np.maximum(J, 0.0))


def _xu_root(G: np.ndarray, gamma: float) -> np.ndarray:
    """P solving P = erf(1/(2 sqrt(G (gamma + (1-gamma) P)))): the right side falls as P rises, so the root is
    unique in (0, 1]; bisection to machine precision (60 halvings), vectorised."""
    lo = np.zeros_like(G)
    hi = np.ones_like(G)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        f = mid - _erf_area(G * (gamma + (1.0 - gamma) * mid))
        lo = np.where(f < 0, mid, lo)
        hi = np.where(f < 0, hi, mid)
    return 0.5 * (lo + hi)


def _erf_area(G: np.ndarray) -> np.ndarray:
    """erf(1 / (2 sqrt G)) with erf(inf) = 1 at G = 0."""
    G = np.asarray(G, dtype=float)
    with np.errstate(divide="ignore"):
        x = 0.5 / np.sqrt(G)
    return special.erf(x)


def _from_table(G, lnG_tab, lnP_tab, small, slope):
    lnG = np.log(np.maximum(G, 1e-300))
    out = np.exp(np.interp(lnG, lnG_tab, lnP_tab))
    below = lnG < lnG_tab[0]
    out = np.where(below, small(G), out)
    above = lnG > lnG_tab[-1]
    if np.any(above):
        out = np.where(above, np.exp(lnP_tab[-1] + slope * (lnG - lnG_tab[-1])), out)
    return out


def _integrate():
    """``scipy.integrate``, imported on first use: it costs about 0.5 s at start-up for every CLI command."""
    from scipy import integrate

    return integrate
