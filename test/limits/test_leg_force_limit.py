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
The leg_force limit kind: a pose is judged with its static leg forces, from the masses carried.

The forces are checked against an independent statics (J^T f = the payload's weight and its
moment, solved here with numpy); with every mass 0 the limit is not checked; a batch of poses
gets exactly the values and verdicts of each pose alone.
"""

import math
from pathlib import Path

import numpy as np
import pytest
from stewart_kinematics import load_geometry, MassProperties, RigidBody
from stewart_kinematics.limits import PoseLimits
from stewart_kinematics.limits.kinds import LIMIT_KINDS, LIMIT_NAMES
from stewart_kinematics.limits.limit_model import LimitModel
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
PAYLOAD = RigidBody(20.0, [0.01, -0.02, 0.1], [0.2, 0.2, 0.2, 0.0, 0.0, 0.0], name='payload')
GRAVITY = 9.80665
#: A tilted pose of the paper's platform (metres, radians), well inside its stroke.
POSE = np.array([0.02, -0.01, 0.44, 0.08, -0.05, 0.1])


@pytest.fixture(scope='module')
def geometry():
    """Return the paper's platform carrying a 20 kg payload on massless legs, no limits."""
    return load_geometry(CONFIG / 'paper_platform.yaml').with_mass_properties(
        MassProperties(payload=PAYLOAD))


def independent_static_forces(geometry, pose):
    """Solve J^T f = [m g, (R c) x m g] with numpy: the legs hold the payload's weight."""
    rotation = euler_zyx_to_matrix(pose[3:])
    joints = pose[:3] + geometry.platform_joints @ rotation.T
    legs = joints - geometry.base_joints
    directions = legs / np.linalg.norm(legs, axis=1)[:, None]
    arms = geometry.platform_joints @ rotation.T
    jacobian = np.hstack([directions, np.cross(arms, directions)])
    weight = np.array([0.0, 0.0, 20.0 * GRAVITY])   # what the legs push up with
    moment = np.cross(rotation @ np.array(PAYLOAD.center_of_mass), weight)
    return np.linalg.solve(jacobian.T, np.concatenate([weight, moment]))


def model_with(geometry, **limits):
    """Return the limits model of ``geometry`` with some pose limits (SI units)."""
    return LimitModel.of_geometry(geometry.__class__(
        geometry.base_joints, geometry.platform_joints, geometry.home_pose,
        limits=PoseLimits(**limits), mass_properties=geometry.mass_properties))


def test_leg_force_is_a_kind_and_its_bounds_are_pose_limits():
    assert 'leg_force' in [kind.name for kind in LIMIT_KINDS]
    assert {'leg_force_min', 'leg_force_max'} <= set(LIMIT_NAMES)


def test_static_forces_are_the_independent_statics(geometry):
    model = model_with(geometry, leg_force_max=1e6)
    values = model.check_poses(POSE[None, :]).values('leg_force_max')
    np.testing.assert_allclose(values[0], independent_static_forces(geometry, POSE),
                               rtol=1e-12, atol=1e-9)


def test_a_pose_whose_static_forces_break_leg_force_max_is_refused_naming_the_legs(geometry):
    forces = independent_static_forces(geometry, POSE)
    allowed = 45.0   # above every force at home (at most 40.5 N), below two at POSE
    model = model_with(geometry, leg_force_max=allowed)
    violations = model.check_pose(POSE[:3], euler_zyx_to_matrix(POSE[3:]))
    over = sorted(int(leg) + 1 for leg in np.flatnonzero(forces > allowed))
    assert over == [3, 4]
    assert [violation.limit for violation in violations] == ['leg_force_max'] * 2
    assert sorted(violation.leg for violation in violations) == over
    for violation in violations:
        assert violation.unit == 'N' and violation.allowed == allowed
        assert 'leg_force_max' in str(violation) and f'leg {violation.leg}' in str(violation)


def test_a_pull_beyond_leg_force_min_is_refused():
    """Gravity upward (the platform hangs): the legs pull, and leg_force_min refuses it."""
    hanging = load_geometry(CONFIG / 'paper_platform.yaml').with_mass_properties(
        MassProperties(payload=PAYLOAD, gravity=[0.0, 0.0, GRAVITY]))
    model = model_with(hanging, leg_force_min=-45.0)   # at home the legs pull at most 40.5 N
    tilted = np.array([0.05, -0.03, 0.44, 0.2, -0.15, 0.1])
    violations = model.check_pose(tilted[:3], euler_zyx_to_matrix(tilted[3:]))
    assert [(violation.limit, violation.leg) for violation in violations] == [
        ('leg_force_min', 3), ('leg_force_min', 6)]
    assert all(violation.value < -45.0 for violation in violations)


def test_with_every_mass_zero_the_limit_is_not_checked():
    massless = load_geometry(CONFIG / 'paper_platform.yaml')
    assert massless.mass_properties.massless
    model = model_with(massless, leg_force_max=1e-9, leg_force_min=-1e-9)
    assert model.check_pose(POSE[:3], euler_zyx_to_matrix(POSE[3:])) == []
    assert 'leg_force_max' not in model.pose_limit_names


def test_batch_equals_one_pose_to_the_bit(geometry):
    rng = np.random.default_rng(29)
    poses = POSE + rng.uniform(-1.0, 1.0, (200, 6)) * [0.05, 0.05, 0.03, 0.2, 0.2, 0.2]
    model = model_with(geometry, leg_force_max=45.0, leg_force_min=-5.0)
    checks = model.check_poses(poses)
    batch = checks.values('leg_force_max')
    assert checks.broken['leg_force_max'].any() and not checks.broken['leg_force_max'].all()
    for index in range(0, len(poses), 17):
        one = model.check_poses(poses[index]).values('leg_force_max')[0]
        assert one.tobytes() == batch[index].tobytes()
        alone = model.check_pose(poses[index, :3], euler_zyx_to_matrix(poses[index, 3:]))
        assert [(v.limit, v.leg) for v in alone] == [
            (v.limit, v.leg) for v in checks.violations(index)]


def test_home_pose_beyond_the_limit_is_refused_when_the_geometry_is_built(geometry):
    with pytest.raises(ValueError, match=r'home pose breaks the limits: leg 1: leg_force_max'):
        model_with(geometry, leg_force_max=1.0)


@pytest.mark.parametrize('changes, words', [
    ({'leg_force_max': 0.0}, 'leg_force_max must be'),
    ({'leg_force_max': -5.0}, 'leg_force_max must be'),
    ({'leg_force_max': math.nan}, 'leg_force_max must be'),
    ({'leg_force_min': 1.0}, 'leg_force_min must be'),
    ({'leg_force_min': math.nan}, 'leg_force_min must be'),
    ({'leg_force_min': math.inf}, 'leg_force_min must be'),
])
def test_bad_force_limits_are_refused_naming_them(changes, words):
    with pytest.raises(ValueError, match=words):
        PoseLimits(**changes)
