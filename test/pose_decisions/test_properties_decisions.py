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
Property tests of the decisions: CommandCheck and PoseTracker never raise, never pass a bad value.

What the nodes publish comes from these objects, so: every accepted command is finite,
positive and within the limits (as the check itself, asked again, says), the three ways of
giving a pose agree, the tracker finds the pose the lengths came from, and every input they
cannot use, however hostile, comes back refused with a code, never raised.
"""

import math

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose
from properties import (
    assert_refusal,
    budget,
    covers,
    floats,
    HUGE,
    LIMITED,
    NON_FINITE,
    NOT_NUMBERS,
    pose_distance,
    poses_near_home,
    with_bad_entry,
    wrong_shapes,
)
import pytest

from stewart_kinematics import (
    CommandCheck,
    euler_zyx_to_matrix,
    euler_zyx_to_quaternion,
    Finding,
    inverse_kinematics,
    leg_velocities,
    LegCommand,
    LegVelocityCommand,
    PoseAnchor,
    PoseEstimate,
    PoseTracker,
    SolverSettings,
    TwistEstimate,
)

pytestmark = pytest.mark.core

#: Poses well beyond the example limits too: about half are refused.
WIDE = poses_near_home(position=0.25, angle=math.radians(40.0))
HOSTILE = st.one_of(NOT_NUMBERS, wrong_shapes((6,)), st.just(np.zeros((0, 6))),
                    NON_FINITE.map(lambda value: [value] * 6), HUGE.map(lambda value: [value] * 6))


def twists(scale=1.0):
    """Platform twists up to ``scale`` m/s and rad/s."""
    return st.tuples(*[floats(-scale, scale)] * 6).map(np.array)


@covers('CommandCheck', 'LegCommand')
@budget(60)
@given(WIDE)
def test_a_command_is_finite_within_the_limits_or_refused_with_a_code(pose):
    check = CommandCheck(LIMITED)
    command = check.pose_vector(pose)
    assert isinstance(command, LegCommand)
    by_matrix = check.pose(pose[:3], euler_zyx_to_matrix(pose[3:]))
    by_quaternion = check.pose_quaternion(pose[:3], euler_zyx_to_quaternion(pose[3:]))
    assert command.accepted == by_matrix.accepted == by_quaternion.accepted
    if command.accepted:
        assert command.refusal is None and command.violations == ()
        assert np.all(np.isfinite(command.lengths)) and np.all(command.lengths > 0.0)
        assert LIMITED.leg_length_min <= command.lengths.min() <= command.lengths.max() <= (
            LIMITED.leg_length_max)
        assert_allclose(command.lengths, inverse_kinematics(LIMITED, pose), rtol=0, atol=1e-15)
        assert_allclose(by_quaternion.lengths, command.lengths, rtol=0, atol=1e-12)
    else:
        assert_refusal(command, ('out_of_limits', 'unreachable'))
        assert command.lengths is None and command.violations
        assert by_matrix.refusal.code == command.refusal.code


@covers('CommandCheck', 'LegCommand', 'LegVelocityCommand')
@budget(60)
@given(HOSTILE)
def test_a_command_of_anything_never_raises(value):
    check = CommandCheck(LIMITED)
    for command in (check.pose_vector(value), check.pose(value, np.eye(3)),
                    check.pose([0.0, 0.0, 0.45], value),
                    check.pose_quaternion(value, [0.0, 0.0, 0.0, 1.0]),
                    check.pose_quaternion([0.0, 0.0, 0.45], value)):
        if command.accepted:   # a finite value that happens to be a reachable pose
            assert np.all(np.isfinite(command.lengths))
        else:
            assert_refusal(command, ('invalid_pose', 'unreachable', 'out_of_limits'))
    assert check.last_pose is None or np.all(np.isfinite(check.last_pose[0]))
    assert_refusal(check.twist(value), ('invalid_twist', 'no_pose_yet'))


@covers('CommandCheck', 'LegVelocityCommand')
@budget(40)
@given(poses_near_home(), st.one_of(twists(), HUGE.map(lambda value: np.full(6, value))))
def test_a_twist_gives_the_leg_velocities_at_the_last_pose_or_a_refusal(pose, twist):
    check = CommandCheck(LIMITED)
    assert_refusal(check.twist(twist), ('no_pose_yet', 'invalid_twist'))
    if not check.pose_vector(pose).accepted:
        return
    command = check.twist(twist)
    assert isinstance(command, LegVelocityCommand)
    if command.accepted:
        assert_allclose(command.velocities, leg_velocities(LIMITED, pose, twist), rtol=1e-12,
                        atol=1e-15)
    else:
        assert_refusal(command, ('invalid_twist',))
        assert abs(twist).max() > 1e100


@covers('PoseTracker', 'PoseEstimate')
@budget(40)
@given(WIDE)
def test_the_tracker_finds_the_pose_the_lengths_came_from_or_refuses(pose):
    tracker = PoseTracker(LIMITED)
    lengths = inverse_kinematics(LIMITED, pose)
    estimate = tracker.update(lengths)
    assert isinstance(estimate, PoseEstimate)
    within = CommandCheck(LIMITED).pose_vector(pose).accepted
    if estimate.accepted:
        assert pose_distance(estimate.pose, pose) <= estimate.pose_error_bound <= 1e-9
        assert within, 'a pose out of the limits was accepted'
        assert np.all(np.isfinite(estimate.pose))
        assert tracker.last_lengths is not None
    else:
        assert_refusal(estimate, ('out_of_limits', 'no_solution', 'inaccurate_pose',
                                  'assembly_mode_jump'))
        assert not within or estimate.refusal.code != 'out_of_limits'


@covers('PoseTracker', 'PoseEstimate')
@budget(15)
@given(st.lists(st.tuples(*[floats(-0.004, 0.004)] * 3, *[floats(-0.01, 0.01)] * 3),
                min_size=2, max_size=12), poses_near_home(position=0.03, angle=0.1))
def test_the_tracker_follows_a_random_walk(steps, start):
    tracker = PoseTracker(LIMITED)
    pose = np.array(start)
    for step in steps:
        pose = pose + np.array(step)
        if not CommandCheck(LIMITED).pose_vector(pose).accepted:
            break
        estimate = tracker.update(inverse_kinematics(LIMITED, pose))
        assert estimate.accepted, estimate.reason
        assert pose_distance(estimate.pose, pose) <= 1e-9
        # Small steps within the limits (singularity margin 50) never come near a fold.
        assert not estimate.ambiguous and estimate.warnings == ()


@covers('PoseTracker', 'PoseEstimate', 'TwistEstimate')
@budget(60)
@given(HOSTILE)
def test_the_tracker_never_raises_and_keeps_its_state_on_a_refusal(value):
    tracker = PoseTracker(LIMITED)
    accepted = tracker.update(LIMITED.home_leg_lengths)
    assert accepted.accepted
    estimate = tracker.update(value)
    if not estimate.accepted:
        assert_refusal(estimate, ('invalid_lengths', 'out_of_limits', 'no_solution',
                                  'inaccurate_pose', 'assembly_mode_jump'))
        np.testing.assert_array_equal(tracker.last_pose, accepted.pose)
    twist = tracker.twist(value)
    assert isinstance(twist, TwistEstimate)
    if twist.accepted:
        assert np.all(np.isfinite(twist.twist))
    else:
        assert_refusal(twist, ('invalid_velocities', 'near_singularity'))


@covers('PoseTracker', 'PoseAnchor')
@budget(40)
@given(WIDE, poses_near_home())
def test_an_anchor_within_the_limits_is_where_the_tracker_goes_on_from(known, other):
    tracker = PoseTracker(LIMITED)
    tracker.update(inverse_kinematics(LIMITED, other))
    anchor = tracker.anchor(known)
    assert isinstance(anchor, PoseAnchor)
    if not CommandCheck(LIMITED).pose_vector(known).accepted:
        assert_refusal(anchor, ('out_of_limits', 'unreachable'))
        return
    assert anchor.accepted, anchor.reason
    assert pose_distance(anchor.pose, known) <= 1e-12 and not tracker.ambiguous
    assert_allclose(anchor.lengths, inverse_kinematics(LIMITED, known), rtol=0, atol=1e-15)
    estimate = tracker.update(inverse_kinematics(LIMITED, known))
    assert estimate.accepted and pose_distance(estimate.pose, known) <= 1e-9
    assert not estimate.ambiguous


@covers('PoseTracker', 'PoseAnchor')
@budget(60)
@given(HOSTILE)
def test_an_anchor_of_anything_never_raises_and_a_refusal_changes_nothing(value):
    tracker = PoseTracker(LIMITED)
    accepted = tracker.update(LIMITED.home_leg_lengths)
    for anchor in (tracker.anchor(value), tracker.anchor_tool_pose(value, [0.0, 0.0, 0.0, 1.0]),
                   tracker.anchor_tool_pose([0.0, 0.0, 0.45], value)):
        assert isinstance(anchor, PoseAnchor)
        if anchor.accepted:   # a finite value that happens to be a pose within the limits
            assert np.all(np.isfinite(anchor.pose)) and np.all(np.isfinite(anchor.lengths))
            return
        assert_refusal(anchor, ('invalid_pose', 'unreachable', 'out_of_limits'))
        np.testing.assert_array_equal(tracker.last_pose, accepted.pose)


@covers('PoseTracker', 'TwistEstimate')
@budget(40)
@given(poses_near_home(), twists())
def test_the_tracker_twist_inverts_the_leg_velocities(pose, twist):
    tracker = PoseTracker(LIMITED)
    if not tracker.update(inverse_kinematics(LIMITED, pose)).accepted:
        return
    estimate = tracker.twist(leg_velocities(LIMITED, pose, twist))
    assert estimate.accepted, estimate.reason
    assert_allclose(estimate.twist, twist, rtol=0, atol=1e-9)


@covers('PoseTracker', 'SolverSettings')
@budget(30)
@given(st.sampled_from(['tolerance', 'max_iterations', 'pose_tolerance',
                        'near_singularity_condition', 'assembly_guard_length_change',
                        'refuse_ambiguous_start', 'no_such_setting']),
       st.one_of(NOT_NUMBERS, NON_FINITE, st.sampled_from([0, -1, 0.0, -1e-3, 1e9, 2.5])))
def test_tracker_settings_out_of_range_are_refused_naming_them(name, value):
    tracker = PoseTracker(LIMITED)
    before = tracker.settings
    try:
        tracker.configure(tracker.settings.replace(**{name: value}))
    except (ValueError, TypeError) as error:   # TypeError: a name no setting has
        assert name in str(error), error
        assert tracker.settings == before
    else:   # None: the default, as for a parameter nobody set
        assert getattr(tracker.settings, name) == (
            value if value is not None else getattr(SolverSettings(), name))
    with pytest.raises(ValueError, match='reset pose'):
        tracker.reset([math.nan] * 6)


@covers('Finding', 'CommandCheck')
@budget(30)
@given(WIDE, st.data())
def test_every_refusal_is_a_finding_with_a_code_and_a_sentence(pose, data):
    bad = data.draw(with_bad_entry(pose, math.nan))
    for command in (CommandCheck(LIMITED).pose_vector(pose),
                    CommandCheck(LIMITED).pose_vector(bad)):
        if command.refusal is None:
            continue
        finding = command.refusal
        assert isinstance(finding, Finding)
        assert finding.code and finding.message and command.reason == finding.message
        assert all(isinstance(key, str) and isinstance(text, str)
                   for key, text in finding.details)


@covers('SolverSettings', 'PoseTracker')
@budget(30)
@given(floats(1e-14, 1e-9), st.integers(5, 200), floats(10.0, 1e6), floats(1e-10, 1e-6),
       st.booleans())
def test_solver_settings_round_trip_and_drive_the_tracker(tolerance, max_iterations,
                                                          condition, pose_tolerance, strict):
    settings = SolverSettings(tolerance=tolerance, max_iterations=max_iterations,
                              near_singularity_condition=condition,
                              pose_tolerance=pose_tolerance, refuse_ambiguous_start=strict)
    assert SolverSettings.from_values(settings.as_values()) == settings
    assert settings.replace(tolerance=None).tolerance == SolverSettings().tolerance
    tracker = PoseTracker(LIMITED, settings)
    estimate = tracker.update(LIMITED.home_leg_lengths)
    if estimate.accepted:
        assert estimate.residual <= tolerance
        assert pose_distance(estimate.pose, LIMITED.home_pose) <= pose_tolerance
    else:
        assert_refusal(estimate, ('inaccurate_pose', 'no_solution', 'ambiguous_assembly_mode'))
