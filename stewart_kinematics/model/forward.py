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
Forward kinematics: the pose of the platform from its six leg lengths.

:func:`forward_kinematics` checks its arguments (:mod:`.inputs`), chooses where each solve
starts (the guess given, a previous result with its Jacobian, the start table's sample of the
lengths (:mod:`.start_table`), or home) and runs the solver (:mod:`.forward_solver`); the
outcome is a :class:`~.forward_result.ForwardKinematicsResult`. :func:`solve_trusted` is the
same solve for a caller that has checked its lengths where they entered (such as
:class:`~stewart_kinematics.PoseTracker`), without checking them again.
"""

import math
from typing import Optional
import weakref

import numpy as np

from stewart_kinematics.model.formulas import constants_of
from stewart_kinematics.model.forward_result import ForwardKinematicsResult
from stewart_kinematics.model.forward_solver import (
    DEFAULT_MAX_ITERATIONS,
    DEFAULT_TOLERANCE,
    solve_batch,
    solve_single,
)
from stewart_kinematics.model.inputs import (
    as_leg_lengths,
    as_poses,
    as_rows,
    is_real,
    single_values,
)
from stewart_kinematics.model.start_table import batch_cold_starts, cold_start, StartTable


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
    if not (is_real(tolerance) and 0.0 < tolerance < np.inf):
        raise ValueError(f'tolerance must be positive and finite (metres), got {tolerance!r}')
    if not (is_real(max_iterations) and math.isfinite(max_iterations)
            and int(max_iterations) == max_iterations and max_iterations >= 1):
        raise ValueError(f'max_iterations must be a positive integer, got {max_iterations!r}')
    constants = constants_of(geometry)
    # One solve: six valid floats each (the common case, checked without numpy's overhead).
    target = single_values(lengths, positive=True)
    guess = constants.home_pose if initial_guess is None else single_values(initial_guess)
    if target is None or guess is None:
        lengths = as_rows(lengths, 'leg lengths')
        guess = as_rows(geometry.home_pose if initial_guess is None else initial_guess,
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
        return solve_single(
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
    return solve_batch(
        geometry, constants, targets, np.array(np.broadcast_to(guesses, (count, 6))),
        tolerance, int(max_iterations))


def solve_trusted(geometry, lengths, start, tolerance, max_iterations) -> ForwardKinematicsResult:
    """
    :func:`forward_kinematics` of one set of leg lengths from a start, checked by the caller.

    The inner entry of a decision that checked its input where it entered (spatialmath's
    ``check=False``): :class:`~stewart_kinematics.PoseTracker` checks a message's lengths once,
    in its :meth:`~stewart_kinematics.PoseTracker.update`, and solves them with this. The same
    solve and the same result as ``forward_kinematics(geometry, lengths, start,
    tolerance=tolerance, max_iterations=max_iterations)``, without its checks: what is not as
    stated below gives a result of no meaning, not an error.

    :param lengths: six finite, positive floats (a list), metres.
    :param start: six finite floats (a sequence or an array (6,)), or the
        :class:`~.forward_result.ForwardKinematicsResult` of a previous solve (its pose, and its
        Jacobian when it converged).
    :param tolerance: a positive, finite float, metres.
    :param max_iterations: a positive int.
    """
    jacobian_inverse = None
    if isinstance(start, ForwardKinematicsResult):
        if start.converged is True:
            jacobian_inverse = start._solve[2]
        start = start.pose
    pose = start.tolist() if isinstance(start, np.ndarray) else [float(value) for value in start]
    return solve_single(geometry, constants_of(geometry), lengths, pose, tolerance,
                        max_iterations, jacobian_inverse)


#: The start table of each geometry still alive, or None where its home is singular; built on
#: the geometry's first cold solve (a Geometry is immutable, so a table never goes stale).
_START_TABLES = weakref.WeakKeyDictionary()


def start_table_of(geometry, constants=None) -> Optional[StartTable]:
    """
    Return the :class:`StartTable` of ``geometry``, built on first use; None: home is singular.

    :param constants: the geometry's :func:`~.formulas.constants_of`, when the caller has them.
    """
    try:
        return _START_TABLES[geometry]
    except KeyError:
        if constants is None:
            constants = constants_of(geometry)
        table = None if constants.home_jacobian_inverse is None else StartTable(geometry)
        _START_TABLES[geometry] = table
        return table


def _forward_kinematics_cold(geometry, constants, target, tolerance, max_iterations):
    """One solve without a guess: from the start table, else (or if that fails) from home."""
    start = cold_start(start_table_of(geometry, constants), target)
    if start is not None:
        result = solve_single(geometry, constants, target, start[0], tolerance,
                              max_iterations, start[1])
        if result.converged:
            return result
    return solve_single(geometry, constants, target, list(constants.home_pose), tolerance,
                        max_iterations, None)


def _forward_kinematics_cold_batch(geometry, constants, targets, tolerance, max_iterations):
    """Solve a batch without guesses: :func:`_forward_kinematics_cold` of each row, vectorised."""
    started, poses, inverses = batch_cold_starts(start_table_of(geometry, constants),
                                                 constants.home_pose, targets)
    result = solve_batch(geometry, constants, targets, poses, tolerance, max_iterations,
                         (started, inverses))
    failed = np.flatnonzero(started & ~result.converged)
    if failed.size == 0:
        return result
    again = solve_batch(
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
