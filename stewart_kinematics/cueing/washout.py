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
The classical washout: Reid and Nahon's three channels, stepped at the input's own times.

Input: the specific force ``f`` (what an accelerometer reads, m/s^2: ``[0, 0, g]`` at rest) and
the angular velocity ``w`` (rad/s), both in the vehicle frame (x forward, y left, z up) at the
driver's head. Output: the cue, the head's displacement ``d`` (metres) and the platform's
rotation angles (roll, pitch, yaw, radians) from neutral. The channels (Reid and Nahon 1985,
*Flight simulation motion-base drive algorithms: part 1*, UTIAS Report 296):

- translational: ``a = k_t (L_IS f - [0, 0, g])`` high-passed and integrated twice,
  ``d = HP(s) a / s^2``. ``L_IS`` is the rotation of the simulator's attitude, the cue's own
  angles (tilt plus rotation) at the previous sample (Reid and Nahon's ``a = L_IS f + g``):
  the vehicle's force is taken in the simulator's frame, so a force along the tilted seat's z
  (an aircraft's coordinated turn, rolled by the rotational channel) asks for the sideways
  acceleration that cancels the gravity the roll shows the driver, rather than for nothing.
  With ``attitude_aware_specific_force`` false, ``L_IS`` is the identity (the force as it
  comes); at zero attitude the two are the same. With the default third-order high-pass
  ``HP = s^2 / (s^2 + 2 zeta omega s + omega^2) * s / (s + omega_b)`` the position filter is
  ``G(s) = s / ((s^2 + 2 zeta omega s + omega^2)(s + omega_b))``: no pole at the origin, so
  the displacement after a sustained acceleration returns to neutral. It never reverses
  through neutral after a step: for ``zeta >= 1`` the impulse response of
  ``1 / (s^2 + 2 zeta omega s + omega^2)`` is non-negative, that of ``1 / (s + omega_b)`` is
  positive, and the step response ``a g(t)`` of ``G`` is ``a`` times their convolution, of one
  sign throughout (tests check it, and that it is single-peaked).
- tilt coordination: ``k_tilt f`` low-passed (x and y), turned into the tilt that makes gravity
  play it, ``roll = asin(f_y / g)`` and ``pitch = -asin(f_x / g)`` (within ``tilt_max``), then
  followed no faster than ``tilt_rate_max`` and ``tilt_acceleration_max`` (a sustained
  acceleration ``a`` ends as the tilt ``asin(k_tilt a / g)``, reached at the rate limit).
- rotational: ``k_r w`` high-passed and integrated once to an angle (small angles: the angles
  are the integrated body rates); second order returns the angle to neutral after a sustained
  rate.

The cue's angles are the tilt plus the rotational channel's. Filters: :mod:`.filters` (exact
discretisation). Nothing here imports ROS.
"""

from dataclasses import dataclass
import math

import numpy as np

from stewart_kinematics.cueing.filters import (
    complement,
    FilterBank,
    high_pass,
    integrated,
    low_pass,
)
from stewart_kinematics.cueing.settings import CueingSettings
from stewart_kinematics.model.arrays import preview
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

#: Rows of the filter bank's outputs: the translational channel's position, velocity and
#: acceleration per axis, the tilt low-pass per axis, the rotational angle and rate per axis.
_TRANSLATION_ROWS = (slice(0, 9, 3), slice(1, 9, 3), slice(2, 9, 3))
_TILT_ROWS = slice(9, 11)
_ROTATION_ROWS = (slice(11, 17, 2), slice(12, 17, 2))


@dataclass(frozen=True)
class WashoutStep:
    """
    The washout's output for one sample.

    :param displacement: the head's displacement from neutral, base frame, metres, (3,).
    :param velocity: its rate, m/s, (3,).
    :param acceleration: the translational channel's high-passed acceleration, m/s^2, (3,).
    :param tilt: roll and pitch of tilt coordination, radians, (2,).
    :param tilt_rate: their rates, rad/s, (2,).
    :param tilt_target: the tilt the low-passed specific force asks for, radians, (2,).
    :param rotation: the rotational channel's roll, pitch and yaw, radians, (3,).
    :param angles: the cue's roll, pitch and yaw: tilt plus rotation, radians, (3,).
    """

    displacement: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    tilt: np.ndarray
    tilt_rate: np.ndarray
    tilt_target: np.ndarray
    rotation: np.ndarray
    angles: np.ndarray


def limit_rate(angle: float, rate: float, target: float, dt: float, rate_max: float,
               acceleration_max: float):
    """
    Follow ``target`` within a rate and an acceleration limit, without overshoot.

    One step of a discrete minimum-time follower (in the spirit of Zanasi, Guarino Lo Bianco and
    Tonielli 2000, *Nonlinear filters for the generation of smooth trajectories*, Automatica
    36(3)): the new rate lands on the target when the limits allow, else moves toward it no
    faster than ``rate_max`` and no faster than it can still brake within the distance left.

    :returns: ``(angle, rate)`` after ``dt`` seconds.
    """
    if dt <= 0.0:
        return angle, rate
    error = target - angle
    distance = abs(error)
    # The largest rate from which one step and then braking at acceleration_max stop within
    # the distance: v dt + v^2 / (2 a) <= distance.
    braking = acceleration_max * (-dt + math.sqrt(dt * dt + 2.0 * distance / acceleration_max))
    wanted = math.copysign(min(rate_max, distance / dt, braking), error)
    change = acceleration_max * dt
    new_rate = min(max(wanted, rate - change), rate + change)
    new_rate = min(max(new_rate, -rate_max), rate_max)
    return angle + new_rate * dt, new_rate


class ClassicalWashout:
    """
    The three channels of the classical washout as one stateful object.

    :param settings: a :class:`~stewart_kinematics.cueing.CueingSettings`.

    The first sample after construction or :meth:`reset` settles the filters at that sample's
    steady state (no onset cue for a sustained input that was already there) with the tilt at
    neutral, from where it follows its target at the rate limit.
    """

    def __init__(self, settings: CueingSettings = CueingSettings()):
        self.settings = s = settings
        blocks = []
        for axis in range(3):
            numerator, denominator = integrated(high_pass(
                s.translation_order, s.translation_frequency[axis], s.translation_damping[axis],
                s.translation_break_frequency[axis]), 2)
            blocks.append((s.translation_scale[axis] * numerator, denominator, 6 + axis,
                           (0, 1, 2)))
        for axis in range(2):
            if s.tilt_complementary:
                numerator, denominator = complement(high_pass(
                    s.translation_order, s.translation_frequency[axis],
                    s.translation_damping[axis], s.translation_break_frequency[axis]))
            else:
                numerator, denominator = low_pass(s.tilt_order, s.tilt_frequency, s.tilt_damping)
            blocks.append((s.tilt_scale[axis] * numerator, denominator, axis, (0,)))
        for axis in range(3):
            numerator, denominator = integrated(high_pass(
                s.rotation_order, s.rotation_frequency[axis], s.rotation_damping[axis]), 1)
            blocks.append((s.rotation_scale[axis] * numerator, denominator, 3 + axis, (0, 1)))
        self.filters = FilterBank(9, blocks)
        self._input_limit = s.translation_input_limit
        self._sin_tilt_max = math.sin(s.tilt_max)
        self._attitude_aware = bool(s.attitude_aware_specific_force)
        self.reset()

    def reset(self) -> None:
        """Forget the input's history: the next sample settles the filters, tilt at neutral."""
        self._settled = False
        self._tilt = [0.0, 0.0]
        self._tilt_rate = [0.0, 0.0]
        #: The cue's roll, pitch and yaw at the last sample (the simulator's attitude), rad.
        self.attitude = np.zeros(3)

    def simulator_force(self, specific_force) -> np.ndarray:
        """
        Return ``L_IS f``: the specific force turned into the simulator's frame, m/s^2, (3,).

        ``L_IS`` is the rotation of :attr:`attitude` (``Rz Ry Rx``, the package's convention);
        ``f`` unchanged when ``attitude_aware_specific_force`` is false.

        :param specific_force: ``f``, m/s^2, vehicle frame, shape (3,), finite.
        """
        force = np.asarray(specific_force, dtype=float)
        if not self._attitude_aware:
            return force
        return euler_zyx_to_matrix(self.attitude) @ force

    @staticmethod
    def filter_input(specific_force, angular_velocity, gravity: float) -> np.ndarray:
        """
        Return the filters' input ``[f - [0, 0, g], w, f - [0, 0, g]]``, shape (9,).

        The last three are the translational channel's, soft-limited by :meth:`step`.
        """
        u = np.empty(9)
        u[:3] = specific_force
        u[2] -= gravity
        u[3:6] = angular_velocity
        return u

    def step(self, specific_force, angular_velocity, dt: float) -> WashoutStep:
        """
        Advance the washout by one sample.

        :param specific_force: ``f``, m/s^2, vehicle frame, shape (3,).
        :param angular_velocity: ``w``, rad/s, vehicle frame, shape (3,).
        :param dt: seconds since the previous sample, finite and >= 0.
        :raises ValueError: naming the argument, if an input is malformed or not finite.
        """
        specific_force = _vector('specific_force', specific_force)
        angular_velocity = _vector('angular_velocity', angular_velocity)
        if not (math.isfinite(dt) and dt >= 0.0):
            raise ValueError(f'dt must be finite and >= 0 seconds, got {dt!r}')
        return self.step_checked(specific_force, angular_velocity, dt)

    def step_checked(self, specific_force, angular_velocity, dt: float) -> WashoutStep:
        """:meth:`step` for inputs already checked (3 finite floats each, ``dt >= 0``)."""
        s = self.settings
        u = self.filter_input(specific_force, angular_velocity, s.gravity)
        translational = u[:3]
        if self._attitude_aware and np.any(self.attitude):
            translational = self.simulator_force(specific_force)
            translational[2] -= s.gravity
        if self._input_limit != math.inf:
            u[6:] = self._input_limit * np.tanh(translational / self._input_limit)
        else:
            u[6:] = translational
        if self._settled:
            y = self.filters.step(u, dt)
        else:
            y = self.filters.settle(u)
            self._settled = True
        tilt_force = y[_TILT_ROWS].tolist()
        # Gravity plays the low-passed force: f_y = g sin(roll), f_x = -g sin(pitch).
        sines = [min(max(force / s.gravity, -self._sin_tilt_max), self._sin_tilt_max)
                 for force in tilt_force]
        target = [math.asin(sines[1]), -math.asin(sines[0])]
        for axis in range(2):
            self._tilt[axis], self._tilt_rate[axis] = limit_rate(
                self._tilt[axis], self._tilt_rate[axis], target[axis], dt, s.tilt_rate_max,
                s.tilt_acceleration_max)
        rotation = y[_ROTATION_ROWS[0]]
        tilt = np.array(self._tilt)
        angles = rotation.copy()
        angles[:2] += tilt
        self.attitude = angles.copy()
        return WashoutStep(
            displacement=y[_TRANSLATION_ROWS[0]], velocity=y[_TRANSLATION_ROWS[1]],
            acceleration=y[_TRANSLATION_ROWS[2]], tilt=tilt, tilt_rate=np.array(self._tilt_rate),
            tilt_target=np.array(target), rotation=rotation, angles=angles)


def _vector(name, value) -> np.ndarray:
    """Return ``value`` as 3 finite floats, or raise ValueError naming ``name``."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f'{name} must be 3 numbers, got {preview(value)}') from None
    if array.shape != (3,):
        raise ValueError(f'{name} must have shape (3,), got {array.shape}')
    if not np.all(np.isfinite(array)):
        raise ValueError(f'{name} must be finite, got {array.tolist()}')
    return array
