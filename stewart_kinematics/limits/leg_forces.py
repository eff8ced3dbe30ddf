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
The leg forces: each actuator's static axial force within ``[leg_force_min, leg_force_max]``.

A pose is judged with its static forces: what the actuators must push (positive) or pull
(negative) to hold the platform, its payload and the legs still against gravity
(:func:`stewart_kinematics.dynamics.inverse_dynamics.static_forces_of_legs`, the terms of
:func:`stewart_kinematics.leg_forces` at rest), from the masses the geometry carries
(:attr:`stewart_kinematics.Geometry.mass_properties`). With every mass 0 the forces are 0 and
the limit is not checked. A singular pose has no forces that balance the load: every leg
breaks the limit there. Nothing here imports ROS.
"""

import math

from stewart_kinematics.dynamics.inverse_dynamics import (
    masses_of,
    single_static_forces_of_legs,
    static_forces_of_legs,
)
from stewart_kinematics.limits.base import Bound, LEG, Limit, row_violations
from stewart_kinematics.limits.kind import BoundLook, LimitKind, LimitParameter
from stewart_kinematics.model.validators import InRange


class LegForces(Limit):
    """
    Evaluator of ``leg_force_min <= f_i <= leg_force_max``, newtons, per leg, at rest.

    :param geometry: a :class:`stewart_kinematics.Geometry`; its masses
        (:attr:`~stewart_kinematics.Geometry.mass_properties`) load the legs.
    :param force_min: the largest pull (negative) or the smallest push, N; ``-inf`` is not set.
    :param force_max: the largest push, N; ``inf`` is not set.
    """

    def __init__(self, geometry, force_min: float = -math.inf, force_max: float = math.inf):
        self._masses = masses_of(geometry)
        checked = not self._masses.massless
        self.bounds = tuple(
            Bound(name, allowed, upper, LEG, 'N')
            for name, allowed, upper in (('leg_force_min', force_min, False),
                                         ('leg_force_max', force_max, True))
            if checked and math.isfinite(allowed))

    def values(self, arrays):
        """Return the static leg forces, (6, n) newtons, once per bound."""
        forces = static_forces_of_legs(arrays.lengths, arrays.vectors, arrays.rotation,
                                       self._masses)
        return (forces,) * len(self.bounds)

    def violations_of_one(self, legs):
        """See :meth:`Limit.violations_of_one`: the same forces, in floats."""
        if legs.floats is None:
            return super().violations_of_one(legs)
        forces = single_static_forces_of_legs(legs.floats, legs.float_rotation, self._masses)
        return [violation for bound in self.bounds
                for violation in row_violations(bound, forces)]


def _evaluator(geometry, limits) -> LegForces:
    return LegForces(geometry, limits.leg_force_min, limits.leg_force_max)


#: The leg forces: their parameters, bounds and evaluator.
KIND = LimitKind(
    name='leg_force',
    title='Leg forces',
    meaning=("Each actuator's static axial force (N, positive pushing the platform away from "
             'the base) that holds the platform, its payload and the legs against gravity, '
             'from the mass parameters; not checked while every mass is 0.'),
    evaluator='LegForces',
    parameters=(
        LimitParameter(
            'leg_force_min', 'N', -math.inf,
            'Largest pull of a leg, newtons, as a negative force (0: the legs may only push); '
            '-.inf for no limit',
            (InRange(-math.inf, 0.0),)),
        LimitParameter(
            'leg_force_max', 'N', math.inf,
            'Largest push of a leg, newtons; .inf for no limit',
            (InRange(0.0, math.inf, low_inclusive=False),))),
    bounds=(BoundLook('leg_force_min', 'leg_force_min (forces)', (0.9, 0.6, 0.0)),
            BoundLook('leg_force_max', 'leg_force_max (forces)', (0.5, 0.5, 0.5))),
    pose_evaluator=_evaluator,
)
