"""Comparison of a model with measured friction: predictions, residuals and where the model fails.

Residuals are ``measured - predicted`` (positive: the model predicts too little friction). The failure tables
group the rows by sliding-speed decade (v_s = slip * V), temperature, pressure, slip range, wet/dry and series;
each group gets its bias (mean residual), RMSE and ``z = bias / (s / sqrt(n))`` with s the within-group standard
deviation of the residuals pooled over the factor's groups (the standard deviation of all residuals when there
are fewer than 3 degrees of freedom); |z| >= 3 marks a systematic deviation rather than scatter.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

import numpy as np

from .errors import InputError
from .measurements import Measurements
from .predict import Prediction, Predictor, mostly_extrapolated

__all__ = ["Comparison", "GroupStat", "compare", "breakdown", "FACTORS"]

#: Factors of the failure tables, in display order.
FACTORS = ("sliding speed", "temperature", "pressure", "slip", "wet/dry", "series")

_SLIP_EDGES = (0.0, 0.02, 0.05, 0.1, 0.3, 1.0)


@dataclass(frozen=True)
class GroupStat:
    """Residual statistics of one group of rows.

    Attributes
    ----------
    factor : str
        ``"sliding speed"``, ``"temperature"``, ``"pressure"``, ``"slip"``, ``"wet/dry"`` or ``"series"``.
    label : str
        The group, e.g. ``"0.1-1 m/s"``, ``"20 C"``, ``"0.3 MPa"``, ``"0.05-0.1"``, ``"wet"``.
    n : int
    measured, predicted : float
        Mean measured and mean predicted mu.
    bias : float
        Mean residual (measured - predicted).
    rmse : float
        Root-mean-square residual.
    z : float
        bias / (s / sqrt(n)), s the pooled within-group standard deviation of the residuals.
    """

    factor: str
    label: str
    n: int
    measured: float
    predicted: float
    bias: float
    rmse: float
    z: float

    def as_dict(self) -> dict:
        """The statistics as a JSON-ready dict.

        Returns
        -------
        dict
            ``factor``, ``group`` (the label), ``n``, ``measured``, ``predicted``, ``bias``, ``rmse`` and ``z``.
        """
        return {"factor": self.factor, "group": self.label, "n": self.n, "measured": self.measured,
                "predicted": self.predicted, "bias": self.bias, "rmse": self.rmse, "z": self.z}


@dataclass(frozen=True, eq=False)
class Comparison:
    """A model compared with measurements.

    Attributes
    ----------
    model : persson.Model
    measurements : Measurements
    contact : persson.slip.Contact or None
    predicted : ndarray
        Predicted mu per row.
    residual : ndarray
        measured - predicted per row.
    rmse : float
        Root-mean-square residual.
    bias : float
        Mean residual.
    max_abs : float
        Largest |residual|.
    chi2 : float or None
        Sum of (residual / mu_std)^2 when the measurements have ``mu_std``.
    tables : dict
        Factor -> tuple of :class:`GroupStat` (see :data:`FACTORS`).
    notes : tuple of str
        Notes of the friction results (extrapolated PSD tails, convergence).
    name : str
        Label of the model (e.g. the case name).
    covariance : validation.refit.ParameterCovariance or None
        The covariance of the model's fitted parameters (a fitted model: :meth:`validation.Improvement.comparison`):
        the figures then draw the model's curves with a 68 % band (:mod:`validation.band`).
    band_note : str
        Why a fitted model's curves carry no band (shown under the figures; "" when there is a band, or when the
        model was not fitted here).
    modulus_extrapolated_share : ndarray or None
        Per row, the share of the hysteresis at the row's sliding point that rests on the master curve's
        extrapolation (:class:`validation.predict.Prediction`); None where not known.
    """

    model: object
    measurements: Measurements
    contact: object
    predicted: np.ndarray
    residual: np.ndarray
    rmse: float
    bias: float
    max_abs: float
    chi2: float | None
    tables: dict
    notes: tuple = ()
    name: str = ""
    covariance: object = field(default=None, repr=False)
    band_note: str = ""
    _predictor: object = field(default=None, repr=False)
    modulus_extrapolated_share: np.ndarray | None = field(default=None, repr=False)

    @property
    def n(self) -> int:
        """Number of measurement rows."""
        return self.measurements.n

    @property
    def effects(self) -> tuple[str, ...]:
        """Names of the model's effects, in the model's order."""
        return tuple(self.model.effect_names)

    @property
    def has_band(self) -> bool:
        """Whether the model's curves are drawn with an uncertainty band (a covariance that identifies every
        fitted parameter)."""
        return self.covariance is not None and not self.band_note and not self.covariance.unavailable()

    def worst_groups(self, z_min: float = 3.0) -> list[GroupStat]:
        """Groups with |z| >= ``z_min`` (systematic deviations), largest |bias| first (series excluded)."""
        rows = [g for f, t in self.tables.items() if f != "series" for g in t if abs(g.z) >= z_min and g.n >= 2]
        return sorted(rows, key=lambda g: -abs(g.bias))

    def summary(self) -> str:
        """A few lines: RMSE, bias, and every systematic deviation (each group with |z| >= 3, largest |bias|
        first; none is left out however many there are)."""
        m = self.measurements
        lines = [f"{self.name or 'model'}: effects {list(self.effects) or ['(none: hysteresis only)']}; "
                 f"{m.describe()}",
                 f"RMSE {self.rmse:.4g}, bias {self.bias:+.4g} (measured - predicted), max |residual| "
                 f"{self.max_abs:.4g}" + (f", chi2/n {self.chi2 / m.n:.3g}" if self.chi2 is not None else "")]
        worst = self.worst_groups()
        if worst:
            lines.append("systematic deviations (|z| >= 3): " + "; ".join(
                f"{g.factor} {g.label}: bias {g.bias:+.3f} (n={g.n})" for g in worst))
        else:
            lines.append("no group deviates systematically (all |z| < 3)")
        if self.extrapolation_summary():
            lines.append(self.extrapolation_summary())
        return "\n".join(lines)

    def extrapolation_summary(self) -> str:
        """How many rows rest for more than half of their predicted hysteresis on the master curve's extrapolation
        beyond its measured frequencies, and what that means for a misfit there ("" when none, or not known)."""
        over = self.rows_mostly_extrapolated()
        if not over.size:
            return ""
        return (f"{over.size} of {self.n} rows rest for more than half of their hysteresis on the master curve's "
                f"extrapolation (up to {float(np.max(self.modulus_extrapolated_share)):.0%}, column "
                "modulus_extrapolated_share): a misfit there may come from the compound's data beyond their "
                "frequencies rather than from a missing effect")

    def rows_mostly_extrapolated(self) -> np.ndarray:
        """Indices of the rows whose predicted hysteresis comes for more than half from reduced frequencies
        outside the measured master curve (empty when that is not known)."""
        return mostly_extrapolated(self.modulus_extrapolated_share)

    def table_text(self) -> str:
        """The failure tables as aligned plain text."""
        out = []
        for factor, rows in self.tables.items():
            if not rows:
                continue
            out.append(f"by {factor}:")
            out.append(f"  {'group':<18}{'n':>5}{'measured':>10}{'predicted':>11}{'bias':>9}{'rmse':>8}{'z':>7}")
            for g in rows:
                out.append(f"  {g.label:<18}{g.n:>5}{g.measured:>10.3f}{g.predicted:>11.3f}{g.bias:>+9.3f}"
                           f"{g.rmse:>8.3f}{g.z:>+7.1f}")
        return "\n".join(out)

    def as_dict(self) -> dict:
        """JSON-ready summary (no per-row arrays)."""
        return {"name": self.name, "effects": list(self.effects), "n": self.n, "rmse": self.rmse,
                "bias": self.bias, "max_abs": self.max_abs, "chi2": self.chi2,
                "tables": {f: [g.as_dict() for g in t] for f, t in self.tables.items()},
                "notes": list(self.notes),
                "rows_mostly_extrapolated": (None if self.modulus_extrapolated_share is None else
                                             int(self.rows_mostly_extrapolated().size))}

    def to_json(self, path=None, *, overwrite: bool = False) -> str:
        """The :meth:`as_dict` summary as JSON text; written atomically to ``path`` when given (never over the
        measurements' file, over another existing file only with ``overwrite=True``)."""
        from persson.io import source_files

        return json_text(self.as_dict(), path, overwrite=overwrite, inputs=source_files(self.measurements))

    def rows_table(self) -> dict[str, np.ndarray]:
        """Per-row columns: the measurement columns plus ``mu_predicted``, ``residual`` and, where known,
        ``modulus_extrapolated_share``."""
        cols = dict(self.measurements.as_table())
        cols["sliding_speed_m_s"] = self.measurements.sliding_speed
        cols["mu_predicted"] = self.predicted
        cols["residual"] = self.residual
        if self.modulus_extrapolated_share is not None:
            cols["modulus_extrapolated_share"] = self.modulus_extrapolated_share
        return cols

    def to_csv(self, path, comments: tuple[str, ...] = (), *, overwrite: bool = False):
        """Write :meth:`rows_table` as a CSV, atomically; never over the measurements' file, over another existing
        file only with ``overwrite=True``."""
        from persson.io import source_files, write_csv

        cols = self.rows_table()
        if "series" in cols:
            cols["series"] = np.asarray([str(s).replace(",", ";") for s in cols["series"]], dtype=object)
        head = (f"comparison: {self.name}", f"effects: {', '.join(self.effects) or 'none'}",
                f"RMSE {self.rmse:.6g}, bias {self.bias:.6g}", "residual = measured - predicted")
        return write_csv(path, cols, comments=head + tuple(comments), overwrite=overwrite,
                         inputs=source_files(self.measurements))

    def figures(self) -> dict:
        """Matplotlib figures (Agg): ``mu_speed``, ``mu_slip`` (when slip rows exist), ``residuals``."""
        from . import plots

        figs = {"mu_speed": plots.plot_mu_speed(self)}
        if self.measurements.has_slip_rows:
            figs["mu_slip"] = plots.plot_mu_slip(self)
        figs["residuals"] = plots.plot_residuals(self)
        return figs

    def save_plots(self, folder, prefix: str = "", *, overwrite: bool = False) -> list:
        """Write the :meth:`figures` as PNGs into ``folder``; returns the paths (existing files are replaced only
        with ``overwrite=True``)."""
        from pathlib import Path

        from persson.plots import save_figure

        folder = Path(folder)
        return [save_figure(fig, folder / f"{prefix}{name}.png", overwrite=overwrite)
                for name, fig in self.figures().items()]

    @property
    def predictor(self) -> Predictor:
        """The :class:`validation.predict.Predictor` of the measurements and the contact (built on first use, then
        reused)."""
        p = self._predictor
        if p is None:
            p = Predictor(self.measurements, self.contact)
            object.__setattr__(self, "_predictor", p)
        return p


def compare(model, measurements: Measurements, contact=None, *, name: str = "") -> Comparison:
    """Compare ``model`` with ``measurements`` row by row.

    Parameters
    ----------
    model : persson.Model
    measurements : Measurements
    contact : persson.slip.Contact, optional
        Brush model of the wheel; needed when some rows have slip < 1 (default: ``measurements.contact``, which
        :func:`validation.load_case` sets).
    name : str
        Label used in summaries and reports.

    Returns
    -------
    Comparison
    """
    if not hasattr(model, "friction"):
        raise InputError(f"model: expected a persson.Model, got {type(model).__name__}")
    pred = Predictor(measurements, contact)
    p = pred.predict(model, full=True)
    return comparison_from(model, measurements, pred.contact, p, name=name, predictor=pred)


def comparison_from(model, measurements: Measurements, contact, prediction: Prediction, *, name: str = "",
                    predictor=None, covariance=None, band_note: str = "") -> Comparison:
    """A :class:`Comparison` from an existing prediction (no new engine calls); ``covariance`` (the fitted
    parameters', :class:`validation.refit.ParameterCovariance`) gives its figures an uncertainty band, and
    ``band_note`` says why a fitted model has none."""
    y = measurements.mu
    f = np.asarray(prediction.mu, dtype=float)
    r = y - f
    chi2 = None if measurements.mu_std is None else float(np.sum((r / measurements.mu_std) ** 2))
    return Comparison(model=model, measurements=measurements, contact=contact, predicted=f, residual=r,
                      rmse=float(np.sqrt(np.mean(r * r))), bias=float(np.mean(r)),
                      max_abs=float(np.max(np.abs(r))), chi2=chi2,
                      tables=breakdown(measurements, r, f), notes=tuple(prediction.notes), name=name,
                      covariance=covariance, band_note=band_note, _predictor=predictor,
                      modulus_extrapolated_share=prediction.modulus_extrapolated_share)


# ==========================================================================================================
def group_labels(m: Measurements) -> dict[str, tuple[np.ndarray, list[str]]]:
    """Factor -> (group index per row, group labels in display order)."""
    out = {}
    vs = m.sliding_speed
    dec = np.floor(np.log10(vs) + 1e-9).astype(int)
    ud = sorted(set(dec.tolist()))
    out["sliding speed"] = (np.searchsorted(ud, dec), [f"{_p10(d)}-{_p10(d + 1)} m/s" for d in ud])
    out["temperature"] = _levels(m.temperature, lambda x: f"{x:g} C", lambda a, b: f"{a:g}-{b:g} C")
    out["pressure"] = _levels(m.pressure / 1e6, lambda x: f"{x:g} MPa", lambda a, b: f"{a:g}-{b:g} MPa")
    s = m.slip
    if np.any(s < 1):
        edges = _SLIP_EDGES
        k = np.where(s >= 1.0, len(edges) - 1, np.searchsorted(edges, s, side="left") - 1)
        labels = [f"{edges[i]:g}-{edges[i + 1]:g}" for i in range(len(edges) - 1)] + ["1 (sliding)"]
        used = sorted(set(k.tolist()))
        out["slip"] = (np.searchsorted(used, k), [labels[i] for i in used])
    else:
        out["slip"] = (np.zeros(m.n, dtype=int), ["1 (sliding)"])
    if np.any(m.wet):
        out["wet/dry"] = (m.wet.astype(int), ["dry", "wet"]) if np.any(~m.wet) else (np.zeros(m.n, dtype=int),
                                                                                      ["wet"])
    labels = m.series_labels
    if len(labels) > 1:
        idx = {lab: i for i, lab in enumerate(labels)}
        lab_all = list(labels)
        if any(s == "" for s in m.series):
            lab_all.append("(none)")
        out["series"] = (np.array([idx.get(s, len(labels)) for s in m.series]), lab_all)
    return out


def breakdown(measurements: Measurements, residual, predicted) -> dict:
    """Failure tables: factor -> tuple of :class:`GroupStat` (see the module docstring)."""
    r = np.asarray(residual, dtype=float)
    f = np.asarray(predicted, dtype=float)
    y = measurements.mu
    s_all = float(np.std(r, ddof=1)) if r.size > 1 else 0.0
    s_all = s_all if s_all > 0 else max(float(np.sqrt(np.mean(r * r))), 1e-12)
    tables = {}
    for factor, (gid, labels) in group_labels(measurements).items():
        s = _pooled_sd(r, gid, len(labels), s_all)
        rows = []
        for k, lab in enumerate(labels):
            sel = gid == k
            n = int(sel.sum())
            if n == 0:
                continue
            b = float(np.mean(r[sel]))
            rows.append(GroupStat(factor=factor, label=lab, n=n, measured=float(np.mean(y[sel])),
                                  predicted=float(np.mean(f[sel])), bias=b,
                                  rmse=float(np.sqrt(np.mean(r[sel] ** 2))), z=b / (s / math.sqrt(n))))
        tables[factor] = tuple(rows)
    return tables


def _pooled_sd(r: np.ndarray, gid: np.ndarray, n_groups: int, fallback: float) -> float:
    """Within-group standard deviation of ``r`` pooled over the groups (``fallback`` with < 3 dof)."""
    dof = r.size - n_groups
    if dof < 3:
        return fallback
    ssw = 0.0
    for k in range(n_groups):
        sel = gid == k
        if np.any(sel):
            ssw += float(np.sum((r[sel] - r[sel].mean()) ** 2))
    return max(float(np.sqrt(ssw / dof)), 1e-6 * float(np.max(np.abs(r))), 1e-12)


def _levels(x: np.ndarray, one, span, max_levels: int = 8):
    u = np.unique(x)
    if u.size <= max_levels:
        return np.searchsorted(u, x), [one(v) for v in u]
    edges = np.quantile(x, np.linspace(0, 1, 6))
    edges = np.unique(edges)
    k = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, edges.size - 2)
    labels = [span(_round(edges[i]), _round(edges[i + 1])) for i in range(edges.size - 1)]
    used = sorted(set(k.tolist()))
    return np.searchsorted(used, k), [labels[i] for i in used]


def _round(x: float) -> float:
    return float(f"{x:.3g}")


def _p10(d: int) -> str:
    return f"{10.0 ** d:g}"


def json_text(data: dict, path=None, *, overwrite: bool = False, inputs=()) -> str:
    """``data`` as indented JSON text (non-finite floats as null); written atomically to ``path`` when given (never
    over one of ``inputs``, over an existing file only with ``overwrite=True``)."""
    text = json.dumps(_clean(data), indent=2)
    if path is not None:
        from persson.io import atomic_write, check_overwrite

        check_overwrite(path, overwrite=overwrite, inputs=inputs)
        with atomic_write(path, "w") as fh:
            fh.write(text + "\n")
    return text


def _clean(obj):
    """Replace non-finite floats by None and numpy scalars by Python ones, recursively (for JSON)."""
    if isinstance(obj, dict):
        return {str(k): _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, (np.bool_, bool)):
        return bool(obj)
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, np.ndarray):
        return _clean(obj.tolist())
    return obj
