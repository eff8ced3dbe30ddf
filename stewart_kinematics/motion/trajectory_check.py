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
singularity margin, leg collisions) or of the actuators (leg velocity, leg acceleration),
naming the time, the waypoints around it, the leg and the limit. The limits are the limits
model's (:class:`~stewart_kinematics.limits.LimitModel`): the pose limits on the samples'
poses, the leg rates on their leg states (:func:`~stewart_kinematics.model.velocities.
leg_states`).

Leg forces: when the geometry carries masses and sets ``leg_force_min`` or ``leg_force_max``,
a sample is judged with its DYNAMIC forces, its pose moving with its twist and acceleration
(:func:`~stewart_kinematics.motion.trajectory_forces.sample_forces`), and its pose, as every
pose, with its static forces (the limits model's ``leg_force`` kind): a platform stopped there
(a trajectory cancelled, a controller halted) must be held. A sample whose static forces keep
the limit but whose dynamic ones break it is too fast there: the result's ``stretch`` says by
how much to slow the timing. With every mass 0 no force is computed.

Units: metres, radians, seconds. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.limits import LimitModel, Violation
from stewart_kinematics.limits.leg_forces import LegForces
from stewart_kinematics.limits.leg_rates import RATE_SLACK
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.velocities import leg_states
from stewart_kinematics.motion.pose_trajectory import MAX_PIECE_SAMPLES, TimedTrajectory
from stewart_kinematics.motion.retiming import raise_if_cancelled
from stewart_kinematics.motion.trajectory_forces import sample_forces

#: The leg speed limits, as :class:`~stewart_kinematics.limits.Violation` names them.
SPEED_LIMITS = ('leg_velocity_max', 'leg_acceleration_max')
#: Default sampling rate of the whole-trajectory check, hertz.
DEFAULT_VALIDATION_RATE = 1000.0
#: Samples checked at once: bounds the memory of a long trajectory's check, and the time
#: between two looks at the cancel flag (one chunk's vectorised check).
CHECK_CHUNK = 2500
#: Most samples a check takes (a few seconds of work); a trajectory that needs more is
#: refused with a reason instead (``complete`` False).
MAX_CHECK_SAMPLES = 1_000_000


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
    :param stretch: for a refused trajectory that is only too fast at the first failing sample
        (leg velocity, leg acceleration, or dynamic leg forces beyond a limit its static
        forces keep), the factor by which a uniform stretch of the timing brings that sample
        within every limit (velocities / k, accelerations / k^2, the forces' dynamic part /
        k^2); ``None`` otherwise (accepted, or a limit no timing can keep).
    :param peak_force_ratio: largest dynamic ``|leg force| / |limit|`` over the samples,
        against the limit of the force's sign (0 when forces are not checked).
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
    stretch: Optional[float] = None
    peak_force_ratio: float = 0.0


def check_trajectory(trajectory: TimedTrajectory, geometry,
                     actuator_limits: Optional[ActuatorLimits] = None, *,
                     validation_rate: float = DEFAULT_VALIDATION_RATE,
                     max_samples: int = MAX_CHECK_SAMPLES, cancel=None) -> TrajectoryCheck:
    """
    Check every sample of a timed trajectory against every limit; stop at the first failure.

    Samples each piece of the trajectory (between waypoints, and between gridpoints of a
    retiming) at both ends and every ``1 / validation_rate`` seconds or closer, with at most
    :data:`~stewart_kinematics.motion.pose_trajectory.MAX_PIECE_SAMPLES` intervals per piece,
    against the pose limits of ``geometry`` and the leg velocity and acceleration limits of
    ``actuator_limits`` (``None``: none; the jerk limit is for streamed commands, and not
    checked here), with :data:`~stewart_kinematics.limits.leg_rates.RATE_SLACK` for rounding.
    When the geometry carries masses, the dynamic leg forces of every sample (its pose with
    its twist and acceleration) against ``leg_force_min`` and ``leg_force_max``, besides the
    static forces of its pose (see the module's docstring).
    Vectorised over samples, in chunks of :data:`CHECK_CHUNK`.

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
    model = LimitModel(geometry, ActuatorLimits(actuator_limits.velocity_max,
                                                actuator_limits.acceleration_max),
                       rate_slack=RATE_SLACK)
    times = trajectory.sample_times(validation_rate)
    force_evaluator = model.evaluator(LegForces)
    force_bounds = () if force_evaluator is None else force_evaluator.bounds
    peaks = dict.fromkeys(SPEED_LIMITS, 0.0)
    peak_force = 0.0
    for start in range(0, times.shape[0], CHECK_CHUNK):
        raise_if_cancelled(cancel)
        chunk = times[start:start + CHECK_CHUNK]
        poses = trajectory.sample(chunk)
        pose_checks = model.check_pose_matrices(poses.positions, poses.rotations, exact=False)
        allowed = pose_checks.allowed
        rates = forces = None
        if actuator_limits.limits_speed:
            legs = leg_states(geometry, poses)
            rates = model.check_leg_states(velocities=legs.velocities,
                                           accelerations=legs.accelerations)
            allowed = allowed & rates.allowed
            for name in peaks:
                if name in rates.broken and len(chunk):
                    peaks[name] = max(peaks[name], float(np.max(rates.values(name)))
                                      / model.bound(name).allowed)
        if force_bounds and len(chunk):
            forces = sample_forces(geometry, poses)
            for bound in force_bounds:
                allowed = allowed & ~np.any(bound.broken(forces), axis=-1)
                if bound.allowed != 0.0:
                    peak_force = max(peak_force, float(np.nanmax(
                        forces / bound.allowed, initial=0.0)))
        failing = np.flatnonzero(~allowed)
        if failing.size:
            first = int(failing[0])
            time = float(chunk[first])
            segment = trajectory.path.points(int(trajectory.segments(np.array([time]))[0]))
            pose_violations = tuple(pose_checks.violations(first))
            rate_violations = () if rates is None else tuple(rates.violations(first))
            force_violations = () if forces is None else _force_violations(
                force_bounds, forces[first])
            # A leg whose static force breaks the bound too is reported once, by the force
            # the actuator would have to give: the dynamic one.
            reported = {(violation.limit, violation.leg) for violation in force_violations}
            violations = tuple(violation for violation in pose_violations
                               if (violation.limit, violation.leg) not in reported) + (
                rate_violations + force_violations)
            stretch = _stretch(pose_violations, rate_violations, force_bounds,
                               forces, pose_checks, first)
            reason = (f't = {time:.4f} s, between points {segment[0]} and {segment[1]}: '
                      + '; '.join(str(violation) for violation in violations))
            return TrajectoryCheck(False, reason, time, segment, violations,
                                   start + first + 1, *peaks.values(), stretch=stretch,
                                   peak_force_ratio=peak_force)
    return TrajectoryCheck(True, samples=times.shape[0],
                           peak_velocity_ratio=peaks['leg_velocity_max'],
                           peak_acceleration_ratio=peaks['leg_acceleration_max'],
                           peak_force_ratio=peak_force)


def _force_violations(bounds, forces) -> Tuple[Violation, ...]:
    """Return the violations of one sample's dynamic forces, newtons, shape (6,)."""
    return tuple(bound.violation(int(leg), float(forces[leg]))
                 for bound in bounds for leg in np.flatnonzero(bound.broken(forces)))


def _stretch(pose_violations, rate_violations, bounds, forces, pose_checks, index):
    """
    Return the uniform stretch that brings sample ``index`` within its limits, or ``None``.

    ``None`` when a pose limit is broken (the static forces included): no timing keeps it.
    A leg velocity ``v`` over its limit needs ``|v| / limit``; an acceleration the square root
    of that ratio; a dynamic force ``f`` over a bound its static force ``c`` keeps, ``sqrt((f -
    c) / (limit - c))`` (the dynamic part ``f - c`` falls with the square of the stretch).
    """
    if pose_violations:
        return None
    stretch = 1.0
    for violation in rate_violations:
        ratio = abs(violation.value) / violation.allowed
        stretch = max(stretch, math.sqrt(ratio) if violation.limit == 'leg_acceleration_max'
                      else ratio)
    for bound in bounds:
        if forces is None:
            break
        dynamic = forces[index]
        static = pose_checks.values(bound.name)[index]
        broken = bound.broken(dynamic)
        if not broken.any():
            continue
        with np.errstate(all='ignore'):
            ratios = (dynamic - static) / (bound.allowed - static)
        ratios = ratios[broken]
        if not np.all(np.isfinite(ratios)) or np.any(ratios <= 0.0):
            return None
        stretch = max(stretch, math.sqrt(float(ratios.max())))
    return stretch if math.isfinite(stretch) else None
