r"""Friction against slip ratio: a braked rubber wheel on a road or a disk.

The wing reads bottom-up:

* :mod:`~persson.slip.contact`: the contact patch (:class:`Contact`: length, width, pressure distribution, tread
  stiffness) and :mod:`~persson.slip.kinematics`: DRFT-style kinematics (slip ratio, sliding speed);
* :mod:`~persson.slip.brush`: the steady-state brush model (Pacejka) and the two-coefficient brush with Sakai's
  pressure; :mod:`~persson.slip.brush_fit`: the Stribeck brush fitted to a measured curve alone;
  :mod:`~persson.slip.brush_identify`: the two-coefficient brush identified from a Magic Formula;
* :mod:`~persson.slip.heating` (with :mod:`~persson.slip.heating_tables` and the numba kernels of
  :mod:`~persson.slip.heating_kernels` with the named tuples they take, :mod:`~persson.slip.heating_arrays`): the
  :class:`PatchHeating` effect, temperature and pressure along the patch;
* :mod:`~persson.slip.curve`: :func:`mu_slip` and :func:`predict_slip` from a :class:`persson.Model`;
  :mod:`~persson.slip.road`: :func:`road_model`, the model with both kinds of frictional heating for road speeds,
  and the published reference curves (Magic Formula, Burckhardt);
  :mod:`~persson.slip.fit`: :func:`fit_slip`, contact and effect parameters fitted to measured curves;
* curve laws: :mod:`~persson.slip.magic` (Pacejka's Magic Formula, its fits and identifications),
  :mod:`~persson.slip.speedlaws` (friction against speed: PIARC, Do-Marsac-Mosset, Stribeck, Gompertz, La Torre,
  Rado, three zones), :mod:`~persson.slip.wetlaws` (Dijks, the product form: speed, texture depth and BPN),
  :mod:`~persson.slip.stribeck_curve` (friction against eta V / p, lubrication regimes),
  :mod:`~persson.slip.speedlaw_fit` (every law fitted and ranked by AICc or BIC, the engine's wet prediction side by
  side), :mod:`~persson.slip.texture_laws` (the constants from MPD, BPN, water and tread depth),
  :mod:`~persson.slip.wet_prediction` (mu(V) predicted for a new surface), :mod:`~persson.slip.peaks`,
  :mod:`~persson.slip.fitting` and :mod:`~persson.slip.separable` (least squares with covariance);
* :mod:`~persson.slip.plots`: figures.

Every public name is importable from ``persson.slip`` (and, as before, the curve laws from ``persson.tire``).
"""

from .brush import BrushCurve, BrushMap, brush_mu, two_coefficient_map, two_coefficient_mu
from .brush import KINEMATICS, BrushTerms, MapSensitivity, brush_terms
from .brush_identify import BrushIdentification, identify_two_coefficient
from .brush_fit import BrushFit, fit_brush, stribeck_brush_mu
from .contact import CONTACT_PARAMETERS, Contact, Tread
from .curve import PatchProfile, SlipResult, mu_slip, predict_slip
from .fit import SlipFit, fit_slip
from .fitting import FitResult
from .heating import PatchHeating, PatchSolution, patch_friction
from .kinematics import Kinematics, drft_from_angular, drft_kinematics, drft_speeds
from .magic import (PACEJKA_TYPICAL, MagicFormula, MagicFormulaFit, SimpleMagicFormula, fit_magic_formula,
                    magic_formula, magic_formula_from_peak, magic_formula_from_points, magic_formula_peak_B,
                    magic_formula_simple)
from .peaks import peak
from .references import (AKAIKE_1974, BLOK_1937, BURCKHARDT_1993, CANUDAS_2003, CARSLAW_JAEGER, DIJKS_1974, DO_2004,
                         GENT_2012, GOMPERTZ_1825, HURVICH_TSAI_1989, JAEGER_1942, LA_TORRE_2001, LAMPAERT_2002,
                         LEU_HENRY_1978, MAGIC_FORMULA, MOORE_1975, PACEJKA_BOOK, PERSSON_TREAD_2026, PIARC_1995,
                         RADO_1994, SAKAI_1981, SCHWARZ_1978, STRIBECK_1902, TIMOSHENKO_GERE)
from .road import (BURCKHARDT_DRY_ASPHALT, MF_DRY_TARMAC, TIRE_205_60R15, RoadCase, burckhardt, carcass_stiffness,
                   example_road_case, road_model, tire_magic_formula, tire_slip_stiffness, with_road_heating)
from .references import TRAILER_2023
from .speedlaw_fit import (ACCEPTANCE_SSE, SPEED_LAW_NAMES, SpeedLawFit, SpeedLawTable, fit_speed_laws,
                           information_criteria, speed_laws_from_model)
from .speedlaws import (SPEED_LAWS, do_marsac_mosset, fit_do_marsac_mosset, fit_gompertz, fit_la_torre, fit_piarc,
                        fit_rado, fit_speed_law, fit_stribeck, fit_three_zone, gompertz, la_torre, piarc, piarc_ifi,
                        rado, stribeck, three_zone, three_zone_fractions)
from .stribeck_curve import StribeckCurve, fit_stribeck_curve, lubrication_regime, stribeck_parameter
from .texture_laws import (ALPHA_WATER_LAW, BLANK_TIRE_SLIP_LAW, Relation, blank_tire_vs, fit_b_slip, fit_mu0_bpn,
                           fit_vs_mpd, fit_vs_mpd_by_device, fit_water_ratio)
from .wet_prediction import SpeedCurvePrediction, WetRelations, predict_speed_curve
from .wetlaws import DIJKS_TERMS, SurfaceLawFit, dijks, fit_dijks, fit_wet_product, three_zone_mu, wet_product

__all__ = [
    # kinematics, contact patch, brush model
    "Contact", "CONTACT_PARAMETERS", "Tread", "Kinematics", "drft_kinematics", "drft_from_angular", "drft_speeds",
    "brush_mu", "BrushCurve", "two_coefficient_mu", "BrushMap", "two_coefficient_map",
    "stribeck_brush_mu", "fit_brush", "BrushFit",
    # the trailer article's brush: kinematics dx = s x, adhesion/sliding terms, identification from a Magic Formula
    "KINEMATICS", "brush_terms", "BrushTerms", "MapSensitivity", "identify_two_coefficient", "BrushIdentification",
    "TRAILER_2023",
    # friction against slip from the engine
    "SlipResult", "PatchProfile", "mu_slip", "predict_slip", "fit_slip", "SlipFit",
    "PatchHeating", "PatchSolution", "patch_friction", "road_model", "with_road_heating",
    "burckhardt", "BURCKHARDT_DRY_ASPHALT", "MF_DRY_TARMAC", "RoadCase", "example_road_case",
    "TIRE_205_60R15", "tire_magic_formula", "tire_slip_stiffness", "carcass_stiffness",
    # curve laws
    "magic_formula", "magic_formula_simple", "MagicFormula", "SimpleMagicFormula", "magic_formula_from_points",
    "magic_formula_from_peak", "magic_formula_peak_B", "FitResult", "MagicFormulaFit", "fit_magic_formula", "peak",
    "PACEJKA_TYPICAL",
    "piarc", "piarc_ifi", "do_marsac_mosset", "rado", "fit_speed_law", "fit_piarc", "fit_do_marsac_mosset",
    "fit_rado", "SPEED_LAWS",
    # wet-road friction against speed: every law, ranked; texture, water and tread; the Stribeck curve
    "gompertz", "la_torre", "stribeck", "three_zone", "three_zone_fractions", "fit_gompertz", "fit_la_torre",
    "fit_stribeck", "fit_three_zone", "dijks", "fit_dijks", "wet_product", "fit_wet_product", "three_zone_mu",
    "SurfaceLawFit", "DIJKS_TERMS", "fit_speed_laws", "SpeedLawFit", "SpeedLawTable", "information_criteria",
    "speed_laws_from_model", "SPEED_LAW_NAMES", "ACCEPTANCE_SSE", "stribeck_parameter", "lubrication_regime",
    "fit_stribeck_curve", "StribeckCurve", "Relation", "fit_vs_mpd", "fit_vs_mpd_by_device", "fit_b_slip",
    "blank_tire_vs", "fit_water_ratio", "fit_mu0_bpn", "BLANK_TIRE_SLIP_LAW", "ALPHA_WATER_LAW", "WetRelations",
    "predict_speed_curve", "SpeedCurvePrediction",
    # citation keys
    "PACEJKA_BOOK", "SAKAI_1981", "CANUDAS_2003", "MAGIC_FORMULA", "PIARC_1995", "DO_2004", "RADO_1994",
    "CARSLAW_JAEGER", "JAEGER_1942", "BLOK_1937", "PERSSON_TREAD_2026", "DIJKS_1974", "LEU_HENRY_1978",
    "LA_TORRE_2001", "GOMPERTZ_1825", "STRIBECK_1902", "LAMPAERT_2002", "MOORE_1975", "AKAIKE_1974",
    "HURVICH_TSAI_1989", "SCHWARZ_1978",
    "GENT_2012", "TIMOSHENKO_GERE", "BURCKHARDT_1993",
]
