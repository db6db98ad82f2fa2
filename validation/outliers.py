r"""Rows that lie too far from the model to be noise: a fault of a single measurement, not missing physics.

A bad run (a wheel that bounced, a wet patch on a dry disk, a mistyped value) puts a row several noise levels away
from every smooth model. Such rows inflate the misfit, and a local-difference noise estimate with it, and can
shift fitted parameters; the pattern tests, made for trends, do not single them out.

Each row's residual from the verdict's model is scaled by that row's noise level,
:math:`z_i = r_i / \sigma_i`, and compared with the two-sided Bonferroni threshold for ``n`` rows at level
:data:`ALPHA`,

.. math:: t = F^{-1}\!\left(1 - \frac{\alpha}{2n}\right),

F Student's t distribution with the noise estimate's degrees of freedom (the normal one with ``mu_std``): with
pure Gaussian noise, a data set has a row beyond t with probability at most :math:`\alpha` (the Bonferroni outlier
test, R. D. Cook, S. Weisberg, Residuals and Influence in Regression, Chapman and Hall (1982), sec. 2.2; the
residual of a fitted model varies a little less than the noise, so the rate is lower still). Rows beyond t are
named, by their line in the measurement file where it is known, when they are few -- at most
:data:`MAX_SHARE` of the rows, and never more than :data:`MAX_ROWS`: many rows far off are a model that misses the
data, which the lack-of-fit and pattern tests describe, not faults of single rows. Nothing is removed: the user
decides whether a row is a fault.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from frictioncite import doi

from .distributions import t_isf
from .errors import InputError

__all__ = ["Outliers", "outlying_rows", "scaled_residual", "ALPHA", "MAX_SHARE", "MAX_ROWS"]

#: Probability that a data set of pure Gaussian noise has any row named.
ALPHA = 0.01
#: Largest share of the rows that can be named as single faults.
MAX_SHARE = 0.05
#: Largest number of rows named.
MAX_ROWS = 5
#: R. D. Cook, S. Weisberg, Residuals and Influence in Regression, Chapman and Hall, New York (1982).
COOK_WEISBERG_1982 = "cook-weisberg:residuals-1982"


@dataclass(frozen=True)
class Outliers:
    """Rows beyond the Bonferroni threshold of the verdict's model.

    Attributes
    ----------
    rows : tuple of int
        Their indices (0-based), farthest first.
    lines : tuple of int
        Their lines in the measurement file (0 where not known).
    z : tuple of float
        Their residuals over their noise levels (measured - predicted).
    threshold : float
        The threshold on |z|.
    model : str
        The model the residuals are of.
    source : str
        The measurement file (or ``"<arrays>"``).
    """

    rows: tuple
    lines: tuple
    z: tuple
    threshold: float
    model: str
    source: str = ""

    def text(self) -> str:
        """One sentence naming the rows and how far each lies, and what to do."""
        where = [f"line {ln}" if ln > 0 else f"row {i}" for i, ln in zip(self.rows, self.lines)]
        far = ", ".join(f"{w} ({z:+.1f})" for w, z in zip(where, self.z))
        one = len(self.rows) == 1
        what = "A row lies" if one else f"{len(self.rows)} rows lie"
        src = f" of {self.source}" if self.source and not self.source.startswith("<") else ""
        check = "Check it for a fault" if one else "Check them for faults"
        return (f"{what} farther from {self.model} than noise would put any row (residual / noise beyond "
                f"{self.threshold:.2f}, which pure noise exceeds anywhere in 1 of {round(1 / ALPHA)} data sets): "
                f"{far}{src}. {check} of the measurement (the verdict uses every row).")

    def as_dict(self) -> dict:
        """``rows``, ``lines``, ``z``, ``threshold``, ``alpha``, ``model`` and ``source``."""
        return {"rows": list(self.rows), "lines": list(self.lines), "z": list(self.z), "threshold": self.threshold,
                "alpha": ALPHA, "model": self.model, "source": self.source}


# ==========================================================================================================
@doi(COOK_WEISBERG_1982)
def outlying_rows(residual, noise, measurements, model: str) -> Outliers | None:
    """The rows whose residual from ``model`` lies beyond the Bonferroni threshold (module docstring).

    Parameters
    ----------
    residual : array_like (n,)
        Measured - predicted mu.
    noise : validation.noise.NoiseEstimate
        Per-row noise levels (``row_sigma``) and their degrees of freedom.
    measurements : validation.Measurements
        For the rows' lines in the file.
    model : str
        What the residual is of, for the text (e.g. ``"the baseline + flash_temperature"``).

    Returns
    -------
    Outliers or None
        None without a noise estimate, when no row is beyond the threshold, or when too many are to be single
        faults.

    Raises
    ------
    InputError
        ``residual`` does not have one finite value per row of ``measurements`` and of the noise.
    """
    z = scaled_residual(residual, noise, measurements)
    if z is None:
        return None
    n = z.size
    tail = ALPHA / (2.0 * n)
    t = t_isf(tail, noise.dof if not math.isfinite(noise.dof) else max(noise.dof, 1.0))
    far = np.flatnonzero(np.abs(z) > t)
    if far.size == 0 or far.size > min(MAX_ROWS, max(1, math.floor(MAX_SHARE * n))):
        return None
    far = far[np.argsort(-np.abs(z[far]))]
    lines = measurements.lines
    return Outliers(rows=tuple(int(i) for i in far),
                    lines=tuple(int(lines[i]) if lines is not None else 0 for i in far),
                    z=tuple(float(z[i]) for i in far), threshold=t, model=model,
                    source=str(getattr(measurements, "source", "") or ""))


def scaled_residual(residual, noise, measurements) -> np.ndarray | None:
    r"""Each row's residual over its noise level, :math:`z_i = r_i / \sigma_i`.

    Parameters
    ----------
    residual : array_like (n,)
        Measured - predicted mu.
    noise : validation.noise.NoiseEstimate
        Per-row noise levels (``row_sigma``).
    measurements : validation.Measurements
        The rows the residual is of.

    Returns
    -------
    ndarray (n,) or None
        None without a noise estimate, without rows, or when a row's noise level is not a positive number.

    Raises
    ------
    InputError
        ``residual`` does not have one finite value per row of ``measurements`` and of the noise.
    """
    if not noise.known:
        return None
    r = np.asarray(residual, dtype=float)
    sigma = np.asarray(noise.row_sigma, dtype=float)
    if r.ndim != 1 or r.size != measurements.n or sigma.shape != r.shape or not np.all(np.isfinite(r)):
        raise InputError(f"residual: expected one finite value per row ({measurements.n} rows, noise levels for "
                         f"{sigma.size}), got shape {r.shape}")
    if r.size == 0 or not np.all(np.isfinite(sigma) & (sigma > 0)):
        return None
    return r / sigma
