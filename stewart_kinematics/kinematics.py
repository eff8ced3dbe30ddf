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

from dataclasses import dataclass
import math
from typing import Tuple, Union
import weakref

import numpy as np

from stewart_kinematics.rotations import (
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
    >>> geometry = Geometry.from_yaml('config/paper_platform.yaml')  # doctest: +SKIP
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
        # Newton-Raphson from the home pose: its first iterate is the same for every call.
        home = np.array(geometry.home_pose, dtype=float)
        self.home_pose = home
        self.home_lengths, home_jacobian = _lengths_and_jacobian(geometry, home)
        try:
            self.home_jacobian_inverse = np.linalg.inv(home_jacobian)
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


def _single_rotation(alpha, beta, gamma) -> np.ndarray:
    """Return ``Rz(gamma) Ry(beta) Rx(alpha)`` of three floats (scalar twin of the batch one)."""
    ca, cb, cg = math.cos(alpha), math.cos(beta), math.cos(gamma)
    sa, sb, sg = math.sin(alpha), math.sin(beta), math.sin(gamma)
    return np.array([
        [cg * cb, cg * sb * sa - sg * ca, cg * sb * ca + sg * sa],
        [sg * cb, sg * sb * sa + cg * ca, sg * sb * ca - cg * sa],
        [-sb, cb * sa, cb * ca],
    ])


def _single_pose_lengths(constants, values):
    """Leg lengths of one pose given as six floats: one small matrix product, no batch code."""
    x, y, z, alpha, beta, gamma = values
    ca, cb, cg = math.cos(alpha), math.cos(beta), math.cos(gamma)
    sa, sb, sg = math.sin(alpha), math.sin(beta), math.sin(gamma)
    coefficients = np.array([
        cg * cb, cg * sb * sa - sg * ca, cg * sb * ca + sg * sa,
        sg * cb, sg * sb * sa + cg * ca, sg * sb * ca - cg * sa,
        -sb, cb * sa, cb * ca, x, y, z, 1.0])
    legs = coefficients @ constants.ik_weights_affine
    legs *= legs
    return np.sqrt(legs @ constants.leg_sums)


def _single_lengths(constants, pose):
    """
    Leg lengths of one pose, with what the Jacobian needs.

    :returns: ``(lengths (6,), legs (3, 6), rotated joints R p_i (3, 6), rotation (3, 3))``.
    """
    x, y, z, alpha, beta, gamma = pose.tolist()
    rotation = _single_rotation(alpha, beta, gamma)
    rotated = rotation @ constants.platform_columns
    legs = rotated - constants.base_columns
    legs += np.array([[x], [y], [z]])
    return np.sqrt(np.einsum('ij,ij->j', legs, legs)), legs, rotated, rotation


def _single_jacobian(lengths, legs, rotated, rotation, gamma) -> np.ndarray:
    """Jacobian of one pose from :func:`_single_lengths`; the formula of :func:`jacobian`."""
    units = legs / lengths
    ax, ay, az = rotated
    ux, uy, uz = units
    moment_arms = np.array([ay * uz - az * uy, az * ux - ax * uz, ax * uy - ay * ux])
    euler_rate_axes = np.array([
        [rotation[0, 0], -math.sin(gamma), 0.0],
        [rotation[1, 0], math.cos(gamma), 0.0],
        [rotation[2, 0], 0.0, 1.0],
    ])
    jac = np.empty((6, 6))
    jac[:, :3] = units.T
    jac[:, 3:] = moment_arms.T @ euler_rate_axes
    return jac


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
    return _lengths_and_jacobian(geometry, as_poses(poses))[1]


def _lengths_and_jacobian(geometry, poses) -> Tuple[np.ndarray, np.ndarray]:
    rotation = euler_zyx_to_matrix(poses[..., 3:])
    rotated_joints = np.swapaxes(rotation @ geometry.platform_joints.T, -1, -2)
    legs = rotated_joints + poses[..., None, :3] - geometry.base_joints
    lengths = np.linalg.norm(legs, axis=-1)
    units = legs / lengths[..., None]
    gamma = poses[..., 5]
    euler_rate_axes = np.zeros(poses.shape[:-1] + (3, 3))
    euler_rate_axes[..., :, 0] = rotation[..., :, 0]
    euler_rate_axes[..., 0, 1] = -np.sin(gamma)
    euler_rate_axes[..., 1, 1] = np.cos(gamma)
    euler_rate_axes[..., 2, 2] = 1.0
    moment_arms = np.cross(rotated_joints, units)
    jac = np.concatenate([units, moment_arms @ euler_rate_axes], axis=-1)
    return lengths, jac


@dataclass(frozen=True)
class ForwardKinematicsResult:
    """
    Outcome of :func:`forward_kinematics`, for one solve or a batch.

    For one solve the fields are scalars and ``pose`` has shape (6,); for a batch of N they are
    arrays of length N and ``pose`` has shape (N, 6).

    :param pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) of the last iterate; the
        solution where ``converged``, with ``beta`` in [-pi/2, pi/2] and the other angles in
        (-pi, pi].
    :param converged: True where every leg length is within the tolerance.
    :param iterations: Newton-Raphson steps taken.
    :param residual: largest leg length error ``max_i |l_i(pose) - lengths_i|``, metres.
    :param reason: ``''`` where converged, else why not (iteration limit, singular Jacobian,
        divergence).
    """

    pose: np.ndarray
    converged: Union[bool, np.ndarray]
    iterations: Union[int, np.ndarray]
    residual: Union[float, np.ndarray]
    reason: Union[str, Tuple[str, ...]]


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

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param lengths: leg lengths l_1..l_6 in metres, shape (6,) or (N, 6).
    :param initial_guess: starting pose(s), shape (6,) or (N, 6); default
        ``geometry.home_pose``. Start from the last solution when tracking a moving platform.
    :param tolerance: largest accepted leg length error, metres (default 1e-12).
    :param max_iterations: Newton-Raphson steps before giving up (default 50).
    :returns: a :class:`ForwardKinematicsResult`; non-convergence is reported there, not
        raised.
    :raises ValueError: if the lengths or the guess are malformed, or a limit is not positive.
    """
    lengths = as_leg_lengths(lengths)
    if initial_guess is None:
        initial_guess = geometry.home_pose
    guess = as_poses(initial_guess, 'initial_guess')
    if not 0.0 < tolerance < np.inf:
        raise ValueError(f'tolerance must be positive and finite (metres), got {tolerance!r}')
    if int(max_iterations) != max_iterations or max_iterations < 1:
        raise ValueError(f'max_iterations must be a positive integer, got {max_iterations!r}')
    single = lengths.ndim == 1 and guess.ndim == 1
    if single:
        return _forward_kinematics_single(
            geometry, lengths, guess, tolerance, int(max_iterations))
    targets = np.atleast_2d(lengths)
    count = max(targets.shape[0], np.atleast_2d(guess).shape[0])
    if np.atleast_2d(guess).shape[0] not in (1, count) or targets.shape[0] not in (1, count):
        raise ValueError(
            f'lengths {lengths.shape} and initial_guess {guess.shape} must hold the same '
            'number of poses, or one of them a single one')
    targets = np.broadcast_to(targets, (count, 6))
    poses = np.array(np.broadcast_to(np.atleast_2d(guess), (count, 6)))

    iterations = np.zeros(count, dtype=int)
    residual = np.full(count, np.inf)
    reason = np.full(count, f'no convergence within {int(max_iterations)} iterations',
                     dtype=object)
    active = np.arange(count)
    for step in range(int(max_iterations) + 1):
        current, jac = _lengths_and_jacobian(geometry, poses[active])
        error = current - targets[active]
        residual[active] = np.max(np.abs(error), axis=-1)
        done = residual[active] <= tolerance
        reason[active[done]] = ''
        active, jac, error = active[~done], jac[~done], error[~done]
        if active.size == 0 or step == max_iterations:
            break
        delta, solvable = _solve_each(jac, error)
        reason[active[~solvable]] = 'singular Jacobian: the pose is at a singularity'
        active, delta = active[solvable], delta[solvable]
        stepped = poses[active] - delta
        # A diverging solve stops at its last plausible iterate, whose residual is known.
        diverged = ~np.all(np.abs(stepped) < DIVERGENCE_BOUND, axis=-1)
        reason[active[diverged]] = 'diverged: the next iterate left every plausible pose'
        active, stepped = active[~diverged], stepped[~diverged]
        poses[active] = stepped
        iterations[active] += 1

    converged = reason == ''
    # Same rotation, canonical angles: beta in [-pi/2, pi/2], alpha and gamma in (-pi, pi].
    finite = np.all(np.isfinite(poses), axis=-1)
    poses[finite, 3:] = matrix_to_euler_zyx(euler_zyx_to_matrix(poses[finite, 3:]))
    if single:
        return ForwardKinematicsResult(
            pose=poses[0], converged=bool(converged[0]), iterations=int(iterations[0]),
            residual=float(residual[0]), reason=str(reason[0]))
    return ForwardKinematicsResult(
        pose=poses, converged=converged, iterations=iterations, residual=residual,
        reason=tuple(str(item) for item in reason))


def _solve_each(jac, error):
    """Solve each system ``jac[k] x = error[k]``; report which were singular."""
    try:
        return np.linalg.solve(jac, error[..., None])[..., 0], np.ones(len(error), dtype=bool)
    except np.linalg.LinAlgError:
        # One singular matrix fails the whole stack: solve them one by one.
        delta = np.zeros_like(error)
        solvable = np.ones(len(error), dtype=bool)
        for k in range(len(error)):
            try:
                delta[k] = np.linalg.solve(jac[k], error[k])
            except np.linalg.LinAlgError:
                solvable[k] = False
        return delta, solvable


def _forward_kinematics_single(geometry, target, guess, tolerance, max_iterations):
    """
    Solve one pose: the loop of :func:`forward_kinematics` without the batch bookkeeping.

    The same iterates, stopping rules and reasons as the batch solver. From the home pose the
    first iterate comes from the cached home lengths and inverse Jacobian (the same for every
    call), and the Jacobian is computed only when a step is taken.
    """
    constants = _constants(geometry)
    pose = guess.copy()
    iterations = 0
    reason = f'no convergence within {max_iterations} iterations'
    from_home = (constants.home_jacobian_inverse is not None
                 and np.array_equal(pose, constants.home_pose))
    for step in range(max_iterations + 1):
        if step == 0 and from_home:
            current = constants.home_lengths
        else:
            current, legs, rotated, rotation = _single_lengths(constants, pose)
        error = current - target
        residual = max(map(abs, error.tolist()))
        if residual <= tolerance:
            reason = ''
            break
        if step == max_iterations:
            break
        if step == 0 and from_home:
            delta = constants.home_jacobian_inverse @ error
        else:
            jac = _single_jacobian(current, legs, rotated, rotation, pose[5])
            try:
                delta = np.linalg.solve(jac, error)
            except np.linalg.LinAlgError:
                reason = 'singular Jacobian: the pose is at a singularity'
                break
        stepped = pose - delta
        # A diverging solve stops at its last plausible iterate, whose residual is known.
        if not all(abs(value) < DIVERGENCE_BOUND for value in stepped.tolist()):
            reason = 'diverged: the next iterate left every plausible pose'
            break
        pose = stepped
        iterations += 1
    if all(map(math.isfinite, pose.tolist())):
        # Same rotation, canonical angles, as in the batch solver.
        pose[3:] = _single_canonical_angles(*pose[3:].tolist())
    return ForwardKinematicsResult(
        pose=pose, converged=reason == '', iterations=iterations, residual=residual,
        reason=reason)


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
