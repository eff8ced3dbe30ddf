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
Property tests of the rotation conversions: round trips, one against batch, hostile inputs.

Every conversion against the textbook product ``Rz Ry Rx`` and half-angle quaternions of
test/reference.py; one rotation and a batch give the same numbers; what is not a finite
array of the right shape, or not a rotation, is refused naming the argument.
"""

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose
from properties import (
    any_angles,
    assert_refused,
    budget,
    covers,
    floats,
    HUGE,
    NON_FINITE,
    NOT_NUMBERS,
    unit_quaternions,
    with_bad_entry,
    wrong_shapes,
)
import pytest
from reference import quaternion_from_euler, quaternion_matrix, rotation_angle, rotation_zyx

from stewart_kinematics import (
    euler_zyx_to_matrix,
    euler_zyx_to_quaternion,
    matrix_to_euler_zyx,
    matrix_to_quaternion,
    quaternion_to_euler_zyx,
    quaternion_to_matrix,
)

pytestmark = pytest.mark.core

ALL = ('euler_zyx_to_matrix', 'euler_zyx_to_quaternion', 'matrix_to_euler_zyx',
       'matrix_to_quaternion', 'quaternion_to_euler_zyx', 'quaternion_to_matrix')


@covers(*ALL)
@budget(60)
@given(any_angles())
def test_every_conversion_agrees_with_the_textbook(angles):
    matrix = rotation_zyx(*angles)
    assert_allclose(euler_zyx_to_matrix(angles), matrix, rtol=0, atol=1e-15)
    quaternion = euler_zyx_to_quaternion(angles)
    assert quaternion[3] >= 0.0
    assert_allclose(quaternion, quaternion_from_euler(*angles), rtol=0, atol=2e-15)
    assert_allclose(quaternion_to_matrix(quaternion), matrix, rtol=0, atol=2e-15)
    assert_allclose(matrix_to_quaternion(matrix), quaternion, rtol=0, atol=2e-15)
    # Angles are not unique near gimbal lock; the rotation they rebuild is.
    for back in (matrix_to_euler_zyx(matrix), quaternion_to_euler_zyx(quaternion)):
        assert -np.pi / 2 <= back[1] <= np.pi / 2
        assert -np.pi < back[0] <= np.pi and -np.pi < back[2] <= np.pi
        assert rotation_angle(rotation_zyx(*back), matrix) < 1e-14


@covers(*ALL)
@budget(30)
@given(st.lists(any_angles(), min_size=0, max_size=6))
def test_a_batch_gives_each_rotation_as_alone(rows):
    angles = np.array(rows).reshape(-1, 3)
    matrices = euler_zyx_to_matrix(angles)
    quaternions = euler_zyx_to_quaternion(angles)
    assert matrices.shape == (len(rows), 3, 3) and quaternions.shape == (len(rows), 4)
    back = matrix_to_euler_zyx(matrices)
    again = quaternion_to_euler_zyx(quaternions)
    assert back.shape == again.shape == (len(rows), 3)
    assert matrix_to_quaternion(matrices).shape == quaternion_to_matrix(quaternions).shape[:-2] + (
        4,)
    for k, row in enumerate(rows):
        assert_allclose(matrices[k], euler_zyx_to_matrix(row), rtol=0, atol=1e-15)
        assert_allclose(quaternions[k], euler_zyx_to_quaternion(row), rtol=0, atol=1e-15)
        assert_allclose(back[k], matrix_to_euler_zyx(matrices[k]), rtol=0, atol=1e-12)


@covers('quaternion_to_matrix', 'quaternion_to_euler_zyx')
@budget(40)
@given(unit_quaternions(), floats(1e-3, 1e3))
def test_a_quaternion_of_any_norm_and_sign_is_the_same_rotation(quaternion, scale):
    matrix = quaternion_matrix(*quaternion)
    for q in (quaternion * scale, -quaternion * scale):
        assert_allclose(quaternion_to_matrix(q), matrix, rtol=0, atol=1e-14)
        assert rotation_angle(rotation_zyx(*quaternion_to_euler_zyx(q)), matrix) < 1e-14


@covers(*ALL)
@budget(40)
@given(st.one_of(NOT_NUMBERS, wrong_shapes((3,), (4,), (3, 3))))
def test_what_is_not_an_array_of_the_right_shape_is_refused(value):
    names = ('Euler angles', 'rotation matri', 'quaternion')
    for function in (euler_zyx_to_matrix, euler_zyx_to_quaternion, matrix_to_euler_zyx,
                     matrix_to_quaternion, quaternion_to_matrix, quaternion_to_euler_zyx):
        shape = np.shape(value) if isinstance(value, np.ndarray) else None
        if shape is not None and shape[-1:] == ((4,) if 'quaternion_to' in function.__name__
                                                else (3,)) and len(shape) >= 1 and (
                'matrix_to' not in function.__name__):
            continue   # a batch of the right last dimension (an empty one included)
        if shape is not None and 'matrix_to' in function.__name__ and shape[-2:] == (3, 3):
            continue
        assert_refused(lambda: function(value), names)


@covers(*ALL)
@budget(40)
@given(any_angles(), st.one_of(NON_FINITE, HUGE), st.data())
def test_non_finite_and_non_rotations_are_refused(angles, bad, data):
    names = ('Euler angles', 'rotation matri', 'quaternion')
    if not np.isfinite(bad):
        bad_angles = data.draw(with_bad_entry(angles, bad))
        assert_refused(lambda: euler_zyx_to_matrix(bad_angles), names)
        assert_refused(lambda: euler_zyx_to_quaternion(bad_angles), names)
        bad_quaternion = data.draw(with_bad_entry(euler_zyx_to_quaternion(angles), bad))
        assert_refused(lambda: quaternion_to_matrix(bad_quaternion), names)
        assert_refused(lambda: quaternion_to_euler_zyx(bad_quaternion), names)
    # Any bad entry makes a matrix no rotation: refused, never angles of garbage.
    bad_matrix = data.draw(with_bad_entry(euler_zyx_to_matrix(angles), bad))
    assert_refused(lambda: matrix_to_euler_zyx(bad_matrix), names)
    assert_refused(lambda: matrix_to_quaternion(bad_matrix), names)
    reflection = euler_zyx_to_matrix(angles) @ np.diag([1.0, 1.0, -1.0])
    assert_refused(lambda: matrix_to_quaternion(reflection), names)
    assert_refused(lambda: quaternion_to_matrix([0.0, 0.0, 0.0, 0.0]), names)
