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
Compare the kinematics speed of two checkouts of this package in the same run.

Each round runs one subprocess per checkout, alternately, with ``PYTHONPATH`` set to that
checkout, so both see the same machine load. A subprocess times, on the paper's platform:
IK of one pose, IK of a batch, FK of one pose from home (cold; the Table 3 rows and random
poses within +-0.1 m and +-15 deg of home), FK tracking the Table 3 ramp at 1 kHz from the last
result (warm) and FK of the whole set as one batch. The median over the rounds is printed for
each, with the ratio new / old (below 1 is faster)::

    git worktree add /tmp/base main
    .venv/bin/python benchmarks/compare_revisions.py /tmp/base . --rounds 5
"""

import argparse
import json
import math
import os
from pathlib import Path
import statistics
import subprocess
import sys
import time

#: Half-widths of the random workspace around the home pose: metres, then radians.
WORKSPACE = [0.1, 0.1, 0.1] + [math.radians(15.0)] * 3
#: What each subprocess measures, in print order, with the unit of its figure.
MEASURES = (
    ('IK one pose', 'us'),
    ('IK batch', 'ns/pose'),
    ('FK cold single', 'us'),
    ('FK warm tracking', 'us'),
    ('FK batch', 'us/pose'),
)


def measure(random_count, batch_count):
    """Time the kinematics of the checkout on sys.path; return ``{measure: figure}``."""
    import numpy as np

    from stewart_kinematics import forward_kinematics, inverse_kinematics
    from stewart_kinematics.parameter_spec import load_geometry
    from stewart_kinematics.trajectory import Ramp

    import stewart_kinematics
    root = Path(stewart_kinematics.__file__).resolve().parent.parent
    geometry = load_geometry(str(root / 'config' / 'paper_platform.yaml'))
    ramp = Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                           [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])
    rng = np.random.default_rng(20260101)
    workspace = np.array(WORKSPACE)
    poses = np.concatenate([
        ramp.rows,
        geometry.home_pose + rng.uniform(-1.0, 1.0, (random_count, 6)) * workspace])
    lengths = inverse_kinematics(geometry, poses)
    batch = geometry.home_pose + rng.uniform(-1.0, 1.0, (batch_count, 6)) * workspace
    tracking = inverse_kinematics(geometry, ramp.sample(np.arange(10001) * 1e-3, 10.0))
    home = geometry.home_pose
    clock = time.perf_counter

    def median_each(call, items):
        times = []
        for item in items:
            start = clock()
            call(item)
            times.append(clock() - start)
        return statistics.median(times)

    def best(call, repeat):
        times = []
        for _ in range(repeat):
            start = clock()
            call()
            times.append(clock() - start)
        return min(times)

    def track():
        times = []
        last = home
        for target in tracking:
            start = clock()
            result = forward_kinematics(geometry, target, last)
            times.append(clock() - start)
            last = result if result.converged else home
        return statistics.median(times)

    figures = {}
    figures['IK one pose'] = 1e6 * median_each(
        lambda pose: inverse_kinematics(geometry, pose), list(poses) * 3)
    figures['IK batch'] = 1e9 * best(lambda: inverse_kinematics(geometry, batch), 3) \
        / batch_count
    figures['FK cold single'] = 1e6 * median_each(
        lambda target: forward_kinematics(geometry, target, home), lengths)
    figures['FK warm tracking'] = 1e6 * track()
    figures['FK batch'] = 1e6 * best(lambda: forward_kinematics(geometry, lengths), 3) \
        / len(lengths)
    return figures


def run_checkout(checkout, random_count, batch_count):
    """Run :func:`measure` in a subprocess that imports the package from ``checkout``."""
    environment = dict(os.environ, PYTHONPATH=str(Path(checkout).resolve()))
    output = subprocess.run(
        [sys.executable, __file__, '--worker', str(random_count), str(batch_count)],
        env=environment, check=True, capture_output=True, text=True).stdout
    return json.loads(output.splitlines()[-1])


def main(argv=None) -> int:
    """Parse the arguments, run the rounds and print the table; return the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('old', nargs='?', help='checkout of the baseline revision')
    parser.add_argument('new', nargs='?', help='checkout of the revision to compare')
    parser.add_argument('--rounds', type=int, default=5, help='runs of each checkout')
    parser.add_argument('--random', type=int, default=1000, help='random FK poses')
    parser.add_argument('--batch', type=int, default=1_000_000, help='IK batch size')
    parser.add_argument('--worker', nargs=2, type=int, help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.worker:
        print(json.dumps(measure(*args.worker)))
        return 0
    if not (args.old and args.new):
        parser.error('give the old and the new checkout')
    runs = {args.old: [], args.new: []}
    for _ in range(args.rounds):
        for checkout in (args.old, args.new):
            runs[checkout].append(run_checkout(checkout, args.random, args.batch))
    print(f'median of {args.rounds} alternating runs; old: {args.old}, new: {args.new}')
    print(f'{"measure":<18} {"unit":>8} {"old":>10} {"new":>10} {"new/old":>8}')
    for name, unit in MEASURES:
        old = statistics.median(run[name] for run in runs[args.old])
        new = statistics.median(run[name] for run in runs[args.new])
        print(f'{name:<18} {unit:>8} {old:>10.3f} {new:>10.3f} {new / old:>8.2f}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
