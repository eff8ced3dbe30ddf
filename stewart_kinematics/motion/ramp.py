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
Ramps described as the paper's Table 3: start, step and end per axis, and how one is played.

A ramp is a lookup table of poses ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians): its rows
go from ``start`` to ``end`` in equal steps. It can be played row by row, or sampled in
time like the paper's clock-driven lookup tables, which interpolate linearly between rows.

A :class:`RampSchedule` is trajectory_node's decision of what to publish when: the mode (rows
or samples, or no ramp), the times and poses of a pass, and the check of every one of those
poses against the limits before anything is played (:meth:`RampSchedule.check`).
"""

from dataclasses import dataclass, field
import math
from typing import Optional

import numpy as np

from stewart_kinematics.findings import Finding
from stewart_kinematics.limits import check_samples
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.inputs import as_poses
from stewart_kinematics.parameters.settings import RampSettings

#: How trajectory_node plays a ramp: rows on a timer, samples in time, or no ramp.
RAMP_MODES = ('table', 'interpolate', 'off')

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
            position = as_float_array(position, 'position')
            orientation = as_float_array(orientation_deg, 'orientation')
            if position.shape != (3,) or orientation.shape != (3,):
                raise ValueError(f'a ramp row is 3 position and 3 orientation values, got '
                                 f'shapes {position.shape} and {orientation.shape}')
            return np.concatenate([position, np.radians(orientation)])
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
        if not (isinstance(duration, (int, float, np.integer, np.floating))
                and not isinstance(duration, bool) and 0.0 < duration < math.inf):
            raise ValueError(f'duration must be positive and finite (seconds), got {duration!r}')
        times = as_float_array(times, 'times')
        if not np.all(np.isfinite(times)):
            raise ValueError(f'times must be finite (seconds), got {preview(times)}')
        rows = self.rows
        if self.step_count == 0:
            return np.broadcast_to(rows[0], times.shape + (6,)).copy()
        row_times = np.linspace(0.0, duration, self.step_count + 1)
        return np.stack([np.interp(times, row_times, rows[:, axis]) for axis in range(6)],
                        axis=-1)


@dataclass(frozen=True, eq=False)
class RampSchedule:
    """
    What trajectory_node publishes of a ramp, and when: a pass of poses at fixed times.

    :param ramp: the table of poses.
    :param mode: ``'table'``: one row every ``row_period``; ``'interpolate'``: the ramp
        sampled at ``publish_rate`` over ``duration`` (its last sample at ``duration``);
        ``'off'``: no ramp.
    :param row_period: seconds between two rows (table mode).
    :param publish_rate: samples per second (interpolate mode), hertz.
    :param duration: seconds from the first row to the last (interpolate mode).
    :param loop: whether a pass starts again after the last pose.
    :raises ValueError: for an unknown mode or a period, rate or duration that is not positive.
    """

    ramp: Ramp
    mode: str = 'table'
    row_period: float = 1.0
    publish_rate: float = 100.0
    duration: float = 10.0
    loop: bool = False

    def __post_init__(self):
        if self.mode not in RAMP_MODES:
            raise ValueError(f'ramp mode must be one of {RAMP_MODES}, got {self.mode!r}')
        for name in ('row_period', 'publish_rate', 'duration'):
            value = getattr(self, name)
            if not (value > 0.0 and math.isfinite(value)):
                raise ValueError(f'{name} must be positive and finite, got {value!r}')

    @classmethod
    def from_settings(cls, settings: RampSettings) -> 'RampSchedule':
        """
        Build the schedule from trajectory_node's ramp settings (the ramp parameters).

        :raises ValueError: naming the parameters, if the table or the timing is not allowed.
        """
        return cls(Ramp.from_settings(settings), settings.mode, settings.row_period,
                   settings.publish_rate, settings.duration, settings.loop)

    @property
    def plays(self) -> bool:
        """Return whether there is a ramp to play (the mode is not ``'off'``)."""
        return self.mode != 'off'

    @property
    def period(self) -> float:
        """Return the seconds between two published poses."""
        return self.row_period if self.mode == 'table' else 1.0 / self.publish_rate

    def samples(self):
        """
        Return the times (seconds from the start of a pass) and the poses of a pass.

        In interpolate mode the timer's jitter moves the real sample times a little; the ramp
        is linear between rows, so those poses lie between samples returned here.

        :returns: ``(times (N,), poses (N, 6))``; empty when the mode is ``'off'``.
        """
        if self.mode == 'off':
            return np.zeros(0), np.zeros((0, 6))
        if self.mode == 'table':
            rows = self.ramp.rows
            return np.arange(len(rows)) * self.row_period, rows
        times = np.append(np.arange(0.0, self.duration, 1.0 / self.publish_rate), self.duration)
        return times, self.ramp.sample(times, self.duration)

    def pose_at(self, elapsed: float) -> np.ndarray:
        """Return the pose of interpolate mode ``elapsed`` seconds into a pass (the last after)."""
        return self.ramp.sample(min(elapsed, self.duration), self.duration)

    def check(self, geometry, frames=None) -> Optional[Finding]:
        """
        Check every pose of a pass against the limits of ``geometry``, before playing.

        The poses are the tool frame's, as ik_node reads them: with ``frames`` (a
        :class:`stewart_kinematics.FrameTree`), the platform poses they put the platform at are
        checked.

        :returns: ``None`` when every pose is allowed (or there is no ramp); else the
            ``out_of_limits`` finding of :func:`stewart_kinematics.limits.check_samples`, which
            lists the failing samples.
        """
        times, poses = self.samples()
        if not len(times):
            return None
        if frames is not None:
            poses = frames.platform_pose_vectors(poses)
        return check_samples(geometry, times, poses, 'ramp')
