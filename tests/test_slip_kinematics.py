"""DRFT kinematics: from wheel and disk speeds (or slip and speed) to slip ratios and sliding speed.

Conventions (persson.slip.Kinematics, docs/slip.md): V is the counter-surface speed under the wheel centre
(Omega_disk R_track on a DRFT), V_w = omega r the wheel's circumferential speed.
* braking slip s = (V - V_w)/V: 0 free rolling, 1 locked wheel, negative when driving (the measurements' column);
* SAE J670 / ISO 8855 longitudinal slip kappa = (V_w - V)/V = -s (Pacejka's Magic Formula sign);
* driving slip s_d = (V_w - V)/V_w in [0, 1) when driving (1: spinning on a standing surface);
* sliding speed v_s = |V - V_w|; theoretical slip theta = |V - V_w|/V_w (bristle displacement per unit length).
Worked example (by hand): disk 5 rad/s at R = 0.2 m -> V = 1 m/s; wheel r = 0.05 m at 18 rad/s -> V_w = 0.9 m/s:
s = 0.1, kappa = -0.1, v_s = 0.1 m/s, theta = 0.1/0.9; at 22 rad/s -> V_w = 1.1 m/s: s = -0.1, s_d = 0.1/1.1.
"""

import numpy as np
import pytest

from persson import slip as ps
from persson.errors import InputError


def test_braking_and_driving_by_hand():
    k = ps.drft_from_angular([18.0, 22.0, 0.0, 20.0], 5.0, wheel_radius=0.05, track_radius=0.2)
    assert np.allclose(k.speed, 1.0) and np.allclose(k.wheel_speed, [0.9, 1.1, 0.0, 1.0])
    assert np.allclose(k.slip, [0.1, -0.1, 1.0, 0.0])
    assert np.allclose(k.longitudinal_slip, [-0.1, 0.1, -1.0, 0.0])
    assert np.allclose(k.driving_slip, [0.0, 0.1 / 1.1, 0.0, 0.0])
    assert np.allclose(k.sliding_speed, [0.1, 0.1, 1.0, 0.0])
    assert np.allclose(k.theoretical_slip[[0, 1, 3]], [0.1 / 0.9, 0.1 / 1.1, 0.0]) and np.isinf(k.theoretical_slip[2])
    assert list(k.braking) == [True, False, True, False] and list(k.driving) == [False, True, False, False]
    assert np.allclose(k.omega_wheel, [18.0, 22.0, 0.0, 20.0]) and np.allclose(k.omega_disk, 5.0)


def test_theoretical_slip_is_the_brush_displacement_rate():
    # braking: theta = s/(1 - s), the rate the brush model uses; driving: theta = s_d
    s = np.array([0.01, 0.2, 0.5, 0.9])
    k = ps.drft_speeds(s, 3.0)
    assert np.allclose(k.theoretical_slip, s / (1 - s))
    kd = ps.drft_speeds(-np.array([0.05, 0.5, 2.0]), 3.0)
    assert np.all(kd.driving) and np.allclose(kd.theoretical_slip, kd.driving_slip)
    assert np.allclose(kd.driving_slip, np.array([0.05, 0.5, 2.0]) / (1 + np.array([0.05, 0.5, 2.0])))


@pytest.mark.parametrize("slip", [-1.5, -0.2, 0.0, 0.03, 0.5, 1.0])
def test_speeds_and_kinematics_are_inverse(slip):
    V = 2.5
    fw = ps.drft_speeds(slip, V, wheel_radius=0.1, track_radius=0.3)
    back = ps.drft_from_angular(fw.omega_wheel, fw.omega_disk, wheel_radius=0.1, track_radius=0.3)
    assert back.slip == pytest.approx(slip, abs=1e-14)
    assert back.sliding_speed == pytest.approx(abs(slip) * V)
    assert back.longitudinal_slip == pytest.approx(-slip, abs=1e-14)
    assert bool(back.braking) == (slip > 0) and bool(back.driving) == (slip < 0)


def test_broadcasting_and_bad_input():
    k = ps.drft_kinematics(np.array([[0.5], [1.0]]), np.array([1.0, 2.0, 4.0]))
    assert k.slip.shape == (2, 3)
    assert np.allclose(k.slip[1], [0.0, 0.5, 0.75])
    with pytest.raises(InputError, match="disk_speed"):
        ps.drft_kinematics(0.5, -1.0)
    with pytest.raises(InputError, match="wheel_speed"):
        ps.drft_kinematics(np.nan, 1.0)
    with pytest.raises(InputError, match="broadcast"):
        ps.drft_kinematics([0.1, 0.2], [1.0, 2.0, 3.0])
    with pytest.raises(InputError, match="omega_disk"):
        ps.drft_from_angular(1.0, 0.0, wheel_radius=0.1, track_radius=0.2)
    with pytest.raises(InputError, match="track_radius"):
        ps.drft_from_angular(1.0, 1.0, wheel_radius=0.1, track_radius=-0.2)
    with pytest.raises(InputError, match="slip"):
        ps.drft_speeds(1.01, 1.0)
    with pytest.raises(InputError, match="speed"):
        ps.drft_speeds(0.1, 0.0)


def test_the_brush_model_takes_the_braking_rows():
    c = ps.Contact(0.02, 0.01, 3e9)
    k = ps.drft_kinematics([0.95, 1.05], 1.0)
    r = ps.mu_slip(lambda v: 0.8 + 0 * v, k.slip[k.braking], k.speed[k.braking], contact=c)
    assert r.sliding_speed == pytest.approx(0.05)
    with pytest.raises(InputError, match="slip"):
        ps.mu_slip(lambda v: 0.8 + 0 * v, k.slip, k.speed, contact=c)  # the driving row
