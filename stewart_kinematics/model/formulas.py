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
The one formula of each quantity of the legs, for one pose in floats and for a batch in arrays.

The leg vector (:func:`legs_of`, the paper's equation 1), the rows of the twist Jacobian
(:func:`twist_rows`), the Newton step in Euler angle rates (:func:`euler_step`) and the product
of a 6x6 matrix and a vector (:func:`apply_matrix`), with
:func:`stewart_kinematics.model.rotations.zyx_entries`, are each written once, so that they run
on floats for one pose (numpy's per-call overhead would cost more than the arithmetic on six
legs) and on numpy arrays for a batch, with the same operations in the same order: a single
solve and a batch take the same steps to the bit. :class:`GeometryConstants` holds what they
read of a geometry, derived once per geometry.

Inverse kinematics (:mod:`.inverse`), the Jacobians (:mod:`.jacobians`) and the forward solver
(:mod:`.forward_solver`) are built on them. Units are metres and radians; frames and the
rotation convention are those of :mod:`.geometry` and :mod:`.rotations`. The arguments are
checked where they enter (:mod:`.inputs`), not here.
"""

import math
import weakref

import numpy as np

from stewart_kinematics.model.rotations import zyx_entries


# The formulas. Each runs on floats (one pose: legs one by one) or on numpy arrays (a batch:
# entries and position of shape (n, 1), joints of shape (6,), so that one pass covers every
# leg of every pose).

def legs_of(rotation_entries, x, y, z, joints, sqrt, with_vectors=True):
    """
    Legs of a pose: lengths, leg vectors ``t + R p_i - b_i`` and rotated joints ``R p_i``.

    The one formula of the leg vector (the paper's equation 1).

    :param rotation_entries: ``(r11, r12, ..., r33)`` of the platform-to-base rotation.
    :param x: ``X`` of the platform frame, metres, base frame; ``y`` and ``z`` likewise.
    :param joints: per leg ``(px, py, pz, bx, by, bz)``, metres: platform joint (platform
        frame) and base joint (base frame); for a batch, one entry of six arrays (6,).
    :param sqrt: ``math.sqrt`` or ``numpy.sqrt``.
    :param with_vectors: False for the lengths alone (inverse kinematics of one pose needs
        only them: a small part of its cost).
    :returns: per entry of ``joints``, ``(l, lx, ly, lz, ax, ay, az)``: length, leg vector and
        rotated platform joint, metres, base frame; or, without ``with_vectors``, ``l`` alone.
    """
    r11, r12, r13, r21, r22, r23, r31, r32, r33 = rotation_entries
    legs = []
    add = legs.append
    for px, py, pz, bx, by, bz in joints:
        ax = r11 * px + r12 * py + r13 * pz
        ay = r21 * px + r22 * py + r23 * pz
        az = r31 * px + r32 * py + r33 * pz
        lx = ax + x - bx
        ly = ay + y - by
        lz = az + z - bz
        length = sqrt(lx * lx + ly * ly + lz * lz)
        add((length, lx, ly, lz, ax, ay, az) if with_vectors else length)
    return legs


def twist_rows(legs):
    """
    Rows ``[u_i, R p_i x u_i]`` of the twist Jacobian, from :func:`legs_of`; the one formula.

    No length may be 0: callers give a leg of zero length the length 1 (:func:`float_twist_rows`,
    :func:`batch_twist_jacobian`). It has no direction, and as its vector is zero, so is its
    row: a singular Jacobian.

    :returns: the rows' entries one after the other, 6 per entry of ``legs``.
    """
    entries = []
    for length, lx, ly, lz, ax, ay, az in legs:
        inverse = 1.0 / length
        ux, uy, uz = lx * inverse, ly * inverse, lz * inverse
        entries += (ux, uy, uz, ay * uz - az * uy, az * ux - ax * uz, ax * uy - ay * ux)
    return entries


def float_twist_rows(legs):
    """:func:`twist_rows` of one pose's legs (floats), a leg of zero length included."""
    try:
        return twist_rows(legs)
    except ZeroDivisionError:
        return twist_rows([(leg[0] or 1.0,) + leg[1:] for leg in legs])


def apply_matrix(matrix_rows, vector):
    """
    Product of a 6x6 matrix, given by rows, and a 6-vector, summed in index order.

    For a batch, one row of six arrays (6, n), the matrices' columns, and the vector as six
    arrays (n,): every row of every matrix at once.
    """
    v0, v1, v2, v3, v4, v5 = vector
    return [m0 * v0 + m1 * v1 + m2 * v2 + m3 * v3 + m4 * v4 + m5 * v5
            for m0, m1, m2, m3, m4, m5 in matrix_rows]


def euler_step(pose, twist, cos_beta, sin_beta, cos_gamma, sin_gamma):
    """
    Pose ``pose - dx`` where ``E dx = twist``: a Newton step taken in Euler angle rates.

    ``E``'s columns are ``R e_x``, ``Rz e_y`` and ``e_z`` (see :func:`~.jacobians.jacobian`), so
    ``d_alpha = (cos(gamma) w_x + sin(gamma) w_y) / cos(beta)``,
    ``d_beta = cos(gamma) w_y - sin(gamma) w_x`` and ``d_gamma = w_z + sin(beta) d_alpha``.
    The caller makes sure that ``cos(beta)`` is not 0, where ``E`` is singular.

    :returns: the new pose, six values.
    """
    x, y, z, alpha, beta, gamma = pose
    vx, vy, vz, wx, wy, wz = twist
    d_alpha = (cos_gamma * wx + sin_gamma * wy) / cos_beta
    return (x - vx, y - vy, z - vz, alpha - d_alpha, beta - (cos_gamma * wy - sin_gamma * wx),
            gamma - (wz + sin_beta * d_alpha))


class GeometryConstants:
    """
    Figures derived once from a geometry, reused by every call (see :func:`constants_of`).

    They hold no reference to the geometry, so that the cache of :func:`constants_of` lets it
    go.
    """

    def __init__(self, geometry):
        base = geometry.base_joints
        platform = geometry.platform_joints
        #: ``(px, py, pz, bx, by, bz)`` of each leg as Python floats, for :func:`legs_of` on one
        #: pose, and the same as six arrays (6, 1) for a batch (legs along the first axis).
        self.joint_pairs = tuple(tuple(p) + tuple(b)
                                 for p, b in zip(platform.tolist(), base.tolist()))
        self.joint_columns = (tuple(np.ascontiguousarray(column[:, None])
                                    for column in np.hstack([platform, base]).T),)
        # Newton-Raphson from the home pose: its first step is the same for every call.
        self.home_pose = tuple(geometry.home_pose.tolist())
        self.home_jacobian_inverse = float_inverse(float_twist_rows(
            single_euler_legs(self, self.home_pose)))


#: Constants of each geometry still alive; a Geometry is immutable, so they never go stale.
_CONSTANTS = weakref.WeakKeyDictionary()


def constants_of(geometry) -> GeometryConstants:
    """Return the derived constants of ``geometry``, computing them on its first use."""
    try:
        return _CONSTANTS[geometry]
    except KeyError:
        constants = _CONSTANTS[geometry] = GeometryConstants(geometry)
        return constants


# One pose, in float arithmetic: the same formulas as the batch path, which on one pose pays
# numpy's per-call overhead on each of its many small array operations, several times the
# arithmetic itself (the one-pose timings: doc/benchmarks.md). Tests prove them equal to the
# batch path.

def single_legs(constants, position, rotation_entries):
    """:func:`legs_of` of one pose, in floats."""
    x, y, z = position
    return legs_of(rotation_entries, x, y, z, constants.joint_pairs, math.sqrt)


def single_euler_legs(constants, pose, with_vectors=True):
    """:func:`legs_of` of a pose ``[X, Y, Z, alpha, beta, gamma]`` given as six floats."""
    x, y, z, alpha, beta, gamma = pose
    cos, sin = math.cos, math.sin
    return legs_of(zyx_entries(cos(alpha), sin(alpha), cos(beta), sin(beta), cos(gamma),
                               sin(gamma)), x, y, z, constants.joint_pairs, math.sqrt,
                   with_vectors)


def float_inverse(entries):
    """Inverse of a 6x6 matrix given by its 36 entries, as nested lists; None if singular."""
    try:
        return np.linalg.inv(np.array(entries).reshape(6, 6)).tolist()
    except np.linalg.LinAlgError:
        return None


# A batch, in numpy arrays.

def batch_legs(constants, position, rotation_entries, with_vectors=True):
    """
    :func:`legs_of` of a batch: positions (n, 3) and rotation entries, nine arrays (n,).

    The arrays are leg by pose, (6, n): with the poses along the last axis, every operation
    runs one long loop per leg (with (n, 6), numpy would run n loops of six).

    :returns: ``(lengths, vectors)``: an array (6, n) and ``(lx, ly, lz, ax, ay, az)``, six
        arrays (6, n); without ``with_vectors``, the lengths alone.
    """
    (legs,) = legs_of(rotation_entries, *np.ascontiguousarray(position.T),
                      constants.joint_columns, np.sqrt, with_vectors)
    return (legs[0], legs[1:]) if with_vectors else legs


def batch_euler_legs(constants, poses, with_vectors=True):
    """:func:`batch_legs` of poses ``[X, Y, Z, alpha, beta, gamma]``, shape (n, 6)."""
    cosines, sines = np.cos(poses[:, 3:]), np.sin(poses[:, 3:])
    return batch_legs(constants, poses[:, :3], zyx_entries(
        cosines[:, 0], sines[:, 0], cosines[:, 1], sines[:, 1], cosines[:, 2], sines[:, 2]),
        with_vectors)


def batch_rotation_legs(constants, position, rotation):
    """:func:`batch_legs` of positions (..., 3) and rotation matrices (..., 3, 3)."""
    shape = position.shape[:-1]
    position = position.reshape(-1, 3)
    rotation = rotation.reshape(-1, 3, 3)
    with np.errstate(over='ignore', invalid='ignore'):   # the callers refuse an overflow
        legs = batch_legs(constants, position,
                          [rotation[:, row, column] for row in range(3) for column in range(3)])
    return shape, legs


def broadcast_pose(position, rotation):
    """Positions (..., 3) and rotations (..., 3, 3) broadcast to the same leading shape."""
    shape = np.broadcast_shapes(position.shape[:-1], rotation.shape[:-2])
    return (np.broadcast_to(position, shape + (3,)),
            np.broadcast_to(rotation, shape + (3, 3)))


def batch_twist_jacobian(lengths, vectors):
    """Twist Jacobians (n, 6, 6) of :func:`batch_legs`'s arrays (6, n)."""
    lengths = np.where(lengths == 0.0, 1.0, lengths)  # see twist_rows
    return np.stack(twist_rows([(lengths, *vectors)]), axis=-1).transpose(1, 0, 2)
