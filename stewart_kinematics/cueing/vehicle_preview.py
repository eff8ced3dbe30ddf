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
The vehicle's motion to come, as the model-predictive cueing's reference over its horizon.

A simulator that knows its next seconds (a replay, a scripted drive, a driver model's
prediction) gives them as an :class:`InputPreview`: samples of the specific force and angular
velocity at the head (vehicle frame, the frame of :meth:`.motion_cueing.MotionCueing.step`'s
inputs) on the clock of the samples cued. :func:`interval_means` turns it into what the MPC
plans against: the mean input over each step of its horizon (the MPC's model holds the
vehicle's input over a step, so the mean is the value that step's perception sees), the
present sample first and the preview's samples after it, linearly interpolated. Past the
preview's last sample the input is predicted as without a preview: that sample held, fading
toward rest with ``mpc_reference_time_constant``. Nothing here imports ROS.
"""

from dataclasses import dataclass

import numpy as np

from stewart_kinematics.model.arrays import as_float_array

#: Points averaged per step of the horizon (midpoints of equal sub-intervals).
POINTS_PER_STEP = 16


@dataclass(frozen=True)
class InputPreview:
    """
    The vehicle's motion to come, sampled.

    :param times: seconds, shape (M,), increasing, finite, M >= 1; the clock of the samples
        cued.
    :param inputs: shape (M, 6): the specific force (m/s^2, with gravity: ``[0, 0, g]`` at
        rest) and the angular velocity (rad/s), head, vehicle frame.
    """

    times: np.ndarray
    inputs: np.ndarray

    @property
    def end(self) -> float:
        """Return the time of the last sample, seconds."""
        return float(self.times[-1])


def input_preview(times, specific_force, angular_velocity, max_specific_force: float,
                  max_angular_velocity: float) -> InputPreview:
    """
    Return a checked :class:`InputPreview`.

    :param times: seconds, shape (M,), M >= 1, finite and increasing.
    :param specific_force: m/s^2, head, vehicle frame, with gravity, shape (M, 3).
    :param angular_velocity: rad/s, shape (M, 3).
    :param max_specific_force: a larger magnitude is refused as absurd, m/s^2 (finite: the
        settings' ``max_specific_force``).
    :param max_angular_velocity: likewise, rad/s (the settings' ``max_angular_velocity``).
    :raises ValueError: naming the argument (and the sample), for a malformed, non-finite or
        absurd preview, or times that do not increase.
    """
    times = np.array(as_float_array(times, 'preview times'))   # a copy, made read-only
    if times.ndim != 1 or times.size < 1:
        raise ValueError(f'preview times must have shape (M,) with M >= 1, got {times.shape}')
    if not np.all(np.isfinite(times)):
        raise ValueError('preview times must be finite')
    # Compared, not subtracted: the difference of -1e308 and 1e308 overflows.
    increasing = times[1:] > times[:-1]
    if not np.all(increasing):
        index = int(np.argmin(increasing)) + 1
        raise ValueError(f'preview times must increase: sample {index} '
                         f'({float(times[index])!r} s) does not come after the one before '
                         f'({float(times[index - 1])!r} s)')
    columns = []
    for name, value, largest, unit in (
            ('preview specific_force', specific_force, max_specific_force, 'm/s^2'),
            ('preview angular_velocity', angular_velocity, max_angular_velocity, 'rad/s')):
        array = as_float_array(value, name)
        if array.shape != (times.size, 3):
            raise ValueError(f'{name} must have shape ({times.size}, 3) to match the times, '
                             f'got {array.shape}')
        if not np.all(np.isfinite(array)):
            index = int(np.argmin(np.all(np.isfinite(array), axis=1)))
            raise ValueError(f'{name} must be finite: sample {index} is {array[index].tolist()}')
        refuse_absurd_rows(name, array, largest, unit)
        columns.append(array)
    inputs = np.concatenate(columns, axis=1)
    times.setflags(write=False)
    inputs.setflags(write=False)
    return InputPreview(times=times, inputs=inputs)


def refuse_absurd_rows(name: str, rows: np.ndarray, largest: float, unit: str,
                       row: str = 'sample') -> None:
    """
    Refuse rows of three finite numbers whose magnitude is beyond ``largest``.

    :param name: the argument, as the message gives it.
    :param rows: shape (M, 3), finite.
    :param largest: the largest magnitude allowed (``max_specific_force`` or
        ``max_angular_velocity``), in ``unit``.
    :param row: what a row is called in the message (``sample``, ``row``).
    :raises ValueError: naming the first row beyond, and its magnitude.
    """
    # The largest component first: squaring 1e308 would overflow.
    norms = np.max(np.abs(rows), axis=1)
    if np.all(norms <= largest):
        norms = np.sqrt(np.sum(rows * rows, axis=1))
    if not np.all(norms <= largest):
        index = int(np.argmax(norms))
        raise ValueError(f'{name}: {row} {index} of magnitude at least {norms[index]:.6g} '
                         f'{unit} is beyond {largest:g} {unit}: absurd for a vehicle')


def interval_means(preview: InputPreview, now: float, current, step: float, horizon: int,
                   rest, fading_time_constant: float) -> np.ndarray:
    """
    Return the mean input over each step of the horizon, shape (horizon, 6).

    Step ``k`` covers ``[now + k step, now + (k + 1) step)``; its mean is that of
    :data:`POINTS_PER_STEP` points spread over it. The input between ``now`` and the first
    preview sample after it is interpolated from ``current``; the preview's samples at or
    before ``now`` are not used. Past the preview's end, its last sample ``u_end`` is held and
    fades toward ``rest``: ``rest + (u_end - rest) exp(-(t - end) / fading_time_constant)``
    (``inf``: held; ``0``: at rest at once), as the MPC predicts an input without a preview.

    :param preview: the :class:`InputPreview`.
    :param now: the present sample's time, seconds, the preview's clock.
    :param current: the present input, shape (6,), as the preview's.
    :param step: seconds per step of the horizon, > 0.
    :param horizon: steps, >= 1.
    :param rest: the input at rest, shape (6,) (``[0, 0, g, 0, 0, 0]``).
    :param fading_time_constant: seconds, >= 0 or ``inf``.
    """
    points = ((np.arange(horizon * POINTS_PER_STEP) + 0.5) / POINTS_PER_STEP) * step + now
    times, inputs = preview.times, preview.inputs
    first = int(np.searchsorted(times, now, side='right'))
    last = min(int(np.searchsorted(times, points[-1], side='right')) + 1, times.size)
    known_times = np.concatenate([[now], times[first:last]])
    known = np.concatenate([np.asarray(current, dtype=float)[None, :], inputs[first:last]])
    end = known_times[-1]
    values = np.empty((points.size, 6))
    for column in range(6):
        values[:, column] = np.interp(points, known_times, known[:, column])
    beyond = points > end
    if np.any(beyond):
        rest = np.asarray(rest, dtype=float)
        if fading_time_constant == 0.0:
            fading = np.zeros(int(np.count_nonzero(beyond)))
        else:
            fading = np.exp(-(points[beyond] - end) / fading_time_constant)
        values[beyond] = rest + (known[-1] - rest) * fading[:, None]
    return values.reshape(horizon, POINTS_PER_STEP, 6).mean(axis=1)
