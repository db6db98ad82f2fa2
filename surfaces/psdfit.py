r"""Self-affine and roll-off fits of a PSD table, and their results.

The arrays-level fits of :mod:`surfaces.powerlaw` made into results that know their model: a self-affine
power law :math:`C(q) = C_0 q^{-2(1+H)}` on a band (:class:`SelfAffineFit`), and a roll-off, flat below
:math:`q_0` and self-affine above (:class:`RolloffFit`) (Persson et al. 2005; Jacobs, Junge & Pastewka 2017).
A line-scan PSD is fitted with its own slope :math:`-(1+2H)` and its prefactor converted to the isotropic
:math:`C_0` with the Gamma factor of a power law. :func:`surfaces.fit_self_affine` and
:func:`surfaces.fit_rolloff` (:mod:`surfaces.cutoffs`) take PSD objects; the functions here take the table.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from .errors import InputError
from .powerlaw import gamma_factor, rolloff_line, self_affine_line
from .psd import PSD, SelfAffine

__all__ = ["SelfAffineFit", "RolloffFit", "fit_table_self_affine", "fit_table_rolloff", "with_estimated_rolloff"]

_PERSSON_2005 = "10.1088/0953-8984/17/1/R01"
_JACOBS_2017 = "10.1088/2051-672X/aa51f8"


@dataclass(frozen=True)
class SelfAffineFit:
    r"""Result of :func:`surfaces.fit_self_affine`: :math:`C(q) = C_0 q^{-2(1+H)}` on ``[q_min, q_max]``.

    Attributes
    ----------
    hurst : float
        Hurst exponent H.
    hurst_stderr : float
        Standard error of H from the regression.
    C0 : float
        Prefactor of the isotropic 2D PSD, m^4 (rad/m)^(2+2H). For a 1D fit it is converted with the Gamma
        factor of a power law, :math:`C_0 = \Gamma(1+H)/(\sqrt\pi\Gamma(H+1/2))\,A` with :math:`C_{1D} = A q^{-(1+2H)}`.
    q_min, q_max : float
        Band of the fit, rad/m.
    n_points : int
        Number of table points in the band.
    rms_log_residual : float
        Rms of the natural-log residuals (0 for a perfect power law).
    kind : str
        ``"isotropic"`` (fitted on a 2D PSD) or ``"1d"`` (fitted on a line-scan PSD).
    """

    hurst: float
    hurst_stderr: float
    C0: float
    q_min: float
    q_max: float
    n_points: int
    rms_log_residual: float
    kind: str

    def C(self, q):
        """The fitted isotropic power law at ``q`` (rad/m), m^4."""
        return self.C0 * np.asarray(q, dtype=float) ** (-2.0 * (1.0 + self.hurst))

    def model(self, q0: float | None = None, q1: float | None = None, qL: float | None = None) -> SelfAffine:
        """The fit as a :class:`surfaces.SelfAffine` (default cut-offs: the fitted band)."""
        return SelfAffine(min(self.hurst, 0.999999), self.q_min if q0 is None else q0,
                          self.q_max if q1 is None else q1, C0=self.C0, qL=qL)


@dataclass(frozen=True)
class RolloffFit:
    r"""Result of :func:`surfaces.fit_rolloff`: flat below the roll-off, self-affine above.

    .. math:: C(q) = C_p \;(q < q_0), \qquad C(q) = C_p (q/q_0)^{-2(1+H)} \;(q \ge q_0)

    Attributes
    ----------
    q0 : float
        Roll-off wavevector, rad/m.
    C_plateau : float
        Plateau value :math:`C_p`, m^4 (m^3 for a 1D fit).
    hurst : float
        Hurst exponent of the power-law part.
    C0 : float
        Prefactor :math:`C_p q_0^{2(1+H)}` of the isotropic power law, m^4 (rad/m)^(2+2H).
    rms_log_residual : float
        Rms of the natural-log residuals.
    kind : str
        ``"isotropic"`` or ``"1d"``.
    """

    q0: float
    C_plateau: float
    hurst: float
    C0: float
    rms_log_residual: float
    kind: str

    def model(self, q1: float, qL: float | None = None) -> SelfAffine:
        """The fit as a :class:`surfaces.SelfAffine` with roll-off ``q0`` and cut-off ``q1``."""
        return SelfAffine(min(self.hurst, 0.999999), self.q0, q1, C0=self.C0, qL=qL)


@doi(_PERSSON_2005, _JACOBS_2017)
def fit_table_self_affine(q, C, kind: str, q_min: float | None = None, q_max: float | None = None,
                          where: str = "PSD") -> SelfAffineFit:
    r"""Self-affine fit of a PSD table ``(q, C)`` on ``[q_min, q_max]`` (see :func:`surfaces.fit_self_affine`).

    Parameters
    ----------
    q, C : ndarray
        The table: rad/m, and m^4 (``kind="isotropic"``) or m^3 (``kind="1d"``, a line-scan PSD).
    kind : {"isotropic", "1d"}
    q_min, q_max : float, optional
        Band, rad/m (default the whole table).
    where : str
        Name of the PSD, for messages.
    """
    line = self_affine_line(q, C, kind, q_min, q_max, where)
    C0 = gamma_factor(min(line.hurst, 1.0)) * line.prefactor if kind == "1d" else line.prefactor
    return SelfAffineFit(hurst=line.hurst, hurst_stderr=line.hurst_stderr, C0=float(C0), q_min=line.q_min,
                         q_max=line.q_max, n_points=line.n_points, rms_log_residual=line.rms_log_residual, kind=kind)


@doi(_PERSSON_2005)
def fit_table_rolloff(q, C, kind: str, q_min: float | None = None, q_max: float | None = None,
                      where: str = "PSD") -> RolloffFit:
    """Roll-off fit of a PSD table (see :func:`surfaces.fit_rolloff`); parameters as :func:`fit_table_self_affine`."""
    line = rolloff_line(q, C, kind, q_min, q_max, where)
    q0, Cp, s = line.q0, line.C_plateau, line.slope
    C0 = Cp * q0 ** s if kind != "1d" else gamma_factor(min(line.hurst, 1.0)) * Cp * q0 ** s
    return RolloffFit(q0=q0, C_plateau=Cp, hurst=line.hurst, C0=float(C0), rms_log_residual=line.rms_log_residual,
                      kind=kind)


def with_estimated_rolloff(psd: PSD) -> PSD:
    """``psd`` with ``q_rolloff`` set from the roll-off fit when it finds a plateau inside the table (the break
    lies past the first two points); unchanged otherwise. Used to label measured PSDs."""
    if psd.q_rolloff is not None or psd.q.size < 8:
        return psd
    try:
        fit = fit_table_rolloff(psd.q, psd.C_values, "isotropic", where=psd.source or "PSD")
    except InputError:
        return psd
    if not psd.q[1] < fit.q0 < psd.q[-1] / 2:
        return psd
    return PSD(psd.q, psd.C_values, q_r=psd.q_r, extrapolated=psd.extrapolated, source=psd.source, qL=psd.qL,
               q_rolloff=fit.q0, hurst=psd.hurst)
