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
fk_node's ``estimated_wrench``: joint states with efforts in, the external wrench out.

Real rclpy, fk_node with the example masses (a 20 kg payload) and a probe on one executor. The
efforts sent are the leg forces of a model (the package's ``leg_forces``); the expected wrench
is written from the masses and gravity alone: a payload the node does not know shows as its
weight and moment, in the platform frame. Hostile efforts give a warning, never a wrench or a
traceback, and the pose is still published. A run-time change of ``payload_mass`` changes the
wrench at once.
"""

import dataclasses
import math
from pathlib import Path

from geometry_msgs.msg import Pose, WrenchStamped
from helpers import DEADLINE
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.node import Node
from rclpy.parameter import Parameter
from reference import TABLE_3
from sensor_msgs.msg import JointState

from stewart_kinematics import inverse_kinematics, leg_forces, RigidBody
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import load_geometry
from stewart_kinematics.ros.fk_node import FkNode

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [str(CONFIG / 'paper_platform.yaml'), str(CONFIG / 'example_masses.yaml')]
ARGS = ['--ros-args', '--params-file', FILES[0], '--params-file', FILES[1]]
GEOMETRY = load_geometry(FILES)
GRAVITY = np.array([0.0, 0.0, -9.80665])
POSE = np.array(TABLE_3[4])


class Probe:
    """Publishes joint_states; records estimated_pose and estimated_wrench."""

    def __init__(self):
        """Create the probe node, its publisher and subscriptions."""
        self.node = Node('fk_wrench_probe')
        self.publisher = self.node.create_publisher(JointState, 'joint_states', 10)
        self.poses, self.wrenches = [], []
        self.node.create_subscription(Pose, 'estimated_pose', self.poses.append, 100)
        self.node.create_subscription(WrenchStamped, 'estimated_wrench', self.wrenches.append,
                                      100)


@pytest.fixture
def start(node_rig, spin_until):
    """Return ``(node, probe, send)``: send(pose, efforts) waits for the pose's answer."""
    node = node_rig.add(FkNode(cli_args=ARGS))
    probe = Probe()
    node_rig.add(probe.node)
    node_rig.connect(lambda: (probe.publisher.get_subscription_count() >= 1
                              and node.pose_publisher.get_subscription_count() >= 1
                              and node.wrench_publisher.get_subscription_count() >= 1),
                     'fk_node and probe')

    def send(pose, efforts, message=None, wrench=True):
        if message is None:
            message = JointState(name=[f'leg_{leg}' for leg in range(1, 7)],
                                 position=inverse_kinematics(GEOMETRY, pose).tolist(),
                                 effort=list(efforts))
            message.header.stamp.sec, message.header.stamp.nanosec = 7, 500
        count, wrenches = len(probe.poses), len(probe.wrenches)
        probe.publisher.publish(message)
        assert spin_until(node_rig.executor, lambda: len(probe.poses) > count)
        # The wrench is published right after the pose. Awaited (one more spin could run
        # another callback first, a timer's, and leave it undelivered); else a window in which
        # none must come.
        arrived = spin_until(node_rig.executor, lambda: len(probe.wrenches) > wrenches,
                             DEADLINE if wrench else 0.2)
        assert arrived == wrench, f'{len(probe.wrenches) - wrenches} wrenches, {wrench} awaited'
    return node, probe, send


def weight_wrench(pose, mass, center):
    """Return the wrench of a mass's weight on the platform: platform frame, its origin."""
    weight = mass * euler_zyx_to_matrix(pose[3:]).T @ GRAVITY
    return np.concatenate([weight, np.cross(center, weight)])


def wrench_values(message):
    """Return ``[Fx, Fy, Fz, Mx, My, Mz]`` of a WrenchStamped."""
    force, torque = message.wrench.force, message.wrench.torque
    return np.array([force.x, force.y, force.z, torque.x, torque.y, torque.z])


def test_efforts_of_the_model_give_zero_and_an_extra_payload_its_weight(start):
    node, probe, send = start
    own = leg_forces(GEOMETRY, POSE)
    send(POSE, own)
    assert len(probe.wrenches) == 1
    message = probe.wrenches[0]
    assert message.header.frame_id == node.tracker.frames.platform_frame == 'stewart_platform'
    assert (message.header.stamp.sec, message.header.stamp.nanosec) == (7, 500)
    assert_allclose(wrench_values(message), np.zeros(6), rtol=0.0, atol=1e-9 * own.max())
    # 5 kg more at 0.1 m beside the payload's centre: a point mass the model does not know.
    masses = GEOMETRY.mass_properties
    payload = masses.payload
    extra, at = 5.0, np.array([0.1, -0.05, 0.375])
    total = payload.mass + extra
    heavier = dataclasses.replace(masses, payload=RigidBody(
        total, (payload.mass * np.array(payload.center_of_mass) + extra * at) / total,
        name='payload'))
    # Statics: the payload's inertia plays no part, only its mass and centre.
    send(POSE, leg_forces(GEOMETRY, POSE, mass_properties=heavier))
    expected = weight_wrench(POSE, extra, at)
    assert_allclose(wrench_values(probe.wrenches[1]), expected, rtol=0.0,
                    atol=1e-9 * np.abs(expected).max())


def test_joint_names_in_another_order_match_their_efforts(start):
    node, probe, send = start
    own = leg_forces(GEOMETRY, POSE)
    order = [3, 0, 5, 1, 4, 2]
    message = JointState(name=[f'leg_{leg + 1}' for leg in order] + ['gripper'],
                         position=inverse_kinematics(GEOMETRY, POSE)[order].tolist() + [0.3],
                         effort=own[order].tolist() + [9e9])
    send(None, None, message)
    assert len(probe.wrenches) == 1
    assert_allclose(wrench_values(probe.wrenches[0]), np.zeros(6), rtol=0.0,
                    atol=1e-9 * own.max())


@pytest.mark.parametrize('efforts, words', [
    ([], 'carries no efforts'),
    ([10.0] * 5, 'one force (N) for each of its 6 names, got 5'),
    ([10.0] * 7, 'got 7'),
    ([math.nan] + [10.0] * 5, 'measured_forces must be finite'),
    ([10.0] * 5 + [math.inf], 'measured_forces must be finite'),
    ([-math.inf] * 6, 'measured_forces must be finite'),
    ([1.7e308] * 6, 'too large'),
])
def test_hostile_efforts_give_a_warning_and_no_wrench_the_pose_still_published(
        start, efforts, words):
    node, probe, send = start
    send(POSE, efforts, wrench=False)
    assert len(probe.poses) == 1 and probe.wrenches == []
    accounting = node.joint_state_accounting
    assert accounting.warnings_by_code == {'invalid_efforts': 1}
    assert accounting.rejected == 0 and accounting.published == 1
    message = accounting.last_warning.message
    assert message.startswith('no estimated_wrench: ') and words in message, message
    assert '\n' not in message
    # The node goes on: good efforts give a wrench again.
    send(POSE, leg_forces(GEOMETRY, POSE))
    assert len(probe.wrenches) == 1


def test_a_huge_but_finite_effort_gives_a_finite_wrench(start):
    node, probe, send = start
    efforts = leg_forces(GEOMETRY, POSE)
    efforts[2] = 1e300
    send(POSE, efforts)
    assert len(probe.wrenches) == 1
    assert np.all(np.isfinite(wrench_values(probe.wrenches[0])))


def test_a_new_payload_at_run_time_changes_the_wrench_at_once(start):
    node, probe, send = start
    efforts = leg_forces(GEOMETRY, POSE)   # of the 20 kg payload
    send(POSE, efforts)
    assert_allclose(wrench_values(probe.wrenches[0]), np.zeros(6), rtol=0.0, atol=1e-6)
    [result] = node.set_parameters([Parameter('payload_mass', value=25.0)])
    assert result.successful, result.reason
    send(POSE, efforts)
    # The model now needs 5 kg more than the legs push: the environment holds 5 kg up.
    center = np.array(GEOMETRY.mass_properties.payload.center_of_mass)
    expected = -weight_wrench(POSE, 5.0, center)
    assert_allclose(wrench_values(probe.wrenches[1]), expected, rtol=0.0,
                    atol=1e-9 * np.abs(expected).max())
    assert node.tracker.geometry.mass_properties.payload.mass == 25.0
    # A refused payload keeps the one before: the wrench is the same again.
    [result] = node.set_parameters([Parameter('payload_mass', value=0.0)])
    assert not result.successful
    assert "parameters 'payload_mass' and 'payload_inertia'" in result.reason, result.reason
    send(POSE, efforts)
    assert_allclose(wrench_values(probe.wrenches[2]), expected, rtol=0.0,
                    atol=1e-9 * np.abs(expected).max())


def test_joint_states_without_efforts_and_no_subscriber_give_no_warning(ros):
    """Most drivers send no efforts: without a subscriber of the wrench, nothing to say."""
    node = FkNode(cli_args=ARGS)
    try:
        message = JointState(name=[f'leg_{leg}' for leg in range(1, 7)],
                             position=inverse_kinematics(GEOMETRY, POSE).tolist())
        node.on_joint_states(message)
        accounting = node.joint_state_accounting
        assert (accounting.published, accounting.warned) == (1, 0)
    finally:
        node.destroy_node()
