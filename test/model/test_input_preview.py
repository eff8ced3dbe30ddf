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
How a refusal shows the input it refuses: whole when small, by its size and a preview when large.

Issue 27: one ``leg_lengths`` message of 10^6 values was refused with a reason that echoed every
value (a 5 MB log line, 10 MB in every ``/diagnostics`` array), and so were the twist, command
check and streaming refusals. :func:`stewart_kinematics.model.arrays.preview` is the one way a
message shows an input; here it is tested alone, then through every decision object of the
core, each given an input of 10^6 values (or a string of 10^7 characters): the refusal is one
short line that still says how large the input was. The messages users see for six values
keep every digit.
"""

import math

import numpy as np
import pytest
from reference import HOME, paper_geometry

from stewart_kinematics import (
    ActuatorLimits,
    CommandCheck,
    CommandFilter,
    FrameTree,
    MotionPlanner,
    PoseTracker,
)
from stewart_kinematics.cueing import MotionCueing
from stewart_kinematics.model.arrays import preview, PREVIEW_MAX

pytestmark = pytest.mark.core

#: Values in an oversized input, and characters in an oversized string.
HUGE = 10 ** 6
LONG = 10 ** 7
#: Longest refusal accepted for an oversized input: a few hundred characters.
SHORT = 600
#: The size as the message must say it.
HUGE_WORDS = '1,000,000 values'
LONG_WORDS = '10,000,000 characters'
LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)


@pytest.fixture(scope='module')
def geometry():
    """Build the paper's platform."""
    return paper_geometry()


@pytest.fixture(scope='module')
def home_lengths(geometry):
    """Return the leg lengths at home, metres."""
    return geometry.home_leg_lengths


def assert_short_and_sized(text, size_words):
    """Check that the text is one short line that says the input's size."""
    assert len(text) <= SHORT, f'{len(text)} characters: {text[:300]}...'
    assert '\n' not in text
    assert size_words in text, text


# The helper alone -----------------------------------------------------------------------------

def test_small_inputs_are_shown_whole_with_every_digit():
    values = [0.1 + 0.2, 1e-17, math.nan, -math.inf, 0.7071067811865476, 1e308]
    assert preview(values) == '[0.30000000000000004, 1e-17, nan, -inf, 0.7071067811865476, 1e+308]'
    assert preview(np.array(values)) == preview(values)
    assert preview(np.eye(3)) == '[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]'
    assert preview((1.5,)) == '(1.5,)' and preview('map') == "'map'" and preview(None) == 'None'


@pytest.mark.filterwarnings('ignore::PendingDeprecationWarning')   # np.matrix
def test_a_large_array_shows_its_first_values_and_its_size():
    assert preview(np.arange(HUGE, dtype=float)) == (
        '[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, ...] (1,000,000 values)')
    assert preview(np.zeros((1000, 6))) == (
        '[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, ...] (shape (1000, 6): 6,000 values)')
    assert preview(list(range(25))) == '[0, 1, 2, 3, 4, 5, ...] (25 values)'
    assert preview(np.matrix(np.ones((1, 100)))).endswith('(shape (1, 100): 100 values)')


def test_a_long_string_shows_its_start_and_its_length():
    text = preview('x' * LONG)
    assert text == repr('x' * 60) + '... (10,000,000 characters)'
    names = preview(['leg_1'] * 10 ** 5)
    assert names == "['leg_1', 'leg_1', 'leg_1', 'leg_1', 'leg_1', 'leg_1', ...] (100,000 values)"


@pytest.mark.parametrize('value', [
    ['y' * LONG] * 24, [[0.5] * HUGE] * 24, {index: 'z' * LONG for index in range(100)},
    10 ** 100_000, np.full((100, 100, 100), math.nan)], ids=[
    'long strings', 'long rows', 'dict', 'huge integer', '3-d array'])
def test_a_preview_is_never_longer_than_its_bound(value):
    assert len(preview(value)) <= PREVIEW_MAX


def test_deep_nesting_is_cut_without_recursion():
    nested = [0.5]
    for _ in range(100_000):   # repr() of this raises RecursionError
        nested = [nested]
    assert preview(nested) == '[[[[...] (1 value)]]]'


class CountingSequence(list):
    """A list that counts the elements read from it."""

    reads = 0

    def __getitem__(self, index):
        """Count each element read."""
        CountingSequence.reads += 1
        return super().__getitem__(index)

    def __iter__(self):
        """Count the elements read by iteration too."""
        for index in range(len(self)):
            yield self[index]


def test_a_preview_reads_only_what_it_shows():
    CountingSequence.reads = 0
    assert HUGE_WORDS in preview(CountingSequence([0.25] * HUGE))
    assert CountingSequence.reads <= 6


# Every decision object, given an input of a million values ------------------------------------

def test_command_check_refusals_of_huge_inputs_are_short(geometry):
    check = CommandCheck(geometry)
    huge = np.full(HUGE, 0.5)
    assert check.pose(np.array([0.0, 0.0, 0.43]), np.eye(3)).accepted
    refusals = [
        check.pose_vector(huge), check.pose_vector(huge.tolist()),
        check.tool_pose(huge, (0.0, 0.0, 0.0, 1.0)),
        check.tool_pose((0.0, 0.0, 0.43), np.full((HUGE // 4, 4), math.nan)),
        check.twist(huge), check.twist(huge.tolist())]
    for command in refusals:
        assert not command.accepted
        assert_short_and_sized(command.reason, '1,000,000' if command is not refusals[2] else
                               '(1000000,)')
    wrong_frame = check.tool_pose((0.0, 0.0, 0.43), (0.0, 0.0, 0.0, 1.0), FrameTree(),
                                  'f' * LONG)
    assert wrong_frame.refusal.code == 'wrong_frame'
    assert_short_and_sized(wrong_frame.reason, LONG_WORDS)


def test_the_twist_refusal_of_six_values_keeps_every_digit(geometry):
    check = CommandCheck(geometry)
    assert check.pose_vector(list(HOME)).accepted
    twist = [0.1, math.nan, 1e-300, 0.30000000000000004, -0.0, 2.5]
    assert str(twist) in check.twist(twist).reason


def test_pose_tracker_refusals_of_huge_inputs_are_short(geometry, home_lengths):
    tracker = PoseTracker(geometry)
    huge = np.full(HUGE, 0.7)
    assert_short_and_sized(tracker.update(huge).reason, '(1000000,)')
    assert_short_and_sized(tracker.twist(huge).reason, HUGE_WORDS)
    estimate = tracker.update(home_lengths, huge)
    assert estimate.accepted
    assert_short_and_sized(estimate.warnings[-1].message, HUGE_WORDS)


def test_streaming_refusal_of_huge_lengths_is_short(home_lengths):
    command_filter = CommandFilter(LIMITS, 0.01, home_lengths)
    refusal = command_filter.set_target(np.full(HUGE, 0.7)).refusal
    assert refusal.code == 'invalid_lengths'
    assert_short_and_sized(refusal.message, HUGE_WORDS)


def test_cueing_refusals_of_huge_inputs_are_short(geometry):
    cueing = MotionCueing(geometry)
    rate = (0.0, 0.0, 0.0)
    refused = cueing.cue('t' * LONG, (0.0, 0.0, 9.81), rate)
    assert_short_and_sized(refused.refusal.message, LONG_WORDS)
    ragged = [[0.0] * HUGE, [1.0]]
    refused = cueing.cue(0.0, ragged, rate)
    assert refused.refusal.code == 'invalid_vehicle_motion'
    assert_short_and_sized(refused.refusal.message, HUGE_WORDS)


def test_planner_refusals_of_huge_inputs_are_short(geometry):
    planner = MotionPlanner(geometry, LIMITS)
    positions = np.tile(HOME[:3], (3, 1))
    quaternions = np.tile([0.0, 0.0, 0.0, 1.0], (3, 1))
    plan = planner.plan_path(positions, quaternions, 'f' * LONG)
    assert plan.refusal.code == 'invalid_trajectory'
    assert_short_and_sized(plan.reason, LONG_WORDS)
    plan = planner.plan_trajectory([0.0, 1.0, 2.0], positions, quaternions, frame_id='f' * LONG)
    assert_short_and_sized(plan.reason, LONG_WORDS)
    plan = planner.plan_trajectory(np.arange(HUGE, dtype=float), np.tile(HOME[:3], (HUGE, 1)),
                                   np.tile([0.0, 0.0, 0.0, 1.0], (HUGE, 1)))
    assert not plan.accepted and len(plan.reason) <= SHORT and '1,000,000' in plan.reason
