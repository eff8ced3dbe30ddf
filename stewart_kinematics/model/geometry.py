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
The platform's geometry: joint positions, home pose, and where the platform may be (limits).

Frames: the base frame is fixed, with its origin on the base and z up; the platform frame moves
with the platform. A pose ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) places the platform
frame at ``(X, Y, Z)`` in the base frame, rotated by ``R = Rz(gamma) Ry(beta) Rx(alpha)``.
Leg ``i`` runs from base joint ``b_i`` (base frame) to platform joint ``p_i`` (platform frame).
"""

from dataclasses import dataclass, field
import math

import numpy as np

from stewart_kinematics.model import limit_bounds
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.model.validators import first_reason

#: Two joints closer than this (metres) count as one: a leg pair would be degenerate.
MIN_JOINT_SEPARATION = 1e-6
#: Joints whose spread off their best-fit line is below this (metres) count as collinear.
MIN_JOINT_SPREAD = 1e-6
#: The rules of each limit: those of its parameter, angles converted to radians.
_LIMIT_RULES = {
    'leg_length_min': limit_bounds.LEG_LENGTH_MIN,
    'leg_length_max': limit_bounds.LEG_LENGTH_MAX,
    'base_joint_max_angle': tuple(rule.converted(math.radians)
                                  for rule in limit_bounds.JOINT_MAX_ANGLE_DEG),
    'platform_joint_max_angle': tuple(rule.converted(math.radians)
                                      for rule in limit_bounds.JOINT_MAX_ANGLE_DEG),
    'max_jacobian_condition': limit_bounds.MAX_JACOBIAN_CONDITION,
    'leg_radius': limit_bounds.LEG_RADIUS,
}


@dataclass(frozen=True, eq=False)
class Geometry:
    """
    A 6-6 Gough-Stewart platform, validated on construction.

    :param base_joints: b_1..b_6 in the base frame, metres, shape (6, 3).
    :param platform_joints: p_1..p_6 in the platform frame, metres, shape (6, 3).
    :param home_pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) of the neutral pose.
    :param leg_length_min: shortest allowed leg length, metres (0 for no limit).
    :param leg_length_max: longest allowed leg length, metres (``inf`` for no limit).
    :param base_joint_max_angle: largest angle between a leg and its home direction at the
        base joint, radians, in (0, pi] (pi for no limit).
    :param platform_joint_max_angle: the same at the platform joint, in the platform frame.
    :param max_jacobian_condition: largest allowed condition number of the dimensionless
        Jacobian (:func:`stewart_kinematics.model.jacobians.jacobian_condition`), >= 1
        (``inf`` for no limit): the singularity margin.
    :param leg_radius: radius of each leg, metres, in [0, 1] (0 for no collision check): a leg
        is a capsule of this radius around the segment from its base joint to its platform
        joint, and two legs collide where their segments come closer than ``2 * leg_radius``.
    :raises ValueError: if an array has the wrong shape or a non-finite value, two joints
        coincide, the joints of the base or of the platform are collinear, a limit is out of
        its range (the range of its parameter, :mod:`stewart_kinematics.model.limit_bounds`),
        or the home pose breaks a limit (two legs that collide there included, named).

    The limits are checked by :mod:`stewart_kinematics.limits`.

    >>> from stewart_kinematics import load_geometry
    >>> geometry = load_geometry('config/paper_platform.yaml')
    >>> geometry.home_leg_lengths.round(6)
    array([0.718855, 0.718855, 0.701146, 0.718855, 0.718855, 0.718855])
    """

    base_joints: np.ndarray
    platform_joints: np.ndarray
    home_pose: np.ndarray = field(default_factory=lambda: np.zeros(6))
    leg_length_min: float = 0.0
    leg_length_max: float = math.inf
    base_joint_max_angle: float = math.pi
    platform_joint_max_angle: float = math.pi
    max_jacobian_condition: float = math.inf
    leg_radius: float = 0.0

    def __post_init__(self):
        for name, shape in (('base_joints', (6, 3)), ('platform_joints', (6, 3)),
                            ('home_pose', (6,))):
            array = _checked_array(name, getattr(self, name), shape)
            array.flags.writeable = False
            object.__setattr__(self, name, array)
        for name in ('base_joints', 'platform_joints'):
            _check_joint_layout(name, getattr(self, name))
        # The limits' rules are the parameters' (model/limit_bounds.py), angles in radians here.
        for name, rules in _LIMIT_RULES.items():
            object.__setattr__(self, name, _checked_limit(name, getattr(self, name), rules))
        if not self.leg_length_min < self.leg_length_max:
            raise ValueError(
                'leg length limits must satisfy leg_length_min < leg_length_max, got '
                f'leg_length_min={self.leg_length_min!r}, leg_length_max={self.leg_length_max!r}')

        # Derived once: every IK request and limit check uses them.
        from stewart_kinematics import limits
        from stewart_kinematics.model.inverse import leg_vectors_from_euler
        home_legs = leg_vectors_from_euler(self, self.home_pose)
        home_lengths = np.linalg.norm(home_legs, axis=-1)
        home_lengths.flags.writeable = False
        with np.errstate(invalid='ignore', divide='ignore'):  # NaN for a leg of zero length
            home_directions = home_legs / home_lengths[:, None]
        home_directions.flags.writeable = False
        centred = self.platform_joints - self.platform_joints.mean(axis=0)
        object.__setattr__(self, 'home_leg_lengths', home_lengths)
        object.__setattr__(self, 'home_leg_directions', home_directions)
        object.__setattr__(self, 'platform_radius',
                           float(np.sqrt(np.mean(np.sum(centred ** 2, axis=-1)))))
        home_violations = limits.check_pose(
            self, self.home_pose[:3], euler_zyx_to_matrix(self.home_pose[3:]))
        if home_violations:
            raise ValueError('the home pose breaks the limits: '
                             + '; '.join(str(v) for v in home_violations))


def _checked_limit(name, value, rules) -> float:
    """Return a limit as a float, or refuse what is not one number its rules allow, naming it."""
    array = as_float_array(value, name)
    if array.shape != ():
        raise ValueError(f'{name} must be one number, got {preview(value)}')
    reason = first_reason(rules, name, float(array))
    if reason:
        raise ValueError(reason)
    return float(array)


def _checked_array(name, value, shape):
    array = np.array(as_float_array(value, name))
    if array.shape != shape:
        raise ValueError(f'{name} must have shape {shape}, got {array.shape}')
    if not np.all(np.isfinite(array)):
        raise ValueError(f'{name} must be finite, got {array.tolist()}')
    return array


def _check_joint_layout(name, joints):
    separation = np.linalg.norm(joints[:, None, :] - joints[None, :, :], axis=-1)
    separation[np.diag_indices(6)] = np.inf
    i, j = np.unravel_index(np.argmin(separation), separation.shape)
    if separation[i, j] < MIN_JOINT_SEPARATION:
        raise ValueError(
            f'{name}: joints {i + 1} and {j + 1} coincide ({separation[i, j]:.3g} m apart, '
            f'at least {MIN_JOINT_SEPARATION:g} m needed)')
    # The second singular value of the centred joints is their spread off the best-fit line.
    spread = np.linalg.svd(joints - joints.mean(axis=0), compute_uv=False)[1] / math.sqrt(6)
    if spread < MIN_JOINT_SPREAD:
        raise ValueError(
            f'{name}: the six joints are collinear (spread {spread:.3g} m off their common '
            f'line, at least {MIN_JOINT_SPREAD:g} m needed); the platform would be singular')
