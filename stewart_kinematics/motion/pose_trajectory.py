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
frame in the base frame) with times, and optionally the platform's velocity (and acceleration)
at each waypoint. Between two waypoints the position follows a Hermite curve and the
orientation a cumulative Bernstein curve on SO(3) (Kim, Kim and Shin, SIGGRAPH 1995): rotations
about fixed axes, so the orientation never passes through Euler angles and has no Euler
interpolation artefacts. Both pass through every waypoint with its velocity and angular
velocity (given, or estimated from the neighbouring waypoints); the motion is C1 (cubic
curves). When accelerations are given too, both curves are quintic and also pass through
them: the motion is C2, as a planner that gave the accelerations meant it.

Two kinds of trajectory are built here:

- **timed** (:class:`PoseTrajectory` itself): the times are the user's; estimated velocities
  are zero at the first and last waypoint and at a waypoint repeated in place (a dwell: the
  platform rests there for the time given).
- **a path** (:meth:`PoseTrajectory.path`, or :meth:`PoseTrajectory.as_path` of a timed one):
  the geometric curve through the waypoint poses and nothing else, for retiming. Repeated
  waypoints are merged; the curve's parameter is the leg travel (the change of the six leg
  lengths between two waypoints, cumulated: the chord length in leg space), and the
  velocities and accelerations are estimated in that parameter from the polynomial through
  five waypoints around each, at the ends too (a C2 curve). So the same poses give the same
  curve whatever times, velocities or accelerations came with them, and a smooth curve sampled
  at any density gives nearly the same curve.

A :class:`TimedTrajectory` is a path played on a clock, as given or retimed
(:mod:`stewart_kinematics.motion.retiming`).

Units: metres, radians, seconds; velocities in the base frame. Nothing here imports ROS.
"""

import math

import numpy as np

from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.inverse import leg_vectors
from stewart_kinematics.model.rotations import (
    euler_zyx_to_matrix,
    matrix_to_quaternion,
    matrix_to_rotation_vector,
    quaternion_to_matrix,
    rotation_vector_to_matrix,
)
from stewart_kinematics.model.velocities import leg_states, LegStates, PoseSamples

#: Most waypoints a trajectory may have.
MAX_WAYPOINTS = 100_000
#: Latest time a waypoint may have, seconds from the start (about 11.6 days).
MAX_TIME = 1e6
#: Smallest step between two waypoint times, seconds (the resolution of a ROS Duration).
MIN_TIME_STEP = 1e-9
#: Largest coordinate of a waypoint's position (m), velocity (m/s, rad/s) or acceleration
#: (m/s^2, rad/s^2): beyond, it is no motion of a platform (and squares would overflow).
MAX_MAGNITUDE = 1e3
#: Two waypoints closer than this (metres, and radians) are the same pose.
SAME_POSE_TOLERANCE = 1e-9
#: On a path, a waypoint less than this leg travel (metres) from the last one kept is merged.
MIN_PATH_STEP = 1e-7
#: Between two waypoints of a path, the platform moving (metres, at its joints) more than this
#: many times what the legs move is a crossing of a singularity (or of assembly modes).
SINGULAR_RATIO = 1e4
#: Waypoints around each one whose polynomial gives its velocity and acceleration on a path.
PATH_STENCIL = 5
#: Most samples in a piece of a timed trajectory (between two waypoints, or two gridpoints of
#: a retiming), whatever its duration: see :meth:`TimedTrajectory.sample_times`.
MAX_PIECE_SAMPLES = 256


def waypoint_times(times) -> np.ndarray:
    """
    Check waypoint times: as many as a trajectory may have, finite, from 0 to MAX_TIME, increasing.

    :param times: seconds from the start, shape (N,).
    :returns: the times as a float array.
    :raises ValueError: naming the first point whose time is wrong, and why.
    """
    times = np.array(as_float_array(times, 'waypoint times'))
    if times.ndim != 1:
        raise ValueError(f'waypoint times must be a list, got shape {times.shape}')
    count = times.shape[0]
    if count < 2:
        raise ValueError(f'a trajectory needs at least 2 waypoints, got {count}' + (
            ': one pose is a command, not a trajectory' if count == 1 else ''))
    if count > MAX_WAYPOINTS:
        raise ValueError(f'a trajectory may have at most {MAX_WAYPOINTS:,} waypoints, got '
                         f'{count:,}: send it in parts')
    bad = ~np.isfinite(times) | (times < 0.0) | (times > MAX_TIME)
    if bad.any():
        index = int(np.argmax(bad))
        raise ValueError(f'point {index} has time {float(times[index])!r} s: waypoint times '
                         f'must be finite, from 0 to {MAX_TIME:g} s (about 11.6 days)')
    steps = np.diff(times)
    if not np.all(steps >= MIN_TIME_STEP):
        index = int(np.argmin(steps >= MIN_TIME_STEP))
        raise ValueError(f'waypoint times must increase strictly, by {MIN_TIME_STEP:g} s at '
                         f'least, got {times[index]:.9g} s then {times[index + 1]:.9g} s '
                         f'(points {index} and {index + 1})')
    return times


class PoseTrajectory:
    """
    Waypoint poses with times: a smooth platform path (see the module's docstring).

    :param times: seconds from the start, strictly increasing, from 0 to :data:`MAX_TIME`,
        shape (N,), 2 <= N <= :data:`MAX_WAYPOINTS` (see :func:`waypoint_times`).
    :param positions: platform origin in the base frame, metres, shape (N, 3).
    :param rotations: platform-to-base rotation matrices, shape (N, 3, 3).
    :param velocities: velocity of the platform origin at each waypoint, m/s, shape (N, 3);
        ``None``: estimated from the neighbours (parabola through three waypoints), zero at the
        first and last waypoint and at both ends of a segment that does not move (a dwell).
    :param angular_velocities: angular velocity at each waypoint, base frame, rad/s, shape
        (N, 3); ``None``: estimated likewise.
    :param accelerations: acceleration of the platform origin at each waypoint, m/s^2, shape
        (N, 3), with ``angular_accelerations`` (rad/s^2, base frame): both or neither, and only
        with the velocities. Given, the curves are quintic (C2) instead of cubic.
    :param path_estimates: estimate the velocities and accelerations at every waypoint, the
        ends included, from the polynomial through the :data:`PATH_STENCIL` waypoints around
        it (fourth order), so that the curve is C2 and converges fast to the curve the
        waypoints were sampled from: what a path without timing wants (see :meth:`path`).
    :param point_indices: the index of each waypoint in the input it comes from (a path
        merges repeated waypoints), for the reasons of a refusal; ``None``: 0 .. N - 1.
    :raises ValueError: on a wrong shape, a non-finite value, a rotation that is not one,
        times refused by :func:`waypoint_times`, or two waypoints that differ by half a turn or
        more (the way between them would be ambiguous).

    Attributes: ``times``, ``positions``, ``rotations``, ``velocities`` as given or
    estimated, ``body_rates``, the angular velocity at each waypoint in the platform
    frame (rad/s), all read-only arrays; ``degree`` (3 or 5) and ``is_path`` (built by
    :meth:`path`).
    """

    is_path = False

    def __init__(self, times, positions, rotations, velocities=None, angular_velocities=None,
                 accelerations=None, angular_accelerations=None, *, path_estimates=False,
                 point_indices=None):
        times = waypoint_times(times)
        count = times.shape[0]
        steps = np.diff(times)
        positions = _array('positions', positions, (count, 3), 'm')
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
        if (velocities is None) != (angular_velocities is None):
            raise ValueError('give velocities and angular velocities together, or neither')
        if (accelerations is None) != (angular_accelerations is None):
            raise ValueError('give accelerations and angular accelerations together, or neither')
        if accelerations is not None and velocities is None:
            raise ValueError('accelerations need the velocities too: give both, or neither')
        body_accelerations = None
        if velocities is None:
            resting = (np.linalg.norm(np.diff(positions, axis=0), axis=-1)
                       <= SAME_POSE_TOLERANCE) & (angles <= SAME_POSE_TOLERANCE)
            if path_estimates:
                velocities, accelerations, body_rates, body_accelerations = _stencil_derivatives(
                    times, positions, rotations, PATH_STENCIL)
            else:
                velocities = _three_point_tangents(
                    np.diff(positions, axis=0) / steps[:, None], steps, resting)
                body_rates = _three_point_tangents(turns / steps[:, None], steps, resting)
        else:
            velocities = _array('velocities', velocities, (count, 3), 'm/s')
            angular_velocities = _array('angular velocities', angular_velocities, (count, 3),
                                        'rad/s')
            body_rates = np.einsum('nji,nj->ni', rotations, angular_velocities)
        self.degree = 3
        if body_accelerations is not None:
            self.degree = 5
        elif accelerations is not None:
            self.degree = 5
            accelerations = _array('accelerations', accelerations, (count, 3), 'm/s^2')
            body_accelerations = np.einsum('nji,nj->ni', rotations, _array(
                'angular accelerations', angular_accelerations, (count, 3), 'rad/s^2'))
        for array in (times, positions, rotations, velocities, body_rates):
            array.flags.writeable = False
        self.times, self.positions, self.rotations = times, positions, rotations
        self.velocities, self.body_rates = velocities, body_rates
        self.accelerations = accelerations
        self.point_indices = (np.arange(count) if point_indices is None
                              else np.asarray(point_indices, dtype=int))
        self._coefficients = _position_coefficients(positions, velocities, accelerations, steps)
        self._increments = _rotation_increments(rotations, body_rates, body_accelerations,
                                                steps, self.degree)
        self._start_quaternions = matrix_to_quaternion(rotations[:-1])

    @classmethod
    def from_poses(cls, times, poses, velocities=None, angular_velocities=None, **kwargs):
        """
        Build a trajectory from poses ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).

        Euler angles only describe the waypoints: the path between them is on SO(3).
        """
        poses = _array('poses', poses, (None, 6))
        return cls(times, poses[:, :3], euler_zyx_to_matrix(poses[:, 3:]), velocities,
                   angular_velocities, **kwargs)

    @classmethod
    def from_quaternions(cls, times, positions, quaternions, velocities=None,
                         angular_velocities=None, **kwargs):
        """Build a trajectory from quaternions ``(x, y, z, w)``, normalised first."""
        return cls(times, positions, quaternion_to_matrix(_array(
            'quaternions', quaternions, (None, 4))), velocities, angular_velocities, **kwargs)

    @classmethod
    def path(cls, geometry, positions, rotations, point_indices=None) -> 'PoseTrajectory':
        """
        Build a path: the curve through waypoint poses, without timing, for :func:`retime`.

        Consecutive waypoints that are the same pose (to :data:`SAME_POSE_TOLERANCE`) are
        merged into one, and so is a waypoint less than :data:`MIN_PATH_STEP` of leg travel
        from the last one kept (the curve passes that close to it anyway; closer waypoints
        would only add rounding noise to the curve's second derivative). The curve's
        parameter is the leg travel: from one waypoint to the next it grows by the change of
        the leg lengths (the Euclidean norm of the six changes, in metres: the chord length in
        leg space), which keeps the curve between unevenly spaced waypoints from overshooting
        and makes it the same whatever timing the waypoints came with. The velocities and
        accelerations are estimated in that parameter, from the polynomial through the
        :data:`PATH_STENCIL` waypoints around each, so the curve is C2, and a denser sampling
        of a smooth curve gives nearly the same curve.

        :param positions: metres, shape (N, 3); ``rotations``: shape (N, 3, 3).
        :param point_indices: as in the constructor; ``None``: 0 .. N - 1.
        :raises ValueError: if fewer than 2 different poses are left, or for more than
            :data:`MAX_WAYPOINTS`.
        :raises SingularPathError: if the platform moves between two waypoints while the legs
            hardly do (:data:`SINGULAR_RATIO`): the way between them crosses a singularity.
        """
        positions = _array('positions', positions, (None, 3), 'm')
        count = positions.shape[0]
        if count < 2 or count > MAX_WAYPOINTS:
            waypoint_times(np.arange(count, dtype=float))   # raises, saying why
        rotations = _array('rotations', rotations, (count, 3, 3))
        indices = np.arange(count) if point_indices is None else np.asarray(point_indices)
        moves = (np.linalg.norm(np.diff(positions, axis=0), axis=-1) > SAME_POSE_TOLERANCE) | (
            _angles_between(rotations[:-1], rotations[1:]) > SAME_POSE_TOLERANCE)
        kept = np.concatenate([[True], moves])
        positions, rotations, indices = positions[kept], rotations[kept], indices[kept]
        lengths = np.linalg.norm(leg_vectors(geometry, positions, rotations), axis=-1)
        travel = np.linalg.norm(np.diff(lengths, axis=0), axis=-1)
        motion = (np.linalg.norm(np.diff(positions, axis=0), axis=-1) + geometry.platform_radius
                  * _angles_between(rotations[:-1], rotations[1:]))
        singular = travel * SINGULAR_RATIO < motion
        if singular.any():
            index = int(np.argmax(singular))
            raise SingularPathError(
                f'between points {indices[index]} and {indices[index + 1]} the platform moves '
                f'{motion[index]:.3g} m (rotation at its joints included) while the legs move '
                f'{travel[index]:.3g} m: the way between them crosses a singularity, or goes '
                'to another assembly mode', int(indices[index]))
        kept = _spaced(travel, MIN_PATH_STEP)
        positions, rotations = positions[kept], rotations[kept]
        indices, lengths = indices[kept], lengths[kept]
        if positions.shape[0] < 2:
            raise ValueError(
                f'a path needs at least 2 different poses, got {positions.shape[0]}'
                + (f' (from {count} waypoints, repeats merged)' if count > 1 else ''))
        travel = np.linalg.norm(np.diff(lengths, axis=0), axis=-1)
        trajectory = cls(np.concatenate([[0.0], np.cumsum(travel)]), positions, rotations,
                         path_estimates=True, point_indices=indices)
        trajectory.is_path = True
        return trajectory

    def as_path(self, geometry) -> 'PoseTrajectory':
        """
        Return the path through this trajectory's waypoint poses, without its timing.

        Only the poses count: the times, velocities and accelerations given describe a timing,
        which retiming replaces (see :meth:`path`). A path is returned as it is.
        """
        if self.is_path:
            return self
        return PoseTrajectory.path(geometry, self.positions, self.rotations, self.point_indices)

    @property
    def waypoint_count(self) -> int:
        """Return the number of waypoints N."""
        return self.times.shape[0]

    def points(self, segment: int):
        """Return the input's indices of the waypoints around ``segment`` (k and k + 1)."""
        return int(self.point_indices[segment]), int(self.point_indices[segment + 1])

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
        :raises ValueError: for times that are not finite numbers of shape (M,) (or one time).
        """
        times = np.atleast_1d(as_float_array(times, 'times'))
        if times.ndim != 1 or not np.all(np.isfinite(times)):
            raise ValueError(f'times must be finite seconds, shape (M,), got {preview(times)}')
        k = self.segments(times)
        h = self.times[k + 1] - self.times[k]
        s = np.clip((times - self.times[k]) / h, 0.0, 1.0)
        h = h[:, None]
        coefficients = self._coefficients[k]
        positions, velocities, accelerations = _polynomial(coefficients, s[:, None])
        omega, alpha, rotations = _cumulative_rotation(self._start_quaternions[k],
                                                       self._increments[k], s)
        # Outside [t_0, t_N-1] the platform rests at the first or last waypoint.
        outside = ((times < self.times[0]) | (times > self.times[-1]))[:, None]
        return PoseSamples(
            positions, rotations, np.where(outside, 0.0, velocities / h),
            np.where(outside, 0.0, omega / h), np.where(outside, 0.0, accelerations / h ** 2),
            np.where(outside, 0.0, alpha / h ** 2))


class SingularPathError(ValueError):
    """
    A path whose leg lengths do not change between two different poses (a singularity).

    :param point: the input's index of the waypoint the crossing starts from.
    """

    def __init__(self, message, point):
        super().__init__(message)
        self.point = point


class TimedTrajectory:
    """
    A :class:`PoseTrajectory` played on a clock: path time ``tau(t)``, piecewise quadratic.

    Between gridpoints ``t_j`` the path time accelerates uniformly: ``tau = tau_j +
    rate_j (t - t_j) + rate'_j (t - t_j)^2 / 2`` (the form a time-optimal parameterisation
    takes). The clock starts at 0 at the first waypoint.

    :param path: the trajectory whose clock is ``tau``.
    :param grid_times: clock times of the gridpoints, seconds, increasing, from 0, shape (G,).
    :param grid_taus: path times of the gridpoints, increasing, from ``path.times[0]`` to
        ``path.times[-1]``, shape (G,).
    :param rates: ``d tau / d t`` at the gridpoints, shape (G,).
    :param partial: the grid may start after the first waypoint and end before the last (a
        part of the path: a braking, :mod:`~stewart_kinematics.motion.path_braking`); the
        clock still starts at 0 at the grid's first path time.

    Attributes: ``waypoint_times``, the clock time of each waypoint, and ``breakpoints``, the
    clock times where the motion's acceleration may jump (waypoints and gridpoints), which
    split the trajectory into the pieces :meth:`sample_times` samples.
    """

    def __init__(self, path: PoseTrajectory, grid_times, grid_taus, rates, *,
                 partial: bool = False):
        if not isinstance(path, PoseTrajectory):
            raise ValueError(f'path must be a PoseTrajectory, got {type(path).__name__}')
        self.path = path
        self.grid_times = _array('grid_times', grid_times, (None,))
        count = self.grid_times.shape[0]
        self.grid_taus = _array('grid_taus', grid_taus, (count,))
        self.rates = _array('rates', rates, (count,))
        if count < 2 or self.grid_times[0] != 0.0 or not np.all(np.diff(self.grid_times) > 0.0):
            raise ValueError('grid_times must increase strictly from 0, at least 2 of them')
        spans = (self.grid_taus[0] >= path.times[0] and self.grid_taus[-1] <= path.times[-1]
                 if partial else self.grid_taus[0] == path.times[0]
                 and self.grid_taus[-1] == path.times[-1])
        if not (np.all(np.diff(self.grid_taus) > 0.0) and spans):
            raise ValueError('grid_taus must increase strictly from the first waypoint time to '
                             'the last (within them for a partial grid)')
        if np.any(self.rates < 0.0):
            raise ValueError('rates (d tau / dt) must not be negative')
        self.partial = partial
        steps = np.diff(self.grid_taus)
        self._rate_changes = (self.rates[1:] ** 2 - self.rates[:-1] ** 2) / (2.0 * steps)
        self.waypoint_times = self.clock_times(path.times)
        self.breakpoints = np.unique(np.concatenate([self.grid_times, self.waypoint_times]))

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
                               self.rates / factor, partial=self.partial)

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

    def clock_times(self, taus) -> np.ndarray:
        """
        Clock times at which the path reaches path times ``taus`` (the inverse of ``tau(t)``).

        :param taus: path times within the grid's, shape (M,).
        """
        taus = np.asarray(taus, dtype=float)
        j = np.clip(np.searchsorted(self.grid_taus, taus, side='right') - 1,
                    0, self.grid_taus.shape[0] - 2)
        ahead = np.clip(taus - self.grid_taus[j], 0.0, None)
        rate = self.rates[j]
        # Solve change e^2 / 2 + rate e = ahead for e >= 0, in the form that keeps its digits.
        root = np.sqrt(np.clip(rate ** 2 + 2.0 * self._rate_changes[j] * ahead, 0.0, None))
        denominator = rate + root
        elapsed = np.where(denominator > 0.0,
                           2.0 * ahead / np.where(denominator > 0.0, denominator, 1.0), 0.0)
        end = np.minimum(elapsed + self.grid_times[j], self.grid_times[j + 1])
        return np.where(taus >= self.grid_taus[-1], self.grid_times[-1], end)

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
        """Waypoint segment k (from path point k to point k + 1) of clock times, shape (M,)."""
        return self.path.segments(self.path_times(times)[0])

    def legs(self, geometry, times) -> LegStates:
        """Leg lengths, velocities and accelerations at clock times, seconds, shape (M,)."""
        return leg_states(geometry, self.sample(times))

    def piece_sample_counts(self, rate: float, max_per_piece: int = MAX_PIECE_SAMPLES):
        """
        How many intervals :meth:`sample_times` puts in each piece, shape (pieces,).

        ``min(ceil(rate * duration of the piece), max_per_piece)``, at least 1.
        """
        if not (_is_number(rate) and 0.0 < rate < math.inf):
            raise ValueError(f'a sampling rate must be positive and finite (Hz), got {rate!r}')
        pieces = np.diff(self.breakpoints)
        return np.maximum(np.ceil(np.minimum(pieces * rate, max_per_piece)), 1).astype(np.int64)

    def sample_count(self, rate: float, max_per_piece: int = MAX_PIECE_SAMPLES) -> int:
        """Return how many times :meth:`sample_times` gives, without computing them."""
        return int(self.piece_sample_counts(rate, max_per_piece).sum()) + 1

    def sample_times(self, rate: float, max_per_piece: int = MAX_PIECE_SAMPLES,
                     max_samples=None) -> np.ndarray:
        """
        Clock times every ``1 / rate`` seconds or closer, piece by piece, ends included.

        Each piece (between two :attr:`breakpoints`: waypoints, and gridpoints of a retimed
        trajectory) is split into ``min(ceil(rate * its duration), max_per_piece)`` equal
        intervals. So the cost of a long, slow piece is bounded: within one piece the motion
        is one smooth curve (a cubic or quintic in path time, played at a uniformly changing
        rate), which ``max_per_piece`` samples resolve, whatever it lasts.

        :param rate: hertz, positive.
        :param max_samples: when given and exceeded, the pieces get proportionally fewer
            intervals (at least one each).
        """
        counts = self.piece_sample_counts(rate, max_per_piece)
        if max_samples is not None and counts.sum() + 1 > max_samples:
            share = max(max_samples - 1 - counts.shape[0], 0) / float(counts.sum())
            counts = np.maximum(np.floor(counts * share), 1).astype(np.int64)
        starts = self.breakpoints[:-1]
        steps = np.diff(self.breakpoints) / counts
        offsets = np.arange(int(counts.sum())) - np.repeat(np.cumsum(counts) - counts, counts)
        times = np.repeat(starts, counts) + offsets * np.repeat(steps, counts)
        return np.append(times, self.breakpoints[-1])


def _spaced(steps, minimum):
    """
    Which points to keep so that each is at least ``minimum`` from the last kept (greedy).

    :param steps: distances from each point to the next, shape (N - 1,).
    :returns: a mask of shape (N,); the first point is kept, and the last (which replaces the
        last kept one when they are closer than ``minimum``, unless that is the first).
    """
    kept = np.ones(steps.shape[0] + 1, dtype=bool)
    if not np.any(steps < minimum):
        return kept
    travelled = 0.0
    last = 0
    for index, step in enumerate(steps.tolist(), start=1):
        travelled += step
        if travelled >= minimum:
            travelled, last = 0.0, index
        else:
            kept[index] = False
    if not kept[-1]:
        kept[-1] = True
        if last > 0:
            kept[last] = False
    return kept


def _stencil_derivatives(times, positions, rotations, width):
    """
    First and second derivatives at each waypoint of the polynomial through ``width`` of them.

    The stencil is centred (one-sided at the ends). Positions are fitted as they are; the
    orientations as the rotation vectors ``log(R_k^T R_j)`` of the stencil's waypoints from
    waypoint k, whose first and second derivatives at k are the body rate and body angular
    acceleration there.

    :returns: ``(velocities, accelerations, body_rates, body_accelerations)``, each (N, 3).
    """
    count = times.shape[0]
    width = min(width, count)
    starts = np.clip(np.arange(count) - width // 2, 0, count - width)
    members = starts[:, None] + np.arange(width)                       # (N, W)
    offsets = times[members] - times[:, None]
    scale = np.abs(offsets).max(axis=-1, keepdims=True)
    powers = np.arange(width)
    factorials = np.array([math.factorial(power) for power in powers], dtype=float)
    vandermonde = (offsets / scale)[:, :, None] ** powers / factorials   # (N, W, W)
    relative = matrix_to_rotation_vector(
        np.swapaxes(rotations, -1, -2)[:, None] @ rotations[members])   # (N, W, 3)
    values = np.concatenate([positions[members], relative], axis=-1)    # (N, W, 6)
    derivatives = np.linalg.solve(vandermonde, values)                   # (N, W, 6)
    first = derivatives[:, 1] / scale
    second = derivatives[:, 2] / (scale * scale) if width > 2 else np.zeros_like(first)
    return first[:, :3], second[:, :3], first[:, 3:], second[:, 3:]


def _three_point_tangents(slopes, steps, resting):
    """
    Estimate derivatives at the waypoints: of the parabola through each three, zero at the ends.

    :param slopes: each segment's mean rate, shape (N - 1, D); ``steps``: durations, (N - 1,).
    :param resting: segments that do not move, shape (N - 1,): zero at both their ends too.
    """
    tangents = np.zeros((slopes.shape[0] + 1, slopes.shape[1]))
    before, after = steps[:-1, None], steps[1:, None]
    tangents[1:-1] = (after * slopes[:-1] + before * slopes[1:]) / (before + after)
    tangents[:-1][resting] = 0.0
    tangents[1:][resting] = 0.0
    return tangents


def _position_coefficients(positions, velocities, accelerations, steps):
    """
    Polynomial coefficients in ``s`` in [0, 1] of each segment's position, shape (N-1, D+1, 3).

    Cubic Hermite (positions and velocities), or quintic Hermite with the accelerations.
    """
    h = steps[:, None]
    p0, p1 = positions[:-1], positions[1:]
    m0, m1 = velocities[:-1] * h, velocities[1:] * h
    delta = p1 - p0
    if accelerations is None:
        return np.stack([p0, m0, 3.0 * delta - 2.0 * m0 - m1, m0 + m1 - 2.0 * delta], axis=1)
    a0, a1 = accelerations[:-1] * h * h, accelerations[1:] * h * h
    return np.stack([
        p0, m0, 0.5 * a0,
        10.0 * delta - 6.0 * m0 - 4.0 * m1 - 0.5 * (3.0 * a0 - a1),
        -15.0 * delta + 8.0 * m0 + 7.0 * m1 + 0.5 * (3.0 * a0 - 2.0 * a1),
        6.0 * delta - 3.0 * m0 - 3.0 * m1 - 0.5 * (a0 - a1)], axis=1)


def _polynomial(coefficients, s):
    """Value and first two derivatives in ``s`` of polynomials, coefficients (M, D+1, 3)."""
    degree = coefficients.shape[1] - 1
    value = coefficients[:, degree]
    first = degree * coefficients[:, degree]
    second = degree * (degree - 1) * coefficients[:, degree]
    for j in range(degree - 1, -1, -1):
        value = value * s + coefficients[:, j]
        if j >= 1:
            first = first * s + j * coefficients[:, j]
        if j >= 2:
            second = second * s + j * (j - 1) * coefficients[:, j]
    return value, first, second


def _rotation_increments(rotations, body_rates, body_accelerations, steps, degree):
    """
    Return the rotation vectors ``w_j`` of each segment's cumulative curve, (N-1, degree, 3).

    ``R(s) = R_k exp(b_1(s) w_1) ... exp(b_n(s) w_n)`` with the cumulative Bernstein basis
    ``b_j``: its angular velocity at the ends is ``n w_1 / h`` and ``n w_n / h`` (platform
    frame), so ``w_1`` and ``w_n`` come from the body rates; in the quintic, ``w_2`` and
    ``w_4`` give the angular accelerations ``20 (w_2 - w_1) / h^2`` and ``20 (w_5 -
    exp(-w_5) w_4) / h^2``; the middle one joins the two waypoints.
    """
    h = steps[:, None]
    first = body_rates[:-1] * h / degree
    last = body_rates[1:] * h / degree
    if degree == 3:
        start, end = [first], [last]
    else:
        second = first + body_accelerations[:-1] * h * h / 20.0
        fourth = last - np.einsum('nij,nj->ni', rotation_vector_to_matrix(last),
                                  body_accelerations[1:]) * h * h / 20.0
        start, end = [first, second], [fourth, last]
    before = rotations[:-1]
    for w in start:
        before = before @ rotation_vector_to_matrix(w)
    after = rotations[1:]
    for w in reversed(end):
        after = after @ rotation_vector_to_matrix(-w)
    middle = matrix_to_rotation_vector(np.swapaxes(before, -1, -2) @ after)
    return np.stack(start + [middle] + end, axis=1)


def _cumulative_basis(s, degree):
    """
    Return the cumulative Bernstein basis of ``degree`` and its two derivatives, (degree, M).

    ``b_j = sum over i >= j of B_i,n``, ``b_j' = n B_j-1,n-1``, ``b_j'' = n (n - 1)
    (B_j-2,n-2 - B_j-1,n-2``), for j = 1 .. n.
    """
    def bernstein(order):
        return np.array([math.comb(order, i) * s ** i * (1.0 - s) ** (order - i)
                         for i in range(order + 1)])
    full, lower, lowest = bernstein(degree), bernstein(degree - 1), bernstein(degree - 2)
    values = np.cumsum(full[::-1], axis=0)[::-1][1:]
    first = degree * lower
    padded = np.concatenate([np.zeros((1, s.shape[0])), lowest, np.zeros((1, s.shape[0]))])
    second = degree * (degree - 1) * (padded[:-1] - padded[1:])
    return values, first, second


def _cumulative_rotation(start, increments, s):
    """
    Orientation, angular velocity and acceleration (base frame, per unit s) of the curves.

    With ``A_j = R_k exp(b_1 w_1) ... exp(b_j-1 w_j-1)`` and ``c_j = A_j w_j``:
    ``omega = sum b_j' c_j`` and ``alpha = sum b_j'' c_j + sum over i < j of
    b_i' b_j' c_i x c_j``. The frames are composed as unit quaternions, component by
    component (a third of the cost of composing matrices), and turned into matrices once.

    :param start: ``R_k`` per sample as unit quaternions ``(x, y, z, w)``, (M, 4);
        ``increments``: ``w_j``, (M, n, 3).
    :returns: ``(omega, alpha, rotations)``: (M, 3), (M, 3), (M, 3, 3).
    """
    degree = increments.shape[1]
    values, first, second = _cumulative_basis(s, degree)
    x, y, z, w = (start[:, axis] for axis in range(4))
    omega = [np.zeros(s.shape[0]) for _ in range(3)]
    alpha = [np.zeros(s.shape[0]) for _ in range(3)]
    for j in range(degree):
        vector = [increments[:, j, axis] for axis in range(3)]
        # c_j: w_j rotated by the frame (t = 2 u x v; v + w t + u x t).
        t = [2.0 * value for value in _cross3((x, y, z), vector)]
        column = [v + w * tv + cross for v, tv, cross in zip(vector, t, _cross3((x, y, z), t))]
        turning = [first[j] * value for value in column]
        bend = _cross3(omega, turning)
        for axis in range(3):
            alpha[axis] += second[j] * column[axis] + bend[axis]
            omega[axis] += turning[axis]
        # The frame turns by exp(b_j w_j): the quaternion (sin(a / 2) n, cos(a / 2)).
        angle = values[j] * np.sqrt(vector[0] ** 2 + vector[1] ** 2 + vector[2] ** 2)
        small = angle < 1e-4
        half_sine = np.where(small, 0.5 - angle * angle / 48.0,
                             np.sin(0.5 * angle) / np.where(small, 1.0, angle)) * values[j]
        ex, ey, ez, ew = (half_sine * vector[0], half_sine * vector[1], half_sine * vector[2],
                          np.cos(0.5 * angle))
        x, y, z, w = (w * ex + x * ew + y * ez - z * ey, w * ey - x * ez + y * ew + z * ex,
                      w * ez + x * ey - y * ex + z * ew, w * ew - x * ex - y * ey - z * ez)
    norm = np.sqrt(x * x + y * y + z * z + w * w)
    x, y, z, w = x / norm, y / norm, z / norm, w / norm
    rotations = np.stack([
        1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - z * w), 2.0 * (x * z + y * w),
        2.0 * (x * y + z * w), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - x * w),
        2.0 * (x * z - y * w), 2.0 * (y * z + x * w), 1.0 - 2.0 * (x * x + y * y)],
        axis=-1).reshape(-1, 3, 3)
    return np.stack(omega, axis=-1), np.stack(alpha, axis=-1), rotations


def _cross3(a, b):
    """Cross product of two vectors given as three component arrays each."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _angles_between(first, second):
    """Rotation angles from each of ``first`` to each of ``second`` (N, 3, 3), radians."""
    relative = np.swapaxes(first, -1, -2) @ second
    cosine = np.clip((np.trace(relative, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    # Near zero arccos loses digits: the skew part's norm gives sin(angle) accurately there.
    skew = np.stack([relative[:, 2, 1] - relative[:, 1, 2], relative[:, 0, 2] - relative[:, 2, 0],
                     relative[:, 1, 0] - relative[:, 0, 1]], axis=-1)
    return np.arctan2(np.linalg.norm(skew, axis=-1) / 2.0, cosine)


def _is_number(value) -> bool:
    """Whether ``value`` is a real number (a bool is not)."""
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(
        value, (bool, np.bool_))


def _array(name, value, shape, unit=None):
    """
    Convert to a finite float array of ``shape`` (``None`` entries: any length).

    :param unit: for positions and their derivatives: the unit of :data:`MAX_MAGNITUDE`,
        beyond which a value is refused (no motion of a platform).
    """
    array = np.array(as_float_array(value, name))
    wrong = any(expected is not None and size != expected
                for size, expected in zip(array.shape, shape))
    if array.ndim != len(shape) or wrong:
        shown = tuple('N' if size is None else size for size in shape)
        raise ValueError(f'{name} must have shape {shown}, got {array.shape}')
    if not np.all(np.isfinite(array)):
        raise ValueError(f'{name} must be finite')
    if unit is not None and array.size and np.abs(array).max() > MAX_MAGNITUDE:
        index = int(np.argmax(np.abs(array).max(axis=-1)))
        raise ValueError(f'point {index}: {name} {array[index].tolist()} {unit}, beyond '
                         f'{MAX_MAGNITUDE:g} {unit}: no motion of a platform')
    return array
