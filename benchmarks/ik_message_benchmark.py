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
Benchmark ik_node's per-message cost: this checkout's callback against another revision's.

Both revisions' ``IkNode`` are built in this one process, the other revision's package copied
under another name (as benchmarks/compare_revisions.py does), with the same parameter files;
their ``target_pose`` callback is called with the same messages, alternately, message by
message (which goes first swaps each round), so that both see the same load of a shared
machine. The callback is the node's whole work for a message: convert, decide, publish
``leg_lengths`` (no subscriber, so the other outputs are skipped by both). Poses: the Table 3
ramp sampled at 1 kHz (all within the example limits) and, apart, poses that break them.

It prints the median and 90th percentile per message, microseconds, and new / old::

    mkdir /tmp/base && git archive main stewart_kinematics config | tar -x -C /tmp/base
    source scripts/ros_env.sh
    .venv/bin/python benchmarks/ik_message_benchmark.py /tmp/base --rounds 5
"""

import argparse
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


def poses(package):
    """Return (accepted, refused) poses: the Table 3 ramp, and the same lowered 0.2 m."""
    accepted = table3_ramp(package).sample(np.linspace(0.0, 10.0, MESSAGES), 10.0)
    refused = accepted - [0.0, 0.0, 0.2, 0.0, 0.0, 0.0]      # every leg below leg_length_min
    return accepted, refused


def ik_node(package, namespace, parameter_files):
    """Build a revision's ik_node with the parameter files, in ``namespace``."""
    return build_node(package, 'ik_node.IkNode', namespace, parameter_files)


def main(argv=None) -> int:
    """Build the nodes, time them, print the table; return the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('old', help='checkout (or archive) of the baseline revision: a folder '
                                    'with stewart_kinematics/ and config/')
    parser.add_argument('--rounds', type=int, default=5, help='rounds of every measurement')
    options = parser.parse_args(argv)
    import rclpy
    import stewart_kinematics as new
    from stewart_kinematics.ros.message_conversions import pose_to_message

    old_root = Path(options.old).resolve()
    config = ROOT / 'config'
    rclpy.init()
    try:
        with tempfile.TemporaryDirectory() as directory:
            old = import_baseline(old_root, directory)
            no_collision = Path(directory) / 'no_leg_radius.yaml'
            no_collision.write_text('/**:\n  ros__parameters:\n    leg_radius: 0.0\n',
                                    encoding='utf-8')
            limits = [config / 'paper_platform.yaml', config / 'example_limits.yaml']
            old_limits = [old_root / 'config' / 'paper_platform.yaml',
                          old_root / 'config' / 'example_limits.yaml']
            nodes = {
                'old, example limits': ik_node(old, 'old', old_limits),
                'new, the same limits (leg_radius 0)': ik_node(
                    new, 'same', limits + [no_collision]),
                'new, example limits with leg_radius 0.02 (collisions)': ik_node(
                    new, 'collisions', limits),
            }
            accepted, refused = poses(new)
            rows = []
            for kind, pose_set in (('accepted', accepted), ('refused', refused)):
                messages = [pose_to_message(pose) for pose in pose_set]
                seconds = time_alternately([node.on_target_pose for node in nodes.values()],
                                           messages, options.rounds)
                baseline = statistics.median(seconds[0])
                for name, times in zip(nodes, seconds):
                    median = statistics.median(times)
                    rows.append((kind, name, median * 1e6, np.percentile(times, 90) * 1e6,
                                 median / baseline))
            for node in nodes.values():
                node.destroy_node()
    finally:
        rclpy.try_shutdown()
    print(f'ik_node target_pose callback, {options.rounds} rounds of {MESSAGES} messages, '
          f'calls alternating; old: {old_root}')
    print(f'{"poses":<9} {"node":<55} {"median us":>10} {"p90 us":>8} {"new/old":>8}')
    for kind, name, median, p90, ratio in rows:
        print(f'{kind:<9} {name:<55} {median:>10.1f} {p90:>8.1f} {ratio:>8.2f}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
