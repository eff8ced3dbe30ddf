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
The vestibular system as linear filters: what a person perceives of a specific force and a rate.

The one place of the perception model, for the evaluator and the model-predictive cueing alike.

**Otoliths** (Young and Meiry 1968, with the parameters Telban and Cardullo 2005 use), per axis
of the specific force at the head, head frame::

    f_hat / f = K (tau_a s + 1) / ((tau_L s + 1) (tau_S s + 1))

with ``K = 0.4``, ``tau_a = 13.2 s``, ``tau_L = 5.33 s``, ``tau_S = 0.66 s``. The gain peaks at
0.89 near 0.5 rad/s (0.8 or more from 0.25 to 1 rad/s) and is 0.4 for a sustained force: the
otoliths cannot tell a sustained force from a tilt, which is what tilt coordination uses.

**Semicircular canals** (Telban and Cardullo 2005), per axis of the angular velocity::

    w_hat / w = tau_a tau_L s^2 / ((tau_a s + 1) (tau_L s + 1) (tau_S s + 1))

with ``tau_L = 6.1, 5.3, 10.2 s`` (roll, pitch, yaw), ``tau_S = 0.1 s`` and the adaptation
``tau_a = 30 s``: a gain of 0.93 to 0.99 between 0.5 and 3 rad/s, nothing of a sustained
rate.

**Thresholds** of perception (the same source): 0.17 m/s^2 along x and y, 0.28 m/s^2 along z;
3.0, 3.6 and 2.6 deg/s about roll, pitch and yaw. They are compared with the models' outputs,
whose gain is near 1 in the band where cues live.

The models act on the motion *relative to rest*: the specific force less ``[0, 0, g]`` and the
angular velocity. :func:`vestibular_bank` stacks the six filters into one
:class:`~.filters.FilterBank` (inputs and outputs ``[f_x, f_y, f_z, w_x, w_y, w_z]``), whose
continuous ``(a, b, c, d)`` and exact discretisation a predictive controller uses as they are;
:func:`perceive` runs it along a sampled motion. Nothing here imports ROS.
"""

from dataclasses import dataclass, field
import math
from typing import Tuple

import numpy as np

from stewart_kinematics.cueing.filters import FilterBank
from stewart_kinematics.cueing.settings import STANDARD_GRAVITY


@dataclass(frozen=True)
class OtolithModel:
    """
    Young and Meiry's otolith model, one per axis of the specific force.

    :param gain: ``K``, the gain of a sustained force, dimensionless.
    :param lead_time_constant: ``tau_a``, seconds.
    :param long_time_constant: ``tau_L``, seconds.
    :param short_time_constant: ``tau_S``, seconds.
    :param thresholds: perception thresholds along x, y, z, m/s^2.
    """

    gain: float = 0.4
    lead_time_constant: float = 13.2
    long_time_constant: float = 5.33
    short_time_constant: float = 0.66
    thresholds: Tuple[float, float, float] = (0.17, 0.17, 0.28)

    def transfer_function(self):
        """Return ``(numerator, denominator)``, the denominator monic (s-polynomials)."""
        scale = self.gain / (self.long_time_constant * self.short_time_constant)
        numerator = np.array([scale * self.lead_time_constant, scale])
        denominator = np.polymul([1.0, 1.0 / self.long_time_constant],
                                 [1.0, 1.0 / self.short_time_constant])
        return numerator, denominator


@dataclass(frozen=True)
class CanalModel:
    """
    The semicircular canals' model, one per axis of the angular velocity.

    :param long_time_constants: ``tau_L`` about roll, pitch, yaw, seconds.
    :param short_time_constant: ``tau_S``, seconds.
    :param adaptation_time_constant: ``tau_a``, seconds.
    :param thresholds: perception thresholds about roll, pitch, yaw, rad/s.
    """

    long_time_constants: Tuple[float, float, float] = (6.1, 5.3, 10.2)
    short_time_constant: float = 0.1
    adaptation_time_constant: float = 30.0
    thresholds: Tuple[float, float, float] = field(
        default=tuple(math.radians(value) for value in (3.0, 3.6, 2.6)))

    def transfer_function(self, axis: int):
        """
        Return ``(numerator, denominator)`` about ``axis`` (0 roll, 1 pitch, 2 yaw), monic.

        ``tau_a tau_L s^2 / ((tau_a s + 1)(tau_L s + 1)(tau_S s + 1))`` divided through by
        ``tau_a tau_L tau_S``.
        """
        long_time_constant = self.long_time_constants[axis]
        numerator = np.array([1.0 / self.short_time_constant, 0.0, 0.0])
        denominator = np.polymul(np.polymul([1.0, 1.0 / self.adaptation_time_constant],
                                            [1.0, 1.0 / long_time_constant]),
                                 [1.0, 1.0 / self.short_time_constant])
        return numerator, denominator


#: The models as Telban and Cardullo (2005) give them.
OTOLITHS = OtolithModel()
CANALS = CanalModel()


def perception_thresholds(otoliths: OtolithModel = OTOLITHS,
                          canals: CanalModel = CANALS) -> np.ndarray:
    """Return the six thresholds ``[f_x, f_y, f_z]`` (m/s^2) and ``[w_x, w_y, w_z]`` (rad/s)."""
    return np.array([*otoliths.thresholds, *canals.thresholds], dtype=float)


def vestibular_bank(otoliths: OtolithModel = OTOLITHS, canals: CanalModel = CANALS
                    ) -> FilterBank:
    """
    Return the six perception filters as one bank, at rest.

    Inputs and outputs: ``[f_x, f_y, f_z]`` (specific force less ``[0, 0, g]``, m/s^2, head
    frame) then ``[w_x, w_y, w_z]`` (angular velocity, rad/s, head frame). Its ``a, b, c, d``
    are the continuous state-space model, 15 states: two per otolith, three per canal.
    """
    numerator, denominator = otoliths.transfer_function()
    blocks = [(numerator, denominator, axis, (0,)) for axis in range(3)]
    blocks += [(*canals.transfer_function(axis), 3 + axis, (0,)) for axis in range(3)]
    return FilterBank(6, blocks)


def perceive(times, specific_force, angular_velocity, gravity: float = STANDARD_GRAVITY,
             otoliths: OtolithModel = OTOLITHS, canals: CanalModel = CANALS):
    """
    Return what a person perceives along a sampled motion, starting from rest.

    :param times: seconds, shape (N,), increasing.
    :param specific_force: m/s^2, head frame, with gravity (``[0, 0, g]`` at rest), (N, 3).
    :param angular_velocity: rad/s, head frame, shape (N, 3).
    :returns: ``(perceived_force, perceived_rate)``, each shape (N, 3): the perceived specific
        force relative to rest (m/s^2) and the perceived angular velocity (rad/s). Each sample
        is held over the interval that ends with it, as in the washout's filters.
    :raises ValueError: for mismatched shapes or times that do not increase.
    """
    times = np.asarray(times, dtype=float)
    force = np.asarray(specific_force, dtype=float)
    rate = np.asarray(angular_velocity, dtype=float)
    if times.ndim != 1 or force.shape != (times.size, 3) or rate.shape != (times.size, 3):
        raise ValueError(f'times must be (N,) and both series (N, 3), got {times.shape}, '
                         f'{force.shape} and {rate.shape}')
    if not np.all(np.diff(times) > 0.0):
        raise ValueError('times must increase')
    if not (np.all(np.isfinite(force)) and np.all(np.isfinite(rate))):
        raise ValueError('the specific force and angular velocity must be finite')
    inputs = np.concatenate([force - [0.0, 0.0, gravity], rate], axis=1)
    steps = np.diff(times)
    bank = vestibular_bank(otoliths, canals)
    outputs = np.empty_like(inputs)
    if times.size:
        outputs[0] = bank.output(inputs[0])
    for index in range(1, times.size):
        outputs[index] = bank.step(inputs[index], float(steps[index - 1]))
    return outputs[:, :3], outputs[:, 3:]
