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
Velocity kinematics: platform twist to leg velocities and back, through the analytic Jacobian.

A twist is ``[vx, vy, vz, wx, wy, wz]``: the velocity of the platform frame's origin and the
platform's angular velocity, both in the base frame (metres per second, radians per second), as
in geometry_msgs/msg/Twist. Leg velocities are the rates of change of the leg lengths l_1..l_6
(metres per second), the paper's "rate of change of the lengths".

Leg ``i`` changes at ``u_i . (v + w x R p_i) = [u_i, R p_i x u_i] . [v, w]``, with ``u_i`` its
unit vector: the rows of :func:`stewart_kinematics.model.jacobians.twist_jacobian`.
"""

from dataclasses import dataclass
import math

import numpy as np

from stewart_kinematics.model.arrays import check_finite_output
from stewart_kinematics.model.inputs import as_poses
from stewart_kinematics.model.inverse import leg_vectors
from stewart_kinematics.model.jacobians import jacobian_condition, twist_jacobian
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

#: Largest condition number of the dimensionless Jacobian at which :func:`platform_twist`
#: answers when the geometry sets no ``max_jacobian_condition``. At 1000 on the paper's
#: platform, 1 mm/s of error on every leg velocity can already turn into 0.2 rad/s; at the
#: singularity it is unbounded (the paper's platform at a yaw of 90.4 degrees: 4300 rad/s).
DEFAULT_MAX_TWIST_CONDITION = 1e3


class SingularPoseError(ValueError):
    """A pose too near a singularity for the asked quantity: its Jacobian is ill-conditioned."""


def leg_velocities(geometry, poses, twists) -> np.ndarray:
    """
    Rates of change of the leg lengths of a platform moving with the given twist.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,) or (N, 6).
    :param twists: ``[vx, vy, vz, wx, wy, wz]`` in the base frame (m/s, rad/s), same shape.
    :returns: leg velocities in metres per second, shape (6,) or (N, 6).
    :raises ValueError: if a pose or twist is malformed or not finite, the numbers of poses
        and twists differ, or the velocities overflow.
    """
    poses = as_poses(poses)
    twists = as_poses(twists, 'twists')
    _check_counts(poses, twists, 'twists')
    jac = twist_jacobian(geometry, poses[..., :3], euler_zyx_to_matrix(poses[..., 3:]))
    with np.errstate(over='ignore', invalid='ignore'):
        velocities = (jac @ twists[..., None])[..., 0]
    return check_finite_output(velocities, 'the leg velocities', 'the twists')


def platform_twist(geometry, poses, velocities, *, max_condition=None) -> np.ndarray:
    """
    Platform twist that produces the given leg velocities at the given pose.

    Near a singularity the twist grows without bound for bounded leg velocities (a small error
    in them becomes a large false motion), so a pose whose dimensionless Jacobian (see
    :func:`stewart_kinematics.model.jacobians.jacobian_condition`) has a condition number above
    ``max_condition`` is refused.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,) or (N, 6).
    :param velocities: leg velocities l_1'..l_6' in metres per second, same shape.
    :param max_condition: largest condition number accepted; default the geometry's
        ``max_jacobian_condition`` where it is finite, else
        :data:`DEFAULT_MAX_TWIST_CONDITION`; ``math.inf`` to refuse only exact singularities.
    :returns: ``[vx, vy, vz, wx, wy, wz]`` in the base frame (m/s, rad/s), same shape.
    :raises SingularPoseError: (a ValueError) if a pose's condition number exceeds
        ``max_condition``, or the pose is singular: the twist is then not determined, or not
        reliably, by the leg velocities.
    :raises ValueError: if an input is malformed, the numbers of poses and velocities differ,
        or the twist overflows (leg velocities beyond about 1e300 m/s).
    """
    poses = as_poses(poses)
    velocities = as_poses(velocities, 'leg velocities')
    _check_counts(poses, velocities, 'leg velocities')
    if max_condition is None:
        # The geometry's limits (a limits.PoseLimits, or None) hold its singularity margin.
        margin = math.inf if geometry.limits is None else geometry.limits.max_jacobian_condition
        max_condition = margin if math.isfinite(margin) else DEFAULT_MAX_TWIST_CONDITION
    position, rotation = poses[..., :3], euler_zyx_to_matrix(poses[..., 3:])
    condition = np.atleast_1d(jacobian_condition(geometry, position, rotation))
    refused = np.flatnonzero(~(condition <= max_condition))
    if refused.size:
        where = f'pose {refused[0]}' if poses.ndim == 2 else 'the pose'
        raise SingularPoseError(
            f'{where} is too near a singularity for its twist: the condition number of the '
            f'dimensionless Jacobian is {condition[refused[0]]:.4g}, above the limit '
            f'{max_condition:.4g}')
    try:
        with np.errstate(over='ignore', invalid='ignore'):
            twists = np.linalg.solve(twist_jacobian(geometry, position, rotation),
                                     velocities[..., None])[..., 0]
    except np.linalg.LinAlgError as error:
        raise SingularPoseError(
            'a pose is singular: leg velocities do not determine the twist') from error
    return check_finite_output(twists, 'the twist', 'the leg velocities')


def _check_counts(poses, values, name):
    """Refuse a batch of values whose number of rows neither matches the poses' nor is one."""
    try:
        np.broadcast_shapes(poses.shape[:-1], values.shape[:-1])
    except ValueError:
        raise ValueError(f'poses {poses.shape} and {name} {values.shape} must hold the same '
                         'number of rows, or one of them a single one') from None


@dataclass(frozen=True)
class PoseSamples:
    """
    Poses and their time derivatives at some times (base frame, SI units).

    :param positions: platform origin, metres, shape (M, 3).
    :param rotations: platform-to-base rotations, shape (M, 3, 3).
    :param velocities: velocity of the platform origin, m/s, shape (M, 3).
    :param angular_velocities: rad/s, base frame, shape (M, 3).
    :param accelerations: m/s^2, shape (M, 3).
    :param angular_accelerations: rad/s^2, base frame, shape (M, 3).
    """

    positions: np.ndarray
    rotations: np.ndarray
    velocities: np.ndarray
    angular_velocities: np.ndarray
    accelerations: np.ndarray
    angular_accelerations: np.ndarray


@dataclass(frozen=True)
class LegStates:
    """
    Leg lengths and their time derivatives at some times.

    :param lengths: metres, shape (M, 6).
    :param velocities: m/s, shape (M, 6).
    :param accelerations: m/s^2, shape (M, 6).
    """

    lengths: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray


def leg_states(geometry, poses: PoseSamples) -> LegStates:
    """
    Leg lengths, velocities and accelerations of a moving platform.

    With ``r_i = R p_i``, the platform joint moves at ``V_i = v + w x r_i`` and accelerates at
    ``A_i = a + alpha x r_i + w x (w x r_i)``; the leg ``L_i`` (length ``l_i``, direction
    ``u_i``) then changes at ``u_i . V_i`` and accelerates at
    ``u_i . A_i + (|V_i|^2 - (u_i . V_i)^2) / l_i``.

    :param poses: the platform's poses and derivatives, M samples.
    """
    legs = leg_vectors(geometry, poses.positions, poses.rotations)
    arms = legs - poses.positions[:, None, :] + geometry.base_joints    # r_i = R p_i
    lengths = np.sqrt(_dot(legs, legs))
    directions = legs / lengths[..., None]
    omega = poses.angular_velocities[:, None, :]
    joint_velocities = poses.velocities[:, None, :] + _cross(omega, arms)
    joint_accelerations = (poses.accelerations[:, None, :]
                           + _cross(poses.angular_accelerations[:, None, :], arms)
                           + _cross(omega, _cross(omega, arms)))
    velocities = _dot(directions, joint_velocities)
    accelerations = (_dot(directions, joint_accelerations)
                     + (_dot(joint_velocities, joint_velocities) - velocities ** 2) / lengths)
    return LegStates(lengths, velocities, accelerations)


def _cross(a, b):
    """Cross products over the last axis, broadcast; twice as fast as numpy.cross here."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    product = np.empty(np.broadcast_shapes(a.shape, b.shape))
    product[..., 0] = a1 * b2 - a2 * b1
    product[..., 1] = a2 * b0 - a0 * b2
    product[..., 2] = a0 * b1 - a1 * b0
    return product


def _dot(a, b):
    """Dot products over the last axis (same shapes)."""
    return np.einsum('...i,...i->...', a, b)
