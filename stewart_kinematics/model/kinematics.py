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
Inverse and forward kinematics of a 6-6 Gough-Stewart platform.

Inverse kinematics is closed form (the paper's equation 1): ``l_i = |t + R p_i - b_i|``.
Forward kinematics solves ``l(x) = lengths`` for the pose ``x = [X, Y, Z, alpha, beta, gamma]``
by Newton-Raphson with the analytic Jacobian ``dl/dx``.

Units are metres and radians; frames and the rotation convention are those of
:mod:`stewart_kinematics.model.geometry` and :mod:`stewart_kinematics.model.rotations`. Every
function takes one pose, shape (6,), or a batch, shape (N, 6), and loops over no poses in
Python.

Each quantity has one formula (:func:`_legs`, :func:`_twist_rows`, :func:`_euler_step`,
:func:`_apply` and :func:`stewart_kinematics.model.rotations.zyx_entries`), written so that it runs
on floats for one pose (numpy's per-call overhead would cost more than the arithmetic on six
legs) and on numpy arrays for a batch, with the same operations in the same order: a single
solve and a batch take the same steps to the bit.
"""

from dataclasses import dataclass, field
from functools import cached_property
import math
from typing import Tuple, Union
import weakref

import numpy as np

from stewart_kinematics.model.arrays import as_float_array, check_finite_output, preview
from stewart_kinematics.model.rotations import (
    _ArrayOperations,
    euler_zyx_matrix_entries,
    euler_zyx_to_matrix,
    zyx_angles,
    zyx_entries,
)

#: Default Newton-Raphson tolerance: the largest leg length error accepted, metres.
DEFAULT_TOLERANCE = 1e-12
#: Default Newton-Raphson iteration limit.
DEFAULT_MAX_ITERATIONS = 50
#: An iterate with a coordinate beyond this (metres or radians) has diverged: no platform
#: reaches a kilometre, and angles wound a hundred times round mean the iteration is lost.
DIVERGENCE_BOUND = 1e3
#: Modified Newton: a step that cut the largest leg length error by at least this factor
#: shows that its Jacobian still fits, and the next step reuses it. Far from the solution a
#: step cuts less, and a new Jacobian is computed, as in plain Newton-Raphson.
JACOBIAN_REUSE_CONTRACTION = 1e-4
#: Reasons a solve fails, as ForwardKinematicsResult.reason gives them.
SINGULAR_JACOBIAN = 'singular Jacobian: the pose is at a singularity'
DIVERGED = 'diverged: the next iterate left every plausible pose'
INVALID_LENGTHS = 'not solved: leg lengths must be finite and positive (metres)'
INVALID_GUESS = 'not solved: the initial guess must be finite'
#: Rounding floor of a computed leg length, in units of the last place of ``|t| + |p_i| +
#: |b_i|`` (the sizes of the terms summed in the leg vector): the residual of a solve is known
#: no better than this (see ForwardKinematicsResult.pose_error_bound).
LENGTH_ROUNDING_ULPS = 16.0
#: Rounding of a computed smallest singular value, in units of the largest one's last place.
SINGULAR_VALUE_ROUNDING_ULPS = 64.0
#: Poses per block of a batched inverse kinematics: the temporaries of one block stay in the
#: processor's cache, which doubles the throughput of batches of millions.
IK_BLOCK_SIZE = 4096


def _as_rows(values, name) -> np.ndarray:
    """Return ``values`` as a float array of shape (6,) or (N, 6), or raise ValueError."""
    values = as_float_array(values, name)
    if values.ndim not in (1, 2) or values.shape[-1] != 6:
        raise ValueError(f'{name} must have shape (6,) or (N, 6), got {values.shape}')
    return values


def as_poses(poses, name='poses') -> np.ndarray:
    """
    Check and convert poses ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).

    :param poses: shape (6,) or (N, 6).
    :returns: a float array of the same shape.
    :raises ValueError: if the shape is wrong or a value is not finite.
    """
    poses = _as_rows(poses, name)
    if not np.all(np.isfinite(poses)):
        bad = np.unique(np.argwhere(~np.isfinite(np.atleast_2d(poses)))[:, 0])
        raise ValueError(f'{name} must be finite; pose(s) {bad[:10].tolist()} are not')
    return poses


def as_leg_lengths(lengths, name='leg lengths') -> np.ndarray:
    """
    Check and convert leg lengths (metres).

    :param lengths: shape (6,) or (N, 6).
    :returns: a float array of the same shape.
    :raises ValueError: if the shape is wrong or a length is not finite and positive.
    """
    if type(lengths) is np.ndarray and lengths.shape == (6,) and lengths.dtype == _FLOAT:
        # One set of six floats (fk_node's per message): checked in floats; a sum of finite
        # numbers can overflow, and then the full checks below decide.
        values = lengths.tolist()
        if math.isfinite(sum(values)) and min(values) > 0.0:
            return lengths
    lengths = _as_rows(lengths, name)
    allowed = _valid_lengths(lengths)
    if not np.all(allowed):
        first_bad = np.atleast_2d(lengths)[~np.atleast_1d(allowed)][0]
        raise ValueError(f'{name} must be finite and positive (metres), got {first_bad.tolist()}')
    return lengths


def _valid_lengths(lengths):
    """Where each set of six lengths, shape (..., 6), is finite and positive: shape (...)."""
    return np.all(np.isfinite(lengths) & (lengths > 0.0), axis=-1)


# The formulas. Each runs on floats (one pose: legs one by one) or on numpy arrays (a batch:
# entries and position of shape (n, 1), joints of shape (6,), so that one pass covers every
# leg of every pose).

def _legs(rotation_entries, x, y, z, joints, sqrt, with_vectors=True):
    """
    Legs of a pose: lengths, leg vectors ``t + R p_i - b_i`` and rotated joints ``R p_i``.

    The one formula of the leg vector (the paper's equation 1).

    :param rotation_entries: ``(r11, r12, ..., r33)`` of the platform-to-base rotation.
    :param x: ``X`` of the platform frame, metres, base frame; ``y`` and ``z`` likewise.
    :param joints: per leg ``(px, py, pz, bx, by, bz)``, metres: platform joint (platform
        frame) and base joint (base frame); for a batch, one entry of six arrays (6,).
    :param sqrt: ``math.sqrt`` or ``numpy.sqrt``.
    :param with_vectors: False for the lengths alone (inverse kinematics of one pose needs
        only them: 0.3 us of its 4 us).
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


def _twist_rows(legs):
    """
    Rows ``[u_i, R p_i x u_i]`` of the twist Jacobian, from :func:`_legs`; the one formula.

    No length may be 0: callers give a leg of zero length the length 1 (:func:`_float_twist_rows`,
    :func:`_batch_twist_jacobian`). It has no direction, and as its vector is zero, so is its
    row: a singular Jacobian.

    :returns: the rows' entries one after the other, 6 per entry of ``legs``.
    """
    entries = []
    for length, lx, ly, lz, ax, ay, az in legs:
        inverse = 1.0 / length
        ux, uy, uz = lx * inverse, ly * inverse, lz * inverse
        entries += (ux, uy, uz, ay * uz - az * uy, az * ux - ax * uz, ax * uy - ay * ux)
    return entries


def _float_twist_rows(legs):
    """:func:`_twist_rows` of one pose's legs (floats), a leg of zero length included."""
    try:
        return _twist_rows(legs)
    except ZeroDivisionError:
        return _twist_rows([(leg[0] or 1.0,) + leg[1:] for leg in legs])


def _apply(matrix_rows, vector):
    """
    Product of a 6x6 matrix, given by rows, and a 6-vector, summed in index order.

    For a batch, one row of six arrays (6, n), the matrices' columns, and the vector as six
    arrays (n,): every row of every matrix at once.
    """
    v0, v1, v2, v3, v4, v5 = vector
    return [m0 * v0 + m1 * v1 + m2 * v2 + m3 * v3 + m4 * v4 + m5 * v5
            for m0, m1, m2, m3, m4, m5 in matrix_rows]


def _euler_step(pose, twist, cos_beta, sin_beta, cos_gamma, sin_gamma):
    """
    Pose ``pose - dx`` where ``E dx = twist``: a Newton step taken in Euler angle rates.

    ``E``'s columns are ``R e_x``, ``Rz e_y`` and ``e_z`` (see :func:`jacobian`), so
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


@dataclass(frozen=True)
class _ErrorBoundTerms:
    """
    The per-leg figures of :attr:`ForwardKinematicsResult.pose_error_bound`, as floats.

    ``arms`` |p_i|, ``base_norms`` |b_i|, ``reaches`` c_i = sqrt(1 + |p_i|^2 / rho^2).
    """

    arms: list
    base_norms: list
    reaches: list


class _GeometryConstants:
    """Arrays derived once from a geometry, reused by every call (see :func:`_constants`)."""

    def __init__(self, geometry):
        base = geometry.base_joints
        platform = geometry.platform_joints
        #: ``(px, py, pz, bx, by, bz)`` of each leg as Python floats, for :func:`_legs` on one
        #: pose, and the same as six arrays (6, 1) for a batch (legs along the first axis).
        self.joint_pairs = tuple(tuple(p) + tuple(b)
                                 for p, b in zip(platform.tolist(), base.tolist()))
        self.joint_columns = (tuple(np.ascontiguousarray(column[:, None])
                                    for column in np.hstack([platform, base]).T),)
        # Newton-Raphson from the home pose: its first step is the same for every call.
        self.home_pose = tuple(geometry.home_pose.tolist())
        self.home_jacobian_inverse = _float_inverse(_float_twist_rows(
            _single_euler_legs(self, self.home_pose)))
        self._geometry = weakref.ref(geometry)  # a strong one would keep the geometry alive

    @cached_property
    def error_bound_terms(self):
        """Per leg, as floats, for the pose error bound of one solve (see pose_error_bound)."""
        geometry = self._geometry()
        arms = np.linalg.norm(geometry.platform_joints, axis=-1)
        return _ErrorBoundTerms(
            arms.tolist(), np.linalg.norm(geometry.base_joints, axis=-1).tolist(),
            np.sqrt(1.0 + (arms / geometry.platform_radius) ** 2).tolist())

    @cached_property
    def start_table(self):
        """Return the geometry's :class:`StartTable`, built on first use (None: home singular)."""
        if self.home_jacobian_inverse is None:
            return None
        # Imported here: the table is built with this module's solver.
        from stewart_kinematics.model.start_table import StartTable
        return StartTable(self._geometry())


#: Constants of each geometry still alive; a Geometry is immutable, so they never go stale.
_CONSTANTS = weakref.WeakKeyDictionary()


def _constants(geometry) -> _GeometryConstants:
    """Return the derived constants of ``geometry``, computing them on its first use."""
    try:
        return _CONSTANTS[geometry]
    except KeyError:
        constants = _CONSTANTS[geometry] = _GeometryConstants(geometry)
        return constants


# One pose, in float arithmetic: the same formulas as the batch path, which on one pose pays
# numpy's per-call overhead (timeit, processor time, this machine: inverse kinematics 3.8 us
# against 19 us, leg_lengths 4.0 against 30 us, twist_jacobian 6.2 against 41 us, a cold
# forward kinematics solve 52 us against 660 us). Tests prove them equal to the batch path.

def _single_legs(constants, position, rotation_entries):
    """:func:`_legs` of one pose, in floats."""
    x, y, z = position
    return _legs(rotation_entries, x, y, z, constants.joint_pairs, math.sqrt)


def _single_euler_legs(constants, pose, with_vectors=True):
    """:func:`_legs` of a pose ``[X, Y, Z, alpha, beta, gamma]`` given as six floats."""
    x, y, z, alpha, beta, gamma = pose
    cos, sin = math.cos, math.sin
    return _legs(zyx_entries(cos(alpha), sin(alpha), cos(beta), sin(beta), cos(gamma),
                             sin(gamma)), x, y, z, constants.joint_pairs, math.sqrt,
                 with_vectors)


def _float_inverse(entries):
    """Inverse of a 6x6 matrix given by its 36 entries, as nested lists; None if singular."""
    try:
        return np.linalg.inv(np.array(entries).reshape(6, 6)).tolist()
    except np.linalg.LinAlgError:
        return None


def _single_canonical_angles(alpha, beta, gamma):
    """
    Euler angles of the same rotation in the canonical ranges (see :func:`zyx_angles`).

    Angles already in them are kept as they are, to the bit.
    """
    if _canonical(alpha, beta, gamma):
        return [alpha, beta, gamma]
    return list(zyx_angles(euler_zyx_matrix_entries(alpha, beta, gamma)))


def _canonical(alpha, beta, gamma):
    """Whether beta is in (-pi/2, pi/2), alpha and gamma in (-pi, pi]; floats or arrays."""
    return ((-_HALF_PI < beta) & (beta < _HALF_PI) & (-math.pi < alpha) & (alpha <= math.pi)
            & (-math.pi < gamma) & (gamma <= math.pi))


_HALF_PI = 0.5 * math.pi


# A batch, in numpy arrays.

def _batch_legs(constants, position, rotation_entries, with_vectors=True):
    """
    :func:`_legs` of a batch: positions (n, 3) and rotation entries, nine arrays (n,).

    The arrays are leg by pose, (6, n): with the poses along the last axis, every operation
    runs one long loop per leg (with (n, 6), numpy would run n loops of six).

    :returns: ``(lengths, vectors)``: an array (6, n) and ``(lx, ly, lz, ax, ay, az)``, six
        arrays (6, n); without ``with_vectors``, the lengths alone.
    """
    (legs,) = _legs(rotation_entries, *np.ascontiguousarray(position.T), constants.joint_columns,
                    np.sqrt, with_vectors)
    return (legs[0], legs[1:]) if with_vectors else legs


def _batch_euler_legs(constants, poses, with_vectors=True):
    """:func:`_batch_legs` of poses ``[X, Y, Z, alpha, beta, gamma]``, shape (n, 6)."""
    cosines, sines = np.cos(poses[:, 3:]), np.sin(poses[:, 3:])
    return _batch_legs(constants, poses[:, :3], zyx_entries(
        cosines[:, 0], sines[:, 0], cosines[:, 1], sines[:, 1], cosines[:, 2], sines[:, 2]),
        with_vectors)


def _batch_rotation_legs(constants, position, rotation):
    """:func:`_batch_legs` of positions (..., 3) and rotation matrices (..., 3, 3)."""
    shape = position.shape[:-1]
    position = position.reshape(-1, 3)
    rotation = rotation.reshape(-1, 3, 3)
    with np.errstate(over='ignore', invalid='ignore'):   # the callers refuse an overflow
        legs = _batch_legs(constants, position,
                           [rotation[:, row, column] for row in range(3) for column in range(3)])
    return shape, legs


def _broadcast_pose(position, rotation):
    """Positions (..., 3) and rotations (..., 3, 3) broadcast to the same leading shape."""
    shape = np.broadcast_shapes(position.shape[:-1], rotation.shape[:-2])
    return (np.broadcast_to(position, shape + (3,)),
            np.broadcast_to(rotation, shape + (3, 3)))


def _batch_twist_jacobian(lengths, vectors):
    """Twist Jacobians (n, 6, 6) of :func:`_batch_legs`'s arrays (6, n)."""
    lengths = np.where(lengths == 0.0, 1.0, lengths)  # see _twist_rows
    return np.stack(_twist_rows([(lengths, *vectors)]), axis=-1).transpose(1, 0, 2)


def _batch_euler_step(poses, twists):
    """
    :func:`_euler_step` of each pose, shape (n, 6), with twists given as six arrays (n,).

    :returns: ``(stepped poses (n, 6), defined (n,))``; a step is undefined where
        ``cos(beta) = 0``.
    """
    beta, gamma = poses[:, 4], poses[:, 5]
    cos_beta = np.cos(beta)
    defined = cos_beta != 0.0
    stepped = _euler_step(poses.T, twists, np.where(defined, cos_beta, 1.0), np.sin(beta),
                          np.cos(gamma), np.sin(gamma))
    return np.stack(stepped, axis=-1), defined


def _invert_each(matrices):
    """Invert each matrix of a stack (n, 6, 6); report which were singular."""
    try:
        return np.linalg.inv(matrices), np.ones(len(matrices), dtype=bool)
    except np.linalg.LinAlgError:
        # One singular matrix fails the whole stack: invert them one by one.
        inverses = np.zeros_like(matrices)
        invertible = np.ones(len(matrices), dtype=bool)
        for k, matrix in enumerate(matrices):
            try:
                inverses[k] = np.linalg.inv(matrix)
            except np.linalg.LinAlgError:
                invertible[k] = False
        return inverses, invertible


# The public functions.

def leg_vectors(geometry, position, rotation) -> np.ndarray:
    """
    Leg vectors ``t + R p_i - b_i`` from each base joint to its platform joint.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param position: platform origin in the base frame, metres, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation matrix, shape (3, 3) or (N, 3, 3).
    :returns: in the base frame, metres, shape (6, 3) or (N, 6, 3).
    :raises ValueError: as :func:`leg_lengths`.
    """
    position, rotation = _as_position_rotation(position, rotation)
    constants = _constants(geometry)
    if position.shape == (3,) and rotation.shape == (3, 3):
        legs = _single_legs(constants, position.tolist(), rotation.ravel().tolist())
        vectors = np.array([leg[1:4] for leg in legs])
    else:
        shape, (_, vectors) = _batch_rotation_legs(constants,
                                                   *_broadcast_pose(position, rotation))
        vectors = np.stack(vectors[:3], axis=-1).transpose(1, 0, 2).reshape(shape + (6, 3))
    return _finite_result(vectors, 'the leg vectors', position, rotation)


def leg_vectors_from_euler(geometry, poses) -> np.ndarray:
    """
    Leg vectors of poses ``[X, Y, Z, alpha, beta, gamma]``; see :func:`leg_vectors`.

    :returns: base frame, metres, shape (6, 3) or (N, 6, 3).
    """
    poses = as_poses(poses)
    return leg_vectors(geometry, poses[..., :3], euler_zyx_to_matrix(poses[..., 3:]))


def leg_lengths(geometry, position, rotation) -> np.ndarray:
    """
    Inverse kinematics for a pose given as position and rotation matrix.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param position: metres, base frame, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation matrix, shape (3, 3) or (N, 3, 3); build it
        from a quaternion with :func:`stewart_kinematics.model.rotations.quaternion_to_matrix`.
    :returns: leg lengths l_1..l_6 in metres, shape (6,) or (N, 6).
    :raises ValueError: if a shape is wrong, the numbers of poses differ, a value is not
        finite or the lengths overflow. The rotation is not checked to be one.
    """
    position, rotation = _as_position_rotation(position, rotation)
    constants = _constants(geometry)
    if position.shape == (3,) and rotation.shape == (3, 3):
        legs = _single_legs(constants, position.tolist(), rotation.ravel().tolist())
        lengths = [leg[0] for leg in legs]
        if all(map(math.isfinite, lengths)):
            return np.array(lengths)
        lengths = np.array(lengths)
    else:
        shape, (lengths, _) = _batch_rotation_legs(constants,
                                                   *_broadcast_pose(position, rotation))
        lengths = lengths.T.reshape(shape + (6,))
    return _finite_result(lengths, 'the leg lengths', position, rotation)


def inverse_kinematics(geometry, poses) -> np.ndarray:
    """
    Leg lengths of one pose or a batch of poses (closed form).

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` in metres and radians, shape (6,) or (N, 6).
    :returns: leg lengths l_1..l_6 in metres, shape (6,) or (N, 6).
    :raises ValueError: if a pose has the wrong shape or a non-finite value, or its lengths
        overflow (a coordinate beyond about 1e154 m).

    >>> from stewart_kinematics import inverse_kinematics, load_geometry
    >>> geometry = load_geometry('config/paper_platform.yaml')
    >>> inverse_kinematics(geometry, [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0])
    array([0.71885487, 0.71885488, 0.70114644, 0.71885487, 0.71885488, 0.71885488])
    """
    poses = as_float_array(poses, 'poses')
    constants = _constants(geometry)
    if poses.shape == (6,):
        values = poses.tolist()
        if all(map(math.isfinite, values)):
            lengths = _single_euler_legs(constants, values, with_vectors=False)
            # One test for six: a sum of lengths is finite only if each is (an overflow
            # beyond that, near 1e307 m, takes the batch path, which names it).
            if math.isfinite(sum(lengths)):
                return np.array(lengths)
    poses = as_poses(poses)
    batch = np.atleast_2d(poses)
    lengths = np.empty((batch.shape[0], 6))
    with np.errstate(over='ignore', invalid='ignore'):   # an overflow is refused below
        for start in range(0, batch.shape[0], IK_BLOCK_SIZE):
            stop = start + IK_BLOCK_SIZE
            lengths[start:stop] = _batch_euler_legs(constants, batch[start:stop], False).T
    return check_finite_output(lengths.reshape(poses.shape), 'the leg lengths', 'the poses')


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
    position, rotation = _as_position_rotation(position, rotation)
    constants = _constants(geometry)
    if position.shape == (3,) and rotation.shape == (3, 3):
        jac = np.array(_float_twist_rows(_single_legs(
            constants, position.tolist(), rotation.ravel().tolist()))).reshape(6, 6)
    else:
        shape, legs = _batch_rotation_legs(constants, *_broadcast_pose(position, rotation))
        jac = _batch_twist_jacobian(*legs).reshape(shape + (6, 6))
    return _finite_result(jac, 'the twist Jacobian', position, rotation)


def _as_position_rotation(position, rotation):
    """Positions (..., 3) and rotation matrices (..., 3, 3) as float arrays, shapes checked."""
    position = as_float_array(position, 'position')
    rotation = as_float_array(rotation, 'rotation')
    if position.shape == (3,) and rotation.shape == (3, 3):   # one pose: the common case
        return position, rotation
    if position.shape[-1:] != (3,) or rotation.shape[-2:] != (3, 3):
        raise ValueError(f'position must have shape (3,) or (N, 3) and rotation (3, 3) or '
                         f'(N, 3, 3), got {position.shape} and {rotation.shape}')
    try:
        np.broadcast_shapes(position.shape[:-1], rotation.shape[:-2])
    except ValueError:
        raise ValueError(f'position {position.shape} and rotation {rotation.shape} must hold '
                         'the same number of poses, or one of them a single one') from None
    return position, rotation


def _finite_result(result, what, position, rotation):
    """Return ``result``, or say why it is not finite: a non-finite input, or an overflow."""
    if isinstance(result, np.ndarray) and result.size <= 36 and all(
            map(math.isfinite, result.ravel().tolist())) or np.all(np.isfinite(result)):
        return result
    for name, values in (('position', position), ('rotation', rotation)):
        if not np.all(np.isfinite(values)):
            raise ValueError(f'{name} must be finite, got {preview(values)}')
    return check_finite_output(result, what, 'the position and rotation')


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
        jac = _batch_twist_jacobian(*_batch_euler_legs(_constants(geometry), batch))
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
    return _condition_number(_dimensionless_singular_values(geometry, position, rotation))


def _condition_number(singular_values):
    """Largest over smallest singular value (largest first), ``inf`` where the smallest is 0."""
    with np.errstate(divide='ignore', invalid='ignore'):
        return singular_values[..., 0] / singular_values[..., -1]


def _dimensionless_singular_values(geometry, position, rotation):
    """Singular values, largest first, of the Jacobian of :func:`jacobian_condition`."""
    return _singular_values(_dimensionless(geometry, twist_jacobian(geometry, position, rotation)))


def _dimensionless(geometry, twist_jacobians):
    """Divide the rotation columns of twist Jacobians by ``rho``, in place; return them."""
    twist_jacobians[..., 3:] /= geometry.platform_radius
    return twist_jacobians


def _singular_values(jacobians):
    """Singular values, largest first, of Jacobians (..., 6, 6); 0 last for a zero row."""
    singular_values = np.linalg.svd(jacobians, compute_uv=False)
    # A zero row (a leg of zero length) is an exact singularity, whatever rounding says.
    singular_values[..., -1] *= ~np.any(np.all(jacobians == 0.0, axis=-1), axis=-1)
    return singular_values


# The leg arrays of a batch, for the limits model (stewart_kinematics.limits), which evaluates
# every limit on them: the formulas above, exposed in their batch layout (legs by poses).

def leg_arrays(geometry, positions, rotation_entries):
    """
    Legs of a batch of poses, leg by pose: :func:`_legs`, the one leg formula, on arrays.

    :param positions: platform origins in the base frame, metres, shape (n, 3).
    :param rotation_entries: ``(r11, r12, ..., r33)`` of the platform-to-base rotations, nine
        arrays (n,): :func:`stewart_kinematics.model.rotations.zyx_entries` of Euler angles,
        or the entries of rotation matrices.
    :returns: ``(lengths, (lx, ly, lz, ax, ay, az))``: the leg lengths, shape (6, n), and the
        components of the leg vectors ``t + R p_i - b_i`` and of the rotated platform joints
        ``R p_i``, each (6, n), metres, base frame. One pose (n = 1) is computed in floats,
        as :func:`leg_lengths` computes one pose: the same values to the bit, three times
        faster than the arrays.
    """
    positions = np.asarray(positions, dtype=float)
    if positions.shape == (1, 3):
        legs = np.array(_single_legs(_constants(geometry), positions[0].tolist(),
                                     [float(entry[0]) for entry in rotation_entries]))
        return legs[:, 0:1], tuple(legs[:, column:column + 1] for column in range(1, 7))
    return _batch_legs(_constants(geometry), positions, rotation_entries)


def dimensionless_jacobians(geometry, lengths, vectors) -> np.ndarray:
    """
    Dimensionless Jacobians of :func:`jacobian_condition` from :func:`leg_arrays`' output.

    Rows ``[u_i, (R p_i x u_i) / rho]`` (the twist rows of :func:`twist_jacobian`, rotation
    columns divided by ``rho``); a leg of zero length gives a zero row.

    :param lengths: shape (6, n); ``vectors``: the six arrays (6, n) of :func:`leg_arrays`.
    :returns: shape (n, 6, 6).
    """
    return _dimensionless(geometry, _batch_twist_jacobian(lengths, vectors))


def conditions_of_jacobians(jacobians) -> np.ndarray:
    """
    Condition numbers of :func:`dimensionless_jacobians`, as :func:`jacobian_condition` gives.

    :param jacobians: shape (n, 6, 6).
    :returns: shape (n,); ``inf`` where a Jacobian is singular or has a zero row.
    """
    return _condition_number(_singular_values(jacobians))


@dataclass(frozen=True, eq=False)
class ForwardKinematicsResult:
    """
    Outcome of :func:`forward_kinematics`, for one solve or a batch.

    For one solve the fields are scalars and ``pose`` has shape (6,); for a batch of N they are
    arrays of length N and ``pose`` has shape (N, 6). Results compare with ``==`` field by
    field (``pose``, ``converged``, ``iterations``, ``residual``, ``reason``) and are
    hashable; the pose a solve returns is read-only.

    :param pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) of the last iterate; the
        solution where ``converged``, with ``beta`` in [-pi/2, pi/2] and the other angles in
        (-pi, pi].
    :param converged: True where every leg length is within the tolerance.
    :param iterations: Newton-Raphson steps taken.
    :param residual: largest leg length error ``max_i |l_i(pose) - lengths_i|``, metres.
    :param reason: ``''`` where converged, else why not (iteration limit, singular Jacobian,
        divergence).

    Three more figures are computed on first access (a singular value decomposition, about
    40 us, and a determinant, that a solve does not pay for) and kept: :attr:`condition`,
    :attr:`pose_error_bound` and :attr:`jacobian_sign`.
    """

    pose: np.ndarray
    converged: Union[bool, np.ndarray]
    iterations: Union[int, np.ndarray]
    residual: Union[float, np.ndarray]
    reason: Union[str, Tuple[str, ...]]
    #: ``(geometry, lengths, jacobian_inverse)``: the geometry and the leg lengths solved for,
    #: for :attr:`condition` and :attr:`pose_error_bound`; for one solve, the inverse of the
    #: twist Jacobian (nested lists) at the last iterate that needed one, so that a solve
    #: started from this result (tracking) begins with it instead of computing one at a pose
    #: only microns away. One field: each field costs a frozen dataclass time to build.
    _solve: tuple = field(default=(None, None, None), repr=False)

    def _fields(self):
        return (self.pose, self.converged, self.iterations, self.residual, self.reason)

    def __eq__(self, other):
        if not isinstance(other, ForwardKinematicsResult):
            return NotImplemented
        return all(np.array_equal(mine, theirs, equal_nan=isinstance(mine, (float, np.ndarray)))
                   if not isinstance(mine, (str, tuple)) else mine == theirs
                   for mine, theirs in zip(self._fields(), other._fields()))

    def __hash__(self):
        pose, converged, iterations, residual, reason = self._fields()
        return hash((_hashable(pose), _hashable(converged, bool), _hashable(iterations, int),
                     _hashable(residual), reason))

    @cached_property
    def _jacobian(self):
        """Return the dimensionless Jacobian at :attr:`pose`, and where it has a zero row."""
        pose = self.pose
        if pose.ndim == 1:
            return _single_dimensionless_jacobian(self._solve[0], pose.tolist())
        jacobians = _dimensionless(self._solve[0], twist_jacobian(
            self._solve[0], pose[..., :3], euler_zyx_to_matrix(pose[..., 3:])))
        return jacobians, np.any(np.all(jacobians == 0.0, axis=-1), axis=-1)

    @cached_property
    def _singular_values(self):
        if self.pose.ndim == 1:
            return _single_singular_values(*self._jacobian)
        return _singular_values(self._jacobian[0])

    @cached_property
    def jacobian_sign(self) -> Union[int, np.ndarray]:
        """
        Sign of the Jacobian's determinant at :attr:`pose`: +1, -1, or 0 at a singularity.

        Which side of the singularity surface the pose lies on: along a path of poses it
        changes only where the path crosses a singularity (``det J = 0``), so two solutions of
        opposite signs are not joined by a path that avoids one. The determinant of the
        dimensionless twist Jacobian (:func:`jacobian_condition`'s: the same sign as the twist
        Jacobian's, whose rotation columns are divided by a positive ``rho``), about 4 us; 0
        where a leg has zero length. Near a singularity (condition numbers of 1e13 and more)
        rounding may give either sign. An int for one solve, an array (N,) for a batch.
        """
        jacobian, zero_row = self._jacobian
        if self.pose.ndim == 1:
            determinant = 0.0 if zero_row else float(np.linalg.det(jacobian))
            return (determinant > 0.0) - (determinant < 0.0)
        return np.where(zero_row, 0, np.sign(np.linalg.det(jacobian))).astype(int)

    @cached_property
    def condition(self) -> Union[float, np.ndarray]:
        """
        Condition number of the dimensionless Jacobian at :attr:`pose`.

        The definition of :func:`jacobian_condition`: about 10 at the paper platform's home,
        growing without bound towards a singularity, ``inf`` at one. A float for one solve, an
        array (N,) for a batch.
        """
        if self.pose.ndim == 1:
            largest, smallest = self._singular_values[0], self._singular_values[-1]
            if smallest == 0.0:
                return math.inf if largest else math.nan
            return largest / smallest
        return _condition_number(self._singular_values)

    @cached_property
    def pose_error_bound(self) -> Union[float, np.ndarray]:
        """
        Proven bound on the distance from :attr:`pose` to the nearest exact pose of the lengths.

        One number in metres and radians: the larger of the position error (m) and the
        rotation angle error (rad) to the pose whose leg lengths are exactly the given ones,
        the one nearest to :attr:`pose`. Near a fold singularity the same lengths have a second
        pose close by (another assembly mode, across the fold): that one is not bounded, and
        the bound is ``inf`` when the two cannot be told apart (below).

        The proof, in the coordinates ``z = (dt, rho phi)`` of a move from :attr:`pose` (``dt``
        the position change, ``phi`` the rotation vector, ``rho`` the platform radius): the
        leg lengths are ``l(z) = l(0) + J z + q(z)`` with ``J`` the dimensionless Jacobian
        (:func:`jacobian_condition`), smallest singular value ``sigma``, and each
        ``|q_i(z)| <= M_i |z|^2 / 2``, where ``M_i = c_i^2 / l_i' + |p_i| / rho^2`` bounds the
        second derivative of leg ``i`` along any line in the ball (``c_i = sqrt(1 + |p_i|^2 /
        rho^2)``, ``l_i'`` the leg's shortest length in the ball). With the leg length error
        ``e`` (the residual plus the rounding floor, ``LENGTH_ROUNDING_ULPS`` units in the last
        place of ``|t| + |p_i| + |b_i|``), ``eta = sqrt(6) e / sigma`` and ``h = eta M /
        sigma`` (``M`` the 2-norm of the ``M_i``), the map ``z -> -J^-1 (l(0) - lengths +
        q(z))`` sends the ball of radius ``r = 2 eta / (1 + sqrt(1 - 2 h))`` into itself when
        ``h <= 1/2`` (Kantorovich's condition), so it holds an exact solution (Brouwer), and
        ``|dt| <= r``, ``|phi| <= r / rho``. The bound is ``r max(1, 1 / rho)``, at most twice
        the first-order figure ``eta max(1, 1 / rho)``. Where ``h > 1/2`` no ball is proven
        to hold a solution (the residual is too large for the curvature near a singularity):
        ``inf``. ``sigma`` is lowered by its rounding, ``SINGULAR_VALUE_ROUNDING_ULPS`` units
        in the last place of the largest singular value.

        On the paper's platform, within +-0.1 m and +-15 degrees of home: 5e-13 for the median
        pose, up to 1e-10 where the residual is just under the default tolerance; 4e-9 at 1e-3
        rad from the singularity at a yaw of 90.38 degrees, and ``inf`` within about 1e-5 rad
        of it, where a residual of 1e-13 m can leave converged solves microns off. ``inf`` at a
        singularity and where the solve did not converge. A float for one solve, an array
        (N,) for a batch.
        """
        geometry, lengths, _ = self._solve
        if self.pose.ndim == 1:
            return _single_pose_error_bound(
                geometry, self.pose.tolist(), np.asarray(lengths, dtype=float).tolist(),
                float(self.residual), bool(self.converged), self._singular_values)
        lengths = np.asarray(lengths, dtype=float)
        pose = np.asarray(self.pose, dtype=float)
        rho = geometry.platform_radius
        arms = np.linalg.norm(geometry.platform_joints, axis=-1)            # |p_i|, (6,)
        sizes = (np.linalg.norm(pose[..., None, :3], axis=-1) + arms
                 + np.linalg.norm(geometry.base_joints, axis=-1))         # (..., 6)
        eps = np.finfo(float).eps
        error = self.residual + LENGTH_ROUNDING_ULPS * eps * np.max(sizes, axis=-1)
        singular_values = self._singular_values
        sigma = singular_values[..., -1] - SINGULAR_VALUE_ROUNDING_ULPS * eps * (
            singular_values[..., 0])
        reach = np.sqrt(1.0 + (arms / rho) ** 2)                          # c_i, (6,)
        with np.errstate(divide='ignore', invalid='ignore', over='ignore'):
            eta = math.sqrt(6.0) * error / sigma
            # The legs' shortest lengths within the largest ball considered, 2 eta.
            shortest = (lengths - np.asarray(self.residual)[..., None]
                        - 2.0 * np.asarray(eta)[..., None] * reach)
            curvature = np.sqrt(np.sum(np.square(
                reach ** 2 / shortest + arms / rho ** 2), axis=-1))
            h = eta * curvature / sigma
            radius = 2.0 * eta / (1.0 + np.sqrt(np.maximum(1.0 - 2.0 * h, 0.0)))
            proven = (np.asarray(self.converged) & (sigma > 0.0) & (h <= 0.5)
                      & np.all(shortest > 0.0, axis=-1) & (radius >= 0.0))
            bound = np.where(proven, radius * max(1.0, 1.0 / rho), np.inf)
        return float(bound) if bound.ndim == 0 else bound


def _single_dimensionless_jacobian(geometry, pose):
    """
    Return the dimensionless Jacobian of one pose (6, 6), and whether it has a zero row.

    The Jacobian's rows in floats from the legs (:func:`_single_euler_legs`): a fifth of the
    time of the array path on one pose, which fk_node pays for every message.

    :param pose: ``[X, Y, Z, alpha, beta, gamma]``, six floats.
    """
    rows = _float_twist_rows(_single_euler_legs(_constants(geometry), pose))
    jacobian = np.array(rows).reshape(6, 6)
    jacobian[:, 3:] /= geometry.platform_radius
    return jacobian, any(not any(rows[start:start + 6]) for start in range(0, 36, 6))


def _single_singular_values(jacobian, zero_row):
    """
    :func:`_dimensionless_singular_values` of one pose, six floats: a list, largest first.

    One SVD of :func:`_single_dimensionless_jacobian`'s answer (12 us against 50 us on the
    array path, with :attr:`ForwardKinematicsResult.pose_error_bound`). test_fk_result.py
    proves the two equal, singular poses and zero rows included.
    """
    values = np.linalg.svd(jacobian, compute_uv=False).tolist()
    # A zero row (a leg of zero length) is an exact singularity, whatever rounding says.
    if zero_row:
        values[-1] = 0.0
    return values


def _single_pose_error_bound(geometry, pose, lengths, residual, converged, singular_values):
    """
    :attr:`ForwardKinematicsResult.pose_error_bound` of one solve, the same proof in floats.

    :param pose: the solution, six floats; ``lengths``: the six lengths solved for.
    :param singular_values: :func:`_single_singular_values` at the pose.
    """
    if not converged:
        return math.inf
    terms = _constants(geometry).error_bound_terms
    rho = geometry.platform_radius
    sigma = singular_values[-1] - SINGULAR_VALUE_ROUNDING_ULPS * _EPSILON * singular_values[0]
    if not sigma > 0.0:
        return math.inf
    offset = math.hypot(*pose[:3])
    error = residual + LENGTH_ROUNDING_ULPS * _EPSILON * max(
        offset + arm + base for arm, base in zip(terms.arms, terms.base_norms))
    eta = math.sqrt(6.0) * error / sigma
    # The legs' shortest lengths within the largest ball considered, 2 eta.
    shortest = [length - residual - 2.0 * eta * reach
                for length, reach in zip(lengths, terms.reaches)]
    if not min(shortest) > 0.0:
        return math.inf
    curvature = math.sqrt(sum((reach * reach / length + arm / (rho * rho)) ** 2
                              for reach, length, arm in zip(terms.reaches, shortest, terms.arms)))
    h = eta * curvature / sigma
    if not h <= 0.5:
        return math.inf
    radius = 2.0 * eta / (1.0 + math.sqrt(max(1.0 - 2.0 * h, 0.0)))
    return radius * max(1.0, 1.0 / rho) if radius >= 0.0 else math.inf


#: The machine epsilon of a float.
_EPSILON = float(np.finfo(float).eps)


def _hashable(value, dtype=float):
    """Bytes of a value or array, equal for values that compare equal (-0.0 and 0.0, NaNs)."""
    array = np.asarray(value, dtype=dtype)
    if dtype is float:
        array = np.where(np.isnan(array), np.nan, array + 0.0)
    return array.shape, array.tobytes()


def forward_kinematics(geometry, lengths, initial_guess=None, *,
                       tolerance=DEFAULT_TOLERANCE,
                       max_iterations=DEFAULT_MAX_ITERATIONS) -> ForwardKinematicsResult:
    """
    Pose of the platform from its six leg lengths, by Newton-Raphson.

    Each iteration solves ``J(x) dx = l(x) - lengths`` with the analytic :func:`jacobian` and
    takes ``x <- x - dx``, as in the paper's equation 8. Convergence is quadratic near the
    solution, so the default tolerance costs one or two iterations more than the paper's 1e-4.
    A platform has several assembly modes for the same lengths: the solver finds the one the
    initial guess leads to, normally the nearest.

    A solve keeps its Jacobian for the next step while it works well (while each step cuts the
    residual by ``JACOBIAN_REUSE_CONTRACTION`` or more): the classic modified Newton method,
    with the same stopping test. The first step from the home pose uses the home Jacobian,
    computed once per geometry, and a solve started from a previous result (tracking) starts
    with the Jacobian of that result. A batch takes, pose by pose, the steps of single solves,
    vectorised, with the same arithmetic: same iterates, iterations and reasons.

    Without an initial guess (a cold solve), the solve starts from the geometry's start table
    (:mod:`stewart_kinematics.model.start_table`, built on the first cold solve, 0.1 to 0.3 s):
    one Newton step from the working-mode sample nearest the lengths, with that sample's
    Jacobian, so that it takes about three steps instead of four from home (home is the
    middle cell's sample: its own lengths take no step). Where the table has no sample
    (lengths far from the workspace around home, or in another assembly mode), or where the
    solve from the table does not converge, it starts from the home pose as a solve given
    ``geometry.home_pose`` does, and returns that solve's result. ``iterations`` counts the
    steps after the start.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param lengths: leg lengths l_1..l_6 in metres, shape (6,) or (N, 6).
    :param initial_guess: starting pose(s), shape (6,) or (N, 6); default: the start table's
        sample, else ``geometry.home_pose`` (see above). When tracking a moving platform, start
        from the last solution: pass the last :class:`ForwardKinematicsResult` itself, and its
        Jacobian is reused too.
    :param tolerance: largest accepted leg length error, metres (default 1e-12).
    :param max_iterations: Newton-Raphson steps before giving up (default 50).
    :returns: a :class:`ForwardKinematicsResult`; non-convergence is reported there, not
        raised. In a batch, a row of lengths that are not finite and positive, or a guess that
        is not finite, is not solved and says so in its reason; the other rows are solved.
    :raises ValueError: if the shapes are wrong, the lengths or the guess of a single solve are
        not valid, or a limit is not positive.
    """
    jacobian_inverse = None
    if isinstance(initial_guess, ForwardKinematicsResult):
        if initial_guess.converged is True:
            jacobian_inverse = initial_guess._solve[2]
        initial_guess = initial_guess.pose
    if not (_is_real(tolerance) and 0.0 < tolerance < np.inf):
        raise ValueError(f'tolerance must be positive and finite (metres), got {tolerance!r}')
    if not (_is_real(max_iterations) and math.isfinite(max_iterations)
            and int(max_iterations) == max_iterations and max_iterations >= 1):
        raise ValueError(f'max_iterations must be a positive integer, got {max_iterations!r}')
    constants = _constants(geometry)
    # One solve: six valid floats each (the common case, checked without numpy's overhead).
    target = _single_values(lengths, positive=True)
    guess = constants.home_pose if initial_guess is None else _single_values(initial_guess)
    if target is None or guess is None:
        lengths = _as_rows(lengths, 'leg lengths')
        guess = _as_rows(geometry.home_pose if initial_guess is None else initial_guess,
                         'initial_guess')
        if lengths.ndim == 1 and guess.ndim == 1:
            target = as_leg_lengths(lengths).tolist()
            guess = as_poses(guess, 'initial_guess').tolist()
        else:
            target = None
    if target is not None:
        if initial_guess is None:
            return _forward_kinematics_cold(geometry, constants, target, tolerance,
                                            int(max_iterations))
        return _forward_kinematics_single(
            geometry, constants, target, list(guess), tolerance, int(max_iterations),
            jacobian_inverse)
    targets = np.atleast_2d(lengths)
    guesses = np.atleast_2d(guess)
    # One guess for every row of lengths, or one row of lengths for every guess; an empty
    # batch (N = 0) gives an empty result, as inverse_kinematics does.
    count = targets.shape[0] if guesses.shape[0] == 1 else guesses.shape[0]
    if targets.shape[0] not in (1, count):
        raise ValueError(
            f'lengths {lengths.shape} and initial_guess {guess.shape} must hold the same '
            'number of poses, or one of them a single one')
    targets = np.broadcast_to(targets, (count, 6))
    if initial_guess is None:
        return _forward_kinematics_cold_batch(geometry, constants, targets, tolerance,
                                              int(max_iterations))
    return _forward_kinematics_batch(
        geometry, constants, targets, np.array(np.broadcast_to(guesses, (count, 6))),
        tolerance, int(max_iterations))


def _forward_kinematics_single(geometry, constants, target, pose, tolerance, max_iterations,
                               jacobian_inverse):
    """
    Solve one pose in float arithmetic: modified Newton-Raphson (see :func:`forward_kinematics`).

    Steps are taken in the twist form ``[u_i, R p_i x u_i] [v, w] = l(x) - lengths`` and turned
    into Euler angle steps by :func:`_euler_step`: the same step as with :func:`jacobian`, whose
    rotation columns are these times ``E``.

    :param target: the six leg lengths, metres, as floats.
    :param pose: the initial guess, as six floats.
    :param jacobian_inverse: inverse twist Jacobian (nested lists) for the first step, or None.
    """
    if jacobian_inverse is None and tuple(pose) == constants.home_pose:
        jacobian_inverse = constants.home_jacobian_inverse
    iterations = 0
    reason = None  # no convergence within max_iterations, unless another reason is found
    last_residual = math.inf
    cos, sin = math.cos, math.sin
    for step in range(max_iterations + 1):
        # _single_euler_legs, keeping the cosines and sines that the Euler step needs.
        x, y, z, alpha, beta, gamma = pose
        cos_beta, sin_beta, cos_gamma, sin_gamma = cos(beta), sin(beta), cos(gamma), sin(gamma)
        legs = _legs(zyx_entries(cos(alpha), sin(alpha), cos_beta, sin_beta, cos_gamma,
                                 sin_gamma), x, y, z, constants.joint_pairs, math.sqrt)
        errors = [leg[0] - length for leg, length in zip(legs, target)]
        residual = max(map(abs, errors))
        if residual <= tolerance:
            reason = ''
            break
        if step == max_iterations:
            break
        if jacobian_inverse is None or residual > JACOBIAN_REUSE_CONTRACTION * last_residual:
            jacobian_inverse = _float_inverse(_float_twist_rows(legs))
            if jacobian_inverse is None:
                reason = SINGULAR_JACOBIAN
                break
        last_residual = residual
        if cos_beta == 0.0:  # the Euler rate matrix is singular
            reason = SINGULAR_JACOBIAN
            break
        stepped = _euler_step(pose, _apply(jacobian_inverse, errors), cos_beta, sin_beta,
                              cos_gamma, sin_gamma)
        # A diverging solve stops at its last plausible iterate, whose residual is known.
        if not all(abs(value) < DIVERGENCE_BOUND for value in stepped):
            reason = DIVERGED
            break
        pose = stepped
        iterations += 1
    if reason is None:
        reason = f'no convergence within {max_iterations} iterations'
    # Same rotation, canonical angles, as in the batch solver.
    pose = np.array(list(pose[:3]) + _single_canonical_angles(*pose[3:]))
    pose.flags.writeable = False
    return ForwardKinematicsResult(
        pose=pose, converged=reason == '', iterations=iterations, residual=residual,
        reason=reason, _solve=(geometry, target, jacobian_inverse))


def _cold_start(constants, target):
    """
    Start of a solve without a guess, from the start table: ``(pose, jacobian_inverse)``.

    One Newton step from the sample of the lengths' cell, with the sample's Jacobian (see
    :mod:`stewart_kinematics.model.start_table`); None, to start from home instead, where the
    table has no sample for the lengths.

    :param target: the six leg lengths, metres, as floats.
    :returns: six floats and the sample's inverse twist Jacobian (nested lists), or None.
    """
    table = constants.start_table
    cell = -1 if table is None else table.cell(target)
    if cell < 0:
        return None
    sample = table.entries[cell].tolist()
    inverse = table.inverses[cell].tolist()
    errors = [length - wanted for length, wanted in zip(sample[6:12], target)]
    return _euler_step(sample[:6], _apply(inverse, errors), *sample[12:]), inverse


def _forward_kinematics_cold(geometry, constants, target, tolerance, max_iterations):
    """One solve without a guess: from the start table, else (or if that fails) from home."""
    start = _cold_start(constants, target)
    if start is not None:
        result = _forward_kinematics_single(geometry, constants, target, start[0], tolerance,
                                            max_iterations, start[1])
        if result.converged:
            return result
    return _forward_kinematics_single(geometry, constants, target, list(constants.home_pose),
                                      tolerance, max_iterations, None)


def _batch_cold_starts(constants, targets):
    """
    :func:`_cold_start` of each row of ``targets`` (N, 6), with the same arithmetic.

    :returns: ``(started (N,), poses (N, 6), inverses (N, 6, 6))``: the rows started from the
        table, and every row's start (home for the others) and inverse twist Jacobian.
    """
    count = len(targets)
    poses = np.array(np.broadcast_to(constants.home_pose, (count, 6)))
    inverses = np.zeros((count, 6, 6))
    started = np.zeros(count, dtype=bool)
    table = constants.start_table
    rows = np.flatnonzero(_valid_lengths(targets))
    if table is None or rows.size == 0:
        return started, poses, inverses
    cells = table.cells_of(targets[rows])
    rows, cells = rows[cells >= 0], cells[cells >= 0]
    sample = table.entries[cells]
    inverses[rows] = table.inverses[cells]
    errors = sample[:, 6:12] - targets[rows]
    # _apply with the six rows of every sample as one row: see _forward_kinematics_batch.
    twists = _apply([np.ascontiguousarray(inverses[rows].transpose(2, 1, 0))], list(errors.T))[0]
    poses[rows] = np.stack(_euler_step(sample[:, :6].T, twists, *sample[:, 12:].T), axis=-1)
    started[rows] = True
    return started, poses, inverses


def _forward_kinematics_cold_batch(geometry, constants, targets, tolerance, max_iterations):
    """Solve a batch without guesses: :func:`_forward_kinematics_cold` of each row, vectorised."""
    started, poses, inverses = _batch_cold_starts(constants, targets)
    result = _forward_kinematics_batch(geometry, constants, targets, poses, tolerance,
                                       max_iterations, (started, inverses))
    failed = np.flatnonzero(started & ~result.converged)
    if failed.size == 0:
        return result
    again = _forward_kinematics_batch(
        geometry, constants, targets[failed],
        np.array(np.broadcast_to(constants.home_pose, (failed.size, 6))), tolerance,
        max_iterations)
    pose, converged = np.array(result.pose), np.array(result.converged)
    iterations, residual = np.array(result.iterations), np.array(result.residual)
    reason = list(result.reason)
    pose[failed], converged[failed] = again.pose, again.converged
    iterations[failed], residual[failed] = again.iterations, again.residual
    for row, text in zip(failed.tolist(), again.reason):
        reason[row] = text
    pose.flags.writeable = False
    return ForwardKinematicsResult(
        pose=pose, converged=converged, iterations=iterations, residual=residual,
        reason=tuple(reason), _solve=(geometry, targets, None))


def _forward_kinematics_batch(geometry, constants, targets, poses, tolerance, max_iterations,
                              start_inverses=None):
    """
    Solve a batch of poses at once: the algorithm of :func:`_forward_kinematics_single`.

    Each pose keeps its own inverse twist Jacobian and takes the same steps, with the same
    stopping rules and reasons, as it would alone, computed by the same formulas on arrays of
    the poses still being solved.

    :param targets: leg lengths, metres, shape (N, 6).
    :param poses: initial guesses, shape (N, 6); overwritten by the iterates.
    :param start_inverses: ``(rows (N,), inverses (N, 6, 6))``: inverse twist Jacobians for
        the first step of the rows where ``rows`` is True, or None.
    """
    count = len(poses)
    iterations = np.zeros(count, dtype=int)
    residual = np.full(count, np.inf)
    last_residual = np.full(count, np.inf)
    reason = np.full(count, f'no convergence within {max_iterations} iterations', dtype=object)
    valid_guess = np.all(np.isfinite(poses), axis=-1)
    reason[~valid_guess] = INVALID_GUESS
    valid_lengths = _valid_lengths(targets)
    reason[~valid_lengths] = INVALID_LENGTHS
    inverses = np.empty((count, 6, 6))
    has_inverse = np.zeros(count, dtype=bool)
    if constants.home_jacobian_inverse is not None:
        has_inverse = np.all(poses == constants.home_pose, axis=-1)
        inverses[has_inverse] = constants.home_jacobian_inverse
    if start_inverses is not None:
        rows, start = start_inverses
        has_inverse = has_inverse | rows
        inverses[rows] = start[rows]
    active = np.flatnonzero(valid_lengths & valid_guess)
    for step in range(max_iterations + 1):
        # Leg by pose, (6, n): see _batch_legs.
        lengths, vectors = _batch_euler_legs(constants, poses[active])
        errors = lengths - targets[active].T
        residual[active] = np.max(np.abs(errors), axis=0)
        going = residual[active] > tolerance
        reason[active[~going]] = ''
        active, errors = active[going], errors[:, going]
        if active.size == 0 or step == max_iterations:
            break
        refresh = ~has_inverse[active] | (
            residual[active] > JACOBIAN_REUSE_CONTRACTION * last_residual[active])
        if np.any(refresh):
            rows = np.flatnonzero(going)[refresh]
            new, invertible = _invert_each(_batch_twist_jacobian(
                lengths[:, rows], [vector[:, rows] for vector in vectors]))
            inverses[active[refresh]] = new
            has_inverse[active[refresh]] = invertible
            reason[active[refresh][~invertible]] = SINGULAR_JACOBIAN
            solvable = np.ones(active.size, dtype=bool)
            solvable[np.flatnonzero(refresh)[~invertible]] = False
            active, errors = active[solvable], errors[:, solvable]
        last_residual[active] = residual[active]
        # _apply with the six rows of every pose as one row: its columns as arrays (6, n).
        columns = np.ascontiguousarray(inverses[active].transpose(2, 1, 0))
        twists = _apply([columns], errors)[0]
        stepped, defined = _batch_euler_step(poses[active], twists)
        reason[active[~defined]] = SINGULAR_JACOBIAN
        # A diverging solve stops at its last plausible iterate, whose residual is known.
        diverged = defined & ~np.all(np.abs(stepped) < DIVERGENCE_BOUND, axis=-1)
        reason[active[diverged]] = DIVERGED
        moving = defined & ~diverged
        active = active[moving]
        poses[active] = stepped[moving]
        iterations[active] += 1

    # Same rotation, canonical angles: beta in [-pi/2, pi/2], alpha and gamma in (-pi, pi].
    outside = np.flatnonzero(~_canonical(*poses[:, 3:].T))
    cosines, sines = np.cos(poses[outside, 3:]), np.sin(poses[outside, 3:])
    entries = zyx_entries(cosines[:, 0], sines[:, 0], cosines[:, 1], sines[:, 1],
                          cosines[:, 2], sines[:, 2])
    poses[outside, 3:] = np.stack(zyx_angles(entries, _ArrayOperations), axis=-1)
    poses.flags.writeable = False
    return ForwardKinematicsResult(
        pose=poses, converged=reason == '', iterations=iterations, residual=residual,
        reason=tuple(reason.tolist()), _solve=(geometry, targets, None))


_FLOAT = np.dtype(float)


def _is_real(value) -> bool:
    """Whether ``value`` is a real number (a bool is not)."""
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, (bool, np.bool_))


def _single_values(values, positive=False):
    """
    Six floats of one pose or one set of leg lengths, or None to leave it to the full checks.

    The fast path of the argument checks for one solve: None unless ``values`` is an array,
    list or tuple of six numbers that are finite (and positive, with ``positive``), so that
    :func:`as_poses` and :func:`as_leg_lengths` say what is wrong, or see a batch.

    :returns: a list of six floats, or None.
    """
    if type(values) is np.ndarray:   # exactly: a matrix or masked array takes the full checks
        if values.shape != (6,) or values.dtype.kind not in 'iuf':
            return None
        if values.dtype == _FLOAT:  # the common case: six Python floats at once
            values = values.tolist()
            # A sum of floats is finite only when each one is (else: the full checks).
            if math.isfinite(sum(values)) and (not positive or min(values) > 0.0):
                return values
            return None
        values = values.tolist()
    elif not isinstance(values, (list, tuple)) or len(values) != 6:
        return None
    # Numbers only: a string or a bool is left to the full checks, which refuse it.
    if not all(type(value) in (float, int) for value in values):
        return None
    try:
        values = [float(value) for value in values]
    except OverflowError:   # an integer beyond the float range
        return None
    low = 0.0 if positive else -math.inf
    return values if all(low < value < math.inf for value in values) else None
