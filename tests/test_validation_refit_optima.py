"""A fit with two nearly equal optima says so: local standard errors describe the best optimum only.

The toy problem has a closed form: mu_i(u) = a (u - 0.2)(u - 0.8) x_i fitted to y_i = 0, so
chi2(u) = a^2 (u - 0.2)^2 (u - 0.8)^2 sum x_i^2 + offset; the offsets of two local optima are set by hand.
"""

import numpy as np
import pytest

from validation.fitting import FreeParameter, ParameterSpace
from validation.refit import GlobalFit, with_uncertainty


class _Toy:
    """The attributes of validation.fitting.Fitter that with_uncertainty uses, for a linear-in-x model."""

    def __init__(self):
        self.space = ParameterSpace([FreeParameter("toy", "k", 0.0, 1.0, log=False)])
        self.x = np.linspace(1.0, 2.0, 20)
        self.y = np.zeros_like(self.x)
        self.w = np.ones_like(self.x)
        self.n_evals = 0
        self.max_evals = 10**6

    def mu(self, u):
        self.n_evals += 1
        u = float(np.atleast_1d(u)[0])
        return 5.0 * (u - 0.2) * (u - 0.8) * self.x

    def chi2(self, u):
        return float(np.sum((self.mu(u) - self.y) ** 2))

    def jacobian(self, u):
        u = float(np.atleast_1d(u)[0])
        return (5.0 * (2 * u - 1.0) * self.x)[:, None]


def _fit(toy, d_other):
    u = np.array([0.2])
    return GlobalFit(u=u, chi2=10.0, mu=toy.mu(u), model=None, contact=None, estimates=(),
                     jacobian=np.zeros((toy.y.size, 0)), n_starts=2, n_good=0, n_evals=0,
                     optima=((10.0, u), (10.0 + d_other, np.array([0.8]))))


def test_a_second_optimum_inside_the_95_percent_range_is_named():
    toy = _Toy()
    out = with_uncertainty(toy, _fit(toy, 2.5), s2=1.0, profile=False)
    notes = [n for n in out.notes if "another local optimum" in n]
    assert len(notes) == 1 and "toy.k = 0.8" in notes[0] and "delta chi2 = 2.50" in notes[0]


def test_a_far_worse_or_an_equal_optimum_is_not_called_almost_as_good():
    toy = _Toy()
    far = with_uncertainty(toy, _fit(toy, 9.0), s2=1.0, profile=False)
    assert not any("another local optimum" in n for n in far.notes)
    # within one chi2 unit the second optimum widens the interval instead (method "+ starts")
    equal = with_uncertainty(toy, _fit(toy, 0.5), s2=1.0, profile=False)
    assert not any("another local optimum" in n for n in equal.notes)
    est = equal.estimates[0]
    assert est.interval[0] <= 0.2 and est.interval[1] >= 0.8 and "starts" in est.method


def test_a_joint_fit_starts_with_parameters_a_member_fit_pushed_away_in_the_middle_of_their_plausible_range():
    """The members of a set fitted alone may push a parameter onto a search bound or out of its plausible range to
    stand in for the partner they lack; the joint fit's extra start puts each such parameter at the middle of its
    plausible range (geometric for a log parameter) and leaves the others, a physical limit included, alone."""
    from validation.refit import plausible_start

    space = ParameterSpace([
        FreeParameter("adhesion", "v_ref", 1e-12, 1e6, log=True, plausible=(1e-6, 1e2)),   # on the upper bound
        FreeParameter("adhesion", "tau_f0", 0.0, 5e7, log=False, physical_limits=(0.0,),
                      plausible=(0.0, 2e7)),                                               # on its physical limit
        FreeParameter("micro", "hurst", 0.5, 1.0, log=False, plausible=(0.5, 1.0)),        # on the lower bound
        FreeParameter("soft", "f", 0.05, 1.0, log=False, plausible=(0.1, 1.0)),            # outside plausible
        FreeParameter("soft", "g", 0.05, 1.5, log=False, plausible=(0.1, 1.5)),            # fine
    ])
    u = np.array([1.0, 0.0, 0.0, space.params[3].to_u(0.07), space.params[4].to_u(0.8)])
    out = plausible_start(space, u)
    vals = space.values_from_u(out)
    assert vals["adhesion.v_ref"] == pytest.approx(1e-2, rel=1e-9)          # sqrt(1e-6 * 1e2)
    assert vals["adhesion.tau_f0"] == 0.0
    assert vals["micro.hurst"] == pytest.approx(0.75)
    assert vals["soft.f"] == pytest.approx(0.55)
    assert out[4] == u[4]
    # nothing to move: no extra start
    assert plausible_start(space, np.array([0.5, 0.0, 0.5, 0.5, 0.5])) is None
    # a plausible range given as a function of the data is evaluated on it
    ranged = ParameterSpace([FreeParameter("a", "v", 1e-12, 1e6, log=True, plausible=lambda r: (r, 1e2 * r))])
    assert ranged.params[0].from_u(plausible_start(ranged, np.array([1.0]), 1e-3)[0]) == pytest.approx(1e-2)
    # with limits, a physical limit moves too (to 1e7, the middle of 0 - 2e7); dims restricts the coordinates moved
    vals = space.values_from_u(plausible_start(space, u, limits=True))
    assert vals["adhesion.tau_f0"] == pytest.approx(1e7) and vals["adhesion.v_ref"] == pytest.approx(1e-2, rel=1e-9)
    only = plausible_start(space, u, dims=[1, 3], limits=True)
    assert np.array_equal(only[[0, 2, 4]], u[[0, 2, 4]])
    assert space.values_from_u(only)["adhesion.tau_f0"] == pytest.approx(1e7)
    assert space.values_from_u(only)["soft.f"] == pytest.approx(0.55)
    assert plausible_start(space, u, dims=[4], limits=True) is None


def test_a_second_optimum_inside_the_95_percent_range_is_inside_the_95_percent_interval():
    """The profile at the second optimum's value is at most its chi^2 (the other parameters refitted can only do
    better), 2.5 above the best: inside the 95 % level 3.84, so the 95 % interval reaches it, while the local
    interval around the best optimum alone stops short of it. One 9 units worse is outside the 95 % level and
    leaves the interval as it was."""
    toy = _Toy()
    near = with_uncertainty(toy, _fit(toy, 2.5), s2=1.0, profile=False).estimates[0]
    far = with_uncertainty(_Toy(), _fit(_Toy(), 9.0), s2=1.0, profile=False).estimates[0]
    assert far.interval95[1] < 0.8 and far.interval == near.interval
    assert near.interval95[0] == far.interval95[0] and near.interval95[1] == pytest.approx(0.8)


class _TwoBasins:
    """The attributes of validation.fitting.Fitter that global_fit uses, on chi2(u) = min(1 + 10 |u - A|^2,
    10 |u - B|^2) in the unit square: a local fit ends at the centre of the basin it starts in."""

    A, B = np.array([0.2, 0.2]), np.array([0.8, 0.7])

    def __init__(self):
        self.space = ParameterSpace([FreeParameter("toy", "a", 0.0, 1.0, log=False),
                                     FreeParameter("toy", "b", 0.0, 1.0, log=False)])
        self.y = np.zeros(3)
        self.n_evals = 0
        self.best = (np.inf, None)
        self.errors = {}
        self.local_starts = []

    def _terms(self, u):
        u = np.asarray(u, dtype=float)
        return 1.0 + 10.0 * float(np.sum((u - self.A) ** 2)), 10.0 * float(np.sum((u - self.B) ** 2))

    def chi2(self, u):
        self.n_evals += 1
        c = min(self._terms(u))
        if c < self.best[0]:
            self.best = (c, np.asarray(u, dtype=float).copy())
        return c

    def screen(self, points):
        return sorted(((self.chi2(p), np.asarray(p, dtype=float)) for p in points), key=lambda t: t[0])

    def local(self, u0, known=()):
        self.local_starts.append(np.asarray(u0, dtype=float).copy())
        a, b = self._terms(u0)
        u = self.A if a <= b else self.B
        return u.copy(), self.chi2(u)

    def mu(self, u):
        return np.zeros(3)

    def notes_at(self, u):
        return ()

    def model_at(self, u):
        return None

    def contact_at(self, u):
        return None


def test_a_start_next_to_an_earlier_one_gives_its_local_fit_to_a_distinct_design_point():
    """Two starts within DISTINCT of each other (every coordinate) lead into the same basin: the later one is not
    fitted again, and the search runs as many local fits as before (the given values, the distinct extra start and
    the best distinct design points, n_local + extra starts in all), none of them from next to another."""
    from validation.refit import DISTINCT, global_fit

    toy = _TwoBasins()
    given, twin, other = np.array([0.2, 0.2]), np.array([0.25, 0.16]), np.array([0.2, 0.9])
    fit = global_fit(toy, given, n_local=3, extra_starts=[twin, other])
    starts = toy.local_starts
    assert len(starts) == 3 + 2 and fit.n_starts == 5
    assert np.array_equal(starts[0], given) and any(np.array_equal(s, other) for s in starts)
    assert not any(np.max(np.abs(s - twin)) < 1e-12 for s in starts)
    assert all(np.max(np.abs(p - q)) > DISTINCT for i, p in enumerate(starts) for q in starts[:i])
    # the design reaches the better basin: the fit is its centre, chi2 0
    assert np.allclose(fit.u, toy.B) and fit.chi2 == 0.0
