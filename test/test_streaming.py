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

"""Unit tests of stewart_kinematics.motion.streaming: the jerk-limited command filter (ruckig)."""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import ActuatorLimits, CommandFilter

pytestmark = pytest.mark.core

LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
PERIOD = 0.01
HOME = np.array([0.7189, 0.7189, 0.7011, 0.7189, 0.7189, 0.7189])


def run(command_filter, steps):
    """Step the filter; return lengths, velocities, accelerations (steps, 6) and settled."""
    commands = [command_filter.step() for _ in range(steps)]
    return (np.array([command.lengths for command in commands]),
            np.array([command.velocities for command in commands]),
            np.array([command.accelerations for command in commands]),
            [command.settled for command in commands])


def assert_within_limits(lengths, velocities, accelerations, start):
    """Velocity, acceleration and jerk (finite differences) within LIMITS at every step."""
    assert np.abs(velocities).max() <= LIMITS.velocity_max * (1 + 1e-9)
    assert np.abs(accelerations).max() <= LIMITS.acceleration_max * (1 + 1e-9)
    # The commands are consistent with their velocities: positions integrate them.
    lengths = np.vstack([start, lengths])
    speeds = np.abs(np.diff(lengths, axis=0)) / PERIOD
    assert speeds.max() <= LIMITS.velocity_max * (1 + 1e-9)
    jerks = np.abs(np.diff(accelerations, axis=0)) / PERIOD
    assert jerks.max() <= LIMITS.jerk_max * (1 + 1e-6)


def test_a_jump_is_smoothed_and_reached_at_rest():
    """A 5 cm target jump: within limits at every step, all legs arrive together, at rest."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME)
    target = HOME + np.array([0.05, 0.04, 0.03, 0.02, 0.01, 0.0])
    command_filter.set_target(target)
    lengths, velocities, accelerations, settled = run(command_filter, 400)
    assert_within_limits(lengths, velocities, accelerations, HOME)
    first_settled = settled.index(True)
    # 5 cm at 0.05 m/s takes over 1 s; with acceleration and jerk phases about 1.3 s.
    assert 1.0 < first_settled * PERIOD < 2.0
    assert_allclose(lengths[first_settled:], np.tile(target, (400 - first_settled, 1)),
                    atol=1e-12)
    # Time-synchronised: each leg's progress is the same fraction of its own jump.
    progress = (lengths[:first_settled, :5] - HOME[:5]) / (target[:5] - HOME[:5])
    assert_allclose(progress, np.tile(progress[:, :1], (1, 5)), atol=1e-6)


def test_a_target_changed_mid_motion_stays_within_limits_and_converges():
    """Irregular targets, as teleop sends them: within limits throughout, then settles."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME)
    rng = np.random.default_rng(0)
    start = HOME
    for _ in range(8):
        command_filter.set_target(HOME + rng.uniform(-0.03, 0.03, 6))
        lengths, velocities, accelerations, _ = run(command_filter, int(rng.integers(5, 40)))
        assert_within_limits(lengths, velocities, accelerations, start)
        start = lengths[-1]
    final = HOME + 0.01
    command_filter.set_target(final)
    lengths, velocities, accelerations, settled = run(command_filter, 500)
    assert_within_limits(lengths, velocities, accelerations, start)
    assert settled[-1]
    assert_allclose(lengths[-1], final, atol=1e-12)
    assert_allclose(velocities[-1], 0.0, atol=1e-12)


def test_infinite_jerk_is_allowed_but_velocity_and_acceleration_must_be_set():
    """Acceleration-limited motion works; without a velocity limit the filter refuses."""
    command_filter = CommandFilter(ActuatorLimits(0.05, 0.25), PERIOD, HOME)
    command_filter.set_target(HOME + 0.01)
    assert run(command_filter, 200)[3][-1]
    for limits in (ActuatorLimits(acceleration_max=0.25), ActuatorLimits(velocity_max=0.05)):
        with pytest.raises(ValueError, match='leg_velocity_max and leg_acceleration_max'):
            CommandFilter(limits, PERIOD, HOME)


def test_reset_and_bad_input():
    """reset() puts the command at rest; non-finite lengths or periods are refused."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME)
    command_filter.set_target(HOME + 0.02)
    run(command_filter, 10)
    command_filter.reset(HOME)
    command = command_filter.step()
    assert_allclose(command.lengths, HOME)
    assert command.settled
    refusal = command_filter.set_target([math.nan] * 6)
    assert refusal.code == 'invalid_lengths' and '6 finite' in refusal.message
    with pytest.raises(ValueError, match='period'):
        CommandFilter(LIMITS, 0.0, HOME)
