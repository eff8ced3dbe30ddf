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
Leg collisions: two legs may not come closer than their thickness.

Each leg is a capsule of radius ``leg_radius`` around the segment from its base joint ``b_i``
to its platform joint ``b_i + L_i`` (base frame); two legs collide when the distance between
their segments is below ``2 * leg_radius``. All 15 pairs of every pose are checked at once,
except the pairs that share a joint (a 6-3 or 3-3 platform's, see
:attr:`stewart_kinematics.Geometry.shared_joints`): their capsules meet at that joint by
design, so their distance is 0 at every pose; they are given an infinite distance (never
broken), and the joint cones still bound how far each of them turns in the joint.

The distance between two segments is the minimum of a convex quadratic over the unit square
(Ericson, Real-Time Collision Detection, section 5.1.9): the parameters of the closest points
of the two lines, clamped, with the second one recomputed for the clamped first and the first
for that second. A segment of zero length (a platform joint on its base joint) is a point, and
parallel segments (no unique closest points) are handled without dividing by zero.

Near-parallel legs need care, and legs are often close to parallel. The textbook parameter of
the closest points, ``(b f - c e) / (a e - b^2)``, divides two differences of nearly equal
products: at an angle theta between the legs both lose about ``-log10(theta^2)`` of their 16
digits, and the clamp-and-project steps do not make up for a wrong parameter (distances up to
1.3e-8 m too large near 1e-8 rad, before this was fixed). Where ``a e - b^2 < NEAR_PARALLEL a e``
(legs within 0.01 rad of parallel or anti-parallel) the parameter comes from cross products
instead, ``((L_j x r) . n) / (n . n)`` with ``n = L_i x L_j``, equal by Lagrange's identity:
each component of ``n`` is exact to the rounding of ``|L_i| |L_j|``, so the parameter is wrong
only where the lines are so close to parallel that the distance hardly changes along them.
The distances are exact to 1e-13 of the leg length at every angle down to exactly parallel
(worst measured 4e-14, just above 0.01 rad; below it 1e-15; test_leg_collision.py checks
1e-12 against an exact rational distance).

One pose (:meth:`LegCollision.violations_of_one`) first tries a lower bound of all 15
distances (:func:`cleared`), a fraction of their cost: where it proves every pair clear of
``2 * leg_radius`` the pose has no violation, and the distances are computed only where it
does not (every pose of the Table 3 ramp is proved; about half of the random poses within 0.15 m
and 0.6 rad of home). Nothing here imports ROS.
"""

import numpy as np

from stewart_kinematics.limits.base import Bound, LEG_PAIRS, Limit, PAIR
from stewart_kinematics.limits.kind import BoundLook, LimitKind, LimitParameter
from stewart_kinematics.model.validators import Finite, InRange

#: The rows of the 15 pairs, legs 0..5: first and second leg of each (see LEG_PAIRS).
FIRST, SECOND = np.triu_indices(6, 1)
#: Pairs with ``a e - b^2`` below this fraction of ``a e`` (the squared sine of the angle between
#: the legs: 1e-4 is 0.01 rad) get the closest points' parameter from cross products. Above it
#: the textbook formula is exact to 4e-14 of the leg length (measured); below it, it is not.
NEAR_PARALLEL = 1e-4
#: The points ``(s0, t0)`` of the unit square where :func:`cleared` bounds the distance: the
#: middle of both legs and the four pairs of ends.
BOUND_POINTS = ((0.5, 0.5), (0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0))
#: The rows of a pose's six leg vectors (and columns of their Gram matrix) of each pair.
PAIR_ROWS = np.concatenate([FIRST, SECOND])


def _bound_coefficients():
    """
    Return the (20, 5) matrix that gives :func:`cleared` its terms from ``a, e, b, c, f``.

    With ``w = r + s0 L_i - t0 L_j``: ``g^2 = |r|^2 + s0^2 a + t0^2 e - 2 s0 t0 b + 2 s0 c
    - 2 t0 f``, ``w . L_i = c + s0 a - t0 b``, ``w . L_j = f + s0 b - t0 e`` (``a = L_i .
    L_i``, ``e = L_j . L_j``, ``b = L_i . L_j``, ``c = L_i . r``, ``f = L_j . r``). Rows: the
    linear part of ``g`` times the bound (``g^2 + (1/2 - s0) w . L_i + (t0 - 1/2) w . L_j``,
    without ``|r|^2``), ``g^2`` (likewise), ``w . L_i / 2`` and ``w . L_j / 2``, five points each.
    """
    rows = {'linear': [], 'squares': [], 'first': [], 'second': []}
    for s0, t0 in BOUND_POINTS:
        squares = np.array([s0 * s0, t0 * t0, -2.0 * s0 * t0, 2.0 * s0, -2.0 * t0])
        first = np.array([s0, 0.0, -t0, 1.0, 0.0])
        second = np.array([0.0, -t0, s0, 0.0, 1.0])
        rows['linear'].append(squares + (0.5 - s0) * first + (t0 - 0.5) * second)
        rows['squares'].append(squares)
        rows['first'].append(0.5 * first)
        rows['second'].append(0.5 * second)
    return np.array([row for name in rows for row in rows[name]])


#: See :func:`_bound_coefficients`.
BOUND_COEFFICIENTS = _bound_coefficients()
#: Where ``a, e, b, c, f`` of the 15 pairs are in the flattened (6, 21) products of
#: :func:`cleared` (leg vectors with themselves, then with the pairs' offsets).
_PRODUCT_INDICES = np.concatenate([FIRST * 22, SECOND * 22, FIRST * 21 + SECOND,
                                   FIRST * 21 + 6 + np.arange(15),
                                   SECOND * 21 + 6 + np.arange(15)])
#: The allowance for rounding in :func:`cleared`, times the square of the pose's scale (the
#: longest offset between base joints plus twice the longest leg): a thousand times its
#: rounding, which is a few 1e-16, and 100 times the distances' own error (1e-13 of the leg).
BOUND_ROUNDING = 1e-11
#: Poses of a larger scale (metres) skip :func:`cleared`, whose squares would overflow.
SCALE_LIMIT = 1e100


class LegCollision(Limit):
    """
    Evaluator of ``leg_collision``: the distance between the axes of each pair, shape (15, n).

    :param geometry: a :class:`stewart_kinematics.Geometry`. Pairs that share a joint are not
        checked: their distance is ``inf``.
    :param radius: ``leg_radius``, metres; 0 (the default) is not set.
    """

    dear = True

    def __init__(self, geometry, radius: float = 0.0):
        self.bounds = (Bound('leg_collision', 2.0 * radius, False, PAIR, 'm'),) if radius else ()
        offsets = geometry.base_joints[FIRST] - geometry.base_joints[SECOND]
        self._offsets = tuple(offsets[:, axis:axis + 1].copy() for axis in range(3))
        #: The rows (of LEG_PAIRS) of the pairs that share a joint: never checked.
        self.shared_rows = np.array(sorted(LEG_PAIRS.index(joint.legs)
                                           for joint in geometry.shared_joints), dtype=int)
        squared = np.zeros((20, len(LEG_PAIRS)))
        squared[:10] = (offsets * offsets).sum(axis=1)
        self._pair_offsets = (offsets.T.copy(), squared)
        self._offset_scale = float(np.sqrt((offsets * offsets).sum(axis=1)).max())
        self._clearances = np.full(len(LEG_PAIRS), 2.0 * radius)

    def values(self, arrays):
        """Return the distances between the legs' axes, metres, (15, n); ``inf`` if shared."""
        distances = segment_distances(*arrays.vectors[:3], arrays.lengths, self._offsets)
        if self.shared_rows.size:
            distances[self.shared_rows] = np.inf
        return (distances,)

    def violations_of_one(self, legs):
        """
        See :meth:`Limit.violations_of_one`: none where :func:`cleared` proves every pair clear.

        Elsewhere the distances of :meth:`values`, as the batch path computes them.
        """
        if legs.floats is None or not self.bounds:
            return super().violations_of_one(legs)
        columns = np.array(legs.floats)   # (6, 7): l, lx, ly, lz, ax, ay, az of each leg
        scale = self._offset_scale + 2.0 * float(columns[:, 0].max())
        if scale < SCALE_LIMIT and cleared(columns[:, 1:4], self._pair_offsets,
                                           self._clearances, self.shared_rows,
                                           BOUND_ROUNDING * scale * scale):
            return []
        return super().violations_of_one(legs)


def cleared(vectors, offsets, clearances, unchecked, rounding: float) -> bool:
    """
    Whether one pose's 15 segment distances are proved above their clearances, cheaply.

    The distance ``g(s, t) = |w(s, t)|``, ``w = r + s L_i - t L_j``, is convex on the unit
    square, so at any point ``(s0, t0)`` it is at least its tangent plane there:
    ``g(s, t) >= g0 + dg/ds (s - s0) + dg/dt (t - t0)``, with ``dg/ds = w . L_i / g0`` and
    ``dg/dt = -w . L_j / g0`` at that point; the smallest of the plane over the square,
    ``g0 - (|w . L_i| + |w . L_j|) / (2 g0) + ((1/2 - s0) w . L_i + (t0 - 1/2) w . L_j) / g0``
    (as ``s - s0`` runs over ``[-s0, 1 - s0]``, ``t - t0`` likewise), is a lower bound of the
    distance. Each pair takes the best of five such bounds (:data:`BOUND_POINTS`: the middle
    and the four pairs of ends, where side by side or converging legs have their closest
    points), multiplied through by ``g0``; all from the six legs' dot products with each other
    and with the offsets (:func:`_bound_coefficients`). A bound proves a pair when it exceeds
    the clearance by ``rounding / g0``: then the distance :func:`segment_distances` computes
    exceeds it too.

    :param vectors: the leg vectors ``L``, shape (6, 3), metres, base frame.
    :param offsets: ``(b_i - b_j)^T`` of the 15 pairs, shape (3, 15), and their squared
        lengths in the first ten rows of (20, 15), zeros below.
    :param clearances: ``2 * leg_radius`` per pair, shape (15,).
    :param unchecked: the rows of the pairs not checked (that share a joint), integers: a
        pair whose segments meet has no positive lower bound.
    :param rounding: allowance for rounding, square metres: much more than the rounding of
        these sums and of the distances.
    :returns: True when every pair is proved clear; False proves nothing (a non-finite value
        included).
    """
    transposed, squared_offsets = offsets
    products = vectors @ np.concatenate((vectors.T, transposed), axis=1)   # (6, 6 + 15)
    terms = BOUND_COEFFICIENTS @ products.take(_PRODUCT_INDICES).reshape(5, 15)
    terms += squared_offsets
    squares = np.fmax(terms[5:10], 0.0, out=terms[5:10])
    halves = np.abs(terms[10:])
    bounds = terms[:5] - halves[:5]
    bounds -= halves[5:]
    bounds -= clearances * np.sqrt(squares)
    best = bounds.max(axis=0)
    if unchecked.size:
        best[unchecked] = np.inf
    return bool(best.min() > rounding)


def segment_distances(lx, ly, lz, lengths, offsets):
    """
    Distances between the segments ``b_i + s L_i`` and ``b_j + t L_j``, ``s, t`` in [0, 1].

    :param lx: x of the leg vectors ``L``, shape (6, n); ``ly`` and ``lz`` likewise.
    :param lengths: ``|L|``, shape (6, n).
    :param offsets: ``b_i - b_j`` of the 15 pairs, x, y and z each shape (15, 1).
    :returns: shape (15, n), metres.
    """
    rx, ry, rz = offsets
    xi, yi, zi = lx.take(FIRST, axis=0), ly.take(FIRST, axis=0), lz.take(FIRST, axis=0)
    xj, yj, zj = lx.take(SECOND, axis=0), ly.take(SECOND, axis=0), lz.take(SECOND, axis=0)
    squares = lengths * lengths
    a, e = squares.take(FIRST, axis=0), squares.take(SECOND, axis=0)
    work = np.empty_like(a)
    # b = L_i . L_j, c = L_i . r, f = L_j . r.
    b = xi * xj
    b += np.multiply(yi, yj, out=work)
    b += np.multiply(zi, zj, out=work)
    c = xi * rx
    c += np.multiply(yi, ry, out=work)
    c += np.multiply(zi, rz, out=work)
    f = xj * rx
    f += np.multiply(yj, ry, out=work)
    f += np.multiply(zj, rz, out=work)
    # s of the closest points of the two lines, clamped; where they are parallel (or a leg is
    # a point) the division gives inf or NaN, which the clamp turns into 0 or 1: any s then
    # does, as t and s are recomputed below. Near-parallel pairs get s from cross products.
    denominator = a * e
    near_parallel = denominator * NEAR_PARALLEL
    denominator -= np.multiply(b, b, out=work)
    s = b * f
    s -= np.multiply(c, e, out=work)
    with np.errstate(divide='ignore', invalid='ignore'):
        s /= denominator
        near_parallel = np.less(denominator, near_parallel)
        if np.count_nonzero(near_parallel):
            _near_parallel_parameters(s, near_parallel, (xi, yi, zi), (xj, yj, zj), offsets)
        _clamp(s)
        # t of the closest point of segment j to the point at s, clamped (0 for a point:
        # 0 / 0); then s for that t.
        t = np.multiply(b, s, out=work)
        t += f
        t /= e
        _clamp(t)
        np.multiply(b, t, out=s)
        s -= c
        s /= a
        _clamp(s)
    # The vector between the two closest points, r + s L_i - t L_j, and its length.
    xi *= s
    xi += rx
    xj *= t
    xi -= xj
    yi *= s
    yi += ry
    yj *= t
    yi -= yj
    zi *= s
    zi += rz
    zj *= t
    zi -= zj
    xi *= xi
    yi *= yi
    zi *= zi
    xi += yi
    xi += zi
    return np.sqrt(xi, out=xi)


def _near_parallel_parameters(s, where, first, second, offsets):
    """
    Set ``s`` where ``where`` holds to the closest points' parameter on the first leg's line.

    ``s = ((L_j x r) . n) / (n . n)``, ``n = L_i x L_j``: equal to ``(b f - c e) / (a e - b^2)``
    (Lagrange's identity) but without its cancellation. Exactly parallel pairs get NaN (0 / 0),
    which the clamp that follows turns into 0. Elementwise, so a pose gives the same bits alone
    and in a batch.

    :param s: shape (15, n), changed in place.
    :param where: boolean, shape (15, n).
    :param first: x, y, z of ``L_i``, each (15, n); ``second`` of ``L_j`` likewise.
    :param offsets: x, y, z of ``r = b_i - b_j``, each (15, 1).
    """
    rows, columns = np.nonzero(where)
    xi, yi, zi = (values[rows, columns] for values in first)
    xj, yj, zj = (values[rows, columns] for values in second)
    rx, ry, rz = (values[rows, 0] for values in offsets)
    nx, ny, nz = yi * zj - zi * yj, zi * xj - xi * zj, xi * yj - yi * xj
    mx, my, mz = yj * rz - zj * ry, zj * rx - xj * rz, xj * ry - yj * rx
    s[rows, columns] = (mx * nx + my * ny + mz * nz) / (nx * nx + ny * ny + nz * nz)


def _clamp(values):
    """Clamp to [0, 1] in place: NaN becomes 0 (fmax ignores it), inf 1 and -inf 0."""
    np.fmax(values, 0.0, out=values)
    np.fmin(values, 1.0, out=values)


def _evaluator(geometry, limits) -> LegCollision:
    return LegCollision(geometry, limits.leg_radius)


#: Leg collisions: their parameter (``leg_radius``), bound (``leg_collision``) and evaluator.
KIND = LimitKind(
    name='leg_collision',
    title='Leg collisions',
    meaning=('Each leg a capsule of this radius around its axis, the segment from its base '
             'joint to its platform joint; two legs collide when their axes come closer than '
             '`2 * leg_radius`. See below.'),
    evaluator='LegCollision',
    parameters=(
        LimitParameter(
            'leg_radius', 'm', 0.0,
            'Radius of each leg, metres: a leg is a capsule of this radius around the segment '
            'from its base joint to its platform joint, and a pose where two legs come closer '
            'than 2 * leg_radius is refused (leg_collision); 0.0 for no collision check',
            (Finite(), InRange(0.0, 1.0))),
    ),
    bounds=(BoundLook('leg_collision', 'leg collision', (0.55, 0.34, 0.29)),),
    pose_evaluator=_evaluator,
)
