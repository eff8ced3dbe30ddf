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
played when (rows or samples, loops, the end), when it starts (``min_subscribers``,
``start_delay``), and the check, are :class:`stewart_kinematics.motion.playback.RampPlayback`'s.

Trajectories: ``pose_trajectory`` (trajectory_msgs/msg/MultiDOFJointTrajectory, one joint,
the tool frame, with its twists and accelerations when given) and ``pose_path``
(nav_msgs/msg/Path, waypoints without timing), in the base frame or the user frame, are
planned by :class:`stewart_kinematics.MotionPlanner`: moved from the tool frame to the
platform frame, checked whole and timed (retimed with ``retime``, and always for a path). An
accepted one goes out on ``leg_trajectory`` (trajectory_msgs/msg/JointTrajectory: the
actuators' positions, velocities and accelerations, for joint_trajectory_controller) and, with
``play``, as poses of the tool frame on ``target_pose`` at ``publish_rate``
(:class:`stewart_kinematics.motion.playback.TrajectoryPlayback`; a newer one replaces it). A
refused one publishes nothing; the reason (time, waypoints, leg, limit) goes to the log and
``/diagnostics``.

Planning runs in a worker thread (:class:`stewart_kinematics.motion.planning_worker.
PlanningWorker`), never in the executor: the node answers parameters, services and
diagnostics, and takes new messages, while a long trajectory is checked. A new trajectory or
path replaces the one being planned, which is answered with ``superseded``; a stop (SIGINT)
cancels it within one step of the work (about 0.1 s). The answers come back to the executor
(:func:`~stewart_kinematics.ros.node_main.hand_to_executor`), where they are published and
counted. A parameter changed at run time (tool frame, ``retime``, ``speed_scale``,
``validation_rate``, ``play``) applies from the next message on, exactly as it would from a
start-up with it.
"""

from dataclasses import dataclass

from nav_msgs.msg import Path
from std_msgs.msg import Header

from stewart_kinematics.model.actuators import ActuatorInterface
from stewart_kinematics.motion.planning import MotionPlanner
from stewart_kinematics.motion.planning_worker import PlanningAnswer, PlanningJob, PlanningWorker
from stewart_kinematics.motion.playback import RampPlayback, TrajectoryPlayback
from stewart_kinematics.motion.retiming import load_retiming
from stewart_kinematics.parameters import (
    actuator_interface_from_settings,
    actuator_limits_from_settings,
    frames_from_settings,
    geometry_from_settings,
    TrajectoryNodeSettings,
)
from stewart_kinematics.ros.command_publishing import send_command
from stewart_kinematics.ros.interfaces import TRAJECTORY_NODE
from stewart_kinematics.ros.managed import ManagedNode
from stewart_kinematics.ros.message_accounting import NodeDiagnostics
from stewart_kinematics.ros.message_conversions import (
    command_pose_message,
    joint_trajectory_message,
    path_from_message,
    pose_trajectory_from_message,
)
from stewart_kinematics.ros.node_main import (
    create_input_subscription,
    create_output_publisher,
    hand_to_executor,
    run_node,
)
from stewart_kinematics.ros.ros_parameters import RunTimePayload
from stewart_kinematics.ros.trajectory_action import JOB_NAME, TrajectoryAction
from trajectory_msgs.msg import MultiDOFJointTrajectory

#: Seconds between two checks for subscribers while waiting for min_subscribers.
WAIT_PERIOD = 0.05


class TrajectoryNode(ManagedNode):
    """Publish a ramp of poses on ``target_pose``; check, time and publish trajectories."""

    SETTINGS = TrajectoryNodeSettings
    #: Its action server needs an executor that runs rclpy's action servers (node_main).
    SERVES_ACTIONS = True

    def __init__(self, **kwargs):
        super().__init__('trajectory_node', **kwargs)

    def run_time_payload(self):
        """Plan every message from the change on with the new payload."""
        return RunTimePayload(lambda: self.geometry, self.set_mass_properties)

    def configure(self):
        """Build the geometry, the planner, the ramp (checked), the worker, every endpoint."""
        settings = self.settings
        self.geometry = geometry_from_settings(settings.geometry)
        self.actuator_limits = actuator_limits_from_settings(settings.geometry)
        self.actuators = actuator_interface_from_settings(settings.actuators)
        self.planner = self.make_planner(settings)
        self.ramp = RampPlayback.from_settings(settings.ramp, self.geometry,
                                               self.planner.planner.frames)
        refusal = self.ramp.check()
        if refusal is not None:
            raise ValueError(refusal.message)     # the node cannot start: main() says why
        depth = settings.queue.queue_depth
        self.publisher = create_output_publisher(
            self, TRAJECTORY_NODE['target_pose'], depth, command_pose_message)
        self.leg_trajectory_publisher = create_output_publisher(
            self, TRAJECTORY_NODE['leg_trajectory'], depth,
            lambda command: joint_trajectory_message(Header(), command.trajectory))
        diagnostics = NodeDiagnostics(self)
        self.trajectory_accounting = diagnostics.accounting('pose_trajectory')
        self.path_accounting = diagnostics.accounting('pose_path')
        # Paths are always retimed: import toppra and scipy (seconds) now, beside the start-up
        # and the ramp, not in the first plan.
        self.worker = self.planning_worker(warm_up=load_retiming)
        #: The follow_joint_trajectory action server (ros/trajectory_action.py).
        self.action = TrajectoryAction(self, diagnostics.accounting('follow_joint_trajectory'),
                                       diagnostics.accounting('joint_states'))
        create_input_subscription(
            self, TRAJECTORY_NODE['pose_trajectory'], self.on_pose_trajectory, depth)
        create_input_subscription(self, TRAJECTORY_NODE['pose_path'], self.on_pose_path, depth)
        self.published = 0
        #: The clock's origin of the playing's times, nanoseconds.
        self.clock_origin_ns = self.get_clock().now().nanoseconds
        self.timer = None
        self.wait_timer = None
        self.playing = None
        self.play_timer = None
        if self.ramp.plays:
            self.wait_timer = self.create_timer(WAIT_PERIOD, self.start_when_subscribed)
            self.get_logger().info(
                f'{settings.ramp.mode} ramp of {len(self.ramp.rows)} rows, '
                + ('looping' if settings.ramp.loop else 'once'))

    def planning_worker(self, warm_up=None) -> PlanningWorker:
        """Return a new planning thread whose answers come back to the executor."""
        return PlanningWorker(lambda task: hand_to_executor(self, task), self.on_planned,
                              warm_up=warm_up, name='trajectory planning')

    def deactivate(self):
        """
        Stop playing (the ramp, a trajectory) and planning: nothing more goes out.

        A plan under way is cancelled and its answer dropped, with the worker: a new one
        plans what comes once active again. The ramp does not resume: it plays once per
        configure (what was published stays counted).
        """
        for timer in (self.timer, self.wait_timer, self.play_timer):
            if timer is not None:
                timer.cancel()
        self.action.deactivate()
        cancelled = self.worker.close()
        if cancelled is not None:
            self.get_logger().info(f'{cancelled.name}: planning cancelled, the node is '
                                   'deactivated')
        self.worker = self.planning_worker()

    def make_planner(self, settings) -> 'PlanSettings':
        """Build the planner and the output settings of ``settings``, as at start-up."""
        motion = settings.motion
        return PlanSettings(
            MotionPlanner(self.geometry, self.actuator_limits, frames_from_settings(
                settings.frames), retime=motion.retime, speed_scale=motion.speed_scale,
                validation_rate=motion.validation_rate, publish_rate=settings.ramp.publish_rate,
                actuators=self.actuators),
            self.actuators, settings.ramp.publish_rate, motion.play, settings.frames.base_frame)

    def on_parameter_change(self, name, value):
        """Take a validated run-time change (the motion settings, the tool frame) from now on."""
        self.settings = self.settings.replace(**{name: value})
        # A new planner for the next message; the one being planned keeps its own.
        self.planner = self.make_planner(self.settings)
        if name.startswith('tool_frame'):
            self.ramp.set_frames(self.planner.planner.frames)

    def set_mass_properties(self, geometry):
        """Plan every message from now on with a new payload (one being planned keeps its own)."""
        self.geometry = geometry
        self.planner = self.make_planner(self.settings)

    def cleanup(self):
        """Stop the worker (a plan under way is cancelled) and the action server, if built."""
        action = getattr(self, 'action', None)
        if action is not None:
            action.destroy()
        worker = getattr(self, 'worker', None)
        cancelled = worker.close() if worker is not None else None
        if cancelled is not None:
            self.get_logger().info(f'{cancelled.name}: planning cancelled, the node stops')

    def start_when_subscribed(self):
        """Start playing once ``min_subscribers`` subscriptions are matched."""
        if not self.ramp.may_start(self.publisher.get_subscription_count()):
            self.get_logger().info(
                f'waiting for {self.ramp.min_subscribers} subscriber(s) on '
                f'{self.publisher.topic_name}', once=True)
            return
        self.wait_timer.cancel()
        self.wait_timer = self.create_timer(self.ramp.start_delay, self.start)

    def start(self):
        """Play the ramp: a pose now, then one at each tick of its timer."""
        self.wait_timer.cancel()
        self.ramp.start(self.clock_seconds())
        self.timer = self.create_timer(self.ramp.period, self.publish_ramp)
        self.publish_ramp()

    def publish_ramp(self):
        """Publish the ramp's pose of this tick on ``target_pose``, as the gate passes it."""
        command, over = self.ramp.next_pose(self.clock_seconds())
        if command.accepted:
            self.publisher.publish(command)
            self.published += 1
        else:
            # Checked before playing; a tool frame changed since may move it out of the limits.
            self.get_logger().warning(f'ramp pose not sent: {command.reason}',
                                      throttle_duration_sec=1.0)
        if over:
            self.timer.cancel()
            self.get_logger().info(f'ramp finished: {self.published} poses published')

    def on_pose_trajectory(self, message: MultiDOFJointTrajectory):
        """Hand a platform trajectory to the worker: checked and timed (``retime``) there."""
        self.trajectory_accounting.receive()
        settings = self.planner
        self.worker.submit(PlanningJob(
            'pose_trajectory', lambda cancel: settings.planner.plan_trajectory(
                **pose_trajectory_from_message(message), cancel=cancel),
            self.leg_trajectory_publisher.prepare,
            (self.trajectory_accounting, settings, len(message.points))))

    def on_pose_path(self, message: Path):
        """Hand a path of waypoints without timing to the worker: always retimed there."""
        self.path_accounting.receive()
        settings = self.planner

        def plan(cancel):
            positions, quaternions, frame_id = path_from_message(message)
            return settings.planner.plan_path(positions, quaternions, frame_id, cancel=cancel)
        self.worker.submit(PlanningJob('pose_path', plan, self.leg_trajectory_publisher.prepare,
                                       (self.path_accounting, settings, len(message.poses))))

    def on_planned(self, answer: PlanningAnswer):
        """Publish a plan the worker accepted, or count its refusal (executor thread)."""
        if answer.job.name == JOB_NAME:
            self.action.on_planned(answer)
            return
        accounting, settings, waypoints = answer.job.context
        if not answer.accepted:
            accounting.reject(answer.refusal)
            return
        plan, prepared = answer.plan, answer.prepared
        prepared.message.header = Header(stamp=self.get_clock().now().to_msg(),
                                         frame_id=settings.base_frame)
        self.action.preempt_by_topic(accounting.topic)
        send_command(self.leg_trajectory_publisher, accounting, prepared)
        self.get_logger().info(
            f'{accounting.topic}: {waypoints} waypoints accepted, '
            + ('retimed to ' if plan.retimed else 'timed ')
            + f'{plan.trajectory.duration:.3f} s; {len(prepared.message.points)} points on '
            'leg_trajectory')
        if settings.play:
            self.play(plan.trajectory, settings)

    def play(self, trajectory, settings: 'PlanSettings'):
        """Stream a timed trajectory's tool poses on ``target_pose``; a new one replaces it."""
        if self.play_timer is not None:
            self.play_timer.cancel()
            self.destroy_timer(self.play_timer)
        self.playing = TrajectoryPlayback(trajectory, self.geometry, settings.planner.frames,
                                          self.clock_seconds())
        self.play_timer = self.create_timer(1.0 / settings.publish_rate, self.publish_playing)
        self.publish_playing()

    def clock_seconds(self) -> float:
        """Return the node's clock, seconds since its start (digits kept, unlike since 1970)."""
        return (self.get_clock().now().nanoseconds - self.clock_origin_ns) * 1e-9

    def publish_playing(self):
        """Publish the tool frame's pose on the trajectory being played, at the current time."""
        command, over = self.playing.pose_at(self.clock_seconds())
        if command.accepted:
            self.publisher.publish(command)
            self.published += 1
        else:
            self.get_logger().warning(f'playing stopped: the pose at this time is not sent: '
                                      f'{command.reason}')
        if over:
            self.play_timer.cancel()


@dataclass(frozen=True)
class PlanSettings:
    """
    What a trajectory is planned and published with: one snapshot of the parameters.

    :param planner: the core's planner (geometry, limits, frames, retiming, check rate).
    :param actuators: joint names and offsets of leg_trajectory.
    :param publish_rate: points per second of leg_trajectory, and of the poses played.
    :param play: also play an accepted trajectory on target_pose.
    :param base_frame: frame of leg_trajectory's header.
    """

    planner: MotionPlanner
    actuators: ActuatorInterface
    publish_rate: float
    play: bool
    base_frame: str


def main(args=None) -> int:
    """Run the trajectory node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(TrajectoryNode, 'trajectory_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
