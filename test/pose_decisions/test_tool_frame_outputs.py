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
The tool frame in the decisions that produce the nodes' outputs, not in the nodes (issue 28).

ik_node's twists (:meth:`CommandCheck.tool_twist`) and fk_node's estimated pose, stamped pose
and twist (:class:`PoseTracker` with its frames; :attr:`PoseEstimate.tool_pose`,
``framed_tool_pose``, ``tool_twist``) are compared with the rigid-body formulas written here
(``p_tool = p + R d``, ``v_tool = v + w x (R d)``), and with the user frame's inverse.
fk_node's margin rounds (:meth:`PoseTracker.follow_margin`) run against a stand-in monitor.
"""

import math
from pathlib import Path

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose
from properties import budget
import pytest
import reference

from stewart_kinematics import (
    ActuatorLimits,
    CommandCheck,
    FrameTree,
    load_geometry,
    PoseTracker,
    Transform,
)
from stewart_kinematics.analysis.assembly_modes import AssemblyModeMargin

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
LIMITED = load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])
LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
HOME = np.array(reference.HOME)
#: A tool 0.1 m above the platform's origin and 0.02 m aside, turned 30 degrees about z.
TOOL_OFFSET = np.array([0.02, 0.0, 0.1])
TOOL = Transform(TOOL_OFFSET, reference.rotation_zyx(0.0, 0.0, math.radians(30.0)))
#: A user frame 1 m ahead, turned 90 degrees about z.
USER = Transform([1.0, 0.0, 0.0], reference.rotation_zyx(0.0, 0.0, math.pi / 2))
FRAMES = FrameTree(user_frame='work', user_pose=USER, tool_frame='tool', tool_pose=TOOL)
POSE = HOME + [0.01, -0.02, 0.01, math.radians(3.0), math.radians(-2.0), math.radians(10.0)]


def tool_position(pose):
    """Return the tool frame's origin in the base frame at a platform pose: p + R d."""
    return pose[:3] + reference.rotation_zyx(*pose[3:]) @ TOOL_OFFSET


def tool_point_twist(platform_twist, pose):
    """Return the velocity of the tool's origin and the angular velocity: [v + w x R d, w]."""
    offset = reference.rotation_zyx(*pose[3:]) @ TOOL_OFFSET
    return np.concatenate([platform_twist[:3] + np.cross(platform_twist[3:], offset),
                           platform_twist[3:]])


def test_a_tool_twist_is_moved_to_the_platform_origin_before_its_leg_velocities():
    """tool_twist(t) gives the leg velocities of the platform twist whose tool point moves at t."""
    check = CommandCheck(LIMITED, LIMITS, twist_over_limit='scale')
    assert check.pose_vector(POSE).accepted
    platform_twist = np.array([0.002, -0.001, 0.001, 0.01, -0.02, 0.015])
    given_twist = tool_point_twist(platform_twist, POSE)
    command = check.tool_twist(given_twist, FRAMES)
    assert command.accepted and command.scale == 1.0
    assert_allclose(command.velocities, reference.twist_jacobian(POSE) @ platform_twist,
                    rtol=0.0, atol=1e-12)
    # Without frames it is the platform's own twist, as twist() takes it.
    assert_allclose(check.tool_twist(platform_twist).velocities,
                    check.twist(platform_twist).velocities, rtol=0.0, atol=0.0)


def test_a_bad_tool_twist_is_refused_with_the_values_given_not_the_moved_ones():
    """NaN, huge or misshapen: invalid_twist naming what came; before any pose: no_pose_yet."""
    check = CommandCheck(LIMITED, LIMITS)
    assert check.tool_twist([0.0] * 6, FRAMES).refusal.code == 'no_pose_yet'
    check.pose_vector(POSE)
    nan = check.tool_twist([math.nan, 0.0, 0.0, 0.0, 0.0, 0.0], FRAMES)
    assert nan.refusal.code == 'invalid_twist' and 'nan, 0.0, 0.0, 0.0, 0.0, 0.0' in nan.reason
    huge = check.tool_twist([0.0, 0.0, 0.0, 0.0, 0.0, 2e3], FRAMES)
    assert huge.refusal.code == 'invalid_twist' and '2000.0' in huge.reason
    assert check.tool_twist([0.0] * 5, FRAMES).refusal.code == 'invalid_twist'


def test_a_fast_tool_twist_is_scaled_as_a_whole():
    """Scaled at the platform origin, by one factor: its tool point's velocity scales with it."""
    check = CommandCheck(LIMITED, LIMITS, twist_over_limit='scale')
    check.pose_vector(POSE)
    platform_twist = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 2.0])
    command = check.tool_twist(tool_point_twist(platform_twist, POSE), FRAMES)
    assert command.accepted and 0.0 < command.scale < 1.0
    assert np.max(np.abs(command.velocities)) == pytest.approx(0.05, rel=1e-9)
    assert_allclose(command.velocities,
                    command.scale * reference.twist_jacobian(POSE) @ platform_twist,
                    rtol=1e-12, atol=1e-15)


def test_an_estimate_carries_the_tool_frames_pose_in_the_base_and_the_user_frame():
    """tool_pose: p + R d and R R_tool; framed_tool_pose: the same seen from the user frame."""
    tracker = PoseTracker(LIMITED, frames=FRAMES, pose_frame='work')
    estimate = tracker.update(reference.leg_lengths(POSE))
    assert estimate.accepted and estimate.pose_frame == 'work'
    rotation = reference.rotation_zyx(*POSE[3:]) @ TOOL.rotation
    tool = estimate.tool_pose
    assert_allclose(tool[:3], tool_position(POSE), rtol=0.0, atol=1e-9)
    assert_allclose(reference.rotation_zyx(*tool[3:]), rotation, rtol=0.0, atol=1e-9)
    framed = estimate.framed_tool_pose
    assert_allclose(framed[:3], USER.rotation.T @ (tool_position(POSE) - USER.position),
                    rtol=0.0, atol=1e-9)
    assert_allclose(reference.rotation_zyx(*framed[3:]), USER.rotation.T @ rotation,
                    rtol=0.0, atol=1e-9)


def test_the_stamped_pose_frame_is_the_base_frame_by_default_and_must_be_placeable():
    """'' is the base frame's name; a frame the tree cannot place fails the start, named."""
    tracker = PoseTracker(LIMITED, frames=FRAMES)
    assert tracker.pose_frame == 'stewart_base'
    estimate = tracker.update(reference.leg_lengths(POSE))
    assert_allclose(estimate.framed_tool_pose, estimate.tool_pose, rtol=0.0, atol=0.0)
    with pytest.raises(ValueError, match="'odom'"):
        PoseTracker(LIMITED, frames=FRAMES, pose_frame='odom')
    plain = PoseTracker(LIMITED).update(reference.leg_lengths(POSE))
    assert_allclose(plain.tool_pose, plain.pose, rtol=0.0, atol=0.0)
    assert plain.pose_frame == 'stewart_base'


def test_a_refused_estimate_has_no_tool_pose_nor_twist():
    """Lengths beyond the stroke: every output None, nothing to publish."""
    tracker = PoseTracker(LIMITED, frames=FRAMES)
    refused = tracker.update(np.full(6, 2.0), np.zeros(6))
    assert not refused.accepted
    assert refused.tool_pose is None and refused.framed_tool_pose is None
    assert refused.tool_twist is None


def test_twists_are_given_about_the_tool_frames_origin():
    """PoseEstimate.tool_twist (a joint state) and TwistEstimate.tool_twist (leg velocities)."""
    tracker = PoseTracker(LIMITED, frames=FRAMES)
    platform_twist = np.array([0.003, 0.001, -0.002, 0.02, -0.01, 0.03])
    velocities = reference.twist_jacobian(POSE) @ platform_twist
    estimate = tracker.update(reference.leg_lengths(POSE), velocities)
    assert_allclose(estimate.twist, platform_twist, rtol=0.0, atol=1e-9)
    assert_allclose(estimate.tool_twist, tool_point_twist(platform_twist, POSE),
                    rtol=0.0, atol=1e-9)
    twist = tracker.twist(velocities)
    assert_allclose(twist.tool_twist, tool_point_twist(platform_twist, POSE), rtol=0.0,
                    atol=1e-9)
    assert tracker.twist([math.nan] * 6).tool_twist is None


def test_a_new_tool_frame_applies_from_the_next_estimate_and_a_bad_one_changes_nothing():
    """set_frames: the next tool_pose is the new tool's; an unplaceable frame raises, kept."""
    tracker = PoseTracker(LIMITED, frames=FRAMES, pose_frame='work')
    before = tracker.update(reference.leg_lengths(POSE))
    tracker.set_frames(FRAMES.with_tool('', Transform([0.0, 0.0, 0.0], np.eye(3))))
    after = tracker.update(reference.leg_lengths(POSE))
    assert_allclose(after.tool_pose, after.pose, rtol=0.0, atol=1e-12)
    assert_allclose(before.tool_pose[:3], tool_position(POSE), rtol=0.0, atol=1e-9)
    with pytest.raises(ValueError, match="'work'"):
        tracker.set_frames(FrameTree())   # no user frame: 'work' cannot be placed
    assert tracker.frames.user_frame == 'work' and tracker.pose_frame == 'work'
    with pytest.raises(TypeError, match='FrameTree'):
        tracker.set_frames('tool')


def test_an_anchor_is_read_in_the_trackers_own_frames_by_default():
    """anchor_tool_pose without frames: the tracker's tool and user frames apply."""
    tracker = PoseTracker(LIMITED, frames=FRAMES)
    estimate = tracker.update(reference.leg_lengths(POSE))
    position, quaternion = estimate.tool_pose[:3], reference.quaternion_from_euler(
        *estimate.tool_pose[3:])
    anchor = tracker.anchor_tool_pose(position, quaternion, frame_id='stewart_base')
    assert anchor.accepted
    assert_allclose(anchor.pose, POSE, rtol=0.0, atol=1e-9)
    refused = tracker.anchor_tool_pose(position, quaternion, frame_id='odom')
    assert refused.refusal.code == 'wrong_frame'


class Monitor:
    """Stands in for AssemblyModeMarginMonitor: records requests, reports a margin when told."""

    def __init__(self):
        self.requests = []
        self.latest = self.latest_tag = self.latest_lengths = None
        self.warning_distance = 0.05

    def request(self, pose, lengths, tag=None):
        self.requests.append((None if pose is None else np.array(pose), lengths, tag))
        return True


def test_a_margin_round_asks_for_the_last_pose_and_takes_the_latest_margin():
    """follow_margin: the request carries the last pose and its number; a margin then clears."""
    tracker = PoseTracker(LIMITED)
    monitor = Monitor()
    assert not tracker.follow_margin(monitor)       # nothing reported yet
    tracker.update(reference.leg_lengths(POSE))
    assert not tracker.follow_margin(monitor)
    pose, lengths, tag = monitor.requests[-1]
    assert_allclose(pose, POSE, rtol=0.0, atol=1e-9) and tag == tracker.accepted_count == 1
    # A near margin reported for that pose flags the estimate; a unique one later clears it.
    monitor.latest = AssemblyModeMargin(0.01, 0.1, 0.02, None, 2, True, '')
    monitor.latest_tag, monitor.latest_lengths = 1, lengths
    assert not tracker.follow_margin(monitor) and tracker.ambiguous
    tracker.update(reference.leg_lengths(POSE + [0.001, 0, 0, 0, 0, 0]))
    monitor.latest = AssemblyModeMargin(math.inf, math.inf, math.inf, None, 1, True, '')
    monitor.latest_tag, monitor.latest_lengths = 2, None
    assert tracker.follow_margin(monitor) and not tracker.ambiguous


def test_a_joint_state_of_another_platform_is_not_ours():
    """ActuatorInterface.concerns: any of our joints named; none named: another platform's."""
    from stewart_kinematics import ActuatorInterface
    actuators = ActuatorInterface(('a1', 'a2', 'a3', 'a4', 'a5', 'a6'))
    assert actuators.concerns(['x', 'a4'])
    assert not actuators.concerns(['leg_1', 'leg_2'])
    assert not actuators.concerns([])


@budget(20)
@given(st.lists(st.floats(-0.05, 0.05), min_size=6, max_size=6))
def test_tool_twist_and_twist_agree_through_the_frame_formula(values):
    """For any small platform twist: tool_twist of its tool-point twist equals twist of it."""
    check = CommandCheck(LIMITED, LIMITS, twist_over_limit='scale')
    check.pose_vector(POSE)
    platform_twist = np.array(values)
    by_tool = check.tool_twist(tool_point_twist(platform_twist, POSE), FRAMES)
    direct = check.twist(platform_twist)
    assert by_tool.accepted == direct.accepted
    if direct.accepted:
        assert_allclose(by_tool.velocities, direct.velocities, rtol=1e-9, atol=1e-15)
