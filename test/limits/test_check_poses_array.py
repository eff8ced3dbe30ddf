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
Tests of limits.check_poses_array: the vectorised limit checks equal check_pose, pose by pose.

Thousands of random poses around the home pose, many of them refused for one or several
reasons, go through both paths; the limits broken, the legs and the values must agree.
"""

import dataclasses
import math

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import limits, load_geometry
from stewart_kinematics.model.inverse import inverse_kinematics
from stewart_kinematics.model.jacobians import jacobian_condition
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

pytestmark = pytest.mark.core

#: Random poses: this far from the home pose on each axis (metres, radians).
SPREAD = np.array([0.2, 0.2, 0.15, 0.7, 0.7, 1.2])


@pytest.fixture
def limited(config_directory):
    """Return the paper's platform under the example limits (stroke, cones, singularity margin)."""
    return load_geometry([config_directory / 'paper_platform.yaml',
                          config_directory / 'example_limits.yaml'])


def tilted_geometry(limited):
    """Return the same platform with a rotated home pose and a tight singularity margin."""
    return dataclasses.replace(limited, home_pose=[0.01, -0.02, 0.45, 0.05, -0.04, 0.1],
                               limits=limited.limits.replace(max_jacobian_condition=14.0))


def random_poses(geometry, count, seed):
    """Return poses spread uniformly around the home pose."""
    rng = np.random.default_rng(seed)
    return geometry.home_pose + rng.uniform(-1.0, 1.0, (count, 6)) * SPREAD


def assert_same_as_check_pose(geometry, poses):
    """Assert that check_poses_array gives check_pose's violations for every pose."""
    checks = limits.check_poses_array(geometry, poses)
    # No masses here, so no force limit (test_leg_force_limit.py compares its batch).
    refused_by_reason = dict.fromkeys(
        (name for name in limits.LIMIT_NAMES if not name.startswith('leg_force_')), 0)
    for index, pose in enumerate(poses):
        expected = limits.check_pose(geometry, pose[:3], euler_zyx_to_matrix(pose[3:]))
        got = checks.violations(index)
        assert [(v.limit, v.leg, v.unit) for v in got] == \
            [(v.limit, v.leg, v.unit) for v in expected], index
        assert_allclose([v.value for v in got], [v.value for v in expected], rtol=1e-12)
        assert_allclose([v.allowed for v in got], [v.allowed for v in expected], rtol=1e-15)
        assert checks.allowed[index] == (expected == [])
        assert checks.broken_limits(index) == sorted({v.limit for v in expected},
                                                     key=limits.LIMIT_NAMES.index)
        for name in {v.limit for v in expected}:
            refused_by_reason[name] += 1
    return refused_by_reason


def test_equal_to_check_pose_on_random_poses(limited):
    poses = random_poses(limited, 4000, seed=11)
    refused = assert_same_as_check_pose(limited, poses)
    # The sample really exercises every limit, so that the comparison means something.
    assert all(count >= 20 for count in refused.values()), refused


def test_equal_to_check_pose_with_a_rotated_home_pose(limited):
    geometry = tilted_geometry(limited)
    refused = assert_same_as_check_pose(geometry, random_poses(geometry, 2000, seed=12))
    assert all(count >= 20 for count in refused.values()), refused


def test_values_are_the_core_quantities(limited):
    geometry = tilted_geometry(limited)
    poses = random_poses(geometry, 500, seed=13)
    rotations = euler_zyx_to_matrix(poses[:, 3:])
    checks = limits.check_poses_array(geometry, poses)
    assert_allclose(checks.lengths, inverse_kinematics(geometry, poses), rtol=1e-14)
    base_angles, platform_angles = limits.joint_angles(geometry, poses[:, :3], rotations)
    assert_allclose(checks.base_angles, base_angles, atol=1e-13)
    assert_allclose(checks.platform_angles, platform_angles, atol=1e-13)
    assert_allclose(checks.condition,
                    jacobian_condition(geometry, poses[:, :3], rotations), rtol=1e-12)


def test_excess_is_the_signed_distance_beyond_each_limit(limited):
    poses = random_poses(limited, 1000, seed=14)
    checks = limits.check_poses_array(limited, poses)
    assert_allclose(checks.excess('leg_length_min'), 0.65 - checks.lengths, rtol=1e-15)
    assert_allclose(checks.excess('leg_length_max'), checks.lengths - 0.90, rtol=1e-15)
    assert_allclose(checks.excess('base_joint_max_angle'),
                    checks.base_angles - math.radians(30.0), rtol=1e-15)
    assert_allclose(checks.excess('max_jacobian_condition'), checks.condition - 50.0)
    for name, mask in checks.broken.items():
        np.testing.assert_array_equal(mask, checks.excess(name) > 0.0)


def test_condition_only_where_the_other_limits_are_kept(limited):
    geometry = tilted_geometry(limited)
    poses = random_poses(geometry, 2000, seed=18)
    full = limits.check_poses_array(geometry, poses)
    partial = limits.check_poses_array(geometry, poses, condition_of_refused=False)
    np.testing.assert_array_equal(partial.allowed, full.allowed)
    others_kept = ~np.any([np.any(full.broken[name], axis=-1)
                           for name in limits.LIMIT_NAMES[:4]], axis=0)
    np.testing.assert_array_equal(np.isnan(partial.condition), ~others_kept)
    assert_allclose(partial.condition[others_kept], full.condition[others_kept], rtol=1e-15)
    assert np.any(partial.broken['max_jacobian_condition'])


def test_only_the_limits_set_are_checked(limited):
    stroke_only = limited.with_limits(
        base_joint_max_angle=math.pi, platform_joint_max_angle=math.pi,
        max_jacobian_condition=math.inf, leg_radius=0.0)
    checks = limits.check_poses_array(stroke_only, random_poses(stroke_only, 100, seed=15))
    assert list(checks.broken) == ['leg_length_min', 'leg_length_max']
    assert checks.base_angles is None and checks.condition is None
    with pytest.raises(KeyError, match='base_joint_max_angle is not set'):
        checks.excess('base_joint_max_angle')
    unlimited = stroke_only.with_limits(leg_length_min=0.0, leg_length_max=math.inf)
    checks = limits.check_poses_array(unlimited, random_poses(unlimited, 10, seed=16))
    assert checks.broken == {} and checks.allowed.all()


def test_one_pose_and_bad_input(limited):
    checks = limits.check_poses_array(limited, limited.home_pose)
    assert len(checks) == 1 and checks.allowed[0] and checks.violations(0) == []
    with pytest.raises(ValueError, match='finite'):
        limits.check_poses_array(limited, [[0.0, 0.0, math.nan, 0.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match='shape'):
        limits.check_poses_array(limited, np.zeros((3, 5)))


def test_check_poses_lists_check_pose_violations(limited):
    poses = random_poses(limited, 300, seed=17)
    expected = [limits.check_pose(limited, pose[:3], euler_zyx_to_matrix(pose[3:]))
                for pose in poses]
    assert limits.check_poses(limited, poses) == expected
