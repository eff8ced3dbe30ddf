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

"""The ``main()`` shared by the nodes: start-up errors, spinning and a clean stop."""

import rclpy
# rclpy exposes these two only from its C extension.
from rclpy._rclpy_pybind11 import RCLError, UnknownROSArgsError
from rclpy.exceptions import ParameterException
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor

#: Exit code of a node that could not start (bad parameters, bad arguments).
EXIT_START_FAILED = 1
#: Longest a node waits for work before it checks again whether it was asked to stop, seconds.
SPIN_SLICE = 0.1


def run_node(node_class, name: str, args=None) -> int:
    """
    Initialise rclpy, build and spin a node until SIGINT or SIGTERM, then shut down.

    :param node_class: the node's class, constructed without arguments.
    :param name: the node's default name, for the log of a failed start.
    :param args: command-line arguments (``--ros-args ...``); ``None`` reads ``sys.argv``.
    :returns: 0 after a clean stop, :data:`EXIT_START_FAILED` when the node could not be
        built, with a fatal log that says why.
    """
    try:
        rclpy.init(args=args)
    except (RCLError, UnknownROSArgsError) as error:
        # rcl rejects unreadable parameter files and malformed --ros-args here.
        rclpy.logging.get_logger(name).fatal(f'cannot start: {error}')
        return EXIT_START_FAILED
    try:
        node = node_class()
    except (ParameterException, ValueError) as error:
        rclpy.logging.get_logger(name).fatal(f'cannot start: {error}')
        rclpy.try_shutdown()
        return EXIT_START_FAILED
    except KeyboardInterrupt:
        rclpy.try_shutdown()
        return 0
    try:
        executor = SingleThreadedExecutor()
        executor.add_node(node)
        # Spinning in slices rather than rclpy.spin(): a signal that lands between two waits
        # of a blocking spin can leave it waiting forever (ros2/rclpy#1166).
        while rclpy.ok():
            executor.spin_once(timeout_sec=SPIN_SLICE)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except RCLError:
        # The signal handler shut the context down while a wait set was being built.
        if rclpy.ok():
            raise
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
    return 0
