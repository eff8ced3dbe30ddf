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
Core defects the node fuzzer found (test_fuzz_nodes.py), each kept as the smallest example.

Each failed before its fix; the fuzzer's message that found it is quoted in the docstring.
"""

from pathlib import Path

import numpy as np
import pytest

from stewart_kinematics.findings import TRAJECTORY_TOO_LONG
from stewart_kinematics.motion.planning import plan_motion
from stewart_kinematics.motion.pose_trajectory import PoseTrajectory, TimedTrajectory
from stewart_kinematics.motion.trajectory_check import check_trajectory, MAX_CHECK_SAMPLES
from stewart_kinematics.parameters import (
    actuator_limits_from_settings,
    GeometrySettings,
    load_geometry,
    read_parameter_files,
)

pytestmark = pytest.mark.core

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
FILES = [CONFIG_DIRECTORY / 'paper_platform.yaml', CONFIG_DIRECTORY / 'example_limits.yaml']
HOME = np.array([0.0, 0.0, 0.4325])


@pytest.fixture(scope='module')
def platform():
    """Return the paper's platform with the example limits, and its actuator limits."""
    values = read_parameter_files(FILES)
    return load_geometry(FILES), actuator_limits_from_settings(GeometrySettings.from_values(
        values))


def test_a_path_to_a_far_waypoint_is_refused_without_sampling_it(platform):
    """
    A pose_path with one waypoint 10^9 m away: refused with a reason, never a MemoryError.

    The fuzzer's path had a waypoint at 1e9 m: its nominal time by leg travel was 2e9 s, toppra
    failed, and the check of the path as given asked numpy for 7 to 15 TiB of sample times
    (MemoryError: trajectory_node exited). Issue 20's inputs now refuse such a waypoint by
    name, before any timing.
    """
    geometry, _ = platform
    with pytest.raises(ValueError, match='beyond 1000 m'):
        PoseTrajectory.path(geometry, [HOME, HOME + [1e9, 0.0, 0.0]], np.stack([np.eye(3)] * 2))


def test_a_check_that_needs_too_many_samples_is_refused_before_sampling(platform):
    """A 10^6 s trajectory of 5000 waypoints at 1 kHz: refused by count, not sampled."""
    geometry, limits = platform
    count = 5000
    steps = np.linspace(0.0, 0.001, count)[:, None] * [1.0, 0.0, 0.0]
    path = PoseTrajectory(np.linspace(0.0, 1e6, count), HOME + steps,
                          np.stack([np.eye(3)] * count))
    check = check_trajectory(TimedTrajectory.as_given(path), geometry, limits,
                             validation_rate=1000.0)
    assert not check.accepted and not check.complete
    assert f'{MAX_CHECK_SAMPLES:,}' in check.reason, check.reason
    plan = plan_motion(path, geometry, limits)
    assert plan.refusal.code == TRAJECTORY_TOO_LONG, plan.refusal


def test_a_frame_offset_too_far_for_the_arithmetic_is_refused():
    """
    tool_frame_position and user_frame_position: within 1 km, or refused naming the parameter.

    The fuzzer set tool_frame_position to about 1e308 m (finite, so allowed), and fk_node then
    published estimated poses some 1e308 m away: a platform pose within every limit, lost in
    the rounding of the offset, and for an offset along two axes at a turned platform the sum
    overflows to inf, a non-finite output.
    """
    from stewart_kinematics.parameters import FrameSettings, frames_from_settings
    for name in ('tool_frame_position', 'user_frame_position'):
        with pytest.raises(ValueError, match=name):
            FrameSettings(**{name: (1.7e308, 1.7e308, 0.0)})
        with pytest.raises(ValueError, match=name):
            FrameSettings(**{name: (0.0, 1001.0, 0.0)})
    # At the bound, a tool pose keeps the platform pose to well below a micrometre.
    frames = frames_from_settings(FrameSettings(tool_frame_position=(1000.0, -1000.0, 1000.0)))
    platform = np.array([0.01, -0.02, 0.45, 0.1, -0.05, 0.785])
    tool = frames.tool_pose_vector(platform)
    from stewart_kinematics.model.frames import Transform
    back = frames.platform_from_tool(Transform.from_pose(tool)).as_pose()
    np.testing.assert_allclose(back, platform, atol=1e-9)
