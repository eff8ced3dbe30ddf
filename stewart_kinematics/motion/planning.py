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
Motion planning: decide whether, and how, to play a platform trajectory.

:func:`plan_motion` checks a trajectory whole (:mod:`~stewart_kinematics.motion.
trajectory_check`), retimes it if asked (:mod:`~stewart_kinematics.motion.retiming`), and
returns a :class:`MotionPlan` that says whether it is accepted and, if not, why.
:class:`MotionPlanner` does the same from what a message carries (waypoints of the tool frame,
in the base or user frame, with or without timing): what trajectory_node calls, and what a
Python user's own loop can call.

Units: metres, radians, seconds. Nothing here imports ROS.
"""

import dataclasses
from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.findings import Decision, Finding, violation_details
from stewart_kinematics.limits import CommandGate, TrajectoryCommand
from stewart_kinematics.limits.base import Bound, LEG
from stewart_kinematics.model.actuators import ActuatorInterface, ActuatorLimits
from stewart_kinematics.model.arrays import as_float_array
from stewart_kinematics.model.frames import FrameTree
from stewart_kinematics.model.rotations import quaternion_to_matrix
from stewart_kinematics.motion.leg_trajectory import sampled_leg_trajectory
from stewart_kinematics.motion.pose_trajectory import (
    PoseTrajectory,
    SingularPathError,
    TimedTrajectory,
)
from stewart_kinematics.motion.retiming import retime, RetimingError
from stewart_kinematics.motion.trajectory_check import (
    check_trajectory,
    DEFAULT_VALIDATION_RATE,
    SPEED_LIMITS,
    TrajectoryCheck,
)
from stewart_kinematics.motion.trajectory_forces import force_limits

#: A retimed trajectory that exceeds a leg limit between toppra's gridpoints is stretched by
#: its excess times this (the samples then fall elsewhere: up to MAX_STRETCHES times).
STRETCH_MARGIN = 1.001
MAX_STRETCHES = 5


@dataclass(frozen=True)
class MotionPlan(Decision):
    """
    What :func:`plan_motion` decided.

    :param refusal: ``None`` when the trajectory may be played, else why not (a
        :class:`~stewart_kinematics.findings.Finding`: ``invalid_trajectory``,
        ``out_of_limits``, ``too_fast``, ``retiming_failed``, ``trajectory_too_long``).
    :param trajectory: the timed trajectory to play, or ``None`` when refused.
    :param check: the whole-trajectory check of the timing played (or refused), if made.
    :param retimed: True when the timing comes from :func:`retime`.
    :param warnings: findings about an accepted trajectory (none yet).
    :param command: with a ``publish_rate``, the command gate's verdict on the leg trajectory
        to send (every point as published, and the controller's interpolation between two);
        ``None`` otherwise.

    ``accepted`` and ``reason`` come from :class:`~stewart_kinematics.findings.Decision`.
    """

    refusal: Optional[Finding]
    trajectory: Optional[TimedTrajectory] = None
    check: Optional[TrajectoryCheck] = None
    retimed: bool = False
    warnings: Tuple[Finding, ...] = ()
    command: Optional[TrajectoryCommand] = None


def plan_motion(path: PoseTrajectory, geometry, actuator_limits: Optional[ActuatorLimits] = None,
                *, retime_path: bool = False, speed_scale: float = 1.0,
                validation_rate: float = DEFAULT_VALIDATION_RATE, cancel=None,
                publish_rate: Optional[float] = None,
                actuators: Optional[ActuatorInterface] = None) -> MotionPlan:
    """
    Decide whether, and how, to play a platform trajectory: checked whole, timed, or refused.

    Without ``retime_path`` the trajectory keeps its own timing, slowed by ``1 /
    speed_scale``, and is refused if any sample breaks a limit, leg velocity and acceleration
    included, and with masses its dynamic leg forces (see :func:`check_trajectory`). With it,
    the path through its waypoint poses is retimed (:func:`retime`: its own times, velocities
    and accelerations are dropped, repeated waypoints merged) and the result
    checked whole (:func:`retime` keeps every leg within its limits at the check's samples;
    should a sample still exceed a leg limit or a dynamic force limit, the timing is stretched
    uniformly by what brings it within (``check.stretch``) times :data:`STRETCH_MARGIN`, and
    checked again).

    :param path: the trajectory; a path without timing comes from :meth:`PoseTrajectory.path`
        and must be retimed.
    :param actuator_limits: leg velocity, acceleration (and jerk, unused here); ``None``: none.
    :param speed_scale: in (0, 1].
    :param validation_rate: samples per second of the check, hertz (see
        :func:`check_trajectory` for its bounds).
    :param cancel: ``None``, or an event: set, the work stops with
        :class:`~stewart_kinematics.motion.retiming.Cancelled` (raised, not a refusal).
    :param publish_rate: points per second of the leg trajectory to send (see
        :func:`~stewart_kinematics.motion.leg_trajectory.leg_trajectory`), or ``None``: none is
        made. With one, every point sent is checked as sent by the command gate, whatever the
        validation rate (:meth:`~stewart_kinematics.limits.CommandGate.trajectory`), and a
        point the check's samples did not see that breaks a limit refuses the trajectory (a
        retimed one that is only too fast there is stretched, as for the check).
    :param actuators: joint names and offsets of the leg trajectory (default: leg_1..leg_6,
        no offsets).
    """
    actuator_limits = actuator_limits or ActuatorLimits()
    output = None if publish_rate is None else (
        publish_rate, actuators if actuators is not None else ActuatorInterface())
    if not retime_path:
        trajectory = TimedTrajectory.as_given(path, speed_scale)
        check = check_trajectory(trajectory, geometry, actuator_limits,
                                 validation_rate=validation_rate, cancel=cancel)
        refusal, command = _check_refusal(check), None
        if refusal is None and output is not None:
            command = _gate(trajectory, geometry, actuator_limits, output)
            refusal = command.refusal
        return MotionPlan(refusal, trajectory if refusal is None else None, check,
                          command=command)
    try:
        trajectory = retime(path, geometry, actuator_limits, speed_scale,
                            sample_rate=validation_rate, cancel=cancel)
    except SingularPathError as error:
        return MotionPlan(Finding(findings.RETIMING_FAILED, str(error), (
            ('cause', 'singularity'), ('segment', f'points {error.point} and after'))),
            retimed=True)
    except RetimingError as error:
        return MotionPlan(Finding(findings.RETIMING_FAILED, str(error), error.details),
                          retimed=True)
    except ValueError as error:
        return MotionPlan(Finding(findings.INVALID_TRAJECTORY, str(error)), retimed=True)
    scaled = actuator_limits.scaled(speed_scale)
    for _ in range(MAX_STRETCHES):
        check = check_trajectory(trajectory, geometry, scaled, validation_rate=validation_rate,
                                 cancel=cancel)
        refusal, stretch, command = _check_refusal(check), check.stretch, None
        if refusal is None and output is not None:
            command = _gate(trajectory, geometry, scaled, output)
            refusal, stretch = command.refusal, _gate_stretch(command.violations)
        if refusal is None or stretch is None:
            break
        # toppra's timing exceeds a leg limit (speed, or dynamic force) between the samples of
        # the check, or at a point sent: stretch on.
        trajectory = trajectory.stretched(stretch * STRETCH_MARGIN)
    return MotionPlan(refusal, trajectory if refusal is None else None, check, True,
                      command=command)


def gated_leg_trajectory(trajectory: TimedTrajectory, geometry, actuator_limits: ActuatorLimits,
                         publish_rate: float, actuators: ActuatorInterface) -> TrajectoryCommand:
    """
    Return the command gate's verdict on a timed trajectory sent as a leg trajectory.

    What :func:`plan_motion` checks before an accepted plan is sent, for a trajectory timed
    elsewhere (a braking, :mod:`~stewart_kinematics.motion.path_braking`).

    :param publish_rate: points per second, hertz.
    """
    return _gate(trajectory, geometry, actuator_limits, (publish_rate, actuators))


def _gate(trajectory, geometry, actuator_limits, output) -> TrajectoryCommand:
    """
    Return the command gate's verdict on the leg trajectory a timed trajectory is sent as.

    With masses, the efforts the points carry (their dynamic leg forces) are checked too: not
    finite (a singular pose), or beyond ``leg_force_min`` / ``leg_force_max``, refuses it.
    """
    rate, actuators = output
    points, poses = sampled_leg_trajectory(trajectory, geometry, actuators, rate)
    gate = CommandGate(geometry, ActuatorLimits(actuator_limits.velocity_max,
                                                actuator_limits.acceleration_max))
    command = gate.trajectory(points, poses.positions, poses.rotations)
    if command.accepted:
        command = _effort_verdict(command, geometry)
    if command.accepted:
        return command
    # Every sample of the check kept the limits: the point sent lies between two of them.
    refusal = command.refusal
    return dataclasses.replace(command, refusal=dataclasses.replace(
        refusal, message=refusal.message + ' (between the samples of the check: raise '
        'validation_rate, or publish more points)'))


def _effort_verdict(command: TrajectoryCommand, geometry) -> TrajectoryCommand:
    """Refuse a gated leg trajectory whose efforts are not finite or break a force limit."""
    points = command.trajectory
    if points.efforts is None:
        return command
    efforts = points.efforts
    limits = force_limits(geometry)
    low, high = limits if limits is not None else (-math.inf, math.inf)
    bounds = (Bound('leg_force_max', high, True, LEG, 'N'),
              Bound('leg_force_min', low, False, LEG, 'N'))
    bad = ~np.all(np.isfinite(efforts), axis=-1)
    for bound in bounds:
        if math.isfinite(bound.allowed):
            bad |= np.any(bound.broken(efforts), axis=-1)
    if not bad.any():
        return command
    first = int(np.argmax(bad))
    violations = tuple(bound.violation(int(leg), float(efforts[first, leg]))
                       for bound in bounds if math.isfinite(bound.allowed)
                       for leg in np.flatnonzero(bound.broken(efforts[first])))
    reason = '; '.join(map(str, violations)) or (
        'no leg forces hold the platform there (a singular pose)')
    return TrajectoryCommand(None, Finding(
        findings.OUT_OF_LIMITS,
        f'published point {first} (t = {points.times[first]:.4f} s) of leg_trajectory: '
        f'effort {reason}', (('point', str(first)), ('time_s', f'{points.times[first]:.4f}'))
        + violation_details(violations)), violations=violations, point=first)


def _gate_stretch(violations) -> Optional[float]:
    """Return the stretch that brings leg speed violations within, ``None`` for others."""
    if not violations or not all(violation.limit in SPEED_LIMITS for violation in violations):
        return None
    return max(_speed_excess(violation) for violation in violations)


def _speed_excess(violation) -> float:
    """Return the stretch that brings one leg speed violation within its limit."""
    ratio = abs(violation.value) / violation.allowed
    return math.sqrt(ratio) if violation.limit == 'leg_acceleration_max' else ratio


def _check_refusal(check: TrajectoryCheck) -> Optional[Finding]:
    """
    Return the refusal of a failed check, or ``None``.

    :data:`TOO_FAST` when only leg velocity, acceleration or dynamic leg forces are broken (a
    slower timing would keep them: ``check.stretch``), :data:`OUT_OF_LIMITS` otherwise,
    :data:`TRAJECTORY_TOO_LONG` when the check was not made; the details give the time, the
    waypoints around it and every violated limit.
    """
    if check.accepted:
        return None
    if not check.complete:
        return Finding(findings.TRAJECTORY_TOO_LONG, check.reason)
    code = findings.TOO_FAST if check.stretch is not None else findings.OUT_OF_LIMITS
    return Finding(code, check.reason, (
        ('time_s', f'{check.time:.4f}'),
        ('segment', f'points {check.segment[0]} and {check.segment[1]}'),
    ) + violation_details(check.violations))


class MotionPlanner:
    """
    Plan the trajectories a message carries: tool-frame waypoints in, a decided plan out.

    The waypoints are poses of the tool frame (:mod:`stewart_kinematics.model.frames`; by
    default the platform frame itself) in the base frame or the user frame, as every pose
    topic; with their twists (about the tool frame's origin, in the same frame) and
    accelerations when given. They are moved to the platform frame in the base frame
    (:meth:`FrameTree.platform_motion`), interpolated and checked there, and planned by
    :func:`plan_motion`. Immutable: a node builds a new planner when a parameter changes, so a
    trajectory is planned with one set of settings from start to end.

    :param geometry: the platform.
    :param actuator_limits: the legs' velocity and acceleration limits.
    :param frames: the frame tree (tool and user frames).
    :param retime: retime timed trajectories too (paths always are).
    :param speed_scale: in (0, 1].
    :param validation_rate: hertz, see :func:`check_trajectory`.
    :param publish_rate: points per second of the leg trajectory an accepted plan is sent as
        (checked point by point by the command gate; see :func:`plan_motion`), or ``None``.
    :param actuators: joint names and offsets of that leg trajectory.
    """

    def __init__(self, geometry, actuator_limits: ActuatorLimits, frames: FrameTree = None, *,
                 retime: bool = False, speed_scale: float = 1.0,
                 validation_rate: float = DEFAULT_VALIDATION_RATE,
                 publish_rate: Optional[float] = None,
                 actuators: Optional[ActuatorInterface] = None):
        self.geometry = geometry
        self.actuator_limits = actuator_limits
        self.frames = frames if frames is not None else FrameTree()
        self.retime = retime
        self.speed_scale = speed_scale
        self.validation_rate = validation_rate
        self.publish_rate = publish_rate
        self.actuators = actuators

    def plan_trajectory(self, times, positions, quaternions, velocities=None,
                        angular_velocities=None, accelerations=None, angular_accelerations=None,
                        frame_id: str = '', cancel=None) -> MotionPlan:
        """
        Plan timed waypoints of the tool frame: as timed, or retimed with ``retime``.

        :param times: seconds from the start, shape (N,); ``positions`` (N, 3), metres;
            ``quaternions`` (N, 4), ``(x, y, z, w)``; optional twists and accelerations
            (N, 3) each, m/s, rad/s, m/s^2, rad/s^2, about the tool frame's origin, all in
            ``frame_id`` (the base frame, the user frame, or ``''`` for the base frame).
        :returns: a :class:`MotionPlan`, refused with ``invalid_trajectory`` (and the reason)
            when the waypoints cannot make a trajectory.
        """
        try:
            motion = self.frames.platform_motion(
                positions, quaternion_to_matrix(_rows('quaternions', quaternions, 4)),
                velocities, angular_velocities, accelerations, angular_accelerations, frame_id)
            trajectory = PoseTrajectory(times, *motion)
        except ValueError as error:
            return MotionPlan(Finding(findings.INVALID_TRAJECTORY, str(error)))
        return plan_motion(trajectory, self.geometry, self.actuator_limits,
                           retime_path=self.retime, speed_scale=self.speed_scale,
                           validation_rate=self.validation_rate, cancel=cancel,
                           publish_rate=self.publish_rate, actuators=self.actuators)

    def plan_path(self, positions, quaternions, frame_id: str = '', cancel=None) -> MotionPlan:
        """
        Plan waypoints of the tool frame without timing: always retimed.

        :param positions: metres, shape (N, 3); ``quaternions`` (N, 4), in ``frame_id``.
        :returns: a :class:`MotionPlan` (see :meth:`plan_trajectory`).
        """
        try:
            motion = self.frames.platform_motion(
                positions, quaternion_to_matrix(_rows('quaternions', quaternions, 4)),
                frame_id=frame_id)
            path = PoseTrajectory.path(self.geometry, motion[0], motion[1])
        except SingularPathError as error:
            return MotionPlan(Finding(findings.RETIMING_FAILED, str(error), (
                ('cause', 'singularity'), ('segment', f'points {error.point} and after'))),
                retimed=True)
        except ValueError as error:
            return MotionPlan(Finding(findings.INVALID_TRAJECTORY, str(error)), retimed=True)
        return plan_motion(path, self.geometry, self.actuator_limits, retime_path=True,
                           speed_scale=self.speed_scale,
                           validation_rate=self.validation_rate, cancel=cancel,
                           publish_rate=self.publish_rate, actuators=self.actuators)


def _rows(name, values, width):
    """Convert to a float array of shape (N, width), saying what is wrong otherwise."""
    array = np.array(as_float_array(values, name))
    if array.size == 0:
        return array.reshape(0, width)
    if array.ndim != 2 or array.shape[1] != width:
        raise ValueError(f'{name} must have shape (N, {width}), got {array.shape}')
    return array
