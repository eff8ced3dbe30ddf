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
Property tests of the limits model: its checks agree with each other and with CommandCheck.

One pose against a batch, a pose against the decision ik_node takes on it, one leg state
against a batch of them; a scale that brings leg velocities within their limit does; and
what is not a pose or a leg state is refused naming it.
"""

import math

from hypothesis import given, strategies as st
import numpy as np
from properties import (
    assert_refused,
    budget,
    covers,
    floats,
    LIMITED,
    NON_FINITE,
    NOT_NUMBERS,
    poses_near_home,
    with_bad_entry,
)
import pytest

from stewart_kinematics import ActuatorLimits, CommandCheck, euler_zyx_to_matrix, LimitModel

pytestmark = pytest.mark.core

WIDE = poses_near_home(position=0.25, angle=math.radians(40.0))
ACTUATOR_LIMITS = ActuatorLimits(0.05, 0.25, 2.5)


@covers('LimitModel', 'CommandCheck')
@budget(40)
@given(st.lists(WIDE, min_size=1, max_size=6))
def test_one_pose_a_batch_and_the_decision_agree(poses):
    model = LimitModel(LIMITED)
    batch = model.check_poses(np.array(poses))
    check = CommandCheck(LIMITED)
    for k, pose in enumerate(poses):
        violations = model.check_pose(pose[:3], euler_zyx_to_matrix(pose[3:]))
        assert bool(batch.allowed[k]) == (not violations)
        command = check.pose_vector(pose)
        assert command.accepted == (not violations)
        if not command.accepted and command.refusal.code == 'out_of_limits':
            assert {v.limit for v in command.violations} == {v.limit for v in violations}


@covers('LimitModel', 'ActuatorLimits')
@budget(40)
@given(st.lists(st.tuples(*[floats(0.5, 1.0)] * 6), min_size=1, max_size=5),
       st.lists(st.tuples(*[floats(-0.2, 0.2)] * 6), min_size=1, max_size=5))
def test_leg_states_one_against_a_batch_and_the_velocity_scale(lengths, velocities):
    model = LimitModel(LIMITED, ACTUATOR_LIMITS)
    count = min(len(lengths), len(velocities))
    lengths, velocities = np.array(lengths[:count]), np.array(velocities[:count])
    batch = model.check_leg_states(lengths=lengths, velocities=velocities)
    for k in range(count):
        violations = model.leg_state_violations(lengths=lengths[k], velocities=velocities[k])
        assert bool(batch.allowed[k]) == (not violations)
        scale = model.leg_velocity_scale(velocities[k])
        assert 0.0 < scale <= 1.0
        assert np.max(np.abs(velocities[k] * scale)) <= ACTUATOR_LIMITS.velocity_max * (
            1 + 1e-12)


@covers('LimitModel')
@budget(40)
@given(st.one_of(NOT_NUMBERS, NON_FINITE.flatmap(
    lambda bad: with_bad_entry(np.zeros((2, 6)) + [0, 0, 0.45, 0, 0, 0], bad))))
def test_what_is_not_a_pose_or_a_leg_state_is_refused(value):
    model = LimitModel(LIMITED, ACTUATOR_LIMITS)
    assert_refused(lambda: model.check_poses(value), ('poses', 'pose'))
    assert_refused(lambda: model.check_pose(value, np.eye(3)), ('position',))
    if isinstance(value, np.ndarray):   # numbers, some not finite: refused as breaking limits
        assert not np.any(model.check_leg_states(lengths=value).allowed)
        assert_refused(lambda: model.leg_velocity_scale(value), ('velocities',))
    elif value is not None:   # None: a quantity not given
        assert_refused(lambda: model.check_leg_states(lengths=value), ('lengths',))
        assert_refused(lambda: model.leg_velocity_scale(value), ('velocities',))
