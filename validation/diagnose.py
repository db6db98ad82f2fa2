r"""Diagnosis of the physical effect missing from a model: signatures, score tests, refits, BIC, ranking.

For a baseline model and measurements (``y``, weights :math:`w_i = 1/\sigma_i` from ``mu_std``, else 1):

1. **Baseline.** The baseline's fitted parameters (``fit``, e.g. ``["adhesion.tau_f0"]``; default none) are
   refitted to the data; :math:`f_0` is its prediction, :math:`r = y - f_0` the residual and :math:`J_b` the
   finite-difference Jacobian of the weighted prediction with respect to the fitted parameters.
2. **Signature** of each candidate effect (every registered effect not in the model, including user-defined
   ones, or the ``candidates`` given): :math:`d = f(\text{baseline} + \text{effect at its given/default
   parameters}) - f_0`.
3. **Score test.** With :math:`Q` an orthonormal basis of :math:`W J_b` (QR), the projected signature is
   :math:`d_\perp = (I - QQ^T) W d`; the score statistic for an amplitude along :math:`d_\perp` is
   :math:`z = d_\perp^T W r / (\hat\sigma \lVert d_\perp\rVert)` (N(0, 1) under the baseline), with
   :math:`\hat\sigma = 1` when ``mu_std`` is given, else :math:`\sqrt{RSS_0/(n - k_b)}`. ``cosine`` is the
   correlation of :math:`d_\perp` with the weighted residual.
4. **Refit.** Stage A: the candidate's free parameters (see :func:`validation.fitting.free_parameters`) with the
   baseline's at their fitted values -- one parameter by a grid scan and bounded Brent minimisation, several by
   bounded least squares (log space for ``log_scale`` parameters) from the given values and the best point of a
   small seeded screening design. Stage B: a joint least-squares polish of the candidate's and the baseline's
   fitted parameters.
5. **Information criterion.** Gaussian likelihood: with ``mu_std``, :math:`BIC = \chi^2 + k \ln n`; without,
   :math:`BIC = n \ln(RSS/n) + k \ln n` (sigma profiled out). :math:`k` counts the fitted parameters that
   change the prediction; :math:`\Delta BIC = BIC_{cand} - BIC_{base}`.
6. **Verdict.** A candidate is *significant* when :math:`\Delta BIC < -10` ("very strong" evidence on the
   Kass & Raftery scale) **and** the likelihood-ratio test rejects the baseline at 1 %: with ``mu_std``,
   :math:`\chi^2_0 - \chi^2_1 \sim \chi^2(k_c)`; without, the F test
   :math:`F = \frac{(RSS_0 - RSS_1)/k_c}{RSS_1/(n - k_b - k_c)}` (:math:`k_c \ge 1` the candidate's parameters).
   The test treats the candidate as nesting the baseline, which holds for effects that vanish at some parameter
   value and approximately otherwise; the BIC criterion does not need nesting.
7. **Ranking** by :math:`\Delta BIC` (best first; candidates without a signature have 0, failed ones come last).
8. **Ambiguity.** Candidates whose projected signatures -- at the given parameters, or the refitted changes
   :math:`f_{refit} - f_0` -- have :math:`|\cos| > 0.95` form a cluster. For each pair (cluster head vs other)
   both refitted models are evaluated on a probe grid of conditions (sliding speeds one decade beyond the data,
   the measured temperatures and 20 K beyond, the measured pressures and a factor 2 beyond, slip ratios 0.02-0.3
   when a contact is given) and the condition with the largest :math:`|\Delta\mu|` is reported as the
   measurement that would separate them (and the largest one inside the measured ranges).
9. **Explanation**: where the residual is systematic (groups by speed decade, temperature, pressure, slip range,
   wet/dry with :math:`|z| \ge 3`; rank correlations with speed, temperature, pressure, slip) and how the top
   effect's refitted change follows it.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass

import numpy as np
from scipy import stats

from .compare import group_labels, json_text
from .errors import InputError
from .fitting import Fitter, FreeParameter, ParameterSpace, free_parameters, halton
from .measurements import Measurements
from .predict import Predictor, dry_model, wet_model

__all__ = ["Diagnosis", "Baseline", "Candidate", "Ambiguity", "Separation", "diagnose", "SIGNIFICANCE_RULE",
           "DELTA_BIC_THRESHOLD", "P_THRESHOLD", "COSINE_THRESHOLD"]

DELTA_BIC_THRESHOLD = -10.0
P_THRESHOLD = 0.01
COSINE_THRESHOLD = 0.95
SIGNIFICANCE_RULE = (f"significant when delta_BIC < {DELTA_BIC_THRESHOLD:g} and the likelihood-ratio test "
                     f"(chi2 with mu_std, else F) gives p < {P_THRESHOLD:g}")


# ==========================================================================================================
@dataclass(frozen=True, eq=False)
class Baseline:
    """The baseline model after refitting its fitted parameters.

    Attributes
    ----------
    model : persson.Model
    effects : tuple of str
    fitted : dict
        Refitted baseline parameters, ``"effect.parameter" -> value``.
    predicted, residual : ndarray
    rmse : float
        Root-mean-square residual (unweighted).
    rss : float
        Weighted residual sum of squares (chi2 with mu_std).
    bic : float
    n_params : int
        Fitted parameters counted in the BIC.
    sigma : float
        Residual standard deviation sqrt(RSS/(n - k)) of the baseline (on the mu scale; with mu_std, the rms of
        mu_std times sqrt(chi2/(n - k))).
    rmse_given : float
        RMSE of the model with the parameter values as given (before the refit).
    """

    model: object
    effects: tuple
    fitted: dict
    predicted: np.ndarray
    residual: np.ndarray
    rmse: float
    rss: float
    bic: float
    n_params: int
    sigma: float
    rmse_given: float


@dataclass(frozen=True, eq=False)
class Candidate:
    """One candidate effect, refitted.

    Attributes
    ----------
    effect : str
        Effect name.
    instance : persson.effects.Effect or None
        The effect with its refitted parameters.
    model : persson.Model or None
        Baseline + effect, everything refitted.
    parameters : dict
        The effect's documented parameters after the refit.
    free : tuple of str
        Parameters refitted (others held at their given values).
    baseline_parameters : dict
        The baseline's fitted parameters re-fitted jointly.
    rmse, rss, bic, delta_bic, p_value : float
    test : str
        ``"F"`` or ``"chi2"``.
    score_z, score_p : float
        Score test of the residual along the projected signature (two-sided p).
    cosine : float
        Correlation of the projected signature with the weighted residual.
    explained : float
        Fraction of the baseline's (weighted) residual sum of squares removed by the refit.
    significant : bool
    status : str
        ``"ok"``, ``"no signature"`` (switching it on changes no prediction for these rows) or ``"failed: ..."``.
    signature : ndarray or None
        f(effect at given parameters) - f0 per row.
    change : ndarray or None
        f(refitted) - f0 per row.
    predicted : ndarray or None
    n_params : int
        Candidate parameters counted in the BIC (those that change the prediction).
    n_evals : int
        Model evaluations spent on this candidate.
    notes : tuple of str
    """

    effect: str
    instance: object
    model: object
    parameters: dict
    free: tuple
    baseline_parameters: dict
    rmse: float
    rss: float
    bic: float
    delta_bic: float
    p_value: float
    test: str
    score_z: float
    score_p: float
    cosine: float
    explained: float
    significant: bool
    status: str
    signature: np.ndarray | None = None
    change: np.ndarray | None = None
    predicted: np.ndarray | None = None
    n_params: int = 0
    n_evals: int = 0
    notes: tuple = ()

    def as_dict(self) -> dict:
        return {"effect": self.effect, "rmse": self.rmse, "delta_bic": self.delta_bic,
                "significant": bool(self.significant), "parameters": dict(self.parameters),
                "bic": self.bic, "p_value": self.p_value, "test": self.test, "score_z": self.score_z,
                "score_p": self.score_p, "cosine": self.cosine, "explained": self.explained,
                "free": list(self.free), "baseline_parameters": dict(self.baseline_parameters),
                "n_params": self.n_params, "status": self.status, "notes": list(self.notes)}


@dataclass(frozen=True)
class Separation:
    """The condition where two refitted candidate models differ most.

    Attributes
    ----------
    effects : (str, str)
    speed : float
        Rolling speed V, m/s (the sliding speed is slip * speed).
    slip : float
    temperature : float
    pressure : float
    wet : bool
    mu : (float, float)
        Predictions of the two models there.
    difference : float
        mu[0] - mu[1].
    in_range : bool
        Whether the condition lies inside the measured ranges.
    """

    effects: tuple
    speed: float
    slip: float
    temperature: float
    pressure: float
    wet: bool
    mu: tuple
    difference: float
    in_range: bool

    def describe(self) -> str:
        vs = self.speed * self.slip
        where = (f"sliding speed {vs:.3g} m/s" + (f" (slip {self.slip:g} at V = {self.speed:.3g} m/s)"
                                                  if self.slip < 1 else "")
                 + f", {self.temperature:g} C, {self.pressure / 1e6:g} MPa" + (", wet" if self.wet else ""))
        return (f"{where}: {self.effects[0]} predicts {self.mu[0]:.3f}, {self.effects[1]} {self.mu[1]:.3f} "
                f"(difference {self.difference:+.3f})")

    def as_dict(self) -> dict:
        return {"effects": list(self.effects), "speed_m_s": self.speed, "slip": self.slip,
                "sliding_speed_m_s": self.speed * self.slip, "T_C": self.temperature,
                "pressure_Pa": self.pressure, "wet": self.wet, "mu": list(self.mu), "difference": self.difference,
                "in_measured_range": self.in_range}


@dataclass(frozen=True)
class Ambiguity:
    """Candidates with near-parallel signatures, and where to measure to tell them apart.

    Attributes
    ----------
    effects : tuple of str
        Best-ranked first.
    cosines : dict
        ``"a|b" -> max(|cos| of projected signatures, |cos| of projected refitted changes)``.
    separations : tuple of Separation
        For the head and each other member: the largest difference on the probe grid.
    separations_in_range : tuple of Separation
        The same restricted to the measured ranges.
    """

    effects: tuple
    cosines: dict
    separations: tuple = ()
    separations_in_range: tuple = ()

    def as_dict(self) -> dict:
        return {"effects": list(self.effects), "cosines": dict(self.cosines),
                "separations": [s.as_dict() for s in self.separations],
                "separations_in_measured_range": [s.as_dict() for s in self.separations_in_range]}


@dataclass(frozen=True, eq=False)
class Diagnosis:
    """Ranked candidate effects for a baseline and measurements.

    Attributes
    ----------
    measurements : Measurements
    contact : persson.slip.Contact or None
    baseline : Baseline
    candidates : tuple of Candidate
        Best first (by delta_BIC).
    clusters : tuple of Ambiguity
    explanation : str
        Plain-language failure pattern and why the top effect fits it.
    rule : str
        The significance rule.
    sigma_known : bool
        Whether the likelihood uses mu_std.
    noise : float
        Noise level: the rms of mu_std; without mu_std the residual standard deviation of the best significant
        candidate (of the baseline when none is significant).
    n_evaluations : int
        Model evaluations (each one prediction of every row).
    seconds : float
        Wall time.
    name : str
    """

    measurements: Measurements
    contact: object
    baseline: Baseline
    candidates: tuple
    clusters: tuple
    explanation: str
    rule: str
    sigma_known: bool
    noise: float
    n_evaluations: int
    seconds: float
    name: str = ""

    @property
    def top(self) -> Candidate | None:
        """The best-ranked candidate (None when there are none)."""
        return self.candidates[0] if self.candidates else None

    @property
    def significant(self) -> tuple:
        """The significant candidates, best first."""
        return tuple(c for c in self.candidates if c.significant)

    @property
    def best(self) -> Candidate | None:
        """The best significant candidate (None when no candidate is significant)."""
        s = self.significant
        return s[0] if s else None

    def candidate(self, name: str) -> Candidate:
        for c in self.candidates:
            if c.effect == name:
                return c
        raise InputError(f"no candidate named {name!r}; candidates: {[c.effect for c in self.candidates]}")

    def as_dict(self) -> dict:
        """``{"baseline": {...}, "candidates": [...]}``, candidates best first (the ``--json`` layout).

        Exactly two top-level keys. ``baseline`` has ``rmse`` and ``effects`` plus the BIC, the refitted
        parameters, the noise level, the significance rule, the explanation and the cost; every candidate has
        ``effect``, ``rmse``, ``delta_bic``, ``significant``, ``parameters`` plus the test statistics and, for
        members of an ambiguity cluster, ``ambiguity`` (the cluster, its cosines and the separating conditions).
        """
        b = self.baseline
        amb = {}
        for cl in self.clusters:
            for e in cl.effects:
                amb[e] = cl.as_dict()
        cands = []
        for c in self.candidates:
            d = c.as_dict()
            if c.effect in amb:
                d["ambiguity"] = amb[c.effect]
            cands.append(d)
        return {
            "baseline": {"rmse": b.rmse, "effects": list(b.effects), "bic": b.bic, "rss": b.rss,
                         "fitted": dict(b.fitted), "n_params": b.n_params, "sigma": b.sigma,
                         "rmse_given": b.rmse_given, "n": self.measurements.n, "noise": self.noise,
                         "sigma_known": self.sigma_known, "rule": self.rule, "explanation": self.explanation,
                         "name": self.name, "n_evaluations": self.n_evaluations, "seconds": self.seconds},
            "candidates": cands,
        }

    def to_json(self, path=None) -> str:
        """JSON text of :meth:`as_dict`; written atomically to ``path`` when given."""
        return json_text(self.as_dict(), path)

    def table_text(self) -> str:
        """The ranking as aligned plain text."""
        lines = [f"baseline {list(self.baseline.effects) or ['(hysteresis only)']}: RMSE {self.baseline.rmse:.4g}"
                 + (f", fitted {_fmt_params(self.baseline.fitted)}" if self.baseline.fitted else ""),
                 f"{'rank':<5}{'effect':<20}{'RMSE':>9}{'dBIC':>10}{'p':>10}{'score z':>9}  {'sig':<4} parameters"]
        for i, c in enumerate(self.candidates, 1):
            if c.status != "ok":
                lines.append(f"{i:<5}{c.effect:<20}{'-':>9}{'-':>10}{'-':>10}{'-':>9}  {'no':<4} ({c.status})")
                continue
            lines.append(f"{i:<5}{c.effect:<20}{c.rmse:>9.4g}{c.delta_bic:>+10.1f}{c.p_value:>10.2g}"
                         f"{c.score_z:>+9.1f}  {'YES' if c.significant else 'no':<4} {_fmt_params(c.parameters)}")
        return "\n".join(lines)

    def summary(self) -> str:
        return self.table_text() + "\n\n" + self.explanation

    def figures(self) -> dict:
        from . import plots

        return {"signatures": plots.plot_signatures(self)}


# ==========================================================================================================
def diagnose(model, measurements: Measurements | None = None, candidates=None, contact=None, *, fit=None,
             parameters: dict | None = None, n_starts: int = 2, seed: int = 0, probe: bool = True,
             name: str = "", max_evals: int | None = None) -> Diagnosis:
    """Rank the effects that could be missing from ``model`` (see the module docstring for the method).

    Parameters
    ----------
    model : persson.Model or validation.Case
        The baseline. A :class:`~validation.Case` supplies the measurements, contact, ``fit`` and name.
    measurements : Measurements
    candidates : sequence of str or Effect, optional
        Effect names or instances (instances set the starting / signature parameter values). Default: every
        registered effect (:func:`persson.effects.available`, including user-defined ones) not in the model.
    contact : persson.slip.Contact, optional
        Needed when rows have slip < 1 (default: ``measurements.contact``, set by :func:`validation.load_case`).
    fit : sequence of str, optional
        Baseline parameters refitted with every candidate (``"effect.parameter"`` or ``"gamma"``).
    parameters : dict, optional
        ``effect name -> list of parameter names`` to refit, overriding the default rule of
        :func:`validation.fitting.free_parameters`.
    n_starts : int
        Least-squares starts per candidate (the best points of the screening design).
    seed : int
        Seed of the screening design.
    probe : bool
        Evaluate the probe grid for ambiguity clusters.
    name : str
    max_evals : int, optional
        Budget of model evaluations per candidate and stage (default 32 for one parameter, 16 + 14 k for k >= 2;
        10 + 5 (k + k_b) for the joint polish with the baseline's k_b fitted parameters).

    Returns
    -------
    Diagnosis
    """
    t_start = time.perf_counter()
    model, measurements, contact, fit, name = _unpack(model, measurements, contact, fit, name)
    from persson.effects import Effect, available

    fit_names = _fit_names(fit, model)
    predictor = Predictor(measurements, contact)
    y = measurements.mu
    n = measurements.n
    sigma_known = measurements.mu_std is not None
    w = 1.0 / measurements.mu_std if sigma_known else np.ones(n)
    parameters = dict(parameters or {})

    # ---- 1. baseline ------------------------------------------------------------------------------------
    base_space = ParameterSpace(_baseline_params(model, fit_names))
    kb = len(base_space)
    f_given = predictor.predict(model).mu
    n_eval = 1
    if kb:
        fitter = Fitter(predictor, y, w, model, base_space, max_evals=40 + 30 * kb)
        u0 = base_space.u_of(model)
        res = fitter.run([u0])
        n_eval += fitter.n_evals
        model_b, f0, ub = res.model, res.mu, res.u
    else:
        model_b, f0, ub = model, f_given, np.zeros(0)
    r0 = y - f0
    rss0 = float(np.sum((r0 * w) ** 2))
    kb_eff = kb
    Q = np.zeros((n, 0))
    if kb:
        J = _jacobian(predictor, model, base_space, ub, f0) * w[:, None]
        n_eval += kb
        norms = np.linalg.norm(J, axis=0)
        keep = norms > 1e-10 * max(float(norms.max()), 1e-300)
        kb_eff = int(keep.sum())
        if kb_eff:
            Q, _ = np.linalg.qr(J[:, keep])
    bic0 = _bic(rss0, n, kb_eff, sigma_known)
    sigma_hat = math.sqrt(rss0 / max(n - kb_eff, 1))   # on the weighted scale (1 = the mu_std) with mu_std
    sigma_mu = sigma_hat * float(np.sqrt(np.mean(measurements.mu_std ** 2))) if sigma_known else sigma_hat
    baseline = Baseline(model=model_b, effects=tuple(model_b.effect_names),
                        fitted=base_space.values(model_b) if kb else {}, predicted=f0, residual=r0,
                        rmse=float(np.sqrt(np.mean(r0 ** 2))), rss=rss0, bic=bic0, n_params=kb_eff,
                        sigma=sigma_mu, rmse_given=float(np.sqrt(np.mean((y - f_given) ** 2))))
    rw = r0 * w
    score_sigma = 1.0 if sigma_known else sigma_hat

    # ---- 2-6. candidates ----------------------------------------------------------------------------------
    cand_effects = _candidates(candidates, model, available, Effect)
    results = []
    for eff in cand_effects:
        c, used = _evaluate_candidate(eff, model_b, base_space, ub, predictor, y, w, f0, rw, rss0, bic0, Q,
                                      score_sigma, kb_eff, sigma_known, parameters.get(eff.name), n_starts,
                                      seed, max_evals)
        n_eval += used
        results.append(c)
    results.sort(key=lambda c: (c.status.startswith("failed"), c.delta_bic if math.isfinite(c.delta_bic) else math.inf))

    # ---- 8. ambiguity ---------------------------------------------------------------------------------------
    clusters = _clusters(results, Q, w)
    if probe and clusters:
        clusters, used = _separate(clusters, results, measurements, contact, predictor)
        n_eval += used
    best = next((c for c in results if c.significant), None)
    if sigma_known:
        noise = float(np.sqrt(np.mean(measurements.mu_std ** 2)))
    elif best is not None:
        noise = math.sqrt(best.rss / max(n - kb_eff - best.n_params, 1))
    else:
        noise = sigma_hat
    dx_partial = dict(baseline=baseline, candidates=tuple(results), clusters=tuple(clusters))
    explanation = _explain(measurements, dx_partial, noise, sigma_known)
    return Diagnosis(measurements=measurements, contact=contact, baseline=baseline, candidates=tuple(results),
                     clusters=tuple(clusters), explanation=explanation, rule=SIGNIFICANCE_RULE,
                     sigma_known=sigma_known, noise=noise, n_evaluations=n_eval,
                     seconds=time.perf_counter() - t_start, name=name)


# ==========================================================================================================
def _unpack(model, measurements, contact, fit, name):
    from .case import Case

    if isinstance(model, Case):
        case = model
        model = case.model
        measurements = case.measurements if measurements is None else measurements
        contact = case.contact if contact is None else contact
        fit = case.fit if fit is None else fit
        name = name or case.name
    if measurements is None:
        raise InputError("measurements: give the measurements (validation.read_measurements) or a Case")
    if not isinstance(measurements, Measurements):
        raise InputError(f"measurements: expected validation.Measurements, got {type(measurements).__name__}")
    if not hasattr(model, "effects") or not hasattr(model, "friction"):
        raise InputError(f"model: expected a persson.Model, got {type(model).__name__}")
    if contact is None:
        contact = measurements.contact
    return model, measurements, contact, tuple(fit or ()), name


def _fit_names(fit, model) -> tuple:
    from .case import parse_fit_names

    return parse_fit_names(list(fit), model, "fit")


def _baseline_params(model, fit_names) -> list[FreeParameter]:
    out = []
    for key in fit_names:
        if key == "gamma":
            out.append(FreeParameter(effect="", name="gamma", lo=0.0, hi=1.0, log=False, unit="1"))
            continue
        eff, _, par = key.partition(".")
        out.extend(free_parameters(model.effect(eff), names=[par]))
    return out


def _candidates(candidates, model, available, Effect) -> list:
    present = set(model.effect_names)
    out = []
    if candidates is None:
        for nm, cls in available().items():
            if nm in present:
                continue
            try:
                out.append(cls())
            except Exception as exc:  # noqa: BLE001
                out.append(_Broken(nm, f"cannot build {cls.__name__}() with default parameters: {exc}"))
        return out
    if isinstance(candidates, (str, Effect)):
        candidates = [candidates]
    seen = set()
    for c in candidates:
        if isinstance(c, str):
            from persson.effects import effect_class

            try:
                cls = effect_class(c)
            except ValueError as exc:
                raise InputError(f"candidates: {exc}") from None
            try:
                inst = cls()
            except Exception as exc:  # noqa: BLE001
                inst = _Broken(c, f"cannot build {cls.__name__}() with default parameters: {exc}")
        elif isinstance(c, Effect):
            inst = c
        elif isinstance(c, type) and issubclass(c, Effect):
            inst = c()
        else:
            raise InputError(f"candidates: expected effect names or persson.effects.Effect instances, got {c!r}")
        if inst.name in present:
            raise InputError(f"candidates: {inst.name!r} is already in the model (effects {sorted(present)})")
        if inst.name in seen:
            raise InputError(f"candidates: {inst.name!r} given twice")
        seen.add(inst.name)
        out.append(inst)
    return out


@dataclass(frozen=True)
class _Broken:
    name: str
    error: str


def _failed(name: str, msg: str, bic0: float, evals: int = 0) -> Candidate:
    return Candidate(effect=name, instance=None, model=None, parameters={}, free=(), baseline_parameters={},
                     rmse=math.nan, rss=math.nan, bic=math.nan, delta_bic=math.inf, p_value=1.0, test="-",
                     score_z=0.0, score_p=1.0, cosine=0.0, explained=0.0, significant=False,
                     status=f"failed: {msg}", n_evals=evals)


def _evaluate_candidate(eff, model_b, base_space, ub, predictor, y, w, f0, rw, rss0, bic0, Q, score_sigma, kb_eff,
                        sigma_known, names, n_starts, seed, max_evals):
    """Signature, score test, two-stage refit and statistics of one candidate; returns (Candidate, evals)."""
    if isinstance(eff, _Broken):
        return _failed(eff.name, eff.error, bic0), 0
    name = eff.name
    n = y.size
    scale = max(float(np.max(np.abs(y))), 1e-12)
    tiny = 1e-9 * scale
    try:
        model_c = model_b.with_effect(eff)
        cand = free_parameters(eff, names=names)
    except Exception as exc:  # noqa: BLE001
        return _failed(name, str(exc), bic0), 0
    kb = len(base_space)
    evals = 0
    notes: dict[str, None] = {}

    # --- signature at the given parameters (baseline parameters at their fitted values)
    space_c = ParameterSpace(cand)
    fit_a = Fitter(predictor, y, w, model_c, space_c, max_evals=max_evals or _budget(len(cand)))
    u_c0 = space_c.u_of(model_c)
    f_sig = fit_a.mu(u_c0)
    if f_sig is None:
        evals += fit_a.n_evals
        return _failed(name, "; ".join(list(fit_a.errors)[:2]) or "evaluation failed", bic0, evals), evals
    d = f_sig - f0
    if np.max(np.abs(d)) <= tiny and names is None:
        released = free_parameters(eff, release=True)
        if len(released) > len(cand):
            evals += fit_a.n_evals
            cand = released
            space_c = ParameterSpace(cand)
            fit_a = Fitter(predictor, y, w, model_c, space_c, max_evals=max_evals or _budget(len(cand)))
            u_c0 = space_c.u_of(model_c)
            fit_a.mu(u_c0)
            notes["no signature at the given values: parameters on their bounds released"] = None
    # --- score test on the projected signature
    dw = d * w
    dperp = dw - Q @ (Q.T @ dw) if Q.shape[1] else dw
    nd = float(np.linalg.norm(dperp))
    nr = float(np.linalg.norm(rw))
    if nd > 1e-12 * max(scale, 1.0):
        z = float(dperp @ rw) / (score_sigma * nd)
        cos = float(dperp @ rw) / (nd * nr) if nr > 0 else 0.0
    else:
        z, cos = 0.0, 0.0
    score_p = float(2 * stats.norm.sf(abs(z)))

    # --- stage A: the candidate's parameters, baseline parameters held at their fitted values
    kc = len(cand)
    res = None
    if kc:
        # a few points first: an effect with no signature anywhere is recognised cheaply
        probe_pts = list(halton(kc, 2, seed=seed + 1))
        fit_a.screen(probe_pts)
        if fit_a.max_change(f0) <= tiny:
            evals += fit_a.n_evals
            return _no_signature(name, model_c, cand, d, f0, y, w, bic0, sigma_known, evals), evals
        try:
            if kc == 1:
                res = fit_a.scan_1d(float(u_c0[0]))
            else:
                pts = list(halton(kc, min(4 * kc + 2, 16), seed=seed))
                screened = fit_a.screen(pts)
                if not any(math.isfinite(c) for c, _ in screened) and not math.isfinite(fit_a.chi2(u_c0)):
                    evals += fit_a.n_evals
                    return _failed(name, "; ".join(list(fit_a.errors)[:2]) or "no valid starting point", bic0,
                                   evals), evals
                # the given values (physically informed) and the best distinct screened points
                starts = [np.asarray(u_c0, dtype=float)] if math.isfinite(fit_a.chi2(u_c0)) else []
                for c, p in screened:
                    if len(starts) >= max(2, n_starts):
                        break
                    if math.isfinite(c) and all(np.max(np.abs(p - q)) > 0.05 for q in starts):
                        starts.append(p)
                res = fit_a.run(starts)
        except InputError as exc:
            evals += fit_a.n_evals
            return _failed(name, str(exc), bic0, evals), evals
        notes.update(dict.fromkeys(res.notes))
        model_c = res.model
        u_c = res.u
    else:
        if np.max(np.abs(d)) <= tiny:
            evals += fit_a.n_evals
            return _no_signature(name, model_c, cand, d, f0, y, w, bic0, sigma_known, evals), evals
        u_c = np.zeros(0)
    evals += fit_a.n_evals
    errors = dict(fit_a.errors)

    # --- stage B: joint polish with the baseline's fitted parameters
    if kb:
        space = base_space + space_c
        fit_b = Fitter(predictor, y, w, model_c, space, max_evals=max_evals or (10 + 5 * (kb + kc)))
        try:
            res_b = fit_b.run([np.concatenate([ub, u_c])], max_nfev=6)
        except InputError as exc:
            evals += fit_b.n_evals
            return _failed(name, str(exc), bic0, evals), evals
        evals += fit_b.n_evals
        errors.update(fit_b.errors)
        notes.update(dict.fromkeys(res_b.notes))
        res = res_b
        jac_c = None if res_b.jac is None else res_b.jac[:, kb:]
    else:
        jac_c = None if res is None or res.jac is None else res.jac
    if res is None:  # nothing fitted: the effect at its given values
        f1 = f_sig
        final_model = model_c
    else:
        f1 = res.mu
        final_model = res.model
    r1 = y - f1
    rss1 = float(np.sum((r1 * w) ** 2))
    change = f1 - f0
    k_eff_c = kc
    if jac_c is not None and kc:
        norms = np.linalg.norm(jac_c, axis=0)
        k_eff_c = int(np.sum(norms > 1e-8 * max(float(norms.max()), 1e-300))) or kc
    k1 = kb_eff + k_eff_c
    bic1 = _bic(rss1, n, k1, sigma_known)
    dfc = max(k_eff_c, 1)
    test = "chi2" if sigma_known else "F"
    if rss1 >= rss0:
        p = 1.0
    elif sigma_known:
        p = float(stats.chi2.sf(rss0 - rss1, dfc))
    else:
        dfd = max(n - k1, 1)
        F = ((rss0 - rss1) / dfc) / max(rss1 / dfd, 1e-300)
        p = float(stats.f.sf(F, dfc, dfd))
    dbic = bic1 - bic0
    significant = bool(dbic < DELTA_BIC_THRESHOLD and p < P_THRESHOLD)
    inst = final_model.effect(name)
    fitted_b = base_space.values(final_model) if kb else {}
    if errors:
        notes["the model failed at some trial parameters (avoided by the fit): " + "; ".join(list(errors)[:2])] = None
    at_bound = [q.name for q in cand if min(q.to_u(getattr(inst, q.name)), 1 - q.to_u(getattr(inst, q.name))) < 1e-3]
    if at_bound:
        notes[f"refitted parameter(s) at a bound: {at_bound}"] = None
    return Candidate(effect=name, instance=inst, model=final_model, parameters=_effect_params(inst),
                     free=tuple(q.name for q in cand), baseline_parameters=fitted_b,
                     rmse=float(np.sqrt(np.mean(r1 ** 2))), rss=rss1, bic=bic1, delta_bic=float(dbic), p_value=p,
                     test=test, score_z=z, score_p=score_p, cosine=cos,
                     explained=float(1.0 - rss1 / rss0) if rss0 > 0 else 0.0, significant=significant,
                     status="ok", signature=d, change=change, predicted=f1, n_params=k_eff_c, n_evals=evals,
                     notes=tuple(notes)), evals


def _budget(k: int) -> int:
    """Model evaluations allowed for stage A with k parameters."""
    return 32 if k <= 1 else 16 + 14 * k


def _no_signature(name, model_c, cand, d, f0, y, w, bic0, sigma_known, evals) -> Candidate:
    r = y - f0
    return Candidate(effect=name, instance=model_c.effect(name), model=model_c,
                     parameters=_effect_params(model_c.effect(name)), free=tuple(q.name for q in cand),
                     baseline_parameters={}, rmse=float(np.sqrt(np.mean(r ** 2))),
                     rss=float(np.sum((r * w) ** 2)), bic=bic0, delta_bic=0.0, p_value=1.0,
                     test="chi2" if sigma_known else "F", score_z=0.0, score_p=1.0, cosine=0.0, explained=0.0,
                     significant=False, status="no signature", signature=d, change=np.zeros_like(f0),
                     predicted=f0, n_params=0, n_evals=evals,
                     notes=("switching it on changes no prediction for these measurements",))


def _effect_params(e) -> dict:
    out = {}
    for p in getattr(e, "parameters", ()):
        v = getattr(e, p.name, None)
        if isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(v, bool):
            out[p.name] = float(v)
    return out


def _bic(rss: float, n: int, k: int, sigma_known: bool) -> float:
    if sigma_known:
        return float(rss + k * math.log(n))
    return float(n * math.log(max(rss, 1e-300) / n) + k * math.log(n))


def _jacobian(predictor, model, space, u, f0, h: float = 1e-3) -> np.ndarray:
    cols = []
    for j in range(len(space)):
        du = np.array(u, dtype=float)
        step = h if du[j] + h <= 1.0 else -h
        du[j] += step
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            f = predictor.predict(space.apply(model, du)).mu
        cols.append((f - f0) / step)
    return np.column_stack(cols) if cols else np.zeros((f0.size, 0))


# ---- ambiguity ---------------------------------------------------------------------------------------------
def _proj(v, Q, w):
    vw = v * w
    return vw - Q @ (Q.T @ vw) if Q.shape[1] else vw


def _cos(a, b) -> float:
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    if na <= 1e-300 or nb <= 1e-300:
        return 0.0
    return float(a @ b) / (na * nb)


def _clusters(results, Q, w) -> list:
    ok = [c for c in results if c.status == "ok" and c.signature is not None]
    if len(ok) < 2:
        return []
    sig = [_proj(c.signature, Q, w) for c in ok]
    chg = [_proj(c.change, Q, w) for c in ok]
    parent = list(range(len(ok)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    cosines = {}
    for i in range(len(ok)):
        for j in range(i + 1, len(ok)):
            c = max(abs(_cos(sig[i], sig[j])), abs(_cos(chg[i], chg[j])))
            if c > COSINE_THRESHOLD:
                cosines[(i, j)] = c
                parent[find(j)] = find(i)
    groups: dict[int, list[int]] = {}
    for i in range(len(ok)):
        groups.setdefault(find(i), []).append(i)
    out = []
    for members in groups.values():
        if len(members) < 2:
            continue
        members.sort()  # results are ranked, so the first is the best
        cs = {f"{ok[i].effect}|{ok[j].effect}": round(c, 4) for (i, j), c in cosines.items()
              if i in members and j in members}
        out.append(Ambiguity(effects=tuple(ok[i].effect for i in members), cosines=cs))
    return out


def _probe_conditions(m: Measurements, contact):
    vs = m.sliding_speed
    lo, hi = float(vs.min()), float(vs.max())
    speeds = np.geomspace(max(lo / 10, 1e-9), min(hi * 10, 100.0), 13)
    T = np.unique(m.temperature)
    if T.size > 5:
        T = np.quantile(m.temperature, [0, 0.25, 0.5, 0.75, 1.0])
    T = np.unique(np.concatenate([T, [T.min() - 20.0, T.max() + 20.0]]))
    p = np.unique(m.pressure)
    if p.size > 3:
        p = np.quantile(m.pressure, [0, 0.5, 1.0])
    p = np.unique(np.concatenate([p, [p.min() / 2, p.max() * 2]]))
    wets = (False, True) if np.any(m.wet) else (False,)
    slips = np.array([0.02, 0.05, 0.1, 0.3]) if contact is not None else np.zeros(0)
    V_slip = float(np.median(m.speed[~m.is_sliding])) if np.any(~m.is_sliding) else float(np.median(m.speed))
    return speeds, T, p, wets, slips, V_slip


def _evaluate_probe(model, cond, contact):
    """Rows (V, slip, T, p, wet, mu) of ``model`` on the probe grid."""
    from persson.slip import mu_slip

    speeds, Ts, ps, wets, slips, V_slip = cond
    rows = []
    calls = 0
    for wet in wets:
        mg = wet_model(model) if wet else dry_model(model)
        for T in Ts:
            for p in ps:
                vs_slip = slips * V_slip
                allv = np.unique(np.concatenate([speeds, vs_slip]))
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    r = mg.friction(allv, temperature=float(T), pressure=float(p))
                calls += 1
                mu = np.atleast_1d(r.mu)
                for v, x in zip(allv, mu):
                    if np.any(np.isclose(v, speeds, rtol=1e-12, atol=0)):
                        rows.append((float(v), 1.0, float(T), float(p), wet, float(x)))
                if slips.size:
                    def local(v, allv=allv, mu=mu):
                        return np.interp(np.log(v), np.log(allv), mu)

                    res = mu_slip(local, slips, V_slip, temperature=float(T), pressure=float(p), contact=contact)
                    for s, x in zip(slips, np.atleast_1d(res.mu)):
                        rows.append((V_slip, float(s), float(T), float(p), wet, float(x)))
    return rows, calls


def _separate(clusters, results, m, contact, predictor):
    by_name = {c.effect: c for c in results}
    cond = _probe_conditions(m, contact)
    vs = m.sliding_speed
    rng = dict(v=(vs.min(), vs.max()), T=(m.temperature.min(), m.temperature.max()),
               p=(m.pressure.min(), m.pressure.max()))
    cache = {}
    calls = 0
    out = []
    for cl in clusters:
        seps, seps_in = [], []
        head = cl.effects[0]
        for other in cl.effects[1:]:
            rows = {}
            for nm in (head, other):
                if nm not in cache:
                    try:
                        cache[nm], c = _evaluate_probe(by_name[nm].model, cond, contact)
                        calls += c
                    except Exception:  # noqa: BLE001
                        cache[nm] = None
                rows[nm] = cache[nm]
            if rows[head] is None or rows[other] is None or len(rows[head]) != len(rows[other]):
                continue
            a, b = rows[head], rows[other]
            diffs = np.array([ra[5] - rb[5] for ra, rb in zip(a, b)])
            inside = np.array([rng["v"][0] / 1.001 <= ra[0] * ra[1] <= rng["v"][1] * 1.001
                               and rng["T"][0] <= ra[2] <= rng["T"][1] and rng["p"][0] <= ra[3] <= rng["p"][1]
                               for ra in a])
            i = int(np.argmax(np.abs(diffs)))
            seps.append(_sep(head, other, a[i], b[i], bool(inside[i])))
            if np.any(inside):
                j = int(np.flatnonzero(inside)[np.argmax(np.abs(diffs[inside]))])
                seps_in.append(_sep(head, other, a[j], b[j], True))
        out.append(Ambiguity(effects=cl.effects, cosines=cl.cosines, separations=tuple(seps),
                             separations_in_range=tuple(seps_in)))
    return out, calls


def _sep(a_name, b_name, ra, rb, inside) -> Separation:
    return Separation(effects=(a_name, b_name), speed=ra[0], slip=ra[1], temperature=ra[2], pressure=ra[3],
                      wet=bool(ra[4]), mu=(ra[5], rb[5]), difference=ra[5] - rb[5], in_range=inside)


# ---- explanation -------------------------------------------------------------------------------------------
def _fmt_params(d: dict) -> str:
    return ", ".join(f"{k}={v:.4g}" for k, v in d.items())


def _factor_phrases(values: np.ndarray, m: Measurements, sd: float, z_min: float = 3.0,
                    kind: str = "residual") -> list[str]:
    """For each factor: where the group means of ``values`` are largest / smallest (only systematic ones).

    ``kind`` "residual" labels the larger deviation "model too low/high"; "change" labels it "raises/lowers mu".
    """
    phrases = []
    for factor, (gid, labels) in group_labels(m).items():
        if factor == "series" or len(labels) < 2:
            continue
        means, zs, ns = [], [], []
        for k in range(len(labels)):
            sel = gid == k
            nk = int(sel.sum())
            mk = float(np.mean(values[sel])) if nk else 0.0
            means.append(mk)
            ns.append(nk)
            zs.append(mk / (sd / math.sqrt(nk)) if nk and sd > 0 else 0.0)
        means = np.array(means)
        zs = np.array(zs)
        if np.max(np.abs(zs)) < z_min:
            continue
        hi_k, lo_k = int(np.argmax(means)), int(np.argmin(means))
        if means[hi_k] - means[lo_k] <= 0:
            continue
        big, small = (hi_k, lo_k) if abs(means[hi_k]) >= abs(means[lo_k]) else (lo_k, hi_k)
        if kind == "residual":
            word = "model too low" if means[big] > 0 else "model too high"
        else:
            word = "raises mu" if means[big] > 0 else "lowers mu"
        phrases.append(f"by {factor}, {means[big]:+.3f} ({word}) at {labels[big]} against {means[small]:+.3f} at "
                       f"{labels[small]}")
    return phrases


def _trends(values: np.ndarray, m: Measurements) -> list[str]:
    out = []
    covs = [("log sliding speed", np.log10(m.sliding_speed)), ("temperature", m.temperature),
            ("pressure", m.pressure), ("slip", m.slip)]
    for label, x in covs:
        if np.ptp(x) <= 0:
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            rho, p = stats.spearmanr(x, values)
        if math.isfinite(rho) and abs(rho) >= 0.3 and p < 0.01:
            out.append(f"{'rises' if rho > 0 else 'falls'} with {label} (Spearman {rho:+.2f})")
    return out


def _explain(m: Measurements, dx: dict, noise: float, sigma_known: bool) -> str:
    b = dx["baseline"]
    cands = dx["candidates"]
    r = b.residual
    sd = float(np.std(r, ddof=1)) if r.size > 1 else float(np.sqrt(np.mean(r * r)))
    paras = []
    noise_txt = ("rms of mu_std" if sigma_known else "residual standard deviation of the best significant model"
                 if any(c.significant for c in cands) else "residual standard deviation of the baseline")
    head = (f"Baseline ({', '.join(b.effects) or 'hysteresis only'}"
            + (f"; refitted {_fmt_params(b.fitted)}" if b.fitted else "") + f"): RMSE {b.rmse:.3g}, mean residual "
            f"{np.mean(r):+.3g} (measured - predicted; positive means the model predicts too little friction); "
            f"noise level {noise:.3g} ({noise_txt}).")
    phrases = _factor_phrases(r, m, sd)
    trends = _trends(r, m)
    if phrases or trends:
        txt = "Where it fails (mean residual of the groups furthest apart): " + "; ".join(phrases) if phrases \
            else "Where it fails:"
        if trends:
            txt += ("; " if phrases else " ") + "overall the residual " + ", ".join(trends)
        paras.append(head + " " + txt + ".")
    else:
        paras.append(head + " No group of rows deviates systematically (every group mean within 3 standard "
                            "errors) and the residual shows no trend with speed, temperature, pressure or slip.")
    ok = [c for c in cands if c.status == "ok"]
    sig = [c for c in ok if c.significant]
    if sig:
        t = sig[0]
        ch = t.change
        ch_sd = float(np.std(ch, ddof=1)) if ch.size > 1 else 0.0
        ch_ph = _factor_phrases(ch, m, max(sd, ch_sd, 1e-12), z_min=2.0, kind="change")
        corr = _cos(ch - ch.mean(), r - r.mean())
        doc = _first_doc_line(t.instance)
        txt = (f"Most likely missing: {t.effect}" + (f" ({doc})" if doc else "") + f". Refitted "
               f"({_fmt_params({k: t.parameters[k] for k in t.free}) or 'no free parameters'}"
               + (f"; baseline {_fmt_params(t.baseline_parameters)}" if t.baseline_parameters else "")
               + "), it changes the prediction "
               + ("(mean change per group) " + "; ".join(ch_ph) if ch_ph else "in a pattern")
               + f". That change follows the baseline residual (correlation {corr:+.2f}) and removes "
               f"{100 * t.explained:.1f} % of its sum of squares: RMSE {b.rmse:.3g} -> {t.rmse:.3g}, "
               f"delta BIC {t.delta_bic:+.1f}, p = {t.p_value:.2g} ({t.test} test); the score test of its "
               f"default-parameter signature gives z = {t.score_z:+.1f}.")
        r1 = y_minus(m, t)
        sd1 = float(np.std(r1, ddof=1)) if r1.size > 1 else 0.0
        rest = _factor_phrases(r1, m, max(sd1, 1e-12)) + _trends(r1, m)
        if sigma_known:
            red = t.rss / max(m.n - b.n_params - t.n_params, 1)
            txt += (f" With it chi2/dof = {red:.2f} (1 means the residual is at the noise level given by mu_std)"
                    + ("." if red < 1.5 else "; the rest is more than noise."))
        if rest:
            txt += (" A systematic pattern remains in its residual (" + "; ".join(rest[:3]) + "): something else may "
                    "be missing too (run the improvement loop).")
        else:
            txt += (" Its residual shows no remaining systematic pattern by speed, temperature, pressure or slip.")
        if len(sig) > 1:
            txt += " Also significant: " + ", ".join(f"{c.effect} (delta BIC {c.delta_bic:+.1f})" for c in sig[1:4]) \
                + "."
        paras.append(txt)
    elif ok:
        t = ok[0]
        paras.append(f"No candidate is significant ({SIGNIFICANCE_RULE}). The best, {t.effect}, changes BIC by "
                     f"{t.delta_bic:+.1f} (p = {t.p_value:.2g}) and RMSE {b.rmse:.3g} -> {t.rmse:.3g}: the data do "
                     "not call for any of the candidate effects.")
    else:
        paras.append("No candidate effect could be evaluated.")
    for cl in dx["clusters"]:
        if not cl.effects:
            continue
        by = {c.effect: c for c in cands}
        head = by[cl.effects[0]]
        gaps = [(e, by[e].delta_bic - head.delta_bic) for e in cl.effects[1:]]
        close = [e for e, g in gaps if g < 10.0]
        txt = (f"Ambiguity: {', '.join(cl.effects)} move the predictions in nearly the same way on these rows "
               f"(|cos| {', '.join(f'{k}: {v:.3f}' for k, v in cl.cosines.items())}).")
        if close:
            txt += (f" The data cannot tell {head.effect} from {', '.join(close)} (delta BIC within 10 of each "
                    "other).")
        else:
            txt += (f" The data still prefer {head.effect} (by {min(g for _, g in gaps):.0f} BIC units or more), "
                    "but that rests on the details of the fits.")
        for s in cl.separations:
            txt += f" To tell {s.effects[0]} from {s.effects[1]}, measure at {s.describe()}."
        for s in cl.separations_in_range:
            if not any(s.effects == t.effects and s.in_range for t in cl.separations):
                txt += f" Inside the measured ranges the largest difference is at {s.describe()}."
        paras.append(txt)
    failed = [c for c in cands if c.status.startswith("failed")]
    if failed:
        paras.append("Could not evaluate: " + "; ".join(f"{c.effect} ({c.status})" for c in failed) + ".")
    none = [c for c in cands if c.status == "no signature"]
    if none:
        paras.append("No signature on these measurements (switching them on changes no prediction): "
                     + ", ".join(c.effect for c in none) + ".")
    return "\n\n".join(paras)


def y_minus(m: Measurements, cand) -> np.ndarray:
    """Residual of a refitted candidate."""
    return m.mu - cand.predicted


def _first_doc_line(obj) -> str:
    doc = (type(obj).__doc__ or "").strip()
    if not doc:
        return ""
    import re

    line = doc.splitlines()[0].strip().rstrip(".")
    line = re.sub(r":\w+:`([^`]*)`", r"\1", line).replace("``", "").replace("`", "")
    return line[:140]
