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
The forward kinematics side's decision: measured leg lengths in, a trusted pose or the reason out.

:class:`PoseTracker` follows a moving platform from its leg lengths, as fk_node does and as a
Python user's own loop can::

    tracker = PoseTracker(load_geometry('config/paper_platform.yaml'))
    estimate = tracker.update(measured_lengths)    # six leg lengths, metres
    if estimate.accepted:
        use(estimate.pose)                          # [X, Y, Z, alpha, beta, gamma]
    else:
        print(estimate.reason)                      # e.g. a jump to another assembly mode
    for warning in estimate.warnings:               # e.g. near a singularity
        print(warning)
    twist = tracker.twist(leg_velocities)           # at the last accepted pose
    estimate.tool_pose, twist.tool_twist            # the tool frame's, as fk_node publishes
    estimate = tracker.update(lengths, velocities)  # a joint state: the pose and its twist
    tracker.reset()                                 # homing: the next solve starts from home
    if estimate.ambiguous:                          # maybe another assembly mode (a fold
        tracker.anchor(known_pose)                  # was crossed): re-anchor at a known pose

Each update checks the lengths against the actuator stroke, solves by Newton-Raphson from the
last accepted solution (its pose and its Jacobian: a platform moves continuously), falls back
to the home pose when that fails, and then refuses a solution that did not converge, whose
pose error bound exceeds ``pose_tolerance`` (near a singularity), that breaks a limit of the
geometry, or that jumped to another assembly mode; an accepted solution near a singularity
comes with a warning. With leg velocities too (a joint state), an accepted pose carries its
twist, or a warning that says why there is none. What fk_node publishes of an estimate is the
tool frame's (:class:`~stewart_kinematics.FrameTree` given to the tracker): its pose in the base
frame (:attr:`PoseEstimate.tool_pose`) and in the frame of the stamped pose
(:attr:`PoseEstimate.framed_tool_pose`, ``estimated_pose_frame``), and its twist about the tool
frame's origin (:attr:`PoseEstimate.tool_twist`, :attr:`TwistEstimate.tool_twist`). Every
limit is the limits model's (:class:`~stewart_kinematics.limits.LimitModel`). What fk_node
reports of the tracker on ``/diagnostics`` is :mod:`.tracker_status`'s. Nothing raises for
lengths it cannot use, and nothing here imports ROS.

Continuity proves the assembly mode only while the estimate stays away from singularities:
where a fold is crossed, two modes meet, and the lengths cannot tell which one the platform
went on in. From the first sign of that (a solution beyond the singularity margin, a change of
sign of the Jacobian's determinant, a solve that failed, jumped or fell back to home, or an
assembly-mode margin below its warning distance, given by :meth:`PoseTracker.note_margin`)
every accepted estimate carries an ``ambiguous_estimate`` warning and ``ambiguous`` is True,
until the tracker is re-anchored: :meth:`PoseTracker.reset`, :meth:`PoseTracker.anchor` (a
known pose), or a margin that finds no other real mode the platform could be in. The rules and
their reasons: doc/assembly_modes.md.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.analysis.assembly_modes import start_ambiguity
from stewart_kinematics.findings import Decision, Finding
from stewart_kinematics.limits import LimitModel, limits_of
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.forward import solve_trusted
from stewart_kinematics.model.forward_result import ForwardKinematicsResult
from stewart_kinematics.model.frames import FrameTree
from stewart_kinematics.model.inputs import as_leg_lengths, as_poses
from stewart_kinematics.model.rotations import (
    euler_zyx_to_matrix,
    matrix_to_euler_zyx,
    rotation_angle_between,
)
from stewart_kinematics.model.velocities import platform_twist, SingularPoseError
from stewart_kinematics.parameters.settings import SolverSettings
from stewart_kinematics.pose_decisions.pose_commands import CommandCheck, LegCommand


@dataclass(frozen=True, eq=False)
class PoseEstimate(Decision):
    """
    The answer to a set of leg lengths: the pose, or why none was accepted.

    :param pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,); ``None``
        when refused.
    :param refusal: why the lengths were refused, with details, or ``None`` when accepted.
    :param warnings: findings about an accepted pose (near a singularity).
    :param solution: the forward kinematics result the decision was made on, or ``None`` when
        no solve ran (lengths malformed or out of the stroke).
    :param twist: with leg velocities given, the platform twist at the accepted pose
        (``[vx, vy, vz, wx, wy, wz]``, base frame); ``None`` otherwise, or when the velocities
        gave none (the reason is then among the warnings: the pose itself was accepted).
    :param ambiguous: True while the tracker's estimates may be in another assembly mode than
        the platform (:attr:`PoseTracker.ambiguity`, then also among the warnings of an
        accepted pose): re-anchor the tracker.
    :param frames: the tracker's :class:`~stewart_kinematics.FrameTree` (its tool frame) when
        the estimate was made, or ``None``: the platform frame is the tool frame.
    :param pose_frame: the frame :attr:`framed_tool_pose` is given in (the base frame or the
        user frame; fk_node's ``estimated_pose_frame``).
    """

    pose: Optional[np.ndarray]
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()
    solution: Optional[ForwardKinematicsResult] = None
    twist: Optional[np.ndarray] = None
    ambiguous: bool = False
    frames: Optional[FrameTree] = None
    pose_frame: str = ''

    @property
    def tool_pose(self) -> Optional[np.ndarray]:
        """Return the tool frame's pose in the base frame (X, Y, Z, alpha, beta, gamma) or None."""
        if self.pose is None or self.frames is None:
            return self.pose
        return self.frames.tool_pose_vector(self.pose)

    @property
    def framed_tool_pose(self) -> Optional[np.ndarray]:
        """Return the tool frame's pose in :attr:`pose_frame` (metres, radians), or ``None``."""
        if self.pose is None or self.frames is None:
            return self.pose
        return self.frames.tool_pose_vector(self.pose, self.pose_frame)

    @property
    def tool_twist(self) -> Optional[np.ndarray]:
        """Return :attr:`twist` about the tool frame's origin (base frame), or ``None``."""
        return _tool_twist(self.twist, self.pose, self.frames)

    @property
    def iterations(self) -> Optional[int]:
        """Newton-Raphson steps of the solve, or ``None`` when none ran."""
        return None if self.solution is None else self.solution.iterations

    @property
    def residual(self) -> Optional[float]:
        """Largest leg length error of the solution, metres, or ``None``."""
        return None if self.solution is None else self.solution.residual

    @property
    def condition(self) -> Optional[float]:
        """Condition number of the dimensionless Jacobian at the solution, or ``None``."""
        return None if self.solution is None else self.solution.condition

    @property
    def pose_error_bound(self) -> Optional[float]:
        """Proven bound on the pose error of the solution, metres and radians, or ``None``."""
        return None if self.solution is None else self.solution.pose_error_bound


@dataclass(frozen=True, eq=False)
class PoseAnchor(Decision):
    """
    The answer to a known pose given to :meth:`PoseTracker.anchor`: taken, or why not.

    :param pose: the platform frame's pose in the base frame the tracker now starts from,
        ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians); ``None`` when refused.
    :param lengths: its leg lengths, metres, shape (6,); ``None`` when refused.
    :param refusal: why the pose was refused (``invalid_pose``, ``wrong_frame``,
        ``unreachable``, ``out_of_limits``), or ``None`` when taken.
    :param warnings: findings about the input (a quaternion that was not unit).
    """

    pose: Optional[np.ndarray]
    lengths: Optional[np.ndarray] = None
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()


@dataclass(frozen=True, eq=False)
class TwistEstimate(Decision):
    """
    The platform twist of a set of leg velocities, or why none was given.

    :param twist: ``[vx, vy, vz, wx, wy, wz]`` of the platform frame's origin, base frame,
        m/s and rad/s; ``None`` when refused.
    :param refusal: why, or ``None`` when accepted.
    :param pose: the platform pose the twist is at (the tracker's last pose), shape (6,).
    :param frames: the tracker's frame tree, or ``None``.
    """

    twist: Optional[np.ndarray]
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()
    pose: Optional[np.ndarray] = None
    frames: Optional[FrameTree] = None

    @property
    def tool_twist(self) -> Optional[np.ndarray]:
        """Return :attr:`twist` about the tool frame's origin (base frame), or ``None``."""
        return _tool_twist(self.twist, self.pose, self.frames)


def _tool_twist(twist, pose, frames):
    """Return a platform origin's twist at ``pose`` about the tool frame's origin."""
    if twist is None or frames is None or pose is None:
        return twist
    return frames.tool_twist_from_platform(twist, euler_zyx_to_matrix(pose[3:]))


class PoseTracker:
    """
    Follow the platform's pose from its measured leg lengths, refusing what cannot be trusted.

    State: the last accepted solution (:attr:`last_pose`, :attr:`last_lengths`,
    :attr:`last_solution`), where the next solve starts and what the assembly-mode guard
    compares with; :meth:`reset` forgets it, :meth:`anchor` replaces it with a known pose.
    And whether continuity since then still proves the assembly mode (:attr:`ambiguity`).

    :param geometry: the platform and its limits (:class:`stewart_kinematics.Geometry`).
    :param settings: the solver's tolerance, iterations and checks (fk_node's solver
        parameters); default: every default, ``SolverSettings()``.
    :param frames: the :class:`~stewart_kinematics.FrameTree` whose tool frame the estimates
        are published as, and whose frames a known pose may be given in
        (:meth:`anchor_tool_pose`); default: ``FrameTree()`` (the platform frame is the tool).
    :param pose_frame: the frame of :attr:`PoseEstimate.framed_tool_pose` (fk_node's
        ``estimated_pose_frame``): ``''`` for the base frame, or the user frame.
    :raises ValueError: for a ``pose_frame`` that ``frames`` cannot place.
    """

    def __init__(self, geometry, settings: Optional[SolverSettings] = None,
                 frames: Optional[FrameTree] = None, pose_frame: str = ''):
        self.geometry = geometry
        self.settings = SolverSettings() if settings is None else settings
        #: The frame tree of the outputs and of a known pose; the frame of the stamped pose
        #: (its name: the base frame's for ``''``).
        self.frames, self.pose_frame, self._pose_frame = FrameTree(), '', ''
        self.set_frames(FrameTree() if frames is None else frames, pose_frame)
        #: The limits a solution must keep: the geometry's (stroke, cones, margin, collisions).
        self.limits = LimitModel.of_geometry(geometry)
        #: The pose the next solve starts from: the last accepted one, or home after a reset.
        self.last_pose = geometry.home_pose
        #: The leg lengths of the last accepted pose, metres, or ``None`` after a reset.
        self.last_lengths = None
        #: The forward kinematics result of the last accepted pose, whose Jacobian the next
        #: solve reuses; ``None`` after a reset.
        self.last_solution = None
        #: After a start or reset: the last start_ambiguity check, with its lengths.
        self._start_check = None
        #: Why the estimate may be in another assembly mode than the platform (an
        #: ``ambiguous_estimate`` finding, the first sign since the last anchor), or ``None``
        #: while continuity since the last anchor proves the mode.
        self.ambiguity: Optional[Finding] = None
        #: How the tracker was last anchored, in words.
        self.anchored_by = 'the start, at the home pose'
        #: Poses accepted so far: the number of the last one, which tags its assembly-mode
        #: margin for :meth:`note_margin`.
        self.accepted_count = 0
        #: ``accepted_count`` at the last anchor; a margin of a pose numbered from
        #: ``_resolvable_from`` on, after the last sign of ambiguity, may clear it.
        self._anchored_at = 0
        self._resolvable_from = 1
        #: Checks a known pose (frames, quaternion, limits) as ik_node checks a command.
        self._anchor_check = CommandCheck(geometry)

    def set_frames(self, frames: FrameTree, pose_frame: Optional[str] = None) -> None:
        """
        Take a new frame tree (a tool frame changed at run time) from the next estimate on.

        :param frames: a :class:`~stewart_kinematics.FrameTree`.
        :param pose_frame: the frame of the stamped pose, ``''`` for the base frame; ``None``
            keeps the one set.
        :raises ValueError: for a frame the tree cannot place (nothing changes then).
        """
        if not isinstance(frames, FrameTree):
            raise TypeError(f'frames must be a FrameTree, got {type(frames).__name__}')
        pose_frame = self._pose_frame if pose_frame is None else pose_frame
        frames.reference(pose_frame)   # raises for a frame poses cannot be given in
        self.frames, self._pose_frame = frames, pose_frame
        self.pose_frame = pose_frame or frames.base_frame

    def configure(self, settings: SolverSettings):
        """
        Take new settings from the next update on, such as ``settings.replace(tolerance=1e-10)``.

        The state (the last solution) is kept.
        """
        if not isinstance(settings, SolverSettings):
            raise TypeError(f'settings must be SolverSettings, got {type(settings).__name__}')
        self.settings = settings

    def set_mass_properties(self, geometry):
        """
        Judge solutions with the masses of ``geometry`` (a new payload) from the next update on.

        The state (the last solution, the anchor) is kept.

        :param geometry: the tracker's geometry carrying other masses
            (:meth:`stewart_kinematics.Geometry.with_mass_properties`): its joints, home pose
            and limits must be the tracker's.
        """
        self.geometry = geometry
        self.limits = LimitModel.of_geometry(geometry)
        self._anchor_check = CommandCheck(geometry)

    @property
    def ambiguous(self) -> bool:
        """Whether the estimate may be in another assembly mode (:attr:`ambiguity` says why)."""
        return self.ambiguity is not None

    @property
    def poses_since_anchor(self) -> int:
        """Poses accepted since the tracker was last anchored."""
        return self.accepted_count - self._anchored_at

    def reset(self, pose=None):
        """
        Forget the last solution: the next solve starts from ``pose``, by default home.

        For homing and restarts. The assembly-mode guard has nothing to compare the next
        solution with, so it accepts whichever assembly mode that start leads to (or, with
        ``refuse_ambiguous_start``, refuses lengths that several modes within the limits
        share). The tracker counts as anchored: the platform is taken to be near ``pose``.

        :param pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,).
        :raises ValueError: if ``pose`` is malformed.
        """
        start = self.geometry.home_pose if pose is None else as_poses(pose, 'reset pose')
        if start.shape != (6,):
            raise ValueError(f'reset pose must have shape (6,), got {start.shape}')
        self.last_pose = np.array(start)
        self.last_lengths = None
        self.last_solution = None
        self._start_check = None
        self._anchor('a reset' if pose is None else 'a reset at a given pose')

    def anchor(self, pose) -> PoseAnchor:
        """
        Take a known pose of the platform (homing, a camera, a probe): the tracker re-anchors.

        The estimate is unambiguous again (:attr:`ambiguity` cleared); the next solve starts
        from ``pose``, and the assembly-mode guard compares its solution with ``pose`` and
        its leg lengths, so lengths that differ from these by at most
        ``assembly_guard_length_change`` must lead near it. Give the pose the platform has
        now. A pose that is malformed, unreachable or beyond a limit is refused, the state
        unchanged.

        :param pose: the platform frame in the base frame, ``[X, Y, Z, alpha, beta, gamma]``
            (metres, radians), shape (6,).
        :returns: a :class:`PoseAnchor`.
        """
        try:
            values = as_float_array(pose, 'anchor pose')
        except ValueError as error:
            return PoseAnchor(None, refusal=Finding(findings.INVALID_POSE, str(error)))
        if values.shape != (6,) or not all(map(math.isfinite, values.tolist())):
            return PoseAnchor(None, refusal=Finding(
                findings.INVALID_POSE,
                'an anchor pose must be six finite numbers [X, Y, Z, alpha, beta, gamma] '
                f'(metres, radians), got {preview(values)}'))
        return self._take_anchor(self._anchor_check.pose_vector(values))

    def anchor_tool_pose(self, position, quaternion, frames=None,
                         frame_id: str = '') -> PoseAnchor:
        """
        :meth:`anchor` at a known pose of the tool frame, given in a frame, as a message has it.

        Converted and checked as ik_node converts a commanded pose
        (:meth:`stewart_kinematics.CommandCheck.tool_pose`): ``frame_id`` ``base_frame``,
        ``user_frame`` or ``''``, a non-unit quaternion normalised with a warning.

        :param position: the tool frame's origin in ``frame_id``, metres, three numbers.
        :param quaternion: its orientation ``(x, y, z, w)``.
        :param frames: the :class:`stewart_kinematics.FrameTree`, or ``None``: the tracker's
            own (:attr:`frames`).
        :param frame_id: the frame the pose is given in.
        :returns: a :class:`PoseAnchor`.
        """
        return self._take_anchor(self._anchor_check.tool_pose(
            position, quaternion, self.frames if frames is None else frames, frame_id))

    def _take_anchor(self, command: LegCommand) -> PoseAnchor:
        """Anchor at the pose of a command the limits accepted, or refuse it."""
        if not command.accepted:
            return PoseAnchor(None, refusal=command.refusal, warnings=command.warnings)
        pose = np.concatenate([command.position, matrix_to_euler_zyx(command.rotation)])
        # The pose solves its own lengths at once: a solution to start from, with its sign.
        # The command's lengths and pose were checked where the pose entered (CommandCheck).
        solution = solve_trusted(self.geometry, command.lengths.tolist(), pose,
                                 self.settings.tolerance, self.settings.max_iterations)
        self.last_pose, self.last_lengths = solution.pose, command.lengths
        self.last_solution = solution if solution.converged else None
        self._start_check = None
        self._anchor('a known pose')
        return PoseAnchor(solution.pose, command.lengths, warnings=command.warnings)

    def _anchor(self, how: str):
        """Clear the ambiguity: the estimate is anchored, ``how`` (in words)."""
        self.ambiguity = None
        self.anchored_by = how
        self._anchored_at = self.accepted_count
        self._resolvable_from = self.accepted_count + 1

    def note_margin(self, margin, pose_number: int, warning_distance: float,
                    lengths=None) -> bool:
        """
        Take the assembly-mode margin of an accepted pose: it may flag the estimate, or clear it.

        A margin below ``warning_distance`` (another real mode within the limits that near)
        flags it: a motion of that size could have taken the platform into that mode. A
        margin that rules out every other mode (its ``rules_out_other_modes``) clears it, if
        the pose came after the last sign of ambiguity: the platform was then at that pose,
        whatever happened before, and continuity holds since. A margin of a pose before the
        last anchor is ignored. Whether the other modes are ruled out depends on the lengths
        alone (the estimate, accepted, is within the limits): a margin of the lengths of the
        last accepted pose counts as that pose's, whatever its number (a platform at rest,
        whose margin is not computed again).

        :param margin: an :class:`~stewart_kinematics.analysis.assembly_modes.AssemblyModeMargin`
            of an accepted pose (from :func:`stewart_kinematics.assembly_mode_margin`, or
            fk_node's monitor).
        :param pose_number: that pose's number, :attr:`accepted_count` just after it was
            accepted.
        :param warning_distance: the margin below which another mode is within reach, metres
            (fk_node: ``assembly_mode_margin_warning``); 0 for never.
        :param lengths: the leg lengths the margin is for, metres, or ``None``.
        :returns: whether the margin cleared the ambiguity.
        :raises TypeError: if ``pose_number`` is not an int.
        """
        if not isinstance(pose_number, int) or isinstance(pose_number, bool):
            raise TypeError(f'pose_number must be an int, got {type(pose_number).__name__}')
        if (lengths is not None and self.accepted_count > self._anchored_at
                and np.array_equal(lengths, self.last_lengths)):
            pose_number = self.accepted_count
        if not self._anchored_at < pose_number <= self.accepted_count:
            return False
        if margin.distance < warning_distance:
            self._flag('assembly_mode_margin', (
                f'another assembly mode within the limits lay {margin.position:.4g} m and '
                f'{math.degrees(margin.angle):.4g} deg from an estimate (combined distance '
                f'{margin.distance:.4g} m < {warning_distance:g} m)'),
                (('margin_distance_m', f'{margin.distance:.4g}'),), pose_number + 1)
            return False
        if self.ambiguity is None or not (margin.rules_out_other_modes
                                          and pose_number >= self._resolvable_from):
            return False
        self._anchor(f'pose {pose_number}, where no other real assembly mode lay within the '
                     'limits')
        return True

    def follow_margin(self, monitor) -> bool:
        """
        One round of the assembly-mode margin: ask for the last pose's, take the latest one.

        fk_node calls it every ``assembly_mode_margin_period``: the monitor computes the
        margin of the last accepted pose in the background (only when the lengths changed),
        and the latest margin it reported goes to :meth:`note_margin`, which may flag the
        estimate ambiguous or re-anchor the tracker.

        :param monitor: an :class:`~stewart_kinematics.analysis.assembly_modes.
            AssemblyModeMarginMonitor` of this tracker's geometry.
        :returns: whether the latest margin cleared the ambiguity.
        """
        monitor.request(self.last_pose, self.last_lengths, tag=self.accepted_count)
        if monitor.latest is None or monitor.latest_tag is None:
            return False
        return self.note_margin(monitor.latest, monitor.latest_tag, monitor.warning_distance,
                                monitor.latest_lengths)

    def update(self, lengths, velocities=None) -> PoseEstimate:
        """
        Estimate the pose of measured leg lengths, or refuse them with the reason.

        :param lengths: leg lengths l_1..l_6, metres, shape (6,).
        :param velocities: their rates l_1'..l_6', m/s, shape (6,), or ``None``: with them an
            accepted pose carries its twist (:meth:`twist`), or a warning saying why not; the
            pose is published either way.
        :returns: a :class:`PoseEstimate`; an accepted one becomes the last solution.

        The lengths are checked here, once, where they enter the core (fk_node only converts a
        message's numbers): refused with ``invalid_lengths`` unless six finite, positive
        numbers, then solved without a second check.
        """
        try:
            lengths = as_leg_lengths(lengths)
            if lengths.shape != (6,):
                raise ValueError(f'expected the 6 lengths of one pose, got shape '
                                 f'{lengths.shape}')
        except ValueError as error:
            return PoseEstimate(None, Finding(findings.INVALID_LENGTHS, str(error)))
        violations = self.limits.leg_state_violations(lengths=lengths)
        if violations:
            return PoseEstimate(None, findings.out_of_limits('the leg lengths are', violations))
        lengths = np.array(lengths, dtype=float)
        solution, fell_back = self._solve(lengths)
        refusal = self._refusal(lengths, solution)
        evidence = self._fold_evidence(solution, refusal, fell_back)
        if evidence is not None:
            self._flag(*evidence, self.accepted_count + 1)
        if refusal is not None:
            return PoseEstimate(None, refusal, solution=solution, ambiguous=self.ambiguous,
                                frames=self.frames, pose_frame=self.pose_frame)
        warnings = ()
        if solution.condition > self.settings.near_singularity_condition:
            warnings = (Finding(
                findings.NEAR_SINGULARITY,
                f'estimated pose is near a singularity: Jacobian condition number '
                f'{solution.condition:.4g} > near_singularity_condition '
                f'{self.settings.near_singularity_condition:g}',
                (('jacobian_condition', f'{solution.condition:.4g}'),)),)
        self.last_pose, self.last_lengths, self.last_solution = solution.pose, lengths, solution
        self.accepted_count += 1
        if self.ambiguity is not None:
            warnings += (self.ambiguity,)
        twist = None
        if velocities is not None:
            estimate = self.twist(velocities)
            twist = estimate.twist
            warnings += () if estimate.accepted else (estimate.refusal,)
        return PoseEstimate(solution.pose, None, warnings, solution, twist, self.ambiguous,
                            self.frames, self.pose_frame)

    def twist(self, velocities) -> TwistEstimate:
        """
        Estimate the platform twist of leg velocities at the last accepted pose.

        Before any pose was accepted, at the home pose (or the pose of :meth:`reset`). Refused
        where the Jacobian's condition number exceeds the singularity margin, the
        smaller of ``near_singularity_condition`` and the geometry's
        ``max_jacobian_condition``: there the leg velocities hardly determine the twist, and
        their errors come out amplified as many times.

        :param velocities: leg velocities l_1'..l_6', metres per second, shape (6,).
        :returns: a :class:`TwistEstimate`, ``[vx, vy, vz, wx, wy, wz]`` in the base frame.
        """
        try:
            velocities = as_float_array(velocities, 'leg velocities')
        except ValueError as error:
            return TwistEstimate(None, Finding(findings.INVALID_VELOCITIES, str(error)))
        if velocities.shape != (6,) or not np.all(np.isfinite(velocities)):
            return TwistEstimate(None, Finding(
                findings.INVALID_VELOCITIES,
                f'leg velocities must be six finite numbers (m/s), got {preview(velocities)}'))
        margin = self.singularity_margin
        try:
            return TwistEstimate(platform_twist(self.geometry, self.last_pose, velocities,
                                                max_condition=margin),
                                 pose=self.last_pose, frames=self.frames)
        except SingularPoseError as error:
            return TwistEstimate(None, Finding(
                findings.NEAR_SINGULARITY,
                f'{error} (the singularity margin: the smaller of near_singularity_condition '
                f'and max_jacobian_condition)'))
        except ValueError as error:   # a twist beyond the float range
            return TwistEstimate(None, Finding(findings.INVALID_VELOCITIES, str(error)))

    @property
    def singularity_margin(self) -> float:
        """
        Give the condition number beyond which a pose counts as near a singularity.

        The smaller of ``near_singularity_condition`` and the geometry's
        ``max_jacobian_condition``: beyond it no twist is given, and an estimate that comes
        there is flagged ambiguous.
        """
        return min(self.settings.near_singularity_condition,
                   limits_of(self.geometry).max_jacobian_condition)

    def _solve(self, lengths) -> Tuple[ForwardKinematicsResult, bool]:
        """
        Solve from the last solution (with its Jacobian), then from home if that fails.

        :param lengths: the six lengths :meth:`update` checked where they entered: solved
            without a second check (:func:`~stewart_kinematics.model.forward.solve_trusted`,
            the same solve as ``forward_kinematics``).
        :returns: the solution, and whether it came from the fallback start at home.
        """
        options = (self.settings.tolerance, self.settings.max_iterations)
        target = lengths.tolist()
        start = self.last_solution if self.last_solution is not None else self.last_pose
        solution = solve_trusted(self.geometry, target, start, *options)
        if not solution.converged and not np.array_equal(self.last_pose,
                                                         self.geometry.home_pose):
            return solve_trusted(self.geometry, target, self.geometry.home_pose, *options), True
        return solution, False

    def _fold_evidence(self, solution, refusal, fell_back):
        """
        Say how a solve shows that a fold may have been crossed: ``(cause, sentence, details)``.

        Or return ``None``. The rules of doc/assembly_modes.md: a refusal whose solve could not
        follow the platform (no solution, a pose the lengths fix only loosely, a jump); a
        solution that came from the fallback start at home; a solve that started (the last
        solution, or an anchor) or ended beyond the singularity margin; a solution across a
        singularity from the last one (its Jacobian's determinant has the other sign).
        """
        if refusal is not None and refusal.code in FOLD_REFUSALS:
            return refusal.code, f'a solve was refused as {refusal.code}', ()
        if not solution.converged:
            return None
        if fell_back:
            return 'fallback_start', (
                'a solve from the last solution failed and the solution came from the home '
                'pose'), ()
        margin = self.singularity_margin
        start = self.last_solution
        for where, result in (('came', solution), ('started', start)):
            if result is not None and not result.condition <= margin:
                return 'near_singularity', (
                    f'a solve {where} near a singularity (Jacobian condition number '
                    f'{result.condition:.4g} > {margin:g}, the singularity margin)'), (
                    ('jacobian_condition', f'{result.condition:.4g}'),)
        if start is not None and solution.jacobian_sign != start.jacobian_sign:
            return 'jacobian_sign', (
                'a solution lay across a singularity from the last accepted pose (the '
                'determinant of its Jacobian changed sign)'), ()
        return None

    def _flag(self, cause: str, sentence: str, details, resolvable_from: int):
        """
        Flag the estimate ambiguous (keeping the first cause since the anchor).

        :param resolvable_from: the first pose number whose margin may clear it.
        """
        self._resolvable_from = max(self._resolvable_from, resolvable_from)
        if self.ambiguity is not None:
            return
        self.ambiguity = Finding(
            findings.AMBIGUOUS_ESTIMATE,
            f'the estimate may be in another assembly mode than the platform: since the '
            f'tracker was anchored ({self.anchored_by}), {sentence}, where two assembly modes '
            'can meet and six leg lengths cannot tell which one the platform went on in; '
            're-anchor it: reset_tracker at the home pose (homing), a known pose on '
            'anchor_pose (PoseTracker.anchor), or a pose where no other real assembly mode '
            'lies within the limits',
            (('cause', cause), *details, ('anchored_by', self.anchored_by)))

    def _refusal(self, lengths, solution) -> Optional[Finding]:
        """Say why a solution cannot be accepted, or return ``None``."""
        if not solution.converged:
            return Finding(
                findings.NO_SOLUTION,
                f'no pose found for leg lengths {np.round(lengths, 6).tolist()} m: '
                f'{solution.reason}',
                (('iterations', str(solution.iterations)),
                 ('residual_m', f'{solution.residual:.3g}')))
        if not solution.pose_error_bound <= self.settings.pose_tolerance:
            if solution.condition > self.settings.near_singularity_condition:
                cause = 'the pose is too near a singularity for the lengths to fix it'
            else:
                cause = 'lower the tolerance, or raise pose_tolerance'
            return Finding(
                findings.INACCURATE_POSE,
                f'the pose of these leg lengths is known only to {solution.pose_error_bound:.3g} '
                f'm and rad (pose_error_bound) > pose_tolerance '
                f'{self.settings.pose_tolerance:g}: the residual {solution.residual:.3g} m '
                f'amplified by the Jacobian condition number {solution.condition:.4g}; {cause}',
                (('iterations', str(solution.iterations)),
                 ('residual_m', f'{solution.residual:.3g}'),
                 ('jacobian_condition', f'{solution.condition:.4g}'),
                 ('pose_error_bound', f'{solution.pose_error_bound:.3g}')))
        violations = self.limits.check_pose(solution.pose[:3],
                                            euler_zyx_to_matrix(solution.pose[3:]),
                                            condition=solution.condition)
        if violations:
            return findings.out_of_limits('the pose of these leg lengths is', violations)
        if self.last_lengths is None:
            return self._ambiguous_start(lengths) if self.settings.refuse_ambiguous_start else None
        return assembly_mode_jump(self.settings, self.last_pose, self.last_lengths,
                                  solution.pose, lengths)

    def _ambiguous_start(self, lengths) -> Optional[Finding]:
        """
        Say why a first solution cannot be trusted to be in the platform's mode, or return None.

        Runs :func:`stewart_kinematics.analysis.assembly_modes.start_ambiguity` from the last known
        pose; its answer is kept while no leg changes by more than
        ``assembly_guard_length_change``, so a platform at rest costs one search.
        """
        settings = self.settings
        if self._start_check is not None and np.max(np.abs(
                lengths - self._start_check[0])) <= settings.assembly_guard_length_change:
            check = self._start_check[1]
        else:
            check = start_ambiguity(self.geometry, lengths, self.last_pose,
                                    settings.assembly_guard_position_change,
                                    math.radians(settings.assembly_guard_angle_change_deg))
            self._start_check = (lengths, check)
        if not check.ambiguous:
            return None
        return Finding(
            findings.AMBIGUOUS_ASSEMBLY_MODE, check.reason,
            (('modes_within_limits', str(check.modes_within_limits)),
             ('search_complete', str(check.complete))))


def assembly_mode_jump(settings: SolverSettings, last_pose, last_lengths, pose,
                       lengths) -> Optional[Finding]:
    """
    Say why ``pose`` looks like a jump to another assembly mode, or return ``None``.

    For the same leg lengths a platform has several poses (assembly modes). A solution far
    from the last one while the lengths barely changed is one of the others, not where the
    platform went: when no leg changed by more than ``assembly_guard_length_change`` metres,
    the platform origin may move at most ``assembly_guard_position_change`` metres and the
    platform turn at most ``assembly_guard_angle_change_deg`` degrees.

    :param last_pose: the last accepted pose, ``[X, Y, Z, alpha, beta, gamma]``.
    :param last_lengths: its leg lengths, metres, shape (6,).
    :param pose: the new solution, same form.
    :param lengths: the new leg lengths, metres, shape (6,).
    """
    length_change = max(map(abs, (np.asarray(lengths) - last_lengths).tolist()))
    if length_change > settings.assembly_guard_length_change:
        return None
    pose, last_pose = np.asarray(pose).tolist(), np.asarray(last_pose).tolist()
    position_change = math.dist(pose[:3], last_pose[:3])
    if (position_change <= settings.assembly_guard_position_change
            and euler_angle_change_bound(last_pose[3:], pose[3:])
            <= math.radians(settings.assembly_guard_angle_change_deg) * ANGLE_BOUND_MARGIN):
        return None   # the rotation angle is at most the bound: no need to compute it
    angle_change = math.degrees(float(rotation_angle_between(
        euler_zyx_to_matrix(last_pose[3:]), euler_zyx_to_matrix(pose[3:]))))
    if (position_change <= settings.assembly_guard_position_change
            and angle_change <= settings.assembly_guard_angle_change_deg):
        return None
    return Finding(
        findings.ASSEMBLY_MODE_JUMP,
        f'the solution jumped {position_change:.4g} m and {angle_change:.4g} deg from the last '
        f'one while no leg changed by more than {length_change:.4g} m: another assembly mode, '
        'not a motion',
        (('position_change_m', f'{position_change:.4g}'),
         ('angle_change_deg', f'{angle_change:.4g}'),
         ('length_change_m', f'{length_change:.4g}')))


#: Refusals whose solve could not follow the platform: evidence that a fold may be near.
FOLD_REFUSALS = (findings.NO_SOLUTION, findings.INACCURATE_POSE, findings.ASSEMBLY_MODE_JUMP)

#: :func:`euler_angle_change_bound` decides alone only this far below the threshold: far
#: beyond the rounding of either figure (about 1e-15 relative).
ANGLE_BOUND_MARGIN = 1.0 - 1e-9


def euler_angle_change_bound(angles_a, angles_b) -> float:
    """
    Bound from above the rotation angle between two Z-Y-X Euler rotations, radians.

    The rotation angle between two rotations is a distance invariant under rotating both
    (bi-invariant), so for ``R = Rz(alpha) Ry(beta) Rx(gamma)`` the triangle inequality gives
    ``angle(R_a, R_b) <= |alpha_a - alpha_b| + |beta_a - beta_b| + |gamma_a - gamma_b|``, each
    difference taken modulo 2 pi into [0, pi]. Three subtractions instead of two rotation
    matrices and a quaternion: :func:`assembly_mode_jump` computes the angle only when this
    bound exceeds its threshold, so its decision is the same.

    :param angles_a: ``(alpha, beta, gamma)``, radians; ``angles_b`` likewise.
    """
    bound = 0.0
    for a, b in zip(angles_a, angles_b):
        difference = abs(a - b) % (2.0 * math.pi)
        bound += min(difference, 2.0 * math.pi - difference)
    return bound
