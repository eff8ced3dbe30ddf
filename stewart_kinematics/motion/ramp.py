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
Ramps described as the paper's Table 3: start, step and end per axis.

A ramp is a lookup table of poses ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians): its rows
go from ``start`` to ``end`` in equal steps. It can be played row by row, or sampled in
time like the paper's clock-driven lookup tables, which interpolate linearly between rows.
"""

from dataclasses import dataclass, field
import math

import numpy as np

from stewart_kinematics.model.kinematics import as_poses
from stewart_kinematics.parameters.settings import RampSettings

#: Relative slack when checking that (end - start) / step is a whole number of steps.
STEP_COUNT_TOLERANCE = 1e-9


@dataclass(frozen=True, eq=False)
class Ramp:
    """
    A table of poses from ``start`` to ``end`` in equal steps, validated on construction.

    :param start: first pose, ``[X, Y, Z, alpha, beta, gamma]`` in metres and radians.
    :param step: change from one row to the next, same units; 0 on an axis that stays put.
    :param end: last pose, same units.
    :raises ValueError: if an axis cannot reach its end in whole steps, or the axes need
        different numbers of steps, naming the axis and the counts.
    """

    start: np.ndarray
    step: np.ndarray
    end: np.ndarray
    step_count: int = field(init=False)

    AXES = ('X', 'Y', 'Z', 'alpha', 'beta', 'gamma')

    def __post_init__(self):
        for name in ('start', 'step', 'end'):
            array = np.array(as_poses(getattr(self, name), f'ramp {name}'))
            if array.shape != (6,):
                raise ValueError(f'ramp {name} must be one pose of shape (6,)')
            array.flags.writeable = False
            object.__setattr__(self, name, array)
        counts = {}
        for index, (axis, start, step, end) in enumerate(
                zip(self.AXES, self.start, self.step, self.end)):
            span = end - start
            scale = max(abs(start), abs(end), abs(step), 1.0)
            # Messages in the units of the parameter files: metres, and degrees for angles.
            shown = (lambda value: f'{value:g} m') if index < 3 else (
                lambda value: f'{math.degrees(value):g} deg')
            if step == 0.0:
                if abs(span) > STEP_COUNT_TOLERANCE * scale:
                    raise ValueError(
                        f'ramp axis {axis}: step is 0 but start {shown(start)} differs from '
                        f'end {shown(end)}')
                continue
            count = span / step
            if count < -STEP_COUNT_TOLERANCE:
                raise ValueError(
                    f'ramp axis {axis}: step {shown(step)} points away from the end: from '
                    f'{shown(start)} to {shown(end)} needs a step of the other sign')
            if abs(count - round(count)) > STEP_COUNT_TOLERANCE * scale / abs(step):
                raise ValueError(
                    f'ramp axis {axis}: from {shown(start)} to {shown(end)} is not a whole '
                    f'number of steps of {shown(step)} ({count:g} steps)')
            counts[axis] = int(round(count))
        if len(set(counts.values())) > 1:
            raise ValueError(
                'every ramp axis must take the same number of steps, got '
                + ', '.join(f'{axis}: {count}' for axis, count in counts.items()))
        object.__setattr__(self, 'step_count', next(iter(counts.values()), 0))

    @classmethod
    def from_settings(cls, settings: RampSettings) -> 'Ramp':
        """
        Build a ramp from the trajectory node's ramp settings (metres and degrees).

        :raises ValueError: naming the axis and its parameters, if the table is inconsistent.
        """
        names = ('position_start', 'position_step', 'position_end',
                 'orientation_start_deg', 'orientation_step_deg', 'orientation_end_deg')
        try:
            return cls.from_table(*(getattr(settings, name) for name in names))
        except ValueError as error:
            raise ValueError(f'{error} (parameters {", ".join(names)})') from error

    @classmethod
    def from_table(cls, position_start, position_step, position_end,
                   orientation_start_deg, orientation_step_deg, orientation_end_deg) -> 'Ramp':
        """
        Build a ramp from a table in the units of the parameter files.

        :param position_start: X, Y, Z of the first row, metres; likewise ``position_step``
            and ``position_end``.
        :param orientation_start_deg: alpha, beta, gamma of the first row, degrees; likewise
            ``orientation_step_deg`` and ``orientation_end_deg``.
        """
        def pose(position, orientation_deg):
            return np.concatenate([np.asarray(position, dtype=float),
                                   np.radians(np.asarray(orientation_deg, dtype=float))])
        return cls(start=pose(position_start, orientation_start_deg),
                   step=pose(position_step, orientation_step_deg),
                   end=pose(position_end, orientation_end_deg))

    @property
    def rows(self) -> np.ndarray:
        """Return the table's poses, shape (step_count + 1, 6); the last is exactly ``end``."""
        index = np.arange(self.step_count + 1)[:, None]
        rows = self.start + index * self.step
        rows[-1] = self.end
        return rows

    def sample(self, times, duration) -> np.ndarray:
        """
        Poses at the given times of a ramp played over ``duration`` seconds.

        Rows are spread evenly over ``[0, duration]`` and poses between them interpolated
        linearly, as a Simulink lookup table driven by a clock does; before 0 the ramp holds the
        first row, after ``duration`` the last.

        :param times: seconds since the start, scalar or shape (N,).
        :param duration: seconds from the first row to the last, positive.
        :returns: shape (6,) or (N, 6).
        """
        if not duration > 0.0:
            raise ValueError(f'duration must be positive (seconds), got {duration!r}')
        times = np.asarray(times, dtype=float)
        rows = self.rows
        if self.step_count == 0:
            return np.broadcast_to(rows[0], times.shape + (6,)).copy()
        row_times = np.linspace(0.0, duration, self.step_count + 1)
        return np.stack([np.interp(times, row_times, rows[:, axis]) for axis in range(6)],
                        axis=-1)
