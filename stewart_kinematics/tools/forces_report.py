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
``stewart_forces``: size the actuators for a motion: per leg peak push, pull, RMS, speed, power.

Plays a motion on the platform given by the nodes' parameter files (geometry, masses, limits)
and prints, per leg, the peak push and pull (N), the RMS force (N, time-weighted), the peak
speed (m/s) and the peak mechanical power ``|f dL/dt|`` (W, delivered or absorbed), each peak
with its time; ``--csv`` and ``--json`` write them, ``--figure`` draws each leg's force
against its speed with the actuator's envelope::

    stewart_forces --trajectory config/table3_ramp.yaml --duration 2 \
        --params-file config/paper_platform.yaml --params-file config/example_limits.yaml \
        --params-file config/example_masses.yaml --figure forces.png

The motion is one of:

- ``--trajectory FILE``: trajectory_node's parameter file with a ramp (the paper's Table 3
  layout: start, step and end per axis; config/table3_ramp.yaml), its rows spread evenly over
  ``--duration`` seconds (default: the file's ``duration`` in ``interpolate`` mode, its rows
  times ``row_period`` in ``table`` mode);
- ``--poses FILE``: a timed pose list, CSV with the header ``time,X,Y,Z,alpha,beta,gamma``
  (seconds, metres, radians; or ``alpha_deg,beta_deg,gamma_deg`` in degrees), times increasing;
- ``--scenario NAME``: a drive of stewart_cueing, played through the motion cueing (the
  ``motion_cueing_node`` sections of the parameter files apply).

A trajectory or a pose list is played as trajectory_node plays timed waypoints: the package's
trajectory through them (cubic, C1, velocities estimated from the neighbours, at rest at the
first and last), sampled at ``--rate`` and on both sides of every waypoint (the acceleration
jumps there); the twists and accelerations are the trajectory's own derivatives, exact. With
``--retime``, the waypoints are played as trajectory_node retimes them instead: as fast as
``leg_velocity_max`` and ``leg_acceleration_max`` allow. The
poses of a cueing scenario are its replay's, one per input sample; their twists and
accelerations are the exact derivatives of the package's C2 trajectory through them (quintic,
derivatives from the polynomial through the 5 samples around each).

Exit codes: 0 done; 2 a bad option, or an input, a parameter file or a motion that cannot be
used (one line saying what is wrong).
"""

import argparse
import csv
import json
import math
from pathlib import Path
import sys

import numpy as np

from stewart_kinematics.tools.cli_arguments import (
    check_output_paths,
    existing_file,
    EXIT_USAGE,
    number_in,
    refuse_parameter_file,
)
from stewart_kinematics.tools.csv_input import read_number_table

PROG = 'stewart_forces'
#: Default sampling rate of a trajectory or a pose list, hertz.
DEFAULT_RATE = 100.0
#: The pose list's columns: angles in radians, or in degrees.
POSE_COLUMNS = ('time', 'X', 'Y', 'Z', 'alpha', 'beta', 'gamma')
POSE_COLUMNS_DEG = ('time', 'X', 'Y', 'Z', 'alpha_deg', 'beta_deg', 'gamma_deg')
#: Columns of the CSV output, one row per leg (the fields of LegDemand).
CSV_COLUMNS = ('leg', 'peak_push', 'peak_push_time', 'peak_pull', 'peak_pull_time',
               'rms_force', 'peak_speed', 'peak_speed_time', 'peak_power', 'peak_power_time',
               'peak_power_delivered')
#: How the table says the sign of the peak power.
POWER_WORDS = {True: 'delivered', False: 'absorbed', None: ''}
#: The parameters of a ramp file: at least one must be in it.
RAMP_TABLE = ('position_start', 'position_step', 'position_end', 'orientation_start_deg',
              'orientation_step_deg', 'orientation_end_deg')
#: Most rows of a pose list, and its largest size in bytes (read whole before any check).
MAX_POSES = 100_000
MAX_POSE_FILE_BYTES = 32 * 1024 * 1024


class InputError(ValueError):
    """An input that cannot be used: the message names it and says why."""


def build_parser() -> argparse.ArgumentParser:
    """Return the command line's parser."""
    from stewart_kinematics.cueing.scenarios import SCENARIO_NAMES
    parser = argparse.ArgumentParser(
        prog=PROG, description=__doc__.split('\n\n')[1].replace('\n', ' '),
        formatter_class=argparse.RawDescriptionHelpFormatter)
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument('--trajectory', type=existing_file,
                        help="trajectory_node's parameter file with a ramp (Table 3 layout)")
    source.add_argument('--poses', type=existing_file,
                        help='CSV of timed poses: ' + ','.join(POSE_COLUMNS)
                             + ' (radians) or ' + ','.join(POSE_COLUMNS_DEG))
    source.add_argument('--scenario', choices=SCENARIO_NAMES,
                        help='a drive of stewart_cueing, played through the motion cueing')
    parser.add_argument('--params-file', dest='params_files', action='append', required=True,
                        type=existing_file,
                        help='ROS 2 parameter file (geometry, masses, limits); repeat to '
                             'layer files, as the nodes take them')
    parser.add_argument('--duration', type=number_in(0.0, 1e6, low_inclusive=False),
                        help='play the --trajectory ramp over this many seconds')
    parser.add_argument('--retime', action='store_true',
                        help='play the --trajectory or --poses waypoints as fast as '
                             'leg_velocity_max and leg_acceleration_max allow (as '
                             'trajectory_node retimes them), not on their own times')
    parser.add_argument('--rate', type=number_in(0.0, 10000.0, low_inclusive=False),
                        default=DEFAULT_RATE,
                        help=f'samples per second (default {DEFAULT_RATE:g}); a --scenario '
                             'is generated at this rate')
    parser.add_argument('--peak-power', type=number_in(0.0, 1e9, low_inclusive=False),
                        help="the actuator's peak mechanical power, W: drawn on the figure "
                             '(|f v| = P) and checked')
    parser.add_argument('--csv', type=Path, help='write the table to this CSV file')
    parser.add_argument('--json', type=Path, help='write the results to this JSON file')
    parser.add_argument('--figure', type=Path,
                        help='draw force against speed per leg, with the envelope, to this PNG')
    return parser


def read_poses(path: Path):
    """
    Read a pose list: ``(times, poses)``, seconds and ``[X, Y, Z, alpha, beta, gamma]`` (m, rad).

    :raises InputError: naming the file, the line and the column.
    """
    try:
        header, rows = read_number_table(path, [POSE_COLUMNS, POSE_COLUMNS_DEG], what='poses',
                                         max_rows=MAX_POSES, max_bytes=MAX_POSE_FILE_BYTES)
    except ValueError as error:
        raise InputError(str(error)) from None
    if len(rows) < 2:
        raise InputError(f'{path}: needs at least 2 poses, got {len(rows)}')
    data = np.array(rows)
    if header == POSE_COLUMNS_DEG:
        data[:, 4:] = np.radians(data[:, 4:])
    return data[:, 0], data[:, 1:]


def ramp_motion(path: Path, duration):
    """
    Read a ramp file: ``(waypoint times, rows, duration)``, rows spread evenly over it.

    :raises ParameterFileError: if the file cannot be read as a parameter file.
    :raises InputError: for a ramp that is not allowed.
    """
    from stewart_kinematics.motion.ramp import Ramp
    from stewart_kinematics.parameters import RampSettings, read_parameter_file
    values = read_parameter_file(path, 'trajectory_node')
    if not any(name in values for name in RAMP_TABLE):
        raise InputError(f'{path}: no ramp in it: none of {", ".join(RAMP_TABLE)} in its '
                         'trajectory_node or /** section')
    try:
        settings = RampSettings.from_values(values)
        ramp = Ramp.from_settings(settings)
    except ValueError as error:
        raise InputError(f'{path}: {error}') from None
    if ramp.step_count == 0:
        raise InputError(f'{path}: the ramp has one row only: no motion to size')
    if duration is None:
        duration = (settings.duration if settings.mode == 'interpolate'
                    else ramp.step_count * settings.row_period)
    return np.linspace(0.0, duration, ramp.step_count + 1), ramp.rows, duration


def motion(options, values):
    """
    Return ``(geometry, trajectory, times, description)`` of the motion the options give.

    :raises InputError: for an input or parameters that cannot be used.
    """
    from stewart_kinematics.dynamics.sizing import sample_times
    from stewart_kinematics.motion.pose_trajectory import MAX_WAYPOINTS, PoseTrajectory
    from stewart_kinematics.parameters import geometry_from_parameters
    if options.scenario is not None:
        from stewart_kinematics.cueing import MotionCueing, replay
        from stewart_kinematics.cueing.scenarios import scenario
        try:
            cueing = MotionCueing.from_parameters(values)
        except ValueError as error:
            raise InputError(f'the parameters: {error}') from None
        drive = scenario(options.scenario, options.rate)
        if drive.times.size > MAX_WAYPOINTS:
            raise InputError(f'scenario {options.scenario} at {options.rate:g} Hz has '
                             f'{drive.times.size:,} samples, more than a trajectory may have '
                             f'({MAX_WAYPOINTS:,}): lower --rate')
        played = replay(cueing, drive.times, drive.specific_force, drive.angular_velocity)
        try:
            trajectory = PoseTrajectory.from_poses(played.times, played.poses,
                                                   path_estimates=True)
        except ValueError as error:
            raise InputError(f'scenario {options.scenario}: {error}') from None
        return (cueing.geometry, trajectory, played.times,
                f'scenario {options.scenario} through the motion cueing at {options.rate:g} Hz, '
                f'{played.times[-1] - played.times[0]:g} s')
    try:
        geometry = geometry_from_parameters(values)
    except ValueError as error:
        raise InputError(f'the parameters: {error}') from None
    if options.trajectory is not None:
        knots, poses, duration = ramp_motion(options.trajectory, options.duration)
        description = (f'{options.trajectory.name}: {len(knots)} rows over {duration:g} s')
        source = str(options.trajectory)
    else:
        knots, poses = read_poses(options.poses)
        description = f'{options.poses.name}: {len(knots)} poses over {knots[-1] - knots[0]:g} s'
        source = str(options.poses)
    try:
        trajectory = PoseTrajectory.from_poses(knots, poses)
        knots = trajectory.times
        if options.retime:
            trajectory, knots = retimed(trajectory, geometry, values)
            description += (f', retimed to the leg speed and acceleration limits: '
                            f'{trajectory.duration:.3f} s')
        times = sample_times(knots, options.rate)
    except ValueError as error:
        raise InputError(f'{source}: {error}') from None
    return geometry, trajectory, times, description


def retimed(trajectory, geometry, values):
    """
    Return the fastest timing within the legs' speed and acceleration, and its breakpoints.

    As trajectory_node retimes a path (:func:`~stewart_kinematics.motion.retiming.retime`):
    the waypoint poses kept, their times replaced, at rest at both ends.
    """
    from stewart_kinematics.motion.retiming import retime
    from stewart_kinematics.parameters import actuator_limits_from_settings, GeometrySettings
    limits = actuator_limits_from_settings(GeometrySettings.from_values(values))
    timed = retime(trajectory, geometry, limits)
    return timed, timed.breakpoints


def limits_of(values) -> dict:
    """Return the actuator's envelope from the parameters: force and speed limits."""
    from stewart_kinematics.parameters import GeometrySettings
    try:
        settings = GeometrySettings.from_values(values)
    except ValueError as error:
        raise InputError(f'the parameters: {error}') from None
    return {'leg_force_min': settings.leg_force_min, 'leg_force_max': settings.leg_force_max,
            'leg_velocity_max': settings.leg_velocity_max}


def exceedances(demands, limits, peak_power=None, geometry=None):
    """
    Return one sentence per peak beyond the envelope (empty: every peak within it).

    With ``geometry``, the poses are checked against its pose limits too (stroke, joints,
    singularity margin, collisions, static leg forces): one sentence with the count and the
    first sample that breaks one.
    """
    found = []
    if geometry is not None and geometry.limits is not None:
        from stewart_kinematics.limits import check_poses_array
        checks = check_poses_array(geometry, demands.poses)
        failing = np.flatnonzero(~checks.allowed)
        if failing.size:
            first = failing[0]
            found.append(f'{failing.size} of {demands.times.size} poses break the pose limits '
                         f'(a pose holds its static forces), the first at '
                         f'{demands.times[first]:.3f} s: '
                         + '; '.join(map(str, checks.violations(first))))
    for leg in demands.legs:
        if leg.peak_push > limits['leg_force_max']:
            found.append(f'leg {leg.leg}: push {leg.peak_push:.1f} N at {leg.peak_push_time:.3f}'
                         f' s beyond leg_force_max {limits["leg_force_max"]:g} N')
        if leg.peak_pull > -limits['leg_force_min']:
            found.append(f'leg {leg.leg}: pull {leg.peak_pull:.1f} N at {leg.peak_pull_time:.3f}'
                         f' s beyond leg_force_min {limits["leg_force_min"]:g} N')
        if leg.peak_speed > limits['leg_velocity_max']:
            found.append(f'leg {leg.leg}: speed {leg.peak_speed:.4f} m/s at '
                         f'{leg.peak_speed_time:.3f} s beyond leg_velocity_max '
                         f'{limits["leg_velocity_max"]:g} m/s')
        if peak_power is not None and leg.peak_power > peak_power:
            found.append(f'leg {leg.leg}: power {leg.peak_power:.1f} W at '
                         f'{leg.peak_power_time:.3f} s beyond --peak-power {peak_power:g} W')
    return found


def table(demands) -> str:
    """Return the per-leg table printed on stdout."""
    lines = [' leg | peak push N (s) | peak pull N (s) | RMS N | peak speed m/s (s) | '
             'peak power W (s)',
             '-----+-----------------+-----------------+-------+--------------------+'
             '-----------------------------']
    for leg in demands.legs:
        lines.append(
            f' {leg.leg:3d} | {_peak(leg.peak_push, leg.peak_push_time, ".1f"):>15} | '
            f'{_peak(leg.peak_pull, leg.peak_pull_time, ".1f"):>15} | {leg.rms_force:5.1f} | '
            f'{_peak(leg.peak_speed, leg.peak_speed_time, ".4f"):>18} | '
            f'{_peak(leg.peak_power, leg.peak_power_time, ".1f")} '
            f'{POWER_WORDS[leg.peak_power_delivered]}')
    return '\n'.join(lines)


def _peak(value, time, spec):
    return f'{value:{spec}} (-)' if time is None else f'{value:{spec}} ({time:.3f})'


def _plain(value):
    if isinstance(value, float):
        if math.isinf(value):
            return None
        return round(value, 9)
    return value


def write_csv(path: Path, demands) -> None:
    """Write one row per leg, the columns :data:`CSV_COLUMNS` (N, m/s, W, seconds)."""
    with open(path, 'w', encoding='utf-8', newline='') as stream:
        writer = csv.writer(stream)
        writer.writerow(CSV_COLUMNS)
        for leg in demands.legs:
            row = leg.as_dict()
            writer.writerow(['' if row[name] is None else _plain(row[name])
                             for name in CSV_COLUMNS])


def results(demands, description, limits, peak_power, found) -> dict:
    """Return what ``--json`` writes."""
    return {
        'motion': description,
        'units': {'force': 'N', 'speed': 'm/s', 'power': 'W', 'time': 's'},
        'duration': _plain(float(demands.times[-1] - demands.times[0])),
        'samples': int(demands.times.size),
        'limits': {name: _plain(float(value)) for name, value in limits.items()},
        'peak_power_limit': peak_power,
        'legs': [{name: _plain(value) for name, value in leg.as_dict().items()}
                 for leg in demands.legs],
        'beyond_limits': found,
    }


def write_figure(path: Path, demands, limits, peak_power, title) -> None:
    """Draw each leg's force against its speed, with the actuator's envelope."""
    import matplotlib
    matplotlib.use('Agg')
    from matplotlib import pyplot
    figure, axes = pyplot.subplots(2, 3, figsize=(11, 6.5), sharex=True, sharey=True)
    force_min, force_max = limits['leg_force_min'], limits['leg_force_max']
    speed_max = limits['leg_velocity_max']
    speed_span = max(float(np.abs(demands.speeds).max()), 1e-6)
    if math.isfinite(speed_max):
        speed_span = max(speed_span, speed_max)
    speed_span *= 1.15
    for leg, axis in enumerate(axes.ravel()):
        axis.plot(demands.speeds[:, leg], demands.forces[:, leg], '.', markersize=2,
                  color=f'C{leg}', label='samples')
        corners_speed = [-speed_max, speed_max] if math.isfinite(speed_max) else [
            -speed_span, speed_span]
        for force, name in ((force_min, 'leg_force_min'), (force_max, 'leg_force_max')):
            if math.isfinite(force):
                axis.plot(corners_speed, [force, force], color='k', linewidth=1)
        if math.isfinite(speed_max):
            low = force_min if math.isfinite(force_min) else demands.forces.min()
            high = force_max if math.isfinite(force_max) else demands.forces.max()
            for speed in (-speed_max, speed_max):
                axis.plot([speed, speed], [low, high], color='k', linewidth=1)
        if peak_power is not None:
            speeds = np.linspace(peak_power / 1e5, speed_span, 400)
            for sign_speed in (-1.0, 1.0):
                for sign_force in (-1.0, 1.0):
                    axis.plot(sign_speed * speeds, sign_force * peak_power / speeds,
                              color='0.4', linestyle='--', linewidth=1)
        axis.axhline(0.0, color='0.8', linewidth=0.8)
        axis.axvline(0.0, color='0.8', linewidth=0.8)
        axis.set_title(f'leg {leg + 1}', fontsize=9)
        axis.grid(alpha=0.3)
    low, high = float(demands.forces.min()), float(demands.forces.max())
    for force in (force_min, force_max):
        if math.isfinite(force):
            low, high = min(low, force), max(high, force)
    margin = 0.1 * max(high - low, 1.0)
    axes[0, 0].set_ylim(low - margin, high + margin)
    axes[0, 0].set_xlim(-speed_span, speed_span)
    for axis in axes[1]:
        axis.set_xlabel('leg speed dL/dt (m/s)')
    for axis in axes[:, 0]:
        axis.set_ylabel('leg force (N, + pushes)')
    envelope = 'envelope: leg_force_min/max, leg_velocity_max (solid)'
    if peak_power is not None:
        envelope += f', |f v| = {peak_power:g} W (dashed)'
    figure.suptitle(f'{title}\n{envelope}', fontsize=10)
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    pyplot.close(figure)


def run(options, stream=None) -> int:
    """Size the actuators for the options' motion; print and write the results; return 0."""
    stream = sys.stdout if stream is None else stream
    from stewart_kinematics.dynamics.sizing import trajectory_demands
    from stewart_kinematics.parameters import read_parameter_files
    node = 'motion_cueing_node' if options.scenario is not None else None
    values = read_parameter_files(options.params_files, node)
    limits = limits_of(values)
    geometry, trajectory, times, description = motion(options, values)
    try:
        demands = trajectory_demands(geometry, trajectory, times)
    except ValueError as error:
        raise InputError(f'{description}: {error}') from None
    found = exceedances(demands, limits, options.peak_power, geometry)
    print(f'{description}; {demands.times.size} samples', file=stream)
    print(table(demands), file=stream)
    print('power: |f dL/dt|, the mechanical power of the actuator; delivered: it drives the '
          'motion, absorbed: the load drives it back', file=stream)
    for sentence in found:
        print(f'beyond the limits: {sentence}', file=stream)
    if not found:
        print('every peak within the limits given', file=stream)
    if options.csv is not None:
        write_csv(options.csv, demands)
        print(f'wrote {options.csv}', file=stream)
    if options.json is not None:
        with open(options.json, 'w', encoding='utf-8') as out:
            json.dump(results(demands, description, limits, options.peak_power, found), out,
                      indent=2)
            out.write('\n')
        print(f'wrote {options.json}', file=stream)
    if options.figure is not None:
        write_figure(options.figure, demands, limits, options.peak_power, description)
        print(f'wrote {options.figure}', file=stream)
    return 0


def main(argv=None) -> int:
    """Run the report; see the module's documentation for the exit codes."""
    parser = build_parser()
    options = parser.parse_args(argv)
    if options.duration is not None and options.trajectory is None:
        parser.error('argument --duration: only with --trajectory (a pose list and a scenario '
                     'have their own times)')
    if options.retime and options.scenario is not None:
        parser.error('argument --retime: not with --scenario (the cueing times its own motion)')
    if options.retime and options.duration is not None:
        parser.error('argument --retime: not with --duration (retiming replaces the times)')
    check_output_paths(parser, [('--csv', options.csv, False), ('--json', options.json, False),
                                ('--figure', options.figure, False)])
    from stewart_kinematics.parameters import ParameterFileError
    try:
        for path in (options.csv, options.json, options.figure):
            if path is not None:
                path.parent.mkdir(parents=True, exist_ok=True)
        return run(options)
    except ParameterFileError as error:
        option = '--trajectory' if str(options.trajectory) in str(error) and (
            options.trajectory is not None) else '--params-file'
        return refuse_parameter_file(PROG, error, option)
    except ValueError as error:
        print(f'{PROG}: error: {error}', file=sys.stderr)
        return EXIT_USAGE
    except OSError as error:
        print(f'{PROG}: error: cannot write {error.filename}: {error.strerror}',
              file=sys.stderr)
        return EXIT_USAGE


if __name__ == '__main__':
    raise SystemExit(main())
