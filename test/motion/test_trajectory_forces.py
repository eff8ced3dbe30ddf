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
Leg forces along trajectories: the check of samples in motion, the retiming, the efforts sent.

The platform is the paper's with config/example_limits.yaml and config/example_masses.yaml
(8 kg platform, 20 kg payload, 2 kg legs). The trajectory is the motion benchmark's 10 s,
100-waypoint wave: retimed without a force limit its dynamic forces reach 144 N while its
static ones stay below 117.4 N, so a leg_force_max of 125 N binds and one of 110 N cannot be
kept at any speed. Every force a test compares against is computed by a direct call of
:func:`stewart_kinematics.leg_forces` on the sampled pose with its twist and acceleration
(``[v, w]`` and ``[dv/dt, dw/dt]``, base frame), not by the code under test.
"""

import math
from pathlib import Path
from unittest import mock

from hypothesis import given, strategies
import numpy as np
from numpy.testing import assert_allclose
import properties  # noqa: F401 (the hypothesis profiles)
import pytest

from stewart_kinematics import (
    ActuatorLimits,
    check_trajectory,
    leg_forces,
    load_geometry,
    plan_motion,
    PoseTrajectory,
)
from stewart_kinematics.model.actuators import ActuatorInterface
from stewart_kinematics.model.rotations import matrix_to_euler_zyx
from stewart_kinematics.motion import retiming, trajectory_check, trajectory_forces
from stewart_kinematics.motion.leg_trajectory import sampled_leg_trajectory
from stewart_kinematics.motion.pose_trajectory import TimedTrajectory
from stewart_kinematics.motion.retiming import retime, RetimingError
from stewart_kinematics.motion.trajectory_forces import force_coefficients

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml']
MASSIVE = load_geometry(FILES + [CONFIG / 'example_masses.yaml'])
MASSLESS = load_geometry(FILES)
LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
#: A push limit the retimed wave breaks without the force constraint (144 N) but its static
#: forces keep (117.4 N at most).
BINDING_MAX = 125.0
#: Dense check of a timing: samples per second.
DENSE_RATE = 5000.0


def wave(duration=10.0, count=100):
    """Build the motion benchmark's 10 s trajectory: 100 waypoints of slow waves around home."""
    times = np.linspace(0.0, duration, count)
    amplitudes = np.array([0.015, 0.015, 0.01, math.radians(4.0), math.radians(4.0),
                           math.radians(7.0)])
    harmonics = np.array([2, 3, 1, 2, 3, 1])
    offsets = amplitudes * (1.0 - np.cos(np.outer(times, harmonics) * math.pi / duration))
    return PoseTrajectory.from_poses(times, MASSIVE.home_pose + offsets)


def direct_forces(geometry, samples):
    """leg_forces of each sample's pose with its twist and acceleration: (M, 6), newtons."""
    poses = np.concatenate([samples.positions, matrix_to_euler_zyx(samples.rotations)], -1)
    twists = np.concatenate([samples.velocities, samples.angular_velocities], -1)
    accelerations = np.concatenate([samples.accelerations, samples.angular_accelerations], -1)
    return leg_forces(geometry, poses, twists, accelerations)


def dense(trajectory, rate=DENSE_RATE):
    """Sample a timed trajectory every 1 / rate seconds, ends included."""
    return trajectory.sample(np.linspace(0.0, trajectory.duration,
                                         int(trajectory.duration * rate) + 1))


@given(strategies.integers(0, 2 ** 32 - 1))
def test_coefficients_give_the_forces_at_any_path_speed_and_acceleration(seed):
    """f(s, sd, sdd) = a sdd + b sd^2 + c to 1e-9 relative, against direct leg_forces calls."""
    rng = np.random.default_rng(seed)
    path = wave().as_path(MASSIVE)
    taus = rng.uniform(path.times[0], path.times[-1], 40)
    scale = rng.uniform(0.01, 10.0)
    speeds, path_accelerations = rng.uniform(-3.0, 3.0, 40), rng.uniform(-30.0, 30.0, 40)
    a, b, c = force_coefficients(MASSIVE, path, taus, scale)
    on_path = path.sample(taus)
    poses = np.concatenate([on_path.positions, matrix_to_euler_zyx(on_path.rotations)], -1)
    first = scale * np.concatenate([on_path.velocities, on_path.angular_velocities], -1)
    second = scale ** 2 * np.concatenate([on_path.accelerations,
                                          on_path.angular_accelerations], -1)
    expected = leg_forces(MASSIVE, poses, first * speeds[:, None],
                          first * path_accelerations[:, None] + second * speeds[:, None] ** 2)
    got = a * path_accelerations[:, None] + b * speeds[:, None] ** 2 + c
    assert_allclose(got, expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max())
    assert_allclose(c, leg_forces(MASSIVE, poses), rtol=0, atol=0)


def test_a_trajectory_too_fast_for_the_force_limit_is_refused_naming_leg_time_and_bound():
    """
    A timing whose dynamic forces break leg_force_max is refused at the first such sample.

    The check names leg_force_max, the legs and the time; the legs and the time are those of
    the first sample, at the validation rate, whose direct forces break the limit; its static
    forces keep it, so it is too fast (with the stretch that brings that sample within), and
    the same trajectory stretched by that factor passes there.
    """
    geometry = MASSIVE.with_limits(leg_force_max=BINDING_MAX)
    timed = retime(wave(), MASSIVE, LIMITS)    # timed without the force limit: 144 N
    check = check_trajectory(timed, geometry, LIMITS)
    assert not check.accepted
    times = timed.sample_times(1000.0)
    forces = direct_forces(geometry, timed.sample(times))
    first = int(np.argmax(np.any(forces > BINDING_MAX, axis=-1)))
    assert check.time == times[first]
    legs = (np.flatnonzero(forces[first] > BINDING_MAX) + 1).tolist()
    assert [violation.leg for violation in check.violations] == legs
    assert {violation.limit for violation in check.violations} == {'leg_force_max'}
    assert_allclose([violation.value for violation in check.violations],
                    forces[first, np.array(legs) - 1], rtol=1e-12)
    assert 'leg_force_max' in check.reason and f't = {times[first]:.4f} s' in check.reason
    assert check.stretch is not None and check.stretch > 1.0
    slower = direct_forces(geometry, timed.stretched(check.stretch * 1.0001).sample(
        np.array([times[first] * check.stretch * 1.0001])))
    assert np.all(slower <= BINDING_MAX)
    plan = plan_motion(timed.path, geometry, LIMITS, retime_path=False)
    assert not plan.accepted


def test_a_timed_trajectory_too_fast_only_for_forces_is_too_fast():
    """
    The wave played in 2 s (no leg speed limits): its forces break 125 N, its static ones not.

    plan_motion refuses it as too_fast naming leg_force_max; played in 10 s it is accepted,
    and without masses the 2 s one is accepted too (no force checked).
    """
    geometry = MASSIVE.with_limits(leg_force_max=BINDING_MAX)
    fast = wave(duration=2.0)
    forces = direct_forces(geometry, dense(TimedTrajectory.as_given(fast), 1000.0))
    assert forces.max() > BINDING_MAX     # what makes it too fast
    plan = plan_motion(fast, geometry, ActuatorLimits())
    assert plan.refusal.code == 'too_fast', plan.reason
    assert 'leg_force_max' in plan.reason and plan.check.stretch > 1.0
    assert plan_motion(wave(duration=10.0), geometry, ActuatorLimits()).accepted
    assert plan_motion(fast, MASSLESS.with_limits(leg_force_max=BINDING_MAX),
                       ActuatorLimits()).accepted


def test_retimed_under_a_binding_force_limit_every_sample_keeps_every_limit():
    """
    Retimed with leg_force_max 125 N: every sample at 5 kHz keeps it, and the leg rates.

    The forces from direct leg_forces calls at 5000 samples a second (five times the
    refinement's rate); the leg velocities and accelerations from leg_states. The timing is
    longer than without the limit, and the limit is reached (within 0.1 %).
    """
    geometry = MASSIVE.with_limits(leg_force_max=BINDING_MAX)
    free = plan_motion(wave(), MASSIVE, LIMITS, retime_path=True)
    plan = plan_motion(wave(), geometry, LIMITS, retime_path=True)
    assert free.accepted and plan.accepted, plan.reason
    assert plan.trajectory.duration > free.trajectory.duration * 1.02
    samples = dense(plan.trajectory)
    forces = direct_forces(geometry, samples)
    assert forces.max() <= BINDING_MAX
    assert forces.max() >= BINDING_MAX * 0.999
    legs = plan.trajectory.legs(geometry, np.linspace(0.0, plan.trajectory.duration,
                                                      int(plan.trajectory.duration * 5000)))
    assert np.abs(legs.velocities).max() <= LIMITS.velocity_max * (1.0 + 1e-6)
    assert np.abs(legs.accelerations).max() <= LIMITS.acceleration_max * (1.0 + 1e-6)
    assert 0.999 < plan.check.peak_force_ratio <= 1.0


def test_retimed_under_a_pull_limit_keeps_it():
    """A pull limit (leg_force_min -20 N) binds too: the retimed forces stay above it."""
    geometry = MASSIVE.with_limits(leg_force_min=-20.0)
    free = plan_motion(wave(), MASSIVE, LIMITS, retime_path=True)
    assert direct_forces(MASSIVE, dense(free.trajectory)).min() < -30.0
    plan = plan_motion(wave(), geometry, LIMITS, retime_path=True)
    assert plan.accepted, plan.reason
    assert direct_forces(geometry, dense(plan.trajectory)).min() >= -20.0


@pytest.mark.parametrize('changes, bound', [({'leg_force_max': 110.0}, 'leg_force_max'),
                                            ({'leg_force_min': -3.0}, 'leg_force_min')])
def test_a_path_whose_static_force_breaks_a_limit_is_refused_naming_leg_and_place(changes,
                                                                                  bound):
    """
    A static force beyond the limit somewhere: refused, naming leg_force, the bound, the legs.

    The legs and the place are checked against the static forces along the path (direct
    leg_forces calls at rest on a fine sampling of it): the legs named break the bound there.
    """
    geometry = MASSIVE.with_limits(**changes)
    with pytest.raises(RetimingError) as raised:
        retime(wave(), geometry, LIMITS)
    error = raised.value
    assert error.cause == 'leg_force'
    message = str(error)
    assert message.startswith(f'leg_force: {bound}')
    assert 'cannot be followed at any speed' in message and 'about t = ' in message
    details = dict(error.details)
    legs = [int(leg) for leg in details['legs'].strip('[]').split(',')]
    time = float(details['time_s'])
    on_path = wave().sample(np.array([time]))
    static = direct_forces(geometry, type(on_path)(
        on_path.positions, on_path.rotations, *(np.zeros((1, 3)),) * 4))[0]
    limit = changes[bound]
    # The time given is where the path parameter is, on the given trajectory's clock (the
    # curves differ a little): the static force there is at the bound to a newton.
    worst = static[np.array(legs) - 1]
    assert np.all(worst > limit - 1.0) if bound == 'leg_force_max' else np.all(
        worst < limit + 1.0)
    plan = plan_motion(wave(), geometry, LIMITS, retime_path=True)
    assert plan.refusal.code == 'retiming_failed' and 'leg_force' in plan.reason


def test_without_masses_no_force_is_computed():
    """Every mass 0 and leg_force_max set: the check, retiming and efforts compute no force."""
    geometry = MASSLESS.with_limits(leg_force_max=1.0)
    with mock.patch.object(trajectory_forces, 'leg_forces',
                           side_effect=AssertionError('forces computed')):
        plan = plan_motion(wave(), geometry, LIMITS, retime_path=True, publish_rate=50.0)
    assert plan.accepted, plan.reason
    assert plan.command.trajectory.efforts is None
    reference_plan = plan_motion(wave(), MASSLESS, LIMITS, retime_path=True)
    assert plan.trajectory.duration == reference_plan.trajectory.duration


def test_efforts_are_the_dynamic_forces_of_the_points():
    """The leg trajectory's efforts equal direct leg_forces at its points (bit for bit)."""
    timed = retime(wave(), MASSIVE, LIMITS)
    points, poses = sampled_leg_trajectory(timed, MASSIVE, ActuatorInterface(), 50.0)
    assert points.efforts.shape == (len(points.times), 6)
    assert_allclose(points.efforts, direct_forces(MASSIVE, timed.sample(points.times)),
                    rtol=0, atol=0)
    plan = plan_motion(wave(), MASSIVE.with_limits(leg_force_max=BINDING_MAX), LIMITS,
                       retime_path=True, publish_rate=50.0)
    assert plan.accepted, plan.reason
    assert plan.command.trajectory.efforts.max() <= BINDING_MAX


def test_efforts_beyond_the_limit_refuse_the_points_sent():
    """A timing whose points sent break leg_force_max is refused naming the point and legs."""
    geometry = MASSIVE.with_limits(leg_force_max=BINDING_MAX)
    fast = wave(duration=2.0)    # 2 s: forces beyond 125 N (see the too_fast test)
    # The check's samples see no force: the efforts of the points sent must still be checked.
    with mock.patch.object(trajectory_check, 'sample_forces',
                           side_effect=lambda geometry, samples: np.zeros(
                               (len(samples.positions), 6))):
        plan = plan_motion(fast, geometry, ActuatorLimits(), publish_rate=50.0)
    assert not plan.accepted
    assert plan.refusal.code == 'out_of_limits'
    assert 'leg_trajectory: effort' in plan.reason and 'leg_force_max' in plan.reason
    point = plan.command.point
    timed = TimedTrajectory.as_given(fast)
    times = timed.sample_times(50.0, max_samples=100_000)    # the points as published
    forces = direct_forces(geometry, timed.sample(times))
    assert point == int(np.argmax(np.any(forces > BINDING_MAX, axis=-1)))


def test_a_singular_sample_breaks_the_force_limit():
    """A sample whose pose has no forces (NaN) breaks the limit rather than pass."""
    geometry = MASSIVE.with_limits(leg_force_max=BINDING_MAX)
    timed = TimedTrajectory.as_given(wave())
    nan_forces = mock.patch.object(trajectory_check, 'sample_forces',
                                   side_effect=lambda geometry, samples: np.full(
                                       (len(samples.positions), 6), np.nan))
    with nan_forces:
        check = check_trajectory(timed, geometry, LIMITS)
    assert not check.accepted and check.time == 0.0 and check.stretch is None


def test_a_place_without_static_forces_is_refused_as_singular():
    """Refuse a path with NaN static forces (a singular pose), naming every leg, not "nan N"."""
    path = wave().as_path(MASSIVE)
    taus = path.times[[3, 4]]
    static = np.full((2, 6), 10.0)
    static[1] = np.nan
    with pytest.raises(RetimingError) as raised:
        retiming._refuse_static_forces(path, path, taus, static, (-math.inf, 100.0))
    message = str(raised.value)
    assert 'leg(s) [1, 2, 3, 4, 5, 6]' in message and 'a singular pose' in message
    assert 'nan' not in message.lower()


def test_the_refinement_stretch_stays_finite_at_a_static_force_on_the_limit():
    """A static force exactly at the limit asks for the capped stretch, not infinity."""
    static = np.array([[100.0, 0.0, 0.0, 0.0, 0.0, 0.0], [50.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    dynamic = np.array([[101.0, 0.0, 0.0, 0.0, 0.0, 0.0], [150.0, 0.0, 0.0, 0.0, 0.0, 0.0]])
    stretch = retiming._force_stretch(static, dynamic, (-math.inf, 100.0))
    assert_allclose(stretch, [retiming.MAX_FORCE_STRETCH, math.sqrt(2.0)], rtol=1e-15)
