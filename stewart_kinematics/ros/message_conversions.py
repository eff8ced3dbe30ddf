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
Conversions between ROS messages and the numpy arrays of the kinematics core.

The only module besides the nodes that imports message types. Every ``*_from_message`` function
raises ``ValueError`` with a sentence a user can act on when a message cannot be used.
"""

import math

from builtin_interfaces.msg import Duration
from geometry_msgs.msg import Pose, Twist, WrenchStamped
from nav_msgs.msg import Path
import numpy as np
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, MultiArrayDimension

from stewart_kinematics.model.actuators import ActuatorInterface
from stewart_kinematics.model.arrays import preview
from stewart_kinematics.model.rotations import (
    euler_zyx_to_quaternion,
    matrix_to_quaternion,
    normalize_quaternion,
    quaternion_to_euler_zyx,
)
from stewart_kinematics.motion.leg_trajectory import LegTrajectory
from stewart_kinematics.motion.leg_trajectory import MAX_POINTS as MAX_LEG_POINTS
from stewart_kinematics.motion.pose_trajectory import MAX_WAYPOINTS
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint, MultiDOFJointTrajectory

#: Label of the one layout dimension of a leg array message.
LEG_DIMENSION_LABEL = 'leg'
#: A quaternion whose norm is this far from 1 is normalised with a warning.
QUATERNION_NORM_TOLERANCE = 1e-6
#: The default actuator interface: joints leg_1 .. leg_6, zero offsets (position = length).
DEFAULT_ACTUATORS = ActuatorInterface()


def position_quaternion_from_message(message: Pose):
    """
    Position and unit quaternion of a geometry_msgs/msg/Pose.

    :returns: ``(position, quaternion, norm)``: position in metres, shape (3,); unit
        quaternion ``(x, y, z, w)``, shape (4,); and the norm the message's quaternion had, so
        that the caller can warn about a non-unit one.
    :raises ValueError: if a coordinate is not finite, or the quaternion is zero or not finite.
    """
    point, orientation = message.position, message.orientation
    position = [point.x, point.y, point.z]
    if not all(map(math.isfinite, position)):
        raise ValueError(f'position must be finite (metres), got {position}')
    quaternion = [orientation.x, orientation.y, orientation.z, orientation.w]
    unit = normalize_quaternion(quaternion)
    return np.array(position), unit, math.sqrt(sum(value * value for value in quaternion))


def pose_from_message(message: Pose) -> np.ndarray:
    """
    Pose ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) of a geometry_msgs/msg/Pose.

    :raises ValueError: as :func:`position_quaternion_from_message`.
    """
    position, quaternion, _ = position_quaternion_from_message(message)
    return np.concatenate([position, quaternion_to_euler_zyx(quaternion)])


def pose_to_message(pose) -> Pose:
    """
    geometry_msgs/msg/Pose of a pose ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).

    The quaternion is unit, with ``w >= 0``.
    """
    pose = np.asarray(pose, dtype=float)
    message = Pose()
    message.position.x, message.position.y, message.position.z = pose[:3].tolist()
    x, y, z, w = euler_zyx_to_quaternion(pose[3:]).tolist()
    message.orientation.x, message.orientation.y = x, y
    message.orientation.z, message.orientation.w = z, w
    return message


def legs_to_message(values) -> Float64MultiArray:
    """
    std_msgs/msg/Float64MultiArray of six per-leg values, leg 1..6.

    The layout has one dimension labelled ``leg`` of size 6, so that ``ros2 topic echo`` and
    generic tools show what the numbers are.
    """
    message = Float64MultiArray()
    message.layout.dim = [MultiArrayDimension(label=LEG_DIMENSION_LABEL, size=6, stride=6)]
    message.data = np.asarray(values, dtype=float).tolist()
    return message


def leg_lengths_from_message(message: Float64MultiArray) -> np.ndarray:
    """
    Six leg lengths in metres from a std_msgs/msg/Float64MultiArray, converted, not judged.

    ``layout.data_offset`` is honoured; the layout's dimensions are not required (a bare
    ``data: [...]`` from ``ros2 topic pub`` is accepted). The values are checked once, where
    they enter the core: :meth:`stewart_kinematics.PoseTracker.update` refuses lengths that are
    not finite and positive (``invalid_lengths``).

    :raises ValueError: if there are not exactly six values after the offset.
    """
    data = message.data
    if not message.layout.data_offset and len(data) == 6:
        return np.array(data, dtype=float)
    data = np.asarray(data, dtype=float)[message.layout.data_offset:]
    if data.shape != (6,):
        raise ValueError(
            f'expected 6 leg lengths (leg 1..6, metres), got {data.size}: {preview(data)}')
    return data


def joint_state_message(header, lengths, velocities=None,
                        actuators: ActuatorInterface = DEFAULT_ACTUATORS,
                        efforts=None) -> JointState:
    """
    sensor_msgs/msg/JointState of the six legs as prismatic joints.

    :param header: std_msgs/msg/Header to carry through (stamp of the pose it comes from).
    :param lengths: the leg lengths in metres, shape (6,); the message carries the actuator
        positions, ``length - offset``.
    :param velocities: leg velocities in metres per second, shape (6,), or ``None`` if unknown
        (the message's velocity list is then empty, as JointState allows).
    :param actuators: joint names and offsets (default ``leg_1`` .. ``leg_6``, zero offsets).
    :param efforts: leg forces in newtons, positive pushing, shape (6,), or ``None`` (the
        message's effort list is then empty).
    """
    message = JointState(header=header, name=list(actuators.joint_names))
    message.position = actuators.positions(lengths).tolist()
    if velocities is not None:
        message.velocity = np.asarray(velocities, dtype=float).tolist()
    if efforts is not None:
        message.effort = np.asarray(efforts, dtype=float).tolist()
    return message


def legs_from_joint_state(message: JointState,
                          actuators: ActuatorInterface = DEFAULT_ACTUATORS):
    """
    Leg lengths, and leg velocities if given, from a JointState naming the legs' joints.

    Joints are matched by name, in any order; other joints are ignored. Lengths are the
    positions plus the actuator offsets.

    :returns: ``(lengths, velocities)``: metres, shape (6,); m/s, shape (6,) or ``None``.
        Neither is judged here: :meth:`stewart_kinematics.PoseTracker.update` checks the
        lengths where they enter the core, and the twist's own check the velocities (a driver
        that sends NaN velocities with good positions still gives a pose).
    :raises ValueError: if a leg is missing or repeated, or the positions do not match the
        names.
    """
    names = list(message.name)
    if len(message.position) != len(names):
        raise ValueError(f'joint state must give a position for each of its {len(names)} '
                         f'names, got {len(message.position)}')
    try:
        order = actuators.order(names)
    except ValueError as error:
        raise ValueError(f'joint state must give a position for each of '
                         f'{", ".join(actuators.joint_names)}: {error}') from error
    lengths = actuators.lengths(np.asarray(message.position, dtype=float)[order])
    velocities = None
    if len(message.velocity) == len(names):
        velocities = np.asarray(message.velocity, dtype=float)[order]
    return lengths, velocities


def leg_efforts_from_joint_state(message: JointState,
                                 actuators: ActuatorInterface = DEFAULT_ACTUATORS):
    """
    Return the measured leg forces of a JointState naming the legs' joints, or ``None``.

    Matched by name like the positions (:func:`legs_from_joint_state`, which has checked the
    names); not judged here: :func:`stewart_kinematics.dynamics.external_wrench.
    external_wrench` refuses forces that are not finite.

    :returns: the legs' efforts, newtons, positive pushing the platform away from the base,
        shape (6,); ``None`` when the message carries no efforts (an empty list).
    :raises ValueError: if there are efforts but not one for each of the message's names.
    """
    names = list(message.name)
    efforts = message.effort
    if len(efforts) == 0:
        return None
    if len(efforts) != len(names):
        raise ValueError(f'joint state efforts must give one force (N) for each of its '
                         f'{len(names)} names, got {len(efforts)}')
    return np.asarray(efforts, dtype=float)[actuators.order(names)]


def wrench_to_message(header, wrench) -> WrenchStamped:
    """
    geometry_msgs/msg/WrenchStamped of ``[Fx, Fy, Fz, Mx, My, Mz]`` (N, N m).

    :param header: std_msgs/msg/Header: the frame the wrench is expressed in (its moment about
        that frame's origin) and the stamp.
    """
    message = WrenchStamped(header=header)
    force, torque = message.wrench.force, message.wrench.torque
    force.x, force.y, force.z, torque.x, torque.y, torque.z = (float(v) for v in wrench)
    return message


def seconds(duration, name: str = 'time_from_start') -> float:
    """
    Seconds of a builtin_interfaces/msg/Duration (or Time).

    :param name: what it is, for the refusal.
    :raises ValueError: for a malformed one (``nanosec`` not below 1e9:
        :func:`malformed_time_reason`), which would move the time on by whole seconds.
    """
    reason = malformed_time_reason(duration, name)
    if reason:
        raise ValueError(reason)
    return duration.sec + duration.nanosec * 1e-9


def stamp_nanoseconds(stamp, name: str = 'header.stamp') -> int:
    """
    Integer nanoseconds of a builtin_interfaces/msg/Time.

    :raises ValueError: for a malformed one (:func:`malformed_time_reason`).
    """
    reason = malformed_time_reason(stamp, name)
    if reason:
        raise ValueError(reason)
    return stamp.sec * 1_000_000_000 + stamp.nanosec


def malformed_time_reason(time, name: str) -> str:
    """
    Return ``''`` for a well-formed builtin_interfaces Time or Duration, else why not.

    ``nanosec`` must be below 1e9 (rclpy does not check it): 4e9 would silently move the
    time 4 s on.

    :param name: what the time is, for the reason (``'header.stamp'``).
    """
    if time.nanosec >= 1_000_000_000:
        return (f'{name} is malformed: nanosec {time.nanosec} is not below 1000000000 '
                f'(sec {time.sec}); a time is sec plus nanosec in [0, 1e9)')
    return ''


def duration_message(value: float) -> Duration:
    """builtin_interfaces/msg/Duration of ``value`` seconds (>= 0), to the nanosecond."""
    nanoseconds = int(round(value * 1e9))
    return Duration(sec=nanoseconds // 1_000_000_000, nanosec=nanoseconds % 1_000_000_000)


def pose_trajectory_from_message(message: MultiDOFJointTrajectory) -> dict:
    """
    Waypoints of a trajectory_msgs/msg/MultiDOFJointTrajectory of one joint, the tool frame.

    Each point's transform places the tool frame (by default the platform frame) in the
    message's frame; its twist (about the tool frame's origin, in that frame) is used when
    every point has one, and its acceleration when every point has one too (the trajectory is
    then C2, see :class:`stewart_kinematics.PoseTrajectory`). The times are not checked here:
    :class:`stewart_kinematics.MotionPlanner` says what is wrong with them.

    :returns: keyword arguments of :meth:`stewart_kinematics.MotionPlanner.plan_trajectory`:
        ``times`` (time_from_start, seconds), ``positions`` (N, 3), ``quaternions`` (N, 4)
        and, when given, ``velocities``, ``angular_velocities``, ``accelerations`` and
        ``angular_accelerations`` (N, 3) each; ``frame_id``, the header's.
    :raises ValueError: if there is not one joint, a point has not one transform, only some
        points have velocities (or accelerations), or a quaternion is zero or not finite.
    """
    if len(message.joint_names) > 1:
        raise ValueError(f'the trajectory must have one joint, the platform; got '
                         f'{len(message.joint_names)}: {preview(message.joint_names)}')
    points = message.points
    _check_count(len(points))
    if any(len(point.transforms) != 1 for point in points):
        raise ValueError('every trajectory point must have exactly one transform (the '
                         'platform, or the tool frame, in the frame of the header)')
    transforms = [point.transforms[0] for point in points]
    arguments = {
        'times': np.array([seconds(point.time_from_start, f"point {index}'s time_from_start")
                           for index, point in enumerate(points)], dtype=float),
        'positions': _rows([(t.translation.x, t.translation.y, t.translation.z)
                            for t in transforms], 3),
        'quaternions': _unit_quaternions(_rows([(t.rotation.x, t.rotation.y, t.rotation.z,
                                                 t.rotation.w) for t in transforms], 4)),
        'frame_id': message.header.frame_id,
    }
    for field, names in (('velocities', ('velocities', 'angular_velocities')),
                         ('accelerations', ('accelerations', 'angular_accelerations'))):
        counts = [len(getattr(point, field)) for point in points]
        if points and all(count == 1 for count in counts):
            twists = [getattr(point, field)[0] for point in points]
            arguments[names[0]] = _rows([(v.linear.x, v.linear.y, v.linear.z)
                                         for v in twists], 3)
            arguments[names[1]] = _rows([(v.angular.x, v.angular.y, v.angular.z)
                                         for v in twists], 3)
        elif any(counts):
            raise ValueError(f'{field} must be given for every point (one twist each) or for '
                             'none')
    return arguments


def vehicle_preview_from_message(message: MultiDOFJointTrajectory):
    """
    Return the vehicle's motion to come from a trajectory_msgs/msg/MultiDOFJointTrajectory.

    Each point gives, ``time_from_start`` after ``header.stamp``, the specific force in
    ``accelerations[0].linear`` (m/s^2, with gravity, as an IMU's ``linear_acceleration``)
    and the angular velocity in ``velocities[0].angular`` (rad/s); ``transforms``,
    ``joint_names`` and the other twist halves are not used.

    :returns: ``(offsets (M,), specific_force (M, 3), angular_velocity (M, 3), frame_id)``:
        seconds after ``header.stamp``, in the header's frame. The values are not checked
        here: :meth:`stewart_kinematics.cueing.MotionCueing.set_preview` says what is wrong
        with them.
    :raises ValueError: naming the first point without one acceleration or one velocity, or
        with a malformed ``time_from_start``, for a malformed ``header.stamp``, or for no
        points or more than a trajectory may have.
    """
    points = message.points
    _check_count(len(points))
    if not points:
        raise ValueError('the preview has no points: give the drive to come, at least one '
                         'point (10 to 100 a second over the horizon)')
    reason = malformed_time_reason(message.header.stamp, "the preview's header.stamp")
    if reason:
        raise ValueError(reason)
    offsets = []
    for index, point in enumerate(points):
        offsets.append(seconds(point.time_from_start, f"preview point {index}'s time_from_start"))
        if len(point.accelerations) != 1 or len(point.velocities) != 1:
            raise ValueError(
                f'preview point {index} must have one acceleration (its linear part: the '
                'specific force) and one velocity (its angular part: the angular velocity), '
                f'got {len(point.accelerations)} and {len(point.velocities)}')
    forces = _rows([(p.accelerations[0].linear.x, p.accelerations[0].linear.y,
                     p.accelerations[0].linear.z) for p in points], 3)
    rates = _rows([(p.velocities[0].angular.x, p.velocities[0].angular.y,
                    p.velocities[0].angular.z) for p in points], 3)
    return np.array(offsets, dtype=float), forces, rates, message.header.frame_id


def path_from_message(message: Path):
    """
    Positions and quaternions of the waypoints of a nav_msgs/msg/Path (no timing).

    :returns: ``(positions (N, 3), quaternions (N, 4), frame_id)``, metres and unit
        quaternions, in the path's frame (a pose's own frame may be empty or the same).
    :raises ValueError: if a pose is in another frame than the path, or a quaternion is zero
        or not finite.
    """
    frame_id = message.header.frame_id
    _check_count(len(message.poses))
    for index, stamped in enumerate(message.poses):
        if stamped.header.frame_id and stamped.header.frame_id != frame_id:
            raise ValueError(f'pose {index} of the path is in frame '
                             f"{preview(stamped.header.frame_id)}, not in the path's frame "
                             f'{preview(frame_id)}')
    poses = [stamped.pose for stamped in message.poses]
    positions = _rows([(p.position.x, p.position.y, p.position.z) for p in poses], 3)
    quaternions = _unit_quaternions(_rows([(p.orientation.x, p.orientation.y,
                                            p.orientation.z, p.orientation.w)
                                           for p in poses], 4))
    return positions, quaternions, frame_id


def _check_count(count):
    """Refuse more waypoints than a trajectory may have before converting any (ValueError)."""
    if count > MAX_WAYPOINTS:
        raise ValueError(f'a trajectory may have at most {MAX_WAYPOINTS:,} waypoints, got '
                         f'{count:,}: send it in parts')


def _rows(values, width):
    """Return a float array of shape (N, width), also for no rows."""
    return np.array(values, dtype=float).reshape(-1, width)


def _unit_quaternions(quaternions):
    """
    Normalise quaternions ``(x, y, z, w)``, shape (N, 4).

    :raises ValueError: naming the first point whose quaternion is zero or not finite.
    """
    norms = np.linalg.norm(quaternions, axis=-1)
    bad = ~np.isfinite(norms) | (norms < 1e-12)
    if bad.any():
        index = int(np.argmax(bad))
        raise ValueError(f'point {index}: a quaternion must be finite and not zero, got '
                         f'{quaternions[index].tolist()}')
    return quaternions / norms[:, None]


def joint_trajectory_message(header, trajectory: LegTrajectory) -> JointTrajectory:
    """
    trajectory_msgs/msg/JointTrajectory of a leg trajectory, for joint_trajectory_controller.

    Joint names, and per point the actuator positions, velocities, accelerations, efforts
    (the leg forces, newtons, when the trajectory has them; empty otherwise) and
    time_from_start, as the controller takes them on its ``joint_trajectory`` topic.
    """
    message = JointTrajectory(header=header, joint_names=list(trajectory.joint_names))
    efforts = ([[]] * len(trajectory.times) if trajectory.efforts is None
               else trajectory.efforts.tolist())
    message.points = [
        JointTrajectoryPoint(positions=positions, velocities=velocities,
                             accelerations=accelerations, effort=effort,
                             time_from_start=duration_message(time))
        for time, positions, velocities, accelerations, effort in zip(
            trajectory.times.tolist(), trajectory.positions.tolist(),
            trajectory.velocities.tolist(), trajectory.accelerations.tolist(), efforts)]
    return message


def leg_trajectory_from_message(message: JointTrajectory,
                                actuators: ActuatorInterface = DEFAULT_ACTUATORS) -> dict:
    """
    Return the points of a JointTrajectory of the legs' joints, converted, not judged.

    Joints are matched by name, in any order; other joints are ignored. Positions become leg
    lengths (plus the actuator offsets). The values are checked where they enter the core
    (:func:`stewart_kinematics.motion.mock_actuators.trajectory_command`).

    :returns: keyword arguments of ``trajectory_command``: ``start`` (the header stamp,
        integer nanoseconds; 0 for "on arrival": the caller places it on its clock),
        ``times`` (time_from_start, seconds, (M,)), ``lengths`` (metres, (M, 6)) and
        ``velocities``, ``accelerations`` (M, 6) or ``None`` when no point gives them.
    :raises ValueError: if a leg's joint is missing or repeated, there are more than
        :data:`~stewart_kinematics.motion.leg_trajectory.MAX_POINTS` points, or a point's
        values are not one per joint name (velocities and accelerations: on every point or
        none).
    """
    names = list(message.joint_names)
    try:
        order = actuators.order(names)
    except ValueError as error:
        raise ValueError(f'a leg trajectory must name each of '
                         f'{", ".join(actuators.joint_names)}: {error}') from error
    points = message.points
    if len(points) > MAX_LEG_POINTS:
        raise ValueError(f'a leg trajectory may have at most {MAX_LEG_POINTS:,} points, got '
                         f'{len(points):,}: send it in parts')
    arguments = {
        'start': stamp_nanoseconds(message.header.stamp),
        'times': np.array([seconds(point.time_from_start, f"point {index}'s time_from_start")
                           for index, point in enumerate(points)], dtype=float)}
    for field, key in (('positions', 'lengths'), ('velocities', 'velocities'),
                       ('accelerations', 'accelerations')):
        counts = {len(getattr(point, field)) for point in points}
        if not points:   # refused by the core, which says so
            arguments[key] = np.zeros((0, 6)) if field == 'positions' else None
            continue
        if field != 'positions' and counts <= {0}:
            arguments[key] = None
            continue
        if counts != {len(names)}:
            raise ValueError(f'every point must give {field} for each of its {len(names)} '
                             f'joint names{"" if field == "positions" else " (or none)"}, got '
                             f'{preview(sorted(counts))} values')
        values = np.array([getattr(point, field) for point in points],
                          dtype=float).reshape(-1, len(names))[:, order]
        arguments[key] = actuators.lengths(values) if field == 'positions' else values
    return arguments


def pose_message(position, rotation) -> Pose:
    """geometry_msgs/msg/Pose of a position (metres) and rotation matrix; unit quaternion."""
    message = Pose()
    message.position.x, message.position.y, message.position.z = (float(v) for v in position)
    x, y, z, w = matrix_to_quaternion(rotation).tolist()
    message.orientation.x, message.orientation.y = x, y
    message.orientation.z, message.orientation.w = z, w
    return message


def command_pose_message(command) -> Pose:
    """
    geometry_msgs/msg/Pose of a pose command the gate passed: the very numbers it checked.

    :param command: a :class:`~stewart_kinematics.limits.LegCommand` with ``tool_pose``
        (the tool frame's position, metres, and quaternion ``(x, y, z, w)``).
    """
    position, quaternion = command.tool_pose
    message = Pose()
    message.position.x, message.position.y, message.position.z = position.tolist()
    x, y, z, w = quaternion.tolist()
    message.orientation.x, message.orientation.y = x, y
    message.orientation.z, message.orientation.w = z, w
    return message


def twist_from_message(message: Twist) -> np.ndarray:
    """
    ``[vx, vy, vz, wx, wy, wz]`` (m/s, rad/s) of a geometry_msgs/msg/Twist.

    :raises ValueError: if a component is not finite.
    """
    twist = np.array([message.linear.x, message.linear.y, message.linear.z,
                      message.angular.x, message.angular.y, message.angular.z])
    if not np.all(np.isfinite(twist)):
        raise ValueError(f'twist must be finite (m/s, rad/s), got {twist.tolist()}')
    return twist


def twist_to_message(twist) -> Twist:
    """geometry_msgs/msg/Twist of ``[vx, vy, vz, wx, wy, wz]`` (m/s, rad/s)."""
    message = Twist()
    message.linear.x, message.linear.y, message.linear.z = (float(v) for v in twist[:3])
    message.angular.x, message.angular.y, message.angular.z = (float(v) for v in twist[3:])
    return message
