r"""Tread patterns: grooves from parameters, or the rubber/void map of a footprint image.

A pattern answers one question for the march: is there rubber at the material point (x, y) of the tread, x along
the circumference (the rolling direction, m) and y across it (m, 0 on the centre line)? Grooves are moulded to a
depth (the full tread depth by default); a tread element that falls in a groove carries nothing. The void
fraction and the groove depth give the water the pattern can hold (:mod:`persson.tread.wet`).

* :class:`Grooves`: straight grooves of width w, pitch P and angle :math:`\theta` from the lateral direction
  (0: lateral grooves across the rolling direction, 90: circumferential grooves); rubber where
  :math:`(x\cos\theta + y\sin\theta - x_0) \bmod P \ge w`.
* :class:`FootprintPattern` (:func:`read_footprint`): a footprint print or photograph thresholded with Otsu's
  method (scikit-image); rubber where the print is dark (ink) or bright, as told; periodic along x with the
  image's length.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from frictioncite import doi

from .._checks import number, positive
from ..errors import InputError

__all__ = ["Grooves", "FootprintPattern", "read_footprint", "OTSU_1979"]

#: N. Otsu, A threshold selection method from gray-level histograms, IEEE Trans. Syst. Man Cybern. 9, 62 (1979).
OTSU_1979 = "10.1109/TSMC.1979.4310076"


@dataclass(frozen=True)
class Grooves:
    r"""Straight grooves of a tread pattern.

    Parameters
    ----------
    width : float
        Groove width w, m (> 0, < ``pitch``).
    pitch : float
        Distance between groove centre lines, m, measured across the grooves.
    depth : float, optional
        Groove depth, m; default the tyre's tread depth.
    angle_deg : float
        Angle of the grooves from the lateral direction, degrees in [-90, 90]: 0 for lateral grooves (across the
        rolling direction), 90 for circumferential (rib) grooves.
    offset : float
        Position of the first groove edge along the direction across the grooves, m.

    Raises
    ------
    InputError
        A groove as wide as or wider than its pitch (no rubber left), non-positive sizes, an angle outside
        [-90, 90] degrees.
    """

    width: float
    pitch: float
    depth: float | None = None
    angle_deg: float = 0.0
    offset: float = 0.0

    def __post_init__(self):
        w = positive(self.width, "grooves.width")
        p = positive(self.pitch, "grooves.pitch")
        if w >= p:
            raise InputError(f"grooves.width: a groove {w * 1e3:g} mm wide on a {p * 1e3:g} mm pitch leaves no "
                             "rubber; expected width < pitch")
        object.__setattr__(self, "width", w)
        object.__setattr__(self, "pitch", p)
        if self.depth is not None:
            object.__setattr__(self, "depth", positive(self.depth, "grooves.depth"))
        a = number(self.angle_deg, "grooves.angle_deg")
        if not -90.0 <= a <= 90.0:
            raise InputError(f"grooves.angle_deg: expected an angle in [-90, 90] degrees, got {a:g}")
        object.__setattr__(self, "angle_deg", a)
        object.__setattr__(self, "offset", number(self.offset, "grooves.offset"))

    @property
    def void_fraction(self) -> float:
        """Fraction of the tread surface taken by grooves, w / P."""
        return self.width / self.pitch

    def land(self, x, y) -> np.ndarray:
        """True where there is rubber at (x, y) (m, broadcast together)."""
        th = math.radians(self.angle_deg)
        n = np.asarray(x, dtype=float) * math.cos(th) + np.asarray(y, dtype=float) * math.sin(th) - self.offset
        return np.mod(n, self.pitch) >= self.width

    def pad_length(self) -> float:
        """Length of the rubber pads between grooves along the rolling direction, m (inf for ribs)."""
        c = abs(math.cos(math.radians(self.angle_deg)))
        if c < 1e-9:
            return math.inf
        return (self.pitch - self.width) / c


@doi(OTSU_1979)
@dataclass(frozen=True, eq=False)
class FootprintPattern:
    """Rubber/void map of a footprint image (see :func:`read_footprint`).

    Parameters
    ----------
    mask : ndarray of bool, shape (ny, nx)
        True where there is rubber; rows run across the tread (y), columns along the rolling direction (x).
    pixel_size : float
        Size of a pixel, m.
    depth : float, optional
        Groove depth, m; default the tyre's tread depth.
    source : str
        The image file.
    """

    mask: np.ndarray
    pixel_size: float
    depth: float | None = None
    source: str = ""
    threshold: float = field(default=float("nan"))

    def __post_init__(self):
        m = np.asarray(self.mask, dtype=bool)
        if m.ndim != 2 or min(m.shape) < 2:
            raise InputError(f"{self.source or 'footprint'}: expected a 2D mask, got shape {m.shape}")
        if not m.any():
            raise InputError(f"{self.source or 'footprint'}: no rubber found in the footprint (all void)")
        object.__setattr__(self, "mask", m)
        object.__setattr__(self, "pixel_size", positive(self.pixel_size, "pixel_size"))
        if self.depth is not None:
            object.__setattr__(self, "depth", positive(self.depth, "footprint depth"))

    @property
    def void_fraction(self) -> float:
        """Fraction of the image that is groove (void)."""
        return float(1.0 - self.mask.mean())

    @property
    def length(self) -> float:
        """Extent of the image along the rolling direction, m (the period of the pattern)."""
        return self.mask.shape[1] * self.pixel_size

    @property
    def width(self) -> float:
        """Extent of the image across the tread, m."""
        return self.mask.shape[0] * self.pixel_size

    def land(self, x, y) -> np.ndarray:
        """True where there is rubber at (x, y) (m; x periodic with the image length; y from the centre line,
        void beyond the image's width)."""
        x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        ny, nx = self.mask.shape
        col = np.mod(np.floor(x / self.pixel_size).astype(np.int64), nx)
        row = np.floor(y / self.pixel_size + ny / 2.0).astype(np.int64)
        inside = (row >= 0) & (row < ny)
        out = np.zeros(x.shape, dtype=bool)
        out[inside] = self.mask[row[inside], col[inside]]
        return out

    def pad_length(self) -> float:
        """Mean length of the rubber runs along the rolling direction, m."""
        runs = []
        for line in self.mask:
            edges = np.flatnonzero(np.diff(np.concatenate(([False], line, [False])).astype(np.int8)))
            runs.extend((edges[1::2] - edges[::2]).tolist())
        return float(np.mean(runs)) * self.pixel_size if runs else 0.0


@doi(OTSU_1979)
def read_footprint(path, pixel_size: float, *, rubber: str = "dark", depth: float | None = None,
                   min_feature: float | None = None) -> FootprintPattern:
    """Read a footprint image (ink print, pressure-film scan, photograph) into a rubber/void map.

    Parameters
    ----------
    path : str or path-like
        An image readable by :func:`skimage.io.imread` (PNG, JPEG, TIFF...), the rolling direction along its
        rows (left to right).
    pixel_size : float
        Size of a pixel on the tread, m.
    rubber : {"dark", "bright"}
        Whether the rubber (contact) is the dark part (ink print) or the bright part.
    depth : float, optional
        Groove depth, m (default: the tyre's tread depth).
    min_feature : float, optional
        Rubber islands and void specks smaller than this size (m) are removed (default two pixels).

    Returns
    -------
    FootprintPattern
        With the Otsu threshold used (grey level in [0, 1]) in ``threshold``.

    Raises
    ------
    InputError
        Naming the file: unreadable, uniform (nothing to threshold), or wrong ``rubber``.
    """
    from pathlib import Path

    p = Path(path)
    if rubber not in ("dark", "bright"):
        raise InputError(f"rubber: expected 'dark' or 'bright', got {rubber!r}")
    size = positive(pixel_size, "pixel_size")
    if not p.is_file():
        raise InputError(f"footprint image {p} does not exist")
    from skimage import color, filters, io, morphology

    try:
        img = np.asarray(io.imread(str(p)), dtype=float)
    except Exception as exc:  # noqa: BLE001 - any reader failure is a bad input file
        raise InputError(f"{p}: not a readable image ({type(exc).__name__}: {exc})") from None
    if img.ndim == 3:
        img = color.rgb2gray(img[..., :3] if img.shape[-1] >= 3 else img[..., 0])
    if img.ndim != 2:
        raise InputError(f"{p}: expected a 2D grey or colour image, got shape {img.shape}")
    lo, hi = float(img.min()), float(img.max())
    if not hi > lo:
        raise InputError(f"{p}: the image is uniform (grey level {lo:g}); no footprint to threshold")
    grey = (img - lo) / (hi - lo)
    t = float(filters.threshold_otsu(grey))
    mask = grey < t if rubber == "dark" else grey > t
    px = 2 if min_feature is None else max(1, int(round(positive(min_feature, "min_feature") / size)))
    mask = ~_drop_specks(~_drop_specks(mask, px * px, morphology), px * px, morphology)
    return FootprintPattern(mask, size, depth, str(p), t)


def _drop_specks(mask, area: int, morphology):
    """``mask`` without its connected True regions smaller than ``area`` pixels."""
    try:  # scikit-image >= 0.26 names the bound max_size (removing objects up to and including it)
        return morphology.remove_small_objects(mask, max_size=area - 1)
    except TypeError:
        return morphology.remove_small_objects(mask, min_size=area)
