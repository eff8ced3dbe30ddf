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
Load and fault tests across processes: a sustained rate, a burst, signals and a crash.

``ik_node`` and ``fk_node`` run as child processes from their console scripts
(:class:`stewart_kinematics.tools.node_processes.NodeProcess`), as in test_node_processes.py. The
test's rclpy client is spun by a background thread, so that the main thread can publish on a
monotonic schedule (no drift) and wait for conditions with a deadline. Messages are counted on
both sides: what the client sent and received, and the counters every node publishes on
``/diagnostics`` (:mod:`stewart_kinematics.ros.message_accounting`). Every publisher and
subscription, the nodes' (``-p queue_depth:=1000``) and the client's, is reliable, keep-last,
depth :data:`QUEUE_DEPTH`.

The two 30 s load tests run one node at a time. At 500 messages/s a node uses most of a core
and the client a good part of one for each stream, so both nodes at once with the client need
nearly all of a 2-core machine: messages are then lost for want of a core, which measures the
machine, not the nodes.

The restart test kills fk_node with SIGKILL, which leaves its Fast DDS shared-memory segment
in /dev/shm unless a surviving participant's watchdog removes it; the test removes it
afterwards if its lock shows that no living process owns it (:func:`remove_dead_segments`).

Run with ``-s`` to see the figures: lines starting ``LOAD``, ``FLOOD``, ``BURST``, ``SIGNAL``
and ``RESTART``.
"""

import contextlib
import fcntl
import math
import os
from pathlib import Path
import signal
import time

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from fuzzing.fuzz_client import paced
from geometry_msgs.msg import Pose
from helpers import fail_with_output, pose_message, SpinningClient, stop_cleanly
import numpy as np
import pytest
from reference import quaternion_angle as rotation_angle, quaternion_from_euler as quaternion
from std_msgs.msg import Float64MultiArray

from stewart_kinematics.model.inverse import inverse_kinematics
from stewart_kinematics.parameters import load_geometry
from stewart_kinematics.ros.node_main import create_executor

# serial: sustained rates and losses need the machine to themselves; run_tests.sh runs these
# modules alone, after the other process tests.
pytestmark = [pytest.mark.process, pytest.mark.serial]

#: Seconds to wait for discovery or data.
DEADLINE = 20.0
#: Depth of every queue: the nodes' queue_depth parameter and the client's publishers and
#: subscriptions. 2 s of messages at LOAD_RATE, so that a moment of CPU contention on a
#: 2-core machine (the client and a node share it) delays messages instead of dropping them:
#: what queue_depth is for.
QUEUE_DEPTH = 1000
#: Messages per second on each input stream during the load test.
LOAD_RATE = 500.0
#: Seconds of load.
LOAD_DURATION = 30.0
#: Seconds of load before the first memory reading: the queues, the DDS histories and Python's
#: allocator pools have grown to their working size by then.
WARM_UP = 3.0
#: One message in this many is one the node must reject.
BAD_EVERY = 50
#: Poses in one period of the load trajectory (one second at LOAD_RATE).
LOAD_CYCLE = 500
#: Largest growth of a node's resident memory from the end of the warm-up to the end of the
#: load, kB. A node that keeps no message stays nearly flat (its allocator's pools aside); 2 MB
#: over the 13,500 messages after the warm-up is 150 bytes a message, less than a kept Pose or
#: Float64MultiArray costs: keeping every message received fails it.
RSS_GROWTH_LIMIT_KB = 2048
#: Bad poses a second, and in all, in the diagnostics flood test (3 s).
FLOOD_RATE = 1000.0
FLOOD_COUNT = 3000
#: target_pose messages published as fast as possible in the burst test.
BURST_SIZE = 5000
#: Seconds a node has to exit after SIGINT or SIGTERM.
STOP_DEADLINE = 10.0
#: Seconds between two Table 3 rows in the restart test.
RAMP_PERIOD = 0.2
#: The last Table 3 row answered by the first fk_node of the restart test.
KILL_AFTER_ROW = 5
#: Topic of fk_node's input when it runs beside ik_node but on its own stream.
FK_INPUT = '/fk_input'
#: Names of the nodes' statuses on /diagnostics (node name, then its input topic).
IK_STATUS = '/ik_node: target_pose'
FK_STATUS = '/fk_node: leg_lengths'
#: Fast DDS's shared-memory files: /dev/shm/fastrtps_<segment id> (a participant's segment,
#: with a lock file <segment>_el) and /dev/shm/fastrtps_port<number> (a port, with _el).
SHM_DIRECTORY = Path('/dev/shm')
SHM_PREFIX = 'fastrtps_'

#: The paper's Table 3 ramp: start and step of X, Y, Z (millimetres) and alpha, beta, gamma
#: (degrees); 11 rows.
TABLE3_START_MM_DEG = (0.0, 0.0, 432.5, 0.0, 0.0, 0.0)
TABLE3_STEP_MM_DEG = (10.0, 15.0, 10.0, 1.5, -1.5, 2.0)
TABLE3_ROWS = 11


def to_si(pose_mm_deg):
    """Pose ``[X, Y, Z, alpha, beta, gamma]`` from millimetres and degrees to metres, radians."""
    return tuple(v / 1000.0 for v in pose_mm_deg[:3]) + tuple(map(math.radians, pose_mm_deg[3:]))


TABLE3 = tuple(
    to_si([start + row * step for start, step in zip(TABLE3_START_MM_DEG, TABLE3_STEP_MM_DEG)])
    for row in range(TABLE3_ROWS))


def pose_error(message, pose):
    """Position error in metres and rotation error in radians of a Pose message to a pose."""
    position = (message.position.x, message.position.y, message.position.z)
    orientation = message.orientation
    return (math.dist(position, pose[:3]),
            rotation_angle((orientation.x, orientation.y, orientation.z, orientation.w),
                           quaternion(*pose[3:])))


def matches(message, pose, tolerance=1e-9):
    """Whether a Pose message is ``pose`` to ``tolerance`` metres and radians."""
    return max(pose_error(message, pose)) <= tolerance


def load_poses(count):
    """
    Return ``count`` poses of one period of a smooth, periodic motion through Table 3's range.

    Every axis swings sinusoidally between the first and the last row, so that consecutive
    poses are less than a millimetre apart, as on a real platform, and the period closes on
    itself.
    """
    first, last = np.array(TABLE3[0]), np.array(TABLE3[-1])
    phases = 2.0 * np.pi * np.arange(count) / count
    return (first + last) / 2.0 + np.outer(np.sin(phases), (last - first) / 2.0)


def node_arguments(config_directory, *extra):
    """Return the command line of ik_node or fk_node: shipped parameter files, then ``extra``."""
    return ['--ros-args', '--params-file', str(config_directory / 'paper_platform.yaml'),
            '--params-file', str(config_directory / 'solver.yaml'), *extra]


def rss_kb(node):
    """Resident memory (VmRSS) of a node's process, kB."""
    # The ROS wheels' start-up hook re-executes Python in place: the pid is the node's.
    with open(f'/proc/{node.process.pid}/status') as status:
        for line in status:
            if line.startswith('VmRSS:'):
                return int(line.split()[1])
    raise AssertionError(f'no VmRSS in /proc/{node.process.pid}/status')


def cpu_seconds(node):
    """CPU time (user and system) a node's process used so far, seconds."""
    with open(f'/proc/{node.process.pid}/stat') as stat:
        # Fields 14 and 15 (utime, stime), counted after the command name in parentheses.
        fields = stat.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


class MessageCounter:
    """A subscription callback that counts the messages and keeps the last few."""

    def __init__(self, keep=0):
        """Count messages; keep the last ``keep`` of them in ``messages``."""
        self.count = 0
        self.keep = keep
        self.messages = []

    def __call__(self, message):
        """Count a message."""
        self.count += 1
        if self.keep:
            self.messages.append(message)
            del self.messages[:-self.keep]


class DiagnosticsRecord:
    """The counters of every status on /diagnostics that carries them, by status name."""

    def __init__(self):
        """Start with no status."""
        self.history = {}

    def __call__(self, array):
        """Record the counters of each status of a DiagnosticArray."""
        for status in array.status:
            values = {pair.key: pair.value for pair in status.values}
            if {'received', 'published', 'rejected'} <= values.keys():
                self.history.setdefault(status.name, []).append(
                    {key: int(values[key]) for key in ('received', 'published', 'rejected')})

    def count(self, name):
        """Return how many statuses named ``name`` arrived so far."""
        return len(self.history.get(name, ()))

    def latest(self, name, since=0):
        """Return the last counters of ``name`` among the statuses from number ``since`` on."""
        statuses = self.history.get(name, [])[since:]
        return statuses[-1] if statuses else None


@pytest.fixture
def client(ros):
    """
    Create a SpinningClient with a fresh node on the session's private domain.

    Spun by a thread of its own (not conftest's client, spun by the test's thread): the tests
    publish at a steady rate meanwhile.
    """
    client = SpinningClient(ros.create_node('stewart_load_client'), create_executor(),
                            QUEUE_DEPTH)
    yield client
    client.close()


@pytest.fixture
def paper_geometry(config_directory):
    """Return the paper's platform, read from the shipped parameter file."""
    return load_geometry(config_directory / 'paper_platform.yaml')


def good_lengths_messages(geometry, poses):
    """Return Float64MultiArray messages of the leg lengths of ``poses``."""
    return [Float64MultiArray(data=[float(v) for v in lengths])
            for lengths in inverse_kinematics(geometry, poses)]


class LoadStream:
    """One node under load: its process, the client's input stream to it and its outputs."""

    def __init__(self, client, process, status, input_topic, good, bad, output_type,
                 output_topic):
        """
        Create the client's publisher and subscription for ``process``.

        :param status: the name of the node's input status on /diagnostics.
        :param good: the good input messages, published in turn.
        :param bad: the message published instead of one in BAD_EVERY.
        :param output_type: the message type of ``output_topic``.
        """
        self.process = process
        self.status = status
        self.good, self.bad = good, bad
        self.publisher = client.publisher(type(bad), input_topic)
        self.outputs = MessageCounter()
        self.subscription = client.subscribe(output_type, output_topic, self.outputs)
        self.sent = self.bad_sent = 0

    def publish(self, index):
        """Publish input message ``index``: a bad one if it is one in BAD_EVERY."""
        if index % BAD_EVERY == BAD_EVERY - 1:
            self.publisher.publish(self.bad)
            self.bad_sent += 1
        else:
            self.publisher.publish(self.good[index % len(self.good)])
        self.sent += 1

    def connected(self, diagnostics):
        """Whether the node is matched with the client on its input, output and /diagnostics."""
        return (self.publisher.get_subscription_count() >= 1
                and self.subscription.get_publisher_count() >= 1
                and diagnostics.count(self.status) >= 1)

    def accounted(self, diagnostics):
        """Whether the node's latest counters account for every message sent and output seen."""
        counters = diagnostics.latest(self.status)
        return (counters is not None and counters['received'] == self.sent
                and counters['published'] + counters['rejected'] == counters['received']
                and counters['published'] == self.outputs.count)


def start_load(client, start_node, config_directory, geometry, names):
    """
    Start the nodes ``names`` with depth-100 queues, each on an input stream of its own.

    ik_node reads target_pose (bad message: a NaN position); fk_node reads FK_INPUT rather than
    ik_node's leg_lengths (bad message: five leg lengths). Waits until every node is matched
    with the client, then settles.

    :returns: the LoadStream of each node and the DiagnosticsRecord of /diagnostics.
    """
    poses = load_poses(LOAD_CYCLE)
    depth = ['-p', f'queue_depth:={QUEUE_DEPTH}']
    streams = []
    if 'ik_node' in names:
        nan_pose = pose_message(TABLE3[0])
        nan_pose.position.x = math.nan
        streams.append(LoadStream(
            client, start_node('ik_node', node_arguments(config_directory, *depth)), IK_STATUS,
            'target_pose', [pose_message(pose) for pose in poses], nan_pose, Float64MultiArray,
            'leg_lengths'))
    if 'fk_node' in names:
        lengths = good_lengths_messages(geometry, poses)
        streams.append(LoadStream(
            client, start_node('fk_node', node_arguments(
                config_directory, *depth, '-r', f'leg_lengths:={FK_INPUT}')),
            FK_STATUS, FK_INPUT, lengths, Float64MultiArray(data=list(lengths[0].data)[:5]),
            Pose, 'estimated_pose'))
    diagnostics = DiagnosticsRecord()
    client.subscribe(DiagnosticArray, '/diagnostics', diagnostics)
    client.wait(lambda: all(stream.connected(diagnostics) for stream in streams),
                f'{", ".join(names)} matched with the client',
                [stream.process for stream in streams])
    client.settle()
    return streams, diagnostics


@pytest.mark.parametrize('names', [('ik_node',), ('fk_node',)], ids=['ik_node', 'fk_node'])
def test_node_loses_nothing_at_500_hz(client, start_node, config_directory, paper_geometry,
                                      names):
    """
    A node fed 500 messages/s for 30 s accounts for every message, in flat memory.

    Reliable, keep-last queues of depth QUEUE_DEPTH on both sides; one message in 50 is bad (a NaN
    position, five leg lengths). The node's /diagnostics counters must show every message sent
    as received, every good one published (and seen by the client) and every bad one rejected;
    its resident memory must stay flat after a 3 s warm-up.
    """
    streams, diagnostics = start_load(client, start_node, config_directory, paper_geometry,
                                      names)
    processes = [stream.process for stream in streams]

    count = int(LOAD_RATE * LOAD_DURATION)
    warm_up_index = int(LOAD_RATE * WARM_UP)
    rss_start, cpu_start = {}, {}
    start = time.monotonic()
    client_cpu_start = time.process_time()
    for index in paced(LOAD_RATE, count):
        for stream in streams:
            stream.publish(index)
        if index == warm_up_index:
            rss_start = {process.name: rss_kb(process) for process in processes}
            cpu_start = {process.name: cpu_seconds(process) for process in processes}
        if index % int(LOAD_RATE) == 0 and not all(p.running() for p in processes):
            fail_with_output(f'a node exited after {index} messages', processes)
    elapsed = time.monotonic() - start
    cpu = {process.name: (cpu_seconds(process) - cpu_start[process.name]) / (elapsed - WARM_UP)
           for process in processes}
    print(f'\nLOAD rate: {count} messages on each stream in {elapsed:.2f} s = '
          f'{(count - 1) / elapsed:.1f} Hz (target {LOAD_RATE:g} Hz); CPU in use (1.0 = one '
          f'core): client {(time.process_time() - client_cpu_start) / elapsed:.2f}, '
          + ', '.join(f'{name} {share:.2f}' for name, share in cpu.items())
          + f'; load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores')

    client.wait(lambda: all(stream.accounted(diagnostics) for stream in streams),
                'every message accounted for on /diagnostics', processes, fail=False)
    # Outputs have stopped: two more summaries (over a second) must not change anything.
    marks = [diagnostics.count(stream.status) for stream in streams]
    counts = [stream.outputs.count for stream in streams]
    client.wait(lambda: all(diagnostics.count(stream.status) >= mark + 2
                            for stream, mark in zip(streams, marks)),
                'two more summaries from each node', processes)

    failures = []
    for stream, outputs_before in zip(streams, counts):
        name, counters, outputs = stream.process.name, diagnostics.latest(stream.status), \
            stream.outputs.count
        rss_end = rss_kb(stream.process)
        print(f'LOAD {name}: sent={stream.sent} bad={stream.bad_sent} '
              f'received={counters["received"]} published={counters["published"]} '
              f'rejected={counters["rejected"]} client_received={outputs} '
              f'rss_start_kb={rss_start[name]} rss_end_kb={rss_end} '
              f'rss_growth_kb={rss_end - rss_start[name]}')
        checks = [
            (counters['received'] == stream.sent,
             f'received {counters["received"]} of the {stream.sent} messages sent'),
            (counters['published'] == outputs,
             f'published {counters["published"]}, the client received {outputs}'),
            (outputs == outputs_before, f'outputs kept arriving: {outputs - outputs_before} more'),
            (counters['published'] + counters['rejected'] == counters['received'],
             f'published {counters["published"]} + rejected {counters["rejected"]} != '
             f'received {counters["received"]}'),
            (counters['rejected'] == stream.bad_sent,
             f'rejected {counters["rejected"]}, {stream.bad_sent} bad messages sent'),
            (rss_end - rss_start[name] <= RSS_GROWTH_LIMIT_KB,
             f'resident memory grew from {rss_start[name]} kB to {rss_end} kB '
             f'(limit {RSS_GROWTH_LIMIT_KB} kB)'),
        ]
        failures += [f'{name}: {message}' for ok, message in checks if not ok]
    assert not failures, '\n'.join(failures)
    for process in processes:
        stop_cleanly(process)


class DiagnosticsArrays:
    """Every DiagnosticArray that carries a status of one name, with its arrival time."""

    def __init__(self, name):
        """Keep the arrays that carry a status named ``name``."""
        self.name = name
        self.arrays = []

    def __call__(self, array):
        """Keep ``array`` (with the monotonic time of arrival) if it carries the status."""
        for status in array.status:
            if status.name == self.name:
                self.arrays.append((time.monotonic(), status))

    def since(self, moment):
        """Return the statuses that arrived at or after ``moment`` (monotonic seconds)."""
        return [status for arrival, status in self.arrays if arrival >= moment]

    def latest_values(self):
        """Return the key-value pairs of the last status, as a dict (empty before the first)."""
        return {pair.key: pair.value for pair in self.arrays[-1][1].values} if self.arrays \
            else {}


def test_a_flood_of_bad_poses_gives_one_diagnostics_report_a_second(
        client, start_node, config_directory):
    """
    1000 bad poses a second for 3 s: about one DiagnosticArray a second, not one per pose.

    ik_node runs in the namespace /flood with the example limits; two poses in three have a
    NaN position (invalid_pose), one in three raises the platform beyond leg_length_max
    (out_of_limits). Queues of FLOOD_COUNT messages on both sides keep every message, so the
    node's report must count each reason exactly; its hardware_id names the namespace. The
    log says each reason at most once a second, so the flood of one does not hide the other.
    """
    node = start_node('ik_node', node_arguments(
        config_directory, '--params-file', str(config_directory / 'example_limits.yaml'),
        '-p', f'queue_depth:={FLOOD_COUNT}', '-r', '__ns:=/flood'))
    reports = DiagnosticsArrays('/flood/ik_node: target_pose')
    client.subscribe(DiagnosticArray, '/diagnostics', reports)
    publisher = client.node.create_publisher(Pose, '/flood/target_pose', FLOOD_COUNT)
    client.wait(lambda: publisher.get_subscription_count() >= 1 and reports.arrays,
                'ik_node in /flood matched with the client, and its first report', [node])
    client.settle()

    nan_pose = pose_message(TABLE3[0])
    nan_pose.position.x = math.nan
    raised = pose_message((0.0, 0.0, 0.62, 0.0, 0.0, 0.0))  # legs 1, 2, 4, 5, 6 beyond 0.9 m
    flood = [nan_pose, nan_pose, raised]
    start = time.monotonic()
    for index in paced(FLOOD_RATE, FLOOD_COUNT):
        publisher.publish(flood[index % 3])
    flood_time = time.monotonic() - start
    client.wait(lambda: reports.latest_values().get('received') == str(FLOOD_COUNT),
                'a report counting every pose of the flood', [node])
    # The node logs while it works through the flood, which on a loaded machine ends after
    # the sending: until this report (a second late at most).
    handled_time = time.monotonic() - start
    during = reports.since(start)
    values = reports.latest_values()
    output = stop_cleanly(node)
    logged = [line for line in output.splitlines() if 'rejected so far' in line]
    print(f'\nFLOOD ik_node: {FLOOD_COUNT} bad poses in {flood_time:.2f} s; '
          f'{len(during)} reports on /diagnostics from the start of the flood to the report '
          f'counting all of them ({time.monotonic() - start:.2f} s); {len(logged)} log lines')

    assert values['rejected'] == str(FLOOD_COUNT) and values['published'] == '0'
    assert values['rejected invalid_pose'] == str(2 * FLOOD_COUNT // 3)
    assert values['rejected out_of_limits'] == str(FLOOD_COUNT // 3)
    assert values['last rejection'].startswith(('position must be finite',
                                                'the pose is out of the limits'))
    assert all(status.hardware_id == 'stewart_platform/flood' for status in during)
    assert any(status.level == DiagnosticStatus.ERROR for status in during)
    # One report a second: three for the flood, give or take one at each end.
    assert 2 <= len(during) <= math.ceil(time.monotonic() - start) + 1, len(during)
    assert any('target_pose rejected: position must be finite' in line for line in logged)
    assert any('target_pose rejected: the pose is out of the limits' in line for line in logged)
    assert len(logged) <= 2 * (math.ceil(handled_time) + 2), '\n'.join(logged)
    assert any('more like it not logged' in line for line in logged)


def test_ik_node_survives_a_burst(client, start_node, config_directory, paper_geometry):
    """
    ik_node survives 5000 poses published as fast as the client can, far above 500/s.

    Keep-last queues of depth QUEUE_DEPTH may drop part of a burst (reported, not asserted).
    The node must keep running, answer the good pose sent right after the burst (queues drop
    the oldest messages, never the newest) and keep its counters consistent.
    """
    node = start_node('ik_node', node_arguments(config_directory, '-p',
                                                f'queue_depth:={QUEUE_DEPTH}'))
    outputs = MessageCounter(keep=1)
    diagnostics = DiagnosticsRecord()
    subscription = client.subscribe(Float64MultiArray, 'leg_lengths', outputs)
    client.subscribe(DiagnosticArray, '/diagnostics', diagnostics)
    publisher = client.publisher(Pose, 'target_pose')
    client.wait(lambda: publisher.get_subscription_count() >= 1
                and subscription.get_publisher_count() >= 1
                and diagnostics.count(IK_STATUS) >= 1, 'ik_node matched with the client', [node])
    client.settle()

    burst = [pose_message(pose) for pose in TABLE3[:-1]]
    start = time.monotonic()
    for index in range(BURST_SIZE):
        publisher.publish(burst[index % len(burst)])
    burst_time = time.monotonic() - start
    final_pose = TABLE3[-1]
    final_lengths = inverse_kinematics(paper_geometry, final_pose)
    publisher.publish(pose_message(final_pose))
    sent = BURST_SIZE + 1

    # Reliable delivery is in order, so the answer to the last pose comes last.
    client.wait(lambda: outputs.messages and np.allclose(
        outputs.messages[-1].data, final_lengths, rtol=0.0, atol=1e-12),
        'the answer to the good pose sent after the burst', [node])
    answered = time.monotonic() - start
    # A summary sent before that answer may arrive after it: wait for the second one after.
    mark = diagnostics.count(IK_STATUS)
    client.wait(lambda: diagnostics.count(IK_STATUS) >= mark + 2,
                'two summaries after the answer', [node])

    counters = diagnostics.latest(IK_STATUS)
    print(f'\nBURST ik_node: sent={BURST_SIZE} in {burst_time:.3f} s '
          f'({BURST_SIZE / burst_time:.0f}/s) then 1 good pose, answered after {answered:.2f} s; '
          f'received={counters["received"]} (lost before the node: '
          f'{sent - counters["received"]}) published={counters["published"]} '
          f'rejected={counters["rejected"]} client_received={outputs.count} '
          f'(lost before the client: {counters["published"] - outputs.count})')
    assert node.running()
    assert counters['published'] + counters['rejected'] == counters['received'], counters
    assert 1 <= counters['received'] <= sent, counters
    assert counters['rejected'] == 0, counters
    stop_cleanly(node)


@pytest.mark.parametrize('signal_number', [signal.SIGINT, signal.SIGTERM],
                         ids=['SIGINT', 'SIGTERM'])
def test_signal_during_load_stops_nodes_cleanly(client, start_node, config_directory,
                                                paper_geometry, signal_number):
    """
    SIGINT or SIGTERM, sent while 500 messages/s flow, stops ik_node and fk_node with code 0.

    Both nodes run, each on its own input stream. The signal reaches each once both have
    answered 100 messages; publishing goes on until both have exited, which must take less
    than 10 s and print no traceback.
    """
    streams, _ = start_load(client, start_node, config_directory, paper_geometry,
                            ('ik_node', 'fk_node'))
    processes = [stream.process for stream in streams]

    start = time.monotonic()
    signalled_at = None
    for index in paced(LOAD_RATE):
        for stream in streams:
            stream.publish(index)
        now = time.monotonic()
        if signalled_at is None:
            if min(stream.outputs.count for stream in streams) >= 100:
                for process in processes:
                    process.send_signal(signal_number)
                signalled_at = now
                answered = [stream.outputs.count for stream in streams]
            elif now > start + DEADLINE:
                fail_with_output('no answers to the load', processes)
        elif not any(p.running() for p in processes) or now > signalled_at + STOP_DEADLINE:
            break

    failures = []
    for stream, outputs_before in zip(streams, answered):
        process = stream.process
        code = process.process.poll()
        output = process.output()
        print(f'\nSIGNAL {signal_number.name} {process.name}: exit code {code} within '
              f'{time.monotonic() - signalled_at:.2f} s; {outputs_before} answers before the '
              f'signal, {stream.sent} messages sent in all')
        if code != 0:
            failures.append(f'{process.name} exit code {code} after {signal_number.name} '
                            f'(None: still running after {STOP_DEADLINE} s):\n{output}')
        elif 'Traceback' in output:
            failures.append(f'{process.name} printed a traceback:\n{output}')
    assert not failures, '\n'.join(failures)


def shm_lock_files(pid):
    """
    Return the Fast DDS shared-memory lock files (``..._el``) a process holds open.

    The owner of a segment ``fastrtps_<id>`` holds its lock file ``fastrtps_<id>_el`` open
    (and flock-ed) for its life, and so does the listener of a port ``fastrtps_port<n>``;
    other participants map a segment or a port but never open its lock file.

    :returns: ``(segments, ports)``: paths of the segments' lock files, and port file names.
    """
    segments, ports = [], []
    for descriptor in Path(f'/proc/{pid}/fd').iterdir():
        with contextlib.suppress(OSError):
            target = Path(os.readlink(descriptor))
            if (target.parent != SHM_DIRECTORY or not target.name.startswith(SHM_PREFIX)
                    or not target.name.endswith('_el')):
                continue
            if target.name.startswith(SHM_PREFIX + 'port'):
                ports.append(target.name[:-len('_el')])
            else:
                segments.append(target)
    return sorted(segments), sorted(ports)


def segments_present(lock_files):
    """Whether every segment of ``lock_files`` (and its lock file) is still in /dev/shm."""
    return all(path.exists() and path.with_name(path.name[:-len('_el')]).exists()
               for path in lock_files)


def remove_dead_segments(lock_files):
    """
    Remove the segments of ``lock_files`` whose lock no living process holds.

    The lock is tested as Fast DDS tests it, with a non-blocking exclusive flock; only a
    segment whose lock can be taken (its owner is dead) is removed, with its lock file.

    :returns: one line per segment saying what was found and done.
    """
    report = []
    for lock_file in lock_files:
        segment = lock_file.with_name(lock_file.name[:-len('_el')])
        try:
            descriptor = os.open(lock_file, os.O_RDONLY)
        except FileNotFoundError:
            report.append(f'{segment.name}: already gone')
            continue
        try:
            fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            report.append(f'{segment.name}: lock held by a living process, kept')
            continue
        finally:
            os.close(descriptor)
        size = segment.stat().st_size if segment.exists() else 0
        for path in (segment, lock_file):
            with contextlib.suppress(FileNotFoundError):
                path.unlink()
        report.append(f'{segment.name} ({size} bytes) and its _el file: left behind, lock '
                      f'free, removed')
    return report


def endpoint_gids(endpoints, node_name):
    """Return the GIDs of ``node_name``'s endpoints in a list of TopicEndpointInfo."""
    return {bytes(endpoint.endpoint_gid) for endpoint in endpoints
            if endpoint.node_name == node_name}


def test_fk_node_killed_mid_ramp_resumes_after_restart(client, start_node, config_directory):
    """
    fk_node killed (SIGKILL) after Table 3 row 5 and started again resumes correct output.

    ik_node and fk_node are chained (target_pose -> leg_lengths -> estimated_pose); the client
    plays the ramp, one row every 0.2 s. After row 5, fk_node is killed as a crash would kill
    it, leaving its Fast DDS shared memory behind; a new fk_node starts beside the stale files.
    Once discovered, row 5 (where the platform still is) is commanded again until the new
    fk_node answers (its first solve starts from the home pose), then the ramp goes on: every
    pose after the restart must equal the pose sent, to 1e-9 m and 1e-9 rad.
    """
    arguments = node_arguments(config_directory)
    ik = start_node('ik_node', arguments)
    fk = start_node('fk_node', arguments)
    estimates = MessageCounter(keep=100)
    diagnostics = DiagnosticsRecord()
    subscription = client.subscribe(Pose, 'estimated_pose', estimates)
    client.subscribe(DiagnosticArray, '/diagnostics', diagnostics)
    publisher = client.publisher(Pose, 'target_pose')
    graph = client.node

    def fk_gids():
        return (endpoint_gids(graph.get_subscriptions_info_by_topic('leg_lengths'), 'fk_node'),
                endpoint_gids(graph.get_publishers_info_by_topic('estimated_pose'), 'fk_node'))

    client.wait(lambda: publisher.get_subscription_count() >= 1
                and subscription.get_publisher_count() >= 1
                and endpoint_gids(graph.get_publishers_info_by_topic('leg_lengths'), 'ik_node')
                and all(fk_gids()), 'ik_node and fk_node chained and matched', [ik, fk])
    client.settle()

    for row in paced(1.0 / RAMP_PERIOD, KILL_AFTER_ROW + 1):
        publisher.publish(pose_message(TABLE3[row]))
    client.wait(lambda: estimates.count == KILL_AFTER_ROW + 1,
                f'estimated_pose of rows 0 to {KILL_AFTER_ROW}', [ik, fk])
    before_kill = list(estimates.messages)
    old_gids = fk_gids()
    # Port numbers are reused by the next participant that takes them: left to Fast DDS.
    old_segments, old_ports = shm_lock_files(fk.process.pid)
    old_pid = fk.process.pid

    fk.process.kill()
    kill_code = fk.process.wait(DEADLINE)
    left_behind = [path.name for path in sorted(SHM_DIRECTORY.glob(SHM_PREFIX + '*'))
                   if any(path.name.startswith(lock.name[:-len('_el')])
                          or path.name.startswith(port) for lock in old_segments
                          for port in old_ports)]
    new_ports = []
    # Whether the killed fk_node's segment files still exist, at each step.
    segment_seen = {'after the kill': segments_present(old_segments)}
    try:
        new_fk = start_node('fk_node', arguments)
        status_mark = diagnostics.count(FK_STATUS)
        client.wait(lambda: all(new - old for new, old in zip(fk_gids(), old_gids)),
                    'the new fk_node in the graph', [ik, new_fk])
        new_ports = shm_lock_files(new_fk.process.pid)[1]
        segment_seen['new fk_node discovered'] = segments_present(old_segments)
        client.settle()

        # The chain is whole once the new fk_node answers; command row 5 again until then.
        deadline = time.monotonic() + DEADLINE
        for _ in paced(1.0 / RAMP_PERIOD):
            if estimates.count > KILL_AFTER_ROW + 1:
                break
            if time.monotonic() > deadline or not (ik.running() and new_fk.running()):
                fail_with_output('no answer from the new fk_node', [ik, new_fk])
            publisher.publish(pose_message(TABLE3[KILL_AFTER_ROW]))
        for row in paced(1.0 / RAMP_PERIOD, TABLE3_ROWS - KILL_AFTER_ROW - 1):
            publisher.publish(pose_message(TABLE3[KILL_AFTER_ROW + 1 + row]))
        # Wait for the last row's pose; a wrong one fails below, with the rows' errors.
        client.wait(lambda: matches(estimates.messages[-1], TABLE3[-1]),
                    'estimated_pose of the last row', [ik, new_fk], fail=False)
        client.wait(lambda: (diagnostics.latest(FK_STATUS, status_mark) or {}).get(
            'published') == estimates.count - KILL_AFTER_ROW - 1,
            'a summary of the new fk_node counting every pose it published', [ik, new_fk])
        counters = diagnostics.latest(FK_STATUS, status_mark)
        after_restart = estimates.messages[KILL_AFTER_ROW + 1:]
        segment_seen['ramp done'] = segments_present(old_segments)
    finally:
        cleanup = remove_dead_segments(old_segments)
        print(f'\nRESTART fk_node pid {old_pid} exit code {kill_code} (SIGKILL); its files in '
              f'{SHM_DIRECTORY} after the kill: {", ".join(left_behind) or "none"}; its '
              'segment still there: '
              + ', '.join(f'{moment}: {present}' for moment, present in segment_seen.items()))
        for line in cleanup:
            print(f'RESTART shm segment {line}')
        print(f'RESTART ports of the killed fk_node: {", ".join(old_ports)} (left to Fast DDS); '
              f'ports of the new fk_node: {", ".join(new_ports)}')

    assert kill_code == -signal.SIGKILL
    for row, message in enumerate(before_kill):
        assert matches(message, TABLE3[row]), (
            f'row {row} before the kill: error {pose_error(message, TABLE3[row])}')
    repeats = next((index for index, message in enumerate(after_restart)
                    if not matches(message, TABLE3[KILL_AFTER_ROW])), len(after_restart))
    print(f'RESTART estimates after the restart: {repeats} of row {KILL_AFTER_ROW} (the probe), '
          f'then {len(after_restart) - repeats}; new fk_node counters {counters}')
    assert repeats >= 1, (
        f'the first pose from the new fk_node, row {KILL_AFTER_ROW} solved from the home pose, '
        f'is off by (m, rad) {pose_error(after_restart[0], TABLE3[KILL_AFTER_ROW])}')
    resumed = after_restart[repeats:]
    expected = TABLE3[KILL_AFTER_ROW + 1:]
    assert len(resumed) == len(expected), (
        f'{len(resumed)} poses after the restart for {len(expected)} rows sent')
    for row, (message, pose) in enumerate(zip(resumed, expected), start=KILL_AFTER_ROW + 1):
        assert matches(message, pose), (
            f'row {row} after the restart: error (m, rad) {pose_error(message, pose)}')
    assert counters['received'] == counters['published'] == len(after_restart), counters
    assert counters['rejected'] == 0, counters
    stop_cleanly(new_fk)
    stop_cleanly(ik)
