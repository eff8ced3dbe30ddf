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

"""Unit tests of stewart_kinematics.model.actuators: leg speed limits, the actuator interface."""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose, assert_array_equal
import pytest

from stewart_kinematics import ActuatorInterface, ActuatorLimits
from stewart_kinematics.parameters import (
    actuator_limits_from_settings,
    GeometrySettings,
    load_settings,
)

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'


def test_example_limits_file_sets_finite_speed_limits():
    """config/example_limits.yaml gives the paper's platform finite speed limits."""
    limits = actuator_limits_from_settings(load_settings(
        GeometrySettings, [CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml']))
    assert (limits.velocity_max, limits.acceleration_max, limits.jerk_max) == (0.05, 0.25, 2.5)
    assert limits.limits_speed


def test_defaults_are_no_limit_and_scaling_follows_time_stretching():
    """No parameter: no limit. Played 1/s times as long: v * s, a * s^2, jerk * s^3."""
    assert actuator_limits_from_settings(load_settings(
        GeometrySettings, CONFIG / 'paper_platform.yaml')) == ActuatorLimits()
    assert not ActuatorLimits().limits_speed
    scaled = ActuatorLimits(0.05, 0.25, 2.5).scaled(0.5)
    assert_allclose([scaled.velocity_max, scaled.acceleration_max, scaled.jerk_max],
                    [0.025, 0.0625, 0.3125])
    assert ActuatorLimits().scaled(0.5).velocity_max == math.inf
    with pytest.raises(ValueError, match='speed_scale'):
        ActuatorLimits().scaled(0.0)


@pytest.mark.parametrize('value', [0.0, -1.0, math.nan])
def test_limits_must_be_positive(value):
    """A zero, negative or NaN limit is refused, naming the parameter."""
    with pytest.raises(ValueError, match='leg_acceleration_max'):
        ActuatorLimits(acceleration_max=value)


def test_positions_are_lengths_minus_offsets():
    """Give position = length - offset, and back."""
    actuators = ActuatorInterface(offsets=[0.6, 0.61, 0.62, 0.63, 0.64, 0.65])
    lengths = np.array([[0.7, 0.71, 0.72, 0.73, 0.74, 0.75]])
    assert_allclose(actuators.positions(lengths), np.full((1, 6), 0.1), atol=1e-15)
    assert_allclose(actuators.lengths(actuators.positions(lengths)), lengths, atol=1e-15)
    assert ActuatorInterface().joint_names == ('leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5',
                                               'leg_6')


def test_order_finds_the_legs_among_other_joints():
    """A JointState in any order, with other joints: the legs' indices, leg 1..6."""
    actuators = ActuatorInterface(('a', 'b', 'c', 'd', 'e', 'f'))
    names = ['gripper', 'f', 'e', 'd', 'c', 'b', 'a']
    assert_array_equal(actuators.order(names), [6, 5, 4, 3, 2, 1])
    with pytest.raises(ValueError, match='missing a'):
        actuators.order(names[:-1])
    with pytest.raises(ValueError, match='repeated b'):
        actuators.order(names + ['b'])


@pytest.mark.parametrize('names, offsets', [
    (('a',) * 6, None), (('a', 'b'), None), (('a', 'b', 'c', 'd', 'e', ''), None),
    (None, [0.0] * 5), (None, [math.inf] + [0.0] * 5)])
def test_malformed_interfaces_are_refused(names, offsets):
    """Six distinct non-empty names and six finite offsets, or ValueError."""
    arguments = {}
    if names is not None:
        arguments['joint_names'] = names
    if offsets is not None:
        arguments['offsets'] = offsets
    with pytest.raises(ValueError):
        ActuatorInterface(**arguments)
