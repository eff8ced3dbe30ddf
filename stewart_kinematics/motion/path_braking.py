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
Braking on the path: a running trajectory brought to rest without leaving its checked path.

A cancelled or preempted goal (:mod:`~stewart_kinematics.ros.trajectory_action`) must stop
within the leg velocity and acceleration limits, never with a jump. Braking each leg on its own
(:meth:`~stewart_kinematics.limits.CommandGate.brake`) leaves the path the trajectory was
checked on; here the platform keeps to it and only its clock slows: the path time ``tau(t)``
of the trajectory is replaced, from the moment of braking, by one whose rate ``tau'``
falls to 0 as fast as every leg's acceleration allows. With ``l_tau`` and ``l_tautau`` the
legs' derivatives along the path, a leg's velocity is ``l_tau tau'`` (below its limit, since
``tau'`` never exceeds the trajectory's own rate there) and its acceleration ``l_tautau tau'^2
+ l_tau tau''``: each step takes the most negative ``tau''`` that keeps every leg within
:data:`BRAKING_MARGIN` of ``leg_acceleration_max``; where the trajectory's own timing slows
faster than that (a retimed trajectory braking at its limit), its own timing is followed to
its end. The result is a partial
:class:`~stewart_kinematics.motion.pose_trajectory.TimedTrajectory` (its clock from 0 at the
moment of braking), sampled and sent like any other, and checked by the command gate as it is.

Units: seconds, metres. Nothing here imports ROS.
"""

import math
from typing import Optional

import numpy as np

from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.velocities import leg_states
from stewart_kinematics.motion.pose_trajectory import TimedTrajectory

#: Clock step of the braking's grid, seconds: the rate's change is held over a step.
BRAKING_STEP = 0.002
#: Share of leg_acceleration_max a braking step may use (the acceleration varies within it).
BRAKING_MARGIN = 0.9
#: Braking time without an acceleration limit, seconds (a stop is never a jump).
UNLIMITED_BRAKING_TIME = 0.5
#: Most steps of a braking; beyond, the path is followed to its end (within its own timing).
MAX_BRAKING_STEPS = 20_000
#: A leg's path derivative below this (m per path second) does not constrain the braking.
FLAT = 1e-12


def braking_trajectory(trajectory: TimedTrajectory, time: float, geometry,
                       actuator_limits: Optional[ActuatorLimits] = None, *,
                       step: float = BRAKING_STEP) -> Optional[TimedTrajectory]:
    """
    Bring a timed trajectory to rest on its path from clock time ``time``, as fast as allowed.

    :param trajectory: the trajectory running (full or partial: a braking may be braked).
    :param time: its clock time at the moment of braking, seconds.
    :param actuator_limits: ``leg_acceleration_max`` bounds the braking (with
        :data:`BRAKING_MARGIN`); without one, the rate falls linearly over
        :data:`UNLIMITED_BRAKING_TIME`.
    :param step: clock step of the grid, seconds.
    :returns: the braking, a partial :class:`TimedTrajectory` whose clock starts at 0 at the
        moment of braking and ends at rest; ``None`` when the trajectory is already at rest there
        (its end, or a rate of 0 or too small to move it in floating point).
    """
    path = trajectory.path
    taus, rates, _ = trajectory.path_times([float(time)])
    tau, rate = float(taus[0]), float(rates[0])
    end = float(path.times[-1])
    if not (rate > 0.0 and tau < end):
        return None
    limit = math.inf if actuator_limits is None else actuator_limits.acceleration_max
    allowed = BRAKING_MARGIN * limit
    grid_times, grid_taus, grid_rates = [0.0], [tau], [rate]
    for _ in range(MAX_BRAKING_STEPS):
        change = _steepest_change(path, geometry, tau, rate, allowed, step)
        interval = step
        new_rate = rate + change * interval
        if new_rate <= 0.0:
            interval, new_rate = rate / -change, 0.0
        advance = rate * interval + 0.5 * change * interval ** 2
        if advance <= 0.0:
            # So slow that the stop moves no path time in floating point (a rate of 1e-313
            # underflows): at rest where it is.
            if len(grid_times) == 1:
                return None
            grid_rates[-1] = 0.0
            break
        if tau + advance >= end:
            # The path ends (at rest) within the step: reach its end at the rate left.
            remaining = end - tau
            new_rate = math.sqrt(max(rate ** 2 + 2.0 * change * remaining, 0.0))
            # Never faster at the end than the trajectory itself (a retimed one stops there).
            new_rate = min(new_rate, float(trajectory.rates[-1]))
            interval = 2.0 * remaining / (rate + new_rate)
            _append(grid_times, grid_taus, grid_rates, interval, end, new_rate)
            break
        new_tau = tau + advance
        own = float(trajectory.path_times(trajectory.clock_times([new_tau]))[1][0])
        if new_rate > own:
            # The trajectory itself slows faster here (a retimed one, braking at its limit):
            # follow its own timing to its end, which kept every limit.
            _follow(trajectory, grid_times, grid_taus, grid_rates, tau, rate)
            break
        _append(grid_times, grid_taus, grid_rates, interval, new_tau, new_rate)
        tau, rate = new_tau, new_rate
        if rate == 0.0:
            break
    else:
        # Held back all along: follow the path to its end at the rate reached.
        _append(grid_times, grid_taus, grid_rates, (end - tau) / rate, end, rate)
    return TimedTrajectory(path, grid_times, grid_taus, grid_rates, partial=True)


def _follow(trajectory, times, taus, rates, tau, rate):
    """Append the trajectory's own gridpoints after path time ``tau`` (rate ``rate`` there)."""
    later = trajectory.grid_taus > tau
    grid_taus, grid_rates = trajectory.grid_taus[later], trajectory.rates[later]
    previous_tau, previous_rate = tau, rate
    for next_tau, next_rate in zip(grid_taus, grid_rates):
        interval = 2.0 * (next_tau - previous_tau) / (previous_rate + next_rate) \
            if previous_rate + next_rate > 0.0 else 0.0
        if not interval > 0.0:
            break
        _append(times, taus, rates, interval, float(next_tau), float(next_rate))
        previous_tau, previous_rate = next_tau, next_rate


def _append(times, taus, rates, interval, tau, rate):
    """Add a gridpoint ``interval`` seconds after the last, where the rate is ``rate``."""
    times.append(times[-1] + interval)
    taus.append(tau)
    rates.append(rate)


def _steepest_change(path, geometry, tau, rate, allowed, step) -> float:
    """
    Return the most negative ``tau''`` (1/s) keeping every leg's acceleration within ``allowed``.

    Each leg asks ``-allowed <= l_tautau r^2 + l_tau change <= allowed`` all along the step:
    at its start and at the farthest path time it can reach (``tau + rate * step``, the path's
    derivatives there), and for every rate ``r`` it passes through, from ``rate`` down to
    ``rate + change * step`` (at least 0). The acceleration is linear in ``r^2``, so both ends
    are asked, the lower with the change the start alone allows (a smaller ``r^2`` than the
    step's end can have). Asking the start only let the curvature that helped the braking
    there vanish as the rate fell, and missed a slope growing along the step: braked just
    after a start from rest, a leg reached 0.2515 and 0.296 m/s^2 against 0.25. The change is
    at most 0 (holding the rate keeps the trajectory's own accelerations, scaled by ``rate^2``).
    """
    if not math.isfinite(allowed):
        return -rate / UNLIMITED_BRAKING_TIME if rate > 0.0 else 0.0
    far = min(tau + rate * step, float(path.times[-1]))
    legs = leg_states(geometry, path.sample(np.array([tau, far])))
    slopes, curvatures = legs.velocities, legs.accelerations * rate ** 2
    if not (np.abs(slopes[0]) > FLAT).any():
        # The legs do not move along the path here: the clock may stop at once.
        return -rate / step
    change = _lowest_change(slopes[0], curvatures[0], allowed)
    # The step's end, at the slowest rate the start's change can reach there.
    end_share = max(1.0 + change * step / rate, 0.0) ** 2 if rate > 0.0 else 0.0
    for point, share in ((0, end_share), (1, 1.0), (1, end_share)):
        change = max(change, _lowest_change(slopes[point], curvatures[point] * share, allowed))
    return min(change, 0.0)


def _lowest_change(slope, curvature, allowed) -> float:
    """Return the most negative change with ``|curvature + slope change| <= allowed`` per leg."""
    moving = np.abs(slope) > FLAT
    if not moving.any():
        return -math.inf
    g, b = slope[moving], curvature[moving]
    return float(np.max(np.where(g > 0.0, (-allowed - b) / g, (allowed - b) / g)))
