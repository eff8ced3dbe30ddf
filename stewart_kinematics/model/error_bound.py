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
The proven bound on the distance from a forward kinematics solution to the exact pose.

:attr:`ForwardKinematicsResult.pose_error_bound
<stewart_kinematics.ForwardKinematicsResult.pose_error_bound>` gives the proof (Kantorovich's
radius from the residual, the rounding floor, the smallest singular value of the dimensionless
Jacobian and the curvature of the leg lengths); this module computes it, for one solve in floats
(:func:`single_pose_error_bound`, fk_node's case, per message) and for a batch in arrays
(:func:`pose_error_bounds`), with the same figures. Metres and radians.
"""

from dataclasses import dataclass
import math
import weakref

import numpy as np

#: Rounding floor of a computed leg length, in units of the last place of ``|t| + |p_i| +
#: |b_i|`` (the sizes of the terms summed in the leg vector): the residual of a solve is known
#: no better than this (see ForwardKinematicsResult.pose_error_bound).
LENGTH_ROUNDING_ULPS = 16.0
#: Rounding of a computed smallest singular value, in units of the largest one's last place.
SINGULAR_VALUE_ROUNDING_ULPS = 64.0


@dataclass(frozen=True)
class _ErrorBoundTerms:
    """
    The per-leg figures of :attr:`ForwardKinematicsResult.pose_error_bound`, as floats.

    ``arms`` |p_i|, ``base_norms`` |b_i|, ``reaches`` c_i = sqrt(1 + |p_i|^2 / rho^2).
    """

    arms: list
    base_norms: list
    reaches: list


#: The terms of each geometry still alive; a Geometry is immutable, so they never go stale.
_TERMS = weakref.WeakKeyDictionary()


def _terms(geometry) -> _ErrorBoundTerms:
    """Return the per-leg figures of ``geometry``'s bounds, computed on its first use."""
    try:
        return _TERMS[geometry]
    except KeyError:
        arms = np.linalg.norm(geometry.platform_joints, axis=-1)
        terms = _TERMS[geometry] = _ErrorBoundTerms(
            arms.tolist(), np.linalg.norm(geometry.base_joints, axis=-1).tolist(),
            np.sqrt(1.0 + (arms / geometry.platform_radius) ** 2).tolist())
        return terms


def pose_error_bounds(geometry, pose, lengths, residual, converged, singular_values):
    """
    :attr:`ForwardKinematicsResult.pose_error_bound` of a batch of solves, in arrays.

    :param pose: the solutions, shape (N, 6); ``lengths``: the lengths solved for, (N, 6).
    :param residual: the solves' residuals, metres, (N,); ``converged``: bools, (N,).
    :param singular_values: the singular values of the dimensionless Jacobian at each
        solution, largest first, (N, 6) (:func:`~.jacobians.singular_values_of`).
    :returns: metres and radians, (N,); ``inf`` where no bound is proven.
    """
    lengths = np.asarray(lengths, dtype=float)
    pose = np.asarray(pose, dtype=float)
    rho = geometry.platform_radius
    arms = np.linalg.norm(geometry.platform_joints, axis=-1)            # |p_i|, (6,)
    sizes = (np.linalg.norm(pose[..., None, :3], axis=-1) + arms
             + np.linalg.norm(geometry.base_joints, axis=-1))         # (..., 6)
    eps = np.finfo(float).eps
    error = residual + LENGTH_ROUNDING_ULPS * eps * np.max(sizes, axis=-1)
    sigma = singular_values[..., -1] - SINGULAR_VALUE_ROUNDING_ULPS * eps * (
        singular_values[..., 0])
    reach = np.sqrt(1.0 + (arms / rho) ** 2)                          # c_i, (6,)
    with np.errstate(divide='ignore', invalid='ignore', over='ignore'):
        eta = math.sqrt(6.0) * error / sigma
        # The legs' shortest lengths within the largest ball considered, 2 eta.
        shortest = (lengths - np.asarray(residual)[..., None]
                    - 2.0 * np.asarray(eta)[..., None] * reach)
        curvature = np.sqrt(np.sum(np.square(
            reach ** 2 / shortest + arms / rho ** 2), axis=-1))
        h = eta * curvature / sigma
        radius = 2.0 * eta / (1.0 + np.sqrt(np.maximum(1.0 - 2.0 * h, 0.0)))
        proven = (np.asarray(converged) & (sigma > 0.0) & (h <= 0.5)
                  & np.all(shortest > 0.0, axis=-1) & (radius >= 0.0))
        bound = np.where(proven, radius * max(1.0, 1.0 / rho), np.inf)
    return float(bound) if bound.ndim == 0 else bound


def single_pose_error_bound(geometry, pose, lengths, residual, converged, singular_values):
    """
    :attr:`ForwardKinematicsResult.pose_error_bound` of one solve, the same proof in floats.

    :param pose: the solution, six floats; ``lengths``: the six lengths solved for.
    :param singular_values: :func:`~.jacobians.single_singular_values` at the pose.
    """
    if not converged:
        return math.inf
    terms = _terms(geometry)
    rho = geometry.platform_radius
    sigma = singular_values[-1] - SINGULAR_VALUE_ROUNDING_ULPS * _EPSILON * singular_values[0]
    if not sigma > 0.0:
        return math.inf
    offset = math.hypot(*pose[:3])
    error = residual + LENGTH_ROUNDING_ULPS * _EPSILON * max(
        offset + arm + base for arm, base in zip(terms.arms, terms.base_norms))
    eta = math.sqrt(6.0) * error / sigma
    # The legs' shortest lengths within the largest ball considered, 2 eta.
    shortest = [length - residual - 2.0 * eta * reach
                for length, reach in zip(lengths, terms.reaches)]
    if not min(shortest) > 0.0:
        return math.inf
    curvature = math.sqrt(sum((reach * reach / length + arm / (rho * rho)) ** 2
                              for reach, length, arm in zip(terms.reaches, shortest, terms.arms)))
    h = eta * curvature / sigma
    if not h <= 0.5:
        return math.inf
    radius = 2.0 * eta / (1.0 + math.sqrt(max(1.0 - 2.0 * h, 0.0)))
    return radius * max(1.0, 1.0 / rho) if radius >= 0.0 else math.inf


#: The machine epsilon of a float.
_EPSILON = float(np.finfo(float).eps)
