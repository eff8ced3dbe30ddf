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
Retiming: the fastest timing of a path within every leg's velocity and acceleration limits.

:func:`retime` is time-optimal path parameterisation in leg space (TOPP-RA, the toppra
library): the leg lengths along the path, under per-leg velocity and acceleration limits,
starting and ending at rest.

It depends on the path and the limits only. The path is the curve through the waypoint poses
(:meth:`~stewart_kinematics.motion.pose_trajectory.PoseTrajectory.as_path`: repeated waypoints
merged, parameterised by leg travel; the times, velocities and accelerations given with the
waypoints are a timing, which retiming replaces). toppra's grid comes from that curve too: its
gridpoints are spread along the leg travel, closer where the legs' path curves
(:func:`gridpoints`), and put on the waypoints (where the curve's second derivative jumps) when
there are few of them. So the same path given with any timing, at any density, retimes to the
same duration.

Leg forces: when the geometry carries masses and sets ``leg_force_min`` or ``leg_force_max``
(:func:`~stewart_kinematics.motion.trajectory_forces.force_limits`), each leg's force along the
path is ``a(s) sdd + b(s) sd^2 + c(s)`` (linear in the path acceleration, quadratic in the
path speed: :func:`~stewart_kinematics.motion.trajectory_forces.force_coefficients`), which
is TOPP-RA's second-order constraint: toppra keeps it at every gridpoint, and the refinement
between them, as it does the velocity and acceleration limits. A path whose static force
``c(s)`` breaks a limit somewhere cannot be followed at any speed (the platform could not be
held there were it stopped): it is refused with a :class:`RetimingError` naming
``leg_force``, the bound, the legs and where. With every mass 0 no force is computed.

Units: metres, radians, seconds, newtons. Nothing here imports ROS.
"""

import math

import numpy as np

from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.velocities import leg_states
from stewart_kinematics.motion.pose_trajectory import PoseTrajectory, TimedTrajectory
from stewart_kinematics.motion.trajectory_forces import (
    force_coefficients,
    force_limits,
    sample_forces,
)

#: toppra's grid: this many gridpoints along a path whose legs do not curve ...
BASE_GRIDPOINTS = 300
#: ... and this many more per radian that the legs' path turns (in leg space) ...
GRIDPOINTS_PER_RADIAN = 40
#: ... and at most this many (toppra's time grows in proportion to them).
MAX_GRIDPOINTS = 1500
#: Waypoints are gridpoints too when there are at most this many.
MAX_WAYPOINT_GRIDPOINTS = 250
#: No two gridpoints are closer than this fraction of the path.
MIN_GRID_STEP = 1e-6
#: Smallest leg slope along the path (metres of leg per metre of path) that toppra sees: a
#: leg stopped exactly on a gridpoint is given this one (see _acceleration_constraint).
STOPPED_LEG_SLOPE = 1e-4
#: Largest squared path rate toppra's solver is given (its own MAXX): where no leg moves,
#: the velocity limit bounds nothing.
MAX_SQUARED_RATE = 1e4
#: Samples of the path that measure its length and curvature for the grid.
MEASURE_SAMPLES = 2048
#: Most times toppra solves again with lower limits where the motion between two gridpoints
#: exceeds them by more than REFINEMENT_TOLERANCE (relative), lowered by the excess times
#: REFINEMENT_MARGIN.
REFINEMENTS = 3
REFINEMENT_TOLERANCE = 1e-3
REFINEMENT_MARGIN = 1.002
#: The timing is stretched uniformly by what the refinements leave, times this: a margin for
#: the motion between the samples (1e-4 of each limit, a hundred times what it exceeds them
#: by there on the shipped examples).
FINAL_STRETCH_MARGIN = 1.0001
#: Largest stretch the refinement asks for a force beyond its limit (where the static force
#: is at the limit, no stretch is enough).
MAX_FORCE_STRETCH = 1e3
#: Samples of a refinement taken at once (between two looks at the cancel flag).
REFINEMENT_CHUNK = 2500


class RetimingError(ValueError):
    """
    No timing found: why, and where on the path.

    :param message: what failed, where (between which waypoints), and on which leg.
    :param cause: ``'limits'`` (none set), ``'path'`` (the leg path is not smooth enough
        there: its derivatives are not finite), ``'grid'`` (toppra's grid failed there) or
        ``'leg_force'`` (a static leg force beyond ``leg_force_min`` or ``leg_force_max``
        there: the path cannot be followed at any speed).
    :param details: ``(key, value)`` pairs for a :class:`~stewart_kinematics.findings.Finding`.
    """

    def __init__(self, message, cause, details=()):
        super().__init__(message)
        self.cause = cause
        self.details = (('cause', cause),) + tuple(details)


class Cancelled(Exception):
    """The caller asked the work to stop (see :func:`raise_if_cancelled`)."""


def raise_if_cancelled(cancel) -> None:
    """
    Raise :class:`Cancelled` if ``cancel`` (``None``, or an object with ``is_set()``) is set.

    A thread cannot be interrupted inside numpy or toppra, so the long computations of
    :mod:`stewart_kinematics.motion` (checks, retiming) are cut into bounded steps (a chunk of
    samples, the toppra solve of a bounded grid) and call this between two: a
    :class:`threading.Event` set by another thread (a node that stops, or a newer trajectory
    that replaces the one being checked) stops them within one step.
    """
    if cancel is not None and cancel.is_set():
        raise Cancelled('cancelled')


def load_retiming() -> None:
    """
    Import toppra (and scipy) now: the first import takes seconds, too long for a callback.

    A node that will retime calls this at start-up, so that its first trajectory is answered
    as fast as the next ones.
    """
    import toppra.algorithm  # noqa: F401
    import toppra.constraint  # noqa: F401


def retime(trajectory: PoseTrajectory, geometry, actuator_limits: ActuatorLimits,
           speed_scale: float = 1.0, *, sample_rate: float = 1000.0,
           cancel=None) -> TimedTrajectory:
    """
    Find the fastest timing of a path that keeps every leg within its velocity and acceleration.

    Time-optimal path parameterisation (TOPP-RA, toppra) of the leg lengths along the path
    through the trajectory's waypoint poses (:meth:`PoseTrajectory.as_path`), starting and
    ending at rest, under ``actuator_limits`` scaled by ``speed_scale`` (velocities by it,
    accelerations by its square: the optimal motion played ``1 / speed_scale`` times as long).

    toppra meets the limits at its gridpoints (:func:`gridpoints`); between two, where the
    legs' path curves, the motion may exceed them a little. So the timing is sampled as the
    check samples it (at ``sample_rate``, see :meth:`TimedTrajectory.sample_times`), and
    where a grid interval exceeds a limit, the limits at its two gridpoints are lowered by
    that excess and toppra solves again (at most :data:`REFINEMENTS` times): a local
    correction, which leaves the rest of the path at full speed. What is left (a tenth of a
    percent, typically) is removed by a uniform stretch, so that the result is within every
    leg limit at those samples; :func:`~stewart_kinematics.motion.planning.plan_motion` then
    checks it whole. With masses and a force limit (see the module's docstring), the dynamic
    leg forces are kept within ``leg_force_min`` and ``leg_force_max`` likewise (the limits
    themselves, not scaled by ``speed_scale``).

    :param trajectory: a path, or a timed trajectory whose timing is replaced.
    :param sample_rate: hertz, the rate at which the refinement samples the timing.
    :param cancel: ``None``, or an event: set, the work stops with :class:`Cancelled`.
    :raises RetimingError: if neither a velocity nor an acceleration limit is set (the fastest
        timing would take no time), a static leg force breaks a force limit somewhere on the
        path (cause ``'leg_force'``: the bound, the legs and where), or toppra finds no timing
        (the reason says where).
    :raises ValueError: if the waypoints do not make a path (see :meth:`PoseTrajectory.path`).
    """
    import toppra  # toppra pulls scipy: imported only by the motion that needs it.

    scaled = actuator_limits.scaled(speed_scale)
    if not scaled.limits_speed:
        raise RetimingError('retiming needs leg_velocity_max or leg_acceleration_max: without '
                            'them the fastest timing takes no time', 'limits')
    path = trajectory.as_path(geometry)
    raise_if_cancelled(cancel)
    toppra.setup_logging('CRITICAL')
    # toppra's path parameter s is the path's (the legs' travel) over a reference speed, so
    # that its rate stays near 1 whatever the limits (toppra's tolerances are absolute).
    length = float(path.times[-1] - path.times[0])
    speed = scaled.velocity_max if math.isfinite(scaled.velocity_max) else math.sqrt(
        scaled.acceleration_max * length)
    leg_path = _leg_path(path, geometry, speed, toppra.interpolator.AbstractGeometricPath)
    grid = gridpoints(path, leg_path, speed)
    raise_if_cancelled(cancel)
    states = leg_path.states(grid / speed)
    # The legs' curvature (second derivative in arc length, 1/m) at the gridpoints.
    curvatures = np.abs(states.accelerations) / (speed * speed)
    bad = ~np.all(np.isfinite(np.concatenate([states.velocities, states.accelerations],
                                             axis=-1)), axis=-1)
    if bad.any():
        raise _failure(path, grid, int(np.argmax(bad)), curvatures, 'path',
                       "the legs' path has no finite derivatives there")
    limits = force_limits(geometry)
    forces = None
    if limits is not None:
        coefficients = force_coefficients(geometry, path, grid, speed)
        _refuse_static_forces(trajectory, path, grid, coefficients[2], limits)
        forces = coefficients, limits
        raise_if_cancelled(cancel)
    factors = np.ones(grid.shape)
    for refinement in range(REFINEMENTS + 1):
        timed = _solve(path, grid, leg_path, curvatures, speed, scaled, factors, forces)
        raise_if_cancelled(cancel)
        excess = _interval_excess(timed, geometry, scaled, sample_rate, cancel, limits,
                                  trajectory)
        if refinement == REFINEMENTS or not excess.max() > 1.0 + REFINEMENT_TOLERANCE:
            break
        over = np.flatnonzero(excess > 1.0)
        for ends in (over, over + 1):
            factors[ends] = np.minimum(factors[ends],
                                       factors[ends] / (excess[over] * REFINEMENT_MARGIN))
    # What is left over (at most REFINEMENT_TOLERANCE, unless the refinements ran out), and
    # a margin for the motion between the samples: a uniform stretch, which divides
    # velocities by it and accelerations by its square.
    return timed.stretched(max(float(excess.max()), 1.0) * FINAL_STRETCH_MARGIN)


def _solve(path, grid, leg_path, curvatures, speed, limits, factors,
           forces=None) -> TimedTrajectory:
    """
    Solve the time-optimal problem on the grid, the limits at gridpoint j times ``factors[j]``.

    :param forces: ``None``, or ``((a, b, c), (low, high))``: the force coefficients at the
        gridpoints (in toppra's parameter) and the force limits, newtons; the dynamic part
        ``a u + b x`` is allowed ``factors[j]^2`` of its room there.

    :raises RetimingError: where toppra finds no timing.
    """
    import toppra.algorithm
    import toppra.constraint

    constraints = []
    if math.isfinite(limits.velocity_max):
        constraints.append(_velocity_constraint(toppra.constraint.LinearConstraint,
                                                limits.velocity_max * factors))
    if math.isfinite(limits.acceleration_max):
        constraints.append(_acceleration_constraint(
            toppra.constraint.JointAccelerationConstraint, limits.acceleration_max,
            factors, STOPPED_LEG_SLOPE * speed,
            toppra.constraint.DiscretizationType.Interpolation))
    if forces is not None:
        constraints.append(_force_constraint(
            toppra.constraint.LinearConstraint, *forces, factors,
            toppra.constraint.DiscretizationType.Interpolation))
    algorithm = toppra.algorithm.TOPPRA(constraints, leg_path, gridpoints=grid / speed,
                                        solver_wrapper='seidel')
    algorithm.compute_parameterization(0.0, 0.0)
    data = algorithm.problem_data
    rates = None if data.sd_vec is None else np.asarray(data.sd_vec, dtype=float)
    if rates is None or rates.shape != grid.shape or not np.all(np.isfinite(rates)):
        controllable = getattr(data, 'K', None)
        if controllable is None:
            controllable = algorithm.compute_controllable_sets(0.0, 0.0)
        failing = ~np.all(np.isfinite(controllable), axis=-1) | (
            controllable[:, 0] > controllable[:, 1])
        index = int(np.flatnonzero(failing)[-1]) if failing.any() else 0
        raise _failure(path, grid, index, curvatures, 'grid',
                       f'toppra found no timing ({data.return_code}) from there on')
    rates = np.maximum(rates, 0.0) * speed
    sums = rates[:-1] + rates[1:]
    if np.any(sums <= 0.0):
        index = int(np.argmax(sums <= 0.0))
        raise _failure(path, grid, index, curvatures, 'grid',
                       'toppra stops the path there (rate 0 at two gridpoints in a row)')
    # t_j+1 - t_j = 2 (tau_j+1 - tau_j) / (rate_j + rate_j+1) under uniform path acceleration.
    durations = 2.0 * np.diff(grid) / sums
    return TimedTrajectory(path, np.concatenate([[0.0], np.cumsum(durations)]), grid, rates)


def _interval_excess(timed, geometry, limits, sample_rate, cancel, force_limits=None,
                     trajectory=None) -> np.ndarray:
    """
    Return the largest excess over a leg limit in each grid interval, shape (G - 1,).

    ``max(|velocity| / velocity_max, sqrt(|acceleration| / acceleration_max))`` over the
    samples of the interval (the stretch that would bring them within), sampled in chunks;
    with ``force_limits`` ``(low, high)``, newtons, also ``sqrt((f - c) / (limit - c))`` where
    a dynamic force ``f`` breaks a limit that its static force ``c`` keeps.

    :param trajectory: the trajectory retimed, to name where a static force breaks a limit.
    :raises RetimingError: where a sample whose dynamic forces break a force limit breaks it
        with its static forces too (no stretch brings it within).
    """
    times = timed.sample_times(sample_rate)
    intervals = np.clip(np.searchsorted(timed.grid_times, times, side='right') - 1,
                        0, timed.grid_times.shape[0] - 2)
    excess = np.zeros(timed.grid_times.shape[0] - 1)
    for start in range(0, times.shape[0], REFINEMENT_CHUNK):
        raise_if_cancelled(cancel)
        chunk = slice(start, start + REFINEMENT_CHUNK)
        samples = timed.sample(times[chunk])
        legs = leg_states(geometry, samples)
        ratio = np.zeros(legs.velocities.shape[0])
        if math.isfinite(limits.velocity_max):
            ratio = np.abs(legs.velocities).max(axis=-1) / limits.velocity_max
        if math.isfinite(limits.acceleration_max):
            ratio = np.maximum(ratio, np.sqrt(np.abs(legs.accelerations).max(axis=-1)
                                              / limits.acceleration_max))
        if force_limits is not None:
            dynamic = sample_forces(geometry, samples)
            low, high = force_limits
            # Only the samples beyond a limit need their static forces (what a stretch keeps).
            beyond = np.flatnonzero(~np.all((dynamic >= low) & (dynamic <= high), axis=-1))
            if beyond.size:
                picked = times[chunk][beyond]
                static = sample_forces(geometry, _at_rest(timed.sample(picked)))
                _refuse_static_forces(trajectory, timed.path, timed.path_times(picked)[0],
                                      static, force_limits, picked)
                ratio[beyond] = np.maximum(ratio[beyond], _force_stretch(
                    static, dynamic[beyond], force_limits))
        np.maximum.at(excess, intervals[chunk], ratio)
    return excess


def _at_rest(samples):
    """Return the poses of samples with every velocity and acceleration 0."""
    zeros = np.zeros_like(samples.velocities)
    return type(samples)(samples.positions, samples.rotations, zeros, zeros, zeros, zeros)


def _force_stretch(static, dynamic, force_limits) -> np.ndarray:
    """
    Return the stretch that brings each sample's dynamic forces within the limits, shape (M,).

    ``sqrt((f - c) / (limit - c))`` for each force ``f`` beyond a limit that its static force
    ``c`` keeps (a uniform stretch k divides the dynamic part ``f - c`` by ``k^2``); 0 where
    every force is within.
    """
    ratio = np.zeros(static.shape)
    with np.errstate(divide='ignore', invalid='ignore'):
        for limit, beyond in ((force_limits[1], dynamic > force_limits[1]),
                              (force_limits[0], dynamic < force_limits[0])):
            if math.isfinite(limit) and beyond.any():
                needed = (dynamic - static) / (limit - static)
                ratio = np.where(beyond, np.maximum(ratio, needed), ratio)
    # A static force exactly at the limit leaves no room (an infinite stretch): capped, so
    # that the refinement stays finite; the check of the result refuses what is left.
    return np.sqrt(np.minimum(np.max(ratio, axis=-1), MAX_FORCE_STRETCH ** 2))


def gridpoints(path: PoseTrajectory, leg_path, speed) -> np.ndarray:
    """
    Place toppra's gridpoints along a path (in its parameter, the legs' travel), from its shape.

    The path's parameter is the legs' chord length (:meth:`PoseTrajectory.path`), which is
    their arc length at the waypoints and very nearly between. The grid's density is uniform
    in it plus a part proportional to the curvature of the legs' path (the largest second
    derivative of a leg length in the parameter), measured on :data:`MEASURE_SAMPLES`
    samples: :data:`BASE_GRIDPOINTS` plus :data:`GRIDPOINTS_PER_RADIAN` per radian of
    turning, at most :data:`MAX_GRIDPOINTS`. With at most :data:`MAX_WAYPOINT_GRIDPOINTS`
    waypoints, each is a gridpoint too (the curve is C2, but its third derivative jumps
    there). The grid depends on the curve only, not on how it was timed.

    :param leg_path: toppra's path of the legs; ``speed``: the reference speed of its
        parameter (path parameter over it).
    :returns: increasing path parameters from ``path.times[0]`` to ``path.times[-1]``.
    """
    start, end = float(path.times[0]), float(path.times[-1])
    measure = np.linspace(start, end, MEASURE_SAMPLES + 1)
    curvature = np.abs(leg_path(measure / speed, 2)).max(axis=-1) / (speed * speed)
    curvature = np.where(np.isfinite(curvature), curvature, 0.0)
    # Trapezoidal integrals of the density 1 / length + curvature / turning.
    turning_steps = 0.5 * (curvature[1:] + curvature[:-1]) * np.diff(measure)
    turning = float(turning_steps.sum())
    count = int(min(MAX_GRIDPOINTS, BASE_GRIDPOINTS + GRIDPOINTS_PER_RADIAN * turning))
    weight = (count - BASE_GRIDPOINTS) / count
    cumulative = np.concatenate([[0.0], np.cumsum(
        (1.0 - weight) * np.diff(measure) / (end - start)
        + (weight * turning_steps / turning if turning > 0.0 else 0.0))])
    cumulative /= cumulative[-1]
    grid = np.interp(np.linspace(0.0, 1.0, count + 1), cumulative, measure)
    if path.waypoint_count <= MAX_WAYPOINT_GRIDPOINTS:
        grid = np.concatenate([grid, path.times])
    grid = np.unique(np.clip(grid, start, end))
    # No two gridpoints closer than MIN_GRID_STEP of the path (toppra divides by the step).
    keep = np.concatenate([[True], np.diff(grid) > MIN_GRID_STEP * (end - start)])
    grid = grid[keep]
    grid[-1] = end
    return grid


def _failure(path, grid, index, curvatures, cause, what):
    """Build the :class:`RetimingError` of a failure at gridpoint ``index``."""
    tau = grid[min(index, grid.shape[0] - 1)]
    segment = int(path.segments(np.array([tau]))[0])
    first, second = path.points(segment)
    fraction = (tau - path.times[segment]) / (path.times[segment + 1] - path.times[segment])
    acceleration = curvatures[min(index, grid.shape[0] - 1)]
    leg = int(np.nanargmax(np.where(np.isfinite(acceleration), acceleration, np.inf))) + 1
    message = (f'no timing found between points {first} and {second} ({fraction:.0%} of the '
               f'way), leg {leg}: {what}')
    return RetimingError(message, cause, (
        ('segment', f'points {first} and {second}'), ('fraction_of_segment', f'{fraction:.3f}'),
        ('leg', str(leg)),
        ('leg_path_curvature_per_m', f'{acceleration[leg - 1]:.6g}')))


def _velocity_constraint(base, velocity_max):
    """
    Build the legs' velocity limit as toppra bounds on the squared path rate ``x``.

    ``x <= (velocity_max / max |q'_i|)^2``: robust where the legs stop along the path (``q' =
    0``, where toppra's own JointVelocityConstraint divides by zero).

    :param velocity_max: m/s at each gridpoint, shape (G,).
    """
    class LegVelocityConstraint(base):
        def __init__(self):
            super().__init__()
            self.dof = 6

        def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
            speeds = np.abs(path(gridpoints, 1)).max(axis=-1)
            floor = velocity_max / math.sqrt(MAX_SQUARED_RATE)
            upper = (velocity_max / np.maximum(speeds, floor)) ** 2
            bounds = np.stack([np.zeros_like(upper), upper], axis=-1)
            return None, None, None, None, None, None, bounds

    return LegVelocityConstraint()


def _acceleration_constraint(base, acceleration_max, factors, smallest_slope, discretization):
    """
    Build the legs' acceleration limit, ``acceleration_max * factors[j]^2`` at gridpoint j.

    toppra's JointAccelerationConstraint (``|q' u + q'' x| <= a``) with ``q'`` and ``q''``
    divided by the squared factor at each gridpoint, which lowers the limit there. Where a
    leg stops on a gridpoint (``q'_i = 0``, as where the path turns back), ``|q'_i|`` becomes
    ``smallest_slope`` instead: toppra's solver fails on a row without ``u`` (and the
    leg's acceleration there is ``q'' x`` within 1e-4 of the speed term).
    """
    from toppra.constraint.linear_constraint import canlinear_colloc_to_interpolate

    class LegAccelerationConstraint(base):
        def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
            scale = 1.0 / (factors * factors)[:, None]
            first, second = path(gridpoints, 1), path(gridpoints, 2)
            first = np.where(np.abs(first) < smallest_slope,
                             np.where(first < 0.0, -smallest_slope, smallest_slope), first)
            bound = np.concatenate([self.alim[:, 1], -self.alim[:, 0]])
            matrix = np.concatenate([np.eye(6), -np.eye(6)])
            return canlinear_colloc_to_interpolate(
                first * scale, second * scale, np.zeros_like(first), matrix, bound, None, None,
                gridpoints, identical=True)

    return LegAccelerationConstraint(np.full(6, acceleration_max),
                                     discretization_scheme=discretization)


def _force_constraint(base, coefficients, force_limits, factors, discretization):
    """
    Build the legs' force limits as a toppra canonical linear constraint.

    ``low <= a u + b x + c <= high`` per leg (``u`` the path acceleration, ``x`` the squared
    path speed, in toppra's parameter), with ``a`` and ``b`` divided by ``factors[j]^2`` at
    gridpoint j (which lowers the dynamic part's room there), all in units of the largest
    limit (toppra's tolerances are absolute).

    :param coefficients: ``(a, b, c)``, newtons, each (G, 6); ``force_limits``: ``(low,
        high)``, newtons, at least one finite.
    """
    from toppra.constraint.linear_constraint import canlinear_colloc_to_interpolate

    low, high = force_limits
    unit = max(abs(limit) for limit in force_limits if math.isfinite(limit) and limit != 0.0)
    rows, bounds = [], []
    if math.isfinite(high):
        rows.append(np.eye(6))
        bounds.append(np.full(6, high / unit))
    if math.isfinite(low):
        rows.append(-np.eye(6))
        bounds.append(np.full(6, -low / unit))
    matrix, bound = np.concatenate(rows), np.concatenate(bounds)
    first, second, static = (values / unit for values in coefficients)
    scale = 1.0 / (factors * factors)[:, None]

    class LegForceConstraint(base):
        def __init__(self):
            super().__init__()
            self.dof = 6
            self.identical = True
            self.set_discretization_type(discretization)

        def compute_constraint_params(self, path, gridpoints, *args, **kwargs):
            return canlinear_colloc_to_interpolate(
                first * scale, second * scale, static, matrix, bound, None, None, gridpoints,
                identical=True)

    return LegForceConstraint()


def _refuse_static_forces(trajectory, path, taus, static, force_limits, times=None):
    """
    Raise a :class:`RetimingError` where a static force breaks a force limit; else nothing.

    :param trajectory: the trajectory given to :func:`retime` (its own times, if it has
        any, say when it reached that place).
    :param path: the path retimed; ``taus``: its parameters of the forces, shape (M,).
    :param static: static leg forces there, newtons, (M, 6); NaN: none hold the platform.
    :param times: the retimed clock times of ``taus``, seconds, or ``None`` (not yet timed).
    """
    low, high = force_limits
    over = ~(static <= high)     # NaN (a singular pose) breaks both
    under = ~(static >= low)
    broken = over | under
    if not broken.any():
        return
    index = int(np.flatnonzero(broken.any(axis=-1))[0])
    name, allowed, legs = ('leg_force_max', high, over[index]) if over[index].any() else (
        'leg_force_min', low, under[index])
    legs = (np.flatnonzero(legs) + 1).tolist()
    tau = float(taus[index])
    segment = int(path.segments(np.array([tau]))[0])
    first, second = path.points(segment)
    fraction = (tau - path.times[segment]) / (path.times[segment + 1] - path.times[segment])
    where = (f'between points {first} and {second} ({fraction:.0%} of the way, leg travel '
             f'{tau - path.times[0]:.4g} m of {path.times[-1] - path.times[0]:.4g} m')
    details = [('limit', name), ('legs', str(legs)),
               ('segment', f'points {first} and {second}'),
               ('fraction_of_segment', f'{fraction:.3f}')]
    if times is not None:
        where += f', t = {float(times[index]):.4f} s of the timing'
        details.append(('time_s', f'{float(times[index]):.4f}'))
    elif not trajectory.is_path:
        given = trajectory.times[[first, second]]
        time = float(given[0] + fraction * (given[1] - given[0]))
        where += f', about t = {time:.4f} s as given'
        details.append(('time_s', f'{time:.4f}'))
    values = static[index, np.array(legs) - 1]
    forces = (f'static forces are {", ".join(f"{value:.6g}" for value in values)} N'
              if np.all(np.isfinite(values)) else
              'no leg forces hold the platform there (a singular pose)')
    raise RetimingError(
        f'leg_force: {name} {allowed:g} N is broken at rest by leg(s) {legs} {where}): '
        f'{forces}, so the path cannot be followed at any speed (the platform could not be '
        'held there)', 'leg_force', details)


def _leg_path(path, geometry, speed, base):
    """
    Wrap the leg lengths along a path as a toppra geometric path (a subclass of ``base``).

    Its parameter is the path's over ``speed``; the leg states of the last gridpoints asked
    for are kept, since toppra asks for each order of the same gridpoints in turn.
    """
    class LegPath(base):
        def __init__(self):
            self._cached = None

        def states(self, parameters):
            parameters = np.atleast_1d(np.asarray(parameters, dtype=float))
            if self._cached is None or not np.array_equal(self._cached[0], parameters):
                states = leg_states(geometry, path.sample(parameters * speed))
                self._cached = parameters.copy(), type(states)(
                    states.lengths, states.velocities * speed,
                    states.accelerations * speed * speed)
            return self._cached[1]

        def __call__(self, path_positions, order=0):
            scalar = np.ndim(path_positions) == 0
            states = self.states(path_positions)
            values = (states.lengths, states.velocities, states.accelerations)[order]
            return values[0] if scalar else values

        @property
        def dof(self):
            return 6

        @property
        def path_interval(self):
            return np.array([path.times[0], path.times[-1]]) / speed

    return LegPath()
