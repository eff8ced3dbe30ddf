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
How fast the legs may change: leg velocity, acceleration and jerk, each at most a bound.

Checked on leg samples (:class:`~stewart_kinematics.limits.base.LegSamples`): the leg
velocities and accelerations of a moving platform
(:func:`stewart_kinematics.model.velocities.leg_states`), the leg velocities of a twist
(:func:`stewart_kinematics.model.velocities.leg_velocities`), or the steps of a command stream.
The limits are those of :class:`stewart_kinematics.ActuatorLimits`. Nothing here imports ROS.
"""

import math

import numpy as np

from stewart_kinematics.limits.base import Bound, LEG, Limit
from stewart_kinematics.limits.kind import ACTUATOR, LimitKind, LimitParameter
from stewart_kinematics.model.actuators import RATE_MAX_RULES

#: Relative slack on a rate limit for sampled motion, for rounding only: a motion timed to meet
#: a limit exactly (a retimed trajectory, a jerk-limited stream) reaches it to within a few units
#: in the last place of its samples.
RATE_SLACK = 1e-9


class LegRate(Limit):
    """
    Evaluator of one rate limit, per leg: ``|x_i| <= allowed`` for one derivative x.

    :param name: ``leg_velocity_max``, ``leg_acceleration_max`` or ``leg_jerk_max``.
    :param allowed: the limit, SI units; ``inf`` is not set.
    :param quantity: the field of the samples it reads: ``velocities``, ``accelerations`` or
        ``jerks``.
    :param unit: ``m/s``, ``m/s^2`` or ``m/s^3``.
    :param slack: relative slack on ``allowed``, for the rounding of sampled motion
        (:data:`RATE_SLACK`); 0 for a strict limit.
    """

    def __init__(self, name: str, allowed: float, quantity: str, unit: str, slack: float = 0.0):
        self.quantity = quantity
        self.bounds = ((Bound(name, allowed, True, LEG, unit, slack=slack),)
                       if allowed < math.inf else ())

    @classmethod
    def all_of(cls, actuator_limits, slack: float = 0.0):
        """Return the velocity, acceleration and jerk evaluators of :class:`ActuatorLimits`."""
        return tuple(cls(name, getattr(actuator_limits, setting), quantity, unit, slack)
                     for name, quantity, setting, unit, _ in RATES)

    def values(self, arrays):
        """Return ``|x|`` of the samples' quantity, (6, n)."""
        return (np.abs(getattr(arrays, self.quantity)),)

    def allows(self, sample: dict) -> bool:
        """Whether six values (floats, ``sample[quantity]``) keep the limit: ``|x| <= allowed``."""
        (bound,) = self.bounds
        return all(bound.holds(abs(value)) for value in sample[self.quantity])

    def scale(self, values) -> float:
        """
        Return the largest factor in (0, 1] that brings every one of ``values`` within the limit.

        Exactly: ``|value| * factor <= allowed`` for every value, without the slack.

        :param values: the quantity, any shape, finite.
        :returns: 1.0 when every value is within the limit already.
        """
        (bound,) = self.bounds
        peak = float(np.max(np.abs(values))) if np.size(values) else 0.0
        if peak <= bound.allowed:
            return 1.0
        factor = bound.allowed / peak
        # Rounding can leave peak * factor a unit in the last place above the limit.
        while peak * factor > bound.allowed:
            factor = math.nextafter(factor, 0.0)
        return factor


#: Each rate: (its name, the field of the samples, the setting of ActuatorLimits, unit, words).
RATES = (('leg_velocity_max', 'velocities', 'velocity_max', 'm/s',
          'Largest speed of a leg (actuator), metres per second: timed trajectories are refused '
          'or retimed to keep within it, streamed commands are limited to it; .inf for no '
          'limit'),
         ('leg_acceleration_max', 'accelerations', 'acceleration_max', 'm/s^2',
          'Largest acceleration of a leg, metres per second squared, as leg_velocity_max; '
          '.inf for no limit'),
         ('leg_jerk_max', 'jerks', 'jerk_max', 'm/s^3',
          'Largest jerk of a leg, metres per second cubed, for streamed commands '
          '(command_rate); .inf for no limit'))


#: The leg rates: their parameters (kept by ActuatorLimits) and leg-state evaluators.
KIND = LimitKind(
    name='leg_rates',
    title='Leg velocity, acceleration, jerk',
    meaning=('Of every sample of a trajectory (checked whole, or retimed to keep them: '
             'velocity and acceleration), of every streamed command (the jerk: a change of '
             "acceleration over a command period), and (velocity) of a twist's leg "
             'velocities. Trajectories retimed by toppra have piecewise constant accelerations '
             'and are not checked for jerk.'),
    evaluator='LegRate',
    parameters=tuple(LimitParameter(name, unit, math.inf, words, RATE_MAX_RULES,
                                    setting=setting, keeps=ACTUATOR)
                     for name, _, setting, unit, words in RATES),
    leg_state_names=tuple(name for name, *_ in RATES),
    leg_state_evaluators=lambda limits, actuator_limits, slack: LegRate.all_of(
        actuator_limits, slack),
)
