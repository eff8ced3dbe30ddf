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
Property tests of the analyses: workspace, assembly modes and calibration.

What they report is checked against the public check of a pose (CommandCheck): every end of
a travel range and every boundary point is reachable, and a move past an end is not; the
reachable points of a slice are those the check accepts; every assembly mode has the given
leg lengths and the pose they came from is among them; a calibration of synthetic
measurements finds the platform that made them. Hostile arguments are refused naming them.
Grids are coarse and examples few: these are the dearest functions of the package.
"""

import math

from hypothesis import given, strategies as st
import numpy as np
from numpy.testing import assert_allclose
from properties import (
    assert_refused,
    budget,
    covers,
    floats,
    HOME_POSE,
    LIMITED,
    NON_FINITE,
    NOT_NUMBERS,
    pose_distance,
    poses_near_home,
    with_bad_entry,
)
import pytest

from stewart_kinematics import (
    assembly_mode_margin,
    assembly_modes,
    AssemblyMode,
    AssemblyModeMargin,
    AssemblyModes,
    calibrate,
    CalibrationError,
    CalibrationResult,
    CommandCheck,
    inverse_kinematics,
    measurement_poses,
    orientation_workspace,
    travel_ranges,
    workspace_slice,
    workspace_volume,
)

pytestmark = pytest.mark.core

CHECK = CommandCheck(LIMITED)
COARSE = math.radians(3.0)


def reachable(pose):
    """Return whether the public check accepts the pose."""
    return CHECK.pose_vector(pose).accepted


@covers('travel_ranges')
@budget(5)
@given(poses_near_home(position=0.02, angle=math.radians(4.0)))
def test_every_end_of_a_travel_range_is_reachable_and_the_next_step_is_not(pose):
    if not reachable(pose):
        assert_refused(lambda: travel_ranges(LIMITED, pose), ('start pose',))
        return
    ranges = travel_ranges(LIMITED, pose, step=(2e-3, 4e-3))
    for axis, travel in enumerate(ranges.axes):
        for end, limit in ((travel.negative, travel.negative_limit),
                           (travel.positive, travel.positive_limit)):
            moved = np.array(pose)
            moved[axis] += end
            assert reachable(moved), (travel, end)
            if limit is not None:
                moved[axis] += math.copysign(1e-5, end)
                assert not reachable(moved), (travel, end)


@covers('workspace_slice', 'orientation_workspace', 'workspace_volume')
@budget(4)
@given(poses_near_home(position=0.01, angle=math.radians(3.0)), st.data())
def test_the_reachable_points_of_a_workspace_are_those_the_check_accepts(pose, data):
    if not reachable(pose):
        return
    plane = data.draw(st.sampled_from(['XY', 'XZ', 'YZ']))
    grid = workspace_slice(LIMITED, plane, pose, resolution=0.01)
    rows = data.draw(st.lists(st.tuples(st.integers(0, len(grid.v) - 1),
                                        st.integers(0, len(grid.u) - 1)), max_size=8))
    for row, column in rows:
        point = np.array(pose)
        point[list(grid.axes)] = grid.u[column], grid.v[row]
        assert bool(grid.allowed[row, column]) == reachable(point)
    for u, v in grid.boundary[:20]:
        point = np.array(pose)
        point[list(grid.axes)] = u, v
        assert reachable(point)
    (angles,) = orientation_workspace(LIMITED, pose[:3], [pose[5]], resolution=COARSE)
    assert angles.labels == ('alpha', 'beta') and angles.area > 0.0
    volume = workspace_volume(LIMITED, pose[3:], position=pose[:3], resolution=0.03)
    assert volume.bounded and volume.volume > 0.0
    low, high = volume.bounding_box
    assert np.all(low <= pose[:3] + 1e-9) and np.all(pose[:3] <= high + 1e-9)
    assert all(reachable(np.concatenate([point, pose[3:]])) for point in volume.boundary[:20])


@covers('travel_ranges', 'workspace_slice', 'workspace_volume', 'orientation_workspace')
@budget(20)
@given(st.one_of(NOT_NUMBERS, NON_FINITE.flatmap(lambda bad: with_bad_entry(HOME_POSE, bad))))
def test_workspace_functions_refuse_bad_poses_and_resolutions(value):
    if value is None:   # the default of every one of these arguments
        value = 'none'
    assert_refused(lambda: travel_ranges(LIMITED, value), ('pose',))
    assert_refused(lambda: workspace_slice(LIMITED, 'XY', value), ('pose',))
    assert_refused(lambda: workspace_slice(LIMITED, 'XY', resolution=value
                                           if not isinstance(value, np.ndarray) else -1.0),
                   ('resolution',))
    assert_refused(lambda: workspace_volume(LIMITED, resolution=value
                                            if not isinstance(value, np.ndarray) else 0.0),
                   ('resolution',))
    assert_refused(lambda: workspace_volume(LIMITED, position=value
                                            if not isinstance(value, np.ndarray)
                                            else [math.nan, 0.0, 0.4]), ('position',))
    assert_refused(lambda: orientation_workspace(LIMITED, gammas=value
                                                 if not isinstance(value, np.ndarray)
                                                 else [math.nan]), ('gamma',))
    assert_refused(lambda: workspace_slice(LIMITED, 'XQ'), ('plane',))


@covers('assembly_modes', 'AssemblyModes', 'AssemblyMode', 'assembly_mode_margin',
        'AssemblyModeMargin')
@budget(3)
@given(poses_near_home(position=0.03, angle=math.radians(8.0)))
def test_every_assembly_mode_has_the_lengths_and_the_pose_is_among_them(pose):
    lengths = inverse_kinematics(LIMITED, pose)
    modes = assembly_modes(LIMITED, lengths, pose)
    assert isinstance(modes, AssemblyModes) and modes.complete, modes.reason
    assert all(isinstance(mode, AssemblyMode) for mode in modes.modes)
    for mode in modes.modes:
        assert_allclose(inverse_kinematics(LIMITED, mode.pose), lengths, rtol=0, atol=1e-9)
        assert mode.within_limits == reachable(mode.pose) or mode.condition > 40.0
    assert min(pose_distance(mode.pose, pose) for mode in modes.modes) < 1e-9
    margin = assembly_mode_margin(LIMITED, pose, lengths, modes)
    assert isinstance(margin, AssemblyModeMargin)
    if margin.nearest is not None:
        assert margin.distance > 0.0 and margin.nearest.within_limits
    else:
        assert margin.distance == math.inf


@covers('assembly_modes', 'assembly_mode_margin')
@budget(20)
@given(st.one_of(NOT_NUMBERS, NON_FINITE.flatmap(
    lambda bad: with_bad_entry(np.array(LIMITED.home_leg_lengths), bad)),
    st.just([-0.7] * 6), st.just([0.7] * 5)))
def test_assembly_modes_refuse_bad_lengths_naming_them(value):
    assert_refused(lambda: assembly_modes(LIMITED, value), ('lengths',))
    if value is None or isinstance(value, list) and len(value) == 6 and all(
            isinstance(item, float) and math.isfinite(item) for item in value):
        return   # six finite numbers: a pose, if not lengths; None: the default pose
    assert_refused(lambda: assembly_modes(LIMITED, LIMITED.home_leg_lengths, value),
                   ('reference', 'pose'))
    assert_refused(lambda: assembly_mode_margin(LIMITED, value), ('pose',))


@covers('calibrate', 'CalibrationResult', 'measurement_poses')
@budget(3)
@given(st.tuples(*[floats(-2e-3, 2e-3)] * 36), st.tuples(*[floats(0.6, 0.7)] * 6),
       st.integers(0, 2 ** 16))
def test_a_calibration_finds_the_platform_that_made_the_measurements(joint_errors, offsets,
                                                                     seed):
    from dataclasses import replace
    errors = np.array(joint_errors).reshape(2, 6, 3)
    built = replace(LIMITED, base_joints=LIMITED.base_joints + errors[0],
                    platform_joints=LIMITED.platform_joints + errors[1])
    selection = measurement_poses(LIMITED, 30, candidates=600, random_draws=3, seed=seed)
    assert selection.poses.shape == (30, 6)
    assert all(reachable(pose) for pose in selection.poses)
    readings = inverse_kinematics(built, selection.poses) - np.array(offsets)
    result = calibrate(LIMITED, selection.poses, readings, np.full(6, 0.65))
    assert isinstance(result, CalibrationResult)
    assert_allclose(result.actuator_offsets, offsets, rtol=0, atol=1e-6)
    assert_allclose(result.geometry.base_joints, built.base_joints, rtol=0, atol=1e-6)
    assert result.rms_after.max() < 1e-9 and result.outliers == ()


@covers('calibrate', 'CalibrationError', 'measurement_poses')
@budget(25)
@given(st.sampled_from(['outlier_threshold', 'max_condition', 'max_noise',
                        'max_outlier_fraction', 'min_outlier_residual', 'loss']),
       st.one_of(NOT_NUMBERS, NON_FINITE, st.sampled_from([-1.0, 0.0, 1e-9, 2.0])), st.data())
def test_calibration_refuses_bad_options_and_data_naming_them(name, value, data):
    poses = np.tile(HOME_POSE, (10, 1)) + np.linspace(0.0, 0.01, 10)[:, None]
    readings = inverse_kinematics(LIMITED, poses) - 0.65
    try:
        calibrate(LIMITED, poses, readings, **{name: value})
    except CalibrationError:
        pass   # an allowed setting: the data (hardly varied poses) decide
    except ValueError as error:
        assert name in str(error), error
    with pytest.raises(CalibrationError, match='too few poses'):
        calibrate(LIMITED, poses[:5], readings[:5])
    assert_refused(lambda: calibrate(LIMITED, poses, readings[:, :5]), ('actuator_positions',))
    bad = data.draw(with_bad_entry(readings, math.nan))
    assert_refused(lambda: calibrate(LIMITED, poses, bad), ('actuator_positions',))
    assert_refused(lambda: measurement_poses(LIMITED, 7), ('count',))
    assert_refused(lambda: measurement_poses(LIMITED, 10, position_range=-0.1),
                   ('position_range',))
    assert issubclass(CalibrationError, ValueError)
