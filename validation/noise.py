r"""The noise of the measurements, estimated without any model, and the lack-of-fit test of a model against it.

A diagnosis can only say "nothing is missing" or "this effect explains the data" against a noise level that does
not come from the model being judged (otherwise every model's residual looks like noise). The sources, in order:

1. ``"mu_std"``: the column given with the measurements. Lack of fit:
   :math:`\chi^2 = \sum_i (r_i/\sigma_i)^2 \sim \chi^2(n - k)` under the model (:math:`k` fitted parameters).
2. ``"replicates"``: rows repeated at identical conditions (slip, speed, temperature, pressure, wet). The pure-error
   sum of squares :math:`SS_{pe} = \sum_g \sum_{i \in g} (y_i - \bar y_g)^2` with :math:`n - g` degrees of freedom
   gives :math:`\hat\sigma^2 = SS_{pe}/(n - g)`; the classical lack-of-fit test is
   :math:`F = \frac{(RSS - SS_{pe})/(g - k)}{SS_{pe}/(n - g)} \sim F(g - k, n - g)` (Draper & Smith, Applied
   Regression Analysis, 3rd ed. 1998, Sec. 2.1). Used when it has at least :data:`MIN_DOF` degrees of freedom.
3. ``"local differences"``: along each series (rows that differ only in sliding speed, or only in slip, ordered
   along it), the pseudo-residuals of Gasser, Sroka & Jennen-Steinmetz (Biometrika 73, 625 (1986)):
   :math:`\tilde e_i = a_i y_{i-1} + b_i y_{i+1} - y_i`, :math:`a_i = (x_{i+1}-x_i)/(x_{i+1}-x_{i-1})`,
   :math:`b_i = 1 - a_i`, scaled by :math:`c_i^2 = 1/(a_i^2 + b_i^2 + 1)`, so that
   :math:`\hat\sigma^2 = \frac1m \sum c_i^2 \tilde e_i^2` is unbiased for a curve that is locally linear in
   :math:`x` (log sliding speed, log slip). The estimate is made on the data minus a smooth reference curve (the
   baseline model's prediction), which removes most of the curvature that would bias it upwards and assumes
   nothing about the model being right: the noise part of a pseudo-residual is the same whatever smooth curve is
   subtracted. Being a quadratic form :math:`\hat\sigma^2 = y^T B^T B y / m` its degrees of freedom follow from
   Satterthwaite (Biometrics Bulletin 2, 110 (1946)): :math:`\nu = m^2 / \lVert B B^T\rVert_F^2` (about
   :math:`18 m / 35` for equal spacing). Lack of fit: :math:`F = \frac{RSS/(n - k)}{\hat\sigma^2} \sim
   F(n - k, \nu)`; the two are computed from the same rows, which makes the test conservative (their positive
   correlation narrows the distribution of F).
4. ``"none"``: none of the above has :data:`MIN_DOF` degrees of freedom; no lack-of-fit test is possible and the
   diagnosis says so.

Sources 2 and 3 pool one noise level over the rows. Where the scatter grows with the friction level, as
with a force sensor whose error is a fraction of its reading, the rows of high friction scatter more than the pooled
estimate allows, and the pattern tests can read that as a misfit. The estimate therefore tests for it: the model
:math:`\sigma_i = s\,(\mu_i/\bar\mu)^{\gamma}` (:math:`\bar\mu` the geometric mean level) is fitted by maximum
likelihood to the units of the estimate (each pseudo-residual, or each group of replicates, its sum of squares
:math:`SS_k` taken as :math:`\sigma^2(\mu_k)` times a :math:`\chi^2` with :math:`d_k` degrees of freedom: 1, or the
group size less one): for a given :math:`\gamma`, :math:`\hat s^2 = \sum_k SS_k (\mu_k/\bar\mu)^{-2\gamma} / D`,
:math:`D = \sum_k d_k`, and the profile log-likelihood :math:`-\frac D2 \ln \hat s^2 - \gamma \sum_k d_k
\ln(\mu_k/\bar\mu)` is maximised over :math:`\gamma \in [0, 1]`, from one noise level to a noise in proportion to mu
(a steeper law, which the few units of a data set often suggest, would give the rows of low friction weights they
cannot bear out). Its likelihood-ratio test against :math:`\gamma = 0` (a test of variance heterogeneity in the
sense of Cook & Weisberg, Biometrika 70, 1 (1983); on the bound of the range, so half a :math:`\chi^2(1)`: Self &
Liang, J. Am. Stat. Assoc. 82, 605 (1987)) is made at :data:`TREND_ALPHA`; neighbouring pseudo-residuals share rows,
so their statistic is scaled by the Satterthwaite degrees of freedom over the number of pseudo-residuals. Where it
is significant, every row gets its own noise level, :math:`\sigma_i = \hat s\,(\mu_i/\bar\mu)^{\hat\gamma}`
(``row_sigma``; :math:`\mu_i` the mean of its group with replicates, with local differences the smooth reference
where one is given, else the measured mu; at least a tenth of :math:`\bar\mu`), ``sigma`` is :math:`\hat s`, the
level at :math:`\bar\mu`, with one degree of freedom less, and ``trend`` and the description say so. The diagnosis
then weights each row by :math:`\hat s/\sigma_i` (its fits, their information criteria and F tests are those of
weighted least squares with known relative weights), the lack-of-fit test compares the weighted residuals with
:math:`\hat s` (the pure error of replicates weighted the same way), and the pattern and outlier tests use
:math:`\sigma_i`. With one noise level the weights are exactly 1 and nothing changes.

:func:`remaining_pattern` looks for what a lack-of-fit test does not localise: group means (by speed decade,
temperature, pressure, slip range, wet/dry) beyond their standard error, too few sign runs along the series
(Wald & Wolfowitz, Ann. Math. Stat. 11, 147 (1940): a hump or a trend gives long runs), and a cubic trend of the
residual against log sliding speed, log slip, temperature and pressure (an F or chi2 test of the polynomial; its
shape tells a monotonic trend from a hump or a dip). Each family is tested at a third of :data:`PATTERN_ALPHA`
with a Bonferroni correction over its members (1.5 % nominal in all; at most 2 % false alarms per case measured
on noise-only simulations of fitted models).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from frictioncite import doi

from . import distributions
from .errors import InputError
from .measurements import Measurements

__all__ = ["NoiseEstimate", "LackOfFit", "Pattern", "estimate_noise", "lack_of_fit", "remaining_pattern",
           "series_of", "ALPHA", "PATTERN_ALPHA", "MIN_DOF", "NOISE_SOURCES"]

#: Significance level of the lack-of-fit test.
ALPHA = 0.01
#: Nominal false-alarm rate of the remaining-pattern search as a whole: each of its three families (group means,
#: sign runs, polynomial trends) is tested at a third of it, with a Bonferroni correction over its members. The
#: runs test on the residual of a fitted model reads somewhat liberal (neighbouring residuals of a fit are
#: correlated), so the nominal rate is 1.5 % for a measured rate of at most 2 % per case on noise-only
#: simulations of fitted models (``benchmarks/pattern_false_alarms.py``).
PATTERN_ALPHA = 0.015
_FAMILY_ALPHA = PATTERN_ALPHA / 3
#: Fewest degrees of freedom a noise source needs to be used.
MIN_DOF = 8
#: The noise sources, in order of preference.
NOISE_SOURCES = ("mu_std", "replicates", "local differences", "none")
#: Significance level of the test of a noise level that changes with the friction level (module docstring).
TREND_ALPHA = 0.01


@dataclass(frozen=True, eq=False)
class NoiseEstimate:
    """The noise level of a set of measurements.

    Attributes
    ----------
    source : str
        One of :data:`NOISE_SOURCES`.
    sigma : float
        Noise standard deviation in mu (the rms of ``mu_std`` for that source; with ``trend``, the level at the
        geometric mean friction level); NaN for ``"none"``.
    dof : float
        Degrees of freedom of the estimate (``inf`` for ``mu_std``; Satterthwaite's for local differences).
    row_sigma : ndarray
        Noise standard deviation per row (``mu_std``; with ``trend``, sigma (mu_i / mu_ref)^trend; else ``sigma``
        everywhere).
    pure_error : float
        Pure-error sum of squares (replicates only, else NaN; with ``trend``, of the residuals scaled to the level
        ``sigma``).
    n_groups : int
        Distinct conditions (replicates only, else 0).
    description : str
        One sentence: where the number comes from (and, with ``trend``, that the scatter changes with mu).
    trend : float
        The exponent gamma of a scatter that changes with the friction level, sigma_i proportional to mu_i^gamma,
        where the data show one at :data:`TREND_ALPHA` (module docstring); 0 otherwise.
    trend_p : float
        The p-value of the test for it (NaN where it was not made: ``mu_std``, no estimate, one friction level).
    """

    source: str
    sigma: float
    dof: float
    row_sigma: np.ndarray
    pure_error: float = math.nan
    n_groups: int = 0
    description: str = ""
    trend: float = 0.0
    trend_p: float = math.nan

    @property
    def known(self) -> bool:
        """Whether a lack-of-fit test is possible (any source but ``"none"``)."""
        return self.source != "none"

    def as_dict(self) -> dict:
        """The estimate as a JSON-ready dict.

        Returns
        -------
        dict
            ``source``, ``sigma``, ``dof``, ``description``, ``trend_exponent`` (gamma of a scatter proportional to
            mu^gamma where the data show one, else 0) and ``trend_p`` (its test's p-value, null where none was
            made).
        """
        return {"source": self.source, "sigma": self.sigma, "dof": self.dof, "description": self.description,
                "trend_exponent": self.trend,
                "trend_p": self.trend_p if math.isfinite(self.trend_p) else None}


@dataclass(frozen=True)
class LackOfFit:
    """A model's residual tested against the noise.

    Attributes
    ----------
    test : str
        ``"chi2"``, ``"F"`` or ``"none"`` (no noise estimate).
    statistic : float
    dof : (float, float)
        Degrees of freedom (the second is ``inf`` for chi2).
    p_value : float
        Probability of a misfit at least this large if the model were right (NaN without a test).
    ratio : float
        Residual standard deviation of the model, sqrt(RSS / (n - k)) (weighted with mu_std), over the noise.
    consistent : bool
        Whether the residual is consistent with the noise (p >= :data:`ALPHA`; True when untestable).
    """

    test: str
    statistic: float
    dof: tuple
    p_value: float
    ratio: float
    consistent: bool

    def describe(self) -> str:
        """One line: the statistic, its degrees of freedom, the p-value and residual / noise (or: no test made)."""
        if self.test == "none":
            return "no lack-of-fit test (no independent noise estimate)"
        stat = (f"chi2 = {self.statistic:.1f} on {self.dof[0]:g} dof" if self.test == "chi2"
                else f"F = {self.statistic:.2f} on ({self.dof[0]:g}, {self.dof[1]:.0f}) dof")
        return f"{stat}, p = {self.p_value:.2g}; residual / noise = {self.ratio:.2f}"

    def as_dict(self) -> dict:
        """The test as a JSON-ready dict.

        Returns
        -------
        dict
            ``test``, ``statistic``, ``dof`` (a list of two), ``p_value``, ``ratio`` and ``consistent``.
        """
        return {"test": self.test, "statistic": self.statistic, "dof": list(self.dof), "p_value": self.p_value,
                "ratio": self.ratio, "consistent": self.consistent}


@dataclass(frozen=True)
class Pattern:
    """Systematic structure left in a residual.

    Attributes
    ----------
    found : bool
    findings : tuple of str
        One phrase per significant finding (strongest first).
    p_value : float
        Smallest Bonferroni-adjusted p-value of the tests (1 when nothing could be tested).
    checked : str
        What was tested, for the "none found" sentence.
    """

    found: bool
    findings: tuple
    p_value: float
    checked: str

    def describe(self, limit: int = 3) -> str:
        """The strongest ``limit`` findings in words ("none detected (...)" when there are none)."""
        if self.found:
            more = len(self.findings) - limit
            return "; ".join(self.findings[:limit]) + (f"; and {more} more" if more > 0 else "")
        return f"none detected ({self.checked})"


#: T. Gasser, L. Sroka, C. Jennen-Steinmetz, Biometrika 73, 625 (1986): pseudo-residuals.
GASSER_1986 = "gasser:biometrika-73-625-1986"
#: F. E. Satterthwaite, Biometrics Bulletin 2, 110 (1946): degrees of freedom of a quadratic form.
SATTERTHWAITE_1946 = "10.2307/3002019"
#: R. D. Cook, S. Weisberg, Biometrika 70, 1 (1983): a test of a variance that changes with the level.
COOK_WEISBERG_1983 = "10.1093/biomet/70.1.1"
#: S. G. Self, K.-Y. Liang, J. Am. Stat. Assoc. 82, 605 (1987): likelihood-ratio tests on the boundary.
SELF_LIANG_1987 = "10.1080/01621459.1987.10478472"
#: A. Wald, J. Wolfowitz, Ann. Math. Stat. 11, 147 (1940): the runs test.
WALD_WOLFOWITZ_1940 = "10.1214/aoms/1177731909"


# ==========================================================================================================
@doi(GASSER_1986, SATTERTHWAITE_1946, COOK_WEISBERG_1983, SELF_LIANG_1987)
def estimate_noise(measurements: Measurements, reference=None) -> NoiseEstimate:
    """The noise level of ``measurements`` from the first source that is available (module docstring).

    Parameters
    ----------
    measurements : Measurements
    reference : array_like, optional
        A smooth curve per row (e.g. the baseline model's prediction) subtracted before the local-difference
        estimate, to remove most of the data's curvature. Default: none.

    Returns
    -------
    NoiseEstimate
    """
    m = measurements
    if not isinstance(m, Measurements):
        raise InputError(f"measurements: expected validation.Measurements, got {type(m).__name__}")
    if m.mu_std is not None:
        s = np.asarray(m.mu_std, dtype=float)
        return NoiseEstimate(source="mu_std", sigma=float(np.sqrt(np.mean(s * s))), dof=math.inf, row_sigma=s,
                             description="the mu_std column of the measurements (rms over the rows)")
    rep = _replicates(m)
    if rep is not None:
        return rep
    y = m.mu if reference is None else m.mu - _row_array(reference, m.n, "reference")
    local = _local_differences(m, y, reference is not None)
    if local is not None:
        return local
    return NoiseEstimate(source="none", sigma=math.nan, dof=0.0, row_sigma=np.full(m.n, math.nan),
                         description=f"no mu_std column, fewer than {MIN_DOF} degrees of freedom from replicate "
                                     "rows and too few rows along series for a local estimate")


def lack_of_fit(residual, n_params: int, noise: NoiseEstimate) -> LackOfFit:
    """Test a model's ``residual`` (measured - predicted, per row) against ``noise`` (module docstring).

    Parameters
    ----------
    residual : array_like
    n_params : int
        Parameters fitted to these rows (baseline and effect parameters that change the prediction).
    noise : NoiseEstimate
    """
    r = np.asarray(residual, dtype=float)
    n = r.size
    k = int(n_params)
    dof1 = max(n - k, 1)
    if noise.source == "none":
        return LackOfFit(test="none", statistic=math.nan, dof=(dof1, math.nan), p_value=math.nan,
                         ratio=math.nan, consistent=True)
    if noise.source == "mu_std":
        chi2 = float(np.sum((r / noise.row_sigma) ** 2))
        p = distributions.chi2_sf(chi2, dof1)
        return LackOfFit(test="chi2", statistic=chi2, dof=(dof1, math.inf), p_value=p,
                         ratio=math.sqrt(chi2 / dof1), consistent=p >= ALPHA)
    # with a noise that changes with mu (noise.trend), the residuals in the units of the reference level; the
    # factors are exactly 1 for one noise level
    rw = r / (noise.row_sigma / noise.sigma)
    rss = float(np.sum(rw * rw))
    ratio = math.sqrt(rss / dof1) / noise.sigma
    if noise.source == "replicates":
        df_pe = n - noise.n_groups
        df_lof = noise.n_groups - k
        if df_lof < 1:
            return LackOfFit(test="none", statistic=math.nan, dof=(df_lof, df_pe), p_value=math.nan, ratio=ratio,
                             consistent=True)
        F = (max(rss - noise.pure_error, 0.0) / df_lof) / (noise.pure_error / df_pe)
        p = distributions.f_sf(F, df_lof, df_pe)
        return LackOfFit(test="F", statistic=F, dof=(df_lof, df_pe), p_value=p, ratio=ratio, consistent=p >= ALPHA)
    F = (rss / dof1) / noise.sigma ** 2
    p = distributions.f_sf(F, dof1, noise.dof)
    return LackOfFit(test="F", statistic=F, dof=(dof1, noise.dof), p_value=p, ratio=ratio, consistent=p >= ALPHA)


@doi(WALD_WOLFOWITZ_1940)
def remaining_pattern(residual, measurements: Measurements, noise: NoiseEstimate) -> Pattern:
    """Systematic structure in ``residual`` beyond ``noise``: groups, sign runs, polynomial trends.

    Without a noise estimate the residual's own standard deviation stands in (the tests then only see structure
    relative to the scatter, and say so).
    """
    r = np.asarray(residual, dtype=float)
    m = measurements
    sig = noise.row_sigma if noise.known else np.full(m.n, max(float(np.std(r, ddof=1)) if r.size > 1 else 0, 1e-12))
    dof = noise.dof if noise.known else max(r.size - 1, 1)
    found: list[tuple[float, str]] = []
    p_all = []
    for test in (_group_findings, _runs_finding, _trend_findings):
        p, phrases = test(r, m, sig, dof)
        p_all.append(p)
        found.extend(phrases)
    found.sort(key=lambda t: t[0])
    checked = ("group means by speed, temperature, pressure, slip and wet/dry; sign runs along each series; "
               "cubic trends with log speed, slip, temperature and pressure; each family at p < "
               f"{_FAMILY_ALPHA:.2g} after Bonferroni, {100 * PATTERN_ALPHA:g} % in all")
    if not noise.known:
        checked += "; relative to the residual's own scatter, as no noise estimate exists"
    p_min = min(p_all) if p_all else 1.0
    return Pattern(found=bool(found), findings=tuple(ph for _, ph in found), p_value=float(p_min), checked=checked)


def series_of(measurements: Measurements) -> list[tuple[np.ndarray, np.ndarray, str]]:
    """The series of the rows: ``(row indices, x, axis)``, rows ordered along ``x``.

    A series is a set of at least 3 rows with distinct ``x`` that share every other condition: sliding rows
    (slip = 1) along log10 sliding speed, slip rows along log10 slip (same rolling speed V), and the rows left
    over along temperature, then pressure. The ``series`` column, when given, splits them further.
    """
    m = measurements
    used = np.zeros(m.n, dtype=bool)
    out = []
    lab = np.asarray(m.series, dtype=object)
    sliding = m.slip >= 1.0
    axes = (
        ("log10 sliding speed", sliding, np.log10(m.sliding_speed),
         (m.wet, m.temperature, m.pressure)),
        ("log10 slip", ~sliding, np.log10(np.maximum(m.slip, 1e-12)),
         (m.wet, m.temperature, m.pressure, m.speed)),
        ("temperature", np.ones(m.n, dtype=bool), m.temperature,
         (m.wet, m.slip, m.speed, m.pressure)),
        ("pressure", np.ones(m.n, dtype=bool), m.pressure / 1e6,
         (m.wet, m.slip, m.speed, m.temperature)),
    )
    for axis, rows, x, keys in axes:
        groups: dict[tuple, list[int]] = {}
        for i in np.flatnonzero(rows & ~used):
            groups.setdefault((lab[i],) + tuple(float(k[i]) for k in keys), []).append(int(i))
        for idx in groups.values():
            idx = np.asarray(idx)
            if np.unique(x[idx]).size < 3:
                continue
            order = np.argsort(x[idx], kind="stable")
            out.append((idx[order], x[idx][order], axis))
            used[idx] = True
    return out


# ---- noise sources -----------------------------------------------------------------------------------------
def _replicates(m: Measurements) -> NoiseEstimate | None:
    keys = np.column_stack([m.slip, m.speed, m.temperature, m.pressure, m.wet.astype(float)])
    _, inverse, counts = np.unique(keys, axis=0, return_inverse=True, return_counts=True)
    inverse = np.asarray(inverse).ravel()
    g = counts.size
    df_pe = m.n - g
    if df_pe < MIN_DOF:
        return None
    means = np.bincount(inverse, weights=m.mu) / counts
    ss = float(np.sum((m.mu - means[inverse]) ** 2))
    sigma = math.sqrt(ss / df_pe)
    est = NoiseEstimate(source="replicates", sigma=sigma, dof=float(df_pe), row_sigma=np.full(m.n, sigma),
                        pure_error=ss, n_groups=int(g),
                        description=f"the scatter of replicate rows ({int(np.sum(counts > 1))} conditions measured "
                                    f"more than once; pure error with {df_pe} degrees of freedom)")
    multi = counts > 1
    ss_g = np.bincount(inverse, weights=(m.mu - means[inverse]) ** 2)
    out = _with_trend(est, ss_g[multi], (counts - 1)[multi].astype(float), means[multi], 1.0, means[inverse])
    if out.trend != 0.0:
        # the pure error in the units of the weighted residuals (r_i sigma / sigma_i), for the lack-of-fit test
        f = out.row_sigma / out.sigma
        out = replace(out, pure_error=float(np.sum(((m.mu - means[inverse]) / f) ** 2)))
    return out


def _local_differences(m: Measurements, y: np.ndarray, reference_given: bool = False) -> NoiseEstimate | None:
    rows, coef = [], []
    n_series = 0
    for idx, x, _ in series_of(m):
        n_series += 1
        for j in range(1, idx.size - 1):
            span = x[j + 1] - x[j - 1]
            if span <= 0:
                continue
            a = (x[j + 1] - x[j]) / span
            b = 1.0 - a
            c = 1.0 / math.sqrt(a * a + b * b + 1.0)
            rows.append((idx[j - 1], idx[j], idx[j + 1]))
            coef.append((c * a, -c, c * b))
    mcount = len(rows)
    if mcount == 0:
        return None
    B = np.zeros((mcount, m.n))
    for k, (ii, cc) in enumerate(zip(rows, coef)):
        for i, c in zip(ii, cc):
            B[k, i] += c
    e = B @ y
    var = float(e @ e) / mcount
    BBt = B @ B.T
    dof = mcount ** 2 / float(np.sum(BBt * BBt))
    if dof < MIN_DOF:
        return None
    sigma = math.sqrt(var)
    est = NoiseEstimate(source="local differences", sigma=sigma, dof=float(dof), row_sigma=np.full(m.n, sigma),
                        description=f"differences of neighbouring rows along {n_series} series (Gasser-Sroka-"
                                    f"Jennen-Steinmetz pseudo-residuals, {mcount} of them, {dof:.0f} effective "
                                    "degrees of freedom)")
    # the level of each row: the smooth reference where given (the data less y), else the measured mu; of each
    # pseudo-residual, the mean level of its three rows
    row_level = m.mu - y if reference_given else m.mu
    level = np.array([(row_level[i] + row_level[j] + row_level[k]) / 3.0 for i, j, k in rows])
    return _with_trend(est, e * e, np.ones(mcount), level, dof / mcount, row_level)


def _with_trend(est: NoiseEstimate, ss, d, level, scale: float, row_level) -> NoiseEstimate:
    """``est`` with the test of a scatter that changes with the friction level (module docstring): ``trend_p``
    always; where it is significant, ``trend``, the noise of every row (``row_sigma``), ``sigma`` the level at the
    reference mu and a sentence in the description.

    Parameters
    ----------
    est : NoiseEstimate
        The estimate (one noise level for every row).
    ss : ndarray (K,)
        The sums of squares of its units (pseudo-residuals or groups of replicates), each sigma^2(level) times a
        chi^2.
    d : ndarray (K,)
        Their degrees of freedom.
    level : ndarray (K,)
        The friction level of each unit (the mean level of its rows); units at a level of 0 or below are left out.
    scale : float
        Factor on the likelihood-ratio statistic for units that are not independent (Satterthwaite's degrees of
        freedom over the number of units; 1 for independent units).
    row_level : ndarray (n,)
        The friction level of every row.
    """
    ok = level > 0
    if int(np.sum(ok)) < 3:
        return est
    ss, d, lv = ss[ok], d[ok], np.log(level[ok])
    ref = float(np.sum(d * lv) / np.sum(d))
    x = lv - ref
    if float(np.ptp(x)) < 1e-6:     # one friction level: nothing to tell a trend from
        return est
    D = float(np.sum(d))

    def profile(gamma: float) -> float:
        s2 = float(np.sum(ss * np.exp(-2.0 * gamma * x))) / D
        return -0.5 * D * math.log(max(s2, 1e-300)) - gamma * float(np.sum(d * x))

    from scipy.optimize import minimize_scalar

    gamma = float(minimize_scalar(lambda g: -profile(g), bounds=(0.0, 1.0), method="bounded",
                                  options={"xatol": 1e-4}).x)
    # gamma = 0 lies on the bound of the range searched: the statistic is half a chi^2(0), half a chi^2(1) (Self &
    # Liang, J. Am. Stat. Assoc. 82, 605 (1987))
    p = 0.5 * float(distributions.chi2_sf(max(2.0 * (profile(gamma) - profile(0.0)) * scale, 0.0), 1))
    if not p < TREND_ALPHA:
        return replace(est, trend_p=p)
    s_ref = math.sqrt(float(np.sum(ss * np.exp(-2.0 * gamma * x))) / D)
    mu_ref = math.exp(ref)
    # a row's level is at least a tenth of the reference level: a near-zero friction does not get a near-zero noise
    lv_row = np.log(np.maximum(np.asarray(row_level, dtype=float), 0.1 * mu_ref)) - ref
    return replace(est, sigma=s_ref, row_sigma=s_ref * np.exp(gamma * lv_row), dof=max(est.dof - 1.0, 1.0),
                   trend=gamma, trend_p=p,
                   description=f"{est.description}; the scatter grows with the friction level, sigma proportional "
                               f"to mu^{gamma:.2f} (likelihood-ratio test p = {p:.2g}): {s_ref:.3g} at mu = "
                               f"{mu_ref:.3g}, the level quoted, and each row weighted by its own; a mu_std column "
                               "per row, where the rig's noise is known, is better still")


def _row_array(x, n: int, name: str) -> np.ndarray:
    a = np.asarray(x, dtype=float)
    if a.shape != (n,) or not np.all(np.isfinite(a)):
        raise InputError(f"{name}: expected {n} finite values, one per row")
    return a


# ---- pattern tests: each returns (Bonferroni-adjusted smallest p, [(p, phrase), ...]) ------------------------
def _group_findings(r, m, sig, dof):
    from .compare import group_labels

    w = 1.0 / sig ** 2
    tests = []
    for factor, (gid, labels) in group_labels(m).items():
        if factor == "series" or len(labels) < 2:
            continue
        for k, lab in enumerate(labels):
            sel = gid == k
            if sel.sum() < 2:
                continue
            mean = float(np.sum(w[sel] * r[sel]) / np.sum(w[sel]))
            z = mean * math.sqrt(float(np.sum(w[sel])))
            p = 2 * distributions.t_sf(abs(z), dof) if math.isfinite(dof) else 2 * distributions.norm_sf(abs(z))
            tests.append((p, factor, lab, mean, z))
    if not tests:
        return 1.0, []
    G = len(tests)
    out = []
    for p, factor, lab, mean, z in sorted(tests):
        if p * G < _FAMILY_ALPHA:
            out.append((p * G, f"by {factor}, mean residual {mean:+.3f} at {lab} (z = {z:+.1f}, "
                               f"{'model too low' if mean > 0 else 'model too high'})"))
    return min(1.0, min(t[0] for t in tests) * G), out[:3]


def _runs_finding(r, m, sig, dof):
    R = E = V = 0.0
    worst = None
    for idx, x, axis in series_of(m):
        s = np.sign(r[idx])
        s = s[s != 0]
        n1, n2 = int(np.sum(s > 0)), int(np.sum(s < 0))
        n = n1 + n2
        if n1 == 0 or n2 == 0 or n < 3:
            if n >= 5:  # one sign all along: the most extreme run count
                e = 1.0
                R += 1.0
                E += e
            continue
        runs = 1 + int(np.sum(s[1:] != s[:-1]))
        e = 1.0 + 2.0 * n1 * n2 / n
        v = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n * n * (n - 1.0))
        R += runs
        E += e
        V += v
        if worst is None or runs - e < worst[0]:
            worst = (runs - e, axis, x, idx)
    if V <= 0:
        return 1.0, []
    z = (R - E) / math.sqrt(V)
    p = distributions.norm_cdf(z)
    if p >= _FAMILY_ALPHA:
        return p, []
    return p, [(p, f"the residual keeps its sign along the series ({R:.0f} sign runs where {E:.0f} are expected "
                   f"by chance; runs test p = {p:.2g})")]


def _trend_findings(r, m, sig, dof):
    covs = [("log sliding speed", np.log10(m.sliding_speed), np.ones(m.n, dtype=bool), lambda v: f"{10 ** v:.3g} m/s"),
            ("slip", np.log10(np.maximum(m.slip, 1e-12)), m.slip < 1.0, lambda v: f"{10 ** v:.3g}"),
            ("temperature", m.temperature, np.ones(m.n, dtype=bool), lambda v: f"{v:.3g} C"),
            ("pressure", m.pressure / 1e6, np.ones(m.n, dtype=bool), lambda v: f"{v:.3g} MPa")]
    tests = []
    for label, x, rows, fmt in covs:
        xs = x[rows]
        nd = np.unique(xs).size
        if nd < 3 or rows.sum() < 5:
            continue
        deg = min(3, nd - 1)
        lo, hi = float(xs.min()), float(xs.max())
        t = (xs - 0.5 * (lo + hi)) / max(0.5 * (hi - lo), 1e-300)
        A = np.vander(t, deg + 1) / sig[rows][:, None]
        b = r[rows] / sig[rows]
        coef, *_ = np.linalg.lstsq(A, b, rcond=None)
        ss = float(np.sum((A @ coef) ** 2))     # explained, in noise units
        k = deg + 1
        if math.isfinite(dof):
            p = distributions.f_sf(ss / k, k, dof)
        else:
            p = distributions.chi2_sf(ss, k)
        tt = np.linspace(-1, 1, 201)
        curve = np.vander(tt, deg + 1) @ coef
        xx = 0.5 * (lo + hi) + tt * 0.5 * (hi - lo)
        tests.append((p, label, _shape(label, xx, curve, fmt)))
    if not tests:
        return 1.0, []
    G = len(tests)
    out = [(p * G, f"{shape} (cubic trend p = {min(1.0, p * G):.2g})") for p, label, shape in sorted(tests)
           if p * G < _FAMILY_ALPHA]
    return min(1.0, min(t[0] for t in tests) * G), out


def _shape(label, x, y, fmt) -> str:
    """Describe a smooth curve: monotonic rise / fall, or a hump / dip with its extremum."""
    i_max, i_min = int(np.argmax(y)), int(np.argmin(y))
    n = y.size
    span = float(y.max() - y.min())
    ends = (y[0], y[-1])
    interior_max = 0 < i_max < n - 1 and y[i_max] - max(ends) > 0.25 * span
    interior_min = 0 < i_min < n - 1 and min(ends) - y[i_min] > 0.25 * span
    if interior_max and not interior_min:
        return (f"the residual rises then falls with {label}, peaking at {y[i_max]:+.3f} near {fmt(x[i_max])} "
                f"({y[0]:+.3f} at {fmt(x[0])}, {y[-1]:+.3f} at {fmt(x[-1])})")
    if interior_min and not interior_max:
        return (f"the residual falls then rises with {label}, lowest {y[i_min]:+.3f} near {fmt(x[i_min])} "
                f"({y[0]:+.3f} at {fmt(x[0])}, {y[-1]:+.3f} at {fmt(x[-1])})")
    if interior_min and interior_max:
        return (f"the residual oscillates with {label} (peak {y[i_max]:+.3f} near {fmt(x[i_max])}, trough "
                f"{y[i_min]:+.3f} near {fmt(x[i_min])})")
    word = "rises" if y[-1] > y[0] else "falls"
    return f"the residual {word} with {label}, from {y[0]:+.3f} at {fmt(x[0])} to {y[-1]:+.3f} at {fmt(x[-1])}"
