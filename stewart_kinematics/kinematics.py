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
from typing import Tuple, Union

import numpy as np

from stewart_kinematics.rotations import euler_zyx_to_matrix, matrix_to_euler_zyx

#: Default Newton-Raphson tolerance: the largest leg length error accepted, metres.
DEFAULT_TOLERANCE = 1e-12
#: Default Newton-Raphson iteration limit.
DEFAULT_MAX_ITERATIONS = 50
#: An iterate with a coordinate beyond this (metres or radians) has diverged: no platform
#: reaches a kilometre, and angles wound a hundred times round mean the iteration is lost.
DIVERGENCE_BOUND = 1e3


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
    return np.linalg.norm(leg_vectors_from_euler(geometry, poses), axis=-1)


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
