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
Where a cold forward-kinematics solve spends its time, against basic-robotics' compiled kernel.

The figures behind the benchmark pages' note on the compiled peer: ``cProfile`` of our cold
solves without a guess (from the start table; time per solve by function with and without its
callees, calls per solve; then the same from home), ``timeit`` of the numpy calls a Newton
step makes on 6-element arrays, and ``timeit`` of basic-robotics' numba-compiled
``SPFKinSpaceR`` stopped after one iteration and run to convergence (in its plate frame, see
benchmarks/run_benchmarks.py). Run after ``scripts/run_benchmarks.sh`` has installed the
baselines: ``.venv/bin/python benchmarks/profile_fk.py``.
"""

import cProfile
import math
from pathlib import Path
import pstats
import sys
import timeit

import numpy as np

from stewart_kinematics import forward_kinematics, inverse_kinematics, load_geometry

sys.path.insert(0, str(Path(__file__).resolve().parent))
import run_benchmarks  # noqa: E402, I100  (a sibling script, not a package)

#: Poses profiled; calls per timeit run, and the runs whose best is reported (the best is the
#: figure least disturbed by other work on the machine).
POSES = 1000
NUMBER = 200
RUNS = 25


def per_call_microseconds(statement, namespace):
    """Best of :data:`RUNS` ``timeit`` runs of ``statement``, microseconds per call."""
    return min(timeit.repeat(statement, globals=namespace, number=NUMBER, repeat=RUNS)) \
        / NUMBER * 1e6


def profile(geometry, lengths, guess, label):
    """Print the ``cProfile`` of one cold solve of each of ``lengths`` from ``guess``."""
    results = [forward_kinematics(geometry, target, guess) for target in lengths]
    iterations = np.mean([result.iterations for result in results])
    inversions = []
    inverse = np.linalg.inv

    def counting_inverse(matrix):
        inversions.append(1)
        return inverse(matrix)
    np.linalg.inv = counting_inverse
    try:
        for target in lengths:
            forward_kinematics(geometry, target, guess)
    finally:
        np.linalg.inv = inverse
    profiler = cProfile.Profile()
    profiler.enable()
    for target in lengths:
        forward_kinematics(geometry, target, guess)
    profiler.disable()
    stats = pstats.Stats(profiler)
    total = stats.total_tt
    print(f'cProfile of {POSES} cold solves {label}: {iterations:.2f} Newton steps and '
          f'{len(inversions) / POSES:.2f} Jacobian inversions each; {total / POSES * 1e6:.1f} us '
          'per solve under the profiler, which inflates small calls:')
    print(f'{"share":>6} {"us/solve":>9} {"own us":>7} {"calls/solve":>11}  function '
          '(share: of the time per solve, callees included; own: without them)')
    rows = sorted(stats.stats.items(), key=lambda item: -item[1][3])
    for (path, line, name), (_, calls, tottime, cumtime, _) in rows[:16]:
        print(f'{100.0 * cumtime / total:5.0f}% {cumtime / POSES * 1e6:9.1f} '
              f'{tottime / POSES * 1e6:7.1f} {calls / POSES:11.1f}  '
              f'{Path(path).name}:{line}({name})')
    print()


def main() -> int:
    """Print the profile and the timings."""
    geometry = load_geometry(run_benchmarks.PLATFORM_FILE)
    rng = np.random.default_rng(20260101)
    poses = geometry.home_pose + rng.uniform(-1.0, 1.0, (POSES, 6)) * run_benchmarks.WORKSPACE
    lengths = inverse_kinematics(geometry, poses)
    for label, guess in (('without a guess (the start table)', None),
                         ('from home (the home pose as the guess)', geometry.home_pose)):
        profile(geometry, lengths, guess, label)

    matrix = np.eye(6) + 0.1 * rng.standard_normal((6, 6))
    vector = rng.standard_normal(6)
    floats = vector.tolist()
    namespace = {'np': np, 'matrix': matrix, 'vector': vector, 'floats': floats,
                 'math': math, 'geometry': geometry, 'target': lengths[0],
                 'forward_kinematics': forward_kinematics}
    print('timeit, microseconds per call:')
    for label, statement in (
            ('forward_kinematics, cold solve without a guess',
             'forward_kinematics(geometry, target)'),
            ('forward_kinematics, cold solve from home',
             'forward_kinematics(geometry, target, geometry.home_pose)'),
            ('np.linalg.inv, 6x6', 'np.linalg.inv(matrix)'),
            ('np.linalg.solve, 6x6', 'np.linalg.solve(matrix, vector)'),
            ('6x6 @ list of 6 floats, .tolist()', '(matrix @ floats).tolist()'),
            ('6-vector numpy add', 'vector + vector'),
            ('six leg errors in float arithmetic (list comprehension)',
             '[a - b for a, b in zip(floats, floats)]'),
            ('math.sqrt of a sum of three squares, six times',
             '[math.sqrt(a * a + a * a + a * a) for a in floats]')):
        print(f'{per_call_microseconds(statement, namespace):9.2f}  {label}')

    try:
        plate = run_benchmarks.BasicRobotics(
            geometry, run_benchmarks.PLATE_FRAME_OFFSET,
            run_benchmarks.BASIC_ROBOTICS_TIGHT_TOLERANCE, 'basic-robotics')
    except Exception as error:  # noqa: B902 - any failure to install or import is reported
        print(f'basic-robotics not available: {type(error).__name__}: {error}')
        return 0
    sp = plate.sp
    kernel_namespace = {'kernel': plate.kernel, 'sp': sp, 'guess': plate.home_guess,
                        'target': np.array(lengths[0])}
    for label, cap, tolerance in (
            ('one iteration', 1, run_benchmarks.BASIC_ROBOTICS_TIGHT_TOLERANCE),
            ('to convergence at its own tolerance (5e-6 m^2)', 200,
             run_benchmarks.BASIC_ROBOTICS_OWN_TOLERANCE),
            ('to convergence at 1e-14 m^2', 200,
             run_benchmarks.BASIC_ROBOTICS_TIGHT_TOLERANCE)):
        statement = (f'kernel(target, guess.copy(), sp._bottom_joints_init, '
                     f'sp._top_joints_init, {cap}, {tolerance}, {tolerance}, sp.leg_ext_min)')
        _, steps = eval(statement, kernel_namespace)  # noqa: S307 - our own statement
        print(f'{per_call_microseconds(statement, kernel_namespace):9.2f}  basic-robotics '
              f'SPFKinSpaceR (numba), {label}: {steps} iterations')
    return 0


if __name__ == '__main__':
    sys.exit(main())
