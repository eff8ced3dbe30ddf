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

# GENERATED FILE: do not edit. Written by scripts/generate_settings.py from the parameter specs
# of stewart_kinematics/parameters/declarations.py; after changing a spec, run
#     .venv/bin/python scripts/generate_settings.py
# (test/parameters/test_settings.py fails until this file is what the script writes).

"""
The settings classes, written out from the parameter specs: one per parameter group, one per node.

Generated (see the comment above): each field of a group is one parameter, with its type, its
default and its description, unit and allowed values, so that an IDE and a type checker see
every field; a field without a default is a required parameter. Each node's class has one field
per group it declares. The behaviour (every value checked by its spec's validators when an
object is made, :meth:`~stewart_kinematics.parameters.settings_base.Settings.from_values`,
``replace``, ``as_values``) is that of the base classes in
:mod:`stewart_kinematics.parameters.settings_base`.
"""

from dataclasses import dataclass
import math  # noqa: F401 - the defaults .inf are math.inf
from typing import ClassVar, Tuple

from stewart_kinematics.parameters import declarations
from stewart_kinematics.parameters.settings_base import NodeSettings, Settings
from stewart_kinematics.parameters.spec import ParameterSpec


@dataclass(frozen=True, kw_only=True)
class GeometrySettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.GEOMETRY_PARAMETERS`.

    The platform: joints, home pose, and every limit (stroke, joint cones, singularity margin, leg
    speed); :func:`~stewart_kinematics.parameters.builders.geometry_from_settings` builds the
    Geometry.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.GEOMETRY_PARAMETERS

    base_joints: Tuple[float, ...]
    """
    Base joint centres b_1..b_6 in the base frame, metres, flattened as x1, y1, z1, ..., x6, y6,
    z6; two legs given the same coordinates share one joint (6-3 and 3-3 platforms). Allowed: 18
    finite values; not collinear; a joint shared by 2 legs at most. Required. Read-only at run
    time.
    """

    platform_joints: Tuple[float, ...]
    """
    Platform joint centres p_1..p_6 in the platform frame, metres, flattened as x1, y1, z1, ...,
    x6, y6, z6; two legs given the same coordinates share one joint (6-3 and 3-3 platforms).
    Allowed: 18 finite values; not collinear; a joint shared by 2 legs at most. Required. Read-only
    at run time.
    """

    home_position: Tuple[float, ...]
    """
    Home (neutral) position X, Y, Z of the platform frame in the base frame, metres; leg extensions
    are measured from it and forward kinematics starts from it. Allowed: 3 finite values. Required.
    Read-only at run time.
    """

    home_orientation_deg: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    Home orientation alpha, beta, gamma (R = Rz(gamma) Ry(beta) Rx(alpha)), degrees. Allowed: 3
    values in [-180, 180]. Read-only at run time.
    """

    leg_length_min: float = 0.0
    """
    Shortest allowed leg length (actuator fully retracted), metres; 0.0 for no limit. Allowed:
    finite, >= 0; < leg_length_max. Read-only at run time.
    """

    leg_length_max: float = math.inf
    """
    Longest allowed leg length (actuator fully extended), metres; .inf for no limit. Allowed: > 0;
    .inf allowed; > leg_length_min. Read-only at run time.
    """

    base_joint_max_angle_deg: float = 180.0
    """
    Largest angle between a leg and its home direction at the base joint (joint cone), degrees;
    180.0 for no limit. Allowed: in (0, 180]. Read-only at run time.
    """

    platform_joint_max_angle_deg: float = 180.0
    """
    Largest angle between a leg and its home direction at the platform joint, in the platform frame
    (joint cone), degrees; 180.0 for no limit. Allowed: in (0, 180]. Read-only at run time.
    """

    max_jacobian_condition: float = math.inf
    """
    Singularity margin: largest condition number of the dimensionless Jacobian (1 is ideal, about
    10 at the paper platform's home pose); .inf for no limit. Allowed: >= 1; .inf allowed.
    Read-only at run time.
    """

    leg_radius: float = 0.0
    """
    Radius of each leg, metres: a leg is a capsule of this radius around the segment from its base
    joint to its platform joint, and a pose where two legs come closer than 2 * leg_radius is
    refused (leg_collision); 0.0 for no collision check. Allowed: in [0, 1]. Read-only at run time.
    """

    leg_force_min: float = -math.inf
    """
    Largest pull of a leg, newtons, as a negative force (0: the legs may only push); -.inf for no
    limit. Allowed: <= 0; -.inf allowed. Read-only at run time.
    """

    leg_force_max: float = math.inf
    """
    Largest push of a leg, newtons; .inf for no limit. Allowed: > 0; .inf allowed. Read-only at run
    time.
    """

    leg_velocity_max: float = math.inf
    """
    Largest speed of a leg (actuator), metres per second: timed trajectories are refused or retimed
    to keep within it, streamed commands are limited to it; .inf for no limit. Allowed: > 0; .inf
    allowed. Read-only at run time.
    """

    leg_acceleration_max: float = math.inf
    """
    Largest acceleration of a leg, metres per second squared, as leg_velocity_max; .inf for no
    limit. Allowed: > 0; .inf allowed. Read-only at run time.
    """

    leg_jerk_max: float = math.inf
    """
    Largest jerk of a leg, metres per second cubed, for streamed commands (command_rate); .inf for
    no limit. Allowed: > 0; .inf allowed. Read-only at run time.
    """

    platform_mass: float = 0.0
    """Mass of the platform, kg; 0 for none. Allowed: in [0, 1e+09]. Read-only at run time."""

    platform_center_of_mass: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    Centre of mass of the platform, X, Y, Z in the platform frame, metres. Allowed: 3 values in
    [-1000, 1000]. Read-only at run time.
    """

    platform_inertia: Tuple[float, ...] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    """
    Inertia tensor of the platform about its centre of mass, axes of the platform frame, kg m^2, as
    Ixx, Iyy, Izz, Ixy, Ixz, Iyz (the entries of the tensor, as URDF's <inertia> writes them).
    Allowed: 6 finite values forming an inertia tensor (positive semi-definite, principal moments
    within the triangle inequality); 0 when the mass is 0. Read-only at run time.
    """

    payload_mass: float = 0.0
    """Mass of the payload fixed to the platform, kg; 0 for none. Allowed: in [0, 1e+09]."""

    payload_center_of_mass: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    Centre of mass of the payload fixed to the platform, X, Y, Z in the platform frame, metres.
    Allowed: 3 values in [-1000, 1000].
    """

    payload_inertia: Tuple[float, ...] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    """
    Inertia tensor of the payload fixed to the platform about its centre of mass, axes of the
    platform frame, kg m^2, as Ixx, Iyy, Izz, Ixy, Ixz, Iyz (the entries of the tensor, as URDF's
    <inertia> writes them). Allowed: 6 finite values forming an inertia tensor (positive
    semi-definite, principal moments within the triangle inequality); 0 when the mass is 0.
    """

    leg_lower_mass: float = 0.0
    """
    Mass of the lower body (cylinder) of each leg, kg; 0 for none. Allowed: in [0, 1e+09].
    Read-only at run time.
    """

    leg_lower_center_of_mass: float = 0.0
    """
    Distance of the centre of mass of the lower body (cylinder) of each leg from the base joint
    along the leg axis, metres (negative: beyond the joint). Allowed: in [-1000, 1000]. Read-only
    at run time.
    """

    leg_lower_inertia: float = 0.0
    """
    Moment of inertia of the lower body (cylinder) of each leg about a transverse axis through its
    centre of mass, kg m^2 (none about the leg axis). Allowed: in [0, 1e+150]; 0 when the mass is
    0. Read-only at run time.
    """

    leg_upper_mass: float = 0.0
    """
    Mass of the upper body (rod) of each leg, kg; 0 for none. Allowed: in [0, 1e+09]. Read-only at
    run time.
    """

    leg_upper_center_of_mass: float = 0.0
    """
    Distance of the centre of mass of the upper body (rod) of each leg from the platform joint
    along the leg axis, metres (negative: beyond the joint). Allowed: in [-1000, 1000]. Read-only
    at run time.
    """

    leg_upper_inertia: float = 0.0
    """
    Moment of inertia of the upper body (rod) of each leg about a transverse axis through its
    centre of mass, kg m^2 (none about the leg axis). Allowed: in [0, 1e+150]; 0 when the mass is
    0. Read-only at run time.
    """

    gravity: Tuple[float, ...] = (0.0, 0.0, -9.80665)
    """
    Gravity X, Y, Z in the base frame, m/s^2. Allowed: 3 values in [-1000, 1000]. Read-only at run
    time.
    """


@dataclass(frozen=True, kw_only=True)
class ActuatorSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.ACTUATOR_PARAMETERS`.

    The actuators as a driver names them: joint names and zeros.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.ACTUATOR_PARAMETERS

    joint_names: Tuple[str, ...] = ('leg_1', 'leg_2', 'leg_3', 'leg_4', 'leg_5', 'leg_6')
    """
    Names of the six leg actuators as prismatic joints, leg 1..6, on every JointState and
    JointTrajectory the package publishes or reads. Allowed: 6 distinct, non-empty names. Read-only
    at run time.
    """

    actuator_offsets: Tuple[float, ...] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    """
    Each actuator's zero as a leg length, metres, leg 1..6: an actuator position is its leg length
    minus its offset. Allowed: 6 finite values. Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class SolverSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.SOLVER_PARAMETERS`.

    The forward kinematics solver and the pose tracker's checks (fk_node).
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.SOLVER_PARAMETERS

    tolerance: float = 1e-12
    """
    Newton-Raphson stops when every leg length of the solution is within this of the measured one,
    metres. Allowed: in (0, 0.01].
    """

    max_iterations: int = 50
    """
    Newton-Raphson iterations before a solve is reported as not converged. Allowed: in [1, 1000].
    """

    near_singularity_condition: float = 100.0
    """
    A solution whose dimensionless Jacobian condition number exceeds this is published with a WARN
    status on /diagnostics: it lies near a singularity; leg velocities are not turned into a twist
    there (they would be amplified up to this many times). Allowed: >= 1; .inf allowed.
    """

    pose_tolerance: float = 1e-09
    """
    Largest accepted bound on the pose error of a solution, metres and radians: near a singularity
    leg lengths matched to the tolerance above fix the pose only loosely, and a solution whose
    first-order error bound exceeds this is refused; .inf for no check. Allowed: > 0; .inf allowed.
    """

    assembly_guard_length_change: float = 0.005
    """
    Assembly-mode guard: when no leg changed by more than this since the last solution, metres, the
    new solution must lie within the two limits below of the last one. Allowed: in [0, 1].
    """

    assembly_guard_position_change: float = 0.05
    """
    Assembly-mode guard: largest move of the platform origin allowed for such a small change of the
    lengths, metres. Allowed: in (0, 10].
    """

    assembly_guard_angle_change_deg: float = 10.0
    """
    Assembly-mode guard: largest rotation of the platform allowed for such a small change of the
    lengths, degrees. Allowed: in (0, 180].
    """

    refuse_ambiguous_start: bool = False
    """
    After a start or reset_tracker, refuse to publish while more than one assembly mode lies within
    the limits and none within the two assembly-guard changes above of the last known pose (home,
    or the reset pose): the lengths alone do not tell which mode the platform is in. Costs one
    search for every mode (about 0.1 s) per new set of lengths until a pose is accepted.
    """


@dataclass(frozen=True, kw_only=True)
class AssemblyModeSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.ASSEMBLY_MODE_PARAMETERS`.

    The assembly-mode margin that fk_node reports.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.ASSEMBLY_MODE_PARAMETERS

    assembly_mode_margin_period: float = 1.0
    """
    Time between two computations of the assembly-mode margin of the last solution (the distance to
    the nearest other real mode within the limits, on /diagnostics), seconds; each runs in a worker
    process, and only when the lengths changed; 0.0 turns the margin off. Allowed: in [0, 3600].
    Read-only at run time.
    """

    assembly_mode_margin_warning: float = 0.05
    """
    A margin below this gives a WARN status and a log line: another real assembly mode within the
    limits lies this close to the estimated pose, metres, as sqrt(position^2 + (rho angle)^2) with
    rho the RMS radius of the platform joints; 0.0 for no warning. Allowed: in [0, 100].
    """


@dataclass(frozen=True, kw_only=True)
class FrameSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.FRAME_PARAMETERS`.

    The base, platform, user and tool frames;
    :func:`~stewart_kinematics.parameters.builders.frames_from_settings` builds the FrameTree.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.FRAME_PARAMETERS

    base_frame: str = 'stewart_base'
    """
    Name of the base frame: the parent of the platform on /tf, and the frame of stamped poses; a
    stamped target in a frame other than this one or user_frame is refused. Allowed: a frame name
    (no spaces, no leading '/', at most 256 characters). Read-only at run time.
    """

    platform_frame: str = 'stewart_platform'
    """
    Name of the platform frame (the frame the platform joints are given in) on /tf. Allowed: a
    frame name (no spaces, no leading '/', at most 256 characters). Read-only at run time.
    """

    user_frame: str = ''
    """
    Name of a user frame fixed to the base (a work piece's frame), on /tf_static, in which stamped
    poses may be given; '' for none. Allowed: a frame name (no spaces, no leading '/', at most 256
    characters) or ''. Read-only at run time.
    """

    user_frame_position: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    Origin of user_frame in the base frame, X, Y, Z, metres. Allowed: 3 values in [-1000, 1000].
    Read-only at run time.
    """

    user_frame_orientation_deg: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    Orientation of user_frame in the base frame, alpha, beta, gamma (R = Rz(gamma) Ry(beta)
    Rx(alpha)), degrees. Allowed: 3 values in [-180, 180]. Read-only at run time.
    """

    tool_frame: str = ''
    """
    Name of the tool frame fixed to the platform, on /tf_static; '' leaves it unnamed (its pose
    below still applies). Allowed: a frame name (no spaces, no leading '/', at most 256 characters)
    or ''.
    """

    tool_frame_position: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    Origin of the tool frame in the platform frame, X, Y, Z, metres: the pivot point. Commanded and
    estimated poses are those of the tool frame, so a pure rotation turns the platform about this
    point. Allowed: 3 values in [-1000, 1000].
    """

    tool_frame_orientation_deg: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    Orientation of the tool frame in the platform frame, alpha, beta, gamma (R = Rz(gamma) Ry(beta)
    Rx(alpha)), degrees. Allowed: 3 values in [-180, 180].
    """


@dataclass(frozen=True, kw_only=True)
class FkFrameSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.FK_FRAME_PARAMETERS`.

    fk_node's broadcast of the estimated pose.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.FK_FRAME_PARAMETERS

    publish_tf: bool = True
    """
    Broadcast the estimated pose on /tf (base_frame -> platform_frame, with the stamp of the
    lengths it comes from) and the user and tool frames on /tf_static. Read-only at run time.
    """

    estimated_pose_frame: str = ''
    """
    Frame of estimated_pose_stamped: base_frame or user_frame; '' means base_frame. Allowed: a
    frame name (no spaces, no leading '/', at most 256 characters) or ''; base_frame or user_frame.
    Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class IkFrameSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.IK_FRAME_PARAMETERS`.

    ik_node's broadcast of the commanded pose.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.IK_FRAME_PARAMETERS

    publish_commanded_tf: bool = False
    """
    Broadcast each accepted command on /tf as base_frame -> <platform_frame>_commanded. Read-only
    at run time.
    """


@dataclass(frozen=True, kw_only=True)
class MarkerSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.MARKER_PARAMETERS`.

    The RViz markers.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.MARKER_PARAMETERS

    marker_rate: float = 30.0
    """
    Highest rate of platform_markers, hertz: RViz needs no more, and a marker array per pose would
    cost a 1 kHz command stream; 0.0 turns the markers off. Allowed: in [0, 1000]. Read-only at run
    time.
    """


@dataclass(frozen=True, kw_only=True)
class WorkspaceSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.WORKSPACE_PARAMETERS`.

    ik_node's workspace outputs.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.WORKSPACE_PARAMETERS

    workspace_resolution: float = 0.01
    """
    Grid step of the constant-orientation workspace (at the home orientation) that
    workspace_markers shows, metres; computed in a worker process once the topic has a subscriber,
    and again when this changes; 0.0 turns the markers off. Allowed: 0.0 or in [0.002, 0.1].
    """

    travel_range_rate: float = 1.0
    """
    Rate of travel_ranges, the range left along each axis from the last accepted pose, hertz;
    computed in a worker process while the topic has a subscriber and the pose has moved; 0.0 turns
    them off. Allowed: in [0, 10]. Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class QueueSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.QUEUE_PARAMETERS`.

    The queues of every subscription and publisher.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.QUEUE_PARAMETERS

    queue_depth: int = 10
    """
    Depth of the reliable, keep-last queues of every subscription and publisher, messages. Allowed:
    in [1, 10000]. Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class LifecycleSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.LIFECYCLE_PARAMETERS`.

    Whether a node runs managed (lifecycle); see :mod:`stewart_kinematics.ros.managed`.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.LIFECYCLE_PARAMETERS

    managed: bool = False
    """
    Run as a managed (lifecycle) node: start unconfigured, publish nothing and act on no command
    until configured and activated through ~/change_state (doc/lifecycle.md); false: configure and
    activate at start-up, as ros2 run does. Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class RampSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.RAMP_PARAMETERS`.

    The Table 3 ramp and how trajectory_node plays it.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.RAMP_PARAMETERS

    position_start: Tuple[float, ...] = (0.0, 0.0, 0.4325)
    """
    First row of the ramp: X, Y, Z in metres. Allowed: 3 finite values. Read-only at run time.
    """

    position_step: Tuple[float, ...] = (0.01, 0.015, 0.01)
    """
    Change of X, Y, Z from one row to the next, metres. Allowed: 3 finite values; same number of
    steps on every axis. Read-only at run time.
    """

    position_end: Tuple[float, ...] = (0.1, 0.15, 0.5325)
    """Last row of the ramp: X, Y, Z in metres. Allowed: 3 finite values. Read-only at run time."""

    orientation_start_deg: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    First row of the ramp: alpha, beta, gamma in degrees. Allowed: 3 values in [-180, 180].
    Read-only at run time.
    """

    orientation_step_deg: Tuple[float, ...] = (1.5, -1.5, 2.0)
    """
    Change of alpha, beta, gamma from one row to the next, degrees. Allowed: 3 finite values; same
    number of steps on every axis. Read-only at run time.
    """

    orientation_end_deg: Tuple[float, ...] = (15.0, -15.0, 20.0)
    """
    Last row of the ramp: alpha, beta, gamma in degrees. Allowed: 3 values in [-180, 180].
    Read-only at run time.
    """

    mode: str = 'table'
    """
    'table': publish the table's rows, one every row_period; 'interpolate': sample the ramp in
    time, like the paper's clock-driven lookup tables, at publish_rate over duration; 'off': no
    ramp, only the trajectories received on pose_trajectory and pose_path. Allowed: 'table',
    'interpolate' or 'off'. Read-only at run time.
    """

    row_period: float = 1.0
    """
    Time between two rows in 'table' mode, seconds. Allowed: in [0.001, 3600]. Read-only at run
    time.
    """

    publish_rate: float = 50.0
    """
    Rate of the samples in 'interpolate' mode; for a received trajectory, rate of the points of
    leg_trajectory (every waypoint is a point too) and of the poses played on target_pose, hertz.
    Allowed: in [0.001, 1000]. Read-only at run time.
    """

    duration: float = 10.0
    """
    Time from the first row to the last in 'interpolate' mode, seconds. Allowed: in [0.001, 86400].
    Read-only at run time.
    """

    loop: bool = False
    """Start again from the first row after the last one. Read-only at run time."""

    start_delay: float = 0.5
    """
    Time between min_subscribers being matched and the first pose, seconds: the subscribers match
    this publisher a moment after it matches them, and a pose sent before that would be lost.
    Allowed: in [0, 3600]. Read-only at run time.
    """

    min_subscribers: int = 0
    """
    Wait until this many subscriptions are matched on target_pose before playing, so that no pose
    is published to nobody. Allowed: in [0, 1000]. Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class MotionSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.MOTION_PARAMETERS`.

    Trajectories and paths received by trajectory_node: checking, retiming, playing.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.MOTION_PARAMETERS

    retime: bool = False
    """
    Retime every received trajectory to the fastest timing within the leg velocity and acceleration
    limits (toppra), instead of refusing one whose own timing breaks them; a path (pose_path) is
    always retimed.
    """

    speed_scale: float = 1.0
    """
    Fraction of the fastest speed: a trajectory is played 1 / speed_scale times as long (retimed:
    at speed_scale of the leg velocity limit, speed_scale^2 of the acceleration limit). Allowed: in
    (0, 1].
    """

    validation_rate: float = 1000.0
    """
    Samples per second at which a whole trajectory is checked against every limit before anything
    is published, hertz. Allowed: in [1, 100000].
    """

    play: bool = False
    """Also play an accepted trajectory on target_pose at publish_rate, for the ik_node chain."""


@dataclass(frozen=True, kw_only=True)
class ActionSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.ACTION_PARAMETERS`.

    trajectory_node's follow_joint_trajectory action: execution, feedback, joints and the default
    tolerances.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.ACTION_PARAMETERS

    action_execution: str = 'leg_trajectory'
    """
    How an accepted goal is sent: 'leg_trajectory' (its leg trajectory on leg_trajectory, for
    joint_trajectory_controller) or 'stream' (its leg commands on joint_commands at publish_rate,
    as ik_node sends them). Allowed: 'leg_trajectory' or 'stream'.
    """

    action_feedback_rate: float = 10.0
    """
    Feedback messages per second of a running goal (desired, actual and error), hertz. Allowed: in
    [0.1, 1000].
    """

    action_cartesian_joints: Tuple[str, ...] = ('x', 'y', 'z', 'roll', 'pitch', 'yaw')
    """
    Names of the six Cartesian joints a goal may give instead of the legs: the tool frame's x, y, z
    (metres) and roll, pitch, yaw (radians, R = Rz(yaw) Ry(pitch) Rx(roll) about the base axes), in
    the header frame (base_frame or user_frame). Allowed: 6 distinct, non-empty names.
    """

    action_leg_path_tolerance: float = 0.02
    """
    Default path tolerance of each leg joint's position while a goal runs, metres; 0.0: none (a
    goal may set its own). Allowed: in [0, 1].
    """

    action_leg_goal_tolerance: float = 0.002
    """
    Default goal tolerance of each leg joint's position at the end, metres; 0.0: none. Allowed: in
    [0, 1].
    """

    action_stopped_velocity_tolerance: float = 0.01
    """
    Default goal tolerance of each leg joint's velocity at the end (when joint_states carries
    velocities), m/s, as joint_trajectory_controller's stopped_velocity_tolerance; 0.0: none.
    Allowed: in [0, 10].
    """

    action_position_path_tolerance: float = 0.02
    """
    Default path tolerance of the Cartesian joints x, y, z while a goal runs, metres; 0.0: none.
    Allowed: in [0, 10].
    """

    action_orientation_path_tolerance: float = 0.05
    """
    Default path tolerance of the Cartesian joints roll, pitch, yaw while a goal runs, radians;
    0.0: none. Allowed: in [0, 3.2].
    """

    action_position_goal_tolerance: float = 0.002
    """Default goal tolerance of x, y, z at the end, metres; 0.0: none. Allowed: in [0, 10]."""

    action_orientation_goal_tolerance: float = 0.005
    """
    Default goal tolerance of roll, pitch, yaw at the end, radians; 0.0: none. Allowed: in [0,
    3.2].
    """

    action_goal_time_tolerance: float = 1.0
    """
    Default time after a goal's end by which the measured state must be within the goal tolerance,
    seconds; 0.0: checked once, at the end time. Allowed: in [0, 3600].
    """

    action_start_tolerance: float = 0.01
    """
    How far a first point at time 0 may be from the current state (metres, or radians for roll,
    pitch, yaw): it is taken as the current state; farther, the goal is refused (it would jump).
    Allowed: in [0, 1].
    """


@dataclass(frozen=True, kw_only=True)
class StreamingSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.STREAMING_PARAMETERS`.

    ik_node's streamed, jerk-limited commands.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.STREAMING_PARAMETERS

    command_rate: float = 0.0
    """
    Rate of joint_commands, hertz: each command moves from the last toward the latest accepted
    target within leg_velocity_max, leg_acceleration_max and leg_jerk_max (ruckig; the first two
    must be set); 0.0: one command per accepted pose, unfiltered. Allowed: in [0, 10000]. Read-only
    at run time.
    """

    twist_over_limit: str = 'refuse'
    """
    What ik_node does with a target_twist whose leg velocities exceed leg_velocity_max: 'refuse' it
    (nothing published, code too_fast), or 'scale' the whole twist down uniformly until the fastest
    leg is at the limit (published, with a twist_scaled warning); never published beyond the limit.
    Allowed: 'refuse' or 'scale'. Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class CueingParameterSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.MOTION_CUEING_PARAMETERS`.

    motion_cueing_node's washout, limit margins and input checks, as the node declares its
    parameters (degrees where named); not the motion cueing's own settings,
    :class:`stewart_kinematics.cueing.CueingSettings` (SI units), which
    :meth:`~stewart_kinematics.cueing.CueingSettings.from_parameters` builds from these.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.MOTION_CUEING_PARAMETERS

    translation_scale: Tuple[float, ...] = (0.5, 0.5, 0.5)
    """
    Gain on the specific force of the translational channel, x y z (vehicle frame: x forward, y
    left, z up); changeable at run time: ramped over gain_ramp_time, refused where its worst-case
    cue leaves the travel (doc/motion_cueing.md). Allowed: 3 values in [0, 10].
    """

    translation_input_limit: float = math.inf
    """
    Soft limit of the translational channel's input, m/s^2 per axis: a = L tanh(a_in / L)
    (nonlinear scaling); .inf for none. Allowed: > 0; .inf allowed. Read-only at run time.
    """

    translation_order: int = 3
    """
    Order of the translational high-pass: 3 returns the platform to neutral after a sustained
    acceleration, 2 keeps a displacement while it lasts. Allowed: 2 or 3. Read-only at run time.
    """

    translation_frequency: Tuple[float, ...] = (2.5, 2.5, 4.0)
    """
    Natural frequency of the second-order translational high-pass, rad/s, x y z. Allowed: 3 values
    in [0.001, 100]. Read-only at run time.
    """

    translation_damping: Tuple[float, ...] = (1.0, 1.0, 1.0)
    """
    Damping ratio of the translational high-pass, x y z; >= 1 never reverses through neutral after
    a step. Allowed: 3 values in (0, 10]. Read-only at run time.
    """

    translation_break_frequency: Tuple[float, ...] = (0.25, 0.25, 0.25)
    """
    Frequency of the first-order part of the third-order translational high-pass, rad/s, x y z.
    Allowed: 3 values in [0.001, 100]. Read-only at run time.
    """

    tilt_scale: Tuple[float, ...] = (0.5, 0.5)
    """
    Gain on the specific force rendered by tilt coordination, x (pitch) and y (roll); changeable at
    run time as translation_scale. Allowed: 2 values in [0, 10].
    """

    tilt_complementary: bool = False
    """
    Use 1 - (the translational high-pass) as the tilt low-pass, per axis, instead of the classical
    low-pass of tilt_order. Read-only at run time.
    """

    tilt_order: int = 2
    """Order of the tilt low-pass. Allowed: 1 or 2. Read-only at run time."""

    tilt_frequency: float = 5.0
    """Cut-off of the tilt low-pass, rad/s. Allowed: in [0.001, 100]. Read-only at run time."""

    tilt_damping: float = 1.0
    """Damping ratio of the tilt low-pass (order 2). Allowed: in (0, 10]. Read-only at run time."""

    tilt_rate_max_deg: float = 3.0
    """
    Largest tilt rate of tilt coordination, degrees per second (the threshold below which a
    rotation is not perceived). Allowed: in (0, 90]. Read-only at run time.
    """

    tilt_acceleration_max_deg: float = 10.0
    """
    Largest tilt acceleration of tilt coordination, degrees per second squared (a smooth onset of
    the tilt). Allowed: in (0, 1000]. Read-only at run time.
    """

    tilt_max_deg: float = 15.0
    """
    Largest tilt angle of tilt coordination, degrees. Allowed: in (0, 45]. Read-only at run time.
    """

    rotation_scale: Tuple[float, ...] = (0.5, 0.5, 0.5)
    """
    Gain on the angular velocity, roll pitch yaw; changeable at run time as translation_scale.
    Allowed: 3 values in [0, 10].
    """

    rotation_order: int = 2
    """
    Order of the rotational high-pass: 2 returns the angle to neutral after a sustained rate.
    Allowed: 1 or 2. Read-only at run time.
    """

    rotation_frequency: Tuple[float, ...] = (1.0, 1.0, 1.0)
    """
    Natural frequency of the rotational high-pass, rad/s, roll pitch yaw. Allowed: 3 values in
    [0.001, 100]. Read-only at run time.
    """

    rotation_damping: Tuple[float, ...] = (1.0, 1.0, 1.0)
    """
    Damping ratio of the rotational high-pass, roll pitch yaw. Allowed: 3 values in (0, 10].
    Read-only at run time.
    """

    attitude_aware_specific_force: bool = False
    """
    Turn the vehicle's specific force into the simulator's frame through the platform's cue
    attitude before the translational high-pass (Reid and Nahon's L_IS): a coordinated turn rolled
    by the rotational channel asks for the sideways acceleration that offsets the gravity the roll
    shows; false: the force as it comes. Read-only at run time.
    """

    head_position: Tuple[float, ...] = (0.0, 0.0, 0.5)
    """
    The cueing reference point (the driver's head) in the platform frame, metres: the cue's
    rotations turn about it, and the perceived specific force is computed there. Allowed: 3 values
    in [-10, 10]. Read-only at run time.
    """

    follower_frequency: float = 10.0
    """
    Bandwidth of the follower that brings the platform back onto the cue after the leg velocity or
    acceleration limits held it back, rad/s. Allowed: in (0, 1000]. Read-only at run time.
    """

    follower_weights: Tuple[float, ...] = (1.0, 1.0, 30.0, 1.0, 1.0, 1.0)
    """
    Weights of the follower's least-squares step where the legs cannot follow the cue: the squared
    miss of the platform twist along x, y, z (per m/s) and roll, pitch, yaw (per rad/s) costs its
    weight; a larger weight keeps that axis closer to the cue (only their ratios matter); heave
    weighted 30: limiting at the literature gains then keeps wrong-way heave on the mixed drive
    within 10 % of the unlimited cue. Allowed: 6 values in [0.001, 1000]. Read-only at run time.
    """

    workspace_recovery_rate: float = 0.5
    """
    Fastest rise of the workspace scale (the share of the cue kept inside the limits) back toward
    1, per second. Allowed: in (0, 1000]. Read-only at run time.
    """

    leg_length_margin: float = 0.01
    """
    The cue keeps this far inside each end of the stroke, metres (raised to the braking distance
    leg_velocity_max^2 / (2 leg_acceleration_max) when that is longer). Allowed: in [0, 1].
    Read-only at run time.
    """

    joint_angle_margin_deg: float = 2.0
    """
    The cue keeps this far inside each joint cone, degrees. Allowed: in [0, 45]. Read-only at run
    time.
    """

    condition_margin: float = 0.9
    """
    The cue keeps the Jacobian condition number below this share of max_jacobian_condition.
    Allowed: in (0, 1]. Read-only at run time.
    """

    max_input_gap: float = 0.1
    """
    A longer time between two vehicle_imu stamps counts as this long (the washout pauses, with an
    input_gap warning), seconds. Allowed: in (0, 3600]. Read-only at run time.
    """

    max_specific_force: float = 100.0
    """
    A larger specific force is refused as absurd (the platform eases to neutral), m/s^2. Allowed:
    in (0, 10000]. Read-only at run time.
    """

    max_angular_velocity: float = 20.0
    """
    A larger angular velocity is refused as absurd (the platform eases to neutral), rad/s. Allowed:
    in (0, 10000]. Read-only at run time.
    """

    vehicle_frame: str = 'base_link'
    """
    The vehicle's body frame (x forward, y left, z up, REP 103): vehicle_imu in this frame (or with
    an empty frame_id) is cued as it is; a sample in a frame neither this nor imu_frame is refused
    with the reason. Allowed: a frame name (no spaces, no leading '/', at most 256 characters).
    Read-only at run time.
    """

    imu_frame: str = ''
    """
    Another frame vehicle_imu may come in (an IMU mounted turned, or in NED axes), placed by
    imu_orientation_rpy_deg; '' for none. Allowed: a frame name (no spaces, no leading '/', at most
    256 characters) or ''. Read-only at run time.
    """

    imu_orientation_rpy_deg: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    Orientation of imu_frame in vehicle_frame: roll, pitch, yaw about the fixed x, y, z axes (R =
    Rz Ry Rx), degrees; [180.0, 0.0, 0.0] for an IMU in NED axes (x forward, y right, z down).
    Allowed: 3 values in [-360, 360]. Read-only at run time.
    """

    input_timeout: float = 0.5
    """
    When no vehicle_imu message came for this long, the platform eases to neutral as if the vehicle
    were at rest, seconds (node clock); 0.0 turns this off. Allowed: in [0, 3600]. Read-only at run
    time.
    """

    cueing_method: str = 'classical'
    """
    How the vehicle's motion becomes a cue: 'classical' (the washout filters) or 'mpc'
    (model-predictive: translation and tilt traded over a horizon against the perceived specific
    force, within the legs; doc/motion_cueing_mpc.md). Allowed: 'classical' or 'mpc'. Read-only at
    run time.
    """

    mpc_horizon: int = 10
    """
    Steps of the MPC horizon (cueing_method mpc). Allowed: in [2, 100]. Read-only at run time.
    """

    mpc_step: float = 0.2
    """
    Length of one MPC step, seconds (the horizon is mpc_horizon times this). Allowed: in [0.005,
    1]. Read-only at run time.
    """

    mpc_force_scale: Tuple[float, ...] = (0.3, 0.3, 0.3)
    """
    Share of the vehicle's perceived specific force the MPC aims at, x y z. Allowed: 3 values in
    [0, 10]. Read-only at run time.
    """

    mpc_force_weight: Tuple[float, ...] = (1.0, 1.0, 1.0)
    """
    MPC weight on the perceived specific-force error, x y z, per (m/s^2)^2. Allowed: 3 values in
    [0, 1e+06]. Read-only at run time.
    """

    mpc_rate_weight: float = 10.0
    """
    MPC weight on the perceived roll and pitch rate error, per (rad/s)^2. Allowed: in [0, 1e+06].
    Read-only at run time.
    """

    mpc_position_weight: Tuple[float, ...] = (0.3, 0.3, 0.3)
    """
    MPC weight on the head's displacement from neutral (the washout), x y z, per m^2. Allowed: 3
    values in [0, 1e+06]. Read-only at run time.
    """

    mpc_velocity_weight: Tuple[float, ...] = (0.1, 0.1, 0.1)
    """
    MPC weight on the head's velocity, x y z, per (m/s)^2. Allowed: 3 values in [0, 1e+06].
    Read-only at run time.
    """

    mpc_tilt_weight: float = 5.0
    """
    MPC weight on the tilt from neutral, per rad^2. Allowed: in [0, 1e+06]. Read-only at run time.
    """

    mpc_tilt_rate_weight: float = 1.0
    """
    MPC weight on the tilt rate, per (rad/s)^2. Allowed: in [0, 1e+06]. Read-only at run time.
    """

    mpc_input_weight: Tuple[float, ...] = (0.01, 0.01)
    """
    MPC weight on its inputs: the head's acceleration per (m/s^2)^2 and the tilt's acceleration per
    (rad/s^2)^2; positive (they keep the QP strictly convex). Allowed: 2 values in (0, 1e+06].
    Read-only at run time.
    """

    mpc_reference_time_constant: float = 0.5
    """
    The MPC predicts the vehicle's current input held over the horizon, fading with this time
    constant, seconds; .inf holds it, 0.0 lets it drop to rest at once. Allowed: >= 0; .inf
    allowed. Read-only at run time.
    """

    mpc_limit_share: float = 0.8
    """
    Share of the leg velocity and acceleration limits and of tilt_rate_max_deg the MPC plans with
    (the rest absorbs its linearisation; the limiter keeps the limits anyway). Allowed: in (0, 1].
    Read-only at run time.
    """

    mpc_workspace_share: float = 0.5
    """
    The MPC keeps each cue coordinate (the head's x, y, z, roll, pitch) within this share of how
    far it reaches alone inside the limits (a box inside the workspace). Allowed: in (0, 1].
    Read-only at run time.
    """

    mpc_max_iterations: int = 1000
    """
    Iteration limit of the MPC's QP solver; beyond it the cue falls back on the last plan. Allowed:
    in [1, 100000]. Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class CueingControlSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.CUEING_CONTROL_PARAMETERS`.

    motion_cueing_node's run-time controls: intensity and gain ramps, soft start and stop, park
    (:mod:`stewart_kinematics.cueing.controls`).
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.CUEING_CONTROL_PARAMETERS

    cueing_intensity: float = 1.0
    """
    Master intensity of the cue, 0 (no motion: the platform eases to neutral) to 1 (the gains as
    set): it multiplies translation_scale, tilt_scale and rotation_scale; a change is ramped over
    gain_ramp_time and refused where the cue would leave the travel. Allowed: in [0, 1].
    """

    gain_ramp_time: float = 2.0
    """
    Time over which a change of cueing_intensity or of a gain is ramped (smoothstep: no jump in the
    gain or its rate), seconds; applies from the next change. Allowed: in [0.01, 600].
    """

    gain_check_specific_force: float = 4.0
    """
    The sustained change of specific force (m/s^2, each axis) a gain change is checked with: a
    change whose cue of it would leave the travel (within the cue margins) is refused. Allowed: in
    (0, 1000]. Read-only at run time.
    """

    gain_check_angular_velocity: float = 0.5
    """
    The sustained angular velocity (rad/s, each axis) a rotation_scale change is checked with, as
    gain_check_specific_force. Allowed: in (0, 100]. Read-only at run time.
    """

    soft_start_time: float = 3.0
    """
    The start service moves the platform from park to the neutral cueing pose in this time (longer
    when the leg velocity or acceleration limits need), seconds. Allowed: in [0.1, 600].
    """

    soft_stop_time: float = 3.0
    """
    The stop service brakes the platform to rest, then moves it to park in this time (longer when
    the leg limits need), seconds. Allowed: in [0.1, 600].
    """

    park_position: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    The park pose's X, Y, Z, metres, base frame, oriented by park_orientation_deg (all 0.0: as
    home): where stop takes the platform and start_parked starts it; all 0.0: the lowest pose
    straight below home that keeps the cue margins (leg_length_margin inside the stroke). Allowed:
    3 values in [-1000, 1000]; within every limit, or all 0.0. Read-only at run time.
    """

    park_orientation_deg: Tuple[float, ...] = (0.0, 0.0, 0.0)
    """
    The park pose's orientation in the base frame, alpha, beta, gamma (R = Rz(gamma) Ry(beta)
    Rx(alpha)), degrees, for a platform that parks tilted: with park_position, that pose; with
    park_position all 0.0, the lowest pose straight below home so oriented; all 0.0: home's
    orientation. Allowed: 3 values in [-180, 180]; the park pose within every limit. Read-only at
    run time.
    """

    start_parked: bool = False
    """
    Start with the platform at park: nothing is cued until the start service; false: the platform
    is taken to be at home, cueing at once. Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class MockPlatformSettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.MOCK_PLATFORM_PARAMETERS`.

    mock_platform's simulated legs: the commands they take, their lag, the joint states' rate, and
    the faults a test gives them.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.MOCK_PLATFORM_PARAMETERS

    command_input: str = 'all'
    """
    The leg command mock_platform takes: 'all' (it subscribes to the three, and whichever commands
    last wins: a set point on leg_lengths or joint_commands drops a running trajectory, a
    leg_trajectory takes over from its start time), or only 'leg_lengths', 'joint_commands' or
    'leg_trajectory'. Allowed: 'all', 'leg_lengths', 'joint_commands' or 'leg_trajectory'.
    Read-only at run time.
    """

    time_constant: float = 0.05
    """
    Time constant of each simulated leg's first-order lag toward its command, seconds (within the
    stroke and leg_velocity_max, leg_acceleration_max); 0.0: as fast as the limits allow. Allowed:
    in [0, 100].
    """

    joint_state_rate: float = 100.0
    """
    Rate at which mock_platform advances the legs and publishes joint_states, hertz (the node's
    clock: simulated time too). Allowed: in [1, 1000]. Read-only at run time.
    """

    max_time_step: float = 0.1
    """
    A longer time between two steps of the simulated legs (a clock jump, a process paused) counts
    as this long, seconds, with a clock_jump warning; a clock that goes back moves nothing.
    Allowed: in [0.0001, 10].
    """

    initial_leg_lengths: Tuple[float, ...] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    """
    Where the simulated legs start, at rest, metres, leg 1..6; all 0.0: the leg lengths of the home
    pose. Allowed: 6 values in [0, 1000]; within the stroke, or all 0.0. Read-only at run time.
    """

    stalled_legs: str = ''
    """
    Legs that stall (a fault for tests): they stop where they are at once, and move again when no
    longer named. Allowed: leg numbers 1..6 or joint names, separated by commas or spaces, or '';
    names of joint_names.
    """

    position_noise: float = 0.0
    """
    Standard deviation of the Gaussian noise added to each published position, metres (a fault for
    tests: the simulated legs do not move with it). Allowed: in [0, 1].
    """

    noise_seed: int = 0
    """
    Seed of the noise; setting it (or position_noise) starts the sequence again. Allowed: in [0,
    1e+09].
    """

    position_bias: Tuple[float, ...] = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    """
    A fixed offset added to each published position, metres, leg 1..6 (a fault for tests: a
    miscalibrated sensor). Allowed: 6 values in [-1, 1].
    """


@dataclass(frozen=True, kw_only=True)
class TelemetrySettings(Settings):
    """
    One field per parameter of :data:`~stewart_kinematics.parameters.TELEMETRY_PARAMETERS`.

    telemetry_bridge's UDP socket, the stream's timeout and the vehicle_imu frame.
    """

    SPECS: ClassVar[Tuple[ParameterSpec, ...]] = declarations.TELEMETRY_PARAMETERS

    telemetry_address: str = '127.0.0.1'
    """
    The address telemetry_bridge's UDP socket binds to: 127.0.0.1 takes packets from this machine
    only, 0.0.0.0 from every interface (a simulator on another computer), or one interface's IPv4
    address. Allowed: an IPv4 address, such as '127.0.0.1' or '0.0.0.0'. Read-only at run time.
    """

    telemetry_port: int = 47800
    """
    The UDP port telemetry_bridge receives the telemetry packets on. Allowed: in [1, 65535].
    Read-only at run time.
    """

    telemetry_frame_id: str = 'base_link'
    """
    The header.frame_id of the vehicle_imu it publishes: motion_cueing_node's vehicle_frame (the
    packets are in the vehicle frame, x forward, y left, z up). Allowed: a frame name (no spaces,
    no leading '/', at most 256 characters). Read-only at run time.
    """

    telemetry_timeout: float = 0.5
    """
    Seconds without a valid packet after which the stream is reported stale on /diagnostics
    (nothing is published meanwhile) and the next packet starts a new stream, whatever its sequence
    number. Allowed: in [0.01, 60]. Read-only at run time.
    """

    telemetry_poll_rate: float = 1000.0
    """
    How often telemetry_bridge empties its socket, hertz: each packet waits at most one period (the
    executor never blocks on the socket). Allowed: in [10, 10000]. Read-only at run time.
    """


@dataclass(frozen=True, kw_only=True)
class IkNodeSettings(NodeSettings):
    """ik_node's settings: one field per parameter group it declares, in that order."""

    geometry: GeometrySettings
    actuators: ActuatorSettings
    frames: FrameSettings
    ik_frames: IkFrameSettings
    markers: MarkerSettings
    workspace: WorkspaceSettings
    streaming: StreamingSettings
    queue: QueueSettings
    lifecycle: LifecycleSettings


@dataclass(frozen=True, kw_only=True)
class FkNodeSettings(NodeSettings):
    """fk_node's settings: one field per parameter group it declares, in that order."""

    geometry: GeometrySettings
    actuators: ActuatorSettings
    solver: SolverSettings
    assembly_modes: AssemblyModeSettings
    frames: FrameSettings
    fk_frames: FkFrameSettings
    markers: MarkerSettings
    queue: QueueSettings
    lifecycle: LifecycleSettings


@dataclass(frozen=True, kw_only=True)
class MotionCueingNodeSettings(NodeSettings):
    """motion_cueing_node's settings: one field per group it declares, in that order."""

    geometry: GeometrySettings
    frames: FrameSettings
    cueing: CueingParameterSettings
    controls: CueingControlSettings
    queue: QueueSettings
    lifecycle: LifecycleSettings


@dataclass(frozen=True, kw_only=True)
class TrajectoryNodeSettings(NodeSettings):
    """trajectory_node's settings: one field per group it declares, in that order."""

    geometry: GeometrySettings
    actuators: ActuatorSettings
    frames: FrameSettings
    ramp: RampSettings
    motion: MotionSettings
    action: ActionSettings
    queue: QueueSettings
    lifecycle: LifecycleSettings


@dataclass(frozen=True, kw_only=True)
class MockPlatformNodeSettings(NodeSettings):
    """mock_platform's settings: one field per parameter group it declares, in that order."""

    geometry: GeometrySettings
    actuators: ActuatorSettings
    mock: MockPlatformSettings
    queue: QueueSettings


@dataclass(frozen=True, kw_only=True)
class TelemetryBridgeNodeSettings(NodeSettings):
    """telemetry_bridge's settings: one field per parameter group it declares, in that order."""

    telemetry: TelemetrySettings
    queue: QueueSettings
    lifecycle: LifecycleSettings
