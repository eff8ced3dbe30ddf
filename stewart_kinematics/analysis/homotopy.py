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
The homotopy behind :func:`stewart_kinematics.analysis.assembly_modes.assembly_modes`.

Every complex solution of six leg lengths, found by homotopy continuation; the module
:mod:`.assembly_modes` turns the real ones into assembly modes.

1. **Formulation** (Husty 1996, Wampler 1996). A pose is written in Study parameters
   ``z = (e, g)``: ``e`` an (unnormalised) quaternion of the rotation, ``g = t e / 2`` with
   ``t`` the position, bound by the Study quadric ``e . g = 0``. Multiplied by ``e . e``, each
   leg's equation ``|t + R p_i - b_i|^2 = l_i^2`` becomes a quadratic form ``z^T Q_i z``, and
   every ``Q_i`` lies in one linear space of quadrics. With a random complex linear chart
   ``c . z = 1`` the system is 8 quadratic and linear equations in 8 unknowns, whose generic
   number of solutions is 40 (Raghavan 1993; Ronga and Vust 1995; Husty 1996).
2. **Start systems.** Once per process (0.3 to 0.5 s, :func:`start_system`): a random complex
   platform with a known solution; monodromy loops (tracking that solution around loops in the
   space of platforms) give the other 39. Once per geometry (about 0.03 s,
   :func:`geometry_start_system`): its 40 solutions tracked to the given geometry with random
   complex leg lengths near its home lengths; a degenerate geometry keeps fewer (the others go
   to infinity): 16 for a 6-3 or 3-3 platform (joints shared by two legs).
3. **Parameter homotopy** to the given lengths (:func:`path_ends`): the geometry's start
   solutions are tracked along ``gamma (1 - s) Q_start + s Q_target`` for s from 0 to 1 (only
   the lengths change; the "gamma trick": with a random complex gamma the path meets no
   singular system before s = 1). By the theory of coefficient-parameter homotopy (Morgan and
   Sommese 1989), the ends of the paths include every isolated solution of the target, real or
   complex.
4. **The tracker** (:func:`track`) advances all paths together, each with its own step, in
   few array operations per step. The homotopy is quadratic in ``z`` and linear in ``s``, so
   the Taylor series of a path at a point follows from one inverse Jacobian by a recursion of
   products with the quadrics (:meth:`Homotopy.series`): the predictor is that series to
   order :data:`ORDER`, and the step is sized from it, so that its last term stays
   :data:`TARGET_STEP_FRACTION` of the step's first-order move (short where the path bends,
   near the branch points of the paths, long where it is straight). Newton's method then
   corrects at the new s, and its last iteration's inverse Jacobian serves the next series.
   A step is refused when the first correction is more than :data:`CORRECTOR_STEP_FRACTION`
   of the step (the guard against jumping to a neighbouring path) or Newton does not
   converge, and retried shorter.
5. **End game**: the ends at s = 1 are polished by Newton's method until they stop moving,
   only those that still move taking another iteration; a path that stalls near s = 1 far out
   goes to infinity (a solution a degenerate platform loses) and is stopped there.

A path that fails (its step size shrinks to nothing, or it ends at a singular point) is
counted, never hidden. Nothing here imports ROS.
"""

from dataclasses import dataclass
import functools
import threading
import weakref

import numpy as np

#: Generic number of complex solutions of a 6-6 platform: the number of homotopy paths.
GENERIC_SOLUTION_COUNT = 40
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
#: Leg lengths of a geometry's start system: the squares of the home leg lengths, each times
#: 1 plus this times a random complex number (a start near the real lengths gives short
#: paths; any generic complex start gives every solution).
START_LENGTH_SPREAD = 0.2
#: Path tracking: largest step in s, smallest step before a path counts as failed, and the
#: most steps a path may take.
MAX_STEP = 0.5
MIN_STEP = 1e-9
MAX_STEPS = 2000
#: Order of the Taylor series predictor (on Dietmaier's platform, 4: 39 steps, 5: 32, 6: 30,
#: each order costing a few more array operations per step).
ORDER = 5
#: The step is sized so that the series' last term is this fraction of the first-order move,
#: and to at most RADIUS_FRACTION of the series' radius of convergence as its last two terms
#: estimate it (the distance to the nearest branch point, where the paths meet).
TARGET_STEP_FRACTION = 0.02
RADIUS_FRACTION = 0.5
#: Newton corrector: the correction (relative to ``|z|``) below which it has converged, and the
#: most iterations per step.
CORRECTOR_TOLERANCE = 1e-7
CORRECTOR_ITERATIONS = 3
#: A step is refused when the corrector's first correction is more than this fraction of the
#: step itself: the guard against jumping to a neighbouring path.
CORRECTOR_STEP_FRACTION = 0.05
#: Below this (relative to ``|z|``) a first correction is rounding noise, never a jump.
CORRECTOR_FLOOR = 1e-8
#: The largest step grows by STEP_GROWTH after an accepted step and shrinks to STEP_SHRINK
#: times the step after a refused one.
STEP_GROWTH = 2.0
STEP_SHRINK = 0.5
#: End game: Newton iterations polishing the ends at s = 1 at most, and the correction
#: (relative to ``|z|``) at which an end stops moving.
END_ITERATIONS = 4
END_TOLERANCE = 1e-14


@dataclass(frozen=True)
class PathEnds:
    """
    Where the homotopy paths of one set of leg lengths ended, in the geometry's frames.

    :param positions: real parts of the ends' positions, metres, (n, 3).
    :param rotations: real parts of their rotation matrices, (n, 3, 3).
    :param real: ends that are solutions with a real pose.
    :param solved: ends that are solutions (regular, small residual), real or complex.
    :param failed: paths that stopped before their end or ended at a singular point.
    :param at_infinity: paths that went to infinity (beyond any real pose's reach).
    :param lost: solutions of the generic start system that the geometry's start lost.
    :param distinct: whether the solved ends are pairwise distinct.
    """

    positions: np.ndarray
    rotations: np.ndarray
    real: np.ndarray
    solved: np.ndarray
    failed: np.ndarray
    at_infinity: np.ndarray
    lost: int
    distinct: bool


def path_ends(geometry, lengths) -> PathEnds:
    """
    Track the geometry's start solutions to the leg lengths ``lengths`` (metres, (6,)).

    :returns: the classified :class:`PathEnds`.
    """
    frame = NormalisedFrame(geometry)
    start, lost = geometry_start_system(geometry)
    target = _normalised_quadrics(start.basis, frame.platform_joints, frame.base_joints,
                                  lengths / frame.scale)
    # Every real pose lies within reach of the base (|t| <= max l + max |p| + max |b|); a path
    # near its end and a thousand times farther goes to infinity: a solution the platform
    # lost, as a degenerate (planar) one does.
    reach = (np.max(lengths) + np.max(np.linalg.norm(geometry.platform_joints, axis=-1))
             + np.max(np.linalg.norm(geometry.base_joints, axis=-1)))
    ends, reached = track(start, target, start.solutions, far=FAR_AWAY * reach / frame.scale)
    ends, residuals, conditions = polish(start, target, ends)
    positions, rotations, real, distance = _real_poses(ends, frame)
    at_infinity = ~(distance < FAR_AWAY * reach) & (reached > 1.0 - END_OF_PATH)
    solved = ((reached >= 1.0) & ~at_infinity & (residuals < END_RESIDUAL)
              & (conditions < SINGULAR_END))
    return PathEnds(positions, rotations, real & solved, solved, ~solved & ~at_infinity,
                    at_infinity, lost, count_distinct(ends[solved]) == np.count_nonzero(solved))


class NormalisedFrame:
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
    e0, e1, e2, e3, g0, g1, g2, g3 = np.moveaxis(z, -1, 0)
    return 2 * np.stack([e0 * g1 - g0 * e1 + e2 * g3 - e3 * g2,
                         e0 * g2 - g0 * e2 + e3 * g1 - e1 * g3,
                         e0 * g3 - g0 * e3 + e1 * g2 - e2 * g1], axis=-1)


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
    Build the start system of the homotopies, once per process and seed (0.3 to 0.5 s).

    A random complex platform (joints and lengths) is made to pass through a random complex
    pose, which is one solution; monodromy loops (its solutions tracked from this platform to
    two other random ones and back, which permutes them) find the others until all 40 are
    known. The first call of :func:`stewart_kinematics.assembly_modes` builds it; call this
    at start-up to keep that cost out of a control loop.

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
            points, reached = track(system, target, points[good], source=source)
            good = reached >= 1.0
        solutions = _merge_distinct(solutions, newton(system, quadrics, points[good])[0])
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


def count_distinct(points):
    """How many of the points (n, 8) are distinct (farther apart than 1e-6 relative)."""
    if len(points) == 0:
        return 0
    # |a - b|^2 = |a|^2 + |b|^2 - 2 Re(a . conj b): one product instead of n^2 differences.
    squares = np.square(_norms(points))
    separation = squares[:, None] + squares[None, :] - 2.0 * (points @ points.conj().T).real
    same = separation <= 1e-12 * squares[None, :]
    return int(np.count_nonzero(~np.any(np.tril(same, k=-1), axis=-1)))


#: The start systems of the geometries seen, by geometry (see geometry_start_system).
_GEOMETRY_STARTS = weakref.WeakKeyDictionary()
_START_LOCK = threading.Lock()


def geometry_start_system(geometry):
    """
    Build (once per geometry) its start system: its solutions for random complex lengths.

    Tracked once from :func:`start_system` (the 40 paths of a general platform, about 0.03 s),
    cached per geometry. The homotopies of :func:`path_ends` then change only the leg lengths,
    a parameter homotopy within the geometry's own family, along paths two to four times
    shorter; a degenerate geometry's lost solutions are not tracked again.

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
    frame = NormalisedFrame(geometry)
    rng = np.random.default_rng(START_SEED + 1)
    home = geometry.home_leg_lengths / frame.scale
    lengths_squared = home ** 2 * (1.0 + START_LENGTH_SPREAD * (
        rng.normal(size=6) + 1j * rng.normal(size=6)))
    quadrics = _leg_quadrics(generic.basis, frame.platform_joints, frame.base_joints,
                             lengths_squared)
    quadrics /= np.linalg.norm(quadrics, axis=(-2, -1), keepdims=True)
    reach = np.max(np.abs(home)) + np.max(np.linalg.norm(frame.platform_joints, axis=-1)) + (
        np.max(np.linalg.norm(frame.base_joints, axis=-1)))
    ends, reached = track(generic, quadrics, generic.solutions, far=1e5 * reach)
    ends, residuals, conditions = polish(generic, quadrics, ends)
    e = ends[:, :4]
    with np.errstate(divide='ignore', invalid='ignore'):
        distance = np.linalg.norm(_translation_times_delta(ends), axis=-1) / np.abs(
            np.sum(e * e, axis=-1))
    at_infinity = ~(distance < 1e5 * reach) & (reached > 1.0 - END_OF_PATH)
    solved = ((reached >= 1.0) & ~at_infinity & (residuals < END_RESIDUAL)
              & (conditions < SINGULAR_END))
    if np.any(~solved & ~at_infinity) or count_distinct(ends[solved]) != np.count_nonzero(
            solved):
        return generic, 0
    gamma = complex(np.exp(2j * np.pi * rng.uniform()))
    return StartSystem(quadrics, newton(generic, quadrics, ends[solved])[0], generic.chart,
                       gamma, generic.basis, 0), int(np.count_nonzero(at_infinity))


class Homotopy:
    """
    The homotopy's equations, evaluated for many points at once in a few array operations.

    ``H(z, s)`` is ``gamma (1 - s) Q_source + s Q_target = A + s D`` for the legs
    (``A = gamma Q_source``, ``D = Q_target - A``), then the Study quadric ``S`` and the chart.
    """

    def __init__(self, start, source, target):
        constant = start.gamma * source
        forms = np.concatenate([constant, target - constant, start.basis.study[None]])
        #: All 13 quadratic forms (A, D, S) as one matrix: one product gives every ``Q z``;
        #: and with the chart as a last column, ``c . z`` too.
        self.forms = np.ascontiguousarray(np.concatenate([forms.reshape(-1, 8).T,
                                                          start.chart[:, None]], axis=1))
        self.chart = start.chart

    def products(self, z):
        """``Q z`` of the 13 forms for points z (n, 8): shape (n, 13, 8)."""
        return (z @ self.forms[:, :104]).reshape(len(z), 13, 8)

    def evaluate(self, z, s):
        """
        Evaluate the equations at points z (n, 8) and times s (n,).

        :returns: ``(values (n, 8), Jacobians (n, 8, 8))``.
        """
        count = len(z)
        everything = z @ self.forms
        products = everything[:, :104].reshape(count, 13, 8)
        forms = _apply(products, z)                             # z^T Q z of every form
        jacobians = np.empty((count, 8, 8), dtype=complex)
        np.multiply(products[:, 6:12], s[:, None, None], out=jacobians[:, :6])
        jacobians[:, :6] += products[:, :6]
        jacobians[:, 6] = products[:, 12]
        jacobians[:, :7] *= 2.0
        jacobians[:, 7] = self.chart
        values = np.empty((count, 8), dtype=complex)
        np.multiply(forms[:, 6:12], s[:, None], out=values[:, :6])
        values[:, :6] += forms[:, :6]
        values[:, 6] = forms[:, 12]
        values[:, 7] = everything[:, 104] - 1.0
        return values, jacobians

    def series(self, z, s, inverse, order):
        """
        Taylor coefficients ``c_0 .. c_order`` of the paths through (z, s): (order + 1, n, 8).

        With ``z(s + u) = sum c_k u^k`` in ``H = 0``, the terms of order k >= 1 give
        ``J c_k = -(sum_{i+j=k; i,j>=1} (A + s D)(c_i, c_j) + sum_{i+j=k-1} D(c_i, c_j))`` for
        the legs and the Study quadric's ``S(c_i, c_j)`` (the chart is linear): one inverse
        Jacobian ``inverse`` (n, 8, 8), at z, serves every order.
        """
        count = len(z)
        coefficients = np.empty((order + 1, count, 8, 1), dtype=complex)
        products = np.empty((order, count, 13, 8), dtype=complex)
        coefficients[0, :, :, 0] = z
        right = np.zeros((count, 8, 1), dtype=complex)
        s = s[:, None, None]
        for k in range(1, order + 1):
            products[k - 1] = self.products(coefficients[k - 1, :, :, 0])
            # sum over i of D c_i . c_(k-1-i), i = 0 .. k-1
            right[:, :6] = np.add.reduce(products[:k, :, 6:12] @ coefficients[k - 1::-1],
                                         axis=0)
            if k > 1:   # sum over i of Q c_i . c_(k-i), i = 1 .. k-1, every form
                forms = np.add.reduce(products[1:k] @ coefficients[k - 1:0:-1], axis=0)
                right[:, :6] += forms[:, :6] + s * forms[:, 6:12]
                right[:, 6] = forms[:, 12]
            np.negative(inverse @ right, out=coefficients[k])
        return coefficients[..., 0]


def _invert(matrices):
    """Invert each matrix (n, 8, 8); a singular one gives NaN (the caller refuses it)."""
    try:
        return np.linalg.inv(matrices)
    except np.linalg.LinAlgError:
        result = np.full(matrices.shape, np.nan, dtype=complex)
        for k, matrix in enumerate(matrices):
            try:
                result[k] = np.linalg.inv(matrix)
            except np.linalg.LinAlgError:
                pass
        return result


def _apply(matrices, vectors):
    """Each matrix (n, k, 8) times its vector (n, 8): (n, k)."""
    return (matrices @ vectors[:, :, None])[:, :, 0]


def _norms(points):
    """Euclidean norm of each row of a complex array (n, 8)."""
    return np.sqrt(np.add.reduce(np.square(points.view(np.float64)), axis=-1))


_POWERS = np.arange(ORDER + 1)


def track(start, target, points, source=None, far=np.inf):
    """
    Track points from s = 0 (the source system, default the start system) to s = 1 (target).

    All paths advance together, each with its own step: the Taylor series predictor
    (:meth:`Homotopy.series`), then Newton's method at the new s (:func:`_correct`). A step is
    accepted when Newton converges within CORRECTOR_ITERATIONS and its first correction was
    less than CORRECTOR_STEP_FRACTION of the step; a refused one is retried shorter.

    :param far: a path that comes within END_OF_PATH of its end farther out than this (the
        normalised position's norm) goes to infinity and is stopped there.
    :returns: ``(ends (n, 8), reached (n,))``: a path that did not reach s = 1 keeps its last
        point, and ``reached`` says where it stopped.
    """
    homotopy = Homotopy(start, start.quadrics if source is None else source, target)
    ends = np.array(points, dtype=complex).reshape(-1, 8)
    reached = np.zeros(len(ends))
    # The paths still going, compactly: their index, point, s, inverse Jacobian, step limit.
    index = np.arange(len(ends))
    z, s = ends.copy(), reached.copy()
    inverse = _invert(homotopy.evaluate(z, s)[1])
    limit = np.full(len(ends), MAX_STEP)
    exponent = 1.0 / (ORDER - 1)
    for _ in range(MAX_STEPS):
        if index.size == 0:
            break
        series = homotopy.series(z, s, inverse, ORDER)
        with np.errstate(divide='ignore', invalid='ignore'):
            last_term = _norms(series[ORDER])
            sized = np.fmin((TARGET_STEP_FRACTION * _norms(series[1]) / last_term) ** exponent,
                            RADIUS_FRACTION * _norms(series[ORDER - 1]) / last_term)
        h = np.fmin(np.minimum(limit, 1.0 - s), sized)   # fmin: a 0 / 0 size is no limit
        predicted = (series.transpose(1, 2, 0) @ (h[:, None] ** _POWERS)[:, :, None])[..., 0]
        s_new = s + h
        corrected, new_inverse, first, last = _correct(homotopy, predicted, s_new)
        scale = _norms(corrected)
        accepted = ((last <= CORRECTOR_TOLERANCE * scale)
                    & (first <= np.maximum(CORRECTOR_STEP_FRACTION * _norms(predicted - z),
                                           CORRECTOR_FLOOR * scale)))
        z = np.where(accepted[:, None], corrected, z)
        inverse = np.where(accepted[:, None, None], new_inverse, inverse)
        s = np.where(accepted, s_new, s)
        limit = np.where(accepted, np.minimum(MAX_STEP, STEP_GROWTH * h), STEP_SHRINK * h)
        done = (s >= 1.0) | (limit < MIN_STEP)
        if far < np.inf:
            # Near its end, a path this far out goes to infinity: stop it there.
            ending = np.flatnonzero(~done & (s > 1.0 - END_OF_PATH))
            done[ending] = _far(z[ending], far)
        if np.any(done):
            ends[index[done]], reached[index[done]] = z[done], s[done]
            going = ~done
            index, z, s = index[going], z[going], s[going]
            inverse, limit = inverse[going], limit[going]
    ends[index], reached[index] = z, s
    return ends, reached


def _far(z, far):
    """
    Say which points (n, 8) lie farther out than ``far`` (the normalised position's norm).

    The position is ``|2 vec(g e*)| / |e . e| <= 2 |z|^2 / |e . e|``: only the points whose
    ``e . e`` is that small need the exact distance.
    """
    e = z[:, :4]
    delta = np.abs(np.add.reduce(e * e, axis=-1))
    result = np.zeros(len(z), dtype=bool)
    maybe = np.flatnonzero(~(delta * far > 2.0 * _norms(z) ** 2))
    if maybe.size:
        with np.errstate(divide='ignore', invalid='ignore'):
            result[maybe] = ~(_norms(_translation_times_delta(z[maybe])) / delta[maybe] <= far)
    return result


def _correct(homotopy, predicted, s):
    """
    Newton's method at ``s`` from the predicted points, CORRECTOR_ITERATIONS at most.

    Every point takes two iterations; only those whose error left after the second (its
    correction times the ratio of its correction to the first: Newton's quadratic
    convergence) is above CORRECTOR_TOLERANCE take a third, with the second's inverse
    Jacobian.

    :returns: ``(points, inverse Jacobians at the last iterate but one, first correction,
        error left)``, the sizes (n,) as norms (NaN where a Jacobian was singular: every
        comparison refuses it).
    """
    values, jacobians = homotopy.evaluate(predicted, s)
    try:
        correction = np.linalg.solve(jacobians, values[..., None])[..., 0]
    except np.linalg.LinAlgError:   # one singular matrix fails the batch: NaN for it alone
        correction = _apply(_invert(jacobians), values)
    z = predicted - correction
    first = _norms(correction)
    values, jacobians = homotopy.evaluate(z, s)
    inverse = _invert(jacobians)
    correction = _apply(inverse, values)
    z -= correction
    # Newton converges quadratically: the next correction would be about this one times its
    # ratio to the one before, the error left in z.
    with np.errstate(divide='ignore', invalid='ignore'):
        last = _norms(correction) * np.minimum(1.0, _norms(correction) / first)
    for _ in range(CORRECTOR_ITERATIONS - 2):
        more = np.flatnonzero(~(last <= CORRECTOR_TOLERANCE * _norms(z)) & np.isfinite(last))
        if more.size == 0:
            break
        # The Jacobian hardly changed: its inverse from the second iteration serves.
        correction = _apply(inverse[more], homotopy.evaluate(z[more], s[more])[0])
        z[more] -= correction
        last[more] = _norms(correction)
    return z, inverse, first, last


def newton(start, quadrics, points, tolerance=END_TOLERANCE):
    """
    Polish points on the system ``quadrics`` (s = 1): the end game's Newton iterations.

    Each point takes iterations until its correction is below ``tolerance`` relative to it
    (END_ITERATIONS at most); only the points still moving take the next one.

    :returns: ``(points, residuals, conditions)``: the polished points, and at each point's
        last iterate but one (a correction of ``tolerance`` away) the equations' largest value
        relative to ``max(1, |z|^2)`` and the Jacobian's condition number, the Frobenius one
        ``|J| |J^-1|`` (at most 8 times the 2-norm's: ample for :data:`SINGULAR_END`).
    """
    z = np.array(points, dtype=complex).reshape(-1, 8)
    residuals = np.full(len(z), np.inf)
    conditions = np.full(len(z), np.inf)
    homotopy = Homotopy(start, quadrics, quadrics)
    moving = np.arange(len(z))
    for _ in range(END_ITERATIONS):
        if moving.size == 0:
            break
        values, jacobians = homotopy.evaluate(z[moving], np.ones(moving.size))
        inverses = _invert(jacobians)
        correction = _apply(inverses, values)
        residuals[moving] = np.max(np.abs(values), axis=-1) / np.maximum(
            1.0, _norms(z[moving]) ** 2)
        with np.errstate(invalid='ignore'):
            conditions[moving] = np.linalg.norm(jacobians, axis=(-2, -1)) * np.linalg.norm(
                inverses, axis=(-2, -1))
        finite = np.all(np.isfinite(correction), axis=-1)
        z[moving[finite]] -= correction[finite]
        moving = moving[finite & ~(_norms(correction) <= tolerance * _norms(z[moving]))]
    return z, residuals, np.where(np.isnan(conditions), np.inf, conditions)


def polish(start, target, ends):
    """Polish the path ends; return them with their residuals and condition numbers (newton)."""
    return newton(start, target, ends)


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
