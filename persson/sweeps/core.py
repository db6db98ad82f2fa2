"""Parameter grids and length-scale band studies: build the tasks, run them, assemble the tidy table."""

from __future__ import annotations

import dataclasses
import itertools
import math
import threading
import time
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..engine.conditions import Conditions
from .._checks import number
from ..errors import InputError
from ..engine.model import Model
from ..engine.results import FLASH_RISE_COMMENT
from .bands import (_BandRestriction, band_contributions, band_edges, check_bands, continuous_cells,
                    interp_ln_q, load_share)
from .execute import Progress, SweepInterrupted, describe_scheduler, run_tasks
from .params import CONDITIONS, apply_parameters, canonical, parse_values
from .table import Table

__all__ = ["grid", "bands", "OUTPUTS", "BAND_MODES"]

#: Output columns every sweep table has.
OUTPUTS = ("mu", "mu_hysteresis", "mu_adhesion", "contact_area")
#: Band modes: restrict the full surface's integrand (a), each band a surface of its own (b), or both.
BAND_MODES = ("restrict", "separate", "both")

_CHECKPOINT_INTERVAL_S = 2.0
# warnings.catch_warnings swaps process-wide state (not thread-safe before Python 3.14): tasks running in threads
# of one process (Dask worker threads, a thread pool) and the re-issuing of their warnings take this lock, so
# that each task records only its own warnings and none is lost. Each task is parallel inside (numba, over the
# speeds), so the cores stay busy.
_WARNINGS_LOCK = threading.RLock()


def grid(model, params=None, *, speed=1.0, temperature: float = 20.0, pressure: float = 0.3e6,
         bands=None, n_bands: int | None = None, band_mode: str | None = None, scheduler=None,
         workers: int | None = None, progress=None, checkpoint=None, partial=None) -> Table:
    """Friction over a grid of parameter values: one row per point (and speed, and band), as a tidy table.

    Parameters
    ----------
    model : persson.Model
        The baseline model; each point is a copy with the swept parameters set.
    params : mapping, optional
        Parameter name -> values (a sequence, or text ``lo:hi:n``, ``lo:hi:n:log``, ``v1,v2``); the grid is
        the Cartesian product in the order given. Names: ``speed``, ``temperature``, ``pressure``, ``nu``,
        ``gamma``, ``grid.<field>``, ``surface.<name>`` (``hurst``, ``hrms``, ``q0``, ``q1``...),
        ``material.<name>`` (nested: ``material.wlf.C1``), ``<effect>.<parameter>`` (``adhesion.tau_f0``);
        see :mod:`persson.sweeps.params`. A list of ``"name=values"`` strings is accepted too.
    speed : float or array_like
        Sliding speed(s), m/s, unless ``params`` sweeps ``speed``. All speeds of a point are one engine call.
    temperature, pressure : float
        Background temperature (deg C) and nominal pressure (Pa), unless swept.
    bands : str or array_like, optional
        Also split each point by length-scale band: a kind of :func:`persson.sweeps.band_edges`
        (``"decades"``, ``"linear_q"``, ``"linear_length"``), explicit edges or pairs (rad/m), or
        ``"continuous"`` (one row per wavevector node with ``dmu_dlog10q``). Edges of the named kinds follow
        each point's own range [q0, q1] (after the effects that change the surface).
    n_bands : int, optional
        Number of bands of a named kind.
    band_mode : {"restrict", "separate", "both"}, optional
        Mode (a), mode (b) or both (default ``"both"``; ``"restrict"`` for ``"continuous"``).
    scheduler : None, "serial", "processes", str or distributed.Client or Executor
        Where the tasks run: serially (default), local processes, a Dask scheduler address
        (``"tcp://host:8786"``) or a ``distributed.Client``, or any :class:`concurrent.futures.Executor`.
        The results are identical. Local processes are started with ``spawn`` (``fork`` is unsafe once
        numba's OpenMP threads run), so a script using them needs the usual ``if __name__ == "__main__":``
        guard, as with any multiprocessing or Dask code.
    workers : int, optional
        Number of processes for ``scheduler="processes"`` (default: CPU count).
    progress : None, bool or callable
        Progress bar on stderr: None shows it on sweeps that run longer than 2 s; ``progress(done, total)``
        is called after each task when a callable.
    checkpoint : path, optional
        CSV rewritten atomically (at most every 2 s, and at the end or on interruption) with the rows
        finished so far.
    partial : path, optional
        CSV written (atomically) with the rows finished so far when the sweep stops early, by an exception or
        Ctrl-C, and nothing else; a complete sweep leaves it alone. The command line puts it beside the output
        (``out.partial.csv``) so that an interrupted run keeps the previous output intact.

    Returns
    -------
    Table
        Columns: ``point`` (index of the parameter combination), the swept model parameters by name,
        ``speed_m_s``, ``temperature_C``, ``pressure_Pa``; with bands ``mode`` (``total``, ``restrict`` or
        ``separate``), ``band`` (-1 for the total), ``q_low``, ``q_high`` (rad/m); with ``"continuous"``
        ``q`` and ``dmu_dlog10q``; then ``mu``, ``mu_hysteresis``, ``mu_adhesion``, ``contact_area``, with
        bands ``fraction`` (band mu_hysteresis / total mu_hysteresis of the point and speed; NaN where that
        total is 0, and in a partial table for ``separate`` rows whose point's total had not finished),
        ``max_flash_temperature_K`` (the flash temperature rise above ``temperature_C``, K) and ``converged``.
        Rows are in task order whatever the scheduler.

        Band rows: in ``restrict`` rows ``mu_hysteresis`` is the band's share of the full surface's hysteresis
        (tiling bands add up to the total), ``contact_area`` is the full surface's A/A0 at ``q_high`` (the
        area seen at that magnification), and ``mu_adhesion`` is the full adhesion term for the band that ends
        at q1 (in Persson's theory adhesion acts on the contact area at the shortest scale q1) and 0 for the
        others; ``mu = mu_hysteresis + mu_adhesion``. Other friction terms are not attributed to bands (they
        are in the ``total`` rows). In ``separate`` rows every output is that of the band as a surface of
        its own.

    Raises
    ------
    InputError
        Unknown parameter name, malformed range, empty band or band outside [q0, q1], bad mode or scheduler,
        before anything runs.
    SweepInterrupted
        On Ctrl-C (KeyboardInterrupt): carries the partial table (``.table``); the checkpoint holds it too.
    """
    if not isinstance(model, Model):
        raise InputError(f"model: expected a persson.Model, got {type(model).__name__}")
    values = _parse_params(params)
    if "speed" in values:
        speeds = _speeds(values.pop("speed"), "params['speed']")
    else:
        speeds = _speeds(speed, "speed")
    names = list(values)
    model_cols = [n for n in names if n not in CONDITIONS]
    continuous = isinstance(bands, str) and bands.strip().lower() == "continuous"
    mode = _mode(band_mode, bands, continuous)

    tasks: list[_Task] = []
    combos = list(itertools.product(*(values[n] for n in names))) if names else [()]
    for point, combo in enumerate(combos):
        setting = dict(zip(names, (float(x) for x in combo)))
        T = number(setting.get("temperature", temperature), "temperature")
        p = number(setting.get("pressure", pressure), "pressure")
        if p <= 0:
            raise InputError(f"pressure: expected a nominal pressure > 0 Pa, got {p:g}")
        m = apply_parameters(model, setting)
        inputs = {n: setting[n] for n in model_cols}
        edges = None
        if bands is not None and not continuous:
            edges = band_edges(bands, effective_q_range(m, speeds, T, p), n_bands)
        common = dict(point=point, inputs=inputs, model=m, speeds=speeds, temperature=T, pressure=p)
        tasks.append(_Task(role="full", edges=edges if mode in ("restrict", "both") else None,
                           banded=bands is not None, continuous=continuous, **common))
        if edges is not None and mode in ("separate", "both"):
            for b, (qa, qb) in enumerate(edges):
                tasks.append(_Task(role="separate", band=b, q_low=float(qa), q_high=float(qb), banded=True,
                                   **common))

    header = _comments(model, names, speeds, bands, n_bands, mode, scheduler, workers, len(combos))
    results: dict[int, dict] = {}
    ckpt = _Checkpoint(checkpoint, tasks, results, header, model_cols)
    bar = Progress(len(tasks), progress)
    try:
        run_tasks(_run_task, tasks, results, scheduler=scheduler, workers=workers, progress=bar,
                  on_result=ckpt.update)
    except KeyboardInterrupt as exc:
        bar.close()
        table = _assemble(tasks, results, header, model_cols, partial=True)
        path = ckpt.write(table)
        _write_partial(partial, table)
        raise SweepInterrupted(table, len(results), len(tasks), path) from exc
    except BaseException:
        bar.close()
        table = _assemble(tasks, results, header, model_cols, partial=True)
        ckpt.write(table)
        _write_partial(partial, table)
        raise
    bar.close()
    table = _assemble(tasks, results, header, model_cols, partial=False)
    ckpt.write(table)
    return table


def bands(model, kind="decades", n: int | None = None, mode: str | None = None, *, speed=1.0,
          temperature: float = 20.0, pressure: float = 0.3e6, params=None, scheduler=None,
          workers: int | None = None, progress=None, checkpoint=None, partial=None) -> Table:
    """Contribution of each length-scale band to the friction, in mode (a), mode (b) or both.

    Parameters
    ----------
    model : persson.Model
    kind : str or array_like
        ``"decades"`` (logarithmic length-scale bands), ``"linear_q"``, ``"linear_length"``, ``"continuous"``
        (d mu / d log10 q at every wavevector node), or explicit edges ``[q0, q1, ...]`` / pairs
        ``[[qa, qb], ...]`` in rad/m (see :func:`persson.sweeps.band_edges`).
    n : int, optional
        Number of bands of a named kind (``"decades"``: default one per decade spanned, rounded).
    mode : {"restrict", "separate", "both"}, optional
        (a) ``"restrict"``: the full surface's integrand over the band (bands add up to the total);
        (b) ``"separate"``: each band as a surface of its own (adds up to at least the total);
        default ``"both"`` (``"restrict"`` for ``"continuous"``).
    speed, temperature, pressure, params, scheduler, workers, progress, checkpoint, partial
        As in :func:`grid` (``params`` adds a parameter grid: bands at every point).

    Returns
    -------
    Table
        See :func:`grid`: rows ``mode="total"`` (band -1) and one row per band, mode and speed (per point).

    Examples
    --------
    >>> import surfaces, materials, persson
    >>> from persson import sweeps
    >>> m = persson.Model(surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6),
    ...                   materials.ConstantModulus(5e6, 2e6), gamma=1.0)
    >>> t = sweeps.bands(m, "decades", mode="restrict", speed=1.0)
    >>> a = t.where(mode="restrict")["mu_hysteresis"].sum(); total = t.where(mode="total")["mu_hysteresis"][0]
    >>> bool(abs(a / total - 1) < 1e-12)
    True
    """
    return grid(model, params, speed=speed, temperature=temperature, pressure=pressure, bands=kind, n_bands=n,
                band_mode=mode, scheduler=scheduler, workers=workers, progress=progress, checkpoint=checkpoint,
                partial=partial)


def effective_q_range(model, speeds, temperature: float, pressure: float) -> tuple[float, float]:
    """The wavevector range [q0, q1] the engine integrates over: ``surface.q_range`` after the effects'
    ``transform_conditions`` and ``transform_surface`` hooks (as in :meth:`persson.Model.friction`)."""
    v = np.atleast_1d(np.asarray(speeds, dtype=float))
    cond = Conditions(speed=v, temperature=float(temperature), pressure=float(pressure),
                      nominal_pressure=float(pressure))
    for e in model.effects:
        cond = e.transform_conditions(cond)
    s = model.surface
    for e in model.effects:
        s = e.transform_surface(s, cond)
    lo, hi = (float(x) for x in s.q_range)
    return lo, hi


# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class _Task:
    point: int
    inputs: dict
    model: Model
    speeds: np.ndarray
    temperature: float
    pressure: float
    role: str  # "full" or "separate"
    banded: bool = False
    edges: np.ndarray | None = None
    continuous: bool = False
    band: int = -1
    q_low: float = math.nan
    q_high: float = math.nan


def _run_task(task: _Task) -> dict:
    """Compute one task (runs in a worker): {"columns": {...}, "notes": (...), "warnings": ((category, text),)}.

    Warnings raised by the engine are recorded and re-issued in the calling process, so a sweep on a cluster
    warns as a serial one does.
    """
    with _WARNINGS_LOCK, warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = _compute(task)
    seen = []
    for w in caught:
        item = (w.category, str(w.message))
        if item not in seen:
            seen.append(item)
    out["warnings"] = tuple(seen)
    return out


def _compute(task: _Task) -> dict:
    v = task.speeds
    nv = v.size
    if task.role == "separate":
        m = task.model.replace(effects=task.model.effects + (_BandRestriction(q_low=task.q_low,
                                                                              q_high=task.q_high),))
        r = m.friction(v, temperature=task.temperature, pressure=task.pressure)
        rows = _Rows(task, nv)
        rows.add("separate", task.band, task.q_low, task.q_high, r.mu, r.mu_hysteresis, r.mu_adhesion,
                 r.contact_area, np.full(nv, math.nan), r.max_flash_temperature, r.converged)
        return {"columns": rows.columns, "notes": tuple(r.notes)}

    model = task.model
    if task.edges is not None:
        # band edges as wavevector nodes: band contributions are then exact interval sums of the engine
        g = model.grid
        model = model.replace(grid=dataclasses.replace(g, extra_q=g.extra_q + tuple(np.ravel(task.edges))))
    r = model.friction(v, temperature=task.temperature, pressure=task.pressure)
    rows = _Rows(task, nv)
    q = r.q
    mu_h = np.atleast_1d(r.mu_hysteresis)
    mu_a = np.atleast_1d(r.mu_adhesion)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv_total = np.where(mu_h != 0.0, 1.0 / mu_h, math.nan)
    if not task.banded:
        rows.add(None, None, None, None, r.mu, r.mu_hysteresis, r.mu_adhesion, r.contact_area, None,
                 r.max_flash_temperature, r.converged)
        return {"columns": rows.columns, "notes": tuple(r.notes)}
    if task.continuous:
        cells = continuous_cells(q)
        contrib = band_contributions(r, cells)
        dlog10 = np.atleast_2d(r.dmu_dlnq) * math.log(10.0) * load_share(r)[:, None]
        for b, (qa, qb) in enumerate(cells):
            adh = mu_a if b == len(cells) - 1 else np.zeros(nv)
            rows.add("restrict", b, qa, qb, contrib[:, b] + adh, contrib[:, b], adh, np.atleast_2d(r.area_q)[:, b],
                     contrib[:, b] * inv_total, r.max_flash_temperature, r.converged,
                     extra={"q": np.full(nv, q[b]), "dmu_dlog10q": dlog10[:, b]})
        return {"columns": rows.columns, "notes": tuple(r.notes)}
    rows.add("total", -1, q[0], q[-1], r.mu, r.mu_hysteresis, r.mu_adhesion, r.contact_area, np.ones(nv),
             r.max_flash_temperature, r.converged)
    if task.edges is not None:
        edges = check_bands(task.edges, (q[0], q[-1]))
        contrib = band_contributions(r, edges)
        area = interp_ln_q(q, r.area_q, edges[:, 1])
        for b, (qa, qb) in enumerate(edges):
            adh = mu_a if qb >= q[-1] * (1 - 1e-9) else np.zeros(nv)
            rows.add("restrict", b, qa, qb, contrib[:, b] + adh, contrib[:, b], adh, area[:, b],
                     contrib[:, b] * inv_total, r.max_flash_temperature, r.converged)
    return {"columns": rows.columns, "notes": tuple(r.notes)}


class _Rows:
    """Accumulates the rows of one task, column by column."""

    def __init__(self, task: _Task, nv: int):
        self.task = task
        self.nv = nv
        self.columns: dict[str, list] = {}

    def add(self, mode, band, q_low, q_high, mu, mu_h, mu_a, area, fraction, flash, converged, extra=None):
        t, nv = self.task, self.nv
        cols = {"point": np.full(nv, t.point, dtype=np.int64)}
        for k, x in t.inputs.items():
            cols[k] = np.full(nv, x)
        cols["speed_m_s"] = t.speeds
        cols["temperature_C"] = np.full(nv, t.temperature)
        cols["pressure_Pa"] = np.full(nv, t.pressure)
        if mode is not None:
            cols["mode"] = np.array([mode] * nv, dtype=object)
            cols["band"] = np.full(nv, band, dtype=np.int64)
            cols["q_low"] = np.full(nv, float(q_low))
            cols["q_high"] = np.full(nv, float(q_high))
        for k, x in (extra or {}).items():
            cols[k] = np.asarray(x, dtype=float)
        cols["mu"] = _vec(mu, nv)
        cols["mu_hysteresis"] = _vec(mu_h, nv)
        cols["mu_adhesion"] = _vec(mu_a, nv)
        cols["contact_area"] = _vec(area, nv)
        if fraction is not None:
            cols["fraction"] = _vec(fraction, nv)
        cols["max_flash_temperature_K"] = _vec(flash, nv)
        cols["converged"] = np.full(nv, bool(converged))
        for k, a in cols.items():
            self.columns.setdefault(k, []).append(a)


def _vec(x, nv: int) -> np.ndarray:
    return np.broadcast_to(np.atleast_1d(np.asarray(x, dtype=float)), (nv,)).copy()


def _assemble(tasks, results: dict, header: tuple, model_cols, partial: bool) -> Table:
    """The table of the finished tasks, in task order; fills ``fraction`` of ``separate`` rows."""
    done = [i for i in range(len(tasks)) if i in results]
    if not done:
        return Table({}, header + (("PARTIAL: no task finished",) if partial else ()))
    names = list(results[done[0]]["columns"])
    cols = {n: np.concatenate([a for i in done for a in results[i]["columns"][n]]) for n in names}
    if "mode" in cols and "fraction" in cols:
        totals = {}
        is_total = cols["mode"] == "total"
        for pt, v, mh in zip(cols["point"][is_total], cols["speed_m_s"][is_total],
                             cols["mu_hysteresis"][is_total]):
            totals[(int(pt), float(v))] = mh
        sep = np.flatnonzero(cols["mode"] == "separate")
        for j in sep:
            tot = totals.get((int(cols["point"][j]), float(cols["speed_m_s"][j])), math.nan)
            cols["fraction"][j] = cols["mu_hysteresis"][j] / tot if tot != 0.0 else math.nan
    notes = []
    for i in done:
        for note in results[i]["notes"]:
            if note not in notes:
                notes.append(note)
    warned = []
    for i in done:
        for _, text in results[i].get("warnings", ()):
            if text not in warned:
                warned.append(text)
    comments = header + tuple(f"note: {n}" for n in notes) + tuple(f"warning: {w}" for w in warned)
    if partial and len(done) < len(tasks):
        comments += (f"PARTIAL: {len(done)} of {len(tasks)} tasks finished (sweep interrupted or failed)",)
    return Table(cols, comments)


class _Checkpoint:
    """As tasks finish: re-issues their warnings here and rewrites the checkpoint CSV atomically (throttled)."""

    def __init__(self, path, tasks, results, header, model_cols):
        self.path = None if path is None else Path(path)
        self.tasks, self.results, self.header, self.model_cols = tasks, results, header, model_cols
        self.last = time.monotonic()
        self.warned: list = []

    def update(self, i, res):
        for category, text in res.get("warnings", ()):
            if (category, text) not in self.warned:
                self.warned.append((category, text))
                with _WARNINGS_LOCK:
                    warnings.warn(f"sweep {_describe(self.tasks[i])}: {text}", category, stacklevel=5)
        if self.path is None:
            return
        now = time.monotonic()
        if now - self.last >= _CHECKPOINT_INTERVAL_S:
            self.last = now
            self.write(_assemble(self.tasks, self.results, self.header, self.model_cols, partial=True))

    def write(self, table: Table):
        if self.path is None or len(table) == 0:
            return None
        return table.to_csv(self.path, overwrite=True)  # the checkpoint is rewritten as the sweep runs


def _write_partial(path, table: Table) -> None:
    """The finished rows of a sweep that stopped early (nothing when no row finished)."""
    if path is not None and len(table):
        table.to_csv(path, overwrite=True)


def _describe(task: _Task) -> str:
    text = f"point {task.point}" + "".join(f", {k} = {v:g}" for k, v in task.inputs.items())
    text += f", T = {task.temperature:g} C, p = {task.pressure:g} Pa"
    if task.role == "separate":
        text += f", band {task.band} [{task.q_low:.4g}, {task.q_high:.4g}] rad/m as a surface of its own"
    return text


def _parse_params(params) -> dict:
    if params is None:
        return {}
    if isinstance(params, str):
        params = [params]
    out: dict[str, np.ndarray] = {}
    if isinstance(params, dict):
        items = list(params.items())
    else:
        from .params import parse_param

        try:
            items = [parse_param(s, "params") for s in params]
        except TypeError:
            raise InputError(f"params: expected a mapping name -> values, got {params!r}") from None
    for raw, vals in items:
        name = canonical(raw)
        if name in out:
            raise InputError(f"params: parameter {name!r} given twice")
        out[name] = parse_values(vals, f"params[{raw!r}]")
    return out


def _speeds(speed, argument: str) -> np.ndarray:
    try:
        v = np.atleast_1d(np.asarray(speed, dtype=float)).ravel()
    except (TypeError, ValueError):
        raise InputError(f"{argument}: expected sliding speeds in m/s, got {speed!r}") from None
    if v.size == 0 or not np.all(np.isfinite(v)) or np.any(v <= 0):
        raise InputError(f"{argument}: expected finite sliding speeds > 0 m/s, got {speed!r}")
    return np.ascontiguousarray(v)


def _mode(band_mode, bands, continuous: bool) -> str | None:
    if bands is None:
        if band_mode is not None:
            raise InputError("band_mode: only meaningful with bands=...")
        return None
    if band_mode is None:
        return "restrict" if continuous else "both"
    if band_mode not in BAND_MODES:
        raise InputError(f"band_mode: expected one of {list(BAND_MODES)}, got {band_mode!r}")
    if continuous and band_mode != "restrict":
        raise InputError("band_mode: 'continuous' bands are cells of the full surface's integrand (mode "
                         f"'restrict'); mode {band_mode!r} is not defined for them")
    return band_mode


def _comments(model, names, speeds, bands, n_bands, mode, scheduler, workers, n_points) -> tuple:
    s = model.surface
    out = [f"persson sweep: {n_points} point(s) x {speeds.size} speed(s)"
           + (f" over {', '.join(names)}" if names else ""),
           f"surface: {getattr(s, 'source', '') or type(s).__name__}; q_range = "
           f"[{s.q_range[0]:.6g}, {s.q_range[1]:.6g}] rad/m",
           f"material: {getattr(model.material, 'label', '') or type(model.material).__name__}",
           f"effects: {', '.join(model.effect_names) or 'none'}; nu = {model.nu:g}, gamma = {model.gamma:g}"]
    if bands is not None:
        kind = bands if isinstance(bands, str) else "explicit edges"
        out.append(f"bands: {kind}" + (f" (n = {n_bands})" if n_bands else "") + f"; mode: {mode}")
    out.append(f"run: {describe_scheduler(scheduler, workers)}")
    out.append(FLASH_RISE_COMMENT)
    return tuple(out)
