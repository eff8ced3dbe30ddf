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
    estimate = tracker.update(lengths, velocities)  # a joint state: the pose and its twist
    tracker.reset()                                 # homing: the next solve starts from home

Each update checks the lengths against the actuator stroke, solves by Newton-Raphson from the
last accepted solution (its pose and its Jacobian: a platform moves continuously), falls back
to the home pose when that fails, and then refuses a solution that did not converge, whose
pose error bound exceeds ``pose_tolerance`` (near a singularity), that breaks a limit of the
geometry, or that jumped to another assembly mode; an accepted solution near a singularity
comes with a warning. With leg velocities too (a joint state), an accepted pose carries its
twist, or a warning that says why there is none. Every limit is the limits model's
(:class:`~stewart_kinematics.limits.LimitModel`). :func:`margin_status` decides what fk_node
reports of the assembly-mode margin. Nothing raises for lengths it cannot use, and nothing
here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics import findings
from stewart_kinematics.analysis.assembly_modes import start_ambiguity
from stewart_kinematics.findings import Decision, Finding
from stewart_kinematics.limits import LimitModel
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.kinematics import (
    as_leg_lengths,
    as_poses,
    forward_kinematics,
    ForwardKinematicsResult,
)
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, rotation_angle_between
from stewart_kinematics.model.velocities import platform_twist, SingularPoseError
from stewart_kinematics.parameters.settings import SolverSettings


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
    """

    pose: Optional[np.ndarray]
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()
    solution: Optional[ForwardKinematicsResult] = None
    twist: Optional[np.ndarray] = None

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
class TwistEstimate(Decision):
    """
    The platform twist of a set of leg velocities, or why none was given.

    :param twist: ``[vx, vy, vz, wx, wy, wz]``, base frame, m/s and rad/s; ``None`` when
        refused.
    :param refusal: why, or ``None`` when accepted.
    """

    twist: Optional[np.ndarray]
    refusal: Optional[Finding] = None
    warnings: Tuple[Finding, ...] = ()


class PoseTracker:
    """
    Follow the platform's pose from its measured leg lengths, refusing what cannot be trusted.

    State: the last accepted solution (:attr:`last_pose`, :attr:`last_lengths`,
    :attr:`last_solution`), where the next solve starts and what the assembly-mode guard
    compares with. :meth:`reset` forgets it.

    :param geometry: the platform and its limits (:class:`stewart_kinematics.Geometry`).
    :param settings: the solver's tolerance, iterations and checks (fk_node's solver
        parameters); default: every default, ``SolverSettings()``.
    """

    def __init__(self, geometry, settings: Optional[SolverSettings] = None):
        self.geometry = geometry
        self.settings = SolverSettings() if settings is None else settings
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

    def configure(self, settings: SolverSettings):
        """
        Take new settings from the next update on, such as ``settings.replace(tolerance=1e-10)``.

        The state (the last solution) is kept.
        """
        if not isinstance(settings, SolverSettings):
            raise TypeError(f'settings must be SolverSettings, got {type(settings).__name__}')
        self.settings = settings

    def reset(self, pose=None):
        """
        Forget the last solution: the next solve starts from ``pose``, by default home.

        For homing and restarts. The assembly-mode guard has nothing to compare the next
        solution with, so it accepts whichever assembly mode that start leads to.

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

    def update(self, lengths, velocities=None) -> PoseEstimate:
        """
        Estimate the pose of measured leg lengths, or refuse them with the reason.

        :param lengths: leg lengths l_1..l_6, metres, shape (6,).
        :param velocities: their rates l_1'..l_6', m/s, shape (6,), or ``None``: with them an
            accepted pose carries its twist (:meth:`twist`), or a warning saying why not; the
            pose is published either way.
        :returns: a :class:`PoseEstimate`; an accepted one becomes the last solution.
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
        solution = self._solve(lengths)
        refusal = self._refusal(lengths, solution)
        if refusal is not None:
            return PoseEstimate(None, refusal, solution=solution)
        warnings = ()
        if solution.condition > self.settings.near_singularity_condition:
            warnings = (Finding(
                findings.NEAR_SINGULARITY,
                f'estimated pose is near a singularity: Jacobian condition number '
                f'{solution.condition:.4g} > near_singularity_condition '
                f'{self.settings.near_singularity_condition:g}',
                (('jacobian_condition', f'{solution.condition:.4g}'),)),)
        self.last_pose, self.last_lengths, self.last_solution = solution.pose, lengths, solution
        twist = None
        if velocities is not None:
            estimate = self.twist(velocities)
            twist = estimate.twist
            warnings += () if estimate.accepted else (estimate.refusal,)
        return PoseEstimate(solution.pose, None, warnings, solution, twist)

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
        margin = min(self.settings.near_singularity_condition,
                     self.geometry.max_jacobian_condition)
        try:
            return TwistEstimate(platform_twist(self.geometry, self.last_pose, velocities,
                                                max_condition=margin))
        except SingularPoseError as error:
            return TwistEstimate(None, Finding(
                findings.NEAR_SINGULARITY,
                f'{error} (the singularity margin: the smaller of near_singularity_condition '
                f'and max_jacobian_condition)'))
        except ValueError as error:   # a twist beyond the float range
            return TwistEstimate(None, Finding(findings.INVALID_VELOCITIES, str(error)))

    def _solve(self, lengths) -> ForwardKinematicsResult:
        """Solve from the last solution (with its Jacobian), then from home if that fails."""
        options = {'tolerance': self.settings.tolerance,
                   'max_iterations': self.settings.max_iterations}
        start = self.last_solution if self.last_solution is not None else self.last_pose
        solution = forward_kinematics(self.geometry, lengths, start, **options)
        if not solution.converged and not np.array_equal(self.last_pose,
                                                         self.geometry.home_pose):
            solution = forward_kinematics(self.geometry, lengths, self.geometry.home_pose,
                                          **options)
        return solution

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


@dataclass(frozen=True)
class MarginStatus:
    """
    What fk_node reports of the assembly-mode margin: a warning or not, a sentence, the values.

    :param warning: an ``assembly_mode_margin`` finding when the margin deserves a warning
        (another mode closer than the warning distance, or a search that was incomplete),
        else ``None``.
    :param message: the status sentence.
    :param values: ``(key, value)`` pairs: the margin, its parts, the modes, the cost.
    """

    warning: Optional[Finding]
    message: str
    values: Tuple[Tuple[str, str], ...] = ()


def margin_status(monitor) -> MarginStatus:
    """
    Decide what to report of the latest assembly-mode margin of a monitor.

    :param monitor: an
        :class:`stewart_kinematics.analysis.assembly_modes.AssemblyModeMarginMonitor`.
    :returns: a :class:`MarginStatus`; its warning, if any, is what the node counts and logs.
    """
    too_close = monitor.warning()
    margin = monitor.latest
    if margin is None:
        return MarginStatus(None, 'no solution yet, or not computed yet')
    if too_close:
        message = too_close
    elif margin.nearest is None:
        message = 'no other assembly mode within the limits'
    else:
        message = (f'nearest other assembly mode within the limits: {margin.position:.4g} m and '
                   f'{math.degrees(margin.angle):.4g} deg away')
    if not margin.complete:
        message += f'; the search was incomplete: {margin.reason}'
    values = (('margin_position_m', f'{margin.position:.6g}'),
              ('margin_angle_deg', f'{math.degrees(margin.angle):.6g}'),
              ('margin_distance_m', f'{margin.distance:.6g}'),
              ('modes_within_limits', str(margin.modes_within_limits)),
              ('search_complete', str(margin.complete)),
              ('computed_in_ms', f'{monitor.latest_seconds * 1e3:.1f}'))
    warning = (Finding(findings.ASSEMBLY_MODE_MARGIN, message, values)
               if too_close or not margin.complete else None)
    return MarginStatus(warning, message, values)
