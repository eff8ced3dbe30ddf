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
Replay a recorded or generated input through :class:`~.motion_cueing.MotionCueing`, in one call.

:func:`replay` steps the same object a node steps, sample by sample, and gathers every output
as arrays (:class:`CueReplay`), with the motion felt at the head computed over the whole run
(centred differences, :func:`~.perception.perceived_motion`). Nothing here imports ROS.
"""

from dataclasses import dataclass
from typing import Callable, Dict, Optional

import numpy as np

from stewart_kinematics.cueing.motion_cueing import MotionCueing
from stewart_kinematics.cueing.perception import perceived_motion, PerceivedMotion
from stewart_kinematics.model.arrays import as_float_array

#: Samples between two calls of the progress callback.
PROGRESS_EVERY = 200


@dataclass(frozen=True)
class CueReplay:
    """
    Everything a replay gave, sample by sample (N samples).

    :param times: seconds, (N,).
    :param specific_force: the input, m/s^2, vehicle frame, (N, 3).
    :param angular_velocity: the input, rad/s, (N, 3).
    :param poses: the platform poses commanded, (N, 6).
    :param lengths: their leg lengths, metres, (N, 6).
    :param displacement: the washout's head displacement, metres, (N, 3).
    :param angles: the washout's roll, pitch, yaw, radians, (N, 3).
    :param tilt: the tilt channel's roll and pitch, radians, (N, 2).
    :param tilt_rate: their rates, rad/s, (N, 2).
    :param workspace_scale: (N,), in [0, 1].
    :param tilt_scale: (N,), in [0, 1].
    :param acceleration_scale: (N,), in [0, 1].
    :param perceived: the specific force and angular velocity felt at the head.
    :param warnings: how many steps carried each warning code.
    """

    times: np.ndarray
    specific_force: np.ndarray
    angular_velocity: np.ndarray
    poses: np.ndarray
    lengths: np.ndarray
    displacement: np.ndarray
    angles: np.ndarray
    tilt: np.ndarray
    tilt_rate: np.ndarray
    workspace_scale: np.ndarray
    tilt_scale: np.ndarray
    acceleration_scale: np.ndarray
    perceived: PerceivedMotion
    warnings: Dict[str, int]


def _samples(name, values, count):
    array = as_float_array(values, name)
    if array.shape != (count, 3):
        raise ValueError(f'{name} must have shape ({count}, 3) to match the times, got '
                         f'{array.shape}')
    return array


def replay(cueing: MotionCueing, times, specific_force, angular_velocity,
           progress: Optional[Callable[[int, int], None]] = None,
           preview: bool = False) -> CueReplay:
    """
    Step ``cueing`` through every sample and return what it gave.

    :param cueing: a fresh :class:`MotionCueing` (or one to continue).
    :param times: seconds, shape (N,), increasing, N >= 3.
    :param specific_force: m/s^2, vehicle frame at the head, shape (N, 3).
    :param angular_velocity: rad/s, shape (N, 3).
    :param progress: called as ``progress(done, total)`` every :data:`PROGRESS_EVERY` samples
        and at the end.
    :param preview: tell a model-predictive cueing the input to come
        (:meth:`MotionCueing.set_preview` with the whole input: at each sample the MPC sees
        the next horizon of it), as a simulator that knows its drive would.
    :raises ValueError: naming the argument and the sample, for a malformed, non-finite or
        absurd sample, or times that do not increase; for a preview, if the cueing is not
        model-predictive.
    """
    times = as_float_array(times, 'times')
    if times.ndim != 1 or times.size < 3:
        raise ValueError(f'times must have shape (N,) with N >= 3, got {times.shape}')
    count = times.size
    forces = _samples('specific_force', specific_force, count)
    rates = _samples('angular_velocity', angular_velocity, count)
    if preview:
        cueing.set_preview(times, forces, rates)
    outputs = {name: np.empty((count, size)) for name, size in (
        ('poses', 6), ('lengths', 6), ('displacement', 3), ('angles', 3), ('tilt', 2),
        ('tilt_rate', 2), ('workspace_scale', 1), ('tilt_scale', 1), ('acceleration_scale', 1))}
    warnings = {}
    for index in range(count):
        try:
            step = cueing.step(times[index], forces[index], rates[index])
        except ValueError as error:
            raise ValueError(f'sample {index} (time {float(times[index])!r} s): {error}') from None
        for name in ('poses', 'lengths'):
            outputs[name][index] = getattr(step, 'pose' if name == 'poses' else name)
        for name in ('displacement', 'angles', 'tilt', 'tilt_rate', 'workspace_scale',
                     'tilt_scale', 'acceleration_scale'):
            outputs[name][index] = getattr(step, name)
        for finding in step.warnings:
            warnings[finding.code] = warnings.get(finding.code, 0) + 1
        if progress is not None and ((index + 1) % PROGRESS_EVERY == 0 or index + 1 == count):
            progress(index + 1, count)
    perceived = perceived_motion(times, outputs['poses'], cueing.settings.head_position,
                                 cueing.settings.gravity)
    return CueReplay(
        times=times, specific_force=forces, angular_velocity=rates, poses=outputs['poses'],
        lengths=outputs['lengths'], displacement=outputs['displacement'],
        angles=outputs['angles'], tilt=outputs['tilt'], tilt_rate=outputs['tilt_rate'],
        workspace_scale=outputs['workspace_scale'][:, 0], tilt_scale=outputs['tilt_scale'][:, 0],
        acceleration_scale=outputs['acceleration_scale'][:, 0], perceived=perceived,
        warnings=warnings)
