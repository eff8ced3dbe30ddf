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
Motion planning: decide whether, and how, to play a platform trajectory.

:func:`plan_motion` checks a trajectory whole (:mod:`~stewart_kinematics.motion.
trajectory_check`), retimes it if asked (:mod:`~stewart_kinematics.motion.retiming`), and
returns a :class:`MotionPlan` that says whether it is accepted and, if not, why.

Units: metres, radians, seconds. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional

import numpy as np

from stewart_kinematics.findings import (
    Finding,
    OUT_OF_LIMITS,
    RETIMING_FAILED,
    TOO_FAST,
    TRAJECTORY_TOO_LONG,
    violation_details,
)
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.motion.pose_trajectory import PoseTrajectory, TimedTrajectory
from stewart_kinematics.motion.retiming import retime
from stewart_kinematics.motion.trajectory_check import (
    check_trajectory,
    DEFAULT_VALIDATION_RATE,
    SPEED_LIMITS,
    too_long_to_check,
    TrajectoryCheck,
)

#: A retimed trajectory that exceeds a leg limit between toppra's gridpoints is stretched by
#: its excess times this (the samples then fall elsewhere: up to MAX_STRETCHES times).
STRETCH_MARGIN = 1.001
MAX_STRETCHES = 5


@dataclass(frozen=True)
class MotionPlan:
    """
    What :func:`plan_motion` decided.

    :param accepted: True when the trajectory may be played.
    :param reason: ``''``, or why it is refused (time, segment, leg, limit).
    :param trajectory: the timed trajectory to play, or ``None`` when refused.
    :param check: the whole-trajectory check (of the timing played, or of the path when the
        path itself breaks a pose limit).
    :param retimed: True when the timing comes from :func:`retime`.
    """

    accepted: bool
    reason: str
    trajectory: Optional[TimedTrajectory]
    check: Optional[TrajectoryCheck]
    retimed: bool = False

    @property
    def refusal(self) -> Optional[Finding]:
        """
        Return why the trajectory is refused, as a finding to count and report; ``None``.

        Its code is :data:`OUT_OF_LIMITS` (stroke, cones, singularity margin), :data:`TOO_FAST`
        (only leg velocity or acceleration broken), :data:`TRAJECTORY_TOO_LONG` (the check
        would take too many samples) or :data:`RETIMING_FAILED`; its details give the time,
        the segment and every violated limit.
        """
        if self.accepted:
            return None
        check = self.check
        if check is not None and not check.complete:
            return Finding(TRAJECTORY_TOO_LONG, self.reason)
        if check is None or check.accepted or not check.violations:
            return Finding(RETIMING_FAILED, self.reason)
        code = TOO_FAST if all(violation.limit in SPEED_LIMITS
                               for violation in check.violations) else OUT_OF_LIMITS
        return Finding(code, self.reason, (
            ('time_s', f'{check.time:.4f}'),
            ('segment', f'points {check.segment[0]} and {check.segment[1]}'),
        ) + violation_details(check.violations))


def plan_motion(path: PoseTrajectory, geometry, actuator_limits: Optional[ActuatorLimits] = None,
                *, retime_path: bool = False, speed_scale: float = 1.0,
                validation_rate: float = DEFAULT_VALIDATION_RATE) -> MotionPlan:
    """
    Decide whether, and how, to play a platform trajectory: checked whole, timed, or refused.

    Without ``retime_path`` the trajectory keeps its own timing, slowed by ``1 /
    speed_scale``, and is refused if any sample breaks a limit, leg velocity and acceleration
    included. With it, the path is retimed (:func:`retime`) and the result checked whole;
    where the motion between toppra's gridpoints exceeds a leg limit, the timing is
    first stretched uniformly by that excess (times :data:`STRETCH_MARGIN`), until every
    sample is within.

    :param path: the trajectory; a path without timing comes from :meth:`PoseTrajectory.path`
        and must be retimed.
    :param actuator_limits: leg velocity, acceleration (and jerk, unused here); ``None``: none.
    :param speed_scale: in (0, 1].
    :param validation_rate: samples per second of the check, hertz.
    """
    actuator_limits = actuator_limits or ActuatorLimits()
    if not retime_path:
        trajectory = TimedTrajectory.as_given(path, speed_scale)
        check = check_trajectory(trajectory, geometry, actuator_limits,
                                 validation_rate=validation_rate)
        if not check.accepted:
            return MotionPlan(False, check.reason, None, check)
        return MotionPlan(True, '', trajectory, check)
    try:
        trajectory = retime(path, geometry, actuator_limits, speed_scale)
    except ValueError as error:
        # Say what is wrong with the path itself, if anything, rather than toppra's failure.
        check = check_trajectory(TimedTrajectory.as_given(path), geometry,
                                 validation_rate=validation_rate)
        reason = f'{check.reason} (on the path as given)' if not check.accepted else str(error)
        return MotionPlan(False, reason, None, check, True)
    # toppra meets the limits at its gridpoints; between them the motion may exceed them
    # slightly: stretch the timing by the largest excess over the check's samples.
    scaled = actuator_limits.scaled(speed_scale)
    for _ in range(MAX_STRETCHES):
        refusal = too_long_to_check(trajectory, validation_rate)
        if refusal is not None:
            return MotionPlan(False, refusal.reason, None, refusal, True)
        legs = trajectory.legs(geometry, trajectory.sample_times(validation_rate))
        excess = max(np.abs(legs.velocities).max() / scaled.velocity_max,
                     math.sqrt(np.abs(legs.accelerations).max() / scaled.acceleration_max))
        if not excess > 1.0:
            break
        trajectory = trajectory.stretched(excess * STRETCH_MARGIN)
    check = check_trajectory(trajectory, geometry, scaled, validation_rate=validation_rate)
    if not check.accepted:
        return MotionPlan(False, check.reason, None, check, True)
    return MotionPlan(True, '', trajectory, check, True)
