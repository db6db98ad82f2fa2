r"""The local friction :math:`\mu_{loc}(v, p)` of the scales the road profile cannot see.

The march resolves the road down to its element size :math:`\Delta x`; the friction of the finer texture
(wavevectors :math:`q > \pi/\Delta x`, the microtexture) enters through :math:`\mu_{loc}` in Eq. 2. It is the
Persson engine's sliding friction (hysteresis, plus adhesion when dry) on the PSD band
:math:`[\pi/\Delta x, q_1]` at the element's sliding speed v, its nominal pressure p and the temperature
(Persson, J. Chem. Phys. 115, 3840 (2001); Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)): the
multiscale picture of Fig. 3, where every scale below the resolution adds its own hysteresis.

The band comes from a measured microtexture PSD when one is given, else from the road's own profiles, whose
self-affine tail is extrapolated past their Nyquist limit to :math:`q_1` (the result says so: the finer texture
is then an assumption, the paper's Fig. 9 point). The friction is tabulated once per surface, material,
temperature and wetness over a grid of sliding speeds (log-spaced) and pressures (log-spaced) and interpolated
(linear in ln v and ln p), so a slip map calls the engine once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from frictioncite import citations_of, doi

from .._checks import finite_array, number, positive
from ..errors import InputError

__all__ = ["LocalFriction", "local_friction", "constant_friction", "DEFAULT_Q1", "PRESSURES"]

#: Default short-distance cut-off of the extrapolated microtexture, rad/m (6 um wavelength).
DEFAULT_Q1 = 1.0e6
#: Pressures of the table, Pa: element pressures from a light touch to the tops of the macrotexture.
PRESSURES = np.geomspace(1.0e4, 3.0e7, 10)
_PER_DECADE = 4


@dataclass(frozen=True, eq=False)
class LocalFriction:
    r""":math:`\mu_{loc}` tabulated over sliding speed and pressure (or a constant).

    Attributes
    ----------
    speeds : ndarray, shape (n_v,)
        Sliding speeds, m/s (log-spaced).
    pressures : ndarray, shape (n_p,)
        Nominal pressures, Pa (log-spaced; one value for a constant).
    mu : ndarray, shape (n_v, n_p)
        Local friction coefficient.
    temperature : float
        Background temperature, deg C.
    wet : bool
        True when adhesion is left out (a wet road).
    q_band : tuple of float
        The PSD band (rad/m) the engine integrated; empty for a constant.
    extrapolated : bool
        True when the band reaches past the measured PSD.
    notes : tuple of str
    citations : tuple of str
    """

    speeds: np.ndarray
    pressures: np.ndarray
    mu: np.ndarray
    temperature: float = float("nan")
    wet: bool = False
    q_band: tuple = ()
    extrapolated: bool = False
    notes: tuple = ()
    citations: tuple = ()

    @property
    def constant(self) -> bool:
        """True for a constant mu_loc."""
        return self.mu.size == 1

    def row(self, speed: float) -> np.ndarray:
        """mu over ``pressures`` at the sliding speed ``speed`` (m/s), linear in ln v, clamped at the ends."""
        if self.constant:
            return self.mu[0].copy()
        lv = np.log(self.speeds)
        x = math.log(positive(speed, "sliding speed"))
        if x <= lv[0]:
            return self.mu[0].copy()
        if x >= lv[-1]:
            return self.mu[-1].copy()
        i = int(np.searchsorted(lv, x)) - 1
        f = (x - lv[i]) / (lv[i + 1] - lv[i])
        return (1.0 - f) * self.mu[i] + f * self.mu[i + 1]

    def __call__(self, speed, pressure) -> np.ndarray:
        """mu_loc at sliding speed(s) (m/s) and pressure(s) (Pa), broadcast together."""
        v, p = np.broadcast_arrays(np.asarray(speed, dtype=float), np.asarray(pressure, dtype=float))
        out = np.empty(v.shape)
        for idx in np.ndindex(v.shape):
            row = self.row(float(v[idx]))
            if row.size == 1:
                out[idx] = row[0]
            else:
                out[idx] = np.interp(math.log(p[idx]), np.log(self.pressures), row)
        return out

    def covers(self, speeds) -> bool:
        """True when the table's speeds span ``speeds`` (m/s)."""
        if self.constant:
            return True
        s = np.asarray(speeds, dtype=float)
        return bool(s.min() >= self.speeds[0] * (1 - 1e-9) and s.max() <= self.speeds[-1] * (1 + 1e-9))


def constant_friction(mu: float) -> LocalFriction:
    """A constant local friction coefficient (used as is at every speed and pressure)."""
    m = number(mu, "mu_loc")
    if m < 0:
        raise InputError(f"mu_loc: expected a friction coefficient >= 0, got {m:g}")
    if m > 3:
        raise InputError(f"mu_loc: {m:g} is not a friction coefficient of rubber on a road (expected 0-3)")
    return LocalFriction(np.array([1.0]), np.array([1.0]), np.array([[m]]), notes=(f"constant mu_loc = {m:g}",))


@doi("10.1063/1.1388626", "10.1088/0953-8984/17/1/R01")
def local_friction(road, material, *, temperature: float = 20.0, speeds, wet: bool = False, microtexture=None,
                   q1: float | None = None, adhesion=True, effects=(), pressures=None, nu: float = 0.5,
                   gamma: float = 0.5) -> LocalFriction:
    r"""Tabulate :math:`\mu_{loc}(v, p)` from the Persson engine on the band above the road's resolution.

    Parameters
    ----------
    road : persson.tread.Road
        The road elements; its element size :math:`\Delta x` sets the band's start :math:`q_0 = \pi/\Delta x` and
        its profiles give the PSD when ``microtexture`` is None.
    material : object
        The tread compound, with ``E(omega, T)`` (:mod:`materials`).
    temperature : float
        Background temperature, deg C.
    speeds : array_like
        Sliding speeds the table must span, m/s (> 0); the table runs from their minimum to their maximum,
        four points per decade.
    wet : bool
        Leave adhesion out (a wet road).
    microtexture : surfaces.PSD or surfaces.SelfAffine, optional
        Measured (or modelled) isotropic PSD of the fine texture; it must reach past :math:`\pi/\Delta x`.
    q1 : float, optional
        Short-distance cut-off, rad/m. Default: the end of ``microtexture``; for the road's own PSD, its tail
        extrapolated to :data:`DEFAULT_Q1`.
    adhesion : bool or persson.effects.Adhesion
        Dry adhesion term (True: :class:`persson.effects.Adhesion` with its defaults; False: none).
    effects : sequence of persson.effects.Effect
        Further effects of the engine (e.g. ``FlashTemperature()``).
    pressures : array_like, optional
        Pressures of the table, Pa (default :data:`PRESSURES`).
    nu, gamma : float
        Poisson ratio and the gamma of S(q), passed to :class:`persson.Model`.

    Returns
    -------
    LocalFriction

    Raises
    ------
    InputError
        A microtexture PSD that ends before :math:`\pi/\Delta x`, non-positive speeds or pressures, a cut-off
        below the band's start.
    """
    from ..engine.model import Model
    from ..effects import Adhesion

    T = number(temperature, "temperature")
    v = finite_array(speeds, "speeds").ravel()
    if np.any(v <= 0):
        raise InputError("speeds: expected sliding speeds > 0 m/s")
    p = PRESSURES if pressures is None else finite_array(pressures, "pressures").ravel()
    if np.any(p <= 0):
        raise InputError("pressures: expected pressures > 0 Pa")
    q0 = math.pi / road.dx
    notes = []
    if microtexture is not None:
        band, extrapolated = _band(microtexture, q0, q1, "microtexture")
    else:
        iso = road.psd()
        end = DEFAULT_Q1 if q1 is None else positive(q1, "q1")
        if end <= q0:
            raise InputError(f"q1: {end:g} rad/m does not reach past the road's resolution pi/dx = {q0:.4g} rad/m")
        ext = iso.extrapolate(end) if end > iso.q_range[1] else iso.with_cutoff(q1=end)
        band, extrapolated = _band(ext, q0, None, "road PSD")
        if extrapolated:
            notes.append(f"mu_loc: the texture finer than the profiles ({q0:.3g}-{end:.3g} rad/m) is the road's "
                         f"self-affine tail extrapolated (H = {getattr(ext, 'hurst', float('nan')):.2f}); give "
                         "a measured microtexture to replace the assumption")
    effs = list(effects)
    if adhesion and not wet:
        effs.append(Adhesion() if adhesion is True else adhesion)
    model = Model(band, material, nu=nu, gamma=gamma, effects=effs)
    lo, hi = float(v.min()), float(v.max())
    n = max(2, int(math.ceil(_PER_DECADE * math.log10(hi / lo))) + 1) if hi > lo * (1 + 1e-9) else 1
    grid_v = np.geomspace(lo, hi, n) if n > 1 else np.array([lo])
    V, P = np.meshgrid(grid_v, p, indexing="ij")
    r = model.friction(V.ravel(), temperature=T, pressure=P.ravel())
    for text in getattr(r, "notes", ()):
        if text not in notes:
            notes.append(text)
    mu = np.asarray(r.mu, dtype=float).reshape(V.shape)
    if not np.all(np.isfinite(mu)) or np.any(mu < 0):
        raise InputError("mu_loc: the engine returned non-finite or negative friction on the sub-resolution band")
    if grid_v.size == 1:  # one speed: duplicate so that row() interpolates trivially
        grid_v = np.array([lo, lo * (1 + 1e-12)])
        mu = np.vstack([mu, mu])
    return LocalFriction(grid_v, np.asarray(p, dtype=float), mu, temperature=T, wet=bool(wet),
                         q_band=(float(band.q_range[0]), float(band.q_range[1])), extrapolated=extrapolated,
                         notes=tuple(notes), citations=citations_of(local_friction, r))


def _band(psd, q0: float, q1, what: str):
    lo, hi = (float(x) for x in psd.q_range)
    end = hi if q1 is None else positive(q1, "q1")
    if end > hi * (1 + 1e-9):
        raise InputError(f"q1: {end:g} rad/m lies past the end of the {what} ({hi:g} rad/m); nothing is "
                         "extrapolated unless asked (PSD.extrapolate)")
    if end <= q0 * (1 + 1e-9):
        raise InputError(f"{what}: ends at {end:.4g} rad/m, before the road's resolution pi/dx = {q0:.4g} rad/m; "
                         "mu_loc needs the scales above it")
    if lo > q0 * (1 + 1e-6):
        raise InputError(f"{what}: starts at {lo:.4g} rad/m, after the road's resolution pi/dx = {q0:.4g} rad/m; "
                         "the band in between would be missing")
    band = psd.with_cutoff(q0=q0, q1=min(end, hi))
    return band, bool(getattr(band, "extrapolated", False))
