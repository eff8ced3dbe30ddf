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
The forward solver's start table: working-mode poses sampled once per geometry.

A solve without an initial guess (a cold solve) from the home pose takes about four Newton
steps, as the home pose is up to a few centimetres and degrees from the solution. The table
starts it closer. Its index is the pose that the first Newton step from home reaches,
``first = home + J_home^-1 (lengths - l(home))``, which costs one product with the home
Jacobian's inverse (computed once per geometry) and lies within a few centimetres of the
solution: a regular grid of :data:`CELLS_PER_AXIS` cells per coordinate around home, over
``+-REACH`` platform radii and ``+-TURN`` in each Euler angle, is then an index in which the
cell of ``first`` holds a sample near the solution.

Each cell holds one sample: the exact pose whose leg lengths ``l_c`` send the first step from
home to the cell's centre, found by Newton-Raphson at build time, with the inverse of its twist
Jacobian. A cold solve starts one Newton step from the sample, ``x0 = x_c - J_c^-1 (l_c -
lengths)`` (no leg evaluation: the sample's lengths are known), and its first step reuses the
sample's Jacobian, as a tracking solve reuses its last one.

Only the working mode: a cell is kept when its sample is reached from the home cell through
neighbouring samples that each predicts (to first order) within :data:`CONTINUITY` cells, the
sign of its Jacobian's determinant is that of home's (a singularity lies between poses of
opposite signs) and its Jacobian's condition number is at most :data:`MAX_CONDITION`. A first
step outside the grid, or in a cell not kept, starts the solve from home as before.

The table is built on the first cold solve of each geometry (about 0.1 to 0.3 s, 6.5 MB, see
:attr:`StartTable.build_seconds` and :attr:`StartTable.nbytes`) and belongs to that geometry's
constants (a geometry is immutable, and another geometry has another table).
"""

import math
import time

import numpy as np

from stewart_kinematics.model.formulas import apply_matrix, constants_of, euler_step
from stewart_kinematics.model.forward_solver import (
    DEFAULT_MAX_ITERATIONS,
    DEFAULT_TOLERANCE,
    solve_batch,
)
from stewart_kinematics.model.inputs import valid_lengths
from stewart_kinematics.model.inverse import inverse_kinematics
from stewart_kinematics.model.jacobians import jacobian, jacobian_condition, twist_jacobian
from stewart_kinematics.model.rotations import euler_zyx_to_matrix

#: Cells of the grid per pose coordinate (5 ** 6 = 15,625 cells; 416 bytes each), odd so that
#: home is the centre of one. More cells start closer, but the step count hardly follows: on
#: the paper's platform, 7 per axis (49 MB) save 0.1 of the 3.2 steps of a cold solve, as the
#: last steps converge quadratically.
CELLS_PER_AXIS = 5
#: Half-width of the grid in each position coordinate, in platform radii (the RMS distance of
#: the platform joints from their centroid): 0.15 m on the paper's platform, whose Table 3
#: ramp ends 0.1 m, 0.15 m and 0.1 m from home.
REACH = 1.0
#: Half-width of the grid in each Euler angle, radians.
TURN = math.radians(20.0)
#: Largest condition number of a sample's dimensionless Jacobian (see
#: :func:`stewart_kinematics.model.jacobians.jacobian_condition`; about 10 at the paper
#: platform's home): a sample nearer a singularity is no good start and is left out.
MAX_CONDITION = 1e3
#: Two neighbouring samples belong to one assembly mode when the first-order prediction of
#: each from the other is within this many cells, in every coordinate.
CONTINUITY = 0.25


class StartTable:
    """
    Working-mode samples of one geometry on a grid around home, indexed by the first step.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :param cells: cells per coordinate (default :data:`CELLS_PER_AXIS`).
    :param reach: half-width in position, platform radii (default :data:`REACH`).
    :param turn: half-width in each Euler angle, radians (default :data:`TURN`).

    The forward solver builds one per geometry, with the defaults, on the first cold solve;
    build one directly to inspect it or to study another size.
    """

    def __init__(self, geometry, cells=CELLS_PER_AXIS, reach=REACH, turn=TURN):
        start = time.process_time()
        self.cells = cells
        home = np.asarray(geometry.home_pose, dtype=float)
        half_width = np.array([reach * geometry.platform_radius] * 3 + [turn] * 3)
        home_jacobian = jacobian(geometry, home)
        home_lengths = inverse_kinematics(geometry, home)
        # The index: cell coordinates (the first step's coordinates in cells from the grid's
        # lower corner) as offset + rows @ lengths, with the first step home + J^-1 (l - l_home).
        scale = cells / (2.0 * half_width)
        rows = scale[:, None] * np.linalg.inv(home_jacobian)
        #: The rows and offset of the index (see :meth:`cell`).
        self.index_rows = rows.tolist()
        self.index_offset = (scale * half_width - rows @ home_lengths).tolist()
        width = 2.0 * half_width / cells
        axes = [home[k] - half_width[k] + width[k] * (np.arange(cells) + 0.5) for k in range(6)]
        centres = np.stack(np.meshgrid(*axes, indexing='ij'), axis=-1).reshape(-1, 6)
        lengths = home_lengths + (centres - home) @ home_jacobian.T
        samples, kept = _solve_samples(geometry, centres, lengths)
        kept &= _working_mode(geometry, home, samples, kept, home_jacobian, width, cells)
        #: Per cell: sample pose (6), its leg lengths (6) and cos, sin of its beta and gamma
        #: (4): all a start needs but the inverse twist Jacobian, which :attr:`inverses` holds.
        self.entries = np.zeros((cells ** 6, 16))
        self.inverses = np.zeros((cells ** 6, 6, 6))
        beta, gamma = samples[kept, 4], samples[kept, 5]
        self.entries[kept] = np.column_stack([samples[kept], lengths[kept], np.cos(beta),
                                              np.sin(beta), np.cos(gamma), np.sin(gamma)])
        self.inverses[kept] = np.linalg.inv(twist_jacobian(
            geometry, samples[kept, :3], euler_zyx_to_matrix(samples[kept, 3:])))
        #: Whether each cell holds a sample, as bytes (indexed faster than a numpy array).
        self.kept = bytes(kept.astype(np.uint8))
        #: Fraction of the grid's cells that hold a sample.
        self.coverage = float(np.mean(kept))
        #: Processor time the build took, seconds.
        self.build_seconds = time.process_time() - start

    @property
    def nbytes(self) -> int:
        """Memory of the table's arrays, bytes."""
        return self.entries.nbytes + self.inverses.nbytes + len(self.kept)

    def cell(self, lengths):
        """
        Index of the cell of six leg lengths (floats, metres), or -1 where it holds no sample.

        The hot path of a cold solve: float arithmetic, no numpy call.
        """
        cells = self.cells
        coordinates = _cell_coordinates(self.index_rows, self.index_offset, lengths)
        if not (0.0 <= min(coordinates) and max(coordinates) < cells):
            return -1
        index = 0
        try:
            for coordinate in coordinates:
                index = index * cells + int(coordinate)
        except ValueError:  # a NaN (absurd lengths: inf - inf) that min and max let through
            return -1
        return index if self.kept[index] else -1

    def cells_of(self, lengths):
        """:meth:`cell` of each row of ``lengths`` (n, 6), with the same arithmetic: (n,)."""
        with np.errstate(over='ignore', invalid='ignore'):  # absurd lengths: not inside
            coordinates = np.stack(_cell_coordinates(self.index_rows, self.index_offset,
                                                     list(lengths.T)), axis=-1)
        inside = np.all((coordinates >= 0.0) & (coordinates < self.cells), axis=-1)
        index = np.zeros(len(lengths), dtype=np.int64)
        for column in np.where(inside[:, None], coordinates, 0.0).T:
            index = index * self.cells + column.astype(np.int64)
        kept = np.frombuffer(self.kept, dtype=np.uint8)[index].astype(bool)
        return np.where(inside & kept, index, -1)


def cold_start(table, target):
    """
    Start of a solve without a guess, from the start table: ``(pose, jacobian_inverse)``.

    One Newton step from the sample of the lengths' cell, with the sample's Jacobian (see
    above); None, to start from home instead, where the table has no sample for the lengths.

    :param table: the geometry's :class:`StartTable`, or None (its home is singular).
    :param target: the six leg lengths, metres, as floats.
    :returns: six floats and the sample's inverse twist Jacobian (nested lists), or None.
    """
    cell = -1 if table is None else table.cell(target)
    if cell < 0:
        return None
    sample = table.entries[cell].tolist()
    inverse = table.inverses[cell].tolist()
    errors = [length - wanted for length, wanted in zip(sample[6:12], target)]
    return euler_step(sample[:6], apply_matrix(inverse, errors), *sample[12:]), inverse


def batch_cold_starts(table, home_pose, targets):
    """
    :func:`cold_start` of each row of ``targets`` (N, 6), with the same arithmetic.

    :param table: as for :func:`cold_start`; ``home_pose``: six floats.
    :returns: ``(started (N,), poses (N, 6), inverses (N, 6, 6))``: the rows started from the
        table, and every row's start (home for the others) and inverse twist Jacobian.
    """
    count = len(targets)
    poses = np.array(np.broadcast_to(home_pose, (count, 6)))
    inverses = np.zeros((count, 6, 6))
    started = np.zeros(count, dtype=bool)
    rows = np.flatnonzero(valid_lengths(targets))
    if table is None or rows.size == 0:
        return started, poses, inverses
    cells = table.cells_of(targets[rows])
    rows, cells = rows[cells >= 0], cells[cells >= 0]
    sample = table.entries[cells]
    inverses[rows] = table.inverses[cells]
    errors = sample[:, 6:12] - targets[rows]
    # apply_matrix with the six rows of every sample as one row: see solve_batch.
    twists = apply_matrix([np.ascontiguousarray(inverses[rows].transpose(2, 1, 0))],
                          list(errors.T))[0]
    poses[rows] = np.stack(euler_step(sample[:, :6].T, twists, *sample[:, 12:].T), axis=-1)
    started[rows] = True
    return started, poses, inverses


def _cell_coordinates(rows, offset, lengths):
    """
    ``offset + rows @ lengths``, summed in index order: six floats, or six arrays for a batch.

    :param lengths: six floats, or six arrays (n,).
    """
    l0, l1, l2, l3, l4, l5 = lengths
    return [o + m0 * l0 + m1 * l1 + m2 * l2 + m3 * l3 + m4 * l4 + m5 * l5
            for o, (m0, m1, m2, m3, m4, m5) in zip(offset, rows)]


def _solve_samples(geometry, centres, lengths):
    """
    Solve the cells' leg lengths for their poses, by Newton-Raphson from the cells' centres.

    :returns: ``(poses (n, 6), solved (n,))``: solved where the solve converged to a pose whose
        Jacobian's condition number is at most :data:`MAX_CONDITION`.
    """
    valid = np.all(lengths > 0.0, axis=-1)
    solved = np.zeros(len(centres), dtype=bool)
    poses = centres.copy()
    result = solve_batch(geometry, constants_of(geometry), lengths[valid], centres[valid],
                         DEFAULT_TOLERANCE, DEFAULT_MAX_ITERATIONS)
    poses[valid] = result.pose
    solved[valid] = result.converged
    condition = np.full(len(centres), np.inf)
    condition[solved] = jacobian_condition(
        geometry, poses[solved, :3], euler_zyx_to_matrix(poses[solved, 3:]))
    return poses, solved & (condition <= MAX_CONDITION)


def _working_mode(geometry, home, samples, solved, home_jacobian, width, cells):
    """
    Which samples belong to home's assembly mode: connected to the home cell, same orientation.

    Two neighbouring cells (one step along one coordinate) connect when each sample predicts
    the other to first order within :data:`CONTINUITY` cells; a cell belongs when a chain of
    connections leads to it from the cell of home and its Jacobian's determinant has the sign
    of home's.

    :param home_jacobian: the Jacobian at home, whose columns times ``width`` are the changes
        of the leg lengths from one cell to the next along each coordinate.
    :param width: the cells' widths, metres and radians, shape (6,).
    :param cells: cells per coordinate.
    """
    def determinants(poses):
        return np.linalg.det(twist_jacobian(
            geometry, poses[:, :3], euler_zyx_to_matrix(poses[:, 3:])))

    ok = solved.copy()
    ok[solved] = np.sign(determinants(samples[solved])) == np.sign(determinants(home[None]))
    # Each sample's Euler Jacobian inverse: the first-order prediction of its neighbours.
    inverses = np.zeros((len(samples), 6, 6))
    inverses[ok] = np.linalg.inv(jacobian(geometry, samples[ok]))
    grid = (cells,) * 6
    ok = ok.reshape(grid)
    samples = samples.reshape(grid + (6,))
    inverses = inverses.reshape(grid + (6, 6))
    tolerance = CONTINUITY * width
    links = []
    for axis in range(6):
        lower = tuple(slice(0, -1) if k == axis else slice(None) for k in range(6))
        upper = tuple(slice(1, None) if k == axis else slice(None) for k in range(6))
        step = home_jacobian[:, axis] * width[axis]
        forward = samples[lower] + inverses[lower] @ step
        backward = samples[upper] - inverses[upper] @ step
        close = (np.all(np.abs(forward - samples[upper]) <= tolerance, axis=-1)
                 & np.all(np.abs(backward - samples[lower]) <= tolerance, axis=-1))
        links.append((lower, upper, close & ok[lower] & ok[upper]))
    reached = np.zeros(grid, dtype=bool)
    home_cell = (cells // 2,) * 6  # the grid is centred on home
    reached[home_cell] = ok[home_cell]
    while True:
        before = np.count_nonzero(reached)
        for lower, upper, link in links:
            reached[upper] |= reached[lower] & link
            reached[lower] |= reached[upper] & link
        if np.count_nonzero(reached) == before:
            return reached.reshape(-1)
