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
Every pose the motion cueing commands keeps the limits model and the actuators' speed limits.

Hostile cues (the literature's gains on a platform with 0.05 m/s and 0.25 m/s^2 per leg,
random steps of up to 8 m/s^2 and 0.5 rad/s, at 100 Hz and at a jittered 1 kHz) are checked
here without the package's own checks: the poses by the limits model's array check, the leg
velocities and accelerations by finite differences of the leg lengths written out below.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import ActuatorLimits, inverse_kinematics, load_geometry
from stewart_kinematics.cueing import CueingSettings, MotionCueing
from stewart_kinematics.cueing.cue_limiter import box_least_squares
from stewart_kinematics.limits import check_poses_array

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
G = 9.80665
LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)


@pytest.fixture(scope='module')
def geometry():
    """Load the paper's platform with the example limits."""
    return load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])


def hostile_input(times, seed):
    """Random steps of specific force (+-8 m/s^2 x, y; +-3 z) and angular velocity, 0.2-2 s."""
    rng = np.random.default_rng(seed)
    force = np.tile([0.0, 0.0, G], (times.size, 1))
    rates = np.zeros((times.size, 3))
    start = 0.0
    while start < times[-1]:
        end = start + rng.uniform(0.2, 2.0)
        held = (times >= start) & (times < end)
        force[held] += rng.uniform([-8.0, -8.0, -3.0], [8.0, 8.0, 3.0])
        rates[held] = rng.uniform(-0.5, 0.5, size=3)
        start = end
    return force, rates


def drive(cueing, times, force, rates):
    """Step through every sample; return poses, lengths and the steps."""
    steps = [cueing.step(t, f, w) for t, f, w in zip(times, force, rates)]
    return np.array([s.pose for s in steps]), np.array([s.lengths for s in steps]), steps


def assert_within_every_limit(geometry, times, poses, lengths):
    """Poses by the limits model; leg speeds by finite differences, both ways of timing them."""
    checks = check_poses_array(geometry, poses)
    assert np.all(checks.allowed), f'{np.count_nonzero(~checks.allowed)} poses out of limits'
    assert_allclose(lengths, inverse_kinematics(geometry, poses), atol=1e-9)
    steps = np.diff(times)
    velocities = np.diff(lengths, axis=0) / steps[:, None]
    assert np.max(np.abs(velocities)) <= 0.05 * (1.0 + 1e-9)
    changes = np.abs(np.diff(velocities, axis=0))
    assert np.max(changes / steps[1:, None]) <= 0.25 * (1.0 + 1e-9)
    centred = 0.5 * (steps[1:] + steps[:-1])
    assert np.max(changes / centred[:, None]) <= 0.25 * (1.0 + 1e-9)


@pytest.mark.parametrize('rate, jitter, seed', [(100.0, 0.0, 1), (100.0, 0.0, 2),
                                                (1000.0, 0.6, 3)])
def test_hostile_cues_keep_every_limit(geometry, rate, jitter, seed):
    """The literature's gains on this small platform: scaled and slowed, never out of limits."""
    rng = np.random.default_rng(seed)
    count = int(40.0 * rate) if rate < 500 else int(8.0 * rate)
    steps = (1.0 + jitter * rng.uniform(-1.0, 1.0, size=count)) / rate
    times = np.cumsum(steps)
    force, rates = hostile_input(times, seed)
    cueing = MotionCueing(geometry, CueingSettings(), LIMITS)
    poses, lengths, results = drive(cueing, times, force, rates)
    assert_within_every_limit(geometry, times, poses, lengths)
    assert min(s.workspace_scale for s in results) < 1.0 or rate > 500
    assert min(s.acceleration_scale for s in results) < 1.0
    assert not any(w.code == 'limits_held' for s in results for w in s.warnings)


def test_platform_returns_home_after_hostile_cues(geometry):
    """After 30 s of hostile input and 40 s at rest the platform is home (no freeze)."""
    times = np.arange(1, 7001) * 0.01
    force, rates = hostile_input(times, 7)
    force[times > 30.0] = [0.0, 0.0, G]
    rates[times > 30.0] = 0.0
    cueing = MotionCueing(geometry, CueingSettings(), LIMITS)
    poses, lengths, _ = drive(cueing, times, force, rates)
    assert_within_every_limit(geometry, times, poses, lengths)
    assert np.linalg.norm(poses[-1, :3] - geometry.home_pose[:3]) < 1e-3
    assert np.max(np.abs(poses[-1, 3:] - geometry.home_pose[3:])) < math.radians(0.1)


def test_cue_within_the_limits_is_followed_exactly(geometry):
    """Small, slow cues: the pose is the cue's pose, nothing scaled or slowed."""
    times = np.arange(1, 1001) * 0.01
    force = np.tile([0.0, 0.0, G], (times.size, 1))
    force[:, 0] += 0.5 * np.sin(2.0 * math.pi * 0.5 * times)
    settings = CueingSettings(translation_scale=(0.2, 0.2, 0.2), tilt_scale=(0.1, 0.1))
    cueing = MotionCueing(geometry, settings, LIMITS)
    steps = [cueing.step(t, f, [0.0, 0.0, 0.0]) for t, f in zip(times, force)]
    assert all(s.workspace_scale == 1.0 and s.acceleration_scale == 1.0 for s in steps[1:])
    for step in steps[1:]:
        assert_allclose(step.pose, step.target, atol=1e-12)
        assert_allclose(step.pose, cueing.limiter.cue_poses(
            step.displacement, step.angles), atol=1e-12)


def test_rotation_turns_about_the_head(geometry):
    """A pure tilt cue moves the platform origin so that the head stays put."""
    settings = CueingSettings(head_position=(0.1, 0.0, 0.6))
    cueing = MotionCueing(geometry, settings, LIMITS)
    pose = cueing.limiter.cue_poses(np.zeros(3), np.array([0.05, -0.08, 0.1]))
    rotation = cueing.limiter.home_rotation
    head_home = geometry.home_pose[:3] + rotation @ settings.head_position
    from reference import rotation_zyx
    head_now = pose[:3] + rotation_zyx(*pose[3:]) @ settings.head_position
    assert_allclose(head_now, head_home, atol=1e-15)


def test_without_actuator_limits_the_cue_is_followed(geometry):
    """No leg speed limits: only the workspace scale acts; the pose equals the scaled cue."""
    times = np.arange(1, 1001) * 0.01
    force, rates = hostile_input(times, 4)
    cueing = MotionCueing(geometry, CueingSettings(), ActuatorLimits())
    poses, _, steps = drive(cueing, times, force, rates)
    assert np.all(check_poses_array(geometry, poses).allowed)
    assert all(s.acceleration_scale == 1.0 for s in steps)
    for step in steps[1:]:
        assert_allclose(step.pose, step.target, atol=1e-12)


def test_margins_too_wide_for_the_platform_are_refused(geometry):
    """A stroke margin of 20 cm leaves nothing around home: refused, naming the margins."""
    with pytest.raises(ValueError, match='leg_length_margin'):
        MotionCueing(geometry, CueingSettings(leg_length_margin=0.2), LIMITS)


def test_box_least_squares_matches_scipy():
    """The follower's active-set solver against scipy.optimize.lsq_linear on random boxes."""
    from scipy.optimize import lsq_linear
    rng = np.random.default_rng(11)
    for _ in range(200):
        factor = rng.normal(size=(6, 6)) + 3.0 * np.eye(6)
        metric = factor.T @ factor
        target = rng.normal(size=6)
        lower = rng.uniform(-1.0, 0.0, size=6)
        upper = lower + rng.uniform(0.0, 1.0, size=6)
        ours = box_least_squares(metric, target, lower, upper)
        theirs = lsq_linear(factor, factor @ target, bounds=(lower, upper), tol=1e-14).x
        assert np.all(ours >= lower) and np.all(ours <= upper)
        cost = (ours - target) @ metric @ (ours - target)
        best = (theirs - target) @ metric @ (theirs - target)
        assert cost <= best + 1e-9 * max(1.0, best)


# The follower's per-axis weights.


@pytest.mark.parametrize('weights', [
    (1.0,) * 5, (1.0,) * 7, (1.0, 1.0, 1.0, 1.0, 1.0, 0.0), (1.0, 1.0, -2.0, 1.0, 1.0, 1.0),
    (1.0, 1.0, math.nan, 1.0, 1.0, 1.0), (math.inf,) * 6, (1e308,) * 6, (1e-300,) * 6,
    'weights', None, 3.0, [[1.0] * 6], []])
def test_follower_weights_are_refused_unless_positive_and_finite(geometry, weights):
    """A bad weight is refused naming follower_weights, as a setting and as a parameter."""
    with pytest.raises(ValueError, match=r'^follower_weights must') as refused:
        CueingSettings(follower_weights=weights)
    assert '\n' not in str(refused.value)
    values = {'follower_weights': weights}
    values.update({'leg_velocity_max': 0.05, 'leg_acceleration_max': 0.25})
    with pytest.raises(ValueError, match='follower_weights'):
        MotionCueing.from_parameters(dict(values, **_geometry_values()))


def _geometry_values():
    """Return the paper's platform with the example limits, as parameter values."""
    from stewart_kinematics.parameters import read_parameter_files
    return read_parameter_files([CONFIG / 'paper_platform.yaml',
                                 CONFIG / 'example_limits.yaml'])


def test_twist_metric_costs_each_axis_its_weight(geometry):
    """The leg velocities of a unit twist along axis k cost w_k; across axes, nothing."""
    weights = (2.0, 3.0, 40.0, 0.5, 0.25, 7.0)
    cueing = MotionCueing(geometry, CueingSettings(follower_weights=weights), LIMITS)
    limiter = cueing.limiter
    limiter.pose = geometry.home_pose + np.array([0.01, -0.02, 0.03, 0.05, -0.04, 0.1])
    from stewart_kinematics.model.jacobians import twist_jacobian
    from stewart_kinematics.model.rotations import euler_zyx_to_matrix
    jacobian = twist_jacobian(geometry, limiter.pose[:3], euler_zyx_to_matrix(limiter.pose[3:]))
    legs = jacobian @ np.eye(6)   # column k: the leg velocities of a unit twist along axis k
    assert_allclose(legs.T @ limiter._twist_metric() @ legs, np.diag(weights), atol=1e-9)


def test_a_heavier_weight_keeps_its_axis_closer_to_the_cue(geometry):
    """One step too fast for the legs, along x and z: weighting z keeps z on its way."""
    def followed(weights):
        cueing = MotionCueing(geometry, CueingSettings(follower_weights=weights), LIMITS)
        limited = cueing.limiter.step([0.02, 0.0, 0.02], np.zeros(3), np.zeros(2), 0.01)
        assert limited.acceleration_scale < 1.0
        # The twist taken, against the twist asked (the cue's: 2 m/s along x and z).
        return (limited.pose - geometry.home_pose) / 0.01

    even, heave = followed((1.0,) * 6), followed((1.0, 1.0, 100.0, 1.0, 1.0, 1.0))
    assert heave[2] > 2.0 * even[2] > 0.0
    assert heave[2] / abs(heave[0]) > 5.0 * even[2] / abs(even[0])


def test_weighted_follower_keeps_wrong_way_heave_near_the_unlimited_cue(geometry):
    """
    Issue 31: limiting at the literature's gains keeps wrong-way heave within 10 %.

    Wrong-way heave: seconds during which the force felt at the head along z opposes the
    input's beyond 0.1 m/s^2 (``[0, 0, g]`` removed from both). On the first 7.5 s of the
    mixed drive the unlimited cue (no actuator limits) has 0.44 s; the follower that weighted
    metres and radians alike had 0.60 s (1.36x; 7.47 s against 4.73 s over the whole 60 s,
    ``benchmarks/follower_weights_benchmark.py``); the default weights (heave 30) 0.43 s.
    """
    from stewart_kinematics.cueing import replay
    from stewart_kinematics.cueing.scenarios import scenario
    drive = scenario('mixed_drive')
    samples = slice(0, 751)

    def wrong_way_heave(settings, limits):
        played = replay(MotionCueing(geometry, settings, limits), drive.times[samples],
                        drive.specific_force[samples], drive.angular_velocity[samples])
        wanted = played.specific_force[:, 2] - G
        felt = played.perceived.specific_force[:, 2] - G
        return 0.01 * np.count_nonzero((wanted * felt < 0.0) & (np.abs(felt) > 0.1))

    unlimited = wrong_way_heave(CueingSettings(), ActuatorLimits())
    weighted = wrong_way_heave(CueingSettings(), LIMITS)
    even = wrong_way_heave(CueingSettings(follower_weights=(1.0,) * 6), LIMITS)
    assert unlimited == pytest.approx(0.44, abs=0.02)
    assert weighted <= 1.1 * unlimited
    assert even > 1.2 * unlimited
