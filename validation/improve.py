"""The improvement loop: add the credible effect the diagnosis names, and stop with the verdict.

Step 0 is the first diagnosis (given, or computed once). While its verdict is ``partly_explained``, the effect it
names -- significant, plausible, refitted jointly with the baseline's parameters -- is added with exactly the
parameters of that diagnosis, and the next diagnosis (of the remaining candidates) starts from them. The loop
stops when the verdict is ``explained`` (that effect is added, and nothing more is called for), ``nothing_missing``
or ``unexplained`` (nothing credible to add), or after ``max_steps`` effects. An effect that is significant only
with implausible parameters is never added.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .compare import Comparison, comparison_from, json_text
from .diagnose import Diagnosis, _unpack, diagnose
from .predict import Prediction

__all__ = ["Improvement", "Step", "improve"]


@dataclass(frozen=True, eq=False)
class Step:
    """One step of the loop.

    Attributes
    ----------
    index : int
        0 for the baseline.
    added : str or None
        The effect added at this step (None for the baseline).
    effects : tuple of str
        Effects of the model after the step.
    parameters : dict
        ``effect -> {parameter: value}`` of every effect in the model (documented parameters), plus
        ``"gamma"``.
    fitted : tuple of str
        Parameters fitted at this step (``"effect.parameter"``).
    rmse : float
    bic : float
    delta_bic : float
        Change of BIC against the previous step (0 for the baseline).
    model : persson.Model
    diagnosis : Diagnosis or None
        The diagnosis of this step's model (None for the last step when the previous verdict was ``explained``:
        nothing more was called for, so it was not diagnosed again).
    predicted : ndarray
        This step's prediction per row.
    contact : persson.slip.Contact or None
    estimates : tuple of validation.refit.Estimate
        The fitted parameters with their uncertainties (from the diagnosis that chose the step).
    lack_of_fit_p : float
        Lack-of-fit p-value of this step's model against the noise.
    """

    index: int
    added: str | None
    effects: tuple
    parameters: dict
    fitted: tuple
    rmse: float
    bic: float
    delta_bic: float
    model: object
    diagnosis: Diagnosis | None
    predicted: np.ndarray | None = None
    contact: object = None
    estimates: tuple = ()
    lack_of_fit_p: float = float("nan")

    def as_dict(self) -> dict:
        return {"step": self.index, "added": self.added, "effects": list(self.effects),
                "parameters": self.parameters, "fitted": list(self.fitted), "rmse": self.rmse, "bic": self.bic,
                "delta_bic": self.delta_bic, "lack_of_fit_p": self.lack_of_fit_p,
                "parameters_std": {e.key: e.std for e in self.estimates},
                "intervals": {e.key: list(e.interval) for e in self.estimates}}


@dataclass(frozen=True, eq=False)
class Improvement:
    """The record of :func:`improve`.

    Attributes
    ----------
    steps : tuple of Step
        The baseline first, then one step per added effect.
    model : persson.Model
        The final model.
    measurements : Measurements
    contact : persson.slip.Contact or None
    noise : float
        Noise level of the last diagnosis (see :attr:`Diagnosis.noise`).
    stopped : str
        Why the loop stopped.
    seconds : float
    name : str
    verdict : str
        ``"nothing_missing"`` (nothing added: the baseline fits the noise), ``"explained"`` (the added effects
        bring the residual to the noise level), ``"partly_explained"`` (effects were added but the misfit is
        not all explained) or ``"unexplained"`` (nothing credible to add to a failing baseline).
    noise_source : str
    """

    steps: tuple
    model: object
    measurements: object
    contact: object
    noise: float
    stopped: str
    seconds: float
    name: str = ""
    verdict: str = ""
    noise_source: str = ""

    @property
    def added(self) -> tuple:
        """Effects added, in order."""
        return tuple(s.added for s in self.steps if s.added)

    @property
    def diagnoses(self) -> tuple:
        return tuple(s.diagnosis for s in self.steps)

    @property
    def rmse(self) -> tuple:
        """RMSE after each step."""
        return tuple(s.rmse for s in self.steps)

    def comparison(self, index: int = -1) -> Comparison:
        """The comparison of step ``index`` (from predictions already computed; no engine calls)."""
        s = self.steps[index]
        pred = Prediction(mu=s.predicted, mu_local=s.predicted)
        return comparison_from(s.model, self.measurements, s.contact or self.contact, pred,
                               name=f"{self.name} step {s.index}" if self.name else f"step {s.index}")

    def table_text(self) -> str:
        lines = [f"verdict: {self.verdict} (noise {self.noise:.3g} from {self.noise_source})",
                 f"{'step':<6}{'added':<20}{'RMSE':>9}{'dBIC':>9}{'LOF p':>9}  effects / fitted parameters"]
        for s in self.steps:
            par = ", ".join(e.describe() for e in s.estimates) or "-"
            lines.append(f"{s.index:<6}{s.added or '(baseline)':<20}{s.rmse:>9.4g}{s.delta_bic:>+9.1f}"
                         f"{s.lack_of_fit_p:>9.2g}  {list(s.effects)} {par}")
        lines.append(f"stopped: {self.stopped}")
        return "\n".join(lines)

    def as_dict(self) -> dict:
        return {"name": self.name, "verdict": self.verdict, "noise": self.noise, "noise_source": self.noise_source,
                "steps": [s.as_dict() for s in self.steps], "stopped": self.stopped, "seconds": self.seconds}

    def to_dict(self) -> dict:
        """Alias of :meth:`as_dict`."""
        return self.as_dict()

    def to_json(self, path=None, *, overwrite: bool = False) -> str:
        """JSON text of :meth:`as_dict`; written atomically to ``path`` when given (an existing file only with
        ``overwrite=True``)."""
        return json_text(self.as_dict(), path, overwrite=overwrite)

    def figures(self) -> dict:
        from . import plots

        return {"steps": plots.plot_steps(self)}


def improve(case_or_model, measurements=None, *, contact=None, candidates=None, fit=None, max_steps: int = 4,
            progress=None, diagnosis: Diagnosis | None = None, **diagnose_options) -> Improvement:
    """Add the credible effect each diagnosis names until the verdict says stop (module docstring).

    Parameters
    ----------
    case_or_model : validation.Case or persson.Model
    measurements : Measurements, optional
        Required with a model.
    contact : persson.slip.Contact, optional
    candidates : sequence of str or Effect, optional
        As for :func:`validation.diagnose` (effects already added are dropped from later rounds).
    fit : sequence of str, optional
        Baseline parameters refitted at every step; the free parameters of each added effect join them.
    max_steps : int
        Largest number of effects added.
    progress : callable, optional
        Called with a one-line message after each diagnosis.
    diagnosis : Diagnosis, optional
        The first diagnosis, when already computed (it must be of this case: same model and measurements); it
        is reused, not recomputed.
    **diagnose_options
        Passed to :func:`validation.diagnose` (``parameters``, ``n_starts``, ``seed``, ``probe``, ...).

    Returns
    -------
    Improvement
    """
    t0 = time.perf_counter()
    name = diagnose_options.pop("name", "")
    model, measurements, contact, fit, name = _unpack(case_or_model, measurements, contact, fit, name)
    fit = list(fit or ())
    cands = None if candidates is None else list(candidates)
    dx = diagnosis
    if dx is not None and dx.measurements is not measurements:
        from .errors import InputError

        raise InputError("diagnosis: it was made for other measurements than the ones given")
    if dx is None:
        dx = diagnose(model, measurements, cands, contact, fit=fit, name=name, **diagnose_options)
    b = dx.baseline
    steps = [Step(index=0, added=None, effects=tuple(b.model.effect_names), parameters=_params(b.model),
                  fitted=tuple(fit), rmse=b.rmse, bic=b.bic, delta_bic=0.0, model=b.model, diagnosis=dx,
                  predicted=b.predicted, contact=b.contact, estimates=b.estimates,
                  lack_of_fit_p=b.lack.p_value)]
    first_verdict = dx.verdict.verdict
    while True:
        v = dx.verdict
        if progress is not None:
            progress(f"step {len(steps) - 1}: RMSE {dx.baseline.rmse:.4g}; verdict {v.verdict}"
                     + (f" ({v.effect})" if v.effect else ""))
        if v.verdict in ("nothing_missing", "unexplained"):
            stopped = {"nothing_missing": "the model is consistent with the noise and no candidate is credible",
                       "unexplained": "no credible candidate is left, but the model still misses the data"}[v.verdict]
            break
        if len(steps) > max_steps:
            stopped = f"max_steps = {max_steps} reached ({v.effect} would be next)"
            break
        best = dx.explaining
        fit = fit + [f"{best.effect}.{p}" for p in best.free]
        steps.append(Step(index=len(steps), added=best.effect, effects=tuple(best.model.effect_names),
                          parameters=_params(best.model), fitted=tuple(fit), rmse=best.rmse, bic=best.bic,
                          delta_bic=best.delta_bic, model=best.model, diagnosis=None, predicted=best.predicted,
                          contact=best.contact, estimates=best.baseline_estimates + best.estimates,
                          lack_of_fit_p=best.lack.p_value))
        if v.verdict == "explained":
            stopped = f"explained: with {best.effect} the residual is at the noise level, without pattern"
            break
        if cands is not None:
            cands = [c for c in cands if (c if isinstance(c, str) else c.name) != best.effect]
        if len(steps) > max_steps:
            stopped = f"max_steps = {max_steps} reached"
            break
        dx = diagnose(best.model, measurements, cands, best.contact or contact, fit=fit, name=name,
                      refit_baseline=False, **diagnose_options)
        steps[-1] = _with_diagnosis(steps[-1], dx)
    final = _final_verdict(first_verdict, dx.verdict.verdict, len(steps) > 1)
    return Improvement(steps=tuple(steps), model=steps[-1].model, measurements=measurements, contact=contact,
                       noise=float(dx.noise), stopped=stopped, seconds=time.perf_counter() - t0, name=name,
                       verdict=final, noise_source=dx.noise_estimate.source)


def _with_diagnosis(step: Step, dx: Diagnosis) -> Step:
    from dataclasses import replace

    return replace(step, diagnosis=dx)


def _final_verdict(first: str, last: str, added: bool) -> str:
    """The loop's verdict: the last diagnosis' verdict on what the added effects left over."""
    if not added:
        return first
    if last in ("explained", "nothing_missing"):
        return "explained"
    return "partly_explained"


def _params(model) -> dict:
    out: dict = {}
    for e in model.effects:
        out[e.name] = {p.name: float(getattr(e, p.name)) for p in e.parameters
                       if isinstance(getattr(e, p.name, None), (int, float, np.integer, np.floating))
                       and not isinstance(getattr(e, p.name), bool)}
    out["gamma"] = float(model.gamma)
    return out
