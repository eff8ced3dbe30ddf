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
Unit tests of motion/tolerances.py: a goal's tolerances resolved and checked as JTC does.

The expected values are worked by hand from joint_trajectory_controller's tolerances.hpp
(Jazzy): > 0 taken, 0 the default, -1 erased, a resolved 0 not enforced.
"""

import math

import numpy as np
from numpy.testing import assert_allclose
import pytest

from stewart_kinematics import findings
from stewart_kinematics.motion.tolerances import (
    GOAL_TOLERANCE_VIOLATED,
    JointToleranceValues,
    PATH_TOLERANCE_VIOLATED,
    resolve_tolerance,
    resolve_tolerances,
    SegmentTolerances,
    state_violation,
    StateTolerances,
    SUCCESSFUL,
    ToleranceMonitor,
)

pytestmark = pytest.mark.core

NAMES = ('a', 'b', 'c')


def defaults(goal_time=1.0):
    return SegmentTolerances(StateTolerances.uniform(3, 0.1, 0.5),
                             StateTolerances.uniform(3, 0.01, 0.02), goal_time)


@pytest.mark.parametrize('value, expected', [
    (0.0, 0.1), (0.3, 0.3), (-1.0, 0.0), (-1.0 + 1e-8, 0.0), (1e-12, 1e-12)])
def test_resolve_tolerance_follows_jtc(value, expected):
    assert resolve_tolerance(0.1, value, 'x') == expected


@pytest.mark.parametrize('value', [-0.5, -2.0, math.nan, math.inf, -math.inf, 1e308])
def test_illegal_tolerance_is_refused_with_the_value(value):
    with pytest.raises(ValueError, match='x is'):
        resolve_tolerance(0.1, value, 'x')


def test_goal_tolerances_override_per_joint_and_keep_the_rest():
    resolution = resolve_tolerances(
        NAMES, defaults(), path_tolerance=[JointToleranceValues('b', 0.2, -1.0, 0.0)],
        goal_tolerance=[JointToleranceValues('c', -1.0, 0.0, 3.0)], goal_time_tolerance=0.0)
    assert resolution.accepted
    tolerances = resolution.tolerances
    assert_allclose(tolerances.path.position, [0.1, 0.2, 0.1], rtol=0, atol=0)
    assert_allclose(tolerances.path.velocity, [0.5, 0.0, 0.5], rtol=0, atol=0)
    assert_allclose(tolerances.goal.position, [0.01, 0.01, 0.0], rtol=0, atol=0)
    assert_allclose(tolerances.goal.acceleration, [0.0, 0.0, 3.0], rtol=0, atol=0)
    assert tolerances.goal_time == 1.0
    # The defaults are untouched.
    assert_allclose(defaults().path.position, [0.1, 0.1, 0.1], rtol=0, atol=0)
    assert resolve_tolerances(NAMES, defaults(), goal_time_tolerance=2.5).tolerances.goal_time \
        == 2.5
    assert resolve_tolerances(NAMES, defaults(), goal_time_tolerance=-1.0).tolerances.goal_time \
        == 0.0


def test_unknown_joint_or_illegal_value_in_a_tolerance_is_refused():
    unknown = resolve_tolerances(NAMES, defaults(),
                                 goal_tolerance=[JointToleranceValues('z', 0.1)])
    assert unknown.refusal.code == findings.INVALID_JOINTS
    assert "'z'" in unknown.reason and 'goal_tolerance' in unknown.reason
    illegal = resolve_tolerances(NAMES, defaults(),
                                 path_tolerance=[JointToleranceValues('a', 0.0, -0.5)])
    assert illegal.refusal.code == findings.INVALID_GOAL
    assert 'path_tolerance of a: velocity is -0.5' in illegal.reason
    time = resolve_tolerances(NAMES, defaults(), goal_time_tolerance=-3.0)
    assert time.refusal.code == findings.INVALID_GOAL and 'goal_time_tolerance' in time.reason


def test_state_violation_names_joint_tolerance_and_excess():
    tolerances = StateTolerances.uniform(3, 0.1, 0.5)
    assert state_violation(NAMES, tolerances, [0.1, -0.1, 0.05]) is None   # at the bound: ok
    violation = state_violation(NAMES, tolerances, [0.05, -0.13, 0.12], [0.0, 0.0, 0.9])
    # Ratios: b 1.3, c 1.2 (position), c 1.8 (velocity): the velocity of c is the worst.
    assert (violation.joint, violation.variable) == ('c', 'velocity')
    assert_allclose(violation.excess, 0.4, rtol=0, atol=1e-12)
    assert 'c velocity error 0.9/s beyond its tolerance 0.5/s by 0.4/s' == str(violation)
    # A tolerance of 0 is not enforced, however large the error.
    assert state_violation(NAMES, StateTolerances.uniform(3), [5.0, 5.0, 5.0]) is None
    # A lost measurement (NaN) breaks an enforced tolerance.
    assert state_violation(NAMES, tolerances, [0.0, math.nan, 0.0]).joint == 'b'


def test_monitor_path_violation_before_the_end_only():
    monitor = ToleranceMonitor(NAMES, defaults(), end_time=2.0)
    assert monitor.update(0.5, np.array([0.05, 0.0, 0.0])) is None
    outcome = monitor.update(1.0, np.array([0.0, 0.15, 0.0]))
    assert outcome.error_code == PATH_TOLERANCE_VIOLATED
    assert 'b position error 0.15 beyond its tolerance 0.1 by 0.05' in outcome.error_string
    assert outcome.finding.code == findings.PATH_TOLERANCE_VIOLATED


def test_monitor_goal_success_and_timeout():
    monitor = ToleranceMonitor(NAMES, defaults(goal_time=0.5), end_time=2.0)
    # After the end, outside the goal tolerance (0.01) but inside the path's: waits.
    assert monitor.update(2.1, np.array([0.02, 0.0, 0.0]), measured_after_end=True) is None
    # A state measured before the end cannot succeed.
    assert monitor.update(2.2, np.zeros(3), measured_after_end=False) is None
    assert monitor.update(2.3, np.array([0.0, 0.005, 0.0]),
                          measured_after_end=True).error_code == SUCCESSFUL
    late = ToleranceMonitor(NAMES, defaults(goal_time=0.5), end_time=2.0)
    assert late.update(2.4, np.array([0.02, 0.0, 0.0]), measured_after_end=True) is None
    outcome = late.update(2.6, np.array([0.03, 0.0, 0.0]), measured_after_end=True)
    assert outcome.error_code == GOAL_TOLERANCE_VIOLATED
    assert 'a position error 0.03 beyond its tolerance 0.01 by 0.02' in outcome.error_string
    assert '0.600 s after the end' in outcome.error_string


def test_monitor_goal_time_zero_checks_once_at_the_end_and_nothing_measured():
    monitor = ToleranceMonitor(NAMES, defaults(goal_time=0.0), end_time=1.0)
    outcome = monitor.update(1.0, np.array([0.02, 0.0, 0.0]), measured_after_end=True)
    assert outcome.error_code == GOAL_TOLERANCE_VIOLATED
    blind = ToleranceMonitor(NAMES, defaults(goal_time=0.2), end_time=1.0)
    assert blind.update(0.5) is None and blind.update(1.1) is None
    outcome = blind.update(1.25)
    assert outcome.error_code == GOAL_TOLERANCE_VIOLATED
    assert 'no joint_states measured' in outcome.error_string
