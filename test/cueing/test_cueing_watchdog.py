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
MotionCueing's input watchdog and its tool frame at run time, without rclpy.

motion_cueing_node calls :meth:`MotionCueing.watch` on a timer with its clock (the clock of
:meth:`MotionCueing.cue`'s ``command_time``), and :meth:`MotionCueing.set_frames` when a tool
frame parameter changes; these tests drive both with chosen times, as the node's clock would.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
import reference

from stewart_kinematics import FrameTree, Transform
from stewart_kinematics.cueing import CueingSettings, MotionCueing
from stewart_kinematics.cueing.motion_cueing import WATCHDOG_PERIOD
from stewart_kinematics.parameters import read_parameter_file

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                    'motion_cueing.yaml')]
G = 9.80665
REST = [0.0, 0.0, G]
STILL = [0.0, 0.0, 0.0]
#: The node's clock ticks of a 100 Hz input.
PERIOD = 0.01


def make_cueing(**changes):
    """Build the node's core as motion_cueing_node builds it from the shipped files."""
    values = {}
    for path in FILES:
        values.update(read_parameter_file(path, 'motion_cueing_node'))
    values.update(changes)
    return MotionCueing.from_parameters(values)


def lean(cueing, samples=300):
    """Push to the left at 100 Hz, stamps and the node's clock alike; return the last time."""
    for k in range(1, samples + 1):
        step = cueing.cue(k * PERIOD, [0.0, 4.0, G], STILL, k * PERIOD)
        assert step.command.accepted
    assert abs(cueing.pose[1]) > 1e-3
    return samples * PERIOD


def test_no_watchdog_step_while_the_input_flows_or_before_any_input():
    """Before the first sample, and within input_timeout of the last, watch gives nothing."""
    cueing = make_cueing(input_timeout=0.5)
    assert cueing.watchdog_period == WATCHDOG_PERIOD
    assert all(cueing.watch(time) is None for time in np.arange(0.0, 3.0, 0.02))
    last = lean(cueing)
    pose = cueing.pose
    assert all(cueing.watch(last + wait) is None for wait in (0.0, 0.1, 0.49))
    assert_allclose(cueing.pose, pose, rtol=0.0, atol=0.0)


def test_after_input_timeout_the_platform_eases_home_until_it_rests():
    """Lost input: steps at rest on each call, every one within the limits, until it settles."""
    cueing = make_cueing(input_timeout=0.5)
    last = lean(cueing)
    time, steps = last + 0.49, []
    assert cueing.watch(time) is None
    while len(steps) < 20000:
        time += WATCHDOG_PERIOD
        step = cueing.watch(time)
        if step is None:
            break
        assert step.command.accepted and step.refusal is None
        steps.append(step)
    assert steps and cueing.settled()
    # Each step covers the time since the last call, on the node's clock.
    assert [step.command.time for step in steps[:3]] == pytest.approx(
        [last + 0.49 + k * WATCHDOG_PERIOD for k in (1, 2, 3)], abs=1e-9)
    home = cueing.geometry.home_pose
    assert_allclose(steps[-1].pose, home, rtol=0.0, atol=1e-6)
    lengths = np.array([step.command.lengths for step in steps])
    assert np.max(np.abs(np.diff(lengths, axis=0))) / WATCHDOG_PERIOD <= 0.05 * (1 + 1e-6)
    # At rest, it stays quiet: nothing more to send.
    assert cueing.watch(time + 1.0) is None


def test_a_sample_refused_for_its_time_is_no_input():
    """A stream of repeated stamps: refused, and after input_timeout the platform eases home."""
    cueing = make_cueing(input_timeout=0.5)
    last = lean(cueing)
    for k in range(1, 100):   # the same stamp again and again, for a second
        assert cueing.cue(last, [0.0, 4.0, G], STILL, last + k * PERIOD).command is None
    step = cueing.watch(last + 1.0)
    assert step is None   # the first call of the watchdog: no time to cover yet
    step = cueing.watch(last + 1.0 + WATCHDOG_PERIOD)
    assert step is not None and step.command.accepted


def test_a_lost_input_starts_a_new_time_line():
    """One absurd stamp (2^31 s), then the stream: refused until the input is lost, then cued."""
    cueing = make_cueing(input_timeout=0.5)
    last = lean(cueing)
    assert cueing.cue(2.0 ** 31, REST, STILL, last + PERIOD).command.accepted
    assert cueing.cue(last + 2 * PERIOD, REST, STILL, last + 2 * PERIOD).command is None
    cueing.watch(last + 0.6)
    step = cueing.cue(last + 3 * PERIOD, REST, STILL, last + 0.61)
    assert step.command is not None and step.refusal is None


def test_a_sample_refused_for_its_values_still_counts_as_input():
    """Forces of NaN take a step at rest (easing home) and keep the watchdog quiet: input."""
    cueing = make_cueing(input_timeout=0.5)
    last = lean(cueing)
    for k in range(1, 200):
        step = cueing.cue(last + k * PERIOD, [math.nan, 0.0, G], STILL, last + k * PERIOD)
        assert step.refusal.code == 'invalid_vehicle_motion' and step.command.accepted
        assert cueing.watch(last + k * PERIOD + 0.005) is None


def test_input_timeout_zero_turns_the_watchdog_off_and_the_period_follows_the_timeout():
    """Zero: no period, never a step; a short timeout: half of it."""
    cueing = make_cueing(input_timeout=0.0)
    assert cueing.watchdog_period is None
    last = lean(cueing)
    assert all(cueing.watch(last + wait) is None for wait in (1.0, 10.0, 100.0))
    assert make_cueing(input_timeout=0.01).watchdog_period == pytest.approx(0.005)
    assert CueingSettings().input_timeout == 0.5


def test_a_broken_clock_gives_nothing_and_breaks_nothing():
    """Times NaN and inf: None, and the watchdog works on with the next finite time."""
    cueing = make_cueing(input_timeout=0.5)
    last = lean(cueing)
    cueing.watch(last + 1.0)
    for time in (math.nan, math.inf, -math.inf, 'soon', None, [1.0]):
        assert cueing.watch(time) is None
    step = cueing.watch(last + 1.0 + WATCHDOG_PERIOD)
    assert step is not None and step.command.accepted


@pytest.mark.parametrize('value', [-0.1, math.nan, math.inf, 3601.0, 'soon'])
def test_a_bad_input_timeout_is_refused_with_its_name(value):
    """The settings say which setting and what is allowed."""
    with pytest.raises(ValueError, match='input_timeout'):
        CueingSettings(input_timeout=value)


def test_a_tool_frame_set_at_run_time_applies_from_the_next_command():
    """set_frames: target_pose carries the new tool frame's pose; the platform does not jump."""
    cueing = make_cueing()
    first = cueing.cue(0.0, REST, STILL, 0.0)
    home = cueing.geometry.home_pose
    assert_allclose(first.command.tool_pose[0], home[:3], rtol=0.0, atol=1e-12)
    cueing.set_frames(FrameTree(tool_frame='seat', tool_pose=Transform([0.0, 0.0, 0.3],
                                                                       np.eye(3))))
    step = cueing.cue(PERIOD, REST, STILL, PERIOD)
    assert step.command.accepted
    assert_allclose(step.command.tool_pose[0], home[:3] + [0.0, 0.0, 0.3], rtol=0.0, atol=1e-12)
    assert_allclose(step.command.lengths, reference.leg_lengths(home), rtol=0.0, atol=1e-12)
    cueing.set_frames(None)
    step = cueing.cue(2 * PERIOD, REST, STILL, 2 * PERIOD)
    assert_allclose(step.command.tool_pose[0], home[:3], rtol=0.0, atol=1e-12)
