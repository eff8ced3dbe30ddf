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

With ``managed:=true`` every node is a managed (lifecycle) node (the ``managed`` parameter,
doc/lifecycle.md), started unconfigured; with ``autostart:=true`` (the default) each is then
configured and, once inactive, activated, as nav2's lifecycle_manager does with autostart:
launch_ros's ``LifecycleNode`` with a ``ChangeState`` event at start and an
``OnStateTransition`` handler. ``autostart:=false`` leaves them unconfigured for a lifecycle
manager or ``ros2 lifecycle set``. In one process (``one_process:=true``), which launch_ros
cannot address node by node, ``stewart_platform --autostart`` takes the same two transitions.
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, EmitEvent, GroupAction, RegisterEventHandler
from launch.conditions import IfCondition, UnlessCondition
from launch.events import matches_action
from launch.substitutions import AndSubstitution, LaunchConfiguration, NotSubstitution
from launch_ros.actions import LifecycleNode, Node
from launch_ros.event_handlers import OnStateTransition
from launch_ros.events.lifecycle import ChangeState
from lifecycle_msgs.msg import Transition

PACKAGE = 'stewart_kinematics'


def platform_nodes(namespace, files, play_ramp, managed, autostart):
    """
    Return the actions of the three nodes, one process each: plain or lifecycle nodes.

    :param files: the parameter files of each executable, by name.
    :param managed: ``None`` for plain nodes; else the nodes are LifecycleNodes given
        ``managed:=true``, and ``autostart`` (a substitution) configures then activates each.
    """
    actions = []
    for executable in ('ik_node', 'fk_node', 'trajectory_node'):
        condition = IfCondition(play_ramp) if executable == 'trajectory_node' else None
        if managed is None:
            actions.append(Node(
                package=PACKAGE, executable=executable, namespace=namespace,
                parameters=files[executable], output='screen', condition=condition))
            continue
        node = LifecycleNode(
            package=PACKAGE, executable=executable, name=executable, namespace=namespace,
            parameters=files[executable], ros_arguments=['-p', 'managed:=true'],
            output='screen', condition=condition)
        actions.append(node)
        started = IfCondition(autostart if condition is None else AndSubstitution(
            play_ramp, autostart))
        actions.append(EmitEvent(event=ChangeState(
            lifecycle_node_matcher=matches_action(node),
            transition_id=Transition.TRANSITION_CONFIGURE), condition=started))
        actions.append(RegisterEventHandler(OnStateTransition(
            target_lifecycle_node=node, start_state='configuring', goal_state='inactive',
            entities=[EmitEvent(event=ChangeState(
                lifecycle_node_matcher=matches_action(node),
                transition_id=Transition.TRANSITION_ACTIVATE))]), condition=started))
    return actions


def generate_launch_description():
    """Declare the launch arguments and the three nodes, in three processes or in one."""
    config = os.path.join(get_package_share_directory(PACKAGE), 'config')
    namespace = LaunchConfiguration('namespace')
    platform_config = LaunchConfiguration('platform_config')
    trajectory_config = LaunchConfiguration('trajectory_config')
    play_ramp = LaunchConfiguration('play_ramp')
    one_process = LaunchConfiguration('one_process')
    managed = LaunchConfiguration('managed')
    autostart = LaunchConfiguration('autostart')
    solver_config = os.path.join(config, 'solver.yaml')
    files = {'ik_node': [platform_config], 'fk_node': [platform_config, solver_config],
             'trajectory_node': [platform_config, trajectory_config]}
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
        DeclareLaunchArgument(
            'managed', default_value='false', choices=['true', 'false'],
            description='Start every node managed (lifecycle), unconfigured (doc/lifecycle.md)'),
        DeclareLaunchArgument(
            'autostart', default_value='true', choices=['true', 'false'],
            description='With managed:=true, configure then activate every node at start'),
        GroupAction(condition=UnlessCondition(one_process), actions=[
            GroupAction(condition=UnlessCondition(managed), actions=platform_nodes(
                namespace, files, play_ramp, None, autostart)),
            GroupAction(condition=IfCondition(managed), actions=platform_nodes(
                namespace, files, play_ramp, managed, autostart)),
        ]),
        # Every node of the process reads the files: each takes its own section and /**.
        Node(
            package=PACKAGE, executable='stewart_platform', namespace=namespace,
            parameters=[platform_config, solver_config, trajectory_config],
            arguments=['--play-ramp', play_ramp], output='screen',
            condition=IfCondition(AndSubstitution(one_process, NotSubstitution(managed)))),
        Node(
            package=PACKAGE, executable='stewart_platform', namespace=namespace,
            parameters=[platform_config, solver_config, trajectory_config],
            arguments=['--play-ramp', play_ramp, '--autostart', autostart],
            ros_arguments=['-p', 'managed:=true'], output='screen',
            condition=IfCondition(AndSubstitution(one_process, managed))),
    ])
