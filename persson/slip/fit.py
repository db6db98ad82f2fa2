"""Fits of contact and effect parameters of a friction model to measured mu(slip, V) curves (:func:`fit_slip`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .._checks import finite_array, number
from ..errors import InputError
from ._arrays import _broadcast, _slip_array, _speed_array
from .contact import CONTACT_PARAMETERS, Contact
from .curve import predict_slip
from .fitting import NamedParameters
from .references import PACEJKA_BOOK

__all__ = ["SlipFit", "fit_slip"]


@dataclass(frozen=True, eq=False)
class SlipFit(NamedParameters):
    r"""Contact and effect parameters of a friction model fitted to measured mu(slip, V) (:func:`fit_slip`).

    Attributes
    ----------
    names : tuple of str
        Fitted parameters (``"contact.stiffness"``, ``"patch_heating.counter_effusivity"``, ``"gamma"``, ...).
    values, stderr : ndarray
        Best-fit values and standard uncertainties.
    covariance, correlation : ndarray (k, k)
    model, contact : the fitted model and contact
    predicted, residual : ndarray (n,)
    rms : float
        Root-mean-square residual.
    chi2 : float
        Weighted residual sum of squares (:math:`\sum r^2/\sigma^2`; the plain sum without ``sigma``).
    dof : int
        n - k.
    sigma : ndarray or None
        The standard uncertainties given.
    lack_of_fit_p : float or None
        With ``sigma``: :math:`P(\chi^2_{dof} \ge \chi^2)`, small when the model cannot describe the data within
        their uncertainties (None without ``sigma``).
    n_evaluations : int
    notes : tuple of str
    """

    names: tuple
    values: np.ndarray
    stderr: np.ndarray
    covariance: np.ndarray
    correlation: np.ndarray
    model: object
    contact: Contact
    predicted: np.ndarray
    residual: np.ndarray
    rms: float
    chi2: float
    dof: int
    sigma: np.ndarray | None
    lack_of_fit_p: float | None
    n_evaluations: int
    notes: tuple = ()

    @property
    def reduced_chi2(self) -> float:
        """chi2 / dof."""
        return self.chi2 / max(self.dof, 1)

    def summary(self) -> str:
        """Plain text: one line per fitted parameter (value +- standard uncertainty), then the rms, chi2 and dof (with
        the lack-of-fit p when ``sigma`` was given), then the notes."""
        lines = [f"{n} = {v:.6g} +- {e:.3g}" for n, v, e in zip(self.names, self.values, self.stderr)]
        lines.append(f"rms {self.rms:.4g}, chi2 {self.chi2:.4g} on {self.dof} dof"
                     + (f", lack-of-fit p = {self.lack_of_fit_p:.3g}" if self.lack_of_fit_p is not None else ""))
        return "\n".join(lines + list(self.notes))

    def _index(self, name):
        try:
            return self.names.index(name)
        except ValueError:
            raise InputError(f"parameter: {name!r} was not fitted (fitted: {list(self.names)})") from None


def _fit_parameter(name: str, model, contact: Contact):
    """(spec, getter, setter) of a fit parameter name."""
    from ..effects.base import Parameter

    if name == "gamma":
        spec = Parameter("gamma", 0.5, (0.0, 1.0), "1", "gamma of S(q)")
        return spec, (lambda m, c: float(m.gamma)), (lambda m, c, v: (m.replace(gamma=v), c))
    if "." not in name:
        raise InputError(f"vary: {name!r}: expected \"contact.<parameter>\", \"<effect>.<parameter>\" or \"gamma\"")
    owner, par = name.split(".", 1)
    if owner == "contact":
        specs = {p.name: p for p in CONTACT_PARAMETERS}
        if par not in specs:
            raise InputError(f"vary: {name!r}: the contact has {sorted(specs)}")
        if par == "sakai_n" and contact.sakai_n is None:
            raise InputError(f"vary: {name!r}: the contact's pressure is {contact.kind!r}, not Sakai's n-power law")
        return (specs[par], (lambda m, c: float(c.parameter_values()[par])),
                (lambda m, c, v: (m, c.with_parameters(**{par: v}))))
    if owner not in getattr(model, "effect_names", ()):
        raise InputError(f"vary: {name!r}: the model has no effect {owner!r} (has {list(model.effect_names)})")
    eff = model.effect(owner)
    specs = {p.name: p for p in eff.parameters}
    if par not in specs:
        raise InputError(f"vary: {name!r}: {owner} has the documented parameters {sorted(specs)}")
    return (specs[par], (lambda m, c: float(getattr(m.effect(owner), par))),
            (lambda m, c, v: (m.with_effect(m.effect(owner).with_parameters(**{par: v})), c)))


@doi(PACEJKA_BOOK)
def fit_slip(model, slip, speed, mu, *, temperature=20.0, pressure=0.3e6, contact: Contact,
             vary=("contact.stiffness",), sigma=None, p0: dict | None = None, bounds: dict | None = None,
             max_nfev: int = 200) -> SlipFit:
    r"""Fit contact and effect parameters of a friction model to measured mu(slip, V), with standard errors.

    Weighted least squares (:func:`scipy.optimize.least_squares`, trust region with bounds; log-scale parameters
    in log space) of the brush-model prediction :func:`predict_slip` (with patch heating when the model has it).
    The covariance is :math:`(J^TJ)^{-1}` of the weighted residuals at the optimum, :math:`J` by central
    differences (step 1e-3 of each scaled parameter), scaled by :math:`\chi^2/(n - k)` when ``sigma`` is not
    given.

    Parameters
    ----------
    model : persson.Model
    slip, speed, mu : array_like
        Measured rows (slip in (0, 1], V in m/s), broadcast together.
    temperature, pressure : float or array_like
        T0 (deg C) and sigma0 (Pa) per row.
    contact : Contact
    vary : sequence of str
        Parameters to fit: ``"contact.stiffness"``, ``"contact.length"``, ``"contact.sakai_n"``,
        ``"<effect>.<parameter>"`` (a documented parameter of an effect in the model, e.g.
        ``"patch_heating.counter_effusivity"``) or ``"gamma"``. Bounds and scales come from
        :data:`CONTACT_PARAMETERS` and the effects' :class:`~persson.effects.Parameter` specifications.
    sigma : float or array_like, optional
        Standard uncertainties of ``mu``.
    p0 : dict, optional
        Starting values by name (default: the current values).
    bounds : dict, optional
        ``name -> (lo, hi)`` narrowing the documented bounds.
    max_nfev : int
        Largest number of model evaluations of the optimiser.

    Returns
    -------
    SlipFit
    """
    from scipy.optimize import least_squares
    from scipy.stats import chi2 as chi2_dist

    if not isinstance(contact, Contact):
        raise InputError(f"contact: expected a persson.slip.Contact, got {contact!r}")
    s = _slip_array(slip)
    V = _speed_array(speed)
    y = finite_array(mu, "mu")
    T = finite_array(temperature, "temperature")
    p = finite_array(pressure, "pressure")
    s, V, y, T, p = (a.ravel().astype(float) for a in _broadcast("slip, speed, mu, temperature, pressure",
                                                                   s, V, y, T, p))
    n = y.size
    sig = None
    if sigma is not None:
        sig = np.broadcast_to(finite_array(sigma, "sigma").ravel(), y.shape).astype(float) \
            if np.size(sigma) in (1, n) else None
        if sig is None or np.any(sig <= 0):
            raise InputError(f"sigma: expected one value or {n} values, all > 0")
    names = tuple(vary)
    if not names:
        raise InputError("vary: expected at least one parameter to fit")
    if len(set(names)) != len(names):
        raise InputError(f"vary: parameters given twice in {list(names)}")
    k = len(names)
    if n <= k:
        raise InputError(f"mu: {n} rows cannot determine {k} parameters")
    pars = [_fit_parameter(nm, model, contact) for nm in names]
    lo = np.empty(k)
    hi = np.empty(k)
    logs = np.zeros(k, dtype=bool)
    x0 = np.empty(k)
    for i, (nm, (spec, get, _)) in enumerate(zip(names, pars)):
        a, b = (float(v) for v in spec.bounds)
        if bounds and nm in bounds:
            a, b = max(a, number(bounds[nm][0], f"bounds[{nm!r}]")), min(b, number(bounds[nm][1], f"bounds[{nm!r}]"))
        logs[i] = bool(spec.log_scale) and a > 0
        v0 = number(p0[nm], f"p0[{nm!r}]") if p0 and nm in p0 else get(model, contact)
        if not a <= v0 <= b:
            raise InputError(f"p0[{nm!r}]: {v0:g} lies outside the bounds [{a:g}, {b:g}] {spec.unit}")
        lo[i], hi[i] = (math.log(a), math.log(b)) if logs[i] else (a, b)
        x0[i] = math.log(v0) if logs[i] else v0
    w = 1.0 / sig if sig is not None else np.ones(n)
    cache: dict = {}
    count = [0]

    def build(x):
        m, c = model, contact
        for i, (_, _, setter) in enumerate(pars):
            v = math.exp(x[i]) if logs[i] else float(x[i])
            m, c = setter(m, c, v)
        return m, c

    def resid(x):
        m, c = build(np.clip(x, lo, hi))
        count[0] += 1
        return (predict_slip(m, s, V, temperature=T, pressure=p, contact=c, cache=cache) - y) * w

    span = np.where(np.isfinite(hi - lo), hi - lo, 1.0)
    x0 = np.clip(x0, lo + 1e-9 * span, hi - 1e-9 * span)
    res = least_squares(resid, x0, bounds=(lo, hi), method="trf", x_scale="jac", diff_step=1e-4,
                        max_nfev=int(max_nfev), xtol=1e-10, ftol=1e-12, gtol=1e-10)
    x = res.x
    r0 = resid(x)
    # Jacobian by central differences at the optimum (steps inside the bounds)
    J = np.empty((n, k))
    for i in range(k):
        h = 1e-3 * max(1.0, abs(x[i])) if not logs[i] else 1e-3
        up, dn = x.copy(), x.copy()
        up[i] = min(x[i] + h, hi[i])
        dn[i] = max(x[i] - h, lo[i])
        J[:, i] = (resid(up) - resid(dn)) / (up[i] - dn[i])
    chi2 = float(r0 @ r0)
    dof = n - k
    notes = []
    try:
        cov_x = np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov_x = np.linalg.pinv(J.T @ J)
        notes.append("the parameters are not all determined by the data (singular normal matrix)")
    if sig is None:
        cov_x = cov_x * chi2 / max(dof, 1)
    vals = np.where(logs, np.exp(x), x)
    D = np.where(logs, vals, 1.0)
    cov = cov_x * D[:, None] * D[None, :]
    std = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(std, std)
    corr = np.where(np.isfinite(corr), corr, 0.0)
    at_bound = [nm for i, nm in enumerate(names) if min(x[i] - lo[i], hi[i] - x[i]) < 1e-6 * span[i]]
    if at_bound:
        notes.append(f"parameter(s) {at_bound} at their bound; their uncertainties are not meaningful")
    if not res.success:
        notes.append(f"the optimiser stopped: {res.message}")
    m_fit, c_fit = build(x)
    pred = y + r0 / w
    p_lof = float(chi2_dist.sf(chi2, dof)) if sig is not None else None
    return SlipFit(names=names, values=vals, stderr=std, covariance=cov, correlation=corr, model=m_fit,
                   contact=c_fit, predicted=pred, residual=y - pred, rms=float(np.sqrt(np.mean((y - pred) ** 2))),
                   chi2=chi2, dof=dof, sigma=sig, lack_of_fit_p=p_lof, n_evaluations=count[0], notes=tuple(notes))
