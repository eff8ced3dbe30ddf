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
The node processes' spin loop (``node_main.spin_slice``) on each executor.

On the EventsExecutor one slice runs every callback that comes within it (``spin_once``
returned after the first, and the loop paid a Python round trip per message:
doc/benchmarks.md, "What stalls the nodes"); on the single-threaded executor it runs one. On
both, a slice ends when its time is up even while callbacks keep coming (the stop signals are
checked between slices), and a timer keeps its period. No assert here depends on the machine
being quiet: counts are bounded loosely, intervals by their median.
"""

import statistics
import time

import pytest
from rclpy.node import Node

from stewart_kinematics.ros.node_main import create_executor, EXECUTORS, spin_slice

pytestmark = pytest.mark.node

#: A timer's period in these tests, seconds.
PERIOD = 0.005


@pytest.fixture(params=list(EXECUTORS))
def ticking(request, ros):
    """Yield ``(executor name, executor, tick times)`` with a node ticking every PERIOD."""
    node = Node('spin_slice_test')
    ticks = []
    node.create_timer(PERIOD, lambda: ticks.append(time.monotonic()))
    executor = create_executor(request.param)
    executor.add_node(node)
    yield request.param, executor, ticks
    executor.shutdown()
    node.destroy_node()


def test_a_slice_of_the_events_executor_runs_every_callback_within_it(ticking):
    """One slice of 0.3 s: many ticks on events, at most one on single_threaded."""
    name, executor, ticks = ticking
    spin_slice(executor, 0.05)   # the timer is set up, whichever tick comes first
    ticks.clear()
    spin_slice(executor, 0.3)
    if name == 'events':
        # 60 are due; before spin_slice, one call ran one callback.
        assert len(ticks) >= 5
    else:
        assert len(ticks) <= 1


def test_a_slice_ends_while_callbacks_keep_coming(ticking):
    """A timer always due does not keep a slice of 0.1 s running (the stop flag is read)."""
    _, executor, _ = ticking
    start = time.monotonic()
    for _ in range(3):
        spin_slice(executor, 0.1)
    # 0.3 s of slices; a slice that ran on would take until the test's own timeout.
    assert time.monotonic() - start < 3.0


def test_a_timer_keeps_its_period_in_slices(ticking):
    """Spun in slices for 0.6 s, a 5 ms timer ticks with a median interval near 5 ms."""
    _, executor, ticks = ticking
    end = time.monotonic() + 0.6
    while time.monotonic() < end:
        spin_slice(executor, 0.1)
    intervals = [later - earlier for earlier, later in zip(ticks, ticks[1:])]

    assert len(ticks) >= 20   # 120 due
    assert 0.5 * PERIOD <= statistics.median(intervals) <= 2.0 * PERIOD
