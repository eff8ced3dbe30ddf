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
The settings of the motion cueing: filters, scale factors, tilt limits, limit margins, timing.

One frozen :class:`CueingSettings`, in SI units (radians, not degrees), validated when built;
:meth:`CueingSettings.from_parameters` builds it from the ROS parameter values declared in
:data:`stewart_kinematics.parameters.MOTION_CUEING_PARAMETERS` (where angles are in degrees and
say so in their names; :class:`stewart_kinematics.parameters.CueingParameterSettings` holds them
as the node declares them).

Defaults are the classical washout's of the literature (Reid and Nahon 1985, UTIAS Report 296;
Nahon and Reid 1990, J. Guidance 13(2)): a third-order translational high-pass (second order at
2.5 rad/s, 4 rad/s in heave, damping 1, times a first-order break at 0.25 rad/s), a second-order
tilt low-pass at 5 rad/s, a second-order rotational high-pass at 1 rad/s, scale factors 0.5, and
the tilt rate limit of 3 deg/s below which a rotation is not perceived (Groen and Bles 2004, J.
Vestibular Research 14(5)). ``config/motion_cueing.yaml`` tunes them for the paper's platform.
Nothing here imports ROS.
"""

from dataclasses import dataclass, fields
import math
from typing import Tuple

from stewart_kinematics.model.arrays import preview

#: Standard gravity, m/s^2: the specific force an accelerometer at rest reads on z.
STANDARD_GRAVITY = 9.80665

#: Fields that hold one value per axis, and how many.
_VECTORS = {
    'translation_scale': 3, 'translation_frequency': 3, 'translation_damping': 3,
    'translation_break_frequency': 3, 'tilt_scale': 2, 'rotation_scale': 3,
    'rotation_frequency': 3, 'rotation_damping': 3, 'head_position': 3,
    'imu_orientation_rpy': 3,
}
#: Fields in radians here and in degrees as parameters (``<name>_deg``).
DEGREE_FIELDS = ('tilt_rate_max', 'tilt_acceleration_max', 'tilt_max', 'joint_angle_margin',
                 'imu_orientation_rpy')
#: Fields that are names.
_NAMES = ('vehicle_frame', 'imu_frame')


@dataclass(frozen=True)
class CueingSettings:
    """
    Every setting of :class:`~stewart_kinematics.cueing.MotionCueing`, SI units.

    Axes: x forward, y left, z up (vehicle frame = base frame at neutral); roll, pitch, yaw.

    :param translation_scale: gain on the specific force of the translational channel, x y z.
    :param translation_input_limit: soft limit of the translational channel's input, m/s^2
        per axis: ``a = L tanh(a_in / L)`` keeps small inputs as they are and compresses large
        ones toward ``L`` (Reid and Nahon's nonlinear scaling, smooth); ``inf`` turns it off.
    :param translation_order: 3 (returns to neutral after a sustained input) or 2 (keeps a
        displacement of ``scale * f / omega^2`` while the input lasts).
    :param translation_frequency: omega of the second-order high-pass, rad/s, x y z.
    :param translation_damping: its damping ratio zeta, x y z; >= 1 guarantees the washout
        never reverses through neutral after a step (see :mod:`.washout`).
    :param translation_break_frequency: omega_b of the first-order high-pass (order 3), rad/s.
    :param tilt_scale: gain on the specific force rendered by tilt, x (pitch) and y (roll).
    :param tilt_complementary: use ``1 - HP`` of the translational channel (per axis) as the
        tilt low-pass instead of the classical one of ``tilt_order``: the two channels then add
        up to the whole specific force (scaled) wherever the tilt keeps within its rate limit.
    :param tilt_order: order of the tilt low-pass, 1 or 2.
    :param tilt_frequency: its omega, rad/s.
    :param tilt_damping: its zeta (order 2).
    :param tilt_rate_max: largest tilt rate, rad/s (the perception threshold of rotation).
    :param tilt_acceleration_max: largest tilt acceleration, rad/s^2 (a smooth onset).
    :param tilt_max: largest tilt angle of the tilt channel, rad.
    :param rotation_scale: gain on the angular velocity, roll pitch yaw.
    :param rotation_order: order of the rotational high-pass on the angular velocity, 1 or 2
        (2 returns the angle to neutral after a sustained rate).
    :param rotation_frequency: its omega, rad/s, roll pitch yaw.
    :param rotation_damping: its zeta, roll pitch yaw.
    :param head_position: the cueing reference point (the driver's head) in the platform frame,
        metres: the cue's rotations turn about it, and the perceived motion is computed there.
    :param follower_frequency: bandwidth of the limit-aware follower that brings the platform
        back onto the cue after the actuator limits held it back, rad/s.
    :param workspace_recovery_rate: fastest rise of the workspace scale back toward 1, 1/s.
    :param leg_length_margin: the cue keeps this far inside the stroke, metres (raised to the
        actuators' braking distance when that is longer).
    :param joint_angle_margin: the cue keeps this far inside each joint cone, rad.
    :param condition_margin: the cue keeps the Jacobian condition number below this fraction
        of ``max_jacobian_condition``.
    :param max_input_gap: a longer time between two samples counts as this long (the washout's
        clock pauses, with a warning), seconds.
    :param max_specific_force: larger specific forces are refused as absurd, m/s^2.
    :param max_angular_velocity: larger angular velocities are refused as absurd, rad/s.
    :param gravity: g, m/s^2.
    :param vehicle_frame: the name of the vehicle's body frame (x forward, y left, z up).
    :param imu_frame: the name of another frame samples may come in, or ``''``.
    :param imu_orientation_rpy: the orientation of ``imu_frame`` in ``vehicle_frame``, roll,
        pitch, yaw about fixed axes (``R = Rz Ry Rx``), radians.
    :param input_timeout: without a sample for this long (the commands' clock), the input is
        lost and the platform eases home (:meth:`~stewart_kinematics.cueing.MotionCueing.
        watch`), seconds; 0 turns the watchdog off.
    :raises ValueError: naming the setting, for a value out of its range or of the wrong size.
    """

    translation_scale: Tuple[float, ...] = (0.5, 0.5, 0.5)
    translation_input_limit: float = math.inf
    translation_order: int = 3
    translation_frequency: Tuple[float, ...] = (2.5, 2.5, 4.0)
    translation_damping: Tuple[float, ...] = (1.0, 1.0, 1.0)
    translation_break_frequency: Tuple[float, ...] = (0.25, 0.25, 0.25)
    tilt_scale: Tuple[float, ...] = (0.5, 0.5)
    tilt_complementary: bool = False
    tilt_order: int = 2
    tilt_frequency: float = 5.0
    tilt_damping: float = 1.0
    tilt_rate_max: float = math.radians(3.0)
    tilt_acceleration_max: float = math.radians(10.0)
    tilt_max: float = math.radians(15.0)
    rotation_scale: Tuple[float, ...] = (0.5, 0.5, 0.5)
    rotation_order: int = 2
    rotation_frequency: Tuple[float, ...] = (1.0, 1.0, 1.0)
    rotation_damping: Tuple[float, ...] = (1.0, 1.0, 1.0)
    head_position: Tuple[float, ...] = (0.0, 0.0, 0.5)
    follower_frequency: float = 10.0
    workspace_recovery_rate: float = 0.5
    leg_length_margin: float = 0.01
    joint_angle_margin: float = math.radians(2.0)
    condition_margin: float = 0.9
    max_input_gap: float = 0.1
    max_specific_force: float = 100.0
    max_angular_velocity: float = 20.0
    gravity: float = STANDARD_GRAVITY
    vehicle_frame: str = 'base_link'
    imu_frame: str = ''
    imu_orientation_rpy: Tuple[float, ...] = (0.0, 0.0, 0.0)
    input_timeout: float = 0.5

    def __post_init__(self):
        for item in fields(self):
            value = getattr(self, item.name)
            if item.name in _VECTORS:
                try:
                    value = tuple(float(entry) for entry in value)
                except (TypeError, ValueError):
                    raise ValueError(f'{item.name} must be {_VECTORS[item.name]} numbers, got '
                                     f'{preview(value)}') from None
                if len(value) != _VECTORS[item.name] or not all(map(math.isfinite, value)):
                    raise ValueError(f'{item.name} must be {_VECTORS[item.name]} finite '
                                     f'numbers, got {preview(list(value))}')
            elif item.name in _NAMES:
                if not isinstance(value, str):
                    raise ValueError(f'{item.name} must be a frame name, got {preview(value)}')
            elif item.name == 'tilt_complementary':
                if not isinstance(value, bool):
                    raise ValueError(f'{item.name} must be true or false, got {preview(value)}')
            elif item.name.endswith('_order'):
                if isinstance(value, bool) or not isinstance(value, int):
                    raise ValueError(f'{item.name} must be an integer, got {preview(value)}')
            else:
                try:
                    value = float(value)
                except (TypeError, ValueError):
                    raise ValueError(f'{item.name} must be a number, got '
                                     f'{preview(value)}') from None
                if not math.isfinite(value) and not (
                        item.name == 'translation_input_limit' and value == math.inf):
                    raise ValueError(f'{item.name} must be finite, got {value!r}')
            object.__setattr__(self, item.name, value)
        self._check_ranges()

    def _check_ranges(self):
        orders = {'translation_order': (2, 3), 'tilt_order': (1, 2), 'rotation_order': (1, 2)}
        for name, allowed in orders.items():
            if getattr(self, name) not in allowed:
                raise ValueError(f'{name} must be one of {allowed}, got {getattr(self, name)!r}')
        positive = ('translation_frequency', 'translation_damping', 'translation_break_frequency',
                    'tilt_frequency', 'tilt_damping', 'tilt_rate_max', 'tilt_acceleration_max',
                    'tilt_max', 'rotation_frequency', 'rotation_damping', 'follower_frequency',
                    'workspace_recovery_rate', 'max_input_gap', 'max_specific_force',
                    'translation_input_limit',
                    'max_angular_velocity', 'gravity')
        for name in positive:
            values = getattr(self, name)
            items = values if isinstance(values, tuple) else (values,)
            if not all(value > 0.0 for value in items):
                raise ValueError(f'{name} must be positive, got {values!r}')
        for name in ('translation_scale', 'tilt_scale', 'rotation_scale'):
            if not all(0.0 <= value <= 10.0 for value in getattr(self, name)):
                raise ValueError(f'{name} must be in [0, 10], got {getattr(self, name)!r}')
        bounded = {'tilt_max': (0.0, math.radians(45.0)),
                   'leg_length_margin': (0.0, 1.0),
                   'joint_angle_margin': (0.0, math.radians(45.0)),
                   'condition_margin': (0.0, 1.0),
                   'input_timeout': (0.0, 3600.0)}
        for name, (low, high) in bounded.items():
            value = getattr(self, name)
            if not low <= value <= high or (name == 'condition_margin' and value == 0.0):
                raise ValueError(f'{name} must be in [{low:g}, {high:g}], got {value!r}')

    @classmethod
    def from_parameters(cls, values: dict) -> 'CueingSettings':
        """
        Build the settings from ROS parameter values (angles ``<name>_deg`` in degrees).

        :param values: parameter name -> value; a missing one keeps its default.
        :raises ValueError: naming the parameter, for a value out of its range.
        """
        arguments = {}
        for item in fields(cls):
            if item.name in DEGREE_FIELDS:
                if item.name + '_deg' in values:
                    value = values[item.name + '_deg']
                    arguments[item.name] = (tuple(math.radians(entry) for entry in value)
                                            if item.name in _VECTORS else math.radians(value))
            elif item.name in values:
                value = values[item.name]
                arguments[item.name] = tuple(value) if item.name in _VECTORS else value
        try:
            return cls(**arguments)
        except ValueError as error:
            message = str(error)
            for name in DEGREE_FIELDS:
                if message.startswith(name + ' '):
                    message = (f'{name}_deg must be in degrees within the allowed range; '
                               f'{message}')
            raise ValueError(message) from None
