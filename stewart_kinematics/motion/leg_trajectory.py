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
Leg trajectories: a timed platform trajectory sampled for the six actuators.

A :class:`LegTrajectory` is what a trajectory_msgs/JointTrajectory carries to
joint_trajectory_controller: actuator positions, velocities and accelerations at times, and,
when the geometry carries masses, the efforts: each point's dynamic leg forces (its pose with
its twist and acceleration, :func:`~stewart_kinematics.motion.trajectory_forces.
sample_forces`), a feed-forward for ros2_control. With every mass 0 there are no efforts.

Units: metres, seconds, newtons. Nothing here imports ROS.
"""

from dataclasses import dataclass, field
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.dynamics.inverse_dynamics import masses_of
from stewart_kinematics.model.actuators import ActuatorInterface
from stewart_kinematics.model.velocities import leg_states
from stewart_kinematics.motion.pose_trajectory import TimedTrajectory
from stewart_kinematics.motion.trajectory_forces import sample_forces

#: Most points of a leg trajectory (a JointTrajectory of 100,000 points is about 20 MB).
MAX_POINTS = 100_000


@dataclass(frozen=True)
class LegTrajectory:
    """
    A timed trajectory of the six actuators, as a JointTrajectory carries it.

    :param joint_names: leg 1..6.
    :param times: time from start of each point, seconds, shape (M,).
    :param positions: actuator positions (leg length minus offset), metres, shape (M, 6).
    :param velocities: m/s, shape (M, 6).
    :param accelerations: m/s^2, shape (M, 6).
    :param offsets: each actuator's zero as a leg length, metres, shape (6,): the positions
        are the leg lengths minus these (:class:`~stewart_kinematics.ActuatorInterface`).
    :param efforts: the dynamic leg forces at each point, newtons, shape (M, 6), positive
        pushing; ``None`` when the geometry carries no mass (every mass 0).
    """

    joint_names: Tuple[str, ...]
    times: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray
    offsets: np.ndarray = field(default_factory=lambda: np.zeros(6))
    efforts: Optional[np.ndarray] = None

    @property
    def lengths(self) -> np.ndarray:
        """Return the leg lengths the points command, as a driver reads them, metres, (M, 6)."""
        return self.positions + self.offsets


def leg_trajectory(trajectory: TimedTrajectory, geometry, actuators: ActuatorInterface,
                   rate: float, max_points: int = MAX_POINTS) -> LegTrajectory:
    """
    Sample a timed trajectory for an actuator interface: every ``1 / rate`` s and at waypoints.

    The points are those of :meth:`TimedTrajectory.sample_times`: every waypoint (and gridpoint
    of a retiming) and, between two, every ``1 / rate`` seconds or closer, at most
    :data:`~stewart_kinematics.motion.pose_trajectory.MAX_PIECE_SAMPLES` intervals; a long
    trajectory that would need more than ``max_points`` gets proportionally fewer points
    between two (the controller interpolates between them with their velocities and
    accelerations). With masses, each point carries its dynamic leg forces (``efforts``).

    :param rate: points per second, hertz.
    """
    return sampled_leg_trajectory(trajectory, geometry, actuators, rate, max_points)[0]


def sampled_leg_trajectory(trajectory: TimedTrajectory, geometry, actuators: ActuatorInterface,
                           rate: float, max_points: int = MAX_POINTS):
    """
    :func:`leg_trajectory`, with the platform poses its points are the legs of.

    :returns: ``(points, poses)``: the :class:`LegTrajectory` and the
        :class:`~stewart_kinematics.model.velocities.PoseSamples` at its times, for the
        command gate to check what is sent
        (:meth:`~stewart_kinematics.limits.command_gate.CommandGate.trajectory`).
    """
    times = trajectory.sample_times(rate, max_samples=max_points)
    poses = trajectory.sample(times)
    legs = leg_states(geometry, poses)
    efforts = None if masses_of(geometry).massless else sample_forces(geometry, poses)
    return LegTrajectory(actuators.joint_names, times, actuators.positions(legs.lengths),
                         legs.velocities, legs.accelerations, actuators.offsets,
                         efforts), poses
