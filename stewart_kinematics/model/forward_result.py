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
The outcome of a forward kinematics solve, and the figures computed from it on demand.

:class:`ForwardKinematicsResult` holds the pose, whether the solve converged, its iterations,
residual and reason; the condition number and the sign of the Jacobian at the pose (which side
of the singularity surface it lies on) and the proven error bound (:mod:`.error_bound`) are
computed on first access.
"""

from dataclasses import dataclass, field
from functools import cached_property
import math
from typing import Tuple, Union

import numpy as np

from stewart_kinematics.model.error_bound import pose_error_bounds, single_pose_error_bound
from stewart_kinematics.model.jacobians import (
    condition_number,
    dimensionless,
    single_dimensionless_jacobian,
    single_singular_values,
    singular_values_of,
    twist_jacobian,
)
from stewart_kinematics.model.rotations import euler_zyx_to_matrix


@dataclass(frozen=True, eq=False)
class ForwardKinematicsResult:
    """
    Outcome of :func:`forward_kinematics`, for one solve or a batch.

    For one solve the fields are scalars and ``pose`` has shape (6,); for a batch of N they are
    arrays of length N and ``pose`` has shape (N, 6). Results compare with ``==`` field by
    field (``pose``, ``converged``, ``iterations``, ``residual``, ``reason``) and are
    hashable; the pose a solve returns is read-only.

    :param pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians) of the last iterate; the
        solution where ``converged``, with ``beta`` in [-pi/2, pi/2] and the other angles in
        (-pi, pi].
    :param converged: True where every leg length is within the tolerance.
    :param iterations: Newton-Raphson steps taken.
    :param residual: largest leg length error ``max_i |l_i(pose) - lengths_i|``, metres.
    :param reason: ``''`` where converged, else why not (iteration limit, singular Jacobian,
        divergence).

    Three more figures are computed on first access (a singular value decomposition and a
    determinant, that a solve does not pay for) and kept: :attr:`condition`,
    :attr:`pose_error_bound` and :attr:`jacobian_sign`.
    """

    pose: np.ndarray
    converged: Union[bool, np.ndarray]
    iterations: Union[int, np.ndarray]
    residual: Union[float, np.ndarray]
    reason: Union[str, Tuple[str, ...]]
    #: ``(geometry, lengths, jacobian_inverse)``: the geometry and the leg lengths solved for,
    #: for :attr:`condition` and :attr:`pose_error_bound`; for one solve, the inverse of the
    #: twist Jacobian (nested lists) at the last iterate that needed one, so that a solve
    #: started from this result (tracking) begins with it instead of computing one at a pose
    #: only microns away. One field: each field costs a frozen dataclass time to build.
    _solve: tuple = field(default=(None, None, None), repr=False)

    def _fields(self):
        return (self.pose, self.converged, self.iterations, self.residual, self.reason)

    def __eq__(self, other):
        if not isinstance(other, ForwardKinematicsResult):
            return NotImplemented
        return all(np.array_equal(mine, theirs, equal_nan=isinstance(mine, (float, np.ndarray)))
                   if not isinstance(mine, (str, tuple)) else mine == theirs
                   for mine, theirs in zip(self._fields(), other._fields()))

    def __hash__(self):
        pose, converged, iterations, residual, reason = self._fields()
        return hash((_hashable(pose), _hashable(converged, bool), _hashable(iterations, int),
                     _hashable(residual), reason))

    @cached_property
    def _jacobian(self):
        """Return the dimensionless Jacobian at :attr:`pose`, and where it has a zero row."""
        pose = self.pose
        if pose.ndim == 1:
            return single_dimensionless_jacobian(self._solve[0], pose.tolist())
        jacobians = dimensionless(self._solve[0], twist_jacobian(
            self._solve[0], pose[..., :3], euler_zyx_to_matrix(pose[..., 3:])))
        return jacobians, np.any(np.all(jacobians == 0.0, axis=-1), axis=-1)

    @cached_property
    def _singular_values(self):
        if self.pose.ndim == 1:
            return single_singular_values(*self._jacobian)
        return singular_values_of(self._jacobian[0])

    @cached_property
    def jacobian_sign(self) -> Union[int, np.ndarray]:
        """
        Sign of the Jacobian's determinant at :attr:`pose`: +1, -1, or 0 at a singularity.

        Which side of the singularity surface the pose lies on: along a path of poses it
        changes only where the path crosses a singularity (``det J = 0``), so two solutions of
        opposite signs are not joined by a path that avoids one. The determinant of the
        dimensionless twist Jacobian (:func:`jacobian_condition`'s: the same sign as the twist
        Jacobian's, whose rotation columns are divided by a positive ``rho``); 0
        where a leg has zero length. Near a singularity (condition numbers of 1e13 and more)
        rounding may give either sign. An int for one solve, an array (N,) for a batch.
        """
        jacobian, zero_row = self._jacobian
        if self.pose.ndim == 1:
            determinant = 0.0 if zero_row else float(np.linalg.det(jacobian))
            return (determinant > 0.0) - (determinant < 0.0)
        return np.where(zero_row, 0, np.sign(np.linalg.det(jacobian))).astype(int)

    @cached_property
    def condition(self) -> Union[float, np.ndarray]:
        """
        Condition number of the dimensionless Jacobian at :attr:`pose`.

        The definition of :func:`jacobian_condition`: about 10 at the paper platform's home,
        growing without bound towards a singularity, ``inf`` at one. A float for one solve, an
        array (N,) for a batch.
        """
        if self.pose.ndim == 1:
            largest, smallest = self._singular_values[0], self._singular_values[-1]
            if smallest == 0.0:
                return math.inf if largest else math.nan
            return largest / smallest
        return condition_number(self._singular_values)

    @cached_property
    def pose_error_bound(self) -> Union[float, np.ndarray]:
        """
        Proven bound on the distance from :attr:`pose` to the nearest exact pose of the lengths.

        One number in metres and radians: the larger of the position error (m) and the
        rotation angle error (rad) to the pose whose leg lengths are exactly the given ones,
        the one nearest to :attr:`pose`. Near a fold singularity the same lengths have a second
        pose close by (another assembly mode, across the fold): that one is not bounded, and
        the bound is ``inf`` when the two cannot be told apart (below).

        The proof, in the coordinates ``z = (dt, rho phi)`` of a move from :attr:`pose` (``dt``
        the position change, ``phi`` the rotation vector, ``rho`` the platform radius): the
        leg lengths are ``l(z) = l(0) + J z + q(z)`` with ``J`` the dimensionless Jacobian
        (:func:`jacobian_condition`), smallest singular value ``sigma``, and each
        ``|q_i(z)| <= M_i |z|^2 / 2``, where ``M_i = c_i^2 / l_i' + |p_i| / rho^2`` bounds the
        second derivative of leg ``i`` along any line in the ball (``c_i = sqrt(1 + |p_i|^2 /
        rho^2)``, ``l_i'`` the leg's shortest length in the ball). With the leg length error
        ``e`` (the residual plus the rounding floor, ``LENGTH_ROUNDING_ULPS`` units in the last
        place of ``|t| + |p_i| + |b_i|``), ``eta = sqrt(6) e / sigma`` and ``h = eta M /
        sigma`` (``M`` the 2-norm of the ``M_i``), the map ``z -> -J^-1 (l(0) - lengths +
        q(z))`` sends the ball of radius ``r = 2 eta / (1 + sqrt(1 - 2 h))`` into itself when
        ``h <= 1/2`` (Kantorovich's condition), so it holds an exact solution (Brouwer), and
        ``|dt| <= r``, ``|phi| <= r / rho``. The bound is ``r max(1, 1 / rho)``, at most twice
        the first-order figure ``eta max(1, 1 / rho)``. Where ``h > 1/2`` no ball is proven
        to hold a solution (the residual is too large for the curvature near a singularity):
        ``inf``. ``sigma`` is lowered by its rounding, ``SINGULAR_VALUE_ROUNDING_ULPS`` units
        in the last place of the largest singular value.

        On the paper's platform, within +-0.1 m and +-15 degrees of home: 5e-13 for the median
        pose, up to 1e-10 where the residual is just under the default tolerance; 4e-9 at 1e-3
        rad from the singularity at a yaw of 90.38 degrees, and ``inf`` within about 1e-5 rad
        of it, where a residual of 1e-13 m can leave converged solves microns off. ``inf`` at a
        singularity and where the solve did not converge. A float for one solve, an array
        (N,) for a batch.
        """
        geometry, lengths, _ = self._solve
        if self.pose.ndim == 1:
            return single_pose_error_bound(
                geometry, self.pose.tolist(), np.asarray(lengths, dtype=float).tolist(),
                float(self.residual), bool(self.converged), self._singular_values)
        return pose_error_bounds(geometry, self.pose, lengths, self.residual, self.converged,
                                 self._singular_values)


def _hashable(value, dtype=float):
    """Bytes of a value or array, equal for values that compare equal (-0.0 and 0.0, NaNs)."""
    array = np.asarray(value, dtype=dtype)
    if dtype is float:
        array = np.where(np.isnan(array), np.nan, array + 0.0)
    return array.shape, array.tobytes()
