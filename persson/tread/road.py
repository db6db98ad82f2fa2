r"""The road under the tread: measured or synthetic profiles turned into road elements and slope angles.

A road is one or more parallel line profiles (the tool of Kane et al. uses 12 profiles of 1.2 m at 0.1 mm, spread
across the wheel path). Each profile is prepared (dropouts filled, detrended), resampled to the road element size
``dx`` by averaging the samples of each element (a low-pass filter: the element cannot see finer detail), and
cut to the length common to all profiles. The local slope angle of road element j (Eq. 2) is the central
difference

.. math:: \tan\alpha_j = \frac{z_{j+1} - z_{j-1}}{2\Delta x}

(one-sided at the ends), interpolated linearly between the elements like the heights. Central differences make the
march second-order accurate: the elastic part of a Kelvin element's force, :math:`K u`, does no net work against
the slopes (its friction vanishes on any periodic road, as it must), and the viscous part converges to
:math:`C v \langle h'^2\rangle` at second order in the element size.
The scales finer than the road elements (wavevectors above :math:`\pi/\Delta x`) are invisible to the march;
their friction enters through :math:`\mu_{loc}` (:mod:`persson.tread.local`).

A tread element with a flat contact face of length :math:`\ell` cannot follow the road on scales shorter than its
face: it rests on the highest point under it. :func:`contact_surface` gives the road as such an element sees it,
the upper envelope (a grey dilation with a flat segment of length :math:`\ell`) and its chord slope across the
face, :math:`\tan\alpha = [z_e(x + \ell/2) - z_e(x - \ell/2)]/\ell`; without a face the element touches the road at
its tip (the heights and central differences above).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from .._checks import finite_array, positive
from ..errors import InputError

__all__ = ["Road", "as_road", "contact_surface"]

#: The element tool's paper, "Tire/pavement friction: presentation of a comprehensive physical tool through
#: advanced contact modelling" (equation numbers of this package are its own; authors and venue not identified).
TOOL_PAPER = "kane:tire-pavement-tool"


@doi(TOOL_PAPER)
@dataclass(frozen=True, eq=False)
class Road:
    r"""Road elements of one or more parallel profiles on a common uniform grid.

    Parameters
    ----------
    z : ndarray, shape (n_rows, n)
        Heights of the road elements, m (mean removed per row).
    dx : float
        Road element size, m.
    names : tuple of str
        One label per row (profile names).
    source : str
        Where the profiles came from.
    profiles : object, optional
        The prepared :class:`surfaces.ProfileSet` (used for the PSD and texture depth); None for arrays.
    notes : tuple of str
        What the preparation did that a user should know.
    """

    z: np.ndarray
    dx: float
    names: tuple = ()
    source: str = ""
    profiles: object = field(default=None, repr=False)
    notes: tuple = ()

    def __post_init__(self):
        z = np.atleast_2d(finite_array(self.z, "road.z"))
        if z.ndim != 2 or z.shape[1] < 3:
            raise InputError(f"road.z: expected shape (n_rows, n) with n >= 3, got {np.shape(self.z)}")
        object.__setattr__(self, "z", np.ascontiguousarray(z, dtype=float))
        object.__setattr__(self, "dx", positive(self.dx, "road.dx"))
        names = tuple(self.names) or tuple(f"row {i + 1}" for i in range(z.shape[0]))
        if len(names) != z.shape[0]:
            raise InputError(f"road.names: {len(names)} names for {z.shape[0]} rows")
        object.__setattr__(self, "names", names)

    @property
    def n_rows(self) -> int:
        """Number of parallel profiles."""
        return int(self.z.shape[0])

    @property
    def length(self) -> float:
        """Length covered by the road elements, m ((n - 1) dx)."""
        return float((self.z.shape[1] - 1) * self.dx)

    @property
    def slope(self) -> np.ndarray:
        r""":math:`\tan\alpha_j = (z_{j+1} - z_{j-1})/(2\Delta x)` (one-sided at the ends), shape (n_rows, n)."""
        return np.gradient(self.z, self.dx, axis=1)

    @property
    def angle_deg(self) -> np.ndarray:
        r"""Local slope angle :math:`\alpha_j` of every road element, degrees, shape (n_rows, n)."""
        return np.degrees(np.arctan(self.slope))

    @property
    def rms_slope(self) -> float:
        """Root-mean-square slope of the road elements (all rows)."""
        return float(np.sqrt(np.mean(self.slope ** 2)))

    def texture_depth(self) -> float:
        """Estimated texture depth ETD = 0.2 mm + 0.8 MPD (ISO 13473-1), m, of the profiles (or of the elements).

        The mean profile depth is that of :func:`surfaces.mpd` on the prepared profiles when the road has them,
        else on the road elements themselves.
        """
        import surfaces

        src = self.profiles
        if src is None:
            src = surfaces.profiles_from_array(self.z, dx=self.dx, source=self.source or "road elements")
        with np.errstate(all="ignore"):
            res = surfaces.mpd(src)
        if not math.isfinite(res.mpd):
            raise InputError(f"{self.source or 'road'}: no valid 100 mm segment for the mean profile depth "
                             f"(length {self.length:.3g} m)")
        return float(res.etd)

    def psd(self):
        """Isotropic 2D PSD of the road's profiles (``ProfileSet.psd().to_isotropic()``)."""
        import surfaces

        src = self.profiles
        if src is None:
            src = surfaces.profiles_from_array(self.z, dx=self.dx, source=self.source or "road elements")
        return src.psd().to_isotropic()

    def crop(self, length: float) -> "Road":
        """The first ``length`` metres of every row."""
        n = int(math.floor(positive(length, "length") / self.dx * (1 + 1e-12))) + 1
        return Road(self.z[:, :n], self.dx, self.names, self.source, self.profiles, self.notes)


def contact_surface(road: Road, face: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    r"""Heights and slopes of the road as a tread element with a flat face of length ``face`` meets it.

    Parameters
    ----------
    road : Road
        The road elements.
    face : float or None
        Length of the element's contact face, m; None (or a face no longer than one road element): a point
        contact at the tip, the road's own heights and :attr:`Road.slope`.

    Returns
    -------
    z : ndarray, shape (n_rows, n)
        The upper envelope :math:`z_e(x) = \max_{|s| \le \ell/2} z(x + s)`, m (the road itself without a face).
    tan_alpha : ndarray, shape (n_rows, n)
        Its chord slope across the face, :math:`[z_e(x + \ell/2) - z_e(x - \ell/2)]/\ell` (one-sided within half a
        face of the ends).
    """
    if face is None:
        return road.z, np.ascontiguousarray(road.slope)
    half = int(round(positive(face, "face") / road.dx / 2.0))
    if half < 1:
        return road.z, np.ascontiguousarray(road.slope)
    from scipy import ndimage

    z = ndimage.maximum_filter1d(road.z, size=2 * half + 1, axis=1, mode="nearest")
    n = z.shape[1]
    idx = np.arange(n)
    hi = np.minimum(idx + half, n - 1)
    lo = np.maximum(idx - half, 0)
    tan = (z[:, hi] - z[:, lo]) / ((hi - lo) * road.dx)
    return np.ascontiguousarray(z), np.ascontiguousarray(tan)


def as_road(road, dx: float | None = None, *, max_dropout_fraction: float = 0.2) -> Road:
    """A :class:`Road` from a road, a :class:`surfaces.Profile`, a :class:`surfaces.ProfileSet` or a path.

    Parameters
    ----------
    road : Road, surfaces.Profile, surfaces.ProfileSet, str or path-like
        Profiles in metres (a path is read with :func:`surfaces.read_profiles`).
    dx : float, optional
        Road element size, m; default the profiles' own (coarsest) spacing. A finer ``dx`` than the data is
        refused (it would invent detail).
    max_dropout_fraction : float
        Dropout fraction above which a profile is refused.

    Returns
    -------
    Road
        Every row on the grid x = j dx over the length common to all profiles, linear trend removed.

    Raises
    ------
    InputError
        Naming the profile: too many dropouts, a ``dx`` finer than the data, or profiles without overlap.
    """
    if isinstance(road, Road):
        if dx is None or abs(dx - road.dx) <= 1e-9 * road.dx:
            return road
        raise InputError(f"dx: the road is already made of {road.dx:g} m elements; give its profiles to "
                         f"resample to {dx:g} m")
    import surfaces

    if isinstance(road, surfaces.Profile):
        road = surfaces.ProfileSet((road,), source=road.source)
    elif not isinstance(road, surfaces.ProfileSet):
        if isinstance(road, (str, bytes)) or hasattr(road, "__fspath__"):
            road = surfaces.read_profiles(road)
        else:
            raise InputError(f"road: expected a surfaces.Profile, ProfileSet, persson.tread.Road or a profile "
                             f"file, got {type(road).__name__}")
    ps = road.fill_dropouts(max_dropout_fraction)
    coarsest = max(p.dx for p in ps)
    step = coarsest if dx is None else positive(dx, "dx")
    if step < coarsest * (1 - 1e-6):
        raise InputError(f"dx: {step:g} m is finer than the profiles' spacing {coarsest:g} m; road elements "
                         "cannot be smaller than the measurement")
    ps = ps.resample(step, method="mean" if step > 1.5 * min(p.dx for p in ps) else "auto").detrend("linear")
    start = max(p.x[0] for p in ps)
    stop = min(p.x[-1] for p in ps)
    if not stop - start > 2 * step:
        raise InputError(f"{road.source or 'road'}: the profiles do not overlap (common x range "
                         f"{start:g}..{stop:g} m)")
    n = int(math.floor((stop - start) / step * (1 + 1e-9))) + 1
    grid = start + step * np.arange(n)
    z = np.stack([np.interp(grid, p.x, p.z) for p in ps])
    z -= z.mean(axis=1, keepdims=True)
    notes = []
    drop = np.asarray(road.dropout_fraction)
    if np.any(drop > 0):
        notes.append(f"dropouts filled by interpolation (up to {drop.max():.1%} of a profile)")
    if step > 1.5 * min(p.dx for p in road):
        notes.append(f"profiles averaged onto {step * 1e3:g} mm road elements")
    return Road(z, step, tuple(p.name for p in ps), road.source, ps, tuple(notes))
