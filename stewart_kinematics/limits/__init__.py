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
The limits model: every reason a pose, or a motion, is not allowed.

Stroke, joint cones and the singularity margin of the geometry; see :mod:`.checks`.

May import: :mod:`stewart_kinematics.model` and numpy. Nothing here imports ROS.
"""

from stewart_kinematics.limits.checks import (
    check_pose,
    check_poses,
    check_poses_array,
    check_samples,
    joint_angles,
    leg_length_violations,
    LIMIT_NAMES,
    LimitChecks,
    Violation,
)

__all__ = [
    'check_pose',
    'check_poses',
    'check_poses_array',
    'check_samples',
    'joint_angles',
    'leg_length_violations',
    'LIMIT_NAMES',
    'LimitChecks',
    'Violation',
]
