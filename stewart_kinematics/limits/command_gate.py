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
The command gate: every command to the actuators, checked exactly as it is sent.

A :class:`CommandGate` stands between the core's answers and the actuators. Whatever decided a
command (:class:`~stewart_kinematics.CommandCheck`, the streaming filter, the cue follower, a
trajectory's planner), the command leaves a node only as the gate's verdict on it: a
:class:`LegCommand` (leg lengths of a pose, or a step of a stream), a
:class:`LegVelocityCommand` (leg velocities) or a :class:`TrajectoryCommand` (every point of a
leg trajectory). The ROS side's command publishers take nothing else
(:class:`stewart_kinematics.ros.command_publishing.CommandPublisher`), and the message is built
from the numbers the gate checked. The limits are the limits model's
(:class:`~stewart_kinematics.limits.LimitModel`): stroke, joint cones, singularity margin, leg
collisions, and the leg rates.

Two kinds of command stream (``timing``):

- :data:`SETPOINT`: each command is a position the drive goes to under its own motion profile
  (ik_node's ``leg_lengths`` and ``joint_commands`` without ``command_rate``, the ramp's
  rows). Its pose limits are checked; the rates between two setpoints are the drive's.
- :data:`MOTION`: each command is a sample of a motion, sent at its time (the node's clock,
  wall or simulated, never an input's stamps): streamed steps, cue poses, a played
  trajectory. Its pose limits are checked, and the leg rates between consecutive commands:
  with ``h_k`` the time since the previous command, the leg velocity ``w_k = (l_k - l_k-1) /
  h_k``, the acceleration ``a_k = (w_k - w_k-1) / ((h_k + h_k-1) / 2)`` and (with ``jerk``) the
  jerk ``j_k = (a_k - a_k-1) / ((h_k + h_k-1 + h_k-2) / 3)``. These are the divided
  differences of the commanded lengths: for a uniform stream the finite differences that
  ros2_control's joint limiters use, and for any timing the derivative that every smooth
  motion through the commands reaches somewhere between them (the mean value theorem of
  divided differences). So a motion within the limits, sampled at whatever times, passes;
  a stream that asks more of a leg than its limit somewhere is refused. After a refusal of a
  motion's command (or a request to stop), the gate gives :meth:`CommandGate.brake`: each leg
  decelerates at ``leg_acceleration_max`` (never one step to rest), with a refusal-class
  ``command_braking`` finding when the command it replaces was refused.

Leg forces (when the geometry carries masses, :attr:`stewart_kinematics.Geometry.
mass_properties`): every accepted :class:`LegCommand` carries ``forces``, the actuators' forces
of the exact pose it puts the platform at (:func:`stewart_kinematics.leg_forces`). A setpoint's
are static (the drive brings the platform to rest there). A motion's are dynamic: the pose with
the twist and acceleration of the divided differences of the poses sent at their send times,
``V_k = [(p_k - p_k-1) / h_k, log(R_k R_k-1^T) / h_k]`` (``log`` the rotation vector, base
frame) and ``A_k = (V_k - V_k-1) / ((h_k + h_k-1) / 2)`` (``V_k-1 = 0`` and the span ``h_k``
after rest), the same spans as the leg rates; a motion's command whose forces leave
``leg_force_min..leg_force_max`` is refused (``too_fast``, naming the limit and the legs), and
its braking command brakes more gently when braking at the acceleration limit would break
them. With every mass 0 no force is computed and ``forces`` is ``None``.

Units: metres, radians, seconds. Nothing here imports ROS.
"""

import dataclasses
from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.dynamics.inverse_dynamics import leg_forces, masses_of
from stewart_kinematics.findings import Decision, Finding
from stewart_kinematics.limits.leg_rates import RATE_SLACK
from stewart_kinematics.limits.limit_model import LimitModel
from stewart_kinematics.limits.settings import limits_of
from stewart_kinematics.limits.violation import Violation
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.arrays import seconds_text
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.frames import Transform
from stewart_kinematics.model.inverse import leg_vectors
from stewart_kinematics.model.rotations import (
    euler_zyx_to_matrix,
    euler_zyx_to_quaternion,
    matrix_to_euler_zyx,
    matrix_to_quaternion,
    matrix_to_rotation_vector,
    normalize_quaternion,
    quaternion_to_matrix,
)

#: The kinds of command stream: positions a drive goes to, or samples of a motion.
SETPOINT, MOTION = 'setpoint', 'motion'
TIMINGS = (SETPOINT, MOTION)
#: Unit roundoff of a float.
_EPSILON = np.finfo(float).eps
#: A divided difference of the k-th order is computed from lengths rounded to a unit in the
#: last place: its rounding is at most about 2^k eps max|l| / h^k; this many times that is
#: forgiven (the rest is motion).
_ROUNDING_FACTOR = 8.0
#: Forward kinematics of a streamed step: the pose it puts the platform at, to 1e-12 m.
_SOLVE_TOLERANCE = 1e-12
_SOLVE_ITERATIONS = 20
#: The controller's quintic between two points of a leg trajectory is checked at this many
#: times in between (joint_trajectory_controller interpolates positions, velocities and
#: accelerations with quintic splines), against the stroke, to this many metres of rounding.
INTERPOLATION_SAMPLES = 16
INTERPOLATION_ROUNDING = 1e-12
#: Braking decelerates at this share of leg_acceleration_max: the rest absorbs the rounding of
#: the pose a braking command is sent as (found by forward kinematics to 1e-12 m).
BRAKING_SHARE = 0.999
#: With masses and a force limit, a braking command whose forces would break it brakes at the
#: next of these shares of ``leg_acceleration_max`` instead (0: the legs keep their speed).
BRAKING_SHARES = (BRAKING_SHARE, 0.5, 0.25, 0.125, 0.0625, 0.0)
#: The lengths a trajectory's point carries match those of its pose to this, metres (the
#: rounding of ``length - offset + offset``).
LENGTH_MATCH = 1e-9


@dataclass(frozen=True, eq=False)
class Verdict(Decision):
    """The gate's answer on a command: the only thing a command publisher sends (a base class)."""


@dataclass(frozen=True, eq=False)
class LegCommand(Verdict):
    """
    The gate's verdict on leg lengths to command: what to send, or why not.

    :param lengths: leg lengths l_1..l_6 to send, metres, shape (6,), finite and positive;
        ``None`` when refused.
    :param violations: every limit the command breaks (:class:`~stewart_kinematics.limits.
        Violation`), also for a refused one, so that a display can show which legs are at
        fault; empty when it could not be evaluated at all.
    :param refusal: why it was refused, or ``None`` when it may be sent.
    :param warnings: findings about an accepted command (a quaternion that was not unit, a
        braking command and why).
    :param position: the platform frame's origin in the base frame, metres, shape (3,), where
        the command puts it; ``None`` when not known.
    :param rotation: the platform-to-base rotation there, shape (3, 3), or ``None``.
    :param velocities: the leg velocities sent with it, m/s, shape (6,), or ``None``.
    :param accelerations: the leg accelerations sent with it, m/s^2, shape (6,), or ``None``.
    :param time: when it is sent (a motion's command), seconds, or ``None``.
    :param braking: True for the gate's braking command (:meth:`CommandGate.brake`).
    :param tool_pose: for a pose message, ``(position (3,), quaternion (4,) (x, y, z, w))``
        of the tool frame as the message carries them, or ``None``.
    :param forces: the leg forces of the command, newtons, shape (6,), positive pushing: of
        its pose at rest (a setpoint) or with the motion's twist and acceleration (a motion's
        command); ``None`` when every mass is 0 (no forces known) or refused.
    """

    lengths: Optional[np.ndarray]
    violations: Tuple[Violation, ...] = ()
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()
    position: Optional[np.ndarray] = None
    rotation: Optional[np.ndarray] = None
    velocities: Optional[np.ndarray] = None
    accelerations: Optional[np.ndarray] = None
    time: Optional[float] = None
    braking: bool = False
    tool_pose: Optional[Tuple[np.ndarray, np.ndarray]] = None
    forces: Optional[np.ndarray] = None

    @property
    def legs_at_fault(self) -> Tuple[Optional[int], ...]:
        """Return the legs that break a limit (``None`` for the whole platform), each once."""
        return tuple(dict.fromkeys(leg for violation in self.violations
                                   for leg in violation.legs))

    @property
    def pose(self) -> Optional[np.ndarray]:
        """Return ``[X, Y, Z, alpha, beta, gamma]`` of the platform, or ``None`` if not known."""
        if self.position is None:
            return None
        return np.concatenate([self.position, matrix_to_euler_zyx(self.rotation)])


@dataclass(frozen=True, eq=False)
class LegVelocityCommand(Verdict):
    """
    The gate's verdict on leg velocities to command (a platform twist): what to send, or why not.

    :param velocities: rates of change of the leg lengths, metres per second, shape (6,),
        within ``leg_velocity_max``; ``None`` when refused.
    :param refusal: why they were refused, or ``None`` when accepted.
    :param warnings: a ``twist_scaled`` finding when the twist was scaled down to the limit.
    :param scale: the factor the twist was scaled by, in (0, 1]; 1.0 when it was not.
    """

    velocities: Optional[np.ndarray]
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()
    scale: float = 1.0


@dataclass(frozen=True, eq=False)
class TrajectoryCommand(Verdict):
    """
    The gate's verdict on a leg trajectory: every point, as a JointTrajectory carries it.

    :param trajectory: the :class:`~stewart_kinematics.motion.leg_trajectory.LegTrajectory`
        to send, or ``None`` when refused.
    :param refusal: why not (the first point, or the first piece of the interpolation between
        two points, that breaks a limit), or ``None``.
    :param warnings: findings about an accepted trajectory (none yet).
    :param violations: every limit the first failing point breaks.
    :param point: the index of that point, or ``None``.
    """

    trajectory: Optional[object]
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()
    violations: Tuple[Violation, ...] = ()
    point: Optional[int] = None


def platform_of_tool_message(position, quaternion, frames=None, frame_id: str = ''):
    """
    Return the platform pose a pose message puts the platform at, as ik_node computes it.

    The quaternion is normalised and turned into a matrix; the tool frame's pose, in
    ``frame_id``, is moved to the platform frame's in the base frame.

    :param position: the tool frame's origin, metres, three finite numbers.
    :param quaternion: its orientation ``(x, y, z, w)``, four numbers, not zero.
    :param frames: a :class:`stewart_kinematics.FrameTree`, or ``None`` (the platform frame,
        in the base frame).
    :returns: ``(position (3,), rotation (3, 3))`` of the platform frame in the base frame.
    :raises ValueError: for a zero or non-finite quaternion, or a frame the tree refuses.
    """
    return platform_of_unit_quaternion(position, normalize_quaternion(quaternion), frames,
                                       frame_id)


def platform_of_unit_quaternion(position, unit, frames=None, frame_id: str = ''):
    """
    :func:`platform_of_tool_message` of a quaternion that the caller has checked and normalised.

    For a decision that checked a message's numbers where they entered
    (:meth:`stewart_kinematics.CommandCheck.tool_pose`): the same conversion, and the same
    arithmetic, without checking the quaternion a second time.

    :param unit: ``normalize_quaternion`` of the message's quaternion, shape (4,).
    """
    rotation = quaternion_to_matrix(unit)
    if frames is None:
        return position, rotation
    return frames.platform_in_base(position, rotation, frame_id)


class CommandGate:
    """
    The last check of every command to the actuators: as sent, against every limit.

    One gate per command stream (a publisher of commands). A :data:`MOTION` gate keeps the
    last command it passed (its time, lengths and their divided differences) and the pose it
    put the platform at.

    :param geometry: the platform and its limits (:class:`stewart_kinematics.Geometry`).
    :param actuator_limits: the legs' velocity, acceleration and jerk limits (``None``: none).
    :param timing: :data:`SETPOINT` or :data:`MOTION`.
    :param jerk: whether the motion's jerk is checked (streamed commands: the only producer
        that limits jerk; the cue and trajectories limit velocity and acceleration).
    :param frames: the frame tree of pose messages (:meth:`tool_pose`), or ``None``.
    :param sends: ``'legs'`` (messages of leg lengths) or ``'poses'`` (pose messages, which a
        node such as ik_node turns into leg lengths): what a braking command is sent as.
    :raises ValueError: for an unknown ``timing`` or ``sends``.
    """

    def __init__(self, geometry, actuator_limits: Optional[ActuatorLimits] = None, *,
                 timing: str = SETPOINT, jerk: bool = False, frames=None, sends: str = 'legs'):
        if timing not in TIMINGS:
            raise ValueError(f'timing must be one of {TIMINGS}, got {timing!r}')
        if sends not in ('legs', 'poses'):
            raise ValueError(f"sends must be 'legs' or 'poses', got {sends!r}")
        self.sends = sends
        self.geometry = geometry
        #: The pose limits' settings: the stroke that braking and interpolation keep.
        self._pose_limits = limits_of(geometry)
        self.actuator_limits = actuator_limits or ActuatorLimits()
        self.timing = timing
        self.frames = frames
        limits = self.actuator_limits
        if not jerk:
            limits = ActuatorLimits(limits.velocity_max, limits.acceleration_max)
        #: The limits every command must keep: the geometry's and the actuators'.
        self.limits = LimitModel(geometry, limits, rate_slack=RATE_SLACK)
        self.checks_jerk = jerk and math.isfinite(limits.jerk_max)
        self._take_masses(geometry)
        self.reset()

    def _take_masses(self, geometry) -> None:
        """Take the masses of ``geometry`` and the force limits it carries."""
        masses = masses_of(geometry)
        #: The masses that load the legs, or ``None`` when every mass is 0: then no force is
        #: computed, for any command.
        self.masses = None if masses.massless else masses
        force_range = (self._pose_limits.leg_force_min, self._pose_limits.leg_force_max)
        #: ``(leg_force_min, leg_force_max)``, N, when a motion's forces are checked, else None.
        self.force_range = (force_range if self.masses is not None and self.timing == MOTION
                            and not force_range == (-math.inf, math.inf) else None)

    def set_mass_properties(self, geometry) -> None:
        """
        Judge the next commands with the masses of ``geometry`` (a new payload), motion kept.

        The last command, its time, its rates and the limits it broke stay, so a stream goes
        on without a jump; its next command is judged with the new masses, statics (the pose
        limits' ``leg_force`` kind) and motion alike. Without masses before, the gate kept no
        twist: the first command after takes its acceleration as 0.

        :param geometry: the gate's geometry carrying other masses (the same platform and
            limits: :meth:`stewart_kinematics.Geometry.with_mass_properties`).
        """
        was_massless = self.masses is None
        self.geometry = geometry
        self._pose_limits = limits_of(geometry)
        self.limits = LimitModel(geometry, self.limits.actuator_limits, rate_slack=RATE_SLACK)
        self._take_masses(geometry)
        if was_massless and self.masses is not None and self._time is not None:
            self._twist = None

    # The state of a motion ------------------------------------------------------------------

    def reset(self, lengths=None, pose=None, time: Optional[float] = None) -> None:
        """
        Start a motion at rest: the last command is ``lengths`` (default: home), sent at ``time``.

        :param lengths: metres, shape (6,) (default: home's); with ``pose`` (``[X, Y, Z,
            alpha, beta, gamma]``) the pose they put the platform at (default: found by forward
            kinematics from home). Lengths beyond a limit are where the platform is: the
            commands after them may only come back.
        :param time: seconds, or ``None``: the first command after it has no rates to check
            but its own (it starts the clock).
        :raises ValueError: for lengths whose pose cannot be found.
        """
        geometry = self.geometry
        self._lengths = (geometry.home_leg_lengths.copy() if lengths is None
                         else np.array(lengths, dtype=float))
        if pose is None and lengths is not None:
            solution = forward_kinematics(geometry, self._lengths, geometry.home_pose,
                                          tolerance=_SOLVE_TOLERANCE)
            if not solution.converged:
                raise ValueError(f'no pose of the leg lengths '
                                 f'{np.round(self._lengths, 6).tolist()} m found: '
                                 f'{solution.reason}')
            pose = solution.pose
        self._pose = np.array(geometry.home_pose if pose is None else pose, dtype=float)
        #: The forward kinematics result of the last command passed, when one was solved
        #: (its Jacobian starts the next solve), and that of the command being judged.
        self._solution = self._candidate = None
        self._time = None if time is None else float(time)
        #: Divided differences of the last command: velocity, acceleration (m/s, m/s^2).
        self._velocity = np.zeros(6)
        self._acceleration = np.zeros(6)
        #: The last three intervals, newest first (``None``: at rest before).
        self._intervals = (None, None, None)
        #: Twist of the last command (divided differences of the poses), with masses only;
        #: and its leg forces, N, or ``None``.
        self._twist = np.zeros(6)
        self._forces = None
        #: The pose limits the last command broke (a braking command may have to), by
        #: ``(limit, leg, other leg)``: their excess, which a motion's next command may not
        #: pass (it may only come back toward the limits).
        self._outside = {}
        if lengths is not None:
            violations = self.limits.violations_of(self.limits.pose_legs(
                self._pose[:3], euler_zyx_to_matrix(self._pose[3:])))
            self._outside = {(violation.limit, violation.leg, violation.other_leg):
                             violation.excess for violation in violations}

    @property
    def last_time(self) -> Optional[float]:
        """Return the time of the last command passed, seconds, or ``None``."""
        return self._time

    @property
    def last_lengths(self) -> np.ndarray:
        """Return the leg lengths of the last command passed, metres, shape (6,)."""
        return self._lengths.copy()

    @property
    def last_velocities(self) -> np.ndarray:
        """Return the leg velocities of the last command passed (divided differences), m/s."""
        return self._velocity.copy()

    @property
    def last_pose(self) -> np.ndarray:
        """Return the pose the last command passed put the platform at, shape (6,)."""
        return self._pose.copy()

    def elapsed(self, time: float) -> Optional[float]:
        """
        Return the seconds from the last command to ``time``, or ``None`` when no time passed.

        A time before the last command's (a simulated clock moved back) starts a new time line
        at ``time``: the motion stays as it was, and ``None`` is returned; so does a first
        command's time.
        """
        time = float(time)
        if self._time is None or not math.isfinite(time):
            if math.isfinite(time):
                self._time = time
            return None
        if time < self._time:
            self._time = time
        if time <= self._time:
            return None
        return time - self._time

    # Setpoints and the poses of a motion ------------------------------------------------------

    def pose(self, position, rotation, time: Optional[float] = None) -> LegCommand:
        """
        Decide on the leg lengths of a platform pose, its numbers already checked valid.

        :param position: the platform origin in the base frame, metres, shape (3,), finite.
        :param rotation: the platform-to-base rotation matrix, shape (3, 3).
        :param time: when the command is sent, seconds (a :data:`MOTION`'s commands).
        :returns: a :class:`LegCommand`: refused (``unreachable``, ``out_of_limits``,
            ``too_fast``, ``clock_not_advancing``) or the lengths to send.
        """
        # The lengths first: a leg of length zero (a platform joint on its base joint) has no
        # direction, so the joint angles and the Jacobian of the limits do not exist there.
        with np.errstate(over='ignore', invalid='ignore'):
            legs = self.limits.pose_legs(position, rotation)
        lengths = legs.lengths[:, 0]
        if not all(0.0 < length < math.inf for length in lengths.tolist()):
            return LegCommand(None, refusal=Finding(
                findings.UNREACHABLE,
                f'its leg lengths must be finite and positive (metres), got '
                f'{np.round(lengths, 6).tolist()}: a platform joint on its base joint, or a pose '
                'beyond any reach'), position=position, rotation=rotation)
        violations = tuple(self.limits.violations_of(legs))
        if violations and not self._coming_back(violations):
            return LegCommand(None, violations, findings.out_of_limits('the pose is', violations),
                              position=position, rotation=rotation)
        if self.timing == SETPOINT:
            forces = None
            if self.masses is not None:
                forces = self._forces_of(np.concatenate([position, matrix_to_euler_zyx(
                    rotation)]), None, None)
                if forces is None:
                    return LegCommand(None, refusal=Finding(
                        findings.OUT_OF_LIMITS, 'no leg forces hold the platform at the pose (a '
                        'singular pose)'), position=position, rotation=rotation)
            return LegCommand(lengths.copy(), position=position, rotation=rotation, time=time,
                              forces=forces)
        return self._motion(lengths.copy(), position, rotation, time, violations)

    def tool_pose(self, position, quaternion, time: Optional[float] = None,
                  frame_id: str = '') -> LegCommand:
        """
        Decide on a pose message's numbers: the tool frame's pose, as ik_node reads it.

        :param position: the tool frame's origin, metres, three finite numbers.
        :param quaternion: ``(x, y, z, w)``, as the message carries it.
        :param time: when it is sent, seconds.
        :returns: a :class:`LegCommand` with ``tool_pose`` set: the numbers to send.
        """
        position = np.array(position, dtype=float)
        quaternion = np.array(quaternion, dtype=float)
        try:
            platform = platform_of_tool_message(position, quaternion, self.frames, frame_id)
        except ValueError as error:
            return LegCommand(None, refusal=Finding(findings.INVALID_POSE, str(error)))
        command = self.pose(*platform, time=time)
        return _replace(command, tool_pose=(position, quaternion))

    def pose_vector(self, pose, time: Optional[float] = None) -> LegCommand:
        """
        Decide on the pose ``[X, Y, Z, alpha, beta, gamma]`` of the tool frame (:meth:`tool_pose`).

        The message's numbers: the position, and the quaternion of the Euler angles.
        """
        pose = np.asarray(pose, dtype=float)
        return self.tool_pose(pose[:3], euler_zyx_to_quaternion(pose[3:]), time)

    # Leg commands of a motion ------------------------------------------------------------------

    def legs(self, lengths, time: float, velocities=None, accelerations=None) -> LegCommand:
        """
        Decide on a motion's leg command (a streamed step): lengths, and what they carry.

        The pose the lengths put the platform at comes from forward kinematics, started at the
        last command's pose; its pose limits are checked with the stroke and the rates.

        :param lengths: metres, shape (6,).
        :param time: when it is sent, seconds.
        :param velocities: the velocities sent with it, m/s, shape (6,), or ``None``.
        :param accelerations: likewise, m/s^2.
        """
        lengths = np.array(lengths, dtype=float)
        carried = {name: np.array(values, dtype=float) for name, values in (
            ('velocities', velocities), ('accelerations', accelerations)) if values is not None}
        if lengths.shape != (6,) or not np.all(np.isfinite(lengths)) or not np.all(
                lengths > 0.0) or any(values.shape != (6,) or not np.all(np.isfinite(values))
                                      for values in carried.values()):
            return LegCommand(None, refusal=Finding(
                findings.INVALID_LENGTHS, 'a leg command must be six finite, positive lengths '
                '(and six finite velocities and accelerations)'))
        violations = tuple(self.limits.leg_state_violations(**carried)) if carried else ()
        if violations:
            return LegCommand(None, violations, findings.out_of_limits(
                'the leg command is', violations), time=time)
        solution = self._solve(lengths)
        if not solution.converged:
            return LegCommand(None, refusal=Finding(
                findings.OUT_OF_LIMITS, 'the pose of the leg command could not be found from '
                f'the last one ({solution.reason}), so its limits cannot be checked'), time=time)
        position, rotation = solution.pose[:3], euler_zyx_to_matrix(solution.pose[3:])
        pose_violations = tuple(self.limits.violations_of(
            self.limits.pose_legs(position, rotation)))
        if pose_violations and not self._coming_back(pose_violations):
            return LegCommand(None, pose_violations, findings.out_of_limits(
                'the pose of the leg command is', pose_violations), position=position,
                rotation=rotation, time=time)
        command = self._motion(lengths, position, rotation, time, pose_violations,
                               solution.pose)
        if command.accepted and carried:
            command = _replace(command, **carried)
        return command

    def _solve(self, lengths):
        """
        Return the forward kinematics of leg lengths, from the last command's pose.

        Started from the last solution itself when there is one (its Jacobian is reused, as
        a tracking solve does), else from the last pose.
        """
        start = self._solution if self._solution is not None else self._pose
        solution = forward_kinematics(self.geometry, lengths, start, tolerance=_SOLVE_TOLERANCE,
                                      max_iterations=_SOLVE_ITERATIONS)
        self._candidate = solution if solution.converged else None
        return solution

    def _coming_back(self, violations) -> bool:
        """
        Whether a motion's command beyond pose limits only comes back toward them.

        After a braking command that could not stay inside (a leg stopped at the end of its
        stroke, a cone passed while braking), the next commands may break the limits the last
        one broke, by no more than it did: a platform outside its limits may move back in
        (as ros2_control's joint limiters let a joint outside its range move toward it), never
        further out.
        """
        if self.timing != MOTION or not self._outside:
            return False
        for violation in violations:
            last = self._outside.get((violation.limit, violation.leg, violation.other_leg))
            if last is None or violation.excess > last:
                return False
        return True

    def _motion(self, lengths, position, rotation, time, violations=(),
                pose=None) -> LegCommand:
        """
        Check the rates from the last command to ``lengths`` at ``time``; pass it if kept.

        :param pose: the pose vector of ``position`` and ``rotation`` when known (a solve's).
        """
        if time is None or not math.isfinite(float(time)):
            return LegCommand(None, refusal=Finding(
                findings.CLOCK_NOT_ADVANCING, f'a command of a motion needs the time it is sent, '
                f'got {time!r}'))
        time = float(time)
        if self._time is not None and not time > self._time and np.array_equal(
                lengths, self._lengths):
            # The last command again, no time later: no motion is commanded.
            if self.masses is not None and self._forces is None:   # at rest since the reset
                self._forces = self._forces_of(pose if pose is not None else np.concatenate(
                    [position, matrix_to_euler_zyx(rotation)]), None, None)
            return LegCommand(lengths, position=position, rotation=rotation, time=time,
                              velocities=np.zeros(6), forces=self._forces)
        if self._time is not None and not time > self._time:
            return LegCommand(None, refusal=Finding(
                findings.CLOCK_NOT_ADVANCING,
                f'the command at {seconds_text(time)} s does not come after the last one '
                f'({seconds_text(self._time)} s): no time passed, so no motion may be commanded'))
        rates = None if self._time is None else self._rates(lengths, time - self._time)
        if rates is not None:
            too_fast = tuple(self.limits.leg_state_violations(**rates['checked']))
            if too_fast:
                return LegCommand(None, too_fast, Finding(
                    findings.TOO_FAST,
                    f'the command {time - self._time:.6g} s after the last asks too much of the '
                    'legs: ' + '; '.join(map(str, too_fast)),
                    findings.violation_details(too_fast)), position=position,
                    rotation=rotation, time=time)
        pose = pose if pose is not None else np.concatenate(
            [position, matrix_to_euler_zyx(rotation)])
        forces = None
        if self.masses is not None:
            forces, strained = self._motion_forces(pose, rotation, rates)
            if strained is not None:
                return LegCommand(None, strained, Finding(
                    findings.TOO_FAST,
                    'the command ' + (f'{time - self._time:.6g} s after the last '
                                      if self._time is not None else '')
                    + 'asks too much force of the legs: ' + '; '.join(map(str, strained)),
                    findings.violation_details(strained)), position=position,
                    rotation=rotation, time=time)
            violations = violations + tuple(self._force_violations(forces))
        self._advance(lengths, pose, time, rates, violations, forces)
        warnings = () if not violations else (Finding(
            findings.RETURNING_TO_LIMITS, 'the platform is coming back within its limits, '
            'never further out: ' + '; '.join(map(str, violations)),
            findings.violation_details(violations)),)
        return LegCommand(lengths, violations, None, warnings, position, rotation, time=time,
                          velocities=None if rates is None else rates['velocities'],
                          accelerations=None if rates is None else rates['accelerations'],
                          forces=forces)

    # Leg forces (only with masses) -------------------------------------------------------------

    def _forces_of(self, pose, twist, acceleration) -> Optional[np.ndarray]:
        """Return the leg forces of a pose moving so, N, shape (6,); ``None`` at a singular one."""
        try:
            return leg_forces(self.geometry, pose, twist, acceleration,
                              mass_properties=self.masses)
        except ValueError:   # a singular pose, or forces beyond the float range
            return None

    def pose_rates(self, position, rotation, interval) -> Tuple[np.ndarray, np.ndarray]:
        """
        Return the twist and acceleration of a pose sent ``interval`` seconds after the last.

        The divided differences of the poses sent (see the module's text): the velocity of the
        platform frame's origin and the angular velocity (the rotation vector of ``R_k
        R_k-1^T`` over the interval), both in the base frame, and their change over the mean
        of the last two intervals.

        :param position: metres, (3,); ``rotation`` (3, 3): the pose sent.
        :param interval: seconds since the last command, positive.
        :returns: ``(twist (6,), acceleration (6,))``, m/s and rad/s, m/s^2 and rad/s^2.
        """
        last_rotation = euler_zyx_to_matrix(self._pose[3:])
        twist = np.concatenate([np.asarray(position, dtype=float) - self._pose[:3],
                                matrix_to_rotation_vector(rotation @ last_rotation.T)]) / interval
        if self._twist is None:     # masses given mid-motion: no earlier twist was kept
            return twist, np.zeros(6)
        last = self._intervals[0]
        span = 0.5 * (interval + (last if last is not None else interval))
        return twist, (twist - self._twist) / span

    def _motion_forces(self, pose, rotation, rates):
        """
        Return a motion's command's forces, and the force limits they break.

        :returns: ``(forces, None)`` within the force limits (or coming back toward them),
            else ``(forces, violations)``; every leg at fault at a singular pose.
        """
        if rates is None:   # the first command of a motion: from rest
            twist = acceleration = None
        else:
            twist, acceleration = self.pose_rates(pose[:3], rotation, rates['interval'])
            rates['twist'] = twist
        forces = self._forces_of(pose, twist, acceleration)
        if forces is None:
            return None, tuple(Violation('leg_force_max', leg, math.inf, self.force_range[1]
                                         if self.force_range else math.inf, 'N')
                               for leg in range(1, 7))
        if self.force_range is None:
            return forces, None
        violations = tuple(self._force_violations(forces))
        if violations and not self._forces_coming_back(violations):
            return forces, violations
        return forces, None

    def _force_violations(self, forces):
        """Yield the :class:`Violation` of each leg force beyond the force limits."""
        if self.force_range is None or forces is None:
            return
        low, high = self.force_range
        for leg, force in enumerate(forces.tolist(), start=1):
            if force > high:
                yield Violation('leg_force_max', leg, force, high, 'N')
            elif force < low:
                yield Violation('leg_force_min', leg, force, low, 'N')

    def _forces_coming_back(self, violations) -> bool:
        """Whether forces beyond their limits break them by no more than the last command's."""
        for violation in violations:
            last = self._outside.get((violation.limit, violation.leg, None))
            if last is None or violation.excess > last:
                return False
        return True

    def _rates(self, lengths, interval) -> dict:
        """
        Return the divided differences of a command ``interval`` seconds after the last one.

        :returns: ``velocities``, ``accelerations``, ``jerks`` (each (6,)), the intervals, and
            ``checked``: the same with their rounding forgiven (toward zero), as the limits
            model checks them.
        """
        last, before, earliest = self._intervals
        velocity_span = interval
        acceleration_span = 0.5 * (interval + (last if last is not None else interval))
        jerk_span = (interval + (last if last is not None else interval)
                     + (before if before is not None else interval)) / 3.0
        velocities = (lengths - self._lengths) / velocity_span
        accelerations = (velocities - self._velocity) / acceleration_span
        jerks = (accelerations - self._acceleration) / jerk_span
        # Rounding of lengths of about a metre: eps |l| per length, doubling with each order.
        size = _ROUNDING_FACTOR * _EPSILON * max(float(np.max(np.abs(lengths))), 1.0)
        rounding_v = 2.0 * size / velocity_span
        rounding_a = 4.0 * size / (velocity_span * acceleration_span)
        rounding_j = 8.0 * size / (velocity_span * acceleration_span * jerk_span)
        checked = {'velocities': _toward_zero(velocities, rounding_v),
                   'accelerations': _toward_zero(accelerations, rounding_a)}
        if self.checks_jerk:
            checked['jerks'] = _toward_zero(jerks, rounding_j)
        return {'velocities': velocities, 'accelerations': accelerations, 'jerks': jerks,
                'interval': interval, 'checked': checked}

    def _advance(self, lengths, pose, time, rates, violations=(), forces=None) -> None:
        """Make a command passed (or a braking one) the last one."""
        self._forces = forces
        self._solution = (self._candidate if self._candidate is not None
                          and np.array_equal(self._candidate.pose, pose) else None)
        self._candidate = None
        self._outside = {(violation.limit, violation.leg, violation.other_leg): violation.excess
                         for violation in violations}
        if rates is not None:
            self._velocity, self._acceleration = rates['velocities'], rates['accelerations']
            self._twist = rates.get('twist', np.zeros(6))
            self._intervals = (rates['interval'],) + self._intervals[:2]
        self._lengths, self._pose, self._time = np.array(lengths, dtype=float), pose, time

    # Braking ---------------------------------------------------------------------------------

    def brake(self, time: float, replaced: Optional[Finding] = None) -> LegCommand:
        """
        Give the command that slows every leg at its acceleration limit, from the last one.

        Each leg's velocity (the divided difference) falls toward zero by at most
        :data:`BRAKING_SHARE` of ``leg_acceleration_max`` times the acceleration span (as
        :meth:`legs` checks it): within the velocity and acceleration limits by construction,
        to rest and no further; the jerk limit may be exceeded. A leg that would pass an end of
        its stroke stops there. Given at rest, it repeats the last command. A gate that sends
        poses (``sends='poses'``) judges the lengths of the pose message it gives, as sent.
        With masses and a force limit, a braking command whose leg forces (with the motion's
        twist and acceleration) would leave ``leg_force_min..leg_force_max`` brakes at the next
        gentler share of :data:`BRAKING_SHARES` instead (down to keeping the legs' speed).

        :param time: when it is sent, seconds, after the last command.
        :param replaced: the refusal of the command it replaces, or ``None`` (a stop asked
            for): with one, the braking command carries a ``command_braking`` finding (a
            refusal class: no command within every limit was given).

        :returns: a :class:`LegCommand` with ``braking`` set; refused only when no time
            passed since the last command (``clock_not_advancing``), the pose of the braked
            lengths cannot be found, or no braking keeps the leg forces (``command_braking``
            naming the limit and the legs): then nothing can be sent, the last command stands.
        """
        interval = None if self._time is None else float(time) - self._time
        if interval is None or not interval > 0.0:
            return LegCommand(None, refusal=Finding(
                findings.CLOCK_NOT_ADVANCING, 'no time passed since the last command: nothing '
                'to brake yet'))
        strained = None
        for share in (BRAKING_SHARES if self.force_range is not None else (BRAKING_SHARE,)):
            braking = self._braking(interval, share)
            if isinstance(braking, LegCommand):
                return braking
            lengths, stopped, position, rotation, tool_pose, violations, rates = braking
            pose = np.concatenate([position, matrix_to_euler_zyx(rotation)])
            if self.masses is None:
                forces = None
                break
            forces, strained = self._motion_forces(pose, rotation, rates)
            if strained is None:
                break
        else:
            return LegCommand(None, strained, Finding(
                findings.COMMAND_BRAKING, 'no command within the limits could be given, and '
                'braking at any rate asks too much force of the legs: '
                + '; '.join(map(str, strained)) + ': the last command stands',
                findings.violation_details(strained)), time=float(time))
        if self.masses is not None:
            violations = violations + tuple(self._force_violations(forces))
        self._advance(lengths, pose, float(time), rates, violations, forces)
        warnings = ()
        if replaced is not None or violations or np.any(stopped) or share != BRAKING_SHARE:
            details = ((('replaced', replaced.code),) + tuple(replaced.details)
                       if replaced is not None else ())
            message = (('braking at leg_acceleration_max' if share == BRAKING_SHARE else
                        f'braking at {share:g} of leg_acceleration_max (harder would break the '
                        'leg force limits)')
                       + (f' instead of a command that was refused: {replaced.message}'
                          if replaced is not None else ''))
            if np.any(stopped):
                message += (f'; legs {(np.flatnonzero(stopped) + 1).tolist()} stopped at the end '
                            'of the stroke')
            if violations:
                message += '; the braking command breaks ' + '; '.join(map(str, violations))
            warnings = (Finding(findings.COMMAND_BRAKING, message,
                                details + findings.violation_details(violations)),)
        return LegCommand(lengths, violations, None, warnings, position, rotation,
                          velocities=rates['velocities'], accelerations=rates['accelerations'],
                          time=float(time), braking=True, tool_pose=tool_pose, forces=forces)

    def _braking(self, interval, share):
        """
        Return the braking command ``interval`` after the last, at ``share`` of the limit.

        :returns: ``(lengths, stopped, position, rotation, tool_pose, violations, rates)``, or
            a refused :class:`LegCommand` when its pose cannot be found.
        """
        last = self._intervals[0]
        span = 0.5 * (interval + (last if last is not None else interval))
        change = share * self.actuator_limits.acceleration_max * span
        velocities = self._velocity - np.clip(self._velocity, -change, change)
        lengths = self._lengths + velocities * interval
        low, high = self._pose_limits.leg_length_min, self._pose_limits.leg_length_max
        stopped = (lengths < low) | (lengths > high)
        lengths = np.clip(lengths, low, high)
        solution = self._solve(lengths)
        if not solution.converged:
            return LegCommand(None, refusal=Finding(
                findings.COMMAND_BRAKING, 'no command within the limits could be given, and the '
                f'pose of the braking command could not be found ({solution.reason}): the last '
                'command stands'))
        position, rotation = solution.pose[:3], euler_zyx_to_matrix(solution.pose[3:])
        tool = (Transform(position, rotation) if self.frames is None
                else self.frames.tool_from_platform(Transform(position, rotation)))
        tool_pose = (np.array(tool.position, dtype=float), matrix_to_quaternion(tool.rotation))
        if self.sends == 'poses':
            # What is sent is the pose message: its numbers, read back, give the lengths.
            position, rotation = platform_of_tool_message(*tool_pose, self.frames)
        legs = self.limits.pose_legs(position, rotation)
        if self.sends == 'poses':
            lengths = legs.lengths[:, 0].copy()
        violations = tuple(self.limits.violations_of(legs))
        return (lengths, stopped, position, rotation, tool_pose, violations,
                self._rates(lengths, interval))

    @property
    def at_rest(self) -> bool:
        """Whether the last command left every leg at rest (its velocity zero)."""
        return not np.any(self._velocity)

    # Velocities ------------------------------------------------------------------------------

    def leg_velocities(self, velocities, lengths, scale: float = 1.0,
                       warnings=()) -> LegVelocityCommand:
        """
        Decide on leg velocities to command at leg lengths (a twist at the last pose).

        Each within ``leg_velocity_max``; and each leg able to stop inside its stroke from
        there at ``leg_acceleration_max``: ``v^2 / (2 a)`` at most the room left toward the end
        it moves to (without an acceleration limit, no motion out of the stroke at its end).

        :param velocities: m/s, shape (6,), finite.
        :param lengths: the legs' lengths where they apply, metres, shape (6,).
        :param scale: the factor the twist was scaled by (reported with the command).
        :param warnings: findings to carry (a scaled twist).
        """
        velocities = np.array(velocities, dtype=float)
        violations = self.limits.leg_state_violations(velocities=velocities)
        if violations:
            return LegVelocityCommand(None, findings.out_of_limits(
                'the leg velocities are', violations))
        lengths = np.asarray(lengths, dtype=float)
        acceleration = self.actuator_limits.acceleration_max
        room = np.where(velocities > 0.0, self._pose_limits.leg_length_max - lengths,
                        lengths - self._pose_limits.leg_length_min)
        stopping = (0.5 * velocities * velocities / acceleration if math.isfinite(acceleration)
                    else np.zeros(6))
        leaving = (velocities != 0.0) & ~(stopping < room) if math.isfinite(acceleration) else (
            (velocities != 0.0) & ~(room > 0.0))
        if np.any(leaving):
            legs = (np.flatnonzero(leaving) + 1).tolist()
            return LegVelocityCommand(None, Finding(
                findings.OUT_OF_LIMITS,
                f'legs {legs} could not stop inside their stroke at these velocities: they need '
                f'{np.round(stopping[leaving], 6).tolist()} m to stop at leg_acceleration_max and '
                f'have {np.round(room[leaving], 6).tolist()} m left',
                (('legs', str(legs)),)))
        return LegVelocityCommand(velocities, None, tuple(warnings), scale)

    # Trajectories ----------------------------------------------------------------------------

    def trajectory(self, points, positions, rotations) -> TrajectoryCommand:
        """
        Decide on every point of a leg trajectory, and on the controller's way between.

        Each point: the leg lengths it carries (positions plus the actuators' offsets, as a
        driver reads them) against the stroke, the pose there (``positions``, ``rotations``:
        the poses whose legs the points are, checked to match) against every pose limit, and
        the velocities and accelerations it carries against their limits. Between two points,
        the quintic a controller interpolates through their positions, velocities and
        accelerations against the stroke, at :data:`INTERPOLATION_SAMPLES` times.

        :param points: a :class:`~stewart_kinematics.motion.leg_trajectory.LegTrajectory`.
        :param positions: the platform origins of the points, metres, (M, 3).
        :param rotations: their rotations, (M, 3, 3).
        :returns: a :class:`TrajectoryCommand` naming the first failing point.
        """
        lengths = points.lengths
        pose_checks = self.limits.check_pose_matrices(positions, rotations, exact=False)
        rate_checks = self.limits.check_leg_states(
            lengths=lengths, velocities=points.velocities, accelerations=points.accelerations)
        allowed = pose_checks.allowed & rate_checks.allowed
        # The lengths sent are those of the poses checked (to the rounding of the offsets).
        legs = leg_vectors(self.geometry, np.asarray(positions), np.asarray(rotations))
        mismatch = np.max(np.abs(np.linalg.norm(legs, axis=-1) - lengths), axis=1)
        allowed &= mismatch <= LENGTH_MATCH
        failing = np.flatnonzero(~allowed)
        if failing.size:
            first = int(failing[0])
            violations = tuple(pose_checks.violations(first)) + tuple(
                rate_checks.violations(first))
            reason = '; '.join(map(str, violations)) or (
                f'its lengths differ from those of its pose by {mismatch[first]:.3g} m')
            return TrajectoryCommand(None, Finding(
                findings.TOO_FAST if violations and all(
                    violation.limit in ('leg_velocity_max', 'leg_acceleration_max')
                    for violation in violations) else findings.OUT_OF_LIMITS,
                f'published point {first} (t = {points.times[first]:.4f} s) of leg_trajectory: '
                + reason, (('point', str(first)), ('time_s', f'{points.times[first]:.4f}'))
                + findings.violation_details(violations)), violations=violations, point=first)
        refusal = self._interpolation_refusal(points)
        if refusal is not None:
            return TrajectoryCommand(None, refusal[1], point=refusal[0])
        return TrajectoryCommand(points)

    def _interpolation_refusal(self, points):
        """Return ``(point, finding)`` where the quintics between points leave the stroke."""
        if len(points.times) < 2:
            return None
        low, high = self._pose_limits.leg_length_min, self._pose_limits.leg_length_max
        if low <= 0.0 and high == math.inf:
            return None
        lengths = points.lengths
        steps = np.diff(points.times)[:, None]
        s = np.arange(1, INTERPOLATION_SAMPLES + 1)[:, None, None] / (INTERPOLATION_SAMPLES + 1)
        p0, p1 = lengths[:-1], lengths[1:]
        m0, m1 = points.velocities[:-1] * steps, points.velocities[1:] * steps
        a0, a1 = points.accelerations[:-1] * steps ** 2, points.accelerations[1:] * steps ** 2
        delta = p1 - p0
        c3 = 10.0 * delta - 6.0 * m0 - 4.0 * m1 - 0.5 * (3.0 * a0 - a1)
        c4 = -15.0 * delta + 8.0 * m0 + 7.0 * m1 + 0.5 * (3.0 * a0 - 2.0 * a1)
        c5 = 6.0 * delta - 3.0 * m0 - 3.0 * m1 - 0.5 * (a0 - a1)
        values = p0 + s * (m0 + s * (0.5 * a0 + s * (c3 + s * (c4 + s * c5))))
        broken = (values < low - INTERPOLATION_ROUNDING) | (values > high + INTERPOLATION_ROUNDING)
        if not np.any(broken):
            return None
        segment = int(np.flatnonzero(np.any(broken, axis=(0, 2)))[0])
        legs = (np.flatnonzero(np.any(broken[:, segment], axis=0)) + 1).tolist()
        extreme = values[:, segment]
        return segment, Finding(
            findings.OUT_OF_LIMITS,
            f'between published points {segment} and {segment + 1} of leg_trajectory '
            f'(t = {points.times[segment]:.4f} to {points.times[segment + 1]:.4f} s) the '
            f"controller's interpolation takes legs {legs} to {extreme.min():.6g} to "
            f'{extreme.max():.6g} m, beyond the stroke [{low:g}, {high:g}] m: publish more points '
            '(publish_rate)', (('segment', f'points {segment} and {segment + 1}'),
                               ('legs', str(legs))))


def _toward_zero(values, rounding):
    """Return ``values`` moved toward zero by ``rounding`` (never past it)."""
    return np.sign(values) * np.maximum(np.abs(values) - rounding, 0.0)


def _replace(command, **changes):
    """Return a copy of a frozen verdict with some fields changed."""
    return dataclasses.replace(command, **changes)
