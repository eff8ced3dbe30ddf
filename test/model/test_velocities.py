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
"""Velocity kinematics against finite differences of the closed-form inverse kinematics."""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import HOME, paper_geometry, rotation_vector_matrix, singular_yaw

from stewart_kinematics import leg_lengths, SingularPoseError
from stewart_kinematics.model.jacobians import jacobian_condition
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.model.velocities import (
    DEFAULT_MAX_TWIST_CONDITION,
    leg_velocities,
    platform_twist,
    twist_jacobian,
)
from stewart_kinematics.parameters import load_geometry

pytestmark = pytest.mark.core

GEOMETRY = load_geometry(
    Path(__file__).resolve().parents[2] / 'config' / 'paper_platform.yaml')
POSES = np.array([
    [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0],
    [0.05, 0.075, 0.4825, math.radians(7.5), math.radians(-7.5), math.radians(10.0)],
    [0.1, 0.15, 0.5325, math.radians(15.0), math.radians(-15.0), math.radians(20.0)],
])
TWISTS = np.array([
    [0.1, 0.0, 0.0, 0.0, 0.0, 0.0],
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.5],
    [0.1, -0.2, 0.05, 0.3, -0.1, 0.2],
])


def moved_lengths(pose, twist, dt):
    """Return the leg lengths after moving with ``twist`` for ``dt`` seconds from ``pose``."""
    rotation = rotation_vector_matrix(np.asarray(twist[3:]) * dt) @ euler_zyx_to_matrix(pose[3:])
    return leg_lengths(GEOMETRY, np.asarray(pose[:3]) + np.asarray(twist[:3]) * dt, rotation)


@pytest.mark.parametrize('pose', POSES)
@pytest.mark.parametrize('twist', TWISTS)
def test_leg_velocities_match_finite_differences(pose, twist):
    """Leg velocities equal the central difference of the lengths along the twist."""
    dt = 1e-6
    expected = (moved_lengths(pose, twist, dt) - moved_lengths(pose, twist, -dt)) / (2 * dt)
    assert_allclose(leg_velocities(GEOMETRY, pose, twist), expected, rtol=0.0, atol=1e-8)


def test_platform_twist_inverts_leg_velocities():
    """platform_twist recovers the twist that produced the leg velocities, in a batch."""
    velocities = leg_velocities(GEOMETRY, POSES, TWISTS)
    assert velocities.shape == (3, 6)
    assert_allclose(platform_twist(GEOMETRY, POSES, velocities), TWISTS, rtol=0.0, atol=1e-12)


def test_pure_vertical_velocity_at_home():
    """At home, rising at 1 m/s lengthens each leg at its vertical direction cosine."""
    legs = GEOMETRY.platform_joints + [0.0, 0.0, 0.4325] - GEOMETRY.base_joints
    expected = legs[:, 2] / np.linalg.norm(legs, axis=1)
    velocities = leg_velocities(GEOMETRY, POSES[0], [0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    assert_allclose(velocities, expected, rtol=0.0, atol=1e-15)


def test_jacobian_shape_and_bad_input():
    """The Jacobian is (6, 6) or (N, 6, 6); non-finite twists raise ValueError."""
    rotation = euler_zyx_to_matrix(POSES[:, 3:])
    assert twist_jacobian(GEOMETRY, POSES[0, :3], rotation[0]).shape == (6, 6)
    assert twist_jacobian(GEOMETRY, POSES[:, :3], rotation).shape == (3, 6, 6)
    with pytest.raises(ValueError, match='twists'):
        leg_velocities(GEOMETRY, POSES[0], [math.nan] * 6)
    with pytest.raises(ValueError, match='leg velocities'):
        platform_twist(GEOMETRY, POSES[0], [0.0] * 5)


def test_twist_jacobian_of_one_pose_equals_its_batch_form():
    """The one-pose path (float arithmetic) gives the batch path's Jacobian to 1e-15."""
    rotations = euler_zyx_to_matrix(POSES[:, 3:])
    batch = twist_jacobian(GEOMETRY, POSES[:, :3], rotations)
    for pose, rotation, expected in zip(POSES, rotations, batch):
        single = twist_jacobian(GEOMETRY, pose[:3], rotation)
        assert single.shape == (6, 6)
        assert_allclose(single, expected, rtol=0.0, atol=1e-15)


def test_platform_twist_refuses_a_pose_near_the_singularity():
    # The defect: 1 mm/s on every leg became about 4300 rad/s near the paper platform's
    # singularity (yaw 90.4 degrees), without a word.
    pose = np.array(HOME[:5] + (singular_yaw() + 3e-7,))
    velocities = [1e-3] * 6
    with pytest.raises(SingularPoseError, match=r'condition number .* above the limit 1000'):
        platform_twist(GEOMETRY, pose, velocities)
    with pytest.raises(ValueError, match='the pose is too near a singularity'):
        platform_twist(GEOMETRY, pose, velocities)
    # Asked to answer anyway, it gives the huge twist the refusal protects from.
    twist = platform_twist(GEOMETRY, pose, velocities, max_condition=math.inf)
    assert np.max(np.abs(twist[3:])) > 1e3
    # In a batch, the refusal names the pose.
    with pytest.raises(SingularPoseError, match='pose 1 is too near'):
        platform_twist(GEOMETRY, [POSES[0], pose], [velocities, velocities])


def test_platform_twist_limit_defaults_to_the_geometry_singularity_margin():
    limited = paper_geometry(max_jacobian_condition=12.0)
    condition = float(jacobian_condition(GEOMETRY, POSES[2, :3],
                                         euler_zyx_to_matrix(POSES[2, 3:])))
    assert 12.0 < condition < DEFAULT_MAX_TWIST_CONDITION
    velocities = leg_velocities(GEOMETRY, POSES[2], TWISTS[2])
    assert_allclose(platform_twist(GEOMETRY, POSES[2], velocities), TWISTS[2], atol=1e-12)
    with pytest.raises(SingularPoseError, match='above the limit 12'):
        platform_twist(limited, POSES[2], velocities)
    assert_allclose(platform_twist(limited, POSES[2], velocities, max_condition=20.0), TWISTS[2],
                    atol=1e-12)
