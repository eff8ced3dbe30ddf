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
Actuator sizing (dynamics/sizing.py) against values worked out independently.

- A symmetric platform (a semi-regular hexagon, mirror and 3-fold symmetric) lifting a mass
  at constant speed: every leg carries ``m g L / (6 h)`` (``h`` the joints' height apart, ``L``
  the leg's length, both by hand), extends at ``v h / L``, and delivers ``m g v / 6``, the
  rate of the potential energy shared six ways; lowering it, the legs absorb that power.
- The RMS of a sine sampled unevenly is ``A / sqrt(2)`` (time-weighted; the plain mean of the
  samples is not).
- Along the Table 3 ramp with the example masses: the speeds are the central differences of
  the leg lengths, the powers the product of forces and speeds, each peak the largest sample
  at its time.
"""

import math

from hypothesis import given, strategies as st
import numpy as np
from properties import assert_refused, budget, floats, PAPER, poses_near_home
import pytest
from scipy.integrate import quad
from stewart_kinematics import (
    Geometry,
    inverse_kinematics,
    LegBody,
    load_geometry,
    MassProperties,
    matrix_to_euler_zyx,
    PoseTrajectory,
    Ramp,
    RigidBody,
)
from stewart_kinematics.dynamics.sizing import (
    actuator_demands,
    MAX_SAMPLES,
    sample_times,
    time_weighted_rms,
    trajectory_demands,
)

pytestmark = pytest.mark.core

G = 9.80665
#: Base joints on a circle of 0.5 m, platform joints on one of 0.3 m, 20 deg either side of the
#: 0, 120 and 240 deg axes (base) and 50 deg either side of 60, 180, 300 (platform).
BASE_RADIUS, PLATFORM_RADIUS = 0.5, 0.3


def _circle(radius, centres, half):
    angles = np.radians([centre + sign * half for centre in centres for sign in (-1, 1)])
    return np.column_stack([radius * np.cos(angles), radius * np.sin(angles),
                            np.zeros(6)])


def symmetric_geometry():
    """Return a 6-6 platform symmetric under 120 deg turns and a mirror."""
    base = _circle(BASE_RADIUS, (0.0, 120.0, 240.0), 20.0)
    platform = np.roll(_circle(PLATFORM_RADIUS, (60.0, 180.0, 300.0), 50.0), 1, axis=0)
    return Geometry(base, platform, np.array([0.0, 0.0, 0.5, 0.0, 0.0, 0.0]))


def horizontal_distance(geometry):
    """Each leg's horizontal reach (equal for all six), by hand from the joints."""
    reach = geometry.base_joints[:, :2] - geometry.platform_joints[:, :2]
    return np.hypot(reach[:, 0], reach[:, 1])


def test_the_symmetric_platform_is_symmetric():
    geometry = symmetric_geometry()
    np.testing.assert_allclose(horizontal_distance(geometry), horizontal_distance(geometry)[0],
                               rtol=1e-12)


@pytest.mark.parametrize('speed', [0.05, -0.05])
def test_lifting_a_mass_at_constant_speed_on_a_symmetric_platform(speed):
    """Every leg: f = m g L / (6 h), dL/dt = v h / L, power = m g v / 6, all along."""
    mass = 30.0
    geometry = symmetric_geometry()
    masses = MassProperties(payload=RigidBody(mass, [0.0, 0.0, 0.1], name='payload'))
    times = np.linspace(0.0, 2.0, 401)
    heights = 0.5 + speed * times                # the platform joints are at z = 0 in its frame
    poses = np.zeros((times.size, 6))
    poses[:, 2] = heights
    twists = np.zeros((times.size, 6))
    twists[:, 2] = speed
    demands = actuator_demands(geometry, times, poses, twists, np.zeros((times.size, 6)),
                               mass_properties=masses)
    reach = horizontal_distance(geometry)[0]
    lengths = np.hypot(reach, heights)
    force = mass * G * lengths / (6.0 * heights)
    np.testing.assert_allclose(demands.forces, np.repeat(force[:, None], 6, axis=1),
                               rtol=1e-12)
    np.testing.assert_allclose(demands.speeds, np.repeat((speed * heights / lengths)[:, None], 6,
                                                         axis=1), rtol=1e-12)
    np.testing.assert_allclose(demands.powers, mass * G * speed / 6.0, rtol=1e-12)
    rms = math.sqrt(quad(lambda t: (mass * G * math.hypot(reach, 0.5 + speed * t)
                                    / (6.0 * (0.5 + speed * t))) ** 2, 0.0, 2.0)[0] / 2.0)
    for leg in demands.legs:
        # Rising, the legs lean less: the largest push is where the platform is lowest.
        lowest = 0 if speed > 0 else -1
        assert leg.peak_push == pytest.approx(force[lowest], rel=1e-12)
        assert leg.peak_push_time == times[lowest]
        assert leg.peak_pull == 0.0 and leg.peak_pull_time is None
        assert leg.rms_force == pytest.approx(rms, rel=1e-5)   # trapezoids of 400 steps
        assert leg.peak_speed == pytest.approx(abs(speed) * heights[-lowest - 1]
                                               / lengths[-lowest - 1], rel=1e-12)
        assert leg.peak_speed_time == times[-lowest - 1]
        assert leg.peak_power == pytest.approx(mass * G * abs(speed) / 6.0, rel=1e-12)
        assert leg.peak_power_delivered is (speed > 0)


def test_a_platform_under_upward_gravity_only_pulls():
    geometry = symmetric_geometry()
    masses = MassProperties(platform=RigidBody(5.0, name='platform'), gravity=(0.0, 0.0, G))
    times = np.array([0.0, 1.0])
    poses = np.tile(geometry.home_pose, (2, 1))
    demands = actuator_demands(geometry, times, poses, np.zeros((2, 6)), np.zeros((2, 6)),
                               mass_properties=masses)
    for leg in demands.legs:
        assert leg.peak_push == 0.0 and leg.peak_push_time is None
        assert leg.peak_pull > 0.0 and leg.peak_pull_time == 0.0
        assert leg.peak_speed == 0.0 and leg.peak_power == 0.0


def test_rms_of_a_sine_is_known_when_sampled_unevenly():
    """1 + 3 sin(2 pi t) over a period: sqrt(1 + 9 / 2), however densely each half is sampled."""
    first_half = np.linspace(0.0, 0.5, 2001)
    second_half = np.linspace(0.5, 1.0, 51)[1:]
    times = np.concatenate([first_half, second_half])
    values = 1.0 + 3.0 * np.sin(2.0 * np.pi * times)
    assert time_weighted_rms(times, values) == pytest.approx(math.sqrt(5.5), rel=1e-3)
    # A plain mean of the samples weights the dense first half (the sine above 0) 40 times
    # more: not the signal's RMS.
    assert abs(math.sqrt(np.mean(values ** 2)) - math.sqrt(5.5)) > 0.3
    columns = np.column_stack([values, 2.0 * values])
    np.testing.assert_allclose(time_weighted_rms(times, columns),
                               [math.sqrt(5.5), 2.0 * math.sqrt(5.5)], rtol=1e-3)


def table3_trajectory():
    ramp = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])
    return PoseTrajectory.from_poses(np.linspace(0.0, 2.0, 11), ramp.rows)


def example_geometry():
    return load_geometry(['config/paper_platform.yaml', 'config/example_masses.yaml'])


def pose_rows(samples):
    return np.hstack([samples.positions, matrix_to_euler_zyx(samples.rotations)])


def test_along_the_ramp_speeds_are_the_leg_lengths_rate_and_power_is_force_times_speed():
    geometry, trajectory = example_geometry(), table3_trajectory()
    times = sample_times(trajectory.times, 100.0)
    demands = trajectory_demands(geometry, trajectory, times)
    step = 1e-6
    inner = (times > step) & (times < 2.0 - step) & (
        np.min(np.abs(times[:, None] - trajectory.times[None, :]), axis=1) > step)
    ahead = inverse_kinematics(geometry, pose_rows(trajectory.sample(times[inner] + step)))
    behind = inverse_kinematics(geometry, pose_rows(trajectory.sample(times[inner] - step)))
    np.testing.assert_allclose(demands.speeds[inner], (ahead - behind) / (2.0 * step),
                               atol=1e-8)
    np.testing.assert_array_equal(demands.powers, demands.forces * demands.speeds)
    for leg in demands.legs:
        column = leg.leg - 1
        index = int(np.argmax(demands.forces[:, column]))
        assert leg.peak_push == demands.forces[index, column] > 0.0
        assert leg.peak_push_time == times[index]
        assert leg.peak_speed == np.abs(demands.speeds[:, column]).max()
        assert leg.peak_power == np.abs(demands.powers[:, column]).max()
        assert leg.rms_force == pytest.approx(
            time_weighted_rms(times, demands.forces[:, column]), rel=1e-15)
    # Legs 1, 2 and 4 push hardest as the payload stops at the end of the ramp.
    end = trajectory.sample([2.0])
    from stewart_kinematics import leg_forces
    final = leg_forces(geometry, pose_rows(end), np.hstack([end.velocities,
                                                           end.angular_velocities]),
                       np.hstack([end.accelerations, end.angular_accelerations]))[0]
    for leg in (1, 2, 4):
        assert demands.legs[leg - 1].peak_push == pytest.approx(final[leg - 1], rel=1e-12)
        assert demands.legs[leg - 1].peak_push_time == 2.0


def test_sample_times_hold_both_sides_of_each_waypoint():
    """The cubic's acceleration jumps at a waypoint: the sample just before sees the other side."""
    geometry, trajectory = example_geometry(), table3_trajectory()
    times = sample_times(trajectory.times, 10.0)
    assert set(trajectory.times) <= set(times)
    assert np.all(np.diff(times) >= 0.0) and times[0] == 0.0 and times[-1] == 2.0
    demands = trajectory_demands(geometry, trajectory, times)
    # At 0.2 s the ramp stops accelerating from rest: the force jumps by 27 N.
    knot = int(np.searchsorted(times, 0.2))
    before, after = demands.forces[knot - 1], demands.forces[knot]
    assert times[knot - 1] == np.nextafter(0.2, 0.0) and times[knot] == 0.2
    assert np.abs(before - after).max() > 20.0
    nearly = trajectory_demands(geometry, trajectory, [0.2 - 1e-7, 0.2]).forces[0]
    np.testing.assert_allclose(before, nearly, atol=1e-3)
    without = trajectory_demands(geometry, trajectory, np.linspace(0.0, 2.0, 21))
    assert np.abs(without.forces - before).max(axis=1).min() > 1.0   # no sample saw that side


def test_leg_masses_count():
    geometry, trajectory = example_geometry(), table3_trajectory()
    times = sample_times(trajectory.times, 50.0)
    light = geometry.mass_properties.__class__(
        platform=geometry.mass_properties.platform, payload=geometry.mass_properties.payload)
    heavy = trajectory_demands(geometry, trajectory, times)
    without = trajectory_demands(geometry, trajectory, times, mass_properties=light)
    assert isinstance(geometry.mass_properties.leg_lower, LegBody)
    assert np.abs(heavy.forces - without.forces).max() > 1.0


BAD_TIMES = [
    ([0.0, math.nan], 'finite'), ([0.0, math.inf], 'finite'), ([1.0, 0.0], 'go back'),
    ([1.0, 1.0], 'span more than 0'), ([0.0], 'N >= 2'), ([[0.0, 1.0]], 'N >= 2'),
    ('abc', 'times'), (None, 'times'), ([], 'N >= 2'),
]


@pytest.mark.parametrize('times, words', BAD_TIMES)
def test_bad_times_are_refused_naming_them(times, words):
    poses = np.tile(PAPER.home_pose, (2, 1))
    error = assert_refused(lambda: actuator_demands(PAPER, times, poses, np.zeros((2, 6)),
                                                    np.zeros((2, 6))), ['times'])
    assert words in str(error)


@pytest.mark.parametrize('name', ['poses', 'twists', 'accelerations'])
@pytest.mark.parametrize('bad', [math.nan, math.inf, 'wrong shape'])
def test_bad_motions_are_refused_naming_the_argument(name, bad):
    arguments = {'poses': np.tile(PAPER.home_pose, (3, 1)), 'twists': np.zeros((3, 6)),
                 'accelerations': np.zeros((3, 6))}
    if bad == 'wrong shape':
        arguments[name] = arguments[name][:2]
    else:
        arguments[name] = arguments[name].copy()
        arguments[name][1, 2] = bad
    assert_refused(lambda: actuator_demands(PAPER, [0.0, 1.0, 2.0], **arguments), [name])


def test_huge_motions_are_refused_or_finite():
    """A translation at 1e300 m/s leaves the forces static; at 1e308 the power overflows."""
    masses = MassProperties(payload=RigidBody(20.0, name='payload'))
    poses = np.tile(PAPER.home_pose, (2, 1))
    twists = np.zeros((2, 6))
    twists[:, 0] = 1e300
    demands = actuator_demands(PAPER, [0.0, 1.0], poses, twists, np.zeros((2, 6)),
                               mass_properties=masses)
    assert np.all(np.isfinite(demands.powers)) and np.all(np.isfinite(demands.speeds))
    twists[:, 0] = 1e308
    with pytest.raises(ValueError, match='overflow'):
        actuator_demands(PAPER, [0.0, 1.0], poses, twists, np.zeros((2, 6)),
                         mass_properties=masses)
    with np.errstate(all='raise'):   # and never a numpy warning on the way
        with pytest.raises(ValueError, match='overflow'):
            actuator_demands(PAPER, [0.0, 1.0], poses, twists, np.zeros((2, 6)),
                             mass_properties=masses)


@pytest.mark.parametrize('rate', [0.0, -1.0, math.nan, math.inf, True, 'fast', None])
def test_sample_times_refuse_a_bad_rate(rate):
    assert_refused(lambda: sample_times([0.0, 1.0], rate), ['rate'])


def test_sample_times_refuse_too_many_samples():
    with pytest.raises(ValueError, match=f'more than {MAX_SAMPLES:,} samples'):
        sample_times([0.0, 1e6], 1e3)
    assert 'finite' in str(assert_refused(lambda: sample_times([0.0, math.nan], 10.0),
                                          ['knots']))


@pytest.mark.parametrize('values', [[1.0, math.nan], [1.0], 'abc', [[1.0, 2.0, 3.0]]])
def test_rms_refuses_bad_values(values):
    assert_refused(lambda: time_weighted_rms([0.0, 1.0], values), ['values'])


@st.composite
def waypoint_motions(draw):
    """Return 3 to 5 poses near home at random increasing times, and random masses."""
    count = draw(st.integers(3, 5))
    poses = np.array([draw(poses_near_home(position=0.04)) for _ in range(count)])
    steps = [draw(floats(0.2, 2.0)) for _ in range(count - 1)]
    masses = MassProperties(
        platform=RigidBody(draw(floats(0.1, 20.0)), [0.0, 0.0, draw(floats(0.0, 0.3))],
                           name='platform'),
        payload=RigidBody(draw(floats(0.0, 50.0)), [draw(floats(-0.1, 0.1)), 0.0, 0.2],
                          name='payload'),
        leg_lower=LegBody(draw(floats(0.0, 3.0)), 0.2, 0.0))
    return np.concatenate([[0.0], np.cumsum(steps)]), poses, masses


@budget(25)
@given(motion=waypoint_motions(), rate=floats(5.0, 60.0))
def test_peaks_rms_and_power_signs_hold_along_random_motions(motion, rate):
    """
    Each peak is a sample's value, bounds every sample, and happens at its time.

    The RMS lies between the smallest and largest |f|, and is additive over time: the mean
    square over the whole motion is the time-weighted mean of those over two parts.
    """
    knots, poses, masses = motion
    trajectory = PoseTrajectory.from_poses(knots, poses)
    times = sample_times(knots, rate)
    demands = trajectory_demands(PAPER, trajectory, times, mass_properties=masses)
    forces, speeds, powers = demands.forces, demands.speeds, demands.powers
    split = times.size // 2
    for leg in demands.legs:
        f, v, p = forces[:, leg.leg - 1], speeds[:, leg.leg - 1], powers[:, leg.leg - 1]
        assert leg.peak_push >= f.max() and leg.peak_push >= 0.0
        assert leg.peak_pull >= -f.min() and leg.peak_pull >= 0.0
        if leg.peak_push > 0.0:
            assert f[times == leg.peak_push_time].max() == leg.peak_push
        if leg.peak_pull > 0.0:
            assert -f[times == leg.peak_pull_time].min() == leg.peak_pull
        assert leg.peak_speed == np.abs(v).max()
        assert np.abs(v[times == leg.peak_speed_time]).max() == leg.peak_speed
        assert leg.peak_power == np.abs(p).max()
        at_peak = p[times == leg.peak_power_time]
        if leg.peak_power > 0.0:
            assert bool(at_peak[np.abs(at_peak) == leg.peak_power][0] > 0.0) is (
                leg.peak_power_delivered)
        assert np.abs(f).min() * (1 - 1e-12) <= leg.rms_force <= np.abs(f).max() * (1 + 1e-12)
        whole = leg.rms_force ** 2 * (times[-1] - times[0])
        first = time_weighted_rms(times[:split + 1], f[:split + 1]) ** 2 * (
            times[split] - times[0])
        second = time_weighted_rms(times[split:], f[split:]) ** 2 * (times[-1] - times[split])
        assert whole == pytest.approx(first + second, rel=1e-12, abs=1e-12)
