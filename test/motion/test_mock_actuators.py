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
The simulated legs of mock_platform: the lag, every limit at every step, faults, trajectories.

Expected values are worked out by hand in each test (the exponential of the lag, the steps
of a leg at its velocity or acceleration limit, the Hermite and quintic blending weights at a
quarter of a segment); the limits are checked at every step of random command sequences.
"""

import math

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose, assert_array_equal
from properties import budget
import pytest
from reference import HOME, paper_geometry

from stewart_kinematics import findings, inverse_kinematics, leg_forces, leg_velocities
from stewart_kinematics.dynamics import MassProperties, RigidBody
from stewart_kinematics.motion.mock_actuators import (
    braking_speed,
    check_lengths,
    lag_step,
    leg_selection,
    LegLimits,
    LegState,
    LegTrajectoryCommand,
    MockActuators,
    SimulatedForces,
    trajectory_command,
)

pytestmark = pytest.mark.core

NAMES = ('leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5', 'leg_6')
#: The example limits of config/example_limits.yaml.
EXAMPLE = LegLimits(0.65, 0.90, 0.05, 0.25)
START = np.full(6, 0.70)


def run(state, target, steps, dt, tau, limits, stalled=None):
    """Return the states of ``steps`` lag steps toward ``target``, the first one included."""
    states = [state]
    for _ in range(steps):
        states.append(lag_step(states[-1], target, dt, tau, limits, stalled))
    return states


def test_without_rate_limits_the_legs_follow_the_exact_first_order_response():
    """With tau = 0.1 s, 10 steps of 0.01 s toward +0.1 m: the error is 0.1 e^-1 = 0.0367879 m."""
    states = run(LegState.at_rest(START), START + 0.1, 10, 0.01, 0.1, LegLimits(0.5, 1.0))
    assert_allclose(states[1].lengths, START + 0.1 * (1.0 - math.exp(-0.1)), atol=1e-15)
    assert_allclose(0.8 - states[10].lengths, 0.0367879441171, atol=1e-12)
    # The velocity of the first step is its move over the step.
    assert_allclose(states[1].velocities, 0.1 * (1.0 - math.exp(-0.1)) / 0.01, atol=1e-12)


def test_with_a_zero_time_constant_the_legs_move_at_their_velocity_limit():
    """With tau = 0, 0.05 m/s, steps of 0.01 s: 0.5 mm a step, 0.75 m after 100 steps."""
    limits = LegLimits(0.65, 0.90, 0.05, math.inf)
    states = run(LegState.at_rest(START), START + 0.1, 100, 0.01, 0.0, limits)
    assert_allclose(states[1].lengths, START + 0.0005, atol=1e-15)
    assert_allclose(states[100].lengths, START + 0.05, atol=1e-12)
    assert_allclose(states[100].velocities, 0.05, atol=1e-12)


def test_the_acceleration_limit_ramps_the_velocity_and_the_leg_stops_at_its_target():
    """0.25 m/s^2, steps of 0.01 s: 2.5 mm/s more each step; then a stop without overshoot."""
    limits = LegLimits(0.65, 0.90, math.inf, 0.25)
    states = run(LegState.at_rest(START), START + 0.02, 200, 0.01, 0.0, limits)
    assert_allclose(states[1].velocities, 0.0025, atol=1e-15)
    assert_allclose(states[2].velocities, 0.005, atol=1e-15)
    assert_allclose(states[2].lengths, START + 0.0025 * 0.01 + 0.005 * 0.01, atol=1e-15)
    lengths = np.array([state.lengths for state in states])
    velocities = np.array([state.velocities for state in states])
    assert lengths.max() <= 0.72 + 1e-12
    assert_allclose(lengths[-1], 0.72, atol=1e-9)
    assert np.abs(np.diff(velocities, axis=0)).max() <= 0.25 * 0.01 * (1 + 1e-9)


def test_a_leg_running_into_the_stroke_end_brakes_before_it():
    """A command beyond the stroke: the leg stops at the end, within the acceleration limit."""
    state = LegState(np.full(6, 0.88), np.full(6, 0.05), np.zeros(6))
    states = run(state, np.full(6, 5.0), 200, 0.01, 0.0, EXAMPLE)
    lengths = np.array([state.lengths for state in states])
    velocities = np.array([state.velocities for state in states])
    assert lengths.max() <= 0.90
    assert_allclose(lengths[-1], 0.90, atol=1e-6)
    assert np.abs(np.diff(velocities, axis=0)).max() <= 0.25 * 0.01 * (1 + 1e-9)


def test_the_braking_speed_stops_a_leg_within_its_distance():
    """Brake from v = sqrt((a dt)^2 + 2 a d) - a dt: 0.1 m at 0.25 m/s^2 and 0.01 s."""
    assert_allclose(braking_speed(0.1, 0.25, 0.01), math.sqrt(0.0025 ** 2 + 0.05) - 0.0025,
                    atol=1e-15)
    assert braking_speed(0.0, 0.25, 0.01) == 0.0
    assert braking_speed(math.inf, 0.25, 0.01) == math.inf
    assert_allclose(braking_speed(0.1, math.inf, 0.01), 10.0)


@budget(40)
@given(st.lists(st.tuples(st.lists(st.floats(0.5, 1.1), min_size=6, max_size=6),
                          st.integers(1, 60), st.floats(1e-4, 0.1), st.floats(0.0, 0.5)),
                min_size=1, max_size=6),
       st.floats(0.005, 1.0), st.floats(0.05, 20.0))
def test_every_step_keeps_the_stroke_velocity_and_acceleration(commands, velocity_max,
                                                               acceleration_max):
    """Random commands (some beyond the stroke), steps and lags: every limit at every step."""
    limits = LegLimits(0.65, 0.90, velocity_max, acceleration_max)
    state = LegState.at_rest(START)
    for target, steps, dt, tau in commands:
        for _ in range(steps):
            new = lag_step(state, target, dt, tau, limits)
            assert np.all(new.lengths >= 0.65) and np.all(new.lengths <= 0.90)
            assert np.abs(new.velocities).max() <= velocity_max * (1 + 1e-9)
            assert np.abs(new.velocities - state.velocities).max() <= (
                acceleration_max * dt * (1 + 1e-9) + 1e-12)
            state = new


def test_a_stalled_leg_stops_where_it_is_and_the_others_go_on():
    """Leg 2 stalled: its length and zero velocity stay; leg 1 reaches the command."""
    limits = LegLimits(0.65, 0.90)
    stalled = np.array([False, True, False, False, False, False])
    states = run(LegState.at_rest(START), START + 0.05, 50, 0.01, 0.02, limits, stalled)
    assert all(state.lengths[1] == 0.70 and state.velocities[1] == 0.0 for state in states)
    assert_allclose(states[-1].lengths[0], 0.75, atol=1e-9)
    legs = MockActuators(limits, START, 0.02)
    legs.set_stalled(leg_selection('leg_2', NAMES))
    legs.command_lengths(START + 0.05)
    for step in range(51):
        legs.advance(step * 0.01)
    assert legs.state.lengths[1] == 0.70 and legs.state.lengths[0] > 0.74


def test_the_noise_has_the_asked_deviation_the_bias_is_exact_and_the_seed_repeats():
    """20,000 samples of 2 mm noise on a 1 mm bias: mean and deviation within statistics."""
    legs = MockActuators(EXAMPLE, START, 0.05)
    legs.set_bias([0.001, 0.0, 0.0, 0.0, 0.0, -0.001])
    legs.set_noise(0.002, 7)
    samples = np.array([legs.measure() for _ in range(20000)])
    errors = samples - START - legs.bias
    # The mean's standard error is 0.002 / sqrt(20000) = 1.4e-5 m: within 5 of them.
    assert np.abs(errors.mean(axis=0)).max() < 7.1e-5
    # The deviation's relative standard error is 1 / sqrt(2 * 20000) = 0.5 %: within 3 %.
    assert_allclose(errors.std(axis=0), 0.002, rtol=0.03)
    legs.set_noise(0.002, 7)
    assert_array_equal(np.array([legs.measure() for _ in range(3)]), samples[:3])
    legs.set_noise(0.0, 7)
    assert_array_equal(legs.measure(), START + legs.bias)
    with pytest.raises(ValueError, match='noise'):
        legs.set_noise(math.nan, 1)
    with pytest.raises(ValueError, match='bias'):
        legs.set_bias([1e308] * 6)


def test_a_trajectory_interpolates_linearly_cubically_or_quintically():
    """A quarter into a segment from a to b: 0.25, 0.15625 and 0.103515625 of the way."""
    a, b = START, START + 0.1
    times, lengths = np.array([0.0, 1.0]), np.array([a, b])
    zeros = np.zeros((2, 6))
    linear = LegTrajectoryCommand(10.0, times, lengths)
    cubic = LegTrajectoryCommand(10.0, times, lengths, zeros)
    quintic = LegTrajectoryCommand(10.0, times, lengths, zeros, zeros)
    for command, share in ((linear, 0.25), (cubic, 0.15625), (quintic, 0.103515625)):
        assert_allclose(command.sample(10.25), a + share * 0.1, atol=1e-15)
        assert_allclose(command.sample(9.0), a, atol=0)
        assert_allclose(command.sample(12.0), b, atol=0)
    # A cubic with velocities: the slope at the start is the given velocity.
    sloped = LegTrajectoryCommand(0.0, times, lengths, np.array([np.full(6, 0.2), np.zeros(6)]))
    assert_allclose((sloped.sample(1e-6) - a) / 1e-6, 0.2, atol=1e-5)


def test_a_trajectory_starts_from_the_legs_state_before_its_first_point():
    """First point at 1 s: from the legs at 0.70 m (0 s) to 0.76 m; a third of the way at 1/3 s."""
    command = LegTrajectoryCommand(5.0, np.array([1.0, 2.0]), np.array([START + 0.06,
                                                                        START + 0.08]))
    started = command.started(5.0, LegState.at_rest(START))
    assert_allclose(started.sample(5.0 + 1.0 / 3.0), START + 0.02, atol=1e-15)
    assert command.started(6.5, LegState.at_rest(START)) is command


def test_the_legs_follow_a_trajectory_and_a_newer_command_replaces_it():
    """No lag, no limits: the legs are on the interpolation; a set point ends the trajectory."""
    legs = MockActuators(LegLimits(0.5, 1.0), START, 0.0)
    legs.advance(0.0)
    command, refusal = trajectory_command(1.0, [0.0, 1.0], [START, START + 0.1], now=0.0)
    assert refusal is None
    legs.command_trajectory(command)
    for time in (0.5, 1.0, 1.25, 1.5):
        legs.advance(time)
    assert_allclose(legs.state.lengths, START + 0.05, atol=1e-12)
    # A second trajectory from 1.75 s: the first runs until then, then this one.
    second, _ = trajectory_command(1.75, [0.0, 1.0], [START + 0.0, START + 0.02], now=1.5)
    legs.command_trajectory(second)
    legs.advance(1.6)
    assert_allclose(legs.state.lengths, START + 0.06, atol=1e-12)
    legs.advance(1.75)
    legs.advance(2.25)
    # From the legs at 1.75 s (0.075 m up) to the first point (0.0 up) at 1.75 s: already on it.
    assert_allclose(legs.state.lengths, START + 0.01, atol=1e-12)
    assert legs.command_lengths(START + 0.03) is None
    legs.advance(2.3)
    legs.advance(5.0)
    assert_allclose(legs.state.lengths, START + 0.03, atol=1e-12)
    assert legs.trajectory is None and legs.pending is None


@pytest.mark.parametrize('lengths, words', [
    ([0.7] * 5, 'must hold 6 lengths'),
    ([0.7] * 7, 'must hold 6 lengths'),
    ([0.7] * 5 + [math.nan], 'must be finite'),
    ([0.7] * 5 + [math.inf], 'must be finite'),
    ([0.7] * 5 + [1e308], 'leg 6 length 1e\\+308 m is outside the stroke'),
    ([0.7] * 5 + [0.6], 'leg 6 length 0.6 m is outside the stroke \\[0.65, 0.9\\] m'),
])
def test_a_bad_command_is_refused_and_the_legs_keep_the_last_valid_one(lengths, words):
    """NaN, inf, 1e308, a wrong count, a length beyond the stroke: refused with the reason."""
    legs = MockActuators(EXAMPLE, START, 0.0)
    assert legs.command_lengths(START + 0.01) is None
    refusal = legs.command_lengths(lengths)
    assert refusal.code == findings.INVALID_LEG_COMMAND
    assert refusal.message == refusal.message.splitlines()[0]
    import re
    assert re.search(words, refusal.message), refusal.message
    assert_array_equal(legs.set_point, START + 0.01)
    assert check_lengths(START, EXAMPLE) is None


@pytest.mark.parametrize('arguments, words', [
    ({'times': [], 'lengths': np.zeros((0, 6))}, 'no point'),
    ({'times': [0.0, 0.0]}, 'increase strictly: point 1'),
    ({'times': [0.0, math.nan]}, 'must be finite'),
    ({'times': [0.0, 2e6]}, 'must be finite, in \\[0, 1e\\+06\\]'),
    ({'lengths': [[0.7] * 6, [math.nan] * 6]}, 'positions must be finite'),
    ({'lengths': [[0.7] * 6, [1e308] * 6]}, 'point 1: leg 1 length 1e\\+308'),
    ({'velocities': [[0.0] * 6, [1e308] * 6]}, 'velocities must be within'),
    ({'velocities': [[0.0] * 6]}, 'velocities must be 6 per point for 2'),
    ({'accelerations': [[0.0] * 6] * 2}, 'accelerations need velocities'),
    ({'start': math.inf}, 'start time must be finite'),
    ({'start': 0.0, 'now': 5.0}, 'ended 4 s ago'),
])
def test_a_bad_trajectory_is_refused_with_the_reason(arguments, words):
    """Every malformed trajectory is refused, in one line naming what is wrong."""
    values = {'start': 10.0, 'times': [0.0, 1.0], 'lengths': [[0.7] * 6, [0.75] * 6],
              'limits': EXAMPLE, 'now': 10.0}
    values.update(arguments)
    command, refusal = trajectory_command(**values)
    assert command is None and refusal.code == findings.INVALID_LEG_COMMAND
    import re
    assert re.search(words, refusal.message), refusal.message


def test_a_clock_that_jumps_or_goes_back_never_makes_a_leg_jump():
    """Back: the legs hold; 1e9 s ahead: one max_time_step of motion; NaN: hold."""
    legs = MockActuators(LegLimits(0.5, 1.0, 0.05, 0.25), START, 0.0, max_time_step=0.1)
    legs.command_lengths(START + 0.1)
    assert legs.advance(100.0) is None
    assert legs.advance(100.01) is None
    before = legs.state.lengths.copy()
    warning = legs.advance(99.0)
    assert warning.code == findings.CLOCK_JUMP and 'went back' in warning.message
    assert_array_equal(legs.state.lengths, before)
    assert legs.advance(99.0) is None       # a paused clock: no step, no warning
    assert_array_equal(legs.state.lengths, before)
    warning = legs.advance(1e9)
    assert warning.code == findings.CLOCK_JUMP and 'max_time_step' in warning.message
    # At most 0.1 s at 0.25 m/s^2 from 0.0025 m/s: under 0.5 mm more.
    assert np.all(legs.state.lengths - before <= 0.0025 * 0.1 + 0.25 * 0.1 * 0.1 + 1e-12)
    assert legs.advance(math.nan).code == findings.CLOCK_JUMP


def test_legs_are_named_by_joint_name_or_number():
    """'leg_2, 5' stalls legs 2 and 5; an unknown word is refused naming it."""
    assert leg_selection('leg_2, 5', NAMES) == (1, 4)
    assert leg_selection('  ', NAMES) == ()
    with pytest.raises(ValueError, match="'leg_7' is neither a joint name"):
        leg_selection('leg_7', NAMES)


def test_the_initial_lengths_must_be_within_the_stroke():
    """Legs cannot start outside their stroke."""
    with pytest.raises(ValueError, match='initial leg lengths.*outside the stroke'):
        MockActuators(EXAMPLE, np.full(6, 0.5), 0.05)


def test_the_forces_at_rest_at_home_are_the_static_forces_of_the_payload():
    """20 kg 0.1 m above the platform's origin, at home: the forces of doc/dynamics.md."""
    geometry = paper_geometry().with_mass_properties(
        MassProperties(payload=RigidBody(20.0, [0.0, 0.0, 0.1], name='payload')))
    forces = SimulatedForces(geometry)
    assert not forces.massless and SimulatedForces(paper_geometry()).massless
    lengths, _ = forces.forces(LegState.at_rest(geometry.home_leg_lengths), 0.01)
    assert_allclose(lengths, [32.91, 33.73, 32.81, 33.39, 33.52, 32.95], atol=0.006)
    assert_allclose(geometry.home_pose, HOME, atol=1e-12)


@budget(30)
@given(st.lists(st.one_of(
    st.tuples(st.just('time'), st.one_of(st.floats(-1e9, 1e9), st.just(math.nan),
                                         st.floats(0.0, 0.05))),
    st.tuples(st.just('lengths'), st.lists(st.one_of(st.floats(0.5, 1.1), st.just(math.nan),
                                                     st.just(1e308)), min_size=5, max_size=7)),
    st.tuples(st.just('trajectory'), st.lists(st.floats(0.6, 0.95), min_size=6, max_size=6),
              st.floats(-1.0, 2.0), st.floats(0.01, 2.0))), min_size=1, max_size=60))
def test_no_command_or_clock_moves_a_leg_beyond_a_limit_or_one_step(events):
    """Commands (some absurd), trajectories and clocks that jump, go back or read NaN."""
    limits = LegLimits(0.65, 0.90, 0.05, 0.25)
    legs = MockActuators(limits, START, 0.05, max_time_step=0.1)
    now = 0.0
    legs.advance(now)
    for event in events:
        before = legs.state
        if event[0] == 'time':
            # Mostly small steps forward, some absolute jumps anywhere, some NaN.
            now = now + event[1] if 0.0 <= event[1] <= 0.05 else event[1]
            legs.advance(now)
        elif event[0] == 'lengths':
            legs.command_lengths(event[1])
        else:
            command, _ = trajectory_command(now + event[2], [0.0, event[3]],
                                            [legs.state.lengths, event[1]], limits=limits,
                                            now=now)
            if command is not None:
                legs.command_trajectory(command)
        after = legs.state
        assert np.all(after.lengths >= 0.65) and np.all(after.lengths <= 0.90)
        assert np.abs(after.velocities).max() <= 0.05 * (1 + 1e-9)
        assert np.abs(after.lengths - before.lengths).max() <= 0.05 * 0.1 * (1 + 1e-9)
        assert np.abs(after.velocities - before.velocities).max() <= 0.25 * 0.1 * (1 + 1e-9)


def test_the_forces_of_a_lift_accelerating_upward_weigh_as_in_a_stronger_gravity():
    """
    A payload lifted at 2 m/s^2: the forces of the rigid payload at rest under g + 2 m/s^2.

    The legs' lengths and velocities are those of a pure vertical translation
    ``z = z0 + a t^2 / 2`` at two instants 0.01 s apart; the twist's change over the step is
    then exactly ``a``. Without rotation, accelerating up at ``a`` loads the legs as standing
    still under gravity ``g + a`` would (no leg mass: no other term).
    """
    payload = RigidBody(20.0, [0.0, 0.0, 0.1], name='payload')
    geometry = paper_geometry().with_mass_properties(MassProperties(payload=payload))
    heavier = paper_geometry().with_mass_properties(MassProperties(
        payload=payload, gravity=[0.0, 0.0, -(9.80665 + 2.0)]))
    forces = SimulatedForces(geometry)
    results = []
    for time in (0.5, 0.51):
        pose = np.array(HOME) + [0.0, 0.0, 0.5 * 2.0 * time ** 2, 0.0, 0.0, 0.0]
        twist = [0.0, 0.0, 2.0 * time, 0.0, 0.0, 0.0]
        state = LegState(inverse_kinematics(geometry, pose),
                         leg_velocities(geometry, pose, twist))
        results.append(forces.forces(state, 0.01))
    (_, problem), (lifted, problem_after) = results
    assert problem is None and problem_after is None
    assert_allclose(lifted, leg_forces(heavier, pose), atol=1e-6)
    assert np.all(lifted > leg_forces(geometry, pose) + 1.0)


def test_hold_stops_the_legs_at_rest_and_forgets_the_clock_and_the_commands():
    """A running trajectory and a moving leg: hold stops both; the next advance only sets time."""
    legs = MockActuators(EXAMPLE, START, 0.0)
    legs.advance(0.0)
    command, _ = trajectory_command(0.0, [0.0, 1.0], [START, START + 0.04], limits=EXAMPLE,
                                    now=0.0)
    legs.command_trajectory(command)
    for step in range(1, 31):
        legs.advance(step * 0.01)
    moving = legs.state.lengths.copy()
    assert np.all(moving > START) and np.all(legs.state.velocities > 0.0)
    legs.hold()
    assert_array_equal(legs.state.velocities, 0.0)
    assert legs.trajectory is None and legs.pending is None
    assert legs.advance(1000.0) is None        # no step across the time held
    legs.advance(1000.5)
    assert_array_equal(legs.state.lengths, moving)
