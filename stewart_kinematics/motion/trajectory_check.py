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
TimedTrajectory` densely in time and reports the first sample that breaks a limit of the
geometry (stroke, joint cones, singularity margin, leg collisions) or of the actuators (leg
velocity, leg acceleration), naming the time, the waypoint segment, the leg and the limit. The
limits are the limits model's (:class:`~stewart_kinematics.limits.LimitModel`): the pose limits
on the samples' poses, the leg rates on their leg states
(:func:`~stewart_kinematics.model.velocities.leg_states`).

:func:`trajectory_frame_refusal` refuses a trajectory given for a tool frame that is offset
from the platform frame (trajectories are interpolated and checked as platform-frame poses).

Units: metres, radians, seconds. Nothing here imports ROS.
"""

from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.findings import Finding
from stewart_kinematics.limits import LimitModel, Violation
from stewart_kinematics.limits.leg_rates import RATE_SLACK
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.velocities import leg_states
from stewart_kinematics.motion.pose_trajectory import TimedTrajectory

#: The leg speed limits, as :class:`~stewart_kinematics.limits.Violation` names them.
SPEED_LIMITS = ('leg_velocity_max', 'leg_acceleration_max')
#: Default sampling rate of the whole-trajectory check, hertz.
DEFAULT_VALIDATION_RATE = 1000.0
#: Samples checked at once: bounds the memory of a long trajectory's check.
CHECK_CHUNK = 20000


@dataclass(frozen=True)
class TrajectoryCheck:
    """
    Result of checking a timed trajectory whole.

    :param accepted: True when no sample breaks a limit.
    :param reason: ``''``, or what the first failing sample breaks: time, segment, legs,
        limits.
    :param time: clock time of the first failing sample, seconds, or ``None``.
    :param segment: ``(k, k + 1)``, the waypoints around it, or ``None``.
    :param violations: every limit the first failing sample breaks.
    :param samples: how many samples were checked.
    :param peak_velocity_ratio: largest ``|leg velocity| / leg_velocity_max`` seen (0 when
        there is no velocity limit).
    :param peak_acceleration_ratio: likewise for the acceleration.
    """

    accepted: bool
    reason: str = ''
    time: Optional[float] = None
    segment: Optional[Tuple[int, int]] = None
    violations: Tuple[Violation, ...] = ()
    samples: int = 0
    peak_velocity_ratio: float = 0.0
    peak_acceleration_ratio: float = 0.0


def check_trajectory(trajectory: TimedTrajectory, geometry,
                     actuator_limits: Optional[ActuatorLimits] = None, *,
                     validation_rate: float = DEFAULT_VALIDATION_RATE) -> TrajectoryCheck:
    """
    Check every sample of a timed trajectory against every limit; stop at the first failure.

    Samples every ``1 / validation_rate`` seconds, at every waypoint and at the end, against
    the pose limits of ``geometry`` and the leg velocity and acceleration limits of
    ``actuator_limits`` (``None``: none; the jerk limit is for streamed commands, and not
    checked here), with :data:`~stewart_kinematics.limits.leg_rates.RATE_SLACK` for rounding.
    Vectorised over samples, in chunks of :data:`CHECK_CHUNK`.

    :returns: a :class:`TrajectoryCheck`; its ``reason`` names the first failing time, the
        waypoint segment (points k and k + 1), and each leg and limit broken there.
    """
    actuator_limits = actuator_limits or ActuatorLimits()
    model = LimitModel(geometry, ActuatorLimits(actuator_limits.velocity_max,
                                                actuator_limits.acceleration_max),
                       rate_slack=RATE_SLACK)
    times = trajectory.sample_times(validation_rate)
    peaks = dict.fromkeys(SPEED_LIMITS, 0.0)
    for start in range(0, times.shape[0], CHECK_CHUNK):
        chunk = times[start:start + CHECK_CHUNK]
        poses = trajectory.sample(chunk)
        pose_checks = model.check_pose_matrices(poses.positions, poses.rotations, exact=False)
        allowed = pose_checks.allowed
        rates = None
        if actuator_limits.limits_speed:
            legs = leg_states(geometry, poses)
            rates = model.check_leg_states(velocities=legs.velocities,
                                           accelerations=legs.accelerations)
            allowed = allowed & rates.allowed
            for name in peaks:
                if name in rates.broken and len(chunk):
                    peaks[name] = max(peaks[name], float(np.max(rates.values(name)))
                                      / model.bound(name).allowed)
        failing = np.flatnonzero(~allowed)
        if failing.size:
            first = int(failing[0])
            time = float(chunk[first])
            segment = int(trajectory.segments(np.array([time]))[0])
            violations = tuple(pose_checks.violations(first)) + (
                () if rates is None else tuple(rates.violations(first)))
            reason = (f't = {time:.4f} s, between points {segment} and {segment + 1}: '
                      + '; '.join(str(violation) for violation in violations))
            return TrajectoryCheck(False, reason, time, (segment, segment + 1), violations,
                                   start + first + 1, *peaks.values())
    return TrajectoryCheck(True, samples=times.shape[0],
                           peak_velocity_ratio=peaks['leg_velocity_max'],
                           peak_acceleration_ratio=peaks['leg_acceleration_max'])


def trajectory_frame_refusal(frames, topic: str) -> Optional[Finding]:
    """
    Refuse a trajectory while the tool frame is offset from the platform frame, or say nothing.

    Trajectories are interpolated and checked as platform-frame poses; with another tool frame
    their velocities would have to be moved to it too.

    :param frames: the node's :class:`stewart_kinematics.FrameTree`.
    :param topic: the topic the trajectory came on, for the message.
    :returns: a ``tool_frame_not_supported`` finding, or ``None`` when the tool frame is the
        platform frame.
    """
    if frames.tool_pose.is_identity():
        return None
    return Finding(findings.TOOL_FRAME_NOT_SUPPORTED, (
        f'{topic} is planned for the platform frame, but tool_frame '
        f"'{frames.tool_frame}' is offset from it: set tool_frame_position and "
        'tool_frame_orientation_deg to zero to send trajectories'))
