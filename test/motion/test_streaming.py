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

"""Unit tests of stewart_kinematics.motion.streaming: the jerk-limited command filter (ruckig)."""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics import ActuatorLimits, CommandFilter
from stewart_kinematics.limits import LimitModel
from stewart_kinematics.limits.leg_rates import RATE_SLACK

pytestmark = pytest.mark.core

LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
PERIOD = 0.01
HOME = np.array([0.7189, 0.7189, 0.7011, 0.7189, 0.7189, 0.7189])


def run(command_filter, steps):
    """Step the filter; return lengths, velocities, accelerations (steps, 6) and settled."""
    commands = [command_filter.step() for _ in range(steps)]
    return (np.array([command.lengths for command in commands]),
            np.array([command.velocities for command in commands]),
            np.array([command.accelerations for command in commands]),
            [command.settled for command in commands])


def assert_within_limits(lengths, velocities, accelerations, start):
    """Velocity, acceleration and jerk (finite differences) within LIMITS at every step."""
    assert np.abs(velocities).max() <= LIMITS.velocity_max * (1 + 1e-9)
    assert np.abs(accelerations).max() <= LIMITS.acceleration_max * (1 + 1e-9)
    # The commands are consistent with their velocities: positions integrate them.
    lengths = np.vstack([start, lengths])
    speeds = np.abs(np.diff(lengths, axis=0)) / PERIOD
    assert speeds.max() <= LIMITS.velocity_max * (1 + 1e-9)
    jerks = np.abs(np.diff(accelerations, axis=0)) / PERIOD
    assert jerks.max() <= LIMITS.jerk_max * (1 + 1e-6)


def test_a_jump_is_smoothed_and_reached_at_rest():
    """A 5 cm target jump: within limits at every step, all legs arrive together, at rest."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME)
    target = HOME + np.array([0.05, 0.04, 0.03, 0.02, 0.01, 0.0])
    command_filter.set_target(target)
    lengths, velocities, accelerations, settled = run(command_filter, 400)
    assert_within_limits(lengths, velocities, accelerations, HOME)
    first_settled = settled.index(True)
    # 5 cm at 0.05 m/s takes over 1 s; with acceleration and jerk phases about 1.3 s.
    assert 1.0 < first_settled * PERIOD < 2.0
    assert_allclose(lengths[first_settled:], np.tile(target, (400 - first_settled, 1)),
                    atol=1e-12)
    # Time-synchronised: each leg's progress is the same fraction of its own jump.
    progress = (lengths[:first_settled, :5] - HOME[:5]) / (target[:5] - HOME[:5])
    assert_allclose(progress, np.tile(progress[:, :1], (1, 5)), atol=1e-6)


def test_a_target_changed_mid_motion_stays_within_limits_and_converges():
    """Irregular targets, as teleop sends them: within limits throughout, then settles."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME)
    rng = np.random.default_rng(0)
    start = HOME
    for _ in range(8):
        command_filter.set_target(HOME + rng.uniform(-0.03, 0.03, 6))
        lengths, velocities, accelerations, _ = run(command_filter, int(rng.integers(5, 40)))
        assert_within_limits(lengths, velocities, accelerations, start)
        start = lengths[-1]
    final = HOME + 0.01
    command_filter.set_target(final)
    lengths, velocities, accelerations, settled = run(command_filter, 500)
    assert_within_limits(lengths, velocities, accelerations, start)
    assert settled[-1]
    assert_allclose(lengths[-1], final, atol=1e-12)
    assert_allclose(velocities[-1], 0.0, atol=1e-12)


def test_infinite_jerk_is_allowed_but_velocity_and_acceleration_must_be_set():
    """Acceleration-limited motion works; without a velocity limit the filter refuses."""
    command_filter = CommandFilter(ActuatorLimits(0.05, 0.25), PERIOD, HOME)
    command_filter.set_target(HOME + 0.01)
    assert run(command_filter, 200)[3][-1]
    for limits in (ActuatorLimits(acceleration_max=0.25), ActuatorLimits(velocity_max=0.05)):
        with pytest.raises(ValueError, match='leg_velocity_max and leg_acceleration_max'):
            CommandFilter(limits, PERIOD, HOME)


def test_reset_and_bad_input():
    """reset() puts the command at rest; non-finite lengths or periods are refused."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME)
    command_filter.set_target(HOME + 0.02)
    run(command_filter, 10)
    command_filter.reset(HOME)
    command = command_filter.step()
    assert_allclose(command.lengths, HOME)
    assert command.settled
    target = command_filter.set_target([math.nan] * 6)
    assert not target.accepted and target.lengths is None
    assert target.refusal.code == 'invalid_lengths' and '6 finite' in target.reason
    with pytest.raises(ValueError, match='period'):
        CommandFilter(LIMITS, 0.0, HOME)


# A filter that never raises ----------------------------------------------------------------

#: The paper's platform with the stroke of config/example_limits.yaml, 0.65 m to 0.90 m.
GEOMETRY = reference.paper_geometry(leg_length_min=0.65, leg_length_max=0.9)


def assert_every_step_within_every_limit(commands, start, geometry=None):
    """Each given step within the stroke and the rates: the limits model's own check."""
    model = LimitModel(geometry, LIMITS, rate_slack=RATE_SLACK)
    given = [command for command in commands if not command.held]
    lengths = np.array([command.lengths for command in given])
    velocities = np.array([command.velocities for command in given])
    accelerations = np.array([command.accelerations for command in given])
    jerks = np.diff(np.vstack([np.zeros(6), accelerations]), axis=0) / PERIOD
    checks = model.check_leg_states(lengths if geometry else None, velocities, accelerations,
                                    jerks)
    assert checks.allowed.all(), checks.violations(checks.first_refused())
    assert_within_limits(lengths, velocities, accelerations, start)


@pytest.mark.parametrize('distance', [1.0, 1e5, 1e150], ids=['1 m', '100 km', '1e150 m'])
def test_a_far_target_is_approached_at_full_speed_within_the_limits(distance):
    """
    The defect: a far target made ruckig fail (-101) and the node's timer raise.

    Now the filter aims at a point on the straight line toward it, at most the distance of
    10 s at full speed away, and moves at 0.05 m/s, every leg in proportion.
    """
    command_filter = CommandFilter(LIMITS, PERIOD, HOME)
    direction = np.array([1.0, 0.5, 0.2, 0.25, 0.0, 1.0])
    assert command_filter.set_target(HOME + distance * direction).accepted
    commands = [command_filter.step() for _ in range(300)]
    assert all(command.accepted and not command.warnings for command in commands)
    assert_every_step_within_every_limit(commands, HOME)
    last = commands[-1]
    assert_allclose(last.velocities, 0.05 * direction, rtol=1e-9)
    assert not last.settled


def test_targets_that_are_not_lengths_or_leave_the_stroke_are_refused_and_ignored():
    """NaN, inf, zero, the wrong length, text, beyond the stroke: a finding, and no motion."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME, GEOMETRY)
    for target in ([math.nan] * 6, [math.inf] * 6, [0.7] * 5, [0.0] * 6, ['a'] * 6, None):
        refusal = command_filter.set_target(target).refusal
        assert refusal.code == 'invalid_lengths', target
    beyond = HOME.copy()
    beyond[2] = 0.95
    refusal = command_filter.set_target(beyond).refusal
    assert refusal.code == 'out_of_limits' and 'leg 3: leg_length_max 0.9 m' in refusal.message
    assert_allclose(command_filter.target, HOME)
    command = command_filter.step()
    assert_allclose(command.lengths, HOME) and command.settled


def test_random_targets_at_the_ends_of_the_stroke_never_leave_it():
    """Targets at the stroke's ends, changed every few steps mid-motion: every step within."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME, GEOMETRY)
    rng = np.random.default_rng(4)
    commands = []
    for _ in range(150):
        target = np.where(rng.random(6) < 0.5, 0.65, 0.9)
        assert command_filter.set_target(target).accepted
        commands += [command_filter.step() for _ in range(int(rng.integers(1, 150)))]
    assert_every_step_within_every_limit(commands, HOME, GEOMETRY)
    assert min(command.lengths.min() for command in commands) < 0.67
    assert max(command.lengths.max() for command in commands) > 0.88


class FailingRuckig:
    """Stands in for ruckig's generator: raises as ruckig does, for some control interfaces."""

    def __init__(self, generator, failing):
        self.generator, self.failing = generator, failing

    def calculate(self, parameters, trajectory):
        """Raise -101 (ruckig's 'trajectory duration' outcome) where asked, else calculate."""
        if parameters.control_interface.name in self.failing:
            raise ValueError('-101 is not a valid Result.')
        return self.generator.calculate(parameters, trajectory)


def test_a_plan_ruckig_refuses_brakes_to_rest_within_the_limits():
    """No plan toward the target: stream_braking once, then braking steps, to rest."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME, GEOMETRY)
    command_filter.set_target(HOME + 0.03)
    moving = [command_filter.step() for _ in range(60)]
    assert np.max(np.abs(moving[-1].velocities)) > 0.02
    command_filter._generator = FailingRuckig(command_filter._generator, {'Position'})
    command_filter.set_target(HOME - 0.03)
    commands = [command_filter.step() for _ in range(200)]
    assert [finding.code for finding in commands[0].warnings] == ['stream_braking']
    assert commands[0].accepted
    assert all(command.accepted and not command.warnings for command in commands[1:])
    assert_every_step_within_every_limit(moving + commands, HOME, GEOMETRY)
    assert_allclose(commands[-1].velocities, 0.0, atol=1e-12)


def test_when_nothing_can_be_planned_the_last_command_stands():
    """Neither a plan nor braking: stream_held, the state unchanged, and nothing raised."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME, GEOMETRY)
    command_filter.set_target(HOME + 0.03)
    last = [command_filter.step() for _ in range(20)][-1]
    command_filter._generator = FailingRuckig(command_filter._generator,
                                              {'Position', 'Velocity'})
    command_filter.set_target(HOME - 0.03)
    for _ in range(3):
        held = command_filter.step()
        assert held.held and not held.accepted and held.refusal.code == 'stream_held'
        assert_allclose(held.lengths, last.lengths, rtol=0.0, atol=0.0)


# The stream's start and its results as Decisions (issue 28) --------------------------------


def test_the_first_target_accepted_at_a_time_starts_the_sending_there():
    """Not started before; a refused target starts nothing; the first accepted one starts it."""
    command_filter = CommandFilter(LIMITS, PERIOD, GEOMETRY.home_leg_lengths, GEOMETRY)
    assert not command_filter.started
    refused = command_filter.set_target([math.nan] * 6, 5.0)
    assert not refused.accepted and not refused.started and not command_filter.started
    assert not command_filter.set_target(HOME, None).started   # no time: nothing starts
    target = command_filter.set_target(GEOMETRY.home_leg_lengths + 0.01, 5.0)
    assert target.accepted and target.started and command_filter.started
    assert_allclose(target.lengths, GEOMETRY.home_leg_lengths + 0.01, rtol=0.0, atol=0.0)
    # The next targets do not start it again: the first command's step covers 5.0 to 5.01 s.
    assert not command_filter.set_target(GEOMETRY.home_leg_lengths + 0.01, 5.005).started
    command = command_filter.send(5.01)
    assert command.accepted and command.time == 5.01
    # From rest at the jerk limit for 0.01 s: moved j t^3 / 6, at j t^2 / 2.
    assert_allclose(command.lengths - GEOMETRY.home_leg_lengths, 2.5 * 0.01 ** 3 / 6.0,
                    rtol=1e-9)
    assert_allclose(command.velocities, 2.5 * 0.01 ** 2 / 2.0, rtol=1e-9)
    # A reset stops the sending until a target comes at a time again.
    assert command_filter.reset(GEOMETRY.home_leg_lengths).accepted
    assert not command_filter.started
    assert command_filter.set_target(GEOMETRY.home_leg_lengths, 9.0).started


def test_a_filter_without_geometry_takes_targets_at_a_time_but_never_sends():
    """No gate without the geometry: the time is not used; the steps still come."""
    command_filter = CommandFilter(LIMITS, PERIOD, HOME)
    target = command_filter.set_target(HOME + 0.01, 1.0)
    assert target.accepted and not target.started and not command_filter.started
    assert command_filter.step().accepted


def test_steps_and_targets_are_the_shared_decision_result():
    """accepted, reason, refusal, warnings: as every decision of the package answers."""
    from stewart_kinematics.findings import Decision
    command_filter = CommandFilter(LIMITS, PERIOD, HOME)
    target = command_filter.set_target(HOME + 0.01)
    step = command_filter.step()
    assert isinstance(target, Decision) and isinstance(step, Decision)
    assert step.accepted and step.reason == '' and step.warnings == () and not step.held
    refused = command_filter.set_target([0.7] * 5)
    assert refused.reason == refused.refusal.message and refused.lengths is None


@pytest.mark.parametrize('time', [math.nan, math.inf, -math.inf, 'now', None, True, [1.0]])
def test_a_time_that_is_not_a_finite_number_starts_nothing_and_sends_nothing(time):
    """
    set_target takes the target but does not start; send refuses; neither raises.

    Before, a NaN start time was kept by the gate: every later command was refused
    (clock_not_advancing) and the stream never started again.
    """
    command_filter = CommandFilter(LIMITS, PERIOD, GEOMETRY.home_leg_lengths, GEOMETRY)
    target = command_filter.set_target(GEOMETRY.home_leg_lengths + 0.01, time)
    assert target.accepted and not target.started and not command_filter.started
    refused = command_filter.send(time)
    assert refused.refusal.code == 'clock_not_advancing' and not command_filter.started
    with pytest.raises(ValueError, match='finite number of seconds'):
        command_filter.start(time)
    # A good time then starts it, and it moves.
    assert command_filter.set_target(GEOMETRY.home_leg_lengths + 0.01, 1.0).started
    commands = [command_filter.send(1.0 + 0.01 * k) for k in range(1, 20)]
    assert all(command.accepted for command in commands)
    assert np.all(commands[-1].lengths > GEOMETRY.home_leg_lengths)
