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
Motion cueing as one decision object: a vehicle's motion in, a pose within every limit out.

:class:`MotionCueing` takes samples of the vehicle's specific force and angular velocity at the
driver's head, each with its time, and returns the platform pose to command: the classical
washout (:mod:`.washout`) turns the sample into a cue, :class:`~.cue_limiter.CueLimiter` scales it
into the limits and follows it within the actuators' speed, and the specific force felt at the
head is estimated as the poses stream (:mod:`.perception`).

Time: each sample's time (seconds, such as a message stamp) sets the washout's step, ``dt`` =
this time minus the previous sample's, so the filters run on the input's own clock whatever
its jitter. A time that does not come after the previous one is refused and nothing moves (the
pose holds). A gap longer than ``max_input_gap`` counts as ``max_input_gap``: the washout's
clock pauses, the cue carries on from where it was, with an ``input_gap`` warning. The platform
is paced by the times its commands are sent (``command_time``: the node's clock, wall or
simulated), not by the input's stamps: a recording played ten times fast gives the cue ten times
fast, and the actuators follow it within their limits, in real time. Without a command time
(an offline run) the commands are sent on the input's clock.

Every command comes with the command gate's verdict (:class:`~stewart_kinematics.limits.
CommandGate`, a motion: every pose limit and the leg velocity and acceleration between
consecutive commands, on the very numbers of the ``target_pose`` message, tool frame
included); a command the gate refuses is replaced by its braking command (``command_braking``).
With masses and a force limit, a command refused for its leg forces (with its motion's twist
and acceleration) is first taken again with a gentler follower (:attr:`~.cue_limiter.
CueLimiter.force_scale` halved, down to :data:`~.cue_limiter.FORCE_SCALE_MIN`; a
``force_limited`` warning naming the legs), and braked only when that fails too.

The input watchdog: a node calls :meth:`MotionCueing.watch` on a timer (every
:attr:`MotionCueing.watchdog_period`) with its clock. When no sample came for
``input_timeout`` seconds (a sample refused for its time counts as none), the input is lost:
the next sample starts a new time line (:meth:`MotionCueing.restart_time`), and each call
takes the platform a step at rest (:meth:`MotionCueing.rest`) until it rests at home.

The vehicle's frame: samples are in the vehicle frame (x forward, y left, z up); with a
``frame_id``, one in ``imu_frame`` is turned into the vehicle frame by
``imu_orientation_rpy``, and one in a frame it cannot place is refused (``wrong_frame``).

Refusals: :meth:`MotionCueing.cue` (the decision, as a node uses it) never raises for what it
is given: a malformed, non-finite or absurd sample (beyond ``max_specific_force`` or
``max_angular_velocity``) is refused with an ``invalid_vehicle_motion`` finding, and the
platform takes the step as if the vehicle were at rest, so that a stream of bad samples
eases it back to neutral. :meth:`MotionCueing.step` is the same for a Python loop that wants an
exception instead: it raises ``ValueError`` naming the argument. Nothing here imports ROS.

>>> from stewart_kinematics.parameters import load_geometry
>>> cueing = MotionCueing(load_geometry(['config/paper_platform.yaml',
...                                      'config/example_limits.yaml']))
>>> first = cueing.step(0.0, [0.0, 0.0, 9.81], [0.0, 0.0, 0.0])
>>> step = cueing.step(0.01, [2.0, 0.0, 9.81], [0.0, 0.0, 0.0])
>>> step.accepted, step.workspace_scale, bool(step.pose[0] > first.pose[0])
(True, 1.0, True)
>>> cueing.cue(0.02, [float('nan'), 0.0, 9.81], [0.0, 0.0, 0.0]).refusal.code
'invalid_vehicle_motion'
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.cueing.cue_limiter import CueLimiter, FORCE_SCALE_MIN
from stewart_kinematics.cueing.mpc_cueing import MpcCueing
from stewart_kinematics.cueing.perception import PerceptionEstimator
from stewart_kinematics.cueing.settings import CueingSettings
from stewart_kinematics.cueing.washout import ClassicalWashout
from stewart_kinematics.findings import (
    COMMAND_BRAKING,
    Decision,
    Finding,
    FORCE_LIMITED,
    INPUT_GAP,
    INVALID_VEHICLE_MOTION,
    TIME_NOT_INCREASING,
    violation_details,
    WRONG_FRAME,
)
from stewart_kinematics.limits import CommandGate, LegCommand, MOTION
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import (
    actuator_limits_from_settings,
    check_values,
    defaults,
    geometry_from_settings,
    GeometrySettings,
    MOTION_CUEING_PARAMETERS,
)

#: Longest period of the input watchdog, seconds (``input_timeout / 2`` when that is shorter).
WATCHDOG_PERIOD = 0.02
#: Leg speed below which :meth:`MotionCueing.brake` takes the legs as resting, m/s.
REST_SPEED = 1e-9


@dataclass(frozen=True)
class CueStep(Decision):
    """
    What one sample gave.

    :param time: the sample's time, seconds.
    :param pose: the platform pose to command, ``[X, Y, Z, alpha, beta, gamma]`` (metres,
        radians, base frame), shape (6,); ``None`` when nothing moved (a refused time).
    :param lengths: its leg lengths, metres, shape (6,), or ``None`` with ``pose``.
    :param target: the pose of the cue as scaled into the limits, shape (6,), or ``None``.
    :param displacement: the washout's head displacement, metres, base frame, shape (3,).
    :param angles: the washout's roll, pitch, yaw (tilt plus rotation), radians, shape (3,).
    :param tilt: roll and pitch of tilt coordination, radians, shape (2,).
    :param tilt_rate: their rates, rad/s, shape (2,).
    :param workspace_scale: the share of the displacement and of the rotational channel kept
        to stay inside the limits, in [0, 1].
    :param tilt_scale: the share of the tilt kept, in [0, 1] (below 1 only when the tilt alone
        would leave the limits).
    :param acceleration_scale: the share of the wanted change of motion the actuators allowed.
    :param perceived: ``(time, specific_force)`` felt at the head at the previous sample
        (platform frame, m/s^2), or ``None`` before three samples.
    :param refusal: why the sample was refused (its step was taken at rest), or ``None``.
    :param warnings: findings about the step: an input gap, the cue scaled, the actuators
        limiting, a braking command (``command_braking``, of the refusal class).
    :param command: the command gate's verdict on the ``target_pose`` message of ``pose`` (the
        tool frame's numbers), sent at its time; ``None`` for a refused time.
    """

    time: float
    pose: Optional[np.ndarray]
    lengths: Optional[np.ndarray] = None
    target: Optional[np.ndarray] = None
    displacement: Optional[np.ndarray] = None
    angles: Optional[np.ndarray] = None
    tilt: Optional[np.ndarray] = None
    tilt_rate: Optional[np.ndarray] = None
    workspace_scale: float = 1.0
    tilt_scale: float = 1.0
    acceleration_scale: float = 1.0
    perceived: Optional[Tuple[float, np.ndarray]] = None
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()
    command: Optional[LegCommand] = None


class MotionCueing:
    """
    Classical washout, limits and perception, stepped sample by sample.

    :param geometry: the platform and its limits (:func:`stewart_kinematics.load_geometry`).
    :param settings: a :class:`~stewart_kinematics.cueing.CueingSettings` (default: the
        literature's).
    :param actuator_limits: leg velocity and acceleration limits (default: none).
    :param frames: the :class:`stewart_kinematics.FrameTree` of the ``target_pose`` messages
        (their tool frame), or ``None``: the platform frame.
    :raises ValueError: if the margins leave no room around the home pose.
    """

    def __init__(self, geometry, settings: Optional[CueingSettings] = None,
                 actuator_limits: Optional[ActuatorLimits] = None, frames=None):
        self.geometry = geometry
        self.settings = settings if settings is not None else CueingSettings()
        self.actuator_limits = (actuator_limits if actuator_limits is not None
                                else ActuatorLimits())
        self.frames = frames
        self.limiter = CueLimiter(geometry, self.actuator_limits, self.settings)
        self.washout = (MpcCueing(self.settings, self.limiter)
                        if self.settings.cueing_method == 'mpc'
                        else ClassicalWashout(self.settings))
        #: The last check of every command, as sent: a motion (leg rates by the send times).
        self.gate = CommandGate(geometry, self.actuator_limits, timing=MOTION, frames=frames,
                                sends='poses')
        #: The IMU frame's orientation in the vehicle frame (vectors from one to the other).
        self._imu_rotation = euler_zyx_to_matrix(np.array(self.settings.imu_orientation_rpy))
        self.perception = PerceptionEstimator(self.settings.head_position, self.settings.gravity)
        self._rest_force = np.array([0.0, 0.0, self.settings.gravity])
        self.time = None
        #: Seconds of the input's motion so far (input steps and rest steps): the clock the
        #: commands are sent on in an offline run.
        self._clock = None
        #: Seconds of commands so far: the perception's clock.
        self._felt_clock = None
        #: The watchdog's clock (the commands' times): the last sample whose time was taken,
        #: and the last call of :meth:`watch`.
        self._last_input = None
        self._last_watch = None

    @classmethod
    def from_parameters(cls, values: dict, frames=None) -> 'MotionCueing':
        """
        Build it from ROS parameter values, as motion_cueing_node declares them.

        :param values: the geometry, limits and cueing parameters (a missing one keeps its
            default), e.g. read from paper_platform.yaml, example_limits.yaml and
            motion_cueing.yaml.
        :raises ValueError: naming the parameter, for a value that is not allowed.
        """
        cueing_values = {spec.name: values[spec.name] for spec in MOTION_CUEING_PARAMETERS
                         if spec.name in values}
        merged = defaults(MOTION_CUEING_PARAMETERS)
        merged.update(cueing_values)
        check_values(MOTION_CUEING_PARAMETERS, merged)
        geometry = GeometrySettings.from_values(values)
        return cls(geometry_from_settings(geometry), CueingSettings.from_parameters(merged),
                   actuator_limits_from_settings(geometry), frames)

    @property
    def pose(self) -> np.ndarray:
        """Return the last pose commanded (the home pose before the first sample)."""
        return self.limiter.pose.copy()

    def set_frames(self, frames) -> None:
        """
        Take a new frame tree (a tool frame changed at run time) from the next command on.

        The platform's motion goes on from where it is; the ``target_pose`` messages carry the
        new tool frame's pose, checked as sent.

        :param frames: a :class:`stewart_kinematics.FrameTree`, or ``None``: the platform frame.
        """
        self.frames = frames
        self.gate.frames = frames

    def settled(self, tolerance: float = 1e-7) -> bool:
        """
        Return whether the platform rests at home.

        Every pose coordinate and leg velocity within ``tolerance`` (metres, radians, m/s) of
        home and of rest.
        """
        limiter = self.limiter
        return bool(np.all(np.abs(limiter.pose - self.geometry.home_pose) <= tolerance)
                    and np.all(np.abs(limiter.leg_velocities) <= tolerance))

    def reset(self) -> None:
        """
        Wash out to neutral: forget the input's history; the platform glides home.

        The washout settles on the next sample (no onset cue from a sustained input), the tilt
        starts again from neutral, and the platform moves to the new cue within the actuator
        limits, from where it is.
        """
        self.washout.reset()

    def restart_time(self) -> None:
        """
        Start a new time line: the next sample's time may be anything, even before the last.

        For an input lost and found again (a restarted simulator, a recording played again, or a
        stream whose one absurd stamp put the last time years ahead): its first sample is taken
        as the first one ever (no step), the motion goes on from where it is.
        """
        self.time = None

    def refusal(self, time, specific_force, angular_velocity) -> Optional[Finding]:
        """
        Say why a sample cannot be used, or return ``None``.

        The time comes first: a refused time means the sample is not used at all.
        """
        try:
            time = float(time)
        except (TypeError, ValueError):
            return Finding(TIME_NOT_INCREASING,
                           f'time must be a number of seconds, got {preview(time)}')
        if not math.isfinite(time):
            return Finding(TIME_NOT_INCREASING, f'time must be finite, got {time!r}')
        if self.time is not None and not time > self.time:
            return Finding(
                TIME_NOT_INCREASING,
                f'time {time:.9f} s does not come after the previous sample ({self.time:.9f} '
                's): a repeated or backward stamp; sample ignored (set header.stamp)',
                (('time', repr(time)), ('previous time', repr(self.time))))
        s = self.settings
        for name, value, largest, unit in (
                ('specific_force', specific_force, s.max_specific_force, 'm/s^2'),
                ('angular_velocity', angular_velocity, s.max_angular_velocity, 'rad/s')):
            try:
                vector = as_float_array(value, name)
            except ValueError as error:
                return Finding(INVALID_VEHICLE_MOTION, str(error))
            if vector.shape != (3,):
                return Finding(INVALID_VEHICLE_MOTION,
                               f'{name} must have shape (3,), got {vector.shape}')
            if not np.all(np.isfinite(vector)):
                return Finding(INVALID_VEHICLE_MOTION,
                               f'{name} must be finite, got {vector.tolist()}')
            norm = float(np.linalg.norm(vector))
            if not norm <= largest:
                return Finding(
                    INVALID_VEHICLE_MOTION,
                    f'{name} of magnitude {norm:.6g} {unit} is beyond {largest:g} {unit}: '
                    'absurd for a vehicle', ((name, str(vector.tolist())),))
        return None

    def vehicle_frame_refusal(self, frame_id: str) -> Optional[Finding]:
        """Say why a sample's frame cannot be placed in the vehicle frame, or return ``None``."""
        settings = self.settings
        known = ['', settings.vehicle_frame] + ([settings.imu_frame] if settings.imu_frame else [])
        if frame_id in known:
            return None
        return Finding(WRONG_FRAME, (
            f'the sample is in frame {preview(frame_id)}, which cannot be placed in the vehicle '
            f'frame: known are {known[1:]!r} (and an empty frame_id, the vehicle frame); set '
            'vehicle_frame, or imu_frame and imu_orientation_rpy_deg'))

    def cue(self, time, specific_force, angular_velocity, command_time: Optional[float] = None,
            frame_id: Optional[str] = None) -> CueStep:
        """
        Decide on one sample: cue it, or refuse it and ease toward neutral.

        :param time: the sample's time, seconds (a message stamp).
        :param specific_force: m/s^2, at the head, shape (3,), in the vehicle frame (or in
            ``frame_id``).
        :param angular_velocity: rad/s, shape (3,), likewise.
        :param command_time: when the command is sent, seconds (the node's clock); ``None``:
            on the input's clock (an offline run).
        :param frame_id: the sample's frame (a message's ``header.frame_id``), or ``None``:
            the vehicle frame.
        :returns: a :class:`CueStep`; never raises for bad input.
        """
        refusal = self.refusal(time, specific_force, angular_velocity)
        if refusal is not None and refusal.code == TIME_NOT_INCREASING:
            return CueStep(time=self.time, pose=None, refusal=refusal)
        if command_time is not None:
            self._last_input = float(command_time)   # input, for the watchdog
        if refusal is None and frame_id is not None:
            refusal = self.vehicle_frame_refusal(frame_id)
            if refusal is None and frame_id and frame_id == self.settings.imu_frame:
                specific_force = self._imu_rotation @ np.asarray(specific_force, dtype=float)
                angular_velocity = self._imu_rotation @ np.asarray(angular_velocity, dtype=float)
        if refusal is not None:
            specific_force, angular_velocity = self._rest_force, np.zeros(3)
        return self._advance(float(time), specific_force, angular_velocity, refusal,
                             command_time)

    def step(self, time, specific_force, angular_velocity,
             command_time: Optional[float] = None) -> CueStep:
        """
        Cue one sample, or raise: :meth:`cue` for a loop that wants exceptions.

        :raises ValueError: naming the argument, for a malformed, non-finite or absurd sample,
            or a time that does not come after the previous one.
        """
        refusal = self.refusal(time, specific_force, angular_velocity)
        if refusal is not None:
            raise ValueError(refusal.message)
        return self._advance(float(time), specific_force, angular_velocity, None, command_time)

    def rest(self, dt: float, command_time: Optional[float] = None) -> CueStep:
        """
        Advance ``dt`` seconds as if the vehicle were at rest: no input came (a watchdog).

        The sample time stays the last one received; the next sample's step then covers the
        pause (as an input gap when longer than ``max_input_gap``).

        :param command_time: when the command is sent, seconds (the node's clock); ``None``:
            ``dt`` after the last command.
        :raises ValueError: if ``dt`` is not a positive, finite number of seconds.
        """
        if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0.0):
            raise ValueError(f'dt must be a positive, finite number of seconds, got {dt!r}')
        time = (self.time or 0.0)
        if command_time is None and self.gate.last_time is not None:
            command_time = self.gate.last_time + dt
        return self._move(time, min(dt, self.settings.max_input_gap), self._rest_force,
                          np.zeros(3), None, [], command_time)

    @property
    def watchdog_period(self) -> Optional[float]:
        """Return the seconds between two calls of :meth:`watch`; ``None``: no watchdog."""
        timeout = self.settings.input_timeout
        return min(WATCHDOG_PERIOD, timeout / 2.0) if timeout > 0.0 else None

    def watch(self, command_time: float) -> Optional[CueStep]:
        """
        Watch the input: without a sample for ``input_timeout``, ease the platform home.

        Called on a timer (every :attr:`watchdog_period`) with the node's clock, the clock of
        :meth:`cue`'s ``command_time``. The input is lost when the last sample whose time was
        taken came ``input_timeout`` seconds or more before (none yet: not lost). Then the next
        sample starts a new time line (:meth:`restart_time`), and, until the platform rests at
        home (:meth:`settled`), each call takes a step at rest (:meth:`rest`) covering the time
        since the last call.

        :param command_time: seconds, the node's clock.
        :returns: the :class:`CueStep` whose accepted ``command`` is to be sent (stamped now:
            no sample to stamp it with), or ``None``: nothing to send (input flowing, none
            yet, the platform at rest, no time passed, a time that is not a finite number, or
            nothing could be sent). Never raises.
        """
        try:
            now = float(command_time)
        except (TypeError, ValueError):
            return None
        if not math.isfinite(now):
            return None
        last_watch, self._last_watch = self._last_watch, now
        timeout = self.settings.input_timeout
        if timeout <= 0.0 or self._last_input is None or now - self._last_input < timeout:
            return None
        self.restart_time()   # whatever comes next starts a new time line
        if last_watch is None or not now > last_watch or self.settled():
            return None
        step = self.rest(now - last_watch, now)
        return step if step.command.accepted else None

    def brake(self, command_time: float) -> Optional[CueStep]:
        """
        Slow the platform to rest where it is: the command gate's braking, a stop asked for.

        Each call gives one braking command (every leg slowed at the gate's braking share of
        the acceleration limit, within the velocity and acceleration limits; see
        :meth:`stewart_kinematics.limits.CommandGate.brake`), which the motion follows on from,
        as from a step the gate refused; called each period until it returns ``None``, the
        platform rests. Then :meth:`reset` makes the next samples glide it home within the
        limits. What a managed motion_cueing_node does when it is deactivated: easing home
        takes the washout's time (tens of seconds from a sustained cue), braking a fraction of
        a second.

        :param command_time: when the command is sent, seconds (the node's clock, after the
            last command).
        :returns: the :class:`CueStep` whose accepted ``command`` is to be sent, or ``None``:
            the legs rest already (every leg velocity within :data:`REST_SPEED`), no time
            passed, or no braking command could be found. Never raises.
        """
        limiter = self.limiter
        if np.all(np.abs(limiter.leg_velocities) <= REST_SPEED):
            return None
        try:
            command_time = float(command_time)
        except (TypeError, ValueError):
            return None
        interval = self.gate.elapsed(command_time)
        if interval is None:
            return None
        previous = (limiter.pose.copy(), limiter.lengths.copy())
        command = self.gate.brake(command_time)
        if not command.accepted:
            return None
        limiter.take_sent(command.pose, command.lengths, interval, previous)
        return CueStep(time=self.time, pose=command.pose, lengths=command.lengths,
                       warnings=command.warnings, command=command)

    def _advance(self, time, specific_force, angular_velocity, refusal,
                 command_time) -> CueStep:
        warnings = []
        if self.time is None:
            dt = 0.0
        else:
            dt = time - self.time
            if dt > self.settings.max_input_gap:
                warnings.append(Finding(
                    INPUT_GAP, f'{dt:.6g} s since the previous sample, more than max_input_gap '
                    f'({self.settings.max_input_gap:g} s): counted as max_input_gap',
                    (('gap', f'{dt:.6g} s'),)))
                dt = self.settings.max_input_gap
        self.time = time
        return self._move(time, dt, specific_force, angular_velocity, refusal, warnings,
                          command_time)

    def _move(self, time, dt, specific_force, angular_velocity, refusal, warnings,
              command_time) -> CueStep:
        washout = self.washout.step_checked(specific_force, angular_velocity, dt)
        if self._clock is None or dt > 0.0:
            self._clock = 0.0 if self._clock is None else self._clock + dt
        # Offline, commands are sent on the motion's own clock (the input's, gaps capped).
        command_time = self._clock if command_time is None else float(command_time)
        limiter = self.limiter
        previous = (limiter.pose.copy(), limiter.lengths.copy())
        interval = self.gate.elapsed(command_time)
        target = None
        workspace_scale, tilt_scale = limiter.scale, limiter.tilt_scale
        acceleration_scale = 1.0
        checks_forces = interval is not None and self.gate.force_range is not None
        state = limiter.state() if checks_forces else None
        given = list(warnings) + list(getattr(washout, 'findings', ()))
        strained = ()
        while True:
            if interval is not None:
                limited = limiter.step(washout.displacement, washout.rotation, washout.tilt,
                                       interval)
                warnings = given + list(limited.findings)
                pose, target = limited.pose, limited.target
                workspace_scale, tilt_scale = limited.workspace_scale, limited.tilt_scale
                acceleration_scale = limited.acceleration_scale
            else:
                # No time passed since the last command: the platform stays where it is.
                pose = limiter.pose.copy()
            command = None if pose is None else self.gate.pose_vector(self._tool_pose(pose),
                                                                      command_time)
            if not (checks_forces and _forces_refused(command)
                    and limiter.force_scale > FORCE_SCALE_MIN):
                break
            # Too much force: the same step again, with a gentler follower.
            strained = strained or command.violations
            limiter.restore(state)
            limiter.set_force_scale(max(0.5 * limiter.force_scale, FORCE_SCALE_MIN))
        if checks_forces and command is not None and command.accepted:
            if strained:
                warnings.append(Finding(
                    FORCE_LIMITED, 'the pose asked for broke the leg forces ('
                    + '; '.join(map(str, strained)) + f'): followed at '
                    f'{limiter.force_scale:.4g} of the leg acceleration limit',
                    (('acceleration_share', f'{limiter.force_scale:.6g}'),)
                    + violation_details(strained)))
            else:
                limiter.recover_force_scale(interval)
        if command is None or not command.accepted:
            replaced = command.refusal if command is not None else Finding(
                COMMAND_BRAKING, 'no pose of the next command could be found')
            command = self.gate.brake(command_time, replaced=replaced)
            if command.accepted:
                pose = command.pose
                limiter.take_sent(pose, command.lengths, interval, previous)
                warnings = [warning for warning in warnings if warning.code != COMMAND_BRAKING]
                warnings.extend(command.warnings)
            else:
                # Nothing can be sent: the last command stands, and the motion with it.
                pose = None
                limiter.take_sent(*previous, interval or 1.0, previous)
        perceived = None
        if pose is not None and (self._felt_clock is None or interval is not None):
            # Felt in the time the commands take: the perception's clock is theirs.
            self._felt_clock = (0.0 if self._felt_clock is None
                                else self._felt_clock + (interval or 0.0))
            perceived = self.perception.update(self._felt_clock, pose, time)
        return CueStep(
            time=time, pose=pose, lengths=None if pose is None else command.lengths,
            target=target, displacement=washout.displacement, angles=washout.angles,
            tilt=washout.tilt, tilt_rate=washout.tilt_rate, workspace_scale=workspace_scale,
            tilt_scale=tilt_scale, acceleration_scale=acceleration_scale, perceived=perceived,
            refusal=refusal, warnings=tuple(warnings), command=command)

    def _tool_pose(self, pose) -> np.ndarray:
        """Return the pose of the ``target_pose`` message's frame (the tool frame's)."""
        return pose if self.frames is None else self.frames.tool_pose_vector(pose)


def _forces_refused(command) -> bool:
    """Whether the gate refused a command for its leg forces (``leg_force_min``/``_max``)."""
    return command is not None and not command.accepted and any(
        violation.limit in ('leg_force_min', 'leg_force_max')
        for violation in command.violations)
