r"""Corrections to Persson's theory of contact, written as maps of G: one for the area, one for the gap and energy.

Uncorrected Persson theory (Persson, J. Chem. Phys. 115, 3840 (2001)) gives the area of real contact at
magnification q as

.. math:: P(q) = \mathrm{erf}\!\left(\frac{1}{2\sqrt{G(q)}}\right),\qquad
          G(q) = \frac{\pi}{4}\left(\frac{E^*}{\sigma_0}\right)^2 \int_{q_0}^{q} dq'\, q'^3 C(q')

(for a viscoelastic solid :math:`G(q)` carries the modulus at the excitation frequencies), and the elastic energy
and the mean separation from the weight :math:`W = P\,S(P)`, :math:`S = \gamma + (1-\gamma)P^2` (Yang & Persson,
J. Phys.: Condens. Matter 20, 215214 (2008)). Against exact numerical solutions (Green's function molecular
dynamics, GFMD; boundary elements, BEM) the area is 20-35 % low at small loads, where it is proportional to the load
with a slope :math:`\sqrt{8/\pi}` instead of about 2, while the separation and the energy are too large there. The
corrections here are published empirical fixes. Each one replaces :math:`P(G)` by another function :math:`P_c(G)` of
the same :math:`G`, so a solver that computes G(q) uses them unchanged.

**Area corrections** (``correction``):

``"yang-persson"``
    The correction factor :math:`S(P) = \gamma + (1-\gamma) P^2` of Yang & Persson (2008), the factor the friction
    integral already carries, applied to the growth of G (the variance of the contact pressure) as in Almqvist et
    al. (J. Mech. Phys. Solids 59, 2355 (2011), arXiv:1102.5412) and, under the name "YP08", in Xu et al.
    (Tribol. Lett. 72 (2024)): :math:`dG_c = S(P(G_c))\, dG`. The equation is autonomous, so :math:`G_c` is a
    function of :math:`G` alone:

    .. math:: G = \int_0^{G_c} \frac{dg}{S\big(\mathrm{erf}(1/(2\sqrt g))\big)},\qquad
              P_c = \mathrm{erf}\!\left(\frac{1}{2\sqrt{G_c}}\right).

``"xu2024"``
    The fudge factor of Xu, Zhu, Xiao & Zhou, "A new fudge factor for Persson's theory of purely normal
    elastic rough surface contact", Tribol. Lett. 72 (2024): the pressure variance of full contact is scaled
    by :math:`\gamma + (1-\gamma)P_c` at the present scale only, so :math:`P_c` solves

    .. math:: P_c = \mathrm{erf}\!\left(\frac{1}{2\sqrt{G\,(\gamma + (1-\gamma) P_c)}}\right).

``"wang-muser"``
    The correction of A. Wang and M. H. Müser, "Gauging Persson theory on adhesion", Tribol. Lett. 65 (2017), as
    implemented by Xu et al. (2024) ("WM17"): the same growth law as ``"yang-persson"`` with Wang & Müser's factor

    .. math:: S_{WM}(P) = a - \tfrac{2}{9} P^2 + \left(\tfrac{11}{9} - a\right) P^4,\qquad a = 5/9,

    which they fitted to their own GFMD pressure distributions (rms gradient 1, H = 0.8, a roll-off). The constant
    a is theirs (:data:`WANG_MUSER_A`); the ``gamma`` argument does not enter this law.

**Gap and energy corrections** (``gap_correction``): the weight :math:`W(G)` of the elastic energy
:math:`U_{el}/A_0 = (\pi E^*/2)\int dq\, q^2 C\, W` and hence of the separation
:math:`\bar u = \int_{\sigma_0}^\infty dp\, p^{-1}\, d(U_{el}/A_0)/dp` (Persson, Phys. Rev. Lett. 99, 125502
(2007)), chosen separately from the area:

``"area"`` (default)
    :math:`W = P_c\, S(P_c)` with the corrected area (:math:`S_{WM}` for ``"wang-muser"``): the energy and the
    separation follow the area law.
``"persson"``
    :math:`W = P\,S(P)` with Persson's uncorrected :math:`P = \mathrm{erf}(1/(2\sqrt G))`, whatever the area
    correction.
``"xu2024-hybrid"``
    The "hybrid" energy of Xu et al. (2024): the area of ``"xu2024"`` with Wang & Müser's factor,
    :math:`W = P_c\, S_{WM}(P_c)`, :math:`S_{WM}` with :math:`a = \gamma` (their Fig. 4, :math:`\gamma = 0.42`).
``"gfmd-gap"``
    :math:`W = P\,S_g(P)` with Persson's uncorrected P and :math:`S_g = \gamma_g + (1-\gamma_g) P^2`,
    :math:`\gamma_g` = :data:`GFMD_GAP_GAMMA`: Yang & Persson's weight with its constant fitted by this package to the
    GFMD mean gaps of Xu et al. (2024) at :math:`p/E^* \le 0.025` (the small-load decay length
    :math:`u_0 \propto \gamma_g`, 0.52-0.53 :math:`h_{rms}` at :math:`\gamma = 0.5` on the GFMD and BEM surfaces of
    ``docs/contact.md``, is too long against both: 0.39-0.42 in BEM); its error on the BEM data it was not tuned on
    (mean gap -11 to +3 %, energy -18 to +21 %) is tabulated there.

Both area corrections of Yang-Persson type tend to :math:`P_c = P/\sqrt\gamma` at small load (the slope
:math:`\sqrt{8/(\pi\gamma)}`, 2.26 for :math:`\gamma = 0.5`; :math:`P/\sqrt a`, 2.14, for ``"wang-muser"``) and to
:math:`P` at full contact.

How a friction solver uses them: the hysteresis friction integrates the weight :math:`S(P)\,P\,dG`
(:math:`q^3 C dq` is proportional to dG, S Yang & Persson's factor with the friction model's gamma), so the
corrected friction replaces P(G) by :func:`corrected_area` everywhere, S included; :func:`weight_antiderivative`
gives :math:`\Phi(G) = \int_0^G S(P_c(g)) P_c(g)\, dg` for a quadrature that integrates the weight exactly. The
interfacial separation uses :func:`separation_kernel` of the energy weight :func:`energy_weight`.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy import special

from frictioncite import doi

from ..errors import InputError

__all__ = ["CORRECTIONS", "GAP_CORRECTIONS", "WANG_MUSER_A", "GFMD_GAP_GAMMA", "corrected_area",
           "weight_antiderivative", "energy_weight", "separation_kernel", "separation_kernel_ln",
           "check_correction", "check_gap_correction", "citations"]

#: Names of the area corrections (``None`` is uncorrected Persson theory).
CORRECTIONS = ("yang-persson", "xu2024", "wang-muser")

#: Names of the gap and energy corrections (``"area"``: follow the area law).
GAP_CORRECTIONS = ("area", "persson", "xu2024-hybrid", "gfmd-gap")

#: The constant a of Wang & Müser's factor S_WM(P) = a - 2/9 P^2 + (11/9 - a) P^4 (their fitted value 5/9).
WANG_MUSER_A = 5.0 / 9.0

#: gamma of the ``"gfmd-gap"`` energy weight: the least-squares fit (in ln u_bar) to the six GFMD mean gaps of Xu et
#: al. (2024) at p/E* <= 0.025 (``tests/test_contact_gap.py`` refits it).
GFMD_GAP_GAMMA = 0.325

_WANG_MUSER = "wang-muser:tribol-lett-65-2017"
_XU = "10.1007/s11249-024-01838-4"
_YP = "10.1088/0953-8984/20/21/215214"
_CITES = {None: ("10.1063/1.1388626",),
          "yang-persson": (_YP, "arxiv:1102.5412", _XU),
          "xu2024": (_XU,),
          "wang-muser": (_WANG_MUSER, _XU)}
_GAP_CITES = {"area": (), "persson": (_YP,), "xu2024-hybrid": (_XU, _WANG_MUSER), "gfmd-gap": (_YP, _XU)}


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
    if correction in ("yang-persson", "xu2024") and g <= 0.0:
        raise InputError(f"gamma: the {correction!r} correction needs gamma > 0 (it divides by it), got {g:g}")
    return correction, g


def check_gap_correction(gap_correction, correction=None, gamma: float = 0.5) -> str:
    """Validate ``gap_correction`` (a name of :data:`GAP_CORRECTIONS`; None means ``"persson"``) against the area
    ``correction``; returns the name.

    Raises
    ------
    InputError
        An unknown name, or gamma = 0 with ``"xu2024-hybrid"``.
    """
    if gap_correction is None:
        return "persson"
    if gap_correction not in GAP_CORRECTIONS:
        raise InputError(f"gap_correction: expected None or one of {list(GAP_CORRECTIONS)}, got {gap_correction!r}")
    if gap_correction == "xu2024-hybrid" and not float(gamma) > 0.0:
        raise InputError("gamma: the 'xu2024-hybrid' gap correction needs gamma > 0")
    return gap_correction


def citations(correction, gap_correction: str = "area") -> tuple[str, ...]:
    """References (DOIs or other keys) of ``correction`` (None: Persson 2001) and of ``gap_correction``."""
    out = list(_CITES[correction])
    for k in _GAP_CITES["persson" if gap_correction is None else gap_correction]:
        if k not in out:
            out.append(k)
    return tuple(out)


@doi("10.1063/1.1388626", _YP, _XU, _WANG_MUSER)
def corrected_area(G, correction: str | None = None, gamma: float = 0.5) -> np.ndarray:
    r"""Area of real contact :math:`P_c(G)` at a scale where Persson's G has the value ``G``.

    Parameters
    ----------
    G : array_like
        Persson's :math:`G(q) \ge 0` (dimensionless), any shape.
    correction : {None, "yang-persson", "xu2024", "wang-muser"}
        None gives :math:`P = \mathrm{erf}(1/(2\sqrt G))` (Persson 2001); the others are described in the
        module docstring (Yang & Persson 2008 factor applied to dG; Xu et al. 2024; Wang & Müser 2017).
    gamma : float
        Parameter of :math:`S(P) = \gamma + (1-\gamma)P^2`, 0 < gamma <= 1 for ``"yang-persson"`` and
        ``"xu2024"`` (1 switches them off); not used by ``"wang-muser"`` (its own constant 5/9).

    Returns
    -------
    ndarray
        :math:`P_c \in (0, 1]`, shape of ``G``; 1 where G = 0.
    """
    correction, gamma = check_correction(correction, gamma)
    G = np.maximum(np.asarray(G, dtype=float), 0.0)
    if correction is None or (gamma == 1.0 and correction != "wang-muser"):
        return _erf_area(G)
    tab = _table(correction, gamma)
    return _from_table(G, tab.lnG, tab.lnP, small=_erf_area, slope=-0.5)


@doi("10.1063/1.1388626", _YP, _XU)
def weight_antiderivative(G, correction: str | None = None, gamma: float = 0.5) -> np.ndarray:
    r""":math:`\Phi(G) = \int_0^G S(P_c(g))\,P_c(g)\,dg` with :math:`S(P) = \gamma + (1-\gamma)P^2`.

    The hysteresis friction is :math:`\mu = \frac12\int dq\, q^3 C\, S P \int d\phi \cos\phi\,
    \mathrm{Im}E/((1-\nu^2)\sigma_0)` and :math:`dG = \frac18 q^3 C \int d\phi |E/((1-\nu^2)\sigma_0)|^2 dq`,
    so on an interval where the ratio of the two angular integrals is r, its contribution is
    :math:`4 r\,[\Phi(G_b) - \Phi(G_a)]`. For a frequency-independent modulus (r constant) the whole
    integral is :math:`4 r\,\Phi(G(q_1))`. S is the friction model's factor for every area law (the engine's).

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


@doi(_YP, _XU, _WANG_MUSER)
def energy_weight(G, correction: str | None = None, gamma: float = 0.5, gap_correction: str = "area") -> np.ndarray:
    r"""Weight :math:`W(G)` of the elastic energy, :math:`U_{el}/A_0 = (\pi E^*/2)\int dq\, q^2 C\, W(G(q))`.

    Parameters
    ----------
    G : array_like
        Persson's G >= 0, any shape.
    correction, gamma
        As in :func:`corrected_area`.
    gap_correction : {"area", "persson", "xu2024-hybrid", "gfmd-gap"} or None
        The energy law (module docstring); None is ``"persson"``.

    Returns
    -------
    ndarray
        :math:`W \in (0, 1]`, shape of ``G``; 1 at G = 0, :math:`\propto G^{-1/2}` at large G.
    """
    correction, gamma = check_correction(correction, gamma)
    gap = check_gap_correction(gap_correction, correction, gamma)
    G = np.maximum(np.asarray(G, dtype=float), 0.0)
    tab = _table(correction, gamma, gap)
    return _from_table(G, tab.lnG, tab.lnW, small=lambda g: np.ones_like(g), slope=-0.5)


@doi("10.1103/PhysRevLett.99.125502", _YP)
def separation_kernel(G, correction: str | None = None, gamma: float = 0.5, gap_correction: str = "area") -> np.ndarray:
    r"""Kernel :math:`J_c(G)` of the mean separation :math:`\bar u = \sqrt\pi\int dq\, q^2 C w\, J_c(G(q))`.

    Persson (Phys. Rev. Lett. 99, 125502 (2007)) obtains :math:`\bar u(\sigma_0)` from the elastic energy,
    :math:`\bar u = \int_{\sigma_0}^\infty \frac{dp}{p}\,\frac{d}{dp}\frac{U_{el}}{A_0}`, with (Yang &
    Persson 2008) :math:`U_{el}/A_0 = \frac{\pi E^*}{2}\int dq\, q^2 C\, W`. With :math:`G \propto 1/p^2` at fixed
    q this becomes

    .. math:: J_c(G) = \sqrt\pi\int_0^G \sqrt g\left(-\frac{dW}{dg}\right)dg
              = \sqrt\pi\left[\sqrt G\,V(G) - \frac12\int_0^G \frac{V(g)}{\sqrt g}\,dg\right],\quad V = 1 - W,

    with W the energy weight :func:`energy_weight`. Uncorrected (:math:`W = P S(P)`) it equals the closed form
    :math:`J(x) = \frac\gamma2 E_1(x^2) + 3(1-\gamma)\int_x^\infty \mathrm{erf}^2(t) e^{-t^2} dt/t`,
    :math:`x = 1/(2\sqrt G)`, of :mod:`persson.contact.separation`.

    Parameters
    ----------
    G : array_like
        Persson's G >= 0, any shape.
    correction, gamma, gap_correction
        As in :func:`energy_weight`.

    Returns
    -------
    ndarray
        :math:`J_c(G) \ge 0`, shape of ``G``; it grows as :math:`c\ln G` for large G.
    """
    correction, gamma = check_correction(correction, gamma)
    gap = check_gap_correction(gap_correction, correction, gamma)
    G = np.maximum(np.asarray(G, dtype=float), 0.0)
    return separation_kernel_ln(np.log(np.maximum(G, 1e-300)), correction, gamma, gap)


def separation_kernel_ln(lnG, correction: str | None = None, gamma: float = 0.5,
                         gap_correction: str = "area") -> np.ndarray:
    """:func:`separation_kernel` of ``exp(lnG)``, for callers that hold ln G (arguments not re-checked)."""
    tab = _table(correction, gamma, "persson" if gap_correction is None else gap_correction)
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
    """P_c, Phi, W and J_c on a grid in ln G (pure data; cached per correction, gamma and gap correction)."""

    __slots__ = ("lnG", "lnP", "Phi", "lnW", "J", "lnJ_floor", "inv_step", "G_min", "G_max", "P_end")

    def __init__(self, lnG, lnP, Phi, lnW, J):
        self.lnG, self.lnP, self.Phi, self.lnW, self.J = lnG, lnP, Phi, lnW, J
        # ln J, floored at -800 where J underflows (exp(-800) = 0): finite, so interpolation never makes NaN
        self.lnJ_floor = np.log(np.maximum(J, math.exp(-700.0)))
        self.lnJ_floor[J <= math.exp(-700.0)] = -800.0
        self.inv_step = (lnG.size - 1) / (lnG[-1] - lnG[0])  # the grid is uniform (np.linspace)
        for a in (lnG, lnP, Phi, lnW, J, self.lnJ_floor):
            a.setflags(write=False)
        self.G_min = math.exp(lnG[0])
        self.G_max = math.exp(lnG[-1])
        self.P_end = math.exp(lnP[-1])


# Table range: below G = 1e-7 every P equals 1 to double precision (erfc(1/(2 sqrt G)) < 1e-300 already at
# 1e-3); 1e28 covers p/E* down to about 1e-14 h'. 400 nodes per e-fold: tables accurate to about 1e-6.
_LNG_MIN, _LNG_MAX, _PER_EFOLD = math.log(1e-7), math.log(1e28), 400


def _s_yang_persson(gamma):
    """S(P) = gamma + (1 - gamma) P^2 and dS/dP."""
    return (lambda P: gamma + (1.0 - gamma) * P * P), (lambda P: 2.0 * (1.0 - gamma) * P)


def _s_wang_muser(a):
    """S_WM(P) = a - 2/9 P^2 + (11/9 - a) P^4 and dS/dP (Wang & Müser 2017)."""
    b = 11.0 / 9.0 - a
    return (lambda P: a - (2.0 / 9.0) * P * P + b * P**4), (lambda P: -(4.0 / 9.0) * P + 4.0 * b * P**3)


@functools.lru_cache(maxsize=32)
def _area(correction: str | None, gamma: float):
    """(ln G grid, P_c, dP_c/dln G) of an area law on the uniform table grid."""
    n = int(round((_LNG_MAX - _LNG_MIN) * _PER_EFOLD)) + 1
    lnG = np.linspace(_LNG_MIN, _LNG_MAX, n)
    if correction in ("yang-persson", "wang-muser"):
        S, _ = _s_yang_persson(gamma) if correction == "yang-persson" else _s_wang_muser(WANG_MUSER_A)
        s0 = S(0.0)
        # Tabulate in ln G_c: G(G_c) = int_0^Gc dg / S(P(g)) (S = 1 below the first node, to 1e-300).
        lnGc = np.linspace(_LNG_MIN, _LNG_MAX + math.log(1.0 / s0) + 1.0, n + 400)
        Gc = np.exp(lnGc)
        f = Gc / S(_erf_area(Gc))
        G_of = Gc[0] + _integrate().cumulative_simpson(f, x=lnGc, initial=0.0)
        Gc_at = np.exp(np.interp(lnG, np.log(G_of), lnGc))
        P = _erf_area(Gc_at)
        x = 0.5 / np.sqrt(Gc_at)
        # dP/dlnG = dP/dlnGc * dlnGc/dlnG, dG_c/dG = S(P)
        dP = -x / math.sqrt(math.pi) * np.exp(-x * x) * np.exp(lnG) / Gc_at * S(P)
    elif correction is None:
        G = np.exp(lnG)
        P = _erf_area(G)
        x = 0.5 / np.sqrt(G)
        dP = -x / math.sqrt(math.pi) * np.exp(-x * x)
    else:
        G = np.exp(lnG)
        P = _xu_root(G, gamma)
        m = gamma + (1.0 - gamma) * P
        y = 0.5 / np.sqrt(G * m)
        e = -y / math.sqrt(math.pi) * np.exp(-y * y)  # dP/dlnG at fixed m
        dP = e / (1.0 - e * (1.0 - gamma) / m)         # implicit differentiation through m(P)
    return lnG, P, dP


@functools.lru_cache(maxsize=32)
def _table(correction: str | None, gamma: float, gap: str = "area") -> _Table:
    lnG, P, dP = _area(correction, gamma)
    G = np.exp(lnG)
    # friction weight S(P_c) P_c with the friction model's S (the engine's kernels use the same)
    Phi = G[0] + _integrate().cumulative_simpson(P * (gamma + (1.0 - gamma) * P * P) * G, x=lnG, initial=0.0)
    # energy weight W = P_e S_e(P_e) of the gap law
    if gap == "area":
        P_e, dP_e = P, dP
        S, dS = _s_wang_muser(WANG_MUSER_A) if correction == "wang-muser" else _s_yang_persson(gamma)
    elif gap == "persson":
        _, P_e, dP_e = _area(None, gamma)
        S, dS = _s_yang_persson(gamma)
    elif gap == "gfmd-gap":
        _, P_e, dP_e = _area(None, gamma)
        S, dS = _s_yang_persson(GFMD_GAP_GAMMA)
    elif gap == "xu2024-hybrid":
        _, P_e, dP_e = _area("xu2024", gamma)
        S, dS = _s_wang_muser(gamma)
    else:  # pragma: no cover - names are checked by the callers
        raise InputError(f"gap_correction: unknown {gap!r}")
    W = P_e * S(P_e)
    dW = (S(P_e) + P_e * dS(P_e)) * dP_e        # dW/dlnG <= 0
    # J_c = sqrt(pi) int_0^G sqrt(g) (-dW/dg) dg = sqrt(pi) int sqrt(g) (-dW/dlng) dlng (no cancellation)
    J = math.sqrt(math.pi) * _integrate().cumulative_simpson(-dW * np.sqrt(G), x=lnG, initial=0.0)
    return _Table(lnG, np.log(P), Phi, np.log(W), np.maximum(J, 0.0))


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
