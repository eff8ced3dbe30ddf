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
The dynamics' arguments: mass properties checked on construction, hostile poses and motions.

Every refusal is one line that names the field or argument and what is allowed, with no
numpy-internal words; singular poses are refused as such; empty batches, matrices and
broadcasting behave as the array-like rule of doc/python_api.md says.
"""

import math

import numpy as np
from properties import assert_refused, PAPER
import pytest
from reference import singular_yaw

from stewart_kinematics import (
    leg_forces,
    LegBody,
    MassProperties,
    platform_wrench,
    RigidBody,
    SingularPoseError,
)

pytestmark = pytest.mark.core

MASSES = MassProperties(platform=RigidBody(5.0, [0.0, 0.0, 0.02], [0.1, 0.1, 0.2, 0, 0, 0]),
                        payload=RigidBody(20.0, [0.0, 0.0, 0.1]),
                        leg_lower=LegBody(1.0, 0.2, 0.01), leg_upper=LegBody(0.5, 0.2, 0.005))
HOME = PAPER.home_pose


def joint_on_its_base_joint():
    """Return a level pose with a leg of length 0 exactly (its platform joint on its base's)."""
    for leg, (base, joint) in enumerate(zip(PAPER.base_joints, PAPER.platform_joints)):
        position = base - joint
        for axis in range(3):   # a few ulps off, until position + joint rounds to the base joint
            up = down = position[axis]
            candidates = [up]
            for _ in range(16):
                up, down = np.nextafter(up, math.inf), np.nextafter(down, -math.inf)
                candidates += [up, down]
            position[axis] = next((value for value in candidates
                                   if value + joint[axis] == base[axis]), math.nan)
        if np.array_equal(position + joint, base):
            return np.concatenate([position, [0.0, 0.0, 0.0]]), leg
    raise AssertionError('no leg of the paper platform reaches its base joint exactly')


@pytest.mark.parametrize('build, words', [
    (lambda: RigidBody(-1.0), ['RigidBody.mass (kg)', '[0, inf]', '-1.0']),
    (lambda: RigidBody(math.nan), ['RigidBody.mass (kg)', 'finite']),
    (lambda: RigidBody(math.inf), ['RigidBody.mass (kg)', 'finite']),
    (lambda: RigidBody(True), ['RigidBody.mass (kg)', 'a number']),
    (lambda: RigidBody('20'), ['RigidBody.mass (kg)', 'a number']),
    (lambda: RigidBody(1.0, [0.0, 0.0]), ['center_of_mass', 'list of 3 numbers']),
    (lambda: RigidBody(1.0, [0.0, 0.0, math.nan]), ['center_of_mass', 'finite']),
    (lambda: RigidBody(1.0, 'abc'), ['center_of_mass', 'list of 3 numbers']),
    (lambda: RigidBody(1.0, inertia=[1.0] * 5), ['inertia', 'list of 6 numbers']),
    (lambda: RigidBody(1.0, inertia=[-1.0, 1.0, 1.0, 0, 0, 0]),
     ['inertia', 'positive semi-definite']),
    (lambda: RigidBody(1.0, inertia=[1.0, 1.0, 1.0, 2.0, 0, 0]),
     ['inertia', 'positive semi-definite']),
    (lambda: RigidBody(1.0, inertia=[1.0, 1.0, 3.0, 0, 0, 0]), ['inertia', 'triangle']),
    (lambda: RigidBody(1.0, inertia=[1e300, 1e300, 1e300, 0, 0, 0]), ['inertia', '1e150']),
    (lambda: RigidBody(0.0, inertia=[1.0, 1.0, 1.0, 0, 0, 0]), ['mass 0', 'no inertia']),
    (lambda: RigidBody(-1.0, name='payload'), ['payload.mass (kg)']),
    (lambda: LegBody(-0.5), ['LegBody.mass (kg)', '[0, inf]']),
    (lambda: LegBody(1.0, math.inf), ['LegBody.center_of_mass (m)', 'finite']),
    (lambda: LegBody(1.0, 0.2, -0.1), ['LegBody.inertia', '[0, inf]']),
    (lambda: LegBody(0.0, 0.2, 0.1), ['mass 0', 'no inertia']),
    (lambda: LegBody(1.0, [0.2]), ['LegBody.center_of_mass (m)', 'a number']),
    (lambda: MassProperties(gravity=[0.0, -9.8]), ['gravity', 'list of 3 numbers']),
    (lambda: MassProperties(gravity=[0.0, 0.0, math.nan]), ['gravity', 'finite']),
    (lambda: MassProperties(payload=LegBody()), ['MassProperties.payload', 'RigidBody']),
    (lambda: MassProperties(leg_upper=20.0), ['MassProperties.leg_upper', 'LegBody']),
])
def test_bad_mass_properties_are_refused_naming_the_field(build, words):
    error = assert_refused(build, words[:1])
    message = str(error)
    assert '\n' not in message
    for word in words:
        assert word in message, (word, message)


def test_mass_properties_keep_their_values_as_floats_and_compare():
    payload = RigidBody(np.float32(20.0), np.array([0, 0, 1]), (1, 1, 1, 0, 0, 0))
    assert payload.mass == 20.0 and type(payload.mass) is float
    assert payload.center_of_mass == (0.0, 0.0, 1.0)
    assert MassProperties(payload=payload) == MassProperties(payload=RigidBody(
        20.0, [0.0, 0.0, 1.0], [1.0, 1.0, 1.0, 0.0, 0.0, 0.0]))
    assert MassProperties().gravity == (0.0, 0.0, -9.80665)
    assert MassProperties().massless and not MassProperties(payload=payload).massless
    # A flat disc's moments: Izz = Ixx + Iyy exactly, at the triangle inequality's edge.
    RigidBody(1.0, inertia=[0.25, 0.25, 0.5, 0.0, 0.0, 0.0])


def test_the_moving_body_combines_platform_and_payload_by_the_parallel_axis_theorem():
    masses = MassProperties(platform=RigidBody(2.0, [0.0, 0.0, 0.0], [1.0, 1.0, 1.0, 0, 0, 0]),
                            payload=RigidBody(2.0, [0.0, 0.0, 1.0], [1.0, 1.0, 1.0, 0, 0, 0]))
    mass, center, tensor = masses.moving_body
    assert mass == 4.0 and center == (0.0, 0.0, 0.5)
    # Each body 0.5 m off the common centre: 1 + 2 * 0.25 about x and y, 1 about z.
    np.testing.assert_allclose(np.reshape(tensor, (3, 3)), np.diag([3.0, 3.0, 2.0]), atol=1e-15)


def test_mass_properties_must_be_given_as_such():
    assert_refused(lambda: leg_forces(PAPER, HOME, mass_properties={'payload_mass': 20.0}),
                   ['mass_properties must be a MassProperties'])


@pytest.mark.parametrize('poses, twists, words', [
    ([0.0] * 5, None, ['poses', 'shape']),
    (np.zeros((2, 3, 6)), None, ['poses', 'shape']),
    (HOME, [0.0] * 7, ['twists', 'shape']),
    (np.tile(HOME, (3, 1)), np.zeros((2, 6)), ['same number of rows']),
    ('home', None, ['poses']),
    ([HOME, HOME[:5]], None, ['poses', 'ragged']),
    (HOME, [0.0, 0.0, math.nan, 0.0, 0.0, 0.0], ['twists', 'finite']),
    (np.where(np.arange(6) == 1, math.inf, HOME), None, ['poses', 'finite']),
    (HOME, np.full(6, 1e308), ['the leg forces', 'too large']),
    (np.tile(HOME, (2, 1)), np.full(6, 1e308), ['the leg forces', 'too large']),
    (np.where(np.arange(6) == 0, 1e308, HOME), None, ['the leg forces', 'too large']),
])
def test_hostile_poses_and_motions_are_refused_in_words(poses, twists, words):
    error = assert_refused(lambda: leg_forces(PAPER, poses, twists, mass_properties=MASSES),
                           words[:1])
    for word in words:
        assert word in str(error)


def test_a_singular_pose_is_refused_as_singular_naming_the_pose():
    singular = np.array(HOME[:5].tolist() + [singular_yaw()])
    singular_legs = leg_forces(PAPER, singular - [0, 0, 0, 0, 0, 1e-3], mass_properties=MASSES)
    assert np.abs(singular_legs).max() > 1e3   # near it, the forces grow without bound
    # A platform joint on its base joint: leg 1 of length 0, no direction.
    on_base, _ = joint_on_its_base_joint()
    for pose in (on_base, np.stack([HOME, on_base])):
        error = assert_refused(lambda: leg_forces(PAPER, pose, mass_properties=MASSES),
                               ['singular'], SingularPoseError)
        assert ('pose 1' if pose.ndim == 2 else 'the pose') in str(error)


def test_at_an_exactly_singular_jacobian_the_refusal_names_it():
    # The home position yawed to the singularity: its Jacobian is singular to rounding, so
    # LAPACK may or may not meet an exact zero; either the refusal or huge finite forces.
    singular = np.array(HOME[:5].tolist() + [singular_yaw()])
    try:
        forces = leg_forces(PAPER, singular, mass_properties=MASSES)
    except SingularPoseError as error:
        assert 'singular' in str(error)
    else:
        assert np.all(np.isfinite(forces)) and np.abs(forces).max() > 1e4


@pytest.mark.filterwarnings('ignore::PendingDeprecationWarning')   # np.matrix
def test_empty_batches_matrices_and_broadcasting():
    assert leg_forces(PAPER, np.zeros((0, 6)), mass_properties=MASSES).shape == (0, 6)
    assert leg_forces(PAPER, np.zeros((0, 6)), mass_properties=MassProperties()).shape == (0, 6)
    assert platform_wrench(PAPER, np.zeros((0, 6)), np.zeros((0, 6))).shape == (0, 6)
    single = leg_forces(PAPER, HOME, mass_properties=MASSES)
    matrix = leg_forces(PAPER, np.matrix(HOME), mass_properties=MASSES)
    assert matrix.shape == (1, 6) and type(matrix) is np.ndarray
    assert matrix[0].tobytes() == single.tobytes()
    twists = np.random.default_rng(2).uniform(-0.2, 0.2, (4, 6))
    moving = leg_forces(PAPER, HOME, twists, mass_properties=MASSES)
    assert moving.shape == (4, 6)
    assert moving[3].tobytes() == leg_forces(PAPER, HOME, twists[3],
                                             mass_properties=MASSES).tobytes()
    assert leg_forces(PAPER, HOME.tolist(), mass_properties=MASSES).tobytes() == (
        single.tobytes())


def test_platform_wrench_refuses_bad_forces_and_gives_no_direction_to_a_zero_leg():
    assert_refused(lambda: platform_wrench(PAPER, HOME, [1.0, 2.0, math.nan, 0, 0, 0]),
                   ['forces', 'finite'])
    assert_refused(lambda: platform_wrench(PAPER, np.tile(HOME, (3, 1)), np.zeros((2, 6))),
                   ['same number of rows'])
    assert_refused(lambda: platform_wrench(PAPER, HOME, np.full(6, 1e308)),
                   ['the platform wrench', 'too large'])
    on_base, leg = joint_on_its_base_joint()
    only_first = platform_wrench(PAPER, on_base, np.eye(6)[leg] * 100.0)
    assert np.array_equal(only_first, np.zeros(6))
