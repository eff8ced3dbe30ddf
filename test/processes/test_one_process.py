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
``stewart_platform``: ik_node, fk_node and trajectory_node in one process, as a user starts it.

The console script runs as a process with the shipped parameter files and a namespace; the
test's node sees the three nodes under their usual names in that namespace, and the Table 3
ramp going through them (trajectory_node -> target_pose -> ik_node -> leg_lengths -> fk_node
-> estimated_pose) to the poses of the table. SIGINT stops the process with exit code 0.
"""

from geometry_msgs.msg import Pose
from numpy.testing import assert_allclose
import pytest
from reference import quaternion_from_euler, TABLE_3

pytestmark = pytest.mark.process


def test_one_process_plays_the_ramp_through_its_three_nodes(
        client, start_node, config_directory):
    """The three nodes, named as usual in the namespace; the ramp arrives as Table 3."""
    process = start_node('stewart_platform', [
        '--play-ramp', 'true', '--ros-args',
        '--params-file', str(config_directory / 'paper_platform.yaml'),
        '--params-file', str(config_directory / 'solver.yaml'),
        '--params-file', str(config_directory / 'table3_ramp.yaml'),
        '-p', 'trajectory_node:row_period:=0.05', '-p', 'trajectory_node:min_subscribers:=2',
        '-r', '__ns:=/platform_a'])
    estimates = []
    client.node.create_subscription(Pose, '/platform_a/estimated_pose', estimates.append, 100)
    client.wait(lambda: client.node.count_publishers('/platform_a/estimated_pose') >= 1,
                'fk_node publishes', [process])
    # The ramp starts once this second subscriber of target_pose (after ik_node) matched.
    client.node.create_subscription(Pose, '/platform_a/target_pose', lambda message: None, 100)
    client.wait(lambda: len(estimates) == len(TABLE_3), 'the 11 poses of the ramp', [process])

    names = set(client.node.get_node_names_and_namespaces())
    assert {('ik_node', '/platform_a'), ('fk_node', '/platform_a'),
            ('trajectory_node', '/platform_a')} <= names
    for message, row in zip(estimates, TABLE_3):
        p, o = message.position, message.orientation
        assert_allclose([p.x, p.y, p.z], row[:3], rtol=0, atol=1e-9)
        assert_allclose([o.x, o.y, o.z, o.w], quaternion_from_euler(*row[3:]), rtol=0,
                        atol=1e-9)
    code = process.stop()
    assert code == 0, process.output()
