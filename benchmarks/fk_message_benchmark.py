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
Benchmark fk_node's per-message cost: this checkout's callback against another revision's.

Both revisions' ``FkNode`` are built in this one process, the other revision's package copied
under another name (as benchmarks/compare_revisions.py does), with the same parameter files
and the assembly-mode margin off (its worker is not on the message path); their
``leg_lengths`` callback is called with the same messages, alternately, message by message
(which goes first swaps each round), so that both see the same load of a shared machine. The
callback is the node's whole work for a message: convert, decide, publish ``estimated_pose``
(no subscriber, so the stamped pose and ``/tf`` are skipped by both). Two sets of lengths:

- ``table 3``: the Table 3 ramp sampled at 1 kHz, with config/example_limits.yaml (every
  pose accepted, none near a singularity);
- ``fold``: the home pose turned in yaw from 0 to -120 degrees in 1000 steps, on the paper's
  platform without limits: the tracker passes the fold singularity near -89.6 degrees and
  then follows the other assembly mode (the new revision flags each estimate after it).

It prints the median and 90th percentile per message, microseconds, and new / old::

    mkdir /tmp/base && git archive main stewart_kinematics config | tar -x -C /tmp/base
    source scripts/ros_env.sh
    .venv/bin/python benchmarks/fk_message_benchmark.py /tmp/base --rounds 5
"""

import argparse
import math
from pathlib import Path
import statistics
import sys
import tempfile

from compare_revisions import (  # benchmarks/, the script's folder
    build_node,
    import_baseline,
    table3_ramp,
    time_alternately,
)
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
#: Messages per round of each set.
MESSAGES = 1000


def length_sets(package, config):
    """Return {set name: (parameter file names, lengths (MESSAGES, 6))}."""
    limited = package.load_geometry([config / 'paper_platform.yaml',
                                     config / 'example_limits.yaml'])
    table = package.inverse_kinematics(
        limited, table3_ramp(package).sample(np.linspace(0.0, 10.0, MESSAGES), 10.0))
    paper = package.load_geometry(config / 'paper_platform.yaml')
    fold = np.tile(paper.home_pose, (MESSAGES, 1))
    fold[:, 5] = np.radians(np.linspace(0.0, -120.0, MESSAGES))
    return {
        'table 3': (('paper_platform.yaml', 'example_limits.yaml'), table),
        'fold': (('paper_platform.yaml',), package.inverse_kinematics(paper, fold)),
    }


def fk_node(package, namespace, parameter_files):
    """Build a revision's fk_node with the parameter files, in ``namespace``, margin off."""
    return build_node(package, 'fk_node.FkNode', namespace, parameter_files,
                      'assembly_mode_margin_period:=0.0')


def reset_trackers(nodes):
    """Return a function that resets every node's pose tracker (each round starts cold)."""
    def reset():
        for node in nodes:
            node.tracker.reset()
    return reset


def main(argv=None) -> int:
    """Build the nodes, time them, print the table; return the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('old', help='checkout (or archive) of the baseline revision: a folder '
                                    'with stewart_kinematics/ and config/')
    parser.add_argument('--rounds', type=int, default=5, help='rounds of every measurement')
    options = parser.parse_args(argv)
    import rclpy
    import stewart_kinematics as new
    from stewart_kinematics.ros.message_conversions import legs_to_message

    old_root = Path(options.old).resolve()
    rclpy.init()
    rows = []
    try:
        with tempfile.TemporaryDirectory() as directory:
            old = import_baseline(old_root, directory)
            for name, (files, lengths) in length_sets(new, ROOT / 'config').items():
                nodes = [fk_node(old, 'old', [old_root / 'config' / f for f in files]),
                         fk_node(new, 'new', [ROOT / 'config' / f for f in files])]
                messages = [legs_to_message(values) for values in lengths]
                seconds = time_alternately([node.on_leg_lengths for node in nodes], messages,
                                           options.rounds, reset_trackers(nodes))
                flagged = bool(getattr(nodes[1].tracker, 'ambiguous', False))
                baseline = statistics.median(seconds[0])
                for label, times in zip(('old', 'new'), seconds):
                    median = statistics.median(times)
                    rows.append((name, label, median * 1e6, np.percentile(times, 90) * 1e6,
                                 median / baseline))
                rows[-1] += (flagged,)
                for node in nodes:
                    node.destroy_node()
    finally:
        rclpy.try_shutdown()
    print(f'fk_node leg_lengths callback, {options.rounds} rounds of {MESSAGES} messages, '
          f'calls alternating; old: {old_root}')
    print(f'{"lengths":<9} {"node":<5} {"median us":>10} {"p90 us":>8} {"new/old":>8}')
    for name, label, median, p90, ratio, *flag in rows:
        note = '' if not flag else f'  (new tracker ends ambiguous: {bool(flag[0])})'
        print(f'{name:<9} {label:<5} {median:>10.1f} {p90:>8.1f} {ratio:>8.2f}{note}')
    return 0 if all(math.isfinite(row[2]) for row in rows) else 1


if __name__ == '__main__':
    sys.exit(main())
