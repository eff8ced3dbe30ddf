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
Compare the kinematics speed of two checkouts of this package, call by call, in one process.

The old checkout's package is copied under another name (``baseline_stewart_kinematics``) so
that both import side by side; every measurement then alternates between them, call by call
(which goes first swaps each round), so that both see the same load of a shared machine. On the
paper's platform it times: IK of one pose, IK of a batch, FK of one pose from home (given as
the guess; the Table 3 rows and random poses within +-0.1 m and +-15 deg of home), FK of the
same without a guess (cold: from home in a revision without a start table), FK tracking the
Table 3 ramp at 1 kHz from the last result (warm), FK of the cold set as one batch without
a guess, and every assembly mode (processor time) on Dietmaier's 40-mode platform and on the
paper's at home and at the end of Table 3. It prints the median per call (per pose for batches;
best of the rounds for them) and new / old::

    git worktree add /tmp/base main
    .venv/bin/python benchmarks/compare_revisions.py /tmp/base . --rounds 5
"""

import argparse
import functools
import importlib
import math
from pathlib import Path
import re
import shutil
import statistics
import sys
import tempfile
import time

import numpy as np

#: Half-widths of the random workspace around the home pose: metres, then radians.
WORKSPACE = np.array([0.1, 0.1, 0.1] + [math.radians(15.0)] * 3)
BASELINE = 'baseline_stewart_kinematics'


def import_baseline(checkout, directory):
    """Import ``checkout``'s package as :data:`BASELINE`, from a renamed copy in ``directory``."""
    target = Path(directory) / BASELINE
    shutil.copytree(Path(checkout) / 'stewart_kinematics', target)
    for path in target.rglob('*.py'):
        text = path.read_text(encoding='utf-8')
        path.write_text(re.sub(r'\bstewart_kinematics\b(?=[.\s])', BASELINE, text),
                        encoding='utf-8')
    sys.path.insert(0, str(directory))
    return importlib.import_module(BASELINE)


def table3_ramp(package):
    """Return a revision's Ramp of the paper's Table 3 (10 s, from home)."""
    return package.Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01],
                                   [0.1, 0.15, 0.5325], [0.0, 0.0, 0.0], [1.5, -1.5, 2.0],
                                   [15.0, -15.0, 20.0])


def build_node(package, node_class, namespace, parameter_files, *parameters):
    """
    Build a revision's node in this process, for the message benchmarks.

    :param node_class: ``'ik_node.IkNode'`` or ``'fk_node.FkNode'``, in the package's ros/.
    :param parameters: ``name:=value`` strings given with ``-p`` after the files.
    """
    module, name = node_class.split('.')
    ros_module = importlib.import_module(f'{package.__name__}.ros.{module}')
    arguments = ['--ros-args', '-r', f'__ns:=/{namespace}']
    for path in parameter_files:
        arguments += ['--params-file', str(path)]
    for parameter in parameters:
        arguments += ['-p', parameter]
    return getattr(ros_module, name)(cli_args=arguments)


def time_alternately(callbacks, messages, rounds, before_round=lambda: None):
    """
    Call every callback with every message, alternating message by message; seconds per call.

    Which callback goes first swaps each round, so that all see the same load of a shared
    machine. ``before_round()`` runs before each round (a tracker's reset).
    """
    clock = time.perf_counter
    seconds = [[] for _ in callbacks]
    for round_ in range(rounds):
        order = list(range(len(callbacks)) if round_ % 2 == 0
                     else reversed(range(len(callbacks))))
        before_round()
        for message in messages:
            for k in order:
                start = clock()
                callbacks[k](message)
                seconds[k].append(clock() - start)
    return seconds


def load_geometry_of(package, name):
    """``load_geometry`` of a revision: in its root, its parameters/ or its parameter_spec."""
    if hasattr(package, 'load_geometry'):
        return package.load_geometry
    for module in ('parameters', 'parameter_spec'):
        try:
            return importlib.import_module(f'{name}.{module}').load_geometry
        except (ImportError, AttributeError):
            continue
    raise ImportError(f'no load_geometry in {name}')


def workload(package, config, random_count, batch_count):
    """Return the inputs of every measurement, from ``package`` (the new one)."""
    geometry = package.load_geometry(config)
    ramp = package.Ramp.from_table([0.0, 0.0, 0.4325], [0.01, 0.015, 0.01], [0.1, 0.15, 0.5325],
                                   [0.0, 0.0, 0.0], [1.5, -1.5, 2.0], [15.0, -15.0, 20.0])
    rng = np.random.default_rng(20260101)
    poses = np.concatenate([
        ramp.rows, geometry.home_pose + rng.uniform(-1.0, 1.0, (random_count, 6)) * WORKSPACE])
    return {
        'poses': poses,
        'lengths': package.inverse_kinematics(geometry, poses),
        'batch': geometry.home_pose + rng.uniform(-1.0, 1.0, (batch_count, 6)) * WORKSPACE,
        'tracking': package.inverse_kinematics(
            geometry, ramp.sample(np.arange(10001) * 1e-3, 10.0)),
    }


def compare(packages, config, rounds, data):
    """Time both packages alternately; return ``{measure: (unit, old, new)}``."""
    clock = time.perf_counter
    geometries = [package.load_geometry(config) for package in packages]
    per_call = {name: ([], []) for name in ('IK one pose', 'FK cold single',
                                            'FK cold no guess', 'FK warm tracking')}
    for k in (0, 1):  # the first cold solve builds a start table: not timed
        packages[k].forward_kinematics(geometries[k], data['lengths'][0])
    batches = {'IK batch': ([], []), 'FK batch': ([], [])}

    def timed(call, *arguments):
        start = clock()
        result = call(*arguments)
        return clock() - start, result

    for round_ in range(rounds):
        order = (0, 1) if round_ % 2 == 0 else (1, 0)
        for pose in data['poses']:
            for k in order:
                per_call['IK one pose'][k].append(timed(
                    packages[k].inverse_kinematics, geometries[k], pose)[0])
        for lengths in data['lengths']:
            for k in order:
                per_call['FK cold single'][k].append(timed(
                    packages[k].forward_kinematics, geometries[k], lengths,
                    geometries[k].home_pose)[0])
        for lengths in data['lengths']:
            for k in order:
                per_call['FK cold no guess'][k].append(timed(
                    packages[k].forward_kinematics, geometries[k], lengths)[0])
        last = [geometry.home_pose for geometry in geometries]
        for lengths in data['tracking']:
            for k in order:
                seconds, result = timed(packages[k].forward_kinematics, geometries[k], lengths,
                                        last[k])
                per_call['FK warm tracking'][k].append(seconds)
                last[k] = result if result.converged else geometries[k].home_pose
        for k in order:
            batches['IK batch'][k].append(timed(
                packages[k].inverse_kinematics, geometries[k], data['batch'])[0]
                / len(data['batch']))
            batches['FK batch'][k].append(timed(
                packages[k].forward_kinematics, geometries[k], data['lengths'])[0]
                / len(data['lengths']))
    modes = assembly_cases(packages, config)
    for round_ in range(rounds):
        for name, calls in modes.items():
            for k in ((0, 1) if round_ % 2 == 0 else (1, 0)):
                start = time.process_time()
                calls[k]()
                per_call.setdefault(name, ([], []))[k].append(time.process_time() - start)
    figures = {name: ('ms' if name in modes else 'us',
                      (1e3 if name in modes else 1e6) * statistics.median(old),
                      (1e3 if name in modes else 1e6) * statistics.median(new))
               for name, (old, new) in per_call.items()}
    figures.update({name: ('us/pose', 1e6 * min(old), 1e6 * min(new))
                    for name, (old, new) in batches.items()})
    return figures


def assembly_cases(packages, config):
    """Every assembly mode of three sets of lengths, as calls of each package (warmed up)."""
    import yaml
    data = yaml.safe_load((Path(config).parent.parent / 'test' / 'resources'
                           / 'dietmaier_40_modes.yaml').read_text(encoding='utf-8'))
    end = np.array([0.1, 0.15, 0.5325] + [math.radians(a) for a in (15.0, -15.0, 20.0)])
    cases = {}
    for name in ('modes Dietmaier', 'modes paper home', 'modes paper end'):
        cases[name] = []
        for package in packages:
            if name == 'modes Dietmaier':
                geometry = package.Geometry(np.array(data['base_joints']),
                                            np.array(data['platform_joints']),
                                            home_pose=[0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
                lengths = np.array(data['leg_lengths'])
            else:
                geometry = package.load_geometry(config)
                lengths = package.inverse_kinematics(
                    geometry, geometry.home_pose if name == 'modes paper home' else end)
            call = functools.partial(package.assembly_modes, geometry, lengths)
            call()   # the start systems: not timed
            cases[name].append(call)
    return cases


def main(argv=None) -> int:
    """Parse the arguments, run the comparison and print the table; return the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('old', help='checkout of the baseline revision')
    parser.add_argument('new', help='checkout of the revision to compare')
    parser.add_argument('--rounds', type=int, default=5, help='rounds of every measurement')
    parser.add_argument('--random', type=int, default=1000, help='random FK poses')
    parser.add_argument('--batch', type=int, default=1_000_000, help='IK batch size')
    args = parser.parse_args(argv)
    sys.path.insert(0, str(Path(args.new).resolve()))
    new = importlib.import_module('stewart_kinematics')
    config = str(Path(args.new).resolve() / 'config' / 'paper_platform.yaml')
    with tempfile.TemporaryDirectory() as directory:
        old = import_baseline(Path(args.old).resolve(), directory)
        old.load_geometry = load_geometry_of(old, BASELINE)
        new.load_geometry = load_geometry_of(new, 'stewart_kinematics')
        data = workload(new, config, args.random, args.batch)
        figures = compare((old, new), config, args.rounds, data)
    print(f'{args.rounds} rounds, calls alternating; old: {args.old} ({Path(old.__file__).parent}'
          f' copied), new: {Path(new.__file__).parent}')
    print(f'{"measure":<18} {"unit":>8} {"old":>10} {"new":>10} {"new/old":>8}')
    for name in ('IK one pose', 'IK batch', 'FK cold single', 'FK cold no guess',
                 'FK warm tracking', 'FK batch', 'modes Dietmaier', 'modes paper home',
                 'modes paper end'):
        unit, old_figure, new_figure = figures[name]
        print(f'{name:<18} {unit:>8} {old_figure:>10.3f} {new_figure:>10.3f} '
              f'{new_figure / old_figure:>8.2f}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
