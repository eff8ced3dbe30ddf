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
Findings: why the core refused an input, or what it warns about, in words and in numbers.

The decision objects (:class:`stewart_kinematics.PoseTracker`,
:class:`stewart_kinematics.CommandCheck`, ...) never raise for input they cannot use: they
return a result that carries a :class:`Finding`. Its ``code`` is short and stable, to count by
(the nodes count their refusals by it on ``/diagnostics``); its ``message`` is a sentence a
user can act on; its ``details`` are ``(key, value)`` pairs such as iterations, residual or the
violated limits.

Every code the package can emit is registered here, once, with what it means and who emits
it (:data:`CODES`); the documentation's table of codes is rendered from the registry
(:func:`codes_table`), and a test finds every code the package emits in it. Nothing here
imports ROS.
"""

from dataclasses import dataclass
from typing import Dict, Tuple


@dataclass(frozen=True)
class Code:
    """
    One code of the registry.

    :param code: the code, short and stable, such as ``out_of_limits``.
    :param kind: ``refusal`` (the input is not used), ``warning`` (it is, with a warning), or
        ``refusal or warning`` (a code used both ways, said where).
    :param emitted_by: the core objects (and nodes, topics) that emit it, in Markdown.
    :param meaning: what it means, in Markdown.
    """

    code: str
    kind: str
    emitted_by: str
    meaning: str


#: Every code the package can emit, by code, in the order of the documentation's table.
CODES: Dict[str, Code] = {}


def _register(code: str, kind: str, emitted_by: str, meaning: str) -> str:
    """Register a code with its meaning; return the code (for its module constant)."""
    if code in CODES or kind not in ('refusal', 'warning', 'refusal or warning'):
        raise ValueError(f'code {code!r} registered twice, or kind {kind!r} unknown')
    CODES[code] = Code(code, kind, emitted_by, meaning)
    return code


# Commanded poses and twists (ik_node) ------------------------------------------------------

INVALID_POSE = _register(
    'invalid_pose', 'refusal',
    '`CommandCheck` (ik_node: `target_pose`, `target_pose_stamped`), `PoseTracker.anchor` '
    '(fk_node: `anchor_pose`)',
    'A pose with a NaN or infinite coordinate, a zero or NaN quaternion, a matrix that is no '
    'rotation, or the wrong shape; a stamped pose whose `header.stamp` is malformed (`nanosec` '
    'not below 1e9: ik_node would pass it on to `joint_commands`).')
WRONG_FRAME = _register(
    'wrong_frame', 'refusal',
    '`CommandCheck.tool_pose` (ik_node: `target_pose_stamped`; fk_node: `anchor_pose`)',
    "A stamped pose in a frame other than `base_frame`, `user_frame` or `''`.")
QUATERNION_NOT_UNIT = _register(
    'quaternion_not_unit', 'warning',
    '`CommandCheck.tool_pose` (ik_node: `target_pose`, `target_pose_stamped`; fk_node: '
    '`anchor_pose`)',
    'A quaternion whose norm is not 1 (within 1e-6): it is normalised and the pose is used.')
UNREACHABLE = _register(
    'unreachable', 'refusal',
    '`CommandCheck` (ik_node), `PoseTracker.anchor` (fk_node: `anchor_pose`)',
    'A pose whose leg lengths are not finite and positive: a platform joint on its base '
    'joint, or a pose so far away that the lengths overflow.')
OUT_OF_LIMITS = _register(
    'out_of_limits', 'refusal',
    '`CommandCheck`, `PoseTracker`, `plan_motion`, `limits.check_samples`, `CommandFilter` '
    '(every node)',
    'A pose, a set of leg lengths, a trajectory sample, a ramp sample or a streamed target '
    'that breaks a limit (stroke, joint cone, singularity margin, leg collision); every '
    'violation is listed with the leg (or the two legs), the value, the limit and the excess.')
INVALID_TWIST = _register(
    'invalid_twist', 'refusal',
    '`CommandCheck.twist` (ik_node: `target_twist`)',
    'A twist that is not six finite numbers, or whose speeds (above 1000 m/s or rad/s) are no '
    'motion of a platform, or whose leg velocities overflow.')
NO_POSE_YET = _register(
    'no_pose_yet', 'refusal',
    '`CommandCheck.twist` (ik_node: `target_twist`)',
    'A twist before any pose was accepted: there is no pose to apply it at.')
TOO_FAST = _register(
    'too_fast', 'refusal',
    '`CommandCheck.twist` (ik_node: `target_twist`), `plan_motion`, `check_trajectory` '
    '(trajectory_node)',
    'A twist whose leg velocities exceed `leg_velocity_max` (with `twist_over_limit: '
    "'refuse'`), or a timed trajectory, not retimed, that breaks a leg velocity or "
    'acceleration limit, or (with masses) a leg force limit with its dynamic forces while its '
    'static ones keep it, naming the time, the segment, the legs and the limits.')
TWIST_SCALED = _register(
    'twist_scaled', 'warning',
    '`CommandCheck.twist` (ik_node: `target_twist`, with `twist_over_limit: '
    "'scale'`)",
    'A twist whose leg velocities exceeded `leg_velocity_max`, scaled down uniformly until '
    'the fastest leg is at the limit; the factor is in the details.')

# Every command as it is sent (the command gate, every node that commands actuators) -------

COMMAND_BRAKING = _register(
    'command_braking', 'refusal',
    '`CommandGate.brake` (ik_node with `command_rate`, trajectory_node playing a trajectory, '
    'motion_cueing_node), `MotionCueing`',
    'The command a motion asked for broke a limit as it would have been sent, or none within '
    'every limit could be computed: a braking command is sent instead, every leg slowing at '
    '`leg_acceleration_max` (within `leg_velocity_max`; `leg_jerk_max` may be exceeded), never '
    'one step to rest; the details name the command it replaced and anything the braking '
    'command itself breaks (a leg stopped at the end of its stroke).')
CLOCK_NOT_ADVANCING = _register(
    'clock_not_advancing', 'refusal',
    '`CommandGate` (every node that commands actuators as a motion)',
    "A command of a motion at a time that does not come after the last command's (the node's "
    'clock, wall or simulated, paused or moved back): no time passed, so no motion may be '
    'commanded; nothing is sent, the last command stands.')

RETURNING_TO_LIMITS = _register(
    'returning_to_limits', 'warning',
    '`CommandGate` (ik_node with `command_rate`, motion_cueing_node)',
    'After a braking command that could not keep every pose limit (a leg stopped at the end of '
    'its stroke, a joint cone passed while braking), a command that breaks only those limits, '
    'by no more than the last command did: the platform comes back within its limits, never '
    'further out.')

# Streamed commands (ik_node with command_rate) ----------------------------------------------

STREAM_BRAKING = _register(
    'stream_braking', 'warning',
    '`CommandFilter.step` (ik_node with `command_rate`)',
    'The jerk-limited generator (ruckig) could not plan a motion toward the target from the '
    'current command: the command brakes to rest within the limits instead, and aims again '
    'at the next step.')
STREAM_HELD = _register(
    'stream_held', 'refusal',
    '`CommandFilter.step` (ik_node with `command_rate`)',
    'No step within every limit could be computed: no command is published this period, and '
    'the last one, within the limits, stands.')
FORCE_LIMITED = _register(
    'force_limited', 'warning',
    '`CommandFilter.send` (ik_node with `command_rate`), `MotionCueing` '
    '(motion_cueing_node)',
    'The streamed step or the cue pose asked for would have broken `leg_force_min` or '
    '`leg_force_max` with its motion (the legs and forces in the details): it was planned '
    'again with less acceleration (the share of `leg_acceleration_max` in the details), '
    'slower toward the same target.')

# Measured leg lengths (fk_node) -------------------------------------------------------------

INVALID_LENGTHS = _register(
    'invalid_lengths', 'refusal',
    '`PoseTracker` (fk_node: `leg_lengths`, `joint_states`), `CommandFilter.set_target`',
    'Leg lengths that are not six finite, positive numbers (or a malformed message).')
INVALID_VELOCITIES = _register(
    'invalid_velocities', 'refusal or warning',
    '`PoseTracker.twist` (fk_node: a refusal on `leg_velocities`, a warning on '
    '`joint_states`)',
    'Leg velocities that are not six finite numbers.')
NO_SOLUTION = _register(
    'no_solution', 'refusal',
    '`PoseTracker` (fk_node)',
    'Forward kinematics found no solution (iteration limit, singular Jacobian, divergence), '
    'with the iterations and the residual.')
INACCURATE_POSE = _register(
    'inaccurate_pose', 'refusal',
    '`PoseTracker` (fk_node)',
    'A converged solution whose `pose_error_bound` exceeds `pose_tolerance`: near a '
    'singularity the lengths fix the pose only loosely.')
ASSEMBLY_MODE_JUMP = _register(
    'assembly_mode_jump', 'refusal',
    '`PoseTracker` (fk_node)',
    'A solution more than `assembly_guard_position_change` or '
    '`assembly_guard_angle_change_deg` from the last one while no leg changed by more than '
    '`assembly_guard_length_change`.')
AMBIGUOUS_ASSEMBLY_MODE = _register(
    'ambiguous_assembly_mode', 'refusal',
    '`PoseTracker` (fk_node, with `refuse_ambiguous_start`)',
    'After a start or `reset_tracker`, more than one assembly mode lies within the limits and '
    "none near the last known pose; with the number of modes and the nearest one's distance.")
ASSEMBLY_MODE_MARGIN = _register(
    'assembly_mode_margin', 'warning',
    '`margin_status` (fk_node, on `/diagnostics`)',
    'Another real assembly mode within the limits lies closer than '
    '`assembly_mode_margin_warning` to the estimated pose, or the search for one was '
    'incomplete.')
AMBIGUOUS_ESTIMATE = _register(
    'ambiguous_estimate', 'warning',
    '`PoseTracker` (fk_node: with every accepted pose while it lasts, and the status `assembly '
    'mode ambiguity` on `/diagnostics`)',
    'Since the tracker was last anchored, a fold singularity may have been crossed: a solve '
    'started or ended nearer a singularity than the singularity margin, or a solution lay '
    "across a singularity from the last one (its Jacobian's determinant changed sign), or a "
    'solve failed, jumped or fell back to home (`no_solution`, `inaccurate_pose`, '
    '`assembly_mode_jump`), or the assembly-mode margin fell below '
    '`assembly_mode_margin_warning`. There two assembly modes meet and six leg lengths cannot '
    'tell which one the platform went on in: the pose is published, with this warning, until '
    'the tracker is re-anchored by `reset_tracker` (homing), a known pose on `anchor_pose`, or '
    'a pose whose margin finds no other real assembly mode the platform could be in (the '
    'rules: Every assembly mode).')
NEAR_SINGULARITY = _register(
    'near_singularity', 'refusal or warning',
    '`PoseTracker` (fk_node: a warning on a pose, a refusal of a twist)',
    "The Jacobian's condition number exceeds `near_singularity_condition`: the pose is "
    'published with a warning, and leg velocities are not turned into a twist there.')

INVALID_EFFORTS = _register(
    'invalid_efforts', 'warning',
    'fk_node (`joint_states`, for `estimated_wrench`)',
    'No external wrench for a joint state whose pose was published: its efforts are missing '
    '(while `estimated_wrench` has a subscriber), not one per joint name, not finite or too '
    'large, or the pose is singular (no leg forces balance the load there).')

# Trajectories (trajectory_node) -------------------------------------------------------------

RETIMING_FAILED = _register(
    'retiming_failed', 'refusal',
    '`plan_motion`, `MotionPlanner` (trajectory_node)',
    'No timing of the path within the leg limits: the path crosses a singularity (the '
    'platform moves while the legs do not), a static leg force breaks `leg_force_min` or '
    '`leg_force_max` somewhere (cause `leg_force`: no speed can follow it), or toppra failed on '
    'its grid; the details give the cause, the waypoints and the leg.')
INVALID_TRAJECTORY = _register(
    'invalid_trajectory', 'refusal',
    '`MotionPlanner` (trajectory_node: `pose_trajectory`, `pose_path`)',
    'A malformed trajectory or path: another frame, more than one joint, no point or one, more '
    'than 100,000, times not finite, negative, beyond 1e6 s or not increasing, velocities or '
    'accelerations on only some points, a zero quaternion, a turn of half a revolution or more '
    'between two waypoints, a path of fewer than two different poses, a malformed '
    '`time_from_start` (`nanosec` not below 1e9).')
TRAJECTORY_TOO_LONG = _register(
    'trajectory_too_long', 'refusal',
    '`check_trajectory`, `plan_motion` (trajectory_node)',
    'A trajectory whose check would take more than 1,000,000 samples (at most 256 between two '
    'waypoints): refused before any sample is computed, with the count.')
SUPERSEDED = _register(
    'superseded', 'refusal',
    'trajectory_node (`pose_trajectory`, `pose_path`)',
    'A trajectory or path replaced by a newer one before it was decided (the newest message is '
    'planned; the one under way is cancelled).')
PLANNING_ERROR = _register(
    'planning_error', 'refusal',
    'trajectory_node (`pose_trajectory`, `pose_path`)',
    'An unexpected error while planning (a bug): the message gives the error; the node goes '
    'on.')

# The follow_joint_trajectory action (trajectory_node) ---------------------------------------

INVALID_JOINTS = _register(
    'invalid_joints', 'refusal',
    'trajectory_node (`follow_joint_trajectory`: result `INVALID_JOINTS`)',
    'A goal whose joint names are not exactly one joint set: the six leg joints '
    '(`joint_names`) or the six Cartesian joints (`action_cartesian_joints`), in any order; '
    'the message names the unknown, missing or repeated joints (a tolerance naming a joint the '
    'goal does not move too).')
INVALID_GOAL = _register(
    'invalid_goal', 'refusal',
    'trajectory_node (`follow_joint_trajectory`: result `INVALID_GOAL`)',
    'A goal that cannot be played as given: no points, sizes that do not match the joints, '
    'values not finite or beyond 1e6, times not increasing, a last point that does not rest, '
    'efforts, a `multi_dof_trajectory`, an illegal tolerance, a malformed time (`nanosec` not '
    'below 1e9), a first point at time 0 away '
    "from the current state, no `joint_states` yet; the planner's refusals (limits, "
    'retiming) answer `INVALID_GOAL` with their own code and reason in `error_string`.')
OLD_HEADER_TIMESTAMP = _register(
    'old_header_timestamp', 'refusal',
    'trajectory_node (`follow_joint_trajectory`: result `OLD_HEADER_TIMESTAMP`)',
    'A goal with a non-zero header stamp whose end (stamp plus the last `time_from_start`) is '
    'already past, as joint_trajectory_controller refuses it.')
PATH_TOLERANCE_VIOLATED = _register(
    'path_tolerance_violated', 'refusal',
    'trajectory_node (`follow_joint_trajectory`: result `PATH_TOLERANCE_VIOLATED`)',
    'While a goal ran, a measured joint (from `joint_states`) left its path tolerance: the '
    'joint, the error, the tolerance and the excess; the platform is braked to rest.')
GOAL_TOLERANCE_VIOLATED = _register(
    'goal_tolerance_violated', 'refusal',
    'trajectory_node (`follow_joint_trajectory`: result `GOAL_TOLERANCE_VIOLATED`)',
    'A goal whose measured end state was not within its goal tolerance by the end time plus '
    '`goal_time_tolerance`: the joint, the error, the tolerance and the excess.')
GOAL_PREEMPTED = _register(
    'goal_preempted', 'refusal',
    'trajectory_node (`follow_joint_trajectory`: result `INVALID_GOAL`)',
    'A goal replaced by a newer goal, or by a trajectory on `pose_trajectory` or `pose_path`, '
    'as joint_trajectory_controller answers it (aborted, `INVALID_GOAL`, "Current goal '
    'preempted by new incoming action."); the platform brakes to rest on its path first.')


# Motion cueing (motion_cueing_node) ---------------------------------------------------------

INVALID_VEHICLE_MOTION = _register(
    'invalid_vehicle_motion', 'refusal',
    '`MotionCueing` (motion_cueing_node: `vehicle_imu`)',
    'A specific force or angular velocity that is not three finite numbers, or beyond '
    '`max_specific_force` or `max_angular_velocity`; the platform takes the step as if the '
    'vehicle were at rest, so that bad input eases it back to neutral.')
INVALID_PREVIEW = _register(
    'invalid_preview', 'refusal',
    '`MotionCueing.set_preview` (motion_cueing_node: `vehicle_preview`)',
    "A preview of the vehicle's motion that cannot be used: a point without its specific "
    'force or angular velocity, times that do not increase, a value that is not finite or '
    'beyond `max_specific_force` or `max_angular_velocity`, a frame that cannot be placed in '
    'the vehicle frame, or a cueing that is not `mpc`. The preview before it stays in use.')
TIME_NOT_INCREASING = _register(
    'time_not_increasing', 'refusal',
    '`MotionCueing` (motion_cueing_node: `vehicle_imu`)',
    'A sample whose time (`header.stamp`) is not after the previous one: repeated, backward '
    'or not finite, or malformed (`nanosec` of 1e9 or more); nothing moves.')
INPUT_GAP = _register(
    'input_gap', 'warning',
    '`MotionCueing` (motion_cueing_node)',
    'More than `max_input_gap` since the previous sample: counted as `max_input_gap` (the '
    "washout's clock pauses).")
CUE_SCALED = _register(
    'cue_scaled', 'warning',
    '`MotionCueing` (motion_cueing_node)',
    'The cue was scaled toward neutral to keep inside the limits model (with its margins); '
    'the details give the workspace and tilt scales.')
ACTUATOR_LIMITED = _register(
    'actuator_limited', 'warning',
    '`MotionCueing` (motion_cueing_node)',
    'The cue asked more leg velocity or acceleration than the actuators allow: the platform '
    'followed as closely as they allow (or braked, or headed home).')
MPC_FALLBACK = _register(
    'mpc_fallback', 'warning',
    '`MotionCueing` (motion_cueing_node, `cueing_method: mpc`)',
    "The model-predictive cueing's QP was not solved (infeasible, out of iterations): the rest "
    'of the last plan was applied, or, once it ran out, the cue braked to rest; the limiter '
    'keeps every limit all the same.')
CUEING_HELD = _register(
    'cueing_held', 'warning',
    '`MotionCueing` (motion_cueing_node: `vehicle_imu`)',
    'A sample not cued because the platform is parked, starting from park, stopping to park '
    'or paused (the start, stop, pause and resume services): its time is kept, nothing else.')
GAIN_REFUSED = _register(
    'gain_refused', 'refusal',
    '`MotionCueing.set_gains` (motion_cueing_node: `cueing_intensity`, the `*_scale` '
    'parameters)',
    'A change of intensity or of a channel gain that is not a number in its range, or whose '
    "cue of the reference input would leave the platform's travel within the cue margins "
    '(`gain_check_specific_force`, `gain_check_angular_velocity`); the gains stay as they were.')


# The telemetry bridge (telemetry_bridge) ----------------------------------------------------

MALFORMED_PACKET = _register(
    'malformed_packet', 'refusal',
    '`TelemetryDecoder` (telemetry_bridge: its UDP port)',
    'A datagram that is not a telemetry packet: not 68 bytes, another magic, another version '
    'or reserved flags set (the layout: `cueing/telemetry_packet.py`, and the simulator '
    'how-to). Nothing is published.')
INVALID_PACKET_VALUES = _register(
    'invalid_packet_values', 'refusal',
    '`TelemetryDecoder` (telemetry_bridge: its UDP port)',
    'A telemetry packet whose specific force or angular velocity is not finite or beyond '
    '1000 m/s^2 or 100 rad/s, or whose timestamp is beyond a ROS time. Nothing is published.')
PACKET_OUT_OF_ORDER = _register(
    'packet_out_of_order', 'refusal',
    '`TelemetryDecoder` (telemetry_bridge: its UDP port)',
    'A telemetry packet whose sequence number or timestamp is not after the last accepted '
    "packet's: a duplicate, or one overtaken on the way. Nothing is published; after "
    '`telemetry_timeout` of silence any sequence number starts a new stream.')

# The geometry report (stewart_geometry) ---------------------------------------------------

_by_report = '`geometry_report` (`stewart_geometry`)'
LIMIT_BROKEN_AT_HOME = _register(
    'limit_broken_at_home', 'warning', _by_report,
    'The home pose breaks a limit (the stroke, the singularity margin): the geometry is '
    'refused and no node starts with these files until the home pose or the limit changes.')
LEGS_COLLIDE_AT_HOME = _register(
    'legs_collide_at_home', 'warning', _by_report,
    'Two legs that share no joint come closer than `2 * leg_radius` at home (the geometry is '
    'refused), or, without `leg_radius`, their axes come within 1 % of the platform radius: '
    'a leg or joint is probably misplaced, or two joints meant to be one are not.')
NEAR_SINGULAR_HOME = _register(
    'near_singular_home', 'warning', _by_report,
    'The condition number at home is above 20 or above half of `max_jacobian_condition`: a '
    'home pose near a singularity (for example a 3-3 platform turned 90 degrees).')
JOINTS_NEARLY_SHARED = _register(
    'joints_nearly_shared', 'warning', _by_report,
    'Two joints of the base or of the platform lie within 1 % of its size but count as two: '
    'if they are one joint shared by two legs, give both legs the same coordinates.')
OTHER_MODE_WITHIN_LIMITS = _register(
    'other_mode_within_limits', 'warning', _by_report,
    "Another assembly mode has home's leg lengths and keeps every limit: the leg lengths "
    'alone do not tell the two apart (see the assembly-mode guard of fk_node).')


# Payload identification (stewart_payload) ---------------------------------------------------

PAYLOAD_UNOBSERVABLE = _register(
    'payload_unobservable', 'warning',
    '`identify_payload` (`stewart_payload`)',
    "The measured poses cannot separate a component of the payload's centre of mass from the "
    'rest (a singular value of the scaled fit below the largest over `max_condition`): poses '
    'all at one tilt, such as all level, see the centre only across gravity, not its height. '
    'The component is kept from the parameter file and named, with the condition number.')

# The simulated platform (mock_platform) ------------------------------------------------------

INVALID_LEG_COMMAND = _register(
    'invalid_leg_command', 'refusal',
    '`MockActuators`, `trajectory_command` (mock_platform: `leg_lengths`, `joint_commands`, '
    '`leg_trajectory`)',
    'A leg command mock_platform cannot follow: not six values (or the joint names missing or '
    'repeated), a value not finite, a length outside the stroke, or a trajectory with no '
    'point, times not increasing or malformed (`nanosec` not below 1e9), absurd velocities or '
    'one that ended in the past. The legs '
    'keep following the last valid command.')
CLOCK_JUMP = _register(
    'clock_jump', 'warning',
    '`MockActuators.advance` (mock_platform)',
    "The node's clock went back, or jumped forward by more than `max_time_step`: the legs "
    'hold for that step, or move only as far as `max_time_step` allows; never a jump.')


def codes_table() -> str:
    """
    Return the documentation's table of every code: code, kind, who emits it, what it means.

    Markdown, one row per code of :data:`CODES`, in their order; doc/safety.md shows it (the
    ``{refusal-codes}`` directive of doc/ext/stewart_docs.py renders it when the site is built).
    """
    lines = ['| Code | Kind | Emitted by | Meaning |', '| --- | --- | --- | --- |']
    lines += [f'| `{code.code}` | {code.kind} | {code.emitted_by} | {code.meaning} |'
              for code in CODES.values()]
    return '\n'.join(lines)


@dataclass(frozen=True)
class Finding:
    """
    One reason to refuse an input, or to warn about an accepted one.

    :param code: short and stable, such as ``out_of_limits``: one of :data:`CODES`.
    :param message: a sentence a user can act on, with the values concerned.
    :param details: ``(key, value)`` pairs of text, such as ``('iterations', '50')``.
    """

    code: str
    message: str
    details: Tuple[Tuple[str, str], ...] = ()

    def __str__(self):
        return self.message


class Decision:
    """
    What every result of a decision object says: accepted, or refused and why.

    A subclass is a dataclass with a ``refusal`` field (a :class:`Finding`, or ``None`` when
    the input was accepted) and a ``warnings`` field (findings about an accepted input).
    """

    @property
    def accepted(self) -> bool:
        """Whether the input was accepted."""
        return self.refusal is None

    @property
    def reason(self) -> str:
        """Why the input was refused, as a sentence; ``''`` when it was accepted."""
        return '' if self.refusal is None else self.refusal.message


def violation_details(violations) -> Tuple[Tuple[str, str], ...]:
    """
    ``(key, value)`` pairs of :class:`~stewart_kinematics.limits.Violation`, for a Finding.

    The key names the limit and the leg or legs (``leg_length_max leg 3``, ``leg_collision
    legs 2 and 3``), the value gives the value reached, the limit and the excess, with their
    unit.
    """
    pairs = []
    for violation in violations:
        unit = f' {violation.unit}' if violation.unit else ''
        key = violation.limit + (f' {violation.subject}' if violation.leg else '')
        pairs.append((key, f'{violation.value:.6g}{unit} (limit {violation.allowed:.6g}{unit}, '
                           f'excess {violation.excess:.3g}{unit})'))
    return tuple(pairs)


def out_of_limits(subject: str, violations) -> Finding:
    """
    Build the refusal of something that breaks limits, listing every violation.

    :param subject: what breaks them, with its verb, such as ``'the pose is'``.
    :param violations: the :class:`~stewart_kinematics.limits.Violation` list, not empty.
    """
    return Finding(OUT_OF_LIMITS,
                   f'{subject} out of the limits: ' + '; '.join(map(str, violations)),
                   violation_details(violations))
