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
The fuzzer's and the soak's side of the wire: a spinning rclpy node, /diagnostics, processes.

:class:`SpinningClient` spins its node in a background thread, so that the caller publishes
on a schedule and waits for answers with a deadline. :class:`DiagnosticsLog` keeps, per node,
the DiagnosticArrays it published and the counters of each of its statuses
(:mod:`stewart_kinematics.ros.message_accounting`), and checks them: counts that add up, codes
from the registry, about one array a second. :func:`paced` yields on a monotonic schedule,
:func:`resident_kb` reads a process's resident memory, and :func:`descendants` finds the
processes a node started (a worker must not outlive its node; whether one still runs is the
core's :func:`~stewart_kinematics.workers.owner_watch.process_running`).
"""

from dataclasses import dataclass, field
import itertools
from pathlib import Path
import threading
import time
from typing import Dict, List, Optional

from rclpy.executors import SingleThreadedExecutor

from stewart_kinematics.findings import CODES
from stewart_kinematics.ros.message_accounting import REPORT_PERIOD

#: Seconds between two checks of a condition being waited for.
POLL_PERIOD = 0.01
#: Arrays a node may publish beyond one per REPORT_PERIOD over the span of its stamps: its
#: first and last are both counted, and a timer's period is not exact.
REPORT_SLACK = 2


def paced(rate: float, count: Optional[int] = None):
    """
    Yield 0, 1, 2, ... on a monotonic schedule of ``rate`` a second, ``count`` times or forever.

    Index ``i`` is due ``i / rate`` seconds after the start, so a late step does not delay the
    following ones (no drift): the average rate stays ``rate`` as long as the caller keeps up.
    """
    start = time.monotonic()
    for index in range(count) if count is not None else itertools.count():
        delay = start + index / rate - time.monotonic()
        if delay > 0.0:
            time.sleep(delay)
        yield index


def resident_kb(pid: int) -> Optional[int]:
    """Resident memory (VmRSS) of a process, kB; ``None`` once it has exited."""
    try:
        with open(f'/proc/{pid}/status') as status:
            for line in status:
                if line.startswith('VmRSS:'):
                    return int(line.split()[1])
    except (FileNotFoundError, ProcessLookupError):
        return None
    return None


def descendants(pid: int) -> List[int]:
    """Return the pids of every living descendant of a process, read from /proc."""
    children: Dict[int, List[int]] = {}
    for entry in Path('/proc').iterdir():
        if not entry.name.isdigit():
            continue
        try:
            fields = (entry / 'stat').read_text().rsplit(')', 1)[1].split()
        except OSError:
            continue
        children.setdefault(int(fields[1]), []).append(int(entry.name))
    found, stack = [], [pid]
    while stack:
        for child in children.get(stack.pop(), []):
            found.append(child)
            stack.append(child)
    return found


class SpinningClient:
    """
    An rclpy node spun by a background thread until :meth:`close`.

    :param node: the node (created by the caller on its context).
    """

    def __init__(self, node):
        self.node = node
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(node)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, name='fuzz_client_spin', daemon=True)
        self._thread.start()

    def _spin(self):
        while not self._stop.is_set():
            self.executor.spin_once(timeout_sec=0.05)

    def close(self):
        """Stop spinning and destroy the node."""
        self._stop.set()
        self._thread.join()
        self.executor.shutdown()
        self.node.destroy_node()

    def wait(self, condition, timeout: float, processes=()) -> bool:
        """
        Wait until ``condition()`` holds, ``timeout`` seconds at most or until a process exits.

        :param processes: NodeProcess instances that must keep running meanwhile.
        :returns: whether the condition holds.
        """
        deadline = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > deadline or not all(p.running() for p in processes):
                return bool(condition())
            time.sleep(POLL_PERIOD)
        return True

    def call(self, client, request, timeout: float):
        """
        Call a service and wait for the answer.

        :returns: the response, or ``None`` if the service does not answer within ``timeout``.
        """
        if not client.wait_for_service(timeout_sec=timeout):
            return None
        future = client.call_async(request)
        if not self.wait(future.done, timeout):
            client.remove_pending_request(future)
            return None
        return future.result()


def status_counters(status) -> Dict[str, object]:
    """
    Return the counters of one of the nodes' diagnostic statuses, or ``{}`` if it has none.

    :returns: ``received``, ``published``, ``rejected`` (ints), ``rejected_by_code`` and
        ``warned_by_code`` (code -> int).
    """
    values = {pair.key: pair.value for pair in status.values}
    if not {'received', 'published', 'rejected'} <= values.keys():
        return {}
    counters = {key: int(values[key]) for key in ('received', 'published', 'rejected')}
    counters['rejected_by_code'] = {key[len('rejected '):]: int(value)
                                    for key, value in values.items()
                                    if key.startswith('rejected ')}
    counters['warned_by_code'] = {key[len('warned '):]: int(value)
                                  for key, value in values.items() if key.startswith('warned ')}
    return counters


@dataclass
class NodeReports:
    """What one node published on /diagnostics: arrays, and each status's latest counters."""

    #: Node-clock stamps (seconds) of its arrays, in order of arrival.
    stamps: List[float] = field(default_factory=list)
    #: Arrival times (monotonic) of its arrays.
    arrivals: List[float] = field(default_factory=list)
    #: Status name -> its latest counters (see :func:`status_counters`).
    latest: Dict[str, Dict[str, object]] = field(default_factory=dict)
    #: Status name -> the ``received`` counter of each report, in order.
    received: Dict[str, List[int]] = field(default_factory=dict)


class DiagnosticsLog:
    """
    A /diagnostics subscription callback that keeps every node's reports, by node name.

    A status belongs to the node named before ``': '`` in its name (``/ik_node: target_pose``).
    """

    def __init__(self):
        self.nodes: Dict[str, NodeReports] = {}
        self._lock = threading.Lock()

    def __call__(self, array):
        """Record a DiagnosticArray: once per node it carries statuses of."""
        now = time.monotonic()
        stamp = array.header.stamp.sec + array.header.stamp.nanosec * 1e-9
        with self._lock:
            seen = set()
            for status in array.status:
                node = status.name.split(': ', 1)[0]
                reports = self.nodes.setdefault(node, NodeReports())
                if node not in seen:
                    seen.add(node)
                    reports.stamps.append(stamp)
                    reports.arrivals.append(now)
                counters = status_counters(status)
                if counters:
                    reports.latest[status.name] = counters
                    reports.received.setdefault(status.name, []).append(counters['received'])

    def reports(self, node: str) -> NodeReports:
        """Return the reports of a node, by fully qualified name (empty if none arrived)."""
        with self._lock:
            return self.nodes.get(node, NodeReports())

    def count(self, node: str) -> int:
        """Return how many arrays of ``node`` arrived."""
        return len(self.reports(node).stamps)

    def settled(self, node: str, since: int, topics=None) -> bool:
        """
        Whether the last two reports of ``node``, after report ``since``, show nothing new.

        :param topics: the input topics to look at (default: every status with counters); a
            status of the node's own making, such as ik_node's ``command_stream``, counts for
            as long as it runs.
        """
        reports = self.reports(node)
        if len(reports.stamps) < since + 2:
            return False
        # Nothing new, and every message answered (a trajectory still being planned is not).
        return all(len(history) >= 2 and history[-1] == history[-2]
                   and _answered(reports.latest[name])
                   for name, history in reports.received.items()
                   if topics is None or name.split(': ', 1)[-1] in topics)

    def problems(self, node: str, sent: Optional[Dict[str, int]] = None) -> List[str]:
        """
        Say what is wrong with a node's reports: counts that do not add up, too many arrays.

        :param sent: messages sent to each input topic (``target_pose`` -> count): a status of
            that input must not count more received.
        :returns: the problems in words (empty: none).
        """
        reports = self.reports(node)
        problems = []
        if not reports.stamps:
            return [f'{node}: no report on /diagnostics']
        span = reports.stamps[-1] - reports.stamps[0]
        allowed = int(span / REPORT_PERIOD) + REPORT_SLACK
        if len(reports.stamps) > allowed:
            problems.append(f'{node}: {len(reports.stamps)} DiagnosticArrays over {span:.1f} s '
                            f'of its clock, more than {allowed} (one a second)')
        for name, counters in sorted(reports.latest.items()):
            received, published, rejected = (counters[key] for key in (
                'received', 'published', 'rejected'))
            by_code = counters['rejected_by_code']
            if received != published + rejected:
                problems.append(f'{name}: received {received} != published {published} + '
                                f'rejected {rejected}')
            if sum(by_code.values()) != rejected:
                problems.append(f'{name}: rejections by code {by_code} do not add up to '
                                f'rejected {rejected}')
            unknown = sorted((set(by_code) | set(counters['warned_by_code'])) - set(CODES))
            if unknown:
                problems.append(f'{name}: codes {unknown} are not in the findings registry')
            topic = name.split(': ', 1)[1]
            if sent is not None and topic in sent and received > sent[topic]:
                problems.append(f'{name}: received {received}, more than the {sent[topic]} '
                                'sent')
        return problems


def _answered(counters) -> bool:
    """Whether every message a status counted was published or rejected."""
    return counters['received'] == counters['published'] + counters['rejected']
