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
:mod:`stewart_kinematics.geometry` and :mod:`stewart_kinematics.rotations`. Every function takes
one pose, shape (6,), or a batch, shape (N, 6), and loops over no poses in Python.
"""

from dataclasses import dataclass, field
from functools import cached_property
import math
from typing import Optional, Tuple, Union
import weakref

import numpy as np

from stewart_kinematics.rotations import (
    euler_zyx_matrix_entries,
    euler_zyx_to_matrix,
    GIMBAL_LOCK_COS_BETA,
    matrix_to_euler_zyx,
)

#: Default Newton-Raphson tolerance: the largest leg length error accepted, metres.
DEFAULT_TOLERANCE = 1e-12
#: Default Newton-Raphson iteration limit.
DEFAULT_MAX_ITERATIONS = 50
#: An iterate with a coordinate beyond this (metres or radians) has diverged: no platform
#: reaches a kilometre, and angles wound a hundred times round mean the iteration is lost.
DIVERGENCE_BOUND = 1e3
#: Modified Newton (one solve): a step that cut the largest leg length error by at least this
#: factor shows that its Jacobian still fits, and the next step reuses it. Far from the solution
#: a step cuts less, and a new Jacobian is computed, as in plain Newton-Raphson.
JACOBIAN_REUSE_CONTRACTION = 1e-4
#: Reasons a solve fails, as ForwardKinematicsResult.reason gives them.
SINGULAR_JACOBIAN = 'singular Jacobian: the pose is at a singularity'
DIVERGED = 'diverged: the next iterate left every plausible pose'
#: Rounding floor of a computed leg length, in units of the length's last place: the residual
#: of a solve is known no better than this (see ForwardKinematicsResult.pose_error_bound).
LENGTH_ROUNDING_ULPS = 4.0
#: Poses per block of a batched inverse kinematics: the temporaries of one block stay in the
#: processor's cache, which doubles the throughput of batches of millions.
IK_BLOCK_SIZE = 4096


def as_poses(poses, name='poses') -> np.ndarray:
    """
    Check and convert poses ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).

    :param poses: shape (6,) or (N, 6).
    :returns: a float array of the same shape.
    :raises ValueError: if the shape is wrong or a value is not finite.
    """
    poses = np.asarray(poses, dtype=float)
    if poses.ndim not in (1, 2) or poses.shape[-1] != 6:
        raise ValueError(f'{name} must have shape (6,) or (N, 6), got {poses.shape}')
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
    lengths = np.asarray(lengths, dtype=float)
    if lengths.ndim not in (1, 2) or lengths.shape[-1] != 6:
        raise ValueError(f'{name} must have shape (6,) or (N, 6), got {lengths.shape}')
    allowed = np.isfinite(lengths) & (lengths > 0.0)
    if not np.all(allowed):
        first_bad = np.atleast_2d(lengths)[~np.all(np.atleast_2d(allowed), axis=-1)][0]
        raise ValueError(f'{name} must be finite and positive (metres), got {first_bad.tolist()}')
    return lengths


def leg_vectors(geometry, position, rotation) -> np.ndarray:
    """
    Leg vectors ``t + R p_i - b_i`` from each base joint to its platform joint.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param position: platform origin in the base frame, metres, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation matrix, shape (3, 3) or (N, 3, 3).
    :returns: in the base frame, metres, shape (6, 3) or (N, 6, 3).
    """
    position = np.asarray(position, dtype=float)
    rotated = np.swapaxes(np.asarray(rotation, dtype=float) @ geometry.platform_joints.T, -1, -2)
    return rotated + position[..., None, :] - geometry.base_joints


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
        from a quaternion with :func:`stewart_kinematics.rotations.quaternion_to_matrix`.
    :returns: leg lengths l_1..l_6 in metres, shape (6,) or (N, 6).
    """
    position = np.asarray(position, dtype=float)
    rotation = np.asarray(rotation, dtype=float)
    if position.shape == (3,) and rotation.shape == (3, 3):
        # One pose (the IK node's case): no batch broadcasting, constants computed once.
        constants = _constants(geometry)
        legs = rotation @ constants.platform_columns
        legs += position[:, None]
        legs -= constants.base_columns
        return np.sqrt(np.einsum('ij,ij->j', legs, legs))
    return np.linalg.norm(leg_vectors(geometry, position, rotation), axis=-1)


def inverse_kinematics(geometry, poses) -> np.ndarray:
    """
    Leg lengths of one pose or a batch of poses (closed form).

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` in metres and radians, shape (6,) or (N, 6).
    :returns: leg lengths l_1..l_6 in metres, shape (6,) or (N, 6).
    :raises ValueError: if a pose has the wrong shape or a non-finite value.

    >>> from stewart_kinematics import Geometry, inverse_kinematics
    >>> geometry = load_geometry('config/paper_platform.yaml')  # doctest: +SKIP
    >>> inverse_kinematics(geometry, [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0])  # doctest: +SKIP
    array([0.71885487, 0.71885488, 0.70114644, 0.71885487, 0.71885488, 0.71885488])
    """
    poses = np.asarray(poses, dtype=float)
    constants = _constants(geometry)
    if poses.shape == (6,):
        values = poses.tolist()
        if all(map(math.isfinite, values)):
            return _single_pose_lengths(constants, values)
    poses = as_poses(poses)
    lengths = np.empty((poses.shape[0], 6))
    for start in range(0, poses.shape[0], IK_BLOCK_SIZE):
        stop = start + IK_BLOCK_SIZE
        _block_lengths(constants, poses[start:stop], lengths[start:stop])
    return lengths


class _GeometryConstants:
    """Arrays derived once from a geometry, reused by every call (see :func:`_constants`)."""

    def __init__(self, geometry):
        base = geometry.base_joints
        platform = geometry.platform_joints
        #: Joints as columns, shape (3, 6), for ``R @ platform_columns``.
        self.base_columns = np.ascontiguousarray(base.T)
        self.platform_columns = np.ascontiguousarray(platform.T)
        #: ``(px, py, pz, bx, by, bz)`` of each leg as Python floats, for the one-pose paths:
        #: on six legs, plain float arithmetic costs less than numpy's per-call overhead.
        self.joint_pairs = tuple(tuple(p) + tuple(b)
                                 for p, b in zip(platform.tolist(), base.tolist()))
        # Batched IK as one matrix product: [r11 .. r33, X, Y, Z] @ weights - base_flat gives
        # the leg vectors flattened as (leg, axis); see _block_lengths.
        weights = np.zeros((12, 18))
        for leg in range(6):
            for axis in range(3):
                weights[3 * axis:3 * axis + 3, 3 * leg + axis] = platform[leg]
                weights[9 + axis, 3 * leg + axis] = 1.0
        self.ik_weights = weights
        self.base_flat = base.reshape(18).copy()
        #: The same with a last row -base_flat, for a coefficient vector ending in 1.0.
        self.ik_weights_affine = np.vstack([weights, -self.base_flat])
        #: Sums the squared components of each leg: (18,) @ leg_sums -> (6,).
        self.leg_sums = np.kron(np.eye(6), np.ones((3, 1)))
        # Newton-Raphson from the home pose: its first step is the same for every call.
        self.home_pose = tuple(geometry.home_pose.tolist())
        home_legs = _single_euler_legs(self, self.home_pose)
        self.home_lengths = [leg[0] for leg in home_legs]
        try:
            self.home_jacobian_inverse = np.linalg.inv(_single_twist_jacobian(home_legs))
        except np.linalg.LinAlgError:
            # A home pose at a singularity: every solve from it reports the singular Jacobian.
            self.home_jacobian_inverse = None


#: Constants of each geometry still alive; a Geometry is immutable, so they never go stale.
_CONSTANTS = weakref.WeakKeyDictionary()


def _constants(geometry) -> _GeometryConstants:
    """Return the derived constants of ``geometry``, computing them on its first use."""
    try:
        return _CONSTANTS[geometry]
    except KeyError:
        constants = _CONSTANTS[geometry] = _GeometryConstants(geometry)
        return constants


def _single_pose_lengths(constants, values):
    """Leg lengths (6,) of one pose given as six floats, in float arithmetic."""
    x, y, z, alpha, beta, gamma = values
    r11, r12, r13, r21, r22, r23, r31, r32, r33 = euler_zyx_matrix_entries(alpha, beta, gamma)
    squares = []
    for px, py, pz, bx, by, bz in constants.joint_pairs:
        lx = r11 * px + r12 * py + r13 * pz + x - bx
        ly = r21 * px + r22 * py + r23 * pz + y - by
        lz = r31 * px + r32 * py + r33 * pz + z - bz
        squares.append(lx * lx + ly * ly + lz * lz)
    return np.sqrt(squares)


def _single_legs(constants, position, rotation_entries):
    """
    Legs of one pose, in float arithmetic.

    :param position: ``(X, Y, Z)`` of the platform frame, metres, base frame.
    :param rotation_entries: its rotation ``(r11, r12, ..., r33)``, row by row.
    :returns: per leg ``(l, lx, ly, lz, ax, ay, az)``: its length, its vector ``t + R p_i - b_i``
        and the rotated platform joint ``R p_i``, metres, base frame.
    """
    x, y, z = position
    r11, r12, r13, r21, r22, r23, r31, r32, r33 = rotation_entries
    sqrt = math.sqrt
    legs = []
    for px, py, pz, bx, by, bz in constants.joint_pairs:
        ax = r11 * px + r12 * py + r13 * pz
        ay = r21 * px + r22 * py + r23 * pz
        az = r31 * px + r32 * py + r33 * pz
        lx, ly, lz = ax + x - bx, ay + y - by, az + z - bz
        legs.append((sqrt(lx * lx + ly * ly + lz * lz), lx, ly, lz, ax, ay, az))
    return legs


def _single_euler_legs(constants, pose):
    """:func:`_single_legs` of a pose ``[X, Y, Z, alpha, beta, gamma]`` given as six floats."""
    return _single_legs(constants, pose[:3], euler_zyx_matrix_entries(*pose[3:]))


def _single_twist_jacobian(legs):
    """
    Jacobian of the leg lengths with respect to the platform twist, from :func:`_single_legs`.

    Row ``i`` is ``[u_i, R p_i x u_i]``: the rates of ``l_i`` per unit velocity of the platform
    origin and per unit angular velocity, both in the base frame. It is :func:`jacobian` without
    the Euler rate matrix ``E``, whose inverse :func:`_euler_step` applies in closed form.

    :returns: shape (6, 6).
    """
    entries = []
    for length, lx, ly, lz, ax, ay, az in legs:
        ux, uy, uz = lx / length, ly / length, lz / length
        entries += (ux, uy, uz, ay * uz - az * uy, az * ux - ax * uz, ax * uy - ay * ux)
    return np.array(entries).reshape(6, 6)


def _euler_step(pose, twist):
    """
    Pose ``pose - dx`` where ``E dx = twist``: a Newton step taken in Euler angle rates.

    ``E``'s columns are ``R e_x``, ``Rz e_y`` and ``e_z`` (see :func:`jacobian`), so
    ``d_alpha = (cos(gamma) w_x + sin(gamma) w_y) / cos(beta)``,
    ``d_beta = cos(gamma) w_y - sin(gamma) w_x`` and ``d_gamma = w_z + sin(beta) d_alpha``.

    :returns: the new pose as a list, or None where ``cos(beta) = 0`` (``E`` is singular).
    """
    x, y, z, alpha, beta, gamma = pose
    vx, vy, vz, wx, wy, wz = twist
    cos_beta = math.cos(beta)
    if cos_beta == 0.0:
        return None
    cg, sg = math.cos(gamma), math.sin(gamma)
    d_alpha = (cg * wx + sg * wy) / cos_beta
    return [x - vx, y - vy, z - vz, alpha - d_alpha, beta - (cg * wy - sg * wx),
            gamma - (wz + math.sin(beta) * d_alpha)]


def twist_jacobian(geometry, position, rotation) -> np.ndarray:
    """
    Jacobian from the platform twist to the leg velocities.

    A twist is ``[vx, vy, vz, wx, wy, wz]``: the velocity of the platform frame's origin and the
    platform's angular velocity, both in the base frame. Leg ``i`` changes at
    ``u_i . (v + w x R p_i)``, so row ``i`` is ``[u_i, R p_i x u_i]``, with ``u_i`` the unit
    vector of the leg. :func:`jacobian` is this times the Euler rate matrix.

    :param position: platform origin in the base frame, metres, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation, shape (3, 3) or (N, 3, 3).
    :returns: shape (6, 6) or (N, 6, 6); translation columns dimensionless, rotation columns
        in metres per radian.
    """
    position = np.asarray(position, dtype=float)
    rotation = np.asarray(rotation, dtype=float)
    if position.shape == (3,) and rotation.shape == (3, 3):
        return _single_twist_jacobian(_single_legs(
            _constants(geometry), position.tolist(), rotation.ravel().tolist()))
    return _batch_twist_jacobian(*_batch_legs_of(_constants(geometry), position, rotation))


def _block_lengths(constants, poses, out):
    """Write the leg lengths of a block of poses (n, 6) into ``out`` (n, 6)."""
    angles = poses[:, 3:].T
    ca, cb, cg = np.cos(angles)
    sa, sb, sg = np.sin(angles)
    # Rows r11..r33 of Rz(gamma) Ry(beta) Rx(alpha), then X, Y, Z: one row per coefficient.
    coefficients = np.empty((12, poses.shape[0]))
    sb_sa, sb_ca = sb * sa, sb * ca
    np.multiply(cg, cb, out=coefficients[0])
    coefficients[1] = cg * sb_sa - sg * ca
    coefficients[2] = cg * sb_ca + sg * sa
    np.multiply(sg, cb, out=coefficients[3])
    coefficients[4] = sg * sb_sa + cg * ca
    coefficients[5] = sg * sb_ca - cg * sa
    np.negative(sb, out=coefficients[6])
    np.multiply(cb, sa, out=coefficients[7])
    np.multiply(cb, ca, out=coefficients[8])
    coefficients[9:] = poses[:, :3].T
    legs = coefficients.T @ constants.ik_weights
    legs -= constants.base_flat
    np.square(legs, out=legs)
    np.sqrt(legs.reshape(-1, 6, 3).sum(axis=-1), out=out)


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
    jac = _batch_twist_jacobian(*_batch_legs(_constants(geometry), poses))
    beta, gamma = poses[..., 4], poses[..., 5]
    cos_beta, cos_gamma, sin_gamma = np.cos(beta), np.cos(gamma), np.sin(gamma)
    euler_rate_axes = np.zeros(poses.shape[:-1] + (3, 3))
    euler_rate_axes[..., :, 0] = np.stack(
        [cos_gamma * cos_beta, sin_gamma * cos_beta, -np.sin(beta)], axis=-1)
    euler_rate_axes[..., 0, 1] = -sin_gamma
    euler_rate_axes[..., 1, 1] = cos_gamma
    euler_rate_axes[..., 2, 2] = 1.0
    jac[..., 3:] = jac[..., 3:] @ euler_rate_axes
    return jac


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
    jac = twist_jacobian(geometry, position, rotation)
    jac[..., 3:] /= geometry.platform_radius
    return np.linalg.svd(jac, compute_uv=False)


@dataclass(frozen=True, eq=False)
class ForwardKinematicsResult:
    """
    Outcome of :func:`forward_kinematics`, for one solve or a batch.

    For one solve the fields are scalars and ``pose`` has shape (6,); for a batch of N they are
    arrays of length N and ``pose`` has shape (N, 6). Results compare with ``==`` field by
    field (``pose``, ``converged``, ``iterations``, ``residual``, ``reason``) and are
    hashable; ``pose`` is read-only.

    :param pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) of the last iterate; the
        solution where ``converged``, with ``beta`` in [-pi/2, pi/2] and the other angles in
        (-pi, pi].
    :param converged: True where every leg length is within the tolerance.
    :param iterations: Newton-Raphson steps taken.
    :param residual: largest leg length error ``max_i |l_i(pose) - lengths_i|``, metres.
    :param reason: ``''`` where converged, else why not (iteration limit, singular Jacobian,
        divergence).

    Two more figures are computed on first access (a singular value decomposition, about
    40 us, that a solve does not pay for) and kept: :attr:`condition` and
    :attr:`pose_error_bound`.
    """

    pose: np.ndarray
    converged: Union[bool, np.ndarray]
    iterations: Union[int, np.ndarray]
    residual: Union[float, np.ndarray]
    reason: Union[str, Tuple[str, ...]]
    #: The geometry and the leg lengths solved for, for :attr:`condition` and
    #: :attr:`pose_error_bound`.
    _geometry: object = field(default=None, repr=False)
    _lengths: object = field(default=None, repr=False)
    #: One solve: the inverse of the twist Jacobian (see :func:`_single_twist_jacobian`) at the
    #: last iterate that needed one, so that a solve started from this result (tracking)
    #: begins with it instead of computing one at a pose only microns away.
    _jacobian_inverse: Optional[np.ndarray] = field(default=None, repr=False)

    def __post_init__(self):
        self.pose.flags.writeable = False

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
    def _singular_values(self):
        pose = self.pose
        return _dimensionless_singular_values(
            self._geometry, pose[..., :3], euler_zyx_to_matrix(pose[..., 3:]))

    @cached_property
    def condition(self) -> Union[float, np.ndarray]:
        """
        Condition number of the dimensionless Jacobian at :attr:`pose`.

        The definition of :func:`jacobian_condition`: about 10 at the paper platform's home,
        growing without bound towards a singularity, ``inf`` at one. A float for one solve, an
        array (N,) for a batch.
        """
        condition = _condition_number(self._singular_values)
        return float(condition) if condition.ndim == 0 else condition

    @cached_property
    def pose_error_bound(self) -> Union[float, np.ndarray]:
        """
        Bound on how far :attr:`pose` can be from the exact pose of the given leg lengths.

        One number in metres and radians: the larger of the bounds on the position error (m)
        and on the rotation angle error (rad). From the leg length error ``e`` (the residual
        plus the rounding floor of a computed length, ``LENGTH_ROUNDING_ULPS`` units in the last
        place of the longest leg), a pose error ``dx`` meets ``J dx = dl`` with
        ``|dl| <= sqrt(6) e``; with ``sigma`` the smallest singular value of the dimensionless
        Jacobian (:func:`jacobian_condition`), the position error is at most
        ``sqrt(6) e / sigma`` and the angle error that divided by ``rho``. The first-order
        figure is doubled: near a fold singularity, where the leg lengths are quadratic in the
        pose, the tangent meets the exact solution only halfway, and twice the first-order
        estimate is Kantorovich's radius around a Newton iterate.

        On the paper's platform, within +-0.1 m and +-15 degrees of home: 5e-13 for the median
        pose, up to 1.5e-10 where the residual is just under the default tolerance; 1e-5 within
        1e-6 rad of the singularity at a yaw of 90.4 degrees, where the residual is still
        1e-13 m. ``inf`` at a singularity and where the solve did not converge. A float for
        one solve, an array (N,) for a batch.
        """
        lengths = np.asarray(self._lengths, dtype=float)
        error = self.residual + LENGTH_ROUNDING_ULPS * np.finfo(float).eps * np.max(
            lengths, axis=-1)
        radius = self._geometry.platform_radius
        with np.errstate(divide='ignore', invalid='ignore'):
            bound = (2.0 * math.sqrt(6.0) * max(1.0, 1.0 / radius) * error
                     / self._singular_values[..., -1])
        bound = np.where(np.asarray(self.converged) & (bound >= 0.0), bound, np.inf)
        return float(bound) if bound.ndim == 0 else bound


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
    vectorised.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param lengths: leg lengths l_1..l_6 in metres, shape (6,) or (N, 6).
    :param initial_guess: starting pose(s), shape (6,) or (N, 6); default
        ``geometry.home_pose``. When tracking a moving platform, start from the last solution:
        pass the last :class:`ForwardKinematicsResult` itself, and its Jacobian is reused too.
    :param tolerance: largest accepted leg length error, metres (default 1e-12).
    :param max_iterations: Newton-Raphson steps before giving up (default 50).
    :returns: a :class:`ForwardKinematicsResult`; non-convergence is reported there, not
        raised.
    :raises ValueError: if the lengths or the guess are malformed, or a limit is not positive.
    """
    jacobian_inverse = None
    if isinstance(initial_guess, ForwardKinematicsResult):
        if initial_guess.converged is True:
            jacobian_inverse = initial_guess._jacobian_inverse
        initial_guess = initial_guess.pose
    if not 0.0 < tolerance < np.inf:
        raise ValueError(f'tolerance must be positive and finite (metres), got {tolerance!r}')
    if int(max_iterations) != max_iterations or max_iterations < 1:
        raise ValueError(f'max_iterations must be a positive integer, got {max_iterations!r}')
    constants = _constants(geometry)
    # One solve: six valid floats each (the common case, checked without numpy's overhead).
    target = _single_values(lengths, positive=True)
    guess = constants.home_pose if initial_guess is None else _single_values(initial_guess)
    if target is None or guess is None:
        lengths = as_leg_lengths(lengths)
        guess = as_poses(geometry.home_pose if initial_guess is None else initial_guess,
                         'initial_guess')
        target, guess = ((lengths.tolist(), guess.tolist())
                         if lengths.ndim == 1 and guess.ndim == 1 else (None, guess))
    if target is not None:
        return _forward_kinematics_single(
            geometry, constants, target, list(guess), tolerance, int(max_iterations),
            jacobian_inverse)
    targets = np.atleast_2d(lengths)
    count = max(targets.shape[0], np.atleast_2d(guess).shape[0])
    if np.atleast_2d(guess).shape[0] not in (1, count) or targets.shape[0] not in (1, count):
        raise ValueError(
            f'lengths {lengths.shape} and initial_guess {guess.shape} must hold the same '
            'number of poses, or one of them a single one')
    targets = np.broadcast_to(targets, (count, 6))
    poses = np.array(np.broadcast_to(np.atleast_2d(guess), (count, 6)))
    return _forward_kinematics_batch(
        geometry, constants, targets, poses, tolerance, int(max_iterations))


def _forward_kinematics_batch(geometry, constants, targets, poses, tolerance, max_iterations):
    """
    Solve a batch of poses at once: the algorithm of :func:`_forward_kinematics_single`.

    Each pose keeps its own inverse twist Jacobian and takes the same steps, with the same
    stopping rules and reasons, as it would alone; the arithmetic is vectorised over the poses
    still being solved.

    :param targets: leg lengths, metres, shape (N, 6).
    :param poses: initial guesses, shape (N, 6); overwritten by the iterates.
    """
    count = len(poses)
    iterations = np.zeros(count, dtype=int)
    residual = np.full(count, np.inf)
    last_residual = np.full(count, np.inf)
    reason = np.full(count, f'no convergence within {max_iterations} iterations', dtype=object)
    inverses = np.empty((count, 6, 6))
    has_inverse = np.zeros(count, dtype=bool)
    if constants.home_jacobian_inverse is not None:
        has_inverse = np.all(poses == constants.home_pose, axis=-1)
        inverses[has_inverse] = constants.home_jacobian_inverse
    active = np.arange(count)
    for step in range(max_iterations + 1):
        lengths, legs, rotated = _batch_legs(constants, poses[active])
        errors = lengths - targets[active]
        residual[active] = np.max(np.abs(errors), axis=-1)
        done = residual[active] <= tolerance
        reason[active[done]] = ''
        active, errors = active[~done], errors[~done]
        if active.size == 0 or step == max_iterations:
            break
        keep = ~done
        refresh = ~has_inverse[active] | (
            residual[active] > JACOBIAN_REUSE_CONTRACTION * last_residual[active])
        if np.any(refresh):
            rows = np.flatnonzero(keep)[refresh]
            new, invertible = _invert_each(
                _batch_twist_jacobian(lengths[rows], legs[rows], rotated[rows]))
            inverses[active[refresh]] = new
            has_inverse[active[refresh]] = invertible
            reason[active[refresh][~invertible]] = SINGULAR_JACOBIAN
            solvable = np.ones(active.size, dtype=bool)
            solvable[np.flatnonzero(refresh)[~invertible]] = False
            active, errors = active[solvable], errors[solvable]
        last_residual[active] = residual[active]
        twists = np.einsum('nij,nj->ni', inverses[active], errors)
        stepped, defined = _batch_euler_step(poses[active], twists)
        reason[active[~defined]] = SINGULAR_JACOBIAN
        # A diverging solve stops at its last plausible iterate, whose residual is known.
        diverged = defined & ~np.all(np.abs(stepped) < DIVERGENCE_BOUND, axis=-1)
        reason[active[diverged]] = DIVERGED
        moving = defined & ~diverged
        active = active[moving]
        poses[active] = stepped[moving]
        iterations[active] += 1

    converged = reason == ''
    # Same rotation, canonical angles: beta in [-pi/2, pi/2], alpha and gamma in (-pi, pi].
    poses[:, 3:] = matrix_to_euler_zyx(euler_zyx_to_matrix(poses[:, 3:]))
    return ForwardKinematicsResult(
        pose=poses, converged=converged, iterations=iterations, residual=residual,
        reason=tuple(reason.tolist()), _geometry=geometry, _lengths=targets)


def _batch_legs(constants, poses):
    """Legs of poses ``[X, Y, Z, alpha, beta, gamma]`` (..., 6); see :func:`_batch_legs_of`."""
    return _batch_legs_of(constants, poses[..., :3], euler_zyx_to_matrix(poses[..., 3:]))


def _batch_legs_of(constants, position, rotation):
    """
    Legs of positions (..., 3) and rotations (..., 3, 3): the arrays of :func:`_single_legs`.

    :returns: ``(lengths (..., 6), legs (..., 6, 3), rotated joints R p_i (..., 6, 3))``,
        metres, base frame.
    """
    rotated = np.swapaxes(rotation @ constants.platform_columns, -1, -2)
    legs = rotated + (position[..., None, :] - constants.base_columns.T)
    lengths = np.sqrt(np.einsum('...ij,...ij->...i', legs, legs))
    return lengths, legs, rotated


def _batch_twist_jacobian(lengths, legs, rotated):
    """Twist Jacobians, shape (n, 6, 6), of :func:`_batch_legs`; see :func:`twist_jacobian`."""
    units = legs / lengths[..., None]
    ax, ay, az = rotated[..., 0], rotated[..., 1], rotated[..., 2]
    ux, uy, uz = units[..., 0], units[..., 1], units[..., 2]
    jac = np.empty(lengths.shape + (6,))
    jac[..., :3] = units
    jac[..., 3] = ay * uz - az * uy
    jac[..., 4] = az * ux - ax * uz
    jac[..., 5] = ax * uy - ay * ux
    return jac


def _batch_euler_step(poses, twists):
    """
    :func:`_euler_step` of each pose, shape (n, 6).

    :returns: ``(stepped poses (n, 6), defined (n,))``; a step is undefined where
        ``cos(beta) = 0``.
    """
    beta, gamma = poses[:, 4], poses[:, 5]
    cos_beta = np.cos(beta)
    defined = cos_beta != 0.0
    cg, sg = np.cos(gamma), np.sin(gamma)
    wx, wy, wz = twists[:, 3], twists[:, 4], twists[:, 5]
    with np.errstate(divide='ignore', invalid='ignore'):
        d_alpha = (cg * wx + sg * wy) / np.where(defined, cos_beta, 1.0)
    stepped = np.empty_like(poses)
    stepped[:, :3] = poses[:, :3] - twists[:, :3]
    stepped[:, 3] = poses[:, 3] - d_alpha
    stepped[:, 4] = beta - (cg * wy - sg * wx)
    stepped[:, 5] = gamma - (wz + np.sin(beta) * d_alpha)
    return stepped, defined


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


def _single_values(values, positive=False):
    """
    Six floats of one pose or one set of leg lengths, or None to leave it to the full checks.

    The fast path of the argument checks for one solve: None unless ``values`` is an array,
    list or tuple of six numbers that are finite (and positive, with ``positive``), so that
    :func:`as_poses` and :func:`as_leg_lengths` say what is wrong, or see a batch.

    :returns: a list of six floats, or None.
    """
    if isinstance(values, np.ndarray):
        if values.shape != (6,):
            return None
        values = values.tolist()
    elif not isinstance(values, (list, tuple)) or len(values) != 6:
        return None
    try:
        values = [float(value) for value in values]
    except (TypeError, ValueError):
        return None
    low = 0.0 if positive else -math.inf
    return values if all(low < value < math.inf for value in values) else None


def _forward_kinematics_single(geometry, constants, target, pose, tolerance, max_iterations,
                               jacobian_inverse):
    """
    Solve one pose in float arithmetic: modified Newton-Raphson (see :func:`forward_kinematics`).

    Steps are taken in the twist form ``[u_i, R p_i x u_i] [v, w] = l(x) - lengths`` and turned
    into Euler angle steps by :func:`_euler_step`: the same step as with :func:`jacobian`, whose
    rotation columns are these times ``E``.

    :param target: the six leg lengths, metres, as floats.
    :param pose: the initial guess, as six floats.
    :param jacobian_inverse: inverse twist Jacobian to take the first step with, or None.
    """
    if jacobian_inverse is None and tuple(pose) == constants.home_pose:
        jacobian_inverse = constants.home_jacobian_inverse
    iterations = 0
    reason = f'no convergence within {max_iterations} iterations'
    last_residual = math.inf
    for step in range(max_iterations + 1):
        legs = _single_euler_legs(constants, pose)
        errors = [leg[0] - length for leg, length in zip(legs, target)]
        residual = max(map(abs, errors))
        if residual <= tolerance:
            reason = ''
            break
        if step == max_iterations:
            break
        if jacobian_inverse is None or residual > JACOBIAN_REUSE_CONTRACTION * last_residual:
            try:
                jacobian_inverse = np.linalg.inv(_single_twist_jacobian(legs))
            except np.linalg.LinAlgError:
                jacobian_inverse = None
                reason = SINGULAR_JACOBIAN
                break
        last_residual = residual
        stepped = _euler_step(pose, (jacobian_inverse @ errors).tolist())
        if stepped is None:
            reason = SINGULAR_JACOBIAN
            break
        # A diverging solve stops at its last plausible iterate, whose residual is known.
        if not all(abs(value) < DIVERGENCE_BOUND for value in stepped):
            reason = DIVERGED
            break
        pose = stepped
        iterations += 1
    # Same rotation, canonical angles, as in the batch solver.
    pose[3:] = _single_canonical_angles(*pose[3:])
    return ForwardKinematicsResult(
        pose=np.array(pose), converged=reason == '', iterations=iterations, residual=residual,
        reason=reason, _geometry=geometry, _lengths=target,
        _jacobian_inverse=jacobian_inverse)


def _single_canonical_angles(alpha, beta, gamma):
    """
    Euler angles of the same rotation in the canonical ranges; scalar twin of the batch one.

    The batch solver's ``matrix_to_euler_zyx(euler_zyx_to_matrix(angles))`` with only the five
    matrix entries it reads: beta in [-pi/2, pi/2], alpha and gamma in (-pi, pi].
    """
    ca, cb, cg = math.cos(alpha), math.cos(beta), math.cos(gamma)
    sa, sb, sg = math.sin(alpha), math.sin(beta), math.sin(gamma)
    r11, r21 = cg * cb, sg * cb
    cos_beta = math.hypot(r11, r21)
    beta = math.atan2(sb, cos_beta)
    if cos_beta < GIMBAL_LOCK_COS_BETA:
        return [0.0, beta, math.atan2(-(cg * sb * sa - sg * ca), sg * sb * sa + cg * ca)]
    return [math.atan2(cb * sa, cb * ca), beta, math.atan2(r21, r11)]
