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
The platform's geometry: joint positions, home pose, and where the platform may be (limits).

Frames: the base frame is fixed, with its origin on the base and z up; the platform frame moves
with the platform. A pose ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) places the platform
frame at ``(X, Y, Z)`` in the base frame, rotated by ``R = Rz(gamma) Ry(beta) Rx(alpha)``.
Leg ``i`` runs from base joint ``b_i`` (base frame) to platform joint ``p_i`` (platform frame).

Shared joints: two legs may end on one joint (a spherical joint with two sockets), at the base,
at the platform or both, which gives the classic 6-3 and 3-3 designs besides the general 6-6.
Joints count as one when they are no farther apart than :data:`SHARED_JOINT_TOLERANCE` times
the size of their set (:func:`joint_set_scale`): the rounding of one point written twice.
Joints any farther apart are two joints, however close (a 6-6 platform that is nearly 6-3 is a
valid 6-6 platform). A joint shared by three or more legs, and two legs sharing both their
joints (one leg twice), are refused. :attr:`Geometry.shared_joints` says which legs share which
joint.
"""

from dataclasses import dataclass, field
import math
from typing import NamedTuple, Tuple

import numpy as np

from stewart_kinematics.model import limit_bounds
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.model.validators import first_reason

#: Two joints of the base (or of the platform) no farther apart than this fraction of the
#: size of their set (:func:`joint_set_scale`) are one joint, shared by two legs: 1e-9 of 0.2 m
#: is 0.2 nm, far below any drawing, far above the rounding of a coordinate written twice
#: (1e-16 relative).
SHARED_JOINT_TOLERANCE = 1e-9
#: A joint may be shared by this many legs at most (a spherical joint with two sockets).
MAX_LEGS_PER_JOINT = 2
#: Joints whose spread off their best-fit line is below this (metres) count as collinear.
MIN_JOINT_SPREAD = 1e-6
#: The sides a joint can be on, as :class:`SharedJoint` names them.
SIDES = ('base', 'platform')


class SharedJoint(NamedTuple):
    """
    One joint that two legs share.

    :param side: ``'base'`` (a base joint, base frame) or ``'platform'`` (platform frame).
    :param legs: the two legs that end on it, 1..6, the lower first.
    """

    side: str
    legs: Tuple[int, int]

    def __str__(self):
        return f'legs {self.legs[0]} and {self.legs[1]} share a {self.side} joint'


#: The rules of each limit: those of its parameter, angles converted to radians.
_LIMIT_RULES = {
    'leg_length_min': limit_bounds.LEG_LENGTH_MIN,
    'leg_length_max': limit_bounds.LEG_LENGTH_MAX,
    'base_joint_max_angle': tuple(rule.converted(math.radians)
                                  for rule in limit_bounds.JOINT_MAX_ANGLE_DEG),
    'platform_joint_max_angle': tuple(rule.converted(math.radians)
                                      for rule in limit_bounds.JOINT_MAX_ANGLE_DEG),
    'max_jacobian_condition': limit_bounds.MAX_JACOBIAN_CONDITION,
    'leg_radius': limit_bounds.LEG_RADIUS,
}


@dataclass(frozen=True, eq=False)
class Geometry:
    """
    A Gough-Stewart platform (6-6, 6-3, 3-3 or between), validated on construction.

    :param base_joints: b_1..b_6 in the base frame, metres, shape (6, 3).
    :param platform_joints: p_1..p_6 in the platform frame, metres, shape (6, 3).
    :param home_pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) of the neutral pose.
    :param leg_length_min: shortest allowed leg length, metres (0 for no limit).
    :param leg_length_max: longest allowed leg length, metres (``inf`` for no limit).
    :param base_joint_max_angle: largest angle between a leg and its home direction at the
        base joint, radians, in (0, pi] (pi for no limit).
    :param platform_joint_max_angle: the same at the platform joint, in the platform frame.
    :param max_jacobian_condition: largest allowed condition number of the dimensionless
        Jacobian (:func:`stewart_kinematics.model.jacobians.jacobian_condition`), >= 1
        (``inf`` for no limit): the singularity margin.
    :param leg_radius: radius of each leg, metres, in [0, 1] (0 for no collision check): a leg
        is a capsule of this radius around the segment from its base joint to its platform
        joint, and two legs collide where their segments come closer than ``2 * leg_radius``.
    :raises ValueError: if an array has the wrong shape or a non-finite value, three or more
        joints of the base or of the platform coincide (a joint is shared by two legs at
        most), two legs share both their joints, the joints of the base or of the platform
        are collinear, a limit is out of its range (the range of its parameter,
        :mod:`stewart_kinematics.model.limit_bounds`), or the home pose breaks a limit (two
        legs that collide there included, named).

    Derived on construction: :attr:`home_leg_lengths`, :attr:`home_leg_directions`,
    :attr:`platform_radius`, :attr:`shared_joints` and :attr:`design`.

    The limits are checked by :mod:`stewart_kinematics.limits`.

    >>> from stewart_kinematics import load_geometry
    >>> geometry = load_geometry('config/paper_platform.yaml')
    >>> geometry.home_leg_lengths.round(6)
    array([0.718855, 0.718855, 0.701146, 0.718855, 0.718855, 0.718855])
    >>> geometry.design, geometry.shared_joints
    ('6-6', ())
    >>> six_three = load_geometry('config/platform_6_3.yaml')
    >>> six_three.design
    '6-3'
    >>> [joint.legs for joint in six_three.shared_joints]
    [(1, 6), (2, 3), (4, 5)]
    >>> print(six_three.shared_joints[0])
    legs 1 and 6 share a platform joint
    """

    base_joints: np.ndarray
    platform_joints: np.ndarray
    home_pose: np.ndarray = field(default_factory=lambda: np.zeros(6))
    leg_length_min: float = 0.0
    leg_length_max: float = math.inf
    base_joint_max_angle: float = math.pi
    platform_joint_max_angle: float = math.pi
    max_jacobian_condition: float = math.inf
    leg_radius: float = 0.0

    def __post_init__(self):
        for name, shape in (('base_joints', (6, 3)), ('platform_joints', (6, 3)),
                            ('home_pose', (6,))):
            array = _checked_array(name, getattr(self, name), shape)
            array.flags.writeable = False
            object.__setattr__(self, name, array)
        shared = {side: _shared_pairs(f'{side}_joints', getattr(self, f'{side}_joints'))
                  for side in SIDES}
        both = sorted(set(shared['base']) & set(shared['platform']))
        if both:
            first, second = both[0]
            raise ValueError(
                f'legs {first} and {second} share both their base joint and their platform '
                'joint: they would be one leg twice (a singular platform); give one of them '
                'its own joint')
        for side in SIDES:
            _check_spread(f'{side}_joints', getattr(self, f'{side}_joints'))
        object.__setattr__(self, 'shared_joints', tuple(
            SharedJoint(side, pair) for side in SIDES for pair in shared[side]))
        object.__setattr__(self, 'design', '-'.join(
            str(6 - len(shared[side])) for side in SIDES))
        # The limits' rules are the parameters' (model/limit_bounds.py), angles in radians here.
        for name, rules in _LIMIT_RULES.items():
            object.__setattr__(self, name, _checked_limit(name, getattr(self, name), rules))
        if not self.leg_length_min < self.leg_length_max:
            raise ValueError(
                'leg length limits must satisfy leg_length_min < leg_length_max, got '
                f'leg_length_min={self.leg_length_min!r}, leg_length_max={self.leg_length_max!r}')

        # Derived once: every IK request and limit check uses them.
        from stewart_kinematics import limits
        from stewart_kinematics.model.inverse import leg_vectors_from_euler
        home_legs = leg_vectors_from_euler(self, self.home_pose)
        home_lengths = np.linalg.norm(home_legs, axis=-1)
        home_lengths.flags.writeable = False
        with np.errstate(invalid='ignore', divide='ignore'):  # NaN for a leg of zero length
            home_directions = home_legs / home_lengths[:, None]
        home_directions.flags.writeable = False
        object.__setattr__(self, 'home_leg_lengths', home_lengths)
        object.__setattr__(self, 'home_leg_directions', home_directions)
        object.__setattr__(self, 'platform_radius', joint_set_size(self.platform_joints))
        home_violations = limits.check_pose(
            self, self.home_pose[:3], euler_zyx_to_matrix(self.home_pose[3:]))
        if home_violations:
            raise ValueError('the home pose breaks the limits: '
                             + '; '.join(str(v) for v in home_violations))


def _checked_limit(name, value, rules) -> float:
    """Return a limit as a float, or refuse what is not one number its rules allow, naming it."""
    array = as_float_array(value, name)
    if array.shape != ():
        raise ValueError(f'{name} must be one number, got {preview(value)}')
    reason = first_reason(rules, name, float(array))
    if reason:
        raise ValueError(reason)
    return float(array)


def _checked_array(name, value, shape):
    array = np.array(as_float_array(value, name))
    if array.shape != shape:
        raise ValueError(f'{name} must have shape {shape}, got {array.shape}')
    if not np.all(np.isfinite(array)):
        raise ValueError(f'{name} must be finite, got {array.tolist()}')
    return array


def joint_separations(joints) -> np.ndarray:
    """
    Distances between the joints of a set, metres, (6, 6), ``inf`` on the diagonal.

    :param joints: six joints, (6, 3), metres; a distance beyond the float range is ``inf``.
    """
    with np.errstate(over='ignore'):
        separation = np.linalg.norm(joints[:, None, :] - joints[None, :, :], axis=-1)
    separation[np.diag_indices(len(joints))] = np.inf
    return separation


def joint_set_scale(joints) -> float:
    """
    Return the size of a set of joints, metres: the median distance from their median point.

    The scale of :data:`SHARED_JOINT_TOLERANCE`: like the RMS radius of the joints on a real
    platform (0.195 m for the 3-3 example's base, whose RMS radius is 0.225 m), but one or two
    misplaced joints (a coordinate typed in millimetres) do not change it.

    :param joints: (6, 3), metres.
    """
    with np.errstate(over='ignore', invalid='ignore'):
        distances = np.linalg.norm(joints - np.median(joints, axis=0), axis=-1)
    return float(np.median(distances))


def joint_set_size(joints) -> float:
    """Return the RMS distance of the joints from their centroid, metres: their scale."""
    centred = joints - joints.mean(axis=0)
    return float(np.sqrt(np.mean(np.sum(centred ** 2, axis=-1))))


def _shared_pairs(name, joints):
    """
    Find the pairs of legs (1-based, the lower first) whose joints in ``joints`` coincide.

    :raises ValueError: if three or more joints coincide (naming them).
    """
    separation = joint_separations(joints)
    same = separation <= SHARED_JOINT_TOLERANCE * joint_set_scale(joints)
    # Groups of coinciding joints (closed under "coincides with", so a chain a-b-c is a group).
    group = list(range(6))
    for i, j in zip(*np.nonzero(np.triu(same))):
        old, new = group[j], group[i]
        group = [new if g == old else g for g in group]
    members = {}
    for leg, g in enumerate(group):
        members.setdefault(g, []).append(leg + 1)
    pairs = []
    for legs in members.values():
        if len(legs) > MAX_LEGS_PER_JOINT:
            named = ', '.join(map(str, legs[:-1])) + f' and {legs[-1]}'
            raise ValueError(
                f'{name}: joints {named} coincide ({len(legs)} legs on one point); a joint may '
                f'be shared by {MAX_LEGS_PER_JOINT} legs at most')
        if len(legs) == 2:
            pairs.append(tuple(legs))
    return tuple(sorted(pairs))


def _check_spread(name, joints):
    # The second singular value of the centred joints is their spread off the best-fit line.
    spread = np.linalg.svd(joints - joints.mean(axis=0), compute_uv=False)[1] / math.sqrt(6)
    if spread < MIN_JOINT_SPREAD:
        raise ValueError(
            f'{name}: the six joints are collinear (spread {spread:.3g} m off their common '
            f'line, at least {MIN_JOINT_SPREAD:g} m needed); the platform would be singular')
