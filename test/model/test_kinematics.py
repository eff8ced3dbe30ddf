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
Unit tests of inverse and forward kinematics and the Jacobians (pure numpy).

The modules are stewart_kinematics.model.inverse, .forward (with .forward_solver) and .jacobians.

Expected leg lengths come from the paper's equation evaluated leg by leg in plain Python, and
the geometry from the paper's Tables 1 and 2, both in test/reference.py.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import (
    BASE_JOINTS,
    HOME,
    leg_lengths as leg_lengths_of,
    paper_geometry,
    PLATFORM_JOINTS,
    random_poses,
    rotation_zyx,
    singular_yaw,
    TABLE_3,
)

from stewart_kinematics.model import formulas, forward_solver, jacobians
from stewart_kinematics.model.forward import forward_kinematics, solve_trusted
from stewart_kinematics.model.forward_result import ForwardKinematicsResult
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.model.inverse import inverse_kinematics, leg_lengths, leg_vectors
from stewart_kinematics.model.jacobians import jacobian

pytestmark = pytest.mark.core


@pytest.fixture(scope='module')
def geometry():
    """Build the paper's platform, home pose at the start of Table 3."""
    return paper_geometry()


# Inverse kinematics.

def test_table_3_rows_are_the_papers_numbers():
    """The first and last rows built here are the paper's start and end points."""
    assert_allclose(TABLE_3[0], [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0], rtol=0.0, atol=1e-15)
    assert_allclose(TABLE_3[10],
                    [0.1, 0.15, 0.5325, math.radians(15), math.radians(-15), math.radians(20)],
                    rtol=0.0, atol=1e-15)


@pytest.mark.parametrize('k', range(11))
def test_inverse_kinematics_table_3_row_matches_paper_equation(geometry, k):
    """Leg lengths of each Table 3 row equal the paper's equation evaluated by hand."""
    assert_allclose(inverse_kinematics(geometry, TABLE_3[k]),
                    leg_lengths_of(TABLE_3[k]), rtol=0.0, atol=1e-12)


def test_inverse_kinematics_home_lengths():
    """At home the legs are 0.718855 m, leg 3 (p_3 z = 0.257) 0.701146 m."""
    geometry = Geometry(base_joints=BASE_JOINTS, platform_joints=PLATFORM_JOINTS)
    assert_allclose(inverse_kinematics(geometry, HOME),
                    [0.71885487, 0.71885488, 0.70114644, 0.71885487, 0.71885488, 0.71885488],
                    rtol=0.0, atol=1e-8)


def test_inverse_kinematics_batch_equals_loop_of_singles(geometry):
    """A (N, 6) batch gives the same lengths as one call per pose."""
    poses = np.vstack([TABLE_3, random_poses(20, seed=3)])
    batch = inverse_kinematics(geometry, poses)
    singles = np.array([inverse_kinematics(geometry, pose) for pose in poses])
    assert_allclose(batch, singles, rtol=0.0, atol=1e-15)
    assert_allclose(batch, [leg_lengths_of(pose) for pose in poses], rtol=0.0, atol=1e-12)


@pytest.mark.parametrize('shape, expected', [((6,), (6,)), ((1, 6), (1, 6)), ((4, 6), (4, 6))])
def test_inverse_kinematics_shapes(geometry, shape, expected):
    """(6,) gives (6,) and (N, 6) gives (N, 6)."""
    poses = np.broadcast_to(np.asarray(HOME), shape)
    assert inverse_kinematics(geometry, poses).shape == expected


@pytest.mark.parametrize('poses, message', [
    (np.zeros(5), 'shape'),
    (np.zeros((2, 7)), 'shape'),
    (np.zeros((2, 2, 6)), 'shape'),
    ([0.0, 0.0, math.nan, 0.0, 0.0, 0.0], 'finite'),
    ([[0.0, 0.0, 0.4, 0.0, 0.0, 0.0], [0.0, math.inf, 0.4, 0.0, 0.0, 0.0]], 'finite'),
])
def test_inverse_kinematics_rejects_bad_poses(geometry, poses, message):
    """Wrong shapes and non-finite values raise ValueError."""
    with pytest.raises(ValueError, match=message):
        inverse_kinematics(geometry, poses)


def test_leg_vectors_are_t_plus_r_p_minus_b(geometry):
    """Each leg vector is t + R p_i - b_i, with R from elementary rotations."""
    pose = TABLE_3[7]
    rotation = rotation_zyx(*pose[3:])
    vectors = leg_vectors(geometry, pose[:3], rotation)
    assert vectors.shape == (6, 3)
    for vector, base, platform in zip(vectors, BASE_JOINTS, PLATFORM_JOINTS):
        expected = np.asarray(pose[:3]) + rotation @ platform - np.asarray(base)
        assert_allclose(vector, expected, rtol=0.0, atol=1e-15)


def test_leg_lengths_from_rotation_matrix_equals_euler_version(geometry):
    """leg_lengths(position, R) matches the Euler pose, single and batch."""
    poses = np.vstack([TABLE_3, random_poses(10, seed=4)])
    rotations = np.array([rotation_zyx(*pose[3:]) for pose in poses])
    expected = [leg_lengths_of(pose) for pose in poses]
    assert_allclose(leg_lengths(geometry, poses[:, :3], rotations), expected,
                    rtol=0.0, atol=1e-12)
    assert leg_lengths(geometry, poses[0, :3], rotations[0]).shape == (6,)
    assert_allclose(leg_lengths(geometry, poses[5, :3], rotations[5]), expected[5],
                    rtol=0.0, atol=1e-12)


# Jacobian.

def central_differences(pose, step=1e-6):
    """Approximate d l_i / d x_j by central differences of the paper's equation."""
    columns = []
    for j in range(6):
        plus, minus = list(pose), list(pose)
        plus[j] += step
        minus[j] -= step
        columns.append((np.array(leg_lengths_of(plus))
                        - np.array(leg_lengths_of(minus))) / (2.0 * step))
    return np.column_stack(columns)


@pytest.mark.parametrize('pose', [
    HOME, TABLE_3[3], TABLE_3[10], (0.05, -0.08, 0.38, -0.2, 0.25, -0.3),
    (0.0, 0.0, 0.45, 0.5, -1.0, 2.5),
])
def test_jacobian_matches_central_differences(geometry, pose):
    """The analytic Jacobian equals central finite differences at several poses."""
    result = jacobian(geometry, pose)
    assert result.shape == (6, 6)
    assert_allclose(result, central_differences(pose), rtol=0.0, atol=1e-7)


def test_jacobian_batch_shape_and_values(geometry):
    """A (N, 6) batch gives (N, 6, 6), each equal to finite differences."""
    poses = random_poses(5, seed=5)
    result = jacobian(geometry, poses)
    assert result.shape == (5, 6, 6)
    for pose, matrix in zip(poses, result):
        assert_allclose(matrix, central_differences(pose), rtol=0.0, atol=1e-7)


def test_jacobian_rejects_bad_pose(geometry):
    """A wrongly shaped pose raises ValueError."""
    with pytest.raises(ValueError, match='shape'):
        jacobian(geometry, np.zeros(5))


# Forward kinematics.

@pytest.mark.parametrize('k', range(11))
def test_forward_kinematics_table_3_row_from_home(geometry, k):
    """Each Table 3 row is found from the home guess to 1e-9 in a few iterations."""
    lengths = leg_lengths_of(TABLE_3[k])
    result = forward_kinematics(geometry, lengths)
    assert result.converged is True
    assert result.reason == ''
    assert result.iterations < 10
    assert result.residual <= 1e-12
    assert_allclose(result.pose[:3], TABLE_3[k][:3], rtol=0.0, atol=1e-9)
    assert_allclose(result.pose[3:], TABLE_3[k][3:], rtol=0.0, atol=1e-9)


def test_forward_kinematics_solution_reproduces_lengths(geometry):
    """The returned pose has the requested leg lengths within the tolerance."""
    lengths = leg_lengths_of(TABLE_3[6])
    result = forward_kinematics(geometry, lengths, tolerance=1e-10)
    assert result.residual <= 1e-10
    assert_allclose(leg_lengths_of(result.pose), lengths, rtol=0.0, atol=1e-10)


def test_forward_kinematics_at_home_takes_no_iteration(geometry):
    """The home lengths are solved by the default guess, the home pose, at once."""
    result = forward_kinematics(geometry, leg_lengths_of(HOME))
    assert result.converged is True
    assert result.iterations == 0
    assert_allclose(result.pose, HOME, rtol=0.0, atol=1e-15)


def test_forward_kinematics_1000_random_poses_batch(geometry):
    """1000 poses within +-0.1 m and +-15 deg of home all converge to within 1e-9."""
    poses = random_poses(1000, seed=6)
    lengths = np.array([leg_lengths_of(pose) for pose in poses])
    result = forward_kinematics(geometry, lengths)
    assert result.pose.shape == (1000, 6)
    assert np.all(result.converged)
    assert np.all(result.residual <= 1e-12)
    assert np.max(np.abs(result.pose - poses)) < 1e-9


def test_forward_kinematics_warm_start_needs_fewer_iterations(geometry):
    """Starting from the previous Table 3 row takes fewer iterations than from home."""
    for k in range(2, 11):
        lengths = leg_lengths_of(TABLE_3[k])
        cold = forward_kinematics(geometry, lengths, initial_guess=HOME)
        warm = forward_kinematics(geometry, lengths, initial_guess=TABLE_3[k - 1])
        assert warm.converged and cold.converged
        assert warm.iterations < cold.iterations, k
        assert_allclose(warm.pose, TABLE_3[k], rtol=0.0, atol=1e-9)


def test_forward_kinematics_single_result_types(geometry):
    """One solve gives a (6,) pose and plain bool, int, float and str fields."""
    result = forward_kinematics(geometry, leg_lengths_of(TABLE_3[4]))
    assert isinstance(result, ForwardKinematicsResult)
    assert result.pose.shape == (6,)
    assert type(result.converged) is bool
    assert type(result.iterations) is int
    assert type(result.residual) is float
    assert type(result.reason) is str


def test_forward_kinematics_batch_result_types(geometry):
    """A batch of N gives a (N, 6) pose, arrays of N flags, counts, residuals and N reasons."""
    lengths = [leg_lengths_of(row) for row in TABLE_3[:3]]
    result = forward_kinematics(geometry, lengths)
    assert result.pose.shape == (3, 6)
    assert result.converged.shape == (3,) and result.converged.dtype == bool
    assert result.iterations.shape == (3,) and np.issubdtype(result.iterations.dtype, np.integer)
    assert result.residual.shape == (3,) and result.residual.dtype == float
    assert result.reason == ('', '', '')


def test_forward_kinematics_one_batch_of_one_is_a_batch(geometry):
    """Lengths of shape (1, 6) give batch fields of length 1, not scalars."""
    result = forward_kinematics(geometry, [leg_lengths_of(TABLE_3[2])])
    assert result.pose.shape == (1, 6)
    assert result.converged.shape == (1,)


def test_forward_kinematics_broadcasts_one_guess_or_one_length_set(geometry):
    """One guess serves a batch of lengths, and one set of lengths a batch of guesses."""
    lengths = np.array([leg_lengths_of(row) for row in TABLE_3[1:4]])
    result = forward_kinematics(geometry, lengths, initial_guess=HOME)
    assert_allclose(result.pose, TABLE_3[1:4], rtol=0.0, atol=1e-9)
    guesses = np.array([HOME, TABLE_3[1], TABLE_3[2]])
    result = forward_kinematics(geometry, lengths[2], initial_guess=guesses)
    assert result.pose.shape == (3, 6)
    assert_allclose(result.pose, [TABLE_3[3]] * 3, rtol=0.0, atol=1e-9)


def test_forward_kinematics_rejects_mismatched_batches(geometry):
    """Two lengths sets and three guesses raise ValueError."""
    lengths = [leg_lengths_of(HOME)] * 2
    with pytest.raises(ValueError, match='same number of poses'):
        forward_kinematics(geometry, lengths, initial_guess=[HOME] * 3)


def test_forward_kinematics_iteration_limit_is_reported(geometry):
    """One iteration from home to the last Table 3 row is reported as not converged."""
    result = forward_kinematics(geometry, leg_lengths_of(TABLE_3[10]), max_iterations=1)
    assert result.converged is False
    assert result.iterations == 1
    assert 'iterations' in result.reason
    assert result.residual > 1e-12


def test_forward_kinematics_batch_reports_each_solve(geometry):
    """In a batch, a failing solve does not spoil the others."""
    lengths = [leg_lengths_of(TABLE_3[3]), [0.01] * 6, leg_lengths_of(HOME)]
    result = forward_kinematics(geometry, lengths)
    assert result.converged.tolist() == [True, False, True]
    assert result.reason[0] == '' and result.reason[2] == ''
    assert result.reason[1] != ''
    assert_allclose(result.pose[0], TABLE_3[3], rtol=0.0, atol=1e-9)
    assert_allclose(result.pose[2], HOME, rtol=0.0, atol=1e-12)


@pytest.mark.parametrize('lengths', [
    [0.01] * 6,
    [10.0, 10.0, 10.0, 0.1, 0.1, 0.1],
    [2.0, 2.0, 2.0, 2.0, 2.0, 0.05],
])
def test_forward_kinematics_impossible_lengths_are_not_solved(geometry, lengths):
    """Lengths no pose can have give converged False and a reason, not a pose or an error."""
    result = forward_kinematics(geometry, lengths)
    assert result.converged is False
    assert result.reason != ''
    assert result.residual > 1e-6
    if np.all(np.isfinite(result.pose)):
        assert np.max(np.abs(np.array(leg_lengths_of(result.pose)) - lengths)) > 1e-6


@pytest.mark.parametrize('lengths, max_iterations', [
    (leg_lengths_of(TABLE_3[10]), 1),
    (leg_lengths_of(TABLE_3[10]), 2),
    ([0.01] * 6, 50),
    ([10.0, 10.0, 10.0, 0.1, 0.1, 0.1], 50),
])
def test_forward_kinematics_residual_is_that_of_the_returned_pose(
        geometry, lengths, max_iterations):
    """When not converged, residual is max |l_i(pose) - lengths_i| of the pose returned."""
    result = forward_kinematics(geometry, lengths, max_iterations=max_iterations)
    assert result.converged is False
    assert np.all(np.isfinite(result.pose))
    actual = np.max(np.abs(np.array(leg_lengths_of(result.pose)) - lengths))
    assert_allclose(result.residual, actual, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize('lengths', [
    [0.7, 0.7, 0.7, 0.7, 0.7, -0.7],
    [0.7, 0.7, 0.0, 0.7, 0.7, 0.7],
    [0.7, math.nan, 0.7, 0.7, 0.7, 0.7],
    [0.7, 0.7, 0.7, math.inf, 0.7, 0.7],
])
def test_forward_kinematics_rejects_non_positive_or_non_finite_lengths(geometry, lengths):
    """Negative, zero, NaN or infinite lengths raise ValueError."""
    with pytest.raises(ValueError, match='finite and positive'):
        forward_kinematics(geometry, lengths)


@pytest.mark.parametrize('lengths', [[0.7] * 5, [[0.7] * 7], [[[0.7] * 6]]])
def test_forward_kinematics_rejects_wrong_length_shape(geometry, lengths):
    """Lengths that are not (6,) or (N, 6) raise ValueError."""
    with pytest.raises(ValueError, match='shape'):
        forward_kinematics(geometry, lengths)


@pytest.mark.parametrize('guess', [[0.0] * 5, [0.0, 0.0, math.nan, 0.0, 0.0, 0.0]])
def test_forward_kinematics_rejects_bad_initial_guess(geometry, guess):
    """A malformed initial guess raises ValueError naming it."""
    with pytest.raises(ValueError, match='initial_guess'):
        forward_kinematics(geometry, leg_lengths_of(HOME), initial_guess=guess)


@pytest.mark.parametrize('tolerance', [0.0, -1e-9, math.nan])
def test_forward_kinematics_rejects_bad_tolerance(geometry, tolerance):
    """A tolerance that is not positive raises ValueError."""
    with pytest.raises(ValueError, match='tolerance'):
        forward_kinematics(geometry, leg_lengths_of(HOME), tolerance=tolerance)


@pytest.mark.parametrize('max_iterations', [0, -3, 2.5])
def test_forward_kinematics_rejects_bad_max_iterations(geometry, max_iterations):
    """An iteration limit that is not a positive integer raises ValueError."""
    with pytest.raises(ValueError, match='max_iterations'):
        forward_kinematics(geometry, leg_lengths_of(HOME), max_iterations=max_iterations)


def test_forward_kinematics_looser_tolerance_is_honoured(geometry):
    """With tolerance 1e-4 the residual is within 1e-4 and no more iterations are taken."""
    lengths = leg_lengths_of(TABLE_3[10])
    loose = forward_kinematics(geometry, lengths, tolerance=1e-4)
    tight = forward_kinematics(geometry, lengths)
    assert loose.converged and loose.residual <= 1e-4
    assert loose.iterations <= tight.iterations


def test_forward_kinematics_returns_canonical_angles(geometry):
    """A guess wound by whole turns gives the same pose with angles in canonical ranges."""
    pose = TABLE_3[5]
    guess = np.array(pose) + [0.0, 0.0, 0.0, 2.0 * math.pi, 0.0, -4.0 * math.pi]
    result = forward_kinematics(geometry, leg_lengths_of(pose), initial_guess=guess)
    assert result.converged
    assert_allclose(result.pose, pose, rtol=0.0, atol=1e-9)


def test_forward_kinematics_random_angles_in_canonical_range(geometry):
    """Solved angles lie in beta in [-pi/2, pi/2] and alpha, gamma in [-pi, pi]."""
    poses = random_poses(200, seed=7)
    guesses = poses + [0.0, 0.0, 0.0, 2.0 * math.pi, 0.0, 2.0 * math.pi]
    lengths = np.array([leg_lengths_of(pose) for pose in poses])
    result = forward_kinematics(geometry, lengths, initial_guess=guesses)
    assert np.all(result.converged)
    assert np.all(np.abs(result.pose[:, [3, 5]]) <= math.pi)
    assert np.all(np.abs(result.pose[:, 4]) <= math.pi / 2)
    assert_allclose(result.pose, poses, rtol=0.0, atol=1e-9)


def test_single_pose_inverse_kinematics_equals_batch(geometry):
    """The one-pose fast path gives the batch path's lengths to 1e-12 m."""
    poses = random_poses(200, seed=7)
    batch = inverse_kinematics(geometry, poses)
    singles = np.array([inverse_kinematics(geometry, pose) for pose in poses])
    assert_allclose(singles, batch, rtol=0.0, atol=1e-12)
    assert_allclose(batch, [leg_lengths_of(pose) for pose in poses], rtol=0.0, atol=1e-12)


def test_batched_inverse_kinematics_spans_blocks(geometry):
    """A batch longer than one block equals the per-pose leg vector norms."""
    from stewart_kinematics.model.inverse import IK_BLOCK_SIZE, leg_vectors_from_euler
    poses = random_poses(2 * IK_BLOCK_SIZE + 3, seed=7)
    expected = np.linalg.norm(leg_vectors_from_euler(geometry, poses), axis=-1)
    assert_allclose(inverse_kinematics(geometry, poses), expected, rtol=0.0, atol=1e-12)


def test_single_pose_leg_lengths_equals_batch(geometry):
    """leg_lengths of one position and matrix equals its batch form."""
    from stewart_kinematics.model.rotations import euler_zyx_to_matrix
    poses = random_poses(50, seed=7)
    rotations = euler_zyx_to_matrix(poses[:, 3:])
    batch = leg_lengths(geometry, poses[:, :3], rotations)
    for pose, rotation, expected in zip(poses, rotations, batch):
        assert_allclose(leg_lengths(geometry, pose[:3], rotation), expected, atol=1e-12)


@pytest.mark.parametrize('start', ['home', 'nearby'])
def test_single_pose_forward_kinematics_equals_batch(geometry, start):
    """The one-pose solver (cold from home, or warm) takes the batch solver's steps."""
    poses = random_poses(100, seed=7)
    lengths = inverse_kinematics(geometry, poses)
    guesses = (np.broadcast_to(geometry.home_pose, poses.shape) if start == 'home'
               else poses + 1e-4)
    batch = forward_kinematics(geometry, lengths, guesses)
    for k in range(len(poses)):
        single = forward_kinematics(geometry, lengths[k], guesses[k])
        assert single.converged and batch.converged[k]
        assert single.iterations == batch.iterations[k]
        assert single.reason == batch.reason[k] == ''
        assert_allclose(single.pose, batch.pose[k], rtol=0.0, atol=1e-10)
        assert_allclose(single.pose, poses[k], rtol=0.0, atol=1e-9)


def test_single_pose_forward_kinematics_failures_match_batch(geometry):
    """Unreachable lengths fail with the same reason in the one-pose and the batch solver."""
    lengths = np.full(6, 5.0)
    single = forward_kinematics(geometry, lengths, max_iterations=5)
    batch = forward_kinematics(geometry, lengths[None, :], max_iterations=5)
    assert not single.converged
    assert single.reason == batch.reason[0]
    assert single.iterations == batch.iterations[0]
    assert single.residual == pytest.approx(batch.residual[0], abs=1e-9)


def test_the_trusted_solve_is_forward_kinematics_without_its_checks(geometry):
    """
    solve_trusted (lengths checked where they entered) gives forward_kinematics' result.

    Converged, unreachable, singular and stopped-early solves, from a pose, from home, from a
    converged and from a failed previous result: the same fields to the bit, and the same
    Jacobian handed on to the next solve.
    """
    poses = random_poses(30, seed=41)
    targets = list(inverse_kinematics(geometry, poses)) + [np.full(6, 5.0), np.full(6, 0.2)]
    converged = forward_kinematics(geometry, targets[0])
    failed = forward_kinematics(geometry, np.full(6, 5.0), max_iterations=3)
    assert converged.converged and not failed.converged
    starts = [np.array(HOME), np.array(TABLE_3[4]), poses[1] + 1e-3, list(TABLE_3[2]),
              converged, failed]
    for target in targets:
        for start in starts:
            for tolerance, max_iterations in ((1e-12, 50), (1e-6, 2), (1e-12, 1)):
                expected = forward_kinematics(geometry, target, start, tolerance=tolerance,
                                              max_iterations=max_iterations)
                trusted = solve_trusted(geometry, target.tolist(), start, tolerance,
                                        max_iterations)
                assert trusted == expected
                assert trusted._solve[1:] == expected._solve[1:]
                assert trusted.pose.flags.writeable is False


def count_jacobian_inversions(monkeypatch):
    """Count the Jacobians the solver inverts (each costs a 6x6 inversion)."""
    calls = []
    inverse = np.linalg.inv

    def counting_inverse(matrix):
        calls.append(1)
        return inverse(matrix)
    monkeypatch.setattr(forward_solver.np.linalg, 'inv', counting_inverse)
    return calls


def ramp_at_1khz(seconds=1.0):
    """Poses along Table 3's ramp (row 0 to row 10 in 10 s) sampled every millisecond."""
    times = np.arange(int(seconds * 1000) + 1) * 1e-3
    return np.array(TABLE_3[0]) + np.outer(times / 10.0, np.subtract(TABLE_3[10], TABLE_3[0]))


def test_tracking_from_the_last_result_reuses_its_jacobian(geometry, monkeypatch):
    """
    Passing the last result as the guess gives the same poses with far fewer Jacobians.

    Along a 1 kHz ramp each solve from the last pose alone needs a Jacobian at its start;
    from the last result, the solver starts with that result's Jacobian, microns away.
    """
    poses = ramp_at_1khz()
    lengths = inverse_kinematics(geometry, poses)
    calls = count_jacobian_inversions(monkeypatch)
    from_pose, last = [], forward_kinematics(geometry, lengths[0])
    for target in lengths[1:]:
        last = forward_kinematics(geometry, target, last.pose)
        assert last.converged
        from_pose.append(last.pose)
    inversions_from_pose = len(calls)
    calls.clear()
    from_result, last = [], forward_kinematics(geometry, lengths[0])
    for target in lengths[1:]:
        last = forward_kinematics(geometry, target, last)
        assert last.converged
        from_result.append(last.pose)
    assert inversions_from_pose >= 0.9 * len(poses)
    assert len(calls) < inversions_from_pose / 2
    assert_allclose(from_result, poses[1:], rtol=0.0, atol=1e-9)
    assert_allclose(from_result, from_pose, rtol=0.0, atol=1e-10)


def test_one_solve_reuses_a_jacobian_while_it_converges_fast(geometry, monkeypatch):
    """
    A cold solve inverts fewer Jacobians than it takes steps, and reaches 1e-9 all the same.

    Its first step uses the cached home Jacobian; later steps reuse the last Jacobian when the
    step before cut the error by JACOBIAN_REUSE_CONTRACTION or more (modified Newton).
    """
    poses = random_poses(200, seed=11)
    lengths = inverse_kinematics(geometry, poses)
    calls = count_jacobian_inversions(monkeypatch)
    results = [forward_kinematics(geometry, target) for target in lengths]
    assert all(result.converged for result in results)
    assert len(calls) < sum(result.iterations for result in results) - len(results)
    assert_allclose([result.pose for result in results], poses, rtol=0.0, atol=1e-9)


def test_a_result_that_did_not_converge_gives_only_its_pose(geometry, monkeypatch):
    """A failed result as the guess starts from its pose with a fresh Jacobian."""
    failed = forward_kinematics(geometry, np.full(6, 5.0), max_iterations=3)
    assert not failed.converged
    target = leg_lengths_of(TABLE_3[1])
    calls = count_jacobian_inversions(monkeypatch)
    from_result = forward_kinematics(geometry, target, failed)
    assert len(calls) >= 1
    from_pose = forward_kinematics(geometry, target, failed.pose)
    assert from_result.converged == from_pose.converged
    assert from_result.reason == from_pose.reason
    assert_allclose(from_result.pose, from_pose.pose, rtol=0.0, atol=0.0)


@pytest.mark.parametrize('lengths', [
    tuple(leg_lengths_of(HOME)),
    list(leg_lengths_of(HOME)),
    np.array(leg_lengths_of(HOME), dtype=np.float32),
])
def test_forward_kinematics_accepts_any_sequence_of_six_numbers(geometry, lengths):
    """Tuples, lists and float32 arrays are lengths like a float array (strings are not)."""
    result = forward_kinematics(geometry, lengths)
    assert result.converged
    assert result.pose.shape == (6,)
    assert_allclose(result.pose, HOME, rtol=0.0, atol=1e-6)


# A batch with bad rows, and single solves against batches ---------------------------------

def test_a_batch_solves_its_valid_rows_and_reports_the_others(geometry):
    # The defect: one NaN row made the whole batch raise ValueError.
    good = inverse_kinematics(geometry, random_poses(3, seed=11))
    lengths = np.array([good[0], [0.7, math.nan, 0.7, 0.7, 0.7, 0.7], good[1],
                        [0.7, 0.7, 0.7, 0.7, 0.7, -0.7], [0.7, 0.7, 0.0, 0.7, 0.7, 0.7],
                        [math.inf] * 6, good[2]])
    result = forward_kinematics(geometry, lengths)
    assert result.converged.tolist() == [True, False, True, False, False, False, True]
    for row in (1, 3, 4, 5):
        assert result.reason[row] == forward_solver.INVALID_LENGTHS
        assert 'finite and positive' in result.reason[row]
        assert result.residual[row] == math.inf and result.iterations[row] == 0
        assert_allclose(result.pose[row], HOME, rtol=0.0, atol=0.0)
    for row, expected in zip((0, 2, 6), good):
        single = forward_kinematics(geometry, expected)
        assert result.reason[row] == '' and result.iterations[row] == single.iterations
        assert_allclose(result.pose[row], single.pose, rtol=0.0, atol=1e-15)
    with pytest.raises(ValueError, match='finite and positive'):
        forward_kinematics(geometry, lengths[1])


def test_a_batch_reports_a_row_whose_guess_is_not_finite(geometry):
    lengths = inverse_kinematics(geometry, random_poses(2, seed=12))
    guesses = np.array([HOME, [0.0, math.nan, 0.4, 0.0, 0.0, 0.0]])
    result = forward_kinematics(geometry, lengths, guesses)
    assert result.converged.tolist() == [True, False]
    assert result.reason[1] == forward_solver.INVALID_GUESS
    with pytest.raises(ValueError, match='initial_guess'):
        forward_kinematics(geometry, lengths[1], guesses[1])


def assert_single_solves_equal_batch(geometry, lengths, guesses, **options):
    """Solve each row alone and the rows as one batch; assert they agree in every field."""
    batch = forward_kinematics(geometry, lengths, guesses, **options)
    for k in range(len(lengths)):
        single = forward_kinematics(geometry, lengths[k], guesses[k], **options)
        assert (single.reason, single.converged, single.iterations) == (
            batch.reason[k], batch.converged[k], batch.iterations[k]), k
        # The same arithmetic: the same residual to the bit; the pose to rounding, as numpy's
        # and the math module's atan2 may differ by one unit in the last place.
        assert single.residual == batch.residual[k]
        assert_allclose(single.pose, batch.pose[k], rtol=0.0, atol=1e-15)
    return batch


def test_single_and_batch_solves_agree_on_every_field_failures_included(geometry):
    # The defect: lengths [10] * 6 gave 'no convergence' alone and 'diverged' in a batch, as
    # the two solvers rounded differently and chaotic iterates drifted apart.
    rng = np.random.default_rng(13)
    reachable = inverse_kinematics(geometry, random_poses(150, seed=14))
    unreachable = np.vstack([rng.uniform(0.2, 3.0, (150, 6)), [[10.0] * 6, [0.01] * 6]])
    singular = np.array(HOME[:5] + (singular_yaw(),))
    near_singular = np.array([leg_lengths_of(singular + np.array([0.0] * 5 + [offset]))
                              for offset in (0.0, 1e-9, 1e-6, -1e-6, 1e-3)])
    lengths = np.vstack([reachable, unreachable, near_singular])
    guesses = np.vstack([np.broadcast_to(HOME, (len(reachable) + len(unreachable), 6)),
                         np.broadcast_to(singular, (len(near_singular), 6))])
    batch = assert_single_solves_equal_batch(geometry, lengths, guesses)
    reasons = set(batch.reason)
    assert '' in reasons and forward_solver.DIVERGED in reasons
    assert_single_solves_equal_batch(geometry, unreachable[:40], guesses[:40], max_iterations=7)


def test_single_and_batch_solves_agree_at_a_singular_jacobian():
    # A platform whose joints coincide at its home pose (every leg of zero length): the
    # Jacobian there is zero, and both solvers say so.
    joints = np.array(PLATFORM_JOINTS)
    joints[:, 2] = 0.0
    flat = Geometry(base_joints=joints, platform_joints=joints, home_pose=[0.0] * 6)
    lengths = np.array([[0.2] * 6, [0.3] * 6])
    batch = assert_single_solves_equal_batch(flat, lengths, np.zeros((2, 6)))
    assert batch.reason == (forward_solver.SINGULAR_JACOBIAN,) * 2


def test_one_pose_paths_equal_the_batch_formulas(geometry):
    # One formula each, run on floats for one pose and on arrays for a batch: the same
    # operations in the same order, so the results are equal to the bit (inverse kinematics
    # from Euler angles to 1e-15 relative: numpy's and the math module's sine may differ in
    # the last place on some processors).
    poses = np.vstack([random_poses(50, seed=15), [[0.0, 0.0, 0.0, 0.0, math.pi / 2, 0.0]]])
    rotations = np.array([rotation_zyx(*pose[3:]) for pose in poses])
    batch_lengths = leg_lengths(geometry, poses[:, :3], rotations)
    batch_vectors = leg_vectors(geometry, poses[:, :3], rotations)
    batch_jacobians = jacobians.twist_jacobian(geometry, poses[:, :3], rotations)
    ik_batch = inverse_kinematics(geometry, poses)
    for k, (pose, rotation) in enumerate(zip(poses, rotations)):
        assert np.array_equal(leg_lengths(geometry, pose[:3], rotation), batch_lengths[k])
        assert np.array_equal(leg_vectors(geometry, pose[:3], rotation), batch_vectors[k])
        assert np.array_equal(jacobians.twist_jacobian(geometry, pose[:3], rotation),
                              batch_jacobians[k])
        assert_allclose(inverse_kinematics(geometry, pose), ik_batch[k], rtol=1e-15, atol=0.0)
        assert_allclose(jacobians.jacobian(geometry, pose),
                        jacobians.jacobian(geometry, poses)[k], rtol=0.0, atol=0.0)
    euler_batch = formulas.batch_euler_legs(formulas.constants_of(geometry), poses)[0].T
    assert np.array_equal(ik_batch, euler_batch)
