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
In-process tests of the trajectory node: real rclpy, a probe node, one executor.

STEWART_EXECUTOR chooses the executor, as for the nodes (test/conftest.py).

The node plays config/table3_ramp.yaml, with a short row period or duration given as
parameter overrides; the received poses are compared with the paper's Table 3 typed here in
millimetres and degrees, orientations as textbook quaternions. What the ramp plays when (rows,
samples, loops) is RampPlayback's, tested without rclpy in test_playback.py; these tests
check that the node plays it on its timers and clock, and stops when it is over.
"""

from pathlib import Path

from geometry_msgs.msg import Pose
import numpy as np
from numpy.testing import assert_allclose
import pytest
import rclpy
from rclpy.node import Node
from rclpy.parameter import Parameter
from reference import quaternion_from_euler, TABLE_3

from stewart_kinematics.ros import trajectory_node
from stewart_kinematics.ros.trajectory_node import TrajectoryNode
import yaml

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
RAMP_FILE = str(CONFIG_DIRECTORY / 'table3_ramp.yaml')
PLATFORM_FILE = str(CONFIG_DIRECTORY / 'paper_platform.yaml')
RAMP_ARGS = ['--ros-args', '--params-file', PLATFORM_FILE, '--params-file', RAMP_FILE]

#: The paper's Table 3, metres and radians (test/reference.py).
TABLE3 = np.array(TABLE_3)
#: Seconds of silence that show a finished ramp has stopped (ten row periods of 0.05 s).
QUIET_TIME = 0.5


def position_of(message):
    """Return a Pose's position as an array."""
    return np.array([message.position.x, message.position.y, message.position.z])


def quaternion_of(message):
    """Return a Pose's quaternion (x, y, z, w) as an array."""
    orientation = message.orientation
    return np.array([orientation.x, orientation.y, orientation.z, orientation.w])


def assert_pose_message(message, pose, tolerance=1e-9):
    """Check a Pose against (X, Y, Z, alpha, beta, gamma): position, then quaternion."""
    assert_allclose(position_of(message), pose[:3], rtol=0.0, atol=tolerance)
    assert_allclose(quaternion_of(message), quaternion_from_euler(*pose[3:]),
                    rtol=0.0, atol=tolerance)


class Probe:
    """A node whose subscription to target_pose can be created late."""

    def __init__(self, subscribe=True):
        """Create the probe node, and its subscription unless ``subscribe`` is False."""
        self.node = Node('trajectory_probe')
        self.poses = []
        if subscribe:
            self.subscribe()

    def subscribe(self):
        """Create the subscription to target_pose."""
        self.node.create_subscription(Pose, 'target_pose', self.poses.append, 100)


@pytest.fixture
def start(node_rig):
    """
    Return a starter of a TrajectoryNode and a Probe on one executor.

    The starter takes the parameter overrides (on top of config/table3_ramp.yaml) and whether
    the probe subscribes at once, and returns ``(node, probe, executor)``.
    """
    def start_nodes(overrides, subscribe=True):
        probe = Probe(subscribe)
        node_rig.add(probe.node)
        parameters = [Parameter(name, value=value) for name, value in overrides.items()]
        node = node_rig.add(TrajectoryNode(cli_args=RAMP_ARGS, parameter_overrides=parameters))
        return node, probe, node_rig.executor
    return start_nodes


def test_table_mode_plays_the_11_rows_in_order_then_stops(start, spin_until):
    """Table mode publishes Table 3's 11 rows in order, once, then nothing more."""
    node, probe, executor = start({'row_period': 0.05, 'min_subscribers': 1})
    assert node.settings.ramp.mode == 'table' and node.settings.ramp.loop is False
    assert spin_until(executor, lambda: len(probe.poses) >= 11), (
        f'{len(probe.poses)} of 11 rows received')
    for message, row in zip(probe.poses, TABLE3):
        assert_pose_message(message, row)
    assert not spin_until(executor, lambda: len(probe.poses) > 11, timeout=QUIET_TIME)
    assert len(probe.poses) == 11
    assert node.published == 11
    assert node.timer.is_canceled()


def test_interpolate_mode_samples_the_straight_line(start, spin_until):
    """Every sample lies on start + s (end - start), s rising from 0 to exactly 1 at the end."""
    duration, rate = 0.5, 50.0
    node, probe, executor = start({
        'mode': 'interpolate', 'duration': duration, 'publish_rate': rate,
        'min_subscribers': 1})

    def finished():
        return (node.timer is not None and node.timer.is_canceled()
                and len(probe.poses) >= node.published)
    assert spin_until(executor, finished), (
        f'ramp not finished: {node.published} published, {len(probe.poses)} received')
    assert not spin_until(executor, lambda: len(probe.poses) > node.published, timeout=0.2)
    start_pose, end_pose = TABLE3[0], TABLE3[-1]
    direction = end_pose - start_pose
    fractions = []
    for message in probe.poses:
        offset = position_of(message) - start_pose[:3]
        s = float(offset @ direction[:3] / (direction[:3] @ direction[:3]))
        pose = start_pose + s * direction
        assert_pose_message(message, pose)
        assert -1e-9 <= s <= 1.0 + 1e-9
        fractions.append(s)
    assert len(fractions) == node.published
    # About duration * rate + 1 samples; a loaded machine may drop timer ticks.
    assert duration * rate * 0.5 <= len(fractions) <= duration * rate + 2
    assert all(later > earlier for earlier, later in zip(fractions, fractions[1:])), fractions
    # The first sample is taken as the ramp starts: well within one sample period of s = 0.
    assert fractions[0] < 0.5 / (duration * rate)
    assert_pose_message(probe.poses[0], start_pose, 1e-3)
    assert fractions[-1] == pytest.approx(1.0, abs=1e-9)
    assert_pose_message(probe.poses[-1], end_pose)


def test_min_subscribers_waits_for_a_subscriber(start, spin_until):
    """Nothing is published while nobody subscribes; the first pose received is row 0."""
    node, probe, executor = start({'row_period': 0.05, 'min_subscribers': 1}, subscribe=False)
    assert not spin_until(executor, lambda: node.published > 0, timeout=1.0)
    assert node.published == 0
    probe.subscribe()
    assert spin_until(executor, lambda: len(probe.poses) >= 11), (
        f'{len(probe.poses)} of 11 rows received')
    assert_pose_message(probe.poses[0], TABLE3[0])
    assert_pose_message(probe.poses[10], TABLE3[10])
    assert node.published == 11


def test_start_delay_of_zero_starts_at_once(start, spin_until):
    """With min_subscribers 0 and no delay the ramp plays with no subscriber at all."""
    node, _, executor = start(
        {'row_period': 0.05, 'min_subscribers': 0, 'start_delay': 0.0}, subscribe=False)
    assert spin_until(executor, lambda: node.published >= 11)
    assert not spin_until(executor, lambda: node.published > 11, timeout=0.3)


@pytest.mark.parametrize('name, value', [
    ('position_end', [0.1, 0.15, 0.54]),
    ('mode', 'circle'),
    ('position_start', [0.0, 0.4325]),
])
def test_main_returns_1_for_a_bad_parameter_file(tmp_path, name, value):
    """A ramp that is not whole steps, an unknown mode or a short array makes main() return 1."""
    with open(RAMP_FILE, encoding='utf-8') as stream:
        document = yaml.safe_load(stream)
    document['/**/trajectory_node']['ros__parameters'][name] = value
    bad_file = tmp_path / 'bad_ramp.yaml'
    bad_file.write_text(yaml.safe_dump(document), encoding='utf-8')
    assert trajectory_node.main(
        ['trajectory_node', '--ros-args', '--params-file', str(bad_file)]) == 1
    assert not rclpy.ok()
