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
The singularity margin: the condition number of the dimensionless Jacobian, at most a bound.

The Jacobian and its condition number are those of
:func:`stewart_kinematics.model.jacobians.jacobian_condition` (rows ``[u_i, (R p_i x u_i) /
rho]``), computed from the legs of the poses by
:func:`~stewart_kinematics.model.jacobians.dimensionless_jacobians`. About 10 at the paper
platform's home pose, ``inf`` at a singularity and for a leg of zero length. Nothing here
imports ROS.
"""

import math

import numpy as np

from stewart_kinematics.limits.base import Bound, Limit, PLATFORM, row_violations
from stewart_kinematics.limits.kind import BoundLook, LimitKind, LimitParameter
from stewart_kinematics.model.jacobians import (
    conditions_of_jacobians,
    dimensionless_jacobians,
    single_condition,
)
from stewart_kinematics.model.validators import InRange

#: Relative rounding allowance of the pivots of the proof (see :func:`proved_within`).
PIVOT_ROUNDING = 1e-13


class SingularityMargin(Limit):
    """
    Evaluator of ``max_jacobian_condition``: one value per pose, shape (1, n).

    A singular value decomposition a pose (the dearest check), so it is :attr:`dear`; with
    ``exact`` False, the poses that a cheaper test proves within the margin get NaN instead.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param allowed: the largest condition number, ``max_jacobian_condition``; ``inf`` (the
        default) is not set.
    """

    dear = True

    def __init__(self, geometry, allowed: float = math.inf):
        self._geometry = geometry
        self.bounds = (() if allowed == np.inf else
                       (Bound('max_jacobian_condition', allowed, True, PLATFORM, ''),))

    def values(self, arrays):
        """Condition numbers, shape (1, n)."""
        jacobians = dimensionless_jacobians(self._geometry, arrays.lengths, arrays.vectors)
        return (conditions_of_jacobians(jacobians)[None, :],)

    def violations_of_one(self, legs):
        """
        See :meth:`Limit.violations_of_one`: the Jacobian's rows in floats, one 6x6 SVD.

        The rows of :func:`~stewart_kinematics.model.formulas.float_twist_rows` and
        :func:`~stewart_kinematics.model.jacobians.single_singular_values`, the one-pose path
        of the same formulas as :meth:`values` (forward kinematics results use it too).
        """
        if legs.floats is None:
            return super().violations_of_one(legs)
        (bound,) = self.bounds
        return row_violations(bound, (single_condition(self._geometry, legs.floats),))

    def evaluate(self, arrays, exact=True):
        """See :meth:`Limit.evaluate`; inexact: NaN (not broken) where proved within."""
        if exact:
            return super().evaluate(arrays)
        (bound,) = self.bounds
        jacobians = dimensionless_jacobians(self._geometry, arrays.lengths, arrays.vectors)
        conditions = np.full(arrays.count, np.nan)
        doubtful = ~proved_within(jacobians, bound.allowed)
        conditions[doubtful] = conditions_of_jacobians(jacobians[doubtful])
        conditions = conditions[None, :]
        return ((conditions, doubtful[None, :] & bound.broken(conditions)),)


def proved_within(jacobians, bound: float) -> np.ndarray:
    """
    Where the condition number of each Jacobian is proved below ``bound``, without an SVD.

    With ``G = J^T J`` and ``U >= lambda_max(G)`` (the smaller of its Frobenius and row-sum
    norms), ``G - (U / bound^2) I`` positive definite (its LDL^T pivots, computed for every
    Jacobian at once, all positive) gives ``lambda_min > U / bound^2``, so the condition
    number ``sqrt(lambda_max / lambda_min)`` is below ``bound``. Most poses are far from the
    bound: this costs a fraction of a singular value decomposition.

    :param jacobians: shape (n, 6, 6).
    :returns: shape (n,), True where proved; False proves nothing.
    """
    gram = np.swapaxes(jacobians, -1, -2) @ jacobians
    upper = np.minimum(np.sqrt(np.sum(gram * gram, axis=(-2, -1))),
                       np.abs(gram).sum(axis=-1).max(axis=-1))
    # The second term covers the rounding of the pivots (about 1e-15 U).
    shifted = gram - (upper / bound ** 2 + PIVOT_ROUNDING * upper)[:, None, None] * np.eye(6)
    proved = np.ones(shifted.shape[0], dtype=bool)
    for j in range(6):
        pivot = shifted[:, j, j]
        proved &= pivot > 0.0
        column = shifted[:, j + 1:, j] / np.where(pivot > 0.0, pivot, 1.0)[:, None]
        shifted[:, j + 1:, j + 1:] -= column[:, :, None] * shifted[:, None, j, j + 1:]
    return proved


def _narrowed(limits, margins) -> dict:
    """Draw the margin, if set, in to its share ``margins.condition`` (never below 1)."""
    if not math.isfinite(limits.max_jacobian_condition):
        return {}
    return {'max_jacobian_condition': max(1.0, limits.max_jacobian_condition * margins.condition)}


def _evaluator(geometry, limits) -> SingularityMargin:
    return SingularityMargin(geometry, limits.max_jacobian_condition)


#: The singularity margin: its parameter, bound and evaluator.
KIND = LimitKind(
    name='singularity',
    title='Singularity margin',
    meaning=('Condition number of the dimensionless Jacobian `[u_i, (R p_i x u_i) / rho]` '
             "(`rho`: RMS radius of the platform joints). About 10 at the paper platform's "
             'home pose, 17 at the end of Table 3; it grows without bound near a singularity.'),
    evaluator='SingularityMargin',
    parameters=(
        LimitParameter(
            'max_jacobian_condition', '', math.inf,
            'Singularity margin: largest condition number of the dimensionless Jacobian '
            "(1 is ideal, about 10 at the paper platform's home pose); .inf for no limit",
            (InRange(1.0, math.inf),)),
    ),
    bounds=(BoundLook('max_jacobian_condition', 'singularity margin', (0.58, 0.4, 0.74),
                      relative=True),),
    pose_evaluator=_evaluator,
    narrowed=_narrowed,
)
