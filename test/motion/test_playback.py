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
Unit tests of RampPlayback (motion/playback.py): what trajectory_node's ramp publishes when.

The ramp is the paper's Table 3 typed in test/reference.py; the poses played are compared
with its rows, and with the straight line from its first row to its last, as the messages'
numbers (position and quaternion) the gate's verdicts carry. The node's timer is stood in for
by calls at chosen times.
"""

import math

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose
from properties import budget
import pytest
import reference
from reference import quaternion_from_euler

from stewart_kinematics import FrameTree, Transform
from stewart_kinematics.motion.playback import RampPlayback
from stewart_kinematics.motion.ramp import Ramp, RampSchedule
from stewart_kinematics.parameters import RampSettings

pytestmark = pytest.mark.core

TABLE3 = np.array(reference.TABLE_3)
GEOMETRY = reference.paper_geometry()
RAMP = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                       [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])


def playback(mode='table', loop=False, duration=10.0, **arguments):
    """Return a RampPlayback of Table 3 on the paper's platform."""
    schedule = RampSchedule(RAMP, mode, row_period=1.0, publish_rate=50.0, duration=duration,
                            loop=loop)
    return RampPlayback(schedule, GEOMETRY, **arguments)


def assert_message_pose(command, pose, tolerance=1e-12):
    """Check the verdict is accepted and its message numbers are ``pose`` (x, y, z, w)."""
    assert command.accepted, command.reason
    position, quaternion = command.tool_pose
    assert_allclose(position, pose[:3], rtol=0.0, atol=tolerance)
    expected = quaternion_from_euler(*pose[3:])
    if np.dot(quaternion, expected) < 0.0:
        expected = -expected
    assert_allclose(quaternion, expected, rtol=0.0, atol=tolerance)


def test_table_mode_gives_the_11_rows_in_order_then_is_over():
    """One row per tick whatever the time; the 11th says the playing is over."""
    player = playback()
    answers = [player.next_pose(time) for time in (5.0, 5.0, 7.0, -1.0, math.nan, 0.0, 1e9,
                                                   2.0, 3.0, 4.0, 5.0)]
    for (command, over), row in zip(answers, TABLE3):
        assert_message_pose(command, row)
    assert [over for _, over in answers] == [False] * 10 + [True]
    assert player.finished


def test_a_looping_table_wraps_back_to_the_first_row_and_is_never_over():
    """Loop: the 12th pose is row 0 again, and 30 ticks never end the playing."""
    player = playback(loop=True)
    answers = [player.next_pose(float(tick)) for tick in range(30)]
    for tick, (command, over) in enumerate(answers):
        assert_message_pose(command, TABLE3[tick % 11])
        assert not over
    assert not player.finished


def test_interpolate_mode_samples_the_straight_line_at_the_time_asked():
    """Each pose is start + (t / duration) (end - start); the one at the duration is the end."""
    player = playback('interpolate', duration=2.0)
    player.start(100.0)
    for elapsed in (0.0, 0.013, 0.5, 1.25, 1.999):
        command, over = player.next_pose(100.0 + elapsed)
        assert_message_pose(command, TABLE3[0] + elapsed / 2.0 * (TABLE3[-1] - TABLE3[0]),
                            1e-12)
        assert not over
    command, over = player.next_pose(102.0)
    assert_message_pose(command, TABLE3[-1])
    assert over and player.finished


def test_interpolate_mode_past_the_end_holds_the_last_pose_and_before_the_start_the_first():
    """A late tick gives the end (and ends the pass); an early one (a clock set back) the start."""
    player = playback('interpolate', duration=2.0, loop=True)
    player.start(10.0)
    command, over = player.next_pose(9.0)
    assert_message_pose(command, TABLE3[0])
    command, over = player.next_pose(50.0)
    assert_message_pose(command, TABLE3[-1])
    assert not over   # looping: the next pass starts at 50 s
    command, _ = player.next_pose(51.0)
    assert_message_pose(command, TABLE3[0] + 0.5 * (TABLE3[-1] - TABLE3[0]))


def test_a_non_finite_time_plays_the_start_of_the_pass():
    """A broken clock's NaN or inf never reaches the ramp's sampling (which refuses it)."""
    player = playback('interpolate', duration=2.0)
    for time in (math.nan, math.inf, -math.inf):
        command, over = player.next_pose(time)
        assert_message_pose(command, TABLE3[0])
        assert not over
    for time in ('now', None, [1.0]):
        with pytest.raises(ValueError, match='a time must be a number of seconds'):
            player.next_pose(time)


def test_a_tool_frame_moves_the_poses_checked_but_not_the_numbers_sent():
    """The rows are the tool frame's: sent as they are; checked at the platform pose they give."""
    tool = Transform([0.0, 0.0, 0.05], np.eye(3))
    frames = FrameTree(tool_frame='tool', tool_pose=tool)
    player = playback(frames=frames)
    command, _ = player.next_pose(0.0)
    assert_message_pose(command, TABLE3[0])
    # The platform frame sits 5 cm below the tool frame (no rotation at row 0).
    assert_allclose(command.position, TABLE3[0][:3] - [0.0, 0.0, 0.05], rtol=0.0, atol=1e-12)
    assert_allclose(command.lengths, reference.leg_lengths(TABLE3[0] - [0, 0, 0.05, 0, 0, 0]),
                    rtol=0.0, atol=1e-12)


def test_a_tool_frame_set_at_run_time_that_breaks_a_limit_refuses_the_pose_and_goes_on():
    """A new tool frame: the next pose is checked with it; refused, then the ramp goes on."""
    limited = reference.paper_geometry(leg_length_min=0.65, leg_length_max=0.9)
    player = RampPlayback(RampSchedule(RAMP), limited)
    assert player.check() is None
    player.set_frames(FrameTree(tool_pose=Transform([0.0, 0.0, -0.3], np.eye(3))))
    command, over = player.next_pose(0.0)
    assert not command.accepted and command.refusal.code == 'out_of_limits'
    assert not over
    player.set_frames(None)
    command, _ = player.next_pose(1.0)
    assert_message_pose(command, TABLE3[1])


def test_the_check_before_playing_names_the_failing_samples_with_the_frames():
    """A ramp a tool frame pushes out of the stroke is refused whole, before anything plays."""
    limited = reference.paper_geometry(leg_length_min=0.65, leg_length_max=0.9)
    player = RampPlayback(RampSchedule(RAMP), limited,
                          FrameTree(tool_pose=Transform([0.0, 0.0, -0.3], np.eye(3))))
    refusal = player.check()
    assert refusal.code == 'out_of_limits' and 'ramp' in refusal.message
    assert RampPlayback(RampSchedule(RAMP), limited).check() is None


def test_it_starts_once_enough_subscribers_listen():
    """min_subscribers and start_delay come from the ramp settings."""
    player = RampPlayback.from_settings(
        RampSettings(min_subscribers=2, start_delay=0.25), GEOMETRY)
    assert [player.may_start(count) for count in (0, 1, 2, 3)] == [False, False, True, True]
    assert player.start_delay == 0.25 and player.plays and player.period == 1.0
    off = RampPlayback.from_settings(RampSettings(mode='off'), GEOMETRY)
    assert not off.plays


@budget(20)
@given(st.lists(st.floats(-1e6, 1e6), min_size=1, max_size=40), st.booleans())
def test_interpolated_poses_always_lie_on_the_ramp(times, loop):
    """Whatever the ticks' times, every pose is on the segment from the first row to the last."""
    player = playback('interpolate', duration=3.0, loop=loop)
    player.start(0.0)
    direction = TABLE3[-1] - TABLE3[0]
    for time in times:
        command, _ = player.next_pose(time)
        position = command.tool_pose[0]
        s = float((position - TABLE3[0][:3]) @ direction[:3] / (direction[:3] @ direction[:3]))
        assert -1e-12 <= s <= 1.0 + 1e-12
        assert_message_pose(command, TABLE3[0] + s * direction, 1e-9)
