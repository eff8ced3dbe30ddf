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
Benchmark the motion cueing: the core's step time and motion_cueing_node's loss-free rate.

Run from the repository root with ``.venv/bin/python benchmarks/cueing_benchmark.py`` (the
node part starts processes on an isolated ROS domain; ``--no-node`` skips it). Prints:

- the core step (:meth:`stewart_kinematics.cueing.MotionCueing.step`, shipped
  ``config/motion_cueing.yaml`` on the paper's platform with the example limits) over the four
  scenarios sampled at 1 kHz: median, p90 and p99 per sample, against the baseline of the
  same process, one call of the limits model's single-pose check
  (:func:`stewart_kinematics.limits.check_pose`, which every step makes once) and one
  single-pose inverse kinematics; and the same step with the limits check replaced by a
  stub, to show what the rest costs;
- the node: ``sensor_msgs/Imu`` published at rising rates for ``--seconds`` per rung (fresh,
  increasing stamps), ``target_pose`` counted; a rung is loss-free when every sample is
  answered. Its ladder is interleaved with the bare echo node's (``benchmarks/echo_node.py``,
  geometry_msgs/Pose in and out), the middleware's own limit, for the ratio; ``--rounds``
  rounds, the median decides;
- the targets of issue 23: core step under 100 us (median), node loss-free at 1 kHz (every
  round).

``--mpc`` measures the model-predictive cueing instead (``cueing_method: mpc``, issue 31): the
MPC's own step (:meth:`stewart_kinematics.cueing.mpc_cueing.MpcCueing.step_checked`: the QP
built, solved warm-started, the plan applied) over the lane change and the mixed drive at
100 Hz, median and p99 against the targets (2 ms, 5 ms); then the same recorded QPs solved
by DAQP, OSQP and ProxQP, each warm-started from its previous solution (median and p99 per
solve, iterations, failures, and the largest difference from DAQP's solution): the
measurement that chose the solver (doc/motion_cueing_mpc.md). OSQP and ProxQP come from
benchmarks/requirements.txt; a solver that is not installed is reported as such.
"""

import argparse
import math
import os
from pathlib import Path
import platform
import statistics
import sys
import time

import numpy as np

from stewart_kinematics import inverse_kinematics
from stewart_kinematics.cueing import cue_limiter, motion_cueing, MotionCueing
from stewart_kinematics.cueing.scenarios import scenario, SCENARIO_NAMES
from stewart_kinematics.limits import check_pose
from stewart_kinematics.model.rotations import euler_zyx_to_matrix
from stewart_kinematics.parameters import read_parameter_file
from stewart_kinematics.tools.node_processes import isolated_ros_environment, NodeProcess

ROOT = Path(__file__).resolve().parent.parent
FILES = [ROOT / 'config' / name for name in ('paper_platform.yaml', 'example_limits.yaml',
                                             'motion_cueing.yaml')]
STEP_TARGET = 100e-6
NODE_TARGET_RATE = 1000.0
LADDER = (500.0, 1000.0, 1500.0, 2000.0, 3000.0)
QUEUE_DEPTH = 100
#: The probe's receive queue: larger than a rung sends, so only the node can lose messages.
PROBE_RECEIVE_DEPTH = 20000
G = 9.80665


def cueing():
    """Return the core as motion_cueing_node builds it from the shipped files."""
    values = {}
    for path in FILES:
        values.update(read_parameter_file(path, 'motion_cueing_node'))
    return MotionCueing.from_parameters(values)


def step_times(rate=1000.0):
    """Time every step of the four scenarios at ``rate``; return seconds per sample."""
    times = []
    clock = time.perf_counter
    for name in SCENARIO_NAMES:
        generated = scenario(name, rate)
        core = cueing()
        for t, force, angular in zip(generated.times, generated.specific_force.tolist(),
                                     generated.angular_velocity.tolist()):
            start = clock()
            core.step(t, force, angular)
            times.append(clock() - start)
    return np.array(times)


def median_call(function, repeats=3000):
    """Return the median time of one call of ``function()``, seconds."""
    times = []
    clock = time.perf_counter
    for _ in range(repeats):
        start = clock()
        function()
        times.append(clock() - start)
    return statistics.median(times)


def core_benchmark():
    """Print the core's step times against the single-pose check and IK; return the median."""
    core = cueing()
    geometry = core.limiter.cue_geometry
    pose = core.geometry.home_pose + np.array([0.01, -0.02, 0.005, 0.02, -0.03, 0.01])
    rotation = euler_zyx_to_matrix(pose[3:])
    check = median_call(lambda: check_pose(geometry, pose[:3], rotation))
    ik = median_call(lambda: inverse_kinematics(core.geometry, pose))
    measured = step_times()
    original = cue_limiter.pose_violations
    cue_limiter.pose_violations = lambda *arguments: []
    try:
        unchecked = step_times()
    finally:
        cue_limiter.pose_violations = original
    median = float(np.median(measured))
    print(f'Core step, {measured.size:,} samples (four scenarios at 1 kHz), shipped tuning:')
    print(f'  step: median {median * 1e6:.1f} us, p90 {np.percentile(measured, 90) * 1e6:.1f} '
          f'us, p99 {np.percentile(measured, 99) * 1e6:.1f} us, max {measured.max() * 1e6:.0f} '
          'us')
    print(f'  baseline check_pose (limits model, one pose): {check * 1e6:.1f} us; step / '
          f'check_pose = {median / check:.2f}x')
    print(f'  baseline inverse kinematics (one pose): {ik * 1e6:.1f} us; step / IK = '
          f'{median / ik:.0f}x')
    print(f'  step with the limits check stubbed out: median '
          f'{np.median(unchecked) * 1e6:.1f} us ({np.median(unchecked) / check:.2f}x '
          'check_pose)')
    return median


class Probe:
    """The benchmark's node: publishes on one topic at a rate, counts arrivals on another."""

    def __init__(self, in_type, in_topic, out_type, out_topic):
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.node import Node
        self.node = Node('cueing_benchmark_probe_' + in_topic)
        self.executor = SingleThreadedExecutor(context=rclpy.get_default_context())
        self.executor.add_node(self.node)
        self.publisher = self.node.create_publisher(in_type, in_topic, QUEUE_DEPTH)
        self.node.create_subscription(out_type, out_topic, self.on_message, PROBE_RECEIVE_DEPTH)
        self.out_topic = self.node.resolve_topic_name(out_topic)
        self.arrivals = 0

    def on_message(self, _message):
        """Count one arrival."""
        self.arrivals += 1

    def connected(self):
        """Whether the node under test has matched the probe both ways."""
        self.executor.spin_once(timeout_sec=0.05)
        return (self.publisher.get_subscription_count() >= 1
                and self.node.count_publishers(self.out_topic) >= 1)

    def rung(self, messages, rate):
        """Publish ``messages`` at ``rate`` without receiving, then collect; return loss-free."""
        self.arrivals = 0
        period = 1.0 / rate
        clock = time.perf_counter
        publish = self.publisher.publish
        start = clock()
        for index, message in enumerate(messages):
            due = start + index * period
            while clock() < due:
                pass
            publish(message)
        end, quiet = time.monotonic() + 10.0, None
        last = -1
        while self.arrivals < len(messages) and time.monotonic() < end:
            self.executor.spin_once(timeout_sec=0.01)
            if self.arrivals != last:
                last, quiet = self.arrivals, time.monotonic() + 0.5
            elif time.monotonic() > quiet:
                break
        return self.arrivals == len(messages)


class ImuStream:
    """sensor_msgs/Imu samples of a scenario at 1 kHz, with stamps that always move forward."""

    def __init__(self, name='multi_sine'):
        generated = scenario(name, 1000.0)
        self.forces = generated.specific_force
        self.rates = generated.angular_velocity
        self.stamp_ns = 1_000_000_000
        self.index = 0

    def messages(self, rate, count):
        """Return ``count`` messages ``1 / rate`` apart, continuing the stream."""
        from sensor_msgs.msg import Imu
        step = int(round(1e9 / rate))
        out = []
        for _ in range(count):
            message = Imu()
            self.stamp_ns += step
            message.header.stamp.sec, message.header.stamp.nanosec = divmod(
                self.stamp_ns, 1_000_000_000)
            force = self.forces[self.index % len(self.forces)]
            rate = self.rates[self.index % len(self.rates)]
            self.index += 1
            (message.linear_acceleration.x, message.linear_acceleration.y,
             message.linear_acceleration.z) = force.tolist()
            (message.angular_velocity.x, message.angular_velocity.y,
             message.angular_velocity.z) = rate.tolist()
            out.append(message)
        return out


def node_benchmark(rounds, seconds, input_name='multi_sine'):
    """Print each node's loss-free rates; return the cueing node's per round and 1 kHz's."""
    import rclpy
    from geometry_msgs.msg import Pose
    from sensor_msgs.msg import Imu
    arguments = ['--ros-args']
    for path in FILES:
        arguments += ['--params-file', str(path)]
    arguments += ['-p', f'queue_depth:={QUEUE_DEPTH}', '-p', 'input_timeout:=0.0']
    with isolated_ros_environment() as domain:
        print(f'\nNode: loss-free rate, {input_name} sampled at each rung, {rounds} rounds, '
              f'{seconds:g} s a rung, ROS_DOMAIN_ID {domain}')
        processes = [
            NodeProcess('motion_cueing_node', arguments),
            NodeProcess(sys.executable, [str(Path(__file__).with_name('echo_node.py')),
                                         '--ros-args', '-p', f'queue_depth:={QUEUE_DEPTH}']),
        ]
        rclpy.init()
        try:
            cueing_probe = Probe(Imu, 'vehicle_imu', Pose, 'target_pose')
            echo_probe = Probe(Pose, 'echo_in', Pose, 'echo_out')
            deadline = time.monotonic() + 30.0
            while not (cueing_probe.connected() and echo_probe.connected()):
                if time.monotonic() > deadline or not all(p.running() for p in processes):
                    raise RuntimeError('nodes did not connect: ' + ' '.join(
                        p.output()[-400:] for p in processes))
            stream = ImuStream(input_name)
            pose = Pose()
            cueing_probe.rung(stream.messages(200.0, 200), 200.0)  # warm-up
            best = {'motion_cueing_node': [], 'echo node': []}
            at_target = []
            for index in range(rounds):
                # Each node climbs the ladder until its first loss; the rungs interleave.
                highest = dict.fromkeys(best, 0.0)
                stopped = set()
                for rate in LADDER:
                    count = int(rate * seconds)
                    for name, probe, messages in (
                            ('motion_cueing_node', cueing_probe, stream.messages(rate, count)),
                            ('echo node', echo_probe, [pose] * count)):
                        if name in stopped:
                            continue
                        ok = probe.rung(messages, rate)
                        if ok:
                            highest[name] = rate
                        else:
                            stopped.add(name)
                        time.sleep(0.2)
                for name in best:
                    best[name].append(highest[name])
                at_target.append(highest['motion_cueing_node'] >= NODE_TARGET_RATE)
                print(f'  round {index + 1}: motion_cueing_node loss-free up to '
                      f'{best["motion_cueing_node"][-1]:,.0f} Hz, echo node '
                      f'{best["echo node"][-1]:,.0f} Hz (ladder '
                      f'{", ".join(f"{rate:g}" for rate in LADDER)} Hz)')
        finally:
            rclpy.try_shutdown()
            for process in processes:
                process.stop()
    cueing_rate = statistics.median(best['motion_cueing_node'])
    echo_rate = statistics.median(best['echo node'])
    print(f'  median: motion_cueing_node {cueing_rate:,.0f} Hz, echo node {echo_rate:,.0f} Hz: '
          f'{cueing_rate / echo_rate:.2f}x echo' if echo_rate else '')
    return at_target


MPC_SCENARIOS = ('lane_change', 'mixed_drive')
MPC_MEDIAN_TARGET = 2e-3
MPC_P99_TARGET = 5e-3


def mpc_cueing(extra_files=(), preview=None):
    """
    Return the core from the shipped files, then ``extra_files``, with ``cueing_method: mpc``.

    :param preview: a scenario whose whole input the core is told (``set_preview``), or None.
    """
    values = {}
    for path in tuple(FILES) + tuple(extra_files):
        values.update(read_parameter_file(path, 'motion_cueing_node'))
    values['cueing_method'] = 'mpc'
    core = MotionCueing.from_parameters(values)
    if preview is not None:
        core.set_preview(preview.times, preview.specific_force, preview.angular_velocity)
    return core


def mpc_steps(rate=100.0, extra_files=(), preview=False):
    """
    Run the MPC scenarios; return the MPC step's seconds per sample and the QPs solved.

    With ``preview``, each scenario's input is the core's preview, and the step's time
    includes the preview's means over the horizon (``vehicle_preview.interval_means``, computed
    by the core before the MPC's step).
    """
    times, problems = [], []
    clock = time.perf_counter
    for name in MPC_SCENARIOS:
        generated = scenario(name, rate)
        core = mpc_cueing(extra_files, generated if preview else None)
        mpc = core.washout
        step = mpc.step_checked
        solve = mpc.solver.solve

        def recording_solve(*problem, solve=solve):
            problems.append(tuple(np.array(part) for part in problem))
            return solve(*problem)

        def timed_step(*arguments, step=step):
            start = clock()
            result = step(*arguments)
            times.append(clock() - start)
            return result

        mpc.solver.solve = recording_solve
        mpc.step_checked = timed_step
        for t, force, angular in zip(generated.times, generated.specific_force.tolist(),
                                     generated.angular_velocity.tolist()):
            core.step(t, force, angular)
        hessian = mpc.hessian
    # Recording the problems costs copies: time the step again without it, in wall-clock time
    # and in the thread's CPU time (which a busy machine's preemption does not inflate).
    times, cpu_times = [], []
    cpu_clock = time.thread_time
    means = motion_cueing.interval_means
    for name in MPC_SCENARIOS:
        generated = scenario(name, rate)
        core = mpc_cueing(extra_files, generated if preview else None)
        step = core.washout.step_checked
        started = []

        def timed_means(*arguments):
            started.append((clock(), cpu_clock()))
            return means(*arguments)

        def timed_step(*arguments, step=step):
            start, cpu_start = started.pop() if started else (clock(), cpu_clock())
            result = step(*arguments)
            times.append(clock() - start)
            cpu_times.append(cpu_clock() - cpu_start)
            return result

        core.washout.step_checked = timed_step
        motion_cueing.interval_means = timed_means
        try:
            for t, force, angular in zip(generated.times, generated.specific_force.tolist(),
                                         generated.angular_velocity.tolist()):
                core.step(t, force, angular)
        finally:
            motion_cueing.interval_means = means
    return np.array(times[1:]), np.array(cpu_times[1:]), problems, hessian


class _Osqp:
    """OSQP (sparse ADMM), warm-started, the constraint matrix's values updated each QP."""

    name = 'OSQP'

    def __init__(self, hessian):
        import osqp
        from scipy import sparse
        self.osqp, self.sparse = osqp, sparse
        self.hessian = sparse.triu(sparse.csc_matrix(hessian), format='csc')
        self.solver = None

    def solve(self, gradient, a, lower, upper, bounds_lower, bounds_upper):
        full = np.vstack([np.eye(a.shape[1]), a])
        low = np.concatenate([bounds_lower, lower])
        high = np.concatenate([bounds_upper, upper])
        matrix = self.sparse.csc_matrix(np.where(full == 0.0, 1e-300, full))
        if self.solver is None:
            self.solver = self.osqp.OSQP()
            self.solver.setup(self.hessian, gradient, matrix, low, high, verbose=False,
                              warm_starting=True, eps_abs=1e-6, eps_rel=1e-6, max_iter=4000,
                              polishing=True)
        else:
            self.solver.update(q=gradient, l=low, u=high, Ax=matrix.data)
        result = self.solver.solve()
        solved = result.info.status_val in (1, 2)
        return result.x, solved, result.info.iter


class _ProxQp:
    """ProxQP (dense proximal augmented Lagrangian), warm-started with its previous result."""

    name = 'ProxQP'

    def __init__(self, hessian):
        import proxsuite
        self.proxsuite = proxsuite
        self.hessian = hessian
        self.qp = None

    def solve(self, gradient, a, lower, upper, bounds_lower, bounds_upper):
        proxqp = self.proxsuite.proxqp
        if self.qp is None:
            self.qp = proxqp.dense.QP(a.shape[1], 0, a.shape[0], True)
            self.qp.settings.eps_abs = 1e-6
            self.qp.settings.initial_guess = proxqp.InitialGuess.WARM_START_WITH_PREVIOUS_RESULT
            self.qp.init(self.hessian, gradient, None, None, a, lower, upper, bounds_lower,
                         bounds_upper)
        else:
            self.qp.update(None, gradient, None, None, a, lower, upper, bounds_lower,
                           bounds_upper)
        self.qp.solve()
        status = self.qp.results.info.status
        return (np.array(self.qp.results.x), status == proxqp.QPSolverOutput.PROXQP_SOLVED,
                self.qp.results.info.iter)


class _Daqp:
    """DAQP (dual active set), the package's own wrapper, every row hard."""

    name = 'DAQP'

    def __init__(self, hessian):
        from stewart_kinematics.cueing.qp_solver import QpSolver
        self.solver = QpSolver(hessian)

    def solve(self, *problem):
        result = self.solver.solve(*problem)
        return result.x, result.solved, result.iterations


def mpc_benchmark(extra_files=(), preview=False):
    """Print the MPC step's cost and the solvers' comparison; return (median, p99)."""
    measured, cpu, problems, hessian = mpc_steps(extra_files=extra_files, preview=preview)
    median, p99 = float(np.median(cpu)), float(np.percentile(cpu, 99))
    load = os.getloadavg()[0] if hasattr(os, 'getloadavg') else math.nan
    tuning = ' + '.join(['shipped mpc_* tuning'] + [str(path) for path in extra_files])
    print(f'MPC step{" with the preview" if preview else ""}, {measured.size:,} samples '
          f'({", ".join(MPC_SCENARIOS)} at 100 Hz), {tuning}: {problems[0][1].shape[1]} '
          f'variables, {problems[0][1].shape[0]} constraint rows + bounds')
    print(f'  step, CPU time: median {median * 1e3:.3f} ms, p90 '
          f'{np.percentile(cpu, 90) * 1e3:.3f} ms, p99 {p99 * 1e3:.3f} ms, max '
          f'{cpu.max() * 1e3:.2f} ms')
    print(f'  step, wall clock: median {np.median(measured) * 1e3:.3f} ms, p90 '
          f'{np.percentile(measured, 90) * 1e3:.3f} ms, p99 '
          f'{np.percentile(measured, 99) * 1e3:.3f} ms, max {measured.max() * 1e3:.2f} ms '
          f'(load average {load:.1f} on {os.cpu_count()} cores: preemption shows here)')
    print(f'Solvers on the same {len(problems):,} QPs, warm-started (every row hard), CPU '
          'time per solve:')
    reference = None
    for kind in (_Daqp, _Osqp, _ProxQp):
        try:
            solver = kind(hessian)
        except ImportError as error:
            print(f'  {kind.name}: not installed ({error})')
            continue
        times, iterations, failures, solutions = [], [], 0, []
        for problem in problems:
            start = time.thread_time()
            x, solved, count = solver.solve(*problem)
            times.append(time.thread_time() - start)
            iterations.append(count)
            failures += not solved
            solutions.append(x if solved else None)
        if reference is None:
            reference = solutions
        differences = [float(np.max(np.abs(x - y))) for x, y in zip(solutions, reference)
                       if x is not None and y is not None]
        times = np.array(times[1:])
        print(f'  {kind.name:6}: median {np.median(times) * 1e3:.3f} ms, p99 '
              f'{np.percentile(times, 99) * 1e3:.3f} ms, max {times.max() * 1e3:.2f} ms; '
              f'iterations median {np.median(iterations):.0f}; failures {failures}; '
              f'largest difference from DAQP {max(differences, default=math.nan):.2g}')
    return median, p99


def main(argv=None) -> int:
    """Run the benchmarks and print the targets; return 0."""
    parser = argparse.ArgumentParser(description='Motion cueing benchmark (issue 23).')
    parser.add_argument('--no-node', action='store_true', help='core only, no processes')
    parser.add_argument('--no-core', action='store_true', help='node only')
    parser.add_argument('--node-scenario', choices=SCENARIO_NAMES, default='multi_sine',
                        help="the node's input (default multi_sine; the lap's road noise "
                             'makes most of its 1 kHz steps actuator-limited)')
    parser.add_argument('--rounds', type=int, default=3, help='node rounds (default 3)')
    parser.add_argument('--seconds', type=float, default=2.0,
                        help='seconds per rung (default 2)')
    parser.add_argument('--mpc', action='store_true',
                        help='the model-predictive cueing and its solvers only (issue 31)')
    parser.add_argument('--params-file', dest='params_files', action='append', default=[],
                        type=Path, help='with --mpc: a parameter file layered after the '
                        'shipped ones (config/motion_cueing_preview.yaml); repeat to layer')
    parser.add_argument('--preview', action='store_true',
                        help="with --mpc: tell the MPC each scenario's input to come")
    options = parser.parse_args(argv)
    if options.mpc:
        median, p99 = mpc_benchmark(options.params_files, options.preview)
        print()
        print(f'{"Target":<44} {"Met":>4}  This run')
        for label, value, target in (('MPC step < 2 ms (median, CPU)', median, MPC_MEDIAN_TARGET),
                                     ('MPC step < 5 ms (p99, CPU)', p99, MPC_P99_TARGET)):
            print(f'{label:<44} {"yes" if value < target else "no":>4}  {value * 1e3:.3f} ms')
        return 0
    print(f'Motion cueing benchmark: Python {platform.python_version()}, numpy '
          f'{np.__version__}, {platform.machine()}')
    median = None if options.no_core else core_benchmark()
    at_target = None if options.no_node else node_benchmark(
        options.rounds, options.seconds, options.node_scenario)
    print()
    print(f'{"Target":<44} {"Met":>4}  This run')
    if median is not None:
        print(f'{"core step < 100 us (median)":<44} '
              f'{"yes" if median < STEP_TARGET else "no":>4}  {median * 1e6:.1f} us')
    if at_target is not None:
        met = bool(at_target) and all(at_target)
        print(f'{"node loss-free at 1 kHz (every round)":<44} {"yes" if met else "no":>4}  '
              f'{sum(at_target)} of {len(at_target)} rounds loss-free at 1,000 Hz')
    return 0


if __name__ == '__main__':
    sys.exit(main())
