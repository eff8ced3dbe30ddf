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

Run-time controls (:mod:`.controls`): :meth:`MotionCueing.set_gains` changes the master
intensity and the channel gains, ramped over ``gain_ramp_time`` (never a jump), refused with the
reason where the cue would leave the platform's travel; :meth:`MotionCueing.stop` brakes the
platform to rest and takes it down to park over ``soft_stop_time``, :meth:`MotionCueing.start`
up from park to neutral over ``soft_start_time`` (leg velocity and acceleration within the
actuator limits: ruckig's motion, each command through the command gate);
:meth:`MotionCueing.pause` brakes the platform to rest where it is and holds it there, the
washout frozen, and :meth:`MotionCueing.resume` goes on cueing from that state. The motions of
start, stop and pause are stepped by :meth:`MotionCueing.operate`, on a timer. While not cueing
(:attr:`MotionCueing.mode`), samples are not cued (``cueing_held``) and the watchdog rests.

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

import dataclasses
from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics.cueing.controls import (
    ControlAnswer,
    effective_gains,
    GainCheck,
    GainRamp,
    lowest_pose,
    SoftMotion,
    WashoutGains,
)
from stewart_kinematics.cueing.cue_limiter import CueLimiter, FORCE_SCALE_MIN
from stewart_kinematics.cueing.limit_margins import pose_violations
from stewart_kinematics.cueing.mpc_cueing import MpcCueing
from stewart_kinematics.cueing.perception import PerceptionEstimator
from stewart_kinematics.cueing.settings import CueingSettings
from stewart_kinematics.cueing.vehicle_preview import input_preview, interval_means
from stewart_kinematics.cueing.washout import ClassicalWashout
from stewart_kinematics.findings import (
    COMMAND_BRAKING,
    CUEING_HELD,
    Decision,
    Finding,
    FORCE_LIMITED,
    GAIN_REFUSED,
    INPUT_GAP,
    INVALID_VEHICLE_MOTION,
    TIME_NOT_INCREASING,
    violation_details,
    WRONG_FRAME,
)
from stewart_kinematics.limits import CommandGate, LegCommand, MOTION
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.arrays import as_float_array, preview, seconds_text
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.inverse import inverse_kinematics
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import (
    actuator_limits_from_settings,
    check_values,
    CUEING_CONTROL_PARAMETERS,
    CueingControlSettings,
    defaults,
    geometry_from_settings,
    GeometrySettings,
    MOTION_CUEING_PARAMETERS,
)

#: Longest period of the input watchdog, seconds (``input_timeout / 2`` when that is shorter).
WATCHDOG_PERIOD = 0.02
#: Leg speed below which :meth:`MotionCueing.brake` takes the legs as resting, m/s.
REST_SPEED = 1e-9

#: What the platform does (:attr:`MotionCueing.mode`): cues the samples; brakes to rest to
#: pause, then holds; rests at park; moves up from park; brakes, then moves down to park.
CUEING = 'cueing'
PAUSING = 'pausing'
PAUSED = 'paused'
PARKED = 'parked'
STARTING = 'starting'
STOPPING = 'stopping'


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
    :param controls: the run-time controls' settings (intensity, ramp and soft times, park),
        a :class:`~stewart_kinematics.parameters.CueingControlSettings` (default: defaults).
    :raises ValueError: if the margins leave no room around the home pose, or ``park_position``
        gives a pose beyond a limit.
    """

    def __init__(self, geometry, settings: Optional[CueingSettings] = None,
                 actuator_limits: Optional[ActuatorLimits] = None, frames=None,
                 controls: Optional[CueingControlSettings] = None):
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
        self._rest_input = np.concatenate([self._rest_force, np.zeros(3)])
        #: The vehicle's motion to come (:meth:`set_preview`), or ``None``.
        self.input_preview = None
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
        self._init_controls(controls if controls is not None else CueingControlSettings())

    @classmethod
    def from_parameters(cls, values: dict, frames=None) -> 'MotionCueing':
        """
        Build it from ROS parameter values, as motion_cueing_node declares them.

        :param values: the geometry, limits and cueing parameters (a missing one keeps its
            default), e.g. read from paper_platform.yaml, example_limits.yaml and
            motion_cueing.yaml.
        :raises ValueError: naming the parameter, for a value that is not allowed.
        """
        specs = MOTION_CUEING_PARAMETERS + CUEING_CONTROL_PARAMETERS
        merged = defaults(specs)
        merged.update({spec.name: values[spec.name] for spec in specs if spec.name in values})
        check_values(specs, merged)
        geometry = GeometrySettings.from_values(values)
        return cls(geometry_from_settings(geometry), CueingSettings.from_parameters(merged),
                   actuator_limits_from_settings(geometry), frames,
                   CueingControlSettings.from_values(merged))

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
        as the first one ever (no step), the motion goes on from where it is. A preview
        (:meth:`set_preview`) is on the old time line's clock: it is dropped. (A resume and the
        end of a start also start a new time line, on the same clock: the preview stays.)
        """
        self.time = None
        self.input_preview = None

    def _continue_clock(self) -> None:
        """
        Start a new time line on the same clock (after a pause, or a start from park).

        The next sample is taken as the first one ever, but the simulator's clock goes on: a
        preview given before (while paused or parked) stays; its samples up to the next
        sample's time are not used.
        """
        self.time = None

    def set_preview(self, times, specific_force, angular_velocity,
                    frame_id: Optional[str] = None) -> None:
        """
        Tell the model-predictive cueing the vehicle's motion to come (``cueing_method: mpc``).

        From the next sample on, the MPC plans against the vehicle's perception of this motion
        over its horizon (:func:`~.vehicle_preview.interval_means`: the mean input over each
        step, the present sample first) instead of the present input held and fading; past the
        preview's last sample, that sample is held and fades. A simulator that knows its next
        seconds (a replay, a scripted drive, a driver model's prediction) gives them here,
        at once or a window at a time; each call replaces the last. doc/motion_cueing_mpc.md
        measures what it is worth.

        :param times: seconds on the clock of :meth:`step`'s ``time``, shape (M,), M >= 1,
            increasing.
        :param specific_force: m/s^2, head, vehicle frame, with gravity, shape (M, 3).
        :param angular_velocity: rad/s, vehicle frame, shape (M, 3).
        :param frame_id: the frame of both (a message's ``header.frame_id``, as for
            :meth:`cue`: ``imu_frame`` is turned into the vehicle frame), or ``None``: the
            vehicle frame.
        :raises ValueError: naming the argument, for a malformed, non-finite or absurd
            preview (beyond ``max_specific_force`` or ``max_angular_velocity``), a frame that
            cannot be placed in the vehicle frame, a preview that ends at or before the last
            sample (none of it to come: times on another clock), or if the cueing is not
            model-predictive (the classical washout has no horizon to use it). The preview
            before stays.
        """
        if not isinstance(self.washout, MpcCueing):
            raise ValueError('a preview needs cueing_method mpc (the classical washout has no '
                             f'horizon to use it); this cueing is '
                             f'{self.settings.cueing_method!r}')
        checked = input_preview(
            times, specific_force, angular_velocity, self.settings.max_specific_force,
            self.settings.max_angular_velocity)
        if self.time is not None and not checked.end > self.time:
            # Nothing of it would be used: most likely a stamp on another clock (unset: 0).
            raise ValueError(
                f'the preview ends at {checked.end!r} s, not after the last sample '
                f'({self.time!r} s): none of it is to come; give its times on the clock of '
                "the samples' times (a message's header.stamp on vehicle_imu's clock)")
        if frame_id is not None:
            refusal = self.vehicle_frame_refusal(frame_id)
            if refusal is not None:
                raise ValueError(refusal.message.replace('the sample is', 'the preview is'))
            if frame_id and frame_id == self.settings.imu_frame:
                forces, rates = self.to_vehicle_frame(
                    checked.inputs[:, :3], checked.inputs[:, 3:], frame_id)
                turned = np.hstack([forces, rates])
                turned.setflags(write=False)
                checked = dataclasses.replace(checked, inputs=turned)
        self.input_preview = checked

    def clear_preview(self) -> None:
        """Forget the preview: the MPC predicts the present input held and fading again."""
        self.input_preview = None

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
                f'time {seconds_text(time)} s does not come after the previous sample '
                f'({seconds_text(self.time)} s): a repeated or backward stamp; sample ignored '
                '(set header.stamp)',
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
            norm = math.hypot(*vector.tolist())   # scaled: 1e308 does not overflow
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

    def to_vehicle_frame(self, specific_force, angular_velocity,
                         frame_id: str) -> Tuple[np.ndarray, np.ndarray]:
        """
        Turn samples given in ``frame_id`` into the vehicle frame, as :meth:`cue` turns them.

        A sample in ``vehicle_frame`` (or an empty ``frame_id``) is returned as it is; one in
        ``imu_frame`` is turned by ``imu_orientation_rpy_deg``. For a recording replayed
        offline, where each message carries its frame.

        :param specific_force: m/s^2, shape (3,) or (N, 3), finite.
        :param angular_velocity: rad/s, the same shape.
        :param frame_id: their frame (a message's ``header.frame_id``).
        :returns: ``(specific_force, angular_velocity)`` in the vehicle frame, new arrays.
        :raises ValueError: for a frame that cannot be placed in the vehicle frame
            (:meth:`vehicle_frame_refusal`'s message).
        """
        refusal = self.vehicle_frame_refusal(frame_id)
        if refusal is not None:
            raise ValueError(refusal.message)
        forces = np.array(specific_force, dtype=float)
        rates = np.array(angular_velocity, dtype=float)
        if frame_id and frame_id == self.settings.imu_frame:
            forces, rates = forces @ self._imu_rotation.T, rates @ self._imu_rotation.T
        return forces, rates

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
        if self.mode != CUEING:
            return self._held(float(time))
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
        if self.mode != CUEING:
            return self._held(float(time))
        return self._advance(float(time), specific_force, angular_velocity, None, command_time)

    def rest(self, dt: float, command_time: Optional[float] = None) -> CueStep:
        """
        Advance ``dt`` seconds as if the vehicle were at rest: no input came (a watchdog).

        The sample time stays the last one received; the next sample's step then covers the
        pause (as an input gap when longer than ``max_input_gap``). A preview
        (:meth:`set_preview`) is not used here (its clock stands still), but kept for the next
        sample.

        :param command_time: when the command is sent, seconds (the node's clock); ``None``:
            the step taken (``dt``, at most ``max_input_gap``) after the last command.
        :raises ValueError: if ``dt`` is not a positive, finite number of seconds.
        """
        if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0.0):
            raise ValueError(f'dt must be a positive, finite number of seconds, got {dt!r}')
        time = (self.time or 0.0)
        step = min(dt, self.settings.max_input_gap)
        if command_time is None and self.gate.last_time is not None:
            # The step taken, not dt: a dt of 1e308 put the command clock where a later step
            # no longer moved it (the platform held for ever) or overflowed the legs' check.
            command_time = self.gate.last_time + step
        self._ramp_gains(step)
        # Without the preview: its clock is the input's, which stands still here, so its motion
        # to come would stay ahead for ever and hold the platform off neutral.
        return self._move(time, step, self._rest_force,
                          np.zeros(3), None, [], command_time, told=False)

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
        if self.mode != CUEING:
            return None   # parked, paused, or moving on operate(): nothing to ease
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
        limits. The first part of :meth:`stop` and :meth:`pause` (and so of a managed
        motion_cueing_node's deactivate): easing home takes the washout's time (tens of
        seconds from a sustained cue), braking a fraction of a second.

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

    # Run-time controls ------------------------------------------------------------------------

    def _init_controls(self, controls: CueingControlSettings) -> None:
        """Take the controls' settings: the gains at the intensity, the park pose, the mode."""
        self.controls = controls
        settings = self.settings
        #: The effective gains (intensity times each channel gain), ramped on changes.
        self.gains = GainRamp(effective_gains(controls.cueing_intensity,
                                              settings.translation_scale, settings.tilt_scale,
                                              settings.rotation_scale))
        self._washout_gains = None
        self._gain_check = None
        if controls.cueing_intensity != 1.0:
            self._apply_gains()
        self._park = None
        tilted = any(controls.park_orientation_deg)
        orientation = (np.radians(np.array(controls.park_orientation_deg, dtype=float)) if tilted
                       else np.array(self.geometry.home_pose[3:], dtype=float))
        if any(controls.park_position):
            self._park = self._checked_park(
                np.concatenate([np.array(controls.park_position, dtype=float), orientation]))
        elif tilted:
            self._park = self._checked_park(lowest_pose(self.geometry, self.limiter, orientation))
        #: What the platform does: CUEING, PAUSING, PAUSED, PARKED, STARTING or STOPPING.
        self.mode = CUEING
        #: The soft motion under way (start or stop), or ``None``.
        self._soft = None
        if controls.start_parked:
            self._place(self.park_pose)
            self.mode = PARKED

    def _checked_park(self, park) -> np.ndarray:
        """Return the park pose asked; raise ``ValueError`` naming it and the limits it breaks."""
        violations = pose_violations(self.geometry, park[:3], euler_zyx_to_matrix(park[3:]))
        if violations:
            controls = self.controls
            raise ValueError(
                f'park_position {list(controls.park_position)} m with park_orientation_deg '
                f'{list(controls.park_orientation_deg)} puts the platform at '
                f'{[round(float(value), 6) for value in park[:3]]} m, '
                f'{[round(math.degrees(value), 4) for value in park[3:]]} deg, beyond its '
                f'limits: {"; ".join(map(str, violations))}; give a pose within every limit '
                '(park_position all 0.0: the lowest pose below home, park_orientation_deg all '
                "0.0: home's orientation)")
        return park

    @property
    def park_pose(self) -> np.ndarray:
        """
        Return the park pose, ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians, base frame).

        ``park_position`` oriented by ``park_orientation_deg`` (all 0.0: as home), or (all
        0.0) the lowest pose straight below home so oriented that keeps the cue margins.
        """
        if self._park is None:
            self._park = lowest_pose(self.geometry, self.limiter)
        return self._park.copy()

    def _place(self, pose) -> None:
        """Put the platform at rest at ``pose`` (not commanded: where it is taken to be)."""
        lengths = inverse_kinematics(self.geometry, pose)
        self.limiter.reset()
        self.limiter.take_sent(pose, lengths, 1.0, (pose, lengths))
        self.gate.reset(lengths, pose)

    def _washout_gain_setter(self) -> WashoutGains:
        """Return the gains' setter of the washout in use (made again if it was replaced)."""
        if self._washout_gains is None or self._washout_gains.washout is not self.washout:
            self._washout_gains = WashoutGains(self.washout)
        return self._washout_gains

    def _apply_gains(self) -> None:
        """Make the ramp's gains the washout's."""
        self._washout_gain_setter().apply(self.gains.value)

    def _ramp_gains(self, dt: float) -> None:
        """Advance the gain ramp by ``dt`` seconds (the washout's step) and apply it."""
        if self.gains.advance(dt):
            self._apply_gains()

    def gain_refusal(self, intensity=None, translation_scale=None, tilt_scale=None,
                     rotation_scale=None, check_travel: bool = True) -> Optional[Finding]:
        """
        Say why gains cannot be taken (``gain_refused``), or return ``None``.

        :param intensity: the master intensity, in [0, 1], or ``None``: as now.
        :param translation_scale: 3 gains, or ``None``: as now; ``tilt_scale`` 2,
            ``rotation_scale`` 3, likewise (each in its parameter's range).

        Refused: a value not allowed by its parameter, or a change that raises the cue of the
        reference input beyond the travel (:class:`~.controls.GainCheck`; with the MPC, whose
        plan keeps the travel whatever its aim, only the yaw gain is checked). Never raises.
        """
        changes = {name: value for name, value in (
            ('translation_scale', translation_scale), ('tilt_scale', tilt_scale),
            ('rotation_scale', rotation_scale)) if value is not None}
        names = tuple(changes) + (('cueing_intensity',) if intensity is not None else ())
        try:
            if intensity is not None:
                self.controls.replace(cueing_intensity=intensity)
            settings = dataclasses.replace(self.settings, **changes)
        except (TypeError, ValueError) as error:
            return Finding(GAIN_REFUSED, str(error))
        if not self._washout_gain_setter().supported:
            return Finding(GAIN_REFUSED, 'this washout takes no gain change at run time')
        if not check_travel:
            return None
        new = effective_gains(self.controls.cueing_intensity if intensity is None
                              else float(intensity), settings.translation_scale,
                              settings.tilt_scale, settings.rotation_scale)
        if getattr(self.washout, 'keeps_travel', False):
            # The MPC plans within the travel whatever its aim (MpcCueing.keeps_travel): only
            # its classical yaw channel (the last gain) is checked.
            new = np.where(np.arange(new.size) == new.size - 1, new, self.gains.target)
        if self._gain_check is None:
            self._gain_check = GainCheck(self.settings, self.limiter,
                                         self.controls.gain_check_specific_force,
                                         self.controls.gain_check_angular_velocity)
        reason = self._gain_check.refusal(
            self.gains.target, new,
            self.controls.cueing_intensity if intensity is None else float(intensity), names)
        return Finding(GAIN_REFUSED, reason) if reason else None

    def set_gains(self, intensity=None, translation_scale=None, tilt_scale=None,
                  rotation_scale=None, ramp_time: Optional[float] = None,
                  check_travel: bool = True) -> Optional[Finding]:
        """
        Change the master intensity and channel gains, ramped: never a jump in the cue.

        The effective gains (intensity times each channel gain) move from where they are to
        the new ones over ``ramp_time`` (default ``gain_ramp_time``) seconds of the input's
        clock, along a smoothstep; the washout's filters keep their states.

        :param intensity: in [0, 1], or ``None``: as now; the gains likewise (see
            :meth:`gain_refusal`).
        :param check_travel: ``False``: the travel was checked already (a node checks a
            request setting several parameters as a whole, then sets them one by one); the
            values are checked all the same.
        :returns: ``None`` when taken, else the ``gain_refused`` finding (nothing changes).
            Never raises.
        """
        refusal = self.gain_refusal(intensity, translation_scale, tilt_scale, rotation_scale,
                                    check_travel)
        if refusal is not None:
            return refusal
        if ramp_time is not None:
            try:
                self.controls.replace(gain_ramp_time=ramp_time)
            except (TypeError, ValueError) as error:
                return Finding(GAIN_REFUSED, str(error))
        changes = {name: tuple(float(entry) for entry in value) for name, value in (
            ('translation_scale', translation_scale), ('tilt_scale', tilt_scale),
            ('rotation_scale', rotation_scale)) if value is not None}
        self.settings = dataclasses.replace(self.settings, **changes)
        if intensity is not None:
            self.controls = self.controls.replace(cueing_intensity=float(intensity))
        self.gains.set_target(
            effective_gains(self.controls.cueing_intensity, self.settings.translation_scale,
                            self.settings.tilt_scale, self.settings.rotation_scale),
            self.controls.gain_ramp_time if ramp_time is None else float(ramp_time))
        return None

    def start(self) -> ControlAnswer:
        """
        Start from park: move up to the neutral cueing pose over ``soft_start_time``.

        Then the washout starts afresh (settled on the next sample) and cueing goes on. From
        any other mode there is nothing to start (cueing, paused: answered, nothing done) or
        it is refused (moving to park: start again once parked).
        """
        if self.mode == PARKED:
            self._soft = SoftMotion(self.actuator_limits, self.geometry, self.limiter.lengths,
                                    self.limiter.home_lengths, self.controls.soft_start_time,
                                    WATCHDOG_PERIOD)
            self.mode = STARTING
            return ControlAnswer(True, f'starting: from park to neutral in about '
                                 f'{self.controls.soft_start_time:g} s, then cueing')
        if self.mode == STARTING:
            return ControlAnswer(True, 'already starting from park')
        if self.mode == STOPPING:
            return ControlAnswer(False, 'stopping to park: call start again once parked')
        return ControlAnswer(True, f'already started ({self.mode}): nothing to do')

    def stop(self) -> ControlAnswer:
        """
        Stop to park: brake to rest, then move down to park over ``soft_stop_time``.

        From any mode: cueing or paused (braked first), starting (the motion turns to park
        from where it is, without stopping first); parked or stopping: nothing to do.
        """
        if self.mode in (PARKED, STOPPING):
            return ControlAnswer(True, f'already {self.mode}: nothing to do')
        if self.mode == STARTING and self._soft is not None and self._soft.retarget(
                inverse_kinematics(self.geometry, self.park_pose)):
            self.mode = STOPPING
            return ControlAnswer(True, 'stopping during the start: turning back to park')
        self._soft = None   # braking first; the motion to park is planned at rest
        self.mode = STOPPING
        return ControlAnswer(True, f'stopping: braking to rest, then to park in about '
                             f'{self.controls.soft_stop_time:g} s')

    def pause(self) -> ControlAnswer:
        """
        Pause: brake to rest where the platform is and hold it; samples are not cued.

        The washout's state is kept (frozen), so :meth:`resume` goes on from it. Only while
        cueing (paused already: nothing to do; starting, stopping, parked: refused).
        """
        if self.mode in (PAUSING, PAUSED):
            return ControlAnswer(True, f'already {self.mode}: nothing to do')
        if self.mode != CUEING:
            return ControlAnswer(False, f'cannot pause while {self.mode}: pause is for cueing')
        self.mode = PAUSING
        return ControlAnswer(True, 'pausing: braking to rest where the platform is, then '
                             'holding; the washout is frozen until resume')

    def resume(self) -> ControlAnswer:
        """
        Resume after a pause: the next sample is cued from the washout's frozen state.

        The next sample starts a new time line (no step over the pause; a preview given
        before stays: the clock is the same), the cue goes on from where it was, and the
        follower brings the held platform back onto it within the actuator limits. Only after
        a pause (cueing: nothing to do; else refused).
        """
        if self.mode in (PAUSING, PAUSED):
            self.mode = CUEING
            self._continue_clock()
            return ControlAnswer(True, 'resumed: cueing from the held state')
        if self.mode == CUEING:
            return ControlAnswer(True, 'not paused: nothing to do')
        return ControlAnswer(False, f'cannot resume while {self.mode}: resume follows pause')

    def operate(self, command_time: float) -> Optional[CueStep]:
        """
        Step the motion of a start, stop or pause: one command, on the node's clock.

        Called on a timer (every :data:`WATCHDOG_PERIOD` or so) with the node's clock.

        :returns: the :class:`CueStep` whose accepted ``command`` is to be sent, or ``None``:
            nothing to send (cueing, parked, paused and at rest, no time passed, a time that
            is not a finite number). Never raises.
        """
        try:
            now = float(command_time)
        except (TypeError, ValueError):
            return None
        if not math.isfinite(now) or self.mode in (CUEING, PARKED, PAUSED):
            return None
        if self.mode == PAUSING or self.mode == STOPPING and self._soft is None:
            step = self.brake(now)
            if step is not None or self.gate.last_time is not None and not (
                    now > self.gate.last_time):
                return step
            # At rest: paused, or the motion to park is planned from here.
            if self.mode == PAUSING:
                self.mode = PAUSED
                return None
            self._soft = SoftMotion(self.actuator_limits, self.geometry, self.limiter.lengths,
                                    inverse_kinematics(self.geometry, self.park_pose),
                                    self.controls.soft_stop_time, WATCHDOG_PERIOD)
        return self._soft_step(now)

    def _soft_step(self, now: float) -> Optional[CueStep]:
        """One command of the soft motion under way; the mode changes when it ends."""
        interval = self.gate.elapsed(now)
        if interval is None:
            return None
        limiter = self.limiter
        previous = (limiter.pose.copy(), limiter.lengths.copy())
        lengths = self._soft.step(interval)
        command = None
        if lengths is not None:
            solution = forward_kinematics(self.geometry, lengths, initial_guess=limiter.pose)
            if solution.converged:
                pose = np.asarray(solution.pose, dtype=float)
                command = self.gate.pose_vector(self._tool_pose(pose), now)
        if command is None or not command.accepted:
            replaced = command.refusal if command is not None else Finding(
                COMMAND_BRAKING, 'no pose of the next step toward park or neutral was found')
            command = self.gate.brake(now, replaced=replaced)
            if not command.accepted:
                return None
            self._soft = None   # planned again from rest (stopping), or ...
            if self.mode == STARTING:
                self.mode = STOPPING   # ... a start that cannot go on parks again
        pose = command.pose
        limiter.take_sent(pose, command.lengths, interval, previous)
        if self._soft is not None and self._soft.settled:
            self._soft = None
            if self.mode == STARTING:
                # At rest at neutral: the cueing starts afresh from the next sample.
                limiter.reset()
                self.washout.reset()
                self._continue_clock()
                self.mode = CUEING
            else:
                self.mode = PARKED
        return CueStep(time=self.time, pose=pose, lengths=command.lengths,
                       warnings=command.warnings, command=command)

    def _held(self, time: float) -> CueStep:
        """Keep the time of a sample not cued (not cueing): nothing moves."""
        self.time = time
        return CueStep(time=time, pose=None, warnings=(Finding(
            CUEING_HELD, f'the sample is not cued: the platform is {self.mode} (start, stop, '
            'pause and resume say what it does)', (('mode', self.mode),)),))

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
        self._ramp_gains(dt)
        return self._move(time, dt, specific_force, angular_velocity, refusal, warnings,
                          command_time)

    def _move(self, time, dt, specific_force, angular_velocity, refusal, warnings,
              command_time, told=True) -> CueStep:
        if self.input_preview is None or not told:
            washout = self.washout.step_checked(specific_force, angular_velocity, dt)
        else:
            mpc = self.washout
            to_come = interval_means(
                self.input_preview, time,
                np.concatenate([specific_force, angular_velocity]), mpc.step_time, mpc.horizon,
                self._rest_input, self.settings.mpc_reference_time_constant)
            washout = mpc.step_checked(specific_force, angular_velocity, dt, to_come)
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
