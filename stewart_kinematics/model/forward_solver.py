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
The forward kinematics solver: modified Newton-Raphson, one pose in floats or a batch in arrays.

It solves ``l(x) = lengths`` for the pose ``x = [X, Y, Z, alpha, beta, gamma]`` from a start
it is given (:mod:`.forward` chooses it), with the analytic Jacobian: each step solves the twist
form ``[u_i, R p_i x u_i] [v, w] = l(x) - lengths`` and turns the twist into Euler angle steps
(:func:`~.formulas.euler_step`), and keeps its Jacobian while each step cuts the largest leg
length error by :data:`JACOBIAN_REUSE_CONTRACTION` or more. :func:`solve_single` runs on floats,
:func:`solve_batch` on arrays of the poses still being solved, with the same formulas
(:mod:`.formulas`): the same iterates, iterations and reasons. The arguments are checked by the
caller. Metres and radians.
"""

import math

import numpy as np

from stewart_kinematics.model.formulas import (
    apply_matrix,
    batch_euler_legs,
    batch_twist_jacobian,
    euler_step,
    float_inverse,
    float_twist_rows,
    legs_of,
)
from stewart_kinematics.model.forward_result import ForwardKinematicsResult
from stewart_kinematics.model.inputs import valid_lengths
from stewart_kinematics.model.rotations import (
    canonical_zyx_angle_rows,
    canonical_zyx_angles,
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


def solve_single(geometry, constants, target, pose, tolerance, max_iterations,
                 jacobian_inverse):
    """
    Solve one pose in floats: modified Newton-Raphson (see :func:`~.forward.forward_kinematics`).

    Steps are taken in the twist form ``[u_i, R p_i x u_i] [v, w] = l(x) - lengths`` and turned
    into Euler angle steps by :func:`~.formulas.euler_step`: the same step as with
    :func:`~.jacobians.jacobian`, whose rotation columns are these times ``E``.

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
        # single_euler_legs, keeping the cosines and sines that the Euler step needs.
        x, y, z, alpha, beta, gamma = pose
        cos_beta, sin_beta, cos_gamma, sin_gamma = cos(beta), sin(beta), cos(gamma), sin(gamma)
        legs = legs_of(zyx_entries(cos(alpha), sin(alpha), cos_beta, sin_beta, cos_gamma,
                                   sin_gamma), x, y, z, constants.joint_pairs, math.sqrt)
        errors = [leg[0] - length for leg, length in zip(legs, target)]
        residual = max(map(abs, errors))
        if residual <= tolerance:
            reason = ''
            break
        if step == max_iterations:
            break
        if jacobian_inverse is None or residual > JACOBIAN_REUSE_CONTRACTION * last_residual:
            jacobian_inverse = float_inverse(float_twist_rows(legs))
            if jacobian_inverse is None:
                reason = SINGULAR_JACOBIAN
                break
        last_residual = residual
        if cos_beta == 0.0:  # the Euler rate matrix is singular
            reason = SINGULAR_JACOBIAN
            break
        stepped = euler_step(pose, apply_matrix(jacobian_inverse, errors), cos_beta, sin_beta,
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
    pose = np.array(list(pose[:3]) + canonical_zyx_angles(*pose[3:]))
    pose.flags.writeable = False
    return ForwardKinematicsResult(
        pose=pose, converged=reason == '', iterations=iterations, residual=residual,
        reason=reason, _solve=(geometry, target, jacobian_inverse))


def solve_batch(geometry, constants, targets, poses, tolerance, max_iterations,
                start_inverses=None):
    """
    Solve a batch of poses at once: the algorithm of :func:`solve_single`.

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
    lengths_valid = valid_lengths(targets)
    reason[~lengths_valid] = INVALID_LENGTHS
    inverses = np.empty((count, 6, 6))
    has_inverse = np.zeros(count, dtype=bool)
    if constants.home_jacobian_inverse is not None:
        has_inverse = np.all(poses == constants.home_pose, axis=-1)
        inverses[has_inverse] = constants.home_jacobian_inverse
    if start_inverses is not None:
        rows, start = start_inverses
        has_inverse = has_inverse | rows
        inverses[rows] = start[rows]
    active = np.flatnonzero(lengths_valid & valid_guess)
    for step in range(max_iterations + 1):
        # Leg by pose, (6, n): see batch_legs.
        lengths, vectors = batch_euler_legs(constants, poses[active])
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
            new, invertible = _invert_each(batch_twist_jacobian(
                lengths[:, rows], [vector[:, rows] for vector in vectors]))
            inverses[active[refresh]] = new
            has_inverse[active[refresh]] = invertible
            reason[active[refresh][~invertible]] = SINGULAR_JACOBIAN
            solvable = np.ones(active.size, dtype=bool)
            solvable[np.flatnonzero(refresh)[~invertible]] = False
            active, errors = active[solvable], errors[:, solvable]
        last_residual[active] = residual[active]
        # apply_matrix with the six rows of every pose as one row: its columns as arrays (6, n).
        columns = np.ascontiguousarray(inverses[active].transpose(2, 1, 0))
        twists = apply_matrix([columns], errors)[0]
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
    canonical_zyx_angle_rows(poses[:, 3:])
    poses.flags.writeable = False
    return ForwardKinematicsResult(
        pose=poses, converged=reason == '', iterations=iterations, residual=residual,
        reason=tuple(reason.tolist()), _solve=(geometry, targets, None))


def _batch_euler_step(poses, twists):
    """
    :func:`euler_step` of each pose, shape (n, 6), with twists given as six arrays (n,).

    :returns: ``(stepped poses (n, 6), defined (n,))``; a step is undefined where
        ``cos(beta) = 0``.
    """
    beta, gamma = poses[:, 4], poses[:, 5]
    cos_beta = np.cos(beta)
    defined = cos_beta != 0.0
    stepped = euler_step(poses.T, twists, np.where(defined, cos_beta, 1.0), np.sin(beta),
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
