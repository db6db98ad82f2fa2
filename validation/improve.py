"""The improvement loop: add the best significant effect, refit, repeat; record the error at each step."""

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
    diagnosis : Diagnosis
        The diagnosis run on this step's model (its best significant candidate is the next step).
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
    diagnosis: Diagnosis

    def as_dict(self) -> dict:
        return {"step": self.index, "added": self.added, "effects": list(self.effects),
                "parameters": self.parameters, "fitted": list(self.fitted), "rmse": self.rmse, "bic": self.bic,
                "delta_bic": self.delta_bic}


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
        Noise level of the last diagnosis (rms of mu_std, or the final model's residual standard deviation).
    stopped : str
        Why the loop stopped.
    seconds : float
    name : str
    """

    steps: tuple
    model: object
    measurements: object
    contact: object
    noise: float
    stopped: str
    seconds: float
    name: str = ""

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
        b = s.diagnosis.baseline
        pred = Prediction(mu=b.predicted, mu_local=b.predicted)
        return comparison_from(s.model, self.measurements, self.contact, pred,
                               name=f"{self.name} step {s.index}" if self.name else f"step {s.index}")

    def table_text(self) -> str:
        lines = [f"{'step':<6}{'added':<20}{'RMSE':>9}{'dBIC':>9}  effects / parameters"]
        for s in self.steps:
            par = "; ".join(f"{e}: " + ", ".join(f"{k}={v:.4g}" for k, v in p.items())
                            for e, p in s.parameters.items() if isinstance(p, dict) and p)
            lines.append(f"{s.index:<6}{s.added or '(baseline)':<20}{s.rmse:>9.4g}{s.delta_bic:>+9.1f}  "
                         f"{list(s.effects)} {par}")
        lines.append(f"stopped: {self.stopped}")
        return "\n".join(lines)

    def as_dict(self) -> dict:
        return {"name": self.name, "steps": [s.as_dict() for s in self.steps], "noise": self.noise,
                "stopped": self.stopped, "seconds": self.seconds}

    def to_json(self, path=None) -> str:
        return json_text(self.as_dict(), path)

    def figures(self) -> dict:
        from . import plots

        return {"steps": plots.plot_steps(self)}


def improve(case_or_model, measurements=None, *, contact=None, candidates=None, fit=None, max_steps: int = 4,
            progress=None, **diagnose_options) -> Improvement:
    """Add the best significant effect with its refitted parameters; repeat until none is significant.

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
    steps = []
    prev_bic = None
    added = None
    stopped = ""
    for i in range(max_steps + 1):
        dx = diagnose(model, measurements, cands, contact, fit=fit, name=name, **diagnose_options)
        b = dx.baseline
        model = b.model
        steps.append(Step(index=i, added=added, effects=tuple(model.effect_names), parameters=_params(model),
                          fitted=tuple(fit), rmse=b.rmse, bic=b.bic,
                          delta_bic=0.0 if prev_bic is None else b.bic - prev_bic, model=model, diagnosis=dx))
        if progress is not None:
            best = dx.best
            progress(f"step {i}: RMSE {b.rmse:.4g}" + (f"; next: {best.effect} (delta BIC {best.delta_bic:+.1f})"
                                                       if best else "; no significant candidate"))
        prev_bic = b.bic
        best = dx.best
        if best is None:
            stopped = "no candidate is significant"
            break
        if i == max_steps:
            stopped = f"max_steps = {max_steps} reached ({best.effect} still significant)"
            break
        model = best.model
        added = best.effect
        fit = fit + [f"{best.effect}.{p}" for p in best.free]
        if cands is not None:
            cands = [c for c in cands if (c if isinstance(c, str) else c.name) != best.effect]
    last = steps[-1].diagnosis
    noise = last.noise
    return Improvement(steps=tuple(steps), model=steps[-1].model, measurements=measurements, contact=contact,
                       noise=float(noise), stopped=stopped, seconds=time.perf_counter() - t0, name=name)


def _params(model) -> dict:
    out: dict = {}
    for e in model.effects:
        out[e.name] = {p.name: float(getattr(e, p.name)) for p in e.parameters
                       if isinstance(getattr(e, p.name, None), (int, float, np.integer, np.floating))
                       and not isinstance(getattr(e, p.name), bool)}
    out["gamma"] = float(model.gamma)
    return out
