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


r"""
``stewart_geometry``: check a platform's parameter files and report what the geometry can do.

Reads the files as the nodes do and prints the design (6-6, 6-3, 3-3, which legs share which
joint), the home leg lengths, the condition number at home and the margin to each limit, the
travel along each axis from home, the workspace volume at the home orientation (coarse, fast),
the assembly modes of the home leg lengths and the nearest other one, and warnings::

    stewart_geometry --params-file config/platform_6_3.yaml
    stewart_geometry --params-file config/paper_platform.yaml \\
        --params-file config/example_limits.yaml --json

Exit codes: 0 when the nodes take the geometry (warnings are printed; with ``--strict`` a
warning exits 3); 1 when they refuse it (the home pose breaks a limit: the report says which;
or the joints make no platform, in one line); 2 for a bad option or a parameter file that
cannot be read (one line, ``file:line: what is wrong``).
"""

import argparse
import json
from pathlib import Path
import sys

from stewart_kinematics.tools.cli_arguments import number_in, refuse_parameter_file

#: Exit code of a geometry the nodes refuse.
EXIT_REFUSED = 1
#: Exit code of a usable geometry with warnings, under ``--strict``.
EXIT_WARNINGS = 3
#: Default and allowed grid steps of the workspace volume, millimetres.
DEFAULT_VOLUME_RESOLUTION_MM = 20.0
VOLUME_RESOLUTION_RANGE_MM = (5.0, 200.0)

PROG = 'stewart_geometry'


def parse_arguments(argv):
    """Return the command-line options (argparse exits 2 with one line for a bad one)."""
    parser = argparse.ArgumentParser(prog=PROG,
                                     description=__doc__.split('\n\n')[1].split('::')[0])
    parser.add_argument('--params-file', dest='params_files', action='append', required=True,
                        type=Path, help='ROS 2 parameter file with the geometry and limits; '
                                        'repeat it to layer files, as the nodes take them')
    parser.add_argument('--node-name', default=None,
                        help="also apply this node's sections of the files (default: /** only)")
    parser.add_argument('--volume-resolution-mm', type=number_in(*VOLUME_RESOLUTION_RANGE_MM),
                        default=DEFAULT_VOLUME_RESOLUTION_MM,
                        help='grid step of the workspace volume, %g to %g (default %g)' % (
                            *VOLUME_RESOLUTION_RANGE_MM, DEFAULT_VOLUME_RESOLUTION_MM))
    parser.add_argument('--json', action='store_true',
                        help='print the report as JSON (SI units) instead of text')
    parser.add_argument('--strict', action='store_true',
                        help=f'exit {EXIT_WARNINGS} when the report has a warning')
    return parser.parse_args(argv)


def main(argv=None) -> int:
    """Print the report; return the exit code (see the module's documentation)."""
    options = parse_arguments(argv)
    from stewart_kinematics.analysis.capabilities import parameters_report
    from stewart_kinematics.parameters import ParameterFileError, read_parameter_files
    files = ', '.join(map(str, options.params_files))
    try:
        values = read_parameter_files(options.params_files, options.node_name)
    except ParameterFileError as error:
        return refuse_parameter_file(PROG, error)
    try:
        report = parameters_report(values,
                                   volume_resolution=options.volume_resolution_mm * 1e-3)
    except ValueError as error:
        print(f'{PROG}: {files}: {error}', file=sys.stderr)
        return EXIT_REFUSED
    if options.json:
        print(json.dumps({'parameter_files': [str(path) for path in options.params_files],
                          **report.as_dict()}, indent=2))
    else:
        print(f'Parameter files: {files}')
        print(report.text())
    if not report.usable:
        return EXIT_REFUSED
    return EXIT_WARNINGS if options.strict and report.warnings else 0


if __name__ == '__main__':
    sys.exit(main())
