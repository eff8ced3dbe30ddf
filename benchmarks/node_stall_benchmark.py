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
Look for what stalls a node under a flood: subjects side by side, one suspect removed at a time.

Each subject is a node process, ``KIND:EXECUTOR[:VARIANT,...]``: ``echo`` (benchmarks/
echo_node.py), ``ik`` or ``fk`` on ``events`` or ``single_threaded``, with the parts a variant
names taken out (:data:`VARIANTS`: the diagnostics timer, the workspace reporter's timer, the
parameter services, ...) or, for the echo node, work added to its callback (``work90``: a busy
loop of 90 us, about ik_node's callback). The subjects are measured as
benchmarks/run_benchmarks.py measures the nodes (its probe, its rate ladder and bisections,
queue depth 100), interleaved rung by rung so that a slow moment of the machine hits them alike,
over ``--rounds`` rounds; it prints per subject the median loss-free rate with its range, the
latency at 1 kHz and the processor time per message, and the load average around each round.

With ``--timing``, every subscription callback of each subject records its wall time and its
thread's processor time (``time.perf_counter_ns``, ``time.thread_time_ns``); ``--hold RATE``
first floods each subject at RATE for ``--hold-rounds`` rungs of 2 s (interleaved) and counts
the rungs that lost a message. The histograms then tell a callback that works long (processor
time) from one that was stopped (wall time far above its processor time: the thread was
preempted or blocked), and show the gaps between callbacks::

    source scripts/ros_env.sh
    .venv/bin/python benchmarks/node_stall_benchmark.py --rounds 3 echo:events ik:events
    .venv/bin/python benchmarks/node_stall_benchmark.py ik:events:nodiag,noworkspace
    .venv/bin/python benchmarks/node_stall_benchmark.py --rounds 0 --timing --hold 2000 \
        ik:events echo:events echo:events:work90

A sampling profile of a subject under the flood: ``py-spy record --native -p PID`` (the PIDs
are printed; py-spy is in benchmarks/requirements.txt).
"""

import argparse
import math
import os
from pathlib import Path
import sys
import tempfile
import time

import numpy as np

#: What a variant takes out of (or adds to) a subject.
VARIANTS = {
    'nodiag': "the /diagnostics report timer (NodeDiagnostics' once a second)",
    'noworkspace': "ik_node's workspace reporter timer (travel ranges, markers)",
    'noparamsrv': 'the parameter services (start_parameter_services=False)',
    'work90': 'echo only: a busy loop of 90 us in the callback, before the republish',
    'nomargin': "fk_node's assembly-mode margin (-p assembly_mode_margin_period:=0.0): its "
                'worker process computes every assembly mode of the last solution',
    'spinonce': "the main loop's old slice on the events executor: spin_once, which returns "
                'after each callback (node_main.spin_slice runs every callback of 0.1 s)',
}
#: Seconds of one rung of ``--hold``.
HOLD_SECONDS = 2.0
#: Histogram edges of the callback times, microseconds.
EDGES_US = (0, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000, math.inf)


def parse_subject(text):
    """Return ``(label, kind, executor, variants)`` of ``KIND:EXECUTOR[:VARIANT,...]``."""
    kind, _, rest = text.partition(':')
    executor, _, variants = rest.partition(':')
    variants = tuple(filter(None, variants.split(',')))
    if kind not in ('echo', 'ik', 'fk') or executor not in ('events', 'single_threaded'):
        raise argparse.ArgumentTypeError(
            f'subject {text!r}: KIND:EXECUTOR[:VARIANT,...] with KIND echo, ik or fk and '
            'EXECUTOR events or single_threaded')
    unknown = [name for name in variants if name not in VARIANTS]
    if unknown:
        raise argparse.ArgumentTypeError(
            f'subject {text!r}: unknown variant {unknown[0]!r}; allowed are '
            f'{", ".join(VARIANTS)}')
    label = '_'.join([kind, executor.replace('single_threaded', 'st'), *variants])
    return label, kind, executor, variants


def without_timers(cls):
    """Wrap ``cls.__init__`` so that the timer it creates on its node is not created."""
    original = cls.__init__

    def init(self, node, *args, **kwargs):
        node.create_timer = lambda *timer_args, **timer_kwargs: None
        try:
            original(self, node, *args, **kwargs)
        finally:
            del node.create_timer
    cls.__init__ = init


def serve(kind, variants, timing_file, arguments):
    """Run one subject in this process, with its variants; return its exit code."""
    import rclpy.node
    from stewart_kinematics.ros import message_accounting, node_main, workspace_publishing

    if 'spinonce' in variants:
        node_main.spin_slice = lambda executor, seconds=node_main.SPIN_SLICE: (
            executor.spin_once(timeout_sec=seconds))
    if 'nodiag' in variants:
        without_timers(message_accounting.NodeDiagnostics)
    if 'noworkspace' in variants:
        without_timers(workspace_publishing.WorkspacePublisher)
    if 'noparamsrv' in variants:
        node_init = rclpy.node.Node.__init__

        def init(self, *args, **kwargs):
            node_init(self, *args, **{**kwargs, 'start_parameter_services': False})
        rclpy.node.Node.__init__ = init
    create_subscription = rclpy.node.Node.create_subscription
    work_ns = 90_000 if 'work90' in variants else 0
    times = []

    def timed_subscription(self, message_type, topic, callback, *args, **kwargs):
        clock, processor, record = time.perf_counter_ns, time.thread_time_ns, times.append

        def timed(message):
            start, start_cpu = clock(), processor()
            if work_ns:
                while clock() < start + work_ns:
                    pass
            callback(message)
            record((start, clock(), start_cpu, processor()))
        # The events executor passes the message alone to a callback of one parameter.
        return create_subscription(self, message_type, topic, timed if (
            timing_file or work_ns) else callback, *args, **kwargs)
    rclpy.node.Node.create_subscription = timed_subscription
    create_timer = rclpy.node.Node.create_timer
    ticks, timers = [], []

    def timed_timer(self, period, callback, *args, **kwargs):
        clock, record, index = time.perf_counter_ns, ticks.append, len(timers)
        timers.append(period)

        def timed():
            start = clock()
            callback()
            record((index, round(period * 1e9), start, clock()))
        return create_timer(self, period, timed if timing_file else callback, *args, **kwargs)
    rclpy.node.Node.create_timer = timed_timer
    try:
        if kind == 'ik':
            from stewart_kinematics.ros.ik_node import main
            return main(arguments)
        if kind == 'fk':
            from stewart_kinematics.ros.fk_node import main
            return main(arguments)
        import echo_node  # benchmarks/, the script's folder
        return echo_node.main(arguments)
    finally:
        if timing_file:
            np.save(timing_file, np.array(times, dtype=np.int64).reshape(-1, 4))
            np.save(timing_file.replace('.npy', '_timers.npy'),
                    np.array(ticks, dtype=np.int64).reshape(-1, 4))


def histogram_lines(label, times):
    """Return the lines that describe one subject's callback times (rows of four ns stamps)."""
    if len(times) < 2:
        return [f'{label}: {len(times)} callbacks timed']
    wall = (times[:, 1] - times[:, 0]) / 1e3
    cpu = (times[:, 3] - times[:, 2]) / 1e3
    gaps = (times[1:, 0] - times[:-1, 1]) / 1e3
    lines = [f'{label}: {len(times)} callbacks']
    for name, values in (('wall', wall), ('thread cpu', cpu), ('gap before next', gaps)):
        p50, p99, p999, top = np.percentile(values, [50, 99, 99.9, 100])
        lines.append(f'  {name:<16} us: p50 {p50:.0f}, p99 {p99:.0f}, p99.9 {p999:.0f}, '
                     f'max {top:.0f}')
    counts, _ = np.histogram(wall, EDGES_US)
    lines.append('  wall histogram  : ' + ', '.join(
        f'<{edge / 1e3:g} ms {count}' for edge, count in zip(EDGES_US[1:], counts) if count))
    lines.append(f'  callbacks over 5 ms: {int(np.sum(wall > 5000))}, of which stopped (wall - '
                 f'cpu > 5 ms) {int(np.sum(wall - cpu > 5000))}, working (cpu > 5 ms) '
                 f'{int(np.sum(cpu > 5000))}; over 20 ms: {int(np.sum(wall > 20000))}')
    return lines


def timer_lines(ticks):
    """Return the lines that describe each timer's ticks (rows: index, period, start, end)."""
    lines = []
    for index in np.unique(ticks[:, 0]):
        period = ticks[ticks[:, 0] == index, 1][0]
        starts = np.sort(ticks[ticks[:, 0] == index, 2])
        if len(starts) < 3:
            continue
        intervals = np.diff(starts) / 1e6
        p50, p99, top = np.percentile(intervals, [50, 99, 100])
        expected = (starts[-1] - starts[0]) / period + 1
        lines.append(f'  timer {index} of {period / 1e6:g} ms: {len(starts)} ticks of '
                     f'{expected:.0f} due; interval ms p50 {p50:.3f}, p99 {p99:.3f}, '
                     f'max {top:.3f}')
    return lines


def measure(options):
    """Start the subjects, measure them interleaved, print the table; return the exit code."""
    import rclpy
    from geometry_msgs.msg import Pose
    import run_benchmarks as bench  # benchmarks/, the script's folder
    from std_msgs.msg import Float64MultiArray
    from stewart_kinematics import inverse_kinematics, load_geometry
    from stewart_kinematics.ros.message_conversions import legs_to_message, pose_to_message
    from stewart_kinematics.tools.node_processes import isolated_ros_environment, NodeProcess

    geometry = load_geometry(bench.PLATFORM_FILE)
    poses = bench.table3_ramp().sample(np.linspace(0.0, 10.0, 2001), 10.0)
    poses = np.concatenate([poses, poses[::-1]])
    pose_messages = [pose_to_message(pose) for pose in poses]
    length_messages = [legs_to_message(lengths)
                       for lengths in inverse_kinematics(geometry, poses)]
    params = ['--params-file', str(bench.PLATFORM_FILE), '--params-file', str(bench.SOLVER_FILE),
              '-p', f'queue_depth:={bench.QUEUE_DEPTH}']
    folder = Path(tempfile.mkdtemp(prefix='node_stall_'))
    subjects = options.subjects
    labels = [label for label, *_ in subjects]
    if len(set(labels)) != len(labels):
        raise SystemExit('each subject once')
    results = {label: {'rate': [], 'p50': [], 'p99': [], 'cpu': []} for label in labels}
    loads = []
    with isolated_ros_environment():
        processes = {}
        for label, kind, executor, variants in subjects:
            arguments = [__file__, '--serve', kind, '--variants', ','.join(variants)]
            if options.timing:
                arguments += ['--timing-file', str(folder / f'{label}.npy')]
            extra = ['-r', 'leg_lengths:=fk_lengths'] if kind == 'fk' else []
            node_arguments = ([] if kind == 'echo' else
                              [word for text in options.node_args for word in text.split()])
            arguments += ['--executor', executor, '--ros-args', '-r', f'__ns:=/{label}',
                          *(params if kind != 'echo' else params[-2:]), *extra,
                          *node_arguments]
            if 'nomargin' in variants:
                arguments += ['-p', 'assembly_mode_margin_period:=0.0']
            processes[label] = NodeProcess('python', arguments)
        rclpy.init()
        try:
            probes = {}
            for label, kind, _, _ in subjects:
                prefix = f'{label}/'
                probes[label] = {
                    'echo': (Pose, 'echo_in', Pose, 'echo_out', pose_messages),
                    'ik': (Pose, 'target_pose', Float64MultiArray, 'leg_lengths', pose_messages),
                    'fk': (Float64MultiArray, 'fk_lengths', Pose, 'estimated_pose',
                           length_messages),
                }[kind]
                in_type, in_topic, out_type, out_topic, messages = probes[label]
                probes[label] = (bench.Probe(in_type, prefix + in_topic, out_type,
                                             prefix + out_topic), messages)
            deadline = time.monotonic() + 60.0
            for label, (probe, messages) in probes.items():
                if not probe.wait_connected(deadline, list(processes.values())):
                    raise SystemExit(f'{label} did not connect: '
                                     + processes[label].output()[-1000:])
                probe.latency(messages, bench.LATENCY_RATE, 0.5)  # warm-up
            pids = ', '.join(f'{label} {process.process.pid}'
                             for label, process in processes.items())
            print(f'process ids: {pids}', flush=True)
            if options.hold:
                lossy = dict.fromkeys(labels, 0)
                before = os.getloadavg()[0]
                for _ in range(options.hold_rounds):
                    for label, (probe, messages) in probes.items():
                        lossy[label] += not probe.loss_free(messages, options.hold,
                                                            HOLD_SECONDS)[0]
                print(f'hold at {options.hold:,.0f} Hz, rungs of {HOLD_SECONDS:g} s that lost a '
                      f'message, of {options.hold_rounds}: '
                      + ', '.join(f'{label} {count}' for label, count in lossy.items())
                      + f' (load average {before:.2f} -> {os.getloadavg()[0]:.2f})', flush=True)
            for round_index in range(options.rounds):
                before = os.getloadavg()[0]
                for label, (probe, messages) in probes.items():
                    used = bench.process_seconds(processes[label])
                    delays = probe.latency(messages, bench.LATENCY_RATE, bench.LATENCY_SECONDS)
                    results[label]['cpu'].append(
                        (bench.process_seconds(processes[label]) - used)
                        / (bench.LATENCY_RATE * bench.LATENCY_SECONDS))
                    p50, p99 = ((math.inf, math.inf) if delays is None
                                else np.percentile(delays, [50, 99]))
                    results[label]['p50'].append(p50)
                    results[label]['p99'].append(p99)
                searches = {label: bench.RateSearch() for label in labels}
                while any(search.next_rate() for search in searches.values()):
                    for label, search in searches.items():
                        rate = search.next_rate()
                        if rate:
                            probe, messages = probes[label]
                            search.record(rate, *probe.loss_free(messages, rate,
                                                                 bench.RUNG_SECONDS))
                for label, search in searches.items():
                    results[label]['rate'].append(search.best)
                loads.append((before, os.getloadavg()[0]))
                print(f'round {round_index + 1} (load average {before:.2f} -> '
                      f'{loads[-1][1]:.2f}): ' + '; '.join(
                          f'{label} {results[label]["rate"][-1]:,.0f} Hz' for label in labels),
                      flush=True)
        finally:
            rclpy.try_shutdown()
            for process in processes.values():
                process.stop()
    if options.rounds:
        print('\n| Subject | Loss-free rate, median (range) | p50 / p99 at 1 kHz, ms | '
              'Processor per message | Load average |\n| --- | --- | --- | --- | --- |')
        low, high = min(min(pair) for pair in loads), max(max(pair) for pair in loads)
        load_text = f'{low:.2f}-{high:.2f}'
        for label in labels:
            figures = results[label]
            rate = figures['rate']
            print(f'| {label} | {np.median(rate):,.0f} Hz ({min(rate):,.0f}-{max(rate):,.0f}) | '
                  f'{np.median(figures["p50"]) * 1e3:.2f} / {np.median(figures["p99"]) * 1e3:.2f} '
                  f'({min(figures["p99"]) * 1e3:.2f}-{max(figures["p99"]) * 1e3:.2f}) | '
                  f'{np.median(figures["cpu"]) * 1e6:.0f} us | {load_text} |')
    if options.timing:
        print()
        for label in labels:
            path = folder / f'{label}.npy'
            if path.exists():
                print('\n'.join(histogram_lines(label, np.load(path))
                                + timer_lines(np.load(path.with_name(f'{label}_timers.npy')))))
    return 0


def main(argv=None) -> int:
    """Measure the subjects given, or (``--serve``) run one of them."""
    argv = sys.argv[1:] if argv is None else argv
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    if argv[:1] == ['--serve']:
        kind, variants = argv[1], tuple(filter(None, argv[3].split(',')))
        timing_file = None
        rest = argv[4:]
        if rest[:1] == ['--timing-file']:
            timing_file, rest = rest[1], rest[2:]
        return serve(kind, variants, timing_file, [sys.argv[0], *rest])
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('subjects', nargs='+', type=parse_subject,
                        help='KIND:EXECUTOR[:VARIANT,...], e.g. ik:events:nodiag; variants: '
                             + '; '.join(f'{name}: {text}' for name, text in VARIANTS.items()))
    parser.add_argument('--rounds', type=int, default=3, help='rounds of the rate search')
    parser.add_argument('--timing', action='store_true',
                        help='time every subscription callback; print the histograms')
    parser.add_argument('--hold', type=float, default=0.0,
                        help='first flood each subject at this rate, Hz (see --hold-rounds)')
    parser.add_argument('--hold-rounds', type=int, default=8,
                        help=f'rungs of {HOLD_SECONDS:g} s per subject at --hold')
    parser.add_argument('--node-args', action='append', default=[],
                        help="more ROS arguments of ik and fk, e.g. '-p command_rate:=500'")
    return measure(parser.parse_args(argv))


if __name__ == '__main__':
    sys.exit(main())
