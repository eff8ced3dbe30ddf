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
"""Stamped poses, joint states and velocities through ik_node and fk_node, in-process."""

import math
from pathlib import Path

from builtin_interfaces.msg import Time
from geometry_msgs.msg import PoseStamped, Twist
import numpy as np
from numpy.testing import assert_allclose
import pytest
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, Header
from stewart_kinematics import inverse_kinematics
from stewart_kinematics.model.velocities import leg_velocities
from stewart_kinematics.parameters import load_geometry
from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.message_conversions import pose_from_message, pose_to_message
from stewart_kinematics.ros.node_main import create_executor

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
ARGS = ['--ros-args', '--params-file', str(CONFIG / 'paper_platform.yaml'),
        '--params-file', str(CONFIG / 'solver.yaml')]
GEOMETRY = load_geometry(CONFIG / 'paper_platform.yaml')
POSE = np.array([0.05, 0.075, 0.4825, math.radians(7.5), math.radians(-7.5), math.radians(10)])
TWIST = np.array([0.1, -0.2, 0.05, 0.3, -0.1, 0.2])


@pytest.fixture
def chain(ros):
    """Start ik_node, fk_node reading ik_node's joint_commands, and a probe node."""
    ik = IkNode(cli_args=ARGS)
    # Fed by joint states only: leg_lengths, its other input, is moved out of the way.
    fk = FkNode(cli_args=ARGS + ['-r', 'joint_states:=joint_commands',
                                 '-r', 'leg_lengths:=unused_lengths'])
    probe = ros.create_node('probe')
    received = {'joint_commands': [], 'estimated_pose_stamped': [], 'leg_velocities': [],
                'estimated_twist': []}
    for topic, kind in (('joint_commands', JointState), ('estimated_pose_stamped', PoseStamped),
                        ('leg_velocities', Float64MultiArray), ('estimated_twist', Twist)):
        probe.create_subscription(kind, topic, received[topic].append, 10)
    publishers = {topic: probe.create_publisher(kind, topic, 10) for topic, kind in (
        ('target_pose_stamped', PoseStamped), ('target_twist', Twist))}
    executor = create_executor()
    for node in (ik, fk, probe):
        executor.add_node(node)
    yield ik, fk, publishers, received, executor
    executor.shutdown()
    for node in (ik, fk, probe):
        node.destroy_node()


def stamped(pose, frame='stewart_base', seconds=123):
    """Return a PoseStamped of ``pose`` with a recognisable stamp."""
    return PoseStamped(header=Header(frame_id=frame, stamp=Time(sec=seconds, nanosec=456)),
                       pose=pose_to_message(pose))


def test_stamp_goes_from_pose_through_joint_commands_to_estimated_pose(chain, spin_until):
    """A stamped pose's stamp reaches joint_commands and, through fk_node, the estimate."""
    ik, fk, publishers, received, executor = chain
    assert spin_until(executor, lambda: publishers['target_pose_stamped']
                      .get_subscription_count() >= 1)
    publishers['target_pose_stamped'].publish(stamped(POSE))
    assert spin_until(executor, lambda: received['estimated_pose_stamped'])
    joints = received['joint_commands'][0]
    assert list(joints.name) == [f'leg_{leg}' for leg in range(1, 7)]
    assert_allclose(joints.position, inverse_kinematics(GEOMETRY, POSE), rtol=0, atol=1e-12)
    assert (joints.header.stamp.sec, joints.header.stamp.nanosec) == (123, 456)
    estimate = received['estimated_pose_stamped'][0]
    assert (estimate.header.stamp.sec, estimate.header.stamp.nanosec) == (123, 456)
    assert estimate.header.frame_id == 'stewart_base'
    assert_allclose(pose_from_message(estimate.pose), POSE, rtol=0, atol=1e-9)


def test_pose_in_another_frame_is_refused(chain, spin_until):
    """A stamped pose in a frame other than base_frame publishes nothing and is counted."""
    ik, fk, publishers, received, executor = chain
    assert spin_until(executor, lambda: publishers['target_pose_stamped']
                      .get_subscription_count() >= 1)
    publishers['target_pose_stamped'].publish(stamped(POSE, frame='world'))
    assert spin_until(executor, lambda: ik.stamped_accounting.rejected == 1)
    assert 'world' in ik.stamped_accounting.last_rejection.message
    assert received['joint_commands'] == []


def test_a_malformed_stamp_is_refused_not_passed_to_the_drives(chain, spin_until):
    """
    A nanosec not below 1e9 (rclpy does not refuse it): refused, counted, nothing sent.

    Before, joint_commands carried it on to the drives, where it reads whole seconds later.
    """
    ik, fk, publishers, received, executor = chain
    assert spin_until(executor, lambda: publishers['target_pose_stamped']
                      .get_subscription_count() >= 1)
    message = stamped(POSE)
    message.header.stamp.nanosec = 4_000_000_000
    publishers['target_pose_stamped'].publish(message)
    assert spin_until(executor, lambda: ik.stamped_accounting.rejected == 1)
    refusal = ik.stamped_accounting.last_rejection
    assert refusal.code == 'invalid_pose'
    assert refusal.message.startswith('header.stamp is malformed: nanosec 4000000000')
    publishers['target_pose_stamped'].publish(stamped(POSE))   # the next one passes
    assert spin_until(executor, lambda: received['joint_commands'])
    assert [(m.header.stamp.sec, m.header.stamp.nanosec)
            for m in received['joint_commands']] == [(123, 456)]


def test_twist_gives_leg_velocities_and_back(chain, spin_until):
    """target_twist -> leg_velocities equals the core; joint velocities -> estimated_twist."""
    ik, fk, publishers, received, executor = chain
    assert spin_until(executor, lambda: publishers['target_twist'].get_subscription_count() >= 1)
    publishers['target_twist'].publish(Twist())
    assert spin_until(executor, lambda: ik.twist_accounting.rejected == 1)
    assert 'no pose accepted yet' in ik.twist_accounting.last_rejection.message
    publishers['target_pose_stamped'].publish(stamped(POSE))
    assert spin_until(executor, lambda: received['estimated_pose_stamped'])
    twist = Twist()
    twist.linear.x, twist.linear.y, twist.linear.z = TWIST[:3]
    twist.angular.x, twist.angular.y, twist.angular.z = TWIST[3:]
    publishers['target_twist'].publish(twist)
    assert spin_until(executor, lambda: received['leg_velocities'])
    expected = leg_velocities(GEOMETRY, POSE, TWIST)
    assert_allclose(received['leg_velocities'][0].data, expected, rtol=0, atol=1e-12)


def test_joint_state_with_velocities_gives_the_twist(ros, spin_until):
    """fk_node turns a measured joint state with velocities into the pose and the twist."""
    fk = FkNode(cli_args=ARGS)
    probe = ros.create_node('probe')
    twists = []
    probe.create_subscription(Twist, 'estimated_twist', twists.append, 10)
    publisher = probe.create_publisher(JointState, 'joint_states', 10)
    executor = create_executor()
    executor.add_node(fk)
    executor.add_node(probe)
    try:
        assert spin_until(executor, lambda: publisher.get_subscription_count() >= 1)
        order = [3, 0, 5, 1, 4, 2]   # any order of the names is accepted
        lengths = inverse_kinematics(GEOMETRY, POSE)
        velocities = leg_velocities(GEOMETRY, POSE, TWIST)
        publisher.publish(JointState(
            name=[f'leg_{i + 1}' for i in order], position=[float(lengths[i]) for i in order],
            velocity=[float(velocities[i]) for i in order]))
        assert spin_until(executor, lambda: twists)
        got = [twists[0].linear.x, twists[0].linear.y, twists[0].linear.z,
               twists[0].angular.x, twists[0].angular.y, twists[0].angular.z]
        assert_allclose(got, TWIST, rtol=0, atol=1e-9)
        publisher.publish(JointState(name=['leg_1'], position=[0.7]))
        assert spin_until(executor, lambda: fk.joint_state_accounting.rejected == 1)
        assert 'leg_2' in fk.joint_state_accounting.last_rejection.message
    finally:
        executor.shutdown()
        fk.destroy_node()
        probe.destroy_node()


def test_markers_show_the_platform_and_colour_violating_legs(ros, spin_until):
    """platform_markers draws base, platform and legs; legs past a limit are red."""
    from visualization_msgs.msg import MarkerArray
    from rclpy.parameter import Parameter
    ik = IkNode(cli_args=ARGS, parameter_overrides=[
        Parameter('leg_length_max', value=0.8), Parameter('marker_rate', value=1000.0)])
    probe = ros.create_node('probe')
    arrays = []
    probe.create_subscription(MarkerArray, 'platform_markers', arrays.append, 10)
    publisher = probe.create_publisher(PoseStamped, 'target_pose_stamped', 10)
    executor = create_executor()
    executor.add_node(ik)
    executor.add_node(probe)
    try:
        assert spin_until(executor, lambda: publisher.get_subscription_count() >= 1)
        publisher.publish(stamped(POSE))
        assert spin_until(executor, lambda: len(arrays) >= 1)
        # marker_rate's 1 ms first: the events executor can answer within it.
        assert spin_until(executor, lambda: ik.get_clock().now().nanoseconds
                          - ik.markers.last_ns >= ik.markers.period_ns)
        far = np.array([0.1, 0.15, 0.5325, math.radians(15), math.radians(-15), math.radians(20)])
        publisher.publish(stamped(far))
        assert spin_until(executor, lambda: ik.stamped_accounting.rejected == 1)
        assert spin_until(executor, lambda: len(arrays) >= 2)
        base, platform, legs = arrays[0].markers
        assert base.header.frame_id == 'stewart_base'
        assert_allclose([[p.x, p.y, p.z] for p in base.points[:6]], GEOMETRY.base_joints)
        tops = [[p.x, p.y, p.z] for p in legs.points[1::2]]
        expected_lengths = inverse_kinematics(GEOMETRY, POSE)
        assert_allclose(np.linalg.norm(np.array(tops) - GEOMETRY.base_joints, axis=1),
                        expected_lengths, rtol=0, atol=1e-12)
        assert all(colour.g > colour.r for colour in legs.colors)
        far_lengths = inverse_kinematics(GEOMETRY, far)
        red = [colour.r > colour.g for colour in arrays[1].markers[2].colors[::2]]
        assert red == list(far_lengths > 0.8) and any(red)
        assert ik.stamped_accounting.rejected == 1
    finally:
        executor.shutdown()
        ik.destroy_node()
        probe.destroy_node()


def test_markers_are_limited_to_marker_rate(ros, spin_until):
    """At marker_rate 1 Hz, a burst of poses gives one marker array, and every pose its lengths."""
    from visualization_msgs.msg import MarkerArray
    from rclpy.parameter import Parameter
    ik = IkNode(cli_args=ARGS, parameter_overrides=[Parameter('marker_rate', value=1.0)])
    probe = ros.create_node('probe')
    arrays, lengths = [], []
    probe.create_subscription(MarkerArray, 'platform_markers', arrays.append, 10)
    probe.create_subscription(Float64MultiArray, 'leg_lengths', lengths.append, 10)
    publisher = probe.create_publisher(PoseStamped, 'target_pose_stamped', 10)
    executor = create_executor()
    executor.add_node(ik)
    executor.add_node(probe)
    try:
        assert spin_until(executor, lambda: publisher.get_subscription_count() >= 1)
        for _ in range(5):
            publisher.publish(stamped(POSE))
        assert spin_until(executor, lambda: len(lengths) == 5)
        executor.spin_once(timeout_sec=0.2)
        assert len(arrays) == 1
    finally:
        executor.shutdown()
        ik.destroy_node()
        probe.destroy_node()
