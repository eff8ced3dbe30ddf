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
``stewart_cueing``: replay a vehicle's motion through the motion cueing and measure the cue.

Runs the generated scenarios (``--scenario``, default all nine), a CSV file (``--csv``) or a
recording of ``vehicle_imu`` (``--mcap``: an ``.mcap`` file or a rosbag2 folder holding one)
through :class:`stewart_kinematics.cueing.MotionCueing`, configured from the nodes' own
parameter files, and reports the measures of :func:`stewart_kinematics.cueing.evaluate`: per
axis of specific force and rate, the vehicle's motion against the platform's as a person
perceives them (RMSE, correlation, delay, wrong-sign and felt-at-rest seconds) with the raw
measures beside, the platform's own rates against the tilt-rate threshold, the share of each
travel range used, the limit violations and the return to neutral; each scenario's targets
(``STRICT_TARGETS``, doc/cueing_evaluation.md) met or missed. It writes to ``--output`` the
Markdown tables (``cueing_results.md``), the numbers (``cueing_results.yaml``) and one figure
per run (input against felt specific force, raw and perceived, the perceived rates, and the
platform's motion, over time)::

    stewart_cueing --params-file config/paper_platform.yaml \
        --params-file config/example_limits.yaml --params-file config/motion_cueing.yaml \
        --output cueing_output

CSV input: a header line, then one row per sample (``#`` starts a comment line)::

    time,specific_force_x,specific_force_y,specific_force_z,angular_velocity_x,angular_velocity_y,angular_velocity_z

in seconds, m/s^2 (what an accelerometer at the driver's head reads: 9.81 on z at rest) and
rad/s, vehicle frame (x forward, y left, z up), times increasing.

Exit codes: 0 done; 1 an input or the parameters cannot be used (the message says why); 2 a
bad option (argparse names it) or a parameter file that cannot be read (one line, ``file:line:
what is wrong``: not YAML, an alias, nested too deep, a value of the wrong type or null); 3
with ``--strict``, a target missed.
"""

import argparse
import math
from pathlib import Path
import re
import sys
import time

import numpy as np

from stewart_kinematics.tools.cli_arguments import (
    check_output_paths,
    existing_file,
    existing_path,
    number_in,
    refuse_parameter_file,
)
from stewart_kinematics.tools.csv_input import read_number_table
import yaml

#: The CSV columns, in order.
CSV_COLUMNS = ('time', 'specific_force_x', 'specific_force_y', 'specific_force_z',
               'angular_velocity_x', 'angular_velocity_y', 'angular_velocity_z')
#: The most samples a CSV input may hold (over half an hour at 1 kHz), and its largest file.
MAX_CSV_SAMPLES = 2_000_000
MAX_CSV_BYTES = 256 * 1024 * 1024
#: The node's name: the parameter files' sections read besides ``/**``.
NODE_NAME = 'motion_cueing_node'
#: Exit codes.
EXIT_INPUT = 1
EXIT_TARGET_MISSED = 3


class ProgressBar:
    """
    A text progress bar on stderr, ``[#####-----]  52% slalom``, fed by a replay's callback.

    Drawn in place on a terminal; on anything else (a log, a test) one line per quarter.
    """

    def __init__(self, label, stream=None, width=30):
        self.label, self.width = label, width
        self.stream = sys.stderr if stream is None else stream
        self.interactive = hasattr(self.stream, 'isatty') and self.stream.isatty()
        self.started = time.monotonic()
        self._quarter = -1

    def __call__(self, done, total):
        """Show ``done`` of ``total`` samples."""
        fraction = done / total if total else 1.0
        if not self.interactive:
            quarter = int(fraction * 4)
            if quarter == self._quarter:
                return
            self._quarter = quarter
        filled = int(self.width * fraction)
        line = (f'[{"#" * filled}{"-" * (self.width - filled)}] {100 * fraction:3.0f}% '
                f'{self.label} ({time.monotonic() - self.started:.1f} s)')
        self.stream.write(f'\r{line:<79}' if self.interactive else line + '\n')
        if self.interactive and done >= total:
            self.stream.write('\n')
        self.stream.flush()


def build_parser() -> argparse.ArgumentParser:
    """Return the command line's parser."""
    from stewart_kinematics.cueing.evaluation import SETTLE_TIME
    from stewart_kinematics.cueing.scenarios import DEFAULT_RATE, SCENARIO_NAMES
    parser = argparse.ArgumentParser(
        prog='stewart_cueing', description=__doc__.split('\n\n')[1].replace('\n', ' '),
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog='CSV columns: ' + ','.join(CSV_COLUMNS))
    source = parser.add_mutually_exclusive_group()
    source.add_argument('--scenario', action='append', choices=SCENARIO_NAMES + ('all',),
                        help='a generated scenario; repeat for several (default: all)')
    source.add_argument('--csv', type=existing_file, help='replay this CSV file')
    source.add_argument('--mcap', type=existing_path,
                        help='replay sensor_msgs/msg/Imu from this .mcap file or rosbag2 folder')
    parser.add_argument('--topic', default='/vehicle_imu',
                        help='the Imu topic in the --mcap recording (default /vehicle_imu)')
    parser.add_argument('--params-file', dest='params_files', action='append', required=True,
                        type=existing_file,
                        help='ROS 2 parameter file (geometry, limits, motion_cueing_node); '
                             'repeat to layer files, as the node takes them')
    parser.add_argument('--rate', type=number_in(0.0, 10000.0, low_inclusive=False),
                        help=f'sampling rate of the scenarios, Hz (default {DEFAULT_RATE:g}; '
                             'a --csv or --mcap replay keeps its own times)')
    parser.add_argument('--output', type=Path, default=Path('cueing_output'),
                        help='folder for the table, the numbers and the figures '
                             '(default cueing_output/)')
    parser.add_argument('--no-figures', action='store_true', help='write no figures')
    parser.add_argument('--false-cue-threshold',
                        type=number_in(0.0, 100.0, low_inclusive=False),
                        default=None,
                        help='perceived specific force beyond this is felt (a false cue when '
                             'of the wrong sign or felt at rest), m/s^2, every axis (default: '
                             "the otoliths' thresholds, 0.17 along x and y, 0.28 along z)")
    parser.add_argument('--settle-time', type=number_in(0.0, 3600.0, low_inclusive=False),
                        default=SETTLE_TIME,
                        help='judge the return to neutral this long after the input rests, s '
                             f'(default {SETTLE_TIME:g})')
    parser.add_argument('--preview', action='store_true',
                        help='tell the model-predictive cueing (cueing_method: mpc) the input '
                             'to come, as a simulator that knows its drive would: at each '
                             'sample the MPC plans against the next horizon of it '
                             '(doc/motion_cueing_mpc.md)')
    parser.add_argument('--strict', action='store_true',
                        help="exit 3 when a target is missed (each scenario's targets: "
                             'doc/cueing_evaluation.md)')
    parser.add_argument('--quiet', action='store_true', help='no progress bar')
    return parser


def check_output(parser, folder: Path) -> None:
    """Make sure the output folder and its files can be written, before any work (exit 2)."""
    check_output_paths(parser, [('--output', folder, True)] + [
        ('--output', folder / name, False)
        for name in ('cueing_results.md', 'cueing_results.yaml')])
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as error:   # what the check cannot foresee (root in /proc)
        parser.error(f'argument --output: cannot write there: {error.filename or folder}: '
                     f'{error.strerror}')


def load_csv(path: Path):
    """
    Read a CSV input: ``(times, specific_force, angular_velocity)``.

    :raises ValueError: naming the file, the line and the column, for a bad header, a row of
        the wrong length, a value that is not a finite number, or times that do not increase.
    """
    _, rows = read_number_table(path, [CSV_COLUMNS], what='samples',
                                max_rows=MAX_CSV_SAMPLES, max_bytes=MAX_CSV_BYTES)
    return _checked_samples(str(path), np.array(rows).reshape(-1, len(CSV_COLUMNS)))


def _checked_samples(source, data):
    if data.shape[0] < 3:
        raise ValueError(f'{source}: needs at least 3 samples, got {data.shape[0]}')
    with np.errstate(over='ignore'):   # -1e308 to 1e308: an infinite step still increases
        steps = np.diff(data[:, 0])
        times = data[:, 0] - data[0, 0]
    if not np.all(steps > 0.0):
        bad = int(np.argmax(~(steps > 0.0))) + 1
        raise ValueError(f'{source}: times must increase; sample {bad} is at '
                         f'{float(data[bad, 0])!r} s after {float(data[bad - 1, 0])!r} s')
    # Counted from the first sample, each step must survive (a stamp of -1e308 first makes
    # every later time 1e308, or inf).
    with np.errstate(over='ignore', invalid='ignore'):   # inf - inf
        kept = np.isfinite(times[1:]) & (np.diff(times) > 0.0)
    if not np.all(kept):
        bad = int(np.argmax(~kept)) + 1
        raise ValueError(f'{source}: sample {bad} at {float(data[bad, 0])!r} s is too far from '
                         f'the first ({float(data[0, 0])!r} s) for its time since the first to '
                         'keep the step from the sample before it: a stamp out of place?')
    return times, data[:, 1:4], data[:, 4:7]


def mcap_file(path: Path) -> Path:
    """Return the .mcap file of a path: the file itself, or the one in a rosbag2 folder."""
    if path.is_dir():
        files = sorted(path.glob('*.mcap'))
        if len(files) != 1:
            raise ValueError(f'{path}: a rosbag2 folder with one .mcap file expected, found '
                             f'{len(files)}')
        return files[0]
    return path


def load_mcap(path: Path, topic: str):
    """
    Read ``sensor_msgs/msg/Imu`` samples of ``topic`` from an MCAP recording.

    Times are the messages' ``header.stamp`` (as the node uses them); a recording whose stamps
    are all zero falls back to the log times.

    :returns: ``(times, specific_force, angular_velocity, frame_ids)``, the samples as
        recorded, each in its message's ``header.frame_id``.
    :raises ValueError: naming the file, when it cannot be read or holds no such messages.
    """
    from mcap.exceptions import McapError
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    source = mcap_file(path)
    rows, frame_ids, wrong_type = [], [], None
    try:
        with open(source, 'rb') as stream:
            reader = make_reader(stream, decoder_factories=[DecoderFactory()])
            for schema, _, message, imu in reader.iter_decoded_messages(topics=[topic]):
                if schema is None or schema.name != 'sensor_msgs/msg/Imu':
                    wrong_type = 'no schema' if schema is None else schema.name
                    break
                stamp = imu.header.stamp.sec + 1e-9 * imu.header.stamp.nanosec
                a, w = imu.linear_acceleration, imu.angular_velocity
                rows.append((stamp, message.log_time * 1e-9, a.x, a.y, a.z, w.x, w.y, w.z))
                frame_ids.append(imu.header.frame_id)
    except (McapError, OSError, ValueError, KeyError, AttributeError) as error:
        raise ValueError(
            f'{source}: cannot read {topic} as sensor_msgs/msg/Imu: {error}') from None
    if wrong_type is not None:
        raise ValueError(f'{source}: {topic} holds {wrong_type}, not sensor_msgs/msg/Imu')
    if not rows:
        raise ValueError(f'{source}: no message on {topic}')
    data = np.array(rows)
    if np.all(data[:, 0] == 0.0):
        data[:, 0] = data[:, 1]
    data = np.delete(data, 1, axis=1)
    finite = np.all(np.isfinite(data), axis=1)
    if not np.all(finite):
        raise ValueError(f'{source}: message {int(np.argmin(finite))} on {topic} is not finite')
    return _checked_samples(f'{source} ({topic})', data) + (frame_ids,)


def in_vehicle_frame(cueing, source: str, forces, rates, frame_ids):
    """
    Turn recorded samples into the vehicle frame, each from its ``frame_id``, as the node does.

    :param cueing: the :class:`~stewart_kinematics.cueing.MotionCueing` whose
        ``vehicle_frame``, ``imu_frame`` and ``imu_orientation_rpy_deg`` apply.
    :param source: the recording, for the message.
    :param forces: m/s^2, shape (N, 3); ``rates``: rad/s, shape (N, 3).
    :param frame_ids: N frame names.
    :raises ValueError: naming the first message in a frame the parameters do not place (the
        node would refuse each of them and cue rest instead).
    """
    frame_ids = np.array(frame_ids, dtype=object)
    forces, rates = np.array(forces, dtype=float), np.array(rates, dtype=float)
    for frame_id in dict.fromkeys(frame_ids.tolist()):
        chosen = frame_ids == frame_id
        try:
            forces[chosen], rates[chosen] = cueing.to_vehicle_frame(
                forces[chosen], rates[chosen], frame_id)
        except ValueError as error:
            raise ValueError(f'{source}: message {int(np.argmax(chosen))} and '
                             f'{int(np.sum(chosen)) - 1} more: {error}') from None
    return forces, rates


def read_parameters(paths):
    """
    Return the parameter values motion_cueing_node would see from ``paths``.

    :raises ParameterFileError: as :func:`~stewart_kinematics.parameters.read_parameter_files`,
        the reader of every tool.
    """
    from stewart_kinematics.parameters import read_parameter_files
    return read_parameter_files(paths, NODE_NAME)


def targets(name, evaluation):
    """Judge one run by its scenario's strict targets: ``[(target, met, value)]``."""
    from stewart_kinematics.cueing.evaluation import judge
    return judge(name, evaluation)


def _triple(values, spec):
    return ' / '.join(_number(value, spec) for value in values)


def markdown_table(results, verdicts=None) -> str:
    """
    Return the results as the documentation's Markdown tables, one row per run.

    Three tables: the perceived fidelity, the false cues, and the platform's rates and limits.

    :param verdicts: run name -> its ``[(target, met, value)]``; default: :func:`targets`.
    """
    fidelity = [
        '| Run | r x / y / z | r roll / pitch / yaw | Delay x / y / z (ms) | '
        'Delay roll / pitch / yaw (ms) | RMSE x / y / z (m/s^2) | Raw r x / y | '
        'Raw RMSE x / y (m/s^2) |',
        '| --- | --- | --- | --- | --- | --- | --- | --- |']
    false = [
        '| Run | Wrong sign x / y / z (s) | Felt at rest x / y / z (s) | '
        'Wrong sign roll / pitch / yaw (s) | Felt at rest roll / pitch / yaw (s) |',
        '| --- | --- | --- | --- | --- |']
    platform = [
        '| Run | Limit violations | Platform rate peak roll / pitch / yaw (deg/s) | '
        'Time over the tilt-rate threshold roll / pitch / yaw (s) | '
        'Perceived tilt rate peak (deg/s) | Tilt channel peak (deg/s) | Travel used (largest) | '
        'Residual 10 s after rest | Workspace scale min | Actuator-limited share | '
        'Strict targets |',
        '| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |']
    from stewart_kinematics.cueing.evaluation import POSE_AXES
    for name, evaluation in results:
        forces, rotations = evaluation.axes, evaluation.rotations
        fidelity.append(
            f'| {name} | {_triple([m.correlation for m in forces], ".2f")} | '
            f'{_triple([m.correlation for m in rotations], ".2f")} | '
            f'{_triple([m.delay * 1e3 for m in forces], ".0f")} | '
            f'{_triple([m.delay * 1e3 for m in rotations], ".0f")} | '
            f'{_triple([m.rmse for m in forces], ".2f")} | '
            f'{_triple([m.raw_correlation for m in forces[:2]], ".2f")} | '
            f'{_triple([m.raw_rmse for m in forces[:2]], ".2f")} |')
        false.append(
            f'| {name} | {_triple([m.wrong_sign_time for m in forces], ".2f")} | '
            f'{_triple([m.felt_at_rest_time for m in forces], ".2f")} | '
            f'{_triple([m.wrong_sign_time for m in rotations], ".2f")} | '
            f'{_triple([m.felt_at_rest_time for m in rotations], ".2f")} |')
        travel = '-'
        if evaluation.travel_used is not None:
            index = int(np.argmax(evaluation.travel_used))
            travel = f'{100 * evaluation.travel_used[index]:.0f} % ({POSE_AXES[index]})'
        residual = '-' if evaluation.residual_position is None else (
            f'{evaluation.residual_position * 1e3:.2f} mm, '
            f'{math.degrees(evaluation.residual_angle):.3f} deg')
        met = targets(name, evaluation) if verdicts is None else verdicts[name]
        platform.append(
            f'| {name} | {evaluation.limit_violations} | '
            f'{_triple(np.degrees(evaluation.platform_rate_peak), ".2f")} | '
            f'{_triple(evaluation.platform_rate_time_over, ".2f")} | '
            f'{math.degrees(evaluation.perceived_tilt_rate_peak):.2f} | '
            f'{math.degrees(evaluation.tilt_rate_peak):.2f} | {travel} | {residual} | '
            f'{evaluation.workspace_scale_min:.2f} | {100 * evaluation.limited_share:.0f} % | '
            f'{sum(ok for _, ok, _ in met)} of {len(met)} |')
    return '\n\n'.join('\n'.join(table) for table in (fidelity, false, platform))


def _number(value, spec='.3f'):
    if math.isnan(value):
        return '-'
    if math.isinf(value):
        from stewart_kinematics.cueing.evaluation import MAX_DELAY
        return f'> {MAX_DELAY * 1e3:.0f}' if value > 0 else f'< -{MAX_DELAY * 1e3:.0f}'
    return format(value, spec)


def write_figure(path: Path, name, replay, evaluation, geometry, scales=(1.0, 1.0)):
    """
    Draw the input against the felt cue and the platform's motion over time.

    The specific force along x and y (input, felt at the head, both perceived), the perceived
    rates, and the platform's pose from neutral.

    :param scales: the translational scale per axis (x, y): the input times it is drawn too.
    """
    import matplotlib
    matplotlib.use('Agg')
    from matplotlib import pyplot
    times = replay.times
    figure, axes = pyplot.subplots(4, 1, figsize=(9, 10), sharex=True)
    for row, (axis, label) in enumerate((('x', 'longitudinal'), ('y', 'lateral'))):
        index = 'xy'.index(axis)
        measures = evaluation.axes[index]
        axes[row].plot(times, replay.specific_force[:, index], color='0.6', label='input')
        if scales[index] != 1.0:
            axes[row].plot(times, scales[index] * replay.specific_force[:, index], color='0.6',
                           linestyle=':', label=f'input x {scales[index]:g}')
        axes[row].plot(times, replay.perceived.specific_force[:, index], color='C0',
                       alpha=0.6, label='felt at the head')
        axes[row].plot(times, evaluation.vehicle.perceived_force[:, index], color='k',
                       linestyle='--', label='vehicle, perceived')
        axes[row].plot(times, evaluation.platform.perceived_force[:, index], color='C1',
                       label='platform, perceived')
        axes[row].set_ylabel(f'f_{axis} (m/s^2)')
        axes[row].set_title(f'{label}, perceived: r = {_number(measures.correlation)}, delay '
                            f'{_number(measures.delay * 1e3, ".0f")} ms, wrong sign '
                            f'{measures.wrong_sign_time:.2f} s, felt at rest '
                            f'{measures.felt_at_rest_time:.2f} s', fontsize=9)
        axes[row].legend(loc='upper right', fontsize=7)
        axes[row].grid(alpha=0.3)
    for index, label in enumerate(('roll', 'pitch', 'yaw')):
        axes[2].plot(times, np.degrees(evaluation.vehicle.perceived_rate[:, index]),
                     color=f'C{index}', linestyle='--', label=f'{label}, vehicle')
        axes[2].plot(times, np.degrees(evaluation.platform.perceived_rate[:, index]),
                     color=f'C{index}', label=f'{label}, platform')
    threshold = math.degrees(evaluation.tilt_rate_max)
    axes[2].axhline(threshold, color='0.5', linewidth=0.8)
    axes[2].axhline(-threshold, color='0.5', linewidth=0.8)
    axes[2].set_ylabel('perceived rate (deg/s)')
    axes[2].set_title(f'perceived tilt rate peak '
                      f'{math.degrees(evaluation.perceived_tilt_rate_peak):.2f} deg/s',
                      fontsize=9)
    axes[2].legend(loc='upper right', fontsize=7, ncol=3)
    axes[2].grid(alpha=0.3)
    offsets = replay.poses - geometry.home_pose
    for column, label in enumerate(('X', 'Y', 'Z')):
        axes[3].plot(times, offsets[:, column] * 1e3, label=f'{label} (mm)')
    for column, label in enumerate(('roll', 'pitch', 'yaw'), start=3):
        axes[3].plot(times, np.degrees(offsets[:, column]) * 10.0, '--',
                     label=f'{label} (0.1 deg)')
    axes[3].set_ylabel('platform from neutral')
    axes[3].set_xlabel('time (s)')
    axes[3].legend(loc='upper right', fontsize=7, ncol=2)
    axes[3].grid(alpha=0.3)
    figure.suptitle(f'motion cueing: {name}')
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    pyplot.close(figure)


def _inputs(options):
    """
    Yield ``(name, times, specific_force, angular_velocity, rest_time, frame_ids)`` of each run.

    ``frame_ids`` is ``None`` for samples in the vehicle frame (a CSV, a scenario).
    """
    from stewart_kinematics.cueing.scenarios import scenario, SCENARIO_NAMES
    if options.csv is not None:
        times, forces, rates = load_csv(options.csv)
        yield options.csv.name, times, forces, rates, None, None
    elif options.mcap is not None:
        times, forces, rates, frame_ids = load_mcap(options.mcap, options.topic)
        yield mcap_file(options.mcap).name, times, forces, rates, None, frame_ids
    else:
        names = options.scenario or ['all']
        names = SCENARIO_NAMES if 'all' in names else list(dict.fromkeys(names))
        for name in names:
            generated = scenario(name, options.rate)
            yield (name, generated.times, generated.specific_force, generated.angular_velocity,
                   generated.rest_time, None)


def _first_clause(meaning: str) -> str:
    """Return a code's meaning up to its first colon or full stop, without Markdown."""
    return re.split(r'[:.](?:\s|$)', meaning.replace('`', ''), maxsplit=1)[0]


def run(options, stream=None):
    """Replay every input and write the outputs; return ``(results, every target met)``."""
    stream = sys.stdout if stream is None else stream
    from stewart_kinematics import travel_ranges
    from stewart_kinematics.cueing import evaluate, MotionCueing, replay
    from stewart_kinematics.findings import CODES
    values = read_parameters(options.params_files)
    template = MotionCueing.from_parameters(values)
    geometry, settings = template.geometry, template.settings
    scenarios = options.csv is None and options.mcap is None
    if scenarios and options.rate * settings.max_input_gap < 1.0:
        # Slower samples would each count as max_input_gap: the replay would run on a wrong
        # clock, and its measures would grade a drive that was not played.
        raise ValueError(
            f'--rate {options.rate:g} Hz samples every {1.0 / options.rate:g} s, longer than '
            f'max_input_gap ({settings.max_input_gap:g} s), which the cueing counts a longer '
            f'gap as: use at least {1.0 / settings.max_input_gap:g} Hz')
    travel = travel_ranges(geometry).as_array()
    results, numbers, verdicts, all_met = [], {}, {}, True
    for name, times, forces, rates, rest, frame_ids in _inputs(options):
        if frame_ids is not None:
            forces, rates = in_vehicle_frame(template, name, forces, rates, frame_ids)
        cueing = MotionCueing(geometry, settings, template.actuator_limits)
        progress = None if options.quiet else ProgressBar(name)
        started = time.perf_counter()
        try:
            played = replay(cueing, times, forces, rates, progress, preview=options.preview)
        except ValueError as error:
            raise ValueError(f'{name}: {error}') from None
        seconds = time.perf_counter() - started
        evaluation = evaluate(played, geometry, template.actuator_limits,
                              settings.tilt_rate_max, rest=rest, travel=travel,
                              false_cue_threshold=options.false_cue_threshold,
                              settle_time=options.settle_time, gravity=settings.gravity)
        results.append((name, evaluation))
        # A file is judged as no scenario, whatever its name (a CSV called slalom included).
        met = targets(name if rest is not None else '', evaluation)
        verdicts[name] = met
        all_met &= all(ok for _, ok, _ in met)
        print(f'{name}: {times.size} samples over {times[-1]:.1f} s, replayed in {seconds:.2f} s '
              f'({1e6 * seconds / times.size:.0f} us a sample)', file=stream)
        for target, ok, value in met:
            print(f'  {"met   " if ok else "MISSED"} {target}: {value}', file=stream)
        for code, count in evaluation.warnings.items():
            # Said, not only counted in the numbers: an MPC that never solved moves nothing,
            # and a platform at rest meets the targets of limits and false cues.
            print(f'  warning {code} at {count} of {times.size} samples: '
                  f'{_first_clause(CODES[code].meaning) if code in CODES else code}',
                  file=stream)
        numbers[name] = _numbers(evaluation, met)
        if not options.no_figures:
            write_figure(options.output / f'{Path(name).stem}.png', name, played, evaluation,
                         geometry, settings.translation_scale[:2])
    table = markdown_table(results, verdicts)
    (options.output / 'cueing_results.md').write_text(table + '\n', encoding='utf-8')
    with open(options.output / 'cueing_results.yaml', 'w', encoding='utf-8') as out:
        yaml.safe_dump(numbers, out, sort_keys=False)
    print(table, file=stream)
    return results, all_met


def _numbers(evaluation, met):
    axes = {axis.axis: {
        'rmse': axis.rmse, 'correlation': _plain(axis.correlation), 'delay': _plain(axis.delay),
        'delay_correlation': _plain(axis.delay_correlation), 'raw_rmse': axis.raw_rmse,
        'raw_correlation': _plain(axis.raw_correlation), 'raw_delay': _plain(axis.raw_delay),
        'wrong_sign_time': axis.wrong_sign_time, 'felt_at_rest_time': axis.felt_at_rest_time,
        'peak': axis.peak, 'vehicle_peak': axis.vehicle_peak, 'threshold': axis.threshold}
        for axis in evaluation.axes + evaluation.rotations}
    return {
        'specific_force': {name: axes[name] for name in ('x', 'y', 'z')},
        'angular_velocity': {name: axes[name] for name in ('roll', 'pitch', 'yaw')},
        'platform_rate_peak_deg': [math.degrees(value)
                                   for value in evaluation.platform_rate_peak],
        'platform_rate_time_over': list(evaluation.platform_rate_time_over),
        'perceived_tilt_rate_peak_deg': math.degrees(evaluation.perceived_tilt_rate_peak),
        'tilt_rate_max_deg': math.degrees(evaluation.tilt_rate_max),
        'tilt_channel_rate_peak_deg': math.degrees(evaluation.tilt_rate_peak),
        'tilt_channel_rate_violations': evaluation.tilt_rate_violations,
        'travel_used': None if evaluation.travel_used is None else list(evaluation.travel_used),
        'pose_violations': evaluation.pose_violations,
        'leg_velocity_violations': evaluation.leg_velocity_violations,
        'leg_acceleration_violations': evaluation.leg_acceleration_violations,
        'leg_velocity_peak': evaluation.leg_velocity_peak,
        'leg_acceleration_peak': evaluation.leg_acceleration_peak,
        'residual_position': evaluation.residual_position,
        'residual_angle_deg': None if evaluation.residual_angle is None else math.degrees(
            evaluation.residual_angle),
        'workspace_scale_min': evaluation.workspace_scale_min,
        'limited_share': evaluation.limited_share,
        'warnings': dict(evaluation.warnings),
        'targets': {target: bool(ok) for target, ok, _ in met},
    }


def _plain(value):
    return None if not math.isfinite(value) else float(value)


def main(argv=None) -> int:
    """Run the report; see the module's documentation for the exit codes."""
    parser = build_parser()
    options = parser.parse_args(argv)
    if options.rate is not None and (options.csv is not None or options.mcap is not None):
        parser.error('argument --rate: a --csv or --mcap replay keeps its own times; '
                     '--rate samples the generated scenarios only')
    if options.rate is None:
        from stewart_kinematics.cueing.scenarios import DEFAULT_RATE
        options.rate = DEFAULT_RATE
    check_output(parser, options.output)
    from stewart_kinematics.parameters import ParameterFileError
    try:
        _, all_met = run(options)
    except ParameterFileError as error:
        return refuse_parameter_file('stewart_cueing', error)
    except ValueError as error:
        print(f'stewart_cueing: {error}', file=sys.stderr)
        return EXIT_INPUT
    except OSError as error:   # a write that fails during the run (a full disk)
        print(f'stewart_cueing: cannot write {error.filename or options.output}: '
              f'{error.strerror}', file=sys.stderr)
        return EXIT_INPUT
    return EXIT_TARGET_MISSED if options.strict and not all_met else 0


if __name__ == '__main__':
    raise SystemExit(main())
