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
Calibration: identify the real joints and actuator offsets of a built hexapod from measurements.

The model is the field's standard one, 42 parameters: the six base joints ``b_i`` (base frame),
the six platform joints ``p_i`` (platform frame, as :class:`~stewart_kinematics.Geometry`
holds them) and the six actuator offsets ``o_i``. At a measured pose
``[X, Y, Z, alpha, beta, gamma]`` (position and orientation of the platform frame in the base
frame, as :class:`~stewart_kinematics.Geometry` takes poses) actuator i reads

    ``a_i = |t + R p_i - b_i| - o_i``     (metres)

Gauge: the base frame and the platform frame are the frames the poses are measured in (a laser
tracker, CMM or camera registered to reference marks on the base, and a target fixed to the
platform). With full poses measured, the legs decouple: each leg's seven parameters are fitted
to that leg's N readings, and all 42 are identifiable from enough varied poses.

Shared joints (6-3 and 3-3 platforms, :attr:`~stewart_kinematics.Geometry.shared_joints`) are
one point: the two legs that share a joint share its three coordinates, which are fitted once
(:class:`ParameterLayout`; a 6-3 platform has 33 free parameters, a 3-3 one 24). Split, they
could drift apart and the calibrated platform would be a 6-6 one that the built machine is
not. Legs tied by a shared joint are fitted together (a 3-3 platform's six legs are one
block); the tie only removes parameters, so poses that determine the 42 of the untied model
determine the tied ones too. What a set of
poses cannot determine is stated from the singular values of the scaled identification
Jacobian (:func:`identifiability`): for example poses that never rotate the platform cannot tell
a base joint from its platform joint (``b_i + d`` and ``p_i + d`` fit alike), and the offset of
a leg is told from its joints' positions along the leg only by how much the leg swings (the
difference is second order in the swing angle).

Fitting is :func:`scipy.optimize.least_squares` with the analytic Jacobian, leg by leg (the
legs decouple), a robust loss first; then poses with a residual far beyond the robust noise
estimate are set aside as outliers (reported by index) and the inliers are fitted with plain
least squares, which gives the parameters' standard deviations.
"""

from dataclasses import dataclass, replace
import math
from typing import Optional, Tuple

import numpy as np
from scipy.linalg import qr
from scipy.optimize import least_squares

from stewart_kinematics import limits
# The files (measurement CSV, calibrated parameter file), re-exported: public here too.
from stewart_kinematics.analysis.calibration_files import (  # noqa: F401
    load_measurements,
    MEASUREMENT_COLUMNS,
    write_measurements,
    write_parameter_file,
)
from stewart_kinematics.analysis.calibration_model import (  # noqa: F401 (public here too)
    block_rows,
    identification_jacobian,
    LEG_COLUMNS,
    leg_jacobian,
    leg_lengths,
    PARAMETER_COUNT,
    parameter_layout,
    PARAMETER_NAMES,
    parameter_vector,
    ParameterLayout,
    PARAMETERS_PER_LEG,
    predict_actuator_positions,
    predicted_positions,
)
from stewart_kinematics.model.arrays import as_float_array, preview
from stewart_kinematics.model.geometry import Geometry
from stewart_kinematics.model.inputs import as_poses
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import (
    ACTUATOR_PARAMETERS,
    all_specs,
    check_values,
    GEOMETRY_PARAMETERS,
)

#: Fewer poses than this leave no redundancy to estimate the noise with (7 parameters per leg).
MIN_POSES = PARAMETERS_PER_LEG + 1
#: Relative tolerances (ftol, xtol, gtol) of the final least-squares fit.
FINAL_TOLERANCE = 1e-14
#: The losses of scipy's least_squares: 'linear' is plain least squares, the others robust.
LOSSES = ('soft_l1', 'huber', 'cauchy', 'arctan', 'linear')
#: Largest number of residual evaluations of one least-squares fit (a good one takes 3 to 10).
MAX_EVALUATIONS = 50
#: measurement_poses: candidates whose smallest eigenvalue is computed exactly at each step.
E_OPTIMAL_SHORTLIST = 200
#: MAD to standard deviation of a normal distribution.
_MAD_TO_SIGMA = 1.4826
#: Spread below which the poses count as not rotating / not moving, for the error's hints.
_STILL_ANGLE = 1e-3
_STILL_POSITION = 1e-4


class CalibrationError(ValueError):
    """The measurements cannot determine the parameters; the message says why."""


@dataclass(frozen=True)
class Combination:
    """
    A parameter combination that a set of poses determines badly (or not at all).

    :param legs: the legs it belongs to, 1..6: one leg (the legs decouple), or the legs tied
        by shared joints (see :class:`ParameterLayout`).
    :param coefficients: parameter name -> coefficient of the unit direction in scaled
        parameters (each column of the Jacobian divided by its norm), largest first.
    :param relative_singular_value: its singular value over the largest one of the scaled
        identification Jacobian; 0 when the poses cannot determine it at all.
    """

    legs: Tuple[int, ...]
    coefficients: Tuple[Tuple[str, float], ...]
    relative_singular_value: float

    @property
    def leg(self) -> int:
        """Return the (first) leg it belongs to."""
        return self.legs[0]

    def __str__(self):
        terms = ' '.join(f'{value:+.2f} {name}' for name, value in self.coefficients)
        legs = (f'leg {self.legs[0]}' if len(self.legs) == 1
                else 'legs ' + ', '.join(map(str, self.legs)))
        return (f'{legs}: {terms} '
                f'(relative singular value {self.relative_singular_value:.1e})')


@dataclass(frozen=True)
class Identifiability:
    """
    What a set of poses can determine: singular values of the scaled identification Jacobian.

    The identification Jacobian holds ``d a_ki / d parameter`` for every pose k and leg i
    (6N rows, a column per free parameter: 42 on a 6-6 platform); each column is divided by
    its norm (all parameters are metres, the scaling only removes the effect of how many poses
    and how the legs point).

    :param singular_values: per block of :attr:`blocks`, largest first (the Jacobian is block
        diagonal): six arrays of 7 on a 6-6 platform.
    :param blocks: the legs of each block, 1..6 (see :class:`ParameterLayout`).
    :param condition_number: largest over smallest singular value of the whole scaled Jacobian
        (``inf`` if a combination is undetermined).
    :param weakest: the worst-determined combination of each block, weakest first.
    :param undetermined: combinations whose relative singular value is below
        ``1 / max_condition``: the poses cannot determine them.
    :param position_spread: largest minus smallest of X, Y, Z over the poses, metres.
    :param angle_spread: the same for alpha, beta, gamma, radians.
    """

    singular_values: Tuple[np.ndarray, ...]
    blocks: Tuple[Tuple[int, ...], ...]
    condition_number: float
    weakest: Tuple[Combination, ...]
    undetermined: Tuple[Combination, ...]
    position_spread: np.ndarray
    angle_spread: np.ndarray

    @property
    def identifiable(self) -> bool:
        """Whether every combination is determined (condition below the limit)."""
        return not self.undetermined

    def problem(self) -> str:
        """Describe what the poses cannot determine and the likely cause; '' when none."""
        if self.identifiable:
            return ''
        lines = [f'the poses cannot determine {len(self.undetermined)} parameter '
                 f'combination(s) (scaled condition number {self.condition_number:.3g}):']
        lines += [f'  {combination}' for combination in self.undetermined[:12]]
        if len(self.undetermined) > 12:
            lines.append(f'  ... and {len(self.undetermined) - 12} more')
        if np.max(self.angle_spread) < _STILL_ANGLE:
            lines.append('the poses never rotate the platform, so a base joint and its platform '
                         'joint shifted alike (b_i + d, p_i + d) fit as well: add rotated poses')
        elif np.min(self.angle_spread) < _STILL_ANGLE:
            axes = [name for name, spread in zip(('alpha', 'beta', 'gamma'), self.angle_spread)
                    if spread < _STILL_ANGLE]
            lines.append(f'the poses never turn {", ".join(axes)}: vary every angle')
        if np.max(self.position_spread) < _STILL_POSITION and np.max(
                self.angle_spread) < _STILL_ANGLE:
            lines.append('the poses are all (nearly) the same pose')
        lines.append(
            f'poses span {_format_spread(self.position_spread, 1e3, "mm")} in X, Y, Z and '
            f'{_format_spread(self.angle_spread, 180.0 / math.pi, "deg")} in alpha, beta, '
            'gamma; spread them over the workspace (measurement_poses proposes well-conditioned '
            'ones)')
        return '\n'.join(lines)


@dataclass(frozen=True)
class CalibrationResult:
    """
    The calibrated platform and how well it fits.

    Residuals are predicted minus measured actuator positions, metres, shape (N, 6); the
    statistics (``rms_*``, ``worst_*``) are per leg over the inlier poses.

    :param geometry: the calibrated geometry (nominal home pose and limits).
    :param actuator_offsets: calibrated offsets o_1..o_6, metres.
    :param nominal: the nominal geometry the fit started from.
    :param nominal_offsets: the offsets the "before" residuals use, metres.
    :param parameters: the 42 calibrated parameters, in :data:`PARAMETER_NAMES` order, metres
        (the two legs of a shared joint hold the same coordinates).
    :param standard_deviations: their standard deviations from the fit, metres.
    :param residuals_before: the nominal model's residuals, every pose.
    :param residuals_after: the calibrated model's residuals, every pose.
    :param inliers: boolean mask of the poses used in the final fit.
    :param outliers: indices of the poses set aside (a mis-read measurement), ascending.
    :param noise: the residuals' standard deviation after the fit (degrees of freedom
        counted), metres: the measurement noise as the fit sees it.
    :param identifiability: the identifiability of the inlier poses at the solution.
    :param iterations: residual evaluations of the final least-squares fit, summed over the
        blocks of legs.
    :param layout: the free parameters: the shared joints tied (:class:`ParameterLayout`).
    """

    geometry: Geometry
    actuator_offsets: np.ndarray
    nominal: Geometry
    nominal_offsets: np.ndarray
    parameters: np.ndarray
    standard_deviations: np.ndarray
    residuals_before: np.ndarray
    residuals_after: np.ndarray
    inliers: np.ndarray
    outliers: Tuple[int, ...]
    noise: float
    identifiability: Identifiability
    iterations: int
    layout: ParameterLayout

    @property
    def condition_number(self) -> float:
        """Scaled condition number of the identification Jacobian at the solution."""
        return self.identifiability.condition_number

    @property
    def rms_before(self) -> np.ndarray:
        """RMS residual of the nominal model per leg, inlier poses, metres, (6,)."""
        return _rms(self.residuals_before[self.inliers])

    @property
    def rms_after(self) -> np.ndarray:
        """RMS residual of the calibrated model per leg, inlier poses, metres, (6,)."""
        return _rms(self.residuals_after[self.inliers])

    @property
    def worst_before(self) -> np.ndarray:
        """Largest absolute residual of the nominal model per leg, inlier poses, metres."""
        return np.max(np.abs(self.residuals_before[self.inliers]), axis=0)

    @property
    def worst_after(self) -> np.ndarray:
        """Largest absolute residual of the calibrated model per leg, inlier poses, metres."""
        return np.max(np.abs(self.residuals_after[self.inliers]), axis=0)

    def report(self) -> str:
        """Return the calibration report as text (micrometres for residuals)."""
        count = self.inliers.size
        lines = [f'poses: {count} measured, {int(np.sum(self.inliers))} used, '
                 f'outliers: {list(self.outliers) if self.outliers else "none"}',
                 '',
                 'residuals (predicted - measured actuator position), micrometres',
                 'leg        RMS before   worst before    RMS after  worst after']
        for leg in range(6):
            lines.append(f'{leg + 1:3d} {self.rms_before[leg] * 1e6:16.1f} '
                         f'{self.worst_before[leg] * 1e6:14.1f} {self.rms_after[leg] * 1e6:12.2f} '
                         f'{self.worst_after[leg] * 1e6:12.2f}')
        inlier_before = self.residuals_before[self.inliers]
        inlier_after = self.residuals_after[self.inliers]
        lines.append(f'all {_rms(inlier_before.ravel()) * 1e6:16.1f} '
                     f'{np.max(np.abs(inlier_before)) * 1e6:14.1f} '
                     f'{_rms(inlier_after.ravel()) * 1e6:12.2f} '
                     f'{np.max(np.abs(inlier_after)) * 1e6:12.2f}')
        lines += ['', f'noise estimate: {self.noise * 1e6:.2f} um; scaled condition number of the '
                  f'identification Jacobian: {self.condition_number:.3g}',
                  '', 'parameter changes from nominal, millimetres (+- one standard deviation)',
                  'leg   ' + ''.join(f'{name:>17s}' for name in (
                      'b.x', 'b.y', 'b.z', 'p.x', 'p.y', 'p.z', 'offset'))]
        nominal = parameter_vector(self.nominal, self.nominal_offsets)
        change = (self.parameters - nominal) * 1e3
        deviation = self.standard_deviations * 1e3
        for leg in range(6):
            cells = [f'{change[column]:+9.3f}+-{deviation[column]:6.3f}'
                     for column in LEG_COLUMNS[leg]]
            lines.append(f'{leg + 1:3d}   ' + ''.join(f'{cell:>17s}' for cell in cells))
        if self.layout.tied:
            lines += ['', 'shared joints, fitted as one point each: ' + ', '.join(
                sorted({name.split('.')[0] for name in self.layout.tied}))]
        lines += ['', 'worst-determined combination of each '
                  + ('leg' if len(self.layout.blocks) == 6 else 'block of legs')
                  + ' (scaled parameters):']
        lines += [f'  {combination}' for combination in self.identifiability.weakest]
        return '\n'.join(lines)


def identifiability(geometry: Geometry, poses, *, max_condition: float = 1e5) -> Identifiability:
    """
    Tell what the poses can determine of the parameters, at ``geometry`` (shared joints tied).

    :param geometry: the platform (nominal, or calibrated).
    :param poses: the measurement poses, shape (N, 6), metres and radians.
    :param max_condition: a combination whose scaled singular value is below the largest over
        this counts as undetermined: the noise is amplified that much in it.
    """
    poses = np.atleast_2d(as_poses(poses))
    rotations = euler_zyx_to_matrix(poses[:, 3:])
    parameters = parameter_vector(geometry, np.zeros(6))
    layout = parameter_layout(geometry)
    jacobian = identification_jacobian(parameters, poses[:, :3], rotations)
    return _identifiability(layout.tie(jacobian), poses, max_condition, layout)


def calibrate(nominal: Geometry, poses, actuator_positions, nominal_offsets=None, *,
              loss: str = 'soft_l1', outlier_threshold: float = 5.0,
              min_outlier_residual: float = 1e-6, max_outlier_fraction: float = 0.25,
              max_condition: float = 1e5, max_noise: float = 1e-3) -> CalibrationResult:
    """
    Identify the 36 joint coordinates and 6 actuator offsets from measured poses.

    A joint that two legs share (:attr:`Geometry.shared_joints`) is one point, fitted once.

    :param nominal: the drawing's geometry: the starting point, and the home pose and limits
        that the calibrated geometry keeps.
    :param poses: measured poses ``[X, Y, Z, alpha, beta, gamma]`` of the platform in the base
        frame (metres, radians; the platform frame's origin), shape (N, 6), N >= 8.
    :param actuator_positions: the six actuator readings at each pose, metres, shape (N, 6).
    :param nominal_offsets: the nominal actuator offsets o_1..o_6, metres; ``None`` when
        unknown: then each leg's mean of nominal length minus reading is used.
    :param loss: scipy's robust loss for the first fit (``'soft_l1'``, ``'huber'``,
        ``'cauchy'``, ``'arctan'``), or ``'linear'`` for plain least squares without outlier
        rejection.
    :param outlier_threshold: a pose is an outlier when one of its six residuals after the
        robust fit exceeds this many robust standard deviations (1.4826 times the median
        absolute residual) ...
    :param min_outlier_residual: ... and this many metres (for noise-free data).
    :param max_outlier_fraction: more outliers than this fraction of the poses means the
        model does not fit the data (wrong units, columns or legs): refused.
    :param max_condition: largest allowed scaled condition number of the identification
        Jacobian (see :func:`identifiability`).
    :param max_noise: a fit whose residuals' standard deviation exceeds this, metres, does not
        describe the platform: refused.
    :raises CalibrationError: too few poses, poses that cannot determine the parameters (the
        message names the combinations and the likely cause), too many outliers, or residuals
        beyond ``max_noise``.
    :raises ValueError: malformed arrays.
    """
    if loss not in LOSSES:
        raise ValueError(f"loss must be one of {', '.join(LOSSES)}; got {loss!r}")
    _check_number('outlier_threshold', outlier_threshold, 1.0, math.inf,
                  'robust standard deviations')
    _check_number('min_outlier_residual', min_outlier_residual, 0.0, math.inf, 'metres')
    _check_number('max_outlier_fraction', max_outlier_fraction, 0.0, 1.0, 'a fraction')
    _check_number('max_condition', max_condition, 1.0, math.inf, 'a condition number')
    _check_number('max_noise', max_noise, 0.0, math.inf, 'metres', low_inclusive=False)
    if not isinstance(nominal, Geometry):
        raise ValueError(f'nominal must be a Geometry, got {type(nominal).__name__}')
    poses = np.atleast_2d(as_poses(poses))
    readings = np.atleast_2d(as_float_array(actuator_positions, 'actuator_positions'))
    if readings.shape != poses.shape:
        raise ValueError(f'actuator_positions must have shape {poses.shape} like the poses, '
                         f'got {readings.shape}')
    if not np.all(np.isfinite(readings)):
        bad = np.unique(np.argwhere(~np.isfinite(readings))[:, 0])
        raise ValueError(f'actuator_positions must be finite; pose(s) {bad[:10].tolist()} are not')
    count = poses.shape[0]
    if count < MIN_POSES:
        raise CalibrationError(
            f'too few poses: {count} given, at least {MIN_POSES} needed (each leg has '
            f'{PARAMETERS_PER_LEG} parameters, and one more reading shows the noise); 30 to 60 '
            'poses spread over the workspace are usual')
    positions, rotations = poses[:, :3], euler_zyx_to_matrix(poses[:, 3:])
    if nominal_offsets is None:
        nominal_parameters = parameter_vector(nominal, np.zeros(6))
        nominal_offsets = np.mean(
            predicted_positions(nominal_parameters, positions, rotations) - readings, axis=0)
    layout = parameter_layout(nominal)
    start = layout.expand(layout.reduce(parameter_vector(nominal, nominal_offsets)))
    jacobian = identification_jacobian(start, positions, rotations)
    report = _identifiability(layout.tie(jacobian), poses, max_condition, layout)
    if not report.identifiable:
        raise CalibrationError(report.problem())

    def fit(x0, mask, fit_loss, scale=1.0, tolerance=1e-8):
        return _fit_blocks(layout, x0, positions[mask], rotations[mask], readings[mask],
                           fit_loss, scale, tolerance)

    def refuse_misfit(error, robust=False):
        if robust:  # a few gross outliers must not count: they are for the robust fit
            noise = _MAD_TO_SIGMA * float(np.median(np.abs(error)))
        else:
            noise = math.sqrt(float(np.sum(np.square(error)))
                              / max(error.size - layout.count, 1))
        if not noise <= max_noise:
            raise CalibrationError(
                f'the calibrated model leaves residuals of {noise * 1e3:.3g} mm (standard '
                f'deviation), above {max_noise * 1e3:.3g} mm: the model does not fit the data; '
                'check the units (metres, radians), the column order, the leg order and the '
                'nominal geometry' + (", or set the outliers aside (loss='soft_l1')"
                                      if loss == 'linear' else ''))
        return noise

    inliers = np.ones(count, dtype=bool)
    x = start
    if loss != 'linear':
        # Robust fit; its scale: the robust noise of a first plain fit, which the outliers
        # disturb little while they are few.
        rough = fit(start, inliers, 'linear')
        # Robust losses would be slow to crawl through data the model cannot fit at all.
        refuse_misfit(rough.fun, robust=True)
        rough = rough.x
        for _ in range(2):
            if not np.any(inliers):
                break   # every pose an outlier: refused just below, with the reason
            error = predicted_positions(rough, positions, rotations) - readings
            sigma = _MAD_TO_SIGMA * np.median(np.abs(error[inliers]))
            scale = max(sigma, min_outlier_residual)
            rough = fit(rough, inliers, loss, scale).x
            error = predicted_positions(rough, positions, rotations) - readings
            sigma = _MAD_TO_SIGMA * np.median(np.abs(error))
            threshold = max(outlier_threshold * sigma, min_outlier_residual)
            inliers = np.max(np.abs(error), axis=1) <= threshold
        x = rough
        outlier_count = int(np.sum(~inliers))
        if outlier_count > max_outlier_fraction * count:
            raise CalibrationError(
                f'{outlier_count} of {count} poses do not fit the model (residual above '
                f'{threshold * 1e6:.1f} um): check the units (metres, radians), the column '
                'order, the leg order and the nominal geometry')
        if int(np.sum(inliers)) < MIN_POSES:
            raise CalibrationError(
                f'only {int(np.sum(inliers))} poses left after removing outliers; at least '
                f'{MIN_POSES} needed')
    # The final fit to the last digits: Gauss-Newton converges in a step or two from here.
    solution = fit(x, inliers, 'linear', tolerance=FINAL_TOLERANCE)
    parameters = solution.x
    inlier_report = _identifiability(
        layout.tie(identification_jacobian(parameters, positions[inliers], rotations[inliers])),
        poses[inliers], max_condition, layout)
    if not inlier_report.identifiable:
        raise CalibrationError('after removing the outlier poses '
                               f'{np.flatnonzero(~inliers).tolist()}: ' + inlier_report.problem())
    noise = refuse_misfit(solution.fun)
    free_deviations = np.empty(layout.count)
    for legs, block in zip(layout.blocks, solution.block_jacobians):
        covariance = np.linalg.pinv(block.T @ block)
        free_deviations[layout.columns(legs)] = noise * np.sqrt(np.diag(covariance))
    standard_deviations = layout.expand(free_deviations)
    geometry = _geometry_of(nominal, parameters)
    return CalibrationResult(
        geometry=geometry, actuator_offsets=parameters[36:].copy(), nominal=nominal,
        nominal_offsets=np.asarray(nominal_offsets, dtype=float).copy(), parameters=parameters,
        standard_deviations=standard_deviations,
        residuals_before=predicted_positions(start, positions, rotations) - readings,
        residuals_after=predicted_positions(parameters, positions, rotations) - readings,
        inliers=inliers, outliers=tuple(int(index) for index in np.flatnonzero(~inliers)),
        noise=noise, identifiability=inlier_report, iterations=int(solution.nfev),
        layout=layout)


@dataclass(frozen=True)
class MeasurementPoseSelection:
    """
    Poses proposed for measurement, and how much better they are than random ones.

    :param poses: shape (n, 6), metres and radians, within the geometry's limits.
    :param smallest_singular_value: of the unscaled identification Jacobian of these poses
        (metres per metre): the noise amplification of the worst-determined combination is its
        inverse.
    :param condition_number: scaled condition number of these poses.
    :param random_smallest_singular_value: median of the same over random draws of n poses
        from the same candidates.
    :param random_condition_number: median scaled condition number of those draws.
    """

    poses: np.ndarray
    smallest_singular_value: float
    condition_number: float
    random_smallest_singular_value: float
    random_condition_number: float

    @property
    def improvement(self) -> float:
        """How many times larger the smallest singular value is than random poses' median."""
        return self.smallest_singular_value / self.random_smallest_singular_value


def measurement_poses(geometry: Geometry, count: int, *, position_range=0.05,
                      angle_range=math.radians(10.0), candidates: int = 2000,
                      random_draws: int = 20, seed: Optional[int] = 0
                      ) -> MeasurementPoseSelection:
    """
    Propose ``count`` measurement poses that make the identification well conditioned.

    Candidates are drawn uniformly within ``home_pose +- range`` and kept where the geometry's
    limits allow them; poses are then picked greedily: first for the largest determinant of
    each leg's information matrix (D-optimal, until every leg is determined), then for the
    largest smallest singular value of the identification Jacobian (E-optimal: the
    worst-determined combination as well determined as possible).

    :param geometry: the nominal platform (its limits bound the candidates).
    :param count: number of poses, at least 8.
    :param position_range: half-width of the candidates' X, Y, Z around home, metres (a float
        or three).
    :param angle_range: half-width of alpha, beta, gamma around home, radians (a float or three).
    :param candidates: number of random candidates drawn.
    :param random_draws: random selections of ``count`` candidates to compare with.
    :param seed: random seed (the same seed, the same poses).
    :raises ValueError: if ``count`` is below 8 or fewer candidates are within the limits.
    """
    for name, value, low in (('count', count, MIN_POSES), ('candidates', candidates, 1),
                             ('random_draws', random_draws, 1)):
        if not isinstance(value, (int, np.integer)) or isinstance(value, bool) or value < low:
            raise ValueError(f'{name} must be an integer of at least {low}, got {preview(value)}')
    generator = np.random.default_rng(seed)
    half_width = []
    for name, value in (('position_range', position_range), ('angle_range', angle_range)):
        value = as_float_array(value, name)
        if value.shape not in ((), (3,)) or not np.all((value > 0.0) & np.isfinite(value)):
            raise ValueError(f'{name} must be one positive finite number or three, got '
                             f'{preview(value)}')
        half_width.append(np.broadcast_to(value, (3,)))
    half_width = np.concatenate(half_width)
    pool = geometry.home_pose + generator.uniform(-1.0, 1.0, (candidates, 6)) * half_width
    allowed = np.array([not violations for violations in limits.check_poses(geometry, pool)])
    pool = pool[allowed]
    if pool.shape[0] < 2 * count:
        raise ValueError(
            f'only {pool.shape[0]} of {candidates} candidate poses are within the limits; '
            f'{2 * count} needed to choose {count}: widen the ranges or draw more candidates')
    parameters = parameter_vector(geometry, np.zeros(6))
    jac = identification_jacobian(parameters, pool[:, :3], euler_zyx_to_matrix(pool[:, 3:]))
    # The poses are chosen for the untied model (each leg's 7 parameters), which bounds the
    # tied one of shared joints from below; their quality is that of the tied model.
    layout = parameter_layout(geometry)
    tied = layout.tie(jac)
    # Per candidate and leg, the row of the leg's 7 parameters: (C, 6, 7).
    rows = np.stack([jac[leg::6, columns] for leg, columns in enumerate(LEG_COLUMNS)], axis=1)
    information = np.zeros((6, PARAMETERS_PER_LEG, PARAMETERS_PER_LEG))
    regularisation = 1e-9 * np.eye(PARAMETERS_PER_LEG)
    chosen = []
    available = np.ones(pool.shape[0], dtype=bool)
    for step in range(count):
        if step < 2 * PARAMETERS_PER_LEG:
            inverse = np.linalg.inv(information + regularisation)
            gain = np.einsum('cli,lij,clj->cl', rows, inverse, rows)
            score = np.sum(np.log1p(gain), axis=1)
        else:
            # The exact smallest eigenvalue after adding each candidate, computed for the
            # candidates that add most along each leg's two weakest directions (a candidate
            # adds (g . v)^2 along an eigenvector v to first order).
            values, vectors = np.linalg.eigh(information)
            along = np.einsum('cli,lik->clk', rows, vectors[:, :, :2]) ** 2
            estimate = np.min(values[None, :, 0] + along[:, :, 0], axis=1) + np.min(
                along[:, :, 1], axis=1) * 1e-3
            estimate[~available] = -np.inf
            shortlist = np.argsort(-estimate)[:E_OPTIMAL_SHORTLIST]
            shortlist = shortlist[available[shortlist]]
            updated = information + rows[shortlist, :, :, None] * rows[shortlist, :, None, :]
            score = np.full(pool.shape[0], -np.inf)
            score[shortlist] = np.min(np.linalg.eigvalsh(updated)[..., 0], axis=1)
        score[~available] = -np.inf
        best = int(np.argmax(score))
        chosen.append(best)
        available[best] = False
        information += rows[best, :, :, None] * rows[best, :, None, :]
    poses = pool[chosen]

    def quality(indices):
        block = tied.reshape(-1, 6, layout.count)[indices].reshape(-1, layout.count)
        smallest = min(np.linalg.svd(block_rows(block, layout, legs), compute_uv=False)[-1]
                       for legs in layout.blocks)
        return smallest, _identifiability(block, pool[indices], math.inf,
                                          layout).condition_number

    random_quality = np.array([
        quality(generator.choice(pool.shape[0], count, replace=False))
        for _ in range(random_draws)])
    smallest, condition = quality(np.array(chosen))
    return MeasurementPoseSelection(
        poses=poses, smallest_singular_value=float(smallest), condition_number=float(condition),
        random_smallest_singular_value=float(np.median(random_quality[:, 0])),
        random_condition_number=float(np.median(random_quality[:, 1])))


def calibrated_parameters(result: CalibrationResult, nominal_values: Optional[dict] = None
                          ) -> dict:
    """
    Return the ROS parameters of the calibrated platform, as a ``/**`` section holds them.

    :param result: a calibration.
    :param nominal_values: the nominal parameter values (from the nominal parameter files);
        every package parameter among them is kept (limits, home pose, frames such as
        ``tool_frame_position``, ...), and ``base_joints``, ``platform_joints`` (platform
        frame) and ``actuator_offsets`` are replaced, so that the loaded geometry is the
        calibrated one. Without nominal values, the calibrated geometry's own home pose and
        limits are written.
    :returns: parameter name -> value, floats as floats.
    """
    known = {spec.name for spec in all_specs()}
    values = {key: value for key, value in (nominal_values or {}).items() if key in known}
    geometry = result.geometry
    if not values:
        values = {
            'home_position': geometry.home_pose[:3].tolist(),
            'home_orientation_deg': np.degrees(geometry.home_pose[3:]).tolist(),
            **limits.limits_of(geometry).parameters(),
        }
    values['base_joints'] = [float(value) for value in geometry.base_joints.ravel()]
    values['platform_joints'] = [float(value) for value in geometry.platform_joints.ravel()]
    values['actuator_offsets'] = [float(value) for value in result.actuator_offsets]
    check_values(GEOMETRY_PARAMETERS + ACTUATOR_PARAMETERS,
                 {**{spec.name: spec.default for spec in GEOMETRY_PARAMETERS}, **values})
    order = [spec.name for spec in all_specs()]
    return {name: values[name] for name in order if name in values}


def _check_number(name, value, low, high, unit, low_inclusive=True):
    """Refuse a setting that is not a number in [low, high] (``(low, high]``), naming it."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f'{name} must be a number ({unit}), got {preview(value)}')
    above = value >= low if low_inclusive else value > low
    if not (above and value <= high):
        interval = f'{"[" if low_inclusive else "("}{low:g}, {high:g}]'
        raise ValueError(f'{name} must be in {interval} ({unit}), got {value!r}')


def _geometry_of(nominal: Geometry, parameters) -> Geometry:
    try:
        return replace(nominal, base_joints=parameters[:18].reshape(6, 3),
                       platform_joints=parameters[18:36].reshape(6, 3))
    except ValueError as error:
        raise CalibrationError(f'the calibrated geometry is not valid: {error}') from error


@dataclass(frozen=True)
class _Fit:
    x: np.ndarray
    fun: np.ndarray
    block_jacobians: Tuple[np.ndarray, ...]
    nfev: int


def _fit_blocks(layout, x0, positions, rotations, readings, loss, scale, tolerance) -> _Fit:
    """
    Fit each block's parameters to its legs' readings: the blocks decouple.

    On a 6-6 platform, six problems of N x 7 instead of one of 6N x 42 (block diagonal): far
    less work, and matrices too small for a multi-threaded BLAS to stall on (it did, 10x, on
    a busy machine). Legs that share a joint form one block, its coordinates fitted once.

    :param x0: the 42 parameters to start from (a shared joint's equal for both legs).
    :returns: the 42 parameters fitted (``x``), the residuals (N * 6, pose by leg), each
        block's Jacobian in its free parameters, and the evaluations.
    """
    free = layout.reduce(x0)
    count = positions.shape[0]
    fun = np.empty(readings.shape)
    jacobians = []
    evaluations = 0
    # Plain fits: MINPACK's Levenberg-Marquardt (compiled, fastest on small dense problems);
    # robust losses need the trust-region reflective method.
    method = 'lm' if loss == 'linear' else 'trf'
    for legs in layout.blocks:
        columns = layout.columns(legs)
        # Each leg's seven parameters, as positions among the block's columns.
        locals_ = [np.searchsorted(columns, layout.index[LEG_COLUMNS[leg - 1]])
                   for leg in legs]

        def residuals(values, legs=legs, locals_=locals_):
            return np.concatenate([
                leg_lengths(values[local], positions, rotations) - values[local[6]]
                - readings[:, leg - 1] for leg, local in zip(legs, locals_)])

        def jac(values, locals_=locals_, width=columns.size):
            block = np.zeros((len(locals_) * count, width))
            for k, local in enumerate(locals_):
                block[k * count:(k + 1) * count, local] = leg_jacobian(
                    values[local], positions, rotations)
            return block
        solution = least_squares(residuals, free[columns], jac=jac, loss=loss, f_scale=scale,
                                 x_scale='jac', method=method, ftol=tolerance, xtol=tolerance,
                                 gtol=tolerance, max_nfev=MAX_EVALUATIONS * len(legs))
        free[columns] = solution.x
        fun[:, np.array(legs) - 1] = solution.fun.reshape(len(legs), count).T
        jacobians.append(jac(solution.x))
        evaluations += solution.nfev
    return _Fit(layout.expand(free), fun.ravel(), tuple(jacobians), evaluations)


def _identifiability(jac, poses, max_condition, layout) -> Identifiability:
    """
    Tell what a tied identification Jacobian (6N, layout.count) determines, block by block.

    :param layout: the free parameters (:func:`parameter_layout`).
    """
    norms = np.linalg.norm(jac, axis=0)
    scaled = jac / np.where(norms > 0.0, norms, 1.0)
    singular_values = []
    directions = []
    for legs in layout.blocks:
        block = block_rows(scaled, layout, legs)
        _, values, right = np.linalg.svd(block)
        if values.size < block.shape[1]:
            values = np.concatenate([values, np.zeros(block.shape[1] - values.size)])
        singular_values.append(values)
        directions.append(right)
    largest = float(max(np.max(values) for values in singular_values))
    smallest = float(min(np.min(values) for values in singular_values))
    condition = largest / smallest if smallest > largest * 1e-300 else math.inf
    weakest = []
    undetermined = []
    for legs, values, vectors in zip(layout.blocks, singular_values, directions):
        columns = layout.columns(legs)
        relative = values / largest
        vectors = vectors.copy()
        null = relative * max_condition < 1.0
        if np.count_nonzero(null) > 1:
            # Any basis of a null space fits; show the one with a unit coefficient on one
            # parameter each (pivoted QR), which reads as "b_i.y and p_i.y shift together".
            basis = vectors[null]
            _, _, pivots = qr(basis, pivoting=True)
            vectors[null] = np.linalg.solve(basis[:, pivots[:basis.shape[0]]], basis)
        combinations = []
        for index in range(columns.size):
            vector = vectors[index] / np.linalg.norm(vectors[index])
            if vector[np.argmax(np.abs(vector))] < 0.0:
                vector = -vector
            # Largest first; equal ones (to the digits shown) in parameter order.
            order = np.lexsort((np.arange(vector.size), -np.round(np.abs(vector), 2)))
            terms = tuple((layout.names[columns[j]], float(vector[j])) for j in order
                          if abs(vector[j]) >= 0.1)
            combinations.append(Combination(tuple(legs), terms, float(relative[index])))
            if null[index]:
                undetermined.append(combinations[-1])
        weakest.append(combinations[-1])
    return Identifiability(
        singular_values=tuple(singular_values), blocks=layout.blocks, condition_number=condition,
        weakest=tuple(sorted(weakest, key=lambda combination:
                             combination.relative_singular_value)),
        undetermined=tuple(undetermined), position_spread=np.ptp(poses[:, :3], axis=0),
        angle_spread=np.ptp(poses[:, 3:], axis=0))


def _rms(values):
    return np.sqrt(np.mean(np.square(values), axis=0))


def _format_spread(spread, factor, unit):
    return ', '.join(f'{value * factor:.3g}' for value in spread) + f' {unit}'
