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
The model-predictive cueing's quadratic programme, solved warm-started with DAQP.

``minimise 0.5 x^T H x + g^T x`` subject to ``bounds_lower <= x <= bounds_upper`` and
``lower <= A x <= upper`` (rows with ``lower == upper`` are equalities), ``H`` fixed, the rest
new each sample. DAQP (Arnstrom, Bemporad and Axehill 2022, *A dual active-set solver for
embedded quadratic programming using recursive LDL^T updates*, IEEE TAC 67(8)) was chosen by
measurement on this very QP against OSQP and ProxQP (doc/motion_cueing_mpc.md, "Solver"); its
workspace (:class:`daqp.Model`) is set up once and warm-started from the last active set.
Nothing here imports ROS.
"""

from dataclasses import dataclass

import numpy as np

#: DAQP's sense flags: an inequality, an equality, a soft inequality.
_INEQUALITY, _EQUALITY, _SOFT = 0, 5, 8
#: DAQP's weight of a soft constraint's violation (its ``rho_soft``: the reciprocal of the
#: quadratic weight): small, so a soft row gives way only where no plan keeps it.
SOFT_WEIGHT = 1e-6


@dataclass(frozen=True)
class QpResult:
    """
    One solve.

    :param x: the solution, shape (n,), or ``None`` when not solved.
    :param solved: whether an optimal solution was found.
    :param iterations: the solver's iterations.
    :param status: the solver's exit flag (DAQP: 1 optimal, 2 soft optimal, < 0 failed:
        -1 infeasible, -2 cycling, -3 unbounded, -4 iteration limit, -5 not convex, -6 not
        set up).
    """

    x: np.ndarray
    solved: bool
    iterations: int
    status: int


class QpSolver:
    """
    A warm-started DAQP workspace for QPs of one Hessian and one shape.

    :param hessian: ``H``, shape (n, n), symmetric positive definite.
    :param max_iterations: the solver's iteration limit.
    :param hard_rows: rows of ``A`` (the first ones) that must hold; the rows after them are
        soft: violated, at a high cost, only where nothing keeps them (``None``: all hard).
    :param bounds: the number of simple bounds (``n``).
    """

    def __init__(self, hessian, max_iterations: int = 1000, hard_rows=None, bounds=None):
        import daqp   # here: only cueing_method mpc needs it
        self._daqp = daqp
        self.hessian = np.ascontiguousarray(hessian, dtype=float)
        self.max_iterations = int(max_iterations)
        self.hard_rows = hard_rows
        self.bounds = self.hessian.shape[0] if bounds is None else bounds
        self.reset()

    def reset(self) -> None:
        """Forget the warm start: the next solve sets the workspace up anew."""
        self._model = None

    def solve(self, gradient, a, lower, upper, bounds_lower, bounds_upper) -> QpResult:
        """
        Solve one QP; never raises for non-finite data (it is not solved instead).

        :param gradient: ``g``, shape (n,).
        :param a: ``A``, shape (m, n).
        :param lower: shape (m,).
        :param upper: shape (m,).
        :param bounds_lower: shape (n,).
        :param bounds_upper: shape (n,).
        """
        blower = np.ascontiguousarray(np.concatenate([bounds_lower, lower]), dtype=float)
        bupper = np.ascontiguousarray(np.concatenate([bounds_upper, upper]), dtype=float)
        a = np.ascontiguousarray(a, dtype=float)
        gradient = np.ascontiguousarray(gradient, dtype=float)
        if not (np.all(np.isfinite(gradient)) and np.all(np.isfinite(a))
                and not np.any(np.isnan(blower)) and not np.any(np.isnan(bupper))):
            return QpResult(None, False, 0, -100)
        sense = np.where(blower == bupper, _EQUALITY, _INEQUALITY).astype(np.int32)
        if self.hard_rows is not None:
            sense[self.bounds + self.hard_rows:] = _SOFT
        if self._model is None:
            self._model = self._daqp.Model()
            flag, _ = self._model.setup(self.hessian, gradient, a, bupper, blower, sense)
            if flag < 0:
                self._model = None
                return QpResult(None, False, 0, int(flag))
            self._model.settings = {'iter_limit': self.max_iterations, 'rho_soft': SOFT_WEIGHT}
        else:
            self._model.update(f=gradient, A=a, bupper=bupper, blower=blower, sense=sense)
        x, _, flag, info = self._model.solve()
        iterations = int(info.get('iterations', 0))
        solved = flag > 0 and np.all(np.isfinite(x))
        if not solved:
            self._model = None   # start the next one cold
        return QpResult(np.array(x, dtype=float) if solved else None, bool(solved), iterations,
                        int(flag))
