r"""Which friction-speed law? Every applicable law fitted to one data set and ranked by an information criterion.

Do, Marsac & Mosset (2004) point out that a user who is no specialist of these models has no easy way to choose one.
:func:`fit_speed_laws` answers with evidence: it fits every law of :mod:`.speedlaws` and :mod:`.wetlaws` that the
data allow, and ranks them by

* AICc, Akaike's criterion (Akaike 1974) with the small-sample correction of Hurvich & Tsai (1989), the default
  (friction-speed curves have a handful of speeds), or
* BIC, Schwarz's (1978) criterion, which penalises extra constants more as the rows grow,

each with a Gaussian likelihood (the noise level profiled out unless ``sigma`` is given, then one more parameter).
Differences of the criterion, not its values, carry the evidence: :math:`\Delta < 2` is a tie, :math:`\Delta > 10`
decisive; the weights :math:`w_i \propto e^{-\Delta_i/2}` say the same as probabilities. Beside the ranking stands
Do et al.'s own acceptance rule: a fit is accepted when the sum of squared residuals is below 3e-3 (for its
4-6 speeds; the rule does not scale with the number of rows).

:func:`speed_laws_from_model` fits the same laws to the engine's prediction, so that a user sees which empirical
constants (PIARC's speed constant, the Stribeck speed, ...) Persson's theory implies for a surface and compound.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass

import numpy as np

from frictioncite import citations_of, doi

from .._checks import UnitWarning, number
from ..errors import AccuracyWarning, InputError
from .fitting import FitResult, _xy
from .references import AKAIKE_1974, DO_2004, HURVICH_TSAI_1989, SCHWARZ_1978
from .speedlaws import fit_speed_law
from .wetlaws import fit_dijks, fit_wet_product, pendulum_number, texture_depth_m

__all__ = ["fit_speed_laws", "SpeedLawFit", "SpeedLawTable", "information_criteria", "speed_laws_from_model",
           "SPEED_LAW_NAMES", "ACCEPTANCE_SSE", "DEFAULT_FIXED"]

#: Every law :func:`fit_speed_laws` knows, in the order it tries them.
SPEED_LAW_NAMES = ("piarc", "do_marsac_mosset", "stribeck", "gompertz", "la_torre", "rado", "three_zone", "dijks",
                   "wet_product")
#: Do, Marsac & Mosset's acceptance rule: sum of squared residuals below this (section 5.2).
ACCEPTANCE_SSE = 3.0e-3
_SURFACE_LAWS = {"dijks": fit_dijks, "wet_product": fit_wet_product}
#: Constants held fixed unless ``fixed`` says otherwise: Rado's three-constant form, as :func:`fit_rado`.
DEFAULT_FIXED = {"rado": {"mu_locked": 0.0}}


@doi(AKAIKE_1974, HURVICH_TSAI_1989, SCHWARZ_1978)
def information_criteria(residuals, k: int, *, sigma=None) -> tuple[float, float, float]:
    r"""AIC, AICc and BIC of a least-squares fit with Gaussian errors.

    With unknown noise, :math:`-2\ln L = n[\ln(2\pi\,\mathrm{SSE}/n) + 1]` and the noise level counts as a parameter
    (K = k + 1); with standard uncertainties ``sigma``, :math:`-2\ln L = \chi^2 + \sum \ln 2\pi\sigma_i^2` and K = k.
    :math:`\mathrm{AIC} = -2\ln L + 2K` (Akaike 1974), :math:`\mathrm{AICc} = \mathrm{AIC} + 2K(K+1)/(n-K-1)`
    (Hurvich & Tsai 1989; infinite when n <= K + 1), :math:`\mathrm{BIC} = -2\ln L + K\ln n` (Schwarz 1978).

    Parameters
    ----------
    residuals : array_like
        Data minus fit.
    k : int
        Free parameters of the law.
    sigma : array_like, optional
        Standard uncertainties of the data.

    Returns
    -------
    (aic, aicc, bic) : tuple of float
    """
    r = np.asarray(residuals, dtype=float).ravel()
    n = r.size
    if sigma is None:
        K = k + 1
        m2logL = n * (math.log(2 * math.pi * max(float(r @ r) / n, 1e-300)) + 1.0)
    else:
        s = np.broadcast_to(np.asarray(sigma, dtype=float), r.shape)
        K = k
        m2logL = float(np.sum((r / s) ** 2) + np.sum(np.log(2 * math.pi * s**2)))
    aic = m2logL + 2 * K
    aicc = aic + 2 * K * (K + 1) / (n - K - 1) if n - K - 1 > 0 else math.inf
    return aic, aicc, m2logL + K * math.log(n)


@dataclass(frozen=True, eq=False)
class SpeedLawFit:
    """One law of a :class:`SpeedLawTable`.

    Attributes
    ----------
    law : str
        Its name (``"piarc"``, ``"dijks"``, ``"la_torre"``, ``"gompertz"``, ``"stribeck"``,
        ``"do_marsac_mosset"``, ``"rado"``, ``"three_zone"``, ``"wet_product"``).
    fit : FitResult
        The fit itself (covariance, data, notes); a :class:`~persson.slip.wetlaws.SurfaceLawFit` for the laws of
        texture depth and BPN.
    k : int
        Free parameters.
    sse : float
        Sum of squared residuals.
    aic, aicc, bic : float
        Information criteria (:func:`information_criteria`).
    delta : float
        The ranking criterion minus the best one's.
    weight : float
        :math:`e^{-\\Delta/2}` normalised over the table (Akaike or Schwarz weight).
    accepted : bool
        ``sse`` below the acceptance threshold of the table.
    """

    law: str
    fit: FitResult
    k: int
    sse: float
    aic: float
    aicc: float
    bic: float
    delta: float = 0.0
    weight: float = 1.0
    accepted: bool = False

    @property
    def params(self) -> dict[str, float]:
        """Parameter values by name."""
        return self.fit.params

    @property
    def std(self) -> dict[str, float]:
        """Standard errors by name (0 for parameters held fixed)."""
        return self.fit.uncertainties

    @property
    def covariance(self) -> np.ndarray:
        """Covariance of the parameters (order of ``params``)."""
        return self.fit.covariance

    @property
    def notes(self) -> tuple:
        """Notes of the fit (``fit.notes``)."""
        return self.fit.notes

    @property
    def citations(self) -> tuple:
        """References of the law (``fit.citations``)."""
        return self.fit.citations

    def __call__(self, speed, *args, **kwargs):
        """The fitted law at ``speed`` (m/s; the laws of texture depth and BPN also take ``mtd``, ``bpn``)."""
        return self.fit(speed, *args, **kwargs)


@dataclass(frozen=True, eq=False)
class SpeedLawTable:
    """Friction-speed laws fitted to one data set, best first (:func:`fit_speed_laws`).

    Iterate over it, index it by rank (``table[0]`` is the best) or by law name (``table["piarc"]``).

    Attributes
    ----------
    fits : tuple of SpeedLawFit
        Best first by ``criterion``.
    skipped : dict
        law -> why it was not fitted.
    criterion : str
        ``"aicc"`` or ``"bic"``.
    acceptance : float
        The SSE threshold of ``accepted``.
    speed, mu : ndarray
    sigma : ndarray or None
    mtd, bpn : ndarray or None
        Texture depth (m) and BPN of the rows, when given.
    source : str
        What the rows are (``"data"``, or the engine prediction they came from).
    notes : tuple of str
    """

    fits: tuple
    skipped: dict
    criterion: str
    acceptance: float
    speed: np.ndarray
    mu: np.ndarray
    sigma: np.ndarray | None = None
    mtd: np.ndarray | None = None
    bpn: np.ndarray | None = None
    source: str = "data"
    notes: tuple = ()

    def __iter__(self):
        return iter(self.fits)

    def __len__(self) -> int:
        return len(self.fits)

    def __getitem__(self, key):
        if isinstance(key, str):
            for f in self.fits:
                if f.law == key:
                    return f
            why = f": {self.skipped[key]}" if key in self.skipped else ""
            raise KeyError(f"{key!r} is not in the table{why}")
        return self.fits[key]

    @property
    def best(self) -> SpeedLawFit:
        """The law ranked first."""
        return self.fits[0]

    @property
    def laws(self) -> tuple[str, ...]:
        """The fitted laws, best first."""
        return tuple(f.law for f in self.fits)

    @property
    def citations(self) -> tuple[str, ...]:
        """References of the laws and the criteria."""
        return citations_of(fit_speed_laws, *(f.fit for f in self.fits))

    def to_rows(self) -> list[dict]:
        """One dict per law, best first: law, k, sse, rms, aicc, bic, delta, weight, accepted, params, std."""
        return [dict(law=f.law, k=f.k, sse=f.sse, rms=f.fit.rms, aicc=f.aicc, bic=f.bic, delta=f.delta,
                     weight=f.weight, accepted=f.accepted, params=f.params, std=f.std) for f in self.fits]

    def summary(self) -> str:
        """The table as text: rank, law, k, SSE, the criteria, the weight, accepted, parameters +- standard errors."""
        lines = [f"{len(self.speed)} rows ({self.source}); ranked by {self.criterion.upper()}; accepted: "
                 f"SSE < {self.acceptance:g}",
                 f"{'#':>2} {'law':<17} {'k':>2} {'SSE':>9} {'AICc':>9} {'BIC':>9} {'delta':>7} {'weight':>6}  ok  "
                 "parameters"]
        for i, f in enumerate(self.fits, 1):
            par = ", ".join(f"{n} = {v:.4g} ± {e:.2g}" for n, v, e in zip(f.fit.names, f.fit.values, f.fit.stderr)
                            if n not in f.fit.fixed)
            lines.append(f"{i:>2} {f.law:<17} {f.k:>2} {f.sse:>9.3g} {f.aicc:>9.2f} {f.bic:>9.2f} {f.delta:>7.2f} "
                         f"{f.weight:>6.3f}  {'yes' if f.accepted else 'no ':<3} {par}")
        for f in self.fits:
            lines += [f"   {f.law:<17} note: {n}" for n in f.notes]
        for law, why in self.skipped.items():
            lines.append(f"   {law:<17} not fitted: {why}")
        lines += [f"note: {n}" for n in self.notes]
        return "\n".join(lines)

    def plot(self, ax=None, *, logx: bool = False, title: str = ""):
        """The data with every fitted law (best drawn heaviest); laws of texture depth and BPN drawn per surface at
        the measured speeds. Returns the figure."""
        from .plots import _axes  # matplotlib (Agg) only when a figure is asked for

        fig, ax = _axes(ax)
        V, m = self.speed, self.mu
        if self.sigma is not None:
            ax.errorbar(V, m, yerr=self.sigma, fmt="ko", ms=3, label="data", zorder=5)
        else:
            ax.plot(V, m, "ko", ms=3, label="data", zorder=5)
        xx = np.geomspace(V.min(), V.max(), 300) if logx else np.linspace(V.min(), V.max(), 300)
        for i, f in enumerate(self.fits):
            label = f"{f.law}: Δ{self.criterion.upper()} = {f.delta:.1f}, SSE = {f.sse:.2g}" + \
                ("" if f.accepted else " (not accepted)")
            style = dict(lw=2.0 if i == 0 else 1.0, color=f"C{i % 10}")
            if f.law in _SURFACE_LAWS:
                for j, (td, b) in enumerate(sorted(set(zip(self.mtd.tolist(), self.bpn.tolist())))):
                    sel = (self.mtd == td) & (self.bpn == b)
                    vv = np.linspace(V[sel].min(), V[sel].max(), 50)
                    ax.plot(vv, f(vv, td, b), "--", label=label if j == 0 else None, **style)
            else:
                ax.plot(xx, f(xx), "-", label=label, **style)
        if logx:
            ax.set_xscale("log")
        ax.set_xlabel("speed V (m/s)")
        ax.set_ylabel("friction coefficient mu")
        ax.set_title(title or f"friction against speed: laws ranked by {self.criterion.upper()} ({self.source})",
                     fontsize=9)
        ax.legend(fontsize=7)
        return fig


@doi(AKAIKE_1974, HURVICH_TSAI_1989, SCHWARZ_1978, DO_2004)
def fit_speed_laws(speed, mu, *, laws=None, sigma=None, mtd=None, bpn=None, mu_ref: float = 1.0,
                   fixed: dict | None = None, criterion: str = "aicc",
                   acceptance: float = ACCEPTANCE_SSE) -> SpeedLawTable:
    """Fit every applicable friction-speed law to one data set and rank the fits (best first).

    Parameters
    ----------
    speed, mu : array_like
        Speeds (m/s, > 0) and friction coefficients (>= 0), one per row.
    laws : sequence of str, optional
        Laws to try (default :data:`SPEED_LAW_NAMES`: every law; ``"dijks"`` and ``"wet_product"`` only when
        ``mtd`` and ``bpn`` are given).
    sigma : array_like, optional
        Standard uncertainties of mu; without them the noise level is estimated by each fit.
    mtd, bpn : float or array_like, optional
        Texture depth (m) and British Pendulum Number of each row, for the laws of Dijks and the product form.
    mu_ref : float
        Reference friction of La Torre's law.
    fixed : dict, optional
        law -> parameters held fixed, e.g. ``{"do_marsac_mosset": {"beta": 0.0, "alpha": 3.0}}``; by default Rado's
        ``mu_locked`` is held at 0 (his three-constant form; ``{"rado": {}}`` frees it).
    criterion : {"aicc", "bic"}
        The ranking criterion (AICc falls back to BIC, with a note, when no law has enough rows for it).
    acceptance : float
        SSE threshold of ``accepted`` (Do et al.'s 3e-3).

    Returns
    -------
    SpeedLawTable
        ``table[0]`` the best law; each entry has ``.law``, ``.params``, ``.std``, ``.aicc``, ``.bic``, ``.sse``,
        ``.accepted``; laws that could not be fitted are in ``table.skipped`` with the reason.

    Raises
    ------
    InputError
        Speeds <= 0 or beyond any tester, mu < 0, NaN, unequal lengths, fewer than three rows, an unknown law or
        criterion, or no law that could be fitted (the message lists each reason).

    Warns
    -----
    UnitWarning
        Speeds above 45 m/s (162 km/h): check that they are not km/h.
    AccuracyWarning
        Laws whose parameters the data do not all determine.
    """
    V, y, sig = _xy(speed, mu, sigma, "speed")
    _check_rows(V, y)
    criterion = str(criterion).lower()
    if criterion not in ("aicc", "bic"):
        raise InputError(f"criterion: expected 'aicc' or 'bic', got {criterion!r}")
    threshold = number(acceptance, "acceptance")
    names = SPEED_LAW_NAMES if laws is None else tuple(laws)
    unknown = [law for law in names if law not in SPEED_LAW_NAMES]
    if unknown:
        raise InputError(f"laws: unknown law(s) {unknown}; expected some of {list(SPEED_LAW_NAMES)}")
    TD = None if mtd is None else texture_depth_m(mtd, "mtd", V.size)
    B = None if bpn is None else pendulum_number(bpn, "bpn", V.size)
    fixed = dict(fixed or {})
    bad = sorted(set(fixed) - set(names))
    if bad:
        raise InputError(f"fixed: {bad} not among the laws fitted ({list(names)})")
    entries, skipped, undetermined = [], {}, []
    for law in names:
        if law in _SURFACE_LAWS and (TD is None or B is None):
            skipped[law] = "needs the texture depth (mtd, m) and the BPN of each row"
            continue
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always", AccuracyWarning)
                if law in _SURFACE_LAWS:
                    kw = {"fixed": fixed[law]} if law in fixed else {}
                    fit = _SURFACE_LAWS[law](V, y, mtd=TD, bpn=B, sigma=sig, **kw)
                else:
                    fit = fit_speed_law(law, V, y, sigma=sig, fixed=fixed.get(law, DEFAULT_FIXED.get(law)),
                                        mu_ref=mu_ref)
            for w in caught:
                if not issubclass(w.category, AccuracyWarning):
                    warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
        except InputError as exc:
            skipped[law] = str(exc)
            continue
        if any(not np.isfinite(e) for e in fit.stderr):
            undetermined.append(law)
        k = len(fit.names) - len(fit.fixed)
        r = y - fit(V)
        aic, aicc, bic = information_criteria(r, k, sigma=sig)
        entries.append(SpeedLawFit(law=law, fit=fit, k=k, sse=float(r @ r), aic=aic, aicc=aicc, bic=bic,
                                   accepted=bool(float(r @ r) < threshold)))
    if not entries:
        reasons = "; ".join(f"{law}: {why}" for law, why in skipped.items())
        raise InputError(f"speed, mu: no law could be fitted ({reasons})")
    notes = []
    if criterion == "aicc" and not any(math.isfinite(e.aicc) for e in entries):
        criterion = "bic"
        notes.append(f"AICc is undefined for every law ({V.size} rows are too few for its correction): ranked by BIC")
    if undetermined:
        msg = (f"the data do not determine every parameter of {undetermined} (a constant these rows do not need): "
               "its uncertainty is infinite")
        notes.append(msg)
        warnings.warn(msg, AccuracyWarning, stacklevel=2)
    return SpeedLawTable(fits=_rank(entries, criterion), skipped=skipped, criterion=criterion, acceptance=threshold,
                         speed=V, mu=y, sigma=sig, mtd=TD, bpn=B, notes=tuple(notes))


def speed_laws_from_model(model, speed, *, temperature: float, pressure: float, laws=None, criterion: str = "aicc",
                          fixed: dict | None = None) -> SpeedLawTable:
    """Fit the friction-speed laws to the engine's own prediction mu(V) (pure sliding).

    Parameters
    ----------
    model : persson.Model
        E.g. ``persson.Model(psd, material, effects=[persson.effects.Wet(lift=1.0, ...)])``.
    speed : array_like
        Sliding speeds, m/s.
    temperature : float
        Background temperature, deg C.
    pressure : float
        Nominal pressure, Pa.
    laws, criterion, fixed
        As in :func:`fit_speed_laws` (the laws of texture depth and BPN need several surfaces and are left out).

    Returns
    -------
    SpeedLawTable
        With ``source`` naming the prediction. The prediction has no noise: the criteria rank how closely each law
        follows the theory's curve, and the standard errors measure the law's misfit, not measurement scatter.
    """
    V = np.asarray(speed, dtype=float).ravel()
    result = model.friction(V, temperature=temperature, pressure=pressure)
    names = [law for law in (SPEED_LAW_NAMES if laws is None else laws) if law not in _SURFACE_LAWS]
    table = fit_speed_laws(V, np.atleast_1d(result.mu), laws=names, criterion=criterion, fixed=fixed)
    effects = ", ".join(getattr(e, "name", type(e).__name__) for e in getattr(model, "effects", ())) or "no effects"
    source = f"engine prediction at {temperature:g} C, {pressure / 1e6:g} MPa ({effects})"
    notes = table.notes + ("fitted to a noise-free prediction: the criteria rank closeness to the theory's curve and "
                           "the standard errors measure each law's misfit",) + tuple(getattr(result, "notes", ()))
    return SpeedLawTable(fits=table.fits, skipped=table.skipped, criterion=table.criterion,
                         acceptance=table.acceptance, speed=table.speed, mu=table.mu, source=source, notes=notes)


# =========================================================================================================
# helpers
# =========================================================================================================
def _check_rows(V, y) -> None:
    if V.size < 3:
        raise InputError(f"speed, mu: {V.size} row(s); a friction-speed law needs at least three")
    if np.any(V <= 0):
        i = int(np.argmax(V <= 0))
        raise InputError(f"speed: expected speeds > 0 m/s, got {V[i]:g} at index {i}")
    if np.any(V > 150.0):
        i = int(np.argmax(V > 150.0))
        raise InputError(f"speed: {V[i]:g} m/s at index {i} is beyond any friction tester; the speeds look like "
                         "km/h: give m/s (km/h / 3.6)")
    if V.max() > 45.0:
        warnings.warn(f"speed: up to {V.max():g} m/s ({V.max() * 3.6:g} km/h); check that the speeds are m/s, not "
                      "km/h", UnitWarning, stacklevel=3)
    if np.any(y < 0):
        i = int(np.argmax(y < 0))
        raise InputError(f"mu: expected friction coefficients >= 0, got {y[i]:g} at index {i}")


def _rank(entries: list, criterion: str) -> tuple:
    crit = np.array([getattr(e, criterion) for e in entries])
    best = np.min(crit[np.isfinite(crit)]) if np.any(np.isfinite(crit)) else 0.0
    delta = crit - best
    w = np.where(np.isfinite(delta), np.exp(-0.5 * np.where(np.isfinite(delta), delta, 0.0)), 0.0)
    w = w / w.sum() if w.sum() > 0 else w
    order = np.argsort(np.where(np.isfinite(crit), crit, np.inf), kind="stable")
    return tuple(dataclasses.replace(entries[i], delta=float(delta[i]), weight=float(w[i])) for i in order)
