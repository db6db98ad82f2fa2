"""A temperature effect describes its settings; the solver runs the self-consistent flash temperature itself."""

import math
from dataclasses import dataclass

import numpy as np
import pytest

import materials
import persson
import surfaces
from persson.effects import Effect, FlashTemperature, TemperatureSolverOptions

TREAD = materials.example_tread()
ROAD = surfaces.SelfAffine(hurst=0.8, q0=2e3, q1=1e5, rms_slope=0.5, qL=5e2)
GRID = persson.GridSettings(q_per_decade=8)
SPEEDS = np.array([0.3, 3.0])


@dataclass(frozen=True)
class SmallHotSpots(Effect):
    """A user's flash temperature: q_m at 8 x the roll-off, contact spots of a fixed diameter."""

    name = "small_hot_spots"
    solver_role = "temperature"
    diameter: float = 1e-4

    def temperature_solver_options(self, *, surface, material, q):
        th = material.thermal
        return TemperatureSolverOptions(q_m=8.0 * surface.q0, contact_diameter=self.diameter,
                                        diffusivity=th.diffusivity, heat_capacity=th.heat_capacity)


def test_flash_temperature_gives_its_settings_from_the_roll_off_and_the_thermal_properties():
    q = GRID.q_nodes(*ROAD.q_range)
    opt = FlashTemperature(macro_scale_ratio=4.0).temperature_solver_options(surface=ROAD, material=TREAD, q=q)
    assert opt.q_m == pytest.approx(4.0 * ROAD.q0) and opt.contact_diameter == pytest.approx(math.pi / opt.q_m)
    th = TREAD.thermal
    assert opt.diffusivity == pytest.approx(th.conductivity / (th.density * th.specific_heat))
    assert opt.heat_capacity == pytest.approx(th.density * th.specific_heat) and opt.notes == ()


def test_a_user_temperature_effect_runs_through_the_same_solver():
    user = persson.Model(ROAD, TREAD, effects=[SmallHotSpots()], grid=GRID).friction(SPEEDS, pressure=3e5)
    same = FlashTemperature(macro_scale_ratio=8.0, contact_diameter=1e-4)
    built_in = persson.Model(ROAD, TREAD, effects=[same], grid=GRID).friction(SPEEDS, pressure=3e5)
    assert user.converged and np.all(user.max_flash_temperature > 0.1)  # it heats
    np.testing.assert_array_equal(user.mu, built_in.mu)
    np.testing.assert_array_equal(user.temperature_q, built_in.temperature_q)


def test_a_temperature_effect_without_settings_and_bad_settings_are_refused():
    @dataclass(frozen=True)
    class Silent(Effect):
        name = "silent_temperature"
        solver_role = "temperature"

    with pytest.raises(persson.InputError, match="silent_temperature.*TemperatureSolverOptions"):
        persson.Model(ROAD, TREAD, effects=[Silent()], grid=GRID).friction(1.0)
    with pytest.raises(persson.InputError, match="contact_diameter"):
        TemperatureSolverOptions(q_m=1e3, contact_diameter=0.0, diffusivity=1e-7, heat_capacity=2e6)
    with pytest.raises(persson.InputError, match="max_iter"):
        TemperatureSolverOptions(q_m=1e3, contact_diameter=1e-3, diffusivity=1e-7, heat_capacity=2e6, max_iter=0)
