"""Specification of the local friction along the contact patch: mu(v_s, p(x), T(x)) (PatchHeating).

Model (persson/slip/heating.py): behind the stick zone the rubber slides with the shear tau = mu(v_s, p, T) p and
the frictional power tau v_s heats the interface; one-dimensional conduction into the tread (moving through the
patch at (1 - s) V) and into the counter-surface (moving at V), both entering at T0, with a common interface
temperature, gives

    T(xi) - T0 = Lambda int_{xi_c}^{xi} mu g / sqrt(xi - xi') dxi',
    Lambda = eta sigma0 v_s sqrt(l) / (sqrt(pi) (e_r sqrt((1 - s) V) + e_c sqrt(V))),   g = p / sigma0.

Independent references used here:
* heat_fraction = 0: the brush model with the local friction mu(v_s, p(x)) (brush_mu; quadrature for p(x));
* uniform pressure and mu = mu0 - b (T - T0): the Abel equation has the closed form
  mu(xi) = mu0 erfcx(c sqrt(xi - xi_c)), c = Lambda b sqrt(pi) (Laplace transform: Y = c / (s (sqrt(s) + c)));
* the real engine: a slow Picard iteration written here (whole profile re-evaluated with the engine each pass).
"""

import itertools
import math
import warnings
from dataclasses import dataclass, field

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import erfcx

import materials
import persson
import surfaces
import validation
from persson import slip as ps
from persson.effects import PatchHeating
from persson.slip import patch_friction
from persson.errors import InputError

L, W, K, SIGMA0, T0 = 0.02, 0.01, 3.0e9, 0.3e6, 20.0
E_R, E_C = 700.0, 1500.0


@dataclass
class ClosedForm:
    """A friction 'model' given by a formula mu(v, p, T); records every engine call."""

    mu: object
    calls: list = field(default_factory=list)
    effect_names: tuple = ()
    material: object = None

    def friction(self, speed, temperature=20.0, pressure=0.3e6):
        v, T, p = np.broadcast_arrays(np.asarray(speed, float), np.asarray(temperature, float),
                                      np.asarray(pressure, float))
        self.calls.append(v.size)

        class R:
            pass

        r = R()
        r.mu = np.asarray(self.mu(v, p, T), dtype=float)
        return r


def lam(s, V, eta=1.0, e_r=E_R, e_c=E_C, sigma0=SIGMA0, length=L):
    return eta * sigma0 * s * V * math.sqrt(length) / (math.sqrt(math.pi) * (e_r * math.sqrt((1 - s) * V)
                                                                             + e_c * math.sqrt(V)))


def road_model(*effects):
    return persson.Model(surfaces.example_road(), materials.example_tread(), effects=list(effects))


# ------------------------------------------------------------------------------------------------------------
def test_without_heating_the_local_friction_follows_speed_and_local_pressure():
    # mu cubic in ln v (the four-point interpolation in speed is exact for it), independent of p and T
    cubic = ClosedForm(lambda v, p, T: 0.9 + 0.05 * np.log(v) - 0.004 * np.log(v) ** 2 - 0.0003 * np.log(v) ** 3)
    h = PatchHeating(heat_fraction=0.0, rubber_effusivity=E_R)
    c = ps.Contact(L, W, K, "parabolic")
    s = np.concatenate([np.geomspace(0.003, 0.5, 25), [0.7, 1.0]])
    for V in (0.3, 3.0):
        sol = patch_friction(cubic, h, c, s, V, T0, SIGMA0)
        ref, ref_xc = ps.brush_mu(c, s, cubic.mu(s * V, SIGMA0, T0), pressure=SIGMA0)
        assert np.allclose(sol.mu, ref, rtol=0, atol=1e-12)
        assert np.allclose(sol.stick_fraction, ref_xc, atol=1e-12)
        assert np.all(sol.max_rise == 0)

    # mu rising with the local pressure: mu(p) = 0.6 + 0.3 p / sigma0 (evaluated at >= 2 % of sigma0 at the edges)
    lin = ClosedForm(lambda v, p, T: 0.6 + 0.3 * p / SIGMA0)

    def mu_g(g):
        return 0.6 + 0.3 * max(g, 0.02)

    def g_of(x):
        return 6 * x * (1 - x)

    def reference(s):
        a = K * (s / (1 - s)) * L / SIGMA0
        margin = lambda x: mu_g(g_of(x)) * g_of(x) - a * x  # noqa: E731
        xc = brentq(margin, 1e-9, 1.0) if margin(1e-9) > 0 else 0.0
        slide, _ = quad(lambda x: mu_g(g_of(x)) * g_of(x), xc, 1.0, points=[0.02, 0.98], limit=200)
        return 0.5 * a * xc**2 + slide

    c = ps.Contact(L, W, K, "parabolic", n_points=801)
    s = np.array([0.002, 0.01, 0.03, 0.1])
    sol = patch_friction(lin, h, c, s, 1.0, T0, SIGMA0)
    assert np.allclose(sol.mu, [reference(x) for x in s], atol=2e-5)


@pytest.mark.parametrize("slip, V", [(1.0, 2.0), (0.3, 2.0), (0.05, 0.5)])
def test_temperature_along_the_patch_matches_the_closed_form_abel_solution(slip, V):
    mu0, b = 1.2, 0.012  # mu = mu0 - b (T - T0)
    lin_T = ClosedForm(lambda v, p, T: mu0 - b * (T - T0))
    h = PatchHeating(counter_effusivity=E_C, heat_fraction=0.9, rubber_effusivity=E_R)
    Lam = lam(slip, V, eta=0.9)
    cc = Lam * b * math.sqrt(math.pi)
    if slip < 1:
        a = K * slip / (1 - slip) * L / SIGMA0
        xc = mu0 / a
        assert xc < 1
    else:
        a, xc = math.inf, 0.0
    slide, _ = quad(lambda t: erfcx(cc * t) * 2 * t, 0.0, math.sqrt(1 - xc), epsabs=1e-13, epsrel=1e-13)
    exact = (0.5 * a * xc**2 if slip < 1 else 0.0) + mu0 * slide
    errors = []
    for n in (101, 201, 401, 801):
        c = ps.Contact(L, W, K, "uniform", n_points=n)
        sol = patch_friction(lin_T, h, c, slip, V, T0, SIGMA0, profiles=True)
        errors.append(abs(sol.mu[0] - exact))
        # the profile: T0 in the stick zone, then the closed form
        x = sol.xi
        T_exact = np.where(x < xc, T0, T0 + mu0 / b * (1 - erfcx(cc * np.sqrt(np.clip(x - xc, 0, None)))))
        assert np.max(np.abs(sol.temperature[0] - T_exact)) < 0.02 * max(1.0, np.max(T_exact) - T0) / n ** 0.5
        assert sol.stick_fraction[0] == pytest.approx(xc, abs=1e-12)
    print(f"\nslip {slip}, V {V}: exact {exact:.6f}, errors by n_points {np.array(errors)}")
    # measured: errors 8e-5 -> 3.5e-6 (slip 1), 1.4e-5 -> 8e-7 (0.3) from 101 to 801 nodes, i.e. order about 1.5:
    # the temperature rises like sqrt(x - x_c) behind the stick zone
    assert errors[-1] < 1e-5
    assert errors[0] / errors[-1] > 12


def test_partition_of_the_heat_between_tread_and_counter_surface():
    h = PatchHeating(counter_effusivity=E_C, rubber_effusivity=E_R)
    s, V = np.array([0.1, 0.5, 1.0]), 2.0
    share = h.rubber_share(s, V, E_R)
    expect = E_R * np.sqrt((1 - s) * V) / (E_R * np.sqrt((1 - s) * V) + E_C * np.sqrt(V))
    assert np.allclose(share, expect) and share[-1] == 0.0  # the locked tread takes no net heat
    assert np.allclose(h.heat_factor(s, V, SIGMA0, L, E_R), [lam(x, V) for x in s])
    # the tread's effusivity comes from material.thermal unless given
    tread = materials.example_tread()
    th = tread.thermal
    assert PatchHeating().effusivity_of(tread) == pytest.approx(
        math.sqrt(th.conductivity * th.density * th.specific_heat))


def picard_reference(model, s, V, contact, heating, iters=80, temperature=T0, sigma0=SIGMA0):
    """Slow reference: iterate the whole temperature profile, every pass one engine call at all nodes (background
    temperature ``temperature``, mean pressure ``sigma0``)."""
    T_bg, p_mean = temperature, sigma0
    xi = contact._xi
    g = contact._g
    p = np.maximum(g, 0.02) * p_mean
    vs = s * V
    e_r = heating.effusivity_of(model.material)
    Lam = heating.heat_fraction * p_mean * vs * math.sqrt(L) / (
        math.sqrt(math.pi) * (e_r * math.sqrt((1 - s) * V) + heating.counter_effusivity * math.sqrt(V)))
    N = xi.size

    def mu_at(T):
        return np.asarray(model.friction(np.full(N, vs), temperature=T, pressure=p).mu, dtype=float)

    mu0 = mu_at(np.full(N, T_bg))
    if s < 1:
        a = K * s / (1 - s) * L / p_mean
        d = mu0 * g - a * xi
        i = int(np.argmax(d[1:] <= 0)) + 1
        t = d[i - 1] / (d[i - 1] - d[i])
        xc = xi[i - 1] + t * (xi[i] - xi[i - 1])
        gc = g[i - 1] + t * (g[i] - g[i - 1])
        mc = mu0[i - 1] + t * (mu0[i] - mu0[i - 1])  # (linear in between: only used at T_bg)
        mc = float(model.friction(vs, temperature=T_bg, pressure=max(gc, 0.02) * p_mean).mu)
        x = np.concatenate([[xc], xi[i:]])
        gs = np.concatenate([[gc], g[i:]])
        sel = slice(i, N)
    else:
        a, xc, i = math.inf, 0.0, 0
        x, gs, sel = xi, g, slice(0, N)
        mc = mu0[0]
    T = np.full(N, T_bg)
    for _ in range(iters):
        mu = mu_at(T)
        f = np.concatenate([[mc * gs[0]], (mu * g)[sel]]) if s < 1 else mu * g
        rise = np.zeros(x.size)
        for k in range(1, x.size):  # product trapezoid: f linear between points, the kernel exactly
            A = x[k] - x[:k]
            B = x[k] - x[1:k + 1]
            h = x[1:k + 1] - x[:k]
            I0 = 2 * (np.sqrt(A) - np.sqrt(B))
            I1 = A * I0 - 2 / 3 * (A**1.5 - B**1.5)
            rise[k] = np.sum(f[:k] * (I0 - I1 / h) + f[1:k + 1] * I1 / h)
        T_new = np.full(N, T_bg)
        T_new[sel] = T_bg + Lam * (rise[1:] if s < 1 else rise)
        if np.max(np.abs(T_new - T)) < 1e-6:
            T = T_new
            break
        T = T_new
    mu = mu_at(T)
    f = np.concatenate([[mc * gs[0]], (mu * g)[sel]]) if s < 1 else mu * g
    total = (0.5 * a * xc**2 if s < 1 else 0.0) + float(np.sum(0.5 * np.diff(x) * (f[1:] + f[:-1])))
    return total, T


def test_tabulated_engine_friction_agrees_with_a_direct_iteration():
    model = road_model(PatchHeating())
    c = ps.Contact(L, W, K, "parabolic", n_points=101)
    rows = [(0.15, 3.0), (1.0, 1.0)]
    # the rows sit in a 30 x 2 sweep so that the table interpolates in speed as it does in practice
    S = np.concatenate([np.geomspace(0.01, 1.0, 30), [r[0] for r in rows]])
    Vs = np.concatenate([np.where(np.arange(30) % 2, 3.0, 1.0), [r[1] for r in rows]])
    sol = patch_friction(model, model.effect("patch_heating"), c, S, Vs, T0, SIGMA0, profiles=True)
    for k, (s, V) in enumerate(rows):
        ref, T_ref = picard_reference(model.without("patch_heating"), s, V, c, model.effect("patch_heating"))
        j = 30 + k
        print(f"\ns = {s}, V = {V}: table {sol.mu[j]:.5f}, direct {ref:.5f}, max rise {np.max(T_ref) - T0:.1f} K")
        assert sol.mu[j] == pytest.approx(ref, abs=1e-3)
        assert np.max(np.abs(sol.temperature[j] - T_ref)) < 0.05 * (np.max(T_ref) - T0)


def test_patch_heating_makes_a_peak_then_a_fall_to_the_locked_wheel():
    c = ps.Contact(L, W, K)
    S = np.concatenate([np.geomspace(0.01, 0.9, 40), [0.95, 1 - 1e-6, 1.0]])
    V = np.array([1.0, 3.0])
    cold = ps.mu_slip(road_model(), S[:, None], V[None, :], contact=c)
    hot = ps.mu_slip(road_model(PatchHeating()), S[:, None], V[None, :], contact=c)
    peak, at = hot.peak(axis=0)
    print(f"\npeak {peak} at slip {at}; locked {hot.mu[-1]}; without heating locked {cold.mu[-1]}")
    # without heating (hysteresis rising with speed on this road) mu(slip) only rises to the locked wheel
    assert np.all(np.diff(cold.mu, axis=0) > -1e-9)
    # with it: a peak at 10-30 % slip, then a fall to the locked wheel (DRFT-like)
    assert np.all((at >= 0.08) & (at <= 0.35))
    assert np.all(hot.mu[-1] < 0.85 * peak)
    # the locked wheel is the limit of the curve (approached like sqrt(1 - s): the tread's share of the heat)
    assert np.allclose(hot.mu[-2], hot.mu[-1], atol=5e-4)
    # heating only lowers the friction here (mu falls with temperature on this compound), most at the locked wheel
    assert np.all(hot.mu <= cold.mu + 1e-3)
    # profiles: T0 in the stick zone, rising behind it (and cooling a little near the trailing edge, where the
    # parabolic pressure and with it the heat flux vanish); the locked wheel heats more at the higher speed
    T = hot.patch.temperature
    j = 20
    stick = hot.patch.x < hot.stick_length[j, 1] - 1e-12
    assert np.allclose(T[j, 1][stick], T0)
    Tl = T[-1, 1]
    assert np.all(Tl >= T0) and 0.5 < hot.patch.x[np.argmax(Tl)] / L < 1.0
    assert np.all(np.diff(Tl[: Tl.size // 2]) > 0)
    assert hot.patch.max_rise[-1, 1] > hot.patch.max_rise[-1, 0] > 5.0
    assert hot.patch.engine_calls == 2 and hot.friction is None
    assert np.allclose(hot.as_table()["max_temperature_rise_K"], hot.patch.max_rise.ravel())
    # mu_local is the engine's friction at (v_s, sigma0, T0)
    direct = road_model().friction(np.array([S[20] * 3.0, 3.0]), temperature=T0, pressure=SIGMA0).mu
    assert np.allclose([hot.mu_local[20, 1], hot.mu_local[-1, 1]], direct, rtol=3e-4)


def test_one_table_per_call_and_reuse_while_only_the_contact_changes():
    mu_T = ClosedForm(lambda v, p, T: (0.8 + 0.1 * np.log10(v)) * (1 - 0.004 * (T - T0)) * (1 + 0.05 * p / SIGMA0))
    h = PatchHeating(rubber_effusivity=E_R)
    c = ps.Contact(L, W, K)
    s = np.geomspace(0.01, 1.0, 40)
    s2, V2 = np.broadcast_arrays(s[:, None], np.array([0.3, 1.0, 3.0])[None, :])
    sol = patch_friction(mu_T, h, c, s2.ravel(), V2.ravel(), T0, SIGMA0)
    # the T0 slice, the heated temperatures up to 1.15 times the rise with the friction held at T0, and one node
    # more where the hottest points lie in the table's top interval (this compound's friction falls so slowly with
    # temperature that the patch nearly reaches that rise)
    assert len(mu_T.calls) == sol.engine_calls == 3
    cache = {}
    named = _Named(mu_T, h)
    ps.predict_slip(named, s2.ravel(), V2.ravel(), contact=c, cache=cache)
    n = len(mu_T.calls)
    ps.predict_slip(named, s2.ravel(), V2.ravel(), contact=c.with_parameters(stiffness=2 * K), cache=cache)
    assert len(mu_T.calls) == n  # a stiffer tread: the same table
    # equal persson Models (new objects, same surface, material and effects) share the table too
    road, tread = surfaces.example_road(), materials.example_tread()
    m1 = persson.Model(road, tread, effects=[PatchHeating()])
    m2 = persson.Model(road, tread, effects=[PatchHeating()])
    cache = {}
    ps.predict_slip(m1, s2.ravel()[:20], V2.ravel()[:20], contact=c, cache=cache)
    tab = cache["value"]
    ps.predict_slip(m2, s2.ravel()[:20], V2.ravel()[:20], contact=c.with_parameters(stiffness=2 * K), cache=cache)
    assert cache["value"] is tab
    # other heating parameters: the same table (its temperature nodes do not depend on them); a hotter patch
    # adds the nodes above the range it had, a cooler one none; the answers are those of a fresh table
    cache = {}
    ps.predict_slip(m2, s2.ravel(), V2.ravel(), contact=c, cache=cache)
    tab = cache["value"]
    calls = tab.calls
    for e_c, more in ((300.0, True), (3000.0, False)):
        other = m2.with_effect(PatchHeating(counter_effusivity=e_c))
        mu = ps.predict_slip(other, s2.ravel(), V2.ravel(), contact=c, cache=cache)
        assert cache["value"] is tab and (tab.calls > calls) == more
        calls = tab.calls
        fresh = ps.predict_slip(other, s2.ravel(), V2.ravel(), contact=c, cache={})
        assert np.allclose(mu, fresh, atol=1e-3)


def test_a_fit_moving_two_engine_parameters_finds_its_earlier_tables_again():
    # a finite-difference Jacobian evaluates the engine at the point (A), moves one engine parameter (B), then moves
    # the heating strength at the point: A's engine again, whose table is still at hand (three kept besides the
    # current one), and gives exactly what it gave; four other engines in a row push A's table out
    from persson.slip.heating import _KEEP_OLDER

    def closed(scale):
        return ClosedForm(lambda v, p, T: scale * (0.8 + 0.1 * np.log10(v)) * (1 - 0.004 * (T - T0)))

    a, others = closed(1.0), [closed(1.0 + 0.01 * k) for k in range(1, _KEEP_OLDER + 2)]
    c = ps.Contact(L, W, K)
    s = np.geomspace(0.01, 1.0, 20)
    rows = dict(slip=s, speed=3.0, temperature=T0, pressure=SIGMA0)
    cool, hot = PatchHeating(rubber_effusivity=E_R), PatchHeating(rubber_effusivity=E_R, counter_effusivity=300.0)
    cache = {}
    first = patch_friction(a, cool, c, tables=cache, **rows)
    patch_friction(others[0], cool, c, tables=cache, **rows)
    n = len(a.calls)
    again = patch_friction(a, cool, c, tables=cache, **rows)
    assert again.engine_calls == 0 and len(a.calls) == n
    np.testing.assert_array_equal(again.mu, first.mu)
    # a hotter patch on A's recalled table: the missing nodes only, and the answer of a fresh table
    hotter = patch_friction(a, hot, c, tables=cache, **rows)
    fresh = patch_friction(a, hot, c, tables={}, **rows)
    assert 0 < hotter.engine_calls < fresh.engine_calls
    np.testing.assert_allclose(hotter.mu, fresh.mu, rtol=1e-9)
    assert np.all(hotter.mu < first.mu)  # heating lowers this friction
    # A's table and every other one kept: none built again; one engine more and A's table is the oldest, gone
    for other in others[:_KEEP_OLDER]:
        patch_friction(other, cool, c, tables=cache, **rows)
    assert len(cache["older"]) == _KEEP_OLDER
    n = len(a.calls)
    assert patch_friction(a, cool, c, tables=cache, **rows).engine_calls == 0 and len(a.calls) == n
    for other in [others[-1]] + others[:_KEEP_OLDER]:  # four other engines in a row, each a new table
        assert patch_friction(other, cool, c, tables=cache, **rows).engine_calls > 0
    assert len(cache["older"]) == _KEEP_OLDER
    assert patch_friction(a, cool, c, tables=cache, **rows).engine_calls > 0

def test_a_kept_table_gives_the_notes_of_the_nodes_a_solution_uses_not_of_its_history():
    """A table that a hotter patch has grown keeps its hot nodes; a cooler solution read from it must carry the
    notes and the convergence of the nodes it interpolates only, as a fresh table would, not those the hot nodes
    brought (a result never depends on which calls came before)."""

    class Noted(ClosedForm):
        def friction(self, speed, temperature=20.0, pressure=0.3e6):
            from types import SimpleNamespace

            r = super().friction(speed, temperature, pressure)
            hot = bool(np.any(np.asarray(temperature, float) > 60.0))
            if hot:
                warnings.warn("rubber above 60 C", persson.AccuracyWarning)
            return SimpleNamespace(mu=r.mu, notes=("rubber above 60 C",) if hot else ("a note of every call",),
                                   converged=not hot)

    model = Noted(lambda v, p, T: 0.9 * (1 - 0.003 * (T - T0)) + 0 * v)
    c = ps.Contact(L, W, K)
    s, V = np.full(6, 0.5), np.geomspace(0.3, 3.0, 6)
    mild = PatchHeating(counter_effusivity=5.0e4, rubber_effusivity=E_R)
    strong = PatchHeating(counter_effusivity=60.0, rubber_effusivity=E_R)
    with warnings.catch_warnings(record=True) as fresh_warned:
        warnings.simplefilter("always")
        fresh = patch_friction(model, mild, c, s, V, T0, SIGMA0, tables={})
    assert fresh.converged and fresh.notes == ("a note of every call",) and not fresh_warned
    cache = {}
    patch_friction(model, mild, c, s, V, T0, SIGMA0, tables=cache)
    with warnings.catch_warnings(record=True) as hot_warned:
        warnings.simplefilter("always")
        hot = patch_friction(model, strong, c, s, V, T0, SIGMA0, tables=cache)
    assert float(np.max(hot.max_rise)) > 60.0 - T0
    assert not hot.converged and "rubber above 60 C" in hot.notes and hot_warned
    with warnings.catch_warnings(record=True) as again_warned:
        warnings.simplefilter("always")
        again = patch_friction(model, mild, c, s, V, T0, SIGMA0, tables=cache)
    assert again.engine_calls == 0                                      # read from the grown table
    np.testing.assert_allclose(again.mu, fresh.mu, rtol=1e-12)
    assert again.converged and again.notes == fresh.notes and not again_warned


def test_a_new_table_for_another_engine_reaches_the_rises_of_the_last_solution_not_the_hottest_ever():
    """In a joint fit of patch heating with an effect that changes the engine's friction (the flash temperature,
    the microtexture), every evaluation needs a new table for the same rows. Its temperature range starts from the
    rises of the last solution (1.15 times), not from the range of the previous table, which only ever grows: after
    one hot evaluation, the cool ones that follow would otherwise fill nodes far above the temperatures they reach.
    A patch hotter than that first guess widens the table, and every answer is that of a fresh table."""

    def law(scale):
        return ClosedForm(lambda v, p, T: scale * (0.8 + 0.1 * np.log10(v)) * np.exp(-0.004 * (T - T0)))

    c = ps.Contact(L, W, K)
    s, V = np.broadcast_arrays(np.geomspace(0.05, 1.0, 10)[:, None], np.array([0.5, 3.0])[None, :])
    s, V = s.ravel(), V.ravel()
    mild = PatchHeating(counter_effusivity=2.0e4, rubber_effusivity=E_R)
    strong = PatchHeating(counter_effusivity=60.0, rubber_effusivity=E_R)
    cache = {}
    first = law(1.0)
    hot = patch_friction(first, strong, c, s, V, T0, SIGMA0, tables=cache)
    tall = patch_friction(first, mild, c, s, V, T0, SIGMA0, tables=cache)  # the same engine: the table is kept
    hot_nodes, n_pressure = int(np.sum(cache["value"].nu)), cache["value"].gnodes.size
    # every point interpolates on a centered stencil, in a table grown by the hot patch as in a fresh one sized
    # for this patch alone: the same answer, whatever the history
    own = patch_friction(first, mild, c, s, V, T0, SIGMA0, tables={})
    assert own.table_points < 0.2 * hot_nodes * n_pressure
    np.testing.assert_allclose(tall.mu, own.mu, rtol=1e-9)
    np.testing.assert_allclose(tall.max_rise, own.max_rise, rtol=1e-9)
    # another engine, a cool patch: a table sized by the cool patch's rises, a small part of the hot range
    cool = patch_friction(law(1.02), mild, c, s, V, T0, SIGMA0, tables=cache)
    assert float(np.max(cool.max_rise)) < 0.05 * float(np.max(hot.max_rise))
    assert int(np.sum(cache["value"].nu)) < 0.2 * hot_nodes
    # another engine, a hot patch: the first guess (the cool range) is widened until it reaches the patch
    hotter = patch_friction(law(1.04), strong, c, s, V, T0, SIGMA0, tables=cache)
    assert hotter.engine_calls >= 3 and hotter.converged
    for kept, scale, heating in ((cool, 1.02, mild), (hotter, 1.04, strong)):
        fresh = patch_friction(law(scale), heating, c, s, V, T0, SIGMA0, tables={})
        np.testing.assert_allclose(kept.mu, fresh.mu, rtol=1e-9)
        np.testing.assert_allclose(kept.max_rise, fresh.max_rise, rtol=1e-9)


@pytest.mark.filterwarnings("ignore::persson.PhysicsWarning")   # the example road's rms slope
def test_a_new_table_whose_solver_problems_are_unchanged_keeps_the_range_just_solved(monkeypatch):
    """An engine that differs only in a term added after the solver (an adhesion the table cannot rescale: friction
    above 3) solves the same problems: its new table starts from the previous table's range, whose nodes
    persson.solver.reuse_solutions returns without solving again. An engine whose solver changed (the flash
    temperature) starts from the rises of the last solution."""
    from persson.effects import Adhesion, FlashTemperature
    from persson.engine import solver
    from persson.slip.heating import solver_key

    road, tread = surfaces.example_road(), materials.example_tread()
    grid = persson.GridSettings(q_per_decade=6, n_phi=12, omega_per_decade=12, tolerance=1e-2)

    def engine(*effects):
        return persson.Model(road, tread, effects=list(effects), grid=grid)

    c = ps.Contact(L, W, K)
    s, V = np.broadcast_arrays(np.geomspace(0.05, 1.0, 6)[:, None], np.array([0.5, 3.0])[None, :])
    s, V = s.ravel(), V.ravel()
    hot, mild = PatchHeating(counter_effusivity=60.0), PatchHeating(counter_effusivity=5000.0)
    sticky, stickier = Adhesion(tau_f0=1.0e6, c=0.0), Adhesion(tau_f0=4.0e7, c=0.0)
    assert solver_key(engine(sticky)) == solver_key(engine(stickier)) != solver_key(engine(sticky, FlashTemperature()))
    solves = []
    real = solver._solve
    monkeypatch.setattr(solver, "_solve", lambda *a: solves.append(1) or real(*a))
    with solver.reuse_solutions(size=64):
        cache = {}
        patch_friction(engine(sticky), hot, c, s, V, T0, SIGMA0, tables=cache)
        patch_friction(engine(sticky), mild, c, s, V, T0, SIGMA0, tables=cache)
        first, n = cache["value"], len(solves)
        loud = patch_friction(engine(stickier), mild, c, s, V, T0, SIGMA0, tables=cache)
        assert cache["value"] is not first and loud.engine_calls == 2
        np.testing.assert_array_equal(cache["value"].nu, first.nu)    # the hot patch's range
        assert len(solves) == n                                        # every node a problem solved before
        flash = patch_friction(engine(sticky, FlashTemperature()), mild, c, s, V, T0, SIGMA0, tables=cache)
        assert flash.engine_calls >= 2 and int(np.sum(cache["value"].nu)) < 0.5 * int(np.sum(first.nu))


@pytest.mark.filterwarnings("ignore::persson.PhysicsWarning")   # the example road's rms slope
def test_a_kept_table_is_not_lent_to_a_model_with_another_area_correction():
    """The area correction changes the engine's friction (the contact area at every scale): a model with another
    correction gets a table of its own, with the answers of a fresh one."""
    from persson.slip.heating import engine_key, solver_key

    road, tread = surfaces.example_road(), materials.example_tread()
    grid = persson.GridSettings(q_per_decade=6, n_phi=12, omega_per_decade=12, tolerance=1e-2)
    plain = persson.Model(road, tread, effects=[PatchHeating()], grid=grid)
    corrected = persson.Model(road, tread, effects=[PatchHeating()], grid=grid, correction="yang-persson")
    assert engine_key(plain) != engine_key(corrected) and solver_key(plain) != solver_key(corrected)
    c = ps.Contact(L, W, K)
    s, V = np.geomspace(0.05, 1.0, 5), np.full(5, 1.0)
    cache = {}
    first = patch_friction(plain, plain.effect("patch_heating"), c, s, V, T0, SIGMA0, tables=cache)
    kept = patch_friction(corrected, corrected.effect("patch_heating"), c, s, V, T0, SIGMA0, tables=cache)
    fresh = patch_friction(corrected, corrected.effect("patch_heating"), c, s, V, T0, SIGMA0)
    assert kept.engine_calls > 0 and np.all(np.abs(kept.mu - first.mu) > 0.05)
    np.testing.assert_allclose(kept.mu, fresh.mu, rtol=1e-9)


@pytest.mark.parametrize("slope, per_decade", [(0.01, 3.0), (0.0005, 3.0), (-0.002, 3.0), (0.0005, 1.0)])
def test_a_solution_does_not_depend_on_how_far_its_table_reaches(slope, per_decade):
    """The friction between temperature nodes comes from a four-point stencil, centered on the point's interval
    where the table has a node below and one above it. A table is widened until every temperature of the patch lies
    below its top interval, so a table sized for one patch gives the answer of one grown far above it by a hotter
    patch before: a result never depends on the calls that came before, at any heating strength."""
    model = ClosedForm(lambda v, p, T: (0.8 + 0.1 * np.log10(v)) * np.exp(-slope * (T - T0)))
    c = ps.Contact(L, W, K)
    s, V = np.broadcast_arrays(np.geomspace(0.05, 1.0, 6)[:, None], np.array([0.5, 3.0])[None, :])
    s, V = s.ravel(), V.ravel()
    cache = {}
    patch_friction(model, PatchHeating(counter_effusivity=50.0, rubber_effusivity=E_R,
                                       temperature_points_per_decade=per_decade), c, s, V, T0, SIGMA0, tables=cache)
    for e_c in np.geomspace(1000.0, 3.0e4, 15):   # rises of 2-150 K, below the table's cap
        heating = PatchHeating(counter_effusivity=e_c, rubber_effusivity=E_R, temperature_points_per_decade=per_decade)
        tall = patch_friction(model, heating, c, s, V, T0, SIGMA0, tables=cache)
        own = patch_friction(model, heating, c, s, V, T0, SIGMA0, tables={})
        assert tall.engine_calls == 0 and own.table_points < cache["value"].points and not own.notes
        np.testing.assert_allclose(own.mu, tall.mu, rtol=1e-10)
        np.testing.assert_allclose(own.max_rise, tall.max_rise, rtol=1e-10)


def test_one_table_serves_every_adhesive_shear_stress():
    """The adhesive term tau_f0 exp(-c x^2) A/A0 / sigma0 is proportional to tau_f0 and nothing else in the engine
    depends on it (the solver never sees adhesion): a table keeps it apart and serves a fit of tau_f0 without
    engine calls, with the answers of a fresh table."""
    from persson.effects import Adhesion, Wet

    c = ps.Contact(L, W, K)
    s, V = np.broadcast_arrays(np.geomspace(0.01, 1.0, 12)[:, None], np.array([0.3, 3.0])[None, :])
    s, V = s.ravel(), V.ravel()
    heat = PatchHeating()
    road, tread = surfaces.example_road(), materials.example_tread()  # a table is kept for these very objects

    def model_of(*effects):
        return persson.Model(road, tread, effects=list(effects))

    for extra in ((), (Wet(),)):  # on a wet road the adhesion is off: the split holds as well
        cache = {}
        model = model_of(heat, Adhesion(tau_f0=1.0e6), *extra)
        first = patch_friction(model, heat, c, s, V, T0, SIGMA0, tables=cache)
        tab = cache["value"]
        for tau in (1.4e6, 0.2e6, 1.0e6):
            other = model_of(heat, Adhesion(tau_f0=tau), *extra)
            kept = patch_friction(other, heat, c, s, V, T0, SIGMA0, tables=cache)
            fresh = patch_friction(other, heat, c, s, V, T0, SIGMA0, tables={})
            assert cache["value"] is tab
            # no engine call unless a hotter patch needs temperature nodes above the table's
            assert kept.engine_calls == 0 or (tau > 1.0e6 and not extra)
            np.testing.assert_allclose(kept.mu, fresh.mu, rtol=1e-9, atol=1e-12)
            np.testing.assert_allclose(kept.mu_local, fresh.mu_local, rtol=1e-12, atol=1e-14)
            assert kept.notes == fresh.notes
            if extra:
                np.testing.assert_allclose(kept.mu, first.mu, rtol=1e-12)
        # the T0 slice is the engine's own friction at each tau_f0 (interpolated between the table's speed nodes)
        direct = model_of(Adhesion(tau_f0=1.0e6), *extra).friction(s * V, temperature=T0, pressure=SIGMA0).mu
        np.testing.assert_allclose(kept.mu_local, direct, rtol=3e-4)
    # friction above 3 carries a note that depends on the level: such a table is not rescaled, and the notes are
    # those of the model asked for
    cache = {}
    patch_friction(model_of(heat, Adhesion(tau_f0=1.0e6, c=0.0)), heat, c, s, V, T0, SIGMA0, tables=cache)
    tab = cache["value"]
    huge = model_of(heat, Adhesion(tau_f0=4.0e7, c=0.0))
    loud = patch_friction(huge, heat, c, s, V, T0, SIGMA0, tables=cache)
    assert cache["value"] is not tab and loud.engine_calls > 0
    assert any("> 3" in n for n in loud.notes)
    back = patch_friction(model_of(heat, Adhesion(tau_f0=1.0e6, c=0.0)), heat, c, s, V, T0, SIGMA0, tables=cache)
    assert back.engine_calls > 0 and not any("> 3" in n for n in back.notes)
    # a model whose results do not carry the adhesive term apart is never split: each tau_f0 fills its own table
    from types import SimpleNamespace

    class Plain:
        def __init__(self, m):
            self.m = m

        def __getattr__(self, name):
            return getattr(self.m, name)

        def replace(self, **kw):
            return Plain(self.m.replace(**kw))

        def without(self, name):
            return Plain(self.m.without(name))

        def friction(self, *a, **k):
            r = self.m.friction(*a, **k)
            return SimpleNamespace(mu=r.mu, notes=r.notes, converged=r.converged)

    cache = {}
    patch_friction(Plain(model_of(heat, Adhesion(tau_f0=1.0e6))), heat, c, s, V, T0, SIGMA0, tables=cache)
    assert not cache["value"].rescalable
    other = Plain(model_of(heat, Adhesion(tau_f0=1.4e6)))
    again = patch_friction(other, heat, c, s, V, T0, SIGMA0, tables=cache)
    assert again.engine_calls > 0
    np.testing.assert_allclose(again.mu, patch_friction(other, heat, c, s, V, T0, SIGMA0).mu, rtol=1e-9)


@pytest.mark.filterwarnings("ignore::persson.PhysicsWarning")   # the example road's rms slope
def test_one_table_serves_every_adhesion_with_the_answers_of_a_fresh_table():
    """The adhesive term is tau_f(v, T_q1) A/A0 / sigma0 with tau_f = tau_f0 exp(-c log10(v a_T(T_q1) / v_ref)^2):
    A/A0 / sigma0 and the rubber temperature T_q1 at q1 (the flash temperature when that effect is on) do not
    depend on the adhesion's parameters. A table that keeps them serves a joint fit of tau_f0, c, v_ref (and
    v_ref_temperature) with patch heating without engine calls, with the answers of a fresh table; on a wet road,
    where the term is off, only tau_f0 is kept apart."""
    from persson.effects import Adhesion, FlashTemperature, Wet

    c = ps.Contact(L, W, K)
    s, V = np.broadcast_arrays(np.geomspace(0.01, 1.0, 8)[:, None], np.array([0.3, 3.0])[None, :])
    s, V = s.ravel(), V.ravel()
    heat = PatchHeating()
    road, tread = surfaces.example_road(), materials.example_tread()
    grid = persson.GridSettings(q_per_decade=8, n_phi=16, omega_per_decade=16, tolerance=1e-2)

    def model_of(*effects):
        return persson.Model(road, tread, effects=list(effects), grid=grid)

    shapes = (dict(tau_f0=1.3e6, c=0.25, v_ref=3e-3), dict(tau_f0=0.7e6, c=0.05, v_ref=0.3),
              dict(tau_f0=1.0e6, c=0.1, v_ref=1e-2, v_ref_temperature=40.0), dict(tau_f0=1.0e6, c=0.1, v_ref=1e-2))
    # the middle (20 C, 0.3 MPa) and the corners: cold and light (the rubber near its glassy side: the flash
    # temperature's T_q1 far above T0) and hot and heavy (rubbery)
    corners = ((T0, SIGMA0), (-20.0, 0.05e6), (70.0, 0.8e6))
    for (t0, p0), extra in itertools.product(corners, ((), (FlashTemperature(),))):
        cache = {}
        patch_friction(model_of(heat, Adhesion(tau_f0=1.0e6, c=0.1, v_ref=1e-2), *extra), heat, c, s, V, t0, p0,
                       tables=cache)
        tab = cache["value"]
        assert tab.separable
        for shape in shapes:
            other = model_of(heat, Adhesion(**shape), *extra)
            kept = patch_friction(other, heat, c, s, V, t0, p0, tables=cache)
            fresh = patch_friction(other, heat, c, s, V, t0, p0, tables={})
            assert cache["value"] is tab
            assert kept.engine_calls == 0 or float(np.max(kept.max_rise)) > float(np.max(fresh.max_rise)) - 1e-9
            # the T0 slice comes from one engine call of the same speeds in both tables: equal to rounding; the
            # heated nodes of a table grown by other patches came in other calls, and the flash temperature's
            # graded nodes depend on the speeds that share a call (about 1e-8 in mu)
            np.testing.assert_allclose(kept.mu_local, fresh.mu_local, rtol=1e-12, atol=1e-14)
            np.testing.assert_allclose(kept.mu, fresh.mu, rtol=1e-7 if extra else 1e-9, atol=1e-12)
            assert kept.notes == fresh.notes
    # wet: the adhesive term is off, its factors cannot be checked; another c or v_ref makes a new table
    cache = {}
    patch_friction(model_of(heat, Adhesion(tau_f0=1.0e6, c=0.1), Wet()), heat, c, s, V, T0, SIGMA0, tables=cache)
    tab = cache["value"]
    assert tab.rescalable and not tab.separable
    again = patch_friction(model_of(heat, Adhesion(tau_f0=1.0e6, c=0.3), Wet()), heat, c, s, V, T0, SIGMA0,
                           tables=cache)
    assert cache["value"] is not tab and again.engine_calls > 0


def test_the_speed_contracted_table_interpolates_as_the_full_lattice():
    """The march sums a row's table over its speed stencil once and interpolates in (p, T) alone where the
    temperature stencil is the same on every speed node: the value of the tensor-product interpolation to rounding,
    and the full interpolation near the top of the shortest table."""
    from persson.slip import heating_kernels as hk
    from persson.slip.heating_arrays import FrictionLattice

    rng = np.random.default_rng(3)
    n_u = np.array([5, 9, 6, 12, 4], dtype=np.int64)
    ng = 3
    sizes = ng * n_u
    offset = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    lattice = FrictionLattice(log_speed=np.log(np.geomspace(0.01, 1.0, n_u.size)),
                              v_offset=np.array([0, n_u.size], dtype=np.int64), g_nodes=np.linspace(0.2, 1.5, ng),
                              values=rng.uniform(0.2, 1.0, int(offset[-1])), value_offset=offset, n_temperature=n_u)
    wv, wg, wu = np.empty(4), np.empty(4), np.empty(4)
    for iv, log_v in ((0, math.log(0.05)), (1, math.log(0.2))):
        wv[:] = [0.1, 0.5, 0.3, 0.1]
        contracted, n_min = hk._speed_contracted(lattice, iv, wv, 4)
        assert n_min == n_u[iv:iv + 4].min()
        for g in (0.2, 0.7, 1.5):
            ig = hk._lagrange(lattice.g_nodes, 0, ng, g, wg)
            for x in np.linspace(-0.5, 13.0, 271):
                full = hk._mu_at(iv, wv, 4, ig, wg, 3, x, lattice.values, offset, n_u, wu)
                row = hk._mu_row(iv, wv, 4, ig, wg, 3, x, lattice.values, offset, n_u, wu, contracted, n_min)
                assert row == pytest.approx(full, rel=1e-13, abs=1e-15)


def test_a_row_on_a_speed_node_reads_that_node_alone():
    """A row whose sliding speed is a node's reads that node alone: its four-point Lagrange weights are exactly one
    there and zero at the other three, so the value is the same to the last bit, and the nodes around it need not
    reach its temperatures (they may hold fewer temperature nodes than it does)."""
    from persson.slip import heating_kernels as hk
    from persson.slip.heating_arrays import FrictionLattice

    rng = np.random.default_rng(5)
    n_u = np.array([14, 14, 14, 14, 14, 14], dtype=np.int64)
    ng = 3
    offset = np.concatenate([[0], np.cumsum(ng * n_u)]).astype(np.int64)
    log_v = np.log(np.geomspace(0.01, 3.0, n_u.size))
    lattice = FrictionLattice(log_speed=log_v, v_offset=np.array([0, n_u.size], dtype=np.int64),
                              g_nodes=np.linspace(0.2, 1.5, ng), values=rng.uniform(0.2, 1.0, int(offset[-1])),
                              value_offset=offset, n_temperature=n_u)
    w1, w4, wg, wu = np.empty(4), np.empty(4), np.empty(4), np.empty(4)
    for k in range(n_u.size):
        iv, mv = hk._speed_stencil(lattice, 0, log_v[k], w1)
        assert (iv, mv, w1[0]) == (k, 1, 1.0)
        i4 = hk._lagrange(lattice.log_speed, 0, n_u.size, log_v[k], w4)   # the four-point stencil around it
        assert w4[k - i4] == 1.0 and np.count_nonzero(w4) == 1
        for g in (0.2, 0.9, 1.5):
            ig = hk._lagrange(lattice.g_nodes, 0, ng, g, wg)
            for x in np.linspace(0.0, 10.5, 43):
                one = hk._mu_at(k, w1, 1, ig, wg, 3, x, lattice.values, offset, n_u, wu)
                four = hk._mu_at(i4, w4, 4, ig, wg, 3, x, lattice.values, offset, n_u, wu)
                assert one == four
    # a speed between nodes still reads the four around it
    assert hk._speed_stencil(lattice, 0, 0.5 * (log_v[2] + log_v[3]), w1) == (1, 4)


def test_the_root_search_at_a_patch_point_meets_its_tolerance_whatever_slope_it_is_handed():
    """T = base + coef mu(T) at a patch point, mu(T) interpolated in the table: the secant's second point is a Newton
    step with the slope of mu(T) handed on from the point before. Whatever that slope (the right one, none, a wrong
    one, one that would make the step diverge), the search ends on the root to its tolerance |F| <= 1e-10 (1 + |T|),
    the same root to that tolerance, and hands on the slope of mu there."""
    from persson.slip import heating_kernels as hk
    from persson.slip.heating_arrays import FrictionLattice

    n_u, ng, h, dT_fine, cap = 40, 2, 1.0 / 3.0, 0.25, 250.0
    dT = dT_fine * np.arange(2 * 1001 - 1)
    y_fine = (dT / 40.0)[None, :]                       # y = (T - T0) / 40 K: 7.5 nodes per 100 K
    T_nodes = 40.0 * h * np.arange(n_u)
    mu_T = 0.9 * np.exp(-T_nodes / 120.0) + 0.1        # friction falling with temperature
    values = np.concatenate([mu_T * f for f in (1.0, 0.8)])
    lattice = FrictionLattice(log_speed=np.zeros(1), v_offset=np.array([0, 1], dtype=np.int64),
                              g_nodes=np.array([0.5, 1.5]), values=values,
                              value_offset=np.array([0, ng * n_u], dtype=np.int64),
                              n_temperature=np.array([n_u], dtype=np.int64))
    wv, wg, wu = np.array([1.0, 0, 0, 0]), np.array([0.75, 0.25, 0, 0]), np.empty(4)
    contracted, n_min = hk._speed_contracted(lattice, 0, wv, 1)
    T0 = 20.0

    def mu(T):
        x = hk._x_at(y_fine, 0, T - T0, cap, dT_fine, h)
        return hk._mu_row(0, wv, 1, 0, wg, 2, x, values, lattice.value_offset, lattice.n_temperature, wu,
                          contracted, n_min)

    for base, coef in ((25.0, 30.0), (60.0, 150.0), (20.5, 2.0)):
        roots = []
        for slope in (np.nan, (mu(base + 1e-3) - mu(base)) / 1e-3, 0.0, -0.5, 10.0):
            T, m, s_out = hk._node_temperature(base, coef, base + 3.0, slope, T0, 1.0, 0, 0, wv, 1, 0, wg, 2,
                                               values, lattice.value_offset, lattice.n_temperature, y_fine, cap,
                                               dT_fine, h, wu, contracted, n_min)
            assert abs(T - base - coef * mu(T)) <= 1e-10 * (1.0 + abs(T))
            assert m == mu(T)
            assert s_out == pytest.approx((mu(T + 1e-4) - mu(T - 1e-4)) / 2e-4, rel=1e-2, abs=1e-7)
            roots.append(T)
        assert np.ptp(roots) <= 1e-9 * (1.0 + abs(roots[0]))


@pytest.mark.parametrize("T_bg, sigma0, V, trimmed", [
    (T0, SIGMA0, (0.01, 0.1, 1.0, 3.0), True),          # the middle
    (-20.0, 0.05e6, (0.03, 0.3, 3.0, 10.0), True),      # glassy: cold, fast, low pressure
    (80.0, 0.6e6, (1e-3, 0.01, 0.1, 0.5), False),       # soft: hot, slow (a_T barely moves: 4 nodes everywhere)
])
def test_a_locked_wheel_at_a_few_speeds_matches_a_direct_iteration_with_a_table_sized_per_speed(T_bg, sigma0, V,
                                                                                                trimmed):
    """Locked-wheel rows at four speeds: the table's speed nodes are the rows' speeds, each row reads its own node,
    and each node reaches the temperatures of its own row only (a slow wheel's patch barely warms; the fast one's
    by tens of kelvin): the friction and the temperature along the patch are those of the direct iteration, in the
    middle of the regime and at its glassy and soft corners."""
    model = road_model(PatchHeating())
    c = ps.Contact(L, W, K, "parabolic", n_points=101)
    V = np.array(V)
    cache = {}
    sol = patch_friction(model, model.effect("patch_heating"), c, 1.0, V, T_bg, sigma0, profiles=True,
                         tables=cache)
    nodes = cache["value"].nus[0]
    rises = sol.max_rise
    print(f"\nrises {np.round(rises, 2)} K; temperature nodes per speed node {nodes}")
    assert rises[0] < 0.1 * rises[-1]
    assert (nodes[0] < nodes[-1]) == trimmed   # before: every node as tall as the fastest
    for k, v in enumerate(V):
        ref, T_ref = picard_reference(model.without("patch_heating"), 1.0, v, c, model.effect("patch_heating"),
                                      temperature=T_bg, sigma0=sigma0)
        assert sol.mu[k] == pytest.approx(ref, abs=1e-3)
        assert np.max(np.abs(sol.temperature[k] - T_ref)) < 0.05 * max(np.max(T_ref) - T_bg, 0.01)


def test_a_kept_table_grown_for_rows_on_its_nodes_serves_rows_between_them():
    """A table is kept by its speed nodes; rows on the nodes need each node's own range only. Rows between the same
    nodes (many speeds, whose log-spaced nodes are exactly the first rows' speeds) get the neighbours' ranges added
    to the kept table: the answers of a fresh table."""
    from persson.slip.heating_tables import _speed_nodes

    model = road_model(PatchHeating())
    heating = model.effect("patch_heating")
    c = ps.Contact(L, W, K, "parabolic", n_points=101)
    many = np.geomspace(0.01, 3.0, 40)
    nodes = _speed_nodes(many, heating.points_per_decade)
    assert nodes.size < many.size
    cache = {}
    on = patch_friction(model, heating, c, 1.0, nodes, T0, SIGMA0, tables=cache)
    kept = cache["value"]
    assert kept.on_nodes.all() and on.converged
    between = patch_friction(model, heating, c, 1.0, many, T0, SIGMA0, tables=cache)
    assert cache["value"] is kept and not kept.on_nodes.any() and between.engine_calls > 0
    fresh = patch_friction(model, heating, c, 1.0, many, T0, SIGMA0)
    np.testing.assert_allclose(between.mu, fresh.mu, rtol=1e-10)
    np.testing.assert_allclose(between.max_rise, fresh.max_rise, rtol=1e-10)
    assert between.converged and fresh.converged


@dataclass
class _Named:
    """A ClosedForm carrying a PatchHeating effect, as a persson.Model does."""

    base: ClosedForm
    heating: PatchHeating

    @property
    def effect_names(self):
        return ("patch_heating",)

    @property
    def material(self):
        return None

    def effect(self, name):
        return self.heating

    def without(self, name):
        return self.base

    def friction(self, *a, **k):
        return self.base.friction(*a, **k)


def test_validation_predicts_every_row_through_the_patch():
    c = ps.Contact(L, W, K)
    model = road_model(PatchHeating(counter_effusivity=2000.0))
    slip = np.array([0.05, 0.2, 1.0, 1.0, 0.1])
    speed = np.array([1.0, 1.0, 1.0, 0.3, 2.0])
    T = np.array([20.0, 20.0, 20.0, 30.0, 30.0])
    m = validation.Measurements.from_arrays(slip=slip, speed=speed, temperature=T, pressure=SIGMA0, mu=0.5,
                                            contact=c)
    pred = validation.predict(model, m)
    for i in range(slip.size):
        one = ps.mu_slip(model, slip[i], speed[i], temperature=T[i], pressure=SIGMA0, contact=c)
        assert pred.mu[i] == pytest.approx(one.mu, abs=2e-4)  # tables built for other rows interpolate alike
    # sliding rows: the locked wheel's heated patch, below the engine's friction at T0
    plain = model.without("patch_heating").friction(speed[2:4], temperature=T[2:4], pressure=SIGMA0).mu
    assert np.all(pred.mu[2:4] < plain)
    assert np.allclose(pred.mu_local[2:4], plain, rtol=5e-4)
    sliding_only = validation.Measurements.from_arrays(slip=1.0, speed=[1.0, 2.0], temperature=20.0,
                                                       pressure=SIGMA0, mu=0.5)
    with pytest.raises(validation.errors.InputError, match="contact"):
        validation.predict(model, sliding_only)


def test_the_effect_is_registered_and_leaves_the_engine_alone():
    assert "patch_heating" in persson.effects.available()
    h = persson.effects.get("patch_heating", counter_effusivity=2500.0)
    assert isinstance(h, PatchHeating) and h.counter_effusivity == 2500.0
    names = {p.name: p for p in PatchHeating.parameters}
    assert names["counter_effusivity"].log_scale and names["counter_effusivity"].unit.startswith("W")
    assert names["heat_fraction"].bounds == (0.0, 1.0)
    v = np.array([0.01, 1.0])
    a = road_model().friction(v)
    b = road_model(h).friction(v)
    assert np.array_equal(a.mu, b.mu)
    assert any("patch_heating acts on the contact patch" in n for n in b.notes)
    assert "isbn:9780198533689" in b.citations


def test_a_patch_hotter_than_the_table_says_so():
    c = ps.Contact(L, W, K)
    r = ps.mu_slip(road_model(PatchHeating(max_rise=3.0)), [0.5, 1.0], 3.0, contact=c)
    assert any("above the table" in n for n in r.notes)


@pytest.mark.parametrize("kwargs, match", [
    (dict(counter_effusivity=-1.0), "counter_effusivity"), (dict(heat_fraction=1.5), "heat_fraction"),
    (dict(max_rise=0.0), "max_rise"), (dict(n_pressure=1), "n_pressure"),
    (dict(points_per_decade=float("nan")), "points_per_decade"), (dict(rubber_effusivity=-5.0), "rubber_effusivity"),
])
def test_bad_parameters(kwargs, match):
    with pytest.raises(InputError, match=match):
        PatchHeating(**kwargs)


def test_bad_input_to_the_patch():
    c = ps.Contact(L, W, K)
    cf = ClosedForm(lambda v, p, T: 0.8 + 0 * v)
    with pytest.raises(InputError, match="rubber_effusivity"):
        patch_friction(cf, PatchHeating(), c, 0.1, 1.0, T0, SIGMA0)  # no material.thermal
    h = PatchHeating(rubber_effusivity=E_R)
    with pytest.raises(InputError, match="slip"):
        patch_friction(cf, h, c, 0.0, 1.0, T0, SIGMA0)
    with pytest.raises(InputError, match="speed"):
        patch_friction(cf, h, c, 0.1, -1.0, T0, SIGMA0)
    with pytest.raises(InputError, match="contact"):
        patch_friction(cf, h, "parabolic", 0.1, 1.0, T0, SIGMA0)
    with pytest.raises(InputError, match="heating"):
        patch_friction(cf, object(), c, 0.1, 1.0, T0, SIGMA0)
    bad = ClosedForm(lambda v, p, T: np.where(T > T0 + 1, np.nan, 0.8))
    with pytest.raises(InputError, match="local sliding friction"):
        patch_friction(bad, h, c, 1.0, 3.0, T0, SIGMA0)
