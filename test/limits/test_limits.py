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
Unit tests of stewart_kinematics.limits (pure numpy).

Expected angles, lengths and condition numbers are computed here independently: leg vectors
``t + R p_i - b_i`` written out per leg, cone angles with ``math.acos`` of dot products, and
the condition number with ``numpy.linalg.cond`` of the matrix built row by row from the
documented formula ``[u_i, (R p_i x u_i) / rho]``.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import BASE_JOINTS, HOME, PLATFORM_JOINTS, rotation_zyx, TABLE_3_END

from stewart_kinematics import limits
from stewart_kinematics.limits import PoseLimits, Violation
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.model.inverse import leg_lengths
from stewart_kinematics.model.jacobians import jacobian_condition

pytestmark = pytest.mark.core

BASE, PLATFORM = BASE_JOINTS, PLATFORM_JOINTS
HOME = np.array(HOME)
TABLE3_END = np.array(TABLE_3_END)


def paper_geometry(home_pose=HOME, **limit_values):
    """Build the paper's platform with the given home pose and limits (radians for cones)."""
    return Geometry(base_joints=BASE, platform_joints=PLATFORM, home_pose=home_pose,
                    limits=PoseLimits(**limit_values))


def legs_by_hand(base, platform, position, rotation):
    """Return the six leg vectors t + R p_i - b_i, one by one."""
    return [np.asarray(position) + rotation @ p - b for b, p in zip(base, platform)]


def unit(vector):
    """Return a vector divided by its length."""
    return vector / math.sqrt(float(vector @ vector))


def angle(a, b):
    """Return the angle between two unit vectors, radians, by math.acos of their dot product."""
    return math.acos(max(-1.0, min(1.0, float(a @ b))))


def cone_angles_by_hand(home_pose, position, rotation, base=BASE, platform=PLATFORM):
    """
    Return the base-side and platform-side cone angles of every leg, radians.

    Base side: angle between the leg's direction now and at home, in the base frame.
    Platform side: the same with both directions taken into the platform frame
    (``R^T u`` now, ``R_home^T u_home`` at home).
    """
    home_rotation = rotation_zyx(*home_pose[3:])
    home_legs = legs_by_hand(base, platform, home_pose[:3], home_rotation)
    legs = legs_by_hand(base, platform, position, rotation)
    base_side, platform_side = [], []
    for leg, home_leg in zip(legs, home_legs):
        u, u_home = unit(leg), unit(home_leg)
        base_side.append(angle(u, u_home))
        platform_side.append(angle(rotation.T @ u, home_rotation.T @ u_home))
    return np.array(base_side), np.array(platform_side)


def condition_by_hand(position, rotation, base=BASE, platform=PLATFORM):
    """Return numpy.linalg.cond of the rows [u_i, (R p_i x u_i) / rho], rho the RMS radius."""
    centroid = sum(platform) / 6.0
    rho = math.sqrt(sum(float((p - centroid) @ (p - centroid)) for p in platform) / 6.0)
    rows = []
    for b, p in zip(base, platform):
        u = unit(np.asarray(position) + rotation @ p - b)
        rows.append(np.concatenate([u, np.cross(rotation @ p, u) / rho]))
    return float(np.linalg.cond(np.array(rows)))


def condition_about_z(geometry, gammas_deg):
    """Return the condition numbers at the home position rotated by each gamma about z."""
    gammas = np.radians(np.asarray(gammas_deg, dtype=float))
    rotations = np.array([rotation_zyx(0.0, 0.0, gamma) for gamma in gammas])
    positions = np.broadcast_to(geometry.home_pose[:3], (len(gammas), 3))
    return jacobian_condition(geometry, positions, rotations)


# leg_length_violations ------------------------------------------------------------------------

def test_leg_length_violations_names_leg_limit_value_and_excess():
    """Each leg outside [min, max] is reported with its number, limit, value and excess."""
    geometry = paper_geometry(leg_length_min=0.65, leg_length_max=0.90)
    violations = limits.leg_length_violations(geometry, [0.60, 0.70, 0.95, 0.90, 0.65, 0.91])
    assert [(v.limit, v.leg) for v in violations] == [
        ('leg_length_min', 1), ('leg_length_max', 3), ('leg_length_max', 6)]
    assert [v.unit for v in violations] == ['m', 'm', 'm']
    assert_allclose([v.value for v in violations], [0.60, 0.95, 0.91], rtol=0.0, atol=0.0)
    assert_allclose([v.allowed for v in violations], [0.65, 0.90, 0.90], rtol=0.0, atol=0.0)
    assert_allclose([v.excess for v in violations], [0.05, 0.05, 0.01], rtol=0.0, atol=1e-15)


def test_leg_lengths_on_the_limits_and_without_limits_are_allowed():
    """Lengths equal to a limit are allowed; a geometry without limits allows any length."""
    geometry = paper_geometry(leg_length_min=0.65, leg_length_max=0.90)
    assert limits.leg_length_violations(geometry, [0.65, 0.90, 0.70, 0.80, 0.65, 0.90]) == []
    assert limits.leg_length_violations(paper_geometry(), [1e-9, 1e9, 1.0, 1.0, 1.0, 1.0]) == []


# joint_angles ---------------------------------------------------------------------------------

def test_joint_angles_are_zero_at_home():
    """At the home pose every leg points along its home direction: all cone angles are 0."""
    for home in (HOME, np.array([0.01, -0.02, 0.45, math.radians(5.0), math.radians(-3.0),
                                 math.radians(10.0)])):
        geometry = paper_geometry(home_pose=home)
        base_angles, platform_angles = limits.joint_angles(
            geometry, home[:3], rotation_zyx(*home[3:]))
        assert_allclose(base_angles, np.zeros(6), rtol=0.0, atol=1e-7)
        assert_allclose(platform_angles, np.zeros(6), rtol=0.0, atol=1e-7)


@pytest.mark.parametrize('d', [0.01, 0.05, -0.12])
def test_joint_angles_of_a_translation_along_x(d):
    """Moving by d along x tilts each leg by acos(u_new . u_home), the same at both joints."""
    geometry = paper_geometry()
    position = HOME[:3] + np.array([d, 0.0, 0.0])
    base_angles, platform_angles = limits.joint_angles(geometry, position, np.eye(3))
    expected = []
    for b, p in zip(BASE, PLATFORM):
        u_home = unit(HOME[:3] + p - b)
        u_new = unit(position + p - b)
        expected.append(math.acos(float(u_new @ u_home)))
    assert min(expected) > 0.0
    assert_allclose(base_angles, expected, rtol=0.0, atol=1e-7)
    # Without rotation the platform frame is the base frame: the same angles.
    assert_allclose(platform_angles, expected, rtol=0.0, atol=1e-7)


def test_joint_angles_of_a_rotation_about_z():
    """A yaw differs at the two joints: the platform side is measured in the platform frame."""
    geometry = paper_geometry()
    rotation = rotation_zyx(0.0, 0.0, math.radians(25.0))
    base_angles, platform_angles = limits.joint_angles(geometry, HOME[:3], rotation)
    expected_base, expected_platform = cone_angles_by_hand(HOME, HOME[:3], rotation)
    assert_allclose(base_angles, expected_base, rtol=0.0, atol=1e-7)
    assert_allclose(platform_angles, expected_platform, rtol=0.0, atol=1e-7)
    assert np.all(np.abs(platform_angles - base_angles) > math.radians(1.0))


def test_joint_angles_from_a_rotated_home_and_in_a_batch():
    """With a rotated home pose, general poses match the hand computation, one or batched."""
    home = np.array([0.0, 0.0, 0.45, math.radians(4.0), math.radians(-6.0), math.radians(15.0)])
    geometry = paper_geometry(home_pose=home)
    poses = [TABLE3_END, np.array([0.03, -0.02, 0.47, 0.1, 0.05, -0.3]), home]
    positions = np.array([pose[:3] for pose in poses])
    rotations = np.array([rotation_zyx(*pose[3:]) for pose in poses])
    base_batch, platform_batch = limits.joint_angles(geometry, positions, rotations)
    assert base_batch.shape == platform_batch.shape == (3, 6)
    for index, pose in enumerate(poses):
        expected_base, expected_platform = cone_angles_by_hand(home, pose[:3], rotations[index])
        base_angles, platform_angles = limits.joint_angles(geometry, pose[:3], rotations[index])
        assert_allclose(base_angles, expected_base, rtol=0.0, atol=1e-7)
        assert_allclose(platform_angles, expected_platform, rtol=0.0, atol=1e-7)
        assert_allclose(base_batch[index], expected_base, rtol=0.0, atol=1e-7)
        assert_allclose(platform_batch[index], expected_platform, rtol=0.0, atol=1e-7)


# jacobian_condition ---------------------------------------------------------------------------

def test_jacobian_condition_at_home_of_the_paper_platform():
    """The paper platform's home condition number is about 9.5, as the README says."""
    geometry = paper_geometry()
    condition = float(jacobian_condition(geometry, HOME[:3], np.eye(3)))
    assert condition == pytest.approx(condition_by_hand(HOME[:3], np.eye(3)), rel=1e-9)
    assert condition == pytest.approx(9.54, abs=0.01)


def test_jacobian_condition_matches_the_documented_formula():
    """Single and batched poses give numpy.linalg.cond of [u_i, (R p_i x u_i)/rho], >= 1."""
    geometry = paper_geometry()
    rng = np.random.default_rng(7)
    poses = HOME + rng.uniform(-1.0, 1.0, (20, 6)) * [0.05, 0.05, 0.05, 0.3, 0.3, 0.6]
    poses = np.vstack([poses, TABLE3_END])
    rotations = np.array([rotation_zyx(*pose[3:]) for pose in poses])
    batch = jacobian_condition(geometry, poses[:, :3], rotations)
    assert batch.shape == (len(poses),)
    for pose, rotation, condition in zip(poses, rotations, batch):
        expected = condition_by_hand(pose[:3], rotation)
        assert condition == pytest.approx(expected, rel=1e-9)
        assert float(jacobian_condition(geometry, pose[:3], rotation)) == (
            pytest.approx(expected, rel=1e-9))
        assert condition >= 1.0


def test_jacobian_condition_is_invariant_to_scale_and_to_a_turn_about_z():
    """Moments over rho make it unit-free; turning the whole machine about z changes nothing."""
    geometry = paper_geometry()
    rotation = rotation_zyx(*TABLE3_END[3:])
    reference = float(jacobian_condition(geometry, TABLE3_END[:3], rotation))

    scale = 3.7
    scaled = Geometry(base_joints=scale * BASE, platform_joints=scale * PLATFORM,
                      home_pose=np.concatenate([scale * HOME[:3], HOME[3:]]))
    assert float(jacobian_condition(scaled, scale * TABLE3_END[:3], rotation)) == (
        pytest.approx(reference, rel=1e-9))

    turn = rotation_zyx(0.0, 0.0, math.radians(40.0))
    turned = Geometry(base_joints=BASE @ turn.T, platform_joints=PLATFORM,
                      home_pose=np.concatenate([turn @ HOME[:3], [0.0, 0.0, math.radians(40.0)]]))
    assert float(jacobian_condition(turned, turn @ TABLE3_END[:3], turn @ rotation)) == (
        pytest.approx(reference, rel=1e-9))


def test_jacobian_condition_grows_without_bound_towards_a_singularity():
    """Yawing the paper platform towards its singularity near 90 deg, the condition explodes."""
    geometry = paper_geometry()
    fine = np.linspace(80.0, 100.0, 200001)
    peak = float(fine[np.argmax(condition_about_z(geometry, fine))])
    assert 85.0 < peak < 95.0
    approach = np.linspace(60.0, peak, 400)
    rising = condition_about_z(geometry, approach)
    assert np.all(np.diff(rising) > 0.0), 'the condition does not grow towards the singularity'
    assert rising[0] < 15.0
    assert float(condition_about_z(geometry, [peak - 0.05])[0]) > 1000.0
    at_peak = float(condition_about_z(geometry, [peak])[0])
    assert at_peak > 1e5
    assert at_peak == pytest.approx(
        condition_by_hand(HOME[:3], rotation_zyx(0.0, 0.0, math.radians(peak))), rel=1e-6)
    # Past the singularity the platform moves away from it again.
    falling = condition_about_z(geometry, np.linspace(peak, 120.0, 200))
    assert np.all(np.diff(falling) < 0.0)


# check_pose and check_poses -------------------------------------------------------------------

def example_geometry():
    """Return the paper platform with the limits of config/example_limits.yaml."""
    return paper_geometry(leg_length_min=0.65, leg_length_max=0.90,
                          base_joint_max_angle=math.radians(30.0),
                          platform_joint_max_angle=math.radians(35.0),
                          max_jacobian_condition=50.0)


def tight_geometry():
    """Return the paper platform with limits that the end of the Table 3 ramp breaks."""
    return paper_geometry(leg_length_min=0.65, leg_length_max=0.80,
                          base_joint_max_angle=math.radians(9.0),
                          platform_joint_max_angle=math.radians(30.0),
                          max_jacobian_condition=15.0)


def test_check_pose_returns_every_violation_at_once():
    """Leg max on several legs, both joint cones and the condition limit, all in one list."""
    geometry = tight_geometry()
    rotation = rotation_zyx(*TABLE3_END[3:])
    violations = limits.check_pose(geometry, TABLE3_END[:3], rotation)

    lengths = [math.sqrt(float(leg @ leg))
               for leg in legs_by_hand(BASE, PLATFORM, TABLE3_END[:3], rotation)]
    base_angles, platform_angles = cone_angles_by_hand(HOME, TABLE3_END[:3], rotation)
    condition = condition_by_hand(TABLE3_END[:3], rotation)
    expected = {('leg_length_max', leg): (length, 0.80, 'm')
                for leg, length in enumerate(lengths, start=1) if length > 0.80}
    expected.update({('base_joint_max_angle', leg): (math.degrees(a), 9.0, 'deg')
                     for leg, a in enumerate(base_angles, start=1) if a > math.radians(9.0)})
    expected.update({('platform_joint_max_angle', leg): (math.degrees(a), 30.0, 'deg')
                     for leg, a in enumerate(platform_angles, start=1)
                     if a > math.radians(30.0)})
    assert condition > 15.0
    expected[('max_jacobian_condition', None)] = (condition, 15.0, '')
    # The pose was chosen to break several legs of each kind.
    assert sum(1 for limit, _ in expected if limit == 'leg_length_max') >= 3
    assert sum(1 for limit, _ in expected if limit == 'base_joint_max_angle') >= 2
    assert sum(1 for limit, _ in expected if limit == 'platform_joint_max_angle') >= 2

    found = {(v.limit, v.leg): v for v in violations}
    assert len(found) == len(violations), 'a violation is listed twice'
    assert set(found) == set(expected)
    for key, (value, allowed, unit_name) in expected.items():
        violation = found[key]
        assert violation.value == pytest.approx(value, rel=1e-7), key
        assert violation.allowed == pytest.approx(allowed, rel=1e-12), key
        assert violation.unit == unit_name, key
        assert violation.excess == pytest.approx(value - allowed, rel=1e-6), key


def test_check_pose_of_an_allowed_pose_is_empty():
    """The home pose and the middle of the ramp break none of the tight limits."""
    geometry = tight_geometry()
    assert limits.check_pose(geometry, HOME[:3], np.eye(3)) == []
    middle = HOME + 0.3 * (TABLE3_END - HOME)
    assert limits.check_pose(geometry, middle[:3], rotation_zyx(*middle[3:])) == []


def test_check_pose_finds_a_leg_below_its_minimum():
    """Lowering the platform reports the legs shorter than leg_length_min, by leg number."""
    geometry = tight_geometry()
    position = HOME[:3] - np.array([0.0, 0.0, 0.08])
    violations = limits.check_pose(geometry, position, np.eye(3))
    lengths = [math.sqrt(float(leg @ leg))
               for leg in legs_by_hand(BASE, PLATFORM, position, np.eye(3))]
    assert [(v.limit, v.leg) for v in violations] == [
        ('leg_length_min', leg) for leg, length in enumerate(lengths, start=1) if length < 0.65]
    assert violations


def test_check_poses_checks_each_pose_of_a_batch():
    """A batch gives one list per pose, equal to check_pose of that pose."""
    geometry = tight_geometry()
    poses = np.array([HOME, TABLE3_END, HOME + [0.0, 0.0, -0.08, 0.0, 0.0, 0.0],
                      HOME + 0.3 * (TABLE3_END - HOME)])
    results = limits.check_poses(geometry, poses)
    assert len(results) == 4
    assert results[0] == [] and results[3] == []
    assert results[1] and results[2]
    for pose, result in zip(poses, results):
        assert result == limits.check_pose(geometry, pose[:3], rotation_zyx(*pose[3:]))
    assert limits.check_poses(geometry, TABLE3_END) == [results[1]]


@pytest.mark.filterwarnings('ignore::RuntimeWarning')
@pytest.mark.parametrize('with_limits, position', [
    (True, [math.nan, 0.0, 0.4325]),
    (False, [0.0, math.inf, 0.4325]),
], ids=['nan with example limits', 'inf without limits'])
def test_check_pose_never_passes_a_non_finite_pose(with_limits, position):
    """A NaN or infinite position is not allowed: ValueError or a violation, never []."""
    geometry = example_geometry() if with_limits else paper_geometry()
    try:
        violations = limits.check_pose(geometry, np.array(position), np.eye(3))
    except ValueError as error:
        # numpy's LinAlgError is a ValueError, but 'SVD did not converge' names no input.
        assert not isinstance(error, np.linalg.LinAlgError), f'{type(error).__name__}: {error}'
        return
    assert violations, f'check_pose passed the non-finite position {position} as allowed'


@pytest.mark.parametrize('with_limits', [True, False], ids=['example limits', 'no limits'])
def test_leg_length_violations_never_passes_a_nan_length(with_limits):
    """A NaN length is not allowed: ValueError or a violation of that leg, never []."""
    geometry = example_geometry() if with_limits else paper_geometry()
    try:
        violations = limits.leg_length_violations(geometry, [0.7, 0.7, math.nan, 0.7, 0.7, 0.7])
    except ValueError:
        return
    assert [v.leg for v in violations] == [3], 'a NaN length of leg 3 passed as allowed'


# Violation ------------------------------------------------------------------------------------

def test_violation_str_names_leg_limit_and_excess_with_unit():
    """The text of a violation says which leg, which limit, by how much, in which unit."""
    text = str(Violation('leg_length_max', 3, 0.85, 0.80, 'm'))
    assert text.startswith('leg 3: ')
    assert 'leg_length_max 0.8 m' in text
    assert 'broken by 0.05 m' in text
    assert 'value 0.85 m' in text
    cone = str(Violation('base_joint_max_angle', 6, 32.5, 30.0, 'deg'))
    assert cone.startswith('leg 6: ') and 'base_joint_max_angle 30 deg' in cone
    assert 'broken by 2.5 deg' in cone


def test_violation_of_the_platform_and_below_a_minimum():
    """A whole-platform limit says 'platform' and has no unit; excess is always positive."""
    condition = Violation('max_jacobian_condition', None, 62.5, 50.0, '')
    assert str(condition) == ('platform: max_jacobian_condition 50 broken by 12.5 '
                              '(value 62.5)')
    below = Violation('leg_length_min', 1, 0.60, 0.65, 'm')
    assert below.excess == pytest.approx(0.05, abs=1e-15)
    assert 'leg 1: leg_length_min 0.65 m broken by 0.05 m' in str(below)


# Geometry and the home pose -------------------------------------------------------------------

@pytest.mark.parametrize('limit_values, words', [
    ({'leg_length_max': 0.71}, ['leg 1: leg_length_max', 'leg 2: leg_length_max']),
    ({'leg_length_min': 0.71}, ['leg 3: leg_length_min']),
    ({'max_jacobian_condition': 9.0}, ['platform: max_jacobian_condition 9']),
])
def test_geometry_refuses_a_home_pose_that_breaks_a_limit(limit_values, words):
    """A home pose outside its own limits is refused, naming the leg and the limit."""
    with pytest.raises(ValueError, match='home pose breaks the limits') as raised:
        paper_geometry(**limit_values)
    for word in words:
        assert word in str(raised.value)


def test_geometry_accepts_limits_the_home_pose_keeps():
    """Limits just around the home pose are accepted and kept as given."""
    geometry = paper_geometry(leg_length_min=0.70, leg_length_max=0.72,
                              base_joint_max_angle=math.radians(1.0),
                              platform_joint_max_angle=math.radians(1.0),
                              max_jacobian_condition=9.6)
    assert (geometry.leg_length_min, geometry.leg_length_max) == (0.70, 0.72)
    assert geometry.max_jacobian_condition == 9.6
    assert geometry.base_joint_max_angle == pytest.approx(math.radians(1.0))


# A platform joint on its base joint ---------------------------------------------------------

#: The paper's joints rounded to multiples of 2^-20 m (about 1 um), so that the pose below puts
#: a platform joint exactly on its base joint, without rounding: a leg of zero length.
DYADIC = 2.0 ** 20
DYADIC_BASE = np.round(BASE * DYADIC) / DYADIC
DYADIC_PLATFORM = np.round(PLATFORM * DYADIC) / DYADIC
#: Rotations whose entries are exact: none, and a quarter turn about z.
EXACT_ROTATIONS = [np.eye(3), np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])]


def dyadic_geometry(**limit_values):
    """Return the paper's platform with dyadic joints and the given limits."""
    return Geometry(base_joints=DYADIC_BASE, platform_joints=DYADIC_PLATFORM, home_pose=HOME,
                    limits=PoseLimits(**limit_values))


def joint_on_its_base_joint(leg, rotation):
    """Return the position that puts platform joint ``leg`` exactly on base joint ``leg``."""
    return DYADIC_BASE[leg] - rotation @ DYADIC_PLATFORM[leg]


@pytest.mark.parametrize('leg', range(6))
@pytest.mark.parametrize('rotation', EXACT_ROTATIONS)
def test_a_leg_of_zero_length_breaks_the_singularity_margin_without_raising(leg, rotation):
    # The defect: with only max_jacobian_condition set, this pose raised ZeroDivisionError
    # (from the unit vector of the zero-length leg), which ended ik_node.
    geometry = dyadic_geometry(max_jacobian_condition=50.0)
    position = joint_on_its_base_joint(leg, rotation)
    assert leg_lengths(geometry, position, rotation)[leg] == 0.0
    violations = limits.check_pose(geometry, position, rotation)
    assert [(v.limit, v.value) for v in violations] == [('max_jacobian_condition', math.inf)]
    assert float(jacobian_condition(geometry, position, rotation)) == math.inf
    batch = jacobian_condition(geometry, position[None], rotation[None])
    assert batch.shape == (1,) and batch[0] == math.inf


@pytest.mark.parametrize('leg', range(6))
def test_a_leg_of_zero_length_breaks_every_limit_set_and_nothing_raises(leg):
    geometry = dyadic_geometry(leg_length_min=0.65, leg_length_max=0.90,
                               base_joint_max_angle=math.radians(30.0),
                               platform_joint_max_angle=math.radians(35.0),
                               max_jacobian_condition=50.0)
    rotation = EXACT_ROTATIONS[1]
    position = joint_on_its_base_joint(leg, rotation)
    broken = {(v.limit, v.leg) for v in limits.check_pose(geometry, position, rotation)}
    assert {('leg_length_min', leg + 1), ('base_joint_max_angle', leg + 1),
            ('platform_joint_max_angle', leg + 1), ('max_jacobian_condition', None)} <= broken
