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
ik_node's ``joint_commands.effort`` (issue 29): the leg forces of the very pose published.

With the example masses (config/example_masses.yaml) each message's efforts are checked against
:func:`stewart_kinematics.leg_forces` computed here from the message itself: the pose of its
positions by forward kinematics, and, for the stream, the twist and acceleration of consecutive
messages' poses by finite differences at their stamps (rotation vectors by scipy). The stream's
motion changes the efforts from the static ones by what that twist and acceleration predict.
Without masses the effort list is empty.
"""

import math
from pathlib import Path

from helpers import pose_message
import numpy as np
from numpy.testing import assert_allclose
import pytest
from rclpy.node import Node
import reference
from scipy.spatial.transform import Rotation
from sensor_msgs.msg import JointState

from stewart_kinematics import forward_kinematics, leg_forces, load_geometry
from stewart_kinematics.ros.ik_node import IkNode

pytestmark = pytest.mark.node

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml',
         CONFIG / 'example_masses.yaml']
PLANT = load_geometry(FILES)
TILTED = (-0.02, 0.03, 0.45, math.radians(-5.0), math.radians(8.0), math.radians(-30.0))


def arguments(*extra, masses=True):
    """Return the node's command line: the parameter files, then ``extra`` parameters."""
    files = FILES if masses else FILES[:2]
    return ['--ros-args'] + [item for path in files for item in ('--params-file', str(path))] + [
        item for parameter in extra for item in ('-p', parameter)]


@pytest.fixture
def start(node_rig):
    """Return a starter of an IkNode with a probe subscribed to joint_commands."""
    def start_nodes(cli_args):
        node = node_rig.add(IkNode(cli_args=cli_args))
        probe = node_rig.add(Node('effort_probe'))
        publisher = probe.create_publisher(type(pose_message(TILTED)), 'target_pose', 10)
        received = []
        probe.create_subscription(JointState, 'joint_commands', received.append, 1000)
        subscription = next(iter(node.subscriptions))
        node_rig.connect(lambda: (publisher.get_subscription_count() >= 1
                                  and subscription.get_publisher_count() >= 1
                                  and node.joint_command_publisher.get_subscription_count() >= 1),
                         'IK node and effort probe')
        return publisher, received, node_rig.executor
    return start_nodes


def pose_of(message, guess):
    """Return the pose of a JointState's positions (offsets 0) by forward kinematics."""
    solution = forward_kinematics(PLANT, np.array(message.position), guess, tolerance=1e-13)
    assert solution.converged
    return solution.pose


def test_a_pose_commands_the_static_forces_of_its_lengths(start, spin_until):
    publisher, received, executor = start(arguments())
    publisher.publish(pose_message(TILTED))
    assert spin_until(executor, lambda: received)
    message = received[0]
    pose = pose_of(message, PLANT.home_pose)
    assert_allclose(pose, TILTED, atol=1e-9)
    assert len(message.effort) == 6
    assert_allclose(message.effort, leg_forces(PLANT, pose), rtol=1e-9, atol=1e-9)
    # Not the forces at home: the pose's own.
    assert np.abs(np.array(message.effort) - leg_forces(PLANT, PLANT.home_pose)).max() > 10.0


def test_without_masses_the_effort_is_not_given(start, spin_until):
    publisher, received, executor = start(arguments(masses=False))
    publisher.publish(pose_message(TILTED))
    assert spin_until(executor, lambda: received)
    assert list(received[0].effort) == []


def test_the_stream_commands_the_forces_of_its_motion(start, spin_until):
    """
    Streamed commands: efforts of each pose with the twist and acceleration of the stream.

    Judged from the third message on (the first two need the start, which is not published).
    """
    publisher, received, executor = start(arguments('command_rate:=200.0'))
    target = np.array(PLANT.home_pose) + [0.0, 0.0, 0.02, 0.0, 0.0, 0.0]
    publisher.publish(pose_message(target))
    assert spin_until(executor, lambda: len(received) >= 150, timeout=30.0)
    # From integer nanoseconds: seconds since 1970 as floats keep only 0.24 us, which a
    # step shortened by load (a timer catching up) turns into a wrong acceleration.
    nanoseconds = np.array([message.header.stamp.sec * 1_000_000_000
                            + message.header.stamp.nanosec for message in received])
    times = (nanoseconds - nanoseconds[0]) * 1e-9
    poses, guess = [], PLANT.home_pose
    for message in received:
        guess = pose_of(message, guess)
        poses.append(guess)
    poses = np.array(poses)
    rotations = Rotation.from_matrix(reference.rotations_zyx(poses[:, 3:]))
    steps = np.diff(times)
    twists = np.concatenate([np.diff(poses[:, :3], axis=0),
                             (rotations[1:] * rotations[:-1].inv()).as_rotvec()],
                            axis=1) / steps[:, None]
    accelerations = np.diff(twists, axis=0) / (0.5 * (steps[1:] + steps[:-1]))[:, None]
    predicted = leg_forces(PLANT, poses[2:], twists[1:], accelerations)
    efforts = np.array([message.effort for message in received])[2:]
    assert_allclose(efforts, predicted, atol=0.02)
    # The motion changes the efforts from the static ones, by what it predicts.
    static = leg_forces(PLANT, poses[2:])
    assert np.abs(efforts - static).max() > 0.5
