r"""Sliding directions: :meth:`persson.Model.friction` with ``direction_deg``, and its result for many directions.

``model.friction(speed, temperature=..., pressure=..., direction_deg=...)`` on an anisotropic surface
(:mod:`surfaces.anisotropy`) solves Persson's general expressions for the sliding direction :math:`\theta`
(:mod:`persson.engine.anisotropic`). One direction gives a :class:`persson.FrictionResult`, exactly as an
isotropic surface does (its notes name the direction); an array of directions gives a
:class:`DirectionalFriction`: :math:`\mu(\theta)` for every direction and speed at once, each direction's full
result, and a polar plot. The directions are solved together (one modulus table, one set of angular tables) and
handed one by one to the model's own assembly of the result, so effects, notes, warnings and the error estimate
are those of the isotropic engine.

Angles are degrees from the x axis of the surface (``docs/conventions.md``). Values that all lie within
:math:`\pm 2\pi` with a fraction look like radians: the Python API warns (:class:`persson.UnitWarning`), a case
file refuses them.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from frictioncite import citations_of

from .anisotropic import is_anisotropic, solve_directions
from .results import FrictionResult
from ..errors import InputError, UnitWarning

__all__ = ["DirectionalFriction", "friction", "directions", "plot_polar"]


def friction(model, speed, temperature, pressure, direction_deg):
    """The friction of ``model`` sliding along ``direction_deg`` (see :meth:`persson.Model.friction`).

    Parameters
    ----------
    model : persson.Model
    speed, temperature, pressure
        As :meth:`persson.Model.friction`.
    direction_deg : float, array_like or None
        Sliding direction(s), degrees from the x axis of the surface; None: the model's ``direction_deg``, else 0.

    Returns
    -------
    FrictionResult or DirectionalFriction
        A :class:`FrictionResult` for one direction (a number), a :class:`DirectionalFriction` for an array.
    """
    value = direction_deg if direction_deg is not None else model.direction_deg
    theta, scalar = (np.zeros(1), True) if value is None else (directions(value, "direction_deg", stacklevel=4),
                                                                 np.ndim(value) == 0)
    theta = np.atleast_1d(theta).ravel()
    if not is_anisotropic(model.surface):
        # the direction does not matter: one isotropic solve serves every direction
        r = model._friction(speed, temperature, pressure)
        return r if scalar else DirectionalFriction.of(theta, (r,) * theta.size)
    solved: dict = {}

    def solver_for(k):
        def solve(surface, material, cond, grid, nu, gamma, thermal, correction, modulus):
            if "all" not in solved:
                solved["all"] = solve_directions(model.surface, surface, material, cond, grid, nu, gamma, thermal,
                                                 correction, modulus, theta)
            return solved["all"][k]
        return solve

    default = (None if value is not None else "no sliding direction given: sliding along the x axis of the surface "
               "(direction_deg = 0); the friction of this anisotropic surface depends on the direction")
    cites = citations_of(solve_directions, model.surface)
    results = []
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for k, th in enumerate(theta):
            r = model._friction(speed, temperature, pressure, solve=solver_for(k))
            head = (f"sliding direction {th:g} deg from the x axis of the surface",) + ((default,) if default else ())
            results.append(r.replace(notes=head + tuple(r.notes),
                                     citations=tuple(dict.fromkeys(tuple(r.citations) + tuple(cites)))))
    _reemit(caught, theta.size)
    return results[0] if scalar else DirectionalFriction.of(theta, tuple(results))


def directions(value, name: str = "direction_deg", *, strict: bool = False, stacklevel: int = 3) -> np.ndarray:
    r"""Sliding direction(s) in degrees as a float array (the shape of ``value``).

    A value that is not a finite number is an InputError naming ``name``. Angles that look like radians (every
    value within :math:`|x| \le 2\pi` and one of them not a whole number of degrees) are an InputError with
    ``strict`` (case files) and a :class:`persson.UnitWarning` otherwise.

    Parameters
    ----------
    value : float or array_like
        The direction(s), degrees.
    name : str
        The argument or case key, named in the messages.
    strict : bool
        Refuse angles that look like radians instead of warning.
    stacklevel : int
        Of the warning.
    """
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name}: expected a sliding direction in degrees (a number or an array of numbers), got "
                         f"{value!r}") from None
    if a.size == 0:
        raise InputError(f"{name}: expected at least one sliding direction in degrees")
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name}: NaN or infinite direction at index {int(np.argmax(~np.isfinite(a.ravel())))}")
    flat = a.ravel()
    frac = np.abs(flat - np.round(flat)) > 1e-9
    if np.all(np.abs(flat) <= 2.0 * math.pi + 1e-9) and np.any(frac):
        x = float(flat[np.argmax(frac)])
        msg = (f"{name}: {x:g} looks like an angle in radians ({math.degrees(x):.4g} degrees); sliding directions "
               f"are in degrees from the x axis of the surface: give {math.degrees(x):.4g}")
        if strict:
            raise InputError(msg)
        warnings.warn(msg, UnitWarning, stacklevel=stacklevel)
    return a


def _reemit(caught, n_dir: int) -> None:
    """Warn once per category and first message of the directions' warnings (they repeat per direction)."""
    seen = {}
    for w in caught:
        seen.setdefault(w.category, [str(w.message), 0])[1] += 1
    for category, (msg, count) in seen.items():
        if n_dir > 1 and count > 1:
            msg = f"{msg} (and similar warnings in {count - 1} more of the {n_dir} directions)"
        warnings.warn(msg, category, stacklevel=4)


# ---------------------------------------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class DirectionalFriction:
    """Friction of an anisotropic surface for several sliding directions.

    Arrays have shape (n_direction,) + the shape of the ``speed`` argument (so (n_direction,) for a scalar speed).

    Attributes
    ----------
    direction_deg : ndarray (n_direction,)
        Sliding directions, degrees from the x axis of the surface.
    results : tuple of FrictionResult
        The full result of each direction (per-scale detail, notes, error estimate).
    mu, mu_hysteresis, mu_adhesion, contact_area, error_estimate : ndarray
        Per direction and speed.
    notes : tuple of str
        The notes of every direction, each once.
    citations : tuple of str
    """

    direction_deg: np.ndarray
    results: tuple
    mu: np.ndarray
    mu_hysteresis: np.ndarray
    mu_adhesion: np.ndarray
    contact_area: np.ndarray
    error_estimate: np.ndarray
    notes: tuple = ()
    citations: tuple = ()

    @classmethod
    def of(cls, theta: np.ndarray, results: tuple) -> "DirectionalFriction":
        """Collect per-direction results."""
        def stack(name):
            return np.stack([np.asarray(getattr(r, name), dtype=float) for r in results])

        notes = tuple(dict.fromkeys(n for r in results for n in r.notes
                                    if not n.startswith("sliding direction ")))
        cites = tuple(dict.fromkeys(c for r in results for c in r.citations))
        return cls(direction_deg=np.asarray(theta, dtype=float), results=tuple(results), mu=stack("mu"),
                   mu_hysteresis=stack("mu_hysteresis"), mu_adhesion=stack("mu_adhesion"),
                   contact_area=stack("contact_area"), error_estimate=stack("error_estimate"), notes=notes,
                   citations=cites)

    def __repr__(self) -> str:
        mu = np.atleast_1d(self.mu)
        return (f"DirectionalFriction({self.direction_deg.size} directions {self.direction_deg.min():g}.."
                f"{self.direction_deg.max():g} deg, {self.speed.size} speed(s), mu {mu.min():.4g}..{mu.max():.4g})")

    @property
    def speed(self) -> np.ndarray:
        """Sliding speeds, m/s (n_speed,)."""
        return self.results[0].speed

    def at(self, direction_deg: float) -> FrictionResult:
        """The result of the direction ``direction_deg`` (one of :attr:`direction_deg`, modulo 360)."""
        d = np.abs((self.direction_deg - float(direction_deg) + 180.0) % 360.0 - 180.0)
        k = int(np.argmin(d))
        if d[k] > 1e-9:
            raise InputError(f"direction_deg: {direction_deg:g} is not one of the directions solved "
                             f"({', '.join(f'{x:g}' for x in self.direction_deg)})")
        return self.results[k]

    def as_table(self) -> dict[str, np.ndarray]:
        """Columns ``direction_deg``, then those of :meth:`persson.FrictionResult.as_table` (``speed_m_s, T_C,
        pressure_Pa, mu, mu_hysteresis, mu_adhesion, contact_area, max_flash_temperature_K`` -- the flash
        temperature RISE above ``T_C``, K, not an absolute temperature -- and the contact geometry where computed),
        and ``error_estimate``, one row per direction and speed. A file written from it should carry
        :data:`persson.engine.results.FLASH_RISE_COMMENT` above its header, as ``persson friction`` does."""
        rows: dict[str, list] = {}
        for th, r in zip(self.direction_deg, self.results):
            cols = {"direction_deg": np.full(r.speed.size, th)} | r.as_table()
            cols["error_estimate"] = np.atleast_1d(r.error_estimate)
            for k, v in cols.items():
                rows.setdefault(k, []).append(np.asarray(v, dtype=float))
        return {k: np.concatenate(v) for k, v in rows.items()}

    def polar_plot(self, speeds=None, ax=None, title: str = ""):
        """:func:`plot_polar` of this result."""
        return plot_polar(self, speeds=speeds, ax=ax, title=title)


def plot_polar(result: DirectionalFriction, speeds=None, ax=None, title: str = ""):
    """Polar plot of mu against the sliding direction, one curve per speed (mu(theta + 180) = mu(theta): the
    directions are mirrored to close the curve when they span less than a full turn).

    Parameters
    ----------
    result : DirectionalFriction
    speeds : sequence of int, optional
        Indices of the speeds to draw (default: up to four, spread over the range).
    ax : matplotlib polar Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    from .. import plots  # noqa: F401  (the Agg backend)
    import matplotlib.pyplot as plt

    v = result.speed
    mu = np.asarray(result.mu, dtype=float).reshape(result.direction_deg.size, -1)
    idx = (np.unique(np.linspace(0, v.size - 1, min(4, v.size)).round().astype(int)) if speeds is None
           else np.atleast_1d(np.asarray(speeds, dtype=int)))
    if ax is None:
        fig, ax = plt.subplots(subplot_kw={"projection": "polar"}, figsize=(5.5, 5), constrained_layout=True)
    else:
        fig = ax.figure
    th = np.radians(result.direction_deg)
    order = np.argsort(th % (2 * math.pi))
    span = float(np.ptp(result.direction_deg % 360.0))
    for i in idx:
        t, m = th[order] % (2 * math.pi), mu[order, i]
        if span < 359.0:
            t, m = np.concatenate([t, t + math.pi]), np.concatenate([m, m])
            o = np.argsort(t % (2 * math.pi))
            t, m = t[o] % (2 * math.pi), m[o]
        ax.plot(np.append(t, t[0]), np.append(m, m[0]), marker=".", label=f"v = {v[i]:.3g} m/s")
    ax.set_title(title or "friction coefficient against the sliding direction (deg from x)")
    ax.legend(loc="lower left", bbox_to_anchor=(0.85, -0.05), fontsize="small")
    return fig
