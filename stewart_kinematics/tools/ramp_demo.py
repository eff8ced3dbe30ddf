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
The main job: the paper's Table 3 ramp through the IK and FK nodes, over real topics.

Starts ``ik_node``, ``fk_node`` and ``trajectory_node`` as separate processes with the shipped
parameter files, as ``ros2 run`` would, records ``target_pose``, ``leg_lengths`` and
``estimated_pose``, and prints for each of the 11 table poses the input pose, the six leg
lengths, the FK pose and the round-trip error: the paper's Figures 5, 7 and 9 as tables.
The run is also recorded as a rosbag2 folder in MCAP format (with ``/diagnostics``), for
``ros2 bag``, Foxglove or PlotJuggler. Exits 0 when every pose came back within the required
error.

The parameter files are read first, as each node will get them: one that cannot be read exits
2 with one line, ``file:line: what is wrong``, before any node starts.
"""

import argparse
import os
from pathlib import Path
import sys
import time

import numpy as np

from stewart_kinematics.tools.cli_arguments import (
    check_output_paths,
    number_in,
    refuse_parameter_file,
)

#: The demo passes when every round trip is within these (metres, radians).
MAX_POSITION_ERROR = 1e-9
MAX_ORIENTATION_ERROR = 1e-9
#: The parameter files the demo starts the nodes with, from ``--config-dir``: the platform,
#: the solver (ik_node and fk_node) and the ramp (trajectory_node).
CONFIG_FILES = ('paper_platform.yaml', 'solver.yaml', 'table3_ramp.yaml')


def default_config_directory() -> Path:
    """Find the installed ``share/stewart_kinematics/config``, else the source ``config/``."""
    candidates = [Path(sys.prefix) / 'share' / 'stewart_kinematics' / 'config',
                  Path(__file__).resolve().parents[2] / 'config']
    try:
        from ament_index_python.packages import get_package_share_directory
        candidates.insert(0, Path(get_package_share_directory('stewart_kinematics')) / 'config')
    except (ImportError, LookupError, OSError, ValueError):
        # Not installed in an ament prefix (AMENT_PREFIX_PATH unset or without the package).
        pass
    for candidate in candidates:
        if (candidate / 'paper_platform.yaml').is_file():
            return candidate
    return candidates[-1]


def parse_arguments(argv):
    """Command-line options of the demo."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--config-dir', type=Path, default=None,
                        help='folder with paper_platform.yaml, solver.yaml, table3_ramp.yaml '
                             '(default: the installed share/stewart_kinematics/config)')
    parser.add_argument('--row-period', type=number_in(0.001, 60.0), default=0.2,
                        help='seconds between two table rows, 0.001 to 60 (default 0.2)')
    parser.add_argument('--timeout', type=number_in(1.0, 3600.0), default=60.0,
                        help='seconds to wait for the nodes and the ramp, 1 to 3600 '
                             '(default 60)')
    parser.add_argument('--figures', type=Path, default=Path('demo_output'),
                        help='folder for the PNG figures (default demo_output/)')
    parser.add_argument('--no-figures', action='store_true',
                        help='print the tables only')
    parser.add_argument('--bag', type=Path, default=Path('demo_output') / 'ramp_demo',
                        help='rosbag2 folder (MCAP) to record the run to, replacing an earlier '
                             'recording there (default demo_output/ramp_demo/)')
    parser.add_argument('--no-bag', action='store_true', help='record no rosbag2 folder')
    options = parser.parse_args(argv)
    check_output_paths(parser, [
        ('--figures', None if options.no_figures else options.figures, True),
        ('--bag', None if options.no_bag else options.bag, True)])
    if options.config_dir is not None and not options.config_dir.is_dir():
        parser.error(f'argument --config-dir: {options.config_dir} is not a folder')
    return options


def main(argv=None) -> int:
    """Run the demo; return 0 when all 11 poses made the round trip within 1e-9."""
    options = parse_arguments(argv)
    from stewart_kinematics.parameters import ParameterFileError
    config_directory = options.config_dir or default_config_directory()
    try:
        read_config_files(config_directory)
    except ParameterFileError as error:
        return refuse_parameter_file('ramp_demo', error, '--config-dir')
    from stewart_kinematics.tools.node_processes import isolated_ros_environment
    with isolated_ros_environment() as domain:
        print(f'ROS_DOMAIN_ID={domain}, ROS_AUTOMATIC_DISCOVERY_RANGE='
              f'{os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"]}', flush=True)
        return run_demo(config_directory,
                        options.row_period, options.timeout,
                        None if options.no_figures else options.figures,
                        None if options.no_bag else options.bag)


def read_config_files(config_directory: Path) -> None:
    """
    Read the demo's parameter files as each node will get them, before any node starts.

    A file that is missing is left to :func:`run_demo`, which says so.

    :raises ParameterFileError: naming the file and the line, if one cannot be read.
    """
    from stewart_kinematics.parameters import read_parameter_files
    platform, solver, ramp = (config_directory / name for name in CONFIG_FILES)
    for node, files in (('ik_node', [platform, solver]), ('fk_node', [platform, solver]),
                        ('trajectory_node', [platform, ramp])):
        read_parameter_files([path for path in files if path.is_file()], node)


def run_demo(config_directory: Path, row_period: float, timeout: float,
             figure_directory=None, bag_path=None) -> int:
    """
    Start the nodes, play the ramp, print the tables; see the module docstring.

    :param figure_directory: where to write the PNG figures, or ``None`` for none.
    :param bag_path: the rosbag2 folder to record to (an earlier recording there is replaced),
        or ``None`` for none.
    """
    # Imported here so that --help works without a ROS environment.
    import rclpy
    from stewart_kinematics.tools.node_processes import NodeProcess
    from stewart_kinematics.tools.ramp_recorder import RampRecorder

    platform, solver, ramp = (config_directory / name for name in CONFIG_FILES)
    for path in (platform, solver, ramp):
        if not path.is_file():
            print(f'error: parameter file {path} not found', file=sys.stderr)
            return 1
    try:
        table_rows = _ramp_rows(ramp)
    except ValueError as error:
        print(f'error: {error}', file=sys.stderr)
        return 1
    row_count = len(table_rows)
    print(f'config: {config_directory}', flush=True)

    if bag_path is not None:
        try:
            bag_path = _prepare_bag(bag_path)
        except FileExistsError as error:
            print(f'error: {error} (choose another with --bag, or --no-bag)', file=sys.stderr)
            return 1
    rclpy.init(args=[])
    recorder = RampRecorder(bag_path)
    nodes = []
    try:
        kinematics_args = ['--ros-args', '--params-file', str(platform),
                           '--params-file', str(solver)]
        nodes.append(NodeProcess('ik_node', kinematics_args))
        nodes.append(NodeProcess('fk_node', kinematics_args))
        deadline = time.monotonic() + timeout
        if not recorder.spin_until(recorder.kinematics_nodes_connected, deadline, nodes):
            return _fail('the IK and FK nodes did not connect', nodes)
        # The recorder and ik_node both subscribe target_pose: wait for both before playing.
        nodes.append(NodeProcess('trajectory_node', [
            '--ros-args', '--params-file', str(platform), '--params-file', str(ramp),
            # Named for the node: a bare -p loses to the file's trajectory_node section.
            '-p', 'trajectory_node:min_subscribers:=2',
            '-p', f'trajectory_node:row_period:={row_period}']))
        if not recorder.spin_until(lambda: recorder.complete(row_count), deadline, nodes):
            return _fail(f'the ramp did not complete: {recorder.counts()} of {row_count} '
                         'poses, lengths, estimates received', nodes)
    finally:
        exit_codes = [node.stop() for node in nodes]
        recorder.close()
        recorder.destroy_node()
        rclpy.try_shutdown()

    run = print_tables(table_rows, recorder)
    # The ramp completed, so every row has its three messages.
    errors = float(run['position_error'].max()), float(run['orientation_error'].max())
    if figure_directory is not None:
        from stewart_kinematics.tools.plots import write_figures
        run['times'] *= row_period
        paths = write_figures(figure_directory, run['times'], run['received'], run['lengths'],
                              run['estimates'], run['position_error'],
                              run['orientation_error'])
        print('\nfigures: ' + ', '.join(str(path) for path in paths))
    if recorder.bag is not None:
        print(f'\nrecorded (rosbag2, MCAP): {recorder.bag.path}: ' + ', '.join(
            f'{topic} {count}' for topic, count in recorder.bag.counts.items()) + ' messages')
    stopped = all(code == 0 for code in exit_codes)
    passed = (errors[0] <= MAX_POSITION_ERROR and errors[1] <= MAX_ORIENTATION_ERROR
              and stopped)
    print(f'\nlargest round-trip error: {errors[0]:.3g} m, {errors[1]:.3g} rad '
          f'(required: <= {MAX_POSITION_ERROR:g} m, <= {MAX_ORIENTATION_ERROR:g} rad; '
          'the paper accepted 1e-4)')
    print('nodes stopped cleanly' if stopped else f'node exit codes: {exit_codes}')
    print('PASS' if passed else 'FAIL')
    return 0 if passed else 1


def _prepare_bag(bag_path):
    """
    Make room for a new recording at ``bag_path``.

    :returns: ``bag_path``, or ``None`` when rosbags is missing (the demo then runs without a
        recording, and says so).
    :raises FileExistsError: when the path holds something other than a rosbag2 folder.
    """
    from stewart_kinematics.tools.bag_writer import remove_previous_bag
    try:
        import rosbags  # noqa: F401  (only to know whether the recording can be written)
    except ImportError:
        print('note: rosbags is not installed (pip install rosbags): no recording',
              file=sys.stderr)
        return None
    remove_previous_bag(bag_path)
    bag_path.parent.mkdir(parents=True, exist_ok=True)
    return bag_path


def _ramp_rows(ramp_file):
    from stewart_kinematics.motion.ramp import Ramp
    from stewart_kinematics.parameters import RampSettings, read_parameter_file
    return Ramp.from_settings(RampSettings.from_values(
        read_parameter_file(ramp_file, 'trajectory_node'))).rows


def _fail(reason, nodes) -> int:
    print(f'error: {reason}', file=sys.stderr)
    for node in nodes:
        print(f'--- output of {node.name} ---\n{node.output()}', file=sys.stderr)
    return 1


def print_tables(table_rows, recorder):
    """
    Print the three tables and the round-trip errors, and return the run's arrays.

    Errors are measured against the table's rows as the parameter file defines them, so that
    the conversions to and from messages on every topic count too.

    :returns: dict of ``times`` (row indices), ``received``, ``lengths``, ``estimates``,
        ``position_error`` (metres) and ``orientation_error`` (radians), one row per pose.
    """
    from stewart_kinematics.model.rotations import euler_zyx_to_matrix, rotation_angle_between
    received = np.array(recorder.target_poses)
    lengths = np.array(recorder.leg_lengths)
    estimates = np.array(recorder.estimated_poses)
    count = min(len(table_rows), len(received), len(lengths), len(estimates))
    targets, received = table_rows[:count], received[:count]
    lengths, estimates = lengths[:count], estimates[:count]

    def pose_rows(poses):
        # Adding 0.0 turns -0.0 into 0.0, which would print as '-0.0000'.
        return np.concatenate([poses[:, :3] * 1e3, np.degrees(poses[:, 3:])], axis=1) + 0.0

    pose_header = ['X [mm]', 'Y [mm]', 'Z [mm]', 'alpha [deg]', 'beta [deg]', 'gamma [deg]']
    _print_table("Input pose received on target_pose (the paper's Figure 5)", pose_header,
                 pose_rows(received), '{:12.4f}')
    _print_table('Leg lengths from ik_node on leg_lengths (Figure 7)',
                 [f'l{leg} [mm]' for leg in range(1, 7)], lengths * 1e3, '{:12.4f}')
    position_error = np.linalg.norm(estimates[:, :3] - targets[:, :3], axis=1)
    orientation_error = rotation_angle_between(
        euler_zyx_to_matrix(targets[:, 3:]), euler_zyx_to_matrix(estimates[:, 3:]))
    _print_table('Pose from fk_node on estimated_pose (Figure 9), and round-trip error',
                 pose_header + ['error [m]', 'error [rad]'],
                 np.column_stack([pose_rows(estimates), position_error, orientation_error]),
                 '{:12.4f}', error_columns=2)
    return {'times': np.arange(count, dtype=float), 'received': received, 'lengths': lengths,
            'estimates': estimates, 'position_error': position_error,
            'orientation_error': orientation_error}


def _print_table(title, header, rows, number_format, error_columns=0):
    print(f'\n{title}')
    print('row ' + ''.join(f'{name:>12}' for name in header))
    for index, row in enumerate(rows):
        cells = [number_format.format(value) for value in row[:len(row) - error_columns]]
        cells += [f'{value:12.1e}' for value in row[len(row) - error_columns:]]
        print(f'{index:3d} ' + ''.join(cells))


if __name__ == '__main__':
    raise SystemExit(main())
