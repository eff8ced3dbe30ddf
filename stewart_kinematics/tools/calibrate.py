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
stewart_calibrate: calibrate a built hexapod from measured poses and actuator readings.

Reads a CSV of measurements and the nominal parameter files, prints the calibration report,
writes a calibrated parameter file that the nodes load as it is (``--params-file``) and a PNG
of the residuals per leg before and after. With ``--propose N`` it instead writes N
well-conditioned poses to measure (the actuator columns left empty).

A parameter file that cannot be read (not YAML, an alias, nested too deep, a value of the
wrong type or null) exits 2 with one line, ``file:line: what is wrong``, before any work.
"""

import argparse
from pathlib import Path
import sys

import numpy as np

from stewart_kinematics.analysis.calibration import (
    calibrate,
    calibrated_parameters,
    CalibrationError,
    LOSSES,
    measurement_poses,
    MIN_POSES,
    predict_actuator_positions,
)
from stewart_kinematics.analysis.calibration_files import (
    load_measurements,
    MEASUREMENT_COLUMNS,
    write_parameter_file,
)
from stewart_kinematics.parameters import (
    ACTUATOR_PARAMETERS,
    check_values,
    geometry_from_parameters,
    ParameterFileError,
    read_parameter_files,
)
from stewart_kinematics.tools.cli_arguments import (
    check_output_paths,
    integer_at_least,
    number_at_least,
    number_in,
    positive_number,
    refuse_parameter_file,
)

EPILOG = """\
measurement CSV: a header row naming the columns, then one row per measured pose, each with
as many fields as the header; other columns are ignored, lines starting with # are comments,
and a byte-order mark and spaces around the fields are accepted. SI units:
  X, Y, Z              measured position of the platform frame's origin in the base frame, m
  alpha, beta, gamma   measured orientation, rad (R = Rz(gamma) Ry(beta) Rx(alpha))
  actuator_1..6        actuator positions read at that pose, m (leg length minus the offset)
The base and platform frames are the frames the poses are measured in (see doc/calibration.md,
the gauge). actuator_offsets in the parameter files are the nominal offsets; without them
each leg's offset is first estimated from the readings.

exit codes: 0 calibrated; 1 refused (too few or too similar poses, data that do not fit:
the reason is printed, or a file that cannot be read, with its line); 2 bad arguments (an
option out of its range, an output that cannot be written).
"""


def parse_arguments(argv):
    """Return the command-line options."""
    parser = argparse.ArgumentParser(
        prog='stewart_calibrate', description=__doc__.strip(),
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('measurements', nargs='?', type=Path,
                        help='CSV of measured poses and actuator positions (columns below)')
    parser.add_argument('--params-file', dest='params_files', action='append', type=Path,
                        required=True,
                        help='nominal parameter file (repeat to layer files, as for the nodes)')
    parser.add_argument('--output', type=Path, default=Path('calibrated.yaml'),
                        help='calibrated parameter file to write (default: %(default)s)')
    parser.add_argument('--figure', type=Path, default=None,
                        help='PNG of the residuals per leg (default: the output file with '
                             '_residuals.png)')
    parser.add_argument('--no-figure', action='store_true', help='write no PNG')
    parser.add_argument('--validate', type=Path, default=None,
                        help='CSV of further measurements, not used for fitting: prints how '
                             'well the nominal and the calibrated model predict them')
    parser.add_argument('--loss', default='soft_l1', choices=LOSSES,
                        help="robust loss of the first fit; 'linear' keeps every pose "
                             '(default: %(default)s)')
    parser.add_argument('--outlier-threshold', type=number_at_least(1.0), default=5.0,
                        help='a pose whose residual exceeds this many robust standard '
                             'deviations is set aside; at least 1 (default: %(default)s)')
    parser.add_argument('--max-condition', type=number_at_least(1.0), default=1e5,
                        help='largest scaled condition number accepted; at least 1 (default: '
                             '%(default)g)')
    parser.add_argument('--propose', type=integer_at_least(MIN_POSES), metavar='N',
                        default=None,
                        help='instead of calibrating, write N well-conditioned measurement '
                             'poses within the limits to --poses-out')
    parser.add_argument('--poses-out', type=Path, default=Path('measurement_poses.csv'),
                        help='CSV for --propose (default: %(default)s)')
    parser.add_argument('--position-range', type=positive_number, default=0.05,
                        help='--propose: half-range of X, Y, Z around home, m '
                             '(default: %(default)s)')
    parser.add_argument('--angle-range-deg', type=number_in(0.0, 90.0, low_inclusive=False),
                        default=10.0,
                        help='--propose: half-range of the angles around home, degrees '
                             '(default: %(default)s)')
    arguments = parser.parse_args(argv)
    if arguments.propose is None and arguments.measurements is None:
        parser.error('give the measurement CSV, or --propose N')
    if arguments.propose is not None:
        outputs = [('--poses-out', arguments.poses_out, False)]
    else:
        outputs = [('--output', arguments.output, False)]
        if not arguments.no_figure:
            outputs.append(('--figure', _figure_path(arguments), False))
    check_output_paths(parser, outputs)
    return arguments


def _figure_path(arguments) -> Path:
    """Return the residual figure's path: --figure, else beside the output file."""
    return arguments.figure or arguments.output.with_name(
        arguments.output.stem + '_residuals.png')


def main(argv=None) -> int:
    """Run stewart_calibrate; return the exit code."""
    arguments = parse_arguments(argv)
    try:
        values = read_parameter_files(arguments.params_files)
        nominal = geometry_from_parameters(values)
        if arguments.propose is not None:
            return _propose(arguments, nominal)
        offsets = None
        if 'actuator_offsets' in values:
            check_values(ACTUATOR_PARAMETERS, values)
            offsets = np.asarray(values['actuator_offsets'], dtype=float)
        poses, readings = load_measurements(arguments.measurements)
        validation = None   # read before the fit: a bad file fails at once
        if arguments.validate is not None:
            validation = load_measurements(arguments.validate)
        result = calibrate(nominal, poses, readings, offsets, loss=arguments.loss,
                           outlier_threshold=arguments.outlier_threshold,
                           max_condition=arguments.max_condition)
    except ParameterFileError as error:
        return refuse_parameter_file('stewart_calibrate', error)
    except CalibrationError as error:
        print(f'stewart_calibrate: cannot calibrate: {error}', file=sys.stderr)
        return 1
    except ValueError as error:
        print(f'stewart_calibrate: {error}', file=sys.stderr)
        return 1
    except OSError as error:
        print(f'stewart_calibrate: cannot write {error.filename}: {error.strerror}',
              file=sys.stderr)
        return 1
    try:
        _write_results(arguments, result, validation, values)
    except OSError as error:
        print(f'stewart_calibrate: cannot write {error.filename}: {error.strerror}',
              file=sys.stderr)
        return 1
    return 0


def _write_results(arguments, result, validation, values) -> None:
    """Print the report and write the calibrated parameter file and the figure."""
    print(result.report())
    if validation is not None:
        print()
        print(_validation_report(result, *validation))
    comment = (f'Calibrated by stewart_calibrate from {arguments.measurements.name}: '
               f'{int(result.inliers.sum())} poses, outliers {list(result.outliers)}.\n'
               f'RMS residual {_rms(result.residuals_before[result.inliers]) * 1e6:.1f} um '
               f'nominal, {_rms(result.residuals_after[result.inliers]) * 1e6:.2f} um '
               'calibrated.\n'
               'platform_joints are in the platform frame, as in the nominal file;\n'
               'actuator_offsets: an actuator position is its leg length minus its offset.')
    arguments.output.parent.mkdir(parents=True, exist_ok=True)
    write_parameter_file(arguments.output, calibrated_parameters(result, values), comment)
    print(f'\nwrote {arguments.output}')
    if not arguments.no_figure:
        from stewart_kinematics.tools.plots import calibration_figure
        figure = _figure_path(arguments)
        figure.parent.mkdir(parents=True, exist_ok=True)
        print(f'wrote {calibration_figure(figure, result)}')


def _propose(arguments, nominal) -> int:
    selection = measurement_poses(
        nominal, arguments.propose, position_range=arguments.position_range,
        angle_range=np.radians(arguments.angle_range_deg))
    lines = [f'# {arguments.propose} measurement poses proposed by stewart_calibrate; measure '
             'each, then fill in X..gamma as measured and the actuator positions',
             ','.join(MEASUREMENT_COLUMNS)]
    lines += [','.join(repr(float(value)) for value in pose) + ',' * 6
              for pose in selection.poses]
    arguments.poses_out.parent.mkdir(parents=True, exist_ok=True)
    arguments.poses_out.write_text('\n'.join(lines) + '\n', encoding='utf-8')
    print(f'proposed {arguments.propose} poses: smallest singular value '
          f'{selection.smallest_singular_value:.3g} ({selection.improvement:.2f}x the median of '
          f'random poses, {selection.random_smallest_singular_value:.3g}); scaled condition '
          f'number {selection.condition_number:.3g} (random: '
          f'{selection.random_condition_number:.3g})')
    print(f'wrote {arguments.poses_out}')
    return 0


def _validation_report(result, poses, readings) -> str:
    nominal = predict_actuator_positions(result.nominal, result.nominal_offsets, poses) - readings
    calibrated = predict_actuator_positions(
        result.geometry, result.actuator_offsets, poses) - readings
    return '\n'.join([
        f'validation on {poses.shape[0]} further poses (predicted - measured), micrometres',
        f'  nominal:    RMS {_rms(nominal) * 1e6:10.1f}   worst '
        f'{np.max(np.abs(nominal)) * 1e6:10.1f}',
        f'  calibrated: RMS {_rms(calibrated) * 1e6:10.2f}   worst '
        f'{np.max(np.abs(calibrated)) * 1e6:10.2f}'])


def _rms(values) -> float:
    return float(np.sqrt(np.mean(np.square(values))))


if __name__ == '__main__':
    sys.exit(main())
