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
Multi-process tests: the console scripts started as ``ros2 run`` starts them, over real topics.

``ik_node``, ``fk_node`` and ``trajectory_node`` run as child processes
(:class:`stewart_kinematics.tools.node_processes.NodeProcess`) with the shipped parameter files; an
rclpy client in the test process publishes and subscribes on the same (private, local) ROS
domain. The expected numbers come from the paper's Tables 1 to 3, typed in below in the paper's
millimetres and degrees, and from the README's leg formula written out in plain Python, so that
the nodes are checked against something that shares no code with them.

Waits have a deadline of :data:`DEADLINE` seconds, since DDS discovery has multi-second tails;
the only fixed waits are the settle time after discovery (a reliable, volatile reader may
match a writer a moment after the writer matched it) and the nodes' one-second warning throttle.
"""

import math
import os
import signal
import subprocess
import sys

from geometry_msgs.msg import Pose
from helpers import pose_message, raw_pose_message, stop_cleanly
import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference
from reference import (
    leg_lengths as expected_leg_lengths,
    quaternion_angle as rotation_angle,
    quaternion_from_euler as quaternion,
)
from std_msgs.msg import Float64MultiArray

from stewart_kinematics.ros.message_accounting import WARNING_PERIOD
from stewart_kinematics.tools.node_processes import NodeProcess

pytestmark = pytest.mark.process

#: Seconds to wait for discovery or data.
DEADLINE = 20.0
#: Seconds to spin after discovery shows every side, before the first message.
SETTLE_TIME = 0.5
#: Queue depth of the test client's publishers and subscriptions.
CLIENT_DEPTH = 100
#: Exit code of a node that could not start (stewart_kinematics.ros.node_main.EXIT_START_FAILED).
EXIT_START_FAILED = 1

# The paper's tables (test/reference.py) as plain tuples of floats, for parameter files.
BASE_JOINTS = tuple(map(tuple, reference.BASE_JOINTS.tolist()))
PLATFORM_JOINTS = tuple(map(tuple, reference.PLATFORM_JOINTS.tolist()))
TABLE3 = reference.TABLE_3
HOME_POSE = TABLE3[0]


def message_position(message):
    """Position of a Pose as a tuple."""
    return (message.position.x, message.position.y, message.position.z)


def message_quaternion(message):
    """Orientation of a Pose as a tuple ``(x, y, z, w)``."""
    o = message.orientation
    return (o.x, o.y, o.z, o.w)


def node_names(endpoints):
    """Names of the nodes of a list of TopicEndpointInfo."""
    return {endpoint.node_name for endpoint in endpoints}


def kinematics_arguments(config_directory):
    """Return the command line of ik_node and fk_node with the shipped parameter files."""
    return ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'solver.yaml')]


def warnings_in(output):
    """Return the lines of a node's output that rclpy logged at WARN level."""
    return '\n'.join(line for line in output.splitlines() if line.startswith('[WARN]'))


def test_ik_and_fk_nodes_play_table3_without_loss(client, start_node, config_directory):
    """
    ik_node and fk_node turn the 11 Table 3 poses into the right lengths and back.

    Each pose is published once after discovery, and answered on leg_lengths (to 1e-12 m),
    leg_extensions (zero at home) and estimated_pose (to 1e-9 m and 1e-9 rad) before the next;
    exactly 11 messages arrive on each topic.
    """
    arguments = kinematics_arguments(config_directory)
    nodes = [start_node('ik_node', arguments), start_node('fk_node', arguments)]
    lengths, extensions, estimates = [], [], []
    subscriptions = [
        client.node.create_subscription(
            Float64MultiArray, 'leg_lengths', lengths.append, CLIENT_DEPTH),
        client.node.create_subscription(
            Float64MultiArray, 'leg_extensions', extensions.append, CLIENT_DEPTH),
        client.node.create_subscription(Pose, 'estimated_pose', estimates.append, CLIENT_DEPTH),
    ]
    publisher = client.node.create_publisher(Pose, 'target_pose', CLIENT_DEPTH)
    graph = client.node

    def connected():
        return (publisher.get_subscription_count() >= 1
                and 'ik_node' in node_names(graph.get_subscriptions_info_by_topic('target_pose'))
                and 'ik_node' in node_names(graph.get_publishers_info_by_topic('leg_lengths'))
                and 'ik_node' in node_names(graph.get_publishers_info_by_topic('leg_extensions'))
                and 'fk_node' in node_names(graph.get_subscriptions_info_by_topic('leg_lengths'))
                and 'fk_node' in node_names(graph.get_publishers_info_by_topic('estimated_pose'))
                and all(s.get_publisher_count() >= 1 for s in subscriptions))

    client.wait(connected, 'ik_node and fk_node in the graph and matched with the client', nodes)
    client.spin_for(SETTLE_TIME)

    for index, pose in enumerate(TABLE3):
        publisher.publish(pose_message(pose))
        client.wait(
            lambda: min(len(lengths), len(extensions), len(estimates)) > index,
            f'leg_lengths, leg_extensions and estimated_pose of Table 3 row {index}', nodes)

    assert (len(lengths), len(extensions), len(estimates)) == (11, 11, 11)
    home_lengths = expected_leg_lengths(HOME_POSE)
    for index, pose in enumerate(TABLE3):
        expected = expected_leg_lengths(pose)
        assert [(d.label, d.size) for d in lengths[index].layout.dim] == [('leg', 6)]
        assert_allclose(lengths[index].data, expected, rtol=0.0, atol=1e-12,
                        err_msg=f'leg_lengths of Table 3 row {index}')
        assert_allclose(extensions[index].data, np.subtract(expected, home_lengths),
                        rtol=0.0, atol=1e-12, err_msg=f'leg_extensions of Table 3 row {index}')
        assert_allclose(message_position(estimates[index]), pose[:3], rtol=0.0, atol=1e-9,
                        err_msg=f'estimated_pose position of Table 3 row {index}')
        angle = rotation_angle(message_quaternion(estimates[index]), quaternion(*pose[3:]))
        assert angle <= 1e-9, f'estimated_pose of row {index} is {angle:.3g} rad off'
    assert_allclose(extensions[0].data, [0.0] * 6, rtol=0.0, atol=1e-12)
    for node in nodes:
        stop_cleanly(node)


def test_trajectory_node_plays_table3(client, start_node, config_directory):
    """trajectory_node with table3_ramp.yaml publishes the 11 rows of Table 3, in order."""
    received = []
    client.node.create_subscription(Pose, 'target_pose', received.append, CLIENT_DEPTH)
    node = start_node('trajectory_node', [
        '--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
        '--params-file', str(config_directory / 'table3_ramp.yaml'),
        '-p', 'row_period:=0.1', '-p', 'min_subscribers:=1'])

    client.wait(lambda: len(received) >= len(TABLE3), '11 poses on target_pose', [node])

    assert len(received) == len(TABLE3)
    for index, (message, pose) in enumerate(zip(received, TABLE3)):
        assert_allclose(message_position(message), pose[:3], rtol=0.0, atol=1e-12,
                        err_msg=f'position of row {index}')
        angle = rotation_angle(message_quaternion(message), quaternion(*pose[3:]))
        assert angle <= 1e-12, f'orientation of row {index} is {angle:.3g} rad off'
    stop_cleanly(node)


@pytest.mark.parametrize('remap, command_topic, lengths_topic', [
    (['-r', 'target_pose:=/platform/command'], '/platform/command', '/leg_lengths'),
    (['-r', '__ns:=/robot_a'], '/robot_a/target_pose', '/robot_a/leg_lengths'),
], ids=['topic_remap', 'namespace'])
def test_ik_node_follows_remaps(client, start_node, config_directory,
                                remap, command_topic, lengths_topic):
    """A topic remap and a namespace given on the command line move ik_node's topics."""
    node = start_node('ik_node', kinematics_arguments(config_directory) + remap)
    lengths = []
    subscription = client.node.create_subscription(
        Float64MultiArray, lengths_topic, lengths.append, CLIENT_DEPTH)
    publisher = client.node.create_publisher(Pose, command_topic, CLIENT_DEPTH)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and subscription.get_publisher_count() >= 1,
                f'ik_node on {command_topic} and {lengths_topic}', [node])
    client.spin_for(SETTLE_TIME)

    pose = TABLE3[4]
    publisher.publish(pose_message(pose))
    client.wait(lambda: lengths, f'leg lengths on {lengths_topic}', [node])

    assert_allclose(lengths[0].data, expected_leg_lengths(pose), rtol=0.0, atol=1e-12)
    stop_cleanly(node)


def parameter_file(section='/**', **parameters):
    """Return the text of a ROS 2 parameter file that sets ``parameters`` in ``section``."""
    lines = [f'{section}:', '  ros__parameters:']
    lines += [f'    {name}: {value!r}' for name, value in parameters.items()]
    return '\n'.join(lines) + '\n'


#: The paper's platform as parameters, from the tables typed in above.
PAPER_PLATFORM = {
    'base_joints': [value for joint in BASE_JOINTS for value in joint],
    'platform_joints': [value for joint in PLATFORM_JOINTS for value in joint],
    'home_position': list(HOME_POSE[:3]),
}
YAML_SYNTAX_ERROR = """\
/**:
  ros__parameters:
    home_position: [0.0, 0.0, 0.4325
    base_joints: {
"""
BAD_PARAMETER_FILES = {
    'base_joints_17_values': (
        'ik_node', parameter_file(**dict(PAPER_PLATFORM, base_joints=[0.1] * 17)),
        ["parameter 'base_joints' must have exactly 18 elements, got 17"]),
    'home_orientation_out_of_range': (
        'ik_node', parameter_file(**PAPER_PLATFORM, home_orientation_deg=[0.0, 190.0, 0.0]),
        ["parameter 'home_orientation_deg' must be in [-180, 180]"]),
    'string_for_double_array': (
        'fk_node', parameter_file(**dict(PAPER_PLATFORM, platform_joints='p1 p2 p3 p4 p5 p6')),
        ['platform_joints', 'DOUBLE_ARRAY']),
    'missing_base_joints': (
        'ik_node', parameter_file(home_position=[0.0, 0.0, 0.4325]),
        ["parameter 'base_joints' is required"]),
    'yaml_syntax_error': ('fk_node', YAML_SYNTAX_ERROR, ['{path}']),
    'nonexistent_file': ('ik_node', None, ['{path}']),
    'tolerance_out_of_range': (
        'fk_node', parameter_file(**PAPER_PLATFORM) + parameter_file('fk_node', tolerance=0.5),
        ["parameter 'tolerance' must be in (0, 0.01]"]),
    'unknown_mode': (
        'trajectory_node', parameter_file('trajectory_node', mode='spiral'),
        ["parameter 'mode' must be one of table, interpolate"]),
}


@pytest.mark.parametrize('executable, file_text, named',
                         list(BAD_PARAMETER_FILES.values()),
                         ids=list(BAD_PARAMETER_FILES))
def test_bad_parameter_file_stops_node_with_reason(start_node, tmp_path,
                                                   executable, file_text, named):
    """A bad parameter file makes a node exit 1 at start-up, naming the parameter or file."""
    path = tmp_path / 'bad_parameters.yaml'
    if file_text is not None:
        path.write_text(file_text)
    node = start_node(executable, ['--ros-args', '--params-file', str(path)])

    try:
        code = node.process.wait(DEADLINE)
    except subprocess.TimeoutExpired:
        code = None
    output = node.output()

    assert code == EXIT_START_FAILED, f'{executable} exit code {code}:\n{output}'
    for text in named:
        assert text.format(path=path) in output, output
    assert 'Traceback' not in output, output


def trajectory_arguments(config_directory):
    """Return a command line that keeps trajectory_node playing Table 3 (looping, fast rows)."""
    return ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'table3_ramp.yaml'),
            '-p', 'loop:=true', '-p', 'row_period:=0.05']


@pytest.mark.parametrize('executable, arguments, topic, role', [
    ('ik_node', kinematics_arguments, 'target_pose', 'subscriptions'),
    ('fk_node', kinematics_arguments, 'leg_lengths', 'subscriptions'),
    ('trajectory_node', trajectory_arguments, 'target_pose', 'publishers'),
], ids=['ik_node', 'fk_node', 'trajectory_node'])
@pytest.mark.parametrize('signal_number', [signal.SIGINT, signal.SIGTERM],
                         ids=['SIGINT', 'SIGTERM'])
def test_signal_stops_node_cleanly(client, start_node, config_directory,
                                   executable, arguments, topic, role, signal_number):
    """
    SIGINT (Ctrl-C) and SIGTERM (what a supervisor sends) stop a node with exit code 0.

    Each node is running when the signal comes: ik_node and fk_node subscribed to their input,
    trajectory_node playing its looping ramp.
    """
    node = start_node(executable, arguments(config_directory))
    endpoints = getattr(client.node, f'get_{role}_info_by_topic')
    client.wait(lambda: executable in node_names(endpoints(topic)),
                f'{executable} among the {role} of {topic}', [node])

    node.send_signal(signal_number)
    try:
        code = node.process.wait(DEADLINE)
    except subprocess.TimeoutExpired:
        code = None
    output = node.output()

    assert code == 0, f'{executable} exit code {code} after {signal_number!r}:\n{output}'
    assert 'Traceback' not in output, output


def test_ik_node_survives_bad_poses(client, start_node, config_directory):
    """
    A pose with NaN coordinates or a zero quaternion is rejected with a warning saying why.

    ik_node keeps running and answers the good poses sent after each bad one; a non-unit
    quaternion is normalised with a warning.
    """
    node = start_node('ik_node', kinematics_arguments(config_directory))
    lengths = []
    subscription = client.node.create_subscription(
        Float64MultiArray, 'leg_lengths', lengths.append, CLIENT_DEPTH)
    publisher = client.node.create_publisher(Pose, 'target_pose', CLIENT_DEPTH)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and subscription.get_publisher_count() >= 1, 'ik_node connected', [node])
    client.spin_for(SETTLE_TIME)

    publisher.publish(raw_pose_message((math.nan, 0.0, 0.4325), (0.0, 0.0, 0.0, 1.0)))
    publisher.publish(pose_message(TABLE3[3]))
    client.wait(lambda: len(lengths) == 1, 'answer to the good pose after a NaN one', [node])
    # The same reason (invalid_pose): wait out its throttle window so that the next is logged.
    client.spin_for(WARNING_PERIOD + 0.25)
    publisher.publish(raw_pose_message(TABLE3[5][:3], (0.0, 0.0, 0.0, 0.0)))
    publisher.publish(pose_message(TABLE3[7], scale=2.0))
    client.wait(lambda: len(lengths) == 2,
                'answer to the good pose after a zero quaternion', [node])

    assert node.running()
    assert_allclose(lengths[0].data, expected_leg_lengths(TABLE3[3]), rtol=0.0, atol=1e-12)
    assert_allclose(lengths[1].data, expected_leg_lengths(TABLE3[7]), rtol=0.0, atol=1e-12)
    warnings = warnings_in(stop_cleanly(node))
    assert 'target_pose rejected: position must be finite' in warnings, warnings
    assert 'zero quaternion describes no rotation' in warnings, warnings
    assert 'norm 2, not 1: normalised' in warnings, warnings


def test_fk_node_survives_wrong_number_of_lengths(client, start_node, config_directory):
    """Five leg lengths are rejected with a warning saying why; the next six are solved."""
    node = start_node('fk_node', kinematics_arguments(config_directory))
    estimates = []
    subscription = client.node.create_subscription(
        Pose, 'estimated_pose', estimates.append, CLIENT_DEPTH)
    publisher = client.node.create_publisher(Float64MultiArray, 'leg_lengths', CLIENT_DEPTH)
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and subscription.get_publisher_count() >= 1, 'fk_node connected', [node])
    client.spin_for(SETTLE_TIME)

    pose = TABLE3[6]
    publisher.publish(Float64MultiArray(data=expected_leg_lengths(pose)[:5]))
    publisher.publish(Float64MultiArray(data=expected_leg_lengths(pose)))
    client.wait(lambda: estimates, 'estimated_pose of six good lengths', [node])

    assert node.running()
    assert len(estimates) == 1
    assert_allclose(message_position(estimates[0]), pose[:3], rtol=0.0, atol=1e-9)
    assert rotation_angle(message_quaternion(estimates[0]), quaternion(*pose[3:])) <= 1e-9
    warnings = warnings_in(stop_cleanly(node))
    assert 'leg_lengths rejected: expected 6 leg lengths (leg 1..6, metres), got 5' in warnings, (
        warnings)


WRITER_LINES = 30000
WRITER_SCRIPT = f"""\
#!{sys.executable}
import sys
for number in range({WRITER_LINES}):
    sys.stderr.write(f'line {{number:07d}}\\n')
    sys.stderr.flush()
"""


def test_output_read_while_running_keeps_everything(tmp_path, monkeypatch):
    """
    NodeProcess.output() of a running process never loses or overwrites what it wrote.

    The tests and ramp_demo read a node's output while it runs; a read must not disturb the
    file position the child writes at.
    """
    script = tmp_path / 'stewart_output_writer'
    script.write_text(WRITER_SCRIPT)
    script.chmod(0o755)
    monkeypatch.setenv('PATH', f'{tmp_path}{os.pathsep}{os.environ["PATH"]}')
    expected = ''.join(f'line {number:07d}\n' for number in range(WRITER_LINES))

    with NodeProcess('stewart_output_writer') as writer:
        reads = disturbed = 0
        while writer.running():
            reads += 1
            disturbed += not expected.startswith(writer.output())
        assert writer.process.wait(DEADLINE) == 0
        final = writer.output()

    assert final == expected, (
        f'{len(final.splitlines())} of {WRITER_LINES} lines kept; it starts with '
        f'{final[:40]!r}')
    assert disturbed == 0, f'{disturbed} of {reads} reads while running were not a prefix'
