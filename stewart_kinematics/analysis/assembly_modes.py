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
Every assembly mode: all the real poses that six leg lengths allow.

Six leg lengths do not fix a 6-6 platform's pose: a general one has 40 complex solutions, and up
to 40 of them can be real (Dietmaier 1998). :func:`assembly_modes` finds them all by homotopy
continuation, complete by construction rather than by the luck of a multi-start search: the
homotopy (:mod:`stewart_kinematics.analysis.homotopy`: the Study-parameter formulation, the start
systems, the path tracker and its end game) gives every complex solution; here the ends whose
pose is real are refined by this package's Newton-Raphson
(:func:`stewart_kinematics.forward_kinematics`) to 1e-12 m in leg lengths, deduplicated, checked
against the geometry's limits and sorted by their distance from a reference pose.

A path that fails (its step size shrinks to nothing, or it ends at a singular point) is
counted in the result, whose ``complete`` flag is then False: a failure is reported, never
hidden. Degenerate platforms (a planar base, a planar platform) need nothing special: a
solution the family loses goes to the chart's points at infinity (``e = 0``), and is reported
as such.

The assembly-mode margin (:func:`assembly_mode_margin`) is the distance from a pose to the
nearest other real mode within the limits: how far a solver would have to be thrown to land in
another mode, and how sure a start from a remembered pose can be (:func:`start_ambiguity`);
:class:`stewart_kinematics.workers.margin_monitor.AssemblyModeMarginMonitor` computes it in a
worker thread, or process (fk_node's).

Units are metres and radians, frames and the rotation convention those of
:mod:`stewart_kinematics.model.geometry`. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Optional, Tuple

import numpy as np

from stewart_kinematics import limits
from stewart_kinematics.analysis.homotopy import (  # noqa: F401 (re-exported)
    GENERIC_SOLUTION_COUNT,
    geometry_start_system,
    path_ends,
    start_system,
    StartSystem,
)
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.inputs import as_leg_lengths, as_poses
from stewart_kinematics.model.jacobians import jacobian_condition
from stewart_kinematics.model.rotations import (
    euler_zyx_to_matrix,
    matrix_to_euler_zyx,
    rotation_angle_between,
)

#: A real mode's largest leg length error after refinement, metres.
REFINED_RESIDUAL = 1e-9
#: Two refined modes closer than this (metres, and radians times the platform radius) are one.
DISTINCT_POSE = 1e-7
#: Limits a platform can physically pass: margins the software keeps, not stops of the
#: hardware. A mode that breaks only these is still where the platform could be.
SOFT_LIMITS = ('max_jacobian_condition',)
#: Reasons a result is empty or incomplete.
NO_REAL_MODE = 'no real assembly mode: the {count} solutions of these lengths are all complex'


@dataclass(frozen=True)
class AssemblyMode:
    """
    One real pose whose leg lengths match.

    :param pose: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), as
        :func:`stewart_kinematics.forward_kinematics` returns poses.
    :param residual: largest leg length error, metres.
    :param condition: condition number of the dimensionless Jacobian
        (:func:`stewart_kinematics.model.jacobians.jacobian_condition`); large near a singularity.
    :param violations: every limit of the geometry the pose breaks (empty when allowed).
    :param position_distance: distance of the platform origin from the reference pose's,
        metres.
    :param angle_distance: angle of the rotation from the reference orientation, radians.
    :param distance: ``sqrt(position_distance^2 + (rho angle_distance)^2)``, metres, with rho
        the platform radius (:attr:`Geometry.platform_radius`): the sort key.
    """

    pose: np.ndarray
    residual: float
    condition: float
    violations: tuple
    position_distance: float
    angle_distance: float
    distance: float

    @property
    def within_limits(self) -> bool:
        """Say whether the pose breaks no limit of the geometry."""
        return not self.violations


@dataclass(frozen=True)
class AssemblyModes:
    """
    Outcome of :func:`assembly_modes`: the real modes, and how complete the answer is.

    :param modes: the distinct real modes, nearest to the reference pose first.
    :param complete: True when every homotopy path reached its end cleanly (a solution, or a
        solution lost at infinity) and the path ends were distinct: then ``modes`` holds every
        real assembly mode, by construction.
    :param reason: ``''`` when ``complete`` and at least one mode was found; else why not
        (no real solution, failed paths).
    :param paths: homotopy paths tracked (40, or fewer for a degenerate geometry).
    :param failed_paths: paths that stopped before their end or ended at a singular point.
    :param complex_solutions: path ends that are complex solutions.
    :param at_infinity: solutions at infinity or beyond any real pose's reach (a degenerate
        platform loses some of the 40; a complex solution may lie far away).
    :param method: how the modes were found.
    """

    modes: Tuple[AssemblyMode, ...]
    complete: bool
    reason: str
    paths: int
    failed_paths: int
    complex_solutions: int
    at_infinity: int
    method: str = 'parameter homotopy in Study parameters from a start system of the geometry'

    @property
    def poses(self) -> np.ndarray:
        """Give the poses of the modes, shape (n, 6), nearest first."""
        return np.array([mode.pose for mode in self.modes]).reshape(-1, 6)

    @property
    def within_limits(self) -> Tuple[AssemblyMode, ...]:
        """Give the modes that break no limit: the physically reachable ones."""
        return tuple(mode for mode in self.modes if mode.within_limits)

    def __len__(self):
        return len(self.modes)


def assembly_modes(geometry, lengths, reference_pose=None) -> AssemblyModes:
    """
    Every real pose of the platform whose leg lengths are ``lengths``.

    See the module's documentation for the method. Lengths that no real pose matches give an
    empty answer with the reason, not an exception.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param lengths: leg lengths l_1..l_6, metres, shape (6,).
    :param reference_pose: ``[X, Y, Z, alpha, beta, gamma]`` the modes are sorted from
        (metres, radians); default ``geometry.home_pose``.
    :returns: an :class:`AssemblyModes`.
    :raises ValueError: if the lengths are not six finite, positive numbers or the reference
        pose is malformed.

    >>> from stewart_kinematics import assembly_modes, load_geometry
    >>> geometry = load_geometry('config/paper_platform.yaml')
    >>> modes = assembly_modes(geometry, geometry.home_leg_lengths)
    >>> len(modes), modes.complete
    (10, True)
    >>> modes.modes[0].distance < 1e-9    # the nearest to the reference pose (home): home
    True
    """
    lengths = as_leg_lengths(lengths)
    if lengths.shape != (6,):
        raise ValueError(f'expected the 6 lengths of one pose, got shape {lengths.shape}')
    reference = as_poses(geometry.home_pose if reference_pose is None else reference_pose,
                         'reference_pose')
    if reference.shape != (6,):
        raise ValueError(f'reference_pose must have shape (6,), got {reference.shape}')
    ends = path_ends(geometry, lengths)
    candidates = np.concatenate(
        [ends.positions[ends.real], matrix_to_euler_zyx(ends.rotations[ends.real])], axis=-1)
    modes = _refined_modes(geometry, lengths, candidates, reference)
    solutions = int(np.count_nonzero(ends.solved))
    failed = int(np.count_nonzero(ends.failed))
    complete = failed == 0 and ends.distinct
    reasons = []
    if not modes:
        reasons.append(NO_REAL_MODE.format(count=solutions))
    if failed:
        reasons.append(f'{failed} of {len(ends.solved)} homotopy paths failed '
                       '(singular end or step size too small): modes may be missing')
    if not ends.distinct:
        reasons.append('two homotopy paths ended at the same solution: modes may be missing')
    return AssemblyModes(
        modes=modes, complete=complete, reason='; '.join(reasons), paths=len(ends.solved),
        failed_paths=failed,
        complex_solutions=int(np.count_nonzero(ends.solved & ~ends.real)),
        at_infinity=ends.lost + int(np.count_nonzero(ends.at_infinity)))


def pose_distance(geometry, pose_a, pose_b):
    """
    Distance between two poses: position (metres) and rotation angle (radians).

    :param pose_a: ``[X, Y, Z, alpha, beta, gamma]``, shape (6,) or (N, 6).
    :param pose_b: the same, broadcast against ``pose_a``.
    :returns: ``(position_distance, angle_distance, distance)``, each shape () or (N,);
        ``distance`` is ``sqrt(position^2 + (rho angle)^2)`` in metres, rho the platform radius.
    """
    pose_a, pose_b = np.broadcast_arrays(as_poses(pose_a), as_poses(pose_b, 'pose_b'))
    position = np.linalg.norm(pose_a[..., :3] - pose_b[..., :3], axis=-1)
    angle = rotation_angle_between(euler_zyx_to_matrix(pose_a[..., 3:]),
                                   euler_zyx_to_matrix(pose_b[..., 3:]))
    return position, angle, np.hypot(position, geometry.platform_radius * angle)


def _refined_modes(geometry, lengths, candidates, reference):
    """Refine candidate poses by Newton-Raphson, keep the matching, distinct ones, sorted."""
    if len(candidates) == 0:
        return ()
    result = forward_kinematics(geometry, np.broadcast_to(lengths, candidates.shape),
                                candidates)
    good = result.converged & (result.residual <= REFINED_RESIDUAL)
    poses, residuals = result.pose[good], result.residual[good]
    # A refinement that moved far went to another mode, which its own path finds.
    _, _, moved = pose_distance(geometry, poses, candidates[good])
    poses, residuals = poses[moved < 1e-4], residuals[moved < 1e-4]
    position_distance, angle_distance, distance = pose_distance(geometry, poses, reference)
    order = np.argsort(distance, kind='stable')
    poses, residuals = poses[order], residuals[order]
    position_distance, angle_distance, distance = (
        position_distance[order], angle_distance[order], distance[order])
    rotations = euler_zyx_to_matrix(poses[:, 3:])
    # Pairwise distances: a pose is kept unless an earlier (nearer) one is the same.
    separation = np.hypot(
        np.linalg.norm(poses[:, None, :3] - poses[None, :, :3], axis=-1),
        geometry.platform_radius * rotation_angle_between(rotations[:, None],
                                                          rotations[None, :]))
    duplicate = np.any(np.tril(separation <= DISTINCT_POSE, k=-1), axis=-1)
    kept = np.flatnonzero(~duplicate)
    conditions = jacobian_condition(geometry, poses[kept, :3], rotations[kept])
    return tuple(
        AssemblyMode(
            pose=poses[index], residual=float(residuals[index]),
            condition=float(condition),
            violations=tuple(limits.check_pose(geometry, poses[index, :3], rotations[index])),
            position_distance=float(position_distance[index]),
            angle_distance=float(angle_distance[index]), distance=float(distance[index]))
        for index, condition in zip(kept, np.atleast_1d(conditions)))


@dataclass(frozen=True)
class AssemblyModeMargin:
    """
    How far the nearest other real assembly mode within the limits lies from a pose.

    :param position: distance of its platform origin, metres (``inf`` when there is none).
    :param angle: angle of its rotation from the pose's, radians (``inf`` when none).
    :param distance: the combined distance of :func:`pose_distance`, metres.
    :param nearest: that mode, or None.
    :param modes_within_limits: real modes within the limits, the pose's own included.
    :param complete: whether the search was complete (see :class:`AssemblyModes`).
    :param reason: ``''``, or why the margin is unknown or partial.
    :param others_beyond_singularity_margin: other real modes that break no limit but the
        singularity margin (``max_jacobian_condition``): a margin kept by the software, not a
        stop of the hardware, so the platform can physically be there.
    """

    position: float
    angle: float
    distance: float
    nearest: Optional[AssemblyMode]
    modes_within_limits: int
    complete: bool
    reason: str
    others_beyond_singularity_margin: int = 0

    @property
    def rules_out_other_modes(self) -> bool:
        """
        Whether the lengths leave the platform no other pose than this one.

        True when the search was complete, the pose is the only real mode within the limits,
        and every other real mode breaks a limit the hardware cannot pass (a joint cone, a leg
        collision; the stroke cannot differ: the modes share their lengths), not only the
        singularity margin. A tracker whose estimate this is knows the platform's pose without
        any history (see :meth:`stewart_kinematics.PoseTracker.note_margin`).
        """
        return (self.complete and self.modes_within_limits == 1 and self.nearest is None
                and self.others_beyond_singularity_margin == 0)


def assembly_mode_margin(geometry, pose, lengths=None, modes=None) -> AssemblyModeMargin:
    """
    Distance from ``pose`` to the nearest other real assembly mode within the limits.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param pose: the current solution ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).
    :param lengths: its leg lengths, metres (default: computed from ``pose``).
    :param modes: the :class:`AssemblyModes` of these lengths if already known.
    :returns: an :class:`AssemblyModeMargin`; ``inf`` distances when no other mode within
        the limits exists.
    """
    from stewart_kinematics.model.inverse import inverse_kinematics
    pose = as_poses(pose, 'pose')
    if lengths is None:
        lengths = inverse_kinematics(geometry, pose)
    if modes is None:
        modes = assembly_modes(geometry, lengths, reference_pose=pose)
    within = modes.within_limits
    others = [mode for mode in within
              if pose_distance(geometry, mode.pose, pose)[2] > DISTINCT_POSE * 1e3]
    beyond_margin = sum(
        1 for mode in modes.modes if mode.violations
        and all(violation.limit in SOFT_LIMITS for violation in mode.violations)
        and pose_distance(geometry, mode.pose, pose)[2] > DISTINCT_POSE * 1e3)
    reason = modes.reason if not modes.complete else ''
    if not others:
        return AssemblyModeMargin(math.inf, math.inf, math.inf, None, len(within),
                                  modes.complete, reason, beyond_margin)
    distances = [pose_distance(geometry, mode.pose, pose) for mode in others]
    nearest = int(np.argmin([d[2] for d in distances]))
    position, angle, distance = distances[nearest]
    return AssemblyModeMargin(float(position), float(angle), float(distance), others[nearest],
                              len(within), modes.complete, reason, beyond_margin)


@dataclass(frozen=True)
class StartAmbiguity:
    """
    Whether a first solution (after a start or a reset) can be trusted to be the platform's.

    :param ambiguous: True when more than one real mode lies within the limits and none is
        near the last known pose: the lengths alone cannot tell which mode the platform is in.
    :param reason: why it is ambiguous, or ``''``.
    :param modes_within_limits: real modes within the limits.
    :param near_known_pose: how many of them lie near the last known pose.
    :param complete: whether the search for modes was complete.
    """

    ambiguous: bool
    reason: str
    modes_within_limits: int
    near_known_pose: int
    complete: bool


def start_ambiguity(geometry, lengths, known_pose, position_change, angle_change,
                    modes=None) -> StartAmbiguity:
    """
    Say whether the first solution of a tracker could be in the wrong assembly mode.

    After a start or a reset, a tracker has no last solution to compare with: Newton-Raphson
    from the last known pose (home, or the pose given to the reset) finds the mode that start
    leads to. That is safe when only one real mode lies within the limits, or when one lies
    near the known pose (within ``position_change`` and ``angle_change``); else the lengths
    alone do not say which mode the platform is in.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param lengths: the measured leg lengths, metres, shape (6,).
    :param known_pose: the last known pose ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians).
    :param position_change: how far from it a mode counts as near, metres.
    :param angle_change: how far it may be turned from it, radians.
    :param modes: the :class:`AssemblyModes` of these lengths if already known.
    :returns: a :class:`StartAmbiguity`.
    """
    known_pose = as_poses(known_pose, 'known_pose')
    if modes is None:
        modes = assembly_modes(geometry, lengths, reference_pose=known_pose)
    within = modes.within_limits
    position, angle, _ = pose_distance(geometry, modes.poses, known_pose)
    near = int(np.count_nonzero((position <= position_change) & (angle <= angle_change)
                                & np.array([mode.within_limits for mode in modes.modes],
                                           dtype=bool)))
    ambiguous = len(within) > 1 and near == 0
    reason = ''
    if ambiguous:
        nearest = within[0]
        reason = (
            f'{len(within)} assembly modes lie within the limits for these leg lengths and '
            f'none within {position_change:g} m and {math.degrees(angle_change):g} deg of the '
            f'last known pose (the nearest is {nearest.position_distance:.4g} m and '
            f'{math.degrees(nearest.angle_distance):.4g} deg away): the lengths do not tell '
            'which one the platform is in')
    return StartAmbiguity(ambiguous, reason, len(within), near, modes.complete)
