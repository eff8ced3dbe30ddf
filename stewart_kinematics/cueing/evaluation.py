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
How good a cue is: the vehicle's motion against the platform's, both as a person perceives them.

:func:`evaluate` measures a :class:`~.replay.CueReplay`. The vehicle's motion (the input: what
an IMU at the driver's head reads) and the platform's (the motion felt at the head) go through
the same vestibular model (:func:`~.perception.perception`: otoliths per axis of specific force,
semicircular canals per axis of rate, with their thresholds), and are compared per axis of
specific force (x, y, z; relative to rest) and of rate (roll, pitch, yaw), vehicle frame =
platform frame at neutral:

- the RMSE of the perceived platform against the perceived vehicle, their Pearson
  correlation, the delay (the lag of their cross-correlation's peak within
  :data:`MAX_DELAY`, positive when the platform lags) and the normalised cross-correlation at
  that lag; the raw RMSE, correlation and delay (input against felt, no perception) beside;
- the false cues (:func:`false_cues`): the time the platform's motion is perceived (beyond
  the threshold) with the wrong sign against the vehicle's perceived one, and the time it is
  perceived while the vehicle's is not (felt at rest), separately;

then the platform's own roll, pitch and yaw rates (body rates of the commanded poses) against
the tilt-rate threshold, the perceived tilt rate (the platform's perceived roll and pitch rates
where the vehicle's are below their thresholds), the tilt channel's rate, the share of each
travel range used, the limit violations (poses breaking the limits model, legs beyond their
velocity or acceleration limits), and how far from neutral the platform is ``settle_time``
after the input came to rest. :data:`STRICT_TARGETS` holds what a believable cue must meet per
built-in scenario; :func:`judge` says which it meets. doc/cueing_evaluation.md defines every
measure. Nothing here imports ROS.
"""

from dataclasses import dataclass, field
import math
from typing import Dict, Mapping, Optional, Tuple

import numpy as np

from stewart_kinematics.cueing.limit_margins import leg_speed_violations, poses_allowed
from stewart_kinematics.cueing.perception import Perception, perception
from stewart_kinematics.cueing.settings import STANDARD_GRAVITY
from stewart_kinematics.cueing.vestibular import CanalModel, CANALS, OtolithModel, OTOLITHS
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, rotation_angle_between

#: The axes of the specific force.
AXES = ('x', 'y', 'z')
#: The axes of the angular velocity.
RATE_AXES = ('roll', 'pitch', 'yaw')
POSE_AXES = ('X', 'Y', 'Z', 'alpha', 'beta', 'gamma')
#: Default time after the input comes to rest at which the return to neutral is judged, s.
SETTLE_TIME = 10.0
#: Largest lag searched for the delay, either way, seconds (tilt coordination lags 0.7 to
#: 1.5 s: the window holds it).
MAX_DELAY = 2.0
#: An input within this of rest counts as rest (for :func:`rest_time`): m/s^2 and rad/s.
REST_TOLERANCE = 1e-3
#: Default tilt-rate threshold the platform's rates are judged against, rad/s (Groen and
#: Bles 2004: below about 3 deg/s a rotation is not perceived).
TILT_RATE_THRESHOLD = math.radians(3.0)


@dataclass(frozen=True)
class AxisMeasures:
    """
    The vehicle's motion against the platform's along one axis, perceived and raw.

    Units: m/s^2 for the axes of specific force, rad/s for those of rate.

    :param axis: ``x``, ``y``, ``z``, ``roll``, ``pitch`` or ``yaw``.
    :param rmse: root mean square of the platform's perceived minus the vehicle's perceived.
    :param correlation: Pearson correlation of the two perceived series, NaN when one is
        constant.
    :param delay: seconds by which the platform's perceived lags the vehicle's (the peak of
        their cross-correlation within :data:`MAX_DELAY`; negative: leads; plus or minus
        infinity when the peak lies at the end of the window; NaN when one is constant).
    :param delay_correlation: their normalised cross-correlation at that lag (1: the one is
        the other delayed and scaled), NaN likewise.
    :param raw_rmse: root mean square of the felt minus the input, no perception.
    :param raw_correlation: Pearson correlation of the felt and the input.
    :param raw_delay: the delay of the felt against the input, seconds.
    :param wrong_sign_time: seconds during which the platform's motion is perceived (beyond
        the threshold) with the opposite sign to the vehicle's, which is perceived too.
    :param felt_at_rest_time: seconds during which the platform's motion is perceived while
        the vehicle's is not (within the threshold).
    :param peak: largest magnitude of the platform's perceived motion.
    :param vehicle_peak: largest magnitude of the vehicle's perceived motion.
    :param threshold: the perception threshold used.
    """

    axis: str
    rmse: float
    correlation: float
    delay: float
    delay_correlation: float
    raw_rmse: float
    raw_correlation: float
    raw_delay: float
    wrong_sign_time: float
    felt_at_rest_time: float
    peak: float
    vehicle_peak: float
    threshold: float

    @property
    def false_cue_time(self) -> float:
        """Return the seconds of false cue: wrong sign and felt at rest, added up."""
        return self.wrong_sign_time + self.felt_at_rest_time


@dataclass(frozen=True)
class CueEvaluation:
    """
    Every measure of one replay.

    :param axes: measures of the specific force along x, y, z.
    :param rotations: measures of the angular velocity about roll, pitch, yaw.
    :param platform_rate_peak: largest body rate of the commanded poses about roll, pitch,
        yaw, rad/s.
    :param platform_rate_time_over: seconds each of those rates exceeds ``tilt_rate_max``.
    :param platform_tilt_rate_peak: the larger of the platform's roll and pitch rate peaks,
        rad/s.
    :param perceived_tilt_rate_peak: the largest perceived roll or pitch rate of the platform
        while the vehicle's own perceived rate about that axis is within its threshold, rad/s
        (the rotation a person feels that the vehicle did not make: tilt or washout).
    :param tilt_rate_max: the tilt-rate threshold judged against, rad/s.
    :param tilt_rate_peak: largest rate of the tilt channel alone as commanded (scaled),
        rad/s; ``0`` for a cueing without one.
    :param tilt_rate_violations: samples where the tilt channel exceeds ``tilt_rate_max``.
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
    :param vehicle: the vehicle's motion, raw and perceived.
    :param platform: the platform's motion at the head, raw and perceived.
    """

    axes: Tuple[AxisMeasures, ...]
    rotations: Tuple[AxisMeasures, ...]
    platform_rate_peak: Tuple[float, float, float]
    platform_rate_time_over: Tuple[float, float, float]
    platform_tilt_rate_peak: float
    perceived_tilt_rate_peak: float
    tilt_rate_max: float
    tilt_rate_peak: float
    tilt_rate_violations: int
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
    vehicle: Perception = field(repr=False, compare=False, default=None)
    platform: Perception = field(repr=False, compare=False, default=None)

    @property
    def limit_violations(self) -> int:
        """Return poses and leg samples beyond a limit, added up."""
        return (self.pose_violations + self.leg_velocity_violations
                + self.leg_acceleration_violations)

    def measures(self, axis: str) -> AxisMeasures:
        """Return the measures of ``axis`` (``x`` ... ``yaw``)."""
        for measures in self.axes + self.rotations:
            if measures.axis == axis:
                return measures
        raise ValueError(f'unknown axis {axis!r}; known: {", ".join(AXES + RATE_AXES)}')


#: A series whose spread about its mean is within this share of its size (plus this much in
#: its units) counts as constant: rounding (a turn by 180 deg leaves 1e-16 along the other
#: axes) is no motion to correlate.
ROUNDING_SPREAD = 1e-12


def _centred(series) -> Optional[np.ndarray]:
    """Return a series less its mean, or ``None`` when it is constant to rounding."""
    series = np.asarray(series, dtype=float)
    centred = series - series.mean()
    spread = math.sqrt(float(np.dot(centred, centred)) / max(centred.size, 1))
    size = float(np.max(np.abs(series))) if series.size else 0.0
    return centred if spread > ROUNDING_SPREAD * (1.0 + size) else None


def pearson(a, b) -> float:
    """Pearson correlation of two equally long series; NaN when one is constant."""
    a, b = _centred(a), _centred(b)
    if a is None or b is None:
        return math.nan
    return float(np.dot(a, b) / math.sqrt(float(np.dot(a, a)) * float(np.dot(b, b))))


def cross_correlation_peak(times, reference, delayed, max_delay: float = MAX_DELAY
                           ) -> Tuple[float, float]:
    """
    Return ``(delay, peak)``: the lag of the cross-correlation's peak and its normalised value.

    Both series are resampled on an even grid of the median step and their means removed;
    ``c[k] = sum a[n] b[n + k] / (|a| |b|)`` is searched for ``|k step| <= max_delay``, the peak
    refined by a parabola through its three samples. ``delay`` is in seconds, positive when
    ``delayed`` lags ``reference``; plus or minus infinity when the peak lies at the end of the
    window searched (no delay within ``max_delay`` explains them). Both NaN when either series
    is constant (to rounding: :data:`ROUNDING_SPREAD`).

    :param max_delay: largest lag searched either way, seconds.
    """
    times = np.asarray(times, dtype=float)
    step = float(np.median(np.diff(times)))
    grid = np.arange(times[0], times[-1] + 0.5 * step, step)
    a = _centred(np.interp(grid, times, reference))
    b = _centred(np.interp(grid, times, delayed))
    if a is None or b is None:
        return math.nan, math.nan
    norm = math.sqrt(float(np.dot(a, a)) * float(np.dot(b, b)))
    size = 1 << int(math.ceil(math.log2(2 * grid.size)))
    # c[k] = sum a[n] b[n + k]: a peak at k > 0 means b lags a.
    correlation = np.fft.irfft(np.conj(np.fft.rfft(a, size)) * np.fft.rfft(b, size),
                               size) / norm
    lags = min(int(max_delay / step), grid.size - 1)
    window = np.concatenate([correlation[-lags:], correlation[:lags + 1]]) if lags else \
        correlation[:1]
    peak = int(np.argmax(window))
    if peak in (0, window.size - 1) and lags:
        # The best lag is at the end of the window: the delay is beyond it (or undefined).
        return math.copysign(math.inf, peak - lags), float(window[peak])
    offset, value = 0.0, float(window[peak])
    if 0 < peak < window.size - 1:
        left, centre, right = window[peak - 1], window[peak], window[peak + 1]
        curvature = left - 2.0 * centre + right
        if curvature < 0.0:
            offset = 0.5 * (left - right) / curvature
            value = float(centre - 0.25 * (left - right) * offset)
    return (peak - lags + offset) * step, value


def delay(times, reference, delayed, max_delay: float = MAX_DELAY) -> float:
    """
    Seconds by which ``delayed`` lags ``reference``: the peak of their cross-correlation.

    :func:`cross_correlation_peak`'s delay: NaN when either is constant, plus or minus
    infinity when the peak lies at the end of the window searched.

    :param max_delay: largest lag searched either way, seconds.
    """
    return cross_correlation_peak(times, reference, delayed, max_delay)[0]


def sample_weights(times) -> np.ndarray:
    """Return the time each sample stands for: half the step on either side of it, seconds."""
    steps = np.diff(np.asarray(times, dtype=float))
    return 0.5 * (np.concatenate([[0.0], steps]) + np.concatenate([steps, [0.0]]))


def false_cues(times, vehicle, platform, threshold: float) -> Tuple[float, float]:
    """
    Return ``(wrong_sign_time, felt_at_rest_time)`` of one axis, seconds.

    A sample is a false cue where the platform's motion is perceived (``|platform| >
    threshold``) and either the vehicle's is perceived too with the opposite sign (wrong sign),
    or it is not (``|vehicle| <= threshold``: felt at rest). Each sample stands for half the
    step on either side of it.

    :param vehicle: the vehicle's perceived motion along the axis, (N,).
    :param platform: the platform's perceived motion along the axis, (N,).
    :param threshold: the perception threshold, in their unit.
    """
    vehicle = np.asarray(vehicle, dtype=float)
    platform = np.asarray(platform, dtype=float)
    felt = np.abs(platform) > threshold
    vehicle_felt = np.abs(vehicle) > threshold
    wrong = felt & vehicle_felt & (platform * vehicle < 0.0)
    at_rest = felt & ~vehicle_felt
    weights = sample_weights(times)
    return float(np.sum(weights[wrong])), float(np.sum(weights[at_rest]))


def time_over(times, values, limit: float) -> float:
    """Return the seconds during which ``|values|`` exceeds ``limit`` (per-sample weights)."""
    over = np.abs(np.asarray(values, dtype=float)) > limit * (1.0 + 1e-9)
    return float(np.sum(sample_weights(times)[over]))


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


def compare(vehicle: Perception, platform: Perception, max_delay: float = MAX_DELAY,
            thresholds=None) -> Tuple[Tuple[AxisMeasures, ...], Tuple[AxisMeasures, ...]]:
    """
    Compare two motions, perceived and raw, axis by axis: ``(force axes, rate axes)``.

    :param vehicle: the motion wanted (the input), from :func:`~.perception.perception`.
    :param platform: the motion given (felt at the head), on the same times.
    :param thresholds: six perception thresholds to use instead of the model's (m/s^2 then
        rad/s), or ``None``.
    """
    times = vehicle.times
    thresholds = vehicle.thresholds if thresholds is None else np.asarray(thresholds, float)
    wanted, given = vehicle.perceived, platform.perceived
    raw_wanted, raw_given = vehicle.raw, platform.raw
    measures = []
    for index, name in enumerate(AXES + RATE_AXES):
        a, b = wanted[:, index], given[:, index]
        raw_a, raw_b = raw_wanted[:, index], raw_given[:, index]
        lag, peak = cross_correlation_peak(times, a, b, max_delay)
        wrong, at_rest = false_cues(times, a, b, float(thresholds[index]))
        measures.append(AxisMeasures(
            axis=name, rmse=float(np.sqrt(np.mean((b - a) ** 2))), correlation=pearson(a, b),
            delay=lag, delay_correlation=peak,
            raw_rmse=float(np.sqrt(np.mean((raw_b - raw_a) ** 2))),
            raw_correlation=pearson(raw_a, raw_b),
            raw_delay=delay(times, raw_a, raw_b, max_delay), wrong_sign_time=wrong,
            felt_at_rest_time=at_rest, peak=float(np.max(np.abs(b))),
            vehicle_peak=float(np.max(np.abs(a))), threshold=float(thresholds[index])))
    return tuple(measures[:3]), tuple(measures[3:])


def perceived_tilt_rate_peak(vehicle: Perception, platform: Perception) -> float:
    """
    Return the platform's largest perceived roll or pitch rate where the vehicle's is not felt.

    Per axis (roll, pitch), the samples where the vehicle's perceived rate is within its
    threshold; the largest perceived rate of the platform among them, rad/s (0 when there is
    none). Where the vehicle does not roll or pitch, that is every sample: the rotation felt
    is the tilt's and the washout's.
    """
    peak = 0.0
    for axis in (0, 1):
        quiet = np.abs(vehicle.perceived_rate[:, axis]) <= vehicle.thresholds[3 + axis]
        if np.any(quiet):
            peak = max(peak, float(np.max(np.abs(platform.perceived_rate[quiet, axis]))))
    return peak


def evaluate(replay, geometry, actuator_limits, tilt_rate_max: float = TILT_RATE_THRESHOLD,
             *, rest: Optional[float] = None, travel=None,
             false_cue_threshold: Optional[float] = None,
             settle_time: float = SETTLE_TIME, max_delay: float = MAX_DELAY,
             gravity: float = STANDARD_GRAVITY, otoliths: OtolithModel = OTOLITHS,
             canals: CanalModel = CANALS) -> CueEvaluation:
    """
    Measure a replay.

    :param replay: a :class:`~.replay.CueReplay`.
    :param geometry: the platform whose limits to judge by.
    :param actuator_limits: the leg velocity and acceleration limits to judge by.
    :param tilt_rate_max: the tilt-rate threshold, rad/s.
    :param rest: when the input came to rest (seconds); default: found by :func:`rest_time`.
    :param travel: travel ranges from the home pose, ``[[negative, positive], ...]`` per pose
        axis, shape (6, 2), metres and radians (``TravelRanges.as_array()``), or ``None``.
    :param false_cue_threshold: the threshold of a false cue of specific force, m/s^2, on
        every axis, instead of the otoliths' (``None``).
    :param settle_time: seconds after rest at which the return to neutral is judged.
    :param max_delay: largest lag searched for the delays, seconds.
    :param otoliths: the otoliths' model.
    :param canals: the canals' model.
    """
    times = replay.times
    vehicle = perception(times, replay.specific_force, replay.angular_velocity, gravity,
                         otoliths, canals)
    platform = perception(times, replay.perceived.specific_force,
                          replay.perceived.angular_velocity, gravity, otoliths, canals)
    thresholds = vehicle.thresholds.copy()
    if false_cue_threshold is not None:
        thresholds[:3] = false_cue_threshold
    axes, rotations = compare(vehicle, platform, max_delay, thresholds)
    steps = np.diff(times)
    commanded_tilt = replay.tilt * replay.tilt_scale[:, None]
    tilt_rates = np.abs(np.diff(commanded_tilt, axis=0) / steps[:, None])
    tilt_rate_peak = float(np.max(tilt_rates, initial=0.0))
    rates = replay.perceived.angular_velocity
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
        axes=axes, rotations=rotations,
        platform_rate_peak=tuple(float(value) for value in np.max(np.abs(rates), axis=0)),
        platform_rate_time_over=tuple(time_over(times, rates[:, axis], tilt_rate_max)
                                      for axis in range(3)),
        platform_tilt_rate_peak=float(np.max(np.abs(rates[:, :2]))),
        perceived_tilt_rate_peak=perceived_tilt_rate_peak(vehicle, platform),
        tilt_rate_max=float(tilt_rate_max), tilt_rate_peak=tilt_rate_peak,
        tilt_rate_violations=int(np.count_nonzero(np.max(tilt_rates, axis=1)
                                                  > tilt_rate_max * (1.0 + 1e-9))),
        travel_used=travel_used,
        pose_violations=int(np.count_nonzero(~poses_allowed(geometry, replay.poses))),
        leg_velocity_violations=legs['velocity'],
        leg_acceleration_violations=legs['acceleration'],
        leg_velocity_peak=legs['velocity_peak'], leg_acceleration_peak=legs['acceleration_peak'],
        rest_time=rest, residual_position=residual_position, residual_angle=residual_angle,
        workspace_scale_min=float(np.min(replay.workspace_scale)),
        limited_share=float(np.mean(replay.acceleration_scale < 1.0)),
        warnings=dict(replay.warnings), vehicle=vehicle, platform=platform)


@dataclass(frozen=True)
class Targets:
    """
    What a believable cue of one scenario must meet (``stewart_cueing --strict``).

    :param correlation: axis -> the least perceived correlation, on the axes the scenario
        drives.
    :param delay: the largest perceived delay either way on those axes, seconds.
    :param wrong_sign_time: the most seconds of wrong-sign cue on any axis.
    :param felt_at_rest_time: the most seconds felt at rest on any axis.
    :param perceived_tilt_rate: the largest perceived tilt rate, rad/s; ``None``: the
        evaluation's ``tilt_rate_max``.
    :param residual_position: the largest distance from neutral ``settle_time`` after rest, m.
    :param residual_angle: the largest rotation from neutral then, radians.
    """

    correlation: Mapping[str, float] = field(default_factory=dict)
    delay: float = 0.5
    wrong_sign_time: float = 1.0
    felt_at_rest_time: float = 1.0
    perceived_tilt_rate: Optional[float] = None
    residual_position: float = 1e-3
    residual_angle: float = math.radians(0.1)


#: The targets of a believable cue per built-in scenario (doc/cueing_evaluation.md says why).
#: Every scenario also needs zero limit violations and the return to neutral.
STRICT_TARGETS: Dict[str, Targets] = {
    'acceleration_braking': Targets(correlation={'x': 0.6}),
    'slalom': Targets(correlation={'y': 0.6, 'yaw': 0.6}),
    'multi_sine': Targets(correlation={'x': 0.8, 'y': 0.8}, delay=0.05),
    'lap': Targets(correlation={'x': 0.6, 'y': 0.6, 'yaw': 0.6}, wrong_sign_time=2.0,
                   felt_at_rest_time=2.0),
    'brake_step': Targets(correlation={'x': 0.6}, wrong_sign_time=0.5, felt_at_rest_time=0.5),
    'lane_change': Targets(correlation={'y': 0.6}, wrong_sign_time=0.5, felt_at_rest_time=0.5),
    'coordinated_turn': Targets(correlation={'roll': 0.6, 'yaw': 0.6}, wrong_sign_time=0.5,
                                felt_at_rest_time=0.5),
    'mixed_drive': Targets(correlation={'x': 0.6, 'y': 0.6}, wrong_sign_time=3.0,
                           felt_at_rest_time=3.0),
    'bumpy_road': Targets(correlation={'z': 0.6, 'pitch': 0.6}),
}
#: The targets of an input that is no built-in scenario (a CSV file, a recording): the limits,
#: the return to neutral and the perceived tilt rate only.
GENERIC_TARGETS = Targets(wrong_sign_time=math.inf, felt_at_rest_time=math.inf)


def judge(name: str, evaluation: CueEvaluation, targets: Optional[Targets] = None):
    """
    Return ``[(target, met, value)]`` of one run: every target, met or not, with its figure.

    :param name: the scenario (its :data:`STRICT_TARGETS`), or any other input's name
        (:data:`GENERIC_TARGETS`).
    :param targets: targets to judge by instead.
    """
    if targets is None:
        targets = STRICT_TARGETS.get(name, GENERIC_TARGETS)
    tilt_limit = evaluation.tilt_rate_max if targets.perceived_tilt_rate is None else \
        targets.perceived_tilt_rate
    result = [
        ('zero limit violations', evaluation.limit_violations == 0,
         str(evaluation.limit_violations)),
        (f'perceived tilt rate <= {math.degrees(tilt_limit):.1f} deg/s',
         evaluation.perceived_tilt_rate_peak <= tilt_limit * (1.0 + 1e-9),
         f'{math.degrees(evaluation.perceived_tilt_rate_peak):.2f} deg/s peak (platform roll '
         f'{math.degrees(evaluation.platform_rate_peak[0]):.2f}, pitch '
         f'{math.degrees(evaluation.platform_rate_peak[1]):.2f} deg/s)')]
    if evaluation.residual_position is not None:
        result.append((
            f'within {targets.residual_position * 1e3:g} mm and '
            f'{math.degrees(targets.residual_angle):g} deg of neutral after rest',
            evaluation.residual_position <= targets.residual_position
            and evaluation.residual_angle <= targets.residual_angle,
            f'{evaluation.residual_position * 1e3:.3f} mm, '
            f'{math.degrees(evaluation.residual_angle):.4f} deg'))
    for axis, least in targets.correlation.items():
        measures = evaluation.measures(axis)
        result.append((f'perceived correlation >= {least:g} ({axis})',
                       measures.correlation >= least, _figure(measures.correlation)))
        result.append((f'perceived delay <= {targets.delay * 1e3:.0f} ms ({axis})',
                       abs(measures.delay) <= targets.delay,
                       f'{_figure(measures.delay * 1e3, ".0f")} ms'))
    if math.isfinite(targets.wrong_sign_time):
        worst = max(evaluation.axes + evaluation.rotations, key=lambda m: m.wrong_sign_time)
        result.append((f'wrong-sign cue <= {targets.wrong_sign_time:g} s on every axis',
                       worst.wrong_sign_time <= targets.wrong_sign_time,
                       f'{worst.wrong_sign_time:.2f} s ({worst.axis})'))
    if math.isfinite(targets.felt_at_rest_time):
        worst = max(evaluation.axes + evaluation.rotations, key=lambda m: m.felt_at_rest_time)
        result.append((f'felt at rest <= {targets.felt_at_rest_time:g} s on every axis',
                       worst.felt_at_rest_time <= targets.felt_at_rest_time,
                       f'{worst.felt_at_rest_time:.2f} s ({worst.axis})'))
    return result


def _figure(value, spec='.3f'):
    if math.isnan(value):
        return '-'
    return format(value, spec)
