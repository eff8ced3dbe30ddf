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
Core objects built from parameter values, as the nodes declare them: the geometry, the frames.

Nothing here imports ROS.
"""

import math

import numpy as np

from stewart_kinematics.model.frames import FrameTree, Transform
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.parameters.declarations import (
    check_values,
    defaults,
    FRAME_PARAMETERS,
    GEOMETRY_PARAMETERS,
)


def geometry_from_parameters(values: dict) -> Geometry:
    """
    Build a geometry from ROS parameter values, as the nodes declare them.

    :param values: parameter name -> value, with the names and units of
        :data:`GEOMETRY_PARAMETERS` (flat joint lists in metres, home orientation in degrees);
        a missing optional one takes its default. A pivot point is the tool frame's origin
        (:func:`frames_from_parameters`), not part of the geometry.
    :raises ValueError: naming the parameter, if a value is missing or not allowed.
    """
    merged = defaults(GEOMETRY_PARAMETERS)
    # None is a value nobody set (as a spec's check takes it): the default stays.
    merged.update({key: value for key, value in values.items()
                   if key in merged and value is not None})
    check_values(GEOMETRY_PARAMETERS, merged)
    home_pose = np.concatenate([
        np.asarray(merged['home_position'], dtype=float),
        np.radians(np.asarray(merged['home_orientation_deg'], dtype=float))])
    return Geometry(
        base_joints=np.reshape(np.asarray(merged['base_joints'], dtype=float), (6, 3)),
        platform_joints=np.reshape(np.asarray(merged['platform_joints'], dtype=float), (6, 3)),
        home_pose=home_pose,
        leg_length_min=float(merged['leg_length_min']),
        leg_length_max=float(merged['leg_length_max']),
        base_joint_max_angle=math.radians(merged['base_joint_max_angle_deg']),
        platform_joint_max_angle=math.radians(merged['platform_joint_max_angle_deg']),
        max_jacobian_condition=float(merged['max_jacobian_condition']))


def frames_from_parameters(values: dict) -> FrameTree:
    """
    Build the frame tree from ROS parameter values, as the nodes declare them.

    :param values: parameter name -> value, with the names and units of
        :data:`FRAME_PARAMETERS` (positions in metres, orientations in degrees); a missing one
        takes its default.
    :raises ValueError: naming the parameter, if a value is not allowed, or for frame names
        that repeat.
    """
    merged = defaults(FRAME_PARAMETERS)
    # None is a value nobody set (as a spec's check takes it): the default stays.
    merged.update({key: value for key, value in values.items()
                   if key in merged and value is not None})
    check_values(FRAME_PARAMETERS, merged)
    return FrameTree(
        base_frame=merged['base_frame'], platform_frame=merged['platform_frame'],
        user_frame=merged['user_frame'],
        user_pose=_frame_pose(merged['user_frame_position'],
                              merged['user_frame_orientation_deg']),
        tool_frame=merged['tool_frame'],
        tool_pose=_frame_pose(merged['tool_frame_position'],
                              merged['tool_frame_orientation_deg']))


def frame_parameters_reason(values: dict) -> str:
    """
    Say why frame parameter values cannot make a frame tree, or return ``''``.

    For a run-time change, where a rule between parameters (frame names must differ) decides.
    """
    try:
        frames_from_parameters(values)
    except ValueError as error:
        return str(error)
    return ''


def _frame_pose(position, orientation_deg) -> Transform:
    """Return the transform of a position (metres) and Euler angles (degrees)."""
    return Transform.from_pose(np.concatenate([
        np.asarray(position, dtype=float), np.radians(np.asarray(orientation_deg, dtype=float))]))
