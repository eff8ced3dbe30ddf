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
trajectory_node's ``follow_joint_trajectory`` action server (FollowJointTrajectory).

The contract is the core's (:mod:`stewart_kinematics.motion.trajectory_execution`,
:mod:`stewart_kinematics.motion.tolerances`, :mod:`stewart_kinematics.motion.path_braking`);
this class only converts messages, runs the goals on the node's executor and publishes:

- Every goal is accepted, then checked at once: a malformed one is aborted with its result code
  and reason (``INVALID_JOINTS``, ``INVALID_GOAL``, ``OLD_HEADER_TIMESTAMP``) and leaves a
  running goal alone. A well-formed one preempts the goal running (aborted ``INVALID_GOAL``,
  "Current goal preempted by new incoming action.", as joint_trajectory_controller answers) or
  planned, and the platform brakes to rest on its path; it is then planned in the node's
  planning worker (the one limits model, ``retime``; a refusal aborts it ``INVALID_GOAL`` with
  the planner's reason) and runs once the braking is over.
- Running, it is sent as ``action_execution`` says: its leg trajectory on ``leg_trajectory``
  once, or its leg commands on ``joint_commands`` at ``publish_rate`` through the command gate.
  Its tolerances are checked against ``joint_states`` at every tick; feedback goes out at
  ``action_feedback_rate``. A cancel, a tolerance violated and a preemption brake on the path.

The node's executor must run rclpy's action servers: the process spins on the single-threaded
executor (:func:`stewart_kinematics.ros.node_main.executor_for_nodes`).
"""

from dataclasses import dataclass, field
import math
import time
from typing import Any, Optional

import numpy as np
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.task import Future

from std_msgs.msg import Header
from stewart_kinematics import findings
from stewart_kinematics.findings import Finding
from stewart_kinematics.limits import CommandGate
from stewart_kinematics.motion.path_braking import braking_trajectory
from stewart_kinematics.motion.planning import gated_leg_trajectory, MotionPlan, plan_motion
from stewart_kinematics.motion.planning_worker import PlanningJob
from stewart_kinematics.motion.pose_trajectory import MAX_WAYPOINTS
from stewart_kinematics.motion.tolerances import (
    INVALID_GOAL,
    JointToleranceValues,
    resolve_tolerances,
    SegmentTolerances,
    StateTolerances,
    SUCCESSFUL,
    ToleranceMonitor,
)
from stewart_kinematics.motion.trajectory_execution import (
    check_goal,
    goal_motion,
    GoalRequest,
    JointSets,
    JointSpace,
    JointState,
    LEGS,
    result_code,
)
from stewart_kinematics.ros.command_publishing import send_command
from stewart_kinematics.ros.interfaces import TRAJECTORY_NODE
from stewart_kinematics.ros.message_conversions import (
    joint_state_message,
    legs_from_joint_state,
    seconds,
    stamp_nanoseconds,
)
from stewart_kinematics.ros.node_main import create_input_subscription, create_output_publisher

#: The action's name, relative (``/follow_joint_trajectory`` without a namespace).
ACTION_NAME = 'follow_joint_trajectory'
#: The planning job's name (its answers come back to :meth:`TrajectoryAction.on_planned`).
JOB_NAME = 'follow_joint_trajectory'
PREEMPTED = 'Current goal preempted by new incoming action.'
#: Longest the lifecycle's deactivate streams a braking, seconds.
MAX_DEACTIVATE_BRAKING = 2.0
#: Goal states a finished goal is put in.
SUCCEEDED, ABORTED, CANCELED = 'succeeded', 'aborted', 'canceled'


@dataclass(eq=False)
class GoalRecord:
    """One goal of the action: its handle, its answer to come, and what it runs."""

    handle: Any
    answer: Future
    kind: str = ''
    names: tuple = ()
    space: Optional[JointSpace] = None
    tolerances: Optional[SegmentTolerances] = None
    stamp: float = 0.0
    plan: Optional[MotionPlan] = None
    prepared: Any = None
    start: float = 0.0
    monitor: Optional[ToleranceMonitor] = None
    next_feedback: float = -math.inf


@dataclass(eq=False)
class Motion:
    """What is being commanded: a timed trajectory from a clock time (node seconds)."""

    trajectory: Any
    start: float
    braking: bool = False
    record: Optional[GoalRecord] = None
    gate: Any = field(default=None)


class TrajectoryAction:
    """
    The ``follow_joint_trajectory`` action server of trajectory_node (see the module).

    :param node: the trajectory_node: its ``planner`` (PlanSettings), ``settings``,
        ``geometry``, ``actuator_limits``, ``actuators``, ``worker``, ``leg_trajectory_publisher``
        and clock are read at each goal (a parameter change applies from the next goal).
    :param accounting: the action's diagnostics accounting.
    :param joint_state_accounting: the diagnostics accounting of ``joint_states``.
    """

    def __init__(self, node, accounting, joint_state_accounting):
        self.node = node
        self.accounting = accounting
        self.joint_state_accounting = joint_state_accounting
        depth = node.settings.queue.queue_depth
        self.commands_publisher = create_output_publisher(
            node, TRAJECTORY_NODE['joint_commands'], depth,
            lambda command, header: joint_state_message(
                header, command.lengths, command.velocities, actuators=node.actuators))
        create_input_subscription(node, TRAJECTORY_NODE['joint_states'], self.on_joint_states,
                                  depth)
        self.measured = None          # (positions (6,), velocities or None, node seconds)
        self.active: Optional[GoalRecord] = None
        self.pending: Optional[GoalRecord] = None
        self.waiting: Optional[GoalRecord] = None   # planned, waits for the braking's end
        self.motion: Optional[Motion] = None
        self.rest: Optional[tuple] = None          # (trajectory, clock time): where it rests
        self.server = ActionServer(
            node, node_action_type(), ACTION_NAME, execute_callback=self.execute,
            goal_callback=self.on_goal,
            cancel_callback=self.on_cancel)
        self.timer = node.create_timer(1.0 / node.settings.ramp.publish_rate, self.tick)

    def on_goal(self, request):
        """Accept every goal while the node is active (it is then checked and answered)."""
        if not getattr(self.node, 'active', True):
            self.node.get_logger().warning(f'{ACTION_NAME}: goal rejected, the node is not '
                                           'active', throttle_duration_sec=1.0)
            return GoalResponse.REJECT
        return GoalResponse.ACCEPT

    def deactivate(self) -> None:
        """
        Abort the goals and bring the platform to rest (the lifecycle's deactivate).

        As joint_trajectory_controller: "Current goal cancelled during deactivate transition."
        (``INVALID_GOAL``). Streamed, the braking is sent now, at ``publish_rate`` (it lasts
        what the leg acceleration limit needs, at most :data:`MAX_DEACTIVATE_BRAKING` s).
        """
        text = 'Current goal cancelled during deactivate transition.'
        for record in (self.pending, self.waiting, self.active):
            if record is not None:
                self.finish(record, ABORTED, INVALID_GOAL, text,
                            Finding(findings.GOAL_PREEMPTED, text))
        self.brake()
        motion = self.motion
        if motion is not None and motion.gate is not None:
            period = 1.0 / self.node.settings.ramp.publish_rate
            deadline = motion.start + min(motion.trajectory.duration, MAX_DEACTIVATE_BRAKING)
            while self.now() < deadline:
                self.stream(motion, self.now() - motion.start, self.now())
                time.sleep(period)
            if motion.trajectory.duration <= MAX_DEACTIVATE_BRAKING:
                # Its end, at rest, whatever the sleeps left out: the last command never moves.
                self.stream(motion, motion.trajectory.duration, self.now())
        if motion is not None:
            self.rest = (motion.trajectory, motion.trajectory.duration)
        self.motion = None

    def destroy(self) -> None:
        """Destroy the action server (the lifecycle's cleanup)."""
        self.server.destroy()

    # Time ---------------------------------------------------------------------------------

    def now(self) -> float:
        """Return the node's clock, seconds (ROS time)."""
        return self.node.get_clock().now().nanoseconds * 1e-9

    # The measured state -------------------------------------------------------------------

    def on_joint_states(self, message):
        """
        Keep the latest measured leg positions (actuator coordinates) and velocities.

        One that names none of the legs belongs to another platform: skipped, not counted. A
        malformed one is refused (logged and counted on ``/diagnostics`` as ``invalid_lengths``,
        as fk_node does) and the last measurement stays.
        """
        if not self.node.actuators.concerns(list(message.name)):
            return
        self.joint_state_accounting.receive()
        try:
            lengths, velocities = legs_from_joint_state(message, self.node.actuators)
        except ValueError as error:
            self.joint_state_accounting.reject(Finding(findings.INVALID_LENGTHS, str(error)))
            return
        positions = self.node.actuators.positions(lengths)
        if not np.all(np.isfinite(positions)):
            positions = np.full(6, math.nan)   # a lost measurement breaks the tolerances
        self.measured = (positions, velocities, self.now())
        self.joint_state_accounting.use()

    # Goals --------------------------------------------------------------------------------

    async def execute(self, handle):
        """Run one goal to its end; return its result (the executor awaits the answer)."""
        record = GoalRecord(handle, Future())
        self.accounting.receive()
        try:
            self.start(record)
        except Exception as error:  # noqa: B902 - a bug must answer the goal, not kill it
            self.finish(record, ABORTED, INVALID_GOAL, f'the goal could not be started: '
                        f'{type(error).__name__}: {error}')
        state, code, text = await record.answer
        if state == SUCCEEDED:
            handle.succeed()
        elif state == CANCELED and handle.is_cancel_requested:
            handle.canceled()
        elif handle.is_active:
            handle.abort()
        result = node_action_type().Result()
        result.error_code = int(code)
        result.error_string = text
        return result

    def finish(self, record: GoalRecord, state: str, code: int, text: str,
               finding: Optional[Finding] = None) -> None:
        """Answer a goal once: its state, result code and reason; count it."""
        for name in ('active', 'pending', 'waiting'):
            if getattr(self, name) is record:
                setattr(self, name, None)
        if record.answer.done():
            return
        if state == SUCCEEDED:
            self.accounting.use()
        else:
            self.accounting.reject(finding or Finding(
                findings.INVALID_GOAL if code == INVALID_GOAL else findings.GOAL_PREEMPTED,
                text))
        record.answer.set_result((state, code, text))

    def start(self, record: GoalRecord) -> None:
        """Check a goal; preempt the running one for a valid goal and have it planned."""
        node = self.node
        settings = node.settings.action
        request = goal_request(record.handle.request)
        if isinstance(request, Finding):
            self.finish(record, ABORTED, result_code(request), request.message, request)
            return
        sets = JointSets(node.actuators, tuple(settings.action_cartesian_joints))
        check = check_goal(request, sets, self.now())
        if not check.accepted:
            self.finish(record, ABORTED, result_code(check.refusal), check.reason, check.refusal)
            return
        record.kind, record.names = check.kind, sets.names(check.kind)
        resolution = resolve_tolerances(
            record.names, default_tolerances(check.kind, settings), request.path_tolerance,
            request.goal_tolerance, request.goal_time_tolerance)
        if not resolution.accepted:
            self.finish(record, ABORTED, result_code(resolution.refusal), resolution.reason,
                        resolution.refusal)
            return
        record.tolerances = resolution.tolerances
        record.stamp = request.stamp
        plan_settings = node.planner
        record.space = JointSpace(check.kind, node.geometry, node.actuators,
                                  plan_settings.planner.frames, request.frame_id)
        # A valid goal replaces the goal planned or running: that one brakes to rest.
        for older in (self.pending, self.waiting, self.active):
            if older is not None:
                self.finish(older, ABORTED, INVALID_GOAL, PREEMPTED,
                            Finding(findings.GOAL_PREEMPTED, PREEMPTED))
        self.brake()
        current = self.current_state(record.space)
        self.pending = record
        geometry, actuators = node.geometry, node.actuators
        start_tolerance = settings.action_start_tolerance

        def plan(cancel):
            motion = goal_motion(check, current, geometry, actuators, start_tolerance,
                                 request.frame_id)
            if not motion.accepted:
                return MotionPlan(motion.refusal)
            planner = plan_settings.planner
            if motion.tool_waypoints is not None:
                return planner.plan_trajectory(**motion.tool_waypoints, cancel=cancel)
            return plan_motion(motion.trajectory, planner.geometry, planner.actuator_limits,
                               retime_path=planner.retime, speed_scale=planner.speed_scale,
                               validation_rate=planner.validation_rate, cancel=cancel,
                               publish_rate=planner.publish_rate, actuators=planner.actuators)
        node.worker.submit(PlanningJob(JOB_NAME, plan, node.leg_trajectory_publisher.prepare,
                                       record))

    def current_state(self, space: JointSpace):
        """Where the next goal starts, in its joints: the rest of the last motion, or measured."""
        if self.motion is not None:
            trajectory = self.motion.trajectory
            return space.desired(trajectory, trajectory.duration).positions
        if self.rest is not None:
            return space.desired(*self.rest).positions
        if self.measured is None:
            return None
        actual = space.actual(self.measured[0])
        return None if actual is None else actual.positions

    def on_planned(self, answer) -> None:
        """Run a goal's plan (executor thread), or abort the goal with its refusal."""
        record = answer.job.context
        if record is not self.pending:
            return                       # preempted or cancelled meanwhile
        if not answer.accepted:
            self.finish(record, ABORTED, result_code(answer.refusal),
                        f'{answer.refusal.code}: {answer.reason}', answer.refusal)
            return
        self.pending = None
        record.plan, record.prepared = answer.plan, answer.prepared
        self.waiting = record
        self.tick()

    def begin(self, record: GoalRecord, now: float) -> None:
        """Start a planned goal now (or at its header stamp, if later)."""
        self.waiting = None
        start = max(now, record.stamp)
        trajectory = record.plan.trajectory
        record.start = start
        record.monitor = ToleranceMonitor(record.names, record.tolerances, trajectory.duration)
        self.active = record
        self.rest = None
        self.motion = Motion(trajectory, start, record=record, gate=self.stream_gate())
        self.node.get_logger().info(
            f'{ACTION_NAME}: {record.kind} goal of {trajectory.duration:.3f} s started '
            f'({self.node.settings.action.action_execution})')
        if self.node.settings.action.action_execution == 'leg_trajectory':
            prepared = record.prepared
            prepared.message.header = Header(stamp=_stamp(start),
                                             frame_id=self.node.planner.base_frame)
            send_command(self.node.leg_trajectory_publisher, self.accounting, prepared)

    def stream_gate(self):
        """Return a command gate for a streamed motion, from the last command, or ``None``."""
        if self.node.settings.action.action_execution != 'stream':
            return None
        previous = self.motion.gate if self.motion is not None else None
        if previous is not None:
            return previous
        gate = CommandGate(self.node.geometry, self.node.actuator_limits)
        return gate

    def brake(self) -> None:
        """Bring the motion under way to rest on its path (within the leg limits)."""
        motion = self.motion
        if motion is None:
            return
        now = self.now()
        elapsed = now - motion.start
        braking = braking_trajectory(motion.trajectory, elapsed, self.node.geometry,
                                     self.node.actuator_limits)
        if braking is None:
            self.rest = (motion.trajectory, min(max(elapsed, 0.0), motion.trajectory.duration))
            self.motion = None
            return
        self.motion = Motion(braking, now, braking=True, gate=motion.gate)
        if self.node.settings.action.action_execution == 'leg_trajectory':
            command = gated_leg_trajectory(braking, self.node.geometry,
                                           self.node.actuator_limits,
                                           self.node.planner.publish_rate,
                                           self.node.actuators)
            if not command.accepted:
                self.node.get_logger().error(f'{ACTION_NAME}: the braking trajectory is not '
                                             f'sent: {command.reason}')
                return
            prepared = self.node.leg_trajectory_publisher.prepare(command)
            prepared.message.header = Header(stamp=_stamp(now),
                                             frame_id=self.node.planner.base_frame)
            self.node.leg_trajectory_publisher.publish(prepared)

    def on_cancel(self, handle):
        """Cancel a goal planned or running: it brakes to rest; a finished one is refused."""
        for record in (self.active, self.waiting, self.pending):
            if record is not None and record.handle is handle:
                if record is self.active:
                    self.brake()
                self.finish(record, CANCELED, SUCCESSFUL,
                            'Goal canceled: the platform brakes to rest on its path',
                            Finding(findings.GOAL_PREEMPTED, 'canceled'))
                return CancelResponse.ACCEPT
        return CancelResponse.REJECT

    def preempt_by_topic(self, topic: str) -> None:
        """Abort the goals: a trajectory on ``pose_trajectory`` or ``pose_path`` replaces them."""
        for record in (self.pending, self.waiting, self.active):
            if record is not None:
                self.finish(record, ABORTED, INVALID_GOAL, f'{PREEMPTED} ({topic})',
                            Finding(findings.GOAL_PREEMPTED, PREEMPTED))
        self.motion, self.rest = None, None

    # The tick: commands, checks, feedback -------------------------------------------------

    def tick(self) -> None:
        """Stream the motion, check the running goal and send its feedback."""
        now = self.now()
        motion = self.motion
        if motion is not None:
            elapsed = now - motion.start
            if motion.gate is not None and elapsed >= 0.0:
                self.stream(motion, elapsed, now)
            if elapsed >= motion.trajectory.duration and (
                    motion.braking or motion.record is not self.active):
                self.rest = (motion.trajectory, motion.trajectory.duration)
                self.motion = None
        if self.motion is None and self.waiting is not None:
            self.begin(self.waiting, now)
        record = self.active
        if record is None:
            return
        self.check(record, now)

    def stream(self, motion: Motion, elapsed: float, now: float) -> None:
        """Send the motion's leg command of this tick on joint_commands, as the gate passes it."""
        if elapsed > motion.trajectory.duration + 1.0 / self.node.settings.ramp.publish_rate:
            return
        legs = motion.trajectory.legs(self.node.geometry, [min(elapsed,
                                                               motion.trajectory.duration)])
        command = motion.gate.legs(legs.lengths[0], now, legs.velocities[0])
        if not command.accepted:
            command = motion.gate.brake(now, command.refusal)
        send_command(self.commands_publisher, self.accounting, command, Header(stamp=_stamp(now)))

    def check(self, record: GoalRecord, now: float) -> None:
        """Check the goal's tolerances against the latest joint_states; send its feedback."""
        elapsed = now - record.start
        if elapsed < 0.0:
            return                      # waiting for its header stamp
        trajectory = record.plan.trajectory
        desired = record.space.desired(trajectory, elapsed)
        actual = error = None
        if self.measured is not None:
            actual = record.space.actual(self.measured[0], self.measured[1])
            if actual is None:          # no pose has the measured legs: a lost measurement
                actual = JointState(np.full(6, math.nan))
            error = record.space.error(desired, actual)
        measured_after_end = (self.measured is not None
                              and self.measured[2] >= record.start + trajectory.duration)
        outcome = record.monitor.update(
            elapsed, None if error is None else error.positions,
            None if error is None else error.velocities, measured_after_end)
        settings = self.node.settings.action
        if now >= record.next_feedback:
            record.next_feedback = now + 1.0 / settings.action_feedback_rate
            record.handle.publish_feedback(feedback_message(
                record.names, now, elapsed, desired, actual, error))
        if outcome is None:
            return
        if outcome.succeeded:
            self.finish(record, SUCCEEDED, SUCCESSFUL, outcome.error_string)
        else:
            self.brake()
            self.finish(record, ABORTED, outcome.error_code, outcome.error_string,
                        outcome.finding)
        self.node.get_logger().info(f'{ACTION_NAME}: {outcome.error_string}')


def node_action_type():
    """Return control_msgs/action/FollowJointTrajectory (imported on first use)."""
    from control_msgs.action import FollowJointTrajectory
    return FollowJointTrajectory


def _stamp(seconds_value: float):
    """Return the builtin_interfaces/msg/Time of node seconds."""
    from builtin_interfaces.msg import Time
    nanoseconds = int(round(seconds_value * 1e9))
    return Time(sec=nanoseconds // 1_000_000_000, nanosec=nanoseconds % 1_000_000_000)


def default_tolerances(kind: str, settings) -> SegmentTolerances:
    """Return the default tolerances of a joint set, from the action's parameters."""
    if kind == LEGS:
        path = StateTolerances.uniform(6, settings.action_leg_path_tolerance)
        goal = StateTolerances.uniform(6, settings.action_leg_goal_tolerance,
                                       settings.action_stopped_velocity_tolerance)
    else:
        path = StateTolerances(
            np.repeat([settings.action_position_path_tolerance,
                       settings.action_orientation_path_tolerance], 3), np.zeros(6), np.zeros(6))
        goal = StateTolerances(
            np.repeat([settings.action_position_goal_tolerance,
                       settings.action_orientation_goal_tolerance], 3), np.zeros(6), np.zeros(6))
    return SegmentTolerances(path, goal, settings.action_goal_time_tolerance)


def goal_request(goal):
    """
    Return the :class:`GoalRequest` of a FollowJointTrajectory goal, or the Finding refusing it.

    Only counts and conversions: every value is judged by :func:`check_goal`.
    """
    trajectory = goal.trajectory
    points = trajectory.points
    if len(points) > MAX_WAYPOINTS:
        return Finding(findings.INVALID_GOAL, f'the trajectory has {len(points):,} points; at '
                       f'most {MAX_WAYPOINTS:,}')
    stamp = trajectory.header.stamp

    def tolerances(entries):
        return tuple(JointToleranceValues(entry.name, entry.position, entry.velocity,
                                          entry.acceleration) for entry in entries)
    multi = goal.multi_dof_trajectory
    try:   # a malformed time (nanosec not below 1e9) would move the goal by whole seconds
        times = tuple(seconds(point.time_from_start, f"point {index}'s time_from_start")
                      for index, point in enumerate(points))
        start = stamp_nanoseconds(stamp, 'trajectory.header.stamp') * 1e-9
        time_tolerance = seconds(goal.goal_time_tolerance, 'goal_time_tolerance')
    except ValueError as error:
        return Finding(findings.INVALID_GOAL, str(error))
    return GoalRequest(
        tuple(trajectory.joint_names), times,
        tuple(point.positions for point in points),
        tuple(point.velocities for point in points),
        tuple(point.accelerations for point in points),
        tuple(point.effort for point in points), trajectory.header.frame_id,
        start, tolerances(goal.path_tolerance),
        tolerances(goal.goal_tolerance), time_tolerance,
        len(multi.points), len(multi.joint_names))


def feedback_message(names, now, elapsed, desired, actual, error):
    """Return the FollowJointTrajectory feedback: desired, actual and error."""
    feedback = node_action_type().Feedback()
    feedback.header.stamp = _stamp(now)
    feedback.joint_names = list(names)
    for point, state in ((feedback.desired, desired), (feedback.actual, actual),
                         (feedback.error, error)):
        if state is None:
            continue
        point.positions = np.asarray(state.positions, dtype=float).tolist()
        if state.velocities is not None:
            point.velocities = np.asarray(state.velocities, dtype=float).tolist()
        point.time_from_start = _duration(max(elapsed, 0.0))
    return feedback


def _duration(value: float):
    """Return the builtin_interfaces/msg/Duration of seconds."""
    from builtin_interfaces.msg import Duration
    nanoseconds = int(round(value * 1e9))
    return Duration(sec=nanoseconds // 1_000_000_000, nanosec=nanoseconds % 1_000_000_000)
