"""Isotropic 2D power spectral densities in Persson's convention.

Two objects share one small interface used by the friction engine:

* :class:`SelfAffine` -- the analytic self-affine PSD :math:`C(q) = C_0 q^{-2(1+H)}` between the roll-off
  ``q0`` and the short-distance cut-off ``q1``, optionally flat from ``qL`` to ``q0``;
* :class:`PSD` -- a tabulated PSD ``(q, C)``, interpolated linearly in log-log.

Both expose ``C(q)``, ``hrms()``, ``rms_slope()``, ``moment(n)``, ``with_cutoff(...)`` and the support
``q_range = (q_start, q_end)`` over which the physics integrals run. ``C`` is zero outside the support.
Both carry their cut-offs (:class:`Cutoffs`: qL, roll-off q0, reliability limit q_r, q1) and say whether the
tail past q_r is measured or extrapolated. :func:`read_psd` and :meth:`PSD.to_csv` read and write the
PSD table of ``docs/conventions.md`` (columns ``q`` in rad/m and ``C`` in m^4, ``#`` comments).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from frictioncite import doi

from ._util import atomic_write_text
from ._util import finite_float, positive, powerlaw_segments_integral
from .errors import InputError
from .powerlaw import rolloff_line, self_affine_line

__all__ = ["SelfAffine", "PSD", "Cutoffs", "read_psd"]


@dataclass(frozen=True)
class Cutoffs:
    """The cut-offs of a PSD (``docs/conventions.md``, "Power spectral densities"), all in rad/m.

    Attributes
    ----------
    qL : float or None
        2 pi / L, L the longest wavelength measured (or the plateau start of a model).
    q0 : float or None
        Roll-off: the PSD is flat below q0 (None when unknown).
    q_r : float or None
        Reliability limit of the instrument (resolution, tip radius); None for an analytic model.
    q1 : float
        Short-distance cut-off used in the physics: the end of the support.
    extrapolated : bool
        True when the part of the PSD beyond ``q_r`` up to ``q1`` is an extrapolation, not a measurement.
    """

    qL: float | None
    q0: float | None
    q_r: float | None
    q1: float
    extrapolated: bool

    def describe(self) -> str:
        """One line for reports, e.g. ``qL=62.8, q0=1e3, q_r=8.4e4, q1=1e7 rad/m (tail extrapolated past q_r)``."""
        parts = [f"{k}={v:.4g}" for k, v in (("qL", self.qL), ("q0", self.q0), ("q_r", self.q_r), ("q1", self.q1))
                 if v is not None]
        tail = " (tail extrapolated past q_r)" if self.extrapolated else " (tail measured)"
        return ", ".join(parts) + " rad/m" + tail


@doi("10.1088/0953-8984/17/1/R01")
@dataclass(frozen=True, init=False)
class SelfAffine:
    r"""Self-affine isotropic PSD with roll-off.

    .. math::
        C(q) = \begin{cases} C_0 q_0^{-2(1+H)} & q_L \le q < q_0 \\
                             C_0 q^{-2(1+H)} & q_0 \le q \le q_1 \\
                             0 & \text{otherwise} \end{cases}

    (Persson et al., J. Phys.: Condens. Matter 17, R1 (2005), Eq. 10).

    Parameters
    ----------
    hurst : float
        Hurst exponent H, 0 < H < 1.
    q0 : float
        Roll-off wavevector, rad/m.
    q1 : float
        Short-distance cut-off, rad/m (> q0).
    hrms : float, optional
        Root-mean-square height over the whole support, m. Give exactly one of ``hrms``, ``C0`` and
        ``rms_slope``.
    C0 : float, optional
        Prefactor of the power law, m^4 (rad/m)^(2(1+H)).
    qL : float, optional
        Smallest wavevector (2 pi / L). ``None`` (default) means no roll-off plateau: C = 0 below q0.
    rms_slope : float, optional
        Root-mean-square slope over the whole support (dimensionless, :math:`\xi^2 = 2\pi\int q^3 C dq`), the
        amplitude used by contact mechanics (e.g. the contact-mechanics challenge, Müser et al., Tribol. Lett.
        65, 118 (2017), specifies a slope of 1).

    Examples
    --------
    >>> s = SelfAffine(hurst=0.8, q0=1e3, q1=1e7, hrms=20e-6)
    >>> print(f"hrms {s.hrms():.3g} m, rms slope {s.rms_slope():.2f}, C(1e4) = {s.C(1e4):.3g} m^4")
    hrms 2e-05 m, rms slope 0.25, C(1e4) = 2.56e-20 m^4
    """

    hurst: float
    q0: float
    q1: float
    C0: float
    qL: float | None

    def __init__(self, hurst: float, q0: float, q1: float, hrms: float | None = None, C0: float | None = None,
                 qL: float | None = None, rms_slope: float | None = None):
        H = finite_float(hurst, "hurst")
        if not 0.0 < H < 1.0:
            raise InputError(f"hurst: expected 0 < H < 1, got {H}")
        q0 = positive(q0, "q0")
        q1 = positive(q1, "q1")
        if not q1 > q0:
            raise InputError(f"q1: expected q1 > q0 = {q0:g} rad/m, got {q1:g}")
        if qL is not None:
            qL = positive(qL, "qL")
            if qL > q0:
                raise InputError(f"qL: expected qL <= q0 = {q0:g} rad/m, got {qL:g}")
        given = [name for name, v in (("hrms", hrms), ("C0", C0), ("rms_slope", rms_slope)) if v is not None]
        if len(given) != 1:
            conflict = f"; got {' and '.join(given)}" if given else ""
            raise InputError("SelfAffine: give exactly one amplitude: hrms= (m), C0= (m^4 (rad/m)^(2+2H)) or "
                             f"rms_slope= (dimensionless){conflict}")
        if hrms is not None:
            h = positive(hrms, "hrms")
            C0 = h**2 / (2.0 * math.pi * _moment_selfaffine(1.0, H, q0, q1, qL, 1))
        elif rms_slope is not None:
            g = positive(rms_slope, "rms_slope")
            C0 = g**2 / (2.0 * math.pi * _moment_selfaffine(1.0, H, q0, q1, qL, 3))
        else:
            C0 = positive(C0, "C0")
        for name, value in (("hurst", H), ("q0", q0), ("q1", q1), ("C0", float(C0)), ("qL", qL)):
            object.__setattr__(self, name, value)

    @property
    def q_range(self) -> tuple[float, float]:
        """Support (q_start, q_end) of C in rad/m: (qL or q0, q1)."""
        return (self.qL if self.qL is not None else self.q0, self.q1)

    def C(self, q):
        """PSD C(q) in m^4 at wavevector(s) ``q`` (rad/m); zero outside the support."""
        q = np.asarray(q, dtype=float)
        H = self.hurst
        lo = self.q_range[0]
        out = np.where(q < self.q0, self.C0 * self.q0 ** (-2 * (1 + H)), self.C0 * np.abs(q) ** (-2 * (1 + H)))
        return np.where((q >= lo * (1 - 1e-12)) & (q <= self.q1 * (1 + 1e-12)), out, 0.0)

    def breakpoints(self) -> np.ndarray:
        """Wavevectors (rad/m) where C(q) has a kink: the roll-off q0 when a plateau (qL < q0) precedes it."""
        return np.array([self.q0]) if self.qL is not None and self.qL < self.q0 else np.empty(0)

    def moment(self, n: int) -> float:
        r"""Spectral moment :math:`2\pi \int q^n C(q)\, dq` over the support (exact)."""
        return 2.0 * math.pi * _moment_selfaffine(self.C0, self.hurst, self.q0, self.q1, self.qL, n)

    def hrms(self) -> float:
        r"""RMS height, m: :math:`h_{rms}^2 = 2\pi\int q C(q) dq`."""
        return math.sqrt(self.moment(1))

    def rms_slope(self) -> float:
        r"""RMS slope: :math:`\xi^2 = 2\pi\int q^3 C(q) dq`."""
        return math.sqrt(self.moment(3))

    def with_cutoff(self, q0: float | None = None, q1: float | None = None) -> "SelfAffine":
        """Same power law (same C0) with other cut-offs."""
        return SelfAffine(self.hurst, self.q0 if q0 is None else q0, self.q1 if q1 is None else q1,
                          C0=self.C0, qL=self.qL if (q0 is None or self.qL is None or self.qL <= q0) else None)

    @property
    def q_r(self) -> None:
        """Reliability limit: None, an analytic model has no instrument."""
        return None

    @property
    def extrapolated(self) -> bool:
        """False: the analytic power law is the model itself, nothing is extrapolated."""
        return False

    @property
    def source(self) -> str:
        """Short description of the model."""
        return f"SelfAffine(H={self.hurst:g}, q0={self.q0:g}, q1={self.q1:g}, C0={self.C0:.4g}, qL={self.qL})"

    @property
    def cutoffs(self) -> Cutoffs:
        """The cut-offs (qL, roll-off q0, q_r = None, q1)."""
        return Cutoffs(qL=self.qL, q0=self.q0, q_r=None, q1=self.q1, extrapolated=False)

    def extrapolate(self, q1: float, hurst: float | None = None) -> "SelfAffine":
        """The same model up to ``q1`` (an analytic power law extends itself; ``hurst`` must match if given)."""
        if hurst is not None and abs(float(hurst) - self.hurst) > 1e-12:
            raise InputError(f"hurst: a SelfAffine extends with its own H = {self.hurst:g}, got {hurst!r}")
        return self.with_cutoff(q1=q1)

    def to_csv(self, path, n_per_decade: int = 64, *, overwrite: bool = False) -> "Path":
        """Write the tabulated model as a PSD table (see :meth:`PSD.to_csv`)."""
        return self.tabulate(n_per_decade).to_csv(path, overwrite=overwrite)

    def tabulate(self, n_per_decade: int = 64) -> "PSD":
        """Tabulated copy on a log grid over the support (the power-law part exactly interpolated)."""
        lo, hi = self.q_range
        n = max(2, int(math.ceil(n_per_decade * math.log10(hi / lo))) + 1)
        q = np.geomspace(lo, hi, n)
        if self.qL is not None and self.qL < self.q0:
            q = np.union1d(q, [self.q0])
        return PSD(q, self.C(q), source=self.source, qL=self.qL, q_rolloff=self.q0, hurst=self.hurst)


@dataclass(frozen=True, eq=False)
class PSD:
    r"""Tabulated isotropic 2D PSD, interpolated linearly in log-log, zero outside ``[q[0], q[-1]]``.

    Parameters
    ----------
    q : array_like
        Strictly increasing wavevectors, rad/m.
    C : array_like
        PSD values, m^4, strictly positive (Persson convention, 2D isotropic).
    q_r : float, optional
        Reliability limit of the instrument, rad/m; past it the tail is extrapolated.
    extrapolated : bool
        True when part of the table beyond ``q_r`` is an extrapolation, not a measurement.
    source : str
        Where the table comes from (file, measurement, model), for messages and reports.
    qL : float, optional
        2 pi / L of the measurement (longest wavelength measured), rad/m.
    q_rolloff : float, optional
        Roll-off wavevector (PSD flat below), rad/m, when known (e.g. from :func:`surfaces.fit_rolloff`).
        Not to be confused with :attr:`q0`, the first q of the table.
    hurst : float, optional
        Hurst exponent of the tail (the one used to extrapolate, when ``extrapolated``).

    Notes
    -----
    The moments are exact for the log-log interpolant:
    :math:`m_n = 2\pi\int q^n C(q)\,dq`, :math:`h_{rms}^2 = m_1`, rms slope :math:`\xi^2 = m_3`.
    """

    q: np.ndarray
    C_values: np.ndarray
    q_r: float | None = None
    extrapolated: bool = False
    source: str = ""
    qL: float | None = None
    q_rolloff: float | None = None
    hurst: float | None = None

    def __init__(self, q, C, q_r: float | None = None, extrapolated: bool = False, source: str = "", *,
                 qL: float | None = None, q_rolloff: float | None = None, hurst: float | None = None):
        q = np.array(q, dtype=float, copy=True).ravel()
        C = np.array(C, dtype=float, copy=True).ravel()
        where = f" ({source})" if source else ""
        if q.size < 2 or q.size != C.size:
            raise InputError(f"PSD{where}: q and C must have the same length >= 2, got {q.size} and {C.size}")
        bad = ~np.isfinite(q) | ~np.isfinite(C)
        if bad.any():
            raise InputError(f"PSD{where}: non-finite value in q or C at row {int(np.argmax(bad))}")
        if (q <= 0).any():
            raise InputError(f"PSD{where}: column q must be > 0 rad/m (row {int(np.argmax(q <= 0))})")
        if (np.diff(q) <= 0).any():
            row = int(np.argmax(np.diff(q) <= 0)) + 1
            raise InputError(f"PSD{where}: column q must be strictly increasing (row {row})")
        if (C <= 0).any():
            raise InputError(f"PSD{where}: column C must be > 0 m^4 (row {int(np.argmax(C <= 0))})")
        if hurst is not None:
            hurst = finite_float(hurst, "hurst")
            if not 0.0 < hurst < 1.0 + 1e-12:
                raise InputError(f"hurst: expected 0 < H <= 1, got {hurst:g}")
        q.setflags(write=False)
        C.setflags(write=False)
        object.__setattr__(self, "q", q)
        object.__setattr__(self, "C_values", C)
        object.__setattr__(self, "q_r", None if q_r is None else positive(q_r, "q_r"))
        object.__setattr__(self, "extrapolated", bool(extrapolated))
        object.__setattr__(self, "source", str(source))
        object.__setattr__(self, "qL", None if qL is None else positive(qL, "qL"))
        object.__setattr__(self, "q_rolloff", None if q_rolloff is None else positive(q_rolloff, "q_rolloff"))
        object.__setattr__(self, "hurst", hurst)

    def __repr__(self) -> str:
        return (f"PSD({self.q.size} points, q {self.q0:.4g}-{self.q1:.4g} rad/m, hrms={self.hrms():.4g} m, "
                f"rms slope={self.rms_slope():.3g}" + (f", q_r={self.q_r:.4g}" if self.q_r is not None else "")
                + (", extrapolated" if self.extrapolated else "")
                + (f", source={self.source!r}" if self.source else "") + ")")

    @property
    def q0(self) -> float:
        """First wavevector of the table, rad/m."""
        return float(self.q[0])

    @property
    def q1(self) -> float:
        """Last wavevector of the table, rad/m."""
        return float(self.q[-1])

    @property
    def q_range(self) -> tuple[float, float]:
        """Support (q_start, q_end), rad/m."""
        return (self.q0, self.q1)

    @property
    def cutoffs(self) -> Cutoffs:
        """The cut-offs: qL, roll-off (``q_rolloff``), reliability limit q_r, q1 = last q, and ``extrapolated``."""
        return Cutoffs(qL=self.qL, q0=self.q_rolloff, q_r=self.q_r, q1=self.q1, extrapolated=self.extrapolated)

    def C(self, q):
        """PSD at ``q`` (rad/m), log-log interpolation, zero outside the table."""
        q = np.asarray(q, dtype=float)
        lq = np.log(np.clip(q, self.q[0], self.q[-1]))
        out = np.exp(np.interp(lq, np.log(self.q), np.log(self.C_values)))
        inside = (q >= self.q[0] * (1 - 1e-12)) & (q <= self.q[-1] * (1 + 1e-12))
        return np.where(inside, out, 0.0)

    def breakpoints(self) -> np.ndarray:
        """Wavevectors (rad/m) where the log-log interpolant changes slope: the rows of the table."""
        return self.q

    def moment(self, n: int) -> float:
        r"""Spectral moment :math:`2\pi\int q^n C(q) dq`, exact for the log-log interpolant."""
        return 2.0 * math.pi * float(np.sum(powerlaw_segments_integral(self.q, self.C_values, n)))

    def hrms(self) -> float:
        """RMS height, m."""
        return math.sqrt(self.moment(1))

    def rms_slope(self) -> float:
        """RMS slope (dimensionless)."""
        return math.sqrt(self.moment(3))

    def with_cutoff(self, q0: float | None = None, q1: float | None = None) -> "PSD":
        """The table restricted to ``[q0, q1]`` (end points interpolated). Extending past the table is not
        done here; see :meth:`extrapolate` for tail extrapolation."""
        lo = self.q0 if q0 is None else positive(q0, "q0")
        hi = self.q1 if q1 is None else positive(q1, "q1")
        if not hi > lo:
            raise InputError(f"with_cutoff: expected q1 > q0, got q0={lo:g}, q1={hi:g}")
        if lo < self.q0 * (1 - 1e-9) or hi > self.q1 * (1 + 1e-9):
            raise InputError(f"with_cutoff: [{lo:g}, {hi:g}] rad/m lies outside the table [{self.q0:g}, {self.q1:g}]; "
                             "extrapolate the tail explicitly")
        inner = self.q[(self.q > lo) & (self.q < hi)]
        q = np.concatenate([[lo], inner, [hi]])
        # The extrapolated part lies past q_r: cutting below q_r leaves only measured data.
        still_extrapolated = self.extrapolated and (self.q_r is None or hi > self.q_r * (1 + 1e-9))
        return PSD(q, self.C(q), q_r=self.q_r, extrapolated=still_extrapolated, source=self.source,
                   qL=self.qL, q_rolloff=self.q_rolloff, hurst=self.hurst)

    def with_rolloff(self, q_rolloff: float | None) -> "PSD":
        """The same table with the roll-off wavevector ``q_rolloff`` (rad/m, inside the table) declared, or none.

        The roll-off sets the macro-asperity scale of the flash temperature (``persson.effects.FlashTemperature``);
        :func:`surfaces.fit_rolloff` estimates it from a table that shows the plateau.
        """
        if q_rolloff is not None:
            q_rolloff = positive(q_rolloff, "q_rolloff")
            if not self.q0 * (1 - 1e-9) <= q_rolloff <= self.q1 * (1 + 1e-9):
                raise InputError(f"q_rolloff: {q_rolloff:g} rad/m lies outside the PSD's q range [{self.q0:g}, "
                                 f"{self.q1:g}] rad/m; expected the wavevector below which the PSD is flat")
        return PSD(self.q, self.C_values, q_r=self.q_r, extrapolated=self.extrapolated, source=self.source,
                   qL=self.qL, q_rolloff=q_rolloff, hurst=self.hurst)

    @doi("10.1088/0953-8984/17/1/R01")
    def extrapolate(self, q1: float, hurst: float | None = None, fit_band: tuple[float, float] | None = None,
                    n_per_decade: int = 32) -> "PSD":
        r"""Extend the self-affine tail past the reliability limit to ``q1``.

        Beyond :math:`q_s` (``q_r`` when the table reaches past it, else the last q of the table) the
        table is replaced by the power law of a self-affine fractal (Persson et al. 2005, Eq. 10)

        .. math:: C(q) = C(q_s)\,(q/q_s)^{-2(1+H)}, \qquad q_s < q \le q_1 .

        Parameters
        ----------
        q1 : float
            New short-distance cut-off, rad/m. If ``q1`` is not past ``q_s`` this is :meth:`with_cutoff`.
        hurst : float, optional
            Hurst exponent of the tail. Default: fitted (log-log least squares) on ``fit_band``.
        fit_band : (float, float), optional
            Band (rad/m) for the fit of H. Default: the last decade below ``q_s``, above the roll-off where the PSD
            records one (``q_rolloff``: the flat part below it is not the tail's power law). Where that band is not
            self-affine or holds too few points (a scan whose limit lies just past the roll-off), the exponent the
            PSD records (:attr:`hurst`: from the model that made the table, or the file's metadata); where it
            records none, the roll-off law -- flat below :math:`q_0`, the power law above -- fitted on the whole
            table below ``q_s`` (:func:`surfaces.powerlaw.rolloff_line`), whose H is that of the part above the
            roll-off (a roll-off inside the band that the PSD does not record).
        n_per_decade : int
            Points per decade of the new tail.

        Returns
        -------
        PSD
            With ``q_r`` = ``q_s``, ``extrapolated=True`` and ``hurst`` recorded.
        """
        q1 = positive(q1, "q1")
        q_s = self.q1 if self.q_r is None else min(self.q_r, self.q1)
        if q1 <= q_s * (1 + 1e-9):
            return self.with_cutoff(q1=q1)
        if hurst is None:
            hurst = self._tail_hurst(q_s, fit_band)
        H = finite_float(hurst, "hurst")
        if not 0.0 < H <= 1.0:
            raise InputError(f"hurst: expected 0 < H <= 1 for the extrapolated tail, got {H:g}")
        measured = self.with_cutoff(q1=q_s) if q_s < self.q1 else self
        n = max(2, int(math.ceil(n_per_decade * math.log10(q1 / q_s))) + 1)
        q_tail = np.geomspace(q_s, q1, n)[1:]
        C_tail = measured.C_values[-1] * (q_tail / q_s) ** (-2.0 * (1.0 + H))
        return PSD(np.concatenate([measured.q, q_tail]), np.concatenate([measured.C_values, C_tail]), q_r=q_s,
                   extrapolated=True, source=self.source, qL=self.qL, q_rolloff=self.q_rolloff, hurst=H)

    def _tail_hurst(self, q_s: float, fit_band) -> float:
        """H of the tail for :meth:`extrapolate` (see its ``fit_band``)."""
        where = self.source or type(self).__name__
        if fit_band is not None:
            lo, hi = fit_band
            return self_affine_line(self.q, self.C_values, "isotropic", max(lo, self.q0), min(hi, q_s),
                                    where=where).hurst
        lo = q_s / 10.0
        if self.q_rolloff is not None and lo < self.q_rolloff < q_s:
            lo = self.q_rolloff
        try:
            return self_affine_line(self.q, self.C_values, "isotropic", max(lo, self.q0), q_s, where=where).hurst
        except InputError as first:
            # the last decade is not a power law: the exponent recorded with the table (by the model that made it,
            # or in the file's metadata) is better knowledge of the tail than a roll-off law fitted to a table that
            # may hold one or two points of it past the roll-off
            if self.hurst is not None:
                return float(self.hurst)
            try:
                return rolloff_line(self.q, self.C_values, "isotropic", None, q_s, where=where).hurst
            except InputError as second:
                raise InputError(f"extrapolate ({where}): the table gives no exponent for the tail: {first}; and the "
                                 f"roll-off law fitted below q_s = {q_s:.4g} rad/m: {second}; give hurst= (e.g. "
                                 "from a scan that reaches further) or fit_band=") from None

    def to_csv(self, path, *, overwrite: bool = False) -> Path:
        """Write the PSD table of ``docs/conventions.md`` (``q,C`` with ``#`` metadata comments), atomically.

        Never over the file the table was read from (its ``source``); over another existing file only with
        ``overwrite=True``.

        The comments record ``source``, ``q_r``, ``extrapolated``, ``qL``, ``q_rolloff`` and ``hurst``;
        :func:`read_psd` reads them back.

        Returns
        -------
        pathlib.Path
            The path written.
        """
        meta = {"source": self.source.replace("\n", " "), "q_r": self.q_r, "extrapolated": self.extrapolated,
                "qL": self.qL, "q_rolloff": self.q_rolloff, "hurst": self.hurst}
        lines = ["# surfaces PSD table: 2D isotropic, Persson convention; q in rad/m, C in m^4"]
        lines += [f"# {k}: {v}" for k, v in meta.items() if v is not None and v != ""]
        lines.append("q,C")
        lines += [f"{a:.17g},{b:.17g}" for a, b in zip(self.q, self.C_values)]
        _check_overwrite(path, overwrite, self.source)
        return atomic_write_text(path, "\n".join(lines) + "\n")


def read_psd(path) -> PSD:
    """Read a PSD table (``docs/conventions.md``, "Files"): CSV with columns ``q`` (rad/m) and ``C`` (m^4), ``#``
    comments.

    Comments of the form ``# key: value`` written by :meth:`PSD.to_csv` (``q_r``, ``extrapolated``, ``qL``,
    ``q_rolloff``, ``hurst``, ``source``) are read back; other comments and extra columns are ignored.

    Parameters
    ----------
    path : str or path-like
        The CSV file.

    Returns
    -------
    PSD

    Raises
    ------
    InputError
        Missing file, no header, missing column ``q`` or ``C``, a non-numeric or non-positive value,
        q not strictly increasing: the message names the file, column and line.
    """
    if not isinstance(path, (str, Path)):
        raise InputError(f"path: expected the PSD table's file name, got {path!r}")
    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: PSD table not found")
    meta: dict[str, str] = {}
    header: list[str] | None = None
    rows: list[tuple[int, list[str]]] = []
    with open(path, encoding="utf-8-sig", errors="replace") as fh:  # -sig: a byte-order mark is not a column name
        for lineno, line in enumerate(fh, start=1):
            text = line.strip()
            if not text:
                continue
            if text.startswith("#"):
                key, sep, value = text[1:].partition(":")
                if sep:
                    meta[key.strip()] = value.strip()
                continue
            fields = [f.strip() for f in text.split(",")]
            if header is None:
                header = fields
            else:
                if len(fields) > len(header) and any(fields[len(header):]):
                    raise InputError(f"{path}, line {lineno}: {len(fields)} fields, but the header has "
                                     f"{len(header)} columns ({', '.join(header)}); expected one value per column")
                rows.append((lineno, fields))
    if header is None:
        raise InputError(f"{path}: empty PSD table (no header row; expected columns q, C)")
    cols = {}
    for name in ("q", "C"):
        if name not in header:
            raise InputError(f"{path}: missing column {name!r} (found {header}); expected columns q (rad/m), C (m^4)")
        cols[name] = header.index(name)
    if len(rows) < 2:
        raise InputError(f"{path}: expected at least 2 data rows, found {len(rows)}")
    values = {}
    for name, j in cols.items():
        out = np.empty(len(rows))
        for i, (lineno, fields) in enumerate(rows):
            try:
                out[i] = float(fields[j])
            except (IndexError, ValueError):
                got = fields[j] if j < len(fields) else "<missing>"
                raise InputError(f"{path}, line {lineno}, column {name}: expected a number, got {got!r}") from None
            if not (math.isfinite(out[i]) and out[i] > 0):
                unit = "rad/m" if name == "q" else "m^4"
                raise InputError(f"{path}, line {lineno}, column {name}: expected a finite value > 0 {unit}, "
                                 f"got {fields[j]!r}")
        values[name] = out
    bad = np.flatnonzero(np.diff(values["q"]) <= 0)
    if bad.size:
        raise InputError(f"{path}, line {rows[bad[0] + 1][0]}, column q: q must be strictly increasing")

    def num(key):
        if key not in meta or meta[key] in ("", "None"):
            return None
        try:
            return float(meta[key])
        except ValueError:
            raise InputError(f"{path}: comment '# {key}: {meta[key]}' is not a number") from None

    extrapolated = meta.get("extrapolated", "False").strip().lower() in ("true", "1", "yes")
    return PSD(values["q"], values["C"], q_r=num("q_r"), extrapolated=extrapolated,
               source=meta.get("source") or str(path), qL=num("qL"), q_rolloff=num("q_rolloff"),
               hurst=num("hurst"))


def _check_overwrite(path, overwrite: bool, source: str) -> None:
    """The writers' rule (as ``persson.io.check_overwrite``): never over the source file, over another existing
    file only when asked."""
    path = Path(path)
    src = Path(source) if source else None
    if src is not None and src.is_file() and path.exists() and path.resolve() == src.resolve():
        raise InputError(f"{path}: this is the file the PSD was read from; choose another file name (inputs are "
                         "never overwritten)")
    if path.is_dir():
        raise InputError(f"{path}: is a folder; expected a file name")
    if path.exists() and not overwrite:
        raise InputError(f"{path}: the file exists; pass overwrite=True to replace it (or choose another name)")


def _moment_selfaffine(C0: float, H: float, q0: float, q1: float, qL: float | None, n: int) -> float:
    r"""Exact :math:`\int q^n C(q) dq` of the self-affine PSD with plateau."""
    a = n + 1 - 2 * (1 + H)
    tail = C0 * ((q1**a - q0**a) / a if abs(a) > 1e-12 else math.log(q1 / q0))
    plateau = 0.0
    if qL is not None and qL < q0:
        plateau = C0 * q0 ** (-2 * (1 + H)) * (q0 ** (n + 1) - qL ** (n + 1)) / (n + 1)
    return tail + plateau
