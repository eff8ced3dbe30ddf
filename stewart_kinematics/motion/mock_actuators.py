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
Six simulated leg actuators: what mock_platform moves and measures, without hardware.

Each leg follows its commanded length with a first-order lag of time constant ``tau``, within
the stroke, the velocity and the acceleration limits (:func:`lag_step`). Commands are set
points (six lengths, :meth:`MockActuators.command_lengths`) or leg trajectories followed in
time as joint_trajectory_controller follows them (:class:`LegTrajectoryCommand`: linear,
cubic or quintic interpolation by what the points give). The newest command wins: a set point
cancels a trajectory; a trajectory replaces what runs from its start time. Faults for tests:
stalled legs (they stop where they are), Gaussian noise and a fixed bias on the measured
positions (:meth:`MockActuators.measure`).

The lag, for a leg at ``l`` commanded to ``c`` over a step ``dt``, asks for the velocity that
the exact first-order response would have on average over the step,
``v = (c - l) (1 - exp(-dt / tau)) / dt`` (``tau = 0``: reach ``c`` in one step), then keeps
it within ``leg_velocity_max``, within ``leg_acceleration_max * dt`` of the last velocity, and
below the speed from which the leg can still brake to rest at ``leg_acceleration_max`` before
the command and before each end of its stroke (:func:`braking_speed`). The position is then
``l + v dt``. So from a state within the limits every step keeps every limit: the stroke, the
velocity and the acceleration.

Units: metres, seconds. Nothing here imports ROS.
"""

from dataclasses import dataclass, field
import math
from typing import Optional, Sequence, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.dynamics.inverse_dynamics import leg_forces, masses_of
from stewart_kinematics.findings import Finding
from stewart_kinematics.model.arrays import preview
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.velocities import platform_twist

#: Most points of a leg trajectory command (as :data:`~stewart_kinematics.motion.
#: leg_trajectory.MAX_POINTS`).
MAX_TRAJECTORY_POINTS = 100_000
#: Latest time_from_start of a trajectory point, seconds (as a pose trajectory's).
MAX_TIME_FROM_START = 1e6
#: Fastest leg velocity a trajectory point may carry, m/s, and fastest acceleration, m/s^2:
#: larger values are absurd (a unit error, an overflow), whatever the limits.
MAX_POINT_VELOCITY = 1e3
MAX_POINT_ACCELERATION = 1e6
#: Largest standard deviation of the position noise, and largest bias, metres.
MAX_NOISE = 1.0
MAX_BIAS = 1.0


@dataclass(frozen=True)
class LegLimits:
    """
    The limits the simulated legs keep: the stroke, the velocity and the acceleration.

    :param length_min: shortest leg, metres (``leg_length_min``; 0 when not set).
    :param length_max: longest leg, metres (``leg_length_max``; ``inf`` when not set).
    :param velocity_max: largest leg speed, m/s (``leg_velocity_max``; ``inf``: none).
    :param acceleration_max: largest leg acceleration, m/s^2 (``leg_acceleration_max``;
        ``inf``: none).
    :raises ValueError: if the stroke is empty or a rate limit is not positive.
    """

    length_min: float = 0.0
    length_max: float = math.inf
    velocity_max: float = math.inf
    acceleration_max: float = math.inf

    def __post_init__(self):
        values = [float(self.length_min), float(self.length_max), float(self.velocity_max),
                  float(self.acceleration_max)]
        if any(math.isnan(value) for value in values) or not (
                0.0 <= values[0] < values[1]) or not (values[2] > 0.0 and values[3] > 0.0):
            raise ValueError(
                f'leg limits must have 0 <= length_min < length_max and positive velocity and '
                f'acceleration limits, got {values}')
        for name, value in zip(('length_min', 'length_max', 'velocity_max',
                                'acceleration_max'), values):
            object.__setattr__(self, name, value)

    @classmethod
    def of(cls, geometry, actuator_limits) -> 'LegLimits':
        """
        Return the limits of a geometry's stroke and an :class:`ActuatorLimits`' rates.

        :param geometry: a :class:`~stewart_kinematics.Geometry` (its ``limits`` may be
            ``None``: no stroke).
        :param actuator_limits: an :class:`~stewart_kinematics.ActuatorLimits`.
        """
        pose_limits = geometry.limits
        return cls(0.0 if pose_limits is None else pose_limits.leg_length_min,
                   math.inf if pose_limits is None else pose_limits.leg_length_max,
                   actuator_limits.velocity_max, actuator_limits.acceleration_max)

    def stroke_reason(self, lengths: np.ndarray) -> str:
        """Return ``''`` if every length is within the stroke (and > 0), else why not."""
        outside = np.flatnonzero(~((lengths >= self.length_min) & (lengths <= self.length_max)
                                   & (lengths > 0.0)))
        if outside.size == 0:
            return ''
        leg = int(outside[0])
        return (f'leg {leg + 1} length {lengths[leg]:.6g} m is outside the stroke '
                f'[{self.length_min:g}, {self.length_max:g}] m')


@dataclass(frozen=True)
class LegState:
    """
    The simulated legs at one instant.

    :param lengths: metres, shape (6,).
    :param velocities: m/s, shape (6,).
    :param accelerations: m/s^2 over the last step, shape (6,).
    """

    lengths: np.ndarray
    velocities: np.ndarray = field(default_factory=lambda: np.zeros(6))
    accelerations: np.ndarray = field(default_factory=lambda: np.zeros(6))

    @classmethod
    def at_rest(cls, lengths) -> 'LegState':
        """Return legs at rest at ``lengths`` (metres, six)."""
        return cls(np.array(lengths, dtype=float).reshape(6), np.zeros(6), np.zeros(6))


def braking_speed(distance, acceleration_max: float, dt: float) -> np.ndarray:
    """
    Fastest speed toward a point ``distance`` ahead from which a leg stops before it.

    The leg moves ``v dt`` this step, then brakes by ``acceleration_max * dt`` each step; it
    stops within ``distance`` when ``v^2 / (2 a) + v dt <= distance``, so
    ``v = sqrt((a dt)^2 + 2 a d) - a dt``. If it holds at one step it holds at the next with
    the velocity lowered by ``a dt``: braking stays possible.

    :param distance: metres ahead, >= 0 (an array: per leg); ``inf`` for no point.
    :param acceleration_max: m/s^2, > 0 (``inf``: the leg can stop at once).
    :param dt: the step, seconds, > 0.
    :returns: m/s, >= 0, of the shape of ``distance``.
    """
    distance = np.maximum(np.asarray(distance, dtype=float), 0.0)
    if math.isinf(acceleration_max):
        return distance / dt
    braking = acceleration_max * dt
    with np.errstate(over='ignore', invalid='ignore'):
        speed = np.sqrt(braking * braking + 2.0 * acceleration_max * distance) - braking
    return np.where(np.isinf(distance), math.inf, np.maximum(speed, 0.0))


def lag_step(state: LegState, target, dt: float, time_constant: float, limits: LegLimits,
             stalled=None) -> LegState:
    """
    Move the legs one step toward ``target`` with a first-order lag, within every limit.

    See the module's description for the law. A stalled leg stops where it is, at once (a
    fault: its velocity drops to 0 whatever the acceleration limit).

    :param state: the legs now.
    :param target: the commanded lengths, metres, shape (6,), finite (clamped to the stroke).
    :param dt: the step, seconds, finite and > 0.
    :param time_constant: the lag's time constant ``tau``, seconds, >= 0.
    :param limits: the :class:`LegLimits` to keep.
    :param stalled: boolean mask of the stalled legs, shape (6,), or ``None``.
    :returns: the legs after the step.
    :raises ValueError: for a ``dt`` that is not finite and positive or a negative
        ``time_constant``.
    """
    if not (math.isfinite(dt) and dt > 0.0):
        raise ValueError(f'the time step must be finite and positive, got {dt!r} s')
    if not (math.isfinite(time_constant) and time_constant >= 0.0):
        raise ValueError(f'the time constant must be finite and >= 0, got {time_constant!r} s')
    lengths, previous = state.lengths, state.velocities
    target = np.clip(np.asarray(target, dtype=float), limits.length_min, limits.length_max)
    error = target - lengths
    share = 1.0 if time_constant == 0.0 else -math.expm1(-dt / time_constant)
    # The lag's velocity, no faster than the leg can brake to rest at the target.
    speed = np.minimum(np.abs(error) * share / dt,
                       braking_speed(np.abs(error), limits.acceleration_max, dt))
    desired = np.sign(error) * np.minimum(speed, limits.velocity_max)
    step = limits.acceleration_max * dt
    low = np.maximum.reduce([previous - step, np.full(6, -limits.velocity_max),
                             -braking_speed(lengths - limits.length_min,
                                            limits.acceleration_max, dt)])
    high = np.minimum.reduce([previous + step, np.full(6, limits.velocity_max),
                              braking_speed(limits.length_max - lengths,
                                            limits.acceleration_max, dt)])
    # From a state within the limits low <= high; otherwise brake as hard as allowed.
    velocity = np.where(low <= high, np.clip(desired, low, np.maximum(low, high)),
                        np.where(previous > high, np.maximum(previous - step, high),
                                 np.minimum(previous + step, low)))
    new_lengths = np.clip(lengths + velocity * dt, limits.length_min, limits.length_max)
    velocity = (new_lengths - lengths) / dt
    if stalled is not None and np.any(stalled):
        stalled = np.asarray(stalled, dtype=bool)
        new_lengths = np.where(stalled, lengths, new_lengths)
        velocity = np.where(stalled, 0.0, velocity)
    return LegState(new_lengths, velocity, (velocity - previous) / dt)


@dataclass(frozen=True)
class LegTrajectoryCommand:
    """
    A leg trajectory to follow in time, as joint_trajectory_controller follows one.

    Between two points the legs are commanded along a linear interpolation (positions only),
    a cubic one (positions and velocities) or a quintic one (accelerations too); before the
    first point, from the legs' state when the trajectory starts (:meth:`started`); after the
    last, its positions are held.

    :param start: the time of ``time_from_start = 0``, seconds on the node's clock.
    :param times: time_from_start of each point, seconds, strictly increasing, shape (M,).
    :param lengths: commanded leg lengths, metres, shape (M, 6).
    :param velocities: m/s, shape (M, 6), or ``None``.
    :param accelerations: m/s^2, shape (M, 6), or ``None`` (only with velocities).
    """

    start: float
    times: np.ndarray
    lengths: np.ndarray
    velocities: Optional[np.ndarray] = None
    accelerations: Optional[np.ndarray] = None

    @property
    def end(self) -> float:
        """Return the time of the last point, seconds on the node's clock."""
        return self.start + float(self.times[-1])

    def started(self, time: float, state: LegState) -> 'LegTrajectoryCommand':
        """
        Return this trajectory started from the legs' state at ``time`` (before its first point).

        As joint_trajectory_controller does, the motion to the first point starts from the
        current state (lengths and velocities, and accelerations for a quintic).
        """
        relative = time - self.start
        if relative >= self.times[0]:
            return self

        def prepend(values, first):
            return None if values is None else np.vstack([first, values])
        return LegTrajectoryCommand(
            self.start, np.concatenate([[relative], self.times]),
            prepend(self.lengths, state.lengths), prepend(self.velocities, state.velocities),
            prepend(self.accelerations, state.accelerations))

    def sample(self, time: float) -> np.ndarray:
        """
        Return the commanded lengths at ``time`` (seconds on the node's clock), metres (6,).

        Before the first point: its lengths (the trajectory is :meth:`started` first).
        """
        relative = time - self.start
        times = self.times
        if relative <= times[0]:
            return self.lengths[0].copy()
        if relative >= times[-1]:
            return self.lengths[-1].copy()
        index = int(np.searchsorted(times, relative, side='right')) - 1
        span = times[index + 1] - times[index]
        s = (relative - times[index]) / span
        p0, p1 = self.lengths[index], self.lengths[index + 1]
        if self.velocities is None:
            return p0 + s * (p1 - p0)
        v0, v1 = self.velocities[index] * span, self.velocities[index + 1] * span
        if self.accelerations is None:
            # Cubic Hermite on s in [0, 1].
            h00 = 2 * s ** 3 - 3 * s ** 2 + 1
            h10 = s ** 3 - 2 * s ** 2 + s
            h01 = -2 * s ** 3 + 3 * s ** 2
            h11 = s ** 3 - s ** 2
            return h00 * p0 + h10 * v0 + h01 * p1 + h11 * v1
        a0 = self.accelerations[index] * span ** 2
        a1 = self.accelerations[index + 1] * span ** 2
        # Quintic with these positions, velocities and accelerations at s = 0 and 1.
        c3 = 10 * (p1 - p0) - 6 * v0 - 4 * v1 - 1.5 * a0 + 0.5 * a1
        c4 = -15 * (p1 - p0) + 8 * v0 + 7 * v1 + 1.5 * a0 - a1
        c5 = 6 * (p1 - p0) - 3 * v0 - 3 * v1 - 0.5 * a0 + 0.5 * a1
        return p0 + s * (v0 + s * (0.5 * a0 + s * (c3 + s * (c4 + s * c5))))


def check_lengths(lengths, limits: LegLimits) -> Optional[Finding]:
    """
    Return ``None`` for six finite lengths within the stroke, else the refusal.

    :param lengths: the commanded lengths, metres.
    """
    lengths = np.asarray(lengths, dtype=float)
    if lengths.shape != (6,):
        return Finding(findings.INVALID_LEG_COMMAND,
                       f'a leg command must hold 6 lengths (metres, leg 1..6), got '
                       f'{lengths.size}: {preview(lengths)}')
    if not np.all(np.isfinite(lengths)):
        return Finding(findings.INVALID_LEG_COMMAND,
                       f'leg lengths must be finite, got {preview(lengths)}')
    reason = limits.stroke_reason(lengths)
    if reason:
        return Finding(findings.INVALID_LEG_COMMAND, f'refused leg command: {reason}')
    return None


def trajectory_command(start: float, times, lengths, velocities=None, accelerations=None,
                       limits: LegLimits = LegLimits(), now: Optional[float] = None):
    """
    Check a leg trajectory and return it as a :class:`LegTrajectoryCommand`, or the refusal.

    :param start: the time of ``time_from_start = 0`` on the node's clock, seconds.
    :param times: time_from_start of each point, seconds, shape (M,).
    :param lengths: leg lengths of each point, metres, shape (M, 6).
    :param velocities: m/s, shape (M, 6), or ``None``.
    :param accelerations: m/s^2, shape (M, 6), or ``None``.
    :param limits: every point's lengths must be within the stroke.
    :param now: the time now; a trajectory that ends before it is refused (as
        joint_trajectory_controller drops one). ``None``: not checked.
    :returns: ``(command, None)`` or ``(None, refusal)``.
    """
    def refuse(message):
        return None, Finding(findings.INVALID_LEG_COMMAND, f'refused leg trajectory: {message}')
    times = np.asarray(times, dtype=float)
    count = times.size
    if count == 0:
        return refuse('it has no point')
    if count > MAX_TRAJECTORY_POINTS:
        return refuse(f'at most {MAX_TRAJECTORY_POINTS:,} points, got {count:,}')
    if not (np.all(np.isfinite(times)) and times[0] >= 0.0
            and times[-1] <= MAX_TIME_FROM_START):
        return refuse(f'times from start must be finite, in [0, {MAX_TIME_FROM_START:g}] s, '
                      f'got {preview(times)}')
    if np.any(np.diff(times) <= 0.0):
        index = int(np.flatnonzero(np.diff(times) <= 0.0)[0]) + 1
        return refuse(f'times from start must increase strictly: point {index} at '
                      f'{times[index]:g} s after {times[index - 1]:g} s')
    if not math.isfinite(start):
        return refuse(f'its start time must be finite, got {start!r}')
    arrays = []
    for name, values, bound in (('positions', lengths, None),
                                ('velocities', velocities, MAX_POINT_VELOCITY),
                                ('accelerations', accelerations, MAX_POINT_ACCELERATION)):
        if values is None:
            arrays.append(None)
            continue
        values = np.asarray(values, dtype=float)
        if values.shape != (count, 6):
            return refuse(f'{name} must be 6 per point for {count} point(s), got shape '
                          f'{values.shape}')
        if not np.all(np.isfinite(values)):
            return refuse(f'{name} must be finite, got {preview(values)}')
        if bound is not None and np.abs(values).max() > bound:
            return refuse(f'{name} must be within +-{bound:g} (m/s, m/s^2), got '
                          f'{np.abs(values).max():.6g}')
        arrays.append(values)
    if arrays[2] is not None and arrays[1] is None:
        return refuse('accelerations need velocities')
    for index, row in enumerate(arrays[0]):
        reason = limits.stroke_reason(row)
        if reason:
            return refuse(f'point {index}: {reason}')
    if now is not None and start + times[-1] < now:
        return refuse(f'it ended {now - start - times[-1]:.6g} s ago (its header stamp and '
                      'last time_from_start are in the past)')
    return LegTrajectoryCommand(float(start), times, *arrays), None


def leg_selection(text: str, joint_names: Sequence[str]) -> Tuple[int, ...]:
    """
    Legs named by joint names or numbers 1..6, separated by commas or spaces.

    >>> leg_selection('leg_2, 5', ['leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5', 'leg_6'])
    (1, 4)

    :param text: ``''`` for none.
    :param joint_names: the six joint names, leg 1..6.
    :returns: the indices of the legs, 0..5, sorted, each once.
    :raises ValueError: naming a word that is neither.
    """
    legs = set()
    for word in text.replace(',', ' ').split():
        if word in joint_names:
            legs.add(list(joint_names).index(word))
        elif word in ('1', '2', '3', '4', '5', '6'):
            legs.add(int(word) - 1)
        else:
            raise ValueError(f'stalled_legs: {preview(word)} is neither a joint name '
                             f'({", ".join(joint_names)}) nor a leg number 1..6')
    return tuple(sorted(legs))


class MockActuators:
    """
    Six simulated legs: commanded, advanced in time, measured with faults.

    :param limits: the :class:`LegLimits` the legs keep.
    :param initial_lengths: where they start, at rest, metres (6,), within the stroke.
    :param time_constant: the lag's ``tau``, seconds, >= 0.
    :param max_time_step: a longer time between two steps counts as this long, seconds (a
        clock jump must not move a leg further than one step allows).
    :raises ValueError: for initial lengths outside the stroke, or a bad time constant.
    """

    def __init__(self, limits: LegLimits, initial_lengths, time_constant: float,
                 max_time_step: float = 0.1):
        self.limits = limits
        refusal = check_lengths(initial_lengths, limits)
        if refusal is not None:
            raise ValueError(f'initial leg lengths: {refusal.message}')
        self.state = LegState.at_rest(initial_lengths)
        #: The set point the legs follow when no trajectory runs, metres (6,).
        self.set_point = self.state.lengths.copy()
        self.trajectory: Optional[LegTrajectoryCommand] = None
        self.pending: Optional[LegTrajectoryCommand] = None
        self.time: Optional[float] = None
        #: The step the last :meth:`advance` took, seconds (0.0: none).
        self.last_step = 0.0
        self.stalled = np.zeros(6, dtype=bool)
        self.noise = 0.0
        self.bias = np.zeros(6)
        self.rng = np.random.default_rng(0)
        self.max_time_step = float(max_time_step)
        self.set_time_constant(time_constant)

    def set_time_constant(self, time_constant: float):
        """Take a new time constant, seconds, >= 0 (ValueError otherwise)."""
        if not (math.isfinite(time_constant) and time_constant >= 0.0):
            raise ValueError(f'time constant must be finite and >= 0, got {time_constant!r} s')
        self.time_constant = float(time_constant)

    def set_stalled(self, legs: Sequence[int]):
        """Stall the legs of indices ``legs`` (0..5); the others move again."""
        self.stalled = np.zeros(6, dtype=bool)
        self.stalled[list(legs)] = True

    def set_noise(self, stddev: float, seed: int):
        """Add Gaussian noise of ``stddev`` metres to the measured positions, seeded anew."""
        if not (math.isfinite(stddev) and 0.0 <= stddev <= MAX_NOISE):
            raise ValueError(f'noise must be in [0, {MAX_NOISE:g}] m, got {stddev!r}')
        self.noise = float(stddev)
        self.rng = np.random.default_rng(int(seed))

    def set_bias(self, bias):
        """Add a fixed ``bias`` (metres, six) to the measured positions."""
        bias = np.asarray(bias, dtype=float)
        if bias.shape != (6,) or not np.all(np.abs(bias) <= MAX_BIAS):
            raise ValueError(f'bias must be 6 values in [-{MAX_BIAS:g}, {MAX_BIAS:g}] m, got '
                             f'{preview(bias)}')
        self.bias = bias

    def hold(self):
        """
        Stop the legs where they are, at rest, and forget the clock and the commands.

        The legs follow their lengths now until the next command; the next :meth:`advance`
        only sets the clock (a simulation paused, its drives disabled, as a managed node's
        deactivate leaves it).
        """
        self.state = LegState.at_rest(self.state.lengths)
        self.set_point = self.state.lengths.copy()
        self.trajectory = self.pending = None
        self.time = None
        self.last_step = 0.0

    def command_lengths(self, lengths) -> Optional[Finding]:
        """
        Follow a new set point from now on (a running or pending trajectory is dropped).

        :returns: ``None``, or the refusal of lengths that are not six finite ones within
            the stroke (the last valid command stands).
        """
        refusal = check_lengths(lengths, self.limits)
        if refusal is None:
            self.set_point = np.array(lengths, dtype=float)
            self.trajectory = self.pending = None
        return refusal

    def command_trajectory(self, trajectory: LegTrajectoryCommand):
        """Follow ``trajectory`` from its start; until then what runs now goes on."""
        self.pending = trajectory

    def target(self, time: float) -> np.ndarray:
        """Return the commanded lengths at ``time``: the trajectory's, or the set point."""
        if self.pending is not None and time >= self.pending.start:
            self.trajectory, self.pending = self.pending.started(time, self.state), None
        if self.trajectory is None:
            return self.set_point
        target = self.trajectory.sample(time)
        if not np.all(np.isfinite(target)):   # not expected: checked points; hold the last
            return self.set_point
        if time >= self.trajectory.end:
            # Its last point becomes the set point: the legs hold it.
            self.set_point, self.trajectory = self.trajectory.lengths[-1].copy(), None
            return self.set_point
        self.set_point = target
        return target

    def advance(self, time: float) -> Optional[Finding]:
        """
        Move the legs to ``time`` (seconds on the node's clock).

        The first call only sets the clock. A time that is not after the last (a paused or
        reset clock) moves nothing; a step longer than ``max_time_step`` counts as that long.

        :returns: ``None``, or a ``clock_jump`` warning for a step that was not taken whole.
        """
        self.last_step = 0.0
        if not math.isfinite(time):
            return Finding(findings.CLOCK_JUMP, f'the clock reads {time!r}: the legs hold')
        if self.time is None:
            self.time = time
            return None
        dt = time - self.time
        warning = None
        if dt <= 0.0:
            if dt < 0.0:
                self.time = time
                return Finding(findings.CLOCK_JUMP,
                               f'the clock went back {-dt:.6g} s: the legs hold this step')
            return None
        if dt > self.max_time_step:
            warning = Finding(findings.CLOCK_JUMP,
                              f'{dt:.6g} s since the last step, more than max_time_step '
                              f'{self.max_time_step:g} s: the legs move as in '
                              f'{self.max_time_step:g} s')
        target = self.target(time)
        self.last_step = min(dt, self.max_time_step)
        self.state = lag_step(self.state, target, self.last_step, self.time_constant,
                              self.limits, self.stalled)
        self.time = time
        return warning

    def measure(self) -> np.ndarray:
        """Return the measured leg lengths: the true ones plus bias and noise, metres (6,)."""
        measured = self.state.lengths + self.bias
        if self.noise > 0.0:
            measured = measured + self.rng.normal(0.0, self.noise, 6)
        return measured


class SimulatedForces:
    """
    The leg forces of the simulated legs: dynamics at the pose their lengths reach.

    Each call solves the forward kinematics of the lengths (from the last solution), the twist
    of their velocities there, and the platform's acceleration as the change of that twist
    over the step, then the inverse dynamics (:func:`~stewart_kinematics.leg_forces`).

    :param geometry: a :class:`~stewart_kinematics.Geometry` carrying the masses.
    """

    def __init__(self, geometry):
        self.geometry = geometry
        self._last = None
        self._twist = None

    @property
    def massless(self) -> bool:
        """Whether every mass is 0: there are no forces to give."""
        return masses_of(self.geometry).massless

    def forces(self, state: LegState, dt: float):
        """
        Return ``(forces, None)`` (N, positive pushing, (6,)) or ``(None, reason)``.

        :param state: the simulated legs now.
        :param dt: seconds since the last call (the twist's change over it is the
            acceleration; 0 or the first call: none).
        """
        result = forward_kinematics(self.geometry, state.lengths,
                                    self._last if self._last is not None else None)
        if not result.converged:
            self._last = self._twist = None
            return None, f'no forward kinematics of the simulated legs: {result.reason}'
        try:
            twist = platform_twist(self.geometry, result.pose, state.velocities,
                                   max_condition=math.inf)
            acceleration = (np.zeros(6) if self._twist is None or not dt > 0.0
                            else (twist - self._twist) / dt)
            forces = leg_forces(self.geometry, result.pose, twist, acceleration)
        except ValueError as error:
            self._last = self._twist = None
            return None, f'no leg forces at the simulated pose: {error}'
        self._last, self._twist = result, twist
        return forces, None
