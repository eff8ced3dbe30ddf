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
Every trajectory gets an answer, bounded in time and memory, with the reason that is true.

The inputs of issue 20, as a planner or a person produces them (each failed before): a last
point at 2^31 - 1 s; the same 5 cm lift given over 1 s to 60 s, and over 2^31 s; a straight
path of 300, 1000 and 10,000 waypoints; a dwell; a 10^4 s trajectory; then every malformed
time, and the reasons of a refusal (a singularity, the check's budget). Through
:class:`stewart_kinematics.MotionPlanner`, which trajectory_node calls with what a message
carries (quaternions ``(x, y, z, w)``).
"""

import math
from pathlib import Path
import threading

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics import (
    ActuatorLimits,
    check_trajectory,
    euler_zyx_to_quaternion,
    FrameTree,
    load_geometry,
    MotionPlanner,
    plan_motion,
    PoseTrajectory,
    retime,
    TimedTrajectory,
)
from stewart_kinematics.model.frames import Transform
from stewart_kinematics.motion.pose_trajectory import MAX_PIECE_SAMPLES, MAX_TIME, MAX_WAYPOINTS
from stewart_kinematics.motion.retiming import Cancelled
from stewart_kinematics.motion.trajectory_check import MAX_CHECK_SAMPLES

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
GEOMETRY = load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])
LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
HOME = GEOMETRY.home_pose
LIFT = HOME + [0.0, 0.0, 0.05, 0.0, 0.0, 0.0]


def planner(retime_path=False, frames=None):
    """Build a planner with the example limits, as trajectory_node builds it."""
    return MotionPlanner(GEOMETRY, LIMITS, frames, retime=retime_path)


def waypoints(poses):
    """Positions and quaternions of poses ``[X, Y, Z, alpha, beta, gamma]``."""
    poses = np.asarray(poses, dtype=float)
    return poses[:, :3], euler_zyx_to_quaternion(poses[:, 3:])


def line(count, spacing_seed=None):
    """``count`` poses on the 5 cm lift, evenly or (with a seed) unevenly spaced."""
    u = np.linspace(0.0, 1.0, count)
    if spacing_seed is not None:
        u = np.sort(np.concatenate([[0.0, 1.0], np.random.default_rng(spacing_seed).uniform(
            0.0, 1.0, count - 2)]))
    return HOME + np.outer(u, LIFT - HOME)


@pytest.mark.parametrize('retime_path', [False, True])
def test_a_last_point_at_2_to_the_31_seconds_is_refused_at_once(retime_path):
    """Before: numpy asked for 15.6 TiB (a crash), or retiming hung; now a reason at once."""
    plan = planner(retime_path).plan_trajectory(
        [0.0, 1.0, 2.0 ** 31 - 1.0], *waypoints([HOME, LIFT, HOME]))
    assert plan.refusal.code == 'invalid_trajectory'
    assert 'point 2 has time 2147483647.0 s' in plan.reason
    assert f'from 0 to {MAX_TIME:g} s' in plan.reason


@pytest.mark.parametrize('seconds', [1.0, 2.0, 4.0, 6.0, 8.0, 10.0, 60.0, 1e4])
def test_the_5_cm_lift_retimes_to_the_same_duration_however_long_it_was_given(seconds):
    """Before: 1.19 s over 1-4 s, refused ('retiming_failed') over 6, 8, 10 and 60 s."""
    plan = planner(True).plan_trajectory([0.0, seconds], *waypoints([HOME, LIFT]))
    assert plan.accepted and plan.retimed, plan.reason
    reference_plan = planner(True).plan_trajectory([0.0, 1.0], *waypoints([HOME, LIFT]))
    assert plan.trajectory.duration == pytest.approx(reference_plan.trajectory.duration,
                                                     rel=1e-9)
    # Bang-bang in leg space: the leg that moves most travels d with a velocity and an
    # acceleration limit: d / v + v / a if it reaches v (it does: d > v^2 / a).
    travel = np.abs(np.subtract(reference.leg_lengths(LIFT), reference.leg_lengths(HOME))).max()
    fastest = travel / LIMITS.velocity_max + LIMITS.velocity_max / LIMITS.acceleration_max
    assert fastest <= plan.trajectory.duration <= fastest * 1.01


def test_the_5_cm_lift_over_2_to_the_31_seconds_is_refused_not_retimed():
    """Before: 'retimed' to 215,285 s. An absurd time is refused even when retiming."""
    plan = planner(True).plan_trajectory([0.0, 2.0 ** 31], *waypoints([HOME, LIFT]))
    assert plan.refusal.code == 'invalid_trajectory' and 'point 1 has time' in plan.reason


@pytest.mark.parametrize('count', [2, 300, 1000, 10_000])
def test_a_straight_path_retimes_at_any_density(count):
    """Before: 300 waypoints retimed, 1000 refused; a 10,000-point pose_path refused."""
    plan = planner().plan_path(*waypoints(line(count, spacing_seed=count)))
    assert plan.accepted, plan.reason
    two = planner().plan_path(*waypoints(line(2)))
    assert plan.trajectory.duration == pytest.approx(two.trajectory.duration, rel=1e-3)


def test_a_dwell_rests_as_timed_and_is_merged_when_retimed():
    """Before: home, home, home + 1 cm accepted as timed, refused retimed."""
    up = HOME + [0.0, 0.0, 0.01, 0.0, 0.0, 0.0]
    arguments = ([0.0, 1.0, 2.0], *waypoints([HOME, HOME, up]))
    timed = planner().plan_trajectory(*arguments)
    assert timed.accepted, timed.reason
    # As timed: the platform rests at home for the first second (no overshoot).
    rest = timed.trajectory.sample(np.linspace(0.0, 1.0, 101))
    assert_allclose(rest.positions, np.tile(HOME[:3], (101, 1)), rtol=0, atol=1e-15)
    assert_allclose(rest.velocities, 0.0, atol=1e-15)
    assert timed.trajectory.duration == 2.0
    # Retimed: the dwell is merged (a path has no time to rest), as home to home + 1 cm.
    retimed = planner(True).plan_trajectory(*arguments)
    assert retimed.accepted and retimed.retimed, retimed.reason
    direct = planner(True).plan_trajectory([0.0, 1.0], *waypoints([HOME, up]))
    assert retimed.trajectory.duration == pytest.approx(direct.trajectory.duration, rel=1e-9)
    assert retimed.trajectory.path.waypoint_count == 2
    assert list(retimed.trajectory.path.point_indices) == [0, 2]


def slow_waves(duration, count):
    """``count`` waypoints of slow waves about home over ``duration`` seconds."""
    times = np.linspace(0.0, duration, count)
    phase = np.outer(times / duration, [2.0, 3.0, 1.0, 2.0, 3.0, 1.0]) * math.pi
    return PoseTrajectory.from_poses(times, HOME + [0.01, 0.01, 0.01, 0.05, 0.05, 0.05]
                                     * (1.0 - np.cos(phase)))


def test_a_10_to_the_4_second_trajectory_is_checked_with_a_bounded_number_of_samples():
    """Before: 10^7 samples, checked one by one; now at most MAX_PIECE_SAMPLES per segment."""
    trajectory = slow_waves(1e4, 1000)
    plan = plan_motion(trajectory, GEOMETRY, LIMITS)
    assert plan.accepted, plan.reason
    assert plan.check.samples == 999 * MAX_PIECE_SAMPLES + 1
    # Retimed: the same waves at full speed, a few seconds.
    retimed = plan_motion(trajectory, GEOMETRY, LIMITS, retime_path=True)
    assert retimed.accepted and retimed.trajectory.duration < 60.0, retimed.reason


def test_a_trajectory_needing_more_samples_than_a_check_takes_is_refused_before_sampling():
    """10^5 waypoints over 10^6 s: 25.6 million samples; refused, saying how many and why."""
    times = np.linspace(0.0, MAX_TIME, MAX_WAYPOINTS)
    poses = np.tile(HOME, (MAX_WAYPOINTS, 1))
    poses[:, 2] += 0.01 * np.sin(np.linspace(0.0, 50.0, MAX_WAYPOINTS))
    plan = plan_motion(PoseTrajectory.from_poses(times, poses), GEOMETRY, LIMITS)
    assert plan.refusal.code == 'trajectory_too_long'
    assert plan.check.samples == 0 and not plan.check.complete
    assert f'more than the {MAX_CHECK_SAMPLES:,} a check may take' in plan.reason


@pytest.mark.parametrize('times, words', [
    ([], 'at least 2 waypoints, got 0'),
    ([0.0], 'at least 2 waypoints, got 1'),
    ([0.0, math.nan], 'point 1 has time nan s'),
    ([0.0, math.inf], 'point 1 has time inf s'),
    ([-1.0, 1.0], 'point 0 has time -1.0 s'),
    ([0.0, 1e300], 'point 1 has time 1e+300 s'),
    ([0.0, 2.0, 1.0], 'by 1e-09 s at least, got 2 s then 1 s (points 1 and 2)'),
    ([0.0, 1.0, 1.0], 'increase strictly'),
    ([0.0, 5e-324, 1e-323], 'by 1e-09 s at least'),
])
def test_malformed_times_are_refused_with_the_point_and_why(times, words):
    """Non-finite, negative, absurd, non-increasing times, no point, one point."""
    poses = np.tile(HOME, (len(times), 1))
    for retime_path in (False, True):
        plan = planner(retime_path).plan_trajectory(times, *waypoints(poses))
        assert plan.refusal.code == 'invalid_trajectory' and words in plan.reason


@pytest.mark.parametrize('retime_path', [False, True])
def test_positions_and_rates_no_platform_reaches_are_refused(retime_path):
    """1e308 m, or a velocity of 1e6 m/s: no motion of a platform, refused by name."""
    far = np.array([HOME, HOME, HOME])
    far[1, 0] = 1e308
    plan = planner(retime_path).plan_trajectory([0.0, 1.0, 2.0], *waypoints(far))
    assert plan.refusal.code == 'invalid_trajectory'
    assert 'point 1: positions [1e+308, 0.0, 0.4325] m, beyond 1000 m' in plan.reason
    fast = np.zeros((2, 3))
    fast[1, 2] = 1e6
    plan = planner(retime_path).plan_trajectory([0.0, 1.0], *waypoints([HOME, LIFT]), fast,
                                                np.zeros((2, 3)))
    assert 'point 1: velocities' in plan.reason and 'm/s: no motion' in plan.reason


def test_too_many_waypoints_and_empty_paths_are_refused():
    """More than MAX_WAYPOINTS, and paths of no or one distinct pose."""
    plan = planner().plan_trajectory(np.arange(MAX_WAYPOINTS + 1.0),
                                     *waypoints(np.tile(HOME, (MAX_WAYPOINTS + 1, 1))))
    assert plan.refusal.code == 'invalid_trajectory' and 'at most 100,000' in plan.reason
    assert 'got 0' in planner().plan_path(np.zeros((0, 3)), np.zeros((0, 4))).reason
    same = planner().plan_path(*waypoints([HOME, HOME, HOME]))
    assert same.refusal.code == 'invalid_trajectory'
    assert 'at least 2 different poses, got 1 (from 3 waypoints' in same.reason


def test_a_path_along_a_singular_direction_is_refused_as_a_singularity():
    """At the singular yaw, a step along the Jacobian's null space moves no leg."""
    pose = np.array(HOME)
    pose[5] = reference.singular_yaw()
    _, _, right = np.linalg.svd(reference.twist_jacobian(pose))
    null = right[-1]        # twist (v, w) the legs do not feel, base frame
    step = 1e-5
    second = Transform(pose[:3] + step * null[:3], reference.rotation_vector_matrix(
        step * null[3:]) @ reference.rotation_zyx(*pose[3:]))
    start = np.array(HOME)
    start[5] = pose[5] - 0.01
    positions = [start[:3], pose[:3], second.position]
    quaternions = [euler_zyx_to_quaternion(start[3:]), euler_zyx_to_quaternion(pose[3:]),
                   reference_quaternion(second.rotation)]
    plan = MotionPlanner(load_geometry(CONFIG / 'paper_platform.yaml'), LIMITS).plan_path(
        positions, quaternions)
    assert plan.refusal.code == 'retiming_failed'
    assert dict(plan.refusal.details)['cause'] == 'singularity'
    assert 'between points 1 and 2' in plan.reason and 'singularity' in plan.reason


def reference_quaternion(rotation):
    """Quaternion ``(x, y, z, w)`` of a rotation matrix (w > 0 here)."""
    w = math.sqrt(1.0 + np.trace(rotation)) / 2.0
    return [(rotation[2, 1] - rotation[1, 2]) / (4 * w), (rotation[0, 2] - rotation[2, 0])
            / (4 * w), (rotation[1, 0] - rotation[0, 1]) / (4 * w), w]


def test_a_check_and_a_retiming_stop_when_cancelled():
    """A set event stops the work between two steps, with Cancelled (not a refusal)."""
    cancel = threading.Event()
    cancel.set()
    trajectory = slow_waves(100.0, 100)
    with pytest.raises(Cancelled):
        check_trajectory(TimedTrajectory.as_given(trajectory), GEOMETRY, LIMITS, cancel=cancel)
    with pytest.raises(Cancelled):
        retime(trajectory, GEOMETRY, LIMITS, cancel=cancel)
    with pytest.raises(Cancelled):
        plan_motion(trajectory, GEOMETRY, LIMITS, retime_path=True, cancel=cancel)


def test_given_accelerations_make_the_trajectory_c2():
    """With accelerations the curves are quintic: they pass through them, on both sides."""
    rng = np.random.default_rng(3)
    times = np.array([0.0, 1.0, 2.5, 4.0])
    poses = HOME + rng.uniform(-1.0, 1.0, (4, 6)) * [0.01, 0.01, 0.01, 0.05, 0.05, 0.05]
    velocities, angular_velocities, accelerations, angular_accelerations = (
        rng.normal(size=(4, 3)) * scale for scale in (0.005, 0.02, 0.01, 0.05))
    position, quaternion = waypoints(poses)
    plan = planner().plan_trajectory(times, position, quaternion, velocities,
                                     angular_velocities, accelerations, angular_accelerations)
    assert plan.accepted, plan.reason
    assert plan.trajectory.path.degree == 5
    for side in (-1e-9, 1e-9):
        sample = plan.trajectory.sample(times[1:-1] + side)
        assert_allclose(sample.accelerations, accelerations[1:-1], atol=1e-7)
        assert_allclose(sample.angular_accelerations, angular_accelerations[1:-1], atol=1e-7)
    sample = plan.trajectory.sample(times)
    assert_allclose(sample.velocities, velocities, atol=1e-12)
    assert_allclose(sample.angular_velocities, angular_velocities, atol=1e-12)


def test_accelerations_without_velocities_are_refused():
    """A quintic needs the velocities too."""
    plan = planner().plan_trajectory([0.0, 1.0], *waypoints([HOME, LIFT]),
                                     accelerations=np.zeros((2, 3)),
                                     angular_accelerations=np.zeros((2, 3)))
    assert plan.refusal.code == 'invalid_trajectory' and 'need the velocities' in plan.reason


def test_a_tool_frame_trajectory_moves_the_platform_as_the_tool_pose_says():
    """Tool 5 cm above the platform, turned 10 deg: the platform poses are the frames' own."""
    tool = Transform([0.02, -0.01, 0.05], reference.rotation_zyx(0.0, 0.0, math.radians(10.0)))
    frames = FrameTree(tool_frame='tool', tool_pose=tool)
    rng = np.random.default_rng(5)
    tool_poses = HOME + [0.0, 0.0, 0.05, 0.0, 0.0, 0.0] + rng.uniform(-1.0, 1.0, (4, 6)) * [
        0.01, 0.01, 0.01, 0.05, 0.05, 0.05]
    times = [0.0, 2.0, 4.0, 6.0]
    plan = planner(frames=frames).plan_trajectory(times, *waypoints(tool_poses))
    assert plan.accepted, plan.reason
    samples = plan.trajectory.sample(np.array(times))
    for pose, position, rotation in zip(tool_poses, samples.positions, samples.rotations):
        tool_in_base = Transform(pose[:3], reference.rotation_zyx(*pose[3:]))
        expected = tool_in_base @ tool.inverse()
        assert_allclose(position, expected.position, atol=1e-12)
        assert_allclose(rotation, expected.rotation, atol=1e-12)
