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

The reference curves: Pacejka's Magic Formula for a dry tarmac (:data:`MF_DRY_TARMAC`) and Burckhardt's law for
dry asphalt (:func:`burckhardt`, :data:`BURCKHARDT_DRY_ASPHALT`). :func:`example_road_case` is the documented
realistic case (a passenger-car tire on a dry asphalt) that ``docs/slip.md`` compares with them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from ..effects.builtin import FlashTemperature
from ..errors import InputError
from .contact import Contact, Tread
from .curve import ROAD_SPEED, mu_slip
from .heating import PatchHeating
from .references import BURCKHARDT_1993, CARSLAW_JAEGER, MAGIC_FORMULA, PACEJKA_BOOK, PERSSON_TREAD_2026

__all__ = ["road_model", "with_road_heating", "ROAD_SPEED", "burckhardt", "BURCKHARDT_DRY_ASPHALT",
           "MF_DRY_TARMAC", "RoadCase", "example_road_case"]

#: Burckhardt's constants (c1, c2, c3) for dry asphalt (Burckhardt 1993): peak 1.17 at 17 % slip, locked 0.76.
BURCKHARDT_DRY_ASPHALT = (1.2801, 23.99, 0.52)

#: Magic Formula constants (B, C, D, E) of a dry tarmac (Pacejka 2012, ch. 4): peak 1.00 near 18 % slip,
#: locked about 0.91.
MF_DRY_TARMAC = (10.0, 1.9, 1.0, 0.97)


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


#: Citations of the reference curves.
REFERENCE_CITATIONS = (MAGIC_FORMULA, PACEJKA_BOOK, BURCKHARDT_1993)


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
    """

    model: object
    tread: Tread
    length: float = 0.12
    width: float = 0.15
    pressure: float = 0.3e6
    pressure_distribution: object = "parabolic"

    def contact(self, speed: float, temperature: float, n_points: int = 401) -> Contact:
        """The contact patch with the tread stiffness of the compound at this rolling speed and temperature."""
        return Contact.from_tread(self.length, self.width, self.tread, self.model.material, speed=speed,
                                  temperature=temperature, pressure_distribution=self.pressure_distribution,
                                  n_points=n_points)

    def curves(self, slip, speeds, temperature: float, *, n_points: int = 401, profiles: bool = False):
        """mu(slip) at each rolling speed (m/s), one :class:`~persson.slip.SlipResult` per speed: the stiffness
        depends on the speed through the loading frequency, so each speed has its own contact."""
        out = []
        for V in np.atleast_1d(np.asarray(speeds, dtype=float)):
            c = self.contact(float(V), temperature, n_points)
            out.append(mu_slip(self.model, slip, float(V), temperature=temperature, pressure=self.pressure,
                               contact=c, profiles=profiles))
        return out


def example_road_case(*, grid=None, patch_heating: PatchHeating | None = None) -> RoadCase:
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
      long, land ratio 0.7 (:class:`Tread`: the brush stiffness from the compound, no belt).

    Parameters
    ----------
    grid : persson.GridSettings, optional
        Quadrature settings of the engine (default: the engine's).
    patch_heating : PatchHeating, optional
        Replaces the default patch heating (e.g. with coarser friction tables).
    """
    import materials
    import surfaces

    from ..effects.builtin import Adhesion

    road = surfaces.SelfAffine(hurst=0.8, q0=2 * math.pi / 5e-3, q1=1e6, hrms=0.2e-3, qL=2 * math.pi / 0.1)
    options = {} if grid is None else {"grid": grid}
    model = road_model(road, materials.example_tire_tread(), effects=(Adhesion(),), patch_heating=patch_heating,
                       **options)
    return RoadCase(model=model, tread=Tread(depth=8e-3, block_length=25e-3, land_ratio=0.7))
