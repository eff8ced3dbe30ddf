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
Tests of ForwardKinematicsResult: condition number, pose error bound, equality and hashing.

The defect these guard against: near the paper platform's singularity (a yaw of 90.4 degrees
at the home height) a solve reported convergence on a leg residual of 1e-13 m while its pose
was 5e-6 off, and nothing in the result said so.
"""

import math

import numpy as np
import pytest
from reference import (
    BASE_JOINTS,
    HOME,
    leg_lengths,
    PLATFORM_JOINTS,
    random_poses,
    rotation_angle,
    rotation_zyx,
    singular_yaw,
    twist_jacobian,
)

from stewart_kinematics.model import error_bound, jacobians
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.inverse import inverse_kinematics
from stewart_kinematics.model.jacobians import jacobian_condition

pytestmark = pytest.mark.core


@pytest.fixture(scope='module')
def geometry():
    """Build the paper's platform."""
    from reference import paper_geometry
    return paper_geometry()


def reference_condition(pose):
    """Return numpy.linalg.cond of the twist Jacobian with rotation columns divided by rho."""
    centred = PLATFORM_JOINTS - PLATFORM_JOINTS.mean(axis=0)
    rho = math.sqrt(float(np.sum(centred ** 2)) / 6.0)
    jac = twist_jacobian(pose)
    jac[:, 3:] /= rho
    return float(np.linalg.cond(jac))


def pose_error(pose, truth):
    """Return the larger of the position error (m) and the rotation angle error (rad)."""
    position = float(np.linalg.norm(np.asarray(pose[:3]) - truth[:3]))
    return max(position, rotation_angle(rotation_zyx(*pose[3:]), rotation_zyx(*truth[3:])))


def test_condition_is_that_of_the_dimensionless_jacobian_at_the_pose(geometry):
    poses = random_poses(20, seed=3)
    batch = forward_kinematics(geometry, inverse_kinematics(geometry, poses))
    expected = [reference_condition(pose) for pose in batch.pose]
    assert isinstance(batch.condition, np.ndarray) and batch.condition.shape == (20,)
    np.testing.assert_allclose(batch.condition, expected, rtol=1e-9)
    single = forward_kinematics(geometry, inverse_kinematics(geometry, poses[0]))
    assert isinstance(single.condition, float)
    assert single.condition == pytest.approx(expected[0], rel=1e-9)
    assert single.condition == pytest.approx(float(jacobian_condition(
        geometry, single.pose[:3], rotation_zyx(*single.pose[3:]))), rel=1e-12)


def test_condition_and_bound_cost_a_solve_nothing(geometry, monkeypatch):
    decompositions = []
    svd = np.linalg.svd
    monkeypatch.setattr(np.linalg, 'svd', lambda *a, **k: decompositions.append(1) or svd(*a, **k))
    lengths = inverse_kinematics(geometry, random_poses(3, seed=4))
    single, batch = forward_kinematics(geometry, lengths[0]), forward_kinematics(geometry, lengths)
    assert decompositions == []
    assert single.condition > 1.0 and single.pose_error_bound > 0.0
    assert np.all(batch.condition > 1.0) and np.all(batch.pose_error_bound > 0.0)
    assert len(decompositions) == 2
    single.condition, single.pose_error_bound, batch.condition  # kept: computed once
    assert len(decompositions) == 2


def test_pose_error_bound_is_small_at_ordinary_poses_and_covers_the_error(geometry):
    poses = np.concatenate([random_poses(300, seed=5), random_poses(5, seed=6, around=HOME,
                                                                    position_range=0.0)])
    # From home, whose last step typically lands far below the tolerance (a cold solve from
    # the start table stops nearer it: median bound 3e-12, test/model/test_start_table.py).
    result = forward_kinematics(geometry, inverse_kinematics(geometry, poses), HOME)
    assert np.all(result.converged)
    errors = [pose_error(found, truth) for found, truth in zip(result.pose, poses)]
    assert np.all(result.pose_error_bound >= errors)
    # Largest where the residual is just under the tolerance (1e-12 m), small elsewhere.
    assert np.max(result.pose_error_bound) < 1e-9
    assert np.median(result.pose_error_bound) < 1e-12


def test_pose_error_bound_covers_the_error_near_the_singularity(geometry):
    # The case: at 1e-6 rad from the singular yaw, solves from nearby starts converge
    # on residuals of 1e-13 m to poses microns off, and the bound must say so.
    singular = np.array(HOME[:5] + (singular_yaw(),))
    truth = singular + [0.0, 0.0, 0.0, 0.0, 0.0, 1e-6]
    lengths = np.array(leg_lengths(truth))
    # The same lengths have a second solution across the fold; a start there converges to it.
    mirror = forward_kinematics(geometry, lengths, 2.0 * singular - truth, tolerance=1e-15,
                                max_iterations=200)
    assert np.max(np.abs(np.array(leg_lengths(mirror.pose)) - lengths)) < 1e-15
    assert pose_error(mirror.pose, truth) > 1e-6
    largest_error = 0.0
    for axis in range(6):
        for offset in (-1e-3, 1e-3):
            guess = truth.copy()
            guess[axis] += offset
            result = forward_kinematics(geometry, lengths, guess)
            assert result.converged and result.residual <= 1e-12
            error = min(pose_error(result.pose, truth), pose_error(result.pose, mirror.pose))
            assert result.condition > 1e5
            # Too near the fold for a proof (test_error_bound.py): inf, not a number
            # that the error beats.
            assert error <= result.pose_error_bound
            largest_error = max(largest_error, error)
    assert largest_error > 1e-6  # the defect: converged, yet microns off


def test_pose_error_bound_is_infinite_where_a_solve_failed(geometry):
    failed = forward_kinematics(geometry, [10.0] * 6)
    assert not failed.converged and failed.pose_error_bound == math.inf
    batch = forward_kinematics(geometry, [[10.0] * 6, list(geometry.home_leg_lengths)])
    assert batch.pose_error_bound[0] == math.inf and batch.pose_error_bound[1] < 1e-12


def test_results_compare_equal_field_by_field_and_hash_alike(geometry):
    lengths = inverse_kinematics(geometry, random_poses(4, seed=7))
    first = forward_kinematics(geometry, lengths[0])
    again = forward_kinematics(geometry, lengths[0])
    other = forward_kinematics(geometry, lengths[1])
    assert first == again and hash(first) == hash(again)
    assert first != other
    assert len({first, again, other}) == 2
    batch = forward_kinematics(geometry, lengths)
    batch_again = forward_kinematics(geometry, lengths)
    assert batch == batch_again and hash(batch) == hash(batch_again)
    assert batch != forward_kinematics(geometry, lengths[::-1])
    assert batch != first and first != 'a result'
    first.condition  # a cached figure changes neither equality nor hash
    assert first == again and hash(first) == hash(again)


def test_a_result_is_immutable(geometry):
    result = forward_kinematics(geometry, geometry.home_leg_lengths)
    with pytest.raises(ValueError):
        result.pose[0] = 1.0
    with pytest.raises(AttributeError):
        result.converged = False


def test_pose_error_bound_definition(geometry):
    # The documented formula: Kantorovich's radius from the smallest singular value of the
    # dimensionless Jacobian and the curvature of the leg lengths.
    pose = random_poses(1, seed=8)[0]
    result = forward_kinematics(geometry, inverse_kinematics(geometry, pose))
    rho = geometry.platform_radius
    jac = twist_jacobian(result.pose)
    jac[:, 3:] /= rho
    singular_values = np.linalg.svd(jac, compute_uv=False)
    eps = np.finfo(float).eps
    sigma = singular_values[-1] - error_bound.SINGULAR_VALUE_ROUNDING_ULPS * eps * (
        singular_values[0])
    arms = np.linalg.norm(PLATFORM_JOINTS, axis=1)
    sizes = np.linalg.norm(result.pose[:3]) + arms + np.linalg.norm(BASE_JOINTS, axis=1)
    error = result.residual + error_bound.LENGTH_ROUNDING_ULPS * eps * max(sizes)
    eta = math.sqrt(6.0) * error / sigma
    reach = np.sqrt(1.0 + (arms / rho) ** 2)
    shortest = np.array(leg_lengths(pose)) - result.residual - 2.0 * eta * reach
    curvature = math.sqrt(float(np.sum((reach ** 2 / shortest + arms / rho ** 2) ** 2)))
    h = eta * curvature / sigma
    expected = 2.0 * eta / (1.0 + math.sqrt(1.0 - 2.0 * h)) * max(1.0, 1.0 / rho)
    assert result.pose_error_bound == pytest.approx(expected, rel=1e-6)


def test_one_solve_figures_equal_the_batch_ones(geometry):
    # One solve takes a float path (fk_node pays for it on every message); a batch of one the
    # array path: the same condition numbers and bounds, also near and at the singularity.
    singular = np.array(HOME[:5] + (singular_yaw(),))
    poses = np.concatenate([random_poses(50, seed=9), [singular + [0, 0, 0, 0, 0, 1e-6]]])
    lengths = inverse_kinematics(geometry, poses)
    for pose, legs in zip(poses, lengths):
        single = forward_kinematics(geometry, legs, pose)
        batch = forward_kinematics(geometry, legs[None, :], pose[None, :])
        np.testing.assert_array_equal(single.pose, batch.pose[0])
        assert single.condition == pytest.approx(batch.condition[0], rel=1e-9)
        assert single.pose_error_bound == pytest.approx(batch.pose_error_bound[0], rel=1e-9)
    assert single.condition > 1e5


def test_one_solve_figures_at_exact_singularities(geometry):
    # A leg of zero length (its platform joint on its base joint): a zero row, condition and
    # bound infinite on both paths; a failed solve: bound infinite.
    from reference import BASE_JOINTS, paper_geometry
    platform_joints = np.array(PLATFORM_JOINTS, dtype=float)
    platform_joints[0] = BASE_JOINTS[0]
    touching = paper_geometry(platform_joints=platform_joints)
    pose = np.zeros(6)  # leg 1's joints coincide: its vector is exactly zero
    single = jacobians.single_singular_values(
        *jacobians.single_dimensionless_jacobian(touching, pose.tolist()))
    batch = jacobians.dimensionless_singular_values(touching, pose[None, :3], np.eye(3)[None])
    assert single[-1] == 0.0 == batch[0, -1]
    np.testing.assert_allclose(single[:-1], batch[0, :-1], rtol=1e-12)
    home = list(HOME)
    for converged, values in ((True, single), (False, [1.0, 0.5])):
        assert error_bound.single_pose_error_bound(
            touching, home, [0.7] * 6, 0.0, converged, values) == math.inf
