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

Starts the chain ``target_pose -> ik_node -> leg_lengths -> fk_node -> estimated_pose`` either
as two console scripts (``ik_node``, ``fk_node``: the three-process layout without the
trajectory node, which idles during a measurement) or as ``stewart_platform`` (every node in
one process, one executor), and measures:

- memory: the resident set size (VmRSS) of the chain's processes, added up, after a warm-up;
- latency: from publishing a pose to receiving the pose fk_node estimates from its lengths, at
  ``--rate`` poses a second for ``--seconds``, p50 and p99.

The two layouts take turns (``--rounds`` each, alternating) on one isolated ROS domain, so that
a slow moment of the machine hits both alike; the figures are the medians over the rounds, and
the ratios one process / three processes. Run from the repository root::

    .venv/bin/python benchmarks/one_process_benchmark.py
"""

import argparse
from pathlib import Path
import statistics
import sys
import time

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
PLATFORM_FILE = ROOT / 'config' / 'paper_platform.yaml'
SOLVER_FILE = ROOT / 'config' / 'solver.yaml'
#: Queue depth of the nodes and the probe: no loss at the rates measured.
QUEUE_DEPTH = 100
#: Seconds of publishing before a measurement (discovery settled, caches warm), not counted.
WARM_UP_SECONDS = 1.0
#: Seconds to wait for the nodes to start and connect.
CONNECT_TIMEOUT = 30.0


def layouts():
    """Return the two layouts: name -> list of (console script, extra arguments)."""
    return {
        'three processes': [('ik_node', []), ('fk_node', [])],
        'one process': [('stewart_platform', ['--play-ramp', 'false'])],
    }


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

    def on_estimate(self, _message):
        """Record the arrival time of one estimated pose."""
        self.arrivals.append(time.perf_counter())

    def connected(self) -> bool:
        """Whether ik_node subscribes target_pose and fk_node publishes estimated_pose."""
        return (self.publisher.get_subscription_count() >= 1
                and self.node.count_publishers('/estimated_pose') >= 1)

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

        :returns: latencies in seconds, one per pose (``None`` if a pose was lost).
        """
        self.arrivals = []
        count = int(rate * seconds)
        sends = []
        start = time.perf_counter()
        for index in range(count):
            due = start + index / rate
            while time.perf_counter() < due:
                self.executor.spin_once(timeout_sec=0.0)
            sends.append(time.perf_counter())
            self.publisher.publish(messages[index % len(messages)])
        end = time.perf_counter() + 2.0
        while time.perf_counter() < end and len(self.arrivals) < count:
            self.executor.spin_once(timeout_sec=0.01)
        if len(self.arrivals) != count:
            return None
        return np.array(self.arrivals) - np.array(sends)


def measure(layout, probe, messages, rate, seconds):
    """
    Start one layout, measure its memory and latency, stop it.

    :returns: ``(resident MiB of its processes, p50 s, p99 s)``.
    """
    from stewart_kinematics.tools.node_processes import NodeProcess
    arguments = ['--ros-args', '--params-file', str(PLATFORM_FILE), '--params-file',
                 str(SOLVER_FILE), '-p', f'queue_depth:={QUEUE_DEPTH}']
    processes = [NodeProcess(script, [*extra, *arguments]) for script, extra in layout]
    try:
        if not probe.spin_until(probe.connected, CONNECT_TIMEOUT, processes):
            raise RuntimeError('the chain did not connect:\n'
                               + '\n'.join(process.output()[-2000:] for process in processes))
        probe.run(messages, rate, WARM_UP_SECONDS)
        resident = sum(resident_kib(process.process.pid) for process in processes) / 1024.0
        latencies = probe.run(messages, rate, seconds)
        if latencies is None:
            raise RuntimeError(f'poses were lost at {rate:g} Hz')
        p50, p99 = np.percentile(latencies, [50, 99])
        return resident, p50, p99
    finally:
        codes = [process.stop() for process in processes]
        if any(codes):
            print(f'warning: exit codes {codes}', file=sys.stderr)


def main(argv=None) -> int:
    """Measure both layouts in turns and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--rate', type=float, default=200.0, help='poses a second (200)')
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
              f'{options.rate:g} Hz per layout', file=sys.stderr)
        rclpy.init()
        try:
            probe = Probe()
            for round_index in range(options.rounds):
                for name, layout in layouts().items():
                    results[name].append(measure(layout, probe, messages, options.rate,
                                                 options.seconds))
                    print(f'round {round_index + 1} {name}: {results[name][-1][0]:.1f} MiB, '
                          f'p50 {results[name][-1][1] * 1e3:.2f} ms, '
                          f'p99 {results[name][-1][2] * 1e3:.2f} ms', file=sys.stderr)
        finally:
            rclpy.try_shutdown()
    medians = {name: [statistics.median(values) for values in zip(*runs)]
               for name, runs in results.items()}
    three, one = medians['three processes'], medians['one process']
    print('| Layout | RSS total [MiB] | pose -> FK pose p50 [ms] | p99 [ms] |')
    print('| --- | --- | --- | --- |')
    for name, (resident, p50, p99) in medians.items():
        print(f'| {name} | {resident:.1f} | {p50 * 1e3:.2f} | {p99 * 1e3:.2f} |')
    print(f'| one / three | {one[0] / three[0]:.2f}x | {one[1] / three[1]:.2f}x | '
          f'{one[2] / three[2]:.2f}x |')
    return 0


if __name__ == '__main__':
    sys.exit(main())
