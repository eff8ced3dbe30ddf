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
Platform trajectories: interpolated on SE(3), checked whole, timed to the actuators.

A :class:`PoseTrajectory` is a list of waypoint poses (position and orientation of the platform
frame in the base frame) with times, and optionally the platform's velocity at each waypoint.
Between two waypoints the position follows a cubic Hermite curve and the orientation a
cumulative cubic curve on SO(3) (Kim, Kim and Shin, SIGGRAPH 1995): three rotations about fixed
axes, so the orientation never passes through Euler angles and has no Euler interpolation
artefacts. Both pass through every waypoint with its velocity and angular velocity (given, or
estimated from the neighbouring waypoints, zero at both ends), so the motion is smooth in
position and orientation (continuous velocity and angular velocity).

A :class:`TimedTrajectory` is such a path played on a clock, as given or retimed.
:func:`check_trajectory` samples it densely in time and reports the first sample that breaks a
limit of the geometry (stroke, joint cones, singularity margin) or of the actuators (leg
velocity, leg acceleration), naming the time, the waypoint segment, the leg and the limit.
:func:`retime` finds the fastest timing of the path within every leg's velocity and
acceleration limits: time-optimal path parameterisation in leg space (TOPP-RA, the toppra
library). :func:`plan_motion` does all of it and returns a :class:`MotionPlan` that says
whether the trajectory is accepted and, if not, why.

Units: metres, radians, seconds; twists in the base frame. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics import findings, limits
from stewart_kinematics.actuators import ActuatorInterface, ActuatorLimits
from stewart_kinematics.findings import Finding, violation_details
from stewart_kinematics.kinematics import leg_vectors, twist_jacobian
from stewart_kinematics.limits import Violation
from stewart_kinematics.rotations import (
    euler_zyx_to_matrix,
    matrix_to_rotation_vector,
    quaternion_to_matrix,
    rotation_vector_to_matrix,
)

#: Codes of the refusals of a trajectory (:class:`~stewart_kinematics.findings.Finding`): a
#: pose limit broken, a leg velocity or acceleration limit broken, no timing found, and a
#: trajectory that is malformed (for a caller that converts messages).
OUT_OF_LIMITS = findings.OUT_OF_LIMITS
TOO_FAST = 'too_fast'
RETIMING_FAILED = 'retiming_failed'
INVALID_TRAJECTORY = 'invalid_trajectory'
#: The leg speed limits, as :class:`~stewart_kinematics.limits.Violation` names them.
SPEED_LIMITS = ('leg_velocity_max', 'leg_acceleration_max')
#: Default sampling rate of the whole-trajectory check, hertz.
DEFAULT_VALIDATION_RATE = 1000.0
#: Samples checked at once: bounds the memory of a long trajectory's check.
CHECK_CHUNK = 20000
#: Relative slack on the leg velocity and acceleration limits, for rounding only.
SPEED_LIMIT_SLACK = 1e-9
#: toppra's grid: at least this many gridpoints over the whole path ...
MIN_GRIDPOINTS = 400
#: ... and at least this many intervals per waypoint segment.
MIN_GRID_INTERVALS_PER_SEGMENT = 4
#: Gap, as a fraction of its segment, between a waypoint and the gridpoint just before it.
WAYPOINT_GRID_GAP = 1e-6
#: A retimed trajectory that exceeds a leg limit between toppra's gridpoints is stretched by
#: its excess times this (the samples then fall elsewhere: up to MAX_STRETCHES times).
STRETCH_MARGIN = 1.001
MAX_STRETCHES = 5


@dataclass(frozen=True)
class PoseSamples:
    """
    Poses and their time derivatives at some times (base frame, SI units).

    :param positions: platform origin, metres, shape (M, 3).
    :param rotations: platform-to-base rotations, shape (M, 3, 3).
    :param velocities: velocity of the platform origin, m/s, shape (M, 3).
    :param angular_velocities: rad/s, base frame, shape (M, 3).
    :param accelerations: m/s^2, shape (M, 3).
    :param angular_accelerations: rad/s^2, base frame, shape (M, 3).
    """

    positions: np.ndarray
    rotations: np.ndarray
    velocities: np.ndarray
    angular_velocities: np.ndarray
    accelerations: np.ndarray
    angular_accelerations: np.ndarray


@dataclass(frozen=True)
class LegStates:
    """
    Leg lengths and their time derivatives at some times.

    :param lengths: metres, shape (M, 6).
    :param velocities: m/s, shape (M, 6).
    :param accelerations: m/s^2, shape (M, 6).
    """

    lengths: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray


def leg_states(geometry, poses: PoseSamples) -> LegStates:
    """
    Leg lengths, velocities and accelerations of a moving platform.

    With ``r_i = R p_i``, the platform joint moves at ``V_i = v + w x r_i`` and accelerates at
    ``A_i = a + alpha x r_i + w x (w x r_i)``; the leg ``L_i`` (length ``l_i``, direction
    ``u_i``) then changes at ``u_i . V_i`` and accelerates at
    ``u_i . A_i + (|V_i|^2 - (u_i . V_i)^2) / l_i``.

    :param poses: the platform's poses and derivatives, M samples.
    """
    legs = leg_vectors(geometry, poses.positions, poses.rotations)
    arms = legs - poses.positions[:, None, :] + geometry.base_joints    # r_i = R p_i
    lengths = np.sqrt(_dot(legs, legs))
    directions = legs / lengths[..., None]
    omega = poses.angular_velocities[:, None, :]
    joint_velocities = poses.velocities[:, None, :] + _cross(omega, arms)
    joint_accelerations = (poses.accelerations[:, None, :]
                           + _cross(poses.angular_accelerations[:, None, :], arms)
                           + _cross(omega, _cross(omega, arms)))
    velocities = _dot(directions, joint_velocities)
    accelerations = (_dot(directions, joint_accelerations)
                     + (_dot(joint_velocities, joint_velocities) - velocities ** 2) / lengths)
    return LegStates(lengths, velocities, accelerations)


def _cross(a, b):
    """Cross products over the last axis, broadcast; twice as fast as numpy.cross here."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    product = np.empty(np.broadcast_shapes(a.shape, b.shape))
    product[..., 0] = a1 * b2 - a2 * b1
    product[..., 1] = a2 * b0 - a0 * b2
    product[..., 2] = a0 * b1 - a1 * b0
    return product


def _dot(a, b):
    """Dot products over the last axis (same shapes)."""
    return np.einsum('...i,...i->...', a, b)


class PoseTrajectory:
    """
    Waypoint poses with times: a smooth platform path (see the module's docstring).

    :param times: seconds, strictly increasing, shape (N,), N >= 2.
    :param positions: platform origin in the base frame, metres, shape (N, 3).
    :param rotations: platform-to-base rotation matrices, shape (N, 3, 3).
    :param velocities: velocity of the platform origin at each waypoint, m/s, shape (N, 3);
        ``None``: estimated from the neighbours (parabola through three waypoints), zero at the
        first and last waypoint.
    :param angular_velocities: angular velocity at each waypoint, base frame, rad/s, shape
        (N, 3); ``None``: estimated likewise.
    :raises ValueError: on a wrong shape, a non-finite value, a rotation that is not one,
        times that do not increase, or two waypoints that differ by half a turn or more (the
        way between them would be ambiguous).

    Attributes: ``times``, ``positions``, ``rotations``, ``velocities`` as given or
    estimated, and ``body_rates``, the angular velocity at each waypoint in the platform
    frame (rad/s), all read-only arrays.
    """

    def __init__(self, times, positions, rotations, velocities=None, angular_velocities=None):
        times = _array('times', times, (None,))
        count = times.shape[0]
        if count < 2:
            raise ValueError(f'a trajectory needs at least 2 waypoints, got {count}')
        steps = np.diff(times)
        if not np.all(steps > 0.0):
            index = int(np.argmin(steps > 0.0))
            raise ValueError(f'waypoint times must increase strictly, got {times[index]:g} s '
                             f'then {times[index + 1]:g} s (points {index} and {index + 1})')
        positions = _array('positions', positions, (count, 3))
        rotations = _array('rotations', rotations, (count, 3, 3))
        error = np.abs(rotations @ np.swapaxes(rotations, -1, -2) - np.eye(3)).max()
        if error > 1e-6 or np.any(np.linalg.det(rotations) < 0.0):
            raise ValueError('rotations must be rotation matrices (orthonormal, det +1)')
        # Segment k turns by turns[k] (a rotation vector in the frame of waypoint k).
        turns = matrix_to_rotation_vector(np.swapaxes(rotations[:-1], -1, -2) @ rotations[1:])
        angles = np.linalg.norm(turns, axis=-1)
        if np.any(angles > 0.99 * math.pi):
            index = int(np.argmax(angles))
            raise ValueError(
                f'points {index} and {index + 1} differ by a rotation of '
                f'{math.degrees(angles[index]):.1f} deg: a segment must turn by less than '
                '178 deg, or the way between them is ambiguous; add a waypoint between them')
        if velocities is None:
            velocities = _three_point_tangents(np.diff(positions, axis=0) / steps[:, None],
                                               steps)
        velocities = _array('velocities', velocities, (count, 3))
        if angular_velocities is None:
            body_rates = _three_point_tangents(turns / steps[:, None], steps)
        else:
            angular_velocities = _array('angular velocities', angular_velocities, (count, 3))
            body_rates = np.einsum('nji,nj->ni', rotations, angular_velocities)
        for array in (times, positions, rotations, velocities, body_rates):
            array.flags.writeable = False
        self.times, self.positions, self.rotations = times, positions, rotations
        self.velocities, self.body_rates = velocities, body_rates
        # Cumulative cubic on SO(3): R(s) = R_k exp(b1 w1) exp(b2 w2) exp(b3 w3), with
        # w1 = h w_k / 3 and w3 = h w_k+1 / 3 (body rates), w2 joining them.
        h = steps[:, None]
        self._w1 = body_rates[:-1] * h / 3.0
        self._w3 = body_rates[1:] * h / 3.0
        first = rotations[:-1] @ rotation_vector_to_matrix(self._w1)
        second = rotations[1:] @ rotation_vector_to_matrix(-self._w3)
        self._w2 = matrix_to_rotation_vector(np.swapaxes(first, -1, -2) @ second)

    @classmethod
    def from_poses(cls, times, poses, velocities=None, angular_velocities=None):
        """
        Build a trajectory from poses ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).

        Euler angles only describe the waypoints: the path between them is on SO(3).
        """
        poses = _array('poses', poses, (None, 6))
        return cls(times, poses[:, :3], euler_zyx_to_matrix(poses[:, 3:]), velocities,
                   angular_velocities)

    @classmethod
    def from_quaternions(cls, times, positions, quaternions, velocities=None,
                         angular_velocities=None):
        """Build a trajectory from quaternions ``(x, y, z, w)``, normalised first."""
        return cls(times, positions, quaternion_to_matrix(_array(
            'quaternions', quaternions, (None, 4))), velocities, angular_velocities)

    @classmethod
    def path(cls, geometry, positions, rotations):
        """
        Build a path without timing: nominal times by leg travel, for :func:`retime` to time.

        The nominal time of a segment is the largest change of a leg length over it, in
        metres, read as seconds (1 m/s on the leg that moves most): a parameterisation by leg
        travel, which keeps the curve between unevenly spaced waypoints from overshooting.

        :param positions: metres, shape (N, 3); ``rotations``: shape (N, 3, 3).
        :raises ValueError: if two consecutive waypoints have the same leg lengths.
        """
        positions = _array('positions', positions, (None, 3))
        rotations = _array('rotations', rotations, (positions.shape[0], 3, 3))
        lengths = np.linalg.norm(leg_vectors(geometry, positions, rotations), axis=-1)
        travel = np.abs(np.diff(lengths, axis=0)).max(axis=-1)
        if np.any(travel < 1e-12):
            index = int(np.argmin(travel))
            raise ValueError(f'points {index} and {index + 1} of the path are the same pose: '
                             'a path needs distinct consecutive waypoints')
        return cls(np.concatenate([[0.0], np.cumsum(travel)]), positions, rotations)

    @property
    def waypoint_count(self) -> int:
        """Return the number of waypoints N."""
        return self.times.shape[0]

    def segments(self, times) -> np.ndarray:
        """
        Find the segment of each time: k for ``times[k] <= t < times[k + 1]``, in [0, N - 2].

        :param times: seconds on this trajectory's clock, shape (M,).
        """
        index = np.searchsorted(self.times, times, side='right') - 1
        return np.clip(index, 0, self.waypoint_count - 2)

    def sample(self, times) -> PoseSamples:
        """
        Poses, velocities and accelerations at the given times (held outside the waypoints).

        :param times: seconds on this trajectory's clock, shape (M,).
        """
        times = np.atleast_1d(np.asarray(times, dtype=float))
        k = self.segments(times)
        h = (self.times[k + 1] - self.times[k])[:, None]
        s = np.clip((times - self.times[k]) / h[:, 0], 0.0, 1.0)[:, None]
        s2, s3 = s * s, s * s * s
        # Cubic Hermite basis and its derivatives in s.
        p0, p1 = self.positions[k], self.positions[k + 1]
        m0, m1 = self.velocities[k] * h, self.velocities[k + 1] * h
        positions = ((2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0
                     + (3 * s2 - 2 * s3) * p1 + (s3 - s2) * m1)
        velocities = ((6 * s2 - 6 * s) * (p0 - p1) + (3 * s2 - 4 * s + 1) * m0
                      + (3 * s2 - 2 * s) * m1) / h
        accelerations = ((12 * s - 6) * (p0 - p1) + (6 * s - 4) * m0 + (6 * s - 2) * m1) / h ** 2
        # Cumulative cubic Bernstein basis and its derivatives in s.
        beta = (1 - (1 - s) ** 3, 3 * s2 - 2 * s3, s3)
        beta_1 = (3 * (1 - s) ** 2, 6 * s - 6 * s2, 3 * s2)
        beta_2 = (-6 * (1 - s), 6 - 12 * s, 6 * s)
        w = (self._w1[k], self._w2[k], self._w3[k])
        exps = [rotation_vector_to_matrix(b * wj) for b, wj in zip(beta, w)]
        a1 = self.rotations[k]
        a2 = a1 @ exps[0]
        a3 = a2 @ exps[1]
        rotations = a3 @ exps[2]
        frames = (a1, a2, a3)
        columns = [np.einsum('mij,mj->mi', frame, wj) for frame, wj in zip(frames, w)]
        omega = sum(b1 * column for b1, column in zip(beta_1, columns))
        alpha = sum(b2 * column for b2, column in zip(beta_2, columns))
        alpha = alpha + beta_1[0] * beta_1[1] * np.einsum('mij,mj->mi', a2, _cross(w[0], w[1]))
        inner = beta_1[0] * np.einsum('mji,mj->mi', exps[1], w[0]) + beta_1[1] * w[1]
        alpha = alpha + beta_1[2] * np.einsum('mij,mj->mi', a3, _cross(inner, w[2]))
        # Outside [t_0, t_N-1] the platform rests at the first or last waypoint.
        outside = ((times < self.times[0]) | (times > self.times[-1]))[:, None]
        return PoseSamples(
            positions, rotations, np.where(outside, 0.0, velocities),
            np.where(outside, 0.0, omega / h), np.where(outside, 0.0, accelerations),
            np.where(outside, 0.0, alpha / h ** 2))


class TimedTrajectory:
    """
    A :class:`PoseTrajectory` played on a clock: path time ``tau(t)``, piecewise quadratic.

    Between gridpoints ``t_j`` the path time accelerates uniformly: ``tau = tau_j +
    rate_j (t - t_j) + rate'_j (t - t_j)^2 / 2`` (the form a time-optimal parameterisation
    takes). The clock starts at 0 at the first waypoint.

    :param path: the trajectory whose clock is ``tau``.
    :param grid_times: clock times of the gridpoints, seconds, increasing, from 0, shape (G,).
    :param grid_taus: path times of the gridpoints, increasing, from ``path.times[0]`` to
        ``path.times[-1]``, every waypoint time among them, shape (G,).
    :param rates: ``d tau / d t`` at the gridpoints, shape (G,).
    """

    def __init__(self, path: PoseTrajectory, grid_times, grid_taus, rates):
        self.path = path
        self.grid_times = np.asarray(grid_times, dtype=float)
        self.grid_taus = np.asarray(grid_taus, dtype=float)
        self.rates = np.asarray(rates, dtype=float)
        steps = np.diff(self.grid_taus)
        self._rate_changes = (self.rates[1:] ** 2 - self.rates[:-1] ** 2) / (2.0 * steps)
        self.waypoint_times = self.grid_times[np.searchsorted(self.grid_taus, path.times)]

    @classmethod
    def as_given(cls, path: PoseTrajectory, speed_scale: float = 1.0) -> 'TimedTrajectory':
        """Play the path on its own clock, slowed by ``1 / speed_scale``, started at 0."""
        if not 0.0 < speed_scale <= 1.0:
            raise ValueError(f'speed_scale must be in (0, 1], got {speed_scale!r}')
        return cls(path, (path.times - path.times[0]) / speed_scale, path.times,
                   np.full(path.waypoint_count, speed_scale))

    @property
    def duration(self) -> float:
        """Return the time from the first waypoint to the last, seconds."""
        return float(self.grid_times[-1])

    def stretched(self, factor: float) -> 'TimedTrajectory':
        """Play the motion ``factor`` times as long (velocities / factor, accelerations / f^2)."""
        return TimedTrajectory(self.path, self.grid_times * factor, self.grid_taus,
                               self.rates / factor)

    def path_times(self, times):
        """
        Path time, its rate and its acceleration at clock times (held outside [0, duration]).

        :param times: seconds, shape (M,).
        :returns: ``(tau, d tau / dt, d2 tau / dt2)``, each shape (M,).
        """
        times = np.atleast_1d(np.asarray(times, dtype=float))
        j = np.clip(np.searchsorted(self.grid_times, times, side='right') - 1,
                    0, self.grid_times.shape[0] - 2)
        elapsed = np.clip(times - self.grid_times[j], 0.0, None)
        change = self._rate_changes[j]
        taus = self.grid_taus[j] + self.rates[j] * elapsed + 0.5 * change * elapsed ** 2
        rates = self.rates[j] + change * elapsed
        # The last gridpoint exactly (rounding would miss it), and rest outside the clock.
        taus = np.where(times >= self.grid_times[-1], self.grid_taus[-1],
                        np.where(times < 0.0, self.grid_taus[0], taus))
        resting = (times > self.grid_times[-1]) | (times < 0.0)
        return taus, np.where(resting, 0.0, rates), np.where(resting, 0.0, change)

    def sample(self, times) -> PoseSamples:
        """Poses, velocities and accelerations at clock times, seconds, shape (M,)."""
        taus, rates, changes = self.path_times(times)
        on_path = self.path.sample(taus)
        r, c = rates[:, None], changes[:, None]
        return PoseSamples(
            on_path.positions, on_path.rotations, on_path.velocities * r,
            on_path.angular_velocities * r,
            on_path.accelerations * r ** 2 + on_path.velocities * c,
            on_path.angular_accelerations * r ** 2 + on_path.angular_velocities * c)

    def segments(self, times) -> np.ndarray:
        """Waypoint segment k (from point k to point k + 1) of each clock time, shape (M,)."""
        return self.path.segments(self.path_times(times)[0])

    def legs(self, geometry, times) -> LegStates:
        """Leg lengths, velocities and accelerations at clock times, seconds, shape (M,)."""
        return leg_states(geometry, self.sample(times))

    def sample_times(self, rate: float) -> np.ndarray:
        """
        Clock times every ``1 / rate`` seconds from 0, plus every waypoint time and the end.

        :param rate: hertz, positive.
        """
        if not rate > 0.0 or not math.isfinite(rate):
            raise ValueError(f'a sampling rate must be positive and finite (Hz), got {rate!r}')
        regular = np.arange(0.0, self.duration, 1.0 / rate)
        return np.unique(np.concatenate([regular, self.waypoint_times, [self.duration]]))


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
    the stroke, joint cones and singularity margin of ``geometry`` and the leg velocity and
    acceleration limits of ``actuator_limits`` (``None``: none). Vectorised over samples, in
    chunks of :data:`CHECK_CHUNK`.

    :returns: a :class:`TrajectoryCheck`; its ``reason`` names the first failing time, the
        waypoint segment (points k and k + 1), and each leg and limit broken there.
    """
    actuator_limits = actuator_limits or ActuatorLimits()
    times = trajectory.sample_times(validation_rate)
    peak_velocity = peak_acceleration = 0.0
    for start in range(0, times.shape[0], CHECK_CHUNK):
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
            segment = int(trajectory.segments(np.array([time]))[0])
            violations = tuple(
                Violation(name, leg + 1 if values.ndim == 2 else None,
                          float(values[first, leg] if values.ndim == 2 else values[first]),
                          allowed, unit)
                for name, mask, values, (allowed, unit) in broken
                for leg in np.flatnonzero(np.atleast_1d(mask[first])))
            reason = (f't = {time:.4f} s, between points {segment} and {segment + 1}: '
                      + '; '.join(str(violation) for violation in violations))
            return TrajectoryCheck(False, reason, time, (segment, segment + 1), violations,
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
        base_angles, platform_angles = limits.joint_angles(geometry, poses.positions,
                                                           poses.rotations)
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
    of :func:`stewart_kinematics.limits.jacobian_condition`) and ``U >= lambda_max(G)`` (the
    smaller of its Frobenius and row-sum norms), ``G - (U / bound^2) I`` positive definite
    (its LDL^T pivots, computed for every sample at once, all positive) gives
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
        conditions[doubtful] = limits.jacobian_condition(
            geometry, poses.positions[doubtful], poses.rotations[doubtful])
    return conditions


def load_retiming() -> None:
    """
    Import toppra (and scipy) now: the first import takes seconds, too long for a callback.

    A node that will retime calls this at start-up, so that its first trajectory is answered
    as fast as the next ones.
    """
    import toppra.algorithm  # noqa: F401
    import toppra.constraint  # noqa: F401


def retime(path: PoseTrajectory, geometry, actuator_limits: ActuatorLimits,
           speed_scale: float = 1.0) -> TimedTrajectory:
    """
    Find the fastest timing of a path that keeps every leg within its velocity and acceleration.

    Time-optimal path parameterisation (TOPP-RA, toppra) of the leg lengths along the path,
    starting and ending at rest, under ``actuator_limits`` scaled by ``speed_scale``
    (velocities by it, accelerations by its square: the optimal motion played ``1 /
    speed_scale`` times as long). toppra meets the limits at its gridpoints (every waypoint
    and at least :data:`MIN_GRID_INTERVALS_PER_SEGMENT` per segment); :func:`plan_motion`
    then checks every sample and stretches the timing where the motion between gridpoints
    exceeds a limit.

    :raises ValueError: if neither a velocity nor an acceleration limit is set (the fastest
        timing would take no time), or toppra finds no timing (the reason says which).
    """
    import toppra  # toppra pulls scipy: imported only by the motion that needs it.
    import toppra.algorithm
    import toppra.constraint

    scaled = actuator_limits.scaled(speed_scale)
    if not scaled.limits_speed:
        raise ValueError('retiming needs leg_velocity_max or leg_acceleration_max: without '
                         'them the fastest timing takes no time')
    toppra.setup_logging('CRITICAL')
    leg_path = _leg_path(path, geometry, toppra.interpolator.AbstractGeometricPath)
    constraints = []
    if math.isfinite(scaled.velocity_max):
        constraints.append(toppra.constraint.JointVelocityConstraint(
            np.full((6, 2), scaled.velocity_max) * [-1.0, 1.0]))
    if math.isfinite(scaled.acceleration_max):
        constraints.append(toppra.constraint.JointAccelerationConstraint(
            np.full(6, scaled.acceleration_max)))
    gridpoints = _gridpoints(path.times)
    algorithm = toppra.algorithm.TOPPRA(constraints, leg_path, gridpoints=gridpoints,
                                        solver_wrapper='seidel')
    algorithm.compute_parameterization(0.0, 0.0)
    data = algorithm.problem_data
    rates = None if data.sd_vec is None else np.asarray(data.sd_vec, dtype=float)
    if rates is None or rates.shape != gridpoints.shape or not np.all(np.isfinite(rates)):
        raise ValueError(f'toppra found no timing within the leg limits ({data.return_code}): '
                         'the path may pass through a singularity')
    rates = np.maximum(rates, 0.0)
    # t_j+1 - t_j = 2 (tau_j+1 - tau_j) / (rate_j + rate_j+1) under uniform path acceleration.
    durations = 2.0 * np.diff(gridpoints) / (rates[:-1] + rates[1:])
    return TimedTrajectory(path, np.concatenate([[0.0], np.cumsum(durations)]), gridpoints,
                           rates)


def _gridpoints(waypoint_times):
    """
    Place toppra's gridpoints: segments split into equal intervals, and waypoints on both sides.

    Every waypoint time is a gridpoint, and so is a point just before each of them. The path
    is C1: its leg accelerations along the path jump at the waypoints. toppra sees
    a gridpoint's path from its right, so the point just before a waypoint makes it meet the
    limits on the left side too.
    """
    segments = waypoint_times.shape[0] - 1
    per_segment = max(MIN_GRID_INTERVALS_PER_SEGMENT, math.ceil(MIN_GRIDPOINTS / segments))
    fractions = np.concatenate([np.arange(per_segment) / per_segment,
                                [1.0 - WAYPOINT_GRID_GAP]])
    inner = waypoint_times[:-1, None] + np.diff(waypoint_times)[:, None] * fractions
    return np.concatenate([inner.ravel(), waypoint_times[-1:]])


def _leg_path(path, geometry, base):
    """Wrap the leg lengths along a path as a toppra geometric path (a subclass of ``base``)."""
    class LegPath(base):
        def __call__(self, path_positions, order=0):
            scalar = np.ndim(path_positions) == 0
            states = leg_states(geometry, path.sample(np.atleast_1d(path_positions)))
            values = (states.lengths, states.velocities, states.accelerations)[order]
            return values[0] if scalar else values

        @property
        def dof(self):
            return 6

        @property
        def path_interval(self):
            return np.array([path.times[0], path.times[-1]])

    return LegPath()


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
        (only leg velocity or acceleration broken) or :data:`RETIMING_FAILED`; its details
        give the time, the segment and every violated limit.
        """
        if self.accepted:
            return None
        check = self.check
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


@dataclass(frozen=True)
class LegTrajectory:
    """
    A timed trajectory of the six actuators, as a JointTrajectory carries it.

    :param joint_names: leg 1..6.
    :param times: time from start of each point, seconds, shape (M,).
    :param positions: actuator positions (leg length minus offset), metres, shape (M, 6).
    :param velocities: m/s, shape (M, 6).
    :param accelerations: m/s^2, shape (M, 6).
    """

    joint_names: Tuple[str, ...]
    times: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray


def leg_trajectory(trajectory: TimedTrajectory, geometry, actuators: ActuatorInterface,
                   rate: float) -> LegTrajectory:
    """
    Sample a timed trajectory for an actuator interface: every ``1 / rate`` s and at waypoints.

    :param rate: points per second, hertz; every waypoint and the end are points too.
    """
    times = trajectory.sample_times(rate)
    legs = trajectory.legs(geometry, times)
    return LegTrajectory(actuators.joint_names, times, actuators.positions(legs.lengths),
                         legs.velocities, legs.accelerations)


def _three_point_tangents(slopes, steps):
    """
    Estimate derivatives at the waypoints: of the parabola through each three, zero at the ends.

    :param slopes: each segment's mean rate, shape (N - 1, D); ``steps``: durations, (N - 1,).
    """
    tangents = np.zeros((slopes.shape[0] + 1, slopes.shape[1]))
    before, after = steps[:-1, None], steps[1:, None]
    tangents[1:-1] = (after * slopes[:-1] + before * slopes[1:]) / (before + after)
    return tangents


def _array(name, value, shape):
    """Convert to a finite float array of ``shape`` (``None`` entries: any length)."""
    array = np.array(value, dtype=float)
    wrong = any(expected is not None and size != expected
                for size, expected in zip(array.shape, shape))
    if array.ndim != len(shape) or wrong:
        shown = tuple('N' if size is None else size for size in shape)
        raise ValueError(f'{name} must have shape {shown}, got {array.shape}')
    if not np.all(np.isfinite(array)):
        raise ValueError(f'{name} must be finite')
    return array
