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
Trajectory node: plays a ramp described as the paper's Table 3 on ``target_pose``.

Publishes ``target_pose`` (geometry_msgs/msg/Pose, base frame, metres). In ``table`` mode it
publishes the table's rows, one every ``row_period``; in ``interpolate`` mode it samples the
ramp in time at ``publish_rate`` over ``duration``, as the paper's clock-driven lookup tables
do. Once, or looping. Before playing, it checks every pose it would publish against the
limits of the geometry (the same parameters as ik_node) and refuses to start, listing the
failing samples, rather than play half of the ramp.
"""

from geometry_msgs.msg import Pose
import numpy as np
from rclpy.node import Node

from stewart_kinematics import limits, parameter_spec
from stewart_kinematics.parameter_spec import geometry_from_parameters
from stewart_kinematics.ros.message_conversions import pose_to_message
from stewart_kinematics.ros.node_main import run_node
from stewart_kinematics.ros.ros_parameters import declare_parameters
from stewart_kinematics.trajectory import Ramp

#: Seconds between two checks for subscribers while waiting for min_subscribers.
WAIT_PERIOD = 0.05


class TrajectoryNode(Node):
    """Publish a ramp of poses on ``target_pose``."""

    def __init__(self, **kwargs):
        super().__init__('trajectory_node', **kwargs)
        values = declare_parameters(
            self, parameter_spec.GEOMETRY_PARAMETERS + parameter_spec.RAMP_PARAMETERS
            + parameter_spec.QUEUE_PARAMETERS)
        self.settings = values
        self.ramp = Ramp.from_parameters(values)
        self.rows = self.ramp.rows
        limits.check_samples(geometry_from_parameters(values), *self.planned_samples())
        self.publisher = self.create_publisher(Pose, 'target_pose', values['queue_depth'])
        self.published = 0
        self.row_index = 0
        self.start_time = None
        self.timer = None
        self.wait_timer = self.create_timer(WAIT_PERIOD, self.start_when_subscribed)
        self.get_logger().info(
            f'{values["mode"]} ramp of {len(self.rows)} rows, '
            + ('looping' if values['loop'] else 'once'))

    def planned_samples(self):
        """
        Return the times (seconds from the start of a pass) and poses the node will publish.

        In interpolate mode the timer's jitter moves the real sample times a little; the ramp
        is linear between rows, so those poses lie between samples checked here.
        """
        if self.settings['mode'] == 'table':
            times = np.arange(len(self.rows)) * self.settings['row_period']
            return times, self.rows
        duration = self.settings['duration']
        times = np.append(np.arange(0.0, duration, 1.0 / self.settings['publish_rate']),
                          duration)
        return times, self.ramp.sample(times, duration)

    def start_when_subscribed(self):
        """Start playing once ``min_subscribers`` subscriptions are matched."""
        wanted = self.settings['min_subscribers']
        if self.publisher.get_subscription_count() < wanted:
            self.get_logger().info(
                f'waiting for {wanted} subscriber(s) on {self.publisher.topic_name}', once=True)
            return
        self.wait_timer.cancel()
        self.wait_timer = self.create_timer(self.settings['start_delay'], self.start)

    def start(self):
        """Play the ramp: rows on a timer in table mode, samples in interpolate mode."""
        self.wait_timer.cancel()
        if self.settings['mode'] == 'table':
            self.timer = self.create_timer(self.settings['row_period'], self.publish_row)
            self.publish_row()
        else:
            self.start_time = self.get_clock().now()
            self.timer = self.create_timer(
                1.0 / self.settings['publish_rate'], self.publish_sample)
            self.publish_sample()

    def publish_row(self):
        """Publish the next row of the table."""
        self.publish(self.rows[self.row_index])
        self.row_index += 1
        if self.row_index == len(self.rows):
            self.row_index = 0
            self.finish_pass()

    def publish_sample(self):
        """Publish the ramp's pose at the current time."""
        duration = self.settings['duration']
        elapsed = (self.get_clock().now() - self.start_time).nanoseconds * 1e-9
        self.publish(self.ramp.sample(min(elapsed, duration), duration))
        if elapsed >= duration:
            self.start_time = self.get_clock().now()
            self.finish_pass()

    def publish(self, pose):
        """Publish one pose on ``target_pose``."""
        self.publisher.publish(pose_to_message(pose))
        self.published += 1

    def finish_pass(self):
        """Start again when looping; otherwise stop the timer and say so."""
        if not self.settings['loop']:
            self.timer.cancel()
            self.get_logger().info(f'ramp finished: {self.published} poses published')


def main(args=None) -> int:
    """Run the trajectory node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(TrajectoryNode, 'trajectory_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
