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
How good a cue is: input against what is felt at the head, and every limit kept or not.

:func:`evaluate` measures a :class:`~.replay.CueReplay`, per axis of the specific force (vehicle
frame = platform frame at neutral; ``[0, 0, g]`` removed from both): the RMSE of the felt
against the input, their Pearson correlation, the delay (the lag of the cross-correlation's
peak, positive when the felt lags), and the false cues (felt beyond ``false_cue_threshold``
with the opposite sign to the input); then the tilt rate against its limit, the share of each
travel range used, the limit violations (poses breaking the limits model, legs beyond their
velocity or acceleration limits), and how far from neutral the platform is ``settle_time``
after the input came to rest. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Dict, Optional, Tuple

import numpy as np

from stewart_kinematics.cueing.limit_margins import leg_speed_violations, poses_allowed
from stewart_kinematics.cueing.settings import STANDARD_GRAVITY
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, rotation_angle_between

AXES = ('x', 'y', 'z')
POSE_AXES = ('X', 'Y', 'Z', 'alpha', 'beta', 'gamma')
#: Default threshold of a false cue, m/s^2 (about the otoliths' threshold of specific force).
FALSE_CUE_THRESHOLD = 0.1
#: Default time after the input comes to rest at which the return to neutral is judged, s.
SETTLE_TIME = 10.0
#: Largest lag searched for the delay, seconds.
MAX_DELAY = 0.5
#: An input within this of rest counts as rest (for :func:`rest_time`): m/s^2 and rad/s.
REST_TOLERANCE = 1e-3


@dataclass(frozen=True)
class AxisMeasures:
    """
    Input against felt specific force along one axis.

    :param axis: ``x``, ``y`` or ``z``.
    :param rmse: root mean square of felt minus input, m/s^2.
    :param correlation: Pearson correlation of the two, NaN when one is constant.
    :param delay: seconds by which the felt lags the input (negative: leads).
    :param false_cues: samples felt beyond the threshold with the opposite sign to the input.
    :param false_cue_time: the time those samples cover, seconds.
    """

    axis: str
    rmse: float
    correlation: float
    delay: float
    false_cues: int
    false_cue_time: float


@dataclass(frozen=True)
class CueEvaluation:
    """
    Every measure of one replay.

    :param axes: specific-force measures for x, y, z.
    :param tilt_rate_peak: largest rate of the tilt channel as commanded (scaled), rad/s.
    :param tilt_rate_violations: samples where it exceeds ``tilt_rate_max``.
    :param platform_tilt_rate_peak: largest roll or pitch rate felt at the head, rad/s (tilt
        plus the rotational channel's cue).
    :param travel_used: share of the travel range used per pose axis, X Y Z alpha beta gamma
        (1 = all of it), or ``None`` without travel ranges.
    :param pose_violations: commanded poses that break the limits model.
    :param leg_velocity_violations: leg velocities beyond ``leg_velocity_max``.
    :param leg_acceleration_violations: leg accelerations beyond ``leg_acceleration_max``.
    :param leg_velocity_peak: m/s.
    :param leg_acceleration_peak: m/s^2.
    :param rest_time: when the input came to rest, seconds, or ``None``.
    :param residual_position: platform position off neutral ``settle_time`` after rest, metres
        (``None`` if the run ends before).
    :param residual_angle: its rotation off neutral then, radians (``None`` likewise).
    :param workspace_scale_min: the smallest share of the cue kept for the limits.
    :param limited_share: share of the samples where the actuators held the platform back.
    :param warnings: warning code -> number of samples.
    """

    axes: Tuple[AxisMeasures, ...]
    tilt_rate_peak: float
    tilt_rate_violations: int
    platform_tilt_rate_peak: float
    travel_used: Optional[Tuple[float, ...]]
    pose_violations: int
    leg_velocity_violations: int
    leg_acceleration_violations: int
    leg_velocity_peak: float
    leg_acceleration_peak: float
    rest_time: Optional[float]
    residual_position: Optional[float]
    residual_angle: Optional[float]
    workspace_scale_min: float
    limited_share: float
    warnings: Dict[str, int]

    @property
    def limit_violations(self) -> int:
        """Return poses and leg samples beyond a limit, added up."""
        return (self.pose_violations + self.leg_velocity_violations
                + self.leg_acceleration_violations)


def pearson(a, b) -> float:
    """Pearson correlation of two equally long series; NaN when one is constant."""
    a = np.asarray(a, dtype=float) - np.mean(a)
    b = np.asarray(b, dtype=float) - np.mean(b)
    norm = math.sqrt(float(np.dot(a, a)) * float(np.dot(b, b)))
    return float(np.dot(a, b) / norm) if norm > 0.0 else math.nan


def delay(times, reference, delayed, max_delay: float = MAX_DELAY) -> float:
    """
    Seconds by which ``delayed`` lags ``reference``: the peak of their cross-correlation.

    Both are resampled on an even grid of the median step; the peak is refined by a parabola
    through its three samples. NaN when either is constant; plus or minus infinity when the
    peak lies at the end of the window searched (no delay within ``max_delay`` explains them).

    :param max_delay: largest lag searched either way, seconds.
    """
    times = np.asarray(times, dtype=float)
    step = float(np.median(np.diff(times)))
    grid = np.arange(times[0], times[-1] + 0.5 * step, step)
    a = np.interp(grid, times, reference)
    b = np.interp(grid, times, delayed)
    a, b = a - a.mean(), b - b.mean()
    if not (np.any(a) and np.any(b)):
        return math.nan
    size = 1 << int(math.ceil(math.log2(2 * grid.size)))
    # c[k] = sum a[n] b[n + k]: a peak at k > 0 means b lags a.
    correlation = np.fft.irfft(np.conj(np.fft.rfft(a, size)) * np.fft.rfft(b, size), size)
    lags = min(int(max_delay / step), grid.size - 1)
    window = np.concatenate([correlation[-lags:], correlation[:lags + 1]]) if lags else \
        correlation[:1]
    peak = int(np.argmax(window))
    if peak in (0, window.size - 1) and lags:
        # The best lag is at the end of the window: the delay is beyond it (or undefined).
        return math.copysign(math.inf, peak - lags)
    offset = 0.0
    if 0 < peak < window.size - 1:
        left, centre, right = window[peak - 1], window[peak], window[peak + 1]
        curvature = left - 2.0 * centre + right
        if curvature < 0.0:
            offset = 0.5 * (left - right) / curvature
    return (peak - lags + offset) * step


def rest_time(times, specific_force, angular_velocity, gravity: float = STANDARD_GRAVITY,
              tolerance: float = REST_TOLERANCE) -> Optional[float]:
    """
    When the input comes to rest for good: the time after its last sample away from rest.

    :returns: seconds, or ``None`` when the last sample is not at rest.
    """
    force = np.asarray(specific_force, dtype=float) - [0.0, 0.0, gravity]
    moving = (np.max(np.abs(force), axis=1) > tolerance) | (
        np.max(np.abs(angular_velocity), axis=1) > tolerance)
    if moving[-1]:
        return None
    last = np.flatnonzero(moving)
    return float(times[0] if last.size == 0 else times[last[-1] + 1])


def evaluate(replay, geometry, actuator_limits, tilt_rate_max: float, *,
             rest: Optional[float] = None, travel=None,
             false_cue_threshold: float = FALSE_CUE_THRESHOLD,
             settle_time: float = SETTLE_TIME, max_delay: float = MAX_DELAY,
             gravity: float = STANDARD_GRAVITY) -> CueEvaluation:
    """
    Measure a replay.

    :param replay: a :class:`~.replay.CueReplay`.
    :param geometry: the platform whose limits to judge by.
    :param actuator_limits: the leg velocity and acceleration limits to judge by.
    :param tilt_rate_max: rad/s.
    :param rest: when the input came to rest (seconds); default: found by :func:`rest_time`.
    :param travel: travel ranges from the home pose, ``[[negative, positive], ...]`` per pose
        axis, shape (6, 2), metres and radians (``TravelRanges.as_array()``), or ``None``.
    :param false_cue_threshold: m/s^2.
    :param settle_time: seconds after rest at which the return to neutral is judged.
    """
    times = replay.times
    rest_of_input = [0.0, 0.0, gravity]
    wanted = replay.specific_force - rest_of_input
    felt = replay.perceived.specific_force - rest_of_input
    steps = np.diff(times)
    axes = []
    for index, name in enumerate(AXES):
        a, b = wanted[:, index], felt[:, index]
        false = (a * b < 0.0) & (np.abs(b) > false_cue_threshold)
        # Each sample stands for the half steps on either side of it.
        weights = np.concatenate([[0.0], steps]) * 0.5 + np.concatenate([steps, [0.0]]) * 0.5
        axes.append(AxisMeasures(
            axis=name, rmse=float(np.sqrt(np.mean((b - a) ** 2))), correlation=pearson(a, b),
            delay=delay(times, a, b, max_delay), false_cues=int(np.count_nonzero(false)),
            false_cue_time=float(np.sum(weights[false]))))
    commanded_tilt = replay.tilt * replay.tilt_scale[:, None]
    tilt_rates = np.abs(np.diff(commanded_tilt, axis=0) / steps[:, None])
    tilt_rate_peak = float(np.max(tilt_rates, initial=0.0))
    home = np.asarray(geometry.home_pose, dtype=float)
    travel_used = None
    if travel is not None:
        travel = np.asarray(travel, dtype=float)
        offsets = replay.poses - home
        used = []
        for axis in range(6):
            negative, positive = travel[axis]
            share = 0.0
            if positive > 0.0:
                share = max(share, float(np.max(offsets[:, axis])) / positive)
            if negative < 0.0:
                share = max(share, float(np.min(offsets[:, axis])) / negative)
            used.append(float(share))
        travel_used = tuple(used)
    legs = leg_speed_violations(times, replay.lengths, actuator_limits)
    if rest is None:
        rest = rest_time(times, replay.specific_force, replay.angular_velocity, gravity)
    residual_position = residual_angle = None
    if rest is not None and times[-1] >= rest + settle_time:
        index = int(np.searchsorted(times, rest + settle_time))
        pose = replay.poses[index]
        residual_position = float(np.linalg.norm(pose[:3] - home[:3]))
        residual_angle = float(rotation_angle_between(euler_zyx_to_matrix(home[3:]),
                                                      euler_zyx_to_matrix(pose[3:])))
    return CueEvaluation(
        axes=tuple(axes), tilt_rate_peak=tilt_rate_peak,
        tilt_rate_violations=int(np.count_nonzero(np.max(tilt_rates, axis=1)
                                                  > tilt_rate_max * (1.0 + 1e-9))),
        platform_tilt_rate_peak=float(np.max(np.abs(replay.perceived.angular_velocity[:, :2]))),
        travel_used=travel_used,
        pose_violations=int(np.count_nonzero(~poses_allowed(geometry, replay.poses))),
        leg_velocity_violations=legs['velocity'],
        leg_acceleration_violations=legs['acceleration'],
        leg_velocity_peak=legs['velocity_peak'], leg_acceleration_peak=legs['acceleration_peak'],
        rest_time=rest, residual_position=residual_position, residual_angle=residual_angle,
        workspace_scale_min=float(np.min(replay.workspace_scale)),
        limited_share=float(np.mean(replay.acceleration_scale < 1.0)),
        warnings=dict(replay.warnings))
