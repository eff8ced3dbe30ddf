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
Rotation conversions: Euler ZYX angles, rotation matrices and unit quaternions.

The one rotation convention of this package is the paper's:
``R = Rz(gamma) @ Ry(beta) @ Rx(alpha)``, that is roll ``alpha`` about x, then pitch ``beta``
about y, then yaw ``gamma`` about z, all about the fixed base axes. ``R`` maps vectors from the
platform frame to the base frame. Angles are in radians.

Quaternions are ``(x, y, z, w)``, the order of geometry_msgs/msg/Quaternion.

Every function accepts a single value or a batch (leading dimensions) and never loops in Python.
"""

import math

import numpy as np

from stewart_kinematics.model.arrays import as_float_array, preview

#: Below this norm a quaternion carries no rotation and is rejected.
QUATERNION_NORM_MIN = 1e-9
#: Where cos(beta) is below this (gimbal lock, or as near it as rounding cannot tell), alpha is
#: set to 0 and gamma carries the whole rotation about the vertical; the angles rebuild the
#: rotation just as exactly on either side (see :func:`matrix_to_euler_zyx`). At 1e-12 the
#: rotations snapped to alpha = 0 were rebuilt only to 1e-12 rad; at 1e-15, to 1e-15 rad.
GIMBAL_LOCK_COS_BETA = 1e-15
#: Largest deviation of ``R^T R`` from the identity of a matrix taken as a rotation: rounding
#: and a product of a few rotations stay far below; a matrix that is no rotation goes beyond.
ROTATION_MATRIX_TOLERANCE = 1e-6


def zyx_entries(cos_alpha, sin_alpha, cos_beta, sin_beta, cos_gamma, sin_gamma):
    """
    Entries ``(r11, r12, r13, r21, r22, r23, r31, r32, r33)`` of ``Rz(gamma) Ry(beta) Rx(alpha)``.

    The one formula of the rotation matrix (the paper's, section 3), for floats (one rotation)
    or numpy arrays (a batch) alike: the same operations in the same order either way.
    """
    sb_sa, sb_ca = sin_beta * sin_alpha, sin_beta * cos_alpha
    return (cos_gamma * cos_beta, cos_gamma * sb_sa - sin_gamma * cos_alpha,
            cos_gamma * sb_ca + sin_gamma * sin_alpha,
            sin_gamma * cos_beta, sin_gamma * sb_sa + cos_gamma * cos_alpha,
            sin_gamma * sb_ca - cos_gamma * sin_alpha,
            -sin_beta, cos_beta * sin_alpha, cos_beta * cos_alpha)


def euler_zyx_to_matrix(angles):
    """
    Rotation matrix of Euler ZYX angles.

    :param angles: ``(alpha, beta, gamma)`` in radians, shape (3,) or (..., 3).
    :returns: ``Rz(gamma) @ Ry(beta) @ Rx(alpha)``, shape (3, 3) or (..., 3, 3).
    :raises ValueError: if the shape is wrong or an angle is not finite.

    >>> import numpy as np
    >>> from stewart_kinematics import euler_zyx_to_matrix
    >>> euler_zyx_to_matrix([0.0, 0.0, np.pi / 2]).round(12) @ [1.0, 0.0, 0.0]
    array([0., 1., 0.])
    """
    angles = _euler_angles(angles)
    if angles.shape == (3,):
        # One rotation (the nodes' case): scalars cost less than numpy's per-call overhead.
        return np.array(euler_zyx_matrix_entries(*angles.tolist())).reshape(3, 3)
    cosines, sines = np.cos(angles), np.sin(angles)
    entries = zyx_entries(cosines[..., 0], sines[..., 0], cosines[..., 1], sines[..., 1],
                          cosines[..., 2], sines[..., 2])
    return np.stack(entries, axis=-1).reshape(angles.shape[:-1] + (3, 3))


def euler_zyx_matrix_entries(alpha, beta, gamma):
    """
    Entries of ``Rz(gamma) Ry(beta) Rx(alpha)`` for three floats (radians).

    The scalar form of :func:`euler_zyx_to_matrix`, for code that works on one pose in float
    arithmetic.

    :returns: ``(r11, r12, r13, r21, r22, r23, r31, r32, r33)``, row by row.
    """
    return zyx_entries(math.cos(alpha), math.sin(alpha), math.cos(beta), math.sin(beta),
                       math.cos(gamma), math.sin(gamma))


class _FloatOperations:
    """The functions :func:`zyx_angles` needs, for floats."""

    atan2, cos, sin = math.atan2, math.cos, math.sin

    @staticmethod
    def where(condition, if_true, if_false):
        return if_true if condition else if_false


class _ArrayOperations:
    """The functions :func:`zyx_angles` needs, for numpy arrays."""

    atan2, cos, sin, where = np.arctan2, np.cos, np.sin, np.where


def zyx_angles(entries, operations=_FloatOperations):
    """
    Euler ZYX angles ``(alpha, beta, gamma)`` of rotation matrix entries; the one formula.

    ``alpha`` comes from the last row, ``(r32, r33) = cos(beta) (sin(alpha), cos(alpha))``, or
    is 0 where ``cos(beta)`` is below :data:`GIMBAL_LOCK_COS_BETA`. Then ``beta`` and ``gamma``
    come from ``R Rx(alpha)^T = Rz(gamma) Ry(beta)``, whose entries ``-sin(gamma)``,
    ``cos(gamma)`` and ``cos(beta)`` are combinations of unit size for any ``beta``: so the
    three angles rebuild the rotation to rounding even where ``alpha`` itself is poorly
    determined (``beta`` near +-90 degrees), instead of taking ``alpha`` and ``gamma`` each
    from entries of size ``cos(beta)`` that rounding has blurred.

    :param entries: ``(r11, r12, ..., r33)``, floats or arrays of one shape.
    :param operations: :class:`_FloatOperations` or :class:`_ArrayOperations`.
    :returns: ``(alpha, beta, gamma)``: beta in [-pi/2, pi/2], alpha and gamma in (-pi, pi].
    """
    _, r12, r13, _, r22, r23, r31, r32, r33 = entries
    locked = r32 * r32 + r33 * r33 < GIMBAL_LOCK_COS_BETA * GIMBAL_LOCK_COS_BETA
    # Adding 0.0 turns -0.0 into 0.0, so that atan2 gives pi rather than -pi for a half turn.
    alpha = operations.where(locked, 0.0, operations.atan2(r32 + 0.0, r33))
    cos_alpha, sin_alpha = operations.cos(alpha), operations.sin(alpha)
    sin_gamma = r13 * sin_alpha - r12 * cos_alpha
    cos_gamma = r22 * cos_alpha - r23 * sin_alpha
    cos_beta = r32 * sin_alpha + r33 * cos_alpha
    gamma = operations.atan2(sin_gamma + 0.0, cos_gamma)
    # atan2 of a tiny negative sine and a cosine of -1 rounds to -pi itself: the range is
    # (-pi, pi], so that half turn is pi.
    return (operations.where(alpha > -math.pi, alpha, math.pi), operations.atan2(-r31, cos_beta),
            operations.where(gamma > -math.pi, gamma, math.pi))


def canonical_zyx_angles(alpha, beta, gamma):
    """
    Euler angles of the same rotation in the canonical ranges (see :func:`zyx_angles`).

    Angles already in them are kept as they are, to the bit.

    :param alpha: radians, a float; ``beta`` and ``gamma`` likewise.
    :returns: ``[alpha, beta, gamma]``, a list of floats.
    """
    if in_canonical_ranges(alpha, beta, gamma):
        return [alpha, beta, gamma]
    return list(zyx_angles(euler_zyx_matrix_entries(alpha, beta, gamma)))


def canonical_zyx_angle_rows(angles):
    """
    :func:`canonical_zyx_angles` of each row of ``angles``, shape (n, 3), in place.

    Rows already in the canonical ranges are kept as they are, to the bit.
    """
    outside = np.flatnonzero(~in_canonical_ranges(*angles.T))
    cosines, sines = np.cos(angles[outside]), np.sin(angles[outside])
    entries = zyx_entries(cosines[:, 0], sines[:, 0], cosines[:, 1], sines[:, 1],
                          cosines[:, 2], sines[:, 2])
    angles[outside] = np.stack(zyx_angles(entries, _ArrayOperations), axis=-1)


def in_canonical_ranges(alpha, beta, gamma):
    """Whether beta is in (-pi/2, pi/2), alpha and gamma in (-pi, pi]; floats or arrays."""
    return ((-_HALF_PI < beta) & (beta < _HALF_PI) & (-math.pi < alpha) & (alpha <= math.pi)
            & (-math.pi < gamma) & (gamma <= math.pi))


_HALF_PI = 0.5 * math.pi


def matrix_to_euler_zyx(rotation):
    """
    Euler ZYX angles of a rotation matrix.

    Returns ``beta`` in [-pi/2, pi/2] and ``alpha``, ``gamma`` in (-pi, pi]. At gimbal lock
    (``|beta| = pi/2``) only ``gamma - alpha`` or ``gamma + alpha`` is defined; ``alpha`` is then
    set to 0. The angles rebuild ``rotation`` to rounding everywhere, gimbal lock and its
    neighbourhood included (see :func:`zyx_angles`).

    :param rotation: rotation matrix, shape (3, 3) or (..., 3, 3).
    :returns: ``(alpha, beta, gamma)`` in radians, shape (3,) or (..., 3).
    :raises ValueError: if the shape is wrong, an entry is not finite or a matrix is no
        rotation (``R^T R`` off the identity by more than ``ROTATION_MATRIX_TOLERANCE``, or a
        reflection).
    """
    rotation = _rotation_matrices(rotation)
    if rotation.shape == (3, 3):
        return np.array(zyx_angles(rotation.ravel().tolist()))
    entries = [rotation[..., row, column] for row in range(3) for column in range(3)]
    return np.stack(zyx_angles(entries, _ArrayOperations), axis=-1)


def quaternion_to_matrix(quaternion):
    """
    Rotation matrix of a quaternion ``(x, y, z, w)``.

    The quaternion is normalised first, so any non-zero quaternion is accepted; use
    :func:`normalize_quaternion` beforehand to detect a non-unit input.

    :param quaternion: shape (4,) or (..., 4).
    :returns: rotation matrix, shape (3, 3) or (..., 3, 3).
    :raises ValueError: if a quaternion is not finite or has (nearly) zero norm.
    """
    unit = normalize_quaternion(quaternion)
    if unit.shape == (4,):
        # One quaternion (the nodes' case): floats cost less than numpy's per-call overhead.
        return np.array(_quaternion_entries(*unit.tolist())).reshape(3, 3)
    x, y, z, w = np.moveaxis(unit, -1, 0)
    return np.stack(_quaternion_entries(x, y, z, w), axis=-1).reshape(np.shape(x) + (3, 3))


def _quaternion_entries(x, y, z, w):
    """Entries r11..r33 of the rotation of a unit quaternion; floats or arrays alike."""
    return (1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w),
            2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w),
            2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y))


def matrix_to_quaternion(rotation):
    """
    Convert a rotation matrix to a unit quaternion ``(x, y, z, w)`` with ``w >= 0``.

    Uses Shepperd's method (the largest of the four candidate pivots), which stays accurate for
    every rotation, including half turns where ``w`` is near zero.

    :param rotation: rotation matrix, shape (3, 3) or (..., 3, 3).
    :returns: shape (4,) or (..., 4).
    :raises ValueError: as :func:`matrix_to_euler_zyx`.
    """
    rotation = _rotation_matrices(rotation)
    if rotation.shape == (3, 3):
        return _matrix_to_quaternion_single(rotation.tolist())
    r = rotation
    trace = r[..., 0, 0] + r[..., 1, 1] + r[..., 2, 2]
    # Four times the square of each component; the largest gives the best-conditioned division.
    pivots = np.stack([
        1.0 + 2.0 * r[..., 0, 0] - trace,
        1.0 + 2.0 * r[..., 1, 1] - trace,
        1.0 + 2.0 * r[..., 2, 2] - trace,
        1.0 + trace,
    ], axis=-1)
    best = np.argmax(pivots, axis=-1)
    scale = np.sqrt(np.maximum(np.take_along_axis(pivots, best[..., None], -1)[..., 0], 0.0))
    half_inverse = 0.5 / scale
    # Off-diagonal sums and differences: each equals 4 * (product of two components).
    xy = r[..., 0, 1] + r[..., 1, 0]
    xz = r[..., 0, 2] + r[..., 2, 0]
    yz = r[..., 1, 2] + r[..., 2, 1]
    wx = r[..., 2, 1] - r[..., 1, 2]
    wy = r[..., 0, 2] - r[..., 2, 0]
    wz = r[..., 1, 0] - r[..., 0, 1]
    candidates = np.stack([
        np.stack([0.5 * scale, xy * half_inverse, xz * half_inverse, wx * half_inverse], -1),
        np.stack([xy * half_inverse, 0.5 * scale, yz * half_inverse, wy * half_inverse], -1),
        np.stack([xz * half_inverse, yz * half_inverse, 0.5 * scale, wz * half_inverse], -1),
        np.stack([wx * half_inverse, wy * half_inverse, wz * half_inverse, 0.5 * scale], -1),
    ], axis=-2)
    quaternion = np.take_along_axis(candidates, best[..., None, None], -2)[..., 0, :]
    quaternion = quaternion / np.linalg.norm(quaternion, axis=-1, keepdims=True)
    return np.where(quaternion[..., 3:] < 0.0, -quaternion, quaternion)


def _matrix_to_quaternion_single(r):
    """Shepperd's method for one matrix (nested lists), in scalars: the nodes' hot path."""
    trace = r[0][0] + r[1][1] + r[2][2]
    pivots = (1.0 + 2.0 * r[0][0] - trace, 1.0 + 2.0 * r[1][1] - trace,
              1.0 + 2.0 * r[2][2] - trace, 1.0 + trace)
    best = max(range(4), key=pivots.__getitem__)
    scale = math.sqrt(max(pivots[best], 0.0))
    half_inverse = 0.5 / scale
    xy, xz, yz = r[0][1] + r[1][0], r[0][2] + r[2][0], r[1][2] + r[2][1]
    wx, wy, wz = r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]
    quaternion = np.array((
        (0.5 * scale, xy * half_inverse, xz * half_inverse, wx * half_inverse),
        (xy * half_inverse, 0.5 * scale, yz * half_inverse, wy * half_inverse),
        (xz * half_inverse, yz * half_inverse, 0.5 * scale, wz * half_inverse),
        (wx * half_inverse, wy * half_inverse, wz * half_inverse, 0.5 * scale))[best])
    quaternion /= math.sqrt(float(quaternion @ quaternion))
    return -quaternion if quaternion[3] < 0.0 else quaternion


def euler_zyx_to_quaternion(angles):
    """
    Convert Euler ZYX angles (radians) to a unit quaternion ``(x, y, z, w)`` with ``w >= 0``.

    :param angles: ``(alpha, beta, gamma)``, shape (3,) or (..., 3).
    :returns: shape (4,) or (..., 4).
    :raises ValueError: as :func:`euler_zyx_to_matrix`.
    """
    angles = _euler_angles(angles)
    if angles.shape == (3,):
        # One rotation (the nodes' case): floats cost less than numpy's per-call overhead.
        alpha, beta, gamma = (0.5 * angle for angle in angles.tolist())
        quaternion = np.array(_half_angle_product(
            math.cos(alpha), math.sin(alpha), math.cos(beta), math.sin(beta), math.cos(gamma),
            math.sin(gamma)))
        return -quaternion if quaternion[3] < 0.0 else quaternion
    half = 0.5 * angles
    cosines, sines = np.cos(half), np.sin(half)
    quaternion = np.stack(_half_angle_product(
        cosines[..., 0], sines[..., 0], cosines[..., 1], sines[..., 1], cosines[..., 2],
        sines[..., 2]), axis=-1)
    return np.where(quaternion[..., 3:] < 0.0, -quaternion, quaternion)


def _half_angle_product(ca, sa, cb, sb, cg, sg):
    """
    ``q_z(gamma) q_y(beta) q_x(alpha)`` from the cosines and sines of the half angles.

    The one formula of the quaternion of Euler ZYX angles, for floats or arrays alike.

    :returns: ``(x, y, z, w)``.
    """
    return (sa * cb * cg - ca * sb * sg, ca * sb * cg + sa * cb * sg,
            ca * cb * sg - sa * sb * cg, ca * cb * cg + sa * sb * sg)


def quaternion_to_euler_zyx(quaternion):
    """
    Euler ZYX angles ``(alpha, beta, gamma)`` in radians of a quaternion ``(x, y, z, w)``.

    :param quaternion: shape (4,) or (..., 4); normalised first.
    :returns: shape (3,) or (..., 3), ranges as in :func:`matrix_to_euler_zyx`.
    """
    return matrix_to_euler_zyx(quaternion_to_matrix(quaternion))


def normalize_quaternion(quaternion):
    """
    Scale a quaternion ``(x, y, z, w)`` to unit norm.

    :param quaternion: shape (4,) or (..., 4).
    :returns: the unit quaternion, same shape.
    :raises ValueError: if a quaternion has a non-finite component or a norm below
        :data:`QUATERNION_NORM_MIN`; such a quaternion describes no rotation.
    """
    quaternion = as_float_array(quaternion, 'quaternion')
    if quaternion.shape[-1:] != (4,):
        raise ValueError(f'quaternions must have shape (..., 4), got {quaternion.shape}')
    if quaternion.shape == (4,):
        # One quaternion (the nodes' case), in scalars; NaN fails both comparisons.
        components = quaternion.tolist()
        norm = math.sqrt(sum(value * value for value in components))
        if QUATERNION_NORM_MIN <= norm < math.inf:
            return np.array([value / norm for value in components])
    if not np.all(np.isfinite(quaternion)):
        raise ValueError(f'quaternion components must be finite, got {preview(quaternion)}')
    with np.errstate(over='ignore'):  # an overflow to inf is handled below
        norm = np.linalg.norm(quaternion, axis=-1, keepdims=True)
    if np.any(norm < QUATERNION_NORM_MIN):
        raise ValueError(
            f'quaternion norm must be at least {QUATERNION_NORM_MIN:g}, got {norm.min():g}: '
            'a zero quaternion describes no rotation')
    if not np.all(np.isfinite(norm)):
        # Finite components whose squares overflow (such as 1e200): scale them down first.
        quaternion = quaternion / np.max(np.abs(quaternion), axis=-1, keepdims=True)
        norm = np.linalg.norm(quaternion, axis=-1, keepdims=True)
    return quaternion / norm


def _euler_angles(angles):
    """Euler angles as a float array (..., 3) of finite angles, or raise ValueError."""
    angles = as_float_array(angles, 'Euler angles')
    if angles.shape[-1:] != (3,):
        raise ValueError(f'Euler angles must have shape (..., 3), got {angles.shape}')
    if not (angles.shape == (3,) and all(map(math.isfinite, angles.tolist()))
            or np.all(np.isfinite(angles))):
        raise ValueError(f'Euler angles must be finite (radians), got {preview(angles)}')
    return angles


def _rotation_matrices(rotation):
    """Rotation matrices as a float array (..., 3, 3), checked to be rotations, or raise."""
    rotation = as_float_array(rotation, 'rotation matrix')
    if rotation.shape[-2:] != (3, 3):
        raise ValueError(f'rotation matrices must have shape (..., 3, 3), got {rotation.shape}')
    if rotation.shape == (3, 3) and _is_rotation(rotation.ravel().tolist()):
        return rotation   # one matrix (the nodes' case), checked in floats
    with np.errstate(over='ignore', invalid='ignore'):
        deviation = np.max(np.abs(np.swapaxes(rotation, -1, -2) @ rotation - np.eye(3)),
                           axis=(-2, -1), initial=0.0) if rotation.size else np.zeros(0)
        determinant = np.linalg.det(rotation) if rotation.size else np.zeros(0)
    if not (np.all(deviation <= ROTATION_MATRIX_TOLERANCE) and np.all(determinant > 0.0)):
        raise ValueError(f'rotation matrix must be a rotation (R^T R = I within '
                         f'{ROTATION_MATRIX_TOLERANCE:g}, determinant +1, finite), got '
                         f'{preview(rotation)}')
    return rotation


def _is_rotation(entries) -> bool:
    """Whether nine floats, row by row, are a rotation (``_rotation_matrices``' test)."""
    r11, r12, r13, r21, r22, r23, r31, r32, r33 = entries
    columns = ((r11, r21, r31), (r12, r22, r32), (r13, r23, r33))
    deviation = max(abs(sum(a * b for a, b in zip(columns[i], columns[j])) - (i == j))
                    for i in range(3) for j in range(i, 3))
    determinant = (r11 * (r22 * r33 - r23 * r32) - r12 * (r21 * r33 - r23 * r31)
                   + r13 * (r21 * r32 - r22 * r31))
    return deviation <= ROTATION_MATRIX_TOLERANCE and determinant > 0.0


def rotation_angle_between(rotation_a, rotation_b):
    """
    Angle in radians of the rotation that takes ``rotation_a`` to ``rotation_b``.

    A frame-independent orientation error: 0 for equal rotations, at most pi.

    :param rotation_a: shape (3, 3) or (..., 3, 3).
    :param rotation_b: same shape as ``rotation_a``.
    :returns: shape () or (...,).
    """
    relative = np.swapaxes(np.asarray(rotation_a, dtype=float), -1, -2) @ rotation_b
    # The quaternion's vector part gives an accurate angle near zero, where arccos of the trace
    # would lose half of the digits.
    if relative.shape == (3, 3):
        x, y, z, w = _matrix_to_quaternion_single(relative.tolist()).tolist()
        return 2.0 * math.atan2(math.sqrt(x * x + y * y + z * z), w)
    quaternion = matrix_to_quaternion(relative)
    return 2.0 * np.arctan2(np.linalg.norm(quaternion[..., :3], axis=-1), quaternion[..., 3])


def rotation_vector_to_matrix(rotation_vector):
    """
    Rotation matrix of a rotation vector (the exponential map of SO(3), Rodrigues' formula).

    :param rotation_vector: axis times angle in radians, shape (3,) or (..., 3).
    :returns: ``exp([r]x)``, shape (3, 3) or (..., 3, 3); exact to rounding near zero too.
    """
    vector = np.asarray(rotation_vector, dtype=float)
    if vector.shape[-1:] != (3,):
        raise ValueError(f'rotation vectors must have shape (..., 3), got {vector.shape}')
    squared = np.sum(vector * vector, axis=-1)
    angle = np.sqrt(squared)
    small = angle < 1e-4
    safe = np.where(small, 1.0, angle)
    # sin(t)/t and (1 - cos(t))/t^2, by their series where t is small (error below 1e-17).
    first = np.where(small, 1.0 - squared / 6.0 + squared * squared / 120.0, np.sin(safe) / safe)
    second = np.where(small, 0.5 - squared / 24.0 + squared * squared / 720.0,
                      (1.0 - np.cos(safe)) / (safe * safe))
    # R = I + first [r]x + second [r]x^2, with [r]x^2 = r r^T - |r|^2 I, entry by entry.
    rotation = second[..., None, None] * vector[..., :, None] * vector[..., None, :]
    diagonal = 1.0 - second * squared
    for axis in range(3):
        rotation[..., axis, axis] += diagonal
    x, y, z = (first * vector[..., axis] for axis in range(3))
    rotation[..., 0, 1] -= z
    rotation[..., 1, 0] += z
    rotation[..., 0, 2] += y
    rotation[..., 2, 0] -= y
    rotation[..., 1, 2] -= x
    rotation[..., 2, 1] += x
    return rotation


def matrix_to_rotation_vector(rotation):
    """
    Rotation vector of a rotation matrix (the logarithm of SO(3)): axis times angle.

    :param rotation: shape (3, 3) or (..., 3, 3).
    :returns: shape (3,) or (..., 3), angle in [0, pi] radians.
    """
    quaternion = matrix_to_quaternion(np.asarray(rotation, dtype=float))
    vector, w = quaternion[..., :3], quaternion[..., 3]
    norm = np.linalg.norm(vector, axis=-1)
    small = norm < 1e-8
    # 2 atan2(|v|, w) / |v|, which tends to 2 / w as |v| -> 0.
    scale = np.where(small, 2.0 / np.where(small, w, 1.0),
                     2.0 * np.arctan2(norm, w) / np.where(small, 1.0, norm))
    return vector * scale[..., None]
