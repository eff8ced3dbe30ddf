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
Benchmark one pose (issue 32): ``check_pose``, ik_node's work per message, a cueing step.

This checkout against another revision, both imported in this one process (the other
revision's package copied under another name, as benchmarks/compare_revisions.py does), called
alternately, call by call (which goes first swaps each round), so that both see the same load
of a shared machine; the ratio new / old is the figure to trust on a busy machine, the
microseconds on an idle one. It times:

- ``limits.check_pose`` of one pose on the paper's platform, (a) with the example limits
  (stroke, joint cones, singularity margin, leg collisions) and (b) with every limit kind on
  (those, plus the example masses and leg force limits of -500 N and 2000 N): the Table 3
  ramp at 1 kHz (every pose allowed) and poses that break limits;
- ik_node's ``target_pose`` callback (convert, decide, publish ``leg_lengths``, no
  subscriber) on the accepted Table 3 ramp, example limits (needs the ROS environment;
  ``--no-node`` skips it);
- :meth:`stewart_kinematics.cueing.MotionCueing.step` of the shipped ``motion_cueing.yaml``
  on the paper's platform with the example limits, over the four scenarios at 1 kHz, and how
  many single-pose limit checks a step makes.

It prints the median (and 90th percentile) per call, microseconds, new / old, and the targets
of issue 32 (check_pose < 30 us with every limit kind on, ik_node's work < 60 us per accepted
message, a cueing step < 100 us; medians)::

    mkdir /tmp/base && git archive main stewart_kinematics config | tar -x -C /tmp/base
    source scripts/ros_env.sh
    .venv/bin/python benchmarks/one_pose_benchmark.py /tmp/base --rounds 5
"""

import argparse
import functools
from pathlib import Path
import statistics
import sys
import tempfile
import time

from compare_revisions import (  # benchmarks/, the script's folder
    build_node,
    import_baseline,
    table3_ramp,
    time_alternately,
)
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
#: Poses (or messages) per round of each set.
POSES = 500
#: Seconds of each cueing scenario at 1 kHz.
CUE_SECONDS = 2.0
TARGETS = {'check_pose': 30e-6, 'ik_node': 60e-6, 'cue step': 100e-6}
#: The leg force limits of the 'every limit kind' case, newtons.
FORCE_LIMITS = {'leg_force_min': -500.0, 'leg_force_max': 2000.0}


def geometries(package, root):
    """Return a revision's (example limits, every limit kind) geometries of the platform."""
    config = Path(root) / 'config'
    load = package.load_geometry
    limited = load([str(config / 'paper_platform.yaml'), str(config / 'example_limits.yaml')])
    every = load([str(config / name) for name in (
        'paper_platform.yaml', 'example_limits.yaml', 'example_masses.yaml')])
    return limited, every.with_limits(**FORCE_LIMITS)


def pose_sets(package):
    """Return (allowed, refused) poses: the Table 3 ramp, and random poses off home."""
    allowed = table3_ramp(package).sample(np.linspace(0.0, 10.0, POSES), 10.0)
    rng = np.random.default_rng(32)
    refused = allowed[0] + rng.uniform(-1.0, 1.0, (POSES, 6)) * [0.15, 0.15, 0.15, 0.6, 0.6,
                                                                 0.6]
    return allowed, refused


def check_pose_rows(packages, roots, rounds):
    """Time check_pose alternately; return rows (case, old s list, new s list, violations)."""
    rows = []
    cases = []
    for package, root in zip(packages, roots):
        limited, every = geometries(package, root)
        cases.append((limited, every))
    allowed, refused = pose_sets(packages[1])
    rotation = packages[1].euler_zyx_to_matrix
    for label, poses in (('ramp (allowed)', allowed), ('off home (most refused)', refused)):
        inputs = [(pose[:3].copy(), rotation(pose[3:])) for pose in poses]
        for index, kind in enumerate(('example limits', 'every limit kind')):
            calls = [functools.partial(_check, package.limits.check_pose, geometry_pair[index])
                     for package, geometry_pair in zip(packages, cases)]
            seconds = time_alternately(calls, inputs, rounds)
            broken = sum(bool(packages[1].limits.check_pose(cases[1][index], *pose))
                         for pose in inputs)
            rows.append((f'check_pose, {kind}, {label} ({broken} of {len(inputs)} refused)',
                         seconds[0], seconds[1]))
    return rows


def _check(check_pose, geometry, pose):
    return check_pose(geometry, *pose)


def ik_node_rows(packages, roots, rounds):
    """Time ik_node's target_pose callback on the accepted ramp; return rows."""
    import rclpy
    from stewart_kinematics.ros.message_conversions import pose_to_message
    rclpy.init()
    try:
        nodes = [build_node(package, 'ik_node.IkNode', f'rev{k}', [
            Path(root) / 'config' / 'paper_platform.yaml',
            Path(root) / 'config' / 'example_limits.yaml'])
            for k, (package, root) in enumerate(zip(packages, roots))]
        allowed, _ = pose_sets(packages[1])
        messages = [pose_to_message(pose) for pose in allowed]
        for node in nodes:   # warm-up: the first message builds what is cached
            node.on_target_pose(messages[0])
        seconds = time_alternately([node.on_target_pose for node in nodes], messages, rounds)
        for node in nodes:
            node.destroy_node()
    finally:
        rclpy.try_shutdown()
    return [('ik_node target_pose callback, accepted ramp, example limits', *seconds)]


def cueing_core(package, root):
    """Return a revision's MotionCueing as motion_cueing_node builds it from the shipped files."""
    values = {}
    for name in ('paper_platform.yaml', 'example_limits.yaml', 'motion_cueing.yaml'):
        values.update(package.parameters.read_parameter_file(
            Path(root) / 'config' / name, 'motion_cueing_node'))
    return package.cueing.MotionCueing.from_parameters(values)


def cue_rows(packages, roots, rounds):
    """Time the cueing step alternately over the four scenarios; return rows and checks a step."""
    import importlib
    scenarios = importlib.import_module(packages[1].__name__ + '.cueing.scenarios')
    samples = []
    for name in scenarios.SCENARIO_NAMES:
        generated = scenarios.scenario(name, 1000.0)
        count = min(len(generated.times), int(CUE_SECONDS * 1000))
        samples.append(list(zip(generated.times[:count].tolist(),
                                generated.specific_force[:count].tolist(),
                                generated.angular_velocity[:count].tolist())))
    clock = time.perf_counter
    seconds = ([], [])
    for round_ in range(rounds):
        order = (0, 1) if round_ % 2 == 0 else (1, 0)
        for scenario_samples in samples:
            cores = [cueing_core(package, root) for package, root in zip(packages, roots)]
            for t, force, angular in scenario_samples:
                for k in order:
                    start = clock()
                    cores[k].step(t, force, angular)
                    seconds[k].append(clock() - start)
    checks = [checks_per_step(package, root, samples) for package, root in zip(packages, roots)]
    return [(f'cueing step, shipped tuning, four scenarios ({CUE_SECONDS:g} s each at 1 kHz)',
             *seconds)], checks


def checks_per_step(package, root, samples):
    """Return the single-pose limit checks per step (mean) of a revision, over the samples."""
    model = package.limits.LimitModel
    original = model.check_pose
    count = [0]

    def counted(self, *arguments, **keywords):
        count[0] += 1
        return original(self, *arguments, **keywords)

    model.check_pose = counted
    try:
        steps = 0
        for scenario_samples in samples:
            core = cueing_core(package, root)
            for t, force, angular in scenario_samples:
                core.step(t, force, angular)
                steps += 1
    finally:
        model.check_pose = original
    return count[0] / steps


def main(argv=None) -> int:
    """Import both revisions, time them, print the table and the targets; return 0."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('old', help='checkout (or archive) of the baseline revision: a folder '
                                    'with stewart_kinematics/ and config/')
    parser.add_argument('--rounds', type=int, default=5, help='rounds of every measurement')
    parser.add_argument('--no-node', action='store_true', help='skip ik_node (no ROS needed)')
    options = parser.parse_args(argv)
    import stewart_kinematics as new
    old_root = Path(options.old).resolve()
    roots = (old_root, ROOT)
    with tempfile.TemporaryDirectory() as directory:
        old = import_baseline(old_root, directory)
        packages = (old, new)
        for package in packages:
            for module in ('limits', 'parameters', 'cueing'):
                setattr(package, module, __import__(f'{package.__name__}.{module}',
                                                    fromlist=['_']))
        rows = check_pose_rows(packages, roots, options.rounds)
        if not options.no_node:
            rows += ik_node_rows(packages, roots, options.rounds)
        cue, checks = cue_rows(packages, roots, options.rounds)
        rows += cue
    print(f'One pose, {options.rounds} rounds, calls alternating; old: {old_root}')
    print(f'{"measure":<86} {"old us":>8} {"new us":>8} {"new p90":>8} {"new/old":>8}')
    medians = {}
    for name, old_seconds, new_seconds in rows:
        old_median, new_median = statistics.median(old_seconds), statistics.median(new_seconds)
        medians[name] = new_median
        print(f'{name:<86} {old_median * 1e6:>8.1f} {new_median * 1e6:>8.1f} '
              f'{np.percentile(new_seconds, 90) * 1e6:>8.1f} {new_median / old_median:>8.2f}')
    print(f'single-pose limit checks (LimitModel.check_pose) per cueing step: old '
          f'{checks[0]:.2f}, new {checks[1]:.2f}')
    print()
    print(f'{"Target (issue 32, median)":<64} {"Met":>4}  This run')
    for target, key in (
            ('check_pose < 30 us, every limit kind on (ramp)', 'check_pose, every limit kind, '
                                                               'ramp'),
            ('ik_node work < 60 us per accepted message', 'ik_node'),
            ('cueing step < 100 us', 'cueing step')):
        matched = [value for name, value in medians.items() if name.startswith(key)]
        if not matched:
            continue
        limit = TARGETS['check_pose' if key.startswith('check') else
                        'ik_node' if key == 'ik_node' else 'cue step']
        print(f'{target:<64} {"yes" if matched[0] < limit else "no":>4}  '
              f'{matched[0] * 1e6:.1f} us')
    return 0


if __name__ == '__main__':
    sys.exit(main())
