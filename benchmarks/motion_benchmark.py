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
Benchmark the motion layer: checking and retiming, bounded costs, invariance, responsiveness.

Run from the repository root::

    .venv/bin/python benchmarks/motion_benchmark.py            # the core, no ROS needed
    .venv/bin/python benchmarks/motion_benchmark.py --node     # and trajectory_node as a process

Method. The machine is shared, so every timed case runs once per round, in a rotating order,
for ``--rounds`` rounds (interleaved: a slow moment hits every case alike), and the tables give
the median over the rounds with the range; the load average (1 minute) before and after is
printed with the core count. Baselines are measured in the same run.

The cases:

- the 10 s trajectory: 100 waypoints on slow waves around the home pose (up to 3 cm and 14
  degrees), within every example limit as timed. *Check as timed*: ``plan_motion`` without
  retiming, 10,001 samples against every limit; *retime*: ``plan_motion(retime_path=True)``:
  toppra, its local refinement, and the check of the result. The target of issue 20: both
  together under 100 ms (before: 82 to 123 ms).
- the 10^4 s trajectory: 1000 waypoints of slow waves over 10,000 s, as timed (256 samples per
  segment: 255,745 samples; before: 10^7 samples, 68 s) and retimed.
- invariance: retimed durations of one path given with other timings, densities and dwells.
- ``--node``: trajectory_node started as a process; the latency of a ``get_parameters`` request
  while it checks a million-sample trajectory, against the same requests to the idle node
  (target of issue 20: < 100 ms); and the time from SIGINT to the process's exit while it
  checks, against an idle node's (target: < 1 s).
- the streaming filter per command, against one single-pose inverse kinematics.
- retiming under a force limit (issue 29): the 10 s trajectory with config/example_masses.yaml
  and ``leg_force_max`` 125 N (the forces of its timing without that limit reach 144 N),
  against the same retiming without masses, in the same rounds: target at most 2x.
"""

import argparse
import math
import os
from pathlib import Path
import platform
import signal
import statistics
import sys
import time

import numpy as np

from stewart_kinematics import (
    CommandFilter,
    inverse_kinematics,
    limits,
    load_geometry,
    plan_motion,
    PoseTrajectory,
    Ramp,
)
from stewart_kinematics.model.rotations import euler_zyx_to_matrix, rotation_vector_to_matrix
from stewart_kinematics.parameters import (
    actuator_limits_from_settings,
    GeometrySettings,
    load_settings,
)

ROOT = Path(__file__).resolve().parent.parent
CONFIG = [ROOT / 'config' / 'paper_platform.yaml', ROOT / 'config' / 'example_limits.yaml']
VALIDATION_RATE = 1000.0
CHECK_TARGET = 0.100       # seconds: check and retime of the 10 s trajectory
RESPONSE_TARGET = 0.100    # seconds: a parameter request while a trajectory is checked
STOP_TARGET = 1.0          # seconds: SIGINT to exit while a trajectory is checked
FILTER_TARGET = 50e-6      # seconds per command
#: Issue 29: retiming under a force limit at most this many times the time without.
FORCE_RATIO_TARGET = 2.0
#: The push limit of that case, newtons: it binds on the 10 s trajectory with the example
#: masses (its timing without it needs 144 N; its static forces stay below 117.4 N).
FORCE_MAX = 125.0
COMMAND_PERIOD = 0.002
#: Points per second of leg_trajectory in the gated case (the shipped publish_rate), hertz.
PUBLISH_RATE = 50.0


def ten_second_trajectory(geometry):
    """Build 100 waypoints over 10 s, within the example limits as timed."""
    return waves(geometry, 10.0, 100)


def waves(geometry, duration, count):
    """``count`` waypoints of slow waves over ``duration`` seconds, at rest at both ends."""
    times = np.linspace(0.0, duration, count)
    # 1 - cos(k pi t / T): at rest at both ends, as the interpolation starts and ends.
    amplitudes = np.array([0.015, 0.015, 0.01, math.radians(4.0), math.radians(4.0),
                           math.radians(7.0)])
    harmonics = np.array([2, 3, 1, 2, 3, 1])
    wave = amplitudes * (1.0 - np.cos(np.outer(times, harmonics) * math.pi / duration))
    return PoseTrajectory.from_poses(times, geometry.home_pose + wave)


def table_3_path():
    """Build the paper's Table 3, one row a second, as the ramp plays it in 'table' mode."""
    rows = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0]).rows
    return PoseTrajectory.from_poses(np.arange(11.0), rows)


def interleaved(cases, rounds, cpu=None):
    """
    Time every case once per round, in a rotating order; return name -> list of seconds.

    :param cases: name -> function of no argument.
    :param cpu: a dict that receives name -> list of the process's CPU seconds per call (on
        a shared machine the wall time also counts the time spent waiting for a core).
    """
    names = list(cases)
    times = {name: [] for name in names}
    if cpu is not None:
        cpu.update({name: [] for name in names})
    for round_index in range(rounds):
        order = names[round_index % len(names):] + names[:round_index % len(names)]
        for name in order:
            start, start_cpu = time.perf_counter(), time.process_time()
            cases[name]()
            times[name].append(time.perf_counter() - start)
            if cpu is not None:
                cpu[name].append(time.process_time() - start_cpu)
    return times


def shown(seconds):
    """Format seconds as ms, us or s."""
    if seconds >= 1.0:
        return f'{seconds:.2f} s'
    return f'{seconds * 1e3:.1f} ms' if seconds >= 1e-3 else f'{seconds * 1e6:.1f} us'


def spread(values):
    """Return 'median (min-max)' of seconds."""
    return (f'{shown(statistics.median(values))} ({shown(min(values))} to '
            f'{shown(max(values))})')


def load():
    """Return the 1-minute load average and the core count, as text."""
    return f'load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores'


def core_benchmark(rounds):
    """Print the tables of the core cases; return the rows of the targets."""
    geometry = load_geometry(CONFIG)
    actuator_limits = actuator_limits_from_settings(load_settings(GeometrySettings, CONFIG))
    ten = ten_second_trajectory(geometry)
    long = waves(geometry, 1e4, 1000)
    plan_motion(ten, geometry, actuator_limits, retime_path=True)   # import toppra first
    massive = load_geometry(CONFIG + [ROOT / 'config' / 'example_masses.yaml']).with_limits(
        leg_force_max=FORCE_MAX)
    forced = plan_motion(ten, massive, actuator_limits, retime_path=True)
    assert forced.accepted, forced.reason
    given = plan_motion(ten, geometry, actuator_limits)
    retimed = plan_motion(ten, geometry, actuator_limits, retime_path=True)
    long_given = plan_motion(long, geometry, actuator_limits)
    long_retimed = plan_motion(long, geometry, actuator_limits, retime_path=True)
    for plan in (given, retimed, long_given, long_retimed):
        assert plan.accepted, plan.reason
    print(f'Before: {load()}')
    cases = {
        'check 10 s as timed': lambda: plan_motion(ten, geometry, actuator_limits),
        'retime 10 s': lambda: plan_motion(ten, geometry, actuator_limits, retime_path=True),
        # What trajectory_node does: the same, and every point of leg_trajectory (50 Hz, the
        # shipped publish_rate) checked as published by the command gate.
        'retime 10 s, points gated': lambda: plan_motion(
            ten, geometry, actuator_limits, retime_path=True, publish_rate=PUBLISH_RATE),
        # Issue 29: the same under leg_force_max with the example masses.
        'retime 10 s, force limit': lambda: plan_motion(
            ten, massive, actuator_limits, retime_path=True),
    }
    cpu = {}
    times = interleaved(cases, rounds, cpu)
    both = [a + b for a, b in zip(times['check 10 s as timed'], times['retime 10 s'])]
    both_cpu = [a + b for a, b in zip(cpu['check 10 s as timed'], cpu['retime 10 s'])]
    long_times = interleaved({
        'check 1e4 s as timed': lambda: plan_motion(long, geometry, actuator_limits),
        'retime 1e4 s': lambda: plan_motion(long, geometry, actuator_limits,
                                            retime_path=True)}, max(3, rounds // 4))
    samples = given.trajectory.sample_times(VALIDATION_RATE)
    baseline_samples = samples[::10]
    baseline_poses = given.trajectory.sample(baseline_samples)
    start = time.perf_counter()
    for position, rotation in zip(baseline_poses.positions, baseline_poses.rotations):
        limits.check_pose(geometry, position, rotation)
    per_pose = (time.perf_counter() - start) * samples.shape[0] / baseline_samples.shape[0]
    print(f'After: {load()}')
    print()
    print(f'| Case | Wall time: median ({rounds} interleaved rounds; range) | CPU time: median '
          '| Compared |')
    print('| --- | --- | --- | --- |')
    check = statistics.median(times['check 10 s as timed'])
    print(f'| 10 s, 100 waypoints: check as timed, {given.check.samples:,} samples, every '
          f'limit | {spread(times["check 10 s as timed"])} | '
          f'{shown(statistics.median(cpu["check 10 s as timed"]))} | {per_pose / check:.0f}x '
          f'faster than `limits.check_pose` per sample ({shown(per_pose)}) |')
    print(f'| 10 s, 100 waypoints: retime (toppra, refinement, check of the '
          f'{retimed.trajectory.duration:.2f} s result, {retimed.check.samples:,} samples) | '
          f'{spread(times["retime 10 s"])} | {shown(statistics.median(cpu["retime 10 s"]))} | |')
    gated = times['retime 10 s, points gated']
    print(f'| 10 s, 100 waypoints: retime, and each point of leg_trajectory at '
          f'{PUBLISH_RATE:g} Hz checked as published (the command gate) | {spread(gated)} | '
          f'{shown(statistics.median(cpu["retime 10 s, points gated"]))} | '
          f'{statistics.median(gated) / statistics.median(times["retime 10 s"]):.2f}x the retime '
          'alone |')
    forced_times = times['retime 10 s, force limit']
    ratio = statistics.median(forced_times) / statistics.median(times['retime 10 s'])
    print(f'| 10 s, 100 waypoints: retime under leg_force_max {FORCE_MAX:g} N with the example '
          f'masses (to {forced.trajectory.duration:.2f} s, peak force '
          f'{forced.check.peak_force_ratio * 100:.2f} % of the limit; target at most '
          f'{FORCE_RATIO_TARGET:g}x the retime without) | {spread(forced_times)} | '
          f'{shown(statistics.median(cpu["retime 10 s, force limit"]))} | {ratio:.2f}x the '
          'retime without masses |')
    print(f'| 10 s, 100 waypoints: check + retime (target < {CHECK_TARGET * 1e3:.0f} ms) | '
          f'{spread(both)} | {shown(statistics.median(both_cpu))} | '
          f'{sum(value < CHECK_TARGET for value in both)} of {rounds} rounds under the target '
          '(wall time) |')
    print(f'| 10^4 s, 1000 waypoints: check as timed, {long_given.check.samples:,} samples | '
          f'{spread(long_times["check 1e4 s as timed"])} | | before: 10^7 samples, 68 s |')
    print(f'| 10^4 s, 1000 waypoints: retime (to {long_retimed.trajectory.duration:.1f} s) and '
          f'check | {spread(long_times["retime 1e4 s"])} | | |')
    rows = [(f'check + retime of the 10 s trajectory < {CHECK_TARGET * 1e3:.0f} ms (wall)',
             statistics.median(both) < CHECK_TARGET, spread(both)),
            (f'check + retime of the 10 s trajectory < {CHECK_TARGET * 1e3:.0f} ms (CPU)',
             statistics.median(both_cpu) < CHECK_TARGET,
             f'{shown(statistics.median(both_cpu))} ({shown(min(both_cpu))} to '
             f'{shown(max(both_cpu))})')]
    rows.append((f'retime under a force limit at most {FORCE_RATIO_TARGET:g}x the time without',
                 ratio <= FORCE_RATIO_TARGET, f'{ratio:.2f}x'))
    rows.append(('check of the 10^4 s trajectory in seconds',
                 statistics.median(long_times['check 1e4 s as timed']) < 10.0,
                 spread(long_times['check 1e4 s as timed'])))

    command_filter = CommandFilter(actuator_limits, COMMAND_PERIOD, geometry.home_leg_lengths,
                                   geometry)
    rng = np.random.default_rng(0)
    targets = geometry.home_leg_lengths + rng.uniform(-0.02, 0.02, size=(200, 6))

    def stream():
        for index in range(10000):
            if index % 50 == 0:
                command_filter.set_target(targets[index // 50])
            command_filter.step()

    sent_filter = CommandFilter(actuator_limits, COMMAND_PERIOD, geometry.home_leg_lengths,
                                geometry)
    clock = [0.0]

    def sent():
        # What ik_node sends: the step at the node's clock, checked as sent by the command
        # gate (the pose of its lengths against every pose limit, the rates between steps).
        for index in range(1000):
            if index % 50 == 0:
                sent_filter.set_target(targets[index // 50])
            clock[0] += COMMAND_PERIOD
            sent_filter.send(clock[0])
    home = geometry.home_pose
    filter_times = interleaved({
        'filter': stream, 'sent': sent,
        'ik': lambda: [inverse_kinematics(geometry, home) for _ in range(10000)]}, 3)
    per_command = statistics.median(filter_times['filter']) / 10000
    per_sent = statistics.median(filter_times['sent']) / 1000
    per_ik = statistics.median(filter_times['ik']) / 10000
    print(f'| streaming filter, per command (ruckig, 6 legs; target < '
          f'{FILTER_TARGET * 1e6:.0f} us) | {shown(per_command)} | | {per_command / per_ik:.2f}x '
          f'one single-pose IK ({shown(per_ik)}) |')
    print(f'| streamed command as sent (the filter, then the command gate: forward kinematics '
          f'of the step and every pose limit; target < {FILTER_TARGET * 1e6:.0f} us) | '
          f'{shown(per_sent)} | | {per_sent / per_command:.0f}x the filter alone |')
    rows.append((f'streaming filter < {FILTER_TARGET * 1e6:.0f} us per command',
                 per_command < FILTER_TARGET, shown(per_command)))
    rows.append((f'streamed command as sent (filter + command gate) < '
                 f'{FILTER_TARGET * 1e6:.0f} us', per_sent < FILTER_TARGET, shown(per_sent)))
    print()
    ramp = table_3_path()
    ramp_given = plan_motion(ramp, geometry, actuator_limits)
    ramp_retimed = plan_motion(ramp, geometry, actuator_limits, retime_path=True)
    print('Table 3 ramp under config/example_limits.yaml '
          f'(leg_velocity_max {actuator_limits.velocity_max:g} m/s, leg_acceleration_max '
          f'{actuator_limits.acceleration_max:g} m/s^2)')
    for name, plan in (('rows 1 s apart, interpolated', ramp_given),
                       ('retimed (toppra)', ramp_retimed)):
        print(f'  {name:<34} {plan.trajectory.duration:6.2f} s, peak leg velocity '
              f'{plan.check.peak_velocity_ratio * 100:5.1f} % and acceleration '
              f'{plan.check.peak_acceleration_ratio * 100:5.1f} % of the limits')
    print()
    invariance(geometry, actuator_limits)
    return rows


def invariance(geometry, actuator_limits):
    """Print the retimed durations of paths given with other timings, densities and dwells."""
    home = geometry.home_pose
    lift = home + [0.0, 0.0, 0.05, 0.0, 0.0, 0.0]
    print('| Path (retimed under the example limits) | Given as | Retimed | Retiming time |')
    print('| --- | --- | --- | --- |')
    for seconds in (1.0, 6.0, 60.0, 1e4, 1e6):
        plan, spent = timed_plan(PoseTrajectory.from_poses([0.0, seconds], [home, lift]),
                                 geometry, actuator_limits)
        print(f'| 5 cm lift | 2 waypoints over {seconds:g} s | {plan.trajectory.duration:.4f} s '
              f'| {shown(spent)} |')
    offset = np.array([0.02, -0.015, 0.03, 0.05, -0.04, 0.1])
    start = euler_zyx_to_matrix(home[3:])
    rng = np.random.default_rng(1)
    for count in (2, 300, 1000, 10_000, 100_000):
        u = np.sort(np.concatenate([[0.0, 1.0], rng.uniform(0.0, 1.0, count - 2)]))
        positions = home[:3] + np.outer(u, offset[:3])
        rotations = start @ rotation_vector_to_matrix(np.outer(u, offset[3:]))
        plan, spent = timed_plan(PoseTrajectory(np.linspace(0.0, 10.0, count), positions,
                                                rotations), geometry, actuator_limits)
        print(f'| screw: 2 cm, 1.5 cm, 3 cm and 0.12 rad about one axis | {count:,} uneven '
              f'waypoints | {plan.trajectory.duration:.4f} s | {shown(spent)} |')
    for count in (100, 300, 1000, 10_000, 99_997):
        u = np.sort(np.concatenate([[0.0, 1.0], rng.uniform(0.0, 1.0, count - 2)]))
        poses = home + waves_at(u)
        dwell = rng.integers(0, count, 3)
        poses = np.insert(poses, dwell, poses[dwell], axis=0)
        times = np.cumsum(np.concatenate([[0.0], rng.uniform(0.1, 1.0, poses.shape[0] - 1)]))
        plan, spent = timed_plan(PoseTrajectory.from_poses(times * 1e3 / times[-1], poses),
                                 geometry, actuator_limits)
        print(f"| waves (the 10 s trajectory's curve) | {count:,} uneven waypoints, 3 dwells, "
              f'over 1000 s | {plan.trajectory.duration:.4f} s | {shown(spent)} |')
    print()


def waves_at(u):
    """Return the 10 s trajectory's offsets from home at fractions ``u`` of its duration."""
    amplitudes = np.array([0.015, 0.015, 0.01, math.radians(4.0), math.radians(4.0),
                           math.radians(7.0)])
    harmonics = np.array([2, 3, 1, 2, 3, 1])
    return amplitudes * (1.0 - np.cos(np.outer(u, harmonics) * math.pi))


def timed_plan(trajectory, geometry, actuator_limits):
    """Retime a trajectory; return the plan and the seconds it took."""
    start = time.perf_counter()
    plan = plan_motion(trajectory, geometry, actuator_limits, retime_path=True)
    assert plan.accepted, plan.reason
    return plan, time.perf_counter() - start


def node_benchmark(rounds):
    """Start trajectory_node processes; measure responses and stops; return target rows."""
    from stewart_kinematics.tools.node_processes import isolated_ros_environment, NodeProcess

    with isolated_ros_environment():
        import rclpy
        rclpy.init(args=[])
        try:
            return _node_benchmark(rclpy, NodeProcess, rounds)
        finally:
            rclpy.try_shutdown()


def _node_benchmark(rclpy, node_process, rounds):
    from rcl_interfaces.srv import GetParameters
    from rclpy.executors import SingleThreadedExecutor
    from trajectory_msgs.msg import MultiDOFJointTrajectory

    sys.path.insert(0, str(ROOT / 'test'))
    from test_motion_responsiveness import long_trajectory, node_args

    config = ROOT / 'config'
    client = rclpy.create_node('motion_benchmark')
    executor = SingleThreadedExecutor()
    executor.add_node(client)
    publisher = client.create_publisher(MultiDOFJointTrajectory, '/bench/pose_trajectory', 10)
    service = client.create_client(GetParameters, '/bench/trajectory_node/get_parameters')
    long = long_trajectory()

    def spin_until(condition, timeout=60.0):
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > deadline:
                raise RuntimeError('timed out')
            executor.spin_once(timeout_sec=0.01)

    def request():
        start = time.perf_counter()
        future = service.call_async(GetParameters.Request(names=['validation_rate']))
        spin_until(future.done)
        return time.perf_counter() - start

    idle, busy, idle_stops, busy_stops = [], [], [], []
    for _ in range(rounds):
        for checking in (False, True):
            node = node_process('trajectory_node', node_args(config, '/bench'))
            spin_until(lambda: publisher.get_subscription_count() >= 1
                       and service.service_is_ready())
            request()   # the first request sets up the connection: not counted
            if checking:
                publisher.publish(long)
                # Let it arrive and the check start: the check takes seconds.
                end = time.monotonic() + 1.0
                spin_until(lambda: time.monotonic() > end)
            latencies = busy if checking else idle
            for _ in range(10):
                latencies.append(request())
                end = time.monotonic() + 0.05
                spin_until(lambda: time.monotonic() > end)
            start = time.perf_counter()
            node.send_signal(signal.SIGINT)
            node.process.wait(30.0)
            (busy_stops if checking else idle_stops).append(time.perf_counter() - start)
            node.stop()
    client.destroy_node()
    print(f'trajectory_node as a process, {rounds} rounds, idle and checking a million-sample '
          f'trajectory in turn ({load()})')
    print()
    print('| Measure | Idle node | Node checking a 10^4 s trajectory (998,145 samples) |')
    print('| --- | --- | --- |')
    print(f'| get_parameters round trip, {len(busy)} requests: median, p95, max | '
          f'{percentiles(idle)} | {percentiles(busy)} |')
    print(f'| SIGINT to exit, {rounds} stops: median (range) | {spread(idle_stops)} | '
          f'{spread(busy_stops)} |')
    print()
    return [(f'parameter request answered < {RESPONSE_TARGET * 1e3:.0f} ms while checking '
             '(max)', max(busy) < RESPONSE_TARGET, percentiles(busy)),
            (f'SIGINT stops the node < {STOP_TARGET:g} s while checking (max)',
             max(busy_stops) < STOP_TARGET, spread(busy_stops))]


def percentiles(values):
    """Return 'median, p95, max' of seconds."""
    ordered = sorted(values)
    p95 = ordered[min(len(ordered) - 1, int(math.ceil(0.95 * len(ordered))) - 1)]
    return f'{shown(statistics.median(ordered))}, {shown(p95)}, {shown(ordered[-1])}'


def main(argv=None) -> int:
    """Print the tables and the targets; return 0."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--rounds', type=int, default=11, help='interleaved rounds')
    parser.add_argument('--node', action='store_true',
                        help='also measure trajectory_node as a process (ROS 2 needed)')
    arguments = parser.parse_args(argv)
    print(f'Motion benchmark: Python {platform.python_version()}, numpy {np.__version__}, '
          f'{platform.machine()}')
    rows = core_benchmark(arguments.rounds)
    if arguments.node:
        rows += node_benchmark(max(3, arguments.rounds // 2))
    print('| Target | Met | This run |')
    print('| --- | --- | --- |')
    for target, met, value in rows:
        print(f'| {target} | {"yes" if met else "**no**"} | {value} |')
    return 0


if __name__ == '__main__':
    sys.exit(main())
