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
the tool frame, with its twists and accelerations when given) and ``pose_path``
(nav_msgs/msg/Path, waypoints without timing), in the base frame or the user frame, are
planned by :class:`stewart_kinematics.MotionPlanner`: moved from the tool frame to the
platform frame, checked whole and timed (retimed with ``retime``, and always for a path). An
accepted one goes out on ``leg_trajectory`` (trajectory_msgs/msg/JointTrajectory: the
actuators' positions, velocities and accelerations, for joint_trajectory_controller) and, with
``play``, as poses of the tool frame on ``target_pose`` at ``publish_rate``. A refused one
publishes nothing; the reason (time, waypoints, leg, limit) goes to the log and
``/diagnostics``.

Planning runs in a worker thread (:class:`PlanningWorker`), never in the executor: the node
answers parameters, services and diagnostics, and takes new messages, while a long trajectory
is checked. A new trajectory or path replaces the one being planned, which is answered with
``superseded``; a stop (SIGINT) cancels it within one step of the work (about 0.1 s). A
parameter changed at run time (tool frame, ``retime``, ``speed_scale``, ``validation_rate``,
``play``) applies from the next message on, exactly as it would from a start-up with it.
"""

from dataclasses import dataclass, field
import os
import threading
from typing import Any, Callable, Optional

from nav_msgs.msg import Path
from rclpy.node import Node
from std_msgs.msg import Header

from stewart_kinematics.findings import Finding, INVALID_TRAJECTORY, PLANNING_ERROR, SUPERSEDED
from stewart_kinematics.limits import CommandGate, SETPOINT
from stewart_kinematics.model.actuators import ActuatorInterface
from stewart_kinematics.motion.planning import MotionPlanner
from stewart_kinematics.motion.playback import TrajectoryPlayback
from stewart_kinematics.motion.ramp import RampSchedule
from stewart_kinematics.motion.retiming import Cancelled, load_retiming
from stewart_kinematics.parameters import (
    actuator_interface_from_settings,
    actuator_limits_from_settings,
    frame_parameters_reason,
    frames_from_settings,
    geometry_from_settings,
    TrajectoryNodeSettings,
)
from stewart_kinematics.ros.command_publishing import send_command
from stewart_kinematics.ros.interfaces import TRAJECTORY_NODE
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
from stewart_kinematics.ros.ros_parameters import declare_settings
from trajectory_msgs.msg import MultiDOFJointTrajectory

#: Seconds between two checks for subscribers while waiting for min_subscribers.
WAIT_PERIOD = 0.05
#: Longest a stopping node waits for the worker to leave the step it is in, seconds (then
#: it leaves it behind: a daemon thread, which publishes nothing once the node is closed).
WORKER_STOP_TIMEOUT = 0.25
#: Scheduling priority of the planning thread below the executor's (nice(2) increment).
WORKER_NICENESS = 10


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
        self.planner = self.make_planner(settings)
        refusal = self.schedule.check(self.geometry, self.frames)
        if refusal is not None:
            raise ValueError(refusal.message)     # the node cannot start: main() says why
        # Paths are always retimed: import toppra and scipy (seconds) now, beside the start-up
        # and the ramp, not in the first plan; a plan that needs them meanwhile waits for the
        # import to finish (Python's import lock).
        threading.Thread(target=load_retiming, name='load_retiming', daemon=True).start()
        depth = settings.queue.queue_depth
        self.publisher = create_output_publisher(
            self, TRAJECTORY_NODE['target_pose'], depth, command_pose_message)
        self.leg_trajectory_publisher = create_output_publisher(
            self, TRAJECTORY_NODE['leg_trajectory'], depth,
            lambda command: joint_trajectory_message(Header(), command.trajectory))
        diagnostics = NodeDiagnostics(self)
        self.trajectory_accounting = diagnostics.accounting('pose_trajectory')
        self.path_accounting = diagnostics.accounting('pose_path')
        self.worker = PlanningWorker(self, self.on_planned)
        create_input_subscription(
            self, TRAJECTORY_NODE['pose_trajectory'], self.on_pose_trajectory, depth)
        create_input_subscription(self, TRAJECTORY_NODE['pose_path'], self.on_pose_path, depth)
        self.published = 0
        #: The clock's origin of the playing's times, nanoseconds.
        self.clock_origin_ns = self.get_clock().now().nanoseconds
        self.row_index = 0
        self.start_time = None
        self.timer = None
        self.wait_timer = None
        self.playing = None
        self.play_timer = None
        if self.schedule.plays:
            self.wait_timer = self.create_timer(WAIT_PERIOD, self.start_when_subscribed)
            self.get_logger().info(
                f'{settings.ramp.mode} ramp of {len(self.rows)} rows, '
                + ('looping' if settings.ramp.loop else 'once'))

    def make_planner(self, settings) -> 'PlanSettings':
        """Build the planner and the output settings of ``settings``, as at start-up."""
        motion = settings.motion
        frames = frames_from_settings(settings.frames)
        return PlanSettings(
            MotionPlanner(self.geometry, self.actuator_limits, frames, retime=motion.retime,
                          speed_scale=motion.speed_scale,
                          validation_rate=motion.validation_rate,
                          publish_rate=settings.ramp.publish_rate, actuators=self.actuators),
            self.actuators, settings.ramp.publish_rate, motion.play, settings.frames.base_frame,
            CommandGate(self.geometry, timing=SETPOINT, frames=frames))

    def on_parameter_change(self, name, value):
        """Take a validated run-time change (the motion settings, the tool frame) from now on."""
        self.settings = self.settings.replace(**{name: value})
        if name.startswith('tool_frame'):
            self.frames = frames_from_settings(self.settings.frames)
        # A new planner for the next message; the one being planned keeps its own.
        self.planner = self.make_planner(self.settings)

    def destroy_node(self):
        """Stop the worker (a plan under way is cancelled), then destroy the node."""
        self.worker.close()
        return super().destroy_node()

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
        """Publish one pose of the ramp on ``target_pose``, as the gate passes it."""
        command = self.planner.ramp_gate.pose_vector(pose)
        if not command.accepted:
            # Checked before playing; a tool frame changed since may move it out of the limits.
            self.get_logger().warning(f'ramp pose not sent: {command.reason}',
                                      throttle_duration_sec=1.0)
            return
        self.publisher.publish(command)
        self.published += 1

    def finish_pass(self):
        """Start again when looping; otherwise stop the timer and say so."""
        if not self.schedule.loop:
            self.timer.cancel()
            self.get_logger().info(f'ramp finished: {self.published} poses published')

    def on_pose_trajectory(self, message: MultiDOFJointTrajectory):
        """Hand a platform trajectory to the worker: checked and timed (``retime``) there."""
        self.trajectory_accounting.receive()
        settings = self.planner
        self.worker.submit(PlanningJob(
            self.trajectory_accounting, settings, len(message.points), lambda cancel: (
                settings.planner.plan_trajectory(**pose_trajectory_from_message(message),
                                                 cancel=cancel)),
            self.leg_trajectory_publisher.prepare))

    def on_pose_path(self, message: Path):
        """Hand a path of waypoints without timing to the worker: always retimed there."""
        self.path_accounting.receive()
        settings = self.planner

        def plan(cancel):
            positions, quaternions, frame_id = path_from_message(message)
            return settings.planner.plan_path(positions, quaternions, frame_id, cancel=cancel)
        self.worker.submit(PlanningJob(self.path_accounting, settings, len(message.poses), plan,
                                       self.leg_trajectory_publisher.prepare))

    def on_planned(self, job: 'PlanningJob', outcome):
        """
        Publish a plan the worker finished, or count its refusal (executor thread).

        :param outcome: a :class:`PlannedTrajectory`, a :class:`Finding` (superseded, or an
            error of the worker), never an exception.
        """
        accounting = job.accounting
        if isinstance(outcome, Finding):
            accounting.reject(outcome)
            return
        plan = outcome.plan
        if not plan.accepted:
            accounting.reject(plan.refusal)
            return
        prepared = outcome.message
        prepared.message.header = Header(stamp=self.get_clock().now().to_msg(),
                                         frame_id=job.settings.base_frame)
        send_command(self.leg_trajectory_publisher, accounting, prepared)
        message = prepared.message
        self.get_logger().info(
            f'{accounting.topic}: {job.waypoints} waypoints accepted, '
            + ('retimed to ' if plan.retimed else 'timed ')
            + f'{plan.trajectory.duration:.3f} s; {len(message.points)} points on '
            'leg_trajectory')
        if job.settings.play:
            self.play(plan.trajectory, job.settings)

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
    :param ramp_gate: the command gate of the ramp's poses on target_pose (with the frames).
    """

    planner: MotionPlanner
    actuators: ActuatorInterface
    publish_rate: float
    play: bool
    base_frame: str
    ramp_gate: CommandGate


@dataclass
class PlanningJob:
    """
    One message to plan in the worker.

    :param accounting: the input's message accounting (where its answer is counted).
    :param settings: the parameters it is planned with (those when it arrived).
    :param waypoints: how many waypoints the message has, for the log.
    :param plan: ``plan(cancel) -> MotionPlan``: converts the message and plans it.
    :param prepare: the leg_trajectory publisher's ``prepare``: the message of the plan's
        verdict, built in the worker.
    """

    accounting: Any
    settings: PlanSettings
    waypoints: int
    plan: Callable
    prepare: Callable
    cancel: threading.Event = field(default_factory=threading.Event)

    def run(self):
        """
        Plan, then sample and convert an accepted plan (worker thread).

        :returns: a :class:`PlannedTrajectory`, or the :class:`Finding` of a message that
            cannot be converted.
        :raises Cancelled: when ``cancel`` is set meanwhile.
        """
        try:
            plan = self.plan(self.cancel)
        except ValueError as error:   # the message cannot be converted
            return Finding(INVALID_TRAJECTORY, str(error))
        if not plan.accepted:
            return PlannedTrajectory(plan)
        return PlannedTrajectory(plan, self.prepare(plan.command))


@dataclass(frozen=True)
class PlannedTrajectory:
    """An answer of the worker: the plan and, accepted, its leg_trajectory message prepared."""

    plan: Any
    message: Optional[Any] = None


class PlanningWorker:
    """
    A thread that plans one message at a time, off the executor; the newest replaces the rest.

    :meth:`submit` (executor thread) makes a job the next one: a job still waiting is answered
    ``superseded`` at once, and the one running is cancelled (its work stops at its next step
    and it is answered ``superseded`` too). Each answer goes back to the node's executor as a
    task (:func:`~stewart_kinematics.ros.node_main.hand_to_executor`; the EventsExecutor
    supports no guard condition), which calls ``on_done(job, outcome)`` there, so that all
    publishing and counting happens on the executor. An unexpected error in the work (a bug)
    is answered with ``planning_error`` and the thread goes on. :meth:`close` cancels the work
    and waits at most :data:`WORKER_STOP_TIMEOUT` for the thread (a daemon, so it never holds
    up the exit).

    :param node: the node whose executor gets the answers.
    :param on_done: ``on_done(job, outcome)``, outcome a :class:`PlannedTrajectory` or a
        :class:`Finding`.
    """

    def __init__(self, node, on_done):
        self.node = node
        self.on_done = on_done
        self._condition = threading.Condition()
        self._next = None
        self._running = None
        self._answers = []
        self._closed = False
        self._thread = threading.Thread(target=self._serve, name='trajectory planning',
                                        daemon=True)
        self._thread.start()

    def submit(self, job: PlanningJob) -> None:
        """Plan ``job`` next: it replaces a job waiting, and cancels the one running."""
        with self._condition:
            replaced, self._next = self._next, job
            if self._running is not None:
                self._running.cancel.set()
            self._condition.notify()
        if replaced is not None:
            self.on_done(replaced, _superseded(replaced))

    def _serve(self):
        # Below the executor's thread: on a busy machine the kernel runs the node's callbacks
        # first (Linux gives each thread its own niceness).
        try:
            os.setpriority(os.PRIO_PROCESS, threading.get_native_id(), WORKER_NICENESS)
        except (AttributeError, OSError):  # not Linux: the thread runs at the node's priority
            pass
        while True:
            with self._condition:
                while self._next is None and not self._closed:
                    self._condition.wait()
                if self._closed:
                    return
                job, self._next = self._next, None
                self._running = job
            try:
                outcome = job.run()
            except Cancelled:
                outcome = _superseded(job)
            except Exception as error:  # noqa: B902 - a bug must not leave messages unanswered
                outcome = Finding(PLANNING_ERROR, f'planning failed unexpectedly: '
                                  f'{type(error).__name__}: {error}')
            with self._condition:
                self._running = None
                if self._closed:
                    return
                self._answers.append((job, outcome))
                # Under the lock: close() marks the worker closed only after it.
                hand_to_executor(self.node, self._deliver)

    def _deliver(self):
        """Hand the finished answers to ``on_done`` (executor thread)."""
        with self._condition:
            if self._closed:   # a task queued before the node was destroyed
                return
            answers, self._answers = self._answers, []
        for job, outcome in answers:
            self.on_done(job, outcome)

    def close(self) -> None:
        """Cancel the work under way and stop the thread."""
        with self._condition:
            self._closed = True
            if self._running is not None:
                self._running.cancel.set()
                self.node.get_logger().info(
                    f'{self._running.accounting.topic}: planning cancelled, the node stops')
            self._condition.notify()
        self._thread.join(WORKER_STOP_TIMEOUT)


def _superseded(job):
    """Return the answer of a job that a newer message replaced."""
    return Finding(SUPERSEDED, f'{job.accounting.topic}: replaced by a newer trajectory or path '
                   'before it was decided')


def main(args=None) -> int:
    """Run the trajectory node until SIGINT or SIGTERM; see :func:`run_node`."""
    return run_node(TrajectoryNode, 'trajectory_node', args)


if __name__ == '__main__':
    raise SystemExit(main())
