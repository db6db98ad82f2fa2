r"""Peak and locked mu along the road: three-point Magic Formula per position, with propagated uncertainties.

At each road position (a bin of ``step_m`` metres) the three tires give three (slip, mu) points, the bin means of
their reduced rows. Through them passes one Magic Formula :math:`\mu(s) = D\sin\{C\arctan(Bs)\}` (Pacejka & Bakker
1992; the simple form :math:`a\sin(b\arctan(cs))` the trailer article identifies, its offset d = 0): three
equations, three unknowns (Study on the influence of environmental conditions on road friction characteristics,
Lubricants 11(7), 277 (2023), Section 2.2 and Figures 12-14). From it

* peak mu: D, at :math:`s_p = \tan(\pi/2C)/B` when C > 1 and :math:`s_p \le 1`; otherwise the curve still
  rises at s = 1 and the peak is :math:`\mu(1)` (the profile's notes say where);
* locked mu: :math:`\mu(1)`, the extrapolation to the locked wheel.

The identification is the project's :func:`persson.tire.magic_formula_from_points` (same equations, same
parametrisation in log B, log C, log D): it identifies the pooled points of the whole road, and that curve, its D
scaled to each position's friction level, starts a batched Levenberg-Marquardt solve of all positions at once;
a position the batch does not solve to 1e-10 goes to :func:`~persson.tire.magic_formula_from_points` alone.

Uncertainties (standard deviations) are propagated linearly (GUM, JCGM 100:2008, 5.1): the standard errors of the
bin means of mu and slip (:meth:`~validation.rigs.TrailerRows.binned`) go through the implicit-function Jacobian of
the solved equations, :math:`dq = J_q^{-1}(d\mu - \mu'(s)\,ds)`, to peak mu, locked mu and the slip at the peak.
They are the noise's share only: the Magic Formula's own model error (a tire whose curve is not of that form)
is not in them. The tests check their coverage against repeated synthetic runs.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from frictioncite import doi
from persson.tire import MAGIC_FORMULA, MagicFormula, magic_formula_from_points

from ..errors import IdentificationWarning, InputError
from .align import TrailerRows, bin_rows
from .balance import TRAILER_2023

__all__ = ["peak_lock_along_road", "RoadProfile", "peak_reduction_by_pavement", "PavementReduction"]

_GUM = "jcgm:100-2008"
_PACEJKA_BOOK = "isbn:9780080970165"
#: Largest relative residual of an identified position's three equations.
_TOL = 1e-10


@doi(TRAILER_2023, MAGIC_FORMULA, _GUM)
@dataclass(frozen=True, eq=False)
class RoadProfile:
    """Peak and locked mu per road position (arrays over positions; per-tire arrays have one column per tire).

    Attributes
    ----------
    position : ndarray
        Centre of each road bin, m.
    peak_mu, peak_mu_std : ndarray
        Peak of the identified Magic Formula on 0 <= s <= 1, and its standard deviation.
    locked_mu, locked_mu_std : ndarray
        mu(s = 1), and its standard deviation.
    peak_mu_std_common, locked_mu_std_common : ndarray
        The part of those standard deviations that the zero-row offsets leave: an error shared by every position
        of the run (averaging positions does not reduce it; :func:`peak_reduction_by_pavement` keeps it apart).
    slip_at_peak, slip_at_peak_std : ndarray
        Slip of the peak (1 where the curve still rises at s = 1), and its standard deviation.
    identified : ndarray of bool
        Whether a Magic Formula was identified (the other values are NaN where not; the notes say why).
    B, C, D : ndarray
        The Magic Formula's factors (E = 0).
    slip, mu, slip_std, mu_std, n_samples : ndarray, shape (n_positions, n_tires)
        The points: bin means of each tire's slip and mu, their standard errors and sample counts.
    speed : ndarray
        Mean vehicle speed per position, m/s.
    step_m : float
        Bin length, m.
    aligned : bool
        Whether the rows were aligned (tire offsets corrected).
    source : str
        The raw file.
    notes : tuple of str
        Positions not identified and why; positions whose curve still rises at s = 1.
    """

    position: np.ndarray
    peak_mu: np.ndarray
    peak_mu_std: np.ndarray
    locked_mu: np.ndarray
    locked_mu_std: np.ndarray
    peak_mu_std_common: np.ndarray
    locked_mu_std_common: np.ndarray
    slip_at_peak: np.ndarray
    slip_at_peak_std: np.ndarray
    identified: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    slip: np.ndarray
    mu: np.ndarray
    slip_std: np.ndarray
    mu_std: np.ndarray
    n_samples: np.ndarray
    speed: np.ndarray
    step_m: float
    aligned: bool = True
    source: str = "<rows>"
    notes: tuple = ()

    def __post_init__(self):
        for name in ("position", "peak_mu", "peak_mu_std", "locked_mu", "locked_mu_std", "peak_mu_std_common",
                     "locked_mu_std_common", "slip_at_peak",
                     "slip_at_peak_std", "identified", "B", "C", "D", "slip", "mu", "slip_std", "mu_std",
                     "n_samples", "speed"):
            getattr(self, name).setflags(write=False)

    @property
    def n(self) -> int:
        """Number of positions."""
        return int(self.position.size)

    def formula(self, i: int) -> MagicFormula:
        """The Magic Formula identified at position ``i``."""
        if not self.identified[i]:
            raise InputError(f"position {self.position[i]:g} m: no Magic Formula was identified there "
                             f"(see the profile's notes)")
        return MagicFormula(B=float(self.B[i]), C=float(self.C[i]), D=float(self.D[i]))

    def as_table(self) -> dict[str, np.ndarray]:
        """Columns ``position_m, peak_mu, peak_mu_std, locked_mu, locked_mu_std, slip_at_peak, ...``."""
        cols = {"position_m": self.position, "speed_m_s": self.speed, "peak_mu": self.peak_mu,
                "peak_mu_std": self.peak_mu_std, "locked_mu": self.locked_mu, "locked_mu_std": self.locked_mu_std,
                "peak_mu_std_common": self.peak_mu_std_common, "locked_mu_std_common": self.locked_mu_std_common,
                "slip_at_peak": self.slip_at_peak, "slip_at_peak_std": self.slip_at_peak_std,
                "identified": self.identified.astype(int), "B": self.B, "C": self.C, "D": self.D}
        for j in range(self.slip.shape[1]):
            cols[f"slip_{j + 1}"] = self.slip[:, j]
            cols[f"mu_{j + 1}"] = self.mu[:, j]
            cols[f"mu_std_{j + 1}"] = self.mu_std[:, j]
            cols[f"n_{j + 1}"] = self.n_samples[:, j]
        return cols

    def two_coefficient_brush(self, *, sakai_n: float = 4.0, kinematics: str = "pacejka"):
        """The two-coefficient brush at every position (:func:`persson.slip.identify_two_coefficient`: mu_D the
        locked mu, the initial slope B C D, mu_s free; the article's Figure 18), the points' standard errors
        propagated through the three-point identification; NaN where no Magic Formula was identified."""
        from persson.slip import identify_two_coefficient

        cov = np.zeros((self.n, 3, 3))
        ok = self.identified
        if np.any(ok):  # dq = J^-1 (dm - mu'(s) ds) in q = log(B, C, D) (module docstring), then to B, C, D
            q = np.log(np.stack([self.B[ok], self.C[ok], self.D[ok]], axis=1))
            _, J, dmu_ds = _curve(q, self.slip[ok])
            Jinv = np.linalg.inv(J) * np.exp(q)[:, :, None]
            var = self.mu_std[ok] ** 2 + (dmu_ds * self.slip_std[ok]) ** 2
            cov[ok] = np.einsum("nik,nk,njk->nij", Jinv, var, Jinv)
        formulas = [self.formula(i) if ok[i] else None for i in range(self.n)]
        return identify_two_coefficient(formulas, covariance=cov, sakai_n=sakai_n, kinematics=kinematics)

    def to_csv(self, path, comments: tuple[str, ...] = (), *, overwrite: bool = False):
        """Write :meth:`as_table` (NaN where not identified) with the notes as comments, atomically."""
        from persson.io import write_csv

        head = ((f"peak and locked mu along the road from {self.source}, bins of {self.step_m:g} m, "
                 f"{'aligned' if self.aligned else 'not aligned'}"),)
        return write_csv(path, self.as_table(), comments=head + tuple(comments) + tuple(self.notes),
                         overwrite=overwrite)  # an existing file only if asked


@doi(TRAILER_2023, MAGIC_FORMULA, _PACEJKA_BOOK, _GUM)
def peak_lock_along_road(rows: TrailerRows, step_m: float = 1.0, *, start_m: float | None = None,
                         min_samples: int = 2) -> RoadProfile:
    """Peak and locked mu per road position from a three-tire run (see the module docstring).

    Parameters
    ----------
    rows : TrailerRows
        Reduced rows (:func:`~validation.rigs.reduce`) of exactly three tires at different slips; aligned rows
        put the three tires' points at the same road position.
    step_m : float
        Length of a road bin, m (several samples per tire: at 12 m/s and 100 Hz a sample every 0.12 m).
    start_m : float, optional
        Where the first bin starts (default: the first row's position); give the same value to runs over the
        same road so that their bins coincide.
    min_samples : int
        A tire needs this many samples in a bin (>= 2, for a standard error).

    Returns
    -------
    RoadProfile

    Raises
    ------
    InputError
        Not three tires, a bad ``step_m``.

    Warns
    -----
    IdentificationWarning
        Positions where too few samples fell or no Magic Formula passes through the points.
    """
    if not isinstance(rows, TrailerRows):
        raise InputError(f"rows: expected the rows of validation.rigs.reduce, got {type(rows).__name__}")
    if len(rows.tires) != 3:
        raise InputError(f"{rows.source}: the three-point identification needs three tires at different slips; "
                         f"the rows have {len(rows.tires)} ({list(rows.tires)})")
    if isinstance(min_samples, bool) or int(min_samples) != min_samples or min_samples < 2:
        raise InputError(f"min_samples: expected an integer >= 2, got {min_samples!r}")
    b = bin_rows(rows, step_m, start_m=start_m)
    used = b.n.sum(axis=1) > 0
    centre, n = b.centre[used], b.n[used]
    s, m, s_se, m_se = b.slip[used], b.mu[used], b.slip_se[used], b.mu_se[used]
    m_common = b.mu_se_common[used]
    speed = np.nansum(b.speed[used] * n, axis=1) / np.maximum(n.sum(axis=1), 1)
    order = np.argsort(np.nanmedian(s, axis=0))
    s, m, s_se, m_se, n = s[:, order], m[:, order], s_se[:, order], m_se[:, order], n[:, order]
    m_common = m_common[:, order]
    notes = []
    enough = np.all(n >= min_samples, axis=1)
    valid = enough & np.all((s > 0) & (s <= 1) & (m > 0), axis=1) & np.all(np.diff(s, axis=1) > 0, axis=1)
    if np.any(~enough):
        notes.append(f"{int(np.sum(~enough))} position(s) with fewer than {min_samples} samples of a tire: "
                     f"{_list(centre[~enough])}")
    odd = enough & ~valid
    if np.any(odd):
        notes.append(f"{int(np.sum(odd))} position(s) whose points are not three braking slips in increasing order "
                     f"in (0, 1] with mu > 0: {_list(centre[odd])}")
    q, solved = _identify(s, m, valid)
    if np.any(valid & ~solved):
        notes.append(f"{int(np.sum(valid & ~solved))} position(s) where no Magic Formula passes through the three "
                     f"points: {_list(centre[valid & ~solved])}")
    out = _characteristics(q, s, m, s_se, m_se, m_common, solved)
    rising = solved & (out["slip_at_peak"] >= 1.0)
    if np.any(rising):
        notes.append(f"{int(np.sum(rising))} position(s) whose curve still rises at s = 1 (peak = locked mu): "
                     f"{_list(centre[rising])}")
    if np.any(~solved):
        warnings.warn(f"{rows.source}: {int(np.sum(~solved))} of {solved.size} position(s) without peak and locked "
                      f"mu:\n" + "\n".join(notes), IdentificationWarning, stacklevel=2)
    B, C, D = (np.where(solved, np.exp(q[:, j]), np.nan) for j in range(3))
    return RoadProfile(position=centre, peak_mu=out["peak"], peak_mu_std=out["peak_std"], locked_mu=out["lock"],
                       locked_mu_std=out["lock_std"], peak_mu_std_common=out["peak_common"],
                       locked_mu_std_common=out["lock_common"], slip_at_peak=out["slip_at_peak"],
                       slip_at_peak_std=out["slip_at_peak_std"], identified=solved, B=B, C=C, D=D, slip=s, mu=m,
                       slip_std=s_se, mu_std=m_se, n_samples=n, speed=speed, step_m=float(step_m),
                       aligned=rows.aligned, source=rows.source, notes=tuple(notes))


@dataclass(frozen=True)
class PavementReduction:
    """The peak-mu reduction from dry to wet over one pavement.

    Attributes
    ----------
    name : str
        The pavement.
    start_m, end_m : float
        Its stretch of road.
    n_positions : int
        Positions identified in both runs.
    peak_dry, peak_wet : float
        Mean peak mu, dry and wet.
    reduction, reduction_std : float
        Mean of (dry - wet) over the positions, and its standard error: the larger of the propagated one and the
        positions' scatter over sqrt(n) (which includes the road's own variation along the stretch), combined
        with the errors that the zero offsets leave in both runs, which are shared by the positions and do not
        average out.
    relative : float
        ``reduction / peak_dry``.
    """

    name: str
    start_m: float
    end_m: float
    n_positions: int
    peak_dry: float
    peak_wet: float
    reduction: float
    reduction_std: float
    relative: float


@doi(TRAILER_2023, _GUM)
def peak_reduction_by_pavement(dry: RoadProfile, wet: RoadProfile, pavements: dict) -> tuple:
    """Peak-mu reduction from dry to wet per pavement, over the positions both runs identified.

    Parameters
    ----------
    dry, wet : RoadProfile
        Profiles of a dry and a wet run over the same road, with the same bins (same ``step_m`` and ``start_m``).
    pavements : dict
        ``{name: (start_m, end_m)}``: each pavement's stretch of road (positions ``start_m <= x < end_m``).

    Returns
    -------
    tuple of PavementReduction

    Raises
    ------
    InputError
        Bins that do not coincide, a bad stretch, a pavement without a position identified in both runs.
    """
    for name, p in (("dry", dry), ("wet", wet)):
        if not isinstance(p, RoadProfile):
            raise InputError(f"{name}: expected a RoadProfile (peak_lock_along_road), got {type(p).__name__}")
    if not math.isclose(dry.step_m, wet.step_m):
        raise InputError(f"dry and wet profiles have bins of {dry.step_m:g} and {wet.step_m:g} m: use the same "
                         "step_m (and start_m)")
    key_d = np.round(dry.position / dry.step_m, 6)
    key_w = np.round(wet.position / wet.step_m, 6)
    if not np.allclose(key_d - np.floor(key_d), key_w[0] - np.floor(key_w[0]), atol=1e-6):
        raise InputError("dry and wet profiles have bins that do not coincide: give both the same start_m")
    common, i_d, i_w = np.intersect1d(key_d, key_w, return_indices=True)
    if not isinstance(pavements, dict) or not pavements:
        raise InputError("pavements: expected {name: (start_m, end_m)}, e.g. {'asphalt': (0, 120)}")
    out = []
    for name, stretch in pavements.items():
        try:
            a, b = (float(x) for x in stretch)
        except (TypeError, ValueError):
            raise InputError(f"pavements[{name!r}]: expected (start_m, end_m), got {stretch!r}") from None
        if not b > a:
            raise InputError(f"pavements[{name!r}]: end {b:g} m must lie beyond start {a:g} m")
        x = dry.position[i_d]
        sel = (x >= a) & (x < b) & dry.identified[i_d] & wet.identified[i_w]
        if not np.any(sel):
            raise InputError(f"pavements[{name!r}]: no position in {a:g}-{b:g} m identified in both runs")
        pd, pw = dry.peak_mu[i_d][sel], wet.peak_mu[i_w][sel]
        cd, cw = dry.peak_mu_std_common[i_d][sel], wet.peak_mu_std_common[i_w][sel]
        var = (dry.peak_mu_std[i_d][sel] ** 2 - cd ** 2) + (wet.peak_mu_std[i_w][sel] ** 2 - cw ** 2)
        d = pd - pw
        k = int(d.size)
        propagated = math.sqrt(max(float(var.sum()), 0.0)) / k
        scatter = float(np.std(d, ddof=1)) / math.sqrt(k) if k > 1 else math.inf
        common = math.hypot(float(cd.mean()), float(cw.mean()))   # fully shared by the positions of a run
        mean_dry = float(pd.mean())
        out.append(PavementReduction(name=str(name), start_m=a, end_m=b, n_positions=k, peak_dry=mean_dry,
                                     peak_wet=float(pw.mean()), reduction=float(d.mean()),
                                     reduction_std=math.hypot(max(propagated, scatter), common),
                                     relative=float(d.mean()) / mean_dry))
    return tuple(out)


# ==========================================================================================================
def _identify(s: np.ndarray, m: np.ndarray, valid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """log(B, C, D) through the three points of every valid row, and which rows were solved."""
    n = s.shape[0]
    q = np.full((n, 3), np.nan)
    solved = np.zeros(n, dtype=bool)
    if not np.any(valid):
        return q, solved
    ref = _project_identification(np.median(s[valid], axis=0), np.median(m[valid], axis=0))
    if ref is None:  # the pooled points admit no curve: start every row from its own identification
        ref_q, ref_level = None, None
    else:
        ref_q, ref_level = np.log([ref.B, ref.C, ref.D]), float(np.median(m[valid], axis=0).mean())
    rows = np.flatnonzero(valid)
    if ref_q is not None:
        start = np.tile(ref_q, (rows.size, 1))
        start[:, 2] += np.log(m[rows].mean(axis=1) / ref_level)
        q[rows], solved[rows] = _levenberg_marquardt(start, s[rows], m[rows])
    for i in np.flatnonzero(valid & ~solved):
        f = _project_identification(s[i], m[i])
        if f is not None:
            q[i] = np.log([f.B, f.C, f.D])
            solved[i] = True
    return q, solved


def _project_identification(s, m):
    try:
        return magic_formula_from_points(s, m)
    except InputError:
        return None


def _curve(q, s):
    """mu(s) and its derivatives in log B, log C, log D and in s (q: (n, 3), s: (n, k))."""
    B, C, D = (np.exp(q[:, j])[:, None] for j in range(3))
    x = B * s
    phi = np.arctan(x)
    u = C * phi
    mu = D * np.sin(u)
    dcos = D * np.cos(u)
    jac = np.stack([dcos * C * x / (1.0 + x * x), dcos * C * phi, mu], axis=-1)
    return mu, jac, dcos * C * B / (1.0 + x * x)


def _levenberg_marquardt(q, s, m, iterations: int = 200):
    """Solve mu(s_i; q) = m_i (relative residuals) for every row at once; returns (q, converged)."""
    q = q.copy()
    lam = np.full(q.shape[0], 1e-3)
    mu, jac, _ = _curve(q, s)
    r = mu / m - 1.0
    cost = np.sum(r * r, axis=1)
    eye = np.eye(3)
    for _ in range(iterations):
        active = np.max(np.abs(r), axis=1) > _TOL
        if not active.any():
            break
        J = jac[active] / m[active][:, :, None]
        JtJ = np.einsum("nij,nik->njk", J, J)
        g = np.einsum("nij,ni->nj", J, r[active])
        A = JtJ + lam[active][:, None, None] * (JtJ * eye + 1e-12 * eye)
        try:
            step = -np.linalg.solve(A, g[..., None])[..., 0]
        except np.linalg.LinAlgError:
            step = -np.einsum("njk,nk->nj", np.linalg.pinv(A), g)
        step = np.clip(step, -2.0, 2.0)  # log factors: at most a factor e^2 per step
        trial = q[active] + step
        mu_t, jac_t, _ = _curve(trial, s[active])
        r_t = mu_t / m[active] - 1.0
        cost_t = np.sum(r_t * r_t, axis=1)
        better = np.isfinite(cost_t) & (cost_t < cost[active])
        idx = np.flatnonzero(active)
        up = idx[better]
        q[up], r[up], cost[up], jac[up] = trial[better], r_t[better], cost_t[better], jac_t[better]
        lam[up] = np.maximum(lam[up] / 3.0, 1e-12)
        lam[idx[~better]] *= 4.0
        if np.all(lam[active] > 1e12):
            break
    converged = (np.max(np.abs(r), axis=1) <= _TOL) & np.all(np.isfinite(q), axis=1)
    return q, converged


def _characteristics(q, s, m, s_se, m_se, m_common, solved):
    """Peak, locked mu and peak slip with their linearly propagated standard deviations (total, and the part
    from the errors shared by all positions)."""
    n = q.shape[0]
    nan = np.full(n, np.nan)
    out = {k: nan.copy() for k in ("peak", "peak_std", "lock", "lock_std", "slip_at_peak", "slip_at_peak_std",
                                   "peak_common", "lock_common")}
    if not np.any(solved):
        return out
    qq = q[solved]
    B, C, D = (np.exp(qq[:, j]) for j in range(3))
    lock, g_lock, _ = _curve(qq, np.ones((qq.shape[0], 1)))
    lock, g_lock = lock[:, 0], g_lock[:, 0, :]
    with np.errstate(invalid="ignore", divide="ignore"):
        half = np.pi / (2.0 * C)
        sp = np.where(C > 1.0, np.tan(half) / B, np.inf)
    interior = sp <= 1.0
    peak = np.where(interior, D, lock)
    g_peak = np.where(interior[:, None], np.stack([0 * D, 0 * D, D], axis=1), g_lock)
    sec2 = 1.0 / np.cos(np.where(interior, half, 0.0)) ** 2
    g_sp = np.where(interior[:, None], np.stack([-sp, -half * sec2 / B, 0 * D], axis=1), 0.0)
    # implicit-function theorem: dq = J^-1 (dm - mu'(s) ds) (module docstring)
    _, J, dmu_ds = _curve(qq, s[solved])
    Jinv = np.linalg.inv(J)
    var_in_m = m_se[solved] ** 2
    var_in_s = (dmu_ds * s_se[solved]) ** 2
    for key, g, value in (("peak", g_peak, peak), ("lock", g_lock, lock),
                          ("slip_at_peak", g_sp, np.where(interior, sp, 1.0))):
        w = np.einsum("nj,nji->ni", g, Jinv)  # d(out)/d(m_i)
        out[key][solved] = value
        out[key + "_std"][solved] = np.sqrt(np.sum(w * w * (var_in_m + var_in_s), axis=1))
        if key != "slip_at_peak":
            out[key + "_common"][solved] = np.sqrt(np.sum(w * w * m_common[solved] ** 2, axis=1))
    return out


def _list(x, most: int = 8) -> str:
    shown = ", ".join(f"{v:g} m" for v in x[:most])
    return shown + (f" and {x.size - most} more" if x.size > most else "")
