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
Tests of the forward solver's start table (stewart_kinematics.model.start_table).

A solve without a guess starts from the table; these check its coverage, the fall-back to the
home start, that both starts agree where both find the working mode, that the table holds
only the working mode, and that each geometry has its own. The poses come from the paper's
platform and test/reference.py's leg lengths, independent of the package.
"""

import gc
import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import (
    HOME,
    leg_lengths as leg_lengths_of,
    paper_geometry,
    PLATFORM_JOINTS,
    random_poses,
    TABLE_3,
    TABLE_3_END,
    twist_jacobian as reference_twist_jacobian,
)

from stewart_kinematics.model import formulas, forward_solver, start_table
from stewart_kinematics.model.forward import forward_kinematics, start_table_of
from stewart_kinematics.model.inverse import inverse_kinematics
from stewart_kinematics.model.jacobians import jacobian_condition
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.model.start_table import StartTable

pytestmark = pytest.mark.core

#: A second real assembly mode of the lengths at the end of Table 3, above the base
#: (doc/assembly_modes.md): metres and radians.
SECOND_MODE_AT_TABLE_3_END = (-0.0802, -0.0019, 0.4962, math.radians(20.9),
                              math.radians(-27.6), math.radians(152.8))


@pytest.fixture(scope='module')
def geometry():
    """Build the paper's platform, home pose at the start of Table 3."""
    return paper_geometry()


@pytest.fixture(scope='module')
def table(geometry):
    """Return the start table the forward solver built for the paper's platform."""
    forward_kinematics(geometry, leg_lengths_of(TABLE_3[1]))
    return start_table_of(geometry)


def kept_samples(table):
    """Return the poses of the cells that hold a sample, shape (n, 6)."""
    return table.entries[np.frombuffer(table.kept, dtype=np.uint8).astype(bool), :6]


def assert_same_result(one, other):
    """Two results agree in every field, the pose to the bit."""
    assert (one.converged, one.iterations, one.reason) == (other.converged, other.iterations,
                                                           other.reason)
    assert one.residual == other.residual
    assert np.array_equal(one.pose, other.pose)


def test_the_table_covers_the_workspace_of_the_benchmark(geometry, table):
    """Every pose within +-0.1 m and +-15 deg of home starts from the table, and converges."""
    poses = np.vstack([random_poses(500, seed=31), TABLE_3])
    lengths = np.array([leg_lengths_of(pose) for pose in poses])
    assert all(table.cell(target) >= 0 for target in lengths.tolist())
    assert table.coverage == 1.0
    results = [forward_kinematics(geometry, target) for target in lengths]
    assert all(result.converged for result in results)
    assert_allclose([result.pose for result in results], poses, rtol=0.0, atol=1e-9)
    # About three steps, against about four from home.
    assert np.mean([result.iterations for result in results]) < 3.3
    from_home = forward_kinematics(geometry, lengths, HOME)
    assert np.mean(from_home.iterations) > 4.0


def test_the_table_is_small(table):
    """The table of the default size takes 6.5 MB (the target: under 20 MB)."""
    assert table.nbytes < 7e6
    assert table.cells ** 6 == len(table.entries) == len(table.inverses) == len(table.kept)


def test_each_sample_solves_its_lengths_and_its_start_is_one_newton_step(geometry, table):
    """A sample's pose has its stored leg lengths; its trigonometry is of its own angles."""
    samples = table.entries[::97]
    assert_allclose(inverse_kinematics(geometry, samples[:, :6]), samples[:, 6:12], rtol=0.0,
                    atol=1e-12)
    assert_allclose(samples[:, 12:], np.column_stack([
        np.cos(samples[:, 4]), np.sin(samples[:, 4]), np.cos(samples[:, 5]),
        np.sin(samples[:, 5])]), rtol=0.0, atol=1e-15)
    jacobians = np.array([reference_twist_jacobian(pose) for pose in samples[:, :6]])
    assert_allclose(table.inverses[::97] @ jacobians, np.broadcast_to(np.eye(6), jacobians.shape),
                    rtol=0.0, atol=1e-9)


def test_home_lengths_start_at_home_and_take_no_step(geometry):
    """Home is the centre of the middle cell: its lengths are solved at once, as before."""
    result = forward_kinematics(geometry, leg_lengths_of(HOME))
    assert result.converged and result.iterations == 0
    assert_allclose(result.pose, HOME, rtol=0.0, atol=1e-15)


@pytest.mark.parametrize('pose', [
    (0.3, 0.0, 0.45, 0.0, 0.0, 0.0),                          # beyond the table's reach
    (0.0, 0.0, 0.4325, 0.0, 0.0, math.radians(40.0)),         # beyond its turn
    (0.0, -0.1, 0.60, math.radians(25.0), 0.0, 0.0),          # beyond both
])
def test_lengths_outside_the_table_start_from_home(geometry, table, pose):
    """Outside the grid the solve is the solve from home, field for field."""
    lengths = leg_lengths_of(pose)
    assert table.cell(lengths) == -1
    cold = forward_kinematics(geometry, lengths)
    assert_same_result(cold, forward_kinematics(geometry, lengths, HOME))
    assert cold.converged
    assert_allclose(cold.pose, pose, rtol=0.0, atol=1e-9)


def test_a_failed_start_from_the_table_falls_back_to_home(geometry, table):
    """A table start that runs out of steps gives the home start's result instead."""
    lengths = leg_lengths_of(TABLE_3_END)
    assert table.cell(lengths) >= 0
    for steps in (1, 2):
        cold = forward_kinematics(geometry, lengths, max_iterations=steps)
        assert_same_result(cold, forward_kinematics(geometry, lengths, HOME,
                                                    max_iterations=steps))
        assert not cold.converged
    assert forward_kinematics(geometry, lengths, max_iterations=3).converged


def test_absurd_lengths_are_not_in_the_table_and_fail_as_from_home(geometry, table):
    """Lengths of no pose near home (overflowing the index, too) fail as they did."""
    for lengths in ([1e308] * 6, [1e308, 1e-300] * 3, [1e-300] * 6, [0.05] * 6):
        assert table.cell(lengths) == -1
        assert table.cells_of(np.array([lengths])).tolist() == [-1]
        assert_same_result(forward_kinematics(geometry, lengths),
                           forward_kinematics(geometry, lengths, HOME))


def test_table_and_home_starts_agree_to_1e_12(geometry):
    """Where both starts find the working mode, they find the same pose (tolerance 1e-14)."""
    near_the_edge = random_poses(100, seed=33, position_range=0.14, angle_range_deg=19.0)
    poses = np.vstack([random_poses(300, seed=32), near_the_edge])
    lengths = np.array([leg_lengths_of(pose) for pose in poses])
    for target, pose in zip(lengths, poses):
        cold = forward_kinematics(geometry, target, tolerance=1e-14)
        home = forward_kinematics(geometry, target, HOME, tolerance=1e-14)
        assert cold.converged and home.converged
        assert_allclose(home.pose, pose, rtol=0.0, atol=1e-9)  # the working mode
        assert_allclose(cold.pose, home.pose, rtol=0.0, atol=1e-12)


def test_at_the_default_tolerance_both_starts_agree_within_their_error_bounds(geometry):
    poses = random_poses(200, seed=34)
    lengths = np.array([leg_lengths_of(pose) for pose in poses])
    cold = forward_kinematics(geometry, lengths)
    home = forward_kinematics(geometry, lengths, HOME)
    assert np.all(cold.converged) and np.all(home.converged)
    difference = np.max(np.abs(cold.pose - home.pose), axis=-1)
    assert np.all(difference <= cold.pose_error_bound + home.pose_error_bound)
    assert np.max(cold.residual) <= 1e-12 and np.max(difference) < 1e-10


def test_lengths_of_two_modes_give_the_working_one(geometry):
    """The end of Table 3 has a second mode above the base; a cold solve finds the first."""
    lengths = leg_lengths_of(TABLE_3_END)
    assert_allclose(leg_lengths_of(SECOND_MODE_AT_TABLE_3_END), lengths, atol=2e-3)
    cold = forward_kinematics(geometry, lengths)
    assert cold.converged
    assert_allclose(cold.pose, TABLE_3_END, rtol=0.0, atol=1e-9)


def test_the_table_holds_only_the_working_mode(geometry):
    """
    A grid that reaches past the singularity keeps only the samples on home's side of it.

    At +-100 degrees the grid holds poses beyond the singular yaw near 90.4 degrees and in
    other assembly modes: none is kept; every kept sample has home's determinant sign, a
    condition number within the bound, and its lengths.
    """
    wide = StartTable(geometry, turn=math.radians(100.0))
    samples = kept_samples(wide)
    assert 0.0 < wide.coverage < 0.5
    signs = [np.sign(np.linalg.det(reference_twist_jacobian(pose))) for pose in samples]
    assert set(signs) == {np.sign(np.linalg.det(reference_twist_jacobian(HOME)))}
    condition = jacobian_condition(
        geometry, samples[:, :3], euler_zyx_to_matrix(samples[:, 3:]))
    assert np.all(condition <= start_table.MAX_CONDITION)
    # Lengths that the wide grid does not hold start from home and are solved as from home.
    poses = random_poses(200, seed=35, position_range=0.1, angle_range_deg=90.0)
    lengths = inverse_kinematics(geometry, poses)
    outside = [target for target in lengths.tolist() if wide.cell(target) < 0]
    assert len(outside) > 50


def test_a_cold_batch_takes_the_steps_of_cold_single_solves(geometry):
    """The batch path starts each row from the same sample, with the same arithmetic."""
    poses = np.vstack([random_poses(100, seed=36), [(0.3, 0.0, 0.45, 0.0, 0.0, 0.0)], HOME])
    lengths = np.vstack([inverse_kinematics(geometry, poses), [[0.05] * 6, [5.0] * 6]])
    batch = forward_kinematics(geometry, lengths)
    failed = forward_kinematics(geometry, lengths[:3], max_iterations=2)
    for k, target in enumerate(lengths):
        single = forward_kinematics(geometry, target)
        assert (single.reason, single.converged, single.iterations) == (
            batch.reason[k], batch.converged[k], batch.iterations[k]), k
        assert single.residual == batch.residual[k]
        assert_allclose(single.pose, batch.pose[k], rtol=0.0, atol=1e-15)
    for k, target in enumerate(lengths[:3]):
        single = forward_kinematics(geometry, target, max_iterations=2)
        assert (single.reason, single.iterations) == (failed.reason[k], failed.iterations[k])


def test_each_geometry_has_its_own_table(geometry, table):
    """Another geometry builds another table, and its cold solves find its own poses."""
    other = paper_geometry(platform_joints=PLATFORM_JOINTS * 1.2,
                           home_pose=(0.0, 0.0, 0.45, 0.0, 0.0, 0.0))
    poses = random_poses(50, seed=37, around=other.home_pose)
    lengths = inverse_kinematics(other, poses)
    results = forward_kinematics(other, lengths)
    other_table = start_table_of(other)
    assert other_table is not table
    assert other_table.index_offset != table.index_offset
    assert np.all(results.converged)
    assert_allclose(results.pose, poses, rtol=0.0, atol=1e-9)
    # The paper's platform still uses its own.
    assert start_table_of(geometry) is table


def test_a_table_does_not_keep_its_geometry_alive():
    """
    The solver's cache holds a geometry weakly: neither its constants nor its table refer to it.

    (So the table goes with its geometry, unless something else keeps the geometry.)
    """
    transient = paper_geometry()
    forward_kinematics(transient, leg_lengths_of(TABLE_3[2]))
    constants = formulas.constants_of(transient)
    table = start_table_of(transient)
    assert isinstance(table, StartTable)
    gc.collect()
    holders = [holder for holder in gc.get_referrers(transient)
               if isinstance(holder, (StartTable, formulas.GeometryConstants))
               or (isinstance(holder, dict) and any(
                   isinstance(owner, (StartTable, formulas.GeometryConstants))
                   for owner in gc.get_referrers(holder)))]
    assert holders == []
    assert formulas.constants_of(transient) is constants and start_table_of(transient) is table


def test_a_geometry_with_a_singular_home_has_no_table():
    """Every leg of zero length at home: no Jacobian, no table, solves start from home."""
    joints = np.array(PLATFORM_JOINTS)
    joints[:, 2] = 0.0
    flat = paper_geometry(base_joints=joints, platform_joints=joints, home_pose=[0.0] * 6)
    assert start_table_of(flat) is None
    result = forward_kinematics(flat, [0.2] * 6)
    assert result.reason == forward_solver.SINGULAR_JACOBIAN
