"""Validation against measured friction: datasets, comparison, diagnosis of missing effects, reports.

The loop of DESIGN.md: compare the model with measured friction, see where it fails, learn which physical effect
is missing, add it and watch the error fall::

    import validation
    case = validation.load_case("case.toml")                 # model + measurements (+ contact, fit)
    cmp = validation.compare(case.model, case.measurements, case.contact)
    dx = validation.diagnose(case)                           # ranked candidate effects
    imp = validation.improve(case)                           # add the best significant effect, repeat
    validation.write_report([cmp, dx, imp], "report.html")
"""

from .case import Case, case_path, load_case, shipped_cases
from .compare import Comparison, GroupStat, compare
from .diagnose import (SIGNIFICANCE_RULE, Ambiguity, Baseline, Candidate, Diagnosis, Separation, diagnose)
from .errors import InputError, UnitWarning
from .improve import Improvement, Step, improve
from .measurements import Measurements, read_measurements
from .predict import Prediction, predict
from .report import write_report

__all__ = [
    "InputError", "UnitWarning",
    "Measurements", "read_measurements", "Case", "load_case", "shipped_cases", "case_path",
    "Prediction", "predict", "Comparison", "GroupStat", "compare",
    "Diagnosis", "Baseline", "Candidate", "Ambiguity", "Separation", "diagnose", "SIGNIFICANCE_RULE",
    "Improvement", "Step", "improve", "write_report",
]
