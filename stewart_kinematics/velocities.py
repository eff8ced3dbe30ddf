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

import numpy as np

from stewart_kinematics.kinematics import as_poses, twist_jacobian
from stewart_kinematics.rotations import euler_zyx_to_matrix


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


def platform_twist(geometry, poses, velocities) -> np.ndarray:
    """
    Platform twist that produces the given leg velocities at the given pose.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,) or (N, 6).
    :param velocities: leg velocities l_1'..l_6' in metres per second, same shape.
    :returns: ``[vx, vy, vz, wx, wy, wz]`` in the base frame (m/s, rad/s), same shape.
    :raises ValueError: if an input is malformed, or a pose is singular (the twist is then
        not determined by the leg velocities).
    """
    poses = as_poses(poses)
    velocities = as_poses(velocities, 'leg velocities')
    jac = twist_jacobian(geometry, poses[..., :3], euler_zyx_to_matrix(poses[..., 3:]))
    try:
        return np.linalg.solve(jac, velocities[..., None])[..., 0]
    except np.linalg.LinAlgError as error:
        raise ValueError('the pose is singular: leg velocities do not determine the twist') \
            from error
