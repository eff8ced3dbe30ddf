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
:class:`Endpoint` and build its declared :class:`Qos`), the tests check that a running node
offers exactly what is declared, with the declared QoS, and the documentation's node tables are
generated from them. Topic names are relative (namespaces and remaps apply), except the
ROS-wide ``/tf``, ``/tf_static`` and ``/diagnostics``.

Message types are named as ROS names them (``geometry_msgs/msg/Pose``) and imported on first
use, and a QoS is declared as data whose rclpy profile is built on demand
(:meth:`Qos.profile`), so this module imports no ROS package: the documentation reads it
without rclpy, and ``tf2_msgs`` stays optional.
"""

from dataclasses import dataclass
import importlib
from typing import Optional, Tuple, Union

#: Kinds of endpoint.
SUBSCRIPTION = 'subscription'
PUBLISHER = 'publisher'
SERVICE = 'service'
#: An action server (its goal, cancel and result services and its feedback and status topics).
ACTION = 'action'

#: A declared depth that is the node's ``queue_depth`` parameter (QUEUE_PARAMETERS).
QUEUE_DEPTH = 'queue_depth'
#: The policies a :class:`Qos` may declare, as rclpy's enums name them (lower case).
RELIABILITIES = ('reliable', 'best_effort')
DURABILITIES = ('volatile', 'transient_local')
HISTORIES = ('keep_last', 'keep_all')


@dataclass(frozen=True)
class Qos:
    """
    A QoS profile, declared: the nodes create the endpoint with it, the docs print it.

    Deadline, lifespan and liveliness are rclpy's defaults. The standard ``qos_overrides``
    parameters may still change reliability, history and depth of a node's publishers and
    subscriptions at start-up (see :mod:`stewart_kinematics.ros.node_main`).

    :param reliability: ``'reliable'`` or ``'best_effort'``.
    :param durability: ``'volatile'``, or ``'transient_local'`` (latched: a subscriber that
        joins later gets the last messages kept).
    :param history: ``'keep_last'`` (``depth`` messages) or ``'keep_all'``.
    :param depth: messages kept, or :data:`QUEUE_DEPTH`: the node's ``queue_depth`` parameter.
    :param note: where the profile comes from or what it is for, printed after it.

    >>> print(Qos(durability='transient_local', depth=1, note='latched'))
    reliable, transient local, keep last 1 (latched)
    >>> print(Qos())
    reliable, keep last `queue_depth`
    """

    reliability: str = 'reliable'
    durability: str = 'volatile'
    history: str = 'keep_last'
    depth: Union[int, str] = QUEUE_DEPTH
    note: str = ''

    def __post_init__(self):
        for name, allowed in (('reliability', RELIABILITIES), ('durability', DURABILITIES),
                              ('history', HISTORIES)):
            if getattr(self, name) not in allowed:
                raise ValueError(f'QoS {name} must be one of {", ".join(allowed)}, got '
                                 f'{getattr(self, name)!r}')
        if self.depth != QUEUE_DEPTH and not (
                isinstance(self.depth, int) and not isinstance(self.depth, bool)
                and self.depth >= 1):
            raise ValueError(f'QoS depth must be a positive integer or {QUEUE_DEPTH!r}, got '
                             f'{self.depth!r}')

    def profile(self, queue_depth: Optional[int] = None):
        """
        Build the rclpy ``QoSProfile`` (a new one each call: rclpy's overrides change it).

        rclpy is imported here, on first use, not by the module.

        :param queue_depth: the node's ``queue_depth``, for a profile declared with
            :data:`QUEUE_DEPTH`; ignored by the others.
        :raises ValueError: for a profile of :data:`QUEUE_DEPTH` without ``queue_depth``.
        """
        from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
        depth = self.depth
        if depth == QUEUE_DEPTH:
            if queue_depth is None:
                raise ValueError("this QoS keeps the queue_depth parameter's number of "
                                 'messages: give queue_depth')
            depth = queue_depth
        return QoSProfile(reliability=ReliabilityPolicy[self.reliability.upper()],
                          durability=DurabilityPolicy[self.durability.upper()],
                          history=HistoryPolicy[self.history.upper()], depth=depth)

    def __str__(self) -> str:
        """Describe the profile as the documentation's tables show it."""
        parts = [self.reliability.replace('_', ' ')]
        if self.durability != 'volatile':
            parts.append(self.durability.replace('_', ' '))
        if self.history == 'keep_all':
            parts.append('keep all')
        else:
            parts.append(f'keep last `{self.depth}`' if self.depth == QUEUE_DEPTH
                         else f'keep last {self.depth}')
        return ', '.join(parts) + (f' ({self.note})' if self.note else '')


#: The QoS of the package's endpoints.
QUEUE = Qos()
LATCHED = Qos(durability='transient_local', depth=1, note='latched')
TF = Qos(depth=100, note='as tf2_ros broadcasts')
TF_STATIC = Qos(durability='transient_local', depth=1,
                note='as tf2_ros static broadcasts')
DIAGNOSTICS = Qos(depth=10)
SERVICE_QOS = Qos(depth=10, note="rclpy's services default")


@dataclass(frozen=True)
class Endpoint:
    """
    One topic or service of a node.

    :param name: topic or service name, relative unless it starts with ``/``.
    :param kind: :data:`SUBSCRIPTION`, :data:`PUBLISHER`, :data:`SERVICE` or :data:`ACTION`.
    :param type_name: the message, service or action type, as ``package/msg/Name``,
        ``package/srv/Name`` or ``package/action/Name``.
    :param qos: the :class:`Qos` it is created with (see the constants of this module).
    :param meaning: what it carries, with units and frames.
    :param condition: when the node has it (a parameter that turns it on), ``''``: always.
    :param commands: True for a publisher whose messages command actuators (directly, or
        through a node that turns them into leg lengths): the node publishes on it only the
        command gate's verdicts (:mod:`stewart_kinematics.ros.command_publishing`).
    """

    name: str
    kind: str
    type_name: str
    qos: Qos
    meaning: str
    condition: str = ''
    commands: bool = False

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
    'counted by code, the latest reason with its details')

IK_NODE = NodeInterface('ik_node', (
    Endpoint('target_pose', SUBSCRIPTION, 'geometry_msgs/msg/Pose', QUEUE,
             'Commanded pose of the tool frame (by default the platform frame) in the base '
             'frame: metres and a unit quaternion (a non-unit quaternion is normalised with a '
             'warning). The outputs carry the time of arrival.'),
    Endpoint('target_pose_stamped', SUBSCRIPTION, 'geometry_msgs/msg/PoseStamped', QUEUE,
             "The same with a header: in `base_frame` (or `''`) or `user_frame`, another "
             'frame is refused with the reason; its stamp is carried to `joint_commands`.'),
    Endpoint('target_twist', SUBSCRIPTION, 'geometry_msgs/msg/Twist', QUEUE,
             "Velocity of the tool frame's origin (m/s) and angular velocity (rad/s), base "
             'frame (about the same point as the poses), applied at the last accepted pose.'),
    Endpoint('leg_lengths', PUBLISHER, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'Six leg lengths of each accepted pose, metres, leg 1..6; layout: one dimension '
             'labelled `leg`, size 6.', commands=True),
    Endpoint('leg_extensions', PUBLISHER, 'std_msgs/msg/Float64MultiArray', QUEUE,
             "Each length minus its length at the home pose (the paper's q_i), metres, same "
             'layout; built only while someone subscribes.', commands=True),
    Endpoint('joint_commands', PUBLISHER, 'sensor_msgs/msg/JointState', QUEUE,
             'The legs as prismatic joints named `joint_names`, position = commanded length '
             'minus `actuator_offsets` (m), with the stamp of the stamped pose (or the time of '
             'arrival), for a ros2_control or actuator driver; built only while someone '
             'subscribes. With `command_rate` > 0: streamed at that rate through the '
             'jerk-limited filter instead, with velocities.', commands=True),
    Endpoint('leg_velocities', PUBLISHER, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'Rates of change of the leg lengths for each accepted `target_twist`, m/s, '
             'through the analytic Jacobian.', commands=True),
    Endpoint('platform_markers', PUBLISHER, 'visualization_msgs/msg/MarkerArray', QUEUE,
             'For RViz (fixed frame `base_frame`): base outline, platform outline and the six '
             'legs at the poses received, at most `marker_rate` times a second; a leg that '
             'breaks a limit is red, even in a refused pose, so you see what was asked and why '
             'it was refused.'),
    Endpoint('workspace_markers', PUBLISHER, 'visualization_msgs/msg/MarkerArray', LATCHED,
             'The boundary of the constant-orientation workspace at the home orientation, as '
             'points coloured by the limit met there, namespace `<ns>/workspace`, after a '
             'DELETEALL. Computed once the topic has a subscriber and again when '
             '`workspace_resolution` changes, in a worker process, so the command path never '
             'waits for it.'),
    Endpoint('travel_ranges', PUBLISHER, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'About `travel_range_rate` times a second: from the last accepted pose (home '
             'before the first), the largest move along each axis alone before a limit, 12 '
             'values `[X-, X+, Y-, Y+, Z-, Z+, alpha-, alpha+, beta-, beta+, gamma-, gamma+]` '
             'as offsets from the pose (m, rad; the negative ends <= 0); layout: dimensions '
             '`axis` (size 6, stride 12) and `end` (size 2, stride 2). Computed in the same '
             'worker process, only while the topic has a subscriber and the pose has moved.'),
    Endpoint('/tf', PUBLISHER, 'tf2_msgs/msg/TFMessage', TF,
             'Each accepted command as `base_frame` -> `<platform_frame>_commanded`, with the '
             "command's stamp.", condition='publish_commanded_tf'),
    DIAGNOSTICS_TOPIC,
))

FK_NODE = NodeInterface('fk_node', (
    Endpoint('leg_lengths', SUBSCRIPTION, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'Six measured leg lengths, metres, leg 1..6 (`layout.data_offset` honoured; a bare '
             '`data: [...]` is fine).'),
    Endpoint('joint_states', SUBSCRIPTION, 'sensor_msgs/msg/JointState', QUEUE,
             'Measured legs as joints named `joint_names` (any order; other joints ignored; a '
             'message naming none of them belongs to another platform and is skipped, so two '
             'hexapods can share one `/joint_states`), positions plus `actuator_offsets` as '
             'leg lengths; with velocities for every leg, the twist is published too.'),
    Endpoint('leg_velocities', SUBSCRIPTION, 'std_msgs/msg/Float64MultiArray', QUEUE,
             'Rates of change of the leg lengths, m/s, turned into the twist at the last '
             'estimated pose.'),
    Endpoint('anchor_pose', SUBSCRIPTION, 'geometry_msgs/msg/PoseStamped', QUEUE,
             'A known pose of the tool frame (from homing, a camera, a probe: where the '
             "platform is now) in `base_frame` (or `''`) or `user_frame`: the tracker "
             're-anchors there (no more `ambiguous_estimate`) and the next solve starts from '
             'it. Another frame, or a pose that is unreachable or breaks a limit, is refused '
             'with the reason.'),
    Endpoint('estimated_pose', PUBLISHER, 'geometry_msgs/msg/Pose', QUEUE,
             'The pose of the tool frame (by default the platform frame) in the base frame '
             'whose leg lengths match; metres, unit quaternion with `w >= 0`.'),
    Endpoint('estimated_pose_stamped', PUBLISHER, 'geometry_msgs/msg/PoseStamped', QUEUE,
             'The same in `estimated_pose_frame` (base or user frame), with the stamp of the '
             'joint state it comes from (or the time of arrival); built only while someone '
             'subscribes.'),
    Endpoint('estimated_twist', PUBLISHER, 'geometry_msgs/msg/Twist', QUEUE,
             "Velocity of the tool frame's origin and angular velocity (m/s, rad/s, base "
             'frame: about the same point as the poses) from leg velocities.'),
    Endpoint('estimated_wrench', PUBLISHER, 'geometry_msgs/msg/WrenchStamped', QUEUE,
             'For each `joint_states` with efforts (the measured leg forces, N, positive '
             'pushing) whose pose is published: the wrench the environment applies to the '
             'platform (an unmodelled payload, a contact), the measured forces minus the '
             "model's static forces at that pose mapped through J^T, sign turned: force (N) "
             "and torque (N m) about the platform frame's origin, both in the platform frame "
             '(`frame_id`: `platform_frame`), with the stamp of the joint state. A payload '
             'the model does not know shows as its weight; a moving platform adds its own '
             'inertial forces.'),
    Endpoint('/tf', PUBLISHER, 'tf2_msgs/msg/TFMessage', TF,
             '`base_frame` -> `platform_frame`: the estimated platform pose, with the stamp of '
             'the lengths it comes from; sent only while someone listens (needs tf2_msgs).',
             condition='publish_tf'),
    Endpoint('/tf_static', PUBLISHER, 'tf2_msgs/msg/TFMessage', TF_STATIC,
             'The named user and tool frames, again when the tool frame changes.',
             condition='publish_tf'),
    Endpoint('reset_tracker', SERVICE, 'std_srvs/srv/Trigger', SERVICE_QOS,
             'Forget the last solution: the next solve starts from the home pose (homing, a '
             'restart, lengths from another session), and the tracker counts as anchored (no '
             'more `ambiguous_estimate`). Answers `success: true`.'),
    Endpoint('/diagnostics', PUBLISHER, 'diagnostic_msgs/msg/DiagnosticArray', DIAGNOSTICS,
             DIAGNOSTICS_TOPIC.meaning + ' (iterations, residual, condition number, pose error '
             'bound), near-singularity warnings; and the status `fk_node: assembly mode '
             'margin`: the distance from the last solution to the nearest other real assembly '
             'mode within the limits, WARN below `assembly_mode_margin_warning`; and the status '
             '`fk_node: assembly mode ambiguity`: WARN, with the reason, from the first sign '
             'that a fold singularity was crossed (`ambiguous_estimate`) until the tracker is '
             're-anchored.'),
))

TRAJECTORY_NODE = NodeInterface('trajectory_node', (
    Endpoint('pose_trajectory', SUBSCRIPTION, 'trajectory_msgs/msg/MultiDOFJointTrajectory',
             QUEUE, 'Waypoints of one joint, the tool frame (by default the platform frame): '
             'per point one transform (the tool frame in the header frame, `base_frame` or '
             '`user_frame`), `time_from_start` (0 to 1e6 s, strictly increasing; the first '
             'point is time 0 of the output), optionally one twist on every point (about the '
             "tool frame's origin, header frame) and with them one acceleration (then the "
             'motion is C2). Planned in a worker: checked whole, timed or retimed, then handed '
             'on; a newer trajectory or path replaces one not yet decided (`superseded`).'),
    Endpoint('pose_path', SUBSCRIPTION, 'nav_msgs/msg/Path', QUEUE,
             'Waypoints of the tool frame without timing, in `base_frame` or `user_frame`: '
             'always retimed (repeated waypoints merged).'),
    Endpoint('target_pose', PUBLISHER, 'geometry_msgs/msg/Pose', QUEUE,
             "The ramp's poses (tool frame, base frame, metres, unit quaternion); with `play`, "
             "the tool frame's poses of an accepted trajectory at `publish_rate`.",
             commands=True),
    Endpoint('leg_trajectory', PUBLISHER, 'trajectory_msgs/msg/JointTrajectory', QUEUE,
             'An accepted trajectory for the actuators: `joint_names`, and per point (every '
             '`1 / publish_rate` s or closer, at most 256 between two waypoints, and at every '
             'waypoint) the actuator positions (leg length '
             'minus `actuator_offsets`, m), velocities (m/s), accelerations (m/s^2), `effort` '
             '(the dynamic leg forces, N, positive pushing, when masses are set; empty with '
             'every mass 0) and `time_from_start`, as joint_trajectory_controller takes it.',
             commands=True),
    Endpoint('joint_states', SUBSCRIPTION, 'sensor_msgs/msg/JointState', QUEUE,
             'The measured legs as joints named `joint_names` (any order, other joints ignored), '
             'positions in actuator coordinates (length minus `actuator_offsets`, m), with '
             'velocities when known: what `follow_joint_trajectory` checks its tolerances '
             'against, and where a goal starts when nothing was commanded.'),
    Endpoint('joint_commands', PUBLISHER, 'sensor_msgs/msg/JointState', QUEUE,
             "With `action_execution: stream`: a running goal's leg commands at `publish_rate` "
             '(positions as `joint_commands` of ik_node, m, and velocities, m/s), braking to rest '
             'on the path after a cancel or a preemption.', commands=True),
    Endpoint('follow_joint_trajectory', ACTION, 'control_msgs/action/FollowJointTrajectory',
             SERVICE_QOS,
             'Goals of the six leg joints (`joint_names`) or the six Cartesian joints '
             '(`action_cartesian_joints`: the tool frame, m and rad) in `trajectory`, checked, '
             'planned as `pose_trajectory` is (limits, `retime`) and sent as `action_execution` '
             'says; tolerances checked against `joint_states`; feedback at '
             '`action_feedback_rate`; a new goal preempts, a cancel brakes to rest. Result '
             'codes: [Drive it from MoveIt, rqt or a script](how-to/drive_from_moveit.md).'),
    Endpoint('/diagnostics', PUBLISHER, 'diagnostic_msgs/msg/DiagnosticArray', DIAGNOSTICS,
             DIAGNOSTICS_TOPIC.meaning + ', with the time, segment and violated limits of a '
             'refused trajectory.'),
))

MOTION_CUEING_NODE = NodeInterface('motion_cueing_node', (
    Endpoint('vehicle_imu', SUBSCRIPTION, 'sensor_msgs/msg/Imu', QUEUE,
             "The vehicle's specific force (linear_acceleration, m/s^2: 9.81 on z at rest) and "
             "angular velocity (rad/s) at the driver's head, vehicle frame (x forward, y left, "
             'z up); header.stamp sets the time step; the orientation is not used'),
    Endpoint('vehicle_preview', SUBSCRIPTION, 'trajectory_msgs/msg/MultiDOFJointTrajectory',
             QUEUE,
             "The vehicle's motion to come, for cueing_method mpc (a replay, a scripted drive, a "
             "driver model's prediction): per point, time_from_start after header.stamp (the "
             "clock of vehicle_imu's stamps), the specific force in accelerations[0].linear "
             '(m/s^2, with gravity) and the angular velocity in velocities[0].angular (rad/s), '
             "in header.frame_id as vehicle_imu's; each message replaces the last, the MPC plans "
             'against it over its horizon (doc/motion_cueing_mpc.md)'),
    Endpoint('target_pose', PUBLISHER, 'geometry_msgs/msg/Pose', QUEUE,
             'The cue as the pose of the tool frame in the base frame, one per sample (and while '
             'easing home after input_timeout), for ik_node', commands=True),
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
    Endpoint('start', SERVICE, 'std_srvs/srv/Trigger', SERVICE_QOS,
             'Soft start: from park up to the neutral cueing pose over soft_start_time (leg '
             'velocity and acceleration within the actuator limits), then cueing'),
    Endpoint('stop', SERVICE, 'std_srvs/srv/Trigger', SERVICE_QOS,
             'Soft stop: brake to rest, then down to park over soft_stop_time; during a start, '
             'turn back to park from where the platform is'),
    Endpoint('pause', SERVICE, 'std_srvs/srv/Trigger', SERVICE_QOS,
             'Pause: brake to rest where the platform is and hold it there, the washout frozen; '
             'samples are not cued (cueing_held)'),
    Endpoint('resume', SERVICE, 'std_srvs/srv/Trigger', SERVICE_QOS,
             "Resume after pause: cueing goes on from the washout's held state, without a "
             'jump'),
    DIAGNOSTICS_TOPIC,
))

MOCK_PLATFORM = NodeInterface('mock_platform', (
    Endpoint('leg_lengths', SUBSCRIPTION, 'std_msgs/msg/Float64MultiArray', QUEUE,
             "A set point: six leg lengths, metres, leg 1..6, as ik_node's `leg_lengths` "
             '(`layout.data_offset` honoured); the legs follow the newest command.',
             condition='`command_input` all or this topic'),
    Endpoint('joint_commands', SUBSCRIPTION, 'sensor_msgs/msg/JointState', QUEUE,
             "A set point as ik_node's `joint_commands`: the six joints `joint_names` (any "
             'order, other joints ignored), positions plus `actuator_offsets` as leg lengths.',
             condition='`command_input` all or this topic'),
    Endpoint('leg_trajectory', SUBSCRIPTION, 'trajectory_msgs/msg/JointTrajectory', QUEUE,
             "A leg trajectory as trajectory_node's `leg_trajectory`, followed as "
             'joint_trajectory_controller follows one: from its header stamp (0: on arrival), '
             'interpolated linearly, cubically (with velocities) or quintically (with '
             "accelerations), from the legs' state to its first point, its last point held; a "
             'new one replaces the old from its start.',
             condition='`command_input` all or this topic'),
    Endpoint('joint_states', PUBLISHER, 'sensor_msgs/msg/JointState', QUEUE,
             "At `joint_state_rate`, stamped with the node's clock: the simulated legs as the "
             'joints `joint_names`, positions (leg length minus `actuator_offsets`, with '
             '`position_bias` and `position_noise`, m), velocities (m/s) and, when the '
             'geometry carries masses, efforts: the leg forces (N, positive pushing) at the '
             'pose of their forward kinematics, with its twist and acceleration.'),
    Endpoint('/diagnostics', PUBLISHER, 'diagnostic_msgs/msg/DiagnosticArray', DIAGNOSTICS,
             DIAGNOSTICS_TOPIC.meaning + "; and the status `mock_platform: legs`: the legs' "
             'lengths, the faults set, clock jumps.'),
))

TELEMETRY_BRIDGE = NodeInterface('telemetry_bridge', (
    Endpoint('vehicle_imu', PUBLISHER, 'sensor_msgs/msg/Imu', QUEUE,
             'One message per accepted telemetry packet of its UDP port (`telemetry_address`, '
             '`telemetry_port`; the layout: [Put it on your simulator](how-to/simulator.md)), '
             'for motion_cueing_node: the specific force (linear_acceleration, m/s^2) and '
             'angular velocity (rad/s) in the vehicle frame (x forward, y left, z up), '
             "header.stamp the packet's timestamp, header.frame_id `telemetry_frame_id`, no "
             'orientation (orientation_covariance[0] = -1). Nothing while the stream is stale.'),
    Endpoint('/diagnostics', PUBLISHER, 'diagnostic_msgs/msg/DiagnosticArray', DIAGNOSTICS,
             DIAGNOSTICS_TOPIC.meaning + ', for the UDP port (status `telemetry_bridge: udp '
             '<address>:<port>`); and the status `telemetry_bridge: stream`: OK while packets '
             'come, STALE after `telemetry_timeout` without one, with the packets the sequence '
             'numbers say were lost.'),
))

#: Every node's interface, by node name.
NODE_INTERFACES = {
    interface.node: interface
    for interface in (IK_NODE, FK_NODE, TRAJECTORY_NODE, MOTION_CUEING_NODE, MOCK_PLATFORM,
                      TELEMETRY_BRIDGE)}


def markdown_table(interface: NodeInterface) -> str:
    """
    Render a node's interface as the documentation's table: name, kind, type, QoS, meaning.

    A test compares the documentation with this, so it cannot drift from the code.
    """
    lines = ['| Topic or service | Kind | Type | QoS | Meaning |',
             '| --- | --- | --- | --- | --- |']
    for endpoint in interface.endpoints:
        meaning = endpoint.meaning + (f' (with `{endpoint.condition}`)'
                                      if endpoint.condition else '') + (
            ' Commands actuators: every message is checked as sent by the command gate.'
            if endpoint.commands else '')
        lines.append(f'| `{endpoint.name}` | {endpoint.kind} | `{endpoint.type_name}` | '
                     f'{endpoint.qos} | {meaning} |')
    return '\n'.join(lines)
