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
Streaming leg commands that actuators can follow: online jerk-limited motion toward a target.

For teleop and servoing, targets arrive irregularly and may jump. A :class:`CommandFilter`
keeps the state of the commanded legs (lengths, velocities, accelerations) and, called once per
control period, moves it toward the latest target within the legs' velocity, acceleration and
jerk limits, synchronised so that all six legs arrive together (in proportion, a straight line
in leg space, whenever the motion allows it), and comes to rest on the target when the target
stays still. The trajectory is recomputed from the current state at every step (online
trajectory generation: the ruckig library), so a new target may arrive at any time.

Units: metres, seconds. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math

import numpy as np

from stewart_kinematics.model.actuators import ActuatorLimits


@dataclass(frozen=True)
class FilteredCommand:
    """
    One step of a :class:`CommandFilter`.

    :param lengths: commanded leg lengths, metres, shape (6,).
    :param velocities: m/s, shape (6,).
    :param accelerations: m/s^2, shape (6,).
    :param settled: True when the command rests on the target.
    """

    lengths: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray
    settled: bool


class CommandFilter:
    """
    Leg commands that move toward the latest target within velocity, acceleration and jerk.

    :param actuator_limits: ``velocity_max`` and ``acceleration_max`` must be finite;
        ``jerk_max`` may be ``inf`` (acceleration-limited motion).
    :param period: seconds between two commands, positive.
    :param lengths: the legs' starting lengths, at rest, metres, shape (6,).
    :raises ValueError: if a limit that must be finite is not, or the period is not positive.

    >>> from stewart_kinematics import ActuatorLimits, CommandFilter, load_geometry
    >>> home_lengths = load_geometry('config/paper_platform.yaml').home_leg_lengths
    >>> command_filter = CommandFilter(ActuatorLimits(0.05, 0.25, 2.5), 0.01, home_lengths)
    >>> command_filter.set_target(home_lengths + 0.01)   # every leg 10 mm longer
    >>> command = command_filter.step()                  # every 10 ms
    >>> command.velocities, command.settled              # m/s, after 10 ms
    (array([0.000125, 0.000125, 0.000125, 0.000125, 0.000125, 0.000125]), False)
    """

    def __init__(self, actuator_limits: ActuatorLimits, period: float, lengths):
        import ruckig  # the field's online trajectory generator; only streaming needs it

        if not (math.isfinite(actuator_limits.velocity_max)
                and math.isfinite(actuator_limits.acceleration_max)):
            raise ValueError('streamed commands need finite leg_velocity_max and '
                             'leg_acceleration_max (leg_jerk_max may be .inf), got '
                             f'{actuator_limits.velocity_max!r} and '
                             f'{actuator_limits.acceleration_max!r}')
        if not (period > 0.0 and math.isfinite(period)):
            raise ValueError(f'the command period must be positive (seconds), got {period!r}')
        self._ruckig = ruckig
        self._generator = ruckig.Ruckig(6, period)
        self._input = ruckig.InputParameter(6)
        self._output = ruckig.OutputParameter(6)
        self._input.max_velocity = [actuator_limits.velocity_max] * 6
        self._input.max_acceleration = [actuator_limits.acceleration_max] * 6
        self._input.max_jerk = [actuator_limits.jerk_max] * 6
        # Phase synchronisation: from rest (or moving along the jump) the legs move in
        # proportion, a straight line in leg space; otherwise ruckig falls back to
        # synchronising the arrival time only.
        self._input.synchronization = ruckig.Synchronization.Phase
        self.period = period
        self.limits = actuator_limits
        self.reset(lengths)

    def reset(self, lengths) -> None:
        """
        Put the command at rest at ``lengths`` (metres, shape (6,)), which is also the target.

        :raises ValueError: if the lengths are not six finite numbers.
        """
        lengths = _six('lengths', lengths)
        self._input.current_position = lengths.tolist()
        self._input.current_velocity = [0.0] * 6
        self._input.current_acceleration = [0.0] * 6
        self.set_target(lengths)

    def set_target(self, lengths) -> None:
        """
        Aim at new leg lengths (metres, shape (6,)), to be reached at rest.

        :raises ValueError: if the lengths are not six finite numbers.
        """
        self._input.target_position = _six('target lengths', lengths).tolist()
        self._input.target_velocity = [0.0] * 6
        self._input.target_acceleration = [0.0] * 6

    @property
    def target(self) -> np.ndarray:
        """Return the leg lengths aimed at, metres, shape (6,)."""
        return np.array(self._input.target_position)

    def step(self) -> FilteredCommand:
        """
        Advance the command by one period toward the target.

        :returns: the new command, within every limit.
        """
        result = self._generator.update(self._input, self._output)
        if result not in (self._ruckig.Result.Working, self._ruckig.Result.Finished):
            # Not expected with finite inputs and limits: hold still rather than move wrongly.
            return self._state(False)
        self._output.pass_to_input(self._input)
        return self._state(result == self._ruckig.Result.Finished)

    def _state(self, settled):
        return FilteredCommand(np.array(self._input.current_position),
                               np.array(self._input.current_velocity),
                               np.array(self._input.current_acceleration), settled)


def _six(name, values):
    values = np.array(values, dtype=float)
    if values.shape != (6,) or not np.all(np.isfinite(values)):
        raise ValueError(f'{name} must be 6 finite values (metres), got {values.tolist()}')
    return values
