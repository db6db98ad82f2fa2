r"""Generalized Maxwell (Prony) fit of a master curve: fixed log-spaced relaxation times, NNLS, pruned.

.. math::
    E'(\omega) = E_\infty + \sum_i E_i \frac{\omega^2\tau_i^2}{1+\omega^2\tau_i^2},\qquad
    E''(\omega) = \sum_i E_i \frac{\omega\tau_i}{1+\omega^2\tau_i^2}

with :math:`E_\infty, E_i \ge 0` (Park & Schapery 1999). Both components are fitted together, each row divided
by its measured value (relative residuals), by non-negative least squares (Lawson & Hanson 1974,
``scipy.optimize.nnls``). Every term is a Debye relaxation, so the fit is causal (Kramers-Kronig consistent)
by construction; non-negative strengths make it thermodynamically admissible.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .errors import InputError
from .viscoelastic import Prony, Thermal

__all__ = ["FitQuality", "PronyFit", "fit_prony", "quality_of"]


@dataclass(frozen=True)
class FitQuality:
    r"""How well a master curve's representation (causal Prony series or interpolated table) reproduces the data.

    Attributes
    ----------
    rms_rel_storage, rms_rel_loss : float
        RMS relative residual :math:`\sqrt{\langle (E'_{fit}/E'_{data} - 1)^2\rangle}` (and for E'').
    rms_rel : float
        Both together, :math:`\sqrt{(\mathrm{rms}_{E'}^2 + \mathrm{rms}_{E''}^2)/2}`.
    max_rel_storage, max_rel_loss : float
        Largest relative residuals.
    n_points : int
        Number of data points fitted.
    n_terms : int
        Number of Maxwell terms kept after pruning.
    shift_rms_log10 : float or None
        RMS scatter (decades) of the shifted data about a smooth master curve, when shifts were computed.
    representation : str
        ``"prony"`` (causal Prony series) or ``"table"`` (interpolated nodes).
    """

    rms_rel_storage: float
    rms_rel_loss: float
    rms_rel: float
    max_rel_storage: float
    max_rel_loss: float
    n_points: int
    n_terms: int
    shift_rms_log10: float | None = None
    representation: str = "prony"

    def __str__(self) -> str:
        what = ("Prony fit: RMS relative residual" if self.representation == "prony"
                else "interpolated table: RMS relative residual")
        size = f", {self.n_terms} terms" if self.representation == "prony" else ""
        s = (f"{what} E' {100 * self.rms_rel_storage:.2f} %, E'' {100 * self.rms_rel_loss:.2f} % "
             f"({self.n_points} points{size})")
        if self.shift_rms_log10 is not None:
            s += f"; shifted-data scatter {self.shift_rms_log10:.3f} decades"
        return s


@dataclass(frozen=True, eq=False, repr=False)
class PronyFit:
    """Result of :func:`fit_prony`: the series (at the reference temperature) and its quality."""

    prony: Prony
    quality: FitQuality

    def __repr__(self) -> str:
        return f"PronyFit({self.prony!r}; {self.quality})"


@doi("10.1016/S0020-7683(98)00055-9", "10.1137/1.9781611971217")
def fit_prony(omega, E_storage, E_loss, *, tau=None, per_decade: float = 2.0, margin: float = 1.0,
              prune: float = 1e-4, thermal: Thermal | None = None, label: str = "") -> PronyFit:
    r"""Fit a generalized Maxwell solid to E'(omega), E''(omega) by NNLS with relative weights.

    Parameters
    ----------
    omega : array_like
        Angular (reduced) frequencies, rad/s (> 0).
    E_storage, E_loss : array_like
        Storage and loss moduli, Pa (> 0).
    tau : array_like, optional
        Relaxation times, s. Default: log-spaced, ``per_decade`` per decade, from
        :math:`10^{-margin}/\omega_{max}` to :math:`10^{margin}/\omega_{min}`.
    per_decade : float
        Density of the default relaxation times.
    margin : float
        Decades by which the default times extend beyond the data window.
    prune : float
        Terms whose removal changes the fitted moduli by less than this fraction anywhere on the data are
        dropped (with a refit); exact zeros from NNLS are always dropped.
    thermal : Thermal, optional
        Carried by the returned Prony series.
    label : str
        Carried by the returned Prony series.

    Returns
    -------
    PronyFit
        ``prony`` (``E_inf``, ``E_i``, ``tau_i``; no WLF: the fit is at the reference temperature) and
        ``quality`` (:class:`FitQuality`).

    Raises
    ------
    InputError
        Fewer than two points, non-positive or non-finite values, mismatched lengths.
    """
    w = np.asarray(omega, dtype=float).ravel()
    E1 = np.asarray(E_storage, dtype=float).ravel()
    E2 = np.asarray(E_loss, dtype=float).ravel()
    if not (w.size == E1.size == E2.size):
        raise InputError(f"fit_prony: omega, E_storage, E_loss differ in length ({w.size}, {E1.size}, {E2.size})")
    if w.size < 2:
        raise InputError("fit_prony: need at least two points")
    for name, a in (("omega", w), ("E_storage", E1), ("E_loss", E2)):
        if not (np.all(np.isfinite(a)) and np.all(a > 0)):
            i = int(np.flatnonzero(~(np.isfinite(a) & (a > 0)))[0])
            raise InputError(f"fit_prony: {name}[{i}] = {a[i]!r}; expected finite positive values")
    if tau is None:
        if not (per_decade > 0 and margin >= 0):
            raise InputError("fit_prony: expected per_decade > 0 and margin >= 0")
        lo = -math.log10(w.max()) - margin
        hi = -math.log10(w.min()) + margin
        n = max(2, int(math.ceil((hi - lo) * per_decade)) + 1)
        tau = np.logspace(lo, hi, n)
    tau = np.asarray(tau, dtype=float).ravel()
    if not (tau.size > 0 and np.all(np.isfinite(tau)) and np.all(tau > 0)):
        raise InputError("fit_prony: tau must be finite positive relaxation times in s")

    E_inf, E_i, tau_k = _nnls(w, E1, E2, tau)
    # prune: drop the smallest terms while the fit moves by less than `prune` (relative) everywhere
    if prune > 0 and E_i.size > 1:
        E_inf, E_i, tau_k = _prune(w, E1, E2, E_inf, E_i, tau_k, prune)
    if E_i.size == 0:            # purely elastic data: keep one (zero) term so the series is well formed
        E_i, tau_k = np.zeros(1), tau[:1]
    prony = Prony(E_inf=float(E_inf), E_i=E_i, tau_i=tau_k, wlf=None, thermal=thermal or Thermal(), label=label)
    return PronyFit(prony=prony, quality=quality_of(prony, w, E1, E2))


def quality_of(material, omega, E_storage, E_loss, *, shift_rms_log10=None, representation: str = "prony"
               ) -> FitQuality:
    """RMS and max relative residuals of ``material.E_reference`` (or ``E``) against data."""
    w = np.asarray(omega, dtype=float)
    fE = material.E_reference(w) if hasattr(material, "E_reference") else material.E(w)
    r1 = fE.real / np.asarray(E_storage) - 1.0
    r2 = fE.imag / np.asarray(E_loss) - 1.0
    rs, rl = float(np.sqrt(np.mean(r1 ** 2))), float(np.sqrt(np.mean(r2 ** 2)))
    n_terms = int(getattr(material, "E_i", np.zeros(0)).size)
    return FitQuality(rms_rel_storage=rs, rms_rel_loss=rl, rms_rel=float(math.sqrt(0.5 * (rs ** 2 + rl ** 2))),
                      max_rel_storage=float(np.max(np.abs(r1))), max_rel_loss=float(np.max(np.abs(r2))),
                      n_points=int(w.size), n_terms=n_terms, shift_rms_log10=shift_rms_log10,
                      representation=representation)


# ==================================================================================================== helpers

def _design(w, tau):
    x = w[:, None] * tau[None, :]
    d = 1.0 / (1.0 + x * x)
    return x * x * d, x * d


def _nnls(w, E1, E2, tau):
    """NNLS on relative residuals; columns scaled to unit norm for conditioning (positive scaling keeps signs)."""
    from scipy import optimize
    R, I = _design(w, tau)
    A = np.vstack([np.column_stack([np.ones_like(w), R]) / E1[:, None],
                   np.column_stack([np.zeros_like(w), I]) / E2[:, None]])
    b = np.ones(2 * w.size)
    scale = np.linalg.norm(A, axis=0)
    scale[scale == 0] = 1.0
    x, _ = optimize.nnls(A / scale, b, maxiter=50 * A.shape[1])
    x = x / scale
    keep = x[1:] > 0
    return x[0], x[1:][keep], tau[keep]


def _prune(w, E1, E2, E_inf, E_i, tau, tol):
    """Remove terms one by one (smallest contribution first) while the fit changes by < tol; refit each time."""
    while E_i.size > 1:
        R, I = _design(w, tau)
        # largest relative change of E' or E'' if term i is removed (without refit)
        contrib = np.maximum((R * E_i / E1[:, None]).max(axis=0), (I * E_i / E2[:, None]).max(axis=0))
        i = int(np.argmin(contrib))
        if contrib[i] >= tol:
            break
        keep = np.ones(E_i.size, dtype=bool)
        keep[i] = False
        E_inf, E_i, tau = _nnls(w, E1, E2, tau[keep])
    return E_inf, E_i, tau
