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
A node killed with SIGKILL leaves no process of its own behind.

Found by the soak (benchmarks/soak.py): ik_node computes its workspace in a worker process
(started through multiprocessing's forkserver, with a resource tracker); when ik_node was
killed, the worker waited for jobs forever, and it, the forkserver and the tracker were still
running twenty minutes later, three processes more for every kill. fk_node's assembly-mode
margin worker (a process pool through the same forkserver) did the same. Each node runs as a
process with its worker started (ik_node: a workspace_markers subscriber; fk_node: its margin
period); its descendants are read from /proc before the kill and must all be gone within the
deadline after it.
"""

import os
from pathlib import Path
import signal
import time

from fuzzing.fuzz_client import descendants
import pytest

from stewart_kinematics.tools.node_processes import NodeProcess
from stewart_kinematics.workers.owner_watch import process_running
from visualization_msgs.msg import MarkerArray

pytestmark = pytest.mark.process

CONFIG_DIRECTORY = Path(__file__).resolve().parents[2] / 'config'
#: Seconds the processes left behind have to exit.
DEADLINE = 20.0


def assert_kill_leaves_nothing(node):
    """
    SIGKILL a node process and assert that every process it started exits within DEADLINE.

    Whatever it started and is still running at the end is killed, so that a failure leaves
    nothing behind either.
    """
    started = descendants(node.process.pid)
    assert started, f'{node.name} started no worker process'
    try:
        node.process.kill()
        assert node.process.wait(DEADLINE) == -signal.SIGKILL
        deadline = time.monotonic() + DEADLINE
        while time.monotonic() < deadline and any(process_running(pid) for pid in started):
            time.sleep(0.1)
        left = [pid for pid in started if process_running(pid)]
        commands = {pid: Path(f'/proc/{pid}/cmdline').read_bytes().replace(b'\0', b' ')[:120]
                    for pid in left if process_running(pid)}
        assert not left, f'{len(left)} of {len(started)} processes left behind: {commands}'
    finally:
        for pid in started:
            if process_running(pid):
                os.kill(pid, signal.SIGKILL)


def test_a_killed_ik_node_leaves_no_worker_process_behind(client):
    """SIGKILL ik_node while its workspace worker runs: every process it started exits too."""
    node = NodeProcess('ik_node', ['--ros-args', '--params-file',
                                   str(CONFIG_DIRECTORY / 'paper_platform.yaml'),
                                   '--params-file', str(CONFIG_DIRECTORY / 'example_limits.yaml')])
    try:
        markers = []
        client.node.create_subscription(MarkerArray, 'workspace_markers', markers.append, 10)
        # The worker starts once workspace_markers has a subscriber; the markers prove it ran.
        client.wait(lambda: markers, 'workspace_markers from the worker', [node])
        assert_kill_leaves_nothing(node)
    finally:
        node.__exit__(None, None, None)


def test_a_killed_fk_node_leaves_no_margin_worker_behind(client):
    """SIGKILL fk_node once its assembly-mode margin worker runs: the worker exits too."""
    node = NodeProcess('fk_node', ['--ros-args', '--params-file',
                                   str(CONFIG_DIRECTORY / 'paper_platform.yaml'),
                                   '-p', 'assembly_mode_margin_period:=0.5'])
    try:
        # The worker starts with the node: resource tracker, forkserver, worker.
        client.wait(lambda: len(descendants(node.process.pid)) >= 3,
                    'the margin worker process', [node])
        assert_kill_leaves_nothing(node)
    finally:
        node.__exit__(None, None, None)
