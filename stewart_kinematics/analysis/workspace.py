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
Workspace: what the platform can reach, under every limit of its geometry.

- :func:`travel_ranges`: from a pose (the home pose by default), the largest move along each
  of the six pose coordinates alone, both ways, and the limit and leg that stop it;
- :func:`workspace_volume`: the constant-orientation workspace, the positions reachable at one
  orientation: volume (m^3), bounding box and boundary points;
- :func:`workspace_slice`: a plane through a pose (XY at a height, XZ, YZ, or two angles such
  as alpha-beta for the orientation workspace at a position): which points are reachable,
  the limit that excludes the others, the boundary and the condition number (dexterity);
- :func:`orientation_workspace`: alpha-beta slices at a position for several gamma values.

Poses are ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians, ``R = Rz(gamma) Ry(beta)
Rx(alpha)``) and place the pivot point, so a change of an angle alone turns the platform about
the pivot (about the base axes x, y, z from a level orientation). The limits are every kind
of :mod:`stewart_kinematics.limits` (:data:`~stewart_kinematics.limits.LIMIT_KINDS`: stroke,
joint cones, singularity margin, leg collision, leg forces), checked with its vectorised
:func:`~stewart_kinematics.limits.check_poses_array` on grids of poses; each crossing of the
boundary between two grid points is then located by bisection to ``tolerance``. The leg
force limit judges each pose with its static forces, from the masses the geometry carries
(:attr:`~stewart_kinematics.Geometry.mass_properties`): a heavy payload shrinks the ranges
and the volume where an actuator would push more than ``leg_force_max`` or pull more than
``-leg_force_min`` to hold it; with every mass 0 nothing changes. Nothing here imports ROS.

Like any sampled method, a forbidden gap narrower than the scan step of a ray or the
resolution of a grid can be missed; the steps are arguments.
"""

from dataclasses import dataclass
import math
from typing import Optional, Sequence, Tuple

import numpy as np

from stewart_kinematics.limits import check_poses_array
from stewart_kinematics.limits.kinds import pose_limit_names
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.inputs import as_poses
from stewart_kinematics.model.jacobians import jacobian_condition
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

#: Names and units of the six pose coordinates.
AXES = ('X', 'Y', 'Z', 'alpha', 'beta', 'gamma')
UNITS = ('m', 'm', 'm', 'rad', 'rad', 'rad')
#: Farthest a travel range or a grid reaches from its start, metres and radians: no hexapod
#: moves a metre, and a rotation beyond half a turn wraps round.
DEFAULT_SPAN = (1.0, math.pi)
#: Step of the scan of a travel range, metres and radians, before bisection: a forbidden
#: gap narrower than this along a ray can be missed.
DEFAULT_SCAN_STEP = (5e-4, 1e-3)
#: Samples of each ray checked at a time, outwards from the start.
SCAN_CHUNK = 256
#: Bisection stops when a boundary is known this closely, metres and radians.
DEFAULT_TOLERANCE = (1e-7, 1e-7)
#: Poses classified at once: bounds the memory of a grid of millions of points.
CHUNK_SIZE = 200_000
#: Times a grid is grown, by half its width, while reachable points touch its border.
MAX_GROWTH = 8
#: The extent of a grid is found on a grid this many times coarser.
COARSE_FACTOR = 4


@dataclass(frozen=True)
class AxisTravel:
    """
    The range along one pose coordinate from a start pose, the others held.

    :param axis: ``X``, ``Y``, ``Z``, ``alpha``, ``beta`` or ``gamma``.
    :param unit: ``m`` or ``rad``.
    :param negative: the largest move in the negative direction, <= 0, in ``unit``.
    :param positive: the largest move in the positive direction, >= 0, in ``unit``.
    :param negative_limit: the limit that stops the negative move (a name of
        :data:`~stewart_kinematics.limits.LIMIT_NAMES`), or ``None`` if none stops it within
        the span searched (then ``negative`` is minus the span).
    :param negative_leg: the leg (1..6) at that limit, or ``None`` (condition number, or no
        limit).
    :param positive_limit: the same at the positive end.
    :param positive_leg: the same at the positive end.
    """

    axis: str
    unit: str
    negative: float
    positive: float
    negative_limit: Optional[str]
    negative_leg: Optional[int]
    positive_limit: Optional[str]
    positive_leg: Optional[int]


@dataclass(frozen=True)
class TravelRanges:
    """
    Travel ranges along the six pose coordinates from one start pose.

    :param start: the start pose ``[X, Y, Z, alpha, beta, gamma]``, metres and radians.
    :param axes: one :class:`AxisTravel` per coordinate, in pose order.
    :param tolerance: how closely each end is located, metres and radians.
    """

    start: np.ndarray
    axes: Tuple[AxisTravel, ...]
    tolerance: Tuple[float, float]

    def as_array(self) -> np.ndarray:
        """Return ``[[negative, positive], ...]`` per coordinate, shape (6, 2), m and rad."""
        return np.array([[axis.negative, axis.positive] for axis in self.axes])

    def table(self) -> str:
        """Return the ranges as a text table, in millimetres and degrees."""
        lines = [f'{"axis":<6} {"negative":>11} {"positive":>11}  '
                 f'{"stopped at negative end by":<34} stopped at positive end by']
        for axis in self.axes:
            scale, unit = (1e3, 'mm') if axis.unit == 'm' else (math.degrees(1.0), 'deg')
            lines.append(
                f'{axis.axis:<6} {axis.negative * scale:>8.3f} {unit:<3}'
                f'{axis.positive * scale:>8.3f} {unit:<3}  '
                f'{describe_limit(axis.negative_limit, axis.negative_leg):<34} '
                f'{describe_limit(axis.positive_limit, axis.positive_leg)}')
        return '\n'.join(lines)


def describe_limit(limit: Optional[str], leg: Optional[int]) -> str:
    """Return ``'leg_length_max, leg 3'``, ``'max_jacobian_condition'`` or ``'none'``."""
    if limit is None:
        return 'none (span searched)'
    return f'{limit}, leg {leg}' if leg else limit


def travel_ranges(geometry, pose=None, *, span=DEFAULT_SPAN, step=DEFAULT_SCAN_STEP,
                  tolerance=DEFAULT_TOLERANCE) -> TravelRanges:
    """
    Find the largest move along each pose coordinate alone, both ways, from ``pose``.

    Each of the twelve rays is scanned outwards at ``step`` until a sample breaks a limit, or
    out to ``span``; that sample and the one before bracket the end of the connected range
    that contains the start (a ray may leave the workspace and come back: the rest is not
    reported), and bisection locates it to ``tolerance``. The reported end is reachable; a
    move beyond it by ``tolerance`` breaks the limit named.

    :param geometry: a :class:`stewart_kinematics.Geometry` with its limits.
    :param pose: start pose ``[X, Y, Z, alpha, beta, gamma]``, metres and radians; default
        ``geometry.home_pose``. A move of an angle alone changes that Euler angle, the pose
        coordinate that the nodes take; from a level orientation it turns the platform about
        the base axis x, y or z through the pivot point.
    :param span: ``(metres, radians)`` searched each way.
    :param step: ``(metres, radians)`` between the samples of the scan.
    :param tolerance: ``(metres, radians)`` to which each end is located.
    :returns: a :class:`TravelRanges`.
    :raises ValueError: if the start pose breaks a limit (its violations are listed).

    >>> from stewart_kinematics import load_geometry, travel_ranges
    >>> geometry = load_geometry(['config/paper_platform.yaml', 'config/example_limits.yaml'])
    >>> print(travel_ranges(geometry).table())  # doctest: +NORMALIZE_WHITESPACE
    axis      negative    positive  stopped at negative end by         stopped at positive end by
    X      -383.825 mm  387.664 mm   base_joint_max_angle, leg 5        base_joint_max_angle, leg 1
    Y      -372.253 mm  382.272 mm   base_joint_max_angle, leg 3        base_joint_max_angle, leg 2
    Z       -52.080 mm  183.457 mm   leg_length_min, leg 3              leg_length_max, leg 5
    alpha   -20.123 deg  20.123 deg  leg_length_min, leg 1              leg_length_min, leg 4
    beta    -22.985 deg  16.830 deg  leg_length_min, leg 5              leg_length_min, leg 3
    gamma   -82.416 deg  83.183 deg  max_jacobian_condition             max_jacobian_condition
    """
    start = _start_pose(geometry, pose)
    span, step = _pair('span', span), _pair('step', step)
    tolerance = _pair('tolerance', tolerance)
    per_axis = np.repeat(step, 3)
    counts = np.ceil(np.repeat(span, 3) / per_axis).astype(int)
    # The twelve rays: axis a, sign s, samples k * step for k = 1 .. counts[a], scanned
    # outwards SCAN_CHUNK samples at a time, a ray dropping out at its first refusal.
    rays = [(axis, sign) for axis in range(6) for sign in (-1.0, 1.0)]
    first_refused = [None] * len(rays)
    active = list(range(len(rays)))
    for start_index in range(1, max(counts) + 1, SCAN_CHUNK):
        active = [ray for ray in active if start_index <= counts[rays[ray][0]]]
        if not active:
            break
        chunks = [np.arange(start_index, min(start_index + SCAN_CHUNK,
                                             counts[rays[ray][0]] + 1)) for ray in active]
        poses = np.repeat(start[None, :], sum(map(len, chunks)), axis=0)
        first = 0
        for ray, chunk in zip(active, chunks):
            axis, sign = rays[ray]
            poses[first:first + len(chunk), axis] += sign * per_axis[axis] * chunk
            first += len(chunk)
        allowed = _classify(geometry, poses).allowed
        first = 0
        for ray, chunk in zip(active, chunks):
            refused = np.flatnonzero(~allowed[first:first + len(chunk)])
            first += len(chunk)
            if refused.size:
                first_refused[ray] = int(chunk[refused[0]])
        active = [ray for ray in active if first_refused[ray] is None]

    inside, outside, stopped = [], [], []
    for ray, (axis, sign) in enumerate(rays):
        stopped.append(first_refused[ray] is not None)
        outside_index = first_refused[ray] if stopped[-1] else counts[axis]
        inside_pose, outside_pose = start.copy(), start.copy()
        inside_pose[axis] += sign * per_axis[axis] * (outside_index - 1 if stopped[-1]
                                                      else outside_index)
        outside_pose[axis] += sign * per_axis[axis] * outside_index
        inside.append(inside_pose)
        outside.append(outside_pose)
    inside, outside = np.array(inside), np.array(outside)
    stopped = np.array(stopped)
    limit = np.full(len(rays), -1)
    leg = np.zeros(len(rays), dtype=int)
    if np.any(stopped):
        refined = _bisect(geometry, inside[stopped], outside[stopped],
                          np.repeat(np.asarray(tolerance, dtype=float), 3))
        inside[stopped], limit[stopped], leg[stopped] = refined[0], refined[2], refined[3]

    axes = []
    for axis in range(6):
        ends = []
        for ray in (2 * axis, 2 * axis + 1):
            name = pose_limit_names()[limit[ray]] if stopped[ray] else None
            ends += [inside[ray, axis] - start[axis], name,
                     int(leg[ray]) if stopped[ray] and leg[ray] else None]
        axes.append(AxisTravel(AXES[axis], UNITS[axis], float(ends[0]), float(ends[3]),
                               ends[1], ends[2], ends[4], ends[5]))
    return TravelRanges(start, tuple(axes), tuple(float(value) for value in tolerance))


@dataclass(frozen=True)
class WorkspaceSlice:
    """
    A plane of the workspace through a pose: two pose coordinates vary, four are held.

    Grid arrays have shape ``(len(v), len(u))`` (rows along ``v``), ready for matplotlib's
    ``pcolormesh(u, v, array)``.

    :param axes: indices (into :data:`AXES`) of the coordinates along ``u`` and ``v``.
    :param pose: the pose whose other four coordinates are held, metres and radians.
    :param u: the grid's values of the first coordinate, metres or radians.
    :param v: the grid's values of the second coordinate.
    :param allowed: True where the pose breaks no limit.
    :param limit: index into :data:`~stewart_kinematics.limits.LIMIT_NAMES` of the limit broken
        the most (relative to its value) at each point, -1 where allowed.
    :param leg: the leg of that limit, 1..6, 0 for the condition number or where allowed.
    :param condition: condition number of the dimensionless Jacobian (dexterity) where allowed,
        NaN elsewhere.
    :param boundary: points on the boundary, shape (M, 2) (u, v): each crossing of it between
        two neighbouring grid points, located to the tolerance; each point is reachable.
    :param boundary_limit: per boundary point, the index of the limit met there.
    :param boundary_leg: per boundary point, the leg of that limit (0: condition number).
    :param bounded: False if the grid reached ``span`` with reachable points on its border.
    """

    axes: Tuple[int, int]
    pose: np.ndarray
    u: np.ndarray
    v: np.ndarray
    allowed: np.ndarray
    limit: np.ndarray
    leg: np.ndarray
    condition: np.ndarray
    boundary: np.ndarray
    boundary_limit: np.ndarray
    boundary_leg: np.ndarray
    bounded: bool

    @property
    def labels(self) -> Tuple[str, str]:
        """Names of the two coordinates, such as ``('X', 'Y')``."""
        return AXES[self.axes[0]], AXES[self.axes[1]]

    @property
    def area(self) -> float:
        """Reachable area, from the grid cells: m^2, rad^2 or m rad."""
        return float(np.count_nonzero(self.allowed) * (self.u[1] - self.u[0])
                     * (self.v[1] - self.v[0]))


def workspace_slice(geometry, plane='XY', pose=None, *, resolution=None, extent=None,
                    tolerance=DEFAULT_TOLERANCE, span=DEFAULT_SPAN) -> WorkspaceSlice:
    """
    Map the reachable points of a plane through ``pose``, its boundary and its dexterity.

    :param plane: two coordinate names, ``'XY'``, ``'XZ'``, ``'YZ'``, or a pair such as
        ``('alpha', 'beta')``.
    :param pose: the pose whose other coordinates are held (and the grid's anchor); default
        ``geometry.home_pose``. Give an XY slice at a height as ``pose`` with that Z.
    :param resolution: grid step along each of the two coordinates (metres or radians);
        default 1 mm and 0.25 degrees.
    :param extent: ``((u_min, u_max), (v_min, v_max))`` to sample, in absolute coordinates;
        default around the travel ranges from ``pose`` (which must then be reachable), grown
        while reachable points touch the border.
    :param tolerance: ``(metres, radians)`` to which boundary points are located.
    :param span: ``(metres, radians)``: the farthest the grid grows from ``pose``.
    :returns: a :class:`WorkspaceSlice`.
    """
    axes = tuple(AXES.index(name) for name in _plane_names(plane))
    base = _base_pose(geometry, pose)
    if resolution is None:
        resolution = tuple(1e-3 if axis < 3 else math.radians(0.25) for axis in axes)
    resolution = _positive('resolution', resolution, 2)
    span, tolerance = _pair('span', span), _pair('tolerance', tolerance)
    if extent is not None:
        extent = as_float_array(extent, 'extent')
        if extent.shape != (2, 2) or not np.all(np.isfinite(extent)) or np.any(
                extent[:, 1] <= extent[:, 0]):
            raise ValueError(f'extent must be ((u_min, u_max), (v_min, v_max)), finite and '
                             f'increasing, got {preview(extent)}')
    grid = _Grid(geometry, base, axes, resolution, extent, span, with_condition=True)
    points, boundary_limit, boundary_leg = grid.boundary(tolerance)
    return WorkspaceSlice(axes, base, grid.coordinates[0], grid.coordinates[1],
                          grid.allowed.T, grid.limit.T, grid.leg.T, grid.condition.T,
                          points[:, list(axes)], boundary_limit, boundary_leg, grid.bounded)


@dataclass(frozen=True)
class WorkspaceVolume:
    """
    The constant-orientation workspace: every position reachable at one orientation.

    :param orientation: ``(alpha, beta, gamma)``, radians.
    :param volume: m^3.
    :param bounding_box: ``[[x_min, y_min, z_min], [x_max, y_max, z_max]]``, metres: in z from
        the boundary points (to the tolerance), in x and y from the reachable grid points
        (within one resolution inside the true box).
    :param resolution: grid step, metres.
    :param boundary: boundary points, shape (M, 3), metres, base frame: the crossings of the
        boundary along z between neighbouring grid points (the top and bottom of the
        workspace over each grid column), each located to the tolerance and reachable.
    :param boundary_limit: per boundary point, the index into
        :data:`~stewart_kinematics.limits.LIMIT_NAMES` of the limit met there.
    :param boundary_leg: per boundary point, the leg of that limit (0: condition number).
    :param bounded: False if the grid reached the span with reachable points on its border:
        the volume is then that of the part inside the span.
    """

    orientation: np.ndarray
    volume: float
    bounding_box: np.ndarray
    resolution: float
    boundary: np.ndarray
    boundary_limit: np.ndarray
    boundary_leg: np.ndarray
    bounded: bool


def workspace_volume(geometry, orientation=None, *, position=None, resolution=0.01,
                     tolerance=DEFAULT_TOLERANCE, span=DEFAULT_SPAN) -> WorkspaceVolume:
    """
    Measure the volume, bounding box and boundary of the positions reachable at one orientation.

    Positions are sampled on a grid of step ``resolution``; along each vertical line of the
    grid, the reachable intervals end at boundary crossings located by bisection, and the
    volume is the sum of their lengths times ``resolution ** 2``: exact along z, a midpoint
    rule across x and y (its error falls with the square of the resolution on a smooth
    boundary).

    :param orientation: ``(alpha, beta, gamma)``, radians; default the home orientation.
    :param position: a reachable position to grow the grid from, metres; default the home
        position.
    :param resolution: grid step, metres; the paper platform's volume under the example
        limits differs by 2e-4 (relative) between 20 mm and 10 mm.
    :returns: a :class:`WorkspaceVolume`.
    :raises ValueError: if the start (position, orientation) breaks a limit.
    """
    base = _base_pose(geometry, None)
    if orientation is not None:
        base[3:] = _finite('orientation', orientation, 3)
    if position is not None:
        base[:3] = _finite('position', position, 3)
    resolution = float(_positive('resolution', resolution, 1)[0])
    span, tolerance = _pair('span', span), _pair('tolerance', tolerance)
    grid = _Grid(geometry, as_poses(base), (0, 1, 2), np.full(3, resolution), None, span)
    points, limit, leg = grid.boundary(tolerance, dimensions=(2,))
    # Each column's reachable length is the sum of (exit - entry) of its intervals.
    heights = points[:, 2]
    length = np.sum(np.where(grid.crossing_entering, -heights, heights))
    # A column reachable at the grid's lowest or highest point (an unbounded workspace) is
    # cut there.
    z = grid.coordinates[2]
    length += np.count_nonzero(grid.allowed[:, :, -1]) * z[-1]
    length -= np.count_nonzero(grid.allowed[:, :, 0]) * z[0]
    volume = float(length * resolution ** 2)
    box = np.zeros((2, 3))
    if np.any(grid.allowed):
        columns = np.nonzero(np.any(grid.allowed, axis=2))
        for dimension in (0, 1):
            values = grid.coordinates[dimension][columns[dimension]]
            box[:, dimension] = values.min(), values.max()
        # In z: the boundary crossings, and the grid's ends where a column reaches them (an
        # unbounded workspace, such as a platform without limits, may have no crossing).
        ends = [heights]
        ends += [z[:1]] if np.any(grid.allowed[:, :, 0]) else []
        ends += [z[-1:]] if np.any(grid.allowed[:, :, -1]) else []
        ends = np.concatenate(ends)
        box[:, 2] = ends.min(), ends.max()
    return WorkspaceVolume(base[3:].copy(), volume, box, float(resolution), points[:, :3],
                           limit, leg, grid.bounded)


def orientation_workspace(geometry, position=None, gammas=(0.0,), *,
                          resolution=math.radians(0.25), tolerance=DEFAULT_TOLERANCE,
                          span=DEFAULT_SPAN) -> Tuple[WorkspaceSlice, ...]:
    """
    Map the reachable (alpha, beta) at one position, one slice per gamma.

    :param position: metres; default the home position.
    :param gammas: the gamma values, radians.
    :param resolution: grid step of alpha and beta, radians.
    :returns: one :class:`WorkspaceSlice` (plane alpha-beta) per gamma; ``area`` in rad^2.
    """
    slices = []
    gammas = as_float_array(gammas, 'gammas')
    if gammas.ndim != 1 or not np.all(np.isfinite(gammas)):
        raise ValueError(f'gammas must be finite angles (radians), shape (N,), got '
                         f'{preview(gammas)}')
    for gamma in gammas.tolist():
        pose = _base_pose(geometry, None)
        if position is not None:
            pose[:3] = _finite('position', position, 3)
        pose[5] = gamma
        slices.append(workspace_slice(geometry, ('alpha', 'beta'), pose, resolution=resolution,
                                      tolerance=tolerance, span=span))
    return tuple(slices)


@dataclass(frozen=True)
class WorkspaceShell:
    """
    Points on the boundary of the constant-orientation workspace, for a 3-D view (RViz).

    :param orientation: ``(alpha, beta, gamma)``, radians.
    :param points: shape (M, 3), metres, base frame: the top and bottom surfaces (the
        crossings along z of :func:`workspace_volume`) and horizontal rings (the boundaries of
        XY slices at ``layers`` heights), each point reachable and located to the tolerance.
    :param limit: per point, the index into :data:`~stewart_kinematics.limits.LIMIT_NAMES`
        of the limit met there.
    :param volume: the workspace volume, m^3.
    """

    orientation: np.ndarray
    points: np.ndarray
    limit: np.ndarray
    volume: float


def workspace_shell(geometry, orientation=None, *, resolution=0.01, layers=10,
                    tolerance=(1e-6, 1e-6)) -> WorkspaceShell:
    """
    Sample the boundary of the constant-orientation workspace as a cloud of points.

    :param orientation: ``(alpha, beta, gamma)``, radians; default the home orientation.
    :param resolution: grid step, metres: about ``(size / resolution) ** 2`` points.
    :param layers: horizontal rings between the lowest and highest reachable heights.
    :returns: a :class:`WorkspaceShell`.
    :raises ValueError: if the home position at that orientation breaks a limit.
    """
    volume = workspace_volume(geometry, orientation, resolution=resolution, tolerance=tolerance)
    points, limit = [volume.boundary], [volume.boundary_limit]
    (x_low, y_low, z_low), (x_high, y_high, z_high) = volume.bounding_box
    margin = 2.0 * resolution
    extent = ((x_low - margin, x_high + margin), (y_low - margin, y_high + margin))
    pose = _base_pose(geometry, None)
    pose[3:] = volume.orientation
    for height in np.linspace(z_low, z_high, layers + 2)[1:-1]:
        pose[2] = height
        ring = workspace_slice(geometry, 'XY', pose, resolution=resolution, extent=extent,
                               tolerance=tolerance)
        points.append(np.column_stack([ring.boundary, np.full(len(ring.boundary), height)]))
        limit.append(ring.boundary_limit)
    return WorkspaceShell(volume.orientation, np.concatenate(points), np.concatenate(limit),
                          volume.volume)


# Classification of poses ------------------------------------------------------------------------

@dataclass(frozen=True)
class _Classification:
    """
    Per pose: allowed, the limit broken the most, its leg, the condition number.

    ``limit`` is an index into LIMIT_NAMES, -1 where allowed; ``leg`` 1..6, 0 for none;
    ``condition`` where allowed (NaN elsewhere, and everywhere when not asked for).
    """

    allowed: np.ndarray
    limit: np.ndarray
    leg: np.ndarray
    condition: np.ndarray


def _classify(geometry, poses, with_condition=False) -> _Classification:
    """
    Classify poses (N, 6) under every limit of ``geometry``, chunk by chunk.

    The condition number, by far the dearest check, is computed only for the poses that keep
    the other limits: a pose refused by them is refused whatever its condition number. A
    refused pose is attributed to the limit it breaks by the largest fraction of that limit's
    value.

    :param with_condition: also give the condition number of the allowed poses when the
        geometry sets no singularity margin.
    """
    parts = [_classify_chunk(geometry, poses[start:start + CHUNK_SIZE], with_condition)
             for start in range(0, len(poses), CHUNK_SIZE)] or [_classify_chunk(
                 geometry, np.zeros((0, 6)), False)]
    return _Classification(*(np.concatenate([getattr(part, name) for part in parts])
                             for name in ('allowed', 'limit', 'leg', 'condition')))


def _classify_chunk(geometry, poses, with_condition):
    count = len(poses)
    if count == 0:
        empty = np.zeros(0, dtype=int)
        return _Classification(np.zeros(0, dtype=bool), empty, empty, np.zeros(0))
    checks = check_poses_array(geometry, poses, condition_of_refused=False)
    names = pose_limit_names()
    scores = np.full((count, len(names)), -np.inf)
    legs = np.zeros((count, len(names)), dtype=int)
    for index, name in enumerate(names):
        if name in checks.broken:
            # Relative to the limit's size: a negative limit (a pull, leg_force_min) must
            # not turn the comparison round.
            scale = abs(checks.model.bound(name).allowed) or 1.0
            relative = np.where(checks.broken[name], checks.excess(name) / scale, -np.inf)
            if relative.ndim == 2:
                legs[:, index] = np.argmax(relative, axis=1) + 1
                relative = np.max(relative, axis=1)
            scores[:, index] = np.nan_to_num(relative, nan=np.inf, neginf=-np.inf)
    allowed = checks.allowed
    limit = np.where(allowed, -1, np.argmax(scores, axis=1))
    leg = np.where(allowed, 0, legs[np.arange(count), np.maximum(limit, 0)])
    if checks.condition is not None:
        condition = np.where(allowed, checks.condition, np.nan)
    else:
        condition = np.full(count, np.nan)
        if with_condition and np.any(allowed):
            chosen = poses[allowed]
            condition[allowed] = jacobian_condition(geometry, chosen[:, :3],
                                                    euler_zyx_to_matrix(chosen[:, 3:]))
    return _Classification(allowed, limit, leg, condition)


def _bisect(geometry, inside, outside, tolerance):
    """
    Locate the boundary between pairs of poses, the first reachable, the second not.

    :param inside: reachable poses, shape (M, 6).
    :param outside: refused poses, shape (M, 6), each differing from its pair along one line.
    :param tolerance: (6,) per coordinate: bisection stops when every pair is this close.
    :returns: ``(inside, outside, limit, leg)``: the final pairs (reachable, refused), and
        the limit and leg that refuse each final outside pose.
    """
    inside, outside = inside.copy(), outside.copy()
    gap = np.max(np.abs(outside - inside) / tolerance) if len(inside) else 0.0
    for _ in range(max(0, math.ceil(math.log2(gap))) if gap > 1.0 else 0):
        middle = 0.5 * (inside + outside)
        allowed = _classify(geometry, middle).allowed
        inside[allowed] = middle[allowed]
        outside[~allowed] = middle[~allowed]
    final = _classify(geometry, outside)
    return inside, outside, final.limit, final.leg


# Grids ------------------------------------------------------------------------------------------

class _Grid:
    """
    Poses on a grid along some pose coordinates, the others held, grown to hold the workspace.

    The grid is anchored at the base pose (a grid point). Its extent is found first on a grid
    ``COARSE_FACTOR`` times coarser: while reachable points lie on a face of it and the span
    allows, that face moves out by half the grid's width. The fine grid then covers that
    extent and one coarse step more.
    """

    def __init__(self, geometry, base, axes, resolution, extent, span, with_condition=False):
        self.geometry, self.base, self.axes = geometry, base, tuple(axes)
        self.resolution = np.asarray(resolution, dtype=float)
        self.with_condition = with_condition
        limits = np.array([span[0] if axis < 3 else span[1] for axis in self.axes])
        reach = np.floor(limits / self.resolution).astype(int)
        if extent is None:
            ranges = travel_ranges(geometry, base, span=span).as_array()[list(self.axes)]
            coarse = self.resolution * COARSE_FACTOR
            low = np.floor(1.2 * ranges[:, 0] / coarse).astype(int) - 1
            high = np.ceil(1.2 * ranges[:, 1] / coarse).astype(int) + 1
            coarse_reach = reach // COARSE_FACTOR
            low, high = np.maximum(low, -coarse_reach), np.minimum(high, coarse_reach)
            for _ in range(MAX_GROWTH):
                allowed = self._sample(low, high, coarse, classify_only=True)
                new_low, new_high = low.copy(), high.copy()
                width = high - low
                for dimension in range(len(self.axes)):
                    if np.any(np.take(allowed, 0, axis=dimension)):
                        new_low[dimension] = max(low[dimension] - width[dimension] // 2 - 1,
                                                 -coarse_reach[dimension])
                    if np.any(np.take(allowed, -1, axis=dimension)):
                        new_high[dimension] = min(high[dimension] + width[dimension] // 2 + 1,
                                                  coarse_reach[dimension])
                if np.array_equal(new_low, low) and np.array_equal(new_high, high):
                    break
                low, high = new_low, new_high
            # Shrink to the reachable coarse points, with two coarse steps of margin (the
            # coarse grid may miss a thin part of the workspace).
            reachable = np.nonzero(allowed)
            if reachable[0].size:
                high = low + np.array([indices.max() for indices in reachable]) + 2
                low = low + np.array([indices.min() for indices in reachable]) - 2
            low, high = low * COARSE_FACTOR, high * COARSE_FACTOR
        else:
            extent = np.asarray(extent, dtype=float) - base[list(self.axes)][:, None]
            low = np.floor(extent[:, 0] / self.resolution).astype(int)
            high = np.ceil(extent[:, 1] / self.resolution).astype(int)
        low, high = np.maximum(low, -reach), np.minimum(high, reach)
        for _ in range(MAX_GROWTH):
            self._sample(low, high, self.resolution)
            if extent is not None:
                break
            # Reachable points on a face the coarse grid missed: move that face out.
            new_low, new_high = low.copy(), high.copy()
            for dimension in range(len(self.axes)):
                if np.any(np.take(self.allowed, 0, axis=dimension)):
                    new_low[dimension] = max(low[dimension] - 2 * COARSE_FACTOR,
                                             -reach[dimension])
                if np.any(np.take(self.allowed, -1, axis=dimension)):
                    new_high[dimension] = min(high[dimension] + 2 * COARSE_FACTOR,
                                              reach[dimension])
            if np.array_equal(new_low, low) and np.array_equal(new_high, high):
                break
            low, high = new_low, new_high
        self.bounded = not any(
            np.any(np.take(self.allowed, end, axis=dimension))
            for dimension in range(len(self.axes)) for end in (0, -1))

    def _sample(self, low, high, resolution, classify_only=False):
        coordinates = [self.base[axis] + step * np.arange(start, stop + 1)
                       for axis, step, start, stop in zip(self.axes, resolution, low, high)]
        shape = tuple(len(values) for values in coordinates)
        classified = _classify(self.geometry, self._poses_of(coordinates),
                               self.with_condition and not classify_only)
        if classify_only:
            return classified.allowed.reshape(shape)
        self.coordinates = coordinates
        self.allowed = classified.allowed.reshape(shape)
        self.limit = classified.limit.reshape(shape)
        self.leg = classified.leg.reshape(shape)
        self.condition = classified.condition.reshape(shape)
        return self.allowed

    def _poses_of(self, coordinates):
        mesh = np.meshgrid(*coordinates, indexing='ij')
        poses = np.repeat(self.base[None, :], mesh[0].size, axis=0)
        for axis, axis_values in zip(self.axes, mesh):
            poses[:, axis] = axis_values.ravel()
        return poses

    def poses(self, indices):
        """Poses (M, 6) of the grid points at the given index arrays, one per dimension."""
        values = [self.coordinates[d][indices[d]] for d in range(len(self.axes))]
        poses = np.repeat(self.base[None, :], len(values[0]), axis=0)
        for axis, axis_values in zip(self.axes, values):
            poses[:, axis] = axis_values
        return poses

    def boundary(self, tolerance, dimensions=None):
        """
        Boundary points: every crossing between grid neighbours along grid axes.

        :param dimensions: the grid dimensions to look along; default all.
        :returns: ``(poses (M, 6), limit (M,), leg (M,))``, the reachable side of each
            crossing located to ``tolerance``; sets ``crossing_entering`` (True where the
            line enters the workspace as the coordinate grows).
        """
        inside, outside, entering = [], [], []
        for dimension in range(len(self.axes)) if dimensions is None else dimensions:
            count = self.allowed.shape[dimension]
            lower = np.take(self.allowed, np.arange(count - 1), axis=dimension)
            upper = np.take(self.allowed, np.arange(1, count), axis=dimension)
            for enters in (False, True):
                found = np.nonzero((lower & ~upper) if not enters else (~lower & upper))
                low_index = list(found)
                high_index = list(found)
                high_index[dimension] = found[dimension] + 1
                inside_index, outside_index = ((high_index, low_index) if enters
                                               else (low_index, high_index))
                inside.append(self.poses(inside_index))
                outside.append(self.poses(outside_index))
                entering.append(np.full(len(found[0]), enters))
        inside, outside = np.concatenate(inside), np.concatenate(outside)
        self.crossing_entering = np.concatenate(entering)
        tolerances = np.repeat(np.asarray(tolerance, dtype=float), 3)
        points, _, limit, leg = _bisect(self.geometry, inside, outside, tolerances)
        return points, limit, leg


# Arguments ---------------------------------------------------------------------------------------

def _start_pose(geometry, pose):
    """Return the start pose as a float array (6,), checked reachable."""
    start = _base_pose(geometry, pose)
    classified = _classify(geometry, start[None, :])
    if not classified.allowed[0]:
        checks = check_poses_array(geometry, start)
        raise ValueError('the start pose breaks the limits: '
                         + '; '.join(str(v) for v in checks.violations(0)))
    return start


def _finite(name, value, size) -> np.ndarray:
    """Return ``size`` finite numbers, or refuse them naming the argument."""
    array = as_float_array(value, name)
    if array.shape != (size,) or not np.all(np.isfinite(array)):
        raise ValueError(f'{name} must be {size} finite numbers, got {preview(value)}')
    return array


def _positive(name, value, size) -> np.ndarray:
    """Return one positive finite number, or ``size`` of them, as an array (size,)."""
    array = as_float_array(value, name)
    if array.shape not in ((), (size,)) or not np.all((array > 0.0) & np.isfinite(array)):
        raise ValueError(f'{name} must be one positive finite number or {size}, got '
                         f'{preview(value)}')
    return np.broadcast_to(array, (size,)).copy()


def _pair(name, value) -> Tuple[float, float]:
    """Return a ``(metres, radians)`` pair of positive finite numbers, or refuse it."""
    return tuple(_positive(name, value, 2).tolist())


def _base_pose(geometry, pose):
    if pose is None:
        return np.array(geometry.home_pose, dtype=float)
    pose = as_poses(pose, 'pose')
    if pose.shape != (6,):
        raise ValueError(f'pose must have shape (6,), got {pose.shape}')
    return pose.copy()


def _plane_names(plane) -> Sequence[str]:
    if isinstance(plane, str):
        names = [plane[0], plane[1]] if plane in ('XY', 'XZ', 'YZ') else plane.split('-')
    else:
        names = list(plane)
    if len(names) != 2 or names[0] == names[1] or any(name not in AXES for name in names):
        raise ValueError(f"plane must name two different coordinates of {AXES}, such as 'XY' "
                         f"or ('alpha', 'beta'), got {plane!r}")
    return names
