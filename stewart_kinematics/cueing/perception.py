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
What a person at the head feels of a motion: raw specific force and rate, and what is perceived.

The head sits at ``head_position`` (platform frame, metres); in the base frame it is at
``h = p + R head_position``. A person (like an accelerometer) there feels the specific force
``f = R^T (h'' + [0, 0, g])`` in the platform frame (``[0, 0, g]`` at rest: the translational
acceleration of the platform, plus the tangential and centripetal terms of its rotation about
an axis away from the head, plus gravity seen from the tilted seat), and the angular velocity
``w = (R^T R')^v`` of the platform (body frame). At neutral the platform frame is the vehicle
frame, so both compare directly with the cueing's input.

Derivatives are finite differences of the sampled poses: the head's acceleration at sample k
from samples k-1, k, k+1 (exact for a parabola; the error is of the order of the step squared
on even steps, of the difference of the two steps on uneven ones), and the angular velocity
from the two rotations around it (:func:`body_rates`).

What a person *perceives* of a motion, vehicle or platform alike, is that raw motion through
the vestibular model of :mod:`.vestibular` (the otoliths per axis of specific force, the
semicircular canals per axis of rate, with their thresholds): :func:`perception` returns the
raw and the perceived series side by side (:class:`Perception`). Nothing here imports ROS.
"""

from dataclasses import dataclass

import numpy as np

from stewart_kinematics.cueing.settings import STANDARD_GRAVITY
from stewart_kinematics.cueing.vestibular import (
    CanalModel,
    CANALS,
    OtolithModel,
    OTOLITHS,
    perceive,
    perception_thresholds,
)
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, matrix_to_rotation_vector


@dataclass(frozen=True)
class PerceivedMotion:
    """
    The motion felt at the head, sample by sample.

    :param times: seconds, shape (N,).
    :param specific_force: platform frame, m/s^2, shape (N, 3).
    :param angular_velocity: platform frame, rad/s, shape (N, 3).
    """

    times: np.ndarray
    specific_force: np.ndarray
    angular_velocity: np.ndarray


def head_positions(poses, head_position) -> np.ndarray:
    """
    Positions of the head in the base frame: ``p + R head_position``.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]``, shape (6,) or (N, 6).
    :param head_position: platform frame, metres, shape (3,).
    :returns: metres, shape (3,) or (N, 3).
    """
    poses = np.asarray(poses, dtype=float)
    return poses[..., :3] + euler_zyx_to_matrix(poses[..., 3:]) @ np.asarray(
        head_position, dtype=float)


def second_derivative(t0, t1, t2, x0, x1, x2):
    """
    Second derivative at ``t1`` from three samples on uneven steps (exact for a parabola).

    Works on floats and on arrays alike (broadcast ``t`` against ``x``).
    """
    return 2.0 * ((x2 - x1) / (t2 - t1) - (x1 - x0) / (t1 - t0)) / (t2 - t0)


def specific_force(rotation, acceleration, gravity: float = STANDARD_GRAVITY) -> np.ndarray:
    """
    Specific force in the platform frame: ``R^T (a + [0, 0, g])``.

    :param rotation: platform-to-base rotation, shape (3, 3) or (N, 3, 3).
    :param acceleration: the head's acceleration in the base frame, m/s^2, (3,) or (N, 3).
    """
    total = np.array(acceleration, dtype=float)
    total[..., 2] += gravity
    return np.einsum('...ji,...j->...i', rotation, total)


def perceived_motion(times, poses, head_position, gravity: float = STANDARD_GRAVITY
                     ) -> PerceivedMotion:
    """
    Return the specific force and angular velocity felt at the head along a sampled motion.

    :param times: seconds, shape (N,), increasing, N >= 3.
    :param poses: the platform's poses, shape (N, 6).
    :param head_position: platform frame, metres, shape (3,).
    :returns: a :class:`PerceivedMotion`; the first and last samples repeat their neighbours'
        values (no centred difference exists there).
    :raises ValueError: for fewer than 3 samples, mismatched shapes or times that do not
        increase.
    """
    times, poses = _sampled_poses(times, poses)
    heads = head_positions(poses, head_position)
    rotations = euler_zyx_to_matrix(poses[:, 3:])
    t0, t1, t2 = times[:-2, None], times[1:-1, None], times[2:, None]
    acceleration = second_derivative(t0, t1, t2, heads[:-2], heads[1:-1], heads[2:])
    force = specific_force(rotations[1:-1], acceleration, gravity)
    return PerceivedMotion(times=times, specific_force=_pad(force),
                           angular_velocity=_body_rates(times, rotations))


def body_rates(times, poses) -> np.ndarray:
    """
    Return the platform's body angular velocity ``(R^T R')^v`` along sampled poses.

    The rotation from each pose to the next, as a rotation vector over its step, gives the
    rate over that interval; each inner sample takes the centred combination of the two around
    it (second order on even steps); the first and last samples repeat their neighbours'.

    :param times: seconds, shape (N,), increasing, N >= 3.
    :param poses: ``[X, Y, Z, alpha, beta, gamma]``, shape (N, 6) (only the angles are read).
    :returns: rad/s, platform frame (roll, pitch, yaw rates about x, y, z), shape (N, 3).
    :raises ValueError: for fewer than 3 samples, mismatched shapes or times that do not
        increase.
    """
    times, poses = _sampled_poses(times, poses)
    return _body_rates(times, euler_zyx_to_matrix(poses[:, 3:]))


def _sampled_poses(times, poses):
    """Return ``times`` (N,) and ``poses`` (N, 6) as float arrays, or raise ``ValueError``."""
    times = np.asarray(times, dtype=float)
    poses = np.asarray(poses, dtype=float)
    if times.ndim != 1 or times.size < 3 or poses.shape != (times.size, 6):
        raise ValueError(f'times must be (N,) with N >= 3 and poses (N, 6), got {times.shape} '
                         f'and {poses.shape}')
    if not np.all(np.diff(times) > 0.0):
        raise ValueError('times must increase')
    return times, poses


def _body_rates(times, rotations):
    # Body rates over each interval, then their centred combination at each inner sample.
    steps = matrix_to_rotation_vector(np.swapaxes(rotations[:-1], -1, -2) @ rotations[1:])
    rates = (steps[:-1] + steps[1:]) / (times[2:, None] - times[:-2, None])
    return _pad(rates)


@dataclass(frozen=True)
class Perception:
    """
    One motion, raw and as perceived (N samples).

    :param times: seconds, (N,).
    :param specific_force: the raw specific force, with gravity (``[0, 0, g]`` at rest),
        m/s^2, head frame, (N, 3).
    :param angular_velocity: the raw angular velocity, rad/s, head frame, (N, 3).
    :param perceived_force: the otoliths' output, specific force relative to rest, m/s^2,
        (N, 3).
    :param perceived_rate: the canals' output, rad/s, (N, 3).
    :param thresholds: the perception thresholds ``[f_x, f_y, f_z]`` (m/s^2) then
        ``[w_x, w_y, w_z]`` (rad/s), (6,).
    :param gravity: m/s^2, the rest removed from the raw force.
    """

    times: np.ndarray
    specific_force: np.ndarray
    angular_velocity: np.ndarray
    perceived_force: np.ndarray
    perceived_rate: np.ndarray
    thresholds: np.ndarray
    gravity: float = STANDARD_GRAVITY

    @property
    def raw(self) -> np.ndarray:
        """Return the raw motion relative to rest, ``[f - [0, 0, g], w]``, (N, 6)."""
        return np.concatenate([self.specific_force - [0.0, 0.0, self.gravity],
                               self.angular_velocity], axis=1)

    @property
    def perceived(self) -> np.ndarray:
        """Return the perceived motion ``[f_hat, w_hat]``, (N, 6)."""
        return np.concatenate([self.perceived_force, self.perceived_rate], axis=1)


def perception(times, specific_force, angular_velocity, gravity: float = STANDARD_GRAVITY,
               otoliths: OtolithModel = OTOLITHS, canals: CanalModel = CANALS) -> Perception:
    """
    Return a motion, raw and through the vestibular model (:func:`.vestibular.perceive`).

    The same call serves the vehicle (its input: what an IMU at the driver's head reads) and
    the platform (the motion felt at the head, :func:`perceived_motion`), so the two compare
    as one person would perceive them. The filters start at rest.

    :param times: seconds, shape (N,), increasing.
    :param specific_force: m/s^2, head frame, with gravity, (N, 3).
    :param angular_velocity: rad/s, head frame, (N, 3).
    :raises ValueError: for mismatched shapes, times that do not increase or a value that is
        not finite.
    """
    force, rate = perceive(times, specific_force, angular_velocity, gravity, otoliths, canals)
    return Perception(times=np.asarray(times, dtype=float),
                      specific_force=np.asarray(specific_force, dtype=float),
                      angular_velocity=np.asarray(angular_velocity, dtype=float),
                      perceived_force=force, perceived_rate=rate,
                      thresholds=perception_thresholds(otoliths, canals), gravity=gravity)


def _pad(inner: np.ndarray) -> np.ndarray:
    """Repeat the first and last rows of the inner samples at both ends."""
    return np.concatenate([inner[:1], inner, inner[-1:]])


class PerceptionEstimator:
    """
    The specific force at the head, estimated as the poses stream in.

    Each new pose gives the value at the sample before it (the centred difference needs the
    next sample): :meth:`update` returns ``(label, specific_force)`` of that sample.

    :param head_position: platform frame, metres, shape (3,).
    :param gravity: m/s^2.
    """

    def __init__(self, head_position, gravity: float = STANDARD_GRAVITY):
        self.head_position = np.asarray(head_position, dtype=float)
        self.gravity = gravity
        self._samples = []

    def reset(self) -> None:
        """Forget the samples so far."""
        self._samples = []

    def update(self, time: float, pose, label=None):
        """
        Add a pose at ``time`` (seconds, increasing); return the previous sample's force.

        :param label: what to return with that sample's force (default: its time), such as
            the time stamp of the input it answered.
        :returns: ``(label, specific_force)`` of the previous sample, or ``None`` until three
            samples have come.
        """
        rotation = euler_zyx_to_matrix(np.asarray(pose[3:], dtype=float))
        head = np.asarray(pose[:3], dtype=float) + rotation @ self.head_position
        self._samples.append((time, head, rotation, time if label is None else label))
        if len(self._samples) > 3:
            del self._samples[0]
        if len(self._samples) < 3:
            return None
        (t0, h0, _, _), (t1, h1, r1, label1), (t2, h2, _, _) = self._samples
        acceleration = second_derivative(t0, t1, t2, h0, h1, h2)
        return label1, specific_force(r1, acceleration, self.gravity)
