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
Forward kinematics node: six leg lengths in, the platform pose out.

Subscribes ``leg_lengths`` (std_msgs/msg/Float64MultiArray, metres, leg 1..6), ``joint_states``
(sensor_msgs/msg/JointState, legs ``leg_1`` .. ``leg_6``) and ``leg_velocities``
(Float64MultiArray, m/s). Publishes ``estimated_pose`` (geometry_msgs/msg/Pose, base frame,
metres), ``estimated_pose_stamped`` (geometry_msgs/msg/PoseStamped: the stamp of the joint
state it comes from, or the time of arrival) and ``estimated_twist`` (geometry_msgs/msg/Twist,
base frame: from leg velocities, at the last pose). Each solve starts from the last
good solution, since a platform moves continuously, and falls back to the home pose when that
fails. Lengths out of the limits, lengths that neither start solves, a solution out of the
limits and a jump to another assembly mode publish nothing: the reason goes to the log and to
``/diagnostics`` (with iterations and residual). A solution near a singularity is published
with a WARN status.
"""

import math

from geometry_msgs.msg import Pose, PoseStamped, Twist
import numpy as np
from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, Header

from stewart_kinematics import limits, parameter_spec
from stewart_kinematics.kinematics import forward_kinematics
from stewart_kinematics.parameter_spec import geometry_from_parameters
from stewart_kinematics.ros.message_accounting import (
    MessageAccounting,
    NodeDiagnostics,
    violation_values,
)
from stewart_kinematics.ros.message_conversions import (
    leg_lengths_from_message,
    legs_from_joint_state,
    pose_to_message,
    twist_to_message,
)
from stewart_kinematics.ros.node_main import create_output_publisher, run_node
from stewart_kinematics.ros.ros_parameters import declare_parameters
from stewart_kinematics.rotations import euler_zyx_to_matrix, rotation_angle_between
from stewart_kinematics.velocities import platform_twist


class FkNode(Node):
    """Publish the platform pose that matches every set of leg lengths received, or refuse."""

    def __init__(self, **kwargs):
        super().__init__('fk_node', **kwargs)
        self.settings = {}
        values = declare_parameters(
            self,
            parameter_spec.GEOMETRY_PARAMETERS + parameter_spec.SOLVER_PARAMETERS
            + parameter_spec.FRAME_PARAMETERS + parameter_spec.QUEUE_PARAMETERS,
            on_change=self.settings.__setitem__)
        self.settings.update(values)
        self.geometry = geometry_from_parameters(values)
        self.last_pose = self.geometry.home_pose
        self.last_lengths = None
        # The last good solution itself: a solve from it reuses its Jacobian too.
        self.last_result = None
        depth = values['queue_depth']
        self.pose_publisher = create_output_publisher(self, Pose, 'estimated_pose', depth)
        self.stamped_publisher = create_output_publisher(
            self, PoseStamped, 'estimated_pose_stamped', depth)
        self.twist_publisher = create_output_publisher(self, Twist, 'estimated_twist', depth)
        diagnostics = NodeDiagnostics(self)
        self.accounting = diagnostics.accounting('leg_lengths')
        self.joint_state_accounting = diagnostics.accounting('joint_states')
        self.velocity_accounting = diagnostics.accounting('leg_velocities')
        self.create_subscription(Float64MultiArray, 'leg_lengths', self.on_leg_lengths, depth)
        self.create_subscription(JointState, 'joint_states', self.on_joint_states, depth)
        self.create_subscription(
            Float64MultiArray, 'leg_velocities', self.on_leg_velocities, depth)
        self.get_logger().info(
            f'ready: tolerance {values["tolerance"]:g} m, '
            f'at most {values["max_iterations"]} iterations')

    def on_leg_lengths(self, message: Float64MultiArray):
        """Solve for the pose of the received lengths and publish it, or say why not."""
        self.accounting.receive()
        try:
            lengths = leg_lengths_from_message(message)
        except ValueError as error:
            self.accounting.reject(f'leg_lengths rejected: {error}')
            return
        header = Header(stamp=self.get_clock().now().to_msg())
        self.estimate(lengths, header, self.accounting)

    def on_joint_states(self, message: JointState):
        """Solve for the pose of a joint state; with leg velocities, publish the twist too."""
        self.joint_state_accounting.receive()
        try:
            lengths, velocities = legs_from_joint_state(message)
        except ValueError as error:
            self.joint_state_accounting.reject(f'joint_states rejected: {error}')
            return
        if self.estimate(lengths, message.header, self.joint_state_accounting) and (
                velocities is not None):
            self.twist_publisher.publish(twist_to_message(
                platform_twist(self.geometry, self.last_pose, velocities)))

    def on_leg_velocities(self, message: Float64MultiArray):
        """Publish the platform twist of leg velocities at the last estimated pose."""
        self.velocity_accounting.receive()
        try:
            velocities = np.asarray(message.data, dtype=float)[message.layout.data_offset:]
            twist = platform_twist(self.geometry, self.last_pose, velocities)
        except ValueError as error:
            self.velocity_accounting.reject(f'leg_velocities rejected: {error}')
            return
        self.velocity_accounting.publish(self.twist_publisher, twist_to_message(twist))

    def estimate(self, lengths, header: Header, accounting: MessageAccounting) -> bool:
        """
        Publish the pose of six leg lengths, or reject them with the reason.

        :param header: stamp to carry to ``estimated_pose_stamped``; its frame is base_frame.
        :returns: whether a pose was published.
        """
        violations = limits.leg_length_violations(self.geometry, lengths)
        if violations:
            accounting.reject(
                f'{accounting.topic} rejected, out of the limits: '
                + '; '.join(map(str, violations)), violation_values(violations))
            return False
        result = self.solve(lengths)
        if not result.converged:
            accounting.reject(
                f'no pose found for leg lengths {np.round(lengths, 6).tolist()} m: '
                f'{result.reason}',
                (('iterations', result.iterations), ('residual_m', f'{result.residual:.3g}')))
            return False
        position, rotation = result.pose[:3], euler_zyx_to_matrix(result.pose[3:])
        violations = limits.check_pose(self.geometry, position, rotation)
        if violations:
            accounting.reject(
                'the pose of these leg lengths is out of the limits: '
                + '; '.join(map(str, violations)), violation_values(violations))
            return False
        jump = self.assembly_mode_jump(lengths, result.pose)
        if jump:
            accounting.reject(f'{accounting.topic} {jump}')
            return False
        condition = float(limits.jacobian_condition(self.geometry, position, rotation))
        if condition > self.settings['near_singularity_condition']:
            accounting.warn(
                f'estimated pose is near a singularity: Jacobian condition number '
                f'{condition:.4g} > near_singularity_condition '
                f'{self.settings["near_singularity_condition"]:g}',
                (('jacobian_condition', f'{condition:.4g}'),))
        self.last_pose, self.last_lengths, self.last_result = result.pose, lengths, result
        pose = pose_to_message(result.pose)
        accounting.publish(self.pose_publisher, pose)
        if self.stamped_publisher.get_subscription_count():  # only for a subscriber, as ik_node
            stamped_header = Header(stamp=header.stamp, frame_id=self.settings['base_frame'])
            self.stamped_publisher.publish(PoseStamped(header=stamped_header, pose=pose))
        return True

    def solve(self, lengths):
        """Solve from the last good pose, then from the home pose if that fails."""
        options = {'tolerance': self.settings['tolerance'],
                   'max_iterations': self.settings['max_iterations']}
        # The last result carries its Jacobian too, but only while it is the last pose.
        last = self.last_result
        start = last if last is not None and last.pose is self.last_pose else self.last_pose
        result = forward_kinematics(self.geometry, lengths, start, **options)
        if not result.converged and not np.array_equal(self.last_pose, self.geometry.home_pose):
            result = forward_kinematics(self.geometry, lengths, self.geometry.home_pose,
                                        **options)
        return result

    def assembly_mode_jump(self, lengths, pose) -> str:
        """
        Say why ``pose`` looks like a jump to another assembly mode, or return ``''``.

        For the same leg lengths a platform has several poses (assembly modes). A solution far
        from the last one while the lengths barely changed is one of the others, not where the
        platform went.
        """
        if self.last_lengths is None:
            return ''
        length_change = max(map(abs, (lengths - self.last_lengths).tolist()))
        if length_change > self.settings['assembly_guard_length_change']:
            return ''
        position_change = math.dist(pose[:3].tolist(), self.last_pose[:3].tolist())
        angle_change = math.degrees(float(rotation_angle_between(
            euler_zyx_to_matrix(self.last_pose[3:]), euler_zyx_to_matrix(pose[3:]))))
        if (position_change <= self.settings['assembly_guard_position_change']
                and angle_change <= self.settings['assembly_guard_angle_change_deg']):
            return ''
        return (f'rejected: the solution jumped {position_change:.4g} m and '
                f'{angle_change:.4g} deg from the last one while no leg changed by more than '
                f'{length_change:.4g} m: another assembly mode, not a motion')


def main(args=None) -> int:
    """Run the FK node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(FkNode, 'fk_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
