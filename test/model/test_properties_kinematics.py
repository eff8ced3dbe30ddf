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
Property tests of the platform model: geometry, inverse and forward kinematics, velocities.

Valid random inputs keep the documented relations (the round trip within the proven bound,
one pose against a batch, Jacobians against finite differences, velocities both ways);
hostile ones (not numbers, wrong shapes, NaN, inf, values whose results overflow, degenerate
geometries) are refused with a ValueError that names the argument, never with numpy's words
and never with a non-finite result.
"""

from dataclasses import replace
import math

from hypothesis import assume, given, strategies as st
import numpy as np
from numpy.testing import assert_allclose, assert_array_equal
from properties import (
    assert_refused,
    budget,
    covers,
    floats,
    HOME_POSE,
    HUGE,
    NON_FINITE,
    NOT_NUMBERS,
    PAPER,
    pose_batches,
    pose_distance,
    poses_near_home,
    with_bad_entry,
    wrong_shapes,
)
import pytest
from reference import BASE_JOINTS, leg_lengths as reference_lengths, PLATFORM_JOINTS
from reference import rotation_zyx, singular_yaw

from stewart_kinematics import (
    euler_zyx_to_matrix,
    forward_kinematics,
    ForwardKinematicsResult,
    Geometry,
    inverse_kinematics,
    jacobian,
    leg_lengths,
    leg_vectors,
    leg_velocities,
    platform_twist,
    PoseLimits,
    SingularPoseError,
    twist_jacobian,
)

pytestmark = pytest.mark.core


def twists():
    """Platform twists up to 0.5 m/s and 1 rad/s."""
    return st.tuples(*[floats(-0.5, 0.5)] * 3, *[floats(-1.0, 1.0)] * 3).map(np.array)


def geometries():
    """Draw valid geometries: the paper's joints moved by up to 2 cm each."""
    offsets = st.tuples(*[floats(-0.02, 0.02)] * 36).map(lambda v: np.array(v).reshape(2, 6, 3))
    return offsets.map(lambda d: Geometry(BASE_JOINTS + d[0], PLATFORM_JOINTS + d[1],
                                          home_pose=HOME_POSE))


@covers('inverse_kinematics', 'forward_kinematics', 'ForwardKinematicsResult', 'Geometry')
@budget(40)
@given(geometries(), poses_near_home())
def test_forward_kinematics_inverts_inverse_kinematics_within_its_bound(geometry, pose):
    lengths = inverse_kinematics(geometry, pose)
    assert np.all(lengths > 0.0) and np.all(np.isfinite(lengths))
    result = forward_kinematics(geometry, lengths)
    assert result.converged and result.residual <= 1e-12 and result.reason == ''
    assert pose_distance(result.pose, pose) <= result.pose_error_bound < 1e-9
    assert isinstance(result, ForwardKinematicsResult) and not result.pose.flags.writeable
    assert result == forward_kinematics(geometry, lengths) and hash(result) == hash(
        forward_kinematics(geometry, lengths))


@covers('inverse_kinematics', 'forward_kinematics', 'ForwardKinematicsResult')
@budget(25)
@given(pose_batches(max_size=6))
def test_a_batch_takes_the_steps_of_single_solves(poses):
    lengths = inverse_kinematics(PAPER, poses)
    assert lengths.shape == (len(poses), 6)
    batch = forward_kinematics(PAPER, lengths)
    assert batch.pose.shape == (len(poses), 6) and len(batch.reason) == len(poses)
    for k, pose in enumerate(poses):
        assert_array_equal(lengths[k], inverse_kinematics(PAPER, pose))
        single = forward_kinematics(PAPER, lengths[k])
        assert_array_equal(batch.pose[k], single.pose)
        assert batch.iterations[k] == single.iterations
        assert batch.residual[k] == single.residual and batch.reason[k] == single.reason
        assert batch.pose_error_bound[k] == pytest.approx(single.pose_error_bound, rel=1e-9)


@covers('leg_lengths', 'leg_vectors', 'inverse_kinematics')
@budget(40)
@given(poses_near_home(position=0.2, angle=math.radians(30.0)))
def test_lengths_and_vectors_agree_with_the_textbook(pose):
    rotation = rotation_zyx(*pose[3:])
    expected = reference_lengths(pose)
    assert_allclose(inverse_kinematics(PAPER, pose), expected, rtol=0, atol=1e-15)
    assert_allclose(leg_lengths(PAPER, pose[:3], rotation), expected, rtol=0, atol=1e-15)
    vectors = leg_vectors(PAPER, pose[:3], rotation)
    assert_allclose(vectors, pose[:3] + PLATFORM_JOINTS @ rotation.T - BASE_JOINTS,
                    rtol=0, atol=1e-15)
    assert_allclose(np.linalg.norm(vectors, axis=1), expected, rtol=0, atol=1e-15)
    batch = leg_lengths(PAPER, np.tile(pose[:3], (3, 1)), np.tile(rotation, (3, 1, 1)))
    assert_allclose(batch, np.tile(expected, (3, 1)), rtol=0, atol=1e-15)


@covers('jacobian', 'twist_jacobian')
@budget(30)
@given(poses_near_home())
def test_jacobians_agree_with_finite_differences(pose):
    step = 1e-6
    numeric = np.column_stack([
        (inverse_kinematics(PAPER, pose + step * unit) - inverse_kinematics(
            PAPER, pose - step * unit)) / (2 * step) for unit in np.eye(6)])
    assert_allclose(jacobian(PAPER, pose), numeric, rtol=0, atol=1e-8)
    rotation = euler_zyx_to_matrix(pose[3:])
    twist_rows = twist_jacobian(PAPER, pose[:3], rotation)
    assert_allclose(twist_rows[:, :3], numeric[:, :3], rtol=0, atol=1e-8)
    assert_allclose(jacobian(PAPER, np.tile(pose, (2, 1)))[1], jacobian(PAPER, pose), atol=0)
    assert_allclose(twist_jacobian(PAPER, pose[None, :3], rotation[None])[0], twist_rows,
                    rtol=0, atol=1e-15)


@covers('leg_velocities', 'platform_twist', 'SingularPoseError')
@budget(40)
@given(poses_near_home(), twists())
def test_velocities_both_ways(pose, twist):
    velocities = leg_velocities(PAPER, pose, twist)
    assert_allclose(platform_twist(PAPER, pose, velocities), twist, rtol=0, atol=1e-9)
    batch = leg_velocities(PAPER, np.tile(pose, (2, 1)), np.tile(twist, (2, 1)))
    assert_allclose(batch[0], velocities, rtol=0, atol=1e-15)
    # At the singularity the twist is not determined: refused, never a huge number.
    singular = np.array([0.0, 0.0, HOME_POSE[2], 0.0, 0.0, singular_yaw()])
    with pytest.raises(SingularPoseError, match='singular'):
        platform_twist(PAPER, singular, velocities)


@covers('inverse_kinematics', 'forward_kinematics', 'jacobian', 'leg_lengths', 'leg_vectors',
        'twist_jacobian', 'leg_velocities', 'platform_twist')
@budget(40)
@given(st.one_of(NOT_NUMBERS, wrong_shapes((6,), (1, 6), (2, 6), (3,), (3, 3))))
def test_what_is_not_an_array_of_poses_is_refused(value):
    rotation, position = np.eye(3), HOME_POSE[:3]
    calls = [
        (lambda: inverse_kinematics(PAPER, value), ('poses',)),
        (lambda: forward_kinematics(PAPER, value), ('leg lengths',)),
        (lambda: forward_kinematics(PAPER, PAPER.home_leg_lengths, value)
         if value is not None else forward_kinematics(PAPER, PAPER.home_leg_lengths, 'x'),
         ('initial_guess',)),
        (lambda: jacobian(PAPER, value), ('poses',)),
        (lambda: leg_lengths(PAPER, value, rotation), ('position',)),
        (lambda: leg_vectors(PAPER, position, value), ('rotation',)),
        (lambda: twist_jacobian(PAPER, value, rotation), ('position',)),
        (lambda: leg_velocities(PAPER, value, np.zeros(6)), ('poses',)),
        (lambda: leg_velocities(PAPER, HOME_POSE, value), ('twists',)),
        (lambda: platform_twist(PAPER, HOME_POSE, value), ('leg velocities',)),
    ]
    shape = value.shape if isinstance(value, np.ndarray) else None
    for call, names in calls:
        last = {'position': (3,), 'rotation': (3, 3)}.get(names[0])
        if shape is not None and (shape[1:] == (6,) if last is None else (
                len(shape) > len(last) and shape[-len(last):] == last)):
            continue   # a batch (maybe empty; positions and rotations of any leading shape)
        assert_refused(call, names)


@covers('inverse_kinematics', 'forward_kinematics', 'jacobian', 'leg_lengths', 'leg_vectors',
        'twist_jacobian', 'leg_velocities', 'platform_twist')
@budget(40)
@given(poses_near_home(), NON_FINITE, st.data())
def test_non_finite_values_are_refused_never_computed(pose, bad, data):
    bad_pose = data.draw(with_bad_entry(pose, bad))
    bad_position = data.draw(with_bad_entry(pose[:3], bad))
    for call, names in [(lambda: inverse_kinematics(PAPER, bad_pose), ('poses',)),
                        (lambda: jacobian(PAPER, bad_pose), ('poses',)),
                        (lambda: leg_velocities(PAPER, bad_pose, np.zeros(6)), ('poses',)),
                        (lambda: leg_velocities(PAPER, pose, bad_pose), ('twists',)),
                        (lambda: platform_twist(PAPER, pose, bad_pose), ('leg velocities',)),
                        (lambda: forward_kinematics(PAPER, PAPER.home_leg_lengths, bad_pose),
                         ('initial_guess',)),
                        (lambda: leg_lengths(PAPER, bad_position, np.eye(3)), ('position',)),
                        (lambda: twist_jacobian(PAPER, pose[:3], np.full((3, 3), bad)),
                         ('rotation',)),
                        (lambda: leg_vectors(PAPER, bad_position, np.eye(3)), ('position',))]:
        assert_refused(call, names)
    lengths = data.draw(with_bad_entry(inverse_kinematics(PAPER, pose), bad))
    assert_refused(lambda: forward_kinematics(PAPER, lengths), ('leg lengths',))
    # In a batch, the bad row alone is not solved, and says why.
    batch = forward_kinematics(PAPER, np.stack([lengths, PAPER.home_leg_lengths]))
    assert not batch.converged[0] and 'finite and positive' in batch.reason[0]
    assert batch.converged[1]


@covers('inverse_kinematics', 'leg_lengths', 'leg_vectors', 'leg_velocities', 'platform_twist',
        'forward_kinematics', 'jacobian', 'twist_jacobian')
@budget(30)
@given(poses_near_home(), HUGE, st.data())
def test_huge_values_give_a_refusal_or_a_finite_result(pose, huge, data):
    huge_pose = data.draw(with_bad_entry(pose, huge))
    huge_twist = data.draw(with_bad_entry(np.zeros(6), huge))
    for call, names in [(lambda: inverse_kinematics(PAPER, huge_pose), ('poses', 'leg lengths')),
                        (lambda: leg_lengths(PAPER, huge_pose[:3], np.eye(3)),
                         ('position', 'leg lengths')),
                        (lambda: leg_vectors(PAPER, huge_pose[:3], np.eye(3)),
                         ('position', 'leg vectors')),
                        (lambda: leg_velocities(PAPER, pose, huge_twist),
                         ('twists', 'leg velocities')),
                        (lambda: jacobian(PAPER, huge_pose), ('poses', 'Jacobian')),
                        (lambda: twist_jacobian(PAPER, huge_pose[:3], np.eye(3)),
                         ('position', 'Jacobian')),
                        (lambda: platform_twist(PAPER, pose, huge_twist),
                         ('leg velocities', 'twist'))]:
        try:
            result = call()
        except ValueError:
            assert_refused(call, names)
        else:
            assert np.all(np.isfinite(result)), result
    result = forward_kinematics(PAPER, np.full(6, abs(huge)))
    assert not result.converged and result.reason and np.all(np.isfinite(result.pose))


@covers('forward_kinematics')
@budget(20)
@given(st.sampled_from([0.0, -1.0, math.nan, math.inf, 'tight', None]),
       st.sampled_from([0, -3, 2.5, math.nan, 'ten', None]))
def test_solver_settings_out_of_range_are_refused(tolerance, max_iterations):
    lengths = PAPER.home_leg_lengths
    if tolerance is not None:
        assert_refused(lambda: forward_kinematics(PAPER, lengths, tolerance=tolerance),
                       ('tolerance',))
    if max_iterations is not None:
        assert_refused(lambda: forward_kinematics(PAPER, lengths, max_iterations=max_iterations),
                       ('max_iterations',))


@covers('Geometry')
@budget(40)
@given(st.sampled_from(['base_joints', 'platform_joints', 'home_pose']), st.data())
def test_a_geometry_with_bad_arrays_is_refused_naming_them(name, data):
    good = getattr(PAPER, name)
    bad = data.draw(st.one_of(
        NOT_NUMBERS, wrong_shapes(good.shape),
        NON_FINITE.flatmap(lambda value: with_bad_entry(np.array(good), value))))
    assert_refused(lambda: replace(PAPER, **{name: bad}), (name,))


@covers('Geometry')
@budget(30)
@given(st.integers(0, 5), st.integers(0, 5), st.sampled_from(['base_joints', 'platform_joints']))
def test_a_degenerate_geometry_is_refused(first, second, name):
    joints = np.array(getattr(PAPER, name))
    if first != second:
        third = next(k for k in range(6) if k not in (first, second))
        joints[[second, third]] = joints[first]      # three joints coincide: one is shared
        assert_refused(lambda: replace(PAPER, **{name: joints}), (name, 'coincide'))
    line = np.outer(np.arange(6.0) + first, [0.1, 0.05 * (second + 1), 0.0])
    assert_refused(lambda: replace(PAPER, **{name: line}), (name, 'collinear'))


@covers('Geometry', 'PoseLimits')
@budget(40)
@given(st.sampled_from([
    ('leg_length_min', -0.1), ('leg_length_min', math.nan), ('leg_length_max', 0.0),
    ('leg_length_max', math.nan), ('base_joint_max_angle', 0.0),
    ('base_joint_max_angle', 4.0), ('platform_joint_max_angle', -1.0),
    ('max_jacobian_condition', 0.5), ('max_jacobian_condition', math.nan),
    ('leg_length_max', 'long'), ('leg_length_min', None), ('max_jacobian_condition', [1.0]),
    ('leg_length_max', 0.5)]))
def test_limits_out_of_their_range_are_refused_naming_them(change):
    name, value = change
    assert_refused(lambda: replace(PAPER, limits=PoseLimits(**{name: value})), (name, 'home pose'))


@covers('forward_kinematics', 'ForwardKinematicsResult')
@budget(20)
@given(st.integers(0, 3), st.integers(0, 3))
def test_empty_and_broadcast_batches_are_consistent(lengths_count, guess_count):
    lengths = np.tile(PAPER.home_leg_lengths, (lengths_count, 1))
    guesses = np.tile(HOME_POSE, (guess_count, 1))
    if lengths_count == guess_count or 1 in (lengths_count, guess_count):
        result = forward_kinematics(PAPER, lengths, guesses)
        count = lengths_count if guess_count == 1 else guess_count
        assert result.pose.shape == (count, 6) and np.all(result.converged)
        assert result.condition.shape == result.pose_error_bound.shape == (count,)
    else:
        assert_refused(lambda: forward_kinematics(PAPER, lengths, guesses),
                       ('same number of poses',))
    assume(True)
