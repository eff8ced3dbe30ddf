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
Reachability: every reason a pose, or a set of leg lengths, is not allowed.

The limits are those of :class:`stewart_kinematics.Geometry`:

- leg length: ``leg_length_min <= l_i <= leg_length_max`` (actuator stroke);
- joint cone angle: the angle between leg ``i`` and its direction at the home pose, seen from
  the base joint (base frame) and from the platform joint (platform frame), is at most
  ``base_joint_max_angle`` and ``platform_joint_max_angle``; the home direction is the joint's
  neutral axis, as a joint is mounted to sit centred there;
- singularity margin: the condition number of the dimensionless Jacobian (see
  :func:`jacobian_condition`) is at most ``max_jacobian_condition``.

Like a hexapod controller's "is this pose valid?", the checks return every violation (which
leg, which limit, by how much), not only the first. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import List, Optional

import numpy as np

from stewart_kinematics.kinematics import (
    as_leg_lengths,
    as_poses,
    jacobian_condition,
    leg_lengths,
    leg_vectors,
)
from stewart_kinematics.rotations import euler_zyx_to_matrix

#: How many failing samples :func:`check_samples` lists in full.
LISTED_FAILURES = 10


@dataclass(frozen=True)
class Violation:
    """
    One limit that a pose or a set of leg lengths breaks.

    :param limit: the limit's parameter name, such as ``leg_length_max``.
    :param leg: the leg concerned, 1..6, or ``None`` for the whole platform.
    :param value: the value reached, in ``unit``.
    :param allowed: the limit, in ``unit``.
    :param unit: ``m``, ``deg`` or ``''`` (condition number).
    """

    limit: str
    leg: Optional[int]
    value: float
    allowed: float
    unit: str

    @property
    def excess(self) -> float:
        """By how much the limit is broken, in ``unit``, always positive."""
        return abs(self.value - self.allowed)

    def __str__(self):
        unit = f' {self.unit}' if self.unit else ''
        subject = f'leg {self.leg}' if self.leg else 'platform'
        return (f'{subject}: {self.limit} {self.allowed:.6g}{unit} broken by '
                f'{self.excess:.6g}{unit} (value {self.value:.6g}{unit})')


def leg_length_violations(geometry, lengths) -> List[Violation]:
    """
    Every leg length outside ``[leg_length_min, leg_length_max]``.

    :param lengths: leg lengths l_1..l_6 in metres, shape (6,).
    :raises ValueError: if the lengths are not six finite, positive numbers.
    """
    lengths = as_leg_lengths(lengths)
    if lengths.shape != (6,):
        raise ValueError(f'expected the 6 lengths of one pose, got shape {lengths.shape}')
    violations = []
    for leg, length in enumerate(lengths.tolist(), start=1):
        if length < geometry.leg_length_min:
            violations.append(Violation('leg_length_min', leg, length, geometry.leg_length_min,
                                        'm'))
        elif length > geometry.leg_length_max:
            violations.append(Violation('leg_length_max', leg, length, geometry.leg_length_max,
                                        'm'))
    return violations


def joint_angles(geometry, position, rotation):
    """
    Cone angles of the joints: each leg's angle to its home direction, radians.

    :param position: platform position in the base frame, metres, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation, shape (3, 3) or (N, 3, 3).
    :returns: ``(base_angles, platform_angles)``, each shape (6,) or (N, 6): at the base joint
        measured in the base frame, at the platform joint measured in the platform frame.
    """
    legs = leg_vectors(geometry, position, rotation)
    directions = legs / np.linalg.norm(legs, axis=-1, keepdims=True)
    home = geometry.home_leg_directions
    home_rotation = euler_zyx_to_matrix(geometry.home_pose[3:])
    # In the platform frame: R^T u now against R_home^T u_home.
    platform_now = np.swapaxes(np.swapaxes(rotation, -1, -2) @ np.swapaxes(directions, -1, -2),
                               -1, -2)
    platform_home = home @ home_rotation
    return _angle_between(directions, home), _angle_between(platform_now, platform_home)


def check_pose(geometry, position, rotation) -> List[Violation]:
    """
    Every limit that one pose breaks; empty when the pose is allowed.

    :param position: platform position in the base frame, metres, shape (3,).
    :param rotation: platform-to-base rotation matrix, shape (3, 3).
    :raises ValueError: if the position or the rotation is malformed or not finite.
    """
    position, rotation = np.asarray(position, dtype=float), np.asarray(rotation, dtype=float)
    if position.shape != (3,) or rotation.shape != (3, 3):
        raise ValueError(f'expected a position (3,) and a rotation (3, 3), got shapes '
                         f'{position.shape} and {rotation.shape}')
    if not all(map(math.isfinite, position.tolist() + rotation.ravel().tolist())):
        raise ValueError(f'pose must be finite, got position {position.tolist()}')
    # Each check runs only where its limit is set: the nodes call this for every message.
    violations = []
    if geometry.leg_length_min > 0.0 or geometry.leg_length_max < math.inf:
        violations += leg_length_violations(geometry, leg_lengths(geometry, position, rotation))
    if min(geometry.base_joint_max_angle, geometry.platform_joint_max_angle) < math.pi:
        base_angles, platform_angles = joint_angles(geometry, position, rotation)
        for limit, angles, allowed in (
                ('base_joint_max_angle', base_angles, geometry.base_joint_max_angle),
                ('platform_joint_max_angle', platform_angles,
                 geometry.platform_joint_max_angle)):
            for leg in np.flatnonzero(angles > allowed):
                violations.append(Violation(limit, int(leg) + 1, math.degrees(angles[leg]),
                                            math.degrees(allowed), 'deg'))
    if math.isfinite(geometry.max_jacobian_condition):
        condition = float(jacobian_condition(geometry, position, rotation))
        if not condition <= geometry.max_jacobian_condition:
            violations.append(Violation('max_jacobian_condition', None, condition,
                                        geometry.max_jacobian_condition, ''))
    return violations


def check_poses(geometry, poses) -> List[List[Violation]]:
    """
    Every limit that each of a batch of poses breaks.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (N, 6).
    :returns: one list per pose, empty for an allowed pose.
    """
    poses = np.atleast_2d(as_poses(poses))
    rotations = euler_zyx_to_matrix(poses[:, 3:])
    return [check_pose(geometry, pose[:3], rotation)
            for pose, rotation in zip(poses, rotations)]


def check_samples(geometry, times, poses):
    """
    Refuse a trajectory any of whose samples breaks a limit of ``geometry``.

    trajectory_node checks every pose it would publish with this before it plays a ramp.

    :param times: seconds from the start of a pass, shape (N,).
    :param poses: the samples, ``[X, Y, Z, alpha, beta, gamma]``, shape (N, 6).
    :raises ValueError: listing the failing samples (time, pose, every violation).
    """
    failures = [(index, violations) for index, violations
                in enumerate(check_poses(geometry, poses)) if violations]
    if not failures:
        return
    lines = [
        f'sample {index} at t={times[index]:.3f} s, pose '
        f'{np.round(poses[index], 6).tolist()}: ' + '; '.join(map(str, violations))
        for index, violations in failures[:LISTED_FAILURES]]
    more = len(failures) - LISTED_FAILURES
    raise ValueError(
        f'ramp refused: {len(failures)} of {len(poses)} samples break the limits of the '
        'geometry:\n  ' + '\n  '.join(lines) + (f'\n  ... and {more} more' if more > 0 else ''))


def _angle_between(a, b):
    # atan2 of |a x b| and a . b is accurate for small and large angles alike.
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))
