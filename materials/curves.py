r"""Master curves used as measured: interpolated tables, their extrapolation, a causality check, smoothing.

:class:`InterpolatedModulus` is a master curve at its reference temperature given by nodes
:math:`(\omega_k, E'_k, E''_k)`. Between nodes, :math:`\log E'` and :math:`\log E''` are interpolated in
:math:`\log\omega` by a monotone piecewise-cubic Hermite interpolant (PCHIP: Fritsch & Carlson 1980; the
derivative formula of Fritsch & Butland 1984, as in ``scipy.interpolate.PchipInterpolator``): the curve passes
through every node exactly, is continuous with a continuous slope, and never overshoots the nodes (a
monotone E' stays monotone). Outside the nodes (the friction engine evaluates E over many decades beyond any
measurement):

* :math:`E'` is held at its end values (the rubbery plateau below the data, the glassy plateau above);
* :math:`E''` continues as the power law of its last decade of data,
  :math:`E''(\omega) = E''_{end} (\omega/\omega_{end})^{s}`, with the exponent limited to
  :math:`0 \le s \le 1` below the data and :math:`-1 \le s \le 0` above it: a passive linear solid has
  :math:`E'' \propto \omega` as :math:`\omega \to 0` and :math:`E'' \propto 1/\omega` as
  :math:`\omega \to \infty` (Ferry 1980, ch. 3), and no extrapolation may make :math:`E''` grow away from
  the data.

:func:`causality_check` compares :math:`E''` with the local Kramers-Kronig estimate of Booij & Thoone (1982),
:math:`E''(\omega) \approx \frac{\pi}{2}\, \mathrm{d}E'/\mathrm{d}\ln\omega`. :func:`smooth_master` turns
scattered, shifted isotherms into such nodes (penalised B-splines, Eilers & Marx 1996).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .errors import InputError

__all__ = ["InterpolatedModulus", "CausalityCheck", "causality_check", "smooth_master", "KK_FACTOR"]

#: Tolerance of the causality check: :math:`E''` may differ from its local Kramers-Kronig estimate by this factor.
#: For a power-law modulus :math:`E^* \propto (i\omega)^n` the exact ratio is
#: :math:`\tan(n\pi/2)/(n\pi/2)`, which stays below 3 for slopes :math:`n \le 0.84` (rubber's transition zone has
#: :math:`n \lesssim 0.7`, Ferry 1980, ch. 12); a single Debye relaxation gives ratios down to 0.64.
KK_FACTOR = 3.0

#: Relative precision assumed for tabulated moduli (four to five significant figures) when the nodes show less
#: scatter: it sets the smallest uncertainty of the slope of E' in the causality check.
_PRECISION = 1e-4

#: Width of the scatter band, in standard deviations: 4 keeps false alarms on a noisy table of a few hundred
#: nodes near 1 % (a one-sided normal tail of 3e-5 per node and criterion).
_Z = 4.0


@doi("10.1137/0717021", "10.1137/0905021", "isbn:978-0-471-04894-7")
@dataclass(frozen=True, eq=False, repr=False)
class InterpolatedModulus:
    r"""Complex modulus at the reference temperature, interpolated through tabulated nodes (see the module).

    Parameters
    ----------
    omega : array_like
        Angular frequencies of the nodes, rad/s (> 0, distinct; sorted on construction).
    E_storage, E_loss : array_like
        :math:`E'` and :math:`E''` at the nodes, Pa (> 0).
    source : str
        Where the nodes come from (in messages and reprs).

    Attributes
    ----------
    loss_slopes : tuple of float
        Exponents :math:`s` of the power laws that continue :math:`E''` below and above the nodes.
    """

    omega: np.ndarray
    E_storage: np.ndarray
    E_loss: np.ndarray
    source: str = ""
    loss_slopes: tuple[float, float] = (0.0, 0.0)

    def __init__(self, omega, E_storage, E_loss, source: str = ""):
        from scipy import interpolate
        w = np.array(omega, dtype=float).ravel()
        E1 = np.array(E_storage, dtype=float).ravel()
        E2 = np.array(E_loss, dtype=float).ravel()
        if not (w.size == E1.size == E2.size):
            raise InputError(f"{source or 'master curve'}: omega, E_storage and E_loss differ in length "
                             f"({w.size}, {E1.size}, {E2.size})")
        if w.size < 2:
            raise InputError(f"{source or 'master curve'}: a master-curve table needs at least two rows")
        for name, a in (("omega", w), ("E_storage", E1), ("E_loss", E2)):
            ok = np.isfinite(a) & (a > 0)
            if not ok.all():
                i = int(np.flatnonzero(~ok)[0])
                raise InputError(f"{source or 'master curve'}: {name}[{i}] = {a[i]!r}; expected finite positive "
                                 "values")
        order = np.argsort(w, kind="stable")
        w, E1, E2 = w[order], E1[order], E2[order]
        if np.any(np.diff(w) == 0):
            i = int(np.flatnonzero(np.diff(w) == 0)[0])
            raise InputError(f"{source or 'master curve'}: frequency {w[i] / (2 * math.pi):g} Hz appears twice "
                             "(one row per frequency expected)")
        for name, a in (("omega", w), ("E_storage", E1), ("E_loss", E2)):
            a.setflags(write=False)
            object.__setattr__(self, name, a)
        object.__setattr__(self, "source", str(source))
        x = np.log10(w)
        object.__setattr__(self, "_x", x)
        object.__setattr__(self, "_p1", interpolate.PchipInterpolator(x, np.log10(E1), extrapolate=False))
        object.__setattr__(self, "_p2", interpolate.PchipInterpolator(x, np.log10(E2), extrapolate=False))
        lo = _end_slope(x, np.log10(E2), low=True)
        hi = _end_slope(x, np.log10(E2), low=False)
        object.__setattr__(self, "loss_slopes", (min(max(lo, 0.0), 1.0), min(max(hi, -1.0), 0.0)))

    def __reduce__(self):
        return (InterpolatedModulus, (self.omega, self.E_storage, self.E_loss, self.source))

    @property
    def frequency_range(self) -> tuple[float, float]:
        """Angular frequencies of the first and last node, rad/s."""
        return float(self.omega[0]), float(self.omega[-1])

    def E_reference(self, omega):
        """Complex modulus at ``omega`` (rad/s, any sign and shape; Im E odd, E(0) real), Pa."""
        omega = np.asarray(omega, dtype=float)
        if np.isnan(omega).any():
            raise InputError("omega: NaN angular frequency (expected numbers in rad/s)")
        aw = np.abs(omega)
        with np.errstate(divide="ignore"):
            x = np.log10(aw)
        x0, xn = self._x[0], self._x[-1]
        xc = np.clip(x, x0, xn)
        l1 = self._p1(xc)
        l2 = self._p2(xc)
        s_lo, s_hi = self.loss_slopes
        # beyond the nodes: flat E', power-law E'' (clipped offsets keep 0 * inf out of the products)
        l2 = l2 + s_lo * np.clip(x - x0, -1e3, 0.0) + s_hi * np.clip(x - xn, 0.0, 1e3)
        E1 = np.where(aw <= self.omega[0], self.E_storage[0], np.where(aw >= self.omega[-1], self.E_storage[-1],
                                                                     10.0 ** l1))
        E2 = 10.0 ** l2
        # the nodes themselves are returned exactly as given
        k = np.clip(np.searchsorted(self.omega, aw), 0, self.omega.size - 1)
        hit = self.omega[k] == aw
        if hit.any():
            E1 = np.where(hit, self.E_storage[k], E1)
            E2 = np.where(hit, self.E_loss[k], E2)
        E2 = np.where(omega == 0.0, 0.0, E2 * np.sign(omega))
        return E1 + 1j * E2

    def scaled(self, omega_factor: float, modulus_factor: float = 1.0) -> "InterpolatedModulus":
        """The same curve with frequencies multiplied by ``omega_factor`` and moduli by ``modulus_factor``."""
        return InterpolatedModulus(self.omega * omega_factor, self.E_storage * modulus_factor,
                                   self.E_loss * modulus_factor, source=self.source)

    def __repr__(self) -> str:
        lo, hi = self.frequency_range
        return (f"InterpolatedModulus({self.omega.size} nodes, {lo / (2 * math.pi):.3g} to {hi / (2 * math.pi):.3g} "
                f"Hz" + (f", {self.source}" if self.source else "") + ")")


# ==================================================================================================== causality

@dataclass(frozen=True, eq=False, repr=False)
class CausalityCheck:
    r"""Where a tabulated :math:`E''` disagrees with the local Kramers-Kronig estimate beyond the data scatter.

    Attributes
    ----------
    omega : ndarray
        Nodes checked, rad/s.
    ratio : ndarray
        :math:`E'' / (\frac{\pi}{2}\,\mathrm{d}E'/\mathrm{d}\ln\omega)` at the nodes (inf where E' is flat).
    violated : ndarray of bool
        Nodes where the disagreement exceeds :data:`KK_FACTOR` beyond the uncertainty of the slope of E', or
        where E' decreases with frequency beyond its scatter.
    scatter : float
        Relative scatter of E' used for the slope uncertainty.
    factor : float
        The tolerance factor.
    """

    omega: np.ndarray
    ratio: np.ndarray
    violated: np.ndarray
    scatter: float
    factor: float
    decreasing: np.ndarray | None = None

    @property
    def ok(self) -> bool:
        """Whether no node violates the check."""
        return not bool(self.violated.any())

    def message(self, source: str = "") -> str:
        """One sentence naming the frequency bands where the check fails (empty when it passes)."""
        if self.ok:
            return ""
        f = self.omega / (2 * math.pi)
        bands = _bands(f, self.violated)
        parts = []
        if self.decreasing is not None and self.decreasing.any():
            parts.append("E' decreases with frequency at " + _bands(f, self.decreasing))
        parts.append(f"E'' differs from (pi/2) dE'/dln(omega) by more than a factor {self.factor:g} beyond the "
                     f"scatter at {bands}")
        return (f"{source + ': ' if source else ''}the master curve looks non-causal (Kramers-Kronig, local "
                f"approximation of Booij & Thoone 1982): " + "; ".join(parts)
                + " (reduced frequency at T_ref); check units, shifts and columns there")

    def __repr__(self) -> str:
        return (f"CausalityCheck({'ok' if self.ok else f'{int(self.violated.sum())} of {self.omega.size} nodes off'}"
                f", factor {self.factor:g}, scatter {self.scatter:.2g})")


@doi("10.1007/BF01520701", "isbn:978-0-471-04894-7")
def causality_check(omega, E_storage, E_loss, *, scatter: float | None = None,
                    factor: float = KK_FACTOR) -> CausalityCheck:
    r"""Check tabulated :math:`E'(\omega), E''(\omega)` against the local Kramers-Kronig relation.

    Booij & Thoone (1982) derive from the Kramers-Kronig relations the local approximation

    .. math:: E''(\omega) \approx \frac{\pi}{2}\, \frac{\mathrm{d} E'(\omega)}{\mathrm{d}\ln\omega},

    exact for a flat spectrum and within a factor :data:`KK_FACTOR` (3) for power-law moduli with slopes up to
    0.84 and for a single relaxation (see :data:`KK_FACTOR`). The slope of E' is taken by finite differences
    on the nodes (second-order differences on the non-uniform grid); its uncertainty :math:`\delta` is four
    standard deviations (:data:`_Z`) of that difference for independent relative errors :math:`\sigma` of the
    nodes, with
    :math:`\sigma` the relative scatter of E' (estimated from the second differences of :math:`\ln E'` when not
    given: the robust scatter of the second differences of :math:`\ln E'` over 25 neighbouring nodes, at least
    that of the whole table and at least :data:`_PRECISION`). A node is flagged when

    * :math:`E'' e^{-4\sigma''} > f\,\frac{\pi}{2}(E'_{\ln\omega} + \delta)` or
      :math:`E'' e^{4\sigma''} < \frac{\pi}{2}(E'_{\ln\omega} - \delta)/f` (the latter only where the lower
      bound is positive; :math:`\sigma''` the relative scatter of E''), or
    * :math:`E'_{\ln\omega} + \delta < 0` (E' decreasing: impossible for a positive relaxation spectrum).

    Parameters
    ----------
    omega, E_storage, E_loss : array_like
        Nodes, rad/s and Pa (sorted by frequency).
    scatter : float, optional
        Relative scatter of E' (e.g. of the shifted data about the master curve).
    factor : float
        Tolerance factor (> 1).

    Returns
    -------
    CausalityCheck
    """
    w = np.asarray(omega, dtype=float)
    E1 = np.asarray(E_storage, dtype=float)
    E2 = np.asarray(E_loss, dtype=float)
    if w.size < 3:
        return CausalityCheck(w, np.full(w.size, np.inf), np.zeros(w.size, dtype=bool), 0.0, factor)
    x = np.log(w)
    if scatter is None:
        s1 = _local_scatter(np.log(E1))
        s2 = _local_scatter(np.log(E2))
    else:
        s1 = s2 = np.full(w.size, float(scatter))
    s1 = np.maximum(s1, _PRECISION)
    s2 = np.maximum(s2, _PRECISION)
    slope, gain = _derivative(x, E1)
    delta = _Z * s1 * E1 * gain
    est = 0.5 * math.pi * slope
    hi = 0.5 * math.pi * (slope + delta)
    lo = 0.5 * math.pi * (slope - delta)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(est > 0, E2 / est, np.inf)
    decreasing = (slope + delta) < 0
    too_big = (hi > 0) & (E2 * np.exp(-_Z * s2) > factor * hi)
    too_small = (lo > 0) & (E2 * np.exp(_Z * s2) < lo / factor)
    sigma = float(np.median(s1))
    return CausalityCheck(omega=w, ratio=ratio, violated=decreasing | too_big | too_small, scatter=sigma,
                          factor=float(factor), decreasing=decreasing)


# ==================================================================================================== smoothing

@doi("10.1214/ss/1038425655", "10.1007/BF01404567")
def smooth_master(log10_omega, ln_storage, ln_loss, *, per_decade: float = 10.0, knots_per_decade: float = 5.0,
                  robust: bool = True, monotone_storage: bool = True):
    r"""Nodes of a smooth master curve through scattered, shifted isotherms.

    Each of :math:`\ln E'` and :math:`\ln E''` is fitted as a function of :math:`\log_{10}\omega` by a
    penalised cubic B-spline (P-spline, Eilers & Marx 1996: ``knots_per_decade`` equally spaced knots and a
    second-difference penalty whose weight minimises the generalised cross-validation score, Craven & Wahba
    1979; with
    ``robust``, three rounds of Huber reweighting (tuning constant 1.345 robust standard deviations) so that a
    few bad points do not bend the curve). The spline is then sampled ``per_decade`` times per decade over
    the data's range; with ``monotone_storage`` the samples of :math:`\ln E'` are made non-decreasing by
    isotonic regression (pool-adjacent-violators), since E' of a solid with a positive relaxation spectrum
    cannot decrease with frequency.

    Parameters
    ----------
    log10_omega, ln_storage, ln_loss : array_like
        The shifted data: log10 of the reduced angular frequency and the natural logs of E' and E'' (Pa).

    Returns
    -------
    omega, E_storage, E_loss : ndarray
        Nodes (rad/s, Pa).
    scatter : float
        Robust RMS residual of :math:`\ln E'` and :math:`\ln E''` about the splines (relative scatter).
    """
    x = np.asarray(log10_omega, dtype=float).ravel()
    ys = [np.asarray(ln_storage, dtype=float).ravel(), np.asarray(ln_loss, dtype=float).ravel()]
    lo, hi = float(x.min()), float(x.max())
    if not hi > lo:
        raise InputError("smooth_master: the shifted data span no frequency range")
    n_nodes = max(2, int(math.ceil((hi - lo) * per_decade)) + 1)
    xn = np.linspace(lo, hi, n_nodes)
    out, resid = [], []
    for y in ys:
        f, r = _pspline(x, y, knots_per_decade, robust)
        out.append(f(xn))
        resid.append(r)
    if monotone_storage:
        out[0] = _isotonic(out[0])
    r = np.concatenate(resid)
    scatter = 1.4826 * float(np.median(np.abs(r)))
    return 10.0 ** xn, np.exp(out[0]), np.exp(out[1]), scatter


# ==================================================================================================== helpers

def _pspline(x, y, knots_per_decade, robust):
    r"""P-spline fit (GCV-chosen penalty, optional Huber reweighting); returns the fitted curve and residuals.

    For each weighting the generalised eigenproblem :math:`D^TD v = s\, B^TWB v` (Demmler-Reinsch basis) makes
    every penalty weight cost one matrix-vector product: the coefficients are
    :math:`V (I + \lambda S)^{-1} V^T B^TWy` and the effective degrees of freedom :math:`\sum_i 1/(1+\lambda s_i)`.
    """
    from scipy import interpolate, linalg
    lo, hi = float(x.min()), float(x.max())
    nseg = max(3, int(math.ceil((hi - lo) * knots_per_decade)))
    k = 3
    inner = np.linspace(lo, hi, nseg + 1)
    t = np.concatenate([[lo] * k, inner, [hi] * k])
    B = interpolate.BSpline.design_matrix(np.clip(x, lo, hi), t, k).tocsr()     # 4 non-zeros per row
    nb = B.shape[1]
    D = np.diff(np.eye(nb), n=2, axis=0)
    DtD = D.T @ D
    w = np.ones(x.size)
    for _ in range(4 if robust else 1):
        BtW = (B.T.multiply(w)).tocsr()
        BtWB = (BtW @ B).toarray()
        ridge = 1e-10 * np.trace(BtWB) / nb           # basis functions without data stay well posed
        s_eig, V = linalg.eigh(DtD, BtWB + ridge * np.eye(nb))
        s_eig = np.maximum(s_eig, 0.0)
        z = V.T @ (BtW @ y)
        yWy = float(np.dot(w * y, y))
        n_eff = float(w.sum())
        scale = np.trace(BtWB) / np.trace(DtD)
        best = None
        for lam in scale * 10.0 ** np.arange(-6.0, 4.01, 0.25):
            shrink = 1.0 / (1.0 + lam * s_eig)
            edf = float(shrink.sum())
            if n_eff - edf < 1.0:
                continue
            # weighted residual sum of squares in the Demmler-Reinsch basis: y'Wy - sum (2h - h^2) z^2
            rss = max(yWy - float(np.sum((2.0 * shrink - shrink * shrink) * z * z)), 0.0)
            gcv = n_eff * rss / (n_eff - edf) ** 2
            if best is None or gcv < best[0]:
                best = (gcv, shrink)
        if best is None:
            raise InputError("smooth_master: too few shifted points for a smooth master curve")
        c = V @ (best[1] * z)
        r = y - B @ c
        if not robust:
            break
        # robust scale of the residuals, at least 0.1 % (exact synthetic data would otherwise be reweighted by
        # their rounding errors)
        sd = max(1.4826 * float(np.median(np.abs(r))), 1e-3)
        a = np.abs(r) / (1.345 * sd)
        w = np.where(a <= 1.0, 1.0, 1.0 / np.maximum(a, 1e-12))
    spline = interpolate.BSpline(t, c, k, extrapolate=False)
    return (lambda z_: spline(np.clip(z_, lo, hi))), r


def _isotonic(y):
    """Non-decreasing least-squares fit of a sequence (pool adjacent violators)."""
    vals, sizes = [], []
    for v in np.asarray(y, dtype=float):
        vals.append(v)
        sizes.append(1)
        while len(vals) > 1 and vals[-2] > vals[-1]:
            v2, n2 = vals.pop(), sizes.pop()
            v1, n1 = vals.pop(), sizes.pop()
            vals.append((v1 * n1 + v2 * n2) / (n1 + n2))
            sizes.append(n1 + n2)
    return np.repeat(vals, sizes)



def _end_slope(x, y, *, low: bool, span: float = 1.0) -> float:
    """Least-squares slope of y(x) over the last ``span`` of x at one end (at least the two end nodes)."""
    if low:
        m = x <= x[0] + span
        if m.sum() < 2:
            m[:2] = True
    else:
        m = x >= x[-1] - span
        if m.sum() < 2:
            m[-2:] = True
    xs, ys = x[m], y[m]
    dx = xs - xs.mean()
    return float(np.dot(dx, ys - ys.mean()) / np.dot(dx, dx))


def _derivative(x, y):
    """dy/dx on a non-uniform grid (second-order central differences, first-order at the ends) and the noise gain
    sqrt(sum of squared weights): the SD of the derivative is gain * SD of y for independent errors."""
    n = x.size
    h1 = np.diff(x)[:-1]
    h2 = np.diff(x)[1:]
    a = -h2 / (h1 * (h1 + h2))
    b = (h2 - h1) / (h1 * h2)
    c = h1 / (h2 * (h1 + h2))
    d = np.empty(n)
    g = np.empty(n)
    d[1:-1] = a * y[:-2] + b * y[1:-1] + c * y[2:]
    g[1:-1] = np.sqrt(a * a + b * b + c * c)
    d[0] = (y[1] - y[0]) / (x[1] - x[0])
    d[-1] = (y[-1] - y[-2]) / (x[-1] - x[-2])
    g[0] = math.sqrt(2.0) / (x[1] - x[0])
    g[-1] = math.sqrt(2.0) / (x[-1] - x[-2])
    return d, g


def _local_scatter(y, half_width: int = 12) -> np.ndarray:
    """Relative scatter of a sequence at each node: robust SD of its second differences over a moving window.

    For white noise of SD sigma the second difference has SD sqrt(6) sigma; the median absolute value over
    2 * half_width + 1 nodes, times 1.4826 / sqrt(6), estimates sigma (a smooth curve contributes only its
    small curvature). The window's estimate is kept at least the whole sequence's, since a median of a few
    correlated differences can fall far below the true scatter (the check then errs on the side of silence).
    """
    d2 = np.abs(np.diff(y, 2))
    d2 = np.concatenate([d2[:1], d2, d2[-1:]])
    n = d2.size
    out = np.empty(n)
    for i in range(n):
        out[i] = np.median(d2[max(0, i - half_width): i + half_width + 1])
    out = np.maximum(out, float(np.median(d2)))
    return 1.4826 * out / math.sqrt(6.0)


def _bands(f, mask) -> str:
    idx = np.flatnonzero(mask)
    groups = np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1)
    return ", ".join(f"{f[g[0]]:.3g}-{f[g[-1]]:.3g} Hz" if g.size > 1 else f"{f[g[0]]:.3g} Hz" for g in groups[:5])
