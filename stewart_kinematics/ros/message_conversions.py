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
from geometry_msgs.msg import Pose, Twist
from nav_msgs.msg import Path
import numpy as np
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, MultiArrayDimension

from stewart_kinematics.model.actuators import ActuatorInterface
from stewart_kinematics.model.kinematics import as_leg_lengths
from stewart_kinematics.model.rotations import (
    euler_zyx_to_quaternion,
    matrix_to_quaternion,
    normalize_quaternion,
    quaternion_to_euler_zyx,
)
from stewart_kinematics.motion.leg_trajectory import LegTrajectory
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
    Six leg lengths in metres from a std_msgs/msg/Float64MultiArray.

    ``layout.data_offset`` is honoured; the layout's dimensions are not required (a bare
    ``data: [...]`` from ``ros2 topic pub`` is accepted).

    :raises ValueError: if there are not exactly six values after the offset, or a value is
        not finite and positive.
    """
    data = message.data
    if not message.layout.data_offset and len(data) == 6:
        # The common case, checked in floats (a sum is finite only when each term is).
        values = list(data)
        if math.isfinite(sum(values)) and min(values) > 0.0:
            return np.array(values)
    data = np.asarray(data, dtype=float)[message.layout.data_offset:]
    if data.shape != (6,):
        raise ValueError(
            f'expected 6 leg lengths (leg 1..6, metres), got {data.size}: {data.tolist()}')
    return as_leg_lengths(data)


def joint_state_message(header, lengths, velocities=None,
                        actuators: ActuatorInterface = DEFAULT_ACTUATORS) -> JointState:
    """
    sensor_msgs/msg/JointState of the six legs as prismatic joints.

    :param header: std_msgs/msg/Header to carry through (stamp of the pose it comes from).
    :param lengths: the leg lengths in metres, shape (6,); the message carries the actuator
        positions, ``length - offset``.
    :param velocities: leg velocities in metres per second, shape (6,), or ``None`` if unknown
        (the message's velocity list is then empty, as JointState allows).
    :param actuators: joint names and offsets (default ``leg_1`` .. ``leg_6``, zero offsets).
    """
    message = JointState(header=header, name=list(actuators.joint_names))
    message.position = actuators.positions(lengths).tolist()
    if velocities is not None:
        message.velocity = np.asarray(velocities, dtype=float).tolist()
    return message


def legs_from_joint_state(message: JointState,
                          actuators: ActuatorInterface = DEFAULT_ACTUATORS):
    """
    Leg lengths, and leg velocities if given, from a JointState naming the legs' joints.

    Joints are matched by name, in any order; other joints are ignored. Lengths are the
    positions plus the actuator offsets.

    :returns: ``(lengths, velocities)``: metres, shape (6,); m/s, shape (6,) or ``None``.
        The velocities are not checked: a driver that sends NaN velocities with good
        positions still gives a pose, and the twist's own check refuses the velocities.
    :raises ValueError: if a leg is missing, or a length is not finite and positive.
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
    lengths = as_leg_lengths(actuators.lengths(np.asarray(message.position, dtype=float)[order]))
    velocities = None
    if len(message.velocity) == len(names):
        velocities = np.asarray(message.velocity, dtype=float)[order]
    return lengths, velocities


def seconds(duration) -> float:
    """Seconds of a builtin_interfaces/msg/Duration."""
    return duration.sec + duration.nanosec * 1e-9


def duration_message(value: float) -> Duration:
    """builtin_interfaces/msg/Duration of ``value`` seconds (>= 0), to the nanosecond."""
    nanoseconds = int(round(value * 1e9))
    return Duration(sec=nanoseconds // 1_000_000_000, nanosec=nanoseconds % 1_000_000_000)


def check_frame(frame_id: str, base_frame: str, what: str) -> None:
    """
    Refuse a frame other than ``base_frame`` (an empty frame counts as ``base_frame``).

    :raises ValueError: naming the frame and what to do.
    """
    if frame_id and frame_id != base_frame:
        raise ValueError(f"{what} is in frame '{frame_id}', not in base_frame "
                         f"'{base_frame}'; transform it first")


def pose_trajectory_from_message(message: MultiDOFJointTrajectory, base_frame: str) -> dict:
    """
    Waypoints of a trajectory_msgs/msg/MultiDOFJointTrajectory of one joint, the platform.

    Transforms place the platform frame in the base frame; velocities (twists, base frame)
    are used when every point has one; accelerations are not used (the interpolation is a
    cubic through positions and velocities).

    :returns: keyword arguments of :meth:`stewart_kinematics.PoseTrajectory.from_quaternions`:
        ``times`` (time_from_start, seconds), ``positions``, ``quaternions`` and, when given,
        ``velocities`` and ``angular_velocities``.
    :raises ValueError: if the frame is not ``base_frame``, there is not one joint, a point
        has not one transform, only some points have velocities, or a value is not finite.
    """
    check_frame(message.header.frame_id, base_frame, 'the trajectory')
    if len(message.joint_names) > 1:
        raise ValueError(f'the trajectory must have one joint, the platform; got '
                         f'{len(message.joint_names)}: {list(message.joint_names)}')
    points = message.points
    if any(len(point.transforms) != 1 for point in points):
        raise ValueError('every trajectory point must have exactly one transform (the '
                         'platform in the base frame)')
    transforms = [point.transforms[0] for point in points]
    arguments = {
        'times': [seconds(point.time_from_start) for point in points],
        'positions': [[t.translation.x, t.translation.y, t.translation.z] for t in transforms],
        'quaternions': [_quaternion(t.rotation, index) for index, t in enumerate(transforms)],
    }
    with_velocity = [len(point.velocities) == 1 for point in points]
    if all(with_velocity) and points:
        twists = [point.velocities[0] for point in points]
        arguments['velocities'] = [[v.linear.x, v.linear.y, v.linear.z] for v in twists]
        arguments['angular_velocities'] = [[v.angular.x, v.angular.y, v.angular.z]
                                           for v in twists]
    elif any(len(point.velocities) for point in points):
        raise ValueError('velocities must be given for every point (one twist each) or for '
                         'none')
    return arguments


def path_from_message(message: Path, base_frame: str):
    """
    Positions and quaternions of the waypoints of a nav_msgs/msg/Path (no timing).

    :returns: ``(positions (N, 3), quaternions (N, 4))``, metres and unit quaternions.
    :raises ValueError: if the path or a pose is in another frame than ``base_frame``, or a
        value is not finite.
    """
    check_frame(message.header.frame_id, base_frame, 'the path')
    positions, quaternions = [], []
    for index, stamped in enumerate(message.poses):
        check_frame(stamped.header.frame_id, base_frame, f'pose {index} of the path')
        point = stamped.pose.position
        positions.append([point.x, point.y, point.z])
        quaternions.append(_quaternion(stamped.pose.orientation, index))
    return np.array(positions, dtype=float).reshape(-1, 3), np.array(quaternions).reshape(-1, 4)


def _quaternion(orientation, index):
    try:
        return normalize_quaternion([orientation.x, orientation.y, orientation.z, orientation.w])
    except ValueError as error:
        raise ValueError(f'point {index}: {error}') from error


def joint_trajectory_message(header, trajectory: LegTrajectory) -> JointTrajectory:
    """
    trajectory_msgs/msg/JointTrajectory of a leg trajectory, for joint_trajectory_controller.

    Joint names, and per point the actuator positions, velocities, accelerations and
    time_from_start, as the controller takes them on its ``joint_trajectory`` topic.
    """
    message = JointTrajectory(header=header, joint_names=list(trajectory.joint_names))
    message.points = [
        JointTrajectoryPoint(positions=positions, velocities=velocities,
                             accelerations=accelerations,
                             time_from_start=duration_message(time))
        for time, positions, velocities, accelerations in zip(
            trajectory.times.tolist(), trajectory.positions.tolist(),
            trajectory.velocities.tolist(), trajectory.accelerations.tolist())]
    return message


def pose_message(position, rotation) -> Pose:
    """geometry_msgs/msg/Pose of a position (metres) and rotation matrix; unit quaternion."""
    message = Pose()
    message.position.x, message.position.y, message.position.z = (float(v) for v in position)
    x, y, z, w = matrix_to_quaternion(rotation).tolist()
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
