"""Tables of the patch-heating march: the modulus shift coordinate and the friction lattice over (speed, pressure,
temperature)."""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np

from materials.shift import SHIFT_RANGE_NOTE

from ..errors import InputError
from ..notes import Note, kind_of_warning

from .heating_arrays import FrictionLattice, TemperatureAxis
from .heating_kernels import _interp_rows, _segment_weights

_NY = 1025  # nodes of the fine y(T) table per sweep from T0 to T0 + max_rise (and as many again above)


_MAX_NU = 512  # most temperature nodes of one speed node


class _Tables:
    r"""Friction tables of every (T0, sigma0) sweep over (v, g = p/sigma0, y).

    The temperature coordinate is :math:`y(T) = \log_{10}a_T(T_0) - \log_{10}a_T(T)` (decades of the shift factor;
    :math:`(T - T_0)/10` K for a material without ``log10_aT``), tabulated finely (``_NY`` nodes from T0 to
    T0 + max_rise, continued as far again so that the lattice node above the cap has its temperature) and
    interpolated linearly. The temperature nodes lie on the lattice :math:`y_k = k h`, :math:`h` = 1 /
    ``temperature_points_per_decade``, the same for every heating strength: a table grows (more nodes per speed) as
    the patch gets hotter and is never refilled. Layout: for the global v node i (``voff`` delimits the sweeps), a
    block of shape (n_g, nu[i]) at ``vtoff[i]`` in ``values``, holding the nodes k = 0 .. nu[i] - 1.
    """

    def __init__(self, model, keys, vnodes, voff, gnodes, V_lo, heating, adhesion_scale=None, adhesion=None,
                 on_nodes=None):
        self.model = model
        # on_nodes[c]: every row of sweep c sits on a speed node (the nodes are the rows' own speeds), so each row
        # reads its node alone (heating_kernels._speed_stencil) and a node's temperatures need reach its own rows'
        # only; else a row between nodes reads the four around it, and each node covers the range of its neighbours
        self.on_nodes = (np.zeros(keys.shape[0], dtype=bool) if on_nodes is None
                         else np.array(on_nodes, dtype=bool))
        # With ``adhesion_scale`` (the model's adhesion tau_f0, > 0) every value is kept as rest + tau_f0 * unit as
        # well (the adhesive term is proportional to tau_f0 and nothing else in the engine depends on it): the
        # table then serves another tau_f0 (:meth:`rescale`) without engine calls. ``rest``/``unit`` blocks
        # parallel ``blocks``; None when the model is not split so. With ``adhesion`` (the model's
        # persson.effects.Adhesion) as well, the factors of the adhesive term tau_f(v, T_q1) A/A0 / sigma0 that do
        # not depend on the adhesion's parameters are kept too: A/A0 / sigma0 and the rubber temperature T_q1 at q1
        # of every node (``area``/``t_q1`` blocks after ``rest``/``unit``); the table then serves any tau_f0, c,
        # v_ref and v_ref_temperature (``separable``), e.g. a joint fit of the adhesion with patch heating.
        self.scale = adhesion_scale
        self.rescalable = adhesion_scale is not None
        self.adhesion = adhesion if self.rescalable else None
        self.separable = self.adhesion is not None and float(getattr(self.adhesion, "c", 0.0)) > 0.0
        self.T0 = np.ascontiguousarray(keys[:, 0])
        self.sig0 = np.ascontiguousarray(keys[:, 1])
        self.vnodes = vnodes
        self.lv = np.ascontiguousarray(np.log(vnodes))
        self.voff = voff
        self.gnodes = gnodes
        self.hy = 1.0 / float(heating.temperature_points_per_decade)
        self.V_lo = np.ascontiguousarray(V_lo)
        self.cap = float(heating.max_rise)
        self.points = 0
        self.calls = 0
        # What each engine call that filled nodes said: its notes, the (category, message) of the warnings it
        # raised (patch_friction issues them again to its caller) and whether it converged. Every node keeps the
        # index of its call (``fill_of``), and a solution reads the outcome of the calls whose nodes it interpolates
        # (:meth:`outcome`): a table grown by a hotter patch does not lend its hot nodes' notes to a cooler one.
        self.fills: list[tuple[tuple, tuple, bool]] = []
        # The engine's note that the rubber left the shift law's fitted range depends on the temperatures of the
        # call that raised it; a table that a hotter solution has grown keeps its nodes, so that note would follow
        # the table's history. It is left out here, and every node keeps the coldest and hottest rubber
        # temperature of its evaluation instead (background and flash), from which patch_friction notes the range
        # of the nodes its own solution interpolates (:meth:`rubber_range`).
        self.parts = None
        nc = keys.shape[0]
        ng = gnodes.size
        self._capped = np.zeros(nc, dtype=bool)
        self.B = np.zeros(nc)  # temperature range of this call: dT_max(v) = min(B v / sqrt(v + V_lo), cap)
        self.dTf = self.cap / (_NY - 1)
        self.yT = np.empty((nc, 2 * _NY - 1))
        la = getattr(model, "material", None)
        la = getattr(la, "log10_aT", None)
        for c in range(nc):
            self.yT[c] = _shift_coordinate(la, self.T0[c], self.T0[c] + self.dTf * np.arange(2 * _NY - 1))
        self.ycap = np.ascontiguousarray(self.yT[:, _NY - 1])
        # the T0 slice (k = 0) of every sweep, one engine call
        V_, G_ = [], []
        for c in range(nc):
            a, b = np.meshgrid(vnodes[voff[c]:voff[c + 1]], gnodes, indexing="ij")
            V_.append(a.ravel())
            G_.append(b.ravel() * self.sig0[c])
        T_ = [np.full(int(voff[c + 1] - voff[c]) * ng, self.T0[c]) for c in range(nc)]
        mu, parts, (t_lo, t_hi), call = self._call(np.concatenate(V_), np.concatenate(T_), np.concatenate(G_))
        # blocks[c]: (n_v of sweep c, n_g, capacity) friction values; nus[c]: nodes filled at each speed node;
        # t_lo[c], t_hi[c] (same shape): the coldest and hottest rubber temperature of each node's evaluation, C;
        # fill_of[c] (same shape): the index in ``fills`` of the engine call that evaluated the node
        self.blocks = [mu.reshape(-1, ng)[voff[c]:voff[c + 1], :, None].copy() for c in range(nc)]
        self.t_lo = [t_lo.reshape(-1, ng)[voff[c]:voff[c + 1], :, None].copy() for c in range(nc)]
        self.t_hi = [t_hi.reshape(-1, ng)[voff[c]:voff[c + 1], :, None].copy() for c in range(nc)]
        self.fill_of = [np.full(b.shape, call, dtype=float) for b in self.blocks]
        self.parts = None
        if parts is not None:
            self.parts = [[a.reshape(-1, ng)[voff[c]:voff[c + 1], :, None].copy() for c in range(nc)] for a in parts]
        self.nus = [np.ones(voff[c + 1] - voff[c], dtype=np.int64) for c in range(nc)]
        self.mu_max = np.array([float(np.max(b)) for b in self.blocks])
        self._layout()

    def _layout(self):
        """Flatten the blocks into (values, vtoff, nu) for the kernels."""
        parts = []
        for c, blk in enumerate(self.blocks):
            for i in range(blk.shape[0]):
                parts.append(np.ascontiguousarray(blk[i, :, :self.nus[c][i]]).ravel())
        self.nu = np.concatenate(self.nus).astype(np.int64)
        sizes = np.array([p_.size for p_ in parts], dtype=np.int64)
        self.vtoff = np.zeros(sizes.size + 1, dtype=np.int64)
        self.vtoff[1:] = np.cumsum(sizes)
        self.values = np.concatenate(parts)

    def dT_max(self, c, v):
        return np.minimum(self.B[c] * v / np.sqrt(v + self.V_lo[c]), self.cap)

    def y_of(self, c, T):
        return np.interp(T, self.T0[c] + self.dTf * np.arange(self.yT.shape[1]), self.yT[c])

    def T_of(self, c, y):
        return np.interp(y, self.yT[c], self.T0[c] + self.dTf * np.arange(self.yT.shape[1]))

    def fill(self, rise0, vs, sweep):
        """Make the table reach the temperatures of this call. ``rise0``: the rise of every row with the friction
        held at its T0 value (an upper bound when the friction falls with temperature); the range covers 1.15
        times it."""
        self.B[:] = self.range_for(rise0, vs, sweep)
        self._grow(np.ones(self.B.size, dtype=bool))

    def range_for(self, rise, vs, sweep) -> np.ndarray:
        """The range factor B of every sweep (:meth:`dT_max`) that covers 1.15 times the temperature rise ``rise``
        of each row (sliding speeds ``vs``, sweeps ``sweep``); a tiny range where nothing rises (it keeps the table
        regular)."""
        B = np.zeros(self.B.size)
        for c in range(B.size):
            sel = sweep == c
            v = vs[sel]
            need = rise[sel] * np.sqrt(v + self.V_lo[c]) / v
            B[c] = 1.15 * float(np.max(need)) if need.size else 0.0
            if not B[c] > 0:
                B[c] = 1e-6 * self.cap
        return B

    def _grow(self, which):
        """Add the lattice nodes that the sweeps ``which`` need for their current range and are missing."""
        ng = self.gnodes.size
        V_, T_, P_, where = [], [], [], []
        for c in np.flatnonzero(which):
            vv = self.vnodes[self.voff[c]:self.voff[c + 1]]
            ymax = np.minimum(self.y_of(c, self.T0[c] + self.dT_max(c, vv)), self.ycap[c])
            self._capped[c] = self._capped[c] or bool(np.any(ymax >= self.ycap[c] * (1 - 1e-12)))
            # a row between speed nodes interpolates over the four around it: each node covers the range of the
            # two above it as well, and the last four that of the last. A row on a node reads that node alone, so
            # where every row of the sweep is on a node, each node reaches its own range only (the speeds of a
            # locked wheel, many times fewer temperature nodes at the slow ones)
            reach = ymax.copy()
            if not self.on_nodes[c]:
                for d in (1, 2):
                    reach[:-d] = np.maximum(reach[:-d], ymax[d:])
                reach[-4:] = np.maximum(reach[-4:], ymax[-1])
            n_new = np.maximum(_temperature_counts(reach, 1.0 / self.hy), self.nus[c])
            grow = np.flatnonzero(n_new > self.nus[c])
            if grow.size == 0:
                continue
            blk = self.blocks[c]
            if int(n_new.max()) > blk.shape[2]:
                self.blocks[c] = _widened(blk, max(int(n_new.max()), 2 * blk.shape[2]))
                self.t_lo[c] = _widened(self.t_lo[c], self.blocks[c].shape[2])
                self.t_hi[c] = _widened(self.t_hi[c], self.blocks[c].shape[2])
                self.fill_of[c] = _widened(self.fill_of[c], self.blocks[c].shape[2])
                for part in self.parts or ():
                    part[c] = _widened(part[c], self.blocks[c].shape[2])
            # the new nodes, speed node by speed node (in ``grow``), each an (n_g, new temperatures) block
            m = (n_new - self.nus[c])[grow]
            size = ng * m
            i_of = np.repeat(grow, size)
            r = np.arange(i_of.size) - np.repeat(np.cumsum(size) - size, size)
            m_of = np.repeat(m, size)
            g_of = r // m_of
            k_of = self.nus[c][i_of] + r % m_of
            V_.append(vv[i_of])
            P_.append(self.gnodes[g_of] * self.sig0[c])
            T_.append(self.T_of(c, k_of * self.hy))
            where.append((c, i_of, g_of, k_of))
            self.nus[c] = n_new
        if not where:
            return
        mu, parts, (t_lo, t_hi), call = self._call(np.concatenate(V_), np.concatenate(T_), np.concatenate(P_))
        k = 0
        for c, i_of, g_of, k_of in where:
            at = slice(k, k + i_of.size)
            self.blocks[c][i_of, g_of, k_of] = mu[at]
            self.t_lo[c][i_of, g_of, k_of] = t_lo[at]
            self.t_hi[c][i_of, g_of, k_of] = t_hi[at]
            self.fill_of[c][i_of, g_of, k_of] = call
            for part, values in zip(self.parts or (), parts or ()):
                part[c][i_of, g_of, k_of] = values[at]
            k += i_of.size
        for c in np.flatnonzero(which):
            self.mu_max[c] = max(self.mu_max[c], float(np.max(self.blocks[c])))
        self._layout()

    def serve(self, on_nodes) -> None:
        """Serve rows whose sweeps have every row on a speed node where ``on_nodes`` says so: a sweep whose table
        was grown for rows on nodes alone and now has rows between them gets the range of its neighbours at every
        node (the nodes a kept table is keyed by are the same; the rows need not be)."""
        need = self.on_nodes & ~np.asarray(on_nodes, dtype=bool)
        if need.any():
            self.on_nodes &= ~need
            self._grow(need)

    def targs(self) -> TemperatureAxis:
        """The temperature coordinate of the lattice, as the march kernel takes it."""
        return TemperatureAxis(T0=self.T0, h=self.hy, cap=self.cap, mu_max=self.mu_max, y_fine=self.yT,
                               dT_fine=self.dTf)

    def has_heated(self) -> bool:
        """Whether every sweep has temperature nodes above T0."""
        return all(int(n.min()) > 1 for n in self.nus)

    def capped(self, c) -> bool:
        return bool(self._capped[c])

    def extend(self, over, umax):
        """Raise the temperature range of the sweeps ``over`` (the patch got hotter than the bound) and grow."""
        for c in np.flatnonzero(over):
            self.B[c] *= 1.25 * float(umax[c])
        self._grow(over)

    def rescale(self, adhesion, model) -> bool:
        """Serve ``model``, the table's model with another ``adhesion`` (its persson.effects.Adhesion), no engine
        call (the nodes a hotter patch needs later come from ``model``): the values become rest + tau_f(v, T_q1)
        A/A0 / sigma0 with the new adhesion's shear stress where the table is :attr:`separable` (any tau_f0, c,
        v_ref), else rest + tau_f0 * unit (the caller makes sure that only tau_f0 differs). Refused (False; the
        caller builds a new table) when the table is not split, or when the values at either adhesion would carry
        notes that depend on the friction's level (friction above 3, below 1e-3: the notes the engine recorded
        would then not be those of the new values)."""
        if not self.rescalable:
            return False
        tau_f0 = float(adhesion.tau_f0)
        if self.separable:
            if adhesion == self.adhesion:
                self.model = model
                return True
            units = self._separable_units(adhesion, model)
            if units is None:
                return False
        else:
            if tau_f0 == self.scale:
                self.model = model
                return True
            units = self.parts[1]
        blocks = [rest + tau_f0 * unit for rest, unit in zip(self.parts[0], units)]
        for c, blk in enumerate(blocks):
            if not _level_note_free(blk.transpose(0, 2, 1)[self._filled(c)]):
                return False
        self.blocks = blocks
        self.parts[1] = units
        self.scale = tau_f0
        if self.separable:
            self.adhesion = adhesion
        self.model = model
        self.mu_max = np.array([float(np.max(b)) for b in self.blocks])
        self._layout()
        return True

    def _separable_units(self, adhesion, model):
        """tau_f(v, T_q1) / tau_f0 * A/A0 / sigma0 of ``adhesion`` at every filled node (zeros elsewhere), per sweep;
        None where it is not finite."""

        units = []
        for c, area in enumerate(self.parts[2]):
            filled = np.broadcast_to(self._filled(c)[:, None, :], area.shape)
            v = np.broadcast_to(self.vnodes[self.voff[c]:self.voff[c + 1]][:, None, None], area.shape)
            unit = np.zeros(area.shape)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # the shift law at the nodes' temperatures: the fills noted it
                tau = adhesion.shear_stress(v[filled], self.parts[3][c][filled], model.material)
            unit[filled] = np.asarray(tau, dtype=float) / float(adhesion.tau_f0) * area[filled]
            if not np.all(np.isfinite(unit)):
                return None
            units.append(unit)
        return units

    def _filled(self, c) -> np.ndarray:
        """The (n_v, capacity) mask of the filled temperature nodes of sweep c."""
        return np.arange(self.blocks[c].shape[2])[None, :] < self.nus[c][:, None]

    def _call(self, v, T, p):
        """The engine's friction at the points (v, T, p); with an adhesion scale its (rest, unit) parts (None
        otherwise); the coldest and hottest rubber temperature at each point (background and flash), C; and the
        index of the call's outcome in ``fills``."""
        from .._checks import UnitWarning
        from ..engine.solver import quadrature_estimate

        # a table outlives the call that fills it and serves later ones: always solved with the error estimate (and
        # its refinement), also for the trial points of a search that skip it (quadrature_estimate(False))
        with warnings.catch_warnings(record=True) as caught, quadrature_estimate(True):
            warnings.simplefilter("always")
            r = self.model.friction(v, temperature=T, pressure=p)
        notes = [note for note in tuple(getattr(r, "notes", ()) or ()) if SHIFT_RANGE_NOTE not in note]
        warned: dict[tuple, None] = {}
        for w in caught:
            if issubclass(w.category, UnitWarning):
                continue  # the table's temperatures are degrees Celsius by construction
            msg = str(w.message)
            if SHIFT_RANGE_NOTE in msg:
                continue  # noted from the nodes a solution uses (rubber_range)
            warned[(w.category, msg)] = None
            if msg not in notes:  # the engine's warnings are among its notes already: once each
                notes.append(Note(msg, kind_of_warning(w.category)))
        self.fills.append((tuple(dict.fromkeys(notes)), tuple(warned), bool(getattr(r, "converged", True))))
        call = len(self.fills) - 1
        self.points += v.size
        self.calls += 1
        mu = np.atleast_1d(np.asarray(r.mu, dtype=float))
        if mu.shape != v.shape:
            raise InputError(f"model: friction returned {mu.shape} values for {v.size} speeds")
        bad = ~np.isfinite(mu) | (mu < 0)
        if np.any(bad):
            j = int(np.argmax(bad))
            raise InputError(f"model: local sliding friction {mu[j]!r} at v_s = {v[j]:g} m/s, T = {T[j]:g} C, "
                             f"p = {p[j]:g} Pa; expected a finite value >= 0")
        trange = _rubber_range(r, T)
        if not self.rescalable:
            return mu, None, trange, call
        terms = getattr(r, "mu_terms", None) or {}
        adh = np.atleast_1d(np.asarray(terms.get("adhesion", np.full_like(mu, np.nan)), dtype=float))
        rest, unit = mu - adh, adh / self.scale
        # the split must give the engine's values back (to rounding), and no note may depend on the level; a
        # result without its adhesive term (not a persson.Model's) is not split
        if (adh.shape != mu.shape or not np.all(np.abs(rest + self.scale * unit - mu) <= 1e-12 * (1.0 + mu))
                or not _level_note_free(mu)):
            self.rescalable = self.separable = False
            self.parts = None
            return mu, None, trange, call
        if self.separable:
            factors = self._adhesion_factors(r, v, p, adh, mu)
            if factors is not None:
                return mu, (rest, unit) + factors, trange, call
            self.separable = False  # e.g. a wet road, where the adhesive term is off: tau_f0 alone is kept apart
            if self.parts is not None:
                del self.parts[2:]
        return mu, (rest, unit), trange, call

    def _adhesion_factors(self, r, v, p, adh, mu):
        """(A/A0 / sigma0, T_q1) at the points of an engine result, when the model's adhesion times them gives the
        engine's adhesive term back (to rounding) at every point and that term is not zero everywhere (so that the
        check means something); else None."""

        area = getattr(r, "contact_area", None)
        tq = getattr(r, "temperature_q", None)
        if area is None or tq is None:
            return None
        a = np.atleast_1d(np.asarray(area, dtype=float)) / p
        tq1 = np.asarray(tq, dtype=float).reshape(v.size, -1)[:, -1].copy()
        if a.shape != v.shape:
            return None
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            term = np.asarray(self.adhesion.shear_stress(v, tq1, self.model.material), dtype=float) * a
        if not (np.all(np.isfinite(term)) and np.any(term > 0)
                and np.all(np.abs(term - adh) <= 1e-12 * (1.0 + mu))):
            return None
        return a, tq1

    def rubber_range(self, rise_top, used=None) -> tuple[float, float]:
        """The coldest and hottest rubber temperature (C) over the nodes a solution interpolates (:meth:`used`,
        given or computed). A function of the solution and of the lattice only (the same whichever calls filled the
        table)."""
        lo, hi = math.inf, -math.inf
        for c, used in enumerate(self.used(rise_top) if used is None else used):
            lo = min(lo, float(np.min(self.t_lo[c].transpose(0, 2, 1)[used])))
            hi = max(hi, float(np.max(self.t_hi[c].transpose(0, 2, 1)[used])))
        return lo, hi

    def outcome(self, rise_top, used=None) -> tuple[tuple, tuple, bool]:
        """(notes, warnings as (category, message), converged) of the engine calls that evaluated the nodes a
        solution interpolates (:meth:`used`, given or computed), in the order of the calls, each once: what a table
        filled for that solution alone would say, whichever hotter solutions grew it before."""
        calls = set()
        for c, used in enumerate(self.used(rise_top) if used is None else used):
            calls.update(int(k) for k in np.unique(self.fill_of[c].transpose(0, 2, 1)[used]))
        notes: dict = {}
        warned: dict = {}
        converged = True
        for k in sorted(calls):
            f_notes, f_warned, f_converged = self.fills[k]
            notes.update(dict.fromkeys(f_notes))
            warned.update(dict.fromkeys(f_warned))
            converged = converged and f_converged
        return tuple(notes), tuple(warned), converged

    def used(self, rise_top) -> list[np.ndarray]:
        """For each sweep c, the (n_v, capacity) mask of the temperature nodes a solution interpolates: at every
        speed and pressure node, those up to the four-point stencil around the hottest background temperature
        T0 + ``rise_top[c]`` of its rows."""
        out = []
        for c in range(self.B.size):
            top = float(np.floor(self.y_of(c, self.T0[c] + max(float(rise_top[c]), 0.0)) / self.hy + 1e-9)) + 3
            n = np.minimum(self.nus[c], int(max(top, 1)))
            out.append(np.arange(self.t_lo[c].shape[2])[None, :] < n[:, None])
        return out

    def args(self) -> FrictionLattice:
        """The friction lattice, as the kernels take it."""
        return FrictionLattice(log_speed=self.lv, v_offset=self.voff, g_nodes=self.gnodes, values=self.values,
                               value_offset=self.vtoff, n_temperature=self.nu)

    def mu_at_sigma0(self, vs, sweep):
        """mu(v_s, sigma0, T0) of every row, interpolated in the T0 slice of the table."""
        return _interp_rows(sweep=sweep.astype(np.int64), log_speed=np.log(vs), lattice=self.args())


def _rubber_range(result, T) -> tuple[np.ndarray, np.ndarray]:
    """The coldest and hottest rubber temperature at each point of an engine result, C: its temperature at every
    scale (``temperature_q``, the flash temperature) where the result has one, else the background ``T``."""
    T = np.asarray(T, dtype=float)
    tq = getattr(result, "temperature_q", None)
    if tq is None:
        return T.copy(), T.copy()
    tq = np.asarray(tq, dtype=float).reshape(T.size, -1)
    return np.minimum(np.min(tq, axis=1), T), np.maximum(np.max(tq, axis=1), T)


def _widened(block: np.ndarray, capacity: int) -> np.ndarray:
    """``block`` (n_v, n_g, k) with its last axis widened to ``capacity`` (zeros after the old entries)."""
    out = np.zeros(block.shape[:2] + (capacity,))
    out[:, :, :block.shape[2]] = block
    return out


def _level_note_free(mu: np.ndarray) -> bool:
    """Whether no note of the engine depends on the level of these friction values: none above 3 (the
    implausible-friction note), none in (0, 1e-3) (the unit-slip note on a road-scale surface)."""
    from .._checks import _MIN_ROAD_MU
    from ..engine.model import _MAX_MU

    mu = np.asarray(mu, dtype=float)
    return bool(np.all(mu <= _MAX_MU) and not np.any((mu > 0) & (mu < _MIN_ROAD_MU)))


def _shift_coordinate(log10_aT, T0: float, T: np.ndarray) -> np.ndarray:
    """y(T) = log10 a_T(T0) - log10 a_T(T) on the increasing temperatures ``T`` (from T0), or (T - T0)/10 when the
    material has no usable shift factor (none, or not finite and increasing in y over the table's first half).
    Beyond the first half (above the cap) a y that stops increasing is continued linearly."""

    half = (T.size + 1) // 2
    y = None
    if log10_aT is not None:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # extrapolated shift factors: the engine's own calls report them
                y = float(np.asarray(log10_aT(T0), dtype=float)) - np.asarray(log10_aT(T), dtype=float)
        except Exception:  # noqa: BLE001  (an unusual material: fall back to kelvin)
            y = None
    if y is None or y.shape != T.shape or not (np.all(np.isfinite(y[:half])) and np.all(np.diff(y[:half]) > 0)):
        return (T - T0) / 10.0
    ok = np.isfinite(y) & np.concatenate([[True], np.diff(y) > 0])
    bad = np.flatnonzero(~ok)
    if bad.size:
        j = int(bad[0])  # >= half
        slope = (y[j - 1] - y[half - 2]) / (T[j - 1] - T[half - 2])
        y[j:] = y[j - 1] + slope * (T[j:] - T[j - 1])
    return y


# =========================================================================================================
# Numba kernels
# =========================================================================================================
@functools.lru_cache(maxsize=8)
def _unit_weights(N: int) -> np.ndarray:
    r"""Product-integration weights of the Abel kernel on a uniform grid of unit spacing.

    For a segment from node j to node j+1 evaluated at node k = j + d (d >= 1), with f linear on the segment,
    :math:`\int f/\sqrt{x_k - x'}\,dx' = h^{1/2}(w_l[d] f_j + w_r[d] f_{j+1})`; see :func:`_segment_weights`.
    Returns shape (2, N) (column 0 unused); a pure function of N, cached: callers must not modify it (it stays
    writeable because numba compiles separate kernels for read-only arrays).
    """
    W = np.zeros((2, N))
    for dd in range(1, N):
        W[0, dd], W[1, dd] = _segment_weights(float(dd), float(dd - 1), 1.0)
    return W


def _speed_nodes(v: np.ndarray, per_decade: float) -> np.ndarray:
    """Table nodes in sliding speed: the distinct values when they are few, else log-spaced nodes spanning them
    (at least four, spacing at most 1/``per_decade`` decade)."""
    u = np.unique(v)
    lo, hi = math.log10(float(u[0])), math.log10(float(u[-1]))
    n_int = max(3, int(math.ceil((hi - lo) * per_decade - 1e-9)))
    if u.size <= n_int + 1:
        return u
    return 10.0 ** np.linspace(lo, hi, n_int + 1)


def _temperature_counts(ymax: np.ndarray, per_decade: float) -> np.ndarray:
    """Temperature nodes of each speed node that reach ``ymax`` (decades of a_T) on the lattice of spacing
    1/``per_decade``: at least 4 (cubic interpolation) when ``ymax`` > 0, else 1 (the T0 slice alone)."""
    x = np.asarray(ymax, dtype=float) * per_decade
    n = np.ceil(np.maximum(x, 0.0) - 1e-9).astype(np.int64) + 1
    n = np.where(x > 0.0, np.maximum(n, 4), 1)
    return np.clip(n, 1, _MAX_NU).astype(np.int64)
