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
``stewart_workspace``: what a platform can reach, from the nodes' own parameter files.

Prints the masses and force limits it works with, the travel ranges from the home pose (or
``--pose``) and the volume of the constant-orientation workspace, and writes to ``--output``:
``workspace.yaml`` (the numbers), ``workspace_slices.png`` (XY, XZ and YZ slices through the
pose, boundary coloured by the limit met), ``orientation_workspace.png`` (reachable alpha and
beta at the position, for three gamma values) and ``dexterity.png`` (condition number over the
slices)::

    stewart_workspace --params-file config/paper_platform.yaml \\
        --params-file config/example_limits.yaml --output workspace_output

A parameter file that cannot be read (not YAML, an alias, nested too deep, a value of the
wrong type or null) exits 2 with one line, ``file:line: what is wrong``; a geometry that cannot
be used exits 1, saying why.
"""

import argparse
import math
from pathlib import Path
import sys
import time

import numpy as np

from stewart_kinematics.tools.cli_arguments import (
    check_output_paths,
    number,
    number_in,
    refuse_parameter_file,
)
import yaml

#: Slice and volume resolutions by default: millimetres, degrees.
DEFAULT_SLICE_RESOLUTION_MM = 2.0
DEFAULT_VOLUME_RESOLUTION_MM = 10.0
DEFAULT_ANGLE_RESOLUTION_DEG = 0.25
#: The resolutions allowed, (finest, coarsest): a finer grid would hold billions of points.
SLICE_RESOLUTION_RANGE_MM = (0.1, 100.0)
VOLUME_RESOLUTION_RANGE_MM = (1.0, 200.0)
ANGLE_RESOLUTION_RANGE_DEG = (0.01, 10.0)
#: gamma of the orientation workspace figure, as fractions of the positive gamma range.
GAMMA_FRACTIONS = (0.0, 0.5, 0.9)


class ProgressBar:
    """
    A plain text progress bar on stderr: ``[#####-----] 3/6 volume``.

    Drawn in place with a carriage return on a terminal, one line per step otherwise (a log
    file, a test capturing the output).
    """

    def __init__(self, total, stream=None, width=30):
        self.total, self.done, self.width = total, 0, width
        self.stream = sys.stderr if stream is None else stream
        self.started = time.monotonic()
        self.interactive = hasattr(self.stream, 'isatty') and self.stream.isatty()

    def step(self, label):
        """Announce the step about to run."""
        filled = self.width * self.done // self.total
        line = (f'[{"#" * filled}{"-" * (self.width - filled)}] {self.done}/{self.total} '
                f'{label} ({time.monotonic() - self.started:.1f} s)')
        self.stream.write(f'\r{line:<79}' if self.interactive else line + '\n')
        self.stream.flush()
        self.done += 1

    def close(self):
        """Draw the full bar and end the line."""
        self.done = self.total
        self.step('done')
        if self.interactive:
            self.stream.write('\n')


def parse_arguments(argv):
    """Return the command-line options."""
    parser = argparse.ArgumentParser(
        prog='stewart_workspace', description=__doc__.split('\n\n')[1].split('::')[0])
    parser.add_argument('--params-file', dest='params_files', action='append', required=True,
                        type=Path, help='ROS 2 parameter file with the geometry and limits; '
                                        'repeat it to layer files, as the nodes take them')
    parser.add_argument('--node-name', default=None,
                        help="also apply this node's sections of the files (default: /** only)")
    parser.add_argument('--output', type=Path, default=Path('workspace_output'),
                        help='folder for workspace.yaml and the figures '
                             '(default workspace_output/)')
    parser.add_argument('--pose', type=number, nargs=6, default=None,
                        metavar=('X', 'Y', 'Z', 'ALPHA', 'BETA', 'GAMMA'),
                        help='start pose in metres and degrees (default: the home pose)')
    parser.add_argument('--slice-resolution-mm', type=number_in(*SLICE_RESOLUTION_RANGE_MM),
                        default=DEFAULT_SLICE_RESOLUTION_MM,
                        help='grid step of the slices, %s to %s (default %s)' % (
                            *SLICE_RESOLUTION_RANGE_MM, DEFAULT_SLICE_RESOLUTION_MM))
    parser.add_argument('--volume-resolution-mm',
                        type=number_in(*VOLUME_RESOLUTION_RANGE_MM),
                        default=DEFAULT_VOLUME_RESOLUTION_MM,
                        help='grid step of the volume, %s to %s (default %s)' % (
                            *VOLUME_RESOLUTION_RANGE_MM, DEFAULT_VOLUME_RESOLUTION_MM))
    parser.add_argument('--angle-resolution-deg',
                        type=number_in(*ANGLE_RESOLUTION_RANGE_DEG),
                        default=DEFAULT_ANGLE_RESOLUTION_DEG,
                        help='grid step of the orientation workspace, %s to %s (default %s)'
                        % (*ANGLE_RESOLUTION_RANGE_DEG, DEFAULT_ANGLE_RESOLUTION_DEG))
    parser.add_argument('--no-figures', action='store_true', help='write the YAML only')
    options = parser.parse_args(argv)
    if options.pose is not None and not all(-180.0 <= angle <= 180.0
                                            for angle in options.pose[3:]):
        parser.error(f'argument --pose: the angles must be in [-180, 180] degrees, got '
                     f'{options.pose[3:]}')
    check_output_paths(parser, [('--output', options.output, True)])
    return options


def main(argv=None) -> int:
    """Run the report; return 0, or 1 with a message when the geometry cannot be used."""
    options = parse_arguments(argv)
    from stewart_kinematics.parameters import load_geometry, ParameterFileError
    try:
        geometry = load_geometry(options.params_files, options.node_name)
        options.output.mkdir(parents=True, exist_ok=True)
        report = workspace_report(geometry, options)
        report['parameter_files'] = [str(path) for path in options.params_files]
        path = options.output / 'workspace.yaml'
        with open(path, 'w', encoding='utf-8') as stream:
            yaml.safe_dump(report, stream, sort_keys=False, default_flow_style=None)
    except ParameterFileError as error:
        return refuse_parameter_file('stewart_workspace', error)
    except ValueError as error:
        print(f'stewart_workspace: {error}', file=sys.stderr)
        return 1
    except OSError as error:
        print(f'stewart_workspace: cannot write {error.filename or options.output}: '
              f'{error.strerror}', file=sys.stderr)
        return 1
    print(f'numbers written to {path}')
    return 0


def workspace_report(geometry, options) -> dict:
    """Compute everything, print the tables, write the figures; return the numbers."""
    from stewart_kinematics.analysis import workspace
    pose = np.array(geometry.home_pose, dtype=float)
    if options.pose is not None:
        pose = np.array(options.pose[:3] + [math.radians(angle) for angle in options.pose[3:]])
    slice_step = options.slice_resolution_mm * 1e-3
    angle_step = math.radians(options.angle_resolution_deg)
    progress = ProgressBar(7 if options.no_figures else 8)
    timings = {}

    def timed(name, label, function, *args, **kwargs):
        progress.step(label)
        start = time.perf_counter()
        result = function(*args, **kwargs)
        timings[name] = round(time.perf_counter() - start, 3)
        return result

    ranges = timed('travel_ranges', 'travel ranges', workspace.travel_ranges, geometry, pose)
    volume = timed('volume', 'volume', workspace.workspace_volume, geometry, pose[3:],
                   position=pose[:3], resolution=options.volume_resolution_mm * 1e-3)
    slices = [timed(f'slice_{plane}', f'{plane} slice', workspace.workspace_slice, geometry,
                    plane, pose, resolution=slice_step) for plane in ('XY', 'XZ', 'YZ')]
    gamma_range = ranges.axes[5].positive
    gammas = [pose[5] + fraction * gamma_range for fraction in GAMMA_FRACTIONS]
    orientation = timed('orientation_workspace', 'orientation workspace',
                        workspace.orientation_workspace, geometry, pose[:3], gammas,
                        resolution=angle_step)
    figures = []
    if not options.no_figures:
        from stewart_kinematics.tools.workspace_plots import write_workspace_figures
        figures = timed('figures', 'figures', write_workspace_figures, options.output, slices,
                        orientation)
    progress.close()

    masses = masses_numbers(geometry)
    print(masses_text(masses))
    print('Travel ranges from the pose '
          + ', '.join(f'{name} {value:.6g}' for name, value in zip(
              ('X [m]', 'Y [m]', 'Z [m]', 'alpha [rad]', 'beta [rad]', 'gamma [rad]'), pose)))
    print(ranges.table())
    box = volume.bounding_box * 1e3
    unbounded = '' if volume.bounded else ', UNBOUNDED: the part within the span'
    print(f'\nConstant-orientation workspace at alpha, beta, gamma = '
          f'{", ".join(f"{math.degrees(a):.4g}" for a in volume.orientation)} deg: '
          f'{volume.volume:.6f} m^3 ({volume.volume * 1e3:.3f} litres), grid '
          f'{volume.resolution * 1e3:g} mm{unbounded}')
    print(f'bounding box: X {box[0, 0]:.1f} .. {box[1, 0]:.1f} mm, '
          f'Y {box[0, 1]:.1f} .. {box[1, 1]:.1f} mm, Z {box[0, 2]:.1f} .. {box[1, 2]:.1f} mm')
    for path in figures:
        print(f'figure written to {path}')
    return {
        'masses': masses,
        'start_pose': _floats(pose),
        'travel_ranges': {
            travel.axis: {'unit': travel.unit, 'negative': float(travel.negative),
                          'positive': float(travel.positive),
                          'negative_limit': travel.negative_limit,
                          'negative_leg': travel.negative_leg,
                          'positive_limit': travel.positive_limit,
                          'positive_leg': travel.positive_leg}
            for travel in ranges.axes},
        'travel_range_tolerance': {'m': ranges.tolerance[0], 'rad': ranges.tolerance[1]},
        'volume': {'orientation_rad': _floats(volume.orientation),
                   'volume_m3': float(volume.volume),
                   'bounding_box_m': {'min': _floats(volume.bounding_box[0]),
                                      'max': _floats(volume.bounding_box[1])},
                   'resolution_m': float(volume.resolution), 'bounded': bool(volume.bounded),
                   'boundary_points': int(len(volume.boundary)),
                   'boundary_points_by_limit': _by_limit(volume.boundary_limit)},
        'slices': [_slice_numbers(result) for result in slices],
        'orientation_workspace': [_slice_numbers(result) for result in orientation],
        'seconds': timings,
    }


def masses_numbers(geometry) -> dict:
    """
    Return the masses the workspace is computed with and the force limits, for the report.

    The leg force limit judges each pose with its static forces, from these masses: a heavy
    payload shrinks the workspace; with every mass 0 the limit is not checked.

    :param geometry: a :class:`stewart_kinematics.Geometry`.
    :returns: ``masses_set``; the payload's and the platform's ``mass_kg`` and
        ``center_of_mass_m`` (platform frame), the legs' ``lower_mass_kg`` and
        ``upper_mass_kg``, ``gravity_m_s2`` (base frame); ``force_limits_n`` with
        ``leg_force_min`` and ``leg_force_max`` in newtons, ``None`` where not set, and
        ``force_limits_checked``.
    """
    from stewart_kinematics.dynamics.inverse_dynamics import masses_of
    from stewart_kinematics.limits.settings import limits_of
    masses = masses_of(geometry)
    limits = limits_of(geometry)
    force_limits = {name: (float(getattr(limits, name)) if limits.is_set(name) else None)
                    for name in ('leg_force_min', 'leg_force_max')}
    return {
        'masses_set': not masses.massless,
        'payload': {'mass_kg': float(masses.payload.mass),
                    'center_of_mass_m': _floats(masses.payload.center_of_mass)},
        'platform': {'mass_kg': float(masses.platform.mass),
                     'center_of_mass_m': _floats(masses.platform.center_of_mass)},
        'legs': {'lower_mass_kg': float(masses.leg_lower.mass),
                 'upper_mass_kg': float(masses.leg_upper.mass)},
        'gravity_m_s2': _floats(masses.gravity),
        'force_limits_n': force_limits,
        'force_limits_checked': bool(not masses.massless and any(
            value is not None for value in force_limits.values())),
    }


def masses_text(masses: dict) -> str:
    """Return the lines of the report that say which masses and force limits are used."""
    limits = masses['force_limits_n']
    shown = ', '.join(f'{name} {value:g} N' for name, value in limits.items()
                      if value is not None) or 'none set'
    if not masses['masses_set']:
        return ('Masses: none set (every mass 0): the leg forces are 0, the force limits '
                f'({shown}) are not checked and change nothing')
    payload, platform, legs = masses['payload'], masses['platform'], masses['legs']
    centre = ', '.join(f'{value:g}' for value in payload['center_of_mass_m'])
    return '\n'.join([
        f'Payload: {payload["mass_kg"]:g} kg, centre of mass [{centre}] m (platform frame); '
        f'platform {platform["mass_kg"]:g} kg; each leg {legs["lower_mass_kg"]:g} kg lower, '
        f'{legs["upper_mass_kg"]:g} kg upper',
        f'Force limits: {shown}' + (' (each pose judged with its static leg forces)'
                                    if masses['force_limits_checked'] else
                                    ': the forces limit nothing')])


def _slice_numbers(result):
    condition = result.condition[np.isfinite(result.condition)]
    return {
        'plane': '-'.join(result.labels), 'pose': _floats(result.pose),
        'area': float(result.area),
        'area_unit': {2: 'm^2', 1: 'm rad', 0: 'rad^2'}[sum(axis < 3 for axis in result.axes)],
        'resolution': _floats([result.u[1] - result.u[0], result.v[1] - result.v[0]]),
        'bounded': bool(result.bounded),
        'boundary_points_by_limit': _by_limit(result.boundary_limit),
        'condition_number': ({'min': float(condition.min()),
                              'median': float(np.median(condition)),
                              'max': float(condition.max())} if condition.size else None),
    }


def _by_limit(limits_met):
    from stewart_kinematics.limits.kinds import pose_limit_names
    names = pose_limit_names()
    counts = np.bincount(limits_met[limits_met >= 0], minlength=len(names))
    return {name: int(count) for name, count in zip(names, counts) if count}


def _floats(values):
    return [float(value) for value in values]


if __name__ == '__main__':
    sys.exit(main())
