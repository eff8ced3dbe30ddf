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
Start a motion simulator's chain: telemetry_bridge -> motion_cueing_node -> ik_node.

A simulator sends UDP telemetry packets to telemetry_bridge, which publishes ``vehicle_imu``;
motion_cueing_node turns it into ``target_pose``; ik_node into leg lengths and
``joint_commands`` for the drives, streamed at ``command_rate`` (100 Hz) within the leg limits
on its own clock. The three share the namespace, so their relative topics
connect without remapping. The files: the platform's geometry (``platform_config``) and its
limits (``limits_config``) for motion_cueing_node and ik_node, a cueing preset per vehicle
(``preset``: ``config/cueing_presets/<preset>.yaml``) or a file of your own
(``cueing_config``), and config/telemetry_bridge.yaml for the bridge, whose port and address
the arguments set::

    ros2 launch stewart_kinematics motion_cueing.launch.py preset:=race_car
    ros2 launch stewart_kinematics motion_cueing.launch.py \
        platform_config:=/path/my_platform.yaml limits_config:=/path/my_limits.yaml \
        cueing_config:=/path/my_cueing.yaml telemetry_address:=0.0.0.0 telemetry_port:=47800

doc/how-to/simulator.md walks through it.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

PACKAGE = 'stewart_kinematics'
#: The presets shipped in config/cueing_presets/, by name.
PRESETS = ['car', 'race_car', 'aircraft']


def generate_launch_description():
    """Declare the launch arguments and the three nodes, one process each."""
    config = os.path.join(get_package_share_directory(PACKAGE), 'config')
    namespace = LaunchConfiguration('namespace')
    platform_config = LaunchConfiguration('platform_config')
    limits_config = LaunchConfiguration('limits_config')
    cueing_config = LaunchConfiguration('cueing_config')
    return LaunchDescription([
        DeclareLaunchArgument(
            'namespace', default_value='',
            description='Namespace of the nodes and their topics, such as platform_a'),
        DeclareLaunchArgument(
            'platform_config', default_value=os.path.join(config, 'paper_platform.yaml'),
            description='Parameter file of the geometry, for motion_cueing_node and ik_node'),
        DeclareLaunchArgument(
            'limits_config', default_value=os.path.join(config, 'example_limits.yaml'),
            description='Parameter file of the limits (stroke, leg speed), for both'),
        DeclareLaunchArgument(
            'preset', default_value='car', choices=PRESETS,
            description='The cueing preset: config/cueing_presets/<preset>.yaml'),
        DeclareLaunchArgument(
            'cueing_config',
            default_value=[os.path.join(config, 'cueing_presets', ''),
                           LaunchConfiguration('preset'), '.yaml'],
            description="motion_cueing_node's parameter file; default the preset's"),
        DeclareLaunchArgument(
            'telemetry_address', default_value='127.0.0.1',
            description='The address telemetry_bridge listens on; 0.0.0.0 for every interface'),
        DeclareLaunchArgument(
            'telemetry_port', default_value='47800',
            description='The UDP port telemetry_bridge listens on'),
        DeclareLaunchArgument(
            'command_rate', default_value='100.0',
            description="ik_node's joint_commands stream, Hz: the drives get the leg rates "
                        'checked at the times they are stamped, whatever the transport did '
                        'to the cue'),
        Node(
            package=PACKAGE, executable='telemetry_bridge', namespace=namespace,
            parameters=[os.path.join(config, 'telemetry_bridge.yaml')],
            ros_arguments=['-p', ['telemetry_address:=',
                                  LaunchConfiguration('telemetry_address')],
                           '-p', ['telemetry_port:=', LaunchConfiguration('telemetry_port')]],
            output='screen'),
        Node(
            package=PACKAGE, executable='motion_cueing_node', namespace=namespace,
            parameters=[platform_config, limits_config, cueing_config], output='screen'),
        Node(
            package=PACKAGE, executable='ik_node', namespace=namespace,
            parameters=[platform_config, limits_config],
            ros_arguments=['-p', ['command_rate:=', LaunchConfiguration('command_rate')]],
            output='screen'),
    ])
