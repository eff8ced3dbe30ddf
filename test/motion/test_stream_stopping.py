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
CommandFilter.stopping_lengths: where a stream stops as soon as its limits allow.

What a managed ik_node aims at when it is deactivated mid-stream; checked against the
stopping distance of a constant deceleration, v^2 / (2 a), written out here.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import ActuatorLimits, CommandFilter

pytestmark = pytest.mark.core

PERIOD = 0.01
HOME = np.array([0.7189, 0.7189, 0.7011, 0.7189, 0.7189, 0.7189])


def cruise(limits, steps=200):
    """Return a filter streaming toward a target 0.1 m away, after ``steps`` steps."""
    command_filter = CommandFilter(limits, PERIOD, HOME)
    assert command_filter.set_target(HOME + 0.1).accepted
    for _ in range(steps):
        command = command_filter.step()
    return command_filter, command


def test_at_cruise_speed_without_a_jerk_limit_the_stop_is_v_squared_over_2a():
    """Acceleration-limited: from 0.05 m/s, 0.25 m/s^2 stops 5 mm further, every leg."""
    limits = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=math.inf)
    command_filter, command = cruise(limits)
    assert_allclose(command.velocities, 0.05, rtol=0, atol=1e-12)

    stop = command_filter.stopping_lengths()

    assert_allclose(stop - command.lengths, 0.05 ** 2 / (2 * 0.25), rtol=0, atol=1e-9)


def test_stopping_there_keeps_every_limit_and_ends_at_rest():
    """With a jerk limit: aimed at, the stream decelerates within the limits and rests there."""
    limits = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
    command_filter, command = cruise(limits, steps=15)   # still accelerating
    assert 0.0 < command.velocities.max() < 0.05 and command.accelerations.max() > 0.0
    stop = command_filter.stopping_lengths()
    # Further than at once, not as far as the target: it stops on the way.
    assert np.all(stop > command.lengths) and np.all(stop < HOME + 0.1)

    assert command_filter.set_target(stop).accepted
    velocities, accelerations, lengths = [command.velocities], [command.accelerations], []
    for _ in range(100):
        step = command_filter.step()
        velocities.append(step.velocities)
        accelerations.append(step.accelerations)
        lengths.append(step.lengths)
        if step.settled:
            break
    velocities, accelerations = np.array(velocities), np.array(accelerations)
    assert step.settled
    assert_allclose(lengths[-1], stop, rtol=0, atol=1e-12)
    assert_allclose(velocities[-1], 0.0, rtol=0, atol=1e-12)
    assert np.abs(velocities).max() <= 0.05 * (1 + 1e-9)
    assert np.abs(accelerations).max() <= 0.25 * (1 + 1e-9)
    assert np.abs(np.diff(accelerations, axis=0)).max() <= 2.5 * PERIOD * (1 + 1e-6)
    # As soon as the limits allow: the acceleration taken away (a/j), then at most the full
    # speed taken away with the jerk-limited ramps (v/a + a/j).
    assert len(lengths) * PERIOD <= 0.25 / 2.5 + 0.05 / 0.25 + 0.25 / 2.5 + PERIOD


def test_at_rest_the_stop_is_where_it_is():
    """A filter at rest stops where it stands."""
    command_filter = CommandFilter(ActuatorLimits(0.05, 0.25, 2.5), PERIOD, HOME)

    assert_allclose(command_filter.stopping_lengths(), HOME, rtol=0, atol=1e-15)
