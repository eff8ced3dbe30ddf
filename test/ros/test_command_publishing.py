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
Every publisher that commands an actuator sends only the command gate's verdicts (issue 27).

The test walks the interface table: for every node, every publisher declared to command
actuators is a :class:`CommandPublisher`, no attribute of the node holds its rclpy publisher
otherwise, and, with each node driven to publish its commands (poses, twists, a stream, a ramp,
a trajectory played, a cue), every message that reaches an rclpy publisher of such a topic was
sent by ``CommandPublisher.publish`` with an accepted verdict whose numbers it carries.
"""

import inspect
import math
from pathlib import Path

from geometry_msgs.msg import Pose, Twist
import numpy as np
import pytest
from rclpy.publisher import Publisher
from sensor_msgs.msg import Imu
from std_msgs.msg import Float64MultiArray
from stewart_kinematics.limits import CommandGate, Verdict
from stewart_kinematics.ros.command_publishing import CommandPublisher
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.interfaces import NODE_INTERFACES, PUBLISHER
from stewart_kinematics.ros.motion_cueing_node import MotionCueingNode
from stewart_kinematics.ros.node_main import create_executor, create_output_publisher
from stewart_kinematics.ros.trajectory_node import TrajectoryNode
from trajectory_msgs.msg import MultiDOFJointTrajectory, MultiDOFJointTrajectoryPoint

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = ['--params-file', str(CONFIG / 'paper_platform.yaml'),
         '--params-file', str(CONFIG / 'example_limits.yaml')]
#: The topics that command actuators, node by node: what the interface table must declare.
COMMANDS = {
    'ik_node': {'leg_lengths', 'leg_extensions', 'joint_commands', 'leg_velocities'},
    'fk_node': set(),
    'trajectory_node': {'target_pose', 'leg_trajectory', 'joint_commands'},
    'motion_cueing_node': {'target_pose'},
    'mock_platform': set(),
    # vehicle_imu is the vehicle's motion, an input of motion_cueing_node, not a command.
    'telemetry_bridge': set(),
}


def test_the_interface_table_declares_every_command_topic():
    """Exactly the topics that command actuators (directly or through ik_node) are declared so."""
    declared = {node: {endpoint.name for endpoint in interface.of_kind(PUBLISHER)
                       if endpoint.commands}
                for node, interface in NODE_INTERFACES.items()}
    assert declared == COMMANDS


def test_a_command_topic_cannot_be_created_without_the_gate(ros):
    """create_output_publisher refuses a command topic without its verdict converter."""
    node = ros.create_node('probe')
    try:
        endpoint = NODE_INTERFACES['ik_node']['leg_lengths']
        with pytest.raises(ValueError, match='commands actuators'):
            create_output_publisher(node, endpoint, 10)
        plain = NODE_INTERFACES['ik_node']['platform_markers']
        with pytest.raises(ValueError):
            create_output_publisher(node, plain, 10, lambda verdict: None)
    finally:
        node.destroy_node()


def test_a_command_publisher_sends_nothing_but_an_accepted_verdict(ros):
    """A bare message, an array or a refused verdict raise; an accepted verdict is sent."""
    node = ros.create_node('probe')
    try:
        endpoint = NODE_INTERFACES['ik_node']['leg_lengths']
        sent = []
        publisher = create_output_publisher(
            node, endpoint, 10, lambda verdict: Float64MultiArray(data=verdict.lengths.tolist()))
        publisher._publisher.publish = sent.append
        with pytest.raises(TypeError, match='verdict of the command gate'):
            publisher.publish(Float64MultiArray(data=[0.7] * 6))
        with pytest.raises(TypeError):
            publisher.publish(np.full(6, 0.7))
        refused = CommandGate(_geometry()).pose(np.array([0.0, 0.0, 2.0]), np.eye(3))
        with pytest.raises(ValueError, match='refused command'):
            publisher.publish(refused)
        assert not sent
        accepted = CommandGate(_geometry()).pose(np.array([0.0, 0.0, 0.45]), np.eye(3))
        publisher.publish(accepted)
        assert sent[0].data.tolist() == accepted.lengths.tolist()
    finally:
        node.destroy_node()


def _geometry():
    from stewart_kinematics import load_geometry
    return load_geometry([str(CONFIG / 'paper_platform.yaml'),
                          str(CONFIG / 'example_limits.yaml')])


class Recorder:
    """Record what reaches a command topic's rclpy publisher, and who sent it."""

    def __init__(self, node):
        self.messages = {}
        self.wrong = []
        names = COMMANDS[node.get_name()]
        for command_publisher in _command_publishers(node):
            topic = command_publisher.endpoint.name
            assert topic in names
            self.messages[topic] = []
            command_publisher._publisher.publish = self._record(topic)

    def _record(self, topic):
        def publish(message):
            caller = inspect.stack()[1]
            sender = caller.frame.f_locals.get('self')
            verdict = caller.frame.f_locals.get('verdict')
            if caller.function != 'publish' or not isinstance(sender, CommandPublisher):
                self.wrong.append(f'{topic} published by {caller.function}')
            elif isinstance(verdict, Verdict) and not verdict.accepted:
                self.wrong.append(f'{topic}: a refused verdict')
            self.messages[topic].append(message)
        return publish


def _command_publishers(node):
    """Every CommandPublisher held by the node's attributes (and their attributes, one deep)."""
    found = []
    for value in _attributes(node):
        if isinstance(value, CommandPublisher):
            found.append(value)
    return found


def _attributes(node):
    """Return the node's attribute values, and those of the objects they hold (one deep)."""
    values = []
    skipped = (type, Publisher, CommandPublisher)
    for value in vars(node).values():
        values.append(value)
        if hasattr(value, '__dict__') and not isinstance(value, skipped):
            values.extend(vars(value).values())
    return values


def _assert_only_wrapped(node):
    """No attribute of the node holds a command topic's rclpy publisher but its wrapper."""
    wrapped = {id(publisher._publisher) for publisher in _command_publishers(node)}
    command_topics = COMMANDS[node.get_name()]
    for publisher in node.publishers:
        if publisher.topic_name.lstrip('/').split('/')[-1] in command_topics:
            assert id(publisher) in wrapped, f'{publisher.topic_name} has no CommandPublisher'
    for value in _attributes(node):
        if isinstance(value, Publisher):
            assert value.topic_name.split('/')[-1] not in command_topics, (
                f'the node holds the bare publisher of {value.topic_name}')


def _pose(x=0.0, y=0.0, z=0.4325, yaw=0.0):
    message = Pose()
    message.position.x, message.position.y, message.position.z = x, y, z
    message.orientation.z, message.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return message


def test_ik_node_publishes_its_commands_only_through_the_gate(ros):
    """Poses, a twist and 20 streamed steps: every command message came from a verdict."""
    node = IkNode(cli_args=['--ros-args'] + FILES + ['-p', 'command_rate:=100.0'])
    try:
        _assert_only_wrapped(node)
        recorder = Recorder(node)
        # Subscribers are not needed: the node builds extensions and joint states only for
        # one, so pretend there is one.
        for publisher in _command_publishers(node):
            publisher.get_subscription_count = lambda: 1
        for k in range(5):
            node.on_target_pose(_pose(x=0.002 * k, yaw=0.01 * k))
        node.on_target_pose(_pose(z=2.0))   # refused: nothing sent
        twist = Twist()
        twist.linear.x = 0.01
        node.on_target_twist(twist)
        for _ in range(20):
            node.publish_streamed_command()
        assert not recorder.wrong
        assert len(recorder.messages['leg_lengths']) == 5
        assert len(recorder.messages['leg_extensions']) == 5
        assert len(recorder.messages['leg_velocities']) == 1
        assert len(recorder.messages['joint_commands']) >= 19
    finally:
        node.destroy_node()


def test_trajectory_node_publishes_its_commands_only_through_the_gate(ros, spin_until):
    """The ramp's rows, a trajectory on leg_trajectory and played: every one from a verdict."""
    node = TrajectoryNode(cli_args=['--ros-args'] + FILES + [
        '--params-file', str(CONFIG / 'table3_ramp.yaml'), '-p', 'play:=true',
        '-p', 'min_subscribers:=0'])
    executor = create_executor()
    executor.add_node(node)
    try:
        _assert_only_wrapped(node)
        recorder = Recorder(node)
        for _ in range(3):
            node.publish_ramp()
        message = MultiDOFJointTrajectory()
        for k, z in enumerate((0.4325, 0.44, 0.4325)):
            point = MultiDOFJointTrajectoryPoint()
            point.transforms.append(_transform(z))
            point.time_from_start.sec = 2 * k
            message.points.append(point)
        node.on_pose_trajectory(message)
        assert spin_until(executor, lambda: recorder.messages['leg_trajectory'])
        assert spin_until(executor, lambda: len(recorder.messages['target_pose']) >= 8)
        assert not recorder.wrong
    finally:
        executor.shutdown()
        node.destroy_node()


def _transform(z):
    from geometry_msgs.msg import Transform
    transform = Transform()
    transform.translation.z = z
    transform.rotation.w = 1.0
    return transform


def test_motion_cueing_node_publishes_its_commands_only_through_the_gate(ros):
    """100 samples of a push, some absurd: every target_pose came from an accepted verdict."""
    node = MotionCueingNode(cli_args=['--ros-args'] + FILES + [
        '--params-file', str(CONFIG / 'motion_cueing.yaml')])
    try:
        _assert_only_wrapped(node)
        recorder = Recorder(node)
        for k in range(100):
            message = Imu()
            message.header.stamp.sec, message.header.stamp.nanosec = divmod(
                10_000_000_000 + k * 10_000_000, 1_000_000_000)
            message.linear_acceleration.x = 500.0 if k % 10 == 9 else 2.0
            message.linear_acceleration.z = 9.81
            node.on_imu(message)
        assert not recorder.wrong
        assert len(recorder.messages['target_pose']) == 100
        assert all(isinstance(message, Pose) for message in recorder.messages['target_pose'])
    finally:
        node.destroy_node()
