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
Trajectory node: plays the paper's Table 3 ramp, and checks, times and hands on trajectories.

The ramp: publishes ``target_pose`` (geometry_msgs/msg/Pose, base frame, metres). In ``table``
mode it publishes the table's rows, one every ``row_period``; in ``interpolate`` mode it samples
the ramp in time at ``publish_rate`` over ``duration``, as the paper's clock-driven lookup
tables do. Once, or looping. Before playing, it checks every pose it would publish against the
limits of the geometry (the same parameters as ik_node) and refuses to start, listing the
failing samples, rather than play half of the ramp. ``mode: 'off'`` plays no ramp. What is
played when, and the check, are :class:`stewart_kinematics.motion.ramp.RampSchedule`'s.

Trajectories: ``pose_trajectory`` (trajectory_msgs/msg/MultiDOFJointTrajectory, one joint,
the platform) and ``pose_path`` (nav_msgs/msg/Path, waypoints without timing) are checked whole
and timed by :func:`stewart_kinematics.plan_motion` (retimed with ``retime`` or for a path);
an accepted one goes out on ``leg_trajectory`` (trajectory_msgs/msg/JointTrajectory: the
actuators' positions, velocities and accelerations, for joint_trajectory_controller) and, with
``play``, as poses on ``target_pose`` at ``publish_rate``. A refused one publishes nothing; the
reason (time, segment, leg, limit) goes to the log and ``/diagnostics``. So does a trajectory
received while the tool frame is offset from the platform frame
(:func:`~stewart_kinematics.motion.trajectory_check.trajectory_frame_refusal`).
"""

import threading


from nav_msgs.msg import Path
from rclpy.node import Node
from std_msgs.msg import Header

from stewart_kinematics.findings import Finding, INVALID_TRAJECTORY
from stewart_kinematics.model.rotations import quaternion_to_matrix
from stewart_kinematics.motion.leg_trajectory import leg_trajectory
from stewart_kinematics.motion.planning import plan_motion
from stewart_kinematics.motion.pose_trajectory import PoseTrajectory
from stewart_kinematics.motion.ramp import RampSchedule
from stewart_kinematics.motion.retiming import load_retiming
from stewart_kinematics.motion.trajectory_check import trajectory_frame_refusal
from stewart_kinematics.parameters import (
    actuator_interface_from_settings,
    actuator_limits_from_settings,
    frame_parameters_reason,
    frames_from_settings,
    geometry_from_settings,
    TrajectoryNodeSettings,
)
from stewart_kinematics.ros.interfaces import TRAJECTORY_NODE
from stewart_kinematics.ros.message_accounting import NodeDiagnostics
from stewart_kinematics.ros.message_conversions import (
    joint_trajectory_message,
    path_from_message,
    pose_message,
    pose_to_message,
    pose_trajectory_from_message,
)
from stewart_kinematics.ros.node_main import (
    create_input_subscription,
    create_output_publisher,
    run_node,
)
from stewart_kinematics.ros.ros_parameters import declare_settings
from trajectory_msgs.msg import MultiDOFJointTrajectory

#: Seconds between two checks for subscribers while waiting for min_subscribers.
WAIT_PERIOD = 0.05


class TrajectoryNode(Node):
    """Publish a ramp of poses on ``target_pose``; check, time and publish trajectories."""

    def __init__(self, **kwargs):
        super().__init__('trajectory_node', **kwargs)
        self.settings = declare_settings(self, TrajectoryNodeSettings,
                                         on_change=self.on_parameter_change,
                                         check=frame_parameters_reason, node_options=kwargs)
        settings = self.settings
        self.geometry = geometry_from_settings(settings.geometry)
        self.actuator_limits = actuator_limits_from_settings(settings.geometry)
        self.actuators = actuator_interface_from_settings(settings.actuators)
        self.schedule = RampSchedule.from_settings(settings.ramp)
        self.rows = self.schedule.ramp.rows
        self.frames = frames_from_settings(settings.frames)
        refusal = self.schedule.check(self.geometry, self.frames)
        if refusal is not None:
            raise ValueError(refusal.message)     # the node cannot start: main() says why
        # Paths are always retimed: import toppra and scipy (seconds) now, beside the start-up
        # and the ramp, not in the first callback; a callback that needs them meanwhile waits
        # for the import to finish (Python's import lock).
        threading.Thread(target=load_retiming, name='load_retiming', daemon=True).start()
        depth = settings.queue.queue_depth
        self.publisher = create_output_publisher(self, TRAJECTORY_NODE['target_pose'], depth)
        self.leg_trajectory_publisher = create_output_publisher(
            self, TRAJECTORY_NODE['leg_trajectory'], depth)
        diagnostics = NodeDiagnostics(self)
        self.trajectory_accounting = diagnostics.accounting('pose_trajectory')
        self.path_accounting = diagnostics.accounting('pose_path')
        create_input_subscription(
            self, TRAJECTORY_NODE['pose_trajectory'], self.on_pose_trajectory, depth)
        create_input_subscription(self, TRAJECTORY_NODE['pose_path'], self.on_pose_path, depth)
        self.published = 0
        self.row_index = 0
        self.start_time = None
        self.timer = None
        self.wait_timer = None
        self.playing = None
        self.play_start = None
        self.play_timer = None
        if self.schedule.plays:
            self.wait_timer = self.create_timer(WAIT_PERIOD, self.start_when_subscribed)
            self.get_logger().info(
                f'{settings.ramp.mode} ramp of {len(self.rows)} rows, '
                + ('looping' if settings.ramp.loop else 'once'))

    def on_parameter_change(self, name, value):
        """Take a validated run-time change (the motion settings, the tool frame) from now on."""
        self.settings = self.settings.replace(**{name: value})
        if name.startswith('tool_frame'):
            self.frames = frames_from_settings(self.settings.frames)

    def start_when_subscribed(self):
        """Start playing once ``min_subscribers`` subscriptions are matched."""
        wanted = self.settings.ramp.min_subscribers
        if self.publisher.get_subscription_count() < wanted:
            self.get_logger().info(
                f'waiting for {wanted} subscriber(s) on {self.publisher.topic_name}', once=True)
            return
        self.wait_timer.cancel()
        self.wait_timer = self.create_timer(self.settings.ramp.start_delay, self.start)

    def start(self):
        """Play the ramp: rows on a timer in table mode, samples in interpolate mode."""
        self.wait_timer.cancel()
        if self.schedule.mode == 'table':
            self.timer = self.create_timer(self.schedule.period, self.publish_row)
            self.publish_row()
        else:
            self.start_time = self.get_clock().now()
            self.timer = self.create_timer(self.schedule.period, self.publish_sample)
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
        elapsed = (self.get_clock().now() - self.start_time).nanoseconds * 1e-9
        self.publish(self.schedule.pose_at(elapsed))
        if elapsed >= self.schedule.duration:
            self.start_time = self.get_clock().now()
            self.finish_pass()

    def publish(self, pose):
        """Publish one pose on ``target_pose``."""
        self.publisher.publish(pose_to_message(pose))
        self.published += 1

    def finish_pass(self):
        """Start again when looping; otherwise stop the timer and say so."""
        if not self.schedule.loop:
            self.timer.cancel()
            self.get_logger().info(f'ramp finished: {self.published} poses published')

    def on_pose_trajectory(self, message: MultiDOFJointTrajectory):
        """Check, time (with ``retime``) and publish a platform trajectory, or refuse it."""
        self.trajectory_accounting.receive()
        try:
            path = PoseTrajectory.from_quaternions(
                **pose_trajectory_from_message(message, self.settings.frames.base_frame))
        except ValueError as error:
            self.trajectory_accounting.reject(Finding(INVALID_TRAJECTORY, str(error)))
            return
        self.plan(path, self.settings.motion.retime, self.trajectory_accounting)

    def on_pose_path(self, message: Path):
        """Check, retime and publish a path of waypoints without timing, or refuse it."""
        self.path_accounting.receive()
        try:
            positions, quaternions = path_from_message(message, self.settings.frames.base_frame)
            path = PoseTrajectory.path(self.geometry, positions,
                                       quaternion_to_matrix(quaternions))
        except ValueError as error:
            self.path_accounting.reject(Finding(INVALID_TRAJECTORY, str(error)))
            return
        self.plan(path, True, self.path_accounting)

    def plan(self, path, retime, accounting):
        """Check and time a path; publish its leg trajectory (and play it) or count the refusal."""
        refusal = trajectory_frame_refusal(self.frames, accounting.topic)
        if refusal is not None:
            accounting.reject(refusal)
            return
        plan = plan_motion(path, self.geometry, self.actuator_limits, retime_path=retime,
                           speed_scale=self.settings.motion.speed_scale,
                           validation_rate=self.settings.motion.validation_rate)
        if not plan.accepted:
            accounting.reject(plan.refusal)
            return
        points = leg_trajectory(plan.trajectory, self.geometry, self.actuators,
                                self.settings.ramp.publish_rate)
        header = Header(stamp=self.get_clock().now().to_msg(),
                        frame_id=self.settings.frames.base_frame)
        accounting.publish(self.leg_trajectory_publisher,
                           joint_trajectory_message(header, points))
        self.get_logger().info(
            f'{accounting.topic}: {path.waypoint_count} waypoints accepted, '
            + ('retimed to ' if plan.retimed else 'timed ')
            + f'{plan.trajectory.duration:.3f} s; {len(points.times)} points on leg_trajectory')
        if self.settings.motion.play:
            self.play(plan.trajectory)

    def play(self, trajectory):
        """Stream a timed trajectory's poses on ``target_pose``; a new one replaces it."""
        if self.play_timer is not None:
            self.play_timer.cancel()
            self.destroy_timer(self.play_timer)
        self.playing = trajectory
        self.play_start = self.get_clock().now()
        self.play_timer = self.create_timer(1.0 / self.settings.ramp.publish_rate,
                                            self.publish_playing)
        self.publish_playing()

    def publish_playing(self):
        """Publish the pose of the trajectory being played at the current time."""
        elapsed = (self.get_clock().now() - self.play_start).nanoseconds * 1e-9
        duration = self.playing.duration
        sample = self.playing.sample([min(elapsed, duration)])
        self.publisher.publish(pose_message(sample.positions[0], sample.rotations[0]))
        self.published += 1
        if elapsed >= duration:
            self.play_timer.cancel()


def main(args=None) -> int:
    """Run the trajectory node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(TrajectoryNode, 'trajectory_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
