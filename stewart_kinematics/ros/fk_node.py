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
fails; the service ``reset_tracker`` (std_srvs/srv/Trigger) makes the next solve start from the
home pose, for homing and restarts. What to publish and what to refuse is decided by
:class:`stewart_kinematics.PoseTracker` (lengths out of the limits, lengths that neither start
solves, a solution whose pose is not fixed to pose_tolerance, out of the limits, or in another
assembly mode); the node converts the messages, publishes, and counts each refusal and each
warning (near a singularity) with the core's reason on the log and ``/diagnostics``.
"""

from geometry_msgs.msg import Pose, PoseStamped, Twist
import numpy as np
from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, Header
from std_srvs.srv import Trigger

from stewart_kinematics import findings, parameter_spec
from stewart_kinematics.findings import Finding
from stewart_kinematics.parameter_spec import geometry_from_parameters
from stewart_kinematics.pose_tracker import PoseTracker, SETTING_NAMES
from stewart_kinematics.ros.message_accounting import MessageAccounting, NodeDiagnostics
from stewart_kinematics.ros.message_conversions import (
    leg_lengths_from_message,
    legs_from_joint_state,
    pose_to_message,
    twist_to_message,
)
from stewart_kinematics.ros.node_main import create_output_publisher, run_node
from stewart_kinematics.ros.ros_parameters import declare_parameters


class FkNode(Node):
    """Publish the platform pose that matches every set of leg lengths received, or refuse."""

    def __init__(self, **kwargs):
        super().__init__('fk_node', **kwargs)
        values = declare_parameters(
            self,
            parameter_spec.GEOMETRY_PARAMETERS + parameter_spec.SOLVER_PARAMETERS
            + parameter_spec.FRAME_PARAMETERS + parameter_spec.QUEUE_PARAMETERS,
            on_change=self.on_parameter_change)
        self.geometry = geometry_from_parameters(values)
        self.tracker = PoseTracker.from_parameters(self.geometry, values)
        self.base_frame = values['base_frame']
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
        self.create_service(Trigger, 'reset_tracker', self.on_reset_tracker)
        self.get_logger().info(
            f'ready: tolerance {values["tolerance"]:g} m, '
            f'at most {values["max_iterations"]} iterations')

    def on_parameter_change(self, name, value):
        """Pass a solver parameter changed at run time (already validated) to the tracker."""
        if name in SETTING_NAMES:
            self.tracker.configure(**{name: value})

    def on_leg_lengths(self, message: Float64MultiArray):
        """Solve for the pose of the received lengths and publish it, or say why not."""
        self.accounting.receive()
        try:
            lengths = leg_lengths_from_message(message)
        except ValueError as error:
            self.accounting.reject(Finding(findings.INVALID_LENGTHS, str(error)))
            return
        header = Header(stamp=self.get_clock().now().to_msg())
        self.estimate(lengths, header, self.accounting)

    def on_joint_states(self, message: JointState):
        """Solve for the pose of a joint state; with leg velocities, publish the twist too."""
        self.joint_state_accounting.receive()
        try:
            lengths, velocities = legs_from_joint_state(message)
        except ValueError as error:
            self.joint_state_accounting.reject(Finding(findings.INVALID_LENGTHS, str(error)))
            return
        if self.estimate(lengths, message.header, self.joint_state_accounting) and (
                velocities is not None):
            twist = self.tracker.twist(velocities)
            if twist.accepted:
                self.twist_publisher.publish(twist_to_message(twist.twist))
            else:  # the pose went out: the message counts as published, its twist as a warning
                self.joint_state_accounting.warn(twist.refusal)

    def on_leg_velocities(self, message: Float64MultiArray):
        """Publish the platform twist of leg velocities at the last estimated pose."""
        self.velocity_accounting.receive()
        velocities = np.asarray(message.data, dtype=float)[message.layout.data_offset:]
        twist = self.tracker.twist(velocities)
        if not twist.accepted:
            self.velocity_accounting.reject(twist.refusal)
            return
        self.velocity_accounting.publish(self.twist_publisher, twist_to_message(twist.twist))

    def on_reset_tracker(self, request: Trigger.Request, response: Trigger.Response):
        """Forget the last solution: the next solve starts from the home pose."""
        self.tracker.reset()
        response.success = True
        response.message = 'tracker reset: the next solve starts from the home pose'
        self.get_logger().info(response.message)
        return response

    def estimate(self, lengths, header: Header, accounting: MessageAccounting) -> bool:
        """
        Publish the tracker's pose of six leg lengths, or reject them with its reason.

        :param header: stamp to carry to ``estimated_pose_stamped``; its frame is base_frame.
        :returns: whether a pose was published.
        """
        estimate = self.tracker.update(lengths)
        for warning in estimate.warnings:
            accounting.warn(warning)
        if not estimate.accepted:
            accounting.reject(estimate.refusal)
            return False
        pose = pose_to_message(estimate.pose)
        accounting.publish(self.pose_publisher, pose)
        if self.stamped_publisher.get_subscription_count():  # only for a subscriber, as ik_node
            stamped_header = Header(stamp=header.stamp, frame_id=self.base_frame)
            self.stamped_publisher.publish(PoseStamped(header=stamped_header, pose=pose))
        return True


def main(args=None) -> int:
    """Run the FK node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(FkNode, 'fk_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
