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
The Jacobians of the leg lengths, and how close a pose is to a singularity.

:func:`twist_jacobian` maps the platform twist to the leg velocities (rows ``[u_i, R p_i x
u_i]``, :func:`~.formulas.twist_rows`); :func:`jacobian` maps the Euler angle rates: ``d l /
d x``. :func:`jacobian_condition` is the condition number of the dimensionless Jacobian
(rotation columns divided by the platform radius ``rho``): 1 is ideal, ``inf`` at a
singularity. The limits model's singularity margin reads it through
:func:`dimensionless_jacobians` and :func:`conditions_of_jacobians`, a forward kinematics
result through :func:`single_dimensionless_jacobian` and :func:`single_singular_values` (the
same figures for one pose, in a fifth of the time).
"""

import math

import numpy as np

from stewart_kinematics.model.arrays import check_finite_output
from stewart_kinematics.model.formulas import (
    batch_euler_legs,
    batch_rotation_legs,
    batch_twist_jacobian,
    broadcast_pose,
    constants_of,
    float_twist_rows,
    single_euler_legs,
    single_legs,
)
from stewart_kinematics.model.inputs import as_poses, as_position_rotation, finite_result


def twist_jacobian(geometry, position, rotation) -> np.ndarray:
    """
    Jacobian from the platform twist to the leg velocities.

    A twist is ``[vx, vy, vz, wx, wy, wz]``: the velocity of the platform frame's origin and the
    platform's angular velocity, both in the base frame. Leg ``i`` changes at
    ``u_i . (v + w x R p_i)``, so row ``i`` is ``[u_i, R p_i x u_i]``, with ``u_i`` the unit
    vector of the leg (a leg of zero length has no direction: its row is zero, a singular
    Jacobian). :func:`jacobian` is this times the Euler rate matrix.

    :param position: platform origin in the base frame, metres, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation, shape (3, 3) or (N, 3, 3).
    :returns: shape (6, 6) or (N, 6, 6); translation columns dimensionless, rotation columns
        in metres per radian.
    :raises ValueError: as :func:`leg_lengths`.
    """
    position, rotation = as_position_rotation(position, rotation)
    constants = constants_of(geometry)
    if position.shape == (3,) and rotation.shape == (3, 3):
        jac = np.array(float_twist_rows(single_legs(
            constants, position.tolist(), rotation.ravel().tolist()))).reshape(6, 6)
    else:
        shape, legs = batch_rotation_legs(constants, *broadcast_pose(position, rotation))
        jac = batch_twist_jacobian(*legs).reshape(shape + (6, 6))
    return finite_result(jac, 'the twist Jacobian', position, rotation)


def jacobian(geometry, poses) -> np.ndarray:
    """
    Analytic Jacobian ``d l_i / d x_j`` of the leg lengths with respect to the pose.

    Row ``i`` is ``[u_i, (R p_i x u_i) . E]`` where ``u_i`` is the unit vector of leg ``i`` and
    ``E`` maps Euler ZYX rates to the angular velocity: its columns are the x axis after the
    yaw and pitch (``R e_x``), the y axis after the yaw (``Rz e_y``) and the base z axis.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]``, shape (6,) or (N, 6).
    :returns: shape (6, 6) or (N, 6, 6); columns in the order of the pose, rows leg 1..6;
        translation columns dimensionless, rotation columns in metres per radian.
    """
    poses = as_poses(poses)
    batch = np.atleast_2d(poses)
    with np.errstate(over='ignore', invalid='ignore'):   # an overflow is refused below
        jac = batch_twist_jacobian(*batch_euler_legs(constants_of(geometry), batch))
    beta, gamma = batch[:, 4], batch[:, 5]
    cos_beta, cos_gamma, sin_gamma = np.cos(beta), np.cos(gamma), np.sin(gamma)
    euler_rate_axes = np.zeros((len(batch), 3, 3))
    euler_rate_axes[:, :, 0] = np.stack(
        [cos_gamma * cos_beta, sin_gamma * cos_beta, -np.sin(beta)], axis=-1)
    euler_rate_axes[:, 0, 1] = -sin_gamma
    euler_rate_axes[:, 1, 1] = cos_gamma
    euler_rate_axes[:, 2, 2] = 1.0
    jac[..., 3:] = jac[..., 3:] @ euler_rate_axes
    return check_finite_output(jac.reshape(poses.shape[:-1] + (6, 6)), 'the Jacobian',
                               'the poses')


def jacobian_condition(geometry, position, rotation):
    """
    Condition number of the dimensionless Jacobian: how close the pose is to a singularity.

    The rows are ``[u_i, (R p_i x u_i) / rho]``: leg directions and their moment arms divided
    by ``rho``, the RMS distance of the platform joints from their centroid, so that
    translation and rotation weigh alike. 1 is ideal; it grows without bound at a singularity,
    where the platform gains a motion that no leg resists.

    :param position: metres, shape (3,) or (N, 3).
    :param rotation: shape (3, 3) or (N, 3, 3).
    :returns: shape () or (N,); ``inf`` at an exact singularity.
    """
    return condition_number(dimensionless_singular_values(geometry, position, rotation))


def condition_number(singular_values):
    """Largest over smallest singular value (largest first), ``inf`` where the smallest is 0."""
    with np.errstate(divide='ignore', invalid='ignore'):
        return singular_values[..., 0] / singular_values[..., -1]


def dimensionless_singular_values(geometry, position, rotation):
    """Singular values, largest first, of the Jacobian of :func:`jacobian_condition`."""
    return singular_values_of(dimensionless(geometry,
                                            twist_jacobian(geometry, position, rotation)))


def dimensionless(geometry, twist_jacobians):
    """Divide the rotation columns of twist Jacobians by ``rho``, in place; return them."""
    twist_jacobians[..., 3:] /= geometry.platform_radius
    return twist_jacobians


def singular_values_of(jacobians):
    """Singular values, largest first, of Jacobians (..., 6, 6); 0 last for a zero row."""
    singular_values = np.linalg.svd(jacobians, compute_uv=False)
    # A zero row (a leg of zero length) is an exact singularity, whatever rounding says.
    singular_values[..., -1] *= ~np.any(np.all(jacobians == 0.0, axis=-1), axis=-1)
    return singular_values


def dimensionless_jacobians(geometry, lengths, vectors) -> np.ndarray:
    """
    Dimensionless Jacobians of :func:`jacobian_condition` from :func:`leg_arrays`' output.

    Rows ``[u_i, (R p_i x u_i) / rho]`` (the twist rows of :func:`twist_jacobian`, rotation
    columns divided by ``rho``); a leg of zero length gives a zero row.

    :param lengths: shape (6, n); ``vectors``: the six arrays (6, n) of :func:`leg_arrays`.
    :returns: shape (n, 6, 6).
    """
    return dimensionless(geometry, batch_twist_jacobian(lengths, vectors))


def conditions_of_jacobians(jacobians) -> np.ndarray:
    """
    Condition numbers of :func:`dimensionless_jacobians`, as :func:`jacobian_condition` gives.

    :param jacobians: shape (n, 6, 6).
    :returns: shape (n,); ``inf`` where a Jacobian is singular or has a zero row.
    """
    return condition_number(singular_values_of(jacobians))


def single_condition(geometry, legs) -> float:
    """
    :func:`conditions_of_jacobians` of one pose, from its legs in floats (:func:`legs_of`).

    :param legs: per leg ``(l, lx, ly, lz, ax, ay, az)``, floats.
    :returns: the condition number; ``inf`` where the Jacobian is singular or has a zero row.
    """
    jacobian, zero_row = _dimensionless_of_legs(geometry, legs)
    largest, *_, smallest = single_singular_values(jacobian, zero_row)
    # condition_number's division, in floats: x / 0 is inf (NaN for 0 / 0), as numpy's.
    if smallest == 0.0:
        return math.inf if largest > 0.0 else math.nan
    return largest / smallest


def single_dimensionless_jacobian(geometry, pose):
    """
    Return the dimensionless Jacobian of one pose (6, 6), and whether it has a zero row.

    The Jacobian's rows in floats from the legs (:func:`single_euler_legs`): a fifth of the
    time of the array path on one pose, which fk_node pays for every message.

    :param pose: ``[X, Y, Z, alpha, beta, gamma]``, six floats.
    """
    return _dimensionless_of_legs(geometry, single_euler_legs(constants_of(geometry), pose))


def _dimensionless_of_legs(geometry, legs):
    """:func:`single_dimensionless_jacobian` of one pose's legs (:func:`legs_of`, floats)."""
    rows = float_twist_rows(legs)
    jacobian = np.array(rows).reshape(6, 6)
    jacobian[:, 3:] /= geometry.platform_radius
    return jacobian, any(not any(rows[start:start + 6]) for start in range(0, 36, 6))


def single_singular_values(jacobian, zero_row):
    """
    :func:`dimensionless_singular_values` of one pose, six floats: a list, largest first.

    One SVD of :func:`single_dimensionless_jacobian`'s answer (a fraction of the array path's
    cost, with :attr:`ForwardKinematicsResult.pose_error_bound`). test_forward_result.py
    proves the two equal, singular poses and zero rows included.
    """
    values = np.linalg.svd(jacobian, compute_uv=False).tolist()
    # A zero row (a leg of zero length) is an exact singularity, whatever rounding says.
    if zero_row:
        values[-1] = 0.0
    return values
