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
The masses of the platform, its payload and the legs, and gravity: what the dynamics read.

Kilograms, metres, kg m^2. :class:`RigidBody` is the platform or the payload (centre of mass
and inertia tensor in the platform frame); :class:`LegBody` is one of the two bodies of every
leg (a point on the leg axis, a transverse moment of inertia; no inertia about the axis);
:class:`MassProperties` gathers them with gravity. All masses default to 0: with every mass 0
the leg forces are 0. Each value is checked when the object is built, and a bad one is refused
with a ``ValueError`` naming the field and what is allowed.
"""

from dataclasses import dataclass, field
from functools import cached_property
import math
from typing import Tuple

import numpy as np

from stewart_kinematics.model.arrays import preview
from stewart_kinematics.model.inputs import is_real
from stewart_kinematics.model.validators import (
    Finite,
    first_reason,
    InertiaTensor,
    InRange,
)

#: Standard gravity (m/s^2), pointing down the base frame's z axis by default.
STANDARD_GRAVITY = 9.80665

_NON_NEGATIVE = (Finite(), InRange(0.0, math.inf))
_FINITE = (Finite(),)


def _number(subject, value, rules) -> float:
    """Return ``value`` as a float if it is a real number that keeps ``rules``, else refuse."""
    if not is_real(value):
        raise ValueError(f'{subject} must be a number, got {preview(value)} '
                         f'({type(value).__name__})')
    value = float(value)
    reason = first_reason(rules, subject, value)
    if reason:
        raise ValueError(reason)
    return value


def _numbers(subject, values, length) -> Tuple[float, ...]:
    """Return ``values`` as a tuple of ``length`` finite floats, else refuse naming them."""
    if isinstance(values, np.ndarray) and values.ndim == 1:
        values = values.tolist()
    if not isinstance(values, (list, tuple)) or len(values) != length or not all(
            is_real(value) for value in values):
        raise ValueError(f'{subject} must be a list of {length} numbers, got {preview(values)} '
                         f'({type(values).__name__})')
    values = tuple(float(value) for value in values)
    reason = Finite().reason(subject, list(values))
    if reason:
        raise ValueError(reason)
    return values


def inertia_matrix(inertia) -> np.ndarray:
    """
    Inertia tensor of its six entries ``[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]``, as URDF writes them.

    :returns: the symmetric 3x3 tensor, kg m^2.
    """
    ixx, iyy, izz, ixy, ixz, iyz = inertia
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


def _check_inertia(subject, inertia):
    """Refuse a tensor that is not positive semi-definite or breaks the triangle inequality."""
    reason = InertiaTensor().reason(subject, list(inertia))
    if reason:
        raise ValueError(reason)


def _check_massless(subject, mass, inertia):
    """Refuse an inertia on a body without mass: with every mass 0, the forces are 0."""
    if mass == 0.0 and any(inertia):
        raise ValueError(f'{subject}: a body of mass 0 has no inertia; set the inertia to 0 '
                         f'or give the mass, got inertia {preview(inertia)}')


@dataclass(frozen=True)
class RigidBody:
    """
    A rigid body fixed to the platform: the platform itself, or its payload.

    :param mass: kg, >= 0.
    :param center_of_mass: ``[x, y, z]`` of its centre of mass in the platform frame, metres.
    :param inertia: its inertia tensor about the centre of mass, axes of the platform frame,
        ``[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]`` in kg m^2: the tensor's entries, as URDF's
        ``<inertia>`` element writes them (the products of inertia are the off-diagonal
        entries, ``-integral(x y dm)``). Positive semi-definite, with principal moments that
        keep the triangle inequality; all 0 when the mass is 0.
    :param name: what messages call it (``'payload'``).
    :raises ValueError: naming the field and what is allowed.
    """

    mass: float = 0.0
    center_of_mass: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    inertia: Tuple[float, float, float, float, float, float] = (0.0,) * 6
    name: str = field(default='RigidBody', compare=False)

    def __post_init__(self):
        object.__setattr__(self, 'mass', _number(f'{self.name}.mass (kg)', self.mass,
                                                 _NON_NEGATIVE))
        object.__setattr__(self, 'center_of_mass', _numbers(
            f'{self.name}.center_of_mass (m)', self.center_of_mass, 3))
        inertia = _numbers(f'{self.name}.inertia (kg m^2)', self.inertia, 6)
        _check_inertia(f'{self.name}.inertia (kg m^2)', inertia)
        _check_massless(self.name, self.mass, inertia)
        object.__setattr__(self, 'inertia', inertia)


@dataclass(frozen=True)
class LegBody:
    """
    One body of a leg: the lower one (a cylinder) or the upper one (a rod).

    The lower body hangs on the base joint, the upper one on the platform joint. Its centre of
    mass is on the leg axis; it turns with the leg, whose spin about its own axis is neglected,
    and has no inertia about that axis.

    :param mass: kg, >= 0.
    :param center_of_mass: distance of the centre of mass from the body's own joint along the
        leg axis, metres: from the base joint towards the platform for the lower body, from the
        platform joint towards the base for the upper body (negative: beyond the joint).
    :param inertia: moment of inertia about a transverse axis through the centre of mass,
        kg m^2, >= 0; 0 when the mass is 0.
    :param name: what messages call it (``'leg_lower'``).
    :raises ValueError: naming the field and what is allowed.
    """

    mass: float = 0.0
    center_of_mass: float = 0.0
    inertia: float = 0.0
    name: str = field(default='LegBody', compare=False)

    def __post_init__(self):
        object.__setattr__(self, 'mass', _number(f'{self.name}.mass (kg)', self.mass,
                                                 _NON_NEGATIVE))
        object.__setattr__(self, 'center_of_mass', _number(
            f'{self.name}.center_of_mass (m)', self.center_of_mass, _FINITE))
        inertia = _number(f'{self.name}.inertia (kg m^2)', self.inertia, _NON_NEGATIVE)
        _check_massless(self.name, self.mass, [inertia])
        object.__setattr__(self, 'inertia', inertia)


@dataclass(frozen=True)
class MassProperties:
    """
    The masses the actuators carry, and gravity.

    >>> payload = RigidBody(20.0, [0.0, 0.0, 0.1], name='payload')
    >>> MassProperties(payload=payload).moving_mass
    20.0

    :param platform: the platform, a :class:`RigidBody` (platform frame).
    :param payload: the payload, a :class:`RigidBody` (platform frame).
    :param leg_lower: the lower body of each of the six legs, a :class:`LegBody` on the base
        joint.
    :param leg_upper: the upper body of each leg, a :class:`LegBody` on the platform joint.
    :param gravity: ``[x, y, z]`` in the base frame, m/s^2; default ``[0, 0, -9.80665]``.
    :raises ValueError: naming the field and what is allowed.
    """

    platform: RigidBody = RigidBody(name='platform')
    payload: RigidBody = RigidBody(name='payload')
    leg_lower: LegBody = LegBody(name='leg_lower')
    leg_upper: LegBody = LegBody(name='leg_upper')
    gravity: Tuple[float, float, float] = (0.0, 0.0, -STANDARD_GRAVITY)

    def __post_init__(self):
        for name, kind in (('platform', RigidBody), ('payload', RigidBody),
                           ('leg_lower', LegBody), ('leg_upper', LegBody)):
            if not isinstance(getattr(self, name), kind):
                raise ValueError(f'MassProperties.{name} must be a {kind.__name__}, got '
                                 f'{preview(getattr(self, name))}')
        object.__setattr__(self, 'gravity', _numbers('gravity (m/s^2)', self.gravity, 3))

    @property
    def moving_mass(self) -> float:
        """Mass of the platform and its payload, kg (the legs' own not included)."""
        return self.platform.mass + self.payload.mass

    @property
    def legs_massless(self) -> bool:
        """Whether both bodies of the legs have no mass (and so no inertia)."""
        return self.leg_lower.mass == 0.0 and self.leg_upper.mass == 0.0

    @property
    def massless(self) -> bool:
        """Whether every body has no mass: the leg forces are then 0."""
        return self.legs_massless and self.moving_mass == 0.0

    @cached_property
    def moving_body(self):
        """
        Platform and payload as one rigid body: ``(mass, centre of mass, inertia tensor)``.

        Mass in kg; centre of mass ``(x, y, z)`` in the platform frame, metres (the origin when
        the mass is 0); the inertia tensor about that centre, platform frame, as nine floats
        by rows, kg m^2 (the parallel axis theorem on each body).
        """
        bodies = (self.platform, self.payload)
        mass = sum(body.mass for body in bodies)
        if mass == 0.0:
            return 0.0, (0.0, 0.0, 0.0), (0.0,) * 9
        center = sum(body.mass * np.array(body.center_of_mass) for body in bodies) / mass
        tensor = np.zeros((3, 3))
        for body in bodies:
            offset = np.array(body.center_of_mass) - center
            tensor += inertia_matrix(body.inertia) + body.mass * (
                offset @ offset * np.eye(3) - np.outer(offset, offset))
        return mass, tuple(center.tolist()), tuple(tensor.ravel().tolist())
