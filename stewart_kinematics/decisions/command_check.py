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
The inverse kinematics side's decision: a commanded pose in, safe leg lengths or every reason out.

:class:`CommandCheck` is what stands between a commanded pose and six actuators, in ik_node and
in a Python user's own control loop alike::

    check = CommandCheck(load_geometry(['config/paper_platform.yaml',
                                        'config/example_limits.yaml']))
    command = check.pose_vector([0.0, 0.0, 0.45, 0.0, 0.0, 0.1])   # or .pose(t, R), or
    #                                                   .pose_quaternion(t, (x, y, z, w))
    if command.accepted:
        actuators.move(command.lengths)          # six finite, positive lengths, metres
    else:
        print(command.reason)                    # every violated limit, leg by leg
    rates = check.twist([0.01, 0.0, 0.0, 0.0, 0.0, 0.0])   # at the last accepted pose

It never raises for input it cannot use and never returns an infinite, NaN or zero length: a
malformed or unreachable pose, or one that breaks a limit of the geometry, comes back refused
with a :class:`~stewart_kinematics.findings.Finding`. Nothing is clamped. Nothing here imports
ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics import findings, limits
from stewart_kinematics.findings import Decision, Finding
from stewart_kinematics.model.arrays import as_float_array
from stewart_kinematics.model.kinematics import leg_lengths, twist_jacobian
from stewart_kinematics.model.rotations import (
    euler_zyx_to_matrix,
    normalize_quaternion,
    quaternion_to_matrix,
)

#: Largest deviation of ``R^T R`` from the identity accepted for a rotation matrix.
ROTATION_TOLERANCE = 1e-6


@dataclass(frozen=True, eq=False)
class LegCommand(Decision):
    """
    The answer to a commanded pose: leg lengths to command, or why not.

    :param lengths: leg lengths l_1..l_6 in metres, shape (6,), finite and positive; ``None``
        when refused.
    :param violations: every limit the pose breaks (:class:`~stewart_kinematics.limits.Violation`),
        also for a refused pose, so that a display can show which legs are at fault; empty
        when the pose could not be evaluated at all.
    :param refusal: why the pose was refused, or ``None`` when accepted.
    """

    lengths: Optional[np.ndarray]
    violations: Tuple[limits.Violation, ...] = ()
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()


@dataclass(frozen=True, eq=False)
class LegVelocityCommand(Decision):
    """
    The answer to a commanded platform twist: leg velocities, or why not.

    :param velocities: rates of change of the leg lengths, metres per second, shape (6,);
        ``None`` when refused.
    :param refusal: why the twist was refused, or ``None`` when accepted.
    """

    velocities: Optional[np.ndarray]
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()


class CommandCheck:
    """
    Turn commanded poses into leg lengths, refusing every pose that is not safe to command.

    The state is the last accepted pose, where :meth:`twist` applies a velocity command.

    :param geometry: the platform and its limits (:class:`stewart_kinematics.Geometry`).
    """

    def __init__(self, geometry):
        self.geometry = geometry
        #: ``(position (3,), rotation (3, 3))`` of the last accepted pose, or ``None``.
        self.last_pose = None

    def pose(self, position, rotation) -> LegCommand:
        """
        Leg lengths of a pose, or the refusal with every reason.

        :param position: platform origin in the base frame, metres, shape (3,).
        :param rotation: platform-to-base rotation matrix, shape (3, 3) (from a quaternion:
            :func:`stewart_kinematics.quaternion_to_matrix`).
        :returns: a :class:`LegCommand`; refused (code ``invalid_pose``, ``unreachable`` or
            ``out_of_limits``) rather than raised.
        """
        try:
            position = as_float_array(position, 'position')
            rotation = as_float_array(rotation, 'rotation')
        except ValueError as error:
            return LegCommand(None, refusal=Finding(findings.INVALID_POSE, str(error)))
        invalid = _invalid_pose(position, rotation)
        if invalid:
            return LegCommand(None, refusal=Finding(findings.INVALID_POSE, invalid))
        return self._command(position, rotation)

    def pose_quaternion(self, position, quaternion) -> LegCommand:
        """
        :meth:`pose` of a position and a quaternion ``(x, y, z, w)``, as geometry_msgs has them.

        A quaternion that is not unit is normalised; a zero or non-finite one is refused.

        :param position: metres, base frame, shape (3,).
        :param quaternion: shape (4,).
        """
        try:
            position = as_float_array(position, 'position')
        except ValueError as error:
            return LegCommand(None, refusal=Finding(findings.INVALID_POSE, str(error)))
        if position.shape != (3,) or not all(map(math.isfinite, position.tolist())):
            return LegCommand(None, refusal=Finding(
                findings.INVALID_POSE,
                f'position must be three finite numbers (metres), got {position.tolist()}'))
        try:
            rotation = quaternion_to_matrix(normalize_quaternion(quaternion))
        except ValueError as error:
            return LegCommand(None, refusal=Finding(findings.INVALID_POSE, str(error)))
        if rotation.shape != (3, 3):
            return LegCommand(None, refusal=Finding(
                findings.INVALID_POSE, f'expected one quaternion (4,), got {rotation.shape}'))
        return self._command(position, rotation)

    def _command(self, position, rotation) -> LegCommand:
        """Decide on a valid position (3,) and rotation matrix (3, 3)."""
        # The lengths first: a leg of length zero (a platform joint on its base joint) has no
        # direction, so the joint angles and the Jacobian of the limits do not exist there.
        with np.errstate(over='ignore', invalid='ignore'):
            try:
                lengths = leg_lengths(self.geometry, position, rotation).tolist()
            except ValueError:   # overflow
                lengths = [math.inf] * 6
        if not all(0.0 < length < math.inf for length in lengths):
            return LegCommand(None, refusal=Finding(
                findings.UNREACHABLE,
                f'its leg lengths must be finite and positive (metres), got {lengths}: '
                'a platform joint on its base joint, or a pose beyond any reach'))
        lengths = np.array(lengths)
        violations = tuple(limits.check_pose(self.geometry, position, rotation))
        if violations:
            return LegCommand(None, violations, findings.out_of_limits('the pose is', violations))
        self.last_pose = position, rotation
        return LegCommand(lengths)

    def pose_vector(self, pose) -> LegCommand:
        """
        :meth:`pose` of ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians; R = Rz Ry Rx).

        :param pose: shape (6,).
        """
        try:
            pose = as_float_array(pose, 'pose')
        except ValueError as error:
            return LegCommand(None, refusal=Finding(findings.INVALID_POSE, str(error)))
        if pose.shape != (6,) or not np.all(np.isfinite(pose)):
            return LegCommand(None, refusal=Finding(
                findings.INVALID_POSE,
                f'a pose must be six finite numbers [X, Y, Z, alpha, beta, gamma] (metres, '
                f'radians), got {pose.tolist()}'))
        return self._command(pose[:3], euler_zyx_to_matrix(pose[3:]))

    def twist(self, twist) -> LegVelocityCommand:
        """
        Leg velocities of a platform twist at the last accepted pose, or the refusal.

        :param twist: ``[vx, vy, vz, wx, wy, wz]``, base frame, m/s and rad/s, shape (6,).
        :returns: a :class:`LegVelocityCommand`; refused (code ``no_pose_yet`` or
            ``invalid_twist``) rather than raised.
        """
        try:
            twist = as_float_array(twist, 'twist')
        except ValueError as error:
            return LegVelocityCommand(None, Finding(findings.INVALID_TWIST, str(error)))
        if twist.shape != (6,) or not np.all(np.isfinite(twist)):
            return LegVelocityCommand(None, Finding(
                findings.INVALID_TWIST,
                f'a twist must be six finite numbers [vx, vy, vz, wx, wy, wz] (m/s, rad/s), '
                f'got {twist.tolist()}'))
        if self.last_pose is None:
            return LegVelocityCommand(None, Finding(
                findings.NO_POSE_YET,
                'no pose accepted yet, so no Jacobian to apply the twist at'))
        with np.errstate(over='ignore', invalid='ignore'):
            velocities = twist_jacobian(self.geometry, *self.last_pose) @ twist
        if not np.all(np.isfinite(velocities)):
            return LegVelocityCommand(None, Finding(
                findings.INVALID_TWIST,
                f'the leg velocities of the twist {twist.tolist()} are beyond the float range '
                '(about 1.8e308): the twist is too large'))
        return LegVelocityCommand(velocities)


def _invalid_pose(position, rotation) -> str:
    """Say what is wrong with a position and a rotation matrix, or return ``''``."""
    if position.shape != (3,) or rotation.shape != (3, 3):
        return (f'expected a position (3,) and a rotation matrix (3, 3), got shapes '
                f'{position.shape} and {rotation.shape}')
    if not all(map(math.isfinite, position.tolist())):
        return f'position must be finite (metres), got {position.tolist()}'
    entries = rotation.ravel().tolist()
    if not all(map(math.isfinite, entries)):
        return f'rotation must be finite, got {rotation.tolist()}'
    # R^T R = I and det R = +1, in float arithmetic: numpy costs more on a 3 x 3 matrix.
    columns = (entries[0::3], entries[1::3], entries[2::3])
    deviation = max(abs(sum(a * b for a, b in zip(columns[i], columns[j])) - (i == j))
                    for i in range(3) for j in range(i, 3))
    (r11, r12, r13), (r21, r22, r23), (r31, r32, r33) = rotation.tolist()
    determinant = (r11 * (r22 * r33 - r23 * r32) - r12 * (r21 * r33 - r23 * r31)
                   + r13 * (r21 * r32 - r22 * r31))
    if not deviation <= ROTATION_TOLERANCE or determinant < 0.0:
        return (f'rotation must be a rotation matrix (R^T R = I within '
                f'{ROTATION_TOLERANCE:g}, determinant +1), got {rotation.tolist()}')
    return ''
