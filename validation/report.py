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
img{max-width:100%;border:1px solid #ddd;margin:0.5em 0}p.expl{white-space:pre-wrap;background:#fafafa;
border-left:4px solid #4a7;padding:0.6em 1em}
"""


def write_report(items, path, title: str | None = None) -> Path:
    """Write one self-contained HTML report of ``items``, atomically.

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

    Returns
    -------
    Path
    """
    text = render_report(items, title=title)
    from persson.io import atomic_write

    path = Path(path)
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
            body.append(_diagnosis_html(it))
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
        fig.savefig(buf, format="png", dpi=90)
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
    out.append(_table(["effects", "rows", "RMSE", "bias", "max |residual|", "chi2 / n"],
                      [[_e(", ".join(cmp.effects) or "none"), _num(cmp.n, "d"), _num(cmp.rmse), _num(cmp.bias, "+.4g"),
                        _num(cmp.max_abs), _num(None if cmp.chi2 is None else cmp.chi2 / cmp.n)]], left=(0,)))
    for note in cmp.notes:
        out.append(f"<p class='note'>Note: {_e(note)}</p>")
    for name, fig in cmp.figures().items():
        out.append(_img(fig, f"{cmp.name} {name}"))
    out.append("<h3>Where the model fails</h3><p class='note'>Groups with |z| &ge; 3 (bias larger than three "
               "standard errors) are marked.</p>")
    for factor, rows in cmp.tables.items():
        if not rows:
            continue
        out.append(f"<h4>by {_e(factor)}</h4>")
        out.append(_table([factor, "n", "measured", "predicted", "bias", "RMSE", "z"],
                          [[_e(g.label), _num(g.n, "d"), _num(g.measured, ".3f"), _num(g.predicted, ".3f"),
                            _num(g.bias, "+.3f"), _num(g.rmse, ".3f"), _num(g.z, "+.1f")] for g in rows],
                          classes=["bad" if abs(g.z) >= 3 else "" for g in rows]))
    return "\n".join(out)


def _diagnosis_html(dx) -> str:
    b = dx.baseline
    out = [f"<h2>Diagnosis: which effect is missing{(' (' + _e(dx.name) + ')') if dx.name else ''}</h2>"]
    out.append(f"<p>Baseline: {_e(', '.join(b.effects) or 'hysteresis only')}; RMSE {_num(b.rmse)}"
               + (f"; refitted {_e(', '.join(f'{k} = {v:.4g}' for k, v in b.fitted.items()))}" if b.fitted else "")
               + f"; BIC {_num(b.bic, '.1f')}. Rule: {_e(dx.rule)}.</p>")
    rows, classes = [], []
    for i, c in enumerate(dx.candidates, 1):
        par = ", ".join(f"{k} = {v:.4g}" for k, v in c.parameters.items() if k in c.free) or "-"
        if c.status != "ok":
            rows.append([_num(i, "d"), _e(c.effect), "-", "-", "-", "-", "-", "no", _e(c.status)])
        else:
            rows.append([_num(i, "d"), _e(c.effect), _num(c.rmse), _num(c.delta_bic, "+.1f"), _num(c.p_value, ".2g"),
                         _num(c.score_z, "+.1f"), _num(100 * c.explained, ".0f") + " %",
                         "YES" if c.significant else "no", _e(par)])
        classes.append("sig" if c.significant else "")
    out.append(_table(["rank", "effect", "RMSE", "delta BIC", "p", "score z", "explained", "significant",
                       "refitted parameters"], rows, left=(1, 8), classes=classes))
    out.append(f"<p class='expl'>{_e(dx.explanation)}</p>")
    for cl in dx.clusters:
        out.append(f"<h4>Ambiguity cluster: {_e(', '.join(cl.effects))}</h4>")
        srows = [[_e(" vs ".join(s.effects)), _num(s.speed * s.slip, ".3g"), _num(s.slip, "g"),
                  _num(s.temperature, "g"), _num(s.pressure / 1e6, "g"), _e("yes" if s.in_range else "no"),
                  _num(s.mu[0], ".3f"), _num(s.mu[1], ".3f")]
                 for s in tuple(cl.separations) + tuple(cl.separations_in_range)]
        if srows:
            out.append(_table(["pair", "sliding speed (m/s)", "slip", "T (C)", "p (MPa)", "inside data",
                               "mu (first)", "mu (second)"], srows))
    for name, fig in dx.figures().items():
        out.append(_img(fig, f"diagnosis {name}"))
    return "\n".join(out)


def _steps_table(steps) -> str:
    rows = []
    for s in steps:
        par = "; ".join(f"{e}: " + ", ".join(f"{k} = {v:.4g}" for k, v in p.items())
                        for e, p in s.parameters.items() if isinstance(p, dict) and p)
        rows.append([_num(s.index, "d"), _e(s.added or "(baseline)"), _e(", ".join(s.effects) or "none"),
                     _num(s.rmse), _num(s.delta_bic, "+.1f"), _e(par or "-")])
    return _table(["step", "added", "effects", "RMSE", "delta BIC", "parameters"], rows, left=(1, 2, 5))


def _improvement_html(imp) -> str:
    out = [f"<h2>Watch the error fall{(' (' + _e(imp.name) + ')') if imp.name else ''}</h2>",
           "<p class='note'>Each step: the model with every effect so far, its fitted parameters refitted to the "
           "measurements (step 0 is the baseline with its <code>[model] fit</code> parameters refitted).</p>"]
    out.append(_steps_table(imp.steps))
    out.append(f"<p>Noise level {_num(imp.noise)}; stopped: {_e(imp.stopped)}.</p>")
    for name, fig in imp.figures().items():
        out.append(_img(fig, f"improvement {name}"))
    if len(imp.steps) > 1:
        final = imp.comparison(-1)
        out.append(f"<h3>Final model ({_e(', '.join(final.effects))}): RMSE {_num(final.rmse)}</h3>")
        for name, fig in final.figures().items():
            out.append(_img(fig, f"final {name}"))
    return "\n".join(out)


