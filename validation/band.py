r"""Uncertainty bands of a fitted model's curves: the delta method on the fitted parameters' covariance.

A curve :math:`f(x; \theta)` predicted with the fitted parameters :math:`\hat\theta` has, to first order, the
variance

.. math:: \mathrm{Var}\,f(x) \approx J(x)\, C\, J(x)^T, \qquad J_j(x) = \partial f(x; \theta) / \partial \theta_j,

with :math:`C` the parameters' covariance (the Gauss-Newton one of :mod:`validation.refit`, the Birge ratio
included when the model misses the data): the linearised confidence band of a nonlinear regression function
(Bard, Nonlinear Parameter Estimation (1974); Seber & Wild, Nonlinear Regression (1989), ch. 5). The
derivatives are central differences in the fit's own coordinates ``u`` (the step of the fit's Jacobian, one-sided
at a bound), each side one prediction of the whole curve set through the same prediction path the fit used
(:class:`validation.predict.Predictor`, with the contact when contact parameters were fitted): ``2 k`` predictions
for ``k`` parameters. The band drawn is :math:`f \pm \sqrt{J C J^T}` -- one standard deviation, a 68 % band.

It is linear in the parameters: where the quadratic approximation of the fit fails (a parameter's interval is a
profile-likelihood one) the band is approximate and the caption says so; where a parameter is not identified or
its variance is infinite there is no band, and :func:`band_note` says why.
"""

from __future__ import annotations

import numpy as np

from frictioncite import doi

__all__ = ["band_half_width", "band_note", "band_caveat", "BARD_1974", "SEBER_WILD_1989", "STEP"]

#: Y. Bard, Nonlinear Parameter Estimation, Academic Press, New York (1974).
BARD_1974 = "isbn:9780120782505"
#: G. A. F. Seber, C. J. Wild, Nonlinear Regression, Wiley, New York (1989).
SEBER_WILD_1989 = "isbn:9780471617600"
#: Central-difference step in the fit's coordinates u (that of :meth:`validation.fitting.Fitter.jacobian`).
STEP = 2e-3


@doi(BARD_1974, SEBER_WILD_1989)
def band_half_width(covariance, model, contact, predict, *, step: float = STEP) -> np.ndarray:
    r"""Half-width :math:`\sqrt{\mathrm{diag}(J C J^T)}` of the 68 % band of the curves ``predict`` gives.

    Parameters
    ----------
    covariance : validation.refit.ParameterCovariance
        The fitted parameters' covariance in the fit's coordinates u and the map u -> model.
    model : persson.Model
        The fitted model (the parameters of ``covariance.space`` are set from u on it).
    contact : persson.slip.Contact or None
        The fitted contact (its ``contact.*`` parameters set from u when the fit varied them).
    predict : callable
        ``predict(model, contact) -> ndarray``: the curves (every point of every curve in one array) of a model,
        through the prediction path the fit used.
    step : float
        Central-difference step in u.

    Returns
    -------
    ndarray
        One standard deviation of the predicted curve at each point, same units as ``predict``'s output.
    """
    space = covariance.space
    u = np.clip(np.asarray(covariance.u, dtype=float), 0.0, 1.0)
    cols = []
    for j in range(u.size):
        up, dn = u.copy(), u.copy()
        up[j] = min(u[j] + step, 1.0)
        dn[j] = max(u[j] - step, 0.0)
        f_up = np.asarray(predict(space.apply(model, up), space.apply_contact(contact, up)), dtype=float)
        f_dn = np.asarray(predict(space.apply(model, dn), space.apply_contact(contact, dn)), dtype=float)
        cols.append((f_up - f_dn) / (up[j] - dn[j]))
    if not cols:
        return np.zeros(0)
    J = np.column_stack(cols)
    var = np.einsum("ij,jk,ik->i", J, np.asarray(covariance.matrix, dtype=float), J)
    return np.sqrt(np.clip(var, 0.0, None))


def band_note(covariance, fitted=()) -> str:
    """Why a fitted model's curves carry no band ("" when they do): no parameter was fitted, the covariance is
    missing, or a parameter is not identified by the data."""
    if covariance is None:
        if not fitted:
            return ("no uncertainty band: no parameter was fitted (the model's parameters are as given, without "
                    "an uncertainty from these data)")
        return "no uncertainty band: the covariance of the fitted parameters is not available"
    why = covariance.unavailable()
    return f"no uncertainty band: {why}" if why else ""


def band_caveat(covariance) -> str:
    """What a reader of a drawn band must know: parameters whose interval is not the quadratic one (profile
    likelihood, or widened by equally good optima), where the linearised band is approximate ("" otherwise)."""
    odd = [e.key for e in covariance.estimates if e.method != "quadratic"]
    if not odd:
        return ""
    return (f"the band is linearised: the intervals of {', '.join(odd)} are not quadratic (profile likelihood or "
            "equally good optima), so it is approximate there")
