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
Tests of stewart_kinematics.analysis.assembly_modes: every real assembly mode, and the margin.

Independent references: Dietmaier's platform with its 40 real solutions as PHCpack lists them
(test/resources/dietmaier_40_modes.yaml), and, for the paper's platform, a multi-start search
written here (its own rotation parametrisation, Jacobian and Newton iteration; thousands of
starts spread over every orientation and over positions above and below the base). Leg lengths
are checked with a plain numpy formula, not the package's inverse kinematics.
"""

import math
from pathlib import Path

import numpy as np
import pytest
import reference
from stewart_kinematics import assembly_mode_margin, assembly_modes, Geometry, load_geometry
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, matrix_to_euler_zyx
import yaml

pytestmark = pytest.mark.core

RESOURCES = Path(__file__).resolve().parents[1] / 'resources'
CONFIG = Path(__file__).resolve().parents[2] / 'config'
#: End of the paper's Table 3: metres and degrees.
TABLE_3_END = (0.1, 0.15, 0.5325, 15.0, -15.0, 20.0)


def pose_of(position, angles_deg):
    return np.array(list(position) + [math.radians(a) for a in angles_deg])


def multi_start_modes(base, platform, lengths, starts=4000, seed=0):
    """
    Every real pose a multi-start Newton search finds: the independent reference.

    Starts: uniformly random rotations (normalised Gaussian quaternions) and positions
    uniform in the ball every solution lies in (|t| <= max l + max |p| + max |b|); each takes
    40 damped Newton steps (:func:`newton`). Returns distinct solutions as (positions,
    rotations).
    """
    rng = np.random.default_rng(seed)
    quaternions = rng.normal(size=(starts, 4))
    quaternions /= np.linalg.norm(quaternions, axis=-1, keepdims=True)
    w, x, y, z = quaternions.T
    rotations = np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], -2)
    reach = (lengths.max() + np.linalg.norm(platform, axis=-1).max()
             + np.linalg.norm(base, axis=-1).max())
    directions = rng.normal(size=(starts, 3))
    directions /= np.linalg.norm(directions, axis=-1, keepdims=True)
    positions = directions * reach * rng.uniform(size=(starts, 1)) ** (1 / 3)
    positions, rotations = newton(base, platform, lengths, positions, rotations, 40, reach)
    residual = np.max(np.abs(reference.leg_lengths_batch(positions, rotations, base, platform)
                             - lengths),
                      axis=-1)
    solved = residual < 1e-10
    found_positions, found_rotations = [], []
    for position, rotation in zip(positions[solved], rotations[solved]):
        if not any(np.linalg.norm(position - p) < 1e-6 and np.abs(rotation - r).max() < 1e-6
                   for p, r in zip(found_positions, found_rotations)):
            found_positions.append(position)
            found_rotations.append(rotation)
    return np.array(found_positions).reshape(-1, 3), np.array(found_rotations).reshape(-1, 3, 3)


def newton(base, platform, lengths, positions, rotations, iterations, reach=np.inf):
    """
    Damped Newton steps on (t, small rotation vector w), R <- exp(w) R, for poses (n, ...).

    The Jacobian rows are [u_i, R p_i x u_i]; no step is longer than half of ``reach`` or
    half a radian.
    """
    for _ in range(iterations):
        arms = np.einsum('nij,kj->nki', rotations, platform)
        legs = positions[:, None, :] + arms - base
        current = np.linalg.norm(legs, axis=-1)
        units = legs / current[..., None]
        jac = np.concatenate([units, np.cross(arms, units)], axis=-1)
        singular = np.abs(np.linalg.det(jac)) < 1e-300
        jac[singular] = np.eye(6)
        step = np.linalg.solve(jac, (current - lengths)[..., None])[..., 0]
        step[singular] = 0.0
        step[:, :3] *= np.minimum(1.0, 0.5 * reach / np.maximum(
            np.linalg.norm(step[:, :3], axis=-1), 1e-300))[:, None]
        step[:, 3:] *= np.minimum(1.0, 0.5 / np.maximum(
            np.linalg.norm(step[:, 3:], axis=-1), 1e-300))[:, None]
        positions = positions - step[:, :3]
        rotations = reference.rotation_vector_matrices(-step[:, 3:]) @ rotations
    return positions, rotations


def assert_same_modes(result, reference_positions, reference_rotations, tolerance=1e-6):
    """Every reference solution is one of the modes found, and the other way round."""
    positions = result.poses[:, :3]
    rotations = euler_zyx_to_matrix(result.poses[:, 3:])
    for position, rotation in zip(reference_positions, reference_rotations):
        match = (np.linalg.norm(positions - position, axis=-1) < tolerance) & (
            np.max(np.abs(rotations - rotation), axis=(-2, -1)) < tolerance)
        assert np.count_nonzero(match) == 1, (
            f'reference solution at {position} not found once among {len(result)} modes')
    assert len(result) == len(reference_positions)


@pytest.fixture(scope='module')
def dietmaier():
    data = yaml.safe_load((RESOURCES / 'dietmaier_40_modes.yaml').read_text())
    base, platform = np.array(data['base_joints']), np.array(data['platform_joints'])
    geometry = Geometry(base, platform, home_pose=[0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    solutions = np.array(data['solutions'])
    first, second = solutions[:, 3:6], solutions[:, 6:9]
    rotations = np.stack([first, second, np.cross(first, second)], axis=-1)
    return geometry, np.array(data['leg_lengths']), solutions[:, :3], rotations


@pytest.fixture(scope='module')
def paper():
    return load_geometry(CONFIG / 'paper_platform.yaml')


@pytest.fixture(scope='module')
def paper_with_limits():
    return load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])


def test_dietmaier_all_40_real_modes_found(dietmaier):
    geometry, lengths, positions, rotations = dietmaier
    result = assembly_modes(geometry, lengths)
    assert result.complete, result.reason
    assert result.reason == ''
    assert (result.paths, result.failed_paths, result.complex_solutions) == (40, 0, 0)
    assert len(result) == 40
    # The published poses solve PHCpack's system, whose coefficients were rounded to about 10
    # digits: they match the exact data's lengths to 6e-10 m, and the modes to 1e-6 except
    # where the pose is ill-conditioned (4 of 40, up to 3.3e-6: condition numbers 1e4 to 7e4).
    assert_same_modes(result, positions, rotations, tolerance=5e-6)
    close = [np.min(np.linalg.norm(result.poses[:, :3] - position, axis=-1)) < 1e-6
             for position in positions]
    assert sum(close) >= 36
    # Two steps of the test's own Newton iteration on the exact data take every published pose
    # to one of the modes found, to 1e-9.
    refined = newton(geometry.base_joints, geometry.platform_joints, lengths, positions,
                     rotations, 2)
    assert_same_modes(result, *refined, tolerance=1e-9)
    # Leg lengths within 1e-9 after refinement, by an independent formula.
    for mode in result.modes:
        rotation = euler_zyx_to_matrix(mode.pose[3:])
        found = reference.leg_lengths_of_matrix(
            mode.pose[:3], rotation, geometry.base_joints, geometry.platform_joints)
        assert np.max(np.abs(found - lengths)) <= 1e-9
        assert mode.residual <= 1e-9
        assert 1.0 <= mode.condition < np.inf


def test_modes_are_sorted_from_the_reference_pose(dietmaier):
    geometry, lengths, positions, rotations = dietmaier
    reference_pose = np.concatenate([positions[17], matrix_to_euler_zyx(rotations[17])])
    result = assembly_modes(geometry, lengths, reference_pose=reference_pose)
    distances = [mode.distance for mode in result.modes]
    assert distances == sorted(distances)
    assert result.modes[0].distance < 1e-6
    np.testing.assert_allclose(result.modes[0].pose[:3], positions[17], atol=1e-6)
    second = result.modes[1]
    expected = math.hypot(second.position_distance,
                          geometry.platform_radius * second.angle_distance)
    assert second.distance == pytest.approx(expected)
    assert second.position_distance == pytest.approx(
        np.linalg.norm(second.pose[:3] - reference_pose[:3]))


ramp_rows = [0, 5, 10]


@pytest.mark.parametrize('row', ramp_rows)
def test_paper_platform_along_table_3_matches_a_multi_start_search(paper, row):
    end = pose_of(TABLE_3_END[:3], TABLE_3_END[3:])
    start = pose_of((0.0, 0.0, 0.4325), (0.0, 0.0, 0.0))
    pose = start + (end - start) * row / 10
    rotation = euler_zyx_to_matrix(pose[3:])
    lengths = reference.leg_lengths_of_matrix(
        pose[:3], rotation, paper.base_joints, paper.platform_joints)
    result = assembly_modes(paper, lengths, reference_pose=pose)
    assert result.complete, result.reason
    expected = multi_start_modes(paper.base_joints, paper.platform_joints, lengths)
    assert_same_modes(result, *expected)
    # The pose the lengths came from is the nearest mode.
    assert result.modes[0].distance < 1e-9
    assert len(result) + result.complex_solutions + result.at_infinity == 40


def test_paper_platform_at_random_poses_matches_a_multi_start_search(paper):
    rng = np.random.default_rng(15)
    for _ in range(3):
        pose = paper.home_pose + np.concatenate([rng.uniform(-0.1, 0.1, 3),
                                                 np.radians(rng.uniform(-15, 15, 3))])
        rotation = euler_zyx_to_matrix(pose[3:])
        lengths = reference.leg_lengths_of_matrix(
            pose[:3], rotation, paper.base_joints, paper.platform_joints)
        result = assembly_modes(paper, lengths, reference_pose=pose)
        assert result.complete, result.reason
        assert_same_modes(result, *multi_start_modes(paper.base_joints, paper.platform_joints,
                                                     lengths, seed=1))


def test_end_of_table_3_has_a_second_mode_above_the_base(paper):
    end = pose_of(TABLE_3_END[:3], TABLE_3_END[3:])
    lengths = reference.leg_lengths_of_matrix(
        end[:3], euler_zyx_to_matrix(end[3:]), paper.base_joints, paper.platform_joints)
    result = assembly_modes(paper, lengths, reference_pose=end)
    above = [mode for mode in result.modes if mode.pose[2] > 0.0]
    below = [mode for mode in result.modes if mode.pose[2] < 0.0]
    assert (len(above), len(below)) == (2, 2)
    assert above[1].position_distance == pytest.approx(0.2385, abs=1e-3)
    assert math.degrees(above[1].angle_distance) == pytest.approx(135.3, abs=0.1)


def test_limits_flag_the_unreachable_modes(paper_with_limits):
    geometry = paper_with_limits
    end = pose_of(TABLE_3_END[:3], TABLE_3_END[3:])
    lengths = reference.leg_lengths_of_matrix(
        end[:3], euler_zyx_to_matrix(end[3:]), geometry.base_joints, geometry.platform_joints)
    result = assembly_modes(geometry, lengths, reference_pose=end)
    assert len(result) == 4
    assert [mode.within_limits for mode in result.modes] == [True, False, False, False]
    assert result.within_limits == result.modes[:1]
    limits_broken = {violation.limit for violation in result.modes[1].violations}
    assert 'platform_joint_max_angle' in limits_broken


def test_planar_base_and_planar_platform(paper):
    # The paper's platform with p_3 at 0.275 m like the other five: both planes.
    platform = paper.platform_joints.copy()
    platform[2, 2] = 0.275
    planar = Geometry(paper.base_joints, platform, home_pose=paper.home_pose)
    pose = planar.home_pose + np.array([0.02, -0.03, 0.05, 0.1, -0.05, 0.2])
    lengths = reference.leg_lengths_of_matrix(
        pose[:3], euler_zyx_to_matrix(pose[3:]), planar.base_joints, platform)
    result = assembly_modes(planar, lengths, reference_pose=pose)
    assert result.complete, result.reason
    assert_same_modes(result, *multi_start_modes(planar.base_joints, platform, lengths))
    # A planar base and platform mirror every mode in the base plane: the mirror image of
    # its joints is another mode's joints.
    joints = (result.poses[:, None, :3]
              + np.einsum('nij,kj->nki', euler_zyx_to_matrix(result.poses[:, 3:]), platform))
    mirrored = joints * np.array([1.0, 1.0, -1.0])
    for image in mirrored:
        assert np.min(np.max(np.abs(joints - image), axis=(-2, -1))) < 1e-7
    assert np.count_nonzero(result.poses[:, 2] < 0.0) == len(result) // 2


@pytest.mark.parametrize('lengths', [[0.01] * 6, [0.1, 0.1, 0.1, 2.0, 2.0, 2.0]])
def test_lengths_without_a_real_solution_give_an_empty_answer_with_the_reason(paper, lengths):
    result = assembly_modes(paper, lengths)
    assert len(result) == 0
    assert result.poses.shape == (0, 6)
    assert 'no real assembly mode' in result.reason


def test_malformed_lengths_are_refused(paper):
    with pytest.raises(ValueError, match='finite and positive'):
        assembly_modes(paper, [0.7, 0.7, 0.7, 0.7, 0.7, -0.7])
    with pytest.raises(ValueError, match='6 lengths'):
        assembly_modes(paper, np.full((2, 6), 0.7))


def test_margin_to_the_nearest_other_mode(paper, paper_with_limits):
    end = pose_of(TABLE_3_END[:3], TABLE_3_END[3:])
    margin = assembly_mode_margin(paper, end)
    assert margin.complete
    assert margin.modes_within_limits == 4
    assert margin.position == pytest.approx(0.2385, abs=1e-3)
    assert math.degrees(margin.angle) == pytest.approx(135.3, abs=0.1)
    assert margin.nearest.pose[2] > 0.0
    # With the example limits no other mode is reachable: an infinite margin.
    limited = assembly_mode_margin(paper_with_limits, end)
    assert (limited.position, limited.angle, limited.nearest) == (math.inf, math.inf, None)
    assert limited.modes_within_limits == 1


def test_a_start_is_ambiguous_when_two_modes_are_reachable_and_none_is_near(paper):
    from stewart_kinematics.analysis.assembly_modes import start_ambiguity
    end = pose_of(TABLE_3_END[:3], TABLE_3_END[3:])
    lengths = reference.leg_lengths_of_matrix(
        end[:3], euler_zyx_to_matrix(end[3:]), paper.base_joints, paper.platform_joints)
    # From home, 0.21 m and 26 deg away, neither above-base mode is near: ambiguous.
    check = start_ambiguity(paper, lengths, paper.home_pose, 0.05, math.radians(10.0))
    assert check.ambiguous
    assert (check.modes_within_limits, check.near_known_pose) == (4, 0)
    assert '4 assembly modes lie within the limits' in check.reason
    # Known to be near the end of the ramp: not ambiguous.
    near_end = end + np.array([0.01, 0.0, 0.0, 0.0, 0.0, math.radians(3.0)])
    check = start_ambiguity(paper, lengths, near_end, 0.05, math.radians(10.0))
    assert not check.ambiguous and check.reason == '' and check.near_known_pose == 1


def test_a_start_with_one_reachable_mode_is_not_ambiguous(paper_with_limits):
    from stewart_kinematics.analysis.assembly_modes import start_ambiguity
    geometry = paper_with_limits
    end = pose_of(TABLE_3_END[:3], TABLE_3_END[3:])
    lengths = reference.leg_lengths_of_matrix(
        end[:3], euler_zyx_to_matrix(end[3:]), geometry.base_joints, geometry.platform_joints)
    check = start_ambiguity(geometry, lengths, geometry.home_pose, 0.05, math.radians(10.0))
    assert not check.ambiguous
    assert (check.modes_within_limits, check.near_known_pose) == (1, 0)


def test_doc_table_of_the_modes_at_the_end_of_table_3_is_current():
    import importlib.util
    script = Path(__file__).resolve().parents[2] / 'scripts' / 'figures' / 'assembly_modes.py'
    spec = importlib.util.spec_from_file_location('assembly_modes_figure', script)
    figure = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(figure)
    markdown_table, table_3_end_modes = figure.markdown_table, figure.table_3_end_modes
    page = (Path(__file__).resolve().parents[2] / 'doc' / 'assembly_modes.md').read_text(
        encoding='utf-8')
    _, modes = table_3_end_modes()
    assert markdown_table(modes) in page, (
        'doc/assembly_modes.md is out of date: run python scripts/figures/assembly_modes.py')


@pytest.mark.parametrize('worker', ['thread', 'process'])
def test_margin_monitor_computes_in_the_background_once_per_set_of_lengths(paper, worker):
    from stewart_kinematics.workers.margin_monitor import AssemblyModeMarginMonitor
    end = pose_of(TABLE_3_END[:3], TABLE_3_END[3:])
    lengths = reference.leg_lengths_of_matrix(
        end[:3], euler_zyx_to_matrix(end[3:]), paper.base_joints, paper.platform_joints)
    monitor = AssemblyModeMarginMonitor(paper, warning_distance=0.5, worker=worker)
    try:
        assert monitor.latest is None and monitor.warning() == ''
        assert not monitor.request(end, None)
        assert monitor.request(end, lengths)
        assert not monitor.request(end, lengths)   # one at a time
        monitor.wait(timeout=30.0)
        assert monitor.latest.position == pytest.approx(0.2385, abs=1e-3)
        assert monitor.latest_seconds > 0.0
        assert not monitor.request(end, lengths)   # the same lengths: nothing new to compute
        # 0.427 m combined < 0.5 m: a warning naming the distances.
        assert '0.2385 m and 135.3 deg' in monitor.warning()
        monitor.warning_distance = 0.1
        assert monitor.warning() == ''
    finally:
        monitor.close()


def test_margin_monitor_refuses_an_unknown_worker_and_outlives_its_process(paper):
    from stewart_kinematics.workers.margin_monitor import AssemblyModeMarginMonitor
    with pytest.raises(ValueError, match="worker must be one of .'thread', 'process'., got 'x'"):
        AssemblyModeMarginMonitor(paper, worker='x')
    monitor = AssemblyModeMarginMonitor(paper, worker='process')
    try:
        monitor._warm_up.result(timeout=30.0)
        for process in list(monitor._pool._processes.values()):
            process.kill()
            process.join()
        # The dead worker is noticed, and the next request gets a new one.
        end = pose_of(TABLE_3_END[:3], TABLE_3_END[3:])
        lengths = reference.leg_lengths_of_matrix(
            end[:3], euler_zyx_to_matrix(end[3:]), paper.base_joints, paper.platform_joints)
        for _ in range(3):
            monitor.request(end, lengths)
            monitor.wait(timeout=30.0)
            if monitor.latest is not None:
                break
        assert monitor.latest.position == pytest.approx(0.2385, abs=1e-3)
    finally:
        monitor.close()
