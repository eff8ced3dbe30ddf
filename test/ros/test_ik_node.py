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
In-process tests of the IK node: real rclpy, a probe node, one executor.

STEWART_EXECUTOR chooses the executor, as for the nodes (test/conftest.py).

Expected leg lengths are computed here with the paper's equation 1 written out in plain Python
(``|t + R p_i - b_i|``, ``R`` from the paper's r11..r33), from the joints read with
yaml.safe_load, so the node is checked against an independent implementation.
"""

import math
from pathlib import Path

from geometry_msgs.msg import Pose
from helpers import pose_message, raw_pose_message
from numpy.testing import assert_allclose
import pytest
import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter
from reference import leg_lengths as expected_lengths
from std_msgs.msg import Float64MultiArray

from stewart_kinematics.ros import ik_node
from stewart_kinematics.ros.ik_node import IkNode
import yaml

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
PLATFORM_FILE = str(CONFIG_DIRECTORY / 'paper_platform.yaml')
SOLVER_FILE = str(CONFIG_DIRECTORY / 'solver.yaml')
KINEMATICS_ARGS = ['--ros-args', '--params-file', PLATFORM_FILE, '--params-file', SOLVER_FILE]

HOME = (0.0, 0.0, 0.4325, 0.0, 0.0, 0.0)
#: Last row of the paper's Table 3: 100 mm, 150 mm, 532.5 mm, 15 deg, -15 deg, 20 deg.
TABLE3_END = (0.1, 0.15, 0.5325, math.radians(15.0), math.radians(-15.0), math.radians(20.0))
TILTED = (-0.02, 0.03, 0.45, math.radians(-5.0), math.radians(8.0), math.radians(-30.0))


def counts(node):
    """Return the node's (received, published, rejected) message counters."""
    accounting = node.accounting
    return accounting.received, accounting.published, accounting.rejected


def paper_joints():
    """Return the base and platform joints of config/paper_platform.yaml as lists of triples."""
    with open(PLATFORM_FILE, encoding='utf-8') as stream:
        parameters = yaml.safe_load(stream)['/**']['ros__parameters']

    def triples(flat):
        return [flat[3 * i:3 * i + 3] for i in range(6)]
    return triples(parameters['base_joints']), triples(parameters['platform_joints'])


class Probe:
    """A node that publishes target poses and records leg_lengths and leg_extensions."""

    def __init__(self, target_topic='target_pose'):
        """Create the probe node, publishing on ``target_topic``."""
        self.node = Node('ik_probe')
        self.publisher = self.node.create_publisher(Pose, target_topic, 10)
        self.lengths = []
        self.extensions = []
        self.node.create_subscription(
            Float64MultiArray, 'leg_lengths', self.lengths.append, 100)
        self.node.create_subscription(
            Float64MultiArray, 'leg_extensions', self.extensions.append, 100)

    def answers(self):
        """Return how many (lengths, extensions) pairs have arrived."""
        return min(len(self.lengths), len(self.extensions))


@pytest.fixture
def start(node_rig):
    """
    Return a starter of an IkNode and a Probe on one executor, connected both ways.

    The starter takes the node's keyword arguments (default: the config files) and the
    probe's target topic, and returns ``(node, probe, executor)``.
    """
    def start_nodes(target_topic='target_pose', **node_kwargs):
        node_kwargs.setdefault('cli_args', KINEMATICS_ARGS)
        node = node_rig.add(IkNode(**node_kwargs))
        probe = Probe(target_topic)
        node_rig.add(probe.node)
        subscription = next(iter(node.subscriptions))
        node_rig.connect(lambda: (probe.publisher.get_subscription_count() >= 1
                                  and subscription.get_publisher_count() >= 1
                                  and node.lengths_publisher.get_subscription_count() >= 1
                                  and node.extensions_publisher.get_subscription_count() >= 1),
                         'IK node and probe')
        return node, probe, node_rig.executor
    return start_nodes


def send_and_wait(spin_until, executor, probe, message, answers):
    """Publish a pose and spin until ``answers`` pairs of answers have arrived in total."""
    probe.publisher.publish(message)
    assert spin_until(executor, lambda: probe.answers() >= answers), (
        f'expected {answers} answers, got {len(probe.lengths)} lengths and '
        f'{len(probe.extensions)} extensions')


def assert_leg_layout(message):
    """Check one layout dimension labelled 'leg', size 6, stride 6, and six values."""
    assert len(message.data) == 6
    assert [(d.label, d.size, d.stride) for d in message.layout.dim] == [('leg', 6, 6)]
    assert message.layout.data_offset == 0


def test_leg_lengths_match_the_paper_equation(start, spin_until):
    """Home, the last Table 3 row and a tilted pose give the lengths of equation 1."""
    node, probe, executor = start()
    home_lengths = expected_lengths(HOME)
    assert_allclose(node.geometry.home_leg_lengths, home_lengths, rtol=0.0, atol=1e-12)
    for count, pose in enumerate((HOME, TABLE3_END, TILTED), start=1):
        send_and_wait(spin_until, executor, probe, pose_message(pose), count)
        lengths, extensions = probe.lengths[-1], probe.extensions[-1]
        assert_leg_layout(lengths)
        assert_leg_layout(extensions)
        wanted = expected_lengths(pose)
        assert_allclose(lengths.data, wanted, rtol=0.0, atol=1e-12)
        assert_allclose(extensions.data, [w - h for w, h in zip(wanted, home_lengths)],
                        rtol=0.0, atol=1e-12)
    assert_allclose(probe.extensions[0].data, [0.0] * 6, rtol=0.0, atol=1e-15)
    assert counts(node) == (3, 3, 0)


def test_home_lengths_are_the_documented_values(start):
    """The node's home lengths match the values printed in the kinematics docstring."""
    node, _, _ = start()
    assert_allclose(
        node.geometry.home_leg_lengths,
        [0.71885487, 0.71885488, 0.70114644, 0.71885487, 0.71885488, 0.71885488], atol=1e-8)


def test_quaternion_of_norm_two_is_normalised(start, spin_until):
    """A quaternion scaled to norm 2 gives the same lengths as the unit one."""
    node, probe, executor = start()
    send_and_wait(spin_until, executor, probe, pose_message(TILTED), 1)
    send_and_wait(spin_until, executor, probe, pose_message(TILTED, scale=2.0), 2)
    send_and_wait(spin_until, executor, probe, pose_message(TILTED, scale=-0.5), 3)
    wanted = expected_lengths(TILTED)
    for message in probe.lengths:
        assert_allclose(message.data, wanted, rtol=0.0, atol=1e-12)
    assert node.accounting.rejected == 0


def test_bad_poses_are_rejected_and_the_node_keeps_working(start, spin_until):
    """Poses with NaN, infinity or a zero quaternion publish nothing and count as rejected."""
    node, probe, executor = start()
    bad = [
        raw_pose_message([math.nan, 0.0, 0.4325], [0.0, 0.0, 0.0, 1.0]),
        raw_pose_message([0.0, 0.0, math.inf], [0.0, 0.0, 0.0, 1.0]),
        raw_pose_message([0.0, 0.0, 0.4325], [0.0, 0.0, 0.0, 0.0]),
        raw_pose_message([0.0, 0.0, 0.4325], [0.0, math.nan, 0.0, 1.0]),
    ]
    for message in bad:
        probe.publisher.publish(message)
    # Messages from one publisher arrive in order: the good pose's answer comes after any
    # answer to the bad ones, so exactly one answer means the bad ones produced none.
    send_and_wait(spin_until, executor, probe, pose_message(TABLE3_END), 1)
    assert (len(probe.lengths), len(probe.extensions)) == (1, 1)
    assert_allclose(probe.lengths[0].data, expected_lengths(TABLE3_END), rtol=0.0, atol=1e-12)
    assert counts(node) == (5, 1, 4)


def test_pose_out_of_reach_is_rejected(start, spin_until):
    """With leg limits around home, poses that need longer or shorter legs are rejected."""
    limits = [Parameter('leg_length_min', value=0.69), Parameter('leg_length_max', value=0.73)]
    node, probe, executor = start(cli_args=KINEMATICS_ARGS, parameter_overrides=limits)
    assert (node.geometry.leg_length_min, node.geometry.leg_length_max) == (0.69, 0.73)
    assert max(expected_lengths(TABLE3_END)) > 0.73
    assert min(expected_lengths((0.0, 0.0, 0.40, 0.0, 0.0, 0.0))) < 0.69
    probe.publisher.publish(pose_message(TABLE3_END))
    probe.publisher.publish(pose_message((0.0, 0.0, 0.40, 0.0, 0.0, 0.0)))
    send_and_wait(spin_until, executor, probe, pose_message(HOME), 1)
    assert (len(probe.lengths), len(probe.extensions)) == (1, 1)
    assert_allclose(probe.lengths[0].data, expected_lengths(HOME), rtol=0.0, atol=1e-12)
    assert counts(node) == (3, 1, 2)


def test_target_pose_remap(start, spin_until):
    """A -r target_pose:=/other remap moves the subscription; the node answers there."""
    node, probe, executor = start(
        target_topic='/other', cli_args=KINEMATICS_ARGS + ['-r', 'target_pose:=/other'])
    assert [s.topic_name for s in node.subscriptions][0] == '/other'
    send_and_wait(spin_until, executor, probe, pose_message(TILTED), 1)
    assert_allclose(probe.lengths[0].data, expected_lengths(TILTED), rtol=0.0, atol=1e-12)


def test_topics_are_relative_to_the_namespace(ros):
    """In a namespace every topic of the node moves with it (names are relative)."""
    node = IkNode(namespace='/robot', cli_args=KINEMATICS_ARGS)
    try:
        assert node.lengths_publisher.topic_name == '/robot/leg_lengths'
        assert node.extensions_publisher.topic_name == '/robot/leg_extensions'
        assert [s.topic_name for s in node.subscriptions] == [
            '/robot/target_pose', '/robot/target_pose_stamped', '/robot/target_twist']
        assert node.joint_command_publisher.topic_name == '/robot/joint_commands'
    finally:
        node.destroy_node()


def test_main_returns_1_for_a_bad_parameter_file(tmp_path):
    """A bad file (base_joints of 17 values) makes main() log and return 1, not raise."""
    with open(PLATFORM_FILE, encoding='utf-8') as stream:
        document = yaml.safe_load(stream)
    document['/**']['ros__parameters']['base_joints'] = [0.1] * 17
    bad_file = tmp_path / 'bad_platform.yaml'
    bad_file.write_text(yaml.safe_dump(document), encoding='utf-8')
    assert ik_node.main(['ik_node', '--ros-args', '--params-file', str(bad_file)]) == 1
    assert not rclpy.ok()


def test_main_returns_1_for_a_missing_parameter_file(tmp_path):
    """A parameter file that does not exist makes main() return 1, not raise."""
    missing = str(tmp_path / 'no_such_file.yaml')
    assert ik_node.main(['ik_node', '--ros-args', '--params-file', missing]) == 1
    assert not rclpy.ok()


def test_main_returns_1_for_a_misspelt_parameter_name(tmp_path, capfd):
    """A typo in a parameter name stops the node naming it, instead of keeping a default."""
    with open(PLATFORM_FILE, encoding='utf-8') as stream:
        document = yaml.safe_load(stream)
    parameters = document['/**']['ros__parameters']
    parameters['leg_length_mx'] = parameters.pop('leg_length_max')
    bad_file = tmp_path / 'typo.yaml'
    bad_file.write_text(yaml.safe_dump(document), encoding='utf-8')
    assert ik_node.main(['ik_node', '--ros-args', '--params-file', str(bad_file)]) == 1
    assert "'leg_length_mx' (did you mean 'leg_length_max'?)" in capfd.readouterr().err


def test_main_returns_1_for_a_misspelt_ros_option(capfd):
    """An unknown --ros-args option is a fatal start-up error, not a traceback."""
    assert ik_node.main(['ik_node', '--ros-args', '--params-fle', PLATFORM_FILE]) == 1
    error = capfd.readouterr().err
    assert 'cannot start' in error and '--params-fle' in error
    assert 'Traceback' not in error
