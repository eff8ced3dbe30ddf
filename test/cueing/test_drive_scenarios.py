# Copyright 2026 stewart_kinematics developers
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.

"""
The five scenarios of issue 31, against the shapes and peaks their documentation states.

Each is generated (no replay: milliseconds each) and checked for rest at its start and after
its rest time, and for the figures the module's docstring gives, computed here by hand.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics.cueing.scenarios import (
    brake_step,
    bumpy_road,
    coordinated_turn,
    lane_change,
    MAX_RATE,
    mixed_drive,
    scenario,
)

pytestmark = pytest.mark.core

G = 9.80665
STEP = 0.01


def relative(generated):
    """Return the force relative to rest and the rates, (N, 3) each."""
    return generated.specific_force - [0.0, 0.0, G], generated.angular_velocity


@pytest.mark.parametrize('name', ['brake_step', 'lane_change', 'coordinated_turn',
                                  'mixed_drive', 'bumpy_road'])
def test_new_scenarios_rest_at_start_and_after_their_rest_time(name):
    """At rest before 1 s and from rest_time on, for at least 12 s; moving between."""
    generated = scenario(name, 100.0)
    force, rates = relative(generated)
    before = generated.times < 1.0
    after = generated.times >= generated.rest_time
    assert np.all(force[before] == 0.0) and np.all(rates[before] == 0.0)
    assert np.all(force[after] == 0.0) and np.all(rates[after] == 0.0)
    assert generated.times[-1] >= generated.rest_time + 12.0 - 1e-9
    assert np.max(np.abs(np.concatenate([force, rates], axis=1))) > 0.1


def test_brake_step_stops_from_15_m_s_at_6_m_s2_and_ends_in_a_step():
    """Peak -6 m/s^2, 15 m/s taken off, the force from -6 to 0 in one sample at 3.65 s."""
    generated = brake_step()
    force, rates = relative(generated)
    assert generated.rest_time == pytest.approx(1.0 + 0.3 + (15.0 - 0.9) / 6.0)
    assert np.min(force[:, 0]) == pytest.approx(-6.0)
    assert np.sum(force[:, 0]) * STEP == pytest.approx(-15.0, abs=0.06)
    stop = int(np.searchsorted(generated.times, generated.rest_time))
    assert force[stop - 1, 0] == pytest.approx(-6.0) and force[stop, 0] == 0.0
    assert_allclose(force[:, 1:], 0.0, atol=0)
    assert_allclose(rates, 0.0, atol=0)


def test_lane_change_is_one_period_of_0_4_g_at_0_5_hz():
    """3.92 m/s^2 peak, 2 s long, lateral speed back to 0 after about 2.5 m, yaw a_y / 25."""
    generated = lane_change()
    force, rates = relative(generated)
    lateral = force[:, 1]
    moving = np.flatnonzero(lateral)
    assert generated.times[moving[0]] == pytest.approx(1.0 + STEP)
    assert generated.times[moving[-1]] == pytest.approx(3.0 - STEP)
    assert np.max(lateral) == pytest.approx(0.4 * G, rel=1e-9)
    assert np.min(lateral) == pytest.approx(-0.4 * G, rel=1e-9)
    velocity = np.cumsum(lateral) * STEP
    assert velocity[-1] == pytest.approx(0.0, abs=1e-9)
    # y(T) = A T / omega = 0.4 g * 2 s / pi.
    assert np.sum(velocity) * STEP == pytest.approx(0.4 * G * 2.0 / math.pi, rel=1e-3)
    assert_allclose(rates[:, 2], lateral / 25.0, atol=0)
    assert math.degrees(np.max(rates[:, 2])) == pytest.approx(8.99, abs=0.01)


def test_coordinated_turn_has_no_lateral_force():
    """
    30 deg of bank by a raised cosine in 3 s, 10 s of turn, out in 3 s, at 100 m/s.

    Roll rate peak 30 deg * pi / 6 = 15.71 deg/s, integrating to the bank; the force along the
    body z only, 1 / cos(30 deg) g; in the turn, body pitch and yaw rates g tan(30) / V
    resolved by sin and cos of the bank.
    """
    generated = coordinated_turn()
    force, rates = relative(generated)
    assert_allclose(force[:, :2], 0.0, atol=0)
    assert np.max(force[:, 2]) == pytest.approx(G / math.cos(math.radians(30.0)) - G,
                                                rel=1e-9)
    assert math.degrees(np.max(rates[:, 0])) == pytest.approx(15.708, abs=1e-3)
    roll_in = generated.times < 4.0
    assert math.degrees(np.sum(rates[roll_in, 0]) * STEP) == pytest.approx(30.0, abs=1e-3)
    assert np.sum(rates[:, 0]) * STEP == pytest.approx(0.0, abs=1e-9)
    turning = (generated.times > 4.0) & (generated.times < 14.0)
    turn_rate = G * math.tan(math.radians(30.0)) / 100.0
    assert_allclose(rates[turning, 1], turn_rate * 0.5, rtol=1e-12)
    assert_allclose(rates[turning, 2], turn_rate * math.cos(math.radians(30.0)), rtol=1e-12)
    assert generated.rest_time == 17.0


def test_mixed_drive_is_60_s_from_standstill_to_standstill_and_seeded():
    """Speed never below 0, back to 0; accelerating, braking and cornering; the seed decides."""
    generated = mixed_drive()
    force, rates = relative(generated)
    assert generated.rest_time == 61.0
    speed = np.cumsum(force[:, 0]) * STEP
    assert np.min(speed) > -0.1 and abs(speed[-1]) < 0.1
    assert np.max(speed) <= 30.0 + 0.5
    assert 3.0 <= np.max(force[:, 0]) <= 6.5 and -6.5 <= np.min(force[:, 0]) <= -3.0
    assert 3.0 <= np.max(np.abs(force[:, 1])) <= 6.5
    assert np.max(np.abs(rates[:, 2])) > 0.1
    again = mixed_drive()
    assert_allclose(again.specific_force, generated.specific_force, atol=0)
    other = mixed_drive(seed=5)
    assert not np.allclose(other.specific_force, generated.specific_force)


def test_bumpy_road_is_heave_and_pitch_only():
    """No force along x or y, no roll or yaw; heave about 4 m/s^2 and pitch 14 deg/s peaks."""
    generated = bumpy_road()
    force, rates = relative(generated)
    assert_allclose(force[:, :2], 0.0, atol=0)
    assert_allclose(rates[:, [0, 2]], 0.0, atol=0)
    assert np.max(np.abs(force[:, 2])) == pytest.approx(4.13, abs=0.01)
    assert math.degrees(np.max(np.abs(rates[:, 1]))) == pytest.approx(13.90, abs=0.01)
    # The noise and the bumps are mostly above 1 Hz: little of the heave below 0.5 Hz.
    spectrum = np.abs(np.fft.rfft(force[:, 2])) ** 2
    frequencies = np.fft.rfftfreq(force.shape[0], STEP)
    assert np.sum(spectrum[frequencies < 0.5]) < 0.05 * np.sum(spectrum)


@pytest.mark.parametrize('rate', [0.0, -1.0, math.nan, math.inf, 1e308, MAX_RATE * 2, '100',
                                  None, True])
def test_bad_rates_are_refused_for_every_new_scenario(rate):
    """A rate that is not a positive number of hertz up to MAX_RATE: ValueError naming it."""
    for name in ('brake_step', 'lane_change', 'coordinated_turn', 'mixed_drive', 'bumpy_road'):
        with pytest.raises(ValueError, match='rate must be'):
            scenario(name, rate)
