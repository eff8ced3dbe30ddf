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
stewart_payload: identify the payload's mass and centre of mass from leg forces measured at rest.

Reads a CSV (or YAML) file of static poses (or leg lengths) and the six leg forces measured at
each, and the platform's parameter files (its geometry, and the platform's and legs' masses,
which are subtracted); prints the payload's mass and centre of mass with their standard
deviations and any warning, and writes a parameter file with ``payload_mass`` and
``payload_center_of_mass`` that the nodes load after the others. With ``--propose N`` it
instead writes N poses to measure, tilted in every direction as far as the limits allow.

A file that cannot be read (a parameter file, or a measurement file: a missing column, a row
of the wrong length, a value that is not a finite number) exits 2 with one line naming the
file, its line and the column.
"""

import argparse
import math
from pathlib import Path
import sys

from stewart_kinematics.analysis.calibration_files import write_parameter_file
from stewart_kinematics.analysis.payload_identification import (
    DEFAULT_MAX_CONDITION,
    FORCE_COLUMNS,
    identify_payload,
    load_force_measurements,
    MIN_POSES,
    payload_poses,
    PayloadIdentificationError,
    POSE_COLUMNS,
)
from stewart_kinematics.parameters import (
    geometry_from_parameters,
    ParameterFileError,
    read_parameter_files,
)
from stewart_kinematics.tools.cli_arguments import (
    check_output_paths,
    integer_at_least,
    number_in,
    refuse_parameter_file,
)

PROG = 'stewart_payload'
#: Exit codes: identified, refused (the reason printed), a bad argument or file.
EXIT_IDENTIFIED, EXIT_REFUSED, EXIT_BAD_INPUT = 0, 1, 2

EPILOG = """\
measurement CSV: a header row naming the columns, then one row per static pose, each with as
many fields as the header; other columns are ignored, lines starting with # are comments. SI
units:
  X, Y, Z              position of the platform frame's origin in the base frame, m
  alpha, beta, gamma   orientation, rad (R = Rz(gamma) Ry(beta) Rx(alpha))
  (or leg_length_1..6  leg lengths between the joints' centres, m, instead of the pose)
  force_1..6           the legs' axial forces measured there, N, positive pushing
A .yaml or .yml file instead holds 'measurements:', a list of mappings with 'pose' (or
'leg_lengths') and 'forces', six numbers each, in the same units.
The platform's and the legs' masses and gravity come from the parameter files (platform_mass,
leg_lower_mass, ...; every mass 0 when absent); their forces are subtracted. The payload given
there is the prior: a component of the centre the poses cannot determine keeps its value.

exit codes: 0 identified (warnings, if any, printed); 1 refused (too few poses, no payload to
be seen: the reason is printed); 2 a bad option, or a file that cannot be read (one line,
naming the file, its line and the column).
"""


def parse_arguments(argv):
    """Return the command-line options."""
    parser = argparse.ArgumentParser(
        prog=PROG, description=__doc__.strip(), epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('measurements', nargs='?', type=Path,
                        help='CSV (or YAML) of static poses and leg forces (below)')
    parser.add_argument('--params-file', dest='params_files', action='append', type=Path,
                        required=True,
                        help='parameter file with the geometry and masses (repeat to layer '
                             'files, as for the nodes)')
    parser.add_argument('--output', type=Path, default=Path('payload.yaml'),
                        help='parameter file to write (default: %(default)s)')
    parser.add_argument('--max-condition', type=number_in(1.0, 1e12, low_inclusive=False),
                        default=DEFAULT_MAX_CONDITION,
                        help='largest scaled condition number of the fit: a combination '
                             'determined worse is kept from the parameter files and named; '
                             'in (1, 1e12] (default: %(default)g)')
    parser.add_argument('--propose', type=integer_at_least(MIN_POSES), metavar='N',
                        default=None,
                        help='instead of identifying, write N poses to measure to '
                             '--poses-out, tilted in every direction within the limits')
    parser.add_argument('--poses-out', type=Path, default=Path('payload_poses.csv'),
                        help='CSV for --propose (default: %(default)s)')
    parser.add_argument('--margin', type=number_in(0.0, 1.0, low_inclusive=False),
                        default=0.9,
                        help='--propose: the fraction of the largest tilt the limits allow '
                             '(default: %(default)s)')
    arguments = parser.parse_args(argv)
    if arguments.propose is None and arguments.measurements is None:
        parser.error('give the measurement CSV, or --propose N')
    if arguments.propose is not None and arguments.propose > 10_000:
        parser.error(f'argument --propose: at most 10000 poses, got {arguments.propose}')
    output = ('--poses-out', arguments.poses_out) if arguments.propose is not None else (
        '--output', arguments.output)
    check_output_paths(parser, [output + (False,)])
    return arguments


def main(argv=None) -> int:
    """Run stewart_payload; return the exit code."""
    arguments = parse_arguments(argv)
    try:
        values = read_parameter_files(arguments.params_files)
    except ParameterFileError as error:
        return refuse_parameter_file(PROG, error)
    try:
        geometry = geometry_from_parameters(values)
    except ValueError as error:
        return _fail(f'error: argument --params-file: {error}', EXIT_BAD_INPUT)
    if arguments.propose is not None:
        return _propose(arguments, geometry)
    try:
        poses, forces = load_force_measurements(arguments.measurements, geometry)
    except ValueError as error:
        return _fail(f'error: {error}', EXIT_BAD_INPUT)
    try:
        estimate = identify_payload(geometry, poses, forces,
                                    max_condition=arguments.max_condition)
    except PayloadIdentificationError as error:
        return _fail(f'cannot identify the payload: {error}', EXIT_REFUSED)
    except ValueError as error:
        return _fail(f'error: {arguments.measurements}: {error}', EXIT_BAD_INPUT)
    print(estimate.report())
    comment = (f'Payload identified by {PROG} from {arguments.measurements.name}: '
               f'{poses.shape[0]} poses, noise {estimate.noise:.3g} N.\n'
               f'payload_mass {estimate.mass:.4f} +- {estimate.mass_deviation:.4f} kg; '
               'payload_center_of_mass in the platform frame, m.\n'
               "Give this file after the platform's parameter files.")
    if estimate.warnings:
        comment += '\nWarnings: ' + '; '.join(finding.code for finding in estimate.warnings)
    try:
        arguments.output.parent.mkdir(parents=True, exist_ok=True)
        write_parameter_file(arguments.output, estimate.parameters(), comment)
    except OSError as error:
        return _fail(f'cannot write {arguments.output}: {error.strerror}', EXIT_REFUSED)
    print(f'\nwrote {arguments.output}')
    return EXIT_IDENTIFIED


def _propose(arguments, geometry) -> int:
    """Write the proposed poses, with empty force columns to fill in."""
    try:
        poses = payload_poses(geometry, arguments.propose, margin=arguments.margin)
    except ValueError as error:
        return _fail(f'cannot propose poses: {error}', EXIT_REFUSED)
    lines = [f'# {arguments.propose} static poses proposed by {PROG}: hold each, then fill in '
             'the six leg forces (N, positive pushing)', ','.join(POSE_COLUMNS + FORCE_COLUMNS)]
    lines += [','.join(repr(float(value)) for value in pose) + ',' * len(FORCE_COLUMNS)
              for pose in poses]
    try:
        arguments.poses_out.parent.mkdir(parents=True, exist_ok=True)
        arguments.poses_out.write_text('\n'.join(lines) + '\n', encoding='utf-8')
    except OSError as error:
        return _fail(f'cannot write {arguments.poses_out}: {error.strerror}', EXIT_REFUSED)
    tilts = [math.degrees(math.hypot(alpha, beta)) for alpha, beta in poses[:, 3:5]]
    print(f'proposed {arguments.propose} poses at Z = {poses[0, 2]:.4f} m, tilted '
          f'{min(tilts):.1f} to {max(tilts):.1f} degrees in every direction')
    print(f'wrote {arguments.poses_out}')
    return EXIT_IDENTIFIED


def _fail(message: str, code: int) -> int:
    """Print one line on stderr; return the exit code."""
    print(f'{PROG}: {message}', file=sys.stderr)
    return code


if __name__ == '__main__':
    sys.exit(main())
