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
What a simulator operator changes at run time: intensity and gains, park, soft start and stop.

The pieces :class:`~stewart_kinematics.cueing.MotionCueing` composes (its methods
``set_gains``, ``start``, ``stop``, ``pause``, ``resume`` and ``operate`` are the interface):

- **Gains.** The cue's gains are the eight channel gains (``translation_scale`` x y z,
  ``tilt_scale`` x y, ``rotation_scale`` roll pitch yaw) times the master intensity (0..1).
  A change never jumps: :class:`GainRamp` moves every effective gain from where it is to its
  new value over ``gain_ramp_time`` along a smoothstep (``3 u^2 - 2 u^3``: no step in a gain
  nor in its rate), and a change during a ramp starts a new ramp from where the gains are.
  The gains act where the washout's filters are read (:class:`WashoutGains`: the outputs of
  each channel's filter scale, the filter states are kept), which is what the settings' gains
  are: the tilt gain acts before the tilt's rate limiter, so a tilt changed by a gain keeps
  ``tilt_rate_max``; a displacement or a rotation is scaled as it stands.
- **The limit a gain change is refused for** (:class:`GainCheck`): the cue of a sustained
  reference input (``gain_check_specific_force`` on each axis, ``gain_check_angular_velocity``
  about each axis) at the new gains, each channel alone, must stay within the platform's travel
  along that axis from neutral within the cue margins (the limits narrowed by
  ``leg_length_margin``, ``joint_angle_margin`` and ``condition_margin``): the translational
  channel's peak displacement, the tilt's steady angle (``asin`` of the low-passed force, at
  most ``tilt_max``), the rotational channel's peak angle. A change that raises such a cue
  beyond the travel is refused with the value, the cue, the travel and the largest gain
  allowed; a change that lowers it is always taken (so a start-up gain beyond it can be
  lowered). The cue limiter keeps every command within the limits whatever the gains; the
  check refuses gains at which it would be scaling the cue down all the time.
- **Park** (:func:`lowest_pose`): the lowest pose straight below home, oriented as home (or
  as ``park_orientation_deg``), that keeps the cue margins; or a pose given.
- **Soft motion** (:class:`SoftMotion`): from rest at some leg lengths to rest at others,
  in the time asked or longer: ruckig's jerk-limited, phase-synchronised motion
  (:class:`~stewart_kinematics.motion.streaming.CommandFilter`: a straight line in leg space)
  planned with the velocity and acceleration that take that time, never beyond
  :data:`SOFT_SHARE` of the actuator limits; a new target mid-way (stop during start) is
  planned from the motion's state.

Nothing here imports ROS.
"""

import dataclasses
import math
from typing import Optional, Sequence, Tuple

import numpy as np

from stewart_kinematics.cueing.limit_margins import limit_margins
from stewart_kinematics.cueing.washout import ClassicalWashout
from stewart_kinematics.model.actuators import ActuatorLimits

#: The gains' names and how many values each holds, in the order of the effective gains.
GAIN_CHANNELS = (('translation_scale', 3), ('tilt_scale', 2), ('rotation_scale', 3))
#: The axes of the effective gains, for messages.
GAIN_AXES = ('x', 'y', 'z', 'x', 'y', 'roll', 'pitch', 'yaw')
#: Share of the actuator limits a soft start or stop plans with at most (the rest absorbs
#: the divided differences the command gate checks).
SOFT_SHARE = 0.9
#: Samples of a step response, and of the travel along an axis.
_RESPONSE_SAMPLES = 4000
_TRAVEL_SAMPLES = 256
#: Farthest displacement (metres) and angle (radians) the travel is looked for within.
_TRAVEL_REACH = (2.0, 1.5)


def smoothstep(fraction: float) -> float:
    """Return ``3 u^2 - 2 u^3`` of ``u`` clipped to [0, 1]: 0 to 1 with zero slope at both ends."""
    u = min(max(fraction, 0.0), 1.0)
    return u * u * (3.0 - 2.0 * u)


def effective_gains(intensity: float, translation_scale: Sequence[float],
                    tilt_scale: Sequence[float], rotation_scale: Sequence[float]) -> np.ndarray:
    """Return the eight effective gains: intensity times each channel gain, shape (8,)."""
    return float(intensity) * np.concatenate([
        np.asarray(translation_scale, dtype=float), np.asarray(tilt_scale, dtype=float),
        np.asarray(rotation_scale, dtype=float)])


class GainRamp:
    """
    Effective gains that move to a new value over a time, along a smoothstep.

    :param gains: the gains now, shape (8,).
    """

    def __init__(self, gains):
        self.value = np.array(gains, dtype=float)
        self._start = self.value.copy()
        self._target = self.value.copy()
        self._duration = 0.0
        self._elapsed = 0.0

    @property
    def target(self) -> np.ndarray:
        """Return the gains ramped to, shape (8,)."""
        return self._target.copy()

    @property
    def ramping(self) -> bool:
        """Return whether a ramp is under way."""
        return self._elapsed < self._duration

    def set_target(self, gains, duration: float) -> None:
        """Ramp from the gains now to ``gains`` (shape (8,)) over ``duration`` seconds (> 0)."""
        self._start = self.value.copy()
        self._target = np.array(gains, dtype=float)
        self._duration = float(duration)
        self._elapsed = 0.0

    def advance(self, dt: float) -> bool:
        """Advance ``dt`` seconds; return whether the gains changed."""
        if not self.ramping or not dt > 0.0:
            return False
        self._elapsed = min(self._elapsed + dt, self._duration)
        share = smoothstep(self._elapsed / self._duration)
        self.value = self._start + share * (self._target - self._start)
        if not self.ramping:
            self.value = self._target.copy()
        return True


def _unit_settings(settings):
    """Return ``settings`` with every channel gain 1 (the unit gains' filters)."""
    return dataclasses.replace(settings, translation_scale=(1.0,) * 3, tilt_scale=(1.0,) * 2,
                               rotation_scale=(1.0,) * 3)


#: Which effective gain scales each output row of the classical washout's filter bank: the
#: translational blocks (position, velocity, acceleration per axis), the tilt low-passes, the
#: rotational blocks (angle, rate per axis), in the order ClassicalWashout builds them.
_ROW_GAINS = np.array([0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 4, 5, 5, 6, 6, 7, 7])


class WashoutGains:
    """
    Set the channel gains of a classical washout at run time, its filter states kept.

    A washout that has its own ``set_gains(gains)`` method (shape (8,), the effective gains)
    is handed the gains instead (another cueing method).

    :param washout: the :class:`~.washout.ClassicalWashout` (or another washout).
    """

    def __init__(self, washout):
        self.washout = washout
        self._unit = None
        if not hasattr(washout, 'set_gains') and isinstance(washout, ClassicalWashout):
            unit = ClassicalWashout(_unit_settings(washout.settings)).filters
            if unit.c.shape == washout.filters.c.shape and unit.c.shape[0] == _ROW_GAINS.size:
                self._unit = (unit.c.copy(), unit.d.copy())

    @property
    def supported(self) -> bool:
        """Return whether the washout's gains can be set at run time."""
        return self._unit is not None or hasattr(self.washout, 'set_gains')

    def apply(self, gains) -> None:
        """Make ``gains`` (the eight effective gains) the washout's from its next output."""
        gains = np.asarray(gains, dtype=float)
        if hasattr(self.washout, 'set_gains'):
            self.washout.set_gains(gains)
        elif self._unit is not None:
            rows = gains[_ROW_GAINS][:, None]
            filters = self.washout.filters
            filters.c = self._unit[0] * rows
            filters.d = self._unit[1] * rows


class GainCheck:
    """
    Whether a gain change would ask the platform for more than its travel (see the module).

    :param settings: the :class:`~.settings.CueingSettings` (filters, tilt limit, gravity).
    :param limiter: the :class:`~.cue_limiter.CueLimiter` (its cue poses and narrowed limits).
    :param specific_force: the reference sustained specific force, m/s^2, on each axis.
    :param angular_velocity: the reference sustained angular velocity, rad/s, about each axis.
    """

    def __init__(self, settings, limiter, specific_force: float, angular_velocity: float):
        self.settings = settings
        self.limiter = limiter
        self.specific_force = float(specific_force)
        self.angular_velocity = float(angular_velocity)
        self._cue = None
        self._travel = None

    def unit_cues(self) -> np.ndarray:
        """
        Return the cue of the reference input at unit gains, per effective gain, shape (8,).

        Metres for the translational channel (peak of the step response, after the soft
        input limit), the tilt's ``sin`` (before ``asin`` and ``tilt_max``) for the tilt,
        radians (peak) for the rotational channel.
        """
        if self._cue is None:
            s = self.settings
            limit = s.translation_input_limit
            force = (limit * math.tanh(self.specific_force / limit) if math.isfinite(limit)
                     else self.specific_force)
            filters = ClassicalWashout(_unit_settings(s)).filters
            rates = np.abs(np.linalg.eigvals(filters.a).real)
            horizon = 12.0 / max(float(np.min(rates[rates > 0.0])), 1e-3)
            dt = horizon / _RESPONSE_SAMPLES
            quanta = max(1, round(dt / 1e-6))
            phi, gamma = filters.discretised(quanta)
            u = np.zeros(9)
            u[:3] = self.specific_force   # tilt input (x, y)
            u[3:6] = self.angular_velocity
            u[6:] = force                 # translational input, soft-limited
            state = np.zeros(filters.order)
            peak = np.zeros(filters.c.shape[0])
            step_input = gamma @ u
            for _ in range(_RESPONSE_SAMPLES):
                state = phi @ state + step_input
                peak = np.maximum(peak, np.abs(filters.c @ state + filters.d @ u))
            cue = np.empty(8)
            cue[:3] = peak[[0, 3, 6]]
            cue[3:5] = peak[[9, 10]] / s.gravity
            cue[5:] = peak[[11, 13, 15]]
            self._cue = cue
        return self._cue

    def travel(self) -> np.ndarray:
        """
        Return the travel along each axis of the effective gains, shape (8,).

        From neutral, the smaller of the two directions, within the cue margins: metres along
        x, y, z of the head; radians of pitch (tilt x), roll (tilt y), and roll, pitch, yaw.
        """
        if self._travel is None:
            limiter = self.limiter
            travel = np.empty(8)
            # (effective gain, displacement axis or None, angle axis or None)
            axes = ((0, 0, None), (1, 1, None), (2, 2, None), (3, None, 1), (4, None, 0),
                    (5, None, 0), (6, None, 1), (7, None, 2))
            for index, displacement_axis, angle_axis in axes:
                reach = _TRAVEL_REACH[0 if displacement_axis is not None else 1]
                found = []
                for sign in (1.0, -1.0):
                    shares = np.linspace(0.0, reach, _TRAVEL_SAMPLES + 1)[1:]
                    displacement = np.zeros((shares.size, 3))
                    angles = np.zeros((shares.size, 3))
                    if displacement_axis is not None:
                        displacement[:, displacement_axis] = sign * shares
                    else:
                        angles[:, angle_axis] = sign * shares
                    margins = limit_margins(limiter.cue_geometry,
                                            limiter.cue_poses(displacement, angles))
                    outside = np.flatnonzero(~(margins < 0.0))
                    found.append(reach if outside.size == 0 else (
                        0.0 if outside[0] == 0 else float(shares[outside[0] - 1])))
                travel[index] = min(found)
            self._travel = travel
        return self._travel

    def cues(self, gains) -> np.ndarray:
        """Return the cue of the reference input at ``gains`` per axis (travel's units)."""
        cue = np.asarray(gains, dtype=float) * self.unit_cues()
        tilt = np.minimum(np.abs(cue[3:5]), math.sin(self.settings.tilt_max))
        cue = np.abs(cue)
        cue[3:5] = np.arcsin(tilt)
        return cue

    def refusal(self, old_gains, new_gains, intensity: float, names: Tuple[str, ...] = ()) -> str:
        """
        Return ``''`` if ``new_gains`` may replace ``old_gains`` (effective, shape (8,)), else why.

        :param intensity: the master intensity of ``new_gains`` (their channel gains are
            ``new_gains / intensity``), for the message.
        :param names: what is being changed, for the message (``'cueing_intensity'``, ...).
        """
        old = self.cues(old_gains)
        new = self.cues(new_gains)
        travel = self.travel()
        unit = self.unit_cues()
        for index in range(8):
            if not (new[index] > travel[index] and new[index] > old[index] + 1e-12):
                continue
            channel = ('translation_scale' if index < 3 else 'tilt_scale' if index < 5
                       else 'rotation_scale')
            axis = GAIN_AXES[index]
            if index < 3:
                cue = f'{new[index]:.3f} m, beyond the {travel[index]:.3f} m of travel'
                largest = travel[index] / unit[index]
                reference = f'{self.specific_force:g} m/s^2'
            elif index < 5:
                cue = (f'{math.degrees(new[index]):.2f} deg of tilt, beyond the '
                       f'{math.degrees(travel[index]):.2f} deg of travel')
                largest = math.sin(travel[index]) / unit[index]
                reference = f'{self.specific_force:g} m/s^2'
            else:
                cue = (f'{math.degrees(new[index]):.2f} deg, beyond the '
                       f'{math.degrees(travel[index]):.2f} deg of travel')
                largest = travel[index] / unit[index]
                reference = f'{self.angular_velocity:g} rad/s'
            # intensity > 0 here: at 0 the cue is 0, never beyond the travel.
            return (f'{" and ".join(names) or channel}: at {channel} {axis} = '
                    f'{new_gains[index] / intensity:.4g} times cueing_intensity '
                    f'{intensity:.4g}, the cue of a sustained {reference} would peak at {cue} '
                    f'along {axis} (within the cue margins); {channel} {axis} at most '
                    f'{largest / intensity:.4g} at this intensity (cueing_intensity at most '
                    f'{min(1.0, largest / (new_gains[index] / intensity)):.4g} at this gain)')
        return ''


def lowest_pose(geometry, limiter, orientation=None) -> np.ndarray:
    """
    Return the lowest pose straight below home, oriented as home, within the cue margins.

    :param geometry: the platform.
    :param limiter: the :class:`~.cue_limiter.CueLimiter` (its narrowed limits).
    :param orientation: alpha, beta, gamma, radians, shape (3,): the pose's orientation
        instead of home's (a platform that parks tilted).
    :returns: ``[X, Y, Z, alpha, beta, gamma]``, shape (6,); home's position (so oriented)
        when no lower pose keeps the margins.
    """
    home = np.array(geometry.home_pose, dtype=float)
    if orientation is not None:
        home[3:] = np.asarray(orientation, dtype=float)
    low, high = 0.0, max(float(home[2]), 1e-3)   # how far below home
    poses = home + np.zeros((_TRAVEL_SAMPLES, 6))
    drops = np.linspace(0.0, high, _TRAVEL_SAMPLES + 1)[1:]
    poses[:, 2] -= drops
    outside = np.flatnonzero(~(limit_margins(limiter.cue_geometry, poses) < 0.0))
    if outside.size == 0:
        low = high = float(drops[-1])
    elif outside[0] > 0:
        low, high = float(drops[outside[0] - 1]), float(drops[outside[0]])
    else:
        low, high = 0.0, float(drops[0])
    for _ in range(40):   # bisection to a micrometre or better
        if high - low <= 1e-7:
            break
        middle = 0.5 * (low + high)
        pose = home.copy()
        pose[2] -= middle
        if limit_margins(limiter.cue_geometry, pose[None, :])[0] < 0.0:
            low = middle
        else:
            high = middle
    pose = home.copy()
    pose[2] -= low
    return pose


class SoftMotion:
    """
    Leg lengths moving from rest to rest at a target, in a time asked or longer (see module).

    :param actuator_limits: the legs' limits; ``jerk_max`` may be ``inf``.
    :param geometry: the platform (its stroke).
    :param lengths: where the legs rest now, metres, shape (6,).
    :param target: where they are to rest, metres, shape (6,).
    :param duration: the time asked, seconds, > 0.
    :param period: the nominal time between two steps, seconds.
    :raises ValueError: for lengths outside the stroke (the caller checks them).
    """

    def __init__(self, actuator_limits: ActuatorLimits, geometry, lengths, target,
                 duration: float, period: float):
        from stewart_kinematics.motion.streaming import CommandFilter

        lengths = np.asarray(lengths, dtype=float)
        target = np.asarray(target, dtype=float)
        distance = max(float(np.max(np.abs(target - lengths))), 1e-6)
        # A trapezoid taking the time asked: a third of it at cruise speed.
        velocity = min(SOFT_SHARE * actuator_limits.velocity_max, 1.5 * distance / duration)
        acceleration = min(SOFT_SHARE * actuator_limits.acceleration_max,
                           4.5 * distance / duration ** 2)
        jerk = (SOFT_SHARE * actuator_limits.jerk_max if math.isfinite(actuator_limits.jerk_max)
                else math.inf)
        self.limits = ActuatorLimits(velocity, acceleration, jerk)
        self.filter = CommandFilter(self.limits, period, lengths, geometry)
        self.settled = False
        self.retarget(target)

    def retarget(self, target) -> bool:
        """Aim at other lengths from the motion's state (stop during start); whether taken."""
        answer = self.filter.set_target(target)
        if answer.accepted:
            self.settled = False
        return answer.accepted

    @property
    def target(self) -> np.ndarray:
        """Return the lengths aimed at, metres, shape (6,)."""
        return self.filter.target

    def step(self, interval: float) -> Optional[np.ndarray]:
        """
        Advance ``interval`` seconds; return the leg lengths, or ``None`` if no step was found.

        :attr:`settled` is set once the legs rest at the target.
        """
        command = self.filter.step(interval)
        if command.held:
            return None
        self.settled = bool(command.settled)
        return command.lengths


@dataclasses.dataclass(frozen=True)
class ControlAnswer:
    """
    The answer to start, stop, pause or resume (a std_srvs/Trigger's response).

    :param success: whether the platform does (or already did) what was asked.
    :param message: what it does, or why not.
    """

    success: bool
    message: str
