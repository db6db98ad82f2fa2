r"""Where the misfit sits: the rows of one kind of measurement that a model misses while it fits the others.

The rows of a DRFT-style data set rest on different parts of the model: sliding rows (slip = 1, dry) on the
friction law alone; rows with slip (slip < 1, dry) also on the slip model (the brush contact: its stiffness, length
and pressure distribution, and patch heating); wet rows also on the wet model. When a model misses the data and
its misfit sits in one of these families while the other rows are at the noise, the missing physics acts there --
a slip curve of another shape than the brush model gives, say -- and the verdict says so; no candidate effect need
be named for that.

The lack-of-fit statistic of the whole data set is split over the families (a partition of the residual sum of
squares, as in the lack-of-fit tests of Draper & Smith, Applied Regression Analysis, 3rd ed. 1998, Sec. 2.1):
with :math:`z_i = r_i/\sigma_i` (the row's noise level) and :math:`S_f = \sum_{i \in f} z_i^2` over the
:math:`n_f` rows of family :math:`f`, the :math:`k` fitted parameters are shared out in proportion to the rows,
:math:`d_f = n_f (n - k)/n` degrees of freedom, and

* with the noise given per row (``mu_std``), :math:`S_f \sim \chi^2(d_f)`;
* with a noise estimated from the data (:math:`\nu` degrees of freedom), :math:`(S_f/d_f) \sim F(d_f, \nu)`.

A family is *missed* when its test gives :math:`p < \alpha/m` (:data:`ALPHA`, Bonferroni over the :math:`m`
families with at least :data:`MIN_ROWS` rows). The misfit is placed in a family when it alone is missed and the
rows outside it, tested the same way, are at the noise (:math:`p \ge` :data:`REST_P`); nothing is reported when
more than one family is missed, or none, or only one family is measured.

A model's fitted parameters can trade the misfit of one family for a misfit of the others: fitted to every row,
they move to meet the family they cannot fit, and the other rows then miss too, so that no family is missed alone.
With the model's Jacobian (``refit``), each family :math:`f` is then tested as in Chow's test of predictive failure
(G. C. Chow, Econometrica 28, 591 (1960), Sec. 3): the parameters are refitted to the other rows alone (Gauss-Newton
steps on the Jacobian at the joint optimum, the model evaluated at each step where it can be), leaving
:math:`R_{\bar f}` on those rows, and with :math:`S` the joint fit's sum over every row,

* :math:`S - R_{\bar f} \sim \chi^2(n_f - r + r_{\bar f})` (noise known; :math:`r`, :math:`r_{\bar f}` the
  ranks of the Jacobian on every row and on the other rows), or its mean square against :math:`F(\cdot, \nu)`,
  tests the family;
* :math:`R_{\bar f}` against :math:`\chi^2(n - n_f - r_{\bar f})` (or F) tests the other rows at the noise.

The misfit is placed where exactly one family passes both (the same levels); this is tried only where the test
without a refit places nothing. In a linear model with Gaussian noise both statistics have these distributions
exactly; a step that the model cannot take, or that leaves the other rows above the noise, places nothing.

A noise estimated from local differences (:mod:`validation.noise`) is made on the data less the baseline's
prediction; where the baseline misses one family by a curve, the curvature of that misfit enters the estimate and
inflates it. The other rows then scatter less than the estimate allows, and where they do beyond chance (the lower
tail of their test below :data:`ALPHA`) the text says so: the tests of the verdict are then conservative.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np
from frictioncite import doi

from .distributions import chi2_cdf, chi2_sf, f_cdf, f_sf
from .errors import InputError
from .outliers import scaled_residual

__all__ = ["Localized", "localize_misfit", "FAMILIES", "ALPHA", "REST_P", "MIN_ROWS", "REFIT_STEPS"]

#: Level of the test that a family is missed (shared over the families, Bonferroni).
ALPHA = 0.01
#: Least p-value of the rows outside the family for them to count as at the noise.
REST_P = 0.05
#: Least number of rows of a family for it to be tested.
MIN_ROWS = 3
#: Most model evaluations of the refit of a model's parameters to the rows outside a family (Gauss-Newton steps).
REFIT_STEPS = 3
#: The families of rows, in order: ``(key, label)``.
FAMILIES = (("sliding", "sliding rows (slip = 1, dry)"), ("slip", "rows with slip (slip < 1, dry)"),
            ("wet", "wet rows"))
#: N. R. Draper, H. Smith, Applied Regression Analysis, 3rd ed., Wiley, New York (1998).
DRAPER_SMITH_1998 = "isbn:9780471170822"
#: G. C. Chow, Tests of equality between sets of coefficients in two linear regressions, Econometrica 28, 591
#: (1960).
CHOW_1960 = "10.2307/1910133"

#: The slip hint where the contact's stiffness and length were refitted with the rest (``refitted``).
_SLIP_REFITTED = ("The contact's stiffness and length were refitted with the rest and the misfit stays: the slip "
                  "curve has a shape the brush model does not give (its peak, or its fall beyond the peak), or "
                  "physics of rolling with slip is missing.")
_CONTACT = ("contact.stiffness", "contact.length")

_HINTS = {
    "slip": ("Rows with slip rest on the slip model (the brush contact: its stiffness, length and pressure "
             "distribution; patch heating) besides the friction law the sliding rows test: refit the contact "
             "(contact.stiffness, contact.length in the fit), or the slip model misses something (a slip curve of "
             "another shape than the brush model gives: its peak, or its fall beyond the peak)."),
    "wet": ("Wet rows rest on the wet model (water sealing the texture) besides the dry friction law the other "
            "rows test: the wet candidate, or water physics it lacks (e.g. viscous hydroplaning at speed)."),
    "sliding": ("The sliding rows test the friction law over the whole range of sliding speeds, at the "
                "temperatures and pressures they were measured at; the rows with slip slide slowly over most of the "
                "patch, at the conditions of their sweeps: the missing physics acts at the sliding speeds, "
                "temperatures or pressures of the sliding rows (a law of speed, temperature or load the model "
                "lacks)."),
}


@dataclass(frozen=True)
class Localized:
    """A family of rows that the model misses while the other rows are at the noise.

    Attributes
    ----------
    family : str
        Its key in :data:`FAMILIES` (``"sliding"``, ``"slip"`` or ``"wet"``).
    n_rows : int
        Its number of rows.
    ratio : float
        Its residual over the noise (root mean square of :math:`z_i` over its degrees of freedom).
    p_value : float
        Its test's p-value.
    share : float
        Its share of the model's misfit (sum of :math:`z_i^2`).
    rest_rows : int
        The number of the other rows.
    rest_ratio : float
        Their residual over the noise.
    rest_p : float
        Their test's p-value.
    model : str
        The model the residuals are of.
    noise_source : str
        The source of the noise estimate (:data:`validation.noise.NOISE_SOURCES`).
    rest_low_p : float
        The lower tail of the other rows' test: small when they scatter less than the noise estimate allows.
    refitted : tuple of str
        The baseline parameters refitted with the model (``"contact.stiffness"``, ...): the hint for rows with slip
        does not ask for a refit of the contact that was made.
    traded : int
        0 when the family is missed alone at the joint fit; else the number of the model's fitted parameters
        (the rank of its Jacobian on the other rows) that were refitted to the other rows alone to find it
        (module docstring): at the joint fit they traded the family's misfit for one on the other rows.
    n_evals : int
        Model evaluations spent on those refits.
    contact : validation.contact_refit.ContactRefit or None
        For the rows with slip: the brush contact refitted with the model's parameters (whether the contact given
        is off, or the slip curve's shape is what the model lacks); None when not made.
    """

    family: str
    n_rows: int
    ratio: float
    p_value: float
    share: float
    rest_rows: int
    rest_ratio: float
    rest_p: float
    model: str
    noise_source: str = ""
    rest_low_p: float = math.nan
    refitted: tuple = ()
    traded: int = 0
    n_evals: int = 0
    contact: object = None

    @property
    def label(self) -> str:
        """The family in words."""
        return dict(FAMILIES)[self.family]

    @property
    def noise_inflated(self) -> bool:
        """Whether the other rows scatter less than a local-difference noise estimate allows, beyond chance (module
        docstring)."""
        return self.noise_source == "local differences" and self.rest_low_p < ALPHA

    def text(self) -> str:
        """Where the misfit sits (with the tests' figures), what rests on those rows, and whether the noise
        estimate looks inflated by the misfit."""
        if self.traded:
            short = self.label.split(" (")[0]
            one = self.traded == 1
            out = (f"The misfit of {self.model} sits in the {self.n_rows} {self.label}: refitted to the other "
                   f"{self.rest_rows} rows alone, its {self.traded} fitted parameter{'' if one else 's'} "
                   f"leave{'s' if one else ''} those at the noise ({self.rest_ratio:.2f}, p = {self.rest_p:.2g}) "
                   f"and miss{'es' if one else ''} the {short} by residual / noise {self.ratio:.2f} (p = "
                   f"{self.p_value:.2g}, {self.share:.0%} of the misfit); fitted to every row, "
                   f"{'it trades' if one else 'they trade'} that misfit for one on the other rows. ")
        else:
            out = (f"The misfit of {self.model} sits in the {self.n_rows} {self.label}: residual / noise "
                   f"{self.ratio:.2f} (p = {self.p_value:.2g}), {self.share:.0%} of the misfit, while the other "
                   f"{self.rest_rows} rows are at the noise ({self.rest_ratio:.2f}, p = {self.rest_p:.2g}). ")
        if self.family == "slip" and self.contact is not None:
            out += self.contact.text()
        else:
            out += (_SLIP_REFITTED if self.family == "slip" and all(c in self.refitted for c in _CONTACT) else
                    _HINTS[self.family])
        if self.noise_inflated:
            out += (f" The other rows scatter less than the noise estimate allows (lower-tail p = "
                    f"{self.rest_low_p:.2g}): the estimate from local differences is likely inflated by the "
                    f"curvature of the misfit in the {self.label}, and the tests are conservative.")
        return out

    def as_dict(self) -> dict:
        """``family``, ``n_rows``, ``ratio``, ``p_value``, ``share``, ``rest_rows``, ``rest_ratio``, ``rest_p``,
        ``model``, ``noise_source``, ``noise_inflated``, ``traded``, ``contact_refit``
        (:meth:`validation.contact_refit.ContactRefit.as_dict`, None when not made) and ``text``."""
        return {"family": self.family, "n_rows": self.n_rows, "ratio": self.ratio, "p_value": self.p_value,
                "share": self.share, "rest_rows": self.rest_rows, "rest_ratio": self.rest_ratio,
                "rest_p": self.rest_p, "model": self.model, "noise_source": self.noise_source,
                "noise_inflated": self.noise_inflated, "traded": self.traded,
                "contact_refit": None if self.contact is None else self.contact.as_dict(), "text": self.text()}


# ==========================================================================================================
@doi(DRAPER_SMITH_1998, CHOW_1960)
def localize_misfit(residual, noise, measurements, model: str, n_params: int = 0,
                    refitted=(), refit=None, on_evals=None) -> Localized | None:
    """The family of rows that ``model`` misses while it fits the others (module docstring), or None.

    Parameters
    ----------
    residual : array_like (n,)
        Measured - predicted mu of the model.
    noise : validation.noise.NoiseEstimate
        Per-row noise levels (``row_sigma``), the source and its degrees of freedom.
    measurements : validation.Measurements
        For the rows' slip and wet flags.
    model : str
        What the residual is of, for the text (e.g. ``"the baseline + flash_temperature"``).
    n_params : int
        Parameters fitted to these rows (shared out over the families in proportion to their rows).
    refitted : sequence of str
        The baseline parameters refitted with the model (``fit`` names such as ``"contact.stiffness"``), for the
        text.
    refit : object or None
        The model's fit at its joint optimum, for the test after a refit of its parameters to the rows outside a
        family (module docstring), tried where the test without it places nothing: ``jacobian``, d mu / d u of
        the prediction (unweighted, rows x parameters), and optionally ``predict(du, measurements)``, the
        prediction with the parameters at u + du (None where the model fails;
        :class:`validation.calibration.SetFit`). Without ``predict`` the refit is linear. None: no refit.
    on_evals : callable or None
        Called with the model evaluations the refit spent, whether or not it places the misfit.

    Returns
    -------
    Localized or None
        None without a noise estimate, with fewer than two families of :data:`MIN_ROWS` rows, and when no family
        is missed alone, with or without the refit.

    Raises
    ------
    InputError
        From :func:`validation.outliers.scaled_residual`: the residual is not one finite value per row; or
        ``refit.jacobian`` is not a finite array of one row per measured row.
    """
    z = scaled_residual(residual, noise, measurements)
    if z is None:           # no noise estimate to judge a misfit by
        return None
    masks = {key: mask for key, mask in zip((k for k, _ in FAMILIES), _family_masks(measurements))
             if int(np.sum(mask)) >= MIN_ROWS}
    if len(masks) < 2:
        return None
    found = _missed_alone(z, noise, masks, model, n_params, refitted)
    if found is not None or refit is None:
        return found
    return _missed_after_refit(z, noise, measurements, masks, model, refit, refitted, on_evals)


def _missed_alone(z, noise, masks, model, n_params, refitted):
    """The family missed alone at the joint fit, the others at the noise, the parameters shared out in proportion
    to the rows (module docstring); None when there is none."""
    z2 = z * z
    n = z2.size
    per_row_dof = max(n - int(n_params), 1) / n
    known = noise.source == "mu_std"
    tests = {key: _test(float(np.sum(z2[mask])), int(np.sum(mask)) * per_row_dof, known, noise.dof)
             for key, mask in masks.items()}
    missed = [key for key, (_, p, _) in tests.items() if p < ALPHA / len(masks)]
    if len(missed) != 1:
        return None
    key = missed[0]
    rest = ~masks[key]
    rest_ratio, rest_p, low = _test(float(np.sum(z2[rest])), int(np.sum(rest)) * per_row_dof, known, noise.dof)
    if rest_p < REST_P:
        return None
    ratio, p, _ = tests[key]
    total = float(np.sum(z2))
    return Localized(family=key, n_rows=int(np.sum(masks[key])), ratio=ratio, p_value=p,
                     share=float(np.sum(z2[masks[key]]) / total) if total > 0 else 0.0,
                     rest_rows=int(np.sum(rest)), rest_ratio=rest_ratio, rest_p=rest_p, model=model,
                     noise_source=noise.source, rest_low_p=low, refitted=tuple(refitted))


def _missed_after_refit(z, noise, measurements, masks, model, refit, refitted, on_evals=None):
    """The family that Chow's predictive test finds missed when the model's parameters are refitted to the other
    rows alone, with those rows at the noise (module docstring); None unless exactly one family is."""
    J = np.asarray(getattr(refit, "jacobian", None), dtype=float)
    if J.ndim != 2 or J.shape[0] != z.size or not np.all(np.isfinite(J)):
        raise InputError(f"refit.jacobian: expected finite d mu / d u of shape ({z.size} rows, parameters), got "
                         f"shape {J.shape}" + ("" if J.ndim != 2 or np.all(np.isfinite(J)) else " with non-finite "
                                               "entries"))
    if J.shape[1] == 0:     # no fitted parameters: nothing to trade
        return None
    sigma = np.asarray(noise.row_sigma, dtype=float)
    A = J / sigma[:, None]                  # d z / d u
    rank_all = _rank(A)
    total = float(z @ z)
    known = noise.source == "mu_std"
    found, n_evals = [], 0
    for key, mask in masks.items():
        rest = ~mask
        n_rest, n_f = int(np.sum(rest)), int(np.sum(mask))
        rank_rest = _rank(A[rest])
        d_rest, d_f = n_rest - rank_rest, n_f - (rank_all - rank_rest)
        if rank_rest == 0 or d_rest < MIN_ROWS or d_f < 1:
            continue
        z_rest, used = _refit_rest(z, A, rest, refit, measurements, sigma)
        n_evals += used
        if z_rest is None:
            continue
        rss_rest = float(z_rest @ z_rest)
        ratio, p, _ = _test(max(total - rss_rest, 0.0), d_f, known, noise.dof)
        rest_ratio, rest_p, low = _test(rss_rest, d_rest, known, noise.dof)
        if p < ALPHA / len(masks) and rest_p >= REST_P:
            found.append(Localized(family=key, n_rows=n_f, ratio=ratio, p_value=p,
                                   share=max(total - rss_rest, 0.0) / total if total > 0 else 0.0,
                                   rest_rows=n_rest, rest_ratio=rest_ratio, rest_p=rest_p, model=model,
                                   noise_source=noise.source, rest_low_p=low, refitted=tuple(refitted),
                                   traded=rank_rest))
    if on_evals is not None and n_evals:
        on_evals(n_evals)
    if len(found) != 1:
        return None
    return dataclasses.replace(found[0], n_evals=n_evals)


def _refit_rest(z, A, rest, refit, measurements, sigma):
    """(z on the rows ``rest`` after the model's parameters are refitted to them, model evaluations spent): up to
    :data:`REFIT_STEPS` Gauss-Newton steps on the Jacobian at the joint optimum (``A`` = d z / d u), each evaluated
    with ``refit.predict`` when it has one (the best kept; None when no step could be evaluated), else the linear
    least-squares residual."""
    A_rest, z_rest = A[rest], z[rest]
    du = _lstsq(A_rest, z_rest)
    predict = getattr(refit, "predict", None)
    if predict is None:
        return z_rest - A_rest @ du, 0
    mu_measured = np.asarray(measurements.mu, dtype=float)[rest]
    best, used, at = None, 0, np.zeros_like(du)
    for _ in range(REFIT_STEPS):
        at = at + du
        mu = predict(at, measurements)
        used += 1
        if mu is None:
            break
        now = (mu_measured - np.asarray(mu, dtype=float)[rest]) / sigma[rest]
        if not np.all(np.isfinite(now)):
            break
        better = best is None or float(now @ now) < float(best @ best)
        converged = best is not None and float(now @ now) >= float(best @ best) * (1.0 - 1e-3)
        best = now if better else best
        if converged:
            break
        du = _lstsq(A_rest, now)        # the chord method: the next step on the same Jacobian
    return best, used


def _lstsq(A, b):
    """The least-squares solution of A x = b (directions A does not determine left at zero)."""
    x, *_ = np.linalg.lstsq(A, b, rcond=_RCOND)
    return x


def _rank(A) -> int:
    """The numerical rank of ``A`` (singular values above :data:`_RCOND` times the largest)."""
    if A.size == 0:
        return 0
    s = np.linalg.svd(A, compute_uv=False)
    return int(np.sum(s > _RCOND * s[0])) if s.size and s[0] > 0 else 0


#: Relative cut of the singular values of the Jacobian below which a direction counts as not determined.
_RCOND = 1e-8


def _family_masks(m):
    """The rows of each family of :data:`FAMILIES`, in its order."""
    wet = np.asarray(m.wet, dtype=bool) if m.wet is not None else np.zeros(m.n, dtype=bool)
    sliding = np.asarray(m.slip, dtype=float) >= 1.0
    return sliding & ~wet, ~sliding & ~wet, wet


def _test(s: float, d: float, known: bool, nu: float) -> tuple[float, float, float]:
    """(residual / noise, upper-tail p, lower-tail p) of a sum ``s`` of squared scaled residuals with ``d`` degrees of
    freedom: chi^2 with the noise known, else F (each tail from its own function: a small lower tail is not lost in
    1 - p)."""
    d = max(d, 1e-9)
    ratio = math.sqrt(s / d)
    if known or not math.isfinite(nu):
        return ratio, chi2_sf(s, d), chi2_cdf(s, d)
    return ratio, f_sf(s / d, d, nu), f_cdf(s / d, d, nu)
