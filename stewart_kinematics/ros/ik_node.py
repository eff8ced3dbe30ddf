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
Inverse kinematics node: a commanded platform pose in, six leg lengths out.

Subscribes ``target_pose`` (geometry_msgs/msg/Pose, base frame) or ``target_pose_stamped``
(geometry_msgs/msg/PoseStamped, base frame or user frame), metres: the pose of the tool frame
(:mod:`stewart_kinematics.model.frames`; by default the platform frame itself), and
``target_twist`` (geometry_msgs/msg/Twist, base frame: the velocity of the tool frame's origin
and the angular velocity, like every pose topic about the tool frame's point).

Publishes ``leg_lengths`` (std_msgs/msg/Float64MultiArray, metres, leg 1..6),
``leg_extensions`` (the same layout: each length minus its length at the home pose, the
paper's q_i), ``joint_commands`` (sensor_msgs/msg/JointState, the legs as prismatic joints
named ``joint_names``, positions ``length - actuator_offsets``, with the stamp of the pose; or,
with ``command_rate``, streamed at that rate through the jerk-limited
:class:`stewart_kinematics.CommandFilter` toward the latest accepted pose; with masses, efforts:
the leg forces in newtons of the pose sent, at rest for a pose, with the stream's twist and
acceleration for a streamed command, as the command gate checked them; without masses the
effort list is empty: not given), ``leg_velocities``
(the rates of change of the lengths for a twist at the last pose, m/s), ``platform_markers``
(visualization_msgs/msg/MarkerArray for RViz: the platform at every pose received, legs that
break a limit in red, even for a refused pose), ``workspace_markers`` (the boundary of the
constant-orientation workspace at the home orientation, latched) and ``travel_ranges`` (the
range left along each axis from the last accepted pose, about once a second), those two
computed by :mod:`stewart_kinematics.ros.workspace_publishing` off the command path; and, if
``publish_commanded_tf`` is set, the commanded platform frame on ``/tf`` as
``<platform_frame>_commanded``.

A change of the tool frame at run time applies from the next message on. What to command and
what to refuse is decided by :class:`stewart_kinematics.CommandCheck` (the frame a pose is given
in, a non-unit quaternion, the tool frame's pose and twist moved to the platform frame's, a
pose that breaks a limit: refused, never clamped; a twist beyond the leg velocity limit:
refused, or scaled to it with ``twist_over_limit: 'scale'``) and, for streamed commands, by
:class:`stewart_kinematics.CommandFilter` (the stream starts at the first accepted pose; every
step within the stroke and the leg velocity, acceleration and jerk limits; reported on
``/diagnostics`` as the ``command_stream`` input). The node converts the messages, publishes,
and counts each refusal with the core's reason (:mod:`stewart_kinematics.ros.
message_accounting`).
"""

import time

from geometry_msgs.msg import Pose, PoseStamped, Twist
import numpy as np
from rclpy.time import Time
from std_msgs.msg import Header

from stewart_kinematics import findings
from stewart_kinematics.findings import Finding
from stewart_kinematics.limits.command_gate import BRAKING_SHARES
from stewart_kinematics.model.frames import Transform
from stewart_kinematics.motion.streaming import CommandFilter
from stewart_kinematics.parameters import (
    actuator_interface_from_settings,
    actuator_limits_from_settings,
    frames_from_settings,
    geometry_from_settings,
    IkNodeSettings,
)
from stewart_kinematics.pose_decisions.pose_commands import CommandCheck
from stewart_kinematics.ros.command_publishing import send_command
from stewart_kinematics.ros.interfaces import IK_NODE
from stewart_kinematics.ros.managed import ManagedNode
from stewart_kinematics.ros.markers import PlatformMarkerPublisher
from stewart_kinematics.ros.message_accounting import MessageAccounting, NodeDiagnostics
from stewart_kinematics.ros.message_conversions import (
    joint_state_message,
    legs_to_message,
    malformed_time_reason,
)
from stewart_kinematics.ros.node_main import (
    create_input_subscription,
    create_output_publisher,
    run_node,
)
from stewart_kinematics.ros.ros_parameters import RunTimePayload
from stewart_kinematics.ros.transforms import TransformBroadcaster
from stewart_kinematics.ros.workspace_publishing import WorkspacePublisher

#: Suffix of the commanded platform frame's name on /tf.
COMMANDED_SUFFIX = '_commanded'
#: Most braking commands the deactivate transition sends (a bound; rest comes far sooner).
MAX_BRAKING_STEPS = 100_000
#: Leg speed below which the deactivate transition takes the legs as resting, m/s.
REST_SPEED = 1e-9


class IkNode(ManagedNode):
    """Publish the leg lengths of every pose received, or refuse it."""

    SETTINGS = IkNodeSettings

    def __init__(self, **kwargs):
        super().__init__('ik_node', **kwargs)

    def run_time_payload(self):
        """Take a new payload at once: every pose from then on is judged with it."""
        return RunTimePayload(lambda: self.geometry, self.set_mass_properties)

    def configure(self):
        """Build the geometry, the checks, the stream, every publisher and subscription."""
        settings = self.settings
        self.geometry = geometry_from_settings(settings.geometry)
        actuator_limits = actuator_limits_from_settings(settings.geometry)
        self.check = CommandCheck(self.geometry, actuator_limits,
                                  twist_over_limit=settings.streaming.twist_over_limit)
        # Replaced whole when a tool frame parameter changes: one tree per message.
        self.frames = frames_from_settings(settings.frames)
        self.actuators = actuator_interface_from_settings(settings.actuators)
        # Streaming: commands at command_rate toward the latest accepted pose, from the home
        # pose (where the platform is assumed to start), once a first pose is accepted.
        self.command_filter = None
        command_rate = settings.streaming.command_rate
        if command_rate > 0.0:
            self.command_filter = CommandFilter(actuator_limits, 1.0 / command_rate,
                                                self.geometry.home_leg_lengths, self.geometry)
        self.base_frame = settings.frames.base_frame
        depth = settings.queue.queue_depth
        home_lengths = self.geometry.home_leg_lengths
        # Every command topic sends only the gate's verdicts, as messages of their numbers.
        self.lengths_publisher = create_output_publisher(
            self, IK_NODE['leg_lengths'], depth, lambda command: legs_to_message(command.lengths))
        self.extensions_publisher = create_output_publisher(
            self, IK_NODE['leg_extensions'], depth,
            lambda command: legs_to_message(command.lengths - home_lengths))
        # Commands, not measurements: joint_states is left to the actuators' driver.
        self.joint_command_publisher = create_output_publisher(
            self, IK_NODE['joint_commands'], depth, lambda command, header: joint_command_message(
                header, command, self.actuators))
        self.velocities_publisher = create_output_publisher(
            self, IK_NODE['leg_velocities'], depth,
            lambda command: legs_to_message(command.velocities))
        #: The clock's origin of the stream's times, nanoseconds: seconds since it keep their
        #: digits (seconds since 1970 would round to a quarter of a microsecond).
        self.clock_origin_ns = self.get_clock().now().nanoseconds
        self.markers = PlatformMarkerPublisher(
            self, create_output_publisher(self, IK_NODE['platform_markers'], depth),
            self.geometry, self.base_frame, settings.markers.marker_rate)
        self.tf = TransformBroadcaster(self, dynamic=IK_NODE['/tf']) if (
            settings.ik_frames.publish_commanded_tf) else None
        diagnostics = NodeDiagnostics(self)
        self.accounting = diagnostics.accounting('target_pose')
        self.stamped_accounting = diagnostics.accounting('target_pose_stamped')
        self.twist_accounting = diagnostics.accounting('target_twist')
        # The steps of the stream, as an input of their own: each counted, given or held.
        self.stream_accounting = (diagnostics.accounting('command_stream')
                                  if self.command_filter is not None else None)
        create_input_subscription(self, IK_NODE['target_pose'], self.on_target_pose, depth)
        create_input_subscription(
            self, IK_NODE['target_pose_stamped'], self.on_target_pose_stamped, depth)
        create_input_subscription(self, IK_NODE['target_twist'], self.on_target_twist, depth)
        if self.command_filter is not None:
            self.create_timer(self.command_filter.period, self.publish_streamed_command)
        self.workspace = WorkspacePublisher(
            self, self.geometry, self.base_frame, settings.workspace.workspace_resolution,
            settings.workspace.travel_range_rate, lambda: self.check.last_pose, depth)
        self.get_logger().info(
            'ready: home leg lengths '
            f'{np.array2string(self.geometry.home_leg_lengths, precision=6, separator=", ")} m')

    def on_parameter_change(self, name, value):
        """Apply a validated run-time change: a new tool frame, or a new workspace resolution."""
        self.settings = self.settings.replace(**{name: value})
        if name.startswith('tool_frame'):
            self.frames = frames_from_settings(self.settings.frames)
        elif name == 'workspace_resolution':
            self.workspace.set_resolution(value)

    def set_mass_properties(self, geometry):
        """Judge every pose from now on with a new payload: the check rebuilt, its state kept."""
        old, self.geometry = self.check, geometry
        self.check = CommandCheck(geometry, old.limits.actuator_limits,
                                  twist_over_limit=old.twist_over_limit)
        self.check.last_pose, self.check.last_lengths = old.last_pose, old.last_lengths
        self.check.gate.reset(old.gate.last_lengths, old.gate.last_pose)
        if self.command_filter is not None:    # a stream in flight checks its next step too
            self.command_filter.set_mass_properties(geometry)
        self.workspace.set_geometry(geometry)

    def activate(self):
        """Send the cleared workspace markers (latched) that a managed configure could not."""
        if self.managed and self.workspace.resolution <= 0.0:
            self.workspace.set_resolution(0.0)

    def deactivate(self):
        """Bring a stream in flight to rest within the limits, before the node goes quiet."""
        if self.command_filter is not None and self.command_filter.started:
            self.brake_stream()

    def brake_stream(self):
        """
        Stop the stream as soon as the limits allow, one command a period, until the legs rest.

        The stream's target becomes where its braking plan ends
        (:meth:`stewart_kinematics.CommandFilter.stopping_lengths`: every leg slowed within
        the velocity, acceleration and jerk limits, from the command's own state), and each
        step goes through the command gate as every streamed command does. The platform rests
        where it can, short of the pose asked for. Runs in the deactivate transition, which
        answers once the legs rest (the speed over the acceleration, plus the acceleration
        over the jerk: 0.3 s with example_limits.yaml). The stream then rests there: the
        next accepted pose, once active again, starts from it.
        """
        stream = self.command_filter
        period = stream.period
        stop = stream.stopping_lengths()
        if stop is None or not stream.set_target(stop).accepted:
            self.get_logger().warning('deactivated mid-stream: no braking plan; the gate '
                                      'brakes the legs instead')
        limits = stream.limits
        gentlest = min(share for share in BRAKING_SHARES if share > 0.0)
        steps = int((limits.velocity_max / limits.acceleration_max
                     + limits.acceleration_max / limits.jerk_max)
                    / gentlest / period) + 3
        # Times on the gate's own line, a period apart: the executor (and with it a simulated
        # clock) does not run meanwhile. Each command is stamped with its time on that line
        # (the node's clock since its origin), so the rates its stamps give are those checked,
        # also under a simulated clock that stands still meanwhile.
        moment = stream.gate.last_time
        last = None
        for _ in range(min(steps, MAX_BRAKING_STEPS)):
            moment += period
            command = stream.send(moment)
            if not command.accepted:
                break
            last = command
            self.stream_accounting.receive()
            stamp = Time(nanoseconds=self.clock_origin_ns + round(moment * 1e9),
                         clock_type=self.get_clock().clock_type).to_msg()
            send_command(self.joint_command_publisher, self.stream_accounting, command, Header(
                stamp=stamp, frame_id=self.base_frame))
            if np.abs(command.velocities).max() <= REST_SPEED:
                break
            time.sleep(period)
        if last is not None:
            stream.reset(last.lengths)
            self.get_logger().info(
                'deactivated mid-stream: braked to rest at leg lengths '
                f'{np.array2string(last.lengths, precision=6, separator=", ")} m')

    def cleanup(self):
        """Stop the workspace worker, if configure got as far as starting it."""
        workspace = getattr(self, 'workspace', None)
        if workspace is not None:
            workspace.shutdown()

    def on_target_pose(self, message: Pose):
        """Turn a pose into leg lengths; the outputs are stamped with the time of the answer."""
        self.accounting.receive()
        # The base frame; the clock is read only for an output that carries a stamp.
        self.command(message, None, self.accounting, self.frames)

    def on_target_pose_stamped(self, message: PoseStamped):
        """Turn a stamped pose into leg lengths; joint_commands carries its stamp."""
        self.stamped_accounting.receive()
        malformed = malformed_time_reason(message.header.stamp, 'header.stamp')
        if malformed:   # joint_commands would carry it to the drives
            self.stamped_accounting.reject(Finding(findings.INVALID_POSE, malformed))
            return
        self.command(message.pose, message.header, self.stamped_accounting, self.frames)

    def command(self, pose: Pose, header: Header, accounting: MessageAccounting, frames):
        """
        Publish the leg lengths, extensions and joint states of a pose, or reject it.

        :param pose: the tool frame's pose, in ``header.frame_id`` (base or user frame).
        :param header: the stamped pose's header, or ``None`` for the base frame and the time
            now, read when an output needs it.
        :param frames: the frame tree to apply, the same for the whole message.
        """
        point, orientation = pose.position, pose.orientation
        command = self.check.tool_pose(
            (point.x, point.y, point.z), (orientation.x, orientation.y, orientation.z,
                                          orientation.w), frames,
            self.base_frame if header is None else header.frame_id)
        for warning in command.warnings:
            accounting.warn(warning)
        self.markers.show(command, None if header is None else header.stamp)
        if not command.accepted:
            accounting.reject(command.refusal)
            return
        accounting.publish(self.lengths_publisher, command)
        # The other forms only for a subscriber: in a 1 kHz command stream, messages that
        # nobody reads would cost the node a third of its rate.
        if self.extensions_publisher.get_subscription_count():
            self.extensions_publisher.publish(command)
        if self.command_filter is not None:
            target = self.command_filter.set_target(command.lengths, self.stream_time())
            if not target.accepted:
                self.stream_accounting.warn(target.refusal)
        elif self.joint_command_publisher.get_subscription_count():
            self.joint_command_publisher.publish(command, self.header_now(header))
        if self.tf is not None:
            self.tf.send(frames.base_frame, frames.platform_frame + COMMANDED_SUFFIX,
                         Transform(command.position, command.rotation),
                         self.header_now(header).stamp)

    def header_now(self, header) -> Header:
        """Return ``header``, or for ``None`` a header of the base frame stamped now."""
        if header is not None:
            return header
        return Header(stamp=self.get_clock().now().to_msg(), frame_id=self.base_frame)

    def stream_time(self, now=None) -> float:
        """Return the seconds of the node's clock (now, by default) since its origin."""
        now = self.get_clock().now() if now is None else now
        return (now.nanoseconds - self.clock_origin_ns) * 1e-9

    def publish_streamed_command(self):
        """
        Publish the next filtered command (position, velocity), once a pose was accepted.

        The filter's command for the time now, checked as sent by its gate; a step it could
        not give within the limits is replaced by a braking command (counted as a rejection
        with ``command_braking``), never by holding the last command.
        """
        if not self.command_filter.started:
            return
        self.stream_accounting.receive()
        now = self.get_clock().now()
        send_command(self.joint_command_publisher, self.stream_accounting,
                     self.command_filter.send(self.stream_time(now)),
                     Header(stamp=now.to_msg(), frame_id=self.base_frame))

    def on_target_twist(self, message: Twist):
        """Publish the leg velocities of a tool-frame twist at the last accepted pose."""
        self.twist_accounting.receive()
        linear, angular = message.linear, message.angular
        send_command(self.velocities_publisher, self.twist_accounting, self.check.tool_twist(
            (linear.x, linear.y, linear.z, angular.x, angular.y, angular.z), self.frames))


def joint_command_message(header, command, actuators):
    """
    sensor_msgs/msg/JointState of a command gate's verdict: what ``joint_commands`` sends.

    Positions (``length - offset``, m) and velocities (m/s, when the command carries them), and
    the efforts: the leg forces of the command (N, positive pushing, the force along each
    prismatic joint), those the gate checked against ``leg_force_min`` and ``leg_force_max``.
    With every mass 0 the command carries no forces and the effort list stays empty, which
    JointState reads as "not given" (a ros2_control controller then adds no feed-forward,
    rather than a feed-forward of 0 N).

    :param command: an accepted :class:`stewart_kinematics.limits.LegCommand`.
    :param actuators: joint names and offsets.
    """
    message = joint_state_message(header, command.lengths, command.velocities,
                                  actuators=actuators)
    if command.forces is not None:
        message.effort = command.forces.tolist()
    return message


def main(args=None) -> int:
    """Run the IK node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(IkNode, 'ik_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
