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
ForwardKinematicsResult.pose_error_bound is a bound: checked in long double near the singularity.

The defect (issue 21): near the yaw singularity of the paper's platform (gamma about 90.38 deg)
converged solves were up to 2.6 times further from the pose whose lengths they were given than
the bound said, because the bound was twice a first-order figure that nothing proved. The
bound is now Kantorovich's radius, with the curvature of the leg lengths, and ``inf`` where no
ball is proven to hold a solution. Each exact pose here is found by Newton's method on leg
lengths computed in long double (64-bit mantissa), then checked to 1e-18 m.
"""

import math

import numpy as np
import pytest
from reference import (
    BASE_JOINTS,
    HOME,
    leg_lengths,
    leg_lengths_long,
    PLATFORM_JOINTS,
    random_poses,
    rotation_angle,
    rotation_zyx,
    singular_yaw,
    twist_jacobian,
)

from stewart_kinematics import forward_kinematics, inverse_kinematics, jacobian
from stewart_kinematics.model.error_bound import LENGTH_ROUNDING_ULPS

pytestmark = pytest.mark.core

#: Largest leg length error of the long double Newton solution, metres.
EXACT_RESIDUAL = 1e-18


@pytest.fixture(scope='module')
def geometry():
    """Build the paper's platform."""
    from reference import paper_geometry
    return paper_geometry()


def exact_pose(geometry, lengths, start):
    """
    Return the pose whose leg lengths are exactly ``lengths``, by Newton's method from ``start``.

    Iterates and residuals in long double; the float Jacobian only steers. Newton's method
    from a point within Kantorovich's radius converges to the solution in that radius.
    """
    pose = np.asarray(start, dtype=np.longdouble)
    target = np.asarray(lengths, dtype=np.longdouble)
    for _ in range(100):
        residual = leg_lengths_long(pose) - target
        if np.max(np.abs(residual)) < EXACT_RESIDUAL / 10:
            break
        step = np.linalg.solve(jacobian(geometry, pose.astype(float)), residual.astype(float))
        pose = pose - step.astype(np.longdouble)
    assert np.max(np.abs(leg_lengths_long(pose) - target)) < EXACT_RESIDUAL
    return pose


def pose_distance(pose, other):
    """Return the larger of the position distance (m) and the rotation angle (rad)."""
    pose, other = np.asarray(pose, dtype=float), np.asarray(other, dtype=float)
    return max(float(np.linalg.norm(pose[:3] - other[:3])),
               rotation_angle(rotation_zyx(*pose[3:]), rotation_zyx(*other[3:])))


def near_singularity(count, seed, closest=1e-9, farthest=1e-3):
    """Return poses at yaws ``closest`` to ``farthest`` rad from the fold, both sides."""
    rng = np.random.default_rng(seed)
    poses = np.tile(np.array(HOME[:5] + (singular_yaw(),)), (count, 1))
    poses[:, 5] += rng.choice([-1.0, 1.0], count) * 10.0 ** rng.uniform(
        math.log10(closest), math.log10(farthest), count)
    poses[:, :5] += rng.normal(0.0, 1e-4, (count, 5)) * rng.uniform(0.0, 1.0, (count, 1))
    return poses


def test_the_bound_holds_against_the_exact_pose_near_the_singularity(geometry):
    rng = np.random.default_rng(21)
    poses = near_singularity(160, seed=22)
    lengths = inverse_kinematics(geometry, poses)
    starts = poses + rng.normal(0.0, 1.0, poses.shape) * 10.0 ** rng.uniform(-8, -2, (160, 1))
    proven = 0
    for target, start in zip(lengths, starts):
        result = forward_kinematics(geometry, target, start)
        if not (result.converged and result.pose_error_bound < math.inf):
            continue
        proven += 1
        distance = pose_distance(result.pose, exact_pose(geometry, target, result.pose))
        assert distance <= result.pose_error_bound, (result, distance)
    assert proven >= 40   # most solves are proven; the closest to the fold are not


def test_the_bound_holds_against_the_pose_the_lengths_came_from(geometry):
    # The case: within 1e-5 rad of the fold the same lengths have a second pose a
    # few bounds away; a finite bound must hold for the pose the lengths came from, not only
    # for the solution that happened to be found.
    rng = np.random.default_rng(23)
    poses = near_singularity(300, seed=24, closest=1e-12, farthest=1e-5)
    starts = poses + rng.normal(0.0, 1.0, poses.shape) * 10.0 ** rng.uniform(-9, -3, (300, 1))
    lengths = inverse_kinematics(geometry, poses)
    unproven = 0
    for truth, target, start in zip(poses, lengths, starts):
        result = forward_kinematics(geometry, target, start)
        if not result.converged:
            continue
        unproven += result.pose_error_bound == math.inf
        assert pose_distance(result.pose, truth) <= result.pose_error_bound, result
    assert unproven > 100


def test_the_bound_is_infinite_where_the_residual_is_too_large_for_the_curvature(geometry):
    # 1e-6 rad from the fold, a residual of 1e-13 m leaves the pose microns off: no ball
    # around the solve is proven to hold a solution.
    truth = np.array(HOME[:5] + (singular_yaw() + 1e-6,))
    lengths = np.array(leg_lengths(truth))
    guess = truth.copy()
    guess[5] += 1e-3
    result = forward_kinematics(geometry, lengths, guess)
    assert result.converged and result.condition > 1e5
    assert result.pose_error_bound == math.inf
    # Farther from the fold the same kind of solve is proven, and its bound is small.
    truth[5] = singular_yaw() + 1e-2
    lengths = np.array(leg_lengths(truth))
    result = forward_kinematics(geometry, lengths, guess)
    assert result.converged and 0.0 < result.pose_error_bound < 1e-9


def test_the_bound_is_between_once_and_twice_the_first_order_figure(geometry):
    # eta = sqrt(6) e / sigma (e the residual plus the rounding floor) times max(1, 1 / rho):
    # Kantorovich's radius lies between eta and 2 eta.
    poses = random_poses(200, seed=25)
    lengths = inverse_kinematics(geometry, poses)
    result = forward_kinematics(geometry, lengths)
    assert np.all(result.converged)
    rho = geometry.platform_radius
    for pose, residual, bound in zip(result.pose, result.residual, result.pose_error_bound):
        jac = twist_jacobian(pose)
        jac[:, 3:] /= rho
        sigma = np.linalg.svd(jac, compute_uv=False)[-1]
        floor = LENGTH_ROUNDING_ULPS * np.finfo(float).eps * max(
            np.linalg.norm(pose[:3]) + np.linalg.norm(p) + np.linalg.norm(b)
            for p, b in zip(PLATFORM_JOINTS, BASE_JOINTS))
        eta = math.sqrt(6.0) * (residual + floor) / sigma
        assert eta * max(1.0, 1.0 / rho) <= bound <= 2.0 * eta * max(1.0, 1.0 / rho) * 1.001
    for pose, target, bound in zip(result.pose[:20], lengths[:20], result.pose_error_bound):
        assert pose_distance(pose, exact_pose(geometry, target, pose)) <= bound
    assert np.max(result.pose_error_bound) < 1e-9
    assert np.median(result.pose_error_bound) < 1e-11
