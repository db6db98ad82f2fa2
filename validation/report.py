"""Self-contained HTML report: comparison, diagnosis and the error falling step by step.

The whole document is built in memory first (figures as base64 PNGs, every user-provided string HTML-escaped),
then written to a temporary file beside the destination and renamed over it: the report is complete or absent.
"""

from __future__ import annotations

import base64
import datetime as _dt
import html
import io
import math
from pathlib import Path


from .errors import InputError

__all__ = ["write_report", "render_report"]

_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;max-width:1150px;margin:2em auto;color:#222;
line-height:1.45;padding:0 1em}
h1{font-size:1.6em;border-bottom:2px solid #444}h2{margin-top:2em;border-bottom:1px solid #aaa}
table{border-collapse:collapse;margin:0.6em 0;font-size:0.88em}
th,td{border:1px solid #ccc;padding:3px 8px;text-align:right}th{background:#f0f0f0}
td.l,th.l{text-align:left}.sig{background:#e3f6e3}.bad{color:#a00}.note{color:#555;font-size:0.9em}
.verdict{font-size:1.15em;padding:0.7em 1em;margin:1em 0;border-radius:4px;border:2px solid}
.v-explained,.v-nothing_missing{background:#e8f6e8;border-color:#3a3}.v-partly_explained{background:#fff6e0;
border-color:#c90}.v-unexplained{background:#fdeaea;border-color:#c33}.v-undetermined{background:#eef0f6;
border-color:#668}
img{max-width:100%;border:1px solid #ddd;margin:0.5em 0}p.expl{white-space:pre-wrap;background:#fafafa;
border-left:4px solid #4a7;padding:0.6em 1em}
"""


def write_report(items, path, title: str | None = None, *, overwrite: bool = False) -> Path:
    """Write one self-contained HTML report of ``items``, atomically.

    The file is never one of the inputs of the items (the case file, the measurements, the PSD...: refused even
    with ``overwrite``), and an existing file is replaced only with ``overwrite=True``, as on the command line.

    Parameters
    ----------
    items : sequence
        :class:`~validation.Case`, :class:`~validation.Comparison`, :class:`~validation.Diagnosis`,
        :class:`~validation.Improvement` or :class:`~validation.Step` objects (in the order shown; a nested
        list such as ``improvement.steps`` is flattened), or plain strings (paragraphs).
    path : str or path-like
        The HTML file. Written to a temporary file and renamed: on any error no (partial) file is left and an
        existing file is untouched.
    title : str, optional
    overwrite : bool
        Replace an existing file (never an input).

    Returns
    -------
    Path
    """
    from persson.io import atomic_write, check_overwrite, source_files

    path = check_overwrite(path, overwrite=overwrite, inputs=source_files(items), what="write_report")
    text = render_report(items, title=title)
    with atomic_write(path, "w", encoding="utf-8") as fh:
        fh.write(text)
    return path


def render_report(items, title: str | None = None) -> str:
    """The HTML text of :func:`write_report` (nothing written)."""
    from .case import Case
    from .compare import Comparison
    from .diagnose import Diagnosis
    from .improve import Improvement

    from .improve import Step

    if isinstance(items, (Comparison, Diagnosis, Improvement, Case, Step, str)):
        items = [items]
    flat = []
    for it in items:   # one level of nesting, e.g. [cmp, dx, imp.steps]
        if isinstance(it, (list, tuple)):
            flat.extend(it)
        else:
            flat.append(it)
    items = flat
    if not items:
        raise InputError("write_report: nothing to report (give comparisons, diagnoses, improvements)")
    name = next((getattr(i, "name", "") for i in items if getattr(i, "name", "")), "")
    title = title or (f"Friction validation report: {name}" if name else "Friction validation report")
    body = [f"<h1>{_e(title)}</h1>",
            f"<p class='note'>Generated {_e(_dt.datetime.now().isoformat(timespec='seconds'))} by "
            f"persson-friction {_e(_version())}. Residual = measured - predicted (positive: the model predicts "
            "too little friction).</p>"]
    banner = _verdict_banner(items)
    if banner:
        body.append(banner)
    pending_steps: list = []
    for it in items + [None]:
        if isinstance(it, Step):
            pending_steps.append(it)
            continue
        if pending_steps:
            body.append("<h2>Steps</h2>" + _steps_table(pending_steps))
            pending_steps = []
        if it is None:
            break
        if isinstance(it, Case):
            body.append(_case_html(it))
        elif isinstance(it, Comparison):
            body.append(_comparison_html(it))
        elif isinstance(it, Diagnosis):
            body.append(_diagnosis_html(it, best_model=not any(isinstance(i, Improvement) for i in items)))
        elif isinstance(it, Improvement):
            body.append(_improvement_html(it))
        elif isinstance(it, str):
            body.append(f"<p>{_e(it)}</p>")
        else:
            raise InputError(f"write_report: cannot report a {type(it).__name__} (expected Case, Comparison, "
                             "Diagnosis, Improvement, Step or str)")
    return ("<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
            f"<title>{_e(title)}</title><style>{_CSS}</style></head><body>\n" + "\n".join(body)
            + "\n</body></html>\n")


# ----------------------------------------------------------------------------------------------------------
def _e(x) -> str:
    return html.escape(str(x), quote=True)


def _version() -> str:
    try:
        import persson

        return persson.__version__
    except Exception:  # noqa: BLE001
        return "?"


def _num(x, fmt=".4g") -> str:
    if x is None:
        return "-"
    try:
        xf = float(x)
    except (TypeError, ValueError):
        return _e(x)
    if not math.isfinite(xf):
        return "-"
    if fmt == "d":
        return _e(str(int(round(xf))))
    return _e(format(xf, fmt))


def _img(fig, alt: str) -> str:
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    try:
        # zlib's fastest level: 5 % larger images, a tenth less time per figure than the default level 6
        fig.savefig(buf, format="png", dpi=90, pil_kwargs={"compress_level": 1})
    finally:
        plt.close(fig)
    data = base64.b64encode(buf.getvalue()).decode("ascii")
    return f"<img alt='{_e(alt)}' src='data:image/png;base64,{data}'>"


def _table(head, rows, left=(0,), classes=None) -> str:
    out = ["<table><tr>" + "".join(f"<th class='{'l' if j in left else ''}'>{_e(h)}</th>"
                                   for j, h in enumerate(head)) + "</tr>"]
    for i, r in enumerate(rows):
        cls = f" class='{classes[i]}'" if classes and classes[i] else ""
        out.append(f"<tr{cls}>" + "".join(f"<td class='{'l' if j in left else ''}'>{c}</td>"
                                          for j, c in enumerate(r)) + "</tr>")
    out.append("</table>")
    return "".join(out)


def _case_html(case) -> str:
    m = case.model
    rows = [("case file", _e(case.path)), ("surface", _e(getattr(m.surface, "source", "") or type(m.surface).__name__)
                                          + _e(f" (q = {m.surface.q_range[0]:.3g}-{m.surface.q_range[1]:.3g} rad/m)")),
            ("material", _e(getattr(m.material, "label", "") or type(m.material).__name__)),
            ("baseline effects", _e(", ".join(m.effect_names) or "none (hysteresis + contact area)")),
            ("fitted baseline parameters", _e(", ".join(case.fit) or "none")),
            ("measurements", _e(case.measurements.source) + "<br>" + _e(case.measurements.describe()))]
    if case.contact is not None:
        c = case.contact
        rows.append(("contact (brush model)", _e(f"l = {c.length:g} m, w = {c.width:g} m, k = {c.stiffness:g} Pa/m, "
                                                 f"pressure {c.pressure_distribution!r}")))
    return f"<h2>Case: {_e(case.name)}</h2>" + _table(["", ""], rows, left=(0, 1))


def _comparison_html(cmp) -> str:
    out = [f"<h2>Comparison: {_e(cmp.name or 'model')} vs measurements</h2>"]
    out.append("<p class='note'>The model with its parameters as given in the case (nothing refitted); the "
               "diagnosis below refits the baseline's fitted parameters first.</p>")
    out.append(_table(["effects", "rows", "RMSE (as given)", "bias", "max |residual|", "chi2 / n"],
                      [[_e(", ".join(cmp.effects) or "none"), _num(cmp.n, "d"), _num(cmp.rmse), _num(cmp.bias, "+.4g"),
                        _num(cmp.max_abs), _num(None if cmp.chi2 is None else cmp.chi2 / cmp.n)]], left=(0,)))
    for note in cmp.notes:
        out.append(f"<p class='note'>Note: {_e(note)}</p>")
    if cmp.extrapolation_summary():
        out.append(f"<p class='note'>Compound data: {_e(cmp.extrapolation_summary())}.</p>")
    for name, fig in cmp.figures().items():
        out.append(_img(fig, f"{cmp.name} {name}"))
    out.append("<h3>Where the model fails</h3><p class='note'>Groups with |z| &ge; 3 (bias larger than three "
               "standard errors) are marked.</p>")
    out.append(_deviations_html(cmp))
    for factor, rows in cmp.tables.items():
        if not rows:
            continue
        out.append(f"<h4>by {_e(factor)}</h4>")
        out.append(_table([factor, "n", "measured", "predicted", "bias", "RMSE", "z"],
                          [[_e(g.label), _num(g.n, "d"), _num(g.measured, ".3f"), _num(g.predicted, ".3f"),
                            _num(g.bias, "+.3f"), _num(g.rmse, ".3f"), _num(g.z, "+.1f")] for g in rows],
                          classes=["bad" if abs(g.z) >= 3 else "" for g in rows]))
    return "\n".join(out)


def _deviations_html(cmp) -> str:
    """Every systematic deviation (|z| >= 3), largest |bias| first, none left out."""
    worst = cmp.worst_groups()
    if not worst:
        return "<p>No group deviates systematically (all |z| &lt; 3).</p>"
    return (f"<p><b>Systematic deviations</b> (|z| &ge; 3, {len(worst)} group{'s' if len(worst) > 1 else ''}): "
            + "; ".join(f"{_e(g.factor)} {_e(g.label)}: bias {_num(g.bias, '+.3f')} (n = {_num(g.n, 'd')}, "
                        f"z = {_num(g.z, '+.1f')})" for g in worst) + ".</p>")


def _diagnosis_html(dx, best_model: bool = False) -> str:
    b = dx.baseline
    v = dx.verdict
    ne = dx.noise_estimate
    out = [f"<h2>Diagnosis: which effect is missing{(' (' + _e(dx.name) + ')') if dx.name else ''}</h2>",
           f"<div class='verdict v-{_e(v.verdict)}'>{_e(v.headline)}</div>",
           (f"<p><b>Noise</b>: {_num(dx.noise)} in mu, from <b>{_e(ne.source)}</b>: {_e(ne.description)}.</p>"
            if dx.noise_known else
            f"<p><b>Noise</b>: <b>unknown</b> ({_e(ne.description)}): no lack-of-fit test is possible, and the "
            "data cannot say whether anything is missing beyond the noise. Give a mu_std column or repeat some "
            "conditions.</p>")]
    out.append(_table(["baseline", "RMSE as given", "RMSE refitted", "BIC", "lack of fit", "refitted parameters"],
                      [[_e(", ".join(b.effects) or "hysteresis only"), _num(b.rmse_given), _num(b.rmse),
                        _num(b.bic, ".1f"), _e(b.lack.describe()), _estimates_html(b.estimates)]],
                      left=(0, 4, 5)))
    out.append(f"<p class='note'>Rule: {_e(dx.rule)}. A candidate is plausible when no fitted parameter sits on "
               "a search bound or outside its declared plausible range; only a significant and plausible "
               "candidate can explain the data. Parameters: value &plusmn; standard error, or a 68 % interval "
               "(profile likelihood where the quadratic approximation fails).</p>")
    rows, classes = [], []
    for i, c in enumerate(dx.candidates, 1):
        if c.status != "ok":
            rows.append([_num(i, "d"), _e(c.effect), "-", "-", "-", "-", "-", "no", "-", _e(c.status)])
            classes.append("")
            continue
        par = _estimates_html(c.estimates)
        if c.placeholders:
            par += "<br><span class='note'>kept: " + _e(", ".join(f"{k} = {t}" for k, t in c.placeholders.items())) \
                + "</span>"
        if c.notes:
            par += "<br><span class='note'>fit notes: " + _e("; ".join(c.notes)) + "</span>"
        rows.append([_num(i, "d"), _e(c.effect), _num(c.rmse), _num(c.delta_bic, "+.1f"), _num(c.p_value, ".2g"),
                     _num(c.lack.p_value, ".2g") if dx.noise_known else "no test",
                     _num(100 * c.explained, ".0f") + " %",
                     "YES" if c.significant else "no",
                     "yes" if c.plausible else "<span class='bad'>NO</span>: " + _e("; ".join(c.issues)), par])
        classes.append("sig" if c.credible else "")
    out.append(_table(["rank", "effect", "RMSE", "delta BIC", "p", "lack-of-fit p", "explained", "significant",
                       "plausible", "refitted parameters"], rows, left=(1, 8, 9), classes=classes))
    out.append(f"<p class='expl'>{_e(dx.explanation)}</p>")
    for cl in dx.clusters:
        out.append(f"<h4>Ambiguity cluster: {_e(', '.join(cl.effects))}</h4>")
        out.append(_probe_table(tuple(cl.separations) + tuple(cl.separations_in_range)))
    if dx.selection is not None:
        out.append(_selection_html(dx.selection))
    for name, fig in dx.figures().items():
        out.append(_img(fig, f"diagnosis {name}"))
    if best_model:
        out.append(_best_model_html(dx))
    refs = dx.references()
    if refs:
        out.append("<h4>References</h4><ul class='note'>" + "".join(f"<li>{_e(r)}</li>" for r in refs) + "</ul>")
    return "\n".join(out)


def _probe_table(seps) -> str:
    """Where two models differ most: the condition (wet flag included), whether it was measured, both mu."""
    if not seps:
        return ""
    rows = [[_e(" vs ".join(s.effects)), _num(s.speed * s.slip, ".3g"), _num(s.slip, "g"), _num(s.temperature, "g"),
             _num(s.pressure / 1e6, "g"), _e("wet" if s.wet else "dry"),
             _e("yes" if s.in_range else f"no (distance {s.distance:.1f})"), _num(s.mu[0], ".3f"),
             _num(s.mu[1], ".3f")] for s in seps]
    return (_table(["pair", "sliding speed (m/s)", "slip", "T (C)", "p (MPa)", "wet/dry", "inside the measured "
                    "conditions", "mu (first)", "mu (second)"], rows, left=(0, 5, 6))
            + "<p class='note'>Inside the measured conditions: within one measurement step of a measured row "
              "(scaled distance to the nearest row below 1, on the combination of speed, temperature, pressure "
              "and slip with the same wet flag).</p>")


def _selection_html(sel) -> str:
    """The best set of effects, the equally supported ones (parameters and intervals) and what separates them."""
    out = [f"<h3>Sets of effects: best {_e(sel.best.label)}</h3>",
           "<p class='note'>Every set is a joint refit of all its parameters from global starts. An effect stays "
           "only if dropping it from the best set costs more than 10 BIC units; sets within 10 BIC units of the "
           "best are equally supported by the data.</p>"]
    rows = []
    for s in (sel.best,) + tuple(sel.supported):
        rows.append([_e(s.label), _num(s.bic - sel.best.bic, "+.1f"), _num(s.rmse), _num(s.lack.p_value, ".2g"),
                     _estimates_html(s.estimates)])
    out.append(_table(["set", "delta BIC", "RMSE", "lack-of-fit p", "parameters (68 % intervals)"], rows,
                      left=(0, 4)))
    if sel.drop_costs:
        out.append("<p>Cost of dropping each effect of the best set: " + _e(", ".join(
            f"{k} {v:+.1f} BIC units" for k, v in sel.drop_costs.items())) + ".</p>")
    if sel.supported:
        out.append("<p><b>The data support these sets equally</b>; the measurement that would separate them:</p>")
        out.append(_probe_table(tuple(sel.separations) + tuple(sel.separations_in_range)))
    cal = getattr(sel, "calibration", None)
    if cal is not None and cal.rivals:
        out.append(f"<p><b>Calibration of the rig.</b> {_e(cal.text())}</p>")
    if sel.set_aside:
        out.append("<p class='note'>Set aside although they fit better (not credible): " + _e("; ".join(
            f"{s.label} ({s.bic - sel.best.bic:+.1f} BIC units: {'; '.join(s.issues)})" for s in sel.set_aside))
            + ".</p>")
    if sel.explored:
        out.append("<p class='note'>Exploring pairs beyond the stepwise path: " + _e("; ".join(sel.explored))
                   + ".</p>")
    if getattr(sel, "resumed", ()):
        out.append("<p class='note'>Fits continued past their budget of model evaluations: "
                   + _e("; ".join(sel.resumed)) + ".</p>")
    if getattr(sel, "reduced", ()):
        out.append("<p class='note'>Subsets of the sets within reach: " + _e("; ".join(sel.reduced)) + ".</p>")
    if getattr(sel, "replaced", ()):
        out.append("<p class='note'>Refitted around an effect the data do not identify: "
                   + _e("; ".join(sel.replaced)) + ".</p>")
    if getattr(sel, "preferred", ()):
        out.append("<p class='note'>The best set fitted, in place of the answer the search reached: "
                   + _e("; ".join(sel.preferred)) + ".</p>")
    if sel.removed:
        out.append("<p class='note'>Removed on the way: " + _e("; ".join(sel.removed)) + ".</p>")
    return "\n".join(out)


def _estimates_html(estimates) -> str:
    if not estimates:
        return "-"
    parts = []
    for e in estimates:
        txt = _e(e.describe())
        parts.append(f"<span class='bad'>{txt}</span>" if e.issue else txt)
    return "<br>".join(parts)


def _verdict_banner(items) -> str:
    """The verdict first: the improvement loop's when there is one, else the first diagnosis'."""
    from .diagnose import Diagnosis
    from .improve import Improvement

    imp = next((i for i in items if isinstance(i, Improvement)), None)
    if imp is not None and imp.verdict:
        added = ", ".join(imp.added) or "nothing"
        noise = (f"against a noise of {imp.noise:.3g} ({imp.noise_source})" if math.isfinite(imp.noise) else
                 "with the noise unknown (no independent estimate)")
        text = (f"Verdict: {imp.verdict.replace('_', ' ').upper()} -- effects added: {added}; RMSE "
                f"{imp.rmse[0]:.4g} -> {imp.rmse[-1]:.4g} {noise}. {imp.stopped}.")
        if imp.final is not None:
            text += " " + imp.final.reason + "".join(" " + t for t in (imp.final.calibration, imp.final.outliers,
                                                                       imp.final.localized) if t)
        sel = imp.selection
        if sel is not None and sel.supported:
            text += (" Equally supported (within 10 BIC units): " + ", ".join(s.label for s in sel.supported)
                     + "; see the measurement that separates them below.")
        return f"<div class='verdict v-{_e(imp.verdict)}'>{_e(text)}</div>"
    dx = next((i for i in items if isinstance(i, Diagnosis)), None)
    if dx is not None and dx.verdict is not None:
        return f"<div class='verdict v-{_e(dx.verdict.verdict)}'>{_e(dx.verdict.headline)}</div>"
    return ""


def _steps_table(steps) -> str:
    rows = []
    for s in steps:
        rows.append([_num(s.index, "d"), _e(s.describe()), _e(", ".join(s.alternatives) or "-"),
                     _e(", ".join(s.effects) or "none"), _num(s.rmse), _num(s.delta_bic, "+.1f"),
                     _num(s.lack_of_fit_p, ".2g"), _estimates_html(s.estimates)])
    return _table(["step", "change", "or as well by", "effects", "RMSE (refitted)", "delta BIC", "lack-of-fit p",
                   "fitted parameters"], rows, left=(1, 2, 3, 7))


def _improvement_html(imp) -> str:
    out = [f"<h2>Watch the error fall{(' (' + _e(imp.name) + ')') if imp.name else ''}</h2>",
           "<p class='note'>Each step: the model with every effect so far, its fitted parameters refitted to the "
           "measurements (step 0 is the baseline with its <code>[model] fit</code> parameters refitted).</p>"]
    out.append(_steps_table(imp.steps))
    noise = (f"noise level {_num(imp.noise)} (from {_e(imp.noise_source)})" if math.isfinite(imp.noise) else
             "noise unknown (no independent estimate)")
    out.append(f"<p>Verdict: <b>{_e(imp.verdict)}</b>; {noise}; stopped: {_e(imp.stopped)}.</p>")
    if imp.selection is not None:
        out.append(_selection_html(imp.selection))
    for name, fig in imp.figures().items():
        out.append(_img(fig, f"improvement {name}"))
    final = imp.comparison(-1)
    what = ", ".join(final.effects) or "none"
    if len(imp.steps) == 1:
        what += "; nothing added: the baseline refitted"
    out.append(f"<h3>Final model ({_e(what)}): RMSE {_num(final.rmse)}</h3>")
    out.append(_band_caption_html(final))
    for name, fig in final.figures().items():
        out.append(_img(fig, f"final {name}"))
    return "\n".join(out)


def _best_model_html(dx) -> str:
    """The diagnosis' best model (the best set of effects, else the explaining candidate, else the refitted
    baseline) against the measurements, its curves with their 68 % band: the final model when no improvement
    loop ran."""
    from . import plots
    from .band import band_note
    from .compare import comparison_from
    from .predict import Prediction

    b = dx.baseline
    if dx.selection is not None:
        s = dx.selection.best
        what, model, contact, mu, cov, est = (f"the best set of effects, {s.label}", s.model, s.contact,
                                              s.predicted, s.covariance, s.estimates)
    elif dx.explaining is not None:
        c = dx.explaining
        what, model, contact, mu, cov, est = (f"the baseline with {c.effect}, which explains the data", c.model,
                                              c.contact, c.predicted, c.covariance,
                                              tuple(c.baseline_estimates) + tuple(c.estimates))
    else:
        what, model, contact, mu, cov, est = ("the baseline refitted (no candidate explains the data)", b.model,
                                              b.contact, b.predicted, None if b.fit is None else b.fit.covariance,
                                              b.estimates)
    m = dx.measurements
    cmp = comparison_from(model, m, contact or dx.contact, Prediction(mu=mu, mu_local=mu),
                          name=f"{dx.name} best model" if dx.name else "best model", covariance=cov,
                          band_note=band_note(cov, tuple(e.key for e in est)))
    out = [f"<h3>Best model: {_e(what)}: RMSE {_num(cmp.rmse)}</h3>", _band_caption_html(cmp),
           _img(plots.plot_mu_speed(cmp), "best model mu_speed")]
    if m.has_slip_rows:
        out.append(_img(plots.plot_mu_slip(cmp), "best model mu_slip"))
    return "\n".join(out)


def _band_caption_html(cmp) -> str:
    """The caption of a fitted model's figures: what the shaded band is, or why there is none."""
    from .band import band_caveat

    if cmp.has_band:
        keys = ", ".join(cmp.covariance.keys)
        caveat = band_caveat(cmp.covariance)
        return ("<p class='note'>Points: measured" + (" with error bars of &plusmn; mu_std" if
                                                      cmp.measurements.mu_std is not None else "")
                + "; lines: the model; shaded: its <b>68 % (1 sigma) band</b> from the covariance of its fitted "
                f"parameters ({_e(keys)}) by the delta method, J C J<sup>T</sup> with J the central-difference "
                "derivative of each curve with respect to the fitted parameters through the fit's own prediction "
                "path (Bard, Nonlinear Parameter Estimation (1974); Seber &amp; Wild, Nonlinear Regression (1989), "
                "ch. 5). It shows the uncertainty of the model, not the scatter of the measurements."
                + (f" Note: {_e(caveat)}." if caveat else "") + "</p>")
    note = cmp.band_note or "no uncertainty band"
    return f"<p class='note'>{_e(note[0].upper() + note[1:])}.</p>"


