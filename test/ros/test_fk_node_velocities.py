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
fk_node's leg velocities: bad ones cost the twist only, and no twist is ever non-finite.

The defects (issue 21): leg velocities of 1e308 on ``leg_velocities`` gave NaN on
``estimated_twist``; a ``joint_states`` message with valid positions and NaN velocities
dropped the pose too, counted as ``invalid_lengths``.
"""

import math
from pathlib import Path

from geometry_msgs.msg import Pose, Twist
import pytest
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray

from stewart_kinematics import inverse_kinematics
from stewart_kinematics.parameters import load_geometry
from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.node_main import create_executor

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
ARGS = ['--ros-args', '--params-file', str(CONFIG / 'paper_platform.yaml'),
        '--params-file', str(CONFIG / 'solver.yaml')]
GEOMETRY = load_geometry(CONFIG / 'paper_platform.yaml')
POSE = [0.01, -0.02, 0.45, 0.05, -0.03, 0.1]
#: Leg velocities whose twist is beyond the float range, and other bad ones.
BAD_VELOCITIES = [[1e308] * 6, [-1.7e308, 1.7e308, 1e308, -1e308, 1.7e308, 0.0],
                  [math.nan] * 6, [0.0, math.inf, 0.0, 0.0, 0.0, 0.0]]


@pytest.fixture
def fk(ros, spin_until):
    """Start fk_node and a probe that records estimated_pose and estimated_twist."""
    node = FkNode(cli_args=ARGS)
    probe = ros.create_node('velocity_probe')
    received = {'poses': [], 'twists': []}
    probe.create_subscription(Pose, 'estimated_pose', received['poses'].append, 100)
    probe.create_subscription(Twist, 'estimated_twist', received['twists'].append, 100)
    publishers = {'joint_states': probe.create_publisher(JointState, 'joint_states', 100),
                  'leg_velocities': probe.create_publisher(
                      Float64MultiArray, 'leg_velocities', 100)}
    executor = create_executor()
    executor.add_node(node)
    executor.add_node(probe)
    assert spin_until(executor, lambda: all(
        publisher.get_subscription_count() >= 1 for publisher in publishers.values())
        and node.twist_publisher.get_subscription_count() >= 1
        and node.pose_publisher.get_subscription_count() >= 1)
    yield node, publishers, received, executor
    executor.shutdown()
    node.destroy_node()
    probe.destroy_node()


def joint_state(velocities):
    """Return a JointState of POSE's leg lengths with the given velocities."""
    lengths = inverse_kinematics(GEOMETRY, POSE)
    return JointState(name=[f'leg_{leg}' for leg in range(1, 7)],
                      position=[float(value) for value in lengths],
                      velocity=[float(value) for value in velocities])


def twist_values(message):
    """Return the six components of a Twist."""
    return [message.linear.x, message.linear.y, message.linear.z,
            message.angular.x, message.angular.y, message.angular.z]


def test_nan_velocities_in_a_joint_state_keep_the_pose_and_refuse_the_twist(fk, spin_until):
    node, publishers, received, executor = fk
    accounting = node.joint_state_accounting
    for count, velocities in enumerate(BAD_VELOCITIES, start=1):
        publishers['joint_states'].publish(joint_state(velocities))
        assert spin_until(executor, lambda: len(received['poses']) == count
                          and accounting.warned == count)
    assert accounting.rejected == 0 and accounting.published == len(BAD_VELOCITIES)
    assert accounting.warnings_by_code == {'invalid_velocities': len(BAD_VELOCITIES)}
    assert 'leg velocities' in accounting.last_warning.message
    assert received['twists'] == []
    # A good joint state still gives both.
    publishers['joint_states'].publish(joint_state([0.001] * 6))
    assert spin_until(executor, lambda: len(received['twists']) == 1)
    assert all(map(math.isfinite, twist_values(received['twists'][0])))


def test_huge_leg_velocities_are_refused_and_never_give_a_non_finite_twist(fk, spin_until):
    node, publishers, received, executor = fk
    accounting = node.velocity_accounting
    for count, velocities in enumerate(BAD_VELOCITIES, start=1):
        publishers['leg_velocities'].publish(Float64MultiArray(data=velocities))
        assert spin_until(executor, lambda: accounting.rejected == count)
    assert accounting.rejections_by_code == {'invalid_velocities': len(BAD_VELOCITIES)}
    assert 'not finite' in accounting.last_rejection.message or (
        'finite numbers' in accounting.last_rejection.message)
    publishers['leg_velocities'].publish(Float64MultiArray(data=[1e-3] * 6))
    assert spin_until(executor, lambda: len(received['twists']) == 1)
    assert all(map(math.isfinite, twist_values(received['twists'][0])))
    assert accounting.published == 1
