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
The joint cones: how far each leg turns from its home direction, at either joint.

A joint is mounted to sit centred on the leg's home direction (its neutral axis); its cone is
the largest angle the leg may make with that axis. At the base joint the angle is measured in
the base frame, between the leg ``L_i`` and its home direction ``u_home_i``; at the platform
joint in the platform frame, between ``R^T L_i`` and ``R_home^T u_home_i`` (the same angle as
between ``L_i`` and ``R R_home^T u_home_i``, which is what is computed). Nothing here imports
ROS.
"""

import math

import numpy as np

from stewart_kinematics.limits.base import Bound, LEG, Limit
from stewart_kinematics.model.rotations import euler_zyx_to_matrix


class JointCones(Limit):
    """
    Evaluator of ``base_joint_max_angle`` and ``platform_joint_max_angle``, per leg.

    Values in radians (violations in degrees); NaN for a leg of zero length, which has no
    direction and breaks every cone that is set.

    :param geometry: a :class:`stewart_kinematics.Geometry`; a cone of pi is not set.
    """

    def __init__(self, geometry):
        home = geometry.home_leg_directions
        # Seen from the platform at home: R_home^T u_home, as rows.
        platform_home = home @ euler_zyx_to_matrix(geometry.home_pose[3:])
        self._home = tuple(home[:, axis:axis + 1].copy() for axis in range(3))
        self._platform_home = tuple(platform_home[:, axis:axis + 1].copy() for axis in range(3))
        self._set = tuple(getattr(geometry, name) < math.pi for name in (
            'base_joint_max_angle', 'platform_joint_max_angle'))
        self.bounds = tuple(
            Bound(name, getattr(geometry, name), True, LEG, 'deg', math.degrees(1.0))
            for name, is_set in zip(('base_joint_max_angle', 'platform_joint_max_angle'),
                                    self._set) if is_set)

    def angles(self, legs):
        """
        Return both cone angles of every leg, radians: ``(base (6, n), platform (6, n))``.

        :param legs: a :class:`~stewart_kinematics.limits.base.PoseLegs`.
        """
        lx, ly, lz = legs.vectors[:3]
        base = _angle(lx, ly, lz, *self._home)
        r11, r12, r13, r21, r22, r23, r31, r32, r33 = legs.rotation
        cx, cy, cz = self._platform_home
        # R (R_home^T u_home): the platform's home direction, turned with the platform.
        platform = _angle(lx, ly, lz, r11 * cx + r12 * cy + r13 * cz,
                          r21 * cx + r22 * cy + r23 * cz, r31 * cx + r32 * cy + r33 * cz)
        # A leg of zero length has no direction (atan2 would say 0): no angle at all.
        zero = legs.lengths == 0.0
        if zero.any():
            base[zero] = platform[zero] = np.nan
        return base, platform

    def values(self, arrays):
        """Return the angles of the cones that are set, radians, each (6, n)."""
        return tuple(angles for angles, is_set in zip(self.angles(arrays), self._set) if is_set)


def _angle(lx, ly, lz, hx, hy, hz):
    """Angles between ``l`` and ``h``: atan2 of ``|l x h|`` and ``l . h`` (any angle)."""
    cx = ly * hz - lz * hy
    cy = lz * hx - lx * hz
    cz = lx * hy - ly * hx
    return np.arctan2(np.sqrt(cx * cx + cy * cy + cz * cz), lx * hx + ly * hy + lz * hz)
