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
Unit tests of stewart_kinematics.trajectories: interpolation, whole checks, retiming.

Independent references: leg lengths from inverse_kinematics of the waypoint poses, velocities
and accelerations from finite differences of sampled positions, rotations and leg lengths.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import (
    ActuatorInterface,
    ActuatorLimits,
    check_trajectory,
    euler_zyx_to_matrix,
    inverse_kinematics,
    leg_lengths,
    leg_trajectory,
    load_geometry,
    plan_motion,
    PoseTrajectory,
    Ramp,
    retime,
    TimedTrajectory,
)
from stewart_kinematics.model.rotations import matrix_to_rotation_vector, rotation_vector_to_matrix
from stewart_kinematics.motion.pose_trajectory import MAX_PIECE_SAMPLES

pytestmark = pytest.mark.core

LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)


@pytest.fixture(scope='module')
def geometry(config_directory_path):
    """Load the paper's platform with the example limits."""
    return load_geometry([config_directory_path / 'paper_platform.yaml',
                          config_directory_path / 'example_limits.yaml'])


@pytest.fixture(scope='module')
def config_directory_path():
    """Return the shipped config/ folder."""
    from pathlib import Path
    return Path(__file__).resolve().parents[2] / 'config'


def table_3_rows():
    """Return the paper's Table 3: 11 poses, metres and radians."""
    return Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0]).rows


def wavy_poses(geometry, count=12, seed=0):
    """Random smooth-ish poses within a few centimetres and degrees of home."""
    rng = np.random.default_rng(seed)
    offsets = rng.uniform(-1.0, 1.0, size=(count, 6)) * [0.02, 0.02, 0.02, 0.08, 0.08, 0.1]
    return geometry.home_pose + offsets


def rates_from_rotations(rotations, step):
    """Angular velocity in the base frame from central differences of rotations."""
    derivative = np.gradient(rotations, step, axis=0)
    skew = derivative @ np.swapaxes(rotations, -1, -2)
    return np.stack([skew[:, 2, 1], skew[:, 0, 2], skew[:, 1, 0]], axis=-1)


def test_exp_and_log_of_so3_are_inverse_and_match_rodrigues():
    """Rotation vectors and matrices: a quarter turn about z, and round trips to 1e-15."""
    assert_allclose(rotation_vector_to_matrix([0.0, 0.0, math.pi / 2]),
                    [[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], atol=1e-15)
    vectors = np.random.default_rng(1).normal(size=(2000, 3))
    vectors = vectors[np.linalg.norm(vectors, axis=-1) < 3.1]
    for scale in (1.0, 1e-6, 1e-12):
        assert_allclose(matrix_to_rotation_vector(rotation_vector_to_matrix(vectors * scale)),
                        vectors * scale, rtol=0, atol=2e-15)


@pytest.mark.parametrize('given_velocities', [False, True])
def test_waypoints_are_passed_exactly(geometry, given_velocities):
    """Legs at the waypoint times equal the IK of the waypoint poses to 1e-9 m."""
    poses = wavy_poses(geometry)
    times = np.cumsum(np.r_[0.0, np.random.default_rng(2).uniform(0.5, 2.0, 11)])
    extra = {}
    if given_velocities:
        rng = np.random.default_rng(3)
        extra = {'velocities': rng.normal(size=(12, 3)) * 0.01,
                 'angular_velocities': rng.normal(size=(12, 3)) * 0.05}
    timed = TimedTrajectory.as_given(PoseTrajectory.from_poses(times, poses, **extra))
    assert_allclose(timed.waypoint_times, times - times[0])
    legs = timed.legs(geometry, timed.waypoint_times)
    assert_allclose(legs.lengths, inverse_kinematics(geometry, poses), rtol=0, atol=1e-9)
    if given_velocities:
        samples = timed.sample(timed.waypoint_times)
        assert_allclose(samples.velocities, extra['velocities'], atol=1e-12)
        assert_allclose(samples.angular_velocities, extra['angular_velocities'], atol=1e-12)


def test_pose_and_leg_derivatives_match_finite_differences(geometry):
    """Velocities and accelerations (pose and legs) match central differences of samples."""
    path = PoseTrajectory.from_poses(np.arange(6.0), wavy_poses(geometry, 6, seed=4))
    step = 1e-4
    # Inside one segment, away from the waypoints where accelerations jump.
    times = np.arange(2.1, 2.9, step)
    samples = path.sample(times)
    inner = slice(2, -2)
    assert_allclose(np.gradient(samples.positions, step, axis=0)[inner],
                    samples.velocities[inner], atol=1e-8)
    assert_allclose(np.gradient(samples.velocities, step, axis=0)[inner],
                    samples.accelerations[inner], atol=1e-8)
    assert_allclose(rates_from_rotations(samples.rotations, step)[inner],
                    samples.angular_velocities[inner], atol=1e-7)
    assert_allclose(np.gradient(samples.angular_velocities, step, axis=0)[inner],
                    samples.angular_accelerations[inner], atol=1e-7)
    timed = TimedTrajectory.as_given(path)
    legs = timed.legs(geometry, times)
    lengths = leg_lengths(geometry, samples.positions, samples.rotations)
    assert_allclose(legs.lengths, lengths, atol=1e-15)
    assert_allclose(np.gradient(lengths, step, axis=0)[inner], legs.velocities[inner], atol=1e-8)
    assert_allclose(np.gradient(legs.velocities, step, axis=0)[inner],
                    legs.accelerations[inner], atol=1e-7)


def test_velocity_is_continuous_at_waypoints(geometry):
    """The motion is smooth: velocity and angular velocity have no jump at a waypoint."""
    path = PoseTrajectory.from_poses(np.arange(5.0), wavy_poses(geometry, 5, seed=5))
    before, after = path.sample([2.0 - 1e-9]), path.sample([2.0])
    assert_allclose(before.velocities, after.velocities, atol=1e-8)
    assert_allclose(before.angular_velocities, after.angular_velocities, atol=1e-8)


def test_orientation_follows_the_rotation_axis_not_euler_angles():
    """
    From rest to rest between two orientations the platform turns about one fixed axis.

    60 degrees about (1, 1, 1): every Euler angle changes, and interpolating them would leave
    the axis; on SO(3) the axis of R0^T R(t) stays (1, 1, 1) and the angle grows monotonically.
    """
    axis = np.ones(3) / math.sqrt(3.0)
    end = rotation_vector_to_matrix(axis * math.radians(60.0))
    path = PoseTrajectory([0.0, 1.0], np.zeros((2, 3)), np.stack([np.eye(3), end]))
    rotations = path.sample(np.linspace(0.0, 1.0, 101)).rotations
    vectors = matrix_to_rotation_vector(rotations)
    angles = np.linalg.norm(vectors, axis=-1)
    assert_allclose(np.cross(vectors, axis), 0.0, atol=1e-14)
    assert np.all(np.diff(angles) > 0.0)
    assert_allclose(angles[[0, 50, 100]], np.radians([0.0, 30.0, 60.0]), atol=1e-14)


def test_a_trajectory_within_the_limits_is_accepted(geometry):
    """
    Table 3 over 10 s (legs at most 0.02 m/s) passes every limit of the example file.

    Each 1 s segment is one cubic: sampled with MAX_PIECE_SAMPLES (256) intervals, not 1000.
    """
    path = PoseTrajectory.from_poses(np.arange(11.0), table_3_rows())
    plan = plan_motion(path, geometry, LIMITS)
    assert plan.accepted, plan.reason
    assert plan.trajectory.duration == 10.0
    assert plan.check.samples == 10 * MAX_PIECE_SAMPLES + 1
    assert 0.3 < plan.check.peak_velocity_ratio < 0.5


def test_an_unreachable_waypoint_is_refused_with_time_segment_leg_and_limit(geometry):
    """Waypoint 2 lifts the platform until legs exceed leg_length_max (0.90 m)."""
    poses = np.tile(geometry.home_pose, (4, 1))
    poses[2, 2] += 0.25
    plan = plan_motion(PoseTrajectory.from_poses([0.0, 10.0, 20.0, 30.0], poses), geometry)
    assert not plan.accepted and plan.trajectory is None
    first = plan.check.violations[0]
    assert first.limit == 'leg_length_max' and first.leg is not None
    assert plan.check.segment == (1, 2)
    assert 10.0 < plan.check.time < 20.0
    # The sample before the reported one is within every limit: it is the first failure.
    timed = TimedTrajectory.as_given(PoseTrajectory.from_poses([0.0, 10.0, 20.0, 30.0], poses))
    samples = timed.sample_times(1000.0)
    before = samples[np.searchsorted(samples, plan.check.time) - 1]
    lengths = leg_lengths(geometry, *(lambda s: (s.positions, s.rotations))(
        timed.sample([before, plan.check.time])))
    assert lengths[0].max() <= geometry.leg_length_max < lengths[1].max()
    assert f't = {plan.check.time:.4f} s' in plan.reason
    assert 'between points 1 and 2' in plan.reason
    assert f'leg {first.leg}: leg_length_max 0.9 m' in plan.reason


def test_a_too_fast_segment_is_refused_naming_the_velocity_limit(geometry):
    """A 5 cm lift in 0.5 s needs more than 0.05 m/s on every leg."""
    poses = np.tile(geometry.home_pose, (3, 1))
    poses[1, 2] += 0.05
    plan = plan_motion(PoseTrajectory.from_poses([0.0, 0.5, 5.0], poses), geometry, LIMITS)
    assert not plan.accepted
    limits_broken = {violation.limit for violation in plan.check.violations}
    assert limits_broken & {'leg_velocity_max', 'leg_acceleration_max'}
    assert plan.check.segment == (0, 1)
    assert 'between points 0 and 1' in plan.reason and 'leg_' in plan.reason
    # Slower, it passes: the speed limits were the only reason.
    assert plan_motion(PoseTrajectory.from_poses([0.0, 5.0, 10.0], poses), geometry,
                       LIMITS).accepted


@pytest.mark.parametrize('speed_scale', [1.0, 0.5])
def test_retimed_trajectory_is_within_every_limit_at_every_sample(geometry, speed_scale):
    """The retimed Table 3 ramp: within limits at 1 kHz and 5 kHz, a limit reached, faster."""
    path = PoseTrajectory.from_poses(np.arange(11.0), table_3_rows())
    plan = plan_motion(path, geometry, LIMITS, retime_path=True, speed_scale=speed_scale)
    assert plan.accepted and plan.retimed, plan.reason
    scaled = LIMITS.scaled(speed_scale)
    timed = plan.trajectory
    legs = timed.legs(geometry, timed.sample_times(1000.0))
    assert np.abs(legs.velocities).max() <= scaled.velocity_max * (1 + 1e-9)
    assert np.abs(legs.accelerations).max() <= scaled.acceleration_max * (1 + 1e-9)
    # Time-optimal: some leg runs at (nearly) its velocity or acceleration limit.
    assert max(plan.check.peak_velocity_ratio, plan.check.peak_acceleration_ratio) > 0.97
    # Between the checked samples too, within rounding of the stretch margin.
    dense = timed.legs(geometry, np.linspace(0.0, timed.duration, 50001))
    assert np.abs(dense.velocities).max() <= scaled.velocity_max * 1.002
    assert np.abs(dense.accelerations).max() <= scaled.acceleration_max * 1.005
    # The waypoints are still passed exactly, at the retimed waypoint times.
    assert_allclose(timed.legs(geometry, timed.waypoint_times).lengths,
                    inverse_kinematics(geometry, table_3_rows()), rtol=0, atol=1e-9)


def test_speed_scale_stretches_the_retimed_duration(geometry):
    """Half the speed takes twice as long (within the stretch margin)."""
    path = PoseTrajectory.from_poses(np.arange(11.0), table_3_rows())
    full = plan_motion(path, geometry, LIMITS, retime_path=True).trajectory.duration
    half = plan_motion(path, geometry, LIMITS, retime_path=True,
                       speed_scale=0.5).trajectory.duration
    assert 2.0 * full / 1.01 < half < 2.0 * full * 1.01
    assert full < 10.0 / 2


def test_a_path_without_timing_is_retimed(geometry):
    """Waypoints without times: parameterised by leg travel (chord in leg space), retimed."""
    rows = table_3_rows()
    path = PoseTrajectory.path(geometry, rows[:, :3], euler_zyx_to_matrix(rows[:, 3:]))
    lengths = inverse_kinematics(geometry, rows)
    assert_allclose(np.diff(path.times), np.linalg.norm(np.diff(lengths, axis=0), axis=1))
    plan = plan_motion(path, geometry, LIMITS, retime_path=True)
    assert plan.accepted, plan.reason
    assert_allclose(plan.trajectory.legs(geometry, plan.trajectory.waypoint_times).lengths,
                    lengths, rtol=0, atol=1e-9)


def test_retiming_without_speed_limits_is_refused(geometry):
    """The fastest timing without any limit would take no time: refused with the reason."""
    path = PoseTrajectory.from_poses(np.arange(11.0), table_3_rows())
    plan = plan_motion(path, geometry, ActuatorLimits(), retime_path=True)
    assert not plan.accepted and 'leg_velocity_max or leg_acceleration_max' in plan.reason
    with pytest.raises(ValueError, match='leg_velocity_max'):
        retime(path, geometry, ActuatorLimits())


def test_an_unreachable_path_is_refused_by_retiming_too(geometry):
    """Retiming cannot fix a pose outside the stroke; the reason says which limit."""
    poses = np.tile(geometry.home_pose, (3, 1))
    poses[1, 2] += 0.25
    plan = plan_motion(PoseTrajectory.from_poses([0.0, 1.0, 2.0], poses), geometry, LIMITS,
                       retime_path=True)
    assert not plan.accepted and 'leg_length_max' in plan.reason


def test_leg_trajectory_carries_names_offsets_and_waypoints(geometry):
    """Actuator positions are lengths minus offsets; every waypoint time is a point."""
    actuators = ActuatorInterface(('a1', 'a2', 'a3', 'a4', 'a5', 'a6'),
                                  np.full(6, 0.5) + np.arange(6) * 0.01)
    path = PoseTrajectory.from_poses([0.0, 0.75, 2.0], table_3_rows()[:3])
    timed = TimedTrajectory.as_given(path)
    points = leg_trajectory(timed, geometry, actuators, rate=10.0)
    assert points.joint_names == actuators.joint_names
    assert {0.0, 0.75, 2.0} <= set(points.times.tolist())
    assert np.diff(points.times).max() <= 0.1
    at_waypoints = np.searchsorted(points.times, [0.0, 0.75, 2.0])
    assert_allclose(points.positions[at_waypoints] + actuators.offsets,
                    inverse_kinematics(geometry, table_3_rows()[:3]), rtol=0, atol=1e-9)
    assert_allclose(points.velocities[[0, -1]], 0.0, atol=1e-15)


def test_check_reports_the_condition_number_limit(geometry):
    """A trajectory through a near-singular pose is refused on max_jacobian_condition."""
    poses = np.tile(geometry.home_pose, (3, 1))
    poses[1, 5] = math.radians(85.0)  # yaw near the paper platform's singularity (about 90)
    check = check_trajectory(TimedTrajectory.as_given(
        PoseTrajectory.from_poses([0.0, 1.0, 2.0], poses)), geometry)
    assert not check.accepted
    assert any(violation.limit in ('max_jacobian_condition', 'base_joint_max_angle',
                                   'platform_joint_max_angle', 'leg_length_max')
               for violation in check.violations)


@pytest.mark.parametrize('times, rotations, message', [
    ([0.0, 1.0, 1.0], None, 'increase strictly'),
    ([0.0, 1.0], [np.eye(3), rotation_vector_to_matrix([0.0, 0.0, 3.13])], 'turn by less'),
    ([0.0], None, 'at least 2'),
])
def test_malformed_trajectories_are_refused(times, rotations, message):
    """Times that do not increase, a half turn, a single waypoint: ValueError with why."""
    count = len(times)
    rotations = np.stack(rotations) if rotations is not None else np.tile(np.eye(3),
                                                                          (count, 1, 1))
    with pytest.raises(ValueError, match=message):
        PoseTrajectory(times, np.zeros((count, 3)), rotations)
