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
The fuzzer's oracle of a command stream (fuzzing/stream_rates.py), against the command gate.

Never a false alarm: streams the real :class:`~stewart_kinematics.limits.CommandGate` passed
(hypothesis: any timing, motions at the limits, holds that the gate turns into braking, clock
origins up to 2^31 s, positions read back through actuator offsets) raise nothing but the gate's
own braking commands. And no miss: a hold, a leg 1 % over its velocity, acceleration or jerk
limit, is found, by an independent reckoning of the divided differences. Then the
:class:`~fuzzing.output_invariants.OutputLog` around it: ``joint_commands`` stamped by the
node's clock, a new publisher, the braking allowance.
"""

import random

from fuzzing.output_invariants import OutputInvariants, OutputLog
from fuzzing.stream_rates import (
    allowance_problems,
    braking_allowance,
    LegRateStream,
)
from hypothesis import given, strategies as st
import numpy as np
from properties import budget
import pytest
import reference
from sensor_msgs.msg import JointState

from stewart_kinematics import ActuatorLimits
from stewart_kinematics.limits import CommandGate, MOTION
from stewart_kinematics.model.frames import FrameTree
from stewart_kinematics.parameters import actuator_interface_from_settings, ActuatorSettings

pytestmark = pytest.mark.node

LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
GEOMETRY = reference.paper_geometry(leg_length_min=0.65, leg_length_max=0.90)
HOME = GEOMETRY.home_leg_lengths
NAMES = [f'leg_{leg}' for leg in range(1, 7)]


def gate_stream(seed, steps=300):
    """
    Yield ``(time ns, lengths, braking)`` of a stream the real command gate passed.

    A random walk of leg accelerations at up to 1.2 times the limits, with random intervals
    (jitter, late and early commands), now and then a hold; a command the gate refuses is
    replaced by its braking command, as the nodes do.
    """
    rng = random.Random(seed)
    jerk = rng.random() < 0.7
    gate = CommandGate(GEOMETRY, LIMITS, timing=MOTION, jerk=jerk)
    origin = rng.choice([0, rng.randrange(10 ** 15), 2 ** 31 * 10 ** 9 - rng.randrange(10 ** 12)])
    ns = origin + rng.randrange(10 ** 9, 10 ** 12)
    gate.reset(HOME, time=(ns - origin) * 1e-9)
    period = rng.choice([1e-3, 5e-3, 1e-2, 2e-2])
    scale = rng.choice([0.5, 1.0, 1.0, 1.2])
    acceleration = np.zeros(6)
    yield jerk, origin
    for _ in range(steps):
        interval = period * rng.choice([1.0, 1.0, 0.5, 1.5, 3.0]) * rng.uniform(0.8, 1.2)
        ns += max(1, int(interval * 1e9))
        time = (ns - origin) * 1e-9
        wanted = np.array([rng.uniform(-1.0, 1.0) for _ in range(6)]) * LIMITS.acceleration_max
        change = LIMITS.jerk_max * scale * interval
        acceleration = acceleration + np.clip(wanted * scale - acceleration, -change, change)
        velocity = np.clip(gate.last_velocities + acceleration * interval,
                           -LIMITS.velocity_max * scale, LIMITS.velocity_max * scale)
        lengths = gate.last_lengths + velocity * interval
        if rng.random() < 0.02:
            lengths = gate.last_lengths   # a hold: one step to rest
        command = gate.legs(lengths, time)
        braking = not command.accepted
        if braking:
            command = gate.brake(time, replaced=command.refusal)
        if command.accepted:
            yield ns, command.lengths, braking


@budget(15)
@given(seed=st.integers(0, 2 ** 32 - 1))
def test_a_stream_the_gate_passed_raises_nothing_but_its_braking(seed):
    """Every command the oracle finds beyond a rate is one of the gate's braking commands."""
    commands = gate_stream(seed)
    jerk, origin = next(commands)
    stream = LegRateStream(LIMITS, jerk, (origin * 1e-9, origin * 1e-9))
    offsets = np.full(6, 0.55)
    for ns, lengths, braking in commands:
        read_back = (lengths - offsets) + offsets   # positions on the wire, plus the offsets
        found = stream.add(ns, read_back, offsets)
        assert braking or not found, found
    assert stream.checked > 100


def independent_rates(times, lengths):
    """Divided differences of commands, by the textbook (midpoint spans), in long double."""
    times = np.asarray(times, dtype=np.longdouble)
    lengths = np.asarray(lengths, dtype=np.longdouble)
    steps = np.diff(times)
    velocities = np.diff(lengths, axis=0) / steps[:, None]
    spans = (steps[1:] + steps[:-1]) / 2
    accelerations = np.diff(velocities, axis=0) / spans[:, None]
    thirds = (steps[2:] + steps[1:-1] + steps[:-2]) / 3
    jerks = np.diff(accelerations, axis=0) / thirds[:, None]
    return velocities, accelerations, jerks


@pytest.mark.parametrize('over', ['velocity', 'acceleration', 'jerk'])
def test_a_stream_one_percent_over_a_limit_is_found_where_it_is(over):
    """A leg that passes one rate limit by 1 % between two commands: found at that command."""
    rng = np.random.default_rng(3)
    steps = np.full(60, 0.01) * rng.uniform(0.7, 1.3, 60)
    times_ns = 10 ** 12 + np.cumsum(np.round(steps * 1e9)).astype(np.int64)
    times = (times_ns - 10 ** 12) * 1e-9
    # Leg 3 moves with a jerk of 1.01 times the limit (or speeds up to 1.01 times the others).
    lengths = np.tile(HOME, (60, 1))
    limit = {'velocity': LIMITS.velocity_max, 'acceleration': LIMITS.acceleration_max,
             'jerk': LIMITS.jerk_max}[over] * 1.01
    power = {'velocity': 1, 'acceleration': 2, 'jerk': 3}[over]
    relative = times - times[30]
    lengths[:, 2] += np.where(relative > 0.0, limit * relative ** power / np.prod(
        range(1, power + 1)), 0.0)
    velocities, accelerations, jerks = independent_rates(times, lengths)
    expected = {'velocity': np.abs(velocities[:, 2]) > LIMITS.velocity_max,
                'acceleration': np.abs(accelerations[:, 2]) > LIMITS.acceleration_max,
                'jerk': np.abs(jerks[:, 2]) > LIMITS.jerk_max}[over]
    offset = {'velocity': 1, 'acceleration': 2, 'jerk': 3}[over]
    flagged_at = [index for index, expect in enumerate(expected) if expect]
    assert flagged_at, 'the stream must pass the limit somewhere'
    # The jerk checked only where it is the limit at stake (a ramp of speed or of acceleration
    # starts with a jump of the next derivative).
    stream = LegRateStream(LIMITS, over == 'jerk', (0.0, 2000.0))
    found = [index for index, (ns, row) in enumerate(zip(times_ns, lengths))
             if stream.add(int(ns), row)]
    assert found == [index + offset for index in flagged_at]
    assert all(f'leg 3 {over}' in problem for problem in stream.problems)


def test_a_hold_is_found_and_a_clock_that_goes_back_is_a_new_time_line():
    """Legs at 0.0245 m/s held for one 10 ms step: 2.45 m/s^2; a jump back: nothing checked."""
    stream = LegRateStream(LIMITS, False, (0.0, 0.0))
    lengths = HOME.copy()
    ns = 10 ** 9
    for _ in range(5):   # moving at 0.0245 m/s
        assert stream.add(ns, lengths) == []
        lengths = lengths + 0.000245
        ns += 10 ** 7
    held = stream.add(ns, lengths - 0.000245)   # the same lengths again, 10 ms later
    assert held and 'acceleration -2.45 m/s^2 beyond 0.25' in held[0]
    # Back in time (a simulated clock set back): a new line; the next two are not compared
    # with the commands before the jump.
    assert stream.add(ns - 10 ** 9, HOME + 0.1) == []
    assert stream.add(ns - 10 ** 9 + 10 ** 7, HOME + 0.1) == []
    assert stream.checked == 6 and stream.violations == 1


def test_braking_allowance_counts_braking_and_returning_findings_of_every_status():
    """Rejected and warned, every status: the commands a node said may break a limit."""
    latest = {'/ik_node: command_stream': {'rejected_by_code': {'command_braking': 3,
                                                                'too_fast': 9},
                                           'warned_by_code': {'returning_to_limits': 2}},
              '/ik_node: target_pose': {'rejected_by_code': {}, 'warned_by_code': {
                  'command_braking': 1}}}
    assert braking_allowance(latest) == 6
    assert allowance_problems(6, 6, ['x'], 'stream') == []
    problems = allowance_problems(7, 6, ['one command'], 'stream')
    assert '7 command(s) beyond a limit, more than the 6' in problems[0]
    assert problems[1] == '  one command'


def joint_commands(ns, positions, names=NAMES):
    """Return a joint_commands message stamped ``ns``."""
    message = JointState(name=list(names), position=[float(value) for value in positions])
    message.header.stamp.sec, message.header.stamp.nanosec = divmod(ns, 10 ** 9)
    return message


def test_the_output_log_checks_joint_commands_of_a_streaming_ik_node_by_their_stamps():
    """command_rate makes joint_commands a stream: its stamps time it, a new publisher restarts."""
    actuators = actuator_interface_from_settings(ActuatorSettings(actuator_offsets=(0.5,) * 6))
    invariants = OutputInvariants(GEOMETRY, LIMITS, actuators, FrameTree(), ['joint_commands'])
    assert OutputInvariants(GEOMETRY, LIMITS, actuators, FrameTree()).stream(
        'joint_commands') is None
    log = OutputLog(invariants)
    callback = log.callback('/ns/joint_commands')
    positions = HOME - 0.5
    ns = 5 * 10 ** 9
    for sequence in range(1, 6):
        callback(joint_commands(ns, positions), {'publication_sequence_number': sequence})
        positions = positions + 0.0004   # 0.04 m/s, within the limit
        ns += 10 ** 7
    assert log.problems() == []
    # A node started again sends from home: a new publisher (its numbers start again), no jump.
    callback(joint_commands(ns, HOME - 0.5), {'publication_sequence_number': 1})
    assert log.problems() == []
    # The same publisher jumping 10 mm in 10 ms: 1 m/s.
    callback(joint_commands(ns + 10 ** 7, HOME - 0.49), {'publication_sequence_number': 2})
    problems = log.problems()
    assert problems and '1 command(s) beyond a limit, more than the 0' in problems[0]
    assert 'velocity 1 m/s beyond 0.05 m/s' in problems[1]
    assert log.problems(allowance=1) == []   # one braking command counted by the node
