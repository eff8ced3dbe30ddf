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
The external wrench from measured leg forces: the load the model does not know.

Zero for the model's own forces, an unmodelled payload's weight and moment for the forces of a
model with that payload, refusals for hostile forces.

The expected wrench of a payload is written here from its mass, centre and gravity alone
(``m R^T g`` and ``c x m R^T g``, platform frame), not from the package's wrench functions.
"""

import math

from hypothesis import given, strategies as st
import numpy as np
from properties import (
    assert_refused,
    budget,
    covers,
    floats,
    HUGE,
    NON_FINITE,
    NOT_NUMBERS,
    PAPER,
    pose_batches,
    poses_near_home,
)
import pytest
from reference import HOME, singular_yaw

from stewart_kinematics import external_wrench, leg_forces, LegBody, MassProperties, RigidBody
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

pytestmark = pytest.mark.core

GRAVITY = np.array([0.0, 0.0, -9.80665])
#: The model: a platform, its payload and legs with masses.
MODEL = MassProperties(
    platform=RigidBody(5.0, [0.0, 0.01, -0.02], [0.08, 0.09, 0.15, 0.001, 0.0, 0.002],
                       name='platform'),
    payload=RigidBody(3.0, [0.02, -0.01, 0.05], [0.02, 0.02, 0.03, 0.0, 0.0, 0.0],
                      name='payload'),
    leg_lower=LegBody(1.5, 0.2, 0.01, name='leg_lower'),
    leg_upper=LegBody(0.8, 0.15, 0.005, name='leg_upper'),
    gravity=GRAVITY)
GEOMETRY = PAPER.with_mass_properties(MODEL)
CENTERS = st.tuples(*[floats(-0.2, 0.2)] * 3).map(np.array)


def expected_payload_wrench(pose, mass, center):
    """Return the wrench of a payload's weight on the platform: platform frame, its origin."""
    weight = mass * euler_zyx_to_matrix(pose[3:]).T @ GRAVITY
    return np.concatenate([weight, np.cross(center, weight)])


def tensor(entries):
    """Return the inertia tensor of ``[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]``."""
    xx, yy, zz, xy, xz, yz = entries
    return np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])


def with_extra_payload(mass, center):
    """Return the model's masses plus a point mass at ``center``, joined to the platform."""
    platform = MODEL.platform
    total = platform.mass + mass
    combined = (platform.mass * np.asarray(platform.center_of_mass) + mass * center) / total
    # A point mass adds no inertia about its own centre; the parallel axis theorem of the two
    # about their common centre, entries as URDF writes them.
    inertia = np.zeros((3, 3))
    for body_mass, body_center, body_inertia in (
            (platform.mass, np.asarray(platform.center_of_mass), tensor(platform.inertia)),
            (mass, center, np.zeros((3, 3)))):
        offset = body_center - combined
        inertia += body_inertia + body_mass * (offset @ offset * np.eye(3)
                                               - np.outer(offset, offset))
    entries = [inertia[0, 0], inertia[1, 1], inertia[2, 2], inertia[0, 1], inertia[0, 2],
               inertia[1, 2]]
    return MassProperties(platform=RigidBody(total, combined, entries, name='platform'),
                          payload=MODEL.payload, leg_lower=MODEL.leg_lower,
                          leg_upper=MODEL.leg_upper, gravity=GRAVITY)


@covers('external_wrench')
@budget(60)
@given(poses_near_home())
def test_the_models_own_forces_give_no_wrench(pose):
    forces = leg_forces(GEOMETRY, pose)
    wrench = external_wrench(GEOMETRY, pose, forces)
    np.testing.assert_allclose(wrench, np.zeros(6), rtol=0.0, atol=1e-9 * np.abs(forces).max())


@covers('external_wrench')
@budget(80)
@given(poses_near_home(), floats(0.5, 50.0), CENTERS)
def test_an_unmodelled_payload_shows_as_its_weight_and_moment(pose, mass, center):
    measured = leg_forces(GEOMETRY, pose, mass_properties=with_extra_payload(mass, center))
    expected = expected_payload_wrench(pose, mass, center)
    wrench = external_wrench(GEOMETRY, pose, measured)
    scale = np.abs(expected).max()
    np.testing.assert_allclose(wrench, expected, rtol=0.0, atol=1e-9 * scale)


def test_a_moving_platform_with_its_twist_and_acceleration_gives_the_payload_alone():
    pose = np.array([0.02, -0.01, 0.45, 0.05, -0.04, 0.1])
    twist = np.array([0.1, -0.05, 0.02, 0.3, -0.2, 0.4])
    acceleration = np.array([0.5, 1.0, -0.3, 2.0, -1.0, 0.5])
    # A point mass at the origin moves with the platform's origin: its inertial force is
    # m * dv/dt, and with gravity the wrench it applies is m (g - dv/dt), no moment.
    mass = 4.0
    measured = leg_forces(GEOMETRY, pose, twist, acceleration,
                          mass_properties=with_extra_payload(mass, np.zeros(3)))
    rotation = euler_zyx_to_matrix(pose[3:])
    expected = np.concatenate([mass * rotation.T @ (GRAVITY - acceleration[:3]), np.zeros(3)])
    wrench = external_wrench(GEOMETRY, pose, measured, twist, acceleration)
    np.testing.assert_allclose(wrench, expected, rtol=0.0, atol=1e-9 * np.abs(expected).max())


def test_the_worked_example_payload_at_home():
    pose = PAPER.home_pose
    payload = MassProperties(payload=RigidBody(20.0, [0.0, 0.0, 0.1], name='payload'))
    measured = leg_forces(PAPER, pose, mass_properties=payload)
    np.testing.assert_allclose(external_wrench(PAPER, pose, measured),
                               [0.0, 0.0, -20.0 * 9.80665, 0.0, 0.0, 0.0], rtol=0.0, atol=1e-9)


@covers('external_wrench')
@budget(30)
@given(pose_batches(max_size=6))
def test_a_batch_gives_each_pose_its_own_wrench(poses):
    measured = leg_forces(GEOMETRY, poses) + 10.0
    batch = external_wrench(GEOMETRY, poses, measured)
    assert batch.shape == poses.shape
    for pose, forces, wrench in zip(poses, measured, batch):
        np.testing.assert_allclose(external_wrench(GEOMETRY, pose, forces), wrench,
                                   rtol=1e-12, atol=1e-9)


@covers('external_wrench')
@budget(40)
@given(st.integers(0, 5), st.one_of(NON_FINITE, HUGE))
def test_non_finite_or_huge_forces_are_refused_or_finite(leg, bad):
    forces = leg_forces(GEOMETRY, GEOMETRY.home_pose)
    forces[leg] = bad
    if math.isfinite(bad):
        try:
            wrench = external_wrench(GEOMETRY, GEOMETRY.home_pose, forces)
        except ValueError as error:
            assert 'too large' in str(error), error
        else:
            assert np.all(np.isfinite(wrench))
    else:
        assert_refused(lambda: external_wrench(GEOMETRY, GEOMETRY.home_pose, forces),
                       ['measured_forces must be finite'])


def test_forces_that_overflow_are_refused_as_too_large():
    forces = np.full(6, 1.7e308)
    forces[1] = -1.7e308
    assert_refused(lambda: external_wrench(GEOMETRY, GEOMETRY.home_pose, forces), ['too large'])


@pytest.mark.parametrize('forces', [[], [1.0] * 5, [1.0] * 7, 'abc', None, np.zeros((2, 3)),
                                    np.zeros((2, 6, 1))])
def test_wrong_shapes_are_refused_naming_the_forces(forces):
    assert_refused(lambda: external_wrench(GEOMETRY, GEOMETRY.home_pose, forces),
                   ['measured_forces', 'rows', 'empty'])


def test_an_empty_batch_gives_no_wrench():
    assert external_wrench(GEOMETRY, GEOMETRY.home_pose, np.zeros((0, 6))).shape == (0, 6)
    assert external_wrench(GEOMETRY, np.zeros((0, 6)), np.zeros(6)).shape == (0, 6)


def test_rows_that_do_not_match_the_poses_are_refused():
    poses = np.tile(GEOMETRY.home_pose, (2, 1))
    assert_refused(lambda: external_wrench(GEOMETRY, poses, np.zeros((3, 6))), ['rows'])


@covers('external_wrench')
@budget(20)
@given(NOT_NUMBERS)
def test_things_that_are_not_numbers_are_refused(value):
    assert_refused(lambda: external_wrench(GEOMETRY, GEOMETRY.home_pose, value),
                   ['measured_forces'])


def test_at_a_singular_pose_the_refusal_names_it():
    # At the yaw singularity, rounding decides: the refusal, or huge but finite numbers.
    singular = np.array(list(HOME[:5]) + [singular_yaw()])
    try:
        wrench = external_wrench(GEOMETRY, singular, np.ones(6))
    except ValueError as error:
        assert 'singular' in str(error)
    else:
        assert np.all(np.isfinite(wrench))
