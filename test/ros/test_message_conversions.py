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
Tests of stewart_kinematics.ros.message_conversions: Pose and leg arrays to numpy and back.

Expected quaternions are typed by hand or built with the textbook roll-pitch-yaw half-angle
formula written out here, never with the package's own rotation functions.
"""

import math

from geometry_msgs.msg import Pose, Quaternion
from helpers import raw_pose_message
import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import paper_geometry, quaternion_from_euler
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, MultiArrayLayout

from stewart_kinematics import PoseTracker
from stewart_kinematics.ros.message_conversions import (
    leg_lengths_from_message,
    legs_from_joint_state,
    legs_to_message,
    pose_from_message,
    pose_to_message,
    position_quaternion_from_message,
)

pytestmark = pytest.mark.node

SQRT_HALF = 0.7071067811865476


def quaternion_of(message):
    """Return the ``(x, y, z, w)`` of a Pose's orientation as an array."""
    orientation = message.orientation
    return np.array([orientation.x, orientation.y, orientation.z, orientation.w])


def lengths_message(data, data_offset=0):
    """Build a Float64MultiArray with only data and data_offset set, as ``ros2 topic pub`` does."""
    return Float64MultiArray(
        layout=MultiArrayLayout(data_offset=data_offset), data=[float(v) for v in data])


POSES = [
    [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0],
    [0.1, 0.15, 0.5325, math.radians(15.0), math.radians(-15.0), math.radians(20.0)],
    [-0.02, 0.03, 0.45, math.radians(-5.0), math.radians(8.0), math.radians(-30.0)],
    [1.0, -2.0, 3.0, math.radians(170.0), math.radians(80.0), math.radians(-170.0)],
    [0.0, 0.0, 0.0, math.radians(-120.0), math.radians(-45.0), math.radians(150.0)],
]


def test_yaw_90_degrees_gives_the_hand_typed_quaternion():
    """A 90 degree yaw is the quaternion (0, 0, sqrt(1/2), sqrt(1/2)); position is copied."""
    message = pose_to_message([1.0, 2.0, 3.0, 0.0, 0.0, math.pi / 2.0])
    assert (message.position.x, message.position.y, message.position.z) == (1.0, 2.0, 3.0)
    assert_allclose(quaternion_of(message), [0.0, 0.0, SQRT_HALF, SQRT_HALF], atol=1e-15)


def test_roll_90_degrees_gives_the_hand_typed_quaternion():
    """A 90 degree roll about x is the quaternion (sqrt(1/2), 0, 0, sqrt(1/2))."""
    message = pose_to_message([0.0, 0.0, 0.0, math.pi / 2.0, 0.0, 0.0])
    assert_allclose(quaternion_of(message), [SQRT_HALF, 0.0, 0.0, SQRT_HALF], atol=1e-15)


def test_hand_typed_quaternions_give_the_expected_angles():
    """Hand-typed quaternions of a 90 degree yaw, a -90 degree roll and no turn decode right."""
    cases = [
        ([0.0, 0.0, SQRT_HALF, SQRT_HALF], [0.0, 0.0, math.pi / 2.0]),
        ([-SQRT_HALF, 0.0, 0.0, SQRT_HALF], [-math.pi / 2.0, 0.0, 0.0]),
        ([0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0]),
        ([0.0, 0.0, 0.0, -1.0], [0.0, 0.0, 0.0]),
    ]
    for quaternion, angles in cases:
        pose = pose_from_message(raw_pose_message([0.5, -0.25, 0.125], quaternion))
        assert_allclose(pose, [0.5, -0.25, 0.125] + angles, atol=1e-15)


@pytest.mark.parametrize('pose', POSES)
def test_pose_to_message_matches_the_textbook_quaternion(pose):
    """The quaternion of a pose is the textbook roll-pitch-yaw one, unit, with w >= 0."""
    message = pose_to_message(pose)
    quaternion = quaternion_of(message)
    assert quaternion[3] >= 0.0
    assert np.linalg.norm(quaternion) == pytest.approx(1.0, abs=1e-15)
    assert_allclose(quaternion, quaternion_from_euler(*pose[3:]), atol=1e-14)


@pytest.mark.parametrize('pose', POSES)
def test_pose_round_trip(pose):
    """Pose -> message -> pose gives the pose back (angles inside the canonical ranges)."""
    assert_allclose(pose_from_message(pose_to_message(pose)), pose, atol=1e-12)


@pytest.mark.parametrize('pose', POSES)
def test_message_round_trip_and_quaternion_sign(pose):
    """Message -> pose -> message keeps the rotation; q and -q decode to the same pose."""
    quaternion = quaternion_from_euler(*pose[3:])
    for sign in (1.0, -1.0):
        message = raw_pose_message(pose[:3], sign * quaternion)
        decoded = pose_from_message(message)
        assert_allclose(decoded, pose, atol=1e-12)
        assert_allclose(quaternion_of(pose_to_message(decoded)), quaternion, atol=1e-12)


def test_w_is_never_negative():
    """Every rotation of a coarse grid of Euler angles is sent with w >= 0."""
    grid = np.radians(np.arange(-180.0, 181.0, 30.0))
    for alpha in grid:
        for beta in np.radians([-89.0, -60.0, -30.0, 0.0, 30.0, 60.0, 89.0]):
            for gamma in grid:
                message = pose_to_message([0.0, 0.0, 0.0, alpha, beta, gamma])
                assert message.orientation.w >= 0.0, (alpha, beta, gamma)


def test_position_quaternion_reports_the_norm_and_normalises():
    """A quaternion of norm 2 comes back unit, with the norm 2 reported for a warning."""
    message = raw_pose_message([0.1, 0.2, 0.3], [0.0, 0.0, 2.0 * SQRT_HALF, 2.0 * SQRT_HALF])
    position, quaternion, norm = position_quaternion_from_message(message)
    assert_allclose(position, [0.1, 0.2, 0.3], atol=0.0)
    assert_allclose(quaternion, [0.0, 0.0, SQRT_HALF, SQRT_HALF], atol=1e-15)
    assert norm == pytest.approx(2.0, abs=1e-15)


@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf])
def test_non_finite_position_is_refused(bad):
    """A NaN or infinite coordinate raises ValueError saying the position must be finite."""
    for axis in range(3):
        position = [0.0, 0.0, 0.4]
        position[axis] = bad
        with pytest.raises(ValueError, match='position must be finite'):
            pose_from_message(raw_pose_message(position, [0.0, 0.0, 0.0, 1.0]))


def test_zero_quaternion_is_refused():
    """The all-zero quaternion (an uninitialised Pose) raises ValueError naming the cause."""
    with pytest.raises(ValueError, match='zero quaternion'):
        pose_from_message(raw_pose_message([0.0, 0.0, 0.4], [0.0, 0.0, 0.0, 0.0]))
    with pytest.raises(ValueError, match='quaternion norm'):
        pose_from_message(Pose(orientation=Quaternion(x=0.0, y=0.0, z=0.0, w=0.0)))


def test_non_finite_quaternion_is_refused():
    """A NaN quaternion component raises ValueError about the quaternion."""
    with pytest.raises(ValueError, match='quaternion components must be finite'):
        pose_from_message(raw_pose_message([0.0, 0.0, 0.4], [0.0, math.nan, 0.0, 1.0]))


def test_legs_to_message_layout():
    """Six values go out as floats with one layout dimension 'leg' of size 6 and stride 6."""
    message = legs_to_message(np.array([0.7, 0.71, 0.72, 0.73, 0.74, 0.75]))
    assert list(message.data) == [0.7, 0.71, 0.72, 0.73, 0.74, 0.75]
    assert all(isinstance(value, float) for value in message.data)
    assert len(message.layout.dim) == 1
    dimension = message.layout.dim[0]
    assert (dimension.label, dimension.size, dimension.stride) == ('leg', 6, 6)
    assert message.layout.data_offset == 0


def test_legs_round_trip():
    """legs_to_message then leg_lengths_from_message returns the same six lengths."""
    lengths = [0.71885487, 0.71885488, 0.70114644, 0.71885487, 0.71885488, 0.71885488]
    assert_allclose(leg_lengths_from_message(legs_to_message(lengths)), lengths, atol=0.0)


def test_leg_lengths_without_layout():
    """A bare data array of six positive values, as from ``ros2 topic pub``, is accepted."""
    lengths = leg_lengths_from_message(lengths_message([0.6, 0.65, 0.7, 0.75, 0.8, 0.85]))
    assert_allclose(lengths, [0.6, 0.65, 0.7, 0.75, 0.8, 0.85], atol=0.0)
    assert lengths.shape == (6,)


def test_leg_lengths_honour_data_offset():
    """Values before layout.data_offset are skipped."""
    message = lengths_message([99.0, -1.0, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85], data_offset=2)
    assert_allclose(leg_lengths_from_message(message), [0.6, 0.65, 0.7, 0.75, 0.8, 0.85],
                    atol=0.0)


@pytest.mark.parametrize('count', [0, 5, 7, 12])
def test_wrong_number_of_leg_lengths_is_refused(count):
    """Anything but six values raises ValueError that says 6 were expected and how many came."""
    with pytest.raises(ValueError, match=f'expected 6 leg lengths .* got {count}'):
        leg_lengths_from_message(lengths_message([0.7] * count))


def test_data_offset_leaving_five_values_is_refused():
    """Six values with data_offset 1 leave five: refused like a short array."""
    with pytest.raises(ValueError, match='expected 6 leg lengths .* got 5'):
        leg_lengths_from_message(lengths_message([0.7] * 6, data_offset=1))


@pytest.mark.parametrize('bad', [math.nan, math.inf, -0.7, 0.0, -math.inf])
def test_a_leg_length_that_is_not_finite_and_positive_is_refused_where_it_enters(bad):
    """
    The conversion converts; the tracker, where the lengths enter the core, refuses them.

    Checked once (issue 28), not in the conversion and the tracker and the solver: fk_node's
    refusal is the sentence the conversion used to raise, word for word.
    """
    data = [0.7, 0.7, 0.7, bad, 0.7, 0.7]
    lengths = leg_lengths_from_message(lengths_message(data))
    assert lengths.shape == (6,) and lengths.dtype == np.float64
    np.testing.assert_array_equal(lengths, data)
    estimate = PoseTracker(paper_geometry()).update(lengths)
    assert not estimate.accepted and estimate.refusal.code == 'invalid_lengths'
    assert estimate.reason == f'leg lengths must be finite and positive (metres), got {data}'


@pytest.mark.parametrize('bad', [math.nan, math.inf, -1.0])
def test_a_joint_state_whose_lengths_are_not_finite_and_positive_is_refused_where_it_enters(bad):
    """Positions plus offsets are converted; the tracker refuses them, naming the lengths."""
    positions = [0.7, 0.7, bad, 0.7, 0.7, 0.7]
    message = JointState(name=[f'leg_{leg}' for leg in range(1, 7)], position=positions)
    lengths, velocities = legs_from_joint_state(message)
    np.testing.assert_array_equal(lengths, positions)
    assert velocities is None
    estimate = PoseTracker(paper_geometry()).update(lengths)
    assert estimate.refusal.code == 'invalid_lengths'
    assert estimate.reason == f'leg lengths must be finite and positive (metres), got {positions}'


def test_a_million_leg_lengths_are_refused_by_their_count_not_echoed():
    """Issue 27: the reason was 5 MB of values; now the count and the first few (one line)."""
    with pytest.raises(ValueError) as raised:
        leg_lengths_from_message(lengths_message([0.7] * 10 ** 6))
    reason = str(raised.value)
    assert len(reason) < 300 and 'got 1000000: [0.7, 0.7' in reason
    assert '(1,000,000 values)' in reason


@pytest.mark.parametrize('names, size', [
    ([f'joint_{index}' for index in range(10 ** 5)], '(100,000 values)'),
    (['n' * 10 ** 7, 'leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5'], '(10,000,000 characters)'),
], ids=['many names', 'a long name'])
def test_a_joint_state_of_oversized_names_is_refused_in_one_short_line(names, size):
    """The names of a JointState that lacks a leg are previewed, never echoed whole."""
    message = JointState(name=names, position=[0.7] * len(names))
    with pytest.raises(ValueError, match='missing') as raised:
        legs_from_joint_state(message)
    assert len(str(raised.value)) < 600 and size in str(raised.value)
