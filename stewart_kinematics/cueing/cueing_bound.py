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
The clairvoyant optimum of a cue along one horizontal axis: a lower bound on its perceived RMSE.

Along x (surge with pitch tilt) or y (sway with roll tilt), the specific force felt at the head
is ``f = a + g s``: ``a`` the translational term (the head's acceleration, base frame; the
tangential and centripetal terms of the tilt are in it, since the head is a point of the
platform) and ``s`` the gravity term (``-sin(beta)`` along x; ``sin(alpha) cos(beta)`` along
y, from ``R^T [0, 0, g]`` with ZYX angles). The whole drive is known in advance; the
decision variables, one per step of ``step`` seconds, are ``a`` and the rate of ``s``
(``r``), each held over its step; the states the head's position ``h`` and velocity ``v``,
``s``, and the otoliths' two states, all starting at rest at neutral. The cost is the mean
square of the perceived platform force (Young and Meiry's otolith, :mod:`.vestibular`, the
evaluator's, discretised exactly for a force held over each step) against the vehicle's
perceived force sampled at the steps. Constraints, each a relaxation of a real limit
(:class:`AxisLimits`): ``|s| <= sin(tilt)``, ``|r| <= tilt_rate`` (``|d sin / dt| <= |rate|``;
along y ``|d(sin(alpha) cos(beta))/dt| <= max(|alpha'|, |beta'|)``), ``|h|`` within the
head's outer travel box, ``|v|`` and ``|a|`` within what the legs' velocity and acceleration
allow (an outer bound, computed by the caller). The two axes are solved apart: dropping the
coupling between them (they share the legs) only enlarges the feasible set, so each axis'
optimum stays a lower bound. The problem is one dense QP per axis (DAQP, exact active set):
its optimum is the least RMSE any cueing can reach on that axis within those limits, up to
the grid (compare two steps) and to the one simplification stated in doc/motion_cueing_mpc.md
("Targets of issue 31"): ``a`` is taken in the base frame (the tilted seat sees it turned by
at most the tilt). Nothing here imports ROS.
"""

from dataclasses import dataclass
import math

import numpy as np

from stewart_kinematics.cueing.filters import expm
from stewart_kinematics.cueing.settings import STANDARD_GRAVITY
from stewart_kinematics.cueing.vestibular import OtolithModel, OTOLITHS, perceive

#: DAQP's infinity.
_INFINITY = 1e30
#: The Hessian's regularisation, relative to its mean diagonal.
REGULARISATION = 1e-9
#: DAQP's sense flag of an inequality.
_INEQUALITY = 0


@dataclass(frozen=True)
class AxisLimits:
    """
    The relaxed limits of one horizontal axis (``math.inf``: none).

    :param tilt: largest tilt, radians (``|s| <= sin(tilt)``).
    :param tilt_rate: largest rate of ``s``, per second (the tilt-rate limit, rad/s).
    :param position: largest distance of the head from neutral along the axis, metres.
    :param velocity: largest speed of the head along the axis, m/s.
    :param acceleration: largest acceleration of the head along the axis, m/s^2.
    """

    tilt: float
    tilt_rate: float
    position: float
    velocity: float = math.inf
    acceleration: float = math.inf


@dataclass(frozen=True)
class AxisBound:
    """
    The clairvoyant optimum of one axis.

    :param rmse: the optimum's perceived RMSE on the grid, m/s^2: the lower bound.
    :param fine_rmse: the optimum held over each step and perceived at the reference's own
        samples (the evaluator's way), m/s^2: how far the grid is from those samples.
    :param times: the grid's times, seconds, (K,).
    :param force: the platform's force along the axis, m/s^2, (K,).
    :param gravity_term: ``g s``, the tilt's share of it, m/s^2, (K,).
    :param position: the head's position, metres, (K,).
    :param velocity: the head's velocity, m/s, (K,).
    :param perceived: the platform's perceived force, m/s^2, (K,).
    :param reference: the vehicle's perceived force at the grid's times, m/s^2, (K,).
    :param status: DAQP's exit flag (1: optimal).
    :param iterations: DAQP's iterations.
    """

    rmse: float
    fine_rmse: float
    times: np.ndarray
    force: np.ndarray
    gravity_term: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    perceived: np.ndarray
    reference: np.ndarray
    status: int
    iterations: int


def otolith_matrix(step: float, count: int, otoliths: OtolithModel = OTOLITHS) -> np.ndarray:
    """
    Return ``P``, (count, count): perceived force at steps ``1..count`` from forces held.

    Force ``k`` is held over the step that ends at sample ``k`` (as :func:`.vestibular.perceive`
    holds each sample), the otolith starting at rest; ``P`` is lower triangular Toeplitz.

    :param step: seconds, > 0.
    """
    numerator, denominator = otoliths.transfer_function()
    # Controllable canonical form of N(s) / D(s), D monic of degree 2, N of degree 1.
    a = np.array([[0.0, 1.0], [-denominator[2], -denominator[1]]])
    b = np.array([0.0, 1.0])
    c = np.array([numerator[1], numerator[0]])
    augmented = np.zeros((3, 3))
    augmented[:2, :2] = a * step
    augmented[:2, 2] = b * step
    exponential = expm(augmented)
    phi, gamma = exponential[:2, :2], exponential[:2, 2]
    impulse = np.empty(count)
    state = gamma.copy()
    for index in range(count):
        impulse[index] = c @ state
        state = phi @ state
    rows, columns = np.indices((count, count))
    lags = rows - columns
    return np.where(lags >= 0, impulse[np.clip(lags, 0, None)], 0.0)


def axis_bound(times, perceived_reference, limits: AxisLimits, step: float,
               gravity: float = STANDARD_GRAVITY, otoliths: OtolithModel = OTOLITHS,
               max_iterations: int = 100000) -> AxisBound:
    """
    Solve the clairvoyant optimum of one axis (see the module).

    :param times: the reference's samples, seconds, (N,), evenly spaced from 0.
    :param perceived_reference: the vehicle's perceived force along the axis at ``times``
        (:func:`.perception.perception`'s ``perceived_force[:, axis]``), m/s^2, (N,).
    :param limits: the relaxed limits.
    :param step: the grid's step, seconds, a whole multiple of the samples' step.
    :param max_iterations: DAQP's iteration limit.
    :returns: an :class:`AxisBound`.
    :raises ValueError: for uneven samples, a step that is no multiple of theirs, a reference
        that is not finite or limits that are negative or NaN.
    """
    times = np.asarray(times, dtype=float)
    reference = np.asarray(perceived_reference, dtype=float)
    if times.ndim != 1 or times.size < 3 or reference.shape != times.shape:
        raise ValueError(f'times and the reference must be (N,) with N >= 3, got {times.shape} '
                         f'and {reference.shape}')
    if not (np.all(np.isfinite(times)) and np.all(np.isfinite(reference))):
        raise ValueError('times and the reference must be finite')
    sample = float(times[1] - times[0])
    if sample <= 0.0 or not np.allclose(np.diff(times), sample, rtol=1e-6, atol=0.0):
        raise ValueError('times must be evenly spaced and increasing')
    ratio = step / sample if math.isfinite(step) else math.nan
    if not (ratio >= 1.0 - 1e-9 and abs(ratio - round(ratio)) < 1e-6):
        raise ValueError(f'step must be a positive whole multiple of the sampling step '
                         f'{sample:g} s, got {step!r}')
    values = (limits.tilt, limits.tilt_rate, limits.position, limits.velocity,
              limits.acceleration)
    if any(math.isnan(value) or value < 0.0 for value in values):
        raise ValueError(f'limits must be >= 0 (inf: none), got {limits}')
    stride = int(round(ratio))
    fine = np.arange(stride, times.size, stride)
    count = fine.size
    target = reference[fine]
    lower = np.tril(np.ones((count, count)))
    # f = a + g s, s = step L r: force = [I, step L] u, u = [a; g r] (both m/s^2-sized).
    force_map = np.hstack([np.eye(count), step * lower])
    perception = otolith_matrix(step, count, otoliths) @ force_map
    # f depends on a + g s only: the Hessian is singular along the trades between them, and
    # DAQP (a dual method) needs it positive definite; REGULARISATION relative to its scale
    # makes it so and changes the optimum by about that share (doc: "Targets of issue 31").
    hessian = perception.T @ perception
    hessian += REGULARISATION * np.trace(hessian) / hessian.shape[0] * np.eye(hessian.shape[0])
    gradient = -perception.T @ target
    # h_k = sum_j a_j step^2 (k - j + 1/2), v_k = step sum_j a_j.
    lags = np.arange(count)[:, None] - np.arange(count)[None, :]
    position_rows = np.where(lags >= 0, step * step * (lags + 0.5), 0.0)
    zeros = np.zeros((count, count))
    rows = [np.hstack([zeros, step * lower]), np.hstack([position_rows, zeros])]
    bounds = [gravity * math.sin(min(limits.tilt, math.pi / 2.0)), limits.position]
    if math.isfinite(limits.velocity):
        rows.append(np.hstack([step * lower, zeros]))
        bounds.append(limits.velocity)
    a = np.vstack(rows)
    simple = np.r_[np.full(count, min(limits.acceleration, _INFINITY)),
                   np.full(count, min(gravity * limits.tilt_rate, _INFINITY))]
    general = np.repeat(np.minimum(bounds, _INFINITY), count)
    upper = np.r_[simple, general]
    sense = np.full(upper.size, _INEQUALITY, dtype=np.int32)
    import daqp  # imported here: the rest of the package does not need it
    model = daqp.Model()
    scale = 1.0 / count
    flag, _ = model.setup(np.ascontiguousarray(hessian * scale), gradient * scale,
                          np.ascontiguousarray(a), upper, -upper, sense)
    if flag < 0:
        raise RuntimeError(f'DAQP could not set up the problem (flag {flag})')
    model.settings = {'iter_limit': max_iterations}
    x, _, status, info = model.solve()
    x = np.asarray(x, dtype=float)
    acceleration, rate = x[:count], x[count:]
    gravity_term = step * (lower @ rate)
    force = acceleration + gravity_term
    perceived = perception @ x
    # The same motion at the reference's samples: a held over each step, s linear in it.
    held = np.zeros(times.size)
    grid_times = times[fine]
    sine = np.interp(times, np.r_[times[0], grid_times], np.r_[0.0, gravity_term])
    for index, end in enumerate(fine):
        held[end - stride + 1:end + 1] = acceleration[index]
    fine_force = held + sine
    forces = np.zeros((times.size, 3))
    forces[:, 0] = fine_force
    forces[:, 2] = gravity
    fine_perceived, _ = perceive(times, forces, np.zeros((times.size, 3)), gravity, otoliths)
    return AxisBound(
        rmse=float(np.sqrt(np.mean((perceived - target) ** 2))),
        fine_rmse=float(np.sqrt(np.mean((fine_perceived[:, 0] - reference) ** 2))),
        times=grid_times, force=force, gravity_term=gravity_term,
        position=position_rows @ acceleration, velocity=step * (lower @ acceleration),
        perceived=perceived, reference=target, status=int(status),
        iterations=int(info.get('iterations', 0)))
