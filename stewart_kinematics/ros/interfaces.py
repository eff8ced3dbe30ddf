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
Every node's interface, declared once: its topics and services, their types, QoS and meaning.

The nodes create their publishers, subscriptions and services from these declarations
(:func:`stewart_kinematics.ros.node_main.create_output_publisher` and its siblings take an
:class:`Endpoint`), the tests check that a running node offers exactly what is declared, and
the documentation's node tables are generated from them. Topic names are relative (namespaces
and remaps apply), except the ROS-wide ``/tf``, ``/tf_static`` and ``/diagnostics``.

Message types are named as ROS names them (``geometry_msgs/msg/Pose``) and imported on first
use, so this module imports no ROS package: the documentation reads it without rclpy, and
``tf2_msgs`` stays optional.
"""

from dataclasses import dataclass
import importlib
from typing import Tuple

#: Kinds of endpoint.
SUBSCRIPTION = 'subscription'
PUBLISHER = 'publisher'
SERVICE = 'service'

#: The QoS of the package's endpoints, in words (the nodes build the profiles).
QUEUE = 'reliable, keep last queue_depth'
LATCHED = 'reliable, transient local, depth 1 (latched)'
TF = 'reliable, keep last 100 (as tf2_ros broadcasts)'
TF_STATIC = 'reliable, transient local, keep last 1 (as tf2_ros static broadcasts)'
DIAGNOSTICS = 'reliable, keep last 10'
SERVICE_QOS = 'services default'


@dataclass(frozen=True)
class Endpoint:
    """
    One topic or service of a node.

    :param name: topic or service name, relative unless it starts with ``/``.
    :param kind: :data:`SUBSCRIPTION`, :data:`PUBLISHER` or :data:`SERVICE`.
    :param type_name: the message or service type, as ``package/msg/Name`` or
        ``package/srv/Name``.
    :param qos: the QoS, in words (see the constants of this module).
    :param meaning: what it carries, with units and frames.
    :param condition: when the node has it (a parameter that turns it on), ``''``: always.
    """

    name: str
    kind: str
    type_name: str
    qos: str
    meaning: str
    condition: str = ''

    @property
    def message_type(self):
        """Return the message or service class, imported now (``ImportError`` if missing)."""
        package, kind, name = self.type_name.split('/')
        return getattr(importlib.import_module(f'{package}.{kind}'), name)


@dataclass(frozen=True)
class NodeInterface:
    """
    A node's topics and services, in the order the node creates them.

    :param node: the node's default name.
    :param endpoints: every :class:`Endpoint`.
    """

    node: str
    endpoints: Tuple[Endpoint, ...]

    def __getitem__(self, name: str) -> Endpoint:
        """Return the endpoint of a topic or service name; ``KeyError`` naming the known ones."""
        for endpoint in self.endpoints:
            if endpoint.name == name:
                return endpoint
        raise KeyError(f'{self.node} declares no {name!r}; it has '
                       + ', '.join(endpoint.name for endpoint in self.endpoints))

    def of_kind(self, kind: str) -> Tuple[Endpoint, ...]:
        """Return the endpoints of one kind, in order."""
        return tuple(endpoint for endpoint in self.endpoints if endpoint.kind == kind)


#: The endpoints every node of the package has.
DIAGNOSTICS_TOPIC = Endpoint(
    '/diagnostics', PUBLISHER, 'diagnostic_msgs/msg/DiagnosticArray', DIAGNOSTICS,
    'One report a second: per input topic, messages received, published and refused, refusals '
    'by reason, the latest reason with its details')

IK_NODE = NodeInterface('ik_node', (
    Endpoint('target_pose', SUBSCRIPTION, 'geometry_msgs/msg/Pose', QUEUE,
             'Commanded pose of the tool frame in the base frame, metres and a quaternion; '
             'the outputs carry the time of arrival'),
    Endpoint('target_pose_stamped', SUBSCRIPTION, 'geometry_msgs/msg/PoseStamped', QUEUE,
             'The same, in base_frame or user_frame; joint_commands carries its stamp'),
    Endpoint('target_twist', SUBSCRIPTION, 'geometry_msgs/msg/Twist', QUEUE,
             'Commanded platform twist, base frame, m/s and rad/s, at the last accepted pose'),
    Endpoint('leg_lengths', PUBLISHER, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'Leg lengths l_1..l_6 of each accepted pose, metres'),
    Endpoint('leg_extensions', PUBLISHER, 'std_msgs/msg/Float64MultiArray', QUEUE,
             "Each length minus its length at the home pose (the paper's q_i), metres"),
    Endpoint('joint_commands', PUBLISHER, 'sensor_msgs/msg/JointState', QUEUE,
             'The legs as prismatic joints (joint_names), positions length - actuator_offsets, '
             'metres; streamed at command_rate with velocities when command_rate is set'),
    Endpoint('leg_velocities', PUBLISHER, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'Rates of change of the leg lengths for each accepted twist, m/s'),
    Endpoint('platform_markers', PUBLISHER, 'visualization_msgs/msg/MarkerArray', QUEUE,
             'The platform and its legs for RViz, legs that break a limit in red, at most '
             'marker_rate'),
    Endpoint('workspace_markers', PUBLISHER, 'visualization_msgs/msg/MarkerArray', LATCHED,
             'Boundary of the constant-orientation workspace at the home orientation'),
    Endpoint('travel_ranges', PUBLISHER, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'Range left along each axis from the last accepted pose, at travel_range_rate: '
             '12 values, negative then positive, X Y Z in metres, alpha beta gamma in radians'),
    Endpoint('/tf', PUBLISHER, 'tf2_msgs/msg/TFMessage', TF,
             'The commanded platform frame, base_frame -> <platform_frame>_commanded',
             condition='publish_commanded_tf'),
    DIAGNOSTICS_TOPIC,
))

FK_NODE = NodeInterface('fk_node', (
    Endpoint('leg_lengths', SUBSCRIPTION, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'Measured leg lengths l_1..l_6, metres'),
    Endpoint('joint_states', SUBSCRIPTION, 'sensor_msgs/msg/JointState', QUEUE,
             'Measured actuator positions (and velocities) by joint name; a state naming none '
             'of joint_names belongs to another platform and is skipped'),
    Endpoint('leg_velocities', SUBSCRIPTION, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'Measured leg velocities, m/s: turned into a twist at the last estimated pose'),
    Endpoint('estimated_pose', PUBLISHER, 'geometry_msgs/msg/Pose', QUEUE,
             'Estimated pose of the tool frame in the base frame, metres and a quaternion'),
    Endpoint('estimated_pose_stamped', PUBLISHER, 'geometry_msgs/msg/PoseStamped', QUEUE,
             'The same in estimated_pose_frame, with the stamp of the measurement'),
    Endpoint('estimated_twist', PUBLISHER, 'geometry_msgs/msg/Twist', QUEUE,
             'Platform twist from leg velocities at the last pose, base frame, m/s and rad/s'),
    Endpoint('/tf', PUBLISHER, 'tf2_msgs/msg/TFMessage', TF,
             'The estimated platform frame, base_frame -> platform_frame, with the stamp of '
             'the measurement', condition='publish_tf'),
    Endpoint('/tf_static', PUBLISHER, 'tf2_msgs/msg/TFMessage', TF_STATIC,
             'The user and tool frames', condition='publish_tf'),
    Endpoint('reset_tracker', SERVICE, 'std_srvs/srv/Trigger', SERVICE_QOS,
             'The next solve starts from the home pose (homing, restarts)'),
    DIAGNOSTICS_TOPIC,
))

TRAJECTORY_NODE = NodeInterface('trajectory_node', (
    Endpoint('pose_trajectory', SUBSCRIPTION, 'trajectory_msgs/msg/MultiDOFJointTrajectory',
             QUEUE, 'A timed platform trajectory (one joint: the tool frame), checked whole, '
             'timed or retimed, then handed on'),
    Endpoint('pose_path', SUBSCRIPTION, 'nav_msgs/msg/Path', QUEUE,
             'Waypoint poses without timing, always retimed'),
    Endpoint('target_pose', PUBLISHER, 'geometry_msgs/msg/Pose', QUEUE,
             'The ramp, and accepted trajectories when play is set: tool frame poses, base '
             'frame'),
    Endpoint('leg_trajectory', PUBLISHER, 'trajectory_msgs/msg/JointTrajectory', QUEUE,
             'An accepted trajectory for the actuators: positions, velocities, accelerations '
             'at publish_rate and every waypoint, for joint_trajectory_controller'),
    DIAGNOSTICS_TOPIC,
))

MOTION_CUEING_NODE = NodeInterface('motion_cueing_node', (
    Endpoint('vehicle_imu', SUBSCRIPTION, 'sensor_msgs/msg/Imu', QUEUE,
             "The vehicle's specific force (linear_acceleration, m/s^2: 9.81 on z at rest) and "
             "angular velocity (rad/s) at the driver's head, vehicle frame (x forward, y left, "
             'z up); header.stamp sets the time step; the orientation is not used'),
    Endpoint('target_pose', PUBLISHER, 'geometry_msgs/msg/Pose', QUEUE,
             'The cue as the pose of the tool frame in the base frame, one per sample (and while '
             'easing home after input_timeout), for ik_node'),
    Endpoint('cue_pose', PUBLISHER, 'geometry_msgs/msg/PoseStamped', QUEUE,
             'The platform frame in base_frame, with the stamp of the sample: for VR motion '
             'compensation and RViz'),
    Endpoint('perceived_accel', PUBLISHER, 'geometry_msgs/msg/AccelStamped', QUEUE,
             'The specific force felt at head_position (platform frame, m/s^2) in accel.linear, '
             'with the stamp of the sample it belongs to (one sample behind); accel.angular is '
             'zero'),
    Endpoint('reset', SERVICE, 'std_srvs/srv/Trigger', SERVICE_QOS,
             'Wash out to neutral: the washout forgets its history, the platform glides home '
             'within the actuator limits'),
    DIAGNOSTICS_TOPIC,
))

#: Every node's interface, by node name.
NODE_INTERFACES = {
    interface.node: interface
    for interface in (IK_NODE, FK_NODE, TRAJECTORY_NODE, MOTION_CUEING_NODE)}


def markdown_table(interface: NodeInterface) -> str:
    """
    Render a node's interface as the documentation's table: name, kind, type, QoS, meaning.

    A test compares the documentation with this, so it cannot drift from the code.
    """
    lines = ['| Topic or service | Kind | Type | QoS | Meaning |',
             '| --- | --- | --- | --- | --- |']
    for endpoint in interface.endpoints:
        meaning = endpoint.meaning + (f' (with `{endpoint.condition}`)'
                                      if endpoint.condition else '')
        lines.append(f'| `{endpoint.name}` | {endpoint.kind} | `{endpoint.type_name}` | '
                     f'{endpoint.qos} | {meaning} |')
    return '\n'.join(lines)
