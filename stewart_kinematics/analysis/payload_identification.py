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
Payload identification: the payload's mass and centre of mass from leg forces measured at rest.

At a static pose the legs hold the platform, the legs' own weight and the payload. The
measured forces minus the forces the model needs without a payload (the platform's and the
legs' known masses, :func:`~stewart_kinematics.leg_forces`) are the payload's share; the legs
exert through them (:func:`~stewart_kinematics.platform_wrench`, ``J^T f``) the wrench

    ``[F, M] = [-m g, (R c) x (-m g)] = [-g m, [g]x R (m c)]``

(base frame, about the platform frame's origin, ``c`` in the platform frame): linear in ``m``
and ``m c``. So is the payload's share of the forces, ``J^-T [F, M]``. What the poses can tell
apart follows from the moment: ``[g]x R`` has rank 2 and misses ``R^T g``, the direction of
gravity in the platform frame. A level platform (any yaw) sees the horizontal components of
the centre, through the moment, but not its height; the height is seen only through poses
whose tilts differ. Poses all at one orientation relative to gravity leave the centre's
component along ``R^T g`` undetermined; the mass is always determined (by ``F``).

:func:`identify_payload` fits ``(m, m c)`` by linear least squares in the forces (the noise is
on the measured forces, independent and alike from leg to leg: the least-squares estimate in
the forces is the maximum-likelihood one, and its covariance is the fit's). A combination the
poses do not determine (a singular value of the scaled design below the largest over
``max_condition``) is kept from the prior payload (the parameter file's) and named in a
:data:`~stewart_kinematics.findings.PAYLOAD_UNOBSERVABLE` warning. Nothing here imports ROS.
"""

from dataclasses import dataclass, replace
import math
from typing import Tuple

import numpy as np

from stewart_kinematics.analysis.calibration_files import load_columns, MEASUREMENT_COLUMNS
from stewart_kinematics.dynamics.inverse_dynamics import leg_forces, masses_of
from stewart_kinematics.dynamics.mass_properties import RigidBody
from stewart_kinematics.findings import Finding, PAYLOAD_UNOBSERVABLE
from stewart_kinematics.limits.geometry_checks import check_poses_array
from stewart_kinematics.model.arrays import preview
from stewart_kinematics.model.forward import forward_kinematics
from stewart_kinematics.model.inputs import as_poses
from stewart_kinematics.parameters.rcl_yaml import read_yaml_file

#: The unknowns: the mass and the first moment of the mass (``m c``, kg m), platform frame.
UNKNOWNS = ('mass', 'm*x', 'm*y', 'm*z')
#: Fewest poses accepted: as many as unknowns (each pose gives six equations, and the noise is
#: estimated from the 6 N - 4 degrees of freedom left).
MIN_POSES = len(UNKNOWNS)
#: Default largest scaled condition number of the fit: a combination whose scaled singular
#: value is below the largest over this is not determined (the noise is amplified as much).
DEFAULT_MAX_CONDITION = 100.0
#: The mass must exceed this many standard deviations to place a centre of mass.
MASS_SIGNIFICANCE = 3.0
#: The columns of a measurement file: the pose (as the calibration's), or the leg lengths
#: (metres, between the joints' centres: the pose is solved from them), then the forces (N).
POSE_COLUMNS = MEASUREMENT_COLUMNS[:6]
LENGTH_COLUMNS = tuple(f'leg_length_{leg}' for leg in range(1, 7))
FORCE_COLUMNS = tuple(f'force_{leg}' for leg in range(1, 7))
#: The axis names of the platform frame, for the messages.
_AXES = ('x', 'y', 'z')


class PayloadIdentificationError(ValueError):
    """The measurements cannot identify a payload: the reason, with the values concerned."""


@dataclass(frozen=True)
class PayloadEstimate:
    """
    The payload identified from measured forces, and how well.

    :param mass: kg.
    :param mass_deviation: its standard deviation, kg.
    :param center_of_mass: ``[x, y, z]``, platform frame, metres.
    :param center_deviation: their standard deviations, metres; ``inf`` for a component the
        poses do not determine (kept from the prior payload).
    :param noise: the force residuals' standard deviation (degrees of freedom counted),
        newtons: the measurement noise as the fit sees it.
    :param residuals: measured minus fitted forces, newtons, shape (N, 6).
    :param condition_number: scaled condition number of the fit's design (``inf`` when a
        combination is not determined at all).
    :param undetermined: the combinations of ``(m, m x, m y, m z)`` the poses do not determine,
        each a unit vector in the scaled unknowns, shape (k, 4).
    :param warnings: :class:`~stewart_kinematics.findings.Finding` (``payload_unobservable``).
    """

    mass: float
    mass_deviation: float
    center_of_mass: np.ndarray
    center_deviation: np.ndarray
    noise: float
    residuals: np.ndarray
    condition_number: float
    undetermined: np.ndarray
    warnings: Tuple[Finding, ...]

    def parameters(self) -> dict:
        """Return the parameters ``payload_mass`` (kg) and ``payload_center_of_mass`` (m)."""
        return {'payload_mass': float(self.mass),
                'payload_center_of_mass': [float(value) for value in self.center_of_mass]}

    def report(self) -> str:
        """Return the identification as text: the estimates with their standard deviations."""
        count = self.residuals.shape[0]
        rms = np.sqrt(np.mean(np.square(self.residuals), axis=0))
        lines = [f'poses: {count}; force residual RMS per leg (N): '
                 + ' '.join(f'{value:.3f}' for value in rms),
                 f'noise estimate: {self.noise:.3f} N; scaled condition number: '
                 f'{self.condition_number:.3g}',
                 '',
                 'payload (platform frame)       estimate   standard deviation',
                 f'  mass (kg)               {self.mass:12.4f} {self.mass_deviation:12.4f}']
        for axis, value, deviation in zip(_AXES, self.center_of_mass, self.center_deviation):
            spread = ('  not determined (kept)' if not np.isfinite(deviation)
                      else f'{deviation * 1e3:12.3f}')
            lines.append(f'  centre {axis} (mm)           {value * 1e3:12.3f} {spread}')
        lines += ['', 'warnings: ' + ('none' if not self.warnings else '')]
        lines += [f'  {finding.code}: {finding.message}' for finding in self.warnings]
        return '\n'.join(lines)


def identify_payload(geometry, poses, forces, *, prior: RigidBody = None,
                     max_condition: float = DEFAULT_MAX_CONDITION) -> PayloadEstimate:
    """
    Identify the payload's mass and centre of mass from leg forces measured at rest.

    The platform's and the legs' masses and gravity are the geometry's
    (:attr:`~stewart_kinematics.Geometry.mass_properties`); their forces are subtracted, and
    what is left is fitted as a point mass fixed to the platform (its inertia plays no part at
    rest).

    :param geometry: a :class:`stewart_kinematics.Geometry` with its mass properties.
    :param poses: the measured static poses ``[X, Y, Z, alpha, beta, gamma]`` (metres,
        radians), shape (N, 6), N >= :data:`MIN_POSES`.
    :param forces: the six leg forces measured at each pose, newtons, positive pushing,
        shape (N, 6).
    :param prior: the payload assumed before (the parameter file's): a combination of the
        centre the poses do not determine keeps its value; ``None``: the geometry's payload.
    :param max_condition: largest scaled condition number accepted (> 1): directions of the
        unknowns whose scaled singular value is below the largest over this are not fitted.
    :returns: a :class:`PayloadEstimate`.
    :raises PayloadIdentificationError: (a ValueError) for too few poses, or a mass that the
        measurements do not tell from 0 (no centre of mass to place).
    :raises ValueError: for poses or forces of the wrong shape, not finite or too large, or a
        singular pose (naming it).

    >>> import numpy as np
    >>> from stewart_kinematics import MassProperties, RigidBody, leg_forces, load_geometry
    >>> geometry = load_geometry('config/paper_platform.yaml')
    >>> true = MassProperties(payload=RigidBody(20.0, [0.01, -0.02, 0.05], name='payload'))
    >>> poses = np.array([[0.0, 0.0, 0.4325, a, b, 0.0] for a in (-0.1, 0.0, 0.1)
    ...                   for b in (-0.1, 0.0, 0.1)])
    >>> estimate = identify_payload(geometry, poses,
    ...                             leg_forces(geometry, poses, mass_properties=true))
    >>> round(estimate.mass, 9), (estimate.center_of_mass * 1e3).round(6) + 0.0
    (20.0, array([ 10., -20.,  50.]))
    """
    if not (isinstance(max_condition, (int, float)) and 1.0 < max_condition < np.inf):
        raise ValueError(f'max_condition must be a number above 1, got {preview(max_condition)}')
    poses = np.atleast_2d(as_poses(poses))
    forces = np.atleast_2d(as_poses(forces, 'forces'))
    if poses.ndim != 2 or forces.shape != poses.shape:
        raise ValueError(f'poses {poses.shape} and forces {forces.shape} must both have shape '
                         '(N, 6), one row of forces per pose')
    count = poses.shape[0]
    if count < MIN_POSES:
        raise PayloadIdentificationError(
            f'{count} pose(s): at least {MIN_POSES} are needed to identify the {MIN_POSES} '
            'unknowns (mass and centre of mass) and the noise')
    masses = masses_of(geometry)
    if prior is None:
        prior = masses.payload
    known = leg_forces(geometry, poses, mass_properties=replace(
        masses, payload=RigidBody(name='payload')))
    design = _design(geometry, poses, masses)
    with np.errstate(all='ignore'):   # forces beyond the float range are refused below
        measured = (forces - known).ravel()
        estimate = _fit(design, measured, _scales(geometry), prior, max_condition)
    theta, covariance, undetermined, condition, residuals, noise = estimate
    if not all(np.all(np.isfinite(value)) for value in (theta, covariance, residuals, noise)):
        raise ValueError(f'forces of up to {np.max(np.abs(forces)):.3g} N: the fit is not '
                         'finite (beyond the float range); the forces are too large')
    mass, moment = theta[0], theta[1:]
    mass_deviation = float(np.sqrt(max(covariance[0, 0], 0.0)))
    if not mass > MASS_SIGNIFICANCE * mass_deviation or mass <= 0.0:
        raise PayloadIdentificationError(
            f'the payload mass {mass:.4g} +- {mass_deviation:.3g} kg is not more than '
            f'{MASS_SIGNIFICANCE:g} standard deviations above 0: no centre of mass can be placed '
            '(is a payload mounted? are the known masses and the force signs right?)')
    center = moment / mass
    gradient = np.hstack([-center[:, None] / mass, np.eye(3) / mass])   # d c / d(m, m c)
    deviation = np.sqrt(np.maximum(np.diag(gradient @ covariance @ gradient.T), 0.0))
    unknown = np.any(np.abs(undetermined[:, 1:]) > 1e-6, axis=0) if undetermined.size else (
        np.zeros(3, bool))
    deviation = np.where(unknown, np.inf, deviation)
    warnings = tuple(_unobservable(vector, condition, max_condition, prior)
                     for vector in undetermined)
    return PayloadEstimate(float(mass), mass_deviation, center, deviation, noise,
                           residuals.reshape(count, 6), condition, undetermined, warnings)


def _design(geometry, poses, masses) -> np.ndarray:
    """
    Return the payload's share of the forces per unknown: shape (6 N, 4), N/kg and N/(kg m).

    The forces of a unit mass at the origin (column ``m``) and the extra forces of moving it
    by one metre along each axis (columns ``m x``, ``m y``, ``m z``), by the package's own
    :func:`~stewart_kinematics.leg_forces`: exact, as the wrench is linear in ``(m, m c)``.
    """
    bare = replace(masses, platform=RigidBody(name='platform'),
                   leg_lower=type(masses.leg_lower)(name='leg_lower'),
                   leg_upper=type(masses.leg_upper)(name='leg_upper'))
    columns = []
    for center in np.vstack([np.zeros(3), np.eye(3)]):
        unit = replace(bare, payload=RigidBody(1.0, center, name='payload'))
        columns.append(leg_forces(geometry, poses, mass_properties=unit).ravel())
    columns[1:] = [column - columns[0] for column in columns[1:]]
    return np.stack(columns, axis=1)


def _scales(geometry) -> np.ndarray:
    """Scales of the unknowns: 1 kg, and 1 kg times the platform's radius for ``m c``."""
    radius = float(np.max(np.linalg.norm(geometry.platform_joints, axis=1)))
    return np.array([1.0, radius, radius, radius])


def _fit(design, measured, scales, prior, max_condition):
    """Least squares of ``design theta = measured``; see :func:`identify_payload`."""
    scaled = design * scales
    # The forces are linear in (m, m c): one linear least squares gives the exact minimiser,
    # with no iteration and no starting guess (unlike the calibration's nonlinear fit).
    # lstsq's rcond drops the directions whose singular values are below the largest over
    # max_condition (the poses do not determine them) and gives the minimum-norm solution,
    # 0 along them; they are set from the prior below.
    solution, _, rank, singular = np.linalg.lstsq(scaled, measured, rcond=1.0 / max_condition)
    _, _, right = np.linalg.svd(scaled, full_matrices=False)
    kept, dropped = right[:rank], right[rank:]
    theta = solution * scales
    if dropped.size:
        target = np.concatenate([[theta[0]], theta[0] * np.asarray(prior.center_of_mass)])
        theta = theta + (dropped.T @ (dropped @ (target / scales))) * scales
    residuals = measured - design @ theta
    freedom = measured.size - rank
    noise = float(np.sqrt(residuals @ residuals / freedom))
    inverse = (kept.T / singular[:rank] ** 2) @ kept   # (S^T S)^-1 in the kept directions
    covariance = noise ** 2 * inverse * np.outer(scales, scales)
    condition = float(singular[0] / singular[-1]) if singular[-1] > 0.0 else np.inf
    return theta, covariance, dropped, condition, residuals, noise


def _unobservable(vector, condition, max_condition, prior) -> Finding:
    """Return the warning of one combination the poses do not determine."""
    moment = vector[1:]
    axis = int(np.argmax(np.abs(moment)))
    if abs(moment[axis]) > 0.99:
        what = f"the centre of mass's {_AXES[axis]} (platform frame)"
    else:
        what = "the centre of mass's component along [" + ', '.join(
            f'{value:.3f}' for value in moment * np.sign(moment[axis])) + '] (platform frame)'
    kept = float(np.dot(prior.center_of_mass, moment)) / float(np.linalg.norm(moment))
    return Finding(
        PAYLOAD_UNOBSERVABLE,
        f'the poses cannot determine {what}: scaled condition number {condition:.3g} above '
        f'{max_condition:g}; it is kept from the prior payload ({kept * 1e3:.1f} mm). Poses at '
        'one tilt (all level, say) see the centre only across gravity: measure poses tilted '
        'in different directions',
        (('combination', ', '.join(f'{name} {value:+.3f}'
                                   for name, value in zip(UNKNOWNS, vector))),
         ('condition_number', f'{condition:.3g}')))


def load_force_measurements(path, geometry) -> Tuple[np.ndarray, np.ndarray]:
    """
    Read leg forces measured at rest, and the poses they were measured at, from a file.

    A CSV file is the calibration's measurement file, with forces instead of actuator
    positions (:func:`~stewart_kinematics.analysis.calibration_files.load_columns` reads it): a
    header naming :data:`POSE_COLUMNS` (``X, Y, Z`` in metres, ``alpha, beta, gamma`` in
    radians) or :data:`LENGTH_COLUMNS` (``leg_length_1`` .. ``leg_length_6``, metres, whose
    pose forward kinematics solves from the geometry's start table), and :data:`FORCE_COLUMNS`
    (``force_1`` .. ``force_6``, newtons, positive pushing), then one row per pose. A YAML file
    (``.yaml``, ``.yml``; read by the package's one YAML reader, with its limits) holds
    ``measurements:``, a list of mappings with ``pose`` (or ``leg_lengths``) and ``forces``,
    six numbers each, in the same units.

    :param path: the CSV or YAML file.
    :param geometry: the platform, to solve poses from leg lengths.
    :returns: ``(poses, forces)``, each shape (N, 6).
    :raises ValueError: naming the file and its line (CSV) or the measurement (YAML), and the
        column, for a missing column, a row with the wrong number of fields, a value that is
        not a finite number, or leg lengths that no pose has.
    """
    if str(path).lower().endswith(('.yaml', '.yml')):
        layout, values = _load_yaml_measurements(path)
        row = 'measurement'
    else:
        layout, values = load_columns(path, POSE_COLUMNS + FORCE_COLUMNS,
                                      LENGTH_COLUMNS + FORCE_COLUMNS)
        row = 'data row'
    forces = values[:, 6:]
    if layout == 0:
        return values[:, :6], forces
    lengths = values[:, :6]
    bad = np.flatnonzero(~np.all(lengths > 0.0, axis=1))
    if bad.size:
        raise ValueError(f'{path}: {row} {bad[0] + 1}: leg lengths must be positive, got '
                         f'{preview(lengths[bad[0]].tolist())}')
    solved = forward_kinematics(geometry, lengths)
    failed = np.flatnonzero(~np.asarray(solved.converged))
    if failed.size:
        raise ValueError(f'{path}: {row} {failed[0] + 1}: no pose has the leg lengths '
                         f'{preview(lengths[failed[0]].tolist())} '
                         f'({np.atleast_1d(solved.reason)[failed[0]]})')
    return np.atleast_2d(solved.pose), forces


#: The keys of a YAML measurement: the pose or the leg lengths, then the forces.
_YAML_LAYOUTS = (('pose', 'forces'), ('leg_lengths', 'forces'))


def _load_yaml_measurements(path) -> Tuple[int, np.ndarray]:
    """Return ``(layout, values)`` of a YAML measurement file, as :func:`load_columns` does."""
    shape = ("a YAML measurement file holds 'measurements:', a list of mappings, each with "
             "'pose' (or 'leg_lengths') and 'forces', six numbers each")
    document = read_yaml_file(path).value
    items = document.get('measurements') if isinstance(document, dict) else None
    if not isinstance(items, list) or not items:
        raise ValueError(f'{path}: {shape}; got {preview(document)}')
    layout, rows = None, []
    for number, item in enumerate(items, start=1):
        where = f'{path}: measurement {number}'
        keys = tuple(sorted(item)) if isinstance(item, dict) else None
        found = next((index for index, names in enumerate(_YAML_LAYOUTS)
                      if keys == tuple(sorted(names))), None)
        if found is None:
            raise ValueError(f'{where}: {shape}; got {preview(item)}')
        if layout is not None and found != layout:
            raise ValueError(f'{where}: {_YAML_LAYOUTS[found][0]}, but measurement 1 has '
                             f'{_YAML_LAYOUTS[layout][0]}: give every measurement the same')
        layout = found
        row = []
        for key in _YAML_LAYOUTS[found]:
            values = item[key]
            if not (isinstance(values, list) and len(values) == 6 and all(
                    isinstance(value, (int, float)) and not isinstance(value, bool)
                    for value in values)):
                raise ValueError(f'{where}: {key} must be a list of six numbers, got '
                                 f'{preview(values)}')
            if not all(math.isfinite(value) for value in values):
                raise ValueError(f'{where}: {key} must be finite, got {preview(values)}')
            row += [float(value) for value in values]
        rows.append(row)
    return layout, np.array(rows)


def payload_poses(geometry, count: int = 20, *, margin: float = 0.9) -> np.ndarray:
    """
    Propose static poses to measure the payload at: tilted in every direction, within limits.

    The height of the centre is seen only through tilts (see the module's docstring), and the
    more the better: the poses tilt by ``margin`` times the largest tilt the geometry's limits
    allow in each of ``count`` directions spread evenly around the vertical, at the height
    (within 0.1 m of home) where those tilts are largest, with home's yaw. Tilts are searched up
    to 45 degrees in steps of 0.25 degrees: give the geometry its limits (a geometry without
    limits gets 45 degrees times ``margin`` in every direction).

    :param geometry: a :class:`stewart_kinematics.Geometry` (its limits).
    :param count: how many poses, at least :data:`MIN_POSES`.
    :param margin: the fraction of the largest tilt taken, in (0, 1].
    :returns: poses ``[X, Y, Z, alpha, beta, gamma]`` (metres, radians), shape (count, 6).
    :raises ValueError: for a count or margin out of range, or limits that allow no tilt.
    """
    if not (isinstance(count, (int, np.integer)) and MIN_POSES <= count <= 10_000):
        raise ValueError(f'count must be an integer from {MIN_POSES} to 10000, got '
                         f'{preview(count)}')
    if not (isinstance(margin, (int, float)) and 0.0 < margin <= 1.0):
        raise ValueError(f'margin must be a number in (0, 1], got {preview(margin)}')
    home = np.asarray(geometry.home_pose, dtype=float)
    azimuths = 2.0 * np.pi * np.arange(count) / count
    tilts = np.radians(np.arange(0.0, 45.25, 0.25))
    heights = np.linspace(-0.1, 0.1, 21)
    grid = np.tile(home, (heights.size, tilts.size, count, 1))
    grid[..., 2] += heights[:, None, None]
    grid[..., 3] = tilts[None, :, None] * np.cos(azimuths)
    grid[..., 4] = tilts[None, :, None] * np.sin(azimuths)
    allowed = check_poses_array(geometry, grid.reshape(-1, 6),
                                condition_of_refused=False).allowed.reshape(grid.shape[:3])
    reached = np.cumprod(allowed, axis=1).astype(bool)   # every smaller tilt allowed too
    largest = np.where(reached, tilts[None, :, None], -1.0).max(axis=1)   # (heights, count)
    score = np.where((largest > 0.0).all(axis=1), np.square(np.sin(largest)).sum(axis=1), -1.0)
    best = int(np.argmax(score))
    if score[best] <= 0.0:
        raise ValueError('the limits allow no tilt in some direction at any height within '
                         "0.1 m of home: the centre of mass's height cannot be identified")
    poses = np.tile(home, (count, 1))
    poses[:, 2] += heights[best]
    poses[:, 3] = margin * largest[best] * np.cos(azimuths)
    poses[:, 4] = margin * largest[best] * np.sin(azimuths)
    return poses
