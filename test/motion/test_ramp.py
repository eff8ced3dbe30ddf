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
Unit tests of stewart_kinematics.motion.ramp (pure numpy): the ramp, its schedule and check.

The paper's Table 3 is typed here in its own units (millimetres and degrees) and converted.
"""

import math

import numpy as np
from numpy.testing import assert_allclose, assert_array_equal
import pytest
from reference import paper_geometry, TABLE_3, TABLE_3_END

from stewart_kinematics.motion.ramp import Ramp, RampSchedule
from stewart_kinematics.parameters import RampSettings

pytestmark = pytest.mark.core

#: Table 3 in metres (X, Y, Z) and degrees (alpha, beta, gamma), as from_table takes it.
POSITION_START = [0.0, 0.0, 0.4325]
POSITION_STEP = [0.01, 0.015, 0.01]
POSITION_END = [0.1, 0.15, 0.5325]
ORIENTATION_START_DEG = [0.0, 0.0, 0.0]
ORIENTATION_STEP_DEG = [1.5, -1.5, 2.0]
ORIENTATION_END_DEG = [15.0, -15.0, 20.0]


def table_3_ramp():
    """Build the ramp of the paper's Table 3."""
    return Ramp.from_table(POSITION_START, POSITION_STEP, POSITION_END,
                           ORIENTATION_START_DEG, ORIENTATION_STEP_DEG, ORIENTATION_END_DEG)


PAPER_ROWS = np.array(TABLE_3)
PAPER_END = TABLE_3_END


def test_table_3_gives_eleven_rows_equal_to_the_paper():
    """Table 3 has 11 rows, start + k * step, in metres and radians."""
    rows = table_3_ramp().rows
    assert rows.shape == (11, 6)
    assert_allclose(rows, PAPER_ROWS, rtol=0.0, atol=1e-12)


def test_table_3_step_count_is_ten():
    """Every axis of Table 3 takes ten steps."""
    assert table_3_ramp().step_count == 10


def test_last_row_is_exactly_end():
    """The last row is the end pose bit for bit, not start + 10 * step."""
    ramp = table_3_ramp()
    assert_array_equal(ramp.rows[-1], ramp.end)
    assert_allclose(ramp.end, PAPER_END, rtol=0.0, atol=1e-15)


def test_first_row_is_start():
    """The first row is the start pose."""
    assert_array_equal(table_3_ramp().rows[0], [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0])


def test_from_table_converts_degrees_to_radians():
    """Orientation start, step and end are stored in radians."""
    ramp = table_3_ramp()
    assert_allclose(ramp.step, [0.01, 0.015, 0.01, 1.5 * math.pi / 180.0,
                                -1.5 * math.pi / 180.0, 2.0 * math.pi / 180.0],
                    rtol=0.0, atol=1e-15)


def test_arrays_are_read_only():
    """Start, step and end cannot be written to."""
    ramp = table_3_ramp()
    with pytest.raises(ValueError, match='read-only'):
        ramp.start[0] = 1.0


@pytest.mark.parametrize('time, expected', [
    (0.0, PAPER_ROWS[0]),
    (5.0, PAPER_ROWS[5]),
    (10.0, PAPER_ROWS[10]),
    (12.5, PAPER_ROWS[10]),
    (1e6, PAPER_ROWS[10]),
    (-1.0, PAPER_ROWS[0]),
    (3.0, PAPER_ROWS[3]),
    (7.0, PAPER_ROWS[7]),
])
def test_sample_at_key_times(time, expected):
    """Over 10 s: t=0 start, t=5 row 5, t=10 end, beyond holds end, before 0 holds start."""
    result = table_3_ramp().sample(time, 10.0)
    assert result.shape == (6,)
    assert_allclose(result, expected, rtol=0.0, atol=1e-12)


def test_sample_at_row_times_with_other_duration():
    """Row k is reached at k * duration / 10 whatever the duration."""
    duration = 4.0
    times = np.arange(11) * duration / 10.0
    assert_allclose(table_3_ramp().sample(times, duration), PAPER_ROWS, rtol=0.0, atol=1e-12)


def test_sample_between_rows_interpolates_linearly():
    """Halfway between rows 2 and 3 is the mean of the two rows."""
    result = table_3_ramp().sample(2.5, 10.0)
    assert_allclose(result, 0.5 * (PAPER_ROWS[2] + PAPER_ROWS[3]), rtol=0.0, atol=1e-12)


def test_sample_batch_shape():
    """N times give (N, 6) poses."""
    result = table_3_ramp().sample([0.0, 1.0, 2.0, 20.0], 10.0)
    assert result.shape == (4, 6)
    assert_allclose(result[-1], PAPER_ROWS[10], rtol=0.0, atol=1e-12)


@pytest.mark.parametrize('duration', [0.0, -1.0, math.nan])
def test_sample_rejects_non_positive_duration(duration):
    """A duration that is not positive raises ValueError."""
    with pytest.raises(ValueError, match='duration'):
        table_3_ramp().sample(1.0, duration)


def test_inconsistent_step_counts_raise_naming_the_axes():
    """X needing 10 steps and Y needing 5 raises ValueError naming both axes and counts."""
    with pytest.raises(ValueError, match=r'same number of steps.*X: 10.*Y: 5'):
        Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.03, 0.01], [0.1, 0.15, 0.5325],
                        ORIENTATION_START_DEG, ORIENTATION_STEP_DEG, ORIENTATION_END_DEG)


def test_inconsistent_orientation_step_count_raises_naming_the_axis():
    """Gamma needing 5 steps where the others need 10 raises ValueError naming gamma."""
    with pytest.raises(ValueError, match=r'gamma: 5'):
        Ramp.from_table(POSITION_START, POSITION_STEP, POSITION_END,
                        ORIENTATION_START_DEG, [1.5, -1.5, 4.0], ORIENTATION_END_DEG)


def test_not_whole_number_of_steps_raises_naming_the_axis():
    """Z from 0.4325 to 0.5325 in steps of 0.03 raises ValueError naming Z."""
    with pytest.raises(ValueError, match=r'ramp axis Z: .*not a whole number of steps'):
        Ramp.from_table(POSITION_START, [0.01, 0.015, 0.03], POSITION_END,
                        ORIENTATION_START_DEG, ORIENTATION_STEP_DEG, ORIENTATION_END_DEG)


def test_step_away_from_end_raises_naming_the_axis():
    """A beta step of +1.5 deg towards an end of -15 deg raises ValueError naming beta."""
    with pytest.raises(ValueError, match=r'ramp axis beta'):
        Ramp.from_table(POSITION_START, POSITION_STEP, POSITION_END,
                        ORIENTATION_START_DEG, [1.5, 1.5, 2.0], ORIENTATION_END_DEG)


def test_zero_step_with_different_end_raises_naming_the_axis():
    """Step 0 on Y while start and end differ raises ValueError naming Y."""
    with pytest.raises(ValueError, match=r'ramp axis Y: step is 0'):
        Ramp.from_table(POSITION_START, [0.01, 0.0, 0.01], POSITION_END,
                        ORIENTATION_START_DEG, ORIENTATION_STEP_DEG, ORIENTATION_END_DEG)


def test_zero_step_on_a_fixed_axis_is_allowed():
    """An axis with step 0 and start equal to end stays put while the others move."""
    ramp = Ramp.from_table([0.0, 0.0, 0.4], [0.01, 0.0, 0.0], [0.05, 0.0, 0.4],
                           [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    assert ramp.rows.shape == (6, 6)
    assert_allclose(ramp.rows[:, 0], [0.0, 0.01, 0.02, 0.03, 0.04, 0.05], rtol=0.0, atol=1e-15)
    assert_allclose(ramp.rows[:, 1:], np.tile([0.0, 0.4, 0.0, 0.0, 0.0], (6, 1)),
                    rtol=0.0, atol=0.0)


def test_all_steps_zero_gives_one_row():
    """A ramp that does not move has a single row, and every sample is that row."""
    pose = [0.0, 0.0, 0.4325, 0.0, 0.0, 0.0]
    ramp = Ramp(start=pose, step=[0.0] * 6, end=pose)
    assert ramp.step_count == 0
    assert_array_equal(ramp.rows, [pose])
    assert_array_equal(ramp.sample(3.0, 10.0), pose)
    assert ramp.sample([0.0, 1.0], 10.0).shape == (2, 6)


@pytest.mark.parametrize('name', ['start', 'step', 'end'])
def test_malformed_pose_raises_naming_it(name):
    """A start, step or end that is not six finite values raises ValueError naming it."""
    arguments = {'start': [0.0] * 6, 'step': [0.0] * 6, 'end': [0.0] * 6}
    arguments[name] = [0.0] * 5
    with pytest.raises(ValueError, match=rf'ramp {name}'):
        Ramp(**arguments)
    arguments[name] = [0.0, 0.0, math.nan, 0.0, 0.0, 0.0]
    with pytest.raises(ValueError, match=rf'ramp {name}'):
        Ramp(**arguments)


def test_step_of_the_wrong_sign_is_named_in_degrees():
    """A step pointing away from the end says so, in the parameter's degrees."""
    with pytest.raises(ValueError, match=r'alpha: step -1\.5 deg points away from the end'):
        Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                        [0.0, 0.0, 0.0], [-1.5, -1.5, 2.0], [15.0, -15.0, 20.0])


def test_from_settings_names_the_parameters():
    """Ramp.from_settings adds the parameter names to a table error."""
    values = {'position_start': [0.0, 0.0, 0.0], 'position_step': [0.1, 0.0, 0.0],
              'position_end': [0.35, 0.0, 0.0], 'orientation_start_deg': [0.0, 0.0, 0.0],
              'orientation_step_deg': [0.0, 0.0, 0.0], 'orientation_end_deg': [0.0, 0.0, 0.0]}
    with pytest.raises(ValueError, match='not a whole number.*parameters position_start'):
        Ramp.from_settings(RampSettings(**values))


# The schedule trajectory_node plays, and its check ----------------------------------------

def test_a_schedule_gives_the_rows_or_the_samples_of_a_pass():
    """Table mode: the rows, row_period apart; interpolate mode: publish_rate, then the end."""
    ramp = table_3_ramp()
    table = RampSchedule(ramp, 'table', row_period=0.5)
    times, poses = table.samples()
    assert_allclose(times, 0.5 * np.arange(11)) and table.period == 0.5
    assert_allclose(poses, ramp.rows)
    sampled = RampSchedule(ramp, 'interpolate', publish_rate=4.0, duration=2.6)
    times, poses = sampled.samples()
    assert_allclose(times, [0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 2.5, 2.6])
    assert_allclose(poses[-1], ramp.end) and sampled.period == 0.25
    assert_allclose(sampled.pose_at(99.0), ramp.end)
    off = RampSchedule(ramp, 'off')
    assert not off.plays and off.samples()[0].shape == (0,) and off.check(None) is None
    settings = RampSettings(mode='interpolate', publish_rate=4.0, duration=2.6, loop=True)
    from_settings = RampSchedule.from_settings(settings)
    assert (from_settings.mode, from_settings.period, from_settings.loop) == (
        'interpolate', 0.25, True)


@pytest.mark.parametrize('changes, words', [
    ({'mode': 'loop'}, 'ramp mode'), ({'row_period': 0.0}, 'row_period'),
    ({'duration': math.inf}, 'duration'), ({'publish_rate': math.nan}, 'publish_rate')])
def test_a_schedule_that_cannot_be_played_is_refused(changes, words):
    """Unknown modes and periods, rates or durations that are not positive and finite."""
    with pytest.raises(ValueError, match=words):
        RampSchedule(table_3_ramp(), **changes)


def test_the_ramp_pre_check_refuses_a_ramp_whose_legs_collide_naming_them():
    """Legs of 50 mm: legs 2 and 3 come within 50 mm from row 7 of Table 3 (47.3 mm at 10)."""
    thick = paper_geometry(leg_radius=0.025)
    refusal = RampSchedule(table_3_ramp(), 'table').check(thick)
    assert refusal.code == 'out_of_limits'
    assert refusal.message.startswith('ramp refused: 4 of 11 samples break the limits')
    assert refusal.message.count('legs 2 and 3: leg_collision, clearance') == 4
    assert dict(refusal.details)['failing_samples'] == '4 of 11'
    assert 'leg_collision legs 2 and 3' in dict(refusal.details)
    assert RampSchedule(table_3_ramp(), 'table').check(paper_geometry(leg_radius=0.02)) is None
