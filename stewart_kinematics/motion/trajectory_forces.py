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
Leg forces along a trajectory: of its samples in motion, and along a path as TOPP-RA wants them.

A sample of a trajectory (:class:`~stewart_kinematics.model.velocities.PoseSamples`) carries
the platform's velocity, angular velocity and their rates, all in the base frame: its twist
``[v, w]`` and acceleration ``[dv/dt, dw/dt]`` as :func:`stewart_kinematics.leg_forces` takes
them, so :func:`sample_forces` gives its dynamic leg forces with one batch call.

Along a path ``q(s)`` played with path speed ``sd`` and path acceleration ``sdd``, the twist is
``q'(s) sd`` and the acceleration ``q'(s) sdd + q''(s) sd^2``. The forces are linear in the
acceleration and quadratic (homogeneous, of degree 2) in the twist, so

    f(s, sd, sdd) = a(s) sdd + b(s) sd^2 + c(s)

exactly: TOPP-RA's second-order constraint. :func:`force_coefficients` gets ``a``, ``b``,
``c`` from three evaluations of the dynamics per path position in one batch call:
``c = f(0, 0)`` (the static forces), ``a = f(0, 1) - c``, ``b = f(1, 0) - c``.

Units: metres, radians, seconds, newtons. Nothing here imports ROS.
"""

import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.dynamics.inverse_dynamics import leg_forces, masses_of
from stewart_kinematics.model.rotations import matrix_to_euler_zyx
from stewart_kinematics.model.velocities import PoseSamples


def force_limits(geometry) -> Optional[Tuple[float, float]]:
    """
    Return ``(leg_force_min, leg_force_max)`` of a geometry when forces are checked, else None.

    Forces are checked when the geometry carries a mass (not every mass 0) and its limits
    set at least one of the two bounds (``-inf`` and ``inf`` are not set).

    :returns: newtons, ``(low, high)``; ``None`` when no force limit applies.
    """
    limits = getattr(geometry, 'limits', None)
    if limits is None or masses_of(geometry).massless:
        return None
    low, high = float(limits.leg_force_min), float(limits.leg_force_max)
    if not (math.isfinite(low) or math.isfinite(high)):
        return None
    return low, high


def sample_poses(samples: PoseSamples) -> np.ndarray:
    """Return the poses ``[X, Y, Z, alpha, beta, gamma]`` of samples, shape (M, 6)."""
    return np.concatenate([samples.positions, matrix_to_euler_zyx(samples.rotations)], axis=-1)


def sample_forces(geometry, samples: PoseSamples) -> np.ndarray:
    """
    Dynamic leg forces of trajectory samples: each pose with its twist and acceleration.

    :param geometry: a :class:`stewart_kinematics.Geometry` with its masses.
    :param samples: poses, velocities and accelerations (base frame), M samples.
    :returns: newtons, shape (M, 6), positive pushing; NaN for every leg of a sample where no
        forces exist (a singular pose, or values beyond the float range): such a sample breaks
        any force limit.
    """
    twists = np.concatenate([samples.velocities, samples.angular_velocities], axis=-1)
    accelerations = np.concatenate([samples.accelerations, samples.angular_accelerations],
                                   axis=-1)
    return _forces(geometry, sample_poses(samples), twists, accelerations)


def force_coefficients(geometry, path, parameters, scale: float = 1.0):
    """
    Return ``(a, b, c)`` of ``f = a sdd + b sd^2 + c`` at positions along a path, each (G, 6).

    :param geometry: a :class:`stewart_kinematics.Geometry` with its masses.
    :param path: a :class:`~stewart_kinematics.motion.pose_trajectory.PoseTrajectory`; its
        own times are the path parameter ``tau``.
    :param parameters: path parameters ``tau``, shape (G,).
    :param scale: the path parameter ``s`` is ``tau / scale`` (``q'(s) = scale q'(tau)``): the
        coefficients are those of ``s``.
    :returns: newtons per unit ``sdd`` (``a``), per unit ``sd^2`` (``b``), and the static forces
        (``c``); NaN rows where no forces exist (see :func:`sample_forces`).
    """
    samples = path.sample(np.asarray(parameters, dtype=float))
    poses = sample_poses(samples)
    first = scale * np.concatenate([samples.velocities, samples.angular_velocities], axis=-1)
    second = scale * scale * np.concatenate(
        [samples.accelerations, samples.angular_accelerations], axis=-1)
    zeros = np.zeros_like(first)
    count = poses.shape[0]
    # (sd, sdd) = (0, 0), (0, 1), (1, 0): one batch of 3 G poses.
    forces = _forces(geometry, np.concatenate([poses, poses, poses]),
                     np.concatenate([zeros, zeros, first]),
                     np.concatenate([zeros, first, second]))
    static = forces[:count]
    return forces[count:2 * count] - static, forces[2 * count:] - static, static


def _forces(geometry, poses, twists, accelerations) -> np.ndarray:
    """:func:`stewart_kinematics.leg_forces` of rows, NaN for the rows that have none."""
    if not poses.shape[0]:
        return np.zeros((0, 6))
    try:
        return leg_forces(geometry, poses, twists, accelerations)
    except ValueError:   # a singular pose or an overflow somewhere: row by row (rare)
        forces = np.full(poses.shape, math.nan)
        for row in range(poses.shape[0]):
            try:
                forces[row] = leg_forces(geometry, poses[row], twists[row], accelerations[row])
            except ValueError:
                pass
        return forces
