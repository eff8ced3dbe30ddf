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
Platform trajectories: waypoint poses interpolated smoothly on SE(3), and played on a clock.

A :class:`PoseTrajectory` is a list of waypoint poses (position and orientation of the platform
frame in the base frame) with times, and optionally the platform's velocity at each waypoint.
Between two waypoints the position follows a cubic Hermite curve and the orientation a
cumulative cubic curve on SO(3) (Kim, Kim and Shin, SIGGRAPH 1995): three rotations about fixed
axes, so the orientation never passes through Euler angles and has no Euler interpolation
artefacts. Both pass through every waypoint with its velocity and angular velocity (given, or
estimated from the neighbouring waypoints, zero at both ends), so the motion is smooth in
position and orientation (continuous velocity and angular velocity).

A :class:`TimedTrajectory` is such a path played on a clock, as given or retimed
(:mod:`stewart_kinematics.motion.retiming`).

Units: metres, radians, seconds; twists in the base frame. Nothing here imports ROS.
"""

import math

import numpy as np

from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.kinematics import leg_vectors
from stewart_kinematics.model.rotations import (
    euler_zyx_to_matrix,
    matrix_to_rotation_vector,
    quaternion_to_matrix,
    rotation_vector_to_matrix,
)
from stewart_kinematics.model.velocities import _cross, leg_states, LegStates, PoseSamples


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
        if not isinstance(path, PoseTrajectory):
            raise ValueError(f'path must be a PoseTrajectory, got {type(path).__name__}')
        self.path = path
        self.grid_times = _array('grid_times', grid_times, (None,))
        count = self.grid_times.shape[0]
        self.grid_taus = _array('grid_taus', grid_taus, (count,))
        self.rates = _array('rates', rates, (count,))
        if count < 2 or self.grid_times[0] != 0.0 or not np.all(np.diff(self.grid_times) > 0.0):
            raise ValueError('grid_times must increase strictly from 0, at least 2 of them')
        if not (np.all(np.diff(self.grid_taus) > 0.0) and self.grid_taus[0] == path.times[0]
                and self.grid_taus[-1] == path.times[-1]
                and np.all(np.isin(path.times, self.grid_taus))):
            raise ValueError('grid_taus must increase strictly from the first waypoint time to '
                             'the last, with every waypoint time among them')
        if np.any(self.rates < 0.0):
            raise ValueError('rates (d tau / dt) must not be negative')
        steps = np.diff(self.grid_taus)
        self._rate_changes = (self.rates[1:] ** 2 - self.rates[:-1] ** 2) / (2.0 * steps)
        self.waypoint_times = self.grid_times[np.searchsorted(self.grid_taus, path.times)]

    @classmethod
    def as_given(cls, path: PoseTrajectory, speed_scale: float = 1.0) -> 'TimedTrajectory':
        """Play the path on its own clock, slowed by ``1 / speed_scale``, started at 0."""
        if not (_is_number(speed_scale) and 0.0 < speed_scale <= 1.0):
            raise ValueError(f'speed_scale must be in (0, 1], got {speed_scale!r}')
        return cls(path, (path.times - path.times[0]) / speed_scale, path.times,
                   np.full(path.waypoint_count, speed_scale))

    @property
    def duration(self) -> float:
        """Return the time from the first waypoint to the last, seconds."""
        return float(self.grid_times[-1])

    def stretched(self, factor: float) -> 'TimedTrajectory':
        """Play the motion ``factor`` times as long (velocities / factor, accelerations / f^2)."""
        if not (_is_number(factor) and 0.0 < factor < math.inf):
            raise ValueError(f'factor must be positive and finite, got {factor!r}')
        return TimedTrajectory(self.path, self.grid_times * factor, self.grid_taus,
                               self.rates / factor)

    def path_times(self, times):
        """
        Path time, its rate and its acceleration at clock times (held outside [0, duration]).

        :param times: seconds, shape (M,).
        :returns: ``(tau, d tau / dt, d2 tau / dt2)``, each shape (M,).
        """
        times = np.atleast_1d(as_float_array(times, 'times'))
        if times.ndim != 1 or not np.all(np.isfinite(times)):
            raise ValueError(f'times must be finite seconds, shape (M,), got {preview(times)}')
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
        if not (_is_number(rate) and 0.0 < rate < math.inf):
            raise ValueError(f'a sampling rate must be positive and finite (Hz), got {rate!r}')
        regular = np.arange(0.0, self.duration, 1.0 / rate)
        return np.unique(np.concatenate([regular, self.waypoint_times, [self.duration]]))


def _three_point_tangents(slopes, steps):
    """
    Estimate derivatives at the waypoints: of the parabola through each three, zero at the ends.

    :param slopes: each segment's mean rate, shape (N - 1, D); ``steps``: durations, (N - 1,).
    """
    tangents = np.zeros((slopes.shape[0] + 1, slopes.shape[1]))
    before, after = steps[:-1, None], steps[1:, None]
    tangents[1:-1] = (after * slopes[:-1] + before * slopes[1:]) / (before + after)
    return tangents


def _is_number(value) -> bool:
    """Whether ``value`` is a real number (a bool is not)."""
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, (bool, np.bool_))


def _array(name, value, shape):
    """Convert to a finite float array of ``shape`` (``None`` entries: any length)."""
    array = np.array(as_float_array(value, name))
    wrong = any(expected is not None and size != expected
                for size, expected in zip(array.shape, shape))
    if array.ndim != len(shape) or wrong:
        shown = tuple('N' if size is None else size for size in shape)
        raise ValueError(f'{name} must have shape {shown}, got {array.shape}')
    if not np.all(np.isfinite(array)):
        raise ValueError(f'{name} must be finite')
    return array
