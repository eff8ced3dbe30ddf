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
Start ik_node, fk_node and, unless asked not to, trajectory_node of one platform in a namespace.

The nodes get the installed parameter files, as in the README's ``ros2 run`` lines: the
geometry (``platform_config``, default the paper's platform) for every node, solver.yaml for
fk_node and the ramp (``trajectory_config``, default Table 3) for trajectory_node. Two platforms
run side by side in two namespaces::

    ros2 launch stewart_kinematics stewart_kinematics.launch.py namespace:=platform_a
    ros2 launch stewart_kinematics stewart_kinematics.launch.py namespace:=platform_b \
        platform_config:=/path/to/platform_b.yaml play_ramp:=false

With ``one_process:=true`` the same nodes, with the same names, parameters and topics, run in
one process and one executor (the ``stewart_platform`` console script), as a component
container would run them.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, GroupAction
from launch.conditions import IfCondition, UnlessCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

PACKAGE = 'stewart_kinematics'


def generate_launch_description():
    """Declare the launch arguments and the three nodes, in three processes or in one."""
    config = os.path.join(get_package_share_directory(PACKAGE), 'config')
    namespace = LaunchConfiguration('namespace')
    platform_config = LaunchConfiguration('platform_config')
    trajectory_config = LaunchConfiguration('trajectory_config')
    play_ramp = LaunchConfiguration('play_ramp')
    one_process = LaunchConfiguration('one_process')
    solver_config = os.path.join(config, 'solver.yaml')
    return LaunchDescription([
        DeclareLaunchArgument(
            'namespace', default_value='',
            description='Namespace of the nodes and their topics, such as platform_a'),
        DeclareLaunchArgument(
            'platform_config', default_value=os.path.join(config, 'paper_platform.yaml'),
            description='Parameter file of the geometry (and limits), for every node'),
        DeclareLaunchArgument(
            'trajectory_config', default_value=os.path.join(config, 'table3_ramp.yaml'),
            description='Parameter file of the ramp that trajectory_node plays'),
        DeclareLaunchArgument(
            'play_ramp', default_value='true', choices=['true', 'false'],
            description='Start trajectory_node; false when a planner publishes target_pose'),
        DeclareLaunchArgument(
            'one_process', default_value='false', choices=['true', 'false'],
            description='Run the nodes in one process and one executor (stewart_platform)'),
        GroupAction(condition=UnlessCondition(one_process), actions=[
            Node(
                package=PACKAGE, executable='ik_node', namespace=namespace,
                parameters=[platform_config], output='screen'),
            Node(
                package=PACKAGE, executable='fk_node', namespace=namespace,
                parameters=[platform_config, solver_config], output='screen'),
            Node(
                package=PACKAGE, executable='trajectory_node', namespace=namespace,
                parameters=[platform_config, trajectory_config],
                output='screen', condition=IfCondition(play_ramp)),
        ]),
        # Every node of the process reads the files: each takes its own section and /**.
        Node(
            package=PACKAGE, executable='stewart_platform', namespace=namespace,
            parameters=[platform_config, solver_config, trajectory_config],
            arguments=['--play-ramp', play_ramp], output='screen',
            condition=IfCondition(one_process)),
    ])
