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
Reachability: every reason a pose, or a set of leg lengths, is not allowed.

The limits are those of :class:`stewart_kinematics.Geometry`:

- leg length: ``leg_length_min <= l_i <= leg_length_max`` (actuator stroke);
- joint cone angle: the angle between leg ``i`` and its direction at the home pose, seen from
  the base joint (base frame) and from the platform joint (platform frame), is at most
  ``base_joint_max_angle`` and ``platform_joint_max_angle``; the home direction is the joint's
  neutral axis, as a joint is mounted to sit centred there;
- singularity margin: the condition number of the dimensionless Jacobian (see
  :func:`jacobian_condition`) is at most ``max_jacobian_condition``.

Like a hexapod controller's "is this pose valid?", the checks return every violation (which
leg, which limit, by how much), not only the first. Nothing here imports ROS.
"""

from dataclasses import dataclass
import math
from typing import Dict, List, Optional

import numpy as np

from stewart_kinematics.model.kinematics import (
    as_leg_lengths,
    as_poses,
    jacobian_condition,
    leg_lengths,
    leg_vectors,
)
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

#: How many failing samples :func:`check_samples` lists in full.
LISTED_FAILURES = 10


@dataclass(frozen=True)
class Violation:
    """
    One limit that a pose or a set of leg lengths breaks.

    :param limit: the limit's parameter name, such as ``leg_length_max``.
    :param leg: the leg concerned, 1..6, or ``None`` for the whole platform.
    :param value: the value reached, in ``unit``.
    :param allowed: the limit, in ``unit``.
    :param unit: ``m``, ``deg`` or ``''`` (condition number).
    """

    limit: str
    leg: Optional[int]
    value: float
    allowed: float
    unit: str

    @property
    def excess(self) -> float:
        """By how much the limit is broken, in ``unit``, always positive."""
        return abs(self.value - self.allowed)

    def __str__(self):
        unit = f' {self.unit}' if self.unit else ''
        subject = f'leg {self.leg}' if self.leg else 'platform'
        return (f'{subject}: {self.limit} {self.allowed:.6g}{unit} broken by '
                f'{self.excess:.6g}{unit} (value {self.value:.6g}{unit})')


def leg_length_violations(geometry, lengths) -> List[Violation]:
    """
    Every leg length outside ``[leg_length_min, leg_length_max]``.

    :param lengths: leg lengths l_1..l_6 in metres, shape (6,).
    :raises ValueError: if the lengths are not six finite, positive numbers.
    """
    lengths = as_leg_lengths(lengths)
    if lengths.shape != (6,):
        raise ValueError(f'expected the 6 lengths of one pose, got shape {lengths.shape}')
    return _length_violations(geometry, lengths.tolist())


def _length_violations(geometry, lengths):
    """:func:`leg_length_violations` of six lengths (floats) known to be finite, maybe 0."""
    violations = []
    for leg, length in enumerate(lengths, start=1):
        if length < geometry.leg_length_min:
            violations.append(Violation('leg_length_min', leg, length, geometry.leg_length_min,
                                        'm'))
        elif length > geometry.leg_length_max:
            violations.append(Violation('leg_length_max', leg, length, geometry.leg_length_max,
                                        'm'))
    return violations


def joint_angles(geometry, position, rotation):
    """
    Cone angles of the joints: each leg's angle to its home direction, radians.

    :param position: platform position in the base frame, metres, shape (3,) or (N, 3).
    :param rotation: platform-to-base rotation, shape (3, 3) or (N, 3, 3).
    :returns: ``(base_angles, platform_angles)``, each shape (6,) or (N, 6): at the base joint
        measured in the base frame, at the platform joint measured in the platform frame; NaN
        for a leg of zero length.
    """
    legs = leg_vectors(geometry, position, rotation)
    # A leg of zero length has no direction: its angles are NaN, which no limit allows.
    with np.errstate(divide='ignore', invalid='ignore'):
        directions = legs / np.linalg.norm(legs, axis=-1, keepdims=True)
    home = geometry.home_leg_directions
    home_rotation = euler_zyx_to_matrix(geometry.home_pose[3:])
    # In the platform frame: R^T u now against R_home^T u_home.
    platform_now = np.swapaxes(np.swapaxes(rotation, -1, -2) @ np.swapaxes(directions, -1, -2),
                               -1, -2)
    platform_home = home @ home_rotation
    return _angle_between(directions, home), _angle_between(platform_now, platform_home)


def check_pose(geometry, position, rotation, condition=None) -> List[Violation]:
    """
    Every limit that one pose breaks; empty when the pose is allowed.

    :param position: platform position in the base frame, metres, shape (3,).
    :param rotation: platform-to-base rotation matrix, shape (3, 3).
    :param condition: the pose's :func:`jacobian_condition` when already known (a forward
        kinematics result carries it), so that it is not computed twice.
    :raises ValueError: if the position or the rotation is malformed or not finite; any other
        pose gets its list, a platform joint on its base joint included (a leg of zero length
        breaks the singularity margin and the joint cones, having no direction).
    """
    position, rotation = np.asarray(position, dtype=float), np.asarray(rotation, dtype=float)
    if position.shape != (3,) or rotation.shape != (3, 3):
        raise ValueError(f'expected a position (3,) and a rotation (3, 3), got shapes '
                         f'{position.shape} and {rotation.shape}')
    if not all(map(math.isfinite, position.tolist() + rotation.ravel().tolist())):
        raise ValueError(f'pose must be finite, got position {position.tolist()}')
    # Each check runs only where its limit is set: the nodes call this for every message.
    violations = []
    if geometry.leg_length_min > 0.0 or geometry.leg_length_max < math.inf:
        lengths = leg_lengths(geometry, position, rotation)
        if not np.all(np.isfinite(lengths)):
            as_leg_lengths(lengths)  # raises: a pose so far away that its lengths overflow
        violations += _length_violations(geometry, lengths.tolist())
    if min(geometry.base_joint_max_angle, geometry.platform_joint_max_angle) < math.pi:
        base_angles, platform_angles = joint_angles(geometry, position, rotation)
        for limit, angles, allowed in (
                ('base_joint_max_angle', base_angles, geometry.base_joint_max_angle),
                ('platform_joint_max_angle', platform_angles,
                 geometry.platform_joint_max_angle)):
            for leg in np.flatnonzero(~(angles <= allowed)):
                violations.append(Violation(limit, int(leg) + 1, math.degrees(angles[leg]),
                                            math.degrees(allowed), 'deg'))
    if math.isfinite(geometry.max_jacobian_condition):
        if condition is None:
            condition = float(jacobian_condition(geometry, position, rotation))
        if not condition <= geometry.max_jacobian_condition:
            violations.append(Violation('max_jacobian_condition', None, condition,
                                        geometry.max_jacobian_condition, ''))
    return violations


def check_poses(geometry, poses) -> List[List[Violation]]:
    """
    Every limit that each of a batch of poses breaks.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (N, 6).
    :returns: one list per pose, empty for an allowed pose, as :func:`check_pose` gives it.
    """
    poses = np.atleast_2d(as_poses(poses))
    # The vectorised checks find the poses to explain; check_pose explains each one.
    refused = np.flatnonzero(~check_poses_array(geometry, poses).allowed)
    violations = [[] for _ in range(len(poses))]
    for index, rotation in zip(refused, euler_zyx_to_matrix(poses[refused, 3:])):
        violations[index] = check_pose(geometry, poses[index, :3], rotation)
    return violations


#: The limits in the order :func:`check_pose` reports them.
LIMIT_NAMES = ('leg_length_min', 'leg_length_max', 'base_joint_max_angle',
               'platform_joint_max_angle', 'max_jacobian_condition')
#: Poses per block of :func:`check_poses_array`: the temporaries of a block stay in the
#: processor's cache (measured fastest between 512 and 2048).
CHECK_BLOCK_SIZE = 1024


@dataclass(frozen=True, eq=False)
class LimitChecks:
    """
    The limit checks of N poses as arrays: which limits each pose breaks, and by how much.

    Only the limits set in the geometry are checked, as in :func:`check_pose`: the values of
    the others are ``None`` and ``broken`` has no key for them.

    :param geometry: the geometry whose limits were checked.
    :param lengths: leg lengths, metres, shape (N, 6) (``None`` without a stroke limit).
    :param base_angles: cone angles at the base joints, radians, shape (N, 6) (``None``
        without a cone limit), as :func:`joint_angles` gives them.
    :param platform_angles: the same at the platform joints, in the platform frame.
    :param condition: condition number of the dimensionless Jacobian, shape (N,) (``None``
        without a singularity margin), as :func:`jacobian_condition` gives it.
    :param broken: per limit name (see :data:`LIMIT_NAMES`), where it is broken, with
        :func:`check_pose`'s comparisons: shape (N, 6) per leg, (N,) for the condition number.
    :param allowed: shape (N,), True where the pose breaks no limit.
    """

    geometry: object
    lengths: Optional[np.ndarray]
    base_angles: Optional[np.ndarray]
    platform_angles: Optional[np.ndarray]
    condition: Optional[np.ndarray]
    broken: Dict[str, np.ndarray]
    allowed: np.ndarray

    def __len__(self):
        return len(self.allowed)

    def excess(self, limit: str) -> np.ndarray:
        """
        How far beyond ``limit`` each pose is, in metres, radians or as a condition number.

        :param limit: one of the keys of ``broken``.
        :returns: shape (N, 6) per leg, (N,) for ``max_jacobian_condition``: positive where
            broken, zero or negative (minus the margin left) where kept.
        :raises KeyError: for a limit that the geometry does not set.
        """
        if limit not in self.broken:
            raise KeyError(f'{limit} is not set in this geometry; checked: {list(self.broken)}')
        geometry = self.geometry
        if limit == 'leg_length_min':
            return geometry.leg_length_min - self.lengths
        values = {'leg_length_max': self.lengths, 'base_joint_max_angle': self.base_angles,
                  'platform_joint_max_angle': self.platform_angles,
                  'max_jacobian_condition': self.condition}[limit]
        return values - getattr(geometry, limit)

    def broken_limits(self, index: int) -> List[str]:
        """Names of the limits that pose ``index`` breaks, in :data:`LIMIT_NAMES` order."""
        return [name for name, mask in self.broken.items() if np.any(mask[index])]

    def violations(self, index: int) -> List[Violation]:
        """
        Return the :class:`Violation` list of pose ``index``, as :func:`check_pose` gives it.

        Stroke per leg, base cones, platform cones, then the condition number: the same limits
        and legs as check_pose, with values equal to within rounding (1e-12 relative).
        """
        geometry = self.geometry
        violations = []
        if self.lengths is not None:
            for leg in range(6):
                for name in ('leg_length_min', 'leg_length_max'):
                    if self.broken[name][index, leg]:
                        violations.append(Violation(name, leg + 1,
                                                    float(self.lengths[index, leg]),
                                                    getattr(geometry, name), 'm'))
        for name, angles in (('base_joint_max_angle', self.base_angles),
                             ('platform_joint_max_angle', self.platform_angles)):
            if angles is None:
                continue
            for leg in np.flatnonzero(self.broken[name][index]):
                violations.append(Violation(name, int(leg) + 1, math.degrees(angles[index, leg]),
                                            math.degrees(getattr(geometry, name)), 'deg'))
        if self.condition is not None and self.broken['max_jacobian_condition'][index]:
            violations.append(Violation('max_jacobian_condition', None,
                                        float(self.condition[index]),
                                        geometry.max_jacobian_condition, ''))
        return violations


def check_poses_array(geometry, poses, *, condition_of_refused=True) -> LimitChecks:
    """
    Every limit that each of a batch of poses breaks, vectorised: :func:`check_pose` as arrays.

    No Python loop runs over the poses: stroke and joint cones cost well under a microsecond a
    pose; the singularity margin, one small singular value decomposition a pose, costs a few.

    :param poses: ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (6,) or (N, 6).
    :param condition_of_refused: with False, the condition number (the dearest check) is
        computed only for the poses that keep the stroke and the cones: elsewhere it is NaN
        and ``broken['max_jacobian_condition']`` False. ``allowed`` is the same either way;
        only the list of reasons of a refused pose may lack the singularity margin.
    :returns: a :class:`LimitChecks`; ``.violations(k)`` gives pose k's :class:`Violation` list.
    :raises ValueError: if a pose has the wrong shape or a non-finite value.

    >>> import numpy as np
    >>> from stewart_kinematics import load_geometry
    >>> from stewart_kinematics.limits import check_poses_array
    >>> geometry = load_geometry(['config/paper_platform.yaml', 'config/example_limits.yaml'])
    >>> poses = geometry.home_pose + [[0.0, 0, 0, 0, 0, 0], [0, 0, 0.2, 0, 0, 0],
    ...                               [0.1, 0, 0, 0, 0, 0]]
    >>> checks = check_poses_array(geometry, poses)
    >>> checks.allowed, checks.excess('leg_length_max').max(axis=-1).round(6)
    (array([ True, False,  True]), array([-0.181145,  0.01638 , -0.15812 ]))
    >>> print(checks.violations(1)[0])
    leg 1: leg_length_max 0.9 m broken by 0.01638 m (value 0.91638 m)
    """
    poses = np.atleast_2d(as_poses(poses))
    count = poses.shape[0]
    stroke = geometry.leg_length_min > 0.0 or geometry.leg_length_max < math.inf
    cones = min(geometry.base_joint_max_angle, geometry.platform_joint_max_angle) < math.pi
    singularity = math.isfinite(geometry.max_jacobian_condition)
    # Computed as (6, N), poses along the last axis (see _check_block), returned as (N, 6).
    values = {name: np.empty((6, count)) for name, wanted in (
        ('lengths', stroke), ('base_angles', cones), ('platform_angles', cones)) if wanted}
    broken = {name: np.empty((6, count), dtype=bool) for name, wanted in (
        ('leg_length_min', stroke), ('leg_length_max', stroke),
        ('base_joint_max_angle', cones), ('platform_joint_max_angle', cones)) if wanted}
    condition = np.full(count, np.nan) if singularity else None
    allowed = np.ones(count, dtype=bool)
    if stroke or cones or singularity:
        constants = _check_constants(geometry)
        for start in range(0, count, CHECK_BLOCK_SIZE):
            block = slice(start, start + CHECK_BLOCK_SIZE)
            _check_block(geometry, poses[block], constants,
                         {name: array[:, block] for name, array in values.items()},
                         {name: array[:, block] for name, array in broken.items()},
                         None if condition is None else condition[block],
                         condition_of_refused, allowed[block])
    values = {name: array.T for name, array in values.items()}
    broken = {name: array.T for name, array in broken.items()}
    if singularity:
        # As in check_pose, a NaN condition number breaks the margin, except where it was
        # not computed (condition_of_refused False): those poses are refused already.
        broken['max_jacobian_condition'] = (
            ~(condition <= geometry.max_jacobian_condition) if condition_of_refused
            else condition > geometry.max_jacobian_condition)
    return LimitChecks(geometry, values.get('lengths'), values.get('base_angles'),
                       values.get('platform_angles'), condition, broken, allowed)


def _check_constants(geometry):
    """
    Joint data for :func:`_check_block`, each component as a (6, 1) column.

    :returns: ``(platform joints p_i, base joints b_i, home leg directions u_home_i, home leg
        directions seen from the platform R_home^T u_home_i)``, each a tuple of its x, y and z
        components.
    """
    home = geometry.home_leg_directions
    platform_home = home @ euler_zyx_to_matrix(geometry.home_pose[3:])
    return tuple(tuple(array[:, axis:axis + 1].copy() for axis in range(3))
                 for array in (geometry.platform_joints, geometry.base_joints, home,
                               platform_home))


def _check_block(geometry, poses, constants, values, broken, condition, condition_of_refused,
                 allowed):
    """
    Check a block of poses (n, 6): write into the (6, n) arrays of ``values`` and ``broken``.

    Elementwise products of (6, 1) columns and (n,) rows rather than a matrix product: with
    a 12-wide inner dimension, BLAS gains nothing, and its threads stall on a busy machine;
    with the poses along the last axis, numpy's inner loops run over the whole block.

    :param condition: (n,) to write the condition numbers into, or None.
    :param allowed: (n,), cleared where a pose breaks a limit.
    """
    platform, base, home, platform_home = constants
    position = poses[:, :3].T
    ca, cb, cg = np.cos(poses[:, 3:].T)
    sa, sb, sg = np.sin(poses[:, 3:].T)
    # Rows of R = Rz(gamma) Ry(beta) Rx(alpha), as in rotations.euler_zyx_to_matrix.
    sb_sa, sb_ca = sb * sa, sb * ca
    rows = ((cg * cb, cg * sb_sa - sg * ca, cg * sb_ca + sg * sa),
            (sg * cb, sg * sb_sa + cg * ca, sg * sb_ca - cg * sa),
            (-sb, cb * sa, cb * ca))
    # R p_i, then the legs t + R p_i - b_i, per component, shape (6, n).
    rotated = [r1 * platform[0] + r2 * platform[1] + r3 * platform[2] for r1, r2, r3 in rows]
    lx, ly, lz = (rotated[axis] + (position[axis] - base[axis]) for axis in range(3))
    if 'lengths' in values:
        lengths = values['lengths']
        np.sqrt(lx * lx + ly * ly + lz * lz, out=lengths)
        np.less(lengths, geometry.leg_length_min, out=broken['leg_length_min'])
        np.greater(lengths, geometry.leg_length_max, out=broken['leg_length_max'])
    if 'base_angles' in values:
        _block_angles(lx, ly, lz, home[0], home[1], home[2], values['base_angles'])
        hx, hy, hz = (r1 * platform_home[0] + r2 * platform_home[1] + r3 * platform_home[2]
                      for r1, r2, r3 in rows)
        _block_angles(lx, ly, lz, hx, hy, hz, values['platform_angles'])
        for name, angles in (('base_joint_max_angle', values['base_angles']),
                             ('platform_joint_max_angle', values['platform_angles'])):
            np.greater(angles, getattr(geometry, name), out=broken[name])
    for mask in broken.values():
        allowed &= ~np.any(mask, axis=0)
    if condition is not None:
        columns = slice(None) if condition_of_refused else np.flatnonzero(allowed)
        condition[columns] = _block_condition(
            lx[:, columns], ly[:, columns], lz[:, columns],
            *(component[:, columns] for component in rotated),
            radius=geometry.platform_radius)
        allowed &= condition <= geometry.max_jacobian_condition


def _block_condition(lx, ly, lz, ax, ay, az, radius):
    """
    Condition numbers of :func:`jacobian_condition` from legs and rotated joints ``R p_i``.

    :param lx: ..., the legs' and the rotated joints' components, each shape (6, n).
    :returns: shape (n,); ``inf`` where a leg has zero length or the Jacobian is singular.
    """
    with np.errstate(divide='ignore', invalid='ignore'):
        lengths = np.sqrt(lx * lx + ly * ly + lz * lz)
        ux, uy, uz = lx / lengths, ly / lengths, lz / lengths
        # Rows [u_i, (R p_i x u_i) / rho], as in kinematics.twist_jacobian.
        rows = np.stack([ux, uy, uz, (ay * uz - az * uy) / radius,
                         (az * ux - ax * uz) / radius, (ax * uy - ay * ux) / radius], axis=-1)
        degenerate = ~np.all(np.isfinite(rows), axis=(0, 2))
        rows[:, degenerate] = 0.0
        singular_values = np.linalg.svd(np.swapaxes(rows, 0, 1), compute_uv=False)
        condition = singular_values[:, 0] / singular_values[:, -1]
    condition[degenerate] = np.inf
    return condition


def _block_angles(lx, ly, lz, hx, hy, hz, out):
    """Angles between legs ``l`` and directions ``h``, atan2 of ``|l x h|`` and ``l . h``."""
    cx = ly * hz - lz * hy
    cy = lz * hx - lx * hz
    cz = lx * hy - ly * hx
    np.arctan2(np.sqrt(cx * cx + cy * cy + cz * cz), lx * hx + ly * hy + lz * hz, out=out)


def check_samples(geometry, times, poses):
    """
    Refuse a trajectory any of whose samples breaks a limit of ``geometry``.

    trajectory_node checks every pose it would publish with this before it plays a ramp.

    :param times: seconds from the start of a pass, shape (N,).
    :param poses: the samples, ``[X, Y, Z, alpha, beta, gamma]``, shape (N, 6).
    :raises ValueError: listing the failing samples (time, pose, every violation).
    """
    failures = [(index, violations) for index, violations
                in enumerate(check_poses(geometry, poses)) if violations]
    if not failures:
        return
    lines = [
        f'sample {index} at t={times[index]:.3f} s, pose '
        f'{np.round(poses[index], 6).tolist()}: ' + '; '.join(map(str, violations))
        for index, violations in failures[:LISTED_FAILURES]]
    more = len(failures) - LISTED_FAILURES
    raise ValueError(
        f'ramp refused: {len(failures)} of {len(poses)} samples break the limits of the '
        'geometry:\n  ' + '\n  '.join(lines) + (f'\n  ... and {more} more' if more > 0 else ''))


def _angle_between(a, b):
    # atan2 of |a x b| and a . b is accurate for small and large angles alike.
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))
