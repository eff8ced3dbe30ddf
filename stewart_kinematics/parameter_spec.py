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
Every ROS parameter of the package, declared once, and the reader of parameter files.

Each :class:`ParameterSpec` gives a parameter's name, type, default (``None``: required),
description with its unit, read-only flag and validators. The nodes turn these specs into ROS
declarations (:mod:`stewart_kinematics.ros.ros_parameters`), the core reads the same names
from YAML (:func:`load_geometry`), and the README's parameter tables list them.

A validator takes ``(name, value)`` and returns ``''`` when the value is allowed, else a sentence
that names the parameter, the value and what is allowed. Nothing here imports ROS.
"""

import array
from dataclasses import dataclass
import difflib
import math
from typing import Any, Callable, Optional, Tuple

import numpy as np

from stewart_kinematics.frames import FrameTree, Transform
from stewart_kinematics.geometry import Geometry
import yaml

Validator = Callable[[str, Any], str]

# Parameter types, spelled as in rcl_interfaces/msg/ParameterType.
BOOL = 'bool'
INTEGER = 'integer'
DOUBLE = 'double'
STRING = 'string'
DOUBLE_ARRAY = 'double_array'
STRING_ARRAY = 'string_array'

_PYTHON_TYPES = {
    BOOL: (bool,),
    INTEGER: (int,),
    DOUBLE: (float,),
    STRING: (str,),
    # rclpy hands double arrays from parameter services over as array.array('d').
    DOUBLE_ARRAY: (list, tuple, array.array),
    STRING_ARRAY: (list, tuple),
}


@dataclass(frozen=True)
class ParameterSpec:
    """
    Declaration of one ROS parameter.

    :param name: parameter name.
    :param value_type: one of ``bool``, ``integer``, ``double``, ``string``, ``double_array``.
    :param description: what it means, with its unit.
    :param default: value used when no parameter file sets it; ``None`` makes it required.
    :param read_only: True where a change at run time makes no sense (the geometry).
    :param validators: checks run on every value, at start-up and on every run-time change.
    :param constraints: the allowed values in words, for the README table.
    """

    name: str
    value_type: str
    description: str
    default: Any = None
    read_only: bool = False
    validators: Tuple[Validator, ...] = ()
    constraints: str = ''

    def check(self, value) -> str:
        """
        Check a value against the type and the validators.

        :returns: ``''`` if the value is allowed, else the first reason it is not.
        """
        if value is None:
            if self.default is None:
                return (f"parameter '{self.name}' is required ({self.description}); set it in "
                        'a parameter file')
            return ''
        # Strict as rcl is: YAML's 1 is an integer, and a double parameter wants 1.0.
        if not isinstance(value, _PYTHON_TYPES[self.value_type]) or (
                self.value_type == INTEGER and isinstance(value, bool)):
            hint = ' (write 1.0, not 1)' if self.value_type == DOUBLE else ''
            return (f"parameter '{self.name}' must be of type {self.value_type}, got {value!r} "
                    f'({type(value).__name__}){hint}')
        if self.value_type == DOUBLE_ARRAY and not all(isinstance(item, float) for item in value):
            return (f"parameter '{self.name}' must be a list of floating-point numbers, got "
                    f'{list(value)!r} (write 1.0, not 1)')
        if self.value_type == STRING_ARRAY and not all(isinstance(item, str) for item in value):
            return f"parameter '{self.name}' must be a list of strings, got {list(value)!r}"
        for validator in self.validators:
            reason = validator(self.name, value)
            if reason:
                return reason
        return ''


def fixed_length(length: int) -> Validator:
    """Require an array of exactly ``length`` elements."""
    def validate(name, value):
        if len(value) != length:
            return (f"parameter '{name}' must have exactly {length} elements, "
                    f'got {len(value)}: {list(value)!r}')
        return ''
    return validate


def finite(name, value) -> str:
    """Require a finite number, or an array of finite numbers."""
    values = value if isinstance(value, _PYTHON_TYPES[DOUBLE_ARRAY]) else [value]
    if not all(math.isfinite(item) for item in values):
        return f"parameter '{name}' must be finite, got {value!r}"
    return ''


def in_range(low: float, high: float, *, low_inclusive: bool = True,
             high_inclusive: bool = True) -> Validator:
    """Require a number (or every element of an array) within ``[low, high]``."""
    def validate(name, value):
        values = value if isinstance(value, _PYTHON_TYPES[DOUBLE_ARRAY]) else [value]
        for item in values:
            above_low = item >= low if low_inclusive else item > low
            below_high = item <= high if high_inclusive else item < high
            if not (above_low and below_high):
                interval = (('[' if low_inclusive else '(') + f'{low:g}, {high:g}'
                            + (']' if high_inclusive else ')'))
                return f"parameter '{name}' must be in {interval}, got {value!r}"
        return ''
    return validate


def zero_or_in_range(low: float, high: float) -> Validator:
    """Require 0 (a feature turned off) or a number within ``[low, high]``."""
    within = in_range(low, high)

    def validate(name, value):
        if value == 0.0 or not within(name, value):
            return ''
        return f"parameter '{name}' must be 0.0 or in [{low:g}, {high:g}], got {value!r}"
    return validate


def one_of(*allowed: str) -> Validator:
    """Require one of the given strings."""
    def validate(name, value):
        if value not in allowed:
            return f"parameter '{name}' must be one of {', '.join(allowed)}; got {value!r}"
        return ''
    return validate


GEOMETRY_PARAMETERS = (
    ParameterSpec(
        'base_joints', DOUBLE_ARRAY,
        'Base joint centres b_1..b_6 in the base frame, metres, flattened as '
        'x1, y1, z1, ..., x6, y6, z6',
        read_only=True, validators=(fixed_length(18), finite),
        constraints='18 finite values; 6 distinct, non-collinear joints'),
    ParameterSpec(
        'platform_joints', DOUBLE_ARRAY,
        'Platform joint centres p_1..p_6 in the platform frame, metres, flattened as '
        'x1, y1, z1, ..., x6, y6, z6',
        read_only=True, validators=(fixed_length(18), finite),
        constraints='18 finite values; 6 distinct, non-collinear joints'),
    ParameterSpec(
        'home_position', DOUBLE_ARRAY,
        'Home (neutral) position X, Y, Z of the platform frame in the base frame, metres; '
        'leg extensions are measured from it and forward kinematics starts from it',
        read_only=True, validators=(fixed_length(3), finite),
        constraints='3 finite values'),
    ParameterSpec(
        'home_orientation_deg', DOUBLE_ARRAY,
        'Home orientation alpha, beta, gamma (R = Rz(gamma) Ry(beta) Rx(alpha)), degrees',
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(fixed_length(3), finite, in_range(-180.0, 180.0)),
        constraints='3 values in [-180, 180]'),
    ParameterSpec(
        'leg_length_min', DOUBLE,
        'Shortest allowed leg length (actuator fully retracted), metres; 0.0 for no limit',
        default=0.0, read_only=True, validators=(finite, in_range(0.0, math.inf)),
        constraints='>= 0, < leg_length_max'),
    ParameterSpec(
        'leg_length_max', DOUBLE,
        'Longest allowed leg length (actuator fully extended), metres; .inf for no limit',
        default=math.inf, read_only=True,
        validators=(in_range(0.0, math.inf, low_inclusive=False),),
        constraints='> leg_length_min; .inf allowed'),
    ParameterSpec(
        'base_joint_max_angle_deg', DOUBLE,
        'Largest angle between a leg and its home direction at the base joint (joint cone), '
        'degrees; 180.0 for no limit',
        default=180.0, read_only=True,
        validators=(finite, in_range(0.0, 180.0, low_inclusive=False)), constraints='in (0, 180]'),
    ParameterSpec(
        'platform_joint_max_angle_deg', DOUBLE,
        'Largest angle between a leg and its home direction at the platform joint, in the '
        'platform frame (joint cone), degrees; 180.0 for no limit',
        default=180.0, read_only=True,
        validators=(finite, in_range(0.0, 180.0, low_inclusive=False)), constraints='in (0, 180]'),
    ParameterSpec(
        'max_jacobian_condition', DOUBLE,
        'Singularity margin: largest condition number of the dimensionless Jacobian '
        "(1 is ideal, about 10 at the paper platform's home pose); .inf for no limit",
        default=math.inf, read_only=True, validators=(in_range(1.0, math.inf),),
        constraints='>= 1; .inf allowed'),
    ParameterSpec(
        'leg_velocity_max', DOUBLE,
        'Largest speed of a leg (actuator), metres per second: timed trajectories are refused '
        'or retimed to keep within it, streamed commands are limited to it; .inf for no limit',
        default=math.inf, read_only=True,
        validators=(in_range(0.0, math.inf, low_inclusive=False),),
        constraints='> 0; .inf allowed'),
    ParameterSpec(
        'leg_acceleration_max', DOUBLE,
        'Largest acceleration of a leg, metres per second squared, as leg_velocity_max; '
        '.inf for no limit',
        default=math.inf, read_only=True,
        validators=(in_range(0.0, math.inf, low_inclusive=False),),
        constraints='> 0; .inf allowed'),
    ParameterSpec(
        'leg_jerk_max', DOUBLE,
        'Largest jerk of a leg, metres per second cubed, for streamed commands (command_rate); '
        '.inf for no limit',
        default=math.inf, read_only=True,
        validators=(in_range(0.0, math.inf, low_inclusive=False),),
        constraints='> 0; .inf allowed'),
)


def distinct_names(name, value) -> str:
    """Require non-empty, distinct strings (joint names)."""
    if not all(value) or len(set(value)) != len(value):
        return f"parameter '{name}' must hold distinct, non-empty names, got {list(value)!r}"
    return ''


#: The legs as the actuator interface sees them: shared by every JointState and
#: JointTrajectory the package publishes or reads.
ACTUATOR_PARAMETERS = (
    ParameterSpec(
        'joint_names', STRING_ARRAY,
        'Names of the six leg actuators as prismatic joints, leg 1..6, on every JointState and '
        'JointTrajectory the package publishes or reads',
        default=['leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5', 'leg_6'], read_only=True,
        validators=(fixed_length(6), distinct_names), constraints='6 distinct, non-empty names'),
    ParameterSpec(
        'actuator_offsets', DOUBLE_ARRAY,
        "Each actuator's zero as a leg length, metres, leg 1..6: an actuator position is its "
        'leg length minus its offset',
        default=[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], read_only=True,
        validators=(fixed_length(6), finite), constraints='6 finite values'),
)

SOLVER_PARAMETERS = (
    ParameterSpec(
        'tolerance', DOUBLE,
        'Newton-Raphson stops when every leg length of the solution is within this of the '
        'measured one, metres',
        default=1e-12, validators=(finite, in_range(0.0, 1e-2, low_inclusive=False)),
        constraints='in (0, 0.01]'),
    ParameterSpec(
        'max_iterations', INTEGER,
        'Newton-Raphson iterations before a solve is reported as not converged',
        default=50, validators=(in_range(1, 1000),), constraints='in [1, 1000]'),
    ParameterSpec(
        'near_singularity_condition', DOUBLE,
        'A solution whose dimensionless Jacobian condition number exceeds this is published '
        'with a WARN status on /diagnostics: it lies near a singularity; leg velocities are '
        'not turned into a twist there (they would be amplified up to this many times)',
        default=100.0, validators=(in_range(1.0, math.inf),), constraints='>= 1; .inf allowed'),
    ParameterSpec(
        'pose_tolerance', DOUBLE,
        'Largest accepted bound on the pose error of a solution, metres and radians: near a '
        'singularity leg lengths matched to the tolerance above fix the pose only loosely, and '
        'a solution whose first-order error bound exceeds this is refused; .inf for no check',
        default=1e-9, validators=(in_range(0.0, math.inf, low_inclusive=False),),
        constraints='> 0; .inf allowed'),
    ParameterSpec(
        'assembly_guard_length_change', DOUBLE,
        'Assembly-mode guard: when no leg changed by more than this since the last solution, '
        'metres, the new solution must lie within the two limits below of the last one',
        default=0.005, validators=(finite, in_range(0.0, 1.0)), constraints='in [0, 1]'),
    ParameterSpec(
        'assembly_guard_position_change', DOUBLE,
        'Assembly-mode guard: largest move of the platform origin allowed for such a small '
        'change of the lengths, metres',
        default=0.05, validators=(finite, in_range(0.0, 10.0, low_inclusive=False)),
        constraints='in (0, 10]'),
    ParameterSpec(
        'assembly_guard_angle_change_deg', DOUBLE,
        'Assembly-mode guard: largest rotation of the platform allowed for such a small '
        'change of the lengths, degrees',
        default=10.0, validators=(finite, in_range(0.0, 180.0, low_inclusive=False)),
        constraints='in (0, 180]'),
    ParameterSpec(
        'refuse_ambiguous_start', BOOL,
        'After a start or reset_tracker, refuse to publish while more than one assembly mode '
        'lies within the limits and none within the two assembly-guard changes above of the '
        'last known pose (home, or the reset pose): the lengths alone do not tell which mode '
        'the platform is in. Costs one search for every mode (about 0.1 s) per new set of '
        'lengths until a pose is accepted',
        default=False, constraints='any'),
)

#: The assembly-mode margin that fk_node reports (see stewart_kinematics.assembly_modes).
ASSEMBLY_MODE_PARAMETERS = (
    ParameterSpec(
        'assembly_mode_margin_period', DOUBLE,
        'Time between two computations of the assembly-mode margin of the last solution '
        '(the distance to the nearest other real mode within the limits, on /diagnostics), '
        'seconds; each runs in a worker thread, and only when the lengths changed; 0.0 turns '
        'the margin off',
        default=1.0, read_only=True, validators=(finite, in_range(0.0, 3600.0)),
        constraints='in [0, 3600]'),
    ParameterSpec(
        'assembly_mode_margin_warning', DOUBLE,
        'A margin below this gives a WARN status and a log line: another real assembly mode '
        'within the limits lies this close to the estimated pose, metres, as '
        'sqrt(position^2 + (rho angle)^2) with rho the RMS radius of the platform joints; '
        '0.0 for no warning',
        default=0.05, validators=(finite, in_range(0.0, 100.0)), constraints='in [0, 100]'),
)


def frame_name(name, value) -> str:
    """Require a tf frame name: no spaces, no leading slash (tf2 refuses those)."""
    if value.startswith('/') or any(character.isspace() for character in value):
        return (f"parameter '{name}' must be a frame name without spaces or a leading '/', "
                f'got {value!r}')
    return ''


def non_empty(name, value) -> str:
    """Require a non-empty string."""
    return '' if value else f"parameter '{name}' must not be empty"


#: The frame tree (stewart_kinematics.frames): names, and the user and tool frames' poses.
FRAME_PARAMETERS = (
    ParameterSpec(
        'base_frame', STRING,
        'Name of the base frame: the parent of the platform on /tf, and the frame of stamped '
        'poses; a stamped target in a frame other than this one or user_frame is refused',
        default='stewart_base', read_only=True, validators=(non_empty, frame_name),
        constraints='a frame name'),
    ParameterSpec(
        'platform_frame', STRING,
        'Name of the platform frame (the frame the platform joints are given in) on /tf',
        default='stewart_platform', read_only=True, validators=(non_empty, frame_name),
        constraints='a frame name'),
    ParameterSpec(
        'user_frame', STRING,
        "Name of a user frame fixed to the base (a work piece's frame), on /tf_static, in "
        "which stamped poses may be given; '' for none",
        default='', read_only=True, validators=(frame_name,), constraints="a frame name or ''"),
    ParameterSpec(
        'user_frame_position', DOUBLE_ARRAY,
        'Origin of user_frame in the base frame, X, Y, Z, metres',
        default=[0.0, 0.0, 0.0], read_only=True, validators=(fixed_length(3), finite),
        constraints='3 finite values'),
    ParameterSpec(
        'user_frame_orientation_deg', DOUBLE_ARRAY,
        'Orientation of user_frame in the base frame, alpha, beta, gamma '
        '(R = Rz(gamma) Ry(beta) Rx(alpha)), degrees',
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(fixed_length(3), finite, in_range(-180.0, 180.0)),
        constraints='3 values in [-180, 180]'),
    ParameterSpec(
        'tool_frame', STRING,
        "Name of the tool frame fixed to the platform, on /tf_static; '' leaves it unnamed "
        '(its pose below still applies)',
        default='', validators=(frame_name,), constraints="a frame name or ''"),
    ParameterSpec(
        'tool_frame_position', DOUBLE_ARRAY,
        'Origin of the tool frame in the platform frame, X, Y, Z, metres: the pivot point. '
        'Commanded and estimated poses are those of the tool frame, so a pure rotation turns '
        'the platform about this point',
        default=[0.0, 0.0, 0.0], validators=(fixed_length(3), finite),
        constraints='3 finite values'),
    ParameterSpec(
        'tool_frame_orientation_deg', DOUBLE_ARRAY,
        'Orientation of the tool frame in the platform frame, alpha, beta, gamma '
        '(R = Rz(gamma) Ry(beta) Rx(alpha)), degrees',
        default=[0.0, 0.0, 0.0], validators=(fixed_length(3), finite, in_range(-180.0, 180.0)),
        constraints='3 values in [-180, 180]'),
)

#: fk_node's broadcast of the estimated pose.
FK_FRAME_PARAMETERS = (
    ParameterSpec(
        'publish_tf', BOOL,
        'Broadcast the estimated pose on /tf (base_frame -> platform_frame, with the stamp '
        'of the lengths it comes from) and the user and tool frames on /tf_static',
        default=True, read_only=True),
    ParameterSpec(
        'estimated_pose_frame', STRING,
        "Frame of estimated_pose_stamped: base_frame or user_frame; '' means base_frame",
        default='', read_only=True, validators=(frame_name,),
        constraints="'', base_frame or user_frame"),
)

#: ik_node's broadcast of the commanded pose.
IK_FRAME_PARAMETERS = (
    ParameterSpec(
        'publish_commanded_tf', BOOL,
        'Broadcast each accepted command on /tf as base_frame -> <platform_frame>_commanded',
        default=False, read_only=True),
)

MARKER_PARAMETERS = (
    ParameterSpec(
        'marker_rate', DOUBLE,
        'Highest rate of platform_markers, hertz: RViz needs no more, and a marker array per '
        'pose would cost a 1 kHz command stream; 0.0 turns the markers off',
        default=30.0, read_only=True, validators=(finite, in_range(0.0, 1000.0)),
        constraints='in [0, 1000]'),
)

WORKSPACE_PARAMETERS = (
    ParameterSpec(
        'workspace_resolution', DOUBLE,
        'Grid step of the constant-orientation workspace (at the home orientation) that '
        'workspace_markers shows, metres; computed in a worker process once the topic has a '
        'subscriber, and again when this changes; 0.0 turns the markers off',
        default=0.01, validators=(finite, zero_or_in_range(0.002, 0.1)),
        constraints='0.0 or in [0.002, 0.1]'),
    ParameterSpec(
        'travel_range_rate', DOUBLE,
        'Rate of travel_ranges, the range left along each axis from the last accepted pose, '
        'hertz; computed in a worker process while the topic has a subscriber and the pose '
        'has moved; 0.0 turns them off',
        default=1.0, read_only=True, validators=(finite, in_range(0.0, 10.0)),
        constraints='in [0, 10]'),
)

QUEUE_PARAMETERS = (
    ParameterSpec(
        'queue_depth', INTEGER,
        'Depth of the reliable, keep-last queues of every subscription and publisher, messages',
        default=10, read_only=True, validators=(in_range(1, 10000),),
        constraints='in [1, 10000]'),
)

RAMP_PARAMETERS = (
    ParameterSpec(
        'position_start', DOUBLE_ARRAY, 'First row of the ramp: X, Y, Z in metres',
        default=[0.0, 0.0, 0.4325], read_only=True, validators=(fixed_length(3), finite),
        constraints='3 finite values'),
    ParameterSpec(
        'position_step', DOUBLE_ARRAY, 'Change of X, Y, Z from one row to the next, metres',
        default=[0.01, 0.015, 0.01], read_only=True, validators=(fixed_length(3), finite),
        constraints='3 finite values; same number of steps on every axis'),
    ParameterSpec(
        'position_end', DOUBLE_ARRAY, 'Last row of the ramp: X, Y, Z in metres',
        default=[0.1, 0.15, 0.5325], read_only=True, validators=(fixed_length(3), finite),
        constraints='3 finite values'),
    ParameterSpec(
        'orientation_start_deg', DOUBLE_ARRAY,
        'First row of the ramp: alpha, beta, gamma in degrees',
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(fixed_length(3), finite, in_range(-180.0, 180.0)),
        constraints='3 values in [-180, 180]'),
    ParameterSpec(
        'orientation_step_deg', DOUBLE_ARRAY,
        'Change of alpha, beta, gamma from one row to the next, degrees',
        default=[1.5, -1.5, 2.0], read_only=True, validators=(fixed_length(3), finite),
        constraints='3 finite values; same number of steps on every axis'),
    ParameterSpec(
        'orientation_end_deg', DOUBLE_ARRAY,
        'Last row of the ramp: alpha, beta, gamma in degrees',
        default=[15.0, -15.0, 20.0], read_only=True,
        validators=(fixed_length(3), finite, in_range(-180.0, 180.0)),
        constraints='3 values in [-180, 180]'),
    ParameterSpec(
        'mode', STRING,
        "'table': publish the table's rows, one every row_period; 'interpolate': sample the "
        "ramp in time, like the paper's clock-driven lookup tables, at publish_rate over "
        "duration; 'off': no ramp, only the trajectories received on pose_trajectory and "
        'pose_path',
        default='table', read_only=True, validators=(one_of('table', 'interpolate', 'off'),),
        constraints="'table', 'interpolate' or 'off'"),
    ParameterSpec(
        'row_period', DOUBLE, "Time between two rows in 'table' mode, seconds",
        default=1.0, read_only=True, validators=(finite, in_range(1e-3, 3600.0)),
        constraints='in [0.001, 3600]'),
    ParameterSpec(
        'publish_rate', DOUBLE,
        "Rate of the samples in 'interpolate' mode; for a received trajectory, rate of the "
        'points of leg_trajectory (every waypoint is a point too) and of the poses played on '
        'target_pose, hertz',
        default=50.0, read_only=True, validators=(finite, in_range(1e-3, 1000.0)),
        constraints='in [0.001, 1000]'),
    ParameterSpec(
        'duration', DOUBLE,
        "Time from the first row to the last in 'interpolate' mode, seconds",
        default=10.0, read_only=True, validators=(finite, in_range(1e-3, 86400.0)),
        constraints='in [0.001, 86400]'),
    ParameterSpec(
        'loop', BOOL, 'Start again from the first row after the last one',
        default=False, read_only=True),
    ParameterSpec(
        'start_delay', DOUBLE,
        'Time between min_subscribers being matched and the first pose, seconds: the '
        'subscribers match this publisher a moment after it matches them, and a pose sent '
        'before that would be lost',
        default=0.5, read_only=True, validators=(finite, in_range(0.0, 3600.0)),
        constraints='in [0, 3600]'),
    ParameterSpec(
        'min_subscribers', INTEGER,
        'Wait until this many subscriptions are matched on target_pose before playing, so '
        'that no pose is published to nobody',
        default=0, read_only=True, validators=(in_range(0, 1000),), constraints='in [0, 1000]'),
)


#: trajectory_node: trajectories and paths received on pose_trajectory and pose_path.
MOTION_PARAMETERS = (
    ParameterSpec(
        'retime', BOOL,
        'Retime every received trajectory to the fastest timing within the leg velocity and '
        'acceleration limits (toppra), instead of refusing one whose own timing breaks them; '
        'a path (pose_path) is always retimed',
        default=False),
    ParameterSpec(
        'speed_scale', DOUBLE,
        'Fraction of the fastest speed: a trajectory is played 1 / speed_scale times as long '
        '(retimed: at speed_scale of the leg velocity limit, speed_scale^2 of the acceleration '
        'limit)',
        default=1.0, validators=(finite, in_range(0.0, 1.0, low_inclusive=False)),
        constraints='in (0, 1]'),
    ParameterSpec(
        'validation_rate', DOUBLE,
        'Samples per second at which a whole trajectory is checked against every limit before '
        'anything is published, hertz',
        default=1000.0, validators=(finite, in_range(1.0, 100000.0)),
        constraints='in [1, 100000]'),
    ParameterSpec(
        'play', BOOL,
        'Also play an accepted trajectory on target_pose at publish_rate, for the ik_node chain',
        default=False),
)

#: ik_node: commands streamed through the jerk-limited filter.
STREAMING_PARAMETERS = (
    ParameterSpec(
        'command_rate', DOUBLE,
        'Rate of joint_commands, hertz: each command moves from the last toward the latest '
        'accepted target within leg_velocity_max, leg_acceleration_max and leg_jerk_max '
        '(ruckig; the first two must be set); 0.0: one command per accepted pose, unfiltered',
        default=0.0, read_only=True, validators=(finite, in_range(0.0, 10000.0)),
        constraints='in [0, 10000]'),
)


def all_specs():
    """Return every parameter spec of the package, each name once."""
    return (GEOMETRY_PARAMETERS + ACTUATOR_PARAMETERS + SOLVER_PARAMETERS
            + ASSEMBLY_MODE_PARAMETERS + FRAME_PARAMETERS + FK_FRAME_PARAMETERS
            + IK_FRAME_PARAMETERS + MARKER_PARAMETERS + WORKSPACE_PARAMETERS + QUEUE_PARAMETERS
            + RAMP_PARAMETERS + MOTION_PARAMETERS + STREAMING_PARAMETERS)


#: Parameters that were replaced, and what replaces them: named in the refusal of an old file.
REPLACED_PARAMETERS = {
    'pivot_point': "'tool_frame_position' (the tool frame's origin is the pivot point)",
}


def check_known_names(names, context: str) -> None:
    """
    Refuse parameter names that no node of the package declares: a typo would go unnoticed.

    :param names: the names given, such as the keys of a parameter file's sections.
    :param context: where they come from, for the message.
    :raises ValueError: naming the unknown names and the closest known ones.
    """
    known = {spec.name for spec in all_specs()}
    unknown = sorted(set(names) - known)
    if unknown:
        def hint(name):
            if name in REPLACED_PARAMETERS:
                return f' (replaced by {REPLACED_PARAMETERS[name]})'
            close = difflib.get_close_matches(name, known, n=1)
            return f" (did you mean '{close[0]}'?)" if close else ''
        described = ', '.join(f"'{name}'{hint(name)}" for name in unknown)
        raise ValueError(f'unknown parameter(s) {described} in {context}; known parameters: '
                         + ', '.join(sorted(known)))


def defaults(specs) -> dict:
    """Map each parameter name of ``specs`` to its default value (``None`` when required)."""
    return {spec.name: spec.default for spec in specs}


def check_values(specs, values: dict) -> None:
    """
    Check every value of ``values`` named in ``specs``.

    :raises ValueError: with the first reason a value is not allowed.
    """
    for spec in specs:
        reason = spec.check(values.get(spec.name))
        if reason:
            raise ValueError(reason)


def read_parameter_file(path, node_name: Optional[str] = None) -> dict:
    """
    Read the parameters a node would get from a ROS 2 parameter file.

    Sections apply as rcl applies them: ``/**`` first, then the section of ``node_name``
    (``name``, ``/name`` or ``/namespace/name``), which overrides it.

    :param path: a YAML file in the ``<node>: ros__parameters: {...}`` layout.
    :param node_name: the node whose view to return: a bare name (``fk_node``) matches its
        section in any namespace, a full name (``/robot_a/fk_node``) only that one; ``None``
        reads only ``/**``.
    :returns: parameter name -> value.
    :raises ValueError: if the file is missing, is not valid YAML or has no such layout.
    """
    try:
        with open(path, encoding='utf-8') as stream:
            document = yaml.safe_load(stream)
    except OSError as error:
        raise ValueError(f'cannot read parameter file {path}: {error.strerror}') from error
    except yaml.YAMLError as error:
        raise ValueError(f'parameter file {path} is not valid YAML: {error}') from error
    if not isinstance(document, dict):
        raise ValueError(f'parameter file {path} must map node names to ros__parameters')

    def applies(key, section):
        if section == '/**' or '/' in section:
            return key.lstrip('/') == section.lstrip('/')
        return key.rsplit('/', 1)[-1] == section

    values = {}
    for section in ['/**'] + ([] if node_name is None else [node_name]):
        for key, content in document.items():
            if applies(str(key), section):
                if not isinstance(content, dict) or not isinstance(
                        content.get('ros__parameters'), dict):
                    raise ValueError(
                        f"section '{key}' of parameter file {path} has no ros__parameters map")
                values.update(content['ros__parameters'])
    return values


def geometry_from_parameters(values: dict) -> Geometry:
    """
    Build a geometry from ROS parameter values, as the nodes declare them.

    :param values: parameter name -> value, with the names and units of
        :data:`GEOMETRY_PARAMETERS` (flat joint lists in metres, home orientation in degrees);
        a missing optional one takes its default. A pivot point is the tool frame's origin
        (:func:`frames_from_parameters`), not part of the geometry.
    :raises ValueError: naming the parameter, if a value is missing or not allowed.
    """
    merged = defaults(GEOMETRY_PARAMETERS)
    merged.update({key: value for key, value in values.items() if key in merged})
    check_values(GEOMETRY_PARAMETERS, merged)
    home_pose = np.concatenate([
        np.asarray(merged['home_position'], dtype=float),
        np.radians(np.asarray(merged['home_orientation_deg'], dtype=float))])
    return Geometry(
        base_joints=np.reshape(np.asarray(merged['base_joints'], dtype=float), (6, 3)),
        platform_joints=np.reshape(np.asarray(merged['platform_joints'], dtype=float), (6, 3)),
        home_pose=home_pose,
        leg_length_min=float(merged['leg_length_min']),
        leg_length_max=float(merged['leg_length_max']),
        base_joint_max_angle=math.radians(merged['base_joint_max_angle_deg']),
        platform_joint_max_angle=math.radians(merged['platform_joint_max_angle_deg']),
        max_jacobian_condition=float(merged['max_jacobian_condition']))


def frames_from_parameters(values: dict) -> FrameTree:
    """
    Build the frame tree from ROS parameter values, as the nodes declare them.

    :param values: parameter name -> value, with the names and units of
        :data:`FRAME_PARAMETERS` (positions in metres, orientations in degrees); a missing one
        takes its default.
    :raises ValueError: naming the parameter, if a value is not allowed, or for frame names
        that repeat.
    """
    merged = defaults(FRAME_PARAMETERS)
    merged.update({key: value for key, value in values.items() if key in merged})
    check_values(FRAME_PARAMETERS, merged)
    return FrameTree(
        base_frame=merged['base_frame'], platform_frame=merged['platform_frame'],
        user_frame=merged['user_frame'],
        user_pose=_frame_pose(merged['user_frame_position'],
                              merged['user_frame_orientation_deg']),
        tool_frame=merged['tool_frame'],
        tool_pose=_frame_pose(merged['tool_frame_position'],
                              merged['tool_frame_orientation_deg']))


def frame_parameters_reason(values: dict) -> str:
    """
    Say why frame parameter values cannot make a frame tree, or return ``''``.

    For a run-time change, where a rule between parameters (frame names must differ) decides.
    """
    try:
        frames_from_parameters(values)
    except ValueError as error:
        return str(error)
    return ''


def _frame_pose(position, orientation_deg) -> Transform:
    """Return the transform of a position (metres) and Euler angles (degrees)."""
    return Transform.from_pose(np.concatenate([
        np.asarray(position, dtype=float), np.radians(np.asarray(orientation_deg, dtype=float))]))


def load_geometry(paths, node_name: Optional[str] = None) -> Geometry:
    """
    Read a geometry from ROS 2 parameter files, the same ones the nodes are given.

    :param paths: a YAML file with the geometry under ``/**:`` (or under ``node_name``), or a
        list of them applied in order, as repeated ``--params-file`` options are (for example
        ``['config/paper_platform.yaml', 'config/example_limits.yaml']``).
    :param node_name: also apply this node's sections, as that node would see them.
    :raises ValueError: naming the file, if a file cannot be read or its geometry is not
        allowed.

    >>> from stewart_kinematics import load_geometry
    >>> geometry = load_geometry(['config/paper_platform.yaml', 'config/example_limits.yaml'])
    >>> geometry.leg_length_min, geometry.leg_length_max
    (0.65, 0.9)
    """
    if isinstance(paths, (str, bytes)) or not hasattr(paths, '__iter__'):
        paths = [paths]
    values = {}
    for path in paths:
        values.update(read_parameter_file(path, node_name))
    try:
        check_known_names(values, 'the file')
        return geometry_from_parameters(values)
    except ValueError as error:
        raise ValueError(f'{", ".join(map(str, paths))}: {error}') from error


def markdown_table(specs) -> str:
    """
    Render the README's table of ``specs``: name, type, default, meaning, allowed values.

    A test compares the README with this, so the documentation cannot drift from the code.
    """
    def shown(value):
        if value is None:
            return 'required'
        if isinstance(value, float) and math.isinf(value):
            return '`.inf`'
        if isinstance(value, str):
            return f"`'{value}'`"
        if isinstance(value, bool):
            return f'`{str(value).lower()}`'
        return f'`{value}`'

    lines = ['| Parameter | Type | Default | Meaning | Allowed | Run-time change |',
             '| --- | --- | --- | --- | --- | --- |']
    for spec in specs:
        lines.append(
            f'| `{spec.name}` | {spec.value_type} | {shown(spec.default)} | {spec.description} | '
            f'{spec.constraints or "any"} | {"no (read-only)" if spec.read_only else "yes"} |')
    return '\n'.join(lines)
