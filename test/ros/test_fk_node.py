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
In-process tests of the FK node: real rclpy, a probe node, one executor.

STEWART_EXECUTOR chooses the executor, as for the nodes (test/conftest.py).

The input lengths of the paper's Table 3 rows come from the package's closed-form inverse
kinematics; the output is checked against the rows typed here in millimetres and degrees, with
orientations compared as textbook quaternions.
"""

import math
from pathlib import Path

from geometry_msgs.msg import Pose
import numpy as np
from numpy.testing import assert_allclose
import pytest
import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter
from reference import quaternion_from_euler, TABLE_3
from std_msgs.msg import Float64MultiArray, MultiArrayDimension, MultiArrayLayout
from std_srvs.srv import Trigger

from stewart_kinematics import forward_kinematics, inverse_kinematics
from stewart_kinematics.parameters import load_geometry
from stewart_kinematics.ros import fk_node
from stewart_kinematics.ros.fk_node import FkNode
import yaml

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
PLATFORM_FILE = str(CONFIG_DIRECTORY / 'paper_platform.yaml')
SOLVER_FILE = str(CONFIG_DIRECTORY / 'solver.yaml')
KINEMATICS_ARGS = ['--ros-args', '--params-file', PLATFORM_FILE, '--params-file', SOLVER_FILE]

#: The paper's Table 3, metres and radians (test/reference.py).
TABLE3 = list(TABLE_3)


def counts(node):
    """Return the node's (received, published, rejected) message counters."""
    accounting = node.accounting
    return accounting.received, accounting.published, accounting.rejected


def assert_pose_message(message, pose, tolerance):
    """Check a Pose against (X, Y, Z, alpha, beta, gamma): position, then quaternion."""
    position = [message.position.x, message.position.y, message.position.z]
    orientation = message.orientation
    quaternion = [orientation.x, orientation.y, orientation.z, orientation.w]
    assert_allclose(position, pose[:3], rtol=0.0, atol=tolerance)
    assert_allclose(quaternion, quaternion_from_euler(*pose[3:]), rtol=0.0, atol=tolerance)


def lengths_message(values, data_offset=0, labelled=True):
    """Build a Float64MultiArray of leg lengths, with or without the 'leg' layout."""
    layout = MultiArrayLayout(data_offset=data_offset)
    if labelled:
        layout.dim = [MultiArrayDimension(label='leg', size=6, stride=6)]
    return Float64MultiArray(layout=layout, data=[float(v) for v in values])


def table_lengths(row):
    """Return the leg lengths of a Table 3 row by closed-form inverse kinematics."""
    geometry = load_geometry(PLATFORM_FILE)
    return inverse_kinematics(geometry, TABLE3[row])


class Probe:
    """A node that publishes leg_lengths and records estimated_pose."""

    def __init__(self):
        """Create the probe node and its publisher and subscription."""
        self.node = Node('fk_probe')
        self.publisher = self.node.create_publisher(Float64MultiArray, 'leg_lengths', 10)
        self.poses = []
        self.node.create_subscription(Pose, 'estimated_pose', self.poses.append, 100)


@pytest.fixture
def start(node_rig):
    """
    Return a starter of an FkNode and a Probe on one executor, connected both ways.

    The starter takes the node's keyword arguments (default: the config files) and returns
    ``(node, probe, executor)``.
    """
    def start_nodes(**node_kwargs):
        node_kwargs.setdefault('cli_args', KINEMATICS_ARGS)
        node = node_rig.add(FkNode(**node_kwargs))
        probe = Probe()
        node_rig.add(probe.node)
        subscription = next(iter(node.subscriptions))
        node_rig.connect(lambda: (probe.publisher.get_subscription_count() >= 1
                                  and subscription.get_publisher_count() >= 1
                                  and node.pose_publisher.get_subscription_count() >= 1),
                         'FK node and probe')
        return node, probe, node_rig.executor
    return start_nodes


def send_and_wait(spin_until, executor, probe, message, answers):
    """Publish leg lengths and spin until ``answers`` poses have arrived in total."""
    probe.publisher.publish(message)
    assert spin_until(executor, lambda: len(probe.poses) >= answers), (
        f'expected {answers} poses, got {len(probe.poses)}')


def test_table3_rows_come_back_as_their_poses(start, spin_until):
    """The lengths of each Table 3 row give that row's pose to 1e-9; the start is warm."""
    node, probe, executor = start()
    assert_allclose(node.tracker.last_pose, TABLE3[0], atol=0.0)
    for row in range(len(TABLE3)):
        send_and_wait(spin_until, executor, probe, lengths_message(table_lengths(row)), row + 1)
        assert_pose_message(probe.poses[-1], TABLE3[row], 1e-9)
        # Warm start: the next solve starts from this solution.
        assert_allclose(node.tracker.last_pose, TABLE3[row], rtol=0.0, atol=1e-9)
    assert counts(node) == (11, 11, 0)


def yawed_home(degrees):
    """Return the home pose turned ``degrees`` about z: (X, Y, Z, alpha, beta, gamma)."""
    return TABLE3[0][:5] + (math.radians(degrees),)


def test_each_solve_starts_from_the_last_solution(start, spin_until):
    """
    Turned 150 degrees about z in steps of 15, the platform is tracked to the right pose.

    From the home pose the lengths of that half turn lead Newton-Raphson to another pose with
    the same lengths (another assembly mode): only a start from the last solution finds it.
    """
    geometry = load_geometry(PLATFORM_FILE)
    turned = yawed_home(150.0)
    cold = forward_kinematics(geometry, inverse_kinematics(geometry, turned))
    assert not (cold.converged and np.allclose(cold.pose, turned, rtol=0.0, atol=1e-6)), (
        'this test needs lengths whose solve from home misses the pose')
    node, probe, executor = start()
    for step in range(1, 11):
        pose = yawed_home(15.0 * step)
        send_and_wait(spin_until, executor, probe,
                      lengths_message(inverse_kinematics(geometry, pose)), step)
        assert_pose_message(probe.poses[-1], pose, 1e-9)
    assert counts(node) == (10, 10, 0)


def test_reset_tracker_service_makes_the_next_solve_start_from_home(start, spin_until):
    """
    The reset_tracker service (a real call) makes the node forget its last solution.

    Tracked to a 150 degree turn, then reset: the same lengths, solved from home, no longer
    give that pose (they lead to another assembly mode); tracking resumes.
    """
    geometry = load_geometry(PLATFORM_FILE)
    turned = yawed_home(150.0)
    node, probe, executor = start()
    for step in range(1, 11):
        send_and_wait(spin_until, executor, probe,
                      lengths_message(inverse_kinematics(geometry, yawed_home(15.0 * step))),
                      step)
    assert_pose_message(probe.poses[-1], turned, 1e-9)

    client = probe.node.create_client(Trigger, 'reset_tracker')
    assert spin_until(executor, client.service_is_ready), 'reset_tracker not offered'
    future = client.call_async(Trigger.Request())
    assert spin_until(executor, future.done)
    response = future.result()
    assert response.success
    assert response.message == 'tracker reset: the next solve starts from the home pose'
    assert_allclose(node.tracker.last_pose, TABLE3[0], atol=0.0)
    assert node.tracker.last_lengths is None and node.tracker.last_solution is None

    probe.publisher.publish(lengths_message(inverse_kinematics(geometry, turned)))
    assert spin_until(executor, lambda: node.accounting.received == 11)
    # From home these lengths give another pose, or none: never the turned one.
    if node.accounting.published == 11:
        assert spin_until(executor, lambda: len(probe.poses) == 11)
        message = probe.poses[-1]
        position = [message.position.x, message.position.y, message.position.z]
        assert not np.allclose(position, turned[:3], rtol=0.0, atol=1e-6)
    answers = len(probe.poses)
    send_and_wait(spin_until, executor, probe, lengths_message(table_lengths(0)), answers + 1)
    assert_pose_message(probe.poses[-1], TABLE3[0], 1e-9)


def test_a_failed_solve_falls_back_to_the_home_pose(start, spin_until):
    """From a turn of -60 degrees about z Table 3's last row diverges; from home it is found."""
    geometry = load_geometry(PLATFORM_FILE)
    turned = yawed_home(-60.0)
    end_lengths = table_lengths(10)
    warm = forward_kinematics(geometry, end_lengths, turned)
    assert not warm.converged, 'this test needs lengths whose solve from the last pose fails'
    node, probe, executor = start()
    send_and_wait(spin_until, executor, probe,
                  lengths_message(inverse_kinematics(geometry, turned)), 1)
    assert_pose_message(probe.poses[-1], turned, 1e-9)
    send_and_wait(spin_until, executor, probe, lengths_message(end_lengths), 2)
    assert_pose_message(probe.poses[-1], TABLE3[10], 1e-9)
    assert counts(node) == (2, 2, 0)


def test_bare_and_offset_arrays_are_accepted(start, spin_until):
    """Lengths without a layout, or after a data_offset, are solved like labelled ones."""
    node, probe, executor = start()
    lengths = list(table_lengths(4))
    send_and_wait(spin_until, executor, probe, lengths_message(lengths, labelled=False), 1)
    send_and_wait(spin_until, executor, probe,
                  lengths_message([-1.0, 42.0] + lengths, data_offset=2, labelled=False), 2)
    for message in probe.poses:
        assert_pose_message(message, TABLE3[4], 1e-9)


def test_bad_lengths_are_rejected_and_the_node_keeps_working(start, spin_until):
    """Wrong sizes, NaN, negative, zero and impossible lengths publish nothing; then it works."""
    node, probe, executor = start()
    send_and_wait(spin_until, executor, probe, lengths_message(table_lengths(5)), 1)
    good = list(table_lengths(6))
    bad = [
        good[:5],
        good + [0.7],
        good[:2] + [math.nan] + good[3:],
        good[:3] + [-0.7] + good[4:],
        good[:5] + [0.0],
        [10.0] * 5 + [0.1],
    ]
    for values in bad:
        probe.publisher.publish(lengths_message(values))
    assert spin_until(executor, lambda: node.accounting.rejected >= len(bad)), (
        f'{node.accounting.rejected} of {len(bad)} bad arrays rejected')
    assert len(probe.poses) == 1
    # A rejected array leaves the warm start where the last good solution put it.
    assert_allclose(node.tracker.last_pose, TABLE3[5], rtol=0.0, atol=1e-9)
    send_and_wait(spin_until, executor, probe, lengths_message(good), 2)
    assert len(probe.poses) == 2
    assert_pose_message(probe.poses[-1], TABLE3[6], 1e-9)
    assert counts(node) == (8, 2, 6)


def test_lengths_beyond_the_limits_are_rejected(start, spin_until):
    """With leg limits around home, lengths outside them are rejected before any solve."""
    limits = [Parameter('leg_length_min', value=0.69), Parameter('leg_length_max', value=0.73)]
    node, probe, executor = start(cli_args=KINEMATICS_ARGS, parameter_overrides=limits)
    probe.publisher.publish(lengths_message(table_lengths(10)))
    send_and_wait(spin_until, executor, probe, lengths_message(table_lengths(0)), 1)
    assert len(probe.poses) == 1
    assert_pose_message(probe.poses[0], TABLE3[0], 1e-9)
    assert node.accounting.rejected == 1


def test_tolerance_change_at_run_time(start, spin_until):
    """
    A valid tolerance is applied to the tracker; -1.0 is refused and changes nothing.

    Leg lengths matched to 1e-9 m fix the pose only to about 1e-8: with the default
    pose_tolerance (1e-9) such a solution may be refused, so the test loosens both.
    """
    node, probe, executor = start()
    settings = node.tracker.settings
    assert (settings.tolerance, settings.max_iterations) == (1e-12, 50)
    for result in node.set_parameters([Parameter('tolerance', value=1e-9),
                                       Parameter('pose_tolerance', value=1e-6)]):
        assert result.successful, result.reason
    assert node.tracker.settings.tolerance == 1e-9
    assert node.tracker.settings.pose_tolerance == 1e-6
    [result] = node.set_parameters([Parameter('tolerance', value=-1.0)])
    assert not result.successful
    assert 'tolerance' in result.reason and '-1.0' in result.reason
    assert node.tracker.settings.tolerance == 1e-9
    assert node.get_parameter('tolerance').value == 1e-9
    send_and_wait(spin_until, executor, probe, lengths_message(table_lengths(3)), 1)
    assert_pose_message(probe.poses[0], TABLE3[3], 1e-6)


def test_max_iterations_change_is_used_by_the_solver(start, spin_until):
    """With max_iterations 1 a far pose is not found (rejected); with 50 again it is."""
    node, probe, executor = start()
    [result] = node.set_parameters([Parameter('max_iterations', value=1)])
    assert result.successful, result.reason
    assert node.tracker.settings.max_iterations == 1
    probe.publisher.publish(lengths_message(table_lengths(10)))
    assert spin_until(executor, lambda: node.accounting.rejected >= 1)
    assert probe.poses == []
    [result] = node.set_parameters([Parameter('max_iterations', value=50)])
    assert result.successful, result.reason
    send_and_wait(spin_until, executor, probe, lengths_message(table_lengths(10)), 1)
    assert_pose_message(probe.poses[0], TABLE3[10], 1e-9)


def test_main_returns_1_for_a_bad_parameter_file(tmp_path):
    """A bad file (base_joints of 17 values) makes main() log and return 1, not raise."""
    with open(PLATFORM_FILE, encoding='utf-8') as stream:
        document = yaml.safe_load(stream)
    document['/**']['ros__parameters']['base_joints'] = [0.1] * 17
    bad_file = tmp_path / 'bad_platform.yaml'
    bad_file.write_text(yaml.safe_dump(document), encoding='utf-8')
    arguments = ['fk_node', '--ros-args', '--params-file', str(bad_file),
                 '--params-file', SOLVER_FILE]
    assert fk_node.main(arguments) == 1
    assert not rclpy.ok()


def test_main_returns_1_for_a_bad_solver_setting(tmp_path):
    """A tolerance out of range in the fk_node section makes main() return 1."""
    bad_file = tmp_path / 'bad_solver.yaml'
    bad_file.write_text(yaml.safe_dump(
        {'fk_node': {'ros__parameters': {'tolerance': 0.5}}}), encoding='utf-8')
    arguments = ['fk_node', '--ros-args', '--params-file', PLATFORM_FILE,
                 '--params-file', str(bad_file)]
    assert fk_node.main(arguments) == 1
    assert not rclpy.ok()
