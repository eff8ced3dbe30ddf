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

Subscribes ``target_pose`` (geometry_msgs/msg/Pose, base frame, metres). Publishes
``leg_lengths`` (std_msgs/msg/Float64MultiArray, metres, leg 1..6) and ``leg_extensions``
(the same layout: each length minus its length at the home pose, the paper's q_i). A pose
that breaks a limit of the geometry is refused, never clamped: see
:mod:`stewart_kinematics.limits` and :mod:`stewart_kinematics.message_accounting`.
"""

from geometry_msgs.msg import Pose
import numpy as np
from rclpy.node import Node
from std_msgs.msg import Float64MultiArray

from stewart_kinematics import limits, parameter_spec
from stewart_kinematics.geometry import Geometry
from stewart_kinematics.kinematics import leg_lengths
from stewart_kinematics.message_accounting import MessageAccounting, violation_values
from stewart_kinematics.message_conversions import (
    legs_to_message,
    position_quaternion_from_message,
    QUATERNION_NORM_TOLERANCE,
)
from stewart_kinematics.node_main import run_node
from stewart_kinematics.ros_parameters import declare_parameters
from stewart_kinematics.rotations import quaternion_to_matrix


class IkNode(Node):
    """Publish the leg lengths of every pose received on ``target_pose``, or refuse it."""

    def __init__(self, **kwargs):
        super().__init__('ik_node', **kwargs)
        values = declare_parameters(
            self, parameter_spec.GEOMETRY_PARAMETERS + parameter_spec.QUEUE_PARAMETERS)
        self.geometry = Geometry.from_parameters(values)
        depth = values['queue_depth']
        self.lengths_publisher = self.create_publisher(Float64MultiArray, 'leg_lengths', depth)
        self.extensions_publisher = self.create_publisher(
            Float64MultiArray, 'leg_extensions', depth)
        self.accounting = MessageAccounting(self, 'target_pose')
        self.create_subscription(Pose, 'target_pose', self.on_target_pose, depth)
        self.get_logger().info(
            'ready: home leg lengths '
            f'{np.array2string(self.geometry.home_leg_lengths, precision=6, separator=", ")} m')

    def on_target_pose(self, message: Pose):
        """Turn a pose into leg lengths and extensions, or reject it with every reason."""
        self.accounting.receive()
        try:
            position, quaternion, norm = position_quaternion_from_message(message)
        except ValueError as error:
            self.accounting.reject(f'target_pose rejected: {error}')
            return
        if abs(norm - 1.0) > QUATERNION_NORM_TOLERANCE:
            self.get_logger().warning(
                f'target_pose orientation has norm {norm:.9g}, not 1: normalised (said once)',
                once=True)
        rotation = quaternion_to_matrix(quaternion)
        violations = limits.check_pose(self.geometry, position, rotation)
        if violations:
            self.accounting.reject(
                'target_pose rejected, out of the limits: '
                + '; '.join(str(violation) for violation in violations),
                violation_values(violations))
            return
        lengths = leg_lengths(self.geometry, position, rotation)
        self.accounting.publish(self.lengths_publisher, legs_to_message(lengths))
        self.extensions_publisher.publish(
            legs_to_message(lengths - self.geometry.home_leg_lengths))


def main(args=None) -> int:
    """Run the IK node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(IkNode, 'ik_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
