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

from stewart_kinematics.limits.base import Bound, LEG, Limit, row_violations
from stewart_kinematics.limits.kind import BoundLook, LimitKind, LimitParameter
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.model.validators import Finite, InRange

#: The names of the two cones, base joint then platform joint: their bounds and settings.
CONES = ('base_joint_max_angle', 'platform_joint_max_angle')


class JointCones(Limit):
    """
    Evaluator of ``base_joint_max_angle`` and ``platform_joint_max_angle``, per leg.

    Values in radians (violations in degrees); NaN for a leg of zero length, which has no
    direction and breaks every cone that is set.

    :param geometry: a :class:`stewart_kinematics.Geometry`: its home leg directions.
    :param base_joint_max_angle: the base joint's cone, radians; pi (the default) is not set.
    :param platform_joint_max_angle: the platform joint's cone, radians; pi is not set.
    """

    def __init__(self, geometry, base_joint_max_angle: float = math.pi,
                 platform_joint_max_angle: float = math.pi):
        home = geometry.home_leg_directions
        # Seen from the platform at home: R_home^T u_home, as rows.
        platform_home = home @ euler_zyx_to_matrix(geometry.home_pose[3:])
        self._home = tuple(home[:, axis:axis + 1].copy() for axis in range(3))
        self._platform_home = tuple(platform_home[:, axis:axis + 1].copy() for axis in range(3))
        # The same, leg by leg in floats, for one pose.
        self._float_homes = tuple(zip(home.tolist(), platform_home.tolist()))
        allowed = (base_joint_max_angle, platform_joint_max_angle)
        self._set = tuple(angle < math.pi for angle in allowed)
        self.bounds = tuple(
            Bound(name, angle, True, LEG, 'deg', math.degrees(1.0))
            for name, angle, is_set in zip(CONES, allowed, self._set) if is_set)

    def angles(self, legs):
        """
        Return both cone angles of every leg, radians: ``(base (6, n), platform (6, n))``.

        :param legs: a :class:`~stewart_kinematics.limits.base.PoseLegs`.
        """
        lx, ly, lz = legs.vectors[:3]
        base, platform = _cone_angles(lx, ly, lz, self._home, self._platform_home,
                                      legs.rotation, np.sqrt, np.arctan2)
        # A leg of zero length has no direction (atan2 would say 0): no angle at all.
        zero = legs.lengths == 0.0
        if zero.any():
            base[zero] = platform[zero] = np.nan
        return base, platform

    def values(self, arrays):
        """Return the angles of the cones that are set, radians, each (6, n)."""
        return tuple(angles for angles, is_set in zip(self.angles(arrays), self._set) if is_set)

    def violations_of_one(self, legs):
        """
        See :meth:`Limit.violations_of_one`: the formulas of :meth:`angles` on floats, leg by leg.

        The arctangents of the twelve angles in one ``numpy.arctan2`` (whose results differ
        from ``math.atan2``'s in the last bit), so that they equal the arrays' to the bit.
        """
        if legs.floats is None:
            return super().violations_of_one(legs)
        rotation = legs.float_rotation
        sines, cosines, zero = [], [], []
        for row, ((length, lx, ly, lz, *_), (home, platform_home)) in enumerate(
                zip(legs.floats, self._float_homes)):
            for sine, cosine in _cone_terms(lx, ly, lz, home, platform_home, rotation, math.sqrt):
                sines.append(sine)
                cosines.append(cosine)
            if length == 0.0:
                zero.append(row)
        angles = np.arctan2(sines, cosines).tolist()
        values = [angles[0::2], angles[1::2]]
        for row in zero:   # no direction: no angle at all (as in angles)
            values[0][row] = values[1][row] = math.nan
        return [violation for bound, angles in zip(
            self.bounds, (angles for angles, is_set in zip(values, self._set) if is_set))
            for violation in row_violations(bound, angles)]


def _cone_angles(lx, ly, lz, home, platform_home, rotation, sqrt, atan2):
    """
    Both cone angles of legs ``l`` (arrays (6, n)): :func:`_cone_terms`' arctangents.

    :returns: ``(base, platform)``, radians.
    """
    (base_sine, base_cosine), (sine, cosine) = _cone_terms(lx, ly, lz, home, platform_home,
                                                           rotation, sqrt)
    return atan2(base_sine, base_cosine), atan2(sine, cosine)


def _cone_terms(lx, ly, lz, home, platform_home, rotation, sqrt):
    """
    Both cone angles of legs ``l`` as ``(|l x h|, l . h)``: to ``home`` and ``R platform_home``.

    The one formula of the cone angles (``atan2`` of the two terms), on floats for one leg
    (``math.sqrt``) or on arrays (6, n) for the legs of poses (``numpy.sqrt``).

    :param home: the home direction's x, y, z (base frame); ``platform_home``: that of the
        platform joint, ``R_home^T u_home`` (platform frame).
    :param rotation: ``(r11, ..., r33)`` of the platform-to-base rotation.
    """
    r11, r12, r13, r21, r22, r23, r31, r32, r33 = rotation
    cx, cy, cz = platform_home
    # R (R_home^T u_home): the platform's home direction, turned with the platform.
    return (_angle_terms(lx, ly, lz, *home, sqrt),
            _angle_terms(lx, ly, lz, r11 * cx + r12 * cy + r13 * cz,
                         r21 * cx + r22 * cy + r23 * cz, r31 * cx + r32 * cy + r33 * cz, sqrt))


def _angle_terms(lx, ly, lz, hx, hy, hz, sqrt):
    """Return the angle between ``l`` and ``h`` as ``(|l x h|, l . h)``, its atan2's terms."""
    cx = ly * hz - lz * hy
    cy = lz * hx - lx * hz
    cz = lx * hy - ly * hx
    return sqrt(cx * cx + cy * cy + cz * cz), lx * hx + ly * hy + lz * hz


def _narrowed(limits, margins) -> dict:
    """Each cone that is set, drawn in by the angle margin (never to 0)."""
    return {name: max(getattr(limits, name) - margins.angle, 1e-9) for name in CONES
            if getattr(limits, name) < math.pi}


def _evaluator(geometry, limits) -> JointCones:
    return JointCones(geometry, limits.base_joint_max_angle, limits.platform_joint_max_angle)


def _cone(joint: str, where: str) -> LimitParameter:
    """Return the parameter of one joint's cone: degrees, in (0, 180], radians as setting."""
    return LimitParameter(
        f'{joint}_joint_max_angle_deg', 'deg', 180.0,
        f'Largest angle between a leg and its home direction at the {joint} joint{where} '
        '(joint cone), degrees; 180.0 for no limit',
        (Finite(), InRange(0.0, 180.0, low_inclusive=False)),
        setting=f'{joint}_joint_max_angle', to_setting=math.radians, to_parameter=math.degrees)


#: The joint cones: their parameters (degrees; radians as settings), bounds and evaluator.
KIND = LimitKind(
    name='joint_cones',
    title='Joint cones',
    meaning=('Angle between each leg and its direction at the home pose, at the base joint '
             '(base frame) and at the platform joint (platform frame): a joint is mounted '
             'centred on its home direction. A leg of zero length has no direction and breaks '
             'every cone set.'),
    evaluator='JointCones',
    parameters=(_cone('base', ''), _cone('platform', ', in the platform frame')),
    bounds=(BoundLook('base_joint_max_angle', 'base joint cone', (0.17, 0.63, 0.17)),
            BoundLook('platform_joint_max_angle', 'platform joint cone', (1.0, 0.5, 0.05))),
    pose_evaluator=_evaluator,
    narrowed=_narrowed,
)
