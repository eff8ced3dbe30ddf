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
The frame tree: transforms, user and tool frames, and the pivot point they replace.

Expected values come from points mapped one frame at a time, by hand, or from the geometry with
the pivot built in, as the package computed it before the tool frame existed.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import inverse_kinematics, leg_lengths, load_geometry
from stewart_kinematics.model.frames import FrameTree, IDENTITY, Transform
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import frames_from_parameters

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
#: A tool 0.1 m above the platform frame's origin, tilted; a user frame beside the base.
TOOL = Transform.from_pose([0.02, -0.01, 0.1, 0.1, -0.2, 0.3])
USER = Transform.from_pose([0.5, -0.2, 0.05, 0.0, 0.0, math.pi / 2])
POINTS = np.array([[0.0, 0.0, 0.0], [0.1, -0.3, 0.7], [-1.0, 2.0, 0.5]])


def tree(**kwargs):
    """Return a frame tree with the names of the paper's platform and the given frames."""
    return FrameTree(base_frame='stewart_base', platform_frame='stewart_platform', **kwargs)


def test_composition_maps_points_one_frame_at_a_time():
    """(T_a_b @ T_b_c) applied to a point equals T_a_b applied to T_b_c applied to it."""
    composed = USER @ TOOL
    assert_allclose(composed.apply(POINTS), USER.apply(TOOL.apply(POINTS)), rtol=0, atol=1e-15)
    assert_allclose(TOOL.inverse().apply(TOOL.apply(POINTS)), POINTS, rtol=0, atol=1e-15)
    assert (TOOL @ TOOL.inverse()).as_pose() == pytest.approx(np.zeros(6), abs=1e-15)


def test_a_pose_vector_round_trips_and_zeros_are_the_identity():
    """from_pose/as_pose round trip, and an all-zero pose is IDENTITY itself (no work)."""
    pose = np.array([0.1, 0.2, 0.3, 0.4, -0.5, 0.6])
    assert_allclose(Transform.from_pose(pose).as_pose(), pose, rtol=0, atol=1e-15)
    assert Transform.from_pose(np.zeros(6)) is IDENTITY
    assert IDENTITY.is_identity() and not TOOL.is_identity()


@pytest.mark.parametrize('position, rotation, message', [
    ([0.0, 0.0], np.eye(3), 'shape'),
    ([0.0, 0.0, math.nan], np.eye(3), 'finite'),
    ([0.0, 0.0, 0.0], 2.0 * np.eye(3), 'proper rotation'),
    ([0.0, 0.0, 0.0], np.diag([1.0, 1.0, -1.0]), 'proper rotation'),
])
def test_a_transform_refuses_what_is_not_rigid(position, rotation, message):
    """Wrong shapes, NaN and matrices that are not rotations are refused on construction."""
    with pytest.raises(ValueError, match=message):
        Transform(position, rotation)


def test_the_tool_origin_is_the_pivot_point():
    """A pure rotation of the commanded tool frame leaves the tool origin where it was."""
    frames = tree(tool_pose=Transform([0.02, -0.01, 0.1], np.eye(3)))
    where = np.array([0.0, 0.0, 0.5325])
    for angles in ([0.0, 0.0, 0.0], [0.2, -0.1, 0.3], [0.0, 0.0, 1.0]):
        platform = frames.platform_from_tool(Transform(where, euler_zyx_to_matrix(angles)))
        assert_allclose(platform.apply([0.02, -0.01, 0.1]), where, rtol=0, atol=1e-15)


def test_the_tool_frame_gives_the_lengths_of_the_old_pivot_point():
    """
    A tool frame at c commands the lengths the geometry with the pivot c built in gave.

    Before the tool frame, a pivot point c made the platform joints p_i - c; the same poses
    must give the same lengths now, through the frame tree and the plain geometry.
    """
    geometry = load_geometry(CONFIG / 'paper_platform.yaml')
    pivot = np.array([0.02, -0.01, 0.3])
    pivoted = Geometry(geometry.base_joints, geometry.platform_joints - pivot,
                       geometry.home_pose + np.r_[pivot, 0.0, 0.0, 0.0])
    frames = tree(tool_pose=Transform(pivot, np.eye(3)))
    for pose in ([0.0, 0.0, 0.7325, 0.0, 0.0, 0.0], [0.05, -0.03, 0.72, 0.1, -0.15, 0.2]):
        platform = frames.platform_from_tool(Transform.from_pose(pose))
        assert_allclose(leg_lengths(geometry, platform.position, platform.rotation),
                        inverse_kinematics(pivoted, pose), rtol=0, atol=1e-14)


def test_a_target_in_the_user_frame_is_placed_through_it():
    """A tool pose in the user frame, by hand: the user frame turned 90 deg about z, shifted."""
    frames = tree(user_frame='work_piece', user_pose=USER)
    platform = frames.platform_from_tool(Transform([0.1, 0.0, 0.4], np.eye(3)), 'work_piece')
    # x of the user frame is y of the base: (0.1, 0, 0.4) in it is (0.5, -0.1, 0.45) in base.
    assert_allclose(platform.position, [0.5, -0.1, 0.45], rtol=0, atol=1e-15)
    assert_allclose(platform.rotation, USER.rotation, rtol=0, atol=1e-15)


@pytest.mark.parametrize('frame_id', ['', 'stewart_base', 'work_piece'])
def test_estimated_tool_pose_inverts_the_commanded_one(frame_id):
    """tool_from_platform undoes platform_from_tool in every accepted frame."""
    frames = tree(user_frame='work_piece', user_pose=USER, tool_frame='tcp', tool_pose=TOOL)
    commanded = Transform.from_pose([0.1, 0.05, 0.3, 0.2, 0.1, -0.3])
    estimated = frames.tool_from_platform(frames.platform_from_tool(commanded, frame_id),
                                          frame_id)
    assert_allclose(estimated.as_pose(), commanded.as_pose(), rtol=0, atol=1e-14)


def test_a_pose_in_another_frame_is_refused_with_the_accepted_ones():
    """Only the base frame, the user frame and '' are accepted, and the reason says so."""
    with pytest.raises(ValueError, match="'camera', not in base_frame 'stewart_base'; trans"):
        tree().reference('camera')
    with pytest.raises(ValueError, match="base_frame 'stewart_base' or user_frame 'work'"):
        tree(user_frame='work', user_pose=USER).tool_from_platform(TOOL, 'camera')


def test_static_transforms_are_those_of_named_frames():
    """/tf_static gets the user frame from the base, the tool frame from the platform."""
    assert tree(tool_pose=TOOL).static_transforms() == []
    frames = tree(user_frame='work', user_pose=USER, tool_frame='tcp', tool_pose=TOOL)
    assert frames.static_transforms() == [('stewart_base', 'work', USER),
                                          ('stewart_platform', 'tcp', TOOL)]
    moved = frames.with_tool('gripper', IDENTITY)
    assert moved.static_transforms()[1] == ('stewart_platform', 'gripper', IDENTITY)
    assert frames.tool_frame == 'tcp'   # trees are immutable: a node swaps them whole


def test_frame_names_must_differ():
    """A user or tool frame named like the base or the platform is refused."""
    with pytest.raises(ValueError, match='frame names must differ'):
        tree(user_frame='stewart_platform')


def test_frames_from_parameters_reads_degrees_and_names():
    """Parameter values (metres, degrees) give the tree; bad names are refused."""
    frames = frames_from_parameters({
        'user_frame': 'work', 'user_frame_position': [0.5, -0.2, 0.05],
        'user_frame_orientation_deg': [0.0, 0.0, 90.0], 'tool_frame': 'tcp',
        'tool_frame_position': [0.02, -0.01, 0.1]})
    assert (frames.base_frame, frames.platform_frame) == ('stewart_base', 'stewart_platform')
    assert_allclose(frames.user_pose.as_pose(), USER.as_pose(), rtol=0, atol=1e-15)
    assert_allclose(frames.tool_pose.position, [0.02, -0.01, 0.1], rtol=0, atol=0)
    assert frames_from_parameters({}).tool_pose is IDENTITY
    with pytest.raises(ValueError, match="'tool_frame' must be a frame name"):
        frames_from_parameters({'tool_frame': '/tcp'})


def test_the_array_forms_agree_with_the_transforms_and_skip_the_identity():
    """platform_in_base, tool_pose_vector, platform_pose_vectors: same numbers, no-op cases."""
    frames = tree(user_frame='work', user_pose=USER, tool_frame='tcp', tool_pose=TOOL)
    tool = Transform.from_pose([0.1, 0.05, 0.3, 0.2, 0.1, -0.3])
    position, rotation = frames.platform_in_base(tool.position, tool.rotation, 'work')
    expected = frames.platform_from_tool(tool, 'work')
    assert_allclose(position, expected.position, rtol=0, atol=1e-15)
    assert_allclose(rotation, expected.rotation, rtol=0, atol=1e-15)
    platform_pose = expected.as_pose()
    assert_allclose(frames.tool_pose_vector(platform_pose, 'work'), tool.as_pose(), rtol=0,
                    atol=1e-14)
    assert_allclose(frames.platform_pose_vectors([tool.as_pose()] * 2),
                    [frames.platform_from_tool(tool).as_pose()] * 2, rtol=0, atol=1e-15)

    plain = tree()
    pose = np.array([0.1, 0.0, 0.4, 0.0, 0.1, 0.0])
    assert plain.tool_pose_vector(pose) is pose
    assert plain.platform_in_base(pose[:3], rotation, '')[1] is rotation
    with pytest.raises(ValueError, match="'camera'"):
        plain.platform_in_base(pose[:3], rotation, 'camera')


def _platform_motion(t):
    """Return a smooth platform motion: position and rotation at time t (base frame)."""
    pose = np.array([0.01 * math.sin(t), -0.02 * t, 0.45 + 0.01 * t * t,
                     0.1 * math.sin(2.0 * t), -0.05 * t, 0.2 * math.cos(t)])
    return pose[:3], euler_zyx_to_matrix(pose[3:])


def _derivatives(function, t, step=1e-4):
    """Return central differences of a function of time returning (position, rotation)."""
    (p_after, _), (p_now, _), (p_before, _) = function(t + step), function(t), function(t - step)
    velocity = (p_after - p_before) / (2.0 * step)
    acceleration = (p_after - 2.0 * p_now + p_before) / step ** 2

    def omega(time):
        (_, after), (_, before) = function(time + step), function(time - step)
        skew = (after - before) / (2.0 * step) @ function(time)[1].T
        return np.array([skew[2, 1], skew[0, 2], skew[1, 0]])
    return velocity, omega(t), acceleration, (omega(t + step) - omega(t - step)) / (2.0 * step)


def test_a_tool_frame_motion_moves_to_the_platform_frame_with_its_derivatives():
    """Poses, twists and accelerations of a tool in the user frame: finite differences."""
    tool = Transform([0.03, -0.02, 0.08], euler_zyx_to_matrix([0.2, -0.1, 0.5]))
    user = Transform([0.1, 0.2, -0.05], euler_zyx_to_matrix([0.0, 0.0, 0.7]))
    frames = FrameTree(user_frame='work', user_pose=user, tool_frame='tool', tool_pose=tool)

    def tool_in_user(t):
        placed = user.inverse() @ Transform(*_platform_motion(t)) @ tool
        return placed.position, placed.rotation
    times = [0.3, 1.1, 2.0]
    given = [tool_in_user(t) for t in times]
    motion = [_derivatives(tool_in_user, t) for t in times]
    positions, rotations, *derivatives = frames.platform_motion(
        [p for p, _ in given], [r for _, r in given],
        *(np.array([m[k] for m in motion]) for k in range(4)), frame_id='work')
    for index, t in enumerate(times):
        position, rotation = _platform_motion(t)
        assert_allclose(positions[index], position, atol=1e-12)
        assert_allclose(rotations[index], rotation, atol=1e-12)
        for computed, expected in zip(derivatives, _derivatives(_platform_motion, t)):
            assert_allclose(computed[index], expected, atol=1e-6)
    with pytest.raises(ValueError, match="not in base_frame 'stewart_base' or user_frame"):
        frames.platform_motion([[0.0, 0.0, 0.5]], [np.eye(3)], frame_id='elsewhere')


def test_a_twist_moves_between_the_platform_origin_and_the_tool_point():
    """v_tool = v + w x (R p_tool), by finite differences of the tool's position."""
    tool = Transform([0.03, -0.02, 0.08], euler_zyx_to_matrix([0.2, -0.1, 0.5]))
    frames = FrameTree(tool_frame='tool', tool_pose=tool)

    def tool_motion(t):
        placed = Transform(*_platform_motion(t)) @ tool
        return placed.position, placed.rotation
    t = 0.7
    platform_twist = np.concatenate(_derivatives(_platform_motion, t)[:2])
    tool_twist = np.concatenate(_derivatives(tool_motion, t)[:2])
    rotation = _platform_motion(t)[1]
    assert_allclose(frames.tool_twist_from_platform(platform_twist, rotation), tool_twist,
                    atol=1e-7)
    assert_allclose(frames.platform_twist_from_tool(tool_twist, rotation), platform_twist,
                    atol=1e-7)
    plain = FrameTree()
    assert plain.tool_twist_from_platform(platform_twist, rotation) is not None
    assert_allclose(plain.platform_twist_from_tool(tool_twist, rotation), tool_twist)
