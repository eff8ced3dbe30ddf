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
Under sim time, a /clock message rclpy cannot take is skipped; the node keeps its clock.

Found with the soak's hostile clock (benchmarks/soak.py): rclpy's time source turns every
/clock message into a Time and raises ValueError inside the executor for negative seconds, so
any node with ``use_sim_time`` exited with a traceback on one such message. Each node is built
in-process; the test's node publishes /clock on the same executor.
"""

from pathlib import Path

from builtin_interfaces.msg import Time
import pytest
from rclpy.executors import SingleThreadedExecutor
from rclpy.parameter import Parameter
from rosgraph_msgs.msg import Clock

from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.trajectory_node import TrajectoryNode

pytestmark = pytest.mark.node

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
ARGUMENTS = ['--ros-args', '--params-file', str(CONFIG_DIRECTORY / 'paper_platform.yaml'),
             '--params-file', str(CONFIG_DIRECTORY / 'example_limits.yaml')]
NODES = [IkNode, FkNode, TrajectoryNode]
IDS = ['ik_node', 'fk_node', 'trajectory_node']


def tick(executor, publisher, node, sec, nanosec=0, spin_until=None):
    """Publish one /clock message and spin until the node's clock reads it (or 5 s pass)."""
    publisher.publish(Clock(clock=Time(sec=sec, nanosec=nanosec)))
    wanted = sec * 10 ** 9 + nanosec
    return spin_until(executor, lambda: node.get_clock().now().nanoseconds == wanted, 5.0)


@pytest.mark.parametrize('node_class', NODES, ids=IDS)
@pytest.mark.parametrize('at_start', [True, False], ids=['from_start', 'switched_on'])
def test_a_negative_clock_is_skipped_and_the_node_keeps_time(ros, spin_until, node_class,
                                                             at_start):
    """A /clock of -5 s between 100 s and 200 s: skipped, no exception; the clock goes on."""
    node = node_class(cli_args=ARGUMENTS + (['-p', 'use_sim_time:=true'] if at_start else []))
    client = ros.create_node('clock_source')
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    executor.add_node(client)
    try:
        if not at_start:
            [result] = node.set_parameters([Parameter('use_sim_time', value=True)])
            assert result.successful, result.reason
        publisher = client.create_publisher(Clock, '/clock', 10)
        assert spin_until(executor, lambda: publisher.get_subscription_count() >= 1)
        assert tick(executor, publisher, node, 100, spin_until=spin_until)
        publisher.publish(Clock(clock=Time(sec=-5, nanosec=0)))
        executor.spin_once(timeout_sec=0.2)     # raised ValueError here before the fix
        for _ in range(5):
            executor.spin_once(timeout_sec=0.02)
        assert node.get_clock().now().nanoseconds == 100 * 10 ** 9
        assert tick(executor, publisher, node, 200, spin_until=spin_until)
    finally:
        executor.shutdown()
        client.destroy_node()
        node.destroy_node()
