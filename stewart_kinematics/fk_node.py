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

Subscribes ``leg_lengths`` (std_msgs/msg/Float64MultiArray, metres, leg 1..6). Publishes
``estimated_pose`` (geometry_msgs/msg/Pose, base frame, metres). Each solve starts from the last
good solution, since a platform moves continuously, and falls back to the home pose when that
fails; lengths that neither start solves are reported and publish nothing.
"""

from geometry_msgs.msg import Pose
import numpy as np
from rclpy.node import Node
from std_msgs.msg import Float64MultiArray

from stewart_kinematics import parameter_spec
from stewart_kinematics.geometry import Geometry
from stewart_kinematics.kinematics import forward_kinematics
from stewart_kinematics.message_conversions import leg_lengths_from_message, pose_to_message
from stewart_kinematics.node_main import run_node
from stewart_kinematics.ros_parameters import declare_parameters

#: Seconds between two repeats of the same warning.
WARNING_PERIOD = 1.0


class FkNode(Node):
    """Publish the platform pose that matches every set of leg lengths received."""

    def __init__(self, **kwargs):
        super().__init__('fk_node', **kwargs)
        self.solver_settings = {}
        values = declare_parameters(
            self,
            parameter_spec.GEOMETRY_PARAMETERS + parameter_spec.SOLVER_PARAMETERS
            + parameter_spec.QUEUE_PARAMETERS,
            on_change=self.solver_settings.__setitem__)
        self.geometry = Geometry.from_parameters(values)
        self.solver_settings.update(
            tolerance=values['tolerance'], max_iterations=values['max_iterations'])
        self.last_pose = self.geometry.home_pose
        self.received = self.published = self.rejected = 0
        depth = values['queue_depth']
        self.pose_publisher = self.create_publisher(Pose, 'estimated_pose', depth)
        self.create_subscription(Float64MultiArray, 'leg_lengths', self.on_leg_lengths, depth)
        self.get_logger().info(
            f'ready: tolerance {values["tolerance"]:g} m, '
            f'at most {values["max_iterations"]} iterations')

    def on_leg_lengths(self, message: Float64MultiArray):
        """Solve for the pose of the received lengths and publish it, or say why not."""
        self.received += 1
        try:
            lengths = leg_lengths_from_message(message)
        except ValueError as error:
            self.reject(f'leg_lengths rejected: {error}')
            return
        violations = self.geometry.leg_length_violations(lengths)
        if violations:
            self.reject('leg_lengths rejected: ' + '; '.join(violations))
            return
        result = self.solve(lengths)
        if not result.converged:
            self.reject(
                f'no pose found for leg lengths {np.round(lengths, 6).tolist()} m: '
                f'{result.reason} ({result.iterations} iterations, residual '
                f'{result.residual:.3g} m)')
            return
        self.last_pose = result.pose
        self.pose_publisher.publish(pose_to_message(result.pose))
        self.published += 1

    def solve(self, lengths):
        """Solve from the last good pose, then from the home pose if that fails."""
        settings = self.solver_settings
        result = forward_kinematics(
            self.geometry, lengths, self.last_pose, tolerance=settings['tolerance'],
            max_iterations=settings['max_iterations'])
        if not result.converged and not np.array_equal(self.last_pose, self.geometry.home_pose):
            result = forward_kinematics(
                self.geometry, lengths, self.geometry.home_pose,
                tolerance=settings['tolerance'], max_iterations=settings['max_iterations'])
        return result

    def reject(self, reason: str):
        """Count a rejected message and log why, at most once per warning period."""
        self.rejected += 1
        self.get_logger().warning(
            f'{reason} ({self.rejected} rejected so far)', throttle_duration_sec=WARNING_PERIOD)


def main(args=None) -> int:
    """Run the FK node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(FkNode, 'fk_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
