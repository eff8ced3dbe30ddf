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
Every ROS parameter of the package, declared once, grouped by what it configures.

The nodes turn these specs into ROS declarations (:mod:`stewart_kinematics.ros.ros_parameters`),
the core reads the same names from YAML (:mod:`stewart_kinematics.parameters.files`), and the
documentation's parameter tables are generated from them
(:mod:`stewart_kinematics.parameters.tables`). Nothing here imports ROS.
"""

import difflib
import math

from stewart_kinematics.limits.kinds import limit_parameters
from stewart_kinematics.model.validators import InertiaTensor, IPv4Address, LegSelection
from stewart_kinematics.parameters.spec import (
    BOOL,
    DistinctNames,
    DOUBLE,
    DOUBLE_ARRAY,
    Finite,
    FixedLength,
    FrameName,
    InRange,
    INTEGER,
    NonEmpty,
    OneOf,
    ParameterSpec,
    STRING,
    STRING_ARRAY,
    ZeroOrInRange,
)


_JOINT_AND_HOME_SPECS = (
    ParameterSpec(
        'base_joints', DOUBLE_ARRAY,
        'Base joint centres b_1..b_6 in the base frame, metres, flattened as '
        'x1, y1, z1, ..., x6, y6, z6; two legs given the same coordinates share one joint '
        '(6-3 and 3-3 platforms)',
        read_only=True, validators=(FixedLength(18), Finite()),
        note='not collinear; a joint shared by 2 legs at most'),
    ParameterSpec(
        'platform_joints', DOUBLE_ARRAY,
        'Platform joint centres p_1..p_6 in the platform frame, metres, flattened as '
        'x1, y1, z1, ..., x6, y6, z6; two legs given the same coordinates share one joint '
        '(6-3 and 3-3 platforms)',
        read_only=True, validators=(FixedLength(18), Finite()),
        note='not collinear; a joint shared by 2 legs at most'),
    ParameterSpec(
        'home_position', DOUBLE_ARRAY,
        'Home (neutral) position X, Y, Z of the platform frame in the base frame, metres; '
        'leg extensions are measured from it and forward kinematics starts from it',
        read_only=True, validators=(FixedLength(3), Finite())),
    ParameterSpec(
        'home_orientation_deg', DOUBLE_ARRAY,
        'Home orientation alpha, beta, gamma (R = Rz(gamma) Ry(beta) Rx(alpha)), degrees',
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-180.0, 180.0))),
)


def limit_specs() -> tuple:
    """
    Return the specs of every limit kind's parameters, in the order of the kinds' list.

    Each comes from its kind's :class:`~stewart_kinematics.limits.kind.LimitParameter` (name,
    unit, default, description, bounds): a kind added to
    :data:`~stewart_kinematics.limits.kinds.LIMIT_KINDS` gets its parameters here.
    """
    return tuple(
        ParameterSpec(parameter.name, DOUBLE, parameter.description, default=parameter.default,
                      read_only=True, validators=parameter.validators, note=parameter.note)
        for parameter in limit_parameters())


#: Largest mass of a body, kg: a value beyond it is a typing error, and keeps the forces finite.
MASS_MAX = 1e9
#: Largest distance of a centre of mass from its frame's origin (or its joint), metres.
CENTER_OF_MASS_MAX = 1000.0
#: Largest magnitude of each component of gravity, m/s^2.
GRAVITY_MAX = 1000.0
#: The lowest frequency of a cueing filter, rad/s (a period of 1.7 h, longer than any drive):
#: below it the filter's polynomial loses its lowest terms (1e-300 cubed is 0).
MIN_FILTER_FREQUENCY = 1e-3

_MASS_RULES = (Finite(), InRange(0.0, MASS_MAX))
_CENTER_RULES = (FixedLength(3), Finite(), InRange(-CENTER_OF_MASS_MAX, CENTER_OF_MASS_MAX))
_INERTIA_RULES = (FixedLength(6), Finite(), InertiaTensor())
_MASSLESS_NOTE = '0 when the mass is 0'


def _rigid_body_specs(body: str, words: str, read_only: bool) -> tuple:
    """Return the mass, centre of mass and inertia specs of the platform or the payload."""
    return (
        ParameterSpec(
            f'{body}_mass', DOUBLE, f'Mass of {words}, kg; 0 for none',
            default=0.0, read_only=read_only, validators=_MASS_RULES),
        ParameterSpec(
            f'{body}_center_of_mass', DOUBLE_ARRAY,
            f'Centre of mass of {words}, X, Y, Z in the platform frame, metres',
            default=[0.0, 0.0, 0.0], read_only=read_only, validators=_CENTER_RULES),
        ParameterSpec(
            f'{body}_inertia', DOUBLE_ARRAY,
            f'Inertia tensor of {words} about its centre of mass, axes of the platform frame, '
            "kg m^2, as Ixx, Iyy, Izz, Ixy, Ixz, Iyz (the entries of the tensor, as URDF's "
            '<inertia> writes them)',
            default=[0.0] * 6, read_only=read_only, validators=_INERTIA_RULES,
            note=_MASSLESS_NOTE),
    )


def _leg_body_specs(body: str, words: str, joint: str) -> tuple:
    """Return the mass, centre of mass and inertia specs of one body of every leg."""
    return (
        ParameterSpec(
            f'leg_{body}_mass', DOUBLE, f'Mass of the {words} of each leg, kg; 0 for none',
            default=0.0, read_only=True, validators=_MASS_RULES),
        ParameterSpec(
            f'leg_{body}_center_of_mass', DOUBLE,
            f'Distance of the centre of mass of the {words} of each leg from the {joint} '
            'joint along the leg axis, metres (negative: beyond the joint)',
            default=0.0, read_only=True,
            validators=(Finite(), InRange(-CENTER_OF_MASS_MAX, CENTER_OF_MASS_MAX))),
        ParameterSpec(
            f'leg_{body}_inertia', DOUBLE,
            f'Moment of inertia of the {words} of each leg about a transverse axis through its '
            'centre of mass, kg m^2 (none about the leg axis)',
            default=0.0, read_only=True, validators=(Finite(), InRange(0.0, 1e150)),
            note=_MASSLESS_NOTE),
    )


#: The masses the actuators carry, and gravity (:class:`stewart_kinematics.MassProperties`);
#: every mass 0 by default, and with every mass 0 the leg forces are 0. The payload's may
#: change at run time: payloads change.
MASS_SPECS = (
    _rigid_body_specs('platform', 'the platform', read_only=True)
    + _rigid_body_specs('payload', 'the payload fixed to the platform', read_only=False)
    + _leg_body_specs('lower', 'lower body (cylinder)', 'base')
    + _leg_body_specs('upper', 'upper body (rod)', 'platform')
    + (ParameterSpec(
        'gravity', DOUBLE_ARRAY,
        'Gravity X, Y, Z in the base frame, m/s^2',
        default=[0.0, 0.0, -9.80665], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-GRAVITY_MAX, GRAVITY_MAX))),))

#: The geometry's parameters: its joints and home pose, every limit kind's, then the masses.
GEOMETRY_PARAMETERS = _JOINT_AND_HOME_SPECS + limit_specs() + MASS_SPECS


ACTUATOR_PARAMETERS = (
    ParameterSpec(
        'joint_names', STRING_ARRAY,
        'Names of the six leg actuators as prismatic joints, leg 1..6, on every JointState and '
        'JointTrajectory the package publishes or reads',
        default=['leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5', 'leg_6'], read_only=True,
        validators=(FixedLength(6), DistinctNames())),
    ParameterSpec(
        'actuator_offsets', DOUBLE_ARRAY,
        "Each actuator's zero as a leg length, metres, leg 1..6: an actuator position is its "
        'leg length minus its offset',
        default=[0.0, 0.0, 0.0, 0.0, 0.0, 0.0], read_only=True,
        validators=(FixedLength(6), Finite())),
)

SOLVER_PARAMETERS = (
    ParameterSpec(
        'tolerance', DOUBLE,
        'Newton-Raphson stops when every leg length of the solution is within this of the '
        'measured one, metres',
        default=1e-12, validators=(Finite(), InRange(0.0, 1e-2, low_inclusive=False))),
    ParameterSpec(
        'max_iterations', INTEGER,
        'Newton-Raphson iterations before a solve is reported as not converged',
        default=50, validators=(InRange(1, 1000),)),
    ParameterSpec(
        'near_singularity_condition', DOUBLE,
        'A solution whose dimensionless Jacobian condition number exceeds this is published '
        'with a WARN status on /diagnostics: it lies near a singularity; leg velocities are '
        'not turned into a twist there (they would be amplified up to this many times)',
        default=100.0, validators=(InRange(1.0, math.inf),)),
    ParameterSpec(
        'pose_tolerance', DOUBLE,
        'Largest accepted bound on the pose error of a solution, metres and radians: near a '
        'singularity leg lengths matched to the tolerance above fix the pose only loosely, and '
        'a solution whose first-order error bound exceeds this is refused; .inf for no check',
        default=1e-9, validators=(InRange(0.0, math.inf, low_inclusive=False),)),
    ParameterSpec(
        'assembly_guard_length_change', DOUBLE,
        'Assembly-mode guard: when no leg changed by more than this since the last solution, '
        'metres, the new solution must lie within the two limits below of the last one',
        default=0.005, validators=(Finite(), InRange(0.0, 1.0))),
    ParameterSpec(
        'assembly_guard_position_change', DOUBLE,
        'Assembly-mode guard: largest move of the platform origin allowed for such a small '
        'change of the lengths, metres',
        default=0.05, validators=(Finite(), InRange(0.0, 10.0, low_inclusive=False))),
    ParameterSpec(
        'assembly_guard_angle_change_deg', DOUBLE,
        'Assembly-mode guard: largest rotation of the platform allowed for such a small '
        'change of the lengths, degrees',
        default=10.0, validators=(Finite(), InRange(0.0, 180.0, low_inclusive=False))),
    ParameterSpec(
        'refuse_ambiguous_start', BOOL,
        'After a start or reset_tracker, refuse to publish while more than one assembly mode '
        'lies within the limits and none within the two assembly-guard changes above of the '
        'last known pose (home, or the reset pose): the lengths alone do not tell which mode '
        'the platform is in. Costs one search for every mode (about 0.1 s) per new set of '
        'lengths until a pose is accepted',
        default=False),
)

#: The assembly-mode margin that fk_node reports (see stewart_kinematics.analysis.assembly_modes).
ASSEMBLY_MODE_PARAMETERS = (
    ParameterSpec(
        'assembly_mode_margin_period', DOUBLE,
        'Time between two computations of the assembly-mode margin of the last solution '
        '(the distance to the nearest other real mode within the limits, on /diagnostics), '
        'seconds; each runs in a worker process, and only when the lengths changed; 0.0 turns '
        'the margin off',
        default=1.0, read_only=True, validators=(Finite(), InRange(0.0, 3600.0))),
    ParameterSpec(
        'assembly_mode_margin_warning', DOUBLE,
        'A margin below this gives a WARN status and a log line: another real assembly mode '
        'within the limits lies this close to the estimated pose, metres, as '
        'sqrt(position^2 + (rho angle)^2) with rho the RMS radius of the platform joints; '
        '0.0 for no warning',
        default=0.05, validators=(Finite(), InRange(0.0, 100.0))),
)


#: Largest coordinate of a user or tool frame's origin, metres: a frame further away loses
#: the platform's pose in the rounding of its offset (and at 1e308 m the sum overflows).
FRAME_OFFSET_MAX = 1000.0

FRAME_PARAMETERS = (
    ParameterSpec(
        'base_frame', STRING,
        'Name of the base frame: the parent of the platform on /tf, and the frame of stamped '
        'poses; a stamped target in a frame other than this one or user_frame is refused',
        default='stewart_base', read_only=True, validators=(NonEmpty(), FrameName())),
    ParameterSpec(
        'platform_frame', STRING,
        'Name of the platform frame (the frame the platform joints are given in) on /tf',
        default='stewart_platform', read_only=True, validators=(NonEmpty(), FrameName())),
    ParameterSpec(
        'user_frame', STRING,
        "Name of a user frame fixed to the base (a work piece's frame), on /tf_static, in "
        "which stamped poses may be given; '' for none",
        default='', read_only=True, validators=(FrameName(),)),
    ParameterSpec(
        'user_frame_position', DOUBLE_ARRAY,
        'Origin of user_frame in the base frame, X, Y, Z, metres',
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-FRAME_OFFSET_MAX, FRAME_OFFSET_MAX))),
    ParameterSpec(
        'user_frame_orientation_deg', DOUBLE_ARRAY,
        'Orientation of user_frame in the base frame, alpha, beta, gamma '
        '(R = Rz(gamma) Ry(beta) Rx(alpha)), degrees',
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-180.0, 180.0))),
    ParameterSpec(
        'tool_frame', STRING,
        "Name of the tool frame fixed to the platform, on /tf_static; '' leaves it unnamed "
        '(its pose below still applies)',
        default='', validators=(FrameName(),)),
    ParameterSpec(
        'tool_frame_position', DOUBLE_ARRAY,
        'Origin of the tool frame in the platform frame, X, Y, Z, metres: the pivot point. '
        'Commanded and estimated poses are those of the tool frame, so a pure rotation turns '
        'the platform about this point',
        default=[0.0, 0.0, 0.0],
        validators=(FixedLength(3), Finite(), InRange(-FRAME_OFFSET_MAX, FRAME_OFFSET_MAX))),
    ParameterSpec(
        'tool_frame_orientation_deg', DOUBLE_ARRAY,
        'Orientation of the tool frame in the platform frame, alpha, beta, gamma '
        '(R = Rz(gamma) Ry(beta) Rx(alpha)), degrees',
        default=[0.0, 0.0, 0.0], validators=(FixedLength(3), Finite(), InRange(-180.0, 180.0))),
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
        default='', read_only=True, validators=(FrameName(),),
        note='base_frame or user_frame'),
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
        default=30.0, read_only=True, validators=(Finite(), InRange(0.0, 1000.0))),
)

WORKSPACE_PARAMETERS = (
    ParameterSpec(
        'workspace_resolution', DOUBLE,
        'Grid step of the constant-orientation workspace (at the home orientation) that '
        'workspace_markers shows, metres; computed in a worker process once the topic has a '
        'subscriber, and again when this changes; 0.0 turns the markers off',
        default=0.01, validators=(Finite(), ZeroOrInRange(0.002, 0.1))),
    ParameterSpec(
        'travel_range_rate', DOUBLE,
        'Rate of travel_ranges, the range left along each axis from the last accepted pose, '
        'hertz; computed in a worker process while the topic has a subscriber and the pose '
        'has moved; 0.0 turns them off',
        default=1.0, read_only=True, validators=(Finite(), InRange(0.0, 10.0))),
)

QUEUE_PARAMETERS = (
    ParameterSpec(
        'queue_depth', INTEGER,
        'Depth of the reliable, keep-last queues of every subscription and publisher, messages',
        default=10, read_only=True, validators=(InRange(1, 10000),)),
)

LIFECYCLE_PARAMETERS = (
    ParameterSpec(
        'managed', BOOL,
        'Run as a managed (lifecycle) node: start unconfigured, publish nothing and act on no '
        'command until configured and activated through ~/change_state (doc/lifecycle.md); '
        'false: configure and activate at start-up, as ros2 run does',
        default=False, read_only=True),
)

RAMP_PARAMETERS = (
    ParameterSpec(
        'position_start', DOUBLE_ARRAY, 'First row of the ramp: X, Y, Z in metres',
        default=[0.0, 0.0, 0.4325], read_only=True, validators=(FixedLength(3), Finite())),
    ParameterSpec(
        'position_step', DOUBLE_ARRAY, 'Change of X, Y, Z from one row to the next, metres',
        default=[0.01, 0.015, 0.01], read_only=True, validators=(FixedLength(3), Finite()),
        note='same number of steps on every axis'),
    ParameterSpec(
        'position_end', DOUBLE_ARRAY, 'Last row of the ramp: X, Y, Z in metres',
        default=[0.1, 0.15, 0.5325], read_only=True, validators=(FixedLength(3), Finite())),
    ParameterSpec(
        'orientation_start_deg', DOUBLE_ARRAY,
        'First row of the ramp: alpha, beta, gamma in degrees',
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-180.0, 180.0))),
    ParameterSpec(
        'orientation_step_deg', DOUBLE_ARRAY,
        'Change of alpha, beta, gamma from one row to the next, degrees',
        default=[1.5, -1.5, 2.0], read_only=True, validators=(FixedLength(3), Finite()),
        note='same number of steps on every axis'),
    ParameterSpec(
        'orientation_end_deg', DOUBLE_ARRAY,
        'Last row of the ramp: alpha, beta, gamma in degrees',
        default=[15.0, -15.0, 20.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-180.0, 180.0))),
    ParameterSpec(
        'mode', STRING,
        "'table': publish the table's rows, one every row_period; 'interpolate': sample the "
        "ramp in time, like the paper's clock-driven lookup tables, at publish_rate over "
        "duration; 'off': no ramp, only the trajectories received on pose_trajectory and "
        'pose_path',
        default='table', read_only=True, validators=(OneOf('table', 'interpolate', 'off'),)),
    ParameterSpec(
        'row_period', DOUBLE, "Time between two rows in 'table' mode, seconds",
        default=1.0, read_only=True, validators=(Finite(), InRange(1e-3, 3600.0))),
    ParameterSpec(
        'publish_rate', DOUBLE,
        "Rate of the samples in 'interpolate' mode; for a received trajectory, rate of the "
        'points of leg_trajectory (every waypoint is a point too) and of the poses played on '
        'target_pose, hertz',
        default=50.0, read_only=True, validators=(Finite(), InRange(1e-3, 1000.0))),
    ParameterSpec(
        'duration', DOUBLE,
        "Time from the first row to the last in 'interpolate' mode, seconds",
        default=10.0, read_only=True, validators=(Finite(), InRange(1e-3, 86400.0))),
    ParameterSpec(
        'loop', BOOL, 'Start again from the first row after the last one',
        default=False, read_only=True),
    ParameterSpec(
        'start_delay', DOUBLE,
        'Time between min_subscribers being matched and the first pose, seconds: the '
        'subscribers match this publisher a moment after it matches them, and a pose sent '
        'before that would be lost',
        default=0.5, read_only=True, validators=(Finite(), InRange(0.0, 3600.0))),
    ParameterSpec(
        'min_subscribers', INTEGER,
        'Wait until this many subscriptions are matched on target_pose before playing, so '
        'that no pose is published to nobody',
        default=0, read_only=True, validators=(InRange(0, 1000),)),
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
        default=1.0, validators=(Finite(), InRange(0.0, 1.0, low_inclusive=False))),
    ParameterSpec(
        'validation_rate', DOUBLE,
        'Samples per second at which a whole trajectory is checked against every limit before '
        'anything is published, hertz',
        default=1000.0, validators=(Finite(), InRange(1.0, 100000.0))),
    ParameterSpec(
        'play', BOOL,
        'Also play an accepted trajectory on target_pose at publish_rate, for the ik_node chain',
        default=False),
)

#: trajectory_node: the follow_joint_trajectory action (control_msgs/action/FollowJointTrajectory);
#: a change applies from the next goal.
ACTION_PARAMETERS = (
    ParameterSpec(
        'action_execution', STRING,
        "How an accepted goal is sent: 'leg_trajectory' (its leg trajectory on leg_trajectory, "
        "for joint_trajectory_controller) or 'stream' (its leg commands on joint_commands at "
        'publish_rate, as ik_node sends them)',
        default='leg_trajectory', validators=(OneOf('leg_trajectory', 'stream'),)),
    ParameterSpec(
        'action_feedback_rate', DOUBLE,
        'Feedback messages per second of a running goal (desired, actual and error), hertz',
        default=10.0, validators=(Finite(), InRange(0.1, 1000.0))),
    ParameterSpec(
        'action_cartesian_joints', STRING_ARRAY,
        "Names of the six Cartesian joints a goal may give instead of the legs: the tool frame's "
        'x, y, z (metres) and roll, pitch, yaw (radians, R = Rz(yaw) Ry(pitch) Rx(roll) about '
        'the base axes), in the header frame (base_frame or user_frame)',
        default=['x', 'y', 'z', 'roll', 'pitch', 'yaw'],
        validators=(FixedLength(6), DistinctNames())),
    ParameterSpec(
        'action_leg_path_tolerance', DOUBLE,
        "Default path tolerance of each leg joint's position while a goal runs, metres; 0.0: "
        'none (a goal may set its own)',
        default=0.02, validators=(Finite(), InRange(0.0, 1.0))),
    ParameterSpec(
        'action_leg_goal_tolerance', DOUBLE,
        "Default goal tolerance of each leg joint's position at the end, metres; 0.0: none",
        default=0.002, validators=(Finite(), InRange(0.0, 1.0))),
    ParameterSpec(
        'action_stopped_velocity_tolerance', DOUBLE,
        "Default goal tolerance of each leg joint's velocity at the end (when joint_states "
        "carries velocities), m/s, as joint_trajectory_controller's "
        'stopped_velocity_tolerance; 0.0: none',
        default=0.01, validators=(Finite(), InRange(0.0, 10.0))),
    ParameterSpec(
        'action_position_path_tolerance', DOUBLE,
        'Default path tolerance of the Cartesian joints x, y, z while a goal runs, metres; '
        '0.0: none',
        default=0.02, validators=(Finite(), InRange(0.0, 10.0))),
    ParameterSpec(
        'action_orientation_path_tolerance', DOUBLE,
        'Default path tolerance of the Cartesian joints roll, pitch, yaw while a goal runs, '
        'radians; 0.0: none',
        default=0.05, validators=(Finite(), InRange(0.0, 3.2))),
    ParameterSpec(
        'action_position_goal_tolerance', DOUBLE,
        'Default goal tolerance of x, y, z at the end, metres; 0.0: none',
        default=0.002, validators=(Finite(), InRange(0.0, 10.0))),
    ParameterSpec(
        'action_orientation_goal_tolerance', DOUBLE,
        'Default goal tolerance of roll, pitch, yaw at the end, radians; 0.0: none',
        default=0.005, validators=(Finite(), InRange(0.0, 3.2))),
    ParameterSpec(
        'action_goal_time_tolerance', DOUBLE,
        "Default time after a goal's end by which the measured state must be within the goal "
        'tolerance, seconds; 0.0: checked once, at the end time',
        default=1.0, validators=(Finite(), InRange(0.0, 3600.0))),
    ParameterSpec(
        'action_start_tolerance', DOUBLE,
        'How far a first point at time 0 may be from the current state (metres, or radians '
        'for roll, pitch, yaw): it is taken as the current state; farther, the goal is refused '
        '(it would jump)',
        default=0.01, validators=(Finite(), InRange(0.0, 1.0))),
)

#: ik_node: commanded rates: commands streamed through the jerk-limited filter, and twists.
STREAMING_PARAMETERS = (
    ParameterSpec(
        'command_rate', DOUBLE,
        'Rate of joint_commands, hertz: each command moves from the last toward the latest '
        'accepted target within leg_velocity_max, leg_acceleration_max and leg_jerk_max '
        '(ruckig; the first two must be set); 0.0: one command per accepted pose, unfiltered',
        default=0.0, read_only=True, validators=(Finite(), InRange(0.0, 10000.0))),
    ParameterSpec(
        'twist_over_limit', STRING,
        'What ik_node does with a target_twist whose leg velocities exceed leg_velocity_max: '
        "'refuse' it (nothing published, code too_fast), or 'scale' the whole twist down "
        'uniformly until the fastest leg is at the limit (published, with a twist_scaled '
        'warning); never published beyond the limit',
        default='refuse', read_only=True, validators=(OneOf('refuse', 'scale'),)),
)


#: motion_cueing_node: the classical washout, its limits and its input checks; the defaults are
#: the literature's (config/motion_cueing.yaml tunes them for the paper's platform), and
#: stewart_kinematics.cueing.CueingSettings takes its defaults and bounds from these specs.
MOTION_CUEING_PARAMETERS = (
    ParameterSpec(
        'translation_scale', DOUBLE_ARRAY,
        'Gain on the specific force of the translational channel, x y z (vehicle frame: x '
        'forward, y left, z up); changeable at run time: ramped over gain_ramp_time, refused '
        'where its worst-case cue leaves the travel (doc/motion_cueing.md)',
        default=[0.5, 0.5, 0.5], read_only=False,
        validators=(FixedLength(3), Finite(), InRange(0.0, 10.0))),
    ParameterSpec(
        'translation_input_limit', DOUBLE,
        "Soft limit of the translational channel's input, m/s^2 per axis: a = L tanh(a_in / L) "
        '(nonlinear scaling); .inf for none',
        default=math.inf, read_only=True,
        validators=(InRange(0.0, math.inf, low_inclusive=False),)),
    ParameterSpec(
        'translation_order', INTEGER,
        'Order of the translational high-pass: 3 returns the platform to neutral after a '
        'sustained acceleration, 2 keeps a displacement while it lasts',
        default=3, read_only=True, validators=(OneOf(2, 3),)),
    ParameterSpec(
        'translation_frequency', DOUBLE_ARRAY,
        'Natural frequency of the second-order translational high-pass, rad/s, x y z',
        default=[2.5, 2.5, 4.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(MIN_FILTER_FREQUENCY, 100.0))),
    ParameterSpec(
        'translation_damping', DOUBLE_ARRAY,
        'Damping ratio of the translational high-pass, x y z; >= 1 never reverses through '
        'neutral after a step',
        default=[1.0, 1.0, 1.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(0.0, 10.0, low_inclusive=False))),
    ParameterSpec(
        'translation_break_frequency', DOUBLE_ARRAY,
        'Frequency of the first-order part of the third-order translational high-pass, rad/s, '
        'x y z',
        default=[0.25, 0.25, 0.25], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(MIN_FILTER_FREQUENCY, 100.0))),
    ParameterSpec(
        'tilt_scale', DOUBLE_ARRAY,
        'Gain on the specific force rendered by tilt coordination, x (pitch) and y (roll); '
        'changeable at run time as translation_scale',
        default=[0.5, 0.5], read_only=False,
        validators=(FixedLength(2), Finite(), InRange(0.0, 10.0))),
    ParameterSpec(
        'tilt_complementary', BOOL,
        'Use 1 - (the translational high-pass) as the tilt low-pass, per axis, instead of the '
        'classical low-pass of tilt_order',
        default=False, read_only=True),
    ParameterSpec(
        'tilt_order', INTEGER, 'Order of the tilt low-pass',
        default=2, read_only=True, validators=(OneOf(1, 2),)),
    ParameterSpec(
        'tilt_frequency', DOUBLE, 'Cut-off of the tilt low-pass, rad/s',
        default=5.0, read_only=True,
        validators=(Finite(), InRange(MIN_FILTER_FREQUENCY, 100.0))),
    ParameterSpec(
        'tilt_damping', DOUBLE, 'Damping ratio of the tilt low-pass (order 2)',
        default=1.0, read_only=True,
        validators=(Finite(), InRange(0.0, 10.0, low_inclusive=False))),
    ParameterSpec(
        'tilt_rate_max_deg', DOUBLE,
        'Largest tilt rate of tilt coordination, degrees per second (the threshold below which '
        'a rotation is not perceived)',
        default=3.0, read_only=True,
        validators=(Finite(), InRange(0.0, 90.0, low_inclusive=False))),
    ParameterSpec(
        'tilt_acceleration_max_deg', DOUBLE,
        'Largest tilt acceleration of tilt coordination, degrees per second squared (a smooth '
        'onset of the tilt)',
        default=10.0, read_only=True,
        validators=(Finite(), InRange(0.0, 1000.0, low_inclusive=False))),
    ParameterSpec(
        'tilt_max_deg', DOUBLE, 'Largest tilt angle of tilt coordination, degrees',
        default=15.0, read_only=True,
        validators=(Finite(), InRange(0.0, 45.0, low_inclusive=False))),
    ParameterSpec(
        'rotation_scale', DOUBLE_ARRAY,
        'Gain on the angular velocity, roll pitch yaw; changeable at run time as '
        'translation_scale',
        default=[0.5, 0.5, 0.5], read_only=False,
        validators=(FixedLength(3), Finite(), InRange(0.0, 10.0))),
    ParameterSpec(
        'rotation_order', INTEGER,
        'Order of the rotational high-pass: 2 returns the angle to neutral after a sustained '
        'rate',
        default=2, read_only=True, validators=(OneOf(1, 2),)),
    ParameterSpec(
        'rotation_frequency', DOUBLE_ARRAY,
        'Natural frequency of the rotational high-pass, rad/s, roll pitch yaw',
        default=[1.0, 1.0, 1.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(MIN_FILTER_FREQUENCY, 100.0))),
    ParameterSpec(
        'rotation_damping', DOUBLE_ARRAY,
        'Damping ratio of the rotational high-pass, roll pitch yaw',
        default=[1.0, 1.0, 1.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(0.0, 10.0, low_inclusive=False))),
    ParameterSpec(
        'attitude_aware_specific_force', BOOL,
        "Turn the vehicle's specific force into the simulator's frame through the platform's "
        "cue attitude before the translational high-pass (Reid and Nahon's L_IS): a "
        'coordinated turn rolled by the rotational channel asks for the sideways acceleration '
        'that offsets the gravity the roll shows; false: the force as it comes',
        default=False, read_only=True),
    ParameterSpec(
        'head_position', DOUBLE_ARRAY,
        "The cueing reference point (the driver's head) in the platform frame, metres: the "
        "cue's rotations turn about it, and the perceived specific force is computed there",
        default=[0.0, 0.0, 0.5], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-10.0, 10.0))),
    ParameterSpec(
        'follower_frequency', DOUBLE,
        'Bandwidth of the follower that brings the platform back onto the cue after the leg '
        'velocity or acceleration limits held it back, rad/s',
        default=10.0, read_only=True,
        validators=(Finite(), InRange(0.0, 1000.0, low_inclusive=False))),
    ParameterSpec(
        'follower_weights', DOUBLE_ARRAY,
        "Weights of the follower's least-squares step where the legs cannot follow the cue: "
        'the squared miss of the platform twist along x, y, z (per m/s) and roll, pitch, yaw '
        '(per rad/s) costs its weight; a larger weight keeps that axis closer to the cue '
        '(only their ratios matter); heave weighted 30: limiting at the literature gains then '
        'keeps wrong-way heave on the mixed drive within 10 % of the unlimited cue',
        default=[1.0, 1.0, 30.0, 1.0, 1.0, 1.0], read_only=True,
        validators=(FixedLength(6), Finite(), InRange(1e-3, 1e3))),
    ParameterSpec(
        'workspace_recovery_rate', DOUBLE,
        'Fastest rise of the workspace scale (the share of the cue kept inside the limits) '
        'back toward 1, per second',
        default=0.5, read_only=True,
        validators=(Finite(), InRange(0.0, 1000.0, low_inclusive=False))),
    ParameterSpec(
        'leg_length_margin', DOUBLE,
        'The cue keeps this far inside each end of the stroke, metres (raised to the braking '
        'distance leg_velocity_max^2 / (2 leg_acceleration_max) when that is longer)',
        default=0.01, read_only=True, validators=(Finite(), InRange(0.0, 1.0))),
    ParameterSpec(
        'joint_angle_margin_deg', DOUBLE,
        'The cue keeps this far inside each joint cone, degrees',
        default=2.0, read_only=True, validators=(Finite(), InRange(0.0, 45.0))),
    ParameterSpec(
        'condition_margin', DOUBLE,
        'The cue keeps the Jacobian condition number below this share of '
        'max_jacobian_condition',
        default=0.9, read_only=True,
        validators=(Finite(), InRange(0.0, 1.0, low_inclusive=False))),
    ParameterSpec(
        'max_input_gap', DOUBLE,
        'A longer time between two vehicle_imu stamps counts as this long (the washout pauses, '
        'with an input_gap warning), seconds',
        default=0.1, read_only=True,
        validators=(Finite(), InRange(0.0, 3600.0, low_inclusive=False))),
    ParameterSpec(
        'max_specific_force', DOUBLE,
        'A larger specific force is refused as absurd (the platform eases to neutral), m/s^2',
        default=100.0, read_only=True,
        validators=(Finite(), InRange(0.0, 1e4, low_inclusive=False))),
    ParameterSpec(
        'max_angular_velocity', DOUBLE,
        'A larger angular velocity is refused as absurd (the platform eases to neutral), rad/s',
        default=20.0, read_only=True,
        validators=(Finite(), InRange(0.0, 1e4, low_inclusive=False))),
    ParameterSpec(
        'vehicle_frame', STRING,
        "The vehicle's body frame (x forward, y left, z up, REP 103): vehicle_imu in this frame "
        '(or with an empty frame_id) is cued as it is; a sample in a frame neither this nor '
        'imu_frame is refused with the reason',
        default='base_link', read_only=True, validators=(NonEmpty(), FrameName())),
    ParameterSpec(
        'imu_frame', STRING,
        'Another frame vehicle_imu may come in (an IMU mounted turned, or in NED axes), placed '
        "by imu_orientation_rpy_deg; '' for none",
        default='', read_only=True, validators=(FrameName(),)),
    ParameterSpec(
        'imu_orientation_rpy_deg', DOUBLE_ARRAY,
        'Orientation of imu_frame in vehicle_frame: roll, pitch, yaw about the fixed x, y, z '
        'axes (R = Rz Ry Rx), degrees; [180.0, 0.0, 0.0] for an IMU in NED axes (x forward, y '
        'right, z down)',
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-360.0, 360.0))),
    ParameterSpec(
        'input_timeout', DOUBLE,
        'When no vehicle_imu message came for this long, the platform eases to neutral as if '
        'the vehicle were at rest, seconds (node clock); 0.0 turns this off',
        default=0.5, read_only=True, validators=(Finite(), InRange(0.0, 3600.0))),
    ParameterSpec(
        'cueing_method', STRING,
        "How the vehicle's motion becomes a cue: 'classical' (the washout filters) or 'mpc' "
        '(model-predictive: translation and tilt traded over a horizon against the perceived '
        'specific force, within the legs; doc/motion_cueing_mpc.md)',
        default='classical', read_only=True, validators=(OneOf('classical', 'mpc'),)),
    ParameterSpec(
        'mpc_horizon', INTEGER, 'Steps of the MPC horizon (cueing_method mpc)',
        default=10, read_only=True, validators=(InRange(2, 100),)),
    ParameterSpec(
        'mpc_step', DOUBLE,
        'Length of one MPC step, seconds (the horizon is mpc_horizon times this)',
        default=0.2, read_only=True, validators=(Finite(), InRange(0.005, 1.0))),
    ParameterSpec(
        'mpc_force_scale', DOUBLE_ARRAY,
        "Share of the vehicle's perceived specific force the MPC aims at, x y z",
        default=[0.3, 0.3, 0.3], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(0.0, 10.0))),
    ParameterSpec(
        'mpc_force_weight', DOUBLE_ARRAY,
        'MPC weight on the perceived specific-force error, x y z, per (m/s^2)^2',
        default=[1.0, 1.0, 1.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(0.0, 1e6))),
    ParameterSpec(
        'mpc_rate_weight', DOUBLE,
        'MPC weight on the perceived roll and pitch rate error, per (rad/s)^2',
        default=10.0, read_only=True, validators=(Finite(), InRange(0.0, 1e6))),
    ParameterSpec(
        'mpc_position_weight', DOUBLE_ARRAY,
        "MPC weight on the head's displacement from neutral (the washout), x y z, per m^2",
        default=[0.3, 0.3, 0.3], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(0.0, 1e6))),
    ParameterSpec(
        'mpc_velocity_weight', DOUBLE_ARRAY,
        "MPC weight on the head's velocity, x y z, per (m/s)^2",
        default=[0.1, 0.1, 0.1], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(0.0, 1e6))),
    ParameterSpec(
        'mpc_tilt_weight', DOUBLE, 'MPC weight on the tilt from neutral, per rad^2',
        default=5.0, read_only=True, validators=(Finite(), InRange(0.0, 1e6))),
    ParameterSpec(
        'mpc_tilt_rate_weight', DOUBLE, 'MPC weight on the tilt rate, per (rad/s)^2',
        default=1.0, read_only=True, validators=(Finite(), InRange(0.0, 1e6))),
    ParameterSpec(
        'mpc_input_weight', DOUBLE_ARRAY,
        "MPC weight on its inputs: the head's acceleration per (m/s^2)^2 and the tilt's "
        'acceleration per (rad/s^2)^2; positive (they keep the QP strictly convex)',
        default=[0.01, 0.01], read_only=True,
        validators=(FixedLength(2), Finite(), InRange(0.0, 1e6, low_inclusive=False))),
    ParameterSpec(
        'mpc_reference_time_constant', DOUBLE,
        "The MPC predicts the vehicle's current input held over the horizon, fading with this "
        'time constant, seconds; .inf holds it, 0.0 lets it drop to rest at once',
        default=0.5, read_only=True, validators=(InRange(0.0, math.inf),)),
    ParameterSpec(
        'mpc_limit_share', DOUBLE,
        'Share of the leg velocity and acceleration limits and of tilt_rate_max_deg the MPC '
        'plans with (the rest absorbs its linearisation; the limiter keeps the limits anyway)',
        default=0.8, read_only=True,
        validators=(Finite(), InRange(0.0, 1.0, low_inclusive=False))),
    ParameterSpec(
        'mpc_workspace_share', DOUBLE,
        "The MPC keeps each cue coordinate (the head's x, y, z, roll, pitch) within this share "
        'of how far it reaches alone inside the limits (a box inside the workspace)',
        default=0.5, read_only=True,
        validators=(Finite(), InRange(0.0, 1.0, low_inclusive=False))),
    ParameterSpec(
        'mpc_max_iterations', INTEGER,
        "Iteration limit of the MPC's QP solver; beyond it the cue falls back on the last plan",
        default=1000, read_only=True, validators=(InRange(1, 100000),)),
)


#: motion_cueing_node: what an operator changes at run time (stewart_kinematics.cueing.controls):
#: the intensity and the gains (ramped), the soft start from park and the soft stop to park.
CUEING_CONTROL_PARAMETERS = (
    ParameterSpec(
        'cueing_intensity', DOUBLE,
        'Master intensity of the cue, 0 (no motion: the platform eases to neutral) to 1 (the '
        'gains as set): it multiplies translation_scale, tilt_scale and rotation_scale; a '
        'change is ramped over gain_ramp_time and refused where the cue would leave the travel',
        default=1.0, validators=(Finite(), InRange(0.0, 1.0))),
    ParameterSpec(
        'gain_ramp_time', DOUBLE,
        'Time over which a change of cueing_intensity or of a gain is ramped (smoothstep: no '
        'jump in the gain or its rate), seconds; applies from the next change',
        default=2.0, validators=(Finite(), InRange(0.01, 600.0))),
    ParameterSpec(
        'gain_check_specific_force', DOUBLE,
        'The sustained change of specific force (m/s^2, each axis) a gain change is checked '
        'with: a change whose cue of it would leave the travel (within the cue margins) is '
        'refused',
        default=4.0, read_only=True,
        validators=(Finite(), InRange(0.0, 1000.0, low_inclusive=False))),
    ParameterSpec(
        'gain_check_angular_velocity', DOUBLE,
        'The sustained angular velocity (rad/s, each axis) a rotation_scale change is checked '
        'with, as gain_check_specific_force',
        default=0.5, read_only=True,
        validators=(Finite(), InRange(0.0, 100.0, low_inclusive=False))),
    ParameterSpec(
        'soft_start_time', DOUBLE,
        'The start service moves the platform from park to the neutral cueing pose in this '
        'time (longer when the leg velocity or acceleration limits need), seconds',
        default=3.0, validators=(Finite(), InRange(0.1, 600.0))),
    ParameterSpec(
        'soft_stop_time', DOUBLE,
        'The stop service brakes the platform to rest, then moves it to park in this time '
        '(longer when the leg limits need), seconds',
        default=3.0, validators=(Finite(), InRange(0.1, 600.0))),
    ParameterSpec(
        'park_position', DOUBLE_ARRAY,
        "The park pose's X, Y, Z, metres, base frame, oriented by park_orientation_deg (all 0.0: "
        'as home): where stop takes the '
        'platform and start_parked starts it; all 0.0: the lowest pose straight below home '
        'that keeps the cue margins (leg_length_margin inside the stroke)',
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-1000.0, 1000.0)),
        note='within every limit, or all 0.0'),
    ParameterSpec(
        'park_orientation_deg', DOUBLE_ARRAY,
        "The park pose's orientation in the base frame, alpha, beta, gamma (R = Rz(gamma) "
        'Ry(beta) Rx(alpha)), degrees, for a platform that parks tilted: with park_position, '
        'that pose; with park_position all 0.0, the lowest pose straight below home so '
        "oriented; all 0.0: home's orientation",
        default=[0.0, 0.0, 0.0], read_only=True,
        validators=(FixedLength(3), Finite(), InRange(-180.0, 180.0)),
        note='the park pose within every limit'),
    ParameterSpec(
        'start_parked', BOOL,
        'Start with the platform at park: nothing is cued until the start service; false: '
        'the platform is taken to be at home, cueing at once',
        default=False, read_only=True),
)

#: mock_platform: the simulated legs, what they follow, and the faults a test gives them.
MOCK_PLATFORM_PARAMETERS = (
    ParameterSpec(
        'command_input', STRING,
        "The leg command mock_platform takes: 'all' (it subscribes to the three, and "
        'whichever commands last wins: a set point on leg_lengths or joint_commands drops a '
        'running trajectory, a leg_trajectory takes over from its start time), or only '
        "'leg_lengths', 'joint_commands' or 'leg_trajectory'",
        default='all', read_only=True,
        validators=(OneOf('all', 'leg_lengths', 'joint_commands', 'leg_trajectory'),)),
    ParameterSpec(
        'time_constant', DOUBLE,
        "Time constant of each simulated leg's first-order lag toward its command, seconds "
        '(within the stroke and leg_velocity_max, leg_acceleration_max); 0.0: as fast as the '
        'limits allow',
        default=0.05, validators=(Finite(), InRange(0.0, 100.0))),
    ParameterSpec(
        'joint_state_rate', DOUBLE,
        'Rate at which mock_platform advances the legs and publishes joint_states, hertz '
        "(the node's clock: simulated time too)",
        default=100.0, read_only=True, validators=(Finite(), InRange(1.0, 1000.0))),
    ParameterSpec(
        'max_time_step', DOUBLE,
        'A longer time between two steps of the simulated legs (a clock jump, a process '
        'paused) counts as this long, seconds, with a clock_jump warning; a clock that goes '
        'back moves nothing',
        default=0.1, validators=(Finite(), InRange(1e-4, 10.0))),
    ParameterSpec(
        'initial_leg_lengths', DOUBLE_ARRAY,
        'Where the simulated legs start, at rest, metres, leg 1..6; all 0.0: the leg lengths '
        'of the home pose',
        default=[0.0] * 6, read_only=True,
        validators=(FixedLength(6), Finite(), InRange(0.0, 1000.0)),
        note='within the stroke, or all 0.0'),
    ParameterSpec(
        'stalled_legs', STRING,
        'Legs that stall (a fault for tests): they stop where they are at once, and move '
        'again when no longer named',
        default='', validators=(LegSelection(),), note='names of joint_names'),
    ParameterSpec(
        'position_noise', DOUBLE,
        'Standard deviation of the Gaussian noise added to each published position, metres '
        '(a fault for tests: the simulated legs do not move with it)',
        default=0.0, validators=(Finite(), InRange(0.0, 1.0))),
    ParameterSpec(
        'noise_seed', INTEGER,
        'Seed of the noise; setting it (or position_noise) starts the sequence again',
        default=0, validators=(InRange(0, 1_000_000_000),)),
    ParameterSpec(
        'position_bias', DOUBLE_ARRAY,
        'A fixed offset added to each published position, metres, leg 1..6 (a fault for '
        'tests: a miscalibrated sensor)',
        default=[0.0] * 6, validators=(FixedLength(6), Finite(), InRange(-1.0, 1.0))),
)


#: telemetry_bridge: the UDP stream it listens to and the vehicle_imu it publishes.
TELEMETRY_PARAMETERS = (
    ParameterSpec(
        'telemetry_address', STRING,
        "The address telemetry_bridge's UDP socket binds to: 127.0.0.1 takes packets from "
        'this machine only, 0.0.0.0 from every interface (a simulator on another computer), '
        "or one interface's IPv4 address",
        default='127.0.0.1', read_only=True, validators=(IPv4Address(),)),
    ParameterSpec(
        'telemetry_port', INTEGER,
        'The UDP port telemetry_bridge receives the telemetry packets on',
        default=47800, read_only=True, validators=(InRange(1, 65535),)),
    ParameterSpec(
        'telemetry_frame_id', STRING,
        "The header.frame_id of the vehicle_imu it publishes: motion_cueing_node's "
        'vehicle_frame (the packets are in the vehicle frame, x forward, y left, z up)',
        default='base_link', read_only=True, validators=(NonEmpty(), FrameName())),
    ParameterSpec(
        'telemetry_timeout', DOUBLE,
        'Seconds without a valid packet after which the stream is reported stale on '
        '/diagnostics (nothing is published meanwhile) and the next packet starts a new '
        'stream, whatever its sequence number',
        default=0.5, read_only=True, validators=(Finite(), InRange(0.01, 60.0))),
    ParameterSpec(
        'telemetry_poll_rate', DOUBLE,
        'How often telemetry_bridge empties its socket, hertz: each packet waits at most one '
        'period (the executor never blocks on the socket)',
        default=1000.0, read_only=True, validators=(Finite(), InRange(10.0, 10000.0))),
)


def all_specs():
    """Return every parameter spec of the package, each name once."""
    return (GEOMETRY_PARAMETERS + ACTUATOR_PARAMETERS + SOLVER_PARAMETERS
            + ASSEMBLY_MODE_PARAMETERS + FRAME_PARAMETERS + FK_FRAME_PARAMETERS
            + IK_FRAME_PARAMETERS + MARKER_PARAMETERS + WORKSPACE_PARAMETERS + QUEUE_PARAMETERS
            + LIFECYCLE_PARAMETERS
            + RAMP_PARAMETERS + MOTION_PARAMETERS + ACTION_PARAMETERS + STREAMING_PARAMETERS
            + MOTION_CUEING_PARAMETERS + CUEING_CONTROL_PARAMETERS + MOCK_PLATFORM_PARAMETERS
            + TELEMETRY_PARAMETERS)


#: Parameters that were replaced, and what replaces them: named in the refusal of an old file.
REPLACED_PARAMETERS = {
    'pivot_point': "'tool_frame_position' (the tool frame's origin is the pivot point)",
}


#: Unknown names a refusal lists (the others are counted).
_UNKNOWN_NAMES_SHOWN = 5


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
        # A few names, each shortened: a hostile file may hold thousands, or a huge one.
        shown = [name if len(name) <= 60 else f'{name[:60]}... ({len(name)} characters)'
                 for name in unknown[:_UNKNOWN_NAMES_SHOWN]]
        described = ', '.join(f"'{text}'{hint(name)}" for text, name in zip(shown, unknown))
        if len(unknown) > _UNKNOWN_NAMES_SHOWN:
            described += f' and {len(unknown) - _UNKNOWN_NAMES_SHOWN} more'
        # The known names are too many for one line (with the masses, over 2000 characters).
        raise ValueError(f'unknown parameter(s) {described} in {context}; the {len(known)} '
                         'known parameters are in the tables of doc/nodes.md')


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
