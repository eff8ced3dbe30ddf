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
The contract of a FollowJointTrajectory goal: which joints, whether it is valid, what to plan.

trajectory_node's ``follow_joint_trajectory`` action (:mod:`stewart_kinematics.ros.
trajectory_action`) converts a goal to a :class:`GoalRequest` and asks, in order:

1. :func:`check_goal`: which joint set it names (:class:`JointSets`: the six leg joints of
   ``joint_commands``, or the six Cartesian joints of the tool frame, default ``x y z roll
   pitch yaw``, metres and radians, ``R = Rz(yaw) Ry(pitch) Rx(roll)`` about the base axes),
   and whether it is well formed, answering with the action's result code
   (``INVALID_JOINTS``, ``INVALID_GOAL``, ``OLD_HEADER_TIMESTAMP``) and the reason, as
   joint_trajectory_controller's ``validate_trajectory_msg`` decides (Jazzy).
2. :func:`goal_motion`: the platform motion to plan, starting where the platform is (a first
   point at a time > 0 gets the current state prepended at time 0, as the controller
   interpolates from the current state; a first point at time 0 must be the current state
   within ``start_tolerance``: no jump). Leg goals become platform poses by forward kinematics
   (their velocities twists through the Jacobian), Cartesian goals tool-frame poses.
3. The motion is planned by :class:`~stewart_kinematics.motion.planning.MotionPlanner` (the
   one limits model, ``retime``), in the planning worker.
4. :class:`JointSpace` gives the desired state of the planned trajectory, and the actual state
   of measured legs, in the goal's joints, for the feedback and the tolerance checks
   (:mod:`~stewart_kinematics.motion.tolerances`).

Where this differs from joint_trajectory_controller, and why: a goal the controller rejects
(no result) is accepted here and aborted at once with its result code and reason, so that a
client learns why (as ROS 1's controller answered); a header stamp in the past whose end is
not yet past starts the trajectory now from its first point, instead of skipping the part
already past (which would jump); a leg goal is interpolated on the platform's poses through
its waypoints, not leg by leg (its waypoints are met exactly, and every sample is checked
against every limit).

Units: metres, radians, seconds. Nothing here imports ROS.
"""

from collections import Counter
from dataclasses import dataclass
import math
from typing import Optional, Sequence, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.findings import Decision, Finding
from stewart_kinematics.model.actuators import ActuatorInterface
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.frames import FrameTree
from stewart_kinematics.model.rotations import (
    euler_zyx_to_matrix,
    matrix_to_euler_zyx,
    matrix_to_quaternion,
)
from stewart_kinematics.model.velocities import leg_states, platform_twist
from stewart_kinematics.motion.pose_trajectory import MAX_WAYPOINTS, PoseTrajectory
from stewart_kinematics.motion.tolerances import (
    GOAL_TOLERANCE_VIOLATED,
    INVALID_GOAL,
    INVALID_JOINTS,
    JointToleranceValues,
    OLD_HEADER_TIMESTAMP,
    PATH_TOLERANCE_VIOLATED,
)

#: The joint sets a goal may name.
LEGS = 'legs'
CARTESIAN = 'cartesian'
#: The Cartesian joints' default names: the tool frame's x, y, z (m), roll, pitch, yaw (rad).
DEFAULT_CARTESIAN_JOINTS = ('x', 'y', 'z', 'roll', 'pitch', 'yaw')
#: Largest time_from_start and header stamp lead, seconds (as pose_trajectory's times).
MAX_TIME = 1e6
#: Largest magnitude of a position, velocity or acceleration a goal may give (joint units).
MAX_VALUE = 1e6
#: A last point's velocity beyond this is not at rest (the controller's float epsilon).
REST_VELOCITY = float(np.finfo(np.float32).eps)

#: The result code of each refusal code (any other refusal: INVALID_GOAL).
RESULT_CODES = {
    findings.INVALID_JOINTS: INVALID_JOINTS,
    findings.OLD_HEADER_TIMESTAMP: OLD_HEADER_TIMESTAMP,
    findings.PATH_TOLERANCE_VIOLATED: PATH_TOLERANCE_VIOLATED,
    findings.GOAL_TOLERANCE_VIOLATED: GOAL_TOLERANCE_VIOLATED,
}


def result_code(finding: Finding) -> int:
    """Return the FollowJointTrajectory result code of a refusal (``INVALID_GOAL`` by default)."""
    return RESULT_CODES.get(finding.code, INVALID_GOAL)


@dataclass(frozen=True)
class GoalRequest:
    """
    A FollowJointTrajectory goal, as plain values (the node converts the message).

    :param joint_names: ``trajectory.joint_names``.
    :param times: each point's ``time_from_start``, seconds.
    :param positions: per point, a sequence of values (any length: checked here).
    :param velocities: per point, empty or one per joint; ``accelerations``, ``efforts`` the
        same.
    :param frame_id: ``trajectory.header.frame_id`` (Cartesian goals: base or user frame).
    :param stamp: ``trajectory.header.stamp``, seconds; 0: start now.
    :param path_tolerance: the goal's :class:`JointToleranceValues`; ``goal_tolerance`` too.
    :param goal_time_tolerance: seconds.
    :param multi_dof_points: how many points ``multi_dof_trajectory`` has, and
        ``multi_dof_joints`` how many joint names: a goal must leave it empty.
    """

    joint_names: Tuple[str, ...]
    times: Tuple[float, ...]
    positions: Tuple[Sequence[float], ...]
    velocities: Tuple[Sequence[float], ...] = ()
    accelerations: Tuple[Sequence[float], ...] = ()
    efforts: Tuple[Sequence[float], ...] = ()
    frame_id: str = ''
    stamp: float = 0.0
    path_tolerance: Tuple[JointToleranceValues, ...] = ()
    goal_tolerance: Tuple[JointToleranceValues, ...] = ()
    goal_time_tolerance: float = 0.0
    multi_dof_points: int = 0
    multi_dof_joints: int = 0


@dataclass(frozen=True)
class JointSets:
    """
    The two joint sets a goal may move: the legs, or the tool frame's pose.

    :param legs: the actuators (joint names, offsets), as ``joint_commands`` names them.
    :param cartesian: six names: x, y, z (m), roll, pitch, yaw (rad) of the tool frame.
    """

    legs: ActuatorInterface
    cartesian: Tuple[str, ...] = DEFAULT_CARTESIAN_JOINTS

    def names(self, kind: str) -> Tuple[str, ...]:
        """Return the joint names of a set, in the set's (the feedback's) order."""
        return tuple(self.legs.joint_names) if kind == LEGS else tuple(self.cartesian)


@dataclass(frozen=True)
class GoalCheck(Decision):
    """
    :func:`check_goal`'s answer: the goal in its joint set's order, or why it is refused.

    :param refusal: ``None``, or the :class:`Finding` (its code gives the result code,
        :func:`result_code`).
    :param kind: :data:`LEGS` or :data:`CARTESIAN`.
    :param times: seconds, shape (N,).
    :param positions: shape (N, 6), in the set's order.
    :param velocities: shape (N, 6), or ``None`` (no point has them).
    :param accelerations: shape (N, 6), or ``None``.
    """

    refusal: Optional[Finding]
    kind: str = ''
    times: Optional[np.ndarray] = None
    positions: Optional[np.ndarray] = None
    velocities: Optional[np.ndarray] = None
    accelerations: Optional[np.ndarray] = None
    warnings: Tuple[Finding, ...] = ()


def _invalid(message: str) -> GoalCheck:
    """Refuse a goal with ``invalid_goal`` and ``message``."""
    return GoalCheck(Finding(findings.INVALID_GOAL, message))


def joint_set(names: Sequence[str], sets: JointSets):
    """
    Which joint set a goal's names are, and where each of the set's joints is among them.

    :returns: ``(kind, order)``: ``order[k]`` is the index in ``names`` of the set's joint k;
        or ``(None, finding)``: ``invalid_joints`` naming what is empty, repeated, unknown or
        missing.
    """
    names = [str(name) for name in names]
    legs, cartesian = sets.names(LEGS), sets.names(CARTESIAN)
    described = (f'the six leg joints ({", ".join(legs)}) or the six Cartesian joints '
                 f'({", ".join(cartesian)}), in any order')
    if not names:
        return None, Finding(findings.INVALID_JOINTS,
                             f'the goal names no joints: give {described}')
    repeated = sorted(name for name, count in Counter(names).items() if count > 1)
    if repeated:
        return None, Finding(findings.INVALID_JOINTS, f'joint names repeated: '
                             f'{", ".join(map(repr, repeated[:6]))}; give {described}')
    kind = LEGS if any(name in legs for name in names) or not any(
        name in cartesian for name in names) else CARTESIAN
    wanted = legs if kind == LEGS else cartesian
    unknown = [name for name in names if name not in wanted]
    missing = [name for name in wanted if name not in names]
    if unknown or missing:
        problems = []
        if unknown:
            shown = ', '.join(repr(name[:40]) for name in unknown[:6])
            problems.append(f'unknown {shown}' + (f' and {len(unknown) - 6} more'
                                                  if len(unknown) > 6 else ''))
        if missing:
            problems.append(f'missing {", ".join(map(repr, missing))}')
        return None, Finding(findings.INVALID_JOINTS, f'joint names: {"; ".join(problems)}: '
                             f'give {described}')
    return kind, np.array([names.index(name) for name in wanted])


def check_goal(request: GoalRequest, sets: JointSets, now: float) -> GoalCheck:
    """
    Check a goal as joint_trajectory_controller validates it, with the action's result codes.

    :param now: the node's clock, seconds (ROS time), for the header stamp.
    :returns: a :class:`GoalCheck`: refused ``invalid_joints`` (names), ``invalid_goal``
        (``multi_dof_trajectory``, no points, too many, sizes, values not finite or beyond
        :data:`MAX_VALUE`, times not finite, negative, beyond :data:`MAX_TIME` or not
        increasing, a last point not at rest, efforts, a stamp too far ahead) or
        ``old_header_timestamp``; else the arrays in the joint set's order.
    """
    if request.multi_dof_points or request.multi_dof_joints:
        both = ' (trajectory is given too)' if request.joint_names or request.times else ''
        return _invalid(f'multi_dof_trajectory is not taken{both}: give '
                        'the six joints in trajectory (a MultiDOFJointTrajectory of the tool '
                        'frame goes to pose_trajectory)')
    kind, order = joint_set(request.joint_names, sets)
    if kind is None:
        return GoalCheck(order)
    count = len(request.times)
    if count == 0:
        return _invalid('the trajectory has no points')
    if count > MAX_WAYPOINTS:
        return _invalid(f'the trajectory has {count:,} points; at most '
                        f'{MAX_WAYPOINTS:,}')
    names = sets.names(kind)
    width = len(request.joint_names)
    arrays = {}
    for field_name, rows, required in (('positions', request.positions, True),
                                       ('velocities', request.velocities, False),
                                       ('accelerations', request.accelerations, False)):
        array, reason = _point_array(field_name, rows, count, width, required)
        if reason:
            return _invalid(reason)
        if array is not None:
            bad = ~(np.abs(array) <= MAX_VALUE)
            if bad.any():
                point, column = (int(i) for i in np.argwhere(bad)[0])
                value = float(array[point, column])
                return _invalid(f'point {point}: {field_name} of '
                                f'{request.joint_names[column]} is {value!r}; '
                                f'a value must be finite and within +-{MAX_VALUE:g}')
            array = array[:, order]
        arrays[field_name] = array
    if any(len(row) for row in request.efforts):
        return _invalid('the points carry efforts: they are not taken '
                        '(the efforts follow from the motion and the masses)')
    times = np.array(request.times, dtype=float)
    bad = ~((times >= 0.0) & (times <= MAX_TIME))
    if bad.any():
        point = int(np.argmax(bad))
        return _invalid(f'point {point}: time_from_start '
                        f'{float(times[point])!r} s; times must be within 0 to {MAX_TIME:g} s')
    steps = np.diff(times)
    if np.any(steps <= 0.0):
        point = int(np.argmax(steps <= 0.0)) + 1
        return _invalid(f'times not strictly increasing: point {point} at '
                        f'{times[point]:.9g} s after point {point - 1} at '
                        f'{times[point - 1]:.9g} s')
    last_velocities = arrays['velocities']
    if last_velocities is not None and np.any(np.abs(last_velocities[-1]) > REST_VELOCITY):
        joint = int(np.argmax(np.abs(last_velocities[-1])))
        return _invalid(f'the last point does not rest: velocity of '
                        f'{names[joint]} is {last_velocities[-1, joint]:.6g}')
    if request.stamp != 0.0:
        end = request.stamp + times[-1]
        if end < now:
            return GoalCheck(Finding(
                findings.OLD_HEADER_TIMESTAMP, f'the trajectory starts at its header stamp '
                f'{request.stamp:.3f} s and ends at {end:.3f} s, before now ({now:.3f} s)'))
        if request.stamp - now > MAX_TIME:
            return _invalid(f'the header stamp {request.stamp:.3f} s is '
                            f'more than {MAX_TIME:g} s ahead of now ({now:.3f} s)')
    return GoalCheck(None, kind, times, arrays['positions'], arrays['velocities'],
                     arrays['accelerations'])


def _point_array(field_name, rows, count, width, required):
    """Return ``(array (N, width) or None, '')`` or ``(None, reason)`` for one point field."""
    rows = list(rows)
    if not required and not any(len(row) for row in rows):
        return None, ''
    if len(rows) != count:
        return None, f'{field_name} given for {len(rows)} of {count} points'
    for point, row in enumerate(rows):
        if len(row) != width:
            some = '' if required else ' (on every point, or on none)'
            return None, (f'point {point}: {len(row)} {field_name} for {width} joints{some}')
    try:
        return np.array([list(row) for row in rows], dtype=float).reshape(count, width), ''
    except (TypeError, ValueError, OverflowError):
        return None, f'{field_name} must be numbers'


@dataclass(frozen=True)
class GoalMotion(Decision):
    """
    :func:`goal_motion`'s answer: the platform motion to plan, or why there is none.

    :param refusal: ``None``, or ``invalid_goal``.
    :param trajectory: for a leg goal, the platform's :class:`PoseTrajectory` (base frame), to
        plan with :func:`~stewart_kinematics.motion.planning.plan_motion`.
    :param tool_waypoints: for a Cartesian goal, the keyword arguments of
        :meth:`~stewart_kinematics.motion.planning.MotionPlanner.plan_trajectory` (tool frame).
    """

    refusal: Optional[Finding]
    trajectory: Optional[PoseTrajectory] = None
    tool_waypoints: Optional[dict] = None
    warnings: Tuple[Finding, ...] = ()


def goal_motion(goal: GoalCheck, current, geometry, actuators: ActuatorInterface,
                start_tolerance: float, frame_id: str = '') -> GoalMotion:
    """
    Return the motion to plan for a checked goal, from the current state of its joints.

    :param goal: an accepted :class:`GoalCheck`.
    :param current: the current positions of the goal's joints (the set's order), shape (6,):
        where the last command left the platform, else as measured; ``None`` when unknown.
    :param start_tolerance: how far (joint units) a first point at time 0 may be from
        ``current``: it is replaced by ``current`` (no jump).
    :param frame_id: the frame of a Cartesian goal's poses (base or user frame, or ``''``).
    """
    if current is None:
        return GoalMotion(Finding(findings.INVALID_GOAL, 'no joint_states received yet: the '
                                  "platform's current state, where the trajectory starts, is "
                                  'unknown'))
    current = np.asarray(current, dtype=float)
    times, positions = goal.times, goal.positions.copy()
    velocities, accelerations = goal.velocities, goal.accelerations
    if times[0] > 0.0:
        times = np.concatenate([[0.0], times])
        positions = np.vstack([current, positions])
        zeros = np.zeros((1, 6))
        velocities = None if velocities is None else np.vstack([zeros, velocities])
        accelerations = None if accelerations is None else np.vstack([zeros, accelerations])
    else:
        offset = _difference(positions[0], current, goal.kind)
        worst = int(np.argmax(np.abs(offset)))
        if abs(offset[worst]) > start_tolerance:
            return GoalMotion(Finding(findings.INVALID_GOAL, f'the first point is at time 0 but '
                                      f'{abs(offset[worst]):.6g} from the current state '
                                      f'(joint {worst + 1}), more than start_tolerance '
                                      f'{start_tolerance:g}: it would jump; start it later'))
        if velocities is not None and np.any(np.abs(velocities[0]) > REST_VELOCITY):
            return GoalMotion(Finding(findings.INVALID_GOAL, 'the first point is at time 0 with '
                                      'velocities, but the platform is at rest there'))
        positions[0] = current
    if goal.kind == CARTESIAN:
        return _cartesian_motion(times, positions, velocities, accelerations, frame_id)
    return _leg_motion(times, positions, velocities, geometry, actuators)


def _difference(positions, reference, kind):
    """Return ``positions - reference``, angles of a Cartesian set wrapped to [-pi, pi]."""
    difference = np.asarray(positions, dtype=float) - reference
    if kind == CARTESIAN:
        difference[..., 3:] = wrap_angles(difference[..., 3:])
    return difference


def wrap_angles(angles):
    """Return angles wrapped to [-pi, pi), radians (the shortest angular distance)."""
    return (np.asarray(angles, dtype=float) + math.pi) % (2.0 * math.pi) - math.pi


def _leg_motion(times, positions, velocities, geometry, actuators) -> GoalMotion:
    """Platform poses (and twists) of leg waypoints, by forward kinematics."""
    lengths = actuators.lengths(positions)
    if np.any(lengths <= 0.0):
        point = int(np.argmax(np.any(lengths <= 0.0, axis=1)))
        return GoalMotion(Finding(findings.INVALID_GOAL, f'point {point}: a leg length '
                                  '(position plus its actuator offset) is not positive'))
    solution = forward_kinematics(geometry, lengths)
    converged = np.atleast_1d(solution.converged)
    if not converged.all():
        point = int(np.argmax(~converged))
        return GoalMotion(Finding(findings.INVALID_GOAL, f'point {point}: no platform pose has '
                                  f'these leg lengths ({np.atleast_1d(solution.reason)[point]})'))
    poses = np.atleast_2d(solution.pose)
    twists = (None, None)
    if velocities is not None:
        try:
            twist = platform_twist(geometry, poses, velocities)
        except ValueError as error:
            return GoalMotion(Finding(findings.INVALID_GOAL, f'the leg velocities: {error}'))
        twists = (twist[:, :3], twist[:, 3:])
    try:
        trajectory = PoseTrajectory(times, poses[:, :3], euler_zyx_to_matrix(poses[:, 3:]),
                                    *twists)
    except ValueError as error:
        return GoalMotion(Finding(findings.INVALID_GOAL, str(error)))
    return GoalMotion(None, trajectory=trajectory)


def angular_velocities(angles, rates):
    """
    Angular velocities (base frame) of roll, pitch, yaw rates, for ``R = Rz Ry Rx``.

    ``w = yaw' e_z + pitch' Rz e_y + roll' Rz Ry e_x``.

    :param angles: ``(roll, pitch, yaw)``, radians, shape (N, 3); ``rates`` their rates.
    :returns: rad/s, shape (N, 3).
    """
    roll_rate, pitch_rate, yaw_rate = np.moveaxis(np.asarray(rates, dtype=float), -1, 0)
    pitch, yaw = angles[..., 1], angles[..., 2]
    cb, sb, cg, sg = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.stack([-sg * pitch_rate + cg * cb * roll_rate,
                     cg * pitch_rate + sg * cb * roll_rate,
                     yaw_rate - sb * roll_rate], axis=-1)


def angular_accelerations(angles, rates, second_rates):
    """
    Angular accelerations (base frame) of roll, pitch, yaw and their first and second rates.

    The time derivative of :func:`angular_velocities`, rad/s^2, shape (N, 3).
    """
    da, db, dg = np.moveaxis(np.asarray(rates, dtype=float), -1, 0)
    dda, ddb, ddg = np.moveaxis(np.asarray(second_rates, dtype=float), -1, 0)
    pitch, yaw = angles[..., 1], angles[..., 2]
    cb, sb, cg, sg = np.cos(pitch), np.sin(pitch), np.cos(yaw), np.sin(yaw)
    return np.stack([
        -cg * dg * db - sg * ddb + (-sg * dg * cb - cg * sb * db) * da + cg * cb * dda,
        -sg * dg * db + cg * ddb + (cg * dg * cb - sg * sb * db) * da + sg * cb * dda,
        ddg - cb * db * da - sb * dda], axis=-1)


def _cartesian_motion(times, positions, velocities, accelerations, frame_id) -> GoalMotion:
    """Return the tool frame's waypoints of a Cartesian goal, for ``plan_trajectory``."""
    angles = positions[:, 3:]
    waypoints = {'times': times, 'positions': positions[:, :3],
                 'quaternions': matrix_to_quaternion(euler_zyx_to_matrix(angles)),
                 'frame_id': frame_id}
    if velocities is not None:
        waypoints['velocities'] = velocities[:, :3]
        waypoints['angular_velocities'] = angular_velocities(angles, velocities[:, 3:])
        if accelerations is not None:
            waypoints['accelerations'] = accelerations[:, :3]
            waypoints['angular_accelerations'] = angular_accelerations(
                angles, velocities[:, 3:], accelerations[:, 3:])
    return GoalMotion(None, tool_waypoints=waypoints)


@dataclass(frozen=True)
class JointState:
    """
    A state of a goal's joints, in its set's order.

    :param positions: shape (6,).
    :param velocities: shape (6,), or ``None`` (not known).
    """

    positions: np.ndarray
    velocities: Optional[np.ndarray] = None


class JointSpace:
    """
    A goal's joints: the desired state of a planned trajectory and the measured state in them.

    :param kind: :data:`LEGS` or :data:`CARTESIAN`.
    :param geometry: the platform (forward kinematics of measured legs, for Cartesian goals).
    :param actuators: the legs' names and offsets.
    :param frames: the frame tree (the tool frame of Cartesian goals).
    :param frame_id: the frame of a Cartesian goal's poses.
    """

    def __init__(self, kind: str, geometry, actuators: ActuatorInterface,
                 frames: Optional[FrameTree] = None, frame_id: str = ''):
        self.kind = kind
        self.geometry = geometry
        self.actuators = actuators
        self.frames = frames if frames is not None else FrameTree()
        self.frame_id = frame_id
        self._guess = None

    def desired(self, trajectory, time: float) -> JointState:
        """
        Return the desired state of a timed trajectory at clock time ``time`` (held at ends).

        Legs: positions and velocities; Cartesian: positions only (the tool frame's pose).
        """
        samples = trajectory.sample(np.array([float(time)]))
        if self.kind == LEGS:
            legs = leg_states(self.geometry, samples)
            return JointState(self.actuators.positions(legs.lengths[0]), legs.velocities[0])
        pose = np.concatenate([samples.positions[0], matrix_to_euler_zyx(samples.rotations[0])])
        return JointState(self.tool_pose(pose))

    def tool_pose(self, platform_pose) -> np.ndarray:
        """Return the tool frame's x, y, z, roll, pitch, yaw of a platform pose (base frame)."""
        return np.asarray(self.frames.tool_pose_vector(platform_pose, self.frame_id), dtype=float)

    def actual(self, positions, velocities=None) -> Optional[JointState]:
        """
        Return the measured state in the goal's joints, from actuator positions (leg order).

        Cartesian: the tool frame's pose by forward kinematics (started at the last one);
        ``None`` when it cannot be found.
        """
        positions = np.asarray(positions, dtype=float)
        if self.kind == LEGS:
            return JointState(positions, None if velocities is None
                              else np.asarray(velocities, dtype=float))
        lengths = self.actuators.lengths(positions)
        try:
            solution = forward_kinematics(self.geometry, lengths, self._guess)
        except ValueError:
            return None
        if not solution.converged:
            return None
        self._guess = np.array(solution.pose)
        return JointState(self.tool_pose(solution.pose))

    def error(self, desired: JointState, actual: JointState) -> JointState:
        """Desired minus actual (angles wrapped to [-pi, pi)); velocities when both have them."""
        velocities = None
        if desired.velocities is not None and actual.velocities is not None:
            velocities = desired.velocities - actual.velocities
        return JointState(_difference(desired.positions, actual.positions, self.kind),
                          velocities)
