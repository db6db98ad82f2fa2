r"""Friction against slip ratio: a braked rubber wheel on a road or a disk.

The wing reads bottom-up:

* :mod:`~persson.slip.contact`: the contact patch (:class:`Contact`: length, width, pressure distribution, tread
  stiffness) and :mod:`~persson.slip.kinematics`: DRFT-style kinematics (slip ratio, sliding speed);
* :mod:`~persson.slip.brush`: the steady-state brush model (Pacejka) and the two-coefficient brush with Sakai's
  pressure; :mod:`~persson.slip.brush_fit`: the Stribeck brush fitted to a measured curve alone;
* :mod:`~persson.slip.heating` (with :mod:`~persson.slip.heating_tables` and the numba kernels of
  :mod:`~persson.slip.heating_kernels`): the :class:`PatchHeating` effect, temperature and pressure along the patch;
* :mod:`~persson.slip.curve`: :func:`mu_slip` and :func:`predict_slip` from a :class:`persson.Model`;
  :mod:`~persson.slip.fit`: :func:`fit_slip`, contact and effect parameters fitted to measured curves;
* curve laws: :mod:`~persson.slip.magic` (Pacejka's Magic Formula, its fits and identifications),
  :mod:`~persson.slip.speedlaws` (friction against speed: PIARC, Do-Marsac-Mosset, Rado),
  :mod:`~persson.slip.peaks` and :mod:`~persson.slip.fitting` (least squares with covariance);
* :mod:`~persson.slip.plots`: figures.

Every public name is importable from ``persson.slip`` (and, as before, the curve laws from ``persson.tire``).
"""

from .brush import BrushCurve, BrushMap, brush_mu, two_coefficient_map, two_coefficient_mu
from .brush_fit import BrushFit, fit_brush, stribeck_brush_mu
from .contact import CONTACT_PARAMETERS, Contact
from .curve import PatchProfile, SlipResult, mu_slip, predict_slip
from .fit import SlipFit, fit_slip
from .fitting import FitResult
from .heating import PatchHeating, PatchSolution, patch_friction
from .kinematics import Kinematics, drft_from_angular, drft_kinematics, drft_speeds
from .magic import (MagicFormula, MagicFormulaFit, SimpleMagicFormula, fit_magic_formula, magic_formula,
                    magic_formula_from_peak, magic_formula_from_points, magic_formula_peak_B, magic_formula_simple)
from .peaks import peak
from .references import (BLOK_1937, CANUDAS_2003, CARSLAW_JAEGER, DO_2004, JAEGER_1942, MAGIC_FORMULA, PACEJKA_BOOK,
                         PERSSON_TREAD_2026, PIARC_1995, RADO_1994, SAKAI_1981)
from .speedlaws import (SPEED_LAWS, do_marsac_mosset, fit_do_marsac_mosset, fit_piarc, fit_rado, fit_speed_law, piarc,
                        piarc_ifi, rado)

__all__ = [
    # kinematics, contact patch, brush model
    "Contact", "CONTACT_PARAMETERS", "Kinematics", "drft_kinematics", "drft_from_angular", "drft_speeds",
    "brush_mu", "BrushCurve", "two_coefficient_mu", "BrushMap", "two_coefficient_map",
    "stribeck_brush_mu", "fit_brush", "BrushFit",
    # friction against slip from the engine
    "SlipResult", "PatchProfile", "mu_slip", "predict_slip", "fit_slip", "SlipFit",
    "PatchHeating", "PatchSolution", "patch_friction",
    # curve laws
    "magic_formula", "magic_formula_simple", "MagicFormula", "SimpleMagicFormula", "magic_formula_from_points",
    "magic_formula_from_peak", "magic_formula_peak_B", "FitResult", "MagicFormulaFit", "fit_magic_formula", "peak",
    "piarc", "piarc_ifi", "do_marsac_mosset", "rado", "fit_speed_law", "fit_piarc", "fit_do_marsac_mosset",
    "fit_rado", "SPEED_LAWS",
    # citation keys
    "PACEJKA_BOOK", "SAKAI_1981", "CANUDAS_2003", "MAGIC_FORMULA", "PIARC_1995", "DO_2004", "RADO_1994",
    "CARSLAW_JAEGER", "JAEGER_1942", "BLOK_1937", "PERSSON_TREAD_2026",
]
