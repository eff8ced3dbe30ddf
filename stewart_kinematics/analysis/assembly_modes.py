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
continuation, complete by construction rather than by the luck of a multi-start search:

1. **Formulation** (Husty 1996, Wampler 1996). A pose is written in Study parameters
   ``z = (e, g)``: ``e`` an (unnormalised) quaternion of the rotation, ``g = t e / 2`` with
   ``t`` the position, bound by the Study quadric ``e . g = 0``. Multiplied by ``e . e``, each
   leg's equation ``|t + R p_i - b_i|^2 = l_i^2`` becomes a quadratic form ``z^T Q_i z``, and
   every ``Q_i`` lies in one linear space of quadrics. With a random complex linear chart
   ``c . z = 1`` the system is 8 quadratic and linear equations in 8 unknowns, whose generic
   number of solutions is 40 (Raghavan 1993; Ronga and Vust 1995; Husty 1996).
2. **Start systems.** Once per process (about 1 s, :func:`start_system`): a random complex
   platform with a known solution; monodromy loops (tracking that solution around loops in the
   space of platforms) give the other 39. Once per geometry (about 0.1 s,
   :func:`geometry_start_system`): its 40 solutions tracked to the given geometry with random
   complex leg lengths near its home lengths; a degenerate geometry keeps fewer (the others go
   to infinity).
3. **Parameter homotopy** to the given lengths: the geometry's start solutions are tracked
   along ``gamma (1 - s) Q_start + s Q_target`` for s from 0 to 1 (only the lengths change;
   the "gamma trick": with a random complex gamma the path meets no singular system before
   s = 1), all paths as one vectorised predictor-corrector (Runge-Kutta predictor, Newton
   corrector, step size adapted per path). By the theory of coefficient-parameter homotopy
   (Morgan and Sommese 1989), the ends of the paths include every isolated solution of the
   target, real or complex.
4. **Real modes**: the path ends whose pose is real are refined by this package's
   Newton-Raphson (:func:`stewart_kinematics.forward_kinematics`) to 1e-12 m in leg lengths,
   deduplicated, checked against the geometry's limits and sorted by their distance from a
   reference pose.

A path that fails (its step size shrinks to nothing, or it ends at a singular point) is
counted in the result, whose ``complete`` flag is then False: a failure is reported, never
hidden. Degenerate platforms (a planar base, a planar platform) need nothing special: a
solution the family loses goes to the chart's points at infinity (``e = 0``), and is reported
as such.

The assembly-mode margin (:func:`assembly_mode_margin`) is the distance from a pose to the
nearest other real mode within the limits: how far a solver would have to be thrown to land in
another mode, and how sure a start from a remembered pose can be.

Units are metres and radians, frames and the rotation convention those of
:mod:`stewart_kinematics.model.geometry`. Nothing here imports ROS.
"""

from dataclasses import dataclass
import functools
import math
import threading
from typing import Optional, Tuple
import weakref

import numpy as np

from stewart_kinematics import limits
from stewart_kinematics.model.kinematics import (
    as_leg_lengths,
    as_poses,
    forward_kinematics,
    jacobian_condition,
)
from stewart_kinematics.model.rotations import (
    euler_zyx_to_matrix,
    matrix_to_euler_zyx,
    rotation_angle_between,
)

#: Generic number of complex solutions of a 6-6 platform: the number of homotopy paths.
GENERIC_SOLUTION_COUNT = 40
#: A real mode's largest leg length error after refinement, metres.
REFINED_RESIDUAL = 1e-9
#: Two refined modes closer than this (metres, and radians times the platform radius) are one.
DISTINCT_POSE = 1e-7
#: A path end whose rotation and normalised position have imaginary parts below this is real
#: (the refinement then checks it).
REAL_IMAGINARY_PART = 1e-6
#: A path that ends (or stalls within END_OF_PATH of its end) at a position this many times
#: farther than any real pose can be goes to infinity: a solution that the platform lost (a
#: degenerate platform has fewer than 40).
FAR_AWAY = 1e3
END_OF_PATH = 1e-3
#: A path end is a solution when the equations' relative residual is below END_RESIDUAL and
#: the Jacobian's condition number below SINGULAR_END.
END_RESIDUAL = 1e-8
SINGULAR_END = 1e12
#: Seed of the random complex start system (any seed serves; a fixed one keeps runs equal).
START_SEED = 20260
#: Path tracking: first and largest step in s, smallest step before a path counts as failed,
#: successes in a row before the step doubles, and the most steps a path may take.
FIRST_STEP = 0.05
MAX_STEP = 0.2
MIN_STEP = 1e-9
MAX_STEPS = 2000
#: Step size control: the step grows by STEP_GROWTH after GROW_AFTER accepted steps in a row
#: and shrinks by STEP_SHRINK after a refused one.
GROW_AFTER = 2
STEP_GROWTH = 2.0
STEP_SHRINK = 0.5
#: Newton corrector: iterations per step and the correction (relative to |z|) that ends it.
CORRECTOR_ITERATIONS = 3
CORRECTOR_TOLERANCE = 1e-7
#: A step is refused when the corrector moved the predicted point by more than this fraction
#: of the step itself: the guard against jumping to a neighbouring path.
CORRECTOR_STEP_FRACTION = 0.05
#: Below this (relative to |z|) a first correction is rounding noise, never a jump.
CORRECTOR_FLOOR = 1e-8
#: Newton iterations polishing the ends at s = 1.
END_ITERATIONS = 4
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
        (:func:`stewart_kinematics.model.kinematics.jacobian_condition`); large near a singularity.
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
    >>> len(modes), modes.complete, modes.modes[0].pose.round(6)
    (10, True, array([0.    , 0.    , 0.4325, 0.    , 0.    , 0.    ]))
    """
    lengths = as_leg_lengths(lengths)
    if lengths.shape != (6,):
        raise ValueError(f'expected the 6 lengths of one pose, got shape {lengths.shape}')
    reference = as_poses(geometry.home_pose if reference_pose is None else reference_pose,
                         'reference_pose')
    if reference.shape != (6,):
        raise ValueError(f'reference_pose must have shape (6,), got {reference.shape}')
    frame = _NormalisedFrame(geometry)
    start, lost = geometry_start_system(geometry)
    target = _normalised_quadrics(start.basis, frame.platform_joints, frame.base_joints,
                                  lengths / frame.scale)
    # Every real pose lies within reach of the base (|t| <= max l + max |p| + max |b|); a path
    # near its end and a thousand times farther goes to infinity: a solution the platform
    # lost, as a degenerate (planar) one does.
    reach = (np.max(lengths) + np.max(np.linalg.norm(geometry.platform_joints, axis=-1))
             + np.max(np.linalg.norm(geometry.base_joints, axis=-1)))
    ends, reached = _track(start, target, start.solutions,
                           far=FAR_AWAY * reach / frame.scale)
    ends, residuals, conditions = _polish(start, target, ends)
    positions, rotations, real, distance = _real_poses(ends, frame)
    at_infinity = ~(distance < FAR_AWAY * reach) & (reached > 1.0 - END_OF_PATH)
    solved = ((reached >= 1.0) & ~at_infinity & (residuals < END_RESIDUAL)
              & (conditions < SINGULAR_END))
    failed = ~solved & ~at_infinity
    real &= solved
    candidates = np.concatenate(
        [positions[real], matrix_to_euler_zyx(rotations[real])], axis=-1)
    modes = _refined_modes(geometry, lengths, candidates, reference)
    solutions = int(np.count_nonzero(solved))
    distinct = _count_distinct(ends[solved]) == solutions
    complete = not np.any(failed) and distinct
    reasons = []
    if not modes:
        reasons.append(NO_REAL_MODE.format(count=solutions))
    if np.any(failed):
        reasons.append(f'{int(np.count_nonzero(failed))} of {len(ends)} homotopy paths failed '
                       '(singular end or step size too small): modes may be missing')
    if not distinct:
        reasons.append('two homotopy paths ended at the same solution: modes may be missing')
    return AssemblyModes(
        modes=modes, complete=complete, reason='; '.join(reasons), paths=len(ends),
        failed_paths=int(np.count_nonzero(failed)),
        complex_solutions=int(np.count_nonzero(solved & ~real)),
        at_infinity=lost + int(np.count_nonzero(at_infinity)))


#: The start systems of the geometries seen, by geometry (see geometry_start_system).
_GEOMETRY_STARTS = weakref.WeakKeyDictionary()
_START_LOCK = threading.Lock()
#: Leg lengths of a geometry's start system: the squares of the home leg lengths, each times
#: 1 plus this times a random complex number (a start near the real lengths gives short
#: paths; any generic complex start gives every solution).
START_LENGTH_SPREAD = 0.2


def geometry_start_system(geometry):
    """
    Build (once per geometry) its start system: its solutions for random complex lengths.

    Tracked once from :func:`start_system` (the 40 paths of a general platform, about 0.1 s),
    cached per geometry. The homotopies of :func:`assembly_modes` then change only the leg
    lengths, a parameter homotopy within the geometry's own family, along paths two to four
    times shorter; a degenerate geometry's lost solutions are not tracked again.

    :returns: ``(StartSystem, lost)``: its solutions, and how many of the 40 went to infinity
        for this geometry. Falls back to the general start system, with ``lost`` 0, if a path
        failed.
    """
    with _START_LOCK:   # a second thread waits for the first one's build, not builds again
        cached = _GEOMETRY_STARTS.get(geometry)
        if cached is None:
            cached = _GEOMETRY_STARTS[geometry] = _build_geometry_start(geometry)
        return cached


def _build_geometry_start(geometry):
    generic = start_system()
    frame = _NormalisedFrame(geometry)
    rng = np.random.default_rng(START_SEED + 1)
    home = geometry.home_leg_lengths / frame.scale
    lengths_squared = home ** 2 * (1.0 + START_LENGTH_SPREAD * (
        rng.normal(size=6) + 1j * rng.normal(size=6)))
    quadrics = _leg_quadrics(generic.basis, frame.platform_joints, frame.base_joints,
                             lengths_squared)
    quadrics /= np.linalg.norm(quadrics, axis=(-2, -1), keepdims=True)
    reach = np.max(np.abs(home)) + np.max(np.linalg.norm(frame.platform_joints, axis=-1)) + (
        np.max(np.linalg.norm(frame.base_joints, axis=-1)))
    ends, reached = _track(generic, quadrics, generic.solutions, far=1e5 * reach)
    ends, residuals, conditions = _polish(generic, quadrics, ends)
    e = ends[:, :4]
    with np.errstate(divide='ignore', invalid='ignore'):
        distance = np.linalg.norm(_translation_times_delta(ends), axis=-1) / np.abs(
            np.sum(e * e, axis=-1))
    at_infinity = ~(distance < 1e5 * reach) & (reached > 1.0 - END_OF_PATH)
    solved = ((reached >= 1.0) & ~at_infinity & (residuals < END_RESIDUAL)
              & (conditions < SINGULAR_END))
    if np.any(~solved & ~at_infinity) or _count_distinct(ends[solved]) != np.count_nonzero(
            solved):
        return generic, 0
    gamma = complex(np.exp(2j * np.pi * rng.uniform()))
    return StartSystem(quadrics, _newton(generic, quadrics, ends[solved]), generic.chart, gamma,
                       generic.basis, 0), int(np.count_nonzero(at_infinity))


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


class _NormalisedFrame:
    """
    Frames moved to the joints' centroids and lengths scaled to about 1, for the homotopy.

    In it, ``b'_i = (b_i - b_c) / scale`` and ``p'_i = (p_i - p_c) / scale``; a pose
    ``(t', R)`` there is ``(scale t' + b_c - R p_c, R)`` in the geometry's frames.
    """

    def __init__(self, geometry):
        self.base_centre = geometry.base_joints.mean(axis=0)
        self.platform_centre = geometry.platform_joints.mean(axis=0)
        base = geometry.base_joints - self.base_centre
        platform = geometry.platform_joints - self.platform_centre
        self.scale = float(np.sqrt(np.mean(np.sum(base ** 2, axis=-1))
                                   + np.mean(np.sum(platform ** 2, axis=-1))))
        self.base_joints = base / self.scale
        self.platform_joints = platform / self.scale

    def pose(self, position, rotation):
        """Positions (n, 3) and rotations (n, 3, 3) in the normalised frames -> the geometry's."""
        return (self.scale * position + self.base_centre
                - rotation @ self.platform_centre, rotation)


# Study parameters z = (e0, e1, e2, e3, g0, g1, g2, g3): e a quaternion (scalar first) of the
# rotation, g = t e / 2. The functions below are the polynomials the quadratic forms come from.

def _quaternion_product(a, b):
    a0, a1, a2, a3 = np.moveaxis(a, -1, 0)
    b0, b1, b2, b3 = np.moveaxis(b, -1, 0)
    return np.stack([a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
                     a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
                     a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
                     a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0], axis=-1)


def _rotation_times_delta(e):
    """``(e . e) R``: the rotation matrix of quaternion ``e`` times ``e . e``, (..., 3, 3)."""
    e0, e1, e2, e3 = np.moveaxis(e, -1, 0)
    return np.stack([
        np.stack([e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3),
                  2 * (e1 * e3 + e0 * e2)], axis=-1),
        np.stack([2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3,
                  2 * (e2 * e3 - e0 * e1)], axis=-1),
        np.stack([2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1),
                  e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3], axis=-1)], axis=-2)


def _translation_times_delta(z):
    """``(e . e) t = 2 vec(g e*)`` on the Study quadric, (..., 3)."""
    e, g = z[..., :4], z[..., 4:]
    return 2 * (e[..., :1] * g[..., 1:] - g[..., :1] * e[..., 1:]
                + np.cross(e[..., 1:], g[..., 1:]))


def _moment(z, axis):
    """``(g p) . e`` for ``p`` the unit vector ``axis``: ``(e . e) t . R p = -2 (g p) . e``."""
    pure = np.zeros(4)
    pure[1 + axis] = 1.0
    return np.sum(_quaternion_product(z[..., 4:], pure) * z[..., :4], axis=-1)


def _quadratic_form(polynomial):
    """Find the symmetric matrix Q with ``polynomial(z) = z^T Q z``, by polarisation."""
    unit = np.eye(8)
    diagonal = polynomial(unit)
    pairs = polynomial(unit[:, None, :] + unit[None, :, :])
    # On the diagonal, f(2 e_j) = 4 Q_jj, which the same formula turns into Q_jj.
    return (pairs - diagonal[:, None] - diagonal[None, :]) / 2.0


@dataclass(frozen=True)
class _QuadricBasis:
    """The quadratic forms that every leg's equation is a combination of (see _leg_quadrics)."""

    delta: np.ndarray        # e . e
    translation: np.ndarray  # g . g
    moment: np.ndarray       # (3, 8, 8): (g p_k) . e
    rotation: np.ndarray     # (3, 3, 8, 8): entries of (e . e) R
    offset: np.ndarray       # (3, 8, 8): entries of (e . e) t
    study: np.ndarray        # e . g


@functools.lru_cache(maxsize=None)
def _quadric_basis() -> _QuadricBasis:
    return _QuadricBasis(
        delta=np.diag([1.0] * 4 + [0.0] * 4),
        translation=np.diag([0.0] * 4 + [1.0] * 4),
        moment=np.array([_quadratic_form(lambda z, k=k: _moment(z, k)) for k in range(3)]),
        rotation=np.array([[_quadratic_form(lambda z, j=j, k=k: _rotation_times_delta(
            z[..., :4])[..., j, k]) for k in range(3)] for j in range(3)]),
        offset=np.array([_quadratic_form(lambda z, j=j: _translation_times_delta(z)[..., j])
                         for j in range(3)]),
        study=_quadratic_form(lambda z: np.sum(z[..., :4] * z[..., 4:], axis=-1)))


def _leg_quadrics(basis, platform_joints, base_joints, lengths_squared):
    """
    Build the six legs' quadratic forms Q_i.

    ``z^T Q_i z = (e . e) (|t + R p_i - b_i|^2 - l_i^2)``, expanded on the Study quadric:

    ``(|p|^2 + |b|^2 - l^2) e.e + 4 g.g - 4 (g p).e
    - 2 b . (e.e) R p - 2 b . (e.e) t``. Works with complex joints and lengths too.
    """
    p, b = platform_joints, base_joints
    constant = np.sum(p * p, axis=-1) + np.sum(b * b, axis=-1) - lengths_squared
    return (constant[:, None, None] * basis.delta + 4.0 * basis.translation
            - 4.0 * np.einsum('ik,kab->iab', p, basis.moment)
            - 2.0 * np.einsum('ij,ik,jkab->iab', b, p, basis.rotation)
            - 2.0 * np.einsum('ij,jab->iab', b, basis.offset))


def _normalised_quadrics(basis, platform_joints, base_joints, lengths):
    """Leg quadrics scaled to unit Frobenius norm (the solutions do not change)."""
    quadrics = _leg_quadrics(basis, platform_joints, base_joints, lengths ** 2)
    return quadrics / np.linalg.norm(quadrics, axis=(-2, -1), keepdims=True)


@dataclass(frozen=True)
class StartSystem:
    """
    A random complex platform and its 40 solutions: where every homotopy starts.

    :param quadrics: its six leg quadrics, (6, 8, 8) complex, unit norm.
    :param solutions: its 40 solutions z, (40, 8) complex, on the chart ``chart . z = 1``.
    :param chart: the random complex linear chart, (8,).
    :param gamma: the random unit complex number of the gamma trick.
    :param basis: the quadric basis.
    :param loops: monodromy loops it took to find the 40.
    """

    quadrics: np.ndarray
    solutions: np.ndarray
    chart: np.ndarray
    gamma: complex
    basis: _QuadricBasis
    loops: int


@functools.lru_cache(maxsize=None)
def start_system(seed=START_SEED) -> StartSystem:
    """
    Build the start system of the homotopies, once per process and seed (about 1 s).

    A random complex platform (joints and lengths) is made to pass through a random complex
    pose, which is one solution; monodromy loops (its solutions tracked from this platform to
    two other random ones and back, which permutes them) find the others until all 40 are
    known. The first call of :func:`assembly_modes` builds it; call this at start-up to keep
    that cost out of a control loop.

    :raises RuntimeError: if 40 solutions are not found within 50 loops (not seen).
    """
    rng = np.random.default_rng(seed)
    basis = _quadric_basis()

    def complex_normal(*shape):
        return rng.normal(size=shape) + 1j * rng.normal(size=shape)

    chart = complex_normal(8)
    chart /= np.linalg.norm(chart)
    gamma = complex(np.exp(2j * np.pi * rng.uniform()))
    e, g = complex_normal(4), complex_normal(4)
    g -= (e @ g) / (e @ e) * e          # onto the Study quadric
    z = np.concatenate([e, g])
    z /= chart @ z
    platform, base = complex_normal(6, 3), complex_normal(6, 3)
    # Lengths that make z a solution: z^T Q(l = 0) z = (e . e) l^2 for each leg.
    free = _leg_quadrics(basis, platform, base, np.zeros(6))
    lengths_squared = np.einsum('a,iab,b->i', z, free, z) / (z[:4] @ z[:4])
    quadrics = _leg_quadrics(basis, platform, base, lengths_squared)
    quadrics /= np.linalg.norm(quadrics, axis=(-2, -1), keepdims=True)
    solutions = z[None, :]
    for loop in range(1, 51):
        system = StartSystem(quadrics, solutions, chart, gamma, basis, loop)
        waypoints = [_random_quadrics(basis, complex_normal) for _ in range(2)]
        points, good = solutions, np.ones(len(solutions), dtype=bool)
        for source, target in zip([quadrics] + waypoints, waypoints + [quadrics]):
            points, reached = _track(system, target, points[good], source=source)
            finished = reached >= 1.0
            good = finished
        new = points[good]
        solutions = _merge_distinct(solutions, _newton(system, quadrics, new))
        if len(solutions) >= GENERIC_SOLUTION_COUNT:
            return StartSystem(quadrics, solutions[:GENERIC_SOLUTION_COUNT], chart, gamma,
                               basis, loop)
    raise RuntimeError(f'monodromy found only {len(solutions)} of {GENERIC_SOLUTION_COUNT} '
                       'start solutions')


def _random_quadrics(basis, complex_normal):
    quadrics = _leg_quadrics(basis, complex_normal(6, 3), complex_normal(6, 3),
                             complex_normal(6))
    return quadrics / np.linalg.norm(quadrics, axis=(-2, -1), keepdims=True)


def _merge_distinct(known, new):
    for point in new:
        if np.all(np.isfinite(point)) and (len(known) == 0 or np.min(
                np.linalg.norm(known - point, axis=-1)) > 1e-6 * np.linalg.norm(point)):
            known = np.concatenate([known, point[None]])
    return known


def _count_distinct(points):
    """How many of the points (n, 8) are distinct (farther apart than 1e-6 relative)."""
    if len(points) == 0:
        return 0
    separation = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=-1)
    same = separation <= 1e-6 * np.linalg.norm(points, axis=-1)[None, :]
    return int(np.count_nonzero(~np.any(np.tril(same, k=-1), axis=-1)))


class _Homotopy:
    """
    The homotopy's equations, evaluated for many points at once.

    ``H(z, s)`` is ``gamma (1 - s) Q_source + s Q_target`` for the legs, then the Study quadric
    and the chart.
    """

    def __init__(self, start, source, target):
        forms = np.concatenate([start.gamma * source, target, start.basis.study[None]])
        #: All quadratic forms as one matrix, so that one product gives every ``Q z``.
        self.forms = np.ascontiguousarray(forms.reshape(-1, 8).T)
        self.chart = start.chart

    def evaluate(self, z, s):
        """
        Evaluate the equations at points z (n, 8) and times s (n,).

        :returns: ``(values (n, 8), Jacobians (n, 8, 8), d values / ds (n, 8))``.
        """
        count = len(z)
        products = (z @ self.forms).reshape(count, 13, 8)
        forms = np.einsum('nka,na->nk', products, z)
        source, target = (1.0 - s)[:, None], s[:, None]
        values = np.empty((count, 8), dtype=complex)
        values[:, :6] = source * forms[:, :6] + target * forms[:, 6:12]
        values[:, 6] = forms[:, 12]
        values[:, 7] = z @ self.chart - 1.0
        jacobians = np.empty((count, 8, 8), dtype=complex)
        jacobians[:, :6] = 2.0 * (source[:, :, None] * products[:, :6]
                                  + target[:, :, None] * products[:, 6:12])
        jacobians[:, 6] = 2.0 * products[:, 12]
        jacobians[:, 7] = self.chart
        rates = np.zeros((count, 8), dtype=complex)
        rates[:, :6] = forms[:, 6:12] - forms[:, :6]
        return values, jacobians, rates

    def velocity(self, z, s):
        """``dz/ds = -H_z^-1 H_s`` along the paths."""
        _, jacobians, rates = self.evaluate(z, s)
        return -_solve(jacobians, rates)


def _solve(matrices, vectors):
    """Solve each system; a singular one gives NaN (the caller refuses that step)."""
    try:
        return np.linalg.solve(matrices, vectors[..., None])[..., 0]
    except np.linalg.LinAlgError:
        result = np.full(vectors.shape, np.nan, dtype=complex)
        for k, (matrix, vector) in enumerate(zip(matrices, vectors)):
            try:
                result[k] = np.linalg.solve(matrix, vector)
            except np.linalg.LinAlgError:
                pass
        return result


def _track(start, target, points, source=None, far=np.inf):
    """
    Track points from s = 0 (the source system, default the start system) to s = 1 (target).

    All paths advance together, each with its own step: a fourth-order Runge-Kutta predictor
    along ``dz/ds = -H_z^-1 H_s``, then Newton's method at the new s. A step is accepted when
    the corrector converges within CORRECTOR_ITERATIONS and moved the prediction by less than
    CORRECTOR_STEP_FRACTION of the step; else it is halved and retried.

    :param far: a path that comes within END_OF_PATH of its end farther out than this (the
        normalised position's norm) goes to infinity and is stopped there.
    :returns: ``(ends (n, 8), reached (n,))``: a path that did not reach s = 1 keeps its last
        point, and ``reached`` says where it stopped.
    """
    homotopy = _Homotopy(start, start.quadrics if source is None else source, target)
    count = len(points)
    z = np.array(points, dtype=complex)
    s = np.zeros(count)
    step = np.full(count, FIRST_STEP)
    successes = np.zeros(count, dtype=int)
    active = np.arange(count)
    for _ in range(MAX_STEPS):
        if active.size == 0:
            break
        za, sa = z[active], s[active]
        h = np.minimum(step[active], 1.0 - sa)
        k1 = homotopy.velocity(za, sa)
        k2 = homotopy.velocity(za + 0.5 * h[:, None] * k1, sa + 0.5 * h)
        k3 = homotopy.velocity(za + 0.5 * h[:, None] * k2, sa + 0.5 * h)
        k4 = homotopy.velocity(za + h[:, None] * k3, sa + h)
        predicted = za + (h / 6.0)[:, None] * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        s_new = sa + h
        corrected = predicted.copy()
        first_correction = None
        for _ in range(CORRECTOR_ITERATIONS):
            values, jacobians, _ = homotopy.evaluate(corrected, s_new)
            correction = _solve(jacobians, values)
            corrected -= correction
            size = np.linalg.norm(correction, axis=-1)
            if first_correction is None:
                first_correction = size
            elif np.all(size <= CORRECTOR_TOLERANCE * np.linalg.norm(corrected, axis=-1)):
                break
        scale = np.linalg.norm(corrected, axis=-1)
        moved = np.linalg.norm(predicted - za, axis=-1)
        accepted = (np.isfinite(size) & (size <= CORRECTOR_TOLERANCE * scale)
                    & (first_correction <= np.maximum(CORRECTOR_STEP_FRACTION * moved,
                                                      CORRECTOR_FLOOR * scale)))
        good, bad = active[accepted], active[~accepted]
        z[good], s[good] = corrected[accepted], s_new[accepted]
        successes[good] += 1
        grow = good[successes[good] >= GROW_AFTER]
        step[grow] = np.minimum(STEP_GROWTH * step[grow], MAX_STEP)
        successes[grow] = 0
        step[bad] *= STEP_SHRINK
        successes[bad] = 0
        active = active[(s[active] < 1.0) & (step[active] >= MIN_STEP)]
        if far < np.inf:
            # Near its end, a path this far out goes to infinity: stop it there.
            ending = s[active] > 1.0 - END_OF_PATH
            if np.any(ending):
                ends = z[active[ending]]
                distance = np.linalg.norm(_translation_times_delta(ends), axis=-1) / np.abs(
                    np.sum(ends[:, :4] ** 2, axis=-1))
                active = np.concatenate([active[~ending], active[ending][~(distance > far)]])
    return z, s


def _newton(start, quadrics, points):
    """Polish points on the system ``quadrics`` (s = 1), END_ITERATIONS Newton steps."""
    if len(points) == 0:
        return points
    homotopy = _Homotopy(start, quadrics, quadrics)
    ones = np.ones(len(points))
    z = np.array(points, dtype=complex)
    for _ in range(END_ITERATIONS):
        values, jacobians, _ = homotopy.evaluate(z, ones)
        correction = _solve(jacobians, values)
        z = np.where(np.isfinite(correction), z - correction, z)
    return z


def _polish(start, target, ends):
    """Polish the path ends; return them with their residuals and Jacobian condition numbers."""
    ends = _newton(start, target, ends)
    ones = np.ones(len(ends))
    values, jacobians, _ = _Homotopy(start, target, target).evaluate(ends, ones)
    residuals = np.max(np.abs(values), axis=-1) / np.maximum(
        1.0, np.linalg.norm(ends, axis=-1) ** 2)
    conditions = np.linalg.cond(jacobians)
    return ends, residuals, conditions


def _real_poses(ends, frame):
    """
    Poses of path ends, in the geometry's frames, and which of them are real.

    :returns: ``(positions (n, 3), rotations (n, 3, 3), real (n,), distance (n,))``: real
        parts, and the distance of the (complex) position from the base's centre, metres.
    """
    e = ends[:, :4]
    delta = np.sum(e * e, axis=-1)
    with np.errstate(divide='ignore', invalid='ignore'):
        rotations = _rotation_times_delta(e) / delta[:, None, None]
        positions = _translation_times_delta(ends) / delta[:, None]
    imaginary = np.maximum(np.max(np.abs(rotations.imag), axis=(-2, -1)),
                           np.max(np.abs(positions.imag), axis=-1))
    real = np.isfinite(imaginary) & (imaginary < REAL_IMAGINARY_PART)
    distance = frame.scale * np.linalg.norm(positions, axis=-1)
    positions, rotations = np.nan_to_num(positions.real), np.nan_to_num(rotations.real)
    positions, rotations = frame.pose(positions, rotations)
    return positions, rotations, real, distance


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
    """

    position: float
    angle: float
    distance: float
    nearest: Optional[AssemblyMode]
    modes_within_limits: int
    complete: bool
    reason: str


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
    from stewart_kinematics.model.kinematics import inverse_kinematics
    pose = as_poses(pose, 'pose')
    if lengths is None:
        lengths = inverse_kinematics(geometry, pose)
    if modes is None:
        modes = assembly_modes(geometry, lengths, reference_pose=pose)
    within = modes.within_limits
    others = [mode for mode in within
              if pose_distance(geometry, mode.pose, pose)[2] > DISTINCT_POSE * 1e3]
    reason = modes.reason if not modes.complete else ''
    if not others:
        return AssemblyModeMargin(math.inf, math.inf, math.inf, None, len(within),
                                  modes.complete, reason)
    distances = [pose_distance(geometry, mode.pose, pose) for mode in others]
    nearest = int(np.argmin([d[2] for d in distances]))
    position, angle, distance = distances[nearest]
    return AssemblyModeMargin(float(position), float(angle), float(distance), others[nearest],
                              len(within), modes.complete, reason)


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


class AssemblyModeMarginMonitor:
    """
    The assembly-mode margin of a tracker's latest solution, computed in the background.

    Finding every mode takes tens of milliseconds, too long for a message callback: fk_node
    calls :meth:`request` at its status rate with the last solution, which starts one
    computation in a worker thread unless one is running or the lengths have not changed, and
    reads :attr:`latest` when it reports. The solutions keep flowing meanwhile.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param warning_distance: a margin (the combined distance of :func:`pose_distance`)
        below this, metres, is worth a warning; 0 for none.
    """

    def __init__(self, geometry, warning_distance=0.0):
        from concurrent.futures import ThreadPoolExecutor
        self.geometry = geometry
        self.warning_distance = float(warning_distance)
        #: The last margin computed, or None; with the lengths it is for and its cost, seconds.
        self.latest: Optional[AssemblyModeMargin] = None
        self.latest_lengths = None
        self.latest_seconds = None
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix='assembly_modes')
        # Build the start systems now, in the background (about 1 s, once per process).
        self._warm_up = self._pool.submit(geometry_start_system, geometry)
        self._running = None

    def request(self, pose, lengths) -> bool:
        """
        Start computing the margin of ``pose`` (with its ``lengths``) unless one is running.

        :returns: whether a computation started; none does for lengths already done.
        """
        self._collect()
        if self._running is not None or lengths is None:
            return False
        lengths = np.array(lengths, dtype=float)
        if self.latest_lengths is not None and np.array_equal(lengths, self.latest_lengths):
            return False
        self._running = self._pool.submit(self._compute, np.array(pose, dtype=float), lengths)
        return True

    def warning(self) -> str:
        """Say why the latest margin deserves a warning, or return ``''``."""
        self._collect()
        margin = self.latest
        if margin is None or not margin.distance < self.warning_distance:
            return ''
        return (f'another assembly mode within the limits lies {margin.position:.4g} m and '
                f'{math.degrees(margin.angle):.4g} deg from the estimated pose '
                f'(combined distance {margin.distance:.4g} m < {self.warning_distance:g} m): a '
                'solver thrown that far would land in it')

    def wait(self, timeout=None):
        """Wait for the running computation, if any (for tests and shutdown)."""
        if self._running is not None:
            self._running.result(timeout)
        self._collect()

    def close(self):
        """Stop the worker thread (a running computation finishes first)."""
        self._pool.shutdown(wait=True)

    def _compute(self, pose, lengths):
        import time
        start = time.perf_counter()
        margin = assembly_mode_margin(self.geometry, pose, lengths)
        return margin, lengths, time.perf_counter() - start

    def _collect(self):
        if self._running is not None and self._running.done():
            future, self._running = self._running, None
            self.latest, self.latest_lengths, self.latest_seconds = future.result()
