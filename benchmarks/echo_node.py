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
Bare rclpy echo node: the middleware's own limit, for the node benchmarks.

Subscribes ``echo_in`` (geometry_msgs/msg/Pose) and republishes every message unchanged on
``echo_out``, with no work in between; reliable, keep-last queues of depth ``queue_depth``
(``-p queue_depth:=100``, default 100); rclpy's defaults otherwise. It spins as the package's
nodes do (:func:`stewart_kinematics.ros.node_main.run_nodes`: slices of 0.1 s in the main
thread) on the executor that ``--executor`` names before ``--ros-args``, else
``STEWART_EXECUTOR``, else the EventsExecutor. Run it as a script:
``python benchmarks/echo_node.py --executor single_threaded --ros-args -p queue_depth:=100``.
"""

import signal
import sys

from geometry_msgs.msg import Pose
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions
from rclpy.utilities import remove_ros_args

from stewart_kinematics.ros import node_main
from stewart_kinematics.ros.node_main import create_executor, executor_name

#: Queue depth when no ``queue_depth`` parameter is given.
DEFAULT_QUEUE_DEPTH = 100


class EchoNode(Node):
    """Republish every pose received on ``echo_in`` on ``echo_out``."""

    def __init__(self, **kwargs):
        super().__init__('echo_node', **kwargs)
        depth = self.declare_parameter('queue_depth', DEFAULT_QUEUE_DEPTH).value
        self.publisher = self.create_publisher(Pose, 'echo_out', depth)
        self.create_subscription(Pose, 'echo_in', self.publisher.publish, depth)


def main(args=None) -> int:
    """Run the echo node until SIGINT or SIGTERM."""
    args = sys.argv if args is None else args
    kind = executor_name(remove_ros_args(args))
    stop = []
    for number in (signal.SIGINT, signal.SIGTERM):
        signal.signal(number, lambda number, frame: stop.append(number))
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    node = EchoNode()
    executor = create_executor(kind)
    executor.add_node(node)
    try:
        while not stop and rclpy.ok():
            node_main.spin_slice(executor)
    except ExternalShutdownException:
        pass
    finally:
        executor.shutdown()
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
