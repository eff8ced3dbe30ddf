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
environment); ``scripts/run_benchmarks.sh --update-docs`` also copies the tables into
doc/benchmarks.md. Prints, and writes to ``benchmarks/results.md``: one table of medians, rates,
ratios against their baseline, success rates and worst errors; then every target of
:data:`TARGETS`, met or not.

Every ratio is measured :data:`ROUNDS` times in one invocation (the kinematics rounds one after
the other, the node rounds interleaved across the nodes); the table gives the median ratio and
its range over the rounds, and a target is met when the median meets it.

Poses: the paper's Table 3 ramp (11 rows) plus random poses within +-0.1 m and +-15 degrees
of the home pose; cold: each solve without a previous pose (ours without a guess, so from its
start table, and once more from the home pose; the others from home); tracking: the same ramp
played over 10 s at 1 kHz, each solve starting from the previous solution. A solve succeeds
when it reports convergence and its pose is within 1e-4 (m and rad, the paper's tolerance) of
the true one; the worst error is over all poses.

basic-robotics' compiled FK (``SPFKinSpaceR``) models a plate whose joints lie in the plane
z = 0 of its top frame (its Jacobian drops their z). The paper's platform frame has the joints
0.275 m above it, where that solver fails on nearly every pose; so the same physical platform
is described to it with its top frame in the plane of the platform joints,
``T_sp = T_paper @ Trans(0, 0, 0.275)`` (and back), its IK is checked against ours there, and
its rows there are the fair ones. The paper-frame rows stay, labelled as such.
"""

import argparse
from dataclasses import dataclass, field
import math
import os
from pathlib import Path
import platform
import statistics
import sys
import time
import warnings

import numpy as np

from stewart_kinematics import (
    euler_zyx_to_matrix,
    forward_kinematics,
    inverse_kinematics,
    load_geometry,
    matrix_to_euler_zyx,
    Ramp,
)
from stewart_kinematics.model.rotations import rotation_angle_between
from stewart_kinematics.tools.node_processes import isolated_ros_environment, NodeProcess

ROOT = Path(__file__).resolve().parent.parent
PLATFORM_FILE = ROOT / 'config' / 'paper_platform.yaml'
SOLVER_FILE = ROOT / 'config' / 'solver.yaml'
RESULTS_FILE = Path(__file__).resolve().with_name('results.md')
#: Every target the benchmark judges, in the order printed. The docs' target table is
#: generated from the results and test/package/test_benchmark_tables.py checks it lists
#: exactly these.
TARGETS = (
    'IK one pose >= 10x faster than basic-robotics SP.IK',
    'IK batch > 2 000 000 poses/s',
    "FK cold >= 5x faster than scipy's root",
    "FK cold >= 1.25x faster than basic-robotics' compiled FK (plate frame, same accuracy)",
    'FK warm >= 2x faster than FK cold from home',
    'FK batch > 100 000 poses/s',
    '100 % convergence, error < 1e-9 (ours, every benchmark)',
    'ik_node loss-free rate >= 1.3x the bare echo node on the single-threaded executor',
    'fk_node loss-free rate >= 1.3x the bare echo node on the single-threaded executor',
    'ik_node loss-free rate >= 80 % of the bare echo node on the events executor',
    'fk_node loss-free rate >= 80 % of the bare echo node on the events executor',
    'ik_node and fk_node p99 latency at 1 kHz < 2 ms (events executor)',
)
#: The targets of the nodes, which run on the events executor (their default), each against
#: the echo node on one executor: (node, echo's executor, the ratio needed).
NODE_TARGETS = (
    ('ik_node', 'single_threaded', 1.3), ('fk_node', 'single_threaded', 1.3),
    ('ik_node', 'events', 0.8), ('fk_node', 'events', 0.8),
)
#: Rounds of every ratio benchmark; the median decides.
ROUNDS = 3
#: Half-widths of the random workspace around the home pose: metres, then radians.
WORKSPACE = np.array([0.1, 0.1, 0.1] + [math.radians(15.0)] * 3)
#: The paper's Newton-Raphson stopping tolerance, and the step of its finite differences.
PAPER_TOLERANCE = 1e-4
FINITE_DIFFERENCE_STEP = 1e-6
#: basic-robotics' top frame for its compiled FK: this far above the paper's platform frame
#: along the platform's z axis, in the plane of the platform joints (five of the paper's six are
#: at z = 0.275 m; p_3 is at 0.257 m, see doc/conventions.md), metres.
PLATE_FRAME_OFFSET = 0.275
#: Iteration cap of basic-robotics' compiled FK here (its own default, 10000, runs every
#: iteration on each pose it does not solve, which would not fit in the time budget).
BASIC_ROBOTICS_MAX_ITERATIONS = 200
#: basic-robotics' own FK tolerances (SP._tol_f on sum |l_i^2 - L_i^2| in m^2, SP._tol_a on the
#: step), and the tighter one at which its poses are as accurate as ours (worst about 1e-11).
BASIC_ROBOTICS_OWN_TOLERANCE = 5e-6
BASIC_ROBOTICS_TIGHT_TOLERANCE = 1e-14
#: The required accuracy of our solvers, metres and radians.
REQUIRED_ERROR = 1e-9
#: Node benchmark: the nodes' queue depth; latency rate and duration, and the p99 latency
#: target there (seconds); the coarse rate ladder, its rung duration and the bisections
#: between the last loss-free rung and the first loss.
QUEUE_DEPTH = 100
LATENCY_RATE = 1000.0
LATENCY_SECONDS = 2.0
LATENCY_TARGET = 2e-3
LADDER = (250.0, 500.0, 1000.0, 1500.0, 2000.0, 3000.0, 4000.0, 6000.0, 8000.0, 12000.0,
          16000.0, 24000.0, 32000.0)
RUNG_SECONDS = 1.0
BISECTIONS = 3
#: The probe's own receive queue, which DDS fills from its own threads while the probe
#: publishes: larger than any rung sends (see RUNG_MESSAGES), so that every loss counted is the
#: node's.
PROBE_RECEIVE_DEPTH = 40000
#: Most messages of one rung: Fast DDS's reader holds at most 5000 samples whatever the depth
#: (its default resource limits; measured: 5100 answers of any longer burst arrive, on either
#: executor), so a rung above this many messages is shorter than RUNG_SECONDS.
RUNG_MESSAGES = 4000
#: The chain of both nodes: latency of a pose to the pose fk_node finds for its leg lengths.
CHAIN = 'ik_node -> fk_node'
ECHO = 'bare echo node'
#: The executors every node is measured on (stewart_kinematics.ros.node_main.EXECUTORS); the
#: nodes' default last.
NODE_EXECUTORS = ('single_threaded', 'events')


@dataclass
class Series:
    """One figure measured once per round: the median decides, the range shows the noise."""

    values: list = field(default_factory=list)

    def add(self, value):
        """Record this round's value."""
        self.values.append(float(value))

    @property
    def median(self):
        """Median over the rounds (NaN before the first)."""
        return statistics.median(self.values) if self.values else math.nan

    def text(self, spec='.2f', suffix='x'):
        """``median (low-high)`` formatted with ``spec`` and ``suffix``."""
        if len(self.values) < 2:
            return f'{self.median:{spec}}{suffix}'
        return (f'{self.median:{spec}}{suffix} ({min(self.values):{spec}}-'
                f'{max(self.values):{spec}})')


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


def pose_errors(poses, truth):
    """Largest position (m) and rotation (rad) error of each pose, as one max per pose."""
    poses, truth = np.atleast_2d(poses), np.atleast_2d(truth)
    finite = np.all(np.isfinite(poses), axis=-1)
    errors = np.full(len(poses), np.inf)
    position = np.linalg.norm(poses[finite, :3] - truth[finite, :3], axis=-1)
    angle = rotation_angle_between(euler_zyx_to_matrix(poses[finite, 3:]),
                                   euler_zyx_to_matrix(truth[finite, 3:]))
    errors[finite] = np.maximum(position, angle)
    return errors


def homogeneous(pose):
    """4x4 transform of one of our poses ``[X, Y, Z, alpha, beta, gamma]``."""
    matrix = np.eye(4)
    matrix[:3, :3] = euler_zyx_to_matrix(pose[3:])
    matrix[:3, 3] = pose[:3]
    return matrix


def translation_z(offset):
    """4x4 transform ``Trans(0, 0, offset)``."""
    matrix = np.eye(4)
    matrix[2, 3] = offset
    return matrix


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
    """
    This package's forward_kinematics, default tolerance 1e-12.

    Cold, without a guess (``cold_guess`` None): it starts from its start table, as a user's
    first call does (the table is built before the timing, on the first call).
    """

    name = 'stewart_kinematics (no guess: its start table)'
    cold_guess = None

    def __init__(self, geometry):
        self.geometry = geometry
        forward_kinematics(geometry, inverse_kinematics(geometry, geometry.home_pose + 0.01))

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

    @staticmethod
    def pose_of(result):
        """Return the pose of a tracking result."""
        return result.pose


class OursFromHome(Ours):
    """This package's forward_kinematics given the home pose as the guess (no start table)."""

    name = 'stewart_kinematics, from home (the home pose as the guess)'

    def __init__(self, geometry):
        super().__init__(geometry)
        self.cold_guess = geometry.home_pose


class BasicRobotics:
    """
    basic-robotics 1.0.2's SP class, describing the paper's platform in a chosen top frame.

    Its top frame is ``T_sp = T_paper @ Trans(0, 0, offset)``: the platform joints become
    ``p_i - (0, 0, offset)`` in it; poses are converted exactly both ways. Its compiled FK
    (``SPFKinSpaceR``) works on translation + axis-angle vectors (TAA) of the top frame and
    stops when ``sum |l_i^2 - L_i^2| < tolerance`` (m^2) or a step sums below it.
    """

    def __init__(self, geometry, offset, tolerance, label):
        with warnings.catch_warnings():
            warnings.simplefilter('ignore')
            from basic_robotics.general import faser_high_performance, tm
            from basic_robotics.kinematics import SP
        self.name = label
        self.tm = tm
        self.kernel = faser_high_performance.SPFKinSpaceR
        self.tolerance = tolerance
        self.to_sp = translation_z(offset)
        self.from_sp = translation_z(-offset)
        top_joints = geometry.platform_joints - np.array([0.0, 0.0, offset])
        # Joints as columns (3, 6) in metres; base plate at the origin; top plate at home.
        self.sp = SP(geometry.base_joints.T.copy(), top_joints.T.copy(), tm(),
                     self.transform(geometry.home_pose), 0.0, 2.0, 0.0, 0.0, 'paper')
        self.home_guess = self.fk_guess(geometry.home_pose)

    def transform(self, pose):
        """Its transform object (tm) of its top frame for one of our poses."""
        return self.tm(homogeneous(pose) @ self.to_sp)

    def ik(self, top):
        """Leg lengths by SP.IK of a prepared transform (validation off: protect=True)."""
        return self.sp.IK(top_plate_pos=top, protect=True)[0].reshape(6)

    def ik_mismatch(self, poses, lengths):
        """Largest difference of its IK from ``lengths`` (ours) over the poses, metres."""
        return float(np.max(np.abs(
            np.array([self.ik(self.transform(pose)) for pose in poses]) - lengths)))

    def fk_guess(self, pose):
        """Its pose vector for one of our poses: translation and axis-angle (TAA)."""
        return self.transform(pose).gTAA().reshape(6).astype(float)

    def fk(self, lengths, guess):
        """Its compiled Newton-Raphson (SPFKinSpaceR) from a TAA guess: ``(TAA, converged)``."""
        sp = self.sp
        taa, iterations = self.kernel(
            np.array(lengths, dtype=float), guess.copy(), sp._bottom_joints_init,
            sp._top_joints_init, BASIC_ROBOTICS_MAX_ITERATIONS, self.tolerance,
            self.tolerance, sp.leg_ext_min)
        return taa, iterations < BASIC_ROBOTICS_MAX_ITERATIONS

    def pose_of(self, taa):
        """One of our poses from its TAA: ``T_paper = T_sp @ Trans(0, 0, -offset)``."""
        if not np.all(np.isfinite(taa)):
            return np.full(6, np.nan)
        matrix = self.tm(np.array(taa, dtype=float)).gTM() @ self.from_sp
        return np.concatenate([matrix[:3, 3], matrix_to_euler_zyx(matrix[:3, :3])])


@dataclass
class SolverRun:
    """One solver over one pose set: median time per round, and its first round's results."""

    seconds: Series = field(default_factory=Series)
    converged: np.ndarray = None
    errors: np.ndarray = None

    def record(self, median, converged, errors):
        """Add a round's median; keep the first round's success and errors."""
        self.seconds.add(median)
        if self.converged is None:
            self.converged, self.errors = converged, errors

    def success(self):
        """Success rate and worst error cells."""
        ok = self.converged & (self.errors <= PAPER_TOLERANCE)
        return f'{100.0 * ok.mean():.1f} % of {len(ok)}', f'{np.max(self.errors):.1e}'


def run_solver(solver, lengths, guesses, truth, pose_of=None):
    """Solve each pose once, timing each: ``(median seconds, converged, errors)``."""
    times, poses, converged = [], [], []
    clock = time.perf_counter
    for target, guess in zip(lengths, guesses):
        start = clock()
        pose, ok = solver(target, guess)
        times.append(clock() - start)
        poses.append(pose_of(pose) if pose_of else pose)
        converged.append(ok)
    return statistics.median(times), np.array(converged), pose_errors(np.array(poses), truth)


def run_tracking(solver, lengths, first_guess, truth, pose_of=None):
    """Track along a ramp, each solve starting from the previous solution."""
    times, poses, converged = [], [], []
    guess = first_guess
    clock = time.perf_counter
    for target in lengths:
        start = clock()
        pose, ok = solver(target, guess)
        times.append(clock() - start)
        guess = pose if ok else first_guess
        poses.append(pose_of(pose) if pose_of else pose)
        converged.append(ok)
    return statistics.median(times), np.array(converged), pose_errors(np.array(poses), truth)


class Table:
    """Rows of the results table and the verdict on every target, as Markdown."""

    def __init__(self, rounds):
        self.rounds = rounds
        self.rows = []
        self.verdicts = {}

    def add(self, *cells):
        """Add one row: what, solver, median/rate, ratio, success, worst error."""
        self.rows.append(cells)

    def target(self, name, met, detail):
        """Record whether the run met one target of :data:`TARGETS`."""
        if name not in TARGETS:
            raise KeyError(f'not a target of TARGETS: {name}')
        self.verdicts[name] = (met, detail)

    def results_markdown(self):
        """Return the results table."""
        header = ('Benchmark', 'Solver', 'Median / rate',
                  f'Ratio (median of {self.rounds} rounds, range)', 'Success', 'Worst error')
        lines = ['| ' + ' | '.join(header) + ' |', '| ' + ' | '.join('---' for _ in header)
                 + ' |']
        lines += ['| ' + ' | '.join(str(cell) for cell in row) + ' |' for row in self.rows]
        return '\n'.join(lines)

    def targets_markdown(self):
        """Return every target, met or not (not measured counts as not met, with the reason)."""
        lines = [f'| Target | Met (median of {self.rounds} rounds) | This run: median (range) |',
                 '| --- | --- | --- |']
        for name in TARGETS:
            met, detail = self.verdicts.get(name, (False, 'not measured in this run'))
            lines.append(f'| {name} | {"yes" if met else "**no**"} | {detail} |')
        return '\n'.join(lines)


def block(name, text):
    """Return a block of results.md, between the markers update_doc_tables.py copies."""
    return f'<!-- benchmark: {name} -->\n{text}\n<!-- end benchmark -->\n'


def microseconds(seconds):
    """Format a duration in microseconds."""
    return f'{seconds * 1e6:.1f} us'


def table3_ramp():
    """Return the paper's Table 3 ramp."""
    return Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])


def kinematics_benchmarks(table, geometry, random_count, batch_count, rounds):
    """IK and FK, one pose, tracking and batches, against the baselines; returns the ramp."""
    ramp = table3_ramp()
    rng = np.random.default_rng(20260101)
    random_poses = geometry.home_pose + rng.uniform(-1.0, 1.0, (random_count, 6)) * WORKSPACE
    poses = np.concatenate([ramp.rows, random_poses])
    lengths = inverse_kinematics(geometry, poses)
    home = geometry.home_pose
    tracking = ramp.sample(np.arange(10001) * 1e-3, 10.0)
    tracking_lengths = inverse_kinematics(geometry, tracking)
    batch = geometry.home_pose + rng.uniform(-1.0, 1.0, (batch_count, 6)) * WORKSPACE
    print(f'poses: {len(ramp.rows)} Table 3 rows + {random_count} random '
          f'(+-0.1 m, +-15 deg); tracking: {len(tracking)} ramp samples at 1 kHz; '
          f'{rounds} rounds', file=sys.stderr)

    ours, paper, scipy_root = Ours(geometry), PaperNewtonRaphson(geometry), ScipyRoot(geometry)
    ours_home = OursFromHome(geometry)
    try:
        plate = BasicRobotics(
            geometry, PLATE_FRAME_OFFSET, BASIC_ROBOTICS_OWN_TOLERANCE,
            'basic-robotics compiled FK, plate frame, its tolerance (5e-6 m^2)')
        tight = BasicRobotics(
            geometry, PLATE_FRAME_OFFSET, BASIC_ROBOTICS_TIGHT_TOLERANCE,
            'basic-robotics compiled FK, plate frame, tolerance 1e-14 m^2 (our accuracy)')
        paper_frame = BasicRobotics(
            geometry, 0.0, BASIC_ROBOTICS_OWN_TOLERANCE,
            "basic-robotics compiled FK, paper's frame (joints 0.275 m off its plate: fails)")
        basic_error = ''
        plate_mismatch = plate.ik_mismatch(poses, lengths)
        paper_mismatch = paper_frame.ik_mismatch(poses, lengths)
        print(f'basic-robotics SP.IK vs ours over {len(poses)} poses: plate frame (top frame '
              f'T_paper @ Trans(0, 0, {PLATE_FRAME_OFFSET})) {plate_mismatch:.1e} m, paper '
              f'frame {paper_mismatch:.1e} m', file=sys.stderr)
        basic_solvers = (plate, tight, paper_frame)
    except Exception as error:  # noqa: B902 - any failure to install or import is reported
        plate = tight = paper_frame = None
        basic_solvers = ()
        basic_error = f'not installable: {type(error).__name__}: {error}'
    fk_solvers = (paper, scipy_root, ours, ours_home, *basic_solvers)

    ik_ours, ik_basic, ik_ratio = Series(), Series(), Series()
    ik_batch, ik_single = Series(), Series()
    cold = {solver.name: SolverRun() for solver in fk_solvers}
    warm = {solver.name: SolverRun() for solver in fk_solvers}
    fk_batch_rate = Series()
    for round_index in range(rounds):
        print(f'kinematics round {round_index + 1} of {rounds}', file=sys.stderr)
        ik_ours.add(median_seconds(lambda pose: inverse_kinematics(geometry, pose), poses,
                                   repeat=3))
        if plate:
            transforms = [plate.transform(pose) for pose in poses]
            ik_basic.add(median_seconds(plate.ik, transforms))
            ik_ratio.add(ik_basic.values[-1] / ik_ours.values[-1])
        ik_batch.add(batch_count / best_seconds(lambda: inverse_kinematics(geometry, batch), 3))
        ik_single.add(1.0 / ik_ours.values[-1])
        for solver in fk_solvers:
            solve = solver.fk if isinstance(solver, BasicRobotics) else solver.solve
            guess = solver.home_guess if isinstance(solver, BasicRobotics) else home
            pose_of = solver.pose_of if isinstance(solver, BasicRobotics) else None
            cold_guess = solver.cold_guess if isinstance(solver, Ours) else guess
            cold[solver.name].record(*run_solver(solve, lengths, [cold_guess] * len(poses),
                                                 poses, pose_of))
            if solver is ours_home:
                continue  # tracking: the same as ours
            track = solver.track if solver is ours else solve
            pose_of = solver.pose_of if solver is ours else pose_of
            warm[solver.name].record(*run_tracking(track, tracking_lengths, guess, tracking,
                                                   pose_of))
        fk_batch_rate.add(len(poses) / best_seconds(
            lambda: forward_kinematics(geometry, lengths), 3))

    ik_error = float(np.max(np.abs(
        np.array([inverse_kinematics(geometry, pose) for pose in poses]) - lengths)))
    batch_error = float(np.max(np.abs(inverse_kinematics(geometry, poses) - lengths)))

    # IK, one pose.
    count = f'100.0 % of {len(poses)}'
    if plate:
        table.add('IK one pose', 'basic-robotics SP.IK (protect=True), plate frame',
                  microseconds(ik_basic.median), '1.00', count,
                  f'{plate_mismatch:.1e} m from ours')
        table.add('IK one pose', 'stewart_kinematics', microseconds(ik_ours.median),
                  ik_ratio.text('.1f', 'x faster'), count, f'{ik_error:.1e} m')
        table.target(TARGETS[0], ik_ratio.median >= 10.0, ik_ratio.text('.1f'))
    else:
        table.add('IK one pose', 'basic-robotics SP.IK', basic_error, '', '', '')
        table.add('IK one pose', 'stewart_kinematics', microseconds(ik_ours.median), '', count,
                  f'{ik_error:.1e} m')
        table.target(TARGETS[0], False, basic_error)

    # IK batch.
    batch_ratio = Series([rate / single for rate, single in
                          zip(ik_batch.values, ik_single.values)])
    table.add('IK batch', 'stewart_kinematics, one pose per call',
              f'{ik_single.median:,.0f} /s', '1.00', '100.0 %', '')
    if plate:
        table.add('IK batch', 'basic-robotics SP.IK, one pose per call',
                  f'{1.0 / ik_basic.median:,.0f} /s',
                  Series([1.0 / ratio for ratio in ik_ratio.values]).text('.3f', ''),
                  '100.0 %', '')
    table.add('IK batch', f'stewart_kinematics, {batch_count:,} poses in one call',
              f'{ik_batch.median:,.0f} /s', batch_ratio.text('.0f'), '100.0 %',
              f'{batch_error:.1e} m')
    table.target(TARGETS[1], ik_batch.median > 2e6, ik_batch.text(',.0f', ' /s'))

    # FK cold and warm: every ratio is taken within its round.
    def ratio_series(runs, name, reference):
        pairs = zip(runs[name].seconds.values, runs[reference].seconds.values)
        return Series([a / b for a, b in pairs])

    for solver in fk_solvers:
        run = cold[solver.name]
        ratio = '1.00' if solver is ours else \
            ratio_series(cold, solver.name, ours.name).text('.2f', 'x ours')
        table.add('FK cold (no previous pose)', solver.name, microseconds(run.seconds.median),
                  ratio, *run.success())
    if not plate:
        table.add('FK cold (no previous pose)', 'basic-robotics SP', basic_error, '', '', '')
    scipy_ratio = ratio_series(cold, scipy_root.name, ours.name)
    table.target(TARGETS[2], scipy_ratio.median >= 5.0, scipy_ratio.text('.2f'))
    if plate:
        tight_ratio = ratio_series(cold, tight.name, ours.name)
        own_ratio = ratio_series(cold, plate.name, ours.name)
        table.target(TARGETS[3], tight_ratio.median >= 1.25,
                     f'its time / ours: {tight_ratio.text(".2f")} at 1e-14 m^2; '
                     f'{own_ratio.text(".2f")} at its own 5e-6 m^2')
    else:
        table.target(TARGETS[3], False, basic_error)

    ours_cold = cold[ours.name].seconds
    warm_speedup = Series([c / w for c, w in zip(cold[ours_home.name].seconds.values,
                                                 warm[ours.name].seconds.values)])
    for solver in fk_solvers:
        if solver is ours_home:
            continue
        run = warm[solver.name]
        ratio = f'{warm_speedup.text(".2f", "x faster")} than ours cold from home' \
            if solver is ours else ratio_series(warm, solver.name, ours.name).text('.2f', 'x ours')
        name = 'stewart_kinematics (from its last result)' if solver is ours else solver.name
        table.add('FK warm (tracking)', name, microseconds(run.seconds.median), ratio,
                  *run.success())
    table.target(TARGETS[4], warm_speedup.median >= 2.0, warm_speedup.text('.2f'))

    # FK batch.
    fk_batch = forward_kinematics(geometry, lengths)
    fk_errors = pose_errors(fk_batch.pose, poses)
    batch_run = SolverRun()
    batch_run.record(0.0, np.asarray(fk_batch.converged), fk_errors)
    table.add('FK batch', 'stewart_kinematics, one pose per call (no guess)',
              f'{1.0 / ours_cold.median:,.0f} /s', '1.00', '', '')
    table.add('FK batch', 'scipy root, one pose per call',
              f'{1.0 / cold[scipy_root.name].seconds.median:,.0f} /s',
              Series([1.0 / r for r in scipy_ratio.values]).text('.2f', ''), '', '')
    table.add('FK batch', f'stewart_kinematics, {len(poses):,} poses in one call (no guess)',
              f'{fk_batch_rate.median:,.0f} /s',
              Series([r * s for r, s in zip(fk_batch_rate.values, ours_cold.values)]).text(
                  '.1f'), *batch_run.success())
    table.target(TARGETS[5], fk_batch_rate.median > 1e5, fk_batch_rate.text(',.0f', ' /s'))

    ours_runs = (cold[ours.name], cold[ours_home.name], warm[ours.name], batch_run)
    all_converged = all(np.all(run.converged) for run in ours_runs)
    worst = max(max(float(np.max(run.errors)) for run in ours_runs), ik_error, batch_error)
    table.target(TARGETS[6], all_converged and worst < REQUIRED_ERROR,
                 f'{"all" if all_converged else "not all"} converged, worst {worst:.1e}')
    return ramp


class Probe:
    """The benchmark's own rclpy node: publishes on one topic, counts arrivals on another."""

    def __init__(self, in_type, in_topic, out_type, out_topic):
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.node import Node
        from rclpy.qos import QoSProfile, ReliabilityPolicy
        self.node = Node('benchmark_probe_' + in_topic.replace('/', '_'))
        self.executor = SingleThreadedExecutor(context=rclpy.get_default_context())
        self.executor.add_node(self.node)
        self.publisher = self.node.create_publisher(
            in_type, in_topic, QoSProfile(depth=QUEUE_DEPTH,
                                          reliability=ReliabilityPolicy.RELIABLE))
        self.node.create_subscription(
            out_type, out_topic, self.on_message,
            QoSProfile(depth=PROBE_RECEIVE_DEPTH, reliability=ReliabilityPolicy.RELIABLE))
        self.out_topic = self.node.resolve_topic_name(out_topic)
        self.arrivals = []

    def on_message(self, _message):
        """Record the arrival time of one message."""
        self.arrivals.append(time.perf_counter())

    def latency(self, messages, rate, seconds):
        """
        Publish at ``rate`` for ``seconds``, receiving as messages arrive.

        :returns: arrival minus send time of every message, seconds (None if one was lost).
        """
        self.arrivals = []
        sends = []
        period = 1.0 / rate
        start = time.perf_counter()
        for k in range(int(rate * seconds)):
            due = start + k * period
            while time.perf_counter() < due:
                self.executor.spin_once(timeout_sec=0.0)
            sends.append(time.perf_counter())
            self.publisher.publish(messages[k % len(messages)])
        self.drain(len(sends))
        if len(self.arrivals) != len(sends):
            return None
        return np.array(self.arrivals) - np.array(sends)

    def loss_free(self, messages, rate, seconds):
        """
        Publish at ``rate`` for ``seconds`` without receiving, then collect what arrived.

        The probe does not spin while publishing, so that it keeps the rate; its receive queue
        (:data:`PROBE_RECEIVE_DEPTH`) holds every answer meanwhile, up to
        :data:`RUNG_MESSAGES` of them: a faster rung is shorter.

        :returns: ``(every message answered, achieved send rate)``.
        """
        self.arrivals = []
        count = min(int(rate * seconds), RUNG_MESSAGES)
        period = 1.0 / rate
        clock = time.perf_counter
        publish = self.publisher.publish
        start = clock()
        for k in range(count):
            due = start + k * period
            while clock() < due:
                pass
            publish(messages[k % len(messages)])
        achieved = count / (clock() - start)
        self.drain(count)
        return len(self.arrivals) == count, achieved

    def drain(self, count, quiet=0.5, limit=10.0):
        """Receive until ``count`` arrived, nothing arrived for ``quiet`` s, or ``limit`` s."""
        end = time.monotonic() + limit
        last, quiet_until = -1, time.monotonic() + quiet
        while len(self.arrivals) < count and time.monotonic() < end:
            self.executor.spin_once(timeout_sec=0.01)
            if len(self.arrivals) != last:
                last, quiet_until = len(self.arrivals), time.monotonic() + quiet
            elif time.monotonic() > quiet_until:
                break

    def wait_connected(self, deadline, processes):
        """Spin until the node under test has matched the probe both ways."""
        while time.monotonic() < deadline:
            if not all(process.running() for process in processes):
                return False
            if (self.publisher.get_subscription_count() >= 1
                    and self.node.count_publishers(self.out_topic) >= 1):
                return True
            self.executor.spin_once(timeout_sec=0.05)
        return False


@dataclass
class RateSearch:
    """The highest loss-free rate of one node: the coarse ladder, then bisections."""

    best: float = 0.0
    lost_at: float = None
    bisections: int = BISECTIONS
    rung: int = 0

    def next_rate(self):
        """Return the rate to try next, or None when done."""
        if self.lost_at is None:
            return LADDER[self.rung] if self.rung < len(LADDER) else None
        if self.bisections == 0:
            return None
        return 0.5 * (self.best + self.lost_at)

    def record(self, rate, loss_free, achieved):
        """Record the outcome of ``rate``."""
        if self.lost_at is None:
            self.rung += 1
        else:
            self.bisections -= 1
        if loss_free:
            self.best = max(self.best, achieved)
        else:
            self.lost_at = rate if self.lost_at is None else min(self.lost_at, rate)


def node_benchmarks(table, geometry, ramp, rounds):
    """
    Latency and loss-free rate of ik_node, fk_node and a bare echo node, on both executors.

    Six subjects (echo, ik_node, fk_node, each on each executor of :data:`NODE_EXECUTORS`,
    each in a namespace of the executor's name) and the chain ik_node -> fk_node on the
    nodes' default executor; the rate searches of the six interleaved, rung by rung.
    """
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
    subjects = [(name, executor) for executor in NODE_EXECUTORS
                for name in (ECHO, 'ik_node', 'fk_node')]
    latency = {subject: (Series(), Series()) for subject in subjects + [(CHAIN, 'events')]}
    cpu = {subject: Series() for subject in subjects}
    rates = {subject: Series() for subject in subjects}
    first_loss = {subject: Series() for subject in subjects}
    load = [os.getloadavg()[0]]
    with isolated_ros_environment() as domain:
        print(f'nodes on ROS_DOMAIN_ID {domain}', file=sys.stderr)
        processes = []
        for executor in NODE_EXECUTORS:
            options = ['--executor', executor, '--ros-args', '-r', f'__ns:=/{executor}']
            processes += [
                NodeProcess('python', [str(Path(__file__).with_name('echo_node.py')), *options,
                                       '-p', f'queue_depth:={QUEUE_DEPTH}']),
                NodeProcess('ik_node', [*options, *params]),
                # Its own input topic, so that it stays idle while ik_node is measured.
                NodeProcess('fk_node', [*options, *params, '-r', 'leg_lengths:=fk_lengths']),
            ]
        subject_processes = dict(zip(subjects, processes))
        # The chain pose -> ik_node -> leg lengths -> fk_node -> pose, on the default executor.
        processes += [NodeProcess(name, ['--ros-args', *params, '-r', '__ns:=/chain'])
                      for name in ('ik_node', 'fk_node')]
        rclpy.init()
        try:
            probes = {}
            for name, executor in subjects:
                prefix = f'{executor}/'
                probes[name, executor] = {
                    ECHO: (Probe(Pose, prefix + 'echo_in', Pose, prefix + 'echo_out'),
                           pose_messages),
                    'ik_node': (Probe(Pose, prefix + 'target_pose', Float64MultiArray,
                                      prefix + 'leg_lengths'), pose_messages),
                    'fk_node': (Probe(Float64MultiArray, prefix + 'fk_lengths', Pose,
                                      prefix + 'estimated_pose'), length_messages),
                }[name]
            probes[CHAIN, 'events'] = (Probe(Pose, 'chain/target_pose', Pose,
                                             'chain/estimated_pose'), pose_messages)
            deadline = time.monotonic() + 60.0
            for subject, (probe, messages) in probes.items():
                if not probe.wait_connected(deadline, processes):
                    raise RuntimeError(f'{subject} did not connect: '
                                       + ' '.join(p.output()[-500:] for p in processes))
                probe.latency(messages, LATENCY_RATE, 0.5)  # warm-up, not counted
            for round_index in range(rounds):
                print(f'node round {round_index + 1} of {rounds} (load average '
                      f'{os.getloadavg()[0]:.2f})', file=sys.stderr)
                for subject, (probe, messages) in probes.items():
                    process = subject_processes.get(subject)
                    used = process and process_seconds(process)
                    delays = probe.latency(messages, LATENCY_RATE, LATENCY_SECONDS)
                    if process:
                        cpu[subject].add((process_seconds(process) - used)
                                         / (LATENCY_RATE * LATENCY_SECONDS))
                    # A round that lost a message counts as an infinite latency.
                    p50, p99 = (math.inf, math.inf) if delays is None else \
                        np.percentile(delays, [50, 99])
                    latency[subject][0].add(p50)
                    latency[subject][1].add(p99)
                # Rates interleaved across the subjects, so that a slow moment of the machine
                # hits them alike; each climbs the ladder to its first loss, then bisects.
                searches = {subject: RateSearch() for subject in subjects}
                while any(search.next_rate() for search in searches.values()):
                    for subject, search in searches.items():
                        rate = search.next_rate()
                        if rate:
                            probe, messages = probes[subject]
                            search.record(rate, *probe.loss_free(messages, rate, RUNG_SECONDS))
                for subject, search in searches.items():
                    rates[subject].add(search.best)
                    first_loss[subject].add(search.lost_at or math.inf)
                    print(f'  {subject[0]} ({subject[1]}): loss-free up to {search.best:,.0f} '
                          f'Hz, first loss at {search.lost_at or math.inf:,.0f} Hz',
                          file=sys.stderr)
                load.append(os.getloadavg()[0])
        finally:
            rclpy.try_shutdown()
            for process in processes:
                process.stop()
    node_rows(table, latency, cpu, rates, first_loss, load)


def process_seconds(process):
    """Processor time a NodeProcess has used so far (user and system, all threads), seconds."""
    fields = Path(f'/proc/{process.process.pid}/stat').read_text().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def node_rows(table, latency, cpu, rates, first_loss, load):
    """
    Add the node rows and judge the node targets.

    :param cpu: per subject, the processor time its process used per message at
        :data:`LATENCY_RATE`, seconds (its timers and worker threads included).
    :param load: the load averages seen (1 min).
    """
    def ratio(values, reference, scale=1.0):
        return Series([scale * a / b for a, b in zip(values.values, reference.values)])

    echo = {executor: rates[ECHO, executor] for executor in NODE_EXECUTORS}
    ceiling = {executor: any(math.isinf(value) for value in first_loss[ECHO, executor].values)
               for executor in NODE_EXECUTORS}
    for (name, executor), rate in rates.items():
        p50, p99 = latency[name, executor]
        limit = ('no loss up to the top of the ladder' if any(
            math.isinf(value) for value in first_loss[name, executor].values)
            else f'first loss at {first_loss[name, executor].median:,.0f} Hz')
        against = '; '.join(f'{ratio(rate, echo[other]).text(".2f")} echo {other}'
                            for other in NODE_EXECUTORS if (name, executor) != (ECHO, other))
        table.add('Node: publish -> receive', f'{name}, {executor} executor',
                  f'at {LATENCY_RATE:,.0f} Hz: p50 {p50.median * 1e3:.2f} ms, p99 '
                  f'{p99.median * 1e3:.2f} ms, {cpu[name, executor].median * 1e6:.0f} us of '
                  f'processor per message; loss-free up to {rate.median:,.0f} Hz ({limit})',
                  f'rate {against}' if against else '1.00', '', '')
    chain_p50, chain_p99 = latency[CHAIN, 'events']
    table.add('Node: pose -> FK pose', f'{CHAIN}, events executor',
              f'at {LATENCY_RATE:,.0f} Hz: p50 {chain_p50.median * 1e3:.2f} ms, p99 '
              f'{chain_p99.median * 1e3:.2f} ms',
              'latency p50 ' + ratio(chain_p50, latency[ECHO, 'events'][0]).text('.2f')
              + ' echo (events)', '', '')
    loads = f'load average {min(load):.2f}-{max(load):.2f}'
    for target, (name, executor, needed) in zip(TARGETS[7:11], NODE_TARGETS):
        fraction = ratio(rates[name, 'events'], echo[executor])
        note = ' (echo never lost a message: a bound)' if ceiling[executor] else ''
        table.target(target, fraction.median >= needed,
                     f'{rates[name, "events"].median:,.0f} Hz vs {echo[executor].median:,.0f} '
                     f'Hz: {fraction.text(".2f")}{note}; {loads}')
    p99 = {name: latency[name, 'events'][1] for name in ('ik_node', 'fk_node')}
    table.target(TARGETS[11], all(series.median < LATENCY_TARGET for series in p99.values()),
                 '; '.join(f'{name} {series.median * 1e3:.2f} ms ({min(series.values) * 1e3:.2f}'
                           f'-{max(series.values) * 1e3:.2f})' for name, series in p99.items())
                 + f'; {loads}')


def main(argv=None) -> int:
    """Run the benchmarks, print the tables and write them to results.md."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--random-poses', type=int, default=1000,
                        help='random poses in the workspace (default 1000)')
    parser.add_argument('--batch', type=int, default=1_000_000,
                        help='poses of the IK batch (default 1000000)')
    parser.add_argument('--rounds', type=int, default=ROUNDS,
                        help=f'rounds of every ratio benchmark (default {ROUNDS})')
    parser.add_argument('--no-nodes', action='store_true', help='skip the node benchmarks')
    parser.add_argument('--nodes-only', action='store_true',
                        help='only the node benchmarks (the other targets: not measured)')
    parser.add_argument('--output', type=Path, default=RESULTS_FILE,
                        help='where to write the tables (default benchmarks/results.md)')
    args = parser.parse_args(argv)
    start = time.monotonic()
    geometry = load_geometry(PLATFORM_FILE)
    table = Table(args.rounds)
    load = os.getloadavg()[0]
    if args.nodes_only:
        ramp = table3_ramp()
    else:
        ramp = kinematics_benchmarks(table, geometry, args.random_poses, args.batch,
                                     args.rounds)
    if not args.no_nodes:
        node_benchmarks(table, geometry, ramp, args.rounds)
    machine = (f'{platform.processor() or platform.machine()}, {platform.python_implementation()} '
               f'{platform.python_version()}, numpy {np.__version__}; {args.rounds} rounds in '
               f'{time.monotonic() - start:.0f} s; load average (1 min) {load:.2f} at the '
               f'start, {os.getloadavg()[0]:.2f} at the end')
    text = (block('machine', machine) + '\n' + block('results', table.results_markdown())
            + '\n' + block('targets', table.targets_markdown()))
    print(text)
    args.output.write_text(
        '# Benchmark results\n\nWritten by benchmarks/run_benchmarks.py; '
        'scripts/update_doc_tables.py copies the blocks into doc/benchmarks.md.\n\n' + text,
        encoding='utf-8')
    print(f'written to {args.output}', file=sys.stderr)
    return 0


if __name__ == '__main__':
    sys.exit(main())
