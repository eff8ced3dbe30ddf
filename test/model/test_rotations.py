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
Unit tests of stewart_kinematics.model.rotations (pure numpy).

Expected values come from elementary rotation matrices and quaternions written out here, never
from the functions under test.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import (
    axis_angle_quaternion,
    quaternion_from_euler,
    quaternion_matrix,
    rodrigues,
    rotation_angle,
    rotation_zyx,
    rx,
    ry,
    rz,
)

from stewart_kinematics.model.rotations import (
    canonical_zyx_angles,
    euler_zyx_to_matrix,
    euler_zyx_to_quaternion,
    matrix_to_euler_zyx,
    matrix_to_quaternion,
    normalize_quaternion,
    quaternion_to_euler_zyx,
    quaternion_to_matrix,
    rotation_angle_between,
)

pytestmark = pytest.mark.core

ATOL = 1e-12
SQRT_HALF = math.sqrt(0.5)


def random_angles(count, seed=0):
    """Random (alpha, beta, gamma) with beta inside (-pi/2, pi/2), shape (count, 3)."""
    rng = np.random.default_rng(seed)
    return np.column_stack([
        rng.uniform(-math.pi, math.pi, count),
        rng.uniform(-0.499 * math.pi, 0.499 * math.pi, count),
        rng.uniform(-math.pi, math.pi, count)])


def test_euler_zyx_to_matrix_equals_product_of_elementary_rotations():
    """The matrix of random angles is Rz(gamma) Ry(beta) Rx(alpha)."""
    for alpha, beta, gamma in random_angles(50):
        assert_allclose(euler_zyx_to_matrix([alpha, beta, gamma]),
                        rotation_zyx(alpha, beta, gamma),
                        rtol=0.0, atol=ATOL)


def test_euler_zyx_to_matrix_of_zero_is_identity():
    """Zero angles give the identity matrix."""
    assert_allclose(euler_zyx_to_matrix([0.0, 0.0, 0.0]), np.eye(3), rtol=0.0, atol=0.0)


@pytest.mark.parametrize('angles, expected', [
    ([math.pi / 2, 0.0, 0.0], [[1, 0, 0], [0, 0, -1], [0, 1, 0]]),
    ([0.0, math.pi / 2, 0.0], [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]),
    ([0.0, 0.0, math.pi / 2], [[0, -1, 0], [1, 0, 0], [0, 0, 1]]),
])
def test_euler_zyx_to_matrix_quarter_turns_by_hand(angles, expected):
    """A quarter turn about x, y or z gives the matrix written by hand."""
    assert_allclose(euler_zyx_to_matrix(angles), np.array(expected, dtype=float),
                    rtol=0.0, atol=ATOL)


def test_euler_zyx_to_matrix_quarter_turn_about_z_maps_x_to_y():
    """Yaw of +90 degrees turns the x axis onto the y axis (right hand rule)."""
    assert_allclose(euler_zyx_to_matrix([0.0, 0.0, math.pi / 2]) @ [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0], rtol=0.0, atol=ATOL)


def test_euler_zyx_to_matrix_batch_shape_matches_singles():
    """A (N, 3) batch gives (N, 3, 3), each equal to the single conversion."""
    angles = random_angles(7)
    batch = euler_zyx_to_matrix(angles)
    assert batch.shape == (7, 3, 3)
    for row, matrix in zip(angles, batch):
        assert_allclose(matrix, rotation_zyx(*row), rtol=0.0, atol=ATOL)


def test_euler_zyx_to_matrix_rejects_wrong_shape():
    """Angles that are not (..., 3) raise ValueError."""
    with pytest.raises(ValueError, match='shape'):
        euler_zyx_to_matrix([0.0, 0.0])


def test_matrix_to_euler_zyx_round_trip_on_random_angles():
    """Angles with beta in (-pi/2, pi/2) and alpha, gamma in (-pi, pi) come back unchanged."""
    angles = random_angles(1000, seed=1)
    matrices = np.array([rotation_zyx(*row) for row in angles])
    assert_allclose(matrix_to_euler_zyx(matrices), angles, rtol=0.0, atol=1e-9)


def test_matrix_to_euler_zyx_single_shape():
    """One matrix gives one angle triple, shape (3,)."""
    result = matrix_to_euler_zyx(rotation_zyx(0.1, -0.2, 0.3))
    assert result.shape == (3,)
    assert_allclose(result, [0.1, -0.2, 0.3], rtol=0.0, atol=ATOL)


def test_matrix_to_euler_zyx_wraps_angles_into_canonical_range():
    """Angles beyond pi are returned as the equivalent angle in (-pi, pi]."""
    result = matrix_to_euler_zyx(rotation_zyx(0.3 + 2.0 * math.pi, 0.2, -0.4 - 2.0 * math.pi))
    assert_allclose(result, [0.3, 0.2, -0.4], rtol=0.0, atol=1e-9)


@pytest.mark.parametrize('beta', [math.pi / 2, -math.pi / 2])
@pytest.mark.parametrize('alpha, gamma', [(0.3, 0.7), (-1.2, 2.5), (0.0, 0.0), (3.0, -3.0)])
def test_matrix_to_euler_zyx_at_gimbal_lock_reproduces_matrix(alpha, beta, gamma):
    """At beta = +-pi/2 the returned angles describe the input rotation exactly."""
    matrix = rotation_zyx(alpha, beta, gamma)
    result = matrix_to_euler_zyx(matrix)
    assert np.all(np.isfinite(result))
    assert_allclose(result[1], beta, rtol=0.0, atol=1e-9)
    assert_allclose(rotation_zyx(*result), matrix, rtol=0.0, atol=1e-9)


def test_matrix_to_euler_zyx_rejects_wrong_shape():
    """A matrix that is not (..., 3, 3) raises ValueError."""
    with pytest.raises(ValueError, match='shape'):
        matrix_to_euler_zyx(np.eye(4))


@pytest.mark.parametrize('quaternion, matrix', [
    ([0.0, 0.0, 0.0, 1.0], np.eye(3)),
    ([0.0, 0.0, SQRT_HALF, SQRT_HALF], rz(math.pi / 2)),
    ([SQRT_HALF, 0.0, 0.0, SQRT_HALF], rx(math.pi / 2)),
    ([0.0, SQRT_HALF, 0.0, SQRT_HALF], ry(math.pi / 2)),
    ([1.0, 0.0, 0.0, 0.0], rx(math.pi)),
    ([0.0, 1.0, 0.0, 0.0], ry(math.pi)),
    ([0.0, 0.0, 1.0, 0.0], rz(math.pi)),
])
def test_quaternion_to_matrix_known_values(quaternion, matrix):
    """Known quaternions, including half turns with w = 0, give the expected matrix."""
    assert_allclose(quaternion_to_matrix(quaternion), matrix, rtol=0.0, atol=ATOL)


def test_quaternion_to_matrix_normalises_a_non_unit_quaternion():
    """A scaled quaternion describes the same rotation as the unit one."""
    assert_allclose(quaternion_to_matrix([0.0, 0.0, 3.0, 3.0]), rz(math.pi / 2),
                    rtol=0.0, atol=ATOL)


def test_matrix_to_quaternion_quarter_turn_about_z():
    """Rz(90 deg) gives (0, 0, sin 45, cos 45)."""
    assert_allclose(matrix_to_quaternion(rz(math.pi / 2)), [0.0, 0.0, SQRT_HALF, SQRT_HALF],
                    rtol=0.0, atol=ATOL)


@pytest.mark.parametrize('matrix, axis', [
    (rx(math.pi), [1.0, 0.0, 0.0]),
    (ry(math.pi), [0.0, 1.0, 0.0]),
    (rz(math.pi), [0.0, 0.0, 1.0]),
    (rz(math.pi / 4) @ rx(math.pi) @ rz(-math.pi / 4), [SQRT_HALF, SQRT_HALF, 0.0]),
])
def test_matrix_to_quaternion_half_turns_have_zero_w(matrix, axis):
    """A half turn gives w = 0 and the rotation axis (up to sign) as vector part."""
    quaternion = matrix_to_quaternion(matrix)
    assert_allclose(quaternion[3], 0.0, rtol=0.0, atol=ATOL)
    assert_allclose(abs(np.dot(quaternion[:3], axis)), 1.0, rtol=0.0, atol=ATOL)


def test_matrix_to_quaternion_has_non_negative_w():
    """Rotations by more than pi about an axis still give w >= 0 (the -q representative)."""
    angles = np.linspace(-2.0 * math.pi + 0.1, 2.0 * math.pi - 0.1, 41)
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    for angle in angles:
        expected = axis_angle_quaternion(axis, angle)
        if expected[3] < 0.0:
            expected = -expected
        quaternion = matrix_to_quaternion(rodrigues(axis, angle))
        assert quaternion[3] >= 0.0
        assert_allclose(quaternion, expected, rtol=0.0, atol=1e-12)


def test_matrix_to_quaternion_round_trip_random_rotations():
    """Matrix -> quaternion -> matrix returns the Euler-built matrix for random angles."""
    matrices = np.array([rotation_zyx(*row) for row in random_angles(500, seed=2)])
    quaternions = matrix_to_quaternion(matrices)
    assert quaternions.shape == (500, 4)
    assert_allclose(np.linalg.norm(quaternions, axis=-1), 1.0, rtol=0.0, atol=1e-12)
    assert np.all(quaternions[:, 3] >= 0.0)
    assert_allclose(quaternion_to_matrix(quaternions), matrices, rtol=0.0, atol=1e-12)


def test_quaternion_conversions_batch_and_single_shapes():
    """(4,) -> (3, 3), (N, 4) -> (N, 3, 3), (N, 3) -> (N, 4) and (3,) -> (4,)."""
    quaternions = np.array([[0.0, 0.0, SQRT_HALF, SQRT_HALF], [0.0, 0.0, 0.0, 1.0]])
    assert quaternion_to_matrix(quaternions[0]).shape == (3, 3)
    assert quaternion_to_matrix(quaternions).shape == (2, 3, 3)
    assert matrix_to_quaternion(np.eye(3)).shape == (4,)
    assert matrix_to_quaternion(np.stack([np.eye(3)] * 5)).shape == (5, 4)
    assert euler_zyx_to_quaternion([0.1, 0.2, 0.3]).shape == (4,)
    assert euler_zyx_to_quaternion(random_angles(5)).shape == (5, 4)
    assert quaternion_to_euler_zyx(quaternions[0]).shape == (3,)
    assert quaternion_to_euler_zyx(quaternions).shape == (2, 3)


def test_euler_zyx_to_quaternion_is_product_of_axis_quaternions():
    """q(alpha, beta, gamma) equals the Hamilton product qz(gamma) * qy(beta) * qx(alpha)."""
    alpha, beta, gamma = 0.4, -0.3, 1.1
    assert_allclose(euler_zyx_to_quaternion([alpha, beta, gamma]),
                    quaternion_from_euler(alpha, beta, gamma), rtol=0.0, atol=ATOL)


def test_quaternion_to_euler_zyx_quarter_turn_about_z():
    """(0, 0, sin 45, cos 45) gives gamma = pi/2 and zero roll and pitch."""
    assert_allclose(quaternion_to_euler_zyx([0.0, 0.0, SQRT_HALF, SQRT_HALF]),
                    [0.0, 0.0, math.pi / 2], rtol=0.0, atol=ATOL)


def test_normalize_quaternion_scales_to_unit_norm():
    """A non-unit quaternion is divided by its norm."""
    assert_allclose(normalize_quaternion([0.0, 3.0, 0.0, 4.0]), [0.0, 0.6, 0.0, 0.8],
                    rtol=0.0, atol=ATOL)


def test_normalize_quaternion_batch():
    """Each quaternion of a batch is normalised on its own."""
    result = normalize_quaternion([[2.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.5]])
    assert_allclose(result, [[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]], rtol=0.0, atol=ATOL)


@pytest.mark.parametrize('quaternion', [[1e200, 1e200, 0.0, 0.0], [[1e200, 1e200, 0.0, 0.0]]],
                         ids=['one', 'batch'])
def test_normalize_quaternion_of_a_norm_that_overflows(quaternion):
    """Components of 1e200 (their squares overflow to inf) give a unit quaternion, not zero."""
    assert_allclose(np.reshape(normalize_quaternion(quaternion), 4),
                    [SQRT_HALF, SQRT_HALF, 0.0, 0.0], rtol=0.0, atol=ATOL)


@pytest.mark.parametrize('quaternion, message', [
    ([0.0, 0.0, 0.0, 0.0], 'norm'),
    ([1e-12, 0.0, 0.0, 0.0], 'norm'),
    ([[0.0, 0.0, 0.0, 1.0], [0.0, 0.0, 0.0, 0.0]], 'norm'),
    ([math.nan, 0.0, 0.0, 1.0], 'finite'),
    ([0.0, math.inf, 0.0, 1.0], 'finite'),
    ([0.0, 0.0, 1.0], 'shape'),
    ([[0.0, 0.0, 0.0, 1.0, 0.0]], 'shape'),
])
def test_normalize_quaternion_rejects_invalid_input(quaternion, message):
    """Zero, tiny, non-finite or wrongly shaped quaternions raise ValueError."""
    with pytest.raises(ValueError, match=message):
        normalize_quaternion(quaternion)


def test_quaternion_to_matrix_rejects_zero_quaternion():
    """A zero quaternion describes no rotation and raises ValueError."""
    with pytest.raises(ValueError, match='norm'):
        quaternion_to_matrix([0.0, 0.0, 0.0, 0.0])


def test_rotation_angle_between_equal_rotations_is_zero():
    """Equal rotations are 0 rad apart."""
    matrix = rotation_zyx(0.3, -0.2, 1.0)
    assert_allclose(rotation_angle_between(matrix, matrix), 0.0, rtol=0.0, atol=1e-15)


@pytest.mark.parametrize('angle', [1e-9, 1e-6, 0.5, 2.0, math.pi - 1e-6])
def test_rotation_angle_between_known_angles(angle):
    """The angle between R and R @ Rk(angle) is angle, accurate even at 1e-9 rad."""
    base = rotation_zyx(0.3, -0.2, 1.0)
    axis = np.array([2.0, -1.0, 2.0]) / 3.0
    relative = rodrigues(axis, angle)
    assert_allclose(rotation_angle_between(base, base @ relative), angle, rtol=1e-6, atol=0.0)


def test_rotation_angle_between_half_turn_is_pi():
    """A half turn is pi rad away."""
    assert_allclose(rotation_angle_between(np.eye(3), rz(math.pi)), math.pi,
                    rtol=0.0, atol=1e-12)


def test_rotation_angle_between_batch_shape():
    """Batches of (N, 3, 3) give N angles."""
    first = np.stack([np.eye(3)] * 3)
    second = np.stack([rx(0.1), ry(0.2), rz(0.3)])
    assert_allclose(rotation_angle_between(first, second), [0.1, 0.2, 0.3],
                    rtol=0.0, atol=1e-12)


def test_single_matrix_path_equals_the_batch_path():
    """One matrix (the nodes' scalar fast path) gives the batch path's quaternion."""
    rng = np.random.default_rng(7)
    angles = rng.uniform(-np.pi, np.pi, (200, 3))
    angles[:, 1] /= 2.0
    matrices = euler_zyx_to_matrix(angles)
    batch = matrix_to_quaternion(matrices)
    for matrix, expected in zip(matrices, batch):
        assert_allclose(matrix_to_quaternion(matrix), expected, rtol=0.0, atol=1e-15)


def test_single_value_paths_equal_the_batch_paths():
    """
    One value (the nodes' float-arithmetic fast paths) gives what the batch path gives.

    Covers Euler angles to matrix and to quaternion (including half turns, where w = 0 and the
    sign rule matters), quaternion to matrix, normalisation and the angle between rotations.
    """
    angles = np.concatenate([random_angles(200, seed=3), [
        [math.pi, 0.0, 0.0], [0.0, 0.0, math.pi], [0.0, math.pi / 2.0, 0.3],
        [0.2, -math.pi / 2.0, -0.4]]])
    matrices = euler_zyx_to_matrix(angles)
    quaternions = euler_zyx_to_quaternion(angles)
    scaled = quaternions * np.linspace(0.5, 3.0, len(quaternions))[:, None]
    shifted = np.roll(matrices, 1, axis=0)
    batch_angles = rotation_angle_between(matrices, shifted)
    for k, triple in enumerate(angles):
        assert_allclose(euler_zyx_to_matrix(triple), matrices[k], rtol=0.0, atol=1e-15)
        single = euler_zyx_to_quaternion(triple)
        assert single[3] >= 0.0
        # q and -q are the same rotation; only w = 0 leaves the sign to rounding.
        sign = 1.0 if abs(quaternions[k, 3]) > 1e-12 else np.sign(single @ quaternions[k])
        assert_allclose(sign * single, quaternions[k], rtol=0.0, atol=1e-15)
        assert_allclose(quaternion_to_matrix(scaled[k]), matrices[k], rtol=0.0, atol=1e-15)
        assert_allclose(normalize_quaternion(scaled[k]), quaternions[k], rtol=0.0, atol=1e-15)
        assert_allclose(rotation_angle_between(matrices[k], shifted[k]), batch_angles[k],
                        rtol=0.0, atol=1e-12)


def gimbal_band_cases():
    """Random alpha, gamma with beta within 1e-12 to 1e-6 rad of +-90 degrees, shape (N, 3)."""
    rng = np.random.default_rng(90)
    offsets = 10.0 ** rng.uniform(-12.0, -6.0, 400)
    signs = rng.choice([-1.0, 1.0], 400)
    return np.column_stack([rng.uniform(-math.pi, math.pi, 400),
                            signs * (0.5 * math.pi - offsets),
                            rng.uniform(-math.pi, math.pi, 400)])


def test_euler_angles_near_gimbal_lock_rebuild_the_rotation_to_rounding():
    # The defect: within 1e-12..1e-6 rad of beta = +-90 degrees, alpha and gamma were taken
    # each from entries of size cos(beta) that rounding had blurred; their rotation was up to
    # 7e-4 rad away from the quaternion's.
    cases = gimbal_band_cases()
    quaternions = np.array([quaternion_from_euler(*angles) for angles in cases])
    batch = quaternion_to_euler_zyx(quaternions)
    worst = 0.0
    for quaternion, angles in zip(quaternions, batch):
        single = quaternion_to_euler_zyx(quaternion)
        assert_allclose(single, angles, rtol=0.0, atol=1e-15)
        expected = quaternion_matrix(*quaternion)
        worst = max(worst, rotation_angle(rotation_zyx(*single), expected))
        assert abs(single[1]) <= math.pi / 2 and np.all(np.abs(single) <= math.pi)
    assert worst <= 1e-14


def test_euler_angles_from_matrices_near_gimbal_lock_rebuild_them():
    cases = gimbal_band_cases()
    matrices = np.array([rotation_zyx(*angles) for angles in cases])
    for matrix, angles in zip(matrices, matrix_to_euler_zyx(matrices)):
        assert rotation_angle(rotation_zyx(*angles), matrix) <= 1e-14


def test_scalar_canonical_angles_agree_with_the_batch_conversion_near_gimbal_lock():
    # The forward solver's scalar twin of matrix_to_euler_zyx(euler_zyx_to_matrix(angles)),
    # on angles out of the canonical ranges (so that they are converted).
    cases = gimbal_band_cases() + [2.0 * math.pi, 0.0, -2.0 * math.pi]
    expected = matrix_to_euler_zyx(euler_zyx_to_matrix(cases))
    for angles, batch in zip(cases, expected):
        single = canonical_zyx_angles(*angles)
        assert_allclose(single, batch, rtol=0.0, atol=1e-15)
        assert rotation_angle(rotation_zyx(*single), rotation_zyx(*angles)) <= 1e-14
