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

Subscribes ``target_pose`` (geometry_msgs/msg/Pose) or ``target_pose_stamped``
(geometry_msgs/msg/PoseStamped), base frame, metres, and ``target_twist``
(geometry_msgs/msg/Twist, base frame). Publishes ``leg_lengths`` (std_msgs/msg/Float64MultiArray,
metres, leg 1..6), ``leg_extensions`` (the same layout: each length minus its length at the
home pose, the paper's q_i), ``joint_commands`` (sensor_msgs/msg/JointState, legs ``leg_1``
.. ``leg_6`` as prismatic joints, with the stamp of the pose) and ``leg_velocities`` (the rates of
change of the lengths for a twist at the last pose, m/s), and ``platform_markers``
(visualization_msgs/msg/MarkerArray for RViz: the platform at every pose received, legs that
break a limit in red, even for a refused pose), ``workspace_markers`` (the boundary of the
constant-orientation workspace at the home orientation, latched) and ``travel_ranges`` (the
range left along each axis from the last accepted pose, about once a second); those two are
computed by :mod:`stewart_kinematics.ros.workspace_reporting` off the command path. What to
command and what to refuse is decided by :class:`stewart_kinematics.CommandCheck` (a pose that
breaks a limit of the geometry is refused, never clamped); the node converts the messages,
publishes, and counts each refusal with the core's reason
(:mod:`stewart_kinematics.ros.message_accounting`).
"""

from geometry_msgs.msg import Pose, PoseStamped, Twist
import numpy as np
from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, Header

from stewart_kinematics import findings, parameter_spec
from stewart_kinematics.command_check import CommandCheck
from stewart_kinematics.findings import Finding
from stewart_kinematics.parameter_spec import geometry_from_parameters
from stewart_kinematics.ros.markers import platform_markers
from stewart_kinematics.ros.message_accounting import MessageAccounting, NodeDiagnostics
from stewart_kinematics.ros.message_conversions import (
    joint_state_message,
    legs_to_message,
    position_quaternion_from_message,
    QUATERNION_NORM_TOLERANCE,
    twist_from_message,
)
from stewart_kinematics.ros.node_main import create_output_publisher, run_node
from stewart_kinematics.ros.ros_parameters import declare_parameters
from stewart_kinematics.ros.workspace_reporting import WorkspaceReporter
from stewart_kinematics.rotations import quaternion_to_matrix
from visualization_msgs.msg import MarkerArray

#: Code of the refusal of a stamped pose in a frame other than base_frame.
WRONG_FRAME = 'wrong_frame'


class IkNode(Node):
    """Publish the leg lengths of every pose received, or refuse it."""

    def __init__(self, **kwargs):
        super().__init__('ik_node', **kwargs)
        values = declare_parameters(
            self, parameter_spec.GEOMETRY_PARAMETERS + parameter_spec.FRAME_PARAMETERS
            + parameter_spec.MARKER_PARAMETERS + parameter_spec.WORKSPACE_PARAMETERS
            + parameter_spec.QUEUE_PARAMETERS, on_change=self.on_parameter_change)
        self.geometry = geometry_from_parameters(values)
        self.check = CommandCheck(self.geometry)
        self.base_frame = values['base_frame']
        self.marker_period_ns = 1e9 / values['marker_rate'] if values['marker_rate'] else None
        self.last_marker_ns = None
        depth = values['queue_depth']
        self.lengths_publisher = create_output_publisher(
            self, Float64MultiArray, 'leg_lengths', depth)
        self.extensions_publisher = create_output_publisher(
            self, Float64MultiArray, 'leg_extensions', depth)
        # Commands, not measurements: joint_states is left to the actuators' driver.
        self.joint_command_publisher = create_output_publisher(
            self, JointState, 'joint_commands', depth)
        self.velocities_publisher = create_output_publisher(
            self, Float64MultiArray, 'leg_velocities', depth)
        self.marker_publisher = create_output_publisher(
            self, MarkerArray, 'platform_markers', depth)
        diagnostics = NodeDiagnostics(self)
        self.accounting = diagnostics.accounting('target_pose')
        self.stamped_accounting = diagnostics.accounting('target_pose_stamped')
        self.twist_accounting = diagnostics.accounting('target_twist')
        self.create_subscription(Pose, 'target_pose', self.on_target_pose, depth)
        self.create_subscription(
            PoseStamped, 'target_pose_stamped', self.on_target_pose_stamped, depth)
        self.create_subscription(Twist, 'target_twist', self.on_target_twist, depth)
        self.workspace = WorkspaceReporter(
            self, self.geometry, self.base_frame, values['workspace_resolution'],
            values['travel_range_rate'], lambda: self.check.last_pose, depth)
        self.get_logger().info(
            'ready: home leg lengths '
            f'{np.array2string(self.geometry.home_leg_lengths, precision=6, separator=", ")} m')

    def on_parameter_change(self, name, value):
        """Recompute the workspace markers when their resolution changes at run time."""
        if name == 'workspace_resolution':
            self.workspace.set_resolution(value)

    def destroy_node(self):
        """Stop the workspace worker, then destroy the node."""
        self.workspace.shutdown()
        return super().destroy_node()

    def on_target_pose(self, message: Pose):
        """Turn a pose into leg lengths; the outputs are stamped with the time of arrival."""
        self.accounting.receive()
        header = Header(stamp=self.get_clock().now().to_msg(), frame_id=self.base_frame)
        self.command(message, header, self.accounting)

    def on_target_pose_stamped(self, message: PoseStamped):
        """Turn a stamped pose into leg lengths; joint_commands carries its stamp."""
        self.stamped_accounting.receive()
        frame = message.header.frame_id
        if frame and frame != self.base_frame:
            self.stamped_accounting.reject(Finding(
                WRONG_FRAME, f"it is in frame '{frame}', not in base_frame "
                f"'{self.base_frame}'; transform it first"))
            return
        self.command(message.pose, message.header, self.stamped_accounting)

    def command(self, pose: Pose, header: Header, accounting: MessageAccounting):
        """Publish the leg lengths, extensions and joint states of a pose, or reject it."""
        try:
            position, quaternion, norm = position_quaternion_from_message(pose)
        except ValueError as error:
            accounting.reject(Finding(findings.INVALID_POSE, str(error)))
            return
        if abs(norm - 1.0) > QUATERNION_NORM_TOLERANCE:
            self.get_logger().warning(
                f'{accounting.topic} orientation has norm {norm:.9g}, not 1: normalised '
                '(said once)', once=True)
        command = self.check.pose_quaternion(position, quaternion)
        if command.violations or command.accepted:
            self.publish_markers(header, position, quaternion, command.violations)
        if not command.accepted:
            accounting.reject(command.refusal)
            return
        lengths = command.lengths
        accounting.publish(self.lengths_publisher, legs_to_message(lengths))
        # The other forms only for a subscriber: in a 1 kHz command stream, messages that
        # nobody reads would cost the node a third of its rate.
        if self.extensions_publisher.get_subscription_count():
            self.extensions_publisher.publish(
                legs_to_message(lengths - self.geometry.home_leg_lengths))
        if self.joint_command_publisher.get_subscription_count():
            self.joint_command_publisher.publish(joint_state_message(header, lengths))

    def publish_markers(self, header, position, quaternion, violations):
        """
        Publish the platform's markers, at most at marker_rate and only to a subscriber.

        Refused poses are shown too, with the offending legs in red: what was asked, and why
        it was refused.
        """
        if self.marker_period_ns is None or self.marker_publisher.get_subscription_count() == 0:
            return
        now_ns = self.get_clock().now().nanoseconds
        if self.last_marker_ns is not None and (
                now_ns - self.last_marker_ns < self.marker_period_ns):
            return
        self.last_marker_ns = now_ns
        self.marker_publisher.publish(platform_markers(
            Header(stamp=header.stamp, frame_id=self.base_frame), self.geometry, position,
            quaternion_to_matrix(quaternion), [violation.leg for violation in violations],
            self.get_namespace().strip('/') or 'stewart_platform'))

    def on_target_twist(self, message: Twist):
        """Publish the leg velocities of a platform twist at the last accepted pose."""
        self.twist_accounting.receive()
        try:
            twist = twist_from_message(message)
        except ValueError as error:
            self.twist_accounting.reject(Finding(findings.INVALID_TWIST, str(error)))
            return
        command = self.check.twist(twist)
        if not command.accepted:
            self.twist_accounting.reject(command.refusal)
            return
        self.twist_accounting.publish(
            self.velocities_publisher, legs_to_message(command.velocities))


def main(args=None) -> int:
    """Run the IK node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(IkNode, 'ik_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
