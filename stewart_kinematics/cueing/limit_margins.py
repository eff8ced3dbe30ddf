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
The cueing's only calls into the limits model, and the margins the cue keeps inside it.

Every pose the cueing outputs is judged by :func:`pose_violations` (one pose) or
:func:`poses_allowed` (a batch), and the workspace boundary is found with
:func:`limit_margins`, over every kind of limit of the limits model; each kind declares how
the cue's margins narrow it (:attr:`stewart_kinematics.limits.LimitKind.narrowed`, used by
:func:`with_margins`), so a kind added to the list needs no edit here. The leg velocity and
acceleration limits of :class:`~stewart_kinematics.ActuatorLimits` are kept by the follower in
:mod:`.cue_limiter`, step by step, and counted by :func:`leg_speed_violations`.

Nothing here imports ROS.
"""

import dataclasses
import math

import numpy as np

from stewart_kinematics.limits import (
    check_pose,
    check_poses_array,
    CueMargins,
    LimitModel,
    limits_of,
)
from stewart_kinematics.limits.kinds import pose_bounds


def pose_violations(geometry, position, rotation) -> list:
    """
    Every limit of ``geometry`` that one pose breaks; empty when it is allowed.

    :param position: platform position in the base frame, metres, shape (3,).
    :param rotation: platform-to-base rotation, shape (3, 3).
    """
    return check_pose(geometry, position, rotation)


def poses_allowed(geometry, poses) -> np.ndarray:
    """
    Whether each pose keeps every limit of ``geometry``.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]``, shape (N, 6).
    :returns: shape (N,), bool.
    """
    return check_poses_array(geometry, poses).allowed


def limit_margins(geometry, poses) -> np.ndarray:
    """
    How far each pose is beyond its nearest limit: negative inside, zero on the boundary.

    The largest excess over every limit set in ``geometry`` (metres for the stroke, radians
    for the joint cones, a share of the allowed value for a bound its kind declares
    ``relative``, such as ``max_jacobian_condition``); continuous in the pose, so that the
    boundary can be found by root finding.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]``, shape (N, 6).
    :returns: shape (N,); ``-inf`` where no limit is set.
    """
    checks = check_poses_array(geometry, poses)
    margins = np.full(len(checks), -np.inf)
    relative = {bound.name for bound in pose_bounds() if bound.relative}
    for limit in checks.broken:
        excess = checks.excess(limit)
        if limit in relative:
            excess = excess / LimitModel.of_geometry(geometry).bound(limit).allowed
        if excess.ndim > 1:
            excess = np.max(excess, axis=-1)
        margins = np.maximum(margins, np.where(np.isnan(excess), np.inf, excess))
    return margins


def leg_speed_violations(times, lengths, actuator_limits, tolerance=1e-9) -> dict:
    """
    Count the leg velocities and accelerations of a stream of leg lengths beyond the limits.

    Velocities are ``(l_k - l_(k-1)) / dt_k``; accelerations the change of velocity over
    ``min(dt_k, (dt_(k-1) + dt_k) / 2)``, as the follower of :mod:`.cue_limiter` bounds them.

    :param times: seconds, shape (N,), increasing.
    :param lengths: metres, shape (N, 6).
    :param actuator_limits: an :class:`~stewart_kinematics.ActuatorLimits`.
    :param tolerance: relative slack for rounding.
    :returns: ``{'velocity': count, 'acceleration': count, 'velocity_peak': m/s,
        'acceleration_peak': m/s^2}`` over every leg and sample; the counts are the limits
        model's (its leg-rate evaluators), the peaks the largest magnitudes seen.
    """
    times = np.asarray(times, dtype=float)
    lengths = np.asarray(lengths, dtype=float)
    steps = np.diff(times)
    velocities = np.diff(lengths, axis=0) / steps[:, None]
    spans = np.minimum(steps[1:], 0.5 * (steps[1:] + steps[:-1]))
    accelerations = np.diff(velocities, axis=0) / spans[:, None]
    model = LimitModel(actuator_limits=actuator_limits, rate_slack=tolerance)

    def broken(limit, **states):
        if not next(iter(states.values())).size:
            return 0
        return int(np.count_nonzero(model.check_leg_states(**states).broken.get(limit, 0)))
    return {
        'velocity': broken('leg_velocity_max', velocities=velocities),
        'acceleration': broken('leg_acceleration_max', accelerations=accelerations),
        'velocity_peak': float(np.max(np.abs(velocities), initial=0.0)),
        'acceleration_peak': float(np.max(np.abs(accelerations), initial=0.0)),
    }


def with_margins(geometry, leg_length_margin: float, joint_angle_margin: float,
                 condition_margin: float):
    """
    Return ``geometry`` with its set limits drawn in by the margins (unset limits stay unset).

    Each kind of limit says how its values narrow
    (:meth:`stewart_kinematics.limits.PoseLimits.narrowed`); the leg radius does not.

    :param leg_length_margin: metres off each end of the stroke.
    :param joint_angle_margin: radians off each joint cone.
    :param condition_margin: fraction of ``max_jacobian_condition`` kept.
    :raises ValueError: if the home pose breaks the narrowed limits (margins too wide for this
        platform), naming the margins.
    """
    margins = CueMargins(leg_length_margin, joint_angle_margin, condition_margin)
    try:
        return dataclasses.replace(geometry, limits=limits_of(geometry).narrowed(margins))
    except ValueError as error:
        raise ValueError(
            f'the cue margins (leg_length_margin {leg_length_margin:g} m, joint_angle_margin '
            f'{math.degrees(joint_angle_margin):g} deg, condition_margin {condition_margin:g}) '
            f'leave no room around the home pose: {error}') from None
