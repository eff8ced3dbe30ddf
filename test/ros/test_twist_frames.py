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
Twists are about the tool frame's point, like every pose topic: ik_node and fk_node in-process.

The platform moves along a straight line in pose coordinates; its tool frame sits 8 cm above
and to the side, turned. The expected twists are finite differences of the tool frame's pose
(the textbook formulas of test/reference.py), the expected leg velocities finite differences of
the legs' lengths: nothing comes from the package.
"""

import math
from pathlib import Path

from geometry_msgs.msg import Pose, Twist
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.node import Node
from rclpy.parameter import Parameter
import reference
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray

from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.node_main import create_executor

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
ARGS = ['--ros-args', '--params-file', str(CONFIG_DIRECTORY / 'paper_platform.yaml'),
        '--params-file', str(CONFIG_DIRECTORY / 'solver.yaml')]
TOOL_POSITION = [0.03, -0.02, 0.08]
TOOL_ORIENTATION_DEG = [10.0, -5.0, 30.0]
#: The platform's pose at t: home plus t times this, per second (metres, radians).
RATE = np.array([0.01, -0.02, 0.015, 0.05, -0.04, 0.08])
TIME = 0.5
STEP = 1e-5


def platform_pose(t):
    """Return the platform's pose ``[X, Y, Z, alpha, beta, gamma]`` at time t."""
    return np.array(reference.HOME) + t * RATE


def tool_pose(t):
    """Return the tool frame's position and rotation in the base frame at time t."""
    pose = platform_pose(t)
    rotation = reference.rotation_zyx(*pose[3:])
    tool_rotation = reference.rotation_zyx(*np.radians(TOOL_ORIENTATION_DEG))
    return pose[:3] + rotation @ TOOL_POSITION, rotation @ tool_rotation


def tool_twist(t):
    """Return the tool frame's origin velocity and angular velocity by central differences."""
    (p_after, r_after), (p_before, r_before) = tool_pose(t + STEP), tool_pose(t - STEP)
    skew = (r_after - r_before) / (2.0 * STEP) @ tool_pose(t)[1].T
    return np.concatenate([(p_after - p_before) / (2.0 * STEP),
                           [skew[2, 1], skew[0, 2], skew[1, 0]]])


def leg_velocities(t):
    """Return the legs' velocities by central differences of their lengths."""
    return (np.array(reference.leg_lengths(platform_pose(t + STEP)))
            - reference.leg_lengths(platform_pose(t - STEP))) / (2.0 * STEP)


def quaternion(rotation):
    """Quaternion ``(x, y, z, w)`` of a rotation matrix with a positive trace."""
    w = math.sqrt(1.0 + np.trace(rotation)) / 2.0
    return ((rotation[2, 1] - rotation[1, 2]) / (4.0 * w),
            (rotation[0, 2] - rotation[2, 0]) / (4.0 * w),
            (rotation[1, 0] - rotation[0, 1]) / (4.0 * w), w)


def twist_values(message):
    """Return a Twist as ``[vx, vy, vz, wx, wy, wz]``."""
    return np.array([message.linear.x, message.linear.y, message.linear.z,
                     message.angular.x, message.angular.y, message.angular.z])


@pytest.fixture
def nodes(ros, spin_until):
    """Start ik_node and fk_node with the tool frame, and a probe, on one executor."""
    tool = [Parameter('tool_frame_position', value=TOOL_POSITION),
            Parameter('tool_frame_orientation_deg', value=TOOL_ORIENTATION_DEG)]
    ik, fk = IkNode(cli_args=ARGS, parameter_overrides=tool), FkNode(
        cli_args=ARGS, parameter_overrides=tool)
    probe = Node('twist_probe')
    received = {'leg_lengths': [], 'leg_velocities': [], 'estimated_twist': []}
    for topic, message_type in (('leg_lengths', Float64MultiArray),
                                ('leg_velocities', Float64MultiArray),
                                ('estimated_twist', Twist)):
        probe.create_subscription(message_type, topic, received[topic].append, 10)
    publishers = {topic: probe.create_publisher(message_type, topic, 10) for topic, message_type
                  in (('target_pose', Pose), ('target_twist', Twist),
                      ('joint_states', JointState))}
    executor = create_executor()
    for node in (ik, fk, probe):
        executor.add_node(node)
    assert spin_until(executor, lambda: all(
        publisher.get_subscription_count() >= 1 for publisher in publishers.values())), (
        'the nodes and the probe did not connect')
    yield executor, publishers, received
    executor.shutdown()
    for node in (ik, fk, probe):
        node.destroy_node()


def test_target_twist_is_about_the_tool_frame_point(nodes, spin_until):
    """The tool's twist at its pose gives the legs' velocities of the platform's motion."""
    executor, publishers, received = nodes
    position, rotation = tool_pose(TIME)
    message = Pose()
    message.position.x, message.position.y, message.position.z = position.tolist()
    o = message.orientation
    o.x, o.y, o.z, o.w = quaternion(rotation)
    publishers['target_pose'].publish(message)
    assert spin_until(executor, lambda: received['leg_lengths'])
    assert_allclose(received['leg_lengths'][-1].data, reference.leg_lengths(platform_pose(TIME)),
                    atol=1e-9)
    twist = Twist()
    (twist.linear.x, twist.linear.y, twist.linear.z,
     twist.angular.x, twist.angular.y, twist.angular.z) = tool_twist(TIME).tolist()
    publishers['target_twist'].publish(twist)
    assert spin_until(executor, lambda: received['leg_velocities'])
    assert_allclose(received['leg_velocities'][-1].data, leg_velocities(TIME), atol=1e-8)


def test_estimated_twist_is_about_the_tool_frame_point(nodes, spin_until):
    """Leg lengths and velocities of the platform's motion give the tool's twist."""
    executor, publishers, received = nodes
    state = JointState(name=[f'leg_{leg}' for leg in range(1, 7)])
    state.position = [float(value) for value in reference.leg_lengths(platform_pose(TIME))]
    state.velocity = leg_velocities(TIME).tolist()
    publishers['joint_states'].publish(state)
    assert spin_until(executor, lambda: received['estimated_twist'])
    assert_allclose(twist_values(received['estimated_twist'][-1]), tool_twist(TIME), atol=1e-8)
