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
Reference values and implementations shared by the tests, independent of the package.

The paper's platform (Tables 1 and 2) and ramp (Table 3) typed from the paper, and the
textbook formulas the package is checked against: elementary rotations multiplied out,
half-angle quaternions, leg lengths leg by leg in plain Python. Nothing here imports
stewart_kinematics except :func:`paper_geometry`, which builds a Geometry from these tables.
"""

from fractions import Fraction
import math

import numpy as np

#: Table 1, base joints b_1..b_6, millimetres.
TABLE_1_MM = (
    (48.6989, 219.6666, 0.0),
    (165.8874, 152.0078, 0.0),
    (165.8874, -152.0078, 0.0),
    (48.6989, -219.6666, 0.0),
    (-214.5863, -67.6588, 0.0),
    (-214.5863, 67.6588, 0.0),
)
#: Table 2, platform joints p_1..p_6, millimetres (p_3 z = 257 as printed).
TABLE_2_MM = (
    (-51.3030, 140.9539, 275.0),
    (147.7212, 26.0472, 275.0),
    (147.7212, -26.0472, 257.0),
    (-51.3030, -140.9539, 275.0),
    (-96.4181, -114.9067, 275.0),
    (-96.4181, 114.9067, 275.0),
)
#: The same in metres, shape (6, 3).
BASE_JOINTS = np.array(TABLE_1_MM) / 1000.0
PLATFORM_JOINTS = np.array(TABLE_2_MM) / 1000.0
#: Table 3: start and step of X, Y, Z (millimetres) and alpha, beta, gamma (degrees), 11 rows.
TABLE_3_START_MM_DEG = (0.0, 0.0, 432.5, 0.0, 0.0, 0.0)
TABLE_3_STEP_MM_DEG = (10.0, 15.0, 10.0, 1.5, -1.5, 2.0)
TABLE_3_ROW_COUNT = 11


def to_si(pose_mm_deg):
    """Return a pose given in millimetres and degrees in metres and radians, as a tuple."""
    return (tuple(value / 1000.0 for value in pose_mm_deg[:3])
            + tuple(math.radians(value) for value in pose_mm_deg[3:]))


def table_3_row(k):
    """Return row k (0..10) of Table 3 as [X, Y, Z, alpha, beta, gamma], metres and radians."""
    return to_si([start + k * step
                  for start, step in zip(TABLE_3_START_MM_DEG, TABLE_3_STEP_MM_DEG)])


#: Table 3's rows, metres and radians; the first is the home pose.
TABLE_3 = tuple(table_3_row(k) for k in range(TABLE_3_ROW_COUNT))
HOME = TABLE_3[0]
TABLE_3_END = TABLE_3[-1]


def joints_on_a_circle(radius, angles_deg):
    """Joints ``(r cos a, r sin a, 0)`` on a circle of ``radius`` metres, one per angle (deg)."""
    return np.array([(radius * math.cos(math.radians(angle)),
                      radius * math.sin(math.radians(angle)), 0.0) for angle in angles_deg])


#: The example designs of config/platform_6_3.yaml and platform_3_3.yaml, from their drawings:
#: the base of the paper's size (radius 0.225 m; joints in pairs 35 degrees apart around 60,
#: -60 and 180 degrees, or at those three angles), the platform joints on a circle of 0.15 m
#: at 120, 0 and -120 degrees, each shared by two legs; home 0.7 m above the base, level.
DESIGN_BASE_ANGLES_DEG = {'6-3': (77.5, 42.5, -42.5, -77.5, -162.5, 162.5),
                          '3-3': (60.0, 60.0, -60.0, -60.0, 180.0, 180.0)}
DESIGN_PLATFORM_ANGLES_DEG = (120.0, 0.0, 0.0, -120.0, -120.0, 120.0)
DESIGN_HOME = (0.0, 0.0, 0.7, 0.0, 0.0, 0.0)
#: The pairs of legs that share a joint in each design, by side.
DESIGN_SHARED = {
    '6-3': {'base': (), 'platform': ((1, 6), (2, 3), (4, 5))},
    '3-3': {'base': ((1, 2), (3, 4), (5, 6)), 'platform': ((1, 6), (2, 3), (4, 5))},
}


def design_joints(design):
    """Return the base and platform joints (6, 3) of an example design, '6-3' or '3-3'."""
    return (joints_on_a_circle(0.225, DESIGN_BASE_ANGLES_DEG[design]),
            joints_on_a_circle(0.15, DESIGN_PLATFORM_ANGLES_DEG))


def paper_geometry(**changes):
    """
    Build the paper's platform (home pose: Table 3's first row), with optional changes.

    :param changes: Geometry's arguments, and the pose limits' settings (SI units, such as
        ``leg_length_max``), which become its ``limits``.
    """
    from stewart_kinematics.limits import PoseLimits
    from stewart_kinematics.limits.kinds import pose_settings
    from stewart_kinematics.model.geometry import Geometry
    limits = {name: changes.pop(name) for name in list(changes) if name in pose_settings()}
    arguments = {'base_joints': BASE_JOINTS, 'platform_joints': PLATFORM_JOINTS,
                 'home_pose': HOME}
    arguments.update(changes)
    if limits:
        arguments['limits'] = PoseLimits(**limits)
    return Geometry(**arguments)


def _cos_sin(angle):
    """Cosine and sine: math's of a float, numpy's of a long double (kept long)."""
    if isinstance(angle, np.longdouble):
        return np.cos(angle), np.sin(angle)
    return math.cos(angle), math.sin(angle)


def rx(angle):
    """Elementary rotation about x (in long double for a long double angle)."""
    c, s = _cos_sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]], dtype=np.result_type(c))


def ry(angle):
    """Elementary rotation about y."""
    c, s = _cos_sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]], dtype=np.result_type(c))


def rz(angle):
    """Elementary rotation about z."""
    c, s = _cos_sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]], dtype=np.result_type(c))


def rotation_zyx(alpha, beta, gamma):
    """Return ``Rz(gamma) @ Ry(beta) @ Rx(alpha)``, the product of the elementary matrices."""
    return rz(gamma) @ ry(beta) @ rx(alpha)


def rotations_zyx(angles):
    """
    Return ``Rz(gamma) @ Ry(beta) @ Rx(alpha)`` for angles (N, 3), shape (N, 3, 3).

    The elementary matrices of each row, stacked and multiplied.
    """
    angles = np.asarray(angles, dtype=float)
    count = len(angles)
    ca, sa = np.cos(angles[:, 0]), np.sin(angles[:, 0])
    cb, sb = np.cos(angles[:, 1]), np.sin(angles[:, 1])
    cg, sg = np.cos(angles[:, 2]), np.sin(angles[:, 2])
    zero, one = np.zeros(count), np.ones(count)
    rx_ = np.stack([one, zero, zero, zero, ca, -sa, zero, sa, ca], -1).reshape(-1, 3, 3)
    ry_ = np.stack([cb, zero, sb, zero, one, zero, -sb, zero, cb], -1).reshape(-1, 3, 3)
    rz_ = np.stack([cg, -sg, zero, sg, cg, zero, zero, zero, one], -1).reshape(-1, 3, 3)
    return rz_ @ ry_ @ rx_


def rodrigues(axis, angle):
    """Matrix of a rotation by ``angle`` (radians) about a unit ``axis``, by Rodrigues' formula."""
    x, y, z = axis
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)


def rotation_vector_matrix(vector):
    """Matrix of the rotation by ``|vector|`` radians about ``vector`` (:func:`rodrigues`)."""
    angle = float(np.linalg.norm(vector))
    return np.eye(3) if angle == 0.0 else rodrigues(np.asarray(vector) / angle, angle)


def rotation_vector_matrices(vectors):
    """Rodrigues' formula for rotation vectors (N, 3), vectorised: shape (N, 3, 3)."""
    vectors = np.asarray(vectors, dtype=float)
    angle = np.linalg.norm(vectors, axis=-1)[:, None, None]
    k = vectors / np.maximum(np.linalg.norm(vectors, axis=-1), 1e-300)[:, None]
    cross = np.zeros((len(vectors), 3, 3))
    cross[:, 0, 1], cross[:, 0, 2], cross[:, 1, 2] = -k[:, 2], k[:, 1], -k[:, 0]
    cross -= np.swapaxes(cross, 1, 2)
    return np.eye(3) + np.sin(angle) * cross + (1.0 - np.cos(angle)) * cross @ cross


def quaternion_product(q, r):
    """Hamilton product of quaternions ``(x, y, z, w)``."""
    qx, qy, qz, qw = q
    rx_, ry_, rz_, rw = r
    return (qw * rx_ + qx * rw + qy * rz_ - qz * ry_,
            qw * ry_ - qx * rz_ + qy * rw + qz * rx_,
            qw * rz_ + qx * ry_ - qy * rx_ + qz * rw,
            qw * rw - qx * rx_ - qy * ry_ - qz * rz_)


def axis_angle_quaternion(axis, angle):
    """Quaternion ``(x, y, z, w)`` of a rotation by ``angle`` (radians) about a unit ``axis``."""
    half = 0.5 * angle
    return np.array([*(math.sin(half) * np.asarray(axis, dtype=float)), math.cos(half)])


def quaternion_from_euler(alpha, beta, gamma):
    """
    Return the unit quaternion ``(x, y, z, w)`` of ``Rz(gamma) Ry(beta) Rx(alpha)``, ``w >= 0``.

    The product ``q_z(gamma) q_y(beta) q_x(alpha)`` of the half-angle quaternions.
    """
    q = quaternion_product(
        quaternion_product((0.0, 0.0, math.sin(gamma / 2), math.cos(gamma / 2)),
                           (0.0, math.sin(beta / 2), 0.0, math.cos(beta / 2))),
        (math.sin(alpha / 2), 0.0, 0.0, math.cos(alpha / 2)))
    return np.array(q) if q[3] >= 0.0 else -np.array(q)


def quaternion_matrix(x, y, z, w):
    """Rotation matrix of a unit quaternion ``(x, y, z, w)``, the textbook formula."""
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def rotation_angle(rotation_a, rotation_b):
    """Angle in radians between two rotation matrices, from the axis-angle of ``A^T B``."""
    relative = np.asarray(rotation_a).T @ np.asarray(rotation_b)
    skew = 0.5 * np.array([relative[2, 1] - relative[1, 2], relative[0, 2] - relative[2, 0],
                           relative[1, 0] - relative[0, 1]])
    return math.atan2(float(np.linalg.norm(skew)), 0.5 * (float(np.trace(relative)) - 1.0))


def quaternion_angle(q, r):
    """Angle in radians between the rotations of two unit quaternions ``(x, y, z, w)``."""
    qx, qy, qz, qw = q
    x, y, z, w = quaternion_product((-qx, -qy, -qz, qw), r)
    # From the vector part: accurate near zero, where acos of w would lose half the digits.
    return 2.0 * math.atan2(math.sqrt(x * x + y * y + z * z), abs(w))


def leg_lengths(pose, base=BASE_JOINTS, platform=PLATFORM_JOINTS):
    """
    Return the six leg lengths ``|t + R p_i - b_i|`` of a pose, leg by leg, in plain Python.

    :param pose: ``[X, Y, Z, alpha, beta, gamma]``, metres and radians.
    """
    position, rotation = np.asarray(pose[:3], dtype=float), rotation_zyx(*pose[3:])
    return [math.sqrt(sum(value * value for value in (position + rotation @ p - b).tolist()))
            for b, p in zip(np.asarray(base), np.asarray(platform))]


def leg_lengths_of_matrix(position, rotation, base=BASE_JOINTS, platform=PLATFORM_JOINTS):
    """
    Return the six leg lengths ``|t + R p_i - b_i|`` of a position and a rotation matrix.

    Leg by leg, shape (6,); ``base`` and ``platform`` are the joints, metres, (6, 3).
    """
    position, rotation = np.asarray(position, dtype=float), np.asarray(rotation, dtype=float)
    return np.array([np.linalg.norm(position + rotation @ p - b)
                     for b, p in zip(np.asarray(base), np.asarray(platform))])


def leg_lengths_batch(positions, rotations, base=BASE_JOINTS, platform=PLATFORM_JOINTS):
    """Return ``|t + R p_i - b_i|`` for positions (N, 3) and rotations (N, 3, 3): (N, 6)."""
    legs = (np.asarray(positions, dtype=float)[:, None, :]
            + np.einsum('nij,kj->nki', rotations, platform) - base)
    return np.linalg.norm(legs, axis=-1)


def leg_lengths_long(pose, base=BASE_JOINTS, platform=PLATFORM_JOINTS):
    """
    Return :func:`leg_lengths` computed in numpy's long double, shape (6,).

    On x86 a long double has a 64-bit mantissa, 2048 times finer than a float: a reference
    for errors near the float rounding floor.
    """
    pose = np.asarray(pose, dtype=np.longdouble)
    rotation = rotation_zyx(*pose[3:])
    legs = pose[:3] + np.asarray(platform, dtype=np.longdouble) @ rotation.T - np.asarray(
        base, dtype=np.longdouble)
    return np.sqrt(np.sum(legs * legs, axis=1))


def random_poses(count, seed, around=HOME, position_range=0.1, angle_range_deg=15.0):
    """Draw poses within +-0.1 m and +-15 degrees of ``around``, shape (count, 6)."""
    rng = np.random.default_rng(seed)
    offsets = np.column_stack([
        rng.uniform(-position_range, position_range, (count, 3)),
        rng.uniform(-math.radians(angle_range_deg), math.radians(angle_range_deg),
                    (count, 3))])
    return np.asarray(around) + offsets


def twist_jacobian(pose, base=BASE_JOINTS, platform=PLATFORM_JOINTS):
    """
    Return the rows ``[u_i, R p_i x u_i]`` that map a twist ``[v, w]`` to leg velocities.

    Leg ``i`` changes at ``u_i . (v + w x R p_i)``, ``u_i`` its unit vector (base frame).
    """
    position, rotation = np.asarray(pose[:3], dtype=float), rotation_zyx(*pose[3:])
    rows = []
    for b, p in zip(np.asarray(base), np.asarray(platform)):
        leg = position + rotation @ p - b
        unit = leg / math.sqrt(float(leg @ leg))
        rows.append(np.concatenate([unit, np.cross(rotation @ p, unit)]))
    return np.array(rows)


def singular_yaw():
    """
    Return the yaw (radians) near 90.4 degrees where the paper's platform is singular.

    At the home position with no roll or pitch: the root of det(twist Jacobian), by bisection.
    """
    def determinant(gamma):
        return float(np.linalg.det(twist_jacobian(HOME[:5] + (gamma,))))

    low, high = math.radians(90.0), math.radians(91.0)
    assert determinant(low) * determinant(high) < 0.0
    for _ in range(100):
        middle = 0.5 * (low + high)
        if determinant(low) * determinant(middle) <= 0.0:
            high = middle
        else:
            low = middle
    return 0.5 * (low + high)


def point_segment_distance(points, starts, ends):
    """
    Distance from points to segments, by the projection clamped to the segment.

    :param points: shape (..., 3); ``starts`` and ``ends`` of the segments likewise.
    :returns: shape (...); a segment of zero length is its start point.
    """
    direction = ends - starts
    squared = np.sum(direction * direction, axis=-1)
    with np.errstate(divide='ignore', invalid='ignore'):
        along = np.sum((points - starts) * direction, axis=-1) / squared
    along = np.where(squared > 0.0, np.clip(along, 0.0, 1.0), 0.0)
    return np.linalg.norm(points - (starts + along[..., None] * direction), axis=-1)


def segment_distance(p0, p1, q0, q1):
    """
    Distance between segments ``p0 p1`` and ``q0 q1``: the textbook enumeration of candidates.

    The squared distance between ``p0 + s (p1 - p0)`` and ``q0 + t (q1 - q0)`` is a convex
    quadratic in ``(s, t)``; its minimum over the unit square is either the critical point of
    the two lines (when they are not parallel and it lies in the square) or on one of the
    square's four edges, each the distance from an end point to the other segment. The
    smallest of those five candidates is the distance.

    In floating point, so not exact for near-parallel segments (within about 1e-6 rad the
    critical point is left out, and above that it is computed with the cancellation of
    ``a e - b^2``): :func:`segment_distance_exact` is exact at every angle.

    :param p0: shape (..., 3); ``p1``, ``q0``, ``q1`` likewise.
    :returns: shape (...).
    """
    p0, p1, q0, q1 = (np.asarray(value, dtype=float) for value in (p0, p1, q0, q1))
    candidates = [point_segment_distance(p0, q0, q1), point_segment_distance(p1, q0, q1),
                  point_segment_distance(q0, p0, p1), point_segment_distance(q1, p0, p1)]
    d1, d2, r = p1 - p0, q1 - q0, p0 - q0
    a, b, e = (np.sum(x * y, axis=-1) for x, y in ((d1, d1), (d1, d2), (d2, d2)))
    c, f = np.sum(d1 * r, axis=-1), np.sum(d2 * r, axis=-1)
    determinant = a * e - b * b
    with np.errstate(divide='ignore', invalid='ignore'):
        # Normal equations: a s - b t = -c, -b s + e t = f (Cramer's rule).
        s = (b * f - c * e) / determinant
        t = (a * f - b * c) / determinant
    inside = (determinant > 1e-12 * a * e) & (s >= 0.0) & (s <= 1.0) & (t >= 0.0) & (t <= 1.0)
    s, t = np.where(inside, s, 0.0), np.where(inside, t, 0.0)
    between = (p0 + s[..., None] * d1) - (q0 + t[..., None] * d2)
    candidates.append(np.where(inside, np.linalg.norm(between, axis=-1), np.inf))
    return np.min(candidates, axis=0)


def segment_distance_exact(first, second, offset):
    """
    Distance between the segments ``p + s first`` and ``q + t second``, exact up to one rounding.

    The same enumeration as :func:`segment_distance` (the critical point of the two lines when
    it lies in the unit square, else the best point of each of the square's four edges: an end
    point's clamped projection onto the other segment) in exact rational arithmetic on the
    floats given, so parallel, near-parallel and zero-length segments cost no digits. The
    squared distance is exact; its square root is rounded once.

    :param first: the first segment's vector ``p1 - p0``, three floats; ``second`` likewise.
    :param offset: ``p0 - q0``, three floats.
    :returns: the distance, a float.
    """
    d1, d2, r = ([Fraction(float(value)) for value in vector]
                 for vector in (first, second, offset))

    def dot(u, v):
        return sum((x * y for x, y in zip(u, v)), Fraction(0))

    def clamp(value):
        return min(max(value, Fraction(0)), Fraction(1))

    def squared(s, t):
        between = [x + s * y - t * z for x, y, z in zip(r, d1, d2)]
        return dot(between, between)

    a, b, e, c, f = dot(d1, d1), dot(d1, d2), dot(d2, d2), dot(d1, r), dot(d2, r)
    candidates = []
    for end in (Fraction(0), Fraction(1)):
        # The end s = 0 or 1 of the first segment, and its projection onto the second.
        candidates.append(squared(end, clamp((b * end + f) / e) if e else Fraction(0)))
        candidates.append(squared(clamp((b * end - c) / a) if a else Fraction(0), end))
    determinant = a * e - b * b
    if determinant:
        s, t = (b * f - c * e) / determinant, (a * f - b * c) / determinant
        if 0 <= s <= 1 and 0 <= t <= 1:
            candidates.append(squared(s, t))
    return math.sqrt(float(min(candidates)))


def segment_distance_by_search(p0, p1, q0, q1, iterations=200):
    """
    Distance between segments by a ternary search over ``s`` (a second, slower reference).

    The distance from ``p0 + s (p1 - p0)`` to the segment ``q0 q1`` is convex in ``s``, so a
    ternary search converges to its minimum; 200 iterations leave an interval of 1e-35.
    """
    p0, p1, q0, q1 = (np.asarray(value, dtype=float) for value in (p0, p1, q0, q1))
    low, high = np.zeros(p0.shape[:-1]), np.ones(p0.shape[:-1])

    def distance(s):
        return point_segment_distance(p0 + s[..., None] * (p1 - p0), q0, q1)

    for _ in range(iterations):
        left, right = low + (high - low) / 3.0, high - (high - low) / 3.0
        closer = distance(left) <= distance(right)
        high = np.where(closer, right, high)
        low = np.where(closer, low, left)
    return np.minimum(distance(0.5 * (low + high)), np.minimum(distance(low), distance(high)))
