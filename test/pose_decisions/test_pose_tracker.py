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
Unit tests of stewart_kinematics.pose_decisions.pose_tracker.PoseTracker (pure numpy, no ROS).

The lengths fed to the tracker are computed from the paper's tables, leg by leg with the
textbook rotation matrices (test/reference.py), so that every pose the tracker returns is
checked against the pose the lengths were made from.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest
from reference import (
    HOME,
    leg_lengths,
    paper_geometry,
    rotation_angle,
    rotation_zyx,
    singular_yaw,
    TABLE_3,
)

from stewart_kinematics import forward_kinematics, platform_twist, PoseTracker
from stewart_kinematics.parameters import SolverSettings
from stewart_kinematics.pose_decisions.pose_tracker import (
    assembly_mode_jump,
    euler_angle_change_bound,
)

pytestmark = pytest.mark.core

HOME = np.array(HOME)
TABLE3 = [np.array(row) for row in TABLE_3]


def geometry(**limits):
    """Build the paper's platform with the given limits."""
    return paper_geometry(**limits)


def lengths_of(pose):
    """|t + R p_i - b_i| leg by leg (test/reference.py)."""
    return np.array(leg_lengths(pose))


def yawed_home(degrees):
    """Return the home pose turned ``degrees`` about z."""
    return HOME + [0.0, 0.0, 0.0, 0.0, 0.0, math.radians(degrees)]


def test_table3_is_tracked_row_by_row():
    """Each row's lengths give that row's pose to 1e-9, with the solve's figures."""
    tracker = PoseTracker(geometry())
    assert_allclose(tracker.last_pose, HOME, atol=0.0)
    for row in TABLE3:
        estimate = tracker.update(lengths_of(row))
        assert estimate.accepted and estimate.reason == '' and estimate.warnings == ()
        assert_allclose(estimate.pose, row, rtol=0.0, atol=1e-9)
        assert estimate.residual <= 1e-12 and estimate.iterations <= 6
        assert 9.0 < estimate.condition < 20.0
        assert estimate.pose_error_bound < 1e-9
        assert_allclose(tracker.last_pose, row, rtol=0.0, atol=1e-9)
        assert_allclose(tracker.last_lengths, lengths_of(row), rtol=0.0, atol=0.0)
        assert tracker.last_solution is estimate.solution


def test_each_solve_starts_from_the_last_solution_and_reset_forgets_it():
    """
    A half turn in steps of 15 degrees is tracked; its lengths alone, from home, are not.

    From the home pose the lengths of a 150 degree turn lead Newton-Raphson to another pose with
    the same lengths (another assembly mode): only the warm start finds it. After reset() the
    tracker starts from home again; reset(pose) starts from the pose given.
    """
    turned = yawed_home(150.0)
    cold = forward_kinematics(geometry(), lengths_of(turned))
    assert not (cold.converged and np.allclose(cold.pose, turned, rtol=0.0, atol=1e-6))
    tracker = PoseTracker(geometry())
    for step in range(1, 11):
        estimate = tracker.update(lengths_of(yawed_home(15.0 * step)))
        assert_allclose(estimate.pose, yawed_home(15.0 * step), rtol=0.0, atol=1e-9)
    tracker.reset()
    assert tracker.last_solution is None and tracker.last_lengths is None
    assert_allclose(tracker.last_pose, HOME, atol=0.0)
    again = tracker.update(lengths_of(turned))
    assert not (again.accepted and np.allclose(again.pose, turned, rtol=0.0, atol=1e-6))
    tracker.reset(yawed_home(140.0))
    assert_allclose(tracker.update(lengths_of(turned)).pose, turned, rtol=0.0, atol=1e-9)
    with pytest.raises(ValueError, match='reset pose'):
        tracker.reset([0.0, math.nan, 0.4, 0.0, 0.0, 0.0])


def test_a_failed_solve_falls_back_to_the_home_pose():
    """From a turn of -60 degrees about z Table 3's last row diverges; from home it is found."""
    turned = yawed_home(-60.0)
    assert not forward_kinematics(geometry(), lengths_of(TABLE3[10]), turned).converged
    tracker = PoseTracker(geometry())
    assert tracker.update(lengths_of(turned)).accepted
    estimate = tracker.update(lengths_of(TABLE3[10]))
    assert estimate.accepted
    assert_allclose(estimate.pose, TABLE3[10], rtol=0.0, atol=1e-9)


@pytest.mark.parametrize('lengths, words', [
    ([0.7] * 5, 'must have shape (6,)'),
    ([0.7] * 5 + [math.nan], 'finite and positive'),
    ([0.7] * 5 + [-0.7], 'finite and positive'),
    ([0.7] * 5 + [0.0], 'finite and positive'),
    ([[0.7] * 6] * 2, 'expected the 6 lengths'),
])
def test_malformed_lengths_are_refused_not_raised(lengths, words):
    """Wrong count, NaN, negative, zero, a batch: invalid_lengths, no solve, state unchanged."""
    tracker = PoseTracker(geometry())
    estimate = tracker.update(lengths)
    assert not estimate.accepted and estimate.pose is None and estimate.solution is None
    assert estimate.refusal.code == 'invalid_lengths'
    assert words in estimate.reason
    assert estimate.iterations is None and estimate.condition is None
    assert tracker.last_lengths is None


def test_lengths_are_checked_once_where_they_enter_then_solved_unchecked(monkeypatch):
    """
    The tracker checks a message's lengths in update; its solves (and anchors) trust them.

    Issue 28: the numbers were checked by the message conversion, by update and again by
    forward_kinematics. The solver's checks now fail the test if anything calls them.
    """
    from stewart_kinematics.model import forward

    def checked_again(*arguments, **options):
        raise AssertionError('the lengths were checked again after update')
    for name in ('single_values', 'as_leg_lengths', 'as_poses', 'as_rows'):
        monkeypatch.setattr(forward, name, checked_again)
    tracker = PoseTracker(geometry())
    for row in TABLE3:
        estimate = tracker.update(lengths_of(row))
        assert estimate.accepted, estimate.reason
        assert_allclose(estimate.pose, row, rtol=0.0, atol=1e-9)
    # From a turn of -60 degrees about z, Table 3's last row diverges: the fallback from home.
    assert tracker.update(lengths_of(yawed_home(-60.0))).accepted
    assert_allclose(tracker.update(lengths_of(TABLE3[10])).pose, TABLE3[10], rtol=0.0,
                    atol=1e-9)
    # An anchor's solve of its own lengths.
    assert tracker.anchor(TABLE3[2]).accepted
    assert tracker.update(lengths_of(TABLE3[3])).accepted
    # Bad lengths are refused by update's own check, as before.
    assert tracker.update([0.7] * 5 + [math.nan]).refusal.code == 'invalid_lengths'


def test_lengths_out_of_the_stroke_are_refused_before_any_solve():
    """Legs beyond leg_length_max: every leg listed, no solve."""
    tracker = PoseTracker(geometry(leg_length_min=0.69, leg_length_max=0.73))
    estimate = tracker.update([0.95] * 6)
    assert estimate.refusal.code == 'out_of_limits' and estimate.solution is None
    assert estimate.reason.startswith('the leg lengths are out of the limits: ')
    for leg in range(1, 7):
        assert f'leg {leg}: leg_length_max 0.73 m broken by 0.22 m' in estimate.reason
        assert f'leg_length_max leg {leg}' in dict(estimate.refusal.details)


def test_lengths_with_no_pose_are_refused_with_iterations_and_residual():
    """Six legs of 10 m reach no pose: no_solution, with the solver's reason and figures."""
    tracker = PoseTracker(geometry())
    estimate = tracker.update([10.0] * 6)
    assert estimate.refusal.code == 'no_solution'
    assert estimate.reason.startswith('no pose found for leg lengths [10.0, 10.0')
    details = dict(estimate.refusal.details)
    assert int(details['iterations']) == estimate.iterations >= 1
    assert float(details['residual_m']) > 1e-3
    assert_allclose(tracker.last_pose, HOME, atol=0.0)


def test_a_solution_beyond_the_limits_is_refused():
    """One step beyond Table 3: leg 4 turns 36.7 deg at its platform joint (limit 35 deg)."""
    beyond = TABLE3[10] + (TABLE3[10] - TABLE3[9])
    tracker = PoseTracker(geometry(platform_joint_max_angle=math.radians(35.0)))
    estimate = tracker.update(lengths_of(beyond))
    assert estimate.refusal.code == 'out_of_limits'
    assert estimate.reason.startswith('the pose of these leg lengths is out of the limits: ')
    assert 'leg 4: platform_joint_max_angle 35 deg broken by' in estimate.reason
    assert_allclose(estimate.solution.pose, beyond, rtol=0.0, atol=1e-9)


def test_the_assembly_mode_guard_compares_with_the_last_solution():
    """The other assembly mode of the home lengths is a jump; a small motion is not."""
    home_lengths = lengths_of(HOME)
    other = forward_kinematics(geometry(), home_lengths, [0.0, 0.0, 0.35, 0.0, 0.0, math.pi])
    assert other.converged and abs(other.pose[2] - HOME[2]) > 0.05
    assert_allclose(lengths_of(other.pose), home_lengths, atol=1e-12)
    settings = SolverSettings()
    jump = assembly_mode_jump(settings, HOME, home_lengths, other.pose, home_lengths + 1e-4)
    assert jump.code == 'assembly_mode_jump' and 'another assembly mode' in jump.message
    assert float(dict(jump.details)['length_change_m']) == pytest.approx(1e-4)
    turned = HOME + [0.0, 0.0, 0.0, 0.0, 0.0, math.radians(20.0)]
    assert '20 deg' in assembly_mode_jump(settings, HOME, home_lengths, turned,
                                          home_lengths + 1e-4).message
    moved = HOME + [0.06, 0.0, 0.0, 0.0, 0.0, 0.0]
    assert '0.06 m' in assembly_mode_jump(settings, HOME, home_lengths, moved,
                                          home_lengths).message
    nearby = HOME + [0.01, -0.01, 0.02, math.radians(5.0), 0.0, math.radians(-5.0)]
    assert assembly_mode_jump(settings, HOME, home_lengths, nearby, home_lengths + 1e-3) is None
    # Lengths changed by more than assembly_guard_length_change (5 mm): a motion.
    assert assembly_mode_jump(settings, HOME, home_lengths, other.pose,
                              home_lengths + 0.006) is None


def test_the_euler_bound_never_changes_the_guard_decision():
    """
    The cheap bound is at least the rotation angle, so the guard decides as on the angle.

    Pairs of poses with the second's angles off by up to 30 degrees each (wrapping through
    pi included), against the angle from the textbook matrices (test/reference.py), at
    thresholds around each pair's own angle.
    """
    rng = np.random.default_rng(22)
    settings = SolverSettings()
    lengths = lengths_of(HOME)
    for _ in range(500):
        first = HOME + np.concatenate([rng.uniform(-0.05, 0.05, 3),
                                       rng.uniform(-math.pi, math.pi, 3)])
        second = first + np.concatenate([rng.uniform(-0.01, 0.01, 3),
                                         rng.uniform(-0.5, 0.5, 3)])
        angle = rotation_angle(rotation_zyx(*first[3:]), rotation_zyx(*second[3:]))
        assert euler_angle_change_bound(first[3:], second[3:]) >= angle - 1e-12
        for factor in (0.5, 0.999999, 1.000001, 2.0):
            threshold = math.degrees(angle) * factor
            guard = settings.replace(assembly_guard_angle_change_deg=threshold,
                                     assembly_guard_position_change=1.0)
            jump = assembly_mode_jump(guard, first, lengths, second, lengths)
            assert (jump is None) == (factor > 1.0), (first, second, factor)
    # Differences that wrap: 350 degrees apart is 10 degrees.
    assert euler_angle_change_bound([math.radians(175.0), 0.0, 0.0],
                                    [math.radians(-175.0), 0.0, 0.0]) == pytest.approx(
        math.radians(10.0))


def test_the_tracker_refuses_a_jump_and_keeps_its_last_solution():
    """Believing the platform 0.1 m along x, unchanged home lengths are refused as a jump."""
    tracker = PoseTracker(geometry())
    assert tracker.update(lengths_of(HOME)).accepted
    believed = HOME + [0.1, 0.0, 0.0, 0.0, 0.0, 0.0]
    tracker.last_pose, tracker.last_solution = believed, None
    estimate = tracker.update(lengths_of(HOME))
    assert estimate.refusal.code == 'assembly_mode_jump'
    assert 'the solution jumped 0.1 m and ' in estimate.reason
    assert_allclose(tracker.last_pose, believed, atol=0.0)
    assert tracker.update(lengths_of(TABLE3[1])).accepted


def test_near_a_singularity_a_pose_comes_with_a_warning():
    """
    With near_singularity_condition 5 (home is about 9.5) home is accepted with a warning.

    Beyond the singularity margin the estimate is also flagged ambiguous (test_ambiguity.py).
    """
    tracker = PoseTracker(geometry(), SolverSettings(near_singularity_condition=5.0))
    estimate = tracker.update(lengths_of(HOME))
    assert estimate.accepted
    warning, ambiguity = estimate.warnings
    assert (warning.code, ambiguity.code) == ('near_singularity', 'ambiguous_estimate')
    assert 'near_singularity_condition 5' in warning.message
    assert float(dict(warning.details)['jacobian_condition']) == pytest.approx(9.54, abs=0.01)


def test_a_pose_the_lengths_fix_only_loosely_is_refused():
    """
    1e-6 rad from the singular yaw (90.4 deg) the solve converges to 1e-13 m, microns off.

    The pose error bound says so, and the tracker refuses the pose with pose_tolerance 1e-9;
    with no pose tolerance it is accepted, with a near-singularity warning (and flagged
    ambiguous from the refusal on: test_ambiguity.py).
    """
    truth = HOME + [0.0, 0.0, 0.0, 0.0, 0.0, singular_yaw() + 1e-6]
    start = truth + [0.0, 0.0, 0.0, 0.0, 0.0, 1e-3]
    tracker = PoseTracker(geometry())
    tracker.reset(start)
    estimate = tracker.update(lengths_of(truth))
    assert estimate.refusal.code == 'inaccurate_pose'
    assert estimate.solution.converged and estimate.residual <= 1e-12
    assert estimate.pose_error_bound > 1e-7 and estimate.condition > 1e5
    assert '> pose_tolerance 1e-09' in estimate.reason
    details = dict(estimate.refusal.details)
    assert float(details['pose_error_bound']) == pytest.approx(estimate.pose_error_bound,
                                                               rel=1e-2)
    assert float(details['jacobian_condition']) > 1e5
    assert_allclose(tracker.last_pose, start, atol=0.0)

    tracker.configure(tracker.settings.replace(pose_tolerance=math.inf))
    accepted = tracker.update(lengths_of(truth))
    assert accepted.accepted
    assert [warning.code for warning in accepted.warnings] == ['near_singularity',
                                                               'ambiguous_estimate']
    # What was refused: converged, yet further from the truth than the tolerance.
    assert np.max(np.abs(accepted.pose - truth)) > 1e-9


def test_twist_at_the_last_pose_and_refused_beyond_the_singularity_margin():
    """The twist of leg velocities at the last pose; refused beyond the margin, or malformed."""
    tracker = PoseTracker(geometry())
    velocities = np.array([0.001, -0.002, 0.003, 0.0, 0.001, -0.001])
    assert_allclose(tracker.twist(velocities).twist,
                    platform_twist(geometry(), HOME, velocities), rtol=0.0, atol=1e-15)
    assert tracker.update(lengths_of(TABLE3[4])).accepted
    estimate = tracker.twist(velocities)
    assert estimate.accepted
    assert_allclose(estimate.twist, platform_twist(geometry(), TABLE3[4], velocities),
                    rtol=1e-12, atol=1e-15)
    tracker.configure(tracker.settings.replace(near_singularity_condition=5.0))
    refused = tracker.twist(velocities)
    assert refused.refusal.code == 'near_singularity' and refused.twist is None
    assert 'above the limit 5 (the singularity margin' in refused.reason
    # The geometry's margin counts too: at Table 3's last row (condition 17) beyond 12.
    strict = PoseTracker(geometry(max_jacobian_condition=12.0))
    assert strict.twist(velocities).accepted
    strict.reset(TABLE3[10])
    assert 'above the limit 12 (the singularity margin' in strict.twist(velocities).reason
    for bad in ([0.0] * 5, [math.nan] + [0.0] * 5):
        assert tracker.twist(bad).refusal.code == 'invalid_velocities'


def test_settings_are_validated_and_used():
    """An unknown or invalid setting raises naming it; max_iterations 1 misses a far pose."""
    with pytest.raises(ValueError, match='tolerance'):
        SolverSettings(tolerance=-1.0)
    with pytest.raises(TypeError, match='tolerence'):
        SolverSettings(tolerence=1e-10)
    with pytest.raises(TypeError, match='SolverSettings'):
        PoseTracker(geometry()).configure({'tolerance': 1e-10})
    tracker = PoseTracker(geometry(), SolverSettings(max_iterations=1))
    with pytest.raises(ValueError, match='pose_tolerance'):
        tracker.configure(tracker.settings.replace(pose_tolerance=0.0))
    assert tracker.settings.pose_tolerance == 1e-9
    slow = tracker.update(lengths_of(TABLE3[10]))
    assert slow.refusal.code == 'no_solution'
    assert 'no convergence within 1 iterations' in slow.reason
    tracker.configure(tracker.settings.replace(max_iterations=50))
    assert tracker.update(lengths_of(TABLE3[10])).accepted


def test_a_joint_state_gives_the_pose_and_its_twist_or_a_warning():
    """update(lengths, velocities): the twist at the new pose; a refused twist only warns."""
    tracker = PoseTracker(geometry())
    velocities = np.full(6, 0.001)
    estimate = tracker.update(lengths_of(TABLE3[3]), velocities)
    assert estimate.accepted
    assert_allclose(estimate.twist, platform_twist(geometry(), estimate.pose, velocities),
                    rtol=0.0, atol=1e-15)
    malformed = tracker.update(lengths_of(TABLE3[4]), [math.nan] * 6)
    assert malformed.accepted and malformed.twist is None
    assert [warning.code for warning in malformed.warnings] == ['invalid_velocities']
    without = tracker.update(lengths_of(TABLE3[5]))
    assert without.accepted and without.twist is None and without.warnings == ()


class FakeMonitor:
    """Stands in for AssemblyModeMarginMonitor: its latest margin and warning."""

    def __init__(self, latest, warning=''):
        self.latest, self._warning, self.latest_seconds = latest, warning, 0.012

    def warning(self):
        """Return the warning sentence, as the monitor decides it."""
        return self._warning


class FakeMargin:
    """An AssemblyModeMargin's fields."""

    def __init__(self, complete=True, nearest=True):
        self.position, self.angle, self.distance = 0.2, 0.5, 0.25
        self.modes_within_limits, self.complete, self.reason = 2, complete, 'time out'
        self.nearest = object() if nearest else None


def test_margin_status_warns_when_the_margin_is_small_or_the_search_incomplete():
    """The level fk_node reports: OK, or WARN with an assembly_mode_margin finding."""
    from stewart_kinematics.pose_decisions.tracker_status import margin_status
    assert margin_status(FakeMonitor(None)).warning is None
    fine = margin_status(FakeMonitor(FakeMargin()))
    assert fine.warning is None and fine.message.startswith('nearest other assembly mode')
    assert dict(fine.values)['computed_in_ms'] == '12.0'
    alone = margin_status(FakeMonitor(FakeMargin(nearest=False)))
    assert alone.message == 'no other assembly mode within the limits'
    close = margin_status(FakeMonitor(FakeMargin(), 'another assembly mode lies 0.01 m'))
    assert close.warning.code == 'assembly_mode_margin' and close.message.startswith('another')
    incomplete = margin_status(FakeMonitor(FakeMargin(complete=False)))
    assert incomplete.warning is not None and 'search was incomplete: time out' in (
        incomplete.message)
