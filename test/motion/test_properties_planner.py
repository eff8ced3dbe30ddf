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
Property tests of MotionPlanner: what a message carries in, a decided plan out, never a raise.

Waypoints of a tool frame offset from the platform, with random times, are planned as timed
or retimed: an accepted plan puts the tool frame on every waypoint (the platform's sampled
pose composed with the tool frame, against the waypoint) and keeps every limit; a refused one
carries a code of the registry and a reason in the package's words. Hostile times, positions,
quaternions and twists are refused as ``invalid_trajectory``, naming what is wrong.
"""

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose
from properties import (
    budget,
    covers,
    floats,
    HOME_POSE,
    LIMITED,
    NON_FINITE,
    NOT_NUMBERS,
    NUMPY_WORDS,
    poses_near_home,
)
import pytest

from stewart_kinematics import (
    ActuatorLimits,
    check_trajectory,
    euler_zyx_to_matrix,
    euler_zyx_to_quaternion,
    FrameTree,
    MotionPlan,
    MotionPlanner,
    Transform,
)
from stewart_kinematics.findings import CODES

pytestmark = pytest.mark.core

LIMITS = ActuatorLimits(velocity_max=0.05, acceleration_max=0.25, jerk_max=2.5)
#: The tool frame: its origin 6 cm above the platform's, turned; the waypoints are lifted as
#: much, so that the platform stays near home.
TOOL = Transform([0.01, -0.02, 0.06], euler_zyx_to_matrix([0.0, 0.1, 0.3]))
FRAMES = FrameTree(tool_frame='tool', tool_pose=TOOL)
LIFT = np.array([0.0, 0.0, 0.06, 0.0, 0.0, 0.0])


def waypoint_sets(max_size=5):
    """Draw (times, tool poses): 2 to max_size waypoints near home, 0.5 to 5 s apart."""
    return st.integers(2, max_size).flatmap(lambda count: st.tuples(
        st.lists(floats(0.5, 5.0), min_size=count - 1, max_size=count - 1),
        st.lists(poses_near_home(position=0.02, angle=0.1), min_size=count,
                 max_size=count))).map(lambda drawn: (
                     np.concatenate([[0.0], np.cumsum(drawn[0])]),
                     np.array(drawn[1]) + LIFT))


def assert_decided(plan):
    """Check that a plan is a decision: accepted, or refused with a registered code."""
    assert isinstance(plan, MotionPlan)
    if not plan.accepted:
        assert plan.refusal.code in CODES and plan.trajectory is None, plan.refusal
        assert not any(words in plan.reason for words in NUMPY_WORDS), plan.reason


@covers('MotionPlanner')
@budget(10)
@given(waypoint_sets(), st.booleans())
def test_an_accepted_plan_puts_the_tool_frame_on_every_waypoint(data, retime):
    """The platform's pose at each waypoint, composed with the tool frame, is the waypoint."""
    times, poses = data
    planner = MotionPlanner(LIMITED, LIMITS, FRAMES, retime=retime)
    plan = planner.plan_trajectory(times, poses[:, :3], euler_zyx_to_quaternion(poses[:, 3:]))
    assert_decided(plan)
    if not plan.accepted:
        return
    trajectory = plan.trajectory
    assert check_trajectory(trajectory, LIMITED, LIMITS).accepted
    samples = trajectory.sample(trajectory.waypoint_times)
    kept = trajectory.path.point_indices
    for index, position, rotation in zip(kept, samples.positions, samples.rotations):
        tool = Transform(position, rotation) @ TOOL
        assert_allclose(tool.position, poses[index, :3], atol=1e-9)
        assert_allclose(tool.rotation, euler_zyx_to_matrix(poses[index, 3:]), atol=1e-9)


@covers('MotionPlanner')
@budget(30)
@given(waypoint_sets(max_size=3),
       st.sampled_from(['times', 'positions', 'quaternions', 'velocities']),
       st.one_of(NOT_NUMBERS, NON_FINITE, st.sampled_from([1e308, -1.0, 2.0 ** 31])),
       st.booleans())
def test_hostile_fields_are_refused_as_invalid_trajectories(data, field, bad, retime):
    """A field replaced by garbage, or one entry by a bad number: refused, never raised."""
    times, poses = data
    fields = {'times': times, 'positions': poses[:, :3],
              'quaternions': euler_zyx_to_quaternion(poses[:, 3:]),
              'velocities': np.zeros((len(times), 3)),
              'angular_velocities': np.zeros((len(times), 3))}
    if isinstance(bad, float):
        fields[field] = np.array(fields[field], dtype=float)
        fields[field].flat[-1] = bad
    else:
        fields[field] = bad
    plan = MotionPlanner(LIMITED, LIMITS, FRAMES, retime=retime).plan_trajectory(**fields)
    assert_decided(plan)
    if isinstance(bad, float) and field in ('positions', 'velocities') and abs(bad) < 1e3:
        return   # a small finite number is a valid input: decided either way
    if isinstance(bad, float) and field == 'quaternions' and np.isfinite(bad):
        return   # normalised: another orientation
    if isinstance(bad, float) and field == 'times' and 0.0 <= bad <= 1e6:
        return
    assert plan.refusal.code == 'invalid_trajectory', plan.refusal


@covers('MotionPlanner')
@budget(10)
@given(st.one_of(NOT_NUMBERS, st.just(np.zeros((0, 3)))), st.booleans())
def test_hostile_paths_are_refused(bad, with_quaternions):
    """Garbage positions or quaternions of a path, or none at all: invalid_trajectory."""
    good = np.tile(HOME_POSE[:3] + LIFT[:3], (2, 1))
    quaternions = np.tile([0.0, 0.0, 0.0, 1.0], (2, 1))
    plan = (MotionPlanner(LIMITED, LIMITS, FRAMES).plan_path(good, bad) if with_quaternions
            else MotionPlanner(LIMITED, LIMITS, FRAMES).plan_path(bad, quaternions))
    assert_decided(plan)
    assert plan.refusal.code == 'invalid_trajectory', plan.refusal
