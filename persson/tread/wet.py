r"""Wet road: the pseudo-hydrodynamic bearing that lifts the tread (Eq. 7 of the element tool's paper, "Tire/pavement
friction: presentation of a comprehensive physical tool through advanced contact modelling").

The water film between the tread and the road is treated as a fixed-incline slider bearing (Reynolds 1886; the
closed form in Hamrock, Schmid & Jacobson, *Fundamentals of Fluid Film Lubrication*, 2nd ed. 2004, ch. 8, with
:math:`m = a - 1`): a pad of length L (rolling direction) and width l moving at V over a film that narrows from
:math:`H_{in}` to :math:`H_{out}` carries

.. math:: W_h = \frac{\alpha\,6\eta V\,\beta\,l\,L^2}{H_{out}^2 (a - 1)^2}
          \left[\ln a - \frac{2(a - 1)}{a + 1}\right],\qquad a = \frac{H_{in}}{H_{out}} ,

with :math:`\alpha = \beta = 1` the pure slider. The element tool applies it to the tyre footprint as a "pseudo"
bearing with two empirical factors :math:`\alpha, \beta` (the wetting effect of the element model: M. Kane, M.-T.
Do, V. Cerezo, Z. Rado, C. Khelifi, Int. J. Pavement Eng. (2017), doi:10.1080/10298436.2017.1369776). Calibrated
values of :math:`\alpha, \beta`, and the authors' choice of :math:`H_{in}, H_{out}`, could not be found in the sources
consulted, so both factors default to 1 and are inputs, and the film thicknesses are this package's choice below.
The asperities carry :math:`W - W_h`; the friction is normalised by W; adhesion is taken out of :math:`\mu_{loc}`.

Choice of the film thicknesses (stated here because the result depends on it as :math:`H_{out}^{-2}`):

* :math:`H_{out}` is the gap left under the trailing edge, where the tread rests on the road's summits and water
  can only flow through the texture: the road's estimated texture depth ETD = 0.2 mm + 0.8 MPD (ISO 13473-1);
* :math:`H_{in} = \max(h_w, H_{out})`: the water depth :math:`h_w` (above the mean road plane) that the leading
  edge meets. When the texture holds all the water (:math:`h_w \le` ETD) there is no wedge and no lift.

The pattern splits the bearing into pads: a pad is ``Grooves.pad_length()`` long in the rolling direction (the
grooves vent the pressure), and the lift of the footprint is the sum over its pads,
:math:`W_h \propto L\,L_{pad}` instead of :math:`L^2`; circumferential grooves shorten the width l to the rubber's
share. Side leakage is neglected (an upper bound).

What the bearing leaves out is reported, not hidden: the film's inertia (the modified Reynolds number
:math:`Re^* = \rho V H_{out}^2/(\eta L)` is large at road speeds), and dynamic hydroplaning (the dynamic pressure
:math:`\rho V^2/2` against the inflation pressure: Horne & Dreher, NASA TN D-2056 (1963)); water deeper than the
texture and the grooves can hold is allowed and noted.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .._checks import positive
from ..errors import InputError
from .pattern import Grooves

__all__ = ["Water", "WetState", "bearing_lift", "wet_state", "REYNOLDS_1886", "KANE_2017", "KANE_2019", "HORNE_1963"]

#: O. Reynolds, On the theory of lubrication, Phil. Trans. R. Soc. Lond. 177, 157 (1886).
REYNOLDS_1886 = "10.1098/rstl.1886.0005"
#: M. Kane, M.-T. Do, V. Cerezo, Z. Rado, C. Khelifi, Contribution to pavement friction modelling: an
#: introduction of the wetting effect, Int. J. Pavement Eng. (published online 6 Sep 2017).
KANE_2017 = "10.1080/10298436.2017.1369776"
#: The same paper under the name this module first gave it (kept for scripts that use it).
KANE_2019 = KANE_2017
#: B. J. Hamrock, S. R. Schmid, B. O. Jacobson, Fundamentals of Fluid Film Lubrication, 2nd ed. (2004), ch. 8.
HAMROCK_2004 = "hamrock:fffl-2004"
#: W. B. Horne, R. C. Dreher, Phenomena of pneumatic tire hydroplaning, NASA TN D-2056 (1963).
HORNE_1963 = "nasa:TN-D-2056"
ISO_13473 = "iso:13473-1:2019"


@dataclass(frozen=True)
class Water:
    r"""The water on the road (Table 1 of the paper: thickness, viscosity, density) and the bearing's factors.

    Parameters
    ----------
    thickness : float
        Water depth :math:`h_w` above the mean road plane, m (> 0; the paper's tests used 1-2 mm).
    viscosity : float
        Dynamic viscosity :math:`\eta`, Pa s (water at 20 C: 1.0e-3).
    density : float
        Density, kg/m^3 (1000): used for the inertia and hydroplaning checks.
    alpha, beta : float
        Empirical factors of Eq. 7 (1: the pure slider bearing).
    outlet_gap : float, optional
        :math:`H_{out}`, m; default the road's estimated texture depth.
    """

    thickness: float
    viscosity: float = 1.0e-3
    density: float = 1000.0
    alpha: float = 1.0
    beta: float = 1.0
    outlet_gap: float | None = None

    def __post_init__(self):
        for name in ("thickness", "viscosity", "density"):
            object.__setattr__(self, name, positive(getattr(self, name), f"water.{name}"))
        if self.thickness > 0.05:
            raise InputError(f"water.thickness: {self.thickness:g} m is a flood, not a water film; expected metres "
                             "(1 mm = 1e-3)")
        for name in ("alpha", "beta"):
            v = float(getattr(self, name))
            if not math.isfinite(v) or v < 0:
                raise InputError(f"water.{name}: expected a factor >= 0, got {v!r}")
            object.__setattr__(self, name, v)
        if self.outlet_gap is not None:
            object.__setattr__(self, "outlet_gap", positive(self.outlet_gap, "water.outlet_gap"))


@doi(REYNOLDS_1886, HAMROCK_2004, KANE_2017)
def bearing_lift(speed, *, viscosity: float, length: float, width: float, inlet: float, outlet: float,
                 alpha: float = 1.0, beta: float = 1.0):
    r"""Load capacity of the pseudo-hydrodynamic bearing, Eq. 7, N.

    .. math:: W_h = \frac{\alpha\,6\eta V\beta\,l L^2}{H_{out}^2 (a - 1)^2}\left[\ln a - \frac{2(a-1)}{a+1}\right],
              \qquad a = H_{in}/H_{out}

    Parameters
    ----------
    speed : float or array_like
        Sliding speed of the pad over the film V, m/s.
    viscosity : float
        :math:`\eta`, Pa s.
    length, width : float
        Pad length L (rolling direction) and width l, m.
    inlet, outlet : float
        :math:`H_{in} \ge H_{out} > 0`, m. Equal gaps (a = 1) carry nothing (the limit of the formula).
    alpha, beta : float
        Empirical factors.

    Returns
    -------
    float or ndarray
        :math:`W_h` (0 where a = 1); for a -> 1 the series :math:`[\ldots]/(a-1)^2 \to (a-1)/12` is used.
    """
    if not inlet >= outlet > 0:
        raise InputError(f"bearing_lift: expected inlet >= outlet > 0, got inlet={inlet:g}, outlet={outlet:g} m")
    a = inlet / outlet
    m = a - 1.0
    if m < 1e-3:  # ln(1+m) - 2m/(2+m) = m^3/12 - m^4/12 + ...
        shape = m / 12.0 - m * m / 12.0
    else:
        shape = (math.log(a) - 2.0 * m / (a + 1.0)) / (m * m)
    return alpha * 6.0 * viscosity * np.asarray(speed, dtype=float) * beta * width * length ** 2 / outlet ** 2 * shape


@dataclass(frozen=True)
class WetState:
    """The bearing of one tyre on one wet road at one speed.

    Attributes
    ----------
    lift : float
        Hydrodynamic load :math:`W_h`, N (capped so that the asperities keep 5 % of the load).
    inlet, outlet : float
        :math:`H_{in}, H_{out}`, m.
    pad_length : float
        Length of one bearing pad, m.
    reynolds : float
        Modified Reynolds number :math:`\\rho V H_{out}^2/(\\eta L)`.
    notes : tuple of str
    """

    lift: float
    inlet: float
    outlet: float
    pad_length: float
    reynolds: float
    notes: tuple = ()


@doi(REYNOLDS_1886, KANE_2017, HORNE_1963, ISO_13473)
def wet_state(water: Water, tire, road, speed: float, slip: float = 1.0, *,
              texture_depth: float | None = None) -> WetState:
    r"""Hydrodynamic lift of ``tire`` on ``road`` under ``water`` at vehicle speed ``speed`` (m/s) and ``slip``.

    The slider formula has one surface moving at U; in the footprint both surfaces drag water into the wedge,
    the road at V and the tread at :math:`\omega r = (1 - s)V` (relative to the wheel centre), so the speed in
    Eq. 7 is their sum :math:`U = (2 - s)V` (twice the mean entrainment speed; U = V for the locked wheel).

    Parameters
    ----------
    water : Water
    tire : persson.tread.Tire
    road : persson.tread.Road
        Its texture depth (ETD) is the default outlet gap.
    speed : float
        Vehicle speed V, m/s.
    slip : float
        Braking slip ratio s in [0, 1].
    texture_depth : float, optional
        The road's ETD, m, when already known (it is the default outlet gap).

    Returns
    -------
    WetState
    """
    if not isinstance(water, Water):
        raise InputError(f"water: expected persson.tread.Water or None, got {type(water).__name__}")
    V = positive(speed, "speed")
    U = (2.0 - float(slip)) * V
    fp = tire.footprint
    if water.outlet_gap is not None:
        etd = water.outlet_gap
    else:
        etd = road.texture_depth() if texture_depth is None else positive(texture_depth, "texture_depth")
    outlet = etd
    inlet = max(water.thickness, outlet)
    L = fp.length
    pad = L
    width = fp.width
    g = tire.grooves
    if g is not None:
        pad = min(L, g.pad_length())
        if isinstance(g, Grooves) and abs(abs(g.angle_deg) - 90.0) < 1e-9:
            width = fp.width * (1.0 - g.void_fraction)
    one = bearing_lift(U, viscosity=water.viscosity, length=pad, width=width, inlet=inlet, outlet=outlet,
                       alpha=water.alpha, beta=water.beta)
    lift = float(one) * (L / pad)
    notes = []
    capacity = etd + tire.void_fraction * tire.groove_depth
    if water.thickness > capacity:
        notes.append(f"water {water.thickness * 1e3:.3g} mm is deeper than the road texture and the tread grooves can "
                     f"hold ({capacity * 1e3:.3g} mm: ETD {etd * 1e3:.3g} mm + grooves); the film is carried "
                     "into the footprint")
    if inlet > outlet and inlet / outlet > 2.2:
        notes.append(f"inlet/outlet gap ratio {inlet / outlet:.3g} is past the slider's optimum (about 2.2): the "
                     "pseudo-bearing lift falls as the water deepens, where a real tyre would ride up")
    re = water.density * U * outlet ** 2 / (water.viscosity * L)
    if re > 1.0:
        notes.append(f"modified Reynolds number of the film {re:.3g} > 1: fluid inertia, which the viscous bearing "
                     "leaves out, matters")
    dyn = 0.5 * water.density * V * V
    if water.thickness > capacity and dyn > 0.5 * tire.inflation_pressure:
        notes.append(f"dynamic water pressure {dyn / 1e5:.3g} bar exceeds half the inflation pressure: dynamic "
                     "hydroplaning (Horne & Dreher 1963) is possible and is not modelled")
    cap = 0.95 * tire.load
    if lift > cap:
        notes.append(f"hydrodynamic lift {lift:.4g} N capped at 95 % of the load: the tread would hydroplane")
        lift = cap
    return WetState(lift=lift, inlet=inlet, outlet=outlet, pad_length=pad, reynolds=re, notes=tuple(notes))
