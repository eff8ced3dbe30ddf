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
The defects of issue 21's first adversarial pass on the core, one test each.

A non-finite output (a twist of NaN from leg velocities of 1e308), an empty batch that forward
kinematics refused while inverse kinematics took it, and the decisions documented as never
raising that raised (or answered in numpy's words) for a string, a ragged list or a dict. The
property tests (test_properties_*.py) look for the next ones.
"""

import math

import numpy as np
import pytest

from stewart_kinematics import (
    CommandCheck,
    euler_zyx_to_matrix,
    forward_kinematics,
    inverse_kinematics,
    leg_lengths,
    leg_velocities,
    platform_twist,
    PoseTracker,
)

pytestmark = pytest.mark.core

#: Arguments that are not numbers, each refused by name and never in numpy's words.
NOT_NUMBERS = ['abc', None, [[1.0, 2.0], [3.0]], {'x': 1.0}, object(), [1 + 2j] * 6,
               ['0.1'] * 6, [True] * 6]
NUMPY_WORDS = ('setting an array element', 'could not convert', 'float() argument',
               'zero-size array', 'could not be broadcast', 'inhomogeneous')


@pytest.fixture(scope='module')
def geometry():
    """Build the paper's platform."""
    from reference import paper_geometry
    return paper_geometry()


def test_a_twist_of_huge_leg_velocities_is_refused_not_nan(geometry):
    tracker = PoseTracker(geometry)
    for velocities in ([1e308] * 6, [1.7e308, -1.7e308, 0.0, 1e308, -1e308, 0.0]):
        estimate = tracker.twist(velocities)
        assert not estimate.accepted and estimate.twist is None
        assert estimate.refusal.code == 'invalid_velocities'
        assert 'not finite' in estimate.reason
        with pytest.raises(ValueError, match='the twist of the leg velocities: not finite'):
            platform_twist(geometry, geometry.home_pose, velocities)
    assert np.all(np.isfinite(tracker.twist([1e-3] * 6).twist))


def test_leg_velocities_and_lengths_that_overflow_are_refused(geometry):
    with pytest.raises(ValueError, match='leg velocities of the twists: not finite'):
        leg_velocities(geometry, geometry.home_pose, [1.7e308] * 6)
    with pytest.raises(ValueError, match='leg lengths of the poses: not finite'):
        inverse_kinematics(geometry, [1e200, 0.0, 0.0, 0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match='leg lengths of the poses: not finite'):
        inverse_kinematics(geometry, [[0.0, 0.0, 0.5, 0.0, 0.0, 0.0], [0.0, 1e200, 0, 0, 0, 0]])
    with pytest.raises(ValueError, match='leg lengths of the position and rotation'):
        leg_lengths(geometry, [1e200, 0.0, 0.0], np.eye(3))
    command = CommandCheck(geometry)
    assert command.pose_vector(geometry.home_pose).accepted
    refused = command.twist([1.7e308] * 6)
    assert not refused.accepted and refused.refusal.code == 'invalid_twist'


def test_forward_kinematics_takes_an_empty_batch_as_inverse_kinematics_does(geometry):
    empty = np.zeros((0, 6))
    assert inverse_kinematics(geometry, empty).shape == (0, 6)
    for guess in (None, geometry.home_pose, empty):
        result = forward_kinematics(geometry, empty, guess)
        assert result.pose.shape == (0, 6) and result.reason == ()
        assert result.converged.shape == result.residual.shape == (0,)
        assert result.condition.shape == result.pose_error_bound.shape == (0,)
    result = forward_kinematics(geometry, geometry.home_leg_lengths, empty)
    assert result.pose.shape == (0, 6)
    with pytest.raises(ValueError, match='same number of poses'):
        forward_kinematics(geometry, empty, np.zeros((2, 6)))


@pytest.mark.parametrize('value', NOT_NUMBERS, ids=repr)
def test_the_decisions_never_raise_for_what_is_not_numbers(geometry, value):
    check = CommandCheck(geometry)
    tracker = PoseTracker(geometry)
    decisions = [check.pose_vector(value), check.pose(value, np.eye(3)),
                 check.pose([0.0, 0.0, 0.45], value), check.pose_quaternion(value, [0, 0, 0, 1]),
                 check.pose_quaternion([0.0, 0.0, 0.45], value), check.twist(value),
                 tracker.update(value), tracker.twist(value)]
    for decision in decisions:
        assert not decision.accepted
        assert not any(words in decision.reason for words in NUMPY_WORDS), decision.reason


@pytest.mark.parametrize('value', NOT_NUMBERS, ids=repr)
def test_functions_name_the_argument_that_is_not_numbers(geometry, value):
    calls = {'poses': lambda: inverse_kinematics(geometry, value),
             'leg lengths': lambda: forward_kinematics(geometry, value),
             'position': lambda: leg_lengths(geometry, value, np.eye(3)),
             'rotation': lambda: leg_lengths(geometry, [0.0, 0.0, 0.45], value),
             'Euler angles': lambda: euler_zyx_to_matrix(value)}
    for name, call in calls.items():
        with pytest.raises(ValueError) as raised:
            call()
        message = str(raised.value)
        assert name in message, message
        assert not any(words in message for words in NUMPY_WORDS), message


def test_non_finite_angles_are_refused_by_the_conversions():
    for angles in ([math.nan, 0.0, 0.0], [[0.0, 0.0, math.inf]]):
        with pytest.raises(ValueError, match='Euler angles must be finite'):
            euler_zyx_to_matrix(angles)


def test_angles_near_gimbal_lock_rebuild_the_rotation_to_rounding():
    # Found by the property tests: within 1e-12 of gimbal lock alpha was snapped to 0 and the
    # rotation rebuilt only to 1e-12 rad.
    from reference import rotation_angle, rotation_zyx
    from stewart_kinematics import matrix_to_euler_zyx
    worst = 0.0
    for alpha in np.linspace(-3.0, 3.0, 13):
        for gap in (1e-11, 1e-12, 5e-13, 1e-14, 0.0):
            for sign in (1.0, -1.0):
                rotation = rotation_zyx(alpha, sign * (math.pi / 2 - gap), 0.7)
                rebuilt = rotation_zyx(*matrix_to_euler_zyx(rotation))
                worst = max(worst, rotation_angle(rebuilt, rotation))
    assert worst < 2e-15
