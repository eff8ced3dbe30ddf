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
Benchmark the kinematics and the nodes against baselines measured in the same run.

Run with ``scripts/run_benchmarks.sh`` (sets up the venv, the baseline packages and the ROS
environment). Prints one table: medians, rates and the ratio of each against its baseline,
success rates and worst errors, and which targets of the benchmark issue are met.

Poses: the paper's Table 3 ramp (11 rows) plus random poses within +-0.1 m and +-15 degrees
of the home pose; tracking: the same ramp played over 10 s at 1 kHz, each solve starting from
the previous solution. A solve succeeds when it reports convergence and its pose is within
1e-4 (m and rad, the paper's tolerance) of the true one; the worst error is over all poses.
"""

import argparse
import math
from pathlib import Path
import platform
import statistics
import sys
import time
import warnings

import numpy as np

from stewart_kinematics import forward_kinematics, inverse_kinematics
from stewart_kinematics.parameter_spec import load_geometry
from stewart_kinematics.rotations import euler_zyx_to_matrix, rotation_angle_between
from stewart_kinematics.tools.node_processes import isolated_ros_environment, NodeProcess
from stewart_kinematics.trajectory import Ramp

ROOT = Path(__file__).resolve().parent.parent
PLATFORM_FILE = ROOT / 'config' / 'paper_platform.yaml'
SOLVER_FILE = ROOT / 'config' / 'solver.yaml'
#: Half-widths of the random workspace around the home pose: metres, then radians.
WORKSPACE = np.array([0.1, 0.1, 0.1] + [math.radians(15.0)] * 3)
#: The paper's Newton-Raphson stopping tolerance, and the step of its finite differences.
PAPER_TOLERANCE = 1e-4
FINITE_DIFFERENCE_STEP = 1e-6
#: Iteration cap of basic-robotics' compiled FK here (its own default, 10000, takes 30 ms on
#: every pose it does not solve, which would not fit in the time budget).
BASIC_ROBOTICS_MAX_ITERATIONS = 200
#: The required accuracy of our solvers, metres and radians.
REQUIRED_ERROR = 1e-9
#: Node benchmark: queue depth, latency rate and duration, the rates stepped through.
QUEUE_DEPTH = 100
LATENCY_RATE = 200.0
LATENCY_SECONDS = 3.0
RATES = (250.0, 500.0, 750.0, 1000.0, 1250.0, 1500.0, 1750.0, 2000.0, 2500.0, 3000.0)
RATE_SECONDS = 2.0
#: The chain of both nodes: latency of a pose to the pose fk_node finds for its leg lengths.
CHAIN = 'ik_node -> fk_node'


def median_seconds(call, items, repeat=1):
    """Median wall time of ``call(item)`` over the items (each timed alone), seconds."""
    times = []
    clock = time.perf_counter
    for _ in range(repeat):
        for item in items:
            start = clock()
            call(item)
            times.append(clock() - start)
    return statistics.median(times)


def best_seconds(call, repeat=5):
    """Best of ``repeat`` wall times of ``call()``, seconds (for batches)."""
    best = math.inf
    for _ in range(repeat):
        start = time.perf_counter()
        call()
        best = min(best, time.perf_counter() - start)
    return best


def pose_errors(geometry, poses, truth):
    """Largest position (m) and rotation (rad) error of each pose, as one max per pose."""
    poses, truth = np.atleast_2d(poses), np.atleast_2d(truth)
    finite = np.all(np.isfinite(poses), axis=-1)
    errors = np.full(len(poses), np.inf)
    position = np.linalg.norm(poses[finite, :3] - truth[finite, :3], axis=-1)
    angle = rotation_angle_between(euler_zyx_to_matrix(poses[finite, 3:]),
                                   euler_zyx_to_matrix(truth[finite, 3:]))
    errors[finite] = np.maximum(position, angle)
    return errors


class PaperNewtonRaphson:
    """The paper's method: Newton-Raphson, forward-difference Jacobian, stop at 1e-4."""

    name = 'paper NR (finite-difference J, 1e-4)'

    def __init__(self, geometry, max_iterations=50):
        self.geometry = geometry
        self.max_iterations = max_iterations

    def solve(self, lengths, guess):
        """Return ``(pose, converged)``."""
        pose = np.array(guess, dtype=float)
        for _ in range(self.max_iterations + 1):
            current = inverse_kinematics(self.geometry, pose)
            error = current - lengths
            if np.max(np.abs(error)) <= PAPER_TOLERANCE:
                return pose, True
            jac = np.empty((6, 6))
            for axis in range(6):
                shifted = pose.copy()
                shifted[axis] += FINITE_DIFFERENCE_STEP
                jac[:, axis] = (inverse_kinematics(self.geometry, shifted) - current) \
                    / FINITE_DIFFERENCE_STEP
            pose = pose - np.linalg.solve(jac, error)
        return pose, False


class ScipyRoot:
    """scipy.optimize.root with MINPACK's hybrid method, default tolerances."""

    name = "scipy.optimize.root('hybr')"

    def __init__(self, geometry):
        from scipy.optimize import root
        self.root = root
        self.geometry = geometry

    def solve(self, lengths, guess):
        """Return ``(pose, converged)``."""
        result = self.root(lambda x: inverse_kinematics(self.geometry, x) - lengths, guess,
                           method='hybr')
        return result.x, bool(result.success)


class Ours:
    """This package's forward_kinematics, default tolerance 1e-12."""

    name = 'stewart_kinematics'

    def __init__(self, geometry):
        self.geometry = geometry

    def solve(self, lengths, guess):
        """Return ``(pose, converged)``."""
        result = forward_kinematics(self.geometry, lengths, guess)
        return result.pose, result.converged

    def track(self, lengths, last):
        """
        Return ``(result, converged)``, starting from the last result (or a pose).

        Tracking as its documentation says and fk_node does: the last result as the guess,
        so that its Jacobian is reused.
        """
        result = forward_kinematics(self.geometry, lengths, last)
        return result, result.converged


class BasicRobotics:
    """basic-robotics 1.0.2: its SP class, set to the paper's platform."""

    name = 'basic-robotics SP'

    def __init__(self, geometry):
        with warnings.catch_warnings():
            warnings.simplefilter('ignore')
            from basic_robotics.general import faser_high_performance, tm
            from basic_robotics.kinematics import SP
        self.tm = tm
        self.kernel = faser_high_performance.SPFKinSpaceR
        # Joints as columns (3, 6) in metres; base plate at the origin; top plate at the home
        # pose. Its IK puts top joints in the top plate's frame, as ours does.
        self.sp = SP(geometry.base_joints.T.copy(), geometry.platform_joints.T.copy(), tm(),
                     self.transform(geometry.home_pose), 0.0, 2.0, 0.0, 0.0, 'paper')
        home_lengths = self.ik(self.transform(geometry.home_pose))
        mismatch = np.max(np.abs(home_lengths - geometry.home_leg_lengths))
        if mismatch > 1e-12:
            raise RuntimeError(f'its home leg lengths differ from ours by {mismatch:.3g} m')

    def transform(self, pose):
        """Its transform object (tm) of one of our poses."""
        matrix = np.eye(4)
        matrix[:3, :3] = euler_zyx_to_matrix(pose[3:])
        matrix[:3, 3] = pose[:3]
        return self.tm(matrix)

    def ik(self, top):
        """Leg lengths by SP.IK of a prepared transform (validation off: protect=True)."""
        return self.sp.IK(top_plate_pos=top, protect=True)[0].reshape(6)

    def fk_guess(self, pose):
        """Its pose vector: translation and axis-angle (TAA)."""
        return self.transform(pose).gTAA().reshape(6).astype(float)

    def fk(self, lengths, guess):
        """Its compiled Newton-Raphson (SPFKinSpaceR) from a TAA guess: ``(TAA, converged)``."""
        sp = self.sp
        taa, iterations = self.kernel(
            np.array(lengths, dtype=float), guess.copy(), sp._bottom_joints_init,
            sp._top_joints_init, BASIC_ROBOTICS_MAX_ITERATIONS, sp._tol_f, sp._tol_a,
            sp.leg_ext_min)
        return taa, iterations < BASIC_ROBOTICS_MAX_ITERATIONS

    def taa_to_pose(self, taa):
        """One of our poses from its TAA (Euler angles from its rotation matrix)."""
        from stewart_kinematics.rotations import matrix_to_euler_zyx
        if not np.all(np.isfinite(taa)):
            return np.full(6, np.nan)
        matrix = self.tm(np.array(taa, dtype=float)).gTM()
        return np.concatenate([matrix[:3, 3], matrix_to_euler_zyx(matrix[:3, :3])])


class Table:
    """Rows of the results table, printed as Markdown."""

    def __init__(self):
        self.rows = []
        self.targets = []

    def add(self, *cells):
        """Add one row: what, solver, median/rate, ratio, success, worst error."""
        self.rows.append(cells)

    def target(self, text, met, detail):
        """Record one target of the issue and whether this run met it."""
        self.targets.append((text, met, detail))

    def show(self):
        """Print the table and the targets."""
        header = ('Benchmark', 'Solver', 'Median / rate', 'Ratio (same run)', 'Success',
                  'Worst error')
        print('| ' + ' | '.join(header) + ' |')
        print('| ' + ' | '.join('---' for _ in header) + ' |')
        for row in self.rows:
            print('| ' + ' | '.join(str(cell) for cell in row) + ' |')
        print()
        print('| Target | Met | This run |')
        print('| --- | --- | --- |')
        for text, met, detail in self.targets:
            print(f'| {text} | {"yes" if met else "**no**"} | {detail} |')


def microseconds(seconds):
    """Format a duration in microseconds."""
    return f'{seconds * 1e6:.1f} us'


def success_cell(converged, errors):
    """Success rate and worst error cells."""
    ok = np.asarray(converged) & (np.asarray(errors) <= PAPER_TOLERANCE)
    return f'{100.0 * ok.mean():.1f} % of {len(ok)}', f'{np.max(errors):.1e}'


def run_solver(solver, lengths, guesses, truth, geometry, convert=None):
    """Solve each pose once, timing each: ``(median seconds, converged, errors)``."""
    times, poses, converged = [], [], []
    for target, guess in zip(lengths, guesses):
        start = time.perf_counter()
        pose, ok = solver(target, guess)
        times.append(time.perf_counter() - start)
        poses.append(convert(pose) if convert else pose)
        converged.append(ok)
    return (statistics.median(times), np.array(converged),
            pose_errors(geometry, np.array(poses), truth))


def run_tracking(solver, lengths, first_guess, truth, geometry, convert=None, to_guess=None):
    """Track along a ramp, each solve starting from the previous solution."""
    times, poses, converged = [], [], []
    guess = first_guess
    for target in lengths:
        start = time.perf_counter()
        pose, ok = solver(target, guess)
        times.append(time.perf_counter() - start)
        guess = pose if ok else first_guess
        poses.append(convert(pose) if convert else pose)
        converged.append(ok)
    return (statistics.median(times), np.array(converged),
            pose_errors(geometry, np.array(poses), truth))


def kinematics_benchmarks(table, geometry, random_count, batch_count):
    """IK and FK, one pose, tracking and batches, against the baselines."""
    ramp = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])
    rng = np.random.default_rng(20260101)
    random_poses = geometry.home_pose + rng.uniform(-1.0, 1.0, (random_count, 6)) * WORKSPACE
    poses = np.concatenate([ramp.rows, random_poses])
    lengths = inverse_kinematics(geometry, poses)
    home = geometry.home_pose
    cold_guesses = [home] * len(poses)
    tracking = ramp.sample(np.arange(10001) * 1e-3, 10.0)
    tracking_lengths = inverse_kinematics(geometry, tracking)
    print(f'poses: {len(ramp.rows)} Table 3 rows + {random_count} random '
          f'(+-0.1 m, +-15 deg); tracking: {len(tracking)} ramp samples at 1 kHz',
          file=sys.stderr)

    try:
        basic = BasicRobotics(geometry)
        basic_error = ''
    except Exception as error:  # noqa: B902 - any failure to install or import is reported
        basic, basic_error = None, f'not installable: {type(error).__name__}: {error}'

    # IK, one pose.
    ours_ik = median_seconds(lambda pose: inverse_kinematics(geometry, pose), poses, repeat=5)
    ik_error = np.max(np.abs(np.array([inverse_kinematics(geometry, p) for p in poses])
                             - lengths))
    if basic:
        transforms = [basic.transform(pose) for pose in poses]
        basic_ik = median_seconds(basic.ik, transforms)
        basic_ik_error = np.max(np.abs(np.array([basic.ik(t) for t in transforms]) - lengths))
        table.add('IK one pose', 'basic-robotics SP.IK (protect=True)', microseconds(basic_ik),
                  '1.00', '100.0 %', f'{basic_ik_error:.1e} m')
        ratio = basic_ik / ours_ik
        table.add('IK one pose', 'stewart_kinematics', microseconds(ours_ik),
                  f'{ratio:.1f}x faster', f'100.0 % of {len(poses)}', f'{ik_error:.1e} m')
        table.target('IK one pose >= 10x faster than basic-robotics SP.IK', ratio >= 10.0,
                     f'{ratio:.1f}x')
    else:
        table.add('IK one pose', 'basic-robotics SP.IK', basic_error, '', '', '')
        table.add('IK one pose', 'stewart_kinematics', microseconds(ours_ik), '', '100.0 %',
                  f'{ik_error:.1e} m')
        table.target('IK one pose >= 10x faster than basic-robotics SP.IK', False, basic_error)

    # IK batch.
    batch = geometry.home_pose + rng.uniform(-1.0, 1.0, (batch_count, 6)) * WORKSPACE
    batch_rate = batch_count / best_seconds(lambda: inverse_kinematics(geometry, batch))
    single_rate = 1.0 / ours_ik
    batch_error = np.max(np.abs(inverse_kinematics(geometry, poses) - lengths))
    table.add('IK batch', 'stewart_kinematics, one pose per call', f'{single_rate:,.0f} /s',
              '1.00', '100.0 %', '')
    if basic:
        table.add('IK batch', 'basic-robotics SP.IK, one pose per call',
                  f'{1.0 / basic_ik:,.0f} /s', f'{basic_ik * single_rate:.2f}', '100.0 %', '')
    table.add('IK batch', f'stewart_kinematics, {batch_count:,} poses in one call',
              f'{batch_rate:,.0f} /s', f'{batch_rate / single_rate:.0f}x', '100.0 %',
              f'{batch_error:.1e} m')
    table.target('IK batch > 2 000 000 poses/s', batch_rate > 2e6, f'{batch_rate:,.0f} /s')

    # FK cold, from the home pose.
    ours = Ours(geometry)
    paper = PaperNewtonRaphson(geometry)
    scipy_root = ScipyRoot(geometry)
    cold = {}
    for solver in (paper, scipy_root, ours):
        cold[solver.name] = run_solver(solver.solve, lengths, cold_guesses, poses, geometry)
    if basic:
        home_taa = basic.fk_guess(home)
        cold[basic.name] = run_solver(basic.fk, lengths, [home_taa] * len(poses), poses,
                                      geometry, basic.taa_to_pose)
    ours_cold = cold[ours.name][0]
    scipy_cold = cold[scipy_root.name][0]
    for name, (median, converged, errors) in cold.items():
        label = f'{name} compiled FK (SPFKinSpaceR)' if basic and name == basic.name else name
        table.add('FK cold (from home)', label, microseconds(median),
                  f'{median / ours_cold:.2f}x ours' if name != ours.name else '1.00',
                  *success_cell(converged, errors))
    if not basic:
        table.add('FK cold (from home)', 'basic-robotics SP', basic_error, '', '', '')
    table.target("FK cold >= 5x faster than scipy's root", scipy_cold / ours_cold >= 5.0,
                 f'{scipy_cold / ours_cold:.1f}x')
    if basic:
        basic_cold = cold[basic.name][0]
        table.target("FK cold no slower than basic-robotics' compiled FK",
                     ours_cold <= basic_cold,
                     f'ours {microseconds(ours_cold)}, basic-robotics '
                     f'{microseconds(basic_cold)} ({basic_cold / ours_cold:.2f}x)')
    else:
        table.target("FK cold no slower than basic-robotics' compiled FK", False, basic_error)

    # FK warm, tracking the ramp at 1 kHz.
    warm = {}
    for solver in (paper, scipy_root):
        warm[solver.name] = run_tracking(solver.solve, tracking_lengths, home, tracking,
                                         geometry)
    warm[ours.name] = run_tracking(ours.track, tracking_lengths, home, tracking, geometry,
                                   convert=lambda result: result.pose)
    if basic:
        warm[basic.name] = run_tracking(basic.fk, tracking_lengths, home_taa, tracking,
                                        geometry, basic.taa_to_pose)
    ours_warm = warm[ours.name][0]
    for name, (median, converged, errors) in warm.items():
        table.add('FK warm (tracking)', name, microseconds(median),
                  f'{median / ours_warm:.2f}x ours' if name != ours.name
                  else f'{ours_cold / ours_warm:.2f}x faster than ours cold',
                  *success_cell(converged, errors))
    table.target('FK warm >= 2x faster than FK cold', ours_cold / ours_warm >= 2.0,
                 f'{ours_cold / ours_warm:.2f}x')

    # FK batch.
    fk_batch = forward_kinematics(geometry, lengths)
    fk_rate = len(poses) / best_seconds(lambda: forward_kinematics(geometry, lengths), 3)
    fk_errors = pose_errors(geometry, fk_batch.pose, poses)
    table.add('FK batch', 'stewart_kinematics, one pose per call',
              f'{1.0 / ours_cold:,.0f} /s', '1.00', '', '')
    table.add('FK batch', 'scipy root, one pose per call', f'{1.0 / scipy_cold:,.0f} /s',
              f'{ours_cold / scipy_cold:.2f}', '', '')
    table.add('FK batch', f'stewart_kinematics, {len(poses):,} poses in one call',
              f'{fk_rate:,.0f} /s', f'{fk_rate * ours_cold:.1f}x',
              *success_cell(fk_batch.converged, fk_errors))
    table.target('FK batch > 100 000 poses/s', fk_rate > 1e5, f'{fk_rate:,.0f} /s')

    ours_errors = [cold[ours.name], warm[ours.name], (0, fk_batch.converged, fk_errors)]
    all_converged = all(np.all(entry[1]) for entry in ours_errors)
    worst = max(float(np.max(entry[2])) for entry in ours_errors)
    worst = max(worst, ik_error, batch_error)
    table.target('100 % convergence, error < 1e-9 (ours, every benchmark)',
                 all_converged and worst < REQUIRED_ERROR,
                 f'{"all" if all_converged else "not all"} converged, worst {worst:.1e}')
    return ramp


class Probe:
    """The benchmark's own rclpy node: publishes on one topic, times arrivals on another."""

    def __init__(self, in_type, in_topic, out_type, out_topic):
        import rclpy
        from rclpy.node import Node
        from rclpy.qos import QoSProfile, ReliabilityPolicy
        self.rclpy = rclpy
        self.node = Node('benchmark_probe_' + in_topic.replace('/', '_'))
        qos = QoSProfile(depth=QUEUE_DEPTH, reliability=ReliabilityPolicy.RELIABLE)
        self.publisher = self.node.create_publisher(in_type, in_topic, qos)
        self.node.create_subscription(out_type, out_topic, self.on_message, qos)
        self.arrivals = []

    def on_message(self, _message):
        """Record the arrival time of one message."""
        self.arrivals.append(time.perf_counter())

    def run(self, messages, rate, seconds, drain=1.0):
        """
        Publish ``messages`` cyclically at ``rate`` for ``seconds`` while receiving.

        :returns: ``(send times, arrival times, achieved send rate)``.
        """
        self.arrivals = []
        count = int(rate * seconds)
        sends = []
        period = 1.0 / rate
        executor = self.rclpy.get_global_executor()
        executor.add_node(self.node)
        try:
            start = time.perf_counter()
            for k in range(count):
                due = start + k * period
                while time.perf_counter() < due:
                    executor.spin_once(timeout_sec=0.0)
                sends.append(time.perf_counter())
                self.publisher.publish(messages[k % len(messages)])
            achieved = count / (time.perf_counter() - start)
            end = time.perf_counter() + drain
            while time.perf_counter() < end and len(self.arrivals) < count:
                executor.spin_once(timeout_sec=0.01)
        finally:
            executor.remove_node(self.node)
        return sends, list(self.arrivals), achieved


def node_benchmarks(table, geometry, ramp):
    """Latency and loss-free rate of ik_node, fk_node and a bare echo node."""
    import rclpy
    from geometry_msgs.msg import Pose
    from std_msgs.msg import Float64MultiArray
    from stewart_kinematics.ros.message_conversions import legs_to_message, pose_to_message

    poses = ramp.sample(np.linspace(0.0, 10.0, 2001), 10.0)
    poses = np.concatenate([poses, poses[::-1]])  # there and back: the FK warm start holds
    pose_messages = [pose_to_message(pose) for pose in poses]
    length_messages = [legs_to_message(lengths)
                       for lengths in inverse_kinematics(geometry, poses)]
    params = ['--params-file', str(PLATFORM_FILE), '--params-file', str(SOLVER_FILE),
              '-p', f'queue_depth:={QUEUE_DEPTH}']
    with isolated_ros_environment() as domain:
        print(f'nodes on ROS_DOMAIN_ID {domain}', file=sys.stderr)
        processes = [
            NodeProcess('python', [str(Path(__file__).with_name('echo_node.py')), '--ros-args',
                                   '-p', f'queue_depth:={QUEUE_DEPTH}']),
            NodeProcess('ik_node', ['--ros-args', *params]),
            # Its own input topic, so that it stays idle while ik_node is measured.
            NodeProcess('fk_node', ['--ros-args', *params, '-r', 'leg_lengths:=fk_lengths']),
            # The chain pose -> ik_node -> leg lengths -> fk_node -> pose, in its own namespace.
            NodeProcess('ik_node', ['--ros-args', *params, '-r', '__ns:=/chain']),
            NodeProcess('fk_node', ['--ros-args', *params, '-r', '__ns:=/chain']),
        ]
        rclpy.init()
        try:
            probes = {
                'bare echo node': (Probe(Pose, 'echo_in', Pose, 'echo_out'), pose_messages),
                'ik_node': (Probe(Pose, 'target_pose', Float64MultiArray, 'leg_lengths'),
                            pose_messages),
                'fk_node': (Probe(Float64MultiArray, 'fk_lengths', Pose, 'estimated_pose'),
                            length_messages),
                CHAIN: (Probe(Pose, 'chain/target_pose', Pose, 'chain/estimated_pose'),
                        pose_messages),
            }
            deadline = time.monotonic() + 30.0
            for name, (probe, messages) in probes.items():
                if not wait_connected(probe, deadline, processes):
                    raise RuntimeError(f'{name} did not connect: '
                                       + ' '.join(p.output()[-500:] for p in processes))
                probe.run(messages, LATENCY_RATE, 0.5)  # warm-up, not counted
            results = {}
            for name, (probe, messages) in probes.items():
                sends, arrivals, _ = probe.run(messages, LATENCY_RATE, LATENCY_SECONDS)
                if len(arrivals) == len(sends):
                    latency = np.array(arrivals) - np.array(sends)
                    p50, p99 = np.percentile(latency, [50, 99])
                else:
                    p50 = p99 = math.nan
                results[name] = [p50, p99, 0.0]
            # Rates interleaved across the nodes, so that a slow moment of the machine hits
            # them alike; a node stops at its first rate with a loss.
            losing = set()
            for rate in RATES:
                for name, (probe, messages) in probes.items():
                    if name in losing or name == CHAIN:
                        continue
                    sends, arrivals, achieved = probe.run(messages, rate, RATE_SECONDS)
                    if len(arrivals) != len(sends):
                        losing.add(name)
                    else:
                        results[name][2] = achieved
        finally:
            rclpy.try_shutdown()
            for process in processes:
                process.stop()
    echo = results['bare echo node']
    chain = results.pop(CHAIN)
    for name, (p50, p99, best) in results.items():
        ratio = '1.00' if name == 'bare echo node' else \
            f'latency p50 {p50 / echo[0]:.2f}x, rate {best / echo[2]:.2f}x echo'
        table.add('Node: publish -> receive', name,
                  f'p50 {p50 * 1e3:.2f} ms, p99 {p99 * 1e3:.2f} ms; loss-free up to '
                  f'{best:,.0f} Hz', ratio, '', '')
    table.add('Node: pose -> FK pose', CHAIN,
              f'p50 {chain[0] * 1e3:.2f} ms, p99 {chain[1] * 1e3:.2f} ms',
              f'latency p50 {chain[0] / echo[0]:.2f}x echo', '', '')
    for name in ('ik_node', 'fk_node'):
        fraction = results[name][2] / echo[2] if echo[2] else 0.0
        table.target(f'{name} loss-free rate >= 80 % of the bare echo node', fraction >= 0.8,
                     f'{results[name][2]:,.0f} Hz vs {echo[2]:,.0f} Hz ({100 * fraction:.0f} %)')


def wait_connected(probe, deadline, processes):
    """Spin until the node under test has matched the probe both ways."""
    node = probe.node
    out_topic = node.resolve_topic_name(next(iter(node.subscriptions)).topic_name)
    while time.monotonic() < deadline:
        if not all(process.running() for process in processes):
            return False
        if (probe.publisher.get_subscription_count() >= 1
                and node.count_publishers(out_topic) >= 1):
            return True
        probe.rclpy.spin_once(node, timeout_sec=0.05)
    return False


def main(argv=None) -> int:
    """Run the benchmarks and print the table."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--random-poses', type=int, default=1000,
                        help='random poses in the workspace (default 1000)')
    parser.add_argument('--batch', type=int, default=1_000_000,
                        help='poses of the IK batch (default 1000000)')
    parser.add_argument('--no-nodes', action='store_true', help='skip the node benchmarks')
    args = parser.parse_args(argv)
    start = time.monotonic()
    geometry = load_geometry(PLATFORM_FILE)
    table = Table()
    ramp = kinematics_benchmarks(table, geometry, args.random_poses, args.batch)
    if not args.no_nodes:
        node_benchmarks(table, geometry, ramp)
    print(f'Machine: {platform.processor() or platform.machine()}, '
          f'{platform.python_implementation()} {platform.python_version()}, numpy '
          f'{np.__version__}; {time.monotonic() - start:.0f} s')
    print()
    table.show()
    return 0


if __name__ == '__main__':
    sys.exit(main())
