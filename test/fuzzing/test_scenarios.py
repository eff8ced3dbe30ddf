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
The generators of issue 27's cases (fuzzing/scenarios.py) make what they say they make.

A bulging trajectory: its waypoints inside the stroke, the whole of it within one period of
its validation rate, and its bulge beyond the stroke (or inside it) by what it claims, as an
independent Hermite curve says; the planner refuses those beyond and takes those inside. An
IMU stream: every sample below the node's bounds, with the noise of the adversarial pass, or a
smooth recording; stamped as asked.
"""

import math
from pathlib import Path
import random

from fuzzing.scenarios import bulging_trajectory, FORCE_NOISE, ImuStream, RATE_NOISE
import numpy as np
import pytest
import reference

from stewart_kinematics.model.frames import FrameTree
from stewart_kinematics.motion.planning import MotionPlanner
from stewart_kinematics.parameters import (
    actuator_limits_from_settings,
    GeometrySettings,
    load_geometry,
    read_parameter_files,
)
from stewart_kinematics.ros.message_conversions import pose_trajectory_from_message

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml']
GEOMETRY = load_geometry(FILES)
LIMITS = actuator_limits_from_settings(GeometrySettings.from_values(read_parameter_files(FILES)))


def hermite_offsets(s, degree):
    """Return the weights of the start and end tangents of a Hermite piece at ``s`` in [0, 1]."""
    if degree == 3:
        return s ** 3 - 2.0 * s ** 2 + s, s ** 3 - s ** 2
    # The quintic with zero accelerations at both ends.
    return (s - 6.0 * s ** 3 + 8.0 * s ** 4 - 3.0 * s ** 5,
            -4.0 * s ** 3 + 7.0 * s ** 4 - 3.0 * s ** 5)


def independent_extremes(arguments):
    """Return the leg lengths along the pieces, by the textbook's Hermite basis, (M, 6)."""
    times, positions = arguments['times'], arguments['positions']
    velocities = arguments['velocities']
    degree = 5 if 'accelerations' in arguments else 3
    x, y, z, w = arguments['quaternions'][0]
    rotation = reference.quaternion_matrix(x, y, z, w)
    lengths = []
    for piece in range(len(times) - 1):
        step = times[piece + 1] - times[piece]
        assert np.array_equal(positions[piece], positions[piece + 1])   # one pose
        s = np.linspace(0.0, 1.0, 4001)[:, None]
        start, end = hermite_offsets(s, degree)
        points = positions[piece] + step * (start * velocities[piece] + end * velocities[
            piece + 1])
        lengths += [reference.leg_lengths_of_matrix(point, rotation) for point in points]
    return np.array(lengths)


@pytest.mark.parametrize('seed', range(10))
def test_a_bulging_trajectory_passes_the_stroke_between_its_waypoints_only(seed):
    """Waypoints inside; the bulge beyond (or inside) by what it says; within one period."""
    rng = random.Random(seed)
    message, case = bulging_trajectory(rng, GEOMETRY, LIMITS, FrameTree(),
                                       frame_id='stewart_base')
    arguments = pose_trajectory_from_message(message)
    assert 1.0 <= case.validation_rate <= 5.0
    assert arguments['times'][-1] < 1.0 / case.validation_rate
    waypoints = [reference.leg_lengths_of_matrix(position, reference.quaternion_matrix(
        *quaternion)) for position, quaternion in zip(arguments['positions'],
                                                      arguments['quaternions'])]
    low, high = GEOMETRY.leg_length_min, GEOMETRY.leg_length_max
    assert low < np.min(waypoints) and np.max(waypoints) < high
    lengths = independent_extremes(arguments)
    excess = max(np.max(lengths) - high, low - np.min(lengths))
    np.testing.assert_allclose(excess, case.peak_excess, atol=2e-7)
    assert (excess > 0.0) == case.beyond
    assert abs(excess) > 1e-6   # by a clear margin, one way or the other


def test_the_planner_refuses_the_bulges_beyond_and_takes_those_inside():
    """At the low validation rate: beyond refused at a published point, inside accepted."""
    rng = random.Random(27)
    outcomes = set()
    for beyond in (True, False, True, False):
        message, case = bulging_trajectory(rng, GEOMETRY, LIMITS, FrameTree(), beyond=beyond)
        planner = MotionPlanner(GEOMETRY, LIMITS, validation_rate=case.validation_rate,
                                publish_rate=50.0)
        plan = planner.plan_trajectory(**pose_trajectory_from_message(message))
        if beyond:
            assert plan.refusal.code == 'out_of_limits', case.describe()
            assert 'leg_length_m' in plan.reason
        else:
            assert plan.accepted, (case.describe(), plan.reason)
        outcomes.add(plan.accepted)
    assert outcomes == {True, False}


def test_noisy_imu_samples_have_the_passs_noise_and_stay_below_the_bounds():
    """Normal noise of 30 m/s^2 and 5 rad/s per axis, every sample below 95 % of each bound."""
    stream = ImuStream(random.Random(5), 'noise', 100.0, 20.0)
    samples = [stream.sample(index * 0.01) for index in range(4000)]
    forces = np.array([force for force, _ in samples])
    rates = np.array([rate for _, rate in samples])
    assert np.linalg.norm(forces, axis=1).max() < 95.0
    assert np.linalg.norm(rates, axis=1).max() < 19.0
    np.testing.assert_allclose(forces.mean(axis=0), [0.0, 0.0, 9.81], atol=2.0)
    np.testing.assert_allclose(forces.std(axis=0), FORCE_NOISE, rtol=0.08)
    np.testing.assert_allclose(rates.std(axis=0), RATE_NOISE, rtol=0.08)
    message = stream.message(1_000_000_000_123, 'base_link')
    assert (message.header.stamp.sec, message.header.stamp.nanosec) == (1000, 123)
    assert message.header.frame_id == 'base_link'
    assert math.isfinite(message.linear_acceleration.x)


def test_a_recording_is_smooth_and_a_function_of_its_stamps():
    """The same stamp gives the same sample; 10 ms apart, a sample moves little."""
    stream = ImuStream(random.Random(8), 'recording', 100.0, 20.0)
    first = stream.sample(12.34)
    np.testing.assert_array_equal(stream.sample(12.34)[0], first[0])
    steps = [np.abs(stream.sample(t + 0.01)[0] - stream.sample(t)[0]).max()
             for t in np.arange(0.0, 10.0, 0.37)]
    assert max(steps) < 0.5
    forces = np.array([stream.sample(t)[0] for t in np.arange(0.0, 10.0, 0.01)])
    assert forces[:, 0].max() - forces[:, 0].min() > 1.0   # it does move
    with pytest.raises(ValueError, match="'noise' or 'recording'"):
        ImuStream(random.Random(1), 'quiet', 100.0, 20.0)
