r"""The tyre, step 1: the static footprint on a smooth rigid road (contact length, width, pressure).

Model (the contact-patch relations of MF-Swift, Pacejka, *Tire and Vehicle Dynamics*, 3rd ed. 2012, Appendix 3,
Eqs. A3.7-A3.8, with the pressure-dependent vertical stiffness of MF-Tyre 6.1):

* equivalent structural stiffness from the inflation pressure :math:`p_i` and the carcass,

  .. math:: C_z(p_i) = C_{z0}\,[1 + p_{Fz1}(p_i - p_{0})/p_{0}]
            = \underbrace{C_{z0}(1 - p_{Fz1})}_{\text{carcass}} + \underbrace{C_{z0}\,p_{Fz1}\,p_i/p_0}_{\text{air}},

* vertical deflection :math:`\rho` from the load, :math:`F_z = C_z(p_i)\,\rho\,(1 + q\,\rho/R_0)` (the quadratic
  stiffening of MF-Tyre's load-deflection law, :math:`q = q_{Fz2}/q_{Fz1}`),
* half length and half width of the footprint,

  .. math:: a = R_0\left(q_{ra2}\frac{\rho}{R_0} + q_{ra1}\sqrt{\frac{\rho}{R_0}}\right),\qquad
            b = w\left(q_{rb2}\frac{\rho}{R_0} + q_{rb1}\left(\frac{\rho}{R_0}\right)^{1/3}\right),

  :math:`R_0 = D/2` the free radius and w the section width; the patch is 2a long and 2b wide, its mean
  pressure :math:`\sigma_0 = F_z/(4ab)`, distributed along the length as the brush model's pressure laws
  (parabolic, uniform, Sakai's n-power law; :class:`persson.slip.Contact`).

Default coefficients: those of the MF-Tyre reference passenger tyre (205/60 R15, 2.2 bar, nominal load 4 kN) as
distributed in public MF-Tyre property files: :math:`C_{z0} = 209\,651` N/m at :math:`p_0` = 2.2 bar,
:math:`p_{Fz1} = 0.7098`, :math:`q_{Fz2} = 15.4` (:math:`q \approx 0.94`), :math:`q_{ra1} = 0.671`,
:math:`q_{ra2} = 0.733`, :math:`q_{rb1} = 1.059`, :math:`q_{rb2} = -1.1878`. For another size the stiffness is
scaled with :math:`\sqrt{w D}` (the dependence of the vertical stiffness on the tyre's size found by Rhyne,
Tire Sci. Technol. 33, 136 (2005)); give ``vertical_stiffness`` when it is known.

At 2.2 bar and 4 kN the reference tyre gets a 128 mm x 140 mm footprint (mean pressure 2.24 bar, 1.02 times the
inflation pressure; area within 3 % of the load / inflation-pressure rule used in pavement design). Against
measured 255/40 R17 passenger tyres (ink prints and load-deflection curves at 1.65-2.48 bar and 2.2-6.2 kN, the
model given only the size, load and pressure) the deflection is within 6 % and the footprint area within 10 %,
but the footprint is 16-35 % too long and 14-20 % too narrow: the shape belongs to the reference tyre. A measured
footprint (``contact_length``, ``contact_width``) replaces the relations; see ``docs/tread.md``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from .._checks import number, positive
from ..errors import InputError, PhysicsWarning
from .pattern import FootprintPattern, Grooves

__all__ = ["Tire", "Footprint", "REFERENCE_TIRE", "RHYNE_2005"]

#: T. B. Rhyne, Development of a vertical stiffness relationship for belted radial tires, Tire Sci. Technol. 33,
#: 136 (2005).
RHYNE_2005 = "10.2346/1.2174340"
PACEJKA_BOOK = "isbn:9780080970165"
SAKAI_1981 = "sakai:ijvd-1981"

#: The MF-Tyre reference passenger tyre (205/60 R15) whose coefficients are the defaults.
REFERENCE_TIRE = {"diameter": 0.627, "width": 0.205, "vertical_stiffness": 209651.0, "reference_pressure": 2.2e5,
                  "pressure_effect": 0.7098, "stiffening": 15.4 / (209651.0 * 0.3135 / 4000.0),
                  "patch_coefficients": (0.671, 0.733, 1.059, -1.1878)}


@doi(PACEJKA_BOOK, RHYNE_2005)
@dataclass(frozen=True)
class Tire:
    r"""A passenger-car tyre: size, load, inflation, tread and its pattern.

    Parameters
    ----------
    diameter : float
        Free (unloaded) outer diameter D, m.
    width : float
        Section width w, m.
    load : float
        Normal load :math:`F_z` on the wheel, N.
    inflation_pressure : float
        Inflation pressure :math:`p_i`, Pa (gauge; 2.2 bar = 2.2e5 Pa).
    tread_depth : float
        Rubber thickness h of the tread above the belt, m (its normal stiffness per unit area is E/h).
    grooves : Grooves, FootprintPattern or None
        The tread pattern; None for a slick.
    slip_stiffness : float or None
        Longitudinal slip stiffness per unit load, :math:`C_{F\kappa}/F_z` (the initial slope of mu(slip)),
        default 20, the order of passenger-car tyres; it sets the shear stiffness of the elements (tread, belt
        and carcass in series) as in the brush model, :math:`k_x = 2\sigma_0 C_{F\kappa}/(F_z\,l)`. None: the
        elements are rigid in shear and every contacting element slides (the paper's equations as written).
    pressure_distribution : str or dict
        Pressure along the footprint: ``"parabolic"`` (default), ``"uniform"`` or ``{"sakai_n": n}``.
    vertical_stiffness : float, optional
        :math:`C_{z0}`, N/m, at ``reference_pressure``; default the reference tyre's scaled with
        :math:`\sqrt{wD}`.
    reference_pressure : float
        :math:`p_0`, Pa, at which ``vertical_stiffness`` holds (default 2.2e5).
    pressure_effect : float
        :math:`p_{Fz1}`: share of the vertical stiffness due to the air at :math:`p_0` (default 0.7098).
    stiffening : float
        q of :math:`F_z = C_z\rho(1 + q\rho/R_0)` (default 0.937).
    patch_coefficients : tuple of 4 floats
        :math:`(q_{ra1}, q_{ra2}, q_{rb1}, q_{rb2})` of the footprint size (default the reference tyre's).
    aspect_ratio : float
        Section height / section width (default 0.6); a deflection beyond half the section height is refused.
    contact_length, contact_width : float, optional
        A measured footprint (e.g. the bounding box of an ASTM F870 ink print at this load and inflation), m: used
        instead of the footprint relations (the deflection still follows from the stiffness). The relations with
        the default coefficients are those of one 205/60 R15 tyre; on a 255/40 R17 they get the area within 10 % but
        the length 16-35 % too long and the width 14-20 % too narrow (docs/tread.md), so give a measured footprint
        (or the tyre's own ``patch_coefficients``) when the footprint's shape matters.

    Raises
    ------
    InputError
        Naming the argument: non-positive sizes or pressures, a tread deeper than a quarter of the section height,
        a load that would press the tyre beyond half its section height (the carcass would bottom out on the rim),
        a footprint longer than the tyre's diameter, or a groove pattern that is not a :class:`Grooves` or
        :class:`FootprintPattern`.
    """

    diameter: float
    width: float
    load: float
    inflation_pressure: float
    tread_depth: float
    grooves: object = None
    slip_stiffness: float | None = 20.0
    pressure_distribution: object = "parabolic"
    vertical_stiffness: float | None = None
    reference_pressure: float = 2.2e5
    pressure_effect: float = 0.7098
    stiffening: float = REFERENCE_TIRE["stiffening"]
    patch_coefficients: tuple = REFERENCE_TIRE["patch_coefficients"]
    aspect_ratio: float = 0.6
    contact_length: float | None = None
    contact_width: float | None = None
    _footprint: object = field(init=False, repr=False, compare=False, default=None)

    def __post_init__(self):
        for name in ("diameter", "width", "load", "inflation_pressure", "tread_depth", "reference_pressure",
                     "aspect_ratio"):
            object.__setattr__(self, name, positive(getattr(self, name), f"tire.{name}"))
        if self.width >= self.diameter:
            raise InputError(f"tire.width: {self.width:g} m is not smaller than the diameter {self.diameter:g} m")
        if self.inflation_pressure < 1e4 or self.inflation_pressure > 2e6:
            raise InputError(f"tire.inflation_pressure: {self.inflation_pressure:g} Pa is outside 0.1-20 bar; give "
                             "the gauge pressure in Pa (2.2 bar = 2.2e5 Pa)")
        height = self.aspect_ratio * self.width
        if self.tread_depth > 0.25 * height:
            raise InputError(f"tire.tread_depth: {self.tread_depth * 1e3:g} mm is deeper than a quarter of the "
                             f"section height ({height * 1e3:.3g} mm); expected metres (8 mm = 8e-3)")
        if self.slip_stiffness is not None:
            object.__setattr__(self, "slip_stiffness", positive(self.slip_stiffness, "tire.slip_stiffness"))
        pe = number(self.pressure_effect, "tire.pressure_effect")
        if not 0.0 <= pe < 1.0:
            raise InputError(f"tire.pressure_effect: expected 0 <= p_Fz1 < 1 (the air's share of the stiffness), "
                             f"got {pe:g}")
        object.__setattr__(self, "pressure_effect", pe)
        q = number(self.stiffening, "tire.stiffening")
        if q < 0:
            raise InputError(f"tire.stiffening: expected q >= 0, got {q:g}")
        object.__setattr__(self, "stiffening", q)
        pc = tuple(number(c, f"tire.patch_coefficients[{i}]") for i, c in enumerate(self.patch_coefficients))
        if len(pc) != 4 or pc[0] <= 0 or pc[2] <= 0:
            raise InputError(f"tire.patch_coefficients: expected (q_ra1 > 0, q_ra2, q_rb1 > 0, q_rb2), got {pc}")
        object.__setattr__(self, "patch_coefficients", pc)
        if self.vertical_stiffness is not None:
            object.__setattr__(self, "vertical_stiffness", positive(self.vertical_stiffness,
                                                                     "tire.vertical_stiffness"))
        for name in ("contact_length", "contact_width"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, positive(getattr(self, name), f"tire.{name}"))
        if self.contact_length is not None and self.contact_length >= self.diameter:
            raise InputError(f"tire.contact_length: {self.contact_length:g} m is not shorter than the diameter "
                             f"{self.diameter:g} m; expected metres (a passenger tyre's footprint is about 0.1 m "
                             "long)")
        if self.contact_width is not None and self.contact_width > 1.2 * self.width:
            raise InputError(f"tire.contact_width: {self.contact_width:g} m is wider than the section width "
                             f"{self.width:g} m allows; expected metres")
        if self.grooves is not None and not isinstance(self.grooves, (Grooves, FootprintPattern)):
            raise InputError(f"tire.grooves: expected persson.tread.Grooves, a FootprintPattern or None, got "
                             f"{type(self.grooves).__name__}")
        from ..slip.contact import _parse_distribution

        try:
            _parse_distribution(self.pressure_distribution)
        except InputError as exc:
            raise InputError(f"tire.pressure_distribution: {exc}") from None
        object.__setattr__(self, "_footprint", _footprint(self))

    # --------------------------------------------------------------------------------------------------------
    @property
    def footprint(self) -> "Footprint":
        """The static footprint (step 1)."""
        return self._footprint

    @property
    def groove_depth(self) -> float:
        """Depth of the grooves, m (the tread depth unless the pattern says otherwise; 0 for a slick)."""
        if self.grooves is None:
            return 0.0
        d = getattr(self.grooves, "depth", None)
        return min(self.tread_depth, d) if d is not None else self.tread_depth

    @property
    def void_fraction(self) -> float:
        """Fraction of the footprint taken by grooves (0 for a slick)."""
        return 0.0 if self.grooves is None else float(self.grooves.void_fraction)

    def land(self, x, y) -> np.ndarray:
        """True where the tread has rubber at material position x (along the circumference) and y (across), m."""
        x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        if self.grooves is None:
            return np.ones(x.shape, dtype=bool)
        return self.grooves.land(x, y)

    def contact(self, n_points: int = 401):
        """The footprint as a :class:`persson.slip.Contact` (the brush model's patch), with the shear stiffness
        per unit area of ``slip_stiffness`` (InputError when it is None)."""
        from ..slip.contact import Contact

        if self.slip_stiffness is None:
            raise InputError("tire.slip_stiffness: None (rigid elements) has no brush-model equivalent")
        fp = self.footprint
        return Contact(length=fp.length, width=fp.width, stiffness=fp.shear_stiffness,
                       pressure_distribution=self.pressure_distribution, n_points=n_points)


@doi(PACEJKA_BOOK, RHYNE_2005)
@dataclass(frozen=True)
class Footprint:
    """The static footprint of a :class:`Tire` on a smooth rigid road.

    Attributes
    ----------
    length : float
        Contact length 2a in the rolling direction, m.
    width : float
        Contact width 2b, m.
    deflection : float
        Vertical deflection rho, m.
    vertical_stiffness : float
        :math:`C_z(p_i)`, N/m (secant stiffness at the load: load / deflection).
    carcass_stiffness : float
        The carcass share :math:`C_{z0}(1 - p_{Fz1})`, N/m.
    mean_pressure : float
        Load / (length x width), Pa (the gross footprint, grooves included).
    membrane_area : float
        Load / inflation pressure, m^2: the area of a membrane without carcass (the pavement-design rule).
    shear_stiffness : float
        Shear stiffness of the tread per unit area, Pa/m (inf for rigid elements).
    notes : tuple of str
    """

    length: float
    width: float
    deflection: float
    vertical_stiffness: float
    carcass_stiffness: float
    mean_pressure: float
    membrane_area: float
    shear_stiffness: float
    notes: tuple = ()

    @property
    def area(self) -> float:
        """Gross footprint area length x width, m^2."""
        return self.length * self.width


def _footprint(t: Tire) -> Footprint:
    ref = REFERENCE_TIRE
    R0 = t.diameter / 2.0
    if t.vertical_stiffness is None:
        Cz0 = ref["vertical_stiffness"] * math.sqrt(t.width * t.diameter / (ref["width"] * ref["diameter"]))
    else:
        Cz0 = t.vertical_stiffness
    dp = (t.inflation_pressure - t.reference_pressure) / t.reference_pressure
    Cz = Cz0 * (1.0 + t.pressure_effect * dp)
    if Cz <= 0:
        raise InputError(f"tire.inflation_pressure: {t.inflation_pressure:g} Pa leaves no vertical stiffness "
                         f"(C_z = {Cz:g} N/m); the tyre is flat")
    # F = Cz rho (1 + q rho / R0): the positive root
    q = t.stiffening
    rho = t.load / Cz if q == 0 else (-1.0 + math.sqrt(1.0 + 4.0 * q * t.load / (Cz * R0))) * R0 / (2.0 * q)
    height = t.aspect_ratio * t.width
    if rho > 0.5 * height:
        raise InputError(f"tire.load: {t.load:g} N deflects the tyre by {rho * 1e3:.3g} mm, beyond half its section "
                         f"height ({height * 1e3:.3g} mm): the load is beyond what the carcass can carry at "
                         f"{t.inflation_pressure / 1e5:.3g} bar (it would bottom out on the rim)")
    x = rho / R0
    qa1, qa2, qb1, qb2 = t.patch_coefficients
    a = R0 * (qa2 * x + qa1 * math.sqrt(x))
    b = t.width * (qb2 * x + qb1 * x ** (1.0 / 3.0))
    notes = []
    if 2.0 * a >= t.diameter:
        raise InputError(f"tire.load: the footprint ({2 * a * 1e3:.3g} mm) would be longer than the diameter")
    if b <= 0:
        raise InputError(f"tire.load: {t.load:g} N is outside the footprint model (its width vanishes at "
                         f"rho/R0 = {x:.3g})")
    if 2.0 * b > t.width:
        notes.append(f"footprint width {2 * b * 1e3:.3g} mm capped at the section width {t.width * 1e3:.3g} mm")
        b = t.width / 2.0
    if rho > 0.3 * height:
        msg = (f"deflection {rho * 1e3:.3g} mm is {rho / height:.0%} of the section height: beyond the usual "
               "operating range of passenger tyres, where the footprint relations were fitted")
        notes.append(msg)
        warnings.warn(msg, PhysicsWarning, stacklevel=4)
    length, width = 2.0 * a, 2.0 * b
    if t.contact_length is not None:
        notes.append(f"footprint length {t.contact_length * 1e3:.4g} mm as given (the relations give "
                     f"{length * 1e3:.4g} mm)")
        length = t.contact_length
    if t.contact_width is not None:
        notes.append(f"footprint width {t.contact_width * 1e3:.4g} mm as given (the relations give "
                     f"{width * 1e3:.4g} mm)")
        width = t.contact_width
    sigma0 = t.load / (length * width)
    shear = math.inf if t.slip_stiffness is None else 2.0 * sigma0 * t.slip_stiffness / length
    return Footprint(length=length, width=width, deflection=rho, vertical_stiffness=t.load / rho,
                     carcass_stiffness=Cz0 * (1.0 - t.pressure_effect), mean_pressure=sigma0,
                     membrane_area=t.load / t.inflation_pressure, shear_stiffness=shear, notes=tuple(notes))
