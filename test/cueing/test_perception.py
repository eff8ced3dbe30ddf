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
The motion felt at the head against the definition, evaluated with finite differences here.

A smooth analytic motion of the platform (sines in every pose coordinate); the reference is
``f = R^T (h'' + [0, 0, g])`` with ``h = p + R head`` and ``w = (R^T R')^v``, the derivatives
taken by central differences with a step of 1e-4 s on the analytic motion, the rotation from
the elementary matrices of test/reference.py. The package samples the motion every millisecond
and differences the samples: the two agree to the order of the sampling step squared.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import rotation_zyx

from stewart_kinematics.cueing.perception import (
    perceived_motion,
    PerceptionEstimator,
    specific_force,
)

pytestmark = pytest.mark.core

G = 9.80665
HEAD = np.array([0.05, -0.02, 0.6])
HOME = np.array([0.0, 0.0, 0.4325, 0.0, 0.0, 0.0])
AMPLITUDES = np.array([0.08, 0.05, 0.02, math.radians(6.0), math.radians(4.0),
                       math.radians(10.0)])
FREQUENCIES = np.array([0.7, 1.1, 1.9, 0.5, 0.9, 0.3]) * 2.0 * math.pi


def pose(t):
    """Return the analytic motion: home plus a sine per coordinate."""
    return HOME + AMPLITUDES * np.sin(FREQUENCIES * t + np.arange(6))


def head(t):
    """Return the head's position in the base frame."""
    p = pose(t)
    return p[:3] + rotation_zyx(*p[3:]) @ HEAD


def reference(t, h=1e-4):
    """Specific force and body angular velocity by central differences of the analytic motion."""
    rotation = rotation_zyx(*pose(t)[3:])
    acceleration = (head(t + h) - 2.0 * head(t) + head(t - h)) / (h * h)
    force = rotation.T @ (acceleration + [0.0, 0.0, G])
    derivative = (rotation_zyx(*pose(t + h)[3:]) - rotation_zyx(*pose(t - h)[3:])) / (2.0 * h)
    skew = rotation.T @ derivative
    return force, np.array([skew[2, 1], skew[0, 2], skew[1, 0]])


def test_batch_perception_matches_the_definition():
    """perceived_motion over 4 s at 1 kHz against the reference at every inner sample."""
    times = np.arange(0.0, 4.0, 0.001)
    perceived = perceived_motion(times, np.array([pose(t) for t in times]), HEAD, G)
    for index in range(5, times.size - 5, 97):
        force, rate = reference(times[index])
        assert_allclose(perceived.specific_force[index], force, atol=2e-4)
        assert_allclose(perceived.angular_velocity[index], rate, atol=1e-5)


def test_uneven_steps_keep_second_order_accuracy():
    """Jittered steps (0.5 to 1.5 ms): the error grows with the steps' difference, still small."""
    rng = np.random.default_rng(5)
    times = np.cumsum(rng.uniform(0.0005, 0.0015, size=3000))
    perceived = perceived_motion(times, np.array([pose(t) for t in times]), HEAD, G)
    for index in range(5, times.size - 5, 101):
        force, rate = reference(times[index])
        assert_allclose(perceived.specific_force[index], force, atol=2e-2)
        assert_allclose(perceived.angular_velocity[index], rate, atol=1e-3)


def test_streaming_estimate_equals_the_batch():
    """Stream: the estimator returns the batch value of the previous sample, with its label."""
    times = np.arange(0.0, 0.5, 0.002)
    poses = np.array([pose(t) for t in times])
    batch = perceived_motion(times, poses, HEAD, G)
    estimator = PerceptionEstimator(HEAD, G)
    for index, (time, sample) in enumerate(zip(times, poses)):
        result = estimator.update(time, sample, label=f'sample {index}')
        if index < 2:
            assert result is None
            continue
        label, force = result
        assert label == f'sample {index - 1}'
        assert_allclose(force, batch.specific_force[index - 1], atol=1e-9)


def test_tilt_at_rest_is_felt_as_gravity():
    """A platform pitched nose-up by beta at rest feels f_x = -g sin(beta): tilt coordination."""
    beta = math.radians(-5.0)
    rotation = rotation_zyx(0.0, beta, 0.0)
    assert_allclose(specific_force(rotation, np.zeros(3), G),
                    [-G * math.sin(beta), 0.0, G * math.cos(beta)], atol=1e-15)
    times = np.arange(0.0, 0.1, 0.01)
    still = np.tile(np.r_[HOME[:3], 0.3, beta, -0.2], (times.size, 1))
    perceived = perceived_motion(times, still, HEAD, G)
    expected = rotation_zyx(0.3, beta, -0.2).T @ [0.0, 0.0, G]
    assert_allclose(perceived.specific_force, np.tile(expected, (times.size, 1)), atol=1e-9)
    assert_allclose(perceived.angular_velocity, 0.0, atol=1e-12)


@pytest.mark.parametrize('times, poses', [
    (np.arange(2.0), np.zeros((2, 6))), (np.arange(5.0), np.zeros((5, 5))),
    (np.array([0.0, 1.0, 1.0, 2.0]), np.zeros((4, 6)))])
def test_malformed_motion_is_refused(times, poses):
    """Too few samples, wrong shapes, repeated times: ValueError."""
    with pytest.raises(ValueError, match='times'):
        perceived_motion(times, poses, HEAD, G)
