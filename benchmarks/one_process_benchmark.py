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
One process against three: memory and the pose -> FK pose latency of ik_node and fk_node.

Starts ik_node, fk_node and trajectory_node either as three console scripts or as
``stewart_platform --play-ramp true`` (the three nodes in one process, one executor), with the
shipped parameter files; the trajectory node waits for more subscribers than will come, so it
is there (memory) but publishes nothing. The benchmark drives the chain
``target_pose -> ik_node -> leg_lengths -> fk_node -> estimated_pose`` and measures:

- memory: the resident set size (VmRSS) of the chain's processes, added up, after a warm-up;
- latency: from publishing a pose to receiving the pose fk_node estimates from its lengths, at
  ``--rate`` poses a second for ``--seconds``, p50 and p99.

The two layouts take turns (``--rounds`` each, alternating) on one isolated ROS domain, so that
a slow moment of the machine hits both alike; the figures are the medians over the rounds, and
the ratios one process / three processes. Run from the repository root::

    .venv/bin/python benchmarks/one_process_benchmark.py
"""

import argparse
import math
import os
from pathlib import Path
import statistics
import sys
import time

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
PLATFORM_FILE = ROOT / 'config' / 'paper_platform.yaml'
SOLVER_FILE = ROOT / 'config' / 'solver.yaml'
RAMP_FILE = ROOT / 'config' / 'table3_ramp.yaml'
#: The trajectory node's min_subscribers: more than will come, so that the ramp never plays.
IDLE_RAMP_SUBSCRIBERS = 1000
#: Queue depth of the nodes and the probe: no loss at the rates measured.
QUEUE_DEPTH = 100
#: Seconds of publishing before a measurement (discovery settled, caches warm), not counted.
WARM_UP_SECONDS = 1.0
#: Seconds to wait for the nodes to start and connect.
CONNECT_TIMEOUT = 30.0


def layouts():
    """Return the two layouts: name -> list of (console script, extra arguments)."""
    return {
        'three processes': [('ik_node', []), ('fk_node', []), ('trajectory_node', [])],
        'one process': [('stewart_platform', ['--play-ramp', 'true'])],
    }


def pose_key(message):
    """
    Return a pose message's position rounded to 1e-6 m: the same for a pose and its FK.

    FK matches a pose to about 1e-13 m, and the benchmark's poses lie 1e-4 m apart.
    """
    position = message.position
    return round(position.x, 6), round(position.y, 6), round(position.z, 6)


def resident_kib(pid: int) -> int:
    """Return a process's resident set size (VmRSS), KiB."""
    for line in Path(f'/proc/{pid}/status').read_text().splitlines():
        if line.startswith('VmRSS:'):
            return int(line.split()[1])
    raise RuntimeError(f'no VmRSS for process {pid}')


class Probe:
    """The benchmark's rclpy node: publishes poses, times the estimated poses that come back."""

    def __init__(self):
        from geometry_msgs.msg import Pose
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.qos import QoSProfile
        self.node = rclpy.create_node('one_process_benchmark_probe')
        qos = QoSProfile(depth=QUEUE_DEPTH)
        self.publisher = self.node.create_publisher(Pose, 'target_pose', qos)
        self.node.create_subscription(Pose, 'estimated_pose', self.on_estimate, qos)
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self.arrivals = []

    def on_estimate(self, message):
        """Record the arrival time of one estimated pose, with the pose it answers."""
        self.arrivals.append((time.perf_counter(), pose_key(message)))

    def connected(self) -> bool:
        """Whether ik_node subscribes target_pose and fk_node publishes estimated_pose."""
        return (self.publisher.get_subscription_count() >= 1
                and self.node.count_publishers('/estimated_pose') >= 1)

    def gone(self) -> bool:
        """Whether no node of the chain is left in the graph (the last layout stopped)."""
        return (self.publisher.get_subscription_count() == 0
                and self.node.count_publishers('/estimated_pose') == 0)

    def answered(self, message) -> bool:
        """Publish ``message`` unless an estimate came back already; say whether one did."""
        if not self.arrivals:
            self.publisher.publish(message)
            self.executor.spin_once(timeout_sec=0.05)
        return bool(self.arrivals)

    def spin_until(self, condition, timeout, processes) -> bool:
        """Spin until ``condition()``, ``timeout`` seconds, or a process exits."""
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > deadline or not all(p.running() for p in processes):
                return False
            self.executor.spin_once(timeout_sec=0.05)
        return True

    def run(self, messages, rate, seconds):
        """
        Publish ``messages`` cyclically at ``rate`` for ``seconds``, then drain.

        An estimate is paired with the oldest unanswered send of the same pose (each pose is
        sent twice per cycle, there and back), so a straggler of an earlier run cannot pass
        for an answer.

        :returns: latencies in seconds, one per pose, and the number of poses lost (the
            latencies are ``None`` when any was).
        """
        self.arrivals = []
        count = int(rate * seconds)
        sends = []
        keys = [pose_key(messages[index % len(messages)]) for index in range(count)]
        start = time.perf_counter()
        for index in range(count):
            due = start + index / rate
            while time.perf_counter() < due:
                self.executor.spin_once(timeout_sec=0.0)
            sends.append(time.perf_counter())
            self.publisher.publish(messages[index % len(messages)])
        end = time.perf_counter() + 2.0
        while time.perf_counter() < end and len(self.pair(keys, sends)) < count:
            self.executor.spin_once(timeout_sec=0.01)
        latencies = self.pair(keys, sends)
        if len(latencies) != count:
            return None, count - len(latencies)
        return np.array(latencies), 0

    def pair(self, keys, sends):
        """Return the latencies of the arrivals that answer a send, in seconds."""
        waiting = {}
        for index, key in enumerate(keys[:len(sends)]):
            waiting.setdefault(key, []).append(index)
        latencies = []
        for arrival, key in self.arrivals:
            # A straggler of an earlier run arrives before any send of its pose in this one.
            if waiting.get(key) and arrival >= sends[waiting[key][0]]:
                latencies.append(arrival - sends[waiting[key].pop(0)])
        return latencies


def measure(layout, probe, messages, rate, seconds):
    """
    Start one layout, measure its memory and latency, stop it.

    :returns: ``(resident MiB of its processes, p50 s, p99 s, poses lost)``; the latencies
        are NaN when poses were lost.
    """
    from stewart_kinematics.tools.node_processes import NodeProcess
    arguments = ['--ros-args', '--params-file', str(PLATFORM_FILE), '--params-file',
                 str(SOLVER_FILE), '--params-file', str(RAMP_FILE),
                 '-p', f'queue_depth:={QUEUE_DEPTH}',
                 '-p', f'trajectory_node:min_subscribers:={IDLE_RAMP_SUBSCRIBERS}']
    processes = [NodeProcess(script, [*extra, *arguments]) for script, extra in layout]
    try:
        probe.arrivals = []
        # Discovered both ends, then a first round trip: ik_node -> fk_node is wired too.
        if not (probe.spin_until(probe.connected, CONNECT_TIMEOUT, processes)
                and probe.spin_until(lambda: probe.answered(messages[0]), CONNECT_TIMEOUT,
                                     processes)):
            raise RuntimeError('the chain did not connect:\n'
                               + '\n'.join(process.output()[-2000:] for process in processes))
        probe.run(messages, rate, WARM_UP_SECONDS)
        resident = sum(resident_kib(process.process.pid) for process in processes) / 1024.0
        latencies, lost = probe.run(messages, rate, seconds)
        if latencies is None:
            return resident, math.nan, math.nan, lost
        p50, p99 = np.percentile(latencies, [50, 99])
        return resident, p50, p99, 0
    finally:
        codes = [process.stop() for process in processes]
        if any(codes):
            print(f'warning: exit codes {codes}', file=sys.stderr)
        # The next layout starts only once this one has left the graph.
        probe.spin_until(probe.gone, CONNECT_TIMEOUT, [])


def main(argv=None) -> int:
    """Measure both layouts in turns and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--rate', type=float, default=100.0, help='poses a second (100)')
    parser.add_argument('--seconds', type=float, default=5.0, help='per measurement (5)')
    parser.add_argument('--rounds', type=int, default=3, help='measurements per layout (3)')
    options = parser.parse_args(argv)

    import rclpy
    from stewart_kinematics import Ramp
    from stewart_kinematics.ros.message_conversions import pose_to_message
    from stewart_kinematics.tools.node_processes import isolated_ros_environment

    # The paper's Table 3, sampled finely.
    ramp = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])
    poses = ramp.sample(np.linspace(0.0, 10.0, 1001), 10.0)
    poses = np.concatenate([poses, poses[::-1]])   # there and back: the FK warm start holds
    messages = [pose_to_message(pose) for pose in poses]
    results = {name: [] for name in layouts()}
    with isolated_ros_environment() as domain:
        print(f'ROS_DOMAIN_ID={domain}; {options.rounds} rounds of {options.seconds:g} s at '
              f'{options.rate:g} Hz per layout; load average {os.getloadavg()[0]:.1f} on '
              f'{os.cpu_count()} CPUs', file=sys.stderr)
        rclpy.init()
        try:
            probe = Probe()
            for round_index in range(options.rounds):
                for name, layout in layouts().items():
                    results[name].append(measure(layout, probe, messages, options.rate,
                                                 options.seconds))
                    resident, p50, p99, lost = results[name][-1]
                    print(f'round {round_index + 1} {name}: {resident:.1f} MiB, '
                          f'p50 {p50 * 1e3:.2f} ms, p99 {p99 * 1e3:.2f} ms, {lost} lost',
                          file=sys.stderr)
        finally:
            rclpy.try_shutdown()
    # Medians over the rounds without losses (NaN latencies sort last: excluded).
    medians = {}
    for name, runs in results.items():
        complete = [run for run in runs if not run[3]] or runs
        medians[name] = [statistics.median(values) for values in zip(*complete)]
        medians[name][3] = sum(run[3] for run in runs)
    three, one = medians['three processes'], medians['one process']
    print('| Layout | RSS total [MiB] | pose -> FK pose p50 [ms] | p99 [ms] | poses lost |')
    print('| --- | --- | --- | --- | --- |')
    for name, (resident, p50, p99, lost) in medians.items():
        print(f'| {name} | {resident:.1f} | {p50 * 1e3:.2f} | {p99 * 1e3:.2f} | {lost} |')
    print(f'| one / three | {one[0] / three[0]:.2f}x | {one[1] / three[1]:.2f}x | '
          f'{one[2] / three[2]:.2f}x | |')
    return 0


if __name__ == '__main__':
    sys.exit(main())
