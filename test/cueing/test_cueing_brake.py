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
MotionCueing.brake: the platform brought to rest where it is, within the leg limits.

What a managed motion_cueing_node does when it is deactivated. Leg lengths are recomputed
from the poses sent with the leg formula of ``reference``; the limits are example_limits.yaml's.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics.cueing import MotionCueing
from stewart_kinematics.parameters import read_parameter_file

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'motion_cueing.yaml')]
G = 9.80665
PERIOD = 0.01
VELOCITY_MAX, ACCELERATION_MAX = 0.05, 0.25


def make_cueing():
    """Build the node's core from the shipped files."""
    values = {}
    for path in FILES:
        values.update(read_parameter_file(path, 'motion_cueing_node'))
    return MotionCueing.from_parameters(values)


def legs(pose):
    """Leg lengths of a platform pose (metres, radians), written out in reference."""
    return np.array(reference.leg_lengths(pose))


def test_brake_stops_a_moving_platform_within_the_limits_and_then_gives_nothing():
    """From a cue in motion: slower every step, at most a*dt each, then at rest: None."""
    cueing = make_cueing()
    time = 0.0
    for k in range(1, 40):   # a strong push forward and left: the legs move
        time = k * PERIOD
        step = cueing.cue(time, [6.0, 4.0, G], [0.0, 0.0, 0.5], time)
    previous = [legs(cueing.pose)]
    speeds = [np.abs(cueing.limiter.leg_velocities).max()]
    assert speeds[0] > 0.005
    steps = []
    for _ in range(1000):
        time += PERIOD
        braked = cueing.brake(time)
        if braked is None:
            break
        assert braked.command.accepted
        steps.append(braked)
        previous.append(legs(braked.pose))
    else:
        pytest.fail('brake never came to rest')
    lengths = np.array(previous)
    velocities = np.diff(lengths, axis=0) / PERIOD
    assert len(steps) >= 2
    assert np.abs(velocities).max() <= VELOCITY_MAX * (1 + 1e-9)
    assert np.abs(np.diff(velocities, axis=0)).max() <= ACCELERATION_MAX * PERIOD * (1 + 1e-6)
    assert_allclose(velocities[-1], 0.0, rtol=0, atol=1e-9)
    # At rest it stays: nothing more to send, the pose kept.
    pose = cueing.pose
    assert cueing.brake(time + PERIOD) is None
    assert_allclose(cueing.pose, pose, rtol=0, atol=0)
    del step


@pytest.mark.parametrize('moment', [math.nan, math.inf, 'soon', None])
def test_brake_of_a_time_that_is_no_number_gives_nothing(moment):
    """A command time that is not a finite number: nothing sent, nothing raised."""
    cueing = make_cueing()
    for k in range(1, 40):
        cueing.cue(k * PERIOD, [6.0, 4.0, G], [0.0, 0.0, 0.5], k * PERIOD)
    pose = cueing.pose

    assert cueing.brake(moment) is None
    assert_allclose(cueing.pose, pose, rtol=0, atol=0)


def test_brake_at_rest_gives_nothing():
    """A platform at rest at home: nothing to brake."""
    assert make_cueing().brake(1.0) is None
