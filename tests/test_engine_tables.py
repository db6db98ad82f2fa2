"""Tables the engine reuses between calls, and the sums of the heated-patch march, specified by what they must equal:
a reused table is the table computed afresh, a scaled table the table of the scaled modulus, and the Abel sums of the
march integrate linear shear exactly.
"""

import math
import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.engine import tabulate
from persson.slip import heating_kernels as hk
from persson.slip.heating_tables import _unit_weights

FIELDS = ("ln_are", "ln_aim", "ln_l")


class SameModulus(materials.StrainSoftened):
    """The modulus f E' + i g E'' of ``material``, without the hook that lets the tables recognise it as a scaling
    (so they are computed from the modulus itself)."""

    scaled_modulus = None


def test_a_strain_softened_material_gets_the_angular_table_of_its_scaled_modulus():
    """A_re, A_im and L of f E' + i g E'' are f^2, g^2 and g times those of E: the scaled table of the wrapped
    material equals the table computed from the softened modulus itself."""
    m = materials.example_tread()
    for f, g in ((0.6, 0.8), (0.1, 1.5), (1.0, 1.0)):
        scaled = tabulate.angular_table(materials.StrainSoftened(m, f, g), 10.0, -2.0, 9.0, 40)
        direct = tabulate.angular_table(SameModulus(m, f, g), 10.0, -2.0, 9.0, 40)
        assert scaled.lw0 == direct.lw0 and scaled.ln_are.size == direct.ln_are.size
        for name in FIELDS:
            np.testing.assert_allclose(getattr(scaled, name), getattr(direct, name), rtol=0, atol=1e-12)


def test_a_reused_table_is_the_table_computed_afresh_and_only_exact_repeats_are_reused():
    m = materials.example_tread()
    first = tabulate.angular_table(m, 20.0, 1.0, 8.0, 40)
    assert tabulate.angular_table(m, 20.0, 1.0, 8.0, 40) is first
    other = tabulate.angular_table(m, 20.0, 1.0, 8.5, 40)             # another range: its own table
    # accurate from the common bottom's pad up (every table reaches down to ANGULAR_LOW) to the top asked for
    assert other is not first and other.lw_valid == (tabulate.ANGULAR_LOW + tabulate.ANGULAR_PAD_DECADES, 8.5)
    fresh = tabulate.angular_table(SameModulus(m), 20.0, 1.0, 8.0, 40)
    for name in FIELDS:
        np.testing.assert_array_equal(getattr(first, name), getattr(fresh, name))


def test_tops_in_the_same_half_decade_share_one_table_whose_values_do_not_depend_on_its_top():
    """The calls of a fit reach top frequencies that move with its parameters: a table's top is rounded up to the
    next half decade, so that 7.6 and 7.8 (log10 rad/s) share one table, which holds both ranges. The angular
    integrals at a frequency see the modulus at that frequency and below it, so a table reaching three decades
    higher has the same values at every node in the range asked for."""
    m = materials.example_tread()
    first = tabulate.angular_table(m, 20.0, 1.0, 7.8, 40)
    assert tabulate.angular_table(m, 20.0, 1.0, 7.6, 40) is first
    assert first.lw_valid[0] <= 1.0 and first.lw_valid[1] >= 7.8
    assert tabulate.angular_table(m, 20.0, 1.0, 8.1, 40) is not first
    wide = tabulate.angular_table(SameModulus(m), 20.0, 1.0, 10.7, 40)
    assert wide.lw0 == first.lw0
    n = int(round((7.8 - first.lw0) / first.dlw)) + 1                  # the nodes up to the top asked for
    for name in FIELDS:
        np.testing.assert_allclose(getattr(first, name)[:n], getattr(wide, name)[:n], rtol=1e-14, atol=0)


def test_friction_does_not_depend_on_what_was_computed_before():
    """The same friction, bit for bit, from a material seen before (tables reused) and from a fresh object."""
    surface = surfaces.SelfAffine(hurst=0.8, q0=2e3, q1=1e6, hrms=1e-4)
    m = materials.example_tread()
    grid = persson.GridSettings(q_per_decade=12, n_phi=16, omega_per_decade=20)
    v = np.geomspace(1e-4, 1.0, 7)
    for effects in ([], [persson.effects.StrainSoftening(storage_factor=0.6, loss_factor=0.9)]):
        persson.Model(surface, m, effects=effects, grid=grid).friction(v[::-1], temperature=30.0)
        again = persson.Model(surface, m, effects=effects, grid=grid).friction(v, temperature=30.0)
        fresh = persson.Model(surface, SameModulus(m), effects=effects, grid=grid).friction(v, temperature=30.0)
        np.testing.assert_array_equal(again.mu, fresh.mu)
        np.testing.assert_array_equal(again.contact_area, fresh.contact_area)


@pytest.mark.parametrize("edge", [False, True])
def test_the_abel_sums_of_the_march_integrate_linear_shear_exactly(edge):
    r"""Product integration with linear shear between points is exact for tau = a + b y:
    :math:`\int_0^Y (a + b y)/\sqrt{Y - y}\,dy = 2a\sqrt Y + \tfrac43 b Y^{3/2}`; with the stick edge between nodes
    (a shorter first segment) as without."""
    N, h = 161, 1.0 / 160
    abel = _unit_weights(N)
    weights = hk._combined_abel_weights(abel)
    y = h * np.arange(N + 1)
    if edge:
        y = np.concatenate([[0.3 * h], y[1:]])       # point 0 at the stick edge, 0.7 h before node 1
    a, b = 0.8, -0.35
    shear = a + b * (y - y[0])
    for k in range(1, N):
        known, own = hk._abel_known_part(k, y, shear, abel, weights, math.sqrt(h), edge, y[1] - y[0])
        Y = y[k] - y[0]
        exact = 2 * a * math.sqrt(Y) + 4.0 / 3.0 * b * Y ** 1.5
        assert known + own * shear[k] == pytest.approx(exact, rel=1e-12, abs=1e-14)


@pytest.mark.parametrize("n", [1, 2, 3, 4, 7])
def test_the_lattice_weights_reproduce_polynomials_up_to_their_degree(n):
    """The weights at x on n uniform nodes (the four nearest, fewer on a shorter table) reproduce every polynomial
    of degree below the stencil's size exactly, across the table and clamped at its ends: the cubic of a four-point
    stencil, the constant of a one-point one."""
    w = np.empty(4)
    m = min(n, 4)
    for x in np.linspace(-0.5, n - 0.5, 23):
        k0 = hk._lagrange_uniform(n, x, w)
        xc = min(max(x, 0.0), n - 1.0)
        nodes = k0 + np.arange(m)
        assert 0 <= k0 and k0 + m <= n
        for degree in range(m):
            assert np.dot(w[:m], nodes ** degree) == pytest.approx(xc ** degree, rel=1e-13, abs=1e-13)


@pytest.mark.parametrize("n_temperature, mg", [((1, 2, 3, 5), 4), ((6, 4, 7, 9), 3), ((4, 4, 4, 4), 1)])
def test_the_stick_limit_is_the_lattice_interpolation_at_T0_to_the_last_bit(n_temperature, mg):
    """At T0 (lattice coordinate 0) the temperature weights are exactly (1, 0, 0, 0): the stick limit read off the
    T0 slice is the full interpolation there, bit for bit, for short temperature tables (1-3 nodes) as for long
    ones and for any pressure stencil."""
    rng = np.random.default_rng(7)
    n_g = 6
    n_temperature = np.array(n_temperature, dtype=np.int64)
    value_offset = np.concatenate([[0], np.cumsum(n_g * n_temperature)]).astype(np.int64)
    values = rng.uniform(0.2, 1.5, value_offset[-1])
    for trial in range(20):
        wv = rng.normal(0.25, 0.4, 4)
        wg = rng.normal(0.25, 0.4, 4)
        ig = int(rng.integers(0, n_g - mg + 1))
        fast = hk._mu_T0(0, wv, 4, ig, wg, mg, values, value_offset, n_temperature)
        full = hk._mu_at(0, wv, 4, ig, wg, mg, 0.0, values, value_offset, n_temperature, np.empty(4))
        assert fast == full


def test_a_temperature_table_halved_in_step_is_exact_for_a_quadratic():
    """The tables' feedback term solves again with every temperature table at half its step; the new midpoints lie
    on the quadratic through the neighbouring nodes, so a quadratic table (and a linear one) is halved exactly."""
    from persson.engine.solver import _halved

    T = np.linspace(-20.0, 60.0, 33)
    Th = np.linspace(-20.0, 60.0, 65)
    for f in (lambda x: 0.3 - 0.02 * x + 4e-4 * x**2, lambda x: 1.5 * x - 2.0):
        np.testing.assert_allclose(_halved(f(T)), f(Th), rtol=0, atol=1e-12)
    rows = np.vstack([T**2, -T])                                           # per-node rows: along the last axis
    np.testing.assert_allclose(_halved(rows), np.vstack([Th**2, -Th]), rtol=0, atol=1e-10)
    np.testing.assert_array_equal(_halved(np.array([1.0, 3.0])), [1.0, 2.0, 3.0])


@pytest.mark.parametrize("surface", [
    surfaces.PSD(np.geomspace(1e3, 1e6, 9), 1e-20 * np.geomspace(1e3, 1e6, 9) ** -3.2
                 * np.array([1.0, 1.3, 0.7, 1.0, 2.0, 0.5, 1.0, 1.1, 0.9])),
    surfaces.SelfAffine(hurst=0.8, q0=1e3, q1=1e6, hrms=1e-4)])
def test_the_quadrature_rule_integrates_the_psd_exactly_between_its_breakpoints(surface):
    """The rule's weights are the integrals of each interval's quadratic Lagrange basis times q^4 C in ln q: on
    nodes that do not fall on the breakpoints of a tabulated PSD (a power law between its rows), a quadratic
    K(ln q) weighted by them gives int c K d ln q to the accuracy of an adaptive quadrature between the
    breakpoints, and the partial weights reach the whole interval at the end of its last piece."""
    from scipy.integrate import quad

    from persson.engine.quadrature import psd_breakpoints, quadrature_rule

    q0, q1 = surface.q_range
    x = np.sort(np.concatenate([np.linspace(np.log(q0), np.log(q1), 12), [np.log(q0) + 0.013]]))
    rule = quadrature_rule(surface, x)

    def c(t):
        q = math.exp(t)
        return q ** 4 * float(np.asarray(surface.C(np.array([q])))[0])

    br = np.log(psd_breakpoints(surface))
    for i in range(x.size - 1):
        a = rule.stencil[i]
        coeffs = np.polyfit(x[a:a + 3], [1.0, -2.0, 0.5], 2)       # a quadratic K through the stencil nodes
        cuts = np.unique(np.concatenate([[x[i], x[i + 1]], br[(br > x[i]) & (br < x[i + 1])]]))
        exact = sum(quad(lambda t: c(t) * np.polyval(coeffs, t), lo, hi, epsabs=0, epsrel=1e-12)[0]
                    for lo, hi in zip(cuts[:-1], cuts[1:]))
        assert rule.W[i] @ [1.0, -2.0, 0.5] == pytest.approx(exact, rel=1e-9)
        last = rule.piece_start[i + 1] - 1
        assert np.allclose(rule.partial[last, 2], rule.W[i], rtol=1e-13, atol=0)
        assert np.all(rule.partial[rule.piece_start[i], 0] == 0.0)
    assert np.allclose(rule.basis.sum(axis=2), 1.0, rtol=0, atol=1e-12)


@pytest.mark.parametrize("power", [0, 1])
@pytest.mark.parametrize("n", [1, 7, 200, tabulate._max_weights(32)])
def test_the_angular_convolution_weights_reproduce_the_angular_integrals_of_a_power_law(power, n):
    """With cos(phi) = 10^-t the angular integral of F(omega cos phi) is a convolution in log10 omega: for
    F = omega^s it is omega^s 4 int_0^(pi/2) cos^(s+p) phi dphi = omega^s 2 sqrt(pi) Gamma((s+p+1)/2) / Gamma((s+p)/2
    + 1). The weights, for any number of cells (the tail beyond them in closed form, on the clamped end value), give
    it to the cubic interpolation of F between the table's nodes (20 decades of cells, the tail 1e-20 of the
    whole); for s = 0 (F = 1) exactly."""
    per_decade = 32
    c = tabulate.convolution_weights(per_decade, n, power)
    exact = lambda s: 2.0 * math.sqrt(math.pi) * math.gamma((s + power + 1) / 2) / math.gamma((s + power) / 2 + 1)  # noqa: E731
    assert c.sum() == pytest.approx(exact(0.0), rel=1e-12)
    if n == tabulate._max_weights(32):
        s = 0.4
        d = np.arange(-1, n + 2)                   # c[d + 1] weighs F at ell - d Delta (ell = 0 here)
        assert c @ 10.0 ** (-s * d / per_decade) == pytest.approx(exact(s), rel=1e-7)  # 1e-8 off: F is not cubic
