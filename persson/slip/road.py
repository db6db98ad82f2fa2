r"""Slip curves at road speeds: the model with both kinds of frictional heating, and the published reference curves.

At road speeds (a braked tire at 20-130 km/h) the rubber heats at two scales: the flash temperature of the
macro-asperity contacts (Persson, J. Phys.: Condens. Matter 18, 7789 (2006)) and the background temperature that
builds up along the contact patch as the tread slides through it (Persson & Miyashita, arXiv:2602.22078 (2026);
Carslaw & Jaeger, *Conduction of Heat in Solids*, ch. II). Persson splits the rubber temperature into exactly these
two parts, the flash riding on the background, and both shape a measured mu-slip curve: the flash temperature makes
the local friction fall with the sliding speed, the background temperature makes the locked wheel (whose tread
stays in the patch) slide on hot rubber. :func:`road_model` builds that model; :func:`with_road_heating` adds the
two effects to an existing one. :func:`persson.slip.mu_slip` leaves the model as given (an explicit model gives the
same numbers as before) and notes when a model without heating is asked for road speeds.

The reference curves: Pacejka's Magic Formula for a dry tarmac (:data:`MF_DRY_TARMAC`), Burckhardt's law for
dry asphalt (:func:`burckhardt`, :data:`BURCKHARDT_DRY_ASPHALT`) and the longitudinal Magic Formula of a measured
passenger-car tire, the 205/60R15 of Pacejka's book (:data:`TIRE_205_60R15`, :func:`tire_magic_formula`,
:func:`tire_slip_stiffness`), whose slip stiffness also gives the carcass and belt compliance that the brush of a tire
adds to its tread (:func:`carcass_stiffness`). :func:`example_road_case` is the documented realistic case (a
passenger-car tire on a dry asphalt) that ``docs/slip.md`` compares with them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .._checks import number, positive
from ..effects.builtin import FlashTemperature
from ..errors import InputError
from .contact import Contact, Tread
from .curve import ROAD_SPEED, mu_slip
from .heating import PatchHeating
from .references import BURCKHARDT_1993, CARSLAW_JAEGER, MAGIC_FORMULA, PACEJKA_BOOK, PERSSON_TREAD_2026

__all__ = ["road_model", "with_road_heating", "ROAD_SPEED", "burckhardt", "BURCKHARDT_DRY_ASPHALT",
           "MF_DRY_TARMAC", "TIRE_205_60R15", "tire_magic_formula", "tire_slip_stiffness", "carcass_stiffness",
           "RoadCase", "example_road_case"]

#: H. B. Pacejka, Tyre and Vehicle Dynamics, 2nd ed., Butterworth-Heinemann (2006), Appendix 3, Table A3.1.
PACEJKA_2006_TABLE = "isbn:9780750669184"

#: Burckhardt's constants (c1, c2, c3) for dry asphalt (Burckhardt 1993): peak 1.17 at 17 % slip, locked 0.76.
BURCKHARDT_DRY_ASPHALT = (1.2801, 23.99, 0.52)

#: Magic Formula constants (B, C, D, E) of a dry tarmac (Pacejka 2012, ch. 4): peak 1.00 near 18 % slip,
#: locked about 0.91.
MF_DRY_TARMAC = (10.0, 1.9, 1.0, 0.97)

#: Longitudinal pure-slip Magic Formula coefficients of a measured passenger-car tire, 205/60R15 91V at 2.2 bar
#: (Pacejka 2006, Appendix 3, Table A3.1): nominal load ``FNOMIN`` (N) and test speed ``LONGVL`` (m/s); the
#: horizontal and vertical shifts (PHX1 = -0.002, PHX2 = 0.002, PVX1 = PVX2 = 0) are left out.
TIRE_205_60R15 = {"FNOMIN": 4000.0, "LONGVL": 16.67, "PCX1": 1.685, "PDX1": 1.210, "PDX2": -0.037,
                  "PEX1": 0.344, "PEX2": 0.095, "PEX3": -0.020, "PKX1": 21.51, "PKX2": -0.163, "PKX3": 0.245}


@doi("10.1088/0953-8984/18/32/025", PERSSON_TREAD_2026, CARSLAW_JAEGER)
def road_model(surface, material, *, effects=(), patch_heating: PatchHeating | None = None,
               flash_temperature: FlashTemperature | None = None, **model_options):
    """The friction model for slip curves at road speeds: the flash temperature riding on the patch heating.

    Parameters
    ----------
    surface, material
        As for :class:`persson.Model`.
    effects : sequence of Effect
        Further effects (adhesion, strain softening, ...). A ``patch_heating`` or ``flash_temperature`` among them
        replaces the default one.
    patch_heating : PatchHeating, optional
        The patch heating (default ``PatchHeating()``: an asphalt road, all the frictional power heating the patch).
    flash_temperature : FlashTemperature, optional
        The flash temperature (default ``FlashTemperature()``).
    **model_options
        ``nu``, ``gamma``, ``grid``, ``correction`` of :class:`persson.Model`.

    Returns
    -------
    persson.Model
        With both heating effects; the patch tables evaluate the engine, flash temperature included, at the local
        background temperature of the patch (:func:`persson.slip.patch_friction`).
    """
    from ..engine.model import Model

    return with_road_heating(Model(surface, material, effects=tuple(effects), **model_options),
                             patch_heating=patch_heating, flash_temperature=flash_temperature)


def with_road_heating(model, *, patch_heating: PatchHeating | None = None,
                      flash_temperature: FlashTemperature | None = None):
    """``model`` with :class:`PatchHeating` and :class:`FlashTemperature` added where it has none (its own are
    kept unless replacements are given).

    Raises
    ------
    InputError
        ``model`` is not a :class:`persson.Model`, or a replacement has the wrong type.
    """
    if not all(hasattr(model, a) for a in ("with_effect", "effect_names")):
        raise InputError(f"model: expected a persson.Model, got {model!r}")
    for name, value, cls in (("patch_heating", patch_heating, PatchHeating),
                             ("flash_temperature", flash_temperature, FlashTemperature)):
        if value is not None and not isinstance(value, cls):
            raise InputError(f"{name}: expected a {cls.__name__} effect, got {value!r}")
        if value is not None or name not in model.effect_names:
            model = model.with_effect(value if value is not None else cls())
    return model


@doi(BURCKHARDT_1993)
def burckhardt(slip, c1: float, c2: float, c3: float):
    r"""Burckhardt's friction-slip law, :math:`\mu(s) = c_1 (1 - e^{-c_2 s}) - c_3 s`.

    (M. Burckhardt, *Fahrwerktechnik: Radschlupf-Regelsysteme*, Vogel 1993; constants per road surface, e.g.
    :data:`BURCKHARDT_DRY_ASPHALT`.) Its peak lies at :math:`s^* = \ln(c_1 c_2 / c_3) / c_2`.

    Parameters
    ----------
    slip : array_like
        Braking slip ratio in [0, 1].
    c1, c2, c3 : float
        The constants (c1 and c3 dimensionless, c2 dimensionless per unit slip).
    """
    s = np.asarray(slip, dtype=float)
    if not np.all(np.isfinite(s)) or np.any((s < 0) | (s > 1)):
        raise InputError("slip: expected braking slip ratios in [0, 1]")
    out = c1 * (1.0 - np.exp(-c2 * s)) - c3 * s
    return out if out.ndim else float(out)


@doi(PACEJKA_2006_TABLE, MAGIC_FORMULA)
def tire_magic_formula(load: float | None = None) -> tuple[float, float, float, float]:
    r"""(B, C, D, E) of the measured tire's longitudinal Magic Formula at ``load``, D as a friction coefficient.

    Pacejka's pure longitudinal slip formulas (*Tyre and Vehicle Dynamics*, 2nd ed., ch. 4; the coefficients of
    :data:`TIRE_205_60R15`, Appendix 3, Table A3.1), :math:`df_z = (F_z - F_{z0})/F_{z0}`:

    .. math:: C = p_{Cx1},\quad \mu_x = D = p_{Dx1} + p_{Dx2}\,df_z,\quad
              E = p_{Ex1} + p_{Ex2}\,df_z + p_{Ex3}\,df_z^2,\quad B = \frac{K_{x\kappa}}{C D F_z}

    with the slip stiffness of :func:`tire_slip_stiffness`. ``persson.slip.magic_formula(s, *tire_magic_formula())``
    is the tire's mu(s) for braking slip s; at the nominal 4 kN it peaks at 1.21 near 14.5 % slip and ends at 0.80
    on the locked wheel.

    Parameters
    ----------
    load : float, optional
        Wheel load F_z, N (default the nominal 4000 N).
    """
    t = TIRE_205_60R15
    Fz0 = t["FNOMIN"]
    dfz = 0.0 if load is None else (positive(load, "load") - Fz0) / Fz0
    C = t["PCX1"]
    D = t["PDX1"] + t["PDX2"] * dfz
    if not D > 0:
        raise InputError(f"load: {load:g} N is far beyond the tire's nominal {Fz0:g} N (the peak mu of its formula "
                         f"would be {D:.3g})")
    E = t["PEX1"] + t["PEX2"] * dfz + t["PEX3"] * dfz * dfz
    return tire_slip_stiffness(load) / (C * D), C, D, E


@doi(PACEJKA_2006_TABLE, MAGIC_FORMULA)
def tire_slip_stiffness(load: float | None = None) -> float:
    r"""Longitudinal slip stiffness of the measured tire per unit load, :math:`K_{x\kappa}/F_z` (the initial slope of
    mu(s)): :math:`(p_{Kx1} + p_{Kx2}\,df_z)\exp(p_{Kx3}\,df_z)` (Pacejka 2006, ch. 4 and Table A3.1); 21.5 at the
    nominal 4 kN, 23.4 at 5.4 kN.

    Parameters
    ----------
    load : float, optional
        Wheel load F_z, N (default the nominal 4000 N).
    """
    t = TIRE_205_60R15
    dfz = 0.0 if load is None else (positive(load, "load") - t["FNOMIN"]) / t["FNOMIN"]
    return (t["PKX1"] + t["PKX2"] * dfz) * math.exp(t["PKX3"] * dfz)


@doi(PACEJKA_BOOK, PACEJKA_2006_TABLE)
def carcass_stiffness(slope: float, tread: Tread, material, *, length: float, pressure: float, speed: float,
                      temperature: float) -> float:
    r"""The carcass and belt's share :math:`k_c` of a tire's brush stiffness, Pa/m, from its measured slip stiffness.

    The brush's initial slope is :math:`C_0 = k l / (2\sigma_0)` (Pacejka, *Tire and Vehicle Dynamics*, ch. 3), so a
    tire whose mu(s) starts with slope ``slope`` has the brush stiffness :math:`k = 2\sigma_0 C_0 / l`; its tread
    (:meth:`Tread.stiffness`, the compound at the test's speed and temperature) and its carcass act in series
    (:meth:`Contact.from_tread`), so

    .. math:: k_c = \left(\frac{l}{2\sigma_0 C_0} - \frac{1}{k_{tread}}\right)^{-1}.

    It assumes the measured tire carries this tread; the carcass then keeps :math:`k_c` at every speed and
    temperature while the tread follows its compound.

    Parameters
    ----------
    slope : float
        Measured initial slope of mu(s), :math:`K_{x\kappa}/F_z` (e.g. :func:`tire_slip_stiffness`).
    tread : Tread
        The tread geometry.
    material : material
        The tread compound.
    length, pressure : float
        Contact length l, m, and mean contact pressure sigma0, Pa.
    speed, temperature : float
        Rolling speed, m/s, and tread temperature, deg C, of the measurement.

    Raises
    ------
    InputError
        The tread alone is not stiffer than the tire (no positive carcass stiffness gives that slope).
    """
    C0 = positive(slope, "slope")
    l = positive(length, "length")
    sigma0 = positive(pressure, "pressure")
    if not isinstance(tread, Tread):
        raise InputError(f"tread: expected a persson.slip.Tread, got {tread!r}")
    k_tire = 2.0 * sigma0 * C0 / l
    k_tread = tread.stiffness(material, speed=speed, temperature=number(temperature, "temperature"),
                              contact_length=l)
    if not k_tread > k_tire:
        raise InputError(f"slope: the tread alone gives the initial slope {k_tread * l / (2 * sigma0):.3g}, not "
                         f"more than the tire's {C0:g}: no carcass compliance can lower it to that slope")
    return 1.0 / (1.0 / k_tire - 1.0 / k_tread)


#: Citations of the reference curves.
REFERENCE_CITATIONS = (MAGIC_FORMULA, PACEJKA_BOOK, BURCKHARDT_1993, PACEJKA_2006_TABLE)


@dataclass(frozen=True)
class RoadCase:
    """A braked tire on a road: the friction model, the tread and the contact patch (see :func:`example_road_case`).

    Attributes
    ----------
    model : persson.Model
        With patch heating and the flash temperature (:func:`road_model`).
    tread : Tread
        The tread geometry; the brush stiffness follows from the compound at each speed and temperature.
    length, width : float
        Contact patch, m.
    pressure : float
        Mean contact pressure, Pa.
    pressure_distribution : str or dict
        As for :class:`Contact`.
    carcass_stiffness : float or None
        Carcass and belt stiffness in series with the tread, Pa/m (:meth:`Contact.from_tread`); None: the tread
        alone.
    """

    model: object
    tread: Tread
    length: float = 0.12
    width: float = 0.15
    pressure: float = 0.3e6
    pressure_distribution: object = "parabolic"
    carcass_stiffness: float | None = None

    def contact(self, speed: float, temperature: float, n_points: int = 401) -> Contact:
        """The contact patch with the tread stiffness of the compound at this rolling speed and temperature, in
        series with the carcass."""
        return Contact.from_tread(self.length, self.width, self.tread, self.model.material, speed=speed,
                                  temperature=temperature, pressure_distribution=self.pressure_distribution,
                                  n_points=n_points, carcass_stiffness=self.carcass_stiffness)

    def curves(self, slip, speeds, temperature: float, *, n_points: int = 401, profiles: bool = False):
        """mu(slip) at each rolling speed (m/s), one :class:`~persson.slip.SlipResult` per speed: the stiffness
        depends on the speed through the loading frequency, so each speed has its own contact."""
        out = []
        for V in np.atleast_1d(np.asarray(speeds, dtype=float)):
            c = self.contact(float(V), temperature, n_points)
            out.append(mu_slip(self.model, slip, float(V), temperature=temperature, pressure=self.pressure,
                               contact=c, profiles=profiles))
        return out


def example_road_case(*, grid=None, patch_heating: PatchHeating | None = None, carcass: bool = True) -> RoadCase:
    r"""A passenger-car tire braking on a dry asphalt: the realistic case of ``docs/slip.md``. **Synthetic inputs.**

    * Road: a self-affine asphalt PSD, H = 0.8, roll-off at 5 mm (:math:`q_0 = 2\pi/5` mm), long-wavelength limit
      :math:`q_L = 2\pi/0.1` m, :math:`h_{rms}` = 0.2 mm, short-distance cut-off :math:`q_1 = 10^6` rad/m: rms
      slope 1.38 (Persson's road calculations take q1 where the rms slope is of order 1).
    * Compound: :func:`materials.example_tire_tread` (a filled passenger-car tread, WLF handing over to Arrhenius
      above T_g + 100 K = 75 C).
    * Friction: hysteresis with the flash temperature riding on the patch heating (:func:`road_model`; asphalt
      effusivity 1500 W s^0.5/(m^2 K)) and the adhesive term with its documented defaults
      (:class:`persson.effects.Adhesion`: 2 MPa peak shear stress in the real contact area).
    * Tire: contact patch 0.12 m x 0.15 m at 0.3 MPa (5.4 kN), parabolic pressure; tread 8 mm deep, blocks 25 mm
      long, land ratio 0.7 (:class:`Tread`: the stiffness from the compound at each speed and temperature) on the
      carcass and belt of the measured 205/60R15 tire of Pacejka's book: :func:`carcass_stiffness` from its slip
      stiffness at 5.4 kN (:func:`tire_slip_stiffness`: 23.4 times the load) at its test speed (60 km/h), taking
      the tread at 20 C (the table gives no temperature): :math:`k_c` = 1.6e8 Pa/m. The initial slope of mu(s)
      is then 18-29 from 40 C to 0 C and 20 to 100 km/h (the tread alone: 43-390).

    Parameters
    ----------
    grid : persson.GridSettings, optional
        Quadrature settings of the engine (default: the engine's).
    patch_heating : PatchHeating, optional
        Replaces the default patch heating (e.g. with coarser friction tables).
    carcass : bool
        With the tire's carcass in series with the tread (default); False: the tread alone, a rigid belt.
    """
    import materials
    import surfaces

    from ..effects.builtin import Adhesion

    road = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3, qL=2 * math.pi / 0.1)
    options = {} if grid is None else {"grid": grid}
    compound = materials.example_tire_tread()
    model = road_model(road, compound, effects=(Adhesion(),), patch_heating=patch_heating, **options)
    tread = Tread(depth=8e-3, block_length=25e-3, land_ratio=0.7)
    length, width, pressure = 0.12, 0.15, 0.3e6
    k_c = None
    if carcass:
        k_c = carcass_stiffness(tire_slip_stiffness(pressure * length * width), tread, compound, length=length,
                                pressure=pressure, speed=TIRE_205_60R15["LONGVL"], temperature=20.0)
    return RoadCase(model=model, tread=tread, length=length, width=width, pressure=pressure, carcass_stiffness=k_c)
