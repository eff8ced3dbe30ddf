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
6-3 and 3-3 platforms (joints shared by two legs), design by design, next to the paper's 6-6.

The designs are config/platform_6_3.yaml and config/platform_3_3.yaml; their drawings (radii
and angles) are typed in test/reference.py, and leg lengths come from its plain-Python formula.
Each design is checked for what the package does with a geometry: which joints are shared,
inverse and forward kinematics, every assembly mode, the workspace, the leg collision check
and calibration (shared joints tied).
"""

from dataclasses import replace
import math
from pathlib import Path

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose, assert_array_equal
from properties import budget
import pytest
import reference

from stewart_kinematics import (
    assembly_modes,
    forward_kinematics,
    inverse_kinematics,
    LimitModel,
    load_geometry,
    workspace_volume,
)
from stewart_kinematics.analysis import homotopy
from stewart_kinematics.analysis.calibration import calibrate, parameter_layout
from stewart_kinematics.limits import LEG_PAIRS, LegCollision, PoseLegs, segment_distances
from stewart_kinematics.model.geometry import SHARED_JOINT_TOLERANCE
from stewart_kinematics.model.jacobians import jacobian_condition
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
#: Each design's parameter files.
DESIGN_FILES = {'6-6': ('paper_platform.yaml', 'example_limits.yaml'),
                '6-3': ('platform_6_3.yaml',), '3-3': ('platform_3_3.yaml',)}
#: Complex solutions of the forward kinematics: 40 for a general 6-6 platform, 16 for the
#: 6-3 and the 3-3 (octahedral) ones (Innocenti and Parenti-Castelli 1990; Husty 1996).
SHARED_SOLUTION_COUNT = 16
GENERIC_SOLUTION_COUNT = 40


def design_geometry(design):
    """Load an example design from its parameter files."""
    return load_geometry([CONFIG / name for name in DESIGN_FILES[design]])


@pytest.fixture(scope='module', params=sorted(DESIGN_FILES))
def design(request):
    """Return ``(name, geometry)`` of each design."""
    return request.param, design_geometry(request.param)


def allowed_random_poses(geometry, count, seed, position_range=0.05, angle_range_deg=10.0):
    """Random poses around home that keep every limit, (count, 6)."""
    poses = reference.random_poses(4 * count, seed, geometry.home_pose, position_range,
                                   angle_range_deg)
    poses = poses[LimitModel.of_geometry(geometry).check_poses(poses).allowed]
    assert len(poses) >= count
    return poses[:count]


def unique_rows(joints):
    """Return the distinct joints, in order of appearance, and each leg's index among them."""
    distinct, index = [], []
    for joint in map(tuple, joints):
        if joint not in distinct:
            distinct.append(joint)
        index.append(distinct.index(joint))
    return np.array(distinct), np.array(index)


def moved_joints(joints, scale, generator):
    """Move each distinct joint by up to ``scale`` metres; a shared joint stays shared."""
    distinct, index = unique_rows(joints)
    return (distinct + generator.uniform(-scale, scale, distinct.shape))[index]


# Which joints are shared ---------------------------------------------------------------------

@pytest.mark.parametrize('name', ['6-3', '3-3'])
def test_files_hold_their_drawings(name):
    """The files' joints are the drawings' (to the 7 decimals written), shared as drawn."""
    geometry = design_geometry(name)
    base, platform = reference.design_joints(name)
    assert_allclose(geometry.base_joints, base, rtol=0.0, atol=5e-8)
    assert_allclose(geometry.platform_joints, platform, rtol=0.0, atol=5e-8)
    assert_allclose(geometry.home_pose, reference.DESIGN_HOME, atol=0.0)
    assert geometry.design == name
    shared = {side: tuple(joint.legs for joint in geometry.shared_joints if joint.side == side)
              for side in ('base', 'platform')}
    assert shared == reference.DESIGN_SHARED[name]
    assert str(geometry.shared_joints[0]) == (
        f'legs {geometry.shared_joints[0].legs[0]} and {geometry.shared_joints[0].legs[1]} '
        f'share a {geometry.shared_joints[0].side} joint')


def test_the_paper_platform_shares_no_joint():
    geometry = design_geometry('6-6')
    assert geometry.design == '6-6' and geometry.shared_joints == ()


def test_two_legs_sharing_both_joints_are_refused():
    """Legs with the same base joint and the same platform joint would be one leg twice."""
    geometry = design_geometry('6-3')
    base = geometry.base_joints.copy()
    base[5] = base[0]     # legs 1 and 6 already share their platform joint
    with pytest.raises(ValueError, match='legs 1 and 6 share both their base joint and their '
                                         'platform joint: they would be one leg twice'):
        replace(geometry, base_joints=base)


def test_a_chain_of_coinciding_joints_is_one_point_of_three_legs():
    """p_1 within the tolerance of p_2, p_2 of p_3: three legs on one point, refused."""
    geometry = design_geometry('6-6')
    platform = geometry.platform_joints.copy()
    step = 0.6 * SHARED_JOINT_TOLERANCE * geometry.platform_radius
    platform[0] = platform[1] + [step, 0.0, 0.0]
    platform[2] = platform[1] - [step, 0.0, 0.0]
    with pytest.raises(ValueError, match=r'platform_joints: joints 1, 2 and 3 coincide'):
        replace(geometry, platform_joints=platform)


def test_six_joints_on_one_point_are_refused():
    geometry = design_geometry('6-6')
    with pytest.raises(ValueError, match=r'base_joints: joints 1, 2, 3, 4, 5 and 6 coincide '
                                         r'\(6 legs on one point\)'):
        replace(geometry, base_joints=np.zeros((6, 3)))


@pytest.mark.parametrize('separation, design', [
    (0.0, '6-3'),                  # written twice, the same numbers
    (1e-11, '6-3'),                # rounding: within 1e-9 of the platform's 0.15 m
    (1e-7, '6-4'),                 # two joints, however close
    (1e-4, '6-4'),                 # 0.1 mm: a 6-4 platform that is nearly 6-3
])
def test_joints_count_as_one_only_within_the_tolerance(separation, design):
    """Joints farther apart than 1e-9 of the set's size are two joints: a valid platform."""
    shared = design_geometry('6-3')
    platform = shared.platform_joints.copy()
    platform[2] += [0.0, separation, 0.0]
    nearly = replace(shared, platform_joints=platform,
                     limits=shared.limits.replace(leg_radius=0.0))
    assert nearly.design == design
    assert (1, 6) in [joint.legs for joint in nearly.shared_joints]
    assert ((2, 3) in [joint.legs for joint in nearly.shared_joints]) == (design == '6-3')
    # Nearly shared, its legs 2 and 3 meet within a leg's thickness at home: a collision that
    # the home pose check names (legs that share a joint are not checked: they meet there).
    if design == '6-4':
        with pytest.raises(ValueError, match='legs 2 and 3: leg_collision'):
            nearly.with_limits(leg_radius=0.02)
    else:
        assert nearly.with_limits(leg_radius=0.02).leg_radius == 0.02


def pairings():
    """Draw disjoint pairs of legs (1..6, the lower first): a side's shared joints."""
    return st.permutations(range(1, 7)).flatmap(lambda order: st.integers(0, 3).map(
        lambda count: tuple(sorted(tuple(sorted(order[2 * k:2 * k + 2]))
                                   for k in range(count)))))


@budget(40)
@given(pairings(), pairings())
def test_pairings_make_platforms_unless_two_legs_share_both(base_pairs, platform_pairs):
    """
    Merge drawn pairs of the paper's joints: shared as drawn, or refused naming the legs.

    A merged pair takes the lower leg's joint; every platform so made has a leg length formula
    of its own and the shared pairs' distances are not checked.
    """
    paper = reference.paper_geometry()      # no limits: some pairings are near-singular
    base, platform = paper.base_joints.copy(), paper.platform_joints.copy()
    for joints, pairs in ((base, base_pairs), (platform, platform_pairs)):
        for first, second in pairs:
            joints[second - 1] = joints[first - 1]
    both = sorted(set(base_pairs) & set(platform_pairs))
    if both:
        with pytest.raises(ValueError, match=f'legs {both[0][0]} and {both[0][1]} share both'):
            replace(paper, base_joints=base, platform_joints=platform)
        return
    geometry = replace(paper, base_joints=base, platform_joints=platform)
    assert geometry.design == f'{6 - len(base_pairs)}-{6 - len(platform_pairs)}'
    assert [(joint.side, joint.legs) for joint in geometry.shared_joints] == (
        [('base', pair) for pair in base_pairs] + [('platform', pair) for pair in platform_pairs])
    pose = np.array(reference.HOME) + [0.01, -0.02, 0.03, 0.05, -0.04, 0.1]
    assert_allclose(inverse_kinematics(geometry, pose),
                    reference.leg_lengths(pose, base, platform), rtol=0.0, atol=1e-12)
    distances = LegCollision(geometry).values(PoseLegs.of_poses(geometry, pose[None]))[0][:, 0]
    shared = [LEG_PAIRS.index(pair) for pair in base_pairs + platform_pairs]
    assert np.all(np.isinf(distances[shared]))
    assert np.all(np.isfinite(np.delete(distances, shared)))


# Inverse and forward kinematics --------------------------------------------------------------

def test_inverse_kinematics_matches_the_textbook_formula(design):
    name, geometry = design
    poses = reference.random_poses(50, 11, geometry.home_pose, 0.08, 15.0)
    expected = np.array([reference.leg_lengths(pose, geometry.base_joints,
                                               geometry.platform_joints) for pose in poses])
    assert_allclose(inverse_kinematics(geometry, poses), expected, rtol=0.0, atol=1e-12)


@pytest.mark.parametrize('name, angle_deg', [('6-3', 42.5), ('3-3', 60.0)])
def test_home_legs_have_the_drawings_length(name, angle_deg):
    """Every leg at home: 0.7 m up, and across the law of cosines of radii 0.225 and 0.15."""
    across = 0.225 ** 2 + 0.15 ** 2 - 2.0 * 0.225 * 0.15 * math.cos(math.radians(angle_deg))
    assert_allclose(design_geometry(name).home_leg_lengths, [math.sqrt(0.49 + across)] * 6,
                    rtol=0.0, atol=1e-7)


def test_forward_kinematics_round_trips(design):
    """Lengths of random allowed poses solve back to the poses, cold and from home."""
    name, geometry = design
    poses = allowed_random_poses(geometry, 200, 12)
    result = forward_kinematics(geometry, inverse_kinematics(geometry, poses))
    assert result.converged.all()
    assert_allclose(result.pose, poses, rtol=0.0, atol=1e-9)
    assert np.max(result.residual) <= 1e-12


def test_home_is_well_conditioned(design):
    """The home pose is far from every singularity: condition numbers of 5 to 10."""
    name, geometry = design
    condition = jacobian_condition(geometry, geometry.home_pose[:3],
                                   euler_zyx_to_matrix(geometry.home_pose[3:]))
    assert condition < {'6-6': 10.0, '6-3': 7.0, '3-3': 6.0}[name]


@pytest.mark.parametrize('name', ['6-3', '3-3'])
def test_a_quarter_turn_is_the_architecture_singularity(name):
    """Turned 90 degrees about z from home, the 6-3 and 3-3 platforms are singular."""
    geometry = design_geometry(name)
    pose = np.array(reference.DESIGN_HOME)
    turned = [jacobian_condition(geometry, pose[:3], euler_zyx_to_matrix([0.0, 0.0, gamma]))
              for gamma in np.radians([80.0, 89.0, 90.0])]
    assert turned[0] < turned[1] < 1e3 < 1e15 < turned[2]
    # A twist that moves no leg there: the Jacobian has a null vector.
    jacobian = reference.twist_jacobian(tuple(pose[:5]) + (math.radians(90.0),),
                                        geometry.base_joints, geometry.platform_joints)
    assert np.linalg.svd(jacobian, compute_uv=False)[-1] < 1e-12


# Assembly modes ------------------------------------------------------------------------------

def test_every_assembly_mode_at_home(design):
    """Every real mode at home has home's lengths; shared designs have 16 solutions, not 40."""
    name, geometry = design
    lengths = geometry.home_leg_lengths
    modes = assembly_modes(geometry, lengths)
    assert modes.complete and modes.failed_paths == 0 and modes.reason == ''
    solutions = len(modes) + modes.complex_solutions
    assert solutions + modes.at_infinity == GENERIC_SOLUTION_COUNT
    if name == '6-6':
        assert len(modes) == 10
    else:
        # Symmetric designs: all 16 real, 8 above the base and their mirror images below it.
        assert (solutions, modes.at_infinity, len(modes)) == (SHARED_SOLUTION_COUNT, 24, 16)
        assert np.count_nonzero(modes.poses[:, 2] > 0.0) == 8
    for mode in modes.modes:
        assert_allclose(reference.leg_lengths(mode.pose, geometry.base_joints,
                                              geometry.platform_joints), lengths,
                        rtol=0.0, atol=1e-9)
    assert modes.modes[0].distance < 1e-9            # home itself, nearest
    # Within the limits, home is the only mode: no other mode to jump to.
    assert len(modes.within_limits) == 1


@pytest.mark.parametrize('name', ['6-3', '3-3'])
@pytest.mark.parametrize('seed', [1, 2, 3])
def test_asymmetric_shared_designs_have_16_solutions(name, seed):
    """Shared designs with every distinct joint moved up to 2 cm: 16 solutions, 24 at infinity."""
    generator = np.random.default_rng(seed)
    drawn = design_geometry(name)
    geometry = replace(drawn, base_joints=moved_joints(drawn.base_joints, 0.02, generator),
                       platform_joints=moved_joints(drawn.platform_joints, 0.02, generator),
                       limits=None)
    assert geometry.design == name
    for pose in reference.random_poses(2, seed, geometry.home_pose, 0.08, 15.0):
        lengths = np.array(reference.leg_lengths(pose, geometry.base_joints,
                                                 geometry.platform_joints))
        modes = assembly_modes(geometry, lengths, reference_pose=pose)
        assert modes.complete and modes.failed_paths == 0
        assert len(modes) + modes.complex_solutions == SHARED_SOLUTION_COUNT
        assert modes.at_infinity == GENERIC_SOLUTION_COUNT - SHARED_SOLUTION_COUNT
        assert len(modes) % 2 == 0                   # complex solutions come in pairs
        assert modes.modes[0].distance < 1e-9        # the pose itself is found


@pytest.mark.parametrize('name', ['6-3', '3-3'])
def test_the_generic_start_system_serves_a_shared_design(monkeypatch, name):
    """
    Track a shared design from the general 40-path start: 24 paths go to infinity.

    The general start system is the fallback of a geometry start system that failed; the same
    real modes are found from it.
    """
    geometry = replace(design_geometry(name))         # a new object: no cached start system
    pose = np.array(reference.DESIGN_HOME) + [0.02, -0.01, 0.03, 0.1, -0.05, 0.2]
    lengths = inverse_kinematics(geometry, pose)
    expected = assembly_modes(geometry, lengths, reference_pose=pose)
    fresh = replace(geometry)
    monkeypatch.setattr(homotopy, '_build_geometry_start',
                        lambda _: (homotopy.start_system(), 0))
    modes = assembly_modes(fresh, lengths, reference_pose=pose)
    assert modes.paths == GENERIC_SOLUTION_COUNT and expected.paths == SHARED_SOLUTION_COUNT
    assert modes.complete and modes.at_infinity == 24
    assert len(modes) + modes.complex_solutions == SHARED_SOLUTION_COUNT
    assert len(modes) == len(expected)
    assert_allclose(modes.poses, expected.poses, rtol=0.0, atol=1e-9)


@pytest.mark.parametrize('separation', [1e-3, 1e-5, 1e-7])
def test_a_nearly_shared_platform_keeps_all_its_modes(separation):
    """A 6-6 platform whose joints nearly coincide: every path ends cleanly, the pose found."""
    shared = design_geometry('6-3')
    platform = shared.platform_joints.copy()
    platform[[2, 4, 5]] += [[0.0, separation, 0.0], [separation, 0.0, 0.0],
                            [0.0, 0.0, separation]]
    geometry = replace(shared, platform_joints=platform,
                       limits=shared.limits.replace(leg_radius=0.0))
    assert geometry.design == '6-6'
    pose = np.array(reference.DESIGN_HOME) + [0.03, 0.02, -0.02, 0.05, 0.1, -0.1]
    modes = assembly_modes(geometry, inverse_kinematics(geometry, pose), reference_pose=pose)
    assert modes.complete and modes.failed_paths == 0
    assert len(modes) + modes.complex_solutions + modes.at_infinity == GENERIC_SOLUTION_COUNT
    assert modes.modes[0].distance < 1e-9


# Leg collisions ------------------------------------------------------------------------------

def test_pairs_that_share_a_joint_are_not_checked_for_collision(design):
    """Their distance is inf; every other pair's is the segments' distance, as before."""
    name, geometry = design
    poses = allowed_random_poses(geometry, 20, 13)
    checks = LimitModel.of_geometry(geometry).check_poses(poses)
    distances = checks.leg_distances
    shared = [LEG_PAIRS.index(joint.legs) for joint in geometry.shared_joints]
    assert np.all(np.isinf(distances[:, shared]))
    for pose, row in zip(poses, distances):
        rotation = reference.rotation_zyx(*pose[3:])
        tops = pose[:3] + geometry.platform_joints @ rotation.T
        for k, (first, second) in enumerate(LEG_PAIRS):
            if k not in shared:
                expected = reference.segment_distance(
                    geometry.base_joints[first - 1], tops[first - 1],
                    geometry.base_joints[second - 1], tops[second - 1])
                assert row[k] == pytest.approx(expected, abs=1e-12)
    assert not checks.broken['leg_collision'].any()


def test_other_pairs_of_a_shared_design_still_collide():
    """Legs 1 and 2 of the 6-3 (no joint shared) are 135 mm apart at home: thicker legs touch."""
    geometry = design_geometry('6-3')
    with pytest.raises(ValueError) as refused:
        geometry.with_limits(leg_radius=0.07)
    message = str(refused.value)
    assert 'legs 1 and 2: leg_collision' in message and 'legs 3 and 4' in message
    assert 'legs 1 and 6' not in message and 'legs 2 and 3' not in message


def test_segment_distances_of_shared_pairs_would_be_zero():
    """What the check skips: the raw distance of a pair that shares a joint is 0 at any pose."""
    geometry = design_geometry('3-3')
    pose = np.array(reference.DESIGN_HOME) + [0.02, 0.01, -0.03, 0.1, 0.05, -0.2]
    rotation = euler_zyx_to_matrix(pose[3:])
    legs = pose[:3] + geometry.platform_joints @ rotation.T - geometry.base_joints
    first, second = np.triu_indices(6, 1)
    offsets = geometry.base_joints[first] - geometry.base_joints[second]
    raw = segment_distances(*(legs[:, axis:axis + 1].copy() for axis in range(3)),
                            np.linalg.norm(legs, axis=1)[:, None],
                            tuple(offsets[:, axis:axis + 1] for axis in range(3)))[:, 0]
    shared = [LEG_PAIRS.index(joint.legs) for joint in geometry.shared_joints]
    assert_allclose(raw[shared], 0.0, atol=1e-15)


# Workspace -----------------------------------------------------------------------------------

def test_workspace_volume_is_positive_and_bounded(design):
    """
    Measure a positive, bounded constant-orientation workspace.

    The grid's volume matches the fraction of random positions in its bounding box that keep
    every limit.
    """
    name, geometry = design
    volume = workspace_volume(geometry, resolution=0.02)
    assert volume.bounded and volume.volume > 0.01
    low, high = volume.bounding_box
    generator = np.random.default_rng(14)
    positions = generator.uniform(low, high, (20000, 3))
    poses = np.column_stack([positions, np.tile(geometry.home_pose[3:], (len(positions), 1))])
    fraction = np.mean(LimitModel.of_geometry(geometry).check_poses(
        poses, every_reason=False).allowed)
    assert fraction * np.prod(high - low) == pytest.approx(volume.volume, rel=0.06)


# Calibration ---------------------------------------------------------------------------------

@pytest.mark.parametrize('name, free', [('6-6', 42), ('6-3', 33), ('3-3', 24)])
def test_calibration_ties_shared_joints(name, free):
    """A built platform's joints, shared as drawn, come back from exact measurements."""
    nominal = design_geometry(name)
    generator = np.random.default_rng(15)
    base = moved_joints(nominal.base_joints, 2e-3, generator)
    platform = moved_joints(nominal.platform_joints, 2e-3, generator)
    offsets = 0.6 + generator.uniform(-5e-3, 5e-3, 6)
    poses = allowed_random_poses(nominal, 40, 16, angle_range_deg=8.0)
    readings = np.array([reference.leg_lengths(pose, base, platform) for pose in poses]) - offsets
    result = calibrate(nominal, poses, readings, np.full(6, 0.6))
    assert result.layout.count == free == parameter_layout(nominal).count
    assert_allclose(result.geometry.base_joints, base, rtol=0.0, atol=1e-9)
    assert_allclose(result.geometry.platform_joints, platform, rtol=0.0, atol=1e-9)
    assert_allclose(result.actuator_offsets, offsets, rtol=0.0, atol=1e-9)
    # Tied: the calibrated joints of two legs are the same numbers, so still shared.
    assert result.geometry.shared_joints == nominal.shared_joints
    for joint in nominal.shared_joints:
        joints = getattr(result.geometry, f'{joint.side}_joints')
        assert_array_equal(joints[joint.legs[0] - 1], joints[joint.legs[1] - 1])
    assert result.identifiability.identifiable
    assert len(result.identifiability.blocks) == {'6-6': 6, '6-3': 3, '3-3': 1}[name]


def test_calibration_of_a_shared_design_with_noise_reaches_the_noise_floor():
    """Noisy readings (1 um): the tied fit predicts new poses as well as the true platform."""
    nominal = design_geometry('3-3')
    generator = np.random.default_rng(17)
    base = moved_joints(nominal.base_joints, 2e-3, generator)
    platform = moved_joints(nominal.platform_joints, 2e-3, generator)
    offsets = 0.6 + generator.uniform(-5e-3, 5e-3, 6)

    def measure(poses):
        exact = np.array([reference.leg_lengths(pose, base, platform) for pose in poses])
        return exact - offsets + generator.normal(0.0, 1e-6, exact.shape)

    poses = allowed_random_poses(nominal, 40, 18, angle_range_deg=8.0)
    result = calibrate(nominal, poses, measure(poses), np.full(6, 0.6))
    held_out = allowed_random_poses(nominal, 100, 19, angle_range_deg=8.0)
    measured = measure(held_out)
    predicted = inverse_kinematics(result.geometry, held_out) - result.actuator_offsets
    assert np.sqrt(np.mean((predicted - measured) ** 2)) < 1.3e-6
    # The report names the tied joints and the one block of legs.
    report = result.report()
    assert 'shared joints, fitted as one point each: b1,2, b3,4, b5,6, p1,6, p2,3, p4,5' in report
    assert 'legs 1, 2, 3, 4, 5, 6:' in report
    # Standard deviations: both legs of a shared joint carry its one value.
    deviations = result.standard_deviations
    assert_array_equal(deviations[0:3], deviations[3:6])
    assert np.all(deviations > 0.0)
