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
Whole-trajectory check: every sample of a timed trajectory against every limit.

:func:`check_trajectory` samples a :class:`~stewart_kinematics.motion.pose_trajectory.
TimedTrajectory` piece by piece (between waypoints, and gridpoints of a retiming: see
:meth:`~stewart_kinematics.motion.pose_trajectory.TimedTrajectory.sample_times`), at the
validation rate but at most :data:`~stewart_kinematics.motion.pose_trajectory.
MAX_PIECE_SAMPLES` samples in a piece, so that its cost is bounded whatever the trajectory
lasts; beyond :data:`MAX_CHECK_SAMPLES` samples it refuses to check rather than run for
minutes. It reports the first sample that breaks a limit of the geometry (stroke, joint cones,
singularity margin) or of the actuators (leg velocity, leg acceleration), naming the time, the
waypoints around it, the leg and the limit.

Units: metres, radians, seconds. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.limits.checks import joint_angles, Violation
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.kinematics import jacobian_condition, twist_jacobian
from stewart_kinematics.model.velocities import leg_states, PoseSamples
from stewart_kinematics.motion.pose_trajectory import MAX_PIECE_SAMPLES, TimedTrajectory
from stewart_kinematics.motion.retiming import raise_if_cancelled

#: The leg speed limits, as :class:`~stewart_kinematics.limits.Violation` names them.
SPEED_LIMITS = ('leg_velocity_max', 'leg_acceleration_max')
#: Default sampling rate of the whole-trajectory check, hertz.
DEFAULT_VALIDATION_RATE = 1000.0
#: Samples checked at once: bounds the memory of a long trajectory's check, and the time
#: between two looks at the cancel flag (about 10 ms on an idle machine).
CHECK_CHUNK = 2500
#: Most samples a check takes (a few seconds of work); a trajectory that needs more is
#: refused with a reason instead (``complete`` False).
MAX_CHECK_SAMPLES = 1_000_000
#: Relative slack on the leg velocity and acceleration limits, for rounding only.
SPEED_LIMIT_SLACK = 1e-9


@dataclass(frozen=True)
class TrajectoryCheck:
    """
    Result of checking a timed trajectory whole.

    :param accepted: True when no sample breaks a limit.
    :param reason: ``''``, or what the first failing sample breaks: time, segment, legs,
        limits; or why the check was not made.
    :param time: clock time of the first failing sample, seconds, or ``None``.
    :param segment: ``(k, k + 1)``, the waypoints around it (numbered as given), or ``None``.
    :param violations: every limit the first failing sample breaks.
    :param samples: how many samples were checked.
    :param peak_velocity_ratio: largest ``|leg velocity| / leg_velocity_max`` seen (0 when
        there is no velocity limit).
    :param peak_acceleration_ratio: likewise for the acceleration.
    :param complete: False when the check was not made: it would need more than
        ``max_samples`` samples (``accepted`` is then False too).
    """

    accepted: bool
    reason: str = ''
    time: Optional[float] = None
    segment: Optional[Tuple[int, int]] = None
    violations: Tuple[Violation, ...] = ()
    samples: int = 0
    peak_velocity_ratio: float = 0.0
    peak_acceleration_ratio: float = 0.0
    complete: bool = True


def check_trajectory(trajectory: TimedTrajectory, geometry,
                     actuator_limits: Optional[ActuatorLimits] = None, *,
                     validation_rate: float = DEFAULT_VALIDATION_RATE,
                     max_samples: int = MAX_CHECK_SAMPLES, cancel=None) -> TrajectoryCheck:
    """
    Check every sample of a timed trajectory against every limit; stop at the first failure.

    Samples each piece of the trajectory (between waypoints, and between gridpoints of a
    retiming) at both ends and every ``1 / validation_rate`` seconds or closer, with at most
    :data:`~stewart_kinematics.motion.pose_trajectory.MAX_PIECE_SAMPLES` intervals per piece,
    against the stroke, joint cones and singularity margin of ``geometry`` and the leg
    velocity and acceleration limits of ``actuator_limits`` (``None``: none). Vectorised over
    samples, in chunks of :data:`CHECK_CHUNK`.

    :param max_samples: a trajectory that needs more samples is not checked: the result says
        so (``complete`` False), before any sample is computed.
    :param cancel: ``None``, or an event: set, the check stops between two chunks with
        :class:`~stewart_kinematics.motion.retiming.Cancelled`.
    :returns: a :class:`TrajectoryCheck`; its ``reason`` names the first failing time, the
        waypoints around it (as numbered in the input), and each leg and limit broken there.
    """
    actuator_limits = actuator_limits or ActuatorLimits()
    count = trajectory.sample_count(validation_rate)
    if count > max_samples:
        return TrajectoryCheck(False, (
            f'checking the trajectory ({trajectory.duration:.6g} s, '
            f'{trajectory.path.waypoint_count:,} waypoints) at {validation_rate:g} Hz, at most '
            f'{MAX_PIECE_SAMPLES} samples between two waypoints, needs {count:,} samples, more '
            f'than the {max_samples:,} a check may take: send it in parts, or lower '
            'validation_rate'), complete=False)
    times = trajectory.sample_times(validation_rate)
    peak_velocity = peak_acceleration = 0.0
    for start in range(0, times.shape[0], CHECK_CHUNK):
        raise_if_cancelled(cancel)
        chunk = times[start:start + CHECK_CHUNK]
        poses = trajectory.sample(chunk)
        legs = leg_states(geometry, poses)
        broken, ratios = _broken_limits(geometry, actuator_limits, poses, legs)
        peak_velocity = max(peak_velocity, ratios[0])
        peak_acceleration = max(peak_acceleration, ratios[1])
        failing = np.flatnonzero(np.any([mask.any(axis=-1) for _, mask, _, _ in broken], axis=0))
        if failing.size:
            first = int(failing[0])
            time = float(chunk[first])
            segment = trajectory.path.points(int(trajectory.segments(np.array([time]))[0]))
            violations = tuple(
                Violation(name, leg + 1 if values.ndim == 2 else None,
                          float(values[first, leg] if values.ndim == 2 else values[first]),
                          allowed, unit)
                for name, mask, values, (allowed, unit) in broken
                for leg in np.flatnonzero(np.atleast_1d(mask[first])))
            reason = (f't = {time:.4f} s, between points {segment[0]} and {segment[1]}: '
                      + '; '.join(str(violation) for violation in violations))
            return TrajectoryCheck(False, reason, time, segment, violations,
                                   start + first + 1, peak_velocity, peak_acceleration)
    return TrajectoryCheck(True, samples=times.shape[0], peak_velocity_ratio=peak_velocity,
                           peak_acceleration_ratio=peak_acceleration)


def _broken_limits(geometry, actuator_limits, poses, legs):
    """
    Masks of broken limits: ``[(name, mask (M, 6) or (M, 1), values, (allowed, unit))]``.

    Also returns the peak velocity and acceleration ratios to their limits.
    """
    broken = []
    lengths = legs.lengths
    broken.append(('leg_length_min', lengths < geometry.leg_length_min, lengths,
                   (geometry.leg_length_min, 'm')))
    broken.append(('leg_length_max', lengths > geometry.leg_length_max, lengths,
                   (geometry.leg_length_max, 'm')))
    if min(geometry.base_joint_max_angle, geometry.platform_joint_max_angle) < math.pi:
        base_angles, platform_angles = joint_angles(geometry, poses.positions, poses.rotations)
        for name, angles, allowed in (
                ('base_joint_max_angle', base_angles, geometry.base_joint_max_angle),
                ('platform_joint_max_angle', platform_angles, geometry.platform_joint_max_angle)):
            broken.append((name, angles > allowed, np.degrees(angles),
                           (math.degrees(allowed), 'deg')))
    if math.isfinite(geometry.max_jacobian_condition):
        condition = _conditions_to_check(geometry, poses, geometry.max_jacobian_condition)
        broken.append(('max_jacobian_condition',
                       (condition > geometry.max_jacobian_condition)[:, None],
                       condition, (geometry.max_jacobian_condition, '')))
    speeds = np.abs(legs.velocities)
    rates = np.abs(legs.accelerations)
    ratios = [0.0, 0.0]
    for index, (name, values, allowed, unit) in enumerate((
            ('leg_velocity_max', speeds, actuator_limits.velocity_max, 'm/s'),
            ('leg_acceleration_max', rates, actuator_limits.acceleration_max, 'm/s^2'))):
        if math.isfinite(allowed):
            ratios[index] = float(values.max() / allowed) if values.size else 0.0
            broken.append((name, values > allowed * (1.0 + SPEED_LIMIT_SLACK), values,
                           (allowed, unit)))
    return broken, ratios


def _conditions_to_check(geometry, poses: PoseSamples, bound: float) -> np.ndarray:
    """
    Condition numbers of the dimensionless Jacobian where they might exceed ``bound``.

    A singular value decomposition per sample costs about 20 us; most samples are far from
    the bound, and a cheaper test proves it. With ``G = J^T J`` (J the dimensionless Jacobian
    of :func:`stewart_kinematics.model.kinematics.jacobian_condition`) and
    ``U >= lambda_max(G)`` (the smaller of its Frobenius and row-sum norms),
    ``G - (U / bound^2) I`` positive definite (its LDL^T pivots, computed for every sample at
    once, all positive) gives
    ``lambda_min > U / bound^2``, so the condition number ``sqrt(lambda_max / lambda_min)``
    is below ``bound``. The other samples get the exact condition number.

    :returns: shape (M,): the condition number, or NaN where it is proved below ``bound``.
    """
    jac = twist_jacobian(geometry, poses.positions, poses.rotations)
    jac[..., 3:] /= geometry.platform_radius
    gram = np.swapaxes(jac, -1, -2) @ jac
    upper = np.minimum(np.sqrt(np.sum(gram * gram, axis=(-2, -1))),
                       np.abs(gram).sum(axis=-1).max(axis=-1))
    # The second term covers the rounding of the pivots (about 1e-15 U).
    shifted = gram - (upper / bound ** 2 + 1e-13 * upper)[:, None, None] * np.eye(6)
    proved = np.ones(shifted.shape[0], dtype=bool)
    for j in range(6):
        pivot = shifted[:, j, j]
        proved &= pivot > 0.0
        column = shifted[:, j + 1:, j] / np.where(pivot > 0.0, pivot, 1.0)[:, None]
        shifted[:, j + 1:, j + 1:] -= column[:, :, None] * shifted[:, None, j, j + 1:]
    conditions = np.full(shifted.shape[0], np.nan)
    doubtful = ~proved
    if doubtful.any():
        conditions[doubtful] = jacobian_condition(
            geometry, poses.positions[doubtful], poses.rotations[doubtful])
    return conditions
