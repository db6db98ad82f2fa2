r"""Length-scale bands: which wavelengths of the surface carry the friction.

Two modes.

``"restrict"`` (mode a)
    The integrand of the full surface, restricted to the band:

    .. math:: \mu_{[q_a, q_b]} = \int_{\ln q_a}^{\ln q_b} \frac{d\mu}{d\ln q}\, d\ln q ,

    with :math:`d\mu/d\ln q = \tfrac12 q^4 C(q) S(q) P(q) \int_0^{2\pi} d\phi \cos\phi\,
    \mathrm{Im}E(qv\cos\phi, T_q)/((1-\nu^2)\sigma_0)` the engine's per-scale integrand
    (:attr:`FrictionResult.dmu_dlnq`), where :math:`P(q)` and :math:`T_q` are those of the *whole* surface
    (the band feels the contact already reduced by the longer wavelengths). The band integral is the difference
    of the engine's cumulative friction (:attr:`FrictionResult.mu_cumulative`, the same exact contact-weight
    quadrature as the total) between the band edges, which :func:`persson.sweeps.bands` makes wavevector nodes
    (``GridSettings(extra_q=...)``). Bands that tile :math:`[q_0, q_1]` therefore add up to the engine's
    hysteresis friction to rounding error.

``"separate"`` (mode b)
    Each band as a surface of its own: the PSD restricted to :math:`[q_a, q_b]` (zero outside,
    :class:`BandSurface`), solved from scratch. Without the longer wavelengths the band sees a larger contact
    area :math:`P`, so the separate contributions add up to *more* than the full-surface result.

Band kinds (:func:`band_edges`): ``"decades"`` (equal widths in log q, i.e. logarithmic length-scale bands; the
default number is the number of decades spanned, rounded, so an integer span gives one band per decade),
``"linear_q"`` (equal widths in q), ``"linear_length"`` (equal widths in the wavelength
:math:`\lambda = 2\pi/q`), explicit edges, and ``"continuous"`` (one cell per wavevector node, with the
continuous :math:`d\mu/d\log_{10} q`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import doi

from ..effects.base import Effect
from ..errors import InputError

__all__ = ["BAND_KINDS", "band_edges", "check_bands", "band_contributions", "continuous_cells", "BandSurface"]

#: Named band kinds accepted by :func:`band_edges` (plus ``"continuous"``, see :func:`continuous_cells`).
BAND_KINDS = ("decades", "linear_q", "linear_length", "continuous")

_TOL = 1e-9


def band_edges(kind, q_range, n: int | None = None) -> np.ndarray:
    """Band edges ``[[q_low, q_high], ...]`` (rad/m) of a band kind over ``q_range``.

    Parameters
    ----------
    kind : str or array_like
        ``"decades"`` (alias ``"log"``): ``n`` bands of equal width in log q (= equal width in log wavelength);
        default ``n`` = the number of decades of ``q_range``, rounded (at least 1).
        ``"linear_q"``: ``n`` bands of equal width in q (default 6).
        ``"linear_length"``: ``n`` bands of equal width in wavelength 2 pi / q (default 6).
        A sequence of increasing edges ``[q_0, q_1, ..., q_n]`` (tiling bands), or of pairs
        ``[[q_a, q_b], ...]`` (any bands, may overlap or leave gaps).
    q_range : (float, float)
        Support (q0, q1) of the surface, rad/m; every band must lie inside.
    n : int, optional
        Number of bands for the named kinds.

    Returns
    -------
    ndarray, shape (n_bands, 2)

    Raises
    ------
    InputError
        Unknown kind, bad ``n``, an empty band (q_low >= q_high) or a band outside ``q_range``.
    """
    q0, q1 = (float(x) for x in q_range)
    if isinstance(kind, str):
        name = kind.strip().lower()
        if name == "continuous":
            raise InputError("bands: kind 'continuous' has one cell per wavevector node of the solver; "
                             "use persson.sweeps.continuous_cells(result.q)")
        if name in ("decades", "log"):
            n_def = max(1, int(round(math.log10(q1 / q0))))
            k = _count(n, n_def)
            e = np.geomspace(q0, q1, k + 1)
        elif name == "linear_q":
            e = np.linspace(q0, q1, _count(n, 6) + 1)
        elif name == "linear_length":
            k = _count(n, 6)
            lam = np.linspace(2 * math.pi / q1, 2 * math.pi / q0, k + 1)
            e = np.sort(2 * math.pi / lam)
        else:
            raise InputError(f"bands: unknown band kind {kind!r}; expected one of {list(BAND_KINDS)} "
                             "or a list of edges")
        e[0], e[-1] = q0, q1
        pairs = np.column_stack([e[:-1], e[1:]])
    else:
        if n is not None:
            raise InputError("n: the number of bands is set by the explicit edges; leave n unset")
        try:
            a = np.asarray(kind, dtype=float)
        except (TypeError, ValueError):
            raise InputError(f"bands: expected a band kind or numeric edges, got {kind!r}") from None
        if a.ndim == 1:
            if a.size < 2:
                raise InputError(f"bands: expected at least 2 edges (one band), got {a.size}")
            pairs = np.column_stack([a[:-1], a[1:]])
        elif a.ndim == 2 and a.shape[1] == 2 and a.shape[0] >= 1:
            pairs = a.copy()
        else:
            raise InputError(f"bands: expected edges [q0, q1, ...] or pairs [[qa, qb], ...], got shape {a.shape}")
    return check_bands(pairs, (q0, q1))


def check_bands(pairs, q_range) -> np.ndarray:
    """Validate bands ``[[q_low, q_high], ...]`` against ``q_range`` (edges within 1e-9 relative are snapped).

    Raises
    ------
    InputError
        ``bands: band i ...`` for a non-finite edge, an empty band or a band outside ``q_range``.
    """
    q0, q1 = (float(x) for x in q_range)
    out = np.array(pairs, dtype=float, copy=True).reshape(-1, 2)
    if out.shape[0] == 0:
        raise InputError("bands: expected at least one band")
    for i, (a, b) in enumerate(out):
        if not (math.isfinite(a) and math.isfinite(b)):
            raise InputError(f"bands: band {i} has a non-finite edge ({a!r}, {b!r})")
        if not b > a:
            raise InputError(f"bands: band {i} is empty: q_low = {a:g} >= q_high = {b:g} rad/m")
        if a < q0 * (1 - _TOL) or b > q1 * (1 + _TOL):
            raise InputError(f"bands: band {i} [{a:g}, {b:g}] rad/m lies outside the surface's range "
                             f"[q0, q1] = [{q0:g}, {q1:g}] rad/m")
        out[i] = (max(a, q0), min(b, q1))
    return out


def continuous_cells(q) -> np.ndarray:
    """Cells ``[[q_low, q_high], ...]`` around each wavevector node (edges at geometric midpoints).

    The first and last cells are halves ending at ``q[0]`` and ``q[-1]``, so the cells tile the range.
    """
    q = np.asarray(q, dtype=float)
    mid = np.sqrt(q[:-1] * q[1:])
    lo = np.concatenate([[q[0]], mid])
    hi = np.concatenate([mid, [q[-1]]])
    return np.column_stack([lo, hi])


@doi("10.1063/1.1388626")
def band_contributions(result, bands) -> np.ndarray:
    """Hysteresis friction carried by each band of the full surface (mode "restrict"), per speed.

    Parameters
    ----------
    result : FrictionResult
        A result of :meth:`persson.Model.friction` (its ``q`` and ``mu_cumulative``).
    bands : array_like, shape (n_bands, 2)
        Band edges in rad/m inside ``[result.q[0], result.q[-1]]`` (see :func:`band_edges`).

    Returns
    -------
    ndarray, shape (n_speed, n_bands)
        The engine's integral of d mu over each band: the difference of ``mu_cumulative`` between the band
        edges. Edges on wavevector nodes give the engine's own interval sums (exact: pass the edges as
        ``GridSettings(extra_q=...)``, as :func:`persson.sweeps.bands` does); between nodes the cumulative
        friction is interpolated by a monotone cubic (PCHIP) in ln q. Bands tiling the range add up to
        ``result.mu_hysteresis`` to rounding error either way.
    """
    q = np.asarray(result.q, dtype=float)
    pairs = check_bands(bands, (q[0], q[-1]))
    F = np.atleast_2d(np.asarray(result.mu_cumulative, dtype=float))
    x = np.log(q)
    lo = _cumulative_at(x, F, np.log(pairs[:, 0]))
    hi = _cumulative_at(x, F, np.log(pairs[:, 1]))
    return hi - lo


def load_share(result) -> np.ndarray:
    """Share of the load the asperities carry, per speed (below 1 with the hydrodynamic lift of ``Wet``)."""
    n = np.atleast_1d(np.asarray(result.mu_hysteresis, dtype=float)).size
    return np.broadcast_to(np.atleast_1d(np.asarray(result.load_share, dtype=float)), (n,)).copy()


def interp_ln_q(result_q, values, q) -> np.ndarray:
    """Per-speed values (n_speed, n_q) interpolated linearly in ln q at ``q`` -> (n_speed, len(q))."""
    x = np.log(np.asarray(result_q, dtype=float))
    v = np.atleast_2d(values)
    xq = np.log(np.asarray(q, dtype=float))
    return np.stack([np.interp(xq, x, row) for row in v])


@dataclass(frozen=True, eq=False)
class BandSurface:
    """A surface's PSD restricted to the band ``[q_low, q_high]`` (zero outside): the band as a surface of its own.

    Works for any PSD object with ``C(q)`` and ``q_range``. (``SelfAffine.with_cutoff`` is not a restriction when
    the model has a plateau below the roll-off: moving ``q0`` there moves the roll-off and changes C.)

    Parameters
    ----------
    surface : PSD-like
        The full surface (``C(q)``, ``q_range``).
    q_low, q_high : float
        Band edges, rad/m, inside ``surface.q_range``.
    """

    surface: object
    q_low: float
    q_high: float

    def __post_init__(self):
        lo, hi = check_bands([[self.q_low, self.q_high]], self.surface.q_range)[0]
        object.__setattr__(self, "q_low", float(lo))
        object.__setattr__(self, "q_high", float(hi))

    @property
    def q_range(self) -> tuple[float, float]:
        """(q_low, q_high), rad/m."""
        return (self.q_low, self.q_high)

    @property
    def q0(self) -> float:
        """Start of the band, rad/m."""
        return self.q_low

    @property
    def q1(self) -> float:
        """End of the band, rad/m."""
        return self.q_high

    def breakpoints(self) -> np.ndarray:
        """The full surface's breakpoints inside the band, and the band edges (rad/m)."""
        f = getattr(self.surface, "breakpoints", None)
        b = np.asarray(f() if callable(f) else (), dtype=float)
        return np.concatenate([b[(b > self.q_low) & (b < self.q_high)], [self.q_low, self.q_high]])

    def C(self, q):
        """The full surface's C(q) inside the band, 0 outside (m^4)."""
        q = np.asarray(q, dtype=float)
        inside = (q >= self.q_low * (1 - 1e-12)) & (q <= self.q_high * (1 + 1e-12))
        return np.where(inside, np.asarray(self.surface.C(q), dtype=float), 0.0)

    @property
    def q_r(self):
        """Reliability limit of the full surface (None when it has none)."""
        return getattr(self.surface, "q_r", None)

    @property
    def extrapolated(self) -> bool:
        """Whether the band reaches into an extrapolated tail of the full surface."""
        q_r = self.q_r
        return bool(getattr(self.surface, "extrapolated", False)) and (q_r is None or self.q_high > q_r * (1 + 1e-9))

    def moment(self, n: int, points_per_decade: int = 200) -> float:
        r""":math:`2\pi\int_{q_a}^{q_b} q^n C(q) dq` by the trapezoid rule in ln q (``points_per_decade``)."""
        k = max(3, int(math.ceil(points_per_decade * math.log10(self.q_high / self.q_low))) + 1)
        q = np.geomspace(self.q_low, self.q_high, k)
        f = q ** (n + 1) * self.C(q)
        return 2 * math.pi * float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(np.log(q))))

    def hrms(self) -> float:
        """Rms height of the band, m."""
        return math.sqrt(self.moment(1))

    def rms_slope(self) -> float:
        """Rms slope of the band."""
        return math.sqrt(self.moment(3))

    @property
    def source(self) -> str:
        """Description."""
        base = getattr(self.surface, "source", "") or type(self.surface).__name__
        return f"{base} restricted to [{self.q_low:.4g}, {self.q_high:.4g}] rad/m"


@dataclass(frozen=True)
class _BandRestriction(Effect):
    """Internal: restrict the (effect-transformed) surface to one band; appended last to a model's effects.

    Appending it as the last effect restricts the surface the engine actually integrates (e.g. after the
    microtexture effect extended the tail), not the surface as read.
    """

    q_low: float = 0.0
    q_high: float = 0.0

    def transform_surface(self, surface, conditions):
        return BandSurface(surface, self.q_low, self.q_high)


# Set after the class is created: a ``name`` in the class body would register this internal helper in
# persson.effects.available(), where diagnosis would offer it as a physical effect.
_BandRestriction.name = "length_scale_band"
# the band's cut of the PSD is the point of a band sweep, not a doubtful result: no "PSD cut" PhysicsWarning
_BandRestriction.cuts_psd_on_purpose = True


# ---------------------------------------------------------------------------------------------------------
def _count(n, default: int) -> int:
    if n is None:
        return default
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError(f"n: expected a number of bands >= 1, got {n!r}")
    return int(n)


def _cumulative_at(x: np.ndarray, F: np.ndarray, xq: np.ndarray) -> np.ndarray:
    """The cumulative friction F (n_speed, n_q) at ln q = xq: exact on nodes, PCHIP in between."""
    from scipy.interpolate import PchipInterpolator

    xq = np.clip(xq, x[0], x[-1])
    out = np.empty((F.shape[0], xq.size))
    j = np.searchsorted(x, xq)
    on_node = np.zeros(xq.size, dtype=bool)
    for k in range(xq.size):
        for c in (j[k] - 1, j[k]):
            if 0 <= c < x.size and abs(x[c] - xq[k]) <= 1e-9:
                out[:, k] = F[:, c]
                on_node[k] = True
                break
    if not on_node.all():
        out[:, ~on_node] = PchipInterpolator(x, F, axis=1)(xq[~on_node])
    return out
