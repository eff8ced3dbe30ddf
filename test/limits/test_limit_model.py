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
Tests of the limits model (stewart_kinematics.limits.LimitModel): one evaluator per limit.

Every evaluator gives the same values on one pose as on a batch, the fast float path of one
pose's legs gives the batch's legs to the bit, the cheap paths (dear limits only where the cheap
ones pass, a condition number proved within its margin) decide as the full check does, the
leg-state limits are exact, and no input an adversary would choose crashes a check.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_array_equal
import pytest
from reference import HOME, paper_geometry, TABLE_3

from stewart_kinematics import ActuatorLimits, load_geometry
from stewart_kinematics.limits import LIMIT_NAMES, LimitModel, PoseLegs
from stewart_kinematics.model.inverse import leg_arrays
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, zyx_entries

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
SPREAD = np.array([0.2, 0.2, 0.15, 0.7, 0.7, 1.2])
SPEEDS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)


@pytest.fixture(scope='module')
def limited():
    """Return the paper's platform under the example limits: every pose limit set."""
    return load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])


def random_poses(geometry, count, seed):
    """Poses spread around the home pose; about half break a limit."""
    return geometry.home_pose + np.random.default_rng(seed).uniform(-1, 1, (count, 6)) * SPREAD


def test_the_model_holds_one_evaluator_per_limit_that_is_set(limited):
    """Every pose limit of the example file, in report order; none for a bare platform."""
    model = LimitModel(limited, SPEEDS)
    # The example file gives no masses: the force limits are not checked.
    assert model.pose_limit_names == tuple(
        name for name in LIMIT_NAMES if name not in ('leg_force_min', 'leg_force_max'))
    assert [type(limit).__name__ for limit in model.pose_limits] == [
        'Stroke', 'JointCones', 'SingularityMargin', 'LegCollision']
    assert [bound.name for limit in model.leg_state_limits for bound in limit.bounds] == [
        'leg_length_min', 'leg_length_max', 'leg_velocity_max', 'leg_acceleration_max',
        'leg_jerk_max']
    bare = limited.with_limits(leg_length_min=0.0, leg_length_max=math.inf,
                               base_joint_max_angle=math.pi, platform_joint_max_angle=math.pi,
                               max_jacobian_condition=math.inf, leg_radius=0.0)
    assert LimitModel(bare).pose_limits == () and LimitModel(bare).leg_state_limits == ()
    only_base = bare.with_limits(base_joint_max_angle=0.5)
    assert LimitModel(only_base).pose_limit_names == ('base_joint_max_angle',)
    with pytest.raises(KeyError, match='leg_jerk_max is not set'):
        LimitModel(limited).bound('leg_jerk_max')
    assert LimitModel.of_geometry(limited) is LimitModel.of_geometry(limited)


def test_one_pose_legs_in_floats_equal_the_batch_to_the_bit(limited):
    """The fast path of leg_arrays (one pose, floats) gives the batch's arrays exactly."""
    poses = random_poses(limited, 200, seed=1)
    poses[0, :3] = [1e160, -1e160, 1e160]          # lengths that overflow: inf on both paths
    cosines, sines = np.cos(poses[:, 3:]), np.sin(poses[:, 3:])
    entries = zyx_entries(cosines[:, 0], sines[:, 0], cosines[:, 1], sines[:, 1],
                          cosines[:, 2], sines[:, 2])
    with np.errstate(over='ignore', invalid='ignore'):
        lengths, vectors = leg_arrays(limited, poses[:, :3], entries)
        for index in range(len(poses)):
            one_lengths, one_vectors = leg_arrays(limited, poses[index:index + 1, :3],
                                                  [entry[index:index + 1] for entry in entries])
            assert_array_equal(one_lengths[:, 0], lengths[:, index])
            for one, many in zip(one_vectors, vectors):
                assert_array_equal(one[:, 0], many[:, index])
    assert np.isinf(lengths[:, 0]).all()


def test_every_evaluator_gives_a_pose_alone_what_it_gives_it_in_a_batch(limited):
    """Values of each evaluator on one pose equal its values on that pose within a batch."""
    model = LimitModel(limited)
    poses = random_poses(limited, 50, seed=2)
    batch = PoseLegs.of_poses(limited, poses)
    for limit in model.pose_limits:
        values = limit.values(batch)
        for index, pose in enumerate(poses):
            alone = limit.values(PoseLegs.of_poses(limited, pose[None]))
            for one, many in zip(alone, values):
                np.testing.assert_allclose(one[:, 0], many[:, index], rtol=1e-14, atol=1e-15)


def test_the_cheap_paths_decide_as_the_full_check(limited):
    """Dear limits only where the cheap pass, and a margin proved without SVD: same decision."""
    tight = limited.with_limits(max_jacobian_condition=14.0)
    model = LimitModel(tight)
    poses = random_poses(tight, 3000, seed=3)
    full = model.check_poses(poses)
    for every_reason, exact in ((False, True), (True, False), (False, False)):
        quick = model.check_poses(poses, every_reason=every_reason, exact=exact)
        assert_array_equal(quick.allowed, full.allowed)
        computed = ~np.isnan(quick.condition)
        assert_array_equal(quick.condition[computed], full.condition[computed])
        assert_array_equal(quick.broken['max_jacobian_condition'][computed],
                           full.broken['max_jacobian_condition'][computed])
    proved = np.isnan(model.check_poses(poses, exact=False).condition)
    assert proved.mean() > 0.1 and np.all(full.condition[proved] < 14.0)
    assert np.any(full.broken['max_jacobian_condition'])


def test_leg_states_are_checked_against_each_rate_and_the_stroke(limited):
    """Velocity, acceleration, jerk and stroke, leg by leg, with their units."""
    model = LimitModel(limited, SPEEDS)
    lengths = np.array([0.70, 0.95, 0.70, 0.70, 0.60, 0.70])
    velocities = np.array([0.0, 0.0, -0.06, 0.0, 0.0, 0.0])
    accelerations = np.array([0.0, 0.3, 0.0, 0.0, 0.0, 0.0])
    jerks = np.array([0.0, 0.0, 0.0, 0.0, 0.0, -3.0])
    violations = model.leg_state_violations(lengths, velocities, accelerations, jerks)
    assert [(v.limit, v.leg, v.unit) for v in violations] == [
        ('leg_length_min', 5, 'm'), ('leg_length_max', 2, 'm'), ('leg_velocity_max', 3, 'm/s'),
        ('leg_acceleration_max', 2, 'm/s^2'), ('leg_jerk_max', 6, 'm/s^3')]
    assert violations[2].value == pytest.approx(0.06) and violations[4].value == 3.0
    checks = model.check_leg_states(lengths, velocities, accelerations, jerks)
    assert checks.violations(0) == violations and not checks.allowed[0]
    only_velocities = model.leg_state_violations(velocities=velocities)
    assert [v.limit for v in only_velocities] == ['leg_velocity_max']
    many = model.check_leg_states(velocities=np.tile(velocities, (4, 1)) * [[0], [1], [0.5], [2]])
    assert_array_equal(many.allowed, [True, False, True, False])


def test_the_rate_slack_is_for_sampled_motion_only(limited):
    """Strict by default: 1e-12 over the limit breaks it; with RATE_SLACK it does not."""
    over = np.full(6, 0.05 * (1.0 + 1e-12))
    assert LimitModel(limited, SPEEDS).leg_state_violations(velocities=over)
    assert not LimitModel(limited, SPEEDS, rate_slack=1e-9).leg_state_violations(velocities=over)


@pytest.mark.parametrize('seed', range(5))
def test_the_velocity_scale_brings_the_fastest_leg_exactly_to_the_limit(limited, seed):
    """Scaled velocities never exceed the limit and miss it by rounding only."""
    model = LimitModel(limited, SPEEDS)
    rng = np.random.default_rng(seed)
    velocities = rng.normal(scale=10.0 ** rng.uniform(-2, 3), size=6)
    scale = model.leg_velocity_scale(velocities)
    peak = np.max(np.abs(velocities))
    if peak <= 0.05:
        assert scale == 1.0
    else:
        scaled = velocities * scale
        assert np.max(np.abs(scaled)) <= 0.05
        assert np.max(np.abs(scaled)) >= 0.05 * (1.0 - 1e-15)
        assert not model.leg_state_violations(velocities=scaled)
    assert LimitModel(limited).leg_velocity_scale(velocities) == 1.0   # no velocity limit


@pytest.mark.parametrize('position', [
    [math.nan, 0.0, 0.45], [0.0, math.inf, 0.45], [1e308, 1e308, 1e308], [0.0, 0.0]],
    ids=['nan', 'inf', '1e308', 'wrong length'])
def test_check_pose_refuses_what_is_no_pose_with_a_value_error(limited, position):
    """NaN, inf, overflowing lengths, a wrong shape: ValueError, never a crash or []."""
    with np.errstate(over='ignore', invalid='ignore'):
        with pytest.raises(ValueError):
            LimitModel(limited).check_pose(position, np.eye(3))


@pytest.mark.parametrize('poses, words', [
    (np.zeros((3, 5)), 'shape'), ([[0.0, 0.0, math.nan, 0.0, 0.0, 0.0]], 'finite'),
    ([['a'] * 6], 'must be numbers'), (np.full((2, 6), np.inf), 'finite')])
def test_check_poses_refuses_malformed_batches(limited, poses, words):
    """Wrong shapes, NaN or inf and text: ValueError naming what is wrong."""
    with pytest.raises(ValueError, match=words):
        LimitModel(limited).check_poses(poses)


def test_an_empty_batch_is_an_empty_check(limited):
    """Zero poses: zero results, every array empty, nothing raised."""
    checks = LimitModel(limited).check_poses(np.zeros((0, 6)))
    assert len(checks) == 0 and checks.first_refused() is None
    assert checks.lengths.shape == (0, 6) and checks.leg_distances.shape == (0, 15)
    matrices = LimitModel(limited).check_pose_matrices(np.zeros((0, 3)), np.zeros((0, 3, 3)))
    assert len(matrices) == 0


def test_leg_state_inputs_of_the_wrong_shape_are_refused(limited):
    """Six values each; batches of one shape."""
    model = LimitModel(limited, SPEEDS)
    with pytest.raises(ValueError, match=r'shape \(6,\)'):
        model.leg_state_violations(velocities=np.zeros(5))
    with pytest.raises(ValueError, match='one shape'):
        model.check_leg_states(velocities=np.zeros((3, 6)), accelerations=np.zeros((2, 6)))


def test_check_pose_matrices_equals_check_poses(limited):
    """Positions and rotation matrices give the violations of the same Euler poses."""
    poses = random_poses(limited, 500, seed=4)
    model = LimitModel(limited)
    by_angles = model.check_poses(poses)
    by_matrices = model.check_pose_matrices(poses[:, :3], euler_zyx_to_matrix(poses[:, 3:]))
    assert_array_equal(by_angles.allowed, by_matrices.allowed)
    for index in np.flatnonzero(~by_angles.allowed)[:100]:
        assert ([(v.limit, v.legs) for v in by_angles.violations(index)]
                == [(v.limit, v.legs) for v in by_matrices.violations(index)])
    with pytest.raises(ValueError, match='shapes'):
        model.check_pose_matrices(poses[:, :3], np.zeros((3, 3, 3)))


def test_the_fast_leg_state_path_decides_as_the_general_one(limited):
    """leg_state_allowed (floats) == no leg_state_violations (arrays), edge values included."""
    model = LimitModel(limited, SPEEDS, rate_slack=1e-9)
    rng = np.random.default_rng(6)
    edges = [0.65, 0.9, 0.05, 0.25, 2.5, 0.05 * (1 + 1e-9), 0.05 * (1 + 2e-9),
             math.nextafter(0.65, 0.0), math.nextafter(0.9, 1.0), math.nan, math.inf, -math.inf,
             0.0, -0.05, -2.5 * (1 + 1e-9), 1e308]
    decided = {True: 0, False: 0}
    for _ in range(3000):
        sample = {name: np.where(rng.random(6) < 0.03, rng.choice(edges, 6),
                                 rng.uniform(low, high, 6)).tolist()
                  for name, (low, high) in (('lengths', (0.64, 0.91)),
                                            ('velocities', (-0.0505, 0.0505)),
                                            ('accelerations', (-0.2525, 0.2525)),
                                            ('jerks', (-2.525, 2.525)))}
        given = dict(list(sample.items())[:int(rng.integers(1, 5))])
        fast = model.leg_state_allowed(**given)
        assert fast == (not model.leg_state_violations(**given)), given
        decided[fast] += 1
    assert min(decided.values()) > 100


def test_a_geometry_is_freed_once_nothing_but_the_package_caches_holds_it():
    """The per-geometry caches (limits model, solver constants, start table) do not leak it."""
    import gc
    import weakref
    from stewart_kinematics import CommandCheck, forward_kinematics, PoseTracker
    from stewart_kinematics.limits import check_pose
    transient = paper_geometry(leg_length_min=0.65, leg_length_max=0.9)
    assert not check_pose(transient, HOME[:3], np.eye(3))
    lengths = CommandCheck(transient).pose_vector(TABLE_3[2]).lengths
    assert forward_kinematics(transient, lengths).converged
    assert PoseTracker(transient).update(lengths).accepted
    alive = weakref.ref(transient)
    del transient
    gc.collect()
    assert alive() is None
