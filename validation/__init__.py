"""Validation against measured friction: datasets, comparison, diagnosis of missing effects, reports.

The validation loop: compare the model with measured friction, see where it fails, learn which physical effect
is missing, add it and watch the error fall::

    import validation
    case = validation.load_case("case.toml")                 # model + measurements (+ contact, fit)
    cmp = validation.compare(case.model, case.measurements, case.contact)
    dx = validation.diagnose(case)                           # verdict + ranked candidate effects
    imp = validation.improve(case, diagnosis=dx)             # the set of effects the data support
    imp.selection.best, imp.selection.supported              # best set, equally supported sets
    validation.write_report([cmp, dx, imp], "report.html")
"""

from .band import band_half_width
from .case import Case, case_path, load_case, shipped_cases
from .compare import Comparison, GroupStat, compare
from .diagnose import (SIGNIFICANCE_RULE, Ambiguity, Baseline, Candidate, Diagnosis, Separation, diagnose_single)
from .errors import ChannelWarning, IdentificationWarning, InputError, UnitWarning
from .improve import Improvement, Step, diagnose, improve
from .measurements import Measurements, read_measurements
from .noise import LackOfFit, NoiseEstimate, Pattern, estimate_noise, lack_of_fit, remaining_pattern
from .predict import Prediction, predict
from .refit import Estimate, ParameterCovariance
from .report import write_report
from .select import EffectSet, Selection
from .verdict import VERDICTS, Verdict

__all__ = [
    "InputError", "UnitWarning", "ChannelWarning", "IdentificationWarning",
    "Measurements", "read_measurements", "Case", "load_case", "shipped_cases", "case_path",
    "Prediction", "predict", "Comparison", "GroupStat", "compare",
    "Diagnosis", "Baseline", "Candidate", "Ambiguity", "Separation", "diagnose", "diagnose_single",
    "SIGNIFICANCE_RULE",
    "Verdict", "VERDICTS", "Estimate", "ParameterCovariance", "band_half_width", "NoiseEstimate", "LackOfFit",
    "Pattern", "estimate_noise", "lack_of_fit", "remaining_pattern",
    "Improvement", "Step", "improve", "write_report", "EffectSet", "Selection",
]
