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
Actuator sizing: what each leg must push, pull, run and deliver along a timed motion.

:func:`actuator_demands` takes the platform's poses at some times with their twists and
accelerations (the derivatives of the motion itself: a trajectory's own, see
:func:`trajectory_demands`, never differences of the poses taken here) and returns, sample by
sample and per leg, the leg force (:func:`~.inverse_dynamics.leg_forces`), the leg speed
``dL/dt`` (the twist Jacobian times the twist) and the actuator's mechanical power
``f dL/dt``; and per leg the peaks a data sheet is compared with, each with the time it
happens (:class:`LegDemand`):

- **peak push**: the largest positive force (N), 0 if the leg never pushes;
- **peak pull**: the largest pull, as a positive number of newtons (the most negative force,
  negated; compare it with ``-leg_force_min``), 0 if the leg never pulls;
- **RMS force**: ``sqrt(integral f^2 dt / T)`` over the samples' time span ``T`` (trapezoids:
  time-weighted, so unevenly spaced samples count for the time they cover), N; what heats a
  motor;
- **peak speed**: the largest ``|dL/dt|``, m/s;
- **peak power**: the largest ``|f dL/dt|``, W. ``f dL/dt`` is the mechanical power the
  actuator delivers to the mechanism (the force it exerts times the rate at which it
  extends): positive when it drives the motion (motoring), negative when the load drives the
  actuator back (braking: the drive absorbs the power, as heat or regenerated). The sign at the
  peak is kept (``peak_power_delivered``). Electrical power adds the drive train's losses,
  which the model does not know.

Nothing here imports ROS or the motion package: a trajectory is anything with a
``sample(times)`` method that returns :class:`~stewart_kinematics.model.velocities.PoseSamples`
(a :class:`~stewart_kinematics.motion.pose_trajectory.PoseTrajectory` or
:class:`~stewart_kinematics.motion.pose_trajectory.TimedTrajectory`).
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.dynamics.inverse_dynamics import leg_forces
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.inputs import as_poses
from stewart_kinematics.model.rotations import matrix_to_euler_zyx
from stewart_kinematics.model.velocities import leg_velocities

#: Most samples a sizing takes (about 100 MB of arrays).
MAX_SAMPLES = 1_000_000


@dataclass(frozen=True)
class LegDemand:
    """
    What one leg needs along a motion: the peaks, each with its time (seconds).

    :param leg: the leg's number, 1 to 6.
    :param peak_push: largest push, N (>= 0; 0 if the leg never pushes); ``peak_push_time``
        ``None`` then.
    :param peak_pull: largest pull, N, as a positive number (>= 0; 0 if it never pulls).
    :param rms_force: time-weighted root mean square of the force, N.
    :param peak_speed: largest ``|dL/dt|``, m/s.
    :param peak_power: largest ``|f dL/dt|``, W.
    :param peak_power_delivered: ``True`` if the actuator delivers that power (``f dL/dt >
        0``: it drives the motion), ``False`` if it absorbs it (the load drives it back),
        ``None`` if the peak power is 0.
    """

    leg: int
    peak_push: float
    peak_push_time: Optional[float]
    peak_pull: float
    peak_pull_time: Optional[float]
    rms_force: float
    peak_speed: float
    peak_speed_time: float
    peak_power: float
    peak_power_time: float
    peak_power_delivered: Optional[bool]

    def as_dict(self) -> dict:
        """Return the fields as plain Python numbers (for JSON, YAML and CSV)."""
        return {name: getattr(self, name) for name in self.__dataclass_fields__}


@dataclass(frozen=True)
class ActuatorDemands:
    """
    Leg forces, speeds and powers along a motion, and each leg's peaks.

    :param times: seconds, shape (N,), non-decreasing.
    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), (N, 6).
    :param forces: leg forces, N, positive pushing the platform away from the base, (N, 6).
    :param speeds: leg rates ``dL/dt``, m/s, positive extending, (N, 6).
    :param powers: ``forces * speeds``, W, the mechanical power each actuator delivers, (N, 6).
    :param legs: one :class:`LegDemand` per leg.
    """

    times: np.ndarray
    poses: np.ndarray
    forces: np.ndarray
    speeds: np.ndarray
    powers: np.ndarray
    legs: Tuple[LegDemand, ...]


def actuator_demands(geometry, times, poses, twists, accelerations, *,
                     mass_properties=None) -> ActuatorDemands:
    """
    Compute the forces, speeds and powers of the six actuators along a timed motion, and peaks.

    :param geometry: a :class:`stewart_kinematics.Geometry` (its masses are used unless
        ``mass_properties`` is given).
    :param times: seconds, shape (N,), N >= 2, finite, non-decreasing, spanning more than 0 s
        (a time may repeat: the two sides of a waypoint where the acceleration jumps).
    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (N, 6).
    :param twists: ``[v, w]`` of each pose, base frame (m/s, rad/s), shape (N, 6): the
        motion's own derivatives.
    :param accelerations: ``[dv/dt, dw/dt]``, base frame (m/s^2, rad/s^2), shape (N, 6).
    :param mass_properties: as :func:`~.inverse_dynamics.leg_forces` takes it.
    :raises ValueError: naming the argument, for a malformed or non-finite value, times that
        go back or span no time, more than :data:`MAX_SAMPLES` samples, or a singular pose
        (:class:`~stewart_kinematics.SingularPoseError`).
    """
    times = _times(times)
    count = times.shape[0]
    arrays = []
    for name, values in (('poses', poses), ('twists', twists),
                         ('accelerations', accelerations)):
        array = as_poses(values, name)
        if array.shape != (count, 6):
            raise ValueError(f'{name} must have shape ({count}, 6) to match the times, got '
                             f'{array.shape}')
        arrays.append(array)
    poses, twists, accelerations = arrays
    forces = leg_forces(geometry, poses, twists, accelerations, mass_properties=mass_properties)
    speeds = leg_velocities(geometry, poses, twists)
    with np.errstate(over='ignore', invalid='ignore'):
        powers = forces * speeds
        squares = forces ** 2
    if not (np.all(np.isfinite(powers)) and np.all(np.isfinite(squares))):
        raise ValueError('the leg powers or squared forces overflow: the motion is too fast or '
                         'the masses too large to size')
    return ActuatorDemands(times, poses, forces, speeds, powers,
                           _peaks(times, forces, speeds, powers))


def trajectory_demands(geometry, trajectory, times, *, mass_properties=None) -> ActuatorDemands:
    """
    Run :func:`actuator_demands` along a trajectory, with the trajectory's own derivatives.

    The twists and accelerations are the trajectory's exact time derivatives at each time (its
    Hermite and Bernstein curves, differentiated in closed form): no finite differences.

    :param trajectory: anything with ``sample(times)`` returning
        :class:`~stewart_kinematics.model.velocities.PoseSamples` (a ``PoseTrajectory`` or a
        ``TimedTrajectory``).
    :param times: seconds on the trajectory's clock, as :func:`actuator_demands` takes them
        (see :func:`sample_times`).
    """
    times = _times(times)
    samples = trajectory.sample(times)
    poses = np.hstack([samples.positions, matrix_to_euler_zyx(samples.rotations)])
    twists = np.hstack([samples.velocities, samples.angular_velocities])
    accelerations = np.hstack([samples.accelerations, samples.angular_accelerations])
    return actuator_demands(geometry, times, poses, twists, accelerations,
                            mass_properties=mass_properties)


def sample_times(knots, rate: float) -> np.ndarray:
    """
    Return the times to size a piecewise trajectory at: every ``1 / rate`` s, both sides of knots.

    A cubic through waypoints is smooth between them, but its acceleration (so the force) jumps
    at each: the times hold every knot, and just before each inner knot (the float before it,
    so that the sample lies on the segment that ends there) the other side of the jump.

    :param knots: the waypoint times, seconds, shape (K,), K >= 2, increasing.
    :param rate: samples per second between them, positive.
    :returns: sorted times from the first knot to the last, shape (M,).
    :raises ValueError: for a bad rate or knots, or more than :data:`MAX_SAMPLES` times.
    """
    knots = _times(knots, 'knots')
    if not (isinstance(rate, (int, float, np.integer, np.floating)) and not isinstance(
            rate, bool) and 0.0 < rate < math.inf):
        raise ValueError(f'rate must be a positive finite number of hertz, got {preview(rate)}')
    span = float(knots[-1] - knots[0])
    steps = span * rate
    if not steps < MAX_SAMPLES:
        raise ValueError(f'{span:g} s at {rate:g} Hz is more than {MAX_SAMPLES:,} samples: '
                         'lower the rate')
    grid = np.linspace(knots[0], knots[-1], int(math.ceil(steps)) + 1)
    before = np.nextafter(knots[1:-1], -np.inf)
    return np.unique(np.concatenate([grid, knots, before]))


def _times(values, name='times') -> np.ndarray:
    times = as_float_array(values, name)
    if times.ndim != 1 or times.shape[0] < 2:
        raise ValueError(f'{name} must have shape (N,) with N >= 2, got {preview(values)}')
    if times.shape[0] > MAX_SAMPLES:
        raise ValueError(f'{name}: at most {MAX_SAMPLES:,} times, got {times.shape[0]:,}')
    if not np.all(np.isfinite(times)):
        bad = int(np.argmax(~np.isfinite(times)))
        raise ValueError(f'{name} must be finite seconds; time {bad} is {times[bad]!r}')
    steps = np.diff(times)
    if np.any(steps < 0.0):
        bad = int(np.argmax(steps < 0.0)) + 1
        raise ValueError(f'{name} must not go back; time {bad} is {times[bad]!r} s after '
                         f'{times[bad - 1]!r} s')
    if not times[-1] > times[0]:
        raise ValueError(f'{name} must span more than 0 s, got all at {times[0]!r} s')
    return times


def time_weighted_rms(times, values) -> float:
    """
    Return the root mean square of a sampled signal over time: ``sqrt(integral x^2 dt / T)``.

    The integral by trapezoids, so that each sample counts for the time it covers (half of the
    step before it and half of the one after): unevenly spaced samples give the RMS of the
    signal, not of the samples.

    :param times: seconds, shape (N,), as :func:`actuator_demands` takes them.
    :param values: the signal, shape (N,) (or (N, K): one RMS per column), finite.
    :raises ValueError: naming the argument, for bad times or values.
    """
    times = _times(times)
    values = as_float_array(values, 'values')
    if values.ndim not in (1, 2) or values.shape[0] != times.shape[0]:
        raise ValueError(f'values must have shape ({times.shape[0]},) or ({times.shape[0]}, K) '
                         f'to match the times, got {values.shape}')
    if not np.all(np.isfinite(values)):
        raise ValueError('values must be finite')
    return np.sqrt(_weights(times) @ values ** 2 / (times[-1] - times[0]))


def _weights(times):
    weights = np.zeros(times.shape)     # trapezoids: each sample covers half of each step
    steps = np.diff(times)
    weights[:-1] += steps / 2.0
    weights[1:] += steps / 2.0
    return weights


def _peaks(times, forces, speeds, powers):
    rms = time_weighted_rms(times, forces)
    legs = []
    for leg in range(6):
        force, speed, power = forces[:, leg], speeds[:, leg], powers[:, leg]
        push, pull = int(np.argmax(force)), int(np.argmin(force))
        fastest, strongest = int(np.argmax(np.abs(speed))), int(np.argmax(np.abs(power)))
        legs.append(LegDemand(
            leg=leg + 1,
            peak_push=max(float(force[push]), 0.0),
            peak_push_time=float(times[push]) if force[push] > 0.0 else None,
            peak_pull=max(-float(force[pull]), 0.0),
            peak_pull_time=float(times[pull]) if force[pull] < 0.0 else None,
            rms_force=float(rms[leg]),
            peak_speed=abs(float(speed[fastest])), peak_speed_time=float(times[fastest]),
            peak_power=abs(float(power[strongest])), peak_power_time=float(times[strongest]),
            peak_power_delivered=(None if power[strongest] == 0.0
                                  else bool(power[strongest] > 0.0))))
    return tuple(legs)
