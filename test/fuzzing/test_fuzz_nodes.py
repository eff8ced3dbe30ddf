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
The message fuzzer against every declared node, as a process: a bounded run of each.

Every node of :data:`stewart_kinematics.ros.interfaces.NODE_INTERFACES` is started from its
console script and fuzzed by :func:`fuzzing.node_fuzzer.fuzz_node`: hostile
messages on every subscription, up to 1 kHz, with parameter changes through its parameter
services; then the invariants (alive and answering, every output finite and within the limits,
parameter refusals, /diagnostics once a second with counts that add up). A node added to the
declaration is fuzzed here without a change.

Environment: ``STEWART_FUZZ_SEED`` (default: a new random seed each run, printed with every
failure), ``STEWART_FUZZ_MESSAGES`` (per node, default :data:`MESSAGES`). A failure prints the
seed and the command that replays it; ``scripts/fuzz_nodes.sh --minutes 10`` runs longer.
Run with ``-s`` to see the figures (lines starting ``FUZZ``).
"""

import os
from pathlib import Path
import random

from fuzzing.node_fuzzer import fuzz_node, FuzzSettings
from helpers import free_udp_port
import pytest

from stewart_kinematics.ros.interfaces import NODE_INTERFACES

# serial: floods of 1 kHz with /diagnostics counted once a second; run_tests.sh runs these
# modules alone, after the other process tests.
pytestmark = [pytest.mark.process, pytest.mark.serial]

CONFIG = Path(__file__).resolve().parents[2] / 'config'
#: Messages per node in the test command: a few seconds of flood at 1 kHz.
MESSAGES = int(os.environ.get('STEWART_FUZZ_MESSAGES', '2000'))
#: One seed for the whole session, so that a failure's seed replays every node's run.
SEED = int(os.environ.get('STEWART_FUZZ_SEED', str(random.SystemRandom().randrange(2 ** 32))))


@pytest.mark.parametrize('node', sorted(NODE_INTERFACES))
def test_node_keeps_its_invariants_under_fuzzed_input(ros, node):
    """Hostile messages and parameter changes: alive, nothing bad published, all accounted."""
    # telemetry_bridge on a free port, not its default 47800 that other runs may hold.
    parameters = {'telemetry_port': free_udp_port()} if node == 'telemetry_bridge' else {}
    report = fuzz_node(FuzzSettings(node, SEED, MESSAGES, parameters=parameters))
    print(report.summary())
    assert not report.problems, report.failure()


def test_mpc_cueing_keeps_its_invariants_under_fuzzed_input_and_previews(ros):
    """motion_cueing_node with the MPC and the preview preset: previews fuzzed with the IMU."""
    files = tuple(str(CONFIG / name) for name in (
        'paper_platform.yaml', 'example_limits.yaml', 'motion_cueing.yaml',
        'motion_cueing_preview.yaml'))
    report = fuzz_node(FuzzSettings('motion_cueing_node', SEED, MESSAGES, files=files,
                                    parameters={'cueing_method': 'mpc'}))
    print(report.summary())
    assert not report.problems, report.failure()
