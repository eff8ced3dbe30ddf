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
Streaming leg commands that actuators can follow: online jerk-limited motion toward a target.

For teleop and servoing, targets arrive irregularly and may jump. A :class:`CommandFilter`
keeps the state of the commanded legs (lengths, velocities, accelerations) and, called once per
control period, moves it toward the latest target within the legs' velocity, acceleration and
jerk limits, synchronised so that all six legs arrive together (in proportion, a straight line
in leg space, whenever the motion allows it), and comes to rest on the target when the target
stays still. The trajectory is recomputed from the current state at every step (online
trajectory generation: the ruckig library), so a new target may arrive at any time.

The filter is total: it never raises for a target or a step.

- A target that is not six finite, positive lengths, or that breaks the stroke, is refused
  (:meth:`CommandFilter.set_target` returns a :class:`StreamTarget`, the shared
  :class:`~stewart_kinematics.findings.Decision` result); the filter keeps moving toward the
  last accepted target.
- A target farther than the legs cover in :data:`WINDOW_SECONDS` at full speed is approached
  through an aim point at that distance on the straight line toward it (ruckig cannot plan a
  motion of days, and need not: the aim moves on at every step).
- A plan ruckig refuses, or whose motion would leave the stroke, is replaced by braking to
  rest within the limits (a ``stream_braking`` warning); if even that fails, the step is
  refused (``stream_held``): no step within every limit could be computed. Each step is a
  :class:`FilteredCommand`, a :class:`~stewart_kinematics.findings.Decision`.
- Every step is checked by the limits model
  (:meth:`~stewart_kinematics.limits.LimitModel.check_leg_states`: stroke, velocity,
  acceleration, and jerk as the change of acceleration over the step) before it is given.
- :meth:`CommandFilter.send` is what a node publishes: the step at the time it is sent,
  checked as sent by the command gate (:class:`~stewart_kinematics.limits.CommandGate`: the
  pose the lengths put the platform at against every pose limit, and the leg rates between
  consecutive commands, jerk included). A step held or refused there is replaced by the gate's
  braking command (``command_braking``: every leg slowing at ``leg_acceleration_max``), never
  by holding the last command (a stop within one step); the filter goes on from what was sent.
  Sending starts with the first target accepted at a time (``set_target(lengths, time)``):
  until then there is nothing to send (:attr:`CommandFilter.started`).
- With masses (:attr:`stewart_kinematics.Geometry.mass_properties`) and a force limit, the
  gate also refuses a step whose dynamic leg forces leave ``leg_force_min..leg_force_max``
  (``too_fast`` naming the limit and the legs). The filter then plans again from the last
  command with half the acceleration, down to :data:`FORCE_SCALE_MIN` of
  ``leg_acceleration_max``, and sends that step if the gate passes it; else the gate's braking
  command (which brakes more gently when braking at the limit would break the forces). The
  acceleration it plans with grows back to ``leg_acceleration_max`` by a factor of two every
  :data:`FORCE_SCALE_RECOVERY` seconds. Without masses none of this is computed.

Units: metres, seconds. Nothing here imports ROS.
"""

import dataclasses
from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.findings import Decision, Finding
from stewart_kinematics.limits import CommandGate, LegCommand, LimitModel, limits_of, MOTION
from stewart_kinematics.limits.leg_rates import RATE_SLACK
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.arrays import as_float_array, preview

#: A target farther than the legs cover in this many seconds at full speed is approached
#: through an aim point at that distance (and never nearer than twice the braking distance).
WINDOW_SECONDS = 10.0
#: A planned motion may pass the stroke by this much, metres, for rounding; a step is clipped
#: back into the stroke when it does (by at most this).
STROKE_ROUNDING = 1e-12
#: After a step refused for its leg forces, the acceleration planned with is halved, down to
#: this share of leg_acceleration_max; it doubles back every FORCE_SCALE_RECOVERY seconds.
FORCE_SCALE_MIN = 1.0 / 64.0
FORCE_SCALE_RECOVERY = 0.25


@dataclass(frozen=True, eq=False)
class FilteredCommand(Decision):
    """
    One step of a :class:`CommandFilter`: the command to give, or why none could be computed.

    :param lengths: commanded leg lengths, metres, shape (6,); of a refused step, the last
        command's, not to be given again (:meth:`CommandFilter.send` brakes instead).
    :param velocities: m/s, shape (6,).
    :param accelerations: m/s^2, shape (6,).
    :param settled: True when the command rests on the target.
    :param refusal: ``None`` when the step may be given; a ``stream_held`` finding when no
        step within every limit could be computed.
    :param warnings: a ``stream_braking`` finding when no motion toward the target could be
        planned and the step brakes to rest instead; else empty.
    """

    lengths: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray
    settled: bool
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()

    @property
    def held(self) -> bool:
        """Whether no new command could be computed (the step is refused, ``stream_held``)."""
        return self.refusal is not None


@dataclass(frozen=True, eq=False)
class StreamTarget(Decision):
    """
    The answer of :meth:`CommandFilter.set_target` (and :meth:`CommandFilter.reset`).

    :param lengths: the leg lengths now aimed at, metres, shape (6,); ``None`` when refused.
    :param refusal: why the lengths cannot be a target (``invalid_lengths``, or
        ``out_of_limits`` beyond the stroke), or ``None``.
    :param warnings: none yet.
    :param started: True when this target started the sending (:meth:`CommandFilter.send`).
    """

    lengths: Optional[np.ndarray]
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()
    started: bool = False


class CommandFilter:
    """
    Leg commands that move toward the latest target within velocity, acceleration and jerk.

    :param actuator_limits: ``velocity_max`` and ``acceleration_max`` must be finite;
        ``jerk_max`` may be ``inf`` (acceleration-limited motion).
    :param period: seconds between two commands, positive.
    :param lengths: the legs' starting lengths, at rest, metres, shape (6,).
    :param geometry: the platform, whose stroke every target and every step must keep
        (``None``: no stroke, and no :meth:`send`, which checks each step's pose).
    :raises ValueError: if a limit that must be finite is not, the period is not positive, or
        the starting lengths are not six finite numbers within the stroke.

    >>> from stewart_kinematics import ActuatorLimits, CommandFilter, load_geometry
    >>> home_lengths = load_geometry('config/paper_platform.yaml').home_leg_lengths
    >>> command_filter = CommandFilter(ActuatorLimits(0.05, 0.25, 2.5), 0.01, home_lengths)
    >>> command_filter.set_target(home_lengths + 0.01).accepted   # every leg 10 mm longer
    True
    >>> command = command_filter.step()                  # every 10 ms
    >>> command.velocities, command.settled              # m/s, after 10 ms
    (array([0.000125, 0.000125, 0.000125, 0.000125, 0.000125, 0.000125]), False)
    >>> command_filter.set_target([float('nan')] * 6).refusal.code
    'invalid_lengths'
    """

    def __init__(self, actuator_limits: ActuatorLimits, period: float, lengths, geometry=None):
        import ruckig  # the field's online trajectory generator; only streaming needs it

        if not (math.isfinite(actuator_limits.velocity_max)
                and math.isfinite(actuator_limits.acceleration_max)):
            raise ValueError('streamed commands need finite leg_velocity_max and '
                             'leg_acceleration_max (leg_jerk_max may be .inf), got '
                             f'{actuator_limits.velocity_max!r} and '
                             f'{actuator_limits.acceleration_max!r}')
        if not (isinstance(period, (int, float)) and not isinstance(period, bool)
                and 0.0 < period < math.inf):
            raise ValueError(f'the command period must be positive (seconds), got {period!r}')
        self._ruckig = ruckig
        self._generator = ruckig.Ruckig(6)
        self._input = ruckig.InputParameter(6)
        self._input.max_velocity = [actuator_limits.velocity_max] * 6
        self._input.max_acceleration = [actuator_limits.acceleration_max] * 6
        #: The share of leg_acceleration_max planned with (below 1 after force refusals).
        self.force_scale = 1.0
        self._input.max_jerk = [actuator_limits.jerk_max] * 6
        # Phase synchronisation: from rest (or moving along the jump) the legs move in
        # proportion, a straight line in leg space; otherwise ruckig falls back to
        # synchronising the arrival time only.
        self._input.synchronization = ruckig.Synchronization.Phase
        self.period = period
        self.limits = actuator_limits
        #: Every limit a step must keep: the stroke and the three rates (with rounding slack).
        self.model = LimitModel(geometry, actuator_limits, rate_slack=RATE_SLACK)
        velocity, acceleration, jerk = (actuator_limits.velocity_max,
                                        actuator_limits.acceleration_max, actuator_limits.jerk_max)
        stopping = velocity * (velocity / acceleration + acceleration / jerk)
        #: Farthest aim from the current command, metres (see :data:`WINDOW_SECONDS`).
        self.window = max(velocity * WINDOW_SECONDS, 2.0 * stopping)
        self._stroke = ((limits_of(geometry).leg_length_min, limits_of(geometry).leg_length_max)
                        if geometry else (-math.inf, math.inf))
        #: The last check of each step as sent (:meth:`send`), or ``None`` without a geometry.
        self.gate = (CommandGate(geometry, actuator_limits, timing=MOTION, jerk=True)
                     if geometry is not None else None)
        start = self.reset(lengths)
        if not start.accepted:
            raise ValueError(start.reason)

    def set_mass_properties(self, geometry) -> None:
        """
        Check the next steps with the masses of ``geometry`` (a new payload), the stream kept.

        :param geometry: the filter's geometry carrying other masses
            (:meth:`stewart_kinematics.Geometry.with_mass_properties`).
        """
        if self.gate is not None:
            self.gate.set_mass_properties(geometry)

    def reset(self, lengths) -> StreamTarget:
        """
        Put the command at rest at ``lengths`` (metres, shape (6,)), which is also the target.

        Sending stops until a target is set at a time again (:meth:`set_target`).

        :returns: a :class:`StreamTarget`; refused (nothing changes then) for lengths that are
            not six finite, positive values within the stroke.
        """
        refusal = self._refusal(lengths)
        if refusal is not None:
            return StreamTarget(None, refusal)
        #: The command's state (lengths, velocities, accelerations), six floats each.
        self._position = np.asarray(lengths, dtype=float).tolist()
        self._velocity = [0.0] * 6
        self._acceleration = [0.0] * 6
        self._target = np.array(self._position)
        self._following = None
        self._started = False
        return StreamTarget(self._target.copy())

    @property
    def started(self) -> bool:
        """Return whether sending started: :meth:`send` then gives a step at every call."""
        return self._started

    def start(self, time: float) -> None:
        """
        Start sending at ``time`` (seconds, the node's clock): the command rests where it is.

        :meth:`set_target` with a time calls it for the first target it accepts; :meth:`send`
        then gives a step at every call. A second call changes nothing.

        :raises ValueError: without the geometry, or for a time that is not a finite number.
        """
        if self.gate is None:
            raise ValueError('sending needs the geometry: build the filter with it')
        seconds = _finite_seconds(time)
        if seconds is None:
            raise ValueError(f'the start time must be a finite number of seconds, got '
                             f'{preview(time)}')
        if not self._started:
            self.gate.reset(self._position, time=seconds)
            self._started = True

    def send(self, time: float) -> LegCommand:
        """
        Give the command to send at ``time`` (seconds, the node's clock), checked as sent.

        The step covers the time since the last command sent. It goes through the command
        gate; a step that is held, or that the gate refuses, is replaced by the gate's braking
        command (its ``command_braking`` finding, a refusal class, names the step it
        replaces), from which the filter goes on. Never raises.

        :returns: a :class:`~stewart_kinematics.limits.LegCommand` with the lengths,
            velocities and accelerations to send; refused (nothing to send, the last command
            stands) only when no time passed since the last command (``clock_not_advancing``)
            or not even a braking command could be found.
        """
        if _finite_seconds(time) is None:
            return LegCommand(None, refusal=Finding(
                findings.CLOCK_NOT_ADVANCING, f'the time of a streamed command must be a '
                f'finite number of seconds, got {preview(time)}: nothing sent'))
        self.start(time)
        interval = self.gate.elapsed(time)
        if interval is None:
            return LegCommand(None, refusal=Finding(
                findings.CLOCK_NOT_ADVANCING, 'no time passed since the last streamed command: '
                'nothing sent this period'))
        state = self._state() if self.gate.force_range is not None else None
        step = self.step(interval)
        if not step.accepted:
            command = self.gate.brake(time, replaced=step.refusal)
        else:
            command = self.gate.legs(step.lengths, time, step.velocities, step.accelerations)
            strained = command.violations if _forces_refused(command) else ()
            while _forces_refused(command) and self.force_scale > FORCE_SCALE_MIN:
                # Too much force: plan again from the last command with less acceleration.
                self._restore(state)
                self._scale_acceleration(max(0.5 * self.force_scale, FORCE_SCALE_MIN))
                step = self.step(interval)
                if not step.accepted:
                    break
                command = self.gate.legs(step.lengths, time, step.velocities,
                                         step.accelerations)
            if not step.accepted:
                command = self.gate.brake(time, replaced=step.refusal)
            elif not command.accepted:
                command = self.gate.brake(time, replaced=command.refusal)
                if not command.accepted and state is not None:
                    self._restore(state)   # nothing sent: go on from the last command
            else:
                warnings = step.warnings
                if strained:
                    warnings = (Finding(
                        findings.FORCE_LIMITED,
                        'the step asked for broke the leg forces ('
                        + '; '.join(map(str, strained)) + '): planned again at '
                        f'{self.force_scale:.4g} of leg_acceleration_max',
                        (('acceleration_share', f'{self.force_scale:.6g}'),)
                        + findings.violation_details(strained)),) + warnings
                if warnings:
                    command = dataclasses.replace(command, warnings=warnings)
                if self.force_scale < 1.0:
                    self._scale_acceleration(min(1.0, self.force_scale * 2.0 ** (
                        interval / FORCE_SCALE_RECOVERY)))
        if command.braking and command.accepted:
            # Go on from what was sent: a new plan from the braking command's state.
            self._position = command.lengths.tolist()
            self._velocity = command.velocities.tolist()
            self._acceleration = command.accelerations.tolist()
            self._following = None
        return command

    def _state(self):
        """Return the command's state and the plan's, to go back to (:meth:`_restore`)."""
        following = self._following
        return (self._position, self._velocity, self._acceleration, following,
                None if following is None else following.time)

    def _restore(self, state) -> None:
        """Go back to a state of :meth:`_state`, with no plan to follow (a new one is made)."""
        self._position, self._velocity, self._acceleration, following, time = state
        if following is not None:
            following.time = time
        self._following = None

    def _scale_acceleration(self, scale: float) -> None:
        """Plan with ``scale`` of leg_acceleration_max from now on (a new plan next step)."""
        if scale != self.force_scale:
            self.force_scale = scale
            self._input.max_acceleration = [self.limits.acceleration_max * scale] * 6
            self._following = None

    def set_target(self, lengths, time: Optional[float] = None) -> StreamTarget:
        """
        Aim at new leg lengths (metres, shape (6,)), to be reached at rest.

        :param time: when the target arrives, seconds (the node's clock), or ``None``: with a
            finite time, the first target accepted starts the sending there (:meth:`start`;
            the command rests where it is until then).
        :returns: a :class:`StreamTarget`: accepted, or refused (``invalid_lengths``, or
            ``out_of_limits`` beyond the stroke) while the filter keeps moving toward its last
            target. Never raises.
        """
        refusal = self._refusal(lengths)
        if refusal is not None:
            return StreamTarget(None, refusal)
        self._target = np.array(lengths, dtype=float)
        started = False
        if (self.gate is not None and not self._started
                and _finite_seconds(time) is not None):
            self.start(time)
            started = True
        return StreamTarget(self._target.copy(), started=started)

    def stopping_lengths(self) -> Optional[np.ndarray]:
        """
        Return where the legs come to rest if they stop as soon as the limits allow, metres.

        The end of ruckig's braking plan from the command's state (every leg slowed within
        the velocity, acceleration and jerk limits, none synchronised to another): set as the
        target (:meth:`set_target`), the stream stops there, without a jump in any rate. What
        a managed ik_node does when it is deactivated mid-stream.

        :returns: shape (6,), or ``None`` when no braking plan could be made.
        """
        plan = self._new_plan(None)
        if plan is None:
            return None
        try:
            position, _, _ = plan.trajectory.at_time(plan.trajectory.duration)
        except (ValueError, RuntimeError, ArithmeticError):
            return None
        stopped = np.array(position, dtype=float)
        return stopped if np.all(np.isfinite(stopped)) else None

    @property
    def target(self) -> np.ndarray:
        """Return the leg lengths aimed at, metres, shape (6,)."""
        return self._target.copy()

    def step(self, interval: Optional[float] = None) -> FilteredCommand:
        """
        Advance the command by ``interval`` seconds toward the target; never raises.

        The plan toward the target (ruckig's, from the command's state) is followed as long
        as the target and the aim stay; a new one is made when they change.

        :param interval: seconds since the last step, positive (default: the period).
        :returns: the new command, within every limit; or, when no step within them could be
            computed, the last command with ``held`` set and the reason.
        """
        interval = self.period if interval is None else interval
        if not (isinstance(interval, (int, float)) and 0.0 < interval < math.inf):
            return self._held(f'the step must cover a positive time (seconds), got {interval!r}')
        following = self._following
        if following is not None and following.aim is not None and not self._new_aim(following):
            state = self._next_state(following, interval)
            if state is not None:
                return self._advance(state, following)
        plan = self._new_plan(self._aim())
        if plan is not None:
            state = self._next_state(plan, interval)
            if state is not None:
                self._following = plan
                return self._advance(state, plan)
        finding = None
        if following is None or following.aim is not None:
            # Brake: a new plan to rest, made once; a braking plan in progress is followed.
            following = self._new_plan(None)
            finding = Finding(
                findings.STREAM_BRAKING,
                f'no motion toward the target {np.round(self._target, 6).tolist()} m within the '
                'limits could be planned from the current command: braking to rest')
        state = None if following is None else self._next_state(following, interval)
        if state is not None:
            self._following = following
            return self._advance(state, following, finding)
        self._following = None
        return self._held('no step within the limits could be computed')

    def _held(self, reason) -> FilteredCommand:
        """Return the last command, refused (``held``), with the reason no step was computed."""
        return FilteredCommand(np.array(self._position), np.array(self._velocity),
                               np.array(self._acceleration), False,
                               Finding(findings.STREAM_HELD, reason))

    def _new_aim(self, plan) -> bool:
        """Whether the plan followed no longer aims right: a new target, or a near aim point."""
        if plan.target is not self._target:
            return True
        if plan.final:
            return False
        # An aim point on the way to a far target: aim farther before the plan starts braking.
        return max(abs(aim - position) for aim, position in zip(
            plan.aim.tolist(), self._position)) < 0.5 * self.window

    def _aim(self):
        """Return the target, or the point :attr:`window` away on the straight line toward it."""
        delta = self._target - self._position
        distance = float(np.max(np.abs(delta)))
        if distance <= self.window:
            return self._target
        return self._position + delta * (self.window / distance)

    def _new_plan(self, aim) -> Optional['_Plan']:
        """
        Plan from the command's state to rest at ``aim`` (``None``: to rest, braking).

        :returns: the plan, or ``None`` when ruckig refuses or the motion would leave the
            stroke.
        """
        ruckig = self._ruckig
        self._input.current_position = list(self._position)
        self._input.current_velocity = list(self._velocity)
        self._input.current_acceleration = list(self._acceleration)
        # Braking: each leg stops as soon as it can (no synchronisation, which would slow some
        # legs and let them run farther), so no farther than any plan it was following.
        self._input.control_interface = (ruckig.ControlInterface.Velocity if aim is None
                                         else ruckig.ControlInterface.Position)
        self._input.synchronization = (ruckig.Synchronization.No if aim is None
                                       else ruckig.Synchronization.Phase)
        if aim is not None:
            self._input.target_position = aim.tolist()
        self._input.target_velocity = [0.0] * 6
        self._input.target_acceleration = [0.0] * 6
        trajectory = ruckig.Trajectory(6)
        try:
            result = self._generator.calculate(self._input, trajectory)
            if result not in (ruckig.Result.Working, ruckig.Result.Finished):
                return None
            low, high = self._stroke
            # A plan to a position must stay within the stroke all along. (ruckig's position
            # extrema of a velocity-control plan are not reliable; each braking step is checked
            # as every step is, below.)
            if not math.isfinite(trajectory.duration) or aim is not None and not all(
                    extremum.min >= low - STROKE_ROUNDING
                    and extremum.max <= high + STROKE_ROUNDING
                    for extremum in trajectory.position_extrema):
                return None
        except (ValueError, RuntimeError, ArithmeticError):
            # ruckig raises for inputs it refuses (RuckigError is a RuntimeError; an outcome
            # its Python enum lacks, such as -101, a ValueError): no plan.
            return None
        return _Plan(trajectory, aim, self._target)

    def _next_state(self, plan, interval):
        """Return the state ``interval`` along ``plan`` if every limit allows it, or None."""
        time = min(plan.time + interval, plan.trajectory.duration)
        try:
            position, velocity, acceleration = plan.trajectory.at_time(time)
        except (ValueError, RuntimeError, ArithmeticError):
            return None
        low, high = self._stroke
        position = [min(max(length, low), high) for length in position]
        jerks = [(new - old) / interval for new, old in zip(acceleration, self._acceleration)]
        if not all(map(math.isfinite, position + velocity + acceleration)) or (
                not self.model.leg_state_allowed(lengths=position, velocities=velocity,
                                                 accelerations=acceleration, jerks=jerks)):
            return None
        return position, velocity, acceleration, time

    def _advance(self, state, plan, finding=None) -> FilteredCommand:
        """Make ``state`` the command, at its time along ``plan``."""
        self._position, self._velocity, self._acceleration, plan.time = state
        settled = (plan.final and plan.target is self._target
                   and plan.time >= plan.trajectory.duration)
        return FilteredCommand(np.array(self._position), np.array(self._velocity),
                               np.array(self._acceleration), settled,
                               warnings=() if finding is None else (finding,))

    def _refusal(self, lengths) -> Optional[Finding]:
        """Say why leg lengths cannot be a target, or return ``None``."""
        try:
            values = np.array(as_float_array(lengths, 'target lengths'))
        except ValueError as error:
            return Finding(findings.INVALID_LENGTHS, str(error))
        if values.shape != (6,) or not np.all(np.isfinite(values)) or not np.all(values > 0.0):
            return Finding(findings.INVALID_LENGTHS,
                           f'target lengths must be 6 finite, positive values (metres), got '
                           f'{preview(values)}')
        violations = self.model.leg_state_violations(lengths=values)
        if violations:
            return findings.out_of_limits('the target lengths are', violations)
        return None


def _forces_refused(command) -> bool:
    """Whether the gate refused a command for its leg forces (``leg_force_min``/``_max``)."""
    return not command.accepted and any(
        violation.limit in ('leg_force_min', 'leg_force_max')
        for violation in command.violations)


def _finite_seconds(time) -> Optional[float]:
    """Return ``time`` as a float if it is a finite real number (not a bool), else ``None``."""
    if isinstance(time, bool) or not isinstance(time, (int, float, np.integer, np.floating)):
        return None
    return float(time) if math.isfinite(time) else None


class _Plan:
    """
    A ruckig trajectory being followed: to rest at ``aim`` (``None``: braking), for a target.

    ``target`` is the filter's target array it was made for (a new target is a new array);
    ``final`` says that the aim is that target itself, not a point on the way.
    """

    __slots__ = ('trajectory', 'aim', 'target', 'final', 'time')

    def __init__(self, trajectory, aim, target):
        self.trajectory, self.aim, self.target, self.time = trajectory, aim, target, 0.0
        self.final = aim is target
