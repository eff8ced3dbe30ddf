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
Property tests of motion: trajectories pass their waypoints, plans keep every limit, refusals.

A trajectory passes through its waypoints; a plan that is accepted keeps, at every sample,
the pose limits (as CommandCheck says) and the leg velocity and acceleration limits; leg
trajectories are the inverse kinematics of the samples; the command filter never exceeds
its limits and settles on its target; the Ramp's rows step evenly from start to end. Hostile
waypoints, times, rates and targets are refused naming what is wrong.
"""

import math

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose
from properties import (
    assert_refused,
    budget,
    covers,
    floats,
    HOME_POSE,
    LIMITED,
    NON_FINITE,
    NOT_NUMBERS,
    NUMPY_WORDS,
    pose_distance,
    poses_near_home,
    with_bad_entry,
)
import pytest

from stewart_kinematics import (
    ActuatorInterface,
    ActuatorLimits,
    check_trajectory,
    CommandCheck,
    CommandFilter,
    euler_zyx_to_matrix,
    FilteredCommand,
    inverse_kinematics,
    leg_trajectory,
    LegTrajectory,
    MotionPlan,
    plan_motion,
    PoseTrajectory,
    Ramp,
    retime,
    TimedTrajectory,
    TrajectoryCheck,
)

pytestmark = pytest.mark.core

ACTUATOR_LIMITS = ActuatorLimits(0.05, 0.25, 2.5)
#: Relative slack on a leg limit between samples and rounding.
LIMIT_SLACK = 1e-6


def waypoints(min_size=2, max_size=5, spread=0.03):
    """Draw (times, poses): increasing times 0.2 to 2 s apart, poses near home."""
    steps = st.lists(floats(0.2, 2.0), min_size=min_size - 1, max_size=max_size - 1)
    return steps.flatmap(lambda gaps: st.tuples(
        st.just(np.concatenate([[0.0], np.cumsum(gaps)])),
        st.lists(poses_near_home(position=spread, angle=math.radians(5.0)),
                 min_size=len(gaps) + 1, max_size=len(gaps) + 1).map(np.array)))


def within_limits(poses):
    """Return whether every pose is one CommandCheck accepts (the public limits)."""
    check = CommandCheck(LIMITED)
    return all(check.pose_vector(pose).accepted for pose in poses)


@covers('PoseTrajectory', 'TimedTrajectory')
@budget(30)
@given(waypoints())
def test_a_trajectory_passes_through_its_waypoints(data):
    times, poses = data
    path = PoseTrajectory.from_poses(times, poses)
    assert path.waypoint_count == len(times)
    samples = path.sample(times)
    for k, pose in enumerate(poses):
        assert pose_distance(np.concatenate([samples.positions[k], _angles(
            samples.rotations[k])]), pose) < 1e-9
    timed = TimedTrajectory.as_given(path, 0.5)
    assert timed.duration == pytest.approx(2.0 * (times[-1] - times[0]))
    clock = timed.sample_times(50.0)
    assert clock[0] == 0.0 and clock[-1] == timed.duration and np.all(np.diff(clock) > 0)
    assert timed.stretched(3.0).duration == pytest.approx(3.0 * timed.duration)
    middle = timed.sample(clock)
    assert np.all(np.isfinite(middle.positions)) and np.all(np.isfinite(middle.velocities))


def _angles(rotation):
    from stewart_kinematics import matrix_to_euler_zyx
    return matrix_to_euler_zyx(rotation)


@covers('PoseTrajectory', 'TimedTrajectory')
@budget(40)
@given(waypoints(), st.one_of(NOT_NUMBERS, NON_FINITE), st.data())
def test_bad_waypoints_and_times_are_refused_naming_them(data, bad, draw):
    times, poses = data
    bad_times = bad if not isinstance(bad, float) else draw.draw(with_bad_entry(times, bad))
    assert_refused(lambda: PoseTrajectory.from_poses(bad_times, poses), ('times',))
    bad_poses = bad if not isinstance(bad, float) else draw.draw(with_bad_entry(poses, bad))
    assert_refused(lambda: PoseTrajectory.from_poses(times, bad_poses),
                   ('poses', 'positions', 'rotations', 'Euler angles'))
    assert_refused(lambda: PoseTrajectory.from_poses(times[::-1], poses), ('times',))
    path = PoseTrajectory.from_poses(times, poses)
    for value in (bad, 0.0, -1.0, 2.0):
        assert_refused(lambda: TimedTrajectory.as_given(path, value), ('speed_scale',))
        assert_refused(lambda: TimedTrajectory.as_given(path).sample_times(value)
                       if value != 2.0 else TimedTrajectory.as_given(path).sample_times(-2.0),
                       ('rate',))


@covers('plan_motion', 'MotionPlan', 'check_trajectory', 'TrajectoryCheck', 'retime')
@budget(8)
@given(waypoints(max_size=4, spread=0.05), st.booleans())
def test_an_accepted_plan_keeps_every_limit_at_every_sample(data, retime_path):
    times, poses = data
    path = PoseTrajectory.from_poses(times, poses)
    plan = plan_motion(path, LIMITED, ACTUATOR_LIMITS, retime_path=retime_path)
    assert isinstance(plan, MotionPlan)
    if not plan.accepted:
        assert plan.trajectory is None and plan.reason
        assert plan.refusal.code in ('out_of_limits', 'too_fast', 'retiming_failed')
        return
    check = check_trajectory(plan.trajectory, LIMITED, ACTUATOR_LIMITS)
    assert isinstance(check, TrajectoryCheck) and check.accepted, check.reason
    clock = plan.trajectory.sample_times(200.0)
    samples = plan.trajectory.sample(clock)
    poses_at = np.concatenate([samples.positions, _angles(samples.rotations)], axis=1)
    assert within_limits(poses_at[::5])
    legs = plan.trajectory.legs(LIMITED, clock)
    assert np.max(np.abs(legs.velocities)) <= ACTUATOR_LIMITS.velocity_max * (1 + LIMIT_SLACK)
    assert np.max(np.abs(legs.accelerations)) <= ACTUATOR_LIMITS.acceleration_max * (
        1 + LIMIT_SLACK)
    if retime_path:
        assert plan.retimed
        timed = retime(path, LIMITED, ACTUATOR_LIMITS)
        assert timed.duration > 0.0


@covers('retime', 'plan_motion', 'check_trajectory')
@budget(20)
@given(waypoints(max_size=3), st.one_of(NOT_NUMBERS, NON_FINITE,
                                        st.sampled_from([0.0, -0.5, 1.5])))
def test_bad_planning_options_are_refused_naming_them(data, bad):
    times, poses = data
    path = PoseTrajectory.from_poses(times, poses)
    assert_refused(lambda: retime(path, LIMITED, ActuatorLimits()), ('leg_velocity_max',))
    assert_refused(lambda: plan_motion(path, LIMITED, ACTUATOR_LIMITS, speed_scale=bad),
                   ('speed_scale',))
    if bad != 1.5:   # a rate of 1.5 Hz is coarse, not wrong
        assert_refused(lambda: plan_motion(path, LIMITED, ACTUATOR_LIMITS, validation_rate=bad),
                       ('validation_rate', 'rate'))
        assert_refused(lambda: check_trajectory(TimedTrajectory.as_given(path), LIMITED,
                                                validation_rate=bad), ('validation_rate', 'rate'))


@covers('leg_trajectory', 'LegTrajectory', 'ActuatorInterface')
@budget(20)
@given(waypoints(max_size=4), st.tuples(*[floats(0.0, 0.7)] * 6), floats(5.0, 200.0))
def test_a_leg_trajectory_is_the_inverse_kinematics_of_the_samples(data, offsets, rate):
    times, poses = data
    timed = TimedTrajectory.as_given(PoseTrajectory.from_poses(times, poses))
    actuators = ActuatorInterface(offsets=np.array(offsets))
    legs = leg_trajectory(timed, LIMITED, actuators, rate)
    assert isinstance(legs, LegTrajectory) and legs.joint_names == actuators.joint_names
    assert legs.times[0] == 0.0 and legs.times[-1] == pytest.approx(timed.duration)
    samples = timed.sample(legs.times)
    expected = inverse_kinematics(LIMITED, np.concatenate(
        [samples.positions, _angles(samples.rotations)], axis=1)) - np.array(offsets)
    assert_allclose(legs.positions, expected, rtol=0, atol=1e-9)
    assert legs.velocities.shape == legs.accelerations.shape == legs.positions.shape
    assert_refused(lambda: leg_trajectory(timed, LIMITED, actuators, 0.0), ('rate',))


@covers('CommandFilter', 'FilteredCommand', 'ActuatorLimits')
@budget(20)
@given(poses_near_home(position=0.03, angle=0.1), floats(0.001, 0.02))
def test_the_command_filter_keeps_its_limits_and_settles_on_the_target(pose, period):
    start = LIMITED.home_leg_lengths
    target = inverse_kinematics(LIMITED, pose)
    command_filter = CommandFilter(ACTUATOR_LIMITS, period, start)
    command_filter.set_target(target)
    previous = np.array(start)
    for _ in range(int(20.0 / period)):
        command = command_filter.step()
        assert isinstance(command, FilteredCommand)
        assert np.all(np.abs(command.velocities) <= ACTUATOR_LIMITS.velocity_max * 1.0001)
        assert np.all(np.abs(command.accelerations) <= ACTUATOR_LIMITS.acceleration_max * 1.0001)
        assert np.all(np.abs(command.lengths - previous) <= ACTUATOR_LIMITS.velocity_max
                      * period * 1.0001 + 1e-12)
        previous = command.lengths
        if command.settled:
            break
    assert command.settled
    assert_allclose(command.lengths, target, rtol=0, atol=1e-9)


@covers('CommandFilter', 'StreamTarget')
@budget(30)
@given(st.one_of(NOT_NUMBERS, NON_FINITE.map(lambda value: [value] * 6), st.just([0.7] * 5)),
       st.one_of(NOT_NUMBERS, NON_FINITE, st.sampled_from([0.0, -0.01])))
def test_the_command_filter_refuses_bad_targets_and_periods(lengths, period):
    command_filter = CommandFilter(ACTUATOR_LIMITS, 0.01, LIMITED.home_leg_lengths)
    for target in (command_filter.set_target(lengths), command_filter.reset(lengths)):
        refusal = target.refusal
        assert not target.accepted and refusal.code == 'invalid_lengths', refusal
        assert 'target lengths' in refusal.message
        assert not any(words in refusal.message for words in NUMPY_WORDS), refusal.message
    assert_refused(lambda: CommandFilter(ACTUATOR_LIMITS, period, LIMITED.home_leg_lengths),
                   ('period',))
    assert_refused(lambda: CommandFilter(ActuatorLimits(), 0.01, LIMITED.home_leg_lengths),
                   ('leg_velocity_max',))
    assert_allclose(command_filter.target, LIMITED.home_leg_lengths)


@covers('Ramp')
@budget(40)
@given(poses_near_home(), st.tuples(*[st.one_of(st.just(0.0), floats(1e-4, 0.01),
                                                floats(-0.01, -1e-4))] * 6).filter(any),
       st.integers(1, 20))
def test_a_ramp_steps_evenly_from_start_to_end(start, step, count):
    step = np.array(step)
    ramp = Ramp(start, step, start + count * step)
    rows = ramp.rows
    assert rows.shape == (count + 1, 6)
    assert_allclose(rows[0], start, atol=0)
    assert_allclose(np.diff(rows, axis=0), np.tile(step, (count, 1)), rtol=0, atol=1e-12)
    assert_allclose(rows[-1], start + count * step, rtol=0, atol=1e-12)
    sampled = ramp.sample([0.0, 1.0], 1.0)
    assert_allclose(sampled[0], start, atol=1e-12)
    assert_allclose(sampled[-1], rows[-1], atol=1e-12)


@covers('Ramp')
@budget(40)
@given(poses_near_home(), st.one_of(NOT_NUMBERS, NON_FINITE), st.data())
def test_a_ramp_of_bad_values_is_refused(start, bad, data):
    step = np.full(6, 0.001)
    end = start + 10 * step
    bad_end = bad if not isinstance(bad, float) else data.draw(with_bad_entry(end, bad))
    assert_refused(lambda: Ramp(start, step, bad_end), ('end',))
    uneven = end.copy()
    uneven[0] += 0.0005
    assert_refused(lambda: Ramp(start, step, uneven), ('X', 'axis', 'steps'))
    assert_refused(lambda: Ramp(start, step, end).sample([0.0], bad if isinstance(
        bad, float) else 'x'), ('duration',))
    assert HOME_POSE.shape == (6,) and euler_zyx_to_matrix(start[3:]).shape == (3, 3)
