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
The platform's geometry: joint positions and home pose, given its limits' settings.

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

Limits: the geometry holds geometry. Its limits are a settings object of their own, a
:class:`stewart_kinematics.limits.PoseLimits`, given as ``limits`` and kept as a reference so
that every object handed a geometry finds them; the values, their bounds and the home-pose check
are the limits'. This module imports nothing outside model/.
"""

import dataclasses
from dataclasses import dataclass, field
import math
from typing import Any, NamedTuple, Tuple

import numpy as np

from stewart_kinematics.model.arrays import as_float_array

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


@dataclass(frozen=True, eq=False)
class Geometry:
    """
    A Gough-Stewart platform (6-6, 6-3, 3-3 or between), validated on construction.

    :param base_joints: b_1..b_6 in the base frame, metres, shape (6, 3).
    :param platform_joints: p_1..p_6 in the platform frame, metres, shape (6, 3).
    :param home_pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) of the neutral pose.
    :param limits: where the platform may be, a :class:`stewart_kinematics.limits.PoseLimits`
        (stroke, joint cones, singularity margin, leg radius: each checked there with the
        bounds of its parameter); ``None`` (the default) for no pose limit. The geometry asks
        it whether its home pose is allowed (``limits.check_home(geometry)``).
    :param mass_properties: the masses it carries and gravity, a
        :class:`stewart_kinematics.MassProperties` (kept as a reference, as ``limits``; the
        leg forces and the ``leg_force`` limit read it); ``None`` (the default): every mass 0.
    :raises ValueError: if an array has the wrong shape or a non-finite value, three or more
        joints of the base or of the platform coincide (a joint is shared by two legs at
        most), two legs share both their joints, the joints of the base or of the platform
        are collinear, or the home pose breaks a limit (two legs that collide there included,
        named).

    Derived on construction: :attr:`home_leg_lengths`, :attr:`home_leg_directions`,
    :attr:`platform_radius`, :attr:`shared_joints` and :attr:`design`.

    The limits' values read as the geometry's attributes too (``geometry.leg_length_max`` is
    ``geometry.limits.leg_length_max``), and :meth:`with_limits` changes some: a thin path
    kept for callers written when the values lived here.

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
    limits: Any = None
    mass_properties: Any = None

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
        # Derived once: every IK request and limit check uses them.
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
        if self.limits is not None:
            if not callable(getattr(self.limits, 'check_home', None)):
                raise ValueError('limits must be a stewart_kinematics.PoseLimits or None, got '
                                 f'a {type(self.limits).__name__}')
            self.limits.check_home(self)

    def __getattr__(self, name):
        """Read a limit's value from :attr:`limits` (``geometry.leg_length_max``)."""
        limits = self.__dict__.get('limits') if not name.startswith('_') else None
        if limits is None:
            raise AttributeError(f'{type(self).__name__!r} object has no attribute {name!r}')
        return getattr(limits, name)

    def with_limits(self, **changes) -> 'Geometry':
        """
        Return this geometry with some of its limits changed (SI units, as :attr:`limits`).

        :raises ValueError: if it has no limits, or as the limits and the geometry do.
        """
        if self.limits is None:
            raise ValueError('this geometry has no limits to change; give it '
                             'limits=PoseLimits(...)')
        return dataclasses.replace(self, limits=self.limits.replace(**changes))

    def with_mass_properties(self, mass_properties) -> 'Geometry':
        """
        Return this geometry carrying other masses (a new payload, say), its limits the same.

        :param mass_properties: a :class:`stewart_kinematics.MassProperties`, or ``None``.
        :raises ValueError: if its home pose breaks a limit with them (the leg forces).
        """
        return dataclasses.replace(self, mass_properties=mass_properties)


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
