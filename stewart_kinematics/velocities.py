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
unit vector: the rows of :func:`stewart_kinematics.kinematics.twist_jacobian`.
"""

import math

import numpy as np

from stewart_kinematics.kinematics import as_poses, jacobian_condition, twist_jacobian
from stewart_kinematics.rotations import euler_zyx_to_matrix

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
    :raises ValueError: if a pose or twist is malformed or not finite.
    """
    poses = as_poses(poses)
    twists = as_poses(twists, 'twists')
    jac = twist_jacobian(geometry, poses[..., :3], euler_zyx_to_matrix(poses[..., 3:]))
    return (jac @ twists[..., None])[..., 0]


def platform_twist(geometry, poses, velocities, *, max_condition=None) -> np.ndarray:
    """
    Platform twist that produces the given leg velocities at the given pose.

    Near a singularity the twist grows without bound for bounded leg velocities (a small error
    in them becomes a large false motion), so a pose whose dimensionless Jacobian (see
    :func:`stewart_kinematics.limits.jacobian_condition`) has a condition number above
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
    :raises ValueError: if an input is malformed.
    """
    poses = as_poses(poses)
    velocities = as_poses(velocities, 'leg velocities')
    if max_condition is None:
        max_condition = (geometry.max_jacobian_condition
                         if math.isfinite(geometry.max_jacobian_condition)
                         else DEFAULT_MAX_TWIST_CONDITION)
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
        return np.linalg.solve(twist_jacobian(geometry, position, rotation),
                               velocities[..., None])[..., 0]
    except np.linalg.LinAlgError as error:
        raise SingularPoseError(
            'a pose is singular: leg velocities do not determine the twist') from error
