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

ik_node calls :meth:`CommandCheck.tool_pose` with the numbers of a message: the frame it is
given in is accepted or refused there, a non-unit quaternion normalised with a warning, and
the tool frame's pose turned into the platform's; and :meth:`CommandCheck.tool_twist` with a
twist about the tool frame's origin, moved there to the platform's. Every limit is the limits
model's (:class:`~stewart_kinematics.limits.LimitModel`): the pose limits for a pose, the leg
velocity limit for a twist (refused, or scaled down uniformly to the limit, never beyond it).

It never raises for input it cannot use and never returns an infinite, NaN or zero length: a
malformed or unreachable pose, or one that breaks a limit of the geometry, comes back refused
with a :class:`~stewart_kinematics.findings.Finding`. Nothing is clamped. Nothing here imports
ROS.
"""

import dataclasses
import math
from typing import Optional

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.findings import Finding
from stewart_kinematics.limits import LimitModel
from stewart_kinematics.limits.command_gate import (
    CommandGate,
    LegCommand,
    LegVelocityCommand,
    platform_of_unit_quaternion,
    SETPOINT,
)
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.jacobians import twist_jacobian
from stewart_kinematics.model.rotations import (
    euler_zyx_matrix_entries,
    normalize_quaternion,
)

#: Largest deviation of ``R^T R`` from the identity accepted for a rotation matrix.
ROTATION_TOLERANCE = 1e-6
#: A quaternion whose norm is this far from 1 is normalised with a warning.
QUATERNION_NORM_TOLERANCE = 1e-6
#: A twist with a component beyond this (m/s or rad/s) is no motion of a platform: refused as
#: invalid whatever ``twist_over_limit`` says (scaling it would only hide a broken input).
TWIST_COMPONENT_MAX = 1e3
#: What :meth:`CommandCheck.twist` does with a twist beyond the leg velocity limit.
TWIST_POLICIES = ('refuse', 'scale')


class CommandCheck:
    """
    Turn commanded poses into leg lengths, refusing every pose that is not safe to command.

    The state is the last accepted pose, where :meth:`twist` applies a velocity command.

    :param geometry: the platform and its limits (:class:`stewart_kinematics.Geometry`).
    :param actuator_limits: the legs' speed limits; the velocity limit applies to twists.
    :param twist_over_limit: ``'refuse'`` a twist whose leg velocities exceed
        ``leg_velocity_max``, or ``'scale'`` it down uniformly to the limit.
    :raises ValueError: for an unknown ``twist_over_limit``.
    """

    def __init__(self, geometry, actuator_limits: Optional[ActuatorLimits] = None, *,
                 twist_over_limit: str = 'refuse'):
        if twist_over_limit not in TWIST_POLICIES:
            raise ValueError(f'twist_over_limit must be one of {TWIST_POLICIES}, got '
                             f'{preview(twist_over_limit)}')
        self.geometry = geometry
        #: Every limit a command must keep: the geometry's and the actuators'.
        self.limits = LimitModel(geometry, actuator_limits)
        #: The last check of what is sent: the leg lengths of each pose, as setpoints.
        self.gate = CommandGate(geometry, actuator_limits, timing=SETPOINT)
        self.twist_over_limit = twist_over_limit
        #: ``(position (3,), rotation (3, 3))`` of the last accepted pose, or ``None``.
        self.last_pose = None
        #: The leg lengths of the last accepted pose, metres, or ``None``.
        self.last_lengths = None

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

        A quaternion that is not unit is normalised (with a ``quaternion_not_unit`` warning);
        a zero or non-finite one is refused.

        :param position: metres, base frame, shape (3,).
        :param quaternion: shape (4,).
        """
        return self.tool_pose(position, quaternion)

    def tool_pose(self, position, quaternion, frames=None, frame_id: str = '') -> LegCommand:
        """
        ik_node's decision on a commanded pose of the tool frame, given in a frame.

        The frame must be one a pose may be given in (``base_frame``, ``user_frame`` or
        ``''``); the quaternion is normalised, with a warning when its norm is off by more
        than :data:`QUATERNION_NORM_TOLERANCE`; the tool frame's pose is turned into the
        platform frame's (``frames.platform_in_base``), whose leg lengths are then decided as
        by :meth:`pose`.

        :param position: the tool frame's origin in ``frame_id``, metres, three numbers.
        :param quaternion: its orientation ``(x, y, z, w)``, four numbers.
        :param frames: the :class:`stewart_kinematics.FrameTree` to apply, or ``None``: the
            pose is the platform frame's, in the base frame.
        :param frame_id: the frame the pose is given in (a message header's ``frame_id``).
        :returns: a :class:`LegCommand`, its ``position`` and ``rotation`` the platform
            frame's; refused with ``invalid_pose``, ``wrong_frame``, ``unreachable`` or
            ``out_of_limits``.
        """
        try:
            position = as_float_array(position, 'position')
        except ValueError as error:
            return LegCommand(None, refusal=Finding(findings.INVALID_POSE, str(error)))
        if position.shape != (3,):
            return LegCommand(None, refusal=Finding(
                findings.INVALID_POSE,
                f'position must be three numbers (metres), got shape {position.shape}'))
        if not all(map(math.isfinite, position.tolist())):
            return LegCommand(None, refusal=Finding(
                findings.INVALID_POSE, f'position must be finite (metres), got '
                f'{position.tolist()}'))
        try:
            unit = normalize_quaternion(quaternion)
            if unit.shape != (4,):
                raise ValueError(f'expected one quaternion (4,), got shape {unit.shape}')
        except ValueError as error:
            return LegCommand(None, refusal=Finding(findings.INVALID_POSE, str(error)))
        warnings = ()
        norm = math.sqrt(sum(value * value for value in np.asarray(quaternion, float).tolist()))
        if not abs(norm - 1.0) <= QUATERNION_NORM_TOLERANCE:
            warnings = (Finding(findings.QUATERNION_NOT_UNIT,
                                f'orientation has norm {norm:.9g}, not 1: normalised',
                                (('quaternion_norm', f'{norm:.9g}'),)),)
        try:
            # As the gate reads a pose message: the same conversion for what is received and
            # for what a node sends on (a cue pose, a played trajectory); the quaternion was
            # checked above, once.
            position, rotation = platform_of_unit_quaternion(position, unit, frames, frame_id)
        except ValueError as error:
            return LegCommand(None, refusal=Finding(findings.WRONG_FRAME, str(error)),
                              warnings=warnings)
        command = self._command(position, rotation)
        if warnings:
            command = dataclasses.replace(command, warnings=warnings + command.warnings)
        return command

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
                f'radians), got {preview(pose)}'))
        # The angles were checked above, once: the matrix of euler_zyx_to_matrix, unchecked.
        rotation = np.array(euler_zyx_matrix_entries(*pose[3:].tolist())).reshape(3, 3)
        return self._command(pose[:3], rotation)

    def _command(self, position, rotation) -> LegCommand:
        """Decide on a valid position (3,) and rotation matrix (3, 3): the gate's verdict."""
        command = self.gate.pose(position, rotation)
        if command.accepted:
            self.last_pose = position, rotation
            self.last_lengths = command.lengths
        return command

    def twist(self, twist) -> LegVelocityCommand:
        """
        Leg velocities of a platform twist at the last accepted pose, within the velocity limit.

        The pose is the last accepted one, so within every pose limit. Leg velocities beyond
        ``leg_velocity_max`` are refused (``too_fast``, with every leg over the limit), or with
        ``twist_over_limit='scale'`` the whole twist is scaled down by the one factor that puts
        the fastest leg at the limit (a ``twist_scaled`` warning): never beyond it.

        :param twist: ``[vx, vy, vz, wx, wy, wz]`` of the platform frame's origin, base frame,
            m/s and rad/s, shape (6,).
        :returns: a :class:`LegVelocityCommand`; refused (code ``invalid_twist``,
            ``no_pose_yet`` or ``too_fast``) rather than raised.
        """
        twist, refusal = _twist_refusal(twist)
        if refusal is not None:
            return refusal
        if self.last_pose is None:
            return _no_pose_yet()
        return self._leg_velocities(twist)

    def tool_twist(self, twist, frames=None) -> LegVelocityCommand:
        """
        ik_node's decision on a twist of the tool frame: :meth:`twist` about the tool point.

        The twist is the velocity of the tool frame's origin and the angular velocity (base
        frame), as every pose topic is about the tool frame's point; it is checked as given,
        then moved to the platform frame's origin at the last accepted pose
        (:meth:`~stewart_kinematics.FrameTree.platform_twist_from_tool`) and decided there.

        :param twist: ``[vx, vy, vz, wx, wy, wz]``, base frame, m/s and rad/s, shape (6,).
        :param frames: the :class:`stewart_kinematics.FrameTree` whose tool frame the twist is
            about, or ``None``: the platform frame's.
        :returns: a :class:`LegVelocityCommand`, as :meth:`twist`.
        """
        twist, refusal = _twist_refusal(twist)
        if refusal is not None:
            return refusal
        if self.last_pose is None:
            return _no_pose_yet()
        if frames is not None:
            twist = frames.platform_twist_from_tool(twist, self.last_pose[1])
        return self._leg_velocities(twist)

    def _leg_velocities(self, twist) -> LegVelocityCommand:
        """Decide on a valid platform twist at the last accepted pose."""
        velocities = twist_jacobian(self.geometry, *self.last_pose) @ twist
        scale = self.limits.leg_velocity_scale(velocities)
        if scale == 1.0:
            return self.gate.leg_velocities(velocities, self.last_lengths)
        violations = self.limits.leg_state_violations(velocities=velocities)
        if self.twist_over_limit == 'refuse':
            return LegVelocityCommand(None, Finding(
                findings.TOO_FAST,
                'the twist is too fast for the legs: ' + '; '.join(map(str, violations))
                + f" (twist_over_limit 'refuse'; scaled by {scale:.6g} it would be within)",
                findings.violation_details(violations)))
        warning = Finding(
            findings.TWIST_SCALED,
            f'the twist was scaled by {scale:.6g} to keep leg_velocity_max: '
            + '; '.join(map(str, violations)),
            (('scale', f'{scale:.6g}'),) + findings.violation_details(violations))
        return self.gate.leg_velocities(velocities * scale, self.last_lengths, scale, (warning,))


def _twist_refusal(twist):
    """Return ``(twist as floats, None)``, or ``(None, the refused command)`` of a bad twist."""
    try:
        twist = as_float_array(twist, 'twist')
    except ValueError as error:
        return None, LegVelocityCommand(None, Finding(findings.INVALID_TWIST, str(error)))
    if twist.shape != (6,) or not np.all(np.isfinite(twist)):
        return None, LegVelocityCommand(None, Finding(
            findings.INVALID_TWIST,
            f'a twist must be six finite numbers [vx, vy, vz, wx, wy, wz] (m/s, rad/s), '
            f'got {preview(twist)}'))
    if not np.all(np.abs(twist) <= TWIST_COMPONENT_MAX):
        return None, LegVelocityCommand(None, Finding(
            findings.INVALID_TWIST,
            f'a twist component beyond {TWIST_COMPONENT_MAX:g} m/s or rad/s is no motion of '
            f'a platform, got {twist.tolist()}'))
    return twist, None


def _no_pose_yet() -> LegVelocityCommand:
    """Return the refusal of a twist before any pose was accepted."""
    return LegVelocityCommand(None, Finding(
        findings.NO_POSE_YET, 'no pose accepted yet, so no Jacobian to apply the twist at'))


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
