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

r"""
The whole chain in one process: ik_node, fk_node and, if asked, trajectory_node.

As a component container would run them: the same node classes, names, parameters and topics
as the three console scripts, in one process and one executor, so that a message between two
of them costs no trip through another process. ROS arguments apply to every node of the
process, as they do in a container: ``--params-file`` files give each node its own section and
``/**``; ``-r __ns:=/platform_a`` moves them all (do not rename them with ``-r __node:=``)::

    stewart_platform --play-ramp true --ros-args --params-file config/paper_platform.yaml \\
        --params-file config/solver.yaml --params-file config/table3_ramp.yaml

With ``-p managed:=true`` the nodes are managed (lifecycle) nodes, each with its own
lifecycle services; ``--autostart true`` configures and activates each at start, as the launch
file's ``autostart`` does for nodes in processes of their own (launch_ros addresses a
lifecycle node by its process).

``--executor single_threaded`` (before ``--ros-args``) spins them on rclpy's default executor
instead of the EventsExecutor, as for every node (:mod:`stewart_kinematics.ros.node_main`).
"""

import argparse
import sys

from rclpy.utilities import remove_ros_args

from stewart_kinematics.ros.fk_node import FkNode
from stewart_kinematics.ros.ik_node import IkNode
from stewart_kinematics.ros.node_main import (
    DEFAULT_EXECUTOR,
    EXECUTOR_OPTION,
    EXECUTOR_VARIABLE,
    EXECUTORS,
    run_nodes,
)
from stewart_kinematics.ros.trajectory_node import TrajectoryNode


def parse_arguments(argv):
    """Return the options before ``--ros-args`` (``argv`` without the program name)."""
    parser = argparse.ArgumentParser(prog='stewart_platform', description=__doc__.split('\n')[1])
    parser.add_argument('--play-ramp', choices=('true', 'false'), default='false',
                        help='also run trajectory_node, which plays its ramp (default false)')
    parser.add_argument('--autostart', choices=('true', 'false'), default='false',
                        help='configure then activate every managed node (managed:=true) at '
                        'start, as a lifecycle manager would (default false)')
    # Checked by run_nodes, as for the other nodes: an unknown name exits with code 1.
    parser.add_argument(EXECUTOR_OPTION, metavar='|'.join(EXECUTORS),
                        help=f'the executor (default: ${EXECUTOR_VARIABLE}, else '
                        f'{DEFAULT_EXECUTOR})')
    return parser.parse_args(argv)


def main(args=None) -> int:
    """Run the nodes in one executor until SIGINT or SIGTERM; see :func:`run_nodes`."""
    argv = sys.argv if args is None else ['stewart_platform', *args]
    options = parse_arguments(remove_ros_args(argv)[1:])
    node_classes = [IkNode, FkNode] + ([TrajectoryNode] if options.play_ramp == 'true' else [])
    # rcl reads only what follows --ros-args: --play-ramp does not disturb it.
    return run_nodes(node_classes, 'stewart_platform', args,
                     autostart=options.autostart == 'true')


if __name__ == '__main__':
    raise SystemExit(main())
