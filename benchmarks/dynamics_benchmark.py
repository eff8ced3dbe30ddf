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
Benchmark the inverse dynamics: ``leg_forces`` on arrays and on one pose, against baselines.

Run from the repository root::

    .venv/bin/python benchmarks/dynamics_benchmark.py [--rounds 7] [--poses 100000]

Method. The machine is shared, so every case runs once per round, in a rotating order, for
``--rounds`` rounds (interleaved: a slow moment hits every case alike); the table gives the
median over the rounds with the range, as CPU time of this process (one core: numpy runs
single-threaded here), and the ratio to the baseline measured in the same run: inverse
kinematics of the same poses (``inverse_kinematics``), the cheapest thing the package does with
a pose. The load average (1 minute) before and after is printed with the core count.

The cases, on the paper's platform, poses within 5 cm and 6 degrees of home, random twists and
accelerations, a 5 kg platform, a 20 kg payload 0.1 m above the platform origin, and legs of
1.5 kg (lower body) and 0.8 kg (upper body):

- *arrays, moving, leg masses*: ``leg_forces(geometry, poses, twists, accelerations)`` on N
  poses; the target of issue 29: at least 300,000 poses/s on one core;
- *arrays, static, massless legs*: the payload's static forces only;
- *one pose, moving, leg masses* and *one pose, static, massless legs*: a single call, timed
  over 2,000 calls; the target of issue 29: at most 30 us.
"""

import argparse
import os
from pathlib import Path
import platform
import statistics
import time

import numpy as np

from stewart_kinematics import (
    inverse_kinematics,
    leg_forces,
    LegBody,
    load_geometry,
    MassProperties,
    RigidBody,
)

ROOT = Path(__file__).resolve().parent.parent
CONFIG = ROOT / 'config' / 'paper_platform.yaml'
ARRAY_TARGET = 300_000     # poses per second, leg masses, one core
SINGLE_TARGET = 30e-6      # seconds per pose
SINGLE_CALLS = 2000
MASSES = MassProperties(
    platform=RigidBody(5.0, [0.0, 0.0, 0.02], [0.06, 0.06, 0.11, 0.0, 0.0, 0.0]),
    payload=RigidBody(20.0, [0.0, 0.0, 0.1], [0.2, 0.2, 0.3, 0.0, 0.0, 0.0]),
    leg_lower=LegBody(1.5, 0.2, 0.02), leg_upper=LegBody(0.8, 0.25, 0.01))
PAYLOAD_ONLY = MassProperties(platform=MASSES.platform, payload=MASSES.payload)


def cases(geometry, count):
    """Return name -> (callable, poses it computes) of every timed case."""
    rng = np.random.default_rng(29)
    offsets = [0.05, 0.05, 0.05] + [np.radians(6.0)] * 3
    poses = geometry.home_pose + rng.uniform(-1, 1, (count, 6)) * offsets
    twists = rng.uniform(-0.3, 0.3, (count, 6))
    accelerations = rng.uniform(-3.0, 3.0, (count, 6))
    pose, twist, acceleration = poses[0], twists[0], accelerations[0]

    def singles(call):
        def run():
            for _ in range(SINGLE_CALLS):
                call()
        return run

    return {
        'arrays: inverse_kinematics (baseline)': (
            lambda: inverse_kinematics(geometry, poses), count),
        'arrays: leg_forces, moving, leg masses': (
            lambda: leg_forces(geometry, poses, twists, accelerations, mass_properties=MASSES),
            count),
        'arrays: leg_forces, static, massless legs': (
            lambda: leg_forces(geometry, poses, mass_properties=PAYLOAD_ONLY), count),
        'one pose: inverse_kinematics (baseline)': (
            singles(lambda: inverse_kinematics(geometry, pose)), SINGLE_CALLS),
        'one pose: leg_forces, moving, leg masses': (
            singles(lambda: leg_forces(geometry, pose, twist, acceleration,
                                       mass_properties=MASSES)), SINGLE_CALLS),
        'one pose: leg_forces, static, leg masses': (
            singles(lambda: leg_forces(geometry, pose, mass_properties=MASSES)), SINGLE_CALLS),
        'one pose: leg_forces, static, massless legs': (
            singles(lambda: leg_forces(geometry, pose, mass_properties=PAYLOAD_ONLY)),
            SINGLE_CALLS),
    }


def interleaved(timed, rounds):
    """CPU seconds per pose of each case, one run per round, the order rotating."""
    names = list(timed)
    per_pose = {name: [] for name in names}
    for round_number in range(rounds):
        shift = round_number % len(names)
        for name in names[shift:] + names[:shift]:
            call, count = timed[name]
            start = time.process_time()
            call()
            per_pose[name].append((time.process_time() - start) / count)
    return per_pose


def main(argv=None):
    """Print the table of every case; exit 0 whether or not the targets are met."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--rounds', type=int, default=7)
    parser.add_argument('--poses', type=int, default=100_000)
    arguments = parser.parse_args(argv)
    geometry = load_geometry(CONFIG)
    timed = cases(geometry, arguments.poses)
    for call, _ in timed.values():   # warm up: constants, caches
        call()
    print(f'{platform.python_implementation()} {platform.python_version()}, numpy '
          f'{np.__version__}, {platform.machine()}')
    print(f'Before: load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores')
    per_pose = interleaved(timed, arguments.rounds)
    print(f'After: load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores')
    print()
    print(f'| Case | CPU time per pose: median ({arguments.rounds} interleaved rounds; range) '
          '| Poses per second | Against the baseline |')
    print('| --- | --- | --- | --- |')
    for name, values in per_pose.items():
        median = statistics.median(values)
        kind = name.split(':')[0]
        baseline = statistics.median(per_pose[f'{kind}: inverse_kinematics (baseline)'])
        print(f'| {name} | {median * 1e6:.2f} us ({min(values) * 1e6:.2f} to '
              f'{max(values) * 1e6:.2f}) | {1.0 / median:,.0f} | {median / baseline:.1f}x |')
    arrays = statistics.median(per_pose['arrays: leg_forces, moving, leg masses'])
    single = statistics.median(per_pose['one pose: leg_forces, moving, leg masses'])
    print()
    print(f'Target: arrays with leg masses >= {ARRAY_TARGET:,} poses/s: {1.0 / arrays:,.0f} '
          f'({"met" if 1.0 / arrays >= ARRAY_TARGET else "missed"})')
    print(f'Target: one pose <= {SINGLE_TARGET * 1e6:.0f} us: {single * 1e6:.1f} us with leg '
          f'masses, moving ({"met" if single <= SINGLE_TARGET else "missed"})')
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
