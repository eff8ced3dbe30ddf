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

from geometry_msgs.msg import Pose, Twist
import numpy as np
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64MultiArray, MultiArrayDimension

from stewart_kinematics.kinematics import as_leg_lengths
from stewart_kinematics.rotations import (
    euler_zyx_to_quaternion,
    normalize_quaternion,
    quaternion_to_euler_zyx,
)

#: Label of the one layout dimension of a leg array message.
LEG_DIMENSION_LABEL = 'leg'
#: Names of the six legs as prismatic joints in sensor_msgs/msg/JointState, leg 1..6.
LEG_JOINT_NAMES = tuple(f'leg_{leg}' for leg in range(1, 7))
#: A quaternion whose norm is this far from 1 is normalised with a warning.
QUATERNION_NORM_TOLERANCE = 1e-6


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
    data = np.asarray(message.data, dtype=float)[message.layout.data_offset:]
    if data.shape != (6,):
        raise ValueError(
            f'expected 6 leg lengths (leg 1..6, metres), got {data.size}: {data.tolist()}')
    return as_leg_lengths(data)


def joint_state_message(header, lengths, velocities=None) -> JointState:
    """
    sensor_msgs/msg/JointState of the six legs as prismatic joints ``leg_1`` .. ``leg_6``.

    :param header: std_msgs/msg/Header to carry through (stamp of the pose it comes from).
    :param lengths: positions, the leg lengths in metres, shape (6,).
    :param velocities: leg velocities in metres per second, shape (6,), or ``None`` if unknown
        (the message's velocity list is then empty, as JointState allows).
    """
    message = JointState(header=header, name=list(LEG_JOINT_NAMES))
    message.position = np.asarray(lengths, dtype=float).tolist()
    if velocities is not None:
        message.velocity = np.asarray(velocities, dtype=float).tolist()
    return message


def legs_from_joint_state(message: JointState):
    """
    Leg lengths, and leg velocities if given, from a JointState naming ``leg_1`` .. ``leg_6``.

    Joints are matched by name, in any order; other joints are ignored.

    :returns: ``(lengths, velocities)``: metres, shape (6,); m/s, shape (6,) or ``None``.
    :raises ValueError: if a leg is missing, or a length is not finite and positive.
    """
    names = list(message.name)
    missing = [name for name in LEG_JOINT_NAMES if name not in names]
    if missing or len(message.position) != len(names):
        raise ValueError(
            f'joint state must give a position for each of {", ".join(LEG_JOINT_NAMES)}; '
            f'missing: {", ".join(missing) or "positions"}')
    order = [names.index(name) for name in LEG_JOINT_NAMES]
    lengths = as_leg_lengths(np.asarray(message.position, dtype=float)[order])
    velocities = None
    if len(message.velocity) == len(names):
        velocities = np.asarray(message.velocity, dtype=float)[order]
        if not np.all(np.isfinite(velocities)):
            raise ValueError(f'leg velocities must be finite, got {velocities.tolist()}')
    return lengths, velocities


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
