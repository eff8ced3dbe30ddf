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
Retiming: the fastest timing of a path within every leg's velocity and acceleration limits.

:func:`retime` is time-optimal path parameterisation in leg space (TOPP-RA, the toppra
library): the leg lengths along the path, under per-leg velocity and acceleration limits,
starting and ending at rest.

Units: metres, radians, seconds. Nothing here imports ROS.
"""

import math

import numpy as np

from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.velocities import leg_states
from stewart_kinematics.motion.pose_trajectory import PoseTrajectory, TimedTrajectory

#: toppra's grid: at least this many gridpoints over the whole path ...
MIN_GRIDPOINTS = 400
#: ... and at least this many intervals per waypoint segment.
MIN_GRID_INTERVALS_PER_SEGMENT = 4
#: Gap, as a fraction of its segment, between a waypoint and the gridpoint just before it.
WAYPOINT_GRID_GAP = 1e-6


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
