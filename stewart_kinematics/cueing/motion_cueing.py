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
washout (:mod:`.washout`) turns the sample into a cue, :class:`~.limiting.CueLimiter` scales it
into the limits and follows it within the actuators' speed, and the specific force felt at the
head is estimated as the poses stream (:mod:`.perception`).

Time: each sample's time (seconds, such as a message stamp) sets the step, ``dt`` = this time
minus the previous sample's, so the filters run on the input's own clock whatever its jitter.
A time that does not come after the previous one is refused and nothing moves (the pose
holds). A gap longer than ``max_input_gap`` counts as ``max_input_gap``: the washout's clock
pauses, the cue carries on from where it was, with an ``input_gap`` warning.

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

from stewart_kinematics.cueing.limiting import CueLimiter
from stewart_kinematics.cueing.perception import PerceptionEstimator
from stewart_kinematics.cueing.settings import CueingSettings
from stewart_kinematics.cueing.washout import ClassicalWashout
from stewart_kinematics.findings import (
    Decision,
    Finding,
    INPUT_GAP,
    INVALID_VEHICLE_MOTION,
    TIME_NOT_INCREASING,
)
from stewart_kinematics.model.actuators import ActuatorLimits
from stewart_kinematics.model.arrays import as_float_array
from stewart_kinematics.parameters import (
    actuator_limits_from_settings,
    check_values,
    defaults,
    geometry_from_settings,
    GeometrySettings,
    MOTION_CUEING_PARAMETERS,
)


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
        limiting.
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


class MotionCueing:
    """
    Classical washout, limits and perception, stepped sample by sample.

    :param geometry: the platform and its limits (:func:`stewart_kinematics.load_geometry`).
    :param settings: a :class:`~stewart_kinematics.cueing.CueingSettings` (default: the
        literature's).
    :param actuator_limits: leg velocity and acceleration limits (default: none).
    :raises ValueError: if the margins leave no room around the home pose.
    """

    def __init__(self, geometry, settings: Optional[CueingSettings] = None,
                 actuator_limits: Optional[ActuatorLimits] = None):
        self.geometry = geometry
        self.settings = settings if settings is not None else CueingSettings()
        self.actuator_limits = (actuator_limits if actuator_limits is not None
                                else ActuatorLimits())
        self.washout = ClassicalWashout(self.settings)
        self.limiter = CueLimiter(geometry, self.actuator_limits, self.settings)
        self.perception = PerceptionEstimator(self.settings.head_position, self.settings.gravity)
        self._rest_force = np.array([0.0, 0.0, self.settings.gravity])
        self.time = None
        #: Seconds of motion so far (input steps and rest steps): the perception's clock.
        self._clock = None

    @classmethod
    def from_parameters(cls, values: dict) -> 'MotionCueing':
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
                   actuator_limits_from_settings(geometry))

    @property
    def pose(self) -> np.ndarray:
        """Return the last pose commanded (the home pose before the first sample)."""
        return self.limiter.pose.copy()

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
            return Finding(TIME_NOT_INCREASING, f'time must be a number of seconds, got {time!r}')
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

    def cue(self, time, specific_force, angular_velocity) -> CueStep:
        """
        Decide on one sample: cue it, or refuse it and ease toward neutral.

        :param time: the sample's time, seconds (a message stamp).
        :param specific_force: m/s^2, vehicle frame at the head, shape (3,).
        :param angular_velocity: rad/s, vehicle frame, shape (3,).
        :returns: a :class:`CueStep`; never raises for bad input.
        """
        refusal = self.refusal(time, specific_force, angular_velocity)
        if refusal is not None and refusal.code == TIME_NOT_INCREASING:
            return CueStep(time=self.time, pose=None, refusal=refusal)
        if refusal is not None:
            specific_force, angular_velocity = self._rest_force, np.zeros(3)
        return self._advance(float(time), specific_force, angular_velocity, refusal)

    def step(self, time, specific_force, angular_velocity) -> CueStep:
        """
        Cue one sample, or raise: :meth:`cue` for a loop that wants exceptions.

        :raises ValueError: naming the argument, for a malformed, non-finite or absurd sample,
            or a time that does not come after the previous one.
        """
        refusal = self.refusal(time, specific_force, angular_velocity)
        if refusal is not None:
            raise ValueError(refusal.message)
        return self._advance(float(time), specific_force, angular_velocity, None)

    def rest(self, dt: float) -> CueStep:
        """
        Advance ``dt`` seconds as if the vehicle were at rest: no input came (a watchdog).

        The sample time stays the last one received; the next sample's step then covers the
        pause (as an input gap when longer than ``max_input_gap``).

        :raises ValueError: if ``dt`` is not a positive, finite number of seconds.
        """
        if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0.0):
            raise ValueError(f'dt must be a positive, finite number of seconds, got {dt!r}')
        time = (self.time or 0.0)
        return self._move(time, min(dt, self.settings.max_input_gap), self._rest_force,
                          np.zeros(3), None, [])

    def _advance(self, time, specific_force, angular_velocity, refusal) -> CueStep:
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
        return self._move(time, dt, specific_force, angular_velocity, refusal, warnings)

    def _move(self, time, dt, specific_force, angular_velocity, refusal, warnings) -> CueStep:
        washout = self.washout.step_checked(specific_force, angular_velocity, dt)
        if dt > 0.0:
            limited = self.limiter.step(washout.displacement, washout.rotation, washout.tilt, dt)
            warnings.extend(limited.findings)
            pose, lengths, target = limited.pose, limited.lengths, limited.target
            workspace_scale, tilt_scale = limited.workspace_scale, limited.tilt_scale
            acceleration_scale = limited.acceleration_scale
        else:
            limiter = self.limiter
            pose, lengths, target = limiter.pose.copy(), limiter.lengths.copy(), None
            workspace_scale, tilt_scale = limiter.scale, limiter.tilt_scale
            acceleration_scale = 1.0
        perceived = None
        if self._clock is None or dt > 0.0:
            self._clock = 0.0 if self._clock is None else self._clock + dt
            perceived = self.perception.update(self._clock, pose, time)
        return CueStep(
            time=time, pose=pose, lengths=lengths, target=target,
            displacement=washout.displacement, angles=washout.angles, tilt=washout.tilt,
            tilt_rate=washout.tilt_rate, workspace_scale=workspace_scale, tilt_scale=tilt_scale,
            acceleration_scale=acceleration_scale, perceived=perceived, refusal=refusal,
            warnings=tuple(warnings))
