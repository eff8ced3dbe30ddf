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
In-process tests of trajectory_node's planning: every message answered, by the worker thread.

Real rclpy, the node with the shipped platform and example limits and no ramp, a probe that
publishes trajectories and records leg_trajectory. Expected leg lengths come from the textbook
formula of test/reference.py at the platform poses the tool poses put it in.
"""

import math
from pathlib import Path

from builtin_interfaces.msg import Duration
from geometry_msgs.msg import Transform, Twist
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.node import Node
from rclpy.parameter import Parameter
import reference

from stewart_kinematics.ros.node_main import create_executor
from stewart_kinematics.ros.trajectory_node import TrajectoryNode
from trajectory_msgs.msg import (
    JointTrajectory,
    MultiDOFJointTrajectory,
    MultiDOFJointTrajectoryPoint,
)

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
ARGS = ['--ros-args', '--params-file', str(CONFIG_DIRECTORY / 'paper_platform.yaml'),
        '--params-file', str(CONFIG_DIRECTORY / 'example_limits.yaml'), '-p', "mode:='off'",
        '-p', 'publish_rate:=20.0']
HOME = np.array(reference.HOME)
TOOL_POSITION = [0.02, -0.01, 0.06]
TOOL_ORIENTATION_DEG = [0.0, 5.0, 20.0]


def quaternion(rotation):
    """Quaternion ``(x, y, z, w)`` of a rotation matrix with a positive trace."""
    w = math.sqrt(1.0 + np.trace(rotation)) / 2.0
    return ((rotation[2, 1] - rotation[1, 2]) / (4.0 * w),
            (rotation[0, 2] - rotation[2, 0]) / (4.0 * w),
            (rotation[1, 0] - rotation[0, 1]) / (4.0 * w), w)


def trajectory_message(times, poses, joints=('platform',), quaternions=None):
    """Build a MultiDOFJointTrajectory through ``[X, Y, Z, alpha, beta, gamma]`` poses."""
    message = MultiDOFJointTrajectory(joint_names=list(joints))
    for index, (time, pose) in enumerate(zip(times, poses)):
        transform = Transform()
        transform.translation.x, transform.translation.y, transform.translation.z = (
            float(v) for v in pose[:3])
        r = transform.rotation
        r.x, r.y, r.z, r.w = (quaternions[index] if quaternions is not None
                              else reference.quaternion_from_euler(*pose[3:]))
        nanoseconds = int(round(time * 1e9))
        message.points.append(MultiDOFJointTrajectoryPoint(
            transforms=[transform], time_from_start=Duration(
                sec=nanoseconds // 10 ** 9, nanosec=nanoseconds % 10 ** 9)))
    return message


@pytest.fixture
def start(ros, spin_until):
    """Return a starter of trajectory_nodes (by namespace and overrides) with one probe."""
    executor = create_executor()
    probe = Node('planning_probe')
    executor.add_node(probe)
    created = [probe]
    received = {}

    def start_node(namespace, overrides=()):
        node = TrajectoryNode(cli_args=ARGS, namespace=namespace, parameter_overrides=[
            Parameter(name, value=value) for name, value in overrides])
        created.append(node)
        executor.add_node(node)
        received[namespace] = []
        probe.create_subscription(JointTrajectory, f'{namespace}/leg_trajectory',
                                  received[namespace].append, 10)
        publisher = probe.create_publisher(MultiDOFJointTrajectory,
                                           f'{namespace}/pose_trajectory', 10)
        assert spin_until(executor, lambda: publisher.get_subscription_count() >= 1 and (
            node.leg_trajectory_publisher.get_subscription_count() >= 1))
        return node, publisher, received[namespace]
    yield start_node, executor
    executor.shutdown()
    for node in created:
        node.destroy_node()


def lift(times):
    """Home, 2 cm up, home, at ``times``."""
    return trajectory_message(times, [HOME, HOME + [0.0, 0.0, 0.02, 0.0, 0.0, 0.0], HOME])


def test_every_malformed_trajectory_is_answered_and_the_node_goes_on(start, spin_until):
    """No point, one point, two joints, a NaN, a zero quaternion, a time of 2^31 - 1 s."""
    start_node, executor = start
    node, publisher, received = start_node('/bad')
    nan_pose = np.array(HOME)
    nan_pose[0] = math.nan
    bad = [
        MultiDOFJointTrajectory(),
        trajectory_message([0.0], [HOME]),
        trajectory_message([0.0, 1.0], [HOME, HOME], joints=('a', 'b')),
        trajectory_message([0.0, 1.0], [HOME, nan_pose]),
        trajectory_message([0.0, 1.0], [HOME, HOME], quaternions=[(0, 0, 0, 1), (0, 0, 0, 0)]),
        lift([0.0, 10.0, 2.0 ** 31 - 1.0]),
    ]
    accounting = node.trajectory_accounting
    for count, message in enumerate(bad, start=1):
        # One at a time: a newer message would replace one not yet decided.
        publisher.publish(message)
        assert spin_until(executor, lambda: accounting.rejected >= count), (
            accounting.rejections_by_code)
    assert accounting.rejections_by_code == {'invalid_trajectory': len(bad)}
    assert 'point 2 has time 2147483647.0 s' in accounting.last_rejection.message
    publisher.publish(lift([0.0, 5.0, 10.0]))
    assert spin_until(executor, lambda: received)
    assert accounting.published == 1


def test_a_newer_trajectory_replaces_the_one_being_planned(start, spin_until):
    """A 10^4 s trajectory of 3000 waypoints, then a short one: the first is superseded."""
    start_node, executor = start
    node, publisher, received = start_node('/replace')
    times = np.linspace(0.0, 1e4, 3000)
    waves = HOME + 0.01 * np.outer(1.0 - np.cos(2.0 * math.pi * times / 1e4),
                                   [1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
    publisher.publish(trajectory_message(times, waves))
    publisher.publish(lift([0.0, 5.0, 10.0]))
    accounting = node.trajectory_accounting
    assert spin_until(executor, lambda: received and accounting.rejected >= 1)
    assert accounting.rejections_by_code == {'superseded': 1}
    assert len(received) == 1 and received[0].points[-1].time_from_start.sec == 10


def test_a_tool_frame_set_at_run_time_plans_like_one_set_at_start_up(start, spin_until):
    """The same tool-frame trajectory to both nodes: the same legs, those of the tool pose."""
    start_node, executor = start
    tool = [('tool_frame_position', TOOL_POSITION),
            ('tool_frame_orientation_deg', TOOL_ORIENTATION_DEG)]
    started, started_publisher, started_received = start_node('/at_start', tool)
    changed, changed_publisher, changed_received = start_node('/at_run_time')
    results = changed.set_parameters([Parameter(name, value=value) for name, value in tool])
    assert all(result.successful for result in results)
    tool_poses = HOME + [0.0, 0.0, 0.06, 0.0, 0.0, 0.0] + np.array(
        [[0.0] * 6, [0.01, 0.0, 0.01, 0.0, 0.03, 0.05], [0.0, -0.01, 0.0, 0.04, 0.0, 0.0]])
    times = [0.0, 4.0, 8.0]
    for publisher in (started_publisher, changed_publisher):
        publisher.publish(trajectory_message(times, tool_poses))
    assert spin_until(executor, lambda: started_received and changed_received)
    first, second = started_received[0], changed_received[0]
    assert [p.time_from_start for p in first.points] == [p.time_from_start
                                                         for p in second.points]
    assert_allclose([p.positions for p in first.points], [p.positions for p in second.points],
                    rtol=0, atol=1e-12)
    # At the waypoints: the legs of the platform pose that puts the tool at the tool pose.
    tool_rotation = reference.rotation_zyx(*np.radians(TOOL_ORIENTATION_DEG))
    at = {round(p.time_from_start.sec + p.time_from_start.nanosec * 1e-9, 6): p.positions
          for p in first.points}
    for time, pose in zip(times, tool_poses):
        platform_rotation = reference.rotation_zyx(*pose[3:]) @ tool_rotation.T
        platform_position = pose[:3] - platform_rotation @ TOOL_POSITION
        lengths = [np.linalg.norm(platform_position + platform_rotation @ p - b) for b, p in zip(
            reference.BASE_JOINTS, reference.PLATFORM_JOINTS)]
        assert_allclose(at[time], lengths, rtol=0, atol=1e-9)


def test_twists_given_with_a_trajectory_are_about_the_tool_point(start, spin_until):
    """A tool frame turning about its own origin: the platform origin moves, legs follow."""
    start_node, executor = start
    node, publisher, received = start_node('/twists', [
        ('tool_frame_position', TOOL_POSITION)])
    # The tool turns about z at 0.02 rad/s through its origin, from rest to rest.
    times = np.linspace(0.0, 10.0, 11)
    angles = 0.1 * (1.0 - np.cos(math.pi * times / 10.0))
    rates = 0.1 * math.pi / 10.0 * np.sin(math.pi * times / 10.0)
    poses = np.tile(HOME + [0.0, 0.0, 0.06, 0.0, 0.0, 0.0], (11, 1))
    poses[:, 5] = angles
    message = trajectory_message(times, poses)
    for point, rate in zip(message.points, rates):
        point.velocities = [Twist()]
        point.velocities[0].angular.z = float(rate)
    publisher.publish(message)
    assert spin_until(executor, lambda: received), node.trajectory_accounting.rejections_by_code
    points = received[0].points
    times_out = np.array([p.time_from_start.sec + p.time_from_start.nanosec * 1e-9
                          for p in points])
    positions = np.array([p.positions for p in points])
    velocities = np.array([p.velocities for p in points])
    # The leg velocities published agree with the legs' own finite differences.
    middle = slice(1, -1)
    differences = (positions[2:] - positions[:-2]) / (times_out[2:] - times_out[:-2])[:, None]
    assert_allclose(velocities[middle], differences, rtol=0, atol=2e-5)
