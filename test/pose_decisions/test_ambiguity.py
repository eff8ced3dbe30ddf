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
PoseTracker's ambiguity flag: a fold crossed, another assembly mode near, and re-anchoring.

The observation of issue 27: the paper's platform (config/paper_platform.yaml, no limits) turned
in yaw from 0 to -120 degrees at the home position. Its true pose crosses a fold singularity
near -89.6 degrees (the determinant of the twist Jacobian, computed here by test/reference.py,
changes sign), while the tracker's estimates come to the fold and turn back on the same side:
they follow the other assembly mode that meets the true one there, and end 60.8 degrees and
39.8 mm from the true pose with a pose error bound of 1e-12 (the lengths are matched exactly:
both poses have them). The leg lengths are computed leg by leg from the true poses
(test/reference.py); the rules are those of doc/assembly_modes.md.
"""

import math
from pathlib import Path

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import (
    leg_lengths,
    paper_geometry,
    rotation_angle,
    rotation_zyx,
    singular_yaw,
    TABLE_3,
    twist_jacobian,
)

from stewart_kinematics import (
    assembly_mode_margin,
    euler_zyx_to_quaternion,
    FrameTree,
    load_geometry,
    PoseTracker,
    Ramp,
    SolverSettings,
)
from stewart_kinematics.analysis.assembly_modes import AssemblyModeMargin
from stewart_kinematics.model.frames import Transform
from stewart_kinematics.pose_decisions.tracker_status import ambiguity_status

pytestmark = pytest.mark.core

CONFIG = Path(__file__).resolve().parents[2] / 'config'
PAPER = load_geometry(CONFIG / 'paper_platform.yaml')
LIMITED = load_geometry([CONFIG / 'paper_platform.yaml', CONFIG / 'example_limits.yaml'])
HOME = np.array(TABLE_3[0])
#: The sweep of the issue: yaw 0 to -120 degrees in steps of 0.5.
SWEEP_DEG = np.linspace(0.0, -120.0, 241)
#: fk_node's default assembly_mode_margin_warning, metres.
WARNING_DISTANCE = 0.05


def yawed(degrees):
    """Return the home pose turned ``degrees`` about z: (X, Y, Z, alpha, beta, gamma)."""
    return HOME + [0.0, 0.0, 0.0, 0.0, 0.0, math.radians(degrees)]


def lengths_of(pose):
    """Return the leg lengths of a pose, leg by leg (test/reference.py)."""
    return np.array(leg_lengths(pose))


def errors(estimate, truth):
    """Position (m) and rotation angle (deg) from a pose to the truth."""
    return (float(np.linalg.norm(estimate[:3] - truth[:3])),
            math.degrees(rotation_angle(rotation_zyx(*estimate[3:]), rotation_zyx(*truth[3:]))))


def determinant(pose):
    """Return det of the twist Jacobian (test/reference.py), independent of the package."""
    return float(np.linalg.det(twist_jacobian(pose)))


def sweep(tracker, degrees):
    """Feed the tracker the lengths of each yaw; return the estimates."""
    return [tracker.update(lengths_of(yawed(angle))) for angle in degrees]


def codes(estimate):
    return [warning.code for warning in estimate.warnings]


def test_the_fold_sweep_ends_in_the_other_mode_and_says_so():
    """The issue's sweep: 60.8 deg and 39.8 mm off at the end, and flagged ambiguous."""
    # The true pose crosses the fold between -89.5 and -90 degrees.
    assert determinant(yawed(-89.5)) > 0.0 > determinant(yawed(-90.0))
    tracker = PoseTracker(PAPER)
    estimates = sweep(tracker, SWEEP_DEG)
    last = estimates[-1]
    assert last.accepted
    position, angle = errors(last.pose, yawed(-120.0))
    assert position == pytest.approx(0.0398, abs=1e-4)
    assert angle == pytest.approx(60.77, abs=0.01)
    assert last.pose_error_bound < 1e-11 and last.condition < 20.0
    # Both poses have the lengths: the estimate is another assembly mode, on the side of the
    # fold the tracker started on (the same sign of det J as home): it turned back there.
    assert_allclose(lengths_of(last.pose), lengths_of(yawed(-120.0)), rtol=0.0, atol=1e-12)
    assert determinant(last.pose) > 0.0 > determinant(yawed(-120.0))
    assert last.solution.jacobian_sign == 1
    # Today's answer: no near-singularity warning at the end, but the flag.
    assert last.ambiguous and codes(last) == ['ambiguous_estimate']
    warning = last.warnings[0]
    assert 're-anchor' in warning.message and 'reset_tracker' in warning.message
    assert 'anchor_pose' in warning.message
    details = dict(warning.details)
    assert details['cause'] == 'near_singularity'
    assert details['anchored_by'] == 'the start, at the home pose'
    # Flagged from the first estimate beyond the singularity margin (condition 100), about
    # 3.5 deg before the fold; every estimate before it was right and unflagged.
    first = next(k for k, estimate in enumerate(estimates) if estimate.ambiguous)
    assert SWEEP_DEG[first] == pytest.approx(-86.5)
    assert estimates[first].condition > 100.0 > estimates[first - 1].condition
    for angle, estimate in zip(SWEEP_DEG[:first], estimates[:first]):
        assert estimate.accepted and not estimate.ambiguous and estimate.warnings == ()
        assert errors(estimate.pose, yawed(angle))[0] < 1e-9
    assert all(estimate.ambiguous for estimate in estimates[first:])
    assert all('ambiguous_estimate' in codes(estimate)
               for estimate in estimates[first:] if estimate.accepted)


@pytest.mark.parametrize('step', [0.1, 1.0, 2.0, 5.0, 7.0])
def test_the_fold_is_seen_whenever_the_steps_resolve_the_near_singular_zone(step):
    """
    Steps up to 7 deg: whatever their offset, an estimate lands beyond condition 100.

    That zone reaches about 3.6 deg each side of the fold.
    """
    for offset in np.linspace(0.0, step, 5, endpoint=False):
        tracker = PoseTracker(PAPER)
        estimates = sweep(tracker, [*np.arange(-offset, -120.0, -step), -120.0])
        assert errors(estimates[-1].pose, yawed(-120.0))[1] > 60.0
        assert estimates[-1].ambiguous, (step, offset)


def test_a_sweep_that_stays_away_from_folds_is_never_flagged():
    """Yaw 0 to -60 and back, then a roll and a lift: condition below 25, never flagged."""
    tracker = PoseTracker(PAPER)
    degrees = np.concatenate([np.linspace(0.0, -60.0, 121), np.linspace(-60.0, 0.0, 121)])
    for angle, estimate in zip(degrees, sweep(tracker, degrees)):
        assert estimate.accepted and not estimate.ambiguous and estimate.warnings == ()
        assert errors(estimate.pose, yawed(angle))[0] < 1e-9
    for k in range(60):
        pose = HOME + [0.0, 0.0, 0.001 * k, math.radians(0.5 * k), 0.0, 0.0]
        estimate = tracker.update(lengths_of(pose))
        assert estimate.accepted and not estimate.ambiguous
    assert not tracker.ambiguous and tracker.poses_since_anchor == 242 + 60


def test_no_false_flag_on_the_table_3_ramp_with_the_example_limits():
    """The ramp at 1 kHz over 10 s, there and back, and its 11 rows: never ambiguous."""
    ramp = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])
    poses = ramp.sample(np.linspace(0.0, 10.0, 1001), 10.0)
    tracker = PoseTracker(LIMITED)
    for pose in [*poses, *poses[::-1], *map(np.array, TABLE_3)]:
        estimate = tracker.update(lengths_of(pose))
        assert estimate.accepted and not estimate.ambiguous and estimate.warnings == ()
        assert errors(estimate.pose, pose)[0] < 1e-9
    assert ambiguity_status(tracker).warning is None


def test_reset_clears_the_flag_and_the_next_solve_starts_from_home():
    tracker = PoseTracker(PAPER)
    sweep(tracker, SWEEP_DEG)
    assert tracker.ambiguous
    tracker.reset()
    assert not tracker.ambiguous and tracker.anchored_by == 'a reset'
    home = tracker.update(lengths_of(HOME))
    assert home.accepted and not home.ambiguous and home.warnings == ()
    assert_allclose(home.pose, HOME, rtol=0.0, atol=1e-9)
    tracker.reset(yawed(-10.0))
    assert tracker.anchored_by == 'a reset at a given pose'


def test_a_known_pose_re_anchors_and_the_tracker_then_follows_the_true_mode():
    """After the sweep, anchored at the true pose: tracked from -120 to -150 deg, right."""
    tracker = PoseTracker(PAPER)
    sweep(tracker, SWEEP_DEG)
    anchor = tracker.anchor(yawed(-120.0))
    assert anchor.accepted and anchor.warnings == ()
    assert errors(anchor.pose, yawed(-120.0))[0] < 1e-12
    assert_allclose(anchor.lengths, lengths_of(yawed(-120.0)), rtol=0.0, atol=1e-12)
    assert not tracker.ambiguous and tracker.anchored_by == 'a known pose'
    assert tracker.poses_since_anchor == 0
    for angle in np.linspace(-120.5, -150.0, 60):
        estimate = tracker.update(lengths_of(yawed(angle)))
        assert estimate.accepted and not estimate.ambiguous
        assert errors(estimate.pose, yawed(angle))[0] < 1e-9
    # The guard now compares with the anchor: lengths barely changed must stay near it.
    tracker.anchor(yawed(-120.0))
    mirror = tracker.update(lengths_of(yawed(-120.0)) + 1e-4)
    assert mirror.accepted and errors(mirror.pose, yawed(-120.0))[0] < 1e-3


def test_an_anchor_in_the_user_frame_is_the_same_pose():
    """The tool frame's pose in the user frame, as anchor_pose carries it."""
    frames = FrameTree(base_frame='base', user_frame='table',
                       user_pose=Transform([0.1, -0.2, 0.05], rotation_zyx(0.0, 0.0, 0.3)),
                       tool_pose=Transform([0.0, 0.0, 0.1], np.eye(3)))
    truth = yawed(-120.0)
    tool = frames.tool_pose_vector(truth, 'table')
    tracker = PoseTracker(PAPER)
    sweep(tracker, SWEEP_DEG)
    anchor = tracker.anchor_tool_pose(tool[:3], euler_zyx_to_quaternion(tool[3:]), frames,
                                      'table')
    assert anchor.accepted and not tracker.ambiguous
    assert errors(anchor.pose, truth)[0] < 1e-12 and errors(anchor.pose, truth)[1] < 1e-9
    wrong = tracker.anchor_tool_pose(tool[:3], euler_zyx_to_quaternion(tool[3:]), frames,
                                     'camera')
    assert wrong.refusal.code == 'wrong_frame'
    half = tracker.anchor_tool_pose(tool[:3], 0.5 * euler_zyx_to_quaternion(tool[3:]), frames,
                                    'table')
    assert half.accepted and [w.code for w in half.warnings] == ['quaternion_not_unit']


@pytest.mark.parametrize('pose, code', [
    ([math.nan] * 6, 'invalid_pose'),
    ([0.0] * 5, 'invalid_pose'),
    (np.zeros(10 ** 6), 'invalid_pose'),
    ('home', 'invalid_pose'),
    ([1e308, 0.0, 0.0, 0.0, 0.0, 0.0], 'unreachable'),
    (HOME + [0.0, 0.0, 0.3, 0.0, 0.0, 0.0], 'out_of_limits'),   # beyond leg_length_max
])
def test_an_anchor_it_cannot_use_is_refused_and_changes_nothing(pose, code):
    tracker = PoseTracker(LIMITED)
    tracker.update(lengths_of(TABLE_3[5]))
    tracker.note_margin(AssemblyModeMargin(0.01, 0.1, 0.02, None, 2, True, ''), 1, 0.05)
    assert tracker.ambiguous
    state = (tracker.last_pose.copy(), tracker.last_lengths.copy(), tracker.ambiguity)
    anchor = tracker.anchor(pose)
    assert not anchor.accepted and anchor.refusal.code == code
    assert anchor.pose is None and anchor.lengths is None
    assert len(anchor.reason) < 1000                   # a million values described, not echoed
    assert_allclose(tracker.last_pose, state[0], atol=0.0)
    assert_allclose(tracker.last_lengths, state[1], atol=0.0)
    assert tracker.ambiguity is state[2]


def test_a_solution_across_the_singularity_from_the_last_one_is_flagged():
    """
    The sign rule alone (the condition rule off) flags a jump across the fold.

    From a known pose 0.4 deg before the fold, the lengths of 105 deg lead Newton-Raphson
    across it, to the true pose: right, but only by chance, which continuity cannot tell.
    """
    tracker = PoseTracker(PAPER, SolverSettings(near_singularity_condition=math.inf))
    assert tracker.anchor(yawed(90.0)).accepted
    estimate = tracker.update(lengths_of(yawed(105.0)))
    assert estimate.accepted and errors(estimate.pose, yawed(105.0))[0] < 1e-9
    assert determinant(yawed(90.0)) > 0.0 > determinant(yawed(105.0))
    assert estimate.ambiguous and dict(estimate.warnings[-1].details)['cause'] == 'jacobian_sign'


def test_a_solve_that_starts_near_a_singularity_is_flagged():
    """A known pose 0.4 deg before the fold (condition 950): the next solution may be either."""
    tracker = PoseTracker(PAPER)
    assert tracker.anchor(yawed(90.0)).accepted and not tracker.ambiguous
    estimate = tracker.update(lengths_of(yawed(100.0)))
    assert estimate.accepted and estimate.condition < 100.0
    assert errors(estimate.pose, yawed(100.0))[1] > 15.0          # the other mode
    details = dict(estimate.warnings[-1].details)
    assert details['cause'] == 'near_singularity' and float(details['jacobian_condition']) > 900


def test_a_fallback_start_from_home_is_flagged():
    """From -60 deg the lengths of Table 3's last row diverge; from home they are found."""
    tracker = PoseTracker(PAPER)
    assert tracker.update(lengths_of(yawed(-60.0))).accepted and not tracker.ambiguous
    estimate = tracker.update(lengths_of(TABLE_3[10]))
    assert estimate.accepted and errors(estimate.pose, np.array(TABLE_3[10]))[0] < 1e-9
    assert dict(estimate.warnings[-1].details)['cause'] == 'fallback_start'


def test_refusals_of_a_solve_that_lost_the_platform_flag_it():
    """inaccurate_pose 1e-6 rad from the fold, and no_solution: flagged; out of stroke: not."""
    tracker = PoseTracker(PAPER)
    truth = HOME + [0.0, 0.0, 0.0, 0.0, 0.0, singular_yaw() + 1e-6]
    tracker.reset(truth + [0.0, 0.0, 0.0, 0.0, 0.0, 1e-3])
    refused = tracker.update(lengths_of(truth))
    assert refused.refusal.code == 'inaccurate_pose' and refused.ambiguous
    assert dict(tracker.ambiguity.details)['cause'] == 'inaccurate_pose'

    tracker = PoseTracker(PAPER)
    tracker.update(lengths_of(HOME))
    refused = tracker.update([10.0] * 5 + [0.1])
    assert refused.refusal.code == 'no_solution' and tracker.ambiguous

    tracker = PoseTracker(LIMITED)
    tracker.update(lengths_of(HOME))
    refused = tracker.update(lengths_of(HOME) + 0.3)          # beyond leg_length_max
    assert refused.refusal.code == 'out_of_limits' and not tracker.ambiguous


def test_a_near_margin_flags_and_a_margin_that_rules_out_every_other_mode_clears():
    """
    The margin rules, with real margins.

    At -85 deg on the paper's platform, 25 mm from the mode across the fold; at the end of
    Table 3 within the example limits, the only mode there.
    """
    tracker = PoseTracker(PAPER)
    sweep(tracker, np.linspace(0.0, -85.0, 171))
    assert not tracker.ambiguous
    near = assembly_mode_margin(PAPER, tracker.last_pose, tracker.last_lengths)
    assert near.distance == pytest.approx(0.025, abs=1e-3)
    assert not tracker.note_margin(near, tracker.accepted_count, WARNING_DISTANCE)
    assert tracker.ambiguous
    assert dict(tracker.ambiguity.details)['cause'] == 'assembly_mode_margin'
    # 0 turns the margin rule off.
    other = PoseTracker(PAPER)
    sweep(other, np.linspace(0.0, -85.0, 171))
    assert not other.note_margin(near, other.accepted_count, 0.0) and not other.ambiguous

    tracker = PoseTracker(LIMITED)
    for row in TABLE_3:
        tracker.update(lengths_of(row))
    unique = assembly_mode_margin(LIMITED, tracker.last_pose, tracker.last_lengths)
    assert unique.rules_out_other_modes and unique.modes_within_limits == 1
    close = AssemblyModeMargin(0.01, 0.1, 0.02, None, 2, True, '')
    assert not tracker.note_margin(close, tracker.accepted_count, WARNING_DISTANCE)
    assert tracker.ambiguous
    # A margin of the flagged pose itself, or of one before it, cannot clear the flag.
    assert not tracker.note_margin(unique, tracker.accepted_count, WARNING_DISTANCE)
    assert not tracker.note_margin(unique, tracker.accepted_count - 1, WARNING_DISTANCE)
    assert tracker.ambiguous
    tracker.update(lengths_of(TABLE_3[10]))             # the next pose, the same lengths
    assert tracker.ambiguous
    assert tracker.note_margin(unique, tracker.accepted_count, WARNING_DISTANCE)
    assert not tracker.ambiguous
    assert tracker.anchored_by == (f'pose {tracker.accepted_count}, where no other real '
                                   'assembly mode lay within the limits')
    # A margin of a pose before the anchor (the tracker's own numbering) is ignored.
    assert not tracker.note_margin(close, tracker.accepted_count, WARNING_DISTANCE)
    assert not tracker.ambiguous
    assert not tracker.note_margin(close, tracker.accepted_count + 1, WARNING_DISTANCE)
    with pytest.raises(TypeError, match='pose_number must be an int'):
        tracker.note_margin(unique, 1.0, WARNING_DISTANCE)


def test_a_margin_of_the_current_lengths_counts_for_the_current_pose():
    """
    At rest, the margin is not computed again: that of the same lengths, older, clears.

    Whether other modes are ruled out depends on the lengths alone.
    """
    tracker = PoseTracker(LIMITED)
    end = lengths_of(TABLE_3[10])
    tracker.update(end)
    unique = assembly_mode_margin(LIMITED, tracker.last_pose, end)
    assert tracker.update([0.9, 0.65, 0.9, 0.65, 0.9, 0.65]).refusal.code == 'no_solution'
    assert tracker.ambiguous
    assert not tracker.note_margin(unique, 1, WARNING_DISTANCE, end)     # no pose since
    tracker.update(end)
    assert not tracker.note_margin(unique, 1, WARNING_DISTANCE, end + 1e-9)
    assert tracker.ambiguous
    assert tracker.note_margin(unique, 1, WARNING_DISTANCE, end)
    assert not tracker.ambiguous and tracker.anchored_by.startswith('pose 2,')


def test_far_from_every_other_mode_is_not_unambiguous():
    """
    The issue's "a pose far from every other mode" does not re-anchor.

    At the end of the sweep the nearest other mode is 0.164 m away (beyond any warning
    distance), and it is the true pose. Only a margin that rules out every other mode
    physically clears the flag.
    """
    tracker = PoseTracker(PAPER)
    sweep(tracker, SWEEP_DEG)
    margin = assembly_mode_margin(PAPER, tracker.last_pose, tracker.last_lengths)
    assert margin.distance == pytest.approx(0.164, abs=1e-3) and margin.complete
    assert errors(margin.nearest.pose, yawed(-120.0))[0] < 1e-9         # the platform
    assert not margin.rules_out_other_modes
    assert not tracker.note_margin(margin, tracker.accepted_count, WARNING_DISTANCE)
    assert tracker.ambiguous


def test_a_mode_beyond_only_the_singularity_margin_is_not_ruled_out():
    """
    A mode that breaks only max_jacobian_condition is where the platform can be.

    The margin is kept by the software, not by the hardware. At the end of Table 3 the
    third mode (condition 30.5) breaks only a margin of 20.
    """
    geometry = paper_geometry(max_jacobian_condition=20.0)
    end = np.array(TABLE_3[10])
    margin = assembly_mode_margin(geometry, end)
    assert margin.others_beyond_singularity_margin == 1
    assert not margin.rules_out_other_modes
    unique = AssemblyModeMargin(math.inf, math.inf, math.inf, None, 1, True, '')
    assert unique.rules_out_other_modes
    for changed in (AssemblyModeMargin(math.inf, math.inf, math.inf, None, 1, False, 'failed'),
                    AssemblyModeMargin(math.inf, math.inf, math.inf, None, 1, True, '', 1),
                    AssemblyModeMargin(math.inf, math.inf, math.inf, None, 2, True, '')):
        assert not changed.rules_out_other_modes


def test_the_status_warns_while_ambiguous():
    tracker = PoseTracker(PAPER)
    status = ambiguity_status(tracker)
    assert status.warning is None
    assert dict(status.values) == {'ambiguous': 'False',
                                   'anchored_by': 'the start, at the home pose',
                                   'poses_since_anchor': '0'}
    sweep(tracker, SWEEP_DEG)
    status = ambiguity_status(tracker)
    assert status.warning is tracker.ambiguity and status.message == tracker.ambiguity.message
    values = dict(status.values)
    assert values['ambiguous'] == 'True' and values['cause'] == 'near_singularity'
    assert values['poses_since_anchor'] == '241'
