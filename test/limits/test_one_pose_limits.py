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
The one-pose path of the limits model against its batch path, with every limit kind on.

``check_pose`` (and the command gate's ``violations_of``) run each evaluator's one-pose path
(``violations_of_one``: the same formulas on floats); ``check_poses`` runs the evaluators on
arrays. Both must give the same violations: the same limits, legs and pairs, in the same
order, the same values (to 1e-12 relative; in practice to the bit). Every kind is set tight
enough that random poses near home break each of them.
"""

import math
from pathlib import Path

from hypothesis import example, given, strategies as st
import numpy as np
from properties import budget, covers, floats, HOME_POSE
import pytest

from stewart_kinematics import euler_zyx_to_matrix, LimitModel, load_geometry
from stewart_kinematics.limits import PoseLegs
from stewart_kinematics.limits.base import violations_in
from stewart_kinematics.limits.kinds import LIMIT_KINDS

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
#: Every limit kind, tight: each is broken somewhere within the poses drawn below.
TIGHT = {'leg_length_min': 0.68, 'leg_length_max': 0.78,
         'base_joint_max_angle': math.radians(12.0),
         'platform_joint_max_angle': math.radians(14.0), 'max_jacobian_condition': 11.0,
         'leg_radius': 0.025, 'leg_force_min': 0.0, 'leg_force_max': 60.0}
EVERY_KIND = load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_masses.yaml']
                           ).with_limits(**TIGHT)
MODEL = LimitModel(EVERY_KIND)
#: Poses near home: position offsets (m) and Euler angle offsets (rad).
OFFSETS = st.tuples(*[floats(-0.12, 0.12)] * 3, *[floats(-0.4, 0.4)] * 3).map(np.array)
#: A pose with platform joint 1 on base joint 1: leg 1 of length 0, no direction.
ZERO_LEG = np.concatenate([EVERY_KIND.base_joints[0] - EVERY_KIND.platform_joints[0],
                           [0.0, 0.0, 0.0]])


def test_every_kind_is_on_and_broken_somewhere():
    names = {bound.name for limit in MODEL.pose_limits for bound in limit.bounds}
    assert names == {name for kind in LIMIT_KINDS if kind.pose_evaluator
                     for name in (bound.name for bound in kind.bounds)}
    rng = np.random.default_rng(32)
    poses = HOME_POSE + rng.uniform(-1.0, 1.0, (400, 6)) * [0.12, 0.12, 0.12, 0.4, 0.4, 0.4]
    broken = {violation.limit for pose in poses
              for violation in MODEL.check_pose(pose[:3], euler_zyx_to_matrix(pose[3:]))}
    assert broken == names


def assert_same(one, batch):
    """Assert the same violations: limits, legs and order exactly, values to 1e-12."""
    assert [(v.limit, v.leg, v.other_leg, v.allowed, v.unit) for v in one] == \
        [(v.limit, v.leg, v.other_leg, v.allowed, v.unit) for v in batch]
    np.testing.assert_allclose([v.value for v in one], [v.value for v in batch], rtol=1e-12,
                               atol=0.0, equal_nan=True)


@covers('LimitModel')
@budget(60)
@given(OFFSETS)
@example(np.zeros(6))                                     # home: nothing broken
@example(np.array([0.0, 0.0, 0.0, 0.0, math.pi / 2, 0.0]))   # far out: every kind broken
def test_one_pose_equals_the_batch_every_kind_on(offset):
    pose = HOME_POSE + offset
    one = MODEL.check_pose(pose[:3], euler_zyx_to_matrix(pose[3:]))
    checks = MODEL.check_poses(pose[None, :])
    assert_same(one, checks.violations(0))
    assert bool(checks.allowed[0]) == (not one)


@budget(60)
@given(OFFSETS)
def test_each_evaluator_one_pose_path_equals_its_arrays(offset):
    pose = HOME_POSE + offset
    rotation = euler_zyx_to_matrix(pose[3:])
    floats_legs = PoseLegs.of_pose(EVERY_KIND, pose[:3].tolist(), rotation.ravel().tolist())
    array_legs = PoseLegs.of_matrices(EVERY_KIND, pose[None, :3], rotation[None])
    # The lazily built arrays of one pose are the arrays of the batch path, to the bit.
    np.testing.assert_array_equal(floats_legs.lengths, array_legs.lengths)
    for built, batch in zip(floats_legs.vectors + floats_legs.rotation,
                            array_legs.vectors + array_legs.rotation):
        np.testing.assert_array_equal(built, batch)
    for limit in MODEL.pose_limits:
        assert_same(limit.violations_of_one(PoseLegs.of_pose(
            EVERY_KIND, pose[:3].tolist(), rotation.ravel().tolist())),
            violations_in(limit.bounds, limit.evaluate(array_legs)))


def test_a_leg_of_zero_length_breaks_the_cones_the_margin_and_the_forces_on_both_paths():
    rotation = euler_zyx_to_matrix(ZERO_LEG[3:])
    one = MODEL.check_pose(ZERO_LEG[:3], rotation)
    assert_same(one, MODEL.check_poses(ZERO_LEG[None, :]).violations(0))
    by_limit = {(v.limit, v.leg): v.value for v in one}
    assert math.isnan(by_limit[('base_joint_max_angle', 1)])
    assert math.isnan(by_limit[('platform_joint_max_angle', 1)])
    assert by_limit[('max_jacobian_condition', None)] == math.inf
    assert all(math.isnan(by_limit[('leg_force_max', leg)]) for leg in range(1, 7))
    assert by_limit[('leg_length_min', 1)] == 0.0


def test_a_known_condition_is_used_as_given():
    pose = HOME_POSE
    rotation = euler_zyx_to_matrix(pose[3:])
    assert [v.limit for v in MODEL.check_pose(pose[:3], rotation, condition=12.5)] == [
        'max_jacobian_condition']
    assert MODEL.check_pose(pose[:3], rotation, condition=10.0) == []
    (violation,) = MODEL.check_pose(pose[:3], rotation, condition=math.nan)
    assert violation.limit == 'max_jacobian_condition' and math.isnan(violation.value)
