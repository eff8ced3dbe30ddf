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
as the node declares them). Those declarations are the one source of each setting's default and
allowed values: a field's default is its parameter's (converted to radians), and a value is
checked by its parameter's validators (their bounds converted to radians), so the settings and
the parameters cannot differ.

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
from stewart_kinematics.model.validators import first_reason
from stewart_kinematics.parameters.declarations import MOTION_CUEING_PARAMETERS

#: Standard gravity, m/s^2: the specific force an accelerometer at rest reads on z.
STANDARD_GRAVITY = 9.80665

#: Fields that hold one value per axis, and how many.
_VECTORS = {
    'translation_scale': 3, 'translation_frequency': 3, 'translation_damping': 3,
    'translation_break_frequency': 3, 'tilt_scale': 2, 'rotation_scale': 3,
    'rotation_frequency': 3, 'rotation_damping': 3, 'head_position': 3,
    'imu_orientation_rpy': 3, 'follower_weights': 6, 'mpc_force_scale': 3,
    'mpc_force_weight': 3, 'mpc_position_weight': 3, 'mpc_velocity_weight': 3,
    'mpc_input_weight': 2,
}
#: Fields in radians here and in degrees as parameters (``<name>_deg``).
DEGREE_FIELDS = ('tilt_rate_max', 'tilt_acceleration_max', 'tilt_max', 'joint_angle_margin',
                 'imu_orientation_rpy')
#: Fields that are true or false.
_BOOLS = ('tilt_complementary', 'attitude_aware_specific_force')
#: Fields that are names.
_NAMES = ('vehicle_frame', 'imu_frame')
#: Fields that are one of a few words, and integer fields besides the filters' orders.
_CHOICES = ('cueing_method',)
_INTEGERS = ('mpc_horizon', 'mpc_max_iterations')
#: The parameter of each field: ``<name>_deg`` for a field in radians, else its own name.
_SPECS = {spec.name.removesuffix('_deg') if spec.name.removesuffix('_deg') in DEGREE_FIELDS
          else spec.name: spec for spec in MOTION_CUEING_PARAMETERS}
#: The rules of each field: its parameter's validators, their bounds in radians where the
#: parameter is in degrees.
_RULES = {name: tuple(rule.converted(math.radians) for rule in spec.validators)
          if name in DEGREE_FIELDS else spec.validators for name, spec in _SPECS.items()}


def _default(name: str):
    """Return the default of a field: its parameter's, in radians where that is in degrees."""
    value = _SPECS[name].default
    if name in DEGREE_FIELDS:
        return tuple(map(math.radians, value)) if name in _VECTORS else math.radians(value)
    return tuple(value) if isinstance(value, list) else value


def _converted(name: str, value):
    """
    Return a field's value as the settings hold it (a tuple of floats, a float, ...).

    :raises ValueError: naming the field, for a value of the wrong kind (its range is checked
        after, by its parameter's rules).
    """
    if name in _VECTORS:
        try:
            return tuple(float(entry) for entry in value)
        except (TypeError, ValueError):
            raise ValueError(f'{name} must be {_VECTORS[name]} numbers, got '
                             f'{preview(value)}') from None
    if name in _NAMES:
        if not isinstance(value, str):
            raise ValueError(f'{name} must be a frame name, got {preview(value)}')
        return value
    if name in _CHOICES:
        if not isinstance(value, str):
            raise ValueError(f'{name} must be a word, got {preview(value)}')
        return value
    if name in _BOOLS:
        if not isinstance(value, bool):
            raise ValueError(f'{name} must be true or false, got {preview(value)}')
        return value
    if name.endswith('_order') or name in _INTEGERS:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ValueError(f'{name} must be an integer, got {preview(value)}')
        return value
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ValueError(f'{name} must be a number, got {preview(value)}') from None


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
    :param attitude_aware_specific_force: turn the specific force into the simulator's frame
        through the cue's attitude before the translational channel (Reid and Nahon's
        ``L_IS``, see :mod:`.washout`), so that a tilt or a coordinated turn is not felt as a
        sideways force; ``False``: the translational channel takes the force as it comes.
    :param head_position: the cueing reference point (the driver's head) in the platform frame,
        metres: the cue's rotations turn about it, and the perceived motion is computed there.
    :param follower_frequency: bandwidth of the limit-aware follower that brings the platform
        back onto the cue after the actuator limits held it back, rad/s.
    :param follower_weights: weights of the follower's least-squares step where the legs
        cannot follow the cue, per axis of the platform's twist: x, y, z (per m/s) and roll,
        pitch, yaw (per rad/s), positive; a larger weight keeps that axis closer to the cue.
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
    :param cueing_method: ``'classical'`` (:class:`~.washout.ClassicalWashout`) or ``'mpc'``
        (:class:`~.mpc_cueing.MpcCueing`, with the ``mpc_*`` settings below).
    :param mpc_horizon: steps of the MPC's horizon.
    :param mpc_step: seconds per MPC step.
    :param mpc_force_scale: share of the vehicle's perceived specific force aimed at, x y z.
    :param mpc_force_weight: weight of the perceived specific-force error, per (m/s^2)^2.
    :param mpc_rate_weight: weight of the perceived roll and pitch rate error, per (rad/s)^2.
    :param mpc_position_weight: weight of the head's displacement, x y z, per m^2.
    :param mpc_velocity_weight: weight of its velocity, per (m/s)^2.
    :param mpc_tilt_weight: weight of the tilt, per rad^2.
    :param mpc_tilt_rate_weight: weight of the tilt rate, per (rad/s)^2.
    :param mpc_input_weight: weights of the head's acceleration, per (m/s^2)^2, and of the
        tilt's acceleration, per (rad/s^2)^2.
    :param mpc_reference_time_constant: the vehicle's input is predicted held, fading with
        this time constant, seconds (``inf``: held).
    :param mpc_limit_share: share of the leg velocity and acceleration limits and of
        ``tilt_rate_max`` the MPC plans with.
    :param mpc_workspace_share: the MPC keeps each cue coordinate within this share of its
        reach alone inside the cue's limits.
    :param mpc_max_iterations: the QP solver's iteration limit.
    :raises ValueError: naming the setting, for a value out of its range or of the wrong size.
    """

    translation_scale: Tuple[float, ...] = _default('translation_scale')
    translation_input_limit: float = _default('translation_input_limit')
    translation_order: int = _default('translation_order')
    translation_frequency: Tuple[float, ...] = _default('translation_frequency')
    translation_damping: Tuple[float, ...] = _default('translation_damping')
    translation_break_frequency: Tuple[float, ...] = _default('translation_break_frequency')
    tilt_scale: Tuple[float, ...] = _default('tilt_scale')
    tilt_complementary: bool = _default('tilt_complementary')
    tilt_order: int = _default('tilt_order')
    tilt_frequency: float = _default('tilt_frequency')
    tilt_damping: float = _default('tilt_damping')
    tilt_rate_max: float = _default('tilt_rate_max')
    tilt_acceleration_max: float = _default('tilt_acceleration_max')
    tilt_max: float = _default('tilt_max')
    rotation_scale: Tuple[float, ...] = _default('rotation_scale')
    rotation_order: int = _default('rotation_order')
    rotation_frequency: Tuple[float, ...] = _default('rotation_frequency')
    rotation_damping: Tuple[float, ...] = _default('rotation_damping')
    attitude_aware_specific_force: bool = _default('attitude_aware_specific_force')
    head_position: Tuple[float, ...] = _default('head_position')
    follower_frequency: float = _default('follower_frequency')
    follower_weights: Tuple[float, ...] = _default('follower_weights')
    workspace_recovery_rate: float = _default('workspace_recovery_rate')
    leg_length_margin: float = _default('leg_length_margin')
    joint_angle_margin: float = _default('joint_angle_margin')
    condition_margin: float = _default('condition_margin')
    max_input_gap: float = _default('max_input_gap')
    max_specific_force: float = _default('max_specific_force')
    max_angular_velocity: float = _default('max_angular_velocity')
    gravity: float = STANDARD_GRAVITY
    vehicle_frame: str = _default('vehicle_frame')
    imu_frame: str = _default('imu_frame')
    imu_orientation_rpy: Tuple[float, ...] = _default('imu_orientation_rpy')
    input_timeout: float = _default('input_timeout')
    cueing_method: str = _default('cueing_method')
    mpc_horizon: int = _default('mpc_horizon')
    mpc_step: float = _default('mpc_step')
    mpc_force_scale: Tuple[float, ...] = _default('mpc_force_scale')
    mpc_force_weight: Tuple[float, ...] = _default('mpc_force_weight')
    mpc_rate_weight: float = _default('mpc_rate_weight')
    mpc_position_weight: Tuple[float, ...] = _default('mpc_position_weight')
    mpc_velocity_weight: Tuple[float, ...] = _default('mpc_velocity_weight')
    mpc_tilt_weight: float = _default('mpc_tilt_weight')
    mpc_tilt_rate_weight: float = _default('mpc_tilt_rate_weight')
    mpc_input_weight: Tuple[float, ...] = _default('mpc_input_weight')
    mpc_reference_time_constant: float = _default('mpc_reference_time_constant')
    mpc_limit_share: float = _default('mpc_limit_share')
    mpc_workspace_share: float = _default('mpc_workspace_share')
    mpc_max_iterations: int = _default('mpc_max_iterations')

    def __post_init__(self):
        for item in fields(self):
            value = _converted(item.name, getattr(self, item.name))
            object.__setattr__(self, item.name, value)
            reason = first_reason(_RULES.get(item.name, ()), item.name, value)
            if reason:
                raise ValueError(reason)
        if not (math.isfinite(self.gravity) and self.gravity > 0.0):
            raise ValueError(f'gravity must be positive and finite (m/s^2), got {self.gravity!r}')

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
                arguments[item.name] = value   # made a tuple, or refused, by _converted
        try:
            return cls(**arguments)
        except ValueError as error:
            message = str(error)
            for name in DEGREE_FIELDS:
                if message.startswith(name + ' '):
                    message = (f'{name}_deg must be in degrees within the allowed range; '
                               f'{message}')
            raise ValueError(message) from None
